// Skeleton (wire) deformation: Burtnyk and Wein's technique after Parent, Computer Animation,
// section 4.10, extended to 3D with dividing planes and a parallel-transported segment frame. The
// construction and its formulas are documented in vdg/deform/skeleton.h.
#include "vdg/deform/skeleton.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>

#include "vdg/geom/error.h"

namespace vdg {

namespace {

enum class WireFault { kNone, kTooFew, kTooMany, kNotFinite, kRepeated, kTooFar, kFolds };

struct WireCheck {
  WireFault fault = WireFault::kNone;
  std::size_t joint = 0;
  double bend_deg = 0;
};

double cosOfMaxBend() { return std::cos(kMaxSkeletonBendDeg * std::numbers::pi / 180.0); }

// The allocation-free core of checkSkeletonWire (apply() calls it on every posed wire).
WireCheck checkWire(std::span<const Eigen::Vector3d> joints) {
  if (joints.size() < 2) return {WireFault::kTooFew, 0, 0};
  if (joints.size() > kMaxSkeletonJoints) return {WireFault::kTooMany, 0, 0};
  double scale = 1.0;
  for (std::size_t k = 0; k < joints.size(); ++k) {
    if (!joints[k].allFinite()) return {WireFault::kNotFinite, k, 0};
    scale = std::max(scale, joints[k].cwiseAbs().maxCoeff());
  }
  const double min_length = 1e-12 * scale;
  for (std::size_t k = 1; k < joints.size(); ++k) {
    const double length = (joints[k] - joints[k - 1]).norm();
    if (!(length > min_length)) return {WireFault::kRepeated, k, 0};
    if (!std::isfinite(length)) return {WireFault::kTooFar, k, 0};
  }
  const double min_cos = cosOfMaxBend();
  for (std::size_t k = 1; k + 1 < joints.size(); ++k) {
    const Eigen::Vector3d a = (joints[k] - joints[k - 1]).normalized();
    const Eigen::Vector3d b = (joints[k + 1] - joints[k]).normalized();
    const double c = a.dot(b);
    if (!(c > min_cos)) return {WireFault::kFolds, k, std::acos(std::clamp(c, -1.0, 1.0)) * 180.0 / std::numbers::pi};
  }
  return {};
}

// The directions, lengths and dividing-plane normals of a (valid) wire with `count` joints, into
// caller-provided storage (d and length: count - 1 entries, m: count entries).
void wireGeometry(std::span<const Eigen::Vector3d> joints, Eigen::Vector3d* d, double* length, Eigen::Vector3d* m) {
  const std::size_t n = joints.size() - 1;  // segments
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector3d e = joints[i + 1] - joints[i];
    length[i] = e.norm();
    d[i] = e / length[i];
  }
  // Parent 4.10: perpendicular to the end segments, bisectors at the interior joints.
  m[0] = d[0];
  m[n] = d[n - 1];
  for (std::size_t k = 1; k < n; ++k) m[k] = (d[k - 1] + d[k]).normalized();
}

Eigen::Matrix3d minimalRotation(const Eigen::Vector3d& from, const Eigen::Vector3d& to) {
  return Eigen::Quaterniond::FromTwoVectors(from, to).toRotationMatrix();
}

}  // namespace

double distanceToSegment(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const Eigen::Vector3d e = b - a;
  const double ee = e.squaredNorm();
  const double t = ee > 0 ? std::clamp((p - a).dot(e) / ee, 0.0, 1.0) : 0.0;
  return (p - (a + t * e)).norm();
}

