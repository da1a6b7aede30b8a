// Smaller glTF exports (`vdg export --compress`, `vdg bake --compress`; docs/gltf-export.md).
//
//  - kQuantize (KHR_mesh_quantization): positions and position morph targets as normalized SHORT
//    on one grid shared by the base and every target, normals (and normal targets whose deltas lie
//    in [-1, 1]) as normalized BYTE, texture coordinates in [0, 1] as normalized UNSIGNED_SHORT
//    (else float). The grid is uniform (one scale for x, y and z, so that normals stay right under
//    the node's scale): mesh-local p in [-1, 1] is offset + scale * p in model units, the mesh
//    node's translation and scale (the extension's standard dequantisation), written also as
//    mesh.extras.vdg.dequantize. A position is off by at most half a step, scale / 32767 / 2 per
//    component; a normal by 1 / 127 / 2. A skinned mesh ignores its node's transform (glTF 2.0,
//    section 3.7.3), so for a skinned base the dequantisation is folded into the skin's inverse
//    bind matrices (IBM' = IBM * D) and there is no dequantize field (the model space is the
//    skinned one); positions stay float when the skin serves another mesh or has no matrices.
//  - kMeshopt (EXT_meshopt_compression, meshoptimizer's codecs): quantised as above, then vertex
//    attribute bufferViews (mode ATTRIBUTES), triangle index bufferViews (mode TRIANGLES) and the
//    other data (animation, sparse parts) encoded; images are left as they are. Morph targets are
//    written dense (their zero rows compress to almost nothing). The uncompressed bytes live in a
//    fallback buffer without data, so the extension is required.
#pragma once

#include <optional>
#include <string_view>

namespace vdg {

enum class GltfCompression { kNone, kQuantize, kMeshopt };

const char* gltfCompressionName(GltfCompression c);  // "none", "quantize", "meshopt"
// The compression a name stands for; nullopt for an unknown name.
std::optional<GltfCompression> gltfCompressionFromName(std::string_view name);

}  // namespace vdg
