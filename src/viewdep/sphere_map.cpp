// Where to key next (vdg/viewdep/sphere_map.h): nearest-key angle, shape speed and uncovered weight
// over an equirectangular grid of the viewing sphere. The blend is Rademacher 99, section 3.2.3
// (v = base + sum_i w_i (v^i - base)); uncovered regions section 3.3; animated keys section 4.
#include "vdg/viewdep/sphere_map.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <string>

#include <Eigen/Geometry>

#include "vdg/geom/error.h"
#include "vdg/geom/parallel.h"

namespace vdg {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

// One view's keys and weights merged with another's, as coefficients of the keys' deltas.
struct Coefficients {
  std::array<int, 6> key{};
  std::array<float, 6> c{};
  int count = 0;
  void add(int k, float value) {
    for (int i = 0; i < count; ++i)
      if (key[i] == k) {
        c[i] += value;
        return;
      }
    key[count] = k;
    c[count] = value;
    ++count;
  }
};

// What the map is computed from: the sphere (weights), each sphere key's delta from the base
// (#V x 3; empty when the key moves nothing) and the length that normalises the speed.
struct MapInput {
  const ViewSphere* sphere = nullptr;
  double sharpness = 1.0;
  std::vector<std::vector<float>> deltas;
  double radius = 1.0;
};

void checkSettings(const SphereMapSettings& s) {
  if (s.width < 1 || s.height < 1 || s.width > kMaxSphereMapSide || s.height > kMaxSphereMapSide)
    throw Error("sphere map: size " + std::to_string(s.width) + "x" + std::to_string(s.height) + " is outside 1.." +
                std::to_string(kMaxSphereMapSide) + " a side");
  if (!(s.step_deg > 0.0 && s.step_deg <= 10.0)) throw Error("sphere map: the speed's step must be in (0, 10] degrees");
}

// Largest vertex displacement between the blends of weights a and b.
double largestDisplacement(const MapInput& in, const ViewWeights& a, const ViewWeights& b) {
  Coefficients co;
  for (int s = 0; s < 3; ++s) {
    if (a.key[s] >= 0 && a.weight[s] != 0.0f) co.add(a.key[s], a.weight[s]);
    if (b.key[s] >= 0 && b.weight[s] != 0.0f) co.add(b.key[s], -b.weight[s]);
  }
  std::array<const float*, 6> d{};
  std::array<float, 6> c{};
  int n = 0;
  std::size_t count = 0;  // floats of every non-empty delta (#V x 3)
  for (int i = 0; i < co.count; ++i) {
    const auto& delta = in.deltas[static_cast<std::size_t>(co.key[i])];
    if (co.c[i] == 0.0f || delta.empty()) continue;
    d[n] = delta.data();
    c[n] = co.c[i];
    count = delta.size();
    ++n;
  }
  if (n == 0) return 0.0;
  float best = 0.0f;
  for (std::size_t v = 0; v + 2 < count; v += 3) {
    float x = 0.0f, y = 0.0f, z = 0.0f;
    for (int i = 0; i < n; ++i) {
      x += c[i] * d[i][v];
      y += c[i] * d[i][v + 1];
      z += c[i] * d[i][v + 2];
    }
    best = std::max(best, x * x + y * y + z * z);
  }
  return std::sqrt(static_cast<double>(best));
}

// Weights at `d` turned by +-step towards the tangent `t`; the largest displacement per degree.
double axisSpeed(const MapInput& in, const Eigen::Vector3d& d, const Eigen::Vector3d& t, double step_deg, int* hint) {
  const double cs = std::cos(step_deg * kDeg), sn = std::sin(step_deg * kDeg);
  ViewWeights plus, minus;
  if (!in.sphere->weights(d * cs + t * sn, in.sharpness, plus, hint) ||
      !in.sphere->weights(d * cs - t * sn, in.sharpness, minus, hint))
    return 0.0;
  return largestDisplacement(in, plus, minus) / (2.0 * step_deg);
}

double nearestKeyDeg(const Eigen::Vector3d& d, const std::vector<Eigen::Vector3d>& keys) {
  double best = std::numbers::pi;
  for (const Eigen::Vector3d& k : keys) best = std::min(best, std::atan2(d.cross(k).norm(), d.dot(k)));
  return best / kDeg;
}

// Fills the per-cell measures of rows [y0, y1).
void fillRows(const MapInput& in, const SphereMapSettings& s, SphereMap& map, int y0, int y1) {
  int hint = -1;
  for (int y = y0; y < y1; ++y) {
    const double lat = (90.0 - (y + 0.5) * 180.0 / s.height) * kDeg;
    for (int x = 0; x < s.width; ++x) {
      const double lon = (-180.0 + (x + 0.5) * 360.0 / s.width) * kDeg;
      const Eigen::Vector3d d = SphereMap::cellDirection(s.width, s.height, x, y);
      const Eigen::Vector3d east(std::cos(lon), 0.0, -std::sin(lon));
      const Eigen::Vector3d north(-std::sin(lat) * std::sin(lon), std::cos(lat), -std::sin(lat) * std::cos(lon));
      const std::size_t cell = static_cast<std::size_t>(y) * s.width + x;
      ViewWeights w;
      map.uncovered[cell] = in.sphere->weights(d, in.sharpness, w, &hint) ? w.base : 0.0f;
      map.nearest_key_deg[cell] = static_cast<float>(nearestKeyDeg(d, map.keys));
      const double speed =
          std::max(axisSpeed(in, d, east, s.step_deg, &hint), axisSpeed(in, d, north, s.step_deg, &hint));
      map.speed[cell] = static_cast<float>(speed / in.radius);
    }
  }
}

// Statistics and the need score once every cell is filled.
void finish(const SphereMapSettings& s, SphereMap& map) {
  const std::size_t cells = map.need.size();
  double area = 0, nearest_sum = 0, uncovered_area = 0;
  for (std::size_t i = 0; i < cells; ++i) {
    const double a = std::cos((90.0 - (static_cast<double>(i / s.width) + 0.5) * 180.0 / s.height) * kDeg);
    area += a;
    nearest_sum += a * map.nearest_key_deg[i];
    if (map.uncovered[i] > kUncoveredWeight) uncovered_area += a;
    map.max_nearest_deg = std::max(map.max_nearest_deg, static_cast<double>(map.nearest_key_deg[i]));
    if (map.speed[i] > map.max_speed) {
      map.max_speed = map.speed[i];
      map.max_speed_view =
          SphereMap::cellDirection(s.width, s.height, static_cast<int>(i % s.width), static_cast<int>(i / s.width));
    }
  }
  map.mean_nearest_deg = area > 0 ? nearest_sum / area : 0.0;
  map.uncovered_fraction = area > 0 ? uncovered_area / area : 0.0;
  float best = -1.0f;
  for (std::size_t i = 0; i < cells; ++i) {
    const double a = map.max_nearest_deg > 0 ? map.nearest_key_deg[i] / map.max_nearest_deg : 0.0;
    const double v = map.max_speed > 0 ? map.speed[i] / map.max_speed : 0.0;
    map.need[i] = static_cast<float>(kNeedAngleWeight * a +
                                     kNeedUncoveredWeight * std::clamp<double>(map.uncovered[i], 0.0, 1.0) +
                                     kNeedSpeedWeight * v);
    if (map.need[i] > best) {
      best = map.need[i];
      map.suggested_cell = static_cast<int>(i);
    }
  }
  map.suggested =
      SphereMap::cellDirection(s.width, s.height, map.suggested_cell % s.width, map.suggested_cell / s.width);
}

SphereMap compute(const MapInput& in, const SphereMapSettings& s) {
  SphereMap map;
  map.width = s.width;
  map.height = s.height;
  const std::size_t cells = static_cast<std::size_t>(s.width) * s.height;
  map.nearest_key_deg.assign(cells, 0.0f);
  map.speed.assign(cells, 0.0f);
  map.uncovered.assign(cells, 0.0f);
  map.need.assign(cells, 0.0f);
  const auto points = in.sphere->points();
  map.keys.assign(points.begin(), points.begin() + static_cast<std::ptrdiff_t>(in.sphere->keyCount()));
  detail::parallelChunks(static_cast<std::size_t>(s.height), 2, [&](std::size_t begin, std::size_t end) {
    fillRows(in, s, map, static_cast<int>(begin), static_cast<int>(end));
  });
  finish(s, map);
  return map;
}

bool allZero(const std::vector<float>& v) {
  return std::all_of(v.begin(), v.end(), [](float x) { return x == 0.0f; });
}

}  // namespace

