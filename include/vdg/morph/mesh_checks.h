// Checks that the shape-interpolation methods need of their meshes.
#pragma once
#include <string>
#include "vdg/geom/tri_mesh.h"

namespace vdg::morph {

// Closed and consistently oriented: every undirected edge is used by exactly two triangles, once
// in each direction. Throws vdg::Error "WHAT: is not closed: edge (I, J) ..." naming the first
// offending edge, or "WHAT: has no triangles". Degenerate triangles (a repeated index) are refused.
void requireClosed(const TriMesh& mesh, const std::string& what);
// V - E + F for a closed mesh (2 for a sphere-like mesh, 0 for a torus); per connected component
// summed. Call after requireClosed.
int eulerCharacteristic(const TriMesh& mesh);

}  // namespace vdg::morph
