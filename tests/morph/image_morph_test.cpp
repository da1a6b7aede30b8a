// 2D image morphs (vdg/morph/image_morph.h): the two-pass mesh warp and the Beier-Neely feature
// warp (Parent 4.10), the cross-dissolve and the image helpers.
#include "vdg/morph/image_morph.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "support/error_of.h"

namespace vdg::morph {
namespace {

using Eigen::Vector2d;
using testing::errorOf;

// A float image's values are about 1 (8-bit steps are 1/255 = 0.004); these bound arithmetic
// rounding, far below one 8-bit step.
constexpr float kExact = 0.0f;      // bit for bit
constexpr float kRounding = 1e-5f;  // float accumulation, inverse-spline solve (1e-12 px) times colour gradients

// A test image without symmetries: smooth ramps in R and G, a fine pattern in B, alpha 1.
Image pattern(int width, int height) {
  Image image{
      .width = width, .height = height, .rgba = std::vector<float>(static_cast<std::size_t>(width) * height * 4)};
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      float* p = image.pixel(x, y);
      p[0] = static_cast<float>(x) / width;
      p[1] = static_cast<float>(y) / height;
      p[2] = static_cast<float>((x * 3 + y * 5) % 11) / 10.0f;
      p[3] = 1.0f;
    }
  return image;
}

Image randomImage(int width, int height, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  Image image{
      .width = width, .height = height, .rgba = std::vector<float>(static_cast<std::size_t>(width) * height * 4)};
  for (float& v : image.rgba) v = unit(rng);
  return image;
}

// Largest channel difference over the pixels with x in [x0, x1), y in [y0, y1).
float maxDifference(const Image& a, const Image& b, int x0, int x1, int y0, int y1) {
  float worst = 0;
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x)
      for (int k = 0; k < 4; ++k) worst = std::max(worst, std::abs(a.pixel(x, y)[k] - b.pixel(x, y)[k]));
  return worst;
}
float maxDifference(const Image& a, const Image& b) { return maxDifference(a, b, 0, a.width, 0, a.height); }

// ---- images ------------------------------------------------------------------------------

TEST(MorphImage, Rgba8RoundTripsAndClamps) {
  const TextureImage eight{.width = 2, .height = 1, .rgba = {0, 1, 128, 255, 7, 200, 254, 3}, .file_bytes = {}};
  const Image image = imageFromRgba8(eight);
  EXPECT_FLOAT_EQ(image.pixel(0, 0)[2], 128.0f / 255.0f);
  EXPECT_EQ(imageToRgba8(image).rgba, eight.rgba);
  Image out_of_range = image;
  out_of_range.rgba[0] = -0.5f;
  out_of_range.rgba[1] = 1.5f;
  out_of_range.rgba[2] = std::nanf("");
  const TextureImage clamped = imageToRgba8(out_of_range);
  EXPECT_EQ(clamped.rgba[0], 0);
  EXPECT_EQ(clamped.rgba[1], 255);
  EXPECT_EQ(clamped.rgba[2], 0);
  EXPECT_EQ(errorOf([] {
              imageFromRgba8(TextureImage{.width = 2, .height = 2, .rgba = {1, 2, 3}, .file_bytes = {}});
            }),
            "image: 2 x 2 pixels with 3 bytes is not an RGBA8 image");
}

TEST(MorphImage, CrossDissolveIsExactAtItsEndsAndLinearBetween) {
  const Image a = randomImage(7, 5, 1), b = randomImage(7, 5, 2);
  EXPECT_EQ(crossDissolve(a, b, 0).rgba, a.rgba);
  EXPECT_EQ(crossDissolve(a, b, 1).rgba, b.rgba);
  const Image quarter = crossDissolve(a, b, 0.25);
  for (std::size_t i = 0; i < a.rgba.size(); ++i)
    EXPECT_NEAR(quarter.rgba[i], 0.75 * a.rgba[i] + 0.25 * b.rgba[i], 1e-6);
  EXPECT_EQ(errorOf([&] { crossDissolve(a, randomImage(5, 7, 3), 0.5); }),
            "cross-dissolve: the images differ in size (7 x 5 and 5 x 7)");
  Image broken = a;
  broken.rgba.pop_back();
  EXPECT_EQ(errorOf([&] { crossDissolve(broken, b, 0.5); }),
            "cross-dissolve: first image: the image is 7 x 5 pixels but holds 139 floats, not 140");
}

