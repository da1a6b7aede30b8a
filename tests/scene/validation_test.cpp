// RawScene::validate and Scene::build: every invalid input is refused with one line naming the
// node, track or action (tests compare whole messages).
#include <gtest/gtest.h>

#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "scene_fixtures.h"
#include "support/error_of.h"

namespace vdg::scene {
namespace {

using namespace fixtures;
using vdg::testing::errorOf;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// root (group), ball (mesh 0), head (model 0), cam (camera).
RawScene validScene() {
  static const std::shared_ptr<const ViewDependentModel> model = sixKeyModel();
  RawScene s;
  s.meshes.push_back(std::make_shared<const TriMesh>(testing::uvSphere()));
  s.models.push_back(model);
  addNode(s, "root");
  addNode(s, "ball", 0, ObjectKind::kMesh, 0);
  addNode(s, "head", 0, ObjectKind::kModel, 0);
  addNode(s, "cam", -1, ObjectKind::kCamera);
  return s;
}

anim::RawTrack translationTrack(int dimension) {
  anim::RawTrack t;
  t.type = anim::TrackType::kVector;
  Eigen::VectorXd v = Eigen::VectorXd::Zero(dimension);
  t.keys = {key(0, v), key(1, v)};
  return t;
}

struct Case {
  const char* what;
  std::function<void(RawScene&)> mutate;
  std::string message;
};

TEST(SceneValidation, ValidSceneBuilds) {
  const RawScene s = validScene();
  EXPECT_EQ(errorOf([&] { s.validate(); }), "");
  const Scene scene = Scene::build(s);
  EXPECT_EQ(scene.nodeCount(), 4);
  EXPECT_EQ(scene.nodeName(2), "head");
  EXPECT_EQ(scene.findNode("cam"), 3);
  EXPECT_EQ(scene.findNode("nobody"), -1);
  EXPECT_EQ(scene.kind(1), ObjectKind::kMesh);
  EXPECT_EQ(scene.parent(1), 0);
  EXPECT_NE(scene.mesh(1), nullptr);
  EXPECT_EQ(scene.mesh(2), nullptr);
  EXPECT_NE(scene.model(2), nullptr);
  EXPECT_EQ(scene.animatedModel(2), nullptr);
  EXPECT_EQ(errorOf([&] { (void)scene.nodeName(4); }), "scene: node 4 out of range (the scene has 4 nodes)");
  EXPECT_EQ(errorOf([&] { (void)scene.rawNode(-1); }), "scene: node -1 out of range (the scene has 4 nodes)");
}

TEST(SceneValidation, EveryMessage) {
  const std::vector<Case> cases = {
      {"no nodes", [](RawScene& s) { s.nodes.clear(); }, "scene: a scene needs at least one node"},
      {"too many nodes", [](RawScene& s) { s.nodes.resize(kMaxSceneNodes + 1); },
       "scene: 100001 nodes, more than the 100000 a scene may have"},
      {"empty name", [](RawScene& s) { s.nodes[1].name = ""; }, "scene: node 1: empty name"},
      {"dotted name", [](RawScene& s) { s.nodes[1].name = "a.b"; },
       "scene: node 'a.b': the name contains '.' (it separates node and field, as in 'earth.rotation')"},
      {"duplicate name", [](RawScene& s) { s.nodes[2].name = "ball"; },
       "scene: node 'ball': duplicate name (node 1 has it too)"},
      {"later parent", [](RawScene& s) { s.nodes[1].parent = 2; },
       "scene: node 'ball': parent 2 is not an earlier node (-1 for a root, or 0..0)"},
      {"own parent", [](RawScene& s) { s.nodes[0].parent = 0; },
       "scene: node 'root': parent 0 is not an earlier node (-1 for a root, or 0..-1)"},
      {"unknown kind", [](RawScene& s) { s.nodes[0].kind = static_cast<ObjectKind>(9); },
       "scene: node 'root': unknown object kind 9"},
      {"object out of range", [](RawScene& s) { s.nodes[1].object = 3; },
       "scene: node 'ball': object 3 out of range (the scene has 1 meshes)"},
      {"null object", [](RawScene& s) { s.models[0] = nullptr; }, "scene: node 'head': object 0 of models is null"},
      {"object on a group", [](RawScene& s) { s.nodes[0].object = 0; },
       "scene: node 'root': a group holds no object (object 0, expected -1)"},
      {"object on a camera", [](RawScene& s) { s.nodes[3].object = 0; },
       "scene: node 'cam': a camera holds no object (object 0, expected -1)"},
      {"zero scale",
       [](RawScene& s) {
         s.nodes[0].link.scale = {1, 0, 1};
       },
       "scene: node 'root': link scale must be finite and non-zero in every component"},
      {"zero quaternion", [](RawScene& s) { s.nodes[1].placement.rotation.coeffs().setZero(); },
       "scene: node 'ball': placement rotation is a zero or non-finite quaternion"},
      {"non-finite translation", [](RawScene& s) { s.nodes[0].link.translation.x() = kNaN; },
       "scene: node 'root': link translation is not finite"},
      {"colour", [](RawScene& s) { s.nodes[1].color[1] = 1.5f; },
       "scene: node 'ball': color component 1 (1.5) is outside [0, 1]"},
      {"sharpness", [](RawScene& s) { s.nodes[2].sharpness = kNaN; }, "scene: node 'head': sharpness is not finite"},
      {"frame offset", [](RawScene& s) { s.nodes[2].frame_offset = -kNaN; },
       "scene: node 'head': frame_offset is not finite"},
      {"fov", [](RawScene& s) { s.nodes[3].fov_deg = 180; }, "scene: node 'cam': fov 180 degrees is outside (0, 180)"},
      {"ortho height", [](RawScene& s) { s.nodes[3].ortho_height = -1; },
       "scene: node 'cam': ortho_height -1 must be finite and >= 0"},
      {"path on a mesh", [](RawScene& s) { s.nodes[1].path = anim::RawCameraPath{}; },
       "scene: node 'ball': a path on a mesh node (only cameras follow paths)"},
      {"look_at on a group", [](RawScene& s) { s.nodes[0].look_at = "ball"; },
       "scene: node 'root': look_at on a group node (only cameras look at nodes)"},
      {"look_at nobody", [](RawScene& s) { s.nodes[3].look_at = "nobody"; },
       "scene: node 'cam': look_at 'nobody' names no node"},
      {"look_at itself", [](RawScene& s) { s.nodes[3].look_at = "cam"; },
       "scene: node 'cam': look_at names the camera itself"},
      {"track node",
       [](RawScene& s) {
         s.tracks.push_back({9, Field::kTranslation, translationTrack(3)});
       },
       "scene: track 0: node 9 out of range (the scene has 4 nodes)"},
      {"track field",
       [](RawScene& s) {
         s.tracks.push_back({0, static_cast<Field>(8), translationTrack(3)});
       },
       "scene: track 0: unknown field 8"},
      {"track on a field the kind lacks",
       [](RawScene& s) {
         s.tracks.push_back({3, Field::kColor, translationTrack(3)});
       },
       "scene: track 'cam.color': a camera node has no field 'color'"},
      {"sharpness track on a mesh",
       [](RawScene& s) {
         s.tracks.push_back({1, Field::kSharpness, translationTrack(1)});
       },
       "scene: track 'ball.sharpness': a mesh node has no field 'sharpness'"},
      {"track type",
       [](RawScene& s) {
         s.tracks.push_back({0, Field::kRotation, translationTrack(4)});
       },
       "scene: track 'root.rotation': field 'rotation' needs a rotation track, not a vector track"},
      {"scalar track on a vector field",
       [](RawScene& s) {
         anim::RawTrack t = translationTrack(1);
         t.type = anim::TrackType::kScalar;
         s.tracks.push_back({0, Field::kScale, t});
       },
       "scene: track 'root.scale': field 'scale' has 3 numbers, not a scalar track"},
      {"track size",
       [](RawScene& s) {
         s.tracks.push_back({0, Field::kTranslation, translationTrack(2)});
       },
       "scene: track 'root.translation': field 'translation' has 3 numbers, the track's keys have 2"},
      {"second track",
       [](RawScene& s) {
         s.tracks.push_back({0, Field::kTranslation, translationTrack(3)});
         s.tracks.push_back({0, Field::kTranslation, translationTrack(3)});
       },
       "scene: track 'root.translation': the field already has a track (track 0)"},
      {"track the library refuses",
       [](RawScene& s) {
         anim::RawTrack t = translationTrack(3);
         t.keys[1].time = 0;
         s.tracks.push_back({0, Field::kTranslation, t});
       },
       "scene: track 'root.translation': 'keys'[1]: 'time' 0 must be greater than the previous key's 0"},
      {"too many actions", [](RawScene& s) { s.actions.resize(kMaxSceneActions + 1); },
       "scene: 1000001 actions, more than the 1000000 a scene may have"},
      {"action node",
       [](RawScene& s) {
         s.actions.push_back(set(-1, Field::kTranslation, values({0, 0, 0}), 0));
       },
       "scene: action 0: node -1 out of range (the scene has 4 nodes)"},
      {"action field", [](RawScene& s) { s.actions.push_back(set(0, static_cast<Field>(-1), values({0}), 0)); },
       "scene: action 0: unknown field -1"},
      {"action kind",
       [](RawScene& s) {
         s.actions.push_back(set(0, Field::kVisible, values({0}), 0));
         s.actions.back().kind = static_cast<RawAction::Kind>(5);
       },
       "scene: action 0 (root.visible): unknown kind 5"},
      {"action on a field the kind lacks",
       [](RawScene& s) { s.actions.push_back(set(1, Field::kSharpness, values({2}), 0)); },
       "scene: action 0 (ball.sharpness): a mesh node has no field 'sharpness'"},
      {"fov on a model", [](RawScene& s) { s.actions.push_back(set(2, Field::kFov, values({2}), 0)); },
       "scene: action 0 (head.fov): a model node has no field 'fov'"},
      {"action size",
       [](RawScene& s) {
         s.actions.push_back(set(0, Field::kTranslation, values({1, 2}), 0));
       },
       "scene: action 1 (root.translation): the value has 2 numbers, field 'translation' has 3"},
      {"action value",
       [](RawScene& s) {
         s.actions.push_back(change(0, Field::kScale, values({1, kNaN, 1}), 0, 1));
       },
       "scene: action 1 (root.scale): the value is not finite"},
      {"action rotation",
       [](RawScene& s) {
         s.actions.push_back(change(0, Field::kRotation, values({0, 0, 0, 0}), 0, 1));
       },
       "scene: action 1 (root.rotation): the rotation is a zero quaternion"},
      {"SET zero scale",
       [](RawScene& s) {
         s.actions.push_back(set(0, Field::kScale, values({1, 1, 0}), 0));
       },
       "scene: action 1 (root.scale): a scale must be non-zero in every component"},
      {"SET colour",
       [](RawScene& s) {
         s.actions.push_back(set(1, Field::kColor, values({0, 0, 2}), 0));
       },
       "scene: action 1 (ball.color): color component 2 (2) is outside [0, 1]"},
      {"SET fov", [](RawScene& s) { s.actions.push_back(set(3, Field::kFov, values({0}), 0)); },
       "scene: action 1 (cam.fov): fov 0 degrees is outside (0, 180)"},
      {"action frames", [](RawScene& s) { s.actions.push_back(change(0, Field::kVisible, values({1}), 0, kNaN)); },
       "scene: action 1 (root.visible): its frames must be finite"},
      {"backwards CHANGE", [](RawScene& s) { s.actions.push_back(change(0, Field::kVisible, values({1}), 2, 1)); },
       "scene: action 1 (root.visible): the CHANGE ends at frame 1, before it starts at frame 2"},
      {"track and actions",
       [](RawScene& s) {
         s.tracks.push_back({0, Field::kTranslation, translationTrack(3)});
         s.actions.push_back(set(0, Field::kTranslation, values({0, 0, 0}), 0));
       },
       "scene: action 1 (root.translation): the field also has a track (track 0); give a field a track or actions, not "
       "both"},
      {"camera nobody", [](RawScene& s) { s.camera = "nobody"; }, "scene: camera 'nobody': no node has that name"},
      {"camera not a camera", [](RawScene& s) { s.camera = "ball"; },
       "scene: camera 'ball': a mesh node, not a camera"},
  };
  for (const Case& c : cases) {
    RawScene s = validScene();
    // Where the message names action 1, a valid action comes first (the index counts all actions).
    if (c.message.find("action 1") != std::string::npos) s.actions.push_back(set(0, Field::kVisible, values({1}), 0));
    c.mutate(s);
    EXPECT_EQ(errorOf([&] { s.validate(); }), c.message) << c.what;
    EXPECT_EQ(errorOf([&] { (void)Scene::build(s); }), c.message) << c.what;
  }
}

TEST(SceneValidation, PathTheLibraryRefusesAndWhere) {
  RawScene s = validScene();
  anim::RawCameraPath path;
  path.position.points = {values({0, 0, 1}), values({1, 0, 1})};
  path.end_time = 0;  // not after start_time
  s.nodes[3].path = path;
  const std::string expected = errorOf([&] { (void)anim::CameraPath::build(path, "shot.lua: node 'cam': path"); });
  ASSERT_NE(expected, "");
  EXPECT_EQ(errorOf([&] { s.validate("shot.lua"); }), expected);
  // Hostile names stay on one line.
  RawScene t = validScene();
  t.nodes[1].name = "x\ny";
  t.nodes[2].name = "x\ny";
  EXPECT_EQ(errorOf([&] { t.validate(); }), "scene: node 'x\\ny': duplicate name (node 1 has it too)");
}

}  // namespace
}  // namespace vdg::scene
