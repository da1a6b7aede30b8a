// Manifest version 2: animated bases (an OBJ sequence; glTF in gltf_base_test.cpp), "offsets", each
// key's "frame"; the round trip through formatManifest; every bad value named.
#include <gtest/gtest.h>

#include <string>

#include "support/error_of.h"
#include "support/test_meshes.h"
#include "vdg/geom/error.h"
#include "vdg/io/manifest.h"
#include "vdg/io/obj.h"
#include "vdg/viewdep/animated_model.h"

namespace vdg {
namespace {

using testing::errorOf;

constexpr int kFrames = 6;
constexpr double kKeyTol = 1e-5;

// walk/f_002.obj .. walk/f_007.obj: a sphere moving up 0.1 a frame; key k5.obj = frame 5 moved.
class ManifestV2 : public ::testing::Test {
 protected:
  void SetUp() override {
    base_ = testing::uvSphere(4, 6);
    std::filesystem::create_directories(dir_.path() / "walk");
    for (int i = 0; i < kFrames; ++i) {
      TriMesh frame = base_;
      for (std::size_t v = 0; v < frame.vertexCount(); ++v) frame.positions[3 * v + 1] += 0.1f * i;
      frames_.push_back(frame);
      writeObj(sequenceFile(i + 2), frame);
    }
    key_ = frames_[3];
    key_.positions[0] += 0.5f;
    writeObj(dir_.file("k.obj"), key_);
  }
  std::string sequenceFile(int number) { return dir_.file("walk/" + sequenceFileName("f_%03d.obj", number)); }
  std::string write(const std::string& json) {
    const std::string path = dir_.file("m.vdg.json");
    testing::writeText(path, json);
    return path;
  }
  // The message with this test's folder left out of the paths.
  std::string loadError(const std::string& json) {
    std::string message = errorOf([&] { (void)loadManifest(write(json)); });
    const std::string folder = dir_.path().string() + "/";
    for (std::size_t at; (at = message.find(folder)) != std::string::npos;) message.erase(at, folder.size());
    return message;
  }
  testing::TempDir dir_;
  TriMesh base_, key_;
  std::vector<TriMesh> frames_;
};

constexpr const char* kGood = R"({"version": 2,
  "base_animation": {"obj_sequence": "walk/f_%03d.obj", "frames": [2, 7], "loop": true},
  "offsets": "world",
  "keys": [{"mesh": "k.obj", "view": [0, 0, 1], "frame": 3}, {"name": "k0", "mesh": "k.obj", "view": [0, 0, 1], "frame": 3}]})";

TEST_F(ManifestV2, LoadsAnObjSequenceAndKeyFrames) {
  std::string good = kGood;
  good.replace(good.find("\"frame\": 3}]"), 12, "\"frame\": 0}]");  // the second key at frame 0
  const RawViewDependentModel raw = loadManifest(write(good));
  ASSERT_TRUE(raw.animated());
  EXPECT_EQ(raw.base_animation->first, 2);
  EXPECT_EQ(raw.base_animation->last, 7);
  EXPECT_TRUE(raw.base_animation->loop);
  ASSERT_EQ(raw.frameCount(), static_cast<std::size_t>(kFrames));
  for (int i = 0; i < kFrames; ++i) EXPECT_EQ(raw.base_frames[static_cast<std::size_t>(i)], frames_[i].positions);
  EXPECT_EQ(raw.base.positions, frames_[0].positions);
  EXPECT_EQ(raw.base.triangles, base_.triangles);
  EXPECT_EQ(raw.keys[0].frame, 3);
  EXPECT_EQ(raw.keys[1].frame, 0);
  // Built, the key is reproduced at its frame and view.
  const auto model = AnimatedViewDependentModel::build(raw);
  EXPECT_EQ(model.viewCount(), 1u);
  std::vector<float> out(key_.positions.size());
  ASSERT_TRUE(model.evaluate(3, Eigen::Vector3d(0, 0, 1), 0.0, out));
  for (std::size_t i = 0; i < out.size(); ++i) EXPECT_NEAR(out[i], key_.positions[i], kKeyTol);
}

