// Chen's slices (Parent 4.10, "Shape Interpolation, Metamorphosis"): "Chen cut object into slices
// and uses center point of overlapping corresponding slices to equal up points on both slices. He
// linearly interpolates between pairs of points, one from each slice and then lofts a new surface
// from the slices."
//
// Here: each mesh is cut by `slices` planes perpendicular to `axis`, at the same fractions of its
// own extent along the axis ((i + 1/2) / slices); each cut must be one closed contour. The
// corresponding contours of A and B are overlaid at their area centroids (the common centre) and
// both are resampled by `samples` rays from it at equal angles (the farthest crossing of each ray),
// so both have the same points. The lofted surface joins neighbouring slices by quads (two
// triangles) and closes the ends with fans to the mesh's lowest and highest vertex along the axis.
// Vertex to vertex interpolation then gives the inbetweens. At t = 0 the mesh is a resampling of A
// (every vertex lies on A; A's own vertices are not kept), at t = 1 of B.
#pragma once
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "vdg/geom/tri_mesh.h"
#include "vdg/morph/vertex_morph.h"

namespace vdg::morph {

struct SliceMorphOptions {
  int axis = 1;      // the slicing axis: 0 x, 1 y, 2 z
  int slices = 32;   // cutting planes, >= 1
  int samples = 64;  // points per contour, >= 3
};

// Builder: checks both meshes closed and the options in range, cuts and resamples. Throws
// vdg::Error: requireClosed's message; "slice morph: axis must be 0, 1 or 2" (and likewise for
// slices and samples); "WHAT: the cut at AXIS = L is N contours; the slice morph needs one closed
// contour per cut"; "WHAT: the cut at AXIS = L is not star-shaped about its centroid (x, y, z): the
// contour's edge from P to Q faces away from it" (or "is seen edge-on from it"; then "... (rays from
// the centroid would miss part of the contour)"), or "...: the contour goes round it N times".
// Star-shaped is tested exactly for every contour: the centroid must lie strictly on the inner
// side of every edge of the contour (an exact orientation test), so that each ray from it crosses
// the contour once and no part of the contour (the walls of a notch) is hidden from the rays.
// The VertexMorph it returns gives the lofted mesh at t: positions (1 - t) pa + t pb, slices *
// samples + 2 vertices, closed, genus 0, counter-clockwise seen from outside; its at() refuses a t
// that is not finite with "slice morph: t T is not a finite number".
// The work (operations, vdg/morph/budget.h) of sliceMorph: every cut tests every triangle of its
// mesh, and every contour is resampled: slices x (triangles of A + B + 2 samples).
double sliceMorphCost(const TriMesh& a, const TriMesh& b, const SliceMorphOptions& options = {});
VertexMorph sliceMorph(const TriMesh& a, const TriMesh& b, const SliceMorphOptions& options = {},
                       const std::string& what_a = "A", const std::string& what_b = "B");

}  // namespace vdg::morph
