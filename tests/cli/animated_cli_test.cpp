// `vdg info` and `vdg weights` on animated models (manifest "base_animation", Rademacher 99,
// section 4) as a user runs them, and the commands that work on static models only refusing an
// animated one with one clear line.
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "cli/run_vdg.h"
#include "support/test_meshes.h"

namespace {

using vdg::testing::readText;

using vdg::testing::Result;
Result run(const std::string& args) { return vdg::testing::runVdg(args); }

const std::string kWalker = "examples/walk/walker.vdg.json";
const std::string kWalkerWorld = "examples/walk/walker-world.vdg.json";
const std::string kSequence = "tests/io/formats/tetra_walk_v2.vdg.json";
constexpr double kSumTol = 1e-6;

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// The "v" lines of an OBJ file.
std::vector<std::array<double, 3>> objVertices(const std::string& path) {
  std::istringstream in(readText(path));
  std::vector<std::array<double, 3>> v;
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("v ", 0) != 0) continue;
    std::istringstream fields(line.substr(2));
    std::array<double, 3> p{};
    fields >> p[0] >> p[1] >> p[2];
    v.push_back(p);
  }
  return v;
}

// Vertices where a key file differs from the base file of its frame (the generator leaves the
// vertices a key does not exaggerate exactly as the base has them).
std::size_t differing(const std::string& key, const std::string& base) {
  const auto k = objVertices(std::string(VDG_SOURCE_DIR) + "/examples/walk/" + key);
  const auto b = objVertices(std::string(VDG_SOURCE_DIR) + "/examples/walk/" + base);
  EXPECT_EQ(k.size(), b.size());
  std::size_t n = 0;
  for (std::size_t i = 0; i < std::min(k.size(), b.size()); ++i) n += k[i] != b[i];
  return n;
}

