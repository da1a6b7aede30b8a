// glTF 2.0 output of a view-dependent model (format documented in docs/gltf-export.md, the
// extras in docs/schema/vdg-gltf-extras.schema.json), and the reader of vdg's own description
// back from a glTF file.
//
// What is written: one mesh whose attributes are the base model (POSITION, NORMAL, TEXCOORD_0 with
// the vertices split on uv seams, _VDG_VERTEX naming each exported vertex's model vertex), one
// triangle primitive per material (base colour factor and texture; a plain dielectric material for
// faces without one; docs/gltf-export.md, "Materials"), and one
// morph target per key (per key view and key frame; Rademacher 99, section 3.2.3 writes the blend
// as base + sum_i w_i (key_i - base), which is exactly glTF's morph target formula with the key
// deltas as targets and the view's weights as morph weights). mesh.weights are all zero (the
// base). mesh.extras.targetNames names the targets (the convention three.js and Blender read);
// mesh.extras.vdg holds the view-dependent description (key views and frames, sharpness,
// uncovered mode, offset mode, centre), from which vdg rebuilds the model.
//
// The writer is independent of tinygltf: the JSON is built with nlohmann-json and the binary
// buffer is laid out here (every bufferView starts on a 4-byte boundary).
//
// A model goes through the neutral GltfExportInput, so that other sources (an animated model:
// one target per (key view, key frame), a skinned base and its animation) fill the same struct.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "vdg/anim/rig.h"
#include "vdg/geom/camera.h"
#include "vdg/geom/tri_mesh.h"
#include "vdg/io/gltf_compress.h"
#include "vdg/io/mesh_read_options.h"
#include "vdg/viewdep/animated_model.h"
#include "vdg/viewdep/camera_bake.h"
#include "vdg/viewdep/model.h"
#include "vdg/viewdep/view_sphere.h"

