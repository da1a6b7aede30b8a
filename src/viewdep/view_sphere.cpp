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
#include <cstdio>
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
// Grid cells list a triangle or feature when their bounding caps come within this angle (radians)
// of touching: covers rounding in the caps and in the cell lookup, and views just outside a
// triangle that still count as inside it (kInsideTol) unless at the tip of a needle-thin triangle.
constexpr double kIndexMarginRad = 1e-5;
// Smooth scheme: below this sum of the squared corner products a view is at a corner (about 1e-140
// from it in barycentric terms), where the blend's limit is that corner's one-hot weights.
constexpr double kMinSmoothBlend = 1e-280;

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

// lambda = inverse * v, written out so that it is inlined in the per-query loops.
inline Vector3d coneCoordinates(const Eigen::Matrix3d& m, const Vector3d& v) {
  return {m(0, 0) * v.x() + m(0, 1) * v.y() + m(0, 2) * v.z(), m(1, 0) * v.x() + m(1, 1) * v.y() + m(1, 2) * v.z(),
          m(2, 0) * v.x() + m(2, 1) * v.y() + m(2, 2) * v.z()};
}

// Angle between two unit vectors, accurate also near 0 and pi.
double angleBetween(const Vector3d& a, const Vector3d& b) { return std::atan2(a.cross(b).norm(), a.dot(b)); }

// Point of the cube [-1, 1]^3 on face `face` (0: +x, 1: -x, 2: +y, 3: -y, 4: +z, 5: -z) with face
// coordinates (s, t): the axes after the face's axis, cyclically (as ViewSphere::cellOf reads them).
Vector3d faceDirection(int face, double s, double t) {
  const int axis = face / 2;
  Vector3d d;
  d[axis] = face % 2 == 0 ? 1.0 : -1.0;
  d[(axis + 1) % 3] = s;
  d[(axis + 2) % 3] = t;
  return d;
}

// Section 3.2.2's sharpening, in place: p_i (>= 0, the largest > 0) becomes r_i^alpha with
// r_i = p_i / max_j p_j, so the largest term is 1 and a sum of the results never underflows to 0
// (plain p^alpha does for alpha above ~1100 when p <= 1/2) nor overflows; equal p_i stay equal.
// Multiplications for small integer alpha (the same value to double rounding) without
// data-dependent branches (random views on the per-frame hot path would mispredict them),
// std::pow otherwise.
// The rbf scheme sharpens all its weights (keys and base) the same way: the pointer form.
void sharpenRelative(std::span<double> p, double alpha) {
  const double largest = *std::max_element(p.begin(), p.end());
  const double inverse = 1.0 / largest;
  if (alpha == 2.0) {
    for (double& x : p) x = (x * inverse) * (x * inverse);
  } else if (alpha <= ViewSphere::kMultiplySharpnessMax && alpha == std::floor(alpha)) {
    const int integer = static_cast<int>(alpha);
    for (double& x : p) {
      const double r = x * inverse;
      x = r;
      for (int i = 1; i < integer; ++i) x *= r;
    }
  } else {
    for (double& x : p) x = x == largest ? 1.0 : std::pow(x * inverse, alpha);  // pow(r < 1, +inf) = 0
  }
}
void sharpenRelative(double (&p)[3], double alpha) { sharpenRelative(std::span<double>(p, 3), alpha); }

// The rbf scheme's kernel g of the scaled squared chord q = (chord / chord(width))^2 (view_sphere.h,
// "Weight schemes"; Buhmann 2003 for the Gaussian and the inverse multiquadric, Wendland 1995 for
// the compactly supported psi_{3,1}, positive definite in R^3).
double rbfKernelOfChord2(RbfKernel kernel, double q) {
  switch (kernel) {
    case RbfKernel::InverseMultiquadric:
      return 1.0 / std::sqrt(1.0 + q);
    case RbfKernel::Wendland: {
      const double r = std::sqrt(q);
      if (r >= 1.0) return 0.0;
      const double u = 1.0 - r;
      return u * u * u * u * (4.0 * r + 1.0);
    }
    case RbfKernel::Gaussian:
      break;
  }
  return std::exp(-q);
}

// The rbf scheme's C1 positive part P (view_sphere.h): 0 below 0, r^2 (2e - r) / e^2 on (0, e),
// r from e on (value and slope match at 0 and at e).
double rbfPositivePart(double r) {
  constexpr double e = ViewSphere::kRbfPositiveSoftness;
  if (r >= e) return r;
  if (r <= 0.0) return 0.0;
  return r * r * (2.0 * e - r) / (e * e);
}

