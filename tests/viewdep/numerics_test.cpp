// Hostile numbers: extreme sharpness, huge and tiny view vectors, many keys. Every
// answer must be the right one or a clear vdg::Error, never a silently wrong one.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "support/random_direction.h"
#include "support/test_meshes.h"
#include "vdg/geom/error.h"
#include "vdg/viewdep/model.h"
#include "vdg/viewdep/view_sphere.h"

namespace vdg {
namespace {

using Eigen::Vector3d;

constexpr float kWeightTol = 1e-5f;  // float weights
constexpr int kManyKeys = 20000;     // the report's slow case: 29 s with three quadratic checks

const std::vector<Vector3d> kOctahedron = {Vector3d(1, 0, 0),  Vector3d(-1, 0, 0), Vector3d(0, 1, 0),
                                           Vector3d(0, -1, 0), Vector3d(0, 0, 1),  Vector3d(0, 0, -1)};

// Weight of `key` in `w` (0 when absent).
float weightOf(const ViewWeights& w, int key) {
  float sum = 0.0f;
  for (int k = 0; k < 3; ++k)
    if (w.key[k] == key) sum += w.weight[k];
  return sum;
}

float total(const ViewWeights& w) { return w.weight[0] + w.weight[1] + w.weight[2] + w.base; }

void expectSameWeights(const ViewWeights& a, const ViewWeights& b, int keys) {
  for (int k = 0; k < keys; ++k) EXPECT_NEAR(weightOf(a, k), weightOf(b, k), kWeightTol) << "key " << k;
  EXPECT_NEAR(a.base, b.base, kWeightTol);
}

// The weights of a view that must be accepted (the per-frame query returns false on a violation).
ViewWeights weightsOf(const ViewSphere& s, const Vector3d& view, double alpha = 1.0) {
  ViewWeights w;
  EXPECT_TRUE(s.weights(view, alpha, w)) << "view " << view.transpose() << ", alpha " << alpha;
  return w;
}
ViewWeights weightsOf(const ViewDependentModel& m, const Vector3d& view, double alpha = 0.0) {
  ViewWeights w;
  EXPECT_TRUE(m.weights(view, alpha, w)) << "view " << view.transpose() << ", alpha " << alpha;
  return w;
}

using testing::randomDirection;

// ---- Sharpness (Rademacher 3.2.2) -------------------------------------------------------------

TEST(Sharpness, HugeAlphaGivesAllWeightToTheLargestKey) {
  const ViewSphere s = ViewSphere::build(kOctahedron);
  const Vector3d view(1, 0.5, 0.2);  // weights of +x, +y, +z: 0.59, 0.29, 0.12
  const ViewWeights plain = weightsOf(s, view, 1.0);
  ASSERT_NEAR(weightOf(plain, 0), 1.0 / 1.7, kWeightTol);
  for (const double alpha : {1100.0, 5000.0, 1e300}) {
    const ViewWeights w = weightsOf(s, view, alpha);
    EXPECT_NEAR(weightOf(w, 0), 1.0f, kWeightTol) << "alpha " << alpha;  // never the alpha = 1 weights
    EXPECT_NEAR(weightOf(w, 2), 0.0f, kWeightTol) << "alpha " << alpha;
    EXPECT_NEAR(weightOf(w, 4), 0.0f, kWeightTol) << "alpha " << alpha;
    EXPECT_NEAR(total(w), 1.0f, kWeightTol);
  }
}

TEST(Sharpness, TiesForTheLargestWeightShareIt) {
  const ViewSphere s = ViewSphere::build(kOctahedron);
  const ViewWeights w = weightsOf(s, Vector3d(1, 1, 0.3), 5000.0);  // +x and +y tie
  EXPECT_NEAR(weightOf(w, 0), 0.5f, kWeightTol);
  EXPECT_NEAR(weightOf(w, 2), 0.5f, kWeightTol);
  EXPECT_NEAR(weightOf(w, 4), 0.0f, kWeightTol);
}

TEST(Sharpness, ModerateAlphaStillFollowsThePaper) {
  const ViewSphere s = ViewSphere::build(kOctahedron);
  const Vector3d view(1, 0.5, 0.2);
  const double alpha = 3.0;
  const double p[3] = {std::pow(1.0, alpha), std::pow(0.5, alpha), std::pow(0.2, alpha)};
  const double sum = p[0] + p[1] + p[2];
  const ViewWeights w = weightsOf(s, view, alpha);
  EXPECT_NEAR(weightOf(w, 0), p[0] / sum, kWeightTol);
  EXPECT_NEAR(weightOf(w, 2), p[1] / sum, kWeightTol);
  EXPECT_NEAR(weightOf(w, 4), p[2] / sum, kWeightTol);
}

TEST(Sharpness, NanZeroNegativeAndInfiniteAreRefusedByTheFrameQuery) {
  const ViewSphere s = ViewSphere::build(kOctahedron);
  const Vector3d view(1, 0.5, 0.2);
  for (const double alpha : {std::numeric_limits<double>::quiet_NaN(), 0.0, -2.0,
                             std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()}) {
    ViewWeights w;
    w.base = 0.25f;  // a sentinel: a refused query writes nothing
    EXPECT_FALSE(s.weights(view, alpha, w)) << alpha;
    EXPECT_EQ(w.base, 0.25f);
  }
}

TEST(Sharpness, ModelRejectsNonFiniteOrNonPositiveSharpness) {
  RawViewDependentModel raw;
  raw.base = testing::uvSphere(4, 6);
  RawKey key;
  key.name = "a";
  key.mesh = raw.base;
  key.view = Vector3d(0, 0, 1);
  raw.keys.push_back(key);
  for (const double alpha :
       {0.0, -1.0, std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
    raw.sharpness = alpha;
    EXPECT_THROW(raw.validate(), Error) << alpha;
  }
  raw.sharpness = 5000.0;
  EXPECT_NO_THROW(ViewDependentModel::build(raw));
}

// ---- Huge and tiny vectors --------------------------------------------------------------------

TEST(RobustViews, HugeAndTinyViewsGiveTheUnitViewsWeights) {
  for (const Uncovered mode : {Uncovered::Base, Uncovered::Cosine}) {
    const ViewSphere s = ViewSphere::build(std::vector<Vector3d>{kOctahedron[0], kOctahedron[2], kOctahedron[4]},
                                           ViewSphereSettings{mode});
    std::mt19937 rng(7);
    for (int i = 0; i < 50; ++i) {
      const Vector3d v = randomDirection(rng);
      const ViewWeights unit = weightsOf(s, v, 1.5);
      for (const double scale : {1e155, 1e200, 1e300, 1e-155, 1e-200, 1e-300}) {
        SCOPED_TRACE(scale);
        expectSameWeights(weightsOf(s, v * scale, 1.5), unit, 3);
      }
    }
  }
}

TEST(RobustViews, HugeAndTinyKeyViewsAreReachable) {
  for (const double scale : {1e200, 1e-200}) {
    std::vector<Vector3d> views = kOctahedron;
    views[0] *= scale;
    const ViewSphere s = ViewSphere::build(views);
    EXPECT_NEAR(s.points()[0].norm(), 1.0, 1e-12);
    EXPECT_NEAR(weightOf(weightsOf(s, Vector3d(1, 0, 0)), 0), 1.0f, kWeightTol) << scale;
  }
}

RawViewDependentModel smallModel(const std::vector<Vector3d>& views) {
  RawViewDependentModel raw;
  raw.base = testing::uvSphere(4, 6);
  for (std::size_t k = 0; k < views.size(); ++k) {
    RawKey key;
    key.name = "k" + std::to_string(k);
    key.mesh = raw.base;
    key.mesh.positions[3 * k] += 0.25f;  // each key moves its own vertex
    key.view = views[k];
    raw.keys.push_back(std::move(key));
  }
  return raw;
}

TEST(RobustViews, ModelWithHugeKeyViewAndFarEyeBuildsAndReachesTheKey) {
  std::vector<Vector3d> views = kOctahedron;
  views[0] = Vector3d(1e200, 0, 0);  // the report's manifest key, once accepted but unreachable
  views[2] = Vector3d(0, 1e-200, 0);
  RawViewDependentModel raw = smallModel(views);
  raw.keys[4].camera = Camera{};
  raw.keys[4].camera->eye = Vector3d(0, 0, 1e250);
  raw.keys[4].camera->target = Vector3d::Zero();
  raw.resolveViews();
  EXPECT_NEAR((raw.keys[4].view - Vector3d(0, 0, 1)).norm(), 0.0, 1e-12);
  const ViewDependentModel model = ViewDependentModel::build(raw);
  EXPECT_NEAR(weightOf(weightsOf(model, Vector3d(1, 0, 0)), 0), 1.0f, kWeightTol);
  EXPECT_NEAR(weightOf(weightsOf(model, Vector3d(0, 1, 0)), 2), 1.0f, kWeightTol);
  EXPECT_NEAR(weightOf(weightsOf(model, model.viewFromEye(Vector3d(0, 0, 1e250))), 4), 1.0f, kWeightTol);
  EXPECT_NEAR(weightOf(weightsOf(model, Vector3d(1e-250, 0, 0), 2.0), 0), 1.0f, kWeightTol);
  EXPECT_EQ(model.viewFromEye(model.center()), Vector3d::Zero());
}

TEST(RobustViews, KeyWhoseOffsetOverflowsAFloatIsRejected) {
  RawViewDependentModel raw = smallModel({Vector3d(1, 0, 0)});
  raw.base.positions[0] = 3e38f;
  raw.keys[0].mesh.positions[0] = -3e38f;
  for (std::size_t i = 1; i < raw.base.positions.size(); ++i) raw.keys[0].mesh.positions[i] = raw.base.positions[i];
  try {
    raw.validate();
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("key 'k0' (keys[0]): vertex 0 moves too far from the base's"),
              std::string::npos)
        << e.what();
  }
}

// ---- Same-view search: once, O(n log n) -------------------------------------------------------

std::vector<Vector3d> randomViews(int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::vector<Vector3d> views;
  for (int i = 0; i < n; ++i) views.push_back(randomDirection(rng));
  return views;
}

TEST(SameView, CloseViewPairsMatchTheBruteForceSearchInOrder) {
  const std::vector<Vector3d> views = randomViews(600, 3);
  for (const double max_angle : {0.02, 0.2, 1.0, 3.2}) {
    std::vector<std::pair<std::size_t, std::size_t>> expected, found;
    for (std::size_t i = 0; i < views.size(); ++i)
      for (std::size_t j = 0; j < i; ++j)
        if (std::atan2(views[i].cross(views[j]).norm(), views[i].dot(views[j])) < max_angle)
          expected.emplace_back(i, j);
    forEachCloseViewPair(views, max_angle, [&](std::size_t i, std::size_t j, double angle) {
      EXPECT_LT(angle, max_angle);
      found.emplace_back(i, j);
      return true;
    });
    EXPECT_EQ(found, expected) << "max angle " << max_angle;
  }
}

// Key views within kNearlySameViewDeg (but not one viewpoint) are the pairs vdg info and vdg studio
// warn about: a near-degenerate hull triangle whose weights flip between its two close corners.
TEST(SameView, NearlySameViewPairsAreTheCloseButDistinctOnes) {
  constexpr double kDeg = std::numbers::pi / 180.0;
  auto at = [&](double azimuth_deg) { return Vector3d(std::sin(azimuth_deg * kDeg), 0, std::cos(azimuth_deg * kDeg)); };
  const std::vector<Vector3d> views = {at(0),   at(kNearlySameViewDeg - 0.1),
                                       at(90),  at(90 + kNearlySameViewDeg + 0.1),
                                       at(200), at(200)};  // the last two: one viewpoint (keys at two frames)
  std::vector<NearlySameViewPair> listed;
  EXPECT_EQ(nearlySameViewPairs(views, 10, 100, listed), 1u);
  ASSERT_EQ(listed.size(), 1u);
  EXPECT_EQ(listed[0].i, 1u);
  EXPECT_EQ(listed[0].j, 0u);
  EXPECT_NEAR(listed[0].angle_deg, kNearlySameViewDeg - 0.1, 1e-9);
  // Listing and counting stop where asked.
  const std::vector<Vector3d> cluster = {at(0), at(1), at(2), at(3)};  // 6 close pairs
  listed.clear();
  EXPECT_EQ(nearlySameViewPairs(cluster, 2, 100, listed), 6u);
  EXPECT_EQ(listed.size(), 2u);
  listed.clear();
  EXPECT_EQ(nearlySameViewPairs(cluster, 2, 4, listed), 4u);
}

TEST(SameView, VisitingStopsWhenAskedTo) {
  const std::vector<Vector3d> views = randomViews(200, 5);
  int calls = 0;
  const std::size_t visited =
      forEachCloseViewPair(views, 3.2, [&](std::size_t, std::size_t, double) { return ++calls < 3; });
  EXPECT_EQ(visited, 3u);
  EXPECT_EQ(calls, 3);
}

TEST(SameView, TwentyThousandKeysBuildAndAPlantedDuplicateIsFound) {
  std::vector<Vector3d> views = randomViews(kManyKeys, 11);
  const ViewSphere s = ViewSphere::build(views);
  EXPECT_EQ(s.keyCount(), static_cast<std::size_t>(kManyKeys));
  // Plant key 17000 within 1e-7 rad of key 1234 (and 7 times as long).
  const Vector3d axis = views[1234].unitOrthogonal();
  views[17000] = 7.0 * (Eigen::AngleAxisd(1e-7, axis) * views[1234]);
  try {
    ViewSphere::build(views);
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), "key 17000: same view direction as key 1234 (within 1e-6 rad)");
  }
}

