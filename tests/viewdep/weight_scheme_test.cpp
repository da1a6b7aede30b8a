// The weight schemes (view_sphere.h, "Weight schemes"; docs/weights.md): the smooth
// scheme is exact at every key, a partition of unity, non-negative, local and C1 along paths that
// cross hull edges and pass through keys; the linear scheme is the paper's barycentric blend, bit
// for bit, and shows its kinks. C1 is measured by halving the step of a dense path: a C1 blend's
// second differences shrink 4x (they are O(step^2)), a kink's only 2x (O(step)).
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "support/dense_weights.h"
#include "support/random_direction.h"
#include "support/test_meshes.h"
#include "vdg/geom/error.h"
#include "vdg/viewdep/continuity.h"
#include "vdg/viewdep/model.h"
#include "vdg/viewdep/view_sphere.h"

namespace vdg {
namespace {

using Eigen::Vector3d;
using testing::randomDirection;

constexpr double kWeightTol = 1e-5;  // float weights
constexpr double kKeyTol = 1e-6;     // a key's own view: one-hot to float rounding
// Halving the step divides the largest second difference along a path by at least kC1Ratio for a
// C1 blend (4 in the limit) and by at most kKinkRatio where it has kinks (2 in the limit).
constexpr double kC1Ratio = 3.2;
constexpr double kKinkRatio = 2.4;
constexpr double kPathStepRad = 2e-3;  // the coarser of the two steps
constexpr int kRandomViews = 10000;
constexpr int kPaths = 16;

using testing::denseWeights;

std::vector<double> denseAt(const ViewSphere& s, const Vector3d& view, double sharpness = 1.0) {
  if (s.settings().scheme == WeightScheme::Rbf) {  // weights over every key: the dense query only
    std::vector<float> f(s.keyCount() + 1);
    EXPECT_TRUE(s.denseWeights(view, sharpness, f)) << view.transpose();
    return {f.begin(), f.end()};
  }
  ViewWeights w;
  EXPECT_TRUE(s.weights(view, sharpness, w)) << view.transpose();
  return denseWeights(s, w);
}

Vector3d fromAngles(double azimuth_deg, double elevation_deg) {
  const double a = azimuth_deg * std::numbers::pi / 180.0, e = elevation_deg * std::numbers::pi / 180.0;
  return {std::cos(e) * std::sin(a), std::sin(e), std::cos(e) * std::cos(a)};
}

std::map<std::string, std::vector<Vector3d>> keySets() {
  std::map<std::string, std::vector<Vector3d>> c;
  c["octahedron"] = {Vector3d(1, 0, 0),  Vector3d(-1, 0, 0), Vector3d(0, 1, 0),
                     Vector3d(0, -1, 0), Vector3d(0, 0, 1),  Vector3d(0, 0, -1)};
  c["keys in one hemisphere"] = {fromAngles(0, 10), fromAngles(60, 30), fromAngles(-50, 20), fromAngles(20, 70),
                                 fromAngles(100, 5)};
  c["two keys"] = {Vector3d(0, 0, 1), Vector3d(1, 0, 0.2)};
  // Triangles wider than a quarter turn (each corner 125 degrees from the opposite edge's middle).
  c["tetrahedron"] = {Vector3d(1, 1, 1), Vector3d(1, -1, -1), Vector3d(-1, 1, -1), Vector3d(-1, -1, 1)};
  std::mt19937 rng(11);
  for (int i = 0; i < 20; ++i) c["twenty random keys"].push_back(randomDirection(rng));
  return c;
}

// The rbf settings matter only when `scheme` is WeightScheme::Rbf.
ViewSphere build(const std::vector<Vector3d>& keys, Uncovered mode, WeightScheme scheme,
                 RbfKernel kernel = RbfKernel::Gaussian, double width_deg = 60.0) {
  ViewSphereSettings settings;
  settings.uncovered = mode;
  settings.scheme = scheme;
  settings.rbf_kernel = kernel;
  settings.rbf_width_deg = width_deg;
  return ViewSphere::build(keys, settings);
}

const Uncovered kModes[] = {Uncovered::Base, Uncovered::Cosine, Uncovered::Cosine2};

TEST(SmoothWeights, EachKeyViewGivesThatKeyAlone) {
  for (const auto& [name, keys] : keySets())
    for (const Uncovered mode : kModes) {
      const ViewSphere s = build(keys, mode, WeightScheme::Smooth);
      for (std::size_t k = 0; k < keys.size(); ++k)
        for (const double alpha : {0.7, 1.0, 3.0}) {
          const auto d = denseAt(s, keys[k], alpha);
          for (std::size_t j = 0; j < d.size(); ++j)
            EXPECT_NEAR(d[j], j == k ? 1.0 : 0.0, kKeyTol) << name << ", key " << k << ", weight " << j;
        }
    }
}

TEST(SmoothWeights, PartitionOfUnityNonNegativeAndLocal) {
  std::mt19937 rng(5);
  for (const auto& [name, keys] : keySets())
    for (const Uncovered mode : kModes) {
      const ViewSphere s = build(keys, mode, WeightScheme::Smooth);
      for (int n = 0; n < kRandomViews / 4; ++n) {
        const Vector3d v = randomDirection(rng);
        ViewWeights w;
        ASSERT_TRUE(s.weights(v, 1.0, w));
        double sum = w.base;
        EXPECT_GE(w.base, 0.0f);
        for (int k = 0; k < 3; ++k) {
          EXPECT_GE(w.weight[k], 0.0f) << name;
          sum += w.weight[k];
          if (w.key[k] < 0 || w.triangle < 0) continue;
          const auto& t = s.triangles()[static_cast<std::size_t>(w.triangle)];
          EXPECT_TRUE(std::find(t.begin(), t.end(), w.key[k]) != t.end()) << name << ": a key off the view's triangle";
        }
        EXPECT_NEAR(sum, 1.0, kWeightTol) << name << " at " << v.transpose();
      }
    }
}

// The weights of the linear scheme are the paper's barycentric coordinates in the view's hull
// triangle (Rademacher 99, 3.2.2), computed here the way view_sphere.cpp does: bit for bit.
TEST(SmoothWeights, TheLinearSchemeIsThePapersBlendBitForBit) {
  std::mt19937 rng(9);
  const auto keys = keySets()["twenty random keys"];
  const ViewSphere s = ViewSphere::build(keys);  // the default settings: linear
  EXPECT_EQ(s.settings().scheme, WeightScheme::Linear);
  for (int n = 0; n < kRandomViews; ++n) {
    const Vector3d v = randomDirection(rng);
    ViewWeights w;
    ASSERT_TRUE(s.weightsByScan(v, 1.0, w));
    ASSERT_GE(w.triangle, 0);
    const Vector3d lambda = s.triangleInverse(static_cast<std::size_t>(w.triangle)) * v;
    const double p[3] = {std::max(lambda[0], 0.0), std::max(lambda[1], 0.0), std::max(lambda[2], 0.0)};
    const double scale = 1.0 / (p[0] + p[1] + p[2]);
    for (int k = 0; k < 3; ++k) {
      if (w.key[k] >= 0) {
        EXPECT_EQ(w.weight[k], static_cast<float>(p[k] * scale));
      }
    }
  }
}

// Largest second difference (L1 over keys and base) along `paths` great circles sampled every
// `step` radians.
double largestSecondDifference(const ViewSphere& s, double step, const std::vector<Vector3d>& normals) {
  double largest = 0.0;
  for (const Vector3d& normal : normals) {
    const Vector3d a = normal.unitOrthogonal(), b = normal.cross(a);
    const int steps = static_cast<int>(2.0 * std::numbers::pi / step);
    std::vector<double> previous2, previous;
    for (int n = 0; n <= steps + 1; ++n) {
      std::vector<double> d = denseAt(s, std::cos(n * step) * a + std::sin(n * step) * b);
      if (n >= 2) {
        double sum = 0.0;
        for (std::size_t k = 0; k < d.size(); ++k) sum += std::abs(d[k] - 2.0 * previous[k] + previous2[k]);
        largest = std::max(largest, sum);
      }
      previous2 = std::move(previous);
      previous = std::move(d);
    }
  }
  return largest;
}

// Great circles through every key (crossing the triangulation there) and random ones.
std::vector<Vector3d> pathNormals(const std::vector<Vector3d>& keys) {
  std::mt19937 rng(3);
  std::vector<Vector3d> normals;
  for (const Vector3d& key : keys) normals.push_back(key.normalized().cross(randomDirection(rng)).normalized());
  for (int i = 0; i < kPaths; ++i) normals.push_back(randomDirection(rng));
  return normals;
}

TEST(SmoothWeights, SmoothIsC1AlongPathsAndLinearHasKinks) {
  for (const char* name : {"octahedron", "tetrahedron", "twenty random keys", "keys in one hemisphere"}) {
    const auto keys = keySets()[name];
    const auto normals = pathNormals(keys);
    for (const WeightScheme scheme : {WeightScheme::Smooth, WeightScheme::Linear}) {
      const ViewSphere s = build(keys, Uncovered::Base, scheme);  // base mode covers the whole sphere
      const double coarse = largestSecondDifference(s, kPathStepRad, normals);
      const double fine = largestSecondDifference(s, kPathStepRad / 2, normals);
      ASSERT_GT(fine, 0.0);
      const double ratio = coarse / fine;
      if (scheme == WeightScheme::Smooth)
        EXPECT_GT(ratio, kC1Ratio) << name << ": second differences " << coarse << " -> " << fine;
      else
        EXPECT_LT(ratio, kKinkRatio) << name << ": second differences " << coarse << " -> " << fine;
    }
  }
}

// Sharpness (the paper's alpha) keeps its meaning in every scheme: on the octahedron's keys, the
// largest weight of a view grows with alpha and a huge alpha picks that key alone.
void expectSharpnessKeepsItsMeaning(const ViewSphere& s) {
  const Vector3d view(1, 0.6, 0.3);
  double previous = 0.0;
  for (const double alpha : {0.5, 1.0, 2.0, 4.0, 16.0}) {
    const double w = denseAt(s, view, alpha)[0];
    EXPECT_GT(w, previous) << "alpha " << alpha;
    previous = w;
  }
  EXPECT_NEAR(denseAt(s, view, 5000.0)[0], 1.0, kWeightTol) << "a huge alpha picks the largest weight";
}

TEST(SmoothWeights, SharpnessKeepsItsMeaning) {
  expectSharpnessKeepsItsMeaning(build(keySets()["octahedron"], Uncovered::Base, WeightScheme::Smooth));
}

// Along great circles through and across the hull (pathNormals), stepping kPathStepRad, the
// weights change by at most kLipschitz per radian: no jump where a view leaves the covered region.
void expectNoJumpsAlongPaths(const ViewSphere& s, const std::vector<Vector3d>& keys) {
  constexpr double kLipschitz = 60.0;
  for (const Vector3d& normal : pathNormals(keys)) {
    const Vector3d a = normal.unitOrthogonal(), b = normal.cross(a);
    std::vector<double> previous = denseAt(s, a);
    for (int n = 1; n * kPathStepRad < 2.0 * std::numbers::pi; ++n) {
      const std::vector<double> d = denseAt(s, std::cos(n * kPathStepRad) * a + std::sin(n * kPathStepRad) * b);
      double change = 0.0;
      for (std::size_t k = 0; k < d.size(); ++k) change += std::abs(d[k] - previous[k]);
      ASSERT_LT(change, kLipschitz * kPathStepRad) << "a jump at step " << n;
      previous = d;
    }
  }
}

// Cosine modes: the weights stay continuous where a view leaves the covered region (the falloff
// takes the smooth edge weights at the border); a path steps kPathStepRad at a time.
TEST(SmoothWeights, CosineModesAreContinuousAtTheBorder) {
  const auto keys = keySets()["keys in one hemisphere"];
  for (const Uncovered mode : {Uncovered::Cosine, Uncovered::Cosine2}) {
    const ViewSphere s = build(keys, mode, WeightScheme::Smooth);
    expectNoJumpsAlongPaths(s, keys);
  }
}

// The blended positions (a linear map of the weights) along paths: measureContinuity's velocity
// jumps shrink with the step for the smooth scheme and stay for the linear one.
TEST(SmoothWeights, BlendedPositionsHaveNoVelocityJumps) {
  RawViewDependentModel raw;
  raw.base = testing::uvSphere(12, 16);
  std::mt19937 rng(2);
  for (int k = 0; k < 8; ++k) {
    RawKey key;
    key.name = "k" + std::to_string(k);
    key.view = randomDirection(rng);
    key.mesh = raw.base;
    for (std::size_t v = 0; v < key.mesh.vertexCount(); ++v) {
      const Vector3d p(key.mesh.positions[3 * v], key.mesh.positions[3 * v + 1], key.mesh.positions[3 * v + 2]);
      const double s = std::max(0.0, p.dot(key.view) - 0.3);
      for (int c = 0; c < 3; ++c) key.mesh.positions[3 * v + c] += static_cast<float>(0.5 * s * key.view[c]);
    }
    raw.keys.push_back(std::move(key));
  }
  for (const WeightScheme scheme : {WeightScheme::Smooth, WeightScheme::Rbf, WeightScheme::Linear}) {
    raw.sphere.scheme = scheme;
    const ViewDependentModel model = ViewDependentModel::build(raw);
    ContinuitySettings settings;
    settings.circles = 8;
    settings.step_deg = 0.2;
    const ContinuityReport coarse = measureContinuity(model, settings);
    settings.step_deg = 0.1;
    const ContinuityReport fine = measureContinuity(model, settings);
    EXPECT_GT(coarse.popping, 0.0);
    const double ratio = coarse.velocity_jump / fine.velocity_jump;
    // velocity_jump is a second difference divided by the step: O(step) for C1, O(1) at kinks.
    if (scheme != WeightScheme::Linear)
      EXPECT_GT(ratio, kC1Ratio / 2) << weightSchemeName(scheme) << ": velocity jumps " << coarse.velocity_jump
                                     << " -> " << fine.velocity_jump;
    else
      EXPECT_LT(ratio, kKinkRatio / 2) << "velocity jumps " << coarse.velocity_jump << " -> " << fine.velocity_jump;
    EXPECT_GT(ratio, 0.8) << "a velocity jump that grows as the step shrinks is a jump in the positions";
  }
  ContinuitySettings bad;
  bad.step_deg = 0.0;
  EXPECT_THROW(measureContinuity(ViewDependentModel::build(raw), bad), Error);
}

// ---- The rbf scheme (view_sphere.h, "Weight schemes"): radial basis functions over every key.

ViewSphere buildRbf(const std::vector<Vector3d>& keys, Uncovered mode, RbfKernel kernel = RbfKernel::Gaussian,
                    double width_deg = 60.0) {
  return build(keys, mode, WeightScheme::Rbf, kernel, width_deg);
}

const RbfKernel kKernels[] = {RbfKernel::Gaussian, RbfKernel::InverseMultiquadric, RbfKernel::Wendland};

TEST(RbfWeights, EachKeyViewGivesThatKeyAlone) {
  for (const auto& [name, keys] : keySets())
    for (const Uncovered mode : kModes)
      for (const RbfKernel kernel : kKernels) {
        const ViewSphere s = buildRbf(keys, mode, kernel);
        for (std::size_t k = 0; k < keys.size(); ++k)
          for (const double alpha : {0.7, 1.0, 3.0}) {
            const auto d = denseAt(s, keys[k], alpha);
            for (std::size_t j = 0; j < d.size(); ++j)
              EXPECT_NEAR(d[j], j == k ? 1.0 : 0.0, kKeyTol)
                  << name << ", " << rbfKernelName(kernel) << ", key " << k << ", weight " << j;
          }
      }
}

// Every key moves the view (not only a triangle's three), and the weights still sum to 1 and are
// never negative (the interpolant's overshoot is cut by the C1 positive part).
TEST(RbfWeights, PartitionOfUnityNonNegativeAndGlobal) {
  std::mt19937 rng(6);
  for (const auto& [name, keys] : keySets())
    for (const Uncovered mode : kModes)
      for (const RbfKernel kernel : kKernels) {
        const ViewSphere s = buildRbf(keys, mode, kernel);
        std::size_t most_keys = 0;
        for (int n = 0; n < kRandomViews / 20; ++n) {
          const auto d = denseAt(s, randomDirection(rng));
          double sum = 0.0;
          std::size_t moving = 0;
          for (std::size_t j = 0; j < d.size(); ++j) {
            EXPECT_GE(d[j], 0.0) << name;
            sum += d[j];
            moving += j + 1 < d.size() && d[j] > 0.0;
          }
          most_keys = std::max(most_keys, moving);
          EXPECT_NEAR(sum, 1.0, kWeightTol) << name << ", " << rbfKernelName(kernel);
        }
        if (kernel == RbfKernel::Gaussian && keys.size() > 3) {
          EXPECT_GT(most_keys, 3u) << name << ": the rbf weights reach beyond a triangle";
        }
      }
}

TEST(RbfWeights, DenseQueryMatchesTheThreeSlotOneForTheOtherSchemes) {
  std::mt19937 rng(8);
  const auto keys = keySets()["keys in one hemisphere"];
  for (const WeightScheme scheme : {WeightScheme::Linear, WeightScheme::Smooth})
    for (const Uncovered mode : kModes) {
      const ViewSphere s = build(keys, mode, scheme);
      std::vector<float> dense(s.keyCount() + 1);
      for (int n = 0; n < 200; ++n) {
        const Vector3d v = randomDirection(rng);
        ASSERT_TRUE(s.denseWeights(v, 2.0, dense));
        const auto expected = denseAt(s, v, 2.0);
        for (std::size_t j = 0; j < dense.size(); ++j) EXPECT_EQ(dense[j], static_cast<float>(expected[j]));
      }
    }
}

TEST(RbfWeights, RbfIsC1AlongPaths) {
  for (const char* name : {"octahedron", "tetrahedron", "twenty random keys", "keys in one hemisphere"})
    for (const RbfKernel kernel : kKernels) {
      const auto keys = keySets()[name];
      const auto normals = pathNormals(keys);
      const ViewSphere s = buildRbf(keys, Uncovered::Base, kernel);  // base mode covers the whole sphere
      const double coarse = largestSecondDifference(s, kPathStepRad, normals);
      const double fine = largestSecondDifference(s, kPathStepRad / 2, normals);
      ASSERT_GT(fine, 0.0);
      EXPECT_GT(coarse / fine, kC1Ratio) << name << ", " << rbfKernelName(kernel) << ": second differences " << coarse
                                         << " -> " << fine;
    }
}

TEST(RbfWeights, SharpnessKeepsItsMeaning) {
  expectSharpnessKeepsItsMeaning(buildRbf(keySets()["octahedron"], Uncovered::Base));
}

// Cosine modes: a covered view gets the rbf weights, an uncovered one those at the nearest covered
// point times the paper's falloff; continuous at the border, and behind a single key the paper's
// max(0, cos) blend to the base.
TEST(RbfWeights, UncoveredModesKeepTheirMeaning) {
  const auto keys = keySets()["keys in one hemisphere"];
  for (const Uncovered mode : {Uncovered::Cosine, Uncovered::Cosine2}) {
    const ViewSphere s = buildRbf(keys, mode);
    expectNoJumpsAlongPaths(s, keys);
    EXPECT_NEAR(denseAt(s, Vector3d(0, -1, 0)).back(), 1.0, kWeightTol) << "far below the keys: the base";
  }
  const ViewSphere one = buildRbf({Vector3d(0, 0, 1)}, Uncovered::Cosine);
  const Vector3d view(0, std::sin(0.7), std::cos(0.7));
  EXPECT_NEAR(denseAt(one, view)[0], std::cos(0.7), kWeightTol) << "the paper's single-key falloff";
  const ViewSphere based = buildRbf(keySets()["keys in one hemisphere"], Uncovered::Base);
  ASSERT_GT(based.points().size(), based.keyCount()) << "dummy base points below the keys";
  for (std::size_t p = based.keyCount(); p < based.points().size(); ++p)
    EXPECT_NEAR(denseAt(based, based.points()[p]).back(), 1.0, kKeyTol) << "at a dummy base point: the base";
  EXPECT_GT(denseAt(based, Vector3d(0, -1, 0)).back(), 0.99) << "far below the keys: nearly the base";
}

// Figure 13's head (four keys, cosine falloff): a view level with three of the keys, just below
// them, falls off towards the nearest key as in the other schemes (a view exactly on the keys'
// great circle once lost its nearest point).
TEST(RbfWeights, FalloffAtTheBorderOfTheKeysGreatCircle) {
  const std::vector<Vector3d> keys = {Vector3d(0, 0, 1), Vector3d(-1, 0, 0), Vector3d(1, 0, 0), Vector3d(0, 1, 0)};
  const ViewSphere rbf = buildRbf(keys, Uncovered::Cosine);
  const ViewSphere linear = build(keys, Uncovered::Cosine, WeightScheme::Linear);
  for (const double z : {0.0, 1e-3, -1e-3}) {
    const Vector3d view(0.9943572200697444, -0.1060835467693743, z);
    const auto r = denseAt(rbf, view), l = denseAt(linear, view);
    EXPECT_NEAR(r.back(), l.back(), kWeightTol) << "z " << z << ": the same falloff in both schemes";
    EXPECT_GT(r[2], 0.99) << "z " << z << ": the nearest key, 'right'";
  }
}

TEST(RbfWeights, SettingsAndIllConditionedKeysAreRefusedInOneLine) {
  const auto keys = keySets()["octahedron"];
  for (const double width : {0.0, -5.0, 181.0, std::nan("")}) {
    try {
      (void)buildRbf(keys, Uncovered::Base, RbfKernel::Gaussian, width);
      ADD_FAILURE() << "width " << width << " accepted";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("width"), std::string::npos) << e.what();
    }
  }
  // Two keys 0.0002 degree apart cannot be told apart by a 60-degree Gaussian.
  std::vector<Vector3d> close = keys;
  close.push_back(fromAngles(0.0002, 0.0));
  const std::vector<std::string> labels = {"a", "b", "c", "d", "front", "f", "nearly front"};
  ViewSphereSettings settings;
  settings.scheme = WeightScheme::Rbf;
  try {
    (void)ViewSphere::build(close, settings, labels);
    ADD_FAILURE() << "an ill-conditioned rbf system accepted";
  } catch (const Error& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("ill-conditioned"), std::string::npos) << m;
    EXPECT_NE(m.find("nearly front"), std::string::npos) << m;
    EXPECT_EQ(m.find('\n'), std::string::npos) << m;
  }
  settings.rbf_width_deg = 0.001;  // a narrow kernel tells them apart
  EXPECT_NO_THROW((void)ViewSphere::build(close, settings, labels));
  // The three-slot queries refuse an rbf sphere (its weights are over every key).
  const ViewSphere s = buildRbf(keys, Uncovered::Base);
  ViewWeights w;
  EXPECT_FALSE(s.weights(Vector3d(1, 0, 0), 1.0, w));
  EXPECT_FALSE(s.weightsByScan(Vector3d(1, 0, 0), 1.0, w));
  std::vector<float> wrong(s.keyCount());
  EXPECT_FALSE(s.denseWeights(Vector3d(1, 0, 0), 1.0, wrong));
  std::vector<float> right(s.keyCount() + 1);
  EXPECT_FALSE(s.denseWeights(Vector3d(0, 0, 0), 1.0, right));
  EXPECT_FALSE(s.denseWeights(Vector3d(1, 0, 0), -1.0, right));
}

}  // namespace
}  // namespace vdg
