// End-to-end tests of `vdg deform` and `vdg align`: run the built binary (VDG_BINARY) on a model
// generated here, and check the files it writes — and that bad input leaves every file untouched.
#include <gtest/gtest.h>
#include <stb/stb_image_write.h>
#include <sys/wait.h>
#include <unistd.h>

#include <Eigen/LU>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "test_meshes.h"
#include "vdg/deform/edits.h"
#include "vdg/deform/key_edit.h"
#include "vdg/deform/skeleton.h"
#include "vdg/io/camera_json.h"
#include "vdg/io/edit_script.h"
#include "vdg/io/manifest.h"
#include "vdg/io/obj.h"
#include "vdg/viewdep/animated_model.h"
#include "vdg/viewdep/model.h"

namespace vdg {
namespace {
namespace fs = std::filesystem;

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}
void spit(const fs::path& p, const std::string& text) { std::ofstream(p, std::ios::binary) << text; }

class DeformCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("vdg_deform_cli_" + std::to_string(::getpid()) + "_" +
                                        std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    base_ = test::sphere(8, 16, 1.0);
    writeObj((dir_ / "base.obj").string(), base_);
    TriMesh front = base_;
    front.positions[1] += 0.2f;  // the north pole pulled up
    writeObj((dir_ / "front.obj").string(), front);
    spit(dir_ / "m.vdg.json", R"({"version": 1, "base": "base.obj",
      "keys": [{"name": "front", "mesh": "front.obj", "view": [0, 0, 1]}]})");
  }
  void TearDown() override { fs::remove_all(dir_); }

  // Runs vdg with `args`; returns the exit status, stdout+stderr in `output_`.
  int vdg(const std::string& args) {
    const std::string out = (dir_ / "out.txt").string();
    const std::string cmd = std::string("\"") + VDG_BINARY + "\" " + args + " > \"" + out + "\" 2>&1";
    const int status = std::system(cmd.c_str());
    output_ = slurp(out);
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  }
  std::string path(const std::string& name) const { return "\"" + (dir_ / name).string() + "\""; }

  fs::path dir_;
  TriMesh base_;
  std::string output_;
};

constexpr const char* kCamera =
    R"("camera": {"eye": [0.5, 0.5, 5], "target": [0, 0, 0], "up": [0, 1, 0], "fov_deg": 40})";

TEST_F(DeformCli, NewKeyStepsLogAndUndo) {
  spit(dir_ / "e1.json",
       std::string("{") + kCamera + R"(, "ops": [{"op": "drag", "vertex": 20, "radius": 0.8, "delta": [0.2, 0.1]}]})");
  spit(dir_ / "e2.json", R"({"ops": [{"op": "push_pull", "vertex": 20, "radius": 0.5, "amount": 0.1},
                                     {"op": "displace", "vertex": 5, "radius": 2, "distance": "edges", "offset": [0, 0.1, 0]}]})");
  ASSERT_EQ(vdg("deform " + path("m.vdg.json") + " --key side --ops " + path("e1.json")), 0) << output_;
  const TriMesh step1 = readObj((dir_ / "side.obj").string());
  EXPECT_NE(step1.positions, base_.positions);
  const RawViewDependentModel model = loadManifest((dir_ / "m.vdg.json").string());
  ASSERT_EQ(model.keys.size(), 2u);
  EXPECT_EQ(model.keys[1].name, "side");
  EXPECT_TRUE(model.keys[1].camera.has_value());

  ASSERT_EQ(vdg("deform " + path("m.vdg.json") + " --key side --ops " + path("e2.json")), 0) << output_;
  EXPECT_EQ(readEditLog((dir_ / "side.edits.json").string()).entries.size(), 2u);
  EXPECT_NE(readObj((dir_ / "side.obj").string()).positions, step1.positions);

  ASSERT_EQ(vdg("deform " + path("m.vdg.json") + " --key side --undo"), 0) << output_;
  EXPECT_EQ(readObj((dir_ / "side.obj").string()).positions, step1.positions);
  ASSERT_EQ(vdg("deform " + path("m.vdg.json") + " --key side --undo"), 0) << output_;
  EXPECT_EQ(readObj((dir_ / "side.obj").string()).positions, base_.positions);
  EXPECT_EQ(vdg("deform " + path("m.vdg.json") + " --key side --undo"), 1);
  EXPECT_NE(output_.find("nothing to undo"), std::string::npos) << output_;
}

