// Silhouette and crease edges of a triangle mesh seen from an eye point (Rademacher 99, section
// 3.2.4, after Raskar and Cohen 99): an edge is on the silhouette when one of its two faces is
// front-facing and the other back-facing.
//
// The edges are those of the mesh's *surface* (SurfaceTopology, vdg/geom/surface.h): vertices
// duplicated along texture or normal seams are welded, so a seam is an ordinary edge with two
// faces and is drawn only where it really is on the silhouette. An edge with a single face is a
// true open border (a hole); drawing it is the caller's choice (the paper's wireframe pass would).
//
// The topology is built once per mesh; the per-frame queries read positions and write into
// caller-owned buffers. They never throw, and they allocate nothing once `out` has the capacity
// of 2 x edgeCount() indices (reserve it at set-up). Sizes are the caller's: `front` holds #F
// entries, `positions` #V x 3 floats of the mesh the topology was built on.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include <Eigen/Core>

#include "vdg/geom/surface.h"

namespace vdg::render {

// Facing of each triangle for an eye point (model space; for a parallel camera pass a point far
// along the view axis): front when (eye - v0) . ((v1 - v0) x (v2 - v0)) > 0.
// `front` must hold #F entries.
void faceFacing(std::span<const float> positions, std::span<const std::int32_t> triangles, const Eigen::Vector3f& eye,
                std::span<std::uint8_t> front);

// Writes the two vertex indices (welded representatives, SurfaceTopology::edgeVertices) of every
// silhouette edge to `out` (cleared first): edges whose two faces differ in facing, and, when
// `borders` is true, every open-border edge (one face), whatever its facing.
void silhouetteEdges(const SurfaceTopology& topology, std::span<const std::uint8_t> front, bool borders,
                     std::vector<std::uint32_t>& out);

// Writes the two vertex indices of every crease edge to `out` (cleared first): edges with two
// faces, both front-facing, whose face normals (from `positions`) make an angle above
// `crease_angle_deg` degrees, i.e. a dihedral angle below 180 - crease_angle_deg. A
// crease_angle_deg <= 0 or not finite finds none (out empty); an edge next to a degenerate face
// (no normal) is never a crease. Silhouette and border edges are never creases, so the crease and
// silhouette lists together hold at most 2 x edgeCount() indices.
void creaseEdges(const SurfaceTopology& topology, std::span<const float> positions, std::span<const std::uint8_t> front,
                 double crease_angle_deg, std::vector<std::uint32_t>& out);

}  // namespace vdg::render
