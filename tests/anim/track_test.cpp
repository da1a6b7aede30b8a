// Tests of tracks (Parent 4.5, 4.9) and camera path following (Parent 4.4).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "vdg/anim/camera_path.h"
#include "vdg/anim/track.h"
#include "vdg/geom/error.h"

namespace vdg::anim {
namespace {

constexpr double kTol = 1e-12;
constexpr double kDeg = std::numbers::pi / 180.0;

RawKey key(double time, std::initializer_list<double> value) {
  RawKey k;
  k.time = time;
  k.value.resize(static_cast<Eigen::Index>(value.size()));
  int i = 0;
  for (double v : value) k.value[i++] = v;
  return k;
}

RawTrack scalarTrack(Interpolation interpolation) {
  RawTrack t;
  t.name = "opacity";
  t.interpolation = interpolation;
  t.keys = {key(0, {0}), key(1, {10}), key(3, {4}), key(4, {6})};
  return t;
}

TEST(Track, EveryInterpolationHitsTheKeys) {
  for (Interpolation i :
       {Interpolation::kStep, Interpolation::kLinear, Interpolation::kCatmullRom, Interpolation::kCentripetalCatmullRom,
        Interpolation::kNaturalCubic, Interpolation::kParabolicBlending, Interpolation::kBezier}) {
    SCOPED_TRACE(interpolationName(i));
    const RawTrack raw = scalarTrack(i);
    const Track t = Track::build(raw);
    for (const RawKey& k : raw.keys) EXPECT_NEAR(t.scalarAt(k.time), k.value[0], kTol);
    EXPECT_EQ(t.dimension(), 1);
  }
}

TEST(Track, StepLinearClampAndLoop) {
  const Track step = Track::build(scalarTrack(Interpolation::kStep));
  EXPECT_EQ(step.scalarAt(0.99), 0.0);
  EXPECT_EQ(step.scalarAt(2.0), 10.0);
  RawTrack raw = scalarTrack(Interpolation::kLinear);
  const Track clamp = Track::build(raw);
  EXPECT_NEAR(clamp.scalarAt(0.5), 5.0, kTol);
  EXPECT_NEAR(clamp.scalarAt(2.0), 7.0, kTol);
  EXPECT_EQ(clamp.scalarAt(-3.0), 0.0);
  EXPECT_EQ(clamp.scalarAt(9.0), 6.0);
  raw.extrapolation = Extrapolation::kLoop;
  const Track loop = Track::build(raw);
  EXPECT_NEAR(loop.scalarAt(4.5), 5.0, kTol);   // 4.5 -> 0.5
  EXPECT_NEAR(loop.scalarAt(-3.5), 5.0, kTol);  // -3.5 -> 0.5
  EXPECT_NEAR(loop.scalarAt(10.0), 7.0, kTol);  // 10 -> 2
}

TEST(Track, PerSegmentEase) {
  RawTrack raw = scalarTrack(Interpolation::kLinear);
  raw.keys[0].ease = Ease::sine();
  const Track t = Track::build(raw);
  EXPECT_NEAR(t.scalarAt(0.25), 10 * easeSine(0.25), kTol);  // 1.465 (text: ease(0.25) = 0.1465)
  EXPECT_NEAR(t.scalarAt(1.0), 10.0, kTol);
  EXPECT_NEAR(t.scalarAt(2.0), 7.0, kTol);  // the next segment is not eased
  EXPECT_NEAR(t.curveTime(0.75), easeSine(0.75), kTol);
}

TEST(Track, BezierHandles) {
  RawTrack raw;
  raw.name = "x";
  raw.interpolation = Interpolation::kBezier;
  raw.keys = {key(0, {0}), key(1, {1})};
  raw.keys[0].out_handle = Eigen::VectorXd::Constant(1, 0.0);
  raw.keys[1].in_handle = Eigen::VectorXd::Constant(1, 1.0);
  const Track t = Track::build(raw);
  const double u = 0.3;  // controls 0, 0, 1, 1: 3u^2 - 2u^3
  EXPECT_NEAR(t.scalarAt(u), 3 * u * u - 2 * u * u * u, kTol);
  // Default handles on the chord of a straight track: linear.
  raw.keys[0].out_handle.reset();
  raw.keys[1].in_handle.reset();
  EXPECT_NEAR(Track::build(raw).scalarAt(u), u, kTol);
}

TEST(Track, VectorAndRotationTracks) {
  RawTrack v;
  v.name = "position";
  v.type = TrackType::kVector;
  v.interpolation = Interpolation::kNaturalCubic;
  v.keys = {key(0, {0, 0, 0}), key(1, {1, 2, 0}), key(2, {2, 0, 1})};
  const Track vt = Track::build(v);
  EXPECT_EQ(vt.dimension(), 3);
  EXPECT_LT((vt.at(1.0) - Eigen::Vector3d(1, 2, 0)).norm(), kTol);

  RawTrack r;
  r.name = "spin";
  r.type = TrackType::kRotation;
  r.interpolation = Interpolation::kSlerp;
  const Quaternion q1 = axisAngleToQuaternion(Eigen::Vector3d::UnitY(), 0.0);
  const Quaternion q2 = axisAngleToQuaternion(Eigen::Vector3d::UnitY(), 170 * kDeg);
  r.keys = {key(0, {q1.w(), q1.x(), q1.y(), q1.z()}), key(2, {-2 * q2.w(), -2 * q2.x(), -2 * q2.y(), -2 * q2.z()})};
  const Track rt = Track::build(r);
  EXPECT_EQ(rt.dimension(), 4);
  EXPECT_TRUE(sameRotation(rt.rotationAt(1.0), axisAngleToQuaternion(Eigen::Vector3d::UnitY(), 85 * kDeg), 1e-12));
  EXPECT_NEAR(rt.rotationAt(0.7).norm(), 1.0, kTol);
  r.interpolation = Interpolation::kQuaternionCurve;
  r.keys.insert(r.keys.begin() + 1, key(1, {std::cos(0.3), std::sin(0.3), 0, 0}));
  const Track qt = Track::build(r);
  EXPECT_TRUE(sameRotation(qt.rotationAt(1.0), Quaternion(std::cos(0.3), std::sin(0.3), 0, 0), 1e-12));
  for (double t = 0; t <= 2; t += 0.05) EXPECT_NEAR(qt.rotationAt(t).norm(), 1.0, kTol);
  // A single key is a constant.
  RawTrack single = scalarTrack(Interpolation::kCatmullRom);
  single.keys.resize(1);
  EXPECT_EQ(Track::build(single).scalarAt(5.0), 0.0);
}

void expectError(const RawTrack& raw, const std::string& message) {
  try {
    Track::build(raw, "spec.json");
    FAIL() << message;
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), message);
  }
}

