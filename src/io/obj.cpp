#include "vdg/io/obj.h"

#include <tiny_obj_loader.h>
#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <sstream>
#include <string_view>
#include <vector>

#include "material_files.h"
#include "vdg/geom/error.h"
#include "vdg/geom/text.h"
#include "vdg/io/atomic_file.h"
#include "vdg/io/read_file.h"

namespace vdg {
namespace {

void appendFloat(std::string& out, float value) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value);
  out.append(buffer, result.ptr);
}

constexpr std::size_t kShownToken = 32;  // bytes of a token or name a message shows
// Faces of more corners than this are fan-triangulated here (corner 1 with corners k and k + 1:
// n - 2 triangles, linear time, exact for convex faces); smaller ones go to tinyobjloader's ear
// clipping, which handles non-convex faces but costs O(n^2) to O(n^3) per face (a face of 10^6
// corners would take hours). At 16 corners the ear clipping is at most 16^2 times the corners read.
constexpr std::size_t kMaxEarClippedCorners = 16;

// The blank-separated tokens of `line` into `out` (cleared first; its capacity is reused, so a file's
// lines are split without allocating once the longest has been seen).
void splitTokens(std::string_view line, std::vector<std::string_view>& out) {
  out.clear();
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r')) ++i;
    const std::size_t a = i;
    while (i < line.size() && line[i] != ' ' && line[i] != '\t' && line[i] != '\r') ++i;
    if (i > a) out.push_back(line.substr(a, i - a));
  }
}

std::vector<std::string_view> tokens(std::string_view line) {
  std::vector<std::string_view> out;
  splitTokens(line, out);
  return out;
}

// `line` without leading and trailing blanks (spaces, tabs, carriage returns).
std::string_view trimmed(std::string_view line) {
  const auto a = line.find_first_not_of(" \t\r");
  if (a == std::string_view::npos) return {};
  const auto b = line.find_last_not_of(" \t\r");
  return line.substr(a, b - a + 1);
}

// A number for tinyobjloader: a finite value that fits a float, appended to `out` (after a space)
// in the shortest form that reads back as the same double, because tinyobjloader's own number
// parser overflows an int on long exponents ("0e2147483648") and a double on long mantissas.
// Returns the problem ("'x' is not a number"), empty when the number is fine.
std::string shortestNumber(std::string_view token, std::string& out, double* parsed = nullptr) {
  std::string_view t = token;
  if (!t.empty() && t.front() == '+') t.remove_prefix(1);
  double value = 0;
  const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), value);
  if (ec == std::errc::result_out_of_range) return quotedText(token, kShownToken) + " is out of range";
  if (ec != std::errc() || end != t.data() + t.size()) return quotedText(token, kShownToken) + " is not a number";
  if (!std::isfinite(value)) return quotedText(token, kShownToken) + " is not a finite number";
  if (std::abs(value) > std::numeric_limits<float>::max())
    return quotedText(token, kShownToken) + " is too large for a float";
  char buffer[32];
  const auto written = std::to_chars(buffer, buffer + sizeof(buffer), value);
  out += ' ';
  out.append(buffer, written.ptr);
  if (parsed) *parsed = value;
  return {};
}

// A reference to a material library: the OBJ line and the file name as written.
struct LibraryRef {
  std::size_t line = 0;
  std::string name;
};

// The strict pass over the text: every v/vt/vn/f line is checked before tinyobjloader, which is
// lenient about exactly the things that silently change a shape, builds the mesh.
//
// tinyobjloader only ever sees what was checked: check() returns the text with every line vdg
// does not read (skin weights `vw`, tags `t`, lines `l`, points `p`, smoothing groups, unknown
// statements) blanked, comments cut off, carriage returns made spaces and every number rewritten,
// one output line per input line (so tinyobjloader's line numbers stay right). Those statements
// are ignored by vdg anyway, and tinyobjloader parses some of them unsafely (a `vw` joint id of
// 1e21 is converted to int, undefined behaviour; a `t` line can ask for 3 x 8192 values).
// Materials are the checker's too: `mtllib` lines are recorded and blanked, and every `o`, `g` and
// `usemtl` line becomes "o K", K the index of the material then in use (its first-use order among
// the usemtl names) or "-" for none. tinyobjloader starts a shape at every `o`, so each shape's
// name is the material of its faces, whatever tinyobjloader's triangulation makes of them, and no
// material file reaches tinyobjloader's OBJ reader.
class ObjChecker {
 public:
  explicit ObjChecker(const std::string& source) : source_(source) {}

