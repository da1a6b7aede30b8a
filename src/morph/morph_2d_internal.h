// Helpers shared by the 2D morphing files (image.cpp, inbetween.cpp, mesh_warp.cpp,
// feature_morph.cpp); internal to vdg_morph.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <span>
#include <string>

#include "vdg/morph/image_morph.h"

namespace vdg::morph::detail {

// Bilinear sample of `image` at the continuous pixel position (x, y) (pixel (i, j) has its centre
// at (i + 0.5, j + 0.5)), positions clamped to the outermost pixel centres, so the border pixels
// extend outwards. At a pixel centre it returns that pixel exactly. Writes 4 floats to `out`.
inline void sampleBilinear(const Image& image, double x, double y, float* out) {
  // NaN (possible only from overflowing inputs) samples the corner pixel rather than casting NaN.
  const double fx = x - 0.5 > 0 ? std::min(x - 0.5, static_cast<double>(image.width - 1)) : 0.0;
  const double fy = y - 0.5 > 0 ? std::min(y - 0.5, static_cast<double>(image.height - 1)) : 0.0;
  const int x0 = static_cast<int>(fx), y0 = static_cast<int>(fy);
  const int x1 = std::min(x0 + 1, image.width - 1), y1 = std::min(y0 + 1, image.height - 1);
  const double ax = fx - x0, ay = fy - y0;
  const float* p00 = image.pixel(x0, y0);
  const float* p10 = image.pixel(x1, y0);
  const float* p01 = image.pixel(x0, y1);
  const float* p11 = image.pixel(x1, y1);
  for (int k = 0; k < 4; ++k) {
    const double top = (1 - ax) * p00[k] + ax * p10[k];
    const double bottom = (1 - ax) * p01[k] + ax * p11[k];
    out[k] = static_cast<float>((1 - ay) * top + ay * bottom);
  }
}

// Interpolation over key times (Parent 4.5 key frames; 4.10 "grids ... interpolated over time ...
// Catmull-Rom"): the value at time t is sum_k weight[k] * P_{index[k]} over at most 4 keys.
// Catmull-Rom is the cubic Hermite form with non-uniform tangents, as the anim module's kCatmullRom
// (vdg/anim/curve.h; Parent 4.1): interior m_i = (P_{i+1} - P_{i-1}) / (t_{i+1} - t_{i-1}), at the
// ends the chord slope of the end segment. On [t_i, t_{i+1}] with h = t_{i+1} - t_i, u = (t - t_i) / h:
//   P(t) = h00(u) P_i + h10(u) h m_i + h01(u) P_{i+1} + h11(u) h m_{i+1}
//   h00 = 2u^3 - 3u^2 + 1, h10 = u^3 - 2u^2 + u, h01 = -2u^3 + 3u^2, h11 = u^3 - u^2.
// t is clamped to [t_0, t_{n-1}]. At a key time the weights are exactly {1 on that key} (u = 0),
// so a key is reproduced bit for bit. `times` strictly increasing, non-empty, t finite.
struct KeyWeights {
  int count = 0;
  int index[4] = {0, 0, 0, 0};
  double weight[4] = {0, 0, 0, 0};
  void add(int i, double w) {
    for (int k = 0; k < count; ++k)
      if (index[k] == i) {
        weight[k] += w;
        return;
      }
    index[count] = i;
    weight[count] = w;
    ++count;
  }
};

inline KeyWeights keyWeights(std::span<const double> times, double t, bool catmull_rom) {
  KeyWeights w;
  const int n = static_cast<int>(times.size());
  if (n == 1 || t <= times.front()) {
    w.add(0, 1.0);
    return w;
  }
  if (t >= times.back()) {
    w.add(n - 1, 1.0);
    return w;
  }
  const int i = static_cast<int>(std::upper_bound(times.begin(), times.end(), t) - times.begin()) - 1;
  const double h = times[i + 1] - times[i];
  const double u = (t - times[i]) / h;
  if (u == 0) {
    w.add(i, 1.0);
    return w;
  }
  if (!catmull_rom) {
    w.add(i, 1 - u);
    w.add(i + 1, u);
    return w;
  }
  const double u2 = u * u, u3 = u2 * u;
  const double h00 = 2 * u3 - 3 * u2 + 1, h10 = u3 - 2 * u2 + u, h01 = -2 * u3 + 3 * u2, h11 = u3 - u2;
  w.add(i, h00);
  w.add(i + 1, h01);
  // m_i as weights of keys: (P_{b} - P_{a}) / (t_b - t_a), a = max(i - 1, 0), b = i + 1.
  auto tangent = [&](int key, double scale) {
    const int a = std::max(key - 1, 0), b = std::min(key + 1, n - 1);
    const double s = scale / (times[b] - times[a]);
    w.add(b, s);
    w.add(a, -s);
  };
  tangent(i, h10 * h);
  tangent(i + 1, h11 * h);
  return w;
}

}  // namespace vdg::morph::detail
