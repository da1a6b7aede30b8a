// SurfaceTopology: welding by position, welded edges, smoothing groups from the file's normals,
// render vertices. See surface.h.
#include "vdg/geom/surface.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <numeric>
#include <string>
#include <unordered_map>
#include <utility>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "vdg/geom/error.h"
#include "vdg/geom/parallel.h"

namespace vdg {
namespace {

// Lowest-index representative of every vertex within `tol` of it (Euclidean). Vertices are
// visited in index order; each looks for an earlier representative in the 27 grid cells around it
// (cell side >= tol), so the result does not depend on hashing order.
std::vector<std::int32_t> weldVertices(std::span<const float> positions, double tol) {
  const std::size_t n = positions.size() / 3;
  std::vector<std::int32_t> weld(n);
  const double cell = tol > 0.0 ? tol : 1.0;
  auto cellOf = [&](std::size_t v, int axis) {
    return static_cast<std::int64_t>(std::floor(static_cast<double>(positions[v * 3 + axis]) / cell));
  };
  auto key = [](std::int64_t x, std::int64_t y, std::int64_t z) {
    // A mix of the three cell indices; collisions only cost extra distance checks.
    std::uint64_t h = static_cast<std::uint64_t>(x) * 0x9E3779B97F4A7C15ull;
    h ^= static_cast<std::uint64_t>(y) * 0xC2B2AE3D27D4EB4Full + (h << 6) + (h >> 2);
    h ^= static_cast<std::uint64_t>(z) * 0x165667B19E3779F9ull + (h << 6) + (h >> 2);
    return h;
  };
  std::unordered_multimap<std::uint64_t, std::int32_t> grid;
  grid.reserve(n);
  const double tol2 = tol * tol;
  for (std::size_t v = 0; v < n; ++v) {
    const std::int64_t cx = cellOf(v, 0), cy = cellOf(v, 1), cz = cellOf(v, 2);
    std::int32_t found = -1;
    const int reach = tol > 0.0 ? 1 : 0;
    for (int dx = -reach; dx <= reach; ++dx)
      for (int dy = -reach; dy <= reach; ++dy)
        for (int dz = -reach; dz <= reach; ++dz) {
          const auto range = grid.equal_range(key(cx + dx, cy + dy, cz + dz));
          for (auto it = range.first; it != range.second; ++it) {
            const auto r = static_cast<std::size_t>(it->second);
            double d2 = 0.0;
            for (int a = 0; a < 3; ++a) {
              const double d = static_cast<double>(positions[v * 3 + a]) - positions[r * 3 + a];
              d2 += d * d;
            }
            if (d2 <= tol2 && (found < 0 || it->second < found)) found = it->second;
          }
        }
    if (found >= 0) {
      weld[v] = found;
    } else {
      weld[v] = static_cast<std::int32_t>(v);
      grid.emplace(key(cx, cy, cz), static_cast<std::int32_t>(v));
    }
  }
  return weld;
}

// Union-find over small index ranges.
std::int32_t findRoot(std::vector<std::int32_t>& parent, std::int32_t i) {
  while (parent[static_cast<std::size_t>(i)] != i) {
    parent[static_cast<std::size_t>(i)] = parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(i)])];
    i = parent[static_cast<std::size_t>(i)];
  }
  return i;
}

