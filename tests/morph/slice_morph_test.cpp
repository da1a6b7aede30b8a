// Chen's slices: the lofted mesh is closed and genus 0 with slices * samples + 2 vertices, lies on
// A at t = 0 and on B at t = 1, interpolates linearly, and cuts that are not one closed contour are
// refused with one clear message.
#include "vdg/morph/slice_morph.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
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

// A resampled point is computed in double and stored in float: within this of the surface.
constexpr double kOnSurface = 1e-5;

// The distance from q to the plane of the nearest triangle whose bounding box (grown by kOnSurface)
// holds q: 0 when q lies on a triangle.
double offSurface(const std::array<double, 3>& q, const TriMesh& m) {
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t f = 0; f < m.triangleCount(); ++f) {
    std::array<std::array<double, 3>, 3> p{};
    for (int c = 0; c < 3; ++c)
      for (int k = 0; k < 3; ++k)
        p[c][k] = m.positions[static_cast<std::size_t>(m.triangles[f * 3 + c]) * 3 + static_cast<std::size_t>(k)];
    bool inside = true;
    for (int k = 0; k < 3; ++k)
      inside = inside && q[k] >= std::min({p[0][k], p[1][k], p[2][k]}) - kOnSurface &&
               q[k] <= std::max({p[0][k], p[1][k], p[2][k]}) + kOnSurface;
    if (!inside) continue;
    const std::array<double, 3> e1{p[1][0] - p[0][0], p[1][1] - p[0][1], p[1][2] - p[0][2]};
    const std::array<double, 3> e2{p[2][0] - p[0][0], p[2][1] - p[0][1], p[2][2] - p[0][2]};
    std::array<double, 3> n{e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                            e1[0] * e2[1] - e1[1] * e2[0]};
    const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (len == 0) continue;
    best =
        std::min(best, std::abs(((q[0] - p[0][0]) * n[0] + (q[1] - p[0][1]) * n[1] + (q[2] - p[0][2]) * n[2]) / len));
  }
  return best;
}

void expectOn(std::span<const float> posed, const TriMesh& original) {
  for (std::size_t v = 0; v * 3 < posed.size(); ++v)
    ASSERT_LE(offSurface({posed[v * 3], posed[v * 3 + 1], posed[v * 3 + 2]}, original), kOnSurface) << "vertex " << v;
}

TEST(SliceMorph, SphereToBoxIsClosedAndOnBothEnds) {
  const TriMesh a = uvSphere(10, 16);
  const TriMesh b = closedBox(3, -1, -2, 5, 2, 0);  // elsewhere, another size
  const SliceMorphOptions options{.axis = 1, .slices = 12, .samples = 20};
  const VertexMorph morph = sliceMorph(a, b, options);
  EXPECT_EQ(morph.vertexCount(), 12u * 20u + 2u);
  for (const double t : {0.0, 0.3, 1.0}) {
    const TriMesh m = morph.at(t);
    EXPECT_EQ(errorOf([&] { requireClosed(m, "lofted"); }), "");
    EXPECT_EQ(eulerCharacteristic(m), 2);
  }
  expectOn(morph.positionsOnA(), a);
  expectOn(morph.positionsOnB(), b);
  // Vertex to vertex, linearly.
  const TriMesh m = morph.at(0.3);
  for (std::size_t i = 0; i < m.positions.size(); ++i)
    ASSERT_NEAR(m.positions[i], 0.7 * morph.positionsOnA()[i] + 0.3 * morph.positionsOnB()[i], 1e-5);
}

TEST(SliceMorph, EveryAxis) {
  for (int axis = 0; axis < 3; ++axis) {
    const VertexMorph morph =
        sliceMorph(closedBox(-1, -2, -3, 1, 2, 3), uvSphere(), {.axis = axis, .slices = 5, .samples = 8});
    const TriMesh m = morph.at(0.5);
    EXPECT_EQ(errorOf([&] { requireClosed(m, "lofted"); }), "") << axis;
    // Outward: the signed volume is positive.
    double volume = 0;
    for (std::size_t f = 0; f < m.triangleCount(); ++f) {
      const float* p = &m.positions[static_cast<std::size_t>(m.triangles[f * 3]) * 3];
      const float* q = &m.positions[static_cast<std::size_t>(m.triangles[f * 3 + 1]) * 3];
      const float* r = &m.positions[static_cast<std::size_t>(m.triangles[f * 3 + 2]) * 3];
      volume += (p[0] * (q[1] * r[2] - q[2] * r[1]) + p[1] * (q[2] * r[0] - q[0] * r[2]) +
                 p[2] * (q[0] * r[1] - q[1] * r[0])) /
                6.0;
    }
    EXPECT_GT(volume, 0.0) << axis;
  }
}

