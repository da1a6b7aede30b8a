// The per-frame contract (model.h, view_sphere.h): every invalid input to every evaluation entry
// point returns false and leaves every output untouched (buffers are filled with a sentinel
// first and compared afterwards); accessors by key index throw vdg::Error naming the index.
#include <gtest/gtest.h>

#include <climits>
#include <cmath>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "support/test_meshes.h"
#include "vdg/geom/error.h"
#include "vdg/viewdep/model.h"

namespace vdg {
namespace {

using Eigen::Vector3d;

constexpr float kSentinel = -12345.5f;
constexpr int kHintSentinel = 424242;  // any value a call must leave alone when it refuses
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

const std::vector<Vector3d>& badViews() {
  static const std::vector<Vector3d> views = {Vector3d::Zero(),          Vector3d(kNaN, 0, 1), Vector3d(0, kNaN, 1),
                                              Vector3d(0, 0, kNaN),      Vector3d(kInf, 0, 1), Vector3d(0, -kInf, 1),
                                              Vector3d(kNaN, kNaN, kNaN)};
  return views;
}

ViewWeights sentinelWeights() {
  ViewWeights w;
  w.key = {7, 7, 7};
  w.weight = {9.0f, 9.0f, 9.0f};
  w.base = 9.0f;
  w.triangle = 7;
  return w;
}

void expectSentinelWeights(const ViewWeights& w) {
  const ViewWeights s = sentinelWeights();
  EXPECT_EQ(w.key, s.key);
  EXPECT_EQ(w.weight, s.weight);
  EXPECT_EQ(w.base, s.base);
  EXPECT_EQ(w.triangle, s.triangle);
}

void expectUntouched(const std::vector<float>& buffer) {
  for (std::size_t i = 0; i < buffer.size(); ++i) ASSERT_EQ(buffer[i], kSentinel) << "element " << i << " was written";
}

std::vector<float> sentinelBuffer(std::size_t size) { return std::vector<float>(size, kSentinel); }

RawViewDependentModel threeKeyModel(Uncovered mode) {
  RawViewDependentModel raw;
  raw.base = testing::uvSphere(6, 8);
  raw.sphere.uncovered = mode;
  const Vector3d views[] = {{1, 0, 0.2}, {0, 1, 0.2}, {0, 0, 1}};
  for (int k = 0; k < 3; ++k) {
    RawKey key;
    key.name = "k" + std::to_string(k);
    key.mesh = raw.base;
    key.mesh.positions[3 * static_cast<std::size_t>(k) + 1] += 0.2f;
    key.view = views[k];
    raw.keys.push_back(key);
  }
  return raw;
}

class Contract : public ::testing::TestWithParam<Uncovered> {
 protected:
  Contract() : raw_(threeKeyModel(GetParam())), model_(ViewDependentModel::build(raw_)) {}
  std::size_t n() const { return raw_.base.positions.size(); }
  // Too short, too long and empty position buffers.
  std::vector<std::size_t> badSizes() const { return {0, 1, 3, n() - 3, n() - 1, n() + 1, n() + 3, 2 * n()}; }
  int triangleCount() const { return static_cast<int>(model_.sphere().triangles().size()); }
  std::vector<int> invalidHints() const { return {-2, triangleCount(), triangleCount() + 1, INT_MAX, INT_MIN}; }

