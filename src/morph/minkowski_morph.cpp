// Minkowski-sum shape interpolation (Parent, 4.10 "Shape Interpolation, Metamorphosis": "translate
// one object all over surface of other object = Minkowski sum. He does linear interpolation of
// sizes of objects to do inbetween shapes of original object. This may overcome differing
// topologies of starting shapes."). See vdg/morph/shape_morph.h for the contract.
//
// The inbetween at t is the Minkowski sum M(t) = (1 - t) A (+) t B = {(1 - t) a + t b : a in A,
// b in B}. Scaling each operand about its bounding-box centre and translating the sum to
// (1 - t) cA + t cB, as the header says, gives exactly this set: the bounding box of a Minkowski
// sum is the sum of the bounding boxes, so (1 - t) A (+) t B is already centred at
// (1 - t) cA + t cB. The sums below are therefore taken about the origin, with no centring step
// (one rounding less). At t = 0 the second operand is the single point 0 and the sum is A itself;
// at t = 1 it is B. Those two ends return the input meshes unchanged (copies, every attribute kept).
//
// Two paths compute the sum for 0 < t < 1:
//   convex hull  When both meshes are convex (isConvexMesh: no vertex in front of any triangle's
//                plane, within a tolerance), the sum of two convex polytopes is the convex hull of
//                the pairwise sums of their vertices. Each mesh is first cut down to its extreme
//                points (CGAL::extreme_points_3), then the n_a * n_b sums are hulled
//                (CGAL::convex_hull_3, exact predicates with inexact constructions: the sums are
//                formed in double, the hull only chooses among them). The sums grow as the product of
//                the extreme-point counts: a sphere of 2000 vertices + a box takes 0.16 s, two
//                spheres of 500 vertices 1.1 s.
//   Nef          Otherwise CGAL::minkowski_sum_3 on Nef_polyhedron_3 over the exact kernel
//                (Exact_predicates_exact_constructions_kernel): each mesh becomes a Surface_mesh of
//                exact points scaled exactly by (1 - t) or t, then a Nef polyhedron; CGAL decomposes
//                both into convex pieces, hulls the pairwise sums and unites them. Exact but slow:
//                measured on a loaded 2-core machine, an L prism + a box 0.2 s, a 256-triangle
//                torus + a box 47 s, a 1024-triangle torus + a box 213 s (the hull path: a
//                3968-triangle sphere + a box 0.16 s, two 960-triangle spheres 1.1 s). CGAL needs
//                each mesh to be a closed 2-manifold without self-intersections; both are checked
//                here first and a refusal names the mesh.
// MinkowskiOptions::path forces either path (the tests compare the two on convex meshes).
//
// All CGAL code of vdg lives in this one translation unit (its templates take about 45 s to
// compile).
// GCC 12 reports a false -Wmaybe-uninitialized inside CGAL's box-intersection templates
// (self_intersections.h) once they are inlined into this file; CGAL's headers are not vdg's to fix.
// Not popped: GCC can report such inlined warnings outside a push/pop region, and this file is
// only the CGAL glue.
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Nef_polyhedron_3.h>
#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/convert_nef_polyhedron_to_polygon_mesh.h>
#include <CGAL/convex_hull_3.h>
#include <CGAL/exceptions.h>
#include <CGAL/minkowski_sum_3.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <iterator>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "d3.h"
#include "vdg/geom/error.h"
#include "vdg/geom/text.h"
#include "vdg/morph/mesh_checks.h"
#include "vdg/morph/shape_morph.h"

