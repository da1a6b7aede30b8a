// Hostile numbers: huge dimensions, impossible tolerances, times whose spans overflow,
// huge quaternions. Every answer must be the right one or a clear vdg::Error naming the field.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <string>

#include "support/error_of.h"
#include "vdg/anim/arc_length.h"
#include "vdg/anim/camera_path.h"
#include "vdg/anim/curve.h"
#include "vdg/anim/quaternion_curve.h"
#include "vdg/anim/rotation.h"
#include "vdg/anim/track.h"
#include "vdg/geom/camera.h"
#include "vdg/geom/error.h"

namespace vdg::anim {
namespace {

constexpr double kLengthTol = 1e-9;     // relative
constexpr double kRotationTol = 1e-12;  // components of unit quaternions and rotated unit vectors

Eigen::VectorXd vec(std::initializer_list<double> v) {
  Eigen::VectorXd r(static_cast<Eigen::Index>(v.size()));
  int i = 0;
  for (double x : v) r[i++] = x;
  return r;
}

// The message of the vdg::Error that `f` throws ("" if none).
using testing::errorOf;

void expectErrorContaining(const std::string& message, const std::string& part) {
  EXPECT_NE(message.find(part), std::string::npos) << "message: '" << message << "', expected: '" << part << "'";
}

RawCurve linearCurve(std::vector<Eigen::VectorXd> points, std::vector<double> times = {}) {
  RawCurve raw;
  raw.kind = CurveKind::kLinear;
  raw.points = std::move(points);
  raw.times = std::move(times);
  return raw;
}

// ---- Curve dimension and arc-length work ------------------------------------------------------

TEST(Bounds, CurveDimensionIsCapped) {
  const Eigen::VectorXd a = Eigen::VectorXd::Zero(kMaxCurveDimension), b = Eigen::VectorXd::Ones(kMaxCurveDimension);
  const Curve c = Curve::build(linearCurve({a, b}));
  const ArcLengthCurve arc = ArcLengthCurve::build(c);
  EXPECT_NEAR(arc.totalLength() / std::sqrt(kMaxCurveDimension), 1.0, kLengthTol);
  const Eigen::VectorXd big = Eigen::VectorXd::Zero(1000);
  expectErrorContaining(errorOf([&] {
                          Curve::build(linearCurve({big, big}), "spec.json: curve");
                        }),
                        "spec.json: curve: 'points'[0]: 1000 coordinates; a curve point may have at most 16");
}

TEST(Bounds, ArcLengthToleranceHasAFloor) {
  const Curve c = Curve::build(linearCurve({vec({0, 0}), vec({3, 4})}));
  expectErrorContaining(errorOf([&] {
                          ArcLengthCurve::build(c, {ArcLengthMethod::kAdaptive, 2, 1e-300}, "spec.json: 'arc_length'");
                        }),
                        "spec.json: 'arc_length': 'tolerance' must be in [1e-12, 1)");
  expectErrorContaining(errorOf([&] { adaptiveLength(c, 0, 1, 1e-300); }), "'tolerance' must be in [1e-12, 1)");
  EXPECT_NEAR(ArcLengthCurve::build(c, {ArcLengthMethod::kAdaptive, 2, kMinArcLengthTolerance}).totalLength(), 5.0,
              5.0 * kLengthTol);
}

TEST(Bounds, ArcLengthTableSamplesAreCapped) {
  const Curve c = Curve::build(linearCurve({vec({0}), vec({1})}));
  expectErrorContaining(
      errorOf([&] {
        ArcLengthCurve::build(c, {ArcLengthMethod::kTable, 2000000000, 1e-9}, "spec.json: 'arc_length'");
      }),
      "spec.json: 'arc_length': 'samples' must be at most 1000000");
}

// |P'| has a kink where a 1D cubic turns back; the globally adaptive quadrature still reaches the
// finest tolerance within its interval budget, and gets the length (the total variation) right.
TEST(Bounds, TurningPointInsideASegmentConvergesAtTheFinestTolerance) {
  RawCurve raw;
  raw.kind = CurveKind::kBezier;
  raw.points = {vec({0}), vec({1}), vec({0.3}), vec({0.2})};
  const Curve c = Curve::build(raw);
  // P'(t)/3 = (1-t)^2 (1) + 2 (1-t) t (-0.7) + t^2 (-0.1) = 2.3 t^2 - 3.4 t + 1.
  const double a = 2.3, b = -3.4, cc = 1.0;
  const double t_turn = (-b - std::sqrt(b * b - 4 * a * cc)) / (2 * a);
  const double p_max = c.at(t_turn)[0];
  const double exact = p_max + (p_max - 0.2);
  const ArcLengthCurve arc = ArcLengthCurve::build(c, {ArcLengthMethod::kAdaptive, 2, kMinArcLengthTolerance});
  EXPECT_NEAR(arc.totalLength() / exact, 1.0, 1e-10);
  EXPECT_NEAR(adaptiveLength(c, 0, 1, kMinArcLengthTolerance) / exact, 1.0, 1e-10);
  EXPECT_NEAR(arc.distanceAt(arc.timeAtDistance(0.5 * exact)), 0.5 * exact, 1e-9);
}

TEST(Bounds, LengthThatOverflowsIsAnError) {
  const Curve c = Curve::build(linearCurve({vec({0}), vec({1e308}), vec({0}), vec({1e308})}));
  expectErrorContaining(errorOf([&] { ArcLengthCurve::build(c, {}, "spec.json: 'arc_length'"); }),
                        "spec.json: 'arc_length': the curve's length overflows");
}

// ---- Time spans that overflow -----------------------------------------------------------------

TEST(Overflow, CurveTimeSpanThatOverflowsIsAnError) {
  const RawCurve raw = linearCurve({vec({0}), vec({1})}, {-1e308, 1e308});
  expectErrorContaining(errorOf([&] { Curve::build(raw, "spec.json: curve"); }),
                        "spec.json: curve: 'times'[1]: the span from -1e+308 to 1e+308 overflows a double");
  const RawCurve tiny = linearCurve({vec({0}), vec({0})}, {0.0, 1e-320});
  expectErrorContaining(errorOf([&] { Curve::build(tiny); }), "'times'[1]: the span from 0 to");
  expectErrorContaining(errorOf([&] { Curve::build(tiny); }), "is too small to divide by");
}

TEST(Overflow, CurveWhoseSlopesOverflowIsAnError) {
  // Each key is finite, but the slope between them (2e308 per unit time) is not.
  const RawCurve raw = linearCurve({vec({-1e308}), vec({1e308})});
  expectErrorContaining(errorOf([&] { Curve::build(raw, "spec.json: curve"); }),
                        "spec.json: curve: 'points': segment 0 overflows");
  RawCurve steep = linearCurve({vec({0}), vec({1e300})}, {0, 1e-10});
  steep.kind = CurveKind::kCatmullRom;
  expectErrorContaining(errorOf([&] { Curve::build(steep); }), "segment 0 overflows");
}

RawKey key(double time, std::initializer_list<double> value) {
  RawKey k;
  k.time = time;
  k.value = vec(value);
  return k;
}

TEST(Overflow, TrackTimeSpansThatOverflowAreErrors) {
  for (const Interpolation interpolation : {Interpolation::kStep, Interpolation::kLinear}) {
    RawTrack t;
    t.name = "x";
    t.interpolation = interpolation;
    t.keys = {key(-1e308, {0}), key(1e308, {1})};
    expectErrorContaining(errorOf([&] { Track::build(t, "spec.json"); }),
                          "spec.json: track 'x': 'keys'[1]: 'time' 1e+308: the span from the previous key's -1e+308 "
                          "overflows a double");
    // Every span finite, but the whole range (the loop period) is not.
    t.keys = {key(-1e308, {0}), key(0, {1}), key(1e308, {2})};
    expectErrorContaining(errorOf([&] { Track::build(t, "spec.json"); }),
                          "'keys'[2]: 'time' 1e+308: the span from the first key's -1e+308 overflows a double");
  }
  RawTrack r;
  r.name = "spin";
  r.type = TrackType::kRotation;
  r.interpolation = Interpolation::kSlerp;
  r.keys = {key(-1e308, {1, 0, 0, 0}), key(1e308, {0, 1, 0, 0})};
  expectErrorContaining(errorOf([&] { Track::build(r); }), "overflows a double");
}

TEST(Overflow, TrackValueDimensionIsCapped) {
  RawTrack t;
  t.name = "v";
  t.type = TrackType::kVector;
  t.keys = {key(0, {}), key(1, {})};
  for (RawKey& k : t.keys) k.value = Eigen::VectorXd::Zero(kMaxCurveDimension + 1);
  expectErrorContaining(errorOf([&] { Track::build(t); }), "'value': 17 numbers; a track value may have at most 16");
}

RawCameraPath straightPath() {
  RawCameraPath raw;
  raw.position = linearCurve({vec({0, 0, 5}), vec({5, 0, 5})});
  raw.up_samples = 16;
  return raw;
}

TEST(Overflow, CameraPathTimeSpanThatOverflowsIsAnError) {
  RawCameraPath raw = straightPath();
  raw.start_time = -1e308;
  raw.end_time = 1e308;
  expectErrorContaining(errorOf([&] { CameraPath::build(raw, "shot.json: camera"); }),
                        "shot.json: camera: 'end_time' (1e+308) - 'start_time' (-1e+308) overflows a double");
  raw = straightPath();
  raw.up_samples = kMaxCameraPathUpSamples + 1;
  expectErrorContaining(errorOf([&] { CameraPath::build(raw, "shot.json: camera"); }),
                        "shot.json: camera: 'up_samples' must be in 2..65536");
}

TEST(Overflow, FarCameraPathKeepsATargetDistinctFromTheEye) {
  RawCameraPath raw;
  raw.position = linearCurve({vec({1e17, 0, 0}), vec({2e17, 0, 0})});
  raw.view = ViewMode::kAlongTangent;
  raw.up = Eigen::Vector3d(0, 1e300, 0);  // huge but finite: a direction like any other
  raw.up_samples = 16;
  const CameraPath path = CameraPath::build(raw);
  const Camera cam = path.cameraAt(0.5);
  EXPECT_NE(cam.target, cam.eye);
  const CameraFrame frame = cameraFrame(cam);
  EXPECT_NEAR((frame.back - Eigen::Vector3d(-1, 0, 0)).norm(), 0.0, kRotationTol);
  EXPECT_NEAR((frame.up - Eigen::Vector3d(0, 1, 0)).norm(), 0.0, kRotationTol);
}

TEST(Overflow, HugeTimesGiveFiniteValuesAndNonFiniteTimesAreRefused) {
  const double inf = std::numeric_limits<double>::infinity(), nan = std::numeric_limits<double>::quiet_NaN();
  RawTrack r;
  r.name = "spin";
  r.type = TrackType::kRotation;
  r.interpolation = Interpolation::kSlerp;
  r.extrapolation = Extrapolation::kLoop;
  r.keys = {key(-1e307, {1, 0, 0, 0}), key(1e307, {0, 1, 0, 0})};
  const Track track = Track::build(r);
  // Huge finite times give finite values; non-finite ones are refused (the per-frame contract).
  for (const double t : {1e308, -1e308, 1e300}) EXPECT_TRUE(track.at(t).allFinite()) << t;
  for (const double t : {inf, -inf, nan}) EXPECT_THROW(track.at(t), Error) << t;
  const CameraPath path = CameraPath::build(straightPath());
  for (const double t : {1e308, -1e308}) {
    const Camera cam = path.cameraAt(t);
    EXPECT_TRUE(cam.eye.allFinite() && cam.target.allFinite() && cam.up.allFinite()) << t;
  }
  for (const double t : {inf, -inf, nan}) {
    Camera cam;
    EXPECT_FALSE(path.evaluate(t, cam)) << t;
  }
}

// ---- Huge and tiny quaternions ----------------------------------------------------------------

TEST(HugeQuaternions, KeepTheirRotation) {
  const Quaternion q = axisAngleToQuaternion(Eigen::Vector3d(1, 2, 3), 0.9);
  const Eigen::Vector3d v(0.3, -1, 2);
  const Eigen::Vector3d expected = q.toRotationMatrix() * v;
  for (const double scale : {1e200, 1e-200}) {
    SCOPED_TRACE(scale);
    const Quaternion big(q.coeffs() * scale);
    EXPECT_NEAR((rotate(big, v) - expected).norm(), 0.0, kRotationTol);
    EXPECT_NEAR((quaternionToMatrix(big) * v - expected).norm(), 0.0, kRotationTol);
    EXPECT_NEAR((multiply(big, inverse(big)).coeffs() - Quaternion::Identity().coeffs()).norm(), 0.0, kRotationTol);
    EXPECT_TRUE(sameRotation(big, q, kRotationTol));
    EXPECT_NEAR(angleBetween(big, q), 0.0, 1e-6);
    EXPECT_TRUE(sameRotation(slerp(big, q, 0.3), q, kRotationTol));
    EXPECT_TRUE(sameRotation(axisAngleToQuaternion(Eigen::Vector3d(1, 2, 3) * scale, 0.9), q, kRotationTol));
  }
  EXPECT_FALSE(sameRotation(Quaternion(0, 0, 0, 0), q));
}

TEST(HugeQuaternions, TrackAndQuaternionCurveKeysKeepTheirRotation) {
  const Quaternion q0 = Quaternion::Identity();
  const Quaternion q1 = axisAngleToQuaternion(Eigen::Vector3d::UnitY(), 1.2);
  for (const Interpolation interpolation : {Interpolation::kSlerp, Interpolation::kQuaternionCurve}) {
    RawTrack t;
    t.name = "spin";
    t.type = TrackType::kRotation;
    t.interpolation = interpolation;
    t.keys = {key(0, {q0.w() * 1e-200, 0, 0, 0}), key(1, {q1.w() * 1e200, q1.x() * 1e200, q1.y() * 1e200, 0})};
    const Track track = Track::build(t);
    EXPECT_TRUE(sameRotation(track.rotationAt(0.0), q0, kRotationTol));
    EXPECT_TRUE(sameRotation(track.rotationAt(1.0), q1, kRotationTol));  // once the identity
    EXPECT_TRUE(sameRotation(track.rotationAt(0.5), slerp(q0, q1, 0.5), 1e-9));
  }
  const QuaternionCurve c = QuaternionCurve::build({Quaternion(q0.coeffs() * 1e-200), Quaternion(q1.coeffs() * 1e200)});
  EXPECT_TRUE(sameRotation(c.at(1.0), q1, kRotationTol));
}

}  // namespace
}  // namespace vdg::anim
