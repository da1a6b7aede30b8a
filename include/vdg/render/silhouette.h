// Silhouette edges of a triangle mesh seen from an eye point (Rademacher 99, section 3.2.4, after
// Raskar and Cohen 99): an edge is on the silhouette when one of its two faces is front-facing and
// the other back-facing. Edges with a single face (open boundaries) are always drawn.
//
// The edge topology depends only on the triangles and is built once per mesh; the per-frame query
// reads positions and writes into caller-owned buffers (no allocation once they have grown).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include <Eigen/Core>

namespace vdg::render {

// Unique undirected edges of a triangle list: edge e joins vertices[2e], vertices[2e+1] and
// borders faces[2e] and faces[2e+1] (-1 when the edge has one face). On a non-manifold edge
// (three or more faces) the first two faces are kept.
struct EdgeTopology {
  std::vector<std::int32_t> vertices;  // #E x 2
  std::vector<std::int32_t> faces;     // #E x 2
  std::size_t edgeCount() const { return vertices.size() / 2; }
};
EdgeTopology buildEdgeTopology(std::span<const std::int32_t> triangles, std::size_t vertex_count);

// Facing of each triangle for an eye point (model space; for a parallel camera pass a point far
// along the view axis): front when (eye - v0) . ((v1 - v0) x (v2 - v0)) > 0.
// `front` must hold #F entries.
void faceFacing(std::span<const float> positions, std::span<const std::int32_t> triangles, const Eigen::Vector3f& eye,
                std::span<std::uint8_t> front);

// Appends the two vertex indices of every silhouette edge to `out` (cleared first).
void silhouetteEdges(const EdgeTopology& topology, std::span<const std::uint8_t> front,
                     std::vector<std::uint32_t>& out);

}  // namespace vdg::render
