#include "vdg/io/obj.h"

#include <tiny_obj_loader.h>
#include <cctype>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <limits>
#include <sstream>
#include <string_view>
#include <vector>

#include "vdg/geom/error.h"
#include "vdg/io/atomic_file.h"
#include "vdg/io/gltf.h"
#include "vdg/io/read_file.h"

namespace vdg {
namespace {

void appendFloat(std::string& out, float value) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value);
  out.append(buffer, result.ptr);
}

// tinyobjloader's messages can span several lines; keep them to one.
std::string oneLine(std::string text) {
  while (!text.empty() && (text.back() == '\n' || text.back() == '\r')) text.pop_back();
  for (char& c : text)
    if (c == '\n') c = ' ';
  return text;
}

// The strict pass over the text: every v/vt/vn/f line is checked before tinyobjloader, which is
// lenient about exactly the things that silently change a shape, builds the mesh.
//
// tinyobjloader only ever sees what was checked: check() returns the text with every line vdg
// does not read (skin weights `vw`, tags `t`, lines `l`, points `p`, materials, smoothing groups,
// unknown statements) blanked, comments cut off, carriage returns made spaces and every number
// rewritten, one output line per input line (so tinyobjloader's line numbers stay right). Those statements are ignored by vdg
// anyway, and tinyobjloader parses some of them unsafely (a `vw` joint id of 1e21 is converted to
// int, undefined behaviour; a `t` line can ask for 3 x 8192 values).
class ObjChecker {
 public:
  explicit ObjChecker(const std::string& source) : source_(source) {}

  std::string check(std::string_view text) {
    std::string checked;
    checked.reserve(text.size());
    std::size_t line_no = 0;
    std::size_t start = 0;
    while (start <= text.size()) {
      std::size_t end = text.find('\n', start);
      if (end == std::string_view::npos) end = text.size();
      ++line_no;
      checkLine(text.substr(start, end - start), line_no, checked);
      checked += '\n';
      start = end + 1;
    }
    for (const auto& [index, line] : {std::pair{max_v_, max_v_line_}}) {
      if (index > counts_[0])
        fail(line, "a face refers to vertex " + std::to_string(index) + " but the file has " +
                       std::to_string(counts_[0]) + " vertices");
    }
    if (max_vt_ > counts_[1])
      fail(max_vt_line_, "a face refers to texture coordinate " + std::to_string(max_vt_) + " but the file has " +
                             std::to_string(counts_[1]));
    if (max_vn_ > counts_[2])
      fail(max_vn_line_,
           "a face refers to normal " + std::to_string(max_vn_) + " but the file has " + std::to_string(counts_[2]));
    return checked;
  }

 private:
  [[noreturn]] void fail(std::size_t line, const std::string& what) const {
    throw Error(source_ + ":" + std::to_string(line) + ": " + what);
  }

  static std::string shown(std::string_view token) {
    std::string s(token.substr(0, 32));
    if (token.size() > 32) s += "...";
    return s;
  }

  static std::vector<std::string_view> tokens(std::string_view line) {
    std::vector<std::string_view> out;
    std::size_t i = 0;
    while (i < line.size()) {
      while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r')) ++i;
      const std::size_t a = i;
      while (i < line.size() && line[i] != ' ' && line[i] != '\t' && line[i] != '\r') ++i;
      if (i > a) out.push_back(line.substr(a, i - a));
    }
    return out;
  }