TEST_F(ManifestV2, RoundTripsThroughFormatManifest) {
  std::string good = kGood;
  good.replace(good.find("\"frame\": 3}]"), 12, "\"frame\": 5}]");
  const RawViewDependentModel raw = loadManifest(write(good));
  const std::string text = formatManifest(raw);
  EXPECT_NE(text.find("\"version\": 2"), std::string::npos) << text;
  EXPECT_NE(text.find("\"base_animation\""), std::string::npos) << text;
  EXPECT_EQ(text.find("\"base\":"), std::string::npos) << text;
  const RawViewDependentModel again = parseManifest(text, "again.vdg.json");
  ASSERT_TRUE(again.base_animation);
  EXPECT_EQ(again.base_animation->obj_sequence, "walk/f_%03d.obj");
  EXPECT_EQ(again.base_animation->first, 2);
  EXPECT_EQ(again.base_animation->last, 7);
  EXPECT_TRUE(again.base_animation->loop);
  EXPECT_EQ(again.offsets, OffsetSpace::kWorld);
  ASSERT_EQ(again.keys.size(), 2u);
  EXPECT_EQ(again.keys[0].frame, 3);
  EXPECT_EQ(again.keys[1].frame, 5);
  EXPECT_EQ(formatManifest(loadManifest(write(text))), text);

  // glTF specs round trip as text (they are not loadable until the glTF reader is glued in).
  RawViewDependentModel gltf = again;
  gltf.base_animation = BaseAnimationSpec{};
  gltf.base_animation->gltf = "walk.glb";
  gltf.base_animation->animation = 2;
  gltf.base_animation->fps = 30;
  gltf.base_animation->mesh = "Body";
  gltf.offsets = OffsetSpace::kSkinned;
  const RawViewDependentModel parsed = parseManifest(formatManifest(gltf), "g.vdg.json");
  EXPECT_EQ(parsed.base_animation->gltf, "walk.glb");
  EXPECT_EQ(parsed.base_animation->animation, 2);
  EXPECT_EQ(parsed.base_animation->fps, 30);
  EXPECT_EQ(parsed.base_animation->mesh, "Body");
  EXPECT_FALSE(parsed.base_animation->loop);
  EXPECT_EQ(parsed.offsets, OffsetSpace::kSkinned);
}

TEST_F(ManifestV2, StaticModelsAreWrittenAsVersion2AndVersion1StillLoads) {
  const std::string v1 = R"({"version": 1, "base": "k.obj", "keys": [{"mesh": "k.obj", "view": [0, 0, 1]}]})";
  const RawViewDependentModel raw = loadManifest(write(v1));
  EXPECT_FALSE(raw.animated());
  const std::string text = formatManifest(raw);
  EXPECT_NE(text.find("\"version\": 2"), std::string::npos);
  EXPECT_EQ(text.find("frame"), std::string::npos) << text;
  EXPECT_EQ(text.find("offsets"), std::string::npos) << text;
  EXPECT_NO_THROW((void)ViewDependentModel::build(loadManifest(write(text))));
}

// Version 3: "weights": {"scheme": ...} (docs/weights.md); written only when not linear.
TEST_F(ManifestV2, Version3CarriesTheWeightScheme) {
  const std::string v3 = R"({"version": 3, "base": "k.obj", "weights": {"scheme": "smooth"},
                             "keys": [{"mesh": "k.obj", "view": [0, 0, 1]}]})";
  const RawViewDependentModel raw = loadManifest(write(v3));
  EXPECT_EQ(raw.sphere.scheme, WeightScheme::Smooth);
  const std::string text = formatManifest(raw);
  EXPECT_NE(text.find("\"version\": 3"), std::string::npos) << text;
  EXPECT_EQ(loadManifest(write(text)).sphere.scheme, WeightScheme::Smooth);
  const std::string linear = R"({"version": 3, "base": "k.obj", "weights": {"scheme": "linear"},
                                 "keys": [{"mesh": "k.obj", "view": [0, 0, 1]}]})";
  const std::string written = formatManifest(loadManifest(write(linear)));
  EXPECT_NE(written.find("\"version\": 2"), std::string::npos) << written;
  EXPECT_EQ(written.find("weights"), std::string::npos) << written;
  const std::string key = R"("keys": [{"mesh": "k.obj", "view": [0, 0, 1]}])";
  EXPECT_EQ(loadError(R"({"version": 2, "base": "k.obj", "weights": {"scheme": "smooth"}, )" + key + "}"),
            "m.vdg.json: 'weights': needs manifest version 3 (this file says \"version\": 2)");
  EXPECT_NE(loadError(R"({"version": 3, "base": "k.obj", "weights": {"scheme": "cubic"}, )" + key + "}")
                .find("m.vdg.json: 'weights'.'scheme': unknown value 'cubic'"),
            std::string::npos);
  EXPECT_NE(loadError(R"({"version": 3, "base": "k.obj", "weights": {"kernel": 1}, )" + key + "}")
                .find("m.vdg.json: 'weights'.'kernel': is a setting of the 'rbf' scheme only"),
            std::string::npos);
  EXPECT_NE(loadError(R"({"version": 3, "base": "k.obj", "weights": {"order": 1}, )" + key + "}")
                .find("m.vdg.json: 'weights': unknown key 'order'"),
            std::string::npos);
  EXPECT_NE(loadError(R"({"version": 3, "base": "k.obj", "weights": "smooth", )" + key + "}")
                .find("m.vdg.json: 'weights': expected an object"),
            std::string::npos);
}

