// Arc-length reparameterised evaluation of a 100-key Catmull-Rom path: the table method against
// adaptive Gauss-Kronrod quadrature with Newton inversion (Parent 4.1), side by side. The
// BM_ArcLengthRatio benchmark times both in the same run and reports adaptive/table as a counter.
#include <benchmark/benchmark.h>

#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "vdg/anim/arc_length.h"
#include "vdg/anim/curve.h"

namespace {

constexpr int kKeys = 100;
constexpr int kSamplesPerIteration = 256;

vdg::anim::Curve makeCurve() {
  vdg::anim::RawCurve raw;
  raw.kind = vdg::anim::CurveKind::kCatmullRom;
  for (int i = 0; i < kKeys; ++i) {
    const double a = 0.37 * i;
    raw.points.push_back(Eigen::Vector3d(10 * std::cos(a) + 0.3 * i, 2 * std::sin(1.7 * a), 10 * std::sin(a)));
  }
  return vdg::anim::Curve::build(raw);
}

const vdg::anim::ArcLengthCurve& table() {
  static const auto a =
      vdg::anim::ArcLengthCurve::build(makeCurve(), {vdg::anim::ArcLengthMethod::kTable, 100 * kKeys, 0});
  return a;
}
const vdg::anim::ArcLengthCurve& adaptive() {
  static const auto a = vdg::anim::ArcLengthCurve::build(makeCurve(), {vdg::anim::ArcLengthMethod::kAdaptive, 2, 1e-9});
  return a;
}

double sampleAll(const vdg::anim::ArcLengthCurve& a) {
  std::array<double, 3> p{};
  double sum = 0;
  for (int i = 0; i < kSamplesPerIteration; ++i) {
    if (!a.evaluateAtFraction((i + 0.5) / kSamplesPerIteration, p)) {
      std::fprintf(stderr, "bench/anim: evaluateAtFraction refused its input (internal error)\n");
      std::abort();
    }
    sum += p[0];
  }
  return sum;
}

void BM_ArcLengthTable(benchmark::State& state) {
  const auto& a = table();
  for (auto _ : state) benchmark::DoNotOptimize(sampleAll(a));
  state.SetItemsProcessed(state.iterations() * kSamplesPerIteration);
}
BENCHMARK(BM_ArcLengthTable);

void BM_ArcLengthAdaptive(benchmark::State& state) {
  const auto& a = adaptive();
  for (auto _ : state) benchmark::DoNotOptimize(sampleAll(a));
  state.SetItemsProcessed(state.iterations() * kSamplesPerIteration);
}
BENCHMARK(BM_ArcLengthAdaptive);

// Both methods in the same run; counters: ns per sample of each and the ratio adaptive/table.
void BM_ArcLengthRatio(benchmark::State& state) {
  const auto& t = table();
  const auto& a = adaptive();
  using Clock = std::chrono::steady_clock;
  Clock::duration table_time{}, adaptive_time{};
  for (auto _ : state) {
    const auto t0 = Clock::now();
    benchmark::DoNotOptimize(sampleAll(t));
    const auto t1 = Clock::now();
    benchmark::DoNotOptimize(sampleAll(a));
    const auto t2 = Clock::now();
    table_time += t1 - t0;
    adaptive_time += t2 - t1;
  }
  const double n = static_cast<double>(state.iterations()) * kSamplesPerIteration;
  const double table_ns = std::chrono::duration<double, std::nano>(table_time).count() / n;
  const double adaptive_ns = std::chrono::duration<double, std::nano>(adaptive_time).count() / n;
  state.counters["table_ns_per_sample"] = table_ns;
  state.counters["adaptive_ns_per_sample"] = adaptive_ns;
  state.counters["adaptive_over_table"] = table_ns > 0 ? adaptive_ns / table_ns : 0.0;
}
BENCHMARK(BM_ArcLengthRatio);

}  // namespace

BENCHMARK_MAIN();
