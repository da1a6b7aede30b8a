// Parent's sheets (vdg/morph/sheet_morph.h): Parent, "Computer Animation", 4.10 "Shape
// Interpolation, Metamorphosis" (../shared/reference/001_ee8e4823a552f1ff.txt): break each object
// into two sheets with the same number of boundary points, then recursively find a path of edges
// between two vertices of a sheet of A, establish the path between the corresponding vertices of
// the corresponding sheet of B, split both sheets along their paths, and recurse until every sheet
// is one face; then interpolate vertex to vertex. (R. E. Parent, "Shape transformation by boundary
// representation interpolation: a recursive approach to establishing face correspondences", The
// Journal of Visualization and Computer Animation 3(4), 1992.)
//
// How it is built here:
//  1. Each mesh (closed, genus 0, a manifold) is split into a front and a back sheet: the front
//     grows from the triangle farthest along +axis, taking the next triangle across its boundary in
//     the order of their centres along the axis, but only a triangle that keeps it a disc (it
//     shares one boundary edge and its third corner is new, or two boundary edges), until it holds
//     half the triangles. Triangulated 2-spheres are shellable, so the growth never gets stuck, and
//     the rest (the back) is a disc too. The cycle between them runs with the front on its left,
//     from its vertex farthest along the axis after `axis`.
//  2. B's sheets are flattened (W. T. Tutte, "How to draw a graph", Proc. London Math. Soc. 13,
//     1963: every inner vertex at the average of its neighbours, the cycle fixed on the unit circle
//     by arc length; with a convex boundary the triangles do not fold (M. S. Floater, "One-to-one
//     piecewise linear mappings over triangulations", Math. Comp. 72, 2003); checked exactly).
//  3. "The same number of points on the boundary": each cycle gets a new point on its edges at every
//     fraction of arc length where the other has a vertex, so both have the union of both sets.
//  4. The recursion, on a pair of corresponding sheets (same boundary count, point k of A's with
//     point k of B's): while A's sheet has more than one face, a breadth-first search through the
//     inside of A's sheet finds an existing path of edges between two of its boundary points i and
//     j (the most even split of the boundary first). On B the path is established as the straight
//     cut between its points i and j in the flattening: B's sheets are convex polygons there (the
//     disc, cut by straight lines), so the cut stays inside, and crossing B's edges only adds
//     points on them (exact orientation signs say which side of the cut a vertex is on; a vertex on
//     it joins the path). A pair (i, j) is usable on B when the boundary points between i and j lie
//     strictly on one side of the cut and the rest strictly on the other. Both paths then get the
//     same points by arc length (as in 3), and both sheets are cut in two along them.
//  5. When A's sheet is one face, B's sheet (a convex region) is laid onto it: B's boundary points
//     onto A's, and B's inner vertices by mean value coordinates (M. S. Floater, "Mean value
//     coordinates", CAGD 20(1), 2003) in the flattening. When B's sheet is one face first, A's sheet
//     is laid onto it instead (Tutte's embedding with A's boundary on B's face). When no path of
//     A's edges ends at a usable pair (i, j), A's sheet is flattened onto B's the same way and both
//     are cut along one straight line (this strays from the text, which always follows A's edges).
//  6. A is the mesh with fewer triangles; when the recursion fails (a sheet of the cut mesh too thin
//     to cut again, where cuts came close), it is run with the meshes the other way round.
// Every point added lies on an edge or a face of its own mesh (a face of B stays inside one
// original triangle, where the flattening is affine, so 3D positions are interpolated along edges
// and by mean values inside B's faces). The common mesh is B's final faces, plus A's faces where A
// was laid onto B; faces are cut into triangles by ears in the flattening.
#include "vdg/morph/sheet_morph.h"

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <optional>
#include <queue>
#include <string>
#include <unordered_map>
#include <unordered_set>
#include <utility>
#include <vector>

#include "exact_orient.h"
#include "vdg/geom/error.h"
#include "vdg/geom/text.h"
#include "vdg/morph/mesh_checks.h"

namespace vdg::morph {
namespace {

using D2 = std::array<double, 2>;
using D3 = std::array<double, 3>;
using Loop = std::vector<std::int32_t>;

std::uint64_t edgeKey(std::int32_t u, std::int32_t v) {
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(std::min(u, v))) << 32) |
         static_cast<std::uint32_t>(std::max(u, v));
}
std::uint64_t directedKey(std::int32_t u, std::int32_t v) {
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(u)) << 32) | static_cast<std::uint32_t>(v);
}
std::size_t at(std::int32_t i) { return static_cast<std::size_t>(i); }
D3 lerp(const D3& p, const D3& q, double f) {
  return {p[0] + f * (q[0] - p[0]), p[1] + f * (q[1] - p[1]), p[2] + f * (q[2] - p[2])};
}
D2 lerp(const D2& p, const D2& q, double f) { return {p[0] + f * (q[0] - p[0]), p[1] + f * (q[1] - p[1])}; }
double distance(const D3& p, const D3& q) { return std::hypot(q[0] - p[0], q[1] - p[1], q[2] - p[2]); }
int orient(const D2& c, const D2& p, const D2& q) { return detail::orient2dSign(c[0], c[1], p[0], p[1], q[0], q[1]); }
std::int32_t count32(std::size_t n) { return static_cast<std::int32_t>(n); }

// ---- The meshes' checks, and the first split into a front and a back sheet -------------------

