// A glTF animated base read through the manifest (examples/walk: walker.glb, skinned, 40 frames
// at 24 fps, looping; Rademacher 99, section 4.3): the frames the loader samples against the
// generator's own poses, the keys at their frames and views, skinned against world offsets on a
// swinging forearm, and the errors of a bad base_animation.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <filesystem>
#include <numbers>
#include <string>
#include <vector>

#include "support/error_of.h"
#include "support/test_meshes.h"
#include "vdg/geom/error.h"
#include "vdg/io/gltf.h"
#include "vdg/io/manifest.h"
#include "vdg/io/obj.h"
#include "vdg/viewdep/animated_model.h"

namespace vdg {
namespace {

namespace fs = std::filesystem;
using testing::errorOf;

const fs::path kWalk = fs::path(VDG_SOURCE_DIR) / "examples/walk";
constexpr int kWalkFrames = 40;
constexpr std::size_t kWalkVertices = 3920;
// The loader samples the glb in float32 (joint matrices in double); base_f10/30.obj come from the
// generator's own skinning of the same float32 data, written with OBJ's decimal digits.
constexpr double kBaseTol = 1e-5;
// At a key's frame and view the model is the key mesh up to float rounding (offsets of ~0.3 m).
constexpr double kKeyTol = 1e-5;
// The forearm's rotation from three of its vertices, applied to offsets of ~0.1 m.
constexpr double kRotationTol = 1e-5;

double maxDifference(std::span<const float> a, std::span<const float> b) {
  EXPECT_EQ(a.size(), b.size());
  double worst = 0;
  for (std::size_t i = 0; i < std::min(a.size(), b.size()); ++i)
    worst = std::max(worst, std::abs(static_cast<double>(a[i]) - static_cast<double>(b[i])));
  return worst;
}

Eigen::Vector3d vertex(std::span<const float> positions, std::size_t v) {
  return {positions[3 * v], positions[3 * v + 1], positions[3 * v + 2]};
}

class GltfBase : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    skinned_raw_ = new RawViewDependentModel(loadManifest((kWalk / "walker.vdg.json").string()));
    world_raw_ = new RawViewDependentModel(loadManifest((kWalk / "walker-world.vdg.json").string()));
    skinned_ = new AnimatedViewDependentModel(AnimatedViewDependentModel::build(*skinned_raw_));
    world_ = new AnimatedViewDependentModel(AnimatedViewDependentModel::build(*world_raw_));
  }
  static void TearDownTestSuite() {
    delete skinned_raw_;
    delete world_raw_;
    delete skinned_;
    delete world_;
  }
  static std::vector<float> evaluate(const AnimatedViewDependentModel& m, int frame, const Eigen::Vector3d& view) {
    std::vector<float> out(3 * m.vertexCount());
    EXPECT_TRUE(m.evaluate(frame, view, 0.0, out)) << "frame " << frame;
    return out;
  }
  static TriMesh walkObj(const std::string& name) { return readObj((kWalk / name).string()); }

  static RawViewDependentModel* skinned_raw_;
  static RawViewDependentModel* world_raw_;
  static AnimatedViewDependentModel* skinned_;
  static AnimatedViewDependentModel* world_;
};
RawViewDependentModel* GltfBase::skinned_raw_ = nullptr;
RawViewDependentModel* GltfBase::world_raw_ = nullptr;
AnimatedViewDependentModel* GltfBase::skinned_ = nullptr;
AnimatedViewDependentModel* GltfBase::world_ = nullptr;

const Eigen::Vector3d kFront(0, 0, 1), kSide(1, 0, 0);

