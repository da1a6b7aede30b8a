// A crowd on the CPU (Rademacher 99, section 1: a character "replicated many times from different
// angles"): N instances of one view-dependent model, each evaluated per frame for its own view
// (locate + weigh + blend + normals), threaded over the instances with oneTBB. The floor, timed in
// the same run with the same threads, is N copies of the base: each instance's positions and normals
// copied from the base's. Counters:
//   vertex_instances_per_s  N x #V evaluated per second (positions + normals)
//   ratio_to_copies         evaluation time / copy time (the figure to watch)
//   instances, vertices     N and #V
// The benchmark argument is N; N = 1 is one character's frame against one copy of its base. Each instance keeps its
// ModelEvaluator (its buffers and last weights), so keys that move few vertices cost what they move. Run from the
// repository root, or set VDG_SOURCE_DIR.
#include <benchmark/benchmark.h>

#include <oneapi/tbb/blocked_range.h>
#include <oneapi/tbb/parallel_for.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "vdg/io/manifest.h"
#include "vdg/viewdep/evaluator.h"
#include "vdg/viewdep/model.h"

namespace {

std::string examplesDir() {
  const char* src = std::getenv("VDG_SOURCE_DIR");
  return std::string(src ? src : ".") + "/examples";
}

const vdg::ViewDependentModel& spot() {
  static const vdg::ViewDependentModel model =
      vdg::ViewDependentModel::build(vdg::loadManifest(examplesDir() + "/spot/spot.vdg.json"));
  return model;
}

struct Crowd {
  std::vector<Eigen::Vector3d> centres;  // instance positions on a square grid, model units
  std::vector<vdg::ModelEvaluator> evaluators;
  std::vector<int> hints;
  std::vector<std::vector<float>> positions, normals;  // the copies of the floor
};

Crowd makeCrowd(const vdg::ViewDependentModel& m, int count) {
  Crowd c;
  const int side = static_cast<int>(std::ceil(std::sqrt(count)));
  const double spacing = 2.5 * m.extentRadius();
  for (int i = 0; i < count; ++i) {
    c.centres.emplace_back(spacing * (i % side - 0.5 * side), 0.0, spacing * (i / side - 0.5 * side));
    c.evaluators.emplace_back(m);
    c.hints.push_back(-1);
    c.positions.emplace_back(m.base().positions.size());
    c.normals.emplace_back(m.base().positions.size());
  }
  return c;
}

void BM_CrowdOnTheCpu(benchmark::State& state) {
  const vdg::ViewDependentModel& m = spot();
  const int count = static_cast<int>(state.range(0));
  Crowd crowd = makeCrowd(m, count);
  std::vector<float> base_normals(m.base().positions.size());
  if (!vdg::computeVertexNormals(m.surface(), m.base().positions, base_normals)) {
    state.SkipWithError("computeVertexNormals refused the base (internal error)");
    return;
  }
  using Clock = std::chrono::steady_clock;
  double eval_s = 0.0, copy_s = 0.0;
  int frame = 0;
  bool ok = true;
  for (auto _ : state) {
    // A camera circling the crowd above it: every instance sees it from its own direction.
    const double t = 0.02 * frame++;
    const double reach = 0.6 * std::sqrt(static_cast<double>(count)) * 2.5 * m.extentRadius() + 5.0;
    const Eigen::Vector3d eye(reach * std::sin(t), 0.5 * reach, reach * std::cos(t));
    const auto t0 = Clock::now();
    oneapi::tbb::parallel_for(oneapi::tbb::blocked_range<int>(0, count), [&](const oneapi::tbb::blocked_range<int>& r) {
      for (int i = r.begin(); i != r.end(); ++i) {
        const Eigen::Vector3d view = m.viewFromEye(eye - crowd.centres[static_cast<std::size_t>(i)]);
        if (!crowd.evaluators[static_cast<std::size_t>(i)].evaluate(view, 0.0,
                                                                    &crowd.hints[static_cast<std::size_t>(i)]))
          ok = false;
      }
    });
    const auto t1 = Clock::now();
    oneapi::tbb::parallel_for(oneapi::tbb::blocked_range<int>(0, count), [&](const oneapi::tbb::blocked_range<int>& r) {
      for (int i = r.begin(); i != r.end(); ++i) {
        const auto k = static_cast<std::size_t>(i);
        std::memcpy(crowd.positions[k].data(), m.base().positions.data(), crowd.positions[k].size() * sizeof(float));
        std::memcpy(crowd.normals[k].data(), base_normals.data(), crowd.normals[k].size() * sizeof(float));
      }
    });
    benchmark::ClobberMemory();
    const auto t2 = Clock::now();
    eval_s += std::chrono::duration<double>(t1 - t0).count();
    copy_s += std::chrono::duration<double>(t2 - t1).count();
    state.SetIterationTime(std::chrono::duration<double>(t1 - t0).count());
  }
  if (!ok) state.SkipWithError("an evaluation refused its input (internal error)");
  const double vertex_instances = static_cast<double>(count) * static_cast<double>(m.vertexCount());
  state.counters["instances"] = count;
  state.counters["vertices"] = static_cast<double>(m.vertexCount());
  state.counters["vertex_instances_per_s"] = vertex_instances * static_cast<double>(state.iterations()) / eval_s;
  state.counters["ratio_to_copies"] = eval_s / copy_s;
}

}  // namespace

BENCHMARK(BM_CrowdOnTheCpu)->Arg(1)->Arg(100)->Arg(1000)->UseManualTime()->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();