std::optional<SkeletonWireProblem> checkSkeletonWire(std::span<const Eigen::Vector3d> joints) {
  const WireCheck c = checkWire(joints);
  switch (c.fault) {
    case WireFault::kNone:
      return std::nullopt;
    case WireFault::kTooFew:
      return SkeletonWireProblem{0, "a wire needs at least 2 joints, got " + std::to_string(joints.size()), true};
    case WireFault::kTooMany:
      return SkeletonWireProblem{
          0,
          "a wire has at most " + std::to_string(kMaxSkeletonJoints) + " joints, got " + std::to_string(joints.size()),
          true};
    case WireFault::kNotFinite:
      return SkeletonWireProblem{c.joint, "must hold finite numbers", false};
    case WireFault::kRepeated:
      return SkeletonWireProblem{
          c.joint, "is the same point as joint " + std::to_string(c.joint - 1) + " (consecutive joints must differ)",
          false};
    case WireFault::kTooFar:
      return SkeletonWireProblem{
          c.joint, "is too far from joint " + std::to_string(c.joint - 1) + " (their distance overflows)", false};
    case WireFault::kFolds: {
      char bend[32];
      std::snprintf(bend, sizeof bend, "%.4g", c.bend_deg);
      return SkeletonWireProblem{c.joint,
                                 std::string("the wire bends by ") + bend + " degrees there; bends must stay below " +
                                     std::to_string(static_cast<int>(kMaxSkeletonBendDeg)) +
                                     " (at 180 it folds back on itself and the dividing plane is undefined)",
                                 false};
    }
  }
  return std::nullopt;
}

SkeletonBinding bindSkeleton(std::span<const Eigen::Vector3d> rest, std::span<const float> positions,
                             std::span<const std::int32_t> vertices, const std::optional<Falloff>& falloff) {
  if (const auto problem = checkSkeletonWire(rest))
    throw Error(problem->count ? "skeleton: " + problem->message
                               : "skeleton: joint " + std::to_string(problem->joint) + ": " + problem->message);
  if (falloff && (!(falloff->radius > 0) || !std::isfinite(falloff->radius) || !(falloff->power >= 0) ||
                  !std::isfinite(falloff->power)))
    throw Error("skeleton: the falloff needs a radius > 0 and a power >= 0, both finite");
  const std::size_t vertex_count = positions.size() / 3;
  for (std::int32_t v : vertices)
    if (v < 0 || static_cast<std::size_t>(v) >= vertex_count)
      throw Error("skeleton: vertex " + std::to_string(v) + " is out of range (the mesh has " +
                  std::to_string(vertex_count) + " vertices)");

  const std::size_t n = rest.size() - 1;  // segments
  std::vector<Eigen::Vector3d> d(n), m(n + 1);
  std::vector<double> length(n);
  wireGeometry(rest, d.data(), length.data(), m.data());

  SkeletonBinding binding;
  binding.rest_joints.assign(rest.begin(), rest.end());
  binding.vertex_count = vertex_count;
  binding.rest_directions = d;
  for (std::size_t i = 0; i + 1 < n; ++i) binding.rest_transport.push_back(minimalRotation(d[i], d[i + 1]));

  const std::size_t count = vertices.empty() ? vertex_count : vertices.size();
  binding.coords.reserve(count);
  for (std::size_t k = 0; k < count; ++k) {
    const std::int32_t v = vertices.empty() ? static_cast<std::int32_t>(k) : vertices[k];
    const Eigen::Vector3d p(positions[3 * static_cast<std::size_t>(v)], positions[3 * static_cast<std::size_t>(v) + 1],
                            positions[3 * static_cast<std::size_t>(v) + 2]);
    // The cells holding p; the nearest segment among them (Parent 4.10: "each vertex of the object
    // falls within one semi-infinite cell"; in 3D several can hold it beyond crossing planes).
    std::size_t best = n;
    double best_distance = std::numeric_limits<double>::infinity();
    double wire_distance = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < n; ++i) {
      const double dist = distanceToSegment(p, rest[i], rest[i + 1]);
      wire_distance = std::min(wire_distance, dist);
      const bool after_start = i == 0 || (p - rest[i]).dot(m[i]) >= 0;
      const bool before_end = i + 1 == n || (p - rest[i + 1]).dot(m[i + 1]) <= 0;
      if (after_start && before_end && dist < best_distance) {
        best = i;
        best_distance = dist;
      }
    }
    // Every point lies in some cell: the sign of (p - J_k) . m_k starts "ahead" before plane 1 and
    // ends "behind" after plane n-1, so it changes somewhere. Rounding cannot undo that, but be safe.
    if (best == n) best = 0;
    const double weight = falloff ? falloffWeight(*falloff, wire_distance) : 1.0;
    if (!(weight > 0)) continue;

    const std::size_t i = best;
    SkeletonCoords c;
    c.vertex = v;
    c.segment = static_cast<std::int32_t>(i);
    c.rest = p;
    c.weight = weight;
    const Eigen::Vector3d r = p - rest[i];
    const double along = r.dot(d[i]);  // the vertex's coordinate along the segment's line
    c.offset = r - along * d[i];
    const double a = r.dot(m[i]);                      // signed distance past plane i
    const double b = (p - rest[i + 1]).dot(m[i + 1]);  // signed distance past plane i+1
    if (i == 0 && a < 0) {
      c.region = SkeletonRegion::kBefore;
      c.s = a;  // m_0 = d_0: the distance along the segment before the start plane
    } else if (i + 1 == n && b > 0) {
      c.region = SkeletonRegion::kAfter;
      c.s = b;
    } else {
      // The parallel line p + t d_i crosses plane i at t_a = -a / (d_i . m_i) and plane i+1 at
      // t_b = -b / (d_i . m_{i+1}); s = (0 - t_a) / (t_b - t_a) (Parent 4.10: "the relative
      // position of the vertex on that line"). Both dot products are > 0 (bends < 180 degrees).
      const double t_a = -a / d[i].dot(m[i]);
      const double t_b = -b / d[i].dot(m[i + 1]);
      const double span = t_b - t_a;  // >= 0 inside the cell; 0 where the two planes cross
      c.region = SkeletonRegion::kBetween;
      c.s = span > 1e-12 * length[i] ? -t_a / span : 0.5;
    }
    binding.coords.push_back(c);
  }
  return binding;
}

