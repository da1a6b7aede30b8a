// glTF 2.0 output of view-dependent models (see vdg/io/gltf_export.h and docs/gltf-export.md).
//
// Rademacher 99, section 3.2.3: the blended model is base + sum_i w_i (key_i - base); glTF 2.0
// (section 3.7.2.2, morph targets) renders base + sum_i weights[i] * target_i, so the key deltas
// are the targets and a view's weights are the morph weights. The JSON follows the glTF 2.0
// specification; the binary buffer is laid out here.
#include "vdg/io/gltf_export.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <numbers>
#include <set>
#include <tuple>

#include "camera_fields.h"
#include "gltf_codes.h"
#include "gltf_compress_pass.h"
#include "json_reader.h"
#include "model_names.h"
#include "vdg/geom/error.h"
#include "vdg/geom/normalize.h"
#include "vdg/geom/text.h"
#include "vdg/io/atomic_file.h"
#include "vdg/io/file_transaction.h"
#include "vdg/io/gltf.h"
#include "vdg/io/gltf_interactivity.h"
#include "vdg/io/image_file.h"
#include "vdg/io/read_file.h"
#include "vdg/version.h"

namespace vdg {
namespace {

static_assert(std::endian::native == std::endian::little, "the glTF buffer is written in the host's byte order");

using OJson = nlohmann::ordered_json;

using namespace gltf_codes;
constexpr int kTriangles = 4;
constexpr std::uint32_t kGlbMagic = 0x46546C67;  // "glTF"
constexpr std::uint32_t kGlbVersion = 2;
constexpr std::uint32_t kChunkJson = 0x4E4F534A;  // "JSON"
constexpr std::uint32_t kChunkBin = 0x004E4942;   // "BIN\0"
// A NORMAL accessor's vectors must be unit length (glTF 2.0 section 3.7.2.1); the validator allows
// a small float error, this is looser than float rounding and far tighter than a wrong normal.
constexpr double kUnitNormalTol = 1e-4;

// The binary buffer and the bufferViews / accessors describing it.
class BufferBuilder {
 public:
  // Appends `bytes` as a new bufferView (starting on a 4-byte boundary); target 0 = none.
  int addView(const void* bytes, std::size_t size, int target) {
    data_.resize(pad4(data_.size()), '\0');
    OJson view = {{"buffer", 0}, {"byteOffset", data_.size()}, {"byteLength", size}};
    if (target != 0) view["target"] = target;
    data_.append(static_cast<const char*>(bytes), size);
    views_.push_back(std::move(view));
    return static_cast<int>(views_.size()) - 1;
  }
  int addAccessor(OJson accessor) {
    accessors_.push_back(std::move(accessor));
    return static_cast<int>(accessors_.size()) - 1;
  }
  // A float accessor over a new view; min/max when `bounds` (required for POSITION).
  int addFloats(std::span<const float> values, int components, int target, bool bounds) {
    const int view = addView(values.data(), values.size() * sizeof(float), target);
    OJson acc = {{"bufferView", view},
                 {"componentType", kFloat},
                 {"count", values.size() / components},
                 {"type", typeName(components)}};
    if (bounds) addBounds(acc, values, components, false);
    return addAccessor(std::move(acc));
  }
  static const char* typeName(int components) {
    switch (components) {
      case 1:
        return "SCALAR";
      case 2:
        return "VEC2";
      case 3:
        return "VEC3";
      default:
        return "VEC4";
    }
  }
  // min/max per component; `with_zero` includes the zero vector (elements a sparse accessor
  // leaves at their initial zeros).
  static void addBounds(OJson& acc, std::span<const float> values, int components, bool with_zero) {
    std::vector<float> lo(components, std::numeric_limits<float>::infinity()), hi(components, -lo[0]);
    if (with_zero) std::fill(lo.begin(), lo.end(), 0.0f), std::fill(hi.begin(), hi.end(), 0.0f);
    for (std::size_t i = 0; i < values.size(); ++i) {
      const int c = static_cast<int>(i % components);
      lo[c] = std::min(lo[c], values[i]);
      hi[c] = std::max(hi[c], values[i]);
    }
    acc["min"] = OJson::array();
    acc["max"] = OJson::array();
    for (int c = 0; c < components; ++c) {
      acc["min"].push_back(static_cast<double>(lo[c]));
      acc["max"].push_back(static_cast<double>(hi[c]));
    }
  }
  std::string& data() { return data_; }
  OJson& views() { return views_; }
  OJson& accessors() { return accessors_; }