TEST_F(GltfBase, WalkerManifestsLoad) {
  for (const RawViewDependentModel* raw : {skinned_raw_, world_raw_}) {
    ASSERT_TRUE(raw->animated());
    EXPECT_EQ(raw->base_animation->gltf, "walker.glb");
    EXPECT_EQ(raw->base_animation->animation, 0);
    EXPECT_EQ(raw->base_animation->fps, 24.0);
    EXPECT_TRUE(raw->base_animation->loop);
    // 41 samples over 40/24 s with the last equal to the first: a loop of 40 frames.
    EXPECT_EQ(raw->frameCount(), static_cast<std::size_t>(kWalkFrames));
    EXPECT_EQ(raw->base.vertexCount(), kWalkVertices);
    EXPECT_EQ(raw->keys.size(), 4u);
  }
  EXPECT_EQ(skinned_raw_->offsets, OffsetSpace::kSkinned);
  EXPECT_EQ(skinned_raw_->base_skin.size(), static_cast<std::size_t>(kWalkFrames));
  EXPECT_EQ(world_raw_->offsets, OffsetSpace::kWorld);
  EXPECT_TRUE(world_raw_->base_skin.empty()) << "world offsets need no skin linear parts";
  for (const AnimatedViewDependentModel* m : {skinned_, world_}) {
    EXPECT_EQ(m->frameCount(), kWalkFrames);
    EXPECT_TRUE(m->loop());
    EXPECT_EQ(m->viewCount(), 2u) << "front and side, each with frames 10 and 30";
  }
}

// base_f10.obj and base_f30.obj are the generator's own skinning (independent of vdg's Rig).
TEST_F(GltfBase, SampledFramesAreTheGeneratorsPoses) {
  const TriMesh f10 = walkObj("base_f10.obj"), f30 = walkObj("base_f30.obj");
  ASSERT_EQ(f10.triangles, skinned_raw_->base.triangles);
  for (const RawViewDependentModel* raw : {skinned_raw_, world_raw_}) {
    EXPECT_LE(maxDifference(raw->base_frames[10], f10.positions), kBaseTol);
    EXPECT_LE(maxDifference(raw->base_frames[30], f30.positions), kBaseTol);
  }
  // The comparison discriminates: the two poses are far apart (the legs swap).
  EXPECT_GT(maxDifference(f10.positions, f30.positions), 0.1);
  EXPECT_GT(maxDifference(skinned_raw_->base_frames[10], f30.positions), 0.1);
}

TEST_F(GltfBase, KeysAtTheirFramesAndViews) {
  const struct {
    int frame;
    Eigen::Vector3d view;
    const char* key;
  } cases[] = {{10, kFront, "keys/front_f10.obj"},
               {30, kSide, "keys/side_f30.obj"},
               {10, kSide, "keys/side_f10.obj"},
               {30, kFront, "keys/front_f30.obj"}};
  for (const auto& c : cases) {
    const TriMesh key = walkObj(c.key);
    for (const AnimatedViewDependentModel* m : {skinned_, world_}) {
      EXPECT_LE(maxDifference(evaluate(*m, c.frame, c.view), key.positions), kKeyTol) << c.key;
      // ... and not the plain base there (the key really moves the limbs).
      EXPECT_GT(maxDifference(m->baseFrame(c.frame), key.positions), 0.05) << c.key;
    }
  }
}

TEST_F(GltfBase, SkinnedAndWorldOffsetsAgreeAtKeyFramesAndDifferBetween) {
  const Eigen::Vector3d between = Eigen::Vector3d(0.6, 0.2, 0.8).normalized();  // front and side blended
  for (int frame : {10, 30})
    for (const Eigen::Vector3d& view : {kFront, kSide, between})
      EXPECT_LE(maxDifference(evaluate(*skinned_, frame, view), evaluate(*world_, frame, view)), kKeyTol)
          << "frame " << frame << " view " << view.transpose();
  // Halfway between the key frames the limbs have swung, and the offsets with them.
  EXPECT_GT(maxDifference(evaluate(*skinned_, 20, kFront), evaluate(*world_, 20, kFront)), 0.01);
}

