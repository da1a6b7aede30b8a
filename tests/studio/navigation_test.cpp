// Camera navigation of vdg studio: each move does what its name says in the picture, and every
// result is a valid camera (up orthogonal to the view axis, unit).
#include <gtest/gtest.h>

#include <cmath>

#include "vdg/studio/navigation.h"

namespace vdg::studio {
namespace {

constexpr double kTol = 1e-9;
constexpr int kW = 640, kH = 480;

Camera frontCamera() {
  Camera c;
  c.eye = {0, 0, 5};
  c.target = {0, 0, 0};
  c.fov_deg = 40;
  return c;
}

void expectValid(const Camera& c) {
  const Eigen::Vector3d axis = (c.target - c.eye).normalized();
  EXPECT_NEAR(c.up.norm(), 1.0, kTol);
  EXPECT_NEAR(c.up.dot(axis), 0.0, kTol);
}

TEST(Navigation, OrbitKeepsTheDistanceAndTurnsAboutTheTarget) {
  const Camera c = orbit(frontCamera(), 90, 0);
  expectValid(c);
  EXPECT_NEAR((c.eye - c.target).norm(), 5.0, kTol);
  EXPECT_NEAR(c.eye.x(), 5.0, kTol);  // a quarter turn about +Y from the front: the eye on +X
  EXPECT_NEAR(c.eye.z(), 0.0, kTol);
}

TEST(Navigation, OrbitStopsShortOfThePoles) {
  const Camera c = orbit(frontCamera(), 0, 200);
  expectValid(c);
  const double elevation = std::asin((c.eye - c.target).normalized().y()) * 180.0 / M_PI;
  EXPECT_NEAR(elevation, 89.0, 1e-6);
}

TEST(Navigation, PanMovesThePointAtTheTargetDepthWithTheMouse) {
  const Camera c0 = frontCamera();
  const Eigen::Vector2d before = project(c0, kW, kH, Eigen::Vector3d(0.3, 0.2, 0)).pixel;
  const Camera c = pan(c0, Eigen::Vector2d(25, -40), kW, kH);
  expectValid(c);
  const Eigen::Vector2d after = project(c, kW, kH, Eigen::Vector3d(0.3, 0.2, 0)).pixel;
  EXPECT_NEAR(after.x() - before.x(), 25.0, 1e-6);
  EXPECT_NEAR(after.y() - before.y(), -40.0, 1e-6);
}

TEST(Navigation, DollyScalesTheDistanceOrTheOrthoHeight) {
  EXPECT_NEAR((dolly(frontCamera(), 0.5).eye - Eigen::Vector3d::Zero()).norm(), 2.5, kTol);
  Camera ortho = frontCamera();
  ortho.ortho_height = 2.0;
  EXPECT_NEAR(dolly(ortho, 1.5).ortho_height, 3.0, kTol);
  EXPECT_NEAR(dolly(frontCamera(), -1).eye.z(), 5.0, kTol);  // a bad factor changes nothing
}

TEST(Navigation, RollTurnsThePictureCounterClockwise) {
  const Camera c = roll(frontCamera(), 90);
  expectValid(c);
  // A point right of the centre appears above it after a counter-clockwise quarter turn.
  const Eigen::Vector2d p = project(c, kW, kH, Eigen::Vector3d(1, 0, 0)).pixel;
  EXPECT_NEAR(p.x(), kW / 2.0, 1e-6);
  EXPECT_LT(p.y(), kH / 2.0 - 10);
}

TEST(Navigation, FrameBoxFitsEveryCornerInTheImage) {
  for (const bool ortho : {false, true}) {
    Camera c = orbit(frontCamera(), 30, 20);
    if (ortho) c.ortho_height = 0.1;
    const Eigen::Vector3d lo(-1, -2, -0.5), hi(3, 1, 0.5);
    const Camera f = frameBox(c, lo, hi, static_cast<double>(kW) / kH);
    expectValid(f);
    for (int i = 0; i < 8; ++i) {
      const Eigen::Vector3d corner((i & 1) ? hi.x() : lo.x(), (i & 2) ? hi.y() : lo.y(), (i & 4) ? hi.z() : lo.z());
      const Eigen::Vector2d px = project(f, kW, kH, corner).pixel;
      EXPECT_GE(px.x(), 0);
      EXPECT_LE(px.x(), kW);
      EXPECT_GE(px.y(), 0);
      EXPECT_LE(px.y(), kH);
    }
  }
}

TEST(Navigation, NormalizedCameraRepairsAnUpAlongTheView) {
  Camera c = frontCamera();
  c.up = {0, 0, 1};
  expectValid(normalizedCamera(c));
}

}  // namespace
}  // namespace vdg::studio
