// glTF 2.0 input: tinygltf parses, vdg checks every index, range and type before reading data.
// Accessor, sparse accessor, skin and animation semantics: glTF 2.0 specification (Khronos),
// sections 3.6 (buffers, accessors, sparse accessors), 3.7 (meshes, morph targets, skins) and
// 3.11 (animations); GLB layout: section 4.4.
//
// The only translation unit with tinygltf's implementation (no image decoding, no file system of
// its own: every file goes through vdg's bounded readers).
#define TINYGLTF_IMPLEMENTATION
#define TINYGLTF_NO_STB_IMAGE
#define TINYGLTF_NO_STB_IMAGE_WRITE
#define TINYGLTF_NO_EXTERNAL_IMAGE
#define TINYGLTF_NO_FS
#include "vdg/io/gltf.h"

// tinygltf 2.7's writer uses std::ofstream even with TINYGLTF_NO_FS, which leaves <fstream> out.
#include <fstream>
// clang-format off
#include <tiny_gltf.h>
// clang-format on

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <functional>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <sstream>

#include "gltf_meshopt.h"
#include "json_reader.h"
#include "material_files.h"
#include "mesh_extent.h"
#include "vdg/geom/error.h"
#include "vdg/geom/text.h"
#include "vdg/io/read_file.h"

namespace vdg {
namespace {

namespace tg = tinygltf;

// Stands for the glTF file's folder in the paths tinygltf hands to the file callbacks, so that the
// callbacks see exactly the URI the file wrote (tinygltf also tries "./URI", which is refused).
constexpr const char* kFolderToken = "<vdg-gltf-folder>";

std::string idx(const char* array, std::size_t i) { return std::string(array) + "[" + std::to_string(i) + "]"; }

struct FileAccess {
  std::string source;
  std::string folder;  // empty: external files are refused
  std::size_t external_bytes = 0;
  std::string error;                         // why the last callback refused
  std::map<std::string, std::size_t> sizes;  // bytes of each external file read, by URI
};

// The URI part of a path tinygltf built as kFolderToken + "/" + URI; false when it is not one.
bool uriOf(const std::string& path, std::string* uri) {
  const std::string head = std::string(kFolderToken) + "/";
  if (path.compare(0, head.size(), head) != 0) return false;
  *uri = path.substr(head.size());
  return true;
}

// A URI vdg reads from the file's folder: relative, no "..", no backslash, no ':', no NUL.
std::string uriProblem(const std::string& uri) { return io::relativePathProblem(uri); }

bool fileExists(const std::string& path, void* user) {
  auto* access = static_cast<FileAccess*>(user);
  std::string uri;
  if (!uriOf(path, &uri)) return false;
  const std::string problem = uriProblem(uri);
  if (!problem.empty()) {
    access->error = quotedText(uri) + " " + problem + " (external files must lie in the glTF file's folder)";
    return false;
  }
  if (access->folder.empty()) {
    access->error = quotedText(uri) + " is an external file, and these bytes come without a folder";
    return false;
  }
  return true;
}

std::string expandPath(const std::string& path, void*) { return path; }

bool readWholeFile(std::vector<unsigned char>* out, std::string* err, const std::string& path, void* user) {
  auto* access = static_cast<FileAccess*>(user);
  std::string uri;
  if (!uriOf(path, &uri) || !uriProblem(uri).empty() || access->folder.empty()) return false;
  const std::string full = access->folder == "." ? uri : (std::filesystem::path(access->folder) / uri).string();
  const std::size_t budget = kMaxMeshFileBytes - std::min(kMaxMeshFileBytes, access->external_bytes);
  try {
    const std::string bytes = readFileLimited(full, "glTF buffer", budget);
    access->external_bytes += bytes.size();
    access->sizes[uri] = bytes.size();
    out->assign(bytes.begin(), bytes.end());
  } catch (const Error& e) {
    access->error = e.what();
    if (err) *err = e.what();
    return false;
  }
  return true;
}

bool writeWholeFile(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
  if (err) *err = "vdg does not write through tinygltf";
  return false;
}

// Images are decoded by vdg (buildRig), not by tinygltf: the bytes of a data: URI image are kept
// as they are; a bufferView image is read later from its checked bufferView (tinygltf hands over a
// pointer it has not checked, so it is not read here).
bool keepImageBytes(tg::Image* image, const int, std::string*, std::string*, int, int, const unsigned char* bytes,
                    int size, void*) {
  if (image->bufferView < 0 && bytes && size > 0) image->image.assign(bytes, bytes + size);
  return true;
}

std::uint32_t le32(std::string_view b, std::size_t at) {
  return static_cast<std::uint32_t>(static_cast<unsigned char>(b[at])) |
         static_cast<std::uint32_t>(static_cast<unsigned char>(b[at + 1])) << 8 |
         static_cast<std::uint32_t>(static_cast<unsigned char>(b[at + 2])) << 16 |
         static_cast<std::uint32_t>(static_cast<unsigned char>(b[at + 3])) << 24;
}

// GLB (section 4.4): 12-byte header, a JSON chunk, an optional BIN chunk. Returns the JSON text;
// `bin` gets the BIN chunk's length when there is one.
std::string_view checkGlb(std::string_view b, const std::string& source, std::optional<std::size_t>* bin) {
  auto fail = [&](const std::string& what) { throw Error(source + ": " + what); };
  if (b.size() < 20)
    fail("truncated GLB: " + std::to_string(b.size()) + " bytes, less than the 20 of a header and a chunk header");
  if (le32(b, 4) != 2) fail("GLB version " + std::to_string(le32(b, 4)) + ", vdg reads version 2");
  const std::uint64_t length = le32(b, 8);
  if (length > b.size())
    fail("truncated GLB: the header says " + std::to_string(length) + " bytes, the file has " +
         std::to_string(b.size()));
  if (length < b.size())
    fail("GLB header says " + std::to_string(length) + " bytes, the file has " + std::to_string(b.size()));
  const std::uint64_t json_length = le32(b, 12);
  if (le32(b, 16) != 0x4E4F534Au) fail("GLB: the first chunk is not JSON");
  if (json_length == 0) fail("GLB: the JSON chunk is empty");
  if (20 + json_length > length)
    fail("truncated GLB: the JSON chunk needs " + std::to_string(json_length) + " bytes, " +
         std::to_string(length - 20) + " remain");
  const std::uint64_t bin_at = 20 + json_length;
  if (bin_at < length) {
    if (bin_at + 8 > length) fail("truncated GLB: the BIN chunk header is cut short");
    const std::uint64_t bin_length = le32(b, bin_at);
    if (le32(b, bin_at + 4) != 0x004E4942u) fail("GLB: the second chunk is not BIN");
    if (bin_at + 8 + bin_length > length)
      fail("truncated GLB: the BIN chunk needs " + std::to_string(bin_length) + " bytes, " +
           std::to_string(length - bin_at - 8) + " remain");
    if (bin_length < 4 || bin_length % 4 != 0)
      fail("GLB: the BIN chunk's length " + std::to_string(bin_length) + " is not a multiple of 4 (at least 4)");
    *bin = static_cast<std::size_t>(bin_length);
  }
  return b.substr(20, json_length);
}

// Component size in bytes, 0 for an unknown type.
std::size_t componentSize(int type) {
  switch (type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
      return 2;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT:
      return 4;
    default:
      return 0;
  }
}

const char* componentName(int type) {
  switch (type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
      return "BYTE";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return "UNSIGNED_BYTE";
    case TINYGLTF_COMPONENT_TYPE_SHORT:
      return "SHORT";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
      return "UNSIGNED_SHORT";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
      return "UNSIGNED_INT";
    case TINYGLTF_COMPONENT_TYPE_FLOAT:
      return "FLOAT";
    default:
      return "an unknown component type";
  }
}

std::size_t componentCount(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR:
      return 1;
    case TINYGLTF_TYPE_VEC2:
      return 2;
    case TINYGLTF_TYPE_VEC3:
      return 3;
    case TINYGLTF_TYPE_VEC4:
    case TINYGLTF_TYPE_MAT2:
      return 4;
    case TINYGLTF_TYPE_MAT3:
      return 9;
    case TINYGLTF_TYPE_MAT4:
      return 16;
    default:
      return 0;
  }
}

const char* typeName(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR:
      return "SCALAR";
    case TINYGLTF_TYPE_VEC2:
      return "VEC2";
    case TINYGLTF_TYPE_VEC3:
      return "VEC3";
    case TINYGLTF_TYPE_VEC4:
      return "VEC4";
    case TINYGLTF_TYPE_MAT2:
      return "MAT2";
    case TINYGLTF_TYPE_MAT3:
      return "MAT3";
    case TINYGLTF_TYPE_MAT4:
      return "MAT4";
    default:
      return "an unknown type";
  }
}

// One component as a double; normalized integers map to [0, 1] or [-1, 1] (section 3.11, "
// Animation samplers", and 3.7.2.1).
double component(const unsigned char* p, int type, bool normalized) {
  switch (type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
      const auto v = static_cast<std::int8_t>(*p);
      return normalized ? std::max(v / 127.0, -1.0) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return normalized ? *p / 255.0 : *p;
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
      std::int16_t v;
      std::memcpy(&v, p, 2);
      return normalized ? std::max(v / 32767.0, -1.0) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      std::uint16_t v;
      std::memcpy(&v, p, 2);
      return normalized ? v / 65535.0 : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
      std::uint32_t v;
      std::memcpy(&v, p, 4);
      return normalized ? v / 4294967295.0 : v;
    }
    default: {
      float v;
      std::memcpy(&v, p, 4);
      return v;
    }
  }
}

// What an accessor may be for a given use.
struct Want {
  std::vector<int> types;  // element types allowed
  // allowed component types: {componentType, normalized}
  std::vector<std::pair<int, bool>> components;
  const char* description;  // "float VEC3"
};

const Want kFloatVec3{{TINYGLTF_TYPE_VEC3}, {{TINYGLTF_COMPONENT_TYPE_FLOAT, false}}, "FLOAT VEC3"};
const Want kTexcoord{{TINYGLTF_TYPE_VEC2},
                     {{TINYGLTF_COMPONENT_TYPE_FLOAT, false},
                      {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, true},
                      {TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, true}},
                     "VEC2 of FLOAT or normalized UNSIGNED_BYTE / UNSIGNED_SHORT"};
const Want kJoints{{TINYGLTF_TYPE_VEC4},
                   {{TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, false}, {TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, false}},
                   "VEC4 of UNSIGNED_BYTE or UNSIGNED_SHORT"};
const Want kWeights{{TINYGLTF_TYPE_VEC4},
                    {{TINYGLTF_COMPONENT_TYPE_FLOAT, false},
                     {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, true},
                     {TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, true}},
                    "VEC4 of FLOAT or normalized UNSIGNED_BYTE / UNSIGNED_SHORT"};
// _VDG_VERTEX of a vdg export (docs/gltf-export.md): integers, as unsigned bytes or shorts, or as floats.
const Want kVertexIds{{TINYGLTF_TYPE_SCALAR},
                      {{TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, false},
                       {TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, false},
                       {TINYGLTF_COMPONENT_TYPE_FLOAT, false}},
                      "SCALAR of UNSIGNED_BYTE, UNSIGNED_SHORT or FLOAT"};
const Want kIndices{{TINYGLTF_TYPE_SCALAR},
                    {{TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, false},
                     {TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, false},
                     {TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, false}},
                    "SCALAR of UNSIGNED_BYTE, UNSIGNED_SHORT or UNSIGNED_INT"};
// KHR_mesh_quantization: POSITION, NORMAL, TEXCOORD_n and morph targets may also be (normalized)
// integers; the reader turns them into floats (section 3.11's normalisation) and the node's
// transform, as for any mesh, dequantises them.
const std::vector<std::pair<int, bool>> kQuantized{
    {TINYGLTF_COMPONENT_TYPE_FLOAT, false},         {TINYGLTF_COMPONENT_TYPE_BYTE, true},
    {TINYGLTF_COMPONENT_TYPE_BYTE, false},          {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, true},
    {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, false}, {TINYGLTF_COMPONENT_TYPE_SHORT, true},
    {TINYGLTF_COMPONENT_TYPE_SHORT, false},         {TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, true},
    {TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, false}};
