// Self-intersections of a triangle mesh (vdg/geom/self_intersection.h): a uniform grid for the
// broad phase, Moller's interval test (Journal of Graphics Tools 2(2), 1997) for each pair.
#include "vdg/geom/self_intersection.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <mutex>
#include <numeric>

#include <Eigen/Geometry>

#include "vdg/geom/parallel.h"

namespace vdg {
namespace {

using Eigen::Vector3d;
using Tri = std::array<Vector3d, 3>;

// Interval of a triangle on the planes' common line (Moller's compute_intervals): p are its
// vertices' projections on the line, d their distances to the other plane (0 when within the
// tolerance); the vertex alone on its side of the plane cuts the two edges that leave it.
void lineInterval(const std::array<double, 3>& p, const std::array<double, 3>& d, double& lo, double& hi) {
  int k = 0;
  if (d[0] * d[1] > 0)
    k = 2;
  else if (d[0] * d[2] > 0)
    k = 1;
  else if (d[1] * d[2] > 0 || d[0] != 0)
    k = 0;
  else if (d[1] != 0)
    k = 1;
  else
    k = 2;
  const int i = (k + 1) % 3, j = (k + 2) % 3;
  const double t0 = p[k] + (p[i] - p[k]) * d[k] / (d[k] - d[i]);
  const double t1 = p[k] + (p[j] - p[k]) * d[k] / (d[k] - d[j]);
  lo = std::min(t0, t1);
  hi = std::max(t0, t1);
}

// Signed distances of t's vertices to the plane (unit normal n through o), snapped to 0 within tol.
// False when all three are strictly on one side (no intersection).
bool planeDistances(const Vector3d& n, const Vector3d& o, const Tri& t, double tol, std::array<double, 3>& d) {
  for (int k = 0; k < 3; ++k) {
    d[k] = n.dot(t[k] - o);
    if (std::abs(d[k]) <= tol) d[k] = 0.0;
  }
  return !((d[0] > 0 && d[1] > 0 && d[2] > 0) || (d[0] < 0 && d[1] < 0 && d[2] < 0));
}

double cross2(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  return (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
}

bool strictlyInside(const Eigen::Vector2d& p, const std::array<Eigen::Vector2d, 3>& t) {
  const double a = cross2(t[0], t[1], p), b = cross2(t[1], t[2], p), c = cross2(t[2], t[0], p);
  return (a > 0 && b > 0 && c > 0) || (a < 0 && b < 0 && c < 0);
}

// Coplanar pair: projected on the plane's dominant axes, edges that properly cross or a corner
// strictly inside the other triangle.
bool coplanarIntersect(const Tri& a, const Tri& b, const Vector3d& n) {
  int drop = 0;
  n.cwiseAbs().maxCoeff(&drop);
  const int u = drop == 0 ? 1 : 0, v = drop == 2 ? 1 : 2;
  std::array<Eigen::Vector2d, 3> p, q;
  for (int k = 0; k < 3; ++k) {
    p[k] = {a[k][u], a[k][v]};
    q[k] = {b[k][u], b[k][v]};
  }
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      const auto &p0 = p[i], &p1 = p[(i + 1) % 3], &q0 = q[j], &q1 = q[(j + 1) % 3];
      if (cross2(p0, p1, q0) * cross2(p0, p1, q1) < 0 && cross2(q0, q1, p0) * cross2(q0, q1, p1) < 0) return true;
    }
  for (int k = 0; k < 3; ++k)
    if (strictlyInside(p[k], q) || strictlyInside(q[k], p)) return true;
  return false;
}

struct Grid {
  Vector3d origin;
  double cell = 1.0;
  std::array<std::int64_t, 3> size{1, 1, 1};
  std::int64_t key(std::int64_t x, std::int64_t y, std::int64_t z) const { return x + size[0] * (y + size[1] * z); }
  std::int64_t index(double value, int axis) const {
    return std::clamp<std::int64_t>(static_cast<std::int64_t>(std::floor((value - origin[axis]) / cell)), 0,
                                    size[axis] - 1);
  }
};

struct Boxes {
  std::vector<Eigen::AlignedBox3d> box;
  std::vector<std::array<std::int64_t, 6>> cells;  // lo x, y, z, hi x, y, z
};

Grid makeGrid(const Boxes& b, std::size_t count) {
  Eigen::AlignedBox3d all;
  double mean = 0;
  for (const auto& box : b.box) {
    all.extend(box);
    mean += box.sizes().maxCoeff();
  }
  Grid g;
  g.origin = all.min();
  const Vector3d extent = all.sizes();
  g.cell = std::max({2.0 * mean / static_cast<double>(std::max<std::size_t>(count, 1)), extent.maxCoeff() * 1e-6,
                     std::numeric_limits<double>::min()});
  const double budget = kMaxGridCellsPerTriangle * static_cast<double>(count) + 1.0;
  double cells = 1;
  for (int a = 0; a < 3; ++a) cells *= std::floor(extent[a] / g.cell) + 1;
  if (cells > budget) g.cell *= std::cbrt(cells / budget) * 1.01;
  for (int a = 0; a < 3; ++a) g.size[a] = static_cast<std::int64_t>(std::floor(extent[a] / g.cell)) + 1;
  return g;
}

}  // namespace

bool trianglesIntersect(const Vector3d& a0, const Vector3d& a1, const Vector3d& a2, const Vector3d& b0,
                        const Vector3d& b1, const Vector3d& b2, double tolerance) {
  const Tri a{a0, a1, a2}, b{b0, b1, b2};
  const Vector3d na = (a1 - a0).cross(a2 - a0), nb = (b1 - b0).cross(b2 - b0);
  const double tol2 = tolerance * tolerance;
  if (!(na.norm() > tol2) || !(nb.norm() > tol2)) return false;  // degenerate (or not finite)
  const Vector3d ua = na.normalized(), ub = nb.normalized();
  std::array<double, 3> db{}, da{};
  if (!planeDistances(ua, a0, b, tolerance, db)) return false;
  if (!planeDistances(ub, b0, a, tolerance, da)) return false;
  const Vector3d line = ua.cross(ub);
  constexpr double kParallel = 1e-12;  // |sin| of the planes' angle below which they are parallel
  if ((db[0] == 0 && db[1] == 0 && db[2] == 0) || line.norm() < kParallel) {
    if (db[0] != 0 || db[1] != 0 || db[2] != 0) return false;  // parallel planes apart
    return coplanarIntersect(a, b, ua);
  }
  // A triangle with no vertex strictly on each side of the other's plane only touches it (a corner
  // or an edge resting on it): nothing passes through.
  auto straddles = [](const std::array<double, 3>& d) {
    return std::min({d[0], d[1], d[2]}) < 0 && std::max({d[0], d[1], d[2]}) > 0;
  };
  if (!straddles(da) || !straddles(db)) return false;
  std::array<double, 3> pa{}, pb{};
  for (int k = 0; k < 3; ++k) {
    pa[k] = line.dot(a[k]);
    pb[k] = line.dot(b[k]);
  }
  double alo = 0, ahi = 0, blo = 0, bhi = 0;
  lineInterval(pa, da, alo, ahi);
  lineInterval(pb, db, blo, bhi);
  return std::min(ahi, bhi) - std::max(alo, blo) > tolerance * line.norm();
}

std::vector<std::int32_t> weldByPosition(std::span<const float> positions) {
  const std::size_t n = positions.size() / 3;
  std::vector<std::int32_t> order(n), weld(n);
  std::iota(order.begin(), order.end(), 0);
  auto at = [&](std::int32_t v) {
    return std::array<float, 3>{positions[3 * v], positions[3 * v + 1], positions[3 * v + 2]};
  };
  std::stable_sort(order.begin(), order.end(), [&](std::int32_t x, std::int32_t y) { return at(x) < at(y); });
  for (std::size_t i = 0; i < n; ++i)
    weld[order[i]] = (i > 0 && at(order[i]) == at(order[i - 1])) ? weld[order[i - 1]] : order[i];
  return weld;
}

std::vector<std::pair<std::int32_t, std::int32_t>> selfIntersections(std::span<const float> positions,
                                                                     std::span<const std::int32_t> triangles,
                                                                     std::span<const std::int32_t> weld,
                                                                     double tolerance) {
  const std::size_t count = triangles.size() / 3;
  if (count < 2) return {};
  auto vertex = [&](std::size_t f, int k) {
    const auto v = static_cast<std::size_t>(triangles[3 * f + k]);
    return Vector3d(positions[3 * v], positions[3 * v + 1], positions[3 * v + 2]);
  };
  auto id = [&](std::size_t f, int k) {
    const std::int32_t v = triangles[3 * f + k];
    return weld.empty() ? v : weld[static_cast<std::size_t>(v)];
  };
  Boxes b;
  b.box.resize(count);
  Eigen::AlignedBox3d all;
  for (std::size_t f = 0; f < count; ++f) {
    for (int k = 0; k < 3; ++k) b.box[f].extend(vertex(f, k));
    all.extend(b.box[f]);
  }
  if (tolerance < 0) tolerance = count ? kIntersectionRelativeTolerance * all.diagonal().norm() : 0.0;
  const Grid g = makeGrid(b, count);
  b.cells.resize(count);
  std::vector<std::pair<std::int64_t, std::int32_t>> entries;
  for (std::size_t f = 0; f < count; ++f) {
    auto& c = b.cells[f];
    for (int a = 0; a < 3; ++a) {
      c[a] = g.index(b.box[f].min()[a] - tolerance, a);
      c[3 + a] = g.index(b.box[f].max()[a] + tolerance, a);
    }
    for (std::int64_t z = c[2]; z <= c[5]; ++z)
      for (std::int64_t y = c[1]; y <= c[4]; ++y)
        for (std::int64_t x = c[0]; x <= c[3]; ++x) entries.emplace_back(g.key(x, y, z), static_cast<std::int32_t>(f));
  }
  std::sort(entries.begin(), entries.end());
  std::vector<std::size_t> runs;  // start of each cell's run, then entries.size()
  for (std::size_t e = 0; e < entries.size(); ++e)
    if (e == 0 || entries[e].first != entries[e - 1].first) runs.push_back(e);
  const std::size_t run_count = runs.size();
  runs.push_back(entries.size());

  std::vector<std::pair<std::int32_t, std::int32_t>> found;
  std::mutex found_mutex;
  detail::parallelChunks(run_count, 64, [&](std::size_t begin, std::size_t end) {
    std::vector<std::pair<std::int32_t, std::int32_t>> local;
    for (std::size_t r = begin; r < end; ++r)
      for (std::size_t e = runs[r]; e < runs[r + 1]; ++e)
        for (std::size_t h = e + 1; h < runs[r + 1]; ++h) {
          const auto i = static_cast<std::size_t>(std::min(entries[e].second, entries[h].second));
          const auto j = static_cast<std::size_t>(std::max(entries[e].second, entries[h].second));
          const auto &ci = b.cells[i], &cj = b.cells[j];
          // Tested once: in the first cell both boxes' cell ranges share.
          if (g.key(std::max(ci[0], cj[0]), std::max(ci[1], cj[1]), std::max(ci[2], cj[2])) != entries[e].first)
            continue;
          Eigen::AlignedBox3d bi = b.box[i];
          bi.min().array() -= tolerance;
          bi.max().array() += tolerance;
          if (!bi.intersects(b.box[j])) continue;
          bool shared = false;
          for (int s = 0; s < 3 && !shared; ++s)
            for (int t = 0; t < 3 && !shared; ++t) shared = id(i, s) == id(j, t);
          if (shared) continue;
          if (trianglesIntersect(vertex(i, 0), vertex(i, 1), vertex(i, 2), vertex(j, 0), vertex(j, 1), vertex(j, 2),
                                 tolerance))
            local.emplace_back(static_cast<std::int32_t>(i), static_cast<std::int32_t>(j));
        }
    const std::lock_guard lock(found_mutex);
    found.insert(found.end(), local.begin(), local.end());
  });
  std::sort(found.begin(), found.end());
  return found;
}

}  // namespace vdg
