// Test meshes and models of the render tests, generated here: a UV sphere, the sphere with a
// bump, and a three-key view-dependent sphere.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cmath>
#include <numbers>

#include "vdg/geom/tri_mesh.h"
#include "vdg/viewdep/model.h"

namespace vdg::render {

// UV sphere of radius 1 around the origin, `rings` x `segments`, closed, CCW from outside.
inline TriMesh uvSphere(int rings, int segments) {
  TriMesh m;
  auto add = [&](double x, double y, double z) {
    m.positions.push_back(static_cast<float>(x));
    m.positions.push_back(static_cast<float>(y));
    m.positions.push_back(static_cast<float>(z));
  };
  add(0, 1, 0);
  for (int r = 1; r < rings; ++r) {
    const double phi = std::numbers::pi * r / rings;
    for (int s = 0; s < segments; ++s) {
      const double theta = 2 * std::numbers::pi * s / segments;
      add(std::sin(phi) * std::sin(theta), std::cos(phi), std::sin(phi) * std::cos(theta));
    }
  }
  add(0, -1, 0);
  const int south = static_cast<int>(m.vertexCount()) - 1;
  auto ring = [&](int r, int s) { return 1 + (r - 1) * segments + (s % segments); };
  auto tri = [&](int a, int b, int c) {
    m.triangles.push_back(a);
    m.triangles.push_back(b);
    m.triangles.push_back(c);
  };
  for (int s = 0; s < segments; ++s) tri(0, ring(1, s), ring(1, s + 1));
  for (int r = 1; r < rings - 1; ++r)
    for (int s = 0; s < segments; ++s) {
      tri(ring(r, s), ring(r + 1, s), ring(r + 1, s + 1));
      tri(ring(r, s), ring(r + 1, s + 1), ring(r, s + 1));
    }
  for (int s = 0; s < segments; ++s) tri(south, ring(rings - 1, s + 1), ring(rings - 1, s));
  return m;
}

// The sphere with a bump towards `dir` (vertices within 60 degrees pushed out by up to `amount`).
inline TriMesh bumped(const TriMesh& base, const Eigen::Vector3d& dir, double amount) {
  TriMesh m = base;
  for (std::size_t v = 0; v < m.vertexCount(); ++v) {
    Eigen::Vector3d p(m.positions[v * 3], m.positions[v * 3 + 1], m.positions[v * 3 + 2]);
    const double c = p.normalized().dot(dir.normalized());
    if (c > 0.5) p *= 1.0 + amount * (c - 0.5) / 0.5;
    for (int i = 0; i < 3; ++i) m.positions[v * 3 + i] = static_cast<float>(p[i]);
  }
  return m;
}

// A sphere with three keys: a bump to the front (+Z), one to the right (+X), one up (+Y);
// uncovered regions revert to the base through dummy keys.
inline RawViewDependentModel bumpyModel() {
  RawViewDependentModel raw;
  raw.source = "test model";
  raw.base = uvSphere(24, 32);
  const std::array<Eigen::Vector3d, 3> views{Eigen::Vector3d(0, 0, 1), Eigen::Vector3d(1, 0, 0),
                                             Eigen::Vector3d(0, 1, 0)};
  const std::array<const char*, 3> names{"front", "right", "top"};
  // Each key bumps the side perpendicular to its view, so the bump changes the outline.
  const std::array<Eigen::Vector3d, 3> bumps{Eigen::Vector3d(1, 0.3, 0), Eigen::Vector3d(0, 1, -0.3),
                                             Eigen::Vector3d(-1, 0, 0.3)};
  for (int k = 0; k < 3; ++k) {
    RawKey key;
    key.name = names[k];
    key.mesh = bumped(raw.base, bumps[k], 0.45);
    key.view = views[k];
    raw.keys.push_back(key);
  }
  raw.center = Eigen::Vector3d::Zero();
  return raw;
}

}  // namespace vdg::render
