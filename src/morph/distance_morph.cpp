// Distance-field shape interpolation (Parent 4.10, "Shape Interpolation, Metamorphosis",
// "Distance Fields"): "For each voxel, calculate distance from surface of object ..., blend these
// distances to create new voxel space with new distances and then threshold to define surface of
// intermediate object." OpenVDB makes the signed distance volumes (tools::meshToSignedDistanceField)
// and polygonises the blend's zero level set (tools::volumeToMesh).
//
// The bands (docs/morph3d.md, "Memory"). The blend d(x) = (1 - t) dA(x) + t dB(x) crosses zero only
// where dA and dB differ in sign (or on a surface), i.e. inside one solid and outside the other.
// Where a volume holds no value OpenVDB returns +-background, which would move (at t = 0.5 even
// flatten) the blend's zero, so both values must be exact wherever the blend can cross zero:
//   - inside each mesh the volume is filled (interior band unbounded): every inside value is exact;
//   - outside A, the band must reach every point inside B that is outside A, and outside B every
//     point inside A that is outside B. bandReach() bounds that distance from a lattice of points
//     over the other mesh's box (the distance to a surface changes by at most the distance moved),
//     and options.band_voxels are added for the polygoniser's neighbourhood.
// Memory is estimated before anything is allocated: each volume at most fills its mesh's bounding
// box padded by its exterior band.
#include <openvdb/openvdb.h>
#include <openvdb/tools/MeshToVolume.h>
#include <openvdb/tools/VolumeToMesh.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <mutex>
#include <string>
#include <vector>

#include "d3.h"
#include "vdg/geom/error.h"
#include "vdg/morph/budget.h"
#include "vdg/morph/mesh_checks.h"
#include "vdg/morph/shape_morph.h"

namespace vdg::morph {
namespace {

using Vec3 = detail::D3;

// Bytes per active voxel of a float volume: the 4-byte value plus the leaf's masks and the tree
// above the leaves (OpenVDB's memUsage of a filled 8^3 leaf is about 4.3 bytes per voxel).
constexpr double kBytesPerVoxel = 4.5;
// Lattice points per axis over a box for the band bound, and the most point-triangle distances
// the bound may cost (fewer points per axis for larger meshes).
constexpr int kMaxBoundSamples = 17;
constexpr double kMaxBoundWork = 2e7;
// The default voxel: the larger bounding-box diagonal of A and B over this.
constexpr double kDefaultVoxelsPerDiagonal = 96.0;

void initialiseOpenVdb() {
  static std::once_flag once;
  std::call_once(once, [] { openvdb::initialize(); });
}

Vec3 vertex(const TriMesh& m, std::int32_t i) {
  const auto k = static_cast<std::size_t>(i) * 3;
  return {m.positions[k], m.positions[k + 1], m.positions[k + 2]};
}
using detail::dot;
using detail::sub;

// Squared distance from p to triangle (a, b, c) (Ericson, Real-Time Collision Detection, 5.1.5:
// the closest point by Voronoi regions of the vertices, edges and face).
double squaredDistanceToTriangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 ab = sub(b, a), ac = sub(c, a), ap = sub(p, a);
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  auto dist2 = [&](const Vec3& q) {
    const Vec3 d = sub(p, q);
    return dot(d, d);
  };
  auto along = [](const Vec3& o, const Vec3& e, double s) {
    return Vec3{o[0] + e[0] * s, o[1] + e[1] * s, o[2] + e[2] * s};
  };
  if (d1 <= 0 && d2 <= 0) return dist2(a);
  const Vec3 bp = sub(p, b);
  const double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) return dist2(b);
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return dist2(along(a, ab, d1 / (d1 - d3)));
  const Vec3 cp = sub(p, c);
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return dist2(c);
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return dist2(along(a, ac, d2 / (d2 - d6)));
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
    return dist2(along(b, sub(c, b), (d4 - d3) / ((d4 - d3) + (d5 - d6))));
  const double denom = va + vb + vc;
  if (!(denom > 0)) return std::min({dist2(a), dist2(b), dist2(c)});  // degenerate (zero area)
  const double v = vb / denom, w = vc / denom;
  return dist2({a[0] + ab[0] * v + ac[0] * w, a[1] + ab[1] * v + ac[1] * w, a[2] + ab[2] * v + ac[2] * w});
}

