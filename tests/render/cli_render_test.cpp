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
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "support/test_meshes.h"
#include "vdg/io/image_file.h"
#include "vdg/io/obj.h"
#include "vdg/render/image.h"

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

// vdg reads its own exports as the same model: the textured Spot and the coloured walker, exported
// (uv seams split, materials as primitives, _VDG_VERTEX welded back), render as their manifests do:
// no channel off by more than one level. (Not byte for byte: glTF's texture coordinates have their
// origin at the top, and v -> 1 - v -> 1 - (1 - v) loses the low bits of a small v, so a texel
// read at a patch's edge may differ in the last bits; the hue rule's dark ramp, (value - 0.2) / 0.3,
// can then round a channel the other way.)
TEST(CliRender, TexturedAndColouredExportsRenderLikeTheirManifests) {
  for (const std::string& model : {kSpot, kSource + "/examples/walk/walker.vdg.json"}) {
    const fs::path dir = freshDir("vdg_render_export");
    fs::create_directories(dir);
    Result r = vdg("export " + model + " -q -o " + (dir / "m.glb").string());
    ASSERT_EQ(r.status, 0) << r.output;
    const std::string common = " --orbit 3 --size 96x96 --quiet";
    r = vdg("render " + model + " -o " + (dir / "manifest").string() + common);
    ASSERT_EQ(r.status, 0) << r.output;
    r = vdg("render " + (dir / "m.glb").string() + " -o " + (dir / "export").string() + common);
    ASSERT_EQ(r.status, 0) << r.output;
    constexpr int kRoundingLevels = 1;
    for (const char* frame : {"frame_0000.png", "frame_0001.png", "frame_0002.png"}) {
      const vdg::render::ImageDiff d =
          vdg::render::compareImages(vdg::render::readPng((dir / "export" / frame).string()),
                                     vdg::render::readPng((dir / "manifest" / frame).string()), kRoundingLevels);
      EXPECT_TRUE(d.same_size) << model << " " << frame;
      EXPECT_EQ(d.differing_pixels, 0) << model << " " << frame << ": max channel difference "
                                       << d.max_channel_difference;
    }
  }
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

// --drawing-textures (docs/drawing-textures.md) on the spot example's synthesised drawings: between the
// front and left keys the drawings' ink blends into ghost lines, which fill-ink removes (the
// silhouettes are the same in both pictures); every misuse is one line.
TEST(CliRender, DrawingTexturesFillInkRemovesGhostLinesAndMisuseIsOneLine) {
  const std::string drawings = kSource + "/examples/spot/spot-drawings.vdg.json";
  const std::string between = " --orbit 1 --azimuth 225 --elevation 8 --size 160x160 --quiet --drawing-textures";
  const fs::path as_drawn = freshDir("vdg_render_as_drawn"), fill = freshDir("vdg_render_fill_ink");
  Result r = vdg("render " + drawings + " -o " + as_drawn.string() + between);
  ASSERT_EQ(r.status, 0) << r.output;
  r = vdg("render " + drawings + " -o " + fill.string() + between + " --drawing-mode fill-ink");
  ASSERT_EQ(r.status, 0) << r.output;
  // Ghost lines are ink blended into paint: pixels of luminance in [0.1, 0.5), darker than the paint
  // (at least 0.3 a channel, most of it far lighter) and lighter than the silhouettes' ink.
  const auto ghostly = [](const fs::path& file) {
    const vdg::render::Image image = vdg::render::readPng(file.string());
    long count = 0;
    for (std::size_t p = 0; p + 3 < image.rgba.size(); p += 4) {
      const int luminance = 299 * image.rgba[p] + 587 * image.rgba[p + 1] + 114 * image.rgba[p + 2];
      count += luminance >= 100 * 255 && luminance < 500 * 255;
    }
    return count;
  };
  const long ghosts = ghostly(as_drawn / "frame_0000.png"), filled = ghostly(fill / "frame_0000.png");
  EXPECT_GT(ghosts, filled + filled / 2) << "as drawn " << ghosts << " ghostly pixels, fill-ink " << filled;

  const std::string out = " -o " + freshDir("x").string();
  expectOneLineError(vdg("render " + drawings + out + " --drawing-mode flat"), 2,
                     "--drawing-mode, --contour-threshold and --contour-dilation need --drawing-textures");
  expectOneLineError(vdg("render " + kSpot + out + " --drawing-textures"), 2,
                     "--drawing-textures: " + kSpot + " has no key with a 'drawing' (manifest version 5)");
  expectOneLineError(vdg("render " + drawings + out + " --drawing-textures --gpu-blend"), 2,
                     "--drawing-textures: not with --gpu-blend");
  expectOneLineError(vdg("render " + drawings + out + " --drawing-textures --contour-threshold 0"), 2,
                     "--contour-threshold");
  expectOneLineError(vdg("render " + drawings + out + " --drawing-textures --contour-dilation 65"), 2,
                     "--contour-dilation");
  // A drawing that is not an image: bad input (1), naming the manifest, the key and the file.
  const fs::path dir = freshDir("vdg_render_bad_drawing");
  fs::create_directories(dir);
  fs::copy_file(kSource + "/examples/spot/spot.obj", dir / "spot.obj");
  std::ofstream(dir / "broken.png") << "not a picture";
  std::ofstream(dir / "m.vdg.json")
      << R"({"version": 5, "base": "spot.obj", "keys": [{"name": "front", "mesh": "spot.obj", )"
      << R"("camera": {"eye": [0, 0, -3], "target": [0, 0, 0], "fov_deg": 40}, "drawing": "broken.png"}]})";
  expectOneLineError(vdg("render " + (dir / "m.vdg.json").string() + out + " --drawing-textures"), 1,
                     "m.vdg.json: key 'front' (keys[0]): drawing 'broken.png': ");
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

TEST(CliRender, LineWidthModes) {
  // Framed by the default distance, the model spans more than half the height: the screen mode
  // draws the fixed width (byte for byte); from far away its strokes thin out.
  const std::string common = " --size 96x96 --quiet";
  std::map<std::string, std::string> frames;
  for (const std::string mode : {"fixed", "screen"})
    for (const std::string distance : {"", " --distance 40"}) {
      const fs::path dir = freshDir("vdg_render_width");
      const Result r =
          vdg("render " + kSpot + " -o " + dir.string() + common + distance + " --line-width-mode " + mode);
      ASSERT_EQ(r.status, 0) << r.output;
      frames[mode + distance] = readBytes(dir / "frame_0000.png");
    }
  EXPECT_EQ(frames["fixed"], frames["screen"]);
  EXPECT_NE(frames["fixed --distance 40"], frames["screen --distance 40"]);
  const std::string out = " -o " + freshDir("x").string();
  expectOneLineError(vdg("render " + kSpot + out + " --line-width-mode fixed --line-width-min 2"), 2,
                     "--line-width-min: only with --line-width-mode screen");
  expectOneLineError(vdg("render " + kSpot + out + " --line-width-min 3 --line-width-max 2"), 2,
                     "--line-width-max: expected at least --line-width-min (3), got 2");
  expectOneLineError(vdg("render " + kSpot + out + " --line-width-mode wide"), 2, "--line-width-mode");
  expectOneLineError(vdg("render " + kSpot + out + " --line-width-min 0"), 2, "--line-width-min");
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

// The video is encoded by ffmpeg from the frames just written, with the same flags as `vdg morph
// --video` (a stand-in ffmpeg writes its arguments into the file it is asked to make), renamed into
// place, and the scratch folder of frames is removed.
TEST(CliRender, VideoIsEncodedFromTheFramesByFfmpeg) {
  const fs::path dir = freshDir("vdg_render_video");
  fs::create_directories(dir / "bin");
  std::ofstream(dir / "bin/ffmpeg") << "#!/bin/sh\nfor a; do last=$a; done\necho \"$@\" > \"$last\"\n";
  fs::permissions(dir / "bin/ffmpeg", fs::perms::owner_all);
  const fs::path video = dir / "orbit.gif";
  const Result r = vdg("render " + kSpot + " -o " + video.string() + " --orbit 4 --frames 1-2 --size 32x32 -q",
                       "PATH=\"" + (dir / "bin").string() + ":$PATH\"");
  ASSERT_EQ(r.status, 0) << r.output;
  const std::string args = readBytes(video);
  EXPECT_EQ(args.rfind("-loglevel error -y -framerate 24 -start_number 1 -i " + video.string() +
                           ".frames/frame_%04d.png -frames:v 2 ",
                       0),
            0u)
      << args;
  EXPECT_NE(args.find("palettegen"), std::string::npos) << args;
  EXPECT_FALSE(fs::exists(video.string() + ".frames"));
  for (const auto& e : fs::directory_iterator(dir))
    EXPECT_NE(e.path().filename().string().rfind(".vdg-", 0), 0u) << "a temporary file was left: " << e.path();
}

// With the real ffmpeg (skipped where it is not installed, unless VDG_REQUIRE_FFMPEG is set): an
// MP4 and a GIF that start as those formats do.
TEST(CliRender, VideoWithTheRealFfmpeg) {
  if (std::system("command -v ffmpeg > /dev/null 2>&1") != 0) {
    if (std::getenv("VDG_REQUIRE_FFMPEG")) FAIL() << "VDG_REQUIRE_FFMPEG is set but ffmpeg is not on PATH";
    GTEST_SKIP() << "ffmpeg is not on PATH";
  }
  const fs::path dir = freshDir("vdg_render_real_video");
  fs::create_directories(dir);
  for (const char* name : {"orbit.mp4", "orbit.gif"}) {
    const Result r = vdg("render " + kSpot + " -o " + (dir / name).string() + " --orbit 3 --size 33x31 -q");
    ASSERT_EQ(r.status, 0) << name << ": " << r.output;
  }
  EXPECT_EQ(readBytes(dir / "orbit.mp4").substr(4, 4), "ftyp");
  EXPECT_EQ(readBytes(dir / "orbit.gif").substr(0, 6), "GIF89a");
}

// --gpu-blend: the frames of the CPU path within the GPU blend tests' tolerance (a pixel differs
// when a channel is off by more than 48 levels; at most 0.4% of the pixels may), and one clear
// line for a model the GPU blend does not take (bad usage) or an OpenGL older than 4.3.
TEST(CliRender, GpuBlendFramesMatchTheCpuFramesAndItsErrorsAreOneLine) {
  constexpr int kLevels = 48;
  constexpr double kMaxDifferingFraction = 0.004;
  const fs::path cpu = freshDir("cpu"), gpu = freshDir("gpu");
  ASSERT_EQ(vdg("render " + kSpot + " -o " + cpu.string() + " --orbit 3 --size 96x96 -q").status, 0);
  const Result r = vdg("render " + kSpot + " -o " + gpu.string() + " --orbit 3 --size 96x96 -q --gpu-blend");
  ASSERT_EQ(r.status, 0) << r.output;
  for (const char* frame : {"frame_0000.png", "frame_0001.png", "frame_0002.png"}) {
    const vdg::render::ImageDiff d = vdg::render::compareImages(vdg::render::readPng((cpu / frame).string()),
                                                                vdg::render::readPng((gpu / frame).string()), kLevels);
    EXPECT_TRUE(d.same_size) << frame;
    EXPECT_LE(d.differing_fraction, kMaxDifferingFraction) << frame;
  }
  expectOneLineError(
      vdg("render " + kSource + "/examples/meshes/teapot.obj -o " + freshDir("x").string() + " --gpu-blend"), 2,
      "--gpu-blend: ");
  expectOneLineError(
      vdg("render " + kSource + "/examples/walk/walker.vdg.json -o " + freshDir("x").string() + " --gpu-blend"), 2,
      "an animated model");
  expectOneLineError(vdg("render " + kSpot + " -o " + freshDir("x").string() + " --gpu-blend", "VDG_RENDER_GL=3.3"), 1,
                     "OpenGL: the GPU blend (--gpu-blend) needs OpenGL 4.3");
}

// ---- Framing: what will be drawn, not the base alone -------------------------------------------

// Rows and columns of a frame holding something other than the (white) background.
struct Covered {
  int top = -1, bottom = -1, left = -1, right = -1;
};
Covered coveredRows(const fs::path& png) {
  const vdg::TextureImage img = vdg::readImageFile(png.string());
  constexpr int kBackgroundLevel = 250;  // --background 1,1,1 gives 255; the model is shaded below this
  Covered c;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      const std::uint8_t* p = &img.rgba[4 * (static_cast<std::size_t>(y) * img.width + x)];
      if (p[0] >= kBackgroundLevel && p[1] >= kBackgroundLevel && p[2] >= kBackgroundLevel) continue;
      if (c.top < 0) c.top = y;
      c.bottom = y;
      c.left = c.left < 0 ? x : std::min(c.left, x);
      c.right = std::max(c.right, x);
    }
  return c;
}

// A unit sphere whose front key (seen from +Z) raises its top half by 80%: fitted to the base, the
// camera cut the key's top off at every size; fitted to the extent, the whole key is in the frame.
fs::path tallKeyModel(const fs::path& dir) {
  fs::create_directories(dir);
  const vdg::TriMesh base = vdg::testing::uvSphere(12, 16);
  vdg::TriMesh key = base;
  for (std::size_t v = 0; v < key.vertexCount(); ++v)
    if (key.positions[3 * v + 1] > 0.0f) key.positions[3 * v + 1] *= 1.8f;
  vdg::writeObj((dir / "ball.obj").string(), base);
  vdg::writeObj((dir / "tall.obj").string(), key);
  std::ofstream(dir / "tall.vdg.json") << R"({"version": 1, "base": "ball.obj",
    "keys": [{"name": "tall", "mesh": "tall.obj", "view": [0, 0, 1]}]})";
  return dir / "tall.vdg.json";
}

