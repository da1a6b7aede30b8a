// Arc-length reparameterisation of a Curve (Parent, Computer Animation, section 4.1).
//
// Length L(t0, t1) = integral of |P'(t)| dt. Two ways of inverting s(t):
//   kTable     Parent's table method: P is sampled at n equidistant parameter values, the chord
//              lengths are accumulated and normalised to [0, 1]; s -> t by binary search and
//              linear interpolation in the table. Cheap, accuracy O(1/n^2) for smooth curves.
//   kAdaptive  per-segment lengths by adaptive Gauss-Kronrod quadrature of the speed |P'(t)|
//              (Parent's "adaptive Gaussian quadrature", Guenter & Parent); s -> t by a Newton
//              iteration safeguarded by bisection within the segment. Accurate to `tolerance`.
// Distances are in the curve's units; fractions are distance / totalLength() in [0, 1]; both are
// clamped to their range. Lookups allocate nothing and never throw.
//
// Work is bounded whatever the input (hostile specs once took a minute per sample):
//  - curves have at most kMaxCurveDimension coordinates (curve.h);
//  - the relative tolerance is at least kMinArcLengthTolerance: double rounding in the summed
//    quadrature (about 1e-13 relative over kMaxArcLengthIntervals pieces) makes finer ones
//    unreachable, so they only burn time;
//  - one adaptive integral uses at most kMaxArcLengthIntervals Gauss-Kronrod pieces (15 speed
//    evaluations each). build() and adaptiveLength() throw vdg::Error naming that limit when a
//    segment does not reach the tolerance within it; per-frame lookups return the best estimate;
//  - s -> t inversion takes at most kMaxArcLengthNewtonSteps steps, each one short integral;
//  - the table method takes at most kMaxArcLengthTableSamples samples.
#pragma once

#include <span>
#include <string>
#include <vector>

#include "vdg/anim/curve.h"

namespace vdg::anim {

inline constexpr double kMinArcLengthTolerance = 1e-12;
inline constexpr int kMaxArcLengthIntervals = 512;  // smooth segments need 1, a cusp ~40
inline constexpr int kMaxArcLengthNewtonSteps = 60;
inline constexpr int kMaxArcLengthTableSamples = 1000000;  // 16 MB of table

// Parent 4.1: L = sum_i w_i f(u_i), Gauss-Legendre quadrature of |P'(t)| over [t0, t1] with
// `order` points (2..8; throws vdg::Error otherwise). Applied per segment, since |P'| is only
// piecewise smooth.
double gaussLegendreLength(const Curve& curve, double t0, double t1, int order = 5);
// Adaptive Gauss-Kronrod (15 points) quadrature of |P'(t)| over [t0, t1], per segment, to a
// relative tolerance in [kMinArcLengthTolerance, 1). Throws vdg::Error for a tolerance outside
// that range, or when a segment needs more than kMaxArcLengthIntervals pieces.
double adaptiveLength(const Curve& curve, double t0, double t1, double tolerance = 1e-10);

enum class ArcLengthMethod { kTable, kAdaptive };
const char* arcLengthMethodName(ArcLengthMethod method);  // "table", "adaptive"

struct ArcLengthOptions {
  ArcLengthMethod method = ArcLengthMethod::kAdaptive;
  int table_samples = 1000;  // kTable: parameter samples, 2..kMaxArcLengthTableSamples
  double tolerance = 1e-9;   // kAdaptive: relative tolerance of lengths and of the inversion,
                             // in [kMinArcLengthTolerance, 1)
};

// A curve together with its arc-length parameterisation. Owns a copy of the curve (immutable).
class ArcLengthCurve {
 public:
  // Throws vdg::Error naming `where` and the field for bad options (table_samples outside
  // 2..kMaxArcLengthTableSamples, tolerance outside [kMinArcLengthTolerance, 1)), for a segment
  // whose length does not reach the tolerance within kMaxArcLengthIntervals pieces, and for a
  // length that overflows.
  static ArcLengthCurve build(const Curve& curve, const ArcLengthOptions& options = {},
                              const std::string& where = "arc length");

  const Curve& curve() const { return curve_; }
  ArcLengthMethod method() const { return options_.method; }
  double totalLength() const { return total_; }

  // s(t): distance along the curve from its start to parameter t (t clamped). s(start) = 0,
  // s(end) = totalLength(), monotonically non-decreasing.
  double distanceAt(double t) const;
  // t(s): the parameter at distance s (clamped to [0, totalLength()]).
  double timeAtDistance(double s) const;
  // t at fraction f = s / totalLength() (clamped to [0, 1]).
  double timeAtFraction(double f) const;
  // P at distance s / at fraction f into `out` (s, f clamped). Per-frame contract of curve.h:
  // violations (return false, `out` untouched): out.size() != curve().dimension(), s or f not
  // finite.
  [[nodiscard]] bool evaluateAtDistance(double s, std::span<double> out) const;
  [[nodiscard]] bool evaluateAtFraction(double f, std::span<double> out) const;

 private:
  Curve curve_;
  ArcLengthOptions options_;
  double total_ = 0.0;
  std::vector<double> table_t_;        // kTable: sample parameters
  std::vector<double> table_s_;        // kTable: normalised accumulated chord length in [0, 1]
  std::vector<double> segment_start_;  // kAdaptive: distance at each key, segmentCount()+1 entries
};

}  // namespace vdg::anim
