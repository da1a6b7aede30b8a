// glTF's numeric codes and buffer alignment, shared by the writers (internal to vdg_io_model):
// gltf_export.cpp writes the buffers, gltf_compress.cpp re-encodes them.
#pragma once

#include <cstddef>

namespace vdg::gltf_codes {

// Accessor component types and bufferView targets (glTF 2.0, sections 5.1.1 and 5.11.1).
inline constexpr int kByte = 5120, kUnsignedByte = 5121, kShort = 5122, kUnsignedShort = 5123, kUnsignedInt = 5125,
                     kFloat = 5126;
inline constexpr int kArrayBuffer = 34962, kElementArrayBuffer = 34963;

// Buffer views and GLB chunks start on 4-byte boundaries (glTF 2.0, sections 3.6.2.4 and 4.4.3).
inline constexpr std::size_t pad4(std::size_t n) { return (n + 3) & ~std::size_t{3}; }

}  // namespace vdg::gltf_codes
