// `vdg render` end to end: frames written, --frames ranges byte-identical, and every bad input
// gives one clear line and exit status 1 (bad usage: 2).
#include <gtest/gtest.h>
#include <unistd.h>

#include <sys/wait.h>
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#ifdef VDG_CLI

namespace {

namespace fs = std::filesystem;
const std::string kSource = VDG_SOURCE_DIR;
const std::string kSpot = kSource + "/examples/spot/spot.vdg.json";

struct Result {
  int status = -1;
  std::string output;  // stdout + stderr
};

// A name unique to this process and test: ctest runs tests in parallel processes.
std::string uniqueName(const std::string& stem) {
  return stem + "_" + std::to_string(::getpid()) + "_" +
         ::testing::UnitTest::GetInstance()->current_test_info()->name();
}

Result vdg(const std::string& args, const std::string& env = "") {
  const std::string log = testing::TempDir() + "/" + uniqueName("vdg_cli_render") + ".log";
  const std::string cmd = env + " " + VDG_CLI + " " + args + " > " + log + " 2>&1";
  const int raw = std::system(cmd.c_str());
  Result r;
  r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  std::ifstream in(log);
  std::stringstream ss;
  ss << in.rdbuf();
  r.output = ss.str();
  return r;
}

std::string readBytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

fs::path freshDir(const std::string& name) {
  const fs::path dir = fs::path(testing::TempDir()) / uniqueName(name);
  fs::remove_all(dir);
  return dir;
}

TEST(CliRender, OrbitWritesFramesAndRangesAreByteIdentical) {
  const fs::path all = freshDir("vdg_render_all"), part = freshDir("vdg_render_part");
  const std::string common = " --orbit 6 --size 96x96 --observer --sphere --quiet";
  Result r = vdg("render " + kSpot + " -o " + all.string() + common);
  ASSERT_EQ(r.status, 0) << r.output;
  r = vdg("render " + kSpot + " -o " + part.string() + common + " --frames 3-4");
  ASSERT_EQ(r.status, 0) << r.output;
  for (int f = 0; f < 6; ++f) {
    char name[32];
    std::snprintf(name, sizeof name, "frame_%04d.png", f);
    EXPECT_TRUE(fs::exists(all / name)) << name;
    EXPECT_EQ(fs::exists(part / name), f == 3 || f == 4) << name;
  }
  EXPECT_EQ(readBytes(all / "frame_0003.png"), readBytes(part / "frame_0003.png"));
  EXPECT_EQ(readBytes(all / "frame_0004.png"), readBytes(part / "frame_0004.png"));
  EXPECT_NE(readBytes(all / "frame_0000.png"), readBytes(all / "frame_0003.png"));
}

// An animated model advances one animation frame per output frame; the frame follows from the
// output frame's number alone, so ranges stay byte-identical. A near-still camera (a huge orbit)
// makes the animation the visible change: the tetrahedron moves by its own size each frame.
TEST(CliRender, AnimatedModelsAdvanceOneFramePerOutputFrameAndRangesAreByteIdentical) {
  const std::string model = kSource + "/tests/io/formats/tetra_walk_v2.vdg.json";
  const fs::path all = freshDir("vdg_render_anim_all"), part = freshDir("vdg_render_anim_part");
  const std::string common = " --orbit 1000000 --size 128x128 --quiet";
  Result r = vdg("render " + model + " -o " + all.string() + common + " --frames 0-4");
  ASSERT_EQ(r.status, 0) << r.output;
  r = vdg("render " + model + " -o " + part.string() + common + " --frames 3-4");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(readBytes(all / "frame_0003.png"), readBytes(part / "frame_0003.png"));
  EXPECT_EQ(readBytes(all / "frame_0004.png"), readBytes(part / "frame_0004.png"));
  EXPECT_NE(readBytes(all / "frame_0000.png"), readBytes(all / "frame_0001.png"));
  EXPECT_NE(readBytes(all / "frame_0001.png"), readBytes(all / "frame_0002.png"));
}

// The paper's Figures 10-12 on the walker: --hold-frame keeps one animation frame under a moving
// camera (frames differ only by the camera), --base-only draws the walk without its keys. Seen
// from the side at key frame 10 the view-dependent walker (its side key) differs from the base.
TEST(CliRender, HoldFrameAndBaseOnlyOnTheWalker) {
  const std::string model = kSource + "/examples/walk/walker.vdg.json";
  const fs::path held = freshDir("vdg_render_held"), base = freshDir("vdg_render_base"), vd = freshDir("vdg_render_vd");
  // --orbit 4 --frames 1: azimuth 90, the side view; output frame 1 shows animation frame 1.
  const std::string side = " --orbit 4 --frames 1 --size 96x96 --quiet";
  Result r = vdg("render " + model + " -o " + held.string() + side + " --hold-frame 10");
  ASSERT_EQ(r.status, 0) << r.output;
  r = vdg("render " + model + " -o " + base.string() + side + " --hold-frame 10 --base-only");
  ASSERT_EQ(r.status, 0) << r.output;
  r = vdg("render " + model + " -o " + vd.string() + side);  // animation frame 1, not 10
  ASSERT_EQ(r.status, 0) << r.output;
  const std::string held_png = readBytes(held / "frame_0001.png");
  EXPECT_NE(held_png, readBytes(base / "frame_0001.png"));  // the side key shows
  EXPECT_NE(held_png, readBytes(vd / "frame_0001.png"));    // another moment of the walk
}

// The surface options: on the teapot (patch seams welded; lid and body rims are true borders),
// --no-borders and --creases each change the frame, --no-materials leaves a mesh without
// materials as it was.
TEST(CliRender, SurfaceOptionsOnTheTeapot) {
  const std::string teapot = kSource + "/examples/meshes/teapot.obj";
  const std::string common = " --size 96x96 --elevation 30 --quiet";
  std::vector<std::string> frames;
  for (const std::string option : {"", " --no-borders", " --creases 20", " --no-materials"}) {
    const fs::path dir = freshDir("vdg_render_teapot" + std::to_string(frames.size()));
    const Result r = vdg("render " + teapot + " -o " + dir.string() + common + option);
    ASSERT_EQ(r.status, 0) << option << ": " << r.output;
    frames.push_back(readBytes(dir / "frame_0000.png"));
    ASSERT_FALSE(frames.back().empty()) << option;
  }
  EXPECT_NE(frames[0], frames[1]) << "--no-borders";
  EXPECT_NE(frames[0], frames[2]) << "--creases";
  EXPECT_EQ(frames[0], frames[3]) << "--no-materials on a mesh without materials";
}

// A full disk (here a file size limit, which fails writes the same way) is an error naming the
// frame, exit status 1, and a frame already there stays byte-identical.
TEST(CliRender, FullDiskFailsAndKeepsExistingFrames) {
  const fs::path dir = freshDir("vdg_render_full");
  Result r = vdg("render " + kSpot + " -o " + dir.string() + " --size 96x96 --quiet");
  ASSERT_EQ(r.status, 0) << r.output;
  const std::string frame = readBytes(dir / "frame_0000.png");
  ASSERT_GT(frame.size(), 1024u);  // more than the 1-block limit below
  r = vdg("render " + kSpot + " -o " + dir.string() + " --size 96x96 --azimuth 90 --quiet",
          "trap '' XFSZ; ulimit -f 1;");
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("frame_0000.png: cannot write file: File too large"), std::string::npos) << r.output;
  EXPECT_EQ(readBytes(dir / "frame_0000.png"), frame);
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
  EXPECT_EQ(names, std::vector<std::string>{"frame_0000.png"});
  fs::remove_all(dir);
}

