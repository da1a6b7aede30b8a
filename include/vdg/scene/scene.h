// Scenes: a hierarchy of placed, animated objects seen by a camera (Parent, Computer Animation,
// sections 4.4, 4.6, 4.7 and 4.9; Rademacher 99, section 5 and Figure 13).
//
//   RawScene (mutable: what a script or a file builds) --Scene::build (validates)--> Scene
//   (immutable) --evaluate(frame, states)--> every node's world transform and animated values,
//   under the per-frame contract (checked on entry, false on a violation with nothing written, no
//   throw, no allocation).
//
// Time is measured in frames (a double: frame 12.5 is half-way between frames 12 and 13). Track
// key times, action frames and camera-path times are all frames.
//
// Hierarchy (Parent 4.7): each node holds an object (a group holds none), a fixed placement
// transform that moves the object so that its point of attachment is at the node's origin, and an
// animated link transform relative to its parent node. With column vectors,
//   world(node)  = world(parent) * link(node)         (world(root's parent) = identity)
//   object(node) = world(node) * placement(node)      (object coordinates -> world)
//   link = T(translation) * R(rotation) * S(scale)    (scale first, then rotate, then translate)
// The text's sun-earth-moon example, M' = M Tm Rm Te Re in its row-vector notation, is the chain
// sun -> earth orbit (rotation Re) -> earth (translation Te) -> moon orbit (Rm) -> moon (Tm).
//
// Animated fields, named "node.field" in messages (the TWIXT-style track naming of 4.9):
//   translation   3 numbers                    link translation
//   rotation      4 numbers (w, x, y, z)       link rotation, a quaternion (normalised)
//   scale         3 numbers                    link scale (each non-zero)
//   color         3 numbers in [0, 1]          the object's base colour Cbase (display RGB; clamped
//                                              into [0, 1] in NodeState when CHANGEs push it out)
//   visible       1 number                     drawn when > 0.5 (a hidden node, a group too, hides
//                                              its whole subtree)
//   sharpness     1 number                     view-dependent models: alpha of section 3.2.2; <= 0: the model's own
//   frame_offset  1 number                     animated models: frame = floor(scene frame + offset) mod N
//   fov           1 number, degrees in (0,180) cameras
// A field's value at frame f is, in this order:
//   1. its node's initial value (RawNode), or its track's value at f when it has a track;
//   2. actions (Parent 4.6), in the order given, each applied when its frame has come:
//      SET    at frame a: from frame a on, the field is `value` (absolute);
//      CHANGE from a to b by `value`: adds value * ease((f - a) / (b - a)) (clamped to [0, 1]) to
//             the field: nothing before a, all of it from b on (relative, spread over the frames).
//             Rotations compose: the field becomes rotation * slerp(identity, value, ease(u)),
//             i.e. `value` is a turn about the node's own (already rotated) axes, taken the way
//             `value` turns (its angle 2 atan2(|xyz|, w) in [0, 360] degrees, no shortest-arc
//             flip: a 270-degree turn turns 270 degrees); several CHANGEs compose in the order given.
//   A SET at frame a discards every earlier contribution, including that of CHANGEs that are
//   still running (they keep adding only what they add after a). The SET in force is the one
//   with the latest frame <= f (among equal frames, the last given); a jump CHANGE (to == from)
//   at exactly its frame counts when it is given after that SET, not when given before.
// A field may have a track or actions, or neither; both at once is refused by validate().
//
// Cameras (Parent 4.4): a camera node without a path looks along its node's -Z axis with its +Y up
// (the glTF convention). With a path (anim::RawCameraPath, times in frames) the path's camera is
// computed in the camera node's coordinates and carried into the world by the node's transform.
// `look_at` names a node whose world origin becomes the centre of interest at every frame (a
// moving centre of interest), overriding the view direction of the node or path; the up vector is
// the node's (or path's) up, orthogonalised (the node's -Z when that up is parallel to the view).
// The field of view is always the node's `fov` field and the parallel height its ortho_height (a
// path's own fov_deg and ortho_height are ignored). Scene::camera(frame) is the active camera.
//
// Instancing: many nodes may hold the same model (shared, immutable). A view-dependent model is
// blended per node with its own view direction (instanceView): the direction from the instance's
// centre to the eye, expressed in the instance's object coordinates, so that every member of a
// crowd is seen from its own angle (Rademacher 99, section 1: "replicated many times from
// different angles").
//
// Part drivers: a model with per-part key sets (ViewDependentModel::hasParts, docs/weights.md) may
// have a part follow another node instead of the active camera: `part_drivers` pairs a part's name
// with a node whose eye drives it (a camera's eye, on its path if it has one; any other node's
// world origin), as Chaudhuri et al. drive parts of one figure from several cameras. An undriven
// part keeps the model's fixed view, or else follows the active camera (instancePartViews).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "vdg/anim/camera_path.h"
#include "vdg/anim/ease.h"
#include "vdg/anim/track.h"
#include "vdg/geom/camera.h"
#include "vdg/geom/tri_mesh.h"
#include "vdg/viewdep/animated_model.h"
#include "vdg/viewdep/model.h"

