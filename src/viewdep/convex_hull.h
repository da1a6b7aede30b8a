// Internal: 3D convex hull through Qhull's reentrant C library (its C++ headers do not compile
// as C++20). Kept in its own translation unit so Qhull's macros stay out of the rest of the code.
#pragma once

#include <array>
#include <vector>

namespace vdg::detail {

struct HullFacet {
  std::array<int, 3> v;          // point indices
  std::array<double, 3> normal;  // outward unit normal
  double offset;                 // normal . x + offset = 0 on the facet's plane
};

// Triangulated ("Qt") hull of `coords` (#P x 3). Throws vdg::Error with Qhull's message on failure
// (fewer than 4 points, all coplanar, ...).
std::vector<HullFacet> convexHull3d(const std::vector<double>& coords);

}  // namespace vdg::detail
