// The glTF reader's pre-pass for EXT_meshopt_compression (gltf.cpp): bufferViews compressed with
// meshoptimizer's codecs are decoded into one plain buffer before tinygltf reads the file.
#pragma once

#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <string_view>

#include "json_reader.h"

namespace vdg {

// True when buffers[i] is an EXT_meshopt_compression fallback buffer (no data of its own needed).
bool isMeshoptFallback(const io::Json& buffer);

// When a bufferView of `doc` (checked by the reader's JSON rules) carries EXT_meshopt_compression,
// or a buffer is a fallback one: the document's JSON text with every compressed view decoded into
// one new buffer (a base64 data: URI, appended), its extension removed, fallback buffers dropped
// (the other buffers renumbered), and EXT_meshopt_compression taken out of extensionsUsed and
// extensionsRequired; else nullopt. `buffer_bytes(i)` gives the bytes of buffers[i] (never a
// fallback one). Every size is checked before decoding (count x byteStride must be the view's
// byteLength, the source must lie in its buffer, a view may not claim more than 256 times its
// compressed bytes, all decoded views together at most `max_bytes`), and every decoder's return
// code; throws vdg::Error "SOURCE: bufferViews[3]: EXT_meshopt_compression: ..." otherwise, or
// "SOURCE: bufferViews[3]: lies in fallback buffer 1, ..." for a plain view without data.
std::optional<std::string> decodeMeshoptViews(const io::Json& doc, const std::string& source, std::size_t max_bytes,
                                              const std::function<std::string_view(std::size_t)>& buffer_bytes);

}  // namespace vdg
