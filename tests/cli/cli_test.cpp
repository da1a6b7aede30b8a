#include <gtest/gtest.h>

#include <sys/wait.h>
#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "support/test_meshes.h"

namespace {

struct Result {
  int code;
  std::string out;
  std::string err;
};

// Runs `vdg ARGS` through the shell, capturing stdout and stderr separately.
Result run(const std::string& args, const std::string& binary = VDG_BINARY) {
  vdg::testing::TempDir dir;
  const std::string out = dir.file("out"), err = dir.file("err");
  const std::string cmd = "cd '" VDG_SOURCE_DIR "' && '" + binary + "' " + args + " >'" + out + "' 2>'" + err + "'";
  const int status = std::system(cmd.c_str());
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, vdg::testing::readText(out), vdg::testing::readText(err)};
}

const std::string kSpot = "examples/spot/spot.vdg.json";
constexpr double kSumTol = 1e-6;

int lineCount(const std::string& s) { return static_cast<int>(std::count(s.begin(), s.end(), '\n')); }

TEST(Cli, HelpAndUsage) {
  EXPECT_EQ(run("--help").code, 0);
  for (const char* sub : {"info", "weights", "eval"}) {
    const Result r = run(std::string(sub) + " --help");
    EXPECT_EQ(r.code, 0) << sub;
    EXPECT_NE(r.out.find("MODEL"), std::string::npos) << sub;
  }
  EXPECT_EQ(run("").code, 2);
  EXPECT_EQ(run("frobnicate").code, 2);
  EXPECT_EQ(run("weights " + kSpot).code, 2) << "neither --view nor --eye";
  EXPECT_EQ(run("weights " + kSpot + " --view 1,2").code, 2);
  EXPECT_EQ(run("weights " + kSpot + " --view 1,2,3 --eye 1,2,3").code, 2);
  EXPECT_EQ(run("weights " + kSpot + " --view 0,0,0").code, 2);
  EXPECT_EQ(run("weights " + kSpot + " --view 1,0,0 --sharpness -1").code, 2);
}

TEST(Cli, WeightsJsonIsOneObjectSummingToOne) {
  for (const char* view : {"0,0.15,-1", "1,1,1", "0,-1,0", "0.3,0.2,-0.9", "-1,0.5,0.5"}) {
    const Result r = run("weights " + kSpot + " --view " + view + " --json");
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(lineCount(r.out), 1);
    const auto j = nlohmann::json::parse(r.out);
    double sum = j.at("base").get<double>();
    for (const auto& [name, w] : j.at("keys").items()) {
      EXPECT_GT(w.get<double>(), 0.0) << name;
      sum += w.get<double>();
    }
    EXPECT_NEAR(sum, 1.0, kSumTol) << view;
  }
  const auto at_key = nlohmann::json::parse(run("weights " + kSpot + " --view 0,0.15,-1 --json").out);
  EXPECT_NEAR(at_key["keys"]["front"].get<double>(), 1.0, kSumTol);
  EXPECT_EQ(at_key["keys"].size(), 1u);
  EXPECT_NEAR(at_key["base"].get<double>(), 0.0, kSumTol);
  // Far below the cow, no key is near: the base model alone.
  const auto below = nlohmann::json::parse(run("weights " + kSpot + " --view 0,-1,0 --json").out);
  EXPECT_NEAR(below["base"].get<double>(), 1.0, kSumTol);
}

