// Tests of key-framed curves (Parent 4.1) and arc length (table, Gaussian and adaptive quadrature).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "vdg/anim/arc_length.h"
#include "vdg/anim/curve.h"
#include "vdg/geom/error.h"

namespace vdg::anim {
namespace {

constexpr double kTol = 1e-10;
constexpr double kContinuityStep = 1e-7;
constexpr double kContinuityTol = 1e-5;
constexpr double kPi = std::numbers::pi;

Eigen::VectorXd vec(std::initializer_list<double> v) {
  Eigen::VectorXd r(static_cast<Eigen::Index>(v.size()));
  int i = 0;
  for (double x : v) r[i++] = x;
  return r;
}

RawCurve sampleRaw(CurveKind kind) {
  RawCurve r;
  r.kind = kind;
  r.points = {vec({0, 0, 0}), vec({1, 2, 0}), vec({3, 2, 1}), vec({4, 0, 1}), vec({6, 1, -1})};
  r.times = {0.0, 1.0, 2.5, 3.0, 4.2};
  if (kind == CurveKind::kBezier) {
    r.points.push_back(vec({7, 2, 0}));
    r.points.push_back(vec({8, 0, 0}));
    r.times = {0.0, 1.0, 2.5};
  }
  return r;
}

const CurveKind kAllKinds[] = {
    CurveKind::kLinear,       CurveKind::kCatmullRom,        CurveKind::kCentripetalCatmullRom,
    CurveKind::kNaturalCubic, CurveKind::kParabolicBlending, CurveKind::kBezier};

TEST(Curve, InterpolatingKindsPassThroughKeysAtKeyTimes) {
  for (CurveKind kind : kAllKinds) {
    SCOPED_TRACE(curveKindName(kind));
    const RawCurve raw = sampleRaw(kind);
    const Curve c = Curve::build(raw);
    EXPECT_EQ(isInterpolating(kind), kind != CurveKind::kBezier);
    if (kind == CurveKind::kBezier) {  // anchors only
      for (std::size_t i = 0; i < raw.times.size(); ++i)
        EXPECT_LT((c.at(raw.times[i]) - raw.points[3 * i]).norm(), kTol);
      continue;
    }
    for (std::size_t i = 0; i < raw.points.size(); ++i) EXPECT_LT((c.at(raw.times[i]) - raw.points[i]).norm(), kTol);
  }
}

TEST(Curve, ContinuityAtKeys) {
  for (CurveKind kind : kAllKinds) {
    SCOPED_TRACE(curveKindName(kind));
    const Curve c = Curve::build(sampleRaw(kind));
    for (std::size_t k = 1; k + 1 < c.keyTimes().size(); ++k) {
      const double t = c.keyTimes()[k];
      EXPECT_LT((c.at(t - kContinuityStep) - c.at(t + kContinuityStep)).norm(), kContinuityTol);  // C0
      const Eigen::VectorXd d_left = c.derivativeAt(t - kContinuityStep), d_right = c.derivativeAt(t + kContinuityStep);
      if (kind == CurveKind::kCatmullRom || kind == CurveKind::kNaturalCubic || kind == CurveKind::kParabolicBlending) {
        EXPECT_LT((d_left - d_right).norm(), 1e-4);  // C1 in t
      }
      if (kind == CurveKind::kCentripetalCatmullRom) {  // G1: tangent direction continuous
        EXPECT_GT(d_left.normalized().dot(d_right.normalized()), 1 - 1e-6);
      }
      if (kind == CurveKind::kNaturalCubic) {  // C2
        const double h = 1e-4;
        const Eigen::VectorXd a_left = (c.derivativeAt(t - h) - c.derivativeAt(t - 2 * h)) / h;
        const Eigen::VectorXd a_right = (c.derivativeAt(t + 2 * h) - c.derivativeAt(t + h)) / h;
        EXPECT_LT((a_left - a_right).norm(), 1e-2);
      }
    }
  }
}

TEST(Curve, DerivativeMatchesFiniteDifferences) {
  for (CurveKind kind : kAllKinds) {
    SCOPED_TRACE(curveKindName(kind));
    const Curve c = Curve::build(sampleRaw(kind));
    for (double t : {0.3, 1.7, 2.2}) {
      const double h = 1e-6;
      const Eigen::VectorXd fd = (c.at(t + h) - c.at(t - h)) / (2 * h);
      EXPECT_LT((fd - c.derivativeAt(t)).norm(), 1e-5);
    }
  }
}

TEST(Curve, NaturalCubicHasZeroEndCurvatureAndEndTangentsAreDocumented) {
  const Curve nat = Curve::build(sampleRaw(CurveKind::kNaturalCubic));
  const double h = 1e-4;
  EXPECT_LT(((nat.derivativeAt(h) - nat.derivativeAt(0)) / h).norm(), 1e-2);
  EXPECT_LT(((nat.derivativeAt(4.2) - nat.derivativeAt(4.2 - h)) / h).norm(), 1e-2);
  // Catmull-Rom: end tangent = chord slope of the end segment; interior = central difference.
  const RawCurve raw = sampleRaw(CurveKind::kCatmullRom);
  const Curve cr = Curve::build(raw);
  EXPECT_LT((cr.derivativeAt(0.0) - (raw.points[1] - raw.points[0]) / 1.0).norm(), kTol);
  EXPECT_LT((cr.derivativeAt(1.0) - (raw.points[2] - raw.points[0]) / 2.5).norm(), 1e-9);
}

TEST(Curve, UniformParabolicBlendingEqualsCatmullRomInTheInterior) {
  RawCurve raw = sampleRaw(CurveKind::kCatmullRom);
  raw.times.clear();  // 0, 1, 2, 3, 4
  const Curve cr = Curve::build(raw);
  raw.kind = CurveKind::kParabolicBlending;
  const Curve pb = Curve::build(raw);
  for (double t = 1.0; t <= 3.0; t += 0.05) EXPECT_LT((cr.at(t) - pb.at(t)).norm(), 1e-12) << t;
  // The classic uniform Catmull-Rom matrix form on segment 1.
  const double u = 0.3;
  const Eigen::VectorXd classic =
      0.5 * ((2 * raw.points[1]) + (-raw.points[0] + raw.points[2]) * u +
             (2 * raw.points[0] - 5 * raw.points[1] + 4 * raw.points[2] - raw.points[3]) * u * u +
             (-raw.points[0] + 3 * raw.points[1] - 3 * raw.points[2] + raw.points[3]) * u * u * u);
  EXPECT_LT((cr.at(1.3) - classic).norm(), 1e-12);
}

TEST(Curve, BezierIsDeCasteljau) {
  RawCurve raw;
  raw.kind = CurveKind::kBezier;
  raw.points = {vec({0, 0}), vec({0, 1}), vec({1, 1}), vec({1, 0})};
  const Curve c = Curve::build(raw);
  const double u = 0.25;
  const Eigen::VectorXd bernstein = std::pow(1 - u, 3) * raw.points[0] + 3 * u * (1 - u) * (1 - u) * raw.points[1] +
                                    3 * u * u * (1 - u) * raw.points[2] + u * u * u * raw.points[3];
  EXPECT_LT((c.at(u) - bernstein).norm(), kTol);
  EXPECT_FALSE(isInterpolating(CurveKind::kBezier));
  EXPECT_FALSE(hasLocalControl(CurveKind::kNaturalCubic));
  EXPECT_TRUE(hasLocalControl(CurveKind::kCatmullRom));
}

TEST(Curve, LocalVersusGlobalControl) {
  // Moving key 0 changes a far segment of the natural spline but not of Catmull-Rom.
  for (CurveKind kind : {CurveKind::kCatmullRom, CurveKind::kNaturalCubic}) {
    RawCurve raw = sampleRaw(kind);
    const Curve before = Curve::build(raw);
    raw.points[0] += vec({0, 5, 0});
    const Curve after = Curve::build(raw);
    const double moved = (before.at(3.6) - after.at(3.6)).norm();
    if (kind == CurveKind::kCatmullRom) {
      EXPECT_EQ(moved, 0.0);
    } else {
      EXPECT_GT(moved, 1e-4);
    }
  }
}

TEST(Curve, CentripetalHasNoCuspOnUnevenKeys) {
  // A classic cusp/loop case for uniform Catmull-Rom: a short segment between long ones.
  RawCurve raw;
  raw.kind = CurveKind::kCentripetalCatmullRom;
  raw.points = {vec({0, 0}), vec({1, 10}), vec({1.2, 10}), vec({2, 0})};
  const Curve c = Curve::build(raw);
  const Eigen::VectorXd chord = raw.points[2] - raw.points[1];
  for (double t = 1.0; t <= 2.0; t += 0.01) EXPECT_GT(c.derivativeAt(t).dot(chord), 0.0) << t;
  double min_speed = 1e9;
  for (double t = 0.0; t <= 3.0; t += 0.001) min_speed = std::min(min_speed, c.derivativeAt(t).norm());
  EXPECT_GT(min_speed, 1e-3);  // no cusp anywhere
}

TEST(Curve, ClampsOutsideTheKeyRangeAndHandlesAnyDimension) {
  RawCurve raw;
  raw.kind = CurveKind::kNaturalCubic;
  raw.points = {vec({1}), vec({3}), vec({2})};
  const Curve c = Curve::build(raw);
  EXPECT_EQ(c.dimension(), 1);
  EXPECT_EQ(c.at(-5)[0], 1.0);
  EXPECT_EQ(c.at(7)[0], 2.0);
  EXPECT_EQ(c.startTime(), 0.0);
  EXPECT_EQ(c.endTime(), 2.0);
}

void expectError(const RawCurve& raw, const std::string& message) {
  try {
    Curve::build(raw, "spec.json");
    FAIL() << "expected: " << message;
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), message);
  }
}

