#include "vdg/geom/obj_io.h"

#include <tiny_obj_loader.h>
#include <charconv>
#include <filesystem>
#include <sstream>

#include "vdg/geom/atomic_file.h"
#include "vdg/geom/error.h"

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

}  // namespace

TriMesh readObj(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw Error(path + ": no such file");

  tinyobj::ObjReaderConfig config;
  config.triangulate = true;
  config.vertex_color = false;
  config.mtl_search_path = std::filesystem::path(path).parent_path().string();
  tinyobj::ObjReader reader;
  if (!reader.ParseFromFile(path, config)) {
    throw Error(path + ": cannot read OBJ: " + oneLine(reader.Error()));
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
        throw Error(path + ": face " + std::to_string(f) + " of '" + shape.name + "' could not be triangulated");
      for (std::size_t k = 0; k < 3; ++k) {
        const auto& idx = shape.mesh.indices[offset + k];
        if (idx.vertex_index < 0 || static_cast<std::size_t>(idx.vertex_index) >= nv)
          throw Error(path + ": a face refers to vertex " + std::to_string(idx.vertex_index + 1) +
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
  if (mesh.triangles.empty()) throw Error(path + ": OBJ file has no faces");
  validateMesh(mesh, path);
  return mesh;
}

void writeObj(const std::string& path, const TriMesh& mesh, const std::string& header) {
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
  writeFileAtomically(path,
                      [&](std::ostream& out) { out.write(text.data(), static_cast<std::streamsize>(text.size())); });
}

TriMesh readMesh(const std::string& path) {
  const std::string ext = std::filesystem::path(path).extension().string();
  if (ext == ".obj" || ext == ".OBJ") return readObj(path);
  throw Error(path + ": unsupported mesh format '" + ext + "' (expected .obj)");
}

}  // namespace vdg
