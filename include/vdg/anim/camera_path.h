// Camera path following (Parent, Computer Animation, section 4.4).
//
// The eye moves along a position curve at a speed set by an ease function over arc length: for
// animation time t in [start_time, end_time], with u = (t - start_time) / (end_time - start_time)
// clamped to [0, 1], the eye is at distance ease(u) * L along the curve (L its length), i.e. at
// curve parameter timeAtDistance(ease(u) * L). Constant speed with a linear ease.
//
// View direction (ViewMode):
//   kCenterOfInterest  towards a fixed point `center`;
//   kAlongTangent      along the path's tangent (direction of travel);
//   kMovingTarget      towards a point moving on its own curve `target_path`, evaluated at the
//                      animation time t (the target curve's key times are animation times; clamped).
// If the view direction is undefined (the eye on the target, a zero tangent) the direction of the
// nearest earlier sample is kept.
//
// Up vector and tilt: the camera's up is `up` (default world +Y) made orthogonal to the view
// direction, then rotated about the view direction by tilt(t) degrees (an optional scalar Track).
// No flips: projecting a fixed up vector onto the view plane spins the image by up to 180 degrees
// in an instant when the view direction passes through (or very near) the up axis. Strategy: at
// build time we precompute an up vector for `up_samples` evenly spaced animation times. Each one
// is the previous one parallel-transported (rotated by the smallest rotation taking the previous
// view direction to the new one), then rolled about the view direction towards the projected world
// up, by at most w * 3 times the angle the view turned in that step, where w depends only on the
// angle between view and world up: w = 1 beyond 30 degrees, falling smoothly to w = 0 within 10
// degrees (pure transport near the pole). Away from the pole this keeps the camera exactly upright
// (transport drifts by less than the view turns); through the pole the camera keeps its roll and
// rolls back to upright smoothly while the view keeps moving (a static view stays as it is).
// The roll rate is tied to the view's own motion, so the result does not depend on the frame rate.
// Evaluation interpolates this table (normalised linear interpolation), re-orthogonalises to the
// exact view direction and then applies the tilt: a right-hand rotation by tilt(t) degrees about
// the backward axis (-view), i.e. the camera's up turns counter-clockwise as the camera sees it.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "vdg/anim/arc_length.h"
#include "vdg/anim/curve.h"
#include "vdg/anim/ease.h"
#include "vdg/anim/track.h"
#include "vdg/geom/camera.h"

namespace vdg::anim {

// Most up-vector samples: each costs an arc-length lookup at build time; 32 times the default.
inline constexpr int kMaxCameraPathUpSamples = 65536;

enum class ViewMode { kCenterOfInterest, kAlongTangent, kMovingTarget };
const char* viewModeName(ViewMode mode);  // "center", "tangent", "target-path"

struct RawCameraPath {
  RawCurve position;  // 3D points
  ArcLengthOptions arc_length;
  Ease speed;  // ease over arc length (linear: constant speed)
  double start_time = 0.0;
  double end_time = 1.0;  // > start_time
  ViewMode view = ViewMode::kCenterOfInterest;
  Eigen::Vector3d center = Eigen::Vector3d::Zero();  // kCenterOfInterest
  std::optional<RawCurve> target_path;               // kMovingTarget: 3D points
  Eigen::Vector3d up = Eigen::Vector3d::UnitY();     // world up, non-zero
  std::optional<RawTrack> tilt_deg;                  // scalar track, degrees
  double fov_deg = 40.0;                             // copied to the Camera
  double ortho_height = 0.0;
  int up_samples = 2048;  // up-vector table size, 2..kMaxCameraPathUpSamples
};

class CameraPath {
 public:
  // Throws vdg::Error naming `where` and the field for bad input (non-3D curves, end_time <=
  // start_time or end_time - start_time overflowing, a missing target path, a zero or non-finite
  // up (any finite length is fine), bad tilt track, fov outside (0, 180), up_samples outside
  // 2..kMaxCameraPathUpSamples, and everything Curve::build and ArcLengthCurve::build reject).
  static CameraPath build(const RawCameraPath& raw, const std::string& where = "camera path");

  double startTime() const { return start_time_; }
  double endTime() const { return end_time_; }
  const ArcLengthCurve& path() const { return path_; }

  // The camera at animation time t (clamped to [startTime, endTime]) into `out`: eye on the path,
  // target = eye + d * view direction, d = max(1, |eye|) (or the centre of interest / moving target itself),
  // orthonormal up. Per-frame contract of curve.h: violation (returns false, `out` untouched): t not finite.
  [[nodiscard]] bool evaluate(double t, Camera& out) const;
  // Convenience forms (tools and tests): eye position / camera at t; throw vdg::Error for a
  // non-finite t.
  Eigen::Vector3d eyeAt(double t) const;
  // The camera at t as evaluate() gives it: target = eye + d * view direction with d = max(1, |eye|)
  // (so that a far eye does not absorb the offset), directions normalised robustly.
  Camera cameraAt(double t) const;

 private:
  bool eyePosition(double t, Eigen::Vector3d& out) const;                             // t finite
  bool rawForward(double t, const Eigen::Vector3d& eye, Eigen::Vector3d& out) const;  // may be zero

  ArcLengthCurve path_;
  Ease speed_;
  double start_time_ = 0.0, end_time_ = 1.0;
  ViewMode view_ = ViewMode::kCenterOfInterest;
  Eigen::Vector3d center_ = Eigen::Vector3d::Zero();
  std::optional<Curve> target_path_;
  Eigen::Vector3d world_up_ = Eigen::Vector3d::UnitY();
  std::optional<Track> tilt_;
  double fov_deg_ = 40.0, ortho_height_ = 0.0;
  std::vector<Eigen::Vector3d> table_forward_, table_up_;  // per up sample
};

}  // namespace vdg::anim
