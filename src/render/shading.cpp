// NPR lighting of Rademacher 99, section 3.2.4 (a variant of Gooch et al. 98):
//   C = ka*Cbase + (l1.n)(Cwarm - Cbase*k1)*k2 + (l2.n)(Ccool - Cbase*k3)*k4
// with k1..k4 varied by the hue of Cbase. The GLSL in shaders.cpp computes the same expression.
#include "vdg/render/shading.h"

#include <algorithm>
#include <cmath>

namespace vdg::render {

Hsv toHsv(const Rgb& c) {
  const float mx = std::max({c[0], c[1], c[2]});
  const float mn = std::min({c[0], c[1], c[2]});
  const float delta = mx - mn;
  Hsv out;
  out.v = mx;
  out.s = mx > 0.0f ? delta / mx : 0.0f;
  if (delta <= 0.0f) return out;
  float h;
  if (mx == c[0]) {
    h = 60.0f * std::fmod((c[1] - c[2]) / delta, 6.0f);
  } else if (mx == c[1]) {
    h = 60.0f * ((c[2] - c[0]) / delta + 2.0f);
  } else {
    h = 60.0f * ((c[0] - c[1]) / delta + 4.0f);
  }
  if (h < 0.0f) h += 360.0f;
  out.h = h;
  return out;
}

ShadingConstants hueAdjustedConstants(const ShadingConstants& k, const Rgb& base) {
  const Hsv hsv = toHsv(base);
  ShadingConstants out = k;
  if (hsv.s < kNeutralSaturation) {
    // Neutral colours (whites, greys, blacks): the paper's whites, "warm light off: soft, cool
    // whites", extended to every grey, which the orange light would otherwise turn beige.
    out.k2 = 0.0f;
  } else if (hsv.h >= 250.0f && hsv.h < 330.0f) {
    // Purples: intensified cool light (the paper), and a quarter of the warm light: at l1.n = 1
    // the warm term leaves Cwarm - 0.1 Cbase whatever the base, which turned purples orange.
    out.k4 = 2.0f * k.k4;
    out.k2 = 0.25f * k.k2;
  } else if (hsv.h < 20.0f || hsv.h >= 330.0f) {  // reds: more cool, less warm
    out.k4 = 1.5f * k.k4;
    out.k2 = 0.5f * k.k2;
  }
  if (hsv.v < kLitValue) {
    // Dark colours, any hue: the two lights add their own colours (Cwarm k2, Ccool k4), which
    // swamp a dark base (black would turn orange and blue). Their strength fades with the value,
    // to nothing at kDarkValue and below, so dark stays dark (ka Cbase).
    const float t = std::max(0.0f, (hsv.v - kDarkValue) / (kLitValue - kDarkValue));
    out.k2 *= t;
    out.k4 *= t;
  }
  return out;
}

Rgb shade(const ShadingParams& p, const Rgb& base, const std::array<float, 3>& normal) {
  const ShadingConstants k = effectiveConstants(p, base);
  auto dot = [&](const std::array<float, 3>& l) {
    const float len = std::sqrt(l[0] * l[0] + l[1] * l[1] + l[2] * l[2]);
    const float d = (l[0] * normal[0] + l[1] * normal[1] + l[2] * normal[2]) / len;
    return std::max(0.0f, d);  // clamped like OpenGL's diffuse max(0, l.n)
  };
  const float d1 = dot(p.light_warm), d2 = dot(p.light_cool);
  Rgb c;
  for (int i = 0; i < 3; ++i) {
    const float value =
        p.ka * base[i] + d1 * (p.warm[i] - base[i] * k.k1) * k.k2 + d2 * (p.cool[i] - base[i] * k.k3) * k.k4;
    c[i] = std::clamp(value, 0.0f, 1.0f);
  }
  return c;
}

}  // namespace vdg::render
