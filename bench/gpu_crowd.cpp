// A crowd blended on the GPU (Renderer::drawBlendInstances; Rademacher 99, section 3.2, for many
// instances "replicated many times from different angles"): N instances of one view-dependent
// model in a grid, each turned its own way so that each is seen from its own view and blends its
// own keys, against the same instances all-base (every weight on the base: the same pipeline, the
// "without view dependence" baseline), timed in the same run, interleaved.
//
// Timed per frame, each ended by Renderer::finish() (glFinish), read-back excluded:
//   frame:      clear + drawBlendInstances (upload, blend, normals, edges, instanced draw, strokes);
//   blend only: blendInstances (upload, blend and normal passes, nothing drawn).
// Counters: ratio_time_to_without (frame with / frame without; goal <= 1.15 on llvmpipe with
// 1,000 instances of spot), vertices_blended_per_s (N x #V / blend-only time),
// ms_blend_per_frame (goal on an NVIDIA GPU: 100,000 x 10k vertices within 8 ms),
// draw_tris_ratio (triangles per second with view dependence / without; goal >= 0.85).
//
// Environment (all optional):
//   VDG_CROWD_INSTANCES  instances (default 1000)
//   VDG_CROWD_VERTICES   0: examples/spot (2,930 vertices, the default); else a generated sphere
//                        of about this many vertices with six keys (bumps), e.g. 10000
//   VDG_CROWD_SIZE       canvas side in pixels (default 512)
//   VDG_CROWD_FRAMES     frames of each kind per iteration (default 3)
// Run from the repository root, or set VDG_SOURCE_DIR. The label gives the OpenGL renderer:
// "llvmpipe" means no GPU was used.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <numbers>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "vdg/io/manifest.h"
#include "vdg/render/renderer.h"
#include "vdg/viewdep/model.h"

namespace {

long envLong(const char* name, long fallback) {
  const char* text = std::getenv(name);
  if (!text || !*text) return fallback;
  char* end = nullptr;
  const long v = std::strtol(text, &end, 10);
  return end && *end == '\0' && v >= 0 ? v : fallback;
}

// A UV sphere of about `vertices` vertices with six keys, one per axis view, each bumping the
// side across from its view (so the outline changes with the view).
vdg::RawViewDependentModel generatedModel(long vertices) {
  const int segments = std::max(8, static_cast<int>(std::lround(std::sqrt(2.0 * static_cast<double>(vertices)))));
  const int rings = std::max(4, segments / 2);
  vdg::RawViewDependentModel raw;
  raw.source = "generated sphere";
  vdg::TriMesh& m = raw.base;
  const auto add = [&](double x, double y, double z) {
    for (const double c : {x, y, z}) m.positions.push_back(static_cast<float>(c));
  };
  add(0, 1, 0);
  for (int r = 1; r < rings; ++r)
    for (int s = 0; s < segments; ++s) {
      const double phi = std::numbers::pi * r / rings, theta = 2 * std::numbers::pi * s / segments;
      add(std::sin(phi) * std::sin(theta), std::cos(phi), std::sin(phi) * std::cos(theta));
    }
  add(0, -1, 0);
  const int south = static_cast<int>(m.vertexCount()) - 1;
  const auto ring = [&](int r, int s) { return 1 + (r - 1) * segments + (s % segments); };
  const auto tri = [&](int a, int b, int c) { m.triangles.insert(m.triangles.end(), {a, b, c}); };
  for (int s = 0; s < segments; ++s) tri(0, ring(1, s), ring(1, s + 1));
  for (int r = 1; r < rings - 1; ++r)
    for (int s = 0; s < segments; ++s) {
      tri(ring(r, s), ring(r + 1, s), ring(r + 1, s + 1));
      tri(ring(r, s), ring(r + 1, s + 1), ring(r, s + 1));
    }
  for (int s = 0; s < segments; ++s) tri(south, ring(rings - 1, s + 1), ring(rings - 1, s));
  const std::array<Eigen::Vector3d, 6> views{Eigen::Vector3d::UnitX(), -Eigen::Vector3d::UnitX(),
                                             Eigen::Vector3d::UnitY(), -Eigen::Vector3d::UnitY(),
                                             Eigen::Vector3d::UnitZ(), -Eigen::Vector3d::UnitZ()};
  for (std::size_t k = 0; k < views.size(); ++k) {
    vdg::RawKey key;
    key.name = "key" + std::to_string(k);
    key.mesh = m;
    const Eigen::Vector3d bump = views[(k + 2) % views.size()];
    for (std::size_t v = 0; v < m.vertexCount(); ++v) {
      Eigen::Vector3d p(m.positions[v * 3], m.positions[v * 3 + 1], m.positions[v * 3 + 2]);
      const double c = p.normalized().dot(bump);
      if (c > 0.5) p *= 1.0 + 0.4 * (c - 0.5) / 0.5;
      for (int i = 0; i < 3; ++i) key.mesh.positions[v * 3 + i] = static_cast<float>(p[i]);
    }
    key.view = views[k];
    raw.keys.push_back(std::move(key));
  }
  raw.center = Eigen::Vector3d::Zero();
  return raw;
}

vdg::ViewDependentModel crowdModel() {
  const long vertices = envLong("VDG_CROWD_VERTICES", 0);
  if (vertices > 0) return vdg::ViewDependentModel::build(generatedModel(vertices));
  const char* src = std::getenv("VDG_SOURCE_DIR");
  return vdg::ViewDependentModel::build(
      vdg::loadManifest(std::string(src ? src : ".") + "/examples/spot/spot.vdg.json"));
}

// The grid, the camera that sees all of it, and each instance's own view's weights.
struct Crowd {
  std::vector<vdg::render::InstanceBlend> with, without;
  vdg::render::View view;
};

Crowd makeCrowd(const vdg::ViewDependentModel& model, std::size_t count, int size) {
  Crowd c;
  const auto columns = static_cast<std::size_t>(std::ceil(std::sqrt(static_cast<double>(count))));
  const std::size_t rows = (count + columns - 1) / columns;
  const double spacing = 2.2 * model.extentRadius();
  const Eigen::Vector3d middle(0.5 * static_cast<double>(columns - 1) * spacing,
                               0.5 * static_cast<double>(rows - 1) * spacing, 0.0);
  const double half = 0.5 * static_cast<double>(std::max(columns, rows)) * spacing;
  constexpr double kFov = 30.0;
  const double distance = 1.1 * half / std::tan(0.5 * kFov * std::numbers::pi / 180.0) + model.extentRadius();
  c.view.viewport = {0, 0, size, size};
  c.view.camera.eye = middle + Eigen::Vector3d(0.0, 0.0, distance);
  c.view.camera.target = middle;
  c.view.camera.up = Eigen::Vector3d::UnitY();
  c.view.camera.fov_deg = kFov;
  c.view.z_near = std::max(1e-3, distance - 3.0 * model.extentRadius());
  c.view.z_far = distance + 3.0 * model.extentRadius();
  for (std::size_t i = 0; i < count; ++i) {
    const Eigen::Vector3d offset(static_cast<double>(i % columns) * spacing, static_cast<double>(i / columns) * spacing,
                                 0.0);
    // Turned about the vertical and tilted by the golden angle's multiples: views all around.
    const double yaw = 2.399963 * static_cast<double>(i), pitch = 0.6 * std::sin(0.37 * static_cast<double>(i));
    const Eigen::Affine3d object = Eigen::Translation3d(offset) * Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitY()) *
                                   Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitX()) *
                                   Eigen::Translation3d(-model.center());
    vdg::render::InstanceBlend instance;
    instance.object = object.matrix().cast<float>();
    if (!model.weights(model.viewFromEye(object.inverse() * c.view.camera.eye), 0.0, instance.weights))
      instance.weights = vdg::ViewWeights{{-1, -1, -1}, {0, 0, 0}, 1.0f, -1};
    c.with.push_back(instance);
    instance.weights = vdg::ViewWeights{{-1, -1, -1}, {0, 0, 0}, 1.0f, -1};
    c.without.push_back(instance);
  }
  return c;
}