// Rotation of a rigid set of vertices between two frames, from three of them: the orthonormal
// frames built from two edges at each frame, R = F(to) * F(from)^T.
Eigen::Matrix3d edgeFrame(std::span<const float> p, std::size_t h, std::size_t a, std::size_t b) {
  const Eigen::Vector3d u = (vertex(p, a) - vertex(p, h)).normalized();
  const Eigen::Vector3d e = vertex(p, b) - vertex(p, h);
  const Eigen::Vector3d v = (e - e.dot(u) * u).normalized();
  Eigen::Matrix3d f;
  f << u, v, u.cross(v);
  return f;
}

// "offsets": "skinned" carries each key's offset in the vertex's skinning frame: a hand vertex
// (bound to the left forearm alone) keeps its exaggeration turned with the forearm. Checked from
// the geometry alone: the forearm's rotation between frames comes from the base's own vertices,
// the offsets from the key and base OBJ files, and the time weights from the symmetry of the
// periodic spline (key frames 10 and 30 in a 40-frame loop: frame 20 lies halfway both ways, so
// each key frame weighs 1/2).
TEST_F(GltfBase, SkinnedOffsetsTurnWithTheForearm) {
  const RawRig rig = readGltfRig((kWalk / "walker.glb").string());
  ASSERT_TRUE(rig.skin.has_value());
  int slot = -1;
  for (std::size_t s = 0; s < rig.skin->joints.size(); ++s)
    if (rig.nodes[static_cast<std::size_t>(rig.skin->joints[s])].name == "forearm_L") slot = static_cast<int>(s);
  ASSERT_GE(slot, 0) << "walker.glb has no joint forearm_L";
  std::vector<std::size_t> rigid;  // vertices bound to the forearm alone (the lower forearm and hand)
  for (std::size_t v = 0; v < rig.mesh.vertexCount(); ++v) {
    double on_forearm = 0, total = 0;
    for (int k = 0; k < 4; ++k) {
      total += rig.weights[4 * v + k];
      if (rig.joints[4 * v + k] == slot) on_forearm += rig.weights[4 * v + k];
    }
    if (on_forearm == total && total > 0) rigid.push_back(v);
  }
  ASSERT_GE(rigid.size(), 3u);
  // h: the hand's tip (lowest in the rest pose, arms hanging); a: the rigid vertex farthest from
  // it; b: the one making the widest triangle with both.
  const std::span<const float> rest = rig.mesh.positions;
  std::size_t h = rigid[0], a = rigid[0], b = rigid[0];
  for (std::size_t v : rigid)
    if (rest[3 * v + 1] < rest[3 * h + 1]) h = v;
  for (std::size_t v : rigid)
    if ((vertex(rest, v) - vertex(rest, h)).norm() > (vertex(rest, a) - vertex(rest, h)).norm()) a = v;
  const Eigen::Vector3d ha = vertex(rest, a) - vertex(rest, h);
  for (std::size_t v : rigid)
    if (ha.cross(vertex(rest, v) - vertex(rest, h)).norm() > ha.cross(vertex(rest, b) - vertex(rest, h)).norm()) b = v;

  const TriMesh base10 = walkObj("base_f10.obj"), base30 = walkObj("base_f30.obj");
  const std::span<const float> base20 = world_raw_->base_frames[20];
  const Eigen::Matrix3d f10 = edgeFrame(base10.positions, h, a, b), f20 = edgeFrame(base20, h, a, b),
                        f30 = edgeFrame(base30.positions, h, a, b);
  const Eigen::Matrix3d r10 = f20 * f10.transpose(), r30 = f20 * f30.transpose();
  // The set really is rigid (the frames describe its whole motion) ...
  for (std::size_t v : rigid) {
    const Eigen::Vector3d at20 = vertex(base20, v) - vertex(base20, h);
    ASSERT_LE((r10 * (vertex(base10.positions, v) - vertex(base10.positions, h)) - at20).norm(), kRotationTol) << v;
    ASSERT_LE((r30 * (vertex(base30.positions, v) - vertex(base30.positions, h)) - at20).norm(), kRotationTol) << v;
  }
  // ... and turns a lot between the key frames and frame 20 (the arm swings).
  EXPECT_GT(Eigen::AngleAxisd(r10).angle(), 10 * std::numbers::pi / 180);
  EXPECT_GT(Eigen::AngleAxisd(r30).angle(), 10 * std::numbers::pi / 180);

  // The time weights at frame 20 are 1/2 and 1/2, as the symmetry says.
  std::size_t front = 0;
  while (front < skinned_->viewCount() && !skinned_->viewDirection(front).isApprox(kFront)) ++front;
  ASSERT_LT(front, skinned_->viewCount());
  ASSERT_EQ(std::vector<int>(skinned_->keyFrames(front).begin(), skinned_->keyFrames(front).end()),
            (std::vector<int>{10, 30}));
  double c[2];
  ASSERT_TRUE(skinned_->timeCoefficients(front, 20.0, c));
  EXPECT_NEAR(c[0], 0.5, 1e-12);
  EXPECT_NEAR(c[1], 0.5, 1e-12);

  const Eigen::Vector3d d10 = vertex(walkObj("keys/front_f10.obj").positions, h) - vertex(base10.positions, h);
  const Eigen::Vector3d d30 = vertex(walkObj("keys/front_f30.obj").positions, h) - vertex(base30.positions, h);
  const Eigen::Vector3d world_expected = 0.5 * (d10 + d30);
  const Eigen::Vector3d skinned_expected = 0.5 * (r10 * d10 + r30 * d30);
  const Eigen::Vector3d world_got = vertex(evaluate(*world_, 20, kFront), h) - vertex(base20, h);
  const Eigen::Vector3d skinned_got = vertex(evaluate(*skinned_, 20, kFront), h) - vertex(base20, h);
  EXPECT_LE((world_got - world_expected).norm(), kRotationTol) << world_got.transpose();
  EXPECT_LE((skinned_got - skinned_expected).norm(), kRotationTol) << skinned_got.transpose();
  // The two predictions differ by far more than the tolerance, so the checks tell the modes apart.
  EXPECT_GT((skinned_expected - world_expected).norm(), 100 * kRotationTol);
}