const Want kQuantizedVec3{{TINYGLTF_TYPE_VEC3}, kQuantized, "VEC3 of FLOAT or (normalized) integers"};
const Want kQuantizedTexcoord{{TINYGLTF_TYPE_VEC2}, kQuantized, "VEC2 of FLOAT or (normalized) integers"};
const Want kMat4{{TINYGLTF_TYPE_MAT4}, {{TINYGLTF_COMPONENT_TYPE_FLOAT, false}}, "FLOAT MAT4"};
const Want kTimes{{TINYGLTF_TYPE_SCALAR}, {{TINYGLTF_COMPONENT_TYPE_FLOAT, false}}, "FLOAT SCALAR"};
const std::vector<std::pair<int, bool>> kFloatOrNormalized{{TINYGLTF_COMPONENT_TYPE_FLOAT, false},
                                                           {TINYGLTF_COMPONENT_TYPE_BYTE, true},
                                                           {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, true},
                                                           {TINYGLTF_COMPONENT_TYPE_SHORT, true},
                                                           {TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, true}};
const Want kRotation{{TINYGLTF_TYPE_VEC4}, kFloatOrNormalized, "VEC4 of FLOAT or normalized integers"};
const Want kMorphWeights{{TINYGLTF_TYPE_SCALAR}, kFloatOrNormalized, "SCALAR of FLOAT or normalized integers"};

// ---- the JSON, checked before tinygltf reads it ---------------------------------------------
//
// tinygltf skips a field of the wrong type (a negative "byteOffset" reads as 0, a "nodes" that is
// not an array as no nodes), fails with its own text on others, and does not look at the asset's
// version, the required extensions or the scene indices. These checks come first, so that every
// refusal is vdg's one line and tinygltf only ever reads a file of the right shape (glTF 2.0
// specification, section 5: the JSON schema of each object).

using io::Json;

// What one field of a glTF object must be.
enum class Kind {
  kIndex,  // an integer >= 0 (an index into another array)
  kCount,  // an integer >= 1
  kUint,   // an integer >= 0
  kString,
  kBool,
  kNumbers,    // an array of numbers
  kIndexList,  // an array of indices
  kObject,
  kObjects,   // an array of objects
  kIndexMap,  // an object whose values are integers >= 0 (a primitive's attributes)
  kNumber,
};

struct Field {
  const char* key;
  Kind kind;
  bool required = false;
};

const char* kindText(Kind kind) {
  switch (kind) {
    case Kind::kIndex:
      return "an index (an integer in [0, 2147483647])";
    case Kind::kUint:
      return "an integer >= 0";
    case Kind::kCount:
      return "an integer >= 1";
    case Kind::kString:
      return "a string";
    case Kind::kBool:
      return "true or false";
    case Kind::kNumbers:
      return "an array of numbers";
    case Kind::kIndexList:
      return "an array of indices";
    case Kind::kObject:
      return "an object";
    case Kind::kObjects:
      return "an array of objects";
    case Kind::kIndexMap:
      return "an object of indices";
    case Kind::kNumber:
      return "a number";
  }
  return "";
}

// A JSON integer (not 3.0: tinygltf skips those) in [lo, hi].
bool isInteger(const Json& v, std::uint64_t lo, std::uint64_t hi) {
  return v.is_number_unsigned() && v.get<std::uint64_t>() >= lo && v.get<std::uint64_t>() <= hi;
}

// An index: tinygltf reads indices as int, and skips one that does not fit.
constexpr std::uint64_t kMaxIndex = 0x7fffffff;
bool isIndex(const Json& v) { return isInteger(v, 0, kMaxIndex); }

bool hasKind(const Json& v, Kind kind) {
  auto all = [&](auto ok) { return std::all_of(v.begin(), v.end(), ok); };
  switch (kind) {
    case Kind::kIndex:
      return isIndex(v);
    case Kind::kUint:
      return isInteger(v, 0, UINT64_MAX);
    case Kind::kCount:
      return isInteger(v, 1, UINT64_MAX);
    case Kind::kNumber:
      return v.is_number();
    case Kind::kString:
      return v.is_string();
    case Kind::kBool:
      return v.is_boolean();
    case Kind::kNumbers:
      return v.is_array() && all([](const Json& x) { return x.is_number(); });
    case Kind::kIndexList:
      return v.is_array() && all(isIndex);
    case Kind::kObject:
      return v.is_object();
    case Kind::kObjects:
      return v.is_array() && all([](const Json& x) { return x.is_object(); });
    case Kind::kIndexMap:
      return v.is_object() && all(isIndex);
  }
  return false;
}

// The first item of `v` (an array or object) that is not of `kind`'s item kind, for the message.
std::string firstBadItem(const Json& v, Kind kind) {
  std::size_t i = 0;
  for (auto it = v.begin(); it != v.end(); ++it, ++i) {
    const bool ok = kind == Kind::kNumbers ? it->is_number() : kind == Kind::kObjects ? it->is_object() : isIndex(*it);
    if (!ok) return (v.is_object() ? quotedText(it.key()) : "[" + std::to_string(i) + "]") + " is " + io::describe(*it);
  }
  return "";
}

class JsonRules {
 public:
  JsonRules(const Json& doc, const std::string& source) : doc_(doc), source_(source) {}

  [[noreturn]] void fail(const std::string& element, const std::string& what) const {
    throw Error(source_ + ": " + element + ": " + what);
  }

  // The fields of object `obj` (named `element`) that `fields` lists: present when required, of
  // their kind when present. Other fields are not looked at (extensions, extras, names...).
  void fields(const Json& obj, const std::string& element, std::initializer_list<Field> list) const {
    if (!obj.is_object()) fail(element, "expected an object, got " + io::describe(obj));
    for (const Field& f : list) {
      const auto it = obj.find(f.key);
      if (it == obj.end()) {
        if (f.required) fail(element, std::string(f.key) + " is missing");
        continue;
      }
      if (hasKind(*it, f.kind)) continue;
      const bool container = it->is_array() || it->is_object();
      const bool item_kind = f.kind == Kind::kNumbers || f.kind == Kind::kIndexList || f.kind == Kind::kObjects ||
                             f.kind == Kind::kIndexMap;
      if (container && item_kind && (it->is_array() == (f.kind != Kind::kIndexMap)))
        fail(element, std::string(f.key) + ": expected " + kindText(f.kind) + ", but " + firstBadItem(*it, f.kind));
      fail(element, std::string(f.key) + ": expected " + kindText(f.kind) + ", got " + io::describe(*it));
    }
  }

  // Top-level array `key` (absent: empty), each item checked by `each(item, "key[i]")`.
  template <typename F>
  void each(const char* key, F each_item) const {
    const auto it = doc_.find(key);
    if (it == doc_.end()) return;
    if (!it->is_array()) fail(key, "expected an array, got " + io::describe(*it));
    for (std::size_t i = 0; i < it->size(); ++i) each_item((*it)[i], idx(key, i));
  }

  std::size_t size(const char* key) const {
    const auto it = doc_.find(key);
    return it != doc_.end() && it->is_array() ? it->size() : 0;
  }

  const Json& doc() const { return doc_; }
  const std::string& source() const { return source_; }

 private:
  const Json& doc_;
  std::string source_;
};

// "2.0" as {2, 0}; false when `text` is not MAJOR.MINOR (digits only, as the schema's pattern).
bool versionOf(const std::string& text, std::pair<long, long>* out) {
  const std::size_t dot = text.find('.');
  auto digits = [](const std::string& s) {
    return !s.empty() && s.size() <= 9 && std::all_of(s.begin(), s.end(), [](char c) { return c >= '0' && c <= '9'; });
  };
  if (dot == std::string::npos || !digits(text.substr(0, dot)) || !digits(text.substr(dot + 1))) return false;
  *out = {std::stol(text.substr(0, dot)), std::stol(text.substr(dot + 1))};
  return true;
}

// asset.version must be 2.x (glTF 2.0, section 3.2: a new major version is not compatible) and
// asset.minVersion, when given, at most the 2.0 vdg implements (and at most the version).
void checkAsset(const JsonRules& r) {
  const auto it = r.doc().find("asset");
  if (it == r.doc().end()) r.fail("asset", "is missing (every glTF file names its version there)");
  r.fields(*it, "asset", {{"version", Kind::kString, true}, {"minVersion", Kind::kString}});
  const std::string version = (*it)["version"].get<std::string>();
  std::pair<long, long> v;
  if (!versionOf(version, &v)) r.fail("asset", "version " + quotedText(version) + " is not MAJOR.MINOR");
  if (v.first != 2) r.fail("asset", "version " + quotedText(version) + ": vdg reads glTF 2.x");
  if (!it->contains("minVersion")) return;
  const std::string min_version = (*it)["minVersion"].get<std::string>();
  std::pair<long, long> m;
  if (!versionOf(min_version, &m)) r.fail("asset", "minVersion " + quotedText(min_version) + " is not MAJOR.MINOR");
  if (m > v)
    r.fail("asset", "minVersion " + quotedText(min_version) + " is greater than version " + quotedText(version));
  if (m > std::pair<long, long>{2, 0})
    r.fail("asset", "minVersion " + quotedText(min_version) + ": the file needs glTF " + min_version +
                        " features, vdg implements glTF 2.0");
}

// The extensions vdg reads (the ones its exports use: vdg/io/gltf_compress.h). Any other that the
// file requires would change what its data means, so such a file is refused.
constexpr const char* kReadExtensions[] = {"KHR_mesh_quantization", "EXT_meshopt_compression"};

void checkExtensions(const JsonRules& r) {
  for (const char* key : {"extensionsUsed", "extensionsRequired"}) {
    const auto it = r.doc().find(key);
    if (it == r.doc().end()) continue;
    if (!it->is_array() || !std::all_of(it->begin(), it->end(), [](const Json& x) { return x.is_string(); }))
      r.fail(key, "expected an array of strings, got " + io::describe(*it));
  }
  const auto it = r.doc().find("extensionsRequired");
  if (it == r.doc().end()) return;
  std::vector<std::string> unknown;
  for (const Json& x : *it)
    if (std::find(std::begin(kReadExtensions), std::end(kReadExtensions), x.get<std::string>()) ==
        std::end(kReadExtensions))
      unknown.push_back(x.get<std::string>());
  if (!unknown.empty())
    r.fail("extensionsRequired",
           quotedText(unknown[0]) + " is an extension vdg does not implement" +
               (unknown.size() > 1 ? " (and " + std::to_string(unknown.size() - 1) + " more)" : std::string()));
}

// True when the document lists `name` in extensionsUsed.
bool usesExtension(const Json& doc, const char* name) {
  const auto it = doc.find("extensionsUsed");
  return it != doc.end() && it->is_array() && std::find(it->begin(), it->end(), Json(name)) != it->end();
}

// The data: URI prefixes tinygltf decodes (base64 only).
bool isDataUri(const std::string& uri) { return uri.compare(0, 5, "data:") == 0; }

// A buffer's bytes: a data: URI (decoded to exactly byteLength bytes), an external file (checked
// by the file callbacks), or for a GLB's first buffer alone the BIN chunk (glTF 4.4.3.3).
void checkBuffer(const JsonRules& r, const Json& b, std::size_t i, bool binary, std::optional<std::size_t> bin) {
  const std::string e = idx("buffers", i);
  r.fields(b, e, {{"byteLength", Kind::kCount, true}, {"uri", Kind::kString}});
  const std::uint64_t length = b["byteLength"].get<std::uint64_t>();
  if (!b.contains("uri")) {
    if (isMeshoptFallback(b)) return;  // EXT_meshopt_compression: decoded before tinygltf reads it
    if (!binary) r.fail(e, "has no uri (only the first buffer of a .glb may stand for its BIN chunk)");
    if (i != 0) r.fail(e, "has no uri (only buffers[0] may stand for the GLB's BIN chunk)");
    if (!bin) r.fail(e, "has no uri, and the GLB has no BIN chunk");
    if (length > *bin)
      r.fail(e, "byteLength " + std::to_string(length) + " is more than the GLB's BIN chunk (" + std::to_string(*bin) +
                    " bytes)");
    return;
  }
  const std::string uri = b["uri"].get<std::string>();
  if (!isDataUri(uri)) return;  // an external file: the file callbacks
  if (!tg::IsDataURI(uri))
    r.fail(e, "a data: URI that is not base64 application/octet-stream or application/gltf-buffer");
  std::vector<unsigned char> bytes;
  std::string mime;
  if (!tg::DecodeDataURI(&bytes, mime, uri, 0, false) || bytes.empty()) r.fail(e, "its data: URI holds no base64 data");
  if (bytes.size() != length)
    r.fail(e,
           "its data: URI holds " + std::to_string(bytes.size()) + " bytes, byteLength says " + std::to_string(length));
}