 private:
  std::string data_;
  OJson views_ = OJson::array(), accessors_ = OJson::array();
};

// A morph target attribute (#V x 3 deltas) as a dense accessor, or as a sparse one (only the
// vertices that move, over implicit zeros) when that takes fewer bytes. Returns the accessor and
// sets `sparse`.
int addDeltaAccessor(BufferBuilder& b, std::span<const float> deltas, bool bounds, bool& sparse) {
  const std::size_t v_count = deltas.size() / 3;
  std::vector<std::uint32_t> moved;
  for (std::size_t v = 0; v < v_count; ++v)
    if (deltas[v * 3] != 0.0f || deltas[v * 3 + 1] != 0.0f || deltas[v * 3 + 2] != 0.0f)
      moved.push_back(static_cast<std::uint32_t>(v));
  // sparse.count must be >= 1: a target that moves nothing lists vertex 0 with a zero delta.
  if (moved.empty()) moved.push_back(0);
  const int index_size = v_count <= 256 ? 1 : v_count <= 65536 ? 2 : 4;
  const std::size_t sparse_bytes = pad4(moved.size() * index_size) + moved.size() * 12;
  const std::size_t dense_bytes = v_count * 12;
  sparse = sparse_bytes < dense_bytes;
  if (!sparse) return b.addFloats(deltas, 3, kArrayBuffer, bounds);

  std::vector<float> values;
  values.reserve(moved.size() * 3);
  for (std::uint32_t v : moved) values.insert(values.end(), deltas.begin() + v * 3, deltas.begin() + v * 3 + 3);
  std::string index_bytes(moved.size() * index_size, '\0');
  for (std::size_t i = 0; i < moved.size(); ++i) {
    if (index_size == 1) index_bytes[i] = static_cast<char>(moved[i]);
    if (index_size == 2) {
      const auto x = static_cast<std::uint16_t>(moved[i]);
      std::memcpy(&index_bytes[i * 2], &x, 2);
    }
    if (index_size == 4) std::memcpy(&index_bytes[i * 4], &moved[i], 4);
  }
  const int index_view = b.addView(index_bytes.data(), index_bytes.size(), 0);
  const int value_view = b.addView(values.data(), values.size() * sizeof(float), 0);
  const int component = index_size == 1 ? kUnsignedByte : index_size == 2 ? kUnsignedShort : kUnsignedInt;
  OJson acc = {{"componentType", kFloat},
               {"count", v_count},
               {"type", "VEC3"},
               {"sparse",
                {{"count", moved.size()},
                 {"indices", {{"bufferView", index_view}, {"componentType", component}}},
                 {"values", {{"bufferView", value_view}}}}}};
  if (bounds) BufferBuilder::addBounds(acc, values, 3, moved.size() < v_count);
  return b.addAccessor(std::move(acc));
}

bool allFinite(std::span<const float> values) {
  return std::all_of(values.begin(), values.end(), [](float x) { return std::isfinite(x); });
}
bool allFinite(std::span<const double> values) {
  return std::all_of(values.begin(), values.end(), [](double x) { return std::isfinite(x); });
}

std::string baseFrameTargetName(int frame) { return "base frame " + std::to_string(frame); }

bool framesBase(const GltfExportInput& in) {
  return in.base_animation && in.base_animation->mode == GltfBaseMode::kFrames;
}
bool skinBase(const GltfExportInput& in) { return in.base_animation && in.base_animation->mode == GltfBaseMode::kSkin; }

// Morph targets written: the keys, then the base frames 1..N-1 of a kFrames base.
std::size_t totalTargets(const GltfExportInput& in) {
  return in.targets.size() + (framesBase(in) ? in.base_animation->frame_deltas.size() : 0);
}

// The view sphere of an input (extras v2): sizes consistent with the targets, indices in range.
template <typename Fail>
void validateViewSphere(const GltfExportInput& in, const Fail& fail) {
  if (!in.view_sphere) {
    if (in.base_animation && !in.targets.empty()) fail("an animated input needs its view sphere (internal error)");
    if (in.base_animation || in.targets.empty()) return;
    std::vector<Eigen::Vector3d> views;  // the writer builds the sphere from the targets: can it?
    for (const GltfTarget& t : in.targets) views.push_back(t.view);
    try {
      (void)ViewSphere::build(views, in.sphere);
    } catch (const Error& e) {
      fail(e.what());
    }
    return;
  }
  const GltfViewSphere& vs = *in.view_sphere;
  const auto points = static_cast<int>(vs.points.size());
  if (vs.views == 0 || vs.views > vs.points.size() || vs.view_targets.size() != vs.views)
    fail("view sphere: expected 1 to #points key views, each with its targets (internal error)");
  if (vs.inverses.size() != vs.triangles.size()) fail("view sphere: one inverse per triangle (internal error)");
  const auto inRange = [&](int i, int n) { return i >= 0 && i < n; };
  for (const auto& t : vs.triangles)
    if (!inRange(t[0], points) || !inRange(t[1], points) || !inRange(t[2], points))
      fail("view sphere: a triangle index is out of range (internal error)");
  for (const auto& a : vs.arcs)
    if (!inRange(a[0], points) || !inRange(a[1], points)) fail("view sphere: an arc index is out of range");
  for (int k : vs.isolated)
    if (!inRange(k, static_cast<int>(vs.views))) fail("view sphere: an isolated key is out of range");
  std::vector<int> seen(in.targets.size(), 0);
  for (const auto& targets : vs.view_targets)
    for (int t : targets)
      if (!inRange(t, static_cast<int>(in.targets.size())) || seen[static_cast<std::size_t>(t)]++)
        fail("view sphere: every key target must belong to exactly one view (internal error)");
  if (std::find(seen.begin(), seen.end(), 0) != seen.end())
    fail("view sphere: a key target belongs to no view (internal error)");
  if (!vs.time.empty() && vs.time.size() != vs.views) fail("view sphere: one time table per view (internal error)");
  for (std::size_t i = 0; i < vs.time.size(); ++i) {
    const std::size_t m = vs.time[i].frames.size();
    if (m != vs.view_targets[i].size() || vs.time[i].second.size() != m * m)
      fail("view sphere: view " + std::to_string(i) + "'s time table does not match its targets (internal error)");
  }
  if (in.base_animation && vs.time.size() != vs.views) fail("view sphere: an animated input needs its time tables");
  // The rbf weights are over every key view (extras v4): the solved interpolation, one row per
  // centre plus the constants, one value per view plus the base.
  const bool rbf = in.sphere.scheme == WeightScheme::Rbf;
  const std::size_t rbf_size = rbf ? (vs.points.size() + 1) * (vs.views + 1) : 0;
  if (vs.rbf_coefficients.size() != rbf_size || (rbf && !(vs.rbf_chord2 > 0.0 && std::isfinite(vs.rbf_chord2))) ||
      !allFinite(vs.rbf_coefficients))
    fail("view sphere: the rbf coefficients do not match the scheme and the points (internal error)");
}

void validateInput(const GltfExportInput& in, const std::string& where) {
  const auto fail = [&](const std::string& what) { throw Error(where + ": " + what); };
  const std::size_t v_count = in.base.vertexCount();
  if (v_count == 0 || in.base.triangleCount() == 0) fail("the base mesh has no vertices or no triangles");
  validateMesh(in.base, where + ": base");
  if (v_count > std::numeric_limits<std::uint32_t>::max()) fail("the base mesh has too many vertices for glTF");
  if (!in.normals.empty()) {
    if (in.normals.size() != in.base.positions.size())
      fail("normals: expected " + std::to_string(v_count) + " x 3 floats, got " + std::to_string(in.normals.size()));
    for (std::size_t v = 0; v < v_count; ++v) {
      const double len = Eigen::Vector3d(in.normals[v * 3], in.normals[v * 3 + 1], in.normals[v * 3 + 2]).norm();
      if (!(std::abs(len - 1.0) <= kUnitNormalTol))
        fail("normals: vertex " + std::to_string(v) + " is not unit length");
    }
  }
  std::set<std::string> names;
  for (std::size_t t = 0; t < in.targets.size(); ++t) {
    const GltfTarget& target = in.targets[t];
    const std::string label = "target " + std::to_string(t) + " '" + target.name + "'";
    if (target.name.empty()) fail("target " + std::to_string(t) + " has no name");
    if (!names.insert(target.name).second) fail(label + ": the name is used twice");
    if (target.deltas.size() != in.base.positions.size())
      fail(label + ": expected " + std::to_string(v_count) + " x 3 deltas, got " +
           std::to_string(target.deltas.size()));
    if (!allFinite(target.deltas)) fail(label + ": a delta is not finite");
    if (!target.normal_deltas.empty() && (in.normals.empty() || target.normal_deltas.size() != in.normals.size()))
      fail(label + ": normal deltas need base normals and " + std::to_string(v_count) + " x 3 floats");
    if (!allFinite(target.normal_deltas)) fail(label + ": a normal delta is not finite");
    if (!target.view.allFinite() || !normalizedOrNone(target.view)) fail(label + ": the view is zero or not finite");
    if (target.frame < 0) fail(label + ": the frame is negative");
  }
  if (!std::isfinite(in.sharpness) || in.sharpness <= 0.0) fail("the sharpness must be finite and > 0");
  if (!in.center.allFinite()) fail("the centre is not finite");
  if (in.base_animation) {
    const GltfBaseAnimation& ba = *in.base_animation;
    if (ba.frame_count < 1 || !std::isfinite(ba.fps) || ba.fps <= 0.0)
      fail("base animation: expected frame_count >= 1 and fps > 0");
    if (ba.mode == GltfBaseMode::kFrames) {
      if (ba.frame_deltas.size() != static_cast<std::size_t>(ba.frame_count) - 1)
        fail("base animation: expected " + std::to_string(ba.frame_count - 1) + " base frame targets, got " +
             std::to_string(ba.frame_deltas.size()));
      if (!ba.frame_normal_deltas.empty() &&
          (in.normals.empty() || ba.frame_normal_deltas.size() != ba.frame_deltas.size()))
        fail("base animation: base frame normal deltas need base normals and one entry per base frame");
      for (std::size_t i = 0; i < ba.frame_deltas.size(); ++i) {
        const std::string label = "base animation: frame " + std::to_string(i + 1);
        if (ba.frame_deltas[i].size() != in.base.positions.size() || !allFinite(ba.frame_deltas[i]))
          fail(label + ": expected " + std::to_string(v_count) + " x 3 finite deltas");
        if (!ba.frame_normal_deltas.empty() &&
            (ba.frame_normal_deltas[i].size() != in.normals.size() || !allFinite(ba.frame_normal_deltas[i])))
          fail(label + ": expected " + std::to_string(v_count) + " x 3 finite normal deltas");
        if (!names.insert(baseFrameTargetName(static_cast<int>(i + 1))).second)
          fail(label + ": a key is named '" + baseFrameTargetName(static_cast<int>(i + 1)) + "'");
      }
    } else {
      if (!ba.rig || !ba.rig->skin) fail("base animation: a skinned base needs its rig with a skin");
      const RawRig& rig = *ba.rig;
      rig.validate();
      if (rig.mesh.vertexCount() != v_count)
        fail("base animation: the rig has " + std::to_string(rig.mesh.vertexCount()) + " vertices, the base " +
             std::to_string(v_count));
      if (ba.rig_animation < 0 || static_cast<std::size_t>(ba.rig_animation) >= rig.animations.size())
        fail("base animation: the rig has no animation " + std::to_string(ba.rig_animation));
      if (!rig.target_positions.empty())
        fail("base animation: the rig's mesh has morph targets of its own, which are not exported");
    }
  }
  if (in.bake) {
    const GltfBakedAnimation& bake = *in.bake;
    const std::size_t n = bake.times.size();
    if (n == 0) fail("bake: no sample times");
    if (!allFinite(bake.times)) fail("bake: a time is not finite");
    for (std::size_t i = 1; i < n; ++i)
      if (!(bake.times[i] > bake.times[i - 1]))
        fail("bake: times are not strictly increasing at sample " + std::to_string(i));
    if (totalTargets(in) == 0) fail("bake: the model has no morph targets to animate");
    const std::size_t target_count = totalTargets(in);
    if (bake.weights.size() != n * target_count)
      fail("bake: expected " + std::to_string(n) + " x " + std::to_string(target_count) + " weights, got " +
           std::to_string(bake.weights.size()));
    const std::size_t rig_nodes =
        in.base_animation && in.base_animation->rig ? in.base_animation->rig->nodes.size() : 0;
    for (const GltfNodeTrack& track : bake.node_tracks) {
      const std::size_t width = track.path == RigPath::kRotation ? 4 : 3;
      if (track.node < 0 || static_cast<std::size_t>(track.node) >= rig_nodes || track.path == RigPath::kWeights ||
          track.values.size() != n * width || !allFinite(track.values))
        fail("bake: a node track does not match the rig or the times");
    }
    if (!allFinite(bake.weights)) fail("bake: a weight is not finite");
    if (!bake.translations.empty()) {
      if (bake.translations.size() != n * 3 || bake.rotations.size() != n * 4)
        fail("bake: expected " + std::to_string(n) + " camera translations and rotations");
      if (!allFinite(bake.translations) || !allFinite(bake.rotations)) fail("bake: a camera value is not finite");
      if (!(bake.yfov_rad > 0.0 && bake.yfov_rad < std::numbers::pi) || !(bake.aspect > 0.0) ||
          !std::isfinite(bake.aspect) || !(bake.znear > 0.0) || !(bake.zfar > bake.znear) || !std::isfinite(bake.zfar))
        fail("bake: expected 0 < yfov < pi, aspect > 0 and 0 < znear < zfar");
    }
  }
  validateViewSphere(in, fail);
}

OJson vec3Json(const Eigen::Vector3d& v) { return OJson::array({v.x(), v.y(), v.z()}); }

// Index of the glTF animation that plays the base (written after a bake's animation), or -1 when
// the base needs none (a kFrames base of one frame, a kSkin animation without TRS channels).
int baseAnimationIndex(const GltfExportInput& in) {
  if (!in.base_animation) return -1;
  const GltfBaseAnimation& ba = *in.base_animation;
  bool any = false;
  if (ba.mode == GltfBaseMode::kFrames) {
    any = ba.frame_count > 1;
  } else if (ba.rig && ba.rig_animation >= 0 &&
             static_cast<std::size_t>(ba.rig_animation) < ba.rig->animations.size()) {
    for (const RigChannel& ch : ba.rig->animations[static_cast<std::size_t>(ba.rig_animation)].channels)
      any = any || ch.path != RigPath::kWeights;
  }
  return any ? (in.bake ? 1 : 0) : -1;
}

OJson vec3Array(std::span<const Eigen::Vector3d> points) {
  OJson out = OJson::array();
  for (const Eigen::Vector3d& p : points) out.push_back(vec3Json(p));
  return out;
}

// Extras v2 "sphere" (and "time" into `vdg` for an animated model): exactly the built sphere.
void addSphereJson(const GltfViewSphere& vs, OJson& vdg) {
  OJson sphere = {{"points", vec3Array(vs.points)}, {"views", vs.views}};
  OJson triangles = OJson::array(), inverses = OJson::array(), arcs = OJson::array();
  for (const auto& t : vs.triangles) triangles.push_back({t[0], t[1], t[2]});
  for (const Eigen::Matrix3d& m : vs.inverses) {
    OJson row_major = OJson::array();
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) row_major.push_back(m(r, c));
    inverses.push_back(std::move(row_major));
  }
  for (const auto& a : vs.arcs) arcs.push_back({a[0], a[1]});
  sphere["triangles"] = std::move(triangles);
  sphere["inverses"] = std::move(inverses);
  sphere["arcs"] = std::move(arcs);
  sphere["isolated"] = vs.isolated;
  sphere["view_targets"] = vs.view_targets;
  if (!vs.rbf_coefficients.empty()) {  // extras v4: rows of views + 1 values (constants, then per point)
    const std::size_t outputs = vs.views + 1;
    OJson rows = OJson::array();
    for (std::size_t r = 0; r * outputs < vs.rbf_coefficients.size(); ++r)
      rows.push_back(std::vector<double>(vs.rbf_coefficients.begin() + static_cast<std::ptrdiff_t>(r * outputs),
                                         vs.rbf_coefficients.begin() + static_cast<std::ptrdiff_t>((r + 1) * outputs)));
    sphere["rbf"] = {{"chord2", vs.rbf_chord2}, {"coefficients", std::move(rows)}};
  }
  vdg["sphere"] = std::move(sphere);
  if (vs.time.empty()) return;
  OJson time = OJson::array();
  for (const GltfViewTime& t : vs.time) time.push_back({{"frames", t.frames}, {"second", t.second}});
  vdg["time"] = std::move(time);
}

// The view-dependent description (mesh.extras.vdg; docs/schema/vdg-gltf-extras.schema.json).
OJson vdgExtras(const GltfExportInput& in) {
  // The oldest version that holds the model: 2 for the paper's linear weights, 3 for smooth ones,
  // 4 for rbf ones (their kernel, width and solved interpolation).
  const bool linear = in.sphere.scheme == WeightScheme::Linear;
  const bool rbf = in.sphere.scheme == WeightScheme::Rbf;
  OJson vdg = {{"version", linear ? 2 : (rbf ? 4 : 3)},
               {"sharpness", in.sharpness},
               {"uncovered", uncoveredName(in.sphere.uncovered)},
               {"base_falloff_deg", in.sphere.base_falloff_deg},
               {"center", vec3Json(in.center)},
               {"offsets", offsetSpaceName(in.offsets)}};
  if (!linear) vdg["weights"] = {{"scheme", weightSchemeName(in.sphere.scheme)}};
  if (rbf) {
    vdg["weights"]["kernel"] = rbfKernelName(in.sphere.rbf_kernel);
    vdg["weights"]["width"] = in.sphere.rbf_width_deg;
  }
  if (in.base_animation) {
    OJson anim = {{"frame_count", in.base_animation->frame_count},
                  {"fps", in.base_animation->fps},
                  {"loop", in.base_animation->loop}};
    if (const int index = baseAnimationIndex(in); index >= 0) anim["animation"] = index;
    anim["base"] = gltfBaseModeName(in.base_animation->mode);
    vdg["animation"] = anim;
  }
  OJson keys = OJson::array();
  for (const GltfTarget& t : in.targets) {
    OJson key = {{"name", t.name}, {"view", vec3Json(t.view)}, {"frame", t.frame}};
    if (t.camera) key["camera"] = io::cameraJson(*t.camera);
    keys.push_back(std::move(key));
  }
  vdg["keys"] = std::move(keys);
  if (in.view_sphere) {
    addSphereJson(*in.view_sphere, vdg);
  } else if (!in.targets.empty()) {  // a hand-made static input: its targets are the keys
    std::vector<Eigen::Vector3d> views;
    for (const GltfTarget& t : in.targets) views.push_back(t.view);
    addSphereJson(gltfViewSphere(ViewSphere::build(views, in.sphere)), vdg);
  }
  return vdg;
}

// The exported vertex list. glTF keeps one value of each attribute per vertex (glTF 2.0 section
// 3.7.2.1), so a model vertex whose corners carry different uvs (a seam) is split: the first copy
// keeps the model's index (exported vertices 0..#V-1 are the model's vertices in order) and every
// further (vertex, uv) pair is appended once. Every copy carries the model vertex's position,
// normal, skin and morph target deltas, and _VDG_VERTEX names its model vertex.
struct ExportVertices {
  std::vector<std::uint32_t> model_vertex;  // per exported vertex: its vertex in the model
  std::vector<std::int32_t> triangles;      // #F x 3 exported vertex indices
  std::vector<float> uvs;                   // empty, or #E x 2 with glTF's top-left origin (v' = 1 - v)
  std::size_t count() const { return model_vertex.size(); }
  bool split() const { return !model_vertex.empty() && model_vertex.back() + 1 != model_vertex.size(); }
};

ExportVertices exportVertices(const TriMesh& base) {
  ExportVertices ev;
  const std::size_t v_count = base.vertexCount();
  ev.model_vertex.resize(v_count);
  for (std::size_t v = 0; v < v_count; ++v) ev.model_vertex[v] = static_cast<std::uint32_t>(v);
  ev.triangles = base.triangles;
  if (base.uvs.empty() || base.uv_triangles.size() != base.triangles.size()) return ev;
  ev.uvs.assign(v_count * 2, 0.0f);
  std::vector<char> seen(v_count, 0);
  // Split copies by (model vertex, u bits, v bits): equal uvs share one copy.
  std::map<std::tuple<std::int32_t, std::uint32_t, std::uint32_t>, std::int32_t> copies;
  for (std::size_t c = 0; c < base.triangles.size(); ++c) {
    const std::int32_t v = base.triangles[c];
    const auto t = static_cast<std::size_t>(base.uv_triangles[c]);
    const float u = base.uvs[t * 2], w = 1.0f - base.uvs[t * 2 + 1];
    const auto vi = static_cast<std::size_t>(v);
    if (!seen[vi]) {
      ev.uvs[vi * 2] = u, ev.uvs[vi * 2 + 1] = w, seen[vi] = 1;
      continue;
    }
    if (ev.uvs[vi * 2] == u && ev.uvs[vi * 2 + 1] == w) continue;
    const auto key = std::make_tuple(v, std::bit_cast<std::uint32_t>(u), std::bit_cast<std::uint32_t>(w));
    auto it = copies.find(key);
    if (it == copies.end()) {
      it = copies.emplace(key, static_cast<std::int32_t>(ev.model_vertex.size())).first;
      ev.model_vertex.push_back(static_cast<std::uint32_t>(v));
      ev.uvs.push_back(u);
      ev.uvs.push_back(w);
    }
    ev.triangles[c] = it->second;
  }
  return ev;
}

// A per-model-vertex array (`width` floats a vertex) copied to the exported vertices.
std::vector<float> gathered(std::span<const float> values, std::size_t width, const ExportVertices& ev) {
  std::vector<float> out(ev.count() * width);
  for (std::size_t e = 0; e < ev.count(); ++e)
    std::copy_n(values.begin() + static_cast<std::ptrdiff_t>(ev.model_vertex[e] * width), width,
                out.begin() + static_cast<std::ptrdiff_t>(e * width));
  return out;
}

// _VDG_VERTEX: each exported vertex's index in the model. Application-specific attributes may not
// use unsigned int (glTF 2.0 section 3.7.2.1), and vertex attribute elements start on 4-byte
// boundaries: unsigned shorts with a byte stride of 4 up to 65536 model vertices, else floats (exact
// below 2^24, kMaxGltfElements).
int addVertexIds(BufferBuilder& b, const ExportVertices& ev, std::size_t v_count) {
  if (v_count <= 65536) {
    std::vector<std::uint16_t> ids(ev.count() * 2, 0);
    for (std::size_t e = 0; e < ev.count(); ++e) ids[e * 2] = static_cast<std::uint16_t>(ev.model_vertex[e]);
    const int view = b.addView(ids.data(), ids.size() * 2, kArrayBuffer);
    b.views()[static_cast<std::size_t>(view)]["byteStride"] = 4;
    return b.addAccessor(
        {{"bufferView", view}, {"componentType", kUnsignedShort}, {"count", ev.count()}, {"type", "SCALAR"}});
  }
  std::vector<float> ids(ev.model_vertex.begin(), ev.model_vertex.end());
  return b.addFloats(ids, 1, kArrayBuffer, false);
}

// One primitive per material (TriMesh::face_materials), in the order of first use so that a mesh
// whose faces are grouped by material keeps its triangle order; faces without a material (-1, or an
// index out of range) share the plain material (-1 here).
struct ExportGroup {
  int material = -1;
  std::vector<std::int32_t> indices;  // exported vertex indices, 3 per triangle
};

std::vector<ExportGroup> exportGroups(const TriMesh& base, const ExportVertices& ev) {
  std::vector<ExportGroup> groups;
  std::map<int, std::size_t> group_of;
  for (std::size_t f = 0; f < base.triangleCount(); ++f) {
    int m = f < base.face_materials.size() ? base.face_materials[f] : -1;
    if (m < 0 || static_cast<std::size_t>(m) >= base.materials.size()) m = -1;
    auto it = group_of.find(m);
    if (it == group_of.end()) {
      it = group_of.emplace(m, groups.size()).first;
      groups.push_back({m, {}});
    }
    std::vector<std::int32_t>& idx = groups[it->second].indices;
    idx.insert(idx.end(), ev.triangles.begin() + static_cast<std::ptrdiff_t>(f * 3),
               ev.triangles.begin() + static_cast<std::ptrdiff_t>(f * 3 + 3));
  }
  return groups;
}

// Where an export's images go: into the buffer (a .glb: bufferView and mimeType), into files beside
// a .gltf (uri "STEM-texture-N.png"), or into data: URIs (a .gltf serialised without side files).
enum class ImageStore { kBuffer, kFiles, kDataUri };

struct ImageOutput {
  ImageStore store = ImageStore::kBuffer;
  std::string stem;                             // kFiles: the names' prefix
  std::vector<GltfImageFile>* files = nullptr;  // kFiles: where the files' bytes go
};

std::string base64(std::string_view bytes) {
  static constexpr char kDigits[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    const std::size_t n = std::min<std::size_t>(3, bytes.size() - i);
    std::uint32_t x = 0;
    for (std::size_t k = 0; k < 3; ++k) x = (x << 8) | (k < n ? static_cast<std::uint8_t>(bytes[i + k]) : 0u);
    for (std::size_t k = 0; k < 4; ++k) out += k <= n ? kDigits[(x >> (18 - 6 * k)) & 63] : '=';
  }
  return out;
}

// A PNG without its ancillary chunks but transparency (tRNS): colour-space information (iCCP, cHRM,
// gAMA, sRGB) must be ignored by glTF clients (glTF 2.0 section 3.8.1, images are sRGB) and the
// validator warns about it; physical size, text and time mean nothing to a texture. The other
// chunks are copied byte for byte (their CRCs cover type and data only). Bytes that do not walk as
// PNG chunks come back as they are.
std::string pngWithoutAncillaryChunks(const std::string& png) {
  std::string out = png.substr(0, 8);
  std::size_t at = 8;
  while (at + 12 <= png.size()) {
    const auto byte = [&](std::size_t i) { return static_cast<std::uint32_t>(static_cast<std::uint8_t>(png[i])); };
    const std::uint32_t length = byte(at) << 24 | byte(at + 1) << 16 | byte(at + 2) << 8 | byte(at + 3);
    if (length > png.size() - at - 12) return png;
    const std::string type = png.substr(at + 4, 4);
    const bool critical = (byte(at + 4) & 0x20) == 0;
    if (critical || type == "tRNS") out.append(png, at, 12 + length);
    at += 12 + length;
  }
  return at == png.size() ? out : png;
}

// A texture as a glTF image: the PNG or JPEG file it was decoded from, as it is, or its pixels
// encoded as PNG when it has no such file. Returns the image's index.
int addImage(BufferBuilder& b, const TextureImage& texture, const ImageOutput& out, OJson& images,
             const std::string& where) {
  const ImageFormat format = imageFormatOf(texture.file_bytes);
  std::string bytes = format == ImageFormat::kUnknown ? encodePng(texture, where + ": texture")
                      : format == ImageFormat::kPng   ? pngWithoutAncillaryChunks(texture.file_bytes)
                                                      : texture.file_bytes;
  const bool jpeg = format == ImageFormat::kJpeg;
  const std::string mime = jpeg ? "image/jpeg" : "image/png";
  OJson image;
  if (out.store == ImageStore::kBuffer) {
    image = {{"bufferView", b.addView(bytes.data(), bytes.size(), 0)}, {"mimeType", mime}};
  } else if (out.store == ImageStore::kFiles) {
    const std::string name = out.stem + "-texture-" + std::to_string(images.size()) + (jpeg ? ".jpg" : ".png");
    out.files->push_back({name, std::move(bytes)});
    image = {{"uri", name}};
  } else {
    image = {{"uri", "data:" + mime + ";base64," + base64(bytes)}};
  }
  images.push_back(std::move(image));
  return static_cast<int>(images.size()) - 1;
}

// Display sRGB to linear (IEC 61966-2-1): vdg's colours are display values (vdg/geom/material.h),
// glTF's baseColorFactor is linear (glTF 2.0 section 3.9.2); the inverse of the reader's encoding.
double srgbToLinear(double c) { return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4); }