TEST(MorphImage, BilinearResampleCopiesAtTheSameSizeAndKeepsARampLinear) {
  const Image image = randomImage(9, 6, 4);
  EXPECT_EQ(resampleBilinear(image, 9, 6).rgba, image.rgba);
  // A horizontal ramp value = x + 0.5 (pixel centres) doubled in width: output centre X samples
  // source position X / 2, so away from the clamped border pixel the value is (X + 0.5) / 2 + ... .
  Image ramp{.width = 16, .height = 1, .rgba = std::vector<float>(64, 1.0f)};
  for (int x = 0; x < 16; ++x) ramp.pixel(x, 0)[0] = static_cast<float>(x + 0.5) / 16.0f;
  const Image wide = resampleBilinear(ramp, 32, 1);
  for (int x = 1; x < 31; ++x) EXPECT_NEAR(wide.pixel(x, 0)[0], ((x + 0.5) / 2) / 16.0, kRounding) << x;
  EXPECT_EQ(errorOf([&] { resampleBilinear(image, 0, 3); }),
            "resample: the output size 0 x 3 needs at least 1 x 1 pixels");
}

// ---- grids -------------------------------------------------------------------------------

TEST(MorphGrid, IdentityGridSpansTheImage) {
  const WarpGrid g = identityGrid(3, 5, 40, 20);
  ASSERT_EQ(g.points.size(), 15u);
  EXPECT_EQ(g.at(0, 0), Vector2d(0, 0));
  EXPECT_EQ(g.at(2, 4), Vector2d(40, 20));
  EXPECT_EQ(g.at(1, 2), Vector2d(20, 10));
  EXPECT_NO_THROW(validateGrid(g, "g"));
}

TEST(MorphGrid, CrossingOrTouchingLinesAreNamedByRowAndColumn) {
  WarpGrid g = identityGrid(3, 4, 30, 20);
  g.at(1, 2).x() = 5;  // left of column 1 (x = 10) on row 1: the column curves cross
  EXPECT_EQ(errorOf([&] { validateGrid(g, "a.json: grid"); }),
            "a.json: grid: row 1: the point at column 2 (x = 5) is not right of column 1 (x = 10); grid lines "
            "must not cross or touch (x increases along a row by at least 1e-06)");
  g = identityGrid(3, 4, 30, 20);
  g.at(2, 3).y() = 10;  // touches row 1 in column 3
  EXPECT_EQ(errorOf([&] { validateGrid(g, "g"); }),
            "g: column 3: the point at row 2 (y = 10) is not below row 1 (y = 10); grid lines must not cross or "
            "touch (y increases down a column by at least 1e-06)");
  g = identityGrid(3, 4, 30, 20);
  g.at(0, 1).y() = std::nan("");
  EXPECT_EQ(errorOf([&] { validateGrid(g, "g"); }), "g: the point at row 0, column 1 is not finite");
  EXPECT_EQ(errorOf([] { validateGrid(WarpGrid{.rows = 1, .cols = 3, .points = std::vector<Vector2d>(3)}, "g"); }),
            "g: the grid is 1 x 3 points; it needs at least 2 x 2");
  EXPECT_EQ(errorOf([] { validateGrid(WarpGrid{.rows = 2, .cols = 2, .points = std::vector<Vector2d>(3)}, "g"); }),
            "g: a 2 x 2 grid needs 4 points but has 3");
  EXPECT_EQ(errorOf([] { requireSameShape(identityGrid(3, 3, 8, 8), identityGrid(4, 3, 8, 8), "morph"); }),
            "morph: the grids differ in shape (3 x 3 and 4 x 3 points)");
}

TEST(MorphGrid, PointsTooFarOrTooCloseAreRefused) {
  WarpGrid g = identityGrid(2, 3, 30, 20);
  g.at(1, 2).x() = 2e7;
  EXPECT_EQ(errorOf([&] { validateGrid(g, "g"); }),
            "g: the point at row 1, column 2 (20000000, 20) is farther than 10000000 pixels from the origin in x or y");
  g = identityGrid(2, 3, 30, 20);
  g.at(0, 1).x() = g.at(0, 0).x() + 1e-7;  // closer than kMinGridSpacing: touching
  EXPECT_NE(errorOf([&] { validateGrid(g, "g"); }).find("g: row 0: the point at column 1"), std::string::npos);
}