TEST(Curve, RejectsInvalidInput) {
  RawCurve raw;
  raw.kind = CurveKind::kLinear;
  raw.points = {vec({0, 0, 0})};
  expectError(raw, "spec.json: 'points': a linear curve needs at least 2 points, got 1");
  raw.points = {vec({0, 0, 0}), vec({1, 1})};
  expectError(raw, "spec.json: 'points'[1]: expected 3 numbers like 'points'[0], got 2");
  raw.points = {vec({0, 0}), vec({1, NAN})};
  expectError(raw, "spec.json: 'points'[1]: coordinates must be finite");
  raw.points = {vec({0, 0}), vec({1, 1})};
  raw.times = {0};
  expectError(raw, "spec.json: 'times': expected 2 key times (one per point), got 1");
  raw.times = {1, 1};
  expectError(raw, "spec.json: 'times'[1]: key times must strictly increase (1 then 1)");
  raw.kind = CurveKind::kBezier;
  raw.times.clear();
  raw.points = {vec({0}), vec({1}), vec({2}), vec({3}), vec({4})};
  expectError(raw, "spec.json: 'points': a bezier curve needs 3s+1 points (anchor, 2 handles, anchor, ...), got 5");
}

// ---- Arc length ------------------------------------------------------------------------------

constexpr double kTableTol = 1e-5;      // relative, 1000 samples on gentle curves
constexpr double kAdaptiveTol = 1e-9;   // relative
constexpr double kCircleFitTol = 2e-4;  // Bezier quarter-circle approximation: radial error 2.7e-4

