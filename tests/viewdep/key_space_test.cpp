// Keys at distances (vdg/viewdep/key_space.h; docs/weights.md, "Keys at distances"): weights of an
// eye POSITION from the key eyes' tetrahedralisation, falling back to the direction sphere outside
// their hull. Properties: exact at every key eye, a partition of unity, non-negative, continuous
// along camera paths that cross the hull surface and pass through keys, allocation-free, and a
// "directions" model unchanged bit for bit.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "support/allocation_counter.h"
#include "support/error_of.h"
#include "support/test_meshes.h"
#include "vdg/geom/error.h"
#include "vdg/viewdep/key_space.h"
#include "vdg/viewdep/model.h"

namespace vdg {
namespace {

using Eigen::Vector3d;

constexpr double kWeightTol = 1e-5;   // float weights: sums and one-hot keys
constexpr double kNegativeTol = 0.0;  // weights are clamped: never below 0
// Continuity along a path: halving the step at least divides the largest weight change between
// samples by kContinuousRatio (2 for a Lipschitz blend; a jump would not shrink at all), and that
// change stays below kMaxStepChange at the finer step.
constexpr double kContinuousRatio = 1.6;
constexpr double kMaxStepChange = 0.02;
constexpr int kPathSamples = 4000;

// Wide shots (distance 10) from eight directions and close-ups (distance 4) from four of them: the
// paper's keys plus a dolly in along four directions.
std::vector<Vector3d> dollyEyes() {
  std::vector<Vector3d> eyes;
  const std::vector<Vector3d> dirs = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0},
                                      {0, 0, 1}, {0, 0, -1}, {1, 1, 1}, {-1, -1, 1}};
  for (const Vector3d& d : dirs) eyes.push_back(10.0 * d.normalized());
  for (int i : {0, 2, 4, 6}) eyes.push_back(4.0 * dirs[static_cast<std::size_t>(i)].normalized());
  return eyes;
}

// Keys on one side of the centre (a front hemisphere), so the hull does not hold the centre.
std::vector<Vector3d> frontEyes() {
  return {{0, 0, 10}, {0, 0, 5}, {6, 0, 8}, {-6, 0, 8}, {0, 6, 8}, {0, -6, 8}, {3, 3, 4}};
}

std::vector<std::string> labelsOf(std::size_t n) {
  std::vector<std::string> labels;
  for (std::size_t k = 0; k < n; ++k) labels.push_back("key 'k" + std::to_string(k) + "'");
  return labels;
}

KeySpace buildSpace(const std::vector<Vector3d>& eyes, ViewSphereSettings sphere = {}) {
  return KeySpace::build(eyes, Vector3d::Zero(), sphere, 0.0, labelsOf(eyes.size()));
}

std::vector<float> weightsAt(const KeySpace& s, const Vector3d& eye, int* hint = nullptr) {
  std::vector<float> w(s.keyCount() + 1, -1.0f);
  EXPECT_TRUE(s.weights(eye, 1.0, w, hint)) << eye.transpose();
  return w;
}

void expectPartition(const std::vector<float>& w, const Vector3d& eye) {
  double sum = 0.0;
  for (const float x : w) {
    EXPECT_GE(x, kNegativeTol) << eye.transpose();
    sum += x;
  }
  EXPECT_NEAR(sum, 1.0, kWeightTol) << eye.transpose();
}

TEST(KeySpace, ExactAtEveryKeyEye) {
  for (const auto& eyes : {dollyEyes(), frontEyes()}) {
    const KeySpace s = buildSpace(eyes);
    int hint = -1;
    for (std::size_t k = 0; k < eyes.size(); ++k) {
      const std::vector<float> w = weightsAt(s, eyes[k], &hint);
      for (std::size_t j = 0; j < w.size(); ++j) EXPECT_NEAR(w[j], j == k ? 1.0 : 0.0, kWeightTol) << k << " " << j;
    }
  }
}