// The smooth scheme (view_sphere.h, "Weight schemes"). F(t) = 3t^2 - 2t^3 on [0, 1],
// clamped outside: C1 with F' = 0 at both ends.
double smoothEdgeStep(double t) {
  t = std::clamp(t, 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}

// Where the view v lies between the unit points a and b: t = |v - a| / (|v - a| + |v - b|) (chord
// lengths), 0 at a, 1 at b, monotonic along the arc from a to b. One smooth function of v away from
// a and b, the same for both triangles of the edge (and for the edge taken as (b, a), where it gives
// 1 - t), defined on the whole sphere (a perpendicular projection onto the edge's great circle is
// not: it wraps round inside triangles wider than a quarter turn). Near a, F(t) ~ 3 |v - a|^2 /
// |b - a|^2 is smooth with zero slope, so the blend stays C1 at the keys.
double edgeParameter(const Vector3d& a, const Vector3d& b, const Vector3d& v) {
  const double to_a = std::sqrt(std::max(0.0, 2.0 - 2.0 * v.dot(a)));
  const double to_b = std::sqrt(std::max(0.0, 2.0 - 2.0 * v.dot(b)));
  return to_a / (to_a + to_b);  // a != b (kSameViewRad), so the sum is > 0
}

// The smooth weights of the corners a[0..2] of a hull triangle for the unit view v with the
// triangle's barycentric coordinates b (>= 0, sum 1), into w (>= 0, sum 1): the side-vertex blend
// sum_k beta_k E_k (view_sphere.h). At a corner (where every product b_i b_j is 0) the corner's
// one-hot weights, the limit of the blend there.
void smoothTriangleWeights(const std::array<const Vector3d*, 3>& a, const Vector3d& v, const double (&b)[3],
                           double (&w)[3]) {
  double beta[3], sum = 0.0;
  for (int k = 0; k < 3; ++k) {
    const double product = b[(k + 1) % 3] * b[(k + 2) % 3];
    beta[k] = product * product;
    sum += beta[k];
  }
  if (!(sum > kMinSmoothBlend)) {
    const int largest = static_cast<int>(std::max_element(b, b + 3) - b);
    for (int k = 0; k < 3; ++k) w[k] = k == largest ? 1.0 : 0.0;
    return;
  }
  w[0] = w[1] = w[2] = 0.0;
  for (int k = 0; k < 3; ++k) {  // the edge (k + 1, k + 2) opposite corner k
    const int i = (k + 1) % 3, j = (k + 2) % 3;
    const double f = smoothEdgeStep(edgeParameter(*a[i], *a[j], v));
    const double weight = beta[k] / sum;
    w[i] += weight * (1.0 - f);
    w[j] += weight * f;
  }
}

// Keys all on one great circle (normal `normal`): the covered region is a chain of arcs between
// neighbours, or the whole circle when no gap between neighbours reaches half a turn.
std::vector<std::array<int, 2>> greatCircleArcs(const std::vector<Vector3d>& keys, const Vector3d& normal) {
  std::vector<std::array<int, 2>> arcs;
  const std::vector<int> order = angularOrder(keys, normal, Vector3d::Zero());
  std::size_t widest = 0;
  double widest_angle = -1.0;
  for (std::size_t i = 0; i < order.size(); ++i) {
    const Vector3d& a = keys[order[i]];
    const Vector3d& b = keys[order[(i + 1) % order.size()]];
    double angle = std::atan2(a.cross(b).dot(normal), a.dot(b));
    if (angle < 0) angle += 2.0 * std::numbers::pi;
    if (angle > widest_angle) {
      widest_angle = angle;
      widest = i;
    }
  }
  for (std::size_t i = 0; i < order.size(); ++i) {
    if (i == widest && widest_angle >= std::numbers::pi - kSameViewRad) continue;
    const int a = order[i], b = order[(i + 1) % order.size()];
    if (keys[a].dot(keys[b]) > -1.0 + 1e-12) arcs.push_back({a, b});
  }
  return arcs;
}

// Bounding caps (centre, angular radius) of the triangles: the circle through the three corners
// (all points lie on the unit sphere, and the spherical triangle lies inside the circle's cap as
// its plane does not pass through the centre). A triangle too close to the centre for that gets
// a cap over the whole sphere.
void boundingCaps(const std::vector<Vector3d>& points, const std::vector<std::array<int, 3>>& triangles,
                  std::vector<Vector3d>& cap_centre, std::vector<double>& cap_radius) {
  cap_centre.resize(triangles.size());
  cap_radius.resize(triangles.size());
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    const Vector3d& a = points[triangles[t][0]];
    const Vector3d& b = points[triangles[t][1]];
    const Vector3d& c = points[triangles[t][2]];
    const Vector3d n = (b - a).cross(c - a).normalized();  // outward: counter-clockwise from outside
    cap_centre[t] = n;
    cap_radius[t] = std::max({angleBetween(n, a), angleBetween(n, b), angleBetween(n, c)});
    if (!(n.allFinite() && std::min({n.dot(a), n.dot(b), n.dot(c)}) > 1e-9)) {
      cap_centre[t] = a;
      cap_radius[t] = 2.0 * std::numbers::pi;
    }
  }
}

}  // namespace

