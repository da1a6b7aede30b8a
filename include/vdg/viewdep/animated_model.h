// Animated view-dependent models (Rademacher 99, section 4): an animated base, key deformations
// given at sparse frames from a few key views, offsets interpolated over time per view, then the
// static method (section 3.2) blending per frame.
//
// Build (section 4.2). Keys are grouped by view (views within ViewSphere::kSameViewRad are one
// point of the viewing sphere; RawViewDependentModel::validate()). For the view with key frames
// f_1 < ... < f_m the offsets
//   world:   o_j = key_j - base(f_j)                                     (the paper's)
//   skinned: o_j = L_v(f_j)^-1 (key_j - base(f_j)) per vertex v          (beyond the paper)
// where L_v(f) is the linear part of vertex v's skinning matrix at frame f (base_skin).
//
// Time interpolation of one view's offsets, o(f) = sum_j c_j(f) o_j:
//  - not looping: the natural cubic spline through (f_j, o_j) (second derivative 0 at f_1 and
//    f_m); one key frame: the constant o_1; two: the straight line (the natural spline of two
//    points). Outside [f_1, f_m] the offset HOLDS its end value (o_1 before f_1, o_m after f_m):
//    the key drawings say nothing about the animation beyond them, and a held offset never
//    extrapolates into a wild curve.
//  - looping ("loop": true): the periodic cubic spline through (f_j, o_j) and (f_1 + N, o_1) over
//    the cycle of N = frameCount() frames, so value, slope and curvature all match where the cycle
//    closes (a walk cycle has no seam); any frame is wrapped into the cycle. One key frame: the
//    constant o_1.
// The spline is linear in its data, so each view keeps the exact cardinal coefficients: c_j(f)
// are the weights timeCoefficients() returns, computed from an m x m table of second-derivative
// coefficients solved once at build (m <= kMaxKeyFramesPerView).
//
// Evaluation at frame f and view V (section 4.1, then 3.2.3): weights w_i of the sphere's points
// (the key views) as for a static model, then per vertex
//   p = base(f) + sum_i w_i * T_v(f) * o_i(f),  T_v = identity (world) or L_v(f) (skinned).
// At a key's frame and view (its weight 1) this is exactly the key mesh (to float rounding).
#pragma once

#include <optional>
#include <span>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "vdg/geom/tri_mesh.h"
#include "vdg/viewdep/model.h"
#include "vdg/viewdep/view_sphere.h"

namespace vdg {

class AnimatedViewDependentModel {
 public:
  // Validates `raw` (RawViewDependentModel::validate(), which must find an animated model with at
  // least one key) and builds the viewing sphere over the distinct key views, the offsets and the
  // time-coefficient tables. Throws vdg::Error naming the model (and key) on invalid input, for a
  // static raw model ("...: the base is not animated; build it as a ViewDependentModel") and for a
  // model without keys.
  static AnimatedViewDependentModel build(const RawViewDependentModel& raw);

  const TriMesh& base() const { return base_; }  // topology and frame 0's positions
  // The base's surface at frame 0 (vdg/geom/surface.h), welded once: the normals of evaluate()
  // and a renderer's shading use it at every frame.
  const SurfaceTopology& surface() const { return surface_; }
  std::size_t vertexCount() const { return base_.vertexCount(); }
  int frameCount() const { return static_cast<int>(base_frames_.size()); }
  bool loop() const { return loop_; }
  OffsetSpace offsetSpace() const { return offsets_space_; }
  bool skinned() const { return !base_skin_.empty(); }
  const Eigen::Vector3d& center() const { return center_; }
  double sharpness() const { return sharpness_; }
  // The viewing sphere; its key points are the views, in viewDirection() order.
  const ViewSphere& sphere() const { return sphere_; }

  // What the model can draw at any frame, for framing and clip planes (computed once in build(),
  // in model units). At frame f a blend is, per vertex, a convex combination of base(f) and the
  // poses base(f) + T_v(f) o_i(f) of every view i (the weights are >= 0 and sum to 1), so every
  // output of evaluate() lies in
  //   extent():       the axis-aligned box of base(f) and of every view's pose at f, over every
  //                   frame f in [0, frameCount()) (at a key's frame its pose is the key mesh);
  //   extentRadius(): the largest distance from center() to a vertex of those meshes (at least 1e-6).
  // Build cost: frameCount() x viewCount() poses of #V vertices, as many as rendering every frame
  // from every key view once. evaluatePosed() with a caller's own base may leave the extent.
  const Bounds& extent() const { return extent_; }
  double extentRadius() const { return extent_radius_; }

