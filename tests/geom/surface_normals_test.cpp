// The per-frame normals of SurfaceTopology (surface.h) are a parallel gather over precomputed
// lists; here they are checked against a naive scalar scatter written in this file (each triangle
// adds its normal to the slots of its corners, in triangle order, then every slot is normalised),
// on small meshes that run inline and on meshes large enough to run threaded, with welded seams,
// hard edges, degenerate triangles and random poses.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <numeric>
#include <random>
#include <string>
#include <tuple>
#include <vector>

#include "support/allocation_counter.h"
#include "support/test_meshes.h"
#include "vdg/geom/surface.h"

namespace vdg {
namespace {

// The gather adds each slot's triangles in the order the scatter does, so the two agree to float
// round-off of the final normalisation at most; any larger difference is a wrong list.
constexpr float kGatherVsScatterTol = 1e-6f;

// The oracle: the scatter the library used before the gather.
std::vector<float> scatterNormals(const SurfaceTopology& t, std::span<const float> positions, bool groups) {
  const auto tris = t.triangles();
  const std::size_t slots = groups ? t.groupCount() : t.vertexCount();
  std::vector<float> out(slots * 3, 0.0f);
  for (std::size_t f = 0; f < tris.size(); f += 3) {
    const float* a = &positions[static_cast<std::size_t>(tris[f]) * 3];
    const float* b = &positions[static_cast<std::size_t>(tris[f + 1]) * 3];
    const float* c = &positions[static_cast<std::size_t>(tris[f + 2]) * 3];
    const float e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    const float e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    const float n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
    for (std::size_t k = 0; k < 3; ++k) {
      const std::size_t corner = f + k;
      const std::size_t slot = groups
                                   ? static_cast<std::size_t>(t.cornerGroups()[corner])
                                   : static_cast<std::size_t>(t.vertexHome()[static_cast<std::size_t>(tris[corner])]);
      for (int i = 0; i < 3; ++i) out[slot * 3 + static_cast<std::size_t>(i)] += n[i];
    }
  }
  for (std::size_t s = 0; s < slots; ++s) {
    float* n = &out[s * 3];
    const float len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (len > 0.0f) {
      for (int i = 0; i < 3; ++i) n[i] *= 1.0f / len;
    }
  }
  if (!groups) {
    for (std::size_t v = 0; v < t.vertexCount(); ++v)
      for (int i = 0; i < 3; ++i)
        out[v * 3 + static_cast<std::size_t>(i)] =
            out[static_cast<std::size_t>(t.vertexHome()[v]) * 3 + static_cast<std::size_t>(i)];
  }
  return out;
}

void expectNear(const std::vector<float>& expected, std::span<const float> actual, const std::string& what) {
  ASSERT_EQ(expected.size(), actual.size()) << what;
  for (std::size_t i = 0; i < expected.size(); ++i)
    ASSERT_NEAR(expected[i], actual[i], kGatherVsScatterTol) << what << ": element " << i << " (slot " << i / 3 << ")";
}

void expectMatchesOracle(const TriMesh& mesh, std::span<const float> pose, const std::string& what) {
  const SurfaceTopology t = SurfaceTopology::build(mesh);
  std::vector<float> normals(pose.size()), group(t.groupCount() * 3);
  ASSERT_TRUE(computeVertexNormals(t, pose, normals)) << what;
  expectNear(scatterNormals(t, pose, false), normals, what + ", vertex normals");
  ASSERT_TRUE(computeGroupNormals(t, pose, group)) << what;
  expectNear(scatterNormals(t, pose, true), group, what + ", group normals");
}

// A random soup over few distinct points (so welding merges many vertices), with degenerate
// triangles (repeated indices), some random file normals (hard edges) and a random pose.
TriMesh randomMesh(std::mt19937& rng, std::size_t vertices, std::size_t triangles) {
  std::uniform_real_distribution<float> coord(-1.0f, 1.0f);
  std::uniform_int_distribution<std::size_t> pick(0, vertices - 1);
  TriMesh m;
  const std::size_t points = std::max<std::size_t>(3, vertices * 2 / 3);
  std::vector<float> point(points * 3);
  for (float& x : point) x = coord(rng);
  for (std::size_t v = 0; v < vertices; ++v) {
    const std::size_t p = v < points ? v : pick(rng) % points;  // the rest duplicate a point
    m.positions.insert(m.positions.end(), point.begin() + static_cast<long>(p * 3),
                       point.begin() + static_cast<long>(p * 3 + 3));
  }
  for (std::size_t f = 0; f < triangles; ++f)
    for (int c = 0; c < 3; ++c) m.triangles.push_back(static_cast<std::int32_t>(pick(rng)));
  if (rng() % 2 == 0) {
    for (int n = 0; n < 4; ++n) m.normals.insert(m.normals.end(), {coord(rng), coord(rng), 1.0f});
    for (std::size_t c = 0; c < m.triangles.size(); ++c)
      m.normal_triangles.push_back(static_cast<std::int32_t>(rng() % 4));
  }
  return m;
}

std::vector<float> jitter(std::mt19937& rng, std::vector<float> positions, float amount) {
  std::uniform_real_distribution<float> d(-amount, amount);
  for (float& x : positions) x += d(rng);
  return positions;
}

TEST(SurfaceNormals, GatherEqualsScatterOnSmallMeshes) {
  expectMatchesOracle(testing::splitCube(), testing::splitCube().positions, "split cube");
  const TriMesh seam = testing::seamSphere(10, 16);
  std::mt19937 rng(7);
  expectMatchesOracle(seam, seam.positions, "seam sphere");
  expectMatchesOracle(seam, jitter(rng, seam.positions, 0.1f), "seam sphere, moved seam apart");
  for (int i = 0; i < 200; ++i) {
    const TriMesh m = randomMesh(rng, 3 + rng() % 60, 1 + rng() % 120);
    expectMatchesOracle(m, jitter(rng, m.positions, 0.5f), "random mesh " + std::to_string(i));
  }
}

TEST(SurfaceNormals, ThreadedGatherEqualsScatter) {
  // Past 2 x kParallelNormalSlots slots the gather runs on TBB's threads.
  const TriMesh sphere = testing::seamSphere(300, 240);
  ASSERT_GT(sphere.vertexCount(), 4 * kParallelNormalSlots);
  std::mt19937 rng(11);
  expectMatchesOracle(sphere, jitter(rng, sphere.positions, 0.01f), "threaded seam sphere");
  const TriMesh soup = randomMesh(rng, 5 * kParallelNormalSlots, 8 * kParallelNormalSlots);
  expectMatchesOracle(soup, jitter(rng, soup.positions, 0.2f), "threaded random soup");
}

// The fast path (4-float cross products, a ring of face normals, a vectorised normalisation;
// surface.cpp, gatherSlots) does the scalar oracle's float operations in the same order, so it
// must agree bit for bit, not just within kGatherVsScatterTol.
void expectBitIdentical(const TriMesh& mesh, std::span<const float> pose, const std::string& what) {
  const SurfaceTopology t = SurfaceTopology::build(mesh);
  std::vector<float> normals(pose.size()), group(t.groupCount() * 3);
  ASSERT_TRUE(computeVertexNormals(t, pose, normals)) << what;
  ASSERT_TRUE(computeGroupNormals(t, pose, group)) << what;
  const auto same = [&](const std::vector<float>& expected, std::span<const float> actual, const char* kind) {
    ASSERT_EQ(expected.size(), actual.size()) << what;
    for (std::size_t i = 0; i < expected.size(); ++i)
      ASSERT_EQ(std::bit_cast<std::uint32_t>(expected[i]), std::bit_cast<std::uint32_t>(actual[i]))
          << what << ", " << kind << ": element " << i << " (" << expected[i] << " vs " << actual[i] << ")";
  };
  same(scatterNormals(t, pose, false), normals, "vertex normals");
  same(scatterNormals(t, pose, true), group, "group normals");
}

// A grid of rows x cols vertices, two triangles per cell in row order (neighbouring vertices have
// neighbouring triangles, the fast path's case), with an unused (isolated) vertex after every
// `gap` vertices, a few collapsed triangles and, optionally, the triangles shuffled (no locality:
// the per-corner path).
TriMesh orderedGrid(std::mt19937& rng, int rows, int cols, int gap, bool shuffle) {
  TriMesh m;
  std::vector<std::int32_t> index(static_cast<std::size_t>(rows * cols));
  std::uniform_real_distribution<float> bump(-0.3f, 0.3f);
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c) {
      if ((m.vertexCount() + 1) % static_cast<std::size_t>(gap) == 0)
        m.positions.insert(m.positions.end(), {5.0f, 5.0f, 5.0f});
      index[static_cast<std::size_t>(r * cols + c)] = static_cast<std::int32_t>(m.vertexCount());
      m.positions.insert(m.positions.end(), {static_cast<float>(c), static_cast<float>(r), bump(rng)});
    }
  for (int r = 0; r + 1 < rows; ++r)
    for (int c = 0; c + 1 < cols; ++c) {
      const auto at = [&](int rr, int cc) { return index[static_cast<std::size_t>(rr * cols + cc)]; };
      m.triangles.insert(m.triangles.end(), {at(r, c), at(r + 1, c), at(r, c + 1)});
      if (rng() % 50 == 0) m.triangles.insert(m.triangles.end(), {at(r, c), at(r, c), at(r + 1, c + 1)});  // degenerate
      m.triangles.insert(m.triangles.end(), {at(r, c + 1), at(r + 1, c), at(r + 1, c + 1)});
    }
  if (shuffle) {
    std::vector<std::array<std::int32_t, 3>> tris(m.triangles.size() / 3);
    std::memcpy(tris.data(), m.triangles.data(), m.triangles.size() * sizeof(std::int32_t));
    std::shuffle(tris.begin(), tris.end(), rng);
    std::memcpy(m.triangles.data(), tris.data(), m.triangles.size() * sizeof(std::int32_t));
  }
  return m;
}

TEST(SurfaceNormals, FastPathIsBitIdenticalToTheScalarOracle) {
  std::mt19937 rng(23);
  // Seams (welded duplicates), hard edges, degenerate triangles, isolated vertices, small meshes.
  const TriMesh seam = testing::seamSphere(10, 16);
  expectBitIdentical(seam, jitter(rng, seam.positions, 0.1f), "seam sphere");
  expectBitIdentical(testing::splitCube(), testing::splitCube().positions, "split cube");
  for (int i = 0; i < 100; ++i) {
    const TriMesh m = randomMesh(rng, 3 + rng() % 60, 1 + rng() % 120);
    expectBitIdentical(m, jitter(rng, m.positions, 0.5f), "random mesh " + std::to_string(i));
  }
  // Ordered meshes (the ring of face normals over many blocks), narrow and wide rows (windows of a
  // few slots up to whole chunks), with and without locality; large ones run threaded.
  for (const auto& [rows, cols, gap, shuffle] :
       {std::tuple{30, 20, 7, false}, std::tuple{30, 20, 7, true}, std::tuple{200, 3000, 101, false},
        std::tuple{400, 600, 13, false}, std::tuple{100, 500, 1000, true}, std::tuple{1200, 5, 3, false}}) {
    const TriMesh grid = orderedGrid(rng, rows, cols, gap, shuffle);
    expectBitIdentical(grid, jitter(rng, grid.positions, 0.05f),
                       "grid " + std::to_string(rows) + " x " + std::to_string(cols) + (shuffle ? ", shuffled" : ""));
  }
  const TriMesh big = testing::seamSphere(300, 240);
  expectBitIdentical(big, jitter(rng, big.positions, 0.01f), "threaded seam sphere");
}

TEST(SurfaceNormals, CoincidingGroupAndHomeListsAreStoredOnce) {
  std::mt19937 rng(31);
  // No seams, no file normals: one group per vertex in vertex order, so the lists coincide.
  const TriMesh grid = orderedGrid(rng, 20, 30, 1000, false);
  const SurfaceTopology plain = SurfaceTopology::build(grid);
  EXPECT_TRUE(plain.groupListsAreHomeLists());
  EXPECT_EQ(plain.groupTriangles().data(), plain.homeTriangles().data());
  EXPECT_EQ(plain.groupTriangleOffsets().size(), plain.groupCount() + 1);
  // Welded seams: groups are per surface point, not per vertex, so the lists differ.
  const SurfaceTopology seam = SurfaceTopology::build(testing::seamSphere(10, 16));
  EXPECT_FALSE(seam.groupListsAreHomeLists());
  EXPECT_NE(seam.groupTriangles().data(), seam.homeTriangles().data());
  // Either way the group normals are the oracle's (shared or not).
  expectBitIdentical(grid, jitter(rng, grid.positions, 0.1f), "plain grid");
}

TEST(SurfaceNormals, GatherListsHoldEveryCornerOnce) {
  std::mt19937 rng(3);
  for (int i = 0; i < 50; ++i) {
    const TriMesh m = randomMesh(rng, 3 + rng() % 40, 1 + rng() % 80);
    const SurfaceTopology t = SurfaceTopology::build(m);
    ASSERT_EQ(t.homeTriangleOffsets().size(), t.vertexCount() + 1);
    ASSERT_EQ(t.groupTriangleOffsets().size(), t.groupCount() + 1);
    EXPECT_EQ(static_cast<std::size_t>(t.homeTriangleOffsets().back()), m.triangles.size());
    EXPECT_EQ(static_cast<std::size_t>(t.groupTriangleOffsets().back()), m.triangles.size());
    for (std::size_t v = 0; v < t.vertexCount(); ++v) {
      const auto begin = t.homeTriangleOffsets()[v], end = t.homeTriangleOffsets()[v + 1];
      if (t.vertexHome()[v] != static_cast<std::int32_t>(v)) {
        EXPECT_EQ(begin, end) << "vertex " << v;
      }
      EXPECT_TRUE(std::is_sorted(t.homeTriangles().begin() + begin, t.homeTriangles().begin() + end));
    }
    std::vector<std::int32_t> copied;
    for (std::size_t v = 0; v < t.vertexCount(); ++v)
      if (t.vertexHome()[v] != static_cast<std::int32_t>(v)) copied.push_back(static_cast<std::int32_t>(v));
    EXPECT_TRUE(std::equal(copied.begin(), copied.end(), t.copiedVertices().begin(), t.copiedVertices().end()));
  }
  // Topologies without triangles or vertices still have their offsets.
  const SurfaceTopology empty = SurfaceTopology::unwelded({}, 4);
  EXPECT_EQ(empty.homeTriangleOffsets().size(), 5u);
  std::vector<float> positions(12, 1.0f), normals(12, 9.0f);
  ASSERT_TRUE(computeVertexNormals(empty, positions, normals));
  for (const float x : normals) EXPECT_EQ(x, 0.0f);
}

TEST(SurfaceNormals, NormalsOfListedVerticesEqualTheFullComputation) {
  const TriMesh seam = testing::seamSphere(120, 100);  // more vertices than the threaded lists below
  const SurfaceTopology t = SurfaceTopology::build(seam);
  std::mt19937 rng(5);
  const std::vector<float> pose = jitter(rng, seam.positions, 0.05f);
  std::vector<float> full(pose.size());
  ASSERT_TRUE(computeVertexNormals(t, pose, full));
  // Random lists (the face cache's tags collide) and ascending ones (ModelEvaluator's: faces hit).
  for (const std::size_t count :
       {std::size_t{0}, std::size_t{1}, std::size_t{100}, 3 * kParallelListedNormals, 3 * kParallelListedNormals + 1}) {
    // Distinct vertices, in random order or ascending.
    std::vector<std::int32_t> list(seam.vertexCount());
    std::iota(list.begin(), list.end(), 0);
    std::shuffle(list.begin(), list.end(), rng);
    list.resize(count);
    if (count % 2 == 1) std::sort(list.begin(), list.end());
    constexpr float kUntouched = 42.0f;
    std::vector<float> some(pose.size(), kUntouched);
    ASSERT_TRUE(computeVertexNormalsOf(t, pose, list, some));
    std::vector<bool> listed(seam.vertexCount(), false);
    for (const std::int32_t v : list) listed[static_cast<std::size_t>(v)] = true;
    for (std::size_t v = 0; v < seam.vertexCount(); ++v)
      for (std::size_t i = 0; i < 3; ++i)
        ASSERT_EQ(some[v * 3 + i], listed[v] ? full[v * 3 + i] : kUntouched) << "vertex " << v << ", " << count;
  }
}

TEST(SurfaceNormals, ListedVerticesKeepTheContract) {
  const TriMesh cube = testing::splitCube();
  const SurfaceTopology t = SurfaceTopology::build(cube);
  constexpr float kSentinel = -7.5f;
  std::vector<float> normals(cube.positions.size(), kSentinel);
  const std::int32_t n = static_cast<std::int32_t>(cube.vertexCount());
  for (const std::vector<std::int32_t>& bad : std::vector<std::vector<std::int32_t>>{{0, n}, {-1}, {3, 2, n + 100}}) {
    EXPECT_FALSE(computeVertexNormalsOf(t, cube.positions, bad, normals));
    for (const float x : normals) ASSERT_EQ(x, kSentinel);
  }
  const std::vector<std::int32_t> good = {0, 1};
  std::vector<float> wrong(cube.positions.size() - 3, kSentinel);
  EXPECT_FALSE(computeVertexNormalsOf(t, cube.positions, good, wrong));
  EXPECT_FALSE(computeVertexNormalsOf(t, std::span<const float>(cube.positions).first(9), good, normals));
  for (const float x : wrong) ASSERT_EQ(x, kSentinel);
  for (const float x : normals) ASSERT_EQ(x, kSentinel);
}

TEST(SurfaceNormals, ThreadedNormalsAllocateNothingAfterAWarmUp) {
  // The first threaded call starts TBB's workers (their set-up may allocate); later calls do not.
  const TriMesh sphere = testing::seamSphere(300, 240);
  const SurfaceTopology t = SurfaceTopology::build(sphere);
  std::vector<float> normals(sphere.positions.size()), group(t.groupCount() * 3);
  std::vector<std::int32_t> list(3 * kParallelNormalSlots);
  for (std::size_t i = 0; i < list.size(); ++i) list[i] = static_cast<std::int32_t>(i);
  ASSERT_TRUE(computeVertexNormals(t, sphere.positions, normals));
  bool ok = true;
  EXPECT_EQ(testing::allocationsDuring([&] {
              for (int i = 0; i < 20; ++i) {
                ok = computeVertexNormals(t, sphere.positions, normals) && ok;
                ok = computeGroupNormals(t, sphere.positions, group) && ok;
                ok = computeVertexNormalsOf(t, sphere.positions, list, normals) && ok;
              }
            }),
            0);
  EXPECT_TRUE(ok);
}

}  // namespace
}  // namespace vdg
