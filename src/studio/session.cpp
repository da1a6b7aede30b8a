// The editing document of vdg studio (see vdg/studio/session.h).
#include "vdg/studio/session.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <numbers>
#include <utility>

#include <Eigen/Geometry>

#include "vdg/deform/falloff.h"
#include "vdg/deform/image_plane.h"
#include "vdg/deform/key_edit.h"
#include "vdg/deform/pick.h"
#include "vdg/geom/error.h"
#include "vdg/geom/normalize.h"
#include "vdg/geom/text.h"
#include "vdg/io/atomic_file.h"
#include "vdg/io/edit_script.h"
#include "vdg/io/file_transaction.h"
#include "vdg/io/manifest.h"
#include "vdg/io/mesh.h"
#include "vdg/io/obj.h"
#include "vdg/io/studio_recovery.h"
#include "vdg/studio/navigation.h"
#include "vdg/viewdep/animated_model.h"
#include "vdg/viewdep/view_sphere.h"

namespace vdg::studio {
namespace fs = std::filesystem;

namespace {

// The journal `vdg deform` uses in a model's folder: the editor writes through the same one, so
// the two never interleave their steps and each completes the other's interrupted step.
constexpr const char* kJournalName = ".vdg-journal";
constexpr const char* kRecoveryFolder = ".vdg-studio";
// Default selection radius as a share of the base's bounding-box diagonal.
constexpr double kDefaultRadiusShare = 0.15;

bool isManifestPath(const std::string& path) { return hasExtension(path, ".json"); }

fs::path meshFile(const fs::path& folder, const std::string& mesh_path) {
  return fs::path(mesh_path).is_absolute() ? fs::path(mesh_path) : folder / mesh_path;
}

Eigen::Vector3d vertexOf(std::span<const float> p, std::int32_t v) { return {p[3 * v], p[3 * v + 1], p[3 * v + 2]}; }

}  // namespace

const char* toolName(Tool tool) {
  switch (tool) {
    case Tool::kDrag:
      return "drag";
    case Tool::kPushPull:
      return "push/pull";
    case Tool::kRotate:
      return "rotate";
    case Tool::kScale:
      return "scale";
  }
  return "?";
}

struct Session::Impl {
  RawViewDependentModel raw;
  std::string model_path, manifest_path, recovery_path;
  fs::path folder;  // the manifest's folder
  bool manifest_exists = false;
  double diagonal = 1.0;
  Bounds pose_bounds;        // the base at every frame
  int frame = 0;             // the timeline's frame
  std::vector<float> posed;  // an animated base at `frame` (shown when no key is current)
  std::uint64_t revision = 1;

  // The current key (-1: none) and its history in this session.
  int current = -1;
  bool is_new = false;
  bool log_existed = false;                // the key had an edit log on disk when it became current
  EditLog base_log;                        // its log as it was when it became current
  std::vector<float> origin;               // its positions then
  std::vector<EditLogEntry> strokes;       // this session's strokes, in order
  std::vector<std::vector<float>> shapes;  // shapes[i]: positions after strokes[undo_floor + i]
  std::size_t undo_floor = 0;              // undo stops here (older shapes are dropped, kMaxUndo)
  std::vector<float> floor_shape;          // positions with strokes[0, undo_floor) applied
  std::size_t cursor = 0;                  // strokes[0, cursor) are applied
  std::size_t saved = 0;                   // strokes[0, saved) are on disk
  bool saved_valid = true;                 // false when an undo went below a save: dirty until saved

  // The stroke in progress.
  bool stroking = false;
  EditOp stroke_op;
  Camera stroke_camera;
  std::int32_t stroke_vertex = 0;
  Eigen::Vector2d stroke_start = Eigen::Vector2d::Zero();
  std::vector<float> stroke_before;
  std::vector<double> stroke_weights;
  Eigen::Vector3d stroke_pivot = Eigen::Vector3d::Zero();
  double stroke_depth = 0;

  std::optional<StudioRecovery> recovery;
  std::size_t recovery_unsaved = 0;  // its strokes not in the key's log on disk

  // The viewport's drawing, which a new key takes with its camera (setDrawing).
  std::string drawing_path;  // as the manifest writes it: relative to `folder` where it can be
  std::shared_ptr<const TextureImage> drawing;

