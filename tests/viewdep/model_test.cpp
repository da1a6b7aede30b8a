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

// Per-part key sets (docs/weights.md, "Per-part key sets").
constexpr double kMaskSumTol = 1e-6;      // the masks sum to 1 (float rounding of 1 - sum)
constexpr double kSmoothstepSlope = 1.5;  // max of d/dt (1 - 3t^2 + 2t^3) over [0, 1]
constexpr float kMaskedTol = 1e-5f;       // float rounding of base + m * w * (key - base), summed over parts

// bulgeModel's octahedron keys twice: "a0".."a5" and "b0".."b5", the same meshes and views.
RawViewDependentModel twoKeySets() {
  RawViewDependentModel raw = bulgeModel(kOctahedron);
  const std::size_t n = raw.keys.size();
  for (std::size_t k = 0; k < n; ++k) {
    RawKey copy = raw.keys[k];
    raw.keys[k].name = "a" + std::to_string(k);
    copy.name = "b" + std::to_string(k);
    raw.keys.push_back(std::move(copy));
  }
  return raw;
}

std::vector<std::int32_t> verticesWhere(const TriMesh& mesh, const std::function<bool(const Vector3d&)>& pick) {
  std::vector<std::int32_t> out;
  for (std::size_t v = 0; v < mesh.vertexCount(); ++v)
    if (pick(Vector3d(mesh.positions[3 * v], mesh.positions[3 * v + 1], mesh.positions[3 * v + 2])))
      out.push_back(static_cast<std::int32_t>(v));
  return out;
}

RawPart partOf(const std::string& name, std::vector<std::int32_t> vertices, double border,
               std::vector<std::string> keys) {
  RawPart part;
  part.name = name;
  part.vertices = std::move(vertices);
  part.border = border;
  part.keys = std::move(keys);
  return part;
}

TEST(ModelParts, AModelWithoutPartsHasNone) {
  const ViewDependentModel model = ViewDependentModel::build(bulgeModel(kOctahedron));
  EXPECT_FALSE(model.hasParts());
  EXPECT_EQ(model.partCount(), 0u);
  EXPECT_NO_THROW(model.requireNoParts("anything"));
  std::vector<float> out(3 * model.vertexCount());
  const std::vector<Vector3d> views;
  EXPECT_FALSE(model.evaluateParts(views, 0.0, out)) << "evaluateParts needs parts";
}

TEST(ModelParts, OnePartCoveringEverythingEqualsThePlainModel) {
  for (const WeightScheme scheme : {WeightScheme::Linear, WeightScheme::Smooth, WeightScheme::Rbf}) {
    RawViewDependentModel raw = bulgeModel(kOctahedron);
    raw.sphere.scheme = scheme;
    const ViewDependentModel plain = ViewDependentModel::build(raw);
    std::vector<std::string> names;
    for (const RawKey& key : raw.keys) names.push_back(key.name);
    raw.parts.push_back(partOf("all", verticesWhere(raw.base, [](const Vector3d&) { return true; }), 0.0, names));
    const ViewDependentModel parts = ViewDependentModel::build(raw);
    ASSERT_EQ(parts.partCount(), 2u);
    EXPECT_EQ(parts.partVertexCount(0), raw.base.vertexCount());
    EXPECT_EQ(parts.partVertexCount(1), 0u);
    EXPECT_EQ(parts.partName(1), kRestPartName);
    std::vector<float> a(raw.base.positions.size()), b(a.size()), na(a.size()), nb(a.size());
    for (const Vector3d& view : {Vector3d(1, 0.3, 0.2), Vector3d(-0.4, -1, 0.1), Vector3d(0.2, 0.1, -1)}) {
      ASSERT_TRUE(plain.evaluate(view, 0.0, a, na));
      ASSERT_TRUE(parts.evaluate(view, 0.0, b, nb));
      for (std::size_t i = 0; i < a.size(); ++i) {
        ASSERT_NEAR(a[i], b[i], kPositionTol) << weightSchemeName(scheme) << " coordinate " << i;
        ASSERT_NEAR(na[i], nb[i], kPositionTol * 10) << weightSchemeName(scheme) << " normal " << i;
      }
    }
  }
}

