// End-to-end tests of `vdg morph`: run the built binary (VDG_BINARY) on images, grids, lines and key
// drawings made here; check the images it writes against the issue's numbers (t = 0 gives SRC,
// t = 1 gives DST, identical features leave SRC unchanged, one translated line pair translates the
// image), and that bad input or usage gives one line, its exit status, and writes nothing.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "support/test_meshes.h"
#include "vdg/io/morph_files.h"
#include "vdg/morph/image_morph.h"
#include "vdg/render/image.h"

namespace vdg {
namespace {
namespace fs = std::filesystem;

constexpr int kW = 40, kH = 30;
// 8-bit rounding of the float pipeline: a morph at t = 0 or 1 must give its image within one level.
constexpr int kRounding = 1;

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// A smooth pattern with a dark square: every warp moves something visible.
render::Image pattern(int w, int h, int square_x, int square_y, int shade) {
  render::Image image{w, h, std::vector<std::uint8_t>(static_cast<std::size_t>(w) * h * 4)};
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      std::uint8_t* p = image.pixel(x, y);
      const bool in_square = x >= square_x && x < square_x + 8 && y >= square_y && y < square_y + 8;
      p[0] = static_cast<std::uint8_t>(in_square ? 20 : 60 + 4 * x);
      p[1] = static_cast<std::uint8_t>(in_square ? 30 : 40 + 5 * y);
      p[2] = static_cast<std::uint8_t>(shade);
      p[3] = 255;
    }
  return image;
}

class MorphCli : public ::testing::Test {
 protected:
  void SetUp() override {
    src_ = pattern(kW, kH, 6, 6, 200);
    dst_ = pattern(kW, kH, 24, 16, 90);
    render::writePng(file("src.png"), src_);
    render::writePng(file("dst.png"), dst_);
    // A 3 x 3 grid whose middle point follows the square, and an identity grid.
    identity_ = morph::identityGrid(3, 3, kW, kH);
    morph::WarpGrid moved = identity_;
    moved.at(1, 1) = {26, 18};
    MorphGridFile grid;
    grid.rows = grid.cols = 3;
    grid.src.push_back({0, identity_});
    grid.dst.push_back({0, moved});
    writeMorphGrid(file("grid.json"), grid);
    grid.dst[0].grid = identity_;
    writeMorphGrid(file("same_grid.json"), grid);
    testing::writeText(file("lines.json"), R"({"version": 1, "lines": [
        {"src": [[6, 6], [14, 6]], "dst": [[24, 16], [32, 16]]},
        {"src": [[6, 6], [6, 14]], "dst": [[24, 16], [24, 24]]}]})");
    testing::writeText(file("same_lines.json"), R"({"version": 1, "lines": [
        {"src": [[6, 6], [14, 6]], "dst": [[6, 6], [14, 6]]}]})");
  }

  std::string file(const std::string& name) const { return dir_.file(name); }

  // A stand-in ffmpeg (a shell script) in bin/; returns the environment that puts it first on PATH.
  std::string fakeFfmpeg(const std::string& script) {
    fs::create_directories(file("bin"));
    testing::writeText(file("bin/ffmpeg"), "#!/bin/sh\n" + script);
    fs::permissions(file("bin/ffmpeg"), fs::perms::owner_all);
    return "PATH=\"" + file("bin") + ":$PATH\"";
  }

  // No temporary file of vdg's was left in the folder.
  void expectNoTemporaryFiles() {
    for (const auto& e : fs::directory_iterator(dir_.path()))
      EXPECT_NE(e.path().filename().string().rfind(".vdg-", 0), 0u) << "a temporary file was left: " << e.path();
  }

  // Runs vdg with `args` in the test's folder; returns the exit status, stdout and stderr kept.
  // `env` is put in front of the command ("PATH=/nonexistent").
  int vdg(const std::string& args, const std::string& env = "") {
    const std::string cmd =
        "cd \"" + dir_.path().string() + "\" && " + env + " \"" + VDG_BINARY + "\" " + args + " > out.txt 2> err.txt";
    const int status = std::system(cmd.c_str());
    out_ = slurp(file("out.txt"));
    err_ = slurp(file("err.txt"));
    fs::remove(file("out.txt"));
    fs::remove(file("err.txt"));
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  }

  // Exit status `code`, stderr exactly `message` and a newline, and no new file in the folder.
  void expectRefused(const std::string& args, int code, const std::string& message, const std::string& env = "") {
    std::size_t before = 0;
    for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir_.path())) ++before;
    EXPECT_EQ(vdg(args, env), code) << args << "\n" << err_;
    EXPECT_EQ(err_, message + "\n") << args;
    std::size_t after = 0;
    for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir_.path())) ++after;
    EXPECT_EQ(after, before) << args << ": a refused run wrote something";
  }

  static int maxDifference(const render::Image& a, const render::Image& b) {
    EXPECT_EQ(a.width, b.width);
    EXPECT_EQ(a.height, b.height);
    if (a.rgba.size() != b.rgba.size()) return 256;
    int worst = 0;
    for (std::size_t i = 0; i < a.rgba.size(); ++i) worst = std::max(worst, std::abs(a.rgba[i] - b.rgba[i]));
    return worst;
  }
  render::Image read(const std::string& name) const { return render::readPng(file(name)); }

  testing::TempDir dir_;
  render::Image src_, dst_;
  morph::WarpGrid identity_;
  std::string out_, err_;
};

