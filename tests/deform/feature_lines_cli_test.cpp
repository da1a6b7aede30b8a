// End-to-end tests of `vdg deform --lines PAIRS.json` (vdg/deform/feature_lines.h): the built
// binary (VDG_BINARY) makes a key from feature-line pairs, logs it as a "lines" op that replays to
// the written key, and refuses bad pairs files and bad usage with one line, writing nothing.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "test_meshes.h"
#include "vdg/deform/key_edit.h"
#include "vdg/io/edit_script.h"
#include "vdg/io/manifest.h"
#include "vdg/io/obj.h"

namespace vdg {
namespace {
namespace fs = std::filesystem;

class DeformLinesCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("vdg_deform_lines_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    writeObj((dir_ / "base.obj").string(), test::sphere(12, 24, 1.0));
    spit("m.vdg.json", R"({"version": 1, "base": "base.obj", "keys": []})");
    spit("pairs.json", R"({"version": 1, "lines": [{"src": [[60, 200], [120, 60]], "dst": [[40, 200], [100, 50]]}]})");
  }
  void TearDown() override { fs::remove_all(dir_); }
  void spit(const std::string& name, const std::string& text) { std::ofstream(dir_ / name) << text; }
  int vdg(const std::string& args) {
    const fs::path out = dir_ / "out.txt";
    const std::string cmd = "cd \"" + dir_.string() + "\" && \"" + VDG_BINARY + "\" " + args + " > out.txt 2>&1";
    const int status = std::system(cmd.c_str());
    std::ifstream in(out);
    std::ostringstream s;
    s << in.rdbuf();
    output_ = s.str();
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  }
  fs::path dir_;
  std::string output_;
};

TEST_F(DeformLinesCli, MakesAKeyWhoseLogReplaysToIt) {
  ASSERT_EQ(vdg("deform m.vdg.json --key side --view 0,0.3,1 --lines pairs.json --size 256x256"), 0) << output_;
  EXPECT_NE(output_.find("lines"), std::string::npos) << output_;
  const TriMesh base = readObj((dir_ / "base.obj").string());
  const TriMesh key = readObj((dir_ / "side.obj").string());
  EXPECT_NE(key.positions, base.positions);
  const EditLog log = readEditLog((dir_ / "side.edits.json").string());
  ASSERT_EQ(log.entries.size(), 1u);
  ASSERT_EQ(log.entries[0].ops.size(), 1u);
  EXPECT_EQ(editKind(log.entries[0].ops[0]), EditKind::kLines);
  EXPECT_EQ(log.entries[0].image_size, (std::array<int, 2>{256, 256}));
  EXPECT_EQ(replayEditLog(base, log, "log"), key.positions);
  EXPECT_EQ(loadManifest((dir_ / "m.vdg.json").string()).keys.size(), 1u);
  // Snapping rewrites the model side in the log; undo removes the step.
  ASSERT_EQ(vdg("deform m.vdg.json --key side --lines pairs.json --size 256x256 --snap-silhouette"), 0) << output_;
  const EditLog two = readEditLog((dir_ / "side.edits.json").string());
  ASSERT_EQ(two.entries.size(), 2u);
  EXPECT_NE(std::get<LinesOp>(two.entries[1].ops[0]).pairs[0].model_p, Eigen::Vector2d(60, 200));
  ASSERT_EQ(vdg("deform m.vdg.json --key side --undo"), 0) << output_;
  EXPECT_EQ(readObj((dir_ / "side.obj").string()).positions, key.positions);
}

TEST_F(DeformLinesCli, BadPairsAndUsageGiveOneLineAndWriteNothing) {
  spit("bad.json", R"({"version": 1, "lines": [{"src": [[60, 200], [60, 200]], "dst": [[40, 200], [100, 50]]}]})");
  const std::pair<std::string, int> cases[] = {
      {"--lines bad.json --size 256x256", 1}, {"--lines missing.json --size 256x256", 1}, {"--lines pairs.json", 2},
      {"--lines pairs.json --size 0x256", 2}, {"--ops pairs.json --snap-silhouette", 2},
  };
  for (const auto& [args, code] : cases) {
    EXPECT_EQ(vdg("deform m.vdg.json --key side --view 0,0,1 " + args), code) << args << ": " << output_;
    EXPECT_EQ(std::count(output_.begin(), output_.end(), '\n'), 1) << args << ": " << output_;
    EXPECT_FALSE(fs::exists(dir_ / "side.obj")) << args;
  }
  EXPECT_EQ(vdg("deform m.vdg.json --key side --view 0,0,1 --lines bad.json --size 256x256"), 1);
  EXPECT_NE(output_.find("bad.json: 'lines'[0].'src': the line has no length"), std::string::npos) << output_;
}

}  // namespace
}  // namespace vdg