// Exactly one of uri and bufferView; a data: URI tinygltf decodes, a bufferView that lies in its
// buffer (tinygltf hands the image loader a pointer into it before vdg's checks).
void checkImage(const JsonRules& r, const Json& image, const std::string& e) {
  r.fields(image, e, {{"uri", Kind::kString}, {"bufferView", Kind::kIndex}, {"mimeType", Kind::kString}});
  const bool has_uri = image.contains("uri"), has_view = image.contains("bufferView");
  if (has_uri == has_view)
    r.fail(e, has_uri ? "has both a uri and a bufferView" : "has neither a uri nor a bufferView");
  if (has_uri) {
    const std::string uri = image["uri"].get<std::string>();
    std::vector<unsigned char> bytes;
    std::string mime;
    if (isDataUri(uri) && tg::IsDataURI(uri) && (!tg::DecodeDataURI(&bytes, mime, uri, 0, false) || bytes.empty()))
      r.fail(e, "its data: URI holds no base64 data");
    return;
  }
  const auto view = image["bufferView"].get<std::size_t>();
  if (view >= r.size("bufferViews"))
    r.fail(e, "bufferView " + std::to_string(view) + " out of range (the file has " +
                  std::to_string(r.size("bufferViews")) + ")");
  const Json& v = r.doc()["bufferViews"][view];
  const auto buffer = v["buffer"].get<std::size_t>();
  if (buffer >= r.size("buffers"))
    r.fail(idx("bufferViews", view), "buffer " + std::to_string(buffer) + " out of range (the file has " +
                                         std::to_string(r.size("buffers")) + ")");
  const std::uint64_t have = r.doc()["buffers"][buffer]["byteLength"].get<std::uint64_t>();
  const std::uint64_t offset = v.value("byteOffset", std::uint64_t{0}), length = v["byteLength"].get<std::uint64_t>();
  if (offset > have || length > have - offset)
    r.fail(idx("bufferViews", view), "bytes " + std::to_string(offset) + " + " + std::to_string(length) +
                                         " lie outside " + idx("buffers", buffer) + " (" + std::to_string(have) +
                                         " bytes)");
}

void checkAccessor(const JsonRules& r, const Json& a, const std::string& e) {
  r.fields(a, e,
           {{"bufferView", Kind::kIndex},
            {"byteOffset", Kind::kUint},
            {"componentType", Kind::kUint, true},
            {"normalized", Kind::kBool},
            {"count", Kind::kCount, true},
            {"type", Kind::kString, true},
            {"sparse", Kind::kObject},
            {"min", Kind::kNumbers},
            {"max", Kind::kNumbers}});
  const auto component = a["componentType"].get<std::uint64_t>();
  if (component > 0xffff || componentSize(static_cast<int>(component)) == 0)
    r.fail(e, "componentType " + std::to_string(component) + " is not a glTF component type");
  const std::string type = a["type"].get<std::string>();
  static const std::set<std::string> kTypes{"SCALAR", "VEC2", "VEC3", "VEC4", "MAT2", "MAT3", "MAT4"};
  if (!kTypes.count(type)) r.fail(e, "type " + quotedText(type) + " is not a glTF accessor type");
  if (!a.contains("sparse")) return;
  const Json& s = a["sparse"];
  const std::string es = e + ": sparse";
  r.fields(s, es, {{"count", Kind::kCount, true}, {"indices", Kind::kObject, true}, {"values", Kind::kObject, true}});
  if (s["count"].get<std::uint64_t>() > a["count"].get<std::uint64_t>())  // tinygltf reads it as an int
    r.fail(es, "count " + std::to_string(s["count"].get<std::uint64_t>()) + " is not in [1, " +
                   std::to_string(a["count"].get<std::uint64_t>()) + "]");
  // tinygltf reads these as int (a larger byteOffset would be skipped, read as 0): index-sized.
  r.fields(s["indices"], es + ".indices",
           {{"bufferView", Kind::kIndex, true}, {"byteOffset", Kind::kIndex}, {"componentType", Kind::kIndex, true}});
  r.fields(s["values"], es + ".values", {{"bufferView", Kind::kIndex, true}, {"byteOffset", Kind::kIndex}});
}

void checkMesh(const JsonRules& r, const Json& mesh, const std::string& e) {
  r.fields(mesh, e, {{"primitives", Kind::kObjects, true}, {"weights", Kind::kNumbers}});
  if (mesh["primitives"].empty()) r.fail(e, "primitives is empty");
  for (std::size_t p = 0; p < mesh["primitives"].size(); ++p) {
    const Json& prim = mesh["primitives"][p];
    const std::string ep = e + ": " + idx("primitives", p);
    r.fields(prim, ep,
             {{"attributes", Kind::kIndexMap, true},
              {"indices", Kind::kIndex},
              {"material", Kind::kIndex},
              {"mode", Kind::kUint},
              {"targets", Kind::kObjects}});
    if (prim.contains("mode") && prim["mode"].get<std::uint64_t>() > 6)
      r.fail(ep,
             "mode " + std::to_string(prim["mode"].get<std::uint64_t>()) + " is not a glTF primitive mode (0 to 6)");
    // Every accessor a primitive names, in range (tinygltf refuses indices out of range with its
    // own text, and an index accessor without a bufferView).
    const std::size_t accessors = r.size("accessors");
    auto inRange = [&](const Json& a, const std::string& user) {
      const auto k = a.get<std::size_t>();
      if (k >= accessors)
        r.fail(user,
               "accessor " + std::to_string(k) + " out of range (the file has " + std::to_string(accessors) + ")");
    };
    for (const auto& [name, a] : prim["attributes"].items()) inRange(a, ep + ": " + shownText(name));
    if (prim.contains("indices")) {
      inRange(prim["indices"], ep + ": indices");
      const std::size_t k = prim["indices"].get<std::size_t>();
      const Json& a = r.doc()["accessors"][k];
      if (!a.contains("bufferView"))
        r.fail(ep + ": indices", idx("accessors", k) + " has no bufferView (indices cannot be sparse values alone)");
      if (a["bufferView"].get<std::size_t>() >= r.size("bufferViews"))
        r.fail(idx("accessors", k), "bufferView " + std::to_string(a["bufferView"].get<std::size_t>()) +
                                        " out of range (the file has " + std::to_string(r.size("bufferViews")) + ")");
    }
    if (!prim.contains("targets")) continue;
    for (std::size_t t = 0; t < prim["targets"].size(); ++t) {
      const std::string et = ep + ": " + idx("targets", t);
      if (!hasKind(prim["targets"][t], Kind::kIndexMap))
        r.fail(et, "expected an object of indices, but " + firstBadItem(prim["targets"][t], Kind::kIndexMap));
      for (const auto& [name, a] : prim["targets"][t].items()) inRange(a, et + ": " + shownText(name));
    }
  }
}

void checkNode(const JsonRules& r, const Json& node, const std::string& e) {
  r.fields(node, e,
           {{"camera", Kind::kIndex},
            {"children", Kind::kIndexList},
            {"skin", Kind::kIndex},
            {"matrix", Kind::kNumbers},
            {"mesh", Kind::kIndex},
            {"rotation", Kind::kNumbers},
            {"scale", Kind::kNumbers},
            {"translation", Kind::kNumbers},
            {"weights", Kind::kNumbers}});
  if (node.contains("matrix") && (node.contains("translation") || node.contains("rotation") || node.contains("scale")))
    r.fail(e, "has both a matrix and translation, rotation or scale (glTF allows one or the other)");
}

void checkAnimation(const JsonRules& r, const Json& anim, const std::string& e) {
  r.fields(anim, e, {{"channels", Kind::kObjects, true}, {"samplers", Kind::kObjects, true}});
  for (std::size_t c = 0; c < anim["channels"].size(); ++c) {
    const Json& ch = anim["channels"][c];
    const std::string ec = e + ": " + idx("channels", c);
    r.fields(ch, ec, {{"sampler", Kind::kIndex, true}, {"target", Kind::kObject, true}});
    // glTF 2.0 allows a target without a node (for extensions); tinygltf 2.7 does not.
    r.fields(ch["target"], ec + ": target", {{"node", Kind::kIndex, true}, {"path", Kind::kString, true}});
  }
  for (std::size_t s = 0; s < anim["samplers"].size(); ++s)
    r.fields(anim["samplers"][s], e + ": " + idx("samplers", s),
             {{"input", Kind::kIndex, true}, {"interpolation", Kind::kString}, {"output", Kind::kIndex, true}});
}

void checkMaterial(const JsonRules& r, const Json& m, const std::string& e) {
  r.fields(m, e, {{"pbrMetallicRoughness", Kind::kObject}, {"emissiveFactor", Kind::kNumbers}});
  if (m.contains("emissiveFactor") && m["emissiveFactor"].size() != 3)
    r.fail(e, "emissiveFactor has " + std::to_string(m["emissiveFactor"].size()) + " numbers, expected 3");
  if (!m.contains("pbrMetallicRoughness")) return;
  const Json& pbr = m["pbrMetallicRoughness"];
  r.fields(pbr, e + ": pbrMetallicRoughness",
           {{"baseColorFactor", Kind::kNumbers}, {"baseColorTexture", Kind::kObject}});
  if (pbr.contains("baseColorFactor") && pbr["baseColorFactor"].size() != 4)
    r.fail(e, "pbrMetallicRoughness.baseColorFactor has " + std::to_string(pbr["baseColorFactor"].size()) +
                  " numbers, expected 4");
  if (pbr.contains("baseColorTexture"))
    r.fields(pbr["baseColorTexture"], e + ": pbrMetallicRoughness.baseColorTexture",
             {{"index", Kind::kIndex, true}, {"texCoord", Kind::kUint}});
}

// vdg does not use cameras, but tinygltf refuses one without its type's projection.
void checkCamera(const JsonRules& r, const Json& c, const std::string& e) {
  r.fields(c, e, {{"type", Kind::kString, true}});
  const std::string type = c["type"].get<std::string>();
  if (type == "perspective") {
    r.fields(c, e, {{"perspective", Kind::kObject, true}});
    r.fields(c["perspective"], e + ": perspective", {{"yfov", Kind::kNumber, true}, {"znear", Kind::kNumber, true}});
  } else if (type == "orthographic") {
    r.fields(c, e, {{"orthographic", Kind::kObject, true}});
    r.fields(c["orthographic"], e + ": orthographic",
             {{"xmag", Kind::kNumber, true},
              {"ymag", Kind::kNumber, true},
              {"zfar", Kind::kNumber, true},
              {"znear", Kind::kNumber, true}});
  } else {
    r.fail(e, "type " + quotedText(type) + " is not perspective or orthographic");
  }
}

// "scene" and every scene's nodes in range; a node listed once per scene.
void checkScenes(const JsonRules& r) {
  const std::size_t nodes = r.size("nodes"), scenes = r.size("scenes");
  r.each("scenes", [&](const Json& s, const std::string& e) {
    r.fields(s, e, {{"nodes", Kind::kIndexList}});
    if (!s.contains("nodes")) return;
    std::set<std::size_t> seen;
    for (const Json& n : s["nodes"]) {
      const auto node = n.get<std::size_t>();
      if (node >= nodes)
        r.fail(e, "node " + std::to_string(node) + " out of range (the file has " + std::to_string(nodes) + ")");
      if (!seen.insert(node).second) r.fail(e, "lists node " + std::to_string(node) + " twice");
    }
  });
  const auto it = r.doc().find("scene");
  if (it == r.doc().end()) return;
  if (!isIndex(*it)) r.fail("scene", "expected an index, got " + io::describe(*it));
  if (it->get<std::size_t>() >= scenes)
    r.fail("scene", std::to_string(it->get<std::size_t>()) + " out of range (the file has " + std::to_string(scenes) +
                        (scenes == 1 ? " scene)" : " scenes)"));
}

