// 3D shape interpolation (Parent 4.10, "Shape Interpolation, Metamorphosis"): from a source mesh A
// at t = 0 to a destination mesh B at t = 1, by three of the methods the text describes.
//   DistanceMorph   signed distance volumes of A and B blended with t, the zero level set
//                   polygonised (OpenVDB); the topology may change on the way.
//   sphericalMorph  Kent: both star-shaped genus-0 meshes projected onto a sphere about their
//                   centres, their edges overlaid (arcs intersected) into one common connectivity,
//                   then vertex-to-vertex interpolation.
//   minkowskiMorph  sizes interpolated through the Minkowski sum (1 - t) A + t B (CGAL).
// Every mesh given must be closed (see vdg/morph/mesh_checks.h). Meshes are in their own units;
// nothing is normalised.
#pragma once
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>
#include "vdg/geom/tri_mesh.h"
#include "vdg/morph/vertex_morph.h"

namespace vdg::morph {

struct DistanceMorphOptions {
  double voxel_size = 0;  // world units; 0: the larger bounding-box diagonal of A and B / 96
  // The narrow band kept each side of the surfaces, in voxels (>= 3).
  double band_voxels = 3;
  // Refused before anything is allocated when the voxel count of the box holding both meshes
  // (plus the band) would exceed this: "... needs N voxels (about M MiB); use a --voxel of at
  // least S".
  std::size_t max_voxels = std::size_t{1} << 28;
};

// Builder: checks both meshes closed, makes both signed distance volumes once (throws vdg::Error
// naming "A"/"B" via the `what` strings for open meshes and too many voxels).
class DistanceMorph {
 public:
  DistanceMorph(const TriMesh& a, const TriMesh& b, const DistanceMorphOptions& options,
                const std::string& what_a = "A", const std::string& what_b = "B");
  ~DistanceMorph();
  DistanceMorph(DistanceMorph&&) noexcept;
  DistanceMorph& operator=(DistanceMorph&&) noexcept;
  // The zero level set of (1 - t) dA + t dB, polygonised (triangles; closed). t in [0, 1].
  TriMesh at(double t) const;
  double voxelSize() const;
  std::size_t activeVoxelCount() const;  // of both volumes together (for the benchmark)
  std::size_t memoryBytes() const;       // of both volumes together

