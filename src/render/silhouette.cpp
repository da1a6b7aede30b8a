// Silhouette edge detection, Rademacher 99 section 3.2.4 (after Raskar and Cohen 99): only the
// edges whose two faces differ in facing are drawn in the silhouette pass. The edges are those of
// the welded surface (SurfaceTopology), so texture and normal seams are not mistaken for borders.
#include "vdg/render/silhouette.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <Eigen/Geometry>

namespace vdg::render {
namespace {

Eigen::Vector3f vertexAt(std::span<const float> positions, std::int32_t v) {
  const float* p = &positions[static_cast<std::size_t>(v) * 3];
  return {p[0], p[1], p[2]};
}

// (v1 - v0) x (v2 - v0) of triangle f: the unnormalised normal (length twice the area).
Eigen::Vector3f faceCross(std::span<const float> positions, std::span<const std::int32_t> triangles, std::size_t f) {
  const Eigen::Vector3f a = vertexAt(positions, triangles[f * 3]);
  return (vertexAt(positions, triangles[f * 3 + 1]) - a).cross(vertexAt(positions, triangles[f * 3 + 2]) - a);
}

}  // namespace

void faceFacing(std::span<const float> positions, std::span<const std::int32_t> triangles, const Eigen::Vector3f& eye,
                std::span<std::uint8_t> front) {
  const std::size_t faces = triangles.size() / 3;
  for (std::size_t f = 0; f < faces; ++f) {
    const Eigen::Vector3f n = faceCross(positions, triangles, f);
    front[f] = n.dot(eye - vertexAt(positions, triangles[f * 3])) > 0.0f ? 1 : 0;
  }
}

void silhouetteEdges(const SurfaceTopology& topology, std::span<const std::uint8_t> front, bool borders,
                     std::vector<std::uint32_t>& out) {
  out.clear();
  const auto vertices = topology.edgeVertices();
  const auto faces = topology.edgeFaces();
  const std::size_t edges = topology.edgeCount();
  for (std::size_t e = 0; e < edges; ++e) {
    const std::int32_t f0 = faces[e * 2], f1 = faces[e * 2 + 1];
    if (f1 < 0 ? !borders : front[static_cast<std::size_t>(f0)] == front[static_cast<std::size_t>(f1)]) continue;
    out.push_back(static_cast<std::uint32_t>(vertices[e * 2]));
    out.push_back(static_cast<std::uint32_t>(vertices[e * 2 + 1]));
  }
}

void creaseEdges(const SurfaceTopology& topology, std::span<const float> positions, std::span<const std::uint8_t> front,
                 double crease_angle_deg, std::vector<std::uint32_t>& out) {
  out.clear();
  if (!std::isfinite(crease_angle_deg) || crease_angle_deg <= 0.0) return;
  // The angle between the normals exceeds the threshold when n0 . n1 < cos(threshold) |n0| |n1|.
  const auto cos_limit = static_cast<float>(std::cos(std::min(crease_angle_deg, 180.0) * std::numbers::pi / 180.0));
  const auto triangles = topology.triangles();
  const auto vertices = topology.edgeVertices();
  const auto faces = topology.edgeFaces();
  const std::size_t edges = topology.edgeCount();
  for (std::size_t e = 0; e < edges; ++e) {
    const std::int32_t f0 = faces[e * 2], f1 = faces[e * 2 + 1];
    if (f1 < 0 || !front[static_cast<std::size_t>(f0)] || !front[static_cast<std::size_t>(f1)]) continue;
    const Eigen::Vector3f n0 = faceCross(positions, triangles, static_cast<std::size_t>(f0));
    const Eigen::Vector3f n1 = faceCross(positions, triangles, static_cast<std::size_t>(f1));
    const float scale = n0.norm() * n1.norm();
    if (!(scale > 0.0f) || n0.dot(n1) >= cos_limit * scale) continue;
    out.push_back(static_cast<std::uint32_t>(vertices[e * 2]));
    out.push_back(static_cast<std::uint32_t>(vertices[e * 2 + 1]));
  }
}

}  // namespace vdg::render
