// The per-frame contract of computeVertexNormals (tri_mesh.h): every invalid input returns false
// and leaves the normals untouched (filled with a sentinel first, compared afterwards).
#include <gtest/gtest.h>

#include <climits>
#include <cstdint>
#include <string>
#include <vector>

#include "support/test_meshes.h"
#include "vdg/geom/tri_mesh.h"

namespace vdg {
namespace {

constexpr float kSentinel = -12345.5f;

void expectRefused(std::span<const float> positions, std::span<const std::int32_t> triangles, std::size_t normals_size,
                   const std::string& what) {
  std::vector<float> normals(normals_size, kSentinel);
  EXPECT_FALSE(computeVertexNormals(positions, triangles, normals)) << what;
  for (std::size_t i = 0; i < normals.size(); ++i) ASSERT_EQ(normals[i], kSentinel) << what << ": element " << i;
}

TEST(GeomContract, NormalsRefuseWrongSizes) {
  const TriMesh m = testing::uvSphere(4, 6);
  const std::size_t n = m.positions.size();
  for (std::size_t size : {std::size_t{0}, std::size_t{1}, n - 3, n - 1, n + 1, n + 3, 2 * n})
    expectRefused(m.positions, m.triangles, size, "normals of size " + std::to_string(size));
  // Positions not a multiple of 3 (normals sized alike, so only that is wrong).
  const std::span<const float> ragged(m.positions.data(), n - 1);
  expectRefused(ragged, m.triangles, n - 1, "positions of size " + std::to_string(n - 1));
  // Triangles not a multiple of 3.
  for (std::size_t cut : {std::size_t{1}, std::size_t{2}}) {
    const std::span<const std::int32_t> partial(m.triangles.data(), m.triangles.size() - cut);
    expectRefused(m.positions, partial, n, "triangle array short by " + std::to_string(cut));
  }
}

TEST(GeomContract, NormalsRefuseIndicesOutOfRange) {
  const TriMesh m = testing::uvSphere(4, 6);
  const auto vertex_count = static_cast<std::int32_t>(m.vertexCount());
  for (std::size_t corner : {std::size_t{0}, std::size_t{4}, m.triangles.size() - 1}) {
    for (std::int32_t bad : {vertex_count, vertex_count + 1, -1, INT_MAX, INT_MIN}) {
      std::vector<std::int32_t> triangles = m.triangles;
      triangles[corner] = bad;
      expectRefused(m.positions, triangles, m.positions.size(),
                    "index " + std::to_string(bad) + " at corner " + std::to_string(corner));
    }
  }
  // A mesh without vertices: any triangle is out of range.
  expectRefused({}, m.triangles, 0, "no vertices");
}

TEST(GeomContract, EmptyMeshAndNoTrianglesAreValid) {
  std::vector<float> none;
  EXPECT_TRUE(computeVertexNormals({}, {}, none));
  const TriMesh m = testing::uvSphere(4, 6);
  std::vector<float> normals(m.positions.size(), kSentinel);
  ASSERT_TRUE(computeVertexNormals(m.positions, {}, normals));
  for (float v : normals) EXPECT_EQ(v, 0.0f);  // no triangle touches any vertex
}

}  // namespace
}  // namespace vdg
