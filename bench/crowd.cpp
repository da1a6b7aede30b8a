// Frames per second of the crowd example (examples/crowd/crowd.lua: one view-dependent model
// replicated many times, each member blended for its own view, Rademacher 99, section 1) as a
// ratio to the same instances drawn without view dependence (every member its base mesh), both
// rendered in this run: the ratio is the cost of per-instance view dependence in a scene. The
// same frames are also drawn with the GPU blend (SceneFrameOptions::gpu_blend: every cow blended,
// shaded and inked in one call), against the same baseline.
// Run from the repository root, or set VDG_SOURCE_DIR.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <string>

#include "vdg/render/scene_renderer.h"
#include "vdg/scene/scene.h"
#include "vdg/script/script.h"

namespace {

constexpr int kSize = 256;

std::string examplesDir() {
  const char* src = std::getenv("VDG_SOURCE_DIR");
  return std::string(src ? src : ".") + "/examples";
}

// Renders the request's frames; returns seconds per frame.
double secondsPerFrame(vdg::render::SceneRenderer& r, int first, int last, vdg::render::Image& img) {
  const auto start = std::chrono::steady_clock::now();
  for (int f = first; f <= last; ++f) r.render(f, img);
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() / (last - first + 1);
}

void BM_CrowdViewDependentVsBase(benchmark::State& state) {
  vdg::script::ScriptOptions so;
  so.print = [](std::string_view) {};
  so.output_dir = "/tmp";
  so.read_root = examplesDir();  // the script loads ../spot
  const vdg::script::Shot shot = vdg::script::runScript(examplesDir() + "/crowd/crowd.lua", so);
  const vdg::scene::Scene scene = vdg::scene::Scene::build(shot.scene);
  const auto& request = shot.renders.at(0);
  vdg::render::SceneFrameOptions o;
  o.width = o.height = kSize;
  o.frame_first = request.first_frame;
  o.frame_last = request.last_frame;
  vdg::render::SceneRenderer blended(scene, o);
  o.gpu_blend = true;  // the same frames with every cow blended on the GPU (one call per frame)
  vdg::render::SceneRenderer gpu(scene, o);
  o.gpu_blend = false;
  o.base_only = true;
  vdg::render::SceneRenderer plain(scene, o);
  // A dozen frames spread over the shot.
  const int first = request.first_frame, last = std::min(request.last_frame, request.first_frame + 11);
  vdg::render::Image img;
  secondsPerFrame(blended, first, first, img);  // warm-up
  secondsPerFrame(plain, first, first, img);
  secondsPerFrame(gpu, first, first, img);
  double t_blend = 0, t_plain = 0, t_gpu = 0;
  for (auto _ : state) {
    t_blend += secondsPerFrame(blended, first, last, img);
    t_plain += secondsPerFrame(plain, first, last, img);
    t_gpu += secondsPerFrame(gpu, first, last, img);
  }
  const double n = static_cast<double>(state.iterations());
  state.counters["instances"] = blended.drawnCount();
  state.counters["fps_view_dependent"] = n / t_blend;
  state.counters["fps_without"] = n / t_plain;
  state.counters["ratio_time_to_without"] = t_blend / t_plain;
  state.counters["fps_gpu_blend"] = n / t_gpu;
  state.counters["gpu_blend_ratio_time_to_without"] = t_gpu / t_plain;
}
BENCHMARK(BM_CrowdViewDependentVsBase)->Unit(benchmark::kMillisecond)->Iterations(3);

}  // namespace

BENCHMARK_MAIN();
