// Distances, falloff, image-plane tools and FFD (Rademacher 99, 3.1.2; Parent 4.10; Sederberg-Parry 86).
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>

#include "support/test_meshes.h"
#include "test_meshes.h"
#include "vdg/deform/distance.h"
#include "vdg/deform/falloff.h"
#include "vdg/deform/ffd.h"
#include "vdg/deform/image_plane.h"
#include "vdg/geom/error.h"

namespace vdg {
namespace {

constexpr double kFloatTol = 2e-6;  // float positions: relative rounding of a few ulps

Eigen::Vector3d vertex(const TriMesh& m, std::size_t v) {
  return {m.positions[3 * v], m.positions[3 * v + 1], m.positions[3 * v + 2]};
}

Camera perspectiveCamera() {
  Camera c;
  c.eye = {1.5, 2.0, 6.0};
  c.target = {0.1, -0.2, 0.0};
  c.up = {0.1, 1.0, 0.0};
  c.fov_deg = 35;
  return c;
}
Camera orthoCamera() {
  Camera c = perspectiveCamera();
  c.ortho_height = 4.0;
  return c;
}

// ---- distances ----

TEST(Distance, EdgesOnGridAreChebyshevWithAlternatingDiagonals) {
  // With both diagonals available around the seed's neighbourhood, the BFS distance on this grid
  // lies between the Chebyshev and Manhattan distances; on the axes it is exactly the offset.
  const TriMesh m = test::grid(9, 1.0);
  const int seed = 4 * 9 + 4;
  std::vector<double> d(m.vertexCount());
  edgeDistances(m.triangles, m.vertexCount(), seed, d);
  EXPECT_EQ(d[seed], 0);
  for (int j = 0; j < 9; ++j)
    for (int i = 0; i < 9; ++i) {
      const int di = std::abs(i - 4), dj = std::abs(j - 4);
      const double got = d[j * 9 + i];
      EXPECT_GE(got, std::max(di, dj));
      EXPECT_LE(got, di + dj);
      if (di == 0 || dj == 0) {
        EXPECT_EQ(got, di + dj);
      }
    }
}

TEST(Distance, EdgesOnPathCountEdgesAndUnreachableIsInfinite) {
  // A strip of triangles plus one detached triangle.
  TriMesh m;
  for (int i = 0; i < 6; ++i) m.positions.insert(m.positions.end(), {float(i / 2), float(i % 2), 0});
  m.triangles = {0, 2, 1, 1, 2, 3, 2, 4, 3, 3, 4, 5};
  m.positions.insert(m.positions.end(), {10, 0, 0, 11, 0, 0, 10, 1, 0});
  m.triangles.insert(m.triangles.end(), {6, 7, 8});
  std::vector<double> d(m.vertexCount());
  edgeDistances(m.triangles, m.vertexCount(), 0, d);
  EXPECT_EQ(d[0], 0);
  EXPECT_EQ(d[1], 1);
  EXPECT_EQ(d[2], 1);
  EXPECT_EQ(d[3], 2);  // 0-2-3 (1-2-3 also 2)
  EXPECT_EQ(d[4], 2);
  EXPECT_EQ(d[5], 3);
  EXPECT_EQ(d[6], kUnreachable);
  std::vector<double> g(m.vertexCount());
  GeodesicSolver(m.positions, m.triangles).distances(0, g);
  EXPECT_EQ(g[7], kUnreachable);
}

TEST(Distance, GeodesicOnFlatGridIsEuclideanInThePlane) {
  // Heat method accuracy on a 41 x 41 unit grid (side 2): away from the seed, the geodesic matches
  // the exact planar distance within 4% relative, and everywhere within 2% of the grid size.
  constexpr double kRelative = 0.04, kAbsolute = 0.02 * 2.0;
  const int n = 41;
  const TriMesh m = test::grid(n, 2.0 / (n - 1));
  const int seed = 20 * n + 20;
  std::vector<double> g(m.vertexCount()), e(m.vertexCount());
  GeodesicSolver(m.positions, m.triangles).distances(seed, g);
  euclideanDistances(m.positions, seed, e);
  double worst_rel = 0, worst_abs = 0;
  for (std::size_t v = 0; v < g.size(); ++v) {
    worst_abs = std::max(worst_abs, std::abs(g[v] - e[v]));
    if (e[v] > 0.25) worst_rel = std::max(worst_rel, std::abs(g[v] - e[v]) / e[v]);
  }
  EXPECT_LT(worst_rel, kRelative);
  EXPECT_LT(worst_abs, kAbsolute);
  EXPECT_EQ(g[seed], 0);
}

TEST(Distance, GeodesicOnSphereIsGreatCircle) {
  // From the north pole of a unit sphere, the geodesic distance is the polar angle; 5% relative
  // on a 24 x 48 UV sphere (its chords are shorter than the arcs by up to 0.2%).
  const TriMesh m = test::sphere(24, 48, 1.0);
  const std::vector<double> g = distancesFrom(DistanceMetric::kGeodesic, m.positions, m.triangles, 0);
  for (std::size_t v = 1; v < m.vertexCount(); ++v) {
    const double exact = std::acos(std::clamp(static_cast<double>(m.positions[3 * v + 1]), -1.0, 1.0));
    if (exact > 0.3) {
      EXPECT_NEAR(g[v], exact, 0.05 * exact) << "vertex " << v;
    }
  }
}

TEST(Distance, SurfaceMetricsCrossTextureSeams) {
  // A sphere with a seam of duplicated vertices along one meridian (as exporters split texture
  // seams): the surface metrics give the same distances as on the unsplit sphere, and both copies
  // of a seam vertex the same value.
  const TriMesh plain = testing::uvSphere(12, 24);
  const TriMesh seam = testing::seamSphere(12, 24);
  ASSERT_GT(seam.vertexCount(), plain.vertexCount());
  // Seed on the equator next to the seam, so that the walk must cross it.
  const std::int32_t seed = 1 + 5 * 24 + 1;
  for (const DistanceMetric metric : {DistanceMetric::kEdges, DistanceMetric::kGeodesic}) {
    const std::vector<double> expected = distancesFrom(metric, plain.positions, plain.triangles, seed);
    const std::vector<double> got = distancesFrom(metric, seam.positions, seam.triangles, seed);
    for (std::size_t v = 0; v < plain.vertexCount(); ++v)
      ASSERT_NEAR(got[v], expected[v], 1e-9 + 1e-6 * expected[v]) << distanceMetricName(metric) << " vertex " << v;
    for (std::size_t v = plain.vertexCount(); v < seam.vertexCount(); ++v) {
      // The copy of a seam vertex sits at the position of an original one.
      std::size_t original = 0;
      while (original < plain.vertexCount() && !(plain.positions[original * 3] == seam.positions[v * 3] &&
                                                 plain.positions[original * 3 + 1] == seam.positions[v * 3 + 1] &&
                                                 plain.positions[original * 3 + 2] == seam.positions[v * 3 + 2]))
        ++original;
      ASSERT_LT(original, plain.vertexCount());
      EXPECT_EQ(got[v], got[original]) << distanceMetricName(metric) << " copy " << v;
    }
  }
  // The index buffer alone stops at the seam: the copies are farther by edges than the originals.
  std::vector<double> raw(seam.vertexCount());
  edgeDistances(seam.triangles, seam.vertexCount(), seed, raw);
  const std::vector<double> welded = distancesFrom(DistanceMetric::kEdges, seam.positions, seam.triangles, seed);
  double worst = 0.0;
  for (std::size_t v = plain.vertexCount(); v < seam.vertexCount(); ++v) worst = std::max(worst, raw[v] - welded[v]);
  EXPECT_GT(worst, 0.0);
}

TEST(Distance, ParseNames) {
  EXPECT_EQ(parseDistanceMetric("geodesic", "x"), DistanceMetric::kGeodesic);
  EXPECT_THROW(parseDistanceMetric("manhattan", "x"), Error);
  EXPECT_EQ(parseFalloffShape("inverse_power", "x"), FalloffShape::kInversePower);
}

// ---- falloff ----

TEST(Falloff, PowerFamily) {
  const Falloff f{2.0, 2.0, FalloffShape::kPower};
  EXPECT_EQ(falloffWeight(f, 0.0), 1.0);
  EXPECT_DOUBLE_EQ(falloffWeight(f, 0.5), 0.75 * 0.75);
  EXPECT_EQ(falloffWeight(f, 2.0), 0.0);
  EXPECT_EQ(falloffWeight(f, 3.0), 0.0);
  EXPECT_EQ(falloffWeight(f, kUnreachable), 0.0);
  const Falloff rigid{1.0, 0.0, FalloffShape::kPower};
  EXPECT_EQ(falloffWeight(rigid, 0.99), 1.0);
  EXPECT_EQ(falloffWeight(rigid, 1.0), 0.0);
  const Falloff inv{1.0, 3.0, FalloffShape::kInversePower};
  EXPECT_DOUBLE_EQ(falloffWeight(inv, 0.5), 1.0 - 0.125);
}

// ---- image-plane tools ----

class ImagePlane : public ::testing::TestWithParam<bool> {
 protected:
  Camera camera() const { return GetParam() ? orthoCamera() : perspectiveCamera(); }
};

TEST_P(ImagePlane, DragFalloffIsExactAndDepthsUnchanged) {
  const Camera cam = camera();
  const TriMesh base = test::sphere(12, 24, 1.0);
  TriMesh m = base;
  const int seed = 40;
  const double r = 0.9;
  const Eigen::Vector2d delta(0.3, -0.2);
  const std::vector<double> w =
      seedWeights(DistanceMetric::kEuclidean, Falloff{r, 2.0, FalloffShape::kPower}, m.positions, m.triangles, seed);
  dragInImagePlane(cam, m.positions, w, delta);
  const CameraFrame f = cameraFrame(cam);
  const Eigen::Vector3d move = delta.x() * f.right + delta.y() * f.up;
  const Eigen::Vector3d s = vertex(base, seed);
  int moved = 0;
  for (std::size_t v = 0; v < m.vertexCount(); ++v) {
    const Eigen::Vector3d p0 = vertex(base, v), p1 = vertex(m, v);
    const double d = (p0 - s).norm();
    if (d >= r) {
      EXPECT_EQ(p0, p1) << "vertex " << v << " beyond r moved";
      continue;
    }
    ++moved;
    const double k = (1 - d / r) * (1 - d / r);
    EXPECT_NEAR((p1 - p0 - k * move).norm(), 0.0, kFloatTol * 4) << "vertex " << v;
    EXPECT_NEAR(project(cam, 640, 480, p1).depth, project(cam, 640, 480, p0).depth, kFloatTol * 8);
  }
  EXPECT_GT(moved, 5);
}

TEST_P(ImagePlane, PixelDeltaMovesThePickedVertexByThosePixels) {
  const Camera cam = camera();
  const Eigen::Vector3d p(0.3, 0.2, -0.1);
  const Projected before = project(cam, 800, 600, p);
  const Eigen::Vector2d px(12.0, -7.0);
  const Eigen::Vector2d delta = imagePlaneDelta(cam, 800, 600, before.depth, px);
  const CameraFrame f = cameraFrame(cam);
  const Projected after = project(cam, 800, 600, p + delta.x() * f.right + delta.y() * f.up);
  EXPECT_NEAR((after.pixel - before.pixel - px).norm(), 0.0, 1e-9);
}

TEST_P(ImagePlane, PushPullChangesDepthByTheFalloff) {
  const Camera cam = camera();
  const TriMesh base = test::sphere(12, 24, 1.0);
  for (PushPullMode mode : {PushPullMode::kAlongRay, PushPullMode::kAlongAxis}) {
    TriMesh m = base;
    const int seed = 30;
    const Falloff fo{0.8, 2.0, FalloffShape::kPower};
    const std::vector<double> w = seedWeights(DistanceMetric::kEuclidean, fo, m.positions, m.triangles, seed);
    pushPull(cam, m.positions, w, 0.25, mode);
    for (std::size_t v = 0; v < m.vertexCount(); ++v) {
      const Projected a = project(cam, 640, 480, vertex(base, v)), b = project(cam, 640, 480, vertex(m, v));
      EXPECT_NEAR(b.depth - a.depth, 0.25 * w[v], kFloatTol * 8) << "vertex " << v;
      if (mode == PushPullMode::kAlongRay || cam.isOrtho()) {
        EXPECT_NEAR((b.pixel - a.pixel).norm(), 0.0, 1e-3) << "vertex " << v;  // pixels
      }
    }
  }
}

TEST_P(ImagePlane, RotateAndScaleKeepDepthAndFollowTheMap) {
  const Camera cam = camera();
  const TriMesh base = test::sphere(12, 24, 1.0);
  const int seed = 50;
  const Eigen::Vector3d pivot = vertex(base, seed);
  const std::vector<double> rigid = seedWeights(DistanceMetric::kEuclidean, Falloff{0.7, 0.0, FalloffShape::kPower},
                                                base.positions, base.triangles, seed);
  const CameraFrame f = cameraFrame(cam);
  TriMesh rotated = base, scaled = base;
  rotateInImagePlane(cam, rotated.positions, rigid, pivot, std::numbers::pi / 6);
  scaleInImagePlane(cam, scaled.positions, rigid, pivot, {1.5, 0.5});
  const Eigen::Vector3d axis = f.back;  // counter-clockwise seen from the eye
  const Eigen::Matrix3d R = Eigen::AngleAxisd(std::numbers::pi / 6, axis).toRotationMatrix();
  for (std::size_t v = 0; v < base.vertexCount(); ++v) {
    const Eigen::Vector3d p = vertex(base, v);
    if (rigid[v] == 0) {
      EXPECT_EQ(vertex(rotated, v), p);
      EXPECT_EQ(vertex(scaled, v), p);
      continue;
    }
    EXPECT_NEAR((vertex(rotated, v) - (pivot + R * (p - pivot))).norm(), 0.0, kFloatTol * 4);
    const Eigen::Vector3d d = p - pivot;
    const Eigen::Vector3d expect =
        pivot + 1.5 * d.dot(f.right) * f.right + 0.5 * d.dot(f.up) * f.up + d.dot(f.back) * f.back;
    EXPECT_NEAR((vertex(scaled, v) - expect).norm(), 0.0, kFloatTol * 4);
    EXPECT_NEAR(project(cam, 64, 48, vertex(rotated, v)).depth, project(cam, 64, 48, p).depth, kFloatTol * 8);
    EXPECT_NEAR(project(cam, 64, 48, vertex(scaled, v)).depth, project(cam, 64, 48, p).depth, kFloatTol * 8);
  }
}

INSTANTIATE_TEST_SUITE_P(Projections, ImagePlane, ::testing::Values(false, true),
                         [](const auto& param_info) { return param_info.param ? "Ortho" : "Perspective"; });

TEST(Displace, GraphDistanceAttenuation) {
  TriMesh m = test::grid(9, 0.1);
  const int seed = 4 * 9 + 4;
  const std::vector<double> w =
      seedWeights(DistanceMetric::kEdges, Falloff{3.0, 1.0, FalloffShape::kPower}, m.positions, m.triangles, seed);
  const TriMesh base = m;
  displaceVertices(m.positions, w, {0, 0, 0.3});
  EXPECT_NEAR(m.positions[3 * seed + 2], 0.3, 1e-7);
  EXPECT_NEAR(m.positions[3 * (seed + 1) + 2], 0.3 * (2.0 / 3.0), 1e-7);  // one edge away
  EXPECT_NEAR(m.positions[3 * (seed + 2) + 2], 0.3 * (1.0 / 3.0), 1e-7);  // two edges
  EXPECT_EQ(m.positions[3 * (seed + 3) + 2], 0.0f);                       // three: at r
}

// ---- FFD ----

TEST(Ffd, UndisplacedLatticeIsIdentity) {
  const TriMesh base = test::sphere(8, 16, 1.0);
  for (const std::array<int, 3> degree : {std::array<int, 3>{1, 1, 1}, {3, 2, 4}}) {
    Eigen::Matrix3d frame = Eigen::AngleAxisd(0.4, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
    const FfdLattice lattice = ffdLatticeAround(base.positions, {}, frame, degree, 0.1);
    const FfdBinding binding = bindFfd(lattice, base.positions);
    EXPECT_EQ(binding.vertices.size(), base.vertexCount());
    TriMesh m = base;
    applyFfd(lattice, binding, m.positions);
    for (std::size_t i = 0; i < m.positions.size(); ++i) EXPECT_NEAR(m.positions[i], base.positions[i], 1e-6);
  }
}

TEST(Ffd, AffineLatticeDisplacementIsThatAffineMap) {
  const TriMesh base = test::sphere(8, 16, 1.0);
  FfdLattice lattice = makeFfdLattice({-1.2, -1.1, -1.3}, Eigen::Vector3d(2.5, 2.3, 2.6).asDiagonal(), {2, 3, 2});
  const FfdBinding binding = bindFfd(lattice, base.positions);
  ASSERT_EQ(binding.vertices.size(), base.vertexCount());
  Eigen::Matrix3d A;
  A << 1.2, 0.3, 0.0, -0.1, 0.8, 0.2, 0.05, 0.0, 1.4;
  const Eigen::Vector3d t(0.3, -0.5, 0.7);
  for (auto& p : lattice.control_points) p = A * p + t;
  TriMesh m = base;
  applyFfd(lattice, binding, m.positions);
  for (std::size_t v = 0; v < m.vertexCount(); ++v)
    EXPECT_NEAR((vertex(m, v) - (A * vertex(base, v) + t)).norm(), 0.0, 1e-5);
}

TEST(Ffd, OutsideVerticesUntouchedAndBadLatticesRejected) {
  const TriMesh base = test::grid(5, 1.0);
  FfdLattice lattice = makeFfdLattice({-0.5, -0.5, -0.5}, Eigen::Matrix3d::Identity(), {1, 1, 1});
  const FfdBinding binding = bindFfd(lattice, base.positions);
  EXPECT_EQ(binding.vertices.size(), 1u);  // only the centre vertex (0, 0, 0)
  lattice.point(1, 1, 1) += Eigen::Vector3d(1, 1, 1);
  TriMesh m = base;
  applyFfd(lattice, binding, m.positions);
  for (std::size_t v = 0; v < m.vertexCount(); ++v)
    if (v != 12) {
      EXPECT_EQ(vertex(m, v), vertex(base, v));
    }
  EXPECT_THROW(makeFfdLattice({0, 0, 0}, Eigen::Matrix3d::Identity(), {0, 1, 1}), Error);
  EXPECT_THROW(makeFfdLattice({0, 0, 0}, Eigen::Vector3d(1, 1, 0).asDiagonal(), {1, 1, 1}), Error);
}

TEST(Affine, SquashStretchPreservesVolume) {
  const Eigen::Matrix3d S = squashStretchMatrix({0, 2, 0}, 1.5, true);
  EXPECT_NEAR(S.determinant(), 1.0, 1e-12);
  EXPECT_NEAR((S * Eigen::Vector3d::UnitY() - 1.5 * Eigen::Vector3d::UnitY()).norm(), 0.0, 1e-12);
  EXPECT_THROW(squashStretchMatrix({0, 1, 0}, 0.0, true), Error);
}

}  // namespace
}  // namespace vdg
