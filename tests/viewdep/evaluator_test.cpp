// Threaded, vectorised evaluation (ViewDependentModel::evaluate, blend) against a naive scalar
// oracle written here, and ModelEvaluator's incremental frames against a fresh evaluate(), on the
// shipped examples and on random models (sparse and dense keys, small meshes that run inline and
// large ones that run on TBB's threads); ModelEvaluator's contract and allocations.
#include "vdg/viewdep/evaluator.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "support/allocation_counter.h"
#include "support/test_meshes.h"
#include "vdg/io/manifest.h"

namespace vdg {
namespace {

using Eigen::Vector3d;

// The oracle blends in double; the library in float, dense keys first: float rounding of a few
// additions of values of the model's size.
constexpr double kBlendRelTol = 1e-6;
// Normals of the oracle (a float scatter in triangle order) against the gather on the same
// positions: the same additions in the same order, so round-off of the normalisation at most.
constexpr float kNormalTol = 1e-6f;
// ModelEvaluator does the same float operations as evaluate() in the same order: bit for bit.
constexpr float kIncrementalTol = 0.0f;

std::mt19937& rng() {
  static std::mt19937 generator(1234);
  return generator;
}

Vector3d randomView() {
  std::normal_distribution<double> g;
  Vector3d v(g(rng()), g(rng()), g(rng()));
  return v.norm() > 1e-3 ? v : Vector3d(0, 0, 1);
}

// --- the oracle -----------------------------------------------------------------------------

std::vector<float> oraclePositions(const RawViewDependentModel& raw, const ViewWeights& w) {
  std::vector<float> out(raw.base.positions.size());
  for (std::size_t i = 0; i < out.size(); ++i) {
    double v = raw.base.positions[i];
    for (int s = 0; s < 3; ++s)
      if (w.key[s] >= 0)
        v += static_cast<double>(w.weight[s]) *
             (static_cast<double>(raw.keys[static_cast<std::size_t>(w.key[s])].mesh.positions[i]) -
              raw.base.positions[i]);
    out[i] = static_cast<float>(v);
  }
  return out;
}

std::vector<float> oracleNormals(const SurfaceTopology& t, std::span<const float> p) {
  const auto tris = t.triangles();
  const auto home = t.vertexHome();
  std::vector<float> out(p.size(), 0.0f);
  for (std::size_t f = 0; f < tris.size(); f += 3) {
    const float* a = &p[static_cast<std::size_t>(tris[f]) * 3];
    const float* b = &p[static_cast<std::size_t>(tris[f + 1]) * 3];
    const float* c = &p[static_cast<std::size_t>(tris[f + 2]) * 3];
    const float e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    const float n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
    for (std::size_t k = 0; k < 3; ++k) {
      const std::size_t s = static_cast<std::size_t>(home[static_cast<std::size_t>(tris[f + k])]) * 3;
      for (std::size_t i = 0; i < 3; ++i) out[s + i] += n[i];
    }
  }
  for (std::size_t v = 0; v < home.size(); ++v) {
    float* n = &out[v * 3];
    const float len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (len > 0.0f) {
      for (std::size_t i = 0; i < 3; ++i) n[i] *= 1.0f / len;
    }
  }
  for (std::size_t v = 0; v < home.size(); ++v)
    for (std::size_t i = 0; i < 3; ++i) out[v * 3 + i] = out[static_cast<std::size_t>(home[v]) * 3 + i];
  return out;
}

void expectOracle(const RawViewDependentModel& raw, const ViewDependentModel& model, const Vector3d& view,
                  const std::string& what) {
  std::vector<float> positions(raw.base.positions.size()), normals(positions.size());
  ViewWeights w;
  ASSERT_TRUE(model.weights(view, 0.0, w)) << what;
  ASSERT_TRUE(model.evaluate(view, 0.0, positions, normals)) << what;
  const std::vector<float> expected = oraclePositions(raw, w);
  for (std::size_t i = 0; i < positions.size(); ++i)
    ASSERT_NEAR(positions[i], expected[i], kBlendRelTol * (1.0 + std::abs(expected[i])))
        << what << ": coordinate " << i;
  const std::vector<float> expected_normals = oracleNormals(model.surface(), positions);
  for (std::size_t i = 0; i < normals.size(); ++i)
    ASSERT_NEAR(normals[i], expected_normals[i], kNormalTol) << what << ": normal coordinate " << i;
}

// --- models ---------------------------------------------------------------------------------

// A sphere (with a UV seam, so some vertices copy their home's normal) and `keys` keys around
// it; each key moves a random contiguous patch of the vertices nearest its view (sparse) or,
// with probability dense_share, every vertex.
RawViewDependentModel randomModel(int rings, int segments, int keys, double dense_share) {
  RawViewDependentModel raw;
  raw.base = testing::seamSphere(rings, segments);
  const std::size_t nv = raw.base.vertexCount();
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int k = 0; k < keys; ++k) {
    RawKey key;
    key.name = "k" + std::to_string(k);
    key.view = randomView();
    key.mesh = raw.base;
    std::vector<std::size_t> order(nv);
    std::iota(order.begin(), order.end(), std::size_t{0});
    const bool dense = u(rng()) < dense_share;
    const std::size_t moved = dense ? nv : 1 + static_cast<std::size_t>(u(rng()) * 0.2 * static_cast<double>(nv));
    const auto along = [&](std::size_t v) {
      const float* p = &raw.base.positions[3 * v];
      return p[0] * key.view.x() + p[1] * key.view.y() + p[2] * key.view.z();
    };
    std::partial_sort(order.begin(), order.begin() + static_cast<long>(moved), order.end(),
                      [&](std::size_t a, std::size_t b) { return along(a) > along(b); });
    const float scale = 1.0f + 0.3f * static_cast<float>(u(rng()));
    for (std::size_t i = 0; i < moved; ++i)
      for (std::size_t c = 0; c < 3; ++c) key.mesh.positions[3 * order[i] + c] *= scale;
    raw.keys.push_back(std::move(key));
  }
  return raw;
}

struct Built {
  RawViewDependentModel raw;
  std::optional<ViewDependentModel> model;
};

Built built(RawViewDependentModel raw) {
  Built b{std::move(raw), std::nullopt};
  b.model.emplace(ViewDependentModel::build(b.raw));
  return b;
}

std::vector<std::string> exampleManifests() {
  const std::string root = std::string(VDG_SOURCE_DIR) + "/examples/";
  return {root + "spot/spot.vdg.json", root + "figure13/head/head.vdg.json", root + "building/building.vdg.json"};
}

// --- threaded, vectorised evaluation against the oracle ---------------------------------------

TEST(Evaluation, ExamplesMatchTheScalarOracle) {
  for (const std::string& path : exampleManifests()) {
    const Built b = built(loadManifest(path));
    for (std::size_t k = 0; k < b.raw.keys.size(); ++k) expectOracle(b.raw, *b.model, b.raw.keys[k].view, path);
    for (int i = 0; i < 20; ++i) expectOracle(b.raw, *b.model, randomView(), path);
  }
}

TEST(Evaluation, RandomModelsMatchTheScalarOracle) {
  for (int i = 0; i < 10; ++i) {
    const Built b = built(randomModel(6 + i, 8 + i, 2 + i % 5, 0.3));
    for (int j = 0; j < 10; ++j) expectOracle(b.raw, *b.model, randomView(), "small model " + std::to_string(i));
  }
}

TEST(Evaluation, ThreadedEvaluationMatchesTheScalarOracle) {
  // Large enough for the threaded blend and normals (more than 2 x 32k vertices).
  for (const double dense_share : {0.0, 1.0, 0.5}) {
    const Built b = built(randomModel(300, 300, 6, dense_share));
    ASSERT_GT(b.raw.base.vertexCount(), 2 * kParallelNormalSlots);
    for (int j = 0; j < 3; ++j) expectOracle(b.raw, *b.model, randomView(), "large model");
  }
}

// --- ModelEvaluator equals a fresh evaluation -----------------------------------------------

void expectFresh(const ModelEvaluator& e, const std::string& what) {
  const ViewDependentModel& m = e.model();
  std::vector<float> positions(3 * m.vertexCount()), normals(positions.size());
  ASSERT_TRUE(m.blend(e.weights(), positions)) << what;
  ASSERT_TRUE(computeVertexNormals(m.surface(), positions, normals)) << what;
  for (std::size_t i = 0; i < positions.size(); ++i) {
    ASSERT_NEAR(e.positions()[i], positions[i], kIncrementalTol) << what << ": coordinate " << i;
    ASSERT_NEAR(e.normals()[i], normals[i], kIncrementalTol) << what << ": normal coordinate " << i;
  }
}

// A random step: a small move along a path, a jump, or (apply) random weights of random keys.
void randomStep(ModelEvaluator& e, Vector3d& view, int& hint, const std::string& what) {
  std::uniform_int_distribution<int> kind(0, 9);
  const int k = kind(rng());
  const int keys = static_cast<int>(e.model().keyCount());
  if (k < 6) {
    view = (view.normalized() + 0.05 * randomView().normalized()).normalized();
    ASSERT_TRUE(e.evaluate(view, 0.0, &hint)) << what;
  } else if (k < 8) {
    view = randomView();
    ASSERT_TRUE(e.evaluate(view, k == 6 ? 3.0 : 0.0, &hint)) << what;
  } else {
    std::uniform_int_distribution<int> key(-1, keys - 1);
    std::uniform_real_distribution<float> weight(-0.5f, 1.0f);
    ViewWeights w;
    for (int s = 0; s < 3; ++s) {
      w.key[s] = key(rng());
      w.weight[s] = rng()() % 4 == 0 ? 0.0f : weight(rng());
    }
    ASSERT_TRUE(e.apply(w)) << what;
  }
}

TEST(ModelEvaluator, StartsAtTheBase) {
  const Built b = built(randomModel(8, 10, 3, 0.5));
  const ModelEvaluator e(*b.model);
  EXPECT_EQ(e.weights().base, 1.0f);
  EXPECT_EQ(e.weights().key, (std::array<int, 3>{-1, -1, -1}));
  expectFresh(e, "a new evaluator");
  EXPECT_EQ(&e.model(), &*b.model);
}

TEST(ModelEvaluator, RandomSequencesEqualAFreshEvaluation) {
  for (int m = 0; m < 12; ++m) {
    const Built b = built(randomModel(5 + m, 6 + m, 1 + m % 6, m % 3 == 0 ? 0.0 : 0.4));
    ModelEvaluator e(*b.model);
    Vector3d view = randomView();
    int hint = -1;
    for (int step = 0; step < 60; ++step) {
      const std::string what = "model " + std::to_string(m) + ", step " + std::to_string(step);
      randomStep(e, view, hint, what);
      expectFresh(e, what);
      if (::testing::Test::HasFatalFailure()) return;
    }
  }
}

TEST(ModelEvaluator, ExamplesAlongAnOrbitEqualAFreshEvaluation) {
  for (const std::string& path : exampleManifests()) {
    const Built b = built(loadManifest(path));
    ModelEvaluator e(*b.model);
    int hint = -1;
    for (int frame = 0; frame < 100; ++frame) {
      const double t = 0.0628 * frame;
      ASSERT_TRUE(e.evaluate(Vector3d(std::sin(t), 0.3 * std::cos(3 * t), std::cos(t)), 0.0, &hint));
      expectFresh(e, path + ", frame " + std::to_string(frame));
    }
  }
}

TEST(ModelEvaluator, InterleavedModelsAndThreadedFramesEqualAFreshEvaluation) {
  // Two large models (threaded paths), one sparse, one mixed, evaluated turn by turn, and a small one.
  const Built sparse = built(randomModel(300, 300, 6, 0.0));
  const Built mixed = built(randomModel(300, 300, 6, 0.5));
  const Built small = built(randomModel(8, 9, 4, 0.3));
  ModelEvaluator a(*sparse.model), b(*mixed.model), c(*small.model), a2(*sparse.model);
  Vector3d va = randomView(), vb = randomView(), vc = randomView(), va2 = randomView();
  int ha = -1, hb = -1, hc = -1, ha2 = -1;
  for (int step = 0; step < 12; ++step) {
    const std::string what = "step " + std::to_string(step);
    randomStep(a, va, ha, "sparse, " + what);
    randomStep(b, vb, hb, "mixed, " + what);
    randomStep(c, vc, hc, "small, " + what);
    randomStep(a2, va2, ha2, "sparse again, " + what);
    expectFresh(a, "sparse, " + what);
    expectFresh(b, "mixed, " + what);
    expectFresh(c, "small, " + what);
    expectFresh(a2, "sparse again, " + what);
    if (::testing::Test::HasFatalFailure()) return;
  }
}

TEST(ModelEvaluator, EvaluateMatchesTheModelsEvaluate) {
  const Built b = built(randomModel(10, 12, 5, 0.3));
  ModelEvaluator e(*b.model);
  std::vector<float> positions(b.raw.base.positions.size()), normals(positions.size());
  int hint = -1, model_hint = -1;
  for (int i = 0; i < 50; ++i) {
    const Vector3d view = randomView();
    ASSERT_TRUE(e.evaluate(view, 2.0, &hint));
    ASSERT_TRUE(b.model->evaluate(view, 2.0, positions, normals, &model_hint));
    EXPECT_EQ(hint, model_hint);
    for (std::size_t j = 0; j < positions.size(); ++j) {
      ASSERT_EQ(e.positions()[j], positions[j]);
      ASSERT_EQ(e.normals()[j], normals[j]);
    }
  }
}

// The rbf scheme weighs every key: an evaluate() is a full frame (positions and normals of
// ViewDependentModel::evaluate, bit for bit), and the incremental frames after it (apply) start
// again from the base, since every vertex may have moved.
TEST(ModelEvaluator, RbfFramesAreFullFramesAndTheFramesAfterThemStillEqualAFreshEvaluation) {
  RawViewDependentModel raw = randomModel(9, 11, 4, 0.25);
  const std::array<Vector3d, 4> views{Vector3d(0, 0, 1), Vector3d(1, 0.2, 0), Vector3d(-0.6, 0.3, -0.7),
                                      Vector3d(0.1, 1, 0.2)};
  for (std::size_t k = 0; k < views.size(); ++k) raw.keys[k].view = views[k];
  raw.sphere.scheme = WeightScheme::Rbf;
  const Built b = built(raw);
  ModelEvaluator e(*b.model);
  std::vector<float> positions(raw.base.positions.size()), normals(positions.size());
  std::vector<float> dense(b.model->keyCount() + 1);
  Vector3d view = randomView();
  int hint = -1, model_hint = -1;
  for (int step = 0; step < 40; ++step) {
    const std::string what = "step " + std::to_string(step);
    if (step % 3 == 2) {  // three-key weights given: the incremental path
      ViewWeights w;
      w.key = {static_cast<int>(step % 4), -1, static_cast<int>((step + 1) % 4)};
      w.weight = {0.6f, 0.0f, 0.3f};
      ASSERT_TRUE(e.apply(w)) << what;
      expectFresh(e, what);
      continue;
    }
    view = (view.normalized() + 0.3 * randomView().normalized()).normalized();
    ASSERT_TRUE(e.evaluate(view, 0.0, &hint)) << what;
    ASSERT_TRUE(b.model->evaluate(view, 0.0, positions, normals, &model_hint)) << what;
    for (std::size_t j = 0; j < positions.size(); ++j) {
      ASSERT_EQ(e.positions()[j], positions[j]) << what;
      ASSERT_EQ(e.normals()[j], normals[j]) << what;
    }
    // What weights() reports: the heaviest keys of the dense weights, the rest as the base.
    ASSERT_TRUE(b.model->denseWeights(view, 0.0, dense));
    const ViewWeights w = e.weights();
    EXPECT_EQ(w.triangle, -1);
    EXPECT_NEAR(w.weight[0] + w.weight[1] + w.weight[2] + w.base, 1.0f, 1e-5f) << what;
    ASSERT_GE(w.key[0], 0) << what;
    EXPECT_EQ(w.weight[0], *std::max_element(dense.begin(), dense.end() - 1)) << what;
  }
}

// --- contract and allocations ---------------------------------------------------------------

TEST(ModelEvaluator, ViolationsChangeNothing) {
  const Built b = built(randomModel(8, 10, 4, 0.3));
  ModelEvaluator e(*b.model);
  ASSERT_TRUE(e.evaluate(Vector3d(0.2, 0.3, 1.0), 0.0));
  const std::vector<float> positions(e.positions().begin(), e.positions().end());
  const std::vector<float> normals(e.normals().begin(), e.normals().end());
  const ViewWeights before = e.weights();
  const auto expectUnchanged = [&](const std::string& what) {
    EXPECT_TRUE(std::equal(positions.begin(), positions.end(), e.positions().begin())) << what;
    EXPECT_TRUE(std::equal(normals.begin(), normals.end(), e.normals().begin())) << what;
    EXPECT_EQ(e.weights().key, before.key) << what;
    EXPECT_EQ(e.weights().weight, before.weight) << what;
    EXPECT_EQ(e.weights().base, before.base) << what;
  };
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  constexpr int kHintSentinel = 424242;
  for (const Vector3d& view : {Vector3d(0, 0, 0), Vector3d(nan, 0, 1), Vector3d(0, inf, 1)}) {
    int hint = -1;
    EXPECT_FALSE(e.evaluate(view, 0.0, &hint));
    EXPECT_EQ(hint, -1);
    expectUnchanged("bad view");
  }
  for (const double sharpness : {nan, inf, -inf}) {
    EXPECT_FALSE(e.evaluate(Vector3d(0, 0, 1), sharpness));
    expectUnchanged("sharpness " + std::to_string(sharpness));
  }
  for (const int bad_hint : {kHintSentinel, -2}) {
    int hint = bad_hint;
    EXPECT_FALSE(e.evaluate(Vector3d(0, 0, 1), 0.0, &hint));
    EXPECT_EQ(hint, bad_hint);
    expectUnchanged("hint " + std::to_string(bad_hint));
  }
  const int keys = static_cast<int>(b.model->keyCount());
  for (const auto& [key, weight] : std::vector<std::pair<int, float>>{{keys, 0.5f},
                                                                      {-2, 0.5f},
                                                                      {0, std::numeric_limits<float>::quiet_NaN()},
                                                                      {1, std::numeric_limits<float>::infinity()}}) {
    ViewWeights w;
    w.key = {0, key, -1};
    w.weight = {0.2f, weight, 0.0f};
    EXPECT_FALSE(e.apply(w));
    expectUnchanged("key " + std::to_string(key) + ", weight " + std::to_string(weight));
  }
}

TEST(ModelEvaluator, FramesAllocateNothingAfterAWarmUp) {
  // Small (inline) and large (threaded) models, sparse and dense keys, valid and refused calls.
  const Built small = built(randomModel(10, 12, 5, 0.3));
  const Built large = built(randomModel(300, 300, 6, 0.3));
  for (const Built* b : {&small, &large}) {
    ModelEvaluator e(*b->model);
    std::vector<Vector3d> views;
    std::vector<ViewWeights> weights;
    for (int i = 0; i < 40; ++i) {
      const double t = 0.1 * i;
      views.emplace_back(std::sin(t), 0.5 * std::cos(2 * t), std::cos(t));
      views.push_back(randomView());
      ViewWeights w;
      ASSERT_TRUE(b->model->weights(randomView(), 0.0, w));
      weights.push_back(w);
    }
    int hint = -1;
    ASSERT_TRUE(e.evaluate(views[0], 0.0, &hint));  // warm-up: TBB starts its threads
    ViewWeights bad;
    bad.key[0] = 1 << 20;
    bad.weight[0] = 1.0f;
    bool ok = true, refused = false;
    EXPECT_EQ(testing::allocationsDuring([&] {
                for (const Vector3d& v : views) ok = e.evaluate(v, 0.0, &hint) && ok;
                for (const ViewWeights& w : weights) ok = e.apply(w) && ok;
                refused = e.apply(bad) || e.evaluate(Vector3d::Zero(), 0.0) || refused;
              }),
              0);
    EXPECT_TRUE(ok);
    EXPECT_FALSE(refused);
  }
}

}  // namespace
}  // namespace vdg
