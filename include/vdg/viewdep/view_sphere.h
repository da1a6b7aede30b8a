// ViewSphere — key viewpoints on the unit viewing sphere, triangulated by their convex hull, and
// the blending weights of any view direction (Rademacher 99, sections 3.2.1-3.2.2 and 3.3).
//
// Built once from the key directions (an immutable run-time object); weights() is then a pure,
// allocation-free, non-throwing query that a renderer calls every frame (its inputs are checked
// and a violation returns false, see weights()).
//
// Uncovered regions (section 3.3), for key sets whose hull does not enclose the sphere's centre:
//  - Uncovered::Base: dummy "base" points are added on the sphere wherever no key lies within
//    `base_falloff_deg`, so the hull of keys + dummies always encloses the centre; a view then
//    always falls in one hull triangle, and the dummies' weights go to the base model. The
//    dummies come from a fixed, evenly spread set of kDummyCandidates directions; any key set gets
//    the same dummies wherever it is rotated to, up to that set's spacing.
//  - Uncovered::Cosine / Cosine2: no dummies. Let R be the part of the sphere covered by the
//    keys' hull triangles (with 2 keys the arc between them, with 1 key the key itself). A view v
//    inside R gets the plain barycentric weights. Outside R, let p be the point of R nearest to v
//    (geodesic distance) and c = max(0, v.p): the keys get f * b_i(p), the base 1 - f, with
//    f = c (Cosine) or c^2 (Cosine2), where b_i(p) are the barycentric weights at p. For a single
//    key this is exactly the paper's max(0, Vkey.Veye) blend (with the base weight taken as
//    1 - w, so that the weights sum to 1 even behind the key); weights are continuous because p
//    moves continuously wherever c > 0 and f reaches 0 where p may jump.
// Sharpness alpha (section 3.2.2): the (up to three) triangle weights become w^a / sum w^a. In
// the cosine modes the sharpening applies among the keys, before the falloff f. It is computed
// relative to the largest weight, (w_i / w_max)^a / sum_j (w_j / w_max)^a, so any alpha > 0 is
// exact: alpha = 5000 gives (to float rounding) weight 1 to the largest key (ties share it evenly),
// never the unsharpened weights. Accepted values: finite alpha > 0. weights() is a per-frame query
// and never throws: it refuses (returns false) a NaN, infinite, zero or negative alpha. Builders
// and loaders (RawViewDependentModel::validate) reject such a model sharpness with vdg::Error.
#pragma once

#include <array>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace vdg {

enum class Uncovered { Base, Cosine, Cosine2 };
// "base", "cosine" or "cosine2": the names the manifest and the command line use.
const char* uncoveredName(Uncovered uncovered);

struct ViewSphereSettings {
  Uncovered uncovered = Uncovered::Base;
  // Base mode: a dummy base point is placed only where every key is farther than this angle.
  double base_falloff_deg = 60.0;
};

// Weights of one view: up to three real keys plus the base model; key[i] < 0 marks an unused slot.
// weight[0] + weight[1] + weight[2] + base == 1 (to float rounding).
struct ViewWeights {
  std::array<int, 3> key{-1, -1, -1};
  std::array<float, 3> weight{0.0f, 0.0f, 0.0f};
  float base = 0.0f;
  // Hull triangle that the view falls in (index into ViewSphere::triangles()), or -1 when the view
  // is in an uncovered region (cosine modes only).
  int triangle = -1;
};

class ViewSphere {
 public:
  static constexpr int kDummyCandidates = 64;
  // Two key directions closer than this angle are the same viewpoint.
  static constexpr double kSameViewRad = 1e-6;

  // key_directions: one direction per key, towards the eye, any finite non-zero length (1e-300 and
  // 1e300 are fine: normalised robustly, vdg/geom/normalize.h). Throws vdg::Error when there are
  // no keys, a direction is zero or not finite, or two directions coincide (within kSameViewRad;
  // found in O(n log n) by forEachCloseViewPair). Messages name keys by `key_labels[i]` when
  // given (one per key, e.g. "key 'front' (keys[0])"), by index ("key 3") otherwise.
  static ViewSphere build(std::span<const Eigen::Vector3d> key_directions, const ViewSphereSettings& settings = {},
                          std::span<const std::string> key_labels = {});

  // Weights of the view direction `view` (towards the eye; any finite non-zero length, normalised
  // robustly, so 1e-200 and 1e200 give the unit view's weights) into `out`. sharpness: see
  // "Sharpness alpha" above. `hint` (optional, in/out) is -1 (no hint) or a triangle index from an
  // earlier call on this sphere; it speeds up coherent queries and is set to the triangle found
  // (left as it is when the view falls in an uncovered region).
  // Per-frame contract (the rule of every vdg evaluation function, after ozz-animation's jobs):
  // inputs are checked on entry; on a violation weights() returns false and has written nothing
  // (neither `out` nor `*hint`); it never throws and never allocates. Violations: a zero or
  // non-finite view, a sharpness that is not finite or not > 0, a hint other than -1 or an index
  // into triangles().
  [[nodiscard]] bool weights(const Eigen::Vector3d& view, double sharpness, ViewWeights& out,
                             int* hint = nullptr) const;

  std::size_t keyCount() const { return key_count_; }
  // Unit directions of all points: the keys first (in input order), then the dummy base points.
  std::span<const Eigen::Vector3d> points() const { return points_; }
  bool isDummy(int point) const { return point >= static_cast<int>(key_count_); }
  // Hull triangles (indices into points()), counter-clockwise seen from outside the sphere.
  std::span<const std::array<int, 3>> triangles() const { return triangles_; }
  // Cosine modes: great-circle arcs bounding the covered region (indices into points()).
  std::span<const std::array<int, 2>> boundaryArcs() const { return arcs_; }
  // Fraction of the sphere's area covered by triangles whose three corners are all real keys.
  double coveredFraction() const { return covered_fraction_; }
  const ViewSphereSettings& settings() const { return settings_; }

 private:
  struct Cone {
    Eigen::Matrix3d inverse;  // inverse of [a b c]: lambda = inverse * v
  };
  // weights() after its checks: view non-zero and finite, sharpness > 0, hint valid.
  ViewWeights locate(const Eigen::Vector3d& view, double sharpness, int* hint) const;
  ViewWeights locateInTriangle(int t, const Eigen::Vector3d& lambda) const;
  ViewWeights falloff(const Eigen::Vector3d& v, double& nearest_cos) const;
  void finishWeights(ViewWeights& w, double sharpness) const;

  ViewSphereSettings settings_;
  std::size_t key_count_ = 0;
  std::vector<Eigen::Vector3d> points_;
  std::vector<std::array<int, 3>> triangles_;
  std::vector<Cone> cones_;
  std::vector<std::array<int, 2>> arcs_;
  std::vector<int> isolated_;  // cosine modes: keys that belong to no triangle and no arc
  double covered_fraction_ = 0.0;
};

// Pairs of `unit_directions` less than `max_angle_rad` apart (angle atan2(|a x b|, a.b)), found
// through a grid on the sphere: O(n log n) plus the number of close pairs, not O(n^2). Calls
// visit(i, j, angle_rad) with j < i, in increasing order of i and then of j; the search stops
// early when visit returns false. Returns the number of pairs visited. Inputs are expected unit
// (non-finite components are tolerated: such a direction is near nothing).
std::size_t forEachCloseViewPair(std::span<const Eigen::Vector3d> unit_directions, double max_angle_rad,
                                 const std::function<bool(std::size_t i, std::size_t j, double angle_rad)>& visit);

}  // namespace vdg
