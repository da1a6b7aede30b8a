// Key-frame tracks through the scene (Parent 4.9): a field driven by a track has exactly the value
// the anim library's Track gives at that frame, and the hierarchy uses it.
#include <gtest/gtest.h>

#include <cmath>

#include "scene_fixtures.h"

namespace vdg::scene {
namespace {

using namespace fixtures;

constexpr double kTol = 1e-12;

anim::RawTrack vectorTrack(anim::Interpolation interpolation) {
  anim::RawTrack t;
  t.type = anim::TrackType::kVector;
  t.interpolation = interpolation;
  t.keys = {key(0, values({0, 0, 0})), key(10, values({4, 1, -2})), key(25, values({5, 6, 0})),
            key(40, values({-3, 2, 1}))};
  t.keys[1].ease = anim::Ease::sine();
  return t;
}

TEST(SceneTracks, FieldTrackEqualsTheLibrarysTrack) {
  for (anim::Interpolation interpolation :
       {anim::Interpolation::kLinear, anim::Interpolation::kCatmullRom, anim::Interpolation::kNaturalCubic,
        anim::Interpolation::kParabolicBlending}) {
    RawScene raw;
    const int cam = addNode(raw, "cam", -1, ObjectKind::kCamera);
    const int box = addNode(raw, "box");
    raw.tracks.push_back({box, Field::kTranslation, vectorTrack(interpolation)});
    anim::RawTrack fov;
    fov.type = anim::TrackType::kScalar;
    fov.interpolation = interpolation;
    fov.keys = {key(0, values({30})), key(12, values({50})), key(20, values({45})), key(33, values({60}))};
    raw.tracks.push_back({cam, Field::kFov, fov});
    anim::RawTrack spin;
    spin.type = anim::TrackType::kRotation;
    spin.interpolation = anim::Interpolation::kQuaternionCurve;
    spin.keys = {key(0, quaternionValue(turn({0, 1, 0}, 0))), key(10, quaternionValue(turn({1, 1, 0}, 80))),
                 key(30, quaternionValue(turn({0, 0, 1}, 120)))};
    raw.tracks.push_back({box, Field::kRotation, spin});
    const Scene scene = Scene::build(raw);

    const anim::Track translation = anim::Track::build(vectorTrack(interpolation));
    const anim::Track fov_track = anim::Track::build(fov);
    const anim::Track spin_track = anim::Track::build(spin);
    for (double f = -3.0; f <= 45.0; f += 0.7) {
      double t[3], q[4], v = 0.0;
      ASSERT_TRUE(scene.fieldValue(box, Field::kTranslation, f, t));
      ASSERT_TRUE(scene.fieldValue(box, Field::kRotation, f, q));
      ASSERT_TRUE(scene.fieldValue(cam, Field::kFov, f, std::span<double>(&v, 1)));
      const Eigen::VectorXd expected_t = translation.at(f), expected_q = spin_track.at(f);
      for (int k = 0; k < 3; ++k) EXPECT_EQ(t[k], expected_t[k]) << anim::interpolationName(interpolation) << " " << f;
      for (int k = 0; k < 4; ++k) EXPECT_EQ(q[k], expected_q[k]) << f;
      EXPECT_EQ(v, fov_track.at(f)[0]) << f;
      // evaluate() puts the track's values into the node's state.
      const auto s = evaluated(scene, f);
      EXPECT_LT((origin(s[static_cast<std::size_t>(box)]) - expected_t).norm(), kTol);
      EXPECT_EQ(s[static_cast<std::size_t>(cam)].fov_deg, fov_track.at(f)[0]);
      const Eigen::Quaterniond r(expected_q[0], expected_q[1], expected_q[2], expected_q[3]);
      EXPECT_LT((s[static_cast<std::size_t>(box)].world.topLeftCorner<3, 3>() - r.toRotationMatrix()).norm(), kTol);
    }
  }
}

TEST(SceneTracks, ScalarFieldsTakeOneComponentVectorTracks) {
  RawScene raw;
  addNode(raw, "g");
  anim::RawTrack visible;
  visible.type = anim::TrackType::kVector;
  visible.interpolation = anim::Interpolation::kStep;
  visible.keys = {key(0, values({1})), key(5, values({0})), key(9, values({1}))};
  raw.tracks.push_back({0, Field::kVisible, visible});
  const Scene scene = Scene::build(raw);
  EXPECT_TRUE(evaluated(scene, 4.9)[0].visible);
  EXPECT_FALSE(evaluated(scene, 5)[0].visible);
  EXPECT_TRUE(evaluated(scene, 9)[0].visible);
}

}  // namespace
}  // namespace vdg::scene
