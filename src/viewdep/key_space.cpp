// KeySpace: key viewpoints at distances (vdg/viewdep/key_space.h; Rademacher 99, section 6's
// future work: key viewpoints at different distances, a tetrahedralisation of space).
#include "vdg/viewdep/key_space.h"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "key_views.h"
#include "vdg/geom/error.h"
#include "vdg/geom/normalize.h"

namespace vdg {

const char* weightSpaceName(WeightSpace space) { return space == WeightSpace::Positions ? "positions" : "directions"; }

namespace {

// Section 3.2.2's sharpness on n weights, relative to the largest: (w_i / w_max)^a / sum (w_j / w_max)^a.
template <int N>
void sharpenTetWeights(Eigen::Matrix<double, N, 1>& w, double alpha) {
  w = w.cwiseMax(0.0);
  const double top = w.maxCoeff();
  if (alpha != 1.0)
    for (int i = 0; i < N; ++i) w[i] = std::pow(w[i] / top, alpha);
  w /= w.sum();
}

// Ericson, Real-Time Collision Detection 5.1.5: the point of triangle (a, b, c) nearest to p, as
// barycentric coordinates (u, v, w) of a, b, c.
Eigen::Vector3d closestOnHullFace(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                  const Eigen::Vector3d& c) {
  const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0.0 && d2 <= 0.0) return {1.0, 0.0, 0.0};
  const Eigen::Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0.0 && d4 <= d3) return {0.0, 1.0, 0.0};
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) {
    const double v = d1 / (d1 - d3);
    return {1.0 - v, v, 0.0};
  }
  const Eigen::Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0.0 && d5 <= d6) return {0.0, 0.0, 1.0};
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) {
    const double w = d2 / (d2 - d6);
    return {1.0 - w, 0.0, w};
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return {0.0, 1.0 - w, w};
  }
  const double denom = 1.0 / (va + vb + vc);
  const double v = vb * denom, w = vc * denom;
  return {1.0 - v - w, v, w};
}

// Tolerance of the inside test on barycentric coordinates (an eye on a face is inside).
constexpr double kTetInsideTolerance = 1e-12;

}  // namespace