// Unsigned distance from p to `mesh`'s surface, and whether p is inside it (generalised winding
// number: the triangles' solid angles seen from p (Van Oosterom and Strackee) sum to 4 pi inside a
// closed mesh wound counter-clockwise seen from outside, to 0 outside).
struct Probe {
  double distance;
  bool inside;
};
Probe probe(const Vec3& p, const TriMesh& mesh) {
  double best = std::numeric_limits<double>::infinity(), solid_angle = 0;
  for (std::size_t f = 0; f < mesh.triangleCount(); ++f) {
    const Vec3 a = vertex(mesh, mesh.triangles[f * 3]), b = vertex(mesh, mesh.triangles[f * 3 + 1]),
               c = vertex(mesh, mesh.triangles[f * 3 + 2]);
    best = std::min(best, squaredDistanceToTriangle(p, a, b, c));
    const Vec3 u = sub(a, p), v = sub(b, p), w = sub(c, p);
    const double lu = std::sqrt(dot(u, u)), lv = std::sqrt(dot(v, v)), lw = std::sqrt(dot(w, w));
    const double triple =
        u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) + u[2] * (v[0] * w[1] - v[1] * w[0]);
    solid_angle += 2 * std::atan2(triple, lu * lv * lw + dot(u, v) * lw + dot(v, w) * lu + dot(w, u) * lv);
  }
  return {std::sqrt(best), solid_angle > 2 * M_PI};
}

// How far outside `outer` its exterior band must reach: an upper bound of dOuter(x) over every
// point x inside `inner` and outside `outer` (where the blend can cross zero; see the top). Over a
// lattice of spacing h (cell diagonal) on `inner`'s box, the lattice point p nearest any such x is
// within h/2 of it, and is inside `inner` or within h/2 of its surface; then dOuter(x) <= dOuter(p)
// + h/2 when p is outside `outer`, and <= h/2 when p is inside it (the segment px crosses the
// surface). So the bound is the largest such dOuter(p), plus h/2.
double bandReach(const Bounds& inner_box, const TriMesh& inner, const TriMesh& outer) {
  const double work = static_cast<double>(std::max<std::size_t>(1, inner.triangleCount() + outer.triangleCount()));
  const int n = std::clamp(static_cast<int>(std::cbrt(kMaxBoundWork / work)), 2, kMaxBoundSamples);
  Vec3 cell{};
  for (int k = 0; k < 3; ++k) cell[k] = (static_cast<double>(inner_box.max[k]) - inner_box.min[k]) / (n - 1);
  const double half_cell = 0.5 * std::sqrt(dot(cell, cell));
  double worst = 0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int l = 0; l < n; ++l) {
        const Vec3 p{inner_box.min[0] + cell[0] * i, inner_box.min[1] + cell[1] * j, inner_box.min[2] + cell[2] * l};
        const Probe in = probe(p, inner);
        if (!in.inside && in.distance > half_cell) continue;
        const Probe out = probe(p, outer);
        if (!out.inside) worst = std::max(worst, out.distance);
      }
  return worst + half_cell;
}

// Voxels of `box` padded by `pad` world units each side, at voxel size `voxel` (one extra voxel per
// axis for the polygoniser's neighbourhood).
double paddedBoxVoxels(const Bounds& box, double pad, double voxel) {
  double count = 1;
  for (int k = 0; k < 3; ++k) count *= std::ceil((static_cast<double>(box.max[k]) - box.min[k] + 2 * pad) / voxel) + 1;
  return count;
}

std::string number(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", v);
  return text;
}

