// Camera alignment from correspondences (Rademacher 99, 3.1.1): DLT + Levenberg-Marquardt.
#include <gtest/gtest.h>

#include <random>

#include "vdg/deform/align.h"
#include "vdg/geom/error.h"

namespace vdg {
namespace {

constexpr int kWidth = 800, kHeight = 600;

std::vector<Eigen::Vector3d> cloud(int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<Eigen::Vector3d> pts;
  for (int i = 0; i < n; ++i) pts.emplace_back(u(rng), u(rng) * 1.5, u(rng) * 0.8);
  return pts;
}

std::vector<Eigen::Vector2d> pixelsOf(const Camera& c, const std::vector<Eigen::Vector3d>& pts, double noise,
                                      unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> g(0.0, noise);
  std::vector<Eigen::Vector2d> px;
  for (const auto& p : pts) px.push_back(project(c, kWidth, kHeight, p).pixel + Eigen::Vector2d(g(rng), g(rng)));
  return px;
}

// Two cameras are the same when their frames, eye (perspective) or in-plane eye (parallel), and
// fov / ortho height agree; compared relative to the scene size.
void expectSameCamera(const Camera& got, const Camera& want, double tol) {
  const CameraFrame a = cameraFrame(got), b = cameraFrame(want);
  EXPECT_LT((a.right - b.right).norm(), tol);
  EXPECT_LT((a.up - b.up).norm(), tol);
  EXPECT_LT((a.back - b.back).norm(), tol);
  const double scale = (want.eye - want.target).norm();
  if (want.isOrtho()) {
    ASSERT_TRUE(got.isOrtho());
    EXPECT_NEAR(got.ortho_height / want.ortho_height, 1.0, tol);
    const Eigen::Vector3d d = got.eye - want.eye;
    EXPECT_LT(std::abs(d.dot(b.right)) / scale, tol);
    EXPECT_LT(std::abs(d.dot(b.up)) / scale, tol);
  } else {
    ASSERT_FALSE(got.isOrtho());
    EXPECT_NEAR(got.fov_deg / want.fov_deg, 1.0, tol);
    EXPECT_LT((got.eye - want.eye).norm() / scale, tol);
  }
}

Camera perspective() {
  Camera c;
  c.eye = {2.0, 1.2, 5.5};
  c.target = {0.2, 0.1, -0.3};
  c.up = {0.05, 1.0, 0.1};
  c.fov_deg = 38;
  return c;
}
Camera parallel() {
  Camera c = perspective();
  c.ortho_height = 3.5;
  c.fov_deg = 0;
  return c;
}

TEST(Align, ExactPerspectiveRecovered) {
  const auto pts = cloud(12, 1);
  const Camera truth = perspective();
  const AlignResult r = alignCamera(pts, pixelsOf(truth, pts, 0.0, 0), kWidth, kHeight);
  expectSameCamera(r.camera, truth, 1e-6);
  EXPECT_LT(r.rms_px, 1e-6);
}

TEST(Align, ExactParallelRecovered) {
  const auto pts = cloud(10, 2);
  const Camera truth = parallel();
  const AlignResult r = alignCamera(pts, pixelsOf(truth, pts, 0.0, 0), kWidth, kHeight, {.ortho = true});
  expectSameCamera(r.camera, truth, 1e-6);
  EXPECT_LT(r.rms_px, 1e-6);
}

TEST(Align, NoisyCorrespondencesGiveCloseCameraAndNoiseLevelRms) {
  constexpr double kNoisePx = 0.5;
  const auto pts = cloud(40, 3);
  for (const bool ortho : {false, true}) {
    const Camera truth = ortho ? parallel() : perspective();
    const auto px = pixelsOf(truth, pts, kNoisePx, 7);
    const AlignResult r = alignCamera(pts, px, kWidth, kHeight, {.ortho = ortho});
    expectSameCamera(r.camera, truth, 0.02);
    EXPECT_LT(r.rms_px, 1.5 * kNoisePx);
    EXPECT_GT(r.rms_px, 0.3 * kNoisePx);
    EXPECT_LE(r.rms_px, r.dlt_rms_px + 1e-9);  // refinement never makes it worse
    // The truth is no better than the solution: it is a least-squares minimum.
    double truth_sum = 0;
    for (double e : reprojectionErrors(truth, pts, px, kWidth, kHeight)) truth_sum += e * e;
    EXPECT_LE(r.rms_px, std::sqrt(truth_sum / pts.size()) + 1e-9);
  }
}

TEST(Align, DegenerateInputsAreClearErrors) {
  const Camera truth = perspective();
  auto pts = cloud(5, 4);
  auto expectError = [&](const std::vector<Eigen::Vector3d>& p, const std::string& word, bool ortho = false) {
    try {
      alignCamera(p, pixelsOf(truth, p, 0.0, 0), kWidth, kHeight, {.ortho = ortho});
      FAIL() << "expected an error containing '" << word << "'";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(word), std::string::npos) << e.what();
    }
  };
  expectError(pts, "at least 6");
  std::vector<Eigen::Vector3d> line, plane;
  for (int i = 0; i < 8; ++i) {
    line.emplace_back(0.1 * i, 0.2 * i, -0.05 * i);
    plane.emplace_back(0.1 * i, 0.3 * ((i * 7) % 5), 0.0);
  }
  expectError(line, "collinear");
  expectError(plane, "coplanar");
  expectError(plane, "coplanar", true);
  EXPECT_THROW(alignCamera(cloud(8, 5), pixelsOf(truth, cloud(7, 5), 0, 0), kWidth, kHeight), Error);
}

}  // namespace
}  // namespace vdg
