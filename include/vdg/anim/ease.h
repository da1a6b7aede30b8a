// Ease-in/ease-out functions (Parent, Computer Animation, section 4.2).
//
// An ease function maps normalised time t in [0, 1] to normalised distance t' in [0, 1]:
// ease(0) = 0, ease(1) = 1, continuous and monotonically non-decreasing. Inputs outside [0, 1] are
// clamped and NaN counts as 0. All functions here are pure and allocation-free.
// Per-frame contract (curve.h): ease functions write no caller memory and have no input they
// reject, so Ease::evaluate has nothing to report: it returns a double, never throws and never
// allocates. Only the parameters (t1, t2 / a, b) can be wrong, and those are checked once, by
// the named constructors.
#pragma once

#include <string>

namespace vdg::anim {

enum class EaseKind {
  kLinear,      // t' = t
  kSine,        // t' = (sin(t*pi - pi/2) + 1) / 2; C-infinity, never constant speed
  kSinusoidal,  // sinusoidal acceleration to t1, constant speed, sinusoidal deceleration from t2; C1
  kParabolic,   // constant acceleration to a, constant speed, constant deceleration from b; C1
};

// "linear", "sine", "sinusoidal", "parabolic".
const char* easeKindName(EaseKind kind);

// Parent 4.2: t' = (sin(t*pi - pi/2) + 1) / 2. ease(0.25) = 0.1464..., ease(0.75) = 0.8535...
double easeSine(double t);

// Parent 4.2, sinusoidal acceleration from time 0 to t1 and deceleration from t2 to 1, constant
// speed between. Requires 0 <= t1 <= t2 <= 1 (throws vdg::Error naming t1/t2 otherwise).
// t1 = 0 means no acceleration phase, t2 = 1 no deceleration phase; t1 = 0, t2 = 1 is linear.
double easeSinusoidal(double t, double t1, double t2);

// Parent 4.2, constant acceleration from 0 to a, constant speed v0 = 2 / (b - a + 1) from a to b,
// constant deceleration from b to 1. Requires 0 <= a <= b <= 1 (throws vdg::Error otherwise).
double easeParabolic(double t, double a, double b);

// An ease function with validated parameters: a small value type, cheap to copy, whose evaluate()
// never throws. Build it with the named constructors (which validate).
class Ease {
 public:
  Ease() = default;  // linear
  static Ease linear();
  static Ease sine();
  static Ease sinusoidal(double t1, double t2);  // throws vdg::Error on bad t1, t2
  static Ease parabolic(double a, double b);     // throws vdg::Error on bad a, b

  EaseKind kind() const { return kind_; }
  // The two parameters: (t1, t2) for kSinusoidal, (a, b) for kParabolic, (0, 1) otherwise.
  double first() const { return p1_; }
  double second() const { return p2_; }

  // t clamped to [0, 1] (NaN counts as 0); result in [0, 1]. Never throws, never allocates.
  double evaluate(double t) const;
  double operator()(double t) const { return evaluate(t); }

  // "sine", "sinusoidal(t1=0.2, t2=0.8)", ...
  std::string describe() const;

 private:
  Ease(EaseKind kind, double p1, double p2) : kind_(kind), p1_(p1), p2_(p2) {}
  EaseKind kind_ = EaseKind::kLinear;
  double p1_ = 0.0;
  double p2_ = 1.0;
};

}  // namespace vdg::anim