namespace vdg::morph {
namespace {

namespace PMP = CGAL::Polygon_mesh_processing;
using InexactKernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using ExactKernel = CGAL::Exact_predicates_exact_constructions_kernel;
using InexactPoint = InexactKernel::Point_3;
using ExactPoint = ExactKernel::Point_3;
using InexactMesh = CGAL::Surface_mesh<InexactPoint>;
using ExactMesh = CGAL::Surface_mesh<ExactPoint>;
using Nef = CGAL::Nef_polyhedron_3<ExactKernel>;

using Vec3 = detail::D3;

Vec3 vertex(const TriMesh& mesh, std::size_t v) {
  return {mesh.positions[v * 3], mesh.positions[v * 3 + 1], mesh.positions[v * 3 + 2]};
}
using detail::cross;
using detail::dot;
using detail::sub;

// The bounding-box centre and diagonal, in double.
std::pair<Vec3, double> boxOf(const TriMesh& mesh) {
  Vec3 lo{std::numeric_limits<double>::max(), std::numeric_limits<double>::max(), std::numeric_limits<double>::max()};
  Vec3 hi{-lo[0], -lo[1], -lo[2]};
  for (std::size_t v = 0; v < mesh.vertexCount(); ++v)
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], static_cast<double>(mesh.positions[v * 3 + k]));
      hi[k] = std::max(hi[k], static_cast<double>(mesh.positions[v * 3 + k]));
    }
  const Vec3 centre{(lo[0] + hi[0]) / 2, (lo[1] + hi[1]) / 2, (lo[2] + hi[2]) / 2};
  const Vec3 extent = sub(hi, lo);
  return {centre, std::sqrt(dot(extent, extent))};
}

// The enclosed volume (divergence theorem: the sum over triangles of det(p0, p1, p2) / 6), taken
// about the bounding-box centre for precision; negative when the triangles are wound inward.
double signedVolume(const TriMesh& mesh, const Vec3& centre) {
  double six_volume = 0;
  for (std::size_t f = 0; f < mesh.triangleCount(); ++f) {
    const auto* t = &mesh.triangles[f * 3];
    const Vec3 p0 = sub(vertex(mesh, static_cast<std::size_t>(t[0])), centre);
    const Vec3 p1 = sub(vertex(mesh, static_cast<std::size_t>(t[1])), centre);
    const Vec3 p2 = sub(vertex(mesh, static_cast<std::size_t>(t[2])), centre);
    six_volume += dot(p0, cross(p1, p2));
  }
  return six_volume / 6;
}

// The first (vertex, triangle) with the vertex more than tolerance * diagonal in front of the
// triangle's plane; (-1, -1) when the mesh is convex. `outward` is +1 for outward winding, -1 for
// inward. Triangles of (near) zero area have no reliable plane and are skipped.
std::pair<std::int64_t, std::int64_t> firstConvexityViolation(const TriMesh& mesh, double relative_tolerance,
                                                              double outward) {
  const auto [centre, diagonal] = boxOf(mesh);
  (void)centre;
  const double tolerance = relative_tolerance * diagonal;
  const double min_doubled_area = 1e-12 * diagonal * diagonal;
  for (std::size_t f = 0; f < mesh.triangleCount(); ++f) {
    const auto* t = &mesh.triangles[f * 3];
    const Vec3 p0 = vertex(mesh, static_cast<std::size_t>(t[0]));
    Vec3 n = cross(sub(vertex(mesh, static_cast<std::size_t>(t[1])), p0),
                   sub(vertex(mesh, static_cast<std::size_t>(t[2])), p0));
    const double length = std::sqrt(dot(n, n));
    if (length <= min_doubled_area) continue;
    for (double& c : n) c *= outward / length;
    for (std::size_t v = 0; v < mesh.vertexCount(); ++v)
      if (dot(n, sub(vertex(mesh, v), p0)) > tolerance)
        return {static_cast<std::int64_t>(v), static_cast<std::int64_t>(f)};
  }
  return {-1, -1};
}

// What the sum needs to know of one operand, checked once.
struct Operand {
  const TriMesh* mesh;
  const std::string* what;
  double outward;  // +1: wound outward; -1: wound inward (its triangles are flipped before use)
  bool convex;
};

