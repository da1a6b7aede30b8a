// Spherical-projection (Kent) shape interpolation: the common mesh is closed and genus 0, it is A as
// a surface at t = 0 and B at t = 1 (every original vertex present, every new vertex on the
// surface, the same volume and area), degenerate overlays (coincident vertices and edges) weld, and
// meshes that are open, of another genus or not star-shaped are refused with one clear message.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <random>
#include <set>
#include <vector>

#include "support/error_of.h"
#include "support/test_meshes.h"
#include "vdg/morph/mesh_checks.h"
#include "vdg/morph/shape_morph.h"

namespace vdg::morph {
namespace {

using vdg::testing::closedBox;
using vdg::testing::errorOf;
using vdg::testing::torus;
using vdg::testing::uvSphere;
using V3 = std::array<double, 3>;

// A new vertex is placed on a triangle of the mesh in float: within this many units of its surface
// (the meshes here are a few units across).
constexpr double kOnSurface = 1e-5;
// Volume and area of the common mesh against the original's, relative.
constexpr double kRelative = 1e-5;

V3 vertex(std::span<const float> p, std::size_t v) { return {p[v * 3], p[v * 3 + 1], p[v * 3 + 2]}; }
V3 sub(const V3& a, const V3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
double dot(const V3& a, const V3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
V3 cross(const V3& a, const V3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

double signedVolume(std::span<const float> p, std::span<const std::int32_t> t) {
  double v = 0;
  for (std::size_t f = 0; f + 2 < t.size(); f += 3)
    v += dot(vertex(p, static_cast<std::size_t>(t[f])),
             cross(vertex(p, static_cast<std::size_t>(t[f + 1])), vertex(p, static_cast<std::size_t>(t[f + 2])))) /
         6.0;
  return v;
}

double area(std::span<const float> p, std::span<const std::int32_t> t) {
  double s = 0;
  for (std::size_t f = 0; f + 2 < t.size(); f += 3) {
    const V3 a = vertex(p, static_cast<std::size_t>(t[f]));
    const V3 n = cross(sub(vertex(p, static_cast<std::size_t>(t[f + 1])), a),
                       sub(vertex(p, static_cast<std::size_t>(t[f + 2])), a));
    s += 0.5 * std::sqrt(dot(n, n));
  }
  return s;
}

// Distance from q to triangle (a, b, c) (closest point by regions, Ericson, "Real-Time Collision
// Detection", 5.1.5).
double pointTriangleDistance(const V3& q, const V3& a, const V3& b, const V3& c) {
  const V3 ab = sub(b, a), ac = sub(c, a), ap = sub(q, a);
  auto at = [&](double v, double w) {
    const V3 x{a[0] + v * ab[0] + w * ac[0], a[1] + v * ab[1] + w * ac[1], a[2] + v * ab[2] + w * ac[2]};
    const V3 d = sub(q, x);
    return std::sqrt(dot(d, d));
  };
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (d1 <= 0 && d2 <= 0) return at(0, 0);
  const V3 bp = sub(q, b);
  const double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) return at(1, 0);
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return at(d1 / (d1 - d3), 0);
  const V3 cp = sub(q, c);
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return at(0, 1);
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return at(0, d2 / (d2 - d6));
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return at(1 - w, w);
  }
  const double denom = 1.0 / (va + vb + vc);
  return at(vb * denom, vc * denom);
}

double distanceToMesh(const V3& q, const TriMesh& m) {
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t f = 0; f < m.triangleCount(); ++f)
    best = std::min(best, pointTriangleDistance(q, vertex(m.positions, static_cast<std::size_t>(m.triangles[f * 3])),
                                                vertex(m.positions, static_cast<std::size_t>(m.triangles[f * 3 + 1])),
                                                vertex(m.positions, static_cast<std::size_t>(m.triangles[f * 3 + 2]))));
  return best;
}

// `posed` (the common mesh at t = 0 or 1) is `original` as a surface.
void expectSameSurface(std::span<const float> posed, std::span<const std::int32_t> triangles, const TriMesh& original) {
  // Every used vertex of the original is a common vertex, bit for bit.
  std::set<std::array<float, 3>> common;
  for (std::size_t v = 0; v * 3 < posed.size(); ++v) common.insert({posed[v * 3], posed[v * 3 + 1], posed[v * 3 + 2]});
  for (const std::int32_t v : original.triangles) {
    const auto i = static_cast<std::size_t>(v) * 3;
    ASSERT_TRUE(common.count({original.positions[i], original.positions[i + 1], original.positions[i + 2]}))
        << "original vertex " << v << " is missing";
  }
  // Every common vertex lies on the original.
  for (std::size_t v = 0; v * 3 < posed.size(); ++v)
    ASSERT_LE(distanceToMesh(vertex(posed, v), original), kOnSurface) << "common vertex " << v;
  // The same volume and area: no fold, no gap.
  const double vol = signedVolume(original.positions, original.triangles);
  EXPECT_NEAR(signedVolume(posed, triangles), vol, kRelative * std::abs(vol));
  const double ar = area(original.positions, original.triangles);
  EXPECT_NEAR(area(posed, triangles), ar, kRelative * ar);
}

void expectGoodMorph(const TriMesh& a, const TriMesh& b) {
  const VertexMorph morph = sphericalMorph(a, b);
  const TriMesh at0 = morph.at(0.0), at1 = morph.at(1.0), mid = morph.at(0.5);
  EXPECT_EQ(errorOf([&] { requireClosed(mid, "common"); }), "");
  EXPECT_EQ(eulerCharacteristic(mid), 2);
  EXPECT_EQ(mid.vertexCount(), morph.vertexCount());
  expectSameSurface(at0.positions, morph.triangles(), a);
  expectSameSurface(at1.positions, morph.triangles(), b);
  // at(t) poses the stored placements: exactly at the ends.
  EXPECT_TRUE(std::equal(at0.positions.begin(), at0.positions.end(), morph.positionsOnA().begin()));
  EXPECT_TRUE(std::equal(at1.positions.begin(), at1.positions.end(), morph.positionsOnB().begin()));
}

TriMesh transformed(TriMesh m, double angle, const V3& axis, const V3& offset, double scale = 1.0) {
  const double n = std::sqrt(dot(axis, axis));
  const V3 k{axis[0] / n, axis[1] / n, axis[2] / n};
  const double c = std::cos(angle), s = std::sin(angle);
  for (std::size_t v = 0; v < m.vertexCount(); ++v) {
    const V3 p = vertex(m.positions, v);
    const V3 kxp = cross(k, p);
    const double kp = dot(k, p);
    for (int i = 0; i < 3; ++i)
      m.positions[v * 3 + static_cast<std::size_t>(i)] =
          static_cast<float>(scale * (p[i] * c + kxp[i] * s + k[i] * kp * (1 - c)) + offset[i]);
  }
  return m;
}

// A sphere with radial bumps (star-shaped about any point near its centre).
TriMesh bumpySphere(int rings, int segments, unsigned seed) {
  TriMesh m = uvSphere(rings, segments);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> r(0.85, 1.15);
  for (std::size_t v = 0; v < m.vertexCount(); ++v) {
    const double k = r(rng);
    for (int i = 0; i < 3; ++i) m.positions[v * 3 + static_cast<std::size_t>(i)] *= static_cast<float>(k);
  }
  return m;
}

// The surface of the cube [-n, n]^3 on the integer grid, each unit square split along one of its
// diagonals (`flip` chooses which, and alternates by square when `checker`): directions with exact
// coincidences, vertices on edges and edges along edges against another such cube.
TriMesh latticeCube(int n, bool flip, bool checker) {
  TriMesh m;
  std::map<std::array<int, 3>, std::int32_t> index;
  auto id = [&](std::array<int, 3> p) {
    const auto [it, fresh] = index.try_emplace(p, static_cast<std::int32_t>(m.vertexCount()));
    if (fresh)
      m.positions.insert(m.positions.end(),
                         {static_cast<float>(p[0]), static_cast<float>(p[1]), static_cast<float>(p[2])});
    return it->second;
  };
  for (int axis = 0; axis < 3; ++axis)
    for (const int sign : {-1, 1}) {
      const int u = (axis + 1) % 3, w = (axis + 2) % 3;
      for (int i = -n; i < n; ++i)
        for (int j = -n; j < n; ++j) {
          auto at = [&](int di, int dj) {
            std::array<int, 3> p{};
            p[axis] = sign * n;
            p[u] = i + di;
            p[w] = j + dj;
            return id(p);
          };
          // Counter-clockwise seen from outside: (u, w) is right-handed about +axis.
          std::array<std::int32_t, 4> q{at(0, 0), at(1, 0), at(1, 1), at(0, 1)};
          if (sign < 0) std::swap(q[1], q[3]);
          const bool diagonal = flip != (checker && ((i + j) & 1));
          if (diagonal)
            m.triangles.insert(m.triangles.end(), {q[0], q[1], q[2], q[0], q[2], q[3]});
          else
            m.triangles.insert(m.triangles.end(), {q[0], q[1], q[3], q[1], q[2], q[3]});
        }
    }
  return m;
}

TEST(SphericalMorph, LatticeCubesWithExactDegeneracies) {
  const TriMesh c1 = latticeCube(1, false, false), c2 = latticeCube(2, true, true), c3 = latticeCube(3, false, true);
  ASSERT_EQ(errorOf([&] { requireClosed(c2, "c2"); }), "");
  expectGoodMorph(c1, c2);
  expectGoodMorph(c2, c3);
  expectGoodMorph(c3, c1);
  expectGoodMorph(c2, latticeCube(2, false, true));
  // An octahedron's corners are the cube's face centres.
  TriMesh octahedron;
  octahedron.positions = {2, 0, 0, -2, 0, 0, 0, 2, 0, 0, -2, 0, 0, 0, 2, 0, 0, -2};
  octahedron.triangles = {0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4, 2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5};
  expectGoodMorph(octahedron, c2);
  expectGoodMorph(c3, octahedron);
  expectGoodMorph(octahedron, uvSphere(8, 12));
}

TEST(SphericalMorph, SphereToBoxIsBothSurfacesAtTheEnds) {
  // Degenerate: the sphere's poles and equator points lie on the box's face diagonals.
  expectGoodMorph(uvSphere(8, 12), closedBox(-1, -1, -1, 1, 1, 1));
  expectGoodMorph(closedBox(-1, -1, -1, 1, 1, 1), uvSphere(8, 12));
}

TEST(SphericalMorph, BoxToStretchedBox) {
  expectGoodMorph(closedBox(-1, -1, -1, 1, 1, 1), closedBox(-2, -0.5f, -1, 2, 0.5f, 1));
}

TEST(SphericalMorph, BoxToRotatedBoxSharesSomeEdges) {
  // Rotated about y: the top and bottom diagonals overlap edges of the other box in part.
  expectGoodMorph(closedBox(-1, -1, -1, 1, 1, 1),
                  transformed(closedBox(-1, -1, -1, 1, 1, 1), M_PI / 4, {0, 1, 0}, {0, 0, 0}));
}

TEST(SphericalMorph, MeshesWithDifferentCentres) {
  const TriMesh a = uvSphere(10, 14);
  const TriMesh b = closedBox(4, -3, 1, 6, -1, 4);  // centre (5, -2, 2.5)
  expectGoodMorph(a, b);
  // Halfway, the common vertices are halfway between their placements.
  const VertexMorph morph = sphericalMorph(a, b);
  const TriMesh mid = morph.at(0.5);
  for (std::size_t i = 0; i < mid.positions.size(); ++i)
    ASSERT_NEAR(mid.positions[i], 0.5 * (morph.positionsOnA()[i] + morph.positionsOnB()[i]), 1e-6);
}

TEST(SphericalMorph, GenericStarShapedMeshes) {
  const TriMesh a = transformed(bumpySphere(10, 13, 1), 0.7, {1, 2, 3}, {0.2, -0.1, 0.3});
  const TriMesh b = transformed(bumpySphere(7, 19, 2), 1.9, {-2, 1, 0.5}, {3, 1, -2}, 1.7);
  expectGoodMorph(a, b);
  expectGoodMorph(b, a);
  // In general position the common vertices are exactly A's, B's and one per crossing of an edge
  // of A with an edge of B on the sphere (counted here by brute force over all pairs of edges).
  auto directions = [](const TriMesh& m) {
    const Bounds box = computeBounds(m.positions);
    std::vector<V3> d;
    for (std::size_t v = 0; v < m.vertexCount(); ++v) {
      V3 p = vertex(m.positions, v);
      for (int k = 0; k < 3; ++k) p[k] -= 0.5 * (static_cast<double>(box.min[k]) + static_cast<double>(box.max[k]));
      const double n = std::sqrt(dot(p, p));
      d.push_back({p[0] / n, p[1] / n, p[2] / n});
    }
    return d;
  };
  auto edges = [](const TriMesh& m) {
    std::set<std::pair<std::int32_t, std::int32_t>> e;
    for (std::size_t f = 0; f < m.triangleCount(); ++f)
      for (std::size_t k = 0; k < 3; ++k) {
        const std::int32_t u = m.triangles[f * 3 + k], w = m.triangles[f * 3 + (k + 1) % 3];
        e.insert({std::min(u, w), std::max(u, w)});
      }
    return e;
  };
  const auto da = directions(a), db = directions(b);
  std::size_t crossings = 0;
  for (const auto& [p, q] : edges(a)) {
    const V3 n = cross(da[static_cast<std::size_t>(p)], da[static_cast<std::size_t>(q)]);
    for (const auto& [r, s] : edges(b)) {
      const V3& dr = db[static_cast<std::size_t>(r)];
      const V3& ds = db[static_cast<std::size_t>(s)];
      const double sr = dot(n, dr), ss = dot(n, ds);
      if ((sr > 0) == (ss > 0)) continue;
      // Where arc r-s meets the plane of p-q; on arc p-q?
      const V3 y{dr[0] * std::abs(ss) + ds[0] * std::abs(sr), dr[1] * std::abs(ss) + ds[1] * std::abs(sr),
                 dr[2] * std::abs(ss) + ds[2] * std::abs(sr)};
      if (dot(cross(da[static_cast<std::size_t>(p)], y), n) > 0 &&
          dot(cross(y, da[static_cast<std::size_t>(q)]), n) > 0)
        ++crossings;
    }
  }
  const VertexMorph morph = sphericalMorph(a, b);
  EXPECT_GT(crossings, a.vertexCount() + b.vertexCount());
  EXPECT_EQ(morph.vertexCount(), a.vertexCount() + b.vertexCount() + crossings);
  EXPECT_EQ(morph.triangles().size() / 3, 2 * morph.vertexCount() - 4);
}

TEST(SphericalMorph, NearlyIdenticalMeshes) {
  // Rotated by a hair (down to float rounding of the positions): crossings next to vertices,
  // slivers of every kind; still closed and both surfaces at the ends.
  for (const double angle : {1e-3, 1e-6, 1e-9}) {
    SCOPED_TRACE(angle);
    expectGoodMorph(uvSphere(8, 12), transformed(uvSphere(8, 12), angle, {0.3, 1, 0.2}, {0, 0, 0}));
    expectGoodMorph(closedBox(-1, -1, -1, 1, 1, 1),
                    transformed(closedBox(-1, -1, -1, 1, 1, 1), angle, {1, 1, 1}, {0, 0, 0}));
  }
}

TEST(SphericalMorph, LargeMeshes) {
  const TriMesh a = transformed(bumpySphere(30, 52, 3), 0.3, {1, 0, 1}, {0, 0, 0});
  const TriMesh b = uvSphere(36, 44);
  ASSERT_GT(a.triangleCount(), 3000u);
  ASSERT_GT(b.triangleCount(), 3000u);
  const VertexMorph morph = sphericalMorph(a, b);
  const TriMesh mid = morph.at(0.5);
  EXPECT_EQ(errorOf([&] { requireClosed(mid, "common"); }), "");
  EXPECT_EQ(eulerCharacteristic(mid), 2);
  const TriMesh at0 = morph.at(0.0), at1 = morph.at(1.0);
  const double va = signedVolume(a.positions, a.triangles), vb = signedVolume(b.positions, b.triangles);
  EXPECT_NEAR(signedVolume(at0.positions, morph.triangles()), va, kRelative * va);
  EXPECT_NEAR(signedVolume(at1.positions, morph.triangles()), vb, kRelative * vb);
}

TEST(SphericalMorph, IdenticalMeshesGiveTheInputBack) {
  for (const TriMesh& m : {uvSphere(8, 12), closedBox(-1, -2, -3, 2, 1, 0)}) {
    const VertexMorph morph = sphericalMorph(m, m);
    ASSERT_EQ(morph.vertexCount(), m.vertexCount());
    ASSERT_EQ(morph.triangles().size(), m.triangles.size());
    // The same triangles up to the order of vertices (matched by position) and of corners.
    std::map<std::array<float, 3>, std::int32_t> index;
    for (std::size_t v = 0; v < m.vertexCount(); ++v)
      index[{m.positions[v * 3], m.positions[v * 3 + 1], m.positions[v * 3 + 2]}] = static_cast<std::int32_t>(v);
    auto canonical = [](std::array<std::int32_t, 3> t) {
      std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
      return t;
    };
    std::set<std::array<std::int32_t, 3>> expected, got;
    for (std::size_t f = 0; f < m.triangleCount(); ++f)
      expected.insert(canonical({m.triangles[f * 3], m.triangles[f * 3 + 1], m.triangles[f * 3 + 2]}));
    const auto pa = morph.positionsOnA();
    const auto tris = morph.triangles();
    for (std::size_t f = 0; f * 3 < tris.size(); ++f) {
      std::array<std::int32_t, 3> t{};
      for (std::size_t k = 0; k < 3; ++k) {
        const auto v = static_cast<std::size_t>(tris[f * 3 + k]);
        t[k] = index.at({pa[v * 3], pa[v * 3 + 1], pa[v * 3 + 2]});
      }
      got.insert(canonical(t));
    }
    EXPECT_EQ(got, expected);
    EXPECT_TRUE(std::equal(pa.begin(), pa.end(), morph.positionsOnB().begin()));
  }
}

TEST(SphericalMorph, ConcentricSpheresMeetHalfway) {
  // The same sphere at radius 1 and 2 about one centre: the directions coincide, so the common mesh
  // is the sphere's and every vertex is at radius 1.5 at t = 0.5.
  const TriMesh a = uvSphere(8, 12);
  const TriMesh b = transformed(a, 0, {0, 1, 0}, {0, 0, 0}, 2.0);
  const VertexMorph morph = sphericalMorph(a, b);
  ASSERT_EQ(morph.vertexCount(), a.vertexCount());
  const TriMesh mid = morph.at(0.5);
  for (std::size_t v = 0; v < mid.vertexCount(); ++v) {
    const V3 p = vertex(mid.positions, v);
    EXPECT_NEAR(std::sqrt(dot(p, p)), 1.5, 1e-6) << v;
  }
}

TEST(SphericalMorph, RefusesAnOpenMesh) {
  TriMesh open = uvSphere(8, 12);
  open.triangles.resize(open.triangles.size() - 3);
  const std::string expected = errorOf([&] { requireClosed(open, "B"); });
  ASSERT_FALSE(expected.empty());
  EXPECT_EQ(errorOf([&] { (void)sphericalMorph(uvSphere(), open); }), expected);
}

TEST(SphericalMorph, RefusesATorus) {
  EXPECT_EQ(errorOf([&] { (void)sphericalMorph(torus(), uvSphere(), "torus.obj", "sphere.obj"); }),
            "torus.obj: is not a single genus-0 surface (Euler characteristic 0; a sphere-like mesh has 2): the "
            "spherical morph needs one star-shaped genus-0 mesh");
  // Two separate spheres in one mesh.
  TriMesh two = uvSphere();
  const TriMesh other = transformed(uvSphere(), 0, {0, 1, 0}, {5, 0, 0});
  const auto offset = static_cast<std::int32_t>(two.vertexCount());
  two.positions.insert(two.positions.end(), other.positions.begin(), other.positions.end());
  for (const std::int32_t v : other.triangles) two.triangles.push_back(v + offset);
  EXPECT_EQ(errorOf([&] { (void)sphericalMorph(uvSphere(), two); }),
            "B: is not a single genus-0 surface (Euler characteristic 4; a sphere-like mesh has 2): the spherical "
            "morph needs one star-shaped genus-0 mesh");
}

TEST(SphericalMorph, RefusesADentedMesh) {
  // One vertex pushed through the centre to the far side: the sphere's bounding box (and centre,
  // the origin) is unchanged, and its triangles turn to face the centre.
  TriMesh dented = uvSphere(8, 12);
  const std::size_t v = 1 + 1 * 12 + 3;  // ring 2, segment 3: (0, 0.707, -0.707)
  for (int i = 0; i < 3; ++i) dented.positions[v * 3 + static_cast<std::size_t>(i)] *= -0.3f;
  std::size_t first = dented.triangleCount();
  for (std::size_t f = 0; f < dented.triangleCount() && first == dented.triangleCount(); ++f) {
    const double det = dot(vertex(dented.positions, static_cast<std::size_t>(dented.triangles[f * 3])),
                           cross(vertex(dented.positions, static_cast<std::size_t>(dented.triangles[f * 3 + 1])),
                                 vertex(dented.positions, static_cast<std::size_t>(dented.triangles[f * 3 + 2]))));
    if (det <= 0) first = f;
  }
  ASSERT_LT(first, dented.triangleCount());
  EXPECT_EQ(errorOf([&] { (void)sphericalMorph(dented, uvSphere(), "dent.obj"); }),
            "dent.obj: is not star-shaped about its centre (0, 0, 0): triangle " + std::to_string(first) +
                " faces the centre or is seen edge-on from it");
  // Turned inside out: every triangle faces the centre; the first is named.
  TriMesh inside_out = closedBox(-1, -1, -1, 1, 1, 1);
  for (std::size_t f = 0; f < inside_out.triangleCount(); ++f)
    std::swap(inside_out.triangles[f * 3 + 1], inside_out.triangles[f * 3 + 2]);
  EXPECT_EQ(errorOf([&] { (void)sphericalMorph(uvSphere(), inside_out); }),
            "B: is not star-shaped about its centre (0, 0, 0): triangle 0 faces the centre or is seen edge-on from it");
}

TEST(SphericalMorph, RefusesASurfaceThatWrapsTwice) {
  // Every triangle faces away from the centre, but the surface winds twice around it: a band of
  // quads around the y axis that turns 4 pi, closed by two fans to poles at the top and bottom
  // (the poles' fans also wind twice). Closed and genus 0 as a triangle mesh, since the band's
  // vertices are distinct (their radius grows with the turn).
  const int n = 24;  // per turn
  TriMesh m;
  auto ring = [&](int i, double y) {
    const double angle = 4.0 * M_PI * i / (2 * n);
    const double r = 1.0 + 0.3 * i / (2 * n);
    m.positions.insert(m.positions.end(), {static_cast<float>(r * std::cos(angle)), static_cast<float>(y),
                                           static_cast<float>(-r * std::sin(angle))});
  };
  for (int i = 0; i < 2 * n; ++i) ring(i, 0.5);
  for (int i = 0; i < 2 * n; ++i) ring(i, -0.5);
  const auto top = static_cast<std::int32_t>(m.vertexCount());
  m.positions.insert(m.positions.end(), {0, 1, 0, 0, -1, 0});
  const std::int32_t bottom = top + 1;
  const std::int32_t k = 2 * n;
  for (std::int32_t i = 0; i < k; ++i) {
    const std::int32_t j = (i + 1) % k;
    m.triangles.insert(m.triangles.end(), {top, i, j});
    m.triangles.insert(m.triangles.end(), {i, k + i, k + j, i, k + j, j});
    m.triangles.insert(m.triangles.end(), {k + i, bottom, k + j});
  }
  ASSERT_EQ(errorOf([&] { requireClosed(m, "m"); }), "");
  ASSERT_EQ(eulerCharacteristic(m), 2);
  const std::string message = errorOf([&] { (void)sphericalMorph(m, uvSphere()); });
  EXPECT_EQ(message.rfind("A: is not star-shaped about its centre (", 0), 0u) << message;
  EXPECT_NE(message.find("its triangles cover the sphere 2 times (triangles 0 and "), std::string::npos) << message;
}

TEST(SphericalMorph, EvaluateChecksItsContract) {
  const VertexMorph morph = sphericalMorph(uvSphere(6, 8), closedBox(-1, -1, -1, 1, 1, 1));
  const std::size_t n = morph.vertexCount() * 3;
  std::vector<float> buffer(n + 3, 7.0f);
  const std::span<float> all(buffer);
  EXPECT_FALSE(morph.evaluate(0.5, all.first(n - 1)));
  EXPECT_FALSE(morph.evaluate(0.5, all.first(n + 3)));
  EXPECT_FALSE(morph.evaluate(0.5, {}));
  EXPECT_FALSE(morph.evaluate(std::nan(""), all.first(n)));
  EXPECT_FALSE(morph.evaluate(std::numeric_limits<double>::infinity(), all.first(n)));
  EXPECT_FALSE(morph.evaluate(-std::numeric_limits<double>::infinity(), all.first(n)));
  EXPECT_TRUE(std::all_of(buffer.begin(), buffer.end(), [](float x) { return x == 7.0f; }));
  ASSERT_TRUE(morph.evaluate(0.25, all.first(n)));
  const TriMesh quarter = morph.at(0.25);
  EXPECT_TRUE(std::equal(quarter.positions.begin(), quarter.positions.end(), buffer.begin()));
  EXPECT_EQ(buffer[n], 7.0f);
  EXPECT_EQ(errorOf([&] { (void)morph.at(std::nan("")); }), "spherical morph: t nan is not a finite number");
}

}  // namespace
}  // namespace vdg::morph
