// View-dependent models: the raw description (what a manifest file or the editor holds), its
// validation, and the immutable run-time ViewDependentModel with allocation-free evaluation.
//
// Rademacher 99: a view-dependent model is a base model, key deformations (same connectivity,
// moved vertices) and key viewpoints (section 3.1). Evaluation at a view (section 3.2):
// locate the view on the ViewSphere, take up to three keys' weights, and blend positions
// v = sum_i w_i * v^i (3.2.3). Keys are stored as deltas from the base, sparse when few vertices
// move, so v = base + sum_i w_i * (v^i - base) costs a copy of the base plus the moved vertices.
//
// Normals of the blended mesh are recomputed from the blended positions (area-weighted), not
// blended: a weighted sum of key normals is not the normal of the weighted sum of key shapes once
// a key shears or bends the surface, and the NPR shading and silhouettes need the true normals.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "vdg/geom/camera.h"
#include "vdg/geom/material.h"
#include "vdg/geom/surface.h"
#include "vdg/geom/tri_mesh.h"
#include "vdg/viewdep/key_space.h"
#include "vdg/viewdep/view_sphere.h"

namespace vdg {

// Most keys a model may have. Far more than any model sheet (a few to a few dozen drawings), yet
// small enough that building the viewing sphere (Qhull, O(n log n)) and a view's un-hinted
// triangle search (linear in the hull's ~2n triangles) stay fast, and that the keys' meshes are
// what limits memory. validate() rejects more; the manifest reader refuses more before reading.
inline constexpr std::size_t kMaxKeys = 100'000;
// Most keys of a model weighed in the 'positions' space: every query writes one weight per key (on
// the stack in evaluate()) and an eye outside the keys' hull tests every hull face.
inline constexpr std::size_t kMaxPositionKeys = 256;

// Animated bases (Rademacher 99, section 4): most frames a base animation may have, and most key
// frames one key view may have (its time spline keeps an m x m table of exact cardinal
// coefficients, see vdg/viewdep/animated_model.h). validate() rejects more.
inline constexpr std::size_t kMaxBaseFrames = 100'000;
inline constexpr std::size_t kMaxKeyFramesPerView = 256;

// Where an animated base comes from (the manifest's "base_animation"; docs/model-format.md).
// Exactly one source: an OBJ sequence (obj_sequence, a printf pattern with one %d or %0Nd, and the
// file numbers first..last; frame i is file first + i) or a glTF animation (gltf, animation index,
// fps, optional mesh or node name; frame i is time i / fps). `loop`: the animation is a cycle of
// frameCount() frames, frame N being frame 0 again (the time splines are then periodic).
struct BaseAnimationSpec {
  std::string obj_sequence;
  int first = 0, last = 0;
  std::string gltf;
  int animation = 0;
  double fps = 24;
  std::string mesh;
  bool loop = false;
};

// Space the key offsets of an animated model live in (section 4.2 and beyond):
//  - kWorld: o = key - base(frame), interpolated and added in model space (the paper's);
//  - kSkinned: o = L_v(frame)^-1 (key - base(frame)), with L_v the linear part of vertex v's
//    skinning matrix, interpolated in the rest pose and re-skinned at every frame, so an
//    exaggeration follows a swinging limb.
enum class OffsetSpace { kWorld, kSkinned };
// "world" or "skinned": the names the manifest uses.
const char* offsetSpaceName(OffsetSpace space);

struct RawKey {
  std::string name;       // unique within the model; defaults to the mesh file's stem
  std::string mesh_path;  // as written in the manifest (relative to the manifest's folder)
  TriMesh mesh;           // the key deformation: the base's triangles, moved positions
  // Direction from the model centre towards the eye, model space. When `camera` is set, this is
  // normalize(camera.eye - centre) and is filled in by resolveViews().
  Eigen::Vector3d view = Eigen::Vector3d::Zero();
  std::optional<Camera> camera;  // the aligned key camera, when the key was made from a drawing
  // A plain eye position (model space) instead of a camera (the manifest's "eye"); view then is
  // normalize(eye - centre), filled in by resolveViews(). At most one of camera and eye is set.
  std::optional<Eigen::Vector3d> eye;
  // The key's eye: camera->eye, else `eye`, else none (a key given by its direction alone).
  std::optional<Eigen::Vector3d> eyePosition() const { return camera ? std::optional(camera->eye) : eye; }
  // The reference drawing this key was made from (the manifest's "drawing", version 5), for
  // view-dependent textures (vdg/render/drawing_textures.h): drawing_path as the manifest writes it
  // (relative to the manifest's folder; empty: none) and the decoded pixels (RGBA8, top row first;
  // null when there is none). A drawing needs `camera`: the drawing is what that camera saw.
  std::string drawing_path;
  std::shared_ptr<const TextureImage> drawing;
  // Frame of the base animation this key deforms: 0 for a static base; in [0, frameCount()) for
  // an animated one. Keys with the same view and different frames share one viewing-sphere point.
  int frame = 0;
};

// Per-part key sets (docs/weights.md, "Per-part key sets"). A part is a set of vertices
// with its own keys and, optionally, its own driving view, so that one region of the model follows
// one view while the rest follows another (the "cubist" views of Chaudhuri et al.). What a part
// selects (exactly one kind):
//  - kVertices: the base's vertices `vertices` (indices < #V);
//  - kMaterial: every vertex of a triangle whose material is named `material`;
//  - kWeights:  a painted mask, `mask` (#V values in [0, 1]; `mask_path` names the file it came
//    from, as the manifest writes it, or is empty for an inline list).
// `border` (model units, finite, >= 0; kVertices and kMaterial only): the selection's weight falls
// from 1 to 0 over this Euclidean distance from the nearest selected vertex, s = 1 - S(d / border)
// with S(t) = 3t^2 - 2t^3; 0 keeps a hard border (1 on the selection and on vertices at the same
// position, 0 elsewhere). `keys`: the names of the part's keys (at least one; a key belongs to at
// most one part; keys in no part drive the rest of the model). `view`: a fixed driving view
// (direction from the centre towards the eye, any finite non-zero length); none: the main view.
struct RawPart {
  enum class Select { kVertices, kMaterial, kWeights };
  std::string name;
  Select select = Select::kVertices;
  std::vector<std::int32_t> vertices;
  std::string material;
  std::vector<float> mask;
  std::string mask_path;
  double border = 0.0;
  std::vector<std::string> keys;
  std::optional<Eigen::Vector3d> view;
};

// Most parts a model may have (the per-frame evaluation keeps one slot per part on the stack).
inline constexpr std::size_t kMaxParts = 64;
// The name of the implicit part that holds the vertices outside every part and the keys of none.
inline constexpr const char* kRestPartName = "rest";

struct RawViewDependentModel {
  std::string source;  // manifest path, used in messages (may be empty)
  // `source`, or "model" when it is empty: how messages name the model.
  std::string where() const { return source.empty() ? std::string("model") : source; }
  std::string base_path;  // as written in the manifest
  std::string comment;    // free text kept with the model (the manifest's "comment")
  TriMesh base;
  std::vector<RawKey> keys;
  double sharpness = 1.0;  // alpha of section 3.2.2, finite and > 0 (see view_sphere.h)
  ViewSphereSettings sphere;
  // "weights": {"space": ...}: directions (the paper's viewing sphere) or positions (key eyes in
  // 3D, vdg/viewdep/key_space.h). Positions need every key's eye, a static base, the linear scheme
  // and at most kMaxPositionKeys keys; validate() refuses otherwise, naming the key.
  KeySpaceSettings key_space;
  std::optional<Eigen::Vector3d> center;  // default: the base's bounding-box centre

