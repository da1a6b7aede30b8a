// The editing document of vdg studio: strokes equal the edit operations `vdg deform` applies,
// undo and redo restore shapes exactly, saving writes what the command-line tools read back, and
// the autosave brings back the strokes of a session that died.
#include <gtest/gtest.h>

#include <filesystem>

#include "support/error_of.h"
#include "support/test_meshes.h"
#include "vdg/deform/edits.h"
#include "vdg/deform/key_edit.h"
#include "vdg/io/edit_script.h"
#include "vdg/io/manifest.h"
#include "vdg/io/obj.h"
#include "vdg/studio/navigation.h"
#include "vdg/studio/session.h"

namespace vdg::studio {
namespace {

using vdg::testing::errorOf;
using vdg::testing::TempDir;
namespace fs = std::filesystem;

// OBJ text keeps 9 significant digits or so; positions read back compare within this.
constexpr double kFileTol = 1e-5;

struct Fixture : ::testing::Test {
  TempDir dir;
  std::string obj;
  void SetUp() override {
    obj = dir.file("ball.obj");
    writeObj(obj, vdg::testing::uvSphere(10, 16));
  }
  // A session on the sphere with a new key 'k' seen from the front-right.
  Session withKey() {
    Session s = Session::open(obj);
    s.camera = orbit(s.camera, 30, 10);
    s.newKey("k");
    return s;
  }
  // Saves ball.vdg.json with key 'k' made by one drag.
  void saveOneStrokeKey() {
    Session s = withKey();
    stroke(s, {330, 250});
    s.saveKey();
  }
  // One drag from the image centre's vertex.
  static void stroke(Session& s, const Eigen::Vector2d& to) {
    s.beginStroke(centerVertex(s), {320, 240});
    s.updateStroke(to);
    s.endStroke();
  }
  // The vertex nearest the image centre (front of the sphere).
  static std::int32_t centerVertex(const Session& s) {
    return *s.pick(Eigen::Vector2d(s.image_width / 2.0, s.image_height / 2.0));
  }
};

double maxDiff(std::span<const float> a, std::span<const float> b) {
  double d = 0;
  for (std::size_t i = 0; i < a.size(); ++i) d = std::max(d, std::abs(static_cast<double>(a[i]) - b[i]));
  return d;
}

TEST_F(Fixture, OpeningAMeshWritesNothingAndNamesItsManifest) {
  const Session s = Session::open(obj);
  EXPECT_EQ(s.manifestPath(), (fs::absolute(dir.path()) / "ball.vdg.json").lexically_normal().string());
  EXPECT_FALSE(fs::exists(s.manifestPath()));
  EXPECT_EQ(s.currentKey(), -1);
  EXPECT_EQ(s.recoverableStrokes(), 0u);
  EXPECT_NEAR(s.falloff.radius, 0.15 * s.baseDiagonal(), 1e-12);
}

TEST_F(Fixture, OpeningRefusesMissingFilesAndAnExistingManifest) {
  EXPECT_EQ(errorOf([&] { Session::open(dir.file("nope.obj")); }), dir.file("nope.obj") + ": no such file");
  vdg::testing::writeText(dir.file("ball.vdg.json"), "{}");
  EXPECT_NE(errorOf([&] { Session::open(obj); }).find("already exists: open it"), std::string::npos);
  vdg::testing::writeText(dir.file("bad.obj"), "v 1 2\nf 1 2 3\n");
  EXPECT_NE(errorOf([&] { Session::open(dir.file("bad.obj")); }), "");
}

// The editor warns about key views nearly the same direction (the decision is viewdep's:
// kNearlySameViewDeg), and says nothing when the key views are well apart.
TEST_F(Fixture, KeysNearlyTheSameDirectionAreWarnedAbout) {
  const std::string manifest = dir.file("close.vdg.json");
  vdg::testing::writeText(manifest, R"({"version": 2, "base": "ball.obj", "keys": [
      {"name": "front", "mesh": "ball.obj", "view": [0, 0, 1]},
      {"name": "almost_front", "mesh": "ball.obj", "view": [0.04, 0, 1]},
      {"name": "side", "mesh": "ball.obj", "view": [1, 0, 0]}]})");
  const std::vector<std::string> warnings = Session::open(manifest).keyViewWarnings();
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_EQ(warnings[0],
            "keys 'front' and 'almost_front' are only 2.3 degrees apart: the weights flip between them (a "
            "near-degenerate hull triangle)");
  vdg::testing::writeText(manifest, R"({"version": 2, "base": "ball.obj", "keys": [
      {"name": "front", "mesh": "ball.obj", "view": [0, 0, 1]},
      {"name": "side", "mesh": "ball.obj", "view": [1, 0, 0]}]})");
  EXPECT_TRUE(Session::open(manifest).keyViewWarnings().empty());
}

