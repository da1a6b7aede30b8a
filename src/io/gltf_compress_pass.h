// The post-pass of vdg's glTF writer that makes the export smaller (vdg/io/gltf_compress.h): it
// rewrites the built document and its binary buffer in place.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "vdg/io/gltf_compress.h"

namespace vdg {

// Quantises (kQuantize, kMeshopt) and encodes (kMeshopt) the document `doc` whose buffers[0] is
// `bin`; kNone leaves both as they are. Every bufferView, accessor and image of the document is
// kept or rewritten (unreferenced bufferViews are dropped); attributes it does not know (JOINTS_0,
// WEIGHTS_0, custom "_NAME" attributes) keep their values. Throws vdg::Error naming `where` when
// an encoder fails. `sparse_targets`, when given and the pass ran, gets the number of morph target
// POSITION accessors that are still sparse (GltfExportReport::sparse_targets).
void compressGltf(nlohmann::ordered_json& doc, std::string& bin, GltfCompression compression, const std::string& where,
                  std::size_t* sparse_targets = nullptr);

}  // namespace vdg
