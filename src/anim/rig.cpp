// Rig: glTF 2.0 nodes, morph targets, linear blend skinning and animation samplers.
// Formulas: glTF 2.0 specification (Khronos), 3.5 (node transforms T * R * S, world = parent *
// local), 3.7.2 (morph targets), 3.7.3 (skins: joint matrix = jointWorld * inverseBind), 3.11 and
// Appendix C (STEP / LINEAR / CUBICSPLINE interpolation, slerp for rotations).
#include "vdg/anim/rig.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "vdg/geom/error.h"

namespace vdg {
namespace {

std::string prefix(const RawRig& raw) { return raw.source.empty() ? std::string() : raw.source + ": "; }

bool allFinite(const std::vector<float>& values) {
  return std::all_of(values.begin(), values.end(), [](float v) { return std::isfinite(v); });
}

template <typename M>
bool allFinite(const Eigen::MatrixBase<M>& m) {
  return m.allFinite();
}

int pathWidth(RigPath path, std::size_t targets) {
  switch (path) {
    case RigPath::kTranslation:
    case RigPath::kScale:
      return 3;
    case RigPath::kRotation:
      return 4;
    case RigPath::kWeights:
      return static_cast<int>(targets);
  }
  return 0;
}

// A finite, non-zero quaternion as a unit one (the sum of squares computed without overflow).
Eigen::Quaterniond normalisedQuaternion(const Eigen::Quaterniond& q) {
  const double m = q.coeffs().cwiseAbs().maxCoeff();
  if (!(m > 0) || !std::isfinite(m)) return Eigen::Quaterniond::Identity();
  Eigen::Vector4d c = q.coeffs() / m;
  c.normalize();
  return Eigen::Quaterniond(c[3], c[0], c[1], c[2]);
}

Eigen::Matrix4d localMatrix(const Eigen::Vector3d& t, const Eigen::Quaterniond& r, const Eigen::Vector3d& s) {
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  m.topLeftCorner<3, 3>() = r.toRotationMatrix() * s.asDiagonal();
  m.topRightCorner<3, 1>() = t;
  return m;
}

// Cofactor matrix of `a` times the sign of its determinant: the inverse transpose up to a positive
// scale, defined for singular matrices too (normals are normalised afterwards).
Eigen::Matrix3d normalMatrix(const Eigen::Matrix3d& a) {
  Eigen::Matrix3d c;
  c.col(0) = a.col(1).cross(a.col(2));
  c.col(1) = a.col(2).cross(a.col(0));
  c.col(2) = a.col(0).cross(a.col(1));
  const double det = a.col(0).dot(c.col(0));
  return det < 0 ? Eigen::Matrix3d(-c) : c;
}

}  // namespace

const char* rigPathName(RigPath path) {
  switch (path) {
    case RigPath::kTranslation:
      return "translation";
    case RigPath::kRotation:
      return "rotation";
    case RigPath::kScale:
      return "scale";
    case RigPath::kWeights:
      return "weights";
  }
  return "?";
}

const char* rigInterpolationName(RigInterpolation mode) {
  switch (mode) {
    case RigInterpolation::kStep:
      return "STEP";
    case RigInterpolation::kLinear:
      return "LINEAR";
    case RigInterpolation::kCubicSpline:
      return "CUBICSPLINE";
  }
  return "?";
}

namespace {

// Throws vdg::Error with the rig's prefix ("FILE: ") before `what`.
struct RigFail {
  std::string prefix;
  [[noreturn]] void operator()(const std::string& what) const { throw Error(prefix + what); }
};

// The node hierarchy: parents in range, no cycle, transforms finite; the mesh node in range.
void checkRigNodes(const RawRig& r, const RigFail& fail) {
  const std::size_t n = r.nodes.size();
  if (n > kMaxRigNodes)
    fail("nodes: " + std::to_string(n) + " nodes, more than the limit of " + std::to_string(kMaxRigNodes));
  for (std::size_t i = 0; i < n; ++i) {
    const RigNode& node = r.nodes[i];
    const std::string e = "nodes[" + std::to_string(i) + "]: ";
    if (node.parent < -1 || node.parent >= static_cast<long>(n))
      fail(e + "parent " + std::to_string(node.parent) + " out of range (the rig has " + std::to_string(n) + " nodes)");
    if (node.matrix) {
      if (!allFinite(*node.matrix)) fail(e + "matrix has a non-finite element");
      if (node.matrix->row(3) != Eigen::RowVector4d(0, 0, 0, 1)) fail(e + "matrix is not affine (last row 0 0 0 1)");
    } else {
      if (!allFinite(node.translation)) fail(e + "translation is not finite");
      if (!allFinite(node.scale)) fail(e + "scale is not finite");
      if (!allFinite(node.rotation.coeffs())) fail(e + "rotation is not finite");
      if (node.rotation.coeffs().cwiseAbs().maxCoeff() == 0) fail(e + "rotation is the zero quaternion");
    }
  }
  // Cycles: follow each node's parents; a chain longer than the node count revisits a node.
  // Colouring (0 unseen, 1 on the current chain, 2 known to reach a root) keeps it O(n).
  std::vector<char> state(n, 0);
  for (std::size_t i = 0; i < n; ++i) {
    std::size_t j = i;
    while (state[j] == 0) {
      state[j] = 1;
      if (r.nodes[j].parent < 0) break;
      j = static_cast<std::size_t>(r.nodes[j].parent);
      if (state[j] == 1) fail("nodes[" + std::to_string(j) + "]: is its own ancestor (the node hierarchy has a cycle)");
    }
    for (std::size_t k = i; state[k] == 1;) {
      state[k] = 2;
      if (r.nodes[k].parent < 0) break;
      k = static_cast<std::size_t>(r.nodes[k].parent);
    }
  }
  if (r.mesh_node < -1 || r.mesh_node >= static_cast<long>(n))
    fail("mesh node " + std::to_string(r.mesh_node) + " out of range (the rig has " + std::to_string(n) + " nodes)");
}

// The mesh, its normals and texture coordinates, and its morph targets.
void checkRigMesh(const RawRig& r, const RigFail& fail) {
  const std::string& p = fail.prefix;
  if (r.mesh.triangles.empty()) fail("mesh: has no triangles");
  validateMesh(r.mesh, p.empty() ? std::string("mesh") : p + "mesh");
  const std::size_t nv = r.mesh.vertexCount();
  // Texture coordinates per corner (validateMesh checks uv_triangles): a vdg export read back keeps
  // the uvs of its split seam vertices while its vertices are welded (docs/gltf-export.md).
  if (!r.mesh.uvs.empty() && r.mesh.uv_triangles.size() != r.mesh.triangles.size())
    fail("mesh: TEXCOORD_0 must have one coordinate pair per triangle corner");
  if (!allFinite(r.mesh.uvs)) fail("mesh: TEXCOORD_0 has a non-finite value");
  if (!r.normals.empty() && r.normals.size() != 3 * nv)
    fail("mesh: NORMAL has " + std::to_string(r.normals.size() / 3) + " entries for " + std::to_string(nv) +
         " vertices");
  if (!allFinite(r.normals)) fail("mesh: NORMAL has a non-finite value");

  const std::size_t nt = r.target_positions.size();
  if (nt > kMaxMorphTargets)
    fail("mesh: " + std::to_string(nt) + " morph targets, more than the limit of " + std::to_string(kMaxMorphTargets));
  if (r.target_normals.size() != nt)
    fail("mesh: target normals given for " + std::to_string(r.target_normals.size()) + " of " + std::to_string(nt) +
         " targets");
  if (!r.target_names.empty() && r.target_names.size() != nt)
    fail("mesh: " + std::to_string(r.target_names.size()) + " target names for " + std::to_string(nt) + " targets");
  if (r.default_weights.size() != nt)
    fail("mesh: " + std::to_string(r.default_weights.size()) + " default weights for " + std::to_string(nt) +
         " targets");
  for (std::size_t t = 0; t < nt; ++t) {
    const std::string e = "mesh: targets[" + std::to_string(t) + "]: ";
    if (r.target_positions[t].size() != 3 * nv)
      fail(e + "POSITION has " + std::to_string(r.target_positions[t].size() / 3) + " entries for " +
           std::to_string(nv) + " vertices");
    if (!allFinite(r.target_positions[t])) fail(e + "POSITION has a non-finite value");
    if (!r.target_normals[t].empty() && (r.normals.empty() || r.target_normals[t].size() != 3 * nv))
      fail(e + "NORMAL must have one entry per vertex, and the mesh must have normals");
    if (!allFinite(r.target_normals[t])) fail(e + "NORMAL has a non-finite value");
    if (!std::isfinite(r.default_weights[t])) fail(e + "default weight is not finite");
  }
}

// The skin (when there is one) and the vertices' joints and weights.
void checkRigSkin(const RawRig& r, const RigFail& fail) {
  const std::size_t n = r.nodes.size();
  const std::size_t nv = r.mesh.vertexCount();
  if (!r.skin) {
    if (!r.joints.empty() || !r.weights.empty()) fail("mesh: JOINTS_0 / WEIGHTS_0 without a skin");
  } else {
    const std::size_t nj = r.skin->joints.size();
    if (nj == 0) fail("skin: has no joints");
    if (nj > kMaxRigJoints)
      fail("skin: " + std::to_string(nj) + " joints, more than the limit of " + std::to_string(kMaxRigJoints));
    for (std::size_t j = 0; j < nj; ++j)
      if (r.skin->joints[j] < 0 || r.skin->joints[j] >= static_cast<long>(n))
        fail("skin: joints[" + std::to_string(j) + "]: node " + std::to_string(r.skin->joints[j]) +
             " out of range (the rig has " + std::to_string(n) + " nodes)");
    if (r.skin->inverse_bind.size() != nj)
      fail("skin: " + std::to_string(r.skin->inverse_bind.size()) + " inverse bind matrices for " + std::to_string(nj) +
           " joints");
    for (std::size_t j = 0; j < nj; ++j)
      if (!allFinite(r.skin->inverse_bind[j]))
        fail("skin: inverseBindMatrices[" + std::to_string(j) + "] has a non-finite element");
    if (r.joints.size() != 4 * nv)
      fail("mesh: JOINTS_0 has " + std::to_string(r.joints.size() / 4) + " entries for " + std::to_string(nv) +
           " vertices");
    if (r.weights.size() != 4 * nv)
      fail("mesh: WEIGHTS_0 has " + std::to_string(r.weights.size() / 4) + " entries for " + std::to_string(nv) +
           " vertices");
    for (std::size_t v = 0; v < nv; ++v) {
      double sum = 0;
      for (std::size_t k = 0; k < 4; ++k) {
        const float w = r.weights[4 * v + k];
        if (!std::isfinite(w) || w < 0)
          fail("mesh: vertex " + std::to_string(v) + ": skin weight " + std::to_string(w) +
               " is negative or not finite");
        if (w > 0 && r.joints[4 * v + k] >= nj)
          fail("mesh: vertex " + std::to_string(v) + ": joint " + std::to_string(r.joints[4 * v + k]) +
               " out of range (the skin has " + std::to_string(nj) + " joints)");
        sum += w;
      }
      if (!(sum > 0)) fail("mesh: vertex " + std::to_string(v) + ": skin weights sum to 0");
    }
  }
}

// The animations: channels (node, sampler, path) and samplers (times, output sizes).
void checkRigAnimations(const RawRig& r, const RigFail& fail) {
  const std::size_t n = r.nodes.size();
  const std::size_t nt = r.target_positions.size();
  if (r.animations.size() > kMaxRigAnimations)
    fail("animations: " + std::to_string(r.animations.size()) + " animations, more than the limit of " +
         std::to_string(kMaxRigAnimations));
  std::size_t keyframes = 0;
  for (std::size_t a = 0; a < r.animations.size(); ++a) {
    const RigAnimation& anim = r.animations[a];
    const std::string ea = "animations[" + std::to_string(a) + "]: ";
    std::vector<int> width(anim.samplers.size(), -1);  // -1: not used by a channel
    for (std::size_t c = 0; c < anim.channels.size(); ++c) {
      const RigChannel& ch = anim.channels[c];
      const std::string e = ea + "channels[" + std::to_string(c) + "]: ";
      if (ch.node < 0 || ch.node >= static_cast<long>(n))
        fail(e + "node " + std::to_string(ch.node) + " out of range (the rig has " + std::to_string(n) + " nodes)");
      if (ch.sampler < 0 || static_cast<std::size_t>(ch.sampler) >= anim.samplers.size())
        fail(e + "sampler " + std::to_string(ch.sampler) + " out of range (the animation has " +
             std::to_string(anim.samplers.size()) + ")");
      if (ch.path == RigPath::kWeights) {
        if (ch.node != r.mesh_node) fail(e + "weights of node " + std::to_string(ch.node) + ", not the mesh's node");
        if (nt == 0) fail(e + "weights of a mesh without morph targets");
      } else if (r.nodes[static_cast<std::size_t>(ch.node)].matrix) {
        fail(e + std::string(rigPathName(ch.path)) + " of node " + std::to_string(ch.node) +
             ", which is given by a matrix");
      }
      const int w = pathWidth(ch.path, nt);
      int& sw = width[static_cast<std::size_t>(ch.sampler)];
      if (sw != -1 && sw != w)
        fail(e + "sampler " + std::to_string(ch.sampler) + " is shared by channels of different widths");
      sw = w;
    }
    for (std::size_t s = 0; s < anim.samplers.size(); ++s) {
      const RigSampler& sampler = anim.samplers[s];
      const std::string e = ea + "samplers[" + std::to_string(s) + "]: ";
      keyframes += sampler.input.size();
      if (keyframes > kMaxRigKeyframes)
        fail(e + "more than " + std::to_string(kMaxRigKeyframes) + " keyframes in all animations");
      if (sampler.input.empty()) fail(e + "has no keyframes");
      for (std::size_t k = 0; k < sampler.input.size(); ++k) {
        const float t = sampler.input[k];
        if (!std::isfinite(t) || t < 0)
          fail(e + "input[" + std::to_string(k) + "]: time " + std::to_string(t) + " is negative or not finite");
        if (k > 0 && !(t > sampler.input[k - 1]))
          fail(e + "input[" + std::to_string(k) + "]: times must increase strictly");
      }
      if (!allFinite(sampler.output)) fail(e + "output has a non-finite value");
      if (width[s] < 0) continue;
      const std::size_t per_key =
          static_cast<std::size_t>(width[s]) * (sampler.interpolation == RigInterpolation::kCubicSpline ? 3 : 1);
      if (sampler.output.size() != sampler.input.size() * per_key)
        fail(e + "output has " + std::to_string(sampler.output.size()) + " values, expected " +
             std::to_string(sampler.input.size()) + " keyframes x " + std::to_string(per_key));
    }
  }
}

}  // namespace

void RawRig::validate() const {
  const RigFail fail{prefix(*this)};
  checkRigNodes(*this, fail);
  checkRigMesh(*this, fail);
  checkRigSkin(*this, fail);
  checkRigAnimations(*this, fail);
}

Rig Rig::build(const RawRig& raw) {
  raw.validate();
  Rig rig;
  rig.mesh_ = raw.mesh;
  rig.normals_ = raw.normals;
  rig.target_positions_ = raw.target_positions;
  rig.target_normals_ = raw.target_normals;
  rig.default_weights_ = raw.default_weights;
  rig.mesh_node_ = raw.mesh_node;
  rig.nodes_.resize(raw.nodes.size());
  for (std::size_t i = 0; i < raw.nodes.size(); ++i) {
    const RigNode& in = raw.nodes[i];
    Node& node = rig.nodes_[i];
    node.parent = in.parent;
    node.has_matrix = in.matrix.has_value();
    if (in.matrix) node.matrix = *in.matrix;
    node.translation = in.translation;
    node.rotation = normalisedQuaternion(in.rotation);
    node.scale = in.scale;
  }
  // Parents before children: depth first from each root (the hierarchy is acyclic, validated).
  std::vector<std::vector<int>> children(raw.nodes.size());
  for (std::size_t i = 0; i < raw.nodes.size(); ++i)
    if (raw.nodes[i].parent >= 0)
      children[static_cast<std::size_t>(raw.nodes[i].parent)].push_back(static_cast<int>(i));
  std::vector<int> stack;
  for (std::size_t i = 0; i < raw.nodes.size(); ++i) {
    if (raw.nodes[i].parent >= 0) continue;
    stack.push_back(static_cast<int>(i));
    while (!stack.empty()) {
      const int j = stack.back();
      stack.pop_back();
      rig.order_.push_back(j);
      for (int c : children[static_cast<std::size_t>(j)]) stack.push_back(c);
    }
  }
  if (raw.skin) {
    rig.skinned_ = true;
    rig.joints_ = raw.skin->joints;
    rig.inverse_bind_ = raw.skin->inverse_bind;
    rig.vertex_joints_ = raw.joints;
    rig.vertex_weights_ = raw.weights;
    for (std::size_t v = 0; v < raw.mesh.vertexCount(); ++v) {
      double sum = 0;
      for (std::size_t k = 0; k < 4; ++k) sum += rig.vertex_weights_[4 * v + k];
      for (std::size_t k = 0; k < 4; ++k) {
        float& w = rig.vertex_weights_[4 * v + k];
        w = static_cast<float>(w / sum);
        if (w == 0) rig.vertex_joints_[4 * v + k] = 0;  // an unused slot may name any joint
      }
    }
  }
  for (const RigAnimation& in : raw.animations) {
    Animation anim;
    anim.name = in.name;
    anim.samplers = in.samplers;
    anim.channels = in.channels;
    for (const RigSampler& s : in.samplers) anim.duration = std::max(anim.duration, double{s.input.back()});
    rig.animations_.push_back(std::move(anim));
  }
  rig.pose_ = rig.nodes_;
  rig.world_.assign(rig.nodes_.size(), Eigen::Matrix4d::Identity());
  rig.joint_matrices_.assign(rig.joints_.size(), Eigen::Matrix4d::Identity());
  rig.morph_weights_ = rig.default_weights_;
  rig.sample_.assign(std::max<std::size_t>(4, rig.targetCount()), 0.0);
  return rig;
}

const std::string& Rig::animationName(int animation) const {
  if (animation < 0 || static_cast<std::size_t>(animation) >= animations_.size())
    throw Error("animation " + std::to_string(animation) + " out of range (the rig has " +
                std::to_string(animations_.size()) + " animations)");
  return animations_[static_cast<std::size_t>(animation)].name;
}

double Rig::duration(int animation) const {
  if (animation == -1) return 0;
  animationName(animation);  // the range check
  return animations_[static_cast<std::size_t>(animation)].duration;
}

// glTF Appendix C. Keyframe k with t_k <= time < t_{k+1}; clamped outside [t_0, t_last].
void Rig::sampleChannel(const RigSampler& s, RigPath path, double time, double* out, int width) const {
  const std::size_t count = s.input.size();
  const std::size_t w = static_cast<std::size_t>(width);
  const bool cubic = s.interpolation == RigInterpolation::kCubicSpline;
  const std::size_t stride = cubic ? 3 * w : w;
  const std::size_t value_offset = cubic ? w : 0;  // CUBICSPLINE: in-tangent, value, out-tangent
  auto value = [&](std::size_t k, std::size_t i) { return double{s.output[k * stride + value_offset + i]}; };
  if (count == 1 || time <= s.input.front() || time >= s.input.back()) {
    const std::size_t k = (count == 1 || time <= s.input.front()) ? 0 : count - 1;
    for (std::size_t i = 0; i < w; ++i) out[i] = value(k, i);
  } else {
    const auto it = std::upper_bound(s.input.begin(), s.input.end(), static_cast<float>(time),
                                     [](float t, float key) { return t < key; });
    // time < back(), so it != end(); time > front() in double, so it != begin() unless the float
    // rounding of `time` reaches front().
    std::size_t k1 = static_cast<std::size_t>(it - s.input.begin());
    k1 = std::clamp<std::size_t>(k1, 1, count - 1);
    const std::size_t k0 = k1 - 1;
    const double t0 = s.input[k0], t1 = s.input[k1];
    const double td = t1 - t0;
    const double u = std::clamp((time - t0) / td, 0.0, 1.0);
    if (s.interpolation == RigInterpolation::kStep) {
      for (std::size_t i = 0; i < w; ++i) out[i] = value(k0, i);
    } else if (!cubic) {
      if (path == RigPath::kRotation) {
        Eigen::Quaterniond a(value(k0, 3), value(k0, 0), value(k0, 1), value(k0, 2));
        Eigen::Quaterniond b(value(k1, 3), value(k1, 0), value(k1, 1), value(k1, 2));
        a = normalisedQuaternion(a);
        b = normalisedQuaternion(b);
        if (a.dot(b) < 0) b.coeffs() = -b.coeffs();  // the shortest arc
        const double d = std::min(1.0, a.dot(b));
        Eigen::Vector4d q;
        if (d > 1.0 - 1e-9) {
          q = (1 - u) * a.coeffs() + u * b.coeffs();
        } else {
          const double theta = std::acos(d);
          const double sin_theta = std::sin(theta);
          q = (std::sin((1 - u) * theta) / sin_theta) * a.coeffs() + (std::sin(u * theta) / sin_theta) * b.coeffs();
        }
        for (std::size_t i = 0; i < 4; ++i) out[i] = q[static_cast<Eigen::Index>(i)];
      } else {
        for (std::size_t i = 0; i < w; ++i) out[i] = (1 - u) * value(k0, i) + u * value(k1, i);
      }
    } else {
      const double u2 = u * u, u3 = u2 * u;
      const double h00 = 2 * u3 - 3 * u2 + 1, h10 = u3 - 2 * u2 + u, h01 = -2 * u3 + 3 * u2, h11 = u3 - u2;
      for (std::size_t i = 0; i < w; ++i) {
        const double b0 = s.output[k0 * stride + 2 * w + i];  // out-tangent of k0
        const double a1 = s.output[k1 * stride + i];          // in-tangent of k1
        out[i] = h00 * value(k0, i) + td * h10 * b0 + h01 * value(k1, i) + td * h11 * a1;
      }
    }
  }
  if (path == RigPath::kRotation) {
    const Eigen::Quaterniond q = normalisedQuaternion(Eigen::Quaterniond(out[3], out[0], out[1], out[2]));
    out[0] = q.x(), out[1] = q.y(), out[2] = q.z(), out[3] = q.w();
  }
}

// Rest transforms and weights, then the animation's channels, into pose_ and morph_weights_.
void Rig::pose(int animation, double time) const {
  std::copy(nodes_.begin(), nodes_.end(), pose_.begin());
  std::copy(default_weights_.begin(), default_weights_.end(), morph_weights_.begin());
  if (animation >= 0) {
    const Animation& anim = animations_[static_cast<std::size_t>(animation)];
    for (const RigChannel& ch : anim.channels) {
      const int width = pathWidth(ch.path, targetCount());
      double* v = sample_.data();
      sampleChannel(anim.samplers[static_cast<std::size_t>(ch.sampler)], ch.path, time, v, width);
      Node& node = pose_[static_cast<std::size_t>(ch.node)];
      switch (ch.path) {
        case RigPath::kTranslation:
          node.translation = Eigen::Vector3d(v[0], v[1], v[2]);
          break;
        case RigPath::kRotation:
          node.rotation = Eigen::Quaterniond(v[3], v[0], v[1], v[2]);
          break;
        case RigPath::kScale:
          node.scale = Eigen::Vector3d(v[0], v[1], v[2]);
          break;
        case RigPath::kWeights:
          std::copy(v, v + width, morph_weights_.begin());
          break;
      }
    }
  }
}

bool Rig::nodePose(int animation, double time, std::span<double> out) const {
  if (animation < -1 || animation >= static_cast<long>(animations_.size()) || !std::isfinite(time)) return false;
  if (out.size() != 10 * nodes_.size()) return false;
  pose(animation, time);
  for (std::size_t i = 0; i < pose_.size(); ++i) {
    const Node& node = pose_[i];
    const Eigen::Quaterniond q = node.rotation.normalized();
    const double values[10] = {
        node.translation.x(), node.translation.y(), node.translation.z(), q.x(), q.y(), q.z(), q.w(),
        node.scale.x(),       node.scale.y(),       node.scale.z()};
    std::copy(values, values + 10, out.begin() + static_cast<std::ptrdiff_t>(i * 10));
  }
  return true;
}

// flatten: GCC's -O2 inliner left Eigen's 3x3 product of the per-vertex loop (and a few helpers)
// as calls; inlining them changes no value (the outputs were compared bit for bit with the code
// before; no floating-point contraction on the baseline x86-64 target) and makes the walker's
// skinning about a tenth faster (docs/performance.md).
[[gnu::flatten]] bool Rig::evaluate(int animation, double time, std::span<float> out_positions,
                                    std::span<float> out_normals, std::span<float> out_skin) const {
  const std::size_t nv = mesh_.vertexCount();
  if (animation < -1 || animation >= static_cast<long>(animations_.size()) || !std::isfinite(time)) return false;
  if (out_positions.size() != 3 * nv) return false;
  if (!out_normals.empty() && out_normals.size() != 3 * nv) return false;
  if (!out_skin.empty() && out_skin.size() != 9 * nv) return false;

  pose(animation, time);
  for (int i : order_) {
    const Node& node = pose_[static_cast<std::size_t>(i)];
    const Eigen::Matrix4d local =
        node.has_matrix ? node.matrix : localMatrix(node.translation, node.rotation, node.scale);
    world_[static_cast<std::size_t>(i)] =
        node.parent < 0 ? local : Eigen::Matrix4d(world_[static_cast<std::size_t>(node.parent)] * local);
  }

  // Morph targets (glTF 3.7.2), written straight into the outputs. Without targets the sums in
  // doubles are the inputs themselves (a finite float, which build() checked, survives the round
  // trip through double exactly), so they are copied.
  const bool file_normals = !normals_.empty() && !out_normals.empty();
  if (target_positions_.empty() && target_normals_.empty()) {
    std::copy(mesh_.positions.begin(), mesh_.positions.end(), out_positions.begin());
    if (file_normals) std::copy(normals_.begin(), normals_.end(), out_normals.begin());
  } else {
    for (std::size_t i = 0; i < 3 * nv; ++i) {
      double p = mesh_.positions[i];
      for (std::size_t t = 0; t < target_positions_.size(); ++t) p += morph_weights_[t] * target_positions_[t][i];
      out_positions[i] = static_cast<float>(p);
      if (file_normals) {
        double q = normals_[i];
        for (std::size_t t = 0; t < target_normals_.size(); ++t)
          if (!target_normals_[t].empty()) q += morph_weights_[t] * target_normals_[t][i];
        out_normals[i] = static_cast<float>(q);
      }
    }
  }

  // Skinning (glTF 3.7.3) or the mesh node's placement.
  for (std::size_t j = 0; j < joints_.size(); ++j)
    joint_matrices_[j] = world_[static_cast<std::size_t>(joints_[j])] * inverse_bind_[j];
  const Eigen::Matrix4d placement =
      mesh_node_ >= 0 ? world_[static_cast<std::size_t>(mesh_node_)] : Eigen::Matrix4d::Identity();
  const Eigen::Matrix3d placement_normals = normalMatrix(placement.topLeftCorner<3, 3>());
  for (std::size_t v = 0; v < nv; ++v) {
    Eigen::Matrix4d m;
    if (skinned_) {
      // m = 0 + w0 J0 + w1 J1 + ... over the non-zero weights, the first term computed as
      // w J + 0.0 in registers: the same IEEE sum as adding it to a zeroed matrix (signed zeros
      // included), without the zeroing, which GCC compiled to a rep stos per vertex.
      bool empty = true;
      for (std::size_t k = 0; k < 4; ++k) {
        const double w = vertex_weights_[4 * v + k];
        if (w == 0) continue;
        const Eigen::Matrix4d& joint = joint_matrices_[vertex_joints_[4 * v + k]];
        if (empty) {
          m.array() = (w * joint).array() + 0.0;
          empty = false;
        } else {
          m += w * joint;
        }
      }
      if (empty) m.setZero();
    } else {
      m = placement;
    }
    const Eigen::Vector3d p(out_positions[3 * v], out_positions[3 * v + 1], out_positions[3 * v + 2]);
    const Eigen::Vector3d q = m.topLeftCorner<3, 3>() * p + m.topRightCorner<3, 1>();
    // Written out coordinate by coordinate (not a loop, which GCC kept, reading q back from the
    // stack right after storing it), here and for the normals and skin below.
    float* const out_p = out_positions.data() + 3 * v;
    out_p[0] = static_cast<float>(q.x());
    out_p[1] = static_cast<float>(q.y());
    out_p[2] = static_cast<float>(q.z());
    if (file_normals) {
      const Eigen::Matrix3d nm = skinned_ ? normalMatrix(m.topLeftCorner<3, 3>()) : placement_normals;
      Eigen::Vector3d n = nm * Eigen::Vector3d(out_normals[3 * v], out_normals[3 * v + 1], out_normals[3 * v + 2]);
      const double len = n.norm();
      if (len > 0 && std::isfinite(len)) n /= len;
      float* const out_n = out_normals.data() + 3 * v;
      out_n[0] = static_cast<float>(n.x());
      out_n[1] = static_cast<float>(n.y());
      out_n[2] = static_cast<float>(n.z());
    }
    if (!out_skin.empty()) {
      float* const out_s = out_skin.data() + 9 * v;  // column-major 3x3
      out_s[0] = static_cast<float>(m(0, 0));
      out_s[1] = static_cast<float>(m(1, 0));
      out_s[2] = static_cast<float>(m(2, 0));
      out_s[3] = static_cast<float>(m(0, 1));
      out_s[4] = static_cast<float>(m(1, 1));
      out_s[5] = static_cast<float>(m(2, 1));
      out_s[6] = static_cast<float>(m(0, 2));
      out_s[7] = static_cast<float>(m(1, 2));
      out_s[8] = static_cast<float>(m(2, 2));
    }
  }
  if (!out_normals.empty() && normals_.empty())
    return computeVertexNormals(out_positions, mesh_.triangles, out_normals);
  return true;
}

}  // namespace vdg
