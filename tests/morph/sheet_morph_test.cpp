// Parent's sheets: the common mesh is closed and genus 0 at every t, is A at t = 0 and B at t = 1
// exactly (every vertex of each is a common vertex, every other vertex lies on it, and it encloses
// the same volume with the same area: nothing folds over), interpolates vertex to vertex, and
// meshes it cannot take are refused with one clear message.
#include "vdg/morph/sheet_morph.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <set>
#include <vector>

#include "support/error_of.h"
#include "support/test_meshes.h"
#include "vdg/morph/mesh_checks.h"

namespace vdg::morph {
namespace {

using vdg::testing::closedBox;
using vdg::testing::errorOf;
using vdg::testing::torus;
using vdg::testing::uvSphere;

// Points added on A's and B's edges and faces are computed in double and stored in float.
constexpr double kOnSurface = 1e-5;
// Volumes and areas of the ends, relative to the originals' (float positions).
constexpr double kRelative = 1e-5;

using P3 = std::array<double, 3>;

P3 point(std::span<const float> positions, std::size_t v) {
  return {positions[v * 3], positions[v * 3 + 1], positions[v * 3 + 2]};
}
P3 sub(const P3& a, const P3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
P3 cross(const P3& a, const P3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double dot(const P3& a, const P3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

struct Measure {
  double volume = 0, area = 0;
};
Measure measure(std::span<const float> positions, std::span<const std::int32_t> triangles) {
  Measure m;
  for (std::size_t f = 0; f * 3 < triangles.size(); ++f) {
    const P3 p = point(positions, static_cast<std::size_t>(triangles[f * 3]));
    const P3 q = point(positions, static_cast<std::size_t>(triangles[f * 3 + 1]));
    const P3 r = point(positions, static_cast<std::size_t>(triangles[f * 3 + 2]));
    m.volume += dot(p, cross(q, r)) / 6.0;
    const P3 n = cross(sub(q, p), sub(r, p));
    m.area += std::sqrt(dot(n, n)) / 2.0;
  }
  return m;
}

// The distance from q to the nearest triangle of m (point-triangle distance, exact enough here).
double offSurface(const P3& q, const TriMesh& m) {
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t f = 0; f < m.triangleCount(); ++f) {
    const P3 a = point(m.positions, static_cast<std::size_t>(m.triangles[f * 3]));
    const P3 b = point(m.positions, static_cast<std::size_t>(m.triangles[f * 3 + 1]));
    const P3 c = point(m.positions, static_cast<std::size_t>(m.triangles[f * 3 + 2]));
    const P3 n = cross(sub(b, a), sub(c, a));
    const double len = std::sqrt(dot(n, n));
    if (len == 0) continue;
    // Inside the prism over the triangle (the edge tests), the distance to the plane; else skip:
    // a point on an edge is inside the prism of one of its two triangles, up to rounding.
    bool inside = true;
    for (const auto& [s, e] : {std::pair{a, b}, std::pair{b, c}, std::pair{c, a}})
      inside = inside && dot(cross(sub(e, s), sub(q, s)), n) >= -kOnSurface * len;
    if (inside) best = std::min(best, std::abs(dot(sub(q, a), n)) / len);
  }
  return best;
}

// Every vertex of `original` is a vertex of the placement, every vertex of the placement lies on
// `original`, and the placement with the common triangles encloses the same volume with the same
// area.
void expectExactly(std::span<const float> placed, std::span<const std::int32_t> triangles, const TriMesh& original) {
  std::set<std::array<float, 3>> corners;
  for (std::size_t v = 0; v * 3 < placed.size(); ++v)
    corners.insert({placed[v * 3], placed[v * 3 + 1], placed[v * 3 + 2]});
  for (std::size_t v = 0; v < original.vertexCount(); ++v)
    ASSERT_TRUE(
        corners.count({original.positions[v * 3], original.positions[v * 3 + 1], original.positions[v * 3 + 2]}))
        << "vertex " << v << " of the original is not a common vertex";
  for (std::size_t v = 0; v * 3 < placed.size(); ++v)
    ASSERT_LE(offSurface(point(placed, v), original), kOnSurface) << "common vertex " << v;
  const Measure want = measure(original.positions, original.triangles), got = measure(placed, triangles);
  EXPECT_NEAR(got.volume, want.volume, kRelative * std::abs(want.volume));
  EXPECT_NEAR(got.area, want.area, kRelative * want.area);
}

void expectClosedGenus0AtEveryT(const VertexMorph& morph) {
  for (const double t : {0.0, 0.25, 0.5, 0.75, 1.0}) {
    const TriMesh m = morph.at(t);
    ASSERT_EQ(errorOf([&] { requireClosed(m, "common"); }), "") << "t = " << t;
    EXPECT_EQ(eulerCharacteristic(m), 2) << "t = " << t;
  }
}

TriMesh moved(TriMesh m, double scale, double dx, double dy, double dz) {
  for (std::size_t v = 0; v < m.vertexCount(); ++v) {
    m.positions[v * 3] = static_cast<float>(m.positions[v * 3] * scale + dx);
    m.positions[v * 3 + 1] = static_cast<float>(m.positions[v * 3 + 1] * scale + dy);
    m.positions[v * 3 + 2] = static_cast<float>(m.positions[v * 3 + 2] * scale + dz);
  }
  return m;
}

TEST(SheetMorph, SphereToBoxHasExactEndsAndStaysClosedGenus0) {
  const TriMesh a = uvSphere(8, 12);
  const TriMesh b = closedBox(3, -1, -2, 5, 2, 0);  // elsewhere, another size, 12 triangles only
  const VertexMorph morph = sheetMorph(a, b);
  expectClosedGenus0AtEveryT(morph);
  expectExactly(morph.positionsOnA(), morph.triangles(), a);
  expectExactly(morph.positionsOnB(), morph.triangles(), b);
  // Vertex to vertex, linearly.
  const TriMesh m = morph.at(0.3);
  for (std::size_t i = 0; i < m.positions.size(); ++i)
    ASSERT_NEAR(m.positions[i], 0.7 * morph.positionsOnA()[i] + 0.3 * morph.positionsOnB()[i], 1e-5);
}

TEST(SheetMorph, EitherWayRoundAndAcrossResolutions) {
  // A coarse sphere into a fine, moved one, and back. The coarser mesh's edges are followed and the
  // finer one is cut either way, so the two orders give one common mesh, its placements swapped.
  const TriMesh coarse = uvSphere(5, 7), fine = moved(uvSphere(14, 22), 1.5, 0.2, -0.3, 0.1);
  const VertexMorph forward = sheetMorph(coarse, fine), backward = sheetMorph(fine, coarse);
  expectClosedGenus0AtEveryT(forward);
  expectExactly(forward.positionsOnA(), forward.triangles(), coarse);
  expectExactly(forward.positionsOnB(), forward.triangles(), fine);
  EXPECT_TRUE(std::ranges::equal(forward.triangles(), backward.triangles()));
  EXPECT_TRUE(std::ranges::equal(forward.positionsOnA(), backward.positionsOnB()));
  EXPECT_TRUE(std::ranges::equal(forward.positionsOnB(), backward.positionsOnA()));
}

TEST(SheetMorph, EveryAxisGivesAClosedOutwardMesh) {
  const TriMesh a = closedBox(-1, -2, -3, 1, 2, 3), b = uvSphere(6, 10);
  for (int axis = 0; axis < 3; ++axis) {
    const VertexMorph morph = sheetMorph(a, b, {.axis = axis});
    expectClosedGenus0AtEveryT(morph);
    const TriMesh m = morph.at(0.5);
    EXPECT_GT(measure(m.positions, m.triangles).volume, 0.0) << axis;
    expectExactly(morph.positionsOnA(), morph.triangles(), a);
    expectExactly(morph.positionsOnB(), morph.triangles(), b);
  }
}

// Two octahedra sharing their two poles: one part, Euler characteristic 2, but each pole has two
// fans of triangles.
TriMesh pinchedOctahedra() {
  TriMesh m;
  m.positions = {0, 1, 0, 0, -1, 0, 1, 0, 0, 0, 0, -1, -1, 0, 0, 0, 0, 1, 2, 0, 0, 0, 0, -2, -2, 0, 0, 0, 0, 2};
  for (const std::int32_t base : {2, 6})
    for (std::int32_t k = 0; k < 4; ++k) {
      const std::int32_t p = base + k, q = base + (k + 1) % 4;
      m.triangles.insert(m.triangles.end(), {0, p, q, 1, q, p});
    }
  return m;
}

TEST(SheetMorph, RefusesMeshesThatAreNotOneSphere) {
  EXPECT_EQ(errorOf([&] { (void)sheetMorph(uvSphere(), torus(), {}, "s", "torus.obj"); }),
            "torus.obj: is not one genus-0 surface (Euler characteristic 0, 1 part); the sheet morph needs a mesh "
            "like a sphere");
  TriMesh two = uvSphere();
  const TriMesh other = moved(uvSphere(), 1, 5, 0, 0);
  const auto offset = static_cast<std::int32_t>(two.vertexCount());
  two.positions.insert(two.positions.end(), other.positions.begin(), other.positions.end());
  for (const std::int32_t v : other.triangles) two.triangles.push_back(v + offset);
  EXPECT_EQ(errorOf([&] { (void)sheetMorph(two, uvSphere(), {}, "two.obj"); }),
            "two.obj: is not one genus-0 surface (Euler characteristic 4, 2 parts); the sheet morph needs a mesh "
            "like a sphere");
  const TriMesh pinched = pinchedOctahedra();
  ASSERT_EQ(errorOf([&] { requireClosed(pinched, "p"); }), "");
  EXPECT_EQ(errorOf([&] { (void)sheetMorph(uvSphere(), pinched, {}, "A", "pinched.obj"); }),
            "pinched.obj: vertex 0 is not a manifold vertex (its triangles make 2 fans or more); the sheet morph "
            "needs one fan round every vertex");
  TriMesh open = uvSphere();
  open.triangles.resize(open.triangles.size() - 3);
  EXPECT_EQ(errorOf([&] { (void)sheetMorph(open, uvSphere()); }), errorOf([&] { requireClosed(open, "A"); }));
  EXPECT_EQ(errorOf([&] { (void)sheetMorph(uvSphere(), uvSphere(), {.axis = 3}); }),
            "sheet morph: axis must be 0, 1 or 2");
}

TEST(SheetMorph, CostIsTrianglesTimesLevels) {
  const TriMesh a = uvSphere(8, 16), b = closedBox(0, 0, 0, 1, 1, 1);  // 224 and 12 triangles
  EXPECT_DOUBLE_EQ(sheetMorphCost(a, b), (224.0 + 12.0) * (std::log2(224.0) + 2.0) * 64.0);
  // Doubling both meshes a little more than doubles the cost (one more level).
  const TriMesh a2 = uvSphere(16, 16);  // 480 triangles
  EXPECT_GT(sheetMorphCost(a2, a2), 2.0 * sheetMorphCost(a, a));
  EXPECT_LT(sheetMorphCost(a2, a2), 2.5 * sheetMorphCost(a, a));
}

TEST(SheetMorph, EvaluateChecksItsContract) {
  const VertexMorph morph = sheetMorph(uvSphere(), closedBox(-1, -1, -1, 1, 1, 1));
  const std::size_t n = morph.vertexCount() * 3;
  std::vector<float> buffer(n + 1, 7.0f);
  const std::span<float> all(buffer);
  EXPECT_FALSE(morph.evaluate(0.5, all.first(n - 1)));
  EXPECT_FALSE(morph.evaluate(std::nan(""), all.first(n)));
  EXPECT_TRUE(std::all_of(buffer.begin(), buffer.end(), [](float x) { return x == 7.0f; }));
  ASSERT_TRUE(morph.evaluate(0.0, all.first(n)));
  EXPECT_TRUE(std::equal(morph.positionsOnA().begin(), morph.positionsOnA().end(), buffer.begin()));
  EXPECT_EQ(errorOf([&] { (void)morph.at(std::nan("")); }), "sheet morph: t nan is not a finite number");
}

}  // namespace
}  // namespace vdg::morph
