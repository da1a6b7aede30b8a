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
// alpha == 1 costs nothing, integer alpha up to kMultiplySharpnessMax is a few multiplications,
// any other alpha one std::pow per key (the results agree to float rounding).
//
// Weight schemes (docs/weights.md). WeightScheme::Linear is the paper's barycentric
// blend (C0: its weights kink across every hull edge). WeightScheme::Smooth is C1 on the whole
// sphere, exact at every key, a partition of unity, non-negative and local (a view's weights come
// from the three corners of its hull triangle only), built as a side-vertex blend on each hull
// triangle (after the transfinite triangle schemes of Barnhill, Birkhoff & Gordon 1973 and Nielsen
// 1979, with Gregory-style squared blending functions):
//  - along each edge (i, j), E_ij gives key j the weight F(t) and key i 1 - F(t), where
//    t = |v - i| / (|v - i| + |v - j|) (chord lengths: 0 at i, 1 at j, one smooth function of the
//    view shared by both triangles of the edge) and F(t) = 3t^2 - 2t^3 (F' = 0 at both ends);
//  - inside the triangle with barycentric coordinates b (the linear scheme's weights), the three
//    edges blend with beta_k = (b_i b_j)^2 / sum over the edges of the same products, for the edge
//    (i, j) opposite corner k: beta_k = 1 on that edge, while the other two betas vanish there
//    together with their gradients; so on every edge the weights and their gradients are E_ij's
//    from both sides (C1 across edges), and at a key every weight's gradient is 0 (C1 at keys).
// Sharpness applies to the smooth weights as to the linear ones (C1 is kept for alpha >= 1; for
// 1/2 < alpha < 1 too, since a weight vanishes quadratically at the edges where it does), and the
// uncovered modes are unchanged: base mode's dummies are triangulation points like the keys; the
// cosine modes' falloff takes at the nearest point of a boundary arc the smooth edge weights (so
// the weights stay continuous at the covered region's border; C1 holds inside the covered region).
//
// WeightScheme::Rbf (docs/weights.md, "The rbf scheme") interpolates the keys with spherical radial
// basis functions over ALL keys, pose-space-deformation style (Lewis, Cordner & Fong 2000; RBF
// theory after Buhmann 2003): the centres are the keys (and, in base mode, the dummy base points,
// whose weights go to the base model), and for each output o (every key, then the base) the
// weight is the interpolant
//   r_o(v) = sum_j c_oj phi(d(v, x_j)) + b_o,  with sum_j c_oj = 0,
// of the data "1 at o's own centres, 0 at every other", solved once by build() from the saddle
// system [Phi 1; 1^T 0] [c; b] = [data; 0] (Phi_ij = phi(d(x_i, x_j))). The constant term b_o
// makes the interpolation reproduce constants, so the r_o sum to exactly 1 at every view (the data
// sum to 1 at every centre): a partition of unity by construction, not by dividing by the sum
// (Shepard-style normalisation would lose exactness at the keys). The kernel is radial in the
// geodesic distance d between directions, written through the chord 2 sin(d/2) (squared chord
// |v - x_j|^2): phi = g(chord(d) / chord(width)), g(s) = exp(-s^2) ("gaussian", the default),
// 1 / sqrt(1 + s^2) ("inverse-multiquadric") or Wendland's C2 (1 - s)^4 (4 s + 1) for s < 1
// ("wendland", compactly supported: keys beyond `width` do not move a view). Through the chord each
// kernel is the restriction to the sphere of a positive-definite function of R^3, so Phi is
// positive definite for distinct keys and phi is smooth everywhere, also at a key's antipode (a
// Gaussian of the geodesic angle itself is neither: Gneiting 2013).
// The interpolant overshoots: between keys some r_o go negative (and others above their 1). vdg
// keeps the weights non-negative with a C1 positive part P(r) = 0 (r <= 0), r^2 (2e - r) / e^2
// (0 < r < e), r (r >= e), e = kRbfPositiveSoftness, and renormalises: w_o = P(r_o) / sum P(r).
// Weights of at least e are the interpolant's (up to the common factor), so at a key (r = one-hot,
// to the solve's rounding) the weights stay one-hot, they sum to 1, are >= 0 and stay C1 (P is C1,
// and sum P >= P(max r) > 0 since max r >= 1 / (keys + 1)). Sharpness applies to the w_o as in the
// other schemes ((w / w_max)^alpha / sum), C1 kept for alpha > 1/2 (P vanishes quadratically).
// Uncovered modes keep their meaning: in base mode the dummy base points are centres whose weight
// goes to the base, so the whole sphere is one C1 blend; in the cosine modes a covered view gets
// the rbf weights at the view, an uncovered one the rbf weights at the nearest point p of the
// covered region times the falloff f (the base 1 - f), as the smooth scheme does at the border.
// build() refuses (vdg::Error, one line naming the closest two keys) a system whose reciprocal
// condition number is below 1 / kRbfMaxCondition (keys too close for the width), more than
// kRbfMaxKeys keys, and a width outside (0, 180] degrees. Cost per view: one kernel per centre and
// keys + 1 multiply-adds per centre whose kernel is not 0 (every centre for the Gaussian and the
// inverse multiquadric: O(keys^2); those within `width` for Wendland's), on the stack (no
// allocation). The rbf weights are over all keys, so they come from denseWeights(); weights() and
// weightsByScan(), whose ViewWeights hold three keys, refuse an rbf sphere (return false).
//
// Locating a view (spatial index). weightsByScan() tests every hull triangle: O(triangles) per
// query, kept as the oracle for tests and debugging. weights() gets the same result faster:
//  - with a hint, it tests the hint's triangle and, when the view lies beyond one of its edges,
//    walks to the neighbour across the edge it is farthest beyond (at most kMaxWalkSteps steps);
//    a coherent camera path therefore costs one or two triangle tests per frame;
//  - otherwise (no hint, or the walk left the covered region or ran out of steps) it looks the view
//    up in a cube-map grid built once by build(): 6 x N x N cells (N = ceil(sqrt(8 (T + F) / 6))
//    for T triangles and F boundary arcs and isolated keys, clamped to [kMinGridSize,
//    kMaxGridSize]: about kCellsPerItem cells per item), each listing the triangles whose
//    circumscribed cap overlaps the cell's bounding cap (those covering most of the cell first),
//    and in the cosine modes the boundary arcs and isolated keys that can be nearest to a view in
//    the cell. A query tests only its cell's lists: O(1) for evenly spread keys.
//    A view that no listed triangle contains lies in no triangle (the lists are conservative,
//    with a margin for rounding); only a view within the 1e-9 inside tolerance of a needle-thin
//    triangle's tip may miss it. Base mode then falls back to the full scan; the cosine modes
//    treat it as uncovered, which at that distance from the covered region gives the same
//    weights to float rounding.
// The grid costs 8 bytes per cell (offsets) plus 4 bytes per listed triangle, arc or key (6 to 10
// per cell): about 100 KB for 200 keys over the sphere, 0.2 MB plus 4 bytes per listed item at
// most (N = 64) for very large key sets. build() spends O(cells x (triangles + arcs)) on it: about
// 30 ms for 200 keys, 0.5 s for 3,000. The result equals weightsByScan()'s except where
// the view lies on an edge shared by two triangles (both contain it, within 1e-9; either
// gives the same weights up to that tolerance), and then only which triangle is reported differs.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace vdg {