 private:
  struct Volumes;
  std::unique_ptr<Volumes> volumes_;
};

// Builder: checks both meshes closed, genus 0 and star-shaped about their centres (the bounding-box
// centre; every ray from it crosses the surface once), and builds the common connectivity (throws
// vdg::Error naming the mesh and the first face that fails).
//
// The checks, in order, each a one-line vdg::Error naming `what_a` / `what_b`:
//   validateMesh and requireClosed (vdg/morph/mesh_checks.h);
//   "WHAT: is not a single genus-0 surface (Euler characteristic X, ...)";
//   "WHAT: is not star-shaped about its centre (x, y, z): triangle F faces the centre or is seen
//    edge-on from it" (the first triangle whose signed volume with the centre is not positive);
//   "WHAT: is not star-shaped about its centre (x, y, z): seen from it, its triangles cover the
//    sphere N times (triangles F and G overlap)".
// The centre is the bounding-box centre of the vertices the triangles use (each mesh its own).
//
// The common connectivity (Kent's overlay): both meshes' vertices are projected onto the unit
// sphere about their centres; every face of the overlay of the two spherical triangulations is the
// intersection of one spherical triangle of A with one of B (a convex spherical polygon, fan-
// triangulated). Its vertices are A's vertices, B's vertices (a B vertex in the same direction as
// an A vertex is that A vertex) and the crossings of A's edges with B's edges. The combinatorics
// use exact orientation predicates on the directions (double precision, exact fallback), so
// coincident vertices, vertices on edges and overlapping edges give a closed manifold mesh with
// no tolerance; a vertex is placed on A by casting the ray from A's centre onto the triangle (or
// edge) of A it lies in, on B likewise. Unused vertices of A and B are left out.
//
// Builds the common mesh; the VertexMorph it returns poses it at any t: exact A at t = 0 and B at
// t = 1 as surfaces (every original vertex of each is a vertex of the common mesh, with its
// position unchanged; every other vertex lies on a triangle or edge of the mesh). Its at() refuses
// a t that is not finite with "spherical morph: t T is not a finite number".
VertexMorph sphericalMorph(const TriMesh& a, const TriMesh& b, const std::string& what_a = "A",
                           const std::string& what_b = "B");

// The Minkowski-sum inbetween (1 - t) A + t B, each scaled about its own centre (the bounding-box
// centre) and the result centred at (1 - t) cA + t cB. A and B closed; t = 0 gives A, t = 1 gives
// B exactly. Non-convex meshes work (CGAL Nef polyhedra) but are slow. Throws vdg::Error.
// Contract (checked first, in this order): A closed, B closed (requireClosed, named what_a and
// what_b), finite coordinates, t finite in [0, 1]; then, for 0 < t < 1, each mesh must enclose a
// volume, and on the Nef path be a 2-manifold without self-intersections (vdg::Error naming it).
// The result is a closed triangle mesh wound outward, positions only (no uvs, normals, materials).
TriMesh minkowskiMorph(const TriMesh& a, const TriMesh& b, double t, const std::string& what_a = "A",
                       const std::string& what_b = "B");

// How minkowskiMorph computes the sum (src/morph/minkowski_morph.cpp explains both paths).
enum class MinkowskiPath {
  automatic,    // the convex-hull path when both meshes are convex (isConvexMesh), else the Nef path
  convex_hull,  // the hull of the pairwise vertex sums; a non-convex mesh is refused (vdg::Error)
  nef,          // CGAL::minkowski_sum_3 on exact Nef polyhedra, whatever the meshes
};
struct MinkowskiOptions {
  MinkowskiPath path = MinkowskiPath::automatic;
  // A vertex may stand this far in front of a triangle's plane, as a fraction of the mesh's
  // bounding-box diagonal, and the mesh still counts as convex (float meshes are rarely exactly so).
  double convex_tolerance = 1e-6;
};
// As above, with the path chosen by `options` (convex_tolerance finite and >= 0, else vdg::Error).
TriMesh minkowskiMorph(const TriMesh& a, const TriMesh& b, double t, const MinkowskiOptions& options,
                       const std::string& what_a = "A", const std::string& what_b = "B");
// ---- Cost estimates (operations, vdg/morph/budget.h; in double, never overflowing) ------------
// Edges of a closed mesh where it folds inwards (reflex: the neighbouring triangle's far corner
// stands in front of the triangle's plane, outward taken by the sign of the enclosed volume).
// Linear (a sort of the edges). CGAL's Nef path cuts a mesh into about that many convex pieces + 1.
std::size_t reflexEdgeCount(const TriMesh& mesh);
// Operations per convex piece pair and triangle on the Nef path (calibrated on the timings in
// minkowski_morph.cpp: a 256-triangle torus + a box, 47 s, estimated 2.6e9 operations).
inline constexpr double kNefOperationsPerPieceTriangle = 5e4;
// Operations per pairwise vertex sum hulled on the convex path (two 500-vertex spheres, 1.1 s).
inline constexpr double kHullOperationsPerSum = 25;
// The work of one minkowskiMorph(a, b, t, options) with 0 < t < 1 (t = 0 and 1 are copies): the
// convexity test of the automatic path (V x F per mesh), then either the convex hull of the
// Va x Vb sums (kHullOperationsPerSum x Va Vb log2(Va Vb)) or, when a mesh is not convex (or the
// path says nef), the Nef sum, kNefOperationsPerPieceTriangle x (reflex edges of A + 1) x (reflex
// edges of B + 1) x (triangles of A + B): the cost that makes a non-convex sum take minutes.
double minkowskiMorphCost(const TriMesh& a, const TriMesh& b, const MinkowskiOptions& options = {});
// The work of one DistanceMorph::at(t): the blend and the polygoniser visit every active voxel of
// both volumes, twice each.
double distanceMorphFrameCost(const DistanceMorph& morph);

// True when no vertex of `mesh` stands more than relative_tolerance * (bounding-box diagonal) in
// front of the plane of any of its non-degenerate triangles, taking the triangles outward by the
// sign of the enclosed volume. O(V * F). The mesh should be closed (requireClosed).
bool isConvexMesh(const TriMesh& mesh, double relative_tolerance = 1e-6);

}  // namespace vdg::morph