namespace vdg {

// Version of the mesh.extras.vdg object ("version" field). Version 2 adds "sphere" (the viewing
// sphere as vdg built it) and, for an animated model, "time" (the key views' spline tables), so
// that a runtime reproduces `vdg weights` exactly (docs/gltf-export.md); version 3 adds "weights"
// ({"scheme": "smooth"}) and is written only for a smooth model;
// version 4 adds the rbf scheme ("weights": {"scheme": "rbf", "kernel", "width"} and the solved
// interpolation in "sphere"."rbf") and is written only for an rbf model; versions 1 to 3 still read.
inline constexpr int kGltfExtrasVersion = 4;

// One key view's time interpolation (mesh.extras.vdg."time"[i]; AnimatedViewDependentModel):
// its key frames f_1 < ... < f_m and the spline's second-derivative table (m x m, row-major).
struct GltfViewTime {
  std::vector<int> frames;
  std::vector<double> second;
};

// The viewing sphere written into mesh.extras.vdg."sphere" (version 2): exactly ViewSphere's
// points (key views first, then the dummy base points), triangles with their cone inverses
// (row-major), boundary arcs and isolated keys, and per key view the morph target of each of its
// key frames. `time` is per key view for an animated model, empty for a static one.
struct GltfViewSphere {
  std::vector<Eigen::Vector3d> points;
  std::size_t views = 0;
  std::vector<std::array<int, 3>> triangles;
  std::vector<Eigen::Matrix3d> inverses;
  std::vector<std::array<int, 2>> arcs;
  std::vector<int> isolated;
  std::vector<std::vector<int>> view_targets;
  std::vector<GltfViewTime> time;
  // Rbf scheme only (version 4, "sphere"."rbf"): ViewSphere::rbfChord2() and rbfCoefficients()
  // ((points + 1) rows of views + 1 values); empty for the other schemes.
  double rbf_chord2 = 0.0;
  std::vector<double> rbf_coefficients;
};

// The sphere of a static model (or of hand-made targets): point i is key i = morph target i.
GltfViewSphere gltfViewSphere(const ViewSphere& sphere);

// One morph target: a key deformation as position deltas from the base.
struct GltfTarget {
  std::string name;                                // unique; written in mesh.extras.targetNames
  Eigen::Vector3d view = Eigen::Vector3d::Zero();  // key view, towards the eye (any finite non-zero length)
  int frame = 0;                                   // key frame (0 for a static model)
  std::optional<Camera> camera;                    // the aligned key camera, when the key has one
  std::vector<float> deltas;                       // #V x 3: key - base (positions)
  std::vector<float> normal_deltas;                // empty, or #V x 3: key normals - base normals
};

// How an animated base is written (mesh.extras.vdg.animation.base; docs/gltf-export.md):
//  - kSkin: the base's skin (nodes, joints, inverse bind matrices, JOINTS_0 / WEIGHTS_0) and its
//    animation; POSITION is the bind pose and the key targets are the offsets in each vertex's
//    skinning frame. glTF morphs before it skins, which is exactly vdg's "skinned" offsets, so the
//    export is exact. Only for "offsets": "skinned" on a skinned glTF base.
//  - kFrames: the base sampled at every frame: POSITION is frame 0 and frames 1..N-1 are extra
//    morph targets ("base frame i", after the key targets) played by a weights animation (frame i
//    at time i / fps: weight 1 on its target). Exact at every frame for "world" offsets on any base
//    (an OBJ sequence, or a glTF base whose offsets are not skinned).
enum class GltfBaseMode { kSkin, kFrames };
const char* gltfBaseModeName(GltfBaseMode mode);  // "skin", "frames"

// An animated base (written into mesh.extras.vdg."animation"; none for a static model).
struct GltfBaseAnimation {
  int frame_count = 1;  // frames 0 .. frame_count-1
  double fps = 24.0;    // > 0
  bool loop = false;
  GltfBaseMode mode = GltfBaseMode::kFrames;
  // kFrames: frame_count - 1 entries, frames 1..N-1 as #V x 3 deltas from POSITION (frame 0), and
  // their normal deltas (empty, or one #V x 3 entry per frame).
  std::vector<std::vector<float>> frame_deltas;
  std::vector<std::vector<float>> frame_normal_deltas;
  // kSkin: the rig whose skin and animation are written. Its nodes follow the mesh node (node i of
  // the rig is glTF node i + 1); the mesh node is a root without transform (the skin ignores it).
  // Only the translation, rotation and scale channels of `rig.animations[rig_animation]` are
  // written (samplers copied as they are).
  std::optional<RawRig> rig;
  int rig_animation = 0;
};

// A resampled node channel of a bake (kSkin bases): one value per bake time, node indexing the rig.
struct GltfNodeTrack {
  int node = 0;
  RigPath path = RigPath::kTranslation;  // translation, rotation or scale
  std::vector<float> values;             // times.size() x 3 (x 4 for rotations, unit, one hemisphere)
};

// A camera path baked into one glTF animation (the samples of vdg/viewdep/camera_bake.h): the morph
// weights of each sample time and, when `translations` is non-empty, the camera as an animated
// node (a perspective camera looking down its node's -Z with +Y up, as glTF cameras do).
struct GltfBakedAnimation : CameraPathBake {
  std::string name = "view-dependent";
  bool step = false;  // sampler interpolation: STEP, or LINEAR (the default)
  // The base's skeleton, resampled at the bake times (kSkin bases; empty otherwise).
  std::vector<GltfNodeTrack> node_tracks;
  // Free description kept in the animation's extras.vdg (camera options, fps); may be empty.
  std::string description;
};

// Everything a glTF export writes.
struct GltfExportInput {
  TriMesh base;                     // positions, triangles, uvs (per corner, see tri_mesh.h)
  std::vector<float> normals;       // empty (no NORMAL) or #V x 3 unit normals
  std::vector<GltfTarget> targets;  // the keys (then, for a kFrames base, the base frames follow)
  // The view-dependent description (mesh.extras.vdg).
  double sharpness = 1.0;
  ViewSphereSettings sphere;
  Eigen::Vector3d center = Eigen::Vector3d::Zero();
  OffsetSpace offsets = OffsetSpace::kWorld;  // only kWorld for a static model
  std::optional<GltfBaseAnimation> base_animation;
  std::optional<GltfBakedAnimation> bake;
  std::string mesh_name = "vdg-model";
  // The built model's viewing sphere (and time tables), written as extras v2 "sphere" / "time".
  // gltfExportInput fills it. Left empty on a static input, the writer builds it from the targets'
  // views and `sphere`; an animated input must carry it.
  std::optional<GltfViewSphere> view_sphere;
  GltfCompression compression = GltfCompression::kNone;  // vdg/io/gltf_compress.h
  // Add the weights as a KHR_interactivity graph (vdg/io/gltf_interactivity.h; static models only:
  // the writer throws vdg::Error naming what is not supported otherwise).
  bool interactivity = false;
};

// Fills the input from a built static model: its base, normals computed from the base positions
// (area-weighted, vertex normals of tri_mesh.h; a vertex on no triangle gets (0, 1, 0)), one target
// per key in key order with deltas keyPositions - base and normal deltas, the model's sharpness,
// sphere settings and centre. Throws vdg::Error when a key's positions cannot be read.
GltfExportInput gltfExportInput(const ViewDependentModel& model);

// The same for an animated model (Rademacher 99, section 4): one target per raw key (so per key
// view and key frame, in raw key order) holding that key's offsets in offset space, normals for
// the export's POSITION, the model's settings and the animated base (above). `raw` is the model's
// raw description (key names, cameras, base_animation) and `rig` the glTF base read again
// (readBaseRig) or null for an OBJ-sequence base. The base is written kSkin when the offsets are
// skinned, else kFrames. Throws vdg::Error naming the model for what cannot be exported exactly:
// skinned offsets on a base that is not a skinned glTF mesh, or whose mesh has morph targets of its
// own.
GltfExportInput gltfExportInput(const AnimatedViewDependentModel& model, const RawViewDependentModel& raw,
                                const RawRig* rig);

// The rig of a glTF animated base (raw.base_animation->gltf, relative to raw.source's folder; its
// mesh or node selection), read again for export. Throws vdg::Error naming the model for a base
// that is not a glTF one.
RawRig readBaseRig(const RawViewDependentModel& raw);

// The glTF animation of a baked camera path (bakeCameraPath, bakeAnimatedCameraPath with
// `base_frame_targets` when `input`'s base is written kFrames) over the model `input` describes: the
// samples as they are and, for a kSkin base, the skeleton's channels sampled at each sample's frame
// (frames[s] / fps) into node_tracks, rotations kept in one hemisphere. Throws vdg::Error "bake: ..."
// when the samples' weights do not match input's targets, or a kSkin base's samples carry no frames.
GltfBakedAnimation gltfBakedAnimation(CameraPathBake samples, const GltfExportInput& input);

// Morph target caps of engines (docs/gltf-export.md, "Target count"): Bevy takes 64 targets a mesh,
// three.js and Filament about 256 (three.js packs them into a texture; Filament's limit).
struct MorphTargetCap {
  const char* engine;
  std::size_t targets;
};
inline constexpr MorphTargetCap kMorphTargetCaps[] = {{"Bevy", 64}, {"three.js", 256}, {"Filament", 256}};

// Morph targets an export writes: the keys, then a kFrames base's frames 1..N-1.
std::size_t gltfTargetCount(const GltfExportInput& input);
// The same for an animated model without building its export: one target per raw key (per key view
// and key frame), plus frameCount() - 1 base frames for "world" offsets (a kFrames base; "skinned"
// offsets are written with the skin, which needs no targets).
std::size_t gltfTargetCount(const AnimatedViewDependentModel& model);
// The engines whose cap `count` exceeds, as "Bevy (64), three.js (256)"; empty when none.
std::string morphTargetCapsExceeded(std::size_t count);
// Throws vdg::Error "WHERE: the export needs N morph targets (K keys + F base frames), more than
// --max-targets M; ..." (what to do) when gltfTargetCount(input) > max_targets.
void checkMaxTargets(const GltfExportInput& input, std::size_t max_targets, const std::string& where);

// What an export wrote and left out, for the command line to tell the user.
struct GltfExportReport {
  bool uvs_written = false;
  std::string note;                // empty, or one line (for instance why a texture was not written)
  std::size_t bytes = 0;           // size of the .glb, or of the .gltf plus its .bin and images
  std::size_t sparse_targets = 0;  // targets whose POSITION deltas went into sparse accessors
  std::size_t materials = 0;       // glTF materials written (one primitive per material)
  std::size_t images = 0;          // images written (embedded, or files beside a .gltf)
  std::size_t split_vertices = 0;  // vertices added by splitting uv seams (exported = model + these)
  std::vector<std::string> files;  // writeGltfExport of a .gltf: the image files written beside it
};

// An image file beside a .gltf: its name (a file name, the uri) and its PNG or JPEG bytes.
struct GltfImageFile {
  std::string name;
  std::string bytes;
};

// Serialises `input` in memory: the GLB bytes (12-byte header, JSON chunk, BIN chunk; images in
// bufferViews), or for the .gltf form the JSON text with the buffer's "uri" set to `bin_uri` and the
// buffer returned in `bin`, and the images returned in `images` (named "STEM-texture-N.png" or
// ".jpg" after bin_uri's stem), or, when `images` is null, written as data: URIs. Names that are not valid UTF-8 are
// written with U+FFFD in place of the bad bytes (JSON is UTF-8). Throws vdg::Error naming `where` and the element for
// an inconsistent input: an empty base, array sizes that do not match #V, a triangle index out of range, non-finite
// values, normals that are not unit length, empty or duplicate target names, a zero target view, a bake whose arrays do
// not match its times or #targets, times not strictly increasing.
std::string gltfToGlb(const GltfExportInput& input, const std::string& where, GltfExportReport* report = nullptr);
std::string gltfToJson(const GltfExportInput& input, const std::string& where, const std::string& bin_uri,
                       std::string& bin, GltfExportReport* report = nullptr,
                       std::vector<GltfImageFile>* images = nullptr);

// Writes `path`: a .glb, or a .gltf with its buffer in a file beside it named after the .gltf's
// stem ("out.gltf" -> "out.bin") and its images beside it ("out-texture-0.png", listed in the
// report's `files`); all are replaced together as one step (a FileTransaction
// with its journal ".vdg-journal" in the output folder, under that folder's lock). Any other
// extension is an error. Throws vdg::Error naming `path`.
GltfExportReport writeGltfExport(const std::string& path, const GltfExportInput& input);

// Reading back. `mesh_extras_json` is the text of the mesh's "extras" object (with "targetNames"
// and "vdg"), `base` the mesh as decoded from the file (positions, triangles, and uvs as vdg holds
// them: a reader flips TEXCOORD_0's v back to 1 - v), and
// `target_deltas` the POSITION deltas of the mesh's morph targets in order (#V x 3 each, sparse
// accessors expanded). Returns a raw model (no meshes' paths; each key's mesh = base + deltas, its
// view, camera and name from the extras) that ViewDependentModel::build accepts. Throws vdg::Error
// "WHERE: mesh extras: 'vdg'.'keys'[2].'view': ..." for a missing or malformed description, a version this vdg
// does not read, a key count that differs from the target count, names that differ from
// targetNames, a version 2 "sphere" / "time" that is malformed or does not match the keys in size
// (vdg re-derives the sphere from the keys; the written one is for runtimes), an animated
// description (key frames other than 0 or an "animation"; it needs the
// file's skin and animation: loadGltfModel), and everything RawViewDependentModel::validate checks.
RawViewDependentModel rawModelFromGltfExtras(std::string_view mesh_extras_json, const TriMesh& base,
                                             std::span<const std::vector<float>> target_deltas,
                                             const std::string& where);

// A view-dependent model from a glTF file vdg exported (`vdg export`, `vdg bake`): the file's mesh
// (the first node with a mesh of the default scene) and its mesh.extras.vdg. Static: as
// rawModelFromGltfExtras. Animated: base_animation names this file (gltf = its file name, resolved
// from the returned source's folder), its base animation, fps and loop; the base is sampled with
// vdg's glTF reader (vdg::Rig) at time i / fps for every frame i (positions, and skin linear parts
// for skinned offsets); each key's mesh is base(frame) + offset (world) or base(frame) +
// L_v(frame) offset (skinned). Throws vdg::Error "FILE: ..." for a file that does not load, has no
// mesh.extras.vdg ("... was not exported by vdg"), or a description that does not match the file.
// `options`: materials and textures of the file's mesh (vdg/io/mesh_read_options.h).
RawViewDependentModel loadGltfModel(const std::string& path, const MeshReadOptions& options = {});

// True when `path` is a glTF file whose default mesh carries mesh.extras.vdg (a view-dependent
// model); false for a plain glTF mesh. Throws vdg::Error for a file that does not load.
bool gltfHasModel(const std::string& path);

}  // namespace vdg