TEST_F(MorphCli, GridMorphAtZeroAndOneGivesTheImages) {
  ASSERT_EQ(vdg("morph src.png dst.png --grid grid.json --t 0 -o t0.png"), 0) << err_;
  EXPECT_LE(maxDifference(read("t0.png"), src_), kRounding);
  ASSERT_EQ(vdg("morph src.png dst.png --grid grid.json --t 1 -o t1.png"), 0) << err_;
  EXPECT_LE(maxDifference(read("t1.png"), dst_), kRounding);
  EXPECT_EQ(out_, "wrote t1.png (40x30, t = 1)\n");
  EXPECT_EQ(err_, "");
  // Halfway is neither.
  ASSERT_EQ(vdg("morph src.png dst.png --grid grid.json --t 0.5 -o half.png -q"), 0) << err_;
  EXPECT_GT(maxDifference(read("half.png"), src_), 20);
  EXPECT_GT(maxDifference(read("half.png"), dst_), 20);
  EXPECT_EQ(out_, "");
}

TEST_F(MorphCli, LinesMorphAtZeroAndOneGivesTheImages) {
  ASSERT_EQ(vdg("morph src.png dst.png --lines lines.json --t 0 -o t0.png"), 0) << err_;
  EXPECT_LE(maxDifference(read("t0.png"), src_), kRounding);
  ASSERT_EQ(vdg("morph src.png dst.png --lines lines.json --t 1 -o t1.png"), 0) << err_;
  EXPECT_LE(maxDifference(read("t1.png"), dst_), kRounding);
}

TEST_F(MorphCli, IdenticalFeaturesLeaveTheSourceUnchanged) {
  for (const char* features : {"--grid same_grid.json", "--lines same_lines.json"}) {
    ASSERT_EQ(vdg(std::string("morph src.png dst.png ") + features + " --warp --t 0.5 -o w.png"), 0) << err_;
    EXPECT_LE(maxDifference(read("w.png"), src_), kRounding) << features;
    // Morphing an image into itself gives it back at every t.
    ASSERT_EQ(vdg(std::string("morph src.png src.png ") + features + " --t 0.3 -o m.png"), 0) << err_;
    EXPECT_LE(maxDifference(read("m.png"), src_), kRounding) << features;
  }
}

