// Small curves, tracks and camera paths shared by the anim contract and allocation tests.
#pragma once

#include <initializer_list>
#include <numbers>
#include <vector>

#include "vdg/anim/arc_length.h"
#include "vdg/anim/camera_path.h"
#include "vdg/anim/curve.h"
#include "vdg/anim/quaternion_curve.h"
#include "vdg/anim/track.h"

namespace vdg::anim::fixtures {

inline RawKey key(double time, std::initializer_list<double> value) {
  RawKey k;
  k.time = time;
  k.value.resize(static_cast<Eigen::Index>(value.size()));
  int i = 0;
  for (double v : value) k.value[i++] = v;
  return k;
}

// A 3D Catmull-Rom curve through five points.
inline Curve curve3(CurveKind kind = CurveKind::kCatmullRom) {
  RawCurve raw;
  raw.kind = kind;
  raw.points = {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 2, 0), Eigen::Vector3d(3, 1, 1), Eigen::Vector3d(4, 3, 2),
                Eigen::Vector3d(6, 0, 1)};
  if (kind == CurveKind::kBezier) raw.points.resize(4);
  return Curve::build(raw);
}

// One track of each value type and interpolation family, easing and looping included.
inline std::vector<Track> tracks() {
  std::vector<Track> out;
  RawTrack scalar;
  scalar.name = "scalar";
  scalar.interpolation = Interpolation::kCatmullRom;
  scalar.extrapolation = Extrapolation::kLoop;
  scalar.keys = {key(0, {0}), key(1, {10}), key(3, {4}), key(4, {6})};
  scalar.keys[1].ease = Ease::sine();
  out.push_back(Track::build(scalar));
  RawTrack step = scalar;
  step.name = "step";
  step.interpolation = Interpolation::kStep;
  out.push_back(Track::build(step));
  RawTrack single;
  single.name = "single";
  single.keys = {key(2, {5})};
  out.push_back(Track::build(single));
  RawTrack vector;
  vector.name = "vector";
  vector.type = TrackType::kVector;
  vector.interpolation = Interpolation::kNaturalCubic;
  vector.keys = {key(0, {0, 1, 2, 3, 4}), key(1, {1, 2, 3, 4, 5}), key(2, {0, 0, 0, 0, 0})};
  out.push_back(Track::build(vector));
  RawTrack slerp;
  slerp.name = "slerp";
  slerp.type = TrackType::kRotation;
  slerp.interpolation = Interpolation::kSlerp;
  slerp.keys = {key(0, {1, 0, 0, 0}), key(1, {std::cos(0.4), std::sin(0.4), 0, 0}), key(2, {0, 0, 1, 0})};
  out.push_back(Track::build(slerp));
  RawTrack qcurve = slerp;
  qcurve.name = "quaternion-curve";
  qcurve.interpolation = Interpolation::kQuaternionCurve;
  out.push_back(Track::build(qcurve));
  return out;
}

inline QuaternionCurve quaternionCurve() {
  return QuaternionCurve::build({Quaternion(1, 0, 0, 0), Quaternion(std::cos(0.4), std::sin(0.4), 0, 0),
                                 Quaternion(0, 0, 1, 0), Quaternion(0.5, 0.5, 0.5, 0.5)});
}

// Camera paths in each view mode, the last one tilted.
inline std::vector<CameraPath> cameraPaths() {
  RawCameraPath raw;
  raw.position.kind = CurveKind::kCatmullRom;
  for (int i = 0; i <= 8; ++i) {
    const double a = 2 * std::numbers::pi * i / 8;
    raw.position.points.push_back(Eigen::Vector3d(5 * std::cos(a), 1, 5 * std::sin(a)));
  }
  raw.end_time = 4;
  raw.speed = Ease::sinusoidal(0.2, 0.8);
  raw.up_samples = 64;
  std::vector<CameraPath> out;
  out.push_back(CameraPath::build(raw));
  raw.view = ViewMode::kAlongTangent;
  raw.arc_length.method = ArcLengthMethod::kTable;
  out.push_back(CameraPath::build(raw));
  raw.view = ViewMode::kMovingTarget;
  RawCurve target;
  target.kind = CurveKind::kLinear;
  target.points = {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(0, 4, 0)};
  target.times = {0, 4};
  raw.target_path = target;
  RawTrack tilt;
  tilt.name = "tilt";
  tilt.keys = {key(0, {0}), key(4, {90})};
  raw.tilt_deg = tilt;
  out.push_back(CameraPath::build(raw));
  return out;
}

}  // namespace vdg::anim::fixtures
