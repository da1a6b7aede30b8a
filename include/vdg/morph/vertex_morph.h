// The runtime of the 3D shape morphs that first give A and B one common connectivity, then
// interpolate vertex to vertex (Parent 4.10): Kent's spherical overlay (sphericalMorph, shape_morph.h),
// Chen's slices (sliceMorph, slice_morph.h) and Parent's sheets (sheetMorph, sheet_morph.h) build one.
// Immutable once built; the per-frame evaluate() neither throws nor allocates.
#pragma once
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "vdg/geom/tri_mesh.h"

namespace vdg::morph {

class VertexMorph {
 public:
  // The common vertices placed on A (t = 0) and on B (t = 1), #V x 3 each, and the common
  // triangles (#F x 3 indices into them). `name` starts the message of at()'s refusal ("spherical
  // morph"). Throws vdg::Error when the two placements differ in size, a size is not a multiple
  // of 3, or an index is out of range.
  VertexMorph(std::vector<float> on_a, std::vector<float> on_b, std::vector<std::int32_t> triangles, std::string name);
  // The common connectivity posed at t: vertex positions (1 - t) pa + t pb (t outside [0, 1]
  // extrapolates). Positions and triangles only (no texture coordinates, normals or materials).
  // Throws vdg::Error "NAME: t T is not a finite number" when t is not finite.
  TriMesh at(double t) const;
  // Per-frame, allocation-free: writes vertexCount() * 3 floats. False (nothing written) when
  // `positions` has the wrong size or t is not finite.
  [[nodiscard]] bool evaluate(double t, std::span<float> positions) const;
  std::size_t vertexCount() const { return pos_a_.size() / 3; }
  std::span<const std::int32_t> triangles() const { return triangles_; }
  std::span<const float> positionsOnA() const { return pos_a_; }
  std::span<const float> positionsOnB() const { return pos_b_; }

 private:
  std::vector<float> pos_a_, pos_b_;
  std::vector<std::int32_t> triangles_;
  std::string name_;
};

}  // namespace vdg::morph