TEST_F(DeformCli, ExistingHandMadeKeyKeepsItsShapeAsOrigin) {
  spit(dir_ / "e.json", R"({"ops": [{"op": "scale", "vertex": 0, "radius": 0.6, "factor": 1.5}]})");
  ASSERT_EQ(vdg("deform " + path("m.vdg.json") + " --key front --ops " + path("e.json")), 0) << output_;
  EXPECT_TRUE(fs::exists(dir_ / "front.origin.obj"));
  ASSERT_EQ(vdg("deform " + path("m.vdg.json") + " --key front --undo"), 0) << output_;
  EXPECT_EQ(readObj((dir_ / "front.obj").string()).positions, readObj((dir_ / "front.origin.obj").string()).positions);
  EXPECT_NE(readObj((dir_ / "front.obj").string()).positions, base_.positions);
}

TEST_F(DeformCli, BadOperationsLeaveEveryFileUntouched) {
  const std::string manifest = slurp(dir_ / "m.vdg.json"), front = slurp(dir_ / "front.obj");
  const struct {
    const char* ops;
    const char* message;
  } cases[] = {
      {R"([{"op": "drag", "vertex": 0, "radius": 0.5, "delta": [0.1, 0]},
           {"op": "drag", "vertex": 9999, "radius": 0.5, "delta": [0.1, 0]}])",
       "'ops'[1] (drag).'vertex': 9999 is out of range"},
      {R"([{"op": "push_pull", "vertex": 3, "radius": -1, "amount": 0.1}])",
       "'ops'[0] (push_pull).'radius': must be > 0"},
      {R"([{"op": "twirl", "vertex": 3}])", "'ops'[0].'op': unknown value 'twirl'"},
      {R"([{"op": "skeleton", "rest": [[0, 0, 0]], "posed": [[0, 0, 0]]}])",
       "'ops'[0] (skeleton).'rest': a wire needs at least 2 joints, got 1"},
      {R"([{"op": "skeleton", "rest": [[0, -1, 0], [0, 0, 0], [0, 1, 0]], "posed": [[0, -1, 0], [0, 0, 0]]}])",
       "'ops'[0] (skeleton).'posed': has 2 joints, 'rest' has 3"},
      {R"([{"op": "skeleton", "rest": [[0, -1, 0], [0, 0, 0], [0, 0, 0]], "posed": [[0, -1, 0], [0, 0, 0], [1, 0, 0]]}])",
       "'ops'[0] (skeleton).'rest'[2]: is the same point as joint 1"},
  };
  for (const auto& c : cases) {
    spit(dir_ / "bad.json", std::string(R"({"ops": )") + c.ops + "}");
    EXPECT_EQ(vdg("deform " + path("m.vdg.json") + " --key front --ops " + path("bad.json")), 1) << c.ops;
    EXPECT_NE(output_.find(c.message), std::string::npos) << output_;
    EXPECT_EQ(output_.find('\n'), output_.size() - 1) << "one line: " << output_;
    EXPECT_EQ(slurp(dir_ / "m.vdg.json"), manifest);
    EXPECT_EQ(slurp(dir_ / "front.obj"), front);
    EXPECT_FALSE(fs::exists(dir_ / "front.edits.json"));
  }
  // A new key without a camera or view.
  spit(dir_ / "e.json", R"({"ops": [{"op": "drag", "vertex": 0, "radius": 0.5, "delta": [0.1, 0]}]})");
  EXPECT_EQ(vdg("deform " + path("m.vdg.json") + " --key side --ops " + path("e.json")), 1);
  EXPECT_NE(output_.find("give its camera or view"), std::string::npos) << output_;
  EXPECT_FALSE(fs::exists(dir_ / "side.obj"));
  EXPECT_EQ(slurp(dir_ / "m.vdg.json"), manifest);
}