openvdb::FloatGrid::Ptr distanceVolume(const TriMesh& mesh, const openvdb::math::Transform::Ptr& transform,
                                       double exterior_voxels) {
  std::vector<openvdb::Vec3s> points(mesh.vertexCount());
  for (std::size_t v = 0; v < points.size(); ++v)
    points[v] = openvdb::Vec3s(mesh.positions[v * 3], mesh.positions[v * 3 + 1], mesh.positions[v * 3 + 2]);
  std::vector<openvdb::Vec3I> triangles(mesh.triangleCount());
  for (std::size_t f = 0; f < triangles.size(); ++f)
    triangles[f] = openvdb::Vec3I(static_cast<openvdb::Index32>(mesh.triangles[f * 3]),
                                  static_cast<openvdb::Index32>(mesh.triangles[f * 3 + 1]),
                                  static_cast<openvdb::Index32>(mesh.triangles[f * 3 + 2]));
  // Interior unbounded (filled); exterior as computed by the caller.
  return openvdb::tools::meshToSignedDistanceField<openvdb::FloatGrid>(
      *transform, points, triangles, std::vector<openvdb::Vec4I>{}, static_cast<float>(exterior_voxels),
      std::numeric_limits<float>::max());
}

}  // namespace

struct DistanceMorph::Volumes {
  double voxel = 0;
  openvdb::FloatGrid::Ptr a, b;
};

DistanceMorph::DistanceMorph(const TriMesh& a, const TriMesh& b, const DistanceMorphOptions& options,
                             const std::string& what_a, const std::string& what_b) {
  requireClosed(a, what_a);
  requireClosed(b, what_b);
  validateMesh(a, what_a);
  validateMesh(b, what_b);
  if (!(options.band_voxels >= 3) || !std::isfinite(options.band_voxels))
    throw Error("distance morph: the band must be at least 3 voxels, got " + number(options.band_voxels));
  if (!(options.voxel_size >= 0) || !std::isfinite(options.voxel_size))
    throw Error("distance morph: the voxel size must be a finite number > 0 (or 0 for the default), got " +
                number(options.voxel_size));
  const Bounds box_a = computeBounds(a.positions), box_b = computeBounds(b.positions);
  double voxel = options.voxel_size;
  if (voxel == 0) voxel = std::max(box_a.diagonal(), box_b.diagonal()) / kDefaultVoxelsPerDiagonal;
  if (!(voxel > 0)) throw Error(what_a + " and " + what_b + ": both meshes are a single point; nothing to morph");

  // The exterior bands (see the top of this file), in world units, and the voxels they need.
  const double reach_a = bandReach(box_b, b, a), reach_b = bandReach(box_a, a, b);
  auto voxelsAt = [&](double size) {
    return paddedBoxVoxels(box_a, reach_a + options.band_voxels * size, size) +
           paddedBoxVoxels(box_b, reach_b + options.band_voxels * size, size);
  };
  const double voxels = voxelsAt(voxel);
  const auto limit = static_cast<double>(options.max_voxels);
  if (!(voxels <= limit)) {
    // The count falls about with the cube of the voxel size; step up from that guess until the
    // count fits, and round the size up to the 3 digits the message shows.
    // Bounded: a count past what a double holds (--voxel 1e-300 gives +infinity, and the guess
    // infinity or NaN) is handed to the bounded search instead of looping for ever.
    double enough = voxel * std::cbrt(voxels / limit);
    bool found = false;
    for (int tries = 0; tries < 1000 && std::isfinite(enough) && enough > 0; ++tries) {
      const double shown = roundUpTo3Digits(enough);
      if (voxelsAt(shown) <= limit) {
        enough = shown;
        found = true;
        break;
      }
      enough *= 1.02;
    }
    if (!found) enough = smallestFittingSize(voxelsAt, voxel, limit);
    const std::string need = std::isfinite(voxels) ? number(voxels) + " voxels (about " +
                                                         number(voxels * kBytesPerVoxel / 1048576.0) + " MiB)"
                                                   : "more than 1e308 voxels";
    throw Error(what_a + " and " + what_b + ": the distance volumes at voxel size " + number(voxel) + " need " + need +
                ", more than the limit of " + number(limit) + "; use a --voxel of at least " + number(enough));
  }
  const double pad_a = reach_a + options.band_voxels * voxel, pad_b = reach_b + options.band_voxels * voxel;

  initialiseOpenVdb();
  volumes_ = std::make_unique<Volumes>();
  volumes_->voxel = voxel;
  const auto transform = openvdb::math::Transform::createLinearTransform(voxel);
  volumes_->a = distanceVolume(a, transform, pad_a / voxel);
  volumes_->b = distanceVolume(b, transform, pad_b / voxel);
}