TEST(Track, RejectsInvalidInput) {
  RawTrack raw = scalarTrack(Interpolation::kLinear);
  raw.keys.clear();
  expectError(raw, "spec.json: track 'opacity': 'keys': a track needs at least one key");
  raw = scalarTrack(Interpolation::kLinear);
  raw.keys[2].time = 1.0;
  expectError(raw, "spec.json: track 'opacity': 'keys'[2]: 'time' 1 must be greater than the previous key's 1");
  raw = scalarTrack(Interpolation::kLinear);
  raw.keys[1].value = Eigen::Vector2d(1, 2);
  expectError(raw, "spec.json: track 'opacity': 'keys'[1]: 'value': expected 1 number, got 2");
  raw = scalarTrack(Interpolation::kSlerp);
  expectError(raw, "spec.json: track 'opacity': interpolation 'slerp' is only available for rotation tracks");
  raw = scalarTrack(Interpolation::kCatmullRom);
  raw.type = TrackType::kRotation;
  expectError(raw,
              "spec.json: track 'opacity': interpolation 'catmull-rom' is not available for rotation tracks (use "
              "'slerp', 'quaternion-curve' or 'step')");
  raw.interpolation = Interpolation::kSlerp;
  raw.keys = {key(0, {0, 0, 0, 0})};
  expectError(raw, "spec.json: track 'opacity': 'keys'[0]: 'value': a rotation quaternion must not be zero");
  raw = scalarTrack(Interpolation::kLinear);
  raw.keys[0].out_handle = Eigen::VectorXd::Constant(1, 1.0);
  expectError(raw, "spec.json: track 'opacity': 'keys'[0]: 'out': handles are only used by 'bezier' interpolation");
  raw = scalarTrack(Interpolation::kLinear);
  raw.keys[3].value[0] = INFINITY;
  expectError(raw, "spec.json: track 'opacity': 'keys'[3]: 'value' must be finite");
}