// The rbf scheme's settings: kernel and width round trip; bad values are refused in one line naming
// the key; keys too close for the width are refused when the model is built.
TEST_F(ManifestV2, Version3CarriesTheRbfSettings) {
  const std::string keys = R"("keys": [{"name": "a", "mesh": "k.obj", "view": [0, 0, 1]},
                                         {"name": "b", "mesh": "k.obj", "view": [1, 0, 0]},
                                         {"name": "c", "mesh": "k.obj", "view": [0, 1, 0.2]}])";
  const std::string v3 = R"({"version": 3, "base": "k.obj",
                             "weights": {"scheme": "rbf", "kernel": "wendland", "width": 75.5}, )" +
                         keys + "}";
  const RawViewDependentModel raw = loadManifest(write(v3));
  EXPECT_EQ(raw.sphere.scheme, WeightScheme::Rbf);
  EXPECT_EQ(raw.sphere.rbf_kernel, RbfKernel::Wendland);
  EXPECT_EQ(raw.sphere.rbf_width_deg, 75.5);
  const std::string text = formatManifest(raw);
  EXPECT_NE(text.find("\"version\": 3"), std::string::npos) << text;
  const RawViewDependentModel again = loadManifest(write(text));
  EXPECT_EQ(again.sphere.scheme, WeightScheme::Rbf);
  EXPECT_EQ(again.sphere.rbf_kernel, RbfKernel::Wendland);
  EXPECT_EQ(again.sphere.rbf_width_deg, 75.5);
  EXPECT_NO_THROW((void)ViewDependentModel::build(again));
  const RawViewDependentModel defaults =
      loadManifest(write(R"({"version": 3, "base": "k.obj", "weights": {"scheme": "rbf"}, )" + keys + "}"));
  EXPECT_EQ(defaults.sphere.rbf_kernel, RbfKernel::Gaussian);
  EXPECT_EQ(defaults.sphere.rbf_width_deg, 60.0);
  const auto error = [&](const std::string& weights) {
    return loadError(R"({"version": 3, "base": "k.obj", "weights": )" + weights + ", " + keys + "}");
  };
  EXPECT_NE(
      error(R"({"scheme": "rbf", "width": 0})").find("m.vdg.json: 'weights'.'width': expected degrees in (0, 180]"),
      std::string::npos);
  EXPECT_NE(error(R"({"scheme": "rbf", "width": 200})").find("'weights'.'width'"), std::string::npos);
  EXPECT_NE(error(R"({"scheme": "rbf", "kernel": "cubic"})").find("'weights'.'kernel': unknown value 'cubic'"),
            std::string::npos);
  EXPECT_NE(error(R"({"scheme": "smooth", "width": 30})").find("'weights'.'width': is a setting of the 'rbf' scheme"),
            std::string::npos);
  RawViewDependentModel close = defaults;
  close.keys[1].view = Eigen::Vector3d(0.000003, 0, 1);
  try {
    (void)ViewDependentModel::build(close);
    ADD_FAILURE() << "keys 0.0002 degrees apart accepted for a 60-degree Gaussian";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("ill-conditioned"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("keys[1]"), std::string::npos) << e.what();
  }
}