// Every exported material is dielectric (glTF's default metallicFactor 1 renders a mirror that
// reflects an empty environment: nearly black) and fairly rough, single-sided as vdg's renderer
// culls back faces.
constexpr double kExportRoughness = 0.8;

OJson pbrMaterial(const std::string& name, const std::array<float, 3>& display_rgb) {
  OJson pbr = OJson::object();
  if (display_rgb != std::array<float, 3>{1, 1, 1})
    pbr["baseColorFactor"] = {srgbToLinear(display_rgb[0]), srgbToLinear(display_rgb[1]), srgbToLinear(display_rgb[2]),
                              1.0};
  pbr["metallicFactor"] = 0.0;
  pbr["roughnessFactor"] = kExportRoughness;
  OJson material = OJson::object();
  if (!name.empty()) material["name"] = name;
  material["pbrMetallicRoughness"] = std::move(pbr);
  return material;
}

// The glTF materials of the groups (each used vdg material once, the plain one for faces without
// a material, marked extras.vdg.plain so that vdg reads those faces back without a material), their
// textures and images; returns each group's glTF material.
std::vector<int> addMaterials(BufferBuilder& b, const TriMesh& base, const std::vector<ExportGroup>& groups,
                              bool with_uvs, const ImageOutput& image_out, OJson& doc, GltfExportReport& rep,
                              const std::string& where) {
  OJson materials = OJson::array(), textures = OJson::array(), images = OJson::array();
  std::map<const TextureImage*, int> texture_of;
  std::map<int, int> material_of;
  std::vector<int> out;
  for (const ExportGroup& g : groups) {
    auto it = material_of.find(g.material);
    if (it == material_of.end()) {
      OJson mat;
      if (g.material < 0) {
        mat = pbrMaterial("vdg-plain", {1, 1, 1});
        mat["extras"] = {{"vdg", {{"plain", true}}}};
      } else {
        const Material& m = base.materials[static_cast<std::size_t>(g.material)];
        mat = pbrMaterial(m.name, m.base_color);
        if (m.texture && with_uvs) {
          auto ti = texture_of.find(m.texture.get());
          if (ti == texture_of.end()) {
            ti = texture_of.emplace(m.texture.get(), addImage(b, *m.texture, image_out, images, where)).first;
            textures.push_back({{"sampler", 0}, {"source", ti->second}});
          }
          mat["pbrMetallicRoughness"]["baseColorTexture"] = {{"index", ti->second}};
        } else if (m.texture) {
          rep.note = "material '" + m.name + "': texture not written: the base has no texture coordinates";
        }
      }
      it = material_of.emplace(g.material, static_cast<int>(materials.size())).first;
      materials.push_back(std::move(mat));
    }
    out.push_back(it->second);
  }
  rep.materials = materials.size();
  rep.images = images.size();
  doc["materials"] = std::move(materials);
  if (!textures.empty()) {
    // LINEAR magnification, LINEAR_MIPMAP_LINEAR minification, REPEAT wrapping (the default).
    doc["samplers"] = OJson::array({OJson{{"magFilter", 9729}, {"minFilter", 9987}}});
    doc["textures"] = std::move(textures);
    doc["images"] = std::move(images);
  }
  return out;
}

