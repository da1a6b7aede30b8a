// libFuzzer target: a views list (`vdg weights --views FILE`) -> parseViewList; every accepted view
// must be a finite unit direction, one per item. The same text -> parseEyeList (the list of a
// 'positions' model): every accepted eye must be finite. See fuzz_support.h for what counts as a finding.
#include <Eigen/Core>
#include <cmath>

#include "fuzz_support.h"
#include "vdg/io/camera_json.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace vdg;
  if (size > fuzz::kMaxInputBytes) return -1;
  fuzz::expectCleanRejection("parseViewList", [&] {
    const auto views = parseViewList(fuzz::text(data, size), "fuzz.json", Eigen::Vector3d(0.5, -1.0, 2.0));
    for (const Eigen::Vector3d& v : views)
      fuzz::require(v.allFinite() && std::abs(v.norm() - 1.0) < 1e-12, "an accepted view is not a unit direction");
  });
  fuzz::expectCleanRejection("parseEyeList", [&] {
    for (const Eigen::Vector3d& e : parseEyeList(fuzz::text(data, size), "fuzz.json"))
      fuzz::require(e.allFinite(), "an accepted eye is not finite");
  });
  return 0;
}