TEST(ArcLength, StraightSegmentsAreExact) {
  RawCurve raw;
  raw.kind = CurveKind::kLinear;
  raw.points = {vec({0, 0, 0}), vec({3, 4, 0}), vec({3, 4, 12})};
  raw.times = {0, 1, 3};
  const Curve c = Curve::build(raw);
  EXPECT_NEAR(gaussLegendreLength(c, 0, 3), 17.0, kTol);
  EXPECT_NEAR(adaptiveLength(c, 0, 3), 17.0, kTol);
  for (ArcLengthMethod m : {ArcLengthMethod::kTable, ArcLengthMethod::kAdaptive}) {
    const ArcLengthCurve a = ArcLengthCurve::build(c, {m, 100, 1e-12});
    EXPECT_NEAR(a.totalLength(), 17.0, 1e-9);
    EXPECT_NEAR(a.distanceAt(0), 0.0, kTol);
    EXPECT_NEAR(a.distanceAt(3), 17.0, 1e-9);
    EXPECT_NEAR(a.timeAtDistance(2.5), 0.5, 1e-9);
    EXPECT_NEAR(a.timeAtDistance(5 + 6), 2.0, 1e-9);
    EXPECT_NEAR(a.timeAtFraction(1.0), 3.0, kTol);
  }
}

// A quarter circle of radius r approximated by one cubic Bezier, k = 4/3 (sqrt 2 - 1).
Curve quarterCircle(double r) {
  const double k = 4.0 / 3.0 * (std::sqrt(2.0) - 1.0);
  RawCurve raw;
  raw.kind = CurveKind::kBezier;
  raw.points = {vec({r, 0}), vec({r, k * r}), vec({k * r, r}), vec({0, r})};
  return Curve::build(raw);
}

