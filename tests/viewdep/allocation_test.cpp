// Per-frame evaluation allocates nothing (the per-frame contract in model.h and view_sphere.h):
// counted through the global operator new (tests/support/allocation_counter.cpp), on valid
// input and on refused input alike.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "support/allocation_counter.h"
#include "support/test_meshes.h"
#include "vdg/viewdep/model.h"

namespace vdg {
namespace {

using testing::allocationsDuring;

constexpr int kFrames = 100;

RawViewDependentModel fourKeyModel(Uncovered mode) {
  RawViewDependentModel raw;
  raw.base = testing::uvSphere(10, 12);
  raw.sphere.uncovered = mode;
  const Eigen::Vector3d views[] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {-1, 0.2, 0}};
  for (int k = 0; k < 4; ++k) {
    RawKey key;
    key.name = "k" + std::to_string(k);
    key.mesh = raw.base;
    if (k == 3) {
      for (float& p : key.mesh.positions) p *= 1.1f;  // a dense key
    } else {
      key.mesh.positions[3 * static_cast<std::size_t>(k)] += 0.1f;  // sparse keys
    }
    key.view = views[k];
    raw.keys.push_back(key);
  }
  return raw;
}

Eigen::Vector3d orbit(int frame) {
  const double t = frame * 0.0628;
  return {std::sin(t), 0.3, std::cos(t)};
}

class Allocation : public ::testing::TestWithParam<Uncovered> {
 protected:
  void SetUp() override {
    raw_ = fourKeyModel(GetParam());
    model_.emplace(ViewDependentModel::build(raw_));
    positions_.assign(raw_.base.positions.size(), 0.0f);
    normals_.assign(raw_.base.positions.size(), 0.0f);
  }
  RawViewDependentModel raw_;
  std::optional<ViewDependentModel> model_;
  std::vector<float> positions_, normals_;
};

TEST_P(Allocation, SphereWeights) {
  const ViewSphere& sphere = model_->sphere();
  int hint = -1;
  bool ok = true;
  EXPECT_EQ(allocationsDuring([&] {
              for (int i = 0; i < kFrames; ++i) {
                ViewWeights w;
                ok = sphere.weights(orbit(i), 1.5, w, &hint) && ok;
                ok = sphere.weightsByScan(orbit(i), 1.5, w) && ok;
              }
            }),
            0);
  EXPECT_TRUE(ok);
}

TEST_P(Allocation, ModelWeights) {
  int hint = -1;
  bool ok = true;
  EXPECT_EQ(allocationsDuring([&] {
              for (int i = 0; i < kFrames; ++i) {
                ViewWeights w;
                ok = model_->weights(orbit(i), 0.0, w, &hint) && ok;
              }
            }),
            0);
  EXPECT_TRUE(ok);
}

TEST_P(Allocation, Blend) {
  std::vector<ViewWeights> weights(kFrames);
  for (int i = 0; i < kFrames; ++i) ASSERT_TRUE(model_->weights(orbit(i), 0.0, weights[i]));
  bool ok = true;
  EXPECT_EQ(allocationsDuring([&] {
              for (const ViewWeights& w : weights) ok = model_->blend(w, positions_) && ok;
            }),
            0);
  EXPECT_TRUE(ok);
}

TEST_P(Allocation, KeyPositions) {
  bool ok = true;
  EXPECT_EQ(allocationsDuring([&] {
              for (std::size_t k = 0; k < model_->keyCount(); ++k) ok = model_->keyPositions(k, positions_) && ok;
            }),
            0);
  EXPECT_TRUE(ok);
}

TEST_P(Allocation, EvaluateWithoutNormals) {
  int hint = -1;
  bool ok = true;
  EXPECT_EQ(allocationsDuring([&] {
              for (int i = 0; i < kFrames; ++i) ok = model_->evaluate(orbit(i), 1.5, positions_, {}, &hint) && ok;
            }),
            0);
  EXPECT_TRUE(ok);
}

TEST_P(Allocation, EvaluateWithNormals) {
  int hint = -1;
  bool ok = true;
  EXPECT_EQ(allocationsDuring([&] {
              for (int i = 0; i < kFrames; ++i) ok = model_->evaluate(orbit(i), 1.5, positions_, normals_, &hint) && ok;
            }),
            0);
  EXPECT_TRUE(ok);
}

TEST_P(Allocation, VertexNormals) {
  bool ok = true;
  EXPECT_EQ(allocationsDuring([&] { ok = computeVertexNormals(raw_.base.positions, raw_.base.triangles, normals_); }),
            0);
  EXPECT_TRUE(ok);
}

TEST_P(Allocation, RefusedCallsAllocateNothingEither) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::vector<float> short_positions(positions_.size() - 3);
  int bad_hint = 1 << 20;
  ViewWeights bad;
  bad.key[0] = 99;
  bad.weight[0] = 1.0f;
  bool any = false;
  EXPECT_EQ(allocationsDuring([&] {
              ViewWeights w;
              any = model_->weights(Eigen::Vector3d(nan, 0, 1), 0.0, w) || any;
              any = model_->weights(Eigen::Vector3d(0, 0, 1), 0.0, w, &bad_hint) || any;
              any = model_->blend(bad, positions_) || any;
              any = model_->keyPositions(model_->keyCount(), positions_) || any;
              any = model_->evaluate(Eigen::Vector3d(0, 0, 1), 0.0, short_positions) || any;
              any = model_->evaluate(Eigen::Vector3d::Zero(), 0.0, positions_, normals_) || any;
              any = computeVertexNormals(raw_.base.positions, raw_.base.triangles, short_positions) || any;
            }),
            0);
  EXPECT_FALSE(any);
}

INSTANTIATE_TEST_SUITE_P(Modes, Allocation, ::testing::Values(Uncovered::Base, Uncovered::Cosine, Uncovered::Cosine2),
                         [](const auto& mode) { return std::string(uncoveredName(mode.param)); });

// A model with parts (one key per part, a fixed driving view on one) evaluates without allocating,
// through evaluate() and evaluateParts(), for every weight scheme.
TEST(AllocationParts, EvaluatePartsAllocatesNothing) {
  for (const WeightScheme scheme : {WeightScheme::Linear, WeightScheme::Smooth, WeightScheme::Rbf}) {
    RawViewDependentModel raw = fourKeyModel(Uncovered::Base);
    raw.sphere.scheme = scheme;
    RawPart part;
    part.name = "cap";
    part.vertices = {0, 1, 2, 3};
    part.border = 0.5;
    part.keys = {"k0", "k1"};
    part.view = Eigen::Vector3d(0, 0, 1);
    raw.parts.push_back(part);
    const ViewDependentModel model = ViewDependentModel::build(raw);
    std::vector<float> positions(raw.base.positions.size()), normals(positions.size());
    std::vector<Eigen::Vector3d> views(model.partCount(), Eigen::Vector3d(1, 0.2, 0));
    bool ok = true;
    const long count = allocationsDuring([&] {
      for (int f = 0; f < kFrames; ++f) {
        ok = model.evaluate(orbit(f), 0.0, positions, normals) && ok;
        views[0] = orbit(f);
        ok = model.evaluateParts(views, 0.0, positions, normals) && ok;
      }
    });
    EXPECT_TRUE(ok) << weightSchemeName(scheme);
    EXPECT_EQ(count, 0) << weightSchemeName(scheme);
  }
}

}  // namespace
}  // namespace vdg
