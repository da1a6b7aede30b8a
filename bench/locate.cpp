// Locate + weigh one view: ViewSphere::weights (hint walk + cube-map grid) in ns per query, and
// its ratio to the plain scan ViewSphere::weightsByScan measured in the same run (x_scan < 1 is
// faster). Goals: <= 50 ns on a coherent camera path (with the hint), <= 150 ns for
// random views (no hint), with 6 and with 200 keys, Base and Cosine modes, sharpness 1 and 2.
// Scheme/...: the smooth and rbf weight schemes' cost per query as a multiple of the linear one's.
// Positions/...: keys at distances (KeySpace::weights, an eye position) as a multiple of the linear
// direction sphere's query of the same key directions ("Keys at distances", docs/weights.md): eyes inside
// the keys' hull (an orbit at radius 7, hinted), outside it (an orbit at radius 20: the nearest hull
// face search) and random eyes in a box of side 30 (no hint).
//
// Key sets: "octahedron" (6 keys around the object, as bench/blend), "half6" (6 keys of a
// character: front, back, sides, top, three-quarter above; the lower half is uncovered),
// "sphere200" (200 random keys over the whole sphere), "half200" (200 random keys on the upper
// half sphere). Views are precomputed so that only the query is timed: a closed orbit sampled every
// ~0.01 rad (the hint carried from frame to frame) or 4096 random directions (no hint). The scan
// ratio (thread CPU time of both, timed back to back) compares like with like: the path against the scan given the same
// hint (the algorithm weights() used before the grid), random views against the scan without one.
#include <benchmark/benchmark.h>

#include <Eigen/Core>
#include <cmath>
#include <cstdlib>
#include <ctime>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "vdg/viewdep/key_space.h"
#include "vdg/viewdep/view_sphere.h"

namespace {

using Eigen::Vector3d;

Vector3d fromAngles(double azimuth_deg, double elevation_deg) {
  const double a = azimuth_deg * std::numbers::pi / 180.0, e = elevation_deg * std::numbers::pi / 180.0;
  return {std::cos(e) * std::sin(a), std::sin(e), std::cos(e) * std::cos(a)};
}

std::vector<Vector3d> randomDirections(int n, unsigned seed, bool upper_half) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> g;
  std::vector<Vector3d> dirs;
  while (static_cast<int>(dirs.size()) < n) {
    Vector3d v(g(rng), g(rng), g(rng));
    if (v.norm() < 1e-6) continue;
    if (upper_half) v.y() = std::abs(v.y());
    dirs.push_back(v.normalized());
  }
  return dirs;
}

std::vector<Vector3d> keySet(const std::string& name) {
  if (name == "octahedron") return {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  if (name == "half6")
    return {fromAngles(0, 0),   fromAngles(90, 0), fromAngles(180, 0),
            fromAngles(270, 0), fromAngles(0, 89), fromAngles(45, 40)};
  if (name == "sphere200") return randomDirections(200, 12, false);
  return randomDirections(200, 13, true);  // half200
}

// A closed orbit slightly above the horizon (as bench/blend's camera), ~0.01 rad per frame.
const std::vector<Vector3d>& pathViews() {
  static const std::vector<Vector3d> views = [] {
    constexpr int kFrames = 628;  // one turn, step 2 pi / 628 ~ 0.01 rad
    std::vector<Vector3d> v;
    for (int i = 0; i < kFrames; ++i) {
      const double t = 2.0 * std::numbers::pi * i / kFrames;
      v.emplace_back(std::sin(t), 0.4, std::cos(t));
    }
    return v;
  }();
  return views;
}

const std::vector<Vector3d>& randomViews() {
  static const std::vector<Vector3d> views = randomDirections(4096, 99, false);
  return views;
}

// Thread CPU seconds (the machine is shared: wall time also counts other people's work).
double threadSeconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

// CPU seconds per query of `query(view, hint)` over `queries` queries cycling through `views`.
template <typename Query>
double secondsPerQuery(const std::vector<Vector3d>& views, long queries, bool hinted, Query query) {
  int hint = -1;
  std::size_t i = 0;
  const double t0 = threadSeconds();
  for (long q = 0; q < queries; ++q) {
    benchmark::DoNotOptimize(query(views[i], hinted ? &hint : nullptr));
    if (++i == views.size()) i = 0;
  }
  return (threadSeconds() - t0) / static_cast<double>(queries);
}

void locateBenchmark(benchmark::State& state, const std::string& keys, vdg::Uncovered mode, bool path,
                     double sharpness) {
  const vdg::ViewSphere sphere = vdg::ViewSphere::build(keySet(keys), {mode});
  const std::vector<Vector3d>& views = path ? pathViews() : randomViews();
  int hint = -1;
  int* hint_ptr = path ? &hint : nullptr;
  std::size_t i = 0;
  vdg::ViewWeights w;
  for (auto _ : state) {
    if (!sphere.weights(views[i], sharpness, w, hint_ptr)) {
      state.SkipWithError("weights refused its input (internal error)");
      break;
    }
    benchmark::DoNotOptimize(w);
    if (++i == views.size()) i = 0;
  }
  // The same queries through the fast path and the scan, timed back to back in this run.
  const long queries = path ? 400'000 : std::max(20'000L, 4'000'000L / static_cast<long>(sphere.triangles().size()));
  auto fast = [&](const Vector3d& v, int* h) {
    vdg::ViewWeights r;
    return sphere.weights(v, sharpness, r, h) ? r.base : -1.0f;
  };
  auto scan = [&](const Vector3d& v, int* h) {
    vdg::ViewWeights r;
    return sphere.weightsByScan(v, sharpness, r, h) ? r.base : -1.0f;
  };
  const double fast_s = secondsPerQuery(views, queries, path, fast);
  const double scan_s = secondsPerQuery(views, queries, path, scan);
  state.counters["triangles"] = static_cast<double>(sphere.triangles().size());
  state.counters["grid"] = sphere.gridSize();
  state.counters["fast_cpu_ns"] = fast_s * 1e9;
  state.counters["scan_cpu_ns"] = scan_s * 1e9;
  state.counters["x_scan"] = fast_s / scan_s;  // the figure to watch with ns per query
}

