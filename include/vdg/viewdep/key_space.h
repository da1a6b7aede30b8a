// KeySpace — key viewpoints at distances: weights from the camera's eye POSITION, not only its
// direction ("Keys at distances"; docs/weights.md).
//
// Rademacher 99 weighs a view by its direction alone (section 3.2: key viewpoints on the viewing
// sphere), and names key viewpoints at different distances, with a tetrahedralisation of space in
// place of the sphere's triangulation, as future work (section 6). KeySpace is that extension:
//  - Inside the convex hull H of the key eyes: the eyes' Delaunay tetrahedralisation (CGAL's
//    Delaunay_triangulation_3, at build time only); an eye x in tetrahedron (a, b, c, d) gets its
//    barycentric coordinates, the 3D analogue of section 3.2.1's triangle weights:
//      x = sum_i b_i e_i,  sum_i b_i = 1,  b_i >= 0,
//    then the section 3.2.2 sharpness, (b_i / b_max)^alpha / sum_j (b_j / b_max)^alpha.
//  - Outside H: let p be the point of H nearest to x (a point of a hull face, so the face's three
//    barycentric weights h(p) are the inside weights at p), d = |x - p|, and s(x) the fallback
//    weights of the direction sphere (below). With t = S(d / falloff), S(u) = 3u^2 - 2u^3 for u < 1,
//    1 beyond:  w(x) = (1 - t) h(p) + t s(x).
//    p is continuous in x (the projection onto a convex set is 1-Lipschitz) and h is continuous on
//    the hull surface (faces sharing an edge agree on it), so w is continuous at the hull surface
//    (t = 0 there) and everywhere outside up to the model centre (below).
//  - The direction sphere: keys whose eyes lie in one direction from the model centre (within
//    ViewSphere::kSameViewRad) are one point of a ViewSphere (the model's uncovered mode and base
//    falloff; the linear scheme). The group's weight g(x) goes to its keys by the eye's distance
//    r = |x - centre| from the centre, piecewise linearly between the keys' distances r_1 < r_2 <
//    ... and clamped outside [r_1, r_n]: between r_i and r_i+1 key i gets g (r_i+1 - r) / (r_i+1 -
//    r_i), key i+1 the rest. The sphere's base weight stays the base's.
// Properties: at a key's eye the weights are that key's alone (eyes are vertices of the
// tetrahedralisation, and every eye lies in H); the weights sum to 1 and are >= 0 everywhere; they
// are continuous everywhere except at the model centre itself when the centre lies outside H (the
// direction of x is undefined there; weights() refuses that one eye, as the sphere refuses a zero
// view). Inside H they are C0 (kinks across the tetrahedra's faces), as the paper's linear scheme.
//
// Refusals (build(), vdg::Error naming the key): fewer than 4 keys, all eyes coplanar (no
// tetrahedron: H has no volume; give the keys directions instead), two keys with the same eye
// (within kSameEyeFraction of the eyes' extent), a non-finite eye, an eye at the centre.
//
// The query (weights()) is allocation-free and non-throwing, checked on entry: a walk through the
// tetrahedra from the hint (the previous frame's tetrahedron), across the face the eye is farthest
// beyond; crossing a hull face means the eye is outside H (the hull is convex), so the walk stops.
// A walk of more than kMaxWalkSteps steps falls back to testing every tetrahedron. Outside H the
// nearest hull point is searched among the hull faces whose plane the eye is in front of and
// nearer than the best so far: one plane test per hull face, a few triangle tests
// (docs/performance.md has the cost per query).
#pragma once

#include <array>
#include <span>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "vdg/viewdep/view_sphere.h"

namespace vdg {

// "weights": {"space": ...}: how keys are located (docs/model-format.md).
enum class WeightSpace { Directions, Positions };
// "directions" or "positions".
const char* weightSpaceName(WeightSpace space);

struct KeySpaceSettings {
  WeightSpace space = WeightSpace::Directions;
  // Positions only: the falloff distance (model units) over which an eye outside the eyes' hull
  // turns from the hull's weights to the direction sphere's; 0 means kAutoFalloff times the
  // diagonal of the eyes' bounding box.
  double falloff = 0.0;
};

class KeySpace {
 public:
  static constexpr double kAutoFalloff = 0.5;
  static constexpr double kSameEyeFraction = 1e-9;
  // A tetrahedron whose volume is below this fraction of the bounding box's is degenerate; when
  // every one is, the eyes are coplanar.
  static constexpr double kFlatFraction = 1e-12;
  static constexpr int kMaxWalkSteps = 64;