Operand prepare(const TriMesh& mesh, const std::string& what, bool test_convexity, double convex_tolerance) {
  const auto [centre, diagonal] = boxOf(mesh);
  const double volume = signedVolume(mesh, centre);
  // A closed surface that encloses nothing (a flat "pillow" of two coincident sheets) has no
  // Minkowski sum CGAL can build, and no convexity test means anything for it.
  if (!(std::abs(volume) > 1e-12 * diagonal * diagonal * diagonal))
    throw Error(what + ": encloses no volume (a closed but flat surface)");
  const double outward = volume > 0 ? 1.0 : -1.0;
  const bool convex = test_convexity && firstConvexityViolation(mesh, convex_tolerance, outward).first < 0;
  return {.mesh = &mesh, .what = &what, .outward = outward, .convex = convex};
}

void requireConvex(const Operand& op, double convex_tolerance) {
  if (op.convex) return;
  const auto [v, f] = firstConvexityViolation(*op.mesh, convex_tolerance, op.outward);
  throw Error(*op.what + ": is not convex (vertex " + std::to_string(v) + " stands in front of triangle " +
              std::to_string(f) + "), so the convex-hull path cannot take its Minkowski sum");
}

TriMesh meshFromSoup(const std::vector<InexactPoint>& points, const std::vector<std::vector<std::size_t>>& polygons) {
  TriMesh out;
  out.positions.reserve(points.size() * 3);
  for (const InexactPoint& p : points)
    out.positions.insert(out.positions.end(),
                         {static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z())});
  for (const auto& polygon : polygons)
    for (std::size_t k = 1; k + 1 < polygon.size(); ++k)  // a fan; CGAL gives triangles already
      out.triangles.insert(out.triangles.end(),
                           {static_cast<std::int32_t>(polygon[0]), static_cast<std::int32_t>(polygon[k]),
                            static_cast<std::int32_t>(polygon[k + 1])});
  return out;
}

// The same mesh in a canonical order: vertices sorted by position, each triangle rotated to start
// at its smallest index (its winding kept), the triangles sorted. CGAL's output order depends on
// memory addresses, so without this two runs could number the same inbetween differently.
void canonicalise(TriMesh& mesh) {
  const std::size_t n = mesh.vertexCount();
  std::vector<std::size_t> order(n);
  for (std::size_t v = 0; v < n; ++v) order[v] = v;
  const auto key = [&](std::size_t v) {
    return std::array<float, 3>{mesh.positions[v * 3], mesh.positions[v * 3 + 1], mesh.positions[v * 3 + 2]};
  };
  std::stable_sort(order.begin(), order.end(), [&](std::size_t x, std::size_t y) { return key(x) < key(y); });
  std::vector<float> positions(n * 3);
  std::vector<std::int32_t> index(n);
  for (std::size_t i = 0; i < n; ++i) {
    index[order[i]] = static_cast<std::int32_t>(i);
    for (std::size_t k = 0; k < 3; ++k) positions[i * 3 + k] = mesh.positions[order[i] * 3 + k];
  }
  std::vector<std::array<std::int32_t, 3>> triangles(mesh.triangleCount());
  for (std::size_t f = 0; f < triangles.size(); ++f) {
    auto& t = triangles[f];
    for (std::size_t k = 0; k < 3; ++k) t[k] = index[static_cast<std::size_t>(mesh.triangles[f * 3 + k])];
    std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
  }
  std::sort(triangles.begin(), triangles.end());
  mesh.positions = std::move(positions);
  for (std::size_t f = 0; f < triangles.size(); ++f)
    for (std::size_t k = 0; k < 3; ++k) mesh.triangles[f * 3 + k] = triangles[f][k];
}

// ---- the convex-hull path ----

// The extreme points of the mesh, scaled by s (in double).
std::vector<InexactPoint> scaledExtremePoints(const TriMesh& mesh, double s) {
  std::vector<InexactPoint> points;
  points.reserve(mesh.vertexCount());
  for (std::size_t v = 0; v < mesh.vertexCount(); ++v)
    points.emplace_back(mesh.positions[v * 3], mesh.positions[v * 3 + 1], mesh.positions[v * 3 + 2]);
  std::vector<InexactPoint> extreme;
  CGAL::extreme_points_3(points, std::back_inserter(extreme));
  for (InexactPoint& p : extreme) p = InexactPoint(p.x() * s, p.y() * s, p.z() * s);
  return extreme;
}