// One feature line moved 5 pixels right, and --warp: the source moves 5 pixels right, no dissolve.
TEST_F(MorphCli, WarpWithOneTranslatedLineTranslatesTheSource) {
  testing::writeText(file("shift.json"),
                     R"({"version": 1, "lines": [{"src": [[10, 10], [10, 20]], "dst": [[15, 10], [15, 20]]}]})");
  ASSERT_EQ(vdg("morph src.png dst.png --lines shift.json --warp --t 1 -o w.png"), 0) << err_;
  EXPECT_EQ(out_, "wrote w.png (40x30, t = 1, source warped only)\n");
  const render::Image w = read("w.png");
  int worst = 0;
  for (int y = 0; y < kH; ++y)
    for (int x = 5; x < kW; ++x)
      for (int c = 0; c < 4; ++c) worst = std::max(worst, std::abs(w.pixel(x, y)[c] - src_.pixel(x - 5, y)[c]));
  EXPECT_LE(worst, kRounding);
  // The destination's blue channel (90) is nowhere: nothing was dissolved in.
  for (int y = 0; y < kH; ++y) EXPECT_EQ(w.pixel(20, y)[2], 200);
}

TEST_F(MorphCli, FramesWritesTheSequenceFromSourceToDestination) {
  ASSERT_EQ(vdg("morph src.png dst.png --grid grid.json --count 5 -o seq"), 0) << err_;
  EXPECT_EQ(out_, "wrote 5 frames (40x30) to seq\n");
  EXPECT_EQ(err_, "");  // the progress bar is drawn only on a terminal
  for (int i = 0; i < 5; ++i) EXPECT_TRUE(fs::exists(file("seq/frame_000" + std::to_string(i) + ".png"))) << i;
  EXPECT_FALSE(fs::exists(file("seq/frame_0005.png")));
  EXPECT_LE(maxDifference(read("seq/frame_0000.png"), src_), kRounding);
  EXPECT_LE(maxDifference(read("seq/frame_0004.png"), dst_), kRounding);
  // Frame 2 is t = 2/4: the same image as --t 0.5.
  ASSERT_EQ(vdg("morph src.png dst.png --grid grid.json --t 0.5 -o half.png"), 0) << err_;
  EXPECT_EQ(maxDifference(read("seq/frame_0002.png"), read("half.png")), 0);
}

TEST_F(MorphCli, KeyFramedGridAnimatesTheGrids) {
  morph::WarpGrid moved = identity_;
  moved.at(1, 1) = {26, 18};
  MorphGridFile keyed;
  keyed.rows = keyed.cols = 3;
  keyed.keyed = true;
  keyed.src = {{0, identity_}, {2, identity_}};
  keyed.dst = {{0, identity_}, {2, moved}};
  writeMorphGrid(file("keys.json"), keyed);
  ASSERT_EQ(vdg("morph src.png dst.png --grid keys.json --count 3 -o seq -q"), 0) << err_;
  EXPECT_LE(maxDifference(read("seq/frame_0002.png"), dst_), kRounding);
  // Frame 1 uses the grids halfway between the keys; --t 0.5 --frame 1 is the same image.
  ASSERT_EQ(vdg("morph src.png dst.png --grid keys.json --t 0.5 --frame 1 -o one.png -q"), 0) << err_;
  EXPECT_EQ(maxDifference(read("seq/frame_0001.png"), read("one.png")), 0);
  expectRefused("morph src.png dst.png --grid keys.json --t 0.5 -o x.png", 2,
                "vdg: morph: --t with a key-framed grid (keys.json) needs --frame F, the output frame whose grids to "
                "use (see vdg morph --help)");
}

