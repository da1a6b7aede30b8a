// Sampling a model's weights along a camera path (vdg/viewdep/camera_bake.h): the weights of each
// sample give back the model's blend from that camera (Rademacher 99, section 3.2; section 4 for
// an animated model), the frames follow the animation's loop rule, and bad paths are refused.
#include "vdg/viewdep/camera_bake.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "support/error_of.h"
#include "support/test_meshes.h"
#include "vdg/io/manifest.h"

namespace vdg {
namespace {

using testing::errorOf;

constexpr double kBlendTol = 1e-5;  // float weights times unit-sized offsets

const std::string kWalk = VDG_SOURCE_DIR "/tests/io/formats/tetra_walk_v2.vdg.json";

// A sphere with three keys, each pushing the side it is seen from outwards.
ViewDependentModel sphereModel() {
  RawViewDependentModel raw;
  raw.base = testing::uvSphere(8, 12);
  for (const auto& [name, dir] :
       {std::pair<std::string, Eigen::Vector3d>{"front", {0, 0, 1}}, {"side", {1, 0, 0}}, {"top", {0, 1, 0}}}) {
    RawKey k;
    k.name = name;
    k.mesh = raw.base;
    k.view = dir;
    for (std::size_t v = 0; v < raw.base.vertexCount(); ++v) {
      Eigen::Vector3d p(k.mesh.positions[v * 3], k.mesh.positions[v * 3 + 1], k.mesh.positions[v * 3 + 2]);
      p *= 1.0 + 0.5 * std::max(0.0, p.dot(dir));
      for (int c = 0; c < 3; ++c) k.mesh.positions[v * 3 + c] = static_cast<float>(p[c]);
    }
    raw.keys.push_back(k);
  }
  return ViewDependentModel::build(raw);
}

std::vector<Camera> orbit(const Eigen::Vector3d& center, int count) {
  std::vector<Camera> cams;
  for (int f = 0; f < count; ++f) {
    const double az = 2.0 * std::numbers::pi * f / count;
    Camera c;
    c.target = center;
    c.eye = center + 5.0 * Eigen::Vector3d(std::sin(az) * 0.9, 0.4, std::cos(az) * 0.9);
    c.fov_deg = 30.0;
    cams.push_back(c);
  }
  return cams;
}

TEST(CameraBake, WeightsGiveBackTheBlendAtEverySample) {
  const ViewDependentModel model = sphereModel();
  const auto cams = orbit(model.center(), 8);
  const CameraPathBake bake = bakeCameraPath(model, cams, 24.0, 1.5, 0.0, true);
  ASSERT_EQ(bake.times.size(), cams.size() + 1);  // the closing sample
  ASSERT_EQ(bake.weights.size(), bake.times.size() * model.keyCount());
  EXPECT_TRUE(bake.frames.empty());
  std::vector<float> expected(model.vertexCount() * 3), keys(expected.size());
  for (std::size_t s = 0; s < bake.times.size(); ++s) {
    EXPECT_NEAR(bake.times[s], s / 24.0, 1e-6);
    ASSERT_TRUE(model.evaluate(model.viewFromEye(cams[s % cams.size()].eye), 0.0, expected));
    std::vector<double> blended(model.base().positions.begin(), model.base().positions.end());
    for (std::size_t k = 0; k < model.keyCount(); ++k) {
      ASSERT_TRUE(model.keyPositions(k, keys));
      for (std::size_t i = 0; i < blended.size(); ++i)
        blended[i] += bake.weights[s * model.keyCount() + k] * (keys[i] - model.base().positions[i]);
    }
    for (std::size_t i = 0; i < blended.size(); ++i) ASSERT_NEAR(blended[i], expected[i], kBlendTol) << s << " " << i;
  }
}

TEST(CameraBake, AnAnimatedPathShowsTheFramesOfTheLoop) {
  const AnimatedViewDependentModel model = AnimatedViewDependentModel::build(loadManifest(kWalk));
  const int n = model.frameCount();
  const auto cams = orbit(model.center(), 5);
  const CameraPathBake bake = bakeAnimatedCameraPath(model, cams, 2, 12.0, 1.0, 0.0, false, true);
  std::size_t keys = 0;
  for (std::size_t i = 0; i < model.viewCount(); ++i) keys += model.keyFrames(i).size();
  const std::size_t targets = keys + static_cast<std::size_t>(n - 1);
  ASSERT_EQ(bake.weights.size(), bake.times.size() * targets);
  ASSERT_EQ(bake.frames.size(), bake.times.size());
  for (std::size_t s = 0; s < bake.frames.size(); ++s) {
    const int frame = model.loop() ? (2 + static_cast<int>(s)) % n : std::min(2 + static_cast<int>(s), n - 1);
    EXPECT_EQ(bake.frames[s], frame);
    // Base frame F's own target carries weight 1, the other base frames none.
    for (int f = 1; f < n; ++f)
      EXPECT_EQ(bake.weights[s * targets + keys + static_cast<std::size_t>(f - 1)], f == frame ? 1.0f : 0.0f);
  }
}

TEST(CameraBake, BadPathsAreRefused) {
  const ViewDependentModel model = sphereModel();
  auto cams = orbit(model.center(), 3);
  EXPECT_EQ(errorOf([&] { bakeCameraPath(model, {}, 24, 1, 0, false); }), "bake: no cameras");
  EXPECT_EQ(errorOf([&] { bakeCameraPath(model, cams, 0, 1, 0, false); }),
            "bake: the frame rate must be finite and > 0");
  EXPECT_EQ(errorOf([&] { bakeCameraPath(model, cams, 24, -1, 0, false); }),
            "bake: the aspect ratio must be finite and > 0");
  cams[1].fov_deg = 50;
  EXPECT_EQ(errorOf([&] { bakeCameraPath(model, cams, 24, 1, 0, false); }),
            "bake: camera 1: every camera must have the same field of view");
  cams[1].fov_deg = 30;
  cams[2].ortho_height = 2;
  EXPECT_EQ(errorOf([&] { bakeCameraPath(model, cams, 24, 1, 0, false); }),
            "bake: camera 2: glTF bakes perspective cameras only");
  cams[2].ortho_height = 0;
  cams[0].eye = model.center();
  EXPECT_EQ(errorOf([&] { bakeCameraPath(model, cams, 24, 1, 0, false); }),
            "bake: camera 0: no view direction (the eye is at the model centre, or the sharpness is not > 0)");
}

}  // namespace
}  // namespace vdg