void expectOneLineError(const Result& r, int status, const std::string& needle) {
  EXPECT_EQ(r.status, status) << r.output;
  EXPECT_NE(r.output.find(needle), std::string::npos) << r.output;
  EXPECT_LE(std::count(r.output.begin(), r.output.end(), '\n'), 2) << r.output;
}

// Materials: the teapot with one material per part renders in their colours (--no-materials: in
// --color); a texture that is missing is one warning naming it and the frame is still written,
// or with --strict an error that writes nothing.
TEST(CliRender, MaterialsWarningsAndStrict) {
  const std::string common = " --size 64x64 --quiet";
  const fs::path parts = freshDir("vdg_render_parts"), plain = freshDir("vdg_render_parts_plain");
  Result r = vdg("render " + kSource + "/examples/meshes/teapot-parts.obj -o " + parts.string() + common);
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(r.output, "");
  r = vdg("render " + kSource + "/examples/meshes/teapot-parts.obj -o " + plain.string() + common + " --no-materials");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(readBytes(parts / "frame_0000.png"), readBytes(plain / "frame_0000.png"));

  const fs::path dir = freshDir("vdg_render_missing_texture");
  fs::create_directories(dir);
  std::ofstream(dir / "tri.obj") << "mtllib tri.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\n"
                                    "usemtl red\nf 1/1 2/2 3/3\n";
  std::ofstream(dir / "tri.mtl") << "newmtl red\nKd 0.8 0.1 0.1\nmap_Kd gone.png\n";
  const fs::path out = dir / "frames";
  r = vdg("render " + (dir / "tri.obj").string() + " -o " + out.string() + common);
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(r.output.rfind("warning: ", 0), 0u) << r.output;
  EXPECT_NE(r.output.find("gone.png"), std::string::npos) << r.output;
  EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
  EXPECT_TRUE(fs::exists(out / "frame_0000.png"));

  const fs::path strict_out = dir / "strict";
  expectOneLineError(vdg("render " + (dir / "tri.obj").string() + " -o " + strict_out.string() + common + " --strict"),
                     1, "gone.png");
  EXPECT_FALSE(fs::exists(strict_out / "frame_0000.png"));
}

