// libFuzzer target: camera JSON -> parseCameraJson; an accepted camera must survive the round trip
// through cameraToJson unchanged, and its matrices and projections are computed.
// See fuzz_support.h for what counts as a finding.
#include <Eigen/Core>

#include "fuzz_support.h"
#include "vdg/geom/camera.h"
#include "vdg/io/camera_json.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace vdg;
  if (size > fuzz::kMaxInputBytes) return -1;
  fuzz::expectCleanRejection("parseCameraJson", [&] {
    const Camera camera = parseCameraJson(fuzz::text(data, size), "fuzz.json");
    Camera again;
    try {
      again = parseCameraJson(cameraToJson(camera), "round trip");
    } catch (const Error& e) {
      std::fprintf(stderr, "FINDING: an accepted camera does not read back: %s\n", e.what());
      std::abort();
    }
    fuzz::require(again.eye == camera.eye && again.target == camera.target && again.up == camera.up &&
                      again.fov_deg == camera.fov_deg && again.ortho_height == camera.ortho_height,
                  "a camera changed in the round trip through cameraToJson");
    (void)cameraFrame(camera);
    (void)viewMatrix(camera);
    (void)projectionMatrix(camera, 1.5, 0.1, 100.0);
    const Projected p = project(camera, 64, 48, camera.target);
    (void)unproject(camera, 64, 48, p.pixel, p.depth);
  });
  return 0;
}
