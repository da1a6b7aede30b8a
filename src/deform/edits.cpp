// Applying edit operations to key deformations (Rademacher 99, section 3.1.2; Parent 4.10).
#include "vdg/deform/edits.h"
#include "vdg/deform/pick.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <set>
#include <sstream>

#include "vdg/deform/ffd.h"
#include "vdg/geom/error.h"
#include "vdg/geom/text.h"

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
    case EditKind::kSkeleton:
      return "skeleton";
    case EditKind::kLines:
      return "lines";
  }
  return "?";
}

namespace {

// The picked vertex shared by the image-plane tools, or nullptr for whole-mesh tools.
const VertexPick* pickOf(const EditOp& op) {
  return std::visit(
      [](const auto& o) -> const VertexPick* {
        if constexpr (requires { o.pick; })
          return &o.pick;
        else
          return nullptr;
      },
      op);
}

const std::vector<std::int32_t>* verticesOf(const EditOp& op) {
  return std::visit(
      [](const auto& o) -> const std::vector<std::int32_t>* {
        if constexpr (requires { o.vertices; })
          return &o.vertices;
        else
          return nullptr;
      },
      op);
}

std::optional<EditOpProblem> problem(const std::string& field, const std::string& message) {
  return EditOpProblem{"'" + field + "'", message};
}

template <typename Vec>
std::optional<EditOpProblem> finiteVector(const Vec& v, const char* field) {
  if (!v.allFinite()) return problem(field, "must hold finite numbers");
  return std::nullopt;
}

std::optional<EditOpProblem> checkCenter(const std::optional<Eigen::Vector3d>& center) {
  if (center) return finiteVector(*center, "center");
  return std::nullopt;
}

std::optional<EditOpProblem> checkPick(const VertexPick& p) {
  if (p.point && p.pixel) return problem("pixel", "give one of 'vertex', 'point' or 'pixel', not several");
  if (p.point) {
    if (auto f = finiteVector(*p.point, "point")) return f;
  } else if (p.pixel) {
    if (auto f = finiteVector(*p.pixel, "pixel")) return f;
  } else if (p.vertex < 0) {
    return problem("vertex", "must be >= 0, got " + std::to_string(p.vertex));
  }
  if (!(p.falloff.radius > 0) || !std::isfinite(p.falloff.radius))
    return problem("radius", "must be > 0 and finite, got " + numberText(p.falloff.radius, 10));
  if (!(p.falloff.power >= 0) || !std::isfinite(p.falloff.power))
    return problem("power", "must be >= 0 and finite, got " + numberText(p.falloff.power, 10));
  return std::nullopt;
}

std::optional<EditOpProblem> checkFields(const DragOp& o) {
  if (o.delta_px) return finiteVector(*o.delta_px, "delta_px");
  return finiteVector(o.delta, "delta");
}
std::optional<EditOpProblem> checkFields(const PushPullOp& o) {
  if (!std::isfinite(o.amount)) return problem("amount", "must be a finite number");
  return std::nullopt;
}
std::optional<EditOpProblem> checkFields(const RotateOp& o) {
  if (!std::isfinite(o.angle_deg)) return problem("angle_deg", "must be a finite number");
  return std::nullopt;
}
std::optional<EditOpProblem> checkFields(const ScaleOp& o) {
  if (!o.factor.allFinite() || !(o.factor.minCoeff() > 0))
    return problem("factor", "must be > 0 and finite, got [" + numberText(o.factor.x(), 10) + ", " +
                                 numberText(o.factor.y(), 10) + "]");
  return std::nullopt;
}
std::optional<EditOpProblem> checkFields(const DisplaceOp& o) { return finiteVector(o.offset, "offset"); }
std::optional<EditOpProblem> checkFields(const FfdOp& o) {
  for (int a = 0; a < 3; ++a)
    if (o.degree[a] < 1 || o.degree[a] > kMaxFfdDegree)
      return problem("degree", "must hold three integers from 1 to " + std::to_string(kMaxFfdDegree) + ", got " +
                                   std::to_string(o.degree[a]));
  if (!(o.padding >= 0) || !(o.padding <= kMaxFfdPadding))
    return problem("padding",
                   "must be from 0 to " + numberText(kMaxFfdPadding, 10) + ", got " + numberText(o.padding, 10));
  for (std::size_t m = 0; m < o.moves.size(); ++m) {
    const std::string at = "'moves'[" + std::to_string(m) + "]";
    for (int a = 0; a < 3; ++a)
      if (o.moves[m].index[a] < 0 || o.moves[m].index[a] > o.degree[a])
        return EditOpProblem{at + ".'index'", "component " + std::to_string(a) + " = " +
                                                  std::to_string(o.moves[m].index[a]) + " is out of range [0, " +
                                                  std::to_string(o.degree[a]) + "]"};
    if (!o.moves[m].offset.allFinite()) return EditOpProblem{at + ".'offset'", "must hold finite numbers"};
  }
  return std::nullopt;
}
std::optional<EditOpProblem> checkFields(const SquashStretchOp& o) {
  if (!o.axis.allFinite() || !(o.axis.norm() > 0)) return problem("axis", "must be a finite, non-zero vector");
  if (!(o.factor > 0) || !std::isfinite(o.factor))
    return problem("factor", "must be > 0 and finite, got " + numberText(o.factor, 10));
  return checkCenter(o.center);
}
std::optional<EditOpProblem> checkFields(const AffineOp& o) {
  if (!o.matrix.allFinite()) return problem("matrix", "must hold finite numbers");
  if (auto p = finiteVector(o.translation, "translation")) return p;
  return checkCenter(o.center);
}

std::optional<EditOpProblem> wireProblem(const std::vector<Eigen::Vector3d>& joints, const char* field) {
  const auto p = checkSkeletonWire(joints);
  if (!p) return std::nullopt;
  if (p->count) return problem(field, p->message);
  return EditOpProblem{"'" + std::string(field) + "'[" + std::to_string(p->joint) + "]", p->message};
}
std::optional<EditOpProblem> checkFields(const SkeletonOp& o) {
  if (auto p = wireProblem(o.rest, "rest")) return p;
  if (o.posed.size() != o.rest.size())
    return problem("posed", "has " + std::to_string(o.posed.size()) + " joints, 'rest' has " +
                                std::to_string(o.rest.size()) + " (each rest joint needs its posed position)");
  if (auto p = wireProblem(o.posed, "posed")) return p;
  if (o.falloff) {
    if (!(o.falloff->radius > 0) || !std::isfinite(o.falloff->radius))
      return problem("radius", "must be > 0 and finite, got " + numberText(o.falloff->radius, 10));
    if (!(o.falloff->power >= 0) || !std::isfinite(o.falloff->power))
      return problem("power", "must be >= 0 and finite, got " + numberText(o.falloff->power, 10));
  }
  return std::nullopt;
}
std::optional<EditOpProblem> checkFields(const LinesOp& o) {
  if (auto p = checkFeatureLines(o.pairs, o.settings)) return EditOpProblem{p->field, p->message};
  return std::nullopt;
}

// The seed vertex of `pick`: its index, or the vertex its point or pixel names on `positions`.
std::int32_t pickedVertex(const VertexPick& pick, const Camera& camera, std::span<const std::int32_t> triangles,
                          std::span<const float> positions, const std::optional<std::array<int, 2>>& image_size,
                          const std::string& at) {
  if (pick.point) {
    if (auto v = nearestVertex(positions, *pick.point)) return *v;
    throw Error(at + ".'point': the mesh has no vertex");
  }
  if (!pick.pixel) return pick.vertex;
  if (!image_size) throw Error(at + ".'pixel': needs the drawing's size: give \"image_size\": [w, h]");
  if (auto v = vertexAtPixel(positions, triangles, camera, (*image_size)[0], (*image_size)[1], *pick.pixel)) return *v;
  throw Error(at + ".'pixel': [" + numberText(pick.pixel->x(), 10) + ", " + numberText(pick.pixel->y(), 10) +
              "] sees no front face of the mesh in the key camera (its ray misses the model)");
}

}  // namespace

