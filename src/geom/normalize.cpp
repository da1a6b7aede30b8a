// Robust normalisation: scale by the largest absolute component before summing squares (the
// classical remedy for overflow and underflow in the Euclidean norm, as in LAPACK's dnrm2).
#include "vdg/geom/normalize.h"

#include <algorithm>
#include <cmath>

namespace vdg {
namespace {

// Largest |v_i|; NaN if any component is NaN.
double maxAbs(std::span<const double> v) {
  double m = 0.0;
  for (const double x : v) {
    if (std::isnan(x)) return x;
    m = std::max(m, std::abs(x));
  }
  return m;
}

// Scaled components v_i / m (m finite and > 0) and the length of that scaled vector, in [1, sqrt(n)].
double scaledLength(std::span<const double> v, double m) {
  double sum = 0.0;
  for (const double x : v) {
    const double s = x / m;
    sum += s * s;
  }
  return std::sqrt(sum);
}

}  // namespace

double robustNorm(std::span<const double> v) {
  const double m = maxAbs(v);
  if (!(m > 0.0) || !std::isfinite(m)) return m;  // zero, NaN or +inf
  return m * scaledLength(v, m);
}

double robustNorm(const Eigen::Vector3d& v) { return robustNorm(std::span<const double>(v.data(), 3)); }

std::optional<Eigen::Vector3d> normalizedOrNone(const Eigen::Vector3d& v) {
  const std::span<const double> s(v.data(), 3);
  const double m = maxAbs(s);
  if (!(m > 0.0) || !std::isfinite(m)) return std::nullopt;
  const Eigen::Vector3d scaled = v / m;
  return Eigen::Vector3d(scaled / scaled.norm());  // scaled.norm() is in [1, sqrt(3)]
}

std::optional<Eigen::Quaterniond> normalizedOrNone(const Eigen::Quaterniond& q) {
  const std::span<const double> s(q.coeffs().data(), 4);
  const double m = maxAbs(s);
  if (!(m > 0.0) || !std::isfinite(m)) return std::nullopt;
  const Eigen::Vector4d scaled = q.coeffs() / m;
  return Eigen::Quaterniond(Eigen::Vector4d(scaled / scaled.norm()));
}

}  // namespace vdg