struct Built {
  OJson doc;
  std::string bin;
};

// The triangle indices: unsigned short when every index fits below 65535 (the largest value of
// the type is the primitive restart value, which glTF forbids), else unsigned int.
int addIndices(BufferBuilder& b, std::span<const std::int32_t> indices, std::size_t vertex_count) {
  if (vertex_count <= 65535) {
    std::vector<std::uint16_t> idx(indices.begin(), indices.end());
    const int view = b.addView(idx.data(), idx.size() * 2, kElementArrayBuffer);
    return b.addAccessor(
        {{"bufferView", view}, {"componentType", kUnsignedShort}, {"count", idx.size()}, {"type", "SCALAR"}});
  } else {
    std::vector<std::uint32_t> idx(indices.begin(), indices.end());
    const int view = b.addView(idx.data(), idx.size() * 4, kElementArrayBuffer);
    return b.addAccessor(
        {{"bufferView", view}, {"componentType", kUnsignedInt}, {"count", idx.size()}, {"type", "SCALAR"}});
  }
}

// Skin attributes of a kSkin base: JOINTS_0 as unsigned shorts, WEIGHTS_0 normalised to sum 1 (the
// validator requires it; vdg::Rig normalises the same way, so the pose is unchanged).
void addSkinAttributes(BufferBuilder& b, const RawRig& rig, const ExportVertices& ev, OJson& attributes) {
  std::vector<std::uint16_t> joints(ev.count() * 4);
  std::vector<float> weights(ev.count() * 4);
  for (std::size_t e = 0; e < ev.count(); ++e) {
    const std::size_t v = ev.model_vertex[e];
    double sum = 0;
    for (std::size_t k = 0; k < 4; ++k) sum += rig.weights[v * 4 + k];
    for (std::size_t k = 0; k < 4; ++k) {
      joints[e * 4 + k] = rig.joints[v * 4 + k];
      weights[e * 4 + k] = static_cast<float>(rig.weights[v * 4 + k] / sum);
    }
  }
  const int joints_view = b.addView(joints.data(), joints.size() * sizeof(std::uint16_t), kArrayBuffer);
  attributes["JOINTS_0"] = b.addAccessor(
      {{"bufferView", joints_view}, {"componentType", kUnsignedShort}, {"count", ev.count()}, {"type", "VEC4"}});
  attributes["WEIGHTS_0"] = b.addFloats(weights, 4, kArrayBuffer, false);
}

// The rig of a kSkin base: its nodes after the mesh node (rig node i is glTF node i + 1), and its
// skin.
void addRigNodes(BufferBuilder& b, const RawRig& rig, OJson& nodes, OJson& scene_nodes, OJson& doc) {
  nodes[0]["skin"] = 0;
  std::vector<std::vector<int>> children(rig.nodes.size());
  for (std::size_t i = 0; i < rig.nodes.size(); ++i) {
    if (rig.nodes[i].parent >= 0)
      children[static_cast<std::size_t>(rig.nodes[i].parent)].push_back(static_cast<int>(i) + 1);
    else
      scene_nodes.push_back(static_cast<int>(i) + 1);
  }
  for (std::size_t i = 0; i < rig.nodes.size(); ++i) {
    const RigNode& n = rig.nodes[i];
    OJson node = OJson::object();
    if (!n.name.empty()) node["name"] = n.name;
    if (!children[i].empty()) node["children"] = children[i];
    if (n.matrix) {
      node["matrix"] = OJson::array();
      for (int c = 0; c < 16; ++c) node["matrix"].push_back((*n.matrix)(c % 4, c / 4));
    } else {
      if (!n.translation.isZero()) node["translation"] = vec3Json(n.translation);
      const Eigen::Quaterniond q = n.rotation.normalized();
      if (!q.coeffs().isApprox(Eigen::Quaterniond::Identity().coeffs()))
        node["rotation"] = {q.x(), q.y(), q.z(), q.w()};
      if (n.scale != Eigen::Vector3d::Ones()) node["scale"] = vec3Json(n.scale);
    }
    nodes.push_back(std::move(node));
  }
  std::vector<float> ibm;
  for (const Eigen::Matrix4d& m : rig.skin->inverse_bind)
    for (int c = 0; c < 16; ++c) ibm.push_back(static_cast<float>(m(c % 4, c / 4)));
  const int ibm_view = b.addView(ibm.data(), ibm.size() * sizeof(float), 0);
  const int ibm_acc = b.addAccessor(
      {{"bufferView", ibm_view}, {"componentType", kFloat}, {"count", rig.skin->joints.size()}, {"type", "MAT4"}});
  OJson joints = OJson::array();
  for (int j : rig.skin->joints) joints.push_back(j + 1);
  doc["skins"] = OJson::array({OJson{{"inverseBindMatrices", ibm_acc}, {"joints", joints}}});
}

// The baked animation: the mesh's weights, the camera's node (added to `nodes`, with its camera in
// `doc`) when the bake has one, and the rig nodes' tracks.
OJson bakedAnimation(BufferBuilder& b, const GltfBakedAnimation& bake, OJson& nodes, OJson& scene_nodes, OJson& doc) {
  const char* interpolation = bake.step ? "STEP" : "LINEAR";
  const int times = b.addFloats(bake.times, 1, 0, true);
  const int weights = b.addFloats(bake.weights, 1, 0, false);
  OJson samplers = OJson::array({OJson{{"input", times}, {"interpolation", interpolation}, {"output", weights}}});
  OJson channels = OJson::array({OJson{{"sampler", 0}, {"target", {{"node", 0}, {"path", "weights"}}}}});
  if (!bake.translations.empty()) {
    const int camera_node = static_cast<int>(nodes.size());
    OJson node = {{"name", "camera"}, {"camera", 0}};
    node["translation"] = {bake.translations[0], bake.translations[1], bake.translations[2]};
    node["rotation"] = {bake.rotations[0], bake.rotations[1], bake.rotations[2], bake.rotations[3]};
    nodes.push_back(std::move(node));
    scene_nodes.push_back(camera_node);
    doc["cameras"] = OJson::array(
        {OJson{{"name", "camera"},
               {"type", "perspective"},
               {"perspective",
                {{"yfov", bake.yfov_rad}, {"aspectRatio", bake.aspect}, {"znear", bake.znear}, {"zfar", bake.zfar}}}}});
    const int translations = b.addFloats(bake.translations, 3, 0, false);
    const int rotations = b.addFloats(bake.rotations, 4, 0, false);
    samplers.push_back({{"input", times}, {"interpolation", interpolation}, {"output", translations}});
    samplers.push_back({{"input", times}, {"interpolation", interpolation}, {"output", rotations}});
    channels.push_back({{"sampler", 1}, {"target", {{"node", camera_node}, {"path", "translation"}}}});
    channels.push_back({{"sampler", 2}, {"target", {{"node", camera_node}, {"path", "rotation"}}}});
  }
  for (const GltfNodeTrack& track : bake.node_tracks) {
    const int output = b.addFloats(track.values, track.path == RigPath::kRotation ? 4 : 3, 0, false);
    channels.push_back(
        {{"sampler", samplers.size()}, {"target", {{"node", track.node + 1}, {"path", rigPathName(track.path)}}}});
    samplers.push_back({{"input", times}, {"interpolation", interpolation}, {"output", output}});
  }
  OJson animation = {{"name", bake.name}, {"channels", channels}, {"samplers", samplers}};
  if (!bake.description.empty()) animation["extras"] = {{"vdg", {{"bake", bake.description}}}};
  return animation;
}

// The base animation: the rig's channels (kSkin), or one weight channel stepping through the base
// frames' targets (kFrames).
void addBaseAnimation(BufferBuilder& b, const GltfExportInput& in, std::size_t target_count, OJson& animations) {
  const GltfBaseAnimation& ba = *in.base_animation;
  OJson samplers = OJson::array(), channels = OJson::array();
  if (ba.mode == GltfBaseMode::kSkin) {
    const RigAnimation& anim = ba.rig->animations[static_cast<std::size_t>(ba.rig_animation)];
    std::vector<int> copied(anim.samplers.size(), -1);
    for (const RigChannel& ch : anim.channels) {
      if (ch.path == RigPath::kWeights) continue;
      const auto si = static_cast<std::size_t>(ch.sampler);
      if (copied[si] < 0) {
        const RigSampler& rs = anim.samplers[si];
        const std::size_t width = ch.path == RigPath::kRotation ? 4 : 3;
        const int input = b.addFloats(rs.input, 1, 0, true);
        const int output = b.addFloats(rs.output, static_cast<int>(width), 0, false);
        copied[si] = static_cast<int>(samplers.size());
        samplers.push_back(
            {{"input", input}, {"interpolation", rigInterpolationName(rs.interpolation)}, {"output", output}});
      }
      channels.push_back(
          {{"sampler", copied[si]}, {"target", {{"node", ch.node + 1}, {"path", rigPathName(ch.path)}}}});
    }
  } else if (ba.frame_count > 1) {
    // Frame i at time i / fps: weight 1 on base frame i's target (frame 0 is POSITION); a loop
    // ends with frame 0 again at N / fps so that a looping viewer has no seam.
    const std::size_t n = static_cast<std::size_t>(ba.frame_count) + (ba.loop ? 1 : 0);
    std::vector<float> times(n), weights(n * target_count, 0.0f);
    for (std::size_t i = 0; i < n; ++i) {
      times[i] = static_cast<float>(static_cast<double>(i) / ba.fps);
      const std::size_t frame = i % static_cast<std::size_t>(ba.frame_count);
      if (frame > 0) weights[i * target_count + in.targets.size() + frame - 1] = 1.0f;
    }
    const int input = b.addFloats(times, 1, 0, true);
    const int output = b.addFloats(weights, 1, 0, false);
    samplers.push_back({{"input", input}, {"interpolation", "LINEAR"}, {"output", output}});
    channels.push_back({{"sampler", 0}, {"target", {{"node", 0}, {"path", "weights"}}}});
  }
  if (!channels.empty()) animations.push_back({{"name", "base"}, {"channels", channels}, {"samplers", samplers}});
}