enum class Uncovered { Base, Cosine, Cosine2 };
// "base", "cosine" or "cosine2": the names the manifest and the command line use.
const char* uncoveredName(Uncovered uncovered);

// How a view's weights follow from the hull triangle it falls in (see "Weight schemes" above).
enum class WeightScheme { Linear, Smooth, Rbf };
// "linear", "smooth" or "rbf": the names the manifest ("weights": {"scheme": ...}) and the exports use.
const char* weightSchemeName(WeightScheme scheme);
// The rbf scheme's kernel (see "Weight schemes" above).
enum class RbfKernel { Gaussian, InverseMultiquadric, Wendland };
// "gaussian", "inverse-multiquadric" or "wendland": the manifest's "weights": {"kernel": ...}.
const char* rbfKernelName(RbfKernel kernel);

struct ViewSphereSettings {
  Uncovered uncovered = Uncovered::Base;
  // Base mode: a dummy base point is placed only where every key is farther than this angle.
  double base_falloff_deg = 60.0;
  WeightScheme scheme = WeightScheme::Linear;
  // Rbf scheme only: the kernel and its width (geodesic angle, degrees, in (0, 180]).
  RbfKernel rbf_kernel = RbfKernel::Gaussian;
  double rbf_width_deg = 60.0;
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

// Dense weights (every key's, then the base's: ViewSphere::denseWeights) as a ViewWeights, for what
// shows or reports three keys (the renderer's inset, the studio's Preview, ModelEvaluator::weights):
// the three heaviest keys with their weights (ties to the lower key index), and as `base` the rest
// (the base's weight and the other keys'), so the four still sum to 1; no triangle. dense.size()
// must be at least 1.
ViewWeights heaviestKeys(std::span<const float> dense);

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
  // into triangles(), an rbf sphere (its weights are over every key: denseWeights()).
  [[nodiscard]] bool weights(const Eigen::Vector3d& view, double sharpness, ViewWeights& out,
                             int* hint = nullptr) const;
  // The same query by testing every hull triangle (and, in the cosine modes, every boundary arc
  // and isolated key): O(triangles) per call. For tests and debugging (the oracle of weights());
  // same contract as weights(): checked on entry, false with nothing written on a violation, no
  // throw, no allocation. The hint is tried first, then the triangles in index order.
  [[nodiscard]] bool weightsByScan(const Eigen::Vector3d& view, double sharpness, ViewWeights& out,
                                   int* hint = nullptr) const;