// Every rule above, in the order of the document's arrays; `bin` is the GLB's BIN chunk size.
void checkJson(const Json& doc, const std::string& source, bool binary, std::optional<std::size_t> bin) {
  if (!doc.is_object()) throw Error(source + ": expected a glTF JSON object, got " + io::describe(doc));
  const JsonRules r(doc, source);
  checkAsset(r);
  checkExtensions(r);
  std::size_t i = 0;
  r.each("buffers", [&](const Json& b, const std::string&) { checkBuffer(r, b, i++, binary, bin); });
  r.each("bufferViews", [&](const Json& v, const std::string& e) {
    r.fields(v, e,
             {{"buffer", Kind::kIndex, true},
              {"byteOffset", Kind::kUint},
              {"byteLength", Kind::kCount, true},
              {"byteStride", Kind::kUint},
              {"target", Kind::kUint}});
  });
  r.each("accessors", [&](const Json& a, const std::string& e) { checkAccessor(r, a, e); });
  r.each("meshes", [&](const Json& m, const std::string& e) { checkMesh(r, m, e); });
  r.each("nodes", [&](const Json& n, const std::string& e) { checkNode(r, n, e); });
  r.each("skins", [&](const Json& s, const std::string& e) {
    r.fields(s, e,
             {{"inverseBindMatrices", Kind::kIndex}, {"skeleton", Kind::kIndex}, {"joints", Kind::kIndexList, true}});
  });
  r.each("animations", [&](const Json& a, const std::string& e) { checkAnimation(r, a, e); });
  r.each("materials", [&](const Json& m, const std::string& e) { checkMaterial(r, m, e); });
  r.each("textures", [&](const Json& t, const std::string& e) {
    r.fields(t, e, {{"sampler", Kind::kIndex}, {"source", Kind::kIndex}});
  });
  r.each("images", [&](const Json& image, const std::string& e) { checkImage(r, image, e); });
  r.each("samplers", [&](const Json& x, const std::string& e) { r.fields(x, e, {}); });
  r.each("cameras", [&](const Json& c, const std::string& e) { checkCamera(r, c, e); });
  checkScenes(r);
}

std::string percentDecoded(const std::string& uri);

// EXT_meshopt_compression (gltf_meshopt.h): the file's bytes with every compressed bufferView
// decoded into a plain buffer, or nullopt when none is compressed. `doc` passed checkJson.
std::optional<std::string> decodedMeshopt(std::string_view bytes, const Json& doc, const std::string& source,
                                          const std::string& folder, std::optional<std::size_t> bin) {
  const bool binary = bytes.substr(0, 4) == "glTF";
  std::map<std::size_t, std::string> cache;
  std::size_t external = 0;
  auto bufferBytes = [&](std::size_t i) -> std::string_view {
    const Json& b = doc["buffers"][i];
    if (!b.contains("uri")) return bytes.substr(20 + le32(bytes, 12) + 8, *bin);  // the BIN chunk (checkBuffer)
    if (const auto it = cache.find(i); it != cache.end()) return it->second;
    const std::string uri = b["uri"].get<std::string>();
    std::string data;
    if (isDataUri(uri)) {
      std::vector<unsigned char> decoded;
      std::string mime;
      (void)tg::DecodeDataURI(&decoded, mime, uri, 0, false);  // checked by checkBuffer
      data.assign(decoded.begin(), decoded.end());
    } else {
      const std::string path = percentDecoded(uri), problem = uriProblem(path);
      if (!problem.empty() || folder.empty())
        throw Error(source + ": " + idx("buffers", i) + ": " + quotedText(path) + " " +
                    (problem.empty() ? "is an external file, and these bytes come without a folder" : problem));
      const std::string full = folder == "." ? path : (std::filesystem::path(folder) / path).string();
      data = readFileLimited(full, "glTF buffer", kMaxMeshFileBytes - std::min(kMaxMeshFileBytes, external));
      external += data.size();
    }
    return cache.emplace(i, std::move(data)).first->second;
  };
  std::optional<std::string> json = decodeMeshoptViews(doc, source, kMaxMeshFileBytes, bufferBytes);
  if (!json || !binary) return json;
  // The GLB again: its header, the new JSON chunk, the BIN chunk as it was.
  json->resize((json->size() + 3) & ~std::size_t{3}, ' ');
  const std::string_view tail = bytes.substr(20 + le32(bytes, 12));
  std::string out = std::string(bytes.substr(0, 12)) + std::string(8, '\0') + *json + std::string(tail);
  const auto put = [&](std::size_t at, std::size_t value) {
    for (int k = 0; k < 4; ++k) out[at + k] = static_cast<char>((value >> (8 * k)) & 0xFF);
  };
  put(8, out.size());
  put(12, json->size());
  put(16, 0x4E4F534Au);
  return out;
}

class Gltf {
 public:
  Gltf(std::string_view bytes, const std::string& source, const std::string& folder)
      : source_(source), folder_(folder) {
    const bool binary = bytes.size() >= 4 && bytes.substr(0, 4) == "glTF";
    binary_ = binary;
    std::optional<std::size_t> bin;
    std::string_view json = binary ? checkGlb(bytes, source, &bin) : bytes;
    if (bytes.size() > std::numeric_limits<unsigned int>::max())
      throw Error(source + ": file is too large for the glTF reader");
    // vdg's JSON layer first: its nesting limit and its message for malformed JSON; then the
    // rules of the glTF schema, so that tinygltf reads only a file of the right shape.
    const Json doc = io::parseJson(json, source);
    checkJson(doc, source, binary, bin);
    quantized_ = usesExtension(doc, "KHR_mesh_quantization");
    // Compressed bufferViews decoded into a plain buffer, and the result checked again.
    std::optional<std::string> decoded = decodedMeshopt(bytes, doc, source, folder, bin);
    if (decoded) {
      bytes = *decoded;
      if (bytes.size() > std::numeric_limits<unsigned int>::max())
        throw Error(source + ": decoded, the file is too large for the glTF reader");
      json = binary ? checkGlb(bytes, source, &bin) : bytes;
      checkJson(io::parseJson(json, source), source, binary, bin);
    }

    FileAccess access{source, folder, 0, {}, {}};
    tg::TinyGLTF loader;
    tg::FsCallbacks fs{};
    fs.FileExists = fileExists;
    fs.ExpandFilePath = expandPath;
    fs.ReadWholeFile = readWholeFile;
    fs.WriteWholeFile = writeWholeFile;
    fs.user_data = &access;
    loader.SetFsCallbacks(fs);
    loader.SetImageLoader(keepImageBytes, nullptr);
    std::string err, warn;
    const bool ok =
        binary ? loader.LoadBinaryFromMemory(&model_, &err, &warn, reinterpret_cast<const unsigned char*>(bytes.data()),
                                             static_cast<unsigned int>(bytes.size()), kFolderToken)
               : loader.LoadASCIIFromString(&model_, &err, &warn, json.data(), static_cast<unsigned int>(json.size()),
                                            kFolderToken);
    if (!access.error.empty() && !ok) throw Error(source + ": buffers: " + joinedLines(access.error));
    if (!ok) refused(json, access);
    checkStructure();
  }

  const tg::Model& model() const { return model_; }
  const std::string& source() const { return source_; }
  const std::string& folder() const { return folder_; }
  bool binary() const { return binary_; }
  // What POSITION, NORMAL and morph targets may be: float, or integers under KHR_mesh_quantization.
  const Want& vec3() const { return quantized_ ? kQuantizedVec3 : kFloatVec3; }
  const Want& texcoord() const { return quantized_ ? kQuantizedTexcoord : kTexcoord; }

  [[noreturn]] void fail(const std::string& element, const std::string& what) const {
    throw Error(source_ + ": " + element + ": " + what);
  }

  // Index `i` into an array of `size` named `array`, for `element`.
  void checkIndex(const std::string& element, const char* array, long i, std::size_t size) const {
    if (i < 0 || static_cast<std::size_t>(i) >= size)
      fail(element,
           std::string(array) + " " + std::to_string(i) + " out of range (the file has " + std::to_string(size) + ")");
  }

  // Every accessor's components as doubles (count x components), sparse values applied, after
  // checking it against `want`. `user` names who refers to it ("meshes[0]: primitives[1]: POSITION").
  std::vector<double> read(int accessor, const Want& want, const std::string& user) const {
    checkIndex(user, "accessor", accessor, model_.accessors.size());
    const tg::Accessor& a = model_.accessors[static_cast<std::size_t>(accessor)];
    const std::string e = idx("accessors", static_cast<std::size_t>(accessor));
    if (std::find(want.types.begin(), want.types.end(), a.type) == want.types.end() ||
        std::find(want.components.begin(), want.components.end(), std::pair{a.componentType, a.normalized}) ==
            want.components.end())
      fail(user, e + " is " + std::string(a.normalized ? "normalized " : "") + componentName(a.componentType) + " " +
                     typeName(a.type) + ", expected " + want.description);
    const std::size_t n = componentCount(a.type);
    std::vector<double> out(a.count * n, 0.0);
    if (a.bufferView >= 0) {
      const View v = view(a.bufferView);
      const std::size_t elem = n * componentSize(a.componentType);
      const std::size_t stride = v.stride ? v.stride : elem;
      for (std::size_t i = 0; i < a.count; ++i)
        for (std::size_t c = 0; c < n; ++c)
          out[i * n + c] = component(v.data + a.byteOffset + i * stride + c * componentSize(a.componentType),
                                     a.componentType, a.normalized);
    }
    if (a.sparse.isSparse) {
      const std::size_t count = static_cast<std::size_t>(a.sparse.count);
      const View iv = view(a.sparse.indices.bufferView);
      const View vv = view(a.sparse.values.bufferView);
      const std::size_t isize = componentSize(a.sparse.indices.componentType);
      const std::size_t vsize = n * componentSize(a.componentType);
      long previous = -1;
      for (std::size_t k = 0; k < count; ++k) {
        const double target = component(iv.data + static_cast<std::size_t>(a.sparse.indices.byteOffset) + k * isize,
                                        a.sparse.indices.componentType, false);
        if (target >= static_cast<double>(a.count) || static_cast<long>(target) <= previous)
          fail(e, "sparse.indices[" + std::to_string(k) + "] = " + std::to_string(static_cast<long>(target)) +
                      (target >= static_cast<double>(a.count)
                           ? " out of range (the accessor has " + std::to_string(a.count) + " elements)"
                           : " does not increase strictly"));
        previous = static_cast<long>(target);
        for (std::size_t c = 0; c < n; ++c)
          out[static_cast<std::size_t>(target) * n + c] =
              component(vv.data + static_cast<std::size_t>(a.sparse.values.byteOffset) + k * vsize +
                            c * componentSize(a.componentType),
                        a.componentType, a.normalized);
      }
    }
    for (std::size_t i = 0; i < out.size(); ++i)
      if (!std::isfinite(out[i])) fail(user, e + ": element " + std::to_string(i / n) + " is not finite");
    return out;
  }

  std::size_t count(int accessor) const { return model_.accessors[static_cast<std::size_t>(accessor)].count; }
  std::size_t componentBytes(int accessor) const {
    return componentSize(model_.accessors[static_cast<std::size_t>(accessor)].componentType);
  }

  // Indices are tightly packed (glTF 3.6.2.4: their bufferView has no byteStride); a stride would
  // skip indices, so it is refused. `accessor` was read by read().
  void checkIndexView(int accessor, const std::string& user) const {
    const tg::Accessor& a = model_.accessors[static_cast<std::size_t>(accessor)];
    if (a.bufferView < 0) return;
    const std::size_t stride = model_.bufferViews[static_cast<std::size_t>(a.bufferView)].byteStride;
    if (stride != 0)
      fail(user, idx("bufferViews", static_cast<std::size_t>(a.bufferView)) + " has byteStride " +
                     std::to_string(stride) + ", which an index buffer must not have");
  }

  // The bytes of a bufferView checked by checkStructure() (index checked by the caller).
  std::string_view viewBytes(int index) const {
    const View v = view(index);
    return {reinterpret_cast<const char*>(v.data), v.length};
  }

 private:
  struct View {
    const unsigned char* data = nullptr;
    std::size_t length = 0;
    std::size_t stride = 0;
  };

  // tinygltf refused what checkJson let through: an external buffer whose file does not hold
  // byteLength bytes, or a rule vdg does not check. Never tinygltf's own text: it names vdg's
  // placeholder folder and echoes whole data: URIs.
  [[noreturn]] void refused(std::string_view json, const FileAccess& access) const {
    const io::Json doc = io::parseJson(json, source_);
    const auto buffers = doc.find("buffers");
    for (std::size_t i = 0; buffers != doc.end() && i < buffers->size(); ++i) {
      const io::Json& b = (*buffers)[i];
      const std::string uri = b.value("uri", std::string());
      const auto read = access.sizes.find(percentDecoded(uri));
      if (uri.empty() || isDataUri(uri) || read == access.sizes.end()) continue;
      const auto length = b["byteLength"].get<std::uint64_t>();
      if (read->second == 0) fail(idx("buffers", i), quotedText(uri) + " is empty");
      if (read->second != length)
        fail(idx("buffers", i), quotedText(uri) + " holds " + std::to_string(read->second) +
                                    " bytes, byteLength says " + std::to_string(length));
    }
    throw Error(source_ +
                ": not a glTF file vdg can read (it breaks a rule of the glTF 2.0 specification that the Khronos glTF "
                "validator names)");
  }

