// Per-part key sets (private to src/viewdep): the checks validate() runs on a model's parts.
#pragma once

#include "vdg/viewdep/model.h"

namespace vdg::detail {

// The part checks of RawViewDependentModel::validate() (model.h), after the keys were checked;
// with `check_view_pairs`, also two keys of one part with the same view (keys of different parts
// may share a view).
void validateParts(const RawViewDependentModel& raw, bool check_view_pairs);

}  // namespace vdg::detail
