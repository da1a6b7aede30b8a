// Distance-field shape interpolation (Parent 4.10, "Distance Fields"; vdg/morph/shape_morph.h).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include "support/error_of.h"
#include "support/test_meshes.h"
#include "vdg/morph/mesh_checks.h"
#include "vdg/morph/shape_morph.h"

namespace vdg::morph {
namespace {

using Vec3 = std::array<double, 3>;

TriMesh scaled(TriMesh m, double s) {
  for (float& p : m.positions) p = static_cast<float>(p * s);
  return m;
}

Vec3 at(const TriMesh& m, std::int32_t i) {
  const auto k = static_cast<std::size_t>(i) * 3;
  return {m.positions[k], m.positions[k + 1], m.positions[k + 2]};
}

// Distance from p to segment/triangle, by dense barycentric search-free formula: the closest point
// of the plane when inside, else the closest point of the three edges.
double distanceToSegment(const Vec3& p, const Vec3& a, const Vec3& b) {
  Vec3 ab{}, ap{};
  for (int k = 0; k < 3; ++k) ab[k] = b[k] - a[k], ap[k] = p[k] - a[k];
  const double len2 = ab[0] * ab[0] + ab[1] * ab[1] + ab[2] * ab[2];
  const double s = len2 > 0 ? std::clamp((ap[0] * ab[0] + ap[1] * ab[1] + ap[2] * ab[2]) / len2, 0.0, 1.0) : 0.0;
  double d2 = 0;
  for (int k = 0; k < 3; ++k) d2 += (ap[k] - ab[k] * s) * (ap[k] - ab[k] * s);
  return std::sqrt(d2);
}

double distanceToTriangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  Vec3 u{}, v{}, w{}, n{};
  for (int k = 0; k < 3; ++k) u[k] = b[k] - a[k], v[k] = c[k] - a[k], w[k] = p[k] - a[k];
  n = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
  const double n2 = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
  if (n2 > 0) {
    // Barycentric coordinates of p's projection.
    auto cross_dot = [&](const Vec3& x, const Vec3& y) {
      const Vec3 c3{x[1] * y[2] - x[2] * y[1], x[2] * y[0] - x[0] * y[2], x[0] * y[1] - x[1] * y[0]};
      return (c3[0] * n[0] + c3[1] * n[1] + c3[2] * n[2]) / n2;
    };
    const double beta = cross_dot(w, v), gamma = cross_dot(u, w);
    if (beta >= 0 && gamma >= 0 && beta + gamma <= 1)
      return std::abs(w[0] * n[0] + w[1] * n[1] + w[2] * n[2]) / std::sqrt(n2);
  }
  return std::min({distanceToSegment(p, a, b), distanceToSegment(p, b, c), distanceToSegment(p, c, a)});
}

// The largest distance from a vertex of `from` to the surface of `to` (one side of the Hausdorff
// distance, sampled at the vertices).
double largestVertexDistance(const TriMesh& from, const TriMesh& to) {
  double worst = 0;
  for (std::size_t v = 0; v < from.vertexCount(); ++v) {
    const Vec3 p = at(from, static_cast<std::int32_t>(v));
    double best = INFINITY;
    for (std::size_t f = 0; f < to.triangleCount(); ++f)
      best = std::min(best, distanceToTriangle(p, at(to, to.triangles[f * 3]), at(to, to.triangles[f * 3 + 1]),
                                               at(to, to.triangles[f * 3 + 2])));
    worst = std::max(worst, best);
  }
  return worst;
}

// Signed volume (divergence theorem): positive for a closed mesh wound counter-clockwise seen
// from outside.
double signedVolume(const TriMesh& m) {
  double volume = 0;
  for (std::size_t f = 0; f < m.triangleCount(); ++f) {
    const Vec3 a = at(m, m.triangles[f * 3]), b = at(m, m.triangles[f * 3 + 1]), c = at(m, m.triangles[f * 3 + 2]);
    volume +=
        (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) + a[2] * (b[0] * c[1] - b[1] * c[0])) /
        6.0;
  }
  return volume;
}

