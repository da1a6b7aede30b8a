// Camera navigation of vdg studio (see vdg/studio/navigation.h).
#include "vdg/studio/navigation.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <Eigen/Geometry>

namespace vdg::studio {
namespace {

constexpr double kDegToRad = std::numbers::pi / 180.0;
// Orbit keeps the view this far from the poles, so up never becomes parallel to the view axis.
constexpr double kMaxElevationDeg = 89.0;
// The smallest eye-target distance or ortho height dolly() gives, against collapsing the camera.
constexpr double kMinExtent = 1e-9;

}  // namespace

Camera normalizedCamera(const Camera& camera) {
  Camera c = camera;
  Eigen::Vector3d axis = c.target - c.eye;
  if (!(axis.norm() > 0)) axis = Eigen::Vector3d(0, 0, -1), c.target = c.eye + axis;
  axis.normalize();
  Eigen::Vector3d up = c.up - c.up.dot(axis) * axis;
  if (!(up.norm() > 1e-9)) {
    const Eigen::Vector3d fallback = std::abs(axis.y()) < 0.99 ? Eigen::Vector3d::UnitY() : Eigen::Vector3d::UnitZ();
    up = fallback - fallback.dot(axis) * axis;
  }
  c.up = up.normalized();
  return c;
}

Camera orbit(const Camera& camera, double yaw_deg, double pitch_deg) {
  Camera c = normalizedCamera(camera);
  const Eigen::Vector3d offset = c.eye - c.target;
  const double distance = offset.norm();
  const Eigen::Vector3d dir = offset / distance;
  // Elevation of the eye above the XZ plane, clamped after the pitch.
  const double elevation = std::asin(std::clamp(dir.y(), -1.0, 1.0)) / kDegToRad;
  const double new_elevation = std::clamp(elevation + pitch_deg, -kMaxElevationDeg, kMaxElevationDeg);
  const Eigen::Vector3d right = cameraFrame(c).right;
  const Eigen::AngleAxisd pitch((new_elevation - elevation) * kDegToRad, -right);
  const Eigen::AngleAxisd yaw(yaw_deg * kDegToRad, Eigen::Vector3d::UnitY());
  const Eigen::Matrix3d r = (yaw * pitch).toRotationMatrix();
  c.eye = c.target + r * offset;
  c.up = r * c.up;
  return normalizedCamera(c);
}

Camera pan(const Camera& camera, const Eigen::Vector2d& pixels, int width, int height) {
  Camera c = normalizedCamera(camera);
  const double depth = (c.target - c.eye).norm();
  // The world motion that moves a point at the target's depth by `pixels`; the scene follows the
  // mouse, so the camera moves the other way.
  const Eigen::Vector3d a = unproject(c, width, height, Eigen::Vector2d(0, 0), depth);
  const Eigen::Vector3d b = unproject(c, width, height, pixels, depth);
  const Eigen::Vector3d shift = a - b;
  c.eye += shift;
  c.target += shift;
  return c;
}

Camera dolly(const Camera& camera, double factor) {
  Camera c = normalizedCamera(camera);
  if (!(factor > 0) || !std::isfinite(factor)) return c;
  if (c.isOrtho()) {
    c.ortho_height = std::max(c.ortho_height * factor, kMinExtent);
    return c;
  }
  const Eigen::Vector3d offset = c.eye - c.target;
  const double distance = std::max(offset.norm() * factor, kMinExtent);
  c.eye = c.target + offset.normalized() * distance;
  return c;
}

Camera roll(const Camera& camera, double deg) {
  Camera c = normalizedCamera(camera);
  // Counter-clockwise in the image: rotating the camera's up clockwise about the view axis seen
  // from the eye turns the picture counter-clockwise.
  const Eigen::Vector3d back = (c.eye - c.target).normalized();
  c.up = Eigen::AngleAxisd(-deg * kDegToRad, back) * c.up;
  return normalizedCamera(c);
}

Camera frameBox(const Camera& camera, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, double aspect) {
  Camera c = normalizedCamera(camera);
  const Eigen::Vector3d center = 0.5 * (lo + hi);
  const double radius = std::max(0.5 * (hi - lo).norm(), kMinExtent);
  const double margin = 1.1;
  const Eigen::Vector3d back = (c.eye - c.target).normalized();
  c.target = center;
  if (c.isOrtho()) {
    c.ortho_height = 2.0 * radius * margin / std::min(1.0, aspect > 0 ? aspect : 1.0);
    c.eye = center + back * (4.0 * radius);
    return c;
  }
  const double half_v = 0.5 * c.fov_deg * kDegToRad;
  const double half_h = std::atan(std::tan(half_v) * (aspect > 0 ? aspect : 1.0));
  const double distance = radius * margin / std::sin(std::min(half_v, half_h));
  c.eye = center + back * distance;
  return c;
}

}  // namespace vdg::studio
