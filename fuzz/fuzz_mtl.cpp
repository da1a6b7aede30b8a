// libFuzzer target: MTL material-library text -> parseMtl (vdg's line checker, then tinyobjloader's
// LoadMtl on the checked text). An accepted library's colours must lie in [0, 1] and its names be
// non-empty. See fuzz_support.h for what counts as a finding.
#include <vector>

#include "fuzz_support.h"
#include "vdg/io/obj.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace vdg;
  if (size > fuzz::kMaxInputBytes) return -1;
  fuzz::expectCleanRejection("parseMtl", [&] {
    const std::vector<Material> materials = parseMtl(fuzz::text(data, size), "fuzz.mtl");
    for (const Material& m : materials) {
      fuzz::require(!m.name.empty(), "parseMtl accepted a material without a name");
      for (const float c : m.base_color) fuzz::require(c >= 0.0f && c <= 1.0f, "base colour outside [0, 1]");
      fuzz::require(m.texture == nullptr, "parseMtl opened a texture");
    }
  });
  return 0;
}
