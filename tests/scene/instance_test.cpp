// Instancing (Rademacher 99, sections 1 and 5): each instance of one view-dependent model is seen
// from its own angle; visibility is inherited down the tree; an animated model's frame follows
// the scene frame and the node's frame_offset.
#include <gtest/gtest.h>

#include <gmock/gmock.h>

#include <array>
#include <cmath>

#include "scene_fixtures.h"
#include "support/error_of.h"

namespace vdg::scene {
namespace {

using namespace fixtures;
using ::testing::HasSubstr;
using vdg::testing::errorOf;

constexpr double kTol = 1e-12;

// The key with the largest weight.
int dominantKey(const ViewWeights& w) {
  int best = 0;
  for (int i = 1; i < 3; ++i)
    if (w.weight[static_cast<std::size_t>(i)] > w.weight[static_cast<std::size_t>(best)]) best = i;
  return w.key[static_cast<std::size_t>(best)];
}

TEST(SceneInstances, TwoInstancesTurnedApartSeeDifferentViews) {
  RawScene raw;
  raw.models.push_back(sixKeyModel());
  const int a = addNode(raw, "a", -1, ObjectKind::kModel, 0);
  const int b = addNode(raw, "b", -1, ObjectKind::kModel, 0);
  raw.nodes[static_cast<std::size_t>(a)].link.translation = {-2, 0, 0};
  raw.nodes[static_cast<std::size_t>(b)].link.translation = {2, 0, 0};
  raw.nodes[static_cast<std::size_t>(b)].link.rotation = turn({0, 1, 0}, 90);
  const Scene scene = Scene::build(raw);
  ASSERT_EQ(scene.model(a), scene.model(b));  // one model, shared
  const auto s = evaluated(scene, 0);
  const Eigen::Vector3d eye_a(-2, 0, 10), eye_b(2, 0, 10);  // straight in front of each
  Eigen::Vector3d view_a, view_b;
  ASSERT_TRUE(scene.instanceView(a, s[0], eye_a, view_a));
  ASSERT_TRUE(scene.instanceView(b, s[1], eye_b, view_b));
  EXPECT_LT((view_a - Eigen::Vector3d(0, 0, 1)).norm(), kTol);
  // b is turned +90 degrees about Y: in its own frame the eye is on its -X side.
  EXPECT_LT((view_b - Eigen::Vector3d(-1, 0, 0)).norm(), kTol);
  // Hence different keys dominate.
  ViewWeights wa, wb;
  ASSERT_TRUE(scene.model(a)->weights(view_a, 0, wa));
  ASSERT_TRUE(scene.model(b)->weights(view_b, 0, wb));
  EXPECT_EQ(dominantKey(wa), 4);  // the key seen from +Z
  EXPECT_EQ(dominantKey(wb), 1);  // the key seen from -X
}

TEST(SceneInstances, InstanceViewIsViewFromEyeInObjectCoordinates) {
  RawScene raw;
  raw.models.push_back(sixKeyModel());
  const int g = addNode(raw, "crowd");
  const int m = addNode(raw, "member", g, ObjectKind::kModel, 0);
  raw.nodes[static_cast<std::size_t>(g)].link.rotation = turn({0.3, 1, 0.2}, 33);
  raw.nodes[static_cast<std::size_t>(g)].link.translation = {1, -2, 4};
  raw.nodes[static_cast<std::size_t>(m)].link.translation = {3, 0, 1};
  raw.nodes[static_cast<std::size_t>(m)].link.rotation = turn({0, 1, 0}, -70);
  raw.nodes[static_cast<std::size_t>(m)].placement.translation = {0, 0.5, 0};
  const Scene scene = Scene::build(raw);
  const auto s = evaluated(scene, 0);
  for (const Eigen::Vector3d& eye :
       {Eigen::Vector3d(0, 1, 12), Eigen::Vector3d(-8, 5, 2), Eigen::Vector3d(9, -3, -9)}) {
    Eigen::Vector3d view;
    ASSERT_TRUE(scene.instanceView(m, s[1], eye, view));
    const Eigen::Vector4d local = s[1].object.inverse() * Eigen::Vector4d(eye.x(), eye.y(), eye.z(), 1.0);
    const Eigen::Vector3d expected = scene.model(m)->viewFromEye(local.head<3>());
    EXPECT_LT((view - expected).norm(), kTol);
  }
}

TEST(SceneInstances, ScalingAnInstanceKeepsItsView) {
  RawScene raw;
  raw.models.push_back(sixKeyModel());
  const int m = addNode(raw, "m", -1, ObjectKind::kModel, 0);
  raw.nodes[0].link.rotation = turn({1, 1, 0}, 50);
  raw.nodes[0].link.translation = {1, 2, 3};
  raw.actions.push_back(set(m, Field::kScale, values({3, 3, 3}), 5));
  const Scene scene = Scene::build(raw);
  const Eigen::Vector3d eye(4, 7, -6);
  Eigen::Vector3d unscaled, scaled;
  ASSERT_TRUE(scene.instanceView(m, evaluated(scene, 0)[0], eye, unscaled));
  ASSERT_TRUE(scene.instanceView(m, evaluated(scene, 5)[0], eye, scaled));
  EXPECT_NEAR(evaluated(scene, 5)[0].world.col(0).norm(), 3.0, kTol);
  EXPECT_LT((scaled - unscaled).norm(), kTol);
}

TEST(SceneInstances, VisibilityIsInheritedDownTheTree) {
  RawScene raw;
  raw.meshes.push_back(std::make_shared<const TriMesh>(testing::uvSphere()));
  const int g = addNode(raw, "group");
  const int child = addNode(raw, "child", g, ObjectKind::kMesh, 0);
  const int grandchild = addNode(raw, "grandchild", child, ObjectKind::kMesh, 0);
  const int other = addNode(raw, "other", -1, ObjectKind::kMesh, 0);
  raw.actions.push_back(set(g, Field::kVisible, values({0}), 10));
  raw.actions.push_back(set(g, Field::kVisible, values({1}), 20));
  raw.actions.push_back(set(grandchild, Field::kVisible, values({0}), 15));
  const Scene scene = Scene::build(raw);
  auto s = evaluated(scene, 0);
  EXPECT_TRUE(s[0].visible && s[1].visible && s[2].visible && s[3].visible);
  s = evaluated(scene, 10);
  EXPECT_FALSE(s[static_cast<std::size_t>(g)].visible);
  EXPECT_FALSE(s[static_cast<std::size_t>(child)].visible);
  EXPECT_FALSE(s[static_cast<std::size_t>(grandchild)].visible);
  EXPECT_TRUE(s[static_cast<std::size_t>(other)].visible);
  s = evaluated(scene, 20);
  EXPECT_TRUE(s[static_cast<std::size_t>(child)].visible);
  EXPECT_FALSE(s[static_cast<std::size_t>(grandchild)].visible);  // hidden itself since 15
}

TEST(SceneInstances, AnimatedModelFrameIsFloorOfFramePlusOffsetModN) {
  constexpr int kFrames = 6;
  RawScene raw;
  raw.animated_models.push_back(bobbingModel(kFrames));
  const int a = addNode(raw, "walker", -1, ObjectKind::kAnimatedModel, 0);
  const int b = addNode(raw, "late", -1, ObjectKind::kAnimatedModel, 0);
  raw.nodes[static_cast<std::size_t>(b)].frame_offset = -2.5;
  const Scene scene = Scene::build(raw);
  ASSERT_EQ(scene.animatedModel(a), scene.animatedModel(b));
  struct Case {
    double frame;
    int a, b;
  };
  // floor(f) mod 6 and floor(f - 2.5) mod 6 (a negative remainder wraps to the end).
  for (const Case& c : {Case{0, 0, 3}, Case{0.99, 0, 4}, Case{2.4, 2, 5}, Case{2.5, 2, 0}, Case{5.9, 5, 3},
                        Case{6, 0, 3}, Case{13.2, 1, 4}, Case{-1, 5, 2}, Case{-6.5, 5, 3}}) {
    const auto s = evaluated(scene, c.frame);
    EXPECT_EQ(s[static_cast<std::size_t>(a)].model_frame, c.a) << c.frame;
    EXPECT_EQ(s[static_cast<std::size_t>(b)].model_frame, c.b) << c.frame;
  }
  Eigen::Vector3d view;
  ASSERT_TRUE(scene.instanceView(a, evaluated(scene, 0)[0], Eigen::Vector3d(0, 0, 9), view));
}
// Part drivers (scene.h): a driven part takes the view of its driver's eye, seen from the
// instance; the others follow the active camera.
TEST(SceneInstances, ADrivenPartFollowsItsDriverAndTheRestTheCamera) {
  RawScene raw;
  raw.models.push_back(twoPartModel());
  const int g = addNode(raw, "stage");
  const int m = addNode(raw, "cow", g, ObjectKind::kModel, 0);
  const int muse = addNode(raw, "muse", g);
  const int cam = addNode(raw, "painter", -1, ObjectKind::kCamera);
  raw.nodes[static_cast<std::size_t>(g)].link.rotation = turn({0, 1, 0}, 25);
  raw.nodes[static_cast<std::size_t>(m)].link.rotation = turn({0.2, 1, 0}, -40);
  raw.nodes[static_cast<std::size_t>(muse)].link.translation = {6, 2, -1};
  raw.tracks.push_back({muse, Field::kTranslation, {}});
  raw.tracks.back().track.type = anim::TrackType::kVector;
  raw.tracks.back().track.keys = {key(0, values({6, 2, -1})), key(10, values({-3, 5, 4}))};
  anim::RawCameraPath path;
  path.position.points = {values({0, 1, 9}), values({9, 1, 0}), values({0, 1, -9})};
  path.start_time = 0;
  path.end_time = 10;
  raw.nodes[static_cast<std::size_t>(cam)].path = path;
  raw.nodes[static_cast<std::size_t>(cam)].link.translation = {0.5, 0, 0};  // the node carries the path
  raw.nodes[static_cast<std::size_t>(m)].part_drivers = {{"top", "muse"}};
  const Scene scene = Scene::build(raw);
  const ViewDependentModel& model = *scene.model(m);
  ASSERT_EQ(model.partCount(), 2u);  // top, rest
  for (double frame : {0.0, 3.5, 10.0}) {
    const auto s = evaluated(scene, frame);
    Camera camera;
    ASSERT_TRUE(scene.camera(frame, s, camera));
    Eigen::Vector3d path_eye;  // a camera drives by its eye on its path, as camera() computes it
    ASSERT_TRUE(scene.driverEye(cam, frame, s, path_eye));
    EXPECT_LT((path_eye - camera.eye).norm(), kTol);
    std::array<Eigen::Vector3d, 2> views;
    ASSERT_TRUE(scene.instancePartViews(m, frame, s, camera.eye, views));
    ASSERT_EQ(model.partName(0), "top");
    Eigen::Vector3d from_muse, from_camera;
    ASSERT_TRUE(
        scene.instanceView(m, s[static_cast<std::size_t>(m)], origin(s[static_cast<std::size_t>(muse)]), from_muse));
    ASSERT_TRUE(scene.instanceView(m, s[static_cast<std::size_t>(m)], camera.eye, from_camera));
    EXPECT_LT((views[0] - from_muse).norm(), kTol) << "frame " << frame;
    EXPECT_LT((views[1] - from_camera).norm(), kTol) << "frame " << frame;
    EXPECT_GT((from_muse - from_camera).norm(), 0.1);  // the two really differ
  }
  // A wrong size or a node without parts is a violation.
  const auto s = evaluated(scene, 0);
  std::array<Eigen::Vector3d, 3> three;
  EXPECT_FALSE(scene.instancePartViews(m, 0, s, {0, 0, 9}, three));
  std::array<Eigen::Vector3d, 2> two;
  EXPECT_FALSE(scene.instancePartViews(muse, 0, s, {0, 0, 9}, two));
}

TEST(SceneInstances, BadPartDriversAreRefusedNamingTheNodeAndPart) {
  auto errorWith = [](const std::vector<RawPartDriver>& drivers, bool parts = true) {
    RawScene raw;
    raw.models.push_back(parts ? twoPartModel() : sixKeyModel());
    addNode(raw, "cow", -1, ObjectKind::kModel, 0);
    addNode(raw, "muse");
    raw.nodes[0].part_drivers = drivers;
    return errorOf([&] { raw.validate(); });
  };
  EXPECT_EQ(errorWith({{"top", "muse"}}), "");
  EXPECT_EQ(errorWith({{"rest", "muse"}}), "");
  EXPECT_THAT(errorWith({{"head", "muse"}}),
              HasSubstr("node 'cow': part driver 'head': the model has no such part (its parts: top, rest)"));
  EXPECT_THAT(errorWith({{"top", "ghost"}}), HasSubstr("part driver 'top': 'ghost' names no node"));
  EXPECT_THAT(errorWith({{"top", "cow"}}), HasSubstr("names the model node itself"));
  EXPECT_THAT(errorWith({{"top", "muse"}, {"top", "muse"}}), HasSubstr("'top': the part has two drivers"));
  EXPECT_THAT(errorWith({{"top", "muse"}}, false), HasSubstr("holds no view-dependent model with parts"));
}

}  // namespace
}  // namespace vdg::scene
