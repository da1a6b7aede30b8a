// Per-frame evaluation of a 1M-vertex, 2M-triangle view-dependent model (three keys active), each
// figure a ratio to a baseline timed in the same run, frame by frame (docs/performance.md):
//   x_memcpy: positions only (locate + weigh + blend) / a memcpy of the positions (single thread);
//   x_floor:  positions + normals / the floor: one streaming pass over both cores (TBB) that reads
//             the base, three dense key deltas and the triangle index buffer and writes positions
//             and normals, the bytes a full evaluation cannot avoid; BM_FullDenseKeysOneThread
//             measures both on one thread (oneTBB limited to one), the figure a loaded machine
//             distorts least;
//   x_floor_per_vertex: the normals alone on a mesh that stays in the caches, per vertex, / the
//             floor per vertex, both on one thread (BM_NormalsInCacheOneThread);
//   x_dense:  sparse keys through ModelEvaluator frame to frame along the same coherent camera path
//             / the full evaluation (positions + normals) of the dense-key model.
// Dense keys move every vertex. "Patch" keys each move a contiguous 1% of the vertices, those
// around the key's view direction, as a real key's edit does; "scattered" keys move every 100th
// vertex (the worst case for sparse keys: their 1% touches nearly every cache line and their
// normals reach 7% of the vertices).
#include <benchmark/benchmark.h>
#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <ctime>
#include <numbers>
#include <numeric>
#include <optional>

#include "vdg/geom/surface.h"
#include "vdg/viewdep/evaluator.h"
#include "vdg/viewdep/model.h"

namespace {

constexpr int kRings = 1000, kSegments = 1000;  // ~1M vertices, ~2M triangles

vdg::TriMesh uvSphere(int rings, int segments) {
  vdg::TriMesh m;
  m.positions.reserve(3 * static_cast<std::size_t>(rings) * segments);
  for (int r = 0; r < rings; ++r) {
    const double theta = std::numbers::pi * (r + 0.5) / rings;
    for (int s = 0; s < segments; ++s) {
      const double phi = 2 * std::numbers::pi * s / segments;
      m.positions.insert(m.positions.end(),
                         {static_cast<float>(std::sin(theta) * std::cos(phi)), static_cast<float>(std::cos(theta)),
                          static_cast<float>(std::sin(theta) * std::sin(phi))});
    }
  }
  for (int r = 0; r + 1 < rings; ++r)
    for (int s = 0; s < segments; ++s) {
      const int a = r * segments + s, b = r * segments + (s + 1) % segments;
      m.triangles.insert(m.triangles.end(), {a, a + segments, b, b, a + segments, b + segments});
    }
  return m;
}

enum class Keys { kDense, kPatch, kScattered };

const vdg::ViewDependentModel& model(Keys kind) {
  static const auto build = [](Keys keys) {
    vdg::RawViewDependentModel raw;
    raw.base = uvSphere(kRings, kSegments);
    const std::size_t nv = raw.base.vertexCount();
    const Eigen::Vector3d views[] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    for (int k = 0; k < 6; ++k) {
      vdg::RawKey key;
      key.name = "k" + std::to_string(k);
      key.mesh = raw.base;
      key.view = views[k];
      std::vector<std::size_t> moved;
      if (keys == Keys::kPatch) {  // the 1% of the vertices nearest the key's view direction
        moved.resize(nv);
        std::iota(moved.begin(), moved.end(), std::size_t{0});
        const auto along = [&](std::size_t v) {
          const float* p = &raw.base.positions[3 * v];
          return p[0] * views[k].x() + p[1] * views[k].y() + p[2] * views[k].z();
        };
        std::nth_element(moved.begin(), moved.begin() + static_cast<long>(nv / 100), moved.end(),
                         [&](std::size_t a, std::size_t b) { return along(a) > along(b); });
        moved.resize(nv / 100);
      } else {
        for (std::size_t v = static_cast<std::size_t>(k); v < nv; v += keys == Keys::kDense ? 1 : 100)
          moved.push_back(v);
      }
      for (const std::size_t v : moved)
        for (std::size_t c = 0; c < 3; ++c) key.mesh.positions[3 * v + c] *= 1.0f + 0.05f * static_cast<float>(k + 1);
      raw.keys.push_back(std::move(key));
    }
    return vdg::ViewDependentModel::build(raw);
  };
  static const vdg::ViewDependentModel dense = build(Keys::kDense);
  if (kind == Keys::kDense) return dense;
  static const vdg::ViewDependentModel patch = build(Keys::kPatch);
  if (kind == Keys::kPatch) return patch;
  static const vdg::ViewDependentModel scattered = build(Keys::kScattered);
  return scattered;
}

Eigen::Vector3d pathView(int frame) {  // a coherent camera path; three keys active
  const double t = 0.01 * frame;
  return {std::sin(t), 0.4, std::cos(t)};
}

using Clock = std::chrono::steady_clock;
double seconds(Clock::time_point a, Clock::time_point b) { return std::chrono::duration<double>(b - a).count(); }
// CPU seconds of the whole process (every thread, TBB's workers included): on a shared, loaded
// machine a thread that waits for a core shows in the wall time but not here, so the cpu_x_*
// counters are the steadier figure there (they count TBB's brief spinning too).
double cpuSeconds() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

// The floor: one pass over both cores reading base + 3 deltas + the triangle indices, writing
// positions and normals (the same bytes a full dense evaluation must move).
struct Floor {
  const float *base, *d0, *d1, *d2;
  const std::int32_t* triangles;
  std::size_t vertices, corners;
  float *positions, *normals;
  std::int64_t sink = 0;