// Batch mode: one JSON array, item n equal to the single --json call at that view (or eye).
TEST(Cli, WeightsViewsFileGivesTheSingleResultsInOrder) {
  vdg::testing::TempDir dir;
  const std::vector<std::string> views = {"0,0.15,-1", "1,1,1", "0,-1,0", "0.3,0.2,-0.9"};
  vdg::testing::writeText(dir.file("v.json"),
                          R"([[0, 0.15, -1], {"view": [1, 1, 1]}, [0, -1, 0], [0.3, 0.2, -0.9], {"eye": [5, 1, 2]}])");
  const Result r = run("weights " + kSpot + " --views " + dir.file("v.json"));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(lineCount(r.out), 1);
  const auto all = nlohmann::json::parse(r.out);
  ASSERT_EQ(all.size(), 5u);
  for (std::size_t i = 0; i < views.size(); ++i)
    EXPECT_EQ(all[i], nlohmann::json::parse(run("weights " + kSpot + " --json --view " + views[i]).out)) << i;
  EXPECT_EQ(all[4], nlohmann::json::parse(run("weights " + kSpot + " --json --eye 5,1,2").out));
  const auto animated = run("weights examples/walk/walker.vdg.json --views " + dir.file("v.json"));
  ASSERT_EQ(animated.code, 0) << animated.err;
  EXPECT_EQ(nlohmann::json::parse(animated.out).at(1),
            nlohmann::json::parse(run("weights examples/walk/walker.vdg.json --json --view 1,1,1").out));
  // A bad file: one line naming the file and the item, exit 1; with --view: a usage error.
  vdg::testing::writeText(dir.file("bad.json"), "[[0, 0, 1], [0, 0]]");
  const Result bad = run("weights " + kSpot + " --views " + dir.file("bad.json"));
  EXPECT_EQ(bad.code, 1);
  EXPECT_EQ(bad.err,
            "vdg: error: " + dir.file("bad.json") + ": --views: [1]: expected 3 numbers, got an array of 2 items\n");
  EXPECT_EQ(run("weights " + kSpot + " --views " + dir.file("missing.json")).code, 1);
  EXPECT_EQ(run("weights " + kSpot + " --views " + dir.file("v.json") + " --view 0,0,1").code, 2);
  EXPECT_NE(run("weights --help").out.find("--views"), std::string::npos);
}

// The smooth weight scheme (docs/weights.md): --scheme overrides the model's, --continuity
// measures both; the smooth example is exact at its keys; the KHR_interactivity graph refuses it.
TEST(Cli, WeightSchemesAndContinuity) {
  const std::string smooth = "examples/spot/spot-smooth.vdg.json";
  const auto at_key = nlohmann::json::parse(run("weights " + smooth + " --view 0,0.15,-1 --json").out);
  EXPECT_NEAR(at_key["keys"]["front"].get<double>(), 1.0, 1e-6) << at_key.dump();
  EXPECT_EQ(run("weights " + kSpot + " --scheme smooth --view 0.3,0.2,-0.9 --json").out,
            run("weights " + smooth + " --view 0.3,0.2,-0.9 --json").out);
  const Result linear = run("weights " + kSpot + " --continuity --step 0.5 --json");
  const Result smoothed = run("weights " + kSpot + " --continuity --step 0.5 --json --scheme smooth");
  ASSERT_EQ(linear.code, 0) << linear.err;
  ASSERT_EQ(smoothed.code, 0) << smoothed.err;
  const auto l = nlohmann::json::parse(linear.out), s = nlohmann::json::parse(smoothed.out);
  EXPECT_EQ(l["scheme"], "linear");
  EXPECT_EQ(s["scheme"], "smooth");
  EXPECT_LT(s["velocity_jump"].get<double>(), l["velocity_jump"].get<double>()) << l.dump() << "\n" << s.dump();
  EXPECT_LT(s["weight_jump"].get<double>(), l["weight_jump"].get<double>());
  EXPECT_EQ(run("weights " + kSpot + " --continuity --view 0,0,1").code, 2);
  EXPECT_EQ(run("weights " + kSpot + " --step 0.5 --view 0,0,1").code, 2) << "--step needs --continuity";
  EXPECT_EQ(run("weights " + kSpot + " --scheme cubic --view 0,0,1").code, 2);
  vdg::testing::TempDir dir;
  const Result graph = run("export " + smooth + " --interactivity -q -o " + dir.file("s.glb"));
  EXPECT_EQ(graph.code, 1);
  EXPECT_NE(graph.err.find("--interactivity: the graph weighs the keys with the linear scheme only"), std::string::npos)
      << graph.err;
  EXPECT_FALSE(std::filesystem::exists(dir.file("s.glb")));
}

