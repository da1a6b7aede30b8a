// Rig — an animated, morphed, skinned triangle mesh: glTF 2.0's data model without the file format.
//
// RawRig is plain data (what a glTF reader or a generator fills in), checked by validate();
// Rig::build turns it into an immutable run-time object whose evaluate() poses the mesh at any
// time of any animation, allocation-free.
//
// The formulas are those of the glTF 2.0 specification (Khronos, sections 3.5 "Nodes and
// hierarchy", 3.7.2 "Morph targets", 3.7.3 "Skins" and 3.11 "Animations", and Appendix C
// "Interpolation"):
//   node local matrix  L = T * R * S (or the node's matrix), world W = W_parent * L;
//   morph              p = p_base + sum_i w_i * d_i        (the same for normals);
//   skinning (LBS)     p' = sum_k w_k * (W_joint(k) * IBM_k) * p, with the mesh node's own
//                      transform ignored; an unskinned mesh is placed by its node's world matrix;
//   samplers           clamped at both ends; STEP holds the earlier keyframe; LINEAR lerps (slerp
//                      along the shortest arc for rotations); CUBICSPLINE is the cubic Hermite
//                      spline with tangents scaled by the keyframe interval; rotations are
//                      normalised after interpolation.
// Units: times in seconds, lengths in the file's units (metres by glTF's convention).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "vdg/geom/tri_mesh.h"

namespace vdg {

// Limits validate() enforces, far above any real character yet small enough that a hostile file
// cannot make vdg reserve absurd memory or time from a count.
inline constexpr std::size_t kMaxRigNodes = 100'000;
inline constexpr std::size_t kMaxRigJoints = 65'536;  // JOINTS_0 may be u16
inline constexpr std::size_t kMaxMorphTargets = 1'024;
inline constexpr std::size_t kMaxRigAnimations = 10'000;
inline constexpr std::size_t kMaxRigKeyframes = 50'000'000;  // all samplers of all animations together

struct RigNode {
  std::string name;
  int parent = -1;  // index into RawRig::nodes, -1 for a root
  // Rest transform: `matrix` (column-major 4x4, affine) when set, else T * R * S. A node with a
  // matrix cannot be the target of a translation, rotation or scale channel (glTF 3.11).
  std::optional<Eigen::Matrix4d> matrix;
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();
  Eigen::Quaterniond rotation = Eigen::Quaterniond::Identity();  // any finite non-zero length; normalised by build
  Eigen::Vector3d scale = Eigen::Vector3d::Ones();
};

struct RigSkin {
  std::vector<int> joints;                    // node indices, at most kMaxRigJoints
  std::vector<Eigen::Matrix4d> inverse_bind;  // one per joint (identity when the file has none)
};

enum class RigPath { kTranslation, kRotation, kScale, kWeights };
enum class RigInterpolation { kStep, kLinear, kCubicSpline };
const char* rigPathName(RigPath path);                    // "translation", ... (glTF's names)
const char* rigInterpolationName(RigInterpolation mode);  // "STEP", "LINEAR", "CUBICSPLINE"

struct RigSampler {
  RigInterpolation interpolation = RigInterpolation::kLinear;
  std::vector<float> input;  // keyframe times (s): finite, >= 0, strictly increasing, at least one
  // Keyframe values, width W per value (3 translation/scale, 4 rotation as x y z w, the morph
  // target count for weights): #K x W, or #K x 3 x W for CUBICSPLINE (in-tangent, value,
  // out-tangent per keyframe, glTF Appendix C).
  std::vector<float> output;
};

struct RigChannel {
  int node = 0;
  RigPath path = RigPath::kTranslation;
  int sampler = 0;  // index into its animation's samplers
};

struct RigAnimation {
  std::string name;
  std::vector<RigSampler> samplers;
  std::vector<RigChannel> channels;
};

struct RawRig {
  std::string source;  // file name in messages (may be empty)
  std::vector<RigNode> nodes;
  // The node that instances the mesh: its world matrix places an unskinned mesh and its weights
  // channels animate the morph weights. -1: no node (identity placement, no weights channels).
  int mesh_node = -1;
  // Rest (bind) positions and triangles; uvs (TEXCOORD_0) are per vertex: uv_triangles equals
  // triangles when present.
  TriMesh mesh;
  std::vector<float> normals;  // empty or #V x 3 (NORMAL); empty: evaluate() derives them
  // Morph targets: per target, position deltas #V x 3 and normal deltas (empty or #V x 3).
  std::vector<std::vector<float>> target_positions;
  std::vector<std::vector<float>> target_normals;
  std::vector<std::string> target_names;  // empty or one per target (mesh.extras.targetNames)
  std::vector<double> default_weights;    // one per target
  std::optional<RigSkin> skin;
  std::vector<std::uint16_t> joints;  // with a skin: #V x 4 indices into skin->joints (JOINTS_0)
  std::vector<float> weights;         // with a skin: #V x 4, finite, >= 0, each row sum > 0 (WEIGHTS_0)
  std::vector<RigAnimation> animations;

