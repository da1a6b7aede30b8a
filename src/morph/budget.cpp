// Work budgets (vdg/morph/budget.h).
#include "vdg/morph/budget.h"

#include <cmath>
#include <cstdio>
#include <limits>

#include "vdg/geom/error.h"

namespace vdg::morph {
namespace {

bool fits(const std::function<double(double)>& count, double size, double limit) {
  const double n = count(size);
  return n <= limit;  // false for NaN
}

}  // namespace

std::string operationsText(double operations) {
  char text[32];
  if (operations >= 0 && operations < 1e6)
    std::snprintf(text, sizeof text, "%.0f", operations);
  else
    std::snprintf(text, sizeof text, "%.3g", operations);
  return text;
}

double roundUpTo3Digits(double v) {
  if (!(v > 0) || !std::isfinite(v)) return v;
  const double scale = std::pow(10.0, 2 - std::floor(std::log10(v)));
  const double r = std::ceil(v * scale - 1e-9) / scale;
  return std::isfinite(r) ? r : v;
}

void checkBudget(double operations, double budget, const std::string& what, const std::string& detail,
                 const std::string& raise) {
  if (operations <= budget) return;  // NaN falls through: refused
  const std::string amount = std::isfinite(operations) ? "about " + operationsText(operations) : "more than 1e308";
  throw Error(what + ": needs " + amount + " operations" + (detail.empty() ? "" : " (" + detail + ")") +
              ", more than the budget of " + operationsText(budget) + (raise.empty() ? "" : "; " + raise));
}

double smallestFittingSize(const std::function<double(double)>& count, double size, double limit) {
  constexpr double kLargest = 1e300;
  if (!(size > 0)) size = std::numeric_limits<double>::min();
  if (fits(count, size, limit)) return size;
  // Grow by factors of 2 until a size fits (at most about 2100 steps from the smallest double).
  double lo = size, hi = size;
  while (!fits(count, hi, limit)) {
    if (hi >= kLargest) return std::numeric_limits<double>::infinity();
    lo = hi;
    hi = std::min(hi * 2, kLargest);
  }
  // Bisect (geometric) between a size that does not fit and one that does.
  for (int i = 0; i < 64 && hi / lo > 1 + 1e-9; ++i) {
    const double mid = std::sqrt(lo) * std::sqrt(hi);
    (fits(count, mid, limit) ? hi : lo) = mid;
  }
  // Round up to the 3 digits a message shows, stepping up while the rounded size does not fit.
  double shown = roundUpTo3Digits(hi);
  for (int i = 0; i < 1000 && !fits(count, shown, limit); ++i) shown = roundUpTo3Digits(shown * 1.001);
  return fits(count, shown, limit) ? shown : hi;
}

}  // namespace vdg::morph