// A skeleton op makes a key: the key mesh is the library's bound-and-posed base, and its edit log
// replays to it.
TEST_F(DeformCli, SkeletonOpBendsANewKey) {
  const std::vector<Eigen::Vector3d> rest{{0, -1.2, 0}, {0, 0, 0}, {0, 1.2, 0}};
  const std::vector<Eigen::Vector3d> posed{{0, -1.2, 0}, {0, 0, 0}, {0.8, 0.9, 0.1}};
  spit(dir_ / "e.json", std::string("{") + kCamera + R"(, "ops": [{"op": "skeleton",
       "rest": [[0, -1.2, 0], [0, 0, 0], [0, 1.2, 0]], "posed": [[0, -1.2, 0], [0, 0, 0], [0.8, 0.9, 0.1]]}]})");
  ASSERT_EQ(vdg("deform " + path("m.vdg.json") + " --key bent --ops " + path("e.json")), 0) << output_;
  std::vector<float> expected = base_.positions;
  ASSERT_TRUE(bindSkeleton(rest, expected).apply(posed, expected));
  const TriMesh bent = readObj((dir_ / "bent.obj").string());
  ASSERT_EQ(bent.positions.size(), expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i) EXPECT_NEAR(bent.positions[i], expected[i], 1e-6) << i;
  const EditLog log = readEditLog((dir_ / "bent.edits.json").string());
  ASSERT_EQ(log.entries.size(), 1u);
  ASSERT_EQ(log.entries[0].ops.size(), 1u);
  EXPECT_EQ(editKind(log.entries[0].ops[0]), EditKind::kSkeleton);
  EXPECT_EQ(replayEditLog(base_, log, "bent.edits.json"), expected);
}

// Every file of the model folder with its contents, to check that nothing changed at all.
std::map<std::string, std::string> folderContents(const fs::path& dir) {
  std::map<std::string, std::string> files;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.path().filename() != "out.txt") files[e.path().filename().string()] = slurp(e.path());
  return files;
}

TEST_F(DeformCli, KeyNamesAndMeshPathsAreChecked) {
  spit(dir_ / "e.json",
       std::string("{") + kCamera + R"(, "ops": [{"op": "drag", "vertex": 20, "radius": 0.8, "delta": [0.2, 0.1]}]})");
  const auto before = folderContents(dir_);
  const struct {
    std::string args;
    const char* message;
  } cases[] = {
      {"--key ../../x", "key name '../../x': not allowed (key names are file names: use 1 to 64 letters"},
      {"--key .hidden", "key name '.hidden': not allowed"},
      {"--key 'bad\xff'", "key name 'bad\\xff': not allowed"},
      {"--key k --mesh k.txt", "--mesh k.txt: a key mesh must be an OBJ file"},
      {"--key k --mesh ../k.obj", "--mesh ../k.obj: must stay inside the manifest's folder"},
      {"--key k --mesh /tmp/k.obj", "--mesh /tmp/k.obj: must be relative"},
  };
  for (const auto& c : cases) {
    EXPECT_EQ(vdg("deform " + path("m.vdg.json") + " " + c.args + " --ops " + path("e.json")), 1) << c.args;
    EXPECT_NE(output_.find(c.message), std::string::npos) << output_;
    EXPECT_EQ(folderContents(dir_), before) << c.args;
  }
  EXPECT_FALSE(fs::exists(dir_.parent_path().parent_path() / "x.obj"));
  EXPECT_FALSE(fs::exists("/tmp/k.obj"));
  // A mesh path in a subfolder is fine.
  fs::create_directories(dir_ / "keys");
  ASSERT_EQ(vdg("deform " + path("m.vdg.json") + " --key k --mesh keys/k.obj --ops " + path("e.json")), 0) << output_;
  EXPECT_EQ(loadManifest((dir_ / "m.vdg.json").string()).keys.back().mesh_path, "keys/k.obj");
}

TEST_F(DeformCli, AKeySharingItsMeshFileIsRefused) {
  spit(dir_ / "m.vdg.json", R"({"version": 1, "base": "base.obj",
    "keys": [{"name": "front", "mesh": "front.obj", "view": [0, 0, 1]},
             {"name": "back", "mesh": "./front.obj", "view": [0, 0, -1]}]})");
  spit(dir_ / "e.json", R"({"ops": [{"op": "drag", "vertex": 0, "radius": 0.5, "delta": [0.1, 0]}]})");
  const auto before = folderContents(dir_);
  EXPECT_EQ(vdg("deform " + path("m.vdg.json") + " --key back --ops " + path("e.json")), 1);
  EXPECT_NE(output_.find("key 'back' shares its mesh file"), std::string::npos) << output_;
  EXPECT_NE(output_.find("with key 'front'"), std::string::npos) << output_;
  EXPECT_EQ(folderContents(dir_), before);
}