  // Distinct usemtl names in the order of their first use, and the line of that use.
  const std::vector<std::string>& materialNames() const { return material_names_; }
  const std::vector<std::size_t>& materialLines() const { return material_lines_; }
  // Every mtllib file name, in order.
  const std::vector<LibraryRef>& libraries() const { return libraries_; }

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

  // "vertex 12", "texture coordinate 3", "normal 7": the element of `kind` (0 v, 1 vt, 2 vn) being
  // read, for messages only (built when a line fails, not for every line).
  std::string elementName(int kind) const {
    static constexpr const char* kNames[3] = {"vertex ", "texture coordinate ", "normal "};
    return kNames[kind] + std::to_string(counts_[kind] + 1);
  }

  // A coordinate of the element of `kind` being read: a finite number that fits a float, passed on
  // rewritten (shortestNumber).
  void number(std::string_view token, std::size_t line, int kind, std::string& out) const {
    const std::string problem = shortestNumber(token, out);
    if (problem.empty()) return;
    const bool bad_number = problem.find("is not a number") != std::string::npos;
    fail(line, elementName(kind) + ": " + (bad_number ? "" : "coordinate ") + problem);
  }

  // An f line as tinyobjloader should see it: as it is up to kMaxEarClippedCorners corners, else
  // fanned into "f c1 ck ck+1" lines (see kMaxEarClippedCorners). `t` are its tokens, "f" first.
  static void appendFace(const std::vector<std::string_view>& t, std::string& out) {
    const std::size_t corners = t.size() - 1;
    const auto append = [&out](std::string_view token) {
      for (char c : token) out += c == '\r' ? ' ' : c;
    };
    if (corners <= kMaxEarClippedCorners) {
      for (std::size_t i = 0; i < t.size(); ++i) {
        if (i) out += ' ';
        append(t[i]);
      }
      return;
    }
    for (std::size_t k = 2; k + 1 <= corners; ++k) {
      if (k > 2) out += '\n';
      out += "f ";
      append(t[1]);
      out += ' ';
      append(t[k]);
      out += ' ';
      append(t[k + 1]);
    }
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
      fail(line, std::string("face: ") + noun + " index " + quotedText(token, kShownToken) + " is out of range");
    if (ec != std::errc() || end != t.data() + t.size())
      fail(line, std::string("face: ") + noun + " index " + quotedText(token, kShownToken) + " is not a whole number");
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
  // their numbers rewritten, f as it is, o, g and usemtl as "o K" (see above), anything else as
  // nothing.
  void checkLine(std::string_view line, std::size_t line_no, std::string& out) {
    const auto hash = line.find('#');
    if (hash != std::string_view::npos) line = line.substr(0, hash);
    splitTokens(line, tokens_);
    const std::vector<std::string_view>& t = tokens_;
    if (t.empty()) return;
    const std::string_view tag = t[0];
    if (tag == "usemtl") {
      const std::string name(trimmed(trimmed(line).substr(tag.size())));
      current_material_ = name.empty() ? -1 : materialIndex(name, line_no);
    }
    if (tag == "o" || tag == "g" || tag == "usemtl") {
      out += current_material_ < 0 ? std::string("o -") : "o " + std::to_string(current_material_);
      return;
    }
    if (tag == "mtllib") {
      for (std::size_t i = 1; i < t.size(); ++i) libraries_.push_back({line_no, std::string(t[i])});
      return;
    }
    if (tag == "f") {
      appendFace(t, out);
    } else if (tag == "v" || tag == "vt" || tag == "vn") {
      out += tag;
    } else {
      return;
    }
    if (tag == "v") {
      if (t.size() < 4)
        fail(line_no, elementName(0) + ": expected 3 coordinates x y z, got " + std::to_string(t.size() - 1));
      if (t.size() > 8)
        fail(line_no,
             elementName(0) + ": expected x y z [w] or x y z r g b, got " + std::to_string(t.size() - 1) + " numbers");
      for (std::size_t i = 1; i < t.size(); ++i) number(t[i], line_no, 0, out);
      if (++counts_[0] > kMaxIndex) fail(line_no, "more than " + std::to_string(kMaxIndex) + " vertices");
    } else if (tag == "vt") {
      if (t.size() < 2 || t.size() > 4) fail(line_no, elementName(1) + ": expected 1 to 3 numbers");
      for (std::size_t i = 1; i < t.size(); ++i) number(t[i], line_no, 1, out);
      if (++counts_[1] > kMaxIndex) fail(line_no, "more than " + std::to_string(kMaxIndex) + " texture coordinates");
    } else if (tag == "vn") {
      if (t.size() != 4) fail(line_no, elementName(2) + ": expected 3 numbers");
      for (std::size_t i = 1; i < t.size(); ++i) number(t[i], line_no, 2, out);
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
            fail(line_no, "face: corner " + quotedText(corner, kShownToken) + " is not v, v/vt, v//vn or v/vt/vn");
          const std::int64_t ni = index(vn, line_no, 2, "normal");
          if (ni > max_vn_) max_vn_ = ni, max_vn_line_ = line_no;
        }
      }
    }
  }

  int materialIndex(const std::string& name, std::size_t line_no) {
    const auto [it, added] = material_index_.emplace(name, static_cast<int>(material_names_.size()));
    if (added) {
      if (material_names_.size() >= kMaxObjMaterials)
        fail(line_no, "usemtl: more than " + std::to_string(kMaxObjMaterials) + " material names");
      material_names_.push_back(name);
      material_lines_.push_back(line_no);
    }
    return it->second;
  }

  static constexpr std::int64_t kMaxIndex = std::numeric_limits<std::int32_t>::max();
  const std::string& source_;
  std::map<std::string, int> material_index_;
  int current_material_ = -1;
  std::vector<std::string> material_names_;
  std::vector<std::size_t> material_lines_;
  std::vector<LibraryRef> libraries_;
  std::vector<std::string_view> tokens_;  // the current line's (splitTokens), reused line to line
  std::int64_t counts_[3] = {0, 0, 0};    // v, vt, vn read so far
  std::int64_t max_v_ = 0, max_vt_ = 0, max_vn_ = 0;
  std::size_t max_v_line_ = 0, max_vt_line_ = 0, max_vn_line_ = 0;
};

