// The GPU blend (Renderer::addBlendModel / drawBlendInstances, ModelRenderer's gpu_blend): its
// positions and normals equal the CPU blend's, its images equal the CPU path's within named
// tolerances (the shipped spot with its texture, the keyed test sphere, creases, the observer
// panel and sphere inset, many instances with their own views, colours and object matrices in
// one call), its per-frame contract, and its error on an OpenGL older than 4.3.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "render/test_models.h"
#include "vdg/geom/error.h"
#include "vdg/geom/surface.h"
#include "vdg/io/manifest.h"
#include "vdg/render/image.h"
#include "vdg/render/model_renderer.h"
#include "vdg/render/renderer.h"
#include "vdg/viewdep/model.h"

namespace vdg::render {
namespace {

const std::string kSourceDir = VDG_SOURCE_DIR;

// Positions: the GPU blends in float as the CPU does, in another order of operations.
constexpr double kPositionTol = 1e-5;  // relative to the model's extent radius
// Group normals: float sums of the same cross products in another order.
constexpr double kNormalTol = 1e-4;
// Images: a pixel differs when a channel is off by more than kLevels; at most
// kMaxDifferingFraction of the pixels may differ (an edge whose facing flips by rounding, a
// stroke drawn in another order), and the mean absolute channel difference over the image is at
// most kMaxMeanDifference levels.
constexpr int kLevels = 48;
constexpr double kMaxDifferingFraction = 0.004;
constexpr double kMaxMeanDifference = 0.35;

struct Difference {
  double differing_fraction = 1.0;
  double mean = 255.0;
};

Difference difference(const Image& a, const Image& b) {
  Difference d;
  if (a.width != b.width || a.height != b.height) return d;
  long differing = 0;
  double sum = 0.0;
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x) {
      int worst = 0;
      for (int c = 0; c < 3; ++c) {
        const int delta = std::abs(int(a.pixel(x, y)[c]) - int(b.pixel(x, y)[c]));
        worst = std::max(worst, delta);
        sum += delta;
      }
      differing += worst > kLevels ? 1 : 0;
    }
  const double pixels = static_cast<double>(a.width) * a.height;
  d.differing_fraction = static_cast<double>(differing) / pixels;
  d.mean = sum / (3.0 * pixels);
  return d;
}

// Writes both images to the test's temp folder for a look when they differ.
void expectSameImage(const Image& cpu, const Image& gpu, const std::string& name) {
  const Difference d = difference(cpu, gpu);
  EXPECT_LE(d.differing_fraction, kMaxDifferingFraction) << name;
  EXPECT_LE(d.mean, kMaxMeanDifference) << name;
  const char* keep = std::getenv("VDG_KEEP_GPU_IMAGES");
  if (d.differing_fraction > kMaxDifferingFraction || d.mean > kMaxMeanDifference || (keep && *keep)) {
    const std::string dir = ::testing::TempDir();
    writePng(dir + "/" + name + "_cpu.png", cpu);
    writePng(dir + "/" + name + "_gpu.png", gpu);
    std::printf("%s: %.5f of the pixels differ, mean %.3f levels; images in %s\n", name.c_str(), d.differing_fraction,
                d.mean, dir.c_str());
  }
}

const ViewDependentModel& spot() {
  static const ViewDependentModel model =
      ViewDependentModel::build(loadManifest(kSourceDir + "/examples/spot/spot.vdg.json"));
  return model;
}

const ViewDependentModel& bumpy() {
  static const ViewDependentModel model = ViewDependentModel::build(bumpyModel());
  return model;
}

// The CPU path and the GPU path of ModelRenderer at the given orbit views.
void compareOrbit(const ViewDependentModel& model, FrameOptions options, const std::string& name,
                  const std::vector<std::array<double, 2>>& views) {
  options.gpu_blend = false;
  ModelRenderer cpu(model, options);
  options.gpu_blend = true;
  ModelRenderer gpu(model, options);
  Image a, b;
  const double distance = fitDistance(model.extentRadius(), 30.0, 1.0);
  for (const auto& [azimuth, elevation] : views) {
    const Camera camera = orbitCamera(model.center(), distance, azimuth, elevation, 30.0);
    const ViewWeights wa = cpu.render(camera, a);
    const ViewWeights wb = gpu.render(camera, b);
    EXPECT_EQ(wa.key, wb.key);
    expectSameImage(a, b, name + "_" + std::to_string(int(azimuth)) + "_" + std::to_string(int(elevation)));
  }
}

FrameOptions options(int size) {
  FrameOptions o;
  o.width = o.height = size;
  return o;
}

TEST(GpuBlend, SpotWithItsTextureEqualsTheCpuPathAtSeveralViews) {
  compareOrbit(spot(), options(192), "spot", {{0, 10}, {55, 25}, {140, -15}, {200, 40}, {290, 5}});
}

TEST(GpuBlend, KeyedSphereEqualsTheCpuPathAtKeyAndInBetweenViews) {
  compareOrbit(bumpy(), options(160), "bumpy", {{0, 0}, {90, 0}, {45, 30}, {20, 80}, {230, -35}});
}

TEST(GpuBlend, CreasesFlatShadingAndNoMaterialsEqualTheCpuPath) {
  FrameOptions o = options(160);
  o.crease_angle_deg = 12.0f;
  o.flat = true;
  o.materials = false;
  o.color = {0.9f, 0.3f, 0.3f};  // red: the hue rule's constants
  compareOrbit(spot(), o, "spot_creases", {{30, 15}, {250, 20}});
}

TEST(GpuBlend, ObserverPanelAndSphereInsetEqualTheCpuPath) {
  FrameOptions o = options(128);
  o.observer = true;
  o.sphere = true;
  compareOrbit(bumpy(), o, "bumpy_observer", {{30, 20}, {120, -10}});
}

TEST(GpuBlend, ParallelCameraEqualsTheCpuPath) {
  FrameOptions o = options(160);
  ModelRenderer cpu(spot(), o);
  o.gpu_blend = true;
  ModelRenderer gpu(spot(), o);
  Camera camera = orbitCamera(spot().center(), 5.0, 70.0, 20.0, 30.0);
  camera.ortho_height = 2.2 * spot().extentRadius();
  Image a, b;
  (void)cpu.render(camera, a);
  (void)gpu.render(camera, b);
  expectSameImage(a, b, "spot_ortho");
}

// A grid of instances, each with its own view (so its own weights), colour and object matrix
// (rotation, uniform scale, translation), drawn in one call, against each instance blended on
// the CPU, transformed and drawn with drawMesh.
struct Crowd {
  std::vector<InstanceBlend> instances;
  View view;
  MeshStyle style;
};

Crowd crowd(const ViewDependentModel& model, int columns, int rows, int size) {
  Crowd c;
  c.view.viewport = {0, 0, size, size};
  const double spacing = 2.6 * model.extentRadius();
  const Eigen::Vector3d middle(0.5 * (columns - 1) * spacing, 0.5 * (rows - 1) * spacing, 0.0);
  c.view.camera.eye = middle + Eigen::Vector3d(0.0, 0.0, 1.2 * std::max(columns, rows) * spacing + 4.0);
  c.view.camera.target = middle;
  c.view.camera.up = Eigen::Vector3d::UnitY();
  c.view.camera.fov_deg = 50.0;
  c.view.z_near = 0.5;
  c.view.z_far = 200.0;
  const std::array<Rgb, 4> colours{Rgb{1.0f, 1.0f, 1.0f}, Rgb{0.9f, 0.25f, 0.2f}, Rgb{0.55f, 0.3f, 0.9f},
                                   Rgb{0.3f, 0.8f, 0.5f}};
  for (int r = 0; r < rows; ++r)
    for (int col = 0; col < columns; ++col) {
      const int i = r * columns + col;
      const Eigen::Vector3d offset(col * spacing, r * spacing, 0.0);
      const double turn = 0.7 * i;
      const Eigen::Affine3d object = Eigen::Translation3d(offset) *
                                     Eigen::AngleAxisd(turn, Eigen::Vector3d(0.2, 1.0, 0.1).normalized()) *
                                     Eigen::Scaling(0.8 + 0.05 * (i % 5)) * Eigen::Translation3d(-model.center());
      InstanceBlend instance;
      instance.object = object.matrix().cast<float>();
      // The view direction in model space: from the instance's centre towards the eye.
      const Eigen::Vector3d eye_model = object.inverse() * c.view.camera.eye;
      if (!model.weights(model.viewFromEye(eye_model), 0.0, instance.weights)) ADD_FAILURE() << "weights";
      instance.color = colours[static_cast<std::size_t>(i) % colours.size()];
      c.instances.push_back(instance);
    }
  c.style.silhouette_width = 2.5f;
  return c;
}

void drawCrowdOnTheCpu(Renderer& r, int mesh, const ViewDependentModel& model, const Crowd& c) {
  std::vector<float> positions(model.vertexCount() * 3);
  for (const InstanceBlend& instance : c.instances) {
    ASSERT_TRUE(model.blend(instance.weights, positions));
    for (std::size_t v = 0; v < model.vertexCount(); ++v) {
      const Eigen::Vector4f p =
          instance.object * Eigen::Vector4f(positions[v * 3], positions[v * 3 + 1], positions[v * 3 + 2], 1.0f);
      for (int i = 0; i < 3; ++i) positions[v * 3 + i] = p[i];
    }
    ASSERT_TRUE(r.updateMesh(mesh, positions, {}));
    MeshStyle style = c.style;
    style.color = instance.color;
    ASSERT_TRUE(r.drawMesh(mesh, c.view, style));
  }
}

TEST(GpuBlend, ManyInstancesWithTheirOwnViewsEqualTheCpuPathInOneCall) {
  for (const ViewDependentModel* model : {&bumpy(), &spot()}) {
    const Crowd c = crowd(*model, 5, 4, 256);
    Renderer cpu(RendererSettings{256, 256, 8});
    const int mesh = cpu.addSurface(model->base(), model->surface());
    cpu.clear({0.97f, 0.97f, 0.95f});
    drawCrowdOnTheCpu(cpu, mesh, *model, c);
    Image a, b;
    cpu.readPixels(a);
    Renderer gpu(RendererSettings{256, 256, 8});
    const int handle = gpu.addBlendModel(*model);
    gpu.clear({0.97f, 0.97f, 0.95f});
    ASSERT_TRUE(gpu.drawBlendInstances(handle, c.instances, c.view, c.style));
    gpu.readPixels(b);
    expectSameImage(a, b, model == &spot() ? "crowd_spot" : "crowd_bumpy");
    // The comparison sees the view dependence: the same crowd all-base is another picture.
    std::vector<InstanceBlend> base = c.instances;
    for (InstanceBlend& i : base) i.weights = ViewWeights{{-1, -1, -1}, {0, 0, 0}, 1.0f, -1};
    gpu.clear({0.97f, 0.97f, 0.95f});
    ASSERT_TRUE(gpu.drawBlendInstances(handle, base, c.view, c.style));
    gpu.readPixels(b);
    const Difference d = difference(a, b);
    EXPECT_TRUE(d.differing_fraction > kMaxDifferingFraction || d.mean > kMaxMeanDifference)
        << d.differing_fraction << " " << d.mean;
    // The views differ: not every instance has the same weights.
    bool different = false;
    for (const InstanceBlend& i : c.instances) different |= i.weights.key != c.instances[0].weights.key;
    EXPECT_TRUE(different);
  }
}

TEST(GpuBlend, PositionsAndGroupNormalsEqualTheCpuBlend) {
  const ViewDependentModel& model = spot();
  const Crowd c = crowd(model, 4, 3, 64);
  Renderer r(RendererSettings{64, 64, 1});
  const int handle = r.addBlendModel(model);
  ASSERT_TRUE(r.drawBlendInstances(handle, c.instances, c.view, c.style));
  const SurfaceTopology& t = model.surface();
  std::vector<float> cpu(model.vertexCount() * 3), gpu(cpu.size()), cpu_normals(t.groupCount() * 3),
      gpu_normals(cpu_normals.size());
  const double scale = model.extentRadius() + model.center().norm() + 3.0 * 2.6 * model.extentRadius();
  for (std::size_t i = 0; i < c.instances.size(); ++i) {
    const InstanceBlend& instance = c.instances[i];
    ASSERT_TRUE(model.blend(instance.weights, cpu));
    for (std::size_t v = 0; v < model.vertexCount(); ++v) {
      const Eigen::Vector4f p = instance.object * Eigen::Vector4f(cpu[v * 3], cpu[v * 3 + 1], cpu[v * 3 + 2], 1.0f);
      for (int k = 0; k < 3; ++k) cpu[v * 3 + k] = p[k];
    }
    ASSERT_TRUE(computeGroupNormals(t, cpu, cpu_normals));
    ASSERT_TRUE(r.readBlendInstance(handle, i, gpu, gpu_normals));
    double worst = 0.0, worst_normal = 0.0;
    for (std::size_t k = 0; k < cpu.size(); ++k) worst = std::max(worst, double(std::abs(cpu[k] - gpu[k])));
    for (std::size_t k = 0; k < cpu_normals.size(); ++k)
      worst_normal = std::max(worst_normal, double(std::abs(cpu_normals[k] - gpu_normals[k])));
    EXPECT_LE(worst, kPositionTol * scale) << "instance " << i;
    EXPECT_LE(worst_normal, kNormalTol) << "instance " << i;
  }
}

// ---------------------------------------------------------------------------------------------
// Contract.

class GpuBlendContract : public ::testing::Test {
 protected:
  void SetUp() override {
    handle = r.addBlendModel(bumpy());
    view.viewport = {0, 0, 64, 64};
    view.camera.eye = {0, 0, 5};
    view.camera.target = {0, 0, 0};
    view.camera.up = {0, 1, 0};
    view.camera.fov_deg = 35;
    instance.weights.key = {0, 1, -1};
    instance.weights.weight = {0.5f, 0.25f, 0.0f};
    instance.weights.base = 0.25f;
    r.clear({1, 1, 1});
    ASSERT_TRUE(r.drawBlendInstances(handle, {&instance, 1}, view, style));
    r.readPixels(before);
  }
  // The call was refused and changed no pixel.
  void expectRefused(const InstanceBlend& i, const View& v, int h) {
    EXPECT_FALSE(r.drawBlendInstances(h, {&i, 1}, v, style));
    Image after;
    r.readPixels(after);
    EXPECT_EQ(before.rgba, after.rgba);
  }
  Renderer r{RendererSettings{64, 64, 1}};
  int handle = -1;
  View view;
  InstanceBlend instance;
  MeshStyle style;
  Image before;
};

TEST_F(GpuBlendContract, RefusesBadHandles) {
  const int mesh = r.addMesh(std::vector<std::int32_t>{0, 1, 2}, 3);
  EXPECT_EQ(mesh, 0);  // a mesh handle is not a blend handle: blend handle 0 exists, 1 does not
  expectRefused(instance, view, -1);
  expectRefused(instance, view, 1);
}

TEST_F(GpuBlendContract, RefusesInvalidViews) {
  View v = view;
  v.viewport.width = 0;
  expectRefused(instance, v, handle);
  v = view;
  v.camera.target = v.camera.eye;
  expectRefused(instance, v, handle);
  v = view;
  v.z_near = 0.0;
  expectRefused(instance, v, handle);
}

TEST_F(GpuBlendContract, RefusesBadInstances) {
  const int keys = static_cast<int>(bumpy().keyCount());
  for (const int bad_key : {keys, -2}) {
    InstanceBlend i = instance;
    i.weights.key[1] = bad_key;
    expectRefused(i, view, handle);
  }
  InstanceBlend i = instance;
  i.weights.weight[0] = std::nanf("");
  expectRefused(i, view, handle);
  i = instance;
  i.object(1, 3) = INFINITY;
  expectRefused(i, view, handle);
  i = instance;
  i.color[2] = std::nanf("");
  expectRefused(i, view, handle);
  // One bad instance among good ones refuses the whole call.
  std::vector<InstanceBlend> several(3, instance);
  several[2].weights.key[0] = keys;
  EXPECT_FALSE(r.drawBlendInstances(handle, several, view, style));
}

TEST_F(GpuBlendContract, EmptyDrawsNothingAndReadBackChecksItsInput) {
  r.clear({1, 1, 1});
  Image cleared, after;
  r.readPixels(cleared);
  EXPECT_TRUE(r.drawBlendInstances(handle, {}, view, style));
  r.readPixels(after);
  EXPECT_EQ(cleared.rgba, after.rgba);
  std::vector<float> p(bumpy().vertexCount() * 3), n(bumpy().surface().groupCount() * 3);
  ASSERT_TRUE(r.drawBlendInstances(handle, {&instance, 1}, view, style));
  EXPECT_TRUE(r.readBlendInstance(handle, 0, p, n));
  EXPECT_FALSE(r.readBlendInstance(handle, 1, p, n));
  EXPECT_FALSE(r.readBlendInstance(1, 0, p, n));
  EXPECT_FALSE(r.readBlendInstance(handle, 0, std::span<float>(p).first(3), n));
  EXPECT_FALSE(r.readBlendInstance(handle, 0, p, {}));
}

TEST(GpuBlendErrors, AnOpenGl33ContextRefusesTheGpuBlendClearly) {
  ::setenv("VDG_RENDER_GL", "3.3", 1);
  Renderer r(RendererSettings{16, 16, 1});
  ::unsetenv("VDG_RENDER_GL");
  try {
    (void)r.addBlendModel(bumpy());
    FAIL() << "expected vdg::Error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("OpenGL: the GPU blend (--gpu-blend) needs OpenGL 4.3 (the driver gives 3.3"),
              std::string::npos)
        << e.what();
  }
}

TEST(GpuBlendErrors, ModelRendererRefusesAPlainMesh) {
  FrameOptions o = options(32);
  o.gpu_blend = true;
  try {
    ModelRenderer r(bumpy().base(), o);
    FAIL() << "expected vdg::Error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("a plain mesh has no keys to blend"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace vdg::render
