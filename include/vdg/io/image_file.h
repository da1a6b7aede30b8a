// Image files vdg reads: PNG and JPEG only (textures, the renderer's golden images), decoded to
// RGBA8 with bounded file size and pixel count, so a hostile file can neither exhaust memory nor
// reach a decoder vdg does not need.
//
// The format is told by the file's first bytes (its magic number), never by its name: PNG starts
// 89 50 4E 47 0D 0A 1A 0A, JPEG FF D8 FF. Anything else is refused before any decoder runs.
// Decoding is stb_image's (Debian libstb-dev's header, compiled into vdg_io with only its PNG and
// JPEG decoders); the size in the file's header is checked before the pixels are allocated.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

#include "vdg/geom/material.h"

namespace vdg {

// Default limits: an image file of at most 128 MiB, at most 16384 pixels a side and at most 2^26
// pixels (8192 x 8192; 256 MiB of RGBA8).
inline constexpr std::size_t kMaxImageFileBytes = std::size_t{128} << 20;
inline constexpr int kMaxImageSide = 16384;
inline constexpr std::size_t kMaxImagePixels = std::size_t{1} << 26;

struct ImageLimits {
  std::size_t max_file_bytes = kMaxImageFileBytes;
  int max_side = kMaxImageSide;              // width and height each in [1, max_side]
  std::size_t max_pixels = kMaxImagePixels;  // width * height
};

enum class ImageFormat { kUnknown, kPng, kJpeg };

// The format `bytes` start with (kUnknown for anything but PNG and JPEG, and for too few bytes).
ImageFormat imageFormatOf(std::string_view bytes);
// "PNG", "JPEG", "unknown".
const char* imageFormatName(ImageFormat format);

// Decodes PNG or JPEG bytes into RGBA8, top row first (any channel count is converted: grey gives
// R = G = B, no alpha gives A = 255). `source` names the bytes in messages. Throws vdg::Error
// "SOURCE: ..." for bytes that are neither PNG nor JPEG, more than limits.max_file_bytes, a size
// outside the limits, or a file the decoder refuses (with its reason: "SOURCE: cannot decode the
// PNG (bad zlib header)").
TextureImage decodeImage(std::string_view bytes, const std::string& source, const ImageLimits& limits = {});

// Reads a regular file (vdg/io/read_file.h: no FIFOs, devices or folders) of at most
// limits.max_file_bytes and decodes it. `what` names the kind of file in messages ("texture").
// Throws vdg::Error "PATH: ..." as readFileLimited and decodeImage do.
TextureImage readImageFile(const std::string& path, const std::string& what = "image", const ImageLimits& limits = {});

// Encodes RGBA8 pixels (top row first) as a PNG file in memory (stb_image_write's encoder; exports
// of textures that have no file of their own). Throws vdg::Error "SOURCE: ..." for an image with no
// pixels or a buffer that does not match its size.
std::string encodePng(const TextureImage& image, const std::string& source);

}  // namespace vdg