// ---- Camera path ------------------------------------------------------------------------------

RawCurve circlePath(double radius, double height) {
  RawCurve c;
  c.kind = CurveKind::kCatmullRom;
  for (int i = 0; i <= 16; ++i) {
    const double a = 2 * std::numbers::pi * i / 16;
    c.points.push_back(Eigen::Vector3d(radius * std::cos(a), height, radius * std::sin(a)));
  }
  return c;
}

TEST(CameraPath, ConstantSpeedAndEasedSpeedOverArcLength) {
  RawCameraPath raw;
  raw.position = circlePath(5, 1);
  raw.start_time = 0;
  raw.end_time = 10;
  const CameraPath path = CameraPath::build(raw);
  const double length = path.path().totalLength();
  // Equal time steps travel equal distances along the path (chord test on a circle-like curve).
  EXPECT_NEAR(path.path().distanceAt(path.path().timeAtDistance(0.3 * length)), 0.3 * length, 1e-6 * length);
  const Camera c = path.cameraAt(5.0);
  EXPECT_LT((c.target - Eigen::Vector3d::Zero()).norm(), kTol);  // centre of interest
  EXPECT_NEAR(c.up.norm(), 1.0, kTol);
  EXPECT_NEAR(c.up.dot((c.target - c.eye).normalized()), 0.0, 1e-12);
  EXPECT_GT(c.up.y(), 0.9);  // upright
  EXPECT_LT((path.cameraAt(0).eye - Eigen::Vector3d(5, 1, 0)).norm(), 1e-12);
  EXPECT_LT((path.cameraAt(10).eye - Eigen::Vector3d(5, 1, 0)).norm(), 1e-9);
  // Sine ease: at time 2.5 the camera has covered ease(0.25) of the length.
  raw.speed = Ease::sine();
  const CameraPath eased = CameraPath::build(raw);
  const Eigen::Vector3d eye = eased.eyeAt(2.5);
  const double s = eased.path().distanceAt(eased.path().timeAtDistance(easeSine(0.25) * length));
  Eigen::Vector3d expected;
  ASSERT_TRUE(eased.path().evaluateAtDistance(s, std::span<double>(expected.data(), 3)));
  EXPECT_LT((eye - expected).norm(), 1e-9);
}