// The edges of the welded surface (welded triangles #F x 3): each edge's two welded vertices
// (lower first) and its first two faces (-1 for a border edge, which is counted), in order of the
// vertex pair.
void weldedEdges(const std::vector<std::int32_t>& welded, std::vector<std::int32_t>& edge_vertices,
                 std::vector<std::int32_t>& edge_faces, std::size_t& border_edges) {
  struct HalfEdge {
    std::uint64_t key;
    std::int32_t face;
  };
  std::vector<HalfEdge> half;
  half.reserve(welded.size());
  for (std::size_t f = 0; f < welded.size() / 3; ++f)
    for (int c = 0; c < 3; ++c) {
      auto a = static_cast<std::uint32_t>(welded[f * 3 + static_cast<std::size_t>(c)]);
      auto b = static_cast<std::uint32_t>(welded[f * 3 + static_cast<std::size_t>((c + 1) % 3)]);
      if (a == b) continue;
      if (a > b) std::swap(a, b);
      half.push_back({(std::uint64_t{a} << 32) | b, static_cast<std::int32_t>(f)});
    }
  std::sort(half.begin(), half.end(),
            [](const HalfEdge& x, const HalfEdge& y) { return x.key != y.key ? x.key < y.key : x.face < y.face; });
  for (std::size_t i = 0; i < half.size();) {
    std::size_t j = i + 1;
    while (j < half.size() && half[j].key == half[i].key) ++j;
    edge_vertices.push_back(static_cast<std::int32_t>(half[i].key >> 32));
    edge_vertices.push_back(static_cast<std::int32_t>(half[i].key & 0xffffffffu));
    edge_faces.push_back(half[i].face);
    edge_faces.push_back(j - i >= 2 ? half[i + 1].face : -1);
    if (j - i == 1) ++border_edges;
    i = j;
  }
}

void checkOptions(const SurfaceOptions& options) {
  if (!std::isfinite(options.weld_tolerance) || options.weld_tolerance < 0.0)
    throw Error("surface: weld tolerance must be a finite number >= 0");
  if (!std::isfinite(options.hard_angle_deg) || options.hard_angle_deg < 0.0 || options.hard_angle_deg > 180.0)
    throw Error("surface: hard-edge angle must be in [0, 180] degrees");
}

}  // namespace

