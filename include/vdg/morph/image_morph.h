// 2D image morphing (Parent 4.10, "Shape Interpolation, Metamorphosis"): the two-pass mesh warp
// over user-placed curvilinear grids, and feature-based morphing (Beier and Neely) over pairs of
// feature lines; both followed by a pixel-by-pixel cross-dissolve.
//
// Images are straight (not premultiplied) RGBA in [0, 1], top row first; pixel (x, y) covers
// [x, x+1) x [y, y+1), so its centre is (x + 0.5, y + 0.5). Grid points and feature lines are in
// the same pixel coordinates (x right, y down). File formats live in vdg/io/morph_files.h.
#pragma once
#include <Eigen/Core>
#include <span>
#include <string>
#include <vector>
#include "vdg/geom/material.h"

namespace vdg::morph {

struct Image {
  int width = 0, height = 0;
  std::vector<float> rgba;  // width * height * 4
  float* pixel(int x, int y) { return &rgba[(static_cast<std::size_t>(y) * width + x) * 4]; }
  const float* pixel(int x, int y) const { return &rgba[(static_cast<std::size_t>(y) * width + x) * 4]; }
};
// Throws vdg::Error "WHAT: ..." unless the image is at least 1 x 1 and holds width * height * 4 floats.
// Every function below that takes an Image checks it so.
void validateImage(const Image& image, const std::string& what);
Image imageFromRgba8(const TextureImage& image);  // 8-bit to [0, 1]; throws vdg::Error for a bad size
TextureImage imageToRgba8(const Image& image);    // rounded, clamped to [0, 255] (NaN to 0)

// (1 - t) a + t b per channel. Throws vdg::Error when the sizes differ.
Image crossDissolve(const Image& a, const Image& b, double t);
// Plain bilinear resample to width x height (the benchmark's baseline): output pixel centre
// (x + 0.5, y + 0.5) samples the source at (x + 0.5) W / width, (y + 0.5) H / height, clamped to
// the outermost pixel centres. The same size gives an exact copy.
Image resampleBilinear(const Image& image, int width, int height);

// ---- Mesh warp (two-pass, Smythe) ----------------------------------------------------------
// A curvilinear grid: rows x cols intersection points, row-major, numbered left to right and top
// to bottom. Columns of points define the curves down the image, rows the curves across it.
struct WarpGrid {
  int rows = 0, cols = 0;
  std::vector<Eigen::Vector2d> points;  // rows * cols
  const Eigen::Vector2d& at(int r, int c) const { return points[static_cast<std::size_t>(r) * cols + c]; }
  Eigen::Vector2d& at(int r, int c) { return points[static_cast<std::size_t>(r) * cols + c]; }
};
// An evenly spaced grid of rows x cols points whose outer points lie on the image border.
WarpGrid identityGrid(int rows, int cols, int width, int height);
// Grid points and feature-line endpoints must lie within this many pixels of the origin (so that
// no slope or weight overflows).
inline constexpr double kMaxMorphCoordinate = 1e7;
// Neighbouring grid points closer than this (pixels) along a row (x) or down a column (y) touch.
inline constexpr double kMinGridSpacing = 1e-6;
// Throws vdg::Error "WHAT: ..." (naming the row and column) for fewer than 2 x 2 points, a
// non-finite point or one beyond kMaxMorphCoordinate, or grid lines that cross or touch: along
// every row x must increase, down every column y must increase, by at least kMinGridSpacing.
void validateGrid(const WarpGrid& grid, const std::string& what);
// Throws vdg::Error "WHAT: ..." unless a and b have the same rows and cols.
void requireSameShape(const WarpGrid& a, const WarpGrid& b, const std::string& what);
// Point-by-point linear interpolation (1 - t) a + t b.
WarpGrid interpolateGrids(const WarpGrid& a, const WarpGrid& b, double t);
// A grid given at key times, interpolated over time per point with Catmull-Rom (linear with two
// keys; clamped outside the keys). Keys sorted by strictly increasing time, all of one shape.
struct GridKey {
  double time = 0;
  WarpGrid grid;
};
WarpGrid gridAtTime(std::span<const GridKey> keys, double time);
// Two-pass warp of `image` so that the features under grid `from` move to grid `to` (same shape):
// pass 1 moves pixels along scanlines (x) onto the intermediate grid (x of `to`, y of `from`; the
// .cpp says why not the other way round), pass 2 along columns (y) onto `to`; Catmull-Rom curves
// through the grid's columns and rows, pixel boundaries mapped through the (index, intercept)
// splines, fractional coverage (box-filter) resampling. Outside the grid's outer curves the
// outermost cells are extended (the .cpp documents how). Output has the input's size; from == to
// returns the image unchanged. Throws vdg::Error for an invalid grid or image, or grids of
// different shapes.
Image meshWarp(const Image& image, const WarpGrid& from, const WarpGrid& to);
// The inbetween at t: both images warped onto interpolateGrids(src_grid, dst_grid, t), then
// cross-dissolved with t. t = 0 gives src, t = 1 gives dst. Images of one size.
Image meshMorph(const Image& src, const Image& dst, const WarpGrid& src_grid, const WarpGrid& dst_grid, double t);

// ---- Feature-based morphing (Beier and Neely) ----------------------------------------------
struct FeatureLine {
  Eigen::Vector2d p{0, 0}, q{0, 0};  // from P to Q
};
// The weight of a line for a pixel: (length^p / (a + dist))^b.
struct FeatureParams {
  double a = 1.0;  // pixels; > 0 keeps the weight finite on the line
  double b = 2.0;  // how fast the weight falls off with distance, >= 0
  double p = 0.5;  // how much longer lines count, in [0, 1]
};
// Throws vdg::Error "WHAT: ..." naming the parameter unless a > 0, b >= 0, p in [0, 1], all finite.
void validateFeatureParams(const FeatureParams& params, const std::string& what);
// Lines shorter than this (pixels) count as zero-length.
inline constexpr double kMinFeatureLineLength = 1e-6;
// Throws vdg::Error "WHAT: source line I: ..." (or "destination line I") for a zero-length
// (shorter than kMinFeatureLineLength) or non-finite line or an endpoint beyond
// kMaxMorphCoordinate, or "WHAT: ..." for differing counts.
// No lines at all is allowed: the warp is then the identity.
void validateFeatureLines(std::span<const FeatureLine> src, std::span<const FeatureLine> dst, const std::string& what);
// Reverse-mapped warp: each output pixel X, with lines `to`, takes the colour at the weighted
// average of its positions X' relative to lines `from` (bilinear sampling, clamped at the border).
Image featureWarp(const Image& image, std::span<const FeatureLine> from, std::span<const FeatureLine> to,
                  const FeatureParams& params);
// Lines interpolated with t (endpoints linearly), both images warped onto them, cross-dissolved.
// t = 0 gives src, t = 1 gives dst. Throws vdg::Error when an interpolated line collapses to a
// point (a pair whose lines point in opposite directions), naming the line and t.
Image featureMorph(const Image& src, const Image& dst, std::span<const FeatureLine> src_lines,
                   std::span<const FeatureLine> dst_lines, double t, const FeatureParams& params);

// ---- Cost estimates (operations, vdg/morph/budget.h; in double, never overflowing) ---------------
// featureWarp: a weight per pixel and line, W H max(lines, 1): O(pixels x lines), the cost that
// makes 100,000 lines on a 256 x 256 image take minutes.
double featureWarpCost(int width, int height, std::size_t lines);
// featureMorph: two warps and the dissolve, 2 featureWarpCost + W H.
double featureMorphCost(int width, int height, std::size_t lines);
// meshWarp: two passes; each resamples every pixel (with a search among the grid's curves,
// log2(curves) + 1) and evaluates every curve on every scanline: 2 (W H (log2(max(rows, cols)) + 1)
// + (W + H) rows cols).
double meshWarpCost(int width, int height, int rows, int cols);
// meshMorph: two warps and the dissolve, 2 meshWarpCost + W H.
double meshMorphCost(int width, int height, int rows, int cols);

}  // namespace vdg::morph
