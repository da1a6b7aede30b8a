#include "vdg/io/mesh.h"

#include <filesystem>

#include "vdg/geom/error.h"
#include "vdg/geom/text.h"
#include "vdg/io/gltf.h"
#include "vdg/io/obj.h"

namespace vdg {

bool isObjPath(const std::string& path) { return hasExtension(path, ".obj"); }

bool isGltfPath(const std::string& path) { return hasGltfExtension(path); }

TriMesh readMesh(const std::string& path, const MeshReadOptions& options) {
  if (isObjPath(path)) return readObj(path, options);
  if (isGltfPath(path)) return readGltfMesh(path, {}, options);
  throw Error(path + ": unsupported mesh format '" + std::filesystem::path(path).extension().string() +
              "' (expected .obj, .gltf or .glb)");
}

}  // namespace vdg