TEST(AnimatedCli, InfoDescribesTheBaseAnimationAndKeyViews) {
  Result r = run("info " + kWalker);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(contains(r.out, "base       glTF walker.glb, animation 0: 3920 vertices, 7808 triangles, skinned\n"))
      << r.out;
  EXPECT_TRUE(contains(r.out, "animation  40 frames at 24 fps, loop")) << r.out;
  EXPECT_TRUE(contains(r.out, "offsets    skinned\n")) << r.out;
  EXPECT_TRUE(contains(r.out, "views      2 (4 keys)\n")) << r.out;
  EXPECT_TRUE(contains(r.out, "  view ( 0.0000,  0.0000,  1.0000)\n    front_f10        frame 10 ")) << r.out;
  EXPECT_TRUE(contains(r.out, "(keys/side_f30.obj)\n")) << r.out;

  r = run("info " + kWalkerWorld + " --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["base_animation"]["gltf"], "walker.glb");
  EXPECT_EQ(j["base_animation"]["animation"], 0);
  EXPECT_EQ(j["base_animation"]["fps"], 24.0);
  EXPECT_EQ(j["base_animation"]["frames"], 40);
  EXPECT_EQ(j["base_animation"]["loop"], true);
  EXPECT_EQ(j["offsets"], "world");
  EXPECT_EQ(j["vertices"], 3920);
  ASSERT_EQ(j["views"].size(), 2u);
  const std::pair<std::array<double, 3>, std::string> views[] = {{{0, 0, 1}, "front"}, {{1, 0, 0}, "side"}};
  for (std::size_t i = 0; i < 2; ++i) {
    const auto& view = j["views"][i];
    EXPECT_EQ((view["view"].get<std::array<double, 3>>()), views[i].first);
    ASSERT_EQ(view["keys"].size(), 2u);
    for (std::size_t k = 0; k < 2; ++k) {
      const int frame = k == 0 ? 10 : 30;
      const std::string name = views[i].second + "_f" + std::to_string(frame);
      EXPECT_EQ(view["keys"][k]["name"], name);
      EXPECT_EQ(view["keys"][k]["frame"], frame);
      EXPECT_EQ(view["keys"][k]["mesh"], "keys/" + name + ".obj");
      // The key moves what it exaggerates, not the rounding between two skinnings of one pose.
      EXPECT_EQ(view["keys"][k]["moved_vertices"].get<std::size_t>(),
                differing("keys/" + name + ".obj", "base_f" + std::to_string(frame) + ".obj"))
          << name;
    }
  }
}

TEST(AnimatedCli, InfoOnAnObjSequence) {
  Result r = run("info " + kSequence);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(contains(r.out, "base       OBJ sequence tetra_walk_%d.obj, files 0..2: ")) << r.out;
  EXPECT_TRUE(contains(r.out, "animation  3 frames, loop")) << r.out;
  EXPECT_TRUE(contains(r.out, "    up               frame 1 ")) << r.out;
  r = run("info " + kSequence + " --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["base_animation"]["obj_sequence"], "tetra_walk_%d.obj");
  EXPECT_EQ(j["base_animation"]["files"], nlohmann::json::array({0, 2}));
  EXPECT_EQ(j["base_animation"]["frames"], 3);
  EXPECT_FALSE(j["base_animation"].contains("fps")) << "an OBJ sequence has no frame rate";
  EXPECT_EQ(j["views"][0]["keys"][0]["frame"], 1);
}

TEST(AnimatedCli, WeightsArePerKeyView) {
  // At the front view: the front view alone, with both of its key frames.
  Result r = run("weights " + kWalker + " --view 0,0,1 --json");
  ASSERT_EQ(r.code, 0) << r.err;
  auto j = nlohmann::json::parse(r.out);
  ASSERT_EQ(j["views"].size(), 1u) << r.out;
  EXPECT_EQ(j["views"][0]["keys"], nlohmann::json::array({"front_f10", "front_f30"}));
  EXPECT_EQ(j["views"][0]["frames"], nlohmann::json::array({10, 30}));
  EXPECT_NEAR(j["views"][0]["weight"].get<double>(), 1.0, kSumTol);
  EXPECT_NEAR(j["base"].get<double>(), 0.0, kSumTol);

  // Between front and side: both views and the base share the weight.
  r = run("weights " + kWalker + " --view 0.6,0.2,0.8 --json");
  ASSERT_EQ(r.code, 0) << r.err;
  j = nlohmann::json::parse(r.out);
  ASSERT_EQ(j["views"].size(), 2u) << r.out;
  double sum = j["base"].get<double>();
  for (const auto& v : j["views"]) {
    EXPECT_GT(v["weight"].get<double>(), 0.0);
    sum += v["weight"].get<double>();
  }
  EXPECT_NEAR(sum, 1.0, kSumTol);
  // The world-offset manifest has the same key views, so the same weights.
  const Result world = run("weights " + kWalkerWorld + " --view 0.6,0.2,0.8 --json");
  ASSERT_EQ(world.code, 0) << world.err;
  EXPECT_EQ(world.out, r.out);

  // --eye is measured from the model's centre (0, 0.9, 0): straight in front of it is the front view.
  r = run("weights " + kWalker + " --eye 0,0.9,5 --json");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NEAR(nlohmann::json::parse(r.out)["views"][0]["weight"].get<double>(), 1.0, kSumTol);

  r = run("weights " + kWalker + " --view 1,0,0");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(contains(r.out, "side_f10 (frame 10), side_f30 (frame 30)")) << r.out;
  EXPECT_EQ(run("weights " + kWalker).code, 2) << "neither --view nor --eye";
}

// Commands that work on static models say so in one line (exit 1) instead of working on frame 0
// or complaining about a field. (vdg deform is checked in a scratch folder by the hostile corpus,
// tests/hostile/cases/animated.jsonl, since it locks and journals the model's folder.)
TEST(AnimatedCli, StaticOnlyCommandsRefuseAnimatedModels) {
  vdg::testing::TempDir dir;
  Result r =
      run("align " + kWalker + " --size 100x100 --points tests/hostile/inputs/pairs.json -o " + dir.file("cam.json"));
  EXPECT_EQ(r.code, 1);
  EXPECT_EQ(r.err, "vdg: error: " + kWalker +
                       ": vdg align works on static models, and this one has an animated base ('base_animation'); "
                       "align against the base posed at the key's frame as a mesh (vdg align FRAME.obj ... -o "
                       "CAMERA.json)\n");
  r = run("sample " + kWalker + " --samples 3");
  EXPECT_EQ(r.code, 1);
  EXPECT_EQ(r.err, "vdg: error: " + kWalker +
                       ": a model manifest, not an animation spec; vdg sample samples eases, curves, tracks and camera "
                       "paths (docs/anim.md); a model is evaluated by vdg eval (--frame F for an animated one) or vdg "
                       "render\n");
  EXPECT_FALSE(std::filesystem::exists(dir.file("cam.json")));
}

}  // namespace
