// Attenuation of a deformation with distance from the picked (seed) vertex.
//
// Rademacher 99, section 3.1.2: vertices within 3D distance r of the picked vertex move by the drag
// scaled by (1 - d/r)^2. Parent, section 4.10: the attenuation is one of a family of power functions
// of the distance, with a maximum distance beyond which nothing moves. Two families:
//   kPower         w(d) = (1 - d/r)^p   (p = 2: Rademacher's falloff; p = 0: a rigid selection)
//   kInversePower  w(d) = 1 - (d/r)^p   (flat near the seed, steep at the rim)
// w(0) = 1 (also for p = 0), w(d) = 0 for d >= r, w is in [0, 1]. r > 0, p >= 0.
#pragma once

#include <span>
#include <string>

#include "vdg/deform/distance.h"

namespace vdg {

enum class FalloffShape { kPower, kInversePower };

// "power" | "inverse_power"; throws vdg::Error naming `what` otherwise.
FalloffShape parseFalloffShape(const std::string& name, const std::string& what);
const char* falloffShapeName(FalloffShape shape);

struct Falloff {
  double radius = 1.0;  // r: maximum distance, in the metric's units (model units or edges)
  double power = 2.0;   // p >= 0
  FalloffShape shape = FalloffShape::kPower;
};

double falloffWeight(const Falloff& falloff, double distance);

// weights[i] = falloffWeight(distances[i]); both #V. Allocates nothing.
void falloffWeights(const Falloff& falloff, std::span<const double> distances, std::span<double> weights);

// distancesFrom() + falloffWeights(): the weight of every vertex for a tool picked at `seed`.
std::vector<double> seedWeights(DistanceMetric metric, const Falloff& falloff, std::span<const float> positions,
                                std::span<const std::int32_t> triangles, std::int32_t seed);

}  // namespace vdg