TEST_F(DeformCli, AStepIsAllOrNothingWhenTheDiskFills) {
  // A long edit log (many ops), so that the key mesh fits under the limit and the log does not.
  std::string ops;
  for (int i = 0; i < 400; ++i)
    ops += std::string(i ? "," : "") + R"({"op": "drag", "vertex": 20, "radius": 0.8, "delta": [0.0001, 0]})";
  spit(dir_ / "e1.json", std::string("{") + kCamera + R"(, "ops": [)" + ops + "]}");
  ASSERT_EQ(vdg("deform -q " + path("m.vdg.json") + " --key side --ops " + path("e1.json")), 0) << output_;
  // ulimit -f 24: 24 blocks, of 512 bytes in POSIX shells (dash), of 1024 in bash.
  constexpr std::uintmax_t kLowLimit = 24 * 512, kHighLimit = 24 * 1024;
  ASSERT_GT(fs::file_size(dir_ / "side.edits.json"), kHighLimit);
  ASSERT_LT(fs::file_size(dir_ / "side.obj"), kLowLimit);
  spit(dir_ / "e2.json", R"({"ops": [{"op": "drag", "vertex": 20, "radius": 0.8, "delta": [0.1, 0]}]})");
  const auto before = folderContents(dir_);
  // The mesh is staged, the log is not.
  const std::string limited = "trap '' XFSZ; ulimit -f 24; \"" + std::string(VDG_BINARY) + "\" deform " +
                              path("m.vdg.json") + " --key side --ops " + path("e2.json") + " > " + path("out.txt") +
                              " 2>&1";
  const int status = std::system(limited.c_str());
  output_ = slurp(dir_ / "out.txt");
  ASSERT_TRUE(WIFEXITED(status)) << output_;
  EXPECT_EQ(WEXITSTATUS(status), 1) << output_;
  EXPECT_NE(output_.find("side.edits.json: cannot write file: File too large"), std::string::npos) << output_;
  EXPECT_EQ(folderContents(dir_), before);  // no file changed, no temporary file or journal left
}

TEST_F(DeformCli, AnInterruptedStepIsCompletedOrRolledBackByTheNextRun) {
  spit(dir_ / "e.json", R"({"ops": [{"op": "drag", "vertex": 0, "radius": 0.5, "delta": [0.1, 0]}]})");
  const std::string d = fs::absolute(dir_).string();
  // Interrupted while committing: the key's temporary file was complete, and is renamed now.
  TriMesh interrupted = base_;
  interrupted.positions[4] += 0.5f;
  spit(dir_ / ".vdg-Abc123", formatObj(interrupted));
  spit(dir_ / ".vdg-journal", R"({"version": 1, "state": "committing", "files": [{"target": ")" + d +
                                  R"(/front.obj", "temp": ")" + d + R"(/.vdg-Abc123"}]})");
  ASSERT_EQ(vdg("deform " + path("m.vdg.json") + " --key front --dry-run --ops " + path("e.json")), 0) << output_;
  EXPECT_NE(output_.find("completed an interrupted step: wrote " + d + "/front.obj"), std::string::npos) << output_;
  EXPECT_EQ(readObj((dir_ / "front.obj").string()).positions, interrupted.positions);
  EXPECT_FALSE(fs::exists(dir_ / ".vdg-journal"));
  EXPECT_FALSE(fs::exists(dir_ / ".vdg-Abc123"));
  // Interrupted while staging: the temporary files go, the targets were never touched.
  const std::string front = slurp(dir_ / "front.obj");
  spit(dir_ / ".vdg-Def456", "half a mesh");
  spit(dir_ / ".vdg-journal", R"({"version": 1, "state": "staging", "files": [{"target": ")" + d +
                                  R"(/front.obj", "temp": ")" + d + R"(/.vdg-Def456"}]})");
  ASSERT_EQ(vdg("deform " + path("m.vdg.json") + " --key front --ops " + path("e.json")), 0) << output_;
  EXPECT_NE(output_.find("rolled back an interrupted step"), std::string::npos) << output_;
  EXPECT_FALSE(fs::exists(dir_ / ".vdg-Def456"));
  EXPECT_FALSE(fs::exists(dir_ / ".vdg-journal"));
  EXPECT_NE(slurp(dir_ / "front.obj"), front);  // and this run's step went through
}