// The mesh's morph targets (the keys, then a kFrames base's frames) over the exported vertices, and
// their names.
void addTargets(BufferBuilder& b, const GltfExportInput& in, const ExportVertices& ev, OJson& targets, OJson& names,
                GltfExportReport& rep) {
  const auto addTarget = [&](const std::string& name, std::span<const float> deltas,
                             std::span<const float> normal_deltas) {
    bool sparse = false;
    OJson target = {{"POSITION", addDeltaAccessor(b, gathered(deltas, 3, ev), true, sparse)}};
    rep.sparse_targets += sparse ? 1 : 0;
    if (!normal_deltas.empty()) {
      bool normal_sparse = false;
      target["NORMAL"] = addDeltaAccessor(b, gathered(normal_deltas, 3, ev), false, normal_sparse);
    }
    targets.push_back(std::move(target));
    names.push_back(name);
  };
  for (const GltfTarget& t : in.targets) addTarget(t.name, t.deltas, t.normal_deltas);
  if (framesBase(in)) {
    const GltfBaseAnimation& ba = *in.base_animation;
    for (std::size_t i = 0; i < ba.frame_deltas.size(); ++i)
      addTarget(baseFrameTargetName(static_cast<int>(i + 1)), ba.frame_deltas[i],
                ba.frame_normal_deltas.empty() ? std::span<const float>()
                                               : std::span<const float>(ba.frame_normal_deltas[i]));
  }
}

Built build(const GltfExportInput& in, const std::string& where, GltfExportReport* report,
            const ImageOutput& image_out = {}) {
  if (in.interactivity) checkInteractivitySupported(in, where);  // before the input's own checks
  validateInput(in, where);
  GltfExportReport rep;
  BufferBuilder b;
  const ExportVertices ev = exportVertices(in.base);
  rep.split_vertices = ev.count() - in.base.vertexCount();

  // The attributes all primitives share (one vertex list; each primitive indexes its faces).
  OJson attributes = OJson::object();
  attributes["POSITION"] = b.addFloats(gathered(in.base.positions, 3, ev), 3, kArrayBuffer, true);
  if (!in.normals.empty()) attributes["NORMAL"] = b.addFloats(gathered(in.normals, 3, ev), 3, kArrayBuffer, false);
  if (!ev.uvs.empty()) {
    attributes["TEXCOORD_0"] = b.addFloats(ev.uvs, 2, kArrayBuffer, false);
    rep.uvs_written = true;
  }
  attributes["_VDG_VERTEX"] = addVertexIds(b, ev, in.base.vertexCount());
  if (skinBase(in)) addSkinAttributes(b, *in.base_animation->rig, ev, attributes);

  OJson targets = OJson::array(), names = OJson::array();
  addTargets(b, in, ev, targets, names, rep);
  const std::size_t target_count = totalTargets(in);

  OJson doc;
  doc["asset"] = {{"version", "2.0"}, {"generator", std::string("vdg ") + versionString()}};
  doc["scene"] = 0;
  const std::vector<ExportGroup> groups = exportGroups(in.base, ev);
  const std::vector<int> group_materials =
      addMaterials(b, in.base, groups, !ev.uvs.empty(), image_out, doc, rep, where);
  OJson primitives = OJson::array();
  for (std::size_t g = 0; g < groups.size(); ++g) {
    OJson primitive = {{"attributes", attributes},
                       {"indices", addIndices(b, groups[g].indices, ev.count())},
                       {"material", group_materials[g]},
                       {"mode", kTriangles}};
    if (target_count > 0) primitive["targets"] = targets;
    primitives.push_back(std::move(primitive));
  }
  OJson mesh = {{"name", in.mesh_name}, {"primitives", std::move(primitives)}};
  if (target_count > 0) mesh["weights"] = std::vector<double>(target_count, 0.0);
  mesh["extras"] = {{"targetNames", names}, {"vdg", vdgExtras(in)}};

  OJson nodes = OJson::array({OJson{{"name", in.mesh_name}, {"mesh", 0}}});
  OJson scene_nodes = OJson::array({0});
  OJson animations = OJson::array();

  if (skinBase(in)) addRigNodes(b, *in.base_animation->rig, nodes, scene_nodes, doc);

  if (in.bake) animations.push_back(bakedAnimation(b, *in.bake, nodes, scene_nodes, doc));

  // The base animation (after the bake's, which a viewer plays first).
  if (in.base_animation) addBaseAnimation(b, in, target_count, animations);

  if (!animations.empty()) doc["animations"] = std::move(animations);
  doc["scenes"] = OJson::array({OJson{{"nodes", scene_nodes}}});
  doc["nodes"] = std::move(nodes);
  doc["meshes"] = OJson::array({mesh});
  b.data().resize(pad4(b.data().size()), '\0');
  doc["buffers"] = OJson::array({OJson{{"byteLength", b.data().size()}}});
  doc["bufferViews"] = std::move(b.views());
  doc["accessors"] = std::move(b.accessors());
  if (report) *report = rep;
  return {std::move(doc), std::move(b.data())};
}

// --interactivity, after compression (which may give the mesh's node its dequantisation): the graph
// as extensions.KHR_interactivity, used, not required (an engine without it shows the base).
void addInteractivity(OJson& doc, const GltfExportInput& in, const std::string& where) {
  if (!in.interactivity) return;
  InteractivityInput graph = interactivityInput(in, where);
  const OJson& node = doc["nodes"][graph.node];
  for (int k = 0; k < 3; ++k) {
    if (node.contains("translation")) graph.node_offset[k] = node["translation"][k].get<double>();
    if (node.contains("scale")) graph.node_scale[k] = node["scale"][k].get<double>();
  }
  if (!doc.contains("extensionsUsed")) doc["extensionsUsed"] = OJson::array();
  doc["extensionsUsed"].push_back("KHR_interactivity");
  doc["extensions"]["KHR_interactivity"] = OJson::parse(interactivityGraphJson(graph));
}

void appendU32(std::string& out, std::uint32_t x) {
  char bytes[4];
  std::memcpy(bytes, &x, 4);
  out.append(bytes, 4);
}

}  // namespace

GltfExportInput gltfExportInput(const ViewDependentModel& model) {
  model.requireNoParts("the glTF export (vdg export, bake, view, the Python module and the Blender add-on)");
  model.requireViewDirections("the glTF export (its runtimes blend the keys of one direction's hull triangle)");
  GltfExportInput in;
  in.base = model.base();
  const std::size_t n = in.base.positions.size();
  const auto normalsOf = [&](std::span<const float> positions, std::vector<float>& out) {
    out.assign(n, 0.0f);
    if (!computeVertexNormals(positions, in.base.triangles, out)) throw Error("model: cannot compute the normals");
    for (std::size_t v = 0; v < n / 3; ++v)
      if (out[v * 3] == 0.0f && out[v * 3 + 1] == 0.0f && out[v * 3 + 2] == 0.0f) out[v * 3 + 1] = 1.0f;
  };
  normalsOf(in.base.positions, in.normals);
  std::vector<float> key(n), key_normals;
  for (std::size_t k = 0; k < model.keyCount(); ++k) {
    if (!model.keyPositions(k, key)) throw Error("model: cannot read key " + std::to_string(k));
    GltfTarget t;
    t.name = model.keyName(k);
    t.view = model.keyView(k);
    t.camera = model.keyCamera(k);
    t.deltas.resize(n);
    for (std::size_t i = 0; i < n; ++i) t.deltas[i] = key[i] - in.base.positions[i];
    normalsOf(key, key_normals);
    t.normal_deltas.resize(n);
    for (std::size_t i = 0; i < n; ++i) t.normal_deltas[i] = key_normals[i] - in.normals[i];
    in.targets.push_back(std::move(t));
  }
  in.sharpness = model.sharpness();
  in.sphere = model.sphere().settings();
  in.center = model.center();
  in.view_sphere = gltfViewSphere(model.sphere());
  return in;
}

GltfViewSphere gltfViewSphere(const ViewSphere& sphere) {
  GltfViewSphere vs;
  vs.points.assign(sphere.points().begin(), sphere.points().end());
  vs.views = sphere.keyCount();
  vs.triangles.assign(sphere.triangles().begin(), sphere.triangles().end());
  for (std::size_t t = 0; t < vs.triangles.size(); ++t) vs.inverses.push_back(sphere.triangleInverse(t));
  vs.arcs.assign(sphere.boundaryArcs().begin(), sphere.boundaryArcs().end());
  vs.isolated.assign(sphere.isolatedKeys().begin(), sphere.isolatedKeys().end());
  for (std::size_t k = 0; k < vs.views; ++k) vs.view_targets.push_back({static_cast<int>(k)});
  if (sphere.settings().scheme == WeightScheme::Rbf) {
    vs.rbf_chord2 = sphere.rbfChord2();
    vs.rbf_coefficients.assign(sphere.rbfCoefficients().begin(), sphere.rbfCoefficients().end());
  }
  return vs;
}

std::size_t gltfTargetCount(const GltfExportInput& input) { return totalTargets(input); }

std::size_t gltfTargetCount(const AnimatedViewDependentModel& model) {
  std::size_t keys = 0;
  for (std::size_t i = 0; i < model.viewCount(); ++i) keys += model.keyFrames(i).size();
  const bool frames = model.offsetSpace() != OffsetSpace::kSkinned;
  return keys + (frames ? static_cast<std::size_t>(std::max(model.frameCount(), 1) - 1) : 0);
}

std::string morphTargetCapsExceeded(std::size_t count) {
  std::string out;
  for (const MorphTargetCap& cap : kMorphTargetCaps)
    if (count > cap.targets)
      out += (out.empty() ? "" : ", ") + std::string(cap.engine) + " (" + std::to_string(cap.targets) + ")";
  return out;
}

void checkMaxTargets(const GltfExportInput& input, std::size_t max_targets, const std::string& where) {
  const std::size_t count = totalTargets(input);
  if (count <= max_targets) return;
  const std::size_t frames = count - input.targets.size();
  std::string what = std::to_string(input.targets.size()) + " keys";
  if (frames > 0) what += " + " + std::to_string(frames) + " base frames";
  std::string todo = "use fewer keys or raise --max-targets";
  if (frames > 0)
    todo =
        "a \"world\"-offset animated model needs one target per base frame: use fewer frames, \"skinned\" "
        "offsets on a skinned glTF base (written with its skin, no frame targets), or raise --max-targets";
  throw Error(where + ": the export needs " + std::to_string(count) + " morph targets (" + what +
              "), more than --max-targets " + std::to_string(max_targets) + "; " + todo);
}

const char* gltfBaseModeName(GltfBaseMode mode) { return mode == GltfBaseMode::kSkin ? "skin" : "frames"; }

namespace {

// Area-weighted vertex normals of `positions`; a vertex on no triangle gets (0, 1, 0).
std::vector<float> exportNormals(std::span<const float> positions, const TriMesh& mesh) {
  std::vector<float> out(positions.size(), 0.0f);
  if (!computeVertexNormals(positions, mesh.triangles, out)) throw Error("model: cannot compute the normals");
  for (std::size_t v = 0; v < out.size() / 3; ++v)
    if (out[v * 3] == 0.0f && out[v * 3 + 1] == 0.0f && out[v * 3 + 2] == 0.0f) out[v * 3 + 1] = 1.0f;
  return out;
}

std::vector<float> difference(std::span<const float> a, std::span<const float> b) {
  std::vector<float> out(a.size());
  for (std::size_t i = 0; i < a.size(); ++i) out[i] = a[i] - b[i];
  return out;
}

}  // namespace

