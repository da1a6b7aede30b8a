// Closedness and Euler characteristic (vdg/morph/mesh_checks.h).
#include "vdg/morph/mesh_checks.h"

#include <gtest/gtest.h>

#include "support/error_of.h"
#include "support/test_meshes.h"

namespace vdg::morph {
namespace {

TEST(MeshChecks, ClosedMeshesPassAndGiveTheirEulerCharacteristic) {
  const TriMesh sphere = testing::uvSphere();
  const TriMesh box = testing::closedBox(0, 0, 0, 1, 2, 3);
  const TriMesh ring = testing::torus();
  EXPECT_NO_THROW(requireClosed(sphere, "sphere"));
  EXPECT_NO_THROW(requireClosed(box, "box"));
  EXPECT_NO_THROW(requireClosed(ring, "torus"));
  EXPECT_EQ(eulerCharacteristic(sphere), 2);
  EXPECT_EQ(eulerCharacteristic(box), 2);
  EXPECT_EQ(eulerCharacteristic(ring), 0);
}

TEST(MeshChecks, AHoleIsNamedByItsEdge) {
  TriMesh box = testing::closedBox(0, 0, 0, 1, 1, 1);
  box.triangles.resize(box.triangles.size() - 3);  // drop the last triangle (1, 7, 5)
  EXPECT_EQ(testing::errorOf([&] { requireClosed(box, "b.obj"); }),
            "b.obj: is not closed: edge (1, 5) borders a hole (one triangle only)");
}

TEST(MeshChecks, AFlippedTriangleAndDegenerateOnesAreRefused) {
  TriMesh box = testing::closedBox(0, 0, 0, 1, 1, 1);
  std::swap(box.triangles[1], box.triangles[2]);
  EXPECT_NE(testing::errorOf([&] { requireClosed(box, "b"); }).find("used twice in the same direction"),
            std::string::npos);
  TriMesh degenerate = testing::closedBox(0, 0, 0, 1, 1, 1);
  degenerate.triangles[1] = degenerate.triangles[0];
  EXPECT_EQ(testing::errorOf([&] { requireClosed(degenerate, "d"); }),
            "d: triangle 0 is degenerate (a vertex repeats)");
  EXPECT_EQ(testing::errorOf([&] { requireClosed(TriMesh{}, "e"); }), "e: has no triangles");
}

}  // namespace
}  // namespace vdg::morph