// The smooth and rbf weight schemes (docs/weights.md) against the linear one on the same
// views, timed back to back in this run: x_linear is the scheme's query cost as a multiple of the
// linear one's. The rbf scheme's query is denseWeights() (every key); sphere200 gets a Wendland
// kernel of width 30 degrees (a 60-degree Gaussian cannot tell 200 random keys apart: refused).
vdg::ViewSphereSettings benchSchemeSettings(const std::string& keys, vdg::WeightScheme scheme) {
  vdg::ViewSphereSettings settings;
  settings.scheme = scheme;
  if (scheme == vdg::WeightScheme::Rbf && keys == "sphere200") {
    settings.rbf_kernel = vdg::RbfKernel::Wendland;
    settings.rbf_width_deg = 30.0;
  }
  return settings;
}

void schemeBenchmark(benchmark::State& state, const std::string& keys, bool path, vdg::WeightScheme scheme) {
  const vdg::ViewSphere linear = vdg::ViewSphere::build(keySet(keys), vdg::ViewSphereSettings{});
  const vdg::ViewSphere other = vdg::ViewSphere::build(keySet(keys), benchSchemeSettings(keys, scheme));
  const std::vector<Vector3d>& views = path ? pathViews() : randomViews();
  std::vector<float> dense(other.keyCount() + 1);
  auto query = [&dense](const vdg::ViewSphere& sphere) {
    return [&sphere, &dense](const Vector3d& v, int* h) {
      if (sphere.settings().scheme == vdg::WeightScheme::Rbf)
        return sphere.denseWeights(v, 1.0, dense, h) ? dense.back() : -1.0f;
      vdg::ViewWeights r;
      return sphere.weights(v, 1.0, r, h) ? r.base : -1.0f;
    };
  };
  int hint = -1;
  std::size_t i = 0;
  const auto timed = query(other);
  for (auto _ : state) {
    const float base = timed(views[i], path ? &hint : nullptr);
    if (base < 0.0f) {
      state.SkipWithError("weights refused its input (internal error)");
      break;
    }
    benchmark::DoNotOptimize(base);
    if (++i == views.size()) i = 0;
  }
  constexpr long kQueries = 400'000;
  const double linear_s = secondsPerQuery(views, kQueries, path, query(linear));
  const double other_s = secondsPerQuery(views, kQueries, path, query(other));
  state.counters["linear_cpu_ns"] = linear_s * 1e9;
  state.counters[std::string(vdg::weightSchemeName(scheme)) + "_cpu_ns"] = other_s * 1e9;
  state.counters["x_linear"] = other_s / linear_s;
}