// Two animated sequences (Parent 4.10): folders of frames whose squares move, and key grids that
// follow each square. Output frame i morphs frame i of each sequence with the grids of frame i at
// t = i / (N - 1): the image the still morph of that pair of frames gives, byte for byte.
TEST_F(MorphCli, SequencesMorphFrameByFrame) {
  fs::create_directories(file("seq_a"));
  fs::create_directories(file("seq_b"));
  MorphGridFile keyed;
  keyed.rows = keyed.cols = 3;
  keyed.keyed = true;
  for (int i = 0; i < 3; ++i) {
    render::writePng(file("seq_a/frame_000" + std::to_string(i) + ".png"), pattern(kW, kH, 6 + 4 * i, 6, 200));
    render::writePng(file("seq_b/frame_000" + std::to_string(i) + ".png"), pattern(kW, kH, 24 - 2 * i, 16, 90));
    morph::WarpGrid a = identity_, b = identity_;
    a.at(1, 1) = {10.0 + 4 * i, 10};
    b.at(1, 1) = {28.0 - 2 * i, 20};
    keyed.src.push_back({static_cast<double>(i), a});
    keyed.dst.push_back({static_cast<double>(i), b});
  }
  writeMorphGrid(file("keys.json"), keyed);
  ASSERT_EQ(vdg("morph seq_a seq_b --grid keys.json --count 3 -o out -q"), 0) << err_;
  for (int i = 0; i < 3; ++i) {
    const std::string n = std::to_string(i), still = "still_" + n + ".png";
    ASSERT_EQ(vdg("morph seq_a/frame_000" + n + ".png seq_b/frame_000" + n + ".png --grid keys.json --t " +
                  std::to_string(i / 2.0) + " --frame " + n + " -o " + still + " -q"),
              0)
        << err_;
    EXPECT_EQ(maxDifference(read("out/frame_000" + n + ".png"), read(still)), 0) << "frame " << i;
    // --t with --frame on the sequences themselves reads the same pair of frames.
    ASSERT_EQ(vdg("morph seq_a seq_b --grid keys.json --t " + std::to_string(i / 2.0) + " --frame " + n + " -o pick_" +
                  n + ".png -q"),
              0)
        << err_;
    EXPECT_EQ(maxDifference(read("pick_" + n + ".png"), read(still)), 0) << "frame " << i;
  }
  EXPECT_LE(maxDifference(read("out/frame_0000.png"), read("seq_a/frame_0000.png")), kRounding);
  EXPECT_LE(maxDifference(read("out/frame_0002.png"), read("seq_b/frame_0002.png")), kRounding);
  // A still and a sequence: the still is every frame of its side.
  ASSERT_EQ(vdg("morph src.png seq_b --lines lines.json --count 3 -o mixed -q"), 0) << err_;
  EXPECT_LE(maxDifference(read("mixed/frame_0002.png"), read("seq_b/frame_0002.png")), kRounding);

  expectRefused("morph seq_a seq_b --grid keys.json --count 4 -o x", 1,
                "vdg: error: seq_a: the source sequence has 3 frames; --count 4 needs frame 3 (output frame i "
                "morphs frame i of each sequence)");
  expectRefused("morph seq_a seq_b --grid grid.json --t 0.5 -o x.png", 2,
                "vdg: morph: --t with a sequence (a folder of frames) needs --frame F, the whole number of the "
                "frame to morph (see vdg morph --help)");
  fs::create_directories(file("empty"));
  expectRefused("morph empty seq_b --grid grid.json --count 3 -o x", 1,
                "vdg: error: empty: the folder holds no PNG or JPEG frames (source sequence)");
  fs::create_directories(file("seq_c"));
  for (int i = 0; i < 3; ++i)
    render::writePng(file("seq_c/frame_000" + std::to_string(i) + ".png"), pattern(i == 1 ? 20 : kW, kH, 0, 0, 0));
  expectRefused("morph seq_a seq_c --grid grid.json --count 3 -o x", 1,
                "vdg: error: seq_c/frame_0001.png: is 20x30 pixels and seq_a/frame_0001.png is 40x30; the two "
                "images must have the same size");
}