TEST(MorphGrid, InterpolationIsExactAtItsEnds) {
  const WarpGrid a = identityGrid(3, 3, 30, 30);
  WarpGrid b = a;
  b.at(1, 1) += Vector2d(4, -2);
  EXPECT_EQ(interpolateGrids(a, b, 0).points, a.points);
  EXPECT_EQ(interpolateGrids(a, b, 1).points, b.points);
  EXPECT_EQ(interpolateGrids(a, b, 0.5).at(1, 1), Vector2d(17, 14));
}

TEST(MorphGrid, GridAtTimeIsExactAtKeysLinearWithTwoKeysAndClamped) {
  const WarpGrid a = identityGrid(3, 3, 30, 30);
  WarpGrid b = a, c = a;
  b.at(1, 1) += Vector2d(3, 1);
  c.at(1, 1) += Vector2d(-2, 5);
  c.at(0, 1) += Vector2d(1, 0);
  const std::vector<GridKey> keys{{0.0, a}, {1.0, b}, {4.0, c}};
  EXPECT_EQ(gridAtTime(keys, 0.0).points, a.points);
  EXPECT_EQ(gridAtTime(keys, 1.0).points, b.points);
  EXPECT_EQ(gridAtTime(keys, 4.0).points, c.points);
  EXPECT_EQ(gridAtTime(keys, -3.0).points, a.points);
  EXPECT_EQ(gridAtTime(keys, 9.0).points, c.points);
  // Between keys the point moves smoothly: C1 at key 1 (one-sided slopes agree).
  const double h = 1e-6;
  const Vector2d left = (gridAtTime(keys, 1.0).at(1, 1) - gridAtTime(keys, 1.0 - h).at(1, 1)) / h;
  const Vector2d right = (gridAtTime(keys, 1.0 + h).at(1, 1) - gridAtTime(keys, 1.0).at(1, 1)) / h;
  EXPECT_LT((left - right).norm(), 1e-4);
  const std::vector<GridKey> two{{0.0, a}, {2.0, b}};
  EXPECT_LT((gridAtTime(two, 1.0).at(1, 1) - Vector2d(16.5, 15.5)).norm(), 1e-12);  // two keys: linear
  const std::vector<GridKey> unordered{{0.0, a}, {0.0, b}};
  EXPECT_EQ(errorOf([&] { gridAtTime(unordered, 0.5); }),
            "grid key 1: time 0 is not after key 0's time 0 (key times must increase strictly)");
  const std::vector<GridKey> shapes{{0.0, a}, {1.0, identityGrid(2, 3, 30, 30)}};
  EXPECT_EQ(errorOf([&] { gridAtTime(shapes, 0.5); }),
            "grid key 1: the grids differ in shape (3 x 3 and 2 x 3 points)");
}

// ---- mesh warp ---------------------------------------------------------------------------

TEST(MeshWarp, EqualGridsLeaveTheImageUnchanged) {
  const Image image = pattern(40, 30);
  const WarpGrid g = identityGrid(4, 5, 40, 30);
  EXPECT_EQ(maxDifference(meshWarp(image, g, g), image), kExact);
  // Through the full two-pass path (the grids differ by 1e-9 px): unchanged within rounding.
  WarpGrid nudged = g;
  nudged.at(1, 2).x() += 1e-9;
  nudged.at(2, 3).y() += 1e-9;
  EXPECT_LE(maxDifference(meshWarp(image, g, nudged), image), kRounding);
  // A curved grid warped onto itself (different objects, equal points).
  WarpGrid curved = g;
  curved.at(1, 1) += Vector2d(2, 1.5);
  curved.at(2, 3) += Vector2d(-1.5, 2);
  WarpGrid curved_nudged = curved;
  curved_nudged.at(1, 3).x() += 1e-9;
  EXPECT_LE(maxDifference(meshWarp(image, curved, curved_nudged), image), kRounding);
}

