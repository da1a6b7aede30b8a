// Smaller glTF exports: KHR_mesh_quantization and EXT_meshopt_compression as a post-pass over the
// document vdg's writer built (vdg/io/gltf_compress.h, docs/gltf-export.md).
//
// KHR_mesh_quantization (Khronos extension specification): POSITION may be normalized SHORT, and a
// morph target's POSITION normalized SHORT too, NORMAL normalized BYTE, TEXCOORD_n normalized
// UNSIGNED_SHORT; the dequantisation is the mesh node's transform. Every vertex attribute element
// starts on a 4-byte boundary (glTF 2.0, section 3.6.2.4), so VEC3 SHORT has byteStride 8 and VEC3
// BYTE byteStride 4. EXT_meshopt_compression: each compressed bufferView keeps its uncompressed
// place in a fallback buffer without data and names its compressed bytes in the extension.
#include <meshoptimizer.h>
#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <map>
#include <optional>
#include <set>
#include <span>
#include <vector>

#include "gltf_codes.h"
#include "gltf_compress_pass.h"
#include "vdg/geom/error.h"

namespace vdg {

const char* gltfCompressionName(GltfCompression c) {
  switch (c) {
    case GltfCompression::kQuantize:
      return "quantize";
    case GltfCompression::kMeshopt:
      return "meshopt";
    default:
      return "none";
  }
}

std::optional<GltfCompression> gltfCompressionFromName(std::string_view name) {
  for (const GltfCompression c : {GltfCompression::kNone, GltfCompression::kQuantize, GltfCompression::kMeshopt})
    if (name == gltfCompressionName(c)) return c;
  return std::nullopt;
}

namespace {

static_assert(std::endian::native == std::endian::little, "the glTF buffer is written in the host's byte order");

using OJson = nlohmann::ordered_json;

using namespace gltf_codes;
// The largest magnitude of a normalized signed integer: value = q / kMax (glTF 2.0, section 3.11).
constexpr double kShortMax = 32767.0, kByteMax = 127.0, kUnsignedShortMax = 65535.0;
constexpr std::array<double, 3> kNoOffset = {0.0, 0.0, 0.0};

std::size_t componentBytes(int type) {
  switch (type) {
    case kByte:
    case kUnsignedByte:
      return 1;
    case kShort:
    case kUnsignedShort:
      return 2;
    default:
      return 4;
  }
}

int componentCount(const std::string& type) {
  if (type == "SCALAR") return 1;
  if (type == "VEC2") return 2;
  if (type == "VEC3") return 3;
  if (type == "VEC4" || type == "MAT2") return 4;
  if (type == "MAT3") return 9;
  return 16;
}

// One bufferView: its JSON (buffer and byteOffset are set when the buffer is laid out) and bytes.
struct View {
  OJson json;
  std::string bytes;
};

// The document being rewritten: bufferViews taken out of the buffer, new ones appended.
struct Doc {
  OJson& doc;
  std::vector<View> views;
  bool quantized = false;

  Doc(OJson& d, const std::string& bin) : doc(d) {
    if (!doc.contains("bufferViews")) return;
    for (const OJson& v : doc["bufferViews"]) {
      const std::size_t offset = v.value("byteOffset", std::size_t{0});
      View view{v, bin.substr(offset, v["byteLength"].get<std::size_t>())};
      view.json.erase("byteOffset");
      view.json.erase("buffer");
      views.push_back(std::move(view));
    }
  }

