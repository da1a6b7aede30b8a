// Small scenes for the scene tests: nodes, tracks and actions built in a line each.
#pragma once

#include <cmath>
#include <initializer_list>
#include <memory>
#include <string>
#include <vector>

#include "support/test_meshes.h"
#include "vdg/scene/scene.h"

namespace vdg::scene::fixtures {

// A unit quaternion turning `degrees` about the unit `axis`.
inline Eigen::Quaterniond turn(const Eigen::Vector3d& axis, double degrees) {
  return Eigen::Quaterniond(Eigen::AngleAxisd(degrees * M_PI / 180.0, axis.normalized()));
}

inline Eigen::VectorXd values(std::initializer_list<double> v) {
  Eigen::VectorXd out(static_cast<Eigen::Index>(v.size()));
  Eigen::Index i = 0;
  for (double x : v) out[i++] = x;
  return out;
}

inline Eigen::VectorXd quaternionValue(const Eigen::Quaterniond& q) { return values({q.w(), q.x(), q.y(), q.z()}); }

// Appends a node and returns its index.
inline int addNode(RawScene& scene, const std::string& name, int parent = -1, ObjectKind kind = ObjectKind::kGroup,
                   int object = -1) {
  RawNode node;
  node.name = name;
  node.parent = parent;
  node.kind = kind;
  node.object = object;
  scene.nodes.push_back(node);
  return static_cast<int>(scene.nodes.size()) - 1;
}

inline RawAction set(int node, Field field, Eigen::VectorXd value, double frame) {
  RawAction a;
  a.kind = RawAction::Kind::kSet;
  a.node = node;
  a.field = field;
  a.value = std::move(value);
  a.from_frame = frame;
  return a;
}

inline RawAction change(int node, Field field, Eigen::VectorXd value, double from, double to,
                        anim::Ease ease = anim::Ease::linear()) {
  RawAction a;
  a.kind = RawAction::Kind::kChange;
  a.node = node;
  a.field = field;
  a.value = std::move(value);
  a.from_frame = from;
  a.to_frame = to;
  a.ease = ease;
  return a;
}

inline anim::RawKey key(double time, Eigen::VectorXd value) {
  anim::RawKey k;
  k.time = time;
  k.value = std::move(value);
  return k;
}

// The world position of a node (the origin of its coordinates).
inline Eigen::Vector3d origin(const NodeState& state) { return state.world.topRightCorner<3, 1>(); }

inline std::vector<NodeState> evaluated(const Scene& scene, double frame) {
  std::vector<NodeState> states(static_cast<std::size_t>(scene.nodeCount()));
  if (!scene.evaluate(frame, states)) states.clear();
  return states;
}

// A view-dependent sphere (centre at the origin) with six keys looking along +-X, +-Y, +-Z, each
// pushing one vertex out.
inline std::shared_ptr<const ViewDependentModel> sixKeyModel() {
  RawViewDependentModel raw;
  raw.base = testing::uvSphere(6, 8);
  const Eigen::Vector3d views[] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  for (int k = 0; k < 6; ++k) {
    RawKey key;
    key.name = "k" + std::to_string(k);
    key.mesh = raw.base;
    key.mesh.positions[3 * static_cast<std::size_t>(k + 1)] *= 1.3f;
    key.view = views[k];
    raw.keys.push_back(key);
  }
  return std::make_shared<const ViewDependentModel>(ViewDependentModel::build(raw));
}

// sixKeyModel's sphere with two key sets: the part "top" (the vertices above y = 0.5) with keys
// t0..t5 and the rest with k0..k5, the same six views for each (per-part key sets, model.h).
inline std::shared_ptr<const ViewDependentModel> twoPartModel() {
  RawViewDependentModel raw;
  raw.base = testing::uvSphere(6, 8);
  const Eigen::Vector3d views[] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  RawPart top;
  top.name = "top";
  for (std::size_t v = 0; v < raw.base.vertexCount(); ++v)
    if (raw.base.positions[3 * v + 1] > 0.5f) top.vertices.push_back(static_cast<std::int32_t>(v));
  for (const char* set : {"t", "k"}) {
    for (int k = 0; k < 6; ++k) {
      RawKey key;
      key.name = set + std::to_string(k);
      key.mesh = raw.base;
      for (float& x : key.mesh.positions) x *= 1.0f + 0.05f * static_cast<float>(k + 1);
      key.view = views[k];
      raw.keys.push_back(key);
      if (*set == 't') top.keys.push_back(key.name);
    }
  }
  raw.parts.push_back(top);
  return std::make_shared<const ViewDependentModel>(ViewDependentModel::build(raw));
}

// An animated sphere of `frames` frames (it bobs along +Y) with one key seen from +Z at frame 0.
inline std::shared_ptr<const AnimatedViewDependentModel> bobbingModel(int frames) {
  RawViewDependentModel raw;
  raw.base = testing::uvSphere(4, 6);
  raw.base_animation = BaseAnimationSpec{};
  raw.base_animation->obj_sequence = "frame_%02d.obj";
  raw.base_animation->last = frames - 1;
  for (int f = 0; f < frames; ++f) {
    std::vector<float> p = raw.base.positions;
    for (std::size_t v = 0; v < raw.base.vertexCount(); ++v) p[3 * v + 1] += 0.1f * static_cast<float>(f);
    raw.base_frames.push_back(p);
  }
  RawKey key;
  key.name = "front";
  key.mesh = raw.base;
  key.mesh.positions[0] += 0.2f;
  key.view = {0, 0, 1};
  raw.keys.push_back(key);
  return std::make_shared<const AnimatedViewDependentModel>(AnimatedViewDependentModel::build(raw));
}

}  // namespace vdg::scene::fixtures
