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
Polyline resampleByArcLength(std::span<const Eigen::Vector2d> polyline, int count);

// Builder: checks the keys (>= 1, strictly increasing times, the same stroke count, every stroke
// >= 2 points; throws vdg::Error naming the key and stroke) and resamples every stroke to the
// largest point count any key gives it.
class Inbetweener {
 public:
  Inbetweener(std::vector<KeyDrawing> keys, InbetweenCurve curve);
  // The drawing at `time` (clamped to the keys' span); exact at each key's time.
  std::vector<Polyline> at(double time) const;
  const std::vector<KeyDrawing>& keys() const { return keys_; }

 private:
  std::vector<KeyDrawing> keys_;  // resampled
  InbetweenCurve curve_;
};

}  // namespace vdg::morph
