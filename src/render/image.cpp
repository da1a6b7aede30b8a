#include "vdg/render/image.h"

#include <stb/stb_image_write.h>

#include <algorithm>
#include <cstdlib>
#include <memory>
#include <utility>

#include "vdg/geom/error.h"
#include "vdg/io/atomic_file.h"
#include "vdg/io/image_file.h"
#include "vdg/io/read_file.h"
#include "vdg/render/renderer.h"

namespace vdg::render {

void writePng(const std::string& path, const Image& image) {
  if (image.width <= 0 || image.height <= 0 ||
      image.rgba.size() != static_cast<std::size_t>(image.width) * image.height * 4)
    throw Error("PNG " + path + ": image has no pixels or a wrong buffer size");
  // Encoded in memory, then written through the atomic writer, which checks every write: a full
  // disk is an error naming the file, never a truncated PNG in place of a good one.
  std::string png;
  const auto append = [](void* context, void* data, int size) {
    static_cast<std::string*>(context)->append(static_cast<const char*>(data), static_cast<std::size_t>(size));
  };
  if (!stbi_write_png_to_func(append, &png, image.width, image.height, 4, image.rgba.data(), image.width * 4))
    throw Error("PNG " + path + ": cannot encode the image");
  writeFileAtomically(path, png);
}

Image readPng(const std::string& path) {
  // One decoder in the link: vdg_io's (PNG and JPEG by their first bytes, bounded file and pixels).
  ImageLimits limits;
  limits.max_file_bytes = kMaxMeshFileBytes;
  limits.max_side = kMaxImageSize;
  limits.max_pixels = static_cast<std::size_t>(kMaxImageSize) * kMaxImageSize;
  const std::string bytes = [&] {
    try {
      return readFileLimited(path, "PNG image", limits.max_file_bytes);  // a FIFO or a device would block
    } catch (const Error& e) {
      throw Error(std::string("PNG ") + e.what());
    }
  }();
  if (imageFormatOf(bytes) != ImageFormat::kPng) throw Error("PNG " + path + ": not a PNG file");
  TextureImage decoded;
  try {
    decoded = decodeImage(bytes, path, limits);
  } catch (const Error& e) {
    throw Error(std::string("PNG ") + e.what());
  }
  Image out;
  out.width = decoded.width;
  out.height = decoded.height;
  out.rgba = std::move(decoded.rgba);
  return out;
}

ImageDiff compareImages(const Image& a, const Image& b, int channel_tolerance) {
  ImageDiff d;
  if (a.width != b.width || a.height != b.height || a.rgba.size() != b.rgba.size()) return d;
  d.same_size = true;
  d.max_channel_difference = 0;
  const std::size_t pixels = a.rgba.size() / 4;
  for (std::size_t i = 0; i < pixels; ++i) {
    int worst = 0;
    for (int c = 0; c < 4; ++c) worst = std::max(worst, std::abs(int(a.rgba[i * 4 + c]) - int(b.rgba[i * 4 + c])));
    d.max_channel_difference = std::max(d.max_channel_difference, worst);
    if (worst > channel_tolerance) ++d.differing_pixels;
  }
  d.differing_fraction = pixels ? static_cast<double>(d.differing_pixels) / static_cast<double>(pixels) : 0.0;
  return d;
}

}  // namespace vdg::render