bool SkeletonBinding::apply(std::span<const Eigen::Vector3d> posed, std::span<float> positions_out) const {
  if (posed.size() != rest_joints.size() || positions_out.size() != 3 * vertex_count) return false;
  if (checkWire(posed).fault != WireFault::kNone) return false;
  const std::size_t n = posed.size() - 1;
  // Per-joint scratch on the stack: nothing allocated per call.
  std::array<Eigen::Vector3d, kMaxSkeletonJoints> d, m;
  std::array<double, kMaxSkeletonJoints> length;
  std::array<Eigen::Matrix3d, kMaxSkeletonJoints> q;
  wireGeometry(posed, d.data(), length.data(), m.data());
  q[0] = minimalRotation(rest_directions.front(), d[0]);
  for (std::size_t i = 0; i + 1 < n; ++i)
    q[i + 1] = minimalRotation(d[i], d[i + 1]) * q[i] * rest_transport[i].transpose();

  for (const SkeletonCoords& c : coords) {
    const std::size_t i = static_cast<std::size_t>(c.segment);
    const Eigen::Vector3d o = q[i] * c.offset;
    Eigen::Vector3d p;
    switch (c.region) {
      case SkeletonRegion::kBefore:
        p = posed[0] + o + c.s * d[0];
        break;
      case SkeletonRegion::kAfter:
        p = posed[n] + o + c.s * d[n - 1];
        break;
      case SkeletonRegion::kBetween: {
        // The posed parallel line J'_i + o' + t d'_i meets posed plane i at t_A and plane i+1 at
        // t_B (Parent 4.10: "relocated using newly computed dividing lines").
        const double t_a = -o.dot(m[i]) / d[i].dot(m[i]);
        const double t_b = length[i] - o.dot(m[i + 1]) / d[i].dot(m[i + 1]);
        p = posed[i] + o + (t_a + c.s * (t_b - t_a)) * d[i];
        break;
      }
    }
    const Eigen::Vector3d out = c.weight == 1 ? p : Eigen::Vector3d(c.rest + c.weight * (p - c.rest));
    const std::size_t v = 3 * static_cast<std::size_t>(c.vertex);
    positions_out[v] = static_cast<float>(out.x());
    positions_out[v + 1] = static_cast<float>(out.y());
    positions_out[v + 2] = static_cast<float>(out.z());
  }
  return true;
}

}  // namespace vdg
