// A view's weights as one dense vector, for property tests of the viewing sphere: one entry per
// key (the slots of ViewWeights added up), then the base.
#pragma once

#include <vector>

#include "vdg/viewdep/view_sphere.h"

namespace vdg::testing {

inline std::vector<double> denseWeights(const ViewSphere& s, const ViewWeights& w) {
  std::vector<double> d(s.keyCount() + 1, 0.0);
  for (int k = 0; k < 3; ++k)
    if (w.key[k] >= 0) d[static_cast<std::size_t>(w.key[k])] += w.weight[k];
  d.back() += w.base;
  return d;
}

}  // namespace vdg::testing
