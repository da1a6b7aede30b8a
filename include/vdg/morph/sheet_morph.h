// Parent's sheets (Parent 4.10, "Shape Interpolation, Metamorphosis"): "Parent breaks each object
// into two sheets (e.g., front and back) and makes the same number of points on boundary of sheets.
// Then, recursively, he finds an existing path of edges between two vertices of one sheet and
// establishes a path of edges between the two corresponding vertices of corresponding sheet. He
// breaks each sheet into two sheets and recurse until each sheet is a single face. Now each object
// has same topology and once again, vertex-to-vertex interpolation can be performed."
//
// Here (src/morph/sheet_morph.cpp tells the steps in full):
//  1. Each mesh is split into a front and a back sheet (two discs) along a cycle of its edges: the
//     front grows from the triangle farthest along +axis, triangle by triangle in the order of
//     their centres along the axis, keeping a disc, until it holds half the triangles.
//  2. Both cycles are given the same number of points: each gets a point on its edges at every
//     fraction of arc length where the other has a vertex (both start at their vertex farthest
//     along the axis after `axis`, and run with the front on their left).
//  3. B's two sheets are flattened onto the unit disc (Tutte's barycentric embedding, the cycle on
//     the circle by arc length). Then, for a pair of corresponding sheets: an existing path of A's
//     edges through the inside of A's sheet joins two boundary points i and j; the corresponding
//     path of B is established as the straight cut between B's points i and j in the flattening
//     (new vertices where it crosses B's edges), so that B's sheets stay convex there; both paths
//     get the same number of points (by arc length, as in 2), and both sheets are cut in two.
//  4. Until A's sheet is a single face: then B's sheet (a convex region) is laid onto that face
//     (its inner vertices by mean value coordinates). When B's sheet is a single face first, A's
//     sheet is laid onto it instead (Tutte's embedding with A's boundary on B's face). When no path
//     of A's edges ends at two points B's sheet can be cut between (both on one straight side of
//     it), A's sheet is flattened onto B's and both are cut along the same straight line.
// "A" here is the mesh with fewer triangles (its edges are followed, the other is cut); when the
// recursion cannot go on that way (a sheet of the cut mesh grown too thin to cut again), it is run
// the other way round. The result is one connectivity for A and B; every vertex of A and of B is
// one of its vertices, at its own position at t = 0 (A) and t = 1 (B); every other vertex lies on
// an edge or a face of the mesh of its end. Faces are triangulated by ears; a triangle may be flat
// at one end (three points on one edge of the other mesh).
#pragma once
#include <string>

#include "vdg/geom/tri_mesh.h"
#include "vdg/morph/vertex_morph.h"

namespace vdg::morph {

struct SheetMorphOptions {
  int axis = 2;  // the front sheet faces +axis, the back sheet -axis: 0 x, 1 y, 2 z
};

// Builder. The checks, in order, each a one-line vdg::Error naming `what_a` / `what_b`:
//   "sheet morph: axis must be 0, 1 or 2";
//   validateMesh and requireClosed (vdg/morph/mesh_checks.h);
//   "WHAT: is not one genus-0 surface (Euler characteristic X, N parts); the sheet morph needs a
//    mesh like a sphere";
//   "WHAT: vertex V is not a manifold vertex (its triangles make 2 fans or more); the sheet morph needs
//    one fan round every vertex";
//   "WHAT: its front|back sheet cannot be flattened: triangle F folds over" (the mesh that is
//    cut; very uneven meshes);
//   "sheet morph: the recursion does not come to an end (more than N splits; ...) (A and B, either
//    way round)", "sheet morph: a sheet pair of N and M faces with K boundary points cannot be cut
//    in two ..." and the like: the recursion failed both ways round (cuts so crowded that a sheet
//    is degenerate; e.g. two UV spheres whose poles lie on the front-back cycle); a limit of the
//    method as built here (docs/morph3d.md).
// The VertexMorph it returns gives the common mesh at t: positions (1 - t) pa + t pb, closed,
// genus 0, counter-clockwise seen from outside where A and B are; its at() refuses a t that is not
// finite with "sheet morph: t T is not a finite number".
VertexMorph sheetMorph(const TriMesh& a, const TriMesh& b, const SheetMorphOptions& options = {},
                       const std::string& what_a = "A", const std::string& what_b = "B");

// The work (operations, vdg/morph/budget.h) of sheetMorph, an estimate: the recursion visits every
// face of both meshes at each of about log2(triangles of A) + 1 levels, and the flattening solves
// a sparse system over B: (triangles of A + B) x (log2(triangles of A) + 2) x 64.
double sheetMorphCost(const TriMesh& a, const TriMesh& b);

}  // namespace vdg::morph