  // A bufferView checked by checkStructure().
  View view(int index) const {
    const tg::BufferView& v = model_.bufferViews[static_cast<std::size_t>(index)];
    const tg::Buffer& b = model_.buffers[static_cast<std::size_t>(v.buffer)];
    return {b.data.data() + v.byteOffset, v.byteLength, v.byteStride};
  }

  // Every buffer, bufferView and accessor checked once, so that read() and describe only index
  // into memory that exists.
  void checkStructure() {
    const auto& m = model_;
    for (std::size_t i = 0; i < m.bufferViews.size(); ++i) {
      const tg::BufferView& v = m.bufferViews[i];
      const std::string e = idx("bufferViews", i);
      checkIndex(e, "buffer", v.buffer, m.buffers.size());
      const std::size_t have = m.buffers[static_cast<std::size_t>(v.buffer)].data.size();
      if (v.byteOffset > have || v.byteLength > have - v.byteOffset)
        fail(e, "bytes " + std::to_string(v.byteOffset) + " + " + std::to_string(v.byteLength) + " lie outside " +
                    idx("buffers", static_cast<std::size_t>(v.buffer)) + " (" + std::to_string(have) + " bytes)");
      if (v.byteStride != 0 && (v.byteStride < 4 || v.byteStride > 252 || v.byteStride % 4 != 0))
        fail(e, "byteStride " + std::to_string(v.byteStride) + " is not a multiple of 4 in [4, 252]");
    }
    for (std::size_t i = 0; i < m.accessors.size(); ++i) {
      const tg::Accessor& a = m.accessors[i];
      const std::string e = idx("accessors", i);
      const std::size_t csize = componentSize(a.componentType);
      const std::size_t n = componentCount(a.type);
      if (csize == 0) fail(e, "componentType " + std::to_string(a.componentType) + " is not a glTF component type");
      if (n == 0) fail(e, "type is not a glTF accessor type");
      if (a.count == 0) fail(e, "count is 0");
      if (a.count > kMaxGltfElements)
        fail(e, "count " + std::to_string(a.count) + " is more than the limit of " + std::to_string(kMaxGltfElements));
      if (a.bufferView >= 0) {
        checkIndex(e, "bufferView", a.bufferView, m.bufferViews.size());
        const tg::BufferView& v = m.bufferViews[static_cast<std::size_t>(a.bufferView)];
        const std::size_t elem = n * csize;
        const std::size_t stride = v.byteStride ? v.byteStride : elem;
        if (stride < elem)
          fail(e, "byteStride " + std::to_string(stride) + " is less than an element's " + std::to_string(elem) +
                      " bytes");
        if (a.byteOffset % csize != 0) fail(e, "byteOffset " + std::to_string(a.byteOffset) + " is not aligned");
        const std::uint64_t end = std::uint64_t{a.byteOffset} + std::uint64_t{stride} * (a.count - 1) + elem;
        if (a.byteOffset > v.byteLength || end > v.byteLength)
          fail(e, std::to_string(a.count) + " elements from byte " + std::to_string(a.byteOffset) + " need " +
                      std::to_string(end) + " bytes, " + idx("bufferViews", static_cast<std::size_t>(a.bufferView)) +
                      " has " + std::to_string(v.byteLength));
      } else if (!a.sparse.isSparse) {
        fail(e, "has neither a bufferView nor sparse values");
      }
      if (a.sparse.isSparse) {
        const std::string es = e + ": sparse";
        if (a.sparse.count <= 0 || static_cast<std::size_t>(a.sparse.count) > a.count)
          fail(es, "count " + std::to_string(a.sparse.count) + " is not in [1, " + std::to_string(a.count) + "]");
        const std::size_t isize = componentSize(a.sparse.indices.componentType);
        if (a.sparse.indices.componentType == TINYGLTF_COMPONENT_TYPE_BYTE ||
            a.sparse.indices.componentType == TINYGLTF_COMPONENT_TYPE_SHORT ||
            a.sparse.indices.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT || isize == 0)
          fail(es, "indices: componentType must be UNSIGNED_BYTE, UNSIGNED_SHORT or UNSIGNED_INT");
        const std::size_t count = static_cast<std::size_t>(a.sparse.count);
        auto checkPart = [&](int view_index, int offset, std::size_t bytes, const char* part) {
          const std::string ep = es + "." + part;
          checkIndex(ep, "bufferView", view_index, m.bufferViews.size());
          if (offset < 0) fail(ep, "byteOffset " + std::to_string(offset) + " is negative");
          const std::size_t length = m.bufferViews[static_cast<std::size_t>(view_index)].byteLength;
          const std::uint64_t end = std::uint64_t(offset) + std::uint64_t{bytes};
          if (end > length)
            fail(ep, std::to_string(count) + " elements need " + std::to_string(end) + " bytes, " +
                         idx("bufferViews", static_cast<std::size_t>(view_index)) + " has " + std::to_string(length));
        };
        checkPart(a.sparse.indices.bufferView, a.sparse.indices.byteOffset, count * isize, "indices");
        checkPart(a.sparse.values.bufferView, a.sparse.values.byteOffset, count * n * csize, "values");
        checkSparseView(es + ".indices", a.sparse.indices.bufferView);
        checkSparseView(es + ".values", a.sparse.values.bufferView);
      }
    }
    checkNodes();
  }

  // Sparse indices and values are read tightly packed (glTF 3.6.2.3: their bufferViews have no
  // byteStride); a stride would be ignored, so it is refused.
  void checkSparseView(const std::string& element, int view_index) const {
    const std::size_t stride = model_.bufferViews[static_cast<std::size_t>(view_index)].byteStride;
    if (stride != 0)
      fail(element, idx("bufferViews", static_cast<std::size_t>(view_index)) + " has byteStride " +
                        std::to_string(stride) + ", which sparse indices and values must not have");
  }

  // Every node's mesh and skin in range (not only the selected node's), and every node a scene
  // lists a root (glTF 3.5.1: "the node hierarchy MUST be a set of disjoint strict trees", and a
  // scene's nodes are its roots); the rest of the hierarchy is checked by readNodeHierarchy.
  void checkNodes() const {
    const auto& m = model_;
    std::vector<int> parent(m.nodes.size(), -1);
    for (std::size_t i = 0; i < m.nodes.size(); ++i) {
      const tg::Node& n = m.nodes[i];
      const std::string e = idx("nodes", i);
      if (n.mesh >= 0) checkIndex(e, "mesh", n.mesh, m.meshes.size());
      if (n.skin >= 0) checkIndex(e, "skin", n.skin, m.skins.size());
      for (const int c : n.children)
        if (c >= 0 && static_cast<std::size_t>(c) < m.nodes.size() && static_cast<std::size_t>(c) != i)
          parent[static_cast<std::size_t>(c)] = static_cast<int>(i);  // a node its own child: readNodeHierarchy
    }
    for (std::size_t s = 0; s < m.scenes.size(); ++s)
      for (const int n : m.scenes[s].nodes)
        if (n >= 0 && static_cast<std::size_t>(n) < m.nodes.size() && parent[static_cast<std::size_t>(n)] >= 0)
          fail(idx("scenes", s), "node " + std::to_string(n) + " is not a root (it is a child of nodes[" +
                                     std::to_string(parent[static_cast<std::size_t>(n)]) + "])");
  }

  std::string source_;
  std::string folder_;
  bool binary_ = false;
  bool quantized_ = false;  // KHR_mesh_quantization in extensionsUsed
  tg::Model model_;
};

// mesh.extras.targetNames when it is an array of `targets` strings, else empty.
std::vector<std::string> targetNames(const tg::Mesh& mesh, std::size_t targets) {
  if (!mesh.extras.IsObject() || !mesh.extras.Has("targetNames")) return {};
  const tg::Value& names = mesh.extras.Get("targetNames");
  if (!names.IsArray() || names.ArrayLen() != targets) return {};
  std::vector<std::string> list;
  for (std::size_t t = 0; t < targets; ++t) {
    if (!names.Get(static_cast<int>(t)).IsString()) return {};
    list.push_back(names.Get(static_cast<int>(t)).Get<std::string>());
  }
  return list;
}

// The node instancing the selected mesh (-1: none) and the mesh.
struct Selection {
  int node = -1;
  int mesh = -1;
};

Selection select(const Gltf& g, const GltfSelect& want) {
  const tg::Model& m = g.model();
  auto meshOf = [&](int node) { return m.nodes[static_cast<std::size_t>(node)].mesh; };
  if (!want.mesh_or_node.empty()) {
    for (std::size_t i = 0; i < m.nodes.size(); ++i)
      if (m.nodes[i].name == want.mesh_or_node) {
        if (meshOf(static_cast<int>(i)) < 0) g.fail(idx("nodes", i), "'" + want.mesh_or_node + "' has no mesh");
        return {static_cast<int>(i), meshOf(static_cast<int>(i))};
      }
    for (std::size_t k = 0; k < m.meshes.size(); ++k)
      if (m.meshes[k].name == want.mesh_or_node) {
        for (std::size_t i = 0; i < m.nodes.size(); ++i)
          if (meshOf(static_cast<int>(i)) == static_cast<int>(k)) return {static_cast<int>(i), static_cast<int>(k)};
        return {-1, static_cast<int>(k)};
      }
    throw Error(g.source() + ": no node or mesh named '" + want.mesh_or_node + "'");
  }
  // Depth first through the default scene (or scene 0); the walk is bounded by the node count,
  // so a cycle cannot loop (validate reports it later).
  const int scene = m.defaultScene >= 0 ? m.defaultScene : (m.scenes.empty() ? -1 : 0);
  if (scene >= 0 && static_cast<std::size_t>(scene) < m.scenes.size()) {
    std::vector<int> stack(m.scenes[static_cast<std::size_t>(scene)].nodes.rbegin(),
                           m.scenes[static_cast<std::size_t>(scene)].nodes.rend());
    std::size_t steps = 0;
    while (!stack.empty() && steps++ <= m.nodes.size()) {
      const int n = stack.back();
      stack.pop_back();
      if (n < 0 || static_cast<std::size_t>(n) >= m.nodes.size()) continue;
      if (meshOf(n) >= 0) return {n, meshOf(n)};
      const auto& ch = m.nodes[static_cast<std::size_t>(n)].children;
      stack.insert(stack.end(), ch.rbegin(), ch.rend());
    }
  }
  for (std::size_t i = 0; i < m.nodes.size(); ++i)
    if (meshOf(static_cast<int>(i)) >= 0) return {static_cast<int>(i), meshOf(static_cast<int>(i))};
  if (!m.meshes.empty()) return {-1, 0};
  throw Error(g.source() + ": the file has no mesh");
}

RigNode readNode(const Gltf& g, std::size_t i) {
  const tg::Node& n = g.model().nodes[i];
  const std::string e = idx("nodes", i);
  RigNode out;
  out.name = n.name;
  auto sized = [&](const std::vector<double>& v, std::size_t size, const char* what) {
    if (!v.empty() && v.size() != size)
      g.fail(e, std::string(what) + " has " + std::to_string(v.size()) + " numbers, expected " + std::to_string(size));
    return !v.empty();
  };
  if (sized(n.matrix, 16, "matrix")) {
    Eigen::Matrix4d mat;
    for (int k = 0; k < 16; ++k) mat(k % 4, k / 4) = n.matrix[static_cast<std::size_t>(k)];
    out.matrix = mat;
  }
  if (sized(n.translation, 3, "translation")) out.translation = {n.translation[0], n.translation[1], n.translation[2]};
  if (sized(n.rotation, 4, "rotation"))
    out.rotation = Eigen::Quaterniond(n.rotation[3], n.rotation[0], n.rotation[1], n.rotation[2]);
  if (sized(n.scale, 3, "scale")) out.scale = {n.scale[0], n.scale[1], n.scale[2]};
  return out;
}

// Linear to display sRGB (IEC 61966-2-1), for baseColorFactor (vdg/geom/material.h: materials
// hold display values).
float linearToSrgb(double c) {
  c = c >= 0.0 ? std::min(c, 1.0) : 0.0;
  return static_cast<float>(c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055);
}