  // eyes: one per key, model space; center: the model centre the direction sphere is measured
  // from; sphere: the fallback sphere's uncovered mode and base falloff (its scheme must be
  // linear); falloff as in KeySpaceSettings. labels: how messages name the keys (one per key).
  static KeySpace build(std::span<const Eigen::Vector3d> eyes, const Eigen::Vector3d& center,
                        const ViewSphereSettings& sphere, double falloff, std::span<const std::string> labels);

  // Weights of the eye position `eye` (model space) into `out` (keyCount() + 1 floats: the keys,
  // then the base; they sum to 1). sharpness: finite and > 0. hint: -1 or a tetrahedron index from
  // an earlier call (set to the tetrahedron found; left as it is outside the hull). Returns false
  // having written nothing on a violation: a non-finite eye, the centre when it lies outside the
  // hull, a bad sharpness, a bad hint, out.size() != keyCount() + 1. Never throws or allocates.
  [[nodiscard]] bool weights(const Eigen::Vector3d& eye, double sharpness, std::span<float> out,
                             int* hint = nullptr) const;

  std::size_t keyCount() const { return eyes_.size(); }
  std::size_t tetrahedronCount() const { return tets_.size(); }
  std::size_t hullFaceCount() const { return hull_.size(); }
  std::size_t directionCount() const { return groups_.size(); }
  double falloff() const { return falloff_; }
  const Eigen::Vector3d& eye(std::size_t key) const { return eyes_[key]; }
  // The fallback direction sphere: one point per direction group (not per key).
  const ViewSphere& sphere() const { return sphere_; }

 private:
  struct Group {
    // The group's keys, nearest to the centre first, and their distances from it.
    std::vector<int> keys;
    std::vector<double> distances;
  };
  bool locate(const Eigen::Vector3d& x, int start, int& tet, Eigen::Vector4d& bary) const;
  Eigen::Vector4d barycentric(int tet, const Eigen::Vector3d& x) const;
  // The nearest point of the hull to x: face index, its barycentric coordinates, squared distance.
  int nearestHullFace(const Eigen::Vector3d& x, Eigen::Vector3d& bary, double& distance) const;
  // prune: skip the faces the eye is behind or whose plane is farther than the best so far.
  int nearestHullFace(const Eigen::Vector3d& x, Eigen::Vector3d& bary, double& distance, bool prune) const;

  std::vector<Eigen::Vector3d> eyes_;
  std::vector<std::array<int, 4>> tets_;        // key indices
  std::vector<std::array<int, 4>> neighbours_;  // across the face opposite corner i; -1: hull face
  std::vector<Eigen::Matrix3d> inverse_;        // per tet: inverse of [b - a, c - a, d - a]
  std::vector<std::array<int, 3>> hull_;        // hull faces (key indices)
  std::vector<Eigen::Vector4d> hull_planes_;    // per hull face: outward unit normal n, offset -n.a
  std::vector<Group> groups_;
  ViewSphere sphere_;
  Eigen::Vector3d center_ = Eigen::Vector3d::Zero();
  double falloff_ = 1.0;
};

namespace detail {
// The Delaunay tetrahedralisation of `points` (CGAL; key_space_delaunay.cpp, the one translation
// unit of viewdep that includes CGAL): finite tetrahedra as point indices (positively oriented),
// their neighbours across the face opposite each corner (-1 where that face is on the hull).
struct Tetrahedralisation {
  std::vector<std::array<int, 4>> tets;
  std::vector<std::array<int, 4>> neighbours;
};
Tetrahedralisation delaunayTetrahedra(std::span<const Eigen::Vector3d> points);
}  // namespace detail

}  // namespace vdg