// Key eyes: each direction of `keys` at distance 10, and every fourth also at distance 4 (a
// close-up from the same direction).
std::vector<Vector3d> dollyEyes(const std::string& keys) {
  std::vector<Vector3d> eyes;
  const std::vector<Vector3d> dirs = keySet(keys);
  for (const Vector3d& d : dirs) eyes.push_back(10.0 * d.normalized());
  for (std::size_t i = 0; i < dirs.size(); i += 4) eyes.push_back(4.0 * dirs[i].normalized());
  return eyes;
}

std::vector<Vector3d> eyePath(const std::string& where) {
  if (where == "random") {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-15.0, 15.0);
    std::vector<Vector3d> v;
    for (int i = 0; i < 4096; ++i) v.emplace_back(u(rng), u(rng), u(rng));
    return v;
  }
  const double radius = where == "inside" ? 7.0 : 20.0;
  std::vector<Vector3d> v;
  for (const Vector3d& d : pathViews()) v.push_back(radius * d.normalized());
  return v;
}

void positionsBenchmark(benchmark::State& state, const std::string& keys, const std::string& where) {
  const std::vector<Vector3d> eyes = dollyEyes(keys);
  const std::vector<std::string> labels(eyes.size(), "key");
  const vdg::KeySpace space = vdg::KeySpace::build(eyes, Vector3d::Zero(), {}, 0.0, labels);
  const vdg::ViewSphere linear = vdg::ViewSphere::build(keySet(keys), vdg::ViewSphereSettings{});
  const std::vector<Vector3d> views = eyePath(where);
  const bool hinted = where != "random";
  std::vector<float> dense(space.keyCount() + 1);
  const auto positions = [&](const Vector3d& eye, int* h) {
    return space.weights(eye, 1.0, dense, h) ? dense.back() : -1.0f;
  };
  int hint = -1;
  std::size_t i = 0;
  for (auto _ : state) {
    const float base = positions(views[i], hinted ? &hint : nullptr);
    if (base < 0.0f) {
      state.SkipWithError("weights refused its input (internal error)");
      break;
    }
    benchmark::DoNotOptimize(base);
    if (++i == views.size()) i = 0;
  }
  constexpr long kQueries = 200'000;
  const double linear_s = secondsPerQuery(views, kQueries, hinted, [&](const Vector3d& v, int* h) {
    vdg::ViewWeights r;
    return linear.weights(v, 1.0, r, h) ? r.base : -1.0f;
  });
  const double positions_s = secondsPerQuery(views, kQueries, hinted, positions);
  state.counters["keys"] = static_cast<double>(eyes.size());
  state.counters["hull_faces"] = static_cast<double>(space.hullFaceCount());
  state.counters["linear_cpu_ns"] = linear_s * 1e9;
  state.counters["positions_cpu_ns"] = positions_s * 1e9;
  state.counters["x_linear"] = positions_s / linear_s;
}

}  // namespace

int main(int argc, char** argv) {
  double load[3] = {0, 0, 0};
  if (getloadavg(load, 3) == 3)
    benchmark::AddCustomContext(
        "load_average", std::to_string(load[0]) + " " + std::to_string(load[1]) + " " + std::to_string(load[2]));
  for (const bool path : {true, false})
    for (const char* keys : {"octahedron", "half6", "sphere200", "half200"})
      for (const vdg::Uncovered mode : {vdg::Uncovered::Base, vdg::Uncovered::Cosine})
        for (const double sharpness : {1.0, 2.0}) {
          const std::string name = std::string("Locate/") + (path ? "path" : "random") + "/" + keys + "/" +
                                   vdg::uncoveredName(mode) + "/alpha" + std::to_string(static_cast<int>(sharpness));
          benchmark::RegisterBenchmark(
              name.c_str(), [=](benchmark::State& state) { locateBenchmark(state, keys, mode, path, sharpness); });
        }
  for (const bool path : {true, false})
    for (const char* keys : {"octahedron", "sphere200"})
      for (const vdg::WeightScheme scheme : {vdg::WeightScheme::Smooth, vdg::WeightScheme::Rbf}) {
        const std::string name =
            std::string("Scheme/") + (path ? "path" : "random") + "/" + keys + "/" + vdg::weightSchemeName(scheme);
        benchmark::RegisterBenchmark(name.c_str(),
                                     [=](benchmark::State& state) { schemeBenchmark(state, keys, path, scheme); });
      }
  for (const char* keys : {"octahedron", "sphere200"})
    for (const char* where : {"inside", "outside", "random"}) {
      const std::string name = std::string("Positions/") + where + "/" + keys;
      benchmark::RegisterBenchmark(name.c_str(),
                                   [=](benchmark::State& state) { positionsBenchmark(state, keys, where); });
    }
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
