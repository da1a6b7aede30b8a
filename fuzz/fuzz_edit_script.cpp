// libFuzzer target: edit script text (EDITS.json) -> parseEditScript; an accepted script is checked
// against and applied to a small grid mesh (validateEdits, applyEdits) with its own camera, or one
// made from its view, or a default one. See fuzz_support.h for what counts as a finding.
#include <optional>

#include "deform/test_meshes.h"
#include "fuzz_support.h"
#include "vdg/deform/edits.h"
#include "vdg/io/edit_script.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace vdg;
  if (size > fuzz::kMaxInputBytes) return -1;
  // 8 x 8 vertices, spacing 0.2: small enough that every op (geodesic distances, FFD) is quick.
  static const TriMesh kBase = test::grid(8, 0.2);
  fuzz::expectCleanRejection("parseEditScript", [&] {
    const EditScript script = parseEditScript(fuzz::text(data, size), "EDITS.json");
    validateEdits(script.ops, kBase.vertexCount(), "EDITS.json");
    Camera camera;
    if (script.camera)
      camera = *script.camera;
    else if (script.view)
      camera = cameraFromView(Eigen::Vector3d::Zero(), script.view->normalized(), 3.0, 2.0);
    TriMesh mesh = kBase;
    const auto reports =
        applyEdits(camera, mesh.triangles, mesh.positions, script.ops, script.image_size, "EDITS.json");
    fuzz::require(reports.size() == script.ops.size(), "applyEdits gave one report per op");
  });
  return 0;
}
