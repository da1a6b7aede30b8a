// Free-form deformation (Sederberg and Parry, "Free-Form Deformation of Solid Geometric Models",
// SIGGRAPH 86; cited by Rademacher 99, section 3.1.2) and affine squash and stretch (Parent,
// section 4.10).
//
// An FFD lattice is a parallelepiped with origin X0 and edge vectors S, T, U (the columns of
// `axes`, any non-degenerate frame: world axes, or the key camera's right/up/back), holding
// (l+1)(m+1)(n+1) control points P_ijk. A point X inside has local coordinates (s, t, u) with
// X = X0 + s S + t T + u U, each in [0, 1]; the deformed point is the trivariate Bernstein sum
//   X' = sum_i sum_j sum_k B_i^l(s) B_j^m(t) B_k^n(u) P_ijk,  B_i^l(s) = C(l,i) s^i (1-s)^(l-i).
// Undisplaced control points P_ijk = X0 + (i/l) S + (j/m) T + (k/n) U reproduce X exactly (up to
// rounding), and an affine map of the control points maps every embedded point by that same map.
// Points outside the lattice are not moved.
//
// Precompute/apply: bindFfd() records the local coordinates of the embedded vertices once; each
// applyFfd() with moved control points is then a Bernstein evaluation per bound vertex.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include <Eigen/Core>

namespace vdg {

struct FfdLattice {
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  Eigen::Matrix3d axes = Eigen::Matrix3d::Identity();  // columns S, T, U (world units)
  std::array<int, 3> degree{1, 1, 1};                  // l, m, n >= 1
  // (l+1)(m+1)(n+1) points, index controlIndex(i, j, k); world coordinates.
  std::vector<Eigen::Vector3d> control_points;

  std::size_t controlIndex(int i, int j, int k) const {
    return (static_cast<std::size_t>(i) * (degree[1] + 1) + j) * (degree[2] + 1) + k;
  }
  Eigen::Vector3d& point(int i, int j, int k) { return control_points[controlIndex(i, j, k)]; }
  const Eigen::Vector3d& point(int i, int j, int k) const { return control_points[controlIndex(i, j, k)]; }
  // The undisplaced position of control point (i, j, k).
  Eigen::Vector3d restPoint(int i, int j, int k) const;
};

// A lattice with undisplaced control points. Throws vdg::Error for a degree < 1 or > 16, or
// (nearly) singular axes.
FfdLattice makeFfdLattice(const Eigen::Vector3d& origin, const Eigen::Matrix3d& axes, std::array<int, 3> degree);

// The lattice that encloses the given vertices (all when `vertices` is empty) with a margin of
// `padding` times the extent on each side (>= 0), aligned with the orthonormal `frame` (columns:
// the lattice's S, T, U directions; identity = world axes, or the key camera's right, up, back).
// A flat extent (all points in a plane) gets a small thickness so that the lattice stays solid.
FfdLattice ffdLatticeAround(std::span<const float> positions, std::span<const std::int32_t> vertices,
                            const Eigen::Matrix3d& frame, std::array<int, 3> degree, double padding);

struct FfdBinding {
  std::vector<std::int32_t> vertices;  // embedded vertices (inside the lattice)
  std::vector<double> stu;             // #bound x 3 local coordinates
};

// positions: #V x 3. Vertices with local coordinates within [0, 1] (tolerance 1e-9) are bound;
// restrict to `vertices` when it is non-empty.
FfdBinding bindFfd(const FfdLattice& lattice, std::span<const float> positions,
                   std::span<const std::int32_t> vertices = {});

// Moves the bound vertices to their Bernstein image under `lattice` (the same lattice, control
// points moved). Unbound vertices are untouched. Allocates nothing.
void applyFfd(const FfdLattice& lattice, const FfdBinding& binding, std::span<float> positions);

// Affine map about a centre: p' = center + A (p - center) + translation, for all vertices (or the
// listed ones when `vertices` is non-empty).
void applyAffine(std::span<float> positions, std::span<const std::int32_t> vertices, const Eigen::Matrix3d& A,
                 const Eigen::Vector3d& center, const Eigen::Vector3d& translation);

// Squash and stretch (Parent 4.10): scale by `factor` along the unit `axis`, and, when
// preserve_volume, by 1/sqrt(factor) across it (determinant 1). factor > 0.
Eigen::Matrix3d squashStretchMatrix(const Eigen::Vector3d& axis, double factor, bool preserve_volume);

}  // namespace vdg