  // Weights of every key and the base into `out` (keyCount() + 1 floats: the keys in order, then
  // the base; they sum to 1), for any scheme: the rbf scheme's only query, and for the linear and
  // smooth ones weights()' three slots spread out. Same contract as weights() (checked on entry,
  // false with nothing written on a violation, no throw, no allocation); a further violation is
  // out.size() != keyCount() + 1.
  [[nodiscard]] bool denseWeights(const Eigen::Vector3d& view, double sharpness, std::span<float> out,
                                  int* hint = nullptr) const;

  // Rbf scheme limits (see "Weight schemes" above).
  static constexpr std::size_t kRbfMaxKeys = 256;
  static constexpr double kRbfMaxCondition = 1e10;
  static constexpr double kRbfPositiveSoftness = 0.05;

  // Spatial index parameters (see "Locating a view" above).
  static constexpr int kMaxWalkSteps = 8;
  static constexpr int kMinGridSize = 4;
  static constexpr double kCellsPerItem = 8.0;  // grid cells per triangle, arc or isolated key
  static constexpr int kMaxGridSize = 64;
  // Most (cell, triangle or feature) pairs the build tests: beyond about 1,000 keys N shrinks below
  // the formula above so that build() stays O(keys) (a few milliseconds per thousand keys), and the
  // cells' lists grow instead.
  static constexpr double kMaxIndexPairs = 5e7;
  // Integer sharpness up to this value is computed by repeated multiplication instead of std::pow.
  static constexpr int kMultiplySharpnessMax = 8;
  // Cells per cube face edge of the grid (N above).
  int gridSize() const { return grid_size_; }

  std::size_t keyCount() const { return key_count_; }
  // Unit directions of all points: the keys first (in input order), then the dummy base points.
  std::span<const Eigen::Vector3d> points() const { return points_; }
  bool isDummy(int point) const { return point >= static_cast<int>(key_count_); }
  // Hull triangles (indices into points()), counter-clockwise seen from outside the sphere.
  std::span<const std::array<int, 3>> triangles() const { return triangles_; }
  // Cosine modes: great-circle arcs bounding the covered region (indices into points()).
  std::span<const std::array<int, 2>> boundaryArcs() const { return arcs_; }
  // Cosine modes: keys on no triangle and no arc (the falloff also pulls towards them).
  std::span<const int> isolatedKeys() const { return isolated_; }
  // Inverse of the matrix whose columns are triangle t's corners: the cone coordinates of a view v
  // are inverse * v (section 3.2.1). For exports that let a runtime repeat the query exactly.
  const Eigen::Matrix3d& triangleInverse(std::size_t t) const { return cones_.at(t).inverse; }
  // Rbf scheme: the solved interpolation (see "Weight schemes" above), for exports that let a runtime
  // repeat denseWeights() exactly. (points().size() + 1) rows of keyCount() + 1 values (the outputs:
  // every key, then the base): row 0 holds the constants b_o, row j + 1 centre j's coefficients c_oj.
  // Empty for the other schemes.
  std::span<const double> rbfCoefficients() const { return rbf_rows_; }
  // Rbf scheme: the width as a squared chord, (2 sin(width / 2))^2; the kernel's argument is
  // q = |x - x_j|^2 / rbfChord2().
  double rbfChord2() const { return rbf_chord2_; }
  // Fraction of the sphere's area covered by triangles whose three corners are all real keys.
  double coveredFraction() const { return covered_fraction_; }
  const ViewSphereSettings& settings() const { return settings_; }

