// Wavefront OBJ input and output (tinyobjloader reads; the writer is ours).
//
// Reading keeps the file's vertex order (key deformations correspond to the base by vertex index),
// triangulates polygons, and keeps texture coordinates with their own indices. Normals in the file
// are ignored: vdg derives normals from positions. Writing is atomic (see atomic_file.h) and
// round-trips every float exactly (shortest representation).
#pragma once

#include <string>

#include "vdg/geom/tri_mesh.h"

namespace vdg {

// Throws vdg::Error naming the file (and the line, where the parser reports one) when the file is
// missing, unreadable, has no triangles, or refers to vertices that do not exist.
TriMesh readObj(const std::string& path);

// Writes `mesh` to `path` atomically. `header` (may be empty) becomes leading comment lines.
void writeObj(const std::string& path, const TriMesh& mesh, const std::string& header = {});

// Reads an OBJ or a glTF/GLB (first mesh primitive) by extension. glTF support lives in the
// glTF module once it lands; until then only .obj is accepted, with a clear message otherwise.
TriMesh readMesh(const std::string& path);

}  // namespace vdg
