// Chen's slice interpolation (Parent 4.10, "Shape Interpolation, Metamorphosis": "Chen cut object
// into slices and uses center point of overlapping corresponding slices to equal up points on both
// slices. He linearly interpolates between pairs of points, one from each slice and then lofts a
// new surface from the slices.").
//
// Each mesh is cut by `slices` planes across `axis`, at the same fractions of its own extent along
// the axis ((k + 0.5) / slices, k = 0 .. slices - 1), so slice k of A corresponds to slice k of B.
// Each cross-section (the polygon the plane cuts from the closed mesh) gets its centre (the area
// centroid); `samples` rays leave the centre at the angles 2 pi j / samples, measured the same way
// on both slices (the slices overlapped at their centres), and each ray's crossing with the
// cross-section is the j-th point of the slice: A and B now have equal points, pairwise
// corresponding. The inbetween at t interpolates each pair, (1 - t) pA + t pB, and lofts a surface
// through the interpolated slices: quads between consecutive slices, closed by one apex at each
// end (at the first and last slice's centre, on the mesh's extremes along the axis).
//
// Every cross-section must be one polygon that is star-shaped about its centre (each ray crosses
// it exactly once); a mesh whose slice splits in two, has a hole around the centre, or folds back
// is refused with vdg::Error naming the mesh, the slice and the ray.
#pragma once
#include <array>
#include <string>
#include <vector>

#include "vdg/geom/tri_mesh.h"

namespace vdg::morph {

struct SliceMorphOptions {
  int slices = 32;   // cross-sections per mesh, >= 2
  int samples = 64;  // points per cross-section (rays from its centre), >= 3
  int axis = 1;      // the slicing direction: 0 x, 1 y (up), 2 z
};

// A slice set of one mesh: slices x samples points, slice-major, plus the two apexes. The same
// layout for A and B, so they interpolate point by point.
struct SliceSamples {
  std::vector<double> points;             // slices * samples * 3
  std::array<double, 3> bottom{}, top{};  // the apexes
};

// Cuts and samples one mesh (closed: requireClosed, named `what`). Throws vdg::Error.
SliceSamples sampleSlices(const TriMesh& mesh, const SliceMorphOptions& options, const std::string& what = "mesh");

// The lofted mesh through (1 - t) sa + t sb (both from sampleSlices with the same options): closed,
// genus 0, wound outward, slices * samples + 2 vertices. t finite in [0, 1].
TriMesh loftSlices(const SliceSamples& sa, const SliceSamples& sb, double t, const SliceMorphOptions& options);

// sampleSlices of both, then loftSlices. At t = 0 and t = 1 the result is A and B as their slices
// sample them (not the input meshes: a morph sequence stays continuous at its ends). Throws
// vdg::Error for open meshes, slices that are not star-shaped, bad options or t.
TriMesh sliceMorph(const TriMesh& a, const TriMesh& b, double t, const SliceMorphOptions& options = {},
                   const std::string& what_a = "A", const std::string& what_b = "B");

}  // namespace vdg::morph
