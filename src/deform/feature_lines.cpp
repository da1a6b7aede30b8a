// Deformation from feature lines: Beier and Neely, "Feature-Based Image Metamorphosis", SIGGRAPH
// 92, section 3 (the field warp of one and of several line pairs), applied forward to the vertices'
// projections and lifted back to 3D at each vertex's depth (Rademacher 99, 3.1.2: image-plane edits
// keep the vertices' Z-distances; section 6 names [Beie92] as future work).
#include "vdg/deform/feature_lines.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <utility>

#include "vdg/geom/text.h"

namespace vdg {

namespace {

Eigen::Vector2d perp(const Eigen::Vector2d& d) { return {-d.y(), d.x()}; }

std::optional<FeatureLineProblem> lineProblem(const Eigen::Vector2d& p, const Eigen::Vector2d& q,
                                              const std::string& field) {
  if (!p.allFinite() || !q.allFinite()) return FeatureLineProblem{field, "must hold finite numbers"};
  if (p.cwiseAbs().maxCoeff() > kMaxFeatureLinePixel || q.cwiseAbs().maxCoeff() > kMaxFeatureLinePixel)
    return FeatureLineProblem{field, "expected coordinates within +-10000000 pixels"};
  if ((q - p).norm() < kMinFeatureLinePixels)
    return FeatureLineProblem{field, "the line has no length (its two ends are the same pixel)"};
  return std::nullopt;
}

// Closest point of segment ab to x.
Eigen::Vector2d closestOnSegment(const Eigen::Vector2d& x, const PixelSegment& s) {
  const Eigen::Vector2d d = s.b - s.a;
  const double len2 = d.squaredNorm();
  const double t = len2 > 0 ? std::clamp((x - s.a).dot(d) / len2, 0.0, 1.0) : 0.0;
  return s.a + t * d;
}

Eigen::Vector2d snapPoint(const Eigen::Vector2d& x, std::span<const PixelSegment> silhouette) {
  Eigen::Vector2d best = x;
  double best_d = std::numeric_limits<double>::infinity();
  for (const PixelSegment& s : silhouette) {
    const Eigen::Vector2d c = closestOnSegment(x, s);
    const double d = (c - x).squaredNorm();
    if (d < best_d) {
      best_d = d;
      best = c;
    }
  }
  return best;
}

}  // namespace

std::optional<FeatureLineProblem> checkFeatureLines(std::span<const FeatureLinePair> pairs,
                                                    const FeatureLineSettings& s) {
  if (!(s.a > 0 && s.a <= kMaxFeatureLineA))
    return FeatureLineProblem{"'a'", "expected a number above 0 and at most 1000000, got " + numberText(s.a, 10)};
  if (!(s.b >= 0 && s.b <= kMaxFeatureLineB))
    return FeatureLineProblem{"'b'", "expected a number from 0 to 16, got " + numberText(s.b, 10)};
  if (!(s.p >= 0 && s.p <= 1))
    return FeatureLineProblem{"'p'", "expected a number from 0 to 1, got " + numberText(s.p, 10)};
  if (!(s.falloff_px > 0) || !std::isfinite(s.falloff_px))
    return FeatureLineProblem{"'falloff_px'", "must be > 0 and finite, got " + numberText(s.falloff_px, 10)};
  if (pairs.empty() || pairs.size() > kMaxFeatureLinePairs)
    return FeatureLineProblem{"'lines'", "expected 1 to " + std::to_string(kMaxFeatureLinePairs) + " line pairs, got " +
                                             std::to_string(pairs.size())};
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    const std::string at = "'lines'[" + std::to_string(i) + "]";
    if (auto p = lineProblem(pairs[i].model_p, pairs[i].model_q, at + ".'src'")) return p;
    if (auto p = lineProblem(pairs[i].drawing_p, pairs[i].drawing_q, at + ".'dst'")) return p;
  }
  return std::nullopt;
}

Eigen::Vector2d featureLineMotion(const Eigen::Vector2d& x, std::span<const FeatureLinePair> pairs,
                                  const FeatureLineSettings& s) {
  Eigen::Vector2d sum = Eigen::Vector2d::Zero();
  double weight_sum = 0;
  double nearest = std::numeric_limits<double>::infinity();
  bool any_motion = false;
  Eigen::Vector2d nearest_motion = Eigen::Vector2d::Zero();
  for (const FeatureLinePair& pair : pairs) {
    // Beier and Neely 92, section 3.1: u along the line, v the perpendicular distance (pixels).
    const Eigen::Vector2d d = pair.model_q - pair.model_p;
    const double len = d.norm();
    const double u = (x - pair.model_p).dot(d) / (len * len);
    const double v = (x - pair.model_p).dot(perp(d)) / len;
    // Section 3.3: dist is |v| beside the segment, else the distance to the nearer endpoint.
    const double dist = u < 0 ? (x - pair.model_p).norm() : u > 1 ? (x - pair.model_q).norm() : std::abs(v);
    const bool is_nearest = dist < nearest;
    nearest = std::min(nearest, dist);
    const double weight = std::pow(std::pow(len, s.p) / (s.a + dist), s.b);
    weight_sum += weight;
    if (pair.model_p == pair.drawing_p && pair.model_q == pair.drawing_q) {  // D_i = 0 exactly
      if (is_nearest) nearest_motion = Eigen::Vector2d::Zero();
      continue;
    }
    const Eigen::Vector2d e = pair.drawing_q - pair.drawing_p;
    const Eigen::Vector2d mapped = pair.drawing_p + u * e + v * perp(e) / e.norm();
    sum += weight * (mapped - x);
    if (is_nearest) nearest_motion = mapped - x;
    any_motion = true;
  }
  if (!any_motion || !(nearest < s.falloff_px)) return Eigen::Vector2d::Zero();
  const double t = 1.0 - nearest / s.falloff_px;  // Rademacher 99, 3.1.2: (1 - d/r)^2
  // A tiny a with a large b can overflow the weights: the nearest line then dominates (the limit).
  if (!(weight_sum > 0) || !std::isfinite(weight_sum) || !sum.allFinite()) return t * t * nearest_motion;
  return (t * t / weight_sum) * sum;
}