const char* weightSchemeName(WeightScheme scheme) {
  switch (scheme) {
    case WeightScheme::Smooth:
      return "smooth";
    case WeightScheme::Rbf:
      return "rbf";
    case WeightScheme::Linear:
      break;
  }
  return "linear";
}

const char* rbfKernelName(RbfKernel kernel) {
  switch (kernel) {
    case RbfKernel::InverseMultiquadric:
      return "inverse-multiquadric";
    case RbfKernel::Wendland:
      return "wendland";
    case RbfKernel::Gaussian:
      break;
  }
  return "gaussian";
}

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
  if (!(settings.rbf_width_deg > 0.0 && settings.rbf_width_deg <= 180.0))
    throw Error("view sphere: the rbf width must be in (0, 180] degrees, got " +
                std::to_string(settings.rbf_width_deg));
  if (settings.scheme == WeightScheme::Rbf && key_directions.size() > kRbfMaxKeys)
    throw Error("view sphere: the rbf weights take at most " + std::to_string(kRbfMaxKeys) + " keys, got " +
                std::to_string(key_directions.size()) + " (use the 'linear' or 'smooth' scheme)");
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
    // All keys on one great circle.
    sphere.arcs_ = greatCircleArcs(keys, fit.normal);
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
  sphere.buildIndex();
  if (settings.scheme == WeightScheme::Rbf) sphere.buildRbf(key_labels);
  return sphere;
}

void ViewSphere::buildIndex() {
  const int triangle_count = static_cast<int>(triangles_.size());
  const int feature_count = static_cast<int>(isolated_.size() + arcs_.size());
  all_features_.resize(static_cast<std::size_t>(feature_count));
  for (int f = 0; f < feature_count; ++f) all_features_[static_cast<std::size_t>(f)] = f;
  // Arc frames: v lies over the arc (a, b) when v.(b x n) >= 0 and v.(n x a) >= 0; those two
  // numbers are also proportional to the barycentric weights of a and b at v's projection.
  arc_frames_.clear();
  for (const auto& arc : arcs_) {
    const Vector3d& a = points_[arc[0]];
    const Vector3d& b = points_[arc[1]];
    const Vector3d normal = a.cross(b).normalized();  // arcs are shorter than half a turn
    arc_frames_.push_back({normal, b.cross(normal), normal.cross(a)});
  }

  // Neighbours across edges: the edge opposite corner k is (v[k+1], v[k+2]).
  std::map<std::pair<int, int>, std::vector<std::pair<int, int>>> edges;  // edge -> (triangle, corner)
  for (int t = 0; t < triangle_count; ++t)
    for (int k = 0; k < 3; ++k) {
      const int a = triangles_[t][(k + 1) % 3], b = triangles_[t][(k + 2) % 3];
      edges[{std::min(a, b), std::max(a, b)}].emplace_back(t, k);
    }
  neighbours_.assign(triangles_.size(), {-1, -1, -1});
  for (const auto& [edge, sides] : edges)
    for (const auto& [t, k] : sides)
      for (const auto& [u, j] : sides)
        if (u != t && neighbours_[t][k] < 0) neighbours_[t][k] = u;

  std::vector<Vector3d> cap_centre;
  std::vector<double> cap_radius;
  boundingCaps(points_, triangles_, cap_centre, cap_radius);

  // The build tests every (cell, item) pair once, so very large key sets get coarser cells: at most
  // kMaxIndexPairs pairs (lists grow instead, and stay exact).
  const double items = std::max(1, triangle_count + feature_count);
  const int affordable = static_cast<int>(std::floor(std::sqrt(kMaxIndexPairs / (6.0 * items))));
  const int n = std::clamp(static_cast<int>(std::ceil(std::sqrt(kCellsPerItem * items / 6.0))), kMinGridSize,
                           std::clamp(affordable, kMinGridSize, kMaxGridSize));
  grid_size_ = n;
  const std::size_t cells = 6u * static_cast<std::size_t>(n) * static_cast<std::size_t>(n);
  cell_triangle_start_.assign(cells + 1, 0);
  cell_feature_start_.assign(cells + 1, 0);
  cell_triangles_.clear();
  cell_features_.clear();
  std::vector<double> distance(static_cast<std::size_t>(feature_count));
  // The cap around a cell's centre through its farthest corner (the cell, a convex spherical
  // quadrilateral less than 55 degrees across, lies inside it).
  auto cellCap = [&](int face, int i, int j, Vector3d& centre) {
    const double s0 = -1.0 + 2.0 * i / n, s1 = -1.0 + 2.0 * (i + 1) / n;
    const double t0 = -1.0 + 2.0 * j / n, t1 = -1.0 + 2.0 * (j + 1) / n;
    centre = faceDirection(face, 0.5 * (s0 + s1), 0.5 * (t0 + t1)).normalized();
    double radius = 0.0;
    for (const double s : {s0, s1})
      for (const double t : {t0, t1})
        radius = std::max(radius, angleBetween(centre, faceDirection(face, s, t).normalized()));
    return radius;
  };
  // A cheap first test (a dot product) of triangle against cell, from the largest cell cap (the
  // faces are alike): the build costs O(cells x triangles) dot products, plus exact tests of the
  // few pairs that pass.
  double largest_cell = 0.0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      Vector3d centre;
      largest_cell = std::max(largest_cell, cellCap(0, i, j, centre));
    }
  std::vector<double> min_dot(triangles_.size());
  for (int t = 0; t < triangle_count; ++t)
    min_dot[t] = std::cos(std::min(std::numbers::pi, largest_cell + cap_radius[t] + 2.0 * kIndexMarginRad)) - 1e-9;
  for (int face = 0; face < 6; ++face)
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) {
        const std::size_t cell = (static_cast<std::size_t>(face) * n + i) * n + j;
        const double s0 = -1.0 + 2.0 * i / n, s1 = -1.0 + 2.0 * (i + 1) / n;
        const double t0 = -1.0 + 2.0 * j / n, t1 = -1.0 + 2.0 * (j + 1) / n;
        Vector3d centre;
        const double radius = cellCap(face, i, j, centre);
        // Listed triangles, the ones that cover most of the cell first (counted on a 5 x 5 grid of
        // sample views): the first one tested then usually contains the view.
        std::vector<std::pair<int, int>> listed;  // (-covered samples, triangle)
        for (int t = 0; t < triangle_count; ++t) {
          if (centre.dot(cap_centre[t]) < min_dot[t] ||
              !(angleBetween(centre, cap_centre[t]) <= radius + cap_radius[t] + kIndexMarginRad))
            continue;
          int covered = 0;
          for (int a = 0; a < 5; ++a)
            for (int b = 0; b < 5; ++b) {
              const Vector3d sample =
                  faceDirection(face, s0 + (s1 - s0) * (a + 0.5) / 5, t0 + (t1 - t0) * (b + 0.5) / 5).normalized();
              covered += coneCoordinates(cones_[t].inverse, sample).minCoeff() >= 0.0;
            }
          listed.emplace_back(-covered, t);
        }
        std::sort(listed.begin(), listed.end());
        for (const auto& [covered, t] : listed) cell_triangles_.push_back(t);
        // A feature can be the nearest to some view x of the cell only if its distance from the
        // centre is at most (distance of x to the nearest feature) + radius, and that is at most
        // (the centre's nearest distance) + 2 radius (geodesic distance is 1-Lipschitz).
        if (feature_count > 0) {
          double nearest = 1e300;
          for (int f = 0; f < feature_count; ++f) {
            distance[f] = featureDistance(centre, f);
            nearest = std::min(nearest, distance[f]);
          }
          for (int f = 0; f < feature_count; ++f)
            if (distance[f] <= nearest + 2.0 * radius + kIndexMarginRad) cell_features_.push_back(f);
        }
        cell_triangle_start_[cell + 1] = static_cast<std::uint32_t>(cell_triangles_.size());
        cell_feature_start_[cell + 1] = static_cast<std::uint32_t>(cell_features_.size());
      }
}

