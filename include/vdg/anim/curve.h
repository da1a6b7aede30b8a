// Key-framed curves P(t) over points of any dimension (Parent, Computer Animation, section 4.1).
//
// A curve takes key points P_0..P_{n-1} (each a vector of `dimension` coordinates) at strictly
// increasing key times t_0 < ... < t_{n-1} and defines P(t) for t in [t_0, t_{n-1}], each
// coordinate independently (X = Px(t), Y = Py(t), ...). Outside that range t is clamped.
//
// Kinds (interpolating = passes through every key point; local = moving a key changes only nearby
// segments):
//   kLinear               interpolating, local, C0.
//   kCatmullRom           interpolating, local, C1 in t. Tangent at an interior key
//                         m_i = (P_{i+1} - P_{i-1}) / (t_{i+1} - t_{i-1}) (the uniform Catmull-Rom
//                         tangent (P_{i+1} - P_{i-1}) / 2 when keys are one time unit apart).
//                         Ends: phantom points reflected, P_{-1} = 2 P_0 - P_1, so the end tangent is
//                         the chord slope of the end segment (P_1 - P_0) / (t_1 - t_0).
//   kCentripetalCatmullRom interpolating, local. Shape from the centripetal knot sequence
//                         (knot spacing |P_{i+1} - P_i|^(1/2)), which has no cusps or self-
//                         intersections within a segment; time maps linearly onto each segment's
//                         knot interval, so P is C0 in t with a continuous tangent direction (G1);
//                         speed may jump at keys (reparameterise by arc length for paths). Ends:
//                         the same reflected phantom points as kCatmullRom.
//   kNaturalCubic         interpolating, global, C2 in t. Natural end conditions P''(t_0) =
//                         P''(t_{n-1}) = 0. Two keys give a straight segment.
//   kParabolicBlending    interpolating, local, C1 in t. On [t_i, t_{i+1}] the parabola through
//                         keys i-1, i, i+1 is blended linearly into the parabola through i, i+1, i+2
//                         (each parabola in t). End segments use the one parabola available. With
//                         equally spaced times it coincides with kCatmullRom in the interior.
//   kBezier               approximating (passes through the anchors only), local, C0 (C1 when the
//                         handles are collinear). Points are P0 C0 C1 P1 C2 C3 P2 ...: 3s+1 points
//                         for s cubic segments; key times are given for the s+1 anchors.
//                         Evaluated by De Casteljau.
// If `times` is empty the key times default to 0, 1, 2, ... (one per key, or per anchor for kBezier).
//
// Every kind is stored as one cubic Bezier segment per key interval, evaluated by De Casteljau.
//
// Per-frame contract (the rule of every vdg evaluation function, after ozz-animation's jobs, here
// and in arc_length.h, track.h, camera_path.h, quaternion_curve.h): a function that writes its
// result into caller-owned memory (a span or an out-reference) returns [[nodiscard]] bool. It
// checks on entry every size (a span must have exactly the size stated), index and value its
// contract names; on a violation it returns false and has written nothing; it never throws and
// never allocates. A time must be finite (NaN and +-infinity are violations); finite times
// outside the keyed range are clamped (or looped), which is not a violation.
// The convenience forms that return their result by value (at(), derivativeAt(), ...) run the same
// checks and throw vdg::Error naming the bad value instead; they are for tools and tests.
#pragma once

#include <Eigen/Core>
#include <span>
#include <string>
#include <vector>

namespace vdg::anim {

// Most coordinates a curve point may have. Animation curves are positions (3), quaternions (4),
// colours (3-4) or a few of these packed together; 16 leaves room for such packs, keeps a point's
// speed on the stack (arc length evaluates it thousands of times per lookup, allocation-free),
// and bounds the cost of one evaluation. A 1,000-dimensional curve once took 50 s per sample.
inline constexpr int kMaxCurveDimension = 16;

enum class CurveKind { kLinear, kCatmullRom, kCentripetalCatmullRom, kNaturalCubic, kParabolicBlending, kBezier };

// "linear", "catmull-rom", "centripetal-catmull-rom", "natural-cubic", "parabolic-blending", "bezier".
const char* curveKindName(CurveKind kind);
bool isInterpolating(CurveKind kind);  // false only for kBezier
bool hasLocalControl(CurveKind kind);  // false only for kNaturalCubic
// Whether `span` = t_{i+1} - t_i (or end - start) can be divided by: finite (times such as
// -1e308 and 1e308 have an infinite span) and at least the smallest normal double.
bool isUsableTimeSpan(double span);

// Authoring description of a curve (what a file or an editor holds).
struct RawCurve {
  CurveKind kind = CurveKind::kCatmullRom;
  std::vector<Eigen::VectorXd> points;  // all of the same dimension >= 1
  std::vector<double> times;            // empty (defaults 0, 1, ...) or one per key (per anchor for kBezier)

  // Throws vdg::Error, message prefixed with `where` (e.g. "spec.json: curve"), when there are too
  // few points (2, or 4 for kBezier; kBezier needs 3s+1), dimensions differ, are 0 or exceed
  // kMaxCurveDimension, a coordinate or time is not finite, the number of times is wrong, the
  // times do not strictly increase, or a time span t_{i+1} - t_i overflows (e.g. -1e308 to 1e308)
  // or is below the smallest normal double (so that 1 / span stays finite).
  void validate(const std::string& where = "curve") const;
};

class Curve {
 public:
  // Validates (see RawCurve::validate) and builds. Throws vdg::Error, also when the built control
  // points overflow (coordinates or slopes too large for doubles), so that no built curve
  // evaluates to inf or NaN.
  static Curve build(const RawCurve& raw, const std::string& where = "curve");

  CurveKind kind() const { return kind_; }
  int dimension() const { return dimension_; }
  int segmentCount() const { return static_cast<int>(times_.size()) - 1; }
  double startTime() const { return times_.front(); }
  double endTime() const { return times_.back(); }
  const std::vector<double>& keyTimes() const { return times_; }

  // P(t) and dP/dt into `out`, t clamped to [startTime, endTime]. Violations (return false, `out`
  // untouched): out.size() != dimension(), t not finite.
  [[nodiscard]] bool evaluate(double t, std::span<double> out) const;
  [[nodiscard]] bool derivative(double t, std::span<double> out) const;
  // Convenience forms that allocate the result; throw vdg::Error for a non-finite t.
  Eigen::VectorXd at(double t) const;
  Eigen::VectorXd derivativeAt(double t) const;

  // Segment containing t (clamped; NaN counts as startTime()): index in [0, segmentCount()), and
  // the local parameter u in [0, 1] into *u (not null).
  int segmentAt(double t, double* u) const;
  // The four Bezier control points of a segment, as a 4 x dimension() row-major span view.
  // Throws vdg::Error "curve: segment S out of range (the curve has N segments)" for a segment
  // outside [0, segmentCount()).
  std::span<const double> segmentControls(int segment) const;

 private:
  CurveKind kind_ = CurveKind::kLinear;
  int dimension_ = 0;
  std::vector<double> times_;     // segmentCount()+1 strictly increasing
  std::vector<double> controls_;  // segmentCount() * 4 * dimension_
};

}  // namespace vdg::anim
