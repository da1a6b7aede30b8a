// Where to key next (vdg/viewdep/sphere_map.h): the nearest-key angle against its analytic value,
// the shape speed (zero where keys agree, largest on hull edges), the suggestion in the largest gap.
#include "vdg/viewdep/sphere_map.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "support/test_meshes.h"
#include "vdg/geom/error.h"

namespace vdg {
namespace {

using Eigen::Vector3d;

constexpr double kAngleTolDeg = 1e-6;  // atan2 of unit doubles, kept as float degrees
constexpr double kFloatAngleTolDeg = 2e-5;
constexpr double kZeroSpeed = 1e-5;  // float rounding of sum_i c_i D with sum_i c_i = 0, per degree
constexpr double kDeg = std::numbers::pi / 180.0;

const std::vector<Vector3d> kOctahedron{Vector3d::UnitX(),  -Vector3d::UnitX(), Vector3d::UnitY(),
                                        -Vector3d::UnitY(), Vector3d::UnitZ(),  -Vector3d::UnitZ()};

// A sphere model with one key per view; key k bulges the cap facing `bulge[k]` (zero: the key is
// the base).
RawViewDependentModel model(const std::vector<Vector3d>& views, const std::vector<Vector3d>& bulge,
                            double sharpness = 1.0) {
  RawViewDependentModel raw;
  raw.base = testing::uvSphere(10, 16);
  raw.sharpness = sharpness;
  for (std::size_t k = 0; k < views.size(); ++k) {
    RawKey key;
    key.name = "k" + std::to_string(k);
    key.mesh = raw.base;
    key.view = views[k];
    for (std::size_t v = 0; v < key.mesh.vertexCount() && bulge[k].norm() > 0; ++v) {
      const Vector3d p(key.mesh.positions[3 * v], key.mesh.positions[3 * v + 1], key.mesh.positions[3 * v + 2]);
      const double s = std::max(0.0, p.dot(bulge[k].normalized()) - 0.3);
      for (int c = 0; c < 3; ++c) key.mesh.positions[3 * v + c] += static_cast<float>(0.5 * s * bulge[k][c]);
    }
    raw.keys.push_back(std::move(key));
  }
  return raw;
}

// n keys equal to the base (Eigen's vectors start uninitialised: say zero).
std::vector<Vector3d> noBulge(std::size_t n) { return std::vector<Vector3d>(n, Vector3d::Zero()); }

double angleDeg(const Vector3d& a, const Vector3d& b) { return std::atan2(a.cross(b).norm(), a.dot(b)) / kDeg; }

TEST(SphereMap, GridDirectionsAndCells) {
  const SphereMap map =
      computeSphereMap(ViewDependentModel::build(model(kOctahedron, noBulge(6))), {.width = 72, .height = 36});
  const double c = std::cos(2.5 * kDeg), s = std::sin(2.5 * kDeg);  // cell (36, 18): longitude 2.5, latitude -2.5
  EXPECT_NEAR(SphereMap::cellDirection(72, 36, 36, 18).dot(Vector3d(c * s, -s, c * c)), 1.0, 1e-12)
      << "+Z is at the centre, Y up";
  for (int y = 0; y < 36; y += 5)
    for (int x = 0; x < 72; x += 7) {
      const Vector3d d = SphereMap::cellDirection(72, 36, x, y);
      EXPECT_NEAR(d.norm(), 1.0, 1e-12);
      EXPECT_EQ(map.cellOf(d), y * 72 + x);
    }
}

// Nearest-key angle: 0 at a key, and the analytic value for the octahedron (acos of the largest
// absolute coordinate) and for two poles (90 - |latitude|).
TEST(SphereMap, NearestKeyAngleIsAnalytic) {
  const SphereMap octa =
      computeSphereMap(ViewDependentModel::build(model(kOctahedron, noBulge(6))), {.width = 90, .height = 45});
  for (int y = 0; y < 45; ++y)
    for (int x = 0; x < 90; ++x) {
      const Vector3d d = SphereMap::cellDirection(90, 45, x, y);
      const double expected = std::acos(std::min(1.0, d.cwiseAbs().maxCoeff())) / kDeg;
      ASSERT_NEAR(octa.nearest_key_deg[y * 90 + x], expected, kFloatAngleTolDeg) << x << "," << y;
    }
  EXPECT_NEAR(octa.max_nearest_deg, std::acos(1 / std::sqrt(3.0)) / kDeg, 1.0) << "the face centres, 54.7 degrees";

  // Keys placed on cell centres: exactly 0 there.
  const std::vector<Vector3d> keys{SphereMap::cellDirection(40, 20, 3, 4), SphereMap::cellDirection(40, 20, 30, 10),
                                   SphereMap::cellDirection(40, 20, 17, 17), SphereMap::cellDirection(40, 20, 8, 12)};
  const SphereMap on =
      computeSphereMap(ViewDependentModel::build(model(keys, noBulge(4))), {.width = 40, .height = 20});
  for (const Vector3d& k : keys) EXPECT_NEAR(on.nearest_key_deg[on.cellOf(k)], 0.0, kAngleTolDeg);
  for (int i = 0; i < 40 * 20; ++i) {
    const Vector3d d = SphereMap::cellDirection(40, 20, i % 40, i / 40);
    double expected = 180;
    for (const Vector3d& k : keys) expected = std::min(expected, angleDeg(d, k));
    ASSERT_NEAR(on.nearest_key_deg[i], expected, kFloatAngleTolDeg);
  }

  RawViewDependentModel poles = model({Vector3d::UnitY(), -Vector3d::UnitY()}, noBulge(2));
  poles.sphere.uncovered = Uncovered::Cosine;
  const SphereMap p = computeSphereMap(ViewDependentModel::build(poles), {.width = 8, .height = 30});
  for (int y = 0; y < 30; ++y)
    EXPECT_NEAR(p.nearest_key_deg[y * 8 + 3], 90.0 - std::abs(90.0 - (y + 0.5) * 6.0), kFloatAngleTolDeg);
}

// Identical keys: the blend is the same shape wherever the keys' hull covers the view (base
// weight 0), so the speed is ~0 there; keys equal to the base give exactly 0 everywhere.
TEST(SphereMap, SpeedIsZeroWhereKeysAgree) {
  const std::vector<Vector3d> same(6, Vector3d(0.3, 0.8, 0.2));
  const SphereMap agree =
      computeSphereMap(ViewDependentModel::build(model(kOctahedron, same)), {.width = 60, .height = 30});
  EXPECT_EQ(agree.uncovered_fraction, 0.0) << "the octahedron surrounds the centre: no dummies";
  EXPECT_LT(agree.max_speed, kZeroSpeed);
  const SphereMap base =
      computeSphereMap(ViewDependentModel::build(model(kOctahedron, noBulge(6))), {.width = 60, .height = 30});
  EXPECT_EQ(base.max_speed, 0.0);
  for (float s : base.speed) ASSERT_EQ(s, 0.0f);

  // Keys +X, +Y, +Z identical, the others different: ~0 inside that triangle (the stencil inside
  // it), > 0 in the opposite one.
  std::vector<Vector3d> bulge{Vector3d(1, 1, 1),  Vector3d(-1, 0, 0), Vector3d(1, 1, 1),
                              Vector3d(0, -1, 0), Vector3d(1, 1, 1),  Vector3d(0, 0, -1)};
  const SphereMap part =
      computeSphereMap(ViewDependentModel::build(model(kOctahedron, bulge)), {.width = 120, .height = 60});
  int inside = 0, outside_moving = 0;
  for (int i = 0; i < 120 * 60; ++i) {
    const Vector3d d = SphereMap::cellDirection(120, 60, i % 120, i / 120);
    if (d.minCoeff() > 0.05) {
      ++inside;
      EXPECT_LT(part.speed[i], kZeroSpeed) << d.transpose();
    }
    if (d.maxCoeff() < -0.05 && part.speed[i] > 100 * kZeroSpeed) ++outside_moving;
  }
  EXPECT_GT(inside, 100);
  EXPECT_GT(outside_moving, 100);
}

// One key differs from its neighbours. With the plain barycentric blend (sharpness 1) the speed is
// largest on the hull's edges (the octahedron's lie on the three coordinate great circles), where
// the weights' gradient jumps; a sharper blend (section 3.2.2) moves the change to where the
// differing key's weight equals its neighbour's (x = max(|y|, |z|)). Away from +X nothing moves.
TEST(SphereMap, SpeedPeaksOnHullEdges) {
  std::vector<Vector3d> bulge = noBulge(6);
  bulge[0] = Vector3d(1, 0, 0);
  constexpr double kCellDeg = 2.0;
  for (double sharpness : {1.0, 4.0}) {
    const SphereMap map =
        computeSphereMap(ViewDependentModel::build(model(kOctahedron, bulge, sharpness)), {.width = 180, .height = 90});
    const Vector3d& at = map.max_speed_view;
    if (sharpness == 1.0)
      EXPECT_LT(std::asin(at.cwiseAbs().minCoeff()) / kDeg, 1.5 * kCellDeg) << at.transpose();
    else
      EXPECT_LT(std::abs(at.x() - std::max(std::abs(at.y()), std::abs(at.z()))), 1.5 * kCellDeg * kDeg)
          << at.transpose();
    EXPECT_GT(at.x(), -std::sin(kCellDeg * kDeg)) << "next to the key that differs";
    EXPECT_GT(map.max_speed, 0.0);
    for (int i = 0; i < 180 * 90; ++i) {
      if (SphereMap::cellDirection(180, 90, i % 180, i / 180).x() >= -0.05) continue;
      ASSERT_EQ(map.speed[i], 0.0f) << "sharpness " << sharpness << " cell " << i << ": "
                                    << SphereMap::cellDirection(180, 90, i % 180, i / 180).transpose();
    }
  }
}

// The suggestion lies in the largest gap: four keys on the equator and the north pole leave the
// south pole 90 degrees from every key (and showing the base).
TEST(SphereMap, SuggestionLiesInTheLargestGap) {
  const std::vector<Vector3d> keys{Vector3d::UnitX(), -Vector3d::UnitX(), Vector3d::UnitZ(), -Vector3d::UnitZ(),
                                   Vector3d::UnitY()};
  const SphereMap map =
      computeSphereMap(ViewDependentModel::build(model(keys, noBulge(5))), {.width = 120, .height = 60});
  EXPECT_LT(angleDeg(map.suggested, -Vector3d::UnitY()), 3.0) << map.suggested.transpose();
  EXPECT_NEAR(map.max_nearest_deg, 90.0, 3.0);
  EXPECT_GT(map.uncovered_fraction, 0.0);
  for (float n : map.need) {
    ASSERT_GE(n, 0.0f);
    ASSERT_LE(n, map.need[map.suggested_cell]);
  }

  // The octahedron: the eight face centres are the gaps (54.7 degrees from three keys).
  const SphereMap octa =
      computeSphereMap(ViewDependentModel::build(model(kOctahedron, noBulge(6))), {.width = 120, .height = 60});
  const Vector3d c = octa.suggested.cwiseAbs();
  EXPECT_LT(angleDeg(c, Vector3d::Ones().normalized()), 3.0) << octa.suggested.transpose();
}

TEST(SphereMap, RefusesBadSettings) {
  const ViewDependentModel m = ViewDependentModel::build(model(kOctahedron, noBulge(6)));
  EXPECT_THROW(computeSphereMap(m, {.width = 0, .height = 10}), Error);
  EXPECT_THROW(computeSphereMap(m, {.width = 10, .height = kMaxSphereMapSide + 1}), Error);
  EXPECT_THROW(computeSphereMap(m, {.width = 10, .height = 10, .step_deg = 0.0}), Error);
  EXPECT_THROW(computeSphereMap(m, {.width = 10, .height = 10, .step_deg = std::nan("")}), Error);
}

}  // namespace
}  // namespace vdg