  // Animated base (section 4.1). Without base_animation the model is static: base_frames and
  // base_skin must be empty, every key's frame 0 and offsets kWorld. With it, `base` holds the
  // topology (and, as the loader fills it, frame 0's positions), and the loader fills
  //   base_frames: frameCount() x (#V x 3), the base's positions at every frame;
  //   base_skin:   empty, or frameCount() x (#V x 9), each vertex's skin linear part (the upper
  //                left 3x3 of its blended skinning matrix, COLUMN-major), as vdg::Rig gives it.
  std::optional<BaseAnimationSpec> base_animation;
  OffsetSpace offsets = OffsetSpace::kWorld;
  std::vector<std::vector<float>> base_frames;
  std::vector<std::vector<float>> base_skin;

  // Per-part key sets (see RawPart); empty: one key set for the whole model (the paper's model).
  std::vector<RawPart> parts;

  bool animated() const { return base_animation.has_value(); }
  // Frames of the base animation: base_frames.size() when animated, 1 for a static base.
  std::size_t frameCount() const { return animated() ? base_frames.size() : 1; }

  // The centre the views are measured from.
  Eigen::Vector3d resolvedCenter() const;
  // Sets view = normalize(camera.eye - centre) for every key given by a camera (robustly: any
  // finite distance works; an eye at the centre leaves a zero view for validate() to report).
  void resolveViews();
  // Throws vdg::Error naming the manifest, key and vertex for: a key whose vertex count
  // or triangles differ from the base, non-finite coordinates, a vertex whose offset from the base
  // overflows a float, a zero or non-finite view (any finite non-zero length is fine), two keys
  // with the same view (within ViewSphere::kSameViewRad; an O(n log n) search), duplicate names,
  // a sharpness that is not finite and > 0, a bad falloff angle, more than kMaxKeys keys.
  // Animated bases (section 4) add: two keys may share a view only when their frames differ (they
  // become one viewing-sphere point with several key frames; the same view AND frame is an
  // error); a key frame outside [0, frameCount()); no frames or more than kMaxBaseFrames; a
  // base_frames entry that is not #V x 3 finite floats; base_skin neither empty nor frameCount()
  // entries of #V x 9 finite floats; offsets kSkinned without base_skin, or with a skin linear
  // part that is singular at a key's frame (naming the key and vertex); more than
  // kMaxKeyFramesPerView key frames for one view. A static model refuses a key frame other than
  // 0, base_frames, base_skin and offsets kSkinned. For an animated base a key's offset is
  // measured from base_frames[frame], and must not overflow a float.
  // Parts (RawPart) add, each naming the part: more than kMaxParts parts, an empty or repeated
  // name or the name kRestPartName, no keys, an unknown key name or a key in two parts, a vertex
  // index out of range, an empty vertex list, a material the base does not have, a mask that is
  // not #V values in [0, 1], a border that is not finite and >= 0 (or any border on a mask), a
  // driving view that is zero or not finite; and parts on an animated base.
  void validate() const;
};

// The per-vertex masks of the parts: raw.parts.size() + 1 arrays of #V floats, the parts in order
// and the rest last (empty when the model has no parts). With s_p(v) the selection weight of part
// p (RawPart: 1 on its selection, falling over `border`), the masks are
//   m_p(v) = s_p(v) / max(1, sum_q s_q(v)),   m_rest(v) = 1 - sum_p m_p(v),
// a partition of unity with every mask in [0, 1]; parts that do not overlap keep their s_p. Cost:
// a uniform grid of cell `border` over each selection; every vertex compares itself with the
// selected vertices of its 27 neighbouring cells (O(#V) for a border of a few edge lengths,
// O(#V x selected vertices) at worst, for a border as large as the model). Expects a validated model.
std::vector<std::vector<float>> computePartMasks(const RawViewDependentModel& raw);

class ViewDependentModel {
 public:
  // Validates `raw` (everything validate() checks; the same-view search runs once, in the viewing
  // sphere's build) and builds the viewing sphere and the (sparse) key deltas. A model without
  // keys can be loaded and saved (an editor starts from one) but not built: that throws vdg::Error.
  // An animated raw model (raw.animated()) is refused with vdg::Error "MODEL: has an animated base
  // ('base_animation'); build it as an AnimatedViewDependentModel (vdg/viewdep/animated_model.h)"
  // rather than silently dropping its animation.
  static ViewDependentModel build(const RawViewDependentModel& raw);