// One MTL text checked: its materials (parseMtl's answer), the line of each one's map_Kd (0:
// none), and the text tinyobjloader reads: "newmtl m<i>" for the i-th newmtl (its name may hold
// any characters), Kd with its three numbers rewritten (shortestNumber), every other line blank.
struct CheckedMtl {
  std::vector<Material> materials;
  std::vector<std::size_t> texture_lines;
  std::vector<char> has_kd;  // whether the material has a Kd (else it stays white)
  std::string text;
};

// map_Kd's options (MTL specification, "Texture map statements") and how many values each takes;
// -o, -s and -t take 1 to 3 numbers.
int textureOptionValues(std::string_view option) {
  static const std::map<std::string_view, int> kOptions = {
      {"-blendu", 1},  {"-blendv", 1}, {"-cc", 1},         {"-clamp", 1}, {"-boost", 1}, {"-texres", 1}, {"-bm", 1},
      {"-imfchan", 1}, {"-type", 1},   {"-colorspace", 1}, {"-mm", 2},    {"-o", 3},     {"-s", 3},      {"-t", 3}};
  const auto it = kOptions.find(option);
  return it == kOptions.end() ? 0 : it->second;
}

bool isNumber(std::string_view token) {
  std::string_view t = token;
  if (!t.empty() && t.front() == '+') t.remove_prefix(1);
  double value = 0;
  const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), value);
  return ec == std::errc() && end == t.data() + t.size();
}