namespace vdg::scene {

// Most nodes, actions and tracks in one scene.
inline constexpr int kMaxSceneNodes = 100000;
inline constexpr int kMaxSceneActions = 1000000;

enum class ObjectKind { kGroup, kMesh, kModel, kAnimatedModel, kCamera };
// "group", "mesh", "model", "animated-model", "camera".
const char* objectKindName(ObjectKind kind);

enum class Field { kTranslation, kRotation, kScale, kColor, kVisible, kSharpness, kFrameOffset, kFov };
inline constexpr int kFieldCount = 8;
// "translation", "rotation", "scale", "color", "visible", "sharpness", "frame_offset", "fov".
const char* fieldName(Field field);
// The field of a name above; std::nullopt for any other name.
std::optional<Field> fieldFromName(std::string_view name);
// Number of values: 3, 4, 3, 3, 1, 1, 1, 1.
int fieldDimension(Field field);
// Whether a node of `kind` has `field` (see the list above): translation, rotation, scale and
// visible on every node; color on meshes and models; sharpness on both model kinds; frame_offset
// on animated models; fov on cameras.
bool hasField(ObjectKind kind, Field field);

struct Transform {
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();
  Eigen::Quaterniond rotation = Eigen::Quaterniond::Identity();  // normalised by Scene::build
  Eigen::Vector3d scale = Eigen::Vector3d::Ones();
  // T * R * S as a 4x4 matrix (column vectors).
  Eigen::Matrix4d matrix() const;
};

// A part of a model node driven by another node (see "Part drivers" above).
struct RawPartDriver {
  std::string part;  // a part of the node's model (kRestPartName for the rest)
  std::string node;  // the driving node's name (not the model node itself)
};

struct RawNode {
  std::string name;  // unique, non-empty, no '.' (it separates node and field in "node.field")
  int parent = -1;   // index of an EARLIER node, or -1 (a root)
  ObjectKind kind = ObjectKind::kGroup;
  // kMesh: index into RawScene::meshes; kModel: into models; kAnimatedModel: into animated_models;
  // -1 for groups and cameras.
  int object = -1;
  Transform placement;  // fixed: object coordinates -> node coordinates
  Transform link;       // initial link transform (fields translation, rotation, scale)
  std::array<float, 3> color{1.0f, 1.0f, 1.0f};
  bool visible = true;
  double sharpness = 0.0;
  double frame_offset = 0.0;
  // Cameras.
  double fov_deg = 40.0;
  double ortho_height = 0.0;                // > 0: parallel projection of this height
  std::optional<anim::RawCameraPath> path;  // times in frames; in the node's coordinates
  std::string look_at;                      // name of a node: moving centre of interest
  // View-dependent models with parts: parts that follow another node (at most one driver a part).
  std::vector<RawPartDriver> part_drivers;
};

// A key-frame track driving one field of one node (Parent 4.9); key times in frames. Its type
// must match the field: kRotation for rotation, kVector of the field's dimension for 3-vectors,
// kScalar (or kVector of 1) for the others.
struct RawFieldTrack {
  int node = -1;
  Field field = Field::kTranslation;
  anim::RawTrack track;
};

// SET / CHANGE (Parent 4.6), see the header comment. Rotations are given as a quaternion
// (w, x, y, z); every other field as its dimension's numbers.
struct RawAction {
  enum class Kind { kSet, kChange };
  Kind kind = Kind::kSet;
  int node = -1;
  Field field = Field::kTranslation;
  Eigen::VectorXd value;
  double from_frame = 0.0;  // SET: the frame it takes effect; CHANGE: start
  double to_frame = 0.0;    // CHANGE: end (> from_frame; equal means a jump at from_frame)
  anim::Ease ease;          // CHANGE only
};

struct RawScene {
  std::vector<std::shared_ptr<const TriMesh>> meshes;
  std::vector<std::shared_ptr<const ViewDependentModel>> models;
  std::vector<std::shared_ptr<const AnimatedViewDependentModel>> animated_models;
  std::vector<RawNode> nodes;
  std::vector<RawFieldTrack> tracks;
  std::vector<RawAction> actions;
  std::string camera;  // name of the active camera node; empty: the first camera node

