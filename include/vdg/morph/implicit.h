// Implicit surfaces (Parent 4.11, "Implicit Surfaces"): blobby objects, soft objects and metaballs.
//
// A BlobModel is a set of point primitives, each with a field function f_i(r) of the distance r
// from its centre c_i; the surface is the iso-surface F(p) = sum_i f_i(|p - c_i|) = T of the summed
// field at the threshold T > 0 (inside where F > T). Primitives near each other blend into one
// smooth surface; far apart they stay separate. The reference text only names the section, so the
// field functions follow the papers that introduced them (as collected in Bloomenthal et al.,
// "Introduction to Implicit Surfaces", Morgan Kaufmann 1997, chapter 7):
//
//   kBlinn      Blinn, "A Generalization of Algebraic Surface Drawing", ACM TOG 1(3), 1982
//               ("blobby objects"): D(r) = b exp(-a r^2), with b = strength and a = B / R^2 for
//               the primitive's radius R and blobbiness B (> 0; larger B: a tighter blob that
//               blends less). An isolated blob's surface lies at r = R sqrt(ln(b / T) / B).
//               The support is infinite: for bounds and sampling a primitive is cut off at
//               r_cut = sqrt(ln(|b| / (1e-3 T)) / a), where |D| falls to T * 1e-3 (no cut-off
//               region when |b| <= 1e-3 T: the primitive is then left out of the sampled grid).
//   kWyvill     Wyvill, McPheeters and Wyvill, "Data Structure for Soft Objects", The Visual
//               Computer 2(4), 1986 ("soft objects"): with q = r^2 / R^2,
//               C(r) = s (1 - 22/9 q + 17/9 q^2 - 4/9 q^3) for r <= R, 0 beyond (C(0) = s,
//               C(R/2) = s/2, C(R) = 0 with zero slope).
//   kNishimura  Nishimura et al., "Object Modeling by Distribution Function and a Method of Image
//               Generation", Trans. IECE Japan J68-D(4), 1985 ("metaballs"), piecewise quadratic:
//               f(r) = b (1 - 3 r^2 / R^2)        for 0 <= r <= R/3,
//               f(r) = 3b/2 (1 - r / R)^2         for R/3 <= r <= R,  0 beyond
//               (C1: both pieces give 2b/3 with slope -2b/R at R/3).
// A negative strength subtracts (a dent or a hole); strength 0 contributes nothing.
//
// Raw data -> builder -> immutable runtime object -> evaluation:
//   RawBlobModel --BlobModel::build--> BlobModel --field/gradient/sample--> values
//   RawBlobAnimation (tracks per primitive) --BlobAnimation::build--> BlobAnimation
//       --evaluate(frame, model)--> BlobModel at that frame
//   polygonise(BlobModel) --> closed triangle mesh (OpenVDB volume to mesh; vdg/morph/polygonise.h,
//   in vdg::morph3d: this header and its library need no OpenVDB).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstddef>
#include <span>
#include <string>
#include <vector>

#include "vdg/anim/track.h"
#include "vdg/geom/tri_mesh.h"

namespace vdg::morph {

enum class FieldKind { kBlinn, kWyvill, kNishimura };
// "blinn", "wyvill", "nishimura" (the names the BLOBS.json file uses).
const char* fieldKindName(FieldKind kind);

// Field values below |T| * kBlinnCutoff are dropped from a Blinn primitive's support (see above).
inline constexpr double kBlinnCutoff = 1e-3;
// Bounds that keep every derived quantity finite (supports, grid boxes, Blinn's a = B / R^2):
// centre coordinates and |strength| at most kMaxBlobValue, radius and threshold in
// [kMinBlobValue, kMaxBlobValue], blobbiness in [1e-3, 1e3].
inline constexpr double kMinBlobValue = 1e-12;
inline constexpr double kMaxBlobValue = 1e12;
inline constexpr double kMinBlobbiness = 1e-3;
inline constexpr double kMaxBlobbiness = 1e3;
// Most primitives one model may hold (each voxel sums every primitive whose support covers it).
inline constexpr std::size_t kMaxBlobPrimitives = 4096;

struct BlobPrimitive {
  FieldKind kind = FieldKind::kWyvill;
  Eigen::Vector3d center = Eigen::Vector3d::Zero();
  double radius = 1.0;      // R > 0, world units (kBlinn: the length scale of a = B / R^2)
  double strength = 1.0;    // b or s: finite, any sign
  double blobbiness = 1.0;  // B > 0, kBlinn only
};

// f_i(r) of one primitive at distance r >= 0 from its centre (formulas above; no cut-off).
double primitiveField(const BlobPrimitive& primitive, double r);
// Radius beyond which the primitive contributes nothing (kWyvill, kNishimura: R) or less than
// |T| * kBlinnCutoff (kBlinn: r_cut above; 0 when |b| <= that). T is the model's threshold.
double supportRadius(const BlobPrimitive& primitive, double threshold);

struct RawBlobModel {
  std::vector<BlobPrimitive> primitives;
  double threshold = 0.5;  // T > 0, finite

  // Throws vdg::Error "WHERE: ..." naming the primitive ("primitives[2]: radius must be > 0, got
  // -1") for: no primitives or more than kMaxBlobPrimitives, a threshold <= 0, a radius <= 0, and
  // any value outside the bounds above (NaN and infinities included).
  void validate(const std::string& where = "blobs") const;
};

class BlobModel {
 public:
  static BlobModel build(const RawBlobModel& raw, const std::string& where = "blobs");