// One genus-0 surface with one fan of triangles round every vertex (what makes every sheet grown
// below a disc).
void requireSphere(const TriMesh& m, const std::string& what) {
  validateMesh(m, what);
  requireClosed(m, what);
  const std::size_t n = m.vertexCount(), faces = m.triangleCount();
  std::vector<std::int32_t> parent(n);
  std::iota(parent.begin(), parent.end(), 0);
  auto root = [&](std::int32_t v) {
    while (parent[at(v)] != v) v = parent[at(v)] = parent[at(parent[at(v)])];
    return v;
  };
  for (std::size_t f = 0; f < faces; ++f)
    for (int k = 0; k < 2; ++k) parent[at(root(m.triangles[f * 3 + k]))] = root(m.triangles[f * 3 + k + 1]);
  std::unordered_set<std::int32_t> roots;
  for (const std::int32_t v : m.triangles) roots.insert(root(v));
  const int chi = eulerCharacteristic(m);
  if (chi != 2 || roots.size() != 1)
    throw Error(what + ": is not one genus-0 surface (Euler characteristic " + std::to_string(chi) + ", " +
                std::to_string(roots.size()) + (roots.size() == 1 ? " part" : " parts") +
                "); the sheet morph needs a mesh like a sphere");
  std::unordered_map<std::uint64_t, std::int32_t> face_of;  // directed edge -> its triangle
  face_of.reserve(faces * 3);
  for (std::size_t f = 0; f < faces; ++f)
    for (int k = 0; k < 3; ++k)
      face_of[directedKey(m.triangles[f * 3 + k], m.triangles[f * 3 + (k + 1) % 3])] = count32(f);
  std::vector<char> seen(faces * 3, 0);
  std::vector<int> fans(n, 0);
  for (std::size_t c = 0; c < faces * 3; ++c) {
    if (seen[c]) continue;
    const std::int32_t v = m.triangles[c];
    if (++fans[at(v)] > 1)
      throw Error(what + ": vertex " + std::to_string(v) +
                  " is not a manifold vertex (its triangles make 2 fans or more); the sheet morph needs one fan "
                  "round every vertex");
    // Round v: from the corner c of triangle f, across its edge v -> x to the triangle with x -> v.
    std::size_t cur = c;
    while (!seen[cur]) {
      seen[cur] = 1;
      const std::size_t f = cur / 3;
      const std::int32_t x = m.triangles[f * 3 + (cur % 3 + 1) % 3];
      const std::size_t g = at(face_of.at(directedKey(x, v)));
      std::size_t k = 0;
      while (m.triangles[g * 3 + k] != v) ++k;
      cur = g * 3 + k;
    }
  }
}

// The front sheet: 1 for its triangles (step 1 above).
std::vector<char> growFront(const TriMesh& m, int axis) {
  const std::size_t faces = m.triangleCount();
  std::unordered_map<std::uint64_t, std::int32_t> face_of;
  face_of.reserve(faces * 3);
  for (std::size_t f = 0; f < faces; ++f)
    for (int k = 0; k < 3; ++k)
      face_of[directedKey(m.triangles[f * 3 + k], m.triangles[f * 3 + (k + 1) % 3])] = count32(f);
  std::vector<std::int32_t> across(faces * 3);  // the triangle across each edge
  std::vector<double> score(faces);
  for (std::size_t f = 0; f < faces; ++f) {
    for (int k = 0; k < 3; ++k) {
      across[f * 3 + k] = face_of.at(directedKey(m.triangles[f * 3 + (k + 1) % 3], m.triangles[f * 3 + k]));
      score[f] += m.positions[at(m.triangles[f * 3 + k]) * 3 + static_cast<std::size_t>(axis)];
    }
  }
  std::vector<char> in(faces, 0);
  std::vector<int> used(m.vertexCount(), 0);  // triangles of the front at each vertex
  std::priority_queue<std::pair<double, std::int32_t>> next;
  std::size_t size = 0;
  auto add = [&](std::size_t f) {
    in[f] = 1;
    ++size;
    for (int k = 0; k < 3; ++k) {
      ++used[at(m.triangles[f * 3 + k])];
      if (!in[at(across[f * 3 + k])]) next.emplace(score[at(across[f * 3 + k])], across[f * 3 + k]);
    }
  };
  add(static_cast<std::size_t>(std::max_element(score.begin(), score.end()) - score.begin()));
  while (size * 2 < faces && !next.empty()) {
    const auto f = at(next.top().second);
    next.pop();
    if (in[f]) continue;
    int shared = 0, edge = 0;
    for (int k = 0; k < 3; ++k)
      if (in[at(across[f * 3 + k])]) {
        ++shared;
        edge = k;
      }
    // One shared edge: the opposite corner must be new. Two: always a disc. Three: closes it.
    if (shared == 3 || (shared == 1 && used[at(m.triangles[f * 3 + (edge + 2) % 3])] > 0)) continue;
    add(f);  // a triangle passed over now comes back when a neighbour joins
  }
  return in;
}

// The cycle between the front and the back, with the front on its left, from its vertex farthest
// along the axis after `axis` (the lowest index of equals).
Loop frontCycle(const TriMesh& m, const std::vector<char>& front, int axis) {
  std::unordered_map<std::uint64_t, std::int32_t> face_of;
  for (std::size_t f = 0; f < m.triangleCount(); ++f)
    for (int k = 0; k < 3; ++k)
      face_of[directedKey(m.triangles[f * 3 + k], m.triangles[f * 3 + (k + 1) % 3])] = count32(f);
  std::unordered_map<std::int32_t, std::int32_t> after;
  for (std::size_t f = 0; f < m.triangleCount(); ++f) {
    if (!front[f]) continue;
    for (int k = 0; k < 3; ++k) {
      const std::int32_t u = m.triangles[f * 3 + k], v = m.triangles[f * 3 + (k + 1) % 3];
      if (!front[at(face_of.at(directedKey(v, u)))]) after[u] = v;
    }
  }
  const auto side = static_cast<std::size_t>((axis + 1) % 3);
  std::int32_t start = after.begin()->first;
  for (const auto& [v, w] : after) {
    const float x = m.positions[at(v) * 3 + side], best = m.positions[at(start) * 3 + side];
    if (x > best || (x == best && v < start)) start = v;
  }
  Loop cycle{start};
  for (std::int32_t v = after.at(start); v != start; v = after.at(v)) cycle.push_back(v);
  return cycle;
}

// ---- A polygon mesh that grows: points added on edges, faces cut in two ------------------------

struct PolyMesh {
  std::vector<D3> xyz;
  std::array<std::vector<D2>, 2> uv;  // each vertex in the flattening of the front (0) and back (1) sheet
  std::vector<Loop> faces;            // counter-clockwise seen from outside
  std::unordered_map<std::uint64_t, std::array<std::int32_t, 2>> edge_faces;  // the two faces of each edge

