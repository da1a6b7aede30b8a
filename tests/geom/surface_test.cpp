// SurfaceTopology (surface.h): welding, welded edges, smoothing groups, render vertices and the
// per-frame normals, on meshes split the way exporters split them.
#include "vdg/geom/surface.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <set>
#include <vector>

#include "support/allocation_counter.h"
#include "support/error_of.h"
#include "support/test_meshes.h"
#include "vdg/geom/error.h"

namespace vdg {
namespace {

using testing::errorOf;

constexpr float kNormalTol = 1e-5f;  // unit normals computed in float

std::array<float, 3> at(std::span<const float> a, std::size_t i) { return {a[i * 3], a[i * 3 + 1], a[i * 3 + 2]}; }

float dot(const std::array<float, 3>& a, const std::array<float, 3>& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

// A quad split into two triangles whose shared edge has duplicated
// vertices (a seam): 6 vertices, 2 at each end of the diagonal.
TriMesh seamQuad() {
  TriMesh m;
  m.positions = {0, 0, 0, 1, 0, 0, 1, 1, 0, /* second triangle: */ 0, 0, 0, 1, 1, 0, 0, 1, 0};
  m.triangles = {0, 1, 2, 3, 4, 5};
  return m;
}

TEST(Surface, SeamDuplicatesWeldAndTheSeamIsNotABorder) {
  const TriMesh m = seamQuad();
  const SurfaceTopology unwelded = SurfaceTopology::unwelded(m.triangles, m.vertexCount());
  EXPECT_EQ(unwelded.borderEdgeCount(), 6u);  // in the index buffer, two separate triangles
  EXPECT_FALSE(unwelded.isWelded());
  const SurfaceTopology t = SurfaceTopology::build(m);
  EXPECT_TRUE(t.isWelded());
  EXPECT_EQ(t.weldedVertexCount(), 4u);
  EXPECT_EQ(t.weld()[3], 0);
  EXPECT_EQ(t.weld()[4], 2);
  EXPECT_EQ(t.edgeCount(), 5u);
  EXPECT_EQ(t.borderEdgeCount(), 4u);  // the square's outline only
  for (std::size_t e = 0; e < t.edgeCount(); ++e) {
    const bool diagonal = t.edgeVertices()[e * 2] == 0 && t.edgeVertices()[e * 2 + 1] == 2;
    EXPECT_EQ(t.edgeFaces()[e * 2 + 1] >= 0, diagonal) << "edge " << e;
  }
  // No file normals: one smooth group per surface point.
  EXPECT_EQ(t.groupCount(), 4u);
  EXPECT_EQ(t.cornerGroups()[0], t.cornerGroups()[3]);
}

TEST(Surface, WeldToleranceIsRelativeToTheModelSize) {
  for (const float scale : {1e-3f, 1.0f, 1e4f}) {
    TriMesh m = seamQuad();
    for (float& p : m.positions) p *= scale;
    m.positions[9] += 1e-8f * scale;  // round-off of a text format: still one point
    const SurfaceTopology t = SurfaceTopology::build(m);
    EXPECT_EQ(t.weldedVertexCount(), 4u) << "scale " << scale;
    m.positions[9] += 1e-3f * scale;  // a real gap: two points
    EXPECT_EQ(SurfaceTopology::build(m).weldedVertexCount(), 5u) << "scale " << scale;
  }
  SurfaceOptions exact;
  exact.weld_tolerance = 0.0;
  TriMesh m = seamQuad();
  EXPECT_EQ(SurfaceTopology::build(m, exact).weldedVertexCount(), 4u);
  m.positions[9] = std::nextafter(0.0f, 1.0f);
  EXPECT_EQ(SurfaceTopology::build(m, exact).weldedVertexCount(), 5u);
}

TEST(Surface, WeldingPicksTheLowestIndexWhateverTheOrder) {
  // Many copies of few points, shuffled: every vertex maps to the lowest index at its point.
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> pick(0, 9);
  TriMesh m;
  std::vector<int> point;
  for (int i = 0; i < 300; ++i) {
    const int p = pick(rng);
    point.push_back(p);
    m.positions.insert(m.positions.end(), {static_cast<float>(p % 3), static_cast<float>(p / 3), 0.5f});
  }
  for (int i = 0; i + 2 < 300; i += 3) m.triangles.insert(m.triangles.end(), {i, i + 1, i + 2});
  const SurfaceTopology t = SurfaceTopology::build(m);
  for (std::size_t v = 0; v < point.size(); ++v) {
    const auto first = std::find(point.begin(), point.end(), point[v]) - point.begin();
    ASSERT_EQ(t.weld()[v], first) << "vertex " << v;
  }
}

TEST(Surface, SplitCubeKeepsItsHardEdges) {
  const TriMesh cube = testing::splitCube();
  const SurfaceTopology t = SurfaceTopology::build(cube);
  EXPECT_EQ(t.weldedVertexCount(), 8u);
  EXPECT_EQ(t.borderEdgeCount(), 0u);  // closed once welded
  EXPECT_EQ(t.edgeCount(), 18u);       // 12 cube edges + 6 face diagonals
  EXPECT_EQ(t.groupCount(), 24u);      // three faces, three normals, at each corner
  EXPECT_EQ(t.renderVertexCount(), 24u);
  std::vector<float> normals(cube.positions.size());
  ASSERT_TRUE(computeVertexNormals(t, cube.positions, normals));
  for (std::size_t v = 0; v < cube.vertexCount(); ++v)
    EXPECT_GT(dot(at(normals, v), at(cube.normals, v)), 1.0f - kNormalTol) << "vertex " << v;
  std::vector<float> group(t.groupCount() * 3);
  ASSERT_TRUE(computeGroupNormals(t, cube.positions, group));
  for (std::size_t r = 0; r < t.renderVertexCount(); ++r)
    EXPECT_GT(dot(at(group, static_cast<std::size_t>(t.renderGroup()[r])),
                  at(cube.normals, static_cast<std::size_t>(t.renderSource()[r]))),
              1.0f - kNormalTol);
}

TEST(Surface, HardEdgesSurviveDeformation) {
  // A blend moves the cube's corners; the recomputed normals stay one per face (flat faces stay
  // flat when a whole face moves rigidly: push the +X face out).
  TriMesh cube = testing::splitCube();
  const SurfaceTopology t = SurfaceTopology::build(cube);
  for (std::size_t v = 0; v < 4; ++v) cube.positions[v * 3] += 0.5f;  // face 0 is +X
  std::vector<float> normals(cube.positions.size());
  ASSERT_TRUE(computeVertexNormals(t, cube.positions, normals));
  for (std::size_t v = 0; v < 4; ++v) EXPECT_GT(normals[v * 3], 1.0f - kNormalTol) << "vertex " << v;
  // The neighbouring faces were stretched but stay planar: their normals are unchanged.
  for (std::size_t v = 8; v < 12; ++v) EXPECT_GT(dot(at(normals, v), at(cube.normals, v)), 1.0f - kNormalTol);
}

TEST(Surface, ObjStyleHardEdgesWithSharedVerticesLiveInTheCornerGroups) {
  // An OBJ cube: 8 `v`, 6 `vn`, each face's corners pointing at its face normal.
  const TriMesh split = testing::splitCube();
  TriMesh cube;
  const SurfaceTopology w = SurfaceTopology::build(split);
  std::vector<int> index(split.vertexCount());
  for (std::size_t v = 0; v < split.vertexCount(); ++v) {
    if (w.weld()[v] == static_cast<std::int32_t>(v)) {
      index[v] = static_cast<int>(cube.vertexCount());
      cube.positions.insert(cube.positions.end(), split.positions.begin() + v * 3, split.positions.begin() + v * 3 + 3);
    } else {
      index[v] = index[static_cast<std::size_t>(w.weld()[v])];
    }
  }
  for (int f = 0; f < 6; ++f)
    cube.normals.insert(cube.normals.end(), split.normals.begin() + f * 12, split.normals.begin() + f * 12 + 3);
  for (std::size_t c = 0; c < split.triangles.size(); ++c) {
    cube.triangles.push_back(index[static_cast<std::size_t>(split.triangles[c])]);
    cube.normal_triangles.push_back(static_cast<std::int32_t>(c / 6));
  }
  const SurfaceTopology t = SurfaceTopology::build(cube);
  EXPECT_FALSE(t.isWelded());
  EXPECT_EQ(t.groupCount(), 24u);
  EXPECT_EQ(t.renderVertexCount(), 24u);
  std::vector<float> group(t.groupCount() * 3);
  ASSERT_TRUE(computeGroupNormals(t, cube.positions, group));
  for (std::size_t c = 0; c < cube.triangles.size(); ++c)
    EXPECT_GT(dot(at(group, static_cast<std::size_t>(t.cornerGroups()[c])),
                  at(cube.normals, static_cast<std::size_t>(cube.normal_triangles[c]))),
              1.0f - kNormalTol)
        << "corner " << c;
}

TEST(Surface, UvSeamShadesSmoothly) {
  const TriMesh sphere = testing::uvSphere(10, 16);
  const TriMesh seam = testing::seamSphere(10, 16);
  ASSERT_GT(seam.vertexCount(), sphere.vertexCount());
  const SurfaceTopology t = SurfaceTopology::build(seam);
  EXPECT_EQ(t.weldedVertexCount(), sphere.vertexCount());
  EXPECT_EQ(t.borderEdgeCount(), 0u);
  EXPECT_EQ(t.groupCount(), sphere.vertexCount());
  EXPECT_GT(t.renderVertexCount(), t.groupCount());  // the seam copies carry their own uvs
  std::vector<float> expected(sphere.positions.size()), normals(seam.positions.size());
  ASSERT_TRUE(computeVertexNormals(sphere.positions, sphere.triangles, expected));
  ASSERT_TRUE(computeVertexNormals(t, seam.positions, normals));
  for (std::size_t v = 0; v < seam.vertexCount(); ++v) {
    const auto original = static_cast<std::size_t>(t.weld()[v]);
    EXPECT_GT(dot(at(normals, v), at(expected, original)), 1.0f - kNormalTol) << "vertex " << v;
  }
  // The index-buffer normals would differ across the seam.
  std::vector<float> split(seam.positions.size());
  ASSERT_TRUE(computeVertexNormals(seam.positions, seam.triangles, split));
  float worst = 1.0f;
  for (std::size_t v = sphere.vertexCount(); v < seam.vertexCount(); ++v)
    worst = std::min(worst, dot(at(split, v), at(split, static_cast<std::size_t>(t.weld()[v]))));
  EXPECT_LT(worst, 0.99f);
}

TEST(Surface, RealHolesStayBorders) {
  TriMesh m = testing::uvSphere(8, 12);
  m.triangles.resize(m.triangles.size() - 12 * 3);  // remove the south cap
  const SurfaceTopology t = SurfaceTopology::build(m);
  EXPECT_EQ(t.borderEdgeCount(), 12u);
}

TEST(Surface, NearbyFileNormalsCountAsOne) {
  TriMesh m = seamQuad();
  m.normals = {0, 0, 1, 0, std::sin(0.5f * 3.14159265f / 180.0f), std::cos(0.5f * 3.14159265f / 180.0f)};
  m.normal_triangles = {0, 0, 0, 1, 1, 1};
  EXPECT_EQ(SurfaceTopology::build(m).groupCount(), 4u);  // 0.5 degrees apart: smooth
  SurfaceOptions strict;
  strict.hard_angle_deg = 0.1;
  EXPECT_EQ(SurfaceTopology::build(m, strict).groupCount(), 6u);
}

TEST(Surface, PerFrameCallsKeepTheContract) {
  const TriMesh cube = testing::splitCube();
  const SurfaceTopology t = SurfaceTopology::build(cube);
  constexpr float kSentinel = -7.5f;
  std::vector<float> wrong(cube.positions.size() + 3, kSentinel);
  EXPECT_FALSE(computeVertexNormals(t, cube.positions, wrong));
  EXPECT_FALSE(computeGroupNormals(t, cube.positions, wrong));
  std::vector<float> normals(cube.positions.size(), kSentinel);
  EXPECT_FALSE(computeVertexNormals(t, std::span<const float>(cube.positions).first(9), normals));
  for (const float x : normals) ASSERT_EQ(x, kSentinel);
  for (const float x : wrong) ASSERT_EQ(x, kSentinel);
  std::vector<float> group(t.groupCount() * 3);
  bool ok = false;
  EXPECT_EQ(testing::allocationsDuring([&] {
              ok = computeGroupNormals(t, cube.positions, group) && computeVertexNormals(t, cube.positions, normals);
            }),
            0);
  EXPECT_TRUE(ok);
}

TEST(Surface, BadInputIsAClearError) {
  TriMesh m = seamQuad();
  m.normals = {0, 0, 1};
  m.normal_triangles = {0, 0, 0, 0, 0, 5};
  EXPECT_EQ(errorOf([&] { (void)SurfaceTopology::build(m); }),
            "surface: triangle 1 refers to normal 5, but the mesh has 1");
  SurfaceOptions bad;
  bad.weld_tolerance = -1;
  EXPECT_EQ(errorOf([&] { (void)SurfaceTopology::build(seamQuad(), bad); }),
            "surface: weld tolerance must be a finite number >= 0");
  const std::vector<std::int32_t> tris = {0, 1, 3};
  EXPECT_EQ(errorOf([&] { (void)SurfaceTopology::unwelded(tris, 3); }),
            "surface: triangle 0 refers to vertex 3, but the mesh has 3 vertices");
}

TEST(Surface, UnweldedRenderVerticesAreTheVertices) {
  const TriMesh m = testing::uvSphere(5, 7);
  const SurfaceTopology t = SurfaceTopology::unwelded(m.triangles, m.vertexCount());
  ASSERT_EQ(t.renderVertexCount(), m.vertexCount());
  for (std::size_t v = 0; v < m.vertexCount(); ++v) EXPECT_EQ(t.renderSource()[v], static_cast<std::int32_t>(v));
  EXPECT_TRUE(std::equal(t.renderTriangles().begin(), t.renderTriangles().end(), m.triangles.begin()));
  std::vector<float> a(m.positions.size()), b(m.positions.size());
  ASSERT_TRUE(computeVertexNormals(m.positions, m.triangles, a));
  ASSERT_TRUE(computeVertexNormals(t, m.positions, b));
  for (std::size_t i = 0; i < a.size(); ++i) EXPECT_NEAR(a[i], b[i], kNormalTol);
}

}  // namespace
}  // namespace vdg
