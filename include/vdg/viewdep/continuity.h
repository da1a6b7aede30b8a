// How smoothly a view-dependent model changes as the camera moves (docs/weights.md):
// along dense great-circle paths of views about the model, the largest move of any vertex per
// degree of camera motion ("popping") and the largest change of that speed from one step to the
// next ("velocity jump", per degree). The paper's linear weights are only C0: wherever a path
// crosses an edge of the key views' triangulation a vertex's speed jumps, by an amount that does
// not shrink with the step. The smooth scheme is C1: its velocity jumps shrink in proportion to
// the step. Both figures are divided by the model's size (2 x extentRadius()), so they read as a
// fraction of the model per degree.
#pragma once

#include <cstddef>

#include "vdg/viewdep/model.h"

namespace vdg {

struct ContinuitySettings {
  double step_deg = 0.1;     // camera motion between samples, in (0, 10]
  int circles = 24;          // evenly spread great circles, in [1, 10000] ...
  bool through_keys = true;  // ... plus one great circle through every key view
  double sharpness = 0.0;    // <= 0: the model's own
};

struct ContinuityReport {
  double popping = 0.0;        // max over samples and vertices of |x(n+1) - x(n)| / step_deg / size
  double velocity_jump = 0.0;  // max of |x(n+2) - 2 x(n+1) + x(n)| / step_deg / size
  double weight_speed = 0.0;   // max over samples of the L1 change of the weights per degree
  double weight_jump = 0.0;    // max of the L1 second difference of the weights per degree
  std::size_t paths = 0, samples = 0;
  double size = 0.0;  // 2 x extentRadius(), the model units the figures are divided by
};

// Measures `model` along the settings' paths. Throws vdg::Error for settings out of range.
// Cost: paths x (360 / step_deg) evaluations of the blend (about a second for a 3,000-vertex
// model at the defaults).
ContinuityReport measureContinuity(const ViewDependentModel& model, const ContinuitySettings& settings = {});

}  // namespace vdg
