// Per-frame evaluation of the animated view-dependent walker (examples/walk, Rademacher 99,
// section 4): skinning of the base (Rig::evaluate, with the skin linear parts for skinned
// offsets) + AnimatedViewDependentModel::evaluatePosed (time coefficients of each view's offsets,
// weights, blend, normals), for both offset modes, as a ratio to the static evaluation
// (ViewDependentModel::evaluate: weights + blend + normals) of the same mesh measured in the same
// run: a static model whose base is the walker at frame 0 and whose keys are the two keys of frame
// 10 (front and side). The parts are reported as ratios to the same baseline:
//   skin_x_static            Rig::evaluate alone (positions, and skin linear parts when skinned)
//   offsets_blend_x_static   evaluatePosed without normals (offsets in time + weights + blend)
//   normals_x_static         evaluatePosed with normals minus without (area-weighted normals)
//   x_static                 the whole frame: skinning + evaluatePosed with normals
//   x_copy                   the whole frame / a copy of the base (positions and its normals, two
//                            memcpys), the cheapest frame a renderer could be handed
//   static_x_copy            the static evaluation / the same copy
// The camera orbits the walker (two key views active most of the time) while the walk advances
// one frame per iteration. Run from the repository root, or set VDG_SOURCE_DIR.
#include <benchmark/benchmark.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "vdg/anim/rig.h"
#include "vdg/io/gltf.h"
#include "vdg/io/manifest.h"
#include "vdg/viewdep/animated_model.h"
#include "vdg/viewdep/model.h"

