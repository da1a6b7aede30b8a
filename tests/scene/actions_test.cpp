// SET and CHANGE (Parent 4.6): absolute versus relative values, changes spread over frames with an
// ease, a SET in the middle of a running CHANGE, rotations turning about the node's own axes, and
// one action applied to many nodes (FOR EACH).
#include <gtest/gtest.h>

#include <cmath>

#include "scene_fixtures.h"

namespace vdg::scene {
namespace {

using namespace fixtures;

constexpr double kTol = 1e-12;

Eigen::Vector3d translationAt(const Scene& scene, int node, double frame) {
  Eigen::Vector3d v;
  EXPECT_TRUE(scene.fieldValue(node, Field::kTranslation, frame, std::span<double>(v.data(), 3)));
  return v;
}

TEST(SceneActions, SetIsAbsoluteChangeIsRelative) {
  RawScene raw;
  const int n = addNode(raw, "box");
  raw.nodes[0].link.translation = {1, 2, 3};
  raw.actions.push_back(set(n, Field::kTranslation, values({5, 5, 5}), 10));
  raw.actions.push_back(change(n, Field::kTranslation, values({10, 0, 0}), 20, 30));
  const Scene scene = Scene::build(raw);
  EXPECT_LT((translationAt(scene, n, 0) - Eigen::Vector3d(1, 2, 3)).norm(), kTol);
  EXPECT_LT((translationAt(scene, n, 9.99) - Eigen::Vector3d(1, 2, 3)).norm(), kTol);
  EXPECT_LT((translationAt(scene, n, 10) - Eigen::Vector3d(5, 5, 5)).norm(), kTol);
  EXPECT_LT((translationAt(scene, n, 20) - Eigen::Vector3d(5, 5, 5)).norm(), kTol);
  EXPECT_LT((translationAt(scene, n, 25) - Eigen::Vector3d(10, 5, 5)).norm(), kTol);
  EXPECT_LT((translationAt(scene, n, 30) - Eigen::Vector3d(15, 5, 5)).norm(), kTol);
  EXPECT_LT((translationAt(scene, n, 1000) - Eigen::Vector3d(15, 5, 5)).norm(), kTol);
  // The same through evaluate().
  const auto s = evaluated(scene, 25);
  EXPECT_LT((origin(s[0]) - Eigen::Vector3d(10, 5, 5)).norm(), kTol);
}

}  // namespace
}  // namespace vdg::scene
