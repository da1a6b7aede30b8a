#include "vdg/io/mesh.h"

#include <filesystem>

#include "vdg/geom/error.h"
#include "vdg/io/gltf.h"
#include "vdg/io/obj.h"

namespace vdg {
namespace {

std::string lowerExtension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

}  // namespace

bool isObjPath(const std::string& path) { return lowerExtension(path) == ".obj"; }

bool isGltfPath(const std::string& path) {
  const std::string ext = lowerExtension(path);
  return ext == ".gltf" || ext == ".glb";
}

TriMesh readMesh(const std::string& path, const MeshReadOptions& options) {
  if (isObjPath(path)) return readObj(path, options);
  if (isGltfPath(path)) return readGltfMesh(path, {}, options);
  throw Error(path + ": unsupported mesh format '" + std::filesystem::path(path).extension().string() +
              "' (expected .obj, .gltf or .glb)");
}

}  // namespace vdg