TEST_F(ManifestV2, SequencePatterns) {
  EXPECT_EQ(sequenceFileName("a_%d.obj", 7), "a_7.obj");
  EXPECT_EQ(sequenceFileName("a_%04d.obj", 7), "a_0007.obj");
  EXPECT_EQ(sequenceFileName("%02d", 123), "123");
  const std::string prefix = "expected a file pattern with one %d or %0Nd (\"walk/frame_%03d.obj\"), got ";
  EXPECT_EQ(errorOf([] { checkSequencePattern("a.obj"); }), prefix + "'a.obj': it has no %d");
  EXPECT_EQ(errorOf([] { checkSequencePattern("a_%s.obj"); }),
            prefix + "'a_%s.obj': the only conversion allowed is %d or %0Nd");
  EXPECT_EQ(errorOf([] { checkSequencePattern("a_%3d.obj"); }),
            prefix + "'a_%3d.obj': the only conversion allowed is %d or %0Nd");
  EXPECT_EQ(errorOf([] { checkSequencePattern("a_%010d.obj"); }),
            prefix + "'a_%010d.obj': the width of %0Nd must be one digit from 1 to 9");
  EXPECT_EQ(errorOf([] { checkSequencePattern("a_%0d.obj"); }),
            prefix + "'a_%0d.obj': the width of %0Nd must be one digit from 1 to 9");
  EXPECT_EQ(errorOf([] { checkSequencePattern("a_%d_%d.obj"); }), prefix + "'a_%d_%d.obj': it has more than one %");
  EXPECT_EQ(errorOf([] { checkSequencePattern("100%%_%d.obj"); }),
            prefix + "'100%%_%d.obj': the only conversion allowed is %d or %0Nd");
  EXPECT_EQ(errorOf([] { checkSequencePattern("a_%d"); }), "");
  EXPECT_EQ(errorOf([] { checkSequencePattern("a_%"); }), prefix + "'a_%': the only conversion allowed is %d or %0Nd");
}