TEST(SameView, ModelNamesBothKeysOfAPlantedDuplicate) {
  std::vector<Vector3d> views = randomViews(kManyKeys, 13);
  views[15000] = views[42] * 1e100;
  RawViewDependentModel raw;
  raw.source = "many.vdg.json";
  raw.base.positions = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  raw.base.triangles = {0, 1, 2};
  for (int k = 0; k < kManyKeys; ++k) {
    RawKey key;
    key.name = "k" + std::to_string(k);
    key.mesh = raw.base;
    key.view = views[static_cast<std::size_t>(k)];
    raw.keys.push_back(std::move(key));
  }
  const std::string expected = "many.vdg.json: key 'k15000' (keys[15000]): same view direction as key 'k42'";
  for (int pass = 0; pass < 2; ++pass) {
    try {
      if (pass == 0) raw.validate();
      if (pass == 1) ViewDependentModel::build(raw);
      FAIL() << "expected an error";
    } catch (const Error& e) {
      EXPECT_EQ(std::string(e.what()).substr(0, expected.size()), expected) << "pass " << pass << ": " << e.what();
    }
  }
  std::mt19937 rng(99);
  raw.keys[15000].view = randomDirection(rng);
  EXPECT_NO_THROW(ViewDependentModel::build(raw));
}

TEST(SameView, TooManyKeysIsAnError) {
  RawViewDependentModel raw;
  raw.base.positions = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  raw.base.triangles = {0, 1, 2};
  raw.keys.resize(kMaxKeys + 1);
  try {
    raw.validate();
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("a model may have at most 100000"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace vdg