// A bad base_animation names the manifest and the field.
class GltfBaseErrors : public ::testing::Test {
 protected:
  void SetUp() override {
    fs::copy_file(kWalk / "walker.glb", dir_.path() / "walker.glb");
    fs::create_directories(dir_.path() / "keys");
    fs::copy_file(kWalk / "keys/front_f10.obj", dir_.path() / "keys/front_f10.obj");
  }
  // The message with this test's folder left out of the paths.
  std::string loadError(const std::string& base_animation) {
    const std::string path = dir_.file("m.vdg.json");
    testing::writeText(path, R"({"version": 2, "base_animation": )" + base_animation +
                                 R"(, "keys": [{"mesh": "keys/front_f10.obj", "view": [0, 0, 1], "frame": 10}]})");
    std::string message = errorOf([&] { (void)loadManifest(path); });
    const std::string folder = dir_.path().string() + "/";
    for (std::size_t at; (at = message.find(folder)) != std::string::npos;) message.erase(at, folder.size());
    return message;
  }
  testing::TempDir dir_;
};

TEST_F(GltfBaseErrors, EachGivesItsMessage) {
  // The same manifest with the right fields loads (so the errors below come from the one field).
  EXPECT_EQ(loadError(R"({"gltf": "walker.glb", "animation": 0, "mesh": "Body", "fps": 24, "loop": true})"), "");
  EXPECT_EQ(loadError(R"({"gltf": "nowhere.glb"})"),
            "m.vdg.json: base_animation.gltf: nowhere.glb: no such file (glTF)");
  EXPECT_EQ(loadError(R"({"gltf": "walker.glb", "animation": 1})"),
            "m.vdg.json: base_animation.animation: 1 is out of range (walker.glb has 1 animation)");
  EXPECT_EQ(loadError(R"({"gltf": "walker.glb", "mesh": "Nobody"})"),
            "m.vdg.json: base_animation.gltf: walker.glb: no node or mesh named 'Nobody'");
}

}  // namespace
}  // namespace vdg
