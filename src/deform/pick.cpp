// Vertices named by a point or a pixel (vdg/deform/pick.h). The ray-triangle test is Moller and
// Trumbore's ("Fast, minimum storage ray-triangle intersection", JGT 1997).
#include "vdg/deform/pick.h"

#include <Eigen/Geometry>
#include <cmath>
#include <limits>

namespace vdg {
namespace {

Eigen::Vector3d vertexOf(std::span<const float> p, std::int32_t v) {
  const auto i = static_cast<std::size_t>(v);
  return {p[3 * i], p[3 * i + 1], p[3 * i + 2]};
}

}  // namespace

std::optional<std::int32_t> nearestVertex(std::span<const float> positions, const Eigen::Vector3d& point) {
  if (!point.allFinite()) return std::nullopt;
  std::optional<std::int32_t> best;
  double best_d2 = std::numeric_limits<double>::infinity();
  for (std::size_t v = 0; v < positions.size() / 3; ++v) {
    const double d2 = (vertexOf(positions, static_cast<std::int32_t>(v)) - point).squaredNorm();
    if (d2 < best_d2) best_d2 = d2, best = static_cast<std::int32_t>(v);
  }
  return best;
}

std::optional<std::int32_t> vertexAtPixel(std::span<const float> positions, std::span<const std::int32_t> triangles,
                                          const Camera& camera, int width, int height, const Eigen::Vector2d& pixel) {
  if (!pixel.allFinite()) return std::nullopt;
  // The ray through the pixel: from view depth 0 (the eye, or the eye plane of a parallel camera).
  const Eigen::Vector3d a = unproject(camera, width, height, pixel, 1.0);
  const Eigen::Vector3d b = unproject(camera, width, height, pixel, 2.0);
  const Eigen::Vector3d dir = b - a;
  const Eigen::Vector3d origin = a - dir;
  double best_t = std::numeric_limits<double>::infinity();
  std::size_t best_face = triangles.size();
  Eigen::Vector3d best_hit = Eigen::Vector3d::Zero();
  for (std::size_t f = 0; f + 2 < triangles.size(); f += 3) {
    const Eigen::Vector3d v0 = vertexOf(positions, triangles[f]), v1 = vertexOf(positions, triangles[f + 1]),
                          v2 = vertexOf(positions, triangles[f + 2]);
    const Eigen::Vector3d e1 = v1 - v0, e2 = v2 - v0;
    const Eigen::Vector3d q = dir.cross(e2);
    const double det = e1.dot(q);
    if (!(det > 0)) continue;  // back-facing, edge-on or not finite (a front face has det > 0)
    const double inv = 1.0 / det;
    const Eigen::Vector3d s = origin - v0;
    const double u = s.dot(q) * inv;
    if (u < 0 || u > 1) continue;
    const Eigen::Vector3d r = s.cross(e1);
    const double v = dir.dot(r) * inv;
    if (v < 0 || u + v > 1) continue;
    const double t = e2.dot(r) * inv;
    if (t > 0 && t < best_t) best_t = t, best_face = f, best_hit = origin + t * dir;
  }
  if (best_face == triangles.size()) return std::nullopt;
  std::int32_t best = triangles[best_face];
  for (std::size_t k = 1; k < 3; ++k)
    if ((vertexOf(positions, triangles[best_face + k]) - best_hit).squaredNorm() <
        (vertexOf(positions, best) - best_hit).squaredNorm())
      best = triangles[best_face + k];
  return best;
}

}  // namespace vdg
