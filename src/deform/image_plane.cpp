// Image-plane deformation tools: Rademacher 99, section 3.1.2 (drag parallel to the image plane
// keeping Z-distances, push/pull along Z, rotations and scalings of groups of vertices), and
// Parent 4.10 attenuated vertex displacement.
#include "vdg/deform/image_plane.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace vdg {

namespace {
Eigen::Vector3d at(std::span<const float> p, std::size_t v) { return {p[3 * v], p[3 * v + 1], p[3 * v + 2]}; }
void put(std::span<float> p, std::size_t v, const Eigen::Vector3d& x) {
  p[3 * v] = static_cast<float>(x.x());
  p[3 * v + 1] = static_cast<float>(x.y());
  p[3 * v + 2] = static_cast<float>(x.z());
}
}  // namespace

void dragInImagePlane(const Camera& camera, std::span<float> positions, std::span<const double> weights,
                      const Eigen::Vector2d& delta) {
  const CameraFrame f = cameraFrame(camera);
  const Eigen::Vector3d move = delta.x() * f.right + delta.y() * f.up;  // orthogonal to the view axis
  for (std::size_t v = 0; v < weights.size(); ++v)
    if (weights[v] != 0) put(positions, v, at(positions, v) + weights[v] * move);
}

Eigen::Vector2d imagePlaneDelta(const Camera& camera, int width, int height, double depth,
                                const Eigen::Vector2d& pixel_delta) {
  // project(): pixel = c + (x, -y) * height / (2 h), h = ortho half height or depth * tan(fov/2).
  const double half =
      camera.isOrtho() ? camera.ortho_height * 0.5 : depth * std::tan(camera.fov_deg * std::numbers::pi / 360.0);
  (void)width;
  const double world_per_pixel = 2.0 * half / height;
  return {pixel_delta.x() * world_per_pixel, -pixel_delta.y() * world_per_pixel};
}

void pushPull(const Camera& camera, std::span<float> positions, std::span<const double> weights, double amount,
              PushPullMode mode) {
  const CameraFrame f = cameraFrame(camera);
  const Eigen::Vector3d forward = -f.back;
  const bool along_ray = mode == PushPullMode::kAlongRay && !camera.isOrtho();
  for (std::size_t v = 0; v < weights.size(); ++v) {
    if (weights[v] == 0) continue;
    const Eigen::Vector3d p = at(positions, v);
    const double step = weights[v] * amount;
    const double depth = (p - camera.eye).dot(forward);
    if (along_ray && depth > 0) {
      const double new_depth = std::max(depth + step, 1e-3 * depth);
      put(positions, v, camera.eye + (p - camera.eye) * (new_depth / depth));
    } else {
      put(positions, v, p + step * forward);
    }
  }
}

void rotateInImagePlane(const Camera& camera, std::span<float> positions, std::span<const double> weights,
                        const Eigen::Vector3d& pivot, double angle_rad) {
  const CameraFrame f = cameraFrame(camera);
  for (std::size_t v = 0; v < weights.size(); ++v) {
    if (weights[v] == 0) continue;
    const Eigen::Vector3d d = at(positions, v) - pivot;
    const double x = d.dot(f.right), y = d.dot(f.up);
    const double a = weights[v] * angle_rad, c = std::cos(a), s = std::sin(a);
    const double nx = c * x - s * y, ny = s * x + c * y;
    put(positions, v, pivot + d + (nx - x) * f.right + (ny - y) * f.up);
  }
}

void scaleInImagePlane(const Camera& camera, std::span<float> positions, std::span<const double> weights,
                       const Eigen::Vector3d& pivot, const Eigen::Vector2d& factor) {
  const CameraFrame f = cameraFrame(camera);
  for (std::size_t v = 0; v < weights.size(); ++v) {
    if (weights[v] == 0) continue;
    const Eigen::Vector3d d = at(positions, v) - pivot;
    const double x = d.dot(f.right), y = d.dot(f.up);
    const double sx = 1.0 + weights[v] * (factor.x() - 1.0), sy = 1.0 + weights[v] * (factor.y() - 1.0);
    put(positions, v, pivot + d + (sx - 1.0) * x * f.right + (sy - 1.0) * y * f.up);
  }
}

void displaceVertices(std::span<float> positions, std::span<const double> weights, const Eigen::Vector3d& offset) {
  for (std::size_t v = 0; v < weights.size(); ++v)
    if (weights[v] != 0) put(positions, v, at(positions, v) + weights[v] * offset);
}

}  // namespace vdg