TEST_F(Fixture, PickFindsTheVertexUnderThePixel) {
  Session s = withKey();
  const auto& p = s.baseMesh().positions;
  int checked = 0;
  for (std::int32_t v = 0; v < static_cast<std::int32_t>(p.size() / 3); ++v) {
    const Eigen::Vector3d x(p[3 * v], p[3 * v + 1], p[3 * v + 2]);
    // Vertices facing the camera well (a vertex on the rim may be hidden by its neighbours).
    if ((s.camera.eye - x).normalized().dot(x.normalized()) < 0.5) continue;
    const Eigen::Vector2d px = project(s.camera, s.image_width, s.image_height, x).pixel;
    EXPECT_EQ(s.pick(px), v);
    ++checked;
  }
  EXPECT_GT(checked, 10);
  EXPECT_EQ(s.pick(Eigen::Vector2d(2, 2)), std::nullopt);  // a corner: the ray misses the ball
}

TEST_F(Fixture, ADragStrokeIsTheDragOpOfVdgDeform) {
  Session s = withKey();
  const std::int32_t v = centerVertex(s);
  const Eigen::Vector2d a(s.image_width / 2.0, s.image_height / 2.0), b = a + Eigen::Vector2d(37, -21);
  s.beginStroke(v, a);
  s.updateStroke(a + Eigen::Vector2d(10, 5));
  s.updateStroke(b);
  const std::vector<float> live(s.positions().begin(), s.positions().end());
  s.endStroke();
  EXPECT_EQ(s.strokeCount(), 1u);
  EXPECT_TRUE(s.dirty());

  // The same operation through the deform library, as `vdg deform --ops` runs it.
  RawViewDependentModel raw = s.model();
  raw.keys[0].mesh.positions = raw.base.positions;
  EditLog log;
  const DragOp op{{v, s.metric, s.falloff, std::nullopt, std::nullopt}, Eigen::Vector2d::Zero(), b - a};
  deformKey(raw, 0, log, std::vector<EditOp>{op}, std::array<int, 2>{s.image_width, s.image_height}, "test");
  EXPECT_EQ(maxDiff(s.positions(), raw.keys[0].mesh.positions), 0.0);
  EXPECT_LT(maxDiff(live, raw.keys[0].mesh.positions), 1e-6);  // what was shown while dragging
  EXPECT_GT(maxDiff(s.positions(), s.baseMesh().positions), 0.01);
}

TEST_F(Fixture, EveryToolMovesTheSelectionAndAStrokeThatDoesNotMoveIsNoStroke) {
  for (const Tool tool : {Tool::kDrag, Tool::kPushPull, Tool::kRotate, Tool::kScale}) {
    Session s = withKey();
    s.tool = tool;
    const std::int32_t v = centerVertex(s);
    const Eigen::Vector2d a(300, 300);
    s.beginStroke(v, a);
    s.endStroke();
    EXPECT_EQ(s.strokeCount(), 0u) << toolName(tool);
    s.beginStroke(v, a);
    s.updateStroke(a + Eigen::Vector2d(40, 40));
    s.endStroke();
    EXPECT_EQ(s.strokeCount(), 1u) << toolName(tool);
    EXPECT_GT(maxDiff(s.positions(), s.baseMesh().positions), 1e-3) << toolName(tool);
  }
}

