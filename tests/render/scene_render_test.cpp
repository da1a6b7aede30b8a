// SceneRenderer: scenes of view-dependent instances (Rademacher 99, section 5) rendered headless.
// Properties: an instance is blended for its own view (turning the whole world, instance and
// camera together, gives the same picture as the model alone), a frame rendered alone equals the
// same frame of a sequence byte for byte, node colours reach the shading, base_only drops the
// keys, a scene without a camera is framed whole.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <memory>
#include <numbers>

#include "render/test_models.h"
#include "vdg/geom/error.h"
#include "vdg/render/model_renderer.h"
#include "vdg/render/scene_renderer.h"
#include "vdg/scene/scene.h"

namespace vdg::render {
namespace {

constexpr int kSize = 128;
// Two renders of the same picture through different float paths (positions carried by a node's
// transform versus drawn in place) may differ at edge pixels: a channel counts as different above
// kChannelTolerance, and at most kMaxDifferingFraction of the pixels may.
constexpr int kChannelTolerance = 40;
constexpr double kMaxDifferingFraction = 0.02;
constexpr double kDegToRad = std::numbers::pi / 180.0;

std::shared_ptr<const ViewDependentModel> sharedModel() {
  static const auto model = std::make_shared<const ViewDependentModel>(ViewDependentModel::build(bumpyModel()));
  return model;
}

// A camera node at `eye` looking at the origin (look_at a group at the origin).
scene::RawScene sceneWithCamera(const Eigen::Vector3d& eye) {
  scene::RawScene raw;
  scene::RawNode origin;
  origin.name = "origin";
  raw.nodes.push_back(origin);
  scene::RawNode cam;
  cam.name = "camera";
  cam.kind = scene::ObjectKind::kCamera;
  cam.link.translation = eye;
  cam.look_at = "origin";
  cam.fov_deg = 35.0;
  raw.nodes.push_back(cam);
  return raw;
}

int addInstance(scene::RawScene& raw, const std::string& name, const Eigen::Vector3d& at,
                const Eigen::Quaterniond& rotation, const Rgb& color = {1, 1, 1}) {
  if (raw.models.empty()) raw.models.push_back(sharedModel());
  scene::RawNode n;
  n.name = name;
  n.kind = scene::ObjectKind::kModel;
  n.object = 0;
  n.link.translation = at;
  n.link.rotation = rotation;
  n.color = color;
  raw.nodes.push_back(n);
  return static_cast<int>(raw.nodes.size()) - 1;
}

// A CHANGE action turning `node` half a turn about Y over frames 0 to 10.
void addHalfTurn(scene::RawScene& raw, int node) {
  scene::RawAction spin;
  spin.kind = scene::RawAction::Kind::kChange;
  spin.node = node;
  spin.field = scene::Field::kRotation;
  const Eigen::Quaterniond q(Eigen::AngleAxisd(std::numbers::pi, Eigen::Vector3d::UnitY()));
  spin.value = Eigen::Vector4d(q.w(), q.x(), q.y(), q.z());
  spin.from_frame = 0;
  spin.to_frame = 10;
  raw.actions.push_back(spin);
}

SceneFrameOptions smallOptions() {
  SceneFrameOptions o;
  o.width = o.height = kSize;
  return o;
}

void expectSimilar(const Image& a, const Image& b) {
  const ImageDiff d = compareImages(a, b, kChannelTolerance);
  ASSERT_TRUE(d.same_size);
  EXPECT_LE(d.differing_fraction, kMaxDifferingFraction) << d.differing_pixels << " pixels differ";
}

TEST(SceneRender, AnInstanceIsBlendedForItsOwnViewInItsOwnFrame) {
  // The model turned by 70 degrees about Y, the camera on +Z: the instance sees the camera from
  // 70 degrees to its own right of its front, so the picture is that of the model alone seen from
  // there, turned with the world. The model alone: ModelRenderer from the rotated-back eye.
  const Eigen::Quaterniond turn(Eigen::AngleAxisd(70.0 * kDegToRad, Eigen::Vector3d::UnitY()));
  const Eigen::Vector3d eye(0, 0, 5);
  scene::RawScene raw = sceneWithCamera(eye);
  addInstance(raw, "turned", Eigen::Vector3d::Zero(), turn);
  const scene::Scene s = scene::Scene::build(raw);
  SceneRenderer sr(s, smallOptions());
  Image in_scene;
  sr.render(0.0, in_scene);
  EXPECT_EQ(sr.drawnCount(), 1);

  // The same picture: a ModelRenderer whose camera is the scene camera carried into the
  // instance's frame (eye and up rotated back); the image is the same since the whole world
  // turned together.
  FrameOptions fo;
  fo.width = fo.height = kSize;
  ModelRenderer mr(*sharedModel(), fo);
  Camera c;
  c.eye = turn.inverse() * eye;
  c.target = Eigen::Vector3d::Zero();
  c.up = turn.inverse() * Eigen::Vector3d::UnitY();
  c.fov_deg = 35.0;
  Image alone;
  mr.render(c, alone);
  expectSimilar(in_scene, alone);

  // And not the picture of an unturned instance (the view direction matters).
  scene::RawScene straight = sceneWithCamera(eye);
  addInstance(straight, "straight", Eigen::Vector3d::Zero(), Eigen::Quaterniond::Identity());
  const scene::Scene s2 = scene::Scene::build(straight);
  SceneRenderer sr2(s2, smallOptions());
  Image unturned;
  sr2.render(0.0, unturned);
  EXPECT_GT(compareImages(in_scene, unturned, kChannelTolerance).differing_fraction, kMaxDifferingFraction);
}

// Part drivers (scene.h): bumpyModel with its keys copied into a part "all" that covers every
// vertex and holds the top view. Driven by a node at the camera's eye, the part follows the camera
// and the picture is the plain model's; undriven, it keeps the top key's bump.
TEST(SceneRender, APartDrivenByANodeAtTheEyeDrawsWhatTheCameraSees) {
  RawViewDependentModel raw = bumpyModel();
  RawPart all;
  all.name = "all";
  for (std::size_t v = 0; v < raw.base.vertexCount(); ++v) all.vertices.push_back(static_cast<std::int32_t>(v));
  all.view = Eigen::Vector3d::UnitY();
  for (std::size_t k = 0; k < 3; ++k) {
    RawKey copy = raw.keys[k];
    copy.name = "all-" + copy.name;
    all.keys.push_back(copy.name);
    raw.keys.push_back(copy);
  }
  raw.parts.push_back(all);
  const auto parts_model = std::make_shared<const ViewDependentModel>(ViewDependentModel::build(raw));
  const Eigen::Vector3d eye(0.4, 0.2, 5);
  auto render = [&](bool parts, bool driven) {
    scene::RawScene sc = sceneWithCamera(eye);
    if (parts) sc.models.push_back(parts_model);
    addInstance(sc, "ball", Eigen::Vector3d::Zero(), Eigen::Quaterniond::Identity());
    scene::RawNode muse;
    muse.name = "muse";
    muse.link.translation = eye;
    sc.nodes.push_back(muse);
    if (driven) sc.nodes[2].part_drivers = {{"all", "muse"}};
    const scene::Scene s = scene::Scene::build(sc);
    SceneRenderer sr(s, smallOptions());
    Image image;
    sr.render(0.0, image);
    return image;
  };
  const Image plain = render(false, false);
  expectSimilar(render(true, true), plain);
  EXPECT_GT(compareImages(render(true, false), plain, kChannelTolerance).differing_fraction, kMaxDifferingFraction);
}

TEST(SceneRender, BaseOnlyDropsTheKeys) {
  scene::RawScene raw = sceneWithCamera(Eigen::Vector3d(0, 0, 5));
  addInstance(raw, "a", Eigen::Vector3d::Zero(), Eigen::Quaterniond::Identity());
  const scene::Scene s = scene::Scene::build(raw);
  SceneFrameOptions o = smallOptions();
  SceneRenderer with(s, o);
  o.base_only = true;
  SceneRenderer without(s, o);
  Image a, b;
  with.render(0.0, a);
  without.render(0.0, b);
  // Seen from the front key's view the front key's bump shows; without keys it does not.
  EXPECT_GT(compareImages(a, b, kChannelTolerance).differing_fraction, kMaxDifferingFraction);
}

TEST(SceneRender, FrameAloneIsByteIdenticalToTheSameFrameOfASequence) {
#if defined(__SANITIZE_ADDRESS__)
  // Under ASan this test passes, but LeakSanitizer's exit-time check then crashes in its own
  // thread tracer ("Tracer caught signal 11") while llvmpipe's worker threads wind down, reliably
  // for this test only. The property is checked in the ci build, and across processes by
  // RunCli.FramesAreWrittenAndARangeEqualsTheSameFramesOfAFullRun.
  GTEST_SKIP() << "LeakSanitizer's tracer crashes at exit after this test on llvmpipe";
#endif
  scene::RawScene raw = sceneWithCamera(Eigen::Vector3d(1, 1, 6));
  const int a = addInstance(raw, "a", Eigen::Vector3d(-1.2, 0, 0), Eigen::Quaterniond::Identity(), {0.9f, 0.3f, 0.3f});
  addInstance(raw, "b", Eigen::Vector3d(1.2, 0, 0), Eigen::Quaterniond::Identity(), {0.3f, 0.4f, 0.9f});
  addHalfTurn(raw, a);
  const scene::Scene s = scene::Scene::build(raw);

  // Frame 6 first, on a fresh renderer; then the whole sequence on the same one: frame 6 does not
  // depend on what was drawn before it. (Separate processes: RunCli's --frames test.)
  SceneRenderer renderer(s, smallOptions());
  Image f6_alone, frame, f6_in_sequence;
  renderer.render(6, f6_alone);
  for (int f = 0; f <= 9; ++f) {
    renderer.render(f, frame);
    if (f == 6) f6_in_sequence = frame;
  }
  EXPECT_EQ(f6_alone.rgba, f6_in_sequence.rgba);
  Image f0;
  renderer.render(0, f0);
  EXPECT_NE(f0.rgba, f6_alone.rgba);  // the spin shows
}

TEST(SceneRender, NodeColoursReachTheShading) {
  // A node's colour is its object's Cbase, with the hue rule of shading.h: the picture equals the
  // model alone rendered with that colour, and two colours give two pictures.
  const Eigen::Vector3d eye(0, 0, 5);
  Camera c;
  c.eye = eye;
  c.fov_deg = 35.0;
  Image first;
  for (const Rgb& color : {Rgb{0.9f, 0.1f, 0.1f}, Rgb{0.1f, 0.2f, 0.9f}}) {
    scene::RawScene raw = sceneWithCamera(eye);
    addInstance(raw, "coloured", Eigen::Vector3d::Zero(), Eigen::Quaterniond::Identity(), color);
    const scene::Scene s = scene::Scene::build(raw);
    SceneRenderer sr(s, smallOptions());
    Image in_scene;
    sr.render(0, in_scene);
    FrameOptions fo;
    fo.width = fo.height = kSize;
    fo.color = color;
    ModelRenderer mr(*sharedModel(), fo);
    Image alone;
    mr.render(c, alone);
    expectSimilar(in_scene, alone);
    if (first.rgba.empty())
      first = in_scene;
    else
      EXPECT_GT(compareImages(first, in_scene, kChannelTolerance).differing_fraction, 0.2);
  }
}

TEST(SceneRender, HiddenNodesAreNotDrawn) {
  scene::RawScene raw = sceneWithCamera(Eigen::Vector3d(0, 0, 7));
  addInstance(raw, "shown", Eigen::Vector3d(-1.2, 0, 0), Eigen::Quaterniond::Identity());
  const int hidden = addInstance(raw, "hidden", Eigen::Vector3d(1.2, 0, 0), Eigen::Quaterniond::Identity());
  raw.nodes[hidden].visible = false;
  const scene::Scene s = scene::Scene::build(raw);
  SceneRenderer sr(s, smallOptions());
  Image img;
  sr.render(0, img);
  EXPECT_EQ(sr.drawnCount(), 1);
}

TEST(SceneRender, ASceneWithoutACameraIsFramedWhole) {
  // Two instances far apart, no camera: the automatic camera sees both, and nothing touches the
  // image border (the framing has a margin).
  scene::RawScene raw;
  raw.models.push_back(sharedModel());
  for (int i = 0; i < 2; ++i) {
    scene::RawNode n;
    n.name = i ? "right" : "left";
    n.kind = scene::ObjectKind::kModel;
    n.object = 0;
    n.link.translation = Eigen::Vector3d(i ? 6.0 : -6.0, 0, 0);
    raw.nodes.push_back(n);
  }
  const scene::Scene s = scene::Scene::build(raw);
  SceneRenderer sr(s, smallOptions());
  Image img;
  sr.render(0, img);
  const Rgb bg = smallOptions().background;
  auto isBg = [&](int x, int y) {
    const std::uint8_t* p = img.pixel(x, y);
    for (int c = 0; c < 3; ++c)
      if (std::abs(int(p[c]) - int(std::lround(bg[c] * 255))) > 6) return false;
    return true;
  };
  long left = 0, right = 0;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      if (isBg(x, y)) continue;
      (x < img.width / 2 ? left : right) += 1;
      EXPECT_TRUE(x > 0 && y > 0 && x < img.width - 1 && y < img.height - 1) << "object pixel on the border";
    }
  EXPECT_GT(left, 50);
  EXPECT_GT(right, 50);
}

// The GPU blend (SceneFrameOptions::gpu_blend) draws every instance of a model in one call; the
// picture equals the CPU path's up to rounding at edge pixels: at most kGpuMaxDifferingFraction of
// the pixels differ by more than kGpuChannelTolerance levels in a channel.
constexpr int kGpuChannelTolerance = 48;
constexpr double kGpuMaxDifferingFraction = 0.004;

TEST(SceneRender, TheGpuBlendDrawsTheSamePictureAsTheCpuPath) {
  // Seven instances turned and coloured differently (each blended for its own view), one of them
  // spinning, and a plain mesh that stays on the CPU path, at three frames. They do not overlap in
  // the picture: where objects overlap the two paths ink in another order (see gpu_blend in
  // scene_renderer.h), and the GPU path's picture is then the better one.
  scene::RawScene raw = sceneWithCamera(Eigen::Vector3d(1.0, 2.0, 14.0));
  int spinning = -1;
  for (int i = 0; i < 7; ++i) {
    const double angle = (i * 47.0 - 120.0) * kDegToRad;
    const Eigen::Quaterniond turn(Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitY()));
    const int node = addInstance(raw, "cow" + std::to_string(i), Eigen::Vector3d(2.5 * (i - 3), 0, -0.6 * (i % 2)),
                                 turn, {0.3f + 0.1f * i, 0.9f - 0.1f * i, 0.6f});
    if (i == 3) spinning = node;
  }
  raw.meshes.push_back(std::make_shared<const TriMesh>(uvSphere(12, 16)));
  scene::RawNode ball;
  ball.name = "ball";
  ball.kind = scene::ObjectKind::kMesh;
  ball.object = 0;
  ball.link.translation = Eigen::Vector3d(0, 2.7, 0);
  ball.link.scale = Eigen::Vector3d::Constant(0.5);
  raw.nodes.push_back(ball);
  addHalfTurn(raw, spinning);
  const scene::Scene s = scene::Scene::build(raw);