// A URI with its %XX escapes decoded (RFC 3986, section 2.1); a malformed escape stays as it is.
std::string percentDecoded(const std::string& uri) {
  auto hex = [](char c) {
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    if (c >= 'A' && c <= 'F') return c - 'A' + 10;
    return -1;
  };
  std::string out;
  for (std::size_t i = 0; i < uri.size(); ++i) {
    if (uri[i] == '%' && i + 2 < uri.size() && hex(uri[i + 1]) >= 0 && hex(uri[i + 2]) >= 0) {
      out += static_cast<char>(hex(uri[i + 1]) * 16 + hex(uri[i + 2]));
      i += 2;
    } else {
      out += uri[i];
    }
  }
  return out;
}

// The materials of one mesh read: each glTF material converted once, each image decoded once.
class MaterialReader {
 public:
  MaterialReader(const Gltf& g, const MeshReadOptions& options) : g_(g), sink_(options) {}

  // glTF material `index` as a vdg Material (vdg/io/gltf.h); a texture that cannot be used is
  // one warning (or, strict, a vdg::Error) and the material keeps its colour alone.
  Material read(std::size_t index, bool has_uvs) {
    const tg::Model& m = g_.model();
    const tg::Material& gm = m.materials[index];
    const std::string e = idx("materials", index);
    Material out;
    out.name = gm.name.empty() ? e : gm.name;
    const auto& factor = gm.pbrMetallicRoughness.baseColorFactor;
    if (factor.size() >= 3)
      for (std::size_t c = 0; c < 3; ++c) out.base_color[c] = linearToSrgb(factor[c]);
    const tg::TextureInfo& info = gm.pbrMetallicRoughness.baseColorTexture;
    if (info.index < 0) return out;
    auto warn = [&](const std::string& why) {
      sink_.warn(g_.source() + ": " + e + ": baseColorTexture: " + why + "; material '" + out.name +
                 "' shows its colour alone");
    };
    if (static_cast<std::size_t>(info.index) >= m.textures.size()) {
      warn("texture " + std::to_string(info.index) + " out of range (the file has " +
           std::to_string(m.textures.size()) + ")");
      return out;
    }
    const tg::Texture& texture = m.textures[static_cast<std::size_t>(info.index)];
    const std::string et = idx("textures", static_cast<std::size_t>(info.index));
    if (texture.source < 0 || static_cast<std::size_t>(texture.source) >= m.images.size()) {
      warn(et + " has no PNG or JPEG image (source " + std::to_string(texture.source) + ")");
      return out;
    }
    const std::size_t image_index = static_cast<std::size_t>(texture.source);
    const tg::Image& image = m.images[image_index];
    const std::string ei = idx("images", image_index);
    out.texture_path = image.bufferView >= 0 ? ei + " (bufferView " + std::to_string(image.bufferView) + ")"
                       : !image.uri.empty()  ? percentDecoded(image.uri)
                                             : ei + " (data: URI)";
    if (info.texCoord != 0) {
      warn("uses TEXCOORD_" + std::to_string(info.texCoord) + "; vdg maps textures by TEXCOORD_0 only");
      return out;
    }
    if (!has_uvs) {
      warn("the mesh has no TEXCOORD_0 (in every triangle primitive) to map it by");
      return out;
    }
    std::string why;
    if (image.bufferView >= 0) {
      if (static_cast<std::size_t>(image.bufferView) >= m.bufferViews.size())
        why = ei + ": bufferView " + std::to_string(image.bufferView) + " out of range (the file has " +
              std::to_string(m.bufferViews.size()) + ")";
      else
        out.texture = cache_.bytes(ei, g_.viewBytes(image.bufferView), g_.source() + ": " + ei, &why);
    } else if (!image.uri.empty()) {
      const std::string uri = out.texture_path;
      const std::string problem = uriProblem(uri);
      if (!problem.empty())
        why = quotedText(uri) + " " + problem + " (images must lie in the glTF file's folder or below)";
      else if (g_.folder().empty())
        why = quotedText(uri) + " is an external file, and these bytes come without a folder";
      else
        out.texture = fileTexture(io::inFolder(g_.folder(), uri), ei, &why);
    } else if (!image.image.empty()) {
      out.texture =
          cache_.bytes(ei, std::string_view(reinterpret_cast<const char*>(image.image.data()), image.image.size()),
                       g_.source() + ": " + ei, &why);
    } else {
      why = ei + " has neither a bufferView nor a uri";
    }
    if (!out.texture && warned_images_.insert(image_index).second) warn(why);
    return out;
  }

  void warn(const std::string& line) const { sink_.warn(line); }

 private:
  const Gltf& g_;
  io::WarningSink sink_;
  io::TextureCache cache_;

  // An image file; one outside the read root is refused (ReadRootError), not a warning.
  std::shared_ptr<const TextureImage> fileTexture(const std::string& path, const std::string& ei, std::string* why) {
    try {
      return cache_.file(path, why);
    } catch (const ReadRootError& e) {
      throw ReadRootError(g_.source() + ": " + ei + ": " + e.what());
    }
  }
  std::set<std::size_t> warned_images_;
};

// The node hierarchy: every node, and each child's parent (a node with two parents, or its own
// child, is refused).
void readNodeHierarchy(const Gltf& g, RawRig& raw) {
  const tg::Model& m = g.model();
  if (m.nodes.size() > kMaxRigNodes)
    g.fail("nodes", std::to_string(m.nodes.size()) + " nodes, more than the limit of " + std::to_string(kMaxRigNodes));
  raw.nodes.reserve(m.nodes.size());
  for (std::size_t i = 0; i < m.nodes.size(); ++i) raw.nodes.push_back(readNode(g, i));
  for (std::size_t i = 0; i < m.nodes.size(); ++i) {
    const auto& children = m.nodes[i].children;
    for (std::size_t c = 0; c < children.size(); ++c) {
      const std::string e = idx("nodes", i) + ": " + idx("children", c);
      g.checkIndex(e, "node", children[c], m.nodes.size());
      RigNode& child = raw.nodes[static_cast<std::size_t>(children[c])];
      if (children[c] == static_cast<int>(i)) g.fail(e, "the node is its own child (the node hierarchy has a cycle)");
      if (child.parent >= 0)
        g.fail(idx("nodes", static_cast<std::size_t>(children[c])),
               "is a child of both nodes[" + std::to_string(child.parent) + "] and nodes[" + std::to_string(i) + "]");
      child.parent = static_cast<int>(i);
    }
  }
}

int attributeOf(const tg::Primitive& p, const char* name) {
  const auto it = p.attributes.find(name);
  return it == p.attributes.end() ? -1 : it->second;
}

// The selected mesh's triangle primitives and what all of them carry.
struct MeshLayout {
  std::string where;               // "meshes[i]"
  std::vector<std::size_t> prims;  // the triangle primitives, concatenated in this order
  bool with_normals = true, with_uvs = true;
  bool with_vertex_ids = true;  // _VDG_VERTEX on every primitive: a vdg export (weldExportedVertices)
  std::size_t targets = 0;
  std::vector<bool> target_has_normals;
};

MeshLayout meshLayout(const Gltf& g, const tg::Mesh& mesh, const std::string& where, bool skinned) {
  MeshLayout l;
  l.where = where;
  for (std::size_t p = 0; p < mesh.primitives.size(); ++p)
    if (mesh.primitives[p].mode == TINYGLTF_MODE_TRIANGLES || mesh.primitives[p].mode == -1) l.prims.push_back(p);
  if (l.prims.empty()) g.fail(where, "has no triangle primitives");
  l.targets = mesh.primitives[l.prims[0]].targets.size();
  for (std::size_t p : l.prims) {
    const tg::Primitive& prim = mesh.primitives[p];
    const std::string ep = where + ": " + idx("primitives", p);
    if (attributeOf(prim, "POSITION") < 0) g.fail(ep, "has no POSITION");
    l.with_normals = l.with_normals && attributeOf(prim, "NORMAL") >= 0;
    l.with_uvs = l.with_uvs && attributeOf(prim, "TEXCOORD_0") >= 0;
    l.with_vertex_ids = l.with_vertex_ids && attributeOf(prim, "_VDG_VERTEX") >= 0;
    if (prim.targets.size() != l.targets)
      g.fail(ep, "has " + std::to_string(prim.targets.size()) + " morph targets, primitives[" +
                     std::to_string(l.prims[0]) + "] has " + std::to_string(l.targets));
    if (skinned && (attributeOf(prim, "JOINTS_0") < 0 || attributeOf(prim, "WEIGHTS_0") < 0))
      g.fail(ep, "is skinned but lacks JOINTS_0 or WEIGHTS_0");
  }
  if (l.targets > kMaxMorphTargets)
    g.fail(where,
           std::to_string(l.targets) + " morph targets, more than the limit of " + std::to_string(kMaxMorphTargets));
  l.target_has_normals.assign(l.targets, false);
  for (std::size_t p : l.prims)
    for (std::size_t t = 0; t < l.targets; ++t)
      if (mesh.primitives[p].targets[t].count("NORMAL")) l.target_has_normals[t] = true;
  return l;
}

// Appends primitive `p` (its vertices numbered from `base`) to raw's mesh, normals, skin weights and
// morph targets; returns its vertex count.
std::size_t appendPrimitive(const Gltf& g, const tg::Primitive& prim, std::size_t p, const MeshLayout& l, bool skinned,
                            std::size_t base, RawRig& raw) {
  const std::string ep = l.where + ": " + idx("primitives", p);
  const int pos = attributeOf(prim, "POSITION");
  const std::vector<double> positions = g.read(pos, g.vec3(), ep + ": POSITION");
  const std::size_t nv = g.count(pos);
  if (base + nv > kMaxGltfElements)
    g.fail(l.where, "more than " + std::to_string(kMaxGltfElements) + " vertices in all primitives");
  auto sameCount = [&](int accessor, const char* name) {
    if (g.count(accessor) != nv)
      g.fail(ep, std::string(name) + " has " + std::to_string(g.count(accessor)) + " elements, POSITION has " +
                     std::to_string(nv));
  };
  raw.mesh.positions.insert(raw.mesh.positions.end(), positions.begin(), positions.end());
  if (l.with_normals) {
    const int a = attributeOf(prim, "NORMAL");
    const auto normals = g.read(a, g.vec3(), ep + ": NORMAL");
    sameCount(a, "NORMAL");
    raw.normals.insert(raw.normals.end(), normals.begin(), normals.end());
  }
  if (l.with_uvs) {
    const int a = attributeOf(prim, "TEXCOORD_0");
    auto uvs = g.read(a, g.texcoord(), ep + ": TEXCOORD_0");
    sameCount(a, "TEXCOORD_0");
    for (std::size_t i = 1; i < uvs.size(); i += 2) uvs[i] = 1.0 - uvs[i];  // top-left origin to bottom-left
    raw.mesh.uvs.insert(raw.mesh.uvs.end(), uvs.begin(), uvs.end());
  }
  if (skinned) {
    const int ja = attributeOf(prim, "JOINTS_0");
    const int wa = attributeOf(prim, "WEIGHTS_0");
    const auto joints = g.read(ja, kJoints, ep + ": JOINTS_0");
    const auto weights = g.read(wa, kWeights, ep + ": WEIGHTS_0");
    sameCount(ja, "JOINTS_0");
    sameCount(wa, "WEIGHTS_0");
    for (double j : joints) raw.joints.push_back(static_cast<std::uint16_t>(j));
    raw.weights.insert(raw.weights.end(), weights.begin(), weights.end());
  }
  for (std::size_t t = 0; t < l.targets; ++t) {
    const auto& target = prim.targets[t];
    const std::string et = ep + ": " + idx("targets", t);
    const auto pit = target.find("POSITION");
    if (pit != target.end()) {
      const auto d = g.read(pit->second, g.vec3(), et + ": POSITION");
      sameCount(pit->second, "a target's POSITION");
      raw.target_positions[t].insert(raw.target_positions[t].end(), d.begin(), d.end());
    } else {
      raw.target_positions[t].resize(raw.target_positions[t].size() + 3 * nv, 0.0f);
    }
    if (l.with_normals && l.target_has_normals[t]) {
      const auto nit = target.find("NORMAL");
      if (nit != target.end()) {
        const auto d = g.read(nit->second, g.vec3(), et + ": NORMAL");
        sameCount(nit->second, "a target's NORMAL");
        raw.target_normals[t].insert(raw.target_normals[t].end(), d.begin(), d.end());
      } else {
        raw.target_normals[t].resize(raw.target_normals[t].size() + 3 * nv, 0.0f);
      }
    }
  }
  // Triangles: the indices, or 0..n-1 without them.
  if (prim.indices >= 0) {
    const auto indices = g.read(prim.indices, kIndices, ep + ": indices");
    g.checkIndexView(prim.indices, ep + ": indices");
    if (indices.size() % 3 != 0)
      g.fail(ep, "indices: " + std::to_string(indices.size()) + " indices, not a multiple of 3");
    // The largest value of the component type restarts a strip in graphics APIs; glTF 3.7.2.1
    // forbids it in indices.
    const double restart = std::ldexp(1.0, 8 * static_cast<int>(g.componentBytes(prim.indices))) - 1.0;
    for (std::size_t k = 0; k < indices.size(); ++k) {
      if (indices[k] == restart && indices[k] < static_cast<double>(nv))
        g.fail(ep, "indices[" + std::to_string(k) + "] = " + std::to_string(static_cast<std::uint64_t>(indices[k])) +
                       ", the primitive restart value of its component type, which glTF indices must not use");
      if (indices[k] >= static_cast<double>(nv))
        g.fail(ep, "indices[" + std::to_string(k) + "] = " + std::to_string(static_cast<std::uint64_t>(indices[k])) +
                       " out of range (the primitive has " + std::to_string(nv) + " vertices)");
      raw.mesh.triangles.push_back(static_cast<std::int32_t>(base + static_cast<std::size_t>(indices[k])));
    }
  } else {
    if (nv % 3 != 0) g.fail(ep, std::to_string(nv) + " vertices without indices, not a multiple of 3");
    for (std::size_t k = 0; k < nv; ++k) raw.mesh.triangles.push_back(static_cast<std::int32_t>(base + k));
  }
  return nv;
}