TEST_F(DeformCli, ASymlinkedManifestStaysALink) {
  fs::rename(dir_ / "m.vdg.json", dir_ / "real.vdg.json");
  fs::create_symlink("real.vdg.json", dir_ / "m.vdg.json");
  spit(dir_ / "e.json",
       std::string("{") + kCamera + R"(, "ops": [{"op": "drag", "vertex": 20, "radius": 0.8, "delta": [0.2, 0.1]}]})");
  ASSERT_EQ(vdg("deform " + path("m.vdg.json") + " --key side --ops " + path("e.json")), 0) << output_;
  EXPECT_TRUE(fs::is_symlink(dir_ / "m.vdg.json"));
  EXPECT_EQ(loadManifest((dir_ / "real.vdg.json").string()).keys.size(), 2u);
}

TEST_F(DeformCli, DryRunReportsAndWritesNothing) {
  const std::string manifest = slurp(dir_ / "m.vdg.json");
  spit(dir_ / "e.json",
       std::string("{") + kCamera + R"(, "ops": [{"op": "drag", "vertex": 20, "radius": 0.8, "delta": [0.2, 0.0]}]})");
  ASSERT_EQ(vdg("deform " + path("m.vdg.json") + " --key side --dry-run --ops " + path("e.json")), 0) << output_;
  EXPECT_NE(output_.find("ops[0] drag"), std::string::npos) << output_;
  EXPECT_NE(output_.find("at most 0.2"), std::string::npos) << output_;
  EXPECT_FALSE(fs::exists(dir_ / "side.obj"));
  EXPECT_EQ(slurp(dir_ / "m.vdg.json"), manifest);
}

TEST_F(DeformCli, AlignRecoversCameraFromDrawing) {
  Camera truth;
  truth.eye = {1.0, 0.8, 4.0};
  truth.target = {0, 0.1, 0};
  truth.fov_deg = 35;
  const int w = 320, h = 240;
  std::vector<unsigned char> pixels(static_cast<std::size_t>(w) * h, 255);
  ASSERT_TRUE(stbi_write_png((dir_ / "drawing.png").string().c_str(), w, h, 1, pixels.data(), w));
  std::string pairs = R"({"pairs": [)";
  for (int v = 1; v < 100; v += 9) {
    const Eigen::Vector3d p(base_.positions[3 * v], base_.positions[3 * v + 1], base_.positions[3 * v + 2]);
    const Eigen::Vector2d px = project(truth, w, h, p).pixel;
    std::ostringstream s;
    s.precision(17);
    s << (v > 1 ? "," : "") << R"({"vertex": )" << v << R"(, "pixel": [)" << px.x() << ", " << px.y() << "]}";
    pairs += s.str();
  }
  spit(dir_ / "pairs.json", pairs + "]}");
  ASSERT_EQ(vdg("align " + path("m.vdg.json") + " --drawing " + path("drawing.png") + " --points " +
                path("pairs.json") + " -o " + path("cam.json")),
            0)
      << output_;
  EXPECT_NE(output_.find("RMS error"), std::string::npos);
  const Camera got = readCameraFile((dir_ / "cam.json").string());
  EXPECT_LT((got.eye - truth.eye).norm(), 1e-6 * truth.eye.norm());
  EXPECT_NEAR(got.fov_deg, truth.fov_deg, 1e-6 * truth.fov_deg);

  // --key stores the camera in the manifest; the key's view follows the camera.
  ASSERT_EQ(vdg("align " + path("m.vdg.json") + " --size 320x240 --points " + path("pairs.json") + " --key front"), 0)
      << output_;
  const RawViewDependentModel model = loadManifest((dir_ / "m.vdg.json").string());
  ASSERT_TRUE(model.keys[0].camera.has_value());
  EXPECT_LT((model.keys[0].camera->eye - truth.eye).norm(), 1e-6 * truth.eye.norm());
  EXPECT_LT((model.keys[0].view - (truth.eye - model.resolvedCenter()).normalized()).norm(), 1e-6);
  const std::string manifest = slurp((dir_ / "m.vdg.json").string());
  EXPECT_EQ(vdg("align " + path("m.vdg.json") + " --size 320x240 --points " + path("pairs.json") + " --key nobody"), 1);
  EXPECT_NE(output_.find("no key named 'nobody'"), std::string::npos) << output_;
  EXPECT_EQ(vdg("align " + path("m.vdg.json") + " --size 320x240 --points " + path("pairs.json")), 2) << output_;
  EXPECT_EQ(slurp((dir_ / "m.vdg.json").string()), manifest);

  spit(dir_ / "few.json", R"([{"vertex": 1, "pixel": [1, 2]}, {"vertex": 2, "pixel": [3, 4]}])");
  EXPECT_EQ(
      vdg("align " + path("m.vdg.json") + " --size 320x240 --points " + path("few.json") + " -o " + path("cam2.json")),
      1);
  EXPECT_NE(output_.find("at least 6"), std::string::npos) << output_;
  EXPECT_FALSE(fs::exists(dir_ / "cam2.json"));
}