// Keys at distances (docs/weights.md, "Keys at distances"): spot-dolly's front close-up and front
// wide shot share a direction; the eye decides. Exact at both eyes, linear in between (inside the
// hull), the wide key far out along the direction; --view, render and export refuse in one line.
TEST(Cli, KeysAtDistances) {
  const std::string dolly = "examples/spot/spot-dolly.vdg.json";
  const auto model = nlohmann::json::parse(vdg::testing::readText(std::string(VDG_SOURCE_DIR "/") + dolly));
  const auto eye = [&](const std::string& key) {
    for (const auto& k : model["keys"])
      if (k["name"] == key) return Eigen::Vector3d(k["eye"][0], k["eye"][1], k["eye"][2]);
    ADD_FAILURE() << key;
    return Eigen::Vector3d::Zero().eval();
  };
  const auto arg = [](const Eigen::Vector3d& e) {
    char buffer[96];
    std::snprintf(buffer, sizeof(buffer), "%.17g,%.17g,%.17g", e.x(), e.y(), e.z());
    return std::string(buffer);
  };
  const Eigen::Vector3d wide = eye("front"), close = eye("front-close");
  for (const auto& [name, at] : {std::pair{"front", wide}, std::pair{"front-close", close}}) {
    const Result r = run("weights " + dolly + " --eye " + arg(at) + " --json");
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_NEAR(nlohmann::json::parse(r.out)["keys"][name].get<double>(), 1.0, 1e-6) << r.out;
  }
  const Result mid = run("weights " + dolly + " --eye " + arg(0.5 * (wide + close)) + " --json");
  ASSERT_EQ(mid.code, 0) << mid.err;
  const auto m = nlohmann::json::parse(mid.out);
  EXPECT_NEAR(m["keys"]["front"].get<double>(), 0.5, 1e-5) << mid.out;
  EXPECT_NEAR(m["keys"]["front-close"].get<double>(), 0.5, 1e-5) << mid.out;
  const Eigen::Vector3d c(model["center"][0], model["center"][1], model["center"][2]);
  const auto far =
      nlohmann::json::parse(run("weights " + dolly + " --eye " + arg(c + 50.0 * (wide - c)) + " --json").out);
  EXPECT_NEAR(far["keys"]["front"].get<double>(), 1.0, 1e-5) << far.dump();
  EXPECT_FALSE(far["keys"].contains("front-close")) << far.dump();
  // --views with eyes gives the same weights as --eye, one item each.
  vdg::testing::TempDir dir;
  vdg::testing::writeText(dir.file("eyes.json"),
                          "[{\"eye\": [" + arg(close) + "]}, {\"eye\": [" + arg(0.5 * (wide + close)) + "]}]");
  const auto batch = nlohmann::json::parse(run("weights " + dolly + " --views " + dir.file("eyes.json")).out);
  ASSERT_EQ(batch.size(), 2u);
  EXPECT_EQ(batch[1], m);
  vdg::testing::writeText(dir.file("views.json"), "[[0, 0, -1]]");
  const Result direction_list = run("weights " + dolly + " --views " + dir.file("views.json"));
  EXPECT_EQ(direction_list.code, 1);
  EXPECT_NE(direction_list.err.find("expected {\"eye\": [x, y, z]}, not a direction"), std::string::npos)
      << direction_list.err;
  const Result eval = run("eval " + dolly + " --eye " + arg(close) + " -q -o " + dir.file("close.obj"));
  ASSERT_EQ(eval.code, 0) << eval.err;
  EXPECT_NE(vdg::testing::readText(dir.file("close.obj")).find("weights: front-close=1.000000 base=0.000000"),
            std::string::npos);
  const Result info = run("info " + dolly);
  EXPECT_NE(info.out.find("space      positions: "), std::string::npos) << info.out;
  EXPECT_NE(run("info " + kSpot).out.find("space      directions"), std::string::npos);
  const Result view = run("weights " + dolly + " --view 0,0,-1");
  EXPECT_EQ(view.code, 2);
  EXPECT_NE(view.err.find("--eye X,Y,Z: the model weighs eye positions"), std::string::npos) << view.err;
  for (const std::string& refused :
       {"render " + dolly + " -o " + dir.file("d.png"), "export " + dolly + " -q -o " + dir.file("d.glb")}) {
    const Result r = run(refused);
    EXPECT_EQ(r.code, 1) << refused;
    EXPECT_NE(r.err.find("the 'positions' weight space is not supported by "), std::string::npos) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << "one line: " << r.err;
  }
}

