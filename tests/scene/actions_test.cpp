// SET and CHANGE (Parent 4.6): absolute versus relative values, changes spread over frames with an
// ease, a SET in the middle of a running CHANGE, rotations turning about the node's own axes, and
// one action applied to many nodes (FOR EACH).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "scene_fixtures.h"

namespace vdg::scene {
namespace {

using namespace fixtures;

constexpr double kTol = 1e-12;
constexpr double kFloatTol = 1e-6;  // colours start as floats

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

double scalarAt(const Scene& scene, int node, Field field, double frame) {
  double v = 0.0;
  EXPECT_TRUE(scene.fieldValue(node, field, frame, std::span<double>(&v, 1)));
  return v;
}

Eigen::Quaterniond rotationAt(const Scene& scene, int node, double frame) {
  double q[4] = {0, 0, 0, 0};
  EXPECT_TRUE(scene.fieldValue(node, Field::kRotation, frame, std::span<double>(q, 4)));
  return Eigen::Quaterniond(q[0], q[1], q[2], q[3]);
}

// The same rotation (q and -q are one rotation).
double rotationDistance(const Eigen::Quaterniond& a, const Eigen::Quaterniond& b) {
  return std::min((a.coeffs() - b.coeffs()).norm(), (a.coeffs() + b.coeffs()).norm());
}

TEST(SceneActions, ChangeSpreadsOverItsFramesWithTheEase) {
  for (const anim::Ease& ease : {anim::Ease::linear(), anim::Ease::sine(), anim::Ease::parabolic(0.2, 0.7)}) {
    RawScene raw;
    const int n = addNode(raw, "box");
    raw.nodes[0].link.translation = {1, 0, 0};
    raw.actions.push_back(change(n, Field::kTranslation, values({0, 8, -4}), 10, 30, ease));
    const Scene scene = Scene::build(raw);
    for (double f : {-5.0, 10.0, 12.5, 15.0, 20.0, 27.0, 30.0, 31.0}) {
      const double u = std::clamp((f - 10.0) / 20.0, 0.0, 1.0);
      const Eigen::Vector3d expected = Eigen::Vector3d(1, 0, 0) + ease.evaluate(u) * Eigen::Vector3d(0, 8, -4);
      EXPECT_LT((translationAt(scene, n, f) - expected).norm(), kTol) << ease.describe() << " frame " << f;
    }
  }
  // The sine ease at a quarter of the way: (sin(pi/4 - pi/2) + 1) / 2 = 0.1464...
  RawScene raw;
  const int n = addNode(raw, "box");
  raw.actions.push_back(change(n, Field::kTranslation, values({1, 0, 0}), 0, 4, anim::Ease::sine()));
  EXPECT_NEAR(translationAt(Scene::build(raw), n, 1.0).x(), (std::sin(M_PI / 4 - M_PI / 2) + 1) / 2, kTol);
}

TEST(SceneActions, ChangesAddUp) {
  RawScene raw;
  const int n = addNode(raw, "box");
  raw.actions.push_back(change(n, Field::kTranslation, values({2, 0, 0}), 0, 10));
  raw.actions.push_back(change(n, Field::kTranslation, values({0, 4, 0}), 5, 15));
  const Scene scene = Scene::build(raw);
  EXPECT_LT((translationAt(scene, n, 7.5) - Eigen::Vector3d(1.5, 1, 0)).norm(), kTol);
  EXPECT_LT((translationAt(scene, n, 15) - Eigen::Vector3d(2, 4, 0)).norm(), kTol);
}

TEST(SceneActions, SetDuringARunningChangeKeepsOnlyWhatItAddsAfterwards) {
  RawScene raw;
  const int n = addNode(raw, "box");
  raw.actions.push_back(change(n, Field::kTranslation, values({10, 0, 0}), 0, 10));
  raw.actions.push_back(set(n, Field::kTranslation, values({0, 1, 0}), 4));
  const Scene scene = Scene::build(raw);
  EXPECT_LT((translationAt(scene, n, 3) - Eigen::Vector3d(3, 0, 0)).norm(), kTol);
  EXPECT_LT((translationAt(scene, n, 4) - Eigen::Vector3d(0, 1, 0)).norm(), kTol);
  // After the SET the CHANGE still adds 1 per frame: 10 * (0.7 - 0.4) = 3 at frame 7.
  EXPECT_LT((translationAt(scene, n, 7) - Eigen::Vector3d(3, 1, 0)).norm(), kTol);
  EXPECT_LT((translationAt(scene, n, 20) - Eigen::Vector3d(6, 1, 0)).norm(), kTol);
}

TEST(SceneActions, SetOrderAndJumps) {
  RawScene raw;
  const int n = addNode(raw, "box");
  // Two SETs at one frame: the last given wins; a later SET given earlier still takes over at its frame.
  raw.actions.push_back(set(n, Field::kTranslation, values({9, 9, 9}), 8));
  raw.actions.push_back(set(n, Field::kTranslation, values({1, 0, 0}), 2));
  raw.actions.push_back(set(n, Field::kTranslation, values({2, 0, 0}), 2));
  // A jump CHANGE at the SET's frame given after it counts; one given before it does not.
  raw.actions.push_back(change(n, Field::kTranslation, values({0, 1, 0}), 2, 2));
  const Scene scene = Scene::build(raw);
  EXPECT_LT((translationAt(scene, n, 1.9) - Eigen::Vector3d(0, 0, 0)).norm(), kTol);
  EXPECT_LT((translationAt(scene, n, 2) - Eigen::Vector3d(2, 1, 0)).norm(), kTol);
  EXPECT_LT((translationAt(scene, n, 7) - Eigen::Vector3d(2, 1, 0)).norm(), kTol);
  EXPECT_LT((translationAt(scene, n, 8) - Eigen::Vector3d(9, 9, 9)).norm(), kTol);

  RawScene before;
  addNode(before, "box");
  before.actions.push_back(change(0, Field::kTranslation, values({0, 1, 0}), 2, 2));
  before.actions.push_back(set(0, Field::kTranslation, values({2, 0, 0}), 2));
  const Scene b = Scene::build(before);
  EXPECT_LT((translationAt(b, 0, 1) - Eigen::Vector3d(0, 0, 0)).norm(), kTol);
  EXPECT_LT((translationAt(b, 0, 2) - Eigen::Vector3d(2, 0, 0)).norm(), kTol);
  EXPECT_LT((translationAt(b, 0, 3) - Eigen::Vector3d(2, 0, 0)).norm(), kTol);
}

TEST(SceneActions, RotationChangeTurnsAboutTheNodesOwnAxes) {
  RawScene raw;
  const int n = addNode(raw, "arm");
  const Eigen::Quaterniond start = turn(Eigen::Vector3d::UnitZ(), 90);
  raw.nodes[0].link.rotation = start;
  raw.actions.push_back(change(n, Field::kRotation, quaternionValue(turn(Eigen::Vector3d::UnitX(), 90)), 0, 10));
  const Scene scene = Scene::build(raw);
  for (double f : {0.0, 2.5, 5.0, 10.0, 12.0}) {
    const double angle = 90.0 * std::clamp(f / 10.0, 0.0, 1.0);
    const Eigen::Quaterniond expected = start * turn(Eigen::Vector3d::UnitX(), angle);
    EXPECT_LT(rotationDistance(rotationAt(scene, n, f), expected), kTol) << "frame " << f;
  }
  // About its own X axis, which the first turn laid along world +Y: world +Y stays put, while a
  // turn about world X would have moved it.
  const auto s = evaluated(scene, 10);
  const Eigen::Matrix3d r = s[0].world.topLeftCorner<3, 3>();
  EXPECT_LT((r * Eigen::Vector3d(1, 0, 0) - Eigen::Vector3d(0, 1, 0)).norm(), kTol);
  EXPECT_LT((r * Eigen::Vector3d(0, 1, 0) - Eigen::Vector3d(0, 0, 1)).norm(), kTol);
}

TEST(SceneActions, RotationChangeTurnsTheWayItsValueTurns) {
  RawScene raw;
  const int n = addNode(raw, "wheel");
  // 270 degrees: w = cos(135) < 0. Half-way is 135 degrees, not the short way's -45.
  raw.actions.push_back(change(n, Field::kRotation, quaternionValue(turn(Eigen::Vector3d::UnitY(), 270)), 0, 10));
  const Scene scene = Scene::build(raw);
  EXPECT_LT(rotationDistance(rotationAt(scene, n, 5), turn(Eigen::Vector3d::UnitY(), 135)), kTol);
  EXPECT_LT(rotationDistance(rotationAt(scene, n, 10), turn(Eigen::Vector3d::UnitY(), 270)), kTol);
  // A SET then a CHANGE: the CHANGE turns from the SET's rotation.
  RawScene again;
  addNode(again, "wheel");
  again.actions.push_back(set(0, Field::kRotation, quaternionValue(turn(Eigen::Vector3d::UnitY(), 30)), 0));
  again.actions.push_back(
      change(0, Field::kRotation, quaternionValue(turn(Eigen::Vector3d::UnitY(), 60)), 0, 6, anim::Ease::sine()));
  const Scene b = Scene::build(again);
  const double eased = anim::Ease::sine().evaluate(0.5);
  EXPECT_LT(rotationDistance(rotationAt(b, 0, 3), turn(Eigen::Vector3d::UnitY(), 30 + 60 * eased)), kTol);
}

TEST(SceneActions, ForEachAppliesOneActionToEveryNode) {
  // FOR EACH OBJECT <set> CHANGE TRANSLATION BY (0, 2, 0) FROM 0 TO 4: every member moves by the
  // same amount from wherever it stands.
  RawScene raw;
  constexpr int kMembers = 12;
  for (int i = 0; i < kMembers; ++i) {
    const int n = addNode(raw, "member" + std::to_string(i));
    raw.nodes[static_cast<std::size_t>(n)].link.translation = {1.5 * i, 0, -0.5 * i};
    raw.actions.push_back(change(n, Field::kTranslation, values({0, 2, 0}), 0, 4, anim::Ease::sine()));
  }
  const Scene scene = Scene::build(raw);
  const auto s = evaluated(scene, 1);
  const double y = 2.0 * anim::Ease::sine().evaluate(0.25);
  for (int i = 0; i < kMembers; ++i) {
    EXPECT_LT((origin(s[static_cast<std::size_t>(i)]) - Eigen::Vector3d(1.5 * i, y, -0.5 * i)).norm(), kTol);
  }
}

TEST(SceneActions, ScalarAndColourFields) {
  RawScene raw;
  raw.meshes.push_back(std::make_shared<const TriMesh>(testing::uvSphere()));
  const int n = addNode(raw, "ball", -1, ObjectKind::kMesh, 0);
  raw.nodes[0].color = {0.2f, 0.4f, 0.6f};
  raw.actions.push_back(change(n, Field::kColor, values({0.6, 0.6, 0.6}), 0, 10));
  raw.actions.push_back(set(n, Field::kVisible, values({0}), 5));
  const Scene scene = Scene::build(raw);
  auto s = evaluated(scene, 5);
  EXPECT_NEAR(s[0].color[0], 0.5, kFloatTol);
  EXPECT_TRUE(!s[0].visible);
  s = evaluated(scene, 4.9);
  EXPECT_TRUE(s[0].visible);
  // Pushed beyond 1: clamped in the state, not in the field.
  s = evaluated(scene, 10);
  EXPECT_EQ(s[0].color[2], 1.0f);
  double c[3];
  ASSERT_TRUE(scene.fieldValue(n, Field::kColor, 10, c));
  EXPECT_NEAR(c[2], 1.2, kFloatTol);
  EXPECT_EQ(scalarAt(scene, n, Field::kVisible, 4), 1.0);
}

}  // namespace
}  // namespace vdg::scene