// Materials in the order of first use; a primitive without one (or with a material index out of
// range, a warning) has none. `face_material` and `face_primitive` give each triangle's glTF
// material (-1: none) and primitive.
void readMeshMaterials(const Gltf& g, const MeshReadOptions& options, const MeshLayout& l,
                       const std::vector<int>& face_material, const std::vector<std::size_t>& face_primitive,
                       RawRig& raw) {
  const tg::Model& m = g.model();
  MaterialReader reader(g, options);
  std::map<int, int> mesh_index;
  std::set<std::size_t> warned_primitives;
  raw.mesh.face_materials.assign(face_material.size(), -1);
  for (std::size_t f = 0; f < face_material.size(); ++f) {
    const int k = face_material[f];
    if (k < 0) continue;
    if (static_cast<std::size_t>(k) >= m.materials.size()) {
      if (warned_primitives.insert(face_primitive[f]).second)
        reader.warn(g.source() + ": " + l.where + ": " + idx("primitives", face_primitive[f]) + ": material " +
                    std::to_string(k) + " out of range (the file has " + std::to_string(m.materials.size()) +
                    "); the primitive has no material");
      continue;
    }
    auto it = mesh_index.find(k);
    if (it == mesh_index.end()) {
      it = mesh_index.emplace(k, static_cast<int>(raw.mesh.materials.size())).first;
      raw.mesh.materials.push_back(reader.read(static_cast<std::size_t>(k), l.with_uvs));
    }
    raw.mesh.face_materials[f] = it->second;
  }
  if (raw.mesh.materials.empty()) raw.mesh.face_materials.clear();
}

// A per-vertex array (`width` values a vertex) keeping the vertices `first` names, in that order.
template <typename T>
void keepVertices(std::vector<T>& values, std::size_t width, const std::vector<std::size_t>& first) {
  if (values.empty()) return;
  std::vector<T> out(first.size() * width);
  for (std::size_t m = 0; m < first.size(); ++m)
    for (std::size_t c = 0; c < width; ++c) out[m * width + c] = values[first[m] * width + c];
  values = std::move(out);
}

// A vdg export (_VDG_VERTEX on every primitive; docs/gltf-export.md): the exported vertices are
// welded back into the model's, so the mesh has the model's vertex count and order whatever the
// seams split or the primitives repeat. Each model vertex takes its first copy's position, normal,
// skin and morph target deltas (every copy carries the same); texture coordinates and file normals
// stay per exported vertex (TriMesh keeps them per corner: uv_triangles, normal_triangles).
void weldExportedVertices(const Gltf& g, const MeshLayout& l, const std::vector<double>& ids, RawRig& raw) {
  const std::size_t n = raw.mesh.vertexCount();
  if (ids.size() != n)
    g.fail(l.where, "_VDG_VERTEX has " + std::to_string(ids.size()) + " values for " + std::to_string(n) + " vertices");
  std::size_t v_count = 0;
  for (std::size_t e = 0; e < n; ++e) {
    if (!(ids[e] >= 0.0 && ids[e] < static_cast<double>(n) && ids[e] == std::floor(ids[e])))
      g.fail(l.where, "_VDG_VERTEX[" + std::to_string(e) + "] = " + std::to_string(ids[e]) +
                          " is not a vertex index below " + std::to_string(n));
    v_count = std::max(v_count, static_cast<std::size_t>(ids[e]) + 1);
  }
  std::vector<std::size_t> first(v_count, n);
  const std::vector<float>& pos = raw.mesh.positions;
  for (std::size_t e = 0; e < n; ++e) {
    const auto m = static_cast<std::size_t>(ids[e]);
    if (first[m] == n) {
      first[m] = e;
    } else if (!std::equal(pos.begin() + static_cast<std::ptrdiff_t>(e * 3),
                           pos.begin() + static_cast<std::ptrdiff_t>(e * 3 + 3),
                           pos.begin() + static_cast<std::ptrdiff_t>(first[m] * 3))) {
      g.fail(l.where, "vertex " + std::to_string(e) + " (_VDG_VERTEX " + std::to_string(m) +
                          ") lies elsewhere than vertex " + std::to_string(first[m]) + ", the same model vertex");
    }
  }
  for (std::size_t m = 0; m < v_count; ++m)
    if (first[m] == n) g.fail(l.where, "_VDG_VERTEX names no vertex for model vertex " + std::to_string(m));
  keepVertices(raw.mesh.positions, 3, first);
  keepVertices(raw.normals, 3, first);
  keepVertices(raw.joints, 4, first);
  keepVertices(raw.weights, 4, first);
  for (auto& t : raw.target_positions) keepVertices(t, 3, first);
  for (auto& t : raw.target_normals) keepVertices(t, 3, first);
  for (std::int32_t& v : raw.mesh.triangles) v = static_cast<std::int32_t>(ids[static_cast<std::size_t>(v)]);
}

// The plain material of a vdg export (extras.vdg.plain): its faces have no material in vdg.
bool plainExportMaterial(const tg::Model& m, int material) {
  if (material < 0 || static_cast<std::size_t>(material) >= m.materials.size()) return false;
  const tg::Value& extras = m.materials[static_cast<std::size_t>(material)].extras;
  if (!extras.IsObject() || !extras.Has("vdg") || !extras.Get("vdg").IsObject()) return false;
  const tg::Value& plain = extras.Get("vdg").Get("plain");
  return plain.IsBool() && plain.Get<bool>();
}

// The mesh: its triangle primitives concatenated, with normals, texture coordinates, skin weights,
// morph targets and materials where all primitives have them.
void readRigMesh(const Gltf& g, const tg::Mesh& mesh, const MeshLayout& l, bool skinned, const MeshReadOptions& options,
                 RawRig& raw) {
  raw.target_positions.assign(l.targets, {});
  raw.target_normals.assign(l.targets, {});
  std::size_t base = 0;
  std::vector<int> face_material;           // per triangle: the primitive's glTF material (-1: none)
  std::vector<std::size_t> face_primitive;  // per triangle: its primitive
  std::vector<double> vertex_ids;           // _VDG_VERTEX of every vertex read
  for (std::size_t p : l.prims) {
    const tg::Primitive& prim = mesh.primitives[p];
    const std::size_t triangles_before = raw.mesh.triangles.size() / 3;
    base += appendPrimitive(g, prim, p, l, skinned, base, raw);
    if (l.with_vertex_ids) {
      const int a = attributeOf(prim, "_VDG_VERTEX");
      const auto ids = g.read(a, kVertexIds, l.where + ": " + idx("primitives", p) + ": _VDG_VERTEX");
      vertex_ids.insert(vertex_ids.end(), ids.begin(), ids.end());
    }
    const bool plain = l.with_vertex_ids && plainExportMaterial(g.model(), prim.material);
    face_material.insert(face_material.end(), raw.mesh.triangles.size() / 3 - triangles_before,
                         plain ? -1 : prim.material);
    face_primitive.insert(face_primitive.end(), raw.mesh.triangles.size() / 3 - triangles_before, p);
  }
  if (l.with_uvs) raw.mesh.uv_triangles = raw.mesh.triangles;
  if (l.with_normals) {
    raw.mesh.normals = raw.normals;
    raw.mesh.normal_triangles = raw.mesh.triangles;
  }
  if (l.with_vertex_ids) weldExportedVertices(g, l, vertex_ids, raw);
  if (options.materials) readMeshMaterials(g, options, l, face_material, face_primitive, raw);
}

// Morph target names and default weights (the node's weights override the mesh's).
void readTargetWeights(const Gltf& g, const tg::Mesh& mesh, const MeshLayout& l, int node, RawRig& raw) {
  const tg::Model& m = g.model();
  raw.target_names = targetNames(mesh, l.targets);
  const std::vector<double>* weights = &mesh.weights;
  if (node >= 0 && !m.nodes[static_cast<std::size_t>(node)].weights.empty())
    weights = &m.nodes[static_cast<std::size_t>(node)].weights;
  if (weights->empty()) {
    raw.default_weights.assign(l.targets, 0.0);
  } else {
    if (weights->size() != l.targets)
      g.fail(weights == &mesh.weights ? l.where : idx("nodes", static_cast<std::size_t>(node)),
             "weights has " + std::to_string(weights->size()) + " numbers for " + std::to_string(l.targets) +
                 " morph targets");
    raw.default_weights = *weights;
  }
}

// The skin of the mesh's node.
RigSkin readSkin(const Gltf& g, int node, int skin_index) {
  const tg::Model& m = g.model();
  const std::string en = idx("nodes", static_cast<std::size_t>(node));
  g.checkIndex(en, "skin", skin_index, m.skins.size());
  const tg::Skin& skin = m.skins[static_cast<std::size_t>(skin_index)];
  const std::string es = idx("skins", static_cast<std::size_t>(skin_index));
  RigSkin rs;
  if (skin.joints.size() > kMaxRigJoints)
    g.fail(es, std::to_string(skin.joints.size()) + " joints, more than the limit of " + std::to_string(kMaxRigJoints));
  for (std::size_t j = 0; j < skin.joints.size(); ++j) {
    g.checkIndex(es + ": " + idx("joints", j), "node", skin.joints[j], m.nodes.size());
    rs.joints.push_back(skin.joints[j]);
  }
  if (skin.inverseBindMatrices >= 0) {
    const auto mats = g.read(skin.inverseBindMatrices, kMat4, es + ": inverseBindMatrices");
    if (g.count(skin.inverseBindMatrices) < skin.joints.size())
      g.fail(es, "inverseBindMatrices has " + std::to_string(g.count(skin.inverseBindMatrices)) + " matrices for " +
                     std::to_string(skin.joints.size()) + " joints");
    for (std::size_t j = 0; j < skin.joints.size(); ++j) {
      Eigen::Matrix4d mat;
      for (int k = 0; k < 16; ++k) mat(k % 4, k / 4) = mats[16 * j + static_cast<std::size_t>(k)];
      rs.inverse_bind.push_back(mat);
    }
  } else {
    rs.inverse_bind.assign(skin.joints.size(), Eigen::Matrix4d::Identity());
  }
  return rs;
}

