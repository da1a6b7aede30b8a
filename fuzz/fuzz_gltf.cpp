// libFuzzer target: glTF 2.0 bytes (.gltf JSON or .glb) -> parseGltfRig and describeGltfData
// (external buffers are refused: no folder), then Rig::build and evaluation of every animation at
// a few times. tinygltf's own code is compiled inside vdg_io (src/io/gltf.cpp), so it is
// instrumented too. See fuzz_support.h for what counts as a finding; besides, here:
// - every refusal is vdg's line about this input: it starts with the source's name and holds
//   neither tinygltf's placeholder folder nor a data: URI echoed back (more base64 after
//   ";base64," than a message quotes of user text);
// - an accepted rig's rest pose (after the node transforms) is finite and its bounding box's
//   diagonal fits a float.
#include <cctype>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "fuzz_support.h"
#include "vdg/anim/rig.h"
#include "vdg/io/gltf.h"
#include "vdg/io/gltf_interactivity.h"

namespace {

constexpr const char* kSource = "fuzz.glb";

// True when `m` holds base64 data of a data: URI longer than the kShownBytes (60) of user text a
// message may quote: the URI was echoed, not quoted.
bool echoesDataUri(const std::string& m) {
  for (std::size_t at = m.find(";base64,"); at != std::string::npos; at = m.find(";base64,", at + 1)) {
    std::size_t run = 0;
    for (std::size_t i = at + 8;
         i < m.size() && (std::isalnum(static_cast<unsigned char>(m[i])) || m[i] == '+' || m[i] == '/' || m[i] == '=');
         ++i)
      ++run;
    if (run >= 60) return true;
  }
  return false;
}

// Runs `f`, checking the message of the vdg::Error it throws before passing it on.
template <typename F>
void withVdgMessage(F&& f) {
  try {
    f();
  } catch (const vdg::Error& e) {
    const std::string m = e.what();
    vdg::fuzz::require(m.rfind(std::string(kSource) + ": ", 0) == 0, "a glTF error that does not name the file first");
    vdg::fuzz::require(m.find("<vdg-gltf-folder>") == std::string::npos, "tinygltf's placeholder folder in a message");
    vdg::fuzz::require(!echoesDataUri(m), "a data: URI echoed in a message");
    throw;
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace vdg;
  if (size > fuzz::kMaxInputBytes) return -1;
  const std::string bytes = fuzz::text(data, size);
  fuzz::expectCleanRejection("describeGltfData",
                             [&] { withVdgMessage([&] { (void)describeGltfData(bytes, kSource); }); });
  // vdg info's KHR_interactivity summary reads the document's JSON on its own (gltf_interactivity.h).
  fuzz::expectCleanRejection("interactivitySizeOfGltfJson", [&] {
    InteractivitySize graph;
    withVdgMessage([&] { (void)interactivitySizeOfGltfJson(bytes, kSource, graph); });
  });
  fuzz::expectCleanRejection("parseGltfRig", [&] {
    RawRig raw;
    withVdgMessage([&] { raw = parseGltfRig(bytes, kSource); });
    const Rig rig = Rig::build(raw);  // parseGltfRig validated: build must not refuse it
    const std::size_t nv = rig.vertexCount();
    fuzz::require(nv > 0 && rig.mesh().triangleCount() > 0, "an accepted rig without triangles");
    std::vector<float> positions(3 * nv), normals(3 * nv), skin(9 * nv);
    fuzz::require(rig.evaluate(-1, 0.0, positions), "evaluate refused the rest pose");
    for (const float c : positions) fuzz::require(std::isfinite(c), "an accepted rig whose rest pose is not finite");
    fuzz::require(std::isfinite(computeBounds(positions).diagonal()),
                  "an accepted rig whose rest pose's extent overflows a float");
    for (int a = -1; a < static_cast<int>(rig.animationCount()) && a < 4; ++a)
      for (double f : {0.0, 0.3, 1.0, 2.0})
        fuzz::require(rig.evaluate(a, f * rig.duration(a), positions, normals, skin), "evaluate refused valid input");
  });
  return 0;
}