KeySpace KeySpace::build(std::span<const Eigen::Vector3d> eyes, const Eigen::Vector3d& center,
                         const ViewSphereSettings& sphere, double falloff, std::span<const std::string> labels) {
  const auto label = [&](std::size_t k) { return k < labels.size() ? labels[k] : "key " + std::to_string(k); };
  if (sphere.scheme != WeightScheme::Linear)
    throw Error("the 'positions' weight space takes the 'linear' scheme only (its tetrahedra weigh linearly), got '" +
                std::string(weightSchemeName(sphere.scheme)) + "'");
  if (eyes.size() < 4)
    throw Error("the 'positions' weight space needs at least 4 keys with eyes not all in one plane, got " +
                std::to_string(eyes.size()));
  if (!(falloff >= 0.0) || !std::isfinite(falloff))
    throw Error("the eye falloff must be a finite distance >= 0 (0: automatic), got " + std::to_string(falloff));
  KeySpace out;
  out.center_ = center;
  Eigen::AlignedBox3d box;
  std::vector<Eigen::Vector3d> views;
  for (std::size_t k = 0; k < eyes.size(); ++k) {
    if (!eyes[k].allFinite()) throw Error(label(k) + ": the eye is not finite");
    const std::optional<Eigen::Vector3d> view = normalizedOrNone(eyes[k] - center);
    if (!view) throw Error(label(k) + ": the eye is at the model centre, so it gives no view direction");
    views.push_back(*view);
    box.extend(eyes[k]);
  }
  out.eyes_.assign(eyes.begin(), eyes.end());
  const double diagonal = box.diagonal().norm();
  out.falloff_ = falloff > 0.0 ? falloff : kAutoFalloff * diagonal;
  // One viewing-sphere point per direction; its keys sorted by distance from the centre.
  const detail::KeyViewGroups groups = detail::groupKeyViews(views);
  out.groups_.resize(groups.first_key.size());
  for (std::size_t k = 0; k < eyes.size(); ++k)
    out.groups_[static_cast<std::size_t>(groups.group_of_key[k])].keys.push_back(static_cast<int>(k));
  std::vector<Eigen::Vector3d> directions;
  std::vector<std::string> group_labels;
  for (std::size_t g = 0; g < out.groups_.size(); ++g) {
    Group& group = out.groups_[g];
    const auto distance = [&](int k) { return (eyes[static_cast<std::size_t>(k)] - center).norm(); };
    std::sort(group.keys.begin(), group.keys.end(), [&](int a, int b) { return distance(a) < distance(b); });
    for (std::size_t i = 0; i < group.keys.size(); ++i) {
      group.distances.push_back(distance(group.keys[i]));
      if (i > 0 && group.distances[i] - group.distances[i - 1] <= kSameEyeFraction * diagonal)
        throw Error(label(static_cast<std::size_t>(group.keys[i])) + ": same eye as " +
                    label(static_cast<std::size_t>(group.keys[i - 1])) + " (same direction and distance)");
    }
    directions.push_back(views[groups.first_key[g]]);
    group_labels.push_back(label(groups.first_key[g]));
  }
  out.sphere_ = ViewSphere::build(directions, sphere, group_labels);
  detail::Tetrahedralisation dt = detail::delaunayTetrahedra(eyes);
  const double min_volume = kFlatFraction * std::max(box.volume(), diagonal * diagonal * diagonal * 1e-9);
  std::size_t solid = 0;
  for (const auto& t : dt.tets) {
    const auto& a = eyes[static_cast<std::size_t>(t[0])];
    Eigen::Matrix3d m;
    m << eyes[static_cast<std::size_t>(t[1])] - a, eyes[static_cast<std::size_t>(t[2])] - a,
        eyes[static_cast<std::size_t>(t[3])] - a;
    if (std::abs(m.determinant()) > min_volume) ++solid;
    out.inverse_.push_back(m.inverse());
  }
  if (solid == 0)
    throw Error("the 'positions' weight space needs key eyes that are not all in one plane (" +
                std::to_string(eyes.size()) + " keys, no tetrahedron between their eyes)");
  out.tets_ = std::move(dt.tets);
  out.neighbours_ = std::move(dt.neighbours);
  for (std::size_t t = 0; t < out.tets_.size(); ++t)
    for (int i = 0; i < 4; ++i)
      if (out.neighbours_[t][static_cast<std::size_t>(i)] < 0) {
        std::array<int, 3> face{};
        for (int j = 0, n = 0; j < 4; ++j)
          if (j != i) face[static_cast<std::size_t>(n++)] = out.tets_[t][static_cast<std::size_t>(j)];
        out.hull_.push_back(face);
        // The face's plane, its unit normal pointing away from the tetrahedron's fourth corner.
        const Eigen::Vector3d& a = eyes[static_cast<std::size_t>(face[0])];
        Eigen::Vector3d n =
            (eyes[static_cast<std::size_t>(face[1])] - a).cross(eyes[static_cast<std::size_t>(face[2])] - a);
        n.normalize();
        if (n.dot(eyes[static_cast<std::size_t>(out.tets_[t][static_cast<std::size_t>(i)])] - a) > 0.0) n = -n;
        out.hull_planes_.emplace_back(n.x(), n.y(), n.z(), -n.dot(a));
      }
  return out;
}

Eigen::Vector4d KeySpace::barycentric(int tet, const Eigen::Vector3d& x) const {
  const auto t = static_cast<std::size_t>(tet);
  const Eigen::Vector3d l = inverse_[t] * (x - eyes_[static_cast<std::size_t>(tets_[t][0])]);
  return {1.0 - l.sum(), l.x(), l.y(), l.z()};
}

// A visibility walk: step across the face the eye is farthest beyond. Every face crossed is a
// Delaunay face (the walk terminates there); a hull face the eye is beyond means it is outside the
// convex hull. A long walk (rounding on slivers) falls back to testing every tetrahedron.
bool KeySpace::locate(const Eigen::Vector3d& x, int start, int& tet, Eigen::Vector4d& bary) const {
  int t = start;
  for (int step = 0; step < kMaxWalkSteps; ++step) {
    bary = barycentric(t, x);
    Eigen::Index worst = 0;
    if (bary.minCoeff(&worst) >= -kTetInsideTolerance) {
      tet = t;
      return true;
    }
    const int next = neighbours_[static_cast<std::size_t>(t)][static_cast<std::size_t>(worst)];
    if (next < 0) return false;
    t = next;
  }
  for (std::size_t i = 0; i < tets_.size(); ++i) {
    bary = barycentric(static_cast<int>(i), x);
    if (bary.minCoeff() >= -kTetInsideTolerance) {
      tet = static_cast<int>(i);
      return true;
    }
  }
  return false;
}

