// Arc length — Parent, Computer Animation, section 4.1: the table method (accumulated chord
// lengths, normalised, inverted by binary search plus linear interpolation), Gaussian quadrature
// L = sum w_i f(u_i) of the speed |P'(u)|, and adaptive Gaussian quadrature with a root finder for
// u(s) (B. Guenter and R. Parent, "Computing the arc length of parametric curves", IEEE CG&A 1990).
#include "vdg/anim/arc_length.h"

#include <algorithm>
#include <array>
#include <boost/math/quadrature/gauss.hpp>
#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <cmath>
#include <limits>
#include <sstream>

#include "vdg/geom/error.h"

namespace vdg::anim {
namespace {

constexpr int kMaxDim = kMaxCurveDimension;  // every curve's speed fits a stack buffer
constexpr int kNewtonIterations = kMaxArcLengthNewtonSteps;

// |P'(t)| without allocating (Curve::build guarantees dimension() <= kMaxCurveDimension).
double speed(const Curve& curve, double t) {
  std::array<double, kMaxDim> buf{};
  if (curve.dimension() <= kMaxDim) {
    std::span<double> d(buf.data(), static_cast<std::size_t>(curve.dimension()));
    if (!curve.derivative(t, d)) return std::numeric_limits<double>::quiet_NaN();  // t not finite
    double sum = 0.0;
    for (double v : d) sum += v * v;
    return std::sqrt(sum);
  }
  return curve.derivativeAt(t).norm();  // unreachable for built curves
}

template <int N>
double gaussFixed(const Curve& curve, double a, double b) {
  return boost::math::quadrature::gauss<double, N>::integrate([&](double t) { return speed(curve, t); }, a, b);
}

double gaussPiece(const Curve& curve, double a, double b, int order) {
  switch (order) {
    case 2:
      return gaussFixed<2>(curve, a, b);
    case 3:
      return gaussFixed<3>(curve, a, b);
    case 4:
      return gaussFixed<4>(curve, a, b);
    case 5:
      return gaussFixed<5>(curve, a, b);
    case 6:
      return gaussFixed<6>(curve, a, b);
    case 7:
      return gaussFixed<7>(curve, a, b);
    default:
      return gaussFixed<8>(curve, a, b);
  }
}

// One 15-point Gauss-Kronrod rule on [a, b] with its error estimate |K15 - G7|.
struct Piece {
  double a = 0.0, b = 0.0, value = 0.0, error = 0.0;
};
Piece kronrod(const Curve& curve, double a, double b) {
  Piece p{a, b, 0.0, 0.0};
  p.value = boost::math::quadrature::gauss_kronrod<double, 15>::integrate([&](double t) { return speed(curve, t); }, a,
                                                                          b, 0, 0.0, &p.error);
  return p;
}

struct Quadrature {
  double value = 0.0;
  bool converged = true;
};

// Globally adaptive Gauss-Kronrod quadrature of |P'| over [a, b] (as QUADPACK's QAG): the piece
// with the largest error estimate is halved until the summed estimate is within `tolerance` of
// the integral, or kMaxArcLengthIntervals pieces exist (converged = false; the estimate so far is
// returned). Work is therefore bounded by 15 (2 kMaxArcLengthIntervals - 1) speed evaluations,
// whatever the tolerance, and nothing is allocated (the pieces live on the stack).
Quadrature adaptivePieceChecked(const Curve& curve, double a, double b, double tolerance) {
  if (!(b > a)) return {};
  std::array<Piece, kMaxArcLengthIntervals> pieces;
  int count = 1;
  pieces[0] = kronrod(curve, a, b);
  for (;;) {
    double total = 0.0, error = 0.0;
    int worst = 0;
    for (int i = 0; i < count; ++i) {
      total += pieces[i].value;
      error += pieces[i].error;
      if (pieces[i].error > pieces[worst].error) worst = i;
    }
    if (error <= tolerance * std::abs(total)) return {total, true};
    const Piece p = pieces[worst];
    const double mid = 0.5 * (p.a + p.b);
    if (count >= kMaxArcLengthIntervals || !(mid > p.a && mid < p.b) || !std::isfinite(error)) return {total, false};
    pieces[worst] = kronrod(curve, p.a, mid);
    pieces[count++] = kronrod(curve, mid, p.b);
  }
}

double adaptivePiece(const Curve& curve, double a, double b, double tolerance) {
  return adaptivePieceChecked(curve, a, b, tolerance).value;
}

void checkTolerance(double tolerance, const std::string& where) {
  if (!(tolerance >= kMinArcLengthTolerance && tolerance < 1.0)) {
    std::ostringstream out;
    out << where << ": 'tolerance' must be in [" << kMinArcLengthTolerance
        << ", 1) (relative; finer is below the rounding of the quadrature sums), got " << tolerance;
    throw Error(out.str());
  }
}

void throwOverflow(const std::string& where) {
  throw Error(where + ": the curve's length overflows (coordinates too large for doubles)");
}

// Throws vdg::Error when the quadrature of one segment ran out of pieces.
void throwUnconverged(const std::string& where, int segment, double tolerance) {
  std::ostringstream out;
  out << where << ": segment " << segment << ": the arc length did not reach 'tolerance' " << tolerance << " within "
      << kMaxArcLengthIntervals << " quadrature intervals (kMaxArcLengthIntervals); use a larger 'tolerance'";
  throw Error(out.str());
}

// Applies `piece` to each sub-interval of [t0, t1] that lies within one segment.
template <typename Piece>
double perSegment(const Curve& curve, double t0, double t1, Piece piece) {
  double sign = 1.0;
  if (t1 < t0) {
    std::swap(t0, t1);
    sign = -1.0;
  }
  t0 = std::clamp(t0, curve.startTime(), curve.endTime());
  t1 = std::clamp(t1, curve.startTime(), curve.endTime());
  const auto& times = curve.keyTimes();
  double sum = 0.0;
  for (int s = 0; s < curve.segmentCount(); ++s) {
    const double a = std::max(t0, times[s]), b = std::min(t1, times[s + 1]);
    if (b > a) sum += piece(a, b);
  }
  return sign * sum;
}

}  // namespace

const char* arcLengthMethodName(ArcLengthMethod method) {
  return method == ArcLengthMethod::kTable ? "table" : "adaptive";
}

double gaussLegendreLength(const Curve& curve, double t0, double t1, int order) {
  if (order < 2 || order > 8) {
    std::ostringstream out;
    out << "Gauss-Legendre arc length: order " << order << " is outside 2..8";
    throw Error(out.str());
  }
  return perSegment(curve, t0, t1, [&](double a, double b) { return gaussPiece(curve, a, b, order); });
}

double adaptiveLength(const Curve& curve, double t0, double t1, double tolerance) {
  checkTolerance(tolerance, "adaptive arc length");
  int segment = 0;
  return perSegment(curve, t0, t1, [&](double a, double b) {
    const Quadrature q = adaptivePieceChecked(curve, a, b, tolerance);
    if (!std::isfinite(q.value)) throwOverflow("adaptive arc length");
    if (!q.converged) throwUnconverged("adaptive arc length", segment, tolerance);
    ++segment;
    return q.value;
  });
}

ArcLengthCurve ArcLengthCurve::build(const Curve& curve, const ArcLengthOptions& options, const std::string& where) {
  if (options.method == ArcLengthMethod::kTable && options.table_samples < 2) {
    std::ostringstream out;
    out << where << ": 'samples' must be at least 2, got " << options.table_samples;
    throw Error(out.str());
  }
  if (options.method == ArcLengthMethod::kTable && options.table_samples > kMaxArcLengthTableSamples) {
    std::ostringstream out;
    out << where << ": 'samples' must be at most " << kMaxArcLengthTableSamples << ", got " << options.table_samples;
    throw Error(out.str());
  }
  if (options.method == ArcLengthMethod::kAdaptive) checkTolerance(options.tolerance, where);
  if (curve.dimension() > kMaxCurveDimension) {  // a built Curve never is; kept for the contract
    std::ostringstream out;
    out << where << ": curves of dimension " << curve.dimension() << " exceed kMaxCurveDimension ("
        << kMaxCurveDimension << ")";
    throw Error(out.str());
  }
  ArcLengthCurve a;
  a.curve_ = curve;
  a.options_ = options;
  const double t0 = curve.startTime(), t1 = curve.endTime();
  if (options.method == ArcLengthMethod::kTable) {
    // Parent 4.1 table: P at n equidistant parameter values, accumulated chord lengths.
    const int n = options.table_samples;
    a.table_t_.resize(n);
    a.table_s_.resize(n);
    Eigen::VectorXd prev = curve.at(t0), cur(curve.dimension());
    a.table_t_[0] = t0;
    a.table_s_[0] = 0.0;
    for (int i = 1; i < n; ++i) {
      const double t = i == n - 1 ? t1 : t0 + (t1 - t0) * i / (n - 1);
      if (!curve.evaluate(t, std::span<double>(cur.data(), static_cast<std::size_t>(cur.size()))))
        throw Error(where + ": curve evaluation failed at t = " + std::to_string(t) + " (internal error)");
      a.table_t_[i] = t;
      a.table_s_[i] = a.table_s_[i - 1] + (cur - prev).norm();
      prev = cur;
    }
    a.total_ = a.table_s_.back();
    // Normalised distances (monotonic, 0 to 1); a zero-length curve keeps a linear table.
    for (int i = 0; i < n; ++i) {
      a.table_s_[i] = a.total_ > 0.0 ? a.table_s_[i] / a.total_ : static_cast<double>(i) / (n - 1);
    }
    a.table_s_.back() = 1.0;
  } else {
    const auto& times = curve.keyTimes();
    a.segment_start_.assign(times.size(), 0.0);
    for (int s = 0; s < curve.segmentCount(); ++s) {
      const Quadrature q = adaptivePieceChecked(curve, times[s], times[s + 1], options.tolerance);
      if (!std::isfinite(q.value)) throwOverflow(where);
      if (!q.converged) throwUnconverged(where, s, options.tolerance);
      a.segment_start_[s + 1] = a.segment_start_[s] + q.value;
    }
    a.total_ = a.segment_start_.back();
  }
  if (!std::isfinite(a.total_)) throwOverflow(where);
  return a;
}

double ArcLengthCurve::distanceAt(double t) const {
  const double t0 = curve_.startTime(), t1 = curve_.endTime();
  if (!(t > t0)) return 0.0;
  if (t >= t1) return total_;
  if (options_.method == ArcLengthMethod::kTable) {
    const auto it = std::upper_bound(table_t_.begin(), table_t_.end(), t);
    const auto i = static_cast<std::size_t>(
        std::clamp<std::ptrdiff_t>(it - table_t_.begin(), 1, static_cast<std::ptrdiff_t>(table_t_.size()) - 1));
    const double w = (t - table_t_[i - 1]) / (table_t_[i] - table_t_[i - 1]);
    return total_ * (table_s_[i - 1] + w * (table_s_[i] - table_s_[i - 1]));
  }
  double u = 0.0;
  const int s = curve_.segmentAt(t, &u);
  const double a = curve_.keyTimes()[s];
  return segment_start_[s] + adaptivePiece(curve_, a, t, options_.tolerance);
}

double ArcLengthCurve::timeAtFraction(double f) const {
  if (std::isnan(f)) f = 0.0;
  return timeAtDistance(std::clamp(f, 0.0, 1.0) * total_);
}

double ArcLengthCurve::timeAtDistance(double s) const {
  const double t0 = curve_.startTime(), t1 = curve_.endTime();
  if (!(s > 0.0) || total_ <= 0.0) return t0;
  if (s >= total_) return t1;
  if (options_.method == ArcLengthMethod::kTable) {
    // Binary search in the normalised table, then linear interpolation between the two entries.
    const double f = s / total_;
    const auto it = std::upper_bound(table_s_.begin(), table_s_.end(), f);
    const auto i = static_cast<std::size_t>(
        std::clamp<std::ptrdiff_t>(it - table_s_.begin(), 1, static_cast<std::ptrdiff_t>(table_s_.size()) - 1));
    const double ds = table_s_[i] - table_s_[i - 1];
    const double w = ds > 0.0 ? (f - table_s_[i - 1]) / ds : 0.0;
    return table_t_[i - 1] + w * (table_t_[i] - table_t_[i - 1]);
  }
  // Segment holding s, then Newton on g(t) = s(t) - s, safeguarded by bisection on [lo, hi].
  const auto it = std::upper_bound(segment_start_.begin(), segment_start_.end(), s);
  const int seg = std::clamp(static_cast<int>(it - segment_start_.begin()) - 1, 0, curve_.segmentCount() - 1);
  const auto& times = curve_.keyTimes();
  double lo = times[seg], hi = times[seg + 1];
  const double target = s - segment_start_[seg];
  const double seg_len = segment_start_[seg + 1] - segment_start_[seg];
  if (seg_len <= 0.0) return lo;
  double t = lo + (hi - lo) * std::clamp(target / seg_len, 0.0, 1.0);
  const double tol = options_.tolerance * std::max(total_, std::numeric_limits<double>::min());
  // s(t) - s(t_seg) is kept up to date by integrating only between successive iterates, so each
  // step costs one short quadrature (bounded by kMaxArcLengthIntervals) and the whole lookup at
  // most kMaxArcLengthNewtonSteps of them.
  double t_at = times[seg];
  double s_at = 0.0;
  for (int iter = 0; iter < kNewtonIterations; ++iter) {
    s_at += t >= t_at ? adaptivePiece(curve_, t_at, t, options_.tolerance)
                      : -adaptivePiece(curve_, t, t_at, options_.tolerance);
    t_at = t;
    const double g = s_at - target;
    if (std::abs(g) <= tol) break;
    if (g > 0.0) {
      hi = t;
    } else {
      lo = t;
    }
    const double v = speed(curve_, t);
    double next = v > 0.0 ? t - g / v : 0.5 * (lo + hi);
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);  // Newton left the bracket: bisect
    if (hi - lo <= 4 * std::numeric_limits<double>::epsilon() * std::max(1.0, std::abs(hi))) break;
    t = next;
  }
  return t;
}

bool ArcLengthCurve::evaluateAtDistance(double s, std::span<double> out) const {
  if (!std::isfinite(s)) return false;
  return curve_.evaluate(timeAtDistance(s), out);
}

bool ArcLengthCurve::evaluateAtFraction(double f, std::span<double> out) const {
  if (!std::isfinite(f)) return false;
  return curve_.evaluate(timeAtFraction(f), out);
}

}  // namespace vdg::anim
