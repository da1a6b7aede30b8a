// Work budgets: what a request will cost, estimated from its inputs before anything is computed,
// and refused past a limit the caller sets (the `vdg` commands' --budget N).
//
// The unit is one "operation": one elementary evaluation of the algorithm's inner loop (a feature
// line's weight at a pixel, a primitive's field at a voxel, a voxel of a distance volume blended,
// a pixel of a warp's pass). One operation is a few to a few tens of nanoseconds on one core, so
// kDefaultBudget, 2e9 operations, is some seconds to about a minute of work. The estimate
// functions sit next to their algorithms (image_morph.h, inbetween.h, implicit.h, shape_morph.h,
// slice_morph.h, sheet_morph.h); they compute in double, so no count overflows (a count past 1e308 is
// +infinity, which every budget refuses).
#pragma once

#include <functional>
#include <string>

namespace vdg::morph {

inline constexpr double kDefaultBudget = 2e9;
// The largest budget one may give (--budget): beyond it a run would take days.
inline constexpr double kMaxBudget = 1e15;

// Throws vdg::Error, one line:
//   "WHAT: needs about N operations (DETAIL), more than the budget of B; RAISE"
// when `operations` is above `budget` or not a finite number (NaN counts as too much). `detail`
// says where the count comes from ("256x256 pixels x 100000 lines x 2 images"); `raise` says how
// to do with less or raise the budget ("give --budget 2e10, or fewer lines"); both may be empty.
void checkBudget(double operations, double budget, const std::string& what, const std::string& detail,
                 const std::string& raise);

// "1.3e+10" style: 3 significant digits (whole numbers below 1e6 as they are).
std::string operationsText(double operations);

// `v` rounded up to 3 significant digits (what operationsText and "%.3g" show); `v` itself when it
// is not a positive finite number.
double roundUpTo3Digits(double v);

// The smallest size s >= `size` (3 significant digits, rounded up) with count(s) <= limit, for
// "use a --voxel of at least S" messages; `count` must fall (weakly) as the size grows. Bounded:
// at most a few thousand evaluations of `count`, whatever `size` is (1e-300 included; a count of
// +infinity or NaN at `size` is fine). Returns +infinity when no finite size up to 1e300 fits.
double smallestFittingSize(const std::function<double(double)>& count, double size, double limit);

}  // namespace vdg::morph
