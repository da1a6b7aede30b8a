// libFuzzer target: Wavefront OBJ text -> parseObj, then the mesh functions a loaded mesh meets
// first (validateMesh, bounds, vertex normals). See fuzz_support.h for what counts as a finding.
#include <vector>

#include "fuzz_support.h"
#include "vdg/io/obj.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace vdg;
  if (size > fuzz::kMaxInputBytes) return -1;
  fuzz::expectCleanRejection("parseObj", [&] {
    // Materials off: an mtllib line must not make the fuzzer open files (fuzz_mtl covers MTL text).
    const TriMesh mesh = parseObj(fuzz::text(data, size), "fuzz.obj", MeshReadOptions{false, false, nullptr});
    // parseObj validates; an accepted mesh must pass validateMesh on its own.
    validateMesh(mesh, "fuzz.obj");
    fuzz::require(mesh.triangleCount() > 0, "parseObj accepted a mesh without triangles");
    fuzz::require(mesh.uvs.empty() == mesh.uv_triangles.empty(), "uvs and uv_triangles disagree");
    fuzz::require(mesh.normals.empty() == mesh.normal_triangles.empty(), "normals and normal_triangles disagree");
    const Bounds b = computeBounds(mesh.positions);
    for (int k = 0; k < 3; ++k) fuzz::require(b.min[k] <= b.max[k], "computeBounds: min > max");
    // Huge (finite) coordinates may overflow to non-finite normals; only memory safety is checked.
    std::vector<float> normals(mesh.positions.size());
    fuzz::require(computeVertexNormals(mesh.positions, mesh.triangles, normals),
                  "computeVertexNormals refused an accepted mesh");
  });
  return 0;
}
