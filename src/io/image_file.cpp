// PNG and JPEG decoding with limits (vdg/io/image_file.h).
//
// The only translation unit with stb_image's implementation in vdg's libraries: static (no symbol
// clashes with a libstb that an application links for other parts of stb), PNG and JPEG decoders
// only, no stdio (bytes come through vdg's bounded file reader). stb_image's own bound on a side
// (2^24) stays, so that stbi_info reports a large size and vdg's message names it.
#define STB_IMAGE_STATIC
#define STB_IMAGE_IMPLEMENTATION
#define STBI_ONLY_PNG
#define STBI_ONLY_JPEG
#define STBI_NO_STDIO
// The PNG encoder of exports (encodePng), static and without stdio the same way.
#define STB_IMAGE_WRITE_STATIC
#define STB_IMAGE_WRITE_IMPLEMENTATION
#define STBI_WRITE_NO_STDIO
#include "vdg/io/image_file.h"

#include <stb/stb_image.h>
#include <stb/stb_image_write.h>

#include <algorithm>
#include <climits>
#include <cstring>
#include <memory>

#include "vdg/geom/error.h"
#include "vdg/io/read_file.h"

namespace vdg {

ImageFormat imageFormatOf(std::string_view bytes) {
  static constexpr unsigned char kPng[8] = {0x89, 'P', 'N', 'G', 0x0D, 0x0A, 0x1A, 0x0A};
  static constexpr unsigned char kJpeg[3] = {0xFF, 0xD8, 0xFF};
  if (bytes.size() >= sizeof(kPng) && std::memcmp(bytes.data(), kPng, sizeof(kPng)) == 0) return ImageFormat::kPng;
  if (bytes.size() >= sizeof(kJpeg) && std::memcmp(bytes.data(), kJpeg, sizeof(kJpeg)) == 0) return ImageFormat::kJpeg;
  return ImageFormat::kUnknown;
}

const char* imageFormatName(ImageFormat format) {
  switch (format) {
    case ImageFormat::kPng:
      return "PNG";
    case ImageFormat::kJpeg:
      return "JPEG";
    default:
      return "unknown";
  }
}

TextureImage decodeImage(std::string_view bytes, const std::string& source, const ImageLimits& limits) {
  const ImageFormat format = imageFormatOf(bytes);
  if (format == ImageFormat::kUnknown) throw Error(source + ": not a PNG or JPEG file (vdg reads only those)");
  if (bytes.size() > limits.max_file_bytes || bytes.size() > static_cast<std::size_t>(INT_MAX))
    throw Error(source + ": image is " + std::to_string(bytes.size()) + " bytes, more than the limit of " +
                std::to_string(limits.max_file_bytes));
  const auto* data = reinterpret_cast<const stbi_uc*>(bytes.data());
  const int length = static_cast<int>(bytes.size());
  const std::string kind = imageFormatName(format);
  int w = 0, h = 0, channels = 0;
  if (!stbi_info_from_memory(data, length, &w, &h, &channels)) {
    const char* reason = stbi_failure_reason();
    throw Error(source + ": cannot read the " + kind + " header (" + (reason ? reason : "unknown reason") + ")");
  }
  const int max_side = std::min(limits.max_side, kMaxImageSide);
  if (w < 1 || h < 1 || w > max_side || h > max_side)
    throw Error(source + ": " + std::to_string(w) + "x" + std::to_string(h) + " pixels, outside 1 to " +
                std::to_string(max_side) + " a side");
  if (static_cast<std::size_t>(w) * static_cast<std::size_t>(h) > limits.max_pixels)
    throw Error(source + ": " + std::to_string(w) + "x" + std::to_string(h) + " pixels, more than the limit of " +
                std::to_string(limits.max_pixels) + " pixels");
  std::unique_ptr<stbi_uc, void (*)(void*)> pixels(stbi_load_from_memory(data, length, &w, &h, &channels, 4),
                                                   stbi_image_free);
  if (!pixels) {
    const char* reason = stbi_failure_reason();
    throw Error(source + ": cannot decode the " + kind + " (" + (reason ? reason : "unknown reason") + ")");
  }
  TextureImage image;
  image.width = w;
  image.height = h;
  image.rgba.assign(pixels.get(), pixels.get() + static_cast<std::size_t>(w) * static_cast<std::size_t>(h) * 4);
  return image;
}

TextureImage readImageFile(const std::string& path, const std::string& what, const ImageLimits& limits) {
  return decodeImage(readFileLimited(path, what, limits.max_file_bytes), path, limits);
}

std::string encodePng(const TextureImage& image, const std::string& source) {
  if (image.width < 1 || image.height < 1 ||
      image.rgba.size() != static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height) * 4)
    throw Error(source + ": the image has no pixels or a wrong buffer size");
  std::string png;
  const auto append = [](void* context, void* data, int size) {
    static_cast<std::string*>(context)->append(static_cast<const char*>(data), static_cast<std::size_t>(size));
  };
  if (!stbi_write_png_to_func(append, &png, image.width, image.height, 4, image.rgba.data(), image.width * 4))
    throw Error(source + ": cannot encode the image as PNG");
  return png;
}

}  // namespace vdg
