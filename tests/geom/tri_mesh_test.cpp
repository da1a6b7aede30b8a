#include "vdg/geom/tri_mesh.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "support/test_meshes.h"
#include "vdg/geom/error.h"

namespace vdg {
namespace {

constexpr float kNormalTol = 1e-5f;
// On a UV sphere of 64 rings x 96 segments, the area-weighted vertex normal must equal the radial
// direction (the exact normal of the sphere) to within this distance. The worst vertices are on
// the rings next to the poles, where the fan triangles and the quad triangles around a vertex
// differ in shape (measured 8.2e-3); a normal from the wrong triangles or left unnormalised is
// off by 0.05 or more.
constexpr double kSphereNormalTol = 1.5e-2;
// Halving the edge length must at least shrink that worst error by this factor (it is O(h)).
constexpr double kSphereRefinementGain = 1.6;

float length3(const std::vector<float>& n, std::size_t v) {
  return std::sqrt(n[3 * v] * n[3 * v] + n[3 * v + 1] * n[3 * v + 1] + n[3 * v + 2] * n[3 * v + 2]);
}

// Largest distance between a vertex normal and the exact (radial) normal of the unit sphere.
double worstRadialError(int rings, int segments) {
  const TriMesh m = testing::uvSphere(rings, segments);
  std::vector<float> n(m.positions.size());
  EXPECT_TRUE(computeVertexNormals(m.positions, m.triangles, n));
  double worst = 0.0;
  for (std::size_t v = 0; v < m.vertexCount(); ++v) {
    const double px = m.positions[3 * v], py = m.positions[3 * v + 1], pz = m.positions[3 * v + 2];
    const double r = std::sqrt(px * px + py * py + pz * pz);
    const double dx = n[3 * v] - px / r, dy = n[3 * v + 1] - py / r, dz = n[3 * v + 2] - pz / r;
    worst = std::max(worst, std::sqrt(dx * dx + dy * dy + dz * dz));
  }
  return worst;
}

TEST(TriMesh, NormalsOfAFineSphereAreRadial) {
  const double coarse = worstRadialError(64, 96);
  EXPECT_LT(coarse, kSphereNormalTol);
  EXPECT_LT(kSphereRefinementGain * worstRadialError(128, 192), coarse);
}

TEST(TriMesh, NormalsOfATetrahedronCornerByHand) {
  // The corner (0,0,0) of the tetrahedron (0,0,0) (1,0,0) (0,2,0) (0,0,3), seen from outside,
  // touches three faces lying in the coordinate planes. Cross products by hand, edges from the
  // first corner of each counter-clockwise triangle:
  //   face z = 0: (0,0,0) (0,2,0) (1,0,0): (0,2,0) x (1,0,0) = (0, 0, -2)   (area 1)
  //   face y = 0: (0,0,0) (1,0,0) (0,0,3): (1,0,0) x (0,0,3) = (0, -3, 0)   (area 1.5)
  //   face x = 0: (0,0,0) (0,0,3) (0,2,0): (0,0,3) x (0,2,0) = (-6, 0, 0)   (area 3)
  // Sum (-6, -3, -2), length 7: the normal at the corner is (-6, -3, -2) / 7.
  // The slanted face (1,0,0) (0,2,0) (0,0,3): (-1,2,0) x (-1,0,3) = (6, 3, 2), also length 7;
  // vertex (1,0,0) gets (0,0,-2) + (0,-3,0) + (6,3,2) = (6, 0, 0): normal (1, 0, 0).
  const std::vector<float> positions = {0, 0, 0, 1, 0, 0, 0, 2, 0, 0, 0, 3};
  const std::vector<std::int32_t> triangles = {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3};
  std::vector<float> n(positions.size());
  ASSERT_TRUE(computeVertexNormals(positions, triangles, n));
  const float expected_corner[3] = {-6.0f / 7, -3.0f / 7, -2.0f / 7};
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(n[c], expected_corner[c], kNormalTol) << c;
  EXPECT_NEAR(n[3], 1.0f, kNormalTol);
  EXPECT_NEAR(n[4], 0.0f, kNormalTol);
  EXPECT_NEAR(n[5], 0.0f, kNormalTol);
  for (std::size_t v = 0; v < 4; ++v) EXPECT_NEAR(length3(n, v), 1.0f, kNormalTol) << v;
}

TEST(TriMesh, NormalsAreAreaWeighted) {
  // Vertex 0 is shared by a big triangle in the z = 0 plane and a small one in the x = 0 plane.
  TriMesh m;
  m.positions = {0, 0, 0, 4, 0, 0, 0, 4, 0, 0, 0, -1, 0, 1, 0};
  m.triangles = {0, 1, 2, 0, 3, 4};
  std::vector<float> n(m.positions.size());
  ASSERT_TRUE(computeVertexNormals(m.positions, m.triangles, n));
  // Areas 8 and 0.5: normal proportional to 16*(0,0,1) + 1*(1,0,0).
  const float len = std::sqrt(16.0f * 16.0f + 1.0f);
  EXPECT_NEAR(n[0], 1.0f / len, kNormalTol);
  EXPECT_NEAR(n[2], 16.0f / len, kNormalTol);
}

TEST(TriMesh, DegenerateTrianglesGiveZeroNormalNotNan) {
  TriMesh m;
  m.positions = {0, 0, 0, 1, 0, 0, 2, 0, 0};
  m.triangles = {0, 1, 2};
  std::vector<float> n(9, 7.0f);
  ASSERT_TRUE(computeVertexNormals(m.positions, m.triangles, n));
  for (float x : n) EXPECT_EQ(x, 0.0f);
}

TEST(TriMesh, Bounds) {
  const TriMesh m = testing::uvSphere();
  const Bounds b = computeBounds(m.positions);
  EXPECT_NEAR(b.max[1], 1.0f, 1e-6f);
  EXPECT_NEAR(b.min[1], -1.0f, 1e-6f);
  EXPECT_NEAR(b.center()[1], 0.0f, 1e-6f);
}

TEST(TriMesh, ValidateNamesTheProblem) {
  TriMesh m = testing::uvSphere();
  EXPECT_NO_THROW(validateMesh(m, "m.obj"));
  TriMesh bad_index = m;
  bad_index.triangles[5] = 9999;
  EXPECT_THROW(
      {
        try {
          validateMesh(bad_index, "m.obj");
        } catch (const Error& e) {
          EXPECT_NE(std::string(e.what()).find("m.obj: triangle 1 refers to vertex 9999"), std::string::npos)
              << e.what();
          throw;
        }
      },
      Error);
  TriMesh nan = m;
  nan.positions[3 * 7 + 1] = std::nanf("");
  try {
    validateMesh(nan, "m.obj");
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("vertex 7 has a non-finite coordinate"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace vdg