  SceneFrameOptions o = smallOptions();
  o.width = 2 * kSize;
  SceneRenderer cpu(s, o);
  o.gpu_blend = true;
  SceneRenderer gpu(s, o);
  Image a, b;
  for (const double frame : {0.0, 4.0, 10.0}) {
    cpu.render(frame, a);
    gpu.render(frame, b);
    EXPECT_EQ(cpu.drawnCount(), 8);
    EXPECT_EQ(gpu.drawnCount(), 8);
    const ImageDiff d = compareImages(a, b, kGpuChannelTolerance);
    ASSERT_TRUE(d.same_size);
    EXPECT_LE(d.differing_fraction, kGpuMaxDifferingFraction)
        << "frame " << frame << ": " << d.differing_pixels << " pixels differ";
  }
  // The spin shows on the GPU path too (the comparison is not between two empty pictures).
  Image first;
  gpu.render(0.0, first);
  EXPECT_GT(compareImages(first, b, kGpuChannelTolerance).differing_fraction, kGpuMaxDifferingFraction);
}

TEST(SceneRender, ANonFiniteFrameIsOneClearError) {
  scene::RawScene raw = sceneWithCamera(Eigen::Vector3d(0, 0, 5));
  addInstance(raw, "a", Eigen::Vector3d::Zero(), Eigen::Quaterniond::Identity());
  const scene::Scene s = scene::Scene::build(raw);
  SceneRenderer sr(s, smallOptions());
  Image img;
  EXPECT_THROW(sr.render(std::nan(""), img), Error);
}

}  // namespace
}  // namespace vdg::render