  const TriMesh& base() const { return base_; }
  // The base's surface (vdg/geom/surface.h): seams welded, the file's hard edges kept; evaluate()'s
  // normals and a renderer's shading use it.
  const SurfaceTopology& surface() const { return surface_; }
  std::size_t vertexCount() const { return base_.vertexCount(); }
  std::size_t keyCount() const { return keys_.size(); }
  // Accessors by key index (tools and editors, not per-frame): `key` must be < keyCount(); an
  // index out of range throws vdg::Error "key K out of range (the model has N keys)".
  const std::string& keyName(std::size_t key) const;
  const Eigen::Vector3d& keyView(std::size_t key) const;
  const std::optional<Camera>& keyCamera(std::size_t key) const;
  // Number of vertices key `key` moves (its delta is stored sparse when this is small).
  std::size_t keyMovedCount(std::size_t key) const;
  const Eigen::Vector3d& center() const { return center_; }
  double sharpness() const { return sharpness_; }
  const ViewSphere& sphere() const { return sphere_; }

  // What the model can draw, for framing and clip planes (computed once in build()). A blend is a
  // convex combination of the base and the keys per vertex (the weights are >= 0 and sum to 1,
  // section 3.2.2), so every blended vertex lies in
  //   extent():       the axis-aligned box of the base's and every key mesh's positions;
  //   extentRadius(): the largest distance from center() to a vertex of the base or of a key mesh
  //                   (a sphere about center() holding every blend; at least 1e-6).
  // Both are in model units; a key that raises the top by 80% raises extent().max[1] with it.
  const Bounds& extent() const { return extent_; }
  double extentRadius() const { return extent_radius_; }

