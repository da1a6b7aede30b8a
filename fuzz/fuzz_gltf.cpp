// libFuzzer target: glTF 2.0 bytes (.gltf JSON or .glb) -> parseGltfRig and describeGltfData
// (external buffers are refused: no folder), then Rig::build and evaluation of every animation at
// a few times. tinygltf's own code is compiled inside vdg_io (src/io/gltf.cpp), so it is
// instrumented too. See fuzz_support.h for what counts as a finding.
#include <vector>

#include "fuzz_support.h"
#include "vdg/anim/rig.h"
#include "vdg/io/gltf.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace vdg;
  if (size > fuzz::kMaxInputBytes) return -1;
  const std::string bytes = fuzz::text(data, size);
  fuzz::expectCleanRejection("describeGltfData", [&] { (void)describeGltfData(bytes, "fuzz.glb"); });
  fuzz::expectCleanRejection("parseGltfRig", [&] {
    const RawRig raw = parseGltfRig(bytes, "fuzz.glb");
    const Rig rig = Rig::build(raw);  // parseGltfRig validated: build must not refuse it
    const std::size_t nv = rig.vertexCount();
    fuzz::require(nv > 0 && rig.mesh().triangleCount() > 0, "an accepted rig without triangles");
    std::vector<float> positions(3 * nv), normals(3 * nv), skin(9 * nv);
    for (int a = -1; a < static_cast<int>(rig.animationCount()) && a < 4; ++a)
      for (double f : {0.0, 0.3, 1.0, 2.0})
        fuzz::require(rig.evaluate(a, f * rig.duration(a), positions, normals, skin), "evaluate refused valid input");
  });
  return 0;
}