TEST(KeySpace, PartitionOfUnityAndNonNegativeEverywhere) {
  std::mt19937 rng(29);
  std::uniform_real_distribution<double> u(-40.0, 40.0);
  for (const auto& eyes : {dollyEyes(), frontEyes()}) {
    for (const Uncovered mode : {Uncovered::Base, Uncovered::Cosine, Uncovered::Cosine2}) {
      ViewSphereSettings settings;
      settings.uncovered = mode;
      const KeySpace s = buildSpace(eyes, settings);
      int hint = -1;
      for (int i = 0; i < 5000; ++i) {
        const Vector3d eye(u(rng), u(rng), u(rng));
        const std::vector<float> hinted = weightsAt(s, eye, &hint);
        expectPartition(hinted, eye);
        // The walk from the previous tetrahedron and the walk from the first agree.
        const std::vector<float> fresh = weightsAt(s, eye);
        for (std::size_t j = 0; j < fresh.size(); ++j) EXPECT_NEAR(hinted[j], fresh[j], kWeightTol);
      }
    }
  }
}

// The largest change of any weight between neighbouring samples of eye(t), t in [0, 1].
double largestStep(const KeySpace& s, const std::function<Vector3d(double)>& path, int samples) {
  std::vector<float> previous = weightsAt(s, path(0.0));
  double largest = 0.0;
  int hint = -1;
  for (int i = 1; i <= samples; ++i) {
    const std::vector<float> w = weightsAt(s, path(static_cast<double>(i) / samples), &hint);
    expectPartition(w, path(static_cast<double>(i) / samples));
    for (std::size_t j = 0; j < w.size(); ++j) largest = std::max(largest, std::abs(double(w[j]) - previous[j]));
    previous = w;
  }
  return largest;
}

TEST(KeySpace, ContinuousAcrossTheHullSurfaceAndThroughKeys) {
  for (const auto& eyes : {dollyEyes(), frontEyes()}) {
    const KeySpace s = buildSpace(eyes);
    for (std::size_t k = 0; k < eyes.size(); ++k) {
      // A dolly from far outside, through key k's eye, out the other side of the hull and beyond.
      const Vector3d through = eyes[k], from = eyes[k] * 3.0 + Vector3d(1.3, -0.7, 0.4);
      const Vector3d to = through + (through - from) * 1.5;
      const auto path = [&](double t) { return Vector3d(from + t * (to - from)); };
      const double coarse = largestStep(s, path, kPathSamples), fine = largestStep(s, path, 2 * kPathSamples);
      EXPECT_LT(fine, kMaxStepChange) << "key " << k;
      EXPECT_GE(coarse / std::max(fine, 1e-12), kContinuousRatio) << "key " << k;
    }
  }
}

TEST(KeySpace, NoPopAtTheHullSurface) {
  // The nearest hull point of an eye just outside a face is the eye's own foot on that face: the
  // weights there are the hull face's, so stepping across the surface changes nothing visible.
  const std::vector<Vector3d> eyes = dollyEyes();
  const KeySpace s = buildSpace(eyes);
  const Vector3d inside = 0.999999 * Vector3d(10, 0, 0) + 0.000001 * Vector3d(0, 0, 0);
  const Vector3d outside = Vector3d(10.000001, 0.0, 0.0) + Vector3d(0, 1e-7, 0);
  const std::vector<float> a = weightsAt(s, inside), b = weightsAt(s, outside);
  for (std::size_t j = 0; j < a.size(); ++j) EXPECT_NEAR(a[j], b[j], kWeightTol);
}

