// A small glTF decoder for tests, written from the glTF 2.0 specification (sections 4.4 GLB, 3.6
// accessors, 3.6.2.3 sparse accessors) and independent of the writer under test: it reads a
// .glb's chunks or a .gltf with its external buffer, and expands accessors to doubles.
#pragma once

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "support/test_meshes.h"

namespace vdg::testing {

struct DecodedGltf {
  nlohmann::json doc;
  std::string bin;
};

inline std::uint32_t u32At(const std::string& bytes, std::size_t offset) {
  if (offset + 4 > bytes.size()) throw std::runtime_error("truncated");
  std::uint32_t x;
  std::memcpy(&x, bytes.data() + offset, 4);
  return x;
}

inline DecodedGltf decodeGlb(const std::string& bytes) {
  if (u32At(bytes, 0) != 0x46546C67u || u32At(bytes, 4) != 2u || u32At(bytes, 8) != bytes.size())
    throw std::runtime_error("bad GLB header");
  const std::uint32_t json_length = u32At(bytes, 12);
  if (u32At(bytes, 16) != 0x4E4F534Au) throw std::runtime_error("first chunk is not JSON");
  DecodedGltf out;
  out.doc = nlohmann::json::parse(bytes.substr(20, json_length));
  const std::size_t bin_at = 20 + json_length;
  const std::uint32_t bin_length = u32At(bytes, bin_at);
  if (u32At(bytes, bin_at + 4) != 0x004E4942u) throw std::runtime_error("second chunk is not BIN");
  out.bin = bytes.substr(bin_at + 8, bin_length);
  if (out.bin.size() != bin_length) throw std::runtime_error("truncated BIN chunk");
  return out;
}

inline DecodedGltf decodeGltfFile(const std::string& path) {
  DecodedGltf out;
  out.doc = nlohmann::json::parse(readText(path));
  const std::string uri = out.doc.at("buffers").at(0).at("uri");
  out.bin = readText((std::filesystem::path(path).parent_path() / uri).string());
  return out;
}

inline int componentCount(const std::string& type) {
  if (type == "SCALAR") return 1;
  if (type == "VEC2") return 2;
  if (type == "VEC3") return 3;
  if (type == "VEC4") return 4;
  throw std::runtime_error("unexpected accessor type " + type);
}

// `count` values of `component_type` starting at byte `at` of the buffer (tightly packed).
inline std::vector<double> readComponents(const std::string& bin, std::size_t at, std::size_t count,
                                          int component_type) {
  std::vector<double> out(count);
  const std::size_t size = component_type == 5121 ? 1 : component_type == 5123 ? 2 : 4;
  if (at + count * size > bin.size()) throw std::runtime_error("accessor past the buffer");
  if (at % size != 0) throw std::runtime_error("misaligned accessor");
  for (std::size_t i = 0; i < count; ++i) {
    const char* p = bin.data() + at + i * size;
    if (component_type == 5121) out[i] = static_cast<unsigned char>(*p);
    if (component_type == 5123) {
      std::uint16_t x;
      std::memcpy(&x, p, 2);
      out[i] = x;
    }
    if (component_type == 5125) {
      std::uint32_t x;
      std::memcpy(&x, p, 4);
      out[i] = x;
    }
    if (component_type == 5126) {
      float x;
      std::memcpy(&x, p, 4);
      out[i] = x;
    }
  }
  return out;
}

inline std::size_t viewStart(const DecodedGltf& g, int view) {
  const auto& v = g.doc.at("bufferViews").at(view);
  return v.value("byteOffset", std::size_t{0});
}

// Accessor `index` expanded: count x components doubles (sparse substitutions applied).
inline std::vector<double> readAccessor(const DecodedGltf& g, int index) {
  const auto& a = g.doc.at("accessors").at(index);
  const std::size_t count = a.at("count");
  const int n = componentCount(a.at("type"));
  std::vector<double> out(count * n, 0.0);
  if (a.contains("bufferView")) {
    if (a.at("bufferView").get<int>() >= 0 &&
        g.doc.at("bufferViews").at(a.at("bufferView").get<int>()).contains("byteStride"))
      throw std::runtime_error("strided views are not expected");
    out = readComponents(g.bin, viewStart(g, a.at("bufferView")) + a.value("byteOffset", std::size_t{0}), count * n,
                         a.at("componentType"));
  }
  if (a.contains("sparse")) {
    const auto& s = a.at("sparse");
    const std::size_t sc = s.at("count");
    const auto idx = readComponents(
        g.bin, viewStart(g, s.at("indices").at("bufferView")) + s.at("indices").value("byteOffset", std::size_t{0}), sc,
        s.at("indices").at("componentType"));
    const auto val = readComponents(
        g.bin, viewStart(g, s.at("values").at("bufferView")) + s.at("values").value("byteOffset", std::size_t{0}),
        sc * n, a.at("componentType"));
    for (std::size_t i = 0; i < sc; ++i) {
      if (i > 0 && !(idx[i] > idx[i - 1])) throw std::runtime_error("sparse indices not increasing");
      const auto e = static_cast<std::size_t>(idx[i]);
      if (e >= count) throw std::runtime_error("sparse index out of range");
      for (int c = 0; c < n; ++c) out[e * n + c] = val[i * n + c];
    }
  }
  return out;
}

// _VDG_VERTEX of a vdg export's primitive: unsigned shorts with a byte stride of 4 (which
// readAccessor does not read), or floats.
inline std::vector<int> readVertexIds(const DecodedGltf& g, const nlohmann::json& primitive) {
  const int index = primitive.at("attributes").at("_VDG_VERTEX");
  const auto& a = g.doc.at("accessors").at(index);
  std::vector<int> ids;
  if (a.at("componentType") == 5126) {
    for (double id : readAccessor(g, index)) ids.push_back(static_cast<int>(id));
    return ids;
  }
  if (a.at("componentType") != 5123) throw std::runtime_error("_VDG_VERTEX: unexpected component type");
  const auto& view = g.doc.at("bufferViews").at(a.at("bufferView").get<int>());
  if (view.value("byteStride", 0) != 4) throw std::runtime_error("_VDG_VERTEX: expected a byte stride of 4");
  const std::size_t start = view.value("byteOffset", std::size_t{0}) + a.value("byteOffset", std::size_t{0});
  for (std::size_t e = 0; e < a.at("count").get<std::size_t>(); ++e) {
    std::uint16_t id = 0;
    std::memcpy(&id, g.bin.data() + start + e * 4, 2);
    ids.push_back(id);
  }
  return ids;
}

inline std::vector<float> toFloats(const std::vector<double>& v) { return std::vector<float>(v.begin(), v.end()); }

}  // namespace vdg::testing