// The nearest point of a convex hull to an outside eye lies on a face whose plane the eye is in
// front of (x - p is in the normal cone at p, a non-negative combination of the normals of the
// faces at p, so one of them has a positive n . (x - p)); and a face whose plane is farther than
// the best distance so far cannot be nearer. Both prune the triangle tests to a handful.
// An eye the walk found beyond a hull face by rounding alone (in front of no face's plane) gets the
// unpruned search.
int KeySpace::nearestHullFace(const Eigen::Vector3d& x, Eigen::Vector3d& bary, double& distance) const {
  const int best = nearestHullFace(x, bary, distance, true);
  return best >= 0 ? best : nearestHullFace(x, bary, distance, false);
}

int KeySpace::nearestHullFace(const Eigen::Vector3d& x, Eigen::Vector3d& bary, double& distance, bool prune) const {
  int best = -1;
  distance = std::numeric_limits<double>::infinity();
  for (std::size_t f = 0; f < hull_.size(); ++f) {
    const double plane = hull_planes_[f].head<3>().dot(x) + hull_planes_[f].w();
    if (prune && (plane <= 0.0 || plane >= distance)) continue;
    const Eigen::Vector3d& a = eyes_[static_cast<std::size_t>(hull_[f][0])];
    const Eigen::Vector3d& b = eyes_[static_cast<std::size_t>(hull_[f][1])];
    const Eigen::Vector3d& c = eyes_[static_cast<std::size_t>(hull_[f][2])];
    const Eigen::Vector3d u = closestOnHullFace(x, a, b, c);
    const double d = (u.x() * a + u.y() * b + u.z() * c - x).norm();
    if (d < distance) {
      distance = d;
      bary = u;
      best = static_cast<int>(f);
    }
  }
  return best;
}

bool KeySpace::weights(const Eigen::Vector3d& eye, double sharpness, std::span<float> out, int* hint) const {
  if (!eye.allFinite() || !(sharpness > 0.0) || !std::isfinite(sharpness) || out.size() != eyes_.size() + 1)
    return false;
  if (hint && (*hint < -1 || *hint >= static_cast<int>(tets_.size()))) return false;
  int tet = -1;
  Eigen::Vector4d bary;
  if (locate(eye, hint && *hint >= 0 ? *hint : 0, tet, bary)) {
    sharpenTetWeights<4>(bary, sharpness);
    std::fill(out.begin(), out.end(), 0.0f);
    for (std::size_t i = 0; i < 4; ++i)
      out[static_cast<std::size_t>(tets_[static_cast<std::size_t>(tet)][i])] +=
          static_cast<float>(bary[static_cast<Eigen::Index>(i)]);
    if (hint) *hint = tet;
    return true;
  }
  // Outside the hull: the hull's weights at the nearest hull point, turning into the direction
  // sphere's over the falloff distance (smoothstep; see the header).
  Eigen::Vector3d face_bary;
  double distance = 0.0;
  const int face = nearestHullFace(eye, face_bary, distance);
  sharpenTetWeights<3>(face_bary, sharpness);
  const double u = std::min(1.0, distance / falloff_);
  const double t = u * u * (3.0 - 2.0 * u);
  ViewWeights sphere_weights;
  const Eigen::Vector3d from_center = eye - center_;
  if (t > 0.0 && !sphere_.weights(from_center, sharpness, sphere_weights)) return false;  // the centre itself
  std::fill(out.begin(), out.end(), 0.0f);
  for (std::size_t i = 0; i < 3; ++i)
    out[static_cast<std::size_t>(hull_[static_cast<std::size_t>(face)][i])] +=
        static_cast<float>((1.0 - t) * face_bary[static_cast<Eigen::Index>(i)]);
  if (t == 0.0) return true;
  const double r = from_center.norm();
  for (std::size_t s = 0; s < 3; ++s) {
    if (sphere_weights.key[s] < 0) continue;
    const Group& g = groups_[static_cast<std::size_t>(sphere_weights.key[s])];
    const double w = t * sphere_weights.weight[s];
    // Piecewise linear in the distance between the group's keys, clamped at both ends.
    const auto above = std::upper_bound(g.distances.begin(), g.distances.end(), r);
    if (above == g.distances.begin() || above == g.distances.end()) {
      out[static_cast<std::size_t>(above == g.distances.begin() ? g.keys.front() : g.keys.back())] +=
          static_cast<float>(w);
      continue;
    }
    const auto i = static_cast<std::size_t>(above - g.distances.begin());
    const double f = (r - g.distances[i - 1]) / (g.distances[i] - g.distances[i - 1]);
    out[static_cast<std::size_t>(g.keys[i - 1])] += static_cast<float>(w * (1.0 - f));
    out[static_cast<std::size_t>(g.keys[i])] += static_cast<float>(w * f);
  }
  out.back() += static_cast<float>(t * sphere_weights.base);
  return true;
}

}  // namespace vdg
