// Spherical-projection shape interpolation (vdg/morph/shape_morph.h, sphericalMorph).
//
// Kent, as Parent's "Computer Animation" describes it in 4.10 "Shape Interpolation, Metamorphosis"
// (../shared/reference/001_ee8e4823a552f1ff.txt): "Kent 'blows up' objects to surface of sphere and
// intersects crossing edges (arcs) to form intersection vertices. He then add new points and points
// from other object to each object and remaps onto both objects. Now each object has same topology
// and he can do vertex-to-vertex interpolation." (J. R. Kent, W. E. Carlson, R. E. Parent, "Shape
// transformation for polyhedral objects", SIGGRAPH 1992.)
//
// How it is built here:
//  1. Each mesh is checked closed, genus 0 (Euler characteristic 2) and star-shaped about its own
//     centre c (the bounding-box centre): every triangle's directions d = p - c have a positive
//     determinant (it faces away from c), and the spherical triangles cover the sphere once: their
//     areas sum to 4 pi (Van Oosterom and Strackee, "The solid angle of a plane triangle", IEEE
//     Trans. Biomed. Eng. 30(2), 1983: tan(E / 2) = det / (1 + a.b + b.c + c.a) for unit a, b, c).
//     Then the projection is a homeomorphism onto the sphere.
//  2. Overlay: every face of the overlay of the two spherical triangulations is the intersection of a
//     triangle a of A with a triangle b of B, a convex spherical polygon, found by clipping a against
//     the three great-circle half-spaces of b (Sutherland and Hodgman, "Reentrant polygon clipping",
//     CACM 17(1), 1974). Candidate pairs come from bounding caps in a grid. The clipping is
//     combinatorial: every polygon vertex is labelled (a vertex of a, a vertex of b, or the crossing
//     of an edge of a with the great circle of an edge of b) and its side of each plane of b is the
//     exact sign of one 3 x 3 determinant of input directions (see side() for the identities that
//     reduce a crossing's side to one). With exact signs, the polygons of neighbouring pairs agree on
//     every shared vertex, so welding by label gives a closed manifold mesh whatever the
//     degeneracies (coincident vertices, a vertex on an edge, overlapping edges). Every vertex of a
//     face is a strict corner of it (a corner of a or of b, or a crossing of their edges), so the
//     fan has no flat triangle.
//  3. Each overlay vertex is placed on A and on B: a vertex of A is itself on A and is found on B by
//     casting the ray from B's centre in its direction onto the triangle b it lies in (barycentric
//     weights det(d, e_j+1, e_j+2)); a crossing lies on an edge of A at the parameter where the edge's
//     direction meets the plane of the B edge's great circle (and on B likewise). The inbetween at t
//     is (1 - t) pa + t pb, vertex by vertex.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <span>
#include <string>
#include <unordered_map>
#include <vector>

#include "exact_orient.h"
#include "vdg/geom/error.h"
#include "vdg/geom/text.h"
#include "vdg/morph/mesh_checks.h"
#include "vdg/morph/shape_morph.h"

namespace vdg::morph {
namespace {

using detail::D3;

using detail::cross;
using detail::dot;
using detail::sub;
D3 normalized(const D3& a) {
  const double n = std::sqrt(dot(a, a));
  return n > 0 ? D3{a[0] / n, a[1] / n, a[2] / n} : D3{0, 0, 0};
}

// The exact sign of a 3 x 3 determinant: src/morph/exact_orient.h.
using detail::orientSign;
using detail::orientValue;

// ---- One mesh, checked and projected -----------------------------------------------------------

struct Projected {
  const TriMesh* mesh = nullptr;
  D3 centre{};
  std::vector<D3> dir;   // #V: position - centre (the direction the vertex is projected along)
  std::vector<D3> unit;  // #V: dir normalised (for the bounding caps only)

