// The polygoniser of the implicit surfaces (Parent 4.11; vdg/morph/polygonise.h): the fields of
// vdg/morph/implicit.h sampled on a grid and meshed with OpenVDB's volumeToMesh.
#include "vdg/morph/polygonise.h"

#include <openvdb/openvdb.h>
#include <openvdb/tools/Dense.h>
#include <openvdb/tools/VolumeToMesh.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "vdg/geom/error.h"
#include "vdg/geom/parallel.h"
#include "vdg/geom/text.h"
#include "vdg/morph/mesh_checks.h"

namespace vdg::morph {
namespace {

// A primitive's support box in grid indices, [lo, hi] per axis (inclusive, within the grid).
struct Splat {
  std::size_t index;
  int lo[3], hi[3];
};

// The boxes of the active primitives whose support reaches the grid of n[0] x n[1] x n[2] points
// at `origin`, spacing h.
std::vector<Splat> splatBoxes(const BlobModel& model, double h, const Eigen::Vector3d& origin, const int n[3]) {
  const auto& prims = model.primitives();
  const double T = model.threshold();
  std::vector<Splat> splats;
  for (std::size_t i = 0; i < prims.size(); ++i) {
    if (!model.active(i) || prims[i].strength == 0) continue;
    const double r = supportRadius(prims[i], T);
    if (!(r > 0)) continue;
    Splat s{i, {}, {}};
    bool empty = false;
    for (int a = 0; a < 3; ++a) {
      const double lo = std::ceil((prims[i].center[a] - r - origin[a]) / h);
      const double hi = std::floor((prims[i].center[a] + r - origin[a]) / h);
      s.lo[a] = static_cast<int>(std::clamp(lo, 0.0, static_cast<double>(n[a] - 1)));
      s.hi[a] = static_cast<int>(std::clamp(hi, -1.0, static_cast<double>(n[a] - 1)));
      if (lo > n[a] - 1 || hi < 0 || s.lo[a] > s.hi[a]) empty = true;
    }
    if (!empty) splats.push_back(s);
  }
  return splats;
}

}  // namespace

double polygoniseCost(const BlobModel& model, double voxel_size) {
  const Eigen::AlignedBox3d box = model.bounds();
  if (box.isEmpty()) return 0;
  const double h = voxel_size > 0 ? voxel_size : defaultVoxelSize(box);
  if (!(h > 0) || !std::isfinite(h)) return std::numeric_limits<double>::infinity();
  const Eigen::Vector3d dims = gridDimensions(box, h);
  const double voxels = dims.prod();
  // Past what an int indexes the grid is refused by the voxel budget anyway: the count is enough.
  if (!(dims.maxCoeff() < 1e9)) return voxels;
  const int n[3] = {static_cast<int>(dims.x()), static_cast<int>(dims.y()), static_cast<int>(dims.z())};
  const Eigen::Vector3d origin = box.min() - Eigen::Vector3d::Constant(kGridPadding * h);
  const std::vector<Splat> splats = splatBoxes(model, h, origin, n);
  double cost = 2 * voxels + dims.x() * dims.y() * static_cast<double>(splats.size());
  for (const Splat& s : splats) {
    double box_voxels = 1;
    for (int a = 0; a < 3; ++a) box_voxels *= s.hi[a] - s.lo[a] + 1;
    cost += box_voxels;
  }
  return cost;
}

TriMesh polygonise(const BlobModel& model, const PolygoniseOptions& options, const std::string& what) {
  if (!std::isfinite(options.voxel_size) || options.voxel_size < 0)
    throw Error(what + ": voxel size must be a finite number >= 0, got " + numberText(options.voxel_size));
  const Eigen::AlignedBox3d box = model.bounds();
  if (box.isEmpty()) return {};
  const double h = options.voxel_size > 0 ? options.voxel_size : defaultVoxelSize(box);
  if (!(h > 0) || !std::isfinite(gridVoxelCount(box, h)))
    throw Error(what + ": voxel size " + numberText(h) + " does not fit the blobs' extent");
  checkVoxelBudget(box, h, options.max_voxels, what);

  const Eigen::Vector3d dims = gridDimensions(box, h);
  const int nx = static_cast<int>(dims.x()), ny = static_cast<int>(dims.y()), nz = static_cast<int>(dims.z());
  // Grid point (i, j, k) lies at origin + h (i, j, k); the box starts kGridPadding voxels in.
  const Eigen::Vector3d origin = box.min() - Eigen::Vector3d::Constant(kGridPadding * h);
  const double T = model.threshold();

  // Dense samples of T - F (OpenVDB's volumeToMesh calls values below the isovalue 0 inside, so
  // inside, where F > T, is negative), z fastest (OpenVDB's LayoutZYX). Primitives are splatted
  // into the grid within their support boxes only.
  const std::size_t count = static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny) * static_cast<std::size_t>(nz);
  std::vector<float> values(count);
  const auto& prims = model.primitives();
  const int n[3] = {nx, ny, nz};
  const std::vector<Splat> splats = splatBoxes(model, h, origin, n);
  vdg::detail::parallelChunks(static_cast<std::size_t>(nx), 1, [&](std::size_t begin, std::size_t end) {
    std::vector<double> row(static_cast<std::size_t>(nz));
    for (std::size_t i = begin; i < end; ++i) {
      const int ii = static_cast<int>(i);
      for (int j = 0; j < ny; ++j) {
        std::fill(row.begin(), row.end(), 0.0);
        for (const Splat& s : splats) {
          if (ii < s.lo[0] || ii > s.hi[0] || j < s.lo[1] || j > s.hi[1]) continue;
          const BlobPrimitive& p = prims[s.index];
          const double dx = origin.x() + h * ii - p.center.x(), dy = origin.y() + h * j - p.center.y();
          for (int k = s.lo[2]; k <= s.hi[2]; ++k) {
            const double dz = origin.z() + h * k - p.center.z();
            row[static_cast<std::size_t>(k)] += primitiveField(p, std::sqrt(dx * dx + dy * dy + dz * dz));
          }
        }
        float* out = values.data() + (i * static_cast<std::size_t>(ny) + static_cast<std::size_t>(j)) * nz;
        for (int k = 0; k < nz; ++k) out[k] = static_cast<float>(T - row[static_cast<std::size_t>(k)]);
      }
    }
  });