RawRig readBaseRig(const RawViewDependentModel& raw) {
  if (!raw.base_animation || raw.base_animation->gltf.empty())
    throw Error(raw.source + ": the base is not a glTF animation");
  const std::filesystem::path file = std::filesystem::path(raw.base_animation->gltf).is_absolute()
                                         ? std::filesystem::path(raw.base_animation->gltf)
                                         : std::filesystem::path(raw.source).parent_path() / raw.base_animation->gltf;
  try {
    return readGltfRig(file.string(), GltfSelect{raw.base_animation->mesh});
  } catch (const Error& e) {
    throw Error(raw.source + ": base_animation.gltf: " + e.what());
  }
}

GltfExportInput gltfExportInput(const AnimatedViewDependentModel& model, const RawViewDependentModel& raw,
                                const RawRig* rig) {
  const std::string& where = raw.source;
  const int n = model.frameCount();
  GltfExportInput in;
  in.sharpness = model.sharpness();
  in.sphere = model.sphere().settings();
  in.center = model.center();
  in.base = model.base();
  GltfBaseAnimation ba;
  ba.frame_count = n;
  ba.fps = raw.base_animation ? raw.base_animation->fps : 24.0;
  ba.loop = model.loop();
  if (model.offsetSpace() == OffsetSpace::kSkinned) {
    // Skinned offsets: the skin itself, morph targets in the bind pose (exact, see kSkin).
    in.offsets = OffsetSpace::kSkinned;
    if (!rig || !rig->skin)
      throw Error(where +
                  ": 'offsets': \"skinned\" is exported only for a skinned glTF base (glTF morphs before it "
                  "skins); this base is not skinned");
    // Morph targets of the base's own (a vdg export read back has the keys as targets) are left
    // out when the base never uses them: zero default weights and no weights channel.
    const RigAnimation& anim = rig->animations.at(static_cast<std::size_t>(raw.base_animation->animation));
    const bool morphs =
        std::any_of(rig->default_weights.begin(), rig->default_weights.end(), [](double w) { return w != 0.0; }) ||
        std::any_of(anim.channels.begin(), anim.channels.end(),
                    [](const RigChannel& c) { return c.path == RigPath::kWeights; });
    if (morphs)
      throw Error(where +
                  ": base_animation.gltf: the base mesh uses morph targets of its own; a model with "
                  "\"skinned\" offsets on it cannot be exported yet");
    if (rig->mesh.vertexCount() != model.vertexCount() || rig->mesh.triangles != model.base().triangles)
      throw Error(where + ": base_animation.gltf: the file's mesh no longer matches the model's base");
    ba.mode = GltfBaseMode::kSkin;
    ba.rig = *rig;
    ba.rig->target_positions.clear();
    ba.rig->target_normals.clear();
    ba.rig->target_names.clear();
    ba.rig->default_weights.clear();
    for (RigAnimation& a : ba.rig->animations)
      std::erase_if(a.channels, [](const RigChannel& c) { return c.path == RigPath::kWeights; });
    ba.rig_animation = raw.base_animation->animation;
    in.base.positions = rig->mesh.positions;  // the bind pose: the skin poses it
    in.normals = exportNormals(in.base.positions, in.base);
  } else {
    // World offsets: the base's frames as morph targets (exact at every frame, any base).
    ba.mode = GltfBaseMode::kFrames;
    in.base.positions.assign(model.baseFrame(0).begin(), model.baseFrame(0).end());
    in.normals = exportNormals(in.base.positions, in.base);
    for (int f = 1; f < n; ++f) {
      ba.frame_deltas.push_back(difference(model.baseFrame(f), in.base.positions));
      ba.frame_normal_deltas.push_back(difference(exportNormals(model.baseFrame(f), in.base), in.normals));
    }
  }
  // One target per raw key: (view i, key frame j) is raw key keyIndex(i, j).
  in.targets.resize(raw.keys.size());
  std::vector<char> filled(raw.keys.size(), 0);
  for (std::size_t i = 0; i < model.viewCount(); ++i)
    for (std::size_t j = 0; j < model.keyFrames(i).size(); ++j) {
      const std::size_t k = model.keyIndex(i, j);
      GltfTarget& t = in.targets.at(k);
      t.name = model.keyName(i, j);
      t.view = model.viewDirection(i);
      t.frame = model.keyFrames(i)[j];
      t.camera = raw.keys[k].camera;
      const auto offsets = model.offsets(i, j);
      t.deltas.assign(offsets.begin(), offsets.end());
      filled[k] = 1;
    }
  if (std::find(filled.begin(), filled.end(), 0) != filled.end())
    throw Error(where + ": the animated model's keys do not match its raw description (internal error)");
  // Extras v2: the sphere's key points are the views; each view's targets are its raw keys.
  GltfViewSphere vs = gltfViewSphere(model.sphere());
  for (std::size_t i = 0; i < model.viewCount(); ++i) {
    vs.view_targets[i].clear();
    for (std::size_t j = 0; j < model.keyFrames(i).size(); ++j)
      vs.view_targets[i].push_back(static_cast<int>(model.keyIndex(i, j)));
    const auto second = model.secondDerivatives(i);
    vs.time.push_back({{model.keyFrames(i).begin(), model.keyFrames(i).end()}, {second.begin(), second.end()}});
  }
  in.view_sphere = std::move(vs);
  in.base_animation = std::move(ba);
  return in;
}

GltfBakedAnimation gltfBakedAnimation(CameraPathBake samples, const GltfExportInput& input) {
  const std::size_t targets = totalTargets(input);
  if (samples.weights.size() != samples.times.size() * targets)
    throw Error("bake: the samples' weights do not match the export input's " + std::to_string(targets) + " targets");
  GltfBakedAnimation bake;
  static_cast<CameraPathBake&>(bake) = std::move(samples);
  if (!skinBase(input)) return bake;
  const GltfBaseAnimation& ba = *input.base_animation;
  if (bake.frames.size() != bake.times.size() || !ba.rig)
    throw Error("bake: the export input does not describe this animated model");
  // The skeleton at each sample's animation frame, re-sampled through vdg::Rig (LINEAR or STEP
  // between samples like the weights; rotations kept in one hemisphere).
  const Rig rig = Rig::build(*ba.rig);
  const RigAnimation& anim = ba.rig->animations[static_cast<std::size_t>(ba.rig_animation)];
  std::vector<double> pose(rig.nodeCount() * 10);
  for (const RigChannel& ch : anim.channels)
    if (ch.path != RigPath::kWeights) bake.node_tracks.push_back({ch.node, ch.path, {}});
  for (std::size_t s = 0; s < bake.times.size(); ++s) {
    if (!rig.nodePose(ba.rig_animation, bake.frames[s] / ba.fps, pose))
      throw Error("bake: the base's skeleton could not be posed (internal error)");
    for (GltfNodeTrack& track : bake.node_tracks) {
      const double* p = pose.data() + static_cast<std::size_t>(track.node) * 10;
      const int offset = track.path == RigPath::kTranslation ? 0 : track.path == RigPath::kRotation ? 3 : 7;
      const int width = track.path == RigPath::kRotation ? 4 : 3;
      double sign = 1.0;
      if (track.path == RigPath::kRotation && s > 0) {
        const float* prev = track.values.data() + (s - 1) * 4;
        double dot = 0;
        for (int c = 0; c < 4; ++c) dot += prev[c] * p[3 + c];
        if (dot < 0) sign = -1.0;
      }
      for (int c = 0; c < width; ++c) track.values.push_back(static_cast<float>(sign * p[offset + c]));
    }
  }
  return bake;
}

std::string gltfToGlb(const GltfExportInput& input, const std::string& where, GltfExportReport* report) {
  Built built = build(input, where, report);
  compressGltf(built.doc, built.bin, input.compression, where, report ? &report->sparse_targets : nullptr);
  addInteractivity(built.doc, input, where);
  built.doc["buffers"][0].erase("uri");
  std::string json = built.doc.dump(-1, ' ', false, OJson::error_handler_t::replace);
  json.resize(pad4(json.size()), ' ');
  const std::size_t total = 12 + 8 + json.size() + 8 + built.bin.size();
  if (total > std::numeric_limits<std::uint32_t>::max())
    throw Error(where + ": the model is too large for a .glb file (4 GiB)");
  std::string out;
  out.reserve(total);
  appendU32(out, kGlbMagic);
  appendU32(out, kGlbVersion);
  appendU32(out, static_cast<std::uint32_t>(total));
  appendU32(out, static_cast<std::uint32_t>(json.size()));
  appendU32(out, kChunkJson);
  out += json;
  appendU32(out, static_cast<std::uint32_t>(built.bin.size()));
  appendU32(out, kChunkBin);
  out += built.bin;
  if (report) report->bytes = out.size();
  return out;
}

std::string gltfToJson(const GltfExportInput& input, const std::string& where, const std::string& bin_uri,
                       std::string& bin, GltfExportReport* report, std::vector<GltfImageFile>* images) {
  ImageOutput image_out;
  if (images) {
    image_out.store = ImageStore::kFiles;
    image_out.stem = std::filesystem::path(bin_uri).stem().string();
    image_out.files = images;
  } else {
    image_out.store = ImageStore::kDataUri;
  }
  Built built = build(input, where, report, image_out);
  compressGltf(built.doc, built.bin, input.compression, where, report ? &report->sparse_targets : nullptr);
  addInteractivity(built.doc, input, where);
  built.doc["buffers"][0]["uri"] = bin_uri;
  std::string json = built.doc.dump(1, ' ', false, OJson::error_handler_t::replace);
  json += '\n';
  bin = std::move(built.bin);
  if (report) report->bytes = json.size() + bin.size();
  return json;
}

GltfExportReport writeGltfExport(const std::string& path, const GltfExportInput& input) {
  namespace fs = std::filesystem;
  const fs::path p(path);
  const std::string ext = p.extension().string();
  GltfExportReport report;
  if (hasExtension(ext, ".glb")) {
    writeFileAtomically(path, gltfToGlb(input, path, &report));
    return report;
  }
  if (!hasExtension(ext, ".gltf")) throw Error(path + ": expected a .glb or .gltf file name");
  // The buffer's URI is a file name only, so the pair can be moved together.
  const std::string bin_name = p.stem().string() + ".bin";
  std::string bin;
  std::vector<GltfImageFile> images;
  std::string json = gltfToJson(input, path, bin_name, bin, &report, &images);
  const fs::path folder = p.parent_path();
  const std::string folder_name = folder.empty() ? "." : folder.string();
  const FolderLock lock(folder_name);
  const std::string journal = (fs::path(folder_name) / ".vdg-journal").string();
  (void)recoverFileTransaction(journal);
  FileTransaction transaction(journal);
  transaction.write((folder / bin_name).string(), std::move(bin));
  // The images beside it (names derived from OUT, listed in the report for the command to print).
  for (GltfImageFile& image : images) {
    const std::string image_path = (folder / image.name).string();
    report.bytes += image.bytes.size();
    report.files.push_back(image_path);
    transaction.write(image_path, std::move(image.bytes));
  }
  transaction.write(path, std::move(json));
  transaction.commit();
  return report;
}

