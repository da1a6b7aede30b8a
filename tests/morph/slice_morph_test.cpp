// Chen's slice interpolation (vdg/morph/slice_morph.h; Parent 4.10).
#include "vdg/morph/slice_morph.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <string>

#include "support/error_of.h"
#include "support/test_meshes.h"
#include "vdg/morph/mesh_checks.h"

namespace vdg::morph {
namespace {

// Float positions of values made in double, relative to their size.
constexpr double kFloatTolerance = 1e-6;
// A slice-sampled uvSphere(16, 32) against the round sphere: the mesh's chords (1 - cos(pi / 32)
// ~ 0.5 %) and the rays that meet them between vertices.
constexpr double kSphereSampling = 0.01;
// The lofted volume against the mesh's own: the two conical ends and the chords between slices.
constexpr double kLoftVolume = 0.03;

double volumeOf(const TriMesh& m) {
  double six = 0;
  for (std::size_t f = 0; f < m.triangleCount(); ++f) {
    const auto p = [&](int k) {
      const auto v = static_cast<std::size_t>(m.triangles[f * 3 + k]);
      return std::array<double, 3>{m.positions[v * 3], m.positions[v * 3 + 1], m.positions[v * 3 + 2]};
    };
    const auto a = p(0), b = p(1), c = p(2);
    six += a[0] * (b[1] * c[2] - b[2] * c[1]) + a[1] * (b[2] * c[0] - b[0] * c[2]) + a[2] * (b[0] * c[1] - b[1] * c[0]);
  }
  return six / 6;
}

TriMesh scaled(TriMesh m, float s) {
  for (float& x : m.positions) x *= s;
  return m;
}

TEST(SliceMorph, TheLoftIsClosedGenusZeroAndOutwardOnEveryAxis) {
  const TriMesh sphere = testing::uvSphere(16, 32);
  const TriMesh box = testing::closedBox(-1, -0.5f, -0.25f, 1, 0.5f, 0.25f);
  for (const int axis : {0, 1, 2}) {
    SCOPED_TRACE(axis);
    const SliceMorphOptions options{.slices = 12, .samples = 20, .axis = axis};
    const TriMesh m = sliceMorph(sphere, box, 0.4, options);
    EXPECT_NO_THROW(requireClosed(m, "loft"));
    EXPECT_EQ(eulerCharacteristic(m), 2);
    EXPECT_EQ(m.vertexCount(), 12u * 20u + 2u);
    EXPECT_GT(volumeOf(m), 0);
  }
}

TEST(SliceMorph, TheEndsAreTheInputsAsTheirSlicesSampleThem) {
  const TriMesh sphere = testing::uvSphere(16, 32);
  const TriMesh m = sliceMorph(sphere, testing::closedBox(0, 0, 0, 1, 1, 1), 0.0);
  // The apexes sit on the poles; every sample lies on the sphere (its chords) at radius about 1.
  const double sphere_volume = volumeOf(sphere);
  EXPECT_NEAR(volumeOf(m), sphere_volume, kLoftVolume * sphere_volume);
  for (std::size_t v = 0; v < m.vertexCount(); ++v) {
    const double r = std::hypot(m.positions[v * 3], m.positions[v * 3 + 1], m.positions[v * 3 + 2]);
    EXPECT_NEAR(r, 1.0, kSphereSampling) << "vertex " << v;
  }
  const Bounds b = computeBounds(m.positions);
  EXPECT_FLOAT_EQ(b.min[1], -1.0f);
  EXPECT_FLOAT_EQ(b.max[1], 1.0f);
}

TEST(SliceMorph, ConcentricSpheresInterpolateTheirRadius) {
  // B is A scaled by 2: its slices are A's scaled by 2, so each point of the inbetween is (1 + t)
  // times the same point at t = 0 (radius 1 and 2 give radius 1.5 at t = 0.5).
  const TriMesh a = testing::uvSphere(16, 32);
  const TriMesh b = scaled(a, 2);
  const TriMesh at0 = sliceMorph(a, b, 0.0);
  for (const double t : {0.25, 0.5, 1.0}) {
    const TriMesh m = sliceMorph(a, b, t);
    ASSERT_EQ(m.positions.size(), at0.positions.size());
    for (std::size_t i = 0; i < m.positions.size(); ++i)
      ASSERT_NEAR(m.positions[i], (1 + t) * at0.positions[i], kFloatTolerance * 2) << "t " << t << " coordinate " << i;
  }
}

TEST(SliceMorph, CorrespondingRaysInterpolateTheirReach) {
  // A cube [-1, 1]^3 to the unit sphere, sliced along y. In the middle slices the ray at 45 degrees
  // (between +z and +x) reaches the cube's edge at sqrt(2) and the sphere at about 1; at t = 0.5
  // the inbetween's point is halfway, (sqrt(2) + 1) / 2 from the axis.
  const TriMesh cube = testing::closedBox(-1, -1, -1, 1, 1, 1);
  const TriMesh sphere = testing::uvSphere(16, 32);
  const SliceMorphOptions options{.slices = 32, .samples = 64, .axis = 1};
  const TriMesh m = sliceMorph(cube, sphere, 0.5, options);
  const std::size_t k = 16, j = 8;  // slice 16 of 32 is at y = 1/32; sample 8 of 64 is at 45 degrees
  const float* p = &m.positions[(k * 64 + j) * 3];
  EXPECT_NEAR(p[0], p[2], kFloatTolerance);  // on the diagonal: x = z
  const double sphere_reach = std::sqrt(1.0 - 1.0 / (32.0 * 32.0));
  EXPECT_NEAR(std::hypot(p[0], p[2]), (std::sqrt(2.0) + sphere_reach) / 2, kSphereSampling);
  EXPECT_NEAR(p[1], 1.0 / 32, kFloatTolerance);
}

TEST(SliceMorph, ShapesItCannotSliceAreRefused) {
  const TriMesh box = testing::closedBox(0, 0, 0, 1, 1, 1);
  // A torus about y: every slice is a ring whose centre lies in the hole.
  const std::string ring = testing::errorOf([&] { (void)sliceMorph(box, testing::torus(), 0.5, {}, "A", "t.obj"); });
  EXPECT_EQ(ring.rfind("t.obj: slice 0 (at y = ", 0), 0u) << ring;
  EXPECT_NE(ring.find(") is not star-shaped about its centre: the ray at 0 degrees crosses it 2 times, not once"),
            std::string::npos)
      << ring;
  TriMesh open = box;
  open.triangles.resize(open.triangles.size() - 3);
  EXPECT_EQ(testing::errorOf([&] { (void)sliceMorph(open, box, 0.5, {}, "open.obj"); }),
            "open.obj: is not closed: edge (1, 5) borders a hole (one triangle only)");
  EXPECT_EQ(testing::errorOf([&] { (void)sliceMorph(box, box, 1.5); }),
            "slice morph: t must be a finite number in [0, 1], not 1.5");
  EXPECT_EQ(testing::errorOf([&] { (void)sliceMorph(box, box, 0.5, {.slices = 1}); }),
            "slice morph: slices must be in [2, 100000], not 1");
  EXPECT_EQ(testing::errorOf([&] { (void)sliceMorph(box, box, 0.5, {.samples = 2}); }),
            "slice morph: samples must be in [3, 100000], not 2");
  EXPECT_EQ(testing::errorOf([&] { (void)sliceMorph(box, box, 0.5, {.axis = 3}); }),
            "slice morph: axis must be 0, 1 or 2, not 3");
}

}  // namespace
}  // namespace vdg::morph
