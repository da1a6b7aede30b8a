#include "vdg/geom/camera.h"

#include <gtest/gtest.h>

#include "vdg/geom/error.h"

namespace vdg {
namespace {

constexpr double kTol = 1e-9;

TEST(Camera, ProjectUnprojectRoundTrip) {
  for (const double ortho : {0.0, 3.0}) {
    Camera c;
    c.eye = {1, 2, 6};
    c.target = {0.2, 0.1, 0};
    c.ortho_height = ortho;
    const Eigen::Vector3d p(0.3, -0.4, 0.5);
    const Projected pr = project(c, 640, 480, p);
    const Eigen::Vector3d back = unproject(c, 640, 480, pr.pixel, pr.depth);
    EXPECT_NEAR((back - p).norm(), 0.0, kTol);
  }
}

TEST(Camera, TargetProjectsToTheImageCentre) {
  Camera c;
  c.eye = {3, 1, 4};
  c.target = {0.5, 0.5, 0.5};
  const Projected pr = project(c, 200, 100, c.target);
  EXPECT_NEAR(pr.pixel.x(), 100.0, kTol);
  EXPECT_NEAR(pr.pixel.y(), 50.0, kTol);
  EXPECT_NEAR(pr.depth, (c.eye - c.target).norm(), kTol);
}

TEST(Camera, MatricesAgreeWithProject) {
  Camera c;
  c.eye = {0, 0, 5};
  const Eigen::Vector4d world(0.5, 0.25, 0, 1);
  const Eigen::Vector4d clip = projectionMatrix(c, 2.0, 0.1, 100.0) * viewMatrix(c) * world;
  const Projected pr = project(c, 200, 100, world.head<3>());
  const double ndc_x = clip.x() / clip.w(), ndc_y = clip.y() / clip.w();
  EXPECT_NEAR((ndc_x + 1) * 100.0, pr.pixel.x(), 1e-9);
  EXPECT_NEAR((1 - ndc_y) * 50.0, pr.pixel.y(), 1e-9);
}

TEST(Camera, DegenerateFrameIsAnError) {
  Camera c;
  c.eye = c.target;
  EXPECT_THROW(cameraFrame(c), Error);
  c.eye = {0, 5, 0};
  c.target = {0, 0, 0};
  c.up = {0, 1, 0};
  EXPECT_THROW(cameraFrame(c), Error);
}

}  // namespace
}  // namespace vdg