// map_Kd's file name: what follows the options, to the end of the line.
std::string textureFileName(std::string_view rest) {
  const auto t = tokens(rest);
  std::size_t i = 0;
  while (i < t.size()) {
    const int values = textureOptionValues(t[i]);
    if (values == 0) break;
    const bool numbers = t[i] == "-o" || t[i] == "-s" || t[i] == "-t";
    ++i;
    for (int k = 0; k < values && i < t.size() && (!numbers || k == 0 || isNumber(t[i])); ++k) ++i;
  }
  if (i >= t.size()) return {};
  const std::size_t at = static_cast<std::size_t>(t[i].data() - rest.data());
  return std::string(trimmed(rest.substr(at)));
}

CheckedMtl checkMtl(std::string_view text, const std::string& source) {
  CheckedMtl out;
  out.text.reserve(text.size() / 2);
  auto fail = [&](std::size_t line, const std::string& what) {
    throw Error(source + ":" + std::to_string(line) + ": " + what);
  };
  std::size_t line_no = 0, start = 0;
  while (start <= text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string_view::npos) end = text.size();
    ++line_no;
    std::string_view line = text.substr(start, end - start);
    start = end + 1;
    // A comment starts with '#' at the start of the line or after a blank.
    for (std::size_t i = 0; i < line.size(); ++i)
      if (line[i] == '#' && (i == 0 || line[i - 1] == ' ' || line[i - 1] == '\t')) {
        line = line.substr(0, i);
        break;
      }
    const auto t = tokens(line);
    if (!t.empty() && t[0] == "newmtl") {
      const std::string name(trimmed(trimmed(line).substr(t[0].size())));
      if (name.empty()) fail(line_no, "newmtl without a material name");
      if (out.materials.size() >= kMaxObjMaterials)
        fail(line_no, "more than " + std::to_string(kMaxObjMaterials) + " materials");
      out.text += "newmtl m" + std::to_string(out.materials.size());
      Material m;
      m.name = name;
      out.materials.push_back(std::move(m));
      out.texture_lines.push_back(0);
      out.has_kd.push_back(0);
    } else if (!t.empty() && t[0] == "Kd" && !out.materials.empty() && t.size() > 1 && t[1] != "spectral" &&
               t[1] != "xyz") {
      if (t.size() != 2 && t.size() != 4)
        fail(line_no, "Kd: expected 1 or 3 numbers (r [g b]), got " + std::to_string(t.size() - 1));
      out.text += "Kd";
      out.has_kd.back() = 1;
      for (std::size_t k = 0; k < 3; ++k) {
        const std::string problem = shortestNumber(t[t.size() == 2 ? 1 : k + 1], out.text);
        if (!problem.empty()) fail(line_no, "Kd: " + problem);
      }
    } else if (!t.empty() && t[0] == "Kd" && t.size() == 1) {
      fail(line_no, "Kd: expected 1 or 3 numbers (r [g b]), got none");
    } else if (!t.empty() && t[0] == "map_Kd" && !out.materials.empty()) {
      const std::string name = textureFileName(trimmed(line).substr(t[0].size()));
      if (name.empty()) fail(line_no, "map_Kd without a file name");
      out.materials.back().texture_path = name;
      out.texture_lines.back() = line_no;
    }
    out.text += '\n';
  }
  // tinyobjloader reads the colours; every number it sees was checked and rewritten above.
  std::map<std::string, int> names;
  std::vector<tinyobj::material_t> parsed;
  std::istringstream stream(out.text);
  std::string warning, error;
  tinyobj::LoadMtl(&names, &parsed, &stream, &warning, &error);
  for (std::size_t i = 0; i < out.materials.size(); ++i) {
    if (!out.has_kd[i]) continue;
    const auto it = names.find("m" + std::to_string(i));
    if (it == names.end() || it->second < 0 || static_cast<std::size_t>(it->second) >= parsed.size())
      throw Error(source + ": material '" + out.materials[i].name + "' was not read");
    const auto& d = parsed[static_cast<std::size_t>(it->second)].diffuse;
    for (std::size_t c = 0; c < 3; ++c)
      out.materials[i].base_color[c] = std::clamp(static_cast<float>(d[c]), 0.0f, 1.0f);
  }
  return out;
}

