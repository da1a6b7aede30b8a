// SurfaceTopology — a mesh's connectivity as a surface rather than as an index buffer.
//
// Meshes from modelling tools split vertices along seams: a vertex is duplicated wherever its
// texture coordinates or normals differ between faces (a glTF vertex carries one of each; OBJ
// patches such as the Utah teapot's are stitched only by position). In the index buffer every seam
// is then an open border, so anything that walks the surface (silhouette edges, geodesic and
// edge-count distances, smooth normals) would stop at it. SurfaceTopology welds vertices by
// position and keeps, beside the welded connectivity, what a renderer needs to keep hard edges:
//
//  - welding: vertices closer than `weld_tolerance` x (bounding-box diagonal) are one surface
//    point, represented by the lowest vertex index among them (weld()[v]); the welded triangles
//    index those representatives;
//  - edges of the welded surface with their one or two faces; an edge with one face is a true
//    open border (a hole), not a seam;
//  - smoothing groups: the triangle corners at one surface point whose file normals
//    (TriMesh::normals) agree within `hard_angle_deg` share one shading normal; corners whose
//    file normals differ meet at a hard edge. A mesh without file normals is smooth everywhere
//    (vertices split only for texture coordinates are not edges);
//  - render vertices: the distinct (smoothing group, texture coordinate) pairs, which is what a
//    GPU vertex must be, with triangles over them.
//
// Raw data (TriMesh) -> build() -> immutable SurfaceTopology -> allocation-free per-frame normals.
// Only the triangles, the file normals and the texture indices define it; positions are read at
// build time for welding alone, so a topology built on a base mesh serves every blend of it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "vdg/geom/tri_mesh.h"

namespace vdg {

struct SurfaceOptions {
  // Vertices at most this fraction of the bounding-box diagonal apart are one surface point.
  // Exporters write seam duplicates with identical coordinates; the tolerance only absorbs
  // round-off of text formats. 0 welds exactly coincident vertices only.
  double weld_tolerance = 1e-6;
  // Corners at one surface point whose file normals differ by more than this angle (degrees)
  // meet at a hard edge.
  double hard_angle_deg = 1.0;
};

class SurfaceTopology {
 public:
  // Throws vdg::Error (as validateMesh, naming "surface") for an inconsistent mesh, and for
  // options that are not finite or are negative.
  static SurfaceTopology build(const TriMesh& mesh, const SurfaceOptions& options = {});
  // The topology of a bare index buffer: nothing welded, one smooth group per vertex, no texture
  // coordinates (render vertices are the vertices). Throws vdg::Error for an index outside
  // [0, vertex_count) or a size that is not a multiple of 3.
  static SurfaceTopology unwelded(std::span<const std::int32_t> triangles, std::size_t vertex_count);

  std::size_t vertexCount() const { return weld_.size(); }
  std::size_t triangleCount() const { return triangles_.size() / 3; }
  std::span<const std::int32_t> triangles() const { return triangles_; }  // the mesh's, #F x 3

  // Welding.
  std::span<const std::int32_t> weld() const { return weld_; }                         // #V
  std::span<const std::int32_t> weldedTriangles() const { return welded_triangles_; }  // #F x 3
  std::size_t weldedVertexCount() const { return welded_count_; }                      // distinct surface points
  bool isWelded() const { return welded_count_ != weld_.size(); }                      // some vertices were merged

  // Edges of the welded surface: edge e joins welded vertices edgeVertices()[2e] < [2e + 1] and
  // borders faces edgeFaces()[2e] and [2e + 1] (-1 when the edge has a single face: an open
  // border). On a non-manifold edge (three or more faces) the first two faces are kept. Edges
  // whose two ends weld together (collapsed triangles) are left out.
  std::size_t edgeCount() const { return edge_vertices_.size() / 2; }
  std::span<const std::int32_t> edgeVertices() const { return edge_vertices_; }
  std::span<const std::int32_t> edgeFaces() const { return edge_faces_; }
  std::size_t borderEdgeCount() const { return border_edges_; }

  // Smoothing groups (corner level): cornerGroups()[3f + c] is the group of corner c of triangle f.
  std::size_t groupCount() const { return group_count_; }
  std::span<const std::int32_t> cornerGroups() const { return corner_groups_; }  // #F x 3
  // Vertex level, for APIs with one normal per vertex: vertexHome()[v] is the vertex whose normal
  // v shares: the lowest index welded to v whose first corner's file normal agrees with v's.
  // Where an OBJ vertex has different file normals on different corners (a hard edge without a
  // split vertex), one normal per vertex cannot keep the edge and the vertex is smooth; the
  // corner-level groups keep it.
  std::span<const std::int32_t> vertexHome() const { return vertex_home_; }  // #V
  // The vertices whose home is another vertex (vertexHome()[v] != v), ascending: seam duplicates.
  std::span<const std::int32_t> copiedVertices() const { return copied_vertices_; }

