// RGBA float images for the 2D morphs (vdg/morph/image_morph.h): conversion from and to 8-bit,
// the cross-dissolve of Parent 4.10 ("A cross dissolve is then performed on a pixel-by-pixel basis
// between the two warped images"), and the plain bilinear resample the benchmark compares against.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <string>

#include "morph_2d_internal.h"
#include "vdg/geom/error.h"
#include "vdg/morph/image_morph.h"

namespace vdg::morph {

void validateImage(const Image& image, const std::string& what) {
  if (image.width < 1 || image.height < 1)
    throw Error(what + ": the image is " + std::to_string(image.width) + " x " + std::to_string(image.height) +
                " pixels; it needs at least 1 x 1");
  const std::size_t expected = static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height) * 4;
  if (image.rgba.size() != expected)
    throw Error(what + ": the image is " + std::to_string(image.width) + " x " + std::to_string(image.height) +
                " pixels but holds " + std::to_string(image.rgba.size()) + " floats, not " + std::to_string(expected));
}

Image imageFromRgba8(const TextureImage& image) {
  if (image.width < 1 || image.height < 1 ||
      image.rgba.size() != static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height) * 4)
    throw Error("image: " + std::to_string(image.width) + " x " + std::to_string(image.height) + " pixels with " +
                std::to_string(image.rgba.size()) + " bytes is not an RGBA8 image");
  Image out{.width = image.width, .height = image.height, .rgba = std::vector<float>(image.rgba.size())};
  for (std::size_t i = 0; i < image.rgba.size(); ++i) out.rgba[i] = static_cast<float>(image.rgba[i]) / 255.0f;
  return out;
}

TextureImage imageToRgba8(const Image& image) {
  validateImage(image, "image");
  TextureImage out;
  out.width = image.width;
  out.height = image.height;
  out.rgba.resize(image.rgba.size());
  for (std::size_t i = 0; i < image.rgba.size(); ++i) {
    const float v = image.rgba[i];
    // NaN counts as 0; otherwise rounded to nearest and clamped to [0, 255].
    const float scaled = std::isnan(v) ? 0.0f : std::clamp(v, 0.0f, 1.0f) * 255.0f;
    out.rgba[i] = static_cast<std::uint8_t>(std::lround(scaled));
  }
  return out;
}

Image crossDissolve(const Image& a, const Image& b, double t) {
  validateImage(a, "cross-dissolve: first image");
  validateImage(b, "cross-dissolve: second image");
  if (a.width != b.width || a.height != b.height)
    throw Error("cross-dissolve: the images differ in size (" + std::to_string(a.width) + " x " +
                std::to_string(a.height) + " and " + std::to_string(b.width) + " x " + std::to_string(b.height) + ")");
  if (!std::isfinite(t)) throw Error("cross-dissolve: t is not finite");
  Image out{.width = a.width, .height = a.height, .rgba = std::vector<float>(a.rgba.size())};
  // Parent 4.10: colour = (1 - t) a + t b per channel; at t = 0 exactly a, at t = 1 exactly b.
  const double s = 1.0 - t;
  for (std::size_t i = 0; i < a.rgba.size(); ++i)
    out.rgba[i] = static_cast<float>(s * static_cast<double>(a.rgba[i]) + t * static_cast<double>(b.rgba[i]));
  return out;
}

Image resampleBilinear(const Image& image, int width, int height) {
  validateImage(image, "resample");
  if (width < 1 || height < 1)
    throw Error("resample: the output size " + std::to_string(width) + " x " + std::to_string(height) +
                " needs at least 1 x 1 pixels");
  Image out{.width = width,
            .height = height,
            .rgba = std::vector<float>(static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 4)};
  // Output pixel centre (x + 0.5, y + 0.5) corresponds to the source position scaled by W / w
  // (pixel centres at +0.5; the image rectangles [0, W] and [0, w] map onto each other).
  const double sx = static_cast<double>(image.width) / width, sy = static_cast<double>(image.height) / height;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) detail::sampleBilinear(image, (x + 0.5) * sx, (y + 0.5) * sy, out.pixel(x, y));
  return out;
}

}  // namespace vdg::morph
