#include "vdg/io/mesh.h"

#include <array>
#include <cmath>
#include <filesystem>
#include <limits>

#include "mesh_extent.h"
#include "vdg/geom/error.h"
#include "vdg/geom/text.h"
#include "vdg/io/gltf.h"
#include "vdg/io/obj.h"

namespace vdg {

namespace io {
namespace {

std::string pointText(std::span<const float> p, std::size_t v) {
  return "(" + numberText(p[3 * v]) + ", " + numberText(p[3 * v + 1]) + ", " + numberText(p[3 * v + 2]) + ")";
}

}  // namespace

void checkMeshExtent(std::span<const float> p, const std::string& where, const std::string& after) {
  const std::size_t nv = p.size() / 3;
  std::array<std::size_t, 3> lo{}, hi{};
  for (std::size_t v = 0; v < nv; ++v)
    for (std::size_t c = 0; c < 3; ++c) {
      if (!std::isfinite(p[3 * v + c]))
        throw Error(where + ": vertex " + std::to_string(v) + " lies at " + pointText(p, v) + after +
                    "; positions must be finite");
      if (p[3 * v + c] < p[3 * lo[c] + c]) lo[c] = v;
      if (p[3 * v + c] > p[3 * hi[c] + c]) hi[c] = v;
    }
  double squared = 0.0, widest = -1.0;
  std::size_t axis = 0;
  for (std::size_t c = 0; c < 3 && nv > 0; ++c) {
    const double extent = double(p[3 * hi[c] + c]) - double(p[3 * lo[c] + c]);
    squared += extent * extent;
    if (extent > widest) widest = extent, axis = c;
  }
  if (std::sqrt(squared) > std::numeric_limits<float>::max())
    throw Error(where + ": vertices " + std::to_string(lo[axis]) + " at " + pointText(p, lo[axis]) + " and " +
                std::to_string(hi[axis]) + " at " + pointText(p, hi[axis]) + " lie too far apart" + after +
                ": the mesh's extent (" + numberText(std::sqrt(squared)) + ") overflows a float");
}

}  // namespace io

bool isObjPath(const std::string& path) { return hasExtension(path, ".obj"); }

bool isGltfPath(const std::string& path) { return hasGltfExtension(path); }

TriMesh readMesh(const std::string& path, const MeshReadOptions& options) {
  if (isObjPath(path)) {
    TriMesh mesh = readObj(path, options);
    io::checkMeshExtent(mesh.positions, path);  // glTF's reader checks its placed rest pose itself
    return mesh;
  }
  if (isGltfPath(path)) return readGltfMesh(path, {}, options);
  throw Error(path + ": unsupported mesh format '" + std::filesystem::path(path).extension().string() +
              "' (expected .obj, .gltf or .glb)");
}

}  // namespace vdg
