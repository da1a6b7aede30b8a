// Triangle pairs of a mesh that pass through each other (vdg info --check-intersections, the
// studio's warning after a stroke; docs/where-to-key.md).
//
// The pair test is Moller's interval test (T. Moller, "A Fast Triangle-Triangle Intersection
// Test", Journal of Graphics Tools 2(2), 1997): each triangle's vertices' signed distances to the
// other's plane, then the two triangles' intervals on the planes' common line, overlapping. A
// distance within `tolerance` of the plane counts as on it (Moller's EPSILON, here a length). A
// triangle that only touches the other's plane (no vertex strictly on each side: a corner or an
// edge resting on it) does not count, nor do intervals that overlap by no more than the tolerance,
// so a sheet resting on another is not reported. Coplanar pairs (every distance within the
// tolerance) are tested in their plane: edges that properly cross, or a corner strictly inside
// the other triangle.
//
// Pairs that share a vertex are never tested (adjacent triangles always touch). Vertices are
// shared by position, not only by index: `weld` maps every vertex to one representative of its
// position (weldByPosition()), so the two sides of a texture seam count as one vertex.
// Degenerate triangles (area below tolerance^2) are skipped.
//
// Broad phase: a uniform grid of cubic cells (side about twice the mean longest side of the
// triangles' boxes, at most kMaxGridCellsPerTriangle cells per triangle over the mesh's box);
// each triangle is listed in the cells its box overlaps and each pair is tested once, in the
// first cell the two boxes share. Threaded over cells (vdg/geom/parallel.h).
#pragma once

#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include <Eigen/Core>

namespace vdg {

// A length relative to a mesh's size (its bounding-box diagonal) that is "on the plane".
inline constexpr double kIntersectionRelativeTolerance = 1e-6;
inline constexpr double kMaxGridCellsPerTriangle = 8.0;

// True when triangles (a0, a1, a2) and (b0, b1, b2) intersect by more than `tolerance` (a length
// >= 0; see above). Symmetric in the two triangles.
bool trianglesIntersect(const Eigen::Vector3d& a0, const Eigen::Vector3d& a1, const Eigen::Vector3d& a2,
                        const Eigen::Vector3d& b0, const Eigen::Vector3d& b1, const Eigen::Vector3d& b2,
                        double tolerance);

// weld[v]: the smallest index of a vertex with exactly v's position (#V entries).
std::vector<std::int32_t> weldByPosition(std::span<const float> positions);

// Every intersecting pair (i, j), i < j, of the triangles (#F x 3 indices into positions, #V x 3),
// sorted. `weld`: as weldByPosition() (#V entries; empty: vertices are shared by index only).
// tolerance < 0 means kIntersectionRelativeTolerance times the positions' bounding-box diagonal.
// Indices are trusted (the caller's mesh was validated).
std::vector<std::pair<std::int32_t, std::int32_t>> selfIntersections(std::span<const float> positions,
                                                                     std::span<const std::int32_t> triangles,
                                                                     std::span<const std::int32_t> weld,
                                                                     double tolerance = -1.0);

}  // namespace vdg