  double threshold() const { return threshold_; }
  const std::vector<BlobPrimitive>& primitives() const { return primitives_; }
  // False when primitive i is switched off at this frame (see BlobAnimation); it then adds nothing.
  bool active(std::size_t i) const { return active_[i] != 0; }

  // F(p): the sum of every primitive's field (exact, no cut-off).
  double field(const Eigen::Vector3d& p) const;
  // grad F(p), analytic (zero outside every support).
  Eigen::Vector3d gradient(const Eigen::Vector3d& p) const;
  // Per-frame form: values[i] = F(points[3i..3i+2]). Violations (false, nothing written):
  // points.size() != 3 * values.size(), a coordinate not finite.
  [[nodiscard]] bool sample(std::span<const double> points, std::span<double> values) const;

  // The box holding every point where the positive-strength primitives can reach T: the union of
  // their support spheres (supportRadius). Empty (isEmpty()) when no primitive adds to the field
  // or none is active.
  Eigen::AlignedBox3d bounds() const;

 private:
  friend class BlobAnimation;
  std::vector<BlobPrimitive> primitives_;
  std::vector<char> active_;  // 0: the primitive is switched off at this frame (see BlobAnimation)
  double threshold_ = 0.5;
};

// ---- Animation ------------------------------------------------------------------------------
// Each primitive's centre (a 3-vector track), radius and strength (scalar tracks) are key-framed
// with the anim module's tracks (vdg/anim/track.h), key times in frames; a quantity that does not
// move is a single-key track. The per-kind parameters (kind, blobbiness) and the threshold stay
// fixed. Keys must satisfy RawBlobModel's rules (radius > 0 at every key); between keys an
// interpolation may overshoot (Catmull-Rom), and a radius that evaluates to <= 0 switches the
// primitive off at that frame (it contributes nothing) instead of failing.
struct RawBlobTrack {
  FieldKind kind = FieldKind::kWyvill;
  anim::RawTrack center;    // kVector, 3 components
  anim::RawTrack radius;    // kScalar
  anim::RawTrack strength;  // kScalar
  double blobbiness = 1.0;
};

struct RawBlobAnimation {
  std::vector<RawBlobTrack> primitives;
  double threshold = 0.5;
  int first_frame = 0;  // the frames a sequence covers by default, first <= last
  int last_frame = 0;

  // Throws vdg::Error "WHERE: primitives[I].'radius': ..." for what RawBlobModel::validate and
  // anim::RawTrack::validate refuse, a track of the wrong type or size, a key radius <= 0, and
  // first_frame > last_frame.
  void validate(const std::string& where = "blobs") const;
};

class BlobAnimation {
 public:
  static BlobAnimation build(const RawBlobAnimation& raw, const std::string& where = "blobs");

  std::size_t primitiveCount() const { return kinds_.size(); }
  double threshold() const { return threshold_; }
  int firstFrame() const { return first_frame_; }
  int lastFrame() const { return last_frame_; }

  // The model at `frame` (any finite frame; tracks clamp or loop outside their keys). Allocates;
  // throws vdg::Error for a frame that is not finite.
  BlobModel modelAt(double frame) const;
  // Per-frame form: poses `model` (which must come from modelAt of this animation, so it has
  // primitiveCount() primitives) at `frame`, allocation-free. Violations (false, `model`
  // untouched): a primitive count that differs, a frame that is not finite.
  [[nodiscard]] bool evaluate(double frame, BlobModel& model) const;

 private:
  std::vector<FieldKind> kinds_;
  std::vector<double> blobbiness_;
  std::vector<anim::Track> centers_, radii_, strengths_;
  double threshold_ = 0.5;
  int first_frame_ = 0, last_frame_ = 0;
};

// ---- The grid of the polygoniser (vdg/morph/polygonise.h) ---------------------------------------

// Bytes the polygoniser needs per voxel (the sampled grid and OpenVDB's copy), for the estimate.
inline constexpr std::size_t kBytesPerVoxel = 8;
// Grid layers added around the bounds on every side, so that the surface never touches the grid's
// boundary (the outermost layers lie outside every positive support: field 0 < T).
inline constexpr int kGridPadding = 2;

// The largest side of `box` / 96 (the same default for every frame of a sequence when the box
// is the union of the frames' bounds); 0 for an empty box.
double defaultVoxelSize(const Eigen::AlignedBox3d& box);
// Grid points along each axis over `box` at spacing `voxel_size`: the box's extent in voxels, plus
// one sample at the far end, plus kGridPadding layers on both sides (in double: no overflow).
Eigen::Vector3d gridDimensions(const Eigen::AlignedBox3d& box, double voxel_size);
// Voxels of the padded grid over `box` at `voxel_size` (computed in double: no overflow).
double gridVoxelCount(const Eigen::AlignedBox3d& box, double voxel_size);
// Throws the "too many voxels" vdg::Error above (prefixed with `what`) when gridVoxelCount(box,
// voxel_size) > max_voxels; voxel_size must be > 0.
void checkVoxelBudget(const Eigen::AlignedBox3d& box, double voxel_size, std::size_t max_voxels,
                      const std::string& what);

// Number of connected components of a mesh (triangles sharing a vertex are connected).
std::size_t connectedComponents(const TriMesh& mesh);

}  // namespace vdg::morph