TEST(DistanceMorph, EndsReproduceSourceAndDestinationWithinOneVoxel) {
  const TriMesh sphere = testing::uvSphere(24, 48);
  TriMesh box = testing::closedBox(-0.8f, -0.5f, -0.6f, 0.9f, 0.7f, 0.5f);
  const DistanceMorph morph(sphere, box, {.voxel_size = 0.05});
  EXPECT_DOUBLE_EQ(morph.voxelSize(), 0.05);
  const double voxel = morph.voxelSize();
  for (const double t : {0.0, 1.0}) {
    const TriMesh& target = t == 0 ? sphere : box;
    const TriMesh out = morph.at(t);
    SCOPED_TRACE("t = " + std::to_string(t));
    ASSERT_GT(out.triangleCount(), 100u);
    EXPECT_LE(largestVertexDistance(out, target), voxel);
    // The box's 8 corners are sharp: a level set rounds them off by up to about a voxel's
    // diagonal; the sphere's vertices are within one voxel.
    EXPECT_LE(largestVertexDistance(target, out), t == 0 ? voxel : voxel * std::sqrt(3.0));
    EXPECT_NO_THROW(requireClosed(out, "out"));
    EXPECT_GT(signedVolume(out), 0) << "counter-clockwise seen from outside";
  }
}

TEST(DistanceMorph, ConcentricSpheresOfRadiusOneAndTwoGiveRadiusOneAndAHalfAtHalfway) {
  const TriMesh small = testing::uvSphere(48, 96), large = scaled(testing::uvSphere(48, 96), 2.0);
  const DistanceMorph morph(small, large, {.voxel_size = 0.05});
  const double voxel = morph.voxelSize();
  const TriMesh half = morph.at(0.5);
  ASSERT_GT(half.vertexCount(), 1000u);
  double sum = 0, worst = 0;
  for (std::size_t v = 0; v < half.vertexCount(); ++v) {
    const Vec3 p = at(half, static_cast<std::int32_t>(v));
    const double r = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
    sum += r;
    worst = std::max(worst, std::abs(r - 1.5));
  }
  EXPECT_NEAR(sum / static_cast<double>(half.vertexCount()), 1.5, voxel);
  EXPECT_LE(worst, voxel);
  EXPECT_NO_THROW(requireClosed(half, "half"));
  EXPECT_EQ(eulerCharacteristic(half), 2);
  // Volume of a ball of radius 1.5, within a voxel's shell.
  const double ball = 4.0 / 3.0 * M_PI * 1.5 * 1.5 * 1.5;
  EXPECT_NEAR(signedVolume(half), ball, 4 * M_PI * 1.5 * 1.5 * voxel);
}

TEST(DistanceMorph, SphereToTorusChangesGenusAndStaysClosed) {
  const TriMesh sphere = testing::uvSphere(32, 64), ring = testing::torus(1.0, 0.4, 64, 32);
  const DistanceMorph morph(sphere, ring, {}, "sphere.obj", "torus.obj");
  // The default voxel: the larger bounding-box diagonal / 96.
  const double diagonal = computeBounds(ring.positions).diagonal();
  EXPECT_NEAR(morph.voxelSize(), diagonal / 96.0, 1e-9 * diagonal);
  EXPECT_GT(morph.activeVoxelCount(), 0u);
  EXPECT_GT(morph.memoryBytes(), morph.activeVoxelCount() * sizeof(float));
  for (const double t : {0.0, 0.25, 0.5, 0.75, 1.0}) {
    SCOPED_TRACE("t = " + std::to_string(t));
    const TriMesh out = morph.at(t);
    ASSERT_NO_THROW(requireClosed(out, "out"));
    EXPECT_GT(signedVolume(out), 0);
    if (t == 0.0) {
      EXPECT_EQ(eulerCharacteristic(out), 2);
    }
    if (t == 1.0) {
      EXPECT_EQ(eulerCharacteristic(out), 0);
    }
  }
}