  // normalize(eye - centre), the view direction for an eye position in model space, for any finite
  // distance (robust normalisation); the zero vector when the eye is at the centre or not finite.
  Eigen::Vector3d viewFromEye(const Eigen::Vector3d& eye) const;

  // Per-frame contract (the rule of every vdg evaluation function, after ozz-animation's jobs):
  // weights(), blend(), keyPositions() and evaluate() check their sizes, indices and values on
  // entry; on a violation they return false and have written nothing (no output span, no `out`,
  // no `*hint`); they never throw and never allocate. Spans must have exactly the size stated.
  // The model's triangles are trusted from build() (validated there); normals are those of
  // computeVertexNormals(surface(), ...): seams welded, the base file's hard edges kept.

  // Weights of a view direction into `out`. sharpness <= 0 means "the model's own"; `hint` as in
  // ViewSphere::weights (-1 or a triangle index of sphere()). Violations: a zero or non-finite
  // view, a non-finite sharpness, a hint out of range, an rbf model (use denseWeights()), a
  // positions model (its weights need the eye: denseWeightsAtEye()). denseWeights() and evaluate()
  // refuse a positions model too.
  [[nodiscard]] bool weights(const Eigen::Vector3d& view, double sharpness, ViewWeights& out,
                             int* hint = nullptr) const;
  // Blended positions for `w` into `out_positions` (#V x 3). Violations: out_positions.size() !=
  // 3 * vertexCount(); a slot's key index >= keyCount() or < -1; a non-finite weight.
  [[nodiscard]] bool blend(const ViewWeights& w, std::span<float> out_positions) const;
  // Every key's weight and the base's (keyCount() + 1 floats, ViewSphere::denseWeights): the only
  // weights query of an rbf model (weights() refuses one: its ViewWeights hold three keys).
  // Violations: those of weights(); out.size() != keyCount() + 1.
  [[nodiscard]] bool denseWeights(const Eigen::Vector3d& view, double sharpness, std::span<float> out,
                                  int* hint = nullptr) const;
  // Blended positions for dense weights (keyCount() + 1 floats, the base last) into out_positions
  // (#V x 3): base + sum_k w_k (key_k - base), section 3.2.3 over every key. Violations: sizes
  // other than stated, a non-finite weight.
  [[nodiscard]] bool blendDense(std::span<const float> weights, std::span<float> out_positions) const;
  // Throws vdg::Error "model parts ('parts') are not supported by WHERE ..." for a model with
  // parts, "the 'positions' weight space is not supported by WHERE ..." for a positions model and
  // "the 'rbf' weight scheme is not supported by WHERE ..." for an rbf model: the callers that
  // blend at most three keys per view (ViewWeights) refuse them with this line.
  void requireThreeKeyWeights(const std::string& where) const;
  // Throws vdg::Error "model parts ('parts') are not supported by WHERE ..." for a model with
  // parts: the callers that weigh one key set for the whole mesh refuse it with this line.
  void requireNoParts(const std::string& where) const;

