// RGBA8 images: what the renderer reads back, PNG output (atomic) and input, and the tolerant
// comparison that golden-image tests use.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace vdg::render {

// Row-major, top row first, 4 bytes per pixel (R, G, B, A), width * height * 4 bytes.
struct Image {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgba;

  const std::uint8_t* pixel(int x, int y) const { return &rgba[(static_cast<std::size_t>(y) * width + x) * 4]; }
  std::uint8_t* pixel(int x, int y) { return &rgba[(static_cast<std::size_t>(y) * width + x) * 4]; }
};

// Writes `image` as a PNG, atomically (temporary file + rename). Throws vdg::Error naming the path.
void writePng(const std::string& path, const Image& image);
// Reads a PNG (any channel count, converted to RGBA8): a regular file of at most kMaxImageSize
// pixels a side (renderer.h), decoded by vdg/io/image_file.h. Throws vdg::Error "PNG PATH: ...".
Image readPng(const std::string& path);

// Comparison of two images of the same size: a pixel differs when any channel differs by more
// than `channel_tolerance` (0..255).
struct ImageDiff {
  bool same_size = false;
  long differing_pixels = 0;
  double differing_fraction = 1.0;  // differing_pixels / pixel count (1 when sizes differ)
  int max_channel_difference = 255;
};
ImageDiff compareImages(const Image& a, const Image& b, int channel_tolerance);

}  // namespace vdg::render