namespace {

// mesh.extras.vdg parsed: the raw model without meshes (keys have names, views, frames, cameras)
// and the animation block.
struct Described {
  RawViewDependentModel raw;
  std::optional<GltfBaseAnimation> animation;  // frame_count, fps, loop, mode
  int animation_index = -1;
};

constexpr std::pair<const char*, GltfBaseMode> kBaseModes[] = {{"skin", GltfBaseMode::kSkin},
                                                               {"frames", GltfBaseMode::kFrames}};

// An array of index tuples (each `width` integers in [0, count)), or of plain indices (width 0).
std::size_t indexArray(const io::Json& j, const io::Ctx& ctx, std::size_t width, std::size_t count) {
  if (!j.is_array()) ctx.fail("expected an array, got " + io::describe(j));
  for (std::size_t i = 0; i < j.size(); ++i) {
    const io::Ctx ic = ctx.index(i);
    if (width == 0) {
      io::integer(j[i], ic, 0, static_cast<std::int64_t>(count) - 1);
      continue;
    }
    if (!j[i].is_array() || j[i].size() != width)
      ic.fail("expected " + std::to_string(width) + " indices, got " + io::describe(j[i]));
    for (std::size_t c = 0; c < width; ++c) io::integer(j[i][c], ic.index(c), 0, static_cast<std::int64_t>(count) - 1);
  }
  return j.size();
}

// Extras v2 "sphere" and "time": vdg re-derives the sphere from the keys on reading, but a runtime
// reads these, so they must be well formed and match the keys in size (one line naming the field).
// Extras v4 "weights" of an rbf model: its kernel and width (degrees, in (0, 180]), both required;
// refused with another scheme, and the rbf scheme refused before version 4.
void readRbfSettings(const io::Json& weights, const io::Ctx& wc, int version, ViewSphereSettings& settings) {
  if (settings.scheme != WeightScheme::Rbf) {
    for (const char* rbf_only : {"kernel", "width"})
      if (weights.contains(rbf_only)) wc.key(rbf_only).fail("belongs to the 'rbf' scheme only");
    return;
  }
  if (version < 4) wc.key("scheme").fail("'rbf' needs extras version 4");
  settings.rbf_kernel = io::enumValue(io::required(weights, "kernel", wc), wc.key("kernel"), io::kRbfKernelNames);
  settings.rbf_width_deg = io::number(io::required(weights, "width", wc), wc.key("width"));
  if (!(settings.rbf_width_deg > 0.0 && settings.rbf_width_deg <= 180.0))
    wc.key("width").fail("expected an angle in (0, 180] degrees, got " + io::describe(weights.at("width")));
}

// Extras v4 "sphere"."rbf": the squared chord of the width (> 0, finite) and (points + 1) rows of
// (views + 1) finite coefficients; only an rbf model has it, and an rbf model must.
void checkRbfDescription(const io::Json& sphere, const io::Ctx& sc, std::size_t points, std::size_t views,
                         WeightScheme scheme) {
  if (scheme != WeightScheme::Rbf) {
    if (sphere.contains("rbf")) sc.key("rbf").fail("belongs to the 'rbf' weight scheme only");
    return;
  }
  const io::Json& rbf = io::required(sphere, "rbf", sc);
  const io::Ctx rc = sc.key("rbf");
  if (!rbf.is_object())
    rc.fail("expected an object {\"chord2\": ..., \"coefficients\": ...}, got " + io::describe(rbf));
  io::allowKeys(rbf, rc, {"chord2", "coefficients"});
  const double chord2 = io::number(io::required(rbf, "chord2", rc), rc.key("chord2"));
  if (!(chord2 > 0.0 && chord2 <= 4.0))
    rc.key("chord2").fail("expected a squared chord in (0, 4], got " + io::describe(rbf.at("chord2")));
  const io::Json& rows = io::required(rbf, "coefficients", rc);
  if (!rows.is_array() || rows.size() != points + 1)
    rc.key("coefficients")
        .fail("expected " + std::to_string(points + 1) + " rows (the constants, then one per point), got " +
              io::describe(rows));
  for (std::size_t r = 0; r < rows.size(); ++r)
    io::vector(rows[r], rc.key("coefficients").index(r), static_cast<long>(views + 1));
}

void checkSphereDescription(const io::Json& vdg, const io::Ctx& ctx, std::size_t key_count, bool animated,
                            WeightScheme scheme) {
  if (key_count == 0 && !vdg.contains("sphere")) return;
  const io::Json& sphere = io::required(vdg, "sphere", ctx);
  const io::Ctx sc = ctx.key("sphere");
  io::allowKeys(sphere, sc, {"points", "views", "triangles", "inverses", "arcs", "isolated", "view_targets", "rbf"});
  const io::Json& points = io::required(sphere, "points", sc);
  if (!points.is_array() || points.empty())
    sc.key("points").fail("expected an array of directions, got " + io::describe(points));
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector3d p = io::vector3(points[i], sc.key("points").index(i));
    if (!(std::abs(p.norm() - 1.0) <= 1e-6)) sc.key("points").index(i).fail("expected a unit direction");
  }
  const auto views = static_cast<std::size_t>(
      io::integer(io::required(sphere, "views", sc), sc.key("views"), 1, static_cast<std::int64_t>(points.size())));
  if (views > key_count || (!animated && views != key_count))
    sc.key("views").fail(std::to_string(views) + " key views for " + std::to_string(key_count) + " keys");
  const std::size_t triangles =
      indexArray(io::required(sphere, "triangles", sc), sc.key("triangles"), 3, points.size());
  const io::Json& inverses = io::required(sphere, "inverses", sc);
  if (!inverses.is_array() || inverses.size() != triangles)
    sc.key("inverses")
        .fail("expected " + std::to_string(triangles) + " matrices (one per triangle), got " + io::describe(inverses));
  for (std::size_t t = 0; t < triangles; ++t) io::vector(inverses[t], sc.key("inverses").index(t), 9);
  indexArray(io::required(sphere, "arcs", sc), sc.key("arcs"), 2, points.size());
  indexArray(io::required(sphere, "isolated", sc), sc.key("isolated"), 0, views);
  const io::Json& view_targets = io::required(sphere, "view_targets", sc);
  const io::Ctx vc = sc.key("view_targets");
  if (!view_targets.is_array() || view_targets.size() != views)
    vc.fail("expected " + std::to_string(views) + " lists (one per key view), got " + io::describe(view_targets));
  std::vector<char> seen(key_count, 0);
  for (std::size_t i = 0; i < views; ++i) {
    indexArray(view_targets[i], vc.index(i), 0, key_count);
    if (view_targets[i].empty()) vc.index(i).fail("a key view without targets");
    for (const io::Json& t : view_targets[i])
      if (seen[t.get<std::size_t>()]++) vc.index(i).fail("target " + t.dump() + " belongs to two views");
  }
  if (std::find(seen.begin(), seen.end(), 0) != seen.end()) vc.fail("a key's target belongs to no view");
  checkRbfDescription(sphere, sc, points.size(), views, scheme);
  if (!animated) {
    if (vdg.contains("time")) ctx.key("time").fail("only an animated model has time tables");
    return;
  }
  const io::Json& time = io::required(vdg, "time", ctx);
  if (!time.is_array() || time.size() != views)
    ctx.key("time").fail("expected " + std::to_string(views) + " tables (one per key view), got " + io::describe(time));
  for (std::size_t i = 0; i < views; ++i) {
    const io::Ctx tc = ctx.key("time").index(i);
    io::allowKeys(time[i], tc, {"frames", "second"});
    const std::size_t m = view_targets[i].size();
    const io::Json& frames = io::required(time[i], "frames", tc);
    if (!frames.is_array() || frames.size() != m)
      tc.key("frames").fail("expected " + std::to_string(m) + " key frames, got " + io::describe(frames));
    for (std::size_t j = 0; j < m; ++j)
      io::integer(frames[j], tc.key("frames").index(j), 0, static_cast<std::int64_t>(kMaxBaseFrames));
    io::vector(io::required(time[i], "second", tc), tc.key("second"), static_cast<long>(m * m));
  }
}

Described describedModel(const io::Json& extras, std::size_t target_count, const std::string& where) {
  const io::Ctx top{where + ": mesh extras", ""};
  if (!extras.is_object()) top.fail("expected an object, got " + io::describe(extras));
  if (!extras.contains("vdg")) top.fail("no 'vdg' description: this glTF file was not exported by vdg");
  const io::Json& names = io::required(extras, "targetNames", top);
  if (!names.is_array()) top.key("targetNames").fail("expected an array of names, got " + io::describe(names));
  const io::Json& vdg = extras.at("vdg");
  const io::Ctx ctx = top.key("vdg");
  io::allowKeys(vdg, ctx,
                {"version", "sharpness", "uncovered", "base_falloff_deg", "center", "offsets", "keys", "animation",
                 "sphere", "time", "dequantize", "weights"});
  const int version = io::formatVersion(vdg, ctx, "view-dependent glTF extras", 1, kGltfExtrasVersion);
  if (vdg.contains("weights") && version < 3) ctx.key("weights").fail("needs extras version 3");
  Described d;
  RawViewDependentModel& raw = d.raw;
  raw.source = where;
  raw.sharpness = io::number(io::required(vdg, "sharpness", ctx), ctx.key("sharpness"));
  raw.sphere.uncovered = io::enumValue(io::required(vdg, "uncovered", ctx), ctx.key("uncovered"), io::kUncoveredNames);
  raw.sphere.base_falloff_deg = io::number(io::required(vdg, "base_falloff_deg", ctx), ctx.key("base_falloff_deg"));
  raw.center = io::vector3(io::required(vdg, "center", ctx), ctx.key("center"));
  if (vdg.contains("weights")) {
    const io::Json& weights = vdg.at("weights");
    const io::Ctx wc = ctx.key("weights");
    if (!weights.is_object()) wc.fail("expected an object {\"scheme\": ...}, got " + io::describe(weights));
    io::allowKeys(weights, wc, {"scheme", "kernel", "width"});
    raw.sphere.scheme = io::enumValue(io::required(weights, "scheme", wc), wc.key("scheme"), io::kWeightSchemeNames);
    readRbfSettings(weights, wc, version, raw.sphere);
  }
  raw.offsets = io::enumValue(io::required(vdg, "offsets", ctx), ctx.key("offsets"), io::kOffsetSpaceNames);
  if (vdg.contains("animation")) {
    const io::Json& anim = vdg.at("animation");
    const io::Ctx ac = ctx.key("animation");
    io::allowKeys(anim, ac, {"frame_count", "fps", "loop", "animation", "base"});
    GltfBaseAnimation ba;
    ba.frame_count = static_cast<int>(io::integer(io::required(anim, "frame_count", ac), ac.key("frame_count"), 1,
                                                  static_cast<std::int64_t>(kMaxBaseFrames)));
    ba.fps = io::number(io::required(anim, "fps", ac), ac.key("fps"));
    if (!(ba.fps > 0.0)) ac.key("fps").fail("expected a number > 0, got " + io::describe(anim.at("fps")));
    ba.loop = io::boolean(io::required(anim, "loop", ac), ac.key("loop"));
    ba.mode = io::enumValue(io::required(anim, "base", ac), ac.key("base"), kBaseModes);
    if (anim.contains("animation"))
      d.animation_index = static_cast<int>(io::integer(anim.at("animation"), ac.key("animation"), 0, 1'000'000));
    else if (ba.frame_count > 1)
      ac.fail("missing key 'animation' (the glTF animation that plays the base's " + std::to_string(ba.frame_count) +
              " frames)");
    if (raw.offsets == OffsetSpace::kSkinned && ba.mode != GltfBaseMode::kSkin)
      ctx.key("offsets").fail("\"skinned\" offsets need a skinned base (animation.base \"skin\")");
    d.animation = std::move(ba);
  } else if (raw.offsets != OffsetSpace::kWorld) {
    ctx.key("offsets").fail("expected \"world\" for a static model, got " + io::describe(vdg.at("offsets")));
  }
  const io::Json& keys = io::required(vdg, "keys", ctx);
  if (!keys.is_array()) ctx.key("keys").fail("expected an array, got " + io::describe(keys));
  const std::size_t frame_targets = d.animation && d.animation->mode == GltfBaseMode::kFrames
                                        ? static_cast<std::size_t>(d.animation->frame_count) - 1
                                        : 0;
  if (keys.size() + frame_targets != target_count)
    ctx.key("keys").fail("describes " + std::to_string(keys.size()) + " keys" +
                         (frame_targets ? " and " + std::to_string(frame_targets) + " base frames" : std::string()) +
                         ", but the mesh has " + std::to_string(target_count) + " morph targets");
  if (names.size() != target_count)
    top.key("targetNames")
        .fail("has " + std::to_string(names.size()) + " names for " + std::to_string(target_count) + " morph targets");
  for (std::size_t k = 0; k < keys.size(); ++k) {
    const io::Ctx kc = ctx.key("keys").index(k);
    const io::Json& key = keys[k];
    io::allowKeys(key, kc, {"name", "view", "frame", "camera"});
    RawKey rk;
    rk.name = io::string(io::required(key, "name", kc), kc.key("name"));
    const std::string target_name = io::string(names[k], top.key("targetNames").index(k));
    if (target_name != rk.name)
      kc.key("name").fail("differs from targetNames[" + std::to_string(k) + "] " + io::describe(names[k]));
    rk.view = io::vector3(io::required(key, "view", kc), kc.key("view"));
    if (key.contains("frame")) {
      rk.frame = static_cast<int>(io::integer(key.at("frame"), kc.key("frame"), 0, std::numeric_limits<int>::max()));
      if (!d.animation && rk.frame != 0)
        kc.key("frame").fail("a key at frame > 0 belongs to an animated model, but 'vdg' has no 'animation'");
      if (d.animation && rk.frame >= d.animation->frame_count)
        kc.key("frame").fail("expected a frame in 0.." + std::to_string(d.animation->frame_count - 1) + ", got " +
                             std::to_string(rk.frame));
    }
    if (key.contains("camera")) rk.camera = io::cameraFrom(key.at("camera"), kc.key("camera"));
    raw.keys.push_back(std::move(rk));
  }
  if (version >= 2) checkSphereDescription(vdg, ctx, raw.keys.size(), d.animation.has_value(), raw.sphere.scheme);
  if (vdg.contains("dequantize")) {  // quantised exports: the mesh node's transform, for runtimes
    const io::Ctx qc = ctx.key("dequantize");
    io::allowKeys(vdg.at("dequantize"), qc, {"scale", "offset"});
    io::vector3(io::required(vdg.at("dequantize"), "scale", qc), qc.key("scale"));
    io::vector3(io::required(vdg.at("dequantize"), "offset", qc), qc.key("offset"));
  }
  return d;
}

