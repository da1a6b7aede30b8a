#include "vdg/geom/tri_mesh.h"

#include <gtest/gtest.h>

#include <cmath>

#include "support/test_meshes.h"
#include "vdg/geom/error.h"

namespace vdg {
namespace {

constexpr float kNormalTol = 1e-5f;

TEST(TriMesh, NormalsOfSphereAreUnitAndPointOutwards) {
  const TriMesh m = testing::uvSphere(16, 24);
  std::vector<float> n(m.positions.size());
  computeVertexNormals(m.positions, m.triangles, n);
  for (std::size_t v = 0; v < m.vertexCount(); ++v) {
    const float len = std::sqrt(n[3 * v] * n[3 * v] + n[3 * v + 1] * n[3 * v + 1] + n[3 * v + 2] * n[3 * v + 2]);
    EXPECT_NEAR(len, 1.0f, kNormalTol);
    const float dot =
        n[3 * v] * m.positions[3 * v] + n[3 * v + 1] * m.positions[3 * v + 1] + n[3 * v + 2] * m.positions[3 * v + 2];
    EXPECT_GT(dot, 0.95f) << "vertex " << v;
  }
}

TEST(TriMesh, NormalsAreAreaWeighted) {
  // Vertex 0 is shared by a big triangle in the z = 0 plane and a small one in the x = 0 plane.
  TriMesh m;
  m.positions = {0, 0, 0, 4, 0, 0, 0, 4, 0, 0, 0, -1, 0, 1, 0};
  m.triangles = {0, 1, 2, 0, 3, 4};
  std::vector<float> n(m.positions.size());
  computeVertexNormals(m.positions, m.triangles, n);
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
  computeVertexNormals(m.positions, m.triangles, n);
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