  // A coordinate: a finite number that fits a float. It is passed on to tinyobjloader rewritten in
  // the shortest form that reads back as the same double, because tinyobjloader's own number parser
  // overflows an int on long exponents ("0e2147483648") and a double on long mantissas.
  void number(std::string_view token, std::size_t line, const std::string& what, std::string& out) const {
    std::string_view t = token;
    if (!t.empty() && t.front() == '+') t.remove_prefix(1);
    double value = 0;
    const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), value);
    if (ec == std::errc::result_out_of_range) fail(line, what + ": coordinate '" + shown(token) + "' is out of range");
    if (ec != std::errc() || end != t.data() + t.size()) fail(line, what + ": '" + shown(token) + "' is not a number");
    if (!std::isfinite(value)) fail(line, what + ": coordinate '" + shown(token) + "' is not a finite number");
    if (std::abs(value) > std::numeric_limits<float>::max())
      fail(line, what + ": coordinate '" + shown(token) + "' is too large for a float");
    char buffer[32];
    const auto written = std::to_chars(buffer, buffer + sizeof(buffer), value);
    out += ' ';
    out.append(buffer, written.ptr);
  }

  // One index of a face corner: a non-zero whole number; negative ones count back from the last
  // element read so far. Returns the 1-based index it refers to.
  std::int64_t index(std::string_view token, std::size_t line, int kind, const char* noun) {
    std::int64_t value = 0;
    std::string_view t = token;
    if (!t.empty() && t.front() == '+') t.remove_prefix(1);
    const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), value);
    if (ec == std::errc::result_out_of_range ||
        (ec == std::errc() && end == t.data() + t.size() && (value > kMaxIndex || value < -kMaxIndex)))
      fail(line, std::string("face: ") + noun + " index '" + shown(token) + "' is out of range");
    if (ec != std::errc() || end != t.data() + t.size())
      fail(line, std::string("face: ") + noun + " index '" + shown(token) + "' is not a whole number");
    if (value == 0) fail(line, std::string("face: ") + noun + " index 0 (OBJ indices start at 1)");
    if (value < 0) {
      const std::int64_t resolved = counts_[kind] + value + 1;
      if (resolved < 1)
        fail(line, std::string("face: relative ") + noun + " index " + std::to_string(value) +
                       " reaches before the first " + noun + " (" + std::to_string(counts_[kind]) + " read so far)");
      return resolved;
    }
    return value;
  }

  // Checks one line and appends what tinyobjloader should see of it to `out`: v, vt and vn with
  // their numbers rewritten, f, o and g (names of shapes in messages) as they are, anything else
  // as nothing.
  void checkLine(std::string_view line, std::size_t line_no, std::string& out) {
    const auto hash = line.find('#');
    if (hash != std::string_view::npos) line = line.substr(0, hash);
    const auto t = tokens(line);
    if (t.empty()) return;
    const std::string_view tag = t[0];
    if (tag == "o" || tag == "g" || tag == "f") {
      for (char c : line) out += c == '\r' ? ' ' : c;
      if (tag != "f") return;
    } else if (tag == "v" || tag == "vt" || tag == "vn") {
      out += tag;
    } else {
      return;
    }
    if (tag == "v") {
      const std::string what = "vertex " + std::to_string(counts_[0] + 1);
      if (t.size() < 4) fail(line_no, what + ": expected 3 coordinates x y z, got " + std::to_string(t.size() - 1));
      if (t.size() > 8)
        fail(line_no, what + ": expected x y z [w] or x y z r g b, got " + std::to_string(t.size() - 1) + " numbers");
      for (std::size_t i = 1; i < t.size(); ++i) number(t[i], line_no, what, out);
      if (++counts_[0] > kMaxIndex) fail(line_no, "more than " + std::to_string(kMaxIndex) + " vertices");
    } else if (tag == "vt") {
      const std::string what = "texture coordinate " + std::to_string(counts_[1] + 1);
      if (t.size() < 2 || t.size() > 4) fail(line_no, what + ": expected 1 to 3 numbers");
      for (std::size_t i = 1; i < t.size(); ++i) number(t[i], line_no, what, out);
      if (++counts_[1] > kMaxIndex) fail(line_no, "more than " + std::to_string(kMaxIndex) + " texture coordinates");
    } else if (tag == "vn") {
      const std::string what = "normal " + std::to_string(counts_[2] + 1);
      if (t.size() != 4) fail(line_no, what + ": expected 3 numbers");
      for (std::size_t i = 1; i < t.size(); ++i) number(t[i], line_no, what, out);
      if (++counts_[2] > kMaxIndex) fail(line_no, "more than " + std::to_string(kMaxIndex) + " normals");
    } else if (tag == "f") {
      if (t.size() < 4) fail(line_no, "face: expected at least 3 corners, got " + std::to_string(t.size() - 1));
      for (std::size_t i = 1; i < t.size(); ++i) {
        const std::string_view corner = t[i];
        const auto s1 = corner.find('/');
        const std::string_view v = corner.substr(0, s1);
        const std::int64_t vi = index(v, line_no, 0, "vertex");
        if (vi > max_v_) max_v_ = vi, max_v_line_ = line_no;
        if (s1 == std::string_view::npos) continue;
        const std::string_view rest = corner.substr(s1 + 1);
        const auto s2 = rest.find('/');
        const std::string_view vt = rest.substr(0, s2);
        if (!vt.empty()) {
          const std::int64_t ti = index(vt, line_no, 1, "texture coordinate");
          if (ti > max_vt_) max_vt_ = ti, max_vt_line_ = line_no;
        }
        if (s2 != std::string_view::npos) {
          const std::string_view vn = rest.substr(s2 + 1);
          if (vn.empty() || vn.find('/') != std::string_view::npos)
            fail(line_no, "face: corner '" + shown(corner) + "' is not v, v/vt, v//vn or v/vt/vn");
          const std::int64_t ni = index(vn, line_no, 2, "normal");
          if (ni > max_vn_) max_vn_ = ni, max_vn_line_ = line_no;
        }
      }
    }
  }

  static constexpr std::int64_t kMaxIndex = std::numeric_limits<std::int32_t>::max();
  const std::string& source_;
  std::int64_t counts_[3] = {0, 0, 0};  // v, vt, vn read so far
  std::int64_t max_v_ = 0, max_vt_ = 0, max_vn_ = 0;
  std::size_t max_v_line_ = 0, max_vt_line_ = 0, max_vn_line_ = 0;
};

}  // namespace