  // Throws vdg::Error "WHERE: node 'NAME': ..." (or "WHERE: track 'NODE.FIELD': ...",
  // "WHERE: action I (NODE.FIELD): ...") for: no nodes or more than kMaxSceneNodes; an empty,
  // duplicate or dotted name; a parent that is not an earlier node; an object index out of range
  // or a null object; an object on a group or camera; non-finite or zero scale, a zero
  // quaternion, non-finite values; a colour outside [0, 1]; a camera's fov outside (0, 180) or a
  // negative ortho_height; a path that anim::CameraPath::build refuses; a path or look_at on a node
  // that is not a camera; look_at naming no node or the camera itself; a track or action on a
  // field its node's kind does not have (color on every drawable node: mesh, model, animated
  // model; sharpness on both model kinds; frame_offset on animated models; fov on cameras;
  // translation, rotation, scale and visible on all), of the wrong type or size, or on a field that
  // also has the other kind or a second track; a SET of a zero scale component, of a colour
  // outside [0, 1] or of a fov outside (0, 180); a track anim::Track::build refuses; non-finite
  // action frames, a CHANGE with to_frame < from_frame; more than kMaxSceneActions actions; a
  // `camera` naming no camera node; part drivers on a node that holds no model with parts, naming
  // a part the model lacks (or one part twice), or naming no node or the model node itself. A scene without cameras is
  // valid (a renderer then frames it itself).
  void validate(const std::string& where = "scene") const;
};

// One node's evaluated state at a frame.
struct NodeState {
  Eigen::Matrix4d world = Eigen::Matrix4d::Identity();   // node coordinates -> world
  Eigen::Matrix4d object = Eigen::Matrix4d::Identity();  // object coordinates -> world (world * placement)
  std::array<float, 3> color{1.0f, 1.0f, 1.0f};
  bool visible = true;  // its own and every ancestor's
  double sharpness = 0.0;
  int model_frame = 0;  // animated models: the model's frame in [0, frameCount())
  double fov_deg = 40.0;
};

class Scene {
 public:
  // Validates (RawScene::validate) and builds the tracks and camera paths. Throws vdg::Error.
  static Scene build(const RawScene& raw, const std::string& where = "scene");

  // Accessors (not per-frame): every one taking a node throws vdg::Error for an index out of range.
  int nodeCount() const;
  const std::string& nodeName(int node) const;
  int findNode(std::string_view name) const;  // -1 when there is none
  ObjectKind kind(int node) const;
  int parent(int node) const;
  int cameraNode() const;                  // the active camera; -1 when the scene has none
  const RawNode& rawNode(int node) const;  // as given (initial values)
  // The node's object, or null when it holds another kind.
  const TriMesh* mesh(int node) const;
  const ViewDependentModel* model(int node) const;
  const AnimatedViewDependentModel* animatedModel(int node) const;

  // Per-frame contract. Every node's state at `frame` into out (out.size() == nodeCount()).
  // Violations (false, nothing written): frame not finite, wrong size.
  [[nodiscard]] bool evaluate(double frame, std::span<NodeState> out) const;
  // One field's value at `frame` (after tracks and actions) into out (fieldDimension numbers).
  // Violations: node out of range, a field the node does not have, frame not finite, wrong size.
  [[nodiscard]] bool fieldValue(int node, Field field, double frame, std::span<double> out) const;
  // The active camera at `frame`, given the states evaluate() wrote for the same frame.
  // Violations: no camera node, states.size() != nodeCount(), frame not finite, a degenerate
  // camera (eye on its centre of interest, a non-invertible world transform, an up vector parallel
  // to the view and to the node's -Z, an animated fov outside (0, 180)).
  [[nodiscard]] bool camera(double frame, std::span<const NodeState> states, Camera& out) const;
  // The view direction for model node `node` seen from world point `eye`: normalize(O^-1 eye -
  // centre) with O = state.object and centre the model's centre(), in object coordinates, as
  // ViewDependentModel::weights takes it. Violations: not a model or animated-model node, a
  // non-invertible object transform, an eye at the centre or not finite.
  [[nodiscard]] bool instanceView(int node, const NodeState& state, const Eigen::Vector3d& eye,
                                  Eigen::Vector3d& out) const;
  // The eye position for model node `node` seen from world point `eye`: O^-1 eye in object
  // coordinates, as ViewDependentModel::evaluateAtEye takes it (keys at distances,
  // vdg/viewdep/key_space.h). Violations: not a model node, a non-invertible transform, a
  // non-finite eye.
  [[nodiscard]] bool instanceEye(int node, const NodeState& state, const Eigen::Vector3d& eye,
                                 Eigen::Vector3d& out) const;
  // The driving view of every part of model node `node` (a model with parts; out.size() ==
  // partCount()), as ViewDependentModel::evaluateParts takes them: a driven part's view is
  // instanceView of its driver's eye (driverEye), an undriven one the model's fixed view or else
  // instanceView of `eye` (the active camera's). Violations: not a model node with parts, the
  // wrong sizes, states not those of `frame`, an eye (or a driver's) at the instance's centre.
  [[nodiscard]] bool instancePartViews(int node, double frame, std::span<const NodeState> states,
                                       const Eigen::Vector3d& eye, std::span<Eigen::Vector3d> out) const;
  // The world eye of node `node` at `frame`: a camera's eye (on its path when it has one, as
  // camera() computes it), any other node's world origin. Violations: node out of range,
  // states.size() != nodeCount(), frame not finite, a non-invertible camera transform.
  [[nodiscard]] bool driverEye(int node, double frame, std::span<const NodeState> states, Eigen::Vector3d& out) const;

 private:
  Scene() = default;  // only build() makes a Scene, so every Scene has its data
  struct Impl;
  std::shared_ptr<const Impl> impl_;
};

}  // namespace vdg::scene
