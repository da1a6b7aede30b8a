// libFuzzer target: BLOBS.json -> parseBlobFile; an accepted file must build its animation, pose
// it at its first, middle and last frames, and those models evaluate their field and gradient and
// report finite bounds. The polygoniser itself is not run (its grid is the cost, not the parsing);
// its voxel budget check is. See fuzz_support.h for what counts as a finding.
#include <cmath>

#include "fuzz_support.h"
#include "vdg/io/blob_files.h"
#include "vdg/morph/implicit.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace vdg;
  if (size > fuzz::kMaxInputBytes) return -1;
  fuzz::expectCleanRejection("parseBlobFile", [&] {
    const BlobFile file = parseBlobFile(fuzz::text(data, size), "fuzz.json");
    const morph::BlobAnimation animation = morph::BlobAnimation::build(file.animation, "fuzz.json");
    morph::BlobModel model = animation.modelAt(animation.firstFrame());
    const int middle = animation.firstFrame() + (animation.lastFrame() - animation.firstFrame()) / 2;
    for (int frame : {animation.firstFrame(), middle, animation.lastFrame()}) {
      fuzz::require(animation.evaluate(frame, model), "a built animation does not evaluate at one of its frames");
      const Eigen::AlignedBox3d box = model.bounds();
      if (!box.isEmpty()) {
        fuzz::require(box.min().allFinite() && box.max().allFinite(), "the bounds of a posed model are not finite");
        const Eigen::Vector3d centre = box.center();
        const double f = model.field(centre);
        fuzz::require(!std::isnan(f), "the field is NaN at the centre of the bounds");
        (void)model.gradient(centre);
        const double h = file.voxel_size > 0 ? file.voxel_size : morph::defaultVoxelSize(box);
        if (h > 0) morph::checkVoxelBudget(box, h, std::size_t{1} << 27, "fuzz.json");
      }
    }
  });
  return 0;
}