SurfaceTopology SurfaceTopology::build(const TriMesh& mesh, const SurfaceOptions& options) {
  validateMesh(mesh, "surface");
  checkOptions(options);
  SurfaceTopology t;
  const std::size_t nv = mesh.vertexCount();
  const std::size_t corners = mesh.triangles.size();
  t.triangles_ = mesh.triangles;
  t.weld_ = weldVertices(mesh.positions,
                         options.weld_tolerance * static_cast<double>(computeBounds(mesh.positions).diagonal()));
  t.welded_count_ = 0;
  for (std::size_t v = 0; v < nv; ++v)
    if (t.weld_[v] == static_cast<std::int32_t>(v)) ++t.welded_count_;
  t.welded_triangles_.resize(corners);
  for (std::size_t c = 0; c < corners; ++c)
    t.welded_triangles_[c] = t.weld_[static_cast<std::size_t>(mesh.triangles[c])];

  // Smoothing groups: the corners at one welded vertex, joined when their file normals agree.
  const bool with_normals = !mesh.normal_triangles.empty();
  const double cos_hard = std::cos(options.hard_angle_deg * std::numbers::pi / 180.0);
  auto normalOf = [&](std::size_t corner) {
    const auto n = static_cast<std::size_t>(mesh.normal_triangles[corner]) * 3;
    return std::array<double, 3>{mesh.normals[n], mesh.normals[n + 1], mesh.normals[n + 2]};
  };
  auto agree = [&](std::size_t a, std::size_t b) {
    if (!with_normals || mesh.normal_triangles[a] == mesh.normal_triangles[b]) return true;
    const auto na = normalOf(a), nb = normalOf(b);
    const double la = std::sqrt(na[0] * na[0] + na[1] * na[1] + na[2] * na[2]);
    const double lb = std::sqrt(nb[0] * nb[0] + nb[1] * nb[1] + nb[2] * nb[2]);
    if (la == 0.0 || lb == 0.0) return la == lb;  // a zero normal agrees only with another one
    return (na[0] * nb[0] + na[1] * nb[1] + na[2] * nb[2]) / (la * lb) >= cos_hard;
  };
  std::vector<std::int32_t> order(corners);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](std::int32_t a, std::int32_t b) {
    return t.welded_triangles_[static_cast<std::size_t>(a)] < t.welded_triangles_[static_cast<std::size_t>(b)];
  });
  t.corner_groups_.assign(corners, -1);
  std::vector<std::int32_t> parent;
  for (std::size_t i = 0; i < corners;) {
    std::size_t j = i;
    while (j < corners && t.welded_triangles_[static_cast<std::size_t>(order[j])] ==
                              t.welded_triangles_[static_cast<std::size_t>(order[i])])
      ++j;
    // Corners order[i..j) meet at one surface point.
    const std::size_t k = j - i;
    parent.resize(k);
    std::iota(parent.begin(), parent.end(), 0);
    if (with_normals) {
      for (std::size_t a = 0; a < k; ++a)
        for (std::size_t b = a + 1; b < k; ++b)
          if (agree(static_cast<std::size_t>(order[i + a]), static_cast<std::size_t>(order[i + b]))) {
            const std::int32_t ra = findRoot(parent, static_cast<std::int32_t>(a));
            const std::int32_t rb = findRoot(parent, static_cast<std::int32_t>(b));
            if (ra != rb) parent[static_cast<std::size_t>(std::max(ra, rb))] = std::min(ra, rb);
          }
    } else {
      std::fill(parent.begin(), parent.end(), 0);
    }
    // Groups numbered in order of their first corner (order[] keeps corner order within a point).
    for (std::size_t a = 0; a < k; ++a) {
      const auto root = static_cast<std::size_t>(findRoot(parent, static_cast<std::int32_t>(a)));
      const auto corner = static_cast<std::size_t>(order[i + a]);
      if (root == a) {
        t.corner_groups_[corner] = static_cast<std::int32_t>(t.group_count_++);
      } else {
        t.corner_groups_[corner] = t.corner_groups_[static_cast<std::size_t>(order[i + root])];
      }
    }
    i = j;
  }

  // Vertex level: welded vertices whose first corners' normals agree share the lowest one's normal.
  std::vector<std::int32_t> first_corner(nv, -1);
  for (std::size_t c = corners; c-- > 0;)
    first_corner[static_cast<std::size_t>(mesh.triangles[c])] = static_cast<std::int32_t>(c);
  t.vertex_home_.resize(nv);
  {
    std::unordered_map<std::int32_t, std::vector<std::int32_t>> homes;  // welded vertex -> homes so far
    for (std::size_t v = 0; v < nv; ++v) {
      t.vertex_home_[v] = static_cast<std::int32_t>(v);
      if (first_corner[v] < 0 || t.weld_[v] == static_cast<std::int32_t>(v)) {
        homes[t.weld_[v]].push_back(static_cast<std::int32_t>(v));
        continue;
      }
      auto& candidates = homes[t.weld_[v]];
      for (const std::int32_t h : candidates) {
        if (first_corner[static_cast<std::size_t>(h)] >= 0 &&
            agree(static_cast<std::size_t>(first_corner[static_cast<std::size_t>(h)]),
                  static_cast<std::size_t>(first_corner[v]))) {
          t.vertex_home_[v] = h;
          break;
        }
      }
      if (t.vertex_home_[v] == static_cast<std::int32_t>(v)) candidates.push_back(static_cast<std::int32_t>(v));
    }
  }

  weldedEdges(t.welded_triangles_, t.edge_vertices_, t.edge_faces_, t.border_edges_);

  // Render vertices: distinct (group, uv) pairs, numbered in order of first use.
  const bool with_uvs = !mesh.uv_triangles.empty();
  std::unordered_map<std::uint64_t, std::int32_t> render_index;
  render_index.reserve(corners);
  t.render_triangles_.resize(corners);
  for (std::size_t c = 0; c < corners; ++c) {
    const std::int32_t g = t.corner_groups_[c];
    const std::int32_t uv = with_uvs ? mesh.uv_triangles[c] : -1;
    const std::uint64_t k = (std::uint64_t{static_cast<std::uint32_t>(g)} << 32) | static_cast<std::uint32_t>(uv);
    const auto [it, inserted] = render_index.emplace(k, static_cast<std::int32_t>(t.render_source_.size()));
    if (inserted) {
      t.render_source_.push_back(mesh.triangles[c]);
      t.render_group_.push_back(g);
      t.render_uv_.push_back(uv);
    }
    t.render_triangles_[c] = it->second;
  }
  t.buildGatherLists();
  return t;
}

