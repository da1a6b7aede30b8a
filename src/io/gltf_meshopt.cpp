// EXT_meshopt_compression decoding before tinygltf (gltf_meshopt.h). The extension (Khronos
// registry, Vendor/EXT_meshopt_compression): a bufferView's "extensions.EXT_meshopt_compression"
// names the compressed bytes (buffer, byteOffset, byteLength) and how to decode them: "count"
// elements of "byteStride" bytes, mode ATTRIBUTES (byteStride a multiple of 4, at most 256),
// TRIANGLES (count a multiple of 3) or INDICES (byteStride 2 or 4), an optional filter (NONE,
// OCTAHEDRAL: stride 4 or 8; QUATERNION: stride 8; EXPONENTIAL: stride a multiple of 4; ATTRIBUTES
// only). The view's own buffer may be a fallback buffer without data.
#include "gltf_meshopt.h"

#include <meshoptimizer.h>

#include <algorithm>
#include <cstdint>
#include <vector>

#include "vdg/geom/error.h"

namespace vdg {
namespace {

constexpr const char* kExt = "EXT_meshopt_compression";
constexpr std::uint64_t kMaxExpansion = 256;  // four times the codecs' own bound

std::string base64(std::string_view bytes) {
  static constexpr char kDigits[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    std::uint32_t x = static_cast<std::uint32_t>(static_cast<unsigned char>(bytes[i])) << 16;
    if (i + 1 < bytes.size()) x |= static_cast<std::uint32_t>(static_cast<unsigned char>(bytes[i + 1])) << 8;
    if (i + 2 < bytes.size()) x |= static_cast<unsigned char>(bytes[i + 2]);
    out += kDigits[(x >> 18) & 63];
    out += kDigits[(x >> 12) & 63];
    out += i + 1 < bytes.size() ? kDigits[(x >> 6) & 63] : '=';
    out += i + 2 < bytes.size() ? kDigits[x & 63] : '=';
  }
  return out;
}

// A non-negative integer field of the extension object (its default when absent and optional).
std::uint64_t uintField(const io::Json& ext, const char* key, std::optional<std::uint64_t> fallback,
                        const std::string& e) {
  const auto it = ext.find(key);
  if (it == ext.end()) {
    if (fallback) return *fallback;
    throw Error(e + ": " + key + " is missing");
  }
  if (!it->is_number_unsigned() && !(it->is_number_integer() && it->get<std::int64_t>() >= 0))
    throw Error(e + ": " + key + ": expected an integer >= 0, got " + io::describe(*it));
  return it->get<std::uint64_t>();
}

std::string stringField(const io::Json& ext, const char* key, const char* fallback, const std::string& e) {
  const auto it = ext.find(key);
  if (it == ext.end()) {
    if (fallback) return fallback;
    throw Error(e + ": " + key + " is missing");
  }
  if (!it->is_string()) throw Error(e + ": " + key + ": expected a string, got " + io::describe(*it));
  return it->get<std::string>();
}

// One compressed view decoded (its sizes checked first) into `out`.
void decodeView(const io::Json& ext, std::uint64_t view_length, const std::string& e, std::size_t budget,
                const std::vector<bool>& fallback, const std::function<std::string_view(std::size_t)>& buffer_bytes,
                std::string& out) {
  if (!ext.is_object()) throw Error(e + ": expected an object, got " + io::describe(ext));
  const std::uint64_t buffer = uintField(ext, "buffer", std::nullopt, e);
  const std::uint64_t offset = uintField(ext, "byteOffset", 0, e);
  const std::uint64_t length = uintField(ext, "byteLength", std::nullopt, e);
  const std::uint64_t stride = uintField(ext, "byteStride", std::nullopt, e);
  const std::uint64_t count = uintField(ext, "count", std::nullopt, e);
  const std::string mode = stringField(ext, "mode", nullptr, e);
  const std::string filter = stringField(ext, "filter", "NONE", e);
  if (buffer >= fallback.size())
    throw Error(e + ": buffer " + std::to_string(buffer) + " out of range (the file has " +
                std::to_string(fallback.size()) + ")");
  if (fallback[buffer]) throw Error(e + ": buffer " + std::to_string(buffer) + " is a fallback buffer without data");
  if (mode != "ATTRIBUTES" && mode != "TRIANGLES" && mode != "INDICES")
    throw Error(e + ": mode '" + mode + "' is not ATTRIBUTES, TRIANGLES or INDICES");
  if (mode == "ATTRIBUTES" ? (stride == 0 || stride % 4 != 0 || stride > 256) : (stride != 2 && stride != 4))
    throw Error(e + ": byteStride " + std::to_string(stride) + " is not allowed in mode " + mode +
                (mode == "ATTRIBUTES" ? " (a multiple of 4 up to 256)" : " (2 or 4)"));
  if (mode == "TRIANGLES" && count % 3 != 0)
    throw Error(e + ": count " + std::to_string(count) + " is not a multiple of 3 (mode TRIANGLES)");
  const bool filter_ok = filter == "NONE" ||
                         (mode == "ATTRIBUTES" && ((filter == "OCTAHEDRAL" && (stride == 4 || stride == 8)) ||
                                                   (filter == "QUATERNION" && stride == 8) || filter == "EXPONENTIAL"));
  if (!filter_ok)
    throw Error(e + ": filter '" + filter + "' does not apply to mode " + mode + ", byteStride " +
                std::to_string(stride));
  if (count == 0 || count > (std::uint64_t{1} << 32) || count * stride != view_length)
    throw Error(e + ": count " + std::to_string(count) + " x byteStride " + std::to_string(stride) +
                " is not the bufferView's byteLength " + std::to_string(view_length));
  // meshoptimizer's codecs expand at most 64 times (a 2-bit header per 16 zero bytes of vertex
  // data; at least a byte per triangle or index): a larger claim is refused before allocating it.
  if (view_length > kMaxExpansion * length + kMaxExpansion)
    throw Error(e + ": byteLength " + std::to_string(length) + " cannot decode to the bufferView's " +
                std::to_string(view_length) + " bytes");
  if (view_length > budget)
    throw Error(e + ": decoded, the compressed bufferViews exceed the limit of " + std::to_string(budget) + " bytes");
  const std::string_view source = buffer_bytes(buffer);
  if (offset > source.size() || length > source.size() - offset)
    throw Error(e + ": bytes " + std::to_string(offset) + " + " + std::to_string(length) + " lie outside buffers[" +
                std::to_string(buffer) + "] (" + std::to_string(source.size()) + " bytes)");
  const auto* src = reinterpret_cast<const unsigned char*>(source.data() + offset);
  const std::size_t at = out.size();
  out.resize(at + view_length, '\0');
  void* dst = out.data() + at;
  const int rc = mode == "ATTRIBUTES"  ? meshopt_decodeVertexBuffer(dst, count, stride, src, length)
                 : mode == "TRIANGLES" ? meshopt_decodeIndexBuffer(dst, count, stride, src, length)
                                       : meshopt_decodeIndexSequence(dst, count, stride, src, length);
  if (rc != 0)
    throw Error(e + ": the " + mode + " data does not decode (meshoptimizer error " + std::to_string(rc) + ")");
  if (filter == "OCTAHEDRAL") meshopt_decodeFilterOct(dst, count, stride);
  if (filter == "QUATERNION") meshopt_decodeFilterQuat(dst, count, stride);
  if (filter == "EXPONENTIAL") meshopt_decodeFilterExp(dst, count, stride);
}

}  // namespace

bool isMeshoptFallback(const io::Json& buffer) {
  if (!buffer.is_object() || buffer.contains("uri")) return false;
  const auto ext = buffer.find("extensions");
  if (ext == buffer.end() || !ext->is_object() || !ext->contains(kExt)) return false;
  const io::Json& m = (*ext)[kExt];
  return m.is_object() && m.value("fallback", false) == true;
}

std::optional<std::string> decodeMeshoptViews(const io::Json& doc, const std::string& source, std::size_t max_bytes,
                                              const std::function<std::string_view(std::size_t)>& buffer_bytes) {
  const auto views = doc.find("bufferViews");
  if (views == doc.end()) return std::nullopt;
  auto compressed = [](const io::Json& v) {
    return v.contains("extensions") && v["extensions"].is_object() && v["extensions"].contains(kExt);
  };
  // checkJson has checked the shapes; a file may still have views (an empty list) and no buffers.
  static const io::Json kNoBuffers = io::Json::array();
  const auto found = doc.find("buffers");
  const io::Json& buffers = found == doc.end() ? kNoBuffers : *found;
  if (std::none_of(views->begin(), views->end(), compressed) &&
      std::none_of(buffers.begin(), buffers.end(), [](const io::Json& b) { return isMeshoptFallback(b); }))
    return std::nullopt;
  io::Json out = doc;
  std::vector<bool> fallback(buffers.size());
  std::vector<std::size_t> renumber(buffers.size());
  io::Json kept = io::Json::array();
  for (std::size_t i = 0; i < buffers.size(); ++i) {
    fallback[i] = isMeshoptFallback(buffers[i]);
    renumber[i] = kept.size();
    if (!fallback[i]) kept.push_back(buffers[i]);
  }
  const std::size_t decoded_buffer = kept.size();
  std::string decoded;
  for (std::size_t i = 0; i < views->size(); ++i) {
    io::Json& v = out["bufferViews"][i];
    const std::string e = source + ": bufferViews[" + std::to_string(i) + "]";
    const auto own = v["buffer"].get<std::size_t>();
    if (!compressed(v)) {
      if (own < fallback.size() && fallback[own])
        throw Error(e + ": lies in fallback buffer " + std::to_string(own) +
                    ", which has no data, and is not compressed");
      if (own < renumber.size()) v["buffer"] = renumber[own];
      continue;
    }
    decoded.resize((decoded.size() + 3) & ~std::size_t{3}, '\0');
    const std::size_t at = decoded.size();
    decodeView(v["extensions"][kExt], v["byteLength"].get<std::uint64_t>(), e + ": " + kExt,
               max_bytes - std::min(max_bytes, decoded.size()), fallback, buffer_bytes, decoded);
    v["buffer"] = decoded_buffer;
    v["byteOffset"] = at;
    v["extensions"].erase(kExt);
    if (v["extensions"].empty()) v.erase("extensions");
  }
  if (!decoded.empty())
    kept.push_back(
        {{"byteLength", decoded.size()}, {"uri", "data:application/octet-stream;base64," + base64(decoded)}});
  out["buffers"] = std::move(kept);
  for (const char* key : {"extensionsUsed", "extensionsRequired"}) {
    if (!out.contains(key)) continue;
    io::Json& list = out[key];
    list.erase(std::remove(list.begin(), list.end(), io::Json(kExt)), list.end());
    if (list.empty()) out.erase(key);
  }
  return out.dump();
}

}  // namespace vdg