  // Accessors for tools and export (not per-frame). An index out of range throws vdg::Error
  // "view I out of range (the model has N views)" (likewise for key frames and frames).
  std::size_t viewCount() const { return views_.size(); }
  const Eigen::Vector3d& viewDirection(std::size_t view) const;  // unit
  std::span<const int> keyFrames(std::size_t view) const;        // f_1 < ... < f_m
  // The name and raw index (into RawViewDependentModel::keys) of key frame j of `view`.
  const std::string& keyName(std::size_t view, std::size_t j) const;
  std::size_t keyIndex(std::size_t view, std::size_t j) const;
  // Offsets o_j of key frame j of `view`: #V x 3 floats, in offsetSpace().
  std::span<const float> offsets(std::size_t view, std::size_t j) const;
  // The spline's second-derivative table of `view` (m x m, row-major, m = keyFrames(view).size()):
  // M_k = sum_j table[k * m + j] o_j, from which timeCoefficients() computes (for exports).
  std::span<const double> secondDerivatives(std::size_t view) const;
  // The base at frame f: #V x 3 positions; its skin linear parts (#V x 9, column-major) or an
  // empty span for an unskinned base.
  std::span<const float> baseFrame(int frame) const;
  std::span<const float> baseSkin(int frame) const;

  // Per-frame contract (the rule of every vdg evaluation function, after ozz-animation's jobs):
  // the functions below check their sizes, indices and values on entry; on a violation they
  // return false and have written nothing (no output span, no `*hint`); they never throw and
  // never allocate. Spans must have exactly the size stated.

  // Cardinal time coefficients of `view` at `frame`: out[j] is the weight of key frame j, and the
  // view's offset at that frame is sum_j out[j] * offsets(view, j) (exactly what evaluate uses).
  // Any finite frame: held outside [f_1, f_m] or wrapped into the cycle when looping; fractional
  // frames lie on the same spline. Violations: view >= viewCount(), a non-finite frame,
  // out.size() != keyFrames(view).size().
  [[nodiscard]] bool timeCoefficients(std::size_t view, double frame, std::span<double> out) const;

  // Weights of a view direction, as ViewDependentModel::weights (key slots index the views).
  [[nodiscard]] bool weights(const Eigen::Vector3d& view, double sharpness, ViewWeights& out,
                             int* hint = nullptr) const;

  // The model at integer `frame` in [0, frameCount()) seen from direction `view`: positions into
  // out_positions (#V x 3) and, when out_normals is non-empty, normals recomputed from them
  // (#V x 3). sharpness <= 0 means the model's own. Violations: a frame outside [0,
  // frameCount()), those of weights(), wrong span sizes.
  [[nodiscard]] bool evaluate(int frame, const Eigen::Vector3d& view, double sharpness, std::span<float> out_positions,
                              std::span<float> out_normals = {}, int* hint = nullptr) const;

  // Engine form: the caller supplies the posed base at (possibly fractional) `frame`:
  // base_positions #V x 3, and base_skin #V x 9 (column-major linear parts) for kSkinned offsets
  // (empty, or ignored when #V x 9, for kWorld). Violations: a non-finite frame, base_positions
  // not #V x 3, base_skin not #V x 9 for kSkinned (not empty and not #V x 9 for kWorld), those of
  // weights(), wrong output sizes. The base's values are trusted (non-finite values give
  // non-finite output, not a refusal).
  [[nodiscard]] bool evaluatePosed(double frame, std::span<const float> base_positions,
                                   std::span<const float> base_skin, const Eigen::Vector3d& view, double sharpness,
                                   std::span<float> out_positions, std::span<float> out_normals = {},
                                   int* hint = nullptr) const;

 private:
  struct View {
    Eigen::Vector3d direction = Eigen::Vector3d::UnitZ();
    std::vector<int> frames;               // f_1 < ... < f_m
    std::vector<std::size_t> key_indices;  // raw key index of each key frame
    std::vector<std::string> names;
    std::vector<float> offsets;  // m x (#V x 3)
    // Second derivatives of the spline as linear functions of the data: M_k = sum_j
    // second[k * m + j] * o_j (m x m, row-major; zero rows at the ends of a natural spline).
    std::vector<double> second;
  };
  // The blend after every check: weights `w` already computed.
  void blendPosed(double frame, std::span<const float> base_positions, std::span<const float> base_skin,
                  const ViewWeights& w, std::span<float> out_positions) const;
  void coefficients(const View& view, double frame, double* out) const;

  TriMesh base_;
  SurfaceTopology surface_;
  std::vector<std::vector<float>> base_frames_;
  std::vector<std::vector<float>> base_skin_;
  std::vector<View> views_;
  ViewSphere sphere_;
  Eigen::Vector3d center_ = Eigen::Vector3d::Zero();
  double sharpness_ = 1.0;
  bool loop_ = false;
  OffsetSpace offsets_space_ = OffsetSpace::kWorld;
  Bounds extent_;
  double extent_radius_ = 1e-6;
};

}  // namespace vdg