TEST(SliceMorph, ConcentricSpheresMeetHalfway) {
  // B is A scaled by 2 about the origin: every resampled point of B is twice A's.
  const TriMesh a = uvSphere(8, 12);
  TriMesh b = a;
  for (float& x : b.positions) x *= 2.0f;
  const VertexMorph morph = sliceMorph(a, b);
  const TriMesh mid = morph.at(0.5);
  for (std::size_t i = 0; i < mid.positions.size(); ++i)
    ASSERT_NEAR(mid.positions[i], 1.5 * morph.positionsOnA()[i], 1e-5) << i;
}

TEST(SliceMorph, RefusesCutsThatAreNotOneContour) {
  // Cut across its axis, a torus gives rings (two contours).
  EXPECT_EQ(
      errorOf([&] { (void)sliceMorph(uvSphere(), torus(), {.axis = 1, .slices = 3, .samples = 8}, "s", "torus.obj"); }),
      "torus.obj: the cut at y = -0.266667 is 2 contours; the slice morph needs one closed contour per cut");
  TriMesh open = uvSphere();
  open.triangles.resize(open.triangles.size() - 3);
  EXPECT_EQ(errorOf([&] { (void)sliceMorph(open, uvSphere()); }), errorOf([&] { requireClosed(open, "A"); }));
  EXPECT_EQ(errorOf([&] { (void)sliceMorph(uvSphere(), uvSphere(), {.axis = 3}); }),
            "slice morph: axis must be 0, 1 or 2");
  EXPECT_EQ(errorOf([&] { (void)sliceMorph(uvSphere(), uvSphere(), {.slices = 0}); }),
            "slice morph: slices must be in [1, 100000]");
  EXPECT_EQ(errorOf([&] { (void)sliceMorph(uvSphere(), uvSphere(), {.samples = 2}); }),
            "slice morph: samples must be in [3, 100000]");
}

TEST(SliceMorph, RefusesACutNotStarShapedAboutItsCentroid) {
  // A thin C-shaped prism (cut across y it is a C whose centroid lies outside it).
  TriMesh c;
  const int k = 24;
  for (int i = 0; i <= k; ++i) {
    const double a = 0.2 + (2 * M_PI - 0.4) * i / k;
    for (const double r : {1.0, 0.9})
      for (const float y : {-1.0f, 1.0f})
        c.positions.insert(c.positions.end(),
                           {static_cast<float>(r * std::cos(a)), y, static_cast<float>(-r * std::sin(a))});
  }
  auto id = [](int i, int outer, int top) {
    return static_cast<std::int32_t>(i * 4 + (outer ? 0 : 2) + (top ? 1 : 0));
  };
  auto quad = [&](std::int32_t p, std::int32_t q, std::int32_t r, std::int32_t s) {
    c.triangles.insert(c.triangles.end(), {p, q, r, p, r, s});
  };
  for (int i = 0; i < k; ++i) {
    quad(id(i, 1, 0), id(i + 1, 1, 0), id(i + 1, 1, 1), id(i, 1, 1));  // outer wall
    quad(id(i + 1, 0, 0), id(i, 0, 0), id(i, 0, 1), id(i + 1, 0, 1));  // inner wall
    quad(id(i, 1, 1), id(i + 1, 1, 1), id(i + 1, 0, 1), id(i, 0, 1));  // top
    quad(id(i + 1, 1, 0), id(i, 1, 0), id(i, 0, 0), id(i + 1, 0, 0));  // bottom
  }
  quad(id(0, 0, 0), id(0, 1, 0), id(0, 1, 1), id(0, 0, 1));  // the C's two ends
  quad(id(k, 1, 0), id(k, 0, 0), id(k, 0, 1), id(k, 1, 1));
  ASSERT_EQ(errorOf([&] { requireClosed(c, "c"); }), "");
  EXPECT_EQ(errorOf([&] { (void)sliceMorph(c, uvSphere(), {.axis = 1, .slices = 2, .samples = 16}, "c.obj"); }),
            "c.obj: the cut at y = -0.5 is not star-shaped about its centroid (-0.0638985, -0.5, 0): the contour's "
            "edge from (0.88206, -0.5, -0.178802) to (0.829739, -0.5, -0.335341) faces away from it (rays from the "
            "centroid would miss part of the contour)");
}