TEST_F(MorphCli, DrawingsAreInbetweenedIntoSvgOrPngFrames) {
  testing::writeText(file("draw.json"), R"({"version": 1, "width": 32, "height": 32, "keys": [
      {"time": 0, "strokes": [[[4, 4], [28, 4]]]},
      {"time": 2, "strokes": [[[4, 28], [16, 16], [28, 28]]]}]})");
  ASSERT_EQ(vdg("morph --drawings draw.json --count 3 -o svg"), 0) << err_;
  EXPECT_EQ(out_, "wrote 3 SVG frames (32x32) to svg\n");
  const std::string first = slurp(file("svg/frame_0000.svg"));
  EXPECT_NE(first.find("<svg"), std::string::npos);
  EXPECT_NE(first.find("points=\"4,4 "), std::string::npos) << first;
  EXPECT_NE(slurp(file("svg/frame_0002.svg")).find(" 28,28\""), std::string::npos);
  ASSERT_EQ(vdg("morph --drawings draw.json --count 3 --format png -o png -q"), 0) << err_;
  const render::Image last = read("png/frame_0002.png");
  ASSERT_EQ(last.width, 32);
  EXPECT_LT(last.pixel(16, 16)[0], 64);  // on the stroke: ink
  EXPECT_EQ(last.pixel(4, 4)[0], 255);   // far from it: paper
  const render::Image first_png = read("png/frame_0000.png");
  EXPECT_LT(first_png.pixel(16, 4)[0], 64);
}

TEST_F(MorphCli, BadInputIsOneLineAndExitOne) {
  testing::writeText(file("crossing.json"),
                     R"({"version": 1, "rows": 2, "cols": 2, "src": [[0, 0], [40, 0], [0, 30], [40, 30]],
                         "dst": [[0, 0], [40, 0], [45, 30], [40, 30]]})");
  const std::string e = [&] {
    EXPECT_EQ(vdg("morph src.png dst.png --grid crossing.json --t 0.5 -o x.png"), 1);
    return err_;
  }();
  EXPECT_EQ(e.rfind("vdg: error: crossing.json: 'dst': ", 0), 0u) << e;
  EXPECT_FALSE(fs::exists(file("x.png")));
  testing::writeText(file("sizes.json"),
                     R"({"version": 1, "rows": 2, "cols": 2, "src": [[0, 0], [40, 0], [0, 30], [40, 30]],
                         "dst": [[0, 0], [20, 0], [40, 0], [0, 30], [20, 30], [40, 30]]})");
  expectRefused("morph src.png dst.png --grid sizes.json --t 0.5 -o x.png", 1,
                "vdg: error: sizes.json: 'dst': expected 4 [x, y] points, got 6");
  testing::writeText(file("zero.json"),
                     R"({"version": 1, "lines": [{"src": [[3, 3], [3, 3]], "dst": [[0, 0], [0, 1]]}]})");
  EXPECT_EQ(vdg("morph src.png dst.png --lines zero.json --t 0.5 -o x.png"), 1);
  EXPECT_EQ(err_.rfind("vdg: error: zero.json: 'lines': ", 0), 0u) << err_;
  EXPECT_EQ(std::count(err_.begin(), err_.end(), '\n'), 1) << err_;
  EXPECT_FALSE(fs::exists(file("x.png")));
  render::writePng(file("small.png"), pattern(20, 30, 0, 0, 0));
  expectRefused("morph src.png small.png --grid grid.json --t 0.5 -o x.png", 1,
                "vdg: error: small.png: is 20x30 pixels and src.png is 40x30; the two images must have the same size");
  expectRefused("morph missing.png dst.png --grid grid.json --t 0.5 -o x.png", 1,
                "vdg: error: missing.png: no such file (image)");
  expectRefused("morph src.png dst.png --grid nogrid.json --count 3 -o seq", 1,
                "vdg: error: nogrid.json: no such file (morph grid)");
  expectRefused("morph --drawings nokeys.json --count 3 -o seq", 1,
                "vdg: error: nokeys.json: no such file (key drawings)");
}

