// Applying edit operations to key deformations (Rademacher 99, section 3.1.2; Parent 4.10).
#include "vdg/deform/edits.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <set>

#include "vdg/deform/ffd.h"
#include "vdg/geom/error.h"

namespace vdg {

const char* editKindName(EditKind kind) {
  switch (kind) {
    case EditKind::kDrag:
      return "drag";
    case EditKind::kPushPull:
      return "push_pull";
    case EditKind::kRotate:
      return "rotate";
    case EditKind::kScale:
      return "scale";
    case EditKind::kDisplace:
      return "displace";
    case EditKind::kFfd:
      return "ffd";
    case EditKind::kSquashStretch:
      return "squash_stretch";
    case EditKind::kAffine:
      return "affine";
  }
  return "?";
}

void validateEdits(std::span<const EditOp> ops, std::size_t vertex_count, const std::string& source) {
  for (std::size_t i = 0; i < ops.size(); ++i) {
    const EditOp& op = ops[i];
    const std::string at = source + ": ops[" + std::to_string(i) + "] (" + editKindName(op.kind) + "): ";
    if (op.vertex >= static_cast<std::int64_t>(vertex_count))
      throw Error(at + "'vertex' = " + std::to_string(op.vertex) + " is out of range (the mesh has " +
                  std::to_string(vertex_count) + " vertices)");
    for (std::int32_t v : op.vertices)
      if (static_cast<std::size_t>(v) >= vertex_count)
        throw Error(at + "'vertices' holds " + std::to_string(v) + ", out of range (the mesh has " +
                    std::to_string(vertex_count) + " vertices)");
  }
}

std::vector<EditReport> applyEdits(const Camera& camera, std::span<const std::int32_t> triangles,
                                   std::span<float> positions, std::span<const EditOp> ops,
                                   const std::optional<std::array<int, 2>>& image_size, const std::string& source) {
  const std::size_t n = positions.size() / 3;
  validateEdits(ops, n, source);
  const CameraFrame frame = cameraFrame(camera);
  Eigen::Matrix3d camera_axes;
  camera_axes << frame.right, frame.up, frame.back;
  std::vector<EditReport> reports;
  std::vector<float> before;
  for (std::size_t i = 0; i < ops.size(); ++i) {
    const EditOp& op = ops[i];
    const std::string at = source + ": ops[" + std::to_string(i) + "] (" + editKindName(op.kind) + "): ";
    before.assign(positions.begin(), positions.end());
    const auto seed = static_cast<std::int32_t>(op.vertex);
    std::vector<double> w;
    Eigen::Vector3d pivot = Eigen::Vector3d::Zero();
    if (op.vertex >= 0) {
      w = seedWeights(op.metric, op.falloff, positions, triangles, seed);
      pivot = Eigen::Vector3d(positions[3 * seed], positions[3 * seed + 1], positions[3 * seed + 2]);
    }
    auto centroid = [&]() -> Eigen::Vector3d {
      if (op.center) return *op.center;
      Eigen::Vector3d c = Eigen::Vector3d::Zero();
      const std::size_t count = op.vertices.empty() ? n : op.vertices.size();
      for (std::size_t k = 0; k < count; ++k) {
        const std::size_t v = op.vertices.empty() ? k : static_cast<std::size_t>(op.vertices[k]);
        c += Eigen::Vector3d(positions[3 * v], positions[3 * v + 1], positions[3 * v + 2]);
      }
      return c / static_cast<double>(std::max<std::size_t>(count, 1));
    };
    switch (op.kind) {
      case EditKind::kDrag: {
        Eigen::Vector2d delta = op.delta;
        if (op.delta_px) {
          if (!image_size) throw Error(at + "'delta_px' needs the drawing's size: give \"image_size\": [w, h]");
          const double depth = project(camera, (*image_size)[0], (*image_size)[1], pivot).depth;
          delta = imagePlaneDelta(camera, (*image_size)[0], (*image_size)[1], depth, *op.delta_px);
        }
        dragInImagePlane(camera, positions, w, delta);
        break;
      }
      case EditKind::kPushPull:
        pushPull(camera, positions, w, op.amount, op.push_mode);
        break;
      case EditKind::kRotate:
        rotateInImagePlane(camera, positions, w, pivot, op.angle_deg * std::numbers::pi / 180.0);
        break;
      case EditKind::kScale:
        scaleInImagePlane(camera, positions, w, pivot, op.factor);
        break;
      case EditKind::kDisplace:
        displaceVertices(positions, w, op.camera_frame ? Eigen::Vector3d(camera_axes * op.offset) : op.offset);
        break;
      case EditKind::kFfd: {
        const Eigen::Matrix3d lattice_frame = op.camera_frame ? camera_axes : Eigen::Matrix3d::Identity();
        FfdLattice lattice = ffdLatticeAround(positions, op.vertices, lattice_frame, op.degree, op.padding);
        const FfdBinding binding = bindFfd(lattice, positions, op.vertices);
        for (const FfdMove& m : op.moves) lattice.point(m.index[0], m.index[1], m.index[2]) += lattice_frame * m.offset;
        applyFfd(lattice, binding, positions);
        break;
      }
      case EditKind::kSquashStretch: {
        const Eigen::Vector3d axis = op.camera_frame ? Eigen::Vector3d(camera_axes * op.axis) : op.axis;
        applyAffine(positions, op.vertices, squashStretchMatrix(axis, op.stretch, op.preserve_volume), centroid(),
                    Eigen::Vector3d::Zero());
        break;
      }
      case EditKind::kAffine:
        applyAffine(positions, op.vertices, op.matrix, centroid(), op.translation);
        break;
    }
    EditReport report;
    for (std::size_t v = 0; v < n; ++v) {
      const double d = (Eigen::Vector3d(positions[3 * v], positions[3 * v + 1], positions[3 * v + 2]) -
                        Eigen::Vector3d(before[3 * v], before[3 * v + 1], before[3 * v + 2]))
                           .norm();
      if (!std::isfinite(d))
        throw Error(at + "produced a non-finite vertex position (vertex " + std::to_string(v) + ")");
      if (d > 0) {
        ++report.moved;
        report.max_displacement = std::max(report.max_displacement, d);
      }
    }
    reports.push_back(report);
  }
  return reports;
}

Camera cameraFromView(const Eigen::Vector3d& center, const Eigen::Vector3d& view, double distance, double height) {
  Camera c;
  const Eigen::Vector3d v = view.normalized();
  c.target = center;
  c.eye = center + v * distance;
  c.up = std::abs(v.y()) > 0.999 ? Eigen::Vector3d(0, 0, v.y() > 0 ? -1.0 : 1.0) : Eigen::Vector3d::UnitY();
  c.ortho_height = height;
  c.fov_deg = 0;
  return c;
}

}  // namespace vdg