TEST(CliRender, HoldFrameNeedsAnAnimatedModelAndAFrameInRange) {
  const std::string walker = kSource + "/examples/walk/walker.vdg.json";
  expectOneLineError(vdg("render " + kSpot + " -o " + freshDir("x").string() + " --hold-frame 0"), 2, "--hold-frame: ");
  expectOneLineError(vdg("render " + walker + " -o " + freshDir("x").string() + " --hold-frame 40"), 2,
                     "expected a frame in [0, 39]");
}

TEST(CliRender, UnknownModelFile) {
  expectOneLineError(vdg("render /nonexistent/model.vdg.json -o " + freshDir("x").string()), 1,
                     "/nonexistent/model.vdg.json");
}

TEST(CliRender, SizeZeroOrHuge) {
  // A bad option value is bad usage (exit 2), whatever makes it bad.
  expectOneLineError(vdg("render " + kSpot + " -o " + freshDir("x").string() + " --size 0x64"), 2, "--size");
  expectOneLineError(vdg("render " + kSpot + " -o " + freshDir("x").string() + " --size 20000x64"), 2, "16384");
  expectOneLineError(vdg("render " + kSpot + " -o " + freshDir("x").string() + " --size big"), 2, "--size");
}

TEST(CliRender, NoOpenGl) {
  expectOneLineError(vdg("render " + kSpot + " -o " + freshDir("x").string(), "VDG_RENDER_NO_GL=1"), 1,
                     "EGL: no display");
}

TEST(CliRender, FramesOutsideTheOrbit) {
  expectOneLineError(vdg("render " + kSpot + " -o " + freshDir("x").string() + " --orbit 4 --frames 2-9"), 2,
                     "--frames");
}

TEST(CliRender, VideoWithoutFfmpeg) {
  // An empty PATH hides ffmpeg whether or not it is installed.
  const Result r = vdg("render " + kSpot + " -o " + testing::TempDir() + "/x.mp4", "PATH=/nonexistent");
  expectOneLineError(r, 1, "ffmpeg");
}

}  // namespace

#endif  // VDG_CLI
