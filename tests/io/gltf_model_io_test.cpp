// Reading vdg's own glTF exports back as models (loadGltfModel), and the animated export and bake
// (Rademacher 99, section 4): the walking character of examples/walk with skinned and world
// offsets, an OBJ-sequence base, and the baked camera path evaluated by vdg's own glTF reader.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <numbers>

#include "support/error_of.h"
#include "support/test_meshes.h"
#include "vdg/anim/rig.h"
#include "vdg/io/gltf.h"
#include "vdg/io/gltf_export.h"
#include "vdg/io/manifest.h"
#include "vdg/io/model.h"
#include "vdg/viewdep/animated_model.h"

namespace vdg {
namespace {

using testing::errorOf;

// The round-trip bound on positions (float storage, skin re-applied in floats).
constexpr double kRoundTripTol = 1e-4;

const std::string kWalk = VDG_SOURCE_DIR "/examples/walk/walker.vdg.json";
const std::string kWalkWorld = VDG_SOURCE_DIR "/examples/walk/walker-world.vdg.json";

std::vector<Eigen::Vector3d> testViews() {
  return {{0, 0, 1}, {1, 0.1, 0}, {0.6, 0.3, 0.7}, {-0.8, 0.2, -0.5}, {0.2, -0.9, 0.3}};
}

void expectSameAnimated(const AnimatedViewDependentModel& a, const AnimatedViewDependentModel& b,
                        std::initializer_list<int> frames) {
  ASSERT_EQ(a.vertexCount(), b.vertexCount());
  ASSERT_EQ(a.frameCount(), b.frameCount());
  ASSERT_EQ(a.loop(), b.loop());
  ASSERT_EQ(a.offsetSpace(), b.offsetSpace());
  std::vector<float> pa(a.vertexCount() * 3), pb(pa.size());
  for (int f : frames)
    for (const Eigen::Vector3d& view : testViews()) {
      ASSERT_TRUE(a.evaluate(f, view.normalized(), 0.0, pa));
      ASSERT_TRUE(b.evaluate(f, view.normalized(), 0.0, pb));
      double worst = 0;
      for (std::size_t i = 0; i < pa.size(); ++i) worst = std::max(worst, std::abs(double(pa[i]) - pb[i]));
      ASSERT_LE(worst, kRoundTripTol) << "frame " << f << " view " << view.transpose();
    }
}

GltfExportInput animatedInput(const RawViewDependentModel& raw) {
  const AnimatedViewDependentModel model = AnimatedViewDependentModel::build(raw);
  std::optional<RawRig> rig;
  if (!raw.base_animation->gltf.empty()) rig = readBaseRig(raw);
  return gltfExportInput(model, raw, rig ? &*rig : nullptr);
}

TEST(GltfModelIo, StaticExportReadsBackAsTheSameModel) {
  testing::TempDir dir;
  const RawViewDependentModel raw = loadManifest(VDG_SOURCE_DIR "/examples/spot/spot.vdg.json");
  const ViewDependentModel model = ViewDependentModel::build(raw);
  for (const char* name : {"spot.glb", "spot.gltf"}) {
    writeGltfExport(dir.file(name), gltfExportInput(model));
    EXPECT_TRUE(gltfHasModel(dir.file(name)));
    const ViewDependentModel back = ViewDependentModel::build(loadModel(dir.file(name)));
    ASSERT_EQ(back.keyCount(), model.keyCount());
    std::vector<float> pa(model.vertexCount() * 3), pb(pa.size());
    for (const Eigen::Vector3d& view : testViews()) {
      ASSERT_TRUE(model.evaluate(view.normalized(), 0.0, pa));
      ASSERT_TRUE(back.evaluate(view.normalized(), 0.0, pb));
      for (std::size_t i = 0; i < pa.size(); ++i) ASSERT_NEAR(pa[i], pb[i], kRoundTripTol) << name << " i " << i;
    }
  }
}

// Extras v2 of an animated model: per key view its targets and the spline's table, exactly the
// model's; malformed time tables are refused naming the field.
TEST(GltfModelIo, AnimatedExtrasV2CarryTheViewsAndTheirTimeTables) {
  const RawViewDependentModel raw = loadManifest(kWalk);
  const AnimatedViewDependentModel model = AnimatedViewDependentModel::build(raw);
  const GltfExportInput input = animatedInput(raw);
  std::string bin;
  const std::string json_text = gltfToJson(input, "w.gltf", "w.bin", bin);
  const nlohmann::json extras = nlohmann::json::parse(json_text).at("meshes").at(0).at("extras");
  const nlohmann::json& vdg = extras.at("vdg");
  ASSERT_EQ(vdg.at("sphere").at("views").get<std::size_t>(), model.viewCount());
  ASSERT_EQ(vdg.at("time").size(), model.viewCount());
  for (std::size_t i = 0; i < model.viewCount(); ++i) {
    const nlohmann::json& targets = vdg.at("sphere").at("view_targets")[i];
    ASSERT_EQ(targets.size(), model.keyFrames(i).size());
    for (std::size_t j = 0; j < targets.size(); ++j) {
      EXPECT_EQ(extras.at("targetNames")[targets[j].get<std::size_t>()], model.keyName(i, j));
      EXPECT_EQ(vdg.at("time")[i].at("frames")[j], model.keyFrames(i)[j]);
    }
    const auto second = model.secondDerivatives(i);
    EXPECT_EQ(vdg.at("time")[i].at("second").get<std::vector<double>>(),
              std::vector<double>(second.begin(), second.end()));
    for (int c = 0; c < 3; ++c) EXPECT_EQ(vdg.at("sphere").at("points")[i][c].get<double>(), model.viewDirection(i)[c]);
  }
  std::vector<std::vector<float>> deltas(extras.at("targetNames").size(),
                                         std::vector<float>(model.base().positions.size(), 0.0f));
  const auto refused = [&](const std::function<void(nlohmann::json&)>& change) {
    nlohmann::json e = extras;
    change(e);
    return errorOf([&] { (void)rawModelFromGltfExtras(e.dump(), model.base(), deltas, "w.glb"); });
  };
  // Well-formed: refused only because an animated model needs loadGltfModel.
  EXPECT_NE(refused([](auto&) {}).find("read it with loadGltfModel"), std::string::npos);
  EXPECT_EQ(refused([](auto& e) { e["vdg"].erase("time"); }), "w.glb: mesh extras: 'vdg': missing key 'time'");
  EXPECT_EQ(refused([](auto& e) { e["vdg"]["time"][0]["second"].erase(0); }),
            "w.glb: mesh extras: 'vdg'.'time'[0].'second': expected 4 numbers, got an array of 3 items");
  EXPECT_EQ(refused([](auto& e) {
              e["vdg"]["time"][1]["frames"] = {10};
            }).rfind("w.glb: mesh extras: 'vdg'.'time'[1].'frames': ", 0),
            0u);
}

TEST(GltfModelIo, SkinnedWalkerExportsItsSkinAndReadsBack) {
  testing::TempDir dir;
  const RawViewDependentModel raw = loadManifest(kWalk);
  const GltfExportInput input = animatedInput(raw);
  ASSERT_TRUE(input.base_animation);
  EXPECT_EQ(input.base_animation->mode, GltfBaseMode::kSkin);
  EXPECT_EQ(input.targets.size(), 4u);
  writeGltfExport(dir.file("walk.glb"), input);
  // The file as a generic reader sees it: a skinned mesh whose animation plays the walk.
  const Rig file = Rig::build(readGltfRig(dir.file("walk.glb")));
  EXPECT_TRUE(file.skinned());
  ASSERT_EQ(file.animationCount(), 1u);
  const AnimatedViewDependentModel model = AnimatedViewDependentModel::build(raw);
  const AnimatedViewDependentModel back = AnimatedViewDependentModel::build(loadModel(dir.file("walk.glb")));
  expectSameAnimated(model, back, {0, 7, 10, 21, 30, 39});
  // With zero morph weights the file's own animation is the base walk.
  std::vector<float> posed(file.vertexCount() * 3);
  for (int f : {3, 25}) {
    ASSERT_TRUE(file.evaluate(0, f / 24.0, posed));
    const auto base = model.baseFrame(f);
    for (std::size_t i = 0; i < posed.size(); ++i) ASSERT_NEAR(posed[i], base[i], kRoundTripTol);
  }
}

TEST(GltfModelIo, WorldOffsetWalkerExportsSampledFramesAndReadsBack) {
  testing::TempDir dir;
  const RawViewDependentModel raw = loadManifest(kWalkWorld);
  const GltfExportInput input = animatedInput(raw);
  ASSERT_TRUE(input.base_animation);
  EXPECT_EQ(input.base_animation->mode, GltfBaseMode::kFrames);
  EXPECT_EQ(input.base_animation->frame_deltas.size(), 39u);
  writeGltfExport(dir.file("walk.gltf"), input);
  const AnimatedViewDependentModel model = AnimatedViewDependentModel::build(raw);
  const AnimatedViewDependentModel back = AnimatedViewDependentModel::build(loadModel(dir.file("walk.gltf")));
  expectSameAnimated(model, back, {0, 10, 13, 30, 39});
}

// An OBJ-sequence base (in memory: a bending bar over 12 frames) with two key views.
RawViewDependentModel sequenceModel(bool loop) {
  RawViewDependentModel raw;
  raw.source = "seq.vdg.json";
  raw.base = testing::uvSphere(6, 8);
  BaseAnimationSpec spec;
  spec.obj_sequence = "f_%02d.obj";
  spec.first = 0;
  spec.last = 11;
  spec.loop = loop;
  raw.base_animation = spec;
  const std::size_t n = raw.base.positions.size();
  for (int f = 0; f < 12; ++f) {
    std::vector<float> p = raw.base.positions;
    for (std::size_t v = 0; v < n / 3; ++v) p[v * 3] += 0.1f * std::sin(f * 0.5f) * p[v * 3 + 1];
    raw.base_frames.push_back(p);
  }
  raw.base.positions = raw.base_frames[0];
  const auto key = [&](const std::string& name, const Eigen::Vector3d& view, int frame, float amount) {
    RawKey k;
    k.name = name;
    k.view = view;
    k.frame = frame;
    k.mesh = raw.base;
    k.mesh.positions = raw.base_frames[static_cast<std::size_t>(frame)];
    for (std::size_t v = 0; v < n / 3; ++v) k.mesh.positions[v * 3 + 2] += amount * k.mesh.positions[v * 3 + 1];
    return k;
  };
  raw.keys = {key("front3", {0, 0, 1}, 3, 0.2f), key("front8", {0, 0, 1}, 8, -0.1f), key("side5", {1, 0, 0}, 5, 0.3f)};
  return raw;
}

TEST(GltfModelIo, ObjSequenceBaseExportsSampledFramesAndReadsBack) {
  for (bool loop : {false, true}) {
    testing::TempDir dir;
    const RawViewDependentModel raw = sequenceModel(loop);
    const AnimatedViewDependentModel model = AnimatedViewDependentModel::build(raw);
    writeGltfExport(dir.file("seq.glb"), gltfExportInput(model, raw, nullptr));
    const AnimatedViewDependentModel back = AnimatedViewDependentModel::build(loadModel(dir.file("seq.glb")));
    expectSameAnimated(model, back, {0, 3, 4, 8, 11});
    // Exporting the read-back model again gives the same model.
    const RawViewDependentModel raw2 = loadModel(dir.file("seq.glb"));
    writeGltfExport(dir.file("again.glb"), animatedInput(raw2));
    const AnimatedViewDependentModel again = AnimatedViewDependentModel::build(loadModel(dir.file("again.glb")));
    expectSameAnimated(model, again, {2, 9});
  }
}

TEST(GltfModelIo, ReexportOfASkinnedExportKeepsTheModel) {
  testing::TempDir dir;
  const RawViewDependentModel raw = loadManifest(kWalk);
  writeGltfExport(dir.file("walk.glb"), animatedInput(raw));
  const RawViewDependentModel back = loadModel(dir.file("walk.glb"));
  writeGltfExport(dir.file("again.glb"), animatedInput(back));
  expectSameAnimated(AnimatedViewDependentModel::build(raw),
                     AnimatedViewDependentModel::build(loadModel(dir.file("again.glb"))), {5, 30});
}

// The baked file through vdg's glTF reader (vdg::Rig, as any viewer would play it) against the
// model evaluated at the frame and view of each output frame.
void expectBakeMatches(const std::string& manifest, int first, bool close_loop) {
  testing::TempDir dir;
  const RawViewDependentModel raw = loadManifest(manifest);
  const AnimatedViewDependentModel model = AnimatedViewDependentModel::build(raw);
  GltfExportInput input = animatedInput(raw);
  constexpr double kFps = 12.0;
  std::vector<Camera> cameras;
  for (int f = 0; f < 9; ++f) {
    Camera c;
    const double a = (first + f) * 2.0 * std::numbers::pi / 9.0;
    c.eye = model.center() + 4.0 * Eigen::Vector3d(std::sin(a), 0.4, std::cos(a));
    c.target = model.center();
    cameras.push_back(c);
  }
  const bool frame_targets = input.base_animation->mode == GltfBaseMode::kFrames;
  input.bake = gltfBakedAnimation(
      bakeAnimatedCameraPath(model, cameras, first, kFps, 1.0, 0.0, close_loop, frame_targets), input);
  writeGltfExport(dir.file("bake.glb"), input);
  const Rig rig = Rig::build(readGltfRig(dir.file("bake.glb")));
  std::vector<float> baked(rig.vertexCount() * 3), expected(baked.size());
  const int n = model.frameCount();
  for (int s : {0, 1, 4, 8}) {
    ASSERT_TRUE(rig.evaluate(0, s / kFps, baked));
    const int out_frame = first + s;
    const int frame = model.loop() ? out_frame % n : std::min(out_frame, n - 1);
    const Eigen::Vector3d view = (cameras[static_cast<std::size_t>(s)].eye - model.center()).normalized();
    ASSERT_TRUE(model.evaluate(frame, view, 0.0, expected));
    double worst = 0;
    for (std::size_t i = 0; i < baked.size(); ++i) worst = std::max(worst, std::abs(double(baked[i]) - expected[i]));
    EXPECT_LE(worst, kRoundTripTol) << manifest << " sample " << s << " frame " << frame;
  }
  // The baked file still reads back as the model (its base animation is the second one).
  expectSameAnimated(model, AnimatedViewDependentModel::build(loadModel(dir.file("bake.glb"))), {12});
}

TEST(GltfModelIo, BakedSkinnedWalkerMatchesTheModelAtEveryFrame) { expectBakeMatches(kWalk, 36, true); }
TEST(GltfModelIo, BakedWorldWalkerMatchesTheModelAtEveryFrame) { expectBakeMatches(kWalkWorld, 3, false); }

TEST(GltfModelIo, RefusesWhatItCannotReadOrExport) {
  testing::TempDir dir;
  // A plain glTF mesh is not a model.
  const RawViewDependentModel raw = loadManifest(kWalk);
  EXPECT_FALSE(gltfHasModel(VDG_SOURCE_DIR "/examples/walk/walker.glb"));
  EXPECT_EQ(errorOf([] { (void)loadGltfModel(VDG_SOURCE_DIR "/examples/walk/walker.glb"); }), VDG_SOURCE_DIR
            "/examples/walk/walker.glb: the mesh has no extras.vdg: this glTF file is a plain mesh, not "
            "a view-dependent model exported by vdg");
  // Skinned offsets need a skinned glTF base.
  const AnimatedViewDependentModel model = AnimatedViewDependentModel::build(raw);
  EXPECT_EQ(errorOf([&] { (void)gltfExportInput(model, raw, nullptr); }),
            kWalk +
                ": 'offsets': \"skinned\" is exported only for a skinned glTF base (glTF morphs before it skins); "
                "this base is not skinned");
  RawRig rig = readBaseRig(raw);
  rig.default_weights.assign(1, 0.5);
  rig.target_positions.assign(1, std::vector<float>(rig.mesh.positions.size(), 0.0f));
  EXPECT_EQ(errorOf([&] { (void)gltfExportInput(model, raw, &rig); }),
            kWalk +
                ": base_animation.gltf: the base mesh uses morph targets of its own; a model with \"skinned\" "
                "offsets on it cannot be exported yet");
  RawViewDependentModel seq = sequenceModel(false);
  seq.source = kWalk;
  EXPECT_EQ(errorOf([&] { (void)readBaseRig(seq); }), kWalk + ": the base is not a glTF animation");
}

}  // namespace
}  // namespace vdg