Eigen::Vector3d SphereMap::cellDirection(int width, int height, int x, int y) {
  const double lon = (-180.0 + (x + 0.5) * 360.0 / width) * kDeg;
  const double lat = (90.0 - (y + 0.5) * 180.0 / height) * kDeg;
  return {std::cos(lat) * std::sin(lon), std::sin(lat), std::cos(lat) * std::cos(lon)};
}

double SphereMap::longitudeDeg(const Eigen::Vector3d& d) { return std::atan2(d.x(), d.z()) / kDeg; }

double SphereMap::latitudeDeg(const Eigen::Vector3d& d) { return std::atan2(d.y(), std::hypot(d.x(), d.z())) / kDeg; }

int SphereMap::cellOf(const Eigen::Vector3d& d) const {
  const int x = std::clamp(static_cast<int>(std::floor((longitudeDeg(d) + 180.0) / 360.0 * width)), 0, width - 1);
  const int y = std::clamp(static_cast<int>(std::floor((90.0 - latitudeDeg(d)) / 180.0 * height)), 0, height - 1);
  return y * width + x;
}

SphereMap computeSphereMap(const ViewDependentModel& model, const SphereMapSettings& settings) {
  model.requireThreeKeyWeights("the sphere map (its cells hold a view's triangle)");
  checkSettings(settings);
  MapInput in;
  in.sphere = &model.sphere();
  in.sharpness = model.sharpness();
  in.radius = model.extentRadius();
  const std::vector<float>& base = model.base().positions;
  for (std::size_t k = 0; k < model.keyCount(); ++k) {
    std::vector<float> delta(base.size());
    if (!model.keyPositions(k, delta)) throw Error("sphere map: cannot read key " + std::to_string(k));
    for (std::size_t i = 0; i < delta.size(); ++i) delta[i] -= base[i];
    if (allZero(delta)) delta.clear();
    in.deltas.push_back(std::move(delta));
  }
  return compute(in, settings);
}