  RawViewDependentModel raw_;
  ViewDependentModel model_;
};

TEST_P(Contract, SphereWeightsRefusesBadViews) {
  const ViewSphere& s = model_.sphere();
  for (const Vector3d& view : badViews()) {
    ViewWeights w = sentinelWeights();
    int hint = kHintSentinel;
    int* no_hint = nullptr;
    EXPECT_FALSE(s.weights(view, 1.0, w, no_hint)) << view.transpose();
    expectSentinelWeights(w);
    hint = 0;
    EXPECT_FALSE(s.weights(view, 1.0, w, &hint)) << view.transpose();
    EXPECT_EQ(hint, 0);
    expectSentinelWeights(w);
  }
}

TEST_P(Contract, SphereWeightsRefusesBadSharpness) {
  for (double sharpness : {0.0, -1.0, kNaN, kInf, -kInf}) {
    ViewWeights w = sentinelWeights();
    int hint = 0;
    EXPECT_FALSE(model_.sphere().weights(Vector3d(0.3, 0.2, 1), sharpness, w, &hint)) << sharpness;
    EXPECT_EQ(hint, 0);
    expectSentinelWeights(w);
  }
}

TEST_P(Contract, SphereWeightsRefusesHintsOutOfRange) {
  for (int bad : invalidHints()) {
    ViewWeights w = sentinelWeights();
    int hint = bad;
    EXPECT_FALSE(model_.sphere().weights(Vector3d(0.3, 0.2, 1), 1.0, w, &hint)) << bad;
    EXPECT_EQ(hint, bad);
    expectSentinelWeights(w);
  }
}

TEST_P(Contract, AnyValidHintGivesTheSameWeightsAsNone) {
  const ViewSphere& s = model_.sphere();
  const Vector3d view(0.3, 0.2, 1);
  ViewWeights expected;
  ASSERT_TRUE(s.weights(view, 1.0, expected));
  for (int t = -1; t < static_cast<int>(s.triangles().size()); ++t) {
    int hint = t;
    ViewWeights w;
    ASSERT_TRUE(s.weights(view, 1.0, w, &hint)) << t;
    EXPECT_EQ(w.key, expected.key) << t;
    EXPECT_EQ(w.weight, expected.weight) << t;
    EXPECT_EQ(w.base, expected.base) << t;
  }
}

TEST_P(Contract, ModelWeightsRefusesBadInput) {
  for (const Vector3d& view : badViews()) {
    ViewWeights w = sentinelWeights();
    int hint = -1;
    EXPECT_FALSE(model_.weights(view, 0.0, w, &hint)) << view.transpose();
    EXPECT_EQ(hint, -1);
    expectSentinelWeights(w);
  }
  for (double sharpness : {kNaN, kInf, -kInf}) {
    ViewWeights w = sentinelWeights();
    EXPECT_FALSE(model_.weights(Vector3d(0.3, 0.2, 1), sharpness, w)) << sharpness;
    expectSentinelWeights(w);
  }
  for (int bad : invalidHints()) {
    ViewWeights w = sentinelWeights();
    int hint = bad;
    EXPECT_FALSE(model_.weights(Vector3d(0.3, 0.2, 1), 0.0, w, &hint)) << bad;
    EXPECT_EQ(hint, bad);
    expectSentinelWeights(w);
  }
}

TEST_P(Contract, ModelWeightsTakesNonPositiveSharpnessAsTheModels) {
  const Vector3d view(0.3, 0.2, 1);
  ViewWeights own, zero, negative;
  ASSERT_TRUE(model_.sphere().weights(view, model_.sharpness(), own));
  ASSERT_TRUE(model_.weights(view, 0.0, zero));
  ASSERT_TRUE(model_.weights(view, -3.0, negative));
  EXPECT_EQ(zero.weight, own.weight);
  EXPECT_EQ(negative.weight, own.weight);
}

TEST_P(Contract, BlendRefusesWrongSizes) {
  ViewWeights w;
  ASSERT_TRUE(model_.weights(Vector3d(0.3, 0.2, 1), 0.0, w));
  for (std::size_t size : badSizes()) {
    std::vector<float> out = sentinelBuffer(size);
    EXPECT_FALSE(model_.blend(w, out)) << size;
    expectUntouched(out);
  }
}

TEST_P(Contract, BlendRefusesBadWeights) {
  const int key_count = static_cast<int>(model_.keyCount());
  for (int slot = 0; slot < 3; ++slot) {
    for (int bad_key : {key_count, key_count + 5, -2, INT_MAX, INT_MIN}) {
      ViewWeights w;
      w.key[slot] = bad_key;
      w.weight[slot] = 1.0f;
      std::vector<float> out = sentinelBuffer(n());
      EXPECT_FALSE(model_.blend(w, out)) << "slot " << slot << " key " << bad_key;
      expectUntouched(out);
    }
    for (float bad_weight : {std::nanf(""), std::numeric_limits<float>::infinity()}) {
      ViewWeights w;
      w.key[slot] = 0;
      w.weight[slot] = bad_weight;
      std::vector<float> out = sentinelBuffer(n());
      EXPECT_FALSE(model_.blend(w, out)) << "slot " << slot << " weight " << bad_weight;
      expectUntouched(out);
    }
  }
}

TEST_P(Contract, KeyPositionsRefusesBadKeysAndSizes) {
  for (std::size_t key : {model_.keyCount(), model_.keyCount() + 1, std::numeric_limits<std::size_t>::max()}) {
    std::vector<float> out = sentinelBuffer(n());
    EXPECT_FALSE(model_.keyPositions(key, out)) << key;
    expectUntouched(out);
  }
  for (std::size_t size : badSizes()) {
    std::vector<float> out = sentinelBuffer(size);
    EXPECT_FALSE(model_.keyPositions(0, out)) << size;
    expectUntouched(out);
  }
  std::vector<float> out = sentinelBuffer(n());
  ASSERT_TRUE(model_.keyPositions(1, out));
  EXPECT_EQ(out, raw_.keys[1].mesh.positions);
}

TEST_P(Contract, EvaluateRefusesWrongSizes) {
  const Vector3d view(0.3, 0.2, 1);
  for (std::size_t size : badSizes()) {
    std::vector<float> positions = sentinelBuffer(size), normals = sentinelBuffer(n());
    int hint = -1;
    EXPECT_FALSE(model_.evaluate(view, 0.0, positions, normals, &hint)) << "positions " << size;
    EXPECT_FALSE(model_.evaluate(view, 0.0, positions)) << "positions " << size;
    EXPECT_EQ(hint, -1);
    expectUntouched(positions);
    expectUntouched(normals);
  }
  for (std::size_t size : badSizes()) {
    if (size == 0) continue;  // empty normals: positions only, valid
    std::vector<float> positions = sentinelBuffer(n()), normals = sentinelBuffer(size);
    int hint = -1;
    EXPECT_FALSE(model_.evaluate(view, 0.0, positions, normals, &hint)) << "normals " << size;
    EXPECT_EQ(hint, -1);
    expectUntouched(positions);
    expectUntouched(normals);
  }
}

TEST_P(Contract, EvaluateRefusesBadViewsSharpnessAndHints) {
  const auto refused = [&](const Vector3d& view, double sharpness, int hint_in) {
    std::vector<float> positions = sentinelBuffer(n()), normals = sentinelBuffer(n());
    int hint = hint_in;
    EXPECT_FALSE(model_.evaluate(view, sharpness, positions, normals, &hint))
        << view.transpose() << " sharpness " << sharpness << " hint " << hint_in;
    EXPECT_EQ(hint, hint_in);
    expectUntouched(positions);
    expectUntouched(normals);
  };
  for (const Vector3d& view : badViews()) refused(view, 0.0, -1);
  for (double sharpness : {kNaN, kInf, -kInf}) refused(Vector3d(0.3, 0.2, 1), sharpness, -1);
  for (int bad : invalidHints()) refused(Vector3d(0.3, 0.2, 1), 0.0, bad);
}

TEST_P(Contract, EvaluateWritesWhenValid) {
  std::vector<float> positions = sentinelBuffer(n()), normals = sentinelBuffer(n());
  int hint = -1;
  ASSERT_TRUE(model_.evaluate(Vector3d(0.3, 0.2, 1), 0.0, positions, normals, &hint));
  for (float p : positions) EXPECT_NE(p, kSentinel);
  for (float v : normals) EXPECT_NE(v, kSentinel);
}

INSTANTIATE_TEST_SUITE_P(Modes, Contract, ::testing::Values(Uncovered::Base, Uncovered::Cosine, Uncovered::Cosine2),
                         [](const auto& mode) { return std::string(uncoveredName(mode.param)); });

void expectKeyOutOfRange(const std::function<void()>& call, const std::string& message) {
  try {
    call();
    ADD_FAILURE() << "no vdg::Error for " << message;
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), message);
  }
}

TEST(ContractAccessors, KeyIndexOutOfRangeThrowsNamingIndexAndCount) {
  const ViewDependentModel model = ViewDependentModel::build(threeKeyModel(Uncovered::Base));
  const std::string message = "key 3 out of range (the model has 3 keys)";
  expectKeyOutOfRange([&] { (void)model.keyName(3); }, message);
  expectKeyOutOfRange([&] { (void)model.keyView(3); }, message);
  expectKeyOutOfRange([&] { (void)model.keyCamera(3); }, message);
  expectKeyOutOfRange([&] { (void)model.keyMovedCount(3); }, message);
  expectKeyOutOfRange([&] { (void)model.keyName(1000000); }, "key 1000000 out of range (the model has 3 keys)");
  EXPECT_EQ(model.keyName(2), "k2");
  EXPECT_NO_THROW((void)model.keyView(2));
}

}  // namespace
}  // namespace vdg
