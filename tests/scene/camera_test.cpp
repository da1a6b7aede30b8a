// Cameras in the scene (Parent 4.4): a fixed camera looks along its node's -Z with +Y up; a path
// camera is the anim library's CameraPath carried by its node; look_at follows a moving node.
#include <gtest/gtest.h>

#include <cmath>

#include "scene_fixtures.h"

namespace vdg::scene {
namespace {

using namespace fixtures;

constexpr double kTol = 1e-9;

Eigen::Vector3d viewDirection(const Camera& c) { return (c.target - c.eye).normalized(); }

anim::RawCameraPath circlePath() {
  anim::RawCameraPath p;
  p.position.kind = anim::CurveKind::kCatmullRom;
  p.position.points = {values({0, 1, 10}), values({7, 1, 7}), values({10, 2, 0}), values({7, 3, -7})};
  p.start_time = 0;
  p.end_time = 48;
  p.speed = anim::Ease::sine();
  p.view = anim::ViewMode::kCenterOfInterest;
  p.center = {0, 0.5, 0};
  return p;
}

TEST(SceneCamera, FixedCameraLooksAlongItsNodesMinusZ) {
  RawScene raw;
  const int rig = addNode(raw, "rig");
  const int cam = addNode(raw, "cam", rig, ObjectKind::kCamera);
  raw.nodes[static_cast<std::size_t>(rig)].link.translation = {1, 2, 3};
  raw.nodes[static_cast<std::size_t>(cam)].fov_deg = 55;
  raw.actions.push_back(change(rig, Field::kRotation, quaternionValue(turn({0, 1, 0}, 90)), 0, 10));
  const Scene scene = Scene::build(raw);
  ASSERT_EQ(scene.cameraNode(), cam);
  Camera c;
  auto s = evaluated(scene, 0);
  ASSERT_TRUE(scene.camera(0, s, c));
  EXPECT_LT((c.eye - Eigen::Vector3d(1, 2, 3)).norm(), kTol);
  EXPECT_LT((viewDirection(c) - Eigen::Vector3d(0, 0, -1)).norm(), kTol);
  EXPECT_LT((c.up - Eigen::Vector3d(0, 1, 0)).norm(), kTol);
  EXPECT_EQ(c.fov_deg, 55);
  // Turned 90 degrees about +Y, -Z becomes -X.
  s = evaluated(scene, 10);
  ASSERT_TRUE(scene.camera(10, s, c));
  EXPECT_LT((viewDirection(c) - Eigen::Vector3d(-1, 0, 0)).norm(), kTol);
  EXPECT_LT((c.up - Eigen::Vector3d(0, 1, 0)).norm(), kTol);
}

TEST(SceneCamera, PathCameraAtIdentityIsTheLibrarysCameraPath) {
  RawScene raw;
  const int cam = addNode(raw, "cam", -1, ObjectKind::kCamera);
  raw.nodes[static_cast<std::size_t>(cam)].path = circlePath();
  const Scene scene = Scene::build(raw);
  const anim::CameraPath path = anim::CameraPath::build(circlePath());
  for (double f = -2; f <= 50; f += 2.5) {
    Camera c;
    ASSERT_TRUE(scene.camera(f, evaluated(scene, f), c));
    const Camera expected = path.cameraAt(f);
    EXPECT_LT((c.eye - expected.eye).norm(), kTol) << f;
    EXPECT_LT((c.target - expected.target).norm(), kTol) << f;
    EXPECT_LT((c.up - expected.up.normalized()).norm(), kTol) << f;
  }
}

TEST(SceneCamera, PathCameraIsCarriedByItsNode) {
  RawScene raw;
  const int rig = addNode(raw, "rig");
  const int cam = addNode(raw, "cam", rig, ObjectKind::kCamera);
  raw.nodes[static_cast<std::size_t>(cam)].path = circlePath();
  const Eigen::Quaterniond r = turn({1, 2, 0.5}, 40);
  const Eigen::Vector3d t(5, -1, 2);
  raw.nodes[static_cast<std::size_t>(rig)].link.rotation = r;
  raw.nodes[static_cast<std::size_t>(rig)].link.translation = t;
  const Scene scene = Scene::build(raw);
  const anim::CameraPath path = anim::CameraPath::build(circlePath());
  for (double f : {0.0, 12.0, 30.0, 48.0}) {
    Camera c;
    ASSERT_TRUE(scene.camera(f, evaluated(scene, f), c));
    const Camera local = path.cameraAt(f);
    EXPECT_LT((c.eye - (r * local.eye + t)).norm(), kTol) << f;
    EXPECT_LT((c.target - (r * local.target + t)).norm(), kTol) << f;
    EXPECT_LT((c.up - r * local.up.normalized()).norm(), kTol) << f;
  }
}

TEST(SceneCamera, LookAtFollowsAMovingNode) {
  RawScene raw;
  const int cam = addNode(raw, "cam", -1, ObjectKind::kCamera);
  const int ball = addNode(raw, "ball");
  raw.nodes[static_cast<std::size_t>(cam)].link.translation = {0, 3, 10};
  raw.nodes[static_cast<std::size_t>(cam)].look_at = "ball";
  raw.actions.push_back(change(ball, Field::kTranslation, values({8, 0, 0}), 0, 8));
  const Scene scene = Scene::build(raw);
  for (double f : {0.0, 2.0, 5.0, 8.0}) {
    Camera c;
    ASSERT_TRUE(scene.camera(f, evaluated(scene, f), c));
    EXPECT_LT((c.target - Eigen::Vector3d(f, 0, 0)).norm(), kTol) << f;
    EXPECT_LT((c.eye - Eigen::Vector3d(0, 3, 10)).norm(), kTol);
    EXPECT_NEAR(c.up.dot(viewDirection(c)), 0.0, kTol);  // orthogonalised
    EXPECT_GT(c.up.y(), 0.9);                            // and still the node's up, nearly
    EXPECT_NEAR(c.up.norm(), 1.0, kTol);
  }
  // Straight down on the ball: +Y is parallel to the view, the node's -Z becomes the up.
  RawScene down;
  addNode(down, "cam", -1, ObjectKind::kCamera);
  addNode(down, "ball");
  down.nodes[0].link.translation = {0, 10, 0};
  down.nodes[0].look_at = "ball";
  const Scene d = Scene::build(down);
  Camera c;
  ASSERT_TRUE(d.camera(0, evaluated(d, 0), c));
  EXPECT_LT((c.up - Eigen::Vector3d(0, 0, -1)).norm(), kTol);
}

TEST(SceneCamera, ActiveCameraByNameAndAnimatedFov) {
  RawScene raw;
  addNode(raw, "first", -1, ObjectKind::kCamera);
  const int second = addNode(raw, "second", -1, ObjectKind::kCamera);
  raw.nodes[static_cast<std::size_t>(second)].ortho_height = 4;
  raw.actions.push_back(change(second, Field::kFov, values({20}), 0, 10));
  EXPECT_EQ(Scene::build(raw).cameraNode(), 0);
  raw.camera = "second";
  const Scene scene = Scene::build(raw);
  EXPECT_EQ(scene.cameraNode(), second);
  Camera c;
  ASSERT_TRUE(scene.camera(5, evaluated(scene, 5), c));
  EXPECT_NEAR(c.fov_deg, 50, kTol);
  EXPECT_EQ(c.ortho_height, 4);
  // A scene without cameras is valid; it has no camera to give.
  RawScene none;
  addNode(none, "g");
  const Scene n = Scene::build(none);
  EXPECT_EQ(n.cameraNode(), -1);
  EXPECT_FALSE(n.camera(0, evaluated(n, 0), c));
}

}  // namespace
}  // namespace vdg::scene