  int addView(std::string bytes, std::size_t stride, int target) {
    OJson json = {{"byteLength", bytes.size()}};
    if (stride != 0) json["byteStride"] = stride;
    if (target != 0) json["target"] = target;
    views.push_back({std::move(json), std::move(bytes)});
    return static_cast<int>(views.size()) - 1;
  }
};

// A float accessor's values, count x components, sparse values applied (the writer's own layout).
std::vector<double> readFloats(const Doc& d, const OJson& acc) {
  const int n = componentCount(acc["type"].get<std::string>());
  const std::size_t count = acc["count"].get<std::size_t>();
  std::vector<double> out(count * static_cast<std::size_t>(n), 0.0);
  auto floatAt = [](const std::string& bytes, std::size_t at) {
    float f = 0.0f;
    std::memcpy(&f, bytes.data() + at, 4);
    return static_cast<double>(f);
  };
  if (acc.contains("bufferView")) {
    const View& v = d.views[acc["bufferView"].get<std::size_t>()];
    const std::size_t stride = v.json.value("byteStride", static_cast<std::size_t>(n) * 4);
    const std::size_t offset = acc.value("byteOffset", std::size_t{0});
    for (std::size_t i = 0; i < count; ++i)
      for (int c = 0; c < n; ++c) out[i * n + c] = floatAt(v.bytes, offset + i * stride + c * 4);
  }
  if (acc.contains("sparse")) {
    const OJson& s = acc["sparse"];
    const View& iv = d.views[s["indices"]["bufferView"].get<std::size_t>()];
    const View& vv = d.views[s["values"]["bufferView"].get<std::size_t>()];
    const int itype = s["indices"]["componentType"].get<int>();
    const std::size_t isize = componentBytes(itype), ioff = s["indices"].value("byteOffset", std::size_t{0});
    const std::size_t voff = s["values"].value("byteOffset", std::size_t{0});
    for (std::size_t k = 0; k < s["count"].get<std::size_t>(); ++k) {
      std::uint32_t index = 0;
      std::memcpy(&index, iv.bytes.data() + ioff + k * isize, isize);
      for (int c = 0; c < n; ++c) out[index * n + c] = floatAt(vv.bytes, voff + (k * n + c) * 4);
    }
  }
  return out;
}

// Integer components written as `component` (BYTE, SHORT or UNSIGNED_SHORT), `stride` bytes apart.
std::string packed(std::span<const std::int32_t> q, int n, int component, std::size_t stride) {
  const std::size_t count = q.size() / static_cast<std::size_t>(n), size = componentBytes(component);
  std::string out(count * stride, '\0');
  for (std::size_t i = 0; i < count; ++i)
    for (int c = 0; c < n; ++c) {
      const std::int32_t x = q[i * n + c];
      if (size == 1) {
        const auto b = static_cast<std::int8_t>(x);
        std::memcpy(&out[i * stride + c], &b, 1);
      } else {
        const auto s = static_cast<std::uint16_t>(x);
        std::memcpy(&out[i * stride + c * 2], &s, 2);
      }
    }
  return out;
}

const char* typeName(int n) { return n == 1 ? "SCALAR" : n == 2 ? "VEC2" : n == 3 ? "VEC3" : "VEC4"; }

// min/max of the integer components (what the accessor stores; a sparse accessor's implicit zeros
// count when `with_zero`).
void addBounds(OJson& acc, std::span<const std::int32_t> q, int n, bool with_zero) {
  std::vector<std::int32_t> lo(n, with_zero ? 0 : INT32_MAX), hi(n, with_zero ? 0 : INT32_MIN);
  for (std::size_t i = 0; i < q.size(); ++i) {
    lo[i % n] = std::min(lo[i % n], q[i]);
    hi[i % n] = std::max(hi[i % n], q[i]);
  }
  acc["min"] = lo;
  acc["max"] = hi;
}

// A new normalized integer accessor for `q` (count x n): dense with each element on a 4-byte
// boundary, or sparse (only the non-zero rows, tightly packed) when `allow_sparse` and smaller.
OJson quantizedAccessor(Doc& d, std::span<const std::int32_t> q, int n, int component, bool bounds, bool allow_sparse) {
  const std::size_t count = q.size() / static_cast<std::size_t>(n), elem = componentBytes(component) * n;
  std::vector<std::uint32_t> moved;
  for (std::size_t i = 0; i < count; ++i)
    if (std::any_of(q.begin() + i * n, q.begin() + (i + 1) * n, [](std::int32_t x) { return x != 0; }))
      moved.push_back(static_cast<std::uint32_t>(i));
  if (moved.empty()) moved.push_back(0);  // sparse.count must be >= 1
  const std::size_t isize = count <= 256 ? 1 : count <= 65536 ? 2 : 4;
  const bool sparse = allow_sparse && pad4(moved.size() * isize) + pad4(moved.size() * elem) < count * pad4(elem);
  OJson acc = {{"componentType", component}, {"normalized", true}, {"count", count}, {"type", typeName(n)}};
  if (!sparse) {
    acc = {{"bufferView", d.addView(packed(q, n, component, pad4(elem)), pad4(elem), kArrayBuffer)},
           {"componentType", component},
           {"normalized", true},
           {"count", count},
           {"type", typeName(n)}};
    if (bounds) addBounds(acc, q, n, false);
    return acc;
  }
  std::vector<std::int32_t> values;
  std::string indices(moved.size() * isize, '\0');
  for (std::size_t k = 0; k < moved.size(); ++k) {
    values.insert(values.end(), q.begin() + moved[k] * n, q.begin() + (moved[k] + 1) * n);
    std::memcpy(&indices[k * isize], &moved[k], isize);
  }
  const int itype = isize == 1 ? kUnsignedByte : isize == 2 ? kUnsignedShort : kUnsignedInt;
  acc["sparse"] = {{"count", moved.size()},
                   {"indices", {{"bufferView", d.addView(std::move(indices), 0, 0)}, {"componentType", itype}}},
                   {"values", {{"bufferView", d.addView(packed(values, n, component, elem), 0, 0)}}}};
  if (bounds) addBounds(acc, values, n, moved.size() < count);
  return acc;
}

// The normalized integers closest to `x`: round(max * (x - offset) / scale), per component with
// the offset of its axis (x, y, z in turn), clamped to [-max, max]; a reader gets q / max back.
std::vector<std::int32_t> quantized(std::span<const double> x, const std::array<double, 3>& offset, double scale,
                                    double max) {
  std::vector<std::int32_t> q(x.size());
  for (std::size_t i = 0; i < x.size(); ++i)
    q[i] = static_cast<std::int32_t>(
        std::clamp(std::lround(max * (x[i] - offset[i % 3]) / scale), -static_cast<long>(max), static_cast<long>(max)));
  return q;
}

// The accessors of a mesh's primitives under attribute `name` (base and, with `targets`, morph
// targets), each once.
std::vector<std::size_t> meshAccessors(const OJson& mesh, const std::string& name, bool base, bool targets) {
  std::set<std::size_t> seen;
  std::vector<std::size_t> out;
  auto add = [&](const OJson& attributes) {
    if (!attributes.contains(name)) return;
    const auto a = attributes[name].get<std::size_t>();
    if (seen.insert(a).second) out.push_back(a);
  };
  for (const OJson& p : mesh["primitives"]) {
    if (base) add(p["attributes"]);
    if (targets && p.contains("targets"))
      for (const OJson& t : p["targets"]) add(t);
  }
  return out;
}

bool isFloat(const OJson& acc) { return acc["componentType"].get<int>() == kFloat; }

// The grid of quantised positions: mesh-local p in [-1, 1] is center + scale * p in model units.
struct Grid {
  std::array<double, 3> center{};
  double scale = 1.0;
};

// Positions and position targets of `mesh` on one uniform grid (nullopt, and nothing changed, when
// one of them is not float).
std::optional<Grid> quantizePositions(Doc& d, OJson& mesh, bool allow_sparse) {
  OJson& accessors = d.doc["accessors"];
  const auto bases = meshAccessors(mesh, "POSITION", true, false);
  std::vector<std::size_t> targets;
  for (std::size_t t : meshAccessors(mesh, "POSITION", false, true))
    if (std::find(bases.begin(), bases.end(), t) == bases.end()) targets.push_back(t);
  for (std::size_t a : bases)
    if (!isFloat(accessors[a])) return std::nullopt;
  for (std::size_t a : targets)
    if (!isFloat(accessors[a])) return std::nullopt;
  if (bases.empty()) return std::nullopt;
  std::map<std::size_t, std::vector<double>> values;
  double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
  for (std::size_t a : bases) {
    values[a] = readFloats(d, accessors[a]);
    for (std::size_t i = 0; i < values[a].size(); ++i)
      lo[i % 3] = std::min(lo[i % 3], values[a][i]), hi[i % 3] = std::max(hi[i % 3], values[a][i]);
  }
  // One scale for the three axes: a normal stays a normal under a uniform scale. It holds the
  // base's half extents and every target delta, so that each fits [-1, 1].
  const std::array<double, 3> center = {(lo[0] + hi[0]) / 2, (lo[1] + hi[1]) / 2, (lo[2] + hi[2]) / 2};
  double s = 0.0;
  for (int c = 0; c < 3; ++c) s = std::max(s, (hi[c] - lo[c]) / 2);
  for (std::size_t a : targets) {
    values[a] = readFloats(d, accessors[a]);
    for (double x : values[a]) s = std::max(s, std::abs(x));
  }
  if (!(s > 0.0) || !std::isfinite(s)) s = 1.0;
  for (std::size_t a : bases)
    accessors[a] = quantizedAccessor(d, quantized(values[a], center, s, kShortMax), 3, kShort, true, false);
  for (std::size_t a : targets)
    accessors[a] = quantizedAccessor(d, quantized(values[a], kNoOffset, s, kShortMax), 3, kShort, true, allow_sparse);
  d.quantized = true;
  return Grid{center, s};
}

// Normals (and normal targets whose deltas fit [-1, 1]) as normalized BYTE, texture coordinates in
// [0, 1] as normalized UNSIGNED_SHORT.
void quantizeOthers(Doc& d, OJson& mesh, bool allow_sparse) {
  OJson& accessors = d.doc["accessors"];
  const auto bases = meshAccessors(mesh, "NORMAL", true, false);
  for (std::size_t a : meshAccessors(mesh, "NORMAL", true, true)) {
    if (!isFloat(accessors[a])) continue;
    const std::vector<double> v = readFloats(d, accessors[a]);
    if (std::any_of(v.begin(), v.end(), [](double x) { return std::abs(x) > 1.0; })) continue;
    const bool base = std::find(bases.begin(), bases.end(), a) != bases.end();
    accessors[a] = quantizedAccessor(d, quantized(v, kNoOffset, 1.0, kByteMax), 3, kByte, false, allow_sparse && !base);
    d.quantized = true;
  }
  std::set<std::string> uv_names;
  for (const OJson& p : mesh["primitives"])
    for (const auto& [name, _] : p["attributes"].items())
      if (name.rfind("TEXCOORD_", 0) == 0) uv_names.insert(name);
  for (const std::string& name : uv_names)
    for (std::size_t a : meshAccessors(mesh, name, true, false)) {
      if (!isFloat(accessors[a])) continue;
      const std::vector<double> v = readFloats(d, accessors[a]);
      if (std::any_of(v.begin(), v.end(), [](double x) { return x < 0.0 || x > 1.0; })) continue;
      const auto q = quantized(v, kNoOffset, 1.0, kUnsignedShortMax);
      accessors[a] = quantizedAccessor(d, q, 2, kUnsignedShort, false, false);
      d.quantized = true;
    }
}

// UNSIGNED_BYTE triangle indices as UNSIGNED_SHORT (meshopt's index codec reads 2 or 4 bytes).
void widenByteIndices(Doc& d) {
  OJson& accessors = d.doc["accessors"];
  for (OJson& mesh : d.doc["meshes"])
    for (const OJson& p : mesh["primitives"]) {
      if (!p.contains("indices")) continue;
      OJson& acc = accessors[p["indices"].get<std::size_t>()];
      if (acc["componentType"].get<int>() != kUnsignedByte || !acc.contains("bufferView")) continue;
      const View& v = d.views[acc["bufferView"].get<std::size_t>()];
      const std::size_t count = acc["count"].get<std::size_t>(), offset = acc.value("byteOffset", std::size_t{0});
      std::string wide(pad4(count * 2), '\0');
      for (std::size_t i = 0; i < count; ++i) {
        const auto x = static_cast<std::uint16_t>(static_cast<unsigned char>(v.bytes[offset + i]));
        std::memcpy(&wide[i * 2], &x, 2);
      }
      wide.resize(count * 2);
      acc["bufferView"] = d.addView(std::move(wide), 0, kElementArrayBuffer);
      acc["componentType"] = kUnsignedShort;
      acc.erase("byteOffset");
    }
}

// Drops the bufferViews nothing refers to any more and renumbers the references.
void compactViews(Doc& d) {
  std::vector<int*> refs;
  std::vector<OJson*> ref_json;
  auto collect = [&](OJson& holder) {
    if (holder.contains("bufferView")) ref_json.push_back(&holder["bufferView"]);
  };
  for (OJson& acc : d.doc["accessors"]) {
    collect(acc);
    if (acc.contains("sparse")) collect(acc["sparse"]["indices"]), collect(acc["sparse"]["values"]);
  }
  if (d.doc.contains("images"))
    for (OJson& image : d.doc["images"]) collect(image);
  std::vector<int> renumber(d.views.size(), -1);
  for (OJson* r : ref_json) renumber[r->get<std::size_t>()] = 0;
  std::vector<View> kept;
  for (std::size_t i = 0; i < d.views.size(); ++i)
    if (renumber[i] == 0) renumber[i] = static_cast<int>(kept.size()), kept.push_back(std::move(d.views[i]));
  for (OJson* r : ref_json) *r = renumber[r->get<std::size_t>()];
  d.views = std::move(kept);
}

void addExtension(OJson& doc, const char* name, bool required) {
  for (const char* key : {"extensionsUsed", "extensionsRequired"}) {
    if (!required && std::string(key) == "extensionsRequired") continue;
    if (!doc.contains(key)) doc[key] = OJson::array();
    if (std::find(doc[key].begin(), doc[key].end(), name) == doc[key].end()) doc[key].push_back(name);
  }
}

// How each bufferView is used: by triangle indices of one component type, by other accessors of
// one element size, by an image.
struct ViewUse {
  int index_type = 0;    // componentType of the index accessors using it (0: none)
  std::size_t elem = 0;  // element size of the other accessors using it (0: none, or differing)
  bool other = false;    // used by an accessor that is not indices
  bool mixed = false;    // element sizes differ
  bool image = false;
};

std::vector<ViewUse> viewUses(const Doc& d) {
  std::vector<ViewUse> uses(d.views.size());
  std::set<std::size_t> index_accessors;
  for (const OJson& mesh : d.doc["meshes"])
    for (const OJson& p : mesh["primitives"])
      if (p.contains("indices")) index_accessors.insert(p["indices"].get<std::size_t>());
  auto other = [&](const OJson& holder, std::size_t elem) {
    if (!holder.contains("bufferView")) return;
    ViewUse& u = uses[holder["bufferView"].get<std::size_t>()];
    if (u.other && u.elem != elem) u.mixed = true;
    u.other = true;
    u.elem = elem;
  };
  for (std::size_t a = 0; a < d.doc["accessors"].size(); ++a) {
    const OJson& acc = d.doc["accessors"][a];
    const int type = acc["componentType"].get<int>();
    const std::size_t elem = componentBytes(type) * componentCount(acc["type"].get<std::string>());
    if (index_accessors.count(a) && acc.contains("bufferView")) {
      ViewUse& u = uses[acc["bufferView"].get<std::size_t>()];
      if (u.index_type != 0 && u.index_type != type) u.mixed = true;
      u.index_type = type;
    } else {
      other(acc, elem);
    }
    if (acc.contains("sparse")) {
      other(acc["sparse"]["indices"], 0);
      other(acc["sparse"]["values"], 0);
    }
  }
  if (d.doc.contains("images"))
    for (const OJson& image : d.doc["images"])
      if (image.contains("bufferView")) uses[image["bufferView"].get<std::size_t>()].image = true;
  return uses;
}

// One bufferView compressed with meshopt (empty `bytes`: left as it is).
struct Encoded {
  std::string bytes;
  OJson extension;
};

Encoded encodeTriangles(const View& v, int type, const std::string& where, std::size_t i) {
  const std::size_t size = componentBytes(type), count = v.bytes.size() / size;
  std::vector<unsigned int> indices(count);
  unsigned int vertices = 0;
  for (std::size_t k = 0; k < count; ++k) {
    std::uint32_t x = 0;
    std::memcpy(&x, v.bytes.data() + k * size, size);
    indices[k] = x;
    vertices = std::max(vertices, x + 1);
  }
  std::string out(meshopt_encodeIndexBufferBound(count, vertices), '\0');
  const std::size_t n =
      meshopt_encodeIndexBuffer(reinterpret_cast<unsigned char*>(out.data()), out.size(), indices.data(), count);
  if (n == 0)
    throw Error(where + ": --compress meshopt: bufferViews[" + std::to_string(i) + "]: the index encoder failed");
  out.resize(n);
  return {std::move(out), {{"byteStride", size}, {"count", count}, {"mode", "TRIANGLES"}}};
}

Encoded encodeAttributes(const View& v, std::size_t stride, const std::string& where, std::size_t i) {
  const std::size_t count = v.bytes.size() / stride;
  std::string out(meshopt_encodeVertexBufferBound(count, stride), '\0');
  const std::size_t n = meshopt_encodeVertexBuffer(reinterpret_cast<unsigned char*>(out.data()), out.size(),
                                                   v.bytes.data(), count, stride);
  if (n == 0)
    throw Error(where + ": --compress meshopt: bufferViews[" + std::to_string(i) + "]: the vertex encoder failed");
  out.resize(n);
  return {std::move(out), {{"byteStride", stride}, {"count", count}, {"mode", "ATTRIBUTES"}}};
}

// The meshopt encoding of every bufferView that has one (EXT_meshopt_compression: ATTRIBUTES with
// a byteStride that is a multiple of 4 up to 256, TRIANGLES over 2- or 4-byte indices, a count of
// elements that fills the view), kept only where it is smaller.
std::vector<Encoded> encodeViews(const Doc& d, const std::string& where) {
  const std::vector<ViewUse> uses = viewUses(d);
  std::vector<Encoded> out(d.views.size());
  for (std::size_t i = 0; i < d.views.size(); ++i) {
    const View& v = d.views[i];
    const ViewUse& u = uses[i];
    if (u.image || v.bytes.empty()) continue;
    Encoded e;
    if (u.index_type != 0) {
      const std::size_t size = componentBytes(u.index_type);
      if (u.other || u.mixed || size == 1 || v.json.contains("byteStride") || v.bytes.size() % (3 * size) != 0)
        continue;
      e = encodeTriangles(v, u.index_type, where, i);
    } else {
      std::size_t stride = v.json.value("byteStride", std::size_t{0});
      if (stride == 0) stride = !u.mixed && u.elem != 0 && u.elem % 4 == 0 && u.elem <= 256 ? u.elem : 4;
      if (stride % 4 != 0 || stride > 256 || v.bytes.size() % stride != 0) continue;
      e = encodeAttributes(v, stride, where, i);
    }
    if (e.bytes.size() < v.bytes.size()) out[i] = std::move(e);
  }
  return out;
}

// Lays the views out in buffers[0] (`bin`); with meshopt, compressed views keep their place in a
// fallback buffer (buffers[1], no data) and name their bytes in buffers[0] in the extension.
void layOut(Doc& d, std::string& bin, const std::vector<Encoded>& encoded) {
  bin.clear();
  std::size_t fallback = 0;
  OJson views = OJson::array();
  for (std::size_t i = 0; i < d.views.size(); ++i) {
    View& v = d.views[i];
    OJson json = {{"buffer", 0}};
    bin.resize(pad4(bin.size()), '\0');
    if (!encoded.empty() && !encoded[i].bytes.empty()) {
      json = {{"buffer", 1}, {"byteOffset", fallback}};
      fallback = pad4(fallback + v.bytes.size());
      OJson ext = {{"buffer", 0}, {"byteOffset", bin.size()}, {"byteLength", encoded[i].bytes.size()}};
      ext.update(encoded[i].extension);
      v.json["extensions"]["EXT_meshopt_compression"] = std::move(ext);
      bin += encoded[i].bytes;
    } else {
      json["byteOffset"] = bin.size();
      bin += v.bytes;
    }
    json.update(v.json);
    views.push_back(std::move(json));
  }
  bin.resize(pad4(bin.size()), '\0');
  d.doc["bufferViews"] = std::move(views);
  OJson buffers = OJson::array({OJson{{"byteLength", bin.size()}}});
  if (fallback > 0) {
    buffers.push_back({{"byteLength", fallback}, {"extensions", {{"EXT_meshopt_compression", {{"fallback", true}}}}}});
    addExtension(d.doc, "EXT_meshopt_compression", true);
  }
  d.doc["buffers"] = std::move(buffers);
}

// Where the dequantisation of mesh `m` can go: the transform of its nodes (none of which has one
// or a skin: vdg writes no other transform on a mesh node), or, when they are all skinned (glTF
// 2.0, section 3.7.3: a skinned mesh ignores its node's transform), the inverse bind matrices of
// their skins (used by no other mesh). `ok` false: nowhere, the positions stay float.
struct Placement {
  bool ok = false;
  std::vector<std::size_t> nodes;  // plain nodes
  std::vector<std::size_t> ibms;   // inverse bind matrix accessors of the skins
};

Placement placement(const OJson& doc, std::size_t m) {
  Placement p;
  if (!doc.contains("nodes")) return p;
  std::set<std::size_t> skins, ibms;
  for (std::size_t n = 0; n < doc["nodes"].size(); ++n) {
    const OJson& node = doc["nodes"][n];
    if (!node.contains("mesh") || node["mesh"].get<std::size_t>() != m) continue;
    if (node.contains("skin")) {
      const OJson& skin = doc["skins"][node["skin"].get<std::size_t>()];
      if (!skin.contains("inverseBindMatrices")) return p;
      skins.insert(node["skin"].get<std::size_t>());
      ibms.insert(skin["inverseBindMatrices"].get<std::size_t>());
      continue;
    }
    for (const char* key : {"matrix", "translation", "rotation", "scale"})
      if (node.contains(key)) return p;
    p.nodes.push_back(n);
  }
  for (const OJson& node : doc["nodes"])  // a skin of this mesh must serve no other
    if (node.contains("skin") && skins.count(node["skin"].get<std::size_t>()) &&
        (!node.contains("mesh") || node["mesh"].get<std::size_t>() != m))
      return p;
  if (!p.nodes.empty() && !skins.empty()) return p;
  p.ibms.assign(ibms.begin(), ibms.end());
  p.ok = !p.nodes.empty() || !p.ibms.empty();
  return p;
}

// The grid's dequantisation on the mesh's nodes (translation, uniform scale) and in
// mesh.extras.vdg.dequantize.
void placeOnNodes(Doc& d, OJson& mesh, const std::vector<std::size_t>& nodes, const Grid& g) {
  const OJson offset = {g.center[0], g.center[1], g.center[2]}, scale = {g.scale, g.scale, g.scale};
  for (std::size_t n : nodes) {
    d.doc["nodes"][n]["translation"] = offset;
    d.doc["nodes"][n]["scale"] = scale;
  }
  if (mesh.contains("extras") && mesh["extras"].is_object() && mesh["extras"].contains("vdg"))
    mesh["extras"]["vdg"]["dequantize"] = {{"scale", scale}, {"offset", offset}};
}

// The grid's dequantisation D (scale, then translate) folded into each inverse bind matrix:
// IBM' = IBM * D, so that skinning a mesh-local point gives what skinning the float point gave
// (glTF 2.0, section 3.7.3.3: joint matrix = joint world transform * inverse bind matrix). The
// morph target deltas, added before skinning, are scaled by D's linear part the same way.
void foldIntoInverseBindMatrices(Doc& d, const std::vector<std::size_t>& ibms, const Grid& g) {
  for (std::size_t a : ibms) {
    OJson& acc = d.doc["accessors"][a];
    const std::vector<double> m = readFloats(d, acc);  // count x 16, column-major
    std::vector<float> out(m.size());
    for (std::size_t k = 0; k + 16 <= m.size(); k += 16)
      for (int row = 0; row < 4; ++row) {
        for (int col = 0; col < 3; ++col) out[k + col * 4 + row] = static_cast<float>(m[k + col * 4 + row] * g.scale);
        out[k + 12 + row] = static_cast<float>(m[k + row] * g.center[0] + m[k + 4 + row] * g.center[1] +
                                               m[k + 8 + row] * g.center[2] + m[k + 12 + row]);
      }
    const int view = d.addView(std::string(reinterpret_cast<const char*>(out.data()), out.size() * 4), 0, 0);
    acc = {{"bufferView", view}, {"componentType", kFloat}, {"count", acc["count"]}, {"type", "MAT4"}};
  }
}

}  // namespace

void compressGltf(OJson& doc, std::string& bin, GltfCompression compression, const std::string& where,
                  std::size_t* sparse_targets) {
  if (compression == GltfCompression::kNone || !doc.contains("meshes")) return;
  Doc d(doc, bin);
  const bool meshopt = compression == GltfCompression::kMeshopt;
  for (std::size_t m = 0; m < doc["meshes"].size(); ++m) {
    OJson& mesh = doc["meshes"][m];
    const Placement p = placement(doc, m);
    if (p.ok)
      if (const std::optional<Grid> g = quantizePositions(d, mesh, !meshopt)) {
        if (p.ibms.empty()) placeOnNodes(d, mesh, p.nodes, *g);
        foldIntoInverseBindMatrices(d, p.ibms, *g);
      }
    quantizeOthers(d, mesh, !meshopt);
  }
  if (d.quantized) addExtension(doc, "KHR_mesh_quantization", true);
  if (meshopt) widenByteIndices(d);
  compactViews(d);
  layOut(d, bin, meshopt ? encodeViews(d, where) : std::vector<Encoded>());
  if (sparse_targets) {
    *sparse_targets = 0;
    for (const OJson& mesh : doc["meshes"])
      for (std::size_t a : meshAccessors(mesh, "POSITION", false, true))
        *sparse_targets += doc["accessors"][a].contains("sparse") ? 1 : 0;
  }
}

}  // namespace vdg