TEST(CliRenderFraming, AKeyThatRaisesTheTopStaysInTheFrameAtEverySize) {
  const fs::path model = tallKeyModel(freshDir("vdg_render_tall"));
  for (const std::string size : {"64x64", "128x64", "64x128", "160x120"}) {
    SCOPED_TRACE(size);
    const fs::path out = freshDir("vdg_render_tall_" + size);
    // --orbit 4: frame 0 is the front (the key fully on), frame 2 the back (the base).
    const Result r = vdg("render " + model.string() + " -o " + out.string() + " --orbit 4 --size " + size +
                         " --background 1,1,1 --quiet");
    ASSERT_EQ(r.status, 0) << r.output;
    const int w = std::stoi(size.substr(0, size.find('x'))), h = std::stoi(size.substr(size.find('x') + 1));
    for (int f = 0; f < 4; ++f) {
      char name[32];
      std::snprintf(name, sizeof name, "frame_%04d.png", f);
      const Covered c = coveredRows(out / name);
      ASSERT_GE(c.top, 0) << name << ": nothing drawn";
      // Nothing touches an edge of the frame: the fit leaves a margin (10% of the radius) all round.
      EXPECT_GT(c.top, 0) << name;
      EXPECT_LT(c.bottom, h - 1) << name;
      EXPECT_GT(c.left, 0) << name;
      EXPECT_LT(c.right, w - 1) << name;
    }
  }
}

