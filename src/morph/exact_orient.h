// An exact orientation predicate shared by the shape morphs (spherical_morph.cpp, slice_morph.cpp);
// internal to vdg_morph.
#pragma once

#include <array>
#include <cmath>

#include "d3.h"

namespace vdg::morph::detail {

// ---- Exact sign of a 3 x 3 determinant of doubles -------------------------------------------
// Shewchuk, "Adaptive precision floating-point arithmetic and fast robust geometric predicates"
// (1997): Two-Sum, Two-Product (here through fma) and Grow-Expansion; a floating-point filter first.
// Exact unless a product underflows (coordinates below about 1e-100), which meshes never reach.

inline void twoSum(double a, double b, double& x, double& y) {
  x = a + b;
  const double bv = x - a;
  const double av = x - bv;
  y = (a - av) + (b - bv);
}

inline void twoProduct(double a, double b, double& x, double& y) {
  x = a * b;
  y = std::fma(a, b, -x);
}

// e (length n, non-overlapping, increasing magnitude) += b, in place; zero components dropped.
inline int growExpansion(double* e, int n, double b) {
  double q = b;
  int out = 0;
  for (int i = 0; i < n; ++i) {
    double sum = 0, err = 0;
    twoSum(q, e[i], sum, err);
    q = sum;
    if (err != 0) e[out++] = err;
  }
  if (q != 0 || out == 0) e[out++] = q;
  return out;
}

inline int orientExact(const D3& a, const D3& b, const D3& c) {
  double e[32];
  int n = 0;
  auto add = [&](double x, double y, double z, double sign) {
    double p = 0, pe = 0, h1 = 0, l1 = 0, h2 = 0, l2 = 0;
    twoProduct(x, y, p, pe);
    twoProduct(p, z, h1, l1);
    twoProduct(pe, z, h2, l2);
    n = growExpansion(e, n, sign * l2);
    n = growExpansion(e, n, sign * l1);
    n = growExpansion(e, n, sign * h2);
    n = growExpansion(e, n, sign * h1);
  };
  add(a[0], b[1], c[2], 1);
  add(a[0], b[2], c[1], -1);
  add(a[1], b[2], c[0], 1);
  add(a[1], b[0], c[2], -1);
  add(a[2], b[0], c[1], 1);
  add(a[2], b[1], c[0], -1);
  const double top = e[n - 1];
  return top > 0 ? 1 : (top < 0 ? -1 : 0);
}

// det(a, b, c) = a . (b x c) in floating point.
inline double orientValue(const D3& a, const D3& b, const D3& c) {
  return a[0] * (b[1] * c[2] - b[2] * c[1]) + a[1] * (b[2] * c[0] - b[0] * c[2]) + a[2] * (b[0] * c[1] - b[1] * c[0]);
}

// The exact sign of det(a, b, c): +1 when c is to the left of the great arc a -> b seen from
// outside the sphere (a, b, c counter-clockwise), 0 when the three directions are coplanar.
inline int orientSign(const D3& a, const D3& b, const D3& c) {
  const double det = orientValue(a, b, c);
  const double permanent = std::abs(a[0]) * (std::abs(b[1] * c[2]) + std::abs(b[2] * c[1])) +
                           std::abs(a[1]) * (std::abs(b[2] * c[0]) + std::abs(b[0] * c[2])) +
                           std::abs(a[2]) * (std::abs(b[0] * c[1]) + std::abs(b[1] * c[0]));
  // The evaluation above rounds at most five times along any path: its error is below
  // 6 eps * permanent (eps = 2^-53); 1e-15 leaves room.
  const double bound = 1e-15 * permanent;
  if (det > bound) return 1;
  if (det < -bound) return -1;
  if (permanent == 0) return 0;
  return orientExact(a, b, c);
}

// The exact sign of the 2D orientation of (c, p, q): +1 when q lies to the left of the line from c
// through p (c, p, q counter-clockwise), 0 when the three points are collinear. It is the 3 x 3
// determinant of the rows (x, y, 1).
inline int orient2dSign(double cx, double cy, double px, double py, double qx, double qy) {
  return orientSign(D3{cx, cy, 1.0}, D3{px, py, 1.0}, D3{qx, qy, 1.0});
}

}  // namespace vdg::morph::detail