// Counting sort of the corners by slot; corners are visited in ascending order, so each slot's
// triangles come out ascending (the order the scatter used to add them in).
void SurfaceTopology::buildGatherLists() {
  const std::size_t nv = weld_.size(), corners = triangles_.size();
  copied_vertices_.clear();
  for (std::size_t v = 0; v < nv; ++v)
    if (vertex_home_[v] != static_cast<std::int32_t>(v)) copied_vertices_.push_back(static_cast<std::int32_t>(v));
  const auto fill = [&](std::size_t slots, auto slot_of, std::vector<std::int32_t>& offsets,
                        std::vector<std::int32_t>& entries) {
    offsets.assign(slots + 1, 0);
    for (std::size_t c = 0; c < corners; ++c) ++offsets[slot_of(c) + 1];
    for (std::size_t s = 0; s < slots; ++s) offsets[s + 1] += offsets[s];
    entries.resize(corners);
    std::vector<std::int32_t> next(offsets.begin(), offsets.end() - 1);
    for (std::size_t c = 0; c < corners; ++c)
      entries[static_cast<std::size_t>(next[slot_of(c)]++)] = static_cast<std::int32_t>(c / 3);
  };
  fill(
      nv,
      [&](std::size_t c) { return static_cast<std::size_t>(vertex_home_[static_cast<std::size_t>(triangles_[c])]); },
      home_offsets_, home_triangles_);
  fill(
      group_count_, [&](std::size_t c) { return static_cast<std::size_t>(corner_groups_[c]); }, group_offsets_,
      group_triangles_);
  groups_are_homes_ = group_offsets_ == home_offsets_ && group_triangles_ == home_triangles_;
  if (groups_are_homes_) {  // the same lists: keep one copy (groupTriangles() returns the homes')
    std::vector<std::int32_t>().swap(group_offsets_);
    std::vector<std::int32_t>().swap(group_triangles_);
  }
}

SurfaceTopology SurfaceTopology::unwelded(std::span<const std::int32_t> triangles, std::size_t vertex_count) {
  if (triangles.size() % 3 != 0)
    throw Error("surface: " + std::to_string(triangles.size()) + " triangle indices is not a multiple of 3");
  for (std::size_t i = 0; i < triangles.size(); ++i)
    if (triangles[i] < 0 || static_cast<std::size_t>(triangles[i]) >= vertex_count)
      throw Error("surface: triangle " + std::to_string(i / 3) + " refers to vertex " + std::to_string(triangles[i]) +
                  ", but the mesh has " + std::to_string(vertex_count) + " vertices");
  // A mesh whose vertices are all distinct points and carry no normals or uvs: build() then welds
  // nothing, groups by vertex and makes every vertex a render vertex.
  TriMesh mesh;
  mesh.triangles.assign(triangles.begin(), triangles.end());
  mesh.positions.resize(vertex_count * 3);
  for (std::size_t v = 0; v < vertex_count; ++v) mesh.positions[v * 3] = static_cast<float>(v);
  if (mesh.triangles.empty() || vertex_count == 0) {
    SurfaceTopology t;
    t.weld_.resize(vertex_count);
    std::iota(t.weld_.begin(), t.weld_.end(), 0);
    t.vertex_home_ = t.weld_;
    t.welded_count_ = vertex_count;
    t.buildGatherLists();
    return t;
  }
  SurfaceOptions exact;
  exact.weld_tolerance = 0.0;
  SurfaceTopology t = build(mesh, exact);
  // Render vertices follow the vertex numbering, so callers can upload #V arrays unchanged.
  t.render_source_.resize(vertex_count);
  std::iota(t.render_source_.begin(), t.render_source_.end(), 0);
  t.render_group_.assign(vertex_count, -1);
  t.render_uv_.assign(vertex_count, -1);
  for (std::size_t c = 0; c < t.triangles_.size(); ++c)
    t.render_group_[static_cast<std::size_t>(t.triangles_[c])] = t.corner_groups_[c];
  t.render_triangles_ = t.triangles_;
  return t;
}

