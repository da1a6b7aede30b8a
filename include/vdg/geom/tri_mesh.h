// TriMesh — the triangle mesh every vdg module works on.
//
// A struct of flat arrays (no per-vertex structs), so that a whole attribute can be handed to a
// blend kernel, a GPU buffer or a file writer as one span:
//   positions  #V x 3 floats, row-major (x0 y0 z0 x1 y1 z1 ...), model units (metres by convention)
//   triangles  #F x 3 vertex indices, counter-clockwise seen from outside (right-handed, Y up)
//   uvs        empty or #T x 2 floats: texture coordinates, as many as the file has (seams keep
//              their own coordinates, so the vertex list is never split or reordered)
//   uv_triangles  empty or #F x 3 indices into uvs, one per triangle corner
//   normals    empty or #N x 3 floats: the file's own normals (OBJ `vn`, glTF NORMAL), as many as
//              the file has, unit length
//   normal_triangles  empty or #F x 3 indices into normals, one per triangle corner
//   face_materials    empty or #F indices into materials (-1: no material)
//   materials  the surfaces' materials (vdg/geom/material.h)
// The file's normals are *classification*, not shading: they say which corners meet at a hard
// edge (corners at one position whose file normals differ) and which are smooth (vertices split
// only for texture coordinates). Shading normals are always derived from the current positions:
// computeVertexNormals() fills a caller-owned #V x 3 buffer, and SurfaceTopology
// (vdg/geom/surface.h) keeps the hard edges and welds the seams.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "vdg/geom/material.h"

namespace vdg {

struct TriMesh {
  std::vector<float> positions;                // #V x 3
  std::vector<std::int32_t> triangles;         // #F x 3
  std::vector<float> uvs;                      // empty or #T x 2
  std::vector<std::int32_t> uv_triangles;      // empty or #F x 3 (indices into uvs)
  std::vector<float> normals;                  // empty or #N x 3 (the file's, unit length)
  std::vector<std::int32_t> normal_triangles;  // empty or #F x 3 (indices into normals)
  std::vector<std::int32_t> face_materials;    // empty or #F (indices into materials, -1: none)
  std::vector<Material> materials;

  std::size_t vertexCount() const { return positions.size() / 3; }
  std::size_t triangleCount() const { return triangles.size() / 3; }
};

// Axis-aligned bounds of a #V x 3 position array. Empty input gives min = max = 0.
struct Bounds {
  std::array<float, 3> min{0, 0, 0};
  std::array<float, 3> max{0, 0, 0};
  std::array<float, 3> center() const;
  float diagonal() const;
};
Bounds computeBounds(std::span<const float> positions);

// Area-weighted vertex normals: each triangle adds its (unnormalised) cross product, whose length
// is twice its area, to its three vertices; the sums are then normalised. A vertex touched only by
// degenerate triangles gets (0, 0, 0). Non-finite positions are not checked (they give non-finite
// normals, never a memory error).
//
// Per-frame contract (the rule of every vdg evaluation function, after ozz-animation's jobs):
// sizes, indices and values are checked on entry; on a violation the function returns false and
// has written nothing; it never throws and never allocates. Here a violation is
//   positions.size() not a multiple of 3, normals.size() != positions.size(),
//   triangles.size() not a multiple of 3, or a triangle index outside [0, #V).
// The index check is per call (this free function takes any arrays): one read pass over the
// #F x 3 indices before the first write, small next to the cross products that follow.
[[nodiscard]] bool computeVertexNormals(std::span<const float> positions, std::span<const std::int32_t> triangles,
                                        std::span<float> normals);

// Checks the mesh's own consistency (array sizes, indices in range, finite coordinates, finite
// normals and colours in [0, 1], texture sizes) and throws vdg::Error naming `what` (usually the
// file) and the first offending vertex, triangle, normal or material.
void validateMesh(const TriMesh& mesh, const std::string& what);

}  // namespace vdg
