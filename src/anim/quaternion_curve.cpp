// Quaternion curves — Parent, Computer Animation, section 4.3 (Shoemake's Bezier construction on
// the quaternion sphere: automatic interior control points a_n, b_n; De Casteljau with slerp).
#include "vdg/anim/quaternion_curve.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

#include "vdg/anim/curve.h"
#include "vdg/geom/error.h"
#include "vdg/geom/normalize.h"

namespace vdg::anim {

Quaternion sphericalBezier(const Quaternion& q0, const Quaternion& a, const Quaternion& b, const Quaternion& q1,
                           double u) {
  const Quaternion p1 = slerp(q0, a, u);
  const Quaternion p2 = slerp(a, b, u);
  const Quaternion p3 = slerp(b, q1, u);
  const Quaternion p12 = slerp(p1, p2, u);
  const Quaternion p23 = slerp(p2, p3, u);
  return slerp(p12, p23, u);
}

QuaternionCurve QuaternionCurve::build(const std::vector<Quaternion>& keys, const std::vector<double>& times,
                                       const QuaternionCurveOptions& options, const std::string& where) {
  auto fail = [&](const std::string& what) { throw Error(where + ": " + what); };
  const int n = static_cast<int>(keys.size());
  if (n < 2) {
    std::ostringstream out;
    out << "needs at least 2 key orientations, got " << n;
    fail(out.str());
  }
  if (!(options.control_fraction > 0.0 && options.control_fraction <= 1.0)) {
    std::ostringstream out;
    out << "'control_fraction' must be in (0, 1], got " << options.control_fraction;
    fail(out.str());
  }
  QuaternionCurve c;
  for (int i = 0; i < n; ++i) {
    const std::optional<Quaternion> unit = normalizedOrNone(keys[i]);  // any finite length, 1e-200 or 1e200
    if (!unit) {
      std::ostringstream out;
      out << "key " << i << ": quaternion must be finite and non-zero";
      fail(out.str());
    }
    Quaternion q = *unit;
    if (i > 0 && c.keys_.back().coeffs().dot(q.coeffs()) < 0.0) q.coeffs() = -q.coeffs();
    c.keys_.push_back(q);
  }
  if (!times.empty() && static_cast<int>(times.size()) != n) {
    std::ostringstream out;
    out << "'times': expected " << n << " key times, got " << times.size();
    fail(out.str());
  }
  for (std::size_t i = 0; i < times.size(); ++i) {
    if (!std::isfinite(times[i]) || (i > 0 && !(times[i] > times[i - 1]))) {
      std::ostringstream out;
      out << "'times'[" << i << "]: key times must be finite and strictly increase";
      fail(out.str());
    }
    if (i > 0 && !isUsableTimeSpan(times[i] - times[i - 1])) {
      std::ostringstream out;
      out << "'times'[" << i << "]: the span from " << times[i - 1] << " to " << times[i]
          << (std::isinf(times[i] - times[i - 1]) ? " overflows a double" : " is too small to divide by");
      fail(out.str());
    }
  }
  c.times_ = times;
  if (c.times_.empty()) {
    for (int i = 0; i < n; ++i) c.times_.push_back(static_cast<double>(i));
  }
  const auto& q = c.keys_;
  c.a_.assign(n, Quaternion::Identity());
  c.b_.assign(n, Quaternion::Identity());
  // Interior keys: a_i from the text's construction, b_i its mirror about q_i.
  for (int i = 1; i + 1 < n; ++i) {
    const Quaternion a_star = slerp(extend(q[i - 1], q[i]), q[i + 1], 0.5);
    c.a_[i] = slerp(q[i], a_star, options.control_fraction);
    c.b_[i] = extend(c.a_[i], q[i]);
  }
  if (n == 2) {
    c.a_[0] = slerp(q[0], q[1], 1.0 / 3.0);
    c.b_[1] = slerp(q[0], q[1], 2.0 / 3.0);
  } else {
    c.a_[0] = slerp(q[0], c.b_[1], 0.5);
    c.b_[n - 1] = slerp(q[n - 1], c.a_[n - 2], 0.5);
  }
  return c;
}

bool QuaternionCurve::evaluate(double t, Quaternion& out) const {
  if (!std::isfinite(t)) return false;
  const int segments = segmentCount();
  int s = 0;
  double u = 0.0;
  if (t >= times_.back()) {
    s = segments - 1;
    u = 1.0;
  } else if (t > times_.front()) {
    const auto it = std::upper_bound(times_.begin(), times_.end(), t);
    s = std::clamp(static_cast<int>(it - times_.begin()) - 1, 0, segments - 1);
    u = std::clamp((t - times_[s]) / (times_[s + 1] - times_[s]), 0.0, 1.0);
  }
  out = sphericalBezier(keys_[s], a_[s], b_[s + 1], keys_[s + 1], u);
  return true;
}

Quaternion QuaternionCurve::at(double t) const {
  Quaternion q;
  if (!evaluate(t, q)) throw Error("quaternion curve: time " + std::to_string(t) + " is not finite");
  return q;
}

}  // namespace vdg::anim
