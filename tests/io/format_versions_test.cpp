// Every saved version of every format still loads (files in tests/io/formats/, see its README).
#include <gtest/gtest.h>

#include <string>

#include "vdg/anim/ease.h"
#include "vdg/anim/track.h"
#include "vdg/deform/edits.h"
#include "vdg/geom/error.h"
#include "vdg/io/anim_json.h"
#include "vdg/io/camera_json.h"
#include "vdg/io/edit_script.h"
#include "vdg/io/gltf_export.h"
#include "vdg/io/manifest.h"
#include "vdg/viewdep/animated_model.h"
#include "vdg/viewdep/model.h"

namespace vdg {
namespace {

constexpr double kExact = 1e-12;  // values written in the files, read back as doubles

std::string formats(const std::string& name) { return std::string(VDG_SOURCE_DIR) + "/tests/io/formats/" + name; }

TEST(FormatVersions, ManifestVersion1) {
  const RawViewDependentModel raw = loadManifest(formats("tetra_v1.vdg.json"));
  EXPECT_EQ(raw.comment, "a version-1 manifest: one key seen from above");
  ASSERT_EQ(raw.keys.size(), 1u);
  EXPECT_EQ(raw.keys[0].name, "up");
  const ViewDependentModel model = ViewDependentModel::build(raw);
  std::vector<float> positions(3 * model.vertexCount());
  // Seen from the key's own view the model is the key mesh: vertex 3 is raised to y = 1.5.
  ASSERT_TRUE(model.evaluate(Eigen::Vector3d(0, 1, 0), 0.0, positions));
  EXPECT_NEAR(positions[3 * 2 + 1], 1.5, 1e-6);
}

TEST(FormatVersions, ManifestVersion2AnimatedBase) {
  const RawViewDependentModel raw = loadManifest(formats("tetra_walk_v2.vdg.json"));
  ASSERT_TRUE(raw.animated());
  EXPECT_TRUE(raw.base_animation->loop);
  ASSERT_EQ(raw.frameCount(), 3u);
  EXPECT_EQ(raw.base_frames[2][0], 2.0f);  // frame 2 moved +2 in x
  ASSERT_EQ(raw.keys.size(), 1u);
  EXPECT_EQ(raw.keys[0].frame, 1);
  const AnimatedViewDependentModel model = AnimatedViewDependentModel::build(raw);
  std::vector<float> positions(3 * model.vertexCount());
  // Seen from the key's view at its frame the model is the key mesh: vertex 3 raised to y = 1.5.
  ASSERT_TRUE(model.evaluate(1, Eigen::Vector3d(0, 1, 0), 0.0, positions));
  EXPECT_NEAR(positions[3 * 2 + 1], 1.5, 1e-6);
  // One key frame: a constant offset, added to the moving base at every frame.
  ASSERT_TRUE(model.evaluate(2, Eigen::Vector3d(0, 1, 0), 0.0, positions));
  EXPECT_NEAR(positions[3 * 2], 2.0, 1e-6);
  EXPECT_NEAR(positions[3 * 2 + 1], 1.5, 1e-6);
}

// glTF exports' mesh.extras.vdg: version 1 (no "sphere" / "time") and version 2, static and animated;
// versions 3 (smooth weights) and 4 (rbf weights, with their interpolation), static. At the key's own
// view every scheme shows the key.
TEST(FormatVersions, GltfExtrasVersions1To4) {
  for (const char* file :
       {"tetra_extras_v1.gltf", "tetra_extras_v2.gltf", "tetra_extras_v3.gltf", "tetra_extras_v4.gltf"}) {
    const ViewDependentModel model = ViewDependentModel::build(loadGltfModel(formats(file)));
    ASSERT_EQ(model.keyCount(), 1u) << file;
    EXPECT_EQ(model.keyName(0), "up");
    std::vector<float> positions(3 * model.vertexCount());
    ASSERT_TRUE(model.evaluate(Eigen::Vector3d(0, 1, 0), 0.0, positions));
    EXPECT_NEAR(positions[3 * 2 + 1], 1.5, 1e-6) << file;  // the key mesh, as the manifest's
  }
  EXPECT_EQ(loadGltfModel(formats("tetra_extras_v3.gltf")).sphere.scheme, WeightScheme::Smooth);
  const RawViewDependentModel rbf = loadGltfModel(formats("tetra_extras_v4.gltf"));
  EXPECT_EQ(rbf.sphere.scheme, WeightScheme::Rbf);
  EXPECT_EQ(rbf.sphere.rbf_kernel, RbfKernel::Gaussian);
  EXPECT_EQ(rbf.sphere.rbf_width_deg, 60.0);
  for (const char* file : {"tetra_walk_extras_v1.gltf", "tetra_walk_extras_v2.gltf"}) {
    const AnimatedViewDependentModel model = AnimatedViewDependentModel::build(loadGltfModel(formats(file)));
    ASSERT_EQ(model.frameCount(), 3) << file;
    std::vector<float> positions(3 * model.vertexCount());
    ASSERT_TRUE(model.evaluate(2, Eigen::Vector3d(0, 1, 0), 0.0, positions));
    EXPECT_NEAR(positions[3 * 2], 2.0, 1e-6) << file;
    EXPECT_NEAR(positions[3 * 2 + 1], 1.5, 1e-6) << file;
  }
}

TEST(FormatVersions, CameraFiles) {
  const Camera old = readCameraFile(formats("camera_unversioned.json"));
  EXPECT_NEAR(old.fov_deg, 35.0, kExact);
  EXPECT_FALSE(old.isOrtho());
  const Camera v1 = readCameraFile(formats("camera_v1.json"));
  EXPECT_NEAR(v1.ortho_height, 2.0, kExact);
  EXPECT_NEAR(v1.eye.z(), 3.0, kExact);
}

TEST(FormatVersions, AnimationSpecs) {
  const anim::AnimSpec ease = anim::loadAnimSpec(formats("ease_unversioned.json"));
  EXPECT_EQ(ease.kind, anim::AnimSpec::Kind::kEase);
  EXPECT_NEAR(ease.ease(0.0), 0.0, kExact);
  EXPECT_NEAR(ease.ease(1.0), 1.0, kExact);
  const anim::AnimSpec track = anim::loadAnimSpec(formats("track_v1.json"));
  ASSERT_EQ(track.kind, anim::AnimSpec::Kind::kTrack);
  EXPECT_NEAR(anim::Track::build(track.track).scalarAt(1.0), 2.0, kExact);
}

TEST(FormatVersions, EditScriptAndLogVersion1) {
  const EditScript script = readEditScript(formats("edits_v1.json"));
  ASSERT_EQ(script.ops.size(), 1u);
  ASSERT_TRUE(script.view.has_value());
  const EditLog log = readEditLog(formats("tetra_up.edits_v1.json"));
  EXPECT_EQ(log.key, "up");
  EXPECT_EQ(log.origin, "base");
  ASSERT_EQ(log.entries.size(), 1u);
  EXPECT_EQ(log.entries[0].ops.size(), 1u);
}

TEST(FormatVersions, NewerVersionsAreRefusedByName) {
  try {
    anim::parseAnimSpec(R"({"version": 2, "ease": "sine"})", "spec.json");
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), "spec.json: 'version': this vdg reads animation specs version 1, got 2");
  }
}

}  // namespace
}  // namespace vdg
