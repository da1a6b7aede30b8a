// The model manifest *.vdg.json (format documented in docs/model-format.md): a base mesh, key
// meshes with their key views or cameras, and the model's settings.
#pragma once

#include <string>

#include "vdg/viewdep/model.h"

namespace vdg {

// Current manifest format version (the "version" field of *.vdg.json).
inline constexpr int kManifestVersion = 1;

// Parses a manifest's text into a raw model WITHOUT reading any mesh: base_path and every key's
// mesh_path are filled, the meshes are left empty. Throws vdg::Error naming `source` and the key
// for unknown fields, a wrong or missing version, and values of the wrong type or range.
RawViewDependentModel parseManifest(const std::string& text, const std::string& source);

// Reads a *.vdg.json manifest and every mesh it names (paths relative to the manifest), resolves
// camera keys' views and validates. Throws vdg::Error naming the file and key for missing files,
// unknown fields, a wrong or missing version, bad values, and everything validate() checks.
RawViewDependentModel loadManifest(const std::string& path);
// The manifest text saveManifest writes (for callers that write it themselves).
std::string formatManifest(const RawViewDependentModel& model);
// Writes the manifest (not the meshes) atomically, with mesh paths as stored in the raw model.
void saveManifest(const std::string& path, const RawViewDependentModel& model);

}  // namespace vdg
