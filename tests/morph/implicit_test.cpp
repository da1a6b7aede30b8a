// Implicit surfaces (Parent 4.11): the field functions against their formulas, the polygonised
// surface against the analytic radius, closedness, components that separate and fuse, and the
// animation tracks.
#include "vdg/morph/implicit.h"
#include "vdg/morph/polygonise.h"

#include <gtest/gtest.h>

#include <limits>

#include <cmath>

#include "support/error_of.h"
#include "vdg/morph/mesh_checks.h"

namespace vdg::morph {
namespace {

using testing::errorOf;

// Closed-form values are computed in double: agreement to rounding.
constexpr double kFormulaTolerance = 1e-12;
// Central differences with step 1e-5 on fields of unit scale: truncation ~1e-10, rounding ~1e-11.
constexpr double kGradientTolerance = 1e-7;
constexpr double kGradientStep = 1e-5;

BlobPrimitive prim(FieldKind kind, Eigen::Vector3d c, double radius, double strength = 1.0, double blobbiness = 1.0) {
  return {.kind = kind, .center = c, .radius = radius, .strength = strength, .blobbiness = blobbiness};
}

BlobModel model(std::vector<BlobPrimitive> p, double threshold) {
  return BlobModel::build(RawBlobModel{.primitives = std::move(p), .threshold = threshold});
}

// Signed volume of a closed mesh (positive when its triangles wind counter-clockwise seen from
// outside).
double signedVolume(const TriMesh& m) {
  double v = 0;
  for (std::size_t f = 0; f < m.triangleCount(); ++f) {
    Eigen::Vector3d p[3];
    for (int k = 0; k < 3; ++k) {
      const auto i = static_cast<std::size_t>(m.triangles[3 * f + k]);
      p[k] = Eigen::Vector3d(m.positions[3 * i], m.positions[3 * i + 1], m.positions[3 * i + 2]);
    }
    v += p[0].dot(p[1].cross(p[2])) / 6.0;
  }
  return v;
}

TEST(ImplicitField, BlinnMatchesItsFormula) {
  const BlobPrimitive p = prim(FieldKind::kBlinn, {1, 2, 3}, 0.8, 2.5, 1.7);
  const BlobModel m = model({p}, 0.5);
  const double a = 1.7 / (0.8 * 0.8);
  for (double r : {0.0, 0.1, 0.5, 0.8, 1.3, 3.0}) {
    const Eigen::Vector3d x = p.center + r * Eigen::Vector3d(0.6, 0.0, 0.8);
    EXPECT_NEAR(m.field(x), 2.5 * std::exp(-a * r * r), kFormulaTolerance) << "r = " << r;
  }
  // Cut-off: D(r_cut) = T * 1e-3.
  const double rc = supportRadius(p, 0.5);
  EXPECT_NEAR(primitiveField(p, rc), 0.5 * kBlinnCutoff, kFormulaTolerance);
}

TEST(ImplicitField, WyvillAndNishimuraKnownValues) {
  const BlobPrimitive w = prim(FieldKind::kWyvill, {0, 0, 0}, 2.0, 3.0);
  EXPECT_NEAR(primitiveField(w, 0.0), 3.0, kFormulaTolerance);
  EXPECT_NEAR(primitiveField(w, 1.0), 1.5, kFormulaTolerance);  // C(R/2) = s/2
  EXPECT_NEAR(primitiveField(w, 2.0), 0.0, kFormulaTolerance);
  EXPECT_EQ(primitiveField(w, 2.5), 0.0);
  const double q = 0.7 * 0.7 / 4.0;
  EXPECT_NEAR(primitiveField(w, 0.7), 3.0 * (1 - 22.0 / 9 * q + 17.0 / 9 * q * q - 4.0 / 9 * q * q * q),
              kFormulaTolerance);
  const BlobPrimitive n = prim(FieldKind::kNishimura, {0, 0, 0}, 3.0, 2.0);
  EXPECT_NEAR(primitiveField(n, 0.0), 2.0, kFormulaTolerance);
  EXPECT_NEAR(primitiveField(n, 1.0), 2.0 * 2.0 / 3.0, kFormulaTolerance);  // both pieces: 2b/3 at R/3
  EXPECT_NEAR(primitiveField(n, 1.0 - 1e-9), primitiveField(n, 1.0 + 1e-9), 1e-8);
  EXPECT_NEAR(primitiveField(n, 2.0), 1.5 * 2.0 / 9.0, kFormulaTolerance);
  EXPECT_EQ(primitiveField(n, 3.0), 0.0);
}

TEST(ImplicitField, GradientMatchesCentralDifferences) {
  const BlobModel m =
      model({prim(FieldKind::kBlinn, {0, 0, 0}, 1.0, 1.0, 2.0), prim(FieldKind::kWyvill, {0.8, 0.1, 0}, 1.2, 0.7),
             prim(FieldKind::kNishimura, {-0.5, 0.4, 0.3}, 1.5, -0.4)},
            0.5);
  for (const Eigen::Vector3d& p : {Eigen::Vector3d(0.1, 0.2, 0.3), Eigen::Vector3d(0.9, -0.3, 0.2),
                                   Eigen::Vector3d(-0.9, 0.6, 0.1), Eigen::Vector3d(-0.2, 0.7, 0.95)}) {
    const Eigen::Vector3d g = m.gradient(p);
    for (int a = 0; a < 3; ++a) {
      Eigen::Vector3d e = Eigen::Vector3d::Zero();
      e[a] = kGradientStep;
      EXPECT_NEAR(g[a], (m.field(p + e) - m.field(p - e)) / (2 * kGradientStep), kGradientTolerance)
          << "axis " << a << " at " << p.transpose();
    }
  }
}

TEST(ImplicitField, SampleChecksItsContract) {
  const BlobModel m = model({prim(FieldKind::kWyvill, {0, 0, 0}, 1.0)}, 0.5);
  const double pts[6] = {0, 0, 0, 0.5, 0, 0};
  double out[2] = {-7, -7};
  EXPECT_FALSE(m.sample(std::span<const double>(pts, 5), std::span<double>(out, 2)));
  const double bad[3] = {std::nan(""), 0, 0};
  EXPECT_FALSE(m.sample(bad, std::span<double>(out, 1)));
  EXPECT_EQ(out[0], -7);
  ASSERT_TRUE(m.sample(pts, out));
  EXPECT_NEAR(out[0], 1.0, kFormulaTolerance);
  EXPECT_NEAR(out[1], 0.5, kFormulaTolerance);
}

// A single soft object: the surface is where C(r) = T; with s = 1, T = 0.5 that is r = R/2
// exactly, and for T = 0.2 the root of the cubic in q (found by bisection).
TEST(ImplicitPolygonise, SingleSoftObjectLiesAtTheAnalyticRadius) {
  for (double T : {0.5, 0.2}) {
    const BlobPrimitive p = prim(FieldKind::kWyvill, {0.3, -0.2, 0.1}, 1.0);
    double lo = 0, hi = 1;
    for (int it = 0; it < 200; ++it) {
      const double mid = 0.5 * (lo + hi);
      (primitiveField(p, mid) > T ? lo : hi) = mid;
    }
    const double r_star = lo;
    if (T == 0.5) {
      EXPECT_NEAR(r_star, 0.5, 1e-12);
    }
    const double h = 0.04;
    const double kOneVoxel = h;
    const TriMesh mesh = polygonise(model({p}, T), {.voxel_size = h});
    ASSERT_GT(mesh.triangleCount(), 100u);
    requireClosed(mesh, "sphere");
    EXPECT_EQ(connectedComponents(mesh), 1u);
    EXPECT_EQ(eulerCharacteristic(mesh), 2);
    for (std::size_t v = 0; v < mesh.vertexCount(); ++v) {
      const Eigen::Vector3d x(mesh.positions[3 * v], mesh.positions[3 * v + 1], mesh.positions[3 * v + 2]);
      ASSERT_NEAR((x - p.center).norm(), r_star, kOneVoxel) << "vertex " << v << ", T = " << T;
    }
    // Outward orientation: a positive volume close to the ball's (the polygon is inscribed: a few %).
    const double ball = 4.0 / 3.0 * M_PI * r_star * r_star * r_star;
    EXPECT_NEAR(signedVolume(mesh), ball, 0.05 * ball);
  }
}

// Two soft objects (R = 1, s = 1, T = 0.5: each alone a sphere of radius 0.5) 3 apart give two
// closed spheres; 1.2 apart the field at the midpoint is 2 C(0.6) = 0.688 > T and they fuse.
// Blinn: b = T e, B = 1, R = 0.5 (alone a sphere of radius 0.5 too).
TEST(ImplicitPolygonise, FarApartTwoComponentsCloseTogetherOne) {
  for (FieldKind kind : {FieldKind::kWyvill, FieldKind::kNishimura, FieldKind::kBlinn}) {
    SCOPED_TRACE(fieldKindName(kind));
    const double s = kind == FieldKind::kBlinn ? 0.5 * std::exp(1.0) : 1.0;  // Blinn: isolated radius R
    const double R = kind == FieldKind::kBlinn ? 0.5 : 1.0;
    const auto pair = [&](double d) {
      return model({prim(kind, {-d / 2, 0, 0}, R, s), prim(kind, {d / 2, 0, 0}, R, s)}, 0.5);
    };
    const TriMesh apart = polygonise(pair(3.0), {.voxel_size = 0.05});
    requireClosed(apart, "apart");
    EXPECT_EQ(connectedComponents(apart), 2u);
    EXPECT_EQ(eulerCharacteristic(apart), 4);
    EXPECT_GT(signedVolume(apart), 0);
    // Nishimura: 2 f(0.5) = 3 (0.5)^2 = 0.75 > T at 1.0 apart (at 1.2 it is 0.48: still apart).
    const double close = kind == FieldKind::kWyvill ? 1.2 : kind == FieldKind::kNishimura ? 1.0 : 1.1;
    EXPECT_GT(pair(close).field(Eigen::Vector3d::Zero()), 0.5);
    const TriMesh fused = polygonise(pair(close), {.voxel_size = 0.05});
    requireClosed(fused, "fused");
    EXPECT_EQ(connectedComponents(fused), 1u);
    EXPECT_EQ(eulerCharacteristic(fused), 2);
    EXPECT_GT(signedVolume(fused), signedVolume(apart));
  }
}

// A negative primitive carves a hole through a flat soft blob: the surface changes genus.
TEST(ImplicitPolygonise, NegativeStrengthSubtracts) {
  std::vector<BlobPrimitive> ring;
  for (int i = 0; i < 12; ++i) {
    const double a = 2 * M_PI * i / 12;
    ring.push_back(prim(FieldKind::kWyvill, {1.2 * std::cos(a), 0, 1.2 * std::sin(a)}, 1.0));
  }
  const TriMesh torus = polygonise(model(ring, 0.5), {.voxel_size = 0.04});
  requireClosed(torus, "ring");
  EXPECT_EQ(eulerCharacteristic(torus), 0);  // a torus
  ring.push_back(prim(FieldKind::kWyvill, {0, 0, 0}, 1.5, -2.0));
  const TriMesh carved = polygonise(model(ring, 0.5), {.voxel_size = 0.04});
  requireClosed(carved, "carved");
  EXPECT_LT(signedVolume(carved), signedVolume(torus));
}

TEST(ImplicitPolygonise, NoSurfaceGivesAnEmptyMesh) {
  EXPECT_EQ(
      polygonise(model({prim(FieldKind::kWyvill, {0, 0, 0}, 1.0, 0.4)}, 0.5), {.voxel_size = 0.1}).triangleCount(), 0u);
  EXPECT_EQ(polygonise(model({prim(FieldKind::kWyvill, {0, 0, 0}, 1.0, -1.0)}, 0.5)).triangleCount(), 0u);
}

TEST(ImplicitPolygonise, RefusesTooManyVoxelsBeforeAllocating) {
  const BlobModel m = model({prim(FieldKind::kWyvill, {0, 0, 0}, 1.0)}, 0.5);
  // Box [-1, 1]^3 at 0.01: (200 + 1 + 4)^3 = 8615125 voxels.
  EXPECT_EQ(errorOf([&] { (void)polygonise(m, {.voxel_size = 0.01, .max_voxels = 1000000}, "b.json"); }),
            "b.json: the grid needs 8615125 voxels (about 66 MiB) at voxel size 0.01; use a --voxel of at least "
            "0.0212");
  // The suggestion fits: ceil(2 / 0.0212) + 1 + 4 = 100 per side.
  EXPECT_EQ(gridVoxelCount(m.bounds(), 0.0212), 1000000.0);
  EXPECT_GT(gridVoxelCount(m.bounds(), 0.0205), 1000000.0);
  EXPECT_EQ(errorOf([&] { (void)polygonise(m, {.voxel_size = -1}, "b.json"); }),
            "b.json: voxel size must be a finite number >= 0, got -1");
}

// A voxel of 1e-300 over a box 2 wide: about 1e903 voxels, past what a double holds. The count
// is +infinity, refused with a finite suggestion that fits (it used to read "at least nan").
TEST(ImplicitPolygonise, AVoxelCountPastWhatADoubleHoldsIsRefusedWithASizeThatFits) {
  const BlobModel m = model({prim(FieldKind::kWyvill, {0, 0, 0}, 1.0)}, 0.5);
  const std::string message = errorOf([&] { checkVoxelBudget(m.bounds(), 1e-300, std::size_t{1} << 27, "b.json"); });
  EXPECT_EQ(message.rfind("b.json: the grid needs more than 1e308 voxels at voxel size "
                          "1e-300; use a --voxel of at least ",
                          0),
            0u)
      << message;
  const double suggested = std::stod(message.substr(message.rfind(' ') + 1));
  EXPECT_LE(gridVoxelCount(m.bounds(), suggested), static_cast<double>(std::size_t{1} << 27)) << message;
  EXPECT_GT(gridVoxelCount(m.bounds(), suggested * 0.99), static_cast<double>(std::size_t{1} << 27)) << message;
}

// The estimate: every grid point twice, every support box per grid row, every primitive at every
// voxel of its support box. Thousands of primitives over one spot cost thousands of grids.
TEST(ImplicitPolygonise, CostCountsEveryPrimitiveAtEveryVoxelOfItsSupport) {
  const BlobModel one = model({prim(FieldKind::kWyvill, {0, 0, 0}, 1.0)}, 0.5);
  const double h = 0.05, voxels = gridVoxelCount(one.bounds(), h);  // (40 + 1 + 4)^3
  ASSERT_EQ(voxels, 45.0 * 45 * 45);
  const double single = polygoniseCost(one, h);
  EXPECT_GT(single, 2 * voxels);
  EXPECT_LT(single, 3 * voxels + 45 * 45);
  std::vector<BlobPrimitive> many(kMaxBlobPrimitives, prim(FieldKind::kWyvill, {0, 0, 0}, 1.0));
  const double crowd = polygoniseCost(model(many, 0.5), h);
  EXPECT_GT(crowd, 0.5 * static_cast<double>(kMaxBlobPrimitives) * voxels);
  // At a voxel of 0.02 (about a million grid points) 4096 blobs at one spot pass the default budget.
  EXPECT_GT(polygoniseCost(model(many, 0.5), 0.02), 2e9);
  // Halving the voxel multiplies the work by about 8; a voxel past any grid is +infinity, not a wrap.
  EXPECT_GT(polygoniseCost(one, h / 2), 6 * single);
  EXPECT_EQ(polygoniseCost(one, 1e-300), std::numeric_limits<double>::infinity());
}

TEST(ImplicitModel, RefusesBadPrimitives) {
  const auto err = [](std::vector<BlobPrimitive> p, double T) {
    return errorOf([&] { (void)BlobModel::build(RawBlobModel{.primitives = std::move(p), .threshold = T}, "b.json"); });
  };
  const BlobPrimitive ok = prim(FieldKind::kWyvill, {0, 0, 0}, 1.0);
  EXPECT_EQ(err({}, 0.5), "b.json: no primitives");
  EXPECT_EQ(err({ok}, 0.0), "b.json: threshold must be > 0, got 0");
  EXPECT_EQ(err({ok}, -1.0), "b.json: threshold must be > 0, got -1");
  EXPECT_EQ(err({ok, prim(FieldKind::kWyvill, {0, 0, 0}, -2.0)}, 0.5),
            "b.json: primitives[1]: radius must be > 0, got -2");
  EXPECT_EQ(err({prim(FieldKind::kBlinn, {0, 0, 0}, 1.0, 1.0, 0.0)}, 0.5),
            "b.json: primitives[0]: blobbiness must be > 0, got 0");
  EXPECT_EQ(err({prim(FieldKind::kBlinn, {0, 0, 0}, 1e-200, 1.0, 1e200)}, 0.5),
            "b.json: primitives[0]: radius must be in [1e-12, 1e+12], got 1e-200");
  EXPECT_EQ(err({prim(FieldKind::kBlinn, {0, 0, 0}, 1.0, 1.0, 1e4)}, 0.5),
            "b.json: primitives[0]: blobbiness must be in [0.001, 1000], got 10000");
  EXPECT_EQ(err({prim(FieldKind::kWyvill, {0, 0, 1e13}, 1.0)}, 0.5),
            "b.json: primitives[0]: center must be 3 numbers in [-1e+12, 1e+12]");
  EXPECT_EQ(err({prim(FieldKind::kWyvill, {0, std::nan(""), 0}, 1.0)}, 0.5),
            "b.json: primitives[0]: center must be 3 numbers in [-1e+12, 1e+12]");
}

anim::RawTrack track(std::vector<std::pair<double, Eigen::VectorXd>> keys, anim::TrackType type,
                     anim::Interpolation interpolation = anim::Interpolation::kCatmullRom) {
  anim::RawTrack t;
  t.type = type;
  t.interpolation = interpolation;
  for (auto& [time, value] : keys) {
    anim::RawKey key;
    key.time = time;
    key.value = value;
    t.keys.push_back(key);
  }
  return t;
}
Eigen::VectorXd v1(double x) { return Eigen::VectorXd::Constant(1, x); }
Eigen::VectorXd v3(double x, double y, double z) { return Eigen::Vector3d(x, y, z); }

RawBlobAnimation twoBlobs() {
  RawBlobAnimation a;
  a.threshold = 0.5;
  a.first_frame = 0;
  a.last_frame = 20;
  a.primitives.push_back({.kind = FieldKind::kWyvill,
                          .center = track({{0, v3(-1.5, 0, 0)}, {10, v3(-0.6, 0.1, 0)}, {20, v3(-1.5, 0.3, 0.2)}},
                                          anim::TrackType::kVector),
                          .radius = track({{0, v1(1.0)}}, anim::TrackType::kScalar),
                          .strength = track({{0, v1(1.0)}, {20, v1(1.2)}}, anim::TrackType::kScalar)});
  a.primitives.push_back(
      {.kind = FieldKind::kWyvill,
       .center = track({{0, v3(1.5, 0, 0)}, {10, v3(0.6, 0, 0)}, {20, v3(1.5, 0, 0)}}, anim::TrackType::kVector),
       .radius = track({{0, v1(1.0)}, {10, v1(1.1)}, {20, v1(0.9)}}, anim::TrackType::kScalar),
       .strength = track({{0, v1(1.0)}}, anim::TrackType::kScalar)});
  return a;
}

TEST(ImplicitAnimation, TracksHitTheirKeysExactly) {
  const BlobAnimation a = BlobAnimation::build(twoBlobs());
  EXPECT_EQ(a.primitiveCount(), 2u);
  EXPECT_EQ(a.lastFrame(), 20);
  const BlobModel m10 = a.modelAt(10);
  EXPECT_EQ(m10.primitives()[0].center, Eigen::Vector3d(-0.6, 0.1, 0));
  EXPECT_EQ(m10.primitives()[1].center, Eigen::Vector3d(0.6, 0, 0));
  EXPECT_EQ(m10.primitives()[1].radius, 1.1);
  EXPECT_EQ(a.modelAt(20).primitives()[0].center, Eigen::Vector3d(-1.5, 0.3, 0.2));
  EXPECT_EQ(a.modelAt(20).primitives()[0].strength, 1.2);
  EXPECT_EQ(a.modelAt(0).primitives()[1].center, Eigen::Vector3d(1.5, 0, 0));
  // Between keys: strictly between (the linear strength track halfway).
  EXPECT_NEAR(a.modelAt(10).primitives()[0].strength, 1.1, kFormulaTolerance);
  // Apart at frame 0, fused at frame 10, apart again at 20.
  EXPECT_EQ(connectedComponents(polygonise(a.modelAt(0), {.voxel_size = 0.06})), 2u);
  EXPECT_EQ(connectedComponents(polygonise(a.modelAt(10), {.voxel_size = 0.06})), 1u);
  EXPECT_EQ(connectedComponents(polygonise(a.modelAt(20), {.voxel_size = 0.06})), 2u);
}

TEST(ImplicitAnimation, EvaluateChecksItsContract) {
  const BlobAnimation a = BlobAnimation::build(twoBlobs());
  BlobModel m = a.modelAt(0);
  ASSERT_TRUE(a.evaluate(10, m));
  EXPECT_EQ(m.primitives()[0].center, Eigen::Vector3d(-0.6, 0.1, 0));
  EXPECT_FALSE(a.evaluate(std::nan(""), m));
  EXPECT_EQ(m.primitives()[0].center, Eigen::Vector3d(-0.6, 0.1, 0));
  BlobModel one = BlobModel::build(RawBlobModel{.primitives = {prim(FieldKind::kWyvill, {0, 0, 0}, 1.0)}});
  EXPECT_FALSE(a.evaluate(5, one));
  EXPECT_EQ(one.primitives()[0].center, Eigen::Vector3d::Zero());
  EXPECT_EQ(errorOf([&] { (void)a.modelAt(INFINITY); }), "blob animation: frame inf is not finite");
}

// A radius track that overshoots below zero between keys switches the primitive off there.
TEST(ImplicitAnimation, RadiusBelowZeroSwitchesThePrimitiveOff) {
  RawBlobAnimation raw = twoBlobs();
  // Bezier handles pull the radius curve below zero between its keys.
  raw.primitives[1].radius =
      track({{0, v1(1.0)}, {10, v1(1.0)}}, anim::TrackType::kScalar, anim::Interpolation::kBezier);
  raw.primitives[1].radius.keys[0].out_handle = v1(-5.0);
  raw.primitives[1].radius.keys[1].in_handle = v1(-5.0);
  const BlobAnimation a = BlobAnimation::build(raw);
  const BlobModel m = a.modelAt(5);
  EXPECT_TRUE(m.active(0));
  EXPECT_FALSE(m.active(1));
  EXPECT_EQ(m.field(Eigen::Vector3d(1.5, 0, 0)), 0.0);
  EXPECT_EQ(connectedComponents(polygonise(m, {.voxel_size = 0.06})), 1u);
  EXPECT_TRUE(a.modelAt(10).active(1));
}

TEST(ImplicitAnimation, RefusesBadTracks) {
  RawBlobAnimation raw = twoBlobs();
  raw.primitives[1].radius.keys[1].value = v1(-0.5);
  EXPECT_EQ(errorOf([&] { (void)BlobAnimation::build(raw, "b.json"); }),
            "b.json: primitives[1].'radius': key 1: radius must be > 0, got -0.5");
  raw = twoBlobs();
  raw.primitives[0].center = track({{0, v1(1.0)}}, anim::TrackType::kScalar);
  EXPECT_EQ(errorOf([&] { (void)BlobAnimation::build(raw, "b.json"); }),
            "b.json: primitives[0].'center': expected a track of 3 numbers");
  raw = twoBlobs();
  raw.first_frame = 30;
  EXPECT_EQ(errorOf([&] { (void)BlobAnimation::build(raw, "b.json"); }),
            "b.json: frames: the first frame 30 is after the last 20");
}

}  // namespace
}  // namespace vdg::morph
