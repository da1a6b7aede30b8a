// libFuzzer target: animation spec text (what `vdg sample` reads) -> parseAnimSpec; an accepted
// spec is built (Curve, ArcLengthCurve, Track, CameraPath) and evaluated at a few times, inside and
// outside its range. See fuzz_support.h for what counts as a finding.
#include <vector>

#include "fuzz_support.h"
#include "vdg/anim/arc_length.h"
#include "vdg/anim/camera_path.h"
#include "vdg/anim/curve.h"
#include "vdg/anim/track.h"
#include "vdg/io/anim_json.h"

namespace {

using namespace vdg::anim;

// A table of this many samples costs as much as the rest of an execution; larger requests (valid,
// up to 10^7) are parsed but built with this many, so that every execution stays fast.
constexpr int kMaxTableSamples = 20'000;

void exercise(AnimSpec& spec) {
  switch (spec.kind) {
    case AnimSpec::Kind::kEase:
      for (double t : {-1.0, 0.0, 0.3, 0.5, 1.0, 2.0}) {
        const double v = spec.ease(t);
        vdg::fuzz::require(v >= 0.0 && v <= 1.0, "an ease left [0, 1]");
      }
      (void)spec.ease.describe();
      break;
    case AnimSpec::Kind::kCurve: {
      const Curve curve = Curve::build(spec.curve);
      std::vector<double> out(static_cast<std::size_t>(curve.dimension()));
      for (double t : {-1.0, 0.0, 0.7, 2.0, 100.0}) {
        vdg::fuzz::require(curve.evaluate(t, out), "Curve::evaluate refused a finite time");
        vdg::fuzz::require(curve.derivative(t, out), "Curve::derivative refused a finite time");
      }
      if (spec.arc_length) {
        ArcLengthOptions options = *spec.arc_length;
        if (options.table_samples > kMaxTableSamples) options.table_samples = kMaxTableSamples;
        const ArcLengthCurve arc = ArcLengthCurve::build(curve, options);
        for (double f : {-0.5, 0.0, 0.25, 0.5, 1.0, 3.0}) {
          (void)arc.timeAtFraction(f);
          vdg::fuzz::require(arc.evaluateAtFraction(f, out), "ArcLengthCurve::evaluateAtFraction refused");
        }
      }
      break;
    }
    case AnimSpec::Kind::kTrack: {
      const Track track = Track::build(spec.track);
      std::vector<double> out(static_cast<std::size_t>(track.dimension()));
      for (double t : {-5.0, 0.0, 0.5, 13.0, 1e6, -1e300})
        vdg::fuzz::require(track.evaluate(t, out), "Track::evaluate refused a finite time");
      break;
    }
    case AnimSpec::Kind::kCameraPath: {
      if (spec.camera_path.arc_length.table_samples > kMaxTableSamples)
        spec.camera_path.arc_length.table_samples = kMaxTableSamples;
      const CameraPath path = CameraPath::build(spec.camera_path);
      vdg::Camera camera;
      for (double t : {-1.0, 0.0, 0.5, 5.0, 10.0, 20.0})
        vdg::fuzz::require(path.evaluate(t, camera), "CameraPath::evaluate refused a finite time");
      break;
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size > vdg::fuzz::kMaxInputBytes) return -1;
  vdg::fuzz::expectCleanRejection("parseAnimSpec", [&] {
    AnimSpec spec = parseAnimSpec(vdg::fuzz::text(data, size), "spec.json");
    exercise(spec);
  });
  return 0;
}
