// The extent of what a view-dependent model draws (private to src/viewdep): an axis-aligned box and
// the largest distance from the model's centre, grown mesh by mesh in build().
#pragma once

#include <algorithm>
#include <cmath>
#include <span>

#include <Eigen/Core>

#include "vdg/geom/tri_mesh.h"

namespace vdg::detail {

class ExtentBuilder {
 public:
  explicit ExtentBuilder(const Eigen::Vector3d& center) : center_(center) {}

  // Adds the #V x 3 positions of one mesh (finite: build() validated them or computed them from
  // validated data).
  void add(std::span<const float> positions) {
    for (std::size_t i = 0; i + 2 < positions.size(); i += 3) {
      for (int c = 0; c < 3; ++c) {
        const float x = positions[i + static_cast<std::size_t>(c)];
        box_.min[c] = empty_ ? x : std::min(box_.min[c], x);
        box_.max[c] = empty_ ? x : std::max(box_.max[c], x);
      }
      empty_ = false;
      // In double: a float square overflows past about 1e19.
      const double dx = double(positions[i]) - center_.x(), dy = double(positions[i + 1]) - center_.y(),
                   dz = double(positions[i + 2]) - center_.z();
      radius_ = std::max(radius_, std::sqrt(dx * dx + dy * dy + dz * dz));
    }
  }

  const Bounds& box() const { return box_; }
  double radius() const { return radius_; }

 private:
  Eigen::Vector3d center_;
  Bounds box_;
  bool empty_ = true;
  double radius_ = 1e-6;  // the floor extentRadius() promises
};

}  // namespace vdg::detail
