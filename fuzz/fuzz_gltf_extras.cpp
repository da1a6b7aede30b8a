// libFuzzer target: a glTF mesh's extras (mesh.extras.vdg, versions 1 to 4, docs/gltf-export.md)
// -> rawModelFromGltfExtras over a fixed tetrahedron with three small morph targets, then
// ViewDependentModel::build and one evaluation of an accepted model. Version 2's "sphere" and
// "time" are checked for shape and size only (vdg re-derives the sphere); the checks must refuse
// cleanly. See fuzz_support.h for what counts as a finding.
#include <Eigen/Core>
#include <cmath>
#include <vector>

#include "fuzz_support.h"
#include "vdg/io/gltf_export.h"
#include "vdg/viewdep/model.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace vdg;
  if (size > fuzz::kMaxInputBytes) return -1;
  TriMesh base;
  base.positions = {0, 0, 1, 0.94f, 0, -0.33f, -0.47f, 0.82f, -0.33f, -0.47f, -0.82f, -0.33f};
  base.triangles = {0, 1, 2, 0, 2, 3, 0, 3, 1, 1, 3, 2};
  std::vector<std::vector<float>> deltas(3, std::vector<float>(base.positions.size(), 0.0f));
  for (std::size_t t = 0; t < deltas.size(); ++t) deltas[t][t * 3] = 0.1f;
  fuzz::expectCleanRejection("rawModelFromGltfExtras", [&] {
    const RawViewDependentModel raw = rawModelFromGltfExtras(fuzz::text(data, size), base, deltas, "fuzz.glb");
    const ViewDependentModel model = ViewDependentModel::build(raw);
    std::vector<float> out(base.positions.size());
    fuzz::require(model.evaluate(Eigen::Vector3d(0.3, 0.4, 0.5), 0.0, out), "an accepted model does not evaluate");
  });
  return 0;
}
