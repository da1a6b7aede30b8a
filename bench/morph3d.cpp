// Distance-field shape interpolation (Parent 4.10, "Distance Fields"; vdg/morph/shape_morph.h):
// time and memory of a sphere -> torus DistanceMorph (both signed distance volumes built, then one
// inbetween at t = 0.5 polygonised) against the voxel count, for voxel sizes of the larger
// bounding-box diagonal / 24, 48, 96 (the default) and 144. Every size is measured in the same
// iteration, and each is reported as a ratio to the smallest size (diagonal / 24, the fewest
// voxels) of that run:
//   voxels_D            active voxels of both volumes at diagonal / D
//   MiB_D               their memory (OpenVDB's memUsage)
//   ms_D                build + at(0.5), milliseconds
//   voxels_x24_D, MiB_x24_D, time_x24_D   the same as ratios to diagonal / 24
// The volumes grow with the cube of 1/voxel inside the meshes (the interiors are filled) and the
// square on the bands; the time follows the voxels.
#include <benchmark/benchmark.h>

#include <array>
#include <chrono>
#include <cmath>
#include <string>

#include "support/test_meshes.h"
#include "vdg/geom/tri_mesh.h"
#include "vdg/morph/shape_morph.h"

namespace {

constexpr std::array<int, 4> kVoxelsPerDiagonal = {24, 48, 96, 144};

void BM_DistanceMorphAgainstVoxelCount(benchmark::State& state) {
  const vdg::TriMesh a = vdg::testing::uvSphere(48, 96), b = vdg::testing::torus(1.0, 0.4, 96, 48);
  const double diagonal =
      std::max(vdg::computeBounds(a.positions).diagonal(), vdg::computeBounds(b.positions).diagonal());
  using Clock = std::chrono::steady_clock;
  std::array<double, kVoxelsPerDiagonal.size()> seconds{}, voxels{}, bytes{};
  for (auto _ : state) {
    for (std::size_t k = 0; k < kVoxelsPerDiagonal.size(); ++k) {
      const auto start = Clock::now();
      const vdg::morph::DistanceMorph morph(a, b, {.voxel_size = diagonal / kVoxelsPerDiagonal[k]});
      const vdg::TriMesh half = morph.at(0.5);
      benchmark::DoNotOptimize(half.positions.data());
      seconds[k] += std::chrono::duration<double>(Clock::now() - start).count();
      voxels[k] = static_cast<double>(morph.activeVoxelCount());
      bytes[k] = static_cast<double>(morph.memoryBytes());
    }
  }
  const auto n = static_cast<double>(state.iterations());
  for (std::size_t k = 0; k < kVoxelsPerDiagonal.size(); ++k) {
    const std::string d = std::to_string(kVoxelsPerDiagonal[k]);
    state.counters["voxels_" + d] = voxels[k];
    state.counters["MiB_" + d] = bytes[k] / 1048576.0;
    state.counters["ms_" + d] = seconds[k] / n * 1e3;
    if (k == 0) continue;
    state.counters["voxels_x24_" + d] = voxels[k] / voxels[0];
    state.counters["MiB_x24_" + d] = bytes[k] / bytes[0];
    state.counters["time_x24_" + d] = seconds[k] / seconds[0];
  }
}
BENCHMARK(BM_DistanceMorphAgainstVoxelCount)->Unit(benchmark::kMillisecond)->Iterations(3);

}  // namespace

BENCHMARK_MAIN();