TEST_F(MorphCli, BadUsageIsOneLineAndExitTwo) {
  const std::string see = " (see vdg morph --help)";
  expectRefused("morph src.png dst.png --t 0.5 -o x.png", 2,
                "vdg: morph: give exactly one of --grid FILE or --lines FILE" + see);
  expectRefused("morph src.png dst.png --grid grid.json --lines lines.json --t 0.5 -o x.png", 2,
                "vdg: morph: give exactly one of --grid FILE or --lines FILE" + see);
  expectRefused("morph src.png dst.png --grid grid.json -o x.png", 2,
                "vdg: morph: give exactly one of --t T (one image) or --count N (a sequence)" + see);
  expectRefused("morph src.png dst.png --grid grid.json --t 0.5 --count 3 -o x", 2,
                "vdg: morph: give exactly one of --t T (one image) or --count N (a sequence)" + see);
  expectRefused("morph src.png dst.png --grid grid.json --count 1 -o x", 2,
                "vdg: morph: --count: an image morph needs N >= 2 (frame 0 is SRC, frame N-1 DST)" + see);
  expectRefused("morph src.png --grid grid.json --t 0.5 -o x.png", 2,
                "vdg: morph: give SRC and DST images (or --drawings KEYS.json)" + see);
  expectRefused("morph src.png dst.png --grid grid.json --count 3 -o seq --video seq.avi", 2,
                "vdg: morph: --video: expected a file name ending in .mp4 or .gif, got 'seq.avi'" + see);
  expectRefused("morph src.png dst.png --grid grid.json --t 0.5 -o x.png --video x.mp4", 2,
                "vdg: morph: --video: needs --count N" + see);
  expectRefused("morph --drawings d.json src.png -o x --count 2", 2,
                "vdg: morph: --drawings takes no SRC or DST images" + see);
  EXPECT_EQ(vdg("morph src.png dst.png --grid grid.json --t 1.5 -o x.png"), 2);
  EXPECT_EQ(err_.rfind("vdg: morph: --t: ", 0), 0u) << err_;
  EXPECT_FALSE(fs::exists(file("x.png")));
}

// A stand-in ffmpeg that writes its arguments into the file it is asked to make: the video is
// encoded from the frames just written and renamed into place.
TEST_F(MorphCli, VideoIsEncodedFromTheFramesByFfmpeg) {
  const std::string env = fakeFfmpeg("for a; do last=$a; done\necho \"$@\" > \"$last\"\n");
  ASSERT_EQ(vdg("morph src.png dst.png --grid grid.json --count 3 -o seq --video seq.gif -q", env), 0) << err_;
  const std::string args = slurp(file("seq.gif"));
  EXPECT_EQ(args.rfind("-loglevel error -y -framerate 24 -start_number 0 -i seq/frame_%04d.png -frames:v 3 ", 0), 0u)
      << args;
  EXPECT_NE(args.find("palettegen"), std::string::npos) << args;
  EXPECT_TRUE(fs::exists(file("seq/frame_0002.png")));
  expectNoTemporaryFiles();
}

// An ffmpeg that never exits is stopped after VDG_FFMPEG_TIMEOUT seconds (here 1; by default 60 s
// + 2 s per frame), killed with whatever it started (the script's own sleep) and reaped; one line
// naming the video, nothing left of it.
TEST_F(MorphCli, AnFfmpegThatNeverExitsIsStoppedAfterItsTimeout) {
  const std::string env = fakeFfmpeg("echo starting >&2\nsleep 600\n");
  EXPECT_EQ(
      vdg("morph src.png dst.png --grid grid.json --count 3 -o seq --video seq.mp4 -q", env + " VDG_FFMPEG_TIMEOUT=1"),
      1);
  EXPECT_EQ(err_,
            "vdg: error: --video seq.mp4: ffmpeg did not finish within 1 s and was stopped (the frames are in seq; "
            "VDG_FFMPEG_TIMEOUT sets the seconds)\n");
  EXPECT_FALSE(fs::exists(file("seq.mp4")));
  expectNoTemporaryFiles();
}

