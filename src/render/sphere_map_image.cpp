// The sphere map as an image (vdg/render/sphere_map_image.h).
#include "vdg/render/sphere_map_image.h"

#include <algorithm>
#include <cmath>
#include <string_view>

namespace vdg::render {
namespace {

using Rgb8 = std::array<std::uint8_t, 3>;

void put(Image& img, int x, int y, const Rgb8& c) {
  if (x < 0 || y < 0 || x >= img.width || y >= img.height) return;
  std::uint8_t* p = img.pixel(x, y);
  p[0] = c[0];
  p[1] = c[1];
  p[2] = c[2];
  p[3] = 255;
}

// Blends `c` over the pixel with opacity `a`.
void blend(Image& img, int x, int y, const Rgb8& c, double a) {
  if (x < 0 || y < 0 || x >= img.width || y >= img.height) return;
  std::uint8_t* p = img.pixel(x, y);
  for (int k = 0; k < 3; ++k) p[k] = static_cast<std::uint8_t>(std::lround(p[k] * (1 - a) + c[k] * a));
}

void disc(Image& img, int cx, int cy, double r, const Rgb8& c) {
  const int n = static_cast<int>(std::ceil(r));
  for (int dy = -n; dy <= n; ++dy)
    for (int dx = -n; dx <= n; ++dx)
      if (dx * dx + dy * dy <= r * r) put(img, cx + dx, cy + dy, c);
}

void ring(Image& img, int cx, int cy, double r, double width, const Rgb8& c) {
  const int n = static_cast<int>(std::ceil(r + width));
  for (int dy = -n; dy <= n; ++dy)
    for (int dx = -n; dx <= n; ++dx) {
      const double d = std::hypot(dx, dy);
      if (std::abs(d - r) <= width / 2) put(img, cx + dx, cy + dy, c);
    }
}

// 3x5 digits and the point, one row of 3 bits per byte (top row first).
constexpr std::array<std::array<std::uint8_t, 5>, 11> kGlyphs{{
    {7, 5, 5, 5, 7},
    {2, 6, 2, 2, 7},
    {7, 1, 7, 4, 7},
    {7, 1, 7, 1, 7},
    {5, 5, 7, 1, 1},
    {7, 4, 7, 1, 7},
    {7, 4, 7, 5, 7},
    {7, 1, 1, 1, 1},
    {7, 5, 7, 5, 7},
    {7, 5, 7, 1, 7},
    {0, 0, 0, 0, 2},
}};

// Draws `text` (digits and '.') with its top-left corner at (x, y), `scale` pixels per font pixel.
void text(Image& img, int x, int y, std::string_view s, int scale, const Rgb8& c) {
  for (char ch : s) {
    const int g = ch == '.' ? 10 : ch - '0';
    if (g < 0 || g > 10) continue;
    for (int row = 0; row < 5; ++row)
      for (int col = 0; col < 3; ++col)
        if (kGlyphs[g][row] & (4 >> col))
          for (int sy = 0; sy < scale; ++sy)
            for (int sx = 0; sx < scale; ++sx) put(img, x + col * scale + sx, y + row * scale + sy, c);
    x += 4 * scale;
  }
}

// Pixel of a unit direction on the map.
void pixelOf(const SphereMap& map, const Eigen::Vector3d& d, int& x, int& y) {
  const int cell = map.cellOf(d);
  x = cell % map.width;
  y = cell / map.width;
}

void drawGraticule(const SphereMap& map, Image& img) {
  const Rgb8 white{255, 255, 255};
  for (int deg = -150; deg <= 180; deg += 30) {
    const int x = static_cast<int>(std::lround((deg + 180.0) / 360.0 * map.width));
    for (int y = 0; y < map.height; ++y) blend(img, std::min(x, map.width - 1), y, white, deg == 0 ? 0.45 : 0.18);
  }
  for (int deg = -60; deg <= 60; deg += 30) {
    const int y = static_cast<int>(std::lround((90.0 - deg) / 180.0 * map.height));
    for (int x = 0; x < map.width; ++x) blend(img, x, std::min(y, map.height - 1), white, deg == 0 ? 0.45 : 0.18);
  }
}

void drawLegend(const SphereMap& map, Image& img) {
  const Rgb8 background{240, 240, 240}, ink{20, 20, 20};
  for (int y = map.height; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) put(img, x, y, background);
  const int margin = std::max(8, img.width / 40), bar_top = map.height + 4, bar_bottom = map.height + 14;
  const int x0 = margin, x1 = img.width - 1 - margin;
  for (int x = x0; x <= x1; ++x) {
    const Rgb8 c = heatColour(x1 > x0 ? static_cast<double>(x - x0) / (x1 - x0) : 0.0);
    for (int y = bar_top; y < bar_bottom; ++y) put(img, x, y, c);
  }
  const std::array<std::string_view, 3> labels{"0", "0.5", "1"};
  const int scale = img.width >= 400 ? 2 : 1;  // font pixels

  for (int t = 0; t < 3; ++t) {
    const int x = x0 + (x1 - x0) * t / 2;
    for (int y = bar_bottom; y < bar_bottom + 3; ++y) put(img, x, y, ink);
    const int w = (static_cast<int>(labels[t].size()) * 4 - 1) * scale;
    text(img, std::clamp(x - w / 2, 0, img.width - w), bar_bottom + 4, labels[t], scale, ink);
  }
}

}  // namespace

std::array<std::uint8_t, 3> heatColour(double value) {
  const double v = std::isnan(value) ? 0.0 : std::clamp(value, 0.0, 1.0);
  constexpr std::array<std::array<double, 3>, 5> kStops{{
      {20, 18, 70},
      {110, 30, 140},
      {210, 50, 70},
      {245, 140, 30},
      {252, 245, 170},
  }};
  const double s = v * 4.0;
  const int i = std::min(3, static_cast<int>(s));
  const double f = s - i;
  std::array<std::uint8_t, 3> out{};
  for (int k = 0; k < 3; ++k)
    out[k] = static_cast<std::uint8_t>(std::lround(kStops[i][k] * (1 - f) + kStops[i + 1][k] * f));
  return out;
}

Image sphereMapImage(const SphereMap& map) {
  Image img;
  img.width = map.width;
  img.height = map.height + kSphereMapLegendHeight;
  img.rgba.assign(static_cast<std::size_t>(img.width) * img.height * 4, 255);
  for (int y = 0; y < map.height; ++y)
    for (int x = 0; x < map.width; ++x)
      put(img, x, y, heatColour(map.need[static_cast<std::size_t>(y) * map.width + x]));
  drawGraticule(map, img);
  const double r = std::max(2.0, map.width / 180.0);
  for (const Eigen::Vector3d& k : map.keys) {
    int x = 0, y = 0;
    pixelOf(map, k, x, y);
    for (int wrap : {-map.width, 0, map.width}) {  // a key near longitude +-180 shows on both edges
      disc(img, x + wrap, y, r + 1, {0, 0, 0});
      disc(img, x + wrap, y, r, {255, 255, 255});
    }
  }
  int sx = 0, sy = 0;
  pixelOf(map, map.suggested, sx, sy);
  const Rgb8 cyan{0, 230, 255};
  ring(img, sx, sy, 3 * r, std::max(1.5, r / 2), cyan);
  for (int d = -static_cast<int>(2 * r); d <= static_cast<int>(2 * r); ++d) {
    put(img, sx + d, sy, cyan);
    put(img, sx, sy + d, cyan);
  }
  drawLegend(map, img);
  return img;
}

}  // namespace vdg::render