int ViewSphere::cellOf(const Eigen::Vector3d& v) const {
  // Written without data-dependent branches: random views would mispredict them.
  const double ax = std::abs(v.x()), ay = std::abs(v.y()), az = std::abs(v.z());
  const bool x_major = (ax >= ay) & (ax >= az);
  const bool y_major = !x_major & (ay >= az);
  const int axis = 2 - 2 * static_cast<int>(x_major) - static_cast<int>(y_major);
  static constexpr int kNext[5] = {0, 1, 2, 0, 1};
  const double major = std::max(ax, std::max(ay, az));  // >= 1 / sqrt(3) for a unit v
  const double s = v[kNext[axis + 1]], t = v[kNext[axis + 2]];
  const int face = 2 * axis + static_cast<int>(v[axis] < 0.0);
  const double scale = 0.5 * grid_size_ / major;
  const int i = std::min(static_cast<int>((s + major) * scale), grid_size_ - 1);
  const int j = std::min(static_cast<int>((t + major) * scale), grid_size_ - 1);
  return (face * grid_size_ + std::max(i, 0)) * grid_size_ + std::max(j, 0);
}

double ViewSphere::featureDistance(const Eigen::Vector3d& x, int feature) const {
  const int isolated = static_cast<int>(isolated_.size());
  if (feature < isolated) return angleBetween(x, points_[isolated_[feature]]);
  // The nearest point of a great-circle arc: the projection onto its circle when that falls on
  // the arc, an end otherwise (as falloff() finds it).
  const auto& arc = arcs_[feature - isolated];
  const Vector3d& a = points_[arc[0]];
  const Vector3d& b = points_[arc[1]];
  const ArcFrame& frame = arc_frames_[feature - isolated];
  const double h = x.dot(frame.normal);
  const double c2 = 1.0 - h * h;
  const double la = x.dot(frame.to_a), lb = x.dot(frame.to_b);
  if (c2 > 1e-24 && la >= 0.0 && lb >= 0.0 && la + lb > 0.0) return std::atan2(std::abs(h), std::sqrt(c2));
  return std::min(angleBetween(x, a), angleBetween(x, b));
}

