// Scenes: hierarchy, animated fields, SET / CHANGE actions, cameras and instancing.
//
// Parent, Computer Animation: 4.7 (hierarchical transforms: world = world(parent) * link, the
// sun-earth-moon chain), 4.6 (the animation language's SET and CHANGE, absolute and relative
// changes spread over frames with an ease), 4.9 (TWIXT-style tracks, one per parameter, named
// "object.field"), 4.4 (cameras following a path with a centre of interest).
// Rademacher 99, sections 1 and 5: one view-dependent model instanced many times, each instance
// blended with its own view direction.
#include "vdg/scene/scene.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <string_view>

#include "vdg/geom/error.h"
#include "vdg/geom/normalize.h"
#include "vdg/geom/text.h"

namespace vdg::scene {

namespace {

constexpr int kMaxFieldDimension = 4;
using FieldValue = std::array<double, kMaxFieldDimension>;

// A matrix whose linear part's |det| is below this fraction of the product of its column lengths
// (Hadamard's bound) counts as singular: the test is independent of the matrix's scale.
constexpr double kSingularRatio = 1e-12;
// An up vector within this fraction of its length of the view direction counts as parallel to it.
constexpr double kParallelRatio = 1e-9;

bool validKind(ObjectKind kind) {
  return static_cast<int>(kind) >= 0 && static_cast<int>(kind) <= static_cast<int>(ObjectKind::kCamera);
}
bool validField(Field field) { return static_cast<int>(field) >= 0 && static_cast<int>(field) < kFieldCount; }

bool drawable(ObjectKind kind) {
  return kind == ObjectKind::kMesh || kind == ObjectKind::kModel || kind == ObjectKind::kAnimatedModel;
}

// The initial value of a field, from the raw node.
FieldValue initialValue(const RawNode& n, Field field) {
  FieldValue v{0.0, 0.0, 0.0, 0.0};
  switch (field) {
    case Field::kTranslation:
      v = {n.link.translation.x(), n.link.translation.y(), n.link.translation.z(), 0.0};
      break;
    case Field::kRotation:
      v = {n.link.rotation.w(), n.link.rotation.x(), n.link.rotation.y(), n.link.rotation.z()};
      break;
    case Field::kScale:
      v = {n.link.scale.x(), n.link.scale.y(), n.link.scale.z(), 0.0};
      break;
    case Field::kColor:
      v = {n.color[0], n.color[1], n.color[2], 0.0};
      break;
    case Field::kVisible:
      v[0] = n.visible ? 1.0 : 0.0;
      break;
    case Field::kSharpness:
      v[0] = n.sharpness;
      break;
    case Field::kFrameOffset:
      v[0] = n.frame_offset;
      break;
    case Field::kFov:
      v[0] = n.fov_deg;
      break;
  }
  return v;
}

// q^s for a unit quaternion q and s in [0, 1]: the turn q scaled by s, the way q turns (its angle
// 2 atan2(|xyz|, w) in [0, 360] degrees), i.e. slerp(identity, q, s) without the shortest-arc
// flip, so that a CHANGE by a 270-degree turn turns 270 degrees.
Eigen::Quaterniond quaternionPower(const Eigen::Quaterniond& q, double s) {
  const double vector_length = q.vec().norm();
  if (!(vector_length > 0.0)) return Eigen::Quaterniond::Identity();
  const double half_angle = std::atan2(vector_length, q.w()) * s;
  const Eigen::Vector3d axis = q.vec() / vector_length;
  const double sin_half = std::sin(half_angle);
  return Eigen::Quaterniond(std::cos(half_angle), sin_half * axis.x(), sin_half * axis.y(), sin_half * axis.z());
}

// The inverse of an affine matrix's linear part and its translation; false when the matrix is
// not finite or its linear part is (numerically) singular.
bool invertAffine(const Eigen::Matrix4d& m, Eigen::Matrix3d& linear_inverse, Eigen::Vector3d& translation) {
  if (!m.allFinite()) return false;
  const Eigen::Matrix3d a = m.topLeftCorner<3, 3>();
  const double det = a.determinant();
  const double bound = robustNorm(Eigen::Vector3d(a.col(0))) * robustNorm(Eigen::Vector3d(a.col(1))) *
                       robustNorm(Eigen::Vector3d(a.col(2)));
  if (!std::isfinite(det) || !std::isfinite(bound) || !(std::abs(det) > kSingularRatio * bound)) return false;
  linear_inverse = a.inverse();
  if (!linear_inverse.allFinite()) return false;
  translation = m.topRightCorner<3, 1>();
  return true;
}

}  // namespace

const char* objectKindName(ObjectKind kind) {
  switch (kind) {
    case ObjectKind::kGroup:
      return "group";
    case ObjectKind::kMesh:
      return "mesh";
    case ObjectKind::kModel:
      return "model";
    case ObjectKind::kAnimatedModel:
      return "animated-model";
    case ObjectKind::kCamera:
      return "camera";
  }
  return "?";
}

const char* fieldName(Field field) {
  switch (field) {
    case Field::kTranslation:
      return "translation";
    case Field::kRotation:
      return "rotation";
    case Field::kScale:
      return "scale";
    case Field::kColor:
      return "color";
    case Field::kVisible:
      return "visible";
    case Field::kSharpness:
      return "sharpness";
    case Field::kFrameOffset:
      return "frame_offset";
    case Field::kFov:
      return "fov";
  }
  return "?";
}

std::optional<Field> fieldFromName(std::string_view name) {
  for (int i = 0; i < kFieldCount; ++i) {
    const Field f = static_cast<Field>(i);
    if (name == fieldName(f)) return f;
  }
  return std::nullopt;
}

int fieldDimension(Field field) {
  switch (field) {
    case Field::kRotation:
      return 4;
    case Field::kTranslation:
    case Field::kScale:
    case Field::kColor:
      return 3;
    default:
      return 1;
  }
}

bool hasField(ObjectKind kind, Field field) {
  switch (field) {
    case Field::kTranslation:
    case Field::kRotation:
    case Field::kScale:
    case Field::kVisible:
      return true;
    case Field::kColor:
      return drawable(kind);
    case Field::kSharpness:
      return kind == ObjectKind::kModel || kind == ObjectKind::kAnimatedModel;
    case Field::kFrameOffset:
      return kind == ObjectKind::kAnimatedModel;
    case Field::kFov:
      return kind == ObjectKind::kCamera;
  }
  return false;
}

Eigen::Matrix4d Transform::matrix() const {
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  m.topLeftCorner<3, 3>() = rotation.normalized().toRotationMatrix() * scale.asDiagonal();
  m.topRightCorner<3, 1>() = translation;
  return m;
}

// ---------------------------------------------------------------------------------------------
// Built data.

namespace detail {

// The built scene (Scene::Impl derives from it, so that the free functions here can name it).
struct BuiltScene {
  struct Action {
    RawAction::Kind kind = RawAction::Kind::kSet;
    double from = 0.0, to = 0.0;
    anim::Ease ease;
    FieldValue value{};  // rotations normalised (w, x, y, z)
  };
  // Where a field's value comes from: its track (index into tracks) or the initial value, then
  // actions [action_begin, action_end) in the order given.
  struct Source {
    int track = -1;
    int action_begin = 0, action_end = 0;
  };

