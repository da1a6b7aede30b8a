// Wavefront OBJ input and output (tinyobjloader builds the mesh; every line is checked first), and
// the MTL material libraries an OBJ names.
//
// Reading keeps the file's vertex order (key deformations correspond to the base by vertex index),
// triangulates polygons (up to 16 corners by ear clipping, which keeps a non-convex face's shape;
// a face of more corners as a fan from its first corner, in linear time), and keeps texture coordinates and normals
// (`vn`) with their own indices (TriMesh::uvs/uv_triangles, normals/normal_triangles; each kept only when every face
// corner has one; normals are scaled to unit length, a zero normal stays zero). The file's normals classify hard edges;
// shading normals are always derived from positions (vdg/geom/tri_mesh.h).
//
// Reading is strict where a lenient reader would silently change the shape: a vertex needs three
// finite coordinates ("v 1 2" and "v nan 1 1" are errors), a face index must be a whole number
// that refers to an existing vertex (no wrap-around of huge numbers), and every error names the
// file and line: "head.obj:12: vertex 7: coordinate 'nan' is not a finite number".
//
// Materials (MeshReadOptions::materials, on by default): `mtllib A.mtl [B.mtl ...]` names material
// libraries (file names split at white space), `usemtl NAME` (the rest of the line) gives the
// following faces a material. TriMesh::materials holds every used name that a library defines, in
// the order of first use; face_materials is -1 for faces before any usemtl or whose name no library
// defines (both stay empty when no face has a material). Of an MTL file, only `newmtl NAME`, `Kd R
// [G B]` (display RGB, clamped to [0, 1]; "Kd spectral"/"Kd xyz" are ignored) and `map_Kd [OPTIONS]
// FILE` (options such as "-s 1 1 1" or "-clamp on" skipped; the file name is the rest of the line)
// are read; the first definition of a name wins. Libraries and textures are opened relative to the
// folder of the file that names them (the OBJ's for mtllib, the MTL's for map_Kd) and only there
// or below: an absolute path, a ".." component, a backslash or a ':' (URI schemes, drive letters)
// is refused. Libraries are regular files of at most kMaxMaterialFileBytes, at most
// kMaxMaterialLibraries per OBJ; textures are PNG or JPEG (vdg/io/image_file.h). A library or
// texture that is refused, missing, too large or broken gives one warning (MeshReadOptions) and
// the fallback: faces without a material (library), a material without its texture (texture).
// Writing is atomic (see atomic_file.h), round-trips every float exactly (shortest form) and writes
// positions, texture coordinates and faces (no normals, no materials).
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "vdg/geom/tri_mesh.h"
#include "vdg/io/mesh_read_options.h"

namespace vdg {

// Largest MTL file (bytes) and most material libraries one OBJ may name.
inline constexpr std::size_t kMaxMaterialFileBytes = std::size_t{64} << 20;
inline constexpr std::size_t kMaxMaterialLibraries = 64;
// Most distinct `usemtl` names in one OBJ file (more is an error of the OBJ file).
inline constexpr std::size_t kMaxObjMaterials = 65536;

// Parses OBJ text; `source` names it in messages, and its folder is where material libraries are
// read from. Throws vdg::Error as described above, and when the text has no triangles; material
// problems are warnings unless options.strict.
TriMesh parseObj(const std::string& text, const std::string& source, const MeshReadOptions& options = {});

// Reads a regular file of at most kMaxMeshFileBytes (vdg/io/read_file.h) and parses it.
TriMesh readObj(const std::string& path, const MeshReadOptions& options = {});

// The materials an MTL text defines, in file order (duplicates included), each with its name,
// base_color (Kd, clamped to [0, 1]; white without Kd) and texture_path (map_Kd's file name as
// written; the texture is not opened). `source` names the text in messages. Throws vdg::Error
// "SOURCE:LINE: ..." for a line it cannot read: a number that is not finite or does not fit a
// float, a Kd with other than 1 or 3 numbers, newmtl without a name, map_Kd without a file name.
std::vector<Material> parseMtl(const std::string& text, const std::string& source);

// The OBJ text writeObj writes (for callers that write it themselves, e.g. in a FileTransaction).
std::string formatObj(const TriMesh& mesh, const std::string& header = {});
// Writes `mesh` to `path` atomically. `header` (may be empty) becomes leading comment lines.
void writeObj(const std::string& path, const TriMesh& mesh, const std::string& header = {});

// A mesh's materials as OBJ + MTL texts (what vdg.Model.save_manifest writes for a base with
// materials): the OBJ is formatObj's with "mtllib MTL_NAME" and a "usemtl" line wherever the face
// material changes; the MTL defines each material once, by a unique name made from its own
// (characters other than letters, digits, '-', '_' and '.' become '_'; repeats get "_2", "_3", ...),
// with Kd its display base colour and, when it has a texture, "map_Kd TEXTURE_FILES[i]" (the file
// names the caller writes the textures' original bytes to, empty for none). Faces without a material
// (-1) after faces with one use a white material "vdg-plain" (OBJ cannot end a material). Without
// face_materials the OBJ is formatObj's alone and the MTL is empty.
struct ObjWithMaterials {
  std::string obj, mtl;
};
ObjWithMaterials formatObjWithMaterials(const TriMesh& mesh, const std::string& header, const std::string& mtl_name,
                                        const std::vector<std::string>& texture_files);

}  // namespace vdg