  explicit PolyMesh(const TriMesh& m) {
    for (std::size_t v = 0; v < m.vertexCount(); ++v)
      xyz.push_back({m.positions[v * 3], m.positions[v * 3 + 1], m.positions[v * 3 + 2]});
    uv[0].resize(xyz.size());
    uv[1].resize(xyz.size());
    edge_faces.reserve(m.triangleCount() * 2);
    for (std::size_t f = 0; f < m.triangleCount(); ++f) {
      faces.push_back({m.triangles[f * 3], m.triangles[f * 3 + 1], m.triangles[f * 3 + 2]});
      for (int k = 0; k < 3; ++k) {
        const auto [it, fresh] = edge_faces.try_emplace(
            edgeKey(m.triangles[f * 3 + k], m.triangles[f * 3 + (k + 1) % 3]), std::array<std::int32_t, 2>{-1, -1});
        it->second[fresh ? 0 : 1] = count32(f);
      }
    }
  }
  std::int32_t vertexCount() const { return count32(xyz.size()); }

  // The face whose loop runs u -> v.
  std::int32_t faceOf(std::int32_t u, std::int32_t v) const {
    for (const std::int32_t f : edge_faces.at(edgeKey(u, v))) {
      const Loop& loop = faces[at(f)];
      for (std::size_t k = 0; k < loop.size(); ++k)
        if (loop[k] == u && loop[(k + 1) % loop.size()] == v) return f;
    }
    throw Error("sheet morph: internal: no face runs along an edge of a sheet's boundary");
  }

  // A new vertex at (1 - f) u + f v on the edge (u, v), put into both faces of the edge.
  std::int32_t splitEdge(std::int32_t u, std::int32_t v, double f) {
    const auto it = edge_faces.find(edgeKey(u, v));
    const std::array<std::int32_t, 2> around = it->second;
    edge_faces.erase(it);
    const std::int32_t w = vertexCount();
    xyz.push_back(lerp(xyz[at(u)], xyz[at(v)], f));
    for (auto& flat : uv) flat.push_back(lerp(flat[at(u)], flat[at(v)], f));
    for (const std::int32_t g : around) {
      Loop& loop = faces[at(g)];
      for (std::size_t k = 0; k < loop.size(); ++k) {
        const std::int32_t p = loop[k], q = loop[(k + 1) % loop.size()];
        if ((p == u && q == v) || (p == v && q == u)) {
          loop.insert(loop.begin() + static_cast<std::ptrdiff_t>(k) + 1, w);
          break;
        }
      }
    }
    edge_faces[edgeKey(u, w)] = around;
    edge_faces[edgeKey(w, v)] = around;
    return w;
  }

  // Cuts face f between the corners at positions i < j of its loop (not neighbours): f keeps
  // loop[i..j], the new face (returned) gets loop[j..] + loop[..i].
  std::int32_t splitFace(std::int32_t f, std::size_t i, std::size_t j) {
    const Loop loop = faces[at(f)];
    Loop first(loop.begin() + static_cast<std::ptrdiff_t>(i), loop.begin() + static_cast<std::ptrdiff_t>(j) + 1);
    Loop second(loop.begin() + static_cast<std::ptrdiff_t>(j), loop.end());
    second.insert(second.end(), loop.begin(), loop.begin() + static_cast<std::ptrdiff_t>(i) + 1);
    const std::int32_t g = count32(faces.size());
    for (std::size_t k = 0; k + 1 < second.size(); ++k)
      for (std::int32_t& x : edge_faces.at(edgeKey(second[k], second[k + 1])))
        if (x == f) {
          x = g;
          break;
        }
    edge_faces[edgeKey(loop[i], loop[j])] = {f, g};
    faces[at(f)] = std::move(first);
    faces.push_back(std::move(second));
    return g;
  }
};

// The arc-length fraction at each point of a path (0 at the first, 1 at the last; by index when
// the path has no length).
std::vector<double> arcFractions(const PolyMesh& m, const Loop& path) {
  std::vector<double> s(path.size(), 0.0);
  for (std::size_t k = 1; k < path.size(); ++k) s[k] = s[k - 1] + distance(m.xyz[at(path[k - 1])], m.xyz[at(path[k])]);
  const double total = s.back();
  for (std::size_t k = 0; k < s.size(); ++k)
    s[k] = total > 0 ? s[k] / total : static_cast<double>(k) / static_cast<double>(s.size() - 1);
  s.back() = 1.0;
  return s;
}

// Adds to the path (edges of m) a point at every fraction of `wanted` that `s` (the path's own
// fractions) lacks, on the edge that holds it.
void addPoints(PolyMesh& m, Loop& path, const std::vector<double>& s, const std::vector<double>& wanted) {
  Loop out;
  std::size_t w = 0;
  for (std::size_t k = 0; k + 1 < path.size(); ++k) {
    out.push_back(path[k]);
    std::int32_t from = path[k];
    double from_s = s[k];
    while (w < wanted.size() && wanted[w] <= s[k]) ++w;
    while (w < wanted.size() && wanted[w] < s[k + 1]) {
      from = m.splitEdge(from, path[k + 1], (wanted[w] - from_s) / (s[k + 1] - from_s));
      from_s = wanted[w++];
      out.push_back(from);
    }
  }
  out.push_back(path.back());
  path = std::move(out);
}

// Gives two paths (A's and B's, closed cycles when `closed`) the same points by arc length.
void matchPoints(PolyMesh& a, Loop& path_a, PolyMesh& b, Loop& path_b, bool closed) {
  if (closed) {
    path_a.push_back(path_a.front());
    path_b.push_back(path_b.front());
  }
  const std::vector<double> sa = arcFractions(a, path_a), sb = arcFractions(b, path_b);
  addPoints(a, path_a, sa, sb);
  addPoints(b, path_b, sb, sa);
  if (closed) {
    path_a.pop_back();
    path_b.pop_back();
  }
}

// ---- Flattening (Tutte), mean values, ears ---------------------------------------------------