// A material as a library defines it, with where it came from (for textures and messages).
struct DefinedMaterial {
  Material material;
  std::string library;           // the MTL file's path
  std::size_t texture_line = 0;  // its map_Kd line in that file
};

// Gives the mesh the materials its usemtl names refer to (see obj.h). `face_names[f]` is the
// usemtl index of triangle f (-1: none).
// A map_Kd texture file; one outside the read root is refused (ReadRootError), not a warning.
std::shared_ptr<const TextureImage> fileTexture(io::TextureCache& textures, const std::string& path,
                                                const std::string& where, std::string* why) {
  try {
    return textures.file(path, why);
  } catch (const ReadRootError& e) {
    throw ReadRootError(where + ": " + e.what());
  }
}

void attachMaterials(TriMesh& mesh, const std::vector<int>& face_names, const ObjChecker& checker,
                     const std::string& source, const MeshReadOptions& options) {
  const io::WarningSink sink(options);
  const auto& names = checker.materialNames();
  std::vector<char> used(names.size(), 0);
  for (const int k : face_names)
    if (k >= 0) used[static_cast<std::size_t>(k)] = 1;
  if (std::find(used.begin(), used.end(), 1) == used.end()) return;

  const std::string folder = io::folderOf(source);
  auto at = [&](std::size_t line) { return source + ":" + std::to_string(line) + ": "; };
  std::map<std::string, DefinedMaterial> defined;  // the first definition of each name
  bool all_read = true;
  std::set<std::string> seen;
  for (const LibraryRef& ref : checker.libraries()) {
    if (!seen.insert(ref.name).second) continue;
    if (seen.size() > kMaxMaterialLibraries) {
      sink.warn(at(ref.line) + "mtllib " + quotedText(ref.name, kShownToken) + ": more than " +
                std::to_string(kMaxMaterialLibraries) + " material libraries; it and later ones are not read");
      all_read = false;
      break;
    }
    const std::string problem = io::relativePathProblem(ref.name);
    if (!problem.empty()) {
      sink.warn(at(ref.line) + "mtllib " + quotedText(ref.name, kShownToken) + " " + problem +
                " (material libraries must lie in the OBJ file's folder or below); not read");
      all_read = false;
      continue;
    }
    const std::string path = io::inFolder(folder, ref.name);
    try {
      CheckedMtl mtl = checkMtl(readFileLimited(path, "material library", kMaxMaterialFileBytes), path);
      for (std::size_t i = 0; i < mtl.materials.size(); ++i) {
        std::string name = mtl.materials[i].name;
        defined.emplace(std::move(name), DefinedMaterial{std::move(mtl.materials[i]), path, mtl.texture_lines[i]});
      }
    } catch (const ReadRootError& e) {
      throw ReadRootError(at(ref.line) + "mtllib: " + e.what());  // the same rule as the OBJ file's own
    } catch (const Error& e) {
      sink.warn(at(ref.line) + "mtllib: " + e.what() + "; its materials are not used");
      all_read = false;
    }
  }

  // The mesh's materials: every used name a library defines, in the order of first use.
  std::vector<int> final_index(names.size(), -1);
  std::vector<std::size_t> undefined;
  io::TextureCache textures;
  std::set<std::string> warned;
  for (std::size_t k = 0; k < names.size(); ++k) {
    if (!used[k]) continue;
    const auto it = defined.find(names[k]);
    if (it == defined.end()) {
      undefined.push_back(k);
      continue;
    }
    DefinedMaterial& d = it->second;
    Material& m = d.material;
    if (!m.texture_path.empty()) {
      const std::string where = d.library + ":" + std::to_string(d.texture_line) + ": map_Kd";
      const std::string problem = io::relativePathProblem(m.texture_path);
      const std::string path = io::inFolder(io::folderOf(d.library), m.texture_path);
      std::string why;
      if (!problem.empty())
        why = where + " " + quotedText(m.texture_path, kShownToken) + " " + problem +
              " (textures must lie in the material library's folder or below)";
      else if (!(m.texture = fileTexture(textures, path, where, &why)))
        why = where + ": " + why;
      if (!why.empty() && warned.insert(problem.empty() ? path : why).second)
        sink.warn(why + "; material " + quotedText(m.name, kShownToken) + " shows its colour alone");
    }
    final_index[k] = static_cast<int>(mesh.materials.size());
    mesh.materials.push_back(m);
  }
  if (all_read && !undefined.empty()) {
    const std::size_t k = undefined.front();
    const std::string more =
        undefined.size() > 1 ? " (and " + std::to_string(undefined.size() - 1) + " more names)" : std::string();
    if (checker.libraries().empty())
      sink.warn(at(checker.materialLines()[k]) + "usemtl " + quotedText(names[k], kShownToken) + more +
                " without a material library (mtllib); those faces have no material");
    else
      sink.warn(at(checker.materialLines()[k]) + "usemtl " + quotedText(names[k], kShownToken) + more +
                " is defined in no material library; those faces have no material");
  }
  if (mesh.materials.empty()) return;
  mesh.face_materials.resize(face_names.size());
  for (std::size_t f = 0; f < face_names.size(); ++f)
    mesh.face_materials[f] = face_names[f] < 0 ? -1 : final_index[static_cast<std::size_t>(face_names[f])];
}