// The rbf weight scheme (docs/weights.md): every key weighs, exact at the keys, the example's
// settings equal --scheme rbf's defaults, --continuity measures it as C1, its settings need it,
// the glTF export carries it (extras v4), and the GPU blend (three keys per view) refuses it in one line.
TEST(Cli, RbfWeightScheme) {
  const std::string rbf = "examples/spot/spot-rbf.vdg.json";
  const auto at_key = nlohmann::json::parse(run("weights " + rbf + " --view 0,0.15,-1 --json").out);
  EXPECT_NEAR(at_key["keys"]["front"].get<double>(), 1.0, 1e-6) << at_key.dump();
  const Result between = run("weights " + kSpot + " --scheme rbf --view 0,0.5,-0.8 --json");
  ASSERT_EQ(between.code, 0) << between.err;
  EXPECT_EQ(between.out, run("weights " + rbf + " --view 0,0.5,-0.8 --json").out);
  const auto w = nlohmann::json::parse(between.out);
  double sum = w["base"].get<double>();
  for (const auto& [name, value] : w["keys"].items()) sum += value.get<double>();
  EXPECT_NEAR(sum, 1.0, 1e-5) << between.out;
  EXPECT_GT(w["keys"].size(), 3u) << "the rbf scheme weighs more than a triangle's keys: " << between.out;
  EXPECT_NE(run("weights " + kSpot + " --scheme rbf --kernel wendland --width 50 --view 0,0.5,-0.8 --json").out,
            between.out);
  const Result linear = run("weights " + kSpot + " --continuity --step 0.5 --json");
  const Result measured = run("weights " + kSpot + " --continuity --step 0.5 --json --scheme rbf");
  ASSERT_EQ(measured.code, 0) << measured.err;
  const auto l = nlohmann::json::parse(linear.out), r = nlohmann::json::parse(measured.out);
  EXPECT_EQ(r["scheme"], "rbf");
  EXPECT_EQ(r["kernel"], "gaussian");
  EXPECT_EQ(r["width"], 60.0);
  EXPECT_LT(r["velocity_jump"].get<double>(), l["velocity_jump"].get<double>()) << l.dump() << "\n" << r.dump();
  EXPECT_LT(r["weight_jump"].get<double>(), l["weight_jump"].get<double>());
  const Result needs = run("weights " + kSpot + " --width 30 --view 0,0,1");
  EXPECT_EQ(needs.code, 2);
  EXPECT_NE(needs.err.find("--kernel, --width: settings of the rbf scheme"), std::string::npos) << needs.err;
  EXPECT_EQ(run("weights " + kSpot + " --scheme rbf --width 0 --view 0,0,1").code, 2);
  vdg::testing::TempDir dir;
  const Result obj = run("eval " + rbf + " --view 0.3,0.2,-0.9 -q -o " + dir.file("e.obj"));
  EXPECT_EQ(obj.code, 0) << obj.err;
  // The glTF export carries the solved interpolation (extras v4): the file weighs as the manifest.
  const Result glb = run("export " + rbf + " -q -o " + dir.file("r.glb"));
  EXPECT_EQ(glb.code, 0) << glb.err;
  EXPECT_EQ(run("weights " + dir.file("r.glb") + " --view 0,0.5,-0.8 --json").out,
            run("weights " + rbf + " --view 0,0.5,-0.8 --json").out);
  // vdg render blends every key on the CPU; the GPU blend (three keys an instance) refuses it.
  const Result image = run("render " + rbf + " --size 64x64 --orbit 4 --quiet -o " + dir.file("frames"));
  EXPECT_EQ(image.code, 0) << image.err;
  EXPECT_TRUE(std::filesystem::exists(dir.file("frames/frame_0003.png")));
  const Result gpu = run("render " + rbf + " --size 64x64 --orbit 4 --gpu-blend --quiet -o " + dir.file("gpu"));
  EXPECT_EQ(gpu.code, 1);
  EXPECT_NE(gpu.err.find("the 'rbf' weight scheme is not supported by the GPU blend"), std::string::npos) << gpu.err;
  EXPECT_EQ(std::count(gpu.err.begin(), gpu.err.end(), '\n'), 1) << gpu.err;
}

