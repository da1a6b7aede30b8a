// The editing document of vdg studio: strokes equal the edit operations `vdg deform` applies,
// undo and redo restore shapes exactly, saving writes what the command-line tools read back, and
// the autosave brings back the strokes of a session that died.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <memory>

#include "support/error_of.h"
#include "support/test_meshes.h"
#include "vdg/deform/edits.h"
#include "vdg/deform/key_edit.h"
#include "vdg/io/edit_script.h"
#include "vdg/io/image_file.h"
#include "vdg/io/manifest.h"
#include "vdg/io/obj.h"
#include "vdg/studio/navigation.h"
#include "vdg/studio/session.h"
#include "vdg/viewdep/animated_model.h"

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

TEST_F(Fixture, ANewKeyMadeOnADrawingSavesItAsItsReferenceDrawing) {
  // vdg studio ball.obj --drawing art/front.png: the drawing in a folder beside the manifest.
  fs::create_directories(dir.file("art"));
  TextureImage drawing;
  drawing.width = 32;
  drawing.height = 24;
  drawing.rgba.assign(32 * 24 * 4, 180);
  const std::string png = dir.file("art/front.png");
  std::ofstream(png, std::ios::binary) << encodePng(drawing, png);
  {
    Session s = Session::open(obj);
    s.setDrawing(png, std::make_shared<const TextureImage>(drawing));
    s.camera = orbit(s.camera, 30, 10);
    s.newKey("k");
    stroke(s, {330, 250});  // the key takes the camera and the drawing here
    ASSERT_TRUE(s.model().keys[0].drawing);
    s.saveKey();
  }
  const RawViewDependentModel saved = loadManifest(dir.file("ball.vdg.json"));
  ASSERT_EQ(saved.keys.size(), 1u);
  EXPECT_EQ(saved.keys[0].drawing_path, "art/front.png");  // relative to the manifest's folder
  ASSERT_TRUE(saved.keys[0].drawing);
  EXPECT_EQ(saved.keys[0].drawing->width, 32);
  EXPECT_EQ(saved.keys[0].drawing->rgba, drawing.rgba);
  ASSERT_TRUE(saved.keys[0].camera);

  // A key made without a drawing has none; the saved key keeps its own.
  Session s = Session::open(dir.file("ball.vdg.json"));
  s.camera = orbit(s.camera, -40, 0);
  s.newKey("side");
  stroke(s, {330, 250});
  s.saveKey();
  const RawViewDependentModel both = loadManifest(dir.file("ball.vdg.json"));
  ASSERT_EQ(both.keys.size(), 2u);
  EXPECT_EQ(both.keys[0].drawing_path, "art/front.png");
  EXPECT_TRUE(both.keys[1].drawing_path.empty());
  EXPECT_FALSE(both.keys[1].drawing);
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

// ---- keys on an animated model (Rademacher 99, section 4): the timeline ---------------------------

// The walker of examples/walk (glTF base of 40 frames, skinned offsets, keys at frames 10 and 30).
struct Walker : ::testing::Test {
  TempDir dir;
  std::string manifest;
  void SetUp() override {
    const fs::path walk = fs::path(VDG_SOURCE_DIR) / "examples" / "walk";
    for (const char* f : {"walker.glb", "walker.vdg.json"}) fs::copy_file(walk / f, dir.path() / f);
    fs::copy(walk / "keys", dir.path() / "keys");
    manifest = dir.file("walker.vdg.json");
  }
  // A vertex near the image centre of the session's camera: on the walker, whatever its pose.
  static std::int32_t centerVertex(const Session& s) {
    return *s.pick(Eigen::Vector2d(s.image_width / 2.0, s.image_height / 2.0));
  }
  static DragOp drag(std::int32_t v, double dx, double dy) {
    DragOp op;
    op.pick.vertex = v;
    op.pick.falloff = Falloff{0.3, 2.0, FalloffShape::kPower};
    op.delta_px = Eigen::Vector2d(dx, dy);
    return op;
  }
};

// The key made at frame 20 from the back: strokes on the base posed at 20, undo and redo exact,
// saved as the manifest's (20, back) key, equal to the posed base with the same ops applied by
// hand, and the animated model gives it back at its frame and view.
TEST_F(Walker, AKeyAtAFrameIsMadeOnThePosedBaseUndoneAndSaved) {
  Session s = Session::open(manifest);
  ASSERT_TRUE(s.animated());
  EXPECT_EQ(s.frameCount(), 40);
  EXPECT_EQ(s.keyFrames(), (std::vector<int>{10, 30}));
  s.setFrame(20);
  const RawViewDependentModel raw = loadManifest(manifest);
  EXPECT_EQ(maxDiff(s.positions(), raw.base_frames[20]), 0.0);
  s.camera = orbit(s.camera, 180, 0);  // from the back
  s.newKey("back_f20");
  EXPECT_EQ(s.model().keys.back().frame, 20);
  EXPECT_EQ(maxDiff(s.positions(), raw.base_frames[20]), 0.0);
  const std::int32_t v = centerVertex(s);
  const std::vector<EditOp> ops1{drag(v, 25, -10)}, ops2{drag(v, -5, 30)};
  s.applyOps(ops1);
  const std::vector<float> after1(s.positions().begin(), s.positions().end());
  s.applyOps(ops2);
  const std::vector<float> after2(s.positions().begin(), s.positions().end());
  EXPECT_GT(maxDiff(after2, raw.base_frames[20]), 0.01);
  s.undo();
  EXPECT_EQ(maxDiff(s.positions(), after1), 0.0);
  s.undo();
  EXPECT_EQ(maxDiff(s.positions(), raw.base_frames[20]), 0.0);
  s.redo();
  s.redo();
  EXPECT_EQ(maxDiff(s.positions(), after2), 0.0);
  s.saveKey();

  // By hand: the base posed at frame 20, the two ops in the key's camera and image size.
  std::vector<float> expected = raw.base_frames[20];
  const std::array<int, 2> size{s.image_width, s.image_height};
  const Camera key_camera = *s.model().keys.back().camera;
  applyEdits(key_camera, raw.base.triangles, expected, ops1, size, "ops1");
  applyEdits(key_camera, raw.base.triangles, expected, ops2, size, "ops2");
  const RawViewDependentModel saved = loadManifest(manifest);
  ASSERT_EQ(saved.keys.size(), 5u);
  EXPECT_EQ(saved.keys.back().frame, 20);
  EXPECT_LT(maxDiff(saved.keys.back().mesh.positions, expected), kFileTol);
  const EditLog log = readEditLog(dir.file("back_f20.edits.json"));
  EXPECT_EQ(log.origin, "base");
  EXPECT_LT(maxDiff(replayEditLog(posedBase(saved, 20), log, "log"), expected), kFileTol);
  // At its frame and view the animated model is the key.
  const AnimatedViewDependentModel model = AnimatedViewDependentModel::build(saved);
  std::vector<float> out(expected.size());
  ASSERT_TRUE(model.evaluate(20, saved.keys.back().view, 0.0, out));
  EXPECT_LT(maxDiff(out, expected), kFileTol);
  EXPECT_EQ(s.keyFrames(), (std::vector<int>{10, 20, 30}));
}

// Jumping to a key moves the timeline to its frame and the camera to its view; moving the timeline
// away leaves it (the base is shown, posed), unless it has unsaved strokes.
TEST_F(Walker, TheTimelineJumpsToKeysAndLeavesThemAtOtherFrames) {
  Session s = Session::open(manifest);
  const RawViewDependentModel raw = loadManifest(manifest);
  EXPECT_EQ(maxDiff(s.positions(), raw.base_frames[0]), 0.0);
  s.editKey(3);  // side_f30
  EXPECT_EQ(s.frame(), 30);
  EXPECT_EQ(s.currentKey(), 3);
  EXPECT_LT((s.camera.eye - keyEditCamera(raw, raw.keys[3]).eye).norm(), 1e-9);
  EXPECT_EQ(maxDiff(s.positions(), raw.keys[3].mesh.positions), 0.0);
  s.applyOps(std::vector<EditOp>{drag(centerVertex(s), 10, 0)});
  EXPECT_NE(errorOf([&] { s.setFrame(5); }).find("unsaved strokes"), std::string::npos);
  s.undo();
  s.setFrame(5);
  EXPECT_EQ(s.currentKey(), -1);
  EXPECT_EQ(maxDiff(s.positions(), raw.base_frames[5]), 0.0);
  EXPECT_NE(errorOf([&] { s.setFrame(40); }).find("frame 40 is outside the base animation's frames 0..39"),
            std::string::npos);
  // A new key at a frame and view another key has is refused, naming it.
  s.setFrame(10);
  s.camera = keyEditCamera(raw, raw.keys[0]);  // front_f10's view
  EXPECT_NE(errorOf([&] { s.newKey("again"); }).find("as key 'front_f10'"), std::string::npos);
}

// The autosave of a new key at a frame brings it back at that frame.
TEST_F(Walker, TheAutosaveOfANewKeyKeepsItsFrame) {
  std::vector<float> expected;
  {
    Session s = Session::open(manifest);
    s.setFrame(25);
    s.camera = orbit(s.camera, 180, 0);
    s.newKey("back_f25");
    s.applyOps(std::vector<EditOp>{drag(centerVertex(s), 20, 5)});
    expected.assign(s.positions().begin(), s.positions().end());
  }
  Session s = Session::open(manifest);
  ASSERT_EQ(s.recoverableStrokes(), 1u);
  s.recover();
  EXPECT_EQ(s.frame(), 25);
  EXPECT_EQ(s.model().keys.back().frame, 25);
  EXPECT_EQ(maxDiff(s.positions(), expected), 0.0);
}

// Framing fits the pose: every frame of the base and every key's pose lie in poseBounds(), which is
// centred on the model's centre (so the framed front view is the manifest's front view).
TEST_F(Walker, FramingFitsTheAnimatedPoseAboutTheModelCentre) {
  const Session s = Session::open(manifest);
  const RawViewDependentModel raw = loadManifest(manifest);
  const Bounds& b = s.poseBounds();
  const auto inside = [&](const std::vector<float>& p) {
    for (std::size_t i = 0; i < p.size(); ++i)
      if (p[i] < b.min[i % 3] || p[i] > b.max[i % 3]) return false;
    return true;
  };
  for (std::size_t f = 0; f < raw.base_frames.size(); ++f) EXPECT_TRUE(inside(raw.base_frames[f])) << "frame " << f;
  for (const RawKey& k : raw.keys) EXPECT_TRUE(inside(k.mesh.positions)) << k.name;
  const Eigen::Vector3d c = raw.resolvedCenter();
  constexpr double kFloatCentre = 1e-6;  // the box is in floats
  for (int a = 0; a < 3; ++a) EXPECT_NEAR(0.5 * (double(b.min[a]) + b.max[a]), c[a], kFloatCentre) << a;
  // Wider than frame 0 alone: the swing of the walk.
  const Bounds b0 = computeBounds(raw.base_frames[0]);
  EXPECT_GT(b.max[2] - b.min[2], b0.max[2] - b0.min[2]);
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