TEST_F(Fixture, UndoAndRedoRestoreShapesExactly) {
  Session s = withKey();
  const std::int32_t v = centerVertex(s);
  std::vector<std::vector<float>> shapes{std::vector<float>(s.positions().begin(), s.positions().end())};
  for (int i = 1; i <= 3; ++i) {
    s.beginStroke(v, {100, 100});
    s.updateStroke({100.0 + 10 * i, 100.0 - 7 * i});
    s.endStroke();
    shapes.emplace_back(s.positions().begin(), s.positions().end());
  }
  EXPECT_FALSE(s.canRedo());
  for (int i = 2; i >= 0; --i) {
    ASSERT_TRUE(s.canUndo());
    s.undo();
    EXPECT_EQ(maxDiff(s.positions(), shapes[i]), 0.0) << i;
  }
  EXPECT_FALSE(s.canUndo());
  EXPECT_FALSE(s.dirty());
  for (int i = 1; i <= 3; ++i) {
    s.redo();
    EXPECT_EQ(maxDiff(s.positions(), shapes[i]), 0.0) << i;
  }
  // A stroke after an undo drops the strokes undone.
  s.undo();
  s.beginStroke(v, {100, 100});
  s.updateStroke({90, 120});
  s.endStroke();
  EXPECT_FALSE(s.canRedo());
  EXPECT_EQ(s.strokeCount(), 3u);
}

TEST_F(Fixture, SavingWritesAModelTheCommandLineToolsRead) {
  Session s = withKey();
  const std::int32_t v = centerVertex(s);
  s.beginStroke(v, {320, 240});
  s.updateStroke({360, 200});
  s.endStroke();
  s.saveKey();
  EXPECT_FALSE(s.dirty());
  EXPECT_FALSE(fs::exists(s.recoveryPath()));
  const RawViewDependentModel raw = loadManifest(s.manifestPath());
  ASSERT_EQ(raw.keys.size(), 1u);
  EXPECT_EQ(raw.keys[0].name, "k");
  ASSERT_TRUE(raw.keys[0].camera);
  EXPECT_LT((raw.keys[0].camera->eye - s.model().keys[0].camera->eye).norm(), 1e-9);
  EXPECT_LT(maxDiff(raw.keys[0].mesh.positions, s.positions()), kFileTol);
  // The edit log replays to the key (what `vdg deform --undo` relies on).
  const EditLog log = readEditLog(editLogPath(dir.file("k.obj")));
  ASSERT_EQ(log.entries.size(), 1u);
  EXPECT_LT(maxDiff(replayEditLog(raw.base, log, "log"), s.positions()), kFileTol);

  // A second stroke and save append to the log; the manifest is not rewritten for a saved key.
  s.beginStroke(v, {320, 240});
  s.updateStroke({300, 260});
  s.endStroke();
  s.saveKey();
  EXPECT_EQ(readEditLog(editLogPath(dir.file("k.obj"))).entries.size(), 2u);
}

TEST_F(Fixture, EditingAKeyUsesItsCameraAndAppendsToItsLog) {
  saveOneStrokeKey();
  Session s = Session::open(dir.file("ball.vdg.json"));
  EXPECT_EQ(s.currentKey(), -1);
  s.editKey(0);
  EXPECT_LT((s.camera.eye - s.model().keys[0].camera->eye).norm(), 1e-9);
  s.beginStroke(centerVertex(s), {320, 240});
  s.updateStroke({310, 230});
  s.endStroke();
  EXPECT_NE(errorOf([&] { s.editKey(0); }).find("unsaved strokes"), std::string::npos);
  s.saveKey();
  EXPECT_EQ(readEditLog(editLogPath(dir.file("k.obj"))).entries.size(), 2u);
}