// Sharpens the (falloff) slot weights (section 3.2.2, see sharpenRelative) and moves dummy points'
// weight to the base. Ties for the largest weight share it evenly.
void ViewSphere::finishWeights(ViewWeights& w, double sharpness) const {
  if (sharpness != 1.0) {
    double p[3] = {0, 0, 0};
    for (int k = 0; k < 3; ++k)
      if (w.key[k] >= 0 && w.weight[k] > 0.0f) p[k] = static_cast<double>(w.weight[k]);
    if (std::max({p[0], p[1], p[2]}) > 0.0) {
      sharpenRelative(p, sharpness);
      const double sum = p[0] + p[1] + p[2];  // >= 1
      for (int k = 0; k < 3; ++k) w.weight[k] = static_cast<float>(p[k] / sum);
    }
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

ViewWeights ViewSphere::falloff(const Eigen::Vector3d& v, std::span<const int> features, double& nearest_cos,
                                Eigen::Vector3d* nearest) const {
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
      if (nearest) *nearest = points_[k];
    }
  };
  const int isolated = static_cast<int>(isolated_.size());
  for (const int feature : features) {
    if (feature < isolated) {
      consider_point(isolated_[feature]);
      continue;
    }
    const auto& arc = arcs_[feature - isolated];
    const ArcFrame& frame = arc_frames_[feature - isolated];
    const double h = v.dot(frame.normal);
    const double c2 = 1.0 - h * h;  // squared length of v's projection onto the arc's plane
    const double la = v.dot(frame.to_a), lb = v.dot(frame.to_b);
    if (c2 > 1e-24 && la >= 0.0 && lb >= 0.0 && la + lb > 0.0) {
      const double c = std::sqrt(c2);  // cosine of the angle to the projection
      if (c > best_cos) {
        best_cos = c;
        best = ViewWeights{};
        best.key[0] = arc[0];
        best.key[1] = arc[1];
        if (nearest) *nearest = (la * points_[arc[0]] + lb * points_[arc[1]]).normalized();
        if (settings_.scheme == WeightScheme::Smooth) {
          // The smooth edge weights at the arc's point p = normalize(la a + lb b) nearest to v
          // (view_sphere.h): continuous where the view leaves the covered region.
          const Vector3d& a = points_[arc[0]];
          const Vector3d& b = points_[arc[1]];
          const double f = smoothEdgeStep(edgeParameter(a, b, (la * a + lb * b).normalized()));
          best.weight[0] = static_cast<float>(1.0 - f);
          best.weight[1] = static_cast<float>(f);
        } else {
          best.weight[0] = static_cast<float>(la / (la + lb));
          best.weight[1] = static_cast<float>(lb / (la + lb));
        }
      }
      continue;
    }
    consider_point(arc[0]);
    consider_point(arc[1]);
  }
  nearest_cos = best_cos;
  return best.key[0] < 0 ? ViewWeights{} : best;
}

bool ViewSphere::checkQuery(const Eigen::Vector3d& view, double sharpness, const int* hint, Eigen::Vector3d& unit,
                            int& start) const {
  if (!(sharpness > 0.0) || !std::isfinite(sharpness)) return false;
  start = hint ? *hint : -1;
  if (start < -1 || start >= static_cast<int>(triangles_.size())) return false;
  // Ordinary lengths directly (NaN and infinity fail the test); 1e-300 or 1e300 long views (and
  // the refused zero and non-finite ones) through the robust normalisation.
  const double squared = view.squaredNorm();
  if (squared >= 1e-250 && squared <= 1e250) {
    unit = view * (1.0 / std::sqrt(squared));
    return true;
  }
  const std::optional<Vector3d> u = normalizedOrNone(view);
  if (!u) return false;  // zero or non-finite
  unit = *u;
  return true;
}

bool ViewSphere::weights(const Eigen::Vector3d& view, double sharpness, ViewWeights& out, int* hint) const {
  Vector3d v;
  int local_hint = -1;
  if (settings_.scheme == WeightScheme::Rbf || !checkQuery(view, sharpness, hint, v, local_hint)) return false;
  out = locate(v, sharpness, &local_hint);
  if (hint) *hint = local_hint;
  return true;
}

bool ViewSphere::weightsByScan(const Eigen::Vector3d& view, double sharpness, ViewWeights& out, int* hint) const {
  Vector3d v;
  int local_hint = -1;
  if (settings_.scheme == WeightScheme::Rbf || !checkQuery(view, sharpness, hint, v, local_hint)) return false;
  out = locateByScan(v, sharpness, &local_hint);
  if (hint) *hint = local_hint;
  return true;
}