  D3 position(std::int32_t v) const {
    const float* p = &mesh->positions[static_cast<std::size_t>(v) * 3];
    return {p[0], p[1], p[2]};
  }
  const D3& d(std::int32_t v) const { return dir[static_cast<std::size_t>(v)]; }
  std::int32_t corner(std::size_t f, int k) const { return mesh->triangles[f * 3 + static_cast<std::size_t>(k)]; }
};

Projected project(const TriMesh& mesh, const std::string& what) {
  validateMesh(mesh, what);
  requireClosed(mesh, what);
  const int chi = eulerCharacteristic(mesh);
  if (chi != 2)
    throw Error(what + ": is not a single genus-0 surface (Euler characteristic " + std::to_string(chi) +
                "; a sphere-like mesh has 2): the spherical morph needs one star-shaped genus-0 mesh");
  Projected out;
  out.mesh = &mesh;
  // The bounding-box centre of the vertices the triangles use; (min + max) / 2 of floats is exact in double.
  D3 lo{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
        std::numeric_limits<double>::infinity()};
  D3 hi{-lo[0], -lo[1], -lo[2]};
  for (const std::int32_t v : mesh.triangles)
    for (int k = 0; k < 3; ++k) {
      const double x = mesh.positions[static_cast<std::size_t>(v) * 3 + static_cast<std::size_t>(k)];
      lo[k] = std::min(lo[k], x);
      hi[k] = std::max(hi[k], x);
    }
  for (int k = 0; k < 3; ++k) out.centre[k] = 0.5 * (lo[k] + hi[k]);
  out.dir.resize(mesh.vertexCount());
  out.unit.resize(mesh.vertexCount());
  for (std::size_t v = 0; v < mesh.vertexCount(); ++v) {
    out.dir[v] = sub(out.position(static_cast<std::int32_t>(v)), out.centre);
    out.unit[v] = normalized(out.dir[v]);
  }
  const std::string centre = "(" + numberText(out.centre[0], 6) + ", " + numberText(out.centre[1], 6) + ", " +
                             numberText(out.centre[2], 6) + ")";
  const std::size_t faces = mesh.triangleCount();
  for (std::size_t f = 0; f < faces; ++f)
    if (orientSign(out.d(out.corner(f, 0)), out.d(out.corner(f, 1)), out.d(out.corner(f, 2))) <= 0)
      throw Error(what + ": is not star-shaped about its centre " + centre + ": triangle " + std::to_string(f) +
                  " faces the centre or is seen edge-on from it");
  // All triangles positive: the spherical areas sum to 4 pi times the number of times they cover
  // the sphere (an integer); once means the projection is one-to-one.
  double area = 0;
  for (std::size_t f = 0; f < faces; ++f) {
    const D3& a = out.unit[static_cast<std::size_t>(out.corner(f, 0))];
    const D3& b = out.unit[static_cast<std::size_t>(out.corner(f, 1))];
    const D3& c = out.unit[static_cast<std::size_t>(out.corner(f, 2))];
    area += 2.0 * std::atan2(orientValue(a, b, c), 1.0 + dot(a, b) + dot(b, c) + dot(c, a));
  }
  const long covers = std::lround(area / (4.0 * M_PI));
  if (covers != 1) {
    // Name a triangle that overlaps triangle 0: one whose closed spherical triangle holds the
    // direction of triangle 0's centroid.
    const D3 g = normalized({out.unit[static_cast<std::size_t>(out.corner(0, 0))][0] +
                                 out.unit[static_cast<std::size_t>(out.corner(0, 1))][0] +
                                 out.unit[static_cast<std::size_t>(out.corner(0, 2))][0],
                             out.unit[static_cast<std::size_t>(out.corner(0, 0))][1] +
                                 out.unit[static_cast<std::size_t>(out.corner(0, 1))][1] +
                                 out.unit[static_cast<std::size_t>(out.corner(0, 2))][1],
                             out.unit[static_cast<std::size_t>(out.corner(0, 0))][2] +
                                 out.unit[static_cast<std::size_t>(out.corner(0, 1))][2] +
                                 out.unit[static_cast<std::size_t>(out.corner(0, 2))][2]});
    std::string pair;
    for (std::size_t f = 1; f < faces && pair.empty(); ++f) {
      bool inside = true;
      for (int k = 0; k < 3 && inside; ++k)
        inside = orientSign(out.d(out.corner(f, k)), out.d(out.corner(f, (k + 1) % 3)), g) >= 0;
      if (inside) pair = " (triangles 0 and " + std::to_string(f) + " overlap)";
    }
    throw Error(what + ": is not star-shaped about its centre " + centre +
                ": seen from it, its triangles cover the sphere " + std::to_string(covers) + " times" + pair);
  }
  return out;
}

// ---- Bounding caps of spherical triangles, and a grid of their centres --------------------------

struct Cap {
  D3 axis{};
  double radius = 0;  // radians, a little over the farthest corner
};

Cap capOf(const Projected& m, std::size_t f) {
  const D3& a = m.unit[static_cast<std::size_t>(m.corner(f, 0))];
  const D3& b = m.unit[static_cast<std::size_t>(m.corner(f, 1))];
  const D3& c = m.unit[static_cast<std::size_t>(m.corner(f, 2))];
  Cap cap;
  cap.axis = normalized({a[0] + b[0] + c[0], a[1] + b[1] + c[1], a[2] + b[2] + c[2]});
  for (const D3* p : {&a, &b, &c})
    cap.radius = std::max(cap.radius, std::acos(std::clamp(dot(cap.axis, *p), -1.0, 1.0)));
  // Margin for the rounding of the unit vectors and acos (both far below 1e-9).
  cap.radius += 1e-9;
  return cap;
}

// B's caps bucketed by their axes in a uniform grid over [-1, 1]^3 (compressed rows).
class CapGrid {
 public:
  CapGrid(const std::vector<Cap>& caps, double cell) : caps_(caps) {
    for (const Cap& c : caps) max_radius_ = std::max(max_radius_, c.radius);
    n_ = std::clamp(static_cast<int>(2.0 / std::max(cell, 1e-9)), 1, 48);
    start_.assign(static_cast<std::size_t>(n_) * n_ * n_ + 1, 0);
    for (const Cap& c : caps) ++start_[cellOf(c.axis) + 1];
    for (std::size_t i = 1; i < start_.size(); ++i) start_[i] += start_[i - 1];
    items_.resize(caps.size());
    std::vector<std::size_t> fill(start_.begin(), start_.end() - 1);
    for (std::size_t i = 0; i < caps.size(); ++i) items_[fill[cellOf(caps[i].axis)]++] = static_cast<std::int32_t>(i);
  }

