// Attenuation functions: Rademacher 99, 3.1.2 ((1 - d/r)^2) and Parent 4.10 (power family with a
// maximum distance).
#include "vdg/deform/falloff.h"

#include <cmath>

#include "vdg/geom/error.h"

namespace vdg {

FalloffShape parseFalloffShape(const std::string& name, const std::string& what) {
  if (name == "power") return FalloffShape::kPower;
  if (name == "inverse_power") return FalloffShape::kInversePower;
  throw Error(what + ": unknown falloff '" + name + "' (expected power or inverse_power)");
}

const char* falloffShapeName(FalloffShape shape) { return shape == FalloffShape::kPower ? "power" : "inverse_power"; }

double falloffWeight(const Falloff& falloff, double distance) {
  if (!(distance < falloff.radius)) return 0.0;  // also +inf and NaN
  const double x = distance / falloff.radius;    // in [0, 1)
  if (falloff.shape == FalloffShape::kPower) return std::pow(1.0 - x, falloff.power);
  return falloff.power == 0 ? 1.0 : 1.0 - std::pow(x, falloff.power);
}

void falloffWeights(const Falloff& falloff, std::span<const double> distances, std::span<double> weights) {
  for (std::size_t i = 0; i < distances.size(); ++i) weights[i] = falloffWeight(falloff, distances[i]);
}

std::vector<double> seedWeights(DistanceMetric metric, const Falloff& falloff, std::span<const float> positions,
                                std::span<const std::int32_t> triangles, std::int32_t seed) {
  std::vector<double> w = distancesFrom(metric, positions, triangles, seed);
  falloffWeights(falloff, w, w);
  return w;
}

}  // namespace vdg
