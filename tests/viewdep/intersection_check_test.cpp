// No vertex through the mesh (vdg/viewdep/intersection_check.h): a key that pushes one sheet
// through another is reported at and near its view, a clean key is not, nor are the base's own
// intersections.
#include "vdg/viewdep/intersection_check.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>

#include "vdg/geom/error.h"

namespace vdg {
namespace {

using Eigen::Vector3d;
constexpr double kDeg = std::numbers::pi / 180.0;

// An n x n grid of quads in the plane y = height over [-1, 1]^2, appended to m.
void addSheet(TriMesh& m, int n, float height) {
  const auto first = static_cast<std::int32_t>(m.vertexCount());
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i)
      m.positions.insert(m.positions.end(), {-1.0f + 2.0f * i / n, height, -1.0f + 2.0f * j / n});
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const std::int32_t a = first + j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
      m.triangles.insert(m.triangles.end(), {a, c, b, b, c, d});
    }
}

// Two sheets 0.3 apart and, in the base already, a small upright quad through the lower sheet
// near a corner. Key "push" (view +Z) lowers the upper sheet's middle to y = -0.2, through the
// lower one; key "clean" (view -Z) is the base.
RawViewDependentModel sheets() {
  RawViewDependentModel raw;
  addSheet(raw.base, 10, 0.0f);
  addSheet(raw.base, 10, 0.3f);
  const auto q = static_cast<std::int32_t>(raw.base.vertexCount());
  raw.base.positions.insert(raw.base.positions.end(),
                            {-0.85f, -0.1f, -0.85f, -0.75f, -0.1f, -0.85f, -0.85f, 0.1f, -0.85f, -0.75f, 0.1f, -0.85f});
  raw.base.triangles.insert(raw.base.triangles.end(), {q, q + 1, q + 2, q + 1, q + 3, q + 2});
  RawKey push;
  push.name = "push";
  push.mesh = raw.base;
  push.view = Vector3d::UnitZ();
  for (std::size_t v = 121; v < 242; ++v) {
    const float x = push.mesh.positions[3 * v], z = push.mesh.positions[3 * v + 2];
    if (x * x + z * z < 0.3f) push.mesh.positions[3 * v + 1] = -0.2f;
  }
  raw.keys.push_back(push);
  RawKey clean = push;
  clean.name = "clean";
  clean.mesh = raw.base;
  clean.view = -Vector3d::UnitZ();
  raw.keys.push_back(clean);
  return raw;
}

IntersectionCheckSettings settings(int samples) {
  IntersectionCheckSettings s;
  s.samples = samples;
  return s;
}

double angleDeg(const Vector3d& a, const Vector3d& b) { return std::atan2(a.cross(b).norm(), a.dot(b)) / kDeg; }

TEST(IntersectionCheck, ReportsThePushedKeyAndNotTheCleanOne) {
  const ViewDependentModel model = ViewDependentModel::build(sheets());
  const IntersectionReport report = checkIntersections(model, settings(300));
  EXPECT_EQ(report.views_checked, 302u) << "two key views and 300 samples";
  EXPECT_EQ(report.base_pairs, 2u) << "the upright quad's two triangles through the lower sheet";
  ASSERT_FALSE(report.views.empty());
  bool push_reported = false;
  for (const IntersectingView& v : report.views) {
    EXPECT_NE(v.key, 1) << "the clean key";
    EXPECT_GT(angleDeg(v.view, -Vector3d::UnitZ()), 60.0) << v.view.transpose();
    EXPECT_LT(angleDeg(v.view, Vector3d::UnitZ()), 90.0) << v.view.transpose();
    EXPECT_GT(v.new_pairs, 0u);
    push_reported |= v.key == 0;
  }
  EXPECT_TRUE(push_reported);
  ASSERT_GE(report.worst, 0);
  for (const IntersectingView& v : report.views) EXPECT_LE(v.new_pairs, report.views[report.worst].new_pairs);
  EXPECT_LT(angleDeg(report.views[report.worst].view, Vector3d::UnitZ()), 30.0);
  // Views near the pushed key are reported: every sample within 10 degrees of it.
  std::size_t near = 0, near_reported = 0;
  for (const Vector3d& d : fibonacciDirections(300))
    if (angleDeg(d, Vector3d::UnitZ()) < 10.0) {
      ++near;
      for (const IntersectingView& v : report.views) near_reported += v.view.isApprox(d) ? 1 : 0;
    }
  EXPECT_GT(near, 0u);
  EXPECT_EQ(near_reported, near);
}

TEST(IntersectionCheck, CleanModelReportsNothing) {
  RawViewDependentModel raw = sheets();
  raw.keys[0].mesh = raw.base;
  const IntersectionReport report = checkIntersections(ViewDependentModel::build(raw), settings(50));
  EXPECT_EQ(report.base_pairs, 2u);
  EXPECT_TRUE(report.views.empty());
  EXPECT_EQ(report.worst, -1);
}

// What the studio checks after a stroke: the key mesh against the base.
TEST(IntersectionCheck, KeyAtItsOwnView) {
  const RawViewDependentModel raw = sheets();
  const auto pushed = keyIntersections(raw.base, raw.keys[0].mesh.positions);
  EXPECT_FALSE(pushed.empty());
  for (const auto& [i, j] : pushed) {
    EXPECT_LT(i, 200) << "a triangle of the lower sheet";
    EXPECT_GE(j, 200) << "through one of the upper sheet";
    EXPECT_LT(j, 400);
  }
  EXPECT_TRUE(keyIntersections(raw.base, raw.keys[1].mesh.positions).empty()) << "the base's own pairs are not new";
}

TEST(IntersectionCheck, RefusesBadSettings) {
  const ViewDependentModel model = ViewDependentModel::build(sheets());
  EXPECT_THROW(checkIntersections(model, settings(-1)), Error);
  EXPECT_THROW(checkIntersections(model, settings(kMaxIntersectionSamples + 1)), Error);
  const auto dirs = fibonacciDirections(64);
  ASSERT_EQ(dirs.size(), 64u);
  for (const Vector3d& d : dirs) EXPECT_NEAR(d.norm(), 1.0, 1e-12);
}

}  // namespace
}  // namespace vdg