  // What the per-frame normals gather (compressed sparse rows, built once by build()): the
  // triangles whose area-weighted normal each normal slot sums, in ascending triangle order, a
  // triangle listed once per corner it has at that slot (so twice where two of its corners weld).
  //   homeTriangleOffsets():  #V + 1; home vertex h sums homeTriangles()[off[h] .. off[h + 1]),
  //                           a vertex that is not its own home has an empty range;
  //   groupTriangleOffsets(): #groups + 1, the same per smoothing group over groupTriangles().
  // Both triangle lists have one entry per corner (#F x 3), so the two cost
  // 4 x (#V + #groups + 2 + 6 #F) bytes: 56 MB for a 1M-vertex, 2M-triangle mesh, about as much as
  // its triangles and positions together (the price of normals without atomics or per-thread copies),
  // half of that where the two coincide (groupListsAreHomeLists() below).
  std::span<const std::int32_t> homeTriangleOffsets() const { return home_offsets_; }
  std::span<const std::int32_t> homeTriangles() const { return home_triangles_; }
  // Where the two lists coincide (a mesh without seams or hard edges: one group per vertex, in
  // vertex order), the group lists are the home lists, stored once (28 MB less for the mesh above).
  std::span<const std::int32_t> groupTriangleOffsets() const {
    return groups_are_homes_ ? home_offsets_ : group_offsets_;
  }
  std::span<const std::int32_t> groupTriangles() const {
    return groups_are_homes_ ? home_triangles_ : group_triangles_;
  }
  bool groupListsAreHomeLists() const { return groups_are_homes_; }

  // Render vertices: the distinct (group, texture coordinate) pairs of the corners.
  std::size_t renderVertexCount() const { return render_source_.size(); }
  std::span<const std::int32_t> renderSource() const { return render_source_; }        // #R: a vertex at it
  std::span<const std::int32_t> renderGroup() const { return render_group_; }          // #R
  std::span<const std::int32_t> renderUv() const { return render_uv_; }                // #R: uv index or -1
  std::span<const std::int32_t> renderTriangles() const { return render_triangles_; }  // #F x 3

 private:
  std::vector<std::int32_t> triangles_, weld_, welded_triangles_, edge_vertices_, edge_faces_, corner_groups_,
      vertex_home_, copied_vertices_, render_source_, render_group_, render_uv_, render_triangles_, home_offsets_,
      home_triangles_, group_offsets_, group_triangles_;
  void buildGatherLists();
  std::size_t welded_count_ = 0, border_edges_ = 0, group_count_ = 0;
  bool groups_are_homes_ = false;
};

// Per-frame normals on a topology; positions are #V x 3 (any pose of the mesh the topology was
// built on). Each slot (a smoothing group, or a home vertex) sums the area-weighted normals (the
// unnormalised cross products (b - a) x (c - a) of triangle (a, b, c)) of the triangles that have
// a corner there, in ascending triangle order, and the sum is normalised (a slot touched only by
// degenerate triangles, or by none, gets (0, 0, 0)). The slots are computed independently (a
// gather over the lists above, no atomics), in parallel with oneTBB (chunks of at least
// kParallelNormalSlots slots) from 2 x kParallelNormalSlots slots on, and inline on the calling
// thread below that; the result does not depend on the number of threads. The first threaded call
// starts TBB's worker threads. Uses at most 168 KB of the calling (or worker) thread's stack.
//
// Per-frame contract: sizes are checked on entry (positions.size() == 3 #V and the output's size
// below); on a violation the function returns false and has written nothing; no throw, no
// operator-new allocation (TBB's tasks come from its own pool).
//   computeGroupNormals:  group_normals #groups x 3 (the renderer gathers them per render vertex).
//   computeVertexNormals: normals #V x 3, each vertex the normal of vertexHome(): seams welded,
//                         hard edges between split vertices kept.
//   computeVertexNormalsOf: what computeVertexNormals writes, for the listed vertices only (any
//                         order; distinct, since the chunks of a list run side by side); other
//                         entries of `normals` are left as they are. For incremental updates
//                         (vdg::ModelEvaluator, whose lists are a key's few percent of the vertices),
//                         so threaded in chunks of at least kParallelListedNormals from twice that
//                         on. Also refuses a listed vertex outside [0, #V).
inline constexpr std::size_t kParallelNormalSlots = 16384;
inline constexpr std::size_t kParallelListedNormals = 2048;
[[nodiscard]] bool computeGroupNormals(const SurfaceTopology& topology, std::span<const float> positions,
                                       std::span<float> group_normals);
[[nodiscard]] bool computeVertexNormals(const SurfaceTopology& topology, std::span<const float> positions,
                                        std::span<float> normals);
[[nodiscard]] bool computeVertexNormalsOf(const SurfaceTopology& topology, std::span<const float> positions,
                                          std::span<const std::int32_t> vertices, std::span<float> normals);

}  // namespace vdg