SphereMap computeSphereMap(const AnimatedViewDependentModel& model, const SphereMapSettings& settings) {
  checkSettings(settings);
  if (settings.frame < 0 || settings.frame >= model.frameCount())
    throw Error("sphere map: frame " + std::to_string(settings.frame) + " is outside 0.." +
                std::to_string(model.frameCount() - 1));
  MapInput in;
  in.sphere = &model.sphere();
  in.sharpness = model.sharpness();
  in.radius = model.extentRadius();
  const std::size_t floats = 3 * model.vertexCount();
  const auto skin = model.baseSkin(settings.frame);
  const bool skinned = model.offsetSpace() == OffsetSpace::kSkinned;
  // Section 4.1: view i's offset at frame f is T_v(f) sum_j c_j(f) o_j.
  for (std::size_t i = 0; i < model.viewCount(); ++i) {
    std::vector<double> c(model.keyFrames(i).size());
    if (!model.timeCoefficients(i, settings.frame, c)) throw Error("sphere map: cannot read view " + std::to_string(i));
    std::vector<float> delta(floats, 0.0f);
    for (std::size_t j = 0; j < c.size(); ++j) {
      const auto o = model.offsets(i, j);
      for (std::size_t f = 0; f < floats; ++f) delta[f] += static_cast<float>(c[j] * o[f]);
    }
    if (skinned)
      for (std::size_t v = 0; v < model.vertexCount(); ++v) {
        const Eigen::Map<const Eigen::Matrix3f> m(skin.data() + 9 * v);
        const Eigen::Vector3f o(delta[3 * v], delta[3 * v + 1], delta[3 * v + 2]);
        const Eigen::Vector3f p = m * o;
        for (int a = 0; a < 3; ++a) delta[3 * v + a] = p[a];
      }
    if (allZero(delta)) delta.clear();
    in.deltas.push_back(std::move(delta));
  }
  return compute(in, settings);
}

}  // namespace vdg