// Weights in a triangle (section 3.2.2) in one pass on doubles (the per-frame hot path): barycentric
// weights l_i / sum l, sharpened as (l_i / l_max)^a / sum_j (l_j / l_max)^a (the normalisation by
// sum l cancels), dummy points' weight moved to the base.
ViewWeights ViewSphere::triangleWeights(int t, const Eigen::Vector3d& v, const Eigen::Vector3d& lambda,
                                        double sharpness) const {
  double p[3] = {std::max(lambda[0], 0.0), std::max(lambda[1], 0.0), std::max(lambda[2], 0.0)};
  const double largest = std::max({p[0], p[1], p[2]});
  if (!(largest > 0.0)) {  // unreachable for a unit view inside the cone: equal weights then
    p[0] = p[1] = p[2] = 1.0;
  } else {
    if (settings_.scheme == WeightScheme::Smooth) {
      const double total = p[0] + p[1] + p[2];
      const double b[3] = {p[0] / total, p[1] / total, p[2] / total};
      const auto& corners = triangles_[t];
      smoothTriangleWeights({&points_[corners[0]], &points_[corners[1]], &points_[corners[2]]}, v, b, p);
    }
    if (sharpness != 1.0) sharpenRelative(p, sharpness);
  }
  const double scale = 1.0 / (p[0] + p[1] + p[2]);
  ViewWeights w;
  w.triangle = t;
  for (int k = 0; k < 3; ++k) {
    const int point = triangles_[t][k];
    const float weight = static_cast<float>(p[k] * scale);
    const bool dummy = isDummy(point);
    const bool keep = !dummy && weight != 0.0f;
    w.base += dummy ? weight : 0.0f;
    w.key[k] = keep ? point : -1;
    w.weight[k] = keep ? weight : 0.0f;
  }
  return w;
}

