// The model manifest *.vdg.json (format documented in docs/model-format.md): a base mesh, key
// meshes with their key views or cameras, and the model's settings.
#pragma once

#include <string>

#include "vdg/io/mesh_read_options.h"
#include "vdg/viewdep/model.h"

namespace vdg {

// Current manifest format version (the "version" field of *.vdg.json). Version 2 added animated
// bases ("base_animation", "offsets", each key's "frame"), version 3 the weight scheme ("weights":
// {"scheme": "linear" | "smooth" | "rbf"}, the rbf scheme with "kernel" and "width" (degrees)),
// version 4 per-part key sets ("parts": [{"name", "select": {"vertices" | "material" |
// "weights"}, "border", "keys", "view"}]; a "weights" mask is a list or a text file of
// one number per vertex, relative to the manifest) and keys at distances ("weights": {"space":
// "directions" | "positions", "falloff": model units} and a key's plain "eye" [x, y, z];
// vdg/viewdep/key_space.h); older files load unchanged, and saveManifest writes the oldest version
// that holds the model (2 for the linear scheme, 3 for another scheme, 4 with parts, the positions
// space or a key given by "eye"), version 5 a key's reference drawing ("drawing": a PNG or JPEG
// file relative to the manifest, on a key given by "camera"; docs/drawing-textures.md), written
// only when a key has one.
inline constexpr int kManifestVersion = 5;

// Parses a manifest's text into a raw model WITHOUT reading any mesh: base_path and every key's
// mesh_path are filled, the meshes are left empty. Throws vdg::Error naming `source` and the key
// for unknown fields, a wrong or missing version, and values of the wrong type or range.
RawViewDependentModel parseManifest(const std::string& text, const std::string& source);

// Reads a *.vdg.json manifest and every mesh it names (paths relative to the manifest), resolves
// camera keys' views and validates. An animated base is read too: every file of an OBJ sequence
// (frame i is file first + i; each frame must have frame 0's vertex count and triangles; at most
// kMaxBaseFrames frames and 2 GiB of positions in all) into raw.base (frame 0) and raw.base_frames.
// A glTF base is sampled at every frame (vdg::Rig; with each vertex's skin linear part into
// raw.base_skin for skinned offsets); its errors name the manifest and the field
// ("FILE: base_animation.gltf: ...", "FILE: base_animation.animation: ..."). Throws vdg::Error naming the file and key
// for missing files, unknown fields, a wrong or missing version, bad values, and everything validate() checks.
// The base mesh (or an animated base's first frame or glTF file) is read with `options` (materials,
// textures and their warnings, vdg/io/mesh_read_options.h); key meshes and later frames are read
// for their geometry only (materials belong to the base). A key's drawing is decoded into
// key.drawing (vdg/io/image_file.h's limits; errors name the manifest, the key and the file). A part's mask file is
// read too (one number per vertex, whitespace-separated; errors name the manifest, the part and the file).
RawViewDependentModel loadManifest(const std::string& path, const MeshReadOptions& options = {});
// The manifest text saveManifest writes (for callers that write it themselves).
std::string formatManifest(const RawViewDependentModel& model);
// Writes the manifest (not the meshes) atomically, with mesh paths as stored in the raw model.
void saveManifest(const std::string& path, const RawViewDependentModel& model);

// OBJ-sequence file patterns: exactly one %d or %0Nd conversion (N one digit, 1-9) and no other
// '%'. checkSequencePattern throws vdg::Error "expected a file pattern with one %d or %0Nd ...,
// got 'PATTERN': WHY"; sequenceFileName gives the file name of `number` (checking the pattern).
void checkSequencePattern(const std::string& pattern);
std::string sequenceFileName(const std::string& pattern, int number);

}  // namespace vdg
