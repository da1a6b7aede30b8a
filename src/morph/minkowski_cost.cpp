// The cost estimate of minkowskiMorph (vdg/morph/shape_morph.h), apart from minkowski_morph.cpp so
// that it compiles without CGAL's templates.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "d3.h"
#include "vdg/morph/shape_morph.h"

namespace vdg::morph {
namespace {

using Vec3 = detail::D3;
constexpr double kFlat = 1e-6;  // sine of the fold angle below which an edge counts as flat

Vec3 at(const TriMesh& m, std::int32_t v) {
  const auto k = static_cast<std::size_t>(v) * 3;
  return {m.positions[k], m.positions[k + 1], m.positions[k + 2]};
}
using detail::cross;
using detail::dot;
using detail::sub;

bool validIndex(const TriMesh& m, std::int32_t v) { return v >= 0 && static_cast<std::size_t>(v) < m.vertexCount(); }

}  // namespace

std::size_t reflexEdgeCount(const TriMesh& mesh) {
  const std::size_t faces = mesh.triangleCount();
  for (const std::int32_t v : mesh.triangles)
    if (!validIndex(mesh, v)) return 0;
  // Outward: the sign of the enclosed volume (the divergence theorem about the origin).
  double volume = 0;
  for (std::size_t f = 0; f < faces; ++f)
    volume += dot(at(mesh, mesh.triangles[3 * f]),
                  cross(at(mesh, mesh.triangles[3 * f + 1]), at(mesh, mesh.triangles[3 * f + 2])));
  const double outward = volume >= 0 ? 1.0 : -1.0;
  // Each directed edge (from, to) with its face; an edge's two faces meet as (a, b) and (b, a).
  struct HalfEdge {
    std::int32_t lo, hi;
    std::size_t face;
    bool operator<(const HalfEdge& o) const { return lo != o.lo ? lo < o.lo : hi != o.hi ? hi < o.hi : face < o.face; }
  };
  std::vector<HalfEdge> edges;
  edges.reserve(3 * faces);
  for (std::size_t f = 0; f < faces; ++f)
    for (int k = 0; k < 3; ++k) {
      const std::int32_t a = mesh.triangles[3 * f + k], b = mesh.triangles[3 * f + (k + 1) % 3];
      edges.push_back({std::min(a, b), std::max(a, b), f});
    }
  std::sort(edges.begin(), edges.end());
  std::size_t reflex = 0;
  for (std::size_t i = 0; i + 1 < edges.size(); ++i) {
    if (edges[i].lo != edges[i + 1].lo || edges[i].hi != edges[i + 1].hi) continue;
    const std::size_t f = edges[i].face, g = edges[i + 1].face;
    const Vec3 p0 = at(mesh, mesh.triangles[3 * f]);
    const Vec3 n = cross(sub(at(mesh, mesh.triangles[3 * f + 1]), p0), sub(at(mesh, mesh.triangles[3 * f + 2]), p0));
    // g's corner off the shared edge.
    for (int k = 0; k < 3; ++k) {
      const std::int32_t v = mesh.triangles[3 * g + k];
      if (v == edges[i].lo || v == edges[i].hi) continue;
      // In front by more than rounding (coplanar triangles, a flat face's diagonals, do not count).
      const Vec3 d = sub(at(mesh, v), p0);
      if (outward * dot(n, d) > kFlat * std::sqrt(dot(n, n) * dot(d, d))) ++reflex;
      break;
    }
    ++i;  // the pair is done
  }
  return reflex;
}

double minkowskiMorphCost(const TriMesh& a, const TriMesh& b, const MinkowskiOptions& options) {
  const double va = static_cast<double>(a.vertexCount()), vb = static_cast<double>(b.vertexCount());
  const double fa = static_cast<double>(a.triangleCount()), fb = static_cast<double>(b.triangleCount());
  double cost = 0;
  bool nef = options.path == MinkowskiPath::nef;
  if (options.path == MinkowskiPath::automatic) {
    cost += va * fa + vb * fb;  // isConvexMesh on each
    nef = reflexEdgeCount(a) > 0 || reflexEdgeCount(b) > 0;
  }
  if (!nef) {
    const double sums = std::max(va * vb, 2.0);
    return cost + kHullOperationsPerSum * sums * std::log2(sums);
  }
  const double ra = static_cast<double>(reflexEdgeCount(a)), rb = static_cast<double>(reflexEdgeCount(b));
  return cost + kNefOperationsPerPieceTriangle * (ra + 1) * (rb + 1) * (fa + fb);
}

}  // namespace vdg::morph
