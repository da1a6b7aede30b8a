// Reading a mesh whichever format holds it, chosen by the file's extension (any letter case).
#pragma once

#include <string>

#include "vdg/geom/tri_mesh.h"
#include "vdg/io/mesh_read_options.h"

namespace vdg {

// True when `path` ends in .obj (any letter case).
bool isObjPath(const std::string& path);
// True when `path` names a .gltf or .glb file (any letter case).
bool isGltfPath(const std::string& path);

// Reads a mesh by its extension: .obj (readObj, vdg/io/obj.h), .gltf and .glb (readGltfMesh,
// vdg/io/gltf.h: the static rest pose of the file's first mesh); other formats are refused with a
// clear message. `options` as for readObj and readGltfMesh. Either format's positions must be
// finite and their bounding box's diagonal must fit a float (3.4e38): "FILE: vertices 0 at
// (0, 0, 0) and 1 at (3e+38, 0, 0) lie too far apart: the mesh's extent (5.2e+38) overflows a
// float" (glTF: after the node transforms, checked by its reader).
TriMesh readMesh(const std::string& path, const MeshReadOptions& options = {});

}  // namespace vdg