// The channels of animation `a`; `output_want` gets, per sampler, the output its channel needs.
// Weights channels of nodes other than `mesh_node` do not move the mesh and are left out.
std::vector<RigChannel> readChannels(const Gltf& g, std::size_t a, int mesh_node,
                                     std::vector<const Want*>& output_want) {
  const tg::Model& m = g.model();
  const tg::Animation& anim = m.animations[a];
  std::vector<RigChannel> channels;
  std::set<std::pair<int, RigPath>> targets;
  for (std::size_t c = 0; c < anim.channels.size(); ++c) {
    const tg::AnimationChannel& ch = anim.channels[c];
    const std::string ec = idx("animations", a) + ": " + idx("channels", c);
    g.checkIndex(ec, "sampler", ch.sampler, anim.samplers.size());
    if (ch.target_node < 0) continue;  // no target node: defined by an extension vdg does not read
    g.checkIndex(ec, "target node", ch.target_node, m.nodes.size());
    RigChannel rc;
    rc.node = ch.target_node;
    rc.sampler = ch.sampler;
    static const Want kVec3 = kFloatVec3;
    const Want* w = nullptr;
    if (ch.target_path == "translation") {
      rc.path = RigPath::kTranslation, w = &kVec3;
    } else if (ch.target_path == "rotation") {
      rc.path = RigPath::kRotation, w = &kRotation;
    } else if (ch.target_path == "scale") {
      rc.path = RigPath::kScale, w = &kVec3;
    } else if (ch.target_path == "weights") {
      rc.path = RigPath::kWeights, w = &kMorphWeights;
      if (ch.target_node != mesh_node) continue;
    } else {
      g.fail(ec, "target path '" + ch.target_path + "' is not translation, rotation, scale or weights");
    }
    // glTF 3.11: "each target (a combination of a node and a path) MUST NOT be used more than once"
    // in an animation; vdg would apply the last channel alone.
    if (!targets.emplace(rc.node, rc.path).second)
      g.fail(ec, "animates " + ch.target_path + " of node " + std::to_string(rc.node) + ", as an earlier channel does");
    output_want[static_cast<std::size_t>(ch.sampler)] = w;
    channels.push_back(rc);
  }
  return channels;
}

RigSampler readSampler(const Gltf& g, const tg::AnimationSampler& sampler, const std::string& es, const Want* want) {
  RigSampler rs;
  if (sampler.interpolation == "LINEAR" || sampler.interpolation.empty())
    rs.interpolation = RigInterpolation::kLinear;
  else if (sampler.interpolation == "STEP")
    rs.interpolation = RigInterpolation::kStep;
  else if (sampler.interpolation == "CUBICSPLINE")
    rs.interpolation = RigInterpolation::kCubicSpline;
  else
    g.fail(es, "interpolation '" + sampler.interpolation + "' is not LINEAR, STEP or CUBICSPLINE");
  const auto input = g.read(sampler.input, kTimes, es + ": input");
  rs.input.assign(input.begin(), input.end());
  static const Want kAnyOutput{{TINYGLTF_TYPE_SCALAR, TINYGLTF_TYPE_VEC3, TINYGLTF_TYPE_VEC4},
                               kFloatOrNormalized,
                               "FLOAT or normalized integers"};
  const auto output = g.read(sampler.output, want ? *want : kAnyOutput, es + ": output");
  rs.output.assign(output.begin(), output.end());
  return rs;
}

// Every animation of the file.
void readAnimations(const Gltf& g, int mesh_node, RawRig& raw) {
  const tg::Model& m = g.model();
  if (m.animations.size() > kMaxRigAnimations)
    g.fail("animations", std::to_string(m.animations.size()) + " animations, more than the limit of " +
                             std::to_string(kMaxRigAnimations));
  for (std::size_t a = 0; a < m.animations.size(); ++a) {
    const tg::Animation& anim = m.animations[a];
    RigAnimation ra;
    ra.name = anim.name;
    std::vector<const Want*> output_want(anim.samplers.size(), nullptr);
    ra.channels = readChannels(g, a, mesh_node, output_want);
    for (std::size_t s = 0; s < anim.samplers.size(); ++s)
      ra.samplers.push_back(
          readSampler(g, anim.samplers[s], idx("animations", a) + ": " + idx("samplers", s), output_want[s]));
    raw.animations.push_back(std::move(ra));
  }
}

// The rest pose as every command sees it (morphed by the default weights, then skinned or placed
// by the node transforms) must be finite and fit a float (mesh_extent.h): a node scale of 1e38 or
// coordinates near the float limit would otherwise give infinite bounds, voxel sizes and camera
// distances later, silently (an empty morph, a blank render). `where` names the mesh and its node.
void checkRestPose(const Gltf& g, const Rig& rig, const std::string& where) {
  std::vector<float> p(3 * rig.vertexCount());
  if (!rig.evaluate(-1, 0.0, p)) g.fail(where, "the rest pose could not be evaluated (internal error)");
  io::checkMeshExtent(p, g.source() + ": " + where, " after the node transforms");
}

RawRig buildRig(const Gltf& g, const GltfSelect& want, const MeshReadOptions& options) {
  const tg::Model& m = g.model();
  RawRig raw;
  raw.source = g.source();
  readNodeHierarchy(g, raw);
  const Selection sel = select(g, want);
  g.checkIndex(sel.node >= 0 ? idx("nodes", static_cast<std::size_t>(sel.node)) : std::string("file"), "mesh", sel.mesh,
               m.meshes.size());
  raw.mesh_node = sel.node;
  const tg::Mesh& mesh = m.meshes[static_cast<std::size_t>(sel.mesh)];
  const int skin_index = sel.node >= 0 ? m.nodes[static_cast<std::size_t>(sel.node)].skin : -1;
  const MeshLayout layout = meshLayout(g, mesh, idx("meshes", static_cast<std::size_t>(sel.mesh)), skin_index >= 0);
  readRigMesh(g, mesh, layout, skin_index >= 0, options, raw);
  readTargetWeights(g, mesh, layout, sel.node, raw);
  if (skin_index >= 0) raw.skin = readSkin(g, sel.node, skin_index);
  readAnimations(g, sel.node, raw);
  raw.validate();
  checkRestPose(g, Rig::build(raw),
                idx("meshes", static_cast<std::size_t>(sel.mesh)) +
                    (sel.node >= 0 ? " (" + idx("nodes", static_cast<std::size_t>(sel.node)) + ")" : std::string()));
  return raw;
}

std::string describe(const Gltf& g) {
  const tg::Model& m = g.model();
  std::ostringstream out;
  auto quoted = [](const std::string& s) { return "'" + s + "'"; };
  out << "file        " << g.source() << " (glTF " << (m.asset.version.empty() ? "?" : m.asset.version) << ", "
      << (g.binary() ? "binary .glb" : "JSON .gltf") << ")\n";
  if (!m.asset.generator.empty()) out << "generator   " << m.asset.generator << "\n";
  out << "scenes      " << m.scenes.size();
  if (m.defaultScene >= 0) out << " (default " << m.defaultScene << ")";
  out << "\nnodes       " << m.nodes.size() << "\n";
  out << "meshes      " << m.meshes.size() << "\n";
  for (std::size_t k = 0; k < m.meshes.size(); ++k) {
    const tg::Mesh& mesh = m.meshes[k];
    std::size_t vertices = 0, triangles = 0, prims = 0, targets = 0;
    for (const tg::Primitive& p : mesh.primitives) {
      if (p.mode != TINYGLTF_MODE_TRIANGLES && p.mode != -1) continue;
      ++prims;
      const auto it = p.attributes.find("POSITION");
      if (it == p.attributes.end()) continue;
      g.checkIndex(idx("meshes", k), "accessor", it->second, m.accessors.size());
      const std::size_t nv = g.count(it->second);
      vertices += nv;
      if (p.indices >= 0) {
        g.checkIndex(idx("meshes", k), "accessor", p.indices, m.accessors.size());
        triangles += g.count(p.indices) / 3;
      } else {
        triangles += nv / 3;
      }
      targets = std::max(targets, p.targets.size());
    }
    out << "  [" << k << "] " << quoted(mesh.name) << ": " << prims << " triangle primitive" << (prims == 1 ? "" : "s")
        << ", " << vertices << " vertices, " << triangles << " triangles, " << targets << " morph target"
        << (targets == 1 ? "" : "s") << "\n";
    if (targets > 0) {
      const auto names = targetNames(mesh, targets);
      out << "      targets:";
      for (std::size_t t = 0; t < targets; ++t)
        out << " " << (names.empty() ? std::string("(unnamed)") : quoted(names[t]));
      out << "\n";
    }
  }
  out << "skins       " << m.skins.size() << "\n";
  for (std::size_t k = 0; k < m.skins.size(); ++k)
    out << "  [" << k << "] " << quoted(m.skins[k].name) << ": " << m.skins[k].joints.size() << " joints"
        << (m.skins[k].inverseBindMatrices >= 0 ? "" : ", no inverse bind matrices") << "\n";
  out << "animations  " << m.animations.size() << "\n";
  for (std::size_t a = 0; a < m.animations.size(); ++a) {
    const tg::Animation& anim = m.animations[a];
    const std::string ea = idx("animations", a);
    std::vector<std::pair<double, double>> ranges;
    double duration = 0;
    for (std::size_t s = 0; s < anim.samplers.size(); ++s) {
      const auto times = g.read(anim.samplers[s].input, kTimes, ea + ": " + idx("samplers", s) + ": input");
      ranges.emplace_back(times.front(), times.back());
      duration = std::max(duration, times.back());
    }
    char buf[64];
    std::snprintf(buf, sizeof(buf), "%.4g s", duration);
    out << "  [" << a << "] " << quoted(anim.name) << ": " << anim.channels.size() << " channel"
        << (anim.channels.size() == 1 ? "" : "s") << ", " << buf << "\n";
    for (std::size_t c = 0; c < anim.channels.size(); ++c) {
      const tg::AnimationChannel& ch = anim.channels[c];
      g.checkIndex(ea + ": " + idx("channels", c), "sampler", ch.sampler, anim.samplers.size());
      const tg::AnimationSampler& s = anim.samplers[static_cast<std::size_t>(ch.sampler)];
      std::string target = "(no node)";
      if (ch.target_node >= 0 && static_cast<std::size_t>(ch.target_node) < m.nodes.size())
        target = "node " + std::to_string(ch.target_node) + " " +
                 quoted(m.nodes[static_cast<std::size_t>(ch.target_node)].name);
      const auto& r = ranges[static_cast<std::size_t>(ch.sampler)];
      std::snprintf(buf, sizeof(buf), "%.4g - %.4g s", r.first, r.second);
      out << "      " << target << " " << ch.target_path << " "
          << (s.interpolation.empty() ? "LINEAR" : s.interpolation) << ", " << g.count(s.input) << " keyframes, " << buf
          << "\n";
    }
  }
  return out.str();
}

std::string folderOf(const std::string& path) {
  const std::string parent = std::filesystem::path(path).parent_path().string();
  return parent.empty() ? std::string(".") : parent;
}

}  // namespace

RawRig parseGltfRig(std::string_view bytes, const std::string& source, const std::string& folder,
                    const GltfSelect& select, const MeshReadOptions& options) {
  const Gltf g(bytes, source, folder);
  return buildRig(g, select, options);
}

std::string describeGltfData(std::string_view bytes, const std::string& source, const std::string& folder) {
  const Gltf g(bytes, source, folder);
  // A file whose default mesh does not load is reported, not described.
  if (!g.model().meshes.empty()) (void)buildRig(g, {}, MeshReadOptions{false, false, nullptr});
  return describe(g);
}

RawRig readGltfRig(const std::string& path, const GltfSelect& select, const MeshReadOptions& options) {
  return parseGltfRig(readFileLimited(path, "glTF", kMaxMeshFileBytes), path, folderOf(path), select, options);
}

TriMesh readGltfMesh(const std::string& path, const GltfSelect& select, const MeshReadOptions& options) {
  const Rig rig = Rig::build(readGltfRig(path, select, options));
  TriMesh mesh = rig.mesh();
  // The file's normals posed with the positions, one a vertex: the rig's normals are welded like
  // its positions (a vdg export's split copies share their model vertex's normal), so they are
  // indexed by the triangles, not by the per-exported-vertex normal_triangles the mesh read with.
  std::vector<float> normals(mesh.normals.empty() ? 0 : mesh.positions.size());
  if (!rig.evaluate(-1, 0.0, mesh.positions, normals)) throw Error(path + ": the rest pose could not be evaluated");
  if (!mesh.normals.empty()) {
    for (float& c : normals)
      if (!std::isfinite(c)) c = 0.0f;  // a transform that overflows a normal leaves no direction
    mesh.normals = std::move(normals);
    mesh.normal_triangles = mesh.triangles;
  }
  validateMesh(mesh, path);
  return mesh;
}

std::string describeGltf(const std::string& path) {
  return describeGltfData(readFileLimited(path, "glTF", kMaxMeshFileBytes), path, folderOf(path));
}

}  // namespace vdg
