// A minimal PNG writer for tests (PNG specification, ISO/IEC 15948: signature, IHDR, one IDAT of
// stored (uncompressed) deflate blocks, IEND; CRC-32 per chunk, Adler-32 for the zlib stream), so
// that tests make the tiny images they decode instead of committing binary files.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace vdg::testing {

inline std::uint32_t pngCrc(const std::string& bytes) {
  std::uint32_t crc = 0xFFFFFFFFu;
  for (const char ch : bytes) {
    crc ^= static_cast<unsigned char>(ch);
    for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
  }
  return crc ^ 0xFFFFFFFFu;
}

inline void appendBigEndian(std::string& out, std::uint32_t v) {
  for (int s = 24; s >= 0; s -= 8) out += static_cast<char>((v >> s) & 0xFF);
}

inline void appendChunk(std::string& out, const char* type, const std::string& data) {
  appendBigEndian(out, static_cast<std::uint32_t>(data.size()));
  const std::string body = std::string(type, 4) + data;
  out += body;
  appendBigEndian(out, pngCrc(body));
}

// An 8-bit PNG of `channels` 3 (RGB) or 4 (RGBA); `pixels` holds width * height * channels bytes,
// top row first. `claimed_width`/`claimed_height` (when > 0) replace the size written in IHDR,
// for tests of files whose header lies.
inline std::string tinyPng(int width, int height, int channels, const std::vector<std::uint8_t>& pixels,
                           int claimed_width = 0, int claimed_height = 0) {
  std::string png("\x89PNG\r\n\x1a\n", 8);
  std::string ihdr;
  appendBigEndian(ihdr, static_cast<std::uint32_t>(claimed_width > 0 ? claimed_width : width));
  appendBigEndian(ihdr, static_cast<std::uint32_t>(claimed_height > 0 ? claimed_height : height));
  ihdr += static_cast<char>(8);                      // bit depth
  ihdr += static_cast<char>(channels == 4 ? 6 : 2);  // colour type: RGBA or RGB
  ihdr += std::string("\0\0\0", 3);                  // deflate, adaptive filtering, no interlace
  appendChunk(png, "IHDR", ihdr);
  std::string raw;  // each row: filter type 0, then its bytes
  const std::size_t row = static_cast<std::size_t>(width) * static_cast<std::size_t>(channels);
  for (int y = 0; y < height; ++y) {
    raw += '\0';
    raw.append(reinterpret_cast<const char*>(pixels.data()) + static_cast<std::size_t>(y) * row, row);
  }
  std::string z("\x78\x01", 2);  // zlib header: deflate, 32 KiB window, no dictionary
  for (std::size_t at = 0; at < raw.size() || at == 0; at += 65535) {
    const std::size_t n = std::min<std::size_t>(65535, raw.size() - at);
    z += static_cast<char>(at + n >= raw.size() ? 1 : 0);  // BFINAL, BTYPE = stored
    z += static_cast<char>(n & 0xFF);
    z += static_cast<char>(n >> 8);
    z += static_cast<char>(~n & 0xFF);
    z += static_cast<char>((~n >> 8) & 0xFF);
    z.append(raw, at, n);
    if (raw.empty()) break;
  }
  std::uint32_t a = 1, b = 0;
  for (const char ch : raw) {
    a = (a + static_cast<unsigned char>(ch)) % 65521u;
    b = (b + a) % 65521u;
  }
  appendBigEndian(z, (b << 16) | a);
  appendChunk(png, "IDAT", z);
  appendChunk(png, "IEND", "");
  return png;
}

}  // namespace vdg::testing
