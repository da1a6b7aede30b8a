// Key-framed curves — Parent, Computer Animation, section 4.1 ("Interpolation") and Appendix A.
// Every kind is converted to one cubic Bezier segment per key interval (Hermite data: values and
// time derivatives at both ends, control points P_i + h m_i / 3 and P_{i+1} - h m_{i+1} / 3) and
// evaluated by De Casteljau's construction.
#include "vdg/anim/curve.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>
#include <utility>

#include "vdg/geom/error.h"

namespace vdg::anim {
namespace {

using Vec = Eigen::VectorXd;

int keyCount(const RawCurve& raw) {
  if (raw.kind == CurveKind::kBezier) return (static_cast<int>(raw.points.size()) - 1) / 3 + 1;
  return static_cast<int>(raw.points.size());
}

// Derivative at x of the parabola through (x0, y0), (x1, y1), (x2, y2) (Lagrange form).
Vec parabolaDerivative(double x0, const Vec& y0, double x1, const Vec& y1, double x2, const Vec& y2, double x) {
  return y0 * ((2 * x - x1 - x2) / ((x0 - x1) * (x0 - x2))) + y1 * ((2 * x - x0 - x2) / ((x1 - x0) * (x1 - x2))) +
         y2 * ((2 * x - x0 - x1) / ((x2 - x0) * (x2 - x1)));
}

// Natural cubic spline (global, C2): the second derivatives M_i at the keys from the tridiagonal
// system h_{i-1} M_{i-1} + 2 (h_{i-1} + h_i) M_i + h_i M_{i+1} = 6 (slope_i - slope_{i-1}), natural
// end conditions M_0 = M_{n-1} = 0; solved by the Thomas algorithm.
std::vector<Vec> naturalSecondDerivatives(const std::vector<double>& T, const std::vector<Vec>& P) {
  const int keys = static_cast<int>(P.size());
  const auto dim = P[0].size();
  std::vector<Vec> M(keys, Vec::Zero(dim));
  const int inner = keys - 2;
  if (inner > 0) {
    std::vector<double> diag(inner), upper(inner);
    std::vector<Vec> rhs(inner);
    for (int j = 0; j < inner; ++j) {
      const int i = j + 1;
      const double h0 = T[i] - T[i - 1], h1 = T[i + 1] - T[i];
      diag[j] = 2 * (h0 + h1);
      upper[j] = h1;
      rhs[j] = 6 * ((P[i + 1] - P[i]) / h1 - (P[i] - P[i - 1]) / h0);
    }
    for (int j = 1; j < inner; ++j) {
      const double lower = T[j + 1] - T[j];  // h_{i-1} for row j (i = j + 1)
      const double w = lower / diag[j - 1];
      diag[j] -= w * upper[j - 1];
      rhs[j] -= w * rhs[j - 1];
    }
    M[inner] = rhs[inner - 1] / diag[inner - 1];
    for (int j = inner - 2; j >= 0; --j) M[j + 1] = (rhs[j] - upper[j] * M[j + 2]) / diag[j];
  }
  return M;
}

// Centripetal Catmull-Rom tangents of segment s (keys s and s + 1, not coincident), with respect to
// the knot parameter (spacing sqrt(chord)) and scaled to the segment's knot interval; missing or
// coincident neighbours are replaced by reflections.
std::pair<Vec, Vec> centripetalTangents(const std::vector<Vec>& P, int s) {
  const int keys = static_cast<int>(P.size());
  const Vec& p1 = P[s];
  const Vec& p2 = P[s + 1];
  const double d12 = std::sqrt((p2 - p1).norm());
  Vec p0 = s > 0 ? P[s - 1] : Vec(2 * p1 - p2);
  Vec p3 = s + 2 < keys ? P[s + 2] : Vec(2 * p2 - p1);
  double d01 = std::sqrt((p1 - p0).norm());
  double d23 = std::sqrt((p3 - p2).norm());
  if (d01 <= 0.0) {
    p0 = 2 * p1 - p2;
    d01 = d12;
  }
  if (d23 <= 0.0) {
    p3 = 2 * p2 - p1;
    d23 = d12;
  }
  return {((p1 - p0) / d01 - (p2 - p0) / (d01 + d12) + (p2 - p1) / d12) * d12,
          ((p2 - p1) / d12 - (p3 - p1) / (d12 + d23) + (p3 - p2) / d23) * d12};
}

// Finite keys can still give infinite slopes (1e308 then -1e308, or a tiny time span): reject
// them here rather than evaluate to inf or NaN later.
void checkFiniteControls(const std::vector<double>& controls, int dim, const std::string& where) {
  for (std::size_t i = 0; i < controls.size(); ++i) {
    if (!std::isfinite(controls[i])) {
      std::ostringstream out;
      out << where << ": 'points': segment " << i / (4 * static_cast<std::size_t>(dim))
          << " overflows: its coordinates or slopes are too large for doubles";
      throw Error(out.str());
    }
  }
}

}  // namespace

bool isUsableTimeSpan(double span) { return std::isfinite(span) && span >= std::numeric_limits<double>::min(); }

const char* curveKindName(CurveKind kind) {
  switch (kind) {
    case CurveKind::kLinear:
      return "linear";
    case CurveKind::kCatmullRom:
      return "catmull-rom";
    case CurveKind::kCentripetalCatmullRom:
      return "centripetal-catmull-rom";
    case CurveKind::kNaturalCubic:
      return "natural-cubic";
    case CurveKind::kParabolicBlending:
      return "parabolic-blending";
    case CurveKind::kBezier:
      return "bezier";
  }
  return "?";
}

bool isInterpolating(CurveKind kind) { return kind != CurveKind::kBezier; }
bool hasLocalControl(CurveKind kind) { return kind != CurveKind::kNaturalCubic; }

void RawCurve::validate(const std::string& where) const {
  auto fail = [&](const std::string& what) { throw Error(where + ": " + what); };
  const std::size_t n = points.size();
  if (kind == CurveKind::kBezier) {
    if (n < 4 || (n - 1) % 3 != 0) {
      std::ostringstream out;
      out << "'points': a bezier curve needs 3s+1 points (anchor, 2 handles, anchor, ...), got " << n;
      fail(out.str());
    }
  } else if (n < 2) {
    std::ostringstream out;
    out << "'points': a " << curveKindName(kind) << " curve needs at least 2 points, got " << n;
    fail(out.str());
  }
  const auto dim = points[0].size();
  if (dim < 1) fail("'points'[0]: a point needs at least one coordinate");
  if (dim > kMaxCurveDimension) {
    std::ostringstream out;
    out << "'points'[0]: " << dim << " coordinates; a curve point may have at most " << kMaxCurveDimension;
    fail(out.str());
  }
  for (std::size_t i = 0; i < n; ++i) {
    std::ostringstream out;
    if (points[i].size() != dim) {
      out << "'points'[" << i << "]: expected " << dim << " numbers like 'points'[0], got " << points[i].size();
      fail(out.str());
    }
    if (!points[i].allFinite()) {
      out << "'points'[" << i << "]: coordinates must be finite";
      fail(out.str());
    }
  }
  if (times.empty()) return;
  const auto keys = static_cast<std::size_t>(keyCount(*this));
  if (times.size() != keys) {
    std::ostringstream out;
    out << "'times': expected " << keys << " key times"
        << (kind == CurveKind::kBezier ? " (one per anchor)" : " (one per point)") << ", got " << times.size();
    fail(out.str());
  }
  for (std::size_t i = 0; i < times.size(); ++i) {
    std::ostringstream out;
    if (!std::isfinite(times[i])) {
      out << "'times'[" << i << "]: must be finite";
      fail(out.str());
    }
    if (i > 0 && !(times[i] > times[i - 1])) {
      out << "'times'[" << i << "]: key times must strictly increase (" << times[i - 1] << " then " << times[i] << ")";
      fail(out.str());
    }
    if (i > 0 && !isUsableTimeSpan(times[i] - times[i - 1])) {
      out << "'times'[" << i << "]: the span from " << times[i - 1] << " to " << times[i]
          << (std::isinf(times[i] - times[i - 1]) ? " overflows a double" : " is too small to divide by");
      fail(out.str());
    }
  }
}

Curve Curve::build(const RawCurve& raw, const std::string& where) {
  raw.validate(where);
  Curve c;
  c.kind_ = raw.kind;
  c.dimension_ = static_cast<int>(raw.points[0].size());
  const int keys = keyCount(raw);
  c.times_ = raw.times;
  if (c.times_.empty()) {
    for (int i = 0; i < keys; ++i) c.times_.push_back(static_cast<double>(i));
  }
  const int segments = keys - 1;
  const int dim = c.dimension_;
  c.controls_.assign(static_cast<std::size_t>(segments) * 4 * dim, 0.0);
  auto set = [&](int s, int k, const Vec& v) {
    for (int d = 0; d < dim; ++d) c.controls_[(static_cast<std::size_t>(s) * 4 + k) * dim + d] = v[d];
  };
  const auto& T = c.times_;
  const auto& P = raw.points;
  // Hermite data (values and time derivatives m0, m1 at both ends) -> Bezier controls.
  auto hermite = [&](int s, const Vec& m0, const Vec& m1) {
    const double h = T[s + 1] - T[s];
    set(s, 0, P[s]);
    set(s, 1, P[s] + m0 * (h / 3.0));
    set(s, 2, P[s + 1] - m1 * (h / 3.0));
    set(s, 3, P[s + 1]);
  };

  switch (raw.kind) {
    case CurveKind::kLinear:
      for (int s = 0; s < segments; ++s) {
        const Vec slope = (P[s + 1] - P[s]) / (T[s + 1] - T[s]);
        hermite(s, slope, slope);
      }
      break;
    case CurveKind::kCatmullRom: {
      // Parent 4.1 / Appendix A: Catmull-Rom tangent (P_{i+1} - P_{i-1}) / (t_{i+1} - t_{i-1});
      // ends by reflected phantom points P_{-1} = 2 P_0 - P_1 (tangent = end chord slope).
      std::vector<Vec> m(keys);
      for (int i = 0; i < keys; ++i) {
        const int lo = std::max(i - 1, 0), hi = std::min(i + 1, keys - 1);
        m[i] = (P[hi] - P[lo]) / (T[hi] - T[lo]);
      }
      for (int s = 0; s < segments; ++s) hermite(s, m[s], m[s + 1]);
      break;
    }
    case CurveKind::kCentripetalCatmullRom: {
      // Centripetal Catmull-Rom (knot spacing sqrt(chord)), as Barry-Goldman's pyramid evaluated
      // through its end tangents; degenerate (coincident) neighbours are replaced by reflections.
      for (int s = 0; s < segments; ++s) {
        const Vec& p1 = P[s];
        const Vec& p2 = P[s + 1];
        const double d12 = std::sqrt((p2 - p1).norm());
        if (d12 <= 0.0) {  // coincident keys: a constant segment
          set(s, 0, p1);
          set(s, 1, p1);
          set(s, 2, p2);
          set(s, 3, p2);
          continue;
        }
        const auto [m1, m2] = centripetalTangents(P, s);
        set(s, 0, p1);
        set(s, 1, p1 + m1 / 3.0);
        set(s, 2, p2 - m2 / 3.0);
        set(s, 3, p2);
      }
      break;
    }
    case CurveKind::kNaturalCubic: {
      // Natural cubic spline (global, C2; see naturalSecondDerivatives).
      const std::vector<Vec> M = naturalSecondDerivatives(T, P);
      for (int s = 0; s < segments; ++s) {
        const double h = T[s + 1] - T[s];
        const Vec slope = (P[s + 1] - P[s]) / h;
        hermite(s, slope - h * (2 * M[s] + M[s + 1]) / 6.0, slope + h * (M[s] + 2 * M[s + 1]) / 6.0);
      }
      break;
    }
    case CurveKind::kParabolicBlending: {
      // Parabolic blending (Parent 4.1; Rogers & Adams): C(t) = (1 - s) p(t) + s q(t) on
      // [t_i, t_{i+1}], p through keys i-1, i, i+1 and q through i, i+1, i+2. C is cubic with
      // C'(t_i) = p'(t_i), C'(t_{i+1}) = q'(t_{i+1}); an end segment uses its one parabola.
      auto slopeAt = [&](int a, double x) {  // derivative at x of the parabola through keys a..a+2
        return parabolaDerivative(T[a], P[a], T[a + 1], P[a + 1], T[a + 2], P[a + 2], x);
      };
      for (int s = 0; s < segments; ++s) {
        if (keys == 2) {
          const Vec slope = (P[1] - P[0]) / (T[1] - T[0]);
          hermite(s, slope, slope);
          continue;
        }
        const int first = s > 0 ? s - 1 : 0;             // parabola used at the start
        const int second = s + 2 < keys ? s : keys - 3;  // parabola used at the end
        hermite(s, slopeAt(first, T[s]), slopeAt(second, T[s + 1]));
      }
      break;
    }
    case CurveKind::kBezier:
      for (int s = 0; s < segments; ++s) {
        for (int k = 0; k < 4; ++k) set(s, k, P[3 * s + k]);
      }
      break;
  }
  checkFiniteControls(c.controls_, dim, where);
  return c;
}

int Curve::segmentAt(double t, double* u) const {
  const int segments = segmentCount();
  if (!(t > times_.front())) {  // also catches NaN
    *u = 0.0;
    return 0;
  }
  if (t >= times_.back()) {
    *u = 1.0;
    return segments - 1;
  }
  const auto it = std::upper_bound(times_.begin(), times_.end(), t);
  const int s = std::clamp(static_cast<int>(it - times_.begin()) - 1, 0, segments - 1);
  *u = std::clamp((t - times_[s]) / (times_[s + 1] - times_[s]), 0.0, 1.0);
  return s;
}

std::span<const double> Curve::segmentControls(int segment) const {
  if (segment < 0 || segment >= segmentCount())
    throw Error("curve: segment " + std::to_string(segment) + " out of range (the curve has " +
                std::to_string(segmentCount()) + " segments)");
  return std::span<const double>(controls_).subspan(static_cast<std::size_t>(segment) * 4 * dimension_,
                                                    4 * static_cast<std::size_t>(dimension_));
}

bool Curve::evaluate(double t, std::span<double> out) const {
  if (out.size() != static_cast<std::size_t>(dimension_) || !std::isfinite(t)) return false;
  double u = 0.0;
  const int s = segmentAt(t, &u);
  const double* c = controls_.data() + static_cast<std::size_t>(s) * 4 * dimension_;
  const int dim = dimension_;
  for (int d = 0; d < dim; ++d) {
    // De Casteljau: three rounds of linear interpolation.
    const double a = c[d] + u * (c[dim + d] - c[d]);
    const double b = c[dim + d] + u * (c[2 * dim + d] - c[dim + d]);
    const double e = c[2 * dim + d] + u * (c[3 * dim + d] - c[2 * dim + d]);
    const double ab = a + u * (b - a);
    const double be = b + u * (e - b);
    out[d] = ab + u * (be - ab);
  }
  return true;
}

bool Curve::derivative(double t, std::span<double> out) const {
  if (out.size() != static_cast<std::size_t>(dimension_) || !std::isfinite(t)) return false;
  double u = 0.0;
  const int s = segmentAt(t, &u);
  const double* c = controls_.data() + static_cast<std::size_t>(s) * 4 * dimension_;
  const int dim = dimension_;
  const double scale = 3.0 / (times_[s + 1] - times_[s]);
  for (int d = 0; d < dim; ++d) {
    const double d0 = c[dim + d] - c[d], d1 = c[2 * dim + d] - c[dim + d], d2 = c[3 * dim + d] - c[2 * dim + d];
    const double a = d0 + u * (d1 - d0);
    const double b = d1 + u * (d2 - d1);
    out[d] = scale * (a + u * (b - a));
  }
  return true;
}

Eigen::VectorXd Curve::at(double t) const {
  Eigen::VectorXd v(dimension_);
  if (!evaluate(t, std::span<double>(v.data(), static_cast<std::size_t>(dimension_))))
    throw Error("curve: time " + std::to_string(t) + " is not finite");
  return v;
}

Eigen::VectorXd Curve::derivativeAt(double t) const {
  Eigen::VectorXd v(dimension_);
  if (!derivative(t, std::span<double>(v.data(), static_cast<std::size_t>(dimension_))))
    throw Error("curve: time " + std::to_string(t) + " is not finite");
  return v;
}

}  // namespace vdg::anim