DistanceMorph::~DistanceMorph() = default;
DistanceMorph::DistanceMorph(DistanceMorph&&) noexcept = default;
DistanceMorph& DistanceMorph::operator=(DistanceMorph&&) noexcept = default;

TriMesh DistanceMorph::at(double t) const {
  if (!(t >= 0 && t <= 1)) throw Error("distance morph: t must be in [0, 1], got " + number(t));
  // Parent 4.10, Distance Fields: blend the distances, d = (1 - t) dA + t dB, voxel by voxel. A
  // voxel outside a band takes that volume's +-background (never where the blend can cross zero).
  const openvdb::FloatGrid& ga = *volumes_->a;
  const openvdb::FloatGrid& gb = *volumes_->b;
  const auto s = static_cast<float>(t);
  const float background = (1 - s) * ga.background() + s * gb.background();
  openvdb::FloatGrid blend(background);
  blend.setTransform(ga.transform().copy());
  blend.setGridClass(openvdb::GRID_LEVEL_SET);
  blend.tree().combine2Extended(ga.tree(), gb.tree(), [s](openvdb::CombineArgs<float>& args) {
    args.setResult((1 - s) * args.a() + s * args.b());
    args.setResultIsActive(args.aIsActive() || args.bIsActive());
  });

  // Threshold at zero: the zero level set, polygonised without adaptivity (quads and triangles).
  std::vector<openvdb::Vec3s> points;
  std::vector<openvdb::Vec3I> triangles;
  std::vector<openvdb::Vec4I> quads;
  openvdb::tools::volumeToMesh(blend, points, triangles, quads, 0.0, 0.0);

  TriMesh out;
  out.positions.reserve(points.size() * 3);
  for (const openvdb::Vec3s& p : points) out.positions.insert(out.positions.end(), {p.x(), p.y(), p.z()});
  out.triangles.reserve((triangles.size() + quads.size() * 2) * 3);
  // volumeToMesh winds its polygons clockwise seen from outside (negative inside), so each is
  // reversed to TriMesh's counter-clockwise; a quad (0 1 2 3) becomes (0 3 2) and (0 2 1).
  auto index = [](openvdb::Index32 i) { return static_cast<std::int32_t>(i); };
  for (const openvdb::Vec3I& f : triangles)
    out.triangles.insert(out.triangles.end(), {index(f[0]), index(f[2]), index(f[1])});
  for (const openvdb::Vec4I& q : quads) {
    out.triangles.insert(out.triangles.end(), {index(q[0]), index(q[3]), index(q[2])});
    out.triangles.insert(out.triangles.end(), {index(q[0]), index(q[2]), index(q[1])});
  }
  return out;
}

double distanceMorphFrameCost(const DistanceMorph& morph) {
  return 4.0 * static_cast<double>(morph.activeVoxelCount());
}

double DistanceMorph::voxelSize() const { return volumes_->voxel; }

std::size_t DistanceMorph::activeVoxelCount() const {
  return static_cast<std::size_t>(volumes_->a->activeVoxelCount() + volumes_->b->activeVoxelCount());
}

std::size_t DistanceMorph::memoryBytes() const {
  return static_cast<std::size_t>(volumes_->a->memUsage() + volumes_->b->memUsage());
}

}  // namespace vdg::morph
