// Free-form deformation: Sederberg and Parry, "Free-Form Deformation of Solid Geometric Models",
// SIGGRAPH 86, section 3 (trivariate Bernstein polynomial lattice). Affine squash and stretch:
// Parent, Computer Animation, section 4.10.
#include "vdg/deform/ffd.h"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "vdg/geom/error.h"

namespace vdg {

namespace {
constexpr int kMaxDegree = 16;
constexpr double kInsideTolerance = 1e-9;

// B_i^n(x) for i = 0..n into out[0..n].
void bernstein(int n, double x, double* out) {
  // de Casteljau-style build-up: stable, no binomials.
  out[0] = 1.0;
  for (int j = 1; j <= n; ++j) {
    double saved = 0.0;
    for (int i = 0; i < j; ++i) {
      const double tmp = out[i];
      out[i] = saved + (1.0 - x) * tmp;
      saved = x * tmp;
    }
    out[j] = saved;
  }
}
}  // namespace

Eigen::Vector3d FfdLattice::restPoint(int i, int j, int k) const {
  return origin + axes.col(0) * (static_cast<double>(i) / degree[0]) +
         axes.col(1) * (static_cast<double>(j) / degree[1]) + axes.col(2) * (static_cast<double>(k) / degree[2]);
}

FfdLattice makeFfdLattice(const Eigen::Vector3d& origin, const Eigen::Matrix3d& axes, std::array<int, 3> degree) {
  for (int a = 0; a < 3; ++a)
    if (degree[a] < 1 || degree[a] > kMaxDegree)
      throw Error("FFD lattice: degree " + std::to_string(degree[a]) + " along axis " + std::to_string(a) +
                  " is out of range [1, " + std::to_string(kMaxDegree) + "]");
  const double scale = axes.col(0).norm() * axes.col(1).norm() * axes.col(2).norm();
  if (!(std::abs(axes.determinant()) > 1e-12 * scale) || !axes.allFinite())
    throw Error("FFD lattice: the lattice axes are degenerate (flat or zero-sized)");
  FfdLattice lattice;
  lattice.origin = origin;
  lattice.axes = axes;
  lattice.degree = degree;
  lattice.control_points.resize(static_cast<std::size_t>(degree[0] + 1) * (degree[1] + 1) * (degree[2] + 1));
  for (int i = 0; i <= degree[0]; ++i)
    for (int j = 0; j <= degree[1]; ++j)
      for (int k = 0; k <= degree[2]; ++k) lattice.point(i, j, k) = lattice.restPoint(i, j, k);
  return lattice;
}

FfdLattice ffdLatticeAround(std::span<const float> positions, std::span<const std::int32_t> vertices,
                            const Eigen::Matrix3d& frame, std::array<int, 3> degree, double padding) {
  if (!(padding >= 0)) throw Error("FFD lattice: padding must be >= 0");
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d hi = -lo;
  const std::size_t count = vertices.empty() ? positions.size() / 3 : vertices.size();
  if (count == 0) throw Error("FFD lattice: no vertices to enclose");
  for (std::size_t n = 0; n < count; ++n) {
    const std::size_t v = vertices.empty() ? n : static_cast<std::size_t>(vertices[n]);
    const Eigen::Vector3d p(positions[3 * v], positions[3 * v + 1], positions[3 * v + 2]);
    const Eigen::Vector3d local = frame.transpose() * p;
    lo = lo.cwiseMin(local);
    hi = hi.cwiseMax(local);
  }
  Eigen::Vector3d extent = hi - lo;
  const double largest = std::max(extent.maxCoeff(), 1e-6);
  for (int a = 0; a < 3; ++a) {
    const double e = std::max(extent[a], 1e-3 * largest);  // keep flat selections solid
    const double pad = padding * e + 0.5 * (e - extent[a]);
    lo[a] -= pad;
    extent[a] = e + 2.0 * padding * e;
  }
  Eigen::Matrix3d axes;
  for (int a = 0; a < 3; ++a) axes.col(a) = frame.col(a) * extent[a];
  return makeFfdLattice(frame * lo, axes, degree);
}

FfdBinding bindFfd(const FfdLattice& lattice, std::span<const float> positions,
                   std::span<const std::int32_t> vertices) {
  FfdBinding binding;
  const Eigen::Matrix3d inverse = lattice.axes.inverse();
  const std::size_t count = vertices.empty() ? positions.size() / 3 : vertices.size();
  for (std::size_t n = 0; n < count; ++n) {
    const std::size_t v = vertices.empty() ? n : static_cast<std::size_t>(vertices[n]);
    const Eigen::Vector3d p(positions[3 * v], positions[3 * v + 1], positions[3 * v + 2]);
    Eigen::Vector3d stu = inverse * (p - lattice.origin);
    if ((stu.array() < -kInsideTolerance).any() || (stu.array() > 1.0 + kInsideTolerance).any()) continue;
    stu = stu.cwiseMax(0.0).cwiseMin(1.0);
    binding.vertices.push_back(static_cast<std::int32_t>(v));
    binding.stu.insert(binding.stu.end(), {stu.x(), stu.y(), stu.z()});
  }
  return binding;
}

void applyFfd(const FfdLattice& lattice, const FfdBinding& binding, std::span<float> positions) {
  const auto [l, m, n] = lattice.degree;
  double bs[kMaxDegree + 1], bt[kMaxDegree + 1], bu[kMaxDegree + 1];
  for (std::size_t b = 0; b < binding.vertices.size(); ++b) {
    bernstein(l, binding.stu[3 * b], bs);
    bernstein(m, binding.stu[3 * b + 1], bt);
    bernstein(n, binding.stu[3 * b + 2], bu);
    Eigen::Vector3d x = Eigen::Vector3d::Zero();
    for (int i = 0; i <= l; ++i)
      for (int j = 0; j <= m; ++j) {
        const double wij = bs[i] * bt[j];
        for (int k = 0; k <= n; ++k) x += (wij * bu[k]) * lattice.point(i, j, k);
      }
    const std::size_t v = static_cast<std::size_t>(binding.vertices[b]);
    positions[3 * v] = static_cast<float>(x.x());
    positions[3 * v + 1] = static_cast<float>(x.y());
    positions[3 * v + 2] = static_cast<float>(x.z());
  }
}

void applyAffine(std::span<float> positions, std::span<const std::int32_t> vertices, const Eigen::Matrix3d& A,
                 const Eigen::Vector3d& center, const Eigen::Vector3d& translation) {
  const std::size_t count = vertices.empty() ? positions.size() / 3 : vertices.size();
  for (std::size_t n = 0; n < count; ++n) {
    const std::size_t v = vertices.empty() ? n : static_cast<std::size_t>(vertices[n]);
    const Eigen::Vector3d p(positions[3 * v], positions[3 * v + 1], positions[3 * v + 2]);
    const Eigen::Vector3d q = center + A * (p - center) + translation;
    positions[3 * v] = static_cast<float>(q.x());
    positions[3 * v + 1] = static_cast<float>(q.y());
    positions[3 * v + 2] = static_cast<float>(q.z());
  }
}

Eigen::Matrix3d squashStretchMatrix(const Eigen::Vector3d& axis, double factor, bool preserve_volume) {
  if (!(factor > 0)) throw Error("squash and stretch: factor must be > 0");
  if (!(axis.norm() > 0)) throw Error("squash and stretch: axis must be non-zero");
  const Eigen::Vector3d a = axis.normalized();
  const Eigen::Matrix3d along = a * a.transpose();
  const double across = preserve_volume ? 1.0 / std::sqrt(factor) : 1.0;
  return factor * along + across * (Eigen::Matrix3d::Identity() - along);
}

}  // namespace vdg