std::size_t warpByFeatureLines(const Camera& camera, int width, int height, std::span<float> positions,
                               std::span<const FeatureLinePair> pairs, const FeatureLineSettings& settings) {
  std::size_t moved = 0;
  const bool ortho = camera.isOrtho();
  for (std::size_t v = 0; v < positions.size() / 3; ++v) {
    const Eigen::Vector3d x(positions[3 * v], positions[3 * v + 1], positions[3 * v + 2]);
    const Projected pr = project(camera, width, height, x);
    if (!ortho && !(pr.depth > 0)) continue;  // at or behind the eye: no pixel to move
    const Eigen::Vector2d motion = featureLineMotion(pr.pixel, pairs, settings);
    if (motion.x() == 0 && motion.y() == 0) continue;
    // The vertex keeps its depth: unproject at the depth it has (as the drag, image_plane.h).
    const Eigen::Vector3d moved_to = x + (unproject(camera, width, height, pr.pixel + motion, pr.depth) -
                                          unproject(camera, width, height, pr.pixel, pr.depth));
    for (int k = 0; k < 3; ++k) positions[3 * v + k] = static_cast<float>(moved_to[k]);
    ++moved;
  }
  return moved;
}

std::vector<PixelSegment> projectedSilhouette(const Camera& camera, int width, int height,
                                              std::span<const float> positions,
                                              std::span<const std::int32_t> triangles) {
  const CameraFrame frame = cameraFrame(camera);
  auto at = [&](std::int32_t v) {
    const auto i = static_cast<std::size_t>(v);
    return Eigen::Vector3d(positions[3 * i], positions[3 * i + 1], positions[3 * i + 2]);
  };
  // Facing of each triangle: its normal against the direction to the eye (the view axis when
  // parallel).
  const std::size_t count = triangles.size() / 3;
  std::vector<char> front(count);
  for (std::size_t t = 0; t < count; ++t) {
    const Eigen::Vector3d a = at(triangles[3 * t]), b = at(triangles[3 * t + 1]), c = at(triangles[3 * t + 2]);
    const Eigen::Vector3d n = (b - a).cross(c - a);
    const Eigen::Vector3d to_eye = camera.isOrtho() ? frame.back : Eigen::Vector3d(camera.eye - (a + b + c) / 3.0);
    front[t] = n.dot(to_eye) > 0;
  }
  // Edge -> the faces on it: (front count, back count).
  std::map<std::pair<std::int32_t, std::int32_t>, std::pair<int, int>> edges;
  for (std::size_t t = 0; t < count; ++t)
    for (int k = 0; k < 3; ++k) {
      std::int32_t a = triangles[3 * t + static_cast<std::size_t>(k)];
      std::int32_t b = triangles[3 * t + static_cast<std::size_t>((k + 1) % 3)];
      if (a > b) std::swap(a, b);
      auto& e = edges[{a, b}];
      (front[t] ? e.first : e.second) += 1;
    }
  std::vector<PixelSegment> out;
  for (const auto& [edge, faces] : edges) {
    const bool silhouette = (faces.first > 0 && faces.second > 0) || (faces.first == 1 && faces.second == 0);
    if (!silhouette) continue;
    out.push_back(
        {project(camera, width, height, at(edge.first)).pixel, project(camera, width, height, at(edge.second)).pixel});
  }
  return out;
}

std::vector<FeatureLinePair> snapToSilhouette(std::span<const FeatureLinePair> pairs,
                                              std::span<const PixelSegment> silhouette) {
  std::vector<FeatureLinePair> out(pairs.begin(), pairs.end());
  if (silhouette.empty()) return out;
  for (FeatureLinePair& pair : out) {
    const Eigen::Vector2d p = snapPoint(pair.model_p, silhouette), q = snapPoint(pair.model_q, silhouette);
    if ((q - p).norm() < kMinFeatureLinePixels) continue;
    pair.model_p = p;
    pair.model_q = q;
  }
  return out;
}

}  // namespace vdg