TEST(KeySpace, FarAlongADirectionTheFarthestKeyOfItTakesOver) {
  const std::vector<Vector3d> eyes = dollyEyes();
  const KeySpace s = buildSpace(eyes);
  // Key 0 (wide, distance 10) and key 8 (close-up, distance 4) share direction +x.
  const std::vector<float> far = weightsAt(s, Vector3d(1000, 0, 0));
  EXPECT_NEAR(far[0], 1.0, kWeightTol);
  EXPECT_NEAR(far[8], 0.0, kWeightTol);
  // Inside the hull, along +x between the close-up and the wide shot: linear in the distance.
  const std::vector<float> mid = weightsAt(s, Vector3d(7, 0, 0));
  EXPECT_NEAR(mid[0], 0.5, kWeightTol);
  EXPECT_NEAR(mid[8], 0.5, kWeightTol);
}

TEST(KeySpace, QueryIsCheckedAndAllocationFree) {
  const KeySpace s = buildSpace(frontEyes());
  std::vector<float> w(s.keyCount() + 1, 7.0f), wrong(s.keyCount(), 7.0f);
  int hint = -1, bad_hint = static_cast<int>(s.tetrahedronCount());
  const double nan = std::nan("");
  EXPECT_FALSE(s.weights(Vector3d(nan, 0, 0), 1.0, w, &hint));
  EXPECT_FALSE(s.weights(Vector3d(1, 2, 3), 0.0, w, &hint));
  EXPECT_FALSE(s.weights(Vector3d(1, 2, 3), 1.0, wrong, &hint));
  EXPECT_FALSE(s.weights(Vector3d(1, 2, 3), 1.0, w, &bad_hint));
  EXPECT_FALSE(s.weights(Vector3d::Zero(), 1.0, w, &hint));  // the centre, outside this hull
  EXPECT_TRUE(std::all_of(w.begin(), w.end(), [](float x) { return x == 7.0f; }));
  EXPECT_EQ(hint, -1);
  const long allocations = testing::allocationsDuring([&] {
    for (int i = 0; i < 100; ++i) (void)s.weights(Vector3d(0.3 * i - 15, 0.1 * i, 12.0 - 0.2 * i), 2.5, w, &hint);
  });
  EXPECT_EQ(allocations, 0);
}

TEST(KeySpace, BuildRefusesDegenerateEyeSets) {
  const auto refusal = [](std::vector<Vector3d> eyes, ViewSphereSettings sphere = {}) {
    return testing::errorOf([&] { (void)buildSpace(eyes, sphere); });
  };
  EXPECT_NE(refusal({{0, 0, 5}, {5, 0, 0}, {0, 5, 0}}).find("at least 4 keys"), std::string::npos);
  EXPECT_NE(refusal({{0, 0, 5}, {5, 0, 5}, {0, 5, 5}, {5, 5, 5}}).find("not all in one plane"), std::string::npos);
  EXPECT_NE(refusal({{0, 0, 5}, {5, 0, 0}, {0, 5, 0}, {0, 0, 5}}).find("same eye as key 'k0'"), std::string::npos);
  EXPECT_NE(refusal({{0, 0, 0}, {5, 0, 0}, {0, 5, 0}, {0, 0, 5}}).find("at the model centre"), std::string::npos);
  ViewSphereSettings smooth;
  smooth.scheme = WeightScheme::Smooth;
  EXPECT_NE(refusal(dollyEyes(), smooth).find("'linear' scheme only"), std::string::npos);
}

// A model whose keys are the dolly eyes: key k moves vertex 0 by k + 1 along x.
RawViewDependentModel dollyModel(WeightSpace space) {
  RawViewDependentModel raw;
  raw.source = "dolly.vdg.json";
  raw.base = testing::uvSphere();
  raw.center = Vector3d::Zero();
  raw.key_space.space = space;
  const std::vector<Vector3d> eyes = dollyEyes();
  for (std::size_t k = 0; k < eyes.size(); ++k) {
    RawKey key;
    key.name = "k" + std::to_string(k);
    key.mesh = raw.base;
    key.mesh.positions[0] += static_cast<float>(k + 1);
    if (space == WeightSpace::Positions)
      key.eye = eyes[k];
    else
      key.view = eyes[k] + Vector3d(0.0, 0.01, 0.02) * static_cast<double>(k);  // distinct directions
    raw.keys.push_back(key);
  }
  raw.resolveViews();
  return raw;
}