  openvdb::initialize();
  const openvdb::CoordBBox bbox(openvdb::Coord(0, 0, 0), openvdb::Coord(nx - 1, ny - 1, nz - 1));
  openvdb::tools::Dense<float, openvdb::tools::LayoutZYX> dense(bbox, values.data());
  openvdb::FloatGrid::Ptr grid = openvdb::FloatGrid::create(static_cast<float>(T));
  openvdb::tools::copyFromDense(dense, *grid, 0.0f);
  std::vector<float>().swap(values);
  openvdb::math::Transform::Ptr xform = openvdb::math::Transform::createLinearTransform(h);
  xform->postTranslate(openvdb::Vec3d(origin.x(), origin.y(), origin.z()));
  grid->setTransform(xform);

  std::vector<openvdb::Vec3s> points;
  std::vector<openvdb::Vec3I> tris;
  std::vector<openvdb::Vec4I> quads;
  openvdb::tools::volumeToMesh(*grid, points, tris, quads, 0.0, 0.0);
  grid.reset();

  TriMesh mesh;
  mesh.positions.reserve(points.size() * 3);
  for (const openvdb::Vec3s& p : points) {
    mesh.positions.push_back(p.x());
    mesh.positions.push_back(p.y());
    mesh.positions.push_back(p.z());
  }
  const auto pos = [&](unsigned v) { return Eigen::Vector3f(points[v].x(), points[v].y(), points[v].z()); };
  // OpenVDB's polygons wind counter-clockwise seen from the positive side (outside, F < T), as
  // vdg's meshes do (the tests check the signed volume).
  const auto add = [&](unsigned a, unsigned b, unsigned c) {
    mesh.triangles.push_back(static_cast<std::int32_t>(a));
    mesh.triangles.push_back(static_cast<std::int32_t>(b));
    mesh.triangles.push_back(static_cast<std::int32_t>(c));
  };
  mesh.triangles.reserve(tris.size() * 3 + quads.size() * 6);
  for (const openvdb::Vec3I& t : tris) add(t[0], t[1], t[2]);
  for (const openvdb::Vec4I& q : quads) {
    // Split along the shorter diagonal (better-shaped triangles).
    if ((pos(q[0]) - pos(q[2])).squaredNorm() <= (pos(q[1]) - pos(q[3])).squaredNorm()) {
      add(q[0], q[1], q[2]);
      add(q[0], q[2], q[3]);
    } else {
      add(q[0], q[1], q[3]);
      add(q[1], q[2], q[3]);
    }
  }
  if (mesh.triangles.empty()) return {};
  requireClosed(mesh, what + ": polygonised surface");
  return mesh;
}

}  // namespace vdg::morph