TEST(MeshWarp, ShiftingTheInteriorColumnsShiftsTheContent) {
  // 96 x 64 image, 9 columns 12 px apart. Columns 1..7 (all rows) move right by 3 px; the outer
  // columns stay on the border. The (index, x) splines of source and intermediate differ by exactly
  // 3 where all four points a Catmull-Rom segment uses moved: indices 2..6, source x 24..72.
  const Image image = pattern(96, 64);
  const WarpGrid from = identityGrid(5, 9, 96, 64);
  WarpGrid to = from;
  for (int r = 0; r < to.rows; ++r)
    for (int c = 1; c + 1 < to.cols; ++c) to.at(r, c).x() += 3;
  const Image warped = meshWarp(image, from, to);
  float worst = 0;
  for (int y = 0; y < 64; ++y)
    for (int x = 27; x < 75; ++x)
      for (int k = 0; k < 4; ++k) worst = std::max(worst, std::abs(warped.pixel(x, y)[k] - image.pixel(x - 3, y)[k]));
  EXPECT_LE(worst, kRounding);
  // Left of the moved columns the content is stretched, right of them compressed: not a shift.
  EXPECT_GT(std::abs(warped.pixel(5, 10)[0] - image.pixel(2, 10)[0]), 0.01f);
}

TEST(MeshWarp, ShiftingTheInteriorRowsShiftsTheContentDown) {
  const Image image = pattern(64, 96);
  const WarpGrid from = identityGrid(9, 5, 64, 96);
  WarpGrid to = from;
  for (int r = 1; r + 1 < to.rows; ++r)
    for (int c = 0; c < to.cols; ++c) to.at(r, c).y() += 3;
  const Image warped = meshWarp(image, from, to);
  float worst = 0;
  for (int y = 27; y < 75; ++y)
    for (int x = 0; x < 64; ++x)
      for (int k = 0; k < 4; ++k) worst = std::max(worst, std::abs(warped.pixel(x, y)[k] - image.pixel(x, y - 3)[k]));
  EXPECT_LE(worst, kRounding);
}

// Both passes together: a small dot under a grid point follows the point when it moves
// diagonally (pass 1 takes it to the destination's x, pass 2 to its y).
TEST(MeshWarp, ADotUnderAGridPointFollowsItDiagonally) {
  Image image{.width = 100, .height = 100, .rgba = std::vector<float>(100 * 100 * 4, 0.0f)};
  for (int y = 48; y < 52; ++y)
    for (int x = 48; x < 52; ++x) image.pixel(x, y)[0] = 1.0f;  // centred on (50, 50)
  const WarpGrid from = identityGrid(3, 3, 100, 100);
  WarpGrid to = from;
  to.at(1, 1) = Vector2d(58, 43);
  const Image warped = meshWarp(image, from, to);
  double sx = 0, sy = 0, sum = 0;
  for (int y = 0; y < 100; ++y)
    for (int x = 0; x < 100; ++x) {
      const double v = warped.pixel(x, y)[0];
      sx += v * (x + 0.5);
      sy += v * (y + 0.5);
      sum += v;
    }
  constexpr double kCentroidTolerance = 0.1;  // px: the warp is not affine across the 4-px dot
  EXPECT_NEAR(sx / sum, 58.0, kCentroidTolerance);
  EXPECT_NEAR(sy / sum, 43.0, kCentroidTolerance);
}

// Coverage resampling conserves colour: along a row, the output's sum of a channel is the sum of
// each source pixel's colour times the width it is stretched to.
TEST(MeshWarp, CoverageResamplingConservesColourUnderAStretch) {
  // Columns at 0, 32, 64 moved to 0, 64, 128: x -> 2x (linear data, so the spline is linear).
  const Image image = randomImage(64, 3, 7);
  const WarpGrid from{.rows = 2, .cols = 3, .points = {{0, 0}, {32, 0}, {64, 0}, {0, 3}, {32, 3}, {64, 3}}};
  const WarpGrid to{.rows = 2, .cols = 3, .points = {{0, 0}, {64, 0}, {128, 0}, {0, 3}, {64, 3}, {128, 3}}};
  const Image warped = meshWarp(image, from, to);
  constexpr double kSumTolerance = 1e-4;  // 64 float pixels summed
  for (int y = 0; y < 3; ++y)
    for (int k = 0; k < 4; ++k) {
      double out_sum = 0, in_sum = 0;
      for (int x = 0; x < 64; ++x) out_sum += warped.pixel(x, y)[k];
      for (int x = 0; x < 32; ++x) in_sum += image.pixel(x, y)[k];  // the left half fills the output
      EXPECT_NEAR(out_sum, 2 * in_sum, kSumTolerance) << y << " " << k;
      for (int x = 0; x < 64; ++x) EXPECT_NEAR(warped.pixel(x, y)[k], image.pixel(x / 2, y)[k], kRounding);
    }
}