namespace {

// (sx, sy, sz) normalised into out[0..2]; (0, 0, 0) stays.
inline void finishNormal(float sx, float sy, float sz, float* out) {
  const float len = std::sqrt(sx * sx + sy * sy + sz * sz);
  if (len > 0.0f) {
    const float inv = 1.0f / len;
    sx *= inv;
    sy *= inv;
    sz *= inv;
  }
  out[0] = sx;
  out[1] = sy;
  out[2] = sz;
}

// A position as a 4-float packet (x, y, z, 0), read as three floats (no read past the array).
inline Eigen::Vector4f point4(const float* p, std::int32_t v) {
  const float* q = p + 3 * static_cast<std::size_t>(v);
  return {q[0], q[1], q[2], 0.0f};
}

// The area-weighted normal (b - a) x (c - a) of triangle f into n[0..2], as gatherNormal adds it.
inline void faceNormal(const std::int32_t* tris, const float* positions, std::int32_t f, float* n) {
  const std::int32_t* t = tris + 3 * static_cast<std::size_t>(f);
  const float* a = positions + 3 * static_cast<std::size_t>(t[0]);
  const float* b = positions + 3 * static_cast<std::size_t>(t[1]);
  const float* c = positions + 3 * static_cast<std::size_t>(t[2]);
  const float e1x = b[0] - a[0], e1y = b[1] - a[1], e1z = b[2] - a[2];
  const float e2x = c[0] - a[0], e2y = c[1] - a[1], e2z = c[2] - a[2];
  n[0] = e1y * e2z - e1z * e2y;
  n[1] = e1z * e2x - e1x * e2z;
  n[2] = e1x * e2y - e1y * e2x;
}

// Face normals computeVertexNormalsOf caches, with their tags (16 x 4096 bytes, 64 KB of stack).
constexpr std::size_t kFaceCache = 4096;
constexpr std::size_t kCacheMask = kFaceCache - 1;
static_assert((kFaceCache & kCacheMask) == 0, "the face cache's size is a power of two");

// The normalised sum of the area-weighted normals of triangles ids[0 .. count) (each computed from
// its first corner, as (b - a) x (c - a)), into out[0..2]; (0, 0, 0) when the sum is zero.
inline void gatherNormal(const std::int32_t* tris, const float* positions, const std::int32_t* ids, std::size_t count,
                         float* out) {
  // Scalar: measured faster here than 4-float packets (a short list per vertex, whose packet
  // would then be taken apart for the normalisation).
  float sx = 0.0f, sy = 0.0f, sz = 0.0f;
  for (std::size_t i = 0; i < count; ++i) {
    const std::int32_t* t = tris + 3 * static_cast<std::size_t>(ids[i]);
    const float* a = positions + 3 * static_cast<std::size_t>(t[0]);
    const float* b = positions + 3 * static_cast<std::size_t>(t[1]);
    const float* c = positions + 3 * static_cast<std::size_t>(t[2]);
    const float e1x = b[0] - a[0], e1y = b[1] - a[1], e1z = b[2] - a[2];
    const float e2x = c[0] - a[0], e2y = c[1] - a[1], e2z = c[2] - a[2];
    sx += e1y * e2z - e1z * e2y;
    sy += e1z * e2x - e1x * e2z;
    sz += e1x * e2y - e1y * e2x;
  }
  finishNormal(sx, sy, sz, out);
}

// Triangles whose normals one block of slots caches on the stack, and slots one block sums at
// most: 16 x 8192 + 20 x 2048 bytes, 168 KB.
constexpr std::size_t kFaceWindow = 8192;
constexpr std::size_t kSlotWindow = 2048;
static_assert(kSlotWindow % 8 == 0, "finishNormals pads to groups of 8");

// The face normals (b - a) x (c - a) of triangles [first, last] into the ring face[f & kFaceMask],
// one 4-float packet each (x, y, z, 0): Eigen's cross3 computes the three components in the lanes
// of one vector register with the same products and differences as gatherNormal's scalar code
// (Eigen/src/Geometry/arch/Geometry_SIMD.h), so the values are bit-identical.
constexpr std::size_t kFaceMask = kFaceWindow - 1;
static_assert((kFaceWindow & kFaceMask) == 0, "the face ring's size is a power of two");
void faceNormals(const std::int32_t* tris, const float* p, std::int32_t first, std::int32_t last,
                 Eigen::Vector4f* __restrict face) {
  for (auto f = static_cast<std::size_t>(first); f <= static_cast<std::size_t>(last); ++f) {
    const std::int32_t* tri = tris + 3 * f;
    const Eigen::Vector4f a = point4(p, tri[0]);
    face[f & kFaceMask] = (point4(p, tri[1]) - a).cross3(point4(p, tri[2]) - a);
  }
}

// Normalises count sums (4-float packets x, y, z, 0) into out (count x 3) as finishNormal does:
// first the reciprocal lengths of groups of slots in vector registers (the square root and the
// division are the same correctly rounded IEEE operations there as in a scalar register, and a
// slot whose length is not > 0 is multiplied by 1, that is left as finishNormal leaves it), then
// each sum times its reciprocal. Bit-identical to finishNormal. `inv` holds kSlotWindow floats.
void finishNormals(Eigen::Vector4f* __restrict sum, std::size_t count, float* __restrict inv, float* __restrict out) {
  // Whole groups of 8 (the buffers hold kSlotWindow, a multiple of 8; the padding is zeroed and
  // never written out), so that -O2's cheap vectoriser replaces the loop entirely.
  const std::size_t padded = (count + 7) & ~std::size_t{7};
  for (std::size_t i = count; i < padded; ++i) sum[i].setZero();
  const float* s = sum[0].data();
  for (std::size_t i = 0; i < padded; ++i) {  // vectorised: check with -fopt-info-vec (docs/performance.md)
    const float x = s[4 * i], y = s[4 * i + 1], z = s[4 * i + 2];
    const float len = std::sqrt(x * x + y * y + z * z);
    inv[i] = 1.0f / (len > 0.0f ? len : 1.0f);  // select, then divide: no branch
  }
  // Four lanes stored at out + 3i: the fourth lands on the next slot's x, written next; the last
  // slot is stored as three floats, so nothing past out[3 count) is touched.
  for (std::size_t i = 0; i + 1 < count; ++i) Eigen::Map<Eigen::Vector4f>(out + 3 * i) = sum[i] * inv[i];
  if (count > 0) {
    const std::size_t last = count - 1;
    for (int k = 0; k < 3; ++k) out[3 * last + static_cast<std::size_t>(k)] = sum[last][k] * inv[last];
  }
}

// sum[k] = the sum of face[f & kFaceMask] over the triangles f of slot k's list (off[k] to
// off[k + 1] of id), k < count, added in list order. Each sum is one chain of dependent additions,
// so four slots are summed side by side (four independent chains the core overlaps); each slot
// still adds its own normals in its own order, so the sums are bit-identical to one slot at a time.
void sumSlots(const std::int32_t* off, const std::int32_t* id, std::size_t count, const Eigen::Vector4f* face,
              Eigen::Vector4f* __restrict sum) {
  const auto at = [&](std::int32_t i) -> const Eigen::Vector4f& {
    return face[static_cast<std::size_t>(id[i]) & kFaceMask];
  };
  std::size_t k = 0;
  for (; k + 4 <= count; k += 4) {
    const std::int32_t b0 = off[k], b1 = off[k + 1], b2 = off[k + 2], b3 = off[k + 3], b4 = off[k + 4];
    const std::int32_t common = std::min(std::min(b1 - b0, b2 - b1), std::min(b3 - b2, b4 - b3));
    Eigen::Vector4f n0 = Eigen::Vector4f::Zero(), n1 = n0, n2 = n0, n3 = n0;
    for (std::int32_t i = 0; i < common; ++i) {
      n0 += at(b0 + i);
      n1 += at(b1 + i);
      n2 += at(b2 + i);
      n3 += at(b3 + i);
    }
    for (std::int32_t i = b0 + common; i < b1; ++i) n0 += at(i);
    for (std::int32_t i = b1 + common; i < b2; ++i) n1 += at(i);
    for (std::int32_t i = b2 + common; i < b3; ++i) n2 += at(i);
    for (std::int32_t i = b3 + common; i < b4; ++i) n3 += at(i);
    sum[k] = n0;
    sum[k + 1] = n1;
    sum[k + 2] = n2;
    sum[k + 3] = n3;
  }
  for (; k < count; ++k) {
    Eigen::Vector4f n = Eigen::Vector4f::Zero();
    for (std::int32_t i = off[k]; i < off[k + 1]; ++i) n += at(i);
    sum[k] = n;
  }
}

// Normals of slots [0, slots) from a CSR (offsets, ids) into out (slots x 3).
//
// Neighbouring slots share triangles (each triangle is in three slots' lists), so rather than
// computing a triangle's normal once per corner, a block of at most kSlotWindow consecutive slots
// whose triangles lie in a window of at most kFaceWindow consecutive indices first computes the
// window's face normals not yet in the ring of the previous windows (a streaming loop), then sums
// them per slot and normalises the block's
// sums together (a vectorised loop). That needs a mesh whose neighbouring vertices have
// neighbouring triangles (as exported meshes do); where the window would compute more normals than
// the block has corners, the block sums per corner instead. Either way each slot adds the same
// float normals in the same order, so the result does not depend on the path.
void gatherSlots(std::span<const std::int32_t> tris, std::span<const float> positions,
                 std::span<const std::int32_t> offsets, std::span<const std::int32_t> ids, std::size_t slots,
                 float* out) {
  const std::int32_t* t = tris.data();
  const float* p = positions.data();
  const std::int32_t* off = offsets.data();
  const std::int32_t* id = ids.data();
  detail::parallelChunks(slots, kParallelNormalSlots, [&](std::size_t begin, std::size_t end) {
    // A ring of face normals: faces [ring_lo, ring_hi] are at face[f & kFaceMask]; windows move
    // forward over an ordered mesh, so each face is computed about once per chunk.
    Eigen::Vector4f face[kFaceWindow], sum[kSlotWindow];
    std::int32_t ring_lo = 0, ring_hi = -1;
    float inv[kSlotWindow];
    std::size_t s = begin;
    while (s < end) {
      // The longest run of slots from s whose triangles fit in one window (lists are ascending).
      std::int32_t lo = std::numeric_limits<std::int32_t>::max(), hi = -1;
      std::size_t e = s;
      const std::size_t stop_at = std::min(end, s + kSlotWindow);
      for (; e < stop_at; ++e) {
        if (off[e] == off[e + 1]) continue;
        const std::int32_t first = id[off[e]], last = id[off[e + 1] - 1];
        const std::int32_t new_lo = std::min(lo, first), new_hi = std::max(hi, last);
        if (static_cast<std::size_t>(new_hi - new_lo) >= kFaceWindow) break;
        lo = new_lo;
        hi = new_hi;
      }
      const std::size_t corners = static_cast<std::size_t>(off[e] - off[s]);
      if (e == s || static_cast<std::size_t>(hi - lo + 1) > corners) {
        // No window worth computing: sum per corner, for at least one slot.
        const std::size_t stop = std::max(e, s + 1);
        for (; s < stop; ++s)
          gatherNormal(t, p, id + off[s], static_cast<std::size_t>(off[s + 1] - off[s]), out + 3 * s);
        continue;
      }
      if (lo >= ring_lo && lo <= ring_hi + 1) {  // the window continues the ring's: its new faces only
        if (hi > ring_hi) {
          faceNormals(t, p, ring_hi + 1, hi, face);
          ring_hi = hi;
          ring_lo = std::max(ring_lo, hi - static_cast<std::int32_t>(kFaceMask));
        }
      } else {
        faceNormals(t, p, lo, hi, face);
        ring_lo = lo;
        ring_hi = hi;
      }
      sumSlots(off + s, id, e - s, face, sum);
      finishNormals(sum, e - s, inv, out + 3 * s);
      s = e;
    }
  });
}

}  // namespace