TEST(ModelParts, MasksAreASmoothPartitionOfUnity) {
  RawViewDependentModel raw = twoKeySets();
  constexpr double kTopBorder = 0.4, kSideBorder = 0.3;
  raw.parts.push_back(partOf("top", verticesWhere(raw.base, [](const Vector3d& p) { return p.y() > 0.6; }), kTopBorder,
                             {"a0", "a2", "a3", "a4", "a5"}));
  raw.parts.push_back(
      partOf("bottom", verticesWhere(raw.base, [](const Vector3d& p) { return p.y() < -0.6; }), kSideBorder, {"a1"}));
  raw.validate();
  const std::vector<std::vector<float>> masks = computePartMasks(raw);
  ASSERT_EQ(masks.size(), 3u);
  const std::size_t nv = raw.base.vertexCount();
  for (std::size_t v = 0; v < nv; ++v) {
    double sum = 0.0;
    for (const auto& m : masks) {
      ASSERT_GE(m[v], 0.0f);
      ASSERT_LE(m[v], 1.0f);
      sum += m[v];
    }
    ASSERT_NEAR(sum, 1.0, kMaskSumTol) << "vertex " << v;
  }
  for (const std::int32_t v : raw.parts[0].vertices) EXPECT_EQ(masks[0][static_cast<std::size_t>(v)], 1.0f);
  const auto at = [&](std::size_t v) {
    return Vector3d(raw.base.positions[3 * v], raw.base.positions[3 * v + 1], raw.base.positions[3 * v + 2]);
  };
  // Bounded change along every edge: |m(a) - m(b)| <= 1.5 |a - b| / border (the smoothstep's
  // slope); the rest's mask is 1 minus the two, whose borders here do not meet.
  const double slope[3] = {kSmoothstepSlope / kTopBorder, kSmoothstepSlope / kSideBorder,
                           kSmoothstepSlope / kTopBorder + kSmoothstepSlope / kSideBorder};
  std::size_t between = 0;
  for (std::size_t t = 0; t < raw.base.triangleCount(); ++t)
    for (int c = 0; c < 3; ++c) {
      const auto a = static_cast<std::size_t>(raw.base.triangles[3 * t + c]);
      const auto b = static_cast<std::size_t>(raw.base.triangles[3 * t + (c + 1) % 3]);
      const double length = (at(a) - at(b)).norm();
      for (std::size_t p = 0; p < 3; ++p)
        ASSERT_LE(std::abs(masks[p][a] - masks[p][b]), slope[p] * length + kMaskSumTol) << "part " << p;
    }
  for (std::size_t v = 0; v < nv; ++v) between += masks[0][v] > 0.0f && masks[0][v] < 1.0f;
  EXPECT_GT(between, 0u) << "the border blends some vertices";
}

TEST(ModelParts, OverlappingPartsShareAVertexAndSeamCopiesAgree) {
  RawViewDependentModel raw = twoKeySets();
  const std::vector<std::int32_t> all = verticesWhere(raw.base, [](const Vector3d&) { return true; });
  raw.parts.push_back(partOf("one", all, 0.0, {"a0", "a1", "a2"}));
  raw.parts.push_back(partOf("two", {0, 1, 2}, 0.0, {"a3", "a4", "a5"}));
  const std::vector<std::vector<float>> masks = computePartMasks(raw);
  EXPECT_FLOAT_EQ(masks[0][1], 0.5f);
  EXPECT_FLOAT_EQ(masks[1][1], 0.5f);
  EXPECT_FLOAT_EQ(masks[2][1], 0.0f);
  // Vertices at the same position (uvSphere's seam copies) get the same masks, hard border or not.
  for (std::size_t u = 0; u < raw.base.vertexCount(); ++u) {
    for (std::size_t v = u + 1; v < raw.base.vertexCount(); ++v) {
      if (!std::equal(&raw.base.positions[3 * u], &raw.base.positions[3 * u + 3], &raw.base.positions[3 * v])) continue;
      for (const auto& m : masks) ASSERT_EQ(m[u], m[v]) << u << " and " << v;
    }
  }
}

// The cubist case: the top follows a fixed view (+x, key a0's), the rest follows the camera. At
// the camera view of key b1 every vertex is base + m_top (a0 - base) + m_rest (b1 - base): fully the
// a0 key on the top, fully the b1 key away from it, blended across the border.
TEST(ModelParts, EachPartTakesItsKeyAtItsOwnView) {
  RawViewDependentModel raw = twoKeySets();
  RawPart top = partOf("top", verticesWhere(raw.base, [](const Vector3d& p) { return p.y() > 0.5; }), 0.3,
                       {"a0", "a1", "a2", "a3", "a4", "a5"});
  top.view = Vector3d(2, 0, 0);
  raw.parts.push_back(top);
  const ViewDependentModel model = ViewDependentModel::build(raw);
  ASSERT_EQ(model.partCount(), 2u);
  ASSERT_TRUE(model.partView(0).has_value());
  EXPECT_NEAR((*model.partView(0) - Vector3d(1, 0, 0)).norm(), 0.0, 1e-12);
  EXPECT_FALSE(model.partView(1).has_value());
  EXPECT_EQ(model.partKeys(1).size(), 6u) << "the b keys drive the rest";
  const std::vector<std::vector<float>> masks = computePartMasks(raw);
  const auto expectBlend = [&](const std::vector<float>& out, std::size_t top_key, std::size_t rest_key) {
    for (std::size_t i = 0; i < out.size(); ++i) {
      const double base = raw.base.positions[i];
      const double expected = base + masks[0][i / 3] * (raw.keys[top_key].mesh.positions[i] - base) +
                              masks[1][i / 3] * (raw.keys[rest_key].mesh.positions[i] - base);
      ASSERT_NEAR(out[i], expected, kMaskedTol) << "coordinate " << i;
    }
  };
  std::vector<float> out(raw.base.positions.size());
  ASSERT_TRUE(model.evaluate(kOctahedron[1], 0.0, out));
  expectBlend(out, 0, 6 + 1);
  // evaluateParts: every part's view chosen by the caller (vdg eval --part-view).
  const std::vector<Vector3d> views = {kOctahedron[4], kOctahedron[2]};
  ASSERT_TRUE(model.evaluateParts(views, 0.0, out));
  expectBlend(out, 4, 6 + 2);
  std::vector<float> w(7);
  ASSERT_TRUE(model.partWeights(0, kOctahedron[4], 0.0, w));
  EXPECT_FLOAT_EQ(w[4], 1.0f);
  EXPECT_FLOAT_EQ(w[6], 0.0f);
}

