// The viewing sphere of Rademacher, "View-Dependent Geometry", SIGGRAPH 99:
//  - 3.2.1: key viewpoints projected to a sphere, triangulated by their convex hull (Qhull);
//    the view ray from the centre picks the hull triangle it crosses.
//  - 3.2.2: the blending weights are the barycentric coordinates of the crossing point, sharpened
//    by w_i' = w_i^alpha / sum_j w_j^alpha.
//  - 3.3: unspecified regions, filled with dummy base keys or a cosine falloff to the base model.
// See view_sphere.h for the exact generalisation of the paper's single-key cosine formula.
#include "vdg/viewdep/view_sphere.h"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <numbers>
#include <string>

#include "convex_hull.h"
#include "vdg/geom/error.h"
#include "vdg/geom/normalize.h"

namespace vdg {
namespace {

using Eigen::Vector3d;

constexpr double kSameViewRad = ViewSphere::kSameViewRad;
// A hull facet whose plane passes closer than this to the centre does not enclose it.
constexpr double kEnclosureMargin = 1e-4;
// Cone coordinates down to -kInsideTol still count as inside a triangle (edges are shared).
constexpr double kInsideTol = 1e-9;
// Relative eigenvalue below which a point set counts as planar.
constexpr double kPlanarTol = 1e-10;

struct Facet {
  std::array<int, 3> v;
  double centre_distance;  // distance of the centre from the facet plane, positive on the inner side
};

// Evenly spread directions (a Fibonacci lattice): candidate positions for dummy base keys.
std::vector<Vector3d> dummyCandidates() {
  std::vector<Vector3d> dirs;
  const int n = ViewSphere::kDummyCandidates;
  const double golden = std::numbers::pi * (3.0 - std::sqrt(5.0));
  for (int i = 0; i < n; ++i) {
    const double y = 1.0 - (i + 0.5) * 2.0 / n;
    const double r = std::sqrt(std::max(0.0, 1.0 - y * y));
    const double phi = golden * i;
    dirs.emplace_back(r * std::cos(phi), y, r * std::sin(phi));
  }
  return dirs;
}

// Convex hull facets of unit points (full-dimensional sets only), oriented counter-clockwise seen
// from the side away from the centre. Throws vdg::Error if Qhull fails.
std::vector<Facet> hullFacets(const std::vector<Vector3d>& points) {
  std::vector<double> coords;
  coords.reserve(points.size() * 3);
  for (const auto& p : points) coords.insert(coords.end(), {p.x(), p.y(), p.z()});
  std::vector<Facet> facets;
  for (const detail::HullFacet& h : detail::convexHull3d(coords)) {
    std::array<int, 3> v = h.v;
    const Vector3d& a = points[v[0]];
    const Vector3d& b = points[v[1]];
    const Vector3d& c = points[v[2]];
    const Vector3d n = (b - a).cross(c - a);
    if (!(n.norm() > 0.0)) continue;  // degenerate sliver: no area, crossed by no ray in its interior
    const Vector3d outward(h.normal[0], h.normal[1], h.normal[2]);
    if (n.dot(outward) < 0.0) std::swap(v[1], v[2]);
    facets.push_back({v, -h.offset});  // offset < 0 when the centre is on the inner side
  }
  return facets;
}

// Solid angle of the spherical triangle (a, b, c) of unit vectors (Van Oosterom and Strackee 1983).
double solidAngle(const Vector3d& a, const Vector3d& b, const Vector3d& c) {
  const double num = std::abs(a.dot(b.cross(c)));
  const double den = 1.0 + a.dot(b) + b.dot(c) + c.dot(a);
  return 2.0 * std::atan2(num, den);
}

// Smallest eigenvector of the scatter of `points` about their mean, and whether they are planar.
struct PlaneFit {
  bool planar;
  Vector3d normal;
  Vector3d centroid;
};
PlaneFit fitPlane(const std::vector<Vector3d>& points) {
  Vector3d mean = Vector3d::Zero();
  for (const auto& p : points) mean += p;
  mean /= static_cast<double>(points.size());
  Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
  for (const auto& p : points) scatter += (p - mean) * (p - mean).transpose();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(scatter);
  const auto& ev = solver.eigenvalues();
  const bool planar = ev(0) <= kPlanarTol * std::max(ev(2), 1e-300);
  return {planar, solver.eigenvectors().col(0), mean};
}

// Orders points lying on one plane by their angle around `axis` about `origin`.
std::vector<int> angularOrder(const std::vector<Vector3d>& points, const Vector3d& axis, const Vector3d& origin) {
  Vector3d u = axis.unitOrthogonal();
  Vector3d w = axis.cross(u);
  std::vector<std::pair<double, int>> order;
  for (int i = 0; i < static_cast<int>(points.size()); ++i) {
    const Vector3d d = points[i] - origin;
    order.emplace_back(std::atan2(d.dot(w), d.dot(u)), i);
  }
  std::sort(order.begin(), order.end());
  std::vector<int> result;
  for (const auto& [angle, i] : order) result.push_back(i);
  return result;
}

}  // namespace

const char* uncoveredName(Uncovered uncovered) {
  switch (uncovered) {
    case Uncovered::Cosine:
      return "cosine";
    case Uncovered::Cosine2:
      return "cosine2";
    case Uncovered::Base:
      break;
  }
  return "base";
}

ViewSphere ViewSphere::build(std::span<const Eigen::Vector3d> key_directions, const ViewSphereSettings& settings,
                             std::span<const std::string> key_labels) {
  if (key_directions.empty()) throw Error("view sphere: a view-dependent model needs at least one key");
  if (!(settings.base_falloff_deg > 0.0 && settings.base_falloff_deg <= 70.0))
    throw Error("view sphere: base_falloff_deg must be in (0, 70] degrees");
  if (!key_labels.empty() && key_labels.size() != key_directions.size())
    throw Error("view sphere: " + std::to_string(key_labels.size()) + " key labels for " +
                std::to_string(key_directions.size()) + " keys (internal error)");
  auto label = [&](std::size_t i) { return key_labels.empty() ? "key " + std::to_string(i) : key_labels[i]; };
  ViewSphere sphere;
  sphere.settings_ = settings;
  sphere.key_count_ = key_directions.size();
  for (std::size_t i = 0; i < key_directions.size(); ++i) {
    const Vector3d& d = key_directions[i];
    if (!d.allFinite()) throw Error(label(i) + ": view direction is not finite");
    const std::optional<Vector3d> u = normalizedOrNone(d);  // any finite length, 1e-300 or 1e300
    if (!u) throw Error(label(i) + ": view direction has zero length");
    sphere.points_.push_back(*u);
  }
  // One O(n log n) pass over all keys (a grid on the sphere), not a comparison of every pair.
  forEachCloseViewPair(sphere.points_, kSameViewRad, [&](std::size_t i, std::size_t j, double) -> bool {
    throw Error(label(i) + ": same view direction as " + label(j) + " (within 1e-6 rad)");
  });

  const std::vector<Vector3d> keys = sphere.points_;
  const std::size_t n = keys.size();
  const PlaneFit fit = n >= 3 ? fitPlane(keys) : PlaneFit{true, Vector3d::UnitZ(), Vector3d::Zero()};
  const bool full_dimensional = n >= 4 && !fit.planar;

  std::vector<Facet> key_facets;
  bool encloses_centre = false;
  if (full_dimensional) {
    key_facets = hullFacets(keys);
    encloses_centre = std::all_of(key_facets.begin(), key_facets.end(),
                                  [](const Facet& f) { return f.centre_distance > kEnclosureMargin; });
  }

  std::vector<Facet> facets;
  if (settings.uncovered == Uncovered::Base) {
    if (encloses_centre) {
      facets = key_facets;
    } else {
      // Section 3.3: insert dummy base keys where no key is near, so the hull encloses the centre.
      const double min_cos = std::cos(settings.base_falloff_deg * std::numbers::pi / 180.0);
      for (const Vector3d& c : dummyCandidates()) {
        const bool near_key =
            std::any_of(keys.begin(), keys.end(), [&](const Vector3d& k) { return k.dot(c) >= min_cos; });
        if (!near_key) sphere.points_.push_back(c);
      }
      facets = hullFacets(sphere.points_);
      for (const Facet& f : facets) {
        if (!(f.centre_distance > 0.0))
          throw Error("view sphere: key viewpoints and dummy base keys do not enclose the centre (internal error)");
      }
    }
  } else if (full_dimensional) {
    // Cosine falloff: the covered region is triangulated by the facets that face away from the
    // centre; facets whose plane passes through (or behind) the centre bound it.
    for (const Facet& f : key_facets)
      if (f.centre_distance > kEnclosureMargin) facets.push_back(f);
    std::map<std::pair<int, int>, int> edge_count;
    for (const Facet& f : facets)
      for (int e = 0; e < 3; ++e) {
        const int a = f.v[e], b = f.v[(e + 1) % 3];
        ++edge_count[{std::min(a, b), std::max(a, b)}];
      }
    for (const auto& [edge, count] : edge_count)
      if (count == 1) sphere.arcs_.push_back({edge.first, edge.second});
  } else if (n >= 3 && std::abs(fit.normal.dot(fit.centroid)) > kEnclosureMargin) {
    // All keys on one small circle: their hull is a flat convex polygon off the centre. Fan it.
    Vector3d axis = fit.normal.dot(fit.centroid) > 0 ? fit.normal : Vector3d(-fit.normal);
    const std::vector<int> order = angularOrder(keys, axis, fit.centroid);
    for (std::size_t i = 1; i + 1 < order.size(); ++i) facets.push_back({{order[0], order[i], order[i + 1]}, 1.0});
    for (std::size_t i = 0; i < order.size(); ++i) sphere.arcs_.push_back({order[i], order[(i + 1) % order.size()]});
  } else if (n >= 3) {
    // All keys on one great circle: the covered region is a chain of arcs, or the whole circle
    // when no gap between neighbours reaches half a turn.
    const std::vector<int> order = angularOrder(keys, fit.normal, Vector3d::Zero());
    std::size_t widest = 0;
    double widest_angle = -1.0;
    for (std::size_t i = 0; i < order.size(); ++i) {
      const Vector3d& a = keys[order[i]];
      const Vector3d& b = keys[order[(i + 1) % order.size()]];
      double angle = std::atan2(a.cross(b).dot(fit.normal), a.dot(b));
      if (angle < 0) angle += 2.0 * std::numbers::pi;
      if (angle > widest_angle) {
        widest_angle = angle;
        widest = i;
      }
    }
    for (std::size_t i = 0; i < order.size(); ++i) {
      if (i == widest && widest_angle >= std::numbers::pi - kSameViewRad) continue;
      const int a = order[i], b = order[(i + 1) % order.size()];
      if (keys[a].dot(keys[b]) > -1.0 + 1e-12) sphere.arcs_.push_back({a, b});
    }
  } else if (n == 2 && keys[0].dot(keys[1]) > -1.0 + 1e-12) {
    sphere.arcs_.push_back({0, 1});
  } else {
    for (int i = 0; i < static_cast<int>(n); ++i) sphere.isolated_.push_back(i);
  }
  // Cosine modes: a key on no triangle and no arc still pulls the views around it.
  if (settings.uncovered != Uncovered::Base && sphere.isolated_.empty()) {
    std::vector<bool> used(n, false);
    for (const Facet& f : facets)
      for (int v : f.v) used[v] = true;
    for (const auto& arc : sphere.arcs_) used[arc[0]] = used[arc[1]] = true;
    for (int i = 0; i < static_cast<int>(n); ++i)
      if (!used[i]) sphere.isolated_.push_back(i);
  }

  double covered = 0.0;
  for (const Facet& f : facets) {
    const Vector3d& a = sphere.points_[f.v[0]];
    const Vector3d& b = sphere.points_[f.v[1]];
    const Vector3d& c = sphere.points_[f.v[2]];
    Eigen::Matrix3d m;
    m << a, b, c;
    Eigen::FullPivLU<Eigen::Matrix3d> lu(m);
    if (!lu.isInvertible()) continue;  // a triangle in a plane through the centre covers nothing
    sphere.triangles_.push_back(f.v);
    sphere.cones_.push_back({lu.inverse()});
    if (!sphere.isDummy(f.v[0]) && !sphere.isDummy(f.v[1]) && !sphere.isDummy(f.v[2])) covered += solidAngle(a, b, c);
  }
  sphere.covered_fraction_ = std::min(1.0, covered / (4.0 * std::numbers::pi));
  return sphere;
}

ViewWeights ViewSphere::locateInTriangle(int t, const Eigen::Vector3d& lambda) const {
  const Vector3d clamped = lambda.cwiseMax(0.0);
  const double sum = clamped.sum();
  ViewWeights w;
  w.triangle = t;
  for (int k = 0; k < 3; ++k) {
    w.key[k] = triangles_[t][k];
    w.weight[k] = static_cast<float>(sum > 0.0 ? clamped[k] / sum : 1.0 / 3.0);
  }
  return w;
}

// Sharpens the three slot weights (section 3.2.2) and moves dummy points' weight to the base.
// w_i^a / sum_j w_j^a is computed as r_i^a / sum_j r_j^a with r_i = w_i / max_j w_j: the same
// value, but the largest term is exactly 1, so the sum never underflows to 0 (plain w^a does for
// a above ~1100 when w <= 1/2) and never overflows. Ties for the largest weight share it evenly.
void ViewSphere::finishWeights(ViewWeights& w, double sharpness) const {
  if (sharpness != 1.0) {
    double largest = 0.0;
    for (int k = 0; k < 3; ++k)
      if (w.key[k] >= 0) largest = std::max(largest, static_cast<double>(w.weight[k]));
    double powered[3] = {0, 0, 0};
    double sum = 0.0;
    for (int k = 0; k < 3; ++k) {
      if (w.key[k] < 0 || !(w.weight[k] > 0.0f)) continue;
      const double r = static_cast<double>(w.weight[k]) / largest;  // in (0, 1]
      powered[k] = r >= 1.0 ? 1.0 : std::pow(r, sharpness);         // pow(r < 1, +inf) = 0
      sum += powered[k];
    }
    if (sum > 0.0)  // sum >= 1 whenever some weight is positive
      for (int k = 0; k < 3; ++k) w.weight[k] = static_cast<float>(powered[k] / sum);
  }
  for (int k = 0; k < 3; ++k) {
    if (w.key[k] >= 0 && isDummy(w.key[k])) {
      w.base += w.weight[k];
      w.key[k] = -1;
      w.weight[k] = 0.0f;
    } else if (w.key[k] >= 0 && w.weight[k] == 0.0f) {
      w.key[k] = -1;
    }
  }
}

ViewWeights ViewSphere::falloff(const Eigen::Vector3d& v, double& nearest_cos) const {
  // Nearest point p of the covered region, and its barycentric weights among the keys.
  double best_cos = -2.0;
  ViewWeights best;
  auto consider_point = [&](int k) {
    const double c = v.dot(points_[k]);
    if (c > best_cos) {
      best_cos = c;
      best = ViewWeights{};
      best.key[0] = k;
      best.weight[0] = 1.0f;
    }
  };
  for (int k : isolated_) consider_point(k);
  for (const auto& arc : arcs_) {
    const Vector3d& a = points_[arc[0]];
    const Vector3d& b = points_[arc[1]];
    const Vector3d n = a.cross(b);
    const double nn = n.squaredNorm();
    const Vector3d proj = v - v.dot(n) / nn * n;
    const double len = proj.norm();
    if (len > 1e-12) {
      const Vector3d q = proj / len;
      const double la = q.cross(b).dot(n) / nn;  // q = la * a + lb * b
      const double lb = a.cross(q).dot(n) / nn;
      if (la >= 0.0 && lb >= 0.0 && la + lb > 0.0) {
        const double c = v.dot(q);
        if (c > best_cos) {
          best_cos = c;
          best = ViewWeights{};
          best.key[0] = arc[0];
          best.key[1] = arc[1];
          best.weight[0] = static_cast<float>(la / (la + lb));
          best.weight[1] = static_cast<float>(lb / (la + lb));
        }
        continue;
      }
    }
    consider_point(arc[0]);
    consider_point(arc[1]);
  }
  nearest_cos = best_cos;
  return best.key[0] < 0 ? ViewWeights{} : best;
}

bool ViewSphere::weights(const Eigen::Vector3d& view, double sharpness, ViewWeights& out, int* hint) const {
  if (!normalizedOrNone(view)) return false;  // zero or non-finite; 1e200 and 1e-200 are fine
  if (!(sharpness > 0.0) || !std::isfinite(sharpness)) return false;
  int local_hint = hint ? *hint : -1;
  if (local_hint < -1 || local_hint >= static_cast<int>(triangles_.size())) return false;
  out = locate(view, sharpness, &local_hint);
  if (hint) *hint = local_hint;
  return true;
}

ViewWeights ViewSphere::locate(const Eigen::Vector3d& view, double sharpness, int* hint) const {
  ViewWeights result;
  const std::optional<Vector3d> unit = normalizedOrNone(view);  // any finite length, 1e-300 or 1e300
  if (!unit) {
    result.base = 1.0f;
    return result;
  }
  const Vector3d v = *unit;

  // Section 3.2.1: the triangle whose cone (centre + triangle) contains the view ray. The cone
  // coordinates lambda = [a b c]^-1 v are non-negative exactly there, and lambda / sum(lambda) are
  // the barycentric coordinates of the point where the ray crosses the planar triangle (3.2.2).
  int found = -1;
  Vector3d found_lambda;
  if (hint && *hint >= 0 && *hint < static_cast<int>(cones_.size())) {
    const Vector3d lambda = cones_[*hint].inverse * v;
    if (lambda.minCoeff() >= -kInsideTol) {
      found = *hint;
      found_lambda = lambda;
    }
  }
  if (found < 0) {
    double best_min = -1e300;
    for (int t = 0; t < static_cast<int>(cones_.size()); ++t) {
      const Vector3d lambda = cones_[t].inverse * v;
      const double m = lambda.minCoeff();
      if (m > best_min && lambda.sum() > 0.0) {
        best_min = m;
        found = t;
        found_lambda = lambda;
        if (m >= -kInsideTol) break;
      }
    }
    // Cosine modes: the view must really be inside a triangle; otherwise it is uncovered.
    if (settings_.uncovered != Uncovered::Base && best_min < -kInsideTol) found = -1;
  }
  if (found >= 0) {
    if (hint) *hint = found;
    result = locateInTriangle(found, found_lambda);
    finishWeights(result, sharpness);
    return result;
  }
  if (settings_.uncovered == Uncovered::Base) {  // unreachable: base mode always encloses
    result.base = 1.0f;
    return result;
  }

  // Section 3.3, cosine falloff towards the base model (generalised; see the header).
  double nearest_cos = 0.0;
  result = falloff(v, nearest_cos);
  if (result.key[0] < 0) {
    result.base = 1.0f;
    return result;
  }
  finishWeights(result, sharpness);
  double f = std::max(0.0, nearest_cos);
  if (settings_.uncovered == Uncovered::Cosine2) f *= f;
  for (int k = 0; k < 3; ++k) result.weight[k] = static_cast<float>(result.weight[k] * f);
  result.base = static_cast<float>(1.0 - f);
  return result;
}

std::size_t forEachCloseViewPair(std::span<const Eigen::Vector3d> directions, double max_angle_rad,
                                 const std::function<bool(std::size_t, std::size_t, double)>& visit) {
  const std::size_t n = directions.size();
  if (n < 2 || !(max_angle_rad > 0.0)) return 0;
  // Two unit vectors less than `max_angle_rad` apart are less than the chord 2 sin(angle / 2)
  // apart in every coordinate, so with cells at least that wide they lie in the same or in
  // adjacent cells of a grid over [-1, 1]^3. Cells narrower than 1e-6 bring nothing but large
  // cell numbers, so the width is at least that (cell numbers then fit 21 bits per axis).
  constexpr double kMinCell = 1e-6;
  constexpr std::int64_t kBias = std::int64_t{1} << 20;
  const double chord = max_angle_rad >= std::numbers::pi ? 2.0 : 2.0 * std::sin(0.5 * max_angle_rad);
  const double cell = std::max(chord * (1.0 + 1e-9), kMinCell);
  auto cellOf = [&](const Vector3d& d) {
    std::array<std::int64_t, 3> c{};
    for (int a = 0; a < 3; ++a) {
      const double x = std::isfinite(d[a]) ? std::floor(d[a] / cell) : 0.0;
      c[a] = static_cast<std::int64_t>(std::clamp(x, static_cast<double>(-kBias + 2), static_cast<double>(kBias - 2)));
    }
    return c;
  };
  auto keyOf = [&](const std::array<std::int64_t, 3>& c) {
    return static_cast<std::uint64_t>(((c[0] + kBias) << 42) | ((c[1] + kBias) << 21) | (c[2] + kBias));
  };
  std::vector<std::pair<std::uint64_t, std::size_t>> sorted(n);
  for (std::size_t i = 0; i < n; ++i) sorted[i] = {keyOf(cellOf(directions[i])), i};
  std::sort(sorted.begin(), sorted.end());

  std::size_t visited = 0;
  std::vector<std::pair<std::size_t, double>> close;  // (j, angle) for the current i
  for (std::size_t i = 0; i < n; ++i) {
    const Vector3d& a = directions[i];
    const std::array<std::int64_t, 3> c = cellOf(a);
    close.clear();
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz) {
          const std::uint64_t key = keyOf({c[0] + dx, c[1] + dy, c[2] + dz});
          auto it = std::lower_bound(sorted.begin(), sorted.end(), std::pair<std::uint64_t, std::size_t>{key, 0});
          for (; it != sorted.end() && it->first == key && it->second < i; ++it) {
            const Vector3d& b = directions[it->second];
            const double angle = std::atan2(a.cross(b).norm(), a.dot(b));
            if (angle < max_angle_rad) close.emplace_back(it->second, angle);
          }
        }
    std::sort(close.begin(), close.end());
    for (const auto& [j, angle] : close) {
      ++visited;
      if (!visit(i, j, angle)) return visited;
    }
  }
  return visited;
}

}  // namespace vdg