  std::vector<std::shared_ptr<const TriMesh>> meshes;
  std::vector<std::shared_ptr<const ViewDependentModel>> models;
  std::vector<std::shared_ptr<const AnimatedViewDependentModel>> animated_models;
  std::vector<RawNode> nodes;  // rotations normalised
  std::vector<Eigen::Matrix4d> placement;
  std::vector<std::array<Source, kFieldCount>> sources;
  std::vector<std::array<FieldValue, kFieldCount>> initial;
  std::vector<anim::Track> tracks;
  std::vector<Action> actions;  // grouped by (node, field), order given within a group
  std::vector<std::optional<anim::CameraPath>> paths;
  std::vector<int> look_at;  // per node: -1 or the node looked at
  // Per node: empty, or (a model with part drivers) per part of its model the driving node or -1.
  std::vector<std::vector<int>> part_driver;
  std::map<std::string, int, std::less<>> by_name;
  int camera = -1;

  // The value of `field` of `node` at finite `frame` into out (fieldDimension numbers).
  void fieldAt(int node, Field field, double frame, FieldValue& out) const;
};

}  // namespace detail

struct Scene::Impl : detail::BuiltScene {};

namespace {

// Progress of a CHANGE at frame t, ease(u) in [0, 1]; `inclusive`: a jump (to == from) at t ==
// from counts as done.
double changeProgress(const detail::BuiltScene::Action& a, double t, bool inclusive) {
  if (a.to > a.from) {
    if (t <= a.from) return 0.0;
    if (t >= a.to) return 1.0;
    return a.ease.evaluate((t - a.from) / (a.to - a.from));
  }
  return (inclusive ? t >= a.from : t > a.from) ? 1.0 : 0.0;
}

}  // namespace

void detail::BuiltScene::fieldAt(int node, Field field, double frame, FieldValue& out) const {
  const int f = static_cast<int>(field);
  const int dim = fieldDimension(field);
  const Source& src = sources[static_cast<std::size_t>(node)][static_cast<std::size_t>(f)];
  if (src.track >= 0) {
    // Finite frame and the right size (checked at build): evaluate cannot refuse.
    (void)tracks[static_cast<std::size_t>(src.track)].evaluate(
        frame, std::span<double>(out.data(), static_cast<std::size_t>(dim)));
  } else {
    out = initial[static_cast<std::size_t>(node)][static_cast<std::size_t>(f)];
  }
  if (src.action_begin == src.action_end) return;

  // Parent 4.6: the latest SET whose frame has come (the last given among equal frames) replaces
  // everything before it; CHANGEs add what they add after it.
  int set = -1;
  for (int i = src.action_begin; i < src.action_end; ++i) {
    const Action& a = actions[static_cast<std::size_t>(i)];
    if (a.kind == RawAction::Kind::kSet && a.from <= frame &&
        (set < 0 || a.from >= actions[static_cast<std::size_t>(set)].from)) {
      set = i;
    }
  }
  if (set >= 0) out = actions[static_cast<std::size_t>(set)].value;
  const double set_frame = set >= 0 ? actions[static_cast<std::size_t>(set)].from : 0.0;

  Eigen::Quaterniond q(out[0], out[1], out[2], out[3]);
  for (int i = src.action_begin; i < src.action_end; ++i) {
    const Action& a = actions[static_cast<std::size_t>(i)];
    if (a.kind != RawAction::Kind::kChange) continue;
    double weight = changeProgress(a, frame, true);
    // A CHANGE given before the SET loses what it added up to and at the SET's frame; one given
    // after it keeps a jump at exactly that frame.
    if (set >= 0) weight -= changeProgress(a, set_frame, i < set);
    if (weight == 0.0) continue;
    if (field == Field::kRotation) {
      q = q * quaternionPower(Eigen::Quaterniond(a.value[0], a.value[1], a.value[2], a.value[3]), weight);
    } else {
      for (int k = 0; k < dim; ++k) out[static_cast<std::size_t>(k)] += a.value[static_cast<std::size_t>(k)] * weight;
    }
  }
  if (field == Field::kRotation) {
    q.normalize();
    out = {q.w(), q.x(), q.y(), q.z()};
  }
}

// ---------------------------------------------------------------------------------------------
// Validation and build: one pass that validates and, when `impl` is given, fills it.

namespace {

std::string nodeLabel(const std::string& where, const RawNode& n, std::size_t i) {
  if (n.name.empty()) return where + ": node " + std::to_string(i);
  return where + ": node '" + n.name + "'";
}

template <typename Fail>
void checkTransform(const Transform& t, const char* which, const Fail& fail) {
  if (!t.translation.allFinite()) fail(std::string(which) + " translation is not finite");
  if (!t.rotation.coeffs().allFinite() || !normalizedOrNone(t.rotation)) {
    fail(std::string(which) + " rotation is a zero or non-finite quaternion");
  }
  if (!t.scale.allFinite() || (t.scale.array() == 0.0).any()) {
    fail(std::string(which) + " scale must be finite and non-zero in every component");
  }
}

bool inUnitRange(double v) { return v >= 0.0 && v <= 1.0; }
bool validFov(double v) { return v > 0.0 && v < 180.0; }

const char* objectListName(ObjectKind kind) {
  switch (kind) {
    case ObjectKind::kMesh:
      return "meshes";
    case ObjectKind::kModel:
      return "models";
    default:
      return "animated_models";
  }
}

using NodeNames = std::map<std::string, int, std::less<>>;
using TrackSlots = std::vector<std::array<int, kFieldCount>>;  // per node and field: its track, or -1

void checkCounts(const RawScene& raw, const std::string& where) {
  const std::size_t n = raw.nodes.size();
  if (n == 0) throw Error(where + ": a scene needs at least one node");
  if (n > static_cast<std::size_t>(kMaxSceneNodes)) {
    throw Error(where + ": " + std::to_string(n) + " nodes, more than the " + std::to_string(kMaxSceneNodes) +
                " a scene may have");
  }
  if (raw.actions.size() > static_cast<std::size_t>(kMaxSceneActions)) {
    throw Error(where + ": " + std::to_string(raw.actions.size()) + " actions, more than the " +
                std::to_string(kMaxSceneActions) + " a scene may have");
  }
}

// Node `i` on its own: name (added to `by_name`), parent, object, transforms, colour, camera fields.
void checkNode(const RawScene& raw, std::size_t i, const std::string& where, NodeNames& by_name) {
  const RawNode& node = raw.nodes[i];
  const std::string label = nodeLabel(where, node, i);
  auto fail = [&](const std::string& what) { throw Error(label + ": " + what); };
  if (node.name.empty()) fail("empty name");
  if (node.name.find('.') != std::string::npos) {
    fail("the name contains '.' (it separates node and field, as in 'earth.rotation')");
  }
  const auto [it, inserted] = by_name.emplace(node.name, static_cast<int>(i));
  if (!inserted) fail("duplicate name (node " + std::to_string(it->second) + " has it too)");
  if (node.parent < -1 || node.parent >= static_cast<int>(i)) {
    fail("parent " + std::to_string(node.parent) + " is not an earlier node (-1 for a root, or 0.." +
         std::to_string(static_cast<long>(i) - 1) + ")");
  }
  if (!validKind(node.kind)) fail("unknown object kind " + std::to_string(static_cast<int>(node.kind)));
  if (node.kind == ObjectKind::kGroup || node.kind == ObjectKind::kCamera) {
    if (node.object != -1) {
      fail(std::string("a ") + objectKindName(node.kind) + " holds no object (object " + std::to_string(node.object) +
           ", expected -1)");
    }
  } else {
    const std::size_t count = node.kind == ObjectKind::kMesh    ? raw.meshes.size()
                              : node.kind == ObjectKind::kModel ? raw.models.size()
                                                                : raw.animated_models.size();
    const char* list = objectListName(node.kind);
    if (node.object < 0 || static_cast<std::size_t>(node.object) >= count) {
      fail(std::string("object ") + std::to_string(node.object) + " out of range (the scene has " +
           std::to_string(count) + " " + list + ")");
    }
    const auto o = static_cast<std::size_t>(node.object);
    const bool null = node.kind == ObjectKind::kMesh    ? !raw.meshes[o]
                      : node.kind == ObjectKind::kModel ? !raw.models[o]
                                                        : !raw.animated_models[o];
    if (null) fail(std::string("object ") + std::to_string(node.object) + " of " + list + " is null");
  }
  checkTransform(node.placement, "placement", fail);
  checkTransform(node.link, "link", fail);
  for (int k = 0; k < 3; ++k) {
    if (!inUnitRange(node.color[static_cast<std::size_t>(k)])) {
      fail("color component " + std::to_string(k) + " (" + numberText(node.color[static_cast<std::size_t>(k)]) +
           ") is outside [0, 1]");
    }
  }
  if (!std::isfinite(node.sharpness)) fail("sharpness is not finite");
  if (!std::isfinite(node.frame_offset)) fail("frame_offset is not finite");
  if (node.kind == ObjectKind::kCamera) {
    if (!validFov(node.fov_deg)) fail("fov " + numberText(node.fov_deg) + " degrees is outside (0, 180)");
    if (!std::isfinite(node.ortho_height) || node.ortho_height < 0.0) {
      fail("ortho_height " + numberText(node.ortho_height) + " must be finite and >= 0");
    }
  } else {
    if (node.path) fail(std::string("a path on a ") + objectKindName(node.kind) + " node (only cameras follow paths)");
    if (!node.look_at.empty()) {
      fail(std::string("look_at on a ") + objectKindName(node.kind) + " node (only cameras look at nodes)");
    }
  }
}

// Cameras: paths and look_at (once every name is known).
void linkCameras(const RawScene& raw, const std::string& where, const NodeNames& by_name, detail::BuiltScene* impl) {
  const std::size_t n = raw.nodes.size();
  if (impl) {
    impl->paths.resize(n);
    impl->look_at.assign(n, -1);
  }
  for (std::size_t i = 0; i < n; ++i) {
    const RawNode& node = raw.nodes[i];
    const std::string label = nodeLabel(where, node, i);
    if (node.path) {
      anim::CameraPath path = anim::CameraPath::build(*node.path, label + ": path");
      if (impl) impl->paths[i].emplace(std::move(path));
    }
    if (!node.look_at.empty()) {
      const auto it = by_name.find(node.look_at);
      if (it == by_name.end()) throw Error(label + ": look_at '" + node.look_at + "' names no node");
      if (it->second == static_cast<int>(i)) throw Error(label + ": look_at names the camera itself");
      if (impl) impl->look_at[i] = it->second;
    }
  }
}

// Part drivers (once every name is known): each names a part of the node's model and a node.
void linkPartDrivers(const RawScene& raw, const std::string& where, const NodeNames& by_name,
                     detail::BuiltScene* impl) {
  const std::size_t n = raw.nodes.size();
  if (impl) impl->part_driver.assign(n, {});
  for (std::size_t i = 0; i < n; ++i) {
    const RawNode& node = raw.nodes[i];
    if (node.part_drivers.empty()) continue;
    const std::string label = nodeLabel(where, node, i) + ": part driver";
    const ViewDependentModel* model =
        node.kind == ObjectKind::kModel ? raw.models[static_cast<std::size_t>(node.object)].get() : nullptr;
    if (!model || !model->hasParts()) {
      throw Error(label + ": the node holds no view-dependent model with parts ('parts' in its manifest)");
    }
    std::vector<int> drivers(model->partCount(), -1);
    for (const RawPartDriver& d : node.part_drivers) {
      std::size_t part = 0;
      while (part < model->partCount() && model->partName(part) != d.part) ++part;
      if (part == model->partCount()) {
        std::string names;
        for (std::size_t p = 0; p < model->partCount(); ++p) names += (p ? ", " : "") + model->partName(p);
        throw Error(label + " '" + d.part + "': the model has no such part (its parts: " + names + ")");
      }
      if (drivers[part] >= 0) throw Error(label + " '" + d.part + "': the part has two drivers");
      const auto it = by_name.find(d.node);
      if (it == by_name.end()) throw Error(label + " '" + d.part + "': '" + d.node + "' names no node");
      if (it->second == static_cast<int>(i)) throw Error(label + " '" + d.part + "': names the model node itself");
      drivers[part] = it->second;
    }
    if (impl) impl->part_driver[i] = std::move(drivers);
  }
}

// The node that a track or an action (`what`: "track 3", "action 0") names, after checking that the
// node exists and the field is one vdg knows.
const RawNode& namedNode(const RawScene& raw, int node, Field field, const std::string& what,
                         const std::string& where) {
  const std::size_t n = raw.nodes.size();
  if (node < 0 || static_cast<std::size_t>(node) >= n) {
    throw Error(where + ": " + what + ": node " + std::to_string(node) + " out of range (the scene has " +
                std::to_string(n) + " nodes)");
  }
  if (!validField(field))
    throw Error(where + ": " + what + ": unknown field " + std::to_string(static_cast<int>(field)));
  return raw.nodes[static_cast<std::size_t>(node)];
}

// Track `t`: its node, field and type; marks the field's slot (a field has one track at most).
anim::Track checkTrack(const RawScene& raw, std::size_t t, const std::string& where, TrackSlots& track_of) {
  const RawFieldTrack& ft = raw.tracks[t];
  const RawNode& node = namedNode(raw, ft.node, ft.field, "track " + std::to_string(t), where);
  const std::string name = node.name + "." + fieldName(ft.field);
  auto fail = [&](const std::string& what) { throw Error(where + ": track '" + name + "': " + what); };
  if (!hasField(node.kind, ft.field)) {
    fail(std::string("a ") + objectKindName(node.kind) + " node has no field '" + fieldName(ft.field) + "'");
  }
  const int dim = fieldDimension(ft.field);
  if (ft.field == Field::kRotation) {
    if (ft.track.type != anim::TrackType::kRotation) {
      fail(std::string("field 'rotation' needs a rotation track, not a ") + anim::trackTypeName(ft.track.type) +
           " track");
    }
  } else if (ft.track.type == anim::TrackType::kRotation || (dim > 1 && ft.track.type == anim::TrackType::kScalar)) {
    fail(std::string("field '") + fieldName(ft.field) + "' has " + std::to_string(dim) + " number" +
         (dim > 1 ? "s" : "") + ", not a " + anim::trackTypeName(ft.track.type) + " track");
  } else if (ft.track.type == anim::TrackType::kVector && !ft.track.keys.empty() &&
             ft.track.keys[0].value.size() != dim) {
    fail(std::string("field '") + fieldName(ft.field) + "' has " + std::to_string(dim) + " number" +
         (dim > 1 ? "s" : "") + ", the track's keys have " + std::to_string(ft.track.keys[0].value.size()));
  }
  int& slot = track_of[static_cast<std::size_t>(ft.node)][static_cast<std::size_t>(ft.field)];
  if (slot >= 0) fail("the field already has a track (track " + std::to_string(slot) + ")");
  slot = static_cast<int>(t);
  anim::RawTrack named = ft.track;
  named.name = name;
  return anim::Track::build(named, where);
}

// Action `a`: its node, field, kind and value; a field with a track takes no action.
void checkAction(const RawScene& raw, std::size_t a, const std::string& where, const TrackSlots& track_of) {
  const RawAction& act = raw.actions[a];
  const RawNode& node = namedNode(raw, act.node, act.field, "action " + std::to_string(a), where);
  const std::string label =
      where + ": action " + std::to_string(a) + " (" + node.name + "." + fieldName(act.field) + ")";
  auto fail = [&](const std::string& what) { throw Error(label + ": " + what); };
  if (act.kind != RawAction::Kind::kSet && act.kind != RawAction::Kind::kChange) {
    fail("unknown kind " + std::to_string(static_cast<int>(act.kind)));
  }
  const bool set = act.kind == RawAction::Kind::kSet;
  if (!hasField(node.kind, act.field)) {
    fail(std::string("a ") + objectKindName(node.kind) + " node has no field '" + fieldName(act.field) + "'");
  }
  const int track = track_of[static_cast<std::size_t>(act.node)][static_cast<std::size_t>(act.field)];
  if (track >= 0) {
    fail("the field also has a track (track " + std::to_string(track) + "); give a field a track or actions, not both");
  }
  const int dim = fieldDimension(act.field);
  if (act.value.size() != dim) {
    fail("the value has " + std::to_string(act.value.size()) + " numbers, field '" + fieldName(act.field) + "' has " +
         std::to_string(dim));
  }
  if (!act.value.allFinite()) fail("the value is not finite");
  if (act.field == Field::kRotation && !(act.value.norm() > 0.0)) fail("the rotation is a zero quaternion");
  if (set && act.field == Field::kScale && (act.value.array() == 0.0).any()) {
    fail("a scale must be non-zero in every component");
  }
  if (set && act.field == Field::kColor) {
    for (Eigen::Index k = 0; k < 3; ++k) {
      if (!inUnitRange(act.value[k])) {
        fail("color component " + std::to_string(k) + " (" + numberText(act.value[k]) + ") is outside [0, 1]");
      }
    }
  }
  if (set && act.field == Field::kFov && !validFov(act.value[0])) {
    fail("fov " + numberText(act.value[0]) + " degrees is outside (0, 180)");
  }
  if (!std::isfinite(act.from_frame) || (!set && !std::isfinite(act.to_frame))) fail("its frames must be finite");
  if (!set && act.to_frame < act.from_frame) {
    fail("the CHANGE ends at frame " + numberText(act.to_frame) + ", before it starts at frame " +
         numberText(act.from_frame));
  }
}

// The active camera: the one named, else the first camera node, else -1.
int activeCamera(const RawScene& raw, const std::string& where, const NodeNames& by_name) {
  const std::size_t n = raw.nodes.size();
  int camera = -1;
  if (!raw.camera.empty()) {
    const auto it = by_name.find(raw.camera);
    if (it == by_name.end()) throw Error(where + ": camera '" + raw.camera + "': no node has that name");
    const RawNode& node = raw.nodes[static_cast<std::size_t>(it->second)];
    if (node.kind != ObjectKind::kCamera) {
      throw Error(where + ": camera '" + raw.camera + "': a " + objectKindName(node.kind) + " node, not a camera");
    }
    camera = it->second;
  } else {
    for (std::size_t i = 0; i < n && camera < 0; ++i)
      if (raw.nodes[i].kind == ObjectKind::kCamera) camera = static_cast<int>(i);
  }
  return camera;
}

// The checked scene into `impl`: nodes, initial field values, and actions grouped by (node, field).
void fillBuilt(const RawScene& raw, const TrackSlots& track_of, detail::BuiltScene* impl) {
  const std::size_t n = raw.nodes.size();
  impl->meshes = raw.meshes;
  impl->models = raw.models;
  impl->animated_models = raw.animated_models;
  impl->nodes = raw.nodes;
  impl->placement.resize(n);
  impl->initial.resize(n);
  impl->sources.assign(n, {});
  for (std::size_t i = 0; i < n; ++i) {
    RawNode& node = impl->nodes[i];
    node.placement.rotation.normalize();
    node.link.rotation.normalize();
    impl->placement[i] = node.placement.matrix();
    for (int f = 0; f < kFieldCount; ++f) {
      impl->initial[i][static_cast<std::size_t>(f)] = initialValue(node, static_cast<Field>(f));
      impl->sources[i][static_cast<std::size_t>(f)].track = track_of[i][static_cast<std::size_t>(f)];
    }
  }
  // Actions grouped by (node, field), order given within each group.
  std::vector<std::size_t> order(raw.actions.size());
  for (std::size_t a = 0; a < order.size(); ++a) order[a] = a;
  auto key = [&](std::size_t a) {
    return static_cast<long>(raw.actions[a].node) * kFieldCount + static_cast<long>(raw.actions[a].field);
  };
  std::stable_sort(order.begin(), order.end(), [&](std::size_t x, std::size_t y) { return key(x) < key(y); });
  impl->actions.reserve(order.size());
  for (std::size_t a : order) {
    const RawAction& act = raw.actions[a];
    detail::BuiltScene::Action built;
    built.kind = act.kind;
    built.from = act.from_frame;
    built.to = act.kind == RawAction::Kind::kChange ? act.to_frame : act.from_frame;
    built.ease = act.ease;
    for (Eigen::Index k = 0; k < act.value.size(); ++k) built.value[static_cast<std::size_t>(k)] = act.value[k];
    if (act.field == Field::kRotation) {
      const Eigen::Vector4d q = act.value.normalized();
      built.value = {q[0], q[1], q[2], q[3]};
    }
    auto& src = impl->sources[static_cast<std::size_t>(act.node)][static_cast<std::size_t>(act.field)];
    const int index = static_cast<int>(impl->actions.size());
    if (src.action_begin == src.action_end) src.action_begin = index;
    src.action_end = index + 1;
    impl->actions.push_back(built);
  }
}

void validateAndBuild(const RawScene& raw, const std::string& where, detail::BuiltScene* impl) {
  checkCounts(raw, where);
  NodeNames by_name;
  for (std::size_t i = 0; i < raw.nodes.size(); ++i) checkNode(raw, i, where, by_name);
  linkCameras(raw, where, by_name, impl);
  linkPartDrivers(raw, where, by_name, impl);
  TrackSlots track_of(raw.nodes.size());
  for (auto& t : track_of) t.fill(-1);
  if (impl) impl->tracks.reserve(raw.tracks.size());
  for (std::size_t t = 0; t < raw.tracks.size(); ++t) {
    anim::Track built = checkTrack(raw, t, where, track_of);
    if (impl) impl->tracks.push_back(std::move(built));
  }
  for (std::size_t a = 0; a < raw.actions.size(); ++a) checkAction(raw, a, where, track_of);
  const int camera = activeCamera(raw, where, by_name);
  if (!impl) return;
  fillBuilt(raw, track_of, impl);
  impl->by_name = std::move(by_name);
  impl->camera = camera;
}

}  // namespace

void RawScene::validate(const std::string& where) const { validateAndBuild(*this, where, nullptr); }

Scene Scene::build(const RawScene& raw, const std::string& where) {
  auto impl = std::make_shared<Impl>();
  validateAndBuild(raw, where, impl.get());
  Scene scene;
  scene.impl_ = std::move(impl);
  return scene;
}

// ---------------------------------------------------------------------------------------------
// Accessors.

namespace {
[[noreturn]] void throwNodeOutOfRange(int node, std::size_t count) {
  throw Error("scene: node " + std::to_string(node) + " out of range (the scene has " + std::to_string(count) +
              " nodes)");
}
}  // namespace

int Scene::nodeCount() const { return static_cast<int>(impl_->nodes.size()); }

const RawNode& Scene::rawNode(int node) const {
  if (node < 0 || node >= nodeCount()) throwNodeOutOfRange(node, impl_->nodes.size());
  return impl_->nodes[static_cast<std::size_t>(node)];
}
const std::string& Scene::nodeName(int node) const { return rawNode(node).name; }
int Scene::findNode(std::string_view name) const {
  const auto it = impl_->by_name.find(name);
  return it == impl_->by_name.end() ? -1 : it->second;
}
ObjectKind Scene::kind(int node) const { return rawNode(node).kind; }
int Scene::parent(int node) const { return rawNode(node).parent; }
int Scene::cameraNode() const { return impl_->camera; }

const TriMesh* Scene::mesh(int node) const {
  const RawNode& n = rawNode(node);
  return n.kind == ObjectKind::kMesh ? impl_->meshes[static_cast<std::size_t>(n.object)].get() : nullptr;
}
const ViewDependentModel* Scene::model(int node) const {
  const RawNode& n = rawNode(node);
  return n.kind == ObjectKind::kModel ? impl_->models[static_cast<std::size_t>(n.object)].get() : nullptr;
}
const AnimatedViewDependentModel* Scene::animatedModel(int node) const {
  const RawNode& n = rawNode(node);
  return n.kind == ObjectKind::kAnimatedModel ? impl_->animated_models[static_cast<std::size_t>(n.object)].get()
                                              : nullptr;
}

// ---------------------------------------------------------------------------------------------
// Per-frame evaluation.

bool Scene::evaluate(double frame, std::span<NodeState> out) const {
  if (!std::isfinite(frame) || out.size() != impl_->nodes.size()) return false;
  const Impl& s = *impl_;
  FieldValue t, r, sc, v;
  for (std::size_t i = 0; i < s.nodes.size(); ++i) {
    const RawNode& node = s.nodes[i];
    const int n = static_cast<int>(i);
    NodeState& st = out[i];
    s.fieldAt(n, Field::kTranslation, frame, t);
    s.fieldAt(n, Field::kRotation, frame, r);
    s.fieldAt(n, Field::kScale, frame, sc);
    // Parent 4.7: link = T R S; world = world(parent) * link; object = world * placement.
    Eigen::Matrix4d link = Eigen::Matrix4d::Identity();
    link.topLeftCorner<3, 3>() = Eigen::Quaterniond(r[0], r[1], r[2], r[3]).toRotationMatrix() *
                                 Eigen::Vector3d(sc[0], sc[1], sc[2]).asDiagonal();
    link.topRightCorner<3, 1>() = Eigen::Vector3d(t[0], t[1], t[2]);
    const bool root = node.parent < 0;
    const NodeState* parent = root ? nullptr : &out[static_cast<std::size_t>(node.parent)];
    st.world = root ? link : Eigen::Matrix4d(parent->world * link);
    st.object = st.world * s.placement[i];

    s.fieldAt(n, Field::kVisible, frame, v);
    st.visible = v[0] > 0.5 && (root || parent->visible);
    s.fieldAt(n, Field::kColor, frame, v);
    for (std::size_t k = 0; k < 3; ++k) st.color[k] = static_cast<float>(std::clamp(v[k], 0.0, 1.0));
    s.fieldAt(n, Field::kSharpness, frame, v);
    st.sharpness = v[0];
    s.fieldAt(n, Field::kFov, frame, v);
    st.fov_deg = v[0];
    st.model_frame = 0;
    if (node.kind == ObjectKind::kAnimatedModel) {
      s.fieldAt(n, Field::kFrameOffset, frame, v);
      const int count = s.animated_models[static_cast<std::size_t>(node.object)]->frameCount();
      const double whole = std::floor(frame + v[0]);
      double m = std::isfinite(whole) && count > 0 ? std::fmod(whole, static_cast<double>(count)) : 0.0;
      if (m < 0.0) m += count;
      st.model_frame = std::clamp(static_cast<int>(m), 0, std::max(count - 1, 0));
    }
  }
  return true;
}

bool Scene::fieldValue(int node, Field field, double frame, std::span<double> out) const {
  if (node < 0 || node >= nodeCount() || !validField(field) || !std::isfinite(frame)) return false;
  if (!hasField(impl_->nodes[static_cast<std::size_t>(node)].kind, field)) return false;
  const auto dim = static_cast<std::size_t>(fieldDimension(field));
  if (out.size() != dim) return false;
  FieldValue v;
  impl_->fieldAt(node, field, frame, v);
  std::copy_n(v.begin(), dim, out.begin());
  return true;
}

namespace {
// A camera path's camera at `frame`, carried from the node's coordinates into the world by `world`.
bool pathCamera(const anim::CameraPath& path, double frame, const Eigen::Matrix4d& world, Camera& out) {
  if (!path.evaluate(frame, out)) return false;
  const Eigen::Matrix3d linear = world.topLeftCorner<3, 3>();
  const Eigen::Vector3d origin = world.topRightCorner<3, 1>();
  out.eye = linear * out.eye + origin;
  out.target = linear * out.target + origin;
  out.up = linear * out.up;
  return true;
}
}  // namespace

bool Scene::camera(double frame, std::span<const NodeState> states, Camera& out) const {
  const Impl& s = *impl_;
  if (s.camera < 0 || states.size() != s.nodes.size() || !std::isfinite(frame)) return false;
  const auto cam = static_cast<std::size_t>(s.camera);
  const NodeState& st = states[cam];
  Eigen::Matrix3d inverse;
  Eigen::Vector3d origin;
  if (!invertAffine(st.world, inverse, origin)) return false;
  const Eigen::Matrix3d linear = st.world.topLeftCorner<3, 3>();
  if (!validFov(st.fov_deg)) return false;

  // Parent 4.4: the path's camera lives in the node's coordinates; the node carries it into the world.
  Eigen::Vector3d eye, target, up;
  if (s.paths[cam]) {
    Camera local;
    if (!pathCamera(*s.paths[cam], frame, st.world, local)) return false;
    eye = local.eye;
    target = local.target;
    up = local.up;
  } else {
    const auto forward = normalizedOrNone(Eigen::Vector3d(linear * Eigen::Vector3d(0, 0, -1)));
    if (!forward) return false;
    eye = origin;
    target = eye + *forward * std::max(1.0, robustNorm(eye));
    up = linear * Eigen::Vector3d::UnitY();
  }
  if (s.look_at[cam] >= 0) target = states[static_cast<std::size_t>(s.look_at[cam])].world.topRightCorner<3, 1>();
  if (!eye.allFinite() || !target.allFinite()) return false;
  const auto forward = normalizedOrNone(Eigen::Vector3d(target - eye));
  if (!forward) return false;
  // The up vector orthogonalised; when it is parallel to the view, the node's -Z axis instead.
  auto orthogonal = [&](const Eigen::Vector3d& candidate) -> std::optional<Eigen::Vector3d> {
    const auto unit = normalizedOrNone(candidate);
    if (!unit) return std::nullopt;
    const Eigen::Vector3d u = *unit - unit->dot(*forward) * *forward;
    if (!(u.norm() > kParallelRatio)) return std::nullopt;
    return normalizedOrNone(u);
  };
  std::optional<Eigen::Vector3d> up_unit = orthogonal(up);
  if (!up_unit) up_unit = orthogonal(linear * Eigen::Vector3d(0, 0, -1));
  if (!up_unit) return false;
  out.eye = eye;
  out.target = target;
  out.up = *up_unit;
  out.fov_deg = st.fov_deg;
  out.ortho_height = s.nodes[cam].ortho_height;
  return true;
}

bool Scene::instanceView(int node, const NodeState& state, const Eigen::Vector3d& eye, Eigen::Vector3d& out) const {
  if (node < 0 || node >= nodeCount() || !eye.allFinite()) return false;
  const RawNode& n = impl_->nodes[static_cast<std::size_t>(node)];
  Eigen::Vector3d center;
  if (n.kind == ObjectKind::kModel) {
    center = impl_->models[static_cast<std::size_t>(n.object)]->center();
  } else if (n.kind == ObjectKind::kAnimatedModel) {
    center = impl_->animated_models[static_cast<std::size_t>(n.object)]->center();
  } else {
    return false;
  }
  Eigen::Matrix3d inverse;
  Eigen::Vector3d translation;
  if (!invertAffine(state.object, inverse, translation)) return false;
  // Rademacher 99, section 1: each instance is blended with the eye seen from its own frame.
  const auto view = normalizedOrNone(Eigen::Vector3d(inverse * (eye - translation) - center));
  if (!view) return false;
  out = *view;
  return true;
}

bool Scene::instanceEye(int node, const NodeState& state, const Eigen::Vector3d& eye, Eigen::Vector3d& out) const {
  if (node < 0 || node >= nodeCount() || !eye.allFinite()) return false;
  if (impl_->nodes[static_cast<std::size_t>(node)].kind != ObjectKind::kModel) return false;
  Eigen::Matrix3d inverse;
  Eigen::Vector3d translation;
  if (!invertAffine(state.object, inverse, translation)) return false;
  const Eigen::Vector3d local = inverse * (eye - translation);
  if (!local.allFinite()) return false;
  out = local;
  return true;
}

bool Scene::driverEye(int node, double frame, std::span<const NodeState> states, Eigen::Vector3d& out) const {
  const Impl& s = *impl_;
  if (node < 0 || node >= nodeCount() || states.size() != s.nodes.size() || !std::isfinite(frame)) return false;
  const auto n = static_cast<std::size_t>(node);
  Eigen::Vector3d eye = states[n].world.topRightCorner<3, 1>();
  if (s.paths[n]) {
    Camera local;
    if (!pathCamera(*s.paths[n], frame, states[n].world, local)) return false;
    eye = local.eye;
  }
  if (!eye.allFinite()) return false;
  out = eye;
  return true;
}

bool Scene::instancePartViews(int node, double frame, std::span<const NodeState> states, const Eigen::Vector3d& eye,
                              std::span<Eigen::Vector3d> out) const {
  const Impl& s = *impl_;
  if (node < 0 || node >= nodeCount() || states.size() != s.nodes.size()) return false;
  const auto n = static_cast<std::size_t>(node);
  const ViewDependentModel* m = model(node);
  if (!m || !m->hasParts() || out.size() != m->partCount()) return false;
  Eigen::Vector3d main;
  if (!instanceView(node, states[n], eye, main) || !m->partViews(main, out)) return false;
  const std::vector<int>& drivers = s.part_driver[n];
  for (std::size_t p = 0; p < drivers.size(); ++p) {
    if (drivers[p] < 0) continue;
    Eigen::Vector3d driver_eye;
    if (!driverEye(drivers[p], frame, states, driver_eye) || !instanceView(node, states[n], driver_eye, out[p]))
      return false;
  }
  return true;
}

}  // namespace vdg::scene