TEST(KeySpace, ModelEvaluatesAtEyesAndRefusesDirectionQueries) {
  const ViewDependentModel model = ViewDependentModel::build(dollyModel(WeightSpace::Positions));
  ASSERT_EQ(model.weightSpace(), WeightSpace::Positions);
  const std::vector<Vector3d> eyes = dollyEyes();
  std::vector<float> positions(3 * model.vertexCount()), normals(3 * model.vertexCount());
  for (std::size_t k = 0; k < eyes.size(); ++k) {
    ASSERT_TRUE(model.evaluateAtEye(eyes[k], 0.0, positions, normals));
    EXPECT_NEAR(positions[0], model.base().positions[0] + static_cast<float>(k + 1), kWeightTol * 10);
    EXPECT_NEAR((model.keyView(k) - eyes[k].normalized()).norm(), 0.0, 1e-12);
  }
  ViewWeights w;
  std::vector<float> dense(model.keyCount() + 1);
  EXPECT_FALSE(model.weights(Vector3d::UnitX(), 0.0, w));
  EXPECT_FALSE(model.denseWeights(Vector3d::UnitX(), 0.0, dense));
  EXPECT_FALSE(model.evaluate(Vector3d::UnitX(), 0.0, positions));
  const std::string e = testing::errorOf([&] { model.requireThreeKeyWeights("the renderer (vdg render, run)"); });
  EXPECT_EQ(e.rfind("the 'positions' weight space is not supported by the renderer (vdg render, run)", 0), 0u) << e;
}

TEST(KeySpace, ModelValidationNamesTheKeyWithoutAnEye) {
  RawViewDependentModel raw = dollyModel(WeightSpace::Positions);
  raw.keys[3].eye.reset();
  raw.keys[3].view = Vector3d::UnitY();
  const std::string e = testing::errorOf([&] { raw.validate(); });
  EXPECT_NE(e.find("key 'k3'"), std::string::npos) << e;
  EXPECT_NE(e.find("needs the key's eye"), std::string::npos) << e;
  RawViewDependentModel smooth = dollyModel(WeightSpace::Positions);
  smooth.sphere.scheme = WeightScheme::Smooth;
  EXPECT_NE(testing::errorOf([&] { smooth.validate(); }).find("'linear' scheme only"), std::string::npos);
}

TEST(KeySpace, DirectionsModelIsUnchangedBitForBit) {
  const RawViewDependentModel raw = dollyModel(WeightSpace::Directions);
  const ViewDependentModel model = ViewDependentModel::build(raw);
  std::vector<Vector3d> views;
  for (const RawKey& key : raw.keys) views.push_back(key.view);
  const ViewSphere sphere = ViewSphere::build(views, raw.sphere);
  std::mt19937 rng(4);
  std::normal_distribution<double> n;
  std::vector<float> a(model.keyCount() + 1), b(model.keyCount() + 1), c(model.keyCount() + 1);
  for (int i = 0; i < 2000; ++i) {
    const Vector3d eye = 20.0 * Vector3d(n(rng), n(rng), n(rng));
    ASSERT_TRUE(model.denseWeightsAtEye(eye, 0.0, a));
    ASSERT_TRUE(model.denseWeights(model.viewFromEye(eye), 0.0, b));
    ASSERT_TRUE(sphere.denseWeights(model.viewFromEye(eye), raw.sharpness, c));
    for (std::size_t j = 0; j < a.size(); ++j) {
      EXPECT_EQ(a[j], b[j]);
      EXPECT_EQ(b[j], c[j]);
    }
  }
}

}  // namespace
}  // namespace vdg
