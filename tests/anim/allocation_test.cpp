// Anim evaluation allocates nothing (the per-frame contract of curve.h): counted through the
// global operator new (tests/support/allocation_counter.cpp), on valid and refused input alike.
#include <gtest/gtest.h>

#include <limits>
#include <vector>

#include "anim_fixtures.h"
#include "support/allocation_counter.h"
#include "vdg/anim/ease.h"

namespace vdg::anim {
namespace {

using vdg::testing::allocationsDuring;

constexpr int kSamples = 200;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

double sampleTime(int i, double start, double end) { return start - 1.0 + (end - start + 2.0) * i / kSamples; }

TEST(AnimAllocation, CurveEvaluateAndDerivative) {
  for (CurveKind kind : {CurveKind::kLinear, CurveKind::kCatmullRom, CurveKind::kNaturalCubic, CurveKind::kBezier}) {
    const Curve c = fixtures::curve3(kind);
    std::vector<double> out(3), bad(2);
    bool ok = true;
    EXPECT_EQ(allocationsDuring([&] {
                for (int i = 0; i <= kSamples; ++i) {
                  const double t = sampleTime(i, c.startTime(), c.endTime());
                  ok = c.evaluate(t, out) && c.derivative(t, out) && ok;
                  ok = !c.evaluate(t, bad) && !c.evaluate(kNaN, out) && ok;
                }
              }),
              0)
        << curveKindName(kind);
    EXPECT_TRUE(ok);
  }
}

TEST(AnimAllocation, ArcLengthEvaluation) {
  for (ArcLengthMethod method : {ArcLengthMethod::kTable, ArcLengthMethod::kAdaptive}) {
    ArcLengthOptions options;
    options.method = method;
    const ArcLengthCurve a = ArcLengthCurve::build(fixtures::curve3(), options);
    std::vector<double> out(3);
    bool ok = true;
    EXPECT_EQ(allocationsDuring([&] {
                for (int i = 0; i <= kSamples; ++i) {
                  const double f = static_cast<double>(i) / kSamples;
                  ok = a.evaluateAtFraction(f, out) && a.evaluateAtDistance(f * a.totalLength(), out) && ok;
                }
              }),
              0)
        << arcLengthMethodName(method);
    EXPECT_TRUE(ok);
  }
}

TEST(AnimAllocation, TrackEvaluate) {
  for (const Track& track : fixtures::tracks()) {
    std::vector<double> out(static_cast<std::size_t>(track.dimension()));
    bool ok = true;
    EXPECT_EQ(allocationsDuring([&] {
                for (int i = 0; i <= kSamples; ++i)
                  ok = track.evaluate(sampleTime(i, track.startTime(), track.endTime()), out) && ok;
              }),
              0)
        << track.name();
    EXPECT_TRUE(ok);
  }
}

TEST(AnimAllocation, QuaternionCurveEvaluate) {
  const QuaternionCurve c = fixtures::quaternionCurve();
  bool ok = true;
  EXPECT_EQ(allocationsDuring([&] {
              for (int i = 0; i <= kSamples; ++i) {
                Quaternion q;
                ok = c.evaluate(sampleTime(i, c.startTime(), c.endTime()), q) && ok;
              }
            }),
            0);
  EXPECT_TRUE(ok);
}

TEST(AnimAllocation, CameraPathEvaluate) {
  for (const CameraPath& path : fixtures::cameraPaths()) {
    bool ok = true;
    EXPECT_EQ(allocationsDuring([&] {
                for (int i = 0; i <= kSamples; ++i) {
                  Camera c;
                  ok = path.evaluate(sampleTime(i, path.startTime(), path.endTime()), c) && ok;
                }
              }),
              0);
    EXPECT_TRUE(ok);
  }
}

TEST(AnimAllocation, Ease) {
  double sum = 0.0;
  EXPECT_EQ(
      allocationsDuring([&] {
        for (const Ease& e : {Ease::linear(), Ease::sine(), Ease::sinusoidal(0.2, 0.7), Ease::parabolic(0.3, 0.6)})
          for (int i = 0; i <= kSamples; ++i) sum += e.evaluate(sampleTime(i, 0.0, 1.0));
        for (int i = 0; i <= kSamples; ++i) sum += easeSine(sampleTime(i, 0.0, 1.0));
      }),
      0);
  EXPECT_GT(sum, 0.0);
}

}  // namespace
}  // namespace vdg::anim
