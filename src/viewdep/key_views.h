// Grouping key views into viewing-sphere points (private to src/viewdep): keys of an animated
// model with the same view (within ViewSphere::kSameViewRad) and different frames share one point.
#pragma once

#include <span>
#include <vector>

#include <Eigen/Core>

namespace vdg::detail {

struct KeyViewGroups {
  std::vector<int> group_of_key;       // per key: its group, numbered by first appearance
  std::vector<std::size_t> first_key;  // per group: the index of its first key
};

// `unit_views`: one unit direction per key. Identical directions are merged first (a sort), then
// directions within kSameViewRad are merged transitively through forEachCloseViewPair, so many
// keys sharing one view cost O(n log n), not a pair search among them.
KeyViewGroups groupKeyViews(std::span<const Eigen::Vector3d> unit_views);

}  // namespace vdg::detail
