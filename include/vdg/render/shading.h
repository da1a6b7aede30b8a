// NPR shading of Rademacher 99, section 3.2.4: a strong ambient term plus a warm and a cool light
// on opposite sides of the surface,
//   C = ka*Cbase + (l1.n)(Cwarm - Cbase*k1)*k2 + (l2.n)(Ccool - Cbase*k3)*k4,
// with k1..k4 varied by the hue of Cbase (warm light off for neutral surfaces, stronger cool light
// for purples, more cool and less warm for reds) and faded out on dark surfaces.
//
// Negative l.n: each light term is clamped at l.n = 0, as OpenGL's fixed-function diffuse term
// max(0, l.n) does (the paper implements the two terms as the diffuse parts of two GL lights).
// The final colour is clamped to [0, 1] per channel, as the framebuffer does.
//
// Light directions are unit vectors in *camera* space (x right, y up, z towards the viewer),
// pointing from the surface towards the light: the lights move with the camera, so every frame
// of a turntable is lit the same way.
#pragma once

#include <array>

namespace vdg::render {

using Rgb = std::array<float, 3>;  // linear colour, each channel in [0, 1]

// The four hue-dependent constants of the lighting equation.
struct ShadingConstants {
  float k1 = 1.0f, k2 = 1.0f, k3 = 1.0f, k4 = 1.0f;
};

struct ShadingParams {
  float ka = 0.9f;                                        // ambient share of the base colour (paper: 0.9)
  ShadingConstants k;                                     // k1..k4 before the hue rule (paper: 1.0)
  bool vary_by_hue = true;                                // apply hueAdjustedConstants() to k for each surface
  Rgb warm{1.0f, 0.8f, 0.5f};                             // Cwarm (orange)
  Rgb cool{0.55f, 0.62f, 0.85f};                          // Ccool (soft blue: cool whites stay light)
  std::array<float, 3> light_warm{-0.6f, 0.6f, 0.5f};     // l1, camera space, towards the light
  std::array<float, 3> light_cool{0.75f, -0.35f, 0.35f};  // l2, the other side of the surface
};

// Hue and saturation/value classification used by the hue rule (HSV, hue in degrees [0, 360)).
struct Hsv {
  float h = 0, s = 0, v = 0;
};
Hsv toHsv(const Rgb& c);

// The paper's per-surface variation of k1..k4 by the colour of Cbase (section 3.2.4: "we disable
// the warm (orange) light when rendering white-ish surfaces ... purple ... red ... There are many
// other hues that can be handled"), applied to the caller's constants `k` (a pure function). First
// by hue:
//   neutral (saturation < 0.2: whites, greys, blacks): k2 = 0   (no warm light: cool whites/greys)
//   purple  (hue in [250, 330), saturation >= 0.2):    k4 = 2 * k4   (intensified cool light),
//                                                      k2 = 0.25 * k2 (vdg: the warm light alone
//                                                      turned purples orange; see docs/render.md)
//   red     (hue < 20 or >= 330, saturation >= 0.2):   k4 = 1.5 * k4, k2 = 0.5 * k2
//                                                      (more cool, less warm: brilliant reds)
//   any other hue: unchanged;
// then by value, for every hue:
//   dark    (value < 0.5): k2 and k4 times t = max(0, (value - 0.2) / 0.3), so that the lights'
//           own colours fade out on dark surfaces and vanish at value <= 0.2 (black stays black).
// A colour of value >= 0.5 and saturation >= 0.2 gets exactly what the paper's rule gives (for
// purples, with the quarter warm light).
inline constexpr float kNeutralSaturation = 0.2f;  // below: no dominant hue
inline constexpr float kDarkValue = 0.2f;          // at or below: no light colour at all
inline constexpr float kLitValue = 0.5f;           // at or above: the lights at full strength
ShadingConstants hueAdjustedConstants(const ShadingConstants& k, const Rgb& base);

// The constants actually used for a surface of colour `base`.
inline ShadingConstants effectiveConstants(const ShadingParams& p, const Rgb& base) {
  return p.vary_by_hue ? hueAdjustedConstants(p.k, base) : p.k;
}

// The lighting equation on the CPU, for one unit normal in camera space (the shader computes the
// same expression; tests use this as the reference). Clamps l.n at 0 and the result to [0, 1].
Rgb shade(const ShadingParams& p, const Rgb& base, const std::array<float, 3>& normal);

}  // namespace vdg::render
