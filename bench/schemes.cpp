// One evaluation of a real model (Spot, examples/spot) under each weight setting of
// docs/weights.md: the linear scheme (the paper's), smooth, rbf, per-part key sets (the cubist
// Spot) and keys at distances (the dolly Spot). Each iteration evaluates the model at one view of
// a turntable (positions and normals, single-threaded, with the hint), the linear model at the
// same view, and copies the base's positions and normals, back to back. Counters:
//   us_per_evaluation   the model's evaluation, microseconds
//   ratio_to_linear     its time / the linear model's at the same views (the figure to watch)
//   ratio_to_copy       its time / the copy of the base (the floor)
// Run from the repository root, or set VDG_SOURCE_DIR.
#include <benchmark/benchmark.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <numbers>
#include <string>
#include <vector>

#include "vdg/io/manifest.h"
#include "vdg/viewdep/model.h"

namespace {

std::string spotDir() {
  const char* src = std::getenv("VDG_SOURCE_DIR");
  return std::string(src ? src : ".") + "/examples/spot/";
}

vdg::ViewDependentModel load(const char* manifest) {
  return vdg::ViewDependentModel::build(vdg::loadManifest(spotDir() + manifest));
}

constexpr int kTurntableViews = 64;

// View i of a turntable 20 degrees above the model; `distance` places the eye for keys at distances.
Eigen::Vector3d turntableEye(const vdg::ViewDependentModel& m, int i, double distance) {
  const double a = 2.0 * std::numbers::pi * (i % kTurntableViews) / kTurntableViews;
  const double e = 20.0 * std::numbers::pi / 180.0;
  return m.center() + distance * Eigen::Vector3d(std::cos(e) * std::sin(a), std::sin(e), -std::cos(e) * std::cos(a));
}

void BM_SpotEvaluation(benchmark::State& state, const char* manifest) {
  static const vdg::ViewDependentModel linear = load("spot.vdg.json");
  const vdg::ViewDependentModel model = load(manifest);
  const std::size_t n = model.base().positions.size();
  std::vector<float> positions(n), normals(n), copy_p(n), copy_n(n), base_normals(n);
  if (!vdg::computeVertexNormals(model.surface(), model.base().positions, base_normals)) {
    state.SkipWithError("computeVertexNormals refused the base (internal error)");
    return;
  }
  const bool at_eye = model.weightSpace() == vdg::WeightSpace::Positions;
  using Clock = std::chrono::steady_clock;
  double model_s = 0.0, linear_s = 0.0, copy_s = 0.0;
  int i = 0, hint = -1, linear_hint = -1;
  bool ok = true;
  for (auto _ : state) {
    // The dolly's keys sit 1.6 to 4 units from the centre: an orbit at 3 crosses its hull.
    const Eigen::Vector3d eye = turntableEye(model, i++, 3.0);
    const Eigen::Vector3d view = (eye - model.center()).normalized();
    const auto t0 = Clock::now();
    ok &= at_eye ? model.evaluateAtEye(eye, 0.0, positions, normals, &hint)
                 : model.evaluate(view, 0.0, positions, normals, &hint);
    benchmark::DoNotOptimize(positions.data());
    const auto t1 = Clock::now();
    ok &= linear.evaluate(view, 0.0, positions, normals, &linear_hint);
    benchmark::DoNotOptimize(positions.data());
    const auto t2 = Clock::now();
    std::memcpy(copy_p.data(), model.base().positions.data(), n * sizeof(float));
    std::memcpy(copy_n.data(), base_normals.data(), n * sizeof(float));
    benchmark::ClobberMemory();
    const auto t3 = Clock::now();
    model_s += std::chrono::duration<double>(t1 - t0).count();
    linear_s += std::chrono::duration<double>(t2 - t1).count();
    copy_s += std::chrono::duration<double>(t3 - t2).count();
    state.SetIterationTime(std::chrono::duration<double>(t1 - t0).count());
  }
  if (!ok) state.SkipWithError("an evaluation refused its input (internal error)");
  const auto iterations = static_cast<double>(state.iterations());
  state.counters["us_per_evaluation"] = 1e6 * model_s / iterations;
  state.counters["ratio_to_linear"] = model_s / linear_s;
  state.counters["ratio_to_copy"] = model_s / copy_s;
}

}  // namespace

BENCHMARK_CAPTURE(BM_SpotEvaluation, linear, "spot.vdg.json")->UseManualTime()->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_SpotEvaluation, smooth, "spot-smooth.vdg.json")->UseManualTime()->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_SpotEvaluation, rbf, "spot-rbf.vdg.json")->UseManualTime()->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_SpotEvaluation, parts, "spot-cubist.vdg.json")->UseManualTime()->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_SpotEvaluation, positions, "spot-dolly.vdg.json")->UseManualTime()->Unit(benchmark::kMicrosecond);
BENCHMARK_MAIN();
