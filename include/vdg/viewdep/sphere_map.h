// Where to key next: measures of every direction of the viewing sphere, sampled on an
// equirectangular grid (vdg info --sphere-map, the studio's heat map; docs/where-to-key.md).
//
// Rademacher 99 leaves the choice of key views to the artist (section 3.1); Fukusato and Maejima
// (MIG 2021) ask for help choosing them. For each sampled direction d this computes
//  - nearest_key_deg: the angle from d to the nearest key view (degrees, atan2(|a x b|, a.b));
//  - speed: how fast the blended shape changes when the camera moves at d. The blend is linear in
//    the weights (section 3.2.3: v = base + sum_i w_i D_i, D_i = key_i - base), so the displacement
//    of vertex v between two views is sum_i (w_i(d1) - w_i(d2)) D_i,v. Central differences over
//    2 * step_deg along the two tangent axes of the grid (east, north), the largest vertex
//    displacement per degree of camera motion over both axes, divided by the model's
//    extentRadius(): 0.01 means 1% of the model's radius per degree. Inside one hull triangle it
//    is smooth; it jumps across hull edges (the barycentric weights' gradient changes there) and
//    is largest where close keys differ (thin triangles): the popping risk;
//  - uncovered: the base model's weight at d (section 3.3): > 0 outside the keys' hull (dummy
//    base points, or the cosine falloff);
//  - need = kNeedAngleWeight * nearest_key_deg / max(nearest_key_deg) + kNeedUncoveredWeight *
//    uncovered + kNeedSpeedWeight * speed / max(speed), in [0, 1] (a term whose maximum is 0 adds
//    0). Distance from every drawing weighs most (a new key there changes most of the map); the
//    base showing through and fast change (popping) share the rest. The suggested view is the cell
//    of largest need (the first in row order on ties).
// An animated model (section 4) is measured at one integer frame: D_i is view i's pose at that
// frame minus the base at that frame (T_v(f) o_i(f), vdg/viewdep/animated_model.h).
//
// Grid: cell (x, y), x in [0, width), y in [0, height), row 0 at the top. Its centre has longitude
// lon = -180 + (x + 0.5) * 360 / width and latitude lat = 90 - (y + 0.5) * 180 / height (degrees),
// direction (cos lat sin lon, sin lat, cos lat cos lon): Y up, +Z (the front) at the image's
// centre, +X at longitude +90 (right of the centre).
// Cost: width x height x (2 x 2 weight queries + the nearest-key scan over K keys + 2 x #V x (up
// to 6) multiply-adds), threaded over rows (vdg/geom/parallel.h): about a second for Spot at
// 360x180 on two cores.
#pragma once

#include <cstddef>
#include <vector>

#include <Eigen/Core>

#include "vdg/viewdep/animated_model.h"
#include "vdg/viewdep/model.h"

namespace vdg {

struct SphereMapSettings {
  int width = 360, height = 180;  // cells, each in [1, kMaxSphereMapSide]
  double step_deg = 0.25;         // finite-difference half step of the speed, in (0, 10]
  int frame = 0;                  // animated models: the frame, in [0, frameCount())
};
inline constexpr int kMaxSphereMapSide = 4096;
// The need score's weights (they sum to 1).
inline constexpr double kNeedAngleWeight = 0.6;
inline constexpr double kNeedUncoveredWeight = 0.2;
inline constexpr double kNeedSpeedWeight = 0.2;
// A cell counts as uncovered when the base's weight there exceeds this.
inline constexpr double kUncoveredWeight = 1e-6;

struct SphereMap {
  int width = 0, height = 0;
  // Per cell, row-major (index y * width + x): see the header comment.
  std::vector<float> nearest_key_deg, speed, uncovered, need;
  std::vector<Eigen::Vector3d> keys;  // unit key views (an animated model's views)

  // Statistics (angles in degrees; fractions weighted by cell area, cos(lat)).
  double max_nearest_deg = 0, mean_nearest_deg = 0;
  double max_speed = 0;
  Eigen::Vector3d max_speed_view = Eigen::Vector3d::UnitZ();
  double uncovered_fraction = 0;  // of the sphere's area with base weight > kUncoveredWeight
  int suggested_cell = 0;         // largest need
  Eigen::Vector3d suggested = Eigen::Vector3d::UnitZ();

  // The unit direction of cell (x, y)'s centre for a width x height grid.
  static Eigen::Vector3d cellDirection(int width, int height, int x, int y);
  // Longitude and latitude (degrees) of a unit direction, as the grid has them.
  static double longitudeDeg(const Eigen::Vector3d& d);
  static double latitudeDeg(const Eigen::Vector3d& d);
  // The cell that the direction d falls in.
  int cellOf(const Eigen::Vector3d& d) const;
};

// The map of a static model. Throws vdg::Error for settings outside their ranges.
SphereMap computeSphereMap(const ViewDependentModel& model, const SphereMapSettings& settings = {});
// The map of an animated model at settings.frame. Throws vdg::Error for settings outside their
// ranges (a frame outside [0, frameCount()) among them).
SphereMap computeSphereMap(const AnimatedViewDependentModel& model, const SphereMapSettings& settings = {});

}  // namespace vdg