TEST_F(ManifestV2, EveryBadValueIsNamed) {
  struct Case {
    std::string json, expected;
  };
  const std::string seq = R"("base_animation": {"obj_sequence": "walk/f_%03d.obj", "frames": [2, 7]})";
  const std::string key = R"("keys": [{"mesh": "k.obj", "view": [0, 0, 1], "frame": 3}])";
  const std::vector<Case> cases = {
      {R"({"version": 2, "base": "k.obj", )" + seq + ", " + key + "}",
       "m.vdg.json: give exactly one of 'base' (a mesh file) or 'base_animation' (an animated base), not both"},
      {R"({"version": 2, "keys": []})",
       "m.vdg.json: missing 'base' (the base mesh file) or 'base_animation' (an animated base)"},
      {R"({"version": 1, )" + seq + ", " + key + "}",
       "m.vdg.json: 'base_animation': needs manifest version 2 (this file says \"version\": 1)"},
      {R"({"version": 1, "base": "k.obj", "offsets": "world", "keys": []})",
       "m.vdg.json: 'offsets': needs manifest version 2 (this file says \"version\": 1)"},
      {R"({"version": 2, "base": "k.obj", "keys": [{"mesh": "k.obj", "view": [0, 0, 1], "frame": 3}]})",
       "m.vdg.json: key 'k' (keys[0]): 'frame' needs an animated base model ('base_animation', manifest version 2)"},
      {R"({"version": 2, "base": "k.obj", "offsets": "skinned", "keys": []})",
       "m.vdg.json: 'offsets': 'skinned' needs an animated, skinned base ('base_animation')"},
      {R"({"version": 2, )" + seq + R"(, "offsets": "bones", "keys": []})",
       "m.vdg.json: 'offsets': unknown value 'bones' (expected one of 'world', 'skinned')"},
      {R"({"version": 2, )" + seq + R"(, "offsets": "skinned", "keys": []})",
       "m.vdg.json: 'offsets': 'skinned' needs a skinned base (the base animation has no skin)"},
      {R"({"version": 2, "base_animation": {"frames": [0, 1]}, "keys": []})",
       "m.vdg.json: 'base_animation': give exactly one of 'obj_sequence' (\"walk/frame_%03d.obj\") or 'gltf' (a "
       ".gltf or .glb file)"},
      {R"({"version": 2, "base_animation": {"obj_sequence": "walk/f_%03d.obj"}, "keys": []})",
       "m.vdg.json: 'base_animation': missing key 'frames'"},
      {R"({"version": 2, "base_animation": {"obj_sequence": "walk/f_%03d.obj", "frames": [7, 2]}, "keys": []})",
       "m.vdg.json: 'base_animation'.'frames': the last frame 2 comes before the first 7"},
      {R"({"version": 2, "base_animation": {"obj_sequence": "walk/f_%03d.obj", "frames": [0, 100000]}, "keys": []})",
       "m.vdg.json: 'base_animation'.'frames': 100001 frames; a base animation may have at most 100000"},
      {R"({"version": 2, "base_animation": {"obj_sequence": "walk/f_%03d.obj", "frames": [-1, 2]}, "keys": []})",
       "m.vdg.json: 'base_animation'.'frames'[0]: expected an integer from 0 to 999999999, got -1"},
      {R"({"version": 2, "base_animation": {"obj_sequence": "walk/f_%03d.obj", "frames": 3}, "keys": []})",
       "m.vdg.json: 'base_animation'.'frames': expected [first, last] (two file numbers), got the number 3"},
      {R"({"version": 2, "base_animation": {"obj_sequence": "walk/f_%s.obj", "frames": [2, 7]}, "keys": []})",
       "m.vdg.json: 'base_animation'.'obj_sequence': expected a file pattern with one %d or %0Nd "
       "(\"walk/frame_%03d.obj\"), got 'walk/f_%s.obj': the only conversion allowed is %d or %0Nd"},
      {R"({"version": 2, "base_animation": {"obj_sequence": "walk/f_%03d.obj", "frames": [2, 7], "fps": 3}, "keys": []})",
       "m.vdg.json: 'base_animation'.'fps': applies to a 'gltf' base, not to an 'obj_sequence'"},
      {R"({"version": 2, "base_animation": {"gltf": "w.glb", "frames": [2, 7]}, "keys": []})",
       "m.vdg.json: 'base_animation'.'frames': applies to an 'obj_sequence' base; a 'gltf' base takes 'animation' and "
       "'fps'"},
      {R"({"version": 2, "base_animation": {"gltf": "w.glb", "fps": 0}, "keys": []})",
       "m.vdg.json: 'base_animation'.'fps': expected frames per second in (0, 1000], got the number 0"},
      {R"({"version": 2, "base_animation": {"gltf": "w.glb", "loop": 1}, "keys": []})",
       "m.vdg.json: 'base_animation'.'loop': expected true or false, got the number 1"},
      {R"({"version": 2, "base_animation": {"gltf": "w.glb", "speed": 1}, "keys": []})",
       "m.vdg.json: 'base_animation': unknown key 'speed' (expected one of 'obj_sequence', 'frames', 'gltf', "
       "'animation', 'fps', 'mesh', 'loop')"},
      {R"({"version": 2, "base_animation": {"gltf": "w.glb"}, "keys": []})",
       "m.vdg.json: base_animation.gltf: w.glb: no such file (glTF)"},
      {R"({"version": 2, )" + seq + R"(, "keys": [{"mesh": "k.obj", "view": [0, 0, 1], "frame": 6}]})",
       "m.vdg.json: key 'k' (keys[0]): frame 6 is outside the base animation's frames 0..5"},
      {R"({"version": 2, )" + seq + R"(, "keys": [{"mesh": "k.obj", "view": [0, 0, 1], "frame": 1.5}]})",
       "m.vdg.json: key 'k' (keys[0]).'frame': expected an integer from 0 to 99999, got the number 1.5"},
      {R"({"version": 2, )" + seq +
           R"(, "keys": [{"mesh": "k.obj", "view": [0, 0, 1], "frame": 2}, {"name": "j", "mesh": "k.obj", "view": [0, 0, 2], "frame": 2}]})",
       "m.vdg.json: key 'j' (keys[1]): same view direction (within 1e-6 rad) and same frame 2 as key 'k'"},
      {R"({"version": 2, "base_animation": {"obj_sequence": "walk/f_%03d.obj", "frames": [2, 8]}, "keys": []})",
       "m.vdg.json: base_animation frame 6: walk/f_008.obj: no such file (mesh)"},
  };
  for (const Case& c : cases) EXPECT_EQ(loadError(c.json), c.expected) << c.json;
}

TEST_F(ManifestV2, EveryFrameMustHaveTheFirstFramesTopology) {
  const std::string json =
      R"({"version": 2, "base_animation": {"obj_sequence": "walk/f_%03d.obj", "frames": [2, 7]}, "keys": []})";
  TriMesh other = testing::uvSphere(5, 6);
  writeObj(sequenceFile(5), other);
  EXPECT_EQ(loadError(json),
            "m.vdg.json: base_animation frame 3 (walk/f_005.obj): 26 vertices but frame 0 "
            "(walk/f_002.obj) has 20; every frame must have the same topology");
  TriMesh flipped = base_;
  std::swap(flipped.triangles[0], flipped.triangles[1]);
  writeObj(sequenceFile(5), flipped);
  EXPECT_EQ(loadError(json),
            "m.vdg.json: base_animation frame 3 (walk/f_005.obj): its triangles differ from frame "
            "0's (walk/f_002.obj); every frame must have the same topology");
}

}  // namespace
}  // namespace vdg