// Every vertex of `face_ids` not in `loop` at the average of its neighbours; the loop's vertices
// stay where `uv` has them. False when the system cannot be solved.
bool tutte(const std::vector<Loop>& faces, const std::vector<std::int32_t>& face_ids, const Loop& loop,
           std::vector<D2>& uv) {
  std::unordered_map<std::int32_t, std::int32_t> row;
  std::unordered_set<std::int32_t> fixed(loop.begin(), loop.end());
  std::vector<std::int32_t> inner;
  for (const std::int32_t f : face_ids)
    for (const std::int32_t v : faces[at(f)])
      if (!fixed.count(v) && row.try_emplace(v, count32(inner.size())).second) inner.push_back(v);
  if (inner.empty()) return true;
  std::vector<Eigen::Triplet<double>> entries;
  Eigen::VectorXd bu = Eigen::VectorXd::Zero(count32(inner.size())), bv = bu;
  std::vector<double> degree(inner.size(), 0.0);
  auto link = [&](std::int32_t p, std::int32_t q) {  // q's pull on p
    const auto it = row.find(p);
    if (it == row.end()) return;
    degree[at(it->second)] += 1;
    const auto jt = row.find(q);
    if (jt != row.end()) {
      entries.emplace_back(it->second, jt->second, -1.0);
    } else {
      bu[it->second] += uv[at(q)][0];
      bv[it->second] += uv[at(q)][1];
    }
  };
  for (const std::int32_t f : face_ids) {
    const Loop& l = faces[at(f)];
    for (std::size_t k = 0; k < l.size(); ++k) {
      const std::int32_t p = l[k], q = l[(k + 1) % l.size()];
      // An edge with an inner end lies between two faces of the sheet: taken once, from p < q. An
      // edge between two fixed vertices pulls on nothing.
      if (p > q || (fixed.count(p) && fixed.count(q))) continue;
      link(p, q);
      link(q, p);
    }
  }
  for (std::size_t i = 0; i < inner.size(); ++i) entries.emplace_back(count32(i), count32(i), degree[i]);
  Eigen::SparseMatrix<double> matrix(count32(inner.size()), count32(inner.size()));
  matrix.setFromTriplets(entries.begin(), entries.end());
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(matrix);
  if (solver.info() != Eigen::Success) return false;
  const Eigen::VectorXd u = solver.solve(bu), v = solver.solve(bv);
  for (std::size_t i = 0; i < inner.size(); ++i) uv[at(inner[i])] = {u[count32(i)], v[count32(i)]};
  return u.allFinite() && v.allFinite();
}

// Flattens one of B's sheets onto the unit disc (its loop on the circle by arc length) into uv.
void flattenSheet(PolyMesh& b, const std::vector<std::int32_t>& face_ids, const Loop& loop, int side,
                  const std::string& what) {
  Loop closed = loop;
  closed.push_back(loop.front());
  const std::vector<double> s = arcFractions(b, closed);
  for (std::size_t k = 0; k < loop.size(); ++k)
    b.uv[at(side)][at(loop[k])] = {std::cos(2.0 * M_PI * s[k]), std::sin(2.0 * M_PI * s[k])};
  const std::string name = what + ": its " + (side == 0 ? "front" : "back") + " sheet cannot be flattened";
  if (!tutte(b.faces, face_ids, loop, b.uv[at(side)])) throw Error(name + " (the system has no solution)");
  for (const std::int32_t f : face_ids) {
    const Loop& l = b.faces[at(f)];
    if (orient(b.uv[at(side)][at(l[0])], b.uv[at(side)][at(l[1])], b.uv[at(side)][at(l[2])]) <= 0)
      throw Error(name + ": triangle " + std::to_string(f) + " folds over");
  }
}

// Mean value coordinates of x in a convex counter-clockwise polygon: w_k = (tan(a_(k-1) / 2) +
// tan(a_k / 2)) / |p_k - x|, normalised (Floater 2003, eq. 3.1), with tan(a / 2) = sin a /
// (1 + cos a) = cross / (r r' + dot); on an edge, the linear weights of its ends.
void meanValues(const std::vector<D2>& poly, const D2& x, std::vector<double>& w) {
  const std::size_t n = poly.size();
  w.assign(n, 0.0);
  std::vector<double> r(n), half_tan(n);
  for (std::size_t k = 0; k < n; ++k) {
    r[k] = std::hypot(poly[k][0] - x[0], poly[k][1] - x[1]);
    if (r[k] == 0) {
      w[k] = 1;
      return;
    }
  }
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t m = (k + 1) % n;
    const double ax = poly[k][0] - x[0], ay = poly[k][1] - x[1], bx = poly[m][0] - x[0], by = poly[m][1] - x[1];
    const double cross = ax * by - ay * bx, denominator = r[k] * r[m] + ax * bx + ay * by;
    if (denominator <= 1e-14 * r[k] * r[m]) {  // x on the edge k -> m
      w[k] = r[m] / (r[k] + r[m]);
      w[m] = r[k] / (r[k] + r[m]);
      return;
    }
    half_tan[k] = std::max(cross, 0.0) / denominator;
  }
  double sum = 0;
  for (std::size_t k = 0; k < n; ++k) sum += w[k] = (half_tan[(k + n - 1) % n] + half_tan[k]) / r[k];
  for (double& x_k : w) x_k = sum > 0 ? x_k / sum : 1.0 / static_cast<double>(n);
}

// Triangles of a convex counter-clockwise polygon (collinear corners allowed), as positions in it:
// an ear (a corner turning counter-clockwise) is cut off at a time; a flat rest by a fan.
std::vector<std::size_t> ears(const std::vector<D2>& poly) {
  std::vector<std::size_t> left(poly.size()), out;
  std::iota(left.begin(), left.end(), 0);
  while (left.size() > 3) {
    std::size_t cut = left.size();
    for (std::size_t k = 0; k < left.size() && cut == left.size(); ++k)
      if (orient(poly[left[(k + left.size() - 1) % left.size()]], poly[left[k]], poly[left[(k + 1) % left.size()]]) > 0)
        cut = k;
    if (cut == left.size()) break;
    out.insert(out.end(), {left[(cut + left.size() - 1) % left.size()], left[cut], left[(cut + 1) % left.size()]});
    left.erase(left.begin() + static_cast<std::ptrdiff_t>(cut));
  }
  for (std::size_t k = 1; k + 1 < left.size(); ++k) out.insert(out.end(), {left[0], left[k], left[k + 1]});
  return out;
}