std::optional<EditOpProblem> checkEditOp(const EditOp& op) {
  if (const VertexPick* pick = pickOf(op))
    if (auto p = checkPick(*pick)) return p;
  if (const auto* vertices = verticesOf(op))
    for (std::int32_t v : *vertices)
      if (v < 0) return problem("vertices", "must hold vertex indices >= 0, got " + std::to_string(v));
  return std::visit([](const auto& o) { return checkFields(o); }, op);
}

void validateEdits(std::span<const EditOp> ops, std::size_t vertex_count, const std::string& source) {
  for (std::size_t i = 0; i < ops.size(); ++i) {
    const EditOp& op = ops[i];
    const std::string at = source + ": 'ops'[" + std::to_string(i) + "] (" + editKindName(op) + ").";
    if (auto p = checkEditOp(op)) throw Error(at + p->field + ": " + p->message);
    const std::string range = " is out of range (the mesh has " + std::to_string(vertex_count) + " vertices)";
    if (const VertexPick* pick = pickOf(op); pick && !pick->point && !pick->pixel)
      if (static_cast<std::size_t>(pick->vertex) >= vertex_count)
        throw Error(at + "'vertex': " + std::to_string(pick->vertex) + range);
    if (const auto* vertices = verticesOf(op))
      for (std::int32_t v : *vertices)
        if (static_cast<std::size_t>(v) >= vertex_count) throw Error(at + "'vertices': " + std::to_string(v) + range);
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
    const std::string at = source + ": 'ops'[" + std::to_string(i) + "] (" + editKindName(op) + ")";
    before.assign(positions.begin(), positions.end());
    std::vector<double> w;
    Eigen::Vector3d pivot = Eigen::Vector3d::Zero();
    if (const VertexPick* pick = pickOf(op)) {
      const std::int32_t seed = pickedVertex(*pick, camera, triangles, positions, image_size, at);
      w = seedWeights(pick->metric, pick->falloff, positions, triangles, seed);
      pivot = Eigen::Vector3d(positions[3 * seed], positions[3 * seed + 1], positions[3 * seed + 2]);
    }
    auto centroid = [&](const std::vector<std::int32_t>& vertices,
                        const std::optional<Eigen::Vector3d>& center) -> Eigen::Vector3d {
      if (center) return *center;
      Eigen::Vector3d c = Eigen::Vector3d::Zero();
      const std::size_t count = vertices.empty() ? n : vertices.size();
      for (std::size_t k = 0; k < count; ++k) {
        const std::size_t v = vertices.empty() ? k : static_cast<std::size_t>(vertices[k]);
        c += Eigen::Vector3d(positions[3 * v], positions[3 * v + 1], positions[3 * v + 2]);
      }
      return c / static_cast<double>(std::max<std::size_t>(count, 1));
    };
    switch (editKind(op)) {
      case EditKind::kDrag: {
        const DragOp& o = std::get<DragOp>(op);
        Eigen::Vector2d delta = o.delta;
        if (o.delta_px) {
          if (!image_size) throw Error(at + ".'delta_px': needs the drawing's size: give \"image_size\": [w, h]");
          const double depth = project(camera, (*image_size)[0], (*image_size)[1], pivot).depth;
          delta = imagePlaneDelta(camera, (*image_size)[0], (*image_size)[1], depth, *o.delta_px);
        }
        dragInImagePlane(camera, positions, w, delta);
        break;
      }
      case EditKind::kPushPull: {
        const PushPullOp& o = std::get<PushPullOp>(op);
        pushPull(camera, positions, w, o.amount, o.mode);
        break;
      }
      case EditKind::kRotate:
        rotateInImagePlane(camera, positions, w, pivot, std::get<RotateOp>(op).angle_deg * std::numbers::pi / 180.0);
        break;
      case EditKind::kScale:
        scaleInImagePlane(camera, positions, w, pivot, std::get<ScaleOp>(op).factor);
        break;
      case EditKind::kDisplace: {
        const DisplaceOp& o = std::get<DisplaceOp>(op);
        displaceVertices(positions, w, o.camera_frame ? Eigen::Vector3d(camera_axes * o.offset) : o.offset);
        break;
      }
      case EditKind::kFfd: {
        const FfdOp& o = std::get<FfdOp>(op);
        const Eigen::Matrix3d lattice_frame = o.camera_frame ? camera_axes : Eigen::Matrix3d::Identity();
        FfdLattice lattice = ffdLatticeAround(positions, o.vertices, lattice_frame, o.degree, o.padding);
        const FfdBinding binding = bindFfd(lattice, positions, o.vertices);
        for (const FfdMove& m : o.moves) lattice.point(m.index[0], m.index[1], m.index[2]) += lattice_frame * m.offset;
        applyFfd(lattice, binding, positions);
        break;
      }
      case EditKind::kSquashStretch: {
        const SquashStretchOp& o = std::get<SquashStretchOp>(op);
        const Eigen::Vector3d axis = o.camera_frame ? Eigen::Vector3d(camera_axes * o.axis) : o.axis;
        applyAffine(positions, o.vertices, squashStretchMatrix(axis, o.factor, o.preserve_volume),
                    centroid(o.vertices, o.center), Eigen::Vector3d::Zero());
        break;
      }
      case EditKind::kAffine: {
        const AffineOp& o = std::get<AffineOp>(op);
        applyAffine(positions, o.vertices, o.matrix, centroid(o.vertices, o.center), o.translation);
        break;
      }
      case EditKind::kSkeleton: {
        const SkeletonOp& o = std::get<SkeletonOp>(op);
        const SkeletonBinding binding = bindSkeleton(o.rest, positions, o.vertices, o.falloff);
        // checkEditOp (validateEdits above) has checked both wires, so the contract holds.
        if (!binding.apply(o.posed, positions)) throw Error(at + ": the posed wire was refused");
        break;
      }
      case EditKind::kLines: {
        const LinesOp& o = std::get<LinesOp>(op);
        if (!image_size) throw Error(at + ": needs the drawing's size: give \"image_size\": [w, h]");
        warpByFeatureLines(camera, (*image_size)[0], (*image_size)[1], positions, o.pairs, o.settings);
        break;
      }
    }
    EditReport report;
    for (std::size_t v = 0; v < n; ++v) {
      const double d = (Eigen::Vector3d(positions[3 * v], positions[3 * v + 1], positions[3 * v + 2]) -
                        Eigen::Vector3d(before[3 * v], before[3 * v + 1], before[3 * v + 2]))
                           .norm();
      if (!std::isfinite(d))
        throw Error(at + ": produced a non-finite vertex position (vertex " + std::to_string(v) + ")");
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
