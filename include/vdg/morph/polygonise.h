// Polygonising implicit surfaces (Parent 4.11): the fields of vdg/morph/implicit.h sampled on a
// grid and meshed with OpenVDB. Part of vdg::morph3d (OpenVDB); the fields, their files and the
// grid's size (vdg/morph/implicit.h) are vdg::morph's and need none of it.
#pragma once

#include <cstddef>
#include <string>

#include "vdg/geom/tri_mesh.h"
#include "vdg/morph/implicit.h"

namespace vdg::morph {

struct PolygoniseOptions {
  // Voxel edge length, world units; 0: defaultVoxelSize(model.bounds()).
  double voxel_size = 0;
  // Refused before anything is allocated when the grid would hold more voxels than this:
  // "WHAT: the grid needs N voxels (about M MiB) at voxel size H; use a --voxel of at least S".
  std::size_t max_voxels = std::size_t{1} << 27;
};

// The work (operations, vdg/morph/budget.h) of polygonise(model, {voxel_size}): every grid point
// sampled and meshed (2 per voxel), every primitive's support box tested on every grid row, and
// every primitive evaluated at every voxel of its support box, so thousands of primitives over one
// spot cost thousands of times the grid. In double: +infinity for a voxel size that is not > 0
// and finite (0: the default, as polygonise).
double polygoniseCost(const BlobModel& model, double voxel_size);

// Samples F over a grid of the model's bounds (padded by kGridPadding voxels) and extracts the
// iso-surface F = T with OpenVDB's volumeToMesh (quads split along their shorter diagonal).
// The result is closed and consistently oriented with outward normals (counter-clockwise seen from
// outside, where F < T); vertices lie on the sampled surface (trilinear within a voxel, so within
// one voxel of the true surface). Each Blinn primitive is sampled within its cut-off only.
// An empty mesh when F reaches T nowhere on the grid (every primitive off or too weak). Throws
// vdg::Error prefixed with `what`: too many voxels (checked before anything is allocated), a
// voxel size not finite or < 0.
TriMesh polygonise(const BlobModel& model, const PolygoniseOptions& options = {}, const std::string& what = "blobs");

}  // namespace vdg::morph