  // Every cap that may overlap `cap`, in a fixed order.
  void query(const Cap& cap, std::vector<std::int32_t>& out) const {
    out.clear();
    const double reach = std::min(cap.radius + max_radius_, M_PI);
    const double chord = 2.0 * std::sin(0.5 * reach) + 1e-9;
    int lo[3], hi[3];
    for (int k = 0; k < 3; ++k) {
      lo[k] = coord(cap.axis[k] - chord);
      hi[k] = coord(cap.axis[k] + chord);
    }
    for (int x = lo[0]; x <= hi[0]; ++x)
      for (int y = lo[1]; y <= hi[1]; ++y)
        for (int z = lo[2]; z <= hi[2]; ++z) {
          const std::size_t cell = (static_cast<std::size_t>(x) * n_ + y) * n_ + z;
          for (std::size_t i = start_[cell]; i < start_[cell + 1]; ++i) {
            const Cap& other = caps_[static_cast<std::size_t>(items_[i])];
            const double sum = cap.radius + other.radius;
            if (sum >= M_PI || dot(cap.axis, other.axis) >= std::cos(sum)) out.push_back(items_[i]);
          }
        }
  }

 private:
  int coord(double x) const { return std::clamp(static_cast<int>((x + 1.0) * 0.5 * n_), 0, n_ - 1); }
  std::size_t cellOf(const D3& p) const {
    return (static_cast<std::size_t>(coord(p[0])) * n_ + coord(p[1])) * n_ + coord(p[2]);
  }
  const std::vector<Cap>& caps_;
  double max_radius_ = 0;
  int n_ = 1;
  std::vector<std::size_t> start_;
  std::vector<std::int32_t> items_;
};

// ---- Clipping a triangle of A against a triangle of B, combinatorially --------------------------

enum class Kind : std::uint8_t {
  kA,      // vertex `index` of a
  kB,      // vertex `index` of b
  kAntiB,  // the antipode of vertex `index` of b (only in an intermediate polygon)
  kCross,  // edge `index` of a (a_index -> a_index+1) crossing the great circle of edge `circle` of b
};

struct PolyVertex {
  Kind kind = Kind::kA;
  std::int8_t index = 0;
  std::int8_t circle = 0;
  // The polygon edge leaving this vertex lies on edge `support` of a (support_b false) or on the
  // great circle of edge `support` of b (b_k -> b_k+1; support_b true).
  bool support_b = false;
  std::int8_t support = 0;
};

constexpr int kMaxPolygon = 8;  // a triangle clipped by three half-spaces has at most 6 corners

struct Pair {
  std::array<const D3*, 3> a{}, b{};
  // side_a[i][k]: the side of a's vertex i of b's plane k (through b_k and b_k+1): exact sign of
  // det(b_k, b_k+1, a_i); positive is inside b.
  int side_a[3][3] = {};
};

[[noreturn]] void internalError(const char* what) {
  throw Error(std::string("spherical morph: internal error (") + what + "); please report the two meshes");
}

// The side of plane k of b on which polygon vertex v lies (exact).
int side(const Pair& pr, const PolyVertex& v, int k) {
  switch (v.kind) {
    case Kind::kA:
      return pr.side_a[v.index][k];
    case Kind::kB:
    case Kind::kAntiB: {
      const int on_plane = v.index == k || v.index == (k + 1) % 3;
      if (on_plane) return 0;
      return v.kind == Kind::kB ? 1 : -1;
    }
    case Kind::kCross: {
      const int c = v.circle;
      if (k == c) return 0;
      // The crossing X of edge (I, O) of a with circle c, I the endpoint inside plane c, is the
      // positive combination (I.m) O - (O.m) I = (I x O) x m, m = b_c x b_c+1. For the plane
      // n = b_k x b_k+1 of the next edge (k = c + 1), m x n = det(b) b_c+1, so
      // n.X = det(I x O, m, n) = (I x O).(m x n) = det(b) det(I, O, b_c+1); for the previous edge
      // (k = c - 1), m x n = -det(b) b_c and n.X = -det(b) det(I, O, b_c). det(b) > 0.
      const int e0 = v.index, e1 = (v.index + 1) % 3;
      const bool first_inside = pr.side_a[e0][c] > 0;
      const D3& in = *pr.a[first_inside ? e0 : e1];
      const D3& out = *pr.a[first_inside ? e1 : e0];
      if (k == (c + 1) % 3) return orientSign(in, out, *pr.b[(c + 1) % 3]);
      return -orientSign(in, out, *pr.b[c]);
    }
  }
  return 0;
}

// The point where the polygon edge leaving p (to a vertex on the other side of plane k, p's side
// sp) meets plane k.
PolyVertex crossing(const Pair& pr, const PolyVertex& p, int sp, int k) {
  PolyVertex x;
  if (!p.support_b) {
    const int e = p.support;
    if (pr.side_a[e][k] * pr.side_a[(e + 1) % 3][k] >= 0) internalError("an edge crosses a plane its ends do not");
    x.kind = Kind::kCross;
    x.index = static_cast<std::int8_t>(e);
    x.circle = static_cast<std::int8_t>(k);
    return x;
  }
  // Along circle c (travelled b_c -> b_c+1, inside on the left), plane c + 1 is left at +b_c+1 and
  // re-entered at -b_c+1; plane c - 1 is entered at +b_c and left at -b_c.
  const int c = p.support;
  const bool leaving = sp > 0;
  if (k == (c + 1) % 3) {
    x.kind = leaving ? Kind::kB : Kind::kAntiB;
    x.index = static_cast<std::int8_t>((c + 1) % 3);
  } else if (k == (c + 2) % 3) {
    x.kind = leaving ? Kind::kAntiB : Kind::kB;
    x.index = static_cast<std::int8_t>(c);
  } else {
    internalError("an edge on a circle crosses that circle");
  }
  return x;
}

// Sutherland-Hodgman against plane k. Returns the new vertex count; 0 when nothing of the polygon
// is strictly inside (the intersection has no area).
int clip(const Pair& pr, const PolyVertex* in, int n, int k, PolyVertex* out) {
  int s[kMaxPolygon];
  bool any_inside = false, any_outside = false;
  for (int i = 0; i < n; ++i) {
    s[i] = side(pr, in[i], k);
    any_inside = any_inside || s[i] > 0;
    any_outside = any_outside || s[i] < 0;
  }
  if (!any_inside) return 0;
  if (!any_outside) {
    std::copy(in, in + n, out);
    return n;
  }
  int m = 0;
  auto push = [&](const PolyVertex& v) {
    if (m == kMaxPolygon) internalError("a clipped polygon has too many corners");
    out[m++] = v;
  };
  for (int i = 0; i < n; ++i) {
    const int j = (i + 1) % n;
    const PolyVertex& p = in[i];
    if (s[i] > 0) {
      push(p);
      if (s[j] < 0) {
        PolyVertex x = crossing(pr, p, s[i], k);
        x.support_b = true;
        x.support = static_cast<std::int8_t>(k);
        push(x);
      }
    } else if (s[i] == 0) {
      PolyVertex v = p;
      if (s[j] < 0) {
        v.support_b = true;
        v.support = static_cast<std::int8_t>(k);
      }
      push(v);
    } else if (s[j] > 0) {
      PolyVertex x = crossing(pr, p, s[i], k);
      x.support_b = p.support_b;
      x.support = p.support;
      push(x);
    }
  }
  return m;
}

// ---- Welding ------------------------------------------------------------------------------------

// A common vertex's identity: a vertex of A, a vertex of B, or (edge of A, edge of B) for a crossing.
struct Key {
  std::uint64_t first = 0, second = 0;
  bool operator==(const Key&) const = default;
};
struct KeyHash {
  std::size_t operator()(const Key& k) const {
    std::uint64_t h = k.first * 0x9E3779B97F4A7C15ull ^ (k.second + 0x7F4A7C159E3779B9ull + (k.first << 6));
    h ^= h >> 31;
    h *= 0xBF58476D1CE4E5B9ull;
    h ^= h >> 29;
    return static_cast<std::size_t>(h);
  }
};

std::uint64_t edgeCode(std::int32_t u, std::int32_t v) {
  const auto lo = static_cast<std::uint64_t>(std::min(u, v)), hi = static_cast<std::uint64_t>(std::max(u, v));
  return (lo << 31) | hi;
}

// Barycentric weights of direction u in the spherical triangle t (directions t0, t1, t2 about its
// own centre): w_j proportional to det(t_j+1, t_j+2, u), with the exact zeros kept exact.
std::array<double, 3> weights(const std::array<const D3*, 3>& t, const D3& u, const int* exact_signs) {
  std::array<double, 3> w{};
  double sum = 0;
  for (int j = 0; j < 3; ++j) {
    w[j] = exact_signs[j] == 0 ? 0.0 : std::max(0.0, orientValue(*t[(j + 1) % 3], *t[(j + 2) % 3], u));
    sum += w[j];
  }
  if (!(sum > 0)) {  // u on a corner whose weight rounded away: fall back to the largest exact sign
    w = {0, 0, 0};
    for (int j = 0; j < 3; ++j)
      if (exact_signs[j] > 0) w[j] = 1;
    sum = w[0] + w[1] + w[2];
    if (!(sum > 0)) internalError("a point lies outside the triangle it was found in");
  }
  for (double& x : w) x /= sum;
  return w;
}

D3 blend(const std::array<D3, 3>& p, const std::array<double, 3>& w) {
  // An exact corner when one weight is 1 and the others 0.
  D3 r{};
  for (int k = 0; k < 3; ++k) r[k] = w[0] * p[0][k] + w[1] * p[1][k] + w[2] * p[2][k];
  return r;
}

D3 alongEdge(const D3& p, const D3& q, double s) {
  return {p[0] + s * (q[0] - p[0]), p[1] + s * (q[1] - p[1]), p[2] + s * (q[2] - p[2])};
}

// The parameter in [0, 1] where the segment between directions dp and dq (strictly on opposite
// sides of the plane through the origin with normal n) meets that plane: no cancellation.
double planeParameter(const D3& n, const D3& dp, const D3& dq) {
  const double vp = std::abs(dot(n, dp)), vq = std::abs(dot(n, dq));
  return vp + vq > 0 ? vp / (vp + vq) : 0.5;
}

// The corners of one overlay polygon, welded by identity: the id of corner `v` (of A's triangle
// with vertices va at pos_a and B's with vb at pos_b), a new vertex placed on A and on B (appended
// to pa and pb) the first time it is met. A crossing exactly at a corner of B's triangle is that
// corner.
using VertexIds = std::unordered_map<Key, std::int32_t, KeyHash>;
std::int32_t weldCorner(PolyVertex v, const Pair& pr, const std::array<std::int32_t, 3>& va,
                        const std::array<std::int32_t, 3>& vb, const std::array<D3, 3>& pos_a,
                        const std::array<D3, 3>& pos_b, VertexIds& ids, std::vector<double>& pa,
                        std::vector<double>& pb) {
  Key key;
  // A crossing exactly at a corner of b is that corner.
  int e0 = 0, e1 = 0, c = 0, in_first = 0;
  if (v.kind == Kind::kCross) {
    e0 = v.index;
    e1 = (v.index + 1) % 3;
    c = v.circle;
    in_first = pr.side_a[e0][c] > 0;
    const D3& in = *pr.a[in_first ? e0 : e1];
    const D3& out = *pr.a[in_first ? e1 : e0];
    if (orientSign(in, out, *pr.b[c]) == 0) {
      v.kind = Kind::kB;
      v.index = static_cast<std::int8_t>(c);
    } else if (orientSign(in, out, *pr.b[(c + 1) % 3]) == 0) {
      v.kind = Kind::kB;
      v.index = static_cast<std::int8_t>((c + 1) % 3);
    }
  }
  switch (v.kind) {
    case Kind::kA:
      key.first = static_cast<std::uint64_t>(va[v.index]);
      break;
    case Kind::kB:
      key.first = (std::uint64_t{1} << 62) | static_cast<std::uint64_t>(vb[v.index]);
      break;
    case Kind::kCross:
      key.first = (std::uint64_t{2} << 62) | edgeCode(va[e0], va[e1]);
      key.second = edgeCode(vb[c], vb[(c + 1) % 3]);
      break;
    case Kind::kAntiB:
      internalError("an antipode survived the clipping");
  }
  const auto [it, fresh] = ids.try_emplace(key, static_cast<std::int32_t>(pa.size() / 3));
  if (fresh) {
    D3 on_a{}, on_b{};
    if (v.kind == Kind::kA) {
      on_a = pos_a[v.index];
      int signs[3];
      for (int j = 0; j < 3; ++j) signs[j] = pr.side_a[v.index][(j + 1) % 3];
      on_b = blend(pos_b, weights(pr.b, *pr.a[v.index], signs));
    } else if (v.kind == Kind::kB) {
      on_b = pos_b[v.index];
      int signs[3];
      for (int j = 0; j < 3; ++j) signs[j] = orientSign(*pr.a[(j + 1) % 3], *pr.a[(j + 2) % 3], *pr.b[v.index]);
      on_a = blend(pos_a, weights(pr.a, *pr.b[v.index], signs));
    } else {
      const D3 m_b = cross(*pr.b[c], *pr.b[(c + 1) % 3]);
      on_a = alongEdge(pos_a[e0], pos_a[e1], planeParameter(m_b, *pr.a[e0], *pr.a[e1]));
      const D3 n_a = cross(*pr.a[e0], *pr.a[e1]);
      on_b = alongEdge(pos_b[c], pos_b[(c + 1) % 3], planeParameter(n_a, *pr.b[c], *pr.b[(c + 1) % 3]));
    }
    pa.insert(pa.end(), on_a.begin(), on_a.end());
    pb.insert(pb.end(), on_b.begin(), on_b.end());
  }
  return it->second;
}

}  // namespace

VertexMorph sphericalMorph(const TriMesh& a, const TriMesh& b, const std::string& what_a, const std::string& what_b) {
  const Projected ma = project(a, what_a);
  const Projected mb = project(b, what_b);
  const std::size_t fa = a.triangleCount(), fb = b.triangleCount();

  std::vector<Cap> caps_a(fa), caps_b(fb);
  double max_a = 0, max_b = 0;
  for (std::size_t f = 0; f < fa; ++f) max_a = std::max(max_a, (caps_a[f] = capOf(ma, f)).radius);
  for (std::size_t f = 0; f < fb; ++f) max_b = std::max(max_b, (caps_b[f] = capOf(mb, f)).radius);
  const CapGrid grid(caps_b, 2.0 * std::sin(0.5 * std::min(max_a + max_b, M_PI)));

  VertexIds ids;
  std::vector<double> pa, pb;
  std::vector<std::int32_t> triangles;
  std::vector<std::int32_t> candidates;
  for (std::size_t ia = 0; ia < fa; ++ia) {
    grid.query(caps_a[ia], candidates);
    Pair pr;
    std::array<std::int32_t, 3> va{}, vb{};
    std::array<D3, 3> pos_a{}, pos_b{};
    for (int i = 0; i < 3; ++i) {
      va[i] = ma.corner(ia, i);
      pr.a[i] = &ma.d(va[i]);
      pos_a[i] = ma.position(va[i]);
    }
    for (const std::int32_t ib32 : candidates) {
      const auto ib = static_cast<std::size_t>(ib32);
      for (int j = 0; j < 3; ++j) {
        vb[j] = mb.corner(ib, j);
        pr.b[j] = &mb.d(vb[j]);
        pos_b[j] = mb.position(vb[j]);
      }
      for (int i = 0; i < 3; ++i)
        for (int k = 0; k < 3; ++k) pr.side_a[i][k] = orientSign(*pr.b[k], *pr.b[(k + 1) % 3], *pr.a[i]);

      PolyVertex poly[2][kMaxPolygon];
      int n = 3;
      for (int i = 0; i < 3; ++i)
        poly[0][i] = PolyVertex{.kind = Kind::kA,
                                .index = static_cast<std::int8_t>(i),
                                .circle = 0,
                                .support_b = false,
                                .support = static_cast<std::int8_t>(i)};
      int cur = 0;
      for (int k = 0; k < 3 && n > 0; ++k) {
        n = clip(pr, poly[cur], n, k, poly[1 - cur]);
        cur = 1 - cur;
      }
      if (n < 3) continue;

      // Weld the polygon's corners by identity and place new ones on A and on B.
      std::int32_t corner_ids[kMaxPolygon];
      int m = 0;
      for (int i = 0; i < n; ++i) {
        const std::int32_t id = weldCorner(poly[cur][i], pr, va, vb, pos_a, pos_b, ids, pa, pb);
        if (m == 0 || corner_ids[m - 1] != id) corner_ids[m++] = id;
      }
      if (m > 1 && corner_ids[m - 1] == corner_ids[0]) --m;
      for (int i = 1; i + 1 < m; ++i)
        triangles.insert(triangles.end(), {corner_ids[0], corner_ids[i], corner_ids[i + 1]});
    }
  }
  VertexMorph morph(std::vector<float>(pa.begin(), pa.end()), std::vector<float>(pb.begin(), pb.end()),
                    std::move(triangles), "spherical morph");

  // The overlay of two sphere triangulations is one: anything else is a defect here, not bad input.
  TriMesh common = morph.at(0.0);
  try {
    requireClosed(common, "the common mesh");
  } catch (const Error& e) {
    throw Error(std::string("spherical morph of ") + what_a + " and " + what_b + ": internal error (" + e.what() +
                "); please report the two meshes");
  }
  if (eulerCharacteristic(common) != 2)
    throw Error(std::string("spherical morph of ") + what_a + " and " + what_b +
                ": internal error (the common mesh is not genus 0); please report the two meshes");
  return morph;
}

}  // namespace vdg::morph