bool computeGroupNormals(const SurfaceTopology& topology, std::span<const float> positions,
                         std::span<float> group_normals) {
  if (positions.size() != topology.vertexCount() * 3 || group_normals.size() != topology.groupCount() * 3) return false;
  gatherSlots(topology.triangles(), positions, topology.groupTriangleOffsets(), topology.groupTriangles(),
              topology.groupCount(), group_normals.data());
  return true;
}

bool computeVertexNormals(const SurfaceTopology& topology, std::span<const float> positions, std::span<float> normals) {
  if (positions.size() != topology.vertexCount() * 3 || normals.size() != positions.size()) return false;
  // Homes gather their triangles; the other vertices' ranges are empty and get (0, 0, 0) here,
  // then their home's normal.
  gatherSlots(topology.triangles(), positions, topology.homeTriangleOffsets(), topology.homeTriangles(),
              topology.vertexCount(), normals.data());
  const auto home = topology.vertexHome();
  for (const std::int32_t v : topology.copiedVertices()) {
    const auto d = static_cast<std::size_t>(v) * 3, h = static_cast<std::size_t>(home[static_cast<std::size_t>(v)]) * 3;
    normals[d] = normals[h];
    normals[d + 1] = normals[h + 1];
    normals[d + 2] = normals[h + 2];
  }
  return true;
}

