// Self-intersections (vdg/geom/self_intersection.h): Moller's pair test on known configurations,
// and the grid's pairs equal to every pair tested by brute force.
#include "vdg/geom/self_intersection.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "support/test_meshes.h"

namespace vdg {
namespace {

using Eigen::Vector3d;
constexpr double kTol = 1e-9;

bool cross(const std::array<Vector3d, 3>& a, const std::array<Vector3d, 3>& b, double tol = kTol) {
  const bool ab = trianglesIntersect(a[0], a[1], a[2], b[0], b[1], b[2], tol);
  const bool ba = trianglesIntersect(b[0], b[1], b[2], a[0], a[1], a[2], tol);
  EXPECT_EQ(ab, ba) << "symmetric";
  return ab;
}

TEST(TrianglesIntersect, KnownConfigurations) {
  const std::array<Vector3d, 3> flat{Vector3d(-1, 0, -1), Vector3d(1, 0, -1), Vector3d(0, 0, 1)};
  // A vertical triangle piercing the flat one.
  EXPECT_TRUE(cross(flat, {Vector3d(0, -1, 0), Vector3d(0, 1, 0.2), Vector3d(0.1, 1, -0.2)}));
  // The same lifted above it, and beside it.
  EXPECT_FALSE(cross(flat, {Vector3d(0, 0.5, 0), Vector3d(0, 1.5, 0.2), Vector3d(0.1, 1.5, -0.2)}));
  EXPECT_FALSE(cross(flat, {Vector3d(3, -1, 0), Vector3d(3, 1, 0.2), Vector3d(3.1, 1, -0.2)}));
  // Crossing the plane outside the flat triangle.
  EXPECT_FALSE(cross(flat, {Vector3d(0, -1, 2), Vector3d(0, 1, 2.2), Vector3d(0.1, 1, 1.8)}));
  // Resting on it with one corner (touching, no overlap): not an intersection.
  EXPECT_FALSE(cross(flat, {Vector3d(0, 0, 0), Vector3d(0, 1, 0.2), Vector3d(0.1, 1, -0.2)}));
  // ... nor an edge lying in its plane across it.
  EXPECT_FALSE(cross(flat, {Vector3d(-0.2, 0, 0), Vector3d(0.2, 0, 0), Vector3d(0, 1, 0)}));
  // Coplanar: overlapping, and apart.
  EXPECT_TRUE(cross(flat, {Vector3d(0, 0, 0), Vector3d(2, 0, 0), Vector3d(0, 0, 2)}));
  EXPECT_TRUE(cross(flat, {Vector3d(-0.1, 0, 0), Vector3d(0.1, 0, 0), Vector3d(0, 0, 0.1)})) << "inside";
  EXPECT_FALSE(cross(flat, {Vector3d(5, 0, 0), Vector3d(6, 0, 0), Vector3d(5, 0, 1)}));
  // Degenerate triangles never intersect.
  EXPECT_FALSE(cross(flat, {Vector3d(0, -1, 0), Vector3d(0, 1, 0), Vector3d(0, 1, 0)}));
  // The tolerance: a piercing shallower than it does not count.
  const std::array<Vector3d, 3> shallow{Vector3d(0, -1e-4, 0), Vector3d(0, 1, 0.2), Vector3d(0.1, 1, -0.2)};
  EXPECT_TRUE(cross(flat, shallow, 1e-6));
  EXPECT_FALSE(cross(flat, shallow, 1e-3));
}

TEST(SelfIntersections, ClosedMeshesHaveNone) {
  EXPECT_TRUE(selfIntersections({}, {}, {}).empty()) << "no triangles";
  const std::vector<float> one{0, 0, 0, 1, 0, 0, 0, 1, 0};
  EXPECT_TRUE(selfIntersections(one, std::vector<std::int32_t>{0, 1, 2}, {}).empty()) << "one triangle";
  for (const TriMesh& m : {testing::closedBox(0, 0, 0, 1, 2, 3), testing::uvSphere(16, 24), testing::torus()})
    EXPECT_TRUE(selfIntersections(m.positions, m.triangles, weldByPosition(m.positions)).empty());
}

// Two boxes, the second pushed into the first: every pair found joins the two boxes.
TEST(SelfIntersections, InterpenetratingBoxes) {
  TriMesh a = testing::closedBox(0, 0, 0, 1, 1, 1);
  const TriMesh b = testing::closedBox(0.5f, 0.3f, 0.3f, 1.5f, 0.7f, 0.7f);
  const auto offset = static_cast<std::int32_t>(a.vertexCount());
  a.positions.insert(a.positions.end(), b.positions.begin(), b.positions.end());
  for (std::int32_t v : b.triangles) a.triangles.push_back(v + offset);
  const auto pairs = selfIntersections(a.positions, a.triangles, weldByPosition(a.positions));
  ASSERT_FALSE(pairs.empty());
  for (const auto& [i, j] : pairs) {
    EXPECT_LT(i, 12);
    EXPECT_GE(j, 12);
  }
}

// A seam: the box's vertices duplicated per face share positions, not indices; welding by
// position keeps the neighbours from counting as intersecting.
TEST(SelfIntersections, SeamsAreWelded) {
  const TriMesh box = testing::closedBox(0, 0, 0, 1, 1, 1);
  TriMesh split;
  for (std::int32_t v : box.triangles) {
    for (int c = 0; c < 3; ++c) split.positions.push_back(box.positions[3 * v + c]);
    split.triangles.push_back(static_cast<std::int32_t>(split.triangles.size()));
  }
  EXPECT_TRUE(selfIntersections(split.positions, split.triangles, weldByPosition(split.positions)).empty());
  const auto weld = weldByPosition(split.positions);
  for (std::size_t v = 0; v < weld.size(); ++v) {
    const auto w = static_cast<std::size_t>(weld[v]);
    for (int c = 0; c < 3; ++c) EXPECT_EQ(split.positions[3 * w + c], split.positions[3 * v + c]);
  }
}

// The grid finds exactly the pairs that testing all pairs finds: a sphere with jittered vertices.
TEST(SelfIntersections, GridEqualsBruteForce) {
  TriMesh m = testing::uvSphere(12, 16);
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> jitter(-0.35f, 0.35f);
  for (float& p : m.positions) p += jitter(rng);
  const auto weld = weldByPosition(m.positions);
  const auto pairs = selfIntersections(m.positions, m.triangles, weld, kTol);
  std::vector<std::pair<std::int32_t, std::int32_t>> brute;
  auto at = [&](std::size_t f, int k) {
    const auto v = static_cast<std::size_t>(m.triangles[3 * f + k]);
    return Vector3d(m.positions[3 * v], m.positions[3 * v + 1], m.positions[3 * v + 2]);
  };
  const std::size_t n = m.triangleCount();
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j) {
      bool shared = false;
      for (int s = 0; s < 3; ++s)
        for (int t = 0; t < 3; ++t) shared |= weld[m.triangles[3 * i + s]] == weld[m.triangles[3 * j + t]];
      if (!shared && trianglesIntersect(at(i, 0), at(i, 1), at(i, 2), at(j, 0), at(j, 1), at(j, 2), kTol))
        brute.emplace_back(static_cast<std::int32_t>(i), static_cast<std::int32_t>(j));
    }
  EXPECT_GT(brute.size(), 10u) << "the jitter folds the sphere";
  EXPECT_EQ(pairs, brute);
}

}  // namespace
}  // namespace vdg