// ---- --camera FILE: a fixed camera or a camera path ---------------------------------------------

constexpr const char* kCirclePath = R"({"camera_path": {
  "position": {"curve": "catmull-rom", "points": [[0, 1, 4], [4, 1, 0], [0, 1, -4], [-4, 1, 0], [0, 1, 4]]},
  "start_time": 0, "end_time": 2, "view": "center", "center": [0, 0, 0], "fov_deg": 35}})";

TEST(CliRenderCamera, AFixedCameraRendersCountIdenticalFrames) {
  const fs::path dir = freshDir("vdg_render_fixed");
  fs::create_directories(dir);
  std::ofstream(dir / "cam.json") << R"({"version": 1, "eye": [2, 1, 4], "target": [0, 0, 0], "fov_deg": 35})";
  std::ofstream(dir / "other.json") << R"({"eye": [-3, 1, 3], "target": [0, 0, 0], "fov_deg": 35})";
  Result r = vdg("render " + kSpot + " -o " + (dir / "a").string() + " --camera " + (dir / "cam.json").string() +
                 " --count 3 --size 64x64 --quiet");
  ASSERT_EQ(r.status, 0) << r.output;
  r = vdg("render " + kSpot + " -o " + (dir / "b").string() + " --camera " + (dir / "other.json").string() +
          " --size 64x64 --quiet");
  ASSERT_EQ(r.status, 0) << r.output;
  const std::string first = readBytes(dir / "a" / "frame_0000.png");
  ASSERT_FALSE(first.empty());
  EXPECT_EQ(first, readBytes(dir / "a" / "frame_0001.png"));
  EXPECT_EQ(first, readBytes(dir / "a" / "frame_0002.png"));
  EXPECT_FALSE(fs::exists(dir / "a" / "frame_0003.png"));
  EXPECT_TRUE(fs::exists(dir / "b" / "frame_0000.png"));  // the default --count is 1
  EXPECT_FALSE(fs::exists(dir / "b" / "frame_0001.png"));
  EXPECT_NE(first, readBytes(dir / "b" / "frame_0000.png"));
}

