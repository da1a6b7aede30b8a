#include "vdg/render/image.h"

#include <stb/stb_image.h>
#include <stb/stb_image_write.h>

#include <algorithm>
#include <cstdlib>
#include <memory>

#include "vdg/geom/error.h"
#include "vdg/io/atomic_file.h"
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
  checkInputFile(path, "PNG image");  // a FIFO or a device would block or never end
  int w = 0, h = 0, channels = 0;
  if (stbi_info(path.c_str(), &w, &h, &channels) && (w > kMaxImageSize || h > kMaxImageSize))
    throw Error("PNG " + path + ": " + std::to_string(w) + "x" + std::to_string(h) + " pixels, more than " +
                std::to_string(kMaxImageSize) + " a side");
  std::unique_ptr<stbi_uc, void (*)(void*)> data(stbi_load(path.c_str(), &w, &h, &channels, 4), stbi_image_free);
  if (!data) {
    const char* reason = stbi_failure_reason();
    throw Error("PNG " + path + ": cannot read (" + (reason ? reason : "unknown reason") + ")");
  }
  Image out;
  out.width = w;
  out.height = h;
  out.rgba.assign(data.get(), data.get() + static_cast<std::size_t>(w) * h * 4);
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
