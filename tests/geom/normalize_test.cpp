#include "vdg/geom/normalize.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "support/test_meshes.h"
#include "vdg/geom/camera.h"
#include "vdg/geom/error.h"
#include "vdg/geom/tri_mesh.h"

namespace vdg {
namespace {

constexpr double kUnitTol = 1e-15;     // a normalised vector's length, and its components
constexpr double kRelNormTol = 1e-15;  // robustNorm against the exact length
constexpr float kNormalTol = 1e-5f;
constexpr double kFrameTol = 1e-12;

TEST(Normalize, AnyFiniteMagnitudeGivesTheSameUnitVector) {
  const Eigen::Vector3d dir(3, -4, 12);  // length 13
  const Eigen::Vector3d expected = dir / 13.0;
  for (const double scale : {1.0, 1e155, 1e200, 1e300, 1e-155, 1e-200, 1e-300, 4e-320}) {
    const auto u = normalizedOrNone(Eigen::Vector3d(dir * scale));
    ASSERT_TRUE(u.has_value()) << "scale " << scale;
    EXPECT_NEAR(u->norm(), 1.0, kUnitTol) << "scale " << scale;
    EXPECT_NEAR((*u - expected).norm(), 0.0, 1e3 * kUnitTol) << "scale " << scale;
  }
  // The plain formula really does fail at these sizes (so the test above can fail).
  EXPECT_FALSE(Eigen::Vector3d(dir * 1e200).normalized().norm() > 0.5);
}

TEST(Normalize, ZeroAndNonFiniteVectorsAreReported) {
  const double inf = std::numeric_limits<double>::infinity();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(normalizedOrNone(Eigen::Vector3d::Zero()).has_value());
  EXPECT_FALSE(normalizedOrNone(Eigen::Vector3d(inf, 0, 0)).has_value());
  EXPECT_FALSE(normalizedOrNone(Eigen::Vector3d(1, nan, 0)).has_value());
  EXPECT_FALSE(normalizedOrNone(Eigen::Quaterniond(0, 0, 0, 0)).has_value());
  EXPECT_FALSE(normalizedOrNone(Eigen::Quaterniond(nan, 0, 0, 1)).has_value());
}

TEST(Normalize, RobustNormIsExactAcrossTheRange) {
  for (const double scale : {1.0, 1e200, 1e-200}) {
    const std::vector<double> v = {3 * scale, 4 * scale};
    EXPECT_NEAR(robustNorm(v) / (5 * scale), 1.0, kRelNormTol) << "scale " << scale;
  }
  EXPECT_EQ(robustNorm(Eigen::Vector3d::Zero()), 0.0);
  EXPECT_TRUE(std::isinf(robustNorm(Eigen::Vector3d(1.5e308, 1.5e308, 0))));  // beyond the double range
  EXPECT_TRUE(std::isnan(robustNorm(Eigen::Vector3d(std::nan(""), 1, 1))));
}

TEST(Normalize, HugeAndTinyQuaternionsKeepTheirRotation) {
  const Eigen::Quaterniond unit(Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()));
  for (const double scale : {1e200, 1e-200}) {
    const auto q = normalizedOrNone(Eigen::Quaterniond(unit.coeffs() * scale));
    ASSERT_TRUE(q.has_value());
    EXPECT_NEAR((q->coeffs() - unit.coeffs()).norm(), 0.0, 1e3 * kUnitTol) << "scale " << scale;
  }
}

TEST(Camera, FarEyeAndHugeUpStillGiveTheRightFrame) {
  Camera near_cam;
  near_cam.eye = {1, 2, 3};
  near_cam.target = {0, 0, 0};
  const CameraFrame expected = cameraFrame(near_cam);
  Camera far_cam = near_cam;
  far_cam.eye *= 1e200;
  far_cam.up *= 1e300;
  const CameraFrame f = cameraFrame(far_cam);
  EXPECT_NEAR((f.back - expected.back).norm(), 0.0, kFrameTol);
  EXPECT_NEAR((f.up - expected.up).norm(), 0.0, kFrameTol);
  EXPECT_NEAR((f.right - expected.right).norm(), 0.0, kFrameTol);
  Camera tiny_up = near_cam;
  tiny_up.up *= 1e-300;
  EXPECT_NEAR((cameraFrame(tiny_up).up - expected.up).norm(), 0.0, kFrameTol);
}

TEST(Camera, NonFiniteOrOverflowingFrameIsAnError) {
  Camera c;
  c.eye = {1e308, 0, 0};
  c.target = {-1e308, 0, 0};  // eye - target overflows
  EXPECT_THROW(cameraFrame(c), Error);
  c = Camera{};
  c.up = Eigen::Vector3d::Zero();
  EXPECT_THROW(cameraFrame(c), Error);
}

// Normals are the same directions whatever the mesh's scale, including far beyond the range in
// which float cross products of the edges stay finite.
TEST(TriMesh, NormalsOfHugeAndTinyMeshesAreUnitAndUnchanged) {
  const TriMesh m = testing::uvSphere(8, 12);
  std::vector<float> expected(m.positions.size());
  computeVertexNormals(m.positions, m.triangles, expected);
  for (const float scale : {1e25f, 1e38f, 1e-25f}) {
    TriMesh scaled = m;
    for (float& p : scaled.positions) p *= scale;
    std::vector<float> n(m.positions.size());
    computeVertexNormals(scaled.positions, scaled.triangles, n);
    for (std::size_t i = 0; i < n.size(); ++i) {
      ASSERT_TRUE(std::isfinite(n[i])) << "scale " << scale << " component " << i;
      EXPECT_NEAR(n[i], expected[i], kNormalTol) << "scale " << scale << " component " << i;
    }
  }
}

TEST(TriMesh, DiagonalOfAHugeMeshIsFinite) {
  const std::vector<float> positions = {-1e20f, 0, 0, 1e20f, 0, 0};
  EXPECT_NEAR(computeBounds(positions).diagonal() / 2e20f, 1.0f, 1e-6f);
}

}  // namespace
}  // namespace vdg