// --- Keys on animated models (Rademacher 99, section 4): vdg deform --frame F -------------------

// OBJ files hold positions to float precision (9 significant digits); a key written and read back,
// and the same float computation made twice, agree to this.
constexpr double kObjRoundTrip = 1e-6;
// Skinning an offset through two float 3x3 products (L(f) L(F)^-1 o): a few float ulps of a
// walker-sized (2 m) model.
constexpr double kSkinRounding = 2e-5;
// The frame the keys are made at, and the view (no shipped key has it, so it carries one key frame).
constexpr int kKeyFrame = 20;
const Eigen::Vector3d kBackView(0.0, 0.0, -1.0);

double maxDifference(std::span<const float> a, std::span<const float> b) {
  EXPECT_EQ(a.size(), b.size());
  double d = 0;
  for (std::size_t i = 0; i < a.size() && i < b.size(); ++i) d = std::max(d, std::abs(double(a[i]) - b[i]));
  return d;
}

Eigen::Matrix3d skinAt(const RawViewDependentModel& raw, int frame, std::size_t v) {
  return Eigen::Map<const Eigen::Matrix3f>(&raw.base_skin[static_cast<std::size_t>(frame)][9 * v]).cast<double>();
}

// The vertex whose skin turns most between frame 0 and kKeyFrame (on a swinging limb), so a
// skinned offset visibly turns with it; `raw` is the skinned walker (both manifests share its base).
std::int32_t mostTurningVertex(const RawViewDependentModel& raw) {
  std::int32_t best = 0;
  double turn = -1;
  for (std::size_t v = 0; v < raw.base.vertexCount(); ++v) {
    const double t = (skinAt(raw, 0, v) * skinAt(raw, kKeyFrame, v).inverse() - Eigen::Matrix3d::Identity()).norm();
    if (t > turn) turn = t, best = static_cast<std::int32_t>(v);
  }
  return best;
}

class AnimatedDeformCli : public DeformCli, public ::testing::WithParamInterface<const char*> {
 protected:
  // Copies the shipped walker (glTF base, keys, both manifests) into the test folder.
  void copyWalker() {
    const fs::path walk = fs::path(VDG_SOURCE_DIR) / "examples" / "walk";
    for (const char* f : {"walker.glb", "walker.vdg.json", "walker-world.vdg.json"}) fs::copy_file(walk / f, dir_ / f);
    fs::copy(walk / "keys", dir_ / "keys");
  }
};