// The JSON text of a .glb (its first chunk) or a .gltf (the whole file).
std::string_view gltfJsonText(std::string_view bytes) {
  if (bytes.size() >= 20 && bytes.substr(0, 4) == "glTF") {
    std::uint32_t length = 0;
    std::memcpy(&length, bytes.data() + 12, 4);
    return bytes.substr(20, std::min<std::size_t>(length, bytes.size() - 20));
  }
  return bytes;
}

// The extras of the rig's mesh in the file's JSON (null when it has none).
io::Json meshExtras(std::string_view bytes, const RawRig& rig, const std::string& where) {
  const io::Json doc = io::parseJson(gltfJsonText(bytes), where);
  std::size_t mesh = 0;
  if (rig.mesh_node >= 0)
    mesh = doc.at("nodes").at(static_cast<std::size_t>(rig.mesh_node)).at("mesh").get<std::size_t>();
  const io::Json& m = doc.at("meshes").at(mesh);
  return m.contains("extras") ? m.at("extras") : io::Json();
}

// The model's base: the rig's rest mesh (the glTF reader has already flipped its uvs to vdg's
// bottom-left origin, so the export's flip is undone exactly once).
TriMesh baseFromRig(const RawRig& rig) { return rig.mesh; }

RawViewDependentModel fromDescription(Described d, const TriMesh& base, std::span<const std::vector<float>> deltas,
                                      const std::string& where) {
  RawViewDependentModel raw = std::move(d.raw);
  raw.base = base;
  for (std::size_t k = 0; k < raw.keys.size(); ++k) {
    RawKey& rk = raw.keys[k];
    if (deltas[k].size() != base.positions.size())
      throw Error(where + ": mesh extras: 'vdg'.'keys'[" + std::to_string(k) + "]: morph target " + std::to_string(k) +
                  " has " + std::to_string(deltas[k].size()) + " delta values, expected " +
                  std::to_string(base.positions.size()));
    rk.mesh.triangles = base.triangles;
    rk.mesh.positions = base.positions;
    for (std::size_t i = 0; i < rk.mesh.positions.size(); ++i) rk.mesh.positions[i] += deltas[k][i];
  }
  raw.validate();
  return raw;
}

// mesh.extras.vdg.dequantize of a quantised export (vdg/io/gltf_compress.h): the file's mesh-local
// positions p lie at offset + scale * p in model units and its deltas d at scale * d. Applied to
// `base` and `deltas` in place; nothing when the field is absent.
void dequantize(const io::Json& extras, TriMesh& base, std::span<std::vector<float>> deltas, const std::string& where) {
  if (!extras.is_object() || !extras.contains("vdg") || !extras["vdg"].is_object() ||
      !extras["vdg"].contains("dequantize"))
    return;
  const io::Json& dq = extras["vdg"]["dequantize"];
  const std::string e = where + ": mesh extras: 'vdg'.'dequantize'";
  if (!dq.is_object()) throw Error(e + ": expected an object, got " + io::describe(dq));
  double field[2][3];
  const char* names[2] = {"scale", "offset"};
  for (int f = 0; f < 2; ++f) {
    const auto it = dq.find(names[f]);
    if (it == dq.end() || !it->is_array() || it->size() != 3 ||
        !std::all_of(it->begin(), it->end(), [](const io::Json& x) { return x.is_number(); }))
      throw Error(e + ".'" + names[f] + "': expected 3 numbers");
    for (int c = 0; c < 3; ++c) field[f][c] = (*it)[static_cast<std::size_t>(c)].get<double>();
    for (int c = 0; c < 3; ++c)
      if (!std::isfinite(field[f][c]) || (f == 0 && !(field[f][c] > 0.0)))
        throw Error(e + ".'" + names[f] + "': expected 3 finite numbers" + (f == 0 ? " > 0" : ""));
  }
  for (std::size_t i = 0; i < base.positions.size(); ++i)
    base.positions[i] = static_cast<float>(field[1][i % 3] + field[0][i % 3] * base.positions[i]);
  for (std::vector<float>& d : deltas)
    for (std::size_t i = 0; i < d.size(); ++i) d[i] = static_cast<float>(field[0][i % 3] * d[i]);
}

}  // namespace

RawViewDependentModel rawModelFromGltfExtras(std::string_view mesh_extras_json, const TriMesh& base,
                                             std::span<const std::vector<float>> target_deltas,
                                             const std::string& where) {
  const io::Json extras = io::parseJson(mesh_extras_json, where + ": mesh extras");
  Described d = describedModel(extras, target_deltas.size(), where);
  if (d.animation)
    throw Error(where +
                ": mesh extras: 'vdg'.'animation': an animated view-dependent model needs its file's skin and "
                "animation; read it with loadGltfModel");
  TriMesh model_base = base;
  std::vector<std::vector<float>> deltas(target_deltas.begin(), target_deltas.end());
  dequantize(extras, model_base, deltas, where);
  return fromDescription(std::move(d), model_base, deltas, where);
}

RawViewDependentModel loadGltfModel(const std::string& path, const MeshReadOptions& options) {
  const std::string bytes = readFileLimited(path, "glTF file", kMaxMeshFileBytes);
  const std::string folder = std::filesystem::path(path).parent_path().string();
  const RawRig rig = parseGltfRig(bytes, path, folder.empty() ? "." : folder, {}, options);
  const io::Json extras = meshExtras(bytes, rig, path);
  if (extras.is_null() || (extras.is_object() && !extras.contains("vdg")))
    throw Error(path +
                ": the mesh has no extras.vdg: this glTF file is a plain mesh, not a view-dependent model "
                "exported by vdg");
  Described d = describedModel(extras, rig.target_positions.size(), path);
  TriMesh base = baseFromRig(rig);
  std::vector<std::vector<float>> deltas = rig.target_positions;
  // An animated base's frames are posed by the node's transform below (Rig), so only its
  // positions taken as they are here (replaced by frame 0) and the deltas need dequantising.
  dequantize(extras, base, deltas, path);
  if (!d.animation) return fromDescription(std::move(d), base, deltas, path);

  // Animated: the base sampled by vdg's own glTF reader at every frame.
  const GltfBaseAnimation ba = *d.animation;
  RawViewDependentModel raw = std::move(d.raw);
  raw.base = base;
  BaseAnimationSpec spec;
  spec.gltf = std::filesystem::path(path).filename().string();
  spec.animation = std::max(d.animation_index, 0);
  spec.fps = ba.fps;
  spec.loop = ba.loop;
  raw.base_animation = spec;
  const bool skinned = raw.offsets == OffsetSpace::kSkinned;
  if (skinned && !rig.skin) throw Error(path + ": mesh extras: 'vdg'.'offsets': \"skinned\", but the mesh has no skin");
  const Rig posed = Rig::build(rig);
  if (d.animation_index >= static_cast<int>(posed.animationCount()))
    throw Error(path + ": mesh extras: 'vdg'.'animation'.'animation': " + std::to_string(d.animation_index) +
                " is out of range (the file has " + std::to_string(posed.animationCount()) + " animations)");
  const std::size_t n = static_cast<std::size_t>(ba.frame_count), floats = rig.mesh.positions.size();
  raw.base_frames.assign(n, std::vector<float>(floats));
  if (skinned) raw.base_skin.assign(n, std::vector<float>(floats * 3));
  for (std::size_t i = 0; i < n; ++i)
    if (!posed.evaluate(d.animation_index, static_cast<double>(i) / ba.fps, raw.base_frames[i], {},
                        skinned ? std::span<float>(raw.base_skin[i]) : std::span<float>()))
      throw Error(path + ": frame " + std::to_string(i) + " could not be evaluated (internal error)");
  raw.base.positions = raw.base_frames.front();
  for (std::size_t k = 0; k < raw.keys.size(); ++k) {
    RawKey& rk = raw.keys[k];
    const std::vector<float>& delta = deltas[k];
    const std::vector<float>& frame = raw.base_frames[static_cast<std::size_t>(rk.frame)];
    rk.mesh.triangles = base.triangles;
    rk.mesh.positions = frame;
    for (std::size_t v = 0; v < floats / 3; ++v) {
      Eigen::Vector3d o(delta[v * 3], delta[v * 3 + 1], delta[v * 3 + 2]);
      if (skinned)
        o = Eigen::Map<const Eigen::Matrix3f>(raw.base_skin[static_cast<std::size_t>(rk.frame)].data() + v * 9)
                .cast<double>() *
            o;
      for (int c = 0; c < 3; ++c) rk.mesh.positions[v * 3 + c] = static_cast<float>(frame[v * 3 + c] + o[c]);
    }
  }
  raw.validate();
  return raw;
}

bool gltfHasModel(const std::string& path) {
  const std::string bytes = readFileLimited(path, "glTF file", kMaxMeshFileBytes);
  const std::string folder = std::filesystem::path(path).parent_path().string();
  const RawRig rig =
      parseGltfRig(bytes, path, folder.empty() ? "." : folder, {}, MeshReadOptions{false, false, nullptr});
  const io::Json extras = meshExtras(bytes, rig, path);
  return extras.is_object() && extras.contains("vdg");
}

}  // namespace vdg