// The straight cut of a sheet (`faces` of m, convex in the flattening m.uv[side]) from its boundary
// point `start` to its boundary point `end`: adds points where the cut crosses edges (their side
// of the cut is 0 by construction, every other vertex's is an exact orientation sign) and cuts
// faces in two; the faces on each side into plus and minus; returns the path from start to end.
Loop straightCut(PolyMesh& m, std::size_t side, const std::vector<std::int32_t>& faces, std::int32_t start,
                 std::int32_t end, std::vector<std::int32_t>& plus, std::vector<std::int32_t>& minus) {
  const D2 from = m.uv[side][at(start)], to = m.uv[side][at(end)];
  std::unordered_map<std::int32_t, int> sign;  // the sheet's vertices only: a cut costs what its sheet holds
  for (const std::int32_t f : faces)
    for (const std::int32_t v : m.faces[at(f)]) sign[v] = orient(from, to, m.uv[side][at(v)]);
  const double du = to[0] - from[0], dv = to[1] - from[1];
  auto height = [&](std::int32_t v) {
    return du * (m.uv[side][at(v)][1] - from[1]) - dv * (m.uv[side][at(v)][0] - from[0]);
  };
  for (const std::int32_t f : faces)
    for (std::size_t k = 0; k < m.faces[at(f)].size(); ++k) {
      const Loop& l = m.faces[at(f)];
      const std::int32_t u = l[k], v = l[(k + 1) % l.size()];
      if (sign.at(u) * sign.at(v) >= 0) continue;
      sign[m.splitEdge(u, v, height(u) / (height(u) - height(v)))] = 0;  // on the cut by construction
    }
  // The cut's pieces of edges: each face cut in two gives one, an edge lying on the line another.
  std::unordered_map<std::int32_t, std::vector<std::int32_t>> along;
  auto link = [&](std::int32_t u, std::int32_t v) {
    for (const auto& [x, y] : {std::pair{u, v}, std::pair{v, u}})
      if (std::find(along[x].begin(), along[x].end(), y) == along[x].end()) along[x].push_back(y);
  };
  for (const std::int32_t f : faces) {
    const Loop& l = m.faces[at(f)];
    std::vector<std::size_t> zeros;
    int pos = 0, neg = 0;
    for (std::size_t k = 0; k < l.size(); ++k) {
      const int s = sign.at(l[k]);
      if (s == 0) zeros.push_back(k);
      if (s == 0 && sign.at(l[(k + 1) % l.size()]) == 0) link(l[k], l[(k + 1) % l.size()]);
      pos += s > 0;
      neg += s < 0;
    }
    if (neg == 0 || pos == 0) {
      (neg == 0 ? plus : minus).push_back(f);
      continue;
    }
    if (zeros.size() != 2 || zeros[1] == zeros[0] + 1 || (zeros[0] == 0 && zeros[1] + 1 == l.size()))
      throw Error("sheet morph: a straight cut of a sheet crosses one of its faces twice (a face too flat to cut)");
    const int first_side = sign.at(l[zeros[0] + 1]);
    link(l[zeros[0]], l[zeros[1]]);
    const std::int32_t g = m.splitFace(f, zeros[0], zeros[1]);
    (first_side > 0 ? plus : minus).push_back(f);
    (first_side > 0 ? minus : plus).push_back(g);
  }
  // Walked from start to end (by the pieces, not by the positions along the line, which points
  // crowded near a corner of many cuts can tie).
  Loop path{start};
  for (std::int32_t prev = -1, cur = start; cur != end;) {
    const std::vector<std::int32_t>& next = along[cur];
    const std::size_t ways = next.size() - (prev >= 0 ? 1 : 0);
    if (ways != 1 || path.size() > along.size())
      throw Error("sheet morph: a straight cut of a sheet does not make one path of edges (a face too flat)");
    const std::int32_t step = next[0] != prev ? next[0] : next[1];
    prev = cur;
    cur = step;
    path.push_back(cur);
  }
  return path;
}

// ---- The recursion --------------------------------------------------------------------------------

struct SheetPair {
  int side = 0;  // which of B's flattenings: 0 front, 1 back
  std::vector<std::int32_t> a_faces, b_faces;
  Loop a_loop, b_loop;  // as long as each other, point k of A's with point k of B's; the sheet on the left
};

// The recursion gives up after this many splits per face of A and B.
constexpr std::size_t kSplitsPerFace = 4;
// How many boundary points of a sheet of A the search for a path starts from.
constexpr std::size_t kChordStarts = 8;

struct Chord {
  std::size_t i = 0, j = 0;
  Loop path;  // A's vertices from a_loop[i] to a_loop[j]
};

class SheetRecursion {
 public:
  SheetRecursion(PolyMesh& a, PolyMesh& b) : a_(a), b_(b) {}

  void run(std::vector<SheetPair> pairs) {
    // Following A's edges, every split leaves fewer faces of A in each part, so there are fewer
    // splits than A has faces; straight cuts of A (the fallback) split A's faces too, so a bound.
    const std::size_t limit = kSplitsPerFace * (a_.faces.size() + b_.faces.size());
    for (std::size_t splits = 0; !pairs.empty(); ++splits) {
      if (splits > limit)
        throw Error("sheet morph: the recursion does not come to an end (more than " + std::to_string(limit) +
                    " splits; straight cuts of sheets too thin to divide)");
      SheetPair p = std::move(pairs.back());
      pairs.pop_back();
      if (p.a_faces.size() == 1) {
        layBOntoA(p);
      } else if (p.b_faces.size() == 1) {
        layAOntoB(p);
      } else {
        auto [first, second] = split(p);
        pairs.push_back(std::move(first));
        pairs.push_back(std::move(second));
      }
    }
  }

