// The viewing-sphere diagram of Rademacher 99, Figure 4 (section 3.2.1: key viewpoints on the
// viewing sphere, triangulated by their convex hull; the view falls in one triangle).
#include "vdg/render/sphere_inset.h"

#include "vdg/render/sphere_map_image.h"
#include "vdg/viewdep/intersection_check.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <set>
#include <utility>

#include "vdg/render/model_renderer.h"

namespace vdg::render {
namespace {

constexpr double kDegToRad = std::numbers::pi / 180.0;
constexpr double kFovDeg = 30.0;
constexpr double kFitRadius = 1.15;  // the sphere plus the view marker's ray, with a margin
constexpr double kSideDeg = 30.0;    // the inset camera's azimuth beyond the view's
constexpr double kAboveDeg = 20.0;   // and its elevation above it
constexpr double kMaxElevationDeg = 70.0;
constexpr int kMinPanel = 1;  // pixels of panel inside the one-pixel frame
constexpr Rgb kKeyColor{0.15f, 0.15f, 0.18f};
constexpr Rgb kActiveKeyColor{0.85f, 0.1f, 0.1f};
constexpr Rgb kDummyColor{0.6f, 0.6f, 0.6f};
constexpr Rgb kViewColor{0.1f, 0.3f, 0.9f};
constexpr Rgb kWireColor{0.35f, 0.35f, 0.38f};
constexpr Rgb kGuideColor{0.8f, 0.8f, 0.8f};
constexpr Rgb kPanelColor{1.0f, 1.0f, 1.0f};
constexpr Rgb kFrameColor{0.7f, 0.7f, 0.7f};
constexpr Rgb kHullColor{0.92f, 0.92f, 0.92f};
constexpr Rgb kActiveColor{0.35f, 0.8f, 0.35f};
constexpr Rgb kSuggestedColor{0.0f, 0.9f, 1.0f};  // the heat map's suggested view (sphere_map_image.h's ring)

void push(std::vector<float>& v, const Eigen::Vector3d& p) {
  v.push_back(static_cast<float>(p.x()));
  v.push_back(static_cast<float>(p.y()));
  v.push_back(static_cast<float>(p.z()));
}

// Distance of the inset camera from the centre for a panel of `aspect` (width / height).
double insetDistance(double aspect) { return fitDistance(kFitRadius, kFovDeg, aspect); }

// The inset camera for `view` at `distance` from the centre.
Camera insetCamera(const Eigen::Vector3d& view, double distance) {
  const double az = std::atan2(view.x(), view.z()) / kDegToRad + kSideDeg;
  const double el = std::clamp(std::asin(std::clamp(view.y(), -1.0, 1.0)) / kDegToRad + kAboveDeg, -kMaxElevationDeg,
                               kMaxElevationDeg);
  return orbitCamera(Eigen::Vector3d::Zero(), distance, az, el, kFovDeg);
}

bool validViewport(const Viewport& v) { return v.width >= kMinPanel + 2 && v.height >= kMinPanel + 2; }

}  // namespace

SphereInset::SphereInset(const ViewSphere& sphere)
    : points_(sphere.points().begin(), sphere.points().end()),
      key_count_(sphere.keyCount()),
      triangles_(sphere.triangles().begin(), sphere.triangles().end()),
      camera_(insetCamera(Eigen::Vector3d::UnitZ(), insetDistance(1.0))) {
  std::set<std::pair<int, int>> edges;
  for (const auto& t : triangles_)
    for (int i = 0; i < 3; ++i) edges.insert(std::minmax(t[i], t[(i + 1) % 3]));
  for (const auto& [a, b] : edges) {
    push(wire_, points_[a]);
    push(wire_, points_[b]);
  }
  // Boundary arcs of the covered region (cosine modes), as great-circle polylines.
  for (const auto& arc : sphere.boundaryArcs()) {
    const Eigen::Vector3d a = points_[arc[0]], b = points_[arc[1]];
    constexpr int kSteps = 16;
    for (int i = 0; i < kSteps; ++i) {
      const auto lerp = [&](double t) { return ((1 - t) * a + t * b).normalized(); };
      push(wire_, lerp(double(i) / kSteps));
      push(wire_, lerp(double(i + 1) / kSteps));
    }
  }
  // Guide circles: the equator and the meridian through the front, for orientation.
  constexpr int kCircle = 48;
  for (int i = 0; i < kCircle; ++i) {
    const double a0 = 2 * std::numbers::pi * i / kCircle, a1 = 2 * std::numbers::pi * (i + 1) / kCircle;
    push(guide_, {std::sin(a0), 0, std::cos(a0)});
    push(guide_, {std::sin(a1), 0, std::cos(a1)});
    push(guide_, {0, std::sin(a0), std::cos(a0)});
    push(guide_, {0, std::sin(a1), std::cos(a1)});
  }
  for (std::size_t i = 0; i < points_.size(); ++i) push(i < key_count_ ? key_dots_ : dummy_dots_, points_[i]);
  hull_rest_.reserve(triangles_.size() * 9);
  active_tri_.reserve(9);
  active_dots_.reserve(9);
  view_ray_.reserve(6);
  view_dot_.reserve(3);
}

void SphereInset::setHeat(const SphereMap* map) {
  for (auto& bin : heat_dots_) bin.clear();
  heat_suggested_.clear();
  if (map == nullptr || map->need.empty()) return;
  for (const Eigen::Vector3d& d : fibonacciDirections(kHeatSamples)) {
    const double need = map->need[static_cast<std::size_t>(map->cellOf(d))];
    push(heat_dots_[static_cast<std::size_t>(std::clamp(static_cast<int>(need * kHeatBins), 0, kHeatBins - 1))], d);
  }
  push(heat_suggested_, map->suggested);
}

Viewport insetPlacement(const Viewport& view, int side, int margin, std::span<const float> points) {
  const int left = view.x + std::max(0, std::min(margin, view.width - side));
  const int top = view.y + std::max(0, std::min(margin, view.height - side));
  const int right = view.x + std::max(0, view.width - side - margin);
  const int bottom = view.y + std::max(0, view.height - side - margin);
  const std::array<std::array<int, 2>, 4> corners{{{right, bottom}, {left, bottom}, {right, top}, {left, top}}};
  std::array<long, 4> inside{};
  double x0 = std::numeric_limits<double>::infinity(), y0 = x0, x1 = -x0, y1 = -x0;
  for (std::size_t i = 0; i + 1 < points.size(); i += 2) {
    const double x = points[i], y = points[i + 1];
    x0 = std::min(x0, x), x1 = std::max(x1, x), y0 = std::min(y0, y), y1 = std::max(y1, y);
    for (std::size_t c = 0; c < corners.size(); ++c)
      inside[c] += x >= corners[c][0] && x <= corners[c][0] + side && y >= corners[c][1] && y <= corners[c][1] + side;
  }
  std::size_t best = 0;
  double best_overlap = std::numeric_limits<double>::infinity();
  for (std::size_t c = 0; c < corners.size(); ++c) {
    const double w = std::min<double>(corners[c][0] + side, x1) - std::max<double>(corners[c][0], x0);
    const double h = std::min<double>(corners[c][1] + side, y1) - std::max<double>(corners[c][1], y0);
    const double overlap = std::max(0.0, w) * std::max(0.0, h);
    // Strictly better only: ties keep the earlier corner.
    if (inside[c] < inside[best] || (inside[c] == inside[best] && overlap < best_overlap)) {
      best = c;
      best_overlap = overlap;
    }
  }
  return {corners[best][0], corners[best][1], side, side};
}

Viewport SphereInset::panel(const Viewport& viewport) {
  return {viewport.x + 1, viewport.y + 1, viewport.width - 2, viewport.height - 2};
}

bool SphereInset::draw(Renderer& r, const Viewport& viewport, const Eigen::Vector3d& view, const ViewWeights& w) {
  if (!validViewport(viewport) || !view.allFinite()) return false;
  if (w.triangle < -1 || w.triangle >= static_cast<int>(triangles_.size())) return false;
  for (const int k : w.key)
    if (k < -1 || k >= static_cast<int>(key_count_)) return false;

  const Viewport inner = panel(viewport);
  r.clear(kFrameColor, &viewport);
  r.clear(kPanelColor, &inner);
  View v;
  v.viewport = inner;
  const double dist = insetDistance(static_cast<double>(inner.width) / inner.height);
  v.camera = insetCamera(view, dist);
  camera_ = v.camera;
  v.z_near = dist - 2.0;
  v.z_far = dist + 2.0;
  const float unit = std::max(1.0f, static_cast<float>(std::min(inner.width, inner.height)) / 120.0f);

  bool ok = r.drawLines(guide_, v, unit, kGuideColor, false);
  hull_rest_.clear();
  active_tri_.clear();
  active_dots_.clear();
  for (std::size_t t = 0; t < triangles_.size(); ++t)
    for (int i = 0; i < 3; ++i)
      push(static_cast<int>(t) == w.triangle ? active_tri_ : hull_rest_, points_[triangles_[t][i]]);
  MeshStyle hull_style;
  hull_style.color = kHullColor;
  hull_style.shading = shading;
  hull_style.shading.ka = 1.0f;  // a diagram: mostly its own colours, lightly shaded
  hull_style.shading.vary_by_hue = false;
  hull_style.shading.k = {1.0f, 0.15f, 1.0f, 0.3f};
  ok = r.drawTriangles(hull_rest_, v, hull_style) && ok;
  MeshStyle active_style = hull_style;
  active_style.color = kActiveColor;
  ok = r.drawTriangles(active_tri_, v, active_style) && ok;
  for (int b = 0; b < kHeatBins; ++b) {
    const auto c = heatColour((b + 0.5) / kHeatBins);
    ok = r.drawDots(heat_dots_[static_cast<std::size_t>(b)], v, unit * 3.5f,
                    {c[0] / 255.0f, c[1] / 255.0f, c[2] / 255.0f}, true, 3.0f) &&
         ok;
  }
  ok = r.drawLines(wire_, v, unit * 1.2f, kWireColor, true, 2.0f) && ok;
  ok = r.drawDots(key_dots_, v, unit * 6.0f, kKeyColor, true, 4.0f) && ok;
  ok = r.drawDots(dummy_dots_, v, unit * 5.0f, kDummyColor, true, 4.0f) && ok;
  ok = r.drawDots(dummy_dots_, v, unit * 2.5f, kPanelColor, true, 5.0f) && ok;
  if (w.triangle >= 0) {  // the triangle's three corners, dummies included (Figure 4's red keys)
    for (int i = 0; i < 3; ++i) push(active_dots_, points_[triangles_[w.triangle][i]]);
  } else {  // uncovered (cosine modes): the keys that weigh
    for (int i = 0; i < 3; ++i)
      if (w.key[i] >= 0 && w.weight[i] > 0.0f) push(active_dots_, points_[w.key[i]]);
  }
  ok = r.drawDots(active_dots_, v, unit * 8.0f, kActiveKeyColor, true, 6.0f) && ok;
  ok = r.drawDots(heat_suggested_, v, unit * 9.0f, kSuggestedColor, true, 7.0f) && ok;
  view_ray_.clear();
  view_dot_.clear();
  push(view_ray_, Eigen::Vector3d::Zero());
  push(view_ray_, view * 1.25);
  push(view_dot_, view);
  ok = r.drawLines(view_ray_, v, unit * 1.5f, kViewColor, true, 2.0f) && ok;
  ok = r.drawDots(view_dot_, v, unit * 7.0f, kViewColor, true, 8.0f) && ok;
  return ok;
}

int SphereInset::keyAt(const Viewport& viewport, const Eigen::Vector2d& pixel, double radius_px) const {
  if (!validViewport(viewport) || !pixel.allFinite() || !std::isfinite(radius_px) || radius_px < 0.0) return -1;
  const Viewport inner = panel(viewport);
  const Eigen::Vector2d origin(inner.x, inner.y);
  int best = -1;
  double best_d2 = radius_px * radius_px;
  for (std::size_t k = 0; k < key_count_; ++k) {
    const Eigen::Vector3d& p = points_[k];
    if (!((camera_.eye - p).dot(p) > 0.0)) continue;  // behind the sphere's outline
    const Projected q = project(camera_, inner.width, inner.height, p);
    const double d2 = (origin + q.pixel - pixel).squaredNorm();
    if (d2 <= best_d2 && (best < 0 || d2 < best_d2)) {
      best = static_cast<int>(k);
      best_d2 = d2;
    }
  }
  return best;
}

}  // namespace vdg::render