TEST(MeshWarp, AStepMovedToAFractionalPositionIsAntiAliasedAndConserved) {
  // Left half white, right half black; the middle column moves from x = 32 to x = 40.5.
  Image image{.width = 64, .height = 2, .rgba = std::vector<float>(64 * 2 * 4, 0.0f)};
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 64; ++x) {
      image.pixel(x, y)[0] = x < 32 ? 1.0f : 0.0f;
      image.pixel(x, y)[3] = 1.0f;
    }
  const WarpGrid from{.rows = 2, .cols = 3, .points = {{0, 0}, {32, 0}, {64, 0}, {0, 2}, {32, 2}, {64, 2}}};
  WarpGrid to = from;
  to.at(0, 1).x() = to.at(1, 1).x() = 40.5;
  const Image warped = meshWarp(image, from, to);
  for (int y = 0; y < 2; ++y) {
    double sum = 0;
    for (int x = 0; x < 64; ++x) sum += warped.pixel(x, y)[0];
    EXPECT_NEAR(sum, 40.5, 1e-4);                          // the white area, 40.5 px wide
    EXPECT_NEAR(warped.pixel(40, y)[0], 0.5f, kRounding);  // half covered: anti-aliased edge
    EXPECT_NEAR(warped.pixel(39, y)[0], 1.0f, kRounding);
    EXPECT_NEAR(warped.pixel(41, y)[0], 0.0f, kRounding);
    for (int x = 0; x < 64; ++x) EXPECT_NEAR(warped.pixel(x, y)[3], 1.0f, kRounding);  // alpha stays whole
  }
}

// A valid but wild grid (cells 0.001 px next to cells of hundreds of px; column curves that bulge
// into each other between control points) still gives a finite image in [0, 1].
TEST(MeshWarp, AWildGridGivesAFiniteImage) {
  const Image image = pattern(64, 48);
  const WarpGrid from = identityGrid(4, 4, 64, 48);
  WarpGrid to = from;
  to.at(1, 1) = Vector2d(10, 16);
  to.at(1, 2) = Vector2d(10.001, 17);
  to.at(1, 3) = Vector2d(2000, 1e-3);
  to.at(2, 1) = Vector2d(60, 31);
  to.at(2, 2) = Vector2d(900, 32);
  to.at(2, 3) = Vector2d(950, 32);
  ASSERT_NO_THROW(validateGrid(to, "to"));
  for (const Image& warped : {meshWarp(image, from, to), meshWarp(image, to, from)})
    for (const float v : warped.rgba) {
      ASSERT_TRUE(std::isfinite(v));
      ASSERT_GE(v, -kRounding);
      ASSERT_LE(v, 1 + kRounding);
    }
}

TEST(MeshWarp, BadGridsAreRefusedWithOneLine) {
  const Image image = pattern(20, 20);
  WarpGrid crossing = identityGrid(3, 3, 20, 20);
  crossing.at(1, 1).x() = 25;  // right of column 2 (x = 20)
  EXPECT_EQ(errorOf([&] { meshWarp(image, identityGrid(3, 3, 20, 20), crossing); }),
            "mesh warp: destination grid: row 1: the point at column 2 (x = 20) is not right of column 1 (x = 25); "
            "grid lines must not cross or touch (x increases along a row by at least 1e-06)");
  EXPECT_EQ(errorOf([&] { meshMorph(image, image, identityGrid(3, 3, 20, 20), identityGrid(3, 4, 20, 20), 0.5); }),
            "mesh morph: the grids differ in shape (3 x 3 and 3 x 4 points)");
  EXPECT_EQ(
      errorOf([&] { meshMorph(image, pattern(20, 21), identityGrid(3, 3, 20, 20), identityGrid(3, 3, 20, 20), 0.5); }),
      "mesh morph: the images differ in size (20 x 20 and 20 x 21)");
}