// A normal scaled to unit length (by its largest component first, so that huge finite values
// cannot overflow); a zero normal stays zero.
void normalize3(float* n) {
  const double scale = std::max({std::abs(double{n[0]}), std::abs(double{n[1]}), std::abs(double{n[2]})});
  if (scale == 0.0) return;
  const double x = n[0] / scale, y = n[1] / scale, z = n[2] / scale;
  const double length = std::sqrt(x * x + y * y + z * z);
  n[0] = static_cast<float>(x / length);
  n[1] = static_cast<float>(y / length);
  n[2] = static_cast<float>(z / length);
}

}  // namespace

std::vector<Material> parseMtl(const std::string& text, const std::string& source) {
  return checkMtl(text, source).materials;
}

TriMesh parseObj(const std::string& text, const std::string& source, const MeshReadOptions& options) {
  ObjChecker checker(source);
  const std::string checked = checker.check(text);

  tinyobj::ObjReaderConfig config;
  config.triangulate = true;
  config.vertex_color = false;
  tinyobj::ObjReader reader;
  // The checked text has no mtllib line: tinyobjloader opens no file.
  if (!reader.ParseFromString(checked, std::string(), config)) {
    throw Error(source + ": cannot read OBJ: " + joinedLines(reader.Error()));
  }
  const auto& attrib = reader.GetAttrib();
  TriMesh mesh;
  mesh.positions.assign(attrib.vertices.begin(), attrib.vertices.end());
  mesh.uvs.assign(attrib.texcoords.begin(), attrib.texcoords.end());
  mesh.normals.assign(attrib.normals.begin(), attrib.normals.end());
  const std::size_t nv = mesh.vertexCount();
  bool all_have_uv = !mesh.uvs.empty();
  bool all_have_normal = !mesh.normals.empty();
  std::vector<int> face_names;  // usemtl index per triangle (-1: none)
  for (const auto& shape : reader.GetShapes()) {
    // The shape's name is the usemtl index of its faces, or "-" (see ObjChecker).
    int name = -1;
    if (shape.name != "-") {
      const auto [end, ec] = std::from_chars(shape.name.data(), shape.name.data() + shape.name.size(), name);
      if (ec != std::errc() || end != shape.name.data() + shape.name.size() || name < 0 ||
          static_cast<std::size_t>(name) >= checker.materialNames().size())
        name = -1;
    }
    std::size_t offset = 0;
    for (std::size_t f = 0; f < shape.mesh.num_face_vertices.size(); ++f) {
      const std::size_t n = shape.mesh.num_face_vertices[f];
      if (n != 3) throw Error(source + ": face " + std::to_string(f + 1) + " could not be triangulated");
      for (std::size_t k = 0; k < 3; ++k) {
        const auto& idx = shape.mesh.indices[offset + k];
        if (idx.vertex_index < 0 || static_cast<std::size_t>(idx.vertex_index) >= nv)
          throw Error(source + ": a face refers to vertex " + std::to_string(std::int64_t{idx.vertex_index} + 1) +
                      " but the file has " + std::to_string(nv) + " vertices");
        mesh.triangles.push_back(idx.vertex_index);
        if (idx.texcoord_index < 0) all_have_uv = false;
        mesh.uv_triangles.push_back(idx.texcoord_index);
        if (idx.normal_index < 0) all_have_normal = false;
        mesh.normal_triangles.push_back(idx.normal_index);
      }
      face_names.push_back(name);
      offset += n;
    }
  }
  if (!all_have_uv) {
    mesh.uvs.clear();
    mesh.uv_triangles.clear();
  }
  if (!all_have_normal) {
    mesh.normals.clear();
    mesh.normal_triangles.clear();
  }
  for (std::size_t i = 0; i + 2 < mesh.normals.size(); i += 3) normalize3(&mesh.normals[i]);
  if (mesh.triangles.empty()) throw Error(source + ": OBJ file has no faces");
  validateMesh(mesh, source);
  if (options.materials) {
    attachMaterials(mesh, face_names, checker, source, options);
    validateMesh(mesh, source);
  }
  return mesh;
}

