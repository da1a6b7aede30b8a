#include "vdg/geom/camera.h"

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>

#include "vdg/geom/error.h"
#include "vdg/geom/normalize.h"

namespace vdg {

CameraFrame cameraFrame(const Camera& camera) {
  // Normalised robustly (vdg/geom/normalize.h): a far eye (1e200) or a huge or tiny up vector
  // still gives the right frame; only zero and non-finite directions are errors.
  const Eigen::Vector3d back_raw = camera.eye - camera.target;
  if (!back_raw.allFinite())
    throw Error("camera: eye or target is not finite, or too far apart to represent eye - target");
  const std::optional<Eigen::Vector3d> back = normalizedOrNone(back_raw);
  if (!back) throw Error("camera: eye and target are the same point");
  const std::optional<Eigen::Vector3d> up = normalizedOrNone(camera.up);
  if (!up) throw Error("camera: up vector is zero or not finite");
  const Eigen::Vector3d right_raw = up->cross(*back);
  if (!(right_raw.norm() > 1e-12)) throw Error("camera: up vector is parallel to the viewing direction");
  const Eigen::Vector3d right = right_raw.normalized();  // length in (1e-12, 1]: no overflow
  return {right, back->cross(right), *back};
}

Eigen::Matrix4d viewMatrix(const Camera& camera) {
  const CameraFrame f = cameraFrame(camera);
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  m.block<1, 3>(0, 0) = f.right.transpose();
  m.block<1, 3>(1, 0) = f.up.transpose();
  m.block<1, 3>(2, 0) = f.back.transpose();
  m(0, 3) = -f.right.dot(camera.eye);
  m(1, 3) = -f.up.dot(camera.eye);
  m(2, 3) = -f.back.dot(camera.eye);
  return m;
}

Eigen::Matrix4d projectionMatrix(const Camera& camera, double aspect, double z_near, double z_far) {
  Eigen::Matrix4d p = Eigen::Matrix4d::Zero();
  if (camera.isOrtho()) {
    const double h = camera.ortho_height * 0.5, w = h * aspect;
    p(0, 0) = 1.0 / w;
    p(1, 1) = 1.0 / h;
    p(2, 2) = -2.0 / (z_far - z_near);
    p(2, 3) = -(z_far + z_near) / (z_far - z_near);
    p(3, 3) = 1.0;
  } else {
    const double f = 1.0 / std::tan(camera.fov_deg * std::numbers::pi / 360.0);
    p(0, 0) = f / aspect;
    p(1, 1) = f;
    p(2, 2) = (z_far + z_near) / (z_near - z_far);
    p(2, 3) = 2.0 * z_far * z_near / (z_near - z_far);
    p(3, 2) = -1.0;
  }
  return p;
}

namespace {
// Half extents of the image plane at unit depth (perspective) or absolute (ortho).
Eigen::Vector2d halfExtent(const Camera& camera, int width, int height) {
  const double aspect = static_cast<double>(width) / height;
  const double h = camera.isOrtho() ? camera.ortho_height * 0.5 : std::tan(camera.fov_deg * std::numbers::pi / 360.0);
  return {h * aspect, h};
}
}  // namespace

Projected project(const Camera& camera, int width, int height, const Eigen::Vector3d& world) {
  const CameraFrame f = cameraFrame(camera);
  const Eigen::Vector3d d = world - camera.eye;
  const double x = d.dot(f.right), y = d.dot(f.up), depth = -d.dot(f.back);
  const Eigen::Vector2d half = halfExtent(camera, width, height);
  const double scale = camera.isOrtho() ? 1.0 : 1.0 / depth;
  const double nx = x * scale / half.x(), ny = y * scale / half.y();  // in [-1, 1] inside the image
  return {{(nx + 1.0) * 0.5 * width, (1.0 - ny) * 0.5 * height}, depth};
}

Eigen::Vector3d unproject(const Camera& camera, int width, int height, const Eigen::Vector2d& pixel, double depth) {
  const CameraFrame f = cameraFrame(camera);
  const Eigen::Vector2d half = halfExtent(camera, width, height);
  const double nx = pixel.x() / width * 2.0 - 1.0, ny = 1.0 - pixel.y() / height * 2.0;
  const double scale = camera.isOrtho() ? 1.0 : depth;
  return camera.eye + f.right * (nx * half.x() * scale) + f.up * (ny * half.y() * scale) - f.back * depth;
}

}  // namespace vdg