namespace {

constexpr int kStaticKeyFrame = 10;  // the static baseline takes the keys of this frame

std::string walkPath(const std::string& file) {
  const char* src = std::getenv("VDG_SOURCE_DIR");
  return std::string(src ? src : ".") + "/examples/walk/" + file;
}

// Everything one benchmark needs, built once per process.
struct Walker {
  vdg::RawViewDependentModel raw;
  vdg::AnimatedViewDependentModel animated;
  vdg::ViewDependentModel still;
  vdg::Rig rig;
  int animation = 0;
  double fps = 24;
};

vdg::ViewDependentModel buildStatic(const vdg::RawViewDependentModel& animated_raw) {
  vdg::RawViewDependentModel raw;
  raw.source =
      animated_raw.source + " (static: base at frame 0, keys of frame " + std::to_string(kStaticKeyFrame) + ")";
  raw.base = animated_raw.base;
  raw.base.positions = animated_raw.base_frames.front();
  raw.center = animated_raw.center;
  raw.sharpness = animated_raw.sharpness;
  raw.sphere = animated_raw.sphere;
  for (const vdg::RawKey& key : animated_raw.keys) {
    if (key.frame != kStaticKeyFrame) continue;
    vdg::RawKey k = key;
    k.frame = 0;
    raw.keys.push_back(std::move(k));
  }
  return vdg::ViewDependentModel::build(raw);
}

Walker loadWalker(const std::string& manifest) {
  vdg::RawViewDependentModel raw = vdg::loadManifest(walkPath(manifest));
  const vdg::BaseAnimationSpec& spec = *raw.base_animation;
  vdg::AnimatedViewDependentModel animated = vdg::AnimatedViewDependentModel::build(raw);
  vdg::ViewDependentModel still = buildStatic(raw);
  vdg::Rig rig = vdg::Rig::build(vdg::readGltfRig(walkPath(spec.gltf), vdg::GltfSelect{spec.mesh}));
  const int animation = spec.animation;
  const double fps = spec.fps;
  return Walker{std::move(raw), std::move(animated), std::move(still), std::move(rig), animation, fps};
}

const Walker& walker(vdg::OffsetSpace space) {
  static const Walker skinned = loadWalker("walker.vdg.json");
  static const Walker world = loadWalker("walker-world.vdg.json");
  return space == vdg::OffsetSpace::kSkinned ? skinned : world;
}

void walkerFrame(benchmark::State& state, vdg::OffsetSpace space) {
  const Walker& w = walker(space);
  if (w.animated.offsetSpace() != space) {
    state.SkipWithError("the manifest's offset mode is not the one this benchmark measures");
    return;
  }
  const std::size_t n = 3 * w.animated.vertexCount();
  const bool skinned = space == vdg::OffsetSpace::kSkinned;
  std::vector<float> base(n), skin(skinned ? 3 * n : 0), out(n), normals(n), still_out(n), still_normals(n);
  std::vector<float> base_normals(n), copy_positions(n), copy_normals(n);
  const std::vector<float>& base_frame = w.raw.base_frames.front();
  if (base_frame.size() != n || !vdg::computeVertexNormals(w.still.surface(), base_frame, base_normals)) {
    state.SkipWithError("the walker's base frame does not fit its model (internal error)");
    return;
  }
  using Clock = std::chrono::steady_clock;
  double static_s = 0, skin_s = 0, blend_s = 0, full_posed_s = 0, copy_s = 0;
  int frame = 0, hint = -1, still_hint = -1;
  const int frames = w.animated.frameCount();
  for (auto _ : state) {
    const double angle = 0.05 * frame;
    const Eigen::Vector3d view(std::sin(angle), 0.3, std::cos(angle));
    const double f = frame % frames;
    ++frame;
    const auto t0 = Clock::now();
    const bool still_ok = w.still.evaluate(view, 0.0, still_out, still_normals, &still_hint);
    benchmark::DoNotOptimize(still_out.data());
    benchmark::DoNotOptimize(still_normals.data());
    benchmark::ClobberMemory();
    const auto t1 = Clock::now();
    const bool skin_ok = w.rig.evaluate(w.animation, f / w.fps, base, {}, skin);
    benchmark::DoNotOptimize(base.data());
    benchmark::ClobberMemory();
    const auto t2 = Clock::now();
    const bool blend_ok = w.animated.evaluatePosed(f, base, skin, view, 0.0, out, {}, &hint);
    benchmark::DoNotOptimize(out.data());
    benchmark::ClobberMemory();
    const auto t3 = Clock::now();
    const bool posed_ok = w.animated.evaluatePosed(f, base, skin, view, 0.0, out, normals, &hint);
    benchmark::DoNotOptimize(out.data());
    benchmark::DoNotOptimize(normals.data());
    benchmark::ClobberMemory();
    const auto t4 = Clock::now();
    std::memcpy(copy_positions.data(), base_frame.data(), n * sizeof(float));
    std::memcpy(copy_normals.data(), base_normals.data(), n * sizeof(float));
    benchmark::DoNotOptimize(copy_positions.data());
    benchmark::DoNotOptimize(copy_normals.data());
    benchmark::ClobberMemory();
    const auto t5 = Clock::now();
    if (!(still_ok && skin_ok && blend_ok && posed_ok)) {
      state.SkipWithError("an evaluation refused its input (internal error)");
      break;
    }
    const auto seconds = [](Clock::duration d) { return std::chrono::duration<double>(d).count(); };
    static_s += seconds(t1 - t0);
    skin_s += seconds(t2 - t1);
    blend_s += seconds(t3 - t2);
    full_posed_s += seconds(t4 - t3);
    copy_s += seconds(t5 - t4);
    state.SetIterationTime(seconds(t2 - t1) + seconds(t4 - t3));  // one animated frame
  }
  if (state.iterations() == 0 || static_s <= 0) return;
  const double per = 1e6 / static_cast<double>(state.iterations());
  state.counters["vertices"] = static_cast<double>(w.animated.vertexCount());
  state.counters["us_static"] = static_s * per;
  state.counters["us_frame"] = (skin_s + full_posed_s) * per;
  state.counters["x_static"] = (skin_s + full_posed_s) / static_s;  // the figure to watch
  state.counters["skin_x_static"] = skin_s / static_s;
  state.counters["offsets_blend_x_static"] = blend_s / static_s;
  state.counters["normals_x_static"] = (full_posed_s - blend_s) / static_s;
  state.counters["x_copy"] = (skin_s + full_posed_s) / copy_s;
  state.counters["static_x_copy"] = static_s / copy_s;
}

void BM_WalkerFrameSkinnedOffsets(benchmark::State& state) { walkerFrame(state, vdg::OffsetSpace::kSkinned); }
void BM_WalkerFrameWorldOffsets(benchmark::State& state) { walkerFrame(state, vdg::OffsetSpace::kWorld); }

}  // namespace

BENCHMARK(BM_WalkerFrameSkinnedOffsets)->UseManualTime()->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_WalkerFrameWorldOffsets)->UseManualTime()->Unit(benchmark::kMicrosecond);
BENCHMARK_MAIN();
