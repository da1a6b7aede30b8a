// Edit scripts: lists of deformation operations applied to a key mesh in its key camera, as made
// by the editor or read from an EDITS.json file (`vdg deform --ops`, parsed by vdg/io/edit_script.h),
// and the per-key edit log that lets a key be rebuilt from the base and undone step by step. The
// file formats are documented, with examples, in docs/deform.md.
//
// Operations ("op"): drag, push_pull, rotate, scale (image-plane tools, Rademacher 99, 3.1.2),
// displace (Parent 4.10 attenuated vertex displacement), ffd (Sederberg-Parry lattice),
// squash_stretch and affine (Parent 4.10). Only positions change; the topology never does.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "vdg/deform/falloff.h"
#include "vdg/deform/image_plane.h"
#include "vdg/geom/camera.h"

namespace vdg {

inline constexpr int kEditsVersion = 1;

enum class EditKind { kDrag, kPushPull, kRotate, kScale, kDisplace, kFfd, kSquashStretch, kAffine };
const char* editKindName(EditKind kind);

struct FfdMove {
  std::array<int, 3> index{0, 0, 0};  // control point (i, j, k)
  Eigen::Vector3d offset = Eigen::Vector3d::Zero();
};

// One parsed operation. Only the fields of its kind are meaningful (see docs/deform.md).
struct EditOp {
  EditKind kind = EditKind::kDrag;
  std::string json;  // the operation as canonical JSON (what the edit log stores)

  // Picked-vertex tools (drag, push_pull, rotate, scale, displace).
  std::int64_t vertex = -1;
  DistanceMetric metric = DistanceMetric::kEuclidean;
  Falloff falloff;
  Eigen::Vector2d delta = Eigen::Vector2d::Zero();  // drag: world units along camera right, up
  std::optional<Eigen::Vector2d> delta_px;          // drag: pixels (x right, y down) instead
  double amount = 0;                                // push_pull: world units, > 0 pushes away
  PushPullMode push_mode = PushPullMode::kAlongRay;
  double angle_deg = 0;                              // rotate: counter-clockwise in the image
  Eigen::Vector2d factor = Eigen::Vector2d::Ones();  // scale: along camera right, up
  Eigen::Vector3d offset = Eigen::Vector3d::Zero();  // displace: world units

  // Whole-mesh tools (ffd, squash_stretch, affine): the vertices they act on (empty = all).
  std::vector<std::int32_t> vertices;
  bool camera_frame = true;  // ffd lattice / offsets / squash axis in the camera's frame
  std::array<int, 3> degree{1, 1, 1};
  double padding = 0.05;
  std::vector<FfdMove> moves;
  Eigen::Vector3d axis = Eigen::Vector3d::UnitY();  // squash_stretch (in camera frame if camera_frame)
  double stretch = 1.0;
  bool preserve_volume = true;
  Eigen::Matrix3d matrix = Eigen::Matrix3d::Identity();  // affine
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();
  std::optional<Eigen::Vector3d> center;  // squash_stretch / affine; default: the vertices' centroid
};

struct EditScript {
  std::optional<Camera> camera;                  // key camera for a new key
  std::optional<Eigen::Vector3d> view;           // or a view direction (model space, towards the eye)
  std::optional<std::array<int, 2>> image_size;  // width, height: needed by delta_px
  std::vector<EditOp> ops;
};

// Checks every vertex index against `vertex_count`; throws vdg::Error naming the op and field.
void validateEdits(std::span<const EditOp> ops, std::size_t vertex_count, const std::string& source);

struct EditReport {
  std::size_t moved = 0;        // vertices that moved
  double max_displacement = 0;  // largest vertex motion, world units
};

// Applies `ops` in order to `positions` (#V x 3, in place) with `camera` as the key camera;
// `image_size` is required by ops with delta_px. Returns one report per op. Throws vdg::Error (and
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
