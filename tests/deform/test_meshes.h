// Tiny meshes generated in code for the deform tests.
#pragma once

#include <cmath>
#include <numbers>

#include "vdg/geom/tri_mesh.h"

namespace vdg::test {

// An n x n vertex grid in the z = 0 plane, spacing h, centred at the origin; vertex (i, j) is
// index j * n + i at x = (i - (n-1)/2) h, y = (j - (n-1)/2) h. Two triangles per cell, counter-clockwise.
inline TriMesh grid(int n, double h) {
  TriMesh m;
  const double c = 0.5 * (n - 1);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
      m.positions.insert(m.positions.end(), {static_cast<float>((i - c) * h), static_cast<float>((j - c) * h), 0.0f});
  for (int j = 0; j + 1 < n; ++j)
    for (int i = 0; i + 1 < n; ++i) {
      const int a = j * n + i, b = a + 1, d = a + n, e = d + 1;
      // Alternate the diagonal so that the grid has no preferred direction.
      if ((i + j) % 2 == 0)
        m.triangles.insert(m.triangles.end(), {a, b, e, a, e, d});
      else
        m.triangles.insert(m.triangles.end(), {a, b, d, b, e, d});
    }
  return m;
}

// A UV sphere of radius r: `rings` latitude bands, `segments` longitudes, poles as single vertices.
// Vertex 0 is the north pole (0, r, 0).
inline TriMesh sphere(int rings, int segments, double r) {
  TriMesh m;
  m.positions.insert(m.positions.end(), {0.0f, static_cast<float>(r), 0.0f});
  for (int k = 1; k < rings; ++k) {
    const double theta = std::numbers::pi * k / rings;
    for (int s = 0; s < segments; ++s) {
      const double phi = 2 * std::numbers::pi * s / segments;
      m.positions.insert(m.positions.end(), {static_cast<float>(r * std::sin(theta) * std::cos(phi)),
                                             static_cast<float>(r * std::cos(theta)),
                                             static_cast<float>(-r * std::sin(theta) * std::sin(phi))});
    }
  }
  const int south = static_cast<int>(m.positions.size() / 3);
  m.positions.insert(m.positions.end(), {0.0f, static_cast<float>(-r), 0.0f});
  auto ring = [&](int k, int s) { return 1 + (k - 1) * segments + (s % segments); };
  for (int s = 0; s < segments; ++s) m.triangles.insert(m.triangles.end(), {0, ring(1, s), ring(1, s + 1)});
  for (int k = 1; k + 1 < rings; ++k)
    for (int s = 0; s < segments; ++s) {
      const int a = ring(k, s), b = ring(k, s + 1), c = ring(k + 1, s), d = ring(k + 1, s + 1);
      m.triangles.insert(m.triangles.end(), {a, c, d, a, d, b});
    }
  for (int s = 0; s < segments; ++s)
    m.triangles.insert(m.triangles.end(), {south, ring(rings - 1, s + 1), ring(rings - 1, s)});
  return m;
}

}  // namespace vdg::test
