// Camera path following — Parent, Computer Animation, section 4.4: position along a curve with
// speed control by an ease function over arc length (4.1, 4.2), view direction towards a centre of
// interest, along the tangent or towards a moving point, and the remaining degree of freedom, the
// tilt, from an up vector ("interpolate the view direction and then calculate the head up
// orientation and apply any tilt to that").
#include "vdg/anim/camera_path.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <string>

#include <Eigen/Geometry>

#include "vdg/geom/error.h"
#include "vdg/geom/normalize.h"

namespace vdg::anim {
namespace {

constexpr double kTransportOnlyDeg = 10.0;  // within this angle of world up: pure parallel transport
constexpr double kUprightDeg = 30.0;        // beyond this angle: exactly the projected world up
constexpr double kTinyDirection = 1e-12;
constexpr double kRollRate = 3.0;  // roll towards upright at most 3 times as fast as the view turns

double smoothstep(double e0, double e1, double x) {
  const double t = std::clamp((x - e0) / (e1 - e0), 0.0, 1.0);
  return t * t * (3 - 2 * t);
}

// Any unit vector perpendicular to unit f.
Eigen::Vector3d anyPerpendicular(const Eigen::Vector3d& f) {
  const Eigen::Vector3d other = std::abs(f.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  return (other - other.dot(f) * f).normalized();
}

// The unit direction of v, or nothing when v is shorter than kTinyDirection (the eye on the
// target, a zero tangent) or not finite. Robust: a direction 1e200 long is still a direction.
std::optional<Eigen::Vector3d> directionOf(const Eigen::Vector3d& v) {
  if (!(robustNorm(v) > kTinyDirection)) return std::nullopt;
  return normalizedOrNone(v);
}

// A point `dir` (unit) away from `eye` that differs from it in doubles: far eyes (|eye| > 1e16)
// would otherwise absorb a unit offset, giving target == eye.
Eigen::Vector3d pointAhead(const Eigen::Vector3d& eye, const Eigen::Vector3d& dir) {
  return eye + dir * std::max(1.0, robustNorm(eye));
}

// v made orthogonal to unit f and normalised; `fallback` (already orthogonal) when degenerate.
Eigen::Vector3d orthonormalise(const Eigen::Vector3d& v, const Eigen::Vector3d& f, const Eigen::Vector3d& fallback) {
  const Eigen::Vector3d p = v - v.dot(f) * f;
  const double n = p.norm();
  return n > 1e-9 ? Eigen::Vector3d(p / n) : fallback;
}

}  // namespace

const char* viewModeName(ViewMode mode) {
  switch (mode) {
    case ViewMode::kCenterOfInterest:
      return "center";
    case ViewMode::kAlongTangent:
      return "tangent";
    case ViewMode::kMovingTarget:
      return "target-path";
  }
  return "?";
}

CameraPath CameraPath::build(const RawCameraPath& raw, const std::string& where) {
  auto fail = [&](const std::string& what) { throw Error(where + ": " + what); };
  CameraPath c;
  const Curve position = Curve::build(raw.position, where + ": 'position'");
  if (position.dimension() != 3) fail("'position': expected 3D points");
  c.path_ = ArcLengthCurve::build(position, raw.arc_length, where + ": 'arc_length'");
  if (!std::isfinite(raw.start_time) || !std::isfinite(raw.end_time) || !(raw.end_time > raw.start_time)) {
    std::ostringstream out;
    out << "'end_time' (" << raw.end_time << ") must be greater than 'start_time' (" << raw.start_time << ")";
    fail(out.str());
  }
  if (!isUsableTimeSpan(raw.end_time - raw.start_time)) {
    std::ostringstream out;
    out << "'end_time' (" << raw.end_time << ") - 'start_time' (" << raw.start_time << ") "
        << (std::isinf(raw.end_time - raw.start_time) ? "overflows a double" : "is too small to divide by");
    fail(out.str());
  }
  c.speed_ = raw.speed;
  c.start_time_ = raw.start_time;
  c.end_time_ = raw.end_time;
  c.view_ = raw.view;
  if (!raw.center.allFinite()) fail("'center' must be finite");
  c.center_ = raw.center;
  if (raw.view == ViewMode::kMovingTarget) {
    if (!raw.target_path) fail("'target_path': required when the view follows a moving target");
    c.target_path_ = Curve::build(*raw.target_path, where + ": 'target_path'");
    if (c.target_path_->dimension() != 3) fail("'target_path': expected 3D points");
  }
  const std::optional<Eigen::Vector3d> world_up = normalizedOrNone(raw.up);  // any finite non-zero length
  if (!world_up) fail("'up' must be a finite non-zero vector");
  c.world_up_ = *world_up;
  if (raw.tilt_deg) {
    if (raw.tilt_deg->type != TrackType::kScalar) fail("'tilt': expected a scalar track (degrees)");
    c.tilt_ = Track::build(*raw.tilt_deg, where + ": 'tilt'");
  }
  if (raw.ortho_height < 0.0 || !std::isfinite(raw.ortho_height)) fail("'ortho_height' must be >= 0");
  if (raw.ortho_height == 0.0 && !(raw.fov_deg > 0.0 && raw.fov_deg < 180.0)) {
    std::ostringstream out;
    out << "'fov_deg' must be in (0, 180), got " << raw.fov_deg;
    fail(out.str());
  }
  c.fov_deg_ = raw.fov_deg;
  c.ortho_height_ = raw.ortho_height;
  if (raw.up_samples < 2 || raw.up_samples > kMaxCameraPathUpSamples) {
    std::ostringstream out;
    out << "'up_samples' must be in 2.." << kMaxCameraPathUpSamples << ", got " << raw.up_samples;
    fail(out.str());
  }

  // Up-vector table (see the header): transport, then roll towards the projected world up.
  const int n = raw.up_samples;
  c.table_forward_.resize(n);
  c.table_up_.resize(n);
  std::vector<Eigen::Vector3d> raw_forward(n);
  for (int i = 0; i < n; ++i) {
    const double t = c.start_time_ + (c.end_time_ - c.start_time_) * i / (n - 1);
    if (!c.rawForward(t, c.eyeAt(t), raw_forward[i]))
      throw Error(where + ": path evaluation failed at t = " + std::to_string(t) + " (internal error)");
  }
  // Undefined directions take the nearest earlier one (the first defined one at the start).
  Eigen::Vector3d last = -Eigen::Vector3d::UnitZ();
  for (int i = 0; i < n; ++i) {
    if (const auto d = directionOf(raw_forward[i])) {
      last = *d;
      break;
    }
  }
  const double sin_lo = std::sin(kTransportOnlyDeg * std::numbers::pi / 180.0),
               sin_hi = std::sin(kUprightDeg * std::numbers::pi / 180.0);
  for (int i = 0; i < n; ++i) {
    if (const auto d = directionOf(raw_forward[i])) last = *d;
    const Eigen::Vector3d f = last;
    c.table_forward_[i] = f;
    const Eigen::Vector3d projected = c.world_up_ - c.world_up_.dot(f) * f;
    const double sin_angle = projected.norm();  // sine of the angle between view and world up
    Eigen::Vector3d up;
    if (i == 0) {
      up = sin_angle > 1e-9 ? Eigen::Vector3d(projected / sin_angle) : anyPerpendicular(f);
    } else {
      const Eigen::Quaterniond transport = Eigen::Quaterniond::FromTwoVectors(c.table_forward_[i - 1], f);
      up = orthonormalise(transport * c.table_up_[i - 1], f, anyPerpendicular(f));
      const double w = smoothstep(sin_lo, sin_hi, sin_angle);
      if (w > 0.0 && sin_angle > 1e-9) {
        const Eigen::Vector3d target = projected / sin_angle;
        const double angle = std::atan2(up.cross(target).dot(f), up.dot(target));  // signed, about f
        const double view_step = std::acos(std::clamp(c.table_forward_[i - 1].dot(f), -1.0, 1.0));
        const double limit = w * kRollRate * view_step;
        up = Eigen::AngleAxisd(std::clamp(angle, -limit, limit), f) * up;
      }
    }
    c.table_up_[i] = up;
  }
  return c;
}

bool CameraPath::eyePosition(double t, Eigen::Vector3d& out) const {
  const double u = std::clamp((t - start_time_) / (end_time_ - start_time_), 0.0, 1.0);
  return path_.evaluateAtDistance(speed_.evaluate(u) * path_.totalLength(), std::span<double>(out.data(), 3));
}

Eigen::Vector3d CameraPath::eyeAt(double t) const {
  Eigen::Vector3d e;
  if (!std::isfinite(t) || !eyePosition(t, e)) throw Error("camera path: time " + std::to_string(t) + " is not finite");
  return e;
}

Camera CameraPath::cameraAt(double t) const {
  Camera c;
  if (!evaluate(t, c)) throw Error("camera path: time " + std::to_string(t) + " is not finite");
  return c;
}

bool CameraPath::rawForward(double t, const Eigen::Vector3d& eye, Eigen::Vector3d& out) const {
  switch (view_) {
    case ViewMode::kCenterOfInterest:
      out = center_ - eye;
      return true;
    case ViewMode::kMovingTarget: {
      Eigen::Vector3d target;
      if (!target_path_->evaluate(t, std::span<double>(target.data(), 3))) return false;
      out = target - eye;
      return true;
    }
    case ViewMode::kAlongTangent: {
      const double u = std::clamp((t - start_time_) / (end_time_ - start_time_), 0.0, 1.0);
      const double ct = path_.timeAtDistance(speed_.evaluate(u) * path_.totalLength());
      return path_.curve().derivative(ct, std::span<double>(out.data(), 3));
    }
  }
  return false;
}

bool CameraPath::evaluate(double t, Camera& out) const {
  if (!std::isfinite(t)) return false;
  const int n = static_cast<int>(table_up_.size());
  const double x = std::clamp((t - start_time_) / (end_time_ - start_time_), 0.0, 1.0) * (n - 1);
  const int i = std::min(static_cast<int>(x), n - 2);
  const double w = x - i;
  Camera cam;
  Eigen::Vector3d raw_f;
  if (!eyePosition(t, cam.eye) || !rawForward(t, cam.eye, raw_f)) return false;
  Eigen::Vector3d f;
  if (const auto d = directionOf(raw_f)) {
    f = *d;
  } else {  // undefined here: the tabulated direction
    f = normalizedOrNone(Eigen::Vector3d(table_forward_[i] * (1 - w) + table_forward_[i + 1] * w))
            .value_or(table_forward_[w < 0.5 ? i : i + 1]);
  }
  Eigen::Vector3d up_mix = table_up_[i] * (1 - w) + table_up_[i + 1] * w;
  if (up_mix.norm() < 1e-9) up_mix = w < 0.5 ? table_up_[i] : table_up_[i + 1];
  Eigen::Vector3d up =
      orthonormalise(up_mix, f, orthonormalise(table_up_[w < 0.5 ? i : i + 1], f, anyPerpendicular(f)));
  if (tilt_) {
    double tilt_deg = 0.0;
    if (!tilt_->evaluate(t, std::span<double>(&tilt_deg, 1))) return false;
    up = Eigen::AngleAxisd(tilt_deg * std::numbers::pi / 180.0, -f) * up;
  }
  switch (view_) {
    case ViewMode::kCenterOfInterest:
      cam.target = directionOf(center_ - cam.eye) ? center_ : pointAhead(cam.eye, f);
      break;
    case ViewMode::kMovingTarget: {
      const Eigen::Vector3d target = cam.eye + raw_f;
      cam.target = directionOf(target - cam.eye) ? target : pointAhead(cam.eye, f);
      break;
    }
    case ViewMode::kAlongTangent:
      cam.target = pointAhead(cam.eye, f);
      break;
  }
  cam.up = up;
  cam.fov_deg = fov_deg_;
  cam.ortho_height = ortho_height_;
  out = cam;
  return true;
}

}  // namespace vdg::anim