TriMesh readObj(const std::string& path, const MeshReadOptions& options) {
  return parseObj(readFileLimited(path, "mesh", kMaxMeshFileBytes), path, options);
}

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

namespace {
// Unique MTL names for `materials` (see formatObjWithMaterials), never "vdg-plain".
std::vector<std::string> mtlNames(const std::vector<Material>& materials) {
  std::vector<std::string> names;
  std::set<std::string> used{"vdg-plain"};
  for (const Material& m : materials) {
    std::string stem;
    for (const char c : m.name)
      stem += (std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' || c == '.') ? c : '_';
    if (stem.empty()) stem = "material";
    std::string name = stem;
    for (int i = 2; used.count(name); ++i) name = stem + "_" + std::to_string(i);
    used.insert(name);
    names.push_back(std::move(name));
  }
  return names;
}
}  // namespace

ObjWithMaterials formatObjWithMaterials(const TriMesh& mesh, const std::string& header, const std::string& mtl_name,
                                        const std::vector<std::string>& texture_files) {
  ObjWithMaterials out;
  if (mesh.face_materials.empty() || mesh.materials.empty()) {
    out.obj = formatObj(mesh, header);
    return out;
  }
  const std::vector<std::string> names = mtlNames(mesh.materials);
  bool plain = false;
  for (std::size_t i = 0; i < mesh.materials.size(); ++i) {
    const Material& m = mesh.materials[i];
    out.mtl += "newmtl " + names[i] + "\nKd ";
    for (int c = 0; c < 3; ++c) {
      appendFloat(out.mtl, m.base_color[static_cast<std::size_t>(c)]);
      out.mtl += c < 2 ? ' ' : '\n';
    }
    if (i < texture_files.size() && !texture_files[i].empty()) out.mtl += "map_Kd " + texture_files[i] + "\n";
  }
  // formatObj's lines, with usemtl before each run of faces of one material.
  const std::string body = formatObj(mesh, header);
  std::istringstream lines(body);
  std::size_t face = 0;
  int current = -1;
  bool started = false, library = false;
  for (std::string line; std::getline(lines, line);) {
    if (!line.empty() && line[0] == 'f') {
      const int material = mesh.face_materials[face++];
      if (!started || material != current) {
        if (started || material >= 0) {
          plain = plain || material < 0;
          out.obj +=
              "usemtl " + (material < 0 ? std::string("vdg-plain") : names[static_cast<std::size_t>(material)]) + "\n";
        }
        current = material;
        started = true;
      }
    } else if (!library && !line.empty() && line[0] != '#') {
      out.obj += "mtllib " + mtl_name + "\n";
      library = true;
    }
    out.obj += line + "\n";
  }
  if (plain) out.mtl += "newmtl vdg-plain\nKd 1 1 1\n";
  return out;
}

void writeObj(const std::string& path, const TriMesh& mesh, const std::string& header) {
  writeFileAtomically(path, formatObj(mesh, header));
}

}  // namespace vdg
