// Key-frame inbetweening of drawings — Parent, Computer Animation, section 4.5 ("Simple Key Frame
// System"): each point of a key drawing is a pair of parameters (x, y) given at the key frames;
// the inbetween frames take each parameter interpolated over the keys' times (linearly, or with
// Catmull-Rom as Parent 4.1 and the anim module's curves define it). Strokes whose point counts
// differ between keys are first resampled by arc length to a common count so that the points
// correspond (Parent 4.1, arc length; here the exact length of the polyline).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include "morph_2d_internal.h"
#include "vdg/anim/curve.h"
#include "vdg/geom/error.h"
#include "vdg/geom/text.h"
#include "vdg/morph/inbetween.h"

namespace vdg::morph {
Polyline resampleByArcLength(std::span<const Eigen::Vector2d> polyline, int count) {
  if (polyline.size() < 2)
    throw Error("resample by arc length: the polyline has " + std::to_string(polyline.size()) +
                " point(s); it needs at least 2");
  if (count < 2) throw Error("resample by arc length: count " + std::to_string(count) + " is below 2");
  for (std::size_t i = 0; i < polyline.size(); ++i)
    if (!polyline[i].allFinite()) throw Error("resample by arc length: point " + std::to_string(i) + " is not finite");
  // Accumulated chord lengths s_0 = 0, s_i = s_{i-1} + |P_i - P_{i-1}| (the polyline's arc length).
  std::vector<double> s(polyline.size(), 0.0);
  for (std::size_t i = 1; i < polyline.size(); ++i) s[i] = s[i - 1] + (polyline[i] - polyline[i - 1]).norm();
  const double total = s.back();
  Polyline out(static_cast<std::size_t>(count));
  out.front() = polyline.front();
  out.back() = polyline.back();
  if (!(total > 0)) {  // every point the same: nothing to space out
    std::fill(out.begin(), out.end(), polyline.front());
    return out;
  }
  std::size_t segment = 1;  // s[segment - 1] <= target <= s[segment]
  for (int k = 1; k + 1 < count; ++k) {
    const double target = total * k / (count - 1);
    while (segment + 1 < s.size() && s[segment] < target) ++segment;
    const double length = s[segment] - s[segment - 1];
    const double f = length > 0 ? std::clamp((target - s[segment - 1]) / length, 0.0, 1.0) : 0.0;
    out[static_cast<std::size_t>(k)] = polyline[segment - 1] + f * (polyline[segment] - polyline[segment - 1]);
  }
  return out;
}

Inbetweener::Inbetweener(std::vector<KeyDrawing> keys, InbetweenCurve curve) : keys_(std::move(keys)), curve_(curve) {
  if (keys_.empty()) throw Error("inbetween: no key drawings (at least one is needed)");
  const std::size_t strokes = keys_.front().strokes.size();
  for (std::size_t k = 0; k < keys_.size(); ++k) {
    const KeyDrawing& key = keys_[k];
    const std::string where = "inbetween: key " + std::to_string(k);
    if (!std::isfinite(key.time)) throw Error(where + ": the time is not finite");
    if (k > 0 && !(key.time > keys_[k - 1].time))
      throw Error(where + ": time " + numberText(key.time, 10) + " is not after key " + std::to_string(k - 1) +
                  "'s time " + numberText(keys_[k - 1].time, 10) + " (key times must increase strictly)");
    if (k > 0 && !anim::isUsableTimeSpan(key.time - keys_[k - 1].time))
      throw Error(where + ": the span from key " + std::to_string(k - 1) + "'s time " +
                  numberText(keys_[k - 1].time, 10) + " to " + numberText(key.time, 10) + " is too small or too large");
    if (key.strokes.size() != strokes)
      throw Error(where + ": has " + std::to_string(key.strokes.size()) + " strokes but key 0 has " +
                  std::to_string(strokes) + " (stroke i of every key corresponds)");
    for (std::size_t s = 0; s < key.strokes.size(); ++s) {
      const Polyline& stroke = key.strokes[s];
      if (stroke.size() < 2)
        throw Error(where + ", stroke " + std::to_string(s) + ": has " + std::to_string(stroke.size()) +
                    " point(s); a stroke needs at least 2");
      for (std::size_t p = 0; p < stroke.size(); ++p)
        if (!stroke[p].allFinite())
          throw Error(where + ", stroke " + std::to_string(s) + ", point " + std::to_string(p) + ": not finite");
    }
  }
  const double total = inbetweenPointCount(keys_);
  if (total > kMaxInbetweenPoints)
    throw Error("inbetween: the keys would hold " + numberText(total, 3) +
                " points once every stroke is resampled to "
                "its largest point count (" +
                std::to_string(keys_.size()) + " keys), more than " + numberText(kMaxInbetweenPoints, 3) +
                "; give fewer keys or fewer points per stroke");
  // A stroke keeps its points where a key already has the largest count (the drawn correspondence);
  // other keys' versions of it are resampled by arc length to that count.
  for (std::size_t s = 0; s < strokes; ++s) {
    std::size_t count = 0;
    for (const KeyDrawing& key : keys_) count = std::max(count, key.strokes[s].size());
    for (KeyDrawing& key : keys_)
      if (key.strokes[s].size() != count) key.strokes[s] = resampleByArcLength(key.strokes[s], static_cast<int>(count));
  }
}

std::vector<Polyline> Inbetweener::at(double time) const {
  if (!std::isfinite(time)) throw Error("inbetween: time " + numberText(time, 10) + " is not finite");
  std::vector<double> times;
  times.reserve(keys_.size());
  for (const KeyDrawing& key : keys_) times.push_back(key.time);
  // Parent 4.5: every coordinate of every point interpolated over the key times (weights shared by
  // all points; see detail::keyWeights for the Catmull-Rom form). Exact at the keys, clamped outside.
  const detail::KeyWeights w = detail::keyWeights(times, time, curve_ == InbetweenCurve::kCatmullRom);
  std::vector<Polyline> out(keys_.front().strokes.size());
  for (std::size_t s = 0; s < out.size(); ++s) {
    const std::size_t points = keys_.front().strokes[s].size();
    out[s].assign(points, Eigen::Vector2d::Zero());
    for (std::size_t p = 0; p < points; ++p) {
      Eigen::Vector2d v = w.weight[0] * keys_[static_cast<std::size_t>(w.index[0])].strokes[s][p];
      for (int k = 1; k < w.count; ++k) v += w.weight[k] * keys_[static_cast<std::size_t>(w.index[k])].strokes[s][p];
      out[s][p] = v;
    }
  }
  return out;
}

double inbetweenPointCount(std::span<const KeyDrawing> keys) {
  if (keys.empty()) return 0;
  double total = 0;
  for (std::size_t s = 0; s < keys.front().strokes.size(); ++s) {
    std::size_t count = 0;
    for (const KeyDrawing& key : keys)
      if (s < key.strokes.size()) count = std::max(count, key.strokes[s].size());
    total += static_cast<double>(count);
  }
  return total * static_cast<double>(keys.size());
}

double inbetweenFrameCost(std::span<const KeyDrawing> keys, int raster_width, int raster_height) {
  if (keys.empty()) return 0;
  const double points = inbetweenPointCount(keys) / static_cast<double>(keys.size());
  if (raster_width <= 0 || raster_height <= 0) return points;
  constexpr double kPad = 3;  // the stroke's width, the anti-aliasing pixel and rounding, each side
  const double canvas = static_cast<double>(raster_width) * static_cast<double>(raster_height);
  double cost = points + canvas;
  for (std::size_t s = 0; s < keys.front().strokes.size(); ++s) {
    std::size_t count = SIZE_MAX;
    for (const KeyDrawing& key : keys) count = std::min(count, s < key.strokes.size() ? key.strokes[s].size() : 0);
    for (std::size_t p = 0; p + 1 < count; ++p) {
      // A linear inbetween of a segment is no longer than its longest key (the norm is convex).
      double dx = 0, dy = 0;
      for (const KeyDrawing& key : keys) {
        const Eigen::Vector2d d = (key.strokes[s][p + 1] - key.strokes[s][p]).cwiseAbs();
        dx = std::max(dx, d.x()), dy = std::max(dy, d.y());
      }
      cost += std::min((std::min(dx, 1e9) + 2 * kPad) * (std::min(dy, 1e9) + 2 * kPad), canvas);
    }
  }
  return cost;
}

}  // namespace vdg::morph