TriMesh parseObj(const std::string& text, const std::string& source) {
  const std::string checked = ObjChecker(source).check(text);

  tinyobj::ObjReaderConfig config;
  config.triangulate = true;
  config.vertex_color = false;
  tinyobj::ObjReader reader;
  // Materials are not used: an empty material text means `mtllib` lines open no file.
  if (!reader.ParseFromString(checked, std::string(), config)) {
    throw Error(source + ": cannot read OBJ: " + oneLine(reader.Error()));
  }
  const auto& attrib = reader.GetAttrib();
  TriMesh mesh;
  mesh.positions.assign(attrib.vertices.begin(), attrib.vertices.end());
  mesh.uvs.assign(attrib.texcoords.begin(), attrib.texcoords.end());
  const std::size_t nv = mesh.vertexCount();
  bool all_have_uv = !mesh.uvs.empty();
  for (const auto& shape : reader.GetShapes()) {
    std::size_t offset = 0;
    for (std::size_t f = 0; f < shape.mesh.num_face_vertices.size(); ++f) {
      const std::size_t n = shape.mesh.num_face_vertices[f];
      if (n != 3)
        throw Error(source + ": face " + std::to_string(f + 1) + " of '" + shape.name + "' could not be triangulated");
      for (std::size_t k = 0; k < 3; ++k) {
        const auto& idx = shape.mesh.indices[offset + k];
        if (idx.vertex_index < 0 || static_cast<std::size_t>(idx.vertex_index) >= nv)
          throw Error(source + ": a face refers to vertex " + std::to_string(std::int64_t{idx.vertex_index} + 1) +
                      " but the file has " + std::to_string(nv) + " vertices");
        mesh.triangles.push_back(idx.vertex_index);
        if (idx.texcoord_index < 0) all_have_uv = false;
        mesh.uv_triangles.push_back(idx.texcoord_index);
      }
      offset += n;
    }
  }
  if (!all_have_uv) {
    mesh.uvs.clear();
    mesh.uv_triangles.clear();
  }
  if (mesh.triangles.empty()) throw Error(source + ": OBJ file has no faces");
  validateMesh(mesh, source);
  return mesh;
}

TriMesh readObj(const std::string& path) { return parseObj(readFileLimited(path, "mesh", kMaxMeshFileBytes), path); }

std::string formatObj(const TriMesh& mesh, const std::string& header) {
  std::string text;
  text.reserve(mesh.positions.size() * 12 + mesh.triangles.size() * 10);
  if (!header.empty()) {
    std::istringstream lines(header);
    for (std::string line; std::getline(lines, line);) text += "# " + line + "\n";
  }
  for (std::size_t i = 0; i + 2 < mesh.positions.size(); i += 3) {
    text += "v ";
    appendFloat(text, mesh.positions[i]);
    text += ' ';
    appendFloat(text, mesh.positions[i + 1]);
    text += ' ';
    appendFloat(text, mesh.positions[i + 2]);
    text += '\n';
  }
  const bool with_uv = !mesh.uvs.empty() && mesh.uv_triangles.size() == mesh.triangles.size();
  if (with_uv) {
    for (std::size_t i = 0; i + 1 < mesh.uvs.size(); i += 2) {
      text += "vt ";
      appendFloat(text, mesh.uvs[i]);
      text += ' ';
      appendFloat(text, mesh.uvs[i + 1]);
      text += '\n';
    }
  }
  for (std::size_t t = 0; t + 2 < mesh.triangles.size(); t += 3) {
    text += 'f';
    for (std::size_t k = 0; k < 3; ++k) {
      text += ' ';
      text += std::to_string(mesh.triangles[t + k] + 1);
      if (with_uv) {
        text += '/';
        text += std::to_string(mesh.uv_triangles[t + k] + 1);
      }
    }
    text += '\n';
  }
  return text;
}

void writeObj(const std::string& path, const TriMesh& mesh, const std::string& header) {
  writeFileAtomically(path, formatObj(mesh, header));
}

TriMesh readMesh(const std::string& path) {
  const std::string ext = std::filesystem::path(path).extension().string();
  std::string lower = ext;
  for (char& c : lower) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (lower == ".obj") return readObj(path);
  if (lower == ".gltf" || lower == ".glb") return readGltfMesh(path);
  throw Error(path + ": unsupported mesh format '" + ext + "' (expected .obj, .gltf or .glb)");
}

}  // namespace vdg
