// Time per frame of an orbit of the shipped example (examples/spot) rendered with view-dependent
// blending (weights + blend + normals + upload, then silhouettes + draw + read-back), as a ratio to
// the same frames of the plain base mesh (a static mesh: normals computed and uploaded once;
// silhouettes, drawing and read-back still every frame). The difference is the cost of the
// view-dependent part (Rademacher 99, section 3.2). Goal: ratio <= 1.15.
// Run from the repository root, or set VDG_SOURCE_DIR.
#include <benchmark/benchmark.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "vdg/geom/tri_mesh.h"
#include "vdg/io/manifest.h"
#include "vdg/render/model_renderer.h"
#include "vdg/viewdep/model.h"

namespace {

constexpr int kFrames = 36;
constexpr int kSize = 256;

const std::string& spotPath() {
  static const std::string path = [] {
    const char* src = std::getenv("VDG_SOURCE_DIR");
    return std::string(src ? src : ".") + "/examples/spot/spot.vdg.json";
  }();
  return path;
}

// Renders one orbit; returns seconds per frame.
double orbitSecondsPerFrame(const vdg::ViewDependentModel& model, vdg::render::ModelRenderer& r,
                            vdg::render::Image& img) {
  const auto start = std::chrono::steady_clock::now();
  for (int f = 0; f < kFrames; ++f) {
    const vdg::Camera cam = vdg::render::orbitCamera(model.center(), 4.0, 360.0 * f / kFrames, 15.0, 30.0);
    r.render(cam, img);
  }
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() / kFrames;
}

void BM_OrbitBlendedVsBase(benchmark::State& state) {
  const vdg::ViewDependentModel model = vdg::ViewDependentModel::build(vdg::loadManifest(spotPath()));
  vdg::render::FrameOptions o;
  o.width = o.height = kSize;
  vdg::render::ModelRenderer blended(model, o);
  vdg::render::ModelRenderer base(model.base(), o);
  vdg::render::Image img;
  orbitSecondsPerFrame(model, blended, img);  // warm-up
  orbitSecondsPerFrame(model, base, img);
  double t_blend = 0, t_base = 0;
  for (auto _ : state) {
    t_blend += orbitSecondsPerFrame(model, blended, img);
    t_base += orbitSecondsPerFrame(model, base, img);
  }
  state.counters["ms_per_frame_blended"] = 1e3 * t_blend / static_cast<double>(state.iterations());
  state.counters["ms_per_frame_base"] = 1e3 * t_base / static_cast<double>(state.iterations());
  state.counters["ratio_blended_to_base"] = t_blend / t_base;
}
BENCHMARK(BM_OrbitBlendedVsBase)->Unit(benchmark::kMillisecond)->Iterations(3);

}  // namespace

BENCHMARK_MAIN();
