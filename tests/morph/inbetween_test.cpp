// Key-frame inbetweening of drawings (vdg/morph/inbetween.h, Parent 4.5).
#include "vdg/morph/inbetween.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "support/error_of.h"

namespace vdg::morph {
namespace {

using Eigen::Vector2d;
using testing::errorOf;

constexpr double kTight = 1e-12;  // double rounding over a few dozen operations on values ~10

double distanceToPolyline(const Vector2d& x, const Polyline& line) {
  double best = 1e300;
  for (std::size_t i = 1; i < line.size(); ++i) {
    const Vector2d d = line[i] - line[i - 1];
    const double u = std::clamp((x - line[i - 1]).dot(d) / d.squaredNorm(), 0.0, 1.0);
    best = std::min(best, (x - (line[i - 1] + u * d)).norm());
  }
  return best;
}

TEST(ResampleByArcLength, GivesEquallySpacedPointsOnThePolylineWithItsEndsKept) {
  // An L with unevenly placed points: total length 10 + 5 = 15.
  const Polyline l{{0, 0}, {1, 0}, {7, 0}, {10, 0}, {10, 0}, {10, 2}, {10, 5}};
  const Polyline out = resampleByArcLength(l, 7);  // spacing 2.5
  ASSERT_EQ(out.size(), 7u);
  EXPECT_EQ(out.front(), l.front());
  EXPECT_EQ(out.back(), l.back());
  for (std::size_t i = 0; i < out.size(); ++i) {
    EXPECT_LT(distanceToPolyline(out[i], l), kTight) << i;
    // Arc length of out[i] along the L: x along the first leg, 10 + y on the second.
    const double s = out[i].y() > 0 ? 10 + out[i].y() : out[i].x();
    EXPECT_NEAR(s, 2.5 * static_cast<double>(i), kTight) << i;
  }
  const Polyline still = resampleByArcLength(Polyline{{3, 4}, {3, 4}}, 3);
  EXPECT_EQ(still, (Polyline{{3, 4}, {3, 4}, {3, 4}}));
  EXPECT_EQ(errorOf([] {
              resampleByArcLength(Polyline{{0, 0}}, 4);
            }),
            "resample by arc length: the polyline has 1 point(s); it needs at least 2");
  EXPECT_EQ(errorOf([&] { resampleByArcLength(l, 1); }), "resample by arc length: count 1 is below 2");
}

KeyDrawing key(double time, std::vector<Polyline> strokes) {
  return KeyDrawing{.time = time, .strokes = std::move(strokes)};
}

TEST(Inbetweener, ExactAtKeysAndClampedOutside) {
  const std::vector<KeyDrawing> keys{key(0, {{{0, 0}, {1, 0.3}, {2, 0}}}), key(1, {{{0, 1}, {1.7, 1.1}, {2, 1.9}}}),
                                     key(3, {{{0.2, 2}, {1, 2.6}, {2.5, 2}}}), key(3.5, {{{1, 1}, {2, 2}, {3, 3}}})};
  for (const InbetweenCurve curve : {InbetweenCurve::kLinear, InbetweenCurve::kCatmullRom}) {
    const Inbetweener in(keys, curve);
    for (const KeyDrawing& k : keys) EXPECT_EQ(in.at(k.time), k.strokes);
    EXPECT_EQ(in.at(-5), keys.front().strokes);
    EXPECT_EQ(in.at(8), keys.back().strokes);
  }
}

TEST(Inbetweener, LinearGivesTheMidpointAndCatmullRomIsSmoothAndKeepsUniformMotion) {
  const std::vector<KeyDrawing> two{key(0, {{{0, 0}, {4, 2}}}), key(2, {{{2, 6}, {4, -2}}})};
  const auto mid = Inbetweener(two, InbetweenCurve::kLinear).at(1);
  EXPECT_LT((mid[0][0] - Vector2d(1, 3)).norm(), kTight);
  EXPECT_LT((mid[0][1] - Vector2d(4, 0)).norm(), kTight);
  // Points moving at constant velocity, keys unevenly spaced in time (0, 1, 4): the non-uniform
  // Catmull-Rom tangents are the velocity, so every inbetween lies exactly on the motion.
  auto at = [](double t) { return Polyline{{2 * t, 1 - t}, {5, 3 * t}}; };
  const std::vector<KeyDrawing> uniform{key(0, {at(0)}), key(1, {at(1)}), key(4, {at(4)})};
  const Inbetweener cr(uniform, InbetweenCurve::kCatmullRom);
  for (const double t : {0.25, 0.5, 1.5, 2.0, 3.9}) {
    const auto d = cr.at(t);
    for (std::size_t p = 0; p < 2; ++p) EXPECT_LT((d[0][p] - at(t)[p]).norm(), kTight) << t;
  }
  // Catmull-Rom is C1 across an interior key where linear has a kink.
  const std::vector<KeyDrawing> bent{key(0, {{{0, 0}, {1, 0}}}), key(1, {{{1, 2}, {1, 0}}}),
                                     key(2, {{{3, 2}, {1, 0}}})};
  const double h = 1e-6;
  auto slopeJump = [&](InbetweenCurve curve) {
    const Inbetweener in(bent, curve);
    const Vector2d left = (in.at(1)[0][0] - in.at(1 - h)[0][0]) / h;
    const Vector2d right = (in.at(1 + h)[0][0] - in.at(1)[0][0]) / h;
    return (left - right).norm();
  };
  EXPECT_LT(slopeJump(InbetweenCurve::kCatmullRom), 1e-4);
  EXPECT_GT(slopeJump(InbetweenCurve::kLinear), 1.0);
}

TEST(Inbetweener, StrokesOfDifferentPointCountsAreResampledByArcLength) {
  // Stroke 0 drawn with 2 points in key 0 and 5 in key 1: key 0's is resampled to 5 evenly
  // spaced points; key 1 (which has the most) keeps its own.
  const Polyline drawn{{0, 10}, {1, 10}, {2, 10}, {6, 10}, {8, 10}};
  const Inbetweener in({key(0, {{{0, 0}, {8, 0}}}), key(1, {drawn})}, InbetweenCurve::kLinear);
  ASSERT_EQ(in.keys()[0].strokes[0].size(), 5u);
  for (int i = 0; i < 5; ++i) EXPECT_LT((in.keys()[0].strokes[0][i] - Vector2d(2.0 * i, 0)).norm(), kTight);
  EXPECT_EQ(in.keys()[1].strokes[0], drawn);
  const auto half = in.at(0.5);
  EXPECT_LT((half[0][1] - Vector2d(1.5, 5)).norm(), kTight);
}

TEST(Inbetweener, BadKeysAreNamedByKeyAndStroke) {
  const Polyline line{{0, 0}, {1, 1}};
  EXPECT_EQ(errorOf([] { Inbetweener({}, InbetweenCurve::kLinear); }),
            "inbetween: no key drawings (at least one is needed)");
  EXPECT_EQ(errorOf([&] {
              Inbetweener({key(1, {line}), key(1, {line})}, InbetweenCurve::kLinear);
            }),
            "inbetween: key 1: time 1 is not after key 0's time 1 (key times must increase strictly)");
  EXPECT_EQ(errorOf([&] {
              Inbetweener({key(0, {line}), key(1, {line, line})}, InbetweenCurve::kLinear);
            }),
            "inbetween: key 1: has 2 strokes but key 0 has 1 (stroke i of every key corresponds)");
  EXPECT_EQ(errorOf([&] {
              Inbetweener({key(0, {line, line}), key(1, {line, Polyline{{2, 2}}})}, InbetweenCurve::kCatmullRom);
            }),
            "inbetween: key 1, stroke 1: has 1 point(s); a stroke needs at least 2");
  EXPECT_EQ(errorOf([&] {
              Inbetweener({key(0, {Polyline{{0, 0}, {std::nan(""), 1}}})}, InbetweenCurve::kLinear);
            }),
            "inbetween: key 0, stroke 0, point 1: not finite");
  const Inbetweener one({key(2, {line})}, InbetweenCurve::kCatmullRom);
  EXPECT_EQ(one.at(0), std::vector<Polyline>{line});
  EXPECT_EQ(errorOf([&] { (void)one.at(std::nan("")); }), "inbetween: time nan is not finite");
}

}  // namespace
}  // namespace vdg::morph
