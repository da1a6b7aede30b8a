// Work budgets (vdg/morph/budget.h) and the 2D morphs' estimates (image_morph.h, inbetween.h).
#include "vdg/morph/budget.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "support/error_of.h"
#include "vdg/morph/image_morph.h"
#include "vdg/morph/inbetween.h"

namespace vdg::morph {
namespace {

using testing::errorOf;

TEST(Budget, RefusesPastTheBudgetInOneLineAndAcceptsUpToIt) {
  EXPECT_NO_THROW(checkBudget(2e9, kDefaultBudget, "x", "", ""));
  EXPECT_EQ(errorOf([] { checkBudget(1.3e10, 2e9, "l.json", "256x256 pixels x 100000 lines", "give --budget N"); }),
            "l.json: needs about 1.3e+10 operations (256x256 pixels x 100000 lines), more than the budget of 2e+09; "
            "give --budget N");
  EXPECT_EQ(errorOf([] { checkBudget(std::numeric_limits<double>::infinity(), 1000, "x", "", ""); }),
            "x: needs more than 1e308 operations, more than the budget of 1000");
  EXPECT_THROW(checkBudget(std::nan(""), 1e300, "x", "", ""), Error);
}

// The search ends, from any start, with the smallest 3-digit size that fits.
TEST(Budget, SmallestFittingSizeIsBoundedAndFits) {
  const auto cube = [](double s) { return std::pow(2.0 / s, 3); };  // +infinity for tiny s
  for (const double start : {1e-300, 1e-5, 0.01}) {
    const double s = smallestFittingSize(cube, start, 1e6);
    EXPECT_LE(cube(s), 1e6) << start;
    EXPECT_GT(cube(s * 0.99), 1e6) << start;
  }
  EXPECT_EQ(smallestFittingSize(cube, 1.0, 1e6), 1.0);  // already fits
  EXPECT_EQ(smallestFittingSize([](double) { return NAN; }, 1.0, 1e6), std::numeric_limits<double>::infinity());
}

// O(pixels x lines): 100,000 lines on a 256 x 256 image is 6.6e9 weights a warp, twice for a morph.
TEST(Budget, FeatureMorphCostIsPixelsTimesLines) {
  EXPECT_DOUBLE_EQ(featureWarpCost(256, 256, 100000), 256.0 * 256 * 100000);
  EXPECT_DOUBLE_EQ(featureMorphCost(256, 256, 100000), 2 * 256.0 * 256 * 100000 + 256 * 256);
  EXPECT_GT(featureMorphCost(256, 256, 100000), kDefaultBudget);
  EXPECT_LT(featureMorphCost(256, 256, 10), kDefaultBudget);
  EXPECT_DOUBLE_EQ(featureWarpCost(8, 8, 0), 64.0);  // no lines: the identity still visits every pixel
  // No wrap-around at the extremes.
  EXPECT_GT(featureWarpCost(65536, 65536, std::size_t{1} << 40), 1e20);
}

TEST(Budget, MeshWarpCostIsAboutLinearInPixels) {
  const double small = meshWarpCost(256, 256, 3, 3), big = meshWarpCost(512, 512, 3, 3);
  EXPECT_NEAR(big / small, 4.0, 0.1);
  EXPECT_GT(meshMorphCost(256, 256, 3, 3), 2 * small);
  EXPECT_LT(meshMorphCost(1024, 1024, 64, 64), kDefaultBudget);
  EXPECT_GT(meshWarpCost(256, 256, 1024, 1024), meshWarpCost(256, 256, 3, 3));
}

KeyDrawing key(double time, std::vector<Polyline> strokes) { return {time, std::move(strokes)}; }

// Points once every stroke is resampled to its largest count, in every key.
TEST(Budget, InbetweenPointsAreCountedBeforeResamplingAndCapped) {
  const Polyline two{{0, 0}, {10, 0}};
  Polyline many(1000, Eigen::Vector2d(5, 5));
  for (int i = 0; i < 1000; ++i) many[static_cast<std::size_t>(i)] = Eigen::Vector2d(i * 0.01, 0);
  const std::vector<KeyDrawing> keys{key(0, {two, two}), key(1, {many, two}), key(2, {two, two})};
  EXPECT_DOUBLE_EQ(inbetweenPointCount(keys), 3 * (1000 + 2));
  // Many keys of a short stroke and one key of a long one would hold keys x points.
  std::vector<KeyDrawing> bomb;
  for (int k = 0; k < 30000; ++k) bomb.push_back(key(k, {two}));
  bomb[0].strokes[0] = many;
  EXPECT_GT(inbetweenPointCount(bomb), kMaxInbetweenPoints);
  EXPECT_EQ(errorOf([&] { Inbetweener(bomb, InbetweenCurve::kLinear); }),
            "inbetween: the keys would hold 3e+07 points once every stroke is resampled to its largest point count "
            "(30000 keys), more than 2e+07; give fewer keys or fewer points per stroke");
}

// A PNG frame fills its canvas once and each segment's box; the SVG frame only the points.
TEST(Budget, InbetweenFrameCostCountsTheCanvasAndTheSegmentsBoxes) {
  const std::vector<KeyDrawing> keys{key(0, {{{0, 0}, {10, 0}, {10, 10}}}), key(1, {{{0, 0}, {20, 0}, {20, 20}}})};
  EXPECT_DOUBLE_EQ(inbetweenFrameCost(keys), 3.0);
  const double png = inbetweenFrameCost(keys, 100, 100);
  EXPECT_GT(png, 100.0 * 100);
  EXPECT_LT(png, 100.0 * 100 + 2 * 30 * 30);
  // A huge canvas costs its pixels: 16384^2 per frame, so 100 frames pass the default budget.
  EXPECT_GT(100 * inbetweenFrameCost(keys, 16384, 16384), kDefaultBudget);
}

}  // namespace
}  // namespace vdg::morph
