// 2D image morphs (Parent 4.10) in megapixels per second, against a plain bilinear resample
// (resampleBilinear to the same size: one bilinear sample per output pixel) of the same image,
// timed alternately in the same iterations of the same run.
//
// Cases (512 x 512 unless the name says otherwise, t = 0.5):
//   MeshMorph    two-pass mesh warp of both images onto the inbetween of two 5 x 5 grids, then the
//                cross-dissolve (meshMorph);
//   MeshWarp     one image, one two-pass warp (meshWarp);
//   FeatureMorph Beier-Neely warp of both images onto the inbetween of 4 line pairs, dissolve;
//   FeatureWarp  one image, one feature warp.
// Counters: mpix_per_s of the morph (output pixels per wall second), bilinear_mpix_per_s, and the
// ratios x_bilinear = morph wall time / bilinear wall time and cpu_x_bilinear = the same in process
// CPU time (all threads: the morphs run their scanlines on oneTBB's threads, the bilinear resample
// on one, so the wall ratio depends on the core count and the CPU ratio on the work).
#include <benchmark/benchmark.h>

#include <Eigen/Core>
#include <chrono>
#include <cstdlib>
#include <ctime>
#include <functional>
#include <string>
#include <vector>

#include "vdg/morph/image_morph.h"

namespace {

using vdg::morph::FeatureLine;
using vdg::morph::Image;
using vdg::morph::WarpGrid;

Image pattern(int size, int seed) {
  Image image{.width = size, .height = size, .rgba = std::vector<float>(static_cast<std::size_t>(size) * size * 4)};
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      float* p = image.pixel(x, y);
      p[0] = static_cast<float>((x + seed) % size) / size;
      p[1] = static_cast<float>(y) / size;
      p[2] = (((x / 32) + (y / 32) + seed) % 2) ? 0.9f : 0.2f;
      p[3] = 1.0f;
    }
  return image;
}

// A 5 x 5 grid with its interior points moved by up to a quarter cell (stays valid).
WarpGrid grid(int size, double sign) {
  WarpGrid g = vdg::morph::identityGrid(5, 5, size, size);
  const double cell = size / 4.0;
  for (int r = 1; r < 4; ++r)
    for (int c = 1; c < 4; ++c)
      g.at(r, c) += sign * 0.25 * cell * Eigen::Vector2d((r % 2) ? 1 : -0.5, (c % 2) ? 0.6 : -1);
  return g;
}

std::vector<FeatureLine> lines(int size, double shift) {
  const double s = size;
  return {{{0.3 * s + shift, 0.3 * s}, {0.7 * s, 0.3 * s + shift}},
          {{0.3 * s, 0.7 * s - shift}, {0.7 * s - shift, 0.7 * s}},
          {{0.2 * s + shift, 0.35 * s}, {0.2 * s, 0.65 * s}},
          {{0.8 * s, 0.35 * s}, {0.8 * s - shift, 0.65 * s + shift}}};
}

double processSeconds() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

void morphBenchmark(benchmark::State& state, const std::string& which, int size) {
  const Image src = pattern(size, 0), dst = pattern(size, 17);
  const WarpGrid g0 = grid(size, 1), g1 = grid(size, -1);
  const std::vector<FeatureLine> l0 = lines(size, 0), l1 = lines(size, 0.08 * size);
  const vdg::morph::FeatureParams params;
  std::function<Image()> run;
  if (which == "MeshMorph") run = [&] { return vdg::morph::meshMorph(src, dst, g0, g1, 0.5); };
  if (which == "MeshWarp") run = [&] { return vdg::morph::meshWarp(src, g0, g1); };
  if (which == "FeatureMorph") run = [&] { return vdg::morph::featureMorph(src, dst, l0, l1, 0.5, params); };
  if (which == "FeatureWarp") run = [&] { return vdg::morph::featureWarp(src, l0, l1, params); };
  using Clock = std::chrono::steady_clock;
  double morph_wall = 0, base_wall = 0, morph_cpu = 0, base_cpu = 0;
  for (auto _ : state) {
    const auto t0 = Clock::now();
    const double c0 = processSeconds();
    Image out = run();
    benchmark::DoNotOptimize(out.rgba.data());
    const auto t1 = Clock::now();
    const double c1 = processSeconds();
    Image base = vdg::morph::resampleBilinear(src, size, size);
    benchmark::DoNotOptimize(base.rgba.data());
    const auto t2 = Clock::now();
    const double c2 = processSeconds();
    morph_wall += std::chrono::duration<double>(t1 - t0).count();
    base_wall += std::chrono::duration<double>(t2 - t1).count();
    morph_cpu += c1 - c0;
    base_cpu += c2 - c1;
  }
  const double pixels = static_cast<double>(size) * size * static_cast<double>(state.iterations());
  state.counters["mpix_per_s"] = pixels / morph_wall * 1e-6;
  state.counters["bilinear_mpix_per_s"] = pixels / base_wall * 1e-6;
  state.counters["x_bilinear"] = morph_wall / base_wall;  // the figure to watch
  state.counters["cpu_x_bilinear"] = base_cpu > 0 ? morph_cpu / base_cpu : 0.0;
}

}  // namespace

int main(int argc, char** argv) {
  double load[3] = {0, 0, 0};
  if (getloadavg(load, 3) == 3)
    benchmark::AddCustomContext(
        "load_average", std::to_string(load[0]) + " " + std::to_string(load[1]) + " " + std::to_string(load[2]));
  for (const char* which : {"MeshMorph", "MeshWarp", "FeatureMorph", "FeatureWarp"})
    for (const int size : {512}) {
      const std::string name = std::string(which) + "/" + std::to_string(size);
      benchmark::RegisterBenchmark(name.c_str(), [=](benchmark::State& state) {
        morphBenchmark(state, which, size);
      })->Unit(benchmark::kMillisecond);
    }
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
