// The per-frame contract of Scene (scene.h): evaluate, fieldValue, camera and instanceView check
// their input on entry, return false on a violation having written nothing, never throw, and
// allocate nothing (counted through tests/support/allocation_counter.cpp) on valid and refused
// input alike.
#include <gtest/gtest.h>

#include <limits>
#include <vector>

#include "scene_fixtures.h"
#include "support/allocation_counter.h"

namespace vdg::scene {
namespace {

using namespace fixtures;
using vdg::testing::allocationsDuring;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr int kFrames = 60;

// Every kind of node, tracks, actions of both kinds and a path camera looking at a moving node.
RawScene busyScene() {
  RawScene s;
  s.meshes.push_back(std::make_shared<const TriMesh>(testing::uvSphere()));
  s.models.push_back(sixKeyModel());
  s.animated_models.push_back(bobbingModel(8));
  const int root = addNode(s, "root");
  const int ball = addNode(s, "ball", root, ObjectKind::kMesh, 0);
  const int head = addNode(s, "head", root, ObjectKind::kModel, 0);
  const int body = addNode(s, "body", head, ObjectKind::kAnimatedModel, 0);
  const int cam = addNode(s, "cam", -1, ObjectKind::kCamera);
  s.nodes[static_cast<std::size_t>(cam)].look_at = "ball";
  anim::RawCameraPath path;
  path.position.points = {values({0, 1, 10}), values({7, 1, 7}), values({10, 2, 0}), values({7, 3, -7})};
  path.end_time = 50;
  path.speed = anim::Ease::sine();
  path.up_samples = 64;
  s.nodes[static_cast<std::size_t>(cam)].path = path;
  anim::RawTrack t;
  t.type = anim::TrackType::kVector;
  t.interpolation = anim::Interpolation::kCatmullRom;
  t.keys = {key(0, values({0, 0, 0})), key(10, values({1, 2, 0})), key(30, values({-1, 0, 3}))};
  s.tracks.push_back({ball, Field::kTranslation, t});
  s.actions.push_back(change(root, Field::kRotation, quaternionValue(turn({0, 1, 0}, 200)), 0, 40, anim::Ease::sine()));
  s.actions.push_back(set(root, Field::kTranslation, values({1, 0, 0}), 5));
  s.actions.push_back(change(root, Field::kTranslation, values({0, 1, 0}), 0, 20));
  s.actions.push_back(change(head, Field::kSharpness, values({2}), 0, 10));
  s.actions.push_back(change(body, Field::kFrameOffset, values({3}), 10, 10));
  s.actions.push_back(change(cam, Field::kFov, values({10}), 0, 30));
  return s;
}

TEST(SceneContract, EvaluationAllocatesNothing) {
  const Scene scene = Scene::build(busyScene());
  std::vector<NodeState> states(static_cast<std::size_t>(scene.nodeCount())), short_states(2);
  bool ok = true;
  long refused = 0;
  EXPECT_EQ(allocationsDuring([&] {
              for (int i = 0; i <= kFrames; ++i) {
                const double f = -5.0 + i;
                Camera c;
                Eigen::Vector3d view;
                double v[3];
                ok = scene.evaluate(f, states) && ok;
                ok = scene.camera(f, states, c) && ok;
                ok = scene.instanceView(2, states[2], c.eye, view) && ok;
                ok = scene.instanceView(3, states[3], c.eye, view) && ok;
                ok = scene.fieldValue(0, Field::kTranslation, f, v) && ok;
                refused += !scene.evaluate(kNaN, states) + !scene.evaluate(f, short_states) +
                           !scene.fieldValue(9, Field::kTranslation, f, v) + !scene.camera(kInf, states, c) +
                           !scene.instanceView(1, states[1], c.eye, view);
              }
            }),
            0);
  EXPECT_TRUE(ok);
  EXPECT_EQ(refused, 5 * (kFrames + 1));
}

TEST(SceneContract, EvaluateRefusesAndWritesNothing) {
  const Scene scene = Scene::build(busyScene());
  NodeState marker;
  marker.model_frame = -77;
  std::vector<NodeState> states(static_cast<std::size_t>(scene.nodeCount()), marker);
  EXPECT_FALSE(scene.evaluate(kNaN, states));
  EXPECT_FALSE(scene.evaluate(kInf, states));
  EXPECT_FALSE(scene.evaluate(0, std::span<NodeState>(states).first(4)));
  std::vector<NodeState> longer(6, marker);
  EXPECT_FALSE(scene.evaluate(0, longer));
  for (const NodeState& s : states) EXPECT_EQ(s.model_frame, -77);
  for (const NodeState& s : longer) EXPECT_EQ(s.model_frame, -77);
  EXPECT_TRUE(scene.evaluate(0, states));
}

TEST(SceneContract, FieldValueRefusesAndWritesNothing) {
  const Scene scene = Scene::build(busyScene());
  double v[4] = {-7, -7, -7, -7};
  EXPECT_FALSE(scene.fieldValue(-1, Field::kTranslation, 0, std::span<double>(v, 3)));
  EXPECT_FALSE(scene.fieldValue(5, Field::kTranslation, 0, std::span<double>(v, 3)));
  EXPECT_FALSE(scene.fieldValue(0, static_cast<Field>(8), 0, std::span<double>(v, 1)));
  EXPECT_FALSE(scene.fieldValue(1, Field::kSharpness, 0, std::span<double>(v, 1)));  // a mesh has none
  EXPECT_FALSE(scene.fieldValue(0, Field::kColor, 0, std::span<double>(v, 3)));      // nor a group
  EXPECT_FALSE(scene.fieldValue(0, Field::kTranslation, kNaN, std::span<double>(v, 3)));
  EXPECT_FALSE(scene.fieldValue(0, Field::kTranslation, 0, std::span<double>(v, 4)));
  EXPECT_FALSE(scene.fieldValue(0, Field::kRotation, 0, std::span<double>(v, 3)));
  for (double x : v) EXPECT_EQ(x, -7);
  EXPECT_TRUE(scene.fieldValue(0, Field::kRotation, 0, std::span<double>(v, 4)));
}

TEST(SceneContract, CameraRefusesAndWritesNothing) {
  const Scene scene = Scene::build(busyScene());
  std::vector<NodeState> states(static_cast<std::size_t>(scene.nodeCount()));
  ASSERT_TRUE(scene.evaluate(3, states));
  Camera untouched;
  untouched.eye = {-9, -9, -9};
  Camera c = untouched;
  EXPECT_FALSE(scene.camera(kNaN, states, c));
  EXPECT_FALSE(scene.camera(3, std::span<const NodeState>(states).first(3), c));
  // A singular camera node.
  std::vector<NodeState> bad = states;
  bad[4].world.topLeftCorner<3, 3>().setZero();
  EXPECT_FALSE(scene.camera(3, bad, c));
  bad = states;
  bad[4].world(0, 0) = kNaN;
  EXPECT_FALSE(scene.camera(3, bad, c));
  // The centre of interest on the eye.
  RawScene raw;
  addNode(raw, "cam", -1, ObjectKind::kCamera);
  addNode(raw, "there");
  raw.nodes[0].look_at = "there";
  const Scene on_eye = Scene::build(raw);
  EXPECT_FALSE(on_eye.camera(0, evaluated(on_eye, 0), c));
  // An animated fov pushed out of (0, 180).
  RawScene wide;
  addNode(wide, "cam", -1, ObjectKind::kCamera);
  wide.actions.push_back(change(0, Field::kFov, values({200}), 0, 1));
  const Scene w = Scene::build(wide);
  EXPECT_FALSE(w.camera(1, evaluated(w, 1), c));
  EXPECT_EQ(c.eye, untouched.eye);
  EXPECT_TRUE(scene.camera(3, states, c));
}

TEST(SceneContract, InstanceViewRefusesAndWritesNothing) {
  const Scene scene = Scene::build(busyScene());
  std::vector<NodeState> states(static_cast<std::size_t>(scene.nodeCount()));
  ASSERT_TRUE(scene.evaluate(0, states));
  const Eigen::Vector3d untouched(-5, -5, -5);
  Eigen::Vector3d view = untouched;
  const Eigen::Vector3d eye(0, 0, 20);
  EXPECT_FALSE(scene.instanceView(-1, states[2], eye, view));
  EXPECT_FALSE(scene.instanceView(5, states[2], eye, view));
  EXPECT_FALSE(scene.instanceView(0, states[0], eye, view));  // a group
  EXPECT_FALSE(scene.instanceView(1, states[1], eye, view));  // a plain mesh
  EXPECT_FALSE(scene.instanceView(4, states[4], eye, view));  // a camera
  EXPECT_FALSE(scene.instanceView(2, states[2], Eigen::Vector3d(kNaN, 0, 0), view));
  NodeState singular = states[2];
  singular.object.col(1).setZero();
  EXPECT_FALSE(scene.instanceView(2, singular, eye, view));
  // The eye on the model's centre.
  const Eigen::Vector4d centre = states[2].object * Eigen::Vector4d(0, 0, 0, 1);
  const Eigen::Vector3d centre3 = centre.head<3>() + states[2].object.topLeftCorner<3, 3>() * scene.model(2)->center();
  EXPECT_FALSE(scene.instanceView(2, states[2], centre3, view));
  EXPECT_EQ(view, untouched);
  EXPECT_TRUE(scene.instanceView(2, states[2], eye, view));
}

TEST(SceneContract, NamesAndDimensions) {
  for (int i = 0; i < kFieldCount; ++i) {
    const Field f = static_cast<Field>(i);
    ASSERT_TRUE(fieldFromName(fieldName(f)).has_value());
    EXPECT_EQ(*fieldFromName(fieldName(f)), f);
  }
  EXPECT_FALSE(fieldFromName("position").has_value());
  EXPECT_FALSE(fieldFromName("").has_value());
  EXPECT_EQ(fieldDimension(Field::kRotation), 4);
  EXPECT_EQ(fieldDimension(Field::kColor), 3);
  EXPECT_EQ(fieldDimension(Field::kFrameOffset), 1);
  EXPECT_STREQ(objectKindName(ObjectKind::kAnimatedModel), "animated-model");
  EXPECT_STREQ(fieldName(Field::kFrameOffset), "frame_offset");
}

}  // namespace
}  // namespace vdg::scene