// A material selection takes every vertex of the material's triangles, and nothing else with a hard
// border (uvSphere's seam copies of a selected vertex excepted: they share its position).
TEST(ModelParts, AMaterialSelectsItsTrianglesVertices) {
  RawViewDependentModel raw = twoKeySets();
  raw.base.materials.resize(1);
  raw.base.materials[0].name = "cap";
  raw.base.face_materials.assign(raw.base.triangleCount(), -1);
  std::vector<std::uint8_t> on(raw.base.vertexCount(), 0);
  for (std::size_t t = 0; t < raw.base.triangleCount(); ++t) {
    if (raw.base.positions[3 * static_cast<std::size_t>(raw.base.triangles[3 * t]) + 1] <= 0.7f) continue;
    raw.base.face_materials[t] = 0;
    for (std::size_t c = 0; c < 3; ++c) on[static_cast<std::size_t>(raw.base.triangles[3 * t + c])] = 1;
  }
  RawPart part = partOf("cap", {}, 0.0, {"a0", "a1", "a2", "a3", "a4", "a5"});
  part.select = RawPart::Select::kMaterial;
  part.material = "cap";
  raw.parts.push_back(part);
  raw.validate();
  const std::vector<std::vector<float>> masks = computePartMasks(raw);
  std::size_t selected = 0;
  for (std::size_t v = 0; v < raw.base.vertexCount(); ++v) {
    if (on[v]) {
      EXPECT_EQ(masks[0][v], 1.0f) << "vertex " << v;
    }
    selected += on[v];
    EXPECT_TRUE(masks[0][v] == 0.0f || masks[0][v] == 1.0f) << "a hard border, vertex " << v;
  }
  EXPECT_GT(selected, 0u);
  EXPECT_EQ(ViewDependentModel::build(raw).partVertexCount(0),
            static_cast<std::size_t>(std::count(masks[0].begin(), masks[0].end(), 1.0f)));
}

TEST(ModelParts, ContractsAndRefusals) {
  RawViewDependentModel raw = twoKeySets();
  EXPECT_THROW(
      {
        raw.parts.push_back(partOf("top", {0, 1}, 0.0, {"a0"}));
        raw.validate();
      },
      Error)
      << "a1 and b1 drive the rest from the same view";
  raw.parts[0].keys = {"a0", "a1", "a2", "a3", "a4", "a5"};
  const ViewDependentModel model = ViewDependentModel::build(raw);
  ViewWeights w;
  EXPECT_FALSE(model.weights(Vector3d(1, 0, 0), 0.0, w)) << "one key set for the whole mesh: partWeights";
  std::vector<float> dense(model.keyCount() + 1), out(3 * model.vertexCount()), short_out(3);
  EXPECT_FALSE(model.denseWeights(Vector3d(1, 0, 0), 0.0, dense));
  const std::vector<Vector3d> one = {Vector3d(1, 0, 0)}, zero = {Vector3d(1, 0, 0), Vector3d::Zero()};
  const std::vector<Vector3d> good = {Vector3d(1, 0, 0), Vector3d(0, 1, 0)};
  EXPECT_FALSE(model.evaluateParts(one, 0.0, out));
  EXPECT_FALSE(model.evaluateParts(zero, 0.0, out));
  EXPECT_FALSE(model.evaluateParts(good, std::nan(""), out));
  EXPECT_FALSE(model.evaluateParts(good, 0.0, short_out));
  EXPECT_TRUE(model.evaluateParts(good, 0.0, out));
  std::vector<float> pw(7);
  EXPECT_FALSE(model.partWeights(2, Vector3d(1, 0, 0), 0.0, pw));
  EXPECT_FALSE(model.partWeights(0, Vector3d(1, 0, 0), 0.0, dense));
  EXPECT_THROW((void)model.partName(2), Error);
  try {
    model.requireThreeKeyWeights("the renderer");
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("model parts ('parts') are not supported by the renderer"), std::string::npos)
        << e.what();
  }
  raw.parts[0].name = "top";
  raw.base_animation = BaseAnimationSpec{};
  raw.base_frames = {raw.base.positions};
  EXPECT_THROW(raw.validate(), Error);
}

}  // namespace
}  // namespace vdg