// A key made at (frame 20, back) on the walker: `vdg eval` at that frame and view gives exactly the
// key mesh, which equals the base posed at frame 20 (base_frames[20]) with the same drag applied by
// hand in the same camera; the manifest lists it as the (20, back) key.
TEST_P(AnimatedDeformCli, AKeyAtAFrameReproducesThereAndEqualsTheHandMadeKey) {
  copyWalker();
  const std::string manifest = GetParam();
  RawViewDependentModel raw = loadManifest((dir_ / manifest).string());
  const std::int32_t vertex = mostTurningVertex(loadManifest((dir_ / "walker.vdg.json").string()));
  const std::string ops =
      R"([{"op": "drag", "vertex": )" + std::to_string(vertex) + R"(, "radius": 0.25, "delta": [0.12, 0.05]}])";
  spit(dir_ / "e.json", R"({"ops": )" + ops + "}");
  ASSERT_EQ(vdg("deform " + path(manifest) + " --frame 20 --key back_f20 --view 0,0,-1 --ops " + path("e.json")), 0)
      << output_;

  const RawViewDependentModel after = loadManifest((dir_ / manifest).string());
  ASSERT_EQ(after.keys.size(), raw.keys.size() + 1);
  const RawKey& key = after.keys.back();
  EXPECT_EQ(key.name, "back_f20");
  EXPECT_EQ(key.frame, kKeyFrame);
  EXPECT_LT((key.view - kBackView).norm(), 1e-12);

  // By hand: the base posed at frame 20, the drag in the key's edit camera.
  RawKey hand;
  hand.frame = kKeyFrame;
  hand.view = kBackView;
  std::vector<float> expected = raw.base_frames[kKeyFrame];
  const std::vector<EditOp> parsed = parseEditScript(R"({"ops": )" + ops + "}", "e.json").ops;
  applyEdits(keyEditCamera(raw, hand), raw.base.triangles, expected, parsed, std::nullopt, "by hand");
  EXPECT_GT(maxDifference(expected, raw.base_frames[kKeyFrame]), 0.05);  // the drag moved the limb
  EXPECT_LT(maxDifference(key.mesh.positions, expected), kObjRoundTrip);

  ASSERT_EQ(vdg("eval " + path(manifest) + " --frame 20 --view 0,0,-1 -q -o " + path("e20.obj")), 0) << output_;
  EXPECT_LT(maxDifference(readObj((dir_ / "e20.obj").string()).positions, key.mesh.positions), kObjRoundTrip);

  // The edit log starts from the posed base and replays to the key; undo gives the posed base back.
  const EditLog log = readEditLog((dir_ / "back_f20.edits.json").string());
  EXPECT_EQ(log.origin, "base");
  ASSERT_EQ(log.entries.size(), 1u);
  EXPECT_LT(maxDifference(replayEditLog(posedBase(after, kKeyFrame), log, "log"), key.mesh.positions), kObjRoundTrip);
  ASSERT_EQ(vdg("deform " + path(manifest) + " --key back_f20 --undo"), 0) << output_;
  EXPECT_LT(maxDifference(readObj((dir_ / "back_f20.obj").string()).positions, raw.base_frames[kKeyFrame]),
            kObjRoundTrip);
}