TEST(CliRenderCamera, ACameraPathMovesTheCameraAndRangesAreByteIdentical) {
  const fs::path dir = freshDir("vdg_render_path");
  fs::create_directories(dir);
  std::ofstream(dir / "path.json") << kCirclePath;
  const std::string common = " --camera " + (dir / "path.json").string() + " --count 5 --size 64x64 --quiet";
  Result r = vdg("render " + kSpot + " -o " + (dir / "all").string() + common);
  ASSERT_EQ(r.status, 0) << r.output;
  r = vdg("render " + kSpot + " -o " + (dir / "part").string() + common + " --frames 2-3");
  ASSERT_EQ(r.status, 0) << r.output;
  std::vector<std::string> frames;
  for (int f = 0; f < 5; ++f) {
    char name[32];
    std::snprintf(name, sizeof name, "frame_%04d.png", f);
    frames.push_back(readBytes(dir / "all" / name));
    ASSERT_FALSE(frames.back().empty()) << name;
    EXPECT_EQ(fs::exists(dir / "part" / name), f == 2 || f == 3) << name;
  }
  EXPECT_FALSE(fs::exists(dir / "all" / "frame_0005.png"));
  EXPECT_EQ(frames[2], readBytes(dir / "part" / "frame_0002.png"));
  EXPECT_EQ(frames[3], readBytes(dir / "part" / "frame_0003.png"));
  // Frames 0-2 look from the front, the side and the back (times 0, 0.5 and 1 of the loop's 2).
  EXPECT_NE(frames[0], frames[1]);
  EXPECT_NE(frames[1], frames[2]);
  EXPECT_NE(frames[0], frames[2]);
}

TEST(CliRenderCamera, CameraExcludesTheOrbitAndCountNeedsCamera) {
  const fs::path dir = freshDir("vdg_render_camera_usage");
  fs::create_directories(dir);
  std::ofstream(dir / "path.json") << kCirclePath;
  const std::string camera = " --camera " + (dir / "path.json").string();
  const std::string out = " -o " + (dir / "out").string();
  expectOneLineError(vdg("render " + kSpot + out + camera + " --orbit 4"), 2, "--camera and --orbit exclude");
  expectOneLineError(vdg("render " + kSpot + out + camera + " --azimuth 30"), 2, "--camera and --azimuth exclude");
  expectOneLineError(vdg("render " + kSpot + out + " --count 4"), 2, "--count: needs --camera");
  expectOneLineError(vdg("render " + kSpot + out + camera + " --count 4 --frames 2-4"), 2,
                     "--frames: expected frames within 0-3 (--count 4)");
  expectOneLineError(vdg("render " + kSpot + out + camera + " --count 0"), 2, "--count");
  EXPECT_FALSE(fs::exists(dir / "out"));
}

}  // namespace

#endif  // VDG_CLI
