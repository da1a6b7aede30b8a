// glTF 2.0 input (.gltf and .glb): meshes, morph targets, the node hierarchy, skins and
// animations, read into a RawRig (vdg/anim/rig.h) or a static TriMesh.
//
// tinygltf parses the JSON; vdg checks everything tinygltf does not before touching a byte:
// the GLB header and chunks (a truncated file is refused), JSON nesting (at most 64 levels),
// every accessor against its bufferView and buffer (offsets, strides, counts), component types and
// element types per use (POSITION, NORMAL and morph targets: float VEC3; TEXCOORD_0: float or
// normalized u8/u16 VEC2; JOINTS_0: u8/u16 VEC4; WEIGHTS_0: float or normalized u8/u16 VEC4;
// indices: u8/u16/u32 SCALAR; inverse bind matrices: float MAT4; animation times: float SCALAR),
// index ranges, sparse accessors (applied, their indices checked), node indices and cycles, a
// node with two parents, counts above kMaxGltfElements. Every error is one vdg::Error line naming
// the file and the element: "walk.glb: accessors[3]: bufferView 7 out of range (the file has 5)";
// never tinygltf's own text, never a data: URI (a URI is cut short with quotedText).
//
// Refused besides, before tinygltf reads the JSON (docs/meshes.md, "What a glTF file must be"):
// a field of the wrong JSON type (glTF 2.0 section 5: a negative byteOffset, a non-array "nodes"),
// asset.version not 2.x or asset.minVersion above 2.0, any extensionsRequired (vdg implements no
// extension), "scene" or a scene's node out of range, a node listed twice in a scene or not a
// root, a data: URI or external buffer that does not hold byteLength bytes, an image data: URI
// without base64 data, an image with both or neither of uri and bufferView; after it: a node with
// a matrix and TRS, a byteStride on an index or sparse bufferView, the restart value in indices,
// two channels of one animation on the same node and path. The selected mesh's rest pose (default morph weights, then
// skinned or placed by the node transforms) must be finite and its bounding box's diagonal must fit a float: "walk.glb:
// meshes[0] (nodes[2]): vertex 7 lies at (inf, 0, 0) after the node transforms; ...".
//
// Files: a .gltf/.glb is read as a regular file of at most kMaxMeshFileBytes (vdg/io/read_file.h).
// External buffers (`"uri": "walk.bin"`) are read from the glTF file's folder only: an absolute
// URI, a `..` component or a backslash is refused, and all external buffers together are bounded
// by kMaxMeshFileBytes; `data:` URIs (base64) are fine. Images follow the same policy (a refused
// URI is a warning, see below).
//
// The mesh: all triangle primitives (mode 4) of the selected mesh, concatenated in order into one
// TriMesh; primitives of other modes (points, lines, strips, fans) are ignored. NORMAL and
// TEXCOORD_0 are kept when every primitive has them: NORMAL as TriMesh::normals with
// normal_triangles = triangles (one normal per vertex), TEXCOORD_0 as uvs with v flipped (glTF's
// origin is the top-left corner of the image, TriMesh's the bottom-left: v' = 1 - v). Morph target
// names come from mesh.extras.targetNames when it is an array of one string per target. A vdg
// export (every primitive has _VDG_VERTEX, docs/gltf-export.md) is welded back to the model's
// vertices: vertex _VDG_VERTEX[e] takes exported vertex e's position, normal, skin and target deltas
// (every copy must lie at the same position), triangles are renumbered, uvs and file normals stay per
// exported vertex (uv_triangles, normal_triangles), and faces of its plain material
// (extras.vdg.plain) get no material.
//
// Materials (MeshReadOptions::materials, vdg/io/mesh_read_options.h): each primitive's material
// gives its triangles' face_materials (-1: a primitive without one); TriMesh::materials holds the
// used glTF materials in the order of first use, named as the file names them ("materials[3]" when
// unnamed). base_color is pbrMetallicRoughness.baseColorFactor's RGB (linear in glTF, section
// 3.9.2) encoded to display sRGB (IEC 61966-2-1: 12.92 c for c <= 0.0031308, else
// 1.055 c^(1/2.4) - 0.055), the values vdg's renderer shades (vdg/geom/material.h); alpha is
// ignored. baseColorTexture is decoded (PNG or JPEG by its bytes, vdg/io/image_file.h) from a
// bufferView (GLB), a data: URI or a file beside the glTF file (same URI policy as buffers); a
// texture that uses a texCoord other than 0, is missing, refused, too large or broken, or a mesh
// without TEXCOORD_0, gives one warning naming the file and element, and the material shows its
// colour alone (strict: the warning is a vdg::Error).
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

#include "vdg/anim/rig.h"
#include "vdg/geom/tri_mesh.h"
#include "vdg/io/mesh_read_options.h"

namespace vdg {

// Most elements one accessor may hold (vertices, indices, keyframes): 2^24.
inline constexpr std::size_t kMaxGltfElements = std::size_t{1} << 24;

struct GltfSelect {
  // A node's name, else a mesh's name (the first node instancing it, or no node). Empty: the
  // first node with a mesh in the default scene (depth first), else the first node with a mesh,
  // else mesh 0 without a node.
  std::string mesh_or_node;
};

// The selected mesh as a RawRig: all of the file's nodes (same indices as the file), the mesh,
// its morph targets, the skin of its node, and every animation (weights channels of other nodes
// are left out). Validated (RawRig::validate) before it is returned. Throws vdg::Error
// "FILE: ELEMENT: what".
RawRig readGltfRig(const std::string& path, const GltfSelect& select = {}, const MeshReadOptions& options = {});

// The selected mesh as a static TriMesh: the rest pose (no animation) with the default morph
// weights applied, skinned by the rest pose when skinned, otherwise placed by its node's world
// transform; file normals posed the same way. Throws as readGltfRig.
TriMesh readGltfMesh(const std::string& path, const GltfSelect& select = {}, const MeshReadOptions& options = {});

// Human-readable description for `vdg info`: meshes (vertices, triangles, morph targets with
// names), skins, animations with their channels and durations. Throws as readGltfRig for a file
// that does not load, or whose default mesh (GltfSelect{}) does not.
std::string describeGltf(const std::string& path);

// The same from bytes in memory (tests, fuzzing): `source` names them in messages; `folder` is
// where external buffers and images are read from (empty: external files are refused).
RawRig parseGltfRig(std::string_view bytes, const std::string& source, const std::string& folder = {},
                    const GltfSelect& select = {}, const MeshReadOptions& options = {});
std::string describeGltfData(std::string_view bytes, const std::string& source, const std::string& folder = {});

}  // namespace vdg