  // The common mesh: B's vertices that some triangle uses, then A's laid onto B's faces.
  VertexMorph result() const {
    std::vector<std::int32_t> index(b_.xyz.size() + extra_a_.size(), -1);
    std::vector<float> on_a, on_b;
    std::vector<std::int32_t> triangles;
    for (const std::int32_t id : triangles_) {
      const std::size_t v = id >= 0 ? at(id) : b_.xyz.size() + at(-1 - id);
      if (index[v] < 0) {
        index[v] = count32(on_a.size() / 3);
        const D3& pa = id >= 0 ? on_a_[v] : extra_a_[at(-1 - id)];
        const D3& pb = id >= 0 ? b_.xyz[v] : extra_b_[at(-1 - id)];
        for (int k = 0; k < 3; ++k) {
          on_a.push_back(static_cast<float>(pa[at(k)]));
          on_b.push_back(static_cast<float>(pb[at(k)]));
        }
      }
      triangles.push_back(index[v]);
    }
    return VertexMorph(std::move(on_a), std::move(on_b), std::move(triangles), "sheet morph");
  }

 private:
  // ---- Step 4: a path of A, the cut of B, both sheets in two.
  std::pair<SheetPair, SheetPair> split(SheetPair& p) {
    std::optional<Chord> chord = findChord(p);
    std::vector<std::int32_t> a_plus, a_minus;
    const bool straight_on_a = !chord;
    if (straight_on_a) chord = cutAStraight(p, a_plus, a_minus);
    Loop path_a = chord->path;
    const int arc_side = cutSide(p, chord->i, chord->j);
    std::vector<std::int32_t> plus, minus;
    Loop path_b = straightCut(b_, at(p.side), p.b_faces, p.b_loop[chord->i], p.b_loop[chord->j], plus, minus);
    matchPoints(a_, path_a, b_, path_b, false);
    const std::size_t n = p.a_loop.size();
    SheetPair first, second;
    first.side = second.side = p.side;
    auto arc = [&](const Loop& loop, std::size_t from, std::size_t to) {
      Loop out;
      for (std::size_t k = from; k != to; k = (k + 1) % n) out.push_back(loop[k]);
      out.push_back(loop[to]);
      return out;
    };
    first.a_loop = arc(p.a_loop, chord->i, chord->j);
    first.b_loop = arc(p.b_loop, chord->i, chord->j);
    second.a_loop = arc(p.a_loop, chord->j, chord->i);
    second.b_loop = arc(p.b_loop, chord->j, chord->i);
    for (std::size_t k = path_a.size() - 2; k >= 1; --k) {
      first.a_loop.push_back(path_a[k]);
      first.b_loop.push_back(path_b[k]);
    }
    for (std::size_t k = 1; k + 1 < path_a.size(); ++k) {
      second.a_loop.push_back(path_a[k]);
      second.b_loop.push_back(path_b[k]);
    }
    if (straight_on_a) {
      first.a_faces = arc_side > 0 ? std::move(a_plus) : std::move(a_minus);
      second.a_faces = arc_side > 0 ? std::move(a_minus) : std::move(a_plus);
    } else {
      splitA(p, path_a, p.a_loop[chord->i], p.a_loop[(chord->i + 1) % n], first.a_faces, second.a_faces);
    }
    first.b_faces = arc_side > 0 ? std::move(plus) : std::move(minus);
    second.b_faces = arc_side > 0 ? std::move(minus) : std::move(plus);
    return {std::move(first), std::move(second)};
  }

  // +1 or -1: the side of the line from B's point i to its point j that the boundary points between
  // i and j are all strictly on, when the points between j and i are all strictly on the other
  // (then the straight cut from i to j splits B's convex sheet in two); 0 otherwise.
  int cutSide(const SheetPair& p, std::size_t i, std::size_t j) const {
    const std::vector<D2>& uv = b_.uv[at(p.side)];
    const std::size_t n = p.b_loop.size();
    const D2 from = uv[at(p.b_loop[i])], to = uv[at(p.b_loop[j])];
    int sides[2] = {0, 0};
    for (int half = 0; half < 2; ++half) {
      const std::size_t start = half == 0 ? i : j, end = half == 0 ? j : i;
      for (std::size_t k = (start + 1) % n; k != end; k = (k + 1) % n) {
        const int s = orient(from, to, uv[at(p.b_loop[k])]);
        if (s == 0 || (sides[half] != 0 && s != sides[half])) return 0;
        sides[half] = s;
      }
    }
    return sides[0] != 0 && sides[1] == -sides[0] ? sides[0] : 0;
  }

  // A path of A's edges through the inside of its sheet, between two boundary points that B's sheet
  // can be cut between; the most even split of the boundary first, then the shortest path.
  std::optional<Chord> findChord(const SheetPair& p) const {
    std::unordered_map<std::int32_t, std::vector<std::int32_t>> next;
    for (const std::int32_t f : p.a_faces) {
      const Loop& l = a_.faces[at(f)];
      for (std::size_t k = 0; k < l.size(); ++k) next[l[k]].push_back(l[(k + 1) % l.size()]);
    }
    std::unordered_map<std::int32_t, std::size_t> on_loop;
    for (std::size_t k = 0; k < p.a_loop.size(); ++k) on_loop[p.a_loop[k]] = k;
    const std::size_t n = p.a_loop.size();
    std::optional<Chord> best;
    double best_score = 0;
    auto search = [&](std::size_t i) {
      // Breadth first from point i through inner vertices; a boundary point reached ends a path.
      std::unordered_map<std::int32_t, std::int32_t> parent{{p.a_loop[i], -1}};
      std::unordered_set<std::size_t> seen;
      std::vector<std::int32_t> queue{p.a_loop[i]};
      for (std::size_t q = 0; q < queue.size(); ++q) {
        const std::int32_t x = queue[q];
        for (const std::int32_t y : next[x]) {
          const auto it = on_loop.find(y);
          if (it == on_loop.end()) {
            if (parent.try_emplace(y, x).second) queue.push_back(y);
            continue;
          }
          const std::size_t j = it->second;
          const bool boundary_edge = x == p.a_loop[i] && (j == (i + 1) % n || (j + 1) % n == i);
          if (j == i || boundary_edge || !seen.insert(j).second) continue;
          const double score = cutScore(p, i, j);
          if (score <= best_score) continue;
          best_score = score;
          best = Chord{i, j, {p.a_loop[j]}};
          for (std::int32_t v = x; v >= 0; v = parent.at(v)) best->path.push_back(v);
          std::reverse(best->path.begin(), best->path.end());
        }
      }
    };
    // Searches from a few points spread round the boundary (not only from the ends of the last
    // cut, which would fan every later cut out of one point), then, if none will do, from all.
    const std::size_t starts = std::min(n, kChordStarts);
    for (std::size_t k = 0; k < starts; ++k) search((k * n) / starts + n / (2 * starts));
    for (std::size_t i = 0; i < n && !best; ++i) search(i);
    return best;
  }

