// One spelling per meaning across subcommands: --frames A-B a range, --count N a number of frames,
// --size WxH, -q; the old spellings kept for one version print one deprecation line and do what the
// new ones do. Also `vdg bake --camera FILE` (a camera path baked as vdg weights sees it) and
// `vdg info` on a model without keys.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "cli/run_vdg.h"
#include "io/gltf_test_decoder.h"
#include "support/test_meshes.h"

namespace {

namespace fs = std::filesystem;
using vdg::testing::readText;
using vdg::testing::Result;
using vdg::testing::runVdg;

// The baked eye goes through float storage and text; weights move little with the view.
constexpr double kBakedWeightTol = 1e-4;

const std::string kFaces =
    "examples/morph2d/face_a.png examples/morph2d/face_b.png --lines examples/morph2d/lines.json";
const std::string kFramesNote =
    "vdg: --frames N is deprecated (it will be removed in the next version): use --count N\n";

TEST(CliOptions, MorphFramesNIsTheOldSpellingOfCount) {
  vdg::testing::TempDir dir;
  Result r = runVdg("morph " + kFaces + " --count 3 -q -o " + dir.file("new"));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.err, "");
  r = runVdg("morph " + kFaces + " --frames 3 -q -o " + dir.file("old"));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.err, kFramesNote);
  for (const char* name : {"frame_0000.png", "frame_0001.png", "frame_0002.png"})
    EXPECT_EQ(readText(dir.file(std::string("old/") + name)), readText(dir.file(std::string("new/") + name))) << name;
}

TEST(CliOptions, MorphFramesABIsAShareOfTheCount) {
  vdg::testing::TempDir dir;
  ASSERT_EQ(runVdg("morph " + kFaces + " --count 5 -q -o " + dir.file("all")).code, 0);
  const Result r = runVdg("morph " + kFaces + " --count 5 --frames 1-2 -o " + dir.file("share"));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("wrote 2 frames"), std::string::npos) << r.out;
  EXPECT_FALSE(fs::exists(dir.file("share/frame_0000.png")));
  EXPECT_FALSE(fs::exists(dir.file("share/frame_0003.png")));
  for (const char* name : {"frame_0001.png", "frame_0002.png"})
    EXPECT_EQ(readText(dir.file(std::string("share/") + name)), readText(dir.file(std::string("all/") + name))) << name;
  EXPECT_EQ(runVdg("morph " + kFaces + " --count 5 --frames 3-5 -o " + dir.file("x")).code, 2);
  EXPECT_EQ(runVdg("morph " + kFaces + " --t 0.5 --frames 0-1 -o " + dir.file("x.png")).code, 2);
}

TEST(CliOptions, Morph3dFramesNIsTheOldSpellingOfCount) {
  vdg::testing::TempDir dir;
  const std::string shapes = "examples/morph3d/sphere.obj examples/morph3d/torus.obj --voxel 0.08 -q";
  Result r = runVdg("morph3d " + shapes + " --count 2 -o " + dir.file("new"));
  ASSERT_EQ(r.code, 0) << r.err;
  r = runVdg("morph3d " + shapes + " --frames 2 -o " + dir.file("old"));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.err, kFramesNote);
  for (const char* name : {"frame_0000.obj", "frame_0001.obj", "camera.json"})
    EXPECT_EQ(readText(dir.file(std::string("old/") + name)), readText(dir.file(std::string("new/") + name))) << name;
  // A range is refused: the sequence's camera frames every frame, so it is written whole.
  r = runVdg("morph3d " + shapes + " --count 4 --frames 0-1 -o " + dir.file("x"));
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("give --count N"), std::string::npos) << r.err;
}

TEST(CliOptions, AlignSizeWithACommaIsTheOldSpellingOfWxH) {
  const std::string rest = " --points tests/hostile/inputs/pairs.json -o /nonexistent/cam.json";
  const Result now = runVdg("align missing.obj --size 100x80" + rest);
  const Result old = runVdg("align missing.obj --size 100,80" + rest);
  EXPECT_EQ(now.code, 1);
  EXPECT_EQ(old.code, now.code);
  EXPECT_EQ(old.err,
            "vdg: --size W,H is deprecated (it will be removed in the next version): use --size WxH\n" + now.err);
}

TEST(CliOptions, StudioFramesNIsTheOldSpellingOfCount) {
  if (runVdg("studio --help").code != 0) GTEST_SKIP() << "this build has no vdg studio";
  // No display: the note comes first, then studio's own one line (the window cannot open).
  ::unsetenv("DISPLAY");
  ::unsetenv("WAYLAND_DISPLAY");
  const Result r = runVdg("studio examples/building/building.vdg.json --frames 2");
  EXPECT_EQ(r.code, 1);
  EXPECT_EQ(r.err.rfind(kFramesNote, 0), 0u) << r.err;
}