 private:
  struct Cone {
    Eigen::Matrix3d inverse;  // inverse of [a b c]: lambda = inverse * v
  };
  struct ArcFrame {  // of an arc (a, b): unit normal n of its plane, b x n and n x a
    Eigen::Vector3d normal, to_a, to_b;
  };
  // The entry checks of weights() and weightsByScan(): false on a violation; otherwise the unit
  // view and the hint to start from (-1 for none).
  bool checkQuery(const Eigen::Vector3d& view, double sharpness, const int* hint, Eigen::Vector3d& unit,
                  int& start) const;
  // After the checks (unit view, sharpness > 0, hint -1 or valid); *hint is updated as documented.
  // `nearest` (optional): for a view in an uncovered region (cosine modes), set to the nearest
  // point of the covered region (unchanged otherwise).
  ViewWeights locate(const Eigen::Vector3d& v, double sharpness, int* hint, Eigen::Vector3d* nearest = nullptr) const;
  ViewWeights locateByScan(const Eigen::Vector3d& v, double sharpness, int* hint) const;
  // Index of the grid cell that the unit direction v falls in.
  int cellOf(const Eigen::Vector3d& v) const;
  // Triangle whose cone contains v (within kInsideTol) among the scan's candidates, or -1.
  int scanTriangles(const Eigen::Vector3d& v, Eigen::Vector3d& lambda) const;
  ViewWeights triangleWeights(int t, const Eigen::Vector3d& v, const Eigen::Vector3d& lambda, double sharpness) const;
  // Uncovered view (cosine modes): falloff towards the nearest of `features` (see features_).
  ViewWeights uncoveredWeights(const Eigen::Vector3d& v, double sharpness, std::span<const int> features,
                               Eigen::Vector3d* nearest = nullptr) const;
  ViewWeights falloff(const Eigen::Vector3d& v, std::span<const int> features, double& nearest_cos,
                      Eigen::Vector3d* nearest = nullptr) const;
  // Rbf scheme: solves the interpolation (build), and the weights at the unit direction x times
  // `scale` into out (keys, then the base, which also gets 1 - scale).
  void buildRbf(std::span<const std::string> key_labels);
  void rbfWeightsAt(const Eigen::Vector3d& x, double sharpness, double scale, std::span<float> out) const;
  void finishWeights(ViewWeights& w, double sharpness) const;
  // Geodesic distance (radians) from the unit direction x to a feature (see features_).
  double featureDistance(const Eigen::Vector3d& x, int feature) const;
  void buildIndex();

  ViewSphereSettings settings_;
  std::size_t key_count_ = 0;
  std::vector<Eigen::Vector3d> points_;
  std::vector<std::array<int, 3>> triangles_;
  std::vector<Cone> cones_;
  std::vector<std::array<int, 2>> arcs_;
  std::vector<int> isolated_;  // cosine modes: keys that belong to no triangle and no arc
  double covered_fraction_ = 0.0;
  // Rbf scheme: the constants b_o over the outputs (keys, then the base), then per centre j (the
  // points) its coefficients c_oj over the outputs; and the width as a squared chord.
  std::vector<double> rbf_rows_;
  double rbf_chord2_ = 1.0;
  // Spatial index (built by buildIndex()). Features of the falloff: 0 .. isolated_.size() - 1 are
  // isolated_ keys, the following ones arcs_, in the order the scan considers them.
  std::vector<int> all_features_;               // 0, 1, ...: every feature (the scan's list)
  std::vector<ArcFrame> arc_frames_;            // per arc
  std::vector<std::array<int, 3>> neighbours_;  // per triangle, across the edge opposite corner k
  int grid_size_ = 0;
  std::vector<std::uint32_t> cell_triangle_start_;  // per cell, into cell_triangles_ (+1 end)
  std::vector<int> cell_triangles_;
  std::vector<std::uint32_t> cell_feature_start_;  // per cell, into cell_features_ (+1 end)
  std::vector<int> cell_features_;
};

// Pairs of `unit_directions` less than `max_angle_rad` apart (angle atan2(|a x b|, a.b)), found
// through a grid on the sphere: O(n log n) plus the number of close pairs, not O(n^2). Calls
// visit(i, j, angle_rad) with j < i, in increasing order of i and then of j; the search stops
// early when visit returns false. Returns the number of pairs visited. Inputs are expected unit
// (non-finite components are tolerated: such a direction is near nothing).
std::size_t forEachCloseViewPair(std::span<const Eigen::Vector3d> unit_directions, double max_angle_rad,
                                 const std::function<bool(std::size_t i, std::size_t j, double angle_rad)>& visit);

// Key views closer than this (degrees) but not the same view (ViewSphere::kSameViewRad) make a
// near-degenerate hull triangle: across its short side the weights flip from one key to the other
// over a small arc of views, so the blend looks abrupt (Rademacher 99, 3.2: the weights are
// barycentric in the hull triangle). `vdg info` and `vdg studio` warn about such pairs.
inline constexpr double kNearlySameViewDeg = 5.0;

// Two key views nearly the same direction: indices into the directions (j < i) and their angle.
struct NearlySameViewPair {
  std::size_t i = 0, j = 0;
  double angle_deg = 0.0;
};
// The pairs of `unit_directions` (expected unit) more than kSameViewRad and less than
// kNearlySameViewDeg apart, in forEachCloseViewPair's order: the first `max_listed` are appended to
// `listed`; returns how many pairs there are, counting no further than `max_counted`.
std::size_t nearlySameViewPairs(std::span<const Eigen::Vector3d> unit_directions, std::size_t max_listed,
                                std::size_t max_counted, std::vector<NearlySameViewPair>& listed);

}  // namespace vdg