TEST(ArcLength, CircularArcToKnownTolerance) {
  const double r = 2.0;
  const Curve c = quarterCircle(r);
  const double exact = kPi * r / 2;
  EXPECT_NEAR(adaptiveLength(c, 0, 1) / exact, 1.0, kCircleFitTol);
  EXPECT_NEAR(gaussLegendreLength(c, 0, 1, 5) / exact, 1.0, kCircleFitTol);
  const ArcLengthCurve table = ArcLengthCurve::build(c, {ArcLengthMethod::kTable, 1000, 1e-9});
  const ArcLengthCurve adaptive = ArcLengthCurve::build(c, {ArcLengthMethod::kAdaptive, 2, kAdaptiveTol});
  EXPECT_NEAR(table.totalLength() / adaptive.totalLength(), 1.0, kTableTol);
  // Points at equal arc length are at (nearly) equal angles.
  for (double f : {0.25, 0.5, 0.75}) {
    Eigen::Vector2d p;
    ASSERT_TRUE(adaptive.evaluateAtFraction(f, std::span<double>(p.data(), 2)));
    EXPECT_NEAR(std::atan2(p.y(), p.x()), f * kPi / 2, 2e-3) << f;
  }
  // Finer polylines converge to the same length (chords underestimate).
  const ArcLengthCurve coarse = ArcLengthCurve::build(c, {ArcLengthMethod::kTable, 10, 1e-9});
  EXPECT_LT(coarse.totalLength(), table.totalLength());
}

TEST(ArcLength, ExactDistanceInversionAndMonotonic) {
  const Curve c = Curve::build(sampleRaw(CurveKind::kCatmullRom));
  const ArcLengthCurve table = ArcLengthCurve::build(c, {ArcLengthMethod::kTable, 2000, 1e-9});
  const ArcLengthCurve adaptive = ArcLengthCurve::build(c, {ArcLengthMethod::kAdaptive, 2, kAdaptiveTol});
  EXPECT_NEAR(table.totalLength() / adaptive.totalLength(), 1.0, kTableTol);
  for (const ArcLengthCurve* a : {&table, &adaptive}) {
    SCOPED_TRACE(arcLengthMethodName(a->method()));
    EXPECT_EQ(a->distanceAt(c.startTime()), 0.0);
    EXPECT_EQ(a->distanceAt(c.endTime()), a->totalLength());
    EXPECT_EQ(a->timeAtDistance(0.0), c.startTime());
    EXPECT_EQ(a->timeAtDistance(a->totalLength()), c.endTime());
    double prev_s = -1, prev_t = -1;
    for (int i = 0; i <= 400; ++i) {
      const double t = c.startTime() + (c.endTime() - c.startTime()) * i / 400;
      const double s = a->distanceAt(t);
      EXPECT_GE(s, prev_s);
      prev_s = s;
      const double tt = a->timeAtFraction(i / 400.0);
      EXPECT_GE(tt, prev_t);
      prev_t = tt;
      EXPECT_NEAR(a->distanceAt(a->timeAtDistance(s)), s, 1e-7 * a->totalLength());
    }
  }
  // Adaptive distance agrees with an independent fine Gauss-Legendre sum.
  double gl = 0;
  for (int i = 0; i < 200; ++i) gl += gaussLegendreLength(c, 4.2 * i / 200, 4.2 * (i + 1) / 200, 8);
  EXPECT_NEAR(adaptive.totalLength(), gl, 1e-9 * gl);
}

TEST(ArcLength, RejectsBadOptions) {
  const Curve c = quarterCircle(1);
  try {
    ArcLengthCurve::build(c, {ArcLengthMethod::kTable, 1, 1e-9}, "spec.json: 'arc_length'");
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), "spec.json: 'arc_length': 'samples' must be at least 2, got 1");
  }
  try {
    ArcLengthCurve::build(c, {ArcLengthMethod::kAdaptive, 2, 0.0}, "spec.json: 'arc_length'");
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()),
              "spec.json: 'arc_length': 'tolerance' must be in [1e-12, 1) (relative; finer is below the "
              "rounding of the quadrature sums), got 0");
  }
  EXPECT_THROW(gaussLegendreLength(c, 0, 1, 9), Error);
}

}  // namespace
}  // namespace vdg::anim