// Per-part key sets (docs/weights.md): the cubist Spot's head follows its fixed front view, the rest
// the camera; --part-view overrides a part's view; info lists the parts; what weighs one key set
// for the whole mesh refuses the model in one line; the evaluated mesh renders as a plain mesh.
TEST(Cli, PerPartKeySets) {
  const std::string cubist = "examples/spot/spot-cubist.vdg.json";
  const Result side = run("weights " + cubist + " --view 1,0.1,0 --json");
  ASSERT_EQ(side.code, 0) << side.err;
  const auto w = nlohmann::json::parse(side.out);
  ASSERT_EQ(w["parts"].size(), 2u) << side.out;
  EXPECT_EQ(w["parts"][0]["name"], "head");
  EXPECT_NEAR(w["parts"][0]["keys"]["head-front"].get<double>(), 1.0, kSumTol) << side.out;
  EXPECT_NEAR(w["parts"][1]["keys"]["body-right"].get<double>(), 1.0, kSumTol) << side.out;
  const auto over =
      nlohmann::json::parse(run("weights " + cubist + " --view 1,0.1,0 --part-view head=1,0.1,0 --json").out);
  EXPECT_NEAR(over["parts"][0]["keys"]["head-right"].get<double>(), 1.0, kSumTol) << over.dump();
  const Result unknown = run("weights " + cubist + " --view 1,0,0 --part-view nose=1,0,0");
  EXPECT_EQ(unknown.code, 2);
  EXPECT_NE(unknown.err.find("the model has no part 'nose' (its parts: head, rest)"), std::string::npos) << unknown.err;
  EXPECT_EQ(run("weights " + kSpot + " --view 1,0,0 --part-view head=1,0,0").code, 2);
  const auto info = nlohmann::json::parse(run("info " + cubist + " --json").out);
  ASSERT_EQ(info["parts"].size(), 2u);
  EXPECT_EQ(info["parts"][0]["keys"].size(), 5u);
  EXPECT_EQ(info["parts"][1]["view"], "main");
  vdg::testing::TempDir dir;
  const Result eval = run("eval " + cubist + " --view 1,0.1,0 -q -o " + dir.file("side.obj"));
  ASSERT_EQ(eval.code, 0) << eval.err;
  EXPECT_NE(vdg::testing::readText(dir.file("side.obj")).find("# part head view"), std::string::npos);
  const Result frame =
      run("render " + dir.file("side.obj") + " --azimuth 90 --elevation 6 --size 96x96 -o " + dir.file("frames"));
  EXPECT_EQ(frame.code, 0) << frame.err;
  EXPECT_TRUE(std::filesystem::exists(dir.file("frames/frame_0000.png")));
  for (const std::string& args :
       {"render " + cubist + " -o " + dir.file("r"), "export " + cubist + " -q -o " + dir.file("c.glb"),
        "weights " + cubist + " --continuity --step 2"}) {
    const Result refused = run(args);
    EXPECT_EQ(refused.code, 1) << args;
    EXPECT_NE(refused.err.find("model parts ('parts') are not supported by"), std::string::npos) << refused.err;
    EXPECT_EQ(std::count(refused.err.begin(), refused.err.end(), '\n'), 1) << refused.err;
  }
  EXPECT_FALSE(std::filesystem::exists(dir.file("c.glb")));
}

TEST(Cli, EyeIsMeasuredFromTheModelCentre) {
  const auto info = nlohmann::json::parse(run("info " + kSpot + " --json").out);
  const auto c = info["center"];
  // The eye straight in front of the centre, along the front key's view, gives that key alone.
  const double x = c[0].get<double>(), y = c[1].get<double>() + 0.15 * 4, z = c[2].get<double>() - 4;
  const Result r = run("weights " + kSpot + " --json --eye " + std::to_string(x) + "," + std::to_string(y) + "," +
                       std::to_string(z));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NEAR(nlohmann::json::parse(r.out)["keys"]["front"].get<double>(), 1.0, 1e-5);
}

TEST(Cli, InfoDescribesTheModel) {
  const Result text = run("info " + kSpot);
  ASSERT_EQ(text.code, 0) << text.err;
  EXPECT_NE(text.out.find("2930 vertices"), std::string::npos);
  const auto j = nlohmann::json::parse(run("info " + kSpot + " --json").out);
  EXPECT_EQ(j["vertices"], 2930);
  EXPECT_EQ(j["triangles"], 5856);
  EXPECT_EQ(j["keys"].size(), 5u);
  EXPECT_GT(j["hull_triangles"].get<int>(), 0);
  EXPECT_GT(j["covered_fraction"].get<double>(), 0.0);
  EXPECT_LE(j["covered_fraction"].get<double>(), 1.0);
}

