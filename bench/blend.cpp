// Locate + weights + blend of a 1M-vertex view-dependent model, per frame, as a ratio to a memcpy
// of the same bytes measured in the same run (the floor: every frame must at least write the
// positions). Dense keys move every vertex; sparse keys move 1% of them, so their cost should
// approach the memcpy alone.
#include <benchmark/benchmark.h>

#include <chrono>
#include <cmath>
#include <cstring>
#include <numbers>

#include "vdg/viewdep/model.h"

namespace {

constexpr int kRings = 1000, kSegments = 1000;  // ~1M vertices

vdg::TriMesh bigSphere() {
  vdg::TriMesh m;
  m.positions.reserve(3 * static_cast<std::size_t>(kRings) * kSegments);
  for (int r = 0; r < kRings; ++r) {
    const double theta = std::numbers::pi * (r + 0.5) / kRings;
    for (int s = 0; s < kSegments; ++s) {
      const double phi = 2 * std::numbers::pi * s / kSegments;
      m.positions.insert(m.positions.end(),
                         {static_cast<float>(std::sin(theta) * std::cos(phi)), static_cast<float>(std::cos(theta)),
                          static_cast<float>(std::sin(theta) * std::sin(phi))});
    }
  }
  for (int r = 0; r + 1 < kRings; ++r)
    for (int s = 0; s < kSegments; ++s) {
      const int a = r * kSegments + s, b = r * kSegments + (s + 1) % kSegments;
      m.triangles.insert(m.triangles.end(), {a, a + kSegments, b, b, a + kSegments, b + kSegments});
    }
  return m;
}

const vdg::ViewDependentModel& model(bool sparse) {
  static const auto build = [](bool sparse_keys) {
    vdg::RawViewDependentModel raw;
    raw.base = bigSphere();
    const Eigen::Vector3d views[] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    for (int k = 0; k < 6; ++k) {
      vdg::RawKey key;
      key.name = "k" + std::to_string(k);
      key.mesh = raw.base;
      key.view = views[k];
      const std::size_t step = sparse_keys ? 100 : 1;
      for (std::size_t v = static_cast<std::size_t>(k); v < key.mesh.vertexCount(); v += step)
        key.mesh.positions[3 * v + static_cast<std::size_t>(k % 3)] += 0.01f;
      raw.keys.push_back(std::move(key));
    }
    return vdg::ViewDependentModel::build(raw);
  };
  static const vdg::ViewDependentModel dense_model = build(false);
  static const vdg::ViewDependentModel sparse_model = build(true);
  return sparse ? sparse_model : dense_model;
}

void blendBenchmark(benchmark::State& state, bool sparse) {
  const vdg::ViewDependentModel& m = model(sparse);
  const std::size_t n = m.base().positions.size();
  std::vector<float> out(n), copy(n);
  using Clock = std::chrono::steady_clock;
  double blend_s = 0.0, memcpy_s = 0.0;
  int frame = 0, hint = -1;
  for (auto _ : state) {
    const double t = 0.01 * frame++;
    const Eigen::Vector3d view(std::sin(t), 0.4, std::cos(t));  // three keys active
    const auto t0 = Clock::now();
    if (!m.evaluate(view, 1.0, out, {}, &hint)) {
      state.SkipWithError("evaluate refused its input (internal error)");
      break;
    }
    benchmark::DoNotOptimize(out.data());
    const auto t1 = Clock::now();
    std::memcpy(copy.data(), m.base().positions.data(), n * sizeof(float));
    benchmark::DoNotOptimize(copy.data());
    benchmark::ClobberMemory();
    const auto t2 = Clock::now();
    blend_s += std::chrono::duration<double>(t1 - t0).count();
    memcpy_s += std::chrono::duration<double>(t2 - t1).count();
    state.SetIterationTime(std::chrono::duration<double>(t1 - t0).count());
  }
  state.counters["vertices"] = static_cast<double>(m.vertexCount());
  state.counters["x_memcpy"] = blend_s / memcpy_s;  // the figure to watch: cost relative to a copy
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations() * n * sizeof(float)));
}

void BM_BlendDenseKeys(benchmark::State& state) { blendBenchmark(state, false); }
void BM_BlendSparseKeys(benchmark::State& state) { blendBenchmark(state, true); }

// Locating the view alone (the per-frame work that does not depend on the mesh size).
void BM_LocateAndWeigh(benchmark::State& state) {
  const vdg::ViewDependentModel& m = model(true);
  int frame = 0, hint = -1;
  for (auto _ : state) {
    const double t = 0.01 * frame++;
    vdg::ViewWeights w;
    if (!m.weights(Eigen::Vector3d(std::sin(t), 0.4, std::cos(t)), 2.0, w, &hint)) {
      state.SkipWithError("weights refused its input (internal error)");
      break;
    }
    benchmark::DoNotOptimize(w);
  }
}

}  // namespace

BENCHMARK(BM_BlendDenseKeys)->UseManualTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_BlendSparseKeys)->UseManualTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_LocateAndWeigh);
BENCHMARK_MAIN();
