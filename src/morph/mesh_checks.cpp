// Closedness and Euler characteristic of triangle meshes (vdg/morph/mesh_checks.h).
#include "vdg/morph/mesh_checks.h"

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <string>
#include <utility>
#include <vector>

#include "vdg/geom/error.h"

namespace vdg::morph {
namespace {

// Directed edges (from, to), sorted: an undirected edge {i, j} of a closed, consistently oriented
// mesh appears exactly once as (i, j) and once as (j, i).
std::vector<std::pair<std::int32_t, std::int32_t>> directedEdges(const TriMesh& mesh) {
  std::vector<std::pair<std::int32_t, std::int32_t>> edges;
  edges.reserve(mesh.triangles.size());
  for (std::size_t f = 0; f < mesh.triangleCount(); ++f)
    for (int k = 0; k < 3; ++k) edges.emplace_back(mesh.triangles[f * 3 + k], mesh.triangles[f * 3 + (k + 1) % 3]);
  std::sort(edges.begin(), edges.end());
  return edges;
}

}  // namespace

void requireClosed(const TriMesh& mesh, const std::string& what) {
  if (mesh.triangleCount() == 0) throw Error(what + ": has no triangles");
  const auto vertex_count = static_cast<std::int64_t>(mesh.vertexCount());
  for (std::size_t f = 0; f < mesh.triangleCount(); ++f) {
    const std::int32_t* t = &mesh.triangles[f * 3];
    for (int k = 0; k < 3; ++k)
      if (t[k] < 0 || t[k] >= vertex_count)
        throw Error(what + ": triangle " + std::to_string(f) + " names vertex " + std::to_string(t[k]) +
                    ", which does not exist");
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2])
      throw Error(what + ": triangle " + std::to_string(f) + " is degenerate (a vertex repeats)");
  }
  const auto edges = directedEdges(mesh);
  for (std::size_t i = 0; i < edges.size(); ++i) {
    const auto [a, b] = edges[i];
    const std::string edge = "edge (" + std::to_string(a) + ", " + std::to_string(b) + ")";
    if (i + 1 < edges.size() && edges[i + 1] == edges[i])
      throw Error(what + ": is not closed and consistently oriented: " + edge + " is used twice in the same direction");
    const auto twins = std::equal_range(edges.begin(), edges.end(), std::make_pair(b, a));
    if (twins.first == twins.second)
      throw Error(what + ": is not closed: " + edge + " borders a hole (one triangle only)");
  }
}

int eulerCharacteristic(const TriMesh& mesh) {
  std::vector<char> used(mesh.vertexCount(), 0);
  for (const std::int32_t v : mesh.triangles) used[static_cast<std::size_t>(v)] = 1;
  const auto vertices = static_cast<int>(std::count(used.begin(), used.end(), 1));
  const auto faces = static_cast<int>(mesh.triangleCount());
  const int edges = faces * 3 / 2;  // closed: every edge is shared by two triangles
  return vertices - edges + faces;
}

}  // namespace vdg::morph