// At other frames the key's offset follows the model's offset mode (animated_model.h): skinned, it
// turns with the limb, o(f) = L_v(f) L_v(F)^-1 o(F); world, it stays the same vector (one key frame
// on the view: a constant offset over time).
TEST_P(AnimatedDeformCli, TheKeyOffsetFollowsTheOffsetModeAtOtherFrames) {
  copyWalker();
  const std::string manifest = GetParam();
  const RawViewDependentModel raw = loadManifest((dir_ / manifest).string());
  spit(dir_ / "e.json", R"({"ops": [{"op": "drag", "vertex": )" +
                            std::to_string(mostTurningVertex(loadManifest((dir_ / "walker.vdg.json").string()))) +
                            R"(, "radius": 0.25, "delta": [0.12, 0.05]}]})");
  ASSERT_EQ(vdg("deform " + path(manifest) + " --frame 20 --key back_f20 --view 0,0,-1 -q --ops " + path("e.json")), 0)
      << output_;
  const RawViewDependentModel after = loadManifest((dir_ / manifest).string());
  const AnimatedViewDependentModel model = AnimatedViewDependentModel::build(after);
  const std::vector<float>& key = after.keys.back().mesh.positions;
  const std::vector<float>& posed = after.base_frames[kKeyFrame];
  const bool skinned = after.offsets == OffsetSpace::kSkinned;
  std::vector<float> out(key.size());
  for (const int f : {0, 7, 33}) {
    ASSERT_TRUE(model.evaluate(f, kBackView, 0.0, out));
    const std::vector<float>& base = after.base_frames[static_cast<std::size_t>(f)];
    double worst = 0, turned = 0;
    for (std::size_t v = 0; v < model.vertexCount(); ++v) {
      const Eigen::Vector3d at_key(key[3 * v] - posed[3 * v], key[3 * v + 1] - posed[3 * v + 1],
                                   key[3 * v + 2] - posed[3 * v + 2]);
      const Eigen::Vector3d expected =
          skinned ? Eigen::Vector3d(skinAt(after, f, v) * skinAt(after, kKeyFrame, v).inverse() * at_key) : at_key;
      const Eigen::Vector3d got(out[3 * v] - base[3 * v], out[3 * v + 1] - base[3 * v + 1],
                                out[3 * v + 2] - base[3 * v + 2]);
      worst = std::max(worst, (got - expected).norm());
      turned = std::max(turned, (expected - at_key).norm());
    }
    EXPECT_LT(worst, kSkinRounding) << "frame " << f;
    if (skinned) {
      EXPECT_GT(turned, 0.01) << "frame " << f << ": the limb's offset should turn";
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Walker, AnimatedDeformCli, ::testing::Values("walker.vdg.json", "walker-world.vdg.json"),
                         [](const ::testing::TestParamInfo<const char*>& p) {
                           return std::string(p.index == 0 ? "Skinned" : "World");
                         });

// Bad --frame: out of range, non-zero on a static model, another frame than an existing key's,
// missing for a new key of an animated model. One line each, nothing written.
TEST_F(AnimatedDeformCli, BadFramesAreRefusedAndChangeNothing) {
  copyWalker();
  spit(dir_ / "e.json", R"({"ops": [{"op": "drag", "vertex": 3, "radius": 0.2, "delta": [0.1, 0]}]})");
  const std::string walker_before = slurp(dir_ / "walker.vdg.json"), static_before = slurp(dir_ / "m.vdg.json");
  const std::string e = " --ops " + path("e.json");
  EXPECT_EQ(vdg("deform " + path("walker.vdg.json") + " --frame 40 --key k --view 0,0,-1" + e), 1);
  EXPECT_NE(output_.find("--frame 40: outside the base animation"), std::string::npos) << output_;
  EXPECT_NE(output_.find("(frames 0..39)"), std::string::npos) << output_;
  EXPECT_EQ(vdg("deform " + path("walker.vdg.json") + " --frame -1 --key k --view 0,0,-1" + e), 1);
  EXPECT_EQ(vdg("deform " + path("m.vdg.json") + " --frame 2 --key k --view 0,1,0" + e), 1);
  EXPECT_NE(output_.find("--frame 2: "), std::string::npos) << output_;
  EXPECT_NE(output_.find("static base"), std::string::npos) << output_;
  EXPECT_EQ(vdg("deform " + path("walker.vdg.json") + " --frame 30 --key front_f10" + e), 1);
  EXPECT_NE(output_.find("key 'front_f10' is the key of frame 10"), std::string::npos) << output_;
  EXPECT_EQ(vdg("deform " + path("walker.vdg.json") + " --frame 10 --key k --view 0,0,1" + e), 1);
  EXPECT_NE(output_.find("same frame 10 as key 'front_f10'"), std::string::npos) << output_;
  EXPECT_EQ(vdg("deform " + path("walker.vdg.json") + " --key k --view 0,0,-1" + e), 2);
  EXPECT_NE(output_.find("give the frame of the new key 'k'"), std::string::npos) << output_;
  EXPECT_EQ(slurp(dir_ / "walker.vdg.json"), walker_before);
  EXPECT_EQ(slurp(dir_ / "m.vdg.json"), static_before);
  EXPECT_FALSE(fs::exists(dir_ / "k.obj"));
  // Static models keep working, with --frame 0 or without it.
  EXPECT_EQ(vdg("deform " + path("m.vdg.json") + " --frame 0 --key k --view 0,1,0 -q" + e), 0) << output_;
}

}  // namespace
}  // namespace vdg