  // How well the straight cut of B's sheet from point i to point j divides it: 0 when it cannot
  // (cutSide), else the thickness of the thinner side (the largest distance of its boundary points
  // from the cut), so that no side is left a sliver that later cuts cannot divide.
  double cutScore(const SheetPair& p, std::size_t i, std::size_t j) const {
    if (cutSide(p, i, j) == 0) return 0;
    const std::vector<D2>& uv = b_.uv[at(p.side)];
    const std::size_t n = p.b_loop.size();
    const D2 from = uv[at(p.b_loop[i])], to = uv[at(p.b_loop[j])];
    const double length = std::hypot(to[0] - from[0], to[1] - from[1]);
    double thickness[2] = {0, 0};
    for (std::size_t k = (i + 1) % n, half = 0; k != i; k = (k + 1) % n) {
      if (k == j) {
        half = 1;
        continue;
      }
      const D2& q = uv[at(p.b_loop[k])];
      const double height = std::abs((to[0] - from[0]) * (q[1] - from[1]) - (to[1] - from[1]) * (q[0] - from[0]));
      thickness[half] = std::max(thickness[half], height / length);
    }
    return std::min(thickness[0], thickness[1]);
  }

  // When no path of A's edges will do: A's sheet is flattened onto B's (Tutte, its boundary points
  // on B's), and both are cut along the same straight line between the two boundary points with
  // the best cutScore.
  Chord cutAStraight(const SheetPair& p, std::vector<std::int32_t>& plus, std::vector<std::int32_t>& minus) {
    const std::size_t n = p.a_loop.size();
    std::size_t best_i = 0, best_j = 0;
    double best_score = 0;
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = i + 2; j < n; ++j) {
        const double score = cutScore(p, i, j);
        if (score > best_score) {
          best_score = score;
          best_i = i;
          best_j = j;
        }
      }
    if (best_score > 0) {
      for (std::size_t k = 0; k < n; ++k) a_.uv[0][at(p.a_loop[k])] = b_.uv[at(p.side)][at(p.b_loop[k])];
      if (!tutte(a_.faces, p.a_faces, p.a_loop, a_.uv[0]))
        throw Error("sheet morph: a sheet of A cannot be flattened onto B's (the system has no solution)");
      return {best_i, best_j, straightCut(a_, 0, p.a_faces, p.a_loop[best_i], p.a_loop[best_j], plus, minus)};
    }
    throw Error("sheet morph: a sheet pair of " + std::to_string(p.a_faces.size()) + " and " +
                std::to_string(p.b_faces.size()) + " faces with " + std::to_string(n) +
                " boundary points cannot be cut in two (its straight cuts came too close); try another axis or "
                "another method");
  }

  // A's sheet cut along its path: the faces on the side of the boundary edge u -> v into first.
  void splitA(const SheetPair& p, const Loop& path, std::int32_t u, std::int32_t v, std::vector<std::int32_t>& first,
              std::vector<std::int32_t>& second) const {
    std::unordered_set<std::uint64_t> wall;
    for (std::size_t k = 0; k + 1 < path.size(); ++k) wall.insert(edgeKey(path[k], path[k + 1]));
    std::unordered_set<std::int32_t> sheet(p.a_faces.begin(), p.a_faces.end()), inside;
    std::vector<std::int32_t> stack{a_.faceOf(u, v)};
    inside.insert(stack.back());
    while (!stack.empty()) {
      const Loop& l = a_.faces[at(stack.back())];
      stack.pop_back();
      for (std::size_t k = 0; k < l.size(); ++k) {
        const std::uint64_t key = edgeKey(l[k], l[(k + 1) % l.size()]);
        if (wall.count(key)) continue;
        for (const std::int32_t g : a_.edge_faces.at(key))
          if (sheet.count(g) && inside.insert(g).second) stack.push_back(g);
      }
    }
    for (const std::int32_t f : p.a_faces) (inside.count(f) ? first : second).push_back(f);
  }

  // ---- Step 5: the ends of the recursion.
  // A's sheet is one face: B's sheet is laid onto it, boundary point to boundary point, B's inner
  // vertices by their mean value coordinates in B's flattening.
  void layBOntoA(const SheetPair& p) {
    const std::vector<D2>& uv = b_.uv[at(p.side)];
    on_a_.resize(b_.xyz.size());
    std::vector<D2> poly;
    std::unordered_set<std::int32_t> boundary(p.b_loop.begin(), p.b_loop.end());
    for (std::size_t k = 0; k < p.b_loop.size(); ++k) {
      on_a_[at(p.b_loop[k])] = a_.xyz[at(p.a_loop[k])];
      poly.push_back(uv[at(p.b_loop[k])]);
    }
    std::vector<double> w;
    for (const std::int32_t f : p.b_faces) {
      const Loop& l = b_.faces[at(f)];
      std::vector<D2> corners;
      for (const std::int32_t v : l) {
        corners.push_back(uv[at(v)]);
        if (!boundary.insert(v).second) continue;
        meanValues(poly, uv[at(v)], w);
        D3 x{0, 0, 0};
        for (std::size_t k = 0; k < w.size(); ++k)
          for (std::size_t c = 0; c < 3; ++c) x[c] += w[k] * a_.xyz[at(p.a_loop[k])][c];
        on_a_[at(v)] = x;
      }
      for (const std::size_t c : ears(corners)) triangles_.push_back(l[c]);
    }
  }

  // B's sheet is one face: A's sheet is laid onto it (Tutte's embedding with A's boundary on B's
  // face in B's flattening); A's inner vertices become new common vertices, on B by mean values.
  void layAOntoB(const SheetPair& p) {
    const std::vector<D2>& uv_b = b_.uv[at(p.side)];
    on_a_.resize(b_.xyz.size());
    std::vector<D2>& uv_a = a_.uv[0];  // A's own flattening is free for this
    uv_a.resize(a_.xyz.size());
    std::unordered_map<std::int32_t, std::int32_t> common;  // A's vertex -> common id
    std::vector<D2> poly;
    for (std::size_t k = 0; k < p.a_loop.size(); ++k) {
      on_a_[at(p.b_loop[k])] = a_.xyz[at(p.a_loop[k])];
      uv_a[at(p.a_loop[k])] = uv_b[at(p.b_loop[k])];
      common[p.a_loop[k]] = p.b_loop[k];
      poly.push_back(uv_b[at(p.b_loop[k])]);
    }
    if (!tutte(a_.faces, p.a_faces, p.a_loop, uv_a))
      throw Error("sheet morph: a sheet of A cannot be laid onto a face of B (the system has no solution)");
    std::vector<double> w;
    for (const std::int32_t f : p.a_faces) {
      const Loop& l = a_.faces[at(f)];
      std::vector<D2> corners;
      for (const std::int32_t v : l) {
        corners.push_back(uv_a[at(v)]);
        if (common.count(v)) continue;
        meanValues(poly, uv_a[at(v)], w);
        D3 x{0, 0, 0};
        for (std::size_t k = 0; k < w.size(); ++k)
          for (std::size_t c = 0; c < 3; ++c) x[c] += w[k] * b_.xyz[at(p.b_loop[k])][c];
        common[v] = -1 - count32(extra_a_.size());
        extra_a_.push_back(a_.xyz[at(v)]);
        extra_b_.push_back(x);
      }
      for (const std::size_t c : ears(corners)) triangles_.push_back(common.at(l[c]));
    }
  }

  PolyMesh& a_;
  PolyMesh& b_;
  std::vector<D3> on_a_;               // B's vertices: their place on A
  std::vector<D3> extra_a_, extra_b_;  // A's inner vertices laid onto B's faces (common id -1 - index)
  std::vector<std::int32_t> triangles_;
};

}  // namespace

