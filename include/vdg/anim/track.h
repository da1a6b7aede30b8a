// Tracks: the key-frame system (Parent, Computer Animation, sections 4.5 and 4.9).
//
// One track per animated parameter (a scalar, a vector, or a rotation), holding keys (time, value),
// one interpolation for the whole track and an optional ease per segment (TWIXT-style: "track per
// display parameter ... linear, parabolic, cubic interpolation with ease-in/ease-out").
//
//   RawTrack (mutable, what a file holds) --Track::build (validates)--> Track (immutable)
//   --evaluate(t, out)--> value, under the per-frame contract of curve.h (checked on entry, false
//   on a violation with nothing written, no throw, no allocation).
//
// Values: kScalar has 1 component; kVector n >= 1 components (all keys alike); kRotation is a
// quaternion given and returned as 4 numbers (w, x, y, z) — keys are normalised at build time.
// Interpolations: kStep (hold the previous key) for every type; kLinear, kCatmullRom,
// kCentripetalCatmullRom, kNaturalCubic, kParabolicBlending, kBezier (see curve.h) for scalars and
// vectors; kSlerp (shortest-arc slerp per segment) and kQuaternionCurve (see quaternion_curve.h)
// for rotations. kBezier keys may carry handles: `out` (the control point after the key) and `in`
// (the control point before it); a missing handle is placed on the Catmull-Rom tangent, one third
// of the segment away.
// Ease: a key's ease reshapes time on the segment from that key to the next: with
// u = (t - t_i) / (t_{i+1} - t_i), the curve is evaluated at t_i + ease(u) (t_{i+1} - t_i); the key
// values are still reached at the key times.
// Outside [first key time, last key time]: kClamp holds the end values; kLoop repeats the keyed
// range with period (last - first) (the last key's time maps onto the first key's, so a seamless
// loop repeats the first value as its last key). A single key gives a constant track.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "vdg/anim/curve.h"
#include "vdg/anim/ease.h"
#include "vdg/anim/quaternion_curve.h"
#include "vdg/anim/rotation.h"

namespace vdg::anim {

enum class TrackType { kScalar, kVector, kRotation };
enum class Interpolation {
  kStep,
  kLinear,
  kCatmullRom,
  kCentripetalCatmullRom,
  kNaturalCubic,
  kParabolicBlending,
  kBezier,
  kSlerp,
  kQuaternionCurve,
};
enum class Extrapolation { kClamp, kLoop };

// "scalar", "vector", "rotation"; "step", "linear", "catmull-rom", "centripetal-catmull-rom",
// "natural-cubic", "parabolic-blending", "bezier", "slerp", "quaternion-curve"; "clamp", "loop".
const char* trackTypeName(TrackType type);
const char* interpolationName(Interpolation interpolation);
const char* extrapolationName(Extrapolation extrapolation);

struct RawKey {
  double time = 0.0;
  Eigen::VectorXd value;                     // 1, n or 4 (w, x, y, z) numbers, see above
  std::optional<Eigen::VectorXd> in_handle;  // kBezier only, same size as value
  std::optional<Eigen::VectorXd> out_handle;
  std::optional<Ease> ease;  // ease of the segment from this key to the next
};

struct RawTrack {
  std::string name;  // used in error messages
  TrackType type = TrackType::kScalar;
  Interpolation interpolation = Interpolation::kLinear;
  Extrapolation extrapolation = Extrapolation::kClamp;
  std::vector<RawKey> keys;

  // Throws vdg::Error "WHERE: track 'NAME': ..." naming the key index, for: no keys, key times not
  // finite or not strictly increasing, a span between two keys (or from the first key, the loop
  // period) that overflows or is too small to divide by (isUsableTimeSpan), value sizes wrong or
  // differing or above kMaxCurveDimension, non-finite values, a zero quaternion (any finite
  // non-zero length is fine), an interpolation not available for the type, handles on a
  // non-Bezier track. Track::build also throws when the built curve overflows (see Curve::build).
  void validate(const std::string& where = "track") const;
};

class Track {
 public:
  static Track build(const RawTrack& raw, const std::string& where = "track");

  const std::string& name() const { return name_; }
  TrackType type() const { return type_; }
  Interpolation interpolation() const { return interpolation_; }
  Extrapolation extrapolation() const { return extrapolation_; }
  int dimension() const { return dimension_; }  // 1, n, or 4 for rotations
  double startTime() const { return times_.front(); }
  double endTime() const { return times_.back(); }
  int keyCount() const { return static_cast<int>(times_.size()); }

  // Value at time t (any finite t; clamped or looped) into `out`. Violations (return false, `out`
  // untouched): out.size() != dimension(), t not finite.
  [[nodiscard]] bool evaluate(double t, std::span<double> out) const;
  // Convenience forms (tools and tests); they throw vdg::Error "track 'NAME': ..." for a
  // non-finite t, and rotationAt for a track that is not kRotation.
  Eigen::VectorXd at(double t) const;     // allocates
  double scalarAt(double t) const;        // first component
  Quaternion rotationAt(double t) const;  // kRotation tracks: unit quaternion

  // The time at which the underlying curve is evaluated for time t: after clamping or looping and
  // after the segment's ease (NaN counts as startTime()).
  double curveTime(double t) const;

 private:
  std::string name_;
  TrackType type_ = TrackType::kScalar;
  Interpolation interpolation_ = Interpolation::kLinear;
  Extrapolation extrapolation_ = Extrapolation::kClamp;
  int dimension_ = 1;
  std::vector<double> times_;
  std::vector<double> values_;  // keyCount() x dimension_ (rotations hemisphere-aligned, unit)
  std::vector<Ease> eases_;     // one per segment (linear when none)
  std::optional<Curve> curve_;  // scalar / vector curves
  std::optional<QuaternionCurve> quaternion_curve_;
};

}  // namespace vdg::anim