double seconds(const std::chrono::steady_clock::time_point& start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void BM_GpuCrowdBlendVsAllBase(benchmark::State& state) {
  const vdg::ViewDependentModel model = crowdModel();
  const auto count = static_cast<std::size_t>(std::max(1L, envLong("VDG_CROWD_INSTANCES", 1000)));
  const int size = static_cast<int>(std::clamp(envLong("VDG_CROWD_SIZE", 512), 1L, 16384L));
  const int frames = static_cast<int>(std::max(1L, envLong("VDG_CROWD_FRAMES", 3)));
  vdg::render::Renderer r(vdg::render::RendererSettings{size, size, 4});
  const int handle = r.addBlendModel(model);
  const Crowd c = makeCrowd(model, count, size);
  const vdg::render::MeshStyle style;
  const vdg::render::Rgb background{0.97f, 0.97f, 0.95f};
  bool ok = true;
  const auto frame = [&](const std::vector<vdg::render::InstanceBlend>& instances) {
    const auto start = std::chrono::steady_clock::now();
    r.clear(background);
    ok &= r.drawBlendInstances(handle, instances, c.view, style);
    r.finish();
    return seconds(start);
  };
  const auto blendOnly = [&](const std::vector<vdg::render::InstanceBlend>& instances) {
    const auto start = std::chrono::steady_clock::now();
    ok &= r.blendInstances(handle, instances);
    r.finish();
    return seconds(start);
  };
  frame(c.with);  // warm-up: buffers allocated, shaders compiled
  frame(c.without);
  double t_with = 0, t_without = 0, b_with = 0, b_without = 0;
  long n = 0;
  for (auto _ : state) {
    for (int f = 0; f < frames; ++f, ++n) {
      t_with += frame(c.with);
      t_without += frame(c.without);
      b_with += blendOnly(c.with);
      b_without += blendOnly(c.without);
    }
  }
  if (!ok) {
    state.SkipWithError("a draw call refused its input (a bug)");
    return;
  }
  const auto per = [&](double t) { return t / static_cast<double>(n); };
  const double vertices = static_cast<double>(count) * static_cast<double>(model.vertexCount());
  const double triangles = static_cast<double>(count) * static_cast<double>(model.base().triangleCount());
  state.counters["instances"] = static_cast<double>(count);
  state.counters["vertices_per_instance"] = static_cast<double>(model.vertexCount());
  state.counters["ms_frame_with"] = 1e3 * per(t_with);
  state.counters["ms_frame_without"] = 1e3 * per(t_without);
  state.counters["ratio_time_to_without"] = t_with / t_without;
  state.counters["ms_blend_per_frame"] = 1e3 * per(b_with);
  state.counters["ms_blend_per_frame_without"] = 1e3 * per(b_without);
  state.counters["vertices_blended_per_s"] = vertices / per(b_with);
  state.counters["triangles_per_s_with"] = triangles / per(t_with);
  state.counters["triangles_per_s_without"] = triangles / per(t_without);
  state.counters["draw_tris_ratio"] = t_without / t_with;
  state.SetLabel(r.glInfo());
}
BENCHMARK(BM_GpuCrowdBlendVsAllBase)->Unit(benchmark::kMillisecond)->Iterations(1);

}  // namespace

BENCHMARK_MAIN();
