// Ease-in/ease-out — Parent, Computer Animation, section 4.2 ("Ease-In/Ease-Out").
//
// The text's two C listings of ease(t, ...) have slips that we do not reproduce: the sinusoidal one
// declares `rt` twice; the parabolic one declares its parameters as (t, t1, t2) but uses a and b,
// never declares d, and writes `vo` for `v0`. We implement what the text's formulas say.
#include "vdg/anim/ease.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>

#include "vdg/geom/error.h"

namespace vdg::anim {
namespace {

constexpr double kPi = std::numbers::pi;

double clamp01(double t) { return std::isnan(t) ? 0.0 : std::clamp(t, 0.0, 1.0); }

void checkPair(double p1, double p2, const char* name1, const char* name2, const char* what) {
  auto bad = [](double v) { return !std::isfinite(v) || v < 0.0 || v > 1.0; };
  std::ostringstream out;
  if (bad(p1)) {
    out << what << " ease: " << name1 << " = " << p1 << " is outside [0, 1]";
  } else if (bad(p2)) {
    out << what << " ease: " << name2 << " = " << p2 << " is outside [0, 1]";
  } else if (p1 > p2) {
    out << what << " ease: " << name1 << " = " << p1 << " must not exceed " << name2 << " = " << p2;
  } else {
    return;
  }
  throw Error(out.str());
}

double sineUnchecked(double t) { return (std::sin(t * kPi - kPi / 2.0) + 1.0) / 2.0; }

// Parent 4.2 sinusoidal ease: velocity rises as a sine quarter-wave to 1 at t1, stays 1, falls as
// a sine quarter-wave from t2; the covered distance is normalised to 1. C1 (velocity continuous).
double sinusoidalUnchecked(double t, double t1, double t2) {
  const double e1 = t1 * 2.0 / kPi;          // distance after the t1 acceleration
  const double e2 = (1.0 - t2) * 2.0 / kPi;  // distance covered in the (1 - t2) deceleration
  double rt = 0.0;
  if (t < t1) {  // acceleration stage (t1 > 0 here)
    const double nt = t / t1;
    rt = (std::sin(-kPi / 2.0 + nt * kPi / 2.0) + 1.0) * e1;
  } else if (t > t2) {  // deceleration stage (t2 < 1 here)
    const double nt = (t - t2) / (1.0 - t2);
    rt = e1 + (t2 - t1) + std::sin(nt * kPi / 2.0) * e2;
  } else {
    rt = e1 + t - t1;
  }
  return rt / (e1 + (t2 - t1) + e2);  // scale back into [0, 1]
}

// Parent 4.2 constant acceleration ease: v0 = 2 / (b - a + 1);
// d = v0 t^2 / (2a)                                        on [0, a]
//   = v0 a / 2 + (t - a) v0                                on [a, b]
//   = v0 a / 2 + (b - a) v0 + (t - t^2/2 - b + b^2/2) v0 / (1 - b)   on [b, 1]
double parabolicUnchecked(double t, double a, double b) {
  const double v0 = 2.0 / (1.0 + b - a);
  if (t < a) return v0 * t * t / (2.0 * a);
  double d = v0 * a / 2.0;
  if (t < b || b >= 1.0) return d + (std::min(t, b) - a) * v0;
  d += (b - a) * v0;
  d += (t - t * t / 2.0 - b + b * b / 2.0) * v0 / (1.0 - b);
  return d;
}

}  // namespace

const char* easeKindName(EaseKind kind) {
  switch (kind) {
    case EaseKind::kLinear:
      return "linear";
    case EaseKind::kSine:
      return "sine";
    case EaseKind::kSinusoidal:
      return "sinusoidal";
    case EaseKind::kParabolic:
      return "parabolic";
  }
  return "?";
}

double easeSine(double t) { return sineUnchecked(clamp01(t)); }

double easeSinusoidal(double t, double t1, double t2) {
  checkPair(t1, t2, "t1", "t2", "sinusoidal");
  return std::clamp(sinusoidalUnchecked(clamp01(t), t1, t2), 0.0, 1.0);
}

double easeParabolic(double t, double a, double b) {
  checkPair(a, b, "a", "b", "parabolic");
  return std::clamp(parabolicUnchecked(clamp01(t), a, b), 0.0, 1.0);
}

Ease Ease::linear() { return Ease(EaseKind::kLinear, 0.0, 1.0); }
Ease Ease::sine() { return Ease(EaseKind::kSine, 0.0, 1.0); }
Ease Ease::sinusoidal(double t1, double t2) {
  checkPair(t1, t2, "t1", "t2", "sinusoidal");
  return Ease(EaseKind::kSinusoidal, t1, t2);
}
Ease Ease::parabolic(double a, double b) {
  checkPair(a, b, "a", "b", "parabolic");
  return Ease(EaseKind::kParabolic, a, b);
}

double Ease::evaluate(double t) const {
  t = clamp01(t);
  switch (kind_) {
    case EaseKind::kLinear:
      return t;
    case EaseKind::kSine:
      return sineUnchecked(t);
    case EaseKind::kSinusoidal:
      return std::clamp(sinusoidalUnchecked(t, p1_, p2_), 0.0, 1.0);
    case EaseKind::kParabolic:
      return std::clamp(parabolicUnchecked(t, p1_, p2_), 0.0, 1.0);
  }
  return t;
}

std::string Ease::describe() const {
  std::ostringstream out;
  out << easeKindName(kind_);
  if (kind_ == EaseKind::kSinusoidal) out << "(t1=" << p1_ << ", t2=" << p2_ << ")";
  if (kind_ == EaseKind::kParabolic) out << "(a=" << p1_ << ", b=" << p2_ << ")";
  return out.str();
}

}  // namespace vdg::anim
