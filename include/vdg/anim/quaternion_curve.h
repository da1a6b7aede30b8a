// Smooth interpolation through many orientations (Parent, Computer Animation, section 4.3):
// cubic Bezier curves on the sphere of unit quaternions with automatically computed interior
// control points, evaluated by De Casteljau's construction with slerp.
//
// For key orientations q_0..q_{n-1} at strictly increasing times (default 0, 1, ...), the text's
// construction, with "adding vectors" replaced by concatenating rotations and "averaging" by
// slerping half-way:
//   a*_i = slerp(extend(q_{i-1}, q_i), q_{i+1}, 1/2)   (q_i + (q_i - q_{i-1}), averaged with q_{i+1})
//   a_i  = slerp(q_i, a*_i, control_fraction)
//   b_i  = extend(a_i, q_i)                             (q_i + (q_i - a_i): mirror of a_i about q_i)
// and segment i is the Bezier curve q_i, a_i, b_{i+1}, q_{i+1} on [t_i, t_{i+1}].
// The text takes a_i = a*_i (control_fraction = 1). With that, keys along one great circle make
// the rotation stop half-way through each segment; we default to control_fraction = 1/3 (the
// cubic Bezier form of the Catmull-Rom tangent, as in Shoemake's paper and Parent's book), which
// reproduces uniform slerp for keys evenly spaced on one great arc. Both are C1 at the keys in
// direction (and in magnitude for equal key spacing).
// Ends: a_0 = slerp(q_0, b_1, 1/2) and b_{n-1} = slerp(q_{n-1}, a_{n-2}, 1/2) (two keys: plain slerp).
// Consecutive keys are first made to lie in the same hemisphere (q_{i+1} negated if q_i.q_{i+1} < 0),
// so every segment takes the short way. Evaluation (6 slerps) follows the per-frame contract of
// curve.h: checked on entry, false on a violation, nothing written, no throw, no allocation;
// finite times outside the key range are clamped.
#pragma once

#include <string>
#include <vector>

#include "vdg/anim/rotation.h"

namespace vdg::anim {

struct QuaternionCurveOptions {
  double control_fraction = 1.0 / 3.0;  // in (0, 1]; 1 = the text's literal construction
};

class QuaternionCurve {
 public:
  // keys: non-zero quaternions of any finite length (normalised here, robustly); times: empty or
  // one per key, strictly increasing, with usable spans (isUsableTimeSpan, curve.h).
  // Throws vdg::Error naming `where` for fewer than 2 keys, a zero or non-finite quaternion, bad times
  // (including a span that overflows) or a control_fraction outside (0, 1].
  static QuaternionCurve build(const std::vector<Quaternion>& keys, const std::vector<double>& times = {},
                               const QuaternionCurveOptions& options = {},
                               const std::string& where = "quaternion curve");

  int segmentCount() const { return static_cast<int>(times_.size()) - 1; }
  double startTime() const { return times_.front(); }
  double endTime() const { return times_.back(); }
  const std::vector<double>& keyTimes() const { return times_; }
  // The hemisphere-aligned unit keys and the control points a_i (after q_i), b_i (before q_i).
  const std::vector<Quaternion>& keys() const { return keys_; }
  const std::vector<Quaternion>& controlsAfter() const { return a_; }
  const std::vector<Quaternion>& controlsBefore() const { return b_; }

  // Unit quaternion at time t (clamped) into `out`. Violation (returns false, `out` untouched):
  // t not finite.
  [[nodiscard]] bool evaluate(double t, Quaternion& out) const;
  // Convenience form; throws vdg::Error for a non-finite t.
  Quaternion at(double t) const;

 private:
  std::vector<double> times_;
  std::vector<Quaternion> keys_, a_, b_;
};

// De Casteljau with slerp on one cubic spherical Bezier segment (Parent 4.3):
// p1 = slerp(q0, a, u), p2 = slerp(a, b, u), p3 = slerp(b, q1, u), p12 = slerp(p1, p2, u),
// p23 = slerp(p2, p3, u), p = slerp(p12, p23, u).
Quaternion sphericalBezier(const Quaternion& q0, const Quaternion& a, const Quaternion& b, const Quaternion& q1,
                           double u);

}  // namespace vdg::anim