  // Per-part key sets (RawPart; docs/weights.md, "Per-part key sets"). A model with parts has
  // partCount() = raw.parts.size() + 1 parts, the rest (kRestPartName: the vertices outside every
  // part, the keys of no part, the main view) last; a model without parts has partCount() == 0
  // and evaluates exactly as before. Each part has its own viewing sphere over its own keys (the
  // model's ViewSphereSettings and sharpness; the rest may have no keys, then it keeps the base).
  // Evaluation, after Rademacher 99, 3.2.3 (the blend is affine, so it is written with offsets)
  // with one key set per part:
  //   p(v) = base(v) + sum_parts m_p(v) sum_{k in p} w_pk(view_p) (key_k(v) - base(v)),
  // m_p the masks of computePartMasks(). build() stores each key's delta already multiplied by its
  // part's mask (sparse: only vertices the masked key moves), so keyPositions() gives a key as its
  // part sees it (and keyMovedCount() the vertices it moves there) and a frame costs what the plain blend of the same
  // keys costs. For a model with parts, sphere() is empty, and weights() and denseWeights() return false (use
  // partWeights()).
  bool hasParts() const { return !parts_.empty(); }
  std::size_t partCount() const { return parts_.size(); }
  // Accessors by part index (< partCount(); out of range throws vdg::Error, as the key accessors).
  const std::string& partName(std::size_t part) const;
  // The part's keys, as indices of the model's keys, in the order of its sphere.
  std::span<const std::size_t> partKeys(std::size_t part) const;
  // The part's fixed driving view (unit), or none when it follows the main view.
  const std::optional<Eigen::Vector3d>& partView(std::size_t part) const;
  // Vertices whose mask for this part is > 0.
  std::size_t partVertexCount(std::size_t part) const;
  // The driving view of every part for a main view: its fixed view, or `view` (partCount()
  // entries). Violations: out.size() != partCount().
  [[nodiscard]] bool partViews(const Eigen::Vector3d& view, std::span<Eigen::Vector3d> out) const;
  // The weights of part `part`'s keys and the base at `view` into `out` (partKeys(part).size() + 1
  // floats, the base last; a part without keys gives the base 1). Violations: part out of range,
  // out of the wrong size, a zero or non-finite view, a non-finite sharpness.
  [[nodiscard]] bool partWeights(std::size_t part, const Eigen::Vector3d& view, double sharpness,
                                 std::span<float> out) const;
  // Evaluation with one driving view per part (partCount() views; a part's fixed view is NOT
  // applied here: the caller chooses every view, e.g. from partViews()). Violations: a model
  // without parts, views.size() != partCount(), a zero or non-finite view, a non-finite
  // sharpness, output sizes as evaluate(). For a model with parts, evaluate() is this with
  // partViews(view); its hint is left as it is.
  [[nodiscard]] bool evaluateParts(std::span<const Eigen::Vector3d> views, double sharpness,
                                   std::span<float> out_positions, std::span<float> out_normals = {}) const;
  // Throws vdg::Error "the 'positions' weight space is not supported by WHERE ..." for a positions
  // model: for callers that weigh a view DIRECTION (any scheme) but have no eye position.
  void requireViewDirections(const std::string& where) const;