  // Throws vdg::Error "SOURCE: ELEMENT: what" (ELEMENT as glTF names it: "nodes[3]",
  // "animations[0]: samplers[2]", "mesh: vertex 12") for: more nodes, joints, targets,
  // animations or keyframes than the limits above; a parent index out of range or a cycle in the
  // hierarchy; non-finite or zero-length transforms; a mesh that fails validateMesh or has no
  // triangles; normals, uvs, target or weight arrays of the wrong size or with non-finite values;
  // joint indices out of range, negative weights or a zero weight sum; joints/weights without a
  // skin; a sampler whose times are not finite, negative or not strictly increasing, or whose
  // output size does not match; a channel whose node or sampler is out of range, a TRS channel on
  // a node given by a matrix, a weights channel on a node other than mesh_node or on a mesh
  // without targets.
  void validate() const;
};

class Rig {
 public:
  // validate(), then precomputes the node order, normalised rotations and weights. Throws as
  // validate() does.
  static Rig build(const RawRig& raw);

  const TriMesh& mesh() const { return mesh_; }  // rest (bind) positions, triangles, uvs
  std::size_t vertexCount() const { return mesh_.vertexCount(); }
  bool skinned() const { return skinned_; }
  std::size_t targetCount() const { return target_positions_.size(); }
  std::size_t animationCount() const { return animations_.size(); }
  // By animation index (tools, not per-frame): out of range throws vdg::Error
  // "animation A out of range (the rig has N animations)". duration(-1) is 0 (the rest pose).
  const std::string& animationName(int animation) const;
  double duration(int animation) const;  // the largest keyframe time of its samplers

  // Posed mesh at `time` seconds of animation `animation` (-1 = rest pose, no animation): morph
  // targets, then skinning (or the mesh node's world transform when unskinned).
  // out_positions #V x 3; out_normals empty or #V x 3 (the file's normals morphed and transformed
  // by the inverse transpose, normalised; without normals in the file, area-weighted normals of
  // the posed positions); out_skin empty or #V x 9 = the linear (upper-left 3x3, COLUMN-major)
  // part of each vertex's blended skinning matrix sum_k w_k * (jointWorld_k * inverseBind_k)
  // (for an unskinned mesh: the mesh node's world 3x3).
  //
  // Per-frame contract (the rule of every vdg evaluation function, after ozz-animation's jobs):
  // sizes, indices and values are checked on entry; on a violation it returns false and has
  // written nothing; it never throws and never allocates. Violations: animation < -1 or >=
  // animationCount(), a non-finite time, out_positions.size() != 3 * vertexCount(), out_normals
  // neither empty nor 3 * vertexCount(), out_skin neither empty nor 9 * vertexCount().
  // Times outside [0, duration] are clamped per sampler (glTF).
  // NOT thread-safe: the joint matrices and morph weights are kept in scratch owned by the Rig
  // (sized by build), so one Rig serves one evaluate() at a time; copy the Rig per thread.
  [[nodiscard]] bool evaluate(int animation, double time, std::span<float> out_positions,
                              std::span<float> out_normals = {}, std::span<float> out_skin = {}) const;

  // The local transform of every node at `time` of `animation` (-1 = rest pose), as the channels
  // set it (for re-sampling an animation, e.g. glTF export): out is nodeCount() x 10 = translation
  // (3), rotation (x y z w, normalised), scale (3). A node given by a matrix writes its (unused)
  // identity TRS. Same contract as evaluate() (false and nothing written on a bad animation, a
  // non-finite time or out.size() != 10 * nodeCount(); no allocation; not thread-safe).
  std::size_t nodeCount() const { return nodes_.size(); }
  [[nodiscard]] bool nodePose(int animation, double time, std::span<double> out) const;

 private:
  void pose(int animation, double time) const;
  struct Node {
    int parent = -1;
    bool has_matrix = false;
    Eigen::Matrix4d matrix = Eigen::Matrix4d::Identity();
    Eigen::Vector3d translation = Eigen::Vector3d::Zero();
    Eigen::Quaterniond rotation = Eigen::Quaterniond::Identity();
    Eigen::Vector3d scale = Eigen::Vector3d::Ones();
  };
  struct Animation {
    std::string name;
    std::vector<RigSampler> samplers;
    std::vector<RigChannel> channels;
    double duration = 0;
  };
  void sampleChannel(const RigSampler& sampler, RigPath path, double time, double* out, int width) const;

  TriMesh mesh_;
  std::vector<float> normals_;
  std::vector<std::vector<float>> target_positions_, target_normals_;
  std::vector<double> default_weights_;
  std::vector<Node> nodes_;
  std::vector<int> order_;  // parents before children
  int mesh_node_ = -1;
  bool skinned_ = false;
  std::vector<int> joints_;
  std::vector<Eigen::Matrix4d> inverse_bind_;
  std::vector<std::uint16_t> vertex_joints_;
  std::vector<float> vertex_weights_;  // normalised to sum 1 per vertex
  std::vector<Animation> animations_;

  // Scratch for evaluate() (see its thread-safety note), sized by build().
  mutable std::vector<Node> pose_;
  mutable std::vector<Eigen::Matrix4d> world_;
  mutable std::vector<Eigen::Matrix4d> joint_matrices_;
  mutable std::vector<double> morph_weights_;
  mutable std::vector<double> sample_;  // one sampled value (width <= max(4, targets))
};

}  // namespace vdg