// A prism along y over a polygon in (x, z) (counter-clockwise seen from -y... whichever: the
// winding is fixed by the signed volume), its caps triangulated by `caps` (index triples into the
// polygon, wound as the polygon), outward.
TriMesh prism(const std::vector<std::array<float, 2>>& polygon, const std::vector<std::int32_t>& caps) {
  TriMesh m;
  const auto n = static_cast<std::int32_t>(polygon.size());
  for (const float y : {-1.0f, 1.0f})
    for (const auto& p : polygon) m.positions.insert(m.positions.end(), {p[0], y, p[1]});
  for (std::int32_t i = 0; i < n; ++i) {
    const std::int32_t j = (i + 1) % n;
    m.triangles.insert(m.triangles.end(), {i, j, n + j, i, n + j, n + i});
  }
  for (std::size_t c = 0; c < caps.size(); c += 3) {
    m.triangles.insert(m.triangles.end(), {n + caps[c], n + caps[c + 1], n + caps[c + 2]});
    m.triangles.insert(m.triangles.end(), {caps[c + 2], caps[c + 1], caps[c]});
  }
  double volume = 0;
  for (std::size_t f = 0; f < m.triangleCount(); ++f) {
    const float* p = &m.positions[static_cast<std::size_t>(m.triangles[f * 3]) * 3];
    const float* q = &m.positions[static_cast<std::size_t>(m.triangles[f * 3 + 1]) * 3];
    const float* r = &m.positions[static_cast<std::size_t>(m.triangles[f * 3 + 2]) * 3];
    volume +=
        p[0] * (q[1] * r[2] - q[2] * r[1]) + p[1] * (q[2] * r[0] - q[0] * r[2]) + p[2] * (q[0] * r[1] - q[1] * r[0]);
  }
  if (volume < 0)
    for (std::size_t f = 0; f < m.triangleCount(); ++f) std::swap(m.triangles[f * 3 + 1], m.triangles[f * 3 + 2]);
  return m;
}

TEST(SliceMorph, RefusesANotchedSquarePrismWhoseNotchWallsNoRayReaches) {
  // The square [-1, 1]^2 with a notch 0.4 wide and 0.5 deep cut into its +z side. Its centroid
  // (0, -0.0395) sees the notch's floor but neither of its walls (x = -0.2 and 0.2; the first piece
  // of the wall at x = 0.2 is named, the cut crossing its two triangles): rays from it
  // reach the floor and go no further, so a resampling would lose both walls; no sampled ray misses
  // the contour, which is why only an exact test per edge finds it.
  const TriMesh notched = prism(
      {{-1, -1}, {1, -1}, {1, 0.5f}, {1, 1}, {0.2f, 1}, {0.2f, 0.5f}, {-0.2f, 0.5f}, {-0.2f, 1}, {-1, 1}, {-1, 0.5f}},
      {0, 1, 2, 0, 2, 5, 0, 5, 6, 0, 6, 9, 2, 3, 4, 2, 4, 5, 9, 6, 7, 9, 7, 8});
  ASSERT_EQ(errorOf([&] { requireClosed(notched, "notched"); }), "");
  for (const int samples : {8, 64, 1000}) {
    const std::string message = errorOf(
        [&] { (void)sliceMorph(uvSphere(), notched, {.axis = 1, .slices = 3, .samples = samples}, "A", "notch.obj"); });
    EXPECT_EQ(message,
              "notch.obj: the cut at y = -0.666667 is not star-shaped about its centroid (0, -0.666667, -0.0394737): "
              "the contour's edge from (0.2, -0.666667, 1) to (0.2, -0.666667, 0.916667) faces away from it (rays "
              "from the centroid would miss part of the contour)")
        << samples;
  }
  // Along z every cut is a rectangle or two (through the notch): refused as two contours, not
  // resampled.
  EXPECT_EQ(errorOf([&] { (void)sliceMorph(notched, uvSphere(), {.axis = 2, .slices = 4, .samples = 8}); }),
            "A: the cut at z = 0.75 is 2 contours; the slice morph needs one closed contour per cut");
}