double sheetMorphCost(const TriMesh& a, const TriMesh& b) {
  const double triangles = static_cast<double>(a.triangleCount() + b.triangleCount());
  return triangles * (std::log2(std::max(static_cast<double>(a.triangleCount()), 1.0)) + 2.0) * 64.0;
}

namespace {

// Steps 1 to 5 on two checked meshes.
VertexMorph sheetsOf(const TriMesh& a, const TriMesh& b, int axis, const std::string& what_b) {
  // Step 1: front and back, and the cycle between them.
  const std::vector<char> front_a = growFront(a, axis), front_b = growFront(b, axis);
  Loop cycle_a = frontCycle(a, front_a, axis), cycle_b = frontCycle(b, front_b, axis);
  PolyMesh pa(a), pb(b);
  std::array<std::vector<std::int32_t>, 2> faces_a, faces_b;  // front, back
  for (std::size_t f = 0; f < a.triangleCount(); ++f) faces_a[front_a[f] ? 0 : 1].push_back(count32(f));
  for (std::size_t f = 0; f < b.triangleCount(); ++f) faces_b[front_b[f] ? 0 : 1].push_back(count32(f));
  auto reversed = [](const Loop& cycle) {
    Loop out{cycle.front()};
    out.insert(out.end(), cycle.rbegin(), cycle.rend() - 1);
    return out;
  };
  // Step 2: B's sheets flattened; step 3: the same points on both cycles.
  flattenSheet(pb, faces_b[0], cycle_b, 0, what_b);
  flattenSheet(pb, faces_b[1], reversed(cycle_b), 1, what_b);
  matchPoints(pa, cycle_a, pb, cycle_b, true);
  std::vector<SheetPair> pairs(2);
  for (int side = 0; side < 2; ++side) {
    pairs[at(side)].side = side;
    pairs[at(side)].a_faces = faces_a[at(side)];
    pairs[at(side)].b_faces = faces_b[at(side)];
    pairs[at(side)].a_loop = side == 0 ? cycle_a : reversed(cycle_a);
    pairs[at(side)].b_loop = side == 0 ? cycle_b : reversed(cycle_b);
  }
  // Steps 4 and 5.
  SheetRecursion recursion(pa, pb);
  recursion.run(std::move(pairs));
  return recursion.result();
}

}  // namespace

VertexMorph sheetMorph(const TriMesh& a, const TriMesh& b, const SheetMorphOptions& options, const std::string& what_a,
                       const std::string& what_b) {
  if (options.axis < 0 || options.axis > 2) throw Error("sheet morph: axis must be 0, 1 or 2");
  requireSphere(a, what_a);
  requireSphere(b, what_b);
  // The mesh with fewer triangles has its edges followed and the other is cut (fewer cuts into a
  // finer mesh); the common mesh does not depend on the names, only its placements swap.
  auto build = [&](bool a_followed) {
    if (a_followed) return sheetsOf(a, b, options.axis, what_b);
    const VertexMorph swapped = sheetsOf(b, a, options.axis, what_a);
    const auto on_b = swapped.positionsOnA(), on_a = swapped.positionsOnB();
    const auto triangles = swapped.triangles();
    return VertexMorph({on_a.begin(), on_a.end()}, {on_b.begin(), on_b.end()}, {triangles.begin(), triangles.end()},
                       "sheet morph");
  };
  const bool a_first = a.triangleCount() <= b.triangleCount();
  try {
    return build(a_first);
  } catch (const Error& first) {
    // A sheet of the mesh that is cut can grow too thin to cut again where straight cuts come
    // close; the other way round the cuts fall elsewhere.
    try {
      return build(!a_first);
    } catch (const Error&) {
      throw Error(std::string(first.what()) + " (" + what_a + " and " + what_b + ", either way round)");
    }
  }
}

}  // namespace vdg::morph
