// Uniformly distributed unit directions for property tests of the viewing sphere (a normalised
// Gaussian vector is uniform on the sphere).
#pragma once

#include <random>

#include <Eigen/Core>

namespace vdg::testing {

inline Eigen::Vector3d randomDirection(std::mt19937& rng) {
  std::normal_distribution<double> n;
  Eigen::Vector3d v;
  do {
    v = Eigen::Vector3d(n(rng), n(rng), n(rng));
  } while (v.norm() < 1e-6);
  return v.normalized();
}

}  // namespace vdg::testing
