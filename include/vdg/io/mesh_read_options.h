// How mesh readers (readObj, readMesh, readGltfMesh, readGltfRig) treat what surrounds the mesh:
// material libraries and textures.
//
// A mesh's geometry is the input; its materials are decoration. So a material library or texture
// that is missing, unreadable, too large, refused by the path policy or broken does not fail the
// read: the reader appends ONE warning line naming the file and why ("spot.mtl:4: map_Kd: spot.png:
// no such file (texture)"), the surface falls back (a material without its texture, or faces without
// a material, which renderers draw in their default colour), and the mesh is returned. With
// `strict`, that warning is thrown instead, as a vdg::Error with the same line.
#pragma once

#include <string>
#include <vector>

namespace vdg {

struct MeshReadOptions {
  // Read materials (OBJ mtllib/usemtl and MTL files, glTF materials) and decode their textures.
  // false: no file besides the mesh (and glTF buffers) is opened, and the mesh has no materials.
  bool materials = true;
  // Material and texture problems are errors (vdg::Error) instead of warnings.
  bool strict = false;
  // Where warnings go, one line each, appended (not cleared); null: they are dropped.
  std::vector<std::string>* warnings = nullptr;
};

}  // namespace vdg