TEST_F(Fixture, AnEmptyDraftKeyGivesWayToTheKeyChosen) {
  saveOneStrokeKey();
  Session s = Session::open(dir.file("ball.vdg.json"));
  s.camera = orbit(s.camera, -60, 0);
  s.newKey("draft");
  ASSERT_EQ(s.model().keys.size(), 2u);
  s.editKey(1);  // the draft itself: it stays current
  EXPECT_EQ(s.currentKey(), 1);
  EXPECT_TRUE(s.currentKeyIsNew());
  s.editKey(0);  // another key: the draft, never stroked, is dropped
  EXPECT_EQ(s.currentKey(), 0);
  EXPECT_EQ(s.model().keys.size(), 1u);
  EXPECT_EQ(s.model().keys[0].name, "k");
}

TEST_F(Fixture, AKeySharingItsMeshFileIsNotEdited) {
  saveOneStrokeKey();
  // A second key, seen from the other side, listed with the first key's mesh file.
  RawViewDependentModel raw = loadManifest(dir.file("ball.vdg.json"));
  RawKey twin = raw.keys[0];
  twin.name = "twin";
  twin.camera.reset();
  twin.view = -raw.keys[0].view;
  raw.keys.push_back(twin);
  saveManifest(dir.file("ball.vdg.json"), raw);
  Session s = Session::open(dir.file("ball.vdg.json"));
  EXPECT_NE(errorOf([&] { s.editKey(1); }).find("shares its mesh file"), std::string::npos);
  EXPECT_EQ(s.currentKey(), -1);
}

TEST_F(Fixture, AFailedSaveChangesNothing) {
  Session s = withKey();
  s.beginStroke(centerVertex(s), {320, 240});
  s.updateStroke({330, 250});
  s.endStroke();
  // The key's mesh path is taken by a folder: the transaction refuses before writing anything.
  fs::create_directories(dir.file("k.obj"));
  EXPECT_NE(errorOf([&] { s.saveKey(); }), "");
  EXPECT_FALSE(fs::exists(s.manifestPath()));
  EXPECT_FALSE(fs::exists(dir.file("k.edits.json")));
  EXPECT_TRUE(s.dirty());
  EXPECT_TRUE(s.currentKeyIsNew());
}

TEST_F(Fixture, NewKeysFollowTheKeyNameRule) {
  Session s = Session::open(obj);
  EXPECT_NE(errorOf([&] { s.newKey("../evil"); }).find("not allowed"), std::string::npos);
  vdg::testing::writeText(dir.file("taken.obj"), "x");
  EXPECT_NE(errorOf([&] { s.newKey("taken"); }).find("already exists"), std::string::npos);
  EXPECT_EQ(s.currentKey(), -1);
  EXPECT_NE(errorOf([&] { s.beginStroke(0, {1, 1}); }).find("no key to edit"), std::string::npos);
}

TEST_F(Fixture, TheAutosaveBringsBackTheStrokesOfASessionThatDied) {
  std::vector<float> expected;
  {
    Session s = withKey();
    const std::int32_t v = centerVertex(s);
    for (int i = 0; i < 2; ++i) {
      s.beginStroke(v, {320, 240});
      s.updateStroke({330.0 + 9 * i, 220});
      s.endStroke();
    }
    expected.assign(s.positions().begin(), s.positions().end());
    EXPECT_TRUE(fs::exists(s.recoveryPath()));
    // The session dies here without saving (its destructor writes nothing).
  }
  Session s = Session::open(obj);
  ASSERT_EQ(s.recoverableStrokes(), 2u);
  s.recover();
  EXPECT_EQ(s.currentKey(), 0);
  EXPECT_TRUE(s.currentKeyIsNew());
  EXPECT_EQ(maxDiff(s.positions(), expected), 0.0);
  s.saveKey();
  EXPECT_FALSE(fs::exists(s.recoveryPath()));
  EXPECT_LT(maxDiff(loadManifest(s.manifestPath()).keys[0].mesh.positions, expected), kFileTol);
}