  void run() {
    const std::size_t chunks = 64;
    std::int64_t sums[chunks] = {};
    tbb::parallel_for(
        tbb::blocked_range<std::size_t>(0, chunks),
        [&](const tbb::blocked_range<std::size_t>& r) {
          for (std::size_t c = r.begin(); c < r.end(); ++c) {
            const std::size_t v0 = vertices * c / chunks * 3, v1 = vertices * (c + 1) / chunks * 3;
            for (std::size_t i = v0; i < v1; ++i) {
              const float p = base[i] + d0[i] + d1[i] + d2[i];
              positions[i] = p;
              normals[i] = p - base[i];
            }
            const std::size_t t0 = corners * c / chunks, t1 = corners * (c + 1) / chunks;
            std::int64_t s = 0;
            for (std::size_t i = t0; i < t1; ++i) s += triangles[i];
            sums[c] = s;
          }
        },
        tbb::static_partitioner());
    for (const std::int64_t s : sums) sink += s;
  }
};

Floor floorOf(const vdg::ViewDependentModel& dense, std::vector<float>& positions, std::vector<float>& normals) {
  std::vector<float> out(dense.base().positions.size());
  // The three keys' deltas, as blend reads them: key positions minus the base.
  static std::vector<float> deltas[3];
  for (std::size_t k = 0; k < 3; ++k) {
    if (deltas[k].empty()) {
      (void)dense.keyPositions(k, out);
      deltas[k].resize(out.size());
      for (std::size_t i = 0; i < out.size(); ++i) deltas[k][i] = out[i] - dense.base().positions[i];
    }
  }
  return Floor{dense.base().positions.data(),
               deltas[0].data(),
               deltas[1].data(),
               deltas[2].data(),
               dense.base().triangles.data(),
               dense.vertexCount(),
               dense.base().triangles.size(),
               positions.data(),
               normals.data()};
}

// Positions only, as a ratio to a single-threaded memcpy of the positions.
void positionsBenchmark(benchmark::State& state, Keys keys) {
  const vdg::ViewDependentModel& m = model(keys);
  const std::size_t n = m.base().positions.size();
  std::vector<float> out(n), copy(n);
  double eval_s = 0.0, memcpy_s = 0.0;
  int frame = 0, hint = -1;
  for (auto _ : state) {
    const auto t0 = Clock::now();
    if (!m.evaluate(pathView(frame++), 1.0, out, {}, &hint)) {
      state.SkipWithError("evaluate refused its input (internal error)");
      break;
    }
    benchmark::DoNotOptimize(out.data());
    const auto t1 = Clock::now();
    std::memcpy(copy.data(), m.base().positions.data(), n * sizeof(float));
    benchmark::DoNotOptimize(copy.data());
    benchmark::ClobberMemory();
    const auto t2 = Clock::now();
    eval_s += seconds(t0, t1);
    memcpy_s += seconds(t1, t2);
    state.SetIterationTime(seconds(t0, t1));
  }
  state.counters["vertices"] = static_cast<double>(m.vertexCount());
  state.counters["x_memcpy"] = eval_s / memcpy_s;
}

// Positions + normals of the dense model, as a ratio to the floor.
void fullDenseBenchmark(benchmark::State& state, bool evaluator, bool one_thread = false) {
  // One thread: the evaluation's chunks and the floor's both run on this thread.
  std::optional<tbb::global_control> limit;
  if (one_thread) limit.emplace(tbb::global_control::max_allowed_parallelism, 1);
  const vdg::ViewDependentModel& m = model(Keys::kDense);
  const std::size_t n = m.base().positions.size();
  std::vector<float> positions(n), normals(n), floor_p(n), floor_n(n);
  Floor floor = floorOf(m, floor_p, floor_n);
  vdg::ModelEvaluator instance(m);
  double eval_s = 0.0, floor_s = 0.0, eval_cpu = 0.0, floor_cpu = 0.0;
  int frame = 0, hint = -1;
  for (auto _ : state) {
    const double c0 = cpuSeconds();
    const auto t0 = Clock::now();
    const bool ok = evaluator ? instance.evaluate(pathView(frame++), 1.0, &hint)
                              : m.evaluate(pathView(frame++), 1.0, positions, normals, &hint);
    if (!ok) {
      state.SkipWithError("evaluate refused its input (internal error)");
      break;
    }
    benchmark::ClobberMemory();
    const auto t1 = Clock::now();
    const double c1 = cpuSeconds();
    floor.run();
    benchmark::ClobberMemory();
    const auto t2 = Clock::now();
    const double c2 = cpuSeconds();
    eval_s += seconds(t0, t1);
    floor_s += seconds(t1, t2);
    eval_cpu += c1 - c0;
    floor_cpu += c2 - c1;
    state.SetIterationTime(seconds(t0, t1));
  }
  benchmark::DoNotOptimize(floor.sink);
  state.counters["vertices"] = static_cast<double>(m.vertexCount());
  state.counters["floor_ms"] = 1e3 * floor_s / static_cast<double>(state.iterations());
  state.counters["x_floor"] = eval_s / floor_s;
  state.counters["cpu_x_floor"] = eval_cpu / floor_cpu;
}

// Sparse keys, positions + normals, as a ratio to the dense model's full evaluation in the same run.
void sparseBenchmark(benchmark::State& state, Keys keys, bool evaluator) {
  const vdg::ViewDependentModel& dense = model(Keys::kDense);
  const vdg::ViewDependentModel& m = model(keys);
  const std::size_t n = m.base().positions.size();
  std::vector<float> positions(n), normals(n), dense_p(n), dense_n(n);
  vdg::ModelEvaluator instance(m);
  double sparse_s = 0.0, dense_s = 0.0, sparse_cpu = 0.0, dense_cpu = 0.0;
  int frame = 0, hint = -1, dense_hint = -1;
  for (auto _ : state) {
    const Eigen::Vector3d view = pathView(frame++);
    const double c0 = cpuSeconds();
    const auto t0 = Clock::now();
    const bool ok = evaluator ? instance.evaluate(view, 1.0, &hint) : m.evaluate(view, 1.0, positions, normals, &hint);
    benchmark::ClobberMemory();
    const auto t1 = Clock::now();
    const double c1 = cpuSeconds();
    const bool dense_ok = dense.evaluate(view, 1.0, dense_p, dense_n, &dense_hint);
    benchmark::ClobberMemory();
    const auto t2 = Clock::now();
    const double c2 = cpuSeconds();
    sparse_cpu += c1 - c0;
    dense_cpu += c2 - c1;
    if (!ok || !dense_ok) {
      state.SkipWithError("evaluate refused its input (internal error)");
      break;
    }
    sparse_s += seconds(t0, t1);
    dense_s += seconds(t1, t2);
    state.SetIterationTime(seconds(t0, t1));
  }
  std::size_t moved = 0;
  for (std::size_t k = 0; k < m.keyCount(); ++k) moved += m.keyMovedCount(k);
  state.counters["moved_per_key"] = static_cast<double>(moved) / static_cast<double>(m.keyCount());
  state.counters["x_dense"] = sparse_s / dense_s;
  state.counters["cpu_x_dense"] = sparse_cpu / dense_cpu;
}

void BM_PositionsDenseKeys(benchmark::State& state) { positionsBenchmark(state, Keys::kDense); }
void BM_PositionsPatchKeys(benchmark::State& state) { positionsBenchmark(state, Keys::kPatch); }
void BM_FullDenseKeys(benchmark::State& state) { fullDenseBenchmark(state, false); }
void BM_FullDenseKeysEvaluator(benchmark::State& state) { fullDenseBenchmark(state, true); }
void BM_FullDenseKeysOneThread(benchmark::State& state) { fullDenseBenchmark(state, false, true); }
void BM_FullPatchKeysEvaluator(benchmark::State& state) { sparseBenchmark(state, Keys::kPatch, true); }
void BM_FullScatteredKeysEvaluator(benchmark::State& state) { sparseBenchmark(state, Keys::kScattered, true); }
void BM_FullPatchKeysNoEvaluator(benchmark::State& state) { sparseBenchmark(state, Keys::kPatch, false); }

// The normals' arithmetic alone: computeVertexNormals on one thread over a 100 x 100 sphere, whose
// positions, triangles and lists (about 600 KB) stay in the core's caches, then the 1M-vertex floor
// on one thread. x_floor_per_vertex = (normals' time per vertex, in cache) / (floor's time per
// vertex): what the normals cost before a byte comes from memory, as a share of the whole floor. A
// full evaluation cannot be cheaper than its blend plus this, whatever the data layout.
void BM_NormalsInCacheOneThread(benchmark::State& state) {
  const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
  const vdg::TriMesh small = uvSphere(100, 100);
  const vdg::SurfaceTopology topology = vdg::SurfaceTopology::build(small);
  std::vector<float> normals(small.positions.size());
  const vdg::ViewDependentModel& m = model(Keys::kDense);
  const std::size_t n = m.base().positions.size();
  std::vector<float> floor_p(n), floor_n(n);
  Floor floor = floorOf(m, floor_p, floor_n);
  // As many small meshes as the floor has vertices, so both times cover 1M vertices.
  const std::size_t repeats = m.vertexCount() / small.vertexCount();
  double normals_s = 0.0, floor_s = 0.0;
  for (auto _ : state) {
    const auto t0 = Clock::now();
    for (std::size_t r = 0; r < repeats; ++r) {
      if (!vdg::computeVertexNormals(topology, small.positions, normals)) {
        state.SkipWithError("computeVertexNormals refused its input (internal error)");
        return;
      }
      benchmark::ClobberMemory();
    }
    const auto t1 = Clock::now();
    floor.run();
    benchmark::ClobberMemory();
    const auto t2 = Clock::now();
    normals_s += seconds(t0, t1);
    floor_s += seconds(t1, t2);
    state.SetIterationTime(seconds(t0, t1));
  }
  benchmark::DoNotOptimize(floor.sink);
  const double per_vertex = static_cast<double>(repeats * small.vertexCount());
  state.counters["normals_ns_per_vertex"] = 1e9 * normals_s / per_vertex / static_cast<double>(state.iterations());
  state.counters["floor_ns_per_vertex"] =
      1e9 * floor_s / static_cast<double>(m.vertexCount()) / static_cast<double>(state.iterations());
  state.counters["x_floor_per_vertex"] = normals_s / per_vertex / (floor_s / static_cast<double>(m.vertexCount()));
}

// Locating the view alone (the per-frame work that does not depend on the mesh size).
void BM_LocateAndWeigh(benchmark::State& state) {
  const vdg::ViewDependentModel& m = model(Keys::kDense);
  int frame = 0, hint = -1;
  for (auto _ : state) {
    vdg::ViewWeights w;
    if (!m.weights(pathView(frame++), 2.0, w, &hint)) {
      state.SkipWithError("weights refused its input (internal error)");
      break;
    }
    benchmark::DoNotOptimize(w);
  }
}

}  // namespace

BENCHMARK(BM_PositionsDenseKeys)->UseManualTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_PositionsPatchKeys)->UseManualTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_FullDenseKeys)->UseManualTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_FullDenseKeysEvaluator)->UseManualTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_FullDenseKeysOneThread)->UseManualTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_FullPatchKeysEvaluator)->UseManualTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_FullScatteredKeysEvaluator)->UseManualTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_FullPatchKeysNoEvaluator)->UseManualTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_NormalsInCacheOneThread)->UseManualTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_LocateAndWeigh);
BENCHMARK_MAIN();