  std::vector<float>& shown() { return current >= 0 ? raw.keys[current].mesh.positions : baseShown(); }
  const std::vector<float>& shown() const { return current >= 0 ? raw.keys[current].mesh.positions : baseShown(); }
  std::vector<float>& baseShown() { return raw.animated() ? posed : raw.base.positions; }
  const std::vector<float>& baseShown() const { return raw.animated() ? posed : raw.base.positions; }
  void poseAt(int f) {
    frame = f;
    if (raw.animated()) posed = raw.base_frames[static_cast<std::size_t>(f)];
  }
  fs::path keyMeshFile(const RawKey& key) const { return meshFile(folder, key.mesh_path); }
  bool dirty() const { return !saved_valid || cursor != saved; }

  void resetHistory() {
    strokes.clear(), shapes.clear();
    undo_floor = cursor = saved = 0;
    saved_valid = true;
    floor_shape = origin;
  }

  // Appends an applied stroke (shown() already holds its result), dropping the strokes undone.
  void pushStroke(EditLogEntry entry) {
    if (saved > cursor) saved_valid = false;  // a saved stroke is replaced
    strokes.resize(cursor);
    shapes.resize(cursor - undo_floor);
    strokes.push_back(std::move(entry));
    shapes.push_back(shown());
    ++cursor;
    if (shapes.size() > kMaxUndo) {
      floor_shape = std::move(shapes.front());
      shapes.erase(shapes.begin());
      ++undo_floor;
    }
    ++revision;
    autosave();
  }

