// Edit operations built in C++ (no JSON text behind them), their one JSON form, and the key
// authoring rules of vdg/deform/key_edit.h: new keys, steps, replay and undo.
#include <gtest/gtest.h>

#include <filesystem>
#include <utility>

#include "support/error_of.h"
#include "support/test_meshes.h"
#include "test_meshes.h"
#include "vdg/deform/edits.h"
#include "vdg/deform/key_edit.h"
#include "vdg/geom/error.h"
#include "vdg/io/edit_script.h"

namespace vdg {
namespace {

Camera frontCamera() {
  Camera c;
  c.eye = {0.3, 0.2, 5};
  c.target = {0, 0, 0};
  c.fov_deg = 40;
  return c;
}

using testing::errorOf;

VertexPick pick(std::int32_t vertex, double radius) {
  VertexPick p;
  p.vertex = vertex;
  p.falloff.radius = radius;
  return p;
}

// One op of every kind, with non-default values, built as an editor would.
std::vector<EditOp> everyKind() {
  std::vector<EditOp> ops;
  ops.push_back(DragOp{pick(24, 0.5), {0.1, 0.05}, std::nullopt});
  ops.push_back(DragOp{pick(10, 0.4), Eigen::Vector2d::Zero(), Eigen::Vector2d(6, -3)});
  ops.push_back(PushPullOp{pick(17, 0.3), -0.07, PushPullMode::kAlongAxis});
  ops.push_back(RotateOp{pick(30, 0.45), 12.5});
  VertexPick geodesic = pick(20, 0.6);
  geodesic.metric = DistanceMetric::kGeodesic;
  geodesic.falloff.shape = FalloffShape::kInversePower;
  geodesic.falloff.power = 3;
  ops.push_back(ScaleOp{geodesic, {1.1, 0.95}});
  VertexPick edges = pick(8, 3);
  edges.metric = DistanceMetric::kEdges;
  ops.push_back(DisplaceOp{edges, {0.01, 0.02, 0.1}, true});
  FfdOp ffd;
  ffd.degree = {2, 1, 1};
  ffd.moves = {{{1, 1, 0}, {0.0, 0.05, 0.01}}};
  ops.push_back(ffd);
  SquashStretchOp squash;
  squash.axis = Eigen::Vector3d(1, 1, 0);  // a camera-frame axis no name describes
  squash.factor = 1.2;
  squash.vertices = {1, 2, 3, 9};
  ops.push_back(squash);
  AffineOp affine;
  affine.matrix << 1, 0.1, 0, 0, 1, 0, 0, 0, 1;
  affine.translation = {0, 0.01, 0};
  affine.center = Eigen::Vector3d(0.1, 0.1, 0);
  ops.push_back(affine);
  return ops;
}

TEST(EditOpJson, EveryKindRoundTripsExactly) {
  for (const EditOp& op : everyKind()) {
    const std::string text = editOpToJson(op);
    const EditOp back = parseEditOp(text, "op");
    EXPECT_EQ(editKind(back), editKind(op)) << text;
    EXPECT_EQ(editOpToJson(back), text);
  }
}

TEST(EditOpJson, AnOpOutOfRangeIsNotWritten) {
  DragOp bad{pick(0, -1), {0, 0}, std::nullopt};
  EXPECT_EQ(errorOf([&] { editOpToJson(bad); }), "op (drag).'radius': must be > 0 and finite, got -1");
  EXPECT_EQ(errorOf([&] { validateEdits(std::vector<EditOp>{bad}, 10, "editor"); }),
            "editor: 'ops'[0] (drag).'radius': must be > 0 and finite, got -1");
  EditLog log;
  log.key = "k";
  log.entries.push_back({frontCamera(), std::nullopt, {bad}});
  EXPECT_NE(errorOf([&] { formatEditLog(log); }).find("'radius': must be > 0"), std::string::npos);
}

// Ops built in C++ are logged, read back and replayed to the very same mesh.
TEST(KeyEdit, OpsBuiltInCppAreLoggedAndReplayExactly) {
  const TriMesh base = test::grid(7, 0.2);
  const std::vector<EditOp> ops = everyKind();
  EditLog log;
  log.key = "k";
  log.entries.push_back({frontCamera(), std::array<int, 2>{64, 48}, {ops.begin(), ops.begin() + 4}});
  log.entries.push_back({frontCamera(), std::array<int, 2>{64, 48}, {ops.begin() + 4, ops.end()}});
  const std::vector<float> direct = replayEditLog(base, log, "log");
  EXPECT_NE(direct, base.positions);

  const testing::TempDir dir;
  const std::string path = editLogPath(dir.file("k.obj"));
  writeEditLog(path, log);
  const EditLog read = readEditLog(path);
  ASSERT_EQ(read.entries.size(), 2u);
  EXPECT_EQ(read.entries[1].ops.size(), ops.size() - 4);
  EXPECT_EQ(replayEditLog(base, read, path), direct);
  EXPECT_EQ(formatEditLog(read), formatEditLog(log));
}

TEST(KeyEdit, KeyNameRule) {
  for (const char* good : {"side", "Front_2", "a.b-c", "x", "0"}) EXPECT_TRUE(isValidKeyName(good)) << good;
  for (const char* bad : {"", ".hidden", "../../x", "a/b", "a b", "sp\xc3\xa4t", "a\\b", "\xff"})
    EXPECT_FALSE(isValidKeyName(bad)) << bad;
  EXPECT_TRUE(isValidKeyName(std::string(kMaxKeyNameLength, 'k')));
  EXPECT_FALSE(isValidKeyName(std::string(kMaxKeyNameLength + 1, 'k')));
  EXPECT_EQ(errorOf([] { checkKeyName("../../x"); }),
            "key name '../../x': not allowed (key names are file names: use 1 to 64 letters, digits, '_', '-' or "
            "'.', not starting with '.')");
  EXPECT_NE(errorOf([] { checkKeyName("bad\xff"); }).find("'bad\\xff'"), std::string::npos);
}

TEST(KeyEdit, MeshPathRule) {
  for (const char* good : {"k.obj", "keys/k.OBJ", "./k.obj", "a/../k.obj", "k\xc3\xa4.obj"})
    EXPECT_NO_THROW(checkKeyMeshPath(good)) << good;
  const std::pair<const char*, const char*> bad[] = {
      {"/tmp/k.obj", "must be relative"}, {"../k.obj", "inside the manifest's folder"},
      {"a/../../k.obj", "inside"},        {"k.txt", "must be an OBJ file"},
      {"k", "must be an OBJ file"},       {"", "is empty"},
      {"k\xff.obj", "valid UTF-8"},       {"k\n.obj", "control characters"},
  };
  for (const auto& [path, needle] : bad)
    EXPECT_NE(errorOf([&] { checkKeyMeshPath(path); }).find(needle), std::string::npos) << path;
}

RawViewDependentModel twoKeyModel() {
  RawViewDependentModel m;
  m.base = test::grid(5, 0.25);
  m.base_path = "base.obj";
  m.keys.push_back({"front", "front.obj", m.base, Eigen::Vector3d(0, 0, 1), std::nullopt, std::nullopt, {}, {}});
  m.keys.push_back({"side", "side.obj", m.base, Eigen::Vector3d(1, 0, 0), std::nullopt, std::nullopt, {}, {}});
  m.keys.push_back({"top", "top.obj", m.base, Eigen::Vector3d(0, 1, 0), std::nullopt, std::nullopt, {}, {}});
  m.resolveViews();
  m.validate();
  return m;
}

// Section 4: a key of an animated model starts from the base posed at its frame, is framed there,
// and its log's origin "base" means that pose; frames out of range are refused, naming them.
TEST(KeyEdit, AKeyOfAnAnimatedModelStartsFromTheBasePosedAtItsFrame) {
  RawViewDependentModel m;
  m.base = test::grid(5, 0.25);
  m.base_path = "";
  m.base_animation = BaseAnimationSpec{};
  m.base_animation->obj_sequence = "f%d.obj";
  std::vector<float> moved = m.base.positions;
  for (std::size_t i = 0; i < moved.size(); i += 3) moved[i] += 2.0f;  // frame 1: 2 along +X
  m.base_frames = {m.base.positions, moved};
  m.keys.push_back({"front0", "front0.obj", m.base, Eigen::Vector3d(0, 0, 1), std::nullopt, std::nullopt, {}, {}, 0});
  m.validate();

  EXPECT_EQ(posedBase(m, 1).positions, moved);
  EXPECT_EQ(posedBase(m, 1).triangles, m.base.triangles);
  const std::size_t k = addKey(m, {"side1", "", std::nullopt, Eigen::Vector3d(1, 0, 0), 1});
  EXPECT_EQ(m.keys[k].frame, 1);
  EXPECT_EQ(m.keys[k].mesh.positions, moved);
  EXPECT_EQ(startEditLog(m, m.keys[k], "side1.origin.obj").origin, "base");
  // The same frame and view as another key, a frame out of range: refused, the model unchanged.
  const std::size_t keys = m.keys.size();
  EXPECT_NE(errorOf([&] {
              addKey(m, {"again", "", std::nullopt, Eigen::Vector3d(1, 0, 0), 1});
            }).find("same frame 1 as key 'side1'"),
            std::string::npos);
  EXPECT_NE(errorOf([&] {
              addKey(m, {"late", "", std::nullopt, Eigen::Vector3d(0, 1, 0), 2});
            }).find("frame 2 is outside the base animation's frames 0..1"),
            std::string::npos);
  EXPECT_EQ(m.keys.size(), keys);
  // A static model has frame 0 only.
  RawViewDependentModel still = twoKeyModel();
  EXPECT_NE(errorOf([&] {
              addKey(still, {"late", "", std::nullopt, Eigen::Vector3d(0, 1, 1), 1});
            }).find("(the base is static)"),
            std::string::npos);
}

TEST(KeyEdit, AddKeyChecksEverythingAndLeavesTheModelAloneOnError) {
  RawViewDependentModel m = twoKeyModel();
  const std::size_t keys = m.keys.size();
  EXPECT_NE(errorOf([&] {
              addKey(m, {"../x", "", std::nullopt, Eigen::Vector3d(0, 1, 1)});
            }).find("not allowed"),
            std::string::npos);
  EXPECT_NE(errorOf([&] {
              addKey(m, {"front", "", std::nullopt, Eigen::Vector3d(0, 1, 1)});
            }).find("already exists"),
            std::string::npos);
  EXPECT_NE(errorOf([&] {
              addKey(m, {"new", "./side.obj", std::nullopt, Eigen::Vector3d(0, 1, 1)});
            }).find("belongs to key 'side'"),
            std::string::npos);
  EXPECT_NE(errorOf([&] {
              addKey(m, {"new", "k.txt", std::nullopt, Eigen::Vector3d(0, 1, 1)});
            }).find("OBJ"),
            std::string::npos);
  EXPECT_NE(errorOf([&] {
              addKey(m, {"new", "", std::nullopt, std::nullopt});
            }).find("camera or its view"),
            std::string::npos);
  EXPECT_EQ(m.keys.size(), keys);
  const std::size_t k = addKey(m, {"new", "", std::nullopt, Eigen::Vector3d(0, 2, 2)});
  EXPECT_EQ(m.keys[k].mesh_path, "new.obj");
  EXPECT_EQ(m.keys[k].mesh.positions, m.base.positions);
  EXPECT_NEAR(m.keys[k].view.norm(), 1.0, 1e-12);
}

TEST(KeyEdit, StepUndoAndOrigin) {
  RawViewDependentModel m = twoKeyModel();
  EditLog log = startEditLog(m, m.keys[0], "front.origin.obj");
  EXPECT_EQ(log.origin, "base");
  const std::vector<EditOp> step1{DragOp{pick(12, 0.3), {0.1, 0}, std::nullopt}};
  const std::vector<EditOp> step2{PushPullOp{pick(12, 0.3), 0.05, PushPullMode::kAlongRay}};
  const auto reports = deformKey(m, 0, log, step1, std::nullopt, "e1");
  ASSERT_EQ(reports.size(), 1u);
  EXPECT_GT(reports[0].moved, 0u);
  const std::vector<float> after1 = m.keys[0].mesh.positions;
  deformKey(m, 0, log, step2, std::nullopt, "e2");
  ASSERT_EQ(log.entries.size(), 2u);
  EXPECT_EQ(replayEditLog(m.base, log, "log"), m.keys[0].mesh.positions);
  // A key that is not the base any more starts its log from a snapshot.
  EXPECT_EQ(startEditLog(m, m.keys[0], "front.origin.obj").origin, "front.origin.obj");

  EXPECT_EQ(undoLastStep(m.base, log, "log"), after1);
  EXPECT_EQ(log.entries.size(), 1u);
  EXPECT_EQ(undoLastStep(m.base, log, "log"), m.base.positions);
  EXPECT_EQ(errorOf([&] { undoLastStep(m.base, log, "log"); }), "log: nothing to undo (the edit log has no step)");
}

TEST(KeyEdit, AFailedStepChangesNothing) {
  RawViewDependentModel m = twoKeyModel();
  EditLog log;
  const std::vector<EditOp> ops{DragOp{pick(12, 0.3), {0.1, 0}, std::nullopt},
                                DragOp{pick(99, 0.3), {0.1, 0}, std::nullopt}};
  EXPECT_EQ(errorOf([&] { deformKey(m, 1, log, ops, std::nullopt, "E.json"); }),
            "E.json: 'ops'[1] (drag).'vertex': 99 is out of range (the mesh has 25 vertices)");
  EXPECT_EQ(m.keys[1].mesh.positions, m.base.positions);
  EXPECT_TRUE(log.entries.empty());
}

TEST(KeyEdit, EditCameraOfAViewKeyLooksAlongTheView) {
  const RawViewDependentModel m = twoKeyModel();
  const Camera c = keyEditCamera(m, m.keys[1]);
  EXPECT_TRUE(c.isOrtho());
  const Eigen::Vector3d towards_eye = (c.eye - c.target).normalized();
  EXPECT_NEAR((towards_eye - m.keys[1].view).norm(), 0.0, 1e-12);
}

}  // namespace
}  // namespace vdg