TriMesh convexSum(const TriMesh& a, const TriMesh& b, double t) {
  const std::vector<InexactPoint> pa = scaledExtremePoints(a, 1.0 - t);
  const std::vector<InexactPoint> pb = scaledExtremePoints(b, t);
  std::vector<InexactPoint> sums;
  sums.reserve(pa.size() * pb.size());
  for (const InexactPoint& p : pa)
    for (const InexactPoint& q : pb) sums.emplace_back(p.x() + q.x(), p.y() + q.y(), p.z() + q.z());
  InexactMesh hull;
  CGAL::convex_hull_3(sums.begin(), sums.end(), hull);  // triangles, wound outward
  TriMesh out;
  std::vector<std::int32_t> index(hull.number_of_vertices() + hull.number_of_removed_vertices(), -1);
  for (const auto v : hull.vertices()) {
    index[v.idx()] = static_cast<std::int32_t>(out.vertexCount());
    const InexactPoint& p = hull.point(v);
    out.positions.insert(out.positions.end(),
                         {static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z())});
  }
  for (const auto f : hull.faces())
    for (const auto v : CGAL::vertices_around_face(hull.halfedge(f), hull)) out.triangles.push_back(index[v.idx()]);
  return out;
}

// ---- the Nef path ----

// The operand as an exact Nef polyhedron scaled by s (exactly: no point collapses however small s
// is). Refuses meshes CGAL cannot take, naming them. The checks run on a double-precision copy,
// which is exact for float coordinates, so the exact predicates give exact answers there.
Nef scaledNef(const Operand& op, double s) {
  const TriMesh& mesh = *op.mesh;
  const std::string& what = *op.what;
  std::vector<InexactPoint> points;
  points.reserve(mesh.vertexCount());
  for (std::size_t v = 0; v < mesh.vertexCount(); ++v)
    points.emplace_back(mesh.positions[v * 3], mesh.positions[v * 3 + 1], mesh.positions[v * 3 + 2]);
  std::vector<std::array<std::size_t, 3>> polygons(mesh.triangleCount());
  for (std::size_t f = 0; f < mesh.triangleCount(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int corner = op.outward > 0 ? k : 2 - k;  // flip inward-wound meshes
      polygons[f][static_cast<std::size_t>(k)] = static_cast<std::size_t>(mesh.triangles[f * 3 + corner]);
    }
  if (!PMP::is_polygon_soup_a_polygon_mesh(polygons))
    throw Error(what +
                ": is not a 2-manifold (the triangles around some vertex form more than one fan), which CGAL's "
                "Minkowski sum needs");
  InexactMesh checked;  // vertex i is mesh vertex i, face f is triangle f (a fresh Surface_mesh)
  PMP::polygon_soup_to_polygon_mesh(points, polygons, checked);
  std::vector<std::pair<InexactMesh::Face_index, InexactMesh::Face_index>> crossing;
  PMP::self_intersections(checked, std::back_inserter(crossing));
  if (!crossing.empty()) {
    const auto [f, g] = *std::min_element(crossing.begin(), crossing.end(), [](const auto& x, const auto& y) {
      return std::minmax(x.first.idx(), x.second.idx()) < std::minmax(y.first.idx(), y.second.idx());
    });
    throw Error(what + ": intersects itself (triangles " + std::to_string(std::min(f.idx(), g.idx())) + " and " +
                std::to_string(std::max(f.idx(), g.idx())) + "), which CGAL's Minkowski sum cannot take");
  }
  // Each closed component wound so that the whole bounds a volume (a cavity's shell inward).
  PMP::orient_to_bound_a_volume(checked);
  ExactMesh exact;
  const ExactKernel::FT scale(s);
  for (const auto v : checked.vertices()) {
    const InexactPoint& p = checked.point(v);
    exact.add_vertex(
        ExactPoint(ExactKernel::FT(p.x()) * scale, ExactKernel::FT(p.y()) * scale, ExactKernel::FT(p.z()) * scale));
  }
  for (const auto f : checked.faces()) {
    std::array<ExactMesh::Vertex_index, 3> corners;
    std::size_t k = 0;
    for (const auto v : CGAL::vertices_around_face(checked.halfedge(f), checked))
      corners[k++] = ExactMesh::Vertex_index(v.idx());
    exact.add_face(corners[0], corners[1], corners[2]);
  }
  return Nef(exact);
}

TriMesh nefSum(const Operand& a, const Operand& b, double t) {
  Nef na = scaledNef(a, 1.0 - t);
  Nef nb = scaledNef(b, t);
  Nef sum = CGAL::minkowski_sum_3(na, nb);
  std::vector<InexactPoint> points;
  std::vector<std::vector<std::size_t>> polygons;
  // One shell per bounded volume, its facets triangulated and wound outward (a cavity's inward).
  CGAL::convert_nef_polyhedron_to_polygon_soup(sum, points, polygons, /*triangulate_all_faces=*/true);
  return meshFromSoup(points, polygons);
}

void requireFinite(const TriMesh& mesh, const std::string& what) {
  for (std::size_t i = 0; i < mesh.positions.size(); ++i)
    if (!std::isfinite(mesh.positions[i]))
      throw Error(what + ": vertex " + std::to_string(i / 3) + " has a coordinate that is not finite");
}

}  // namespace