  // Writes or removes the recovery file so that it holds exactly the unsaved strokes. Autosave
  // never stops the artist: a folder that cannot be written loses the recovery only.
  void autosave() {
    std::error_code ec;
    if (current < 0 || !dirty()) {
      fs::remove(recovery_path, ec);
      return;
    }
    const RawKey& key = raw.keys[current];
    StudioRecovery r;
    r.model = model_path;
    r.manifest = manifest_path;
    r.key = key.name;
    r.new_key = is_new;
    if (is_new) r.mesh_path = key.mesh_path, r.key_camera = key.camera, r.key_frame = key.frame;
    r.logged = base_log.entries.size();
    r.strokes.assign(strokes.begin(), strokes.begin() + static_cast<std::ptrdiff_t>(cursor));
    try {
      fs::create_directories(fs::path(recovery_path).parent_path());
      writeFileAtomically(recovery_path, formatStudioRecovery(r));
    } catch (const std::exception&) {
    }
  }
};

Session::Session() : impl_(std::make_unique<Impl>()) {}
Session::~Session() = default;
Session::Session(Session&&) noexcept = default;
Session& Session::operator=(Session&&) noexcept = default;

Session Session::open(const std::string& path, const OpenOptions& options) {
  Session s;
  Impl& m = *s.impl_;
  m.model_path = fs::absolute(path).lexically_normal().string();
  if (!fs::exists(path)) throw Error(path + ": no such file");
  if (isManifestPath(path)) {
    m.raw = loadManifest(path);
    m.manifest_path = m.model_path;
    m.manifest_exists = true;
  } else {
    m.raw.base = readMesh(path);
    m.raw.source = path;
    m.manifest_path =
        options.manifest_out.empty()
            ? (fs::path(m.model_path).parent_path() / (fs::path(path).stem().string() + ".vdg.json")).string()
            : fs::absolute(options.manifest_out).lexically_normal().string();
    if (fs::exists(m.manifest_path))
      throw Error(m.manifest_path + " already exists: open it (vdg studio " + m.manifest_path +
                  ") to add keys to that model, or give another manifest to create");
    m.raw.base_path = fs::relative(m.model_path, fs::path(m.manifest_path).parent_path()).generic_string();
    m.raw.validate();
  }
  m.folder = fs::path(m.manifest_path).parent_path();
  m.recovery_path =
      (m.folder / kRecoveryFolder / (fs::path(m.manifest_path).filename().string() + ".recovery.json")).string();
  const Bounds b0 = computeBounds(m.raw.base.positions);
  m.diagonal = std::max(static_cast<double>(b0.diagonal()), 1e-9);
  s.falloff = Falloff{kDefaultRadiusShare * m.diagonal, 2.0, FalloffShape::kPower};
  m.pose_bounds = b0;
  for (const std::vector<float>& f : m.raw.base_frames) {
    const Bounds bf = computeBounds(f);
    for (int a = 0; a < 3; ++a)
      m.pose_bounds.min[a] = std::min(m.pose_bounds.min[a], bf.min[a]),
      m.pose_bounds.max[a] = std::max(m.pose_bounds.max[a], bf.max[a]);
  }
  if (m.raw.animated() && !m.raw.keys.empty()) {
    // The animated model's extent: the base and every view's pose at every frame (what it draws).
    try {
      const Bounds e = AnimatedViewDependentModel::build(m.raw).extent();
      for (int a = 0; a < 3; ++a)
        m.pose_bounds.min[a] = std::min(m.pose_bounds.min[a], e.min[a]),
        m.pose_bounds.max[a] = std::max(m.pose_bounds.max[a], e.max[a]);
    } catch (const Error&) {  // loadManifest validated it; the base's frames alone still frame it
    }
  }
  if (m.raw.animated()) {
    // Symmetric about the model's centre: a camera framing it looks at the centre, so the view it
    // keys is the direction the manifest stores (front is exactly +Z, one view at every frame).
    const Eigen::Vector3d c = m.raw.resolvedCenter();
    for (int a = 0; a < 3; ++a) {
      const float r =
          static_cast<float>(std::max(std::abs(m.pose_bounds.min[a] - c[a]), std::abs(m.pose_bounds.max[a] - c[a])));
      m.pose_bounds.min[a] = static_cast<float>(c[a]) - r;
      m.pose_bounds.max[a] = static_cast<float>(c[a]) + r;
    }
  }
  m.poseAt(0);
  const Bounds& b = m.pose_bounds;
  // A front view framing the base (an animated base at every frame).
  const Eigen::Vector3d lo(b.min[0], b.min[1], b.min[2]), hi(b.max[0], b.max[1], b.max[2]);
  const Eigen::Vector3d center = 0.5 * (lo + hi);
  Camera c;
  c.target = center;
  c.eye = center + Eigen::Vector3d(0, 0, 1);
  s.camera = frameBox(c, lo, hi, static_cast<double>(s.image_width) / s.image_height);
  if (fs::exists(m.recovery_path)) {
    try {
      StudioRecovery r = readStudioRecovery(m.recovery_path);
      // Strokes a save in the lost session wrote to the key's log are not offered again.
      std::size_t saved = 0;
      for (const RawKey& key : m.raw.keys) {
        const std::string log = editLogPath(m.keyMeshFile(key).string());
        if (!r.new_key && key.name == r.key && fs::exists(log)) {
          const std::size_t n = readEditLog(log).entries.size();
          saved = n > r.logged ? n - r.logged : 0;
        }
      }
      if (r.strokes.size() > saved) {
        m.recovery_unsaved = r.strokes.size() - saved;
        m.recovery = std::move(r);
      }
    } catch (const Error&) {
      // An unreadable recovery file is offered as nothing; recover() is never called on it.
    }
  }
  return s;
}

const RawViewDependentModel& Session::model() const { return impl_->raw; }
const std::string& Session::modelPath() const { return impl_->model_path; }
const std::string& Session::manifestPath() const { return impl_->manifest_path; }
bool Session::animated() const { return impl_->raw.animated(); }
const TriMesh& Session::baseMesh() const { return impl_->raw.base; }
double Session::baseDiagonal() const { return impl_->diagonal; }
const Bounds& Session::poseBounds() const { return impl_->pose_bounds; }
std::span<const float> Session::basePositions() const { return impl_->baseShown(); }
int Session::frame() const { return impl_->frame; }
int Session::frameCount() const { return static_cast<int>(impl_->raw.frameCount()); }
int Session::currentKey() const { return impl_->current; }
bool Session::currentKeyIsNew() const { return impl_->current >= 0 && impl_->is_new; }
std::span<const float> Session::positions() const { return impl_->shown(); }
std::uint64_t Session::revision() const { return impl_->revision; }
bool Session::dirty() const { return impl_->current >= 0 && impl_->dirty(); }
bool Session::stroking() const { return impl_->stroking; }
std::size_t Session::strokeCount() const { return impl_->cursor; }
const std::string& Session::recoveryPath() const { return impl_->recovery_path; }
std::size_t Session::recoverableStrokes() const { return impl_->recovery ? impl_->recovery_unsaved : 0; }

std::optional<std::int32_t> Session::pick(const Eigen::Vector2d& pixel) const {
  return vertexAtPixel(impl_->shown(), impl_->raw.base.triangles, camera, image_width, image_height, pixel);
}

std::vector<std::string> Session::keyViewWarnings() const {
  constexpr std::size_t kMaxListed = 5;
  constexpr std::size_t kMaxCounted = 1000000;
  const RawViewDependentModel& raw = model();
  const Eigen::Vector3d center = raw.resolvedCenter();
  std::vector<Eigen::Vector3d> views;
  views.reserve(raw.keys.size());
  for (const RawKey& k : raw.keys)
    views.push_back(normalizedOrNone(k.camera ? Eigen::Vector3d(k.camera->eye - center) : k.view)
                        .value_or(Eigen::Vector3d::Zero()));
  std::vector<NearlySameViewPair> close;
  const std::size_t count = nearlySameViewPairs(views, kMaxListed, kMaxCounted, close);
  std::vector<std::string> out;
  for (const NearlySameViewPair& p : close) {
    char angle[32];
    std::snprintf(angle, sizeof angle, "%.1f", p.angle_deg);
    out.push_back("keys '" + raw.keys[p.j].name + "' and '" + raw.keys[p.i].name + "' are only " + angle +
                  " degrees apart: the weights flip between them (a near-degenerate hull triangle)");
  }
  if (count > close.size()) out.push_back("... and " + std::to_string(count - close.size()) + " more close pairs");
  return out;
}

std::vector<double> Session::selectionWeights(std::int32_t vertex) const {
  return seedWeights(metric, falloff, impl_->shown(), impl_->raw.base.triangles, vertex);
}

namespace {

void requireIdle(const Session& s, const char* what) {
  if (s.stroking()) throw Error(std::string(what) + ": a stroke is in progress");
  if (s.dirty())
    throw Error(std::string(what) + ": key '" + s.model().keys[s.currentKey()].name +
                "' has unsaved strokes; save them (Ctrl+S) or undo them first");
}

}  // namespace

void Session::newKey(const std::string& name) {
  Impl& m = *impl_;
  requireIdle(*this, "new key");
  RawViewDependentModel raw = m.raw;
  if (m.current >= 0 && m.is_new) raw.keys.erase(raw.keys.begin() + m.current);  // an unstroked draft
  const std::size_t index = addKey(raw, {name, "", camera, std::nullopt, m.frame});
  const fs::path target = m.keyMeshFile(raw.keys[index]);
  if (fs::exists(fs::symlink_status(target)) || fs::exists(fs::symlink_status(editLogPath(target.string()))))
    throw Error("key '" + name + "': " + target.string() + " (or its edit log) already exists; choose another name");
  m.raw = std::move(raw);
  m.current = static_cast<int>(index);
  m.is_new = true;
  m.log_existed = false;
  m.base_log = EditLog{name, "base", {}};
  m.origin = m.raw.keys[index].mesh.positions;
  m.resetHistory();
  ++m.revision;
}

void Session::editKey(std::size_t index) {
  Impl& m = *impl_;
  requireIdle(*this, "edit key");
  if (index >= m.raw.keys.size())
    throw Error("key " + std::to_string(index) + " is out of range (the model has " +
                std::to_string(m.raw.keys.size()) + " keys)");
  if (static_cast<int>(index) == m.current && m.is_new) {  // the draft itself: back to its camera
    camera = keyEditCamera(m.raw, m.raw.keys[index]);
    ++m.revision;
    return;
  }
  const RawKey& key = m.raw.keys[index];
  const fs::path mesh = m.keyMeshFile(key);
  // A key whose mesh file another key also uses cannot be edited alone (as `vdg deform` says).
  std::error_code ec;
  for (const RawKey& other : m.raw.keys)
    if (&other != &key && fs::weakly_canonical(m.keyMeshFile(other), ec) == fs::weakly_canonical(mesh, ec))
      throw Error("key '" + key.name + "' shares its mesh file " + mesh.string() + " with key '" + other.name +
                  "': a stroke would change both; give each key its own mesh file in the manifest");
  const std::string log_path = editLogPath(mesh.string());
  const fs::path snapshot = mesh.parent_path() / (mesh.stem().string() + ".origin.obj");
  const bool log_existed = fs::exists(log_path);
  EditLog log = log_existed ? readEditLog(log_path) : startEditLog(m.raw, key, snapshot.filename().string());
  // Nothing throws from here on. A new key never saved (and never stroked: requireIdle) is dropped.
  if (m.current >= 0 && m.is_new) {
    m.raw.keys.erase(m.raw.keys.begin() + m.current);
    if (static_cast<int>(index) > m.current) --index;
  }
  m.log_existed = log_existed;
  m.base_log = std::move(log);
  m.current = static_cast<int>(index);
  m.is_new = false;
  m.poseAt(m.raw.keys[index].frame);
  m.origin = m.raw.keys[index].mesh.positions;
  m.resetHistory();
  camera = keyEditCamera(m.raw, m.raw.keys[index]);
  ++m.revision;
}

void Session::setFrame(int f) {
  Impl& m = *impl_;
  if (f < 0 || f >= frameCount())
    throw Error("frame " + std::to_string(f) + " is outside the base animation's frames 0.." +
                std::to_string(frameCount() - 1));
  if (f == m.frame) return;
  if (m.current >= 0 && m.raw.keys[m.current].frame != f) {
    requireIdle(*this, "frame");
    if (m.is_new) m.raw.keys.erase(m.raw.keys.begin() + m.current);
    m.current = -1;
    m.is_new = false;
    m.origin.clear();
    m.resetHistory();
  }
  m.poseAt(f);
  ++m.revision;
}

std::vector<int> Session::keyFrames() const {
  std::vector<int> frames;
  for (const RawKey& k : impl_->raw.keys) frames.push_back(k.frame);
  std::sort(frames.begin(), frames.end());
  frames.erase(std::unique(frames.begin(), frames.end()), frames.end());
  return frames;
}

void Session::setKeyCamera(const Camera& key_camera) {
  Impl& m = *impl_;
  if (m.current < 0 || !m.is_new) throw Error("set key camera: only a new key's camera can change");
  RawKey& key = m.raw.keys[m.current];
  key.camera = key_camera;
  key.drawing_path = m.drawing_path;
  key.drawing = m.drawing;
  m.raw.resolveViews();
  ++m.revision;
}

void Session::setDrawing(const std::string& path, std::shared_ptr<const TextureImage> image) {
  Impl& m = *impl_;
  m.drawing = path.empty() ? nullptr : std::move(image);
  m.drawing_path.clear();
  if (path.empty()) return;
  // The manifest resolves a relative drawing against its own folder; a file on another root (no
  // relative path) is written absolute.
  std::error_code ec;
  const fs::path file = fs::absolute(path, ec).lexically_normal();
  const fs::path folder = fs::absolute(m.folder.empty() ? fs::path(".") : m.folder, ec).lexically_normal();
  const fs::path relative = file.lexically_relative(folder);
  m.drawing_path = (ec || relative.empty() ? file : relative).generic_string();
}

// ---- strokes ----

namespace {

EditOp strokeOp(const Session& s, Tool tool, std::int32_t vertex, const Eigen::Vector2d& motion, double diagonal) {
  const VertexPick pick{vertex, s.metric, s.falloff, std::nullopt, std::nullopt};
  switch (tool) {
    case Tool::kDrag: {
      DragOp op{pick, Eigen::Vector2d::Zero(), motion};
      return op;
    }
    case Tool::kPushPull:
      // Mouse down (y grows) pushes away from the camera.
      return PushPullOp{pick, motion.y() * kPushPullPerPixel * diagonal, PushPullMode::kAlongRay};
    case Tool::kRotate: {
      RotateOp op;
      op.pick = pick;
      op.angle_deg = -motion.x() * kRotateDegPerPixel;  // mouse right turns clockwise, as a dial
      return op;
    }
    case Tool::kScale: {
      ScaleOp op;
      op.pick = pick;
      const double f = std::exp(motion.x() * kScalePerPixel);
      op.factor = Eigen::Vector2d(f, f);
      return op;
    }
  }
  return DragOp{pick, Eigen::Vector2d::Zero(), motion};
}

bool opMoves(const EditOp& op) {
  if (const auto* d = std::get_if<DragOp>(&op)) return d->delta_px && d->delta_px->squaredNorm() > 0;
  if (const auto* p = std::get_if<PushPullOp>(&op)) return p->amount != 0;
  if (const auto* r = std::get_if<RotateOp>(&op)) return r->angle_deg != 0;
  if (const auto* s = std::get_if<ScaleOp>(&op)) return s->factor != Eigen::Vector2d::Ones();
  return true;
}

}  // namespace

void Session::beginStroke(std::int32_t vertex, const Eigen::Vector2d& pixel) {
  Impl& m = *impl_;
  if (m.current < 0) throw Error("no key to edit: make a new key or choose one (the base itself is never edited)");
  if (m.stroking) throw Error("a stroke is in progress");
  const std::vector<float>& p = m.shown();
  if (vertex < 0 || static_cast<std::size_t>(vertex) >= p.size() / 3)
    throw Error("vertex " + std::to_string(vertex) + " is out of range (the mesh has " + std::to_string(p.size() / 3) +
                " vertices)");
  if (const auto problem = checkEditOp(strokeOp(*this, tool, vertex, Eigen::Vector2d::Zero(), m.diagonal)))
    throw Error("stroke: " + problem->field + " " + problem->message);
  // A new key takes the camera of its first stroke: the one it was aligned to the drawing in.
  if (m.is_new && m.cursor == 0) setKeyCamera(camera);
  m.stroking = true;
  m.stroke_camera = camera;
  m.stroke_vertex = vertex;
  m.stroke_start = pixel;
  m.stroke_before = p;
  m.stroke_weights = selectionWeights(vertex);
  m.stroke_pivot = vertexOf(p, vertex);
  m.stroke_depth = project(camera, image_width, image_height, m.stroke_pivot).depth;
  m.stroke_op = strokeOp(*this, tool, vertex, Eigen::Vector2d::Zero(), m.diagonal);
}

void Session::updateStroke(const Eigen::Vector2d& pixel) {
  Impl& m = *impl_;
  if (!m.stroking) return;
  const Eigen::Vector2d motion = pixel - m.stroke_start;
  m.stroke_op = strokeOp(*this, tool, m.stroke_vertex, motion, m.diagonal);
  // The live shape: the tool applied with the weights computed once at the stroke's start (the
  // same functions applyEdits calls, so endStroke's canonical result equals what was shown).
  std::vector<float>& p = m.shown();
  std::copy(m.stroke_before.begin(), m.stroke_before.end(), p.begin());
  const Camera& c = m.stroke_camera;
  std::visit(
      [&](const auto& op) {
        using T = std::decay_t<decltype(op)>;
        if constexpr (std::is_same_v<T, DragOp>) {
          dragInImagePlane(c, p, m.stroke_weights,
                           imagePlaneDelta(c, image_width, image_height, m.stroke_depth, *op.delta_px));
        } else if constexpr (std::is_same_v<T, PushPullOp>) {
          pushPull(c, p, m.stroke_weights, op.amount, op.mode);
        } else if constexpr (std::is_same_v<T, RotateOp>) {
          rotateInImagePlane(c, p, m.stroke_weights, m.stroke_pivot, op.angle_deg * std::numbers::pi / 180.0);
        } else if constexpr (std::is_same_v<T, ScaleOp>) {
          scaleInImagePlane(c, p, m.stroke_weights, m.stroke_pivot, op.factor);
        }
      },
      m.stroke_op);
  ++m.revision;
}

void Session::cancelStroke() {
  Impl& m = *impl_;
  if (!m.stroking) return;
  m.shown() = m.stroke_before;
  m.stroking = false;
  ++m.revision;
}

void Session::endStroke() {
  Impl& m = *impl_;
  if (!m.stroking) return;
  m.stroking = false;
  if (!opMoves(m.stroke_op)) {
    m.shown() = m.stroke_before;
    ++m.revision;
    return;
  }
  const std::array<int, 2> size{image_width, image_height};
  const EditOp op = m.stroke_op;
  const Camera c = m.stroke_camera;
  // The canonical result: the op applied as `vdg deform` and a replay of the log apply it.
  std::vector<float> after = m.stroke_before;
  try {
    applyEdits(c, m.raw.base.triangles, after, std::span<const EditOp>(&op, 1), size, "stroke");
  } catch (...) {
    m.shown() = m.stroke_before;
    ++m.revision;
    throw;
  }
  m.shown() = std::move(after);
  m.pushStroke({c, size, {op}});
}

void Session::applyOps(std::span<const EditOp> ops) {
  Impl& m = *impl_;
  if (m.current < 0) throw Error("no key to edit: make a new key or choose one");
  if (m.stroking) throw Error("a stroke is in progress");
  validateEdits(ops, m.shown().size() / 3, "ops");
  if (m.is_new && m.cursor == 0) setKeyCamera(camera);
  const std::array<int, 2> size{image_width, image_height};
  std::vector<float> after = m.shown();
  applyEdits(camera, m.raw.base.triangles, after, ops, size, "ops");
  m.shown() = std::move(after);
  m.pushStroke({camera, size, std::vector<EditOp>(ops.begin(), ops.end())});
}

void Session::applyLines(bool snap_silhouette) {
  if (line_pairs.empty()) throw Error("no feature lines: drag the model's line, then the drawing's");
  LinesOp op{line_pairs, line_settings};
  if (snap_silhouette)
    op.pairs = snapToSilhouette(
        op.pairs, projectedSilhouette(camera, image_width, image_height, positions(), baseMesh().triangles));
  const EditOp edit = std::move(op);
  applyOps(std::span<const EditOp>(&edit, 1));
  line_pairs.clear();
}

bool Session::canUndo() const { return !impl_->stroking && impl_->cursor > impl_->undo_floor; }
bool Session::canRedo() const { return !impl_->stroking && impl_->cursor < impl_->strokes.size(); }

void Session::undo() {
  Impl& m = *impl_;
  if (!canUndo()) return;
  --m.cursor;
  m.shown() = m.cursor == m.undo_floor ? m.floor_shape : m.shapes[m.cursor - m.undo_floor - 1];
  ++m.revision;
  m.autosave();
}

void Session::redo() {
  Impl& m = *impl_;
  if (!canRedo()) return;
  const EditLogEntry& e = m.strokes[m.cursor];
  std::vector<float> after = m.shown();
  applyEdits(e.camera, m.raw.base.triangles, after, e.ops, e.image_size, "redo");
  m.shown() = std::move(after);
  ++m.cursor;
  m.shapes.resize(m.cursor - m.undo_floor - 1);
  m.shapes.push_back(m.shown());
  ++m.revision;
  m.autosave();
}

AlignResult Session::solveAlignment(bool ortho) const {
  std::vector<Eigen::Vector3d> points;
  std::vector<Eigen::Vector2d> pixels;
  const std::vector<float>& base = impl_->raw.animated() ? impl_->posed : impl_->raw.base.positions;
  for (const Pair& pair : pairs) {
    if (pair.vertex < 0 || static_cast<std::size_t>(pair.vertex) >= base.size() / 3)
      throw Error("alignment: vertex " + std::to_string(pair.vertex) + " is out of range");
    points.push_back(vertexOf(base, pair.vertex));
    pixels.push_back(pair.pixel);
  }
  AlignOptions options;
  options.ortho = ortho;
  return alignCamera(points, pixels, image_width, image_height, options);
}

// ---- files ----

void Session::saveKey() {
  Impl& m = *impl_;
  if (m.current < 0) throw Error("save key: no key to save (make a new key or choose one)");
  if (m.stroking) throw Error("save key: a stroke is in progress");
  RawKey& key = m.raw.keys[m.current];
  m.raw.validate();
  const fs::path mesh = m.keyMeshFile(key);
  const std::string log_path = editLogPath(mesh.string());
  const fs::path snapshot = mesh.parent_path() / (mesh.stem().string() + ".origin.obj");
  EditLog log = m.base_log;
  log.entries.insert(log.entries.end(), m.strokes.begin(), m.strokes.begin() + static_cast<std::ptrdiff_t>(m.cursor));

  const std::string folder = m.folder.empty() ? "." : m.folder.string();
  const FolderLock lock(folder);
  const std::string journal = (m.folder / kJournalName).string();
  std::vector<std::string> key_files;  // an interrupted step may have written these in keys/
  for (const RawKey& k : m.raw.keys) {
    key_files.push_back(m.keyMeshFile(k).string());
    key_files.push_back(editLogPath(m.keyMeshFile(k).string()));
    key_files.push_back((m.keyMeshFile(k).parent_path() / (m.keyMeshFile(k).stem().string() + ".origin.obj")).string());
  }
  recoverFileTransaction(journal, key_files);
  FileTransaction transaction(journal);
  // No write may land on the base or another key's files through another name (a link).
  // (An OBJ sequence's frames are many files; the glTF of an animated base is one.)
  const std::string base_file = m.raw.base_animation ? m.raw.base_animation->gltf : m.raw.base_path;
  if (!base_file.empty()) transaction.protect((m.folder / base_file).string(), "the base mesh " + base_file);
  for (const RawKey& other : m.raw.keys)
    if (&other != &key) transaction.protect(m.keyMeshFile(other).string(), "the mesh of key '" + other.name + "'");
  if (!m.log_existed && log.origin != "base") {
    TriMesh before = key.mesh;
    before.positions = m.origin;
    transaction.write(snapshot.string(),
                      formatObj(before, "vdg studio: key '" + key.name + "' before its first logged edit"));
  }
  transaction.write(mesh.string(), formatObj(key.mesh, "vdg studio: key '" + key.name + "'"));
  transaction.write(log_path, formatEditLog(log));
  if (m.is_new || !m.manifest_exists) transaction.write(m.manifest_path, formatManifest(m.raw));
  transaction.commit();
  m.manifest_exists = true;
  m.is_new = false;
  m.log_existed = true;
  m.saved = m.cursor;
  m.saved_valid = true;
  m.autosave();
}

void Session::recover() {
  Impl& m = *impl_;
  if (!m.recovery) throw Error("recover: no recovered strokes for " + m.manifest_path);
  requireIdle(*this, "recover");
  const StudioRecovery r = *m.recovery;
  const std::string where = m.recovery_path;
  if (r.manifest != m.manifest_path) throw Error(where + ": it recovers " + r.manifest + ", not " + m.manifest_path);
  int index = -1;
  for (std::size_t k = 0; k < m.raw.keys.size(); ++k)
    if (m.raw.keys[k].name == r.key) index = static_cast<int>(k);
  if (r.new_key) {
    if (index >= 0) throw Error(where + ": key '" + r.key + "' was saved since; nothing to recover");
    if (!r.key_camera) throw Error(where + ": the new key has no camera");
    const Camera keep = camera;
    camera = *r.key_camera;
    setFrame(r.key_frame);
    newKey(r.key);
    camera = keep;
  } else {
    if (index < 0) throw Error(where + ": the model has no key '" + r.key + "' any more");
    editKey(static_cast<std::size_t>(index));
    // The log on disk may hold strokes saved in the lost session after the recovered ones began.
    if (m.base_log.entries.size() < r.logged)
      throw Error(where + ": the edit log of key '" + r.key + "' is shorter than when the strokes were made");
    if (m.base_log.entries.size() > r.logged) {
      m.base_log.entries.resize(r.logged);
      const RawKey& key = m.raw.keys[m.current];
      TriMesh origin = posedBase(m.raw, key.frame);
      if (m.base_log.origin != "base") {
        const fs::path mesh = m.keyMeshFile(key);
        origin.positions = readObj((mesh.parent_path() / m.base_log.origin).string()).positions;
        if (origin.positions.size() != m.raw.base.positions.size())
          throw Error(where + ": the origin of key '" + r.key + "' no longer fits the base");
      }
      m.origin = replayEditLog(origin, m.base_log, editLogPath(m.keyMeshFile(key).string()));
      m.shown() = m.origin;
      m.floor_shape = m.origin;
      m.saved_valid = false;
    }
  }
  const Camera keep = camera;
  const int keep_w = image_width, keep_h = image_height;
  try {
    for (const EditLogEntry& e : r.strokes) {
      camera = e.camera;
      if (e.image_size) image_width = (*e.image_size)[0], image_height = (*e.image_size)[1];
      applyOps(e.ops);
    }
  } catch (...) {
    camera = keep, image_width = keep_w, image_height = keep_h;
    throw;
  }
  camera = keep, image_width = keep_w, image_height = keep_h;
  m.recovery.reset();
}

void Session::discardRecovery() {
  std::error_code ec;
  fs::remove(impl_->recovery_path, ec);
  impl_->recovery.reset();
}

}  // namespace vdg::studio