bool computeVertexNormalsOf(const SurfaceTopology& topology, std::span<const float> positions,
                            std::span<const std::int32_t> vertices, std::span<float> normals) {
  const std::size_t nv = topology.vertexCount();
  if (positions.size() != nv * 3 || normals.size() != positions.size()) return false;
  for (const std::int32_t v : vertices)
    if (v < 0 || static_cast<std::size_t>(v) >= nv) return false;
  const std::int32_t* t = topology.triangles().data();
  const float* p = positions.data();
  const std::int32_t* home = topology.vertexHome().data();
  const std::int32_t* off = topology.homeTriangleOffsets().data();
  const std::int32_t* id = topology.homeTriangles().data();
  const std::int32_t* list = vertices.data();
  float* out = normals.data();
  detail::parallelChunks(vertices.size(), kParallelListedNormals, [&](std::size_t begin, std::size_t end) {
    // Neighbouring listed vertices share faces; a direct-mapped cache of face normals (face f at
    // f & kCacheMask, tagged with f) computes each about once where the list is in memory order
    // (ModelEvaluator's lists are ascending). Scalar, as gatherNormal: 4-float packets measured
    // slower here (GCC assembles a cross3 result through the stack, and reloading it stalls). Each
    // vertex adds the same floats in the same order as gatherNormal, and its sum is normalised by
    // finishNormals with a block of others (no square root's latency per vertex), so the result
    // is bit-identical.
    std::int32_t tag[kFaceCache];
    float cached[3 * kFaceCache], inv[kSlotWindow], block[3 * kSlotWindow];
    Eigen::Vector4f sum[kSlotWindow];
    std::fill(tag, tag + kFaceCache, -1);
    for (std::size_t b = begin; b < end; b += kSlotWindow) {
      const std::size_t count = std::min(kSlotWindow, end - b);
      for (std::size_t i = 0; i < count; ++i) {
        const auto h = static_cast<std::size_t>(home[static_cast<std::size_t>(list[b + i])]);
        float sx = 0.0f, sy = 0.0f, sz = 0.0f;
        for (std::int32_t k = off[h]; k < off[h + 1]; ++k) {
          const std::int32_t f = id[k];
          const std::size_t slot = static_cast<std::size_t>(f) & kCacheMask;
          float* n = cached + 3 * slot;
          if (tag[slot] != f) {
            tag[slot] = f;
            faceNormal(t, p, f, n);
          }
          sx += n[0];
          sy += n[1];
          sz += n[2];
        }
        sum[i] = {sx, sy, sz, 0.0f};
      }
      finishNormals(sum, count, inv, block);
      for (std::size_t i = 0; i < count; ++i) {
        float* o = out + 3 * static_cast<std::size_t>(list[b + i]);
        o[0] = block[3 * i];
        o[1] = block[3 * i + 1];
        o[2] = block[3 * i + 2];
      }
    }
  });
  return true;
}

}  // namespace vdg