TEST_F(Fixture, RecoveryOfASavedKeyKeepsItsEarlierLog) {
  std::vector<float> expected;
  {
    Session s = withKey();
    const std::int32_t v = centerVertex(s);
    s.beginStroke(v, {320, 240});
    s.updateStroke({340, 240});
    s.endStroke();
    s.saveKey();
    s.beginStroke(v, {320, 240});
    s.updateStroke({320, 200});
    s.endStroke();
    expected.assign(s.positions().begin(), s.positions().end());
  }
  Session s = Session::open(dir.file("ball.vdg.json"));
  ASSERT_EQ(s.recoverableStrokes(), 1u);
  s.recover();
  EXPECT_LT(maxDiff(s.positions(), expected), kFileTol);
  s.saveKey();
  EXPECT_EQ(readEditLog(editLogPath(dir.file("k.obj"))).entries.size(), 2u);
}

TEST_F(Fixture, DiscardingTheRecoveryRemovesIt) {
  {
    Session s = withKey();
    s.beginStroke(centerVertex(s), {320, 240});
    s.updateStroke({340, 240});
    s.endStroke();
  }
  Session s = Session::open(obj);
  EXPECT_EQ(s.recoverableStrokes(), 1u);
  s.discardRecovery();
  EXPECT_EQ(s.recoverableStrokes(), 0u);
  EXPECT_FALSE(fs::exists(s.recoveryPath()));
}

TEST_F(Fixture, AlignmentRecoversTheCameraThatMadeThePairs) {
  Session s = Session::open(obj);
  Camera truth;
  truth.eye = {1.5, 0.8, 4.0};
  truth.target = {0.1, -0.1, 0};
  truth.fov_deg = 35;
  const auto& p = s.baseMesh().positions;
  for (std::int32_t v = 0; v < static_cast<std::int32_t>(p.size() / 3); v += 7) {
    const Eigen::Vector3d x(p[3 * v], p[3 * v + 1], p[3 * v + 2]);
    s.pairs.push_back({v, project(truth, s.image_width, s.image_height, x).pixel});
  }
  const AlignResult r = s.solveAlignment(false);
  EXPECT_LT(r.rms_px, 1e-6);
  EXPECT_LT((r.camera.eye - truth.eye).norm(), 1e-6);
  s.pairs.resize(3);
  EXPECT_NE(errorOf([&] { s.solveAlignment(false); }), "");
}

}  // namespace
TEST_F(Fixture, FeatureLinesAreOneUndoableStrokeEqualToTheLinesOp) {
  Session s = withKey();
  EXPECT_NE(errorOf([&] { s.applyLines(); }).find("no feature lines"), std::string::npos);
  const Eigen::Vector2d c(s.image_width / 2.0, s.image_height / 2.0);
  s.line_pairs = {{c - Eigen::Vector2d(0, 60), c + Eigen::Vector2d(0, 60), c - Eigen::Vector2d(-12, 60),
                   c + Eigen::Vector2d(12, 60)}};
  const LinesOp op{s.line_pairs, s.line_settings};
  s.applyLines();
  EXPECT_TRUE(s.line_pairs.empty());
  EXPECT_EQ(s.strokeCount(), 1u);
  RawViewDependentModel raw = s.model();
  raw.keys[0].mesh.positions = raw.base.positions;
  EditLog log;
  deformKey(raw, 0, log, std::vector<EditOp>{op}, std::array<int, 2>{s.image_width, s.image_height}, "test");
  EXPECT_EQ(maxDiff(s.positions(), raw.keys[0].mesh.positions), 0.0);
  EXPECT_GT(maxDiff(s.positions(), s.baseMesh().positions), 0.01);
  s.undo();
  EXPECT_EQ(maxDiff(s.positions(), s.baseMesh().positions), 0.0);
  // Snapped: the model side lands on the sphere's outline, away from the centre line drawn.
  s.line_pairs = {{c, c + Eigen::Vector2d(0, 40), c + Eigen::Vector2d(5, 0), c + Eigen::Vector2d(5, 40)}};
  s.applyLines(true);
  ASSERT_EQ(s.strokeCount(), 1u);
}

}  // namespace vdg::studio