TEST(MeshMorph, ReproducesSourceAndDestinationAtItsEnds) {
  const Image src = pattern(48, 40), dst = randomImage(48, 40, 9);
  const WarpGrid g0 = identityGrid(4, 4, 48, 40);
  WarpGrid g1 = g0;
  g1.at(1, 1) += Vector2d(3, 2);
  g1.at(2, 2) += Vector2d(-2, 3);
  g1.at(1, 2) += Vector2d(1, -2);
  EXPECT_EQ(maxDifference(meshMorph(src, dst, g0, g1, 0.0), src), kExact);
  EXPECT_EQ(maxDifference(meshMorph(src, dst, g0, g1, 1.0), dst), kExact);
  // Just inside the ends, through the full warp-and-dissolve path: within the dissolve weight of
  // the other image (1e-7) plus the warp's tiny motion (1e-7 of at most 3 px of colour change).
  EXPECT_LE(maxDifference(meshMorph(src, dst, g0, g1, 1e-7), src), 2e-5f);
  EXPECT_LE(maxDifference(meshMorph(src, dst, g0, g1, 1 - 1e-7), dst), 2e-5f);
  // Halfway it differs from both.
  const Image half = meshMorph(src, dst, g0, g1, 0.5);
  EXPECT_GT(maxDifference(half, src), 0.1f);
  EXPECT_GT(maxDifference(half, dst), 0.1f);
}

// ---- feature-based morphing (Beier-Neely) ------------------------------------------------

TEST(FeatureWarp, IdenticalLinesLeaveTheImageUnchanged) {
  const Image image = pattern(40, 30);
  const std::vector<FeatureLine> lines{{{5, 5}, {30, 8}}, {{10, 25}, {12, 10}}};
  EXPECT_EQ(maxDifference(featureWarp(image, lines, lines, {}), image), kExact);
  // Through the weighted-displacement path (one endpoint moved 1e-9 px): unchanged within rounding.
  std::vector<FeatureLine> nudged = lines;
  nudged[1].q.x() += 1e-9;
  EXPECT_LE(maxDifference(featureWarp(image, lines, nudged, {}), image), kRounding);
}

// One line pair rotated by 90 degrees about the image centre: a single pair defines a similarity,
// so the image turns by 90 degrees. Output pixel (i, j) takes source position
// c + rot(X - c), rot(d) = (-d_y, d_x), which is the centre of pixel (W - 1 - j, i).
TEST(FeatureWarp, OneLinePairRotatedByNinetyDegreesRotatesTheImage) {
  const int n = 64;
  const Image image = pattern(n, n);
  const std::vector<FeatureLine> to{{{16, 32}, {48, 32}}};
  const std::vector<FeatureLine> from{{{32, 16}, {32, 48}}};
  Image rotated = image;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
      std::copy(image.pixel(n - 1 - j, i), image.pixel(n - 1 - j, i) + 4, rotated.pixel(i, j));
  const Image warped = featureWarp(image, from, to, {});
  EXPECT_LE(maxDifference(warped, rotated, 1, n - 1, 1, n - 1), kRounding);
  // Several pairs all turned the same way give the same rotation whatever their weights.
  auto turn = [&](const Vector2d& p) { return Vector2d(32 - (p.y() - 32), 32 + (p.x() - 32)); };
  const std::vector<FeatureLine> to3{{{16, 32}, {48, 32}}, {{5, 5}, {20, 9}}, {{50, 40}, {44, 60}}};
  std::vector<FeatureLine> from3;
  for (const FeatureLine& l : to3) from3.push_back({turn(l.p), turn(l.q)});
  const Image warped3 = featureWarp(image, from3, to3, {.a = 0.5, .b = 1.5, .p = 0.3});
  EXPECT_LE(maxDifference(warped3, rotated, 1, n - 1, 1, n - 1), kRounding);
}

