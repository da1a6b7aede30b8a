// Edit scripts: lists of deformation operations applied to a key mesh in its key camera, as made
// by the editor or read from an EDITS.json file (`vdg deform --ops`, parsed by vdg/io/edit_script.h),
// and the per-key edit log that lets a key be rebuilt from the base and undone step by step. The
// file formats are documented, with examples, in docs/deform.md.
//
// Operations ("op"): drag, push_pull, rotate, scale (image-plane tools, Rademacher 99, 3.1.2),
// displace (Parent 4.10 attenuated vertex displacement), ffd (Sederberg-Parry lattice),
// squash_stretch and affine (Parent 4.10), skeleton (Burtnyk and Wein's wire deformation, Parent
// 4.10; vdg/deform/skeleton.h), lines (Beier and Neely's feature-line warp lifted to 3D,
// vdg/deform/feature_lines.h). Only positions change; the topology never does.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <variant>
#include <vector>

#include <Eigen/Core>

#include "vdg/deform/falloff.h"
#include "vdg/deform/feature_lines.h"
#include "vdg/deform/image_plane.h"
#include "vdg/deform/skeleton.h"
#include "vdg/geom/camera.h"

namespace vdg {

inline constexpr int kEditsVersion = 1;

enum class EditKind { kDrag, kPushPull, kRotate, kScale, kDisplace, kFfd, kSquashStretch, kAffine, kSkeleton, kLines };
// "drag", "push_pull", ... : the "op" field of the JSON form.
const char* editKindName(EditKind kind);

// The picked (seed) vertex of the image-plane tools and the region it drags along: vertices whose
// distance (`metric`) from it is below `falloff.radius` move by falloffWeight() of the full edit.
// Instead of an index, the seed may be named by a model-space `point` (the nearest vertex) or by a
// `pixel` of the key camera's image of the script's image_size (the vertex seen there), both found
// on the mesh as it is before the op (vdg/deform/pick.h); `vertex` is then ignored. At most one.
struct VertexPick {
  std::int32_t vertex = 0;  // index into the mesh, < #V
  DistanceMetric metric = DistanceMetric::kEuclidean;
  Falloff falloff;                       // radius > 0 and finite; power >= 0 and finite
  std::optional<Eigen::Vector3d> point;  // model space: the nearest vertex
  std::optional<Eigen::Vector2d> pixel;  // x right, y down: the vertex the pixel's ray hits first
};

// Image-plane drag (Rademacher 99, 3.1.2): the picked vertex moves by `delta` (world units along
// the camera's right and up axes), or by `delta_px` pixels (x right, y down) of an image of the
// script's image_size, converted at the picked vertex's depth. Vertices keep their view depth.
struct DragOp {
  VertexPick pick;
  Eigen::Vector2d delta = Eigen::Vector2d::Zero();
  std::optional<Eigen::Vector2d> delta_px;  // when set, replaces `delta`
};
// View-depth change by w * amount (world units, > 0 away from the camera), along each vertex's ray
// from the eye (kAlongRay: it keeps its pixel) or along the view axis.
struct PushPullOp {
  VertexPick pick;
  double amount = 0;
  PushPullMode mode = PushPullMode::kAlongRay;
};
// Rotation by angle_deg (counter-clockwise in the image) about the view-axis line through the
// picked vertex. A rigid group by default: pick.falloff.power = 0.
struct RotateOp {
  VertexPick pick{0, DistanceMetric::kEuclidean, Falloff{1.0, 0.0, FalloffShape::kPower}, std::nullopt, std::nullopt};
  double angle_deg = 0;
};
// Scaling by `factor` (> 0, along camera right and up) about the picked vertex, parallel to the
// image plane. A rigid group by default.
struct ScaleOp {
  VertexPick pick{0, DistanceMetric::kEuclidean, Falloff{1.0, 0.0, FalloffShape::kPower}, std::nullopt, std::nullopt};
  Eigen::Vector2d factor = Eigen::Vector2d::Ones();
};
// Attenuated displacement (Parent 4.10): every vertex moves by w * offset (world units, in the
// world frame, or in the camera's right/up/back frame when camera_frame).
struct DisplaceOp {
  VertexPick pick;
  Eigen::Vector3d offset = Eigen::Vector3d::Zero();
  bool camera_frame = false;
};

struct FfdMove {
  std::array<int, 3> index{0, 0, 0};                 // control point (i, j, k), each in [0, degree]
  Eigen::Vector3d offset = Eigen::Vector3d::Zero();  // in the lattice frame, world units
};
// Sederberg-Parry free-form deformation: a Bernstein lattice of `degree` (each 1..16) around
// `vertices` (empty: all) padded by `padding` (>= 0, fraction of the extent per side), aligned
// with the camera's axes (camera_frame) or the world's; `moves` displace control points.
inline constexpr int kMaxFfdDegree = 16;        // as makeFfdLattice (vdg/deform/ffd.h) allows
inline constexpr double kMaxFfdPadding = 10.0;  // ten extents per side is already far beyond use
struct FfdOp {
  std::vector<std::int32_t> vertices;
  bool camera_frame = true;
  std::array<int, 3> degree{1, 1, 1};
  double padding = 0.05;
  std::vector<FfdMove> moves;
};
// Squash and stretch (Parent 4.10): `factor` (> 0) along `axis` (non-zero; in the camera's
// right/up/back frame when camera_frame, else world), 1/sqrt(factor) across it when
// preserve_volume, about `center` (default: the vertices' centroid).
struct SquashStretchOp {
  std::vector<std::int32_t> vertices;
  Eigen::Vector3d axis = Eigen::Vector3d::UnitY();
  bool camera_frame = true;
  double factor = 1.0;
  bool preserve_volume = true;
  std::optional<Eigen::Vector3d> center;
};
// p' = center + matrix (p - center) + translation (world frame; center default: the centroid).
struct AffineOp {
  std::vector<std::int32_t> vertices;
  Eigen::Matrix3d matrix = Eigen::Matrix3d::Identity();
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();
  std::optional<Eigen::Vector3d> center;
};

// Skeleton (wire) deformation (Burtnyk and Wein, Parent 4.10; vdg/deform/skeleton.h): the wire
// `rest` (model coordinates, drawn through the mesh as it is before this op) is moved to `posed`
// (the same number of joints), and `vertices` (empty: all) follow it. With `falloff` the motion
// fades out with the distance from the rest wire (falloff.radius in model units).
struct SkeletonOp {
  std::vector<std::int32_t> vertices;
  std::vector<Eigen::Vector3d> rest;   // 2..kMaxSkeletonJoints joints, checkSkeletonWire
  std::vector<Eigen::Vector3d> posed;  // rest.size() joints, checkSkeletonWire
  std::optional<Falloff> falloff;
};

// Deformation from feature lines (vdg/deform/feature_lines.h): line pairs in pixels of the
// script's image_size (model side "src", drawing side "dst", as `vdg morph --lines` files), the
// weight parameters and the falloff. Every vertex near the model-side lines moves across the image
// plane at its own depth. Needs "image_size".
struct LinesOp {
  std::vector<FeatureLinePair> pairs;
  FeatureLineSettings settings;
};

// One operation: plain data, built in C++ or read from JSON by vdg/io/edit_script.h, which holds
// the one conversion to and from the JSON form. The alternatives are in EditKind's order.
using EditOp = std::variant<DragOp, PushPullOp, RotateOp, ScaleOp, DisplaceOp, FfdOp, SquashStretchOp, AffineOp,
                            SkeletonOp, LinesOp>;

inline EditKind editKind(const EditOp& op) { return static_cast<EditKind>(op.index()); }
inline const char* editKindName(const EditOp& op) { return editKindName(editKind(op)); }

// A value of an op outside its range: `field` is the key path inside the op as the JSON form
// writes it ("'radius'", "'moves'[1].'index'"), `message` says what is wrong ("must be > 0, got
// -1"). Vertex indices are checked against a mesh by validateEdits() only.
struct EditOpProblem {
  std::string field;
  std::string message;
};
// The first value of `op` out of its documented range (radius, power, factors, degree, indices,
// finite numbers), or nothing. The JSON reader and validateEdits() both use it: one set of rules.
std::optional<EditOpProblem> checkEditOp(const EditOp& op);

struct EditScript {
  std::optional<Camera> camera;                  // key camera for a new key
  std::optional<Eigen::Vector3d> view;           // or a view direction (model space, towards the eye)
  std::optional<std::array<int, 2>> image_size;  // width, height: needed by delta_px
  std::vector<EditOp> ops;
};

// Checks every op (checkEditOp) and every vertex index against `vertex_count`; throws vdg::Error
// "SOURCE: 'ops'[1] (drag).'vertex': 99 is out of range (the mesh has 25 vertices)".
void validateEdits(std::span<const EditOp> ops, std::size_t vertex_count, const std::string& source);

struct EditReport {
  std::size_t moved = 0;        // vertices that moved
  double max_displacement = 0;  // largest vertex motion, world units
};

// Applies `ops` in order to `positions` (#V x 3, in place) with `camera` as the key camera;
// `image_size` is required by ops with delta_px or a pick's pixel. A pick's point or pixel is
// resolved to a vertex on the positions as they are before its op; a pixel that sees no front face
// of the mesh is an error naming the op. Returns one report per op. Throws vdg::Error (and
// leaves `positions` partly edited: callers edit a copy) for an invalid op.
std::vector<EditReport> applyEdits(const Camera& camera, std::span<const std::int32_t> triangles,
                                   std::span<float> positions, std::span<const EditOp> ops,
                                   const std::optional<std::array<int, 2>>& image_size = std::nullopt,
                                   const std::string& source = "edits");

// A camera for a key known only by its view direction: a parallel camera looking at `center` from
// `view` (unit, towards the eye), `distance` away, with Y up (Z up when the view is vertical), and
// ortho height `height`.
Camera cameraFromView(const Eigen::Vector3d& center, const Eigen::Vector3d& view, double distance, double height);

// The edit log of a key: KEY.edits.json beside the key mesh. `origin` is "base" when the key was
// made from the base, else the path (relative to the log) of a snapshot of the key mesh as it was
// before its first logged edit. Each entry is one `vdg deform` run (or one editor edit): the camera
// it used and its operations; replaying the entries in order from the origin rebuilds the key.
struct EditLogEntry {
  Camera camera;
  std::optional<std::array<int, 2>> image_size;
  std::vector<EditOp> ops;
};
struct EditLog {
  std::string key;
  std::string origin = "base";
  std::vector<EditLogEntry> entries;
};

}  // namespace vdg
