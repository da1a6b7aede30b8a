// Key-frame inbetweening of drawings (Parent 4.5, "Simple Key Frame System"): key drawings made of
// strokes (polylines) whose points correspond from key to key; each point's x and y interpolated
// over the keys' times, linearly or with Catmull-Rom. A stroke drawn with a different number of
// points in two keys is first resampled by arc length to a common count.
#pragma once
#include <Eigen/Core>
#include <span>
#include <vector>

namespace vdg::morph {

using Polyline = std::vector<Eigen::Vector2d>;

struct KeyDrawing {
  double time = 0;
  std::vector<Polyline> strokes;  // stroke i of every key corresponds
};

enum class InbetweenCurve { kLinear, kCatmullRom };

// `count` (>= 2) points evenly spaced by arc length along the polyline, first and last kept.
// Throws vdg::Error for fewer than 2 points, count < 2 or a non-finite point. A polyline of one
// repeated point gives `count` copies of it.
Polyline resampleByArcLength(std::span<const Eigen::Vector2d> polyline, int count);

// Points every key holds together once each stroke is resampled to its largest count: the sum over
// strokes of (keys x the stroke's largest point count), in double (never overflowing). The
// Inbetweener refuses more than kMaxInbetweenPoints (16 bytes each: 320 MiB) before resampling.
inline constexpr double kMaxInbetweenPoints = 2e7;
double inbetweenPointCount(std::span<const KeyDrawing> keys);
// The work (operations, vdg/morph/budget.h) of one drawing at a time: every point of every stroke
// of one key (Inbetweener::at). With `raster_width` x `raster_height` > 0, also what `vdg morph
// --format png` spends drawing it: every pixel once, plus, per segment, the pixels of its box (the
// largest a key gives it, padded by the stroke, at most the canvas; a linear inbetween is never
// longer). `keys` as Inbetweener::keys() holds them (each stroke one point count in every key).
double inbetweenFrameCost(std::span<const KeyDrawing> keys, int raster_width = 0, int raster_height = 0);

// Builder: checks the keys (>= 1, finite strictly increasing times whose spans anim::isUsableTimeSpan
// accepts, the same stroke count, every stroke >= 2 finite points; throws vdg::Error "inbetween:
// key K[, stroke S]: ...", or "inbetween: the keys would hold N points once resampled, more than
// 2e+07 (...)" past kMaxInbetweenPoints) and resamples every stroke to the largest point count any key gives it
// (a key that already has that count keeps its points as drawn).
class Inbetweener {
 public:
  Inbetweener(std::vector<KeyDrawing> keys, InbetweenCurve curve);
  // The drawing at `time` (clamped to the keys' span); exact at each key's time. Catmull-Rom is
  // non-uniform in time (tangent (P_{i+1} - P_{i-1}) / (t_{i+1} - t_{i-1}), chord at the ends, as
  // vdg/anim/curve.h's kCatmullRom); two keys give linear motion. Throws vdg::Error for a
  // non-finite time.
  std::vector<Polyline> at(double time) const;
  const std::vector<KeyDrawing>& keys() const { return keys_; }

 private:
  std::vector<KeyDrawing> keys_;  // resampled
  InbetweenCurve curve_;
};

}  // namespace vdg::morph