TEST(CliOptions, QuietEverywhere) {
  vdg::testing::TempDir dir;
  for (const std::string& args :
       {"eval examples/spot/spot.vdg.json --view 0,0,1 -o " + dir.file("e.obj"),
        "export examples/spot/spot.vdg.json -o " + dir.file("s.glb"),
        "bake examples/spot/spot.vdg.json --orbit 2 -o " + dir.file("b.glb"),
        "morph " + kFaces + " --count 2 -o " + dir.file("m"),
        "implicit examples/implicit/blobs.json --frame 0 --voxel 0.2 -o " + dir.file("i.obj")}) {
    const Result r = runVdg(args + " -q");
    EXPECT_EQ(r.code, 0) << args << ": " << r.err;
    EXPECT_EQ(r.out, "") << args;
  }
}

TEST(CliOptions, BakeAlongACameraPathIsWhatVdgWeightsSeesAtEachFrame) {
  vdg::testing::TempDir dir;
  constexpr int kCount = 12;
  const std::string spot = "examples/spot/spot.vdg.json";
  const Result r = runVdg("bake " + spot + " -o " + dir.file("swoop.glb") +
                          " --camera examples/spot/swoop.camera.json --count " + std::to_string(kCount) + " -q");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto g = vdg::testing::decodeGlb(readText(dir.file("swoop.glb")));
  const auto names = g.doc.at("meshes").at(0).at("extras").at("targetNames");
  const auto& anim = g.doc.at("animations").at(0);
  const auto times = vdg::testing::readAccessor(g, anim.at("samplers").at(0).at("input"));
  const auto weights = vdg::testing::readAccessor(g, anim.at("samplers").at(0).at("output"));
  const auto eyes = vdg::testing::readAccessor(g, anim.at("samplers").at(1).at("output"));
  ASSERT_EQ(times.size(), static_cast<std::size_t>(kCount)) << "a camera path is not closed like an orbit";
  // The path moves: its first and last eyes differ.
  EXPECT_GT(std::abs(eyes[0] - eyes[3 * (kCount - 1)]) + std::abs(eyes[2] - eyes[3 * (kCount - 1) + 2]), 1.0);
  for (int f = 0; f < kCount; ++f) {
    char eye[128];
    std::snprintf(eye, sizeof eye, "%.9g,%.9g,%.9g", eyes[3 * f], eyes[3 * f + 1], eyes[3 * f + 2]);
    const Result w = runVdg("weights " + spot + " --eye " + eye + " --json");
    ASSERT_EQ(w.code, 0) << w.err;
    const auto expected = nlohmann::json::parse(w.out).at("keys");
    for (std::size_t k = 0; k < names.size(); ++k) {
      const std::string name = names[k];
      const double want = expected.contains(name) ? expected.at(name).get<double>() : 0.0;
      EXPECT_NEAR(weights[f * names.size() + k], want, kBakedWeightTol) << "frame " << f << " key " << name;
    }
  }
  // Usage: --camera replaces the orbit, --count belongs to --camera.
  EXPECT_EQ(
      runVdg("bake " + spot + " -o " + dir.file("x.glb") + " --camera examples/spot/swoop.camera.json --orbit 4").code,
      2);
  EXPECT_EQ(runVdg("bake " + spot + " -o " + dir.file("x.glb") + " --count 4").code, 2);
  EXPECT_EQ(runVdg("bake " + spot + " -o " + dir.file("x.glb") + " --camera missing.json").code, 1);
}

TEST(CliOptions, InfoOnAModelWithoutKeysNamesTheCommandThatAddsOne) {
  const Result r = runVdg("info examples/tutorial/suzanne.vdg.json");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("keys       0\n"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("add the first key with 'vdg deform examples/tutorial/suzanne.vdg.json --key NAME"),
            std::string::npos)
      << r.out;
  const Result j = runVdg("info examples/tutorial/suzanne.vdg.json --json");
  ASSERT_EQ(j.code, 0) << j.err;
  const auto doc = nlohmann::json::parse(j.out);
  EXPECT_TRUE(doc.at("keys").empty());
  EXPECT_NE(doc.at("warnings").at(0).get<std::string>().find("vdg deform"), std::string::npos);
}

// vdg info names two key views nearly the same direction (the decision is viewdep's
// nearlySameViewPairs, tested there; this is the message a user reads).
TEST(CliOptions, InfoWarnsAboutKeyViewsNearlyTheSameDirection) {
  vdg::testing::TempDir dir;
  fs::copy_file(VDG_SOURCE_DIR "/tests/hostile/inputs/cube.obj", dir.file("cube.obj"));
  fs::copy_file(VDG_SOURCE_DIR "/tests/hostile/inputs/front.obj", dir.file("front.obj"));
  std::ofstream(dir.file("m.vdg.json")) << R"({"version": 2, "base": "cube.obj", "keys": [
      {"name": "front", "mesh": "front.obj", "view": [0, 0, 1]},
      {"name": "almost_front", "mesh": "front.obj", "view": [0.04, 0, 1]}]})";
  const Result r = runVdg("info " + dir.file("m.vdg.json"));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("warning: keys 'front' and 'almost_front' are only 2.29 degrees apart (a near-degenerate hull "
                       "triangle): the weights flip between them"),
            std::string::npos)
      << r.out;
}

}  // namespace
