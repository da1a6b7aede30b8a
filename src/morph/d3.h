// Vectors of three doubles and their products, shared by the shape morphs (internal to vdg_morph):
// the meshes store floats, and the morphs measure and orient in double.
#pragma once

#include <array>

namespace vdg::morph::detail {

using D3 = std::array<double, 3>;

inline D3 sub(const D3& a, const D3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
inline D3 cross(const D3& a, const D3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
inline double dot(const D3& a, const D3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

}  // namespace vdg::morph::detail
