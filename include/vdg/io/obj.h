// Wavefront OBJ input and output (tinyobjloader builds the mesh; every line is checked first).
//
// Reading keeps the file's vertex order (key deformations correspond to the base by vertex index),
// triangulates polygons, and keeps texture coordinates with their own indices. Normals in the file
// are ignored: vdg derives normals from positions. Material libraries (`mtllib`) are not read:
// vdg does not use materials yet, and a material file is never opened on a mesh's behalf.
//
// Reading is strict where a lenient reader would silently change the shape: a vertex needs three
// finite coordinates ("v 1 2" and "v nan 1 1" are errors), a face index must be a whole number
// that refers to an existing vertex (no wrap-around of huge numbers), and every error names the
// file and line: "head.obj:12: vertex 7: coordinate 'nan' is not a finite number".
// Writing is atomic (see atomic_file.h) and round-trips every float exactly (shortest form).
#pragma once

#include <string>

#include "vdg/geom/tri_mesh.h"

namespace vdg {

// Parses OBJ text; `source` names it in messages. Throws vdg::Error as described above, and when
// the text has no triangles.
TriMesh parseObj(const std::string& text, const std::string& source);

// Reads a regular file of at most kMaxMeshFileBytes (vdg/io/read_file.h) and parses it.
TriMesh readObj(const std::string& path);

// The OBJ text writeObj writes (for callers that write it themselves, e.g. in a FileTransaction).
std::string formatObj(const TriMesh& mesh, const std::string& header = {});
// Writes `mesh` to `path` atomically. `header` (may be empty) becomes leading comment lines.
void writeObj(const std::string& path, const TriMesh& mesh, const std::string& header = {});

// Reads a mesh by its extension (any letter case): .obj (readObj), .gltf and .glb (readGltfMesh,
// vdg/io/gltf.h: the static rest pose of the file's first mesh); other formats are refused with a
// clear message.
TriMesh readMesh(const std::string& path);

}  // namespace vdg
