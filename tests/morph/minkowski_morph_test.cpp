// Minkowski-sum shape interpolation (vdg/morph/shape_morph.h; Parent 4.10, "Minkowski Sums").
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "support/error_of.h"
#include "support/test_meshes.h"
#include "vdg/morph/mesh_checks.h"
#include "vdg/morph/shape_morph.h"

namespace vdg::morph {
namespace {

// Float positions: a coordinate made from exact inputs is within a few float ulps of its value.
constexpr double kPositionTolerance = 1e-5;
// The two paths agree on convex meshes within this relative difference.
constexpr double kPathAgreement = 1e-9;
// Volumes from float positions, relative.
constexpr double kVolumeTolerance = 1e-5;

struct Box3 {
  std::array<double, 3> lo{}, hi{};
};

Box3 boundsOf(const TriMesh& m) {
  Box3 b{{1e300, 1e300, 1e300}, {-1e300, -1e300, -1e300}};
  for (std::size_t v = 0; v < m.vertexCount(); ++v)
    for (int k = 0; k < 3; ++k) {
      b.lo[k] = std::min(b.lo[k], static_cast<double>(m.positions[v * 3 + k]));
      b.hi[k] = std::max(b.hi[k], static_cast<double>(m.positions[v * 3 + k]));
    }
  return b;
}

// The enclosed volume, positive for outward winding (divergence theorem).
double volumeOf(const TriMesh& m) {
  double six = 0;
  for (std::size_t f = 0; f < m.triangleCount(); ++f) {
    const auto p = [&](int k) {
      const auto v = static_cast<std::size_t>(m.triangles[f * 3 + k]);
      return std::array<double, 3>{m.positions[v * 3], m.positions[v * 3 + 1], m.positions[v * 3 + 2]};
    };
    const auto a = p(0), b = p(1), c = p(2);
    six += a[0] * (b[1] * c[2] - b[2] * c[1]) + a[1] * (b[2] * c[0] - b[0] * c[2]) + a[2] * (b[0] * c[1] - b[1] * c[0]);
  }
  return six / 6;
}

void expectBox(const TriMesh& m, const Box3& want, const std::string& label) {
  const Box3 got = boundsOf(m);
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(got.lo[k], want.lo[k], kPositionTolerance) << label << " axis " << k;
    EXPECT_NEAR(got.hi[k], want.hi[k], kPositionTolerance) << label << " axis " << k;
  }
}

// An L-shaped prism: the hexagon (0,0) (2,0) (2,1) (1,1) (1,2) (0,2) in x-y, extruded over z in
// [0, 1]; closed, wound outward; not convex (the reflex corner at (1, 1)). Volume 3.
TriMesh lShape() {
  const float xy[6][2] = {{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}};
  TriMesh m;
  for (int z = 0; z < 2; ++z)
    for (const auto& p : xy) m.positions.insert(m.positions.end(), {p[0], p[1], static_cast<float>(z)});
  // Caps: a fan from the reflex corner 3, which sees the whole hexagon.
  const int fan[4][2] = {{4, 5}, {5, 0}, {0, 1}, {1, 2}};
  for (const auto& e : fan) {
    m.triangles.insert(m.triangles.end(), {6 + 3, 6 + e[0], 6 + e[1]});  // top, counter-clockwise from +z
    m.triangles.insert(m.triangles.end(), {3, e[1], e[0]});              // bottom, reversed
  }
  for (int i = 0; i < 6; ++i) {
    const int j = (i + 1) % 6;
    m.triangles.insert(m.triangles.end(), {i, j, 6 + j, i, 6 + j, 6 + i});
  }
  return m;
}

// An octahedron of radius r about c (convex; vertices on the axes).
TriMesh octahedron(double r, std::array<float, 3> c) {
  TriMesh m;
  for (int axis = 0; axis < 3; ++axis)
    for (const double sign : {1.0, -1.0}) {
      std::array<float, 3> p = c;
      p[static_cast<std::size_t>(axis)] += static_cast<float>(sign * r);
      m.positions.insert(m.positions.end(), p.begin(), p.end());
    }
  // Vertices: 0 +x, 1 -x, 2 +y, 3 -y, 4 +z, 5 -z.
  m.triangles = {0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4, 2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5};
  return m;
}

// A square frame (genus 1): the square [0,3]^2 less the hole [1,2]^2, extruded over z in [0, 1].
// Volume 8.
TriMesh squareFrame() {
  const float outer[4][2] = {{0, 0}, {3, 0}, {3, 3}, {0, 3}};
  const float inner[4][2] = {{1, 1}, {2, 1}, {2, 2}, {1, 2}};
  TriMesh m;
  // Vertex o(i, z) = z * 8 + i, inner one n(i, z) = z * 8 + 4 + i.
  for (int z = 0; z < 2; ++z) {
    for (const auto& p : outer) m.positions.insert(m.positions.end(), {p[0], p[1], static_cast<float>(z)});
    for (const auto& p : inner) m.positions.insert(m.positions.end(), {p[0], p[1], static_cast<float>(z)});
  }
  auto o = [](int i, int z) { return z * 8 + i % 4; };
  auto n = [](int i, int z) { return z * 8 + 4 + i % 4; };
  for (int i = 0; i < 4; ++i) {
    // Top (counter-clockwise from +z) and bottom (reversed) trapezoids between the squares.
    m.triangles.insert(m.triangles.end(), {o(i, 1), o(i + 1, 1), n(i + 1, 1), o(i, 1), n(i + 1, 1), n(i, 1)});
    m.triangles.insert(m.triangles.end(), {o(i, 0), n(i + 1, 0), o(i + 1, 0), o(i, 0), n(i, 0), n(i + 1, 0)});
    // Outer walls face away from the centre, inner walls towards it.
    m.triangles.insert(m.triangles.end(), {o(i, 0), o(i + 1, 0), o(i + 1, 1), o(i, 0), o(i + 1, 1), o(i, 1)});
    m.triangles.insert(m.triangles.end(), {n(i, 0), n(i + 1, 1), n(i + 1, 0), n(i, 0), n(i, 1), n(i + 1, 1)});
  }
  return m;
}

TEST(MinkowskiMorph, TwoBoxesGiveTheBoxOfSummedExtents) {
  // A: extents (2, 1, 1) centred at (1, 0.5, 0.5); B: extents (1, 3, 2) centred at (5.5, 1.5, -1).
  const TriMesh a = testing::closedBox(0, 0, 0, 2, 1, 1);
  const TriMesh b = testing::closedBox(5, 0, -2, 6, 3, 0);
  ASSERT_TRUE(isConvexMesh(a));
  ASSERT_TRUE(isConvexMesh(b));
  for (const double t : {0.5, 0.25, 0.9}) {
    SCOPED_TRACE(t);
    const TriMesh m = minkowskiMorph(a, b, t);
    EXPECT_NO_THROW(requireClosed(m, "M"));
    // Extents (1 - t) (2, 1, 1) + t (1, 3, 2); centre (1 - t) cA + t cB. At t = 0.5: (1.5, 2, 1.5).
    const std::array<double, 3> extent{(1 - t) * 2 + t * 1, (1 - t) * 1 + t * 3, (1 - t) * 1 + t * 2};
    const std::array<double, 3> centre{(1 - t) * 1 + t * 5.5, (1 - t) * 0.5 + t * 1.5, (1 - t) * 0.5 + t * -1};
    Box3 want;
    for (int k = 0; k < 3; ++k) {
      want.lo[k] = centre[k] - extent[k] / 2;
      want.hi[k] = centre[k] + extent[k] / 2;
    }
    expectBox(m, want, "box sum");
    // Every vertex is a corner of that box (the hull keeps only extreme points): 8 of them.
    EXPECT_EQ(m.vertexCount(), 8u);
    for (std::size_t v = 0; v < m.vertexCount(); ++v)
      for (int k = 0; k < 3; ++k) {
        const double x = m.positions[v * 3 + k];
        EXPECT_TRUE(std::abs(x - want.lo[k]) < kPositionTolerance || std::abs(x - want.hi[k]) < kPositionTolerance)
            << "vertex " << v << " axis " << k << " at " << x;
      }
    const double want_volume = extent[0] * extent[1] * extent[2];
    EXPECT_NEAR(volumeOf(m), want_volume, kVolumeTolerance * want_volume);
  }
  // The number at t = 0.5: the box of extents (1.5, 2, 1.5), volume 4.5.
  EXPECT_NEAR(volumeOf(minkowskiMorph(a, b, 0.5)), 1.5 * 2 * 1.5, kVolumeTolerance * 4.5);
}

TEST(MinkowskiMorph, TheEndsReproduceTheInputsExactly) {
  TriMesh a = testing::uvSphere();
  a.uvs = {0.25f, 0.75f};  // an attribute the morph does not use, kept at the ends
  const TriMesh b = lShape();
  const TriMesh at0 = minkowskiMorph(a, b, 0.0);
  const TriMesh at1 = minkowskiMorph(a, b, 1.0);
  EXPECT_EQ(at0.positions, a.positions);
  EXPECT_EQ(at0.triangles, a.triangles);
  EXPECT_EQ(at0.uvs, a.uvs);
  EXPECT_EQ(at1.positions, b.positions);
  EXPECT_EQ(at1.triangles, b.triangles);
}

TEST(MinkowskiMorph, ConvexHullAndNefPathsAgreeOnConvexMeshes) {
  const TriMesh a = testing::closedBox(-1, 0, 0, 2, 1, 3);
  const TriMesh b = octahedron(1.5, {4, 1, -2});
  ASSERT_TRUE(isConvexMesh(b));
  for (const double t : {0.3, 0.5, 0.75}) {
    SCOPED_TRACE(t);
    const TriMesh hull = minkowskiMorph(a, b, t, MinkowskiOptions{.path = MinkowskiPath::convex_hull});
    const TriMesh nef = minkowskiMorph(a, b, t, MinkowskiOptions{.path = MinkowskiPath::nef});
    const TriMesh automatic = minkowskiMorph(a, b, t);
    EXPECT_NO_THROW(requireClosed(hull, "hull"));
    EXPECT_NO_THROW(requireClosed(nef, "nef"));
    EXPECT_EQ(automatic.positions, hull.positions);  // both convex: the automatic choice is the hull
    const double vh = volumeOf(hull), vn = volumeOf(nef);
    EXPECT_GT(vh, 0);
    EXPECT_NEAR(vn, vh, kPathAgreement * vh);
    const Box3 bh = boundsOf(hull), bn = boundsOf(nef);
    for (int k = 0; k < 3; ++k) {
      const double scale = bh.hi[k] - bh.lo[k];
      EXPECT_NEAR(bn.lo[k], bh.lo[k], kPathAgreement * scale);
      EXPECT_NEAR(bn.hi[k], bh.hi[k], kPathAgreement * scale);
    }
    // Bounds: the sum of the scaled bounds, (1 - t) A + t B.
    expectBox(hull,
              Box3{{(1 - t) * -1 + t * 2.5, (1 - t) * 0 + t * -0.5, (1 - t) * 0 + t * -3.5},
                   {(1 - t) * 2 + t * 5.5, (1 - t) * 1 + t * 2.5, (1 - t) * 3 + t * -0.5}},
              "box + octahedron");
  }
}

TEST(MinkowskiMorph, ANonConvexMeshGoesThroughNefAndGivesAClosedSum) {
  const TriMesh l = lShape();
  ASSERT_NO_THROW(requireClosed(l, "L"));
  ASSERT_NEAR(volumeOf(l), 3.0, 1e-12);
  EXPECT_FALSE(isConvexMesh(l));
  const TriMesh box = testing::closedBox(0, 0, 0, 1, 3, 2);
  const double t = 0.5;
  const TriMesh m = minkowskiMorph(l, box, t);
  EXPECT_NO_THROW(requireClosed(m, "L + box"));
  // The automatic path is the Nef path (the L is not convex), and the hull path refuses the L.
  EXPECT_EQ(m.positions, minkowskiMorph(l, box, t, MinkowskiOptions{.path = MinkowskiPath::nef}).positions);
  EXPECT_EQ(testing::errorOf([&] {
              (void)minkowskiMorph(l, box, t, MinkowskiOptions{.path = MinkowskiPath::convex_hull}, "l.obj");
            }),
            "l.obj: is not convex (vertex 4 stands in front of triangle 12), so the convex-hull path cannot take its "
            "Minkowski sum");
  // 0.5 L is the union of [0,1]x[0,0.5] and [0,0.5]x[0,1] (z in [0, 0.5]); 0.5 box is
  // [0,0.5]x[0,1.5]x[0,1]. Their sum: ([0,1.5]x[0,2] union [0,1]x[0,2.5]) x [0,1.5], still an L
  // (the dent survives: the sum of a non-convex and a convex shape need not be convex).
  expectBox(m, Box3{{0, 0, 0}, {1.5, 2.5, 1.5}}, "L + box");
  const double want_volume = (1.5 * 2 + 1 * 2.5 - 1 * 2) * 1.5;  // 5.25
  EXPECT_NEAR(volumeOf(m), want_volume, kVolumeTolerance * want_volume);
  EXPECT_FALSE(isConvexMesh(m));
}

TEST(MinkowskiMorph, InwardWoundMeshesAreTakenAsTheSameSolid) {
  TriMesh l = lShape();
  for (std::size_t f = 0; f < l.triangleCount(); ++f) std::swap(l.triangles[f * 3 + 1], l.triangles[f * 3 + 2]);
  ASSERT_NEAR(volumeOf(l), -3.0, 1e-12);
  const TriMesh box = testing::closedBox(0, 0, 0, 1, 3, 2);
  const TriMesh m = minkowskiMorph(l, box, 0.5);
  EXPECT_NEAR(volumeOf(m), 5.25, kVolumeTolerance * 5.25);
}

TEST(MinkowskiMorph, BadInputIsRefusedWithOneClearMessage) {
  const TriMesh box = testing::closedBox(0, 0, 0, 1, 1, 1);
  TriMesh open = box;
  open.triangles.resize(open.triangles.size() - 3);
  EXPECT_EQ(testing::errorOf([&] { (void)minkowskiMorph(open, box, 0.5, "open.obj", "box.obj"); }),
            "open.obj: is not closed: edge (1, 5) borders a hole (one triangle only)");
  EXPECT_EQ(testing::errorOf([&] { (void)minkowskiMorph(box, open, 0.5, "box.obj", "open.obj"); }),
            "open.obj: is not closed: edge (1, 5) borders a hole (one triangle only)");
  // Closedness is checked even at the ends, where nothing is computed.
  EXPECT_NE(testing::errorOf([&] { (void)minkowskiMorph(open, box, 0.0, "open.obj"); }), "");
  for (const double t : {-0.1, 1.5, std::nan(""), std::numeric_limits<double>::infinity()}) {
    const std::string message = testing::errorOf([&] { (void)minkowskiMorph(box, box, t); });
    EXPECT_EQ(message.rfind("Minkowski morph: t must be a finite number in [0, 1], not ", 0), 0u) << message;
  }
  TriMesh far = box;
  far.positions[4] = std::nanf("");
  EXPECT_EQ(testing::errorOf([&] { (void)minkowskiMorph(box, far, 0.5, "A", "far.obj"); }),
            "far.obj: vertex 1 has a coordinate that is not finite");
  // A closed surface enclosing nothing: two triangles back to back.
  TriMesh pillow;
  pillow.positions = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  pillow.triangles = {0, 1, 2, 0, 2, 1};
  EXPECT_EQ(testing::errorOf([&] { (void)minkowskiMorph(box, pillow, 0.5, "A", "pillow.obj"); }),
            "pillow.obj: encloses no volume (a closed but flat surface)");
}

TEST(MinkowskiMorph, MeshesCgalCannotTakeAreNamed) {
  // Two overlapping boxes in one mesh: closed, but its surface crosses itself.
  const TriMesh first = testing::closedBox(0, 0, 0, 2, 2, 2);
  const TriMesh second = testing::closedBox(1, 1, 1, 3, 3, 3);
  TriMesh crossing = first;
  crossing.positions.insert(crossing.positions.end(), second.positions.begin(), second.positions.end());
  for (const std::int32_t v : second.triangles) crossing.triangles.push_back(v + 8);
  ASSERT_NO_THROW(requireClosed(crossing, "crossing"));
  const TriMesh box = testing::closedBox(0, 0, 0, 1, 1, 1);
  const std::string message = testing::errorOf([&] { (void)minkowskiMorph(box, crossing, 0.5, "A", "crossing.obj"); });
  EXPECT_EQ(message.rfind("crossing.obj: intersects itself (triangles ", 0), 0u) << message;
  EXPECT_NE(message.find("), which CGAL's Minkowski sum cannot take"), std::string::npos) << message;
  // Two boxes sharing one corner vertex: closed (every edge twice), but not a 2-manifold there.
  TriMesh bowtie = testing::closedBox(0, 0, 0, 1, 1, 1);
  const TriMesh other = testing::closedBox(1, 1, 1, 2, 2, 2);
  bowtie.positions.insert(bowtie.positions.end(), other.positions.begin() + 3, other.positions.end());
  for (const std::int32_t v : other.triangles) bowtie.triangles.push_back(v == 0 ? 7 : v + 7);
  ASSERT_NO_THROW(requireClosed(bowtie, "bowtie"));
  EXPECT_EQ(testing::errorOf([&] { (void)minkowskiMorph(box, bowtie, 0.5, "A", "bowtie.obj"); }),
            "bowtie.obj: is not a 2-manifold (the triangles around some vertex form more than one fan), which "
            "CGAL's Minkowski sum needs");
}

TEST(MinkowskiMorph, DifferentTopologiesMorphThroughSums) {
  // Parent: the sum "may overcome differing topologies". A is a genus-1 square frame, B a box.
  const TriMesh frame = squareFrame();
  ASSERT_NO_THROW(requireClosed(frame, "frame"));
  ASSERT_EQ(eulerCharacteristic(frame), 0);
  ASSERT_NEAR(volumeOf(frame), 8.0, 1e-12);
  const TriMesh box = testing::closedBox(0, 0, 0, 3, 3, 3);
  // t = 0.1: 0.9 A has a hole 0.9 wide, 0.1 B is 0.3 wide: a hole 0.6 wide is left (genus 1).
  const TriMesh early = minkowskiMorph(frame, box, 0.1);
  EXPECT_NO_THROW(requireClosed(early, "early"));
  EXPECT_EQ(eulerCharacteristic(early), 0);
  expectBox(early, Box3{{0, 0, 0}, {3, 3, 1.2}}, "early");
  EXPECT_NEAR(volumeOf(early), (3.0 * 3 - 0.6 * 0.6) * 1.2, kVolumeTolerance * 10);
  // t = 0.5: 0.5 A is [0,1.5]^2 minus the hole [0.5,1]^2 (z in [0, 0.5]), 0.5 B is [0,1.5]^3;
  // the hole (0.5) is narrower than the box (1.5), so the sum is the solid [0,3]^2 x [0,2].
  const TriMesh half = minkowskiMorph(frame, box, 0.5);
  EXPECT_NO_THROW(requireClosed(half, "half"));
  EXPECT_EQ(eulerCharacteristic(half), 2);
  expectBox(half, Box3{{0, 0, 0}, {3, 3, 2}}, "half");
  EXPECT_NEAR(volumeOf(half), 3.0 * 3 * 2, kVolumeTolerance * 18);
}

// The estimate counts what makes the Nef path slow: the reflex edges (a convex mesh has none) and
// the triangles; the convex path costs the pairwise vertex sums.
TEST(MinkowskiCost, ReflexEdgesAndTheNefPathCostMore) {
  const TriMesh box = testing::closedBox(0, 0, 0, 1, 1, 1), sphere = testing::uvSphere(), ring = testing::torus();
  EXPECT_EQ(reflexEdgeCount(box), 0u);
  EXPECT_EQ(reflexEdgeCount(sphere), 0u);
  EXPECT_GT(reflexEdgeCount(lShape()), 0u);
  EXPECT_GT(reflexEdgeCount(ring), ring.triangleCount() / 8);  // the inner half of the ring folds inwards
  const double convex = minkowskiMorphCost(sphere, box), nef = minkowskiMorphCost(ring, box);
  EXPECT_LT(convex, 1e8);
  // A torus of 1024 triangles + a box took 213 s: far past the default budget of 2e9.
  EXPECT_GT(nef, 1e10);
  EXPECT_GT(minkowskiMorphCost(sphere, box, {.path = MinkowskiPath::nef}), convex);
  // The estimate grows with both reflex edge counts.
  EXPECT_GT(minkowskiMorphCost(ring, ring), nef);
}

}  // namespace
}  // namespace vdg::morph
