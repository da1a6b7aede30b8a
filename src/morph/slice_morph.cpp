// Chen's slice interpolation (Parent 4.10; vdg/morph/slice_morph.h has the method and contract).
#include "vdg/morph/slice_morph.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "vdg/geom/error.h"
#include "vdg/morph/mesh_checks.h"

namespace vdg::morph {
namespace {

std::string number(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.9g", v);
  return text;
}

void requireOptions(const SliceMorphOptions& o) {
  if (o.slices < 2 || o.slices > 100000)
    throw Error("slice morph: slices must be in [2, 100000], not " + std::to_string(o.slices));
  if (o.samples < 3 || o.samples > 100000)
    throw Error("slice morph: samples must be in [3, 100000], not " + std::to_string(o.samples));
  if (o.axis < 0 || o.axis > 2) throw Error("slice morph: axis must be 0, 1 or 2, not " + std::to_string(o.axis));
}

using Point2 = std::array<double, 2>;

// One directed segment of a cross-section, in the plane's coordinates (u, w).
struct Segment {
  Point2 p, q;
};

// The cross-section of `mesh` by the plane {x[axis] = h}: one segment per crossing triangle,
// directed from where the triangle's boundary goes up through the plane to where it comes down
// (a vertex counts as above when x[axis] >= h). A neighbouring triangle sees the shared edge's
// crossing the other way round, so the segments chain head to tail into closed loops. The
// crossing point of an edge is computed from its lower-indexed end, so both triangles get the
// same point bit for bit.
std::vector<Segment> crossSection(const TriMesh& mesh, int axis, double h) {
  const int u = (axis + 1) % 3, w = (axis + 2) % 3;
  auto coord = [&](std::int32_t v, int k) {
    return static_cast<double>(mesh.positions[static_cast<std::size_t>(v) * 3 + static_cast<std::size_t>(k)]);
  };
  auto crossing = [&](std::int32_t i, std::int32_t j) {
    if (j < i) std::swap(i, j);
    const double s = (h - coord(i, axis)) / (coord(j, axis) - coord(i, axis));
    return Point2{coord(i, u) + s * (coord(j, u) - coord(i, u)), coord(i, w) + s * (coord(j, w) - coord(i, w))};
  };
  std::vector<Segment> segments;
  for (std::size_t f = 0; f < mesh.triangleCount(); ++f) {
    const std::int32_t* t = &mesh.triangles[f * 3];
    Point2 up{}, down{};
    int ups = 0, downs = 0;
    for (int k = 0; k < 3; ++k) {
      const std::int32_t a = t[k], b = t[(k + 1) % 3];
      const bool a_above = coord(a, axis) >= h, b_above = coord(b, axis) >= h;
      if (!a_above && b_above) {
        up = crossing(a, b);
        ++ups;
      } else if (a_above && !b_above) {
        down = crossing(a, b);
        ++downs;
      }
    }
    if (ups == 1 && downs == 1) segments.push_back({up, down});
  }
  return segments;
}

double cross2(const Point2& a, const Point2& b) { return a[0] * b[1] - a[1] * b[0]; }

}  // namespace

SliceSamples sampleSlices(const TriMesh& mesh, const SliceMorphOptions& options, const std::string& what) {
  requireOptions(options);
  requireClosed(mesh, what);
  for (std::size_t i = 0; i < mesh.positions.size(); ++i)
    if (!std::isfinite(mesh.positions[i]))
      throw Error(what + ": vertex " + std::to_string(i / 3) + " has a coordinate that is not finite");
  const int axis = options.axis, u = (axis + 1) % 3, w = (axis + 2) % 3;
  double lo = std::numeric_limits<double>::max(), hi = -lo;
  for (std::size_t v = 0; v < mesh.vertexCount(); ++v) {
    lo = std::min(lo, static_cast<double>(mesh.positions[v * 3 + static_cast<std::size_t>(axis)]));
    hi = std::max(hi, static_cast<double>(mesh.positions[v * 3 + static_cast<std::size_t>(axis)]));
  }
  if (!(hi > lo)) throw Error(what + ": is flat across the slicing axis (no extent to slice)");
  const auto slices = static_cast<std::size_t>(options.slices), samples = static_cast<std::size_t>(options.samples);
  SliceSamples out;
  out.points.resize(slices * samples * 3);
  for (std::size_t k = 0; k < slices; ++k) {
    const double h = lo + (static_cast<double>(k) + 0.5) / static_cast<double>(slices) * (hi - lo);
    const std::string slice = what + ": slice " + std::to_string(k) + " (at " + "xyz"[axis] + " = " + number(h) + ")";
    const std::vector<Segment> segments = crossSection(mesh, axis, h);
    // The area centroid of the cross-section (shoelace sums over the closed, oriented loops).
    double area2 = 0, cu = 0, cw = 0;
    for (const Segment& s : segments) {
      const double c = cross2(s.p, s.q);
      area2 += c;
      cu += (s.p[0] + s.q[0]) * c;
      cw += (s.p[1] + s.q[1]) * c;
    }
    if (segments.empty() || !(std::abs(area2) > 0)) throw Error(slice + " is empty");
    const Point2 centre{cu / (3 * area2), cw / (3 * area2)};
    // Ray j from the centre crosses the cross-section exactly once when the centre lies inside one
    // loop that is star-shaped about it. A segment crosses the ray's line when its ends lie on
    // opposite sides (a point on the line counts as the left side); a loop's vertex is the same
    // point bit for bit in both its segments, so a line through it is counted exactly once.
    for (std::size_t j = 0; j < samples; ++j) {
      const double angle = 2.0 * M_PI * static_cast<double>(j) / static_cast<double>(samples);
      const Point2 d{std::cos(angle), std::sin(angle)};
      int hits = 0;
      double reach = 0;
      for (const Segment& s : segments) {
        const Point2 cp{s.p[0] - centre[0], s.p[1] - centre[1]};
        const Point2 cq{s.q[0] - centre[0], s.q[1] - centre[1]};
        const double side_p = cross2(d, cp), side_q = cross2(d, cq);
        if ((side_p >= 0) == (side_q >= 0)) continue;
        const Point2 e{s.q[0] - s.p[0], s.q[1] - s.p[1]};
        const double r = cross2(cp, e) / (side_q - side_p);  // the crossing's distance along the ray
        if (r > 0) {
          ++hits;
          reach = r;
        }
      }
      if (hits != 1)
        throw Error(slice + " is not star-shaped about its centre: the ray at " + number(angle * 180 / M_PI) +
                    " degrees crosses it " + std::to_string(hits) + " times, not once");
      double* p = &out.points[(k * samples + j) * 3];
      p[axis] = h;
      p[u] = centre[0] + reach * d[0];
      p[w] = centre[1] + reach * d[1];
    }
    if (k == 0) {
      out.bottom[static_cast<std::size_t>(axis)] = lo;
      out.bottom[static_cast<std::size_t>(u)] = centre[0];
      out.bottom[static_cast<std::size_t>(w)] = centre[1];
    }
    if (k + 1 == slices) {
      out.top[static_cast<std::size_t>(axis)] = hi;
      out.top[static_cast<std::size_t>(u)] = centre[0];
      out.top[static_cast<std::size_t>(w)] = centre[1];
    }
  }
  return out;
}

TriMesh loftSlices(const SliceSamples& sa, const SliceSamples& sb, double t, const SliceMorphOptions& options) {
  requireOptions(options);
  const auto slices = static_cast<std::size_t>(options.slices), samples = static_cast<std::size_t>(options.samples);
  if (sa.points.size() != slices * samples * 3 || sb.points.size() != sa.points.size())
    throw Error("slice morph: the slice samples do not match the options (" + std::to_string(slices) + " x " +
                std::to_string(samples) + " points)");
  if (!std::isfinite(t) || t < 0 || t > 1)
    throw Error("slice morph: t must be a finite number in [0, 1], not " + number(t));
  TriMesh m;
  m.positions.resize(sa.points.size() + 6);
  // Parent 4.10: "linearly interpolates between pairs of points, one from each slice".
  for (std::size_t i = 0; i < sa.points.size(); ++i)
    m.positions[i] = static_cast<float>((1 - t) * sa.points[i] + t * sb.points[i]);
  const std::size_t bottom = slices * samples, top = bottom + 1;
  for (std::size_t k = 0; k < 3; ++k) {
    m.positions[bottom * 3 + k] = static_cast<float>((1 - t) * sa.bottom[k] + t * sb.bottom[k]);
    m.positions[top * 3 + k] = static_cast<float>((1 - t) * sa.top[k] + t * sb.top[k]);
  }
  // "... and then lofts a new surface from the slices". The rays turn counter-clockwise about +axis
  // ((axis, u, w) is right-handed), so with slice k + 1 above slice k the triangle
  // (k, j) (k, j + 1) (k + 1, j + 1) has the normal tangent x axis = outward; the bottom cap turns
  // the other way round its apex and the top cap the same way.
  auto at = [&](std::size_t k, std::size_t j) { return static_cast<std::int32_t>(k * samples + j % samples); };
  const auto b = static_cast<std::int32_t>(bottom), tp = static_cast<std::int32_t>(top);
  for (std::size_t j = 0; j < samples; ++j) {
    m.triangles.insert(m.triangles.end(), {b, at(0, j + 1), at(0, j)});
    for (std::size_t k = 0; k + 1 < slices; ++k)
      m.triangles.insert(m.triangles.end(),
                         {at(k, j), at(k, j + 1), at(k + 1, j + 1), at(k, j), at(k + 1, j + 1), at(k + 1, j)});
    m.triangles.insert(m.triangles.end(), {tp, at(slices - 1, j), at(slices - 1, j + 1)});
  }
  return m;
}

TriMesh sliceMorph(const TriMesh& a, const TriMesh& b, double t, const SliceMorphOptions& options,
                   const std::string& what_a, const std::string& what_b) {
  requireOptions(options);
  if (!std::isfinite(t) || t < 0 || t > 1)
    throw Error("slice morph: t must be a finite number in [0, 1], not " + number(t));
  const SliceSamples sa = sampleSlices(a, options, what_a);
  const SliceSamples sb = sampleSlices(b, options, what_b);
  return loftSlices(sa, sb, t, options);
}

}  // namespace vdg::morph
