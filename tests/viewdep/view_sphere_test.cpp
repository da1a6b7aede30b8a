#include "vdg/viewdep/view_sphere.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <map>
#include <numbers>
#include <random>

#include "support/dense_weights.h"
#include "support/random_direction.h"
#include "vdg/geom/error.h"

namespace vdg {
namespace {

using Eigen::Vector3d;

constexpr double kWeightTol = 1e-5;  // float weights
constexpr int kRandomViews = 10000;
// Along a path sampled every kPathStep radians, the weights (as a vector over keys and base) may
// change by at most kLipschitz * kPathStep in L1: continuous, with a generous slope bound; a jump
// anywhere would be of order 0.1 to 1.
constexpr double kPathStep = 5e-4;
constexpr double kLipschitz = 60.0;

using testing::denseWeights;

// weights() for a query that is valid by construction (the contract cases are in contract_test).
ViewWeights weightsOf(const ViewSphere& s, const Vector3d& view, double sharpness = 1.0, int* hint = nullptr) {
  ViewWeights w;
  EXPECT_TRUE(s.weights(view, sharpness, w, hint)) << view.transpose();
  return w;
}

using testing::randomDirection;

Vector3d fromAngles(double azimuth_deg, double elevation_deg) {
  const double a = azimuth_deg * std::numbers::pi / 180.0, e = elevation_deg * std::numbers::pi / 180.0;
  return {std::cos(e) * std::sin(a), std::sin(e), std::cos(e) * std::cos(a)};
}

// Every key-set configuration the issue names, plus a few more.
std::map<std::string, std::vector<Vector3d>> configurations() {
  std::map<std::string, std::vector<Vector3d>> c;
  c["one key"] = {Vector3d(0, 0, 1)};
  c["two keys"] = {Vector3d(0, 0, 1), Vector3d(1, 0, 0.2)};
  c["two antipodal keys"] = {Vector3d(0, 0, 1), Vector3d(0, 0, -1)};
  c["three keys on a great circle, within a half"] = {fromAngles(-60, 0), fromAngles(0, 0), fromAngles(70, 0)};
  c["five keys around a great circle"] = {fromAngles(0, 0), fromAngles(72, 0), fromAngles(144, 0), fromAngles(216, 0),
                                          fromAngles(288, 0)};
  c["keys on a small circle"] = {fromAngles(0, 40), fromAngles(90, 40), fromAngles(180, 40), fromAngles(270, 40)};
  c["keys in one hemisphere"] = {fromAngles(0, 10), fromAngles(60, 30), fromAngles(-50, 20), fromAngles(20, 70),
                                 fromAngles(100, 5)};
  c["keys in a closed hemisphere, some on its rim"] = {fromAngles(0, 0), fromAngles(120, 0), fromAngles(240, 0) * 1.0,
                                                       fromAngles(30, 60)};
  c["octahedron"] = {Vector3d(1, 0, 0),  Vector3d(-1, 0, 0), Vector3d(0, 1, 0),
                     Vector3d(0, -1, 0), Vector3d(0, 0, 1),  Vector3d(0, 0, -1)};
  c["cube corners (square faces)"] = {};
  for (int i = 0; i < 8; ++i)
    c["cube corners (square faces)"].push_back(Vector3d(i & 1 ? 1 : -1, i & 2 ? 1 : -1, i & 4 ? 1 : -1));
  std::mt19937 rng(7);
  for (int i = 0; i < 20; ++i) c["twenty random keys"].push_back(randomDirection(rng));
  return c;
}

const std::vector<Uncovered> kModes = {Uncovered::Base, Uncovered::Cosine, Uncovered::Cosine2};

std::string modeName(Uncovered u) {
  return u == Uncovered::Base ? "base" : u == Uncovered::Cosine ? "cosine" : "cosine2";
}

TEST(ViewSphere, OctahedronMatchesTheNumbersOfTheIssue) {
  const auto keys = configurations()["octahedron"];
  const ViewSphere s = ViewSphere::build(keys);
  EXPECT_EQ(s.points().size(), 6u) << "an enclosing key set needs no dummy base keys";
  EXPECT_EQ(s.triangles().size(), 8u);
  EXPECT_NEAR(s.coveredFraction(), 1.0, 1e-12);
  auto d = denseWeights(s, weightsOf(s, Vector3d(1, 1, 1)));
  EXPECT_NEAR(d[0], 1.0 / 3, kWeightTol);  // +X
  EXPECT_NEAR(d[2], 1.0 / 3, kWeightTol);  // +Y
  EXPECT_NEAR(d[4], 1.0 / 3, kWeightTol);  // +Z
  d = denseWeights(s, weightsOf(s, Vector3d(1, 1, 0.2)));
  EXPECT_NEAR(d[0], 1.0 / 2.2, kWeightTol);
  EXPECT_NEAR(d[2], 1.0 / 2.2, kWeightTol);
  EXPECT_NEAR(d[4], 0.2 / 2.2, kWeightTol);
  // Sharpness alpha = 2: squares, renormalised (paper 3.2.2).
  d = denseWeights(s, weightsOf(s, Vector3d(1, 1, 0.2), 2.0));
  const double sum = (1.0 + 1.0 + 0.04) / (2.2 * 2.2);
  EXPECT_NEAR(d[0], (1.0 / (2.2 * 2.2)) / sum, kWeightTol);
  EXPECT_NEAR(d[4], (0.04 / (2.2 * 2.2)) / sum, kWeightTol);
  EXPECT_NEAR(d.back(), 0.0, kWeightTol);
}

TEST(ViewSphere, SharpnessMovesTowardsTheNearestKey) {
  const ViewSphere s = ViewSphere::build(configurations()["octahedron"]);
  const Vector3d view(1, 0.5, 0.3);
  double previous = 0.0;
  for (double alpha : {0.5, 1.0, 2.0, 4.0, 16.0}) {
    const double w = denseWeights(s, weightsOf(s, view, alpha))[0];
    EXPECT_GT(w, previous) << "alpha " << alpha;
    previous = w;
  }
  EXPECT_GT(previous, 0.99);
}

TEST(ViewSphere, EachKeyViewGivesThatKeyAlone) {
  for (const auto& [name, keys] : configurations()) {
    for (Uncovered mode : kModes) {
      const ViewSphere s = ViewSphere::build(keys, {mode});
      for (std::size_t k = 0; k < keys.size(); ++k) {
        for (double alpha : {0.5, 1.0, 3.0}) {
          const auto d = denseWeights(s, weightsOf(s, keys[k], alpha));
          for (std::size_t j = 0; j < d.size(); ++j)
            EXPECT_NEAR(d[j], j == k ? 1.0 : 0.0, kWeightTol) << name << ", " << modeName(mode) << ", key " << k;
        }
      }
    }
  }
}

TEST(ViewSphere, WeightsSumToOneEverywhere) {
  std::mt19937 rng(42);
  for (const auto& [name, keys] : configurations()) {
    for (Uncovered mode : kModes) {
      const ViewSphere s = ViewSphere::build(keys, {mode});
      int hint = -1;
      for (int i = 0; i < kRandomViews; ++i) {
        const Vector3d v = randomDirection(rng);
        const double alpha = i % 3 == 0 ? 2.0 : 1.0;
        const ViewWeights w = weightsOf(s, v, alpha, &hint);
        double sum = w.base;
        EXPECT_GE(w.base, -kWeightTol);
        for (int k = 0; k < 3; ++k) {
          EXPECT_GE(w.weight[k], -kWeightTol);
          EXPECT_LE(w.weight[k], 1.0 + kWeightTol);
          if (w.key[k] >= 0) {
            EXPECT_LT(w.key[k], static_cast<int>(keys.size()));
          }
          sum += w.weight[k];
        }
        ASSERT_NEAR(sum, 1.0, kWeightTol) << name << ", " << modeName(mode) << ", view " << v.transpose();
      }
    }
  }
}

TEST(ViewSphere, WeightsAreContinuousAlongGreatCircles) {
  // Several great circles, through keys, hull edges and dummy points alike.
  const std::vector<std::pair<Vector3d, Vector3d>> circles = {
      {Vector3d(0, 0, 1), Vector3d(1, 0, 0)},
      {Vector3d(0, 0, 1), Vector3d(0, 1, 0)},
      {Vector3d(1, 1, 1).normalized(), Vector3d(1, -1, 0).normalized()},
      {Vector3d(0.3, -0.2, 0.93).normalized(), Vector3d(0.2, 0.97, 0).normalized()}};
  for (const auto& [name, keys] : configurations()) {
    for (Uncovered mode : kModes) {
      const ViewSphere s = ViewSphere::build(keys, {mode});
      for (const auto& [a, b_raw] : circles) {
        const Vector3d b = (b_raw - b_raw.dot(a) * a).normalized();
        std::vector<double> previous = denseWeights(s, weightsOf(s, a));
        const int steps = static_cast<int>(2 * std::numbers::pi / kPathStep);
        double worst = 0.0;
        for (int i = 1; i <= steps; ++i) {
          const double t = i * kPathStep;
          const Vector3d v = std::cos(t) * a + std::sin(t) * b;
          const std::vector<double> d = denseWeights(s, weightsOf(s, v));
          double change = 0.0;
          for (std::size_t j = 0; j < d.size(); ++j) change += std::abs(d[j] - previous[j]);
          worst = std::max(worst, change);
          previous = d;
        }
        EXPECT_LE(worst, kLipschitz * kPathStep)
            << name << ", " << modeName(mode) << ", circle through " << a.transpose();
      }
    }
  }
}

TEST(ViewSphere, BaseModeRevertsToTheBaseFarFromEveryKey) {
  const std::vector<Vector3d> front = {fromAngles(0, 0), fromAngles(40, 0), fromAngles(-40, 0), fromAngles(0, 35)};
  const ViewSphere s = ViewSphere::build(front);
  EXPECT_GT(s.points().size(), front.size()) << "a one-sided key set needs dummy base keys";
  for (const Vector3d& v : {fromAngles(180, 0), fromAngles(150, 20), Vector3d(0, -1, 0), fromAngles(-120, -30)}) {
    const ViewWeights w = weightsOf(s, v);
    EXPECT_NEAR(w.base, 1.0, kWeightTol) << v.transpose();
  }
  // Every dummy is farther than the falloff angle from every key.
  const double min_cos = std::cos(ViewSphereSettings{}.base_falloff_deg * std::numbers::pi / 180.0);
  for (std::size_t p = front.size(); p < s.points().size(); ++p)
    for (const Vector3d& k : front) EXPECT_LT(s.points()[p].dot(k.normalized()), min_cos);
  EXPECT_LT(s.coveredFraction(), 0.2);
}

TEST(ViewSphere, SingleKeyCosineIsThePapersFormula) {
  const Vector3d key = Vector3d(0.2, 0.1, 1).normalized();
  const ViewSphere cosine = ViewSphere::build(std::vector<Vector3d>{key}, {Uncovered::Cosine});
  const ViewSphere cosine2 = ViewSphere::build(std::vector<Vector3d>{key}, {Uncovered::Cosine2});
  std::mt19937 rng(3);
  for (int i = 0; i < 1000; ++i) {
    const Vector3d v = randomDirection(rng);
    const double c = std::max(0.0, key.dot(v));
    // Paper 3.3: max(0, Vkey.Veye) for the key; the base gets the rest (1 - w), also behind the key.
    ViewWeights w = weightsOf(cosine, v);
    EXPECT_NEAR(denseWeights(cosine, w)[0], c, kWeightTol);
    EXPECT_NEAR(w.base, 1.0 - c, kWeightTol);
    w = weightsOf(cosine2, v);
    EXPECT_NEAR(denseWeights(cosine2, w)[0], c * c, kWeightTol);
  }
}

TEST(ViewSphere, TwoKeyCosineBlendsAlongTheArcAndFallsOffAcrossIt) {
  const Vector3d a(0, 0, 1), b(1, 0, 0);
  const ViewSphere s = ViewSphere::build(std::vector<Vector3d>{a, b}, {Uncovered::Cosine});
  // On the arc: chord-barycentric weights, no base.
  const Vector3d mid = (a + b).normalized();
  auto d = denseWeights(s, weightsOf(s, mid));
  EXPECT_NEAR(d[0], 0.5, kWeightTol);
  EXPECT_NEAR(d[1], 0.5, kWeightTol);
  EXPECT_NEAR(d[2], 0.0, kWeightTol);
  // 30 degrees off the arc's middle, straight up: falloff cos(30 deg) of the same 50/50 blend.
  const Vector3d off = std::cos(std::numbers::pi / 6) * mid + std::sin(std::numbers::pi / 6) * Vector3d(0, 1, 0);
  d = denseWeights(s, weightsOf(s, off));
  const double c = std::cos(std::numbers::pi / 6);
  EXPECT_NEAR(d[0], 0.5 * c, kWeightTol);
  EXPECT_NEAR(d[1], 0.5 * c, kWeightTol);
  EXPECT_NEAR(d[2], 1.0 - c, kWeightTol);
}

TEST(ViewSphere, CosineModeIsPlainBarycentricInsideTheKeys) {
  const std::vector<Vector3d> keys = {fromAngles(0, 0), fromAngles(60, 0), fromAngles(30, 50)};
  const ViewSphere s = ViewSphere::build(keys, {Uncovered::Cosine});
  const Vector3d inside = (keys[0] + keys[1] + keys[2]).normalized();
  const ViewWeights w = weightsOf(s, inside);
  EXPECT_NEAR(w.base, 0.0, kWeightTol);
  const auto d = denseWeights(s, w);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(d[k], 1.0 / 3, kWeightTol);
}

TEST(ViewSphere, DegenerateQueriesAreRefused) {
  const ViewSphere s = ViewSphere::build(configurations()["octahedron"]);
  ViewWeights w;
  EXPECT_FALSE(s.weights(Vector3d::Zero(), 1.0, w));
  EXPECT_FALSE(s.weights(Vector3d(std::nan(""), 0, 1), 1.0, w));
}

std::string buildError(const std::vector<Vector3d>& keys, ViewSphereSettings settings = {}) {
  try {
    ViewSphere::build(keys, settings);
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(ViewSphere, InvalidKeySetsAreClearErrors) {
  EXPECT_NE(buildError({}).find("at least one key"), std::string::npos);
  EXPECT_NE(buildError({Vector3d(0, 0, 1), Vector3d::Zero()}).find("key 1: view direction has zero length"),
            std::string::npos);
  EXPECT_NE(buildError({Vector3d(0, 0, 1), Vector3d(0, 0, 2)}).find("key 1: same view direction as key 0"),
            std::string::npos);
  EXPECT_NE(buildError({Vector3d(0, 0, 1)}, {Uncovered::Base, 89.0}).find("base_falloff_deg"), std::string::npos);
}

}  // namespace
}  // namespace vdg
