// Silhouette edge detection, Rademacher 99 section 3.2.4 (after Raskar and Cohen 99): only the
// faces adjacent to an edge whose two faces differ in facing are drawn in the silhouette pass.
#include "vdg/render/silhouette.h"

#include <algorithm>
#include <utility>

#include <Eigen/Geometry>

namespace vdg::render {

EdgeTopology buildEdgeTopology(std::span<const std::int32_t> triangles, std::size_t vertex_count) {
  (void)vertex_count;
  struct HalfEdge {
    std::uint64_t key;  // (min vertex << 32) | max vertex
    std::int32_t face;
  };
  std::vector<HalfEdge> half;
  const std::size_t faces = triangles.size() / 3;
  half.reserve(faces * 3);
  for (std::size_t f = 0; f < faces; ++f) {
    for (int c = 0; c < 3; ++c) {
      auto a = static_cast<std::uint32_t>(triangles[f * 3 + c]);
      auto b = static_cast<std::uint32_t>(triangles[f * 3 + (c + 1) % 3]);
      if (a > b) std::swap(a, b);
      half.push_back({(std::uint64_t{a} << 32) | b, static_cast<std::int32_t>(f)});
    }
  }
  std::sort(half.begin(), half.end(),
            [](const HalfEdge& x, const HalfEdge& y) { return x.key != y.key ? x.key < y.key : x.face < y.face; });
  EdgeTopology t;
  for (std::size_t i = 0; i < half.size();) {
    std::size_t j = i + 1;
    while (j < half.size() && half[j].key == half[i].key) ++j;
    t.vertices.push_back(static_cast<std::int32_t>(half[i].key >> 32));
    t.vertices.push_back(static_cast<std::int32_t>(half[i].key & 0xffffffffu));
    t.faces.push_back(half[i].face);
    t.faces.push_back(j - i >= 2 ? half[i + 1].face : -1);
    i = j;
  }
  return t;
}

void faceFacing(std::span<const float> positions, std::span<const std::int32_t> triangles, const Eigen::Vector3f& eye,
                std::span<std::uint8_t> front) {
  const std::size_t faces = triangles.size() / 3;
  for (std::size_t f = 0; f < faces; ++f) {
    const float* a = &positions[static_cast<std::size_t>(triangles[f * 3]) * 3];
    const float* b = &positions[static_cast<std::size_t>(triangles[f * 3 + 1]) * 3];
    const float* c = &positions[static_cast<std::size_t>(triangles[f * 3 + 2]) * 3];
    const Eigen::Vector3f va(a[0], a[1], a[2]);
    const Eigen::Vector3f n = (Eigen::Vector3f(b[0], b[1], b[2]) - va).cross(Eigen::Vector3f(c[0], c[1], c[2]) - va);
    front[f] = n.dot(eye - va) > 0.0f ? 1 : 0;
  }
}

void silhouetteEdges(const EdgeTopology& topology, std::span<const std::uint8_t> front,
                     std::vector<std::uint32_t>& out) {
  out.clear();
  const std::size_t edges = topology.edgeCount();
  for (std::size_t e = 0; e < edges; ++e) {
    const std::int32_t f0 = topology.faces[e * 2], f1 = topology.faces[e * 2 + 1];
    if (f1 >= 0 && front[f0] == front[f1]) continue;
    out.push_back(static_cast<std::uint32_t>(topology.vertices[e * 2]));
    out.push_back(static_cast<std::uint32_t>(topology.vertices[e * 2 + 1]));
  }
}

}  // namespace vdg::render
