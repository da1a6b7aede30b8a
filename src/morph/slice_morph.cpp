// Chen's slices (vdg/morph/slice_morph.h): Parent, "Computer Animation", 4.10 "Shape Interpolation,
// Metamorphosis" (../shared/reference/001_ee8e4823a552f1ff.txt): cut both objects into slices,
// equal up the points of corresponding slices about the centre of their overlap, interpolate pairs
// of points and loft a surface through the slices.
#include "vdg/morph/slice_morph.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <unordered_map>
#include <vector>

#include "exact_orient.h"
#include "vdg/geom/error.h"
#include "vdg/geom/text.h"
#include "vdg/morph/mesh_checks.h"

namespace vdg::morph {
namespace {

struct Resampled {
  std::vector<double> points;           // slices * samples * 3: slice by slice, angle by angle
  std::array<double, 3> low{}, high{};  // the end vertices
};

// Throws unless the contour `loop` (indices into `pts`, wound counter-clockwise when `sense` is 1,
// clockwise when -1) is star-shaped about `centre`, with the centre inside its kernel: the kernel
// of a simple polygon is the intersection of the inner half-planes of its edges, so the centre
// must lie strictly on the inner side of every edge's supporting line (an exact orientation test
// per edge), and the contour must go round it once. Then every ray from the centre crosses the
// contour exactly once and the resampling keeps all of it; an edge that faces away from the centre
// or is seen edge-on from it would be hidden behind another part of the contour (a notch's walls)
// and lost. Zero-length edges (two crossings at one mesh vertex on the plane) constrain nothing.
void requireStarShaped(const std::vector<std::array<double, 2>>& pts, const std::vector<std::int32_t>& loop,
                       const std::array<double, 2>& centre, int sense, int ax, double level, const std::string& where) {
  // A point (pu, pw) of the cutting plane as "(x, y, z)", with no 1e-17 for a 0.
  auto text = [&](double pu, double pw) {
    std::array<double, 3> x{};
    x[static_cast<std::size_t>(ax)] = level;
    x[static_cast<std::size_t>((ax + 1) % 3)] = pu;
    x[static_cast<std::size_t>((ax + 2) % 3)] = pw;
    auto shown = [](double c) { return numberText(std::abs(c) < 1e-12 ? 0.0 : c, 6); };
    return "(" + shown(x[0]) + ", " + shown(x[1]) + ", " + shown(x[2]) + ")";
  };
  auto prefix = [&] { return where + " is not star-shaped about its centroid " + text(centre[0], centre[1]) + ": "; };
  double turned = 0;  // the angle the contour turns through about the centre
  for (std::size_t i = 0; i < loop.size(); ++i) {
    const auto& p = pts[static_cast<std::size_t>(loop[i])];
    const auto& q = pts[static_cast<std::size_t>(loop[(i + 1) % loop.size()])];
    if (p == q) continue;
    const int side = detail::orient2dSign(centre[0], centre[1], p[0], p[1], q[0], q[1]);
    if (side != sense)
      throw Error(prefix() + "the contour's edge from " + text(p[0], p[1]) + " to " + text(q[0], q[1]) +
                  (side == 0 ? " is seen edge-on from it" : " faces away from it") +
                  " (rays from the centroid would miss part of the contour)");
    const double au = p[0] - centre[0], aw = p[1] - centre[1], bu = q[0] - centre[0], bw = q[1] - centre[1];
    turned += std::atan2(std::abs(au * bw - aw * bu), au * bu + aw * bw);
  }
  // Every edge turns forwards, so the total is a whole number of turns; more than one is a contour
  // that overlaps itself.
  const long turns = std::lround(turned / (2.0 * M_PI));
  if (turns != 1)
    throw Error(prefix() + "the contour goes round it " + std::to_string(turns) + " times (it overlaps itself)");
}

// The area centroid (u, w) of a contour and twice its signed area (the shoelace formula).
std::array<double, 3> areaCentroid(const std::vector<std::array<double, 2>>& pts,
                                   const std::vector<std::int32_t>& loop) {
  double area2 = 0, cu = 0, cw = 0;
  for (std::size_t i = 0; i < loop.size(); ++i) {
    const auto& p = pts[static_cast<std::size_t>(loop[i])];
    const auto& q = pts[static_cast<std::size_t>(loop[(i + 1) % loop.size()])];
    const double cr = p[0] * q[1] - q[0] * p[1];
    area2 += cr;
    cu += (p[0] + q[0]) * cr;
    cw += (p[1] + q[1]) * cr;
  }
  return {cu / (3.0 * area2), cw / (3.0 * area2), area2};
}

// One mesh cut and resampled. (u, w) = the axes after `axis`, so that u x w = axis: angle theta
// runs counter-clockwise seen from the +axis side.
Resampled resample(const TriMesh& mesh, const SliceMorphOptions& o, const std::string& what) {
  validateMesh(mesh, what);
  requireClosed(mesh, what);
  const int ax = o.axis, u = (ax + 1) % 3, w = (ax + 2) % 3;
  const char* axis_name[3] = {"x", "y", "z"};
  auto coord = [&](std::int32_t v, int k) {
    return static_cast<double>(mesh.positions[static_cast<std::size_t>(v) * 3 + static_cast<std::size_t>(k)]);
  };
  Resampled r;
  std::int32_t lowest = mesh.triangles[0], highest = mesh.triangles[0];
  for (const std::int32_t v : mesh.triangles) {
    if (coord(v, ax) < coord(lowest, ax)) lowest = v;
    if (coord(v, ax) > coord(highest, ax)) highest = v;
  }
  for (int k = 0; k < 3; ++k) {
    r.low[k] = coord(lowest, k);
    r.high[k] = coord(highest, k);
  }
  const double lo = coord(lowest, ax), hi = coord(highest, ax);
  r.points.reserve(static_cast<std::size_t>(o.slices) * static_cast<std::size_t>(o.samples) * 3);

  std::unordered_map<std::uint64_t, std::int32_t> point_of_edge;
  std::vector<std::array<double, 2>> pts;
  std::vector<std::array<std::int32_t, 2>> links;
  std::vector<std::int32_t> loop;
  for (int s = 0; s < o.slices; ++s) {
    const double level = lo + (hi - lo) * (s + 0.5) / o.slices;
    const std::string where = what + ": the cut at " + axis_name[ax] + " = " + numberText(level, 6);
    point_of_edge.clear();
    pts.clear();
    links.clear();
    // Each triangle with corners on both sides (a corner at the level counts as above) crosses the
    // plane along a segment between two of its edges; a crossing is named by its undirected edge.
    auto point = [&](std::int32_t p, std::int32_t q) {
      const std::uint64_t key =
          (static_cast<std::uint64_t>(std::min(p, q)) << 32) | static_cast<std::uint32_t>(std::max(p, q));
      const auto [it, fresh] = point_of_edge.try_emplace(key, static_cast<std::int32_t>(pts.size()));
      if (fresh) {
        const double dp = coord(p, ax) - level, dq = coord(q, ax) - level;
        const double f = dp / (dp - dq);  // dp and dq on opposite sides: no cancellation
        pts.push_back({coord(p, u) + f * (coord(q, u) - coord(p, u)), coord(p, w) + f * (coord(q, w) - coord(p, w))});
        links.push_back({-1, -1});
      }
      return it->second;
    };
    for (std::size_t f = 0; f < mesh.triangleCount(); ++f) {
      const std::int32_t* t = &mesh.triangles[f * 3];
      std::int32_t ends[2];
      int n = 0;
      for (int k = 0; k < 3; ++k) {
        const std::int32_t p = t[k], q = t[(k + 1) % 3];
        if ((coord(p, ax) >= level) != (coord(q, ax) >= level)) ends[n++] = point(p, q);
      }
      if (n != 2) continue;
      for (int e = 0; e < 2; ++e) {
        auto& l = links[static_cast<std::size_t>(ends[e])];
        (l[0] < 0 ? l[0] : l[1]) = ends[1 - e];
      }
    }
    // Walk the loops (every crossing has two neighbours on a closed mesh); keep the first.
    std::vector<char> seen(pts.size(), 0);
    int loops = 0;
    for (std::size_t start = 0; start < pts.size(); ++start) {
      if (seen[start]) continue;
      ++loops;
      std::int32_t prev = -1, cur = static_cast<std::int32_t>(start);
      while (!seen[static_cast<std::size_t>(cur)]) {
        seen[static_cast<std::size_t>(cur)] = 1;
        if (loops == 1) loop.push_back(cur);
        const auto& l = links[static_cast<std::size_t>(cur)];
        const std::int32_t next = l[0] != prev ? l[0] : l[1];
        if (next < 0) throw Error(where + " is not a closed contour");  // not reached for a closed mesh
        prev = cur;
        cur = next;
      }
    }
    if (loops != 1)
      throw Error(where + " is " + std::to_string(loops) +
                  " contours; the slice morph needs one closed contour per cut");
    // The area centroid of the contour, the centre the rays start from.
    const auto [cu, cw, area2] = areaCentroid(pts, loop);
    if (std::abs(area2) <= 0) throw Error(where + " has no area");
    requireStarShaped(pts, loop, {cu, cw}, area2 > 0 ? 1 : -1, ax, level, where);
    // Rays at equal angles; each takes the farthest crossing of the contour.
    for (int j = 0; j < o.samples; ++j) {
      const double theta = 2.0 * M_PI * j / o.samples;
      const double du = std::cos(theta), dw = std::sin(theta);
      double best = -1;
      for (std::size_t i = 0; i < loop.size(); ++i) {
        const auto& p = pts[static_cast<std::size_t>(loop[i])];
        const auto& q = pts[static_cast<std::size_t>(loop[(i + 1) % loop.size()])];
        // centre + s d = p + r (q - p): solve by Cramer's rule.
        const double eu = q[0] - p[0], ew = q[1] - p[1];
        const double den = du * (-ew) - dw * (-eu);
        if (den == 0) continue;
        const double bu = p[0] - cu, bw = p[1] - cw;
        const double s_ray = (bu * (-ew) - bw * (-eu)) / den;
        const double r_edge = (du * bw - dw * bu) / den;
        if (r_edge >= 0 && r_edge <= 1 && s_ray >= 0) best = std::max(best, s_ray);
      }
      if (best < 0) throw Error(where + " is not star-shaped about its centroid (a ray from it misses the contour)");
      std::array<double, 3> x{};
      x[static_cast<std::size_t>(ax)] = level;
      x[static_cast<std::size_t>(u)] = cu + best * du;
      x[static_cast<std::size_t>(w)] = cw + best * dw;
      r.points.insert(r.points.end(), x.begin(), x.end());
    }
    loop.clear();
  }
  return r;
}

}  // namespace

double sliceMorphCost(const TriMesh& a, const TriMesh& b, const SliceMorphOptions& options) {
  return std::max(options.slices, 1) * (static_cast<double>(a.triangleCount()) +
                                        static_cast<double>(b.triangleCount()) + 2.0 * std::max(options.samples, 3));
}

VertexMorph sliceMorph(const TriMesh& a, const TriMesh& b, const SliceMorphOptions& options, const std::string& what_a,
                       const std::string& what_b) {
  if (options.axis < 0 || options.axis > 2) throw Error("slice morph: axis must be 0, 1 or 2");
  if (options.slices < 1 || options.slices > 100000) throw Error("slice morph: slices must be in [1, 100000]");
  if (options.samples < 3 || options.samples > 100000) throw Error("slice morph: samples must be in [3, 100000]");
  const Resampled ra = resample(a, options, what_a);
  const Resampled rb = resample(b, options, what_b);
  // Vertices: the slices' points, then the low and the high end.
  std::vector<float> pos_a(ra.points.begin(), ra.points.end()), pos_b(rb.points.begin(), rb.points.end());
  std::vector<std::int32_t> triangles;
  pos_a.insert(pos_a.end(), ra.low.begin(), ra.low.end());
  pos_a.insert(pos_a.end(), ra.high.begin(), ra.high.end());
  pos_b.insert(pos_b.end(), rb.low.begin(), rb.low.end());
  pos_b.insert(pos_b.end(), rb.high.begin(), rb.high.end());
  const std::int32_t m = options.samples, n = options.slices;
  const std::int32_t low = n * m, high = low + 1;
  auto at = [&](std::int32_t s, std::int32_t j) { return s * m + (j % m); };
  // Counter-clockwise seen from outside: theta runs counter-clockwise seen from +axis, so along a
  // band it runs to the right seen from outside.
  for (std::int32_t j = 0; j < m; ++j) triangles.insert(triangles.end(), {low, at(0, j + 1), at(0, j)});
  for (std::int32_t s = 0; s + 1 < n; ++s)
    for (std::int32_t j = 0; j < m; ++j)
      triangles.insert(triangles.end(),
                       {at(s, j), at(s, j + 1), at(s + 1, j + 1), at(s, j), at(s + 1, j + 1), at(s + 1, j)});
  for (std::int32_t j = 0; j < m; ++j) triangles.insert(triangles.end(), {high, at(n - 1, j), at(n - 1, j + 1)});
  return VertexMorph(std::move(pos_a), std::move(pos_b), std::move(triangles), "slice morph");
}

}  // namespace vdg::morph
