// Tests of ease-in/ease-out (Parent 4.2): the text's numbers and the properties every ease has.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "vdg/anim/ease.h"
#include "vdg/geom/error.h"

namespace vdg::anim {
namespace {

constexpr double kTol = 1e-12;
constexpr double kTextTol = 1e-4;  // the text prints 4 decimals (0.146447 as .1465)
constexpr double kStep = 1e-4;     // finite-difference step for continuity checks
constexpr double kC1Tol = 1e-2;    // allowed jump of the finite-difference slope at a phase joint

std::vector<Ease> allEases() {
  return {Ease::linear(),
          Ease::sine(),
          Ease::sinusoidal(0.2, 0.8),
          Ease::sinusoidal(0.0, 1.0),
          Ease::sinusoidal(0.3, 0.3),
          Ease::sinusoidal(0, 0),
          Ease::sinusoidal(1, 1),
          Ease::parabolic(0.2, 0.8),
          Ease::parabolic(0.0, 1.0),
          Ease::parabolic(0.5, 0.5),
          Ease::parabolic(0, 0),
          Ease::parabolic(1, 1)};
}

TEST(Ease, SineMatchesTheText) {
  EXPECT_NEAR(easeSine(0.25), 0.1465, kTextTol);
  EXPECT_NEAR(easeSine(0.75), 0.8535, kTextTol);
  EXPECT_NEAR(easeSine(0.25), (1 - std::sqrt(0.5)) / 2, kTol);
  EXPECT_NEAR(easeSine(0.5), 0.5, kTol);
}

TEST(Ease, EndpointsMonotonicContinuous) {
  for (const Ease& e : allEases()) {
    SCOPED_TRACE(e.describe());
    EXPECT_NEAR(e(0.0), 0.0, kTol);
    EXPECT_NEAR(e(1.0), 1.0, kTol);
    double prev = 0.0;
    for (int i = 1; i <= 10000; ++i) {
      const double v = e(i / 10000.0);
      EXPECT_GE(v, prev - kTol);
      EXPECT_LE(v - prev, 2.0 * 1e-4 * 2.5);  // continuous: bounded slope (v0 <= 2)
      prev = v;
    }
  }
}

TEST(Ease, ClampsOutsideUnitInterval) {
  EXPECT_EQ(Ease::sine()(-1.0), 0.0);
  EXPECT_EQ(Ease::sine()(2.0), 1.0);
  EXPECT_EQ(easeParabolic(-0.5, 0.2, 0.8), 0.0);
  EXPECT_EQ(easeSinusoidal(1.5, 0.2, 0.8), 1.0);
}

double slope(const Ease& e, double t) { return (e(t + kStep) - e(t - kStep)) / (2 * kStep); }

TEST(Ease, SinusoidalIsC1WithConstantMiddleSpeed) {
  const Ease e = Ease::sinusoidal(0.2, 0.8);
  // Joints at t1 and t2: the slope is the same on both sides.
  for (double joint : {0.2, 0.8}) {
    const double left = (e(joint) - e(joint - kStep)) / kStep, right = (e(joint + kStep) - e(joint)) / kStep;
    EXPECT_NEAR(left, right, kC1Tol) << joint;
  }
  // Constant speed between t1 and t2, zero speed at both ends.
  const double v = slope(e, 0.5);
  EXPECT_NEAR(slope(e, 0.3), v, 1e-6);
  EXPECT_NEAR(slope(e, 0.7), v, 1e-6);
  EXPECT_NEAR((e(kStep) - e(0)) / kStep, 0.0, kC1Tol);
  EXPECT_NEAR((e(1) - e(1 - kStep)) / kStep, 0.0, kC1Tol);
  // The text's formula: distance e1 + (t - t1) in the middle, normalised by e1 + (t2 - t1) + e2.
  const double e1 = 0.2 * 2 / M_PI, e2 = 0.2 * 2 / M_PI;
  EXPECT_NEAR(e(0.5), (e1 + 0.3) / (e1 + 0.6 + e2), kTol);
  EXPECT_NEAR(e(0.1), (std::sin(-M_PI / 2 + 0.5 * M_PI / 2) + 1) * e1 / (e1 + 0.6 + e2), kTol);
}

TEST(Ease, ParabolicMatchesTheTextsDistanceFormulas) {
  const double a = 0.2, b = 0.7;
  const Ease e = Ease::parabolic(a, b);
  const double v0 = 2 / (b - a + 1);
  EXPECT_NEAR(v0, 2 / 1.5, kTol);
  EXPECT_NEAR(e(0.1), v0 * 0.01 / (2 * a), kTol);
  EXPECT_NEAR(e(0.5), v0 * a / 2 + (0.5 - a) * v0, kTol);
  const double t = 0.9;
  EXPECT_NEAR(e(t), v0 * a / 2 + (b - a) * v0 + (t - t * t / 2 - b + b * b / 2) * v0 / (1 - b), kTol);
  // Constant speed v0 between a and b; C1 at a and b; speed 0 at the ends.
  EXPECT_NEAR(slope(e, 0.45), v0, 1e-6);
  for (double joint : {a, b}) {
    const double left = (e(joint) - e(joint - kStep)) / kStep, right = (e(joint + kStep) - e(joint)) / kStep;
    EXPECT_NEAR(left, right, kC1Tol) << joint;
  }
  EXPECT_NEAR((e(kStep) - e(0)) / kStep, 0.0, kC1Tol);
}

TEST(Ease, DefaultCasesAreLinear) {
  for (double t : {0.1, 0.37, 0.9}) {
    EXPECT_NEAR(easeSinusoidal(t, 0.0, 1.0), t, kTol);
    EXPECT_NEAR(easeParabolic(t, 0.0, 1.0), t, kTol);
    EXPECT_NEAR(Ease::linear()(t), t, kTol);
  }
}

void expectError(auto f, const std::string& message) {
  try {
    f();
    FAIL() << "expected vdg::Error: " << message;
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), message);
  }
}

TEST(Ease, RejectsBadParameters) {
  expectError([] { Ease::sinusoidal(0.8, 0.2); }, "sinusoidal ease: t1 = 0.8 must not exceed t2 = 0.2");
  expectError([] { Ease::sinusoidal(-0.1, 0.2); }, "sinusoidal ease: t1 = -0.1 is outside [0, 1]");
  expectError([] { Ease::sinusoidal(0.1, 1.5); }, "sinusoidal ease: t2 = 1.5 is outside [0, 1]");
  expectError([] { Ease::sinusoidal(NAN, 0.5); }, "sinusoidal ease: t1 = nan is outside [0, 1]");
  expectError([] { Ease::parabolic(0.9, 0.1); }, "parabolic ease: a = 0.9 must not exceed b = 0.1");
  expectError([] { Ease::parabolic(0.1, 2); }, "parabolic ease: b = 2 is outside [0, 1]");
  expectError([] { easeSinusoidal(0.5, 0.6, 0.4); }, "sinusoidal ease: t1 = 0.6 must not exceed t2 = 0.4");
  expectError([] { easeParabolic(0.5, -1, 0.4); }, "parabolic ease: a = -1 is outside [0, 1]");
}

}  // namespace
}  // namespace vdg::anim
