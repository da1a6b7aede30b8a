#include "vdg/viewdep/model.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>
#include <string>
#include <vector>

#include "support/test_meshes.h"
#include "vdg/geom/error.h"
#include "vdg/io/manifest.h"

namespace vdg {
namespace {

using Eigen::Vector3d;

constexpr float kPositionTol = 1e-6f;    // float rounding of base + (key - base)
constexpr double kPathStep = 1e-3;       // radians between samples along a camera path
constexpr double kMeshLipschitz = 60.0;  // max vertex motion per radian of view, per unit of key delta

// weights() for a query that is valid by construction (the contract cases are in contract_test).
ViewWeights weightsOf(const ViewDependentModel& model, const Vector3d& view, double sharpness = 0.0) {
  ViewWeights w;
  EXPECT_TRUE(model.weights(view, sharpness, w)) << view.transpose();
  return w;
}

// A sphere with one key per octahedron direction, each bulging the sphere towards its view.
RawViewDependentModel bulgeModel(const std::vector<Vector3d>& views, Uncovered mode = Uncovered::Base) {
  RawViewDependentModel raw;
  raw.base = testing::uvSphere(12, 16);
  raw.sphere.uncovered = mode;
  for (std::size_t k = 0; k < views.size(); ++k) {
    RawKey key;
    key.name = "k" + std::to_string(k);
    key.mesh = raw.base;
    key.view = views[k];
    const Vector3d dir = views[k].normalized();
    for (std::size_t v = 0; v < key.mesh.vertexCount(); ++v) {
      const Vector3d p(key.mesh.positions[3 * v], key.mesh.positions[3 * v + 1], key.mesh.positions[3 * v + 2]);
      const double s = std::max(0.0, p.dot(dir) - 0.5);  // only the cap facing the view moves: sparse
      for (int c = 0; c < 3; ++c) key.mesh.positions[3 * v + c] += static_cast<float>(0.4 * s * dir[c]);
    }
    raw.keys.push_back(std::move(key));
  }
  return raw;
}

// Section 3.2.3 written out: v = w_base * base + sum_i w_i * key_i, vertex by vertex.
void expectWeightedSumOfKeys(const RawViewDependentModel& raw, const ViewWeights& w, const std::vector<float>& out) {
  for (std::size_t i = 0; i < out.size(); ++i) {
    double expected = w.base * raw.base.positions[i];
    for (int k = 0; k < 3; ++k)
      if (w.key[k] >= 0) expected += w.weight[k] * raw.keys[static_cast<std::size_t>(w.key[k])].mesh.positions[i];
    ASSERT_NEAR(out[i], expected, kPositionTol) << "coordinate " << i;
  }
}

const std::vector<Vector3d> kOctahedron = {Vector3d(1, 0, 0),  Vector3d(-1, 0, 0), Vector3d(0, 1, 0),
                                           Vector3d(0, -1, 0), Vector3d(0, 0, 1),  Vector3d(0, 0, -1)};

TEST(ViewDependentModel, KeyViewReproducesTheKeyMesh) {
  for (Uncovered mode : {Uncovered::Base, Uncovered::Cosine}) {
    const RawViewDependentModel raw = bulgeModel(kOctahedron, mode);
    const ViewDependentModel model = ViewDependentModel::build(raw);
    std::vector<float> out(raw.base.positions.size());
    for (std::size_t k = 0; k < raw.keys.size(); ++k) {
      EXPECT_LT(model.keyMovedCount(k), raw.base.vertexCount() / 2) << "bulges are sparse";
      ASSERT_TRUE(model.evaluate(raw.keys[k].view, 0.0, out));
      for (std::size_t i = 0; i < out.size(); ++i) ASSERT_NEAR(out[i], raw.keys[k].mesh.positions[i], kPositionTol);
    }
  }
}

TEST(ViewDependentModel, KeyViewReproducesTheShippedExample) {
  const RawViewDependentModel raw = loadManifest(std::string(VDG_SOURCE_DIR) + "/examples/spot/spot.vdg.json");
  const ViewDependentModel model = ViewDependentModel::build(raw);
  std::vector<float> out(raw.base.positions.size());
  for (std::size_t k = 0; k < raw.keys.size(); ++k) {
    ASSERT_TRUE(model.evaluate(raw.keys[k].view, 0.0, out));
    for (std::size_t i = 0; i < out.size(); ++i) ASSERT_NEAR(out[i], raw.keys[k].mesh.positions[i], kPositionTol) << k;
  }
}

TEST(ViewDependentModel, BlendIsTheWeightedSumOfKeyMeshes) {
  const RawViewDependentModel raw = bulgeModel(kOctahedron);
  const ViewDependentModel model = ViewDependentModel::build(raw);
  const Vector3d view(0.3, 0.5, 0.8);
  const ViewWeights w = weightsOf(model, view);
  std::vector<float> out(raw.base.positions.size());
  ASSERT_TRUE(model.blend(w, out));
  expectWeightedSumOfKeys(raw, w, out);
}

TEST(ViewDependentModel, DenseAndSparseKeysBlendTheSame) {
  RawViewDependentModel raw = bulgeModel(kOctahedron);
  // Make key 0 dense: move every vertex a little.
  for (float& p : raw.keys[0].mesh.positions) p *= 1.01f;
  const ViewDependentModel model = ViewDependentModel::build(raw);
  EXPECT_EQ(model.keyMovedCount(0), raw.base.vertexCount());
  const ViewWeights w = weightsOf(model, Vector3d(1, 0.4, 0.4));
  std::vector<float> out(raw.base.positions.size());
  ASSERT_TRUE(model.blend(w, out));
  expectWeightedSumOfKeys(raw, w, out);
}

TEST(ViewDependentModel, FarFromAllKeysTheBaseModelIsBack) {
  const RawViewDependentModel raw = bulgeModel({Vector3d(0, 0, 1), Vector3d(0.5, 0, 1), Vector3d(-0.5, 0.2, 1)});
  const ViewDependentModel model = ViewDependentModel::build(raw);
  std::vector<float> out(raw.base.positions.size());
  ASSERT_TRUE(model.evaluate(Vector3d(0, 0, -1), 0.0, out));
  EXPECT_EQ(out, raw.base.positions);
}

TEST(ViewDependentModel, BlendedMeshIsContinuousAlongCameraPaths) {
  const std::vector<Vector3d> views = {Vector3d(0, 0, 1), Vector3d(1, 0.2, 0), Vector3d(-1, 0.1, 0.1),
                                       Vector3d(0, 1, 0.3)};
  // Paths: an orbit at 20 degrees elevation between the keys, and the great circle through the
  // first two keys (it crosses hull vertices exactly, and hull edges and dummy points on the way).
  const Vector3d a = views[0].normalized();
  const Vector3d b = (views[1] - views[1].dot(a) * a).normalized();
  const std::vector<std::function<Vector3d(double)>> paths = {
      [](double t) { return Vector3d(std::sin(t) * std::cos(0.35), std::sin(0.35), std::cos(t) * std::cos(0.35)); },
      [a, b](double t) { return Vector3d(std::cos(t) * a + std::sin(t) * b); }};
  for (Uncovered mode : {Uncovered::Base, Uncovered::Cosine, Uncovered::Cosine2}) {
    const RawViewDependentModel raw = bulgeModel(views, mode);
    const ViewDependentModel model = ViewDependentModel::build(raw);
    double max_delta = 0.0;
    for (const RawKey& key : raw.keys)
      for (std::size_t i = 0; i < key.mesh.positions.size(); ++i)
        max_delta = std::max(max_delta, static_cast<double>(std::abs(key.mesh.positions[i] - raw.base.positions[i])));
    for (std::size_t p = 0; p < paths.size(); ++p) {
      std::vector<float> previous(raw.base.positions.size()), current(raw.base.positions.size());
      int hint = -1;
      ASSERT_TRUE(model.evaluate(paths[p](0.0), 0.0, previous, {}, &hint));
      double worst = 0.0;
      for (double t = kPathStep; t < 2 * std::numbers::pi; t += kPathStep) {
        ASSERT_TRUE(model.evaluate(paths[p](t), 0.0, current, {}, &hint));
        for (std::size_t i = 0; i < current.size(); ++i)
          worst = std::max(worst, static_cast<double>(std::abs(current[i] - previous[i])));
        std::swap(previous, current);
      }
      EXPECT_LE(worst, kMeshLipschitz * kPathStep * max_delta) << "path " << p << ", mode " << uncoveredName(mode);
    }
  }
}

TEST(ViewDependentModel, NormalsAreRecomputedFromTheBlendedShape) {
  // One key stretches the unit sphere along x into the ellipsoid x^2/4 + y^2 + z^2 = 1. Every
  // blend is then the ellipsoid with semi-axis a = 1 + w along x (w the key's weight), whose
  // surface normal at (x, y, z) is the gradient (x / a^2, y, z), normalised: an independent,
  // analytic expectation (a blend of the two shapes' normals would not satisfy it).
  constexpr double kSmoothNormalTol = 1e-2;  // |n - n_exact| on a 96 x 128 sphere (measured 5.5e-3)
  RawViewDependentModel raw;
  raw.base = testing::uvSphere(96, 128);
  RawKey key;
  key.name = "stretched";
  key.mesh = raw.base;
  for (std::size_t v = 0; v < key.mesh.vertexCount(); ++v) key.mesh.positions[3 * v] *= 2.0f;
  key.view = Vector3d(0, 0, 1);
  raw.keys.push_back(key);
  const ViewDependentModel model = ViewDependentModel::build(raw);
  const Vector3d view(0.3, 0.2, 1.0);
  const ViewWeights w = weightsOf(model, view);
  double key_weight = 0.0;
  for (int slot = 0; slot < 3; ++slot)
    if (w.key[slot] == 0) key_weight += w.weight[slot];
  ASSERT_GT(key_weight, 0.2);  // a real blend, neither shape alone
  ASSERT_LT(key_weight, 0.99);
  const double a = 1.0 + key_weight;
  std::vector<float> positions(raw.base.positions.size()), normals(positions.size());
  ASSERT_TRUE(model.evaluate(view, 0.0, positions, normals));
  double worst = 0.0, worst_radial = 0.0;
  for (std::size_t v = 0; v < raw.base.vertexCount(); ++v) {
    const Vector3d p(positions[3 * v], positions[3 * v + 1], positions[3 * v + 2]);
    const Vector3d exact = Vector3d(p.x() / (a * a), p.y(), p.z()).normalized();
    const Vector3d n(normals[3 * v], normals[3 * v + 1], normals[3 * v + 2]);
    worst = std::max(worst, (n - exact).norm());
    worst_radial = std::max(worst_radial, (p.normalized() - exact).norm());
  }
  EXPECT_LT(worst, kSmoothNormalTol);
  // The tolerance tells shapes apart: the radial direction (the sphere's normal) is far off.
  EXPECT_GT(worst_radial, 10 * kSmoothNormalTol);
}

TEST(ViewDependentModel, EyePositionsAreMeasuredFromTheCentre) {
  RawViewDependentModel raw = bulgeModel(kOctahedron);
  raw.center = Vector3d(10, 0, 0);
  const ViewDependentModel model = ViewDependentModel::build(raw);
  EXPECT_NEAR((model.viewFromEye(Vector3d(10, 0, 5)) - Vector3d(0, 0, 1)).norm(), 0.0, 1e-12);
}

// ---- extent(): what the model can draw ---------------------------------------------------------

// Views spread over the whole sphere (a Fibonacci lattice): every blend the model can make.
std::vector<Vector3d> spreadViews(int count) {
  std::vector<Vector3d> views;
  const double golden = std::numbers::pi * (3.0 - std::sqrt(5.0));
  for (int i = 0; i < count; ++i) {
    const double y = 1.0 - 2.0 * (i + 0.5) / count, r = std::sqrt(1.0 - y * y);
    views.emplace_back(r * std::cos(golden * i), y, r * std::sin(golden * i));
  }
  return views;
}

void expectInside(const Bounds& box, double radius, const Vector3d& center, const std::vector<float>& positions,
                  const std::string& what) {
  for (std::size_t v = 0; v < positions.size() / 3; ++v) {
    for (int c = 0; c < 3; ++c) {
      ASSERT_GE(positions[3 * v + c], box.min[c] - kPositionTol) << what << " vertex " << v;
      ASSERT_LE(positions[3 * v + c], box.max[c] + kPositionTol) << what << " vertex " << v;
    }
    const Vector3d p(positions[3 * v], positions[3 * v + 1], positions[3 * v + 2]);
    ASSERT_LE((p - center).norm(), radius + kPositionTol) << what << " vertex " << v;
  }
}

// The box is exactly the union of the base's and the keys' boxes, the radius the farthest of their
// vertices from the centre, and every blend from any view stays inside both.
TEST(ViewDependentModelExtent, HoldsTheBaseAndEveryKeyAndEveryBlend) {
  const RawViewDependentModel raw = bulgeModel(kOctahedron);
  const ViewDependentModel model = ViewDependentModel::build(raw);
  Bounds expected = computeBounds(raw.base.positions);
  double radius = 0.0;
  auto grow = [&](const std::vector<float>& positions) {
    const Bounds b = computeBounds(positions);
    for (int c = 0; c < 3; ++c) {
      expected.min[c] = std::min(expected.min[c], b.min[c]);
      expected.max[c] = std::max(expected.max[c], b.max[c]);
    }
    for (std::size_t v = 0; v < positions.size() / 3; ++v)
      radius = std::max(
          radius, (Vector3d(positions[3 * v], positions[3 * v + 1], positions[3 * v + 2]) - model.center()).norm());
  };
  grow(raw.base.positions);
  for (const RawKey& key : raw.keys) grow(key.mesh.positions);
  EXPECT_EQ(model.extent().min, expected.min);
  EXPECT_EQ(model.extent().max, expected.max);
  EXPECT_NEAR(model.extentRadius(), radius, kPositionTol);
  // The bulges (0.4 * 0.5 beyond the unit sphere) reach past the base on every axis.
  EXPECT_GT(model.extent().max[1], computeBounds(raw.base.positions).max[1] + 0.1f);

  std::vector<float> out(raw.base.positions.size());
  for (const Vector3d& view : spreadViews(400)) {
    ASSERT_TRUE(model.evaluate(view, 0.0, out));
    expectInside(model.extent(), model.extentRadius(), model.center(), out, "view");
  }
}

// The case: a front key that raises the top of the model by 80% raises the extent's top
// by as much; the base alone would frame it 80% too low.
TEST(ViewDependentModelExtent, AKeyRaisingTheTopRaisesTheExtent) {
  RawViewDependentModel raw;
  raw.base = testing::uvSphere(8, 12);  // unit sphere: y in [-1, 1]
  RawKey key;
  key.name = "tall";
  key.mesh = raw.base;
  for (std::size_t v = 0; v < key.mesh.vertexCount(); ++v)
    if (key.mesh.positions[3 * v + 1] > 0.0f) key.mesh.positions[3 * v + 1] *= 1.8f;
  key.view = Vector3d(0, 0, 1);
  raw.keys.push_back(key);
  const ViewDependentModel model = ViewDependentModel::build(raw);
  EXPECT_NEAR(model.extent().max[1], 1.8f, kPositionTol);
  EXPECT_NEAR(model.extent().min[1], -1.0f, kPositionTol);
  EXPECT_NEAR(model.extentRadius(), 1.8, kPositionTol);  // the centre is the base's box centre, the origin
}

}  // namespace
}  // namespace vdg