TEST(Cli, InfoDescribesGltfFiles) {
  const Result glb = run("info tests/data/gltf/RiggedSimple/RiggedSimple.glb");
  ASSERT_EQ(glb.code, 0) << glb.err;
  EXPECT_NE(glb.out.find("[0] 'Cylinder': 1 triangle primitive, 96 vertices, 188 triangles, 0 morph targets"),
            std::string::npos)
      << glb.out;
  EXPECT_NE(glb.out.find("[0] 'Armature': 2 joints"), std::string::npos) << glb.out;
  EXPECT_NE(glb.out.find("6 channels, 2.083 s"), std::string::npos) << glb.out;
  EXPECT_NE(glb.out.find("node 3 '' scale LINEAR, 3 keyframes"), std::string::npos) << glb.out;
  const Result morph = run("info tests/data/gltf/AnimatedMorphCube/AnimatedMorphCube.gltf");
  ASSERT_EQ(morph.code, 0) << morph.err;
  EXPECT_NE(morph.out.find("24 vertices, 12 triangles, 2 morph targets"), std::string::npos) << morph.out;
  EXPECT_NE(morph.out.find("weights LINEAR, 127 keyframes, 0 - 4.2 s"), std::string::npos) << morph.out;
  const Result missing = run("info tests/data/gltf/none.glb");
  EXPECT_EQ(missing.code, 1);
  EXPECT_EQ(lineCount(missing.err), 1);
}

TEST(Cli, EvalWritesTheBlendedMeshWithTheBaseTopology) {
  vdg::testing::TempDir dir;
  const std::string out = dir.file("front.obj");
  const Result r = run("eval " + kSpot + " --view 0,0.15,-1 -o " + out);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(vdg::testing::readText(out).substr(vdg::testing::readText(out).find("\nv ")),
            vdg::testing::readText(VDG_SOURCE_DIR "/examples/spot/keys/front.obj")
                .substr(vdg::testing::readText(VDG_SOURCE_DIR "/examples/spot/keys/front.obj").find("\nv ")))
      << "at a key's view, eval writes that key's mesh";
}

// An animated model (manifest version 2): --frame picks the frame; at the key's frame and view
// eval writes the key mesh, at another frame the offset rides on the moving base.
TEST(Cli, EvalAnimatedModelsTakeAFrame) {
  vdg::testing::TempDir dir;
  const std::string model = "tests/io/formats/tetra_walk_v2.vdg.json", out = dir.file("o.obj");
  Result r = run("eval " + model + " --view 0,1,0 --frame 1 -o " + out);
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string key = vdg::testing::readText(VDG_SOURCE_DIR "/tests/io/formats/tetra_walk_up1.obj");
  std::string text = vdg::testing::readText(out);
  EXPECT_EQ(text.substr(text.find("\nv ")), key.substr(key.find("\nv "))) << text;
  r = run("eval " + model + " --view 0,1,0 --frame 2 -o " + out);
  ASSERT_EQ(r.code, 0) << r.err;
  text = vdg::testing::readText(out);
  EXPECT_NE(text.find("\nv 2 1.5 0\n"), std::string::npos) << text;

  const std::string keep = dir.file("keep.obj");
  vdg::testing::writeText(keep, "keep");
  const std::pair<std::string, std::string> usage[] = {
      {"eval " + model + " --view 0,1,0 -o " + keep,
       "vdg: eval: --frame: 'tests/io/formats/tetra_walk_v2.vdg.json' is animated (3 frames); give --frame F with F "
       "in 0..2 (see vdg eval --help)\n"},
      {"eval " + model + " --view 0,1,0 --frame 3 -o " + keep,
       "vdg: eval: --frame: expected a frame in 0..2 (the model has 3 frames), got 3 (see vdg eval --help)\n"},
      {"eval tests/io/formats/tetra_v1.vdg.json --view 0,1,0 --frame 0 -o " + keep,
       "vdg: eval: --frame: 'tests/io/formats/tetra_v1.vdg.json' is not animated (no 'base_animation'); --frame "
       "applies to animated models only (see vdg eval --help)\n"},
  };
  for (const auto& [args, message] : usage) {
    r = run(args);
    EXPECT_EQ(r.code, 2) << args;
    EXPECT_EQ(r.err, message) << args;
  }
  r = run("eval " + model + " --view 0,1,0 --frame -1 -o " + keep);
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(lineCount(r.err), 1) << r.err;
  EXPECT_EQ(vdg::testing::readText(keep), "keep");
}

