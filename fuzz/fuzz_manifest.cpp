// libFuzzer target: model manifest text (*.vdg.json) -> parseManifest, which reads no mesh. An
// accepted manifest is then given small in-memory meshes in place of its files (an octahedron as
// the base, each key moving one vertex), so that the views, cameras and settings it carries go
// through resolveViews, validate, ViewDependentModel::build (the viewing sphere) and evaluate.
// See fuzz_support.h for what counts as a finding.
#include <Eigen/Core>
#include <cmath>
#include <vector>

#include "fuzz_support.h"
#include "vdg/io/manifest.h"
#include "vdg/viewdep/model.h"

namespace {

// Building is quadratic in the key count (validate compares every pair of views); manifests with
// more keys are only parsed, which keeps every execution fast.
constexpr std::size_t kMaxKeysBuilt = 256;

vdg::TriMesh octahedron() {
  vdg::TriMesh m;
  m.positions = {1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1};
  m.triangles = {0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4, 2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5};
  return m;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace vdg;
  if (size > fuzz::kMaxInputBytes) return -1;
  fuzz::expectCleanRejection("parseManifest", [&] {
    RawViewDependentModel raw = parseManifest(fuzz::text(data, size), "fuzz.vdg.json");
    fuzz::require(!raw.base_path.empty(), "parseManifest accepted an empty base path");
    for (const RawKey& key : raw.keys) fuzz::require(!key.mesh_path.empty(), "parseManifest accepted an empty mesh");
    if (raw.keys.size() > kMaxKeysBuilt) return;
    raw.base = octahedron();
    for (std::size_t k = 0; k < raw.keys.size(); ++k) {
      raw.keys[k].mesh = raw.base;
      raw.keys[k].mesh.positions[3 * (k % 6) + 1] += 0.25f;
    }
    raw.resolveViews();
    const ViewDependentModel model = ViewDependentModel::build(raw);
    std::vector<float> positions(3 * model.vertexCount()), normals(3 * model.vertexCount());
    int hint = -1;
    for (const Eigen::Vector3d& view :
         {Eigen::Vector3d(0, 0, 1), Eigen::Vector3d(0.3, -0.4, 0.5), Eigen::Vector3d(-1, 1e-9, 0)}) {
      // A positions model (keys at distances) weighs eye positions, never directions.
      const bool ok =
          model.weightSpace() == WeightSpace::Positions
              ? model.evaluateAtEye(model.center() + 5.0 * view.normalized(), 0.0, positions, normals, &hint)
              : model.evaluate(view.normalized(), 0.0, positions, normals, &hint);
      fuzz::require(ok, "evaluate refused a unit view (or an eye off the centre)");
      for (float p : positions) fuzz::require(std::isfinite(p), "evaluate gave a non-finite position");
    }
  });
  return 0;
}