bool isConvexMesh(const TriMesh& mesh, double relative_tolerance) {
  if (mesh.triangleCount() == 0) return false;
  const auto [centre, diagonal] = boxOf(mesh);
  (void)diagonal;
  const double outward = signedVolume(mesh, centre) >= 0 ? 1.0 : -1.0;
  return firstConvexityViolation(mesh, relative_tolerance, outward).first < 0;
}

TriMesh minkowskiMorph(const TriMesh& a, const TriMesh& b, double t, const MinkowskiOptions& options,
                       const std::string& what_a, const std::string& what_b) {
  requireClosed(a, what_a);
  requireClosed(b, what_b);
  requireFinite(a, what_a);
  requireFinite(b, what_b);
  if (!std::isfinite(t) || t < 0 || t > 1)
    throw Error("Minkowski morph: t must be a finite number in [0, 1], not " + numberText(t, 17));
  if (!std::isfinite(options.convex_tolerance) || options.convex_tolerance < 0)
    throw Error("Minkowski morph: the convex tolerance must be a finite number >= 0, not " +
                numberText(options.convex_tolerance, 17));
  // A zero-scaled operand is the single point at the origin: the sum is the other mesh itself.
  if (t == 0) return a;
  if (t == 1) return b;
  const bool test_convexity = options.path != MinkowskiPath::nef;  // O(V * F): skipped when not needed
  const Operand oa = prepare(a, what_a, test_convexity, options.convex_tolerance);
  const Operand ob = prepare(b, what_b, test_convexity, options.convex_tolerance);
  bool hull = false;
  switch (options.path) {
    case MinkowskiPath::automatic:
      hull = oa.convex && ob.convex;
      break;
    case MinkowskiPath::convex_hull:
      requireConvex(oa, options.convex_tolerance);
      requireConvex(ob, options.convex_tolerance);
      hull = true;
      break;
    case MinkowskiPath::nef:
      hull = false;
      break;
  }
  try {
    TriMesh sum = hull ? convexSum(a, b, t) : nefSum(oa, ob, t);
    canonicalise(sum);
    return sum;
  } catch (const CGAL::Failure_exception& e) {
    // A CGAL precondition or assertion that the checks above did not foresee.
    throw Error("Minkowski morph of " + what_a + " and " + what_b + ": CGAL failed: " + e.what());
  }
}

TriMesh minkowskiMorph(const TriMesh& a, const TriMesh& b, double t, const std::string& what_a,
                       const std::string& what_b) {
  return minkowskiMorph(a, b, t, MinkowskiOptions{}, what_a, what_b);
}

}  // namespace vdg::morph