TEST(DistanceMorph, OpenMeshesAreRefusedByName) {
  TriMesh open = testing::uvSphere();
  open.triangles.erase(open.triangles.begin(), open.triangles.begin() + 3);  // drop (0, 1, 2)
  const TriMesh sphere = testing::uvSphere();
  EXPECT_EQ(testing::errorOf([&] { DistanceMorph(open, sphere, {}, "a.obj", "b.obj"); }),
            "a.obj: is not closed: edge (0, 2) borders a hole (one triangle only)");
  EXPECT_EQ(testing::errorOf([&] { DistanceMorph(sphere, open, {}, "a.obj", "b.obj"); }),
            "b.obj: is not closed: edge (0, 2) borders a hole (one triangle only)");
  EXPECT_EQ(testing::errorOf([&] { DistanceMorph(sphere, sphere, {.band_voxels = 2}); }),
            "distance morph: the band must be at least 3 voxels, got 2");
  EXPECT_EQ(testing::errorOf([&] { DistanceMorph(sphere, sphere, {.voxel_size = -1}); }),
            "distance morph: the voxel size must be a finite number > 0 (or 0 for the default), got -1");
}

TEST(DistanceMorph, TooManyVoxelsAreRefusedBeforeAllocatingAndTheSuggestedVoxelWorks) {
  const TriMesh sphere = testing::uvSphere(), ring = testing::torus();
  // 1e-4 on meshes 2-3 units wide: about 1e13 voxels. Refused from the estimate (an allocation
  // would take minutes and terabytes; no time is asserted, since these machines are shared).
  const std::string message = testing::errorOf([&] { DistanceMorph(sphere, ring, {.voxel_size = 1e-4}); });
  EXPECT_EQ(message.rfind("A and B: the distance volumes at voxel size 0.0001 need ", 0), 0u) << message;
  EXPECT_NE(message.find(" MiB), more than the limit of 2.68e+08; use a --voxel of at least "), std::string::npos)
      << message;
  // The suggested voxel size is enough under a smaller limit too.
  const std::string small = testing::errorOf([&] { DistanceMorph(sphere, ring, {.max_voxels = 200000}); });
  const auto from = small.rfind(' ');
  ASSERT_NE(from, std::string::npos) << small;
  const double suggested = std::stod(small.substr(from + 1));
  EXPECT_GT(suggested, computeBounds(ring.positions).diagonal() / 96.0);
  const DistanceMorph morph(sphere, ring, {.voxel_size = suggested, .max_voxels = 200000});
  EXPECT_LE(morph.activeVoxelCount(), 200000u);
  EXPECT_NO_THROW(requireClosed(morph.at(0.5), "coarse"));
}

// --voxel 1e-300: the count (about 1e900) is past what a double holds. It used to be +infinity,
// the suggested size infinity and its rounding NaN, and the search for it looped for ever; now it
// is refused at once with a finite suggestion that fits.
TEST(DistanceMorph, AVoxelCountPastWhatADoubleHoldsIsRefusedWithASizeThatFits) {
  const TriMesh sphere = testing::uvSphere(), ring = testing::torus();
  const std::string message = testing::errorOf([&] { DistanceMorph(sphere, ring, {.voxel_size = 1e-300}); });
  EXPECT_EQ(message.rfind("A and B: the distance volumes at voxel size 1e-300 need more than 1e308 voxels, more than "
                          "the limit of 2.68e+08; use a --voxel of at least ",
                          0),
            0u)
      << message;
  // Under a small limit (so that the volumes stay quick to build) the suggestion fits.
  const std::string small =
      testing::errorOf([&] { DistanceMorph(sphere, ring, {.voxel_size = 1e-300, .max_voxels = 200000}); });
  const double suggested = std::stod(small.substr(small.rfind(' ') + 1));
  EXPECT_TRUE(std::isfinite(suggested) && suggested > 0) << small;
  const DistanceMorph morph(sphere, ring, {.voxel_size = suggested, .max_voxels = 200000});
  EXPECT_LE(morph.activeVoxelCount(), 200000u);
  // Each frame blends and polygonises every active voxel of both volumes (the budget's estimate).
  EXPECT_DOUBLE_EQ(distanceMorphFrameCost(morph), 4.0 * static_cast<double>(morph.activeVoxelCount()));
}

TEST(DistanceMorph, TOutsideTheUnitIntervalIsRefused) {
  const TriMesh sphere = testing::uvSphere();
  const DistanceMorph morph(sphere, scaled(sphere, 1.5), {});
  EXPECT_EQ(testing::errorOf([&] { (void)morph.at(1.5); }), "distance morph: t must be in [0, 1], got 1.5");
  EXPECT_EQ(testing::errorOf([&] { (void)morph.at(NAN); }), "distance morph: t must be in [0, 1], got nan");
}

}  // namespace
}  // namespace vdg::morph
