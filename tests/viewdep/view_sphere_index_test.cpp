// ViewSphere::weights (hint walk + cube-map grid, view_sphere.h "Locating a view") against its
// oracle ViewSphere::weightsByScan, which tests every hull triangle: about a million random views
// and camera-path views over key sets of 1 to 300 keys, in every Uncovered mode, including the
// degenerate sets (1, 2, 3 keys, coplanar keys, keys on a small circle, keys on a half sphere).
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "support/dense_weights.h"
#include "support/random_direction.h"
#include "vdg/viewdep/view_sphere.h"

namespace vdg {
namespace {

using Eigen::Vector3d;

// Weights are floats computed from the same doubles; the fast path may sharpen integer alphas by
// multiplication instead of std::pow (a double rounding apart) and, on an edge tie, use the other
// triangle (whose weights agree up to the inside tolerance of the cone test, 1e-9).
constexpr double kFloatRoundingTol = 2e-6;
// Two different triangles are both valid only when the view lies on their shared edge: both
// triangles' cone coordinates must then be at least -kEdgeTieTol (the sphere counts -1e-9 as in).
constexpr double kEdgeTieTol = 1e-8;
// Ties are views exactly on an edge: a random view almost never is. Path views that start on a key
// or cross a vertex can be; allow a small share, not a systematic difference.
constexpr double kMaxTieShare = 1e-3;
// About a million views in all (random + path), spread over the key sets below, in optimised
// builds; a tenth in Debug and sanitizer builds (NDEBUG unset), where the O(triangles) oracle is
// some 50 times slower (a million views would take minutes there).
// Debug builds also build fewer large spheres (building the grid dominates there).
#ifdef NDEBUG
constexpr int kTotalViews = 1'000'000;
const std::vector<int> kLargeKeyCounts = {47, 64, 80, 100, 128, 150, 200, 256, 300};
constexpr int kAllShapesUpTo = 12;
#else
constexpr int kTotalViews = 100'000;
const std::vector<int> kLargeKeyCounts = {64, 300};
constexpr int kAllShapesUpTo = 6;
#endif
// Camera path: a great circle sampled every kPathStepRad (a camera orbiting at 60 frames/s).
constexpr double kPathStepRad = 0.01;

const std::vector<Uncovered> kModes = {Uncovered::Base, Uncovered::Cosine, Uncovered::Cosine2};

using testing::randomDirection;

Vector3d fromAngles(double azimuth_rad, double elevation_rad) {
  return {std::cos(elevation_rad) * std::sin(azimuth_rad), std::sin(elevation_rad),
          std::cos(elevation_rad) * std::cos(azimuth_rad)};
}

struct KeySet {
  std::string name;
  std::vector<Vector3d> keys;
};

// Key sets of n keys, several shapes per n. Keys are kept at least ~1e-3 rad apart (the sphere
// rejects coinciding keys; a random set of 300 is far from that).
std::vector<KeySet> keySetsOf(int n, std::mt19937& rng) {
  std::vector<KeySet> sets;
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  KeySet random{"random on the sphere", {}};
  for (int i = 0; i < n; ++i) random.keys.push_back(randomDirection(rng));
  sets.push_back(random);
  KeySet half{"random on a half sphere", {}};
  for (int i = 0; i < n; ++i) {
    Vector3d v = randomDirection(rng);
    if (v.y() < 0) v.y() = -v.y();
    half.keys.push_back(v);
  }
  sets.push_back(half);
  // A ring around the horizon and a few above: a character's typical keys (half sphere).
  KeySet ring{"ring and crown", {}};
  const int ring_count = std::max(1, (2 * n + 2) / 3);
  for (int i = 0; i < ring_count; ++i) ring.keys.push_back(fromAngles(2 * std::numbers::pi * i / ring_count, 0.0));
  for (int i = ring_count; i < n; ++i)
    ring.keys.push_back(fromAngles(2 * std::numbers::pi * unit(rng), 0.2 + 1.2 * unit(rng)));
  sets.push_back(ring);
  if (n >= 3) {
    KeySet great{"coplanar on a great circle", {}};
    const Vector3d axis = randomDirection(rng);
    const Vector3d u = axis.unitOrthogonal(), w = axis.cross(u);
    for (int i = 0; i < n; ++i) {
      const double a = 2 * std::numbers::pi * (i + 0.3 * unit(rng)) / n;
      great.keys.push_back(std::cos(a) * u + std::sin(a) * w);
    }
    sets.push_back(great);
    KeySet arc{"coplanar on a third of a great circle", {}};
    for (int i = 0; i < n; ++i) arc.keys.push_back(std::cos(2.0 * i / n) * u + std::sin(2.0 * i / n) * w);
    sets.push_back(arc);
    KeySet small{"on a small circle", {}};
    for (int i = 0; i < n; ++i) {
      const double a = 2 * std::numbers::pi * (i + 0.3 * unit(rng)) / n;
      small.keys.push_back((0.6 * axis + 0.8 * (std::cos(a) * u + std::sin(a) * w)).normalized());
    }
    sets.push_back(small);
  }
  if (n >= 2) {
    KeySet cluster{"clustered within 20 degrees", {}};
    const Vector3d centre = randomDirection(rng);
    for (int i = 0; i < n; ++i) cluster.keys.push_back((centre + 0.35 * randomDirection(rng)).normalized());
    sets.push_back(cluster);
  }
  return sets;
}

// Cone coordinates of v in triangle t (non-negative inside), as ViewSphere defines them.
double insideness(const ViewSphere& s, int t, const Vector3d& v) {
  const auto& tri = s.triangles()[static_cast<std::size_t>(t)];
  Eigen::Matrix3d m;
  m << s.points()[tri[0]], s.points()[tri[1]], s.points()[tri[2]];
  return (m.inverse() * v).minCoeff();
}

using testing::denseWeights;

struct Tally {
  long views = 0;
  long ties = 0;
};

// One comparison; a failure message names the set, mode, sharpness and view.
void expectSame(const ViewSphere& s, const Vector3d& v, const ViewWeights& fast, const ViewWeights& oracle,
                const std::string& where, Tally& tally) {
  ++tally.views;
  const std::vector<double> a = denseWeights(s, fast), b = denseWeights(s, oracle);
  double worst = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) worst = std::max(worst, std::abs(a[i] - b[i]));
  ASSERT_LE(worst, kFloatRoundingTol) << where << ", view " << v.transpose() << ": triangle " << fast.triangle
                                      << " vs the scan's " << oracle.triangle;
  if (fast.triangle == oracle.triangle) return;
  ++tally.ties;
  if (fast.triangle >= 0) {
    ASSERT_GE(insideness(s, fast.triangle, v), -kEdgeTieTol)
        << where << ", view " << v.transpose() << ": triangle " << fast.triangle << " does not contain the view";
  }
  if (oracle.triangle >= 0) {
    ASSERT_GE(insideness(s, oracle.triangle, v), -kEdgeTieTol)
        << where << ", view " << v.transpose() << ": the scan's triangle " << oracle.triangle
        << " does not contain the view (oracle broken)";
  }
}

void compareOn(const ViewSphere& s, const std::string& where, int views, std::mt19937& rng, Tally& tally) {
  const int random_views = views / 2;
  for (int i = 0; i < random_views; ++i) {
    const Vector3d v = randomDirection(rng);
    const double alpha = i % 3 == 0 ? 1.0 : i % 3 == 1 ? 2.0 : 1.7;
    ViewWeights fast, oracle;
    ASSERT_TRUE(s.weights(v, alpha, fast));
    ASSERT_TRUE(s.weightsByScan(v, alpha, oracle));
    expectSame(s, v, fast, oracle, where + ", random, alpha " + std::to_string(alpha), tally);
    if (::testing::Test::HasFatalFailure()) return;
  }
  // Camera paths: great circles through random points, with the hint carried from frame to frame.
  int hint = -1;
  Vector3d a = randomDirection(rng), b = randomDirection(rng);
  b = (b - b.dot(a) * a).normalized();
  for (int i = 0; i < views - random_views; ++i) {
    if (i % 700 == 0) {  // a new path now and then (the hint stays: a cut in the film)
      a = randomDirection(rng);
      b = randomDirection(rng);
      b = (b - b.dot(a) * a).normalized();
    }
    const double t = kPathStepRad * (i % 700);
    const Vector3d v = std::cos(t) * a + std::sin(t) * b;
    const double alpha = (i / 700) % 2 == 0 ? 2.0 : 1.0;
    ViewWeights fast, oracle;
    const int before = hint;
    ASSERT_TRUE(s.weights(v, alpha, fast, &hint));
    ASSERT_TRUE(s.weightsByScan(v, alpha, oracle));
    expectSame(s, v, fast, oracle, where + ", path, alpha " + std::to_string(alpha), tally);
    if (::testing::Test::HasFatalFailure()) return;
    // The hint follows the triangle found and stays as it was for an uncovered view.
    ASSERT_EQ(hint, fast.triangle >= 0 ? fast.triangle : before) << where;
  }
}

TEST(ViewSphereIndex, WeightsEqualTheScanFromOneTo300Keys) {
  std::vector<int> counts;
  for (int n = 1; n <= 40; ++n) counts.push_back(n);
  for (int n : kLargeKeyCounts) counts.push_back(n);
  std::mt19937 rng(1201);
  struct Case {
    std::string name;
    ViewSphere sphere;
  };
  std::vector<Case> cases;
  for (int n : counts) {
    const std::vector<KeySet> sets = keySetsOf(n, rng);
    // Every shape for the small sets; one shape per count (in turn) for the large ones.
    for (std::size_t i = 0; i < sets.size(); ++i) {
      if (n > kAllShapesUpTo && i != static_cast<std::size_t>(n) % sets.size()) continue;
      for (Uncovered mode : kModes)
        cases.push_back({std::to_string(n) + " keys, " + sets[i].name + ", " + uncoveredName(mode),
                         ViewSphere::build(sets[i].keys, {mode})});
    }
  }
  // Fixed degenerate and regular sets.
  const std::vector<KeySet> fixed = {
      {"one key", {Vector3d(0, 0, 1)}},
      {"two keys", {Vector3d(0, 0, 1), Vector3d(1, 0, 0.2)}},
      {"two antipodal keys", {Vector3d(0, 0, 1), Vector3d(0, 0, -1)}},
      {"three keys", {Vector3d(0, 0, 1), Vector3d(1, 0, 0), Vector3d(0, 1, 0)}},
      {"three keys on a great circle", {fromAngles(-1, 0), fromAngles(0, 0), fromAngles(1.2, 0)}},
      {"octahedron",
       {Vector3d(1, 0, 0), Vector3d(-1, 0, 0), Vector3d(0, 1, 0), Vector3d(0, -1, 0), Vector3d(0, 0, 1),
        Vector3d(0, 0, -1)}},
  };
  for (const KeySet& set : fixed)
    for (Uncovered mode : kModes)
      cases.push_back({set.name + ", " + uncoveredName(mode), ViewSphere::build(set.keys, {mode})});

  const int per_case = kTotalViews / static_cast<int>(cases.size());
  Tally tally;
  for (const Case& c : cases) {
    compareOn(c.sphere, c.name, per_case, rng, tally);
    if (HasFatalFailure()) return;
  }
  EXPECT_GE(tally.views, kTotalViews * 99L / 100);
  EXPECT_LE(static_cast<double>(tally.ties), kMaxTieShare * static_cast<double>(tally.views))
      << tally.ties << " of " << tally.views << " views report another triangle than the scan";
}

// Views exactly on keys, on edges and at their midpoints: the ties the random views never hit.
TEST(ViewSphereIndex, ViewsOnKeysAndEdgesAreTiesAtMost) {
  std::mt19937 rng(77);
  Tally tally;
  for (int n : {4, 6, 20, 200}) {
    for (Uncovered mode : kModes) {
      std::vector<Vector3d> keys;
      for (int i = 0; i < n; ++i) keys.push_back(randomDirection(rng));
      const ViewSphere s = ViewSphere::build(keys, {mode});
      std::vector<Vector3d> views(s.points().begin(), s.points().end());
      for (const auto& t : s.triangles())
        for (int k = 0; k < 3; ++k) views.push_back((s.points()[t[k]] + s.points()[t[(k + 1) % 3]]).normalized());
      for (const Vector3d& v : views) {
        for (double alpha : {1.0, 2.0}) {
          ViewWeights fast, oracle;
          ASSERT_TRUE(s.weights(v, alpha, fast));
          ASSERT_TRUE(s.weightsByScan(v, alpha, oracle));
          expectSame(s, v, fast, oracle, std::to_string(n) + " keys, " + uncoveredName(mode), tally);
          if (HasFatalFailure()) return;
          const int triangles = static_cast<int>(s.triangles().size());
          for (int start = 0; start < triangles; start += std::max(1, triangles / 8)) {
            int hint = start;
            ASSERT_TRUE(s.weights(v, alpha, fast, &hint));
            expectSame(s, v, fast, oracle, std::to_string(n) + " keys, hinted", tally);
            if (HasFatalFailure()) return;
          }
        }
      }
    }
  }
  EXPECT_GT(tally.views, 0);
}

// The grid sizes itself to the triangles (about four cells per triangle), within its bounds.
TEST(ViewSphereIndex, GridGrowsWithTheKeys) {
  std::mt19937 rng(5);
  std::vector<Vector3d> keys;
  for (int i = 0; i < 200; ++i) keys.push_back(randomDirection(rng));
  const ViewSphere big = ViewSphere::build(keys);
  const ViewSphere one = ViewSphere::build(std::vector<Vector3d>{Vector3d(0, 0, 1)}, {Uncovered::Cosine});
  EXPECT_EQ(one.gridSize(), ViewSphere::kMinGridSize);
  EXPECT_GT(big.gridSize(), 10);
  EXPECT_LE(big.gridSize(), ViewSphere::kMaxGridSize);
  const double cells = 6.0 * big.gridSize() * big.gridSize();
  EXPECT_GE(cells, 3.0 * static_cast<double>(big.triangles().size()));
}

// Sentinel output: anything weightsByScan writes on a refused query shows.
ViewWeights sentinel() {
  ViewWeights w;
  w.key = {7, 8, 9};
  w.weight = {0.25f, 0.5f, 0.125f};
  w.base = 0.0625f;
  w.triangle = 3;
  return w;
}

void expectUntouched(const ViewWeights& w) {
  const ViewWeights s = sentinel();
  EXPECT_EQ(w.key, s.key);
  EXPECT_EQ(w.weight, s.weight);
  EXPECT_EQ(w.base, s.base);
  EXPECT_EQ(w.triangle, s.triangle);
}

// weightsByScan keeps the per-frame contract of weights(): refused inputs write nothing.
TEST(ViewSphereIndex, ScanRefusesWhatWeightsRefuses) {
  const ViewSphere s = ViewSphere::build(std::vector<Vector3d>{Vector3d(1, 0, 0), Vector3d(-1, 0, 0), Vector3d(0, 1, 0),
                                                               Vector3d(0, -1, 0), Vector3d(0, 0, 1)});
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  for (const Vector3d& view : {Vector3d::Zero().eval(), Vector3d(nan, 0, 1), Vector3d(inf, 0, 0)}) {
    ViewWeights w = sentinel();
    int hint = 1;
    EXPECT_FALSE(s.weightsByScan(view, 1.0, w, &hint)) << view.transpose();
    expectUntouched(w);
    EXPECT_EQ(hint, 1);
  }
  for (double sharpness : {0.0, -1.0, nan, inf}) {
    ViewWeights w = sentinel();
    EXPECT_FALSE(s.weightsByScan(Vector3d(0.3, 0.2, 1), sharpness, w)) << sharpness;
    expectUntouched(w);
  }
  for (int bad : {-2, static_cast<int>(s.triangles().size()), 1 << 30}) {
    ViewWeights w = sentinel();
    int hint = bad;
    EXPECT_FALSE(s.weightsByScan(Vector3d(0.3, 0.2, 1), 1.0, w, &hint)) << bad;
    expectUntouched(w);
    EXPECT_EQ(hint, bad);
  }
  ViewWeights w = sentinel();
  int hint = -1;
  EXPECT_TRUE(s.weightsByScan(Vector3d(1e-200, 2e-200, 3e-200), 1.0, w, &hint));
  EXPECT_GE(hint, 0);
}

}  // namespace
}  // namespace vdg