TEST(CameraPath, TangentAndMovingTargetAndTilt) {
  RawCameraPath raw;
  raw.position = circlePath(5, 0);
  raw.view = ViewMode::kAlongTangent;
  const CameraPath tangent = CameraPath::build(raw);
  const Camera c = tangent.cameraAt(0.0);
  // Travelling towards +z at the start; the end tangent is the first chord's (11.25 degrees off).
  EXPECT_GT((c.target - c.eye).normalized().dot(Eigen::Vector3d(0, 0, 1)), std::cos(12 * kDeg));

  raw.view = ViewMode::kMovingTarget;
  RawCurve target;
  target.kind = CurveKind::kLinear;
  target.points = {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(0, 4, 0)};
  target.times = {0, 1};
  raw.target_path = target;
  RawTrack tilt;
  tilt.name = "tilt";
  tilt.keys = {key(0, {0}), key(1, {90})};
  raw.tilt_deg = tilt;
  const CameraPath moving = CameraPath::build(raw);
  const Camera m = moving.cameraAt(0.5);
  EXPECT_LT((m.target - Eigen::Vector3d(0, 2, 0)).norm(), 1e-12);
  // 45 degrees of tilt at t = 0.5: the up vector is 45 degrees from the untilted one.
  raw.tilt_deg.reset();
  const Camera untilted = CameraPath::build(raw).cameraAt(0.5);
  EXPECT_NEAR(std::acos(m.up.dot(untilted.up)), 45 * kDeg, 1e-9);
  const Eigen::Vector3d fwd = (m.target - m.eye).normalized();
  // Counter-clockwise as the camera sees it: up turns towards the camera's left.
  const Eigen::Vector3d left = untilted.up.cross(fwd);  // -(right), right = forward x up
  EXPECT_GT(m.up.dot(left), 0.5);
}

TEST(CameraPath, NoFlipWhenTheViewPassesThroughTheUpAxis) {
  // The camera goes over the top of the centre of interest: view direction passes through -Y.
  RawCameraPath raw;
  raw.position.kind = CurveKind::kCatmullRom;
  for (int i = 0; i <= 12; ++i) {
    const double a = std::numbers::pi * i / 12;  // from +x over +y to -x
    raw.position.points.push_back(Eigen::Vector3d(5 * std::cos(a), 5 * std::sin(a), 0.0));
  }
  const CameraPath path = CameraPath::build(raw);
  Camera prev = path.cameraAt(0.0);
  double max_turn = 0.0;
  for (int i = 1; i <= 2000; ++i) {
    const Camera c = path.cameraAt(i / 2000.0);
    max_turn = std::max(max_turn, std::acos(std::clamp(c.up.dot(prev.up), -1.0, 1.0)));
    EXPECT_NEAR(c.up.dot((c.target - c.eye).normalized()), 0.0, 1e-9);
    prev = c;
  }
  EXPECT_LT(max_turn, 5 * kDeg);               // smooth: no 180-degree spin between frames
  EXPECT_GT(path.cameraAt(0.0).up.y(), 0.99);  // upright away from the pole
}

TEST(CameraPath, RejectsInvalidInput) {
  auto expect = [](const RawCameraPath& raw, const std::string& message) {
    try {
      CameraPath::build(raw, "spec.json: 'camera_path'");
      FAIL() << message;
    } catch (const Error& e) {
      EXPECT_EQ(std::string(e.what()), message);
    }
  };
  RawCameraPath raw;
  raw.position = circlePath(5, 0);
  raw.end_time = 0.0;
  expect(raw, "spec.json: 'camera_path': 'end_time' (0) must be greater than 'start_time' (0)");
  raw.end_time = 1.0;
  raw.view = ViewMode::kMovingTarget;
  expect(raw, "spec.json: 'camera_path': 'target_path': required when the view follows a moving target");
  raw.view = ViewMode::kCenterOfInterest;
  raw.up = Eigen::Vector3d::Zero();
  expect(raw, "spec.json: 'camera_path': 'up' must be a finite non-zero vector");
  raw.up = Eigen::Vector3d::UnitY();
  raw.fov_deg = 180;
  expect(raw, "spec.json: 'camera_path': 'fov_deg' must be in (0, 180), got 180");
  raw.fov_deg = 40;
  raw.position.points = {Eigen::Vector2d(0, 0), Eigen::Vector2d(1, 0)};
  expect(raw, "spec.json: 'camera_path': 'position': expected 3D points");
}

}  // namespace
}  // namespace vdg::anim