TEST(SliceMorph, AcceptsANonConvexCutThatIsStarShapedAboutItsCentroid) {
  // A plus sign: not convex, but its centroid (the origin) sees every edge from the inside.
  const TriMesh plus =
      prism({{-0.3f, -1},
             {0.3f, -1},
             {0.3f, -0.3f},
             {1, -0.3f},
             {1, 0.3f},
             {0.3f, 0.3f},
             {0.3f, 1},
             {-0.3f, 1},
             {-0.3f, 0.3f},
             {-1, 0.3f},
             {-1, -0.3f},
             {-0.3f, -0.3f}},
            {2, 5, 8, 2, 8, 11, 0, 1, 2, 0, 2, 11, 2, 3, 4, 2, 4, 5, 5, 6, 7, 5, 7, 8, 8, 9, 10, 8, 10, 11});
  ASSERT_EQ(errorOf([&] { requireClosed(plus, "plus"); }), "");
  const VertexMorph morph = sliceMorph(uvSphere(), plus, {.axis = 1, .slices = 4, .samples = 48});
  expectOn(morph.positionsOnB(), plus);
  // Every resampled contour reaches the tips of the arms (|x| or |z| = 1 in some direction).
  const auto on_b = morph.positionsOnB();
  for (int s = 0; s < 4; ++s) {
    float reach = 0;
    for (int j = 0; j < 48; ++j) {
      const std::size_t v = static_cast<std::size_t>(s * 48 + j) * 3;
      reach = std::max({reach, std::abs(on_b[v]), std::abs(on_b[v + 2])});
    }
    EXPECT_NEAR(reach, 1.0f, 1e-6f) << "slice " << s;
  }
}

TEST(SliceMorph, EvaluateChecksItsContract) {
  const VertexMorph morph = sliceMorph(uvSphere(), closedBox(-1, -1, -1, 1, 1, 1), {.slices = 4, .samples = 6});
  const std::size_t n = morph.vertexCount() * 3;
  std::vector<float> buffer(n + 1, 7.0f);
  const std::span<float> all(buffer);
  EXPECT_FALSE(morph.evaluate(0.5, all.first(n - 1)));
  EXPECT_FALSE(morph.evaluate(0.5, all));
  EXPECT_FALSE(morph.evaluate(std::nan(""), all.first(n)));
  EXPECT_FALSE(morph.evaluate(std::numeric_limits<double>::infinity(), all.first(n)));
  EXPECT_TRUE(std::all_of(buffer.begin(), buffer.end(), [](float x) { return x == 7.0f; }));
  ASSERT_TRUE(morph.evaluate(1.0, all.first(n)));
  EXPECT_TRUE(std::equal(morph.positionsOnB().begin(), morph.positionsOnB().end(), buffer.begin()));
  EXPECT_EQ(buffer[n], 7.0f);
}

// The runtime both shape-morph builders return refuses placements that do not make one mesh.
TEST(VertexMorph, RefusesPlacementsThatDoNotMakeOneMesh) {
  const std::string sizes = "m: the placements on A and B must be #V x 3 each and the triangles #F x 3";
  EXPECT_EQ(errorOf([&] { VertexMorph({0, 0, 0}, {0, 0, 0, 1, 1, 1}, {}, "m"); }), sizes);
  EXPECT_EQ(errorOf([&] { VertexMorph({0, 0}, {0, 0}, {}, "m"); }), sizes);
  EXPECT_EQ(errorOf([&] { VertexMorph({0, 0, 0}, {0, 0, 0}, {0, 0, 1}, "m"); }), "m: a triangle names vertex 1 of 1");
  const VertexMorph one({0, 0, 0}, {2, 4, 6}, {0, 0, 0}, "m");
  EXPECT_EQ(one.at(0.5).positions, (std::vector<float>{1, 2, 3}));
  EXPECT_EQ(errorOf([&] { (void)one.at(std::nan("")); }), "m: t nan is not a finite number");
}

TEST(SliceMorph, CostIsSlicesTimesTrianglesAndSamples) {
  const TriMesh a = testing::uvSphere(), b = testing::closedBox(0, 0, 0, 1, 1, 1);
  const double triangles = static_cast<double>(a.triangleCount() + b.triangleCount());
  EXPECT_DOUBLE_EQ(sliceMorphCost(a, b, {.axis = 1, .slices = 10, .samples = 64}), 10 * (triangles + 128));
  EXPECT_DOUBLE_EQ(sliceMorphCost(a, b, {.axis = 1, .slices = 20, .samples = 64}),
                   2 * sliceMorphCost(a, b, {.axis = 1, .slices = 10, .samples = 64}));
}

}  // namespace
}  // namespace vdg::morph