// A failing ffmpeg's many lines become one: the video named, the exit status, ffmpeg's last line.
TEST_F(MorphCli, AFailingFfmpegIsOneLineWithItsLastLineAndStatus) {
  std::string env = fakeFfmpeg(
      "for i in $(seq 1 200); do echo \"noise $i\" >&2; done\n"
      "printf 'seq.mp4: Invalid argument\\n\\n' >&2\nexit 3\n");
  EXPECT_EQ(vdg("morph src.png dst.png --grid grid.json --count 3 -o seq --video seq.mp4 -q", env), 1);
  EXPECT_EQ(err_,
            "vdg: error: --video seq.mp4: ffmpeg failed (exit status 3): seq.mp4: Invalid argument (the frames are in "
            "seq)\n");
  EXPECT_FALSE(fs::exists(file("seq.mp4")));
  // Nothing on stderr: the exit status alone.
  env = fakeFfmpeg("exit 9\n");
  EXPECT_EQ(vdg("morph src.png dst.png --grid grid.json --count 3 -o seq --video seq.mp4 -q", env), 1);
  EXPECT_EQ(err_, "vdg: error: --video seq.mp4: ffmpeg failed (exit status 9) (the frames are in seq)\n");
}

TEST_F(MorphCli, ABadFfmpegTimeoutIsRefusedBeforeAnyFrame) {
  const std::string env = fakeFfmpeg("exit 0\n");
  expectRefused("morph src.png dst.png --grid grid.json --count 3 -o seq --video seq.mp4", 1,
                "vdg: error: VDG_FFMPEG_TIMEOUT: expected a number of seconds > 0, got 'soon'",
                env + " VDG_FFMPEG_TIMEOUT=soon");
}

// The work is estimated from the images, the features and the frames before any pixel.
TEST_F(MorphCli, WorkPastTheBudgetIsRefusedUpFront) {
  expectRefused("morph src.png dst.png --lines lines.json --t 0.5 -o x.png --budget 1000", 1,
                "vdg: error: lines.json: needs about 6000 operations (" + std::to_string(kW) + "x" +
                    std::to_string(kH) +
                    " pixels x 2 lines x 2 images x 1 frame), more than the budget of 1000; "
                    "give --budget N to allow more, or fewer lines, pixels or frames");
  EXPECT_EQ(vdg("morph src.png dst.png --lines lines.json --t 0.5 -o x.png --budget 1e6"), 0) << err_;
  expectRefused("morph src.png dst.png --grid grid.json --count 100 -o seq --budget 1e5", 1,
                "vdg: error: grid.json: needs about 1.61e+06 operations (" + std::to_string(kW) + "x" +
                    std::to_string(kH) +
                    " pixels x a 3x3 grid x 2 images x 100 frames), more than the budget of "
                    "100000; give --budget N to allow more, or fewer grid points, pixels or frames");
}

// With the real ffmpeg (skipped where it is not installed, unless VDG_REQUIRE_FFMPEG is set).
TEST_F(MorphCli, VideoWithTheRealFfmpeg) {
  if (std::system("command -v ffmpeg > /dev/null 2>&1") != 0) {
    if (std::getenv("VDG_REQUIRE_FFMPEG")) FAIL() << "VDG_REQUIRE_FFMPEG is set but ffmpeg is not on PATH";
    GTEST_SKIP() << "ffmpeg is not on PATH";
  }
  ASSERT_EQ(vdg("morph src.png dst.png --grid grid.json --frames 3 -o seq --video seq.mp4 -q"), 0) << err_;
  EXPECT_EQ(slurp(file("seq.mp4")).substr(4, 4), "ftyp");
}

TEST_F(MorphCli, VideoWithoutFfmpegIsOneLine) {
  expectRefused(
      "morph src.png dst.png --grid grid.json --count 3 -o seq --video seq.mp4", 1,
      "vdg: error: --video seq.mp4: writing a video needs the 'ffmpeg' program, which is not on PATH; install "
      "it, or leave out --video (the frames go to -o DIR)",
      "PATH=/nonexistent");
}

}  // namespace
}  // namespace vdg
