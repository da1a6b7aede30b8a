// The transformation hierarchy (Parent 4.7): world = world(parent) * link, object = world *
// placement, checked on the text's sun-earth-moon example with numbers worked out by hand.
#include <gtest/gtest.h>

#include <cmath>

#include "scene_fixtures.h"

namespace vdg::scene {
namespace {

using namespace fixtures;

// Positions are ~1e8 miles; rounding in the slerped rotations is ~1e-16 of that.
constexpr double kTolMiles = 1e-3;
constexpr double kTol = 1e-12;

constexpr double kEarthOrbitMiles = 93e6;
constexpr double kEarthPeriodDays = 365.0;
constexpr double kMoonOrbitMiles = 220e3;
constexpr double kMoonPeriodDays = 28.0;

// A rotation track turning once about +Y every `period` frames, looping: keys every quarter turn
// (slerp between keys 90 degrees apart turns at a constant rate).
RawFieldTrack orbitTrack(int node, double period) {
  RawFieldTrack t;
  t.node = node;
  t.field = Field::kRotation;
  t.track.type = anim::TrackType::kRotation;
  t.track.interpolation = anim::Interpolation::kSlerp;
  t.track.extrapolation = anim::Extrapolation::kLoop;
  for (int q = 0; q <= 4; ++q) {
    t.track.keys.push_back(key(period * q / 4.0, quaternionValue(turn(Eigen::Vector3d::UnitY(), 90.0 * q))));
  }
  return t;
}

// sun -> earth orbit (Re) -> earth (Te) -> moon orbit (Rm) -> moon (Tm): M' = M Tm Rm Te Re.
RawScene sunEarthMoon() {
  RawScene s;
  const int sun = addNode(s, "sun");
  const int earth_orbit = addNode(s, "earth_orbit", sun);
  const int earth = addNode(s, "earth", earth_orbit);
  const int moon_orbit = addNode(s, "moon_orbit", earth);
  const int moon = addNode(s, "moon", moon_orbit);
  s.nodes[static_cast<std::size_t>(earth)].link.translation = {kEarthOrbitMiles, 0, 0};
  s.nodes[static_cast<std::size_t>(moon)].link.translation = {kMoonOrbitMiles, 0, 0};
  s.tracks.push_back(orbitTrack(earth_orbit, kEarthPeriodDays));
  s.tracks.push_back(orbitTrack(moon_orbit, kMoonPeriodDays));
  return s;
}

// A turn by angle a about +Y takes (r, 0, 0) to (r cos a, 0, -r sin a).
Eigen::Vector3d onOrbit(double radius, double angle) {
  return {radius * std::cos(angle), 0.0, -radius * std::sin(angle)};
}

TEST(SceneHierarchy, SunEarthMoonPositionsByHand) {
  const Scene scene = Scene::build(sunEarthMoon());
  const int earth = scene.findNode("earth"), moon = scene.findNode("moon");
  ASSERT_GE(earth, 0);
  ASSERT_GE(moon, 0);
  for (double day : {0.0, 7.0, 14.0, 91.25, 182.5, 200.0, 365.0, 400.0}) {
    const auto states = evaluated(scene, day);
    ASSERT_EQ(states.size(), 5u);
    const double earth_angle = 2.0 * M_PI * day / kEarthPeriodDays;
    const double moon_angle = 2.0 * M_PI * day / kMoonPeriodDays;
    const Eigen::Vector3d earth_expected = onOrbit(kEarthOrbitMiles, earth_angle);
    // The moon's turn about the earth is carried by the earth's own turn about the sun.
    const Eigen::Vector3d moon_expected = earth_expected + onOrbit(kMoonOrbitMiles, earth_angle + moon_angle);
    EXPECT_LT((origin(states[static_cast<std::size_t>(earth)]) - earth_expected).norm(), kTolMiles) << "day " << day;
    EXPECT_LT((origin(states[static_cast<std::size_t>(moon)]) - moon_expected).norm(), kTolMiles) << "day " << day;
  }
}

TEST(SceneHierarchy, SunEarthMoonNamedDays) {
  const Scene scene = Scene::build(sunEarthMoon());
  const auto earth = static_cast<std::size_t>(scene.findNode("earth"));
  const auto moon = static_cast<std::size_t>(scene.findNode("moon"));
  // Day 0: earth on +X, moon 220e3 miles further out.
  auto s = evaluated(scene, 0.0);
  EXPECT_LT((origin(s[earth]) - Eigen::Vector3d(93e6, 0, 0)).norm(), kTolMiles);
  EXPECT_LT((origin(s[moon]) - Eigen::Vector3d(93.22e6, 0, 0)).norm(), kTolMiles);
  // Day 91.25: a quarter year, the earth on -Z; the moon 3.2589... of its turns on.
  s = evaluated(scene, 91.25);
  EXPECT_LT((origin(s[earth]) - Eigen::Vector3d(0, 0, -93e6)).norm(), kTolMiles);
  // Day 182.5: half a year, the earth on -X.
  s = evaluated(scene, 182.5);
  EXPECT_LT((origin(s[earth]) - Eigen::Vector3d(-93e6, 0, 0)).norm(), kTolMiles);
  // Day 14: half a moon turn; the earth has turned 14/365 of a circle, the moon is on the sun's side.
  s = evaluated(scene, 14.0);
  const Eigen::Vector3d to_sun = -origin(s[earth]).normalized();
  EXPECT_LT((origin(s[moon]) - (origin(s[earth]) + kMoonOrbitMiles * to_sun)).norm(), kTolMiles);
}

TEST(SceneHierarchy, MoonIsEarthPlusItsRotatedOffset) {
  const Scene scene = Scene::build(sunEarthMoon());
  const auto earth = static_cast<std::size_t>(scene.findNode("earth"));
  const auto moon_orbit = static_cast<std::size_t>(scene.findNode("moon_orbit"));
  const auto moon = static_cast<std::size_t>(scene.findNode("moon"));
  for (double day = 0.0; day <= 60.0; day += 3.7) {
    const auto s = evaluated(scene, day);
    const Eigen::Matrix3d rotation = s[moon_orbit].world.topLeftCorner<3, 3>();
    const Eigen::Vector3d expected = origin(s[earth]) + rotation * Eigen::Vector3d(kMoonOrbitMiles, 0, 0);
    EXPECT_LT((origin(s[moon]) - expected).norm(), kTolMiles) << "day " << day;
    // The world matrices stay rigid: rotation columns orthonormal.
    EXPECT_LT((rotation.transpose() * rotation - Eigen::Matrix3d::Identity()).norm(), kTol);
  }
}

TEST(SceneHierarchy, LinkIsTranslateRotateScaleAndObjectAddsPlacement) {
  RawScene raw;
  const int root = addNode(raw, "root");
  const int child = addNode(raw, "child", root);
  RawNode& r = raw.nodes[static_cast<std::size_t>(root)];
  r.link.translation = {1, 2, 3};
  r.link.rotation = turn(Eigen::Vector3d::UnitZ(), 90);
  r.link.scale = {2, 2, 2};
  RawNode& c = raw.nodes[static_cast<std::size_t>(child)];
  c.link.translation = {1, 0, 0};
  c.placement.translation = {0, -1, 0};  // the object's attachment point (0, 1, 0) moved to the origin
  const Scene scene = Scene::build(raw);
  const auto s = evaluated(scene, 0.0);
  // root: p -> T(1,2,3) Rz(90) S(2) p; child origin (1,0,0) -> (0,2,0) -> +(1,2,3) = (1,4,3).
  EXPECT_LT((origin(s[1]) - Eigen::Vector3d(1, 4, 3)).norm(), kTol);
  // The object's point (0, 1, 0) (its attachment point) lands on the child's origin.
  const Eigen::Vector4d attached = s[1].object * Eigen::Vector4d(0, 1, 0, 1);
  EXPECT_LT((attached.head<3>() - Eigen::Vector3d(1, 4, 3)).norm(), kTol);
  EXPECT_LT((s[0].world - r.link.matrix()).norm(), kTol);
}

}  // namespace
}  // namespace vdg::scene