ViewWeights ViewSphere::uncoveredWeights(const Eigen::Vector3d& v, double sharpness, std::span<const int> features,
                                         Eigen::Vector3d* nearest) const {
  // Section 3.3, cosine falloff towards the base model (generalised; see the header).
  ViewWeights result;
  double nearest_cos = 0.0;
  result = falloff(v, features, nearest_cos, nearest);
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

// Section 3.2.1: the triangle whose cone (centre + triangle) contains the view ray. The cone
// coordinates lambda = [a b c]^-1 v are non-negative exactly there, and lambda / sum(lambda) are
// the barycentric coordinates of the point where the ray crosses the planar triangle (3.2.2).
// Base mode always finds one (the one nearest to containing v when rounding leaves a gap).
int ViewSphere::scanTriangles(const Eigen::Vector3d& v, Eigen::Vector3d& found_lambda) const {
  int found = -1;
  double best_min = -1e300;
  for (int t = 0; t < static_cast<int>(cones_.size()); ++t) {
    const Vector3d lambda = coneCoordinates(cones_[t].inverse, v);
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
  return found;
}

ViewWeights ViewSphere::locateByScan(const Eigen::Vector3d& v, double sharpness, int* hint) const {
  int found = -1;
  Vector3d found_lambda;
  if (*hint >= 0) {
    const Vector3d lambda = coneCoordinates(cones_[*hint].inverse, v);
    if (lambda.minCoeff() >= -kInsideTol) {
      found = *hint;
      found_lambda = lambda;
    }
  }
  if (found < 0) found = scanTriangles(v, found_lambda);
  if (found >= 0) {
    *hint = found;
    return triangleWeights(found, v, found_lambda, sharpness);
  }
  if (settings_.uncovered == Uncovered::Base) {  // unreachable: base mode always encloses
    ViewWeights result;
    result.base = 1.0f;
    return result;
  }
  return uncoveredWeights(v, sharpness, all_features_);
}

ViewWeights ViewSphere::locate(const Eigen::Vector3d& v, double sharpness, int* hint, Eigen::Vector3d* nearest) const {
  // Walk from the hint towards the view: across the edge that v lies farthest beyond.
  int t = *hint;
  for (int step = 0; t >= 0 && step <= kMaxWalkSteps; ++step) {
    const Vector3d lambda = coneCoordinates(cones_[t].inverse, v);
    int k = lambda[1] < lambda[0] ? 1 : 0;
    if (lambda[2] < lambda[k]) k = 2;
    if (lambda[k] >= -kInsideTol) {
      *hint = t;
      return triangleWeights(t, v, lambda, sharpness);
    }
    t = neighbours_[t][k];
  }
  // The grid cell's triangles, those covering most of the cell first.
  const int cell = cellOf(v);
  const std::uint32_t begin = cell_triangle_start_[cell], end = cell_triangle_start_[cell + 1];
  for (std::uint32_t i = begin; i < end; ++i) {
    const int c = cell_triangles_[i];
    const Vector3d lambda = coneCoordinates(cones_[c].inverse, v);
    if (lambda.minCoeff() >= -kInsideTol) {
      *hint = c;
      return triangleWeights(c, v, lambda, sharpness);
    }
  }
  if (settings_.uncovered == Uncovered::Base) {
    // Only through rounding at a needle-thin triangle's tip: the scan's choice.
    Vector3d lambda;
    const int found = scanTriangles(v, lambda);
    if (found < 0) {
      ViewWeights result;
      result.base = 1.0f;
      return result;
    }
    *hint = found;
    return triangleWeights(found, v, lambda, sharpness);
  }
  // Cosine modes: no triangle listed in the cell contains v, so none does (the lists hold every
  // triangle that reaches into the cell).
  const std::uint32_t fbegin = cell_feature_start_[cell], fend = cell_feature_start_[cell + 1];
  return uncoveredWeights(v, sharpness, std::span<const int>(cell_features_.data() + fbegin, fend - fbegin), nearest);
}

bool ViewSphere::denseWeights(const Eigen::Vector3d& view, double sharpness, std::span<float> out, int* hint) const {
  Vector3d v;
  int local_hint = -1;
  if (out.size() != key_count_ + 1 || !checkQuery(view, sharpness, hint, v, local_hint)) return false;
  if (settings_.scheme != WeightScheme::Rbf) {
    const ViewWeights w = locate(v, sharpness, &local_hint);
    std::fill(out.begin(), out.end(), 0.0f);
    for (int k = 0; k < 3; ++k)
      if (w.key[k] >= 0) out[static_cast<std::size_t>(w.key[k])] += w.weight[k];
    out.back() = w.base;
  } else if (settings_.uncovered == Uncovered::Base) {  // the whole sphere is covered
    (void)locate(v, 1.0, &local_hint);                  // only to keep the hint's meaning
    rbfWeightsAt(v, sharpness, 1.0, out);
  } else {
    // Cosine modes (view_sphere.h): the rbf weights at the view when it is covered, else at the
    // nearest point p of the covered region, times the falloff f = max(0, v.p) (squared for cosine2).
    Vector3d nearest = v;
    const ViewWeights located = locate(v, 1.0, &local_hint, &nearest);
    double f = 1.0;
    if (located.triangle < 0) {
      // No key at all only when the covered region is out of reach (falloff() found no feature);
      // a key of zero falloff weight leaves its slot empty, so look at every slot.
      const bool reached = located.key[0] >= 0 || located.key[1] >= 0 || located.key[2] >= 0;
      f = reached ? std::max(0.0, v.dot(nearest)) : 0.0;
      if (settings_.uncovered == Uncovered::Cosine2) f *= f;
    }
    rbfWeightsAt(located.triangle < 0 ? nearest : v, sharpness, f, out);
  }
  if (hint) *hint = local_hint;
  return true;
}

// Rbf scheme (view_sphere.h, "Weight schemes"): r_o(x) = b_o + sum_j c_oj g(q_j) with q_j the scaled
// squared chord to centre j, then the positive part, the normalisation and the sharpening; the
// keys get scale x their weight, the base the rest. Stack buffers only (the per-frame rule).
void ViewSphere::rbfWeightsAt(const Eigen::Vector3d& x, double sharpness, double scale, std::span<float> out) const {
  constexpr std::size_t kMaxCentres = kRbfMaxKeys + kDummyCandidates;
  std::array<double, kMaxCentres> phi;
  std::array<double, kRbfMaxKeys + 1> w;
  const std::size_t m = points_.size(), outputs = key_count_ + 1;
  for (std::size_t j = 0; j < m; ++j)
    phi[j] = rbfKernelOfChord2(settings_.rbf_kernel, (x - points_[j]).squaredNorm() / rbf_chord2_);
  // Centre by centre (rbf_rows_: the constants b_o, then each centre's c_oj over the outputs), so
  // that a compactly supported kernel skips the centres out of reach.
  std::copy_n(rbf_rows_.data(), outputs, w.data());
  for (std::size_t j = 0; j < m; ++j) {
    if (phi[j] == 0.0) continue;
    const double* row = rbf_rows_.data() + (j + 1) * outputs;
    for (std::size_t o = 0; o < outputs; ++o) w[o] += row[o] * phi[j];
  }
  double sum = 0.0;
  for (std::size_t o = 0; o < outputs; ++o) {
    w[o] = rbfPositivePart(w[o]);
    sum += w[o];
  }
  // sum >= P(max r) > 0: the r sum to 1 over keys + 1 outputs (see the header).
  if (sharpness != 1.0) {
    for (std::size_t o = 0; o < outputs; ++o) w[o] /= sum;
    sharpenRelative(std::span<double>(w.data(), outputs), sharpness);
    sum = 0.0;
    for (std::size_t o = 0; o < outputs; ++o) sum += w[o];
  }
  const double factor = scale / sum;
  for (std::size_t o = 0; o + 1 < outputs; ++o) out[o] = static_cast<float>(w[o] * factor);
  out[outputs - 1] = static_cast<float>(w[outputs - 1] * factor + (1.0 - scale));
}

// Solves the rbf interpolation once (view_sphere.h): the saddle system [Phi 1; 1^T 0] for the data
// of every output at once (Lewis et al. 2000's pose-space solve with a constant term, Buhmann 2003
// ch. 2 for its solvability), refused when its reciprocal condition number is too small.
void ViewSphere::buildRbf(std::span<const std::string> key_labels) {
  const double half = 0.5 * settings_.rbf_width_deg * std::numbers::pi / 180.0;
  const double chord = 2.0 * std::sin(half);
  rbf_chord2_ = chord * chord;
  const auto m = static_cast<Eigen::Index>(points_.size());
  const auto outputs = static_cast<Eigen::Index>(key_count_ + 1);
  Eigen::MatrixXd system = Eigen::MatrixXd::Zero(m + 1, m + 1);
  Eigen::MatrixXd data = Eigen::MatrixXd::Zero(m + 1, outputs);
  for (Eigen::Index i = 0; i < m; ++i) {
    for (Eigen::Index j = 0; j < m; ++j)
      system(i, j) = rbfKernelOfChord2(settings_.rbf_kernel, (points_[i] - points_[j]).squaredNorm() / rbf_chord2_);
    system(i, m) = system(m, i) = 1.0;
    data(i, isDummy(static_cast<int>(i)) ? outputs - 1 : i) = 1.0;
  }
  const Eigen::PartialPivLU<Eigen::MatrixXd> lu(system);
  const double rcond = lu.rcond();
  if (!(rcond * kRbfMaxCondition >= 1.0)) {
    std::size_t a = 0, b = 0;
    double closest = 1e300;
    for (std::size_t i = 0; i < key_count_; ++i)
      for (std::size_t j = 0; j < i; ++j)
        if (const double d = angleBetween(points_[i], points_[j]); d < closest) {
          closest = d;
          a = i;
          b = j;
        }
    auto label = [&](std::size_t i) { return key_labels.empty() ? "key " + std::to_string(i) : key_labels[i]; };
    char numbers[160];
    std::snprintf(numbers, sizeof(numbers), " (%.3g degrees apart) are too close for a %s width of %g degrees",
                  closest * 180.0 / std::numbers::pi, rbfKernelName(settings_.rbf_kernel), settings_.rbf_width_deg);
    const std::string pair = key_count_ < 2 ? std::string("the key and the dummy base points are too close")
                                            : label(a) + " and " + label(b) + numbers;
    std::snprintf(numbers, sizeof(numbers), "%.2g", rcond);
    throw Error("view sphere: the rbf weights are ill-conditioned (reciprocal condition " + std::string(numbers) +
                "): " + pair + "; lower 'width' or move the keys apart");
  }
  const Eigen::MatrixXd solution = lu.solve(data);
  // Layout (rbfWeightsAt): the constants b_o (solution row m), then per centre j its c_oj.
  rbf_rows_.assign(static_cast<std::size_t>(outputs * (m + 1)), 0.0);
  for (Eigen::Index o = 0; o < outputs; ++o) {
    rbf_rows_[static_cast<std::size_t>(o)] = solution(m, o);
    for (Eigen::Index j = 0; j < m; ++j) rbf_rows_[static_cast<std::size_t>((j + 1) * outputs + o)] = solution(j, o);
  }
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

std::size_t nearlySameViewPairs(std::span<const Eigen::Vector3d> unit_directions, std::size_t max_listed,
                                std::size_t max_counted, std::vector<NearlySameViewPair>& listed) {
  std::size_t count = 0;
  if (max_counted == 0) return 0;
  forEachCloseViewPair(unit_directions, kNearlySameViewDeg * std::numbers::pi / 180.0,
                       [&](std::size_t i, std::size_t j, double angle) {
                         if (angle <= ViewSphere::kSameViewRad) return true;  // one viewpoint (keys at frames)
                         if (++count <= max_listed) listed.push_back({i, j, angle * 180.0 / std::numbers::pi});
                         return count < max_counted;
                       });
  return count;
}

ViewWeights heaviestKeys(std::span<const float> dense) {
  ViewWeights w;
  const std::size_t keys = dense.size() - 1;
  float rest = 1.0f;
  for (int slot = 0; slot < 3; ++slot) {
    int best = -1;
    for (std::size_t k = 0; k < keys; ++k) {
      const bool taken = std::find(w.key.begin(), w.key.end(), static_cast<int>(k)) != w.key.end();
      if (!taken && dense[k] > 0.0f && (best < 0 || dense[k] > dense[static_cast<std::size_t>(best)]))
        best = static_cast<int>(k);
    }
    if (best < 0) break;
    w.key[slot] = best;
    w.weight[slot] = dense[static_cast<std::size_t>(best)];
    rest -= w.weight[slot];
  }
  w.base = std::max(0.0f, rest);
  return w;
}

}  // namespace vdg