  // Keys at distances ("weights": {"space": "positions"}; vdg/viewdep/key_space.h).
  WeightSpace weightSpace() const { return key_space_ ? WeightSpace::Positions : WeightSpace::Directions; }
  // The key space of a positions model; nullptr for a directions model.
  const KeySpace* keySpace() const { return key_space_ ? &*key_space_ : nullptr; }
  // Weights of an eye POSITION (model space): keyCount() + 1 floats, the base last. A positions
  // model weighs the eye in its key space (hint: a tetrahedron index); a directions model weighs
  // viewFromEye(eye) on its sphere (hint: a triangle index). Same contract as denseWeights();
  // a further violation: an eye at the centre (no direction) where the model needs a direction.
  [[nodiscard]] bool denseWeightsAtEye(const Eigen::Vector3d& eye, double sharpness, std::span<float> out,
                                       int* hint = nullptr) const;
  // Positions of key `key` (its full mesh) into `out_positions` (#V x 3). Violations: key >=
  // keyCount(), out_positions.size() != 3 * vertexCount().
  [[nodiscard]] bool keyPositions(std::size_t key, std::span<float> out_positions) const;
  // weights + blend + (when out_normals is non-empty) normals recomputed from the blended
  // positions. Violations: those of weights(); out_positions.size() != 3 * vertexCount();
  // out_normals neither empty nor 3 * vertexCount() floats.
  [[nodiscard]] bool evaluate(const Eigen::Vector3d& view, double sharpness, std::span<float> out_positions,
                              std::span<float> out_normals = {}, int* hint = nullptr) const;
  // denseWeightsAtEye + blendDense + normals, as evaluate(); any weight space, any scheme (the
  // weights on the stack: the rbf and positions models have at most 256 keys; a directions model
  // with more keys and a three-key scheme blends its ViewWeights).
  [[nodiscard]] bool evaluateAtEye(const Eigen::Vector3d& eye, double sharpness, std::span<float> out_positions,
                                   std::span<float> out_normals = {}, int* hint = nullptr) const;

 private:
  struct Key {
    std::string name;
    std::optional<Camera> camera;
    Eigen::Vector3d view = Eigen::Vector3d::Zero();  // unit: keyView()
    std::size_t moved_count = 0;
    std::vector<std::uint32_t> indices;  // sparse: moved vertex indices (empty when dense)
    std::vector<float> deltas;           // sparse: moved_count x 3; dense: #V x 3
    bool dense = false;
    // Sparse keys: the vertices whose normal a move of this key can change (the homes of the
    // corners of every triangle at a moved vertex, and the vertices copying those homes),
    // ascending; ModelEvaluator recomputes only these.
    std::vector<std::int32_t> normal_vertices;
  };
  friend class ModelEvaluator;
  // Floats of positions per chunk of the threaded blend: a 3k-vertex model runs inline.
  static constexpr std::size_t kBlendGrain = 3 * 16384;
  bool checkWeights(const ViewWeights& w) const;
  // Adds w's sparse keys' weighted deltas to out (#V x 3), slot by slot.
  void scatterSparse(const ViewWeights& w, float* out) const;
  void findNormalVertices();
  struct Part {
    std::string name;
    std::vector<std::size_t> keys;        // model key indices
    std::optional<ViewSphere> sphere;     // over `keys` (none when the part has no keys)
    std::optional<Eigen::Vector3d> view;  // fixed driving view (unit)
    std::size_t vertex_count = 0;         // vertices with a mask > 0
  };
  // Builds parts_ and the masked deltas (parts.cpp); `views` are the keys' unit views.
  void buildParts(const RawViewDependentModel& raw, std::span<const std::string> labels);
  // Adds weight * delta of key k to out (#V x 3).
  void addKey(std::size_t k, float weight, float* out) const;
  // Fills the keys' deltas from raw (each multiplied by masks[v] when masks is non-empty).
  void storeDeltas(const RawViewDependentModel& raw, std::span<const std::vector<float>> masks,
                   std::span<const std::size_t> part_of_key);

  TriMesh base_;
  SurfaceTopology surface_;
  std::vector<Key> keys_;
  ViewSphere sphere_;  // positions models: the key space's sphere of direction groups
  std::optional<KeySpace> key_space_;
  Eigen::Vector3d center_ = Eigen::Vector3d::Zero();
  double sharpness_ = 1.0;
  Bounds extent_;
  double extent_radius_ = 1e-6;
  std::vector<float> base_normals_;  // computeVertexNormals of the base, #V x 3
  std::vector<Part> parts_;          // empty, or the raw parts then the rest
};

}  // namespace vdg