TEST(FeatureWarp, ALinePairMovedSidewaysTranslatesTheImage) {
  const Image image = pattern(40, 40);
  const std::vector<FeatureLine> from{{{10, 10}, {10, 30}}};
  const std::vector<FeatureLine> to{{{14, 10}, {14, 30}}};  // moved 4 px right: content moves right
  const Image warped = featureWarp(image, from, to, {});
  float worst = 0;
  for (int y = 0; y < 40; ++y)
    for (int x = 4; x < 40; ++x)
      for (int k = 0; k < 4; ++k) worst = std::max(worst, std::abs(warped.pixel(x, y)[k] - image.pixel(x - 4, y)[k]));
  EXPECT_LE(worst, kRounding);
}

TEST(FeatureMorph, ReproducesSourceAndDestinationAtItsEnds) {
  const Image src = pattern(40, 32), dst = randomImage(40, 32, 11);
  const std::vector<FeatureLine> a{{{5, 5}, {30, 6}}, {{8, 28}, {8, 10}}};
  const std::vector<FeatureLine> b{{{7, 9}, {33, 4}}, {{12, 26}, {9, 12}}};
  EXPECT_EQ(maxDifference(featureMorph(src, dst, a, b, 0.0, {}), src), kExact);
  EXPECT_EQ(maxDifference(featureMorph(src, dst, a, b, 1.0, {}), dst), kExact);
  EXPECT_LE(maxDifference(featureMorph(src, dst, a, b, 1e-7, {}), src), 2e-5f);
  EXPECT_LE(maxDifference(featureMorph(src, dst, a, b, 1 - 1e-7, {}), dst), 2e-5f);
}

TEST(FeatureMorph, BadLinesAndParametersAreRefusedWithOneLine) {
  const Image image = pattern(20, 20);
  const std::vector<FeatureLine> good{{{2, 2}, {10, 2}}};
  const std::vector<FeatureLine> point{{{4, 5}, {4, 5}}};
  EXPECT_EQ(errorOf([&] { featureMorph(image, image, good, point, 0.5, {}); }),
            "feature morph: destination line 0: has zero length (from (4, 5) to (4, 5)); a feature line needs two "
            "endpoints at least 1e-06 pixels apart");
  EXPECT_EQ(errorOf([&] { validateFeatureLines(point, good, "l.json"); }),
            "l.json: source line 0: has zero length (from (4, 5) to (4, 5)); a feature line needs two endpoints at "
            "least 1e-06 pixels apart");
  const std::vector<FeatureLine> two{{{2, 2}, {10, 2}}, {{2, 8}, {10, 8}}};
  EXPECT_EQ(errorOf([&] { validateFeatureLines(good, two, "l.json"); }),
            "l.json: 1 source lines but 2 destination lines (they come in pairs)");
  const std::vector<FeatureLine> reversed{{{10, 2}, {2, 2}}};
  EXPECT_EQ(errorOf([&] { featureMorph(image, image, good, reversed, 0.5, {}); }),
            "feature morph: line 0 collapses to a point at t = 0.5 (its source and destination lines point in "
            "opposite directions)");
  EXPECT_EQ(errorOf([&] { featureWarp(image, good, good, {.a = 0}); }),
            "feature warp: a = 0 must be finite and > 0 (pixels)");
  EXPECT_EQ(errorOf([&] { featureWarp(image, good, good, {.p = 2}); }), "feature warp: p = 2 must lie in [0, 1]");
  EXPECT_EQ(errorOf([&] { featureWarp(image, good, good, {.b = -1}); }),
            "feature warp: b = -1 must be finite and >= 0");
  const std::vector<FeatureLine> far{{{2, 2}, {3e7, 2}}};
  EXPECT_EQ(errorOf([&] { featureWarp(image, good, far, {}); }),
            "feature warp: destination line 0: from (2, 2) to (30000000, 2) reaches farther than 10000000 pixels from "
            "the origin in x or y");
  EXPECT_EQ(errorOf([&] { featureWarp(image, {}, good, {}); }),
            "feature warp: 0 source lines but 1 destination lines (they come in pairs)");
  EXPECT_EQ(maxDifference(featureWarp(image, {}, {}, {}), image), kExact);  // no lines: identity
}

}  // namespace
}  // namespace vdg::morph
