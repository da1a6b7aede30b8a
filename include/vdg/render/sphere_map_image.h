// The "where to key next" map as a picture (vdg info --sphere-map; docs/where-to-key.md): the need
// score of vdg/viewdep/sphere_map.h as an equirectangular heat map with the keys and the suggested
// view marked and a colour-scale legend below. No OpenGL: plain pixels.
#pragma once

#include <array>
#include <cstdint>

#include "vdg/render/image.h"
#include "vdg/viewdep/sphere_map.h"

namespace vdg::render {

// The heat colour of a value in [0, 1] (clamped; NaN as 0): a ramp through dark blue (0), purple
// (0.25), red (0.5), orange (0.75) to pale yellow (1), brighter as the value grows so that it
// reads in grey too. RGB, 0..255.
std::array<std::uint8_t, 3> heatColour(double value);

// Legend strip height below the map, in pixels.
inline constexpr int kSphereMapLegendHeight = 30;

// map.width x (map.height + kSphereMapLegendHeight) pixels, opaque. The map: one pixel per cell,
// coloured by heatColour(need), a faint graticule every 30 degrees (the equator and longitude 0 a
// little stronger); each key view a white dot with a black rim (radius ~ width / 180, at least 2
// pixels); the suggested view a cyan ring with a cross. The legend: the colour bar from need 0
// (left) to 1 (right) with ticks and labels at 0, 0.5 and 1 (digits drawn from a built-in 3x5 font).
Image sphereMapImage(const SphereMap& map);

}  // namespace vdg::render