// Runs a shell command line from the source folder; returns its exit status (-1 for a signal).
int shell(const std::string& line) {
  const int status = std::system(("cd '" VDG_SOURCE_DIR "' && " + line).c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

TEST(Cli, StdoutThatGoesAwayOrFillsUp) {
  vdg::testing::TempDir dir;
  const std::string vdg = "'" VDG_BINARY "'", err = dir.file("err");
  // A reader that stops early (head -1) ends the run quietly with status 0, not by SIGPIPE.
  EXPECT_EQ(shell("( " + vdg + " sample tests/hostile/inputs/ease.json --samples 200000 2>'" + err + "'; echo $? >'" +
                  dir.file("status") + "' ) | head -1 >/dev/null"),
            0);
  EXPECT_EQ(vdg::testing::readText(dir.file("status")), "0\n");
  EXPECT_EQ(vdg::testing::readText(err), "");
  // A full disk under a redirection is one line and status 1.
  EXPECT_EQ(shell(vdg + " info " + kSpot + " >/dev/full 2>'" + err + "'"), 1);
  EXPECT_EQ(vdg::testing::readText(err), "vdg: error: standard output: cannot write: No space left on device\n");
}

TEST(Cli, AFailedRunLeavesNoNewFolder) {
  vdg::testing::TempDir dir;
  // A sequence into a new folder that fails at its first frame (ulimit -f) removes the folder.
  EXPECT_EQ(
      shell("ulimit -f 1 && '" VDG_BINARY "' implicit examples/implicit/blobs.json --frames 0-1 --voxel 0.1 -q -o '" +
            dir.file("new/seq") + "' 2>'" + dir.file("err") + "'"),
      1);
  EXPECT_NE(vdg::testing::readText(dir.file("err")).find("File too large"), std::string::npos);
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "new"));
}

TEST(Cli, BadInputIsOneLineAndExitOneAndLeavesFilesAlone) {
  vdg::testing::TempDir dir;
  const std::string keep = dir.file("keep.obj");
  vdg::testing::writeText(keep, "precious");
  Result r = run("eval " + dir.file("missing.vdg.json") + " --view 0,0,1 -o " + keep);
  EXPECT_EQ(r.code, 1);
  EXPECT_EQ(lineCount(r.err), 1) << r.err;
  EXPECT_NE(r.err.find("missing.vdg.json"), std::string::npos) << r.err;
  EXPECT_EQ(vdg::testing::readText(keep), "precious");

  vdg::testing::writeText(dir.file("bad.vdg.json"), "{\"version\": 1, \"base\": \"nowhere.obj\", \"keys\": []}");
  r = run("info " + dir.file("bad.vdg.json"));
  EXPECT_EQ(r.code, 1);
  EXPECT_EQ(lineCount(r.err), 1) << r.err;
  EXPECT_NE(r.err.find("nowhere.obj"), std::string::npos) << r.err;

  r = run("eval " + kSpot + " --view 0,0,1 -o " + dir.file("no/such/dir/out.obj"));
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("out.obj"), std::string::npos) << r.err;
}

TEST(Examples, SpotExampleIsReproducible) {
  vdg::testing::TempDir dir;
  const Result r = run("examples/spot/spot.obj '" + dir.path().string() + "'", VDG_MAKE_SPOT_EXAMPLE);
  ASSERT_EQ(r.code, 0) << r.err;
  for (const char* file : {"spot.vdg.json", "keys/front.obj", "keys/left.obj", "keys/right.obj", "keys/back.obj",
                           "keys/top.obj", "spot-dolly.vdg.json", "keys/front-close.obj"}) {
    EXPECT_EQ(vdg::testing::readText(dir.file(file)),
              vdg::testing::readText(std::string(VDG_SOURCE_DIR "/examples/spot/") + file))
        << file << " differs from what make_spot_example writes";
  }
}

TEST(Examples, BuildingExampleIsReproducible) {
  vdg::testing::TempDir dir;
  const Result r = run("'" + dir.path().string() + "'", VDG_MAKE_BUILDING);
  ASSERT_EQ(r.code, 0) << r.err;
  for (const char* file : {"building.vdg.json", "base.obj", "front.obj"}) {
    EXPECT_EQ(vdg::testing::readText(dir.file(file)),
              vdg::testing::readText(std::string(VDG_SOURCE_DIR "/examples/building/") + file))
        << file << " differs from what make_building writes";
  }
}

}  // namespace
