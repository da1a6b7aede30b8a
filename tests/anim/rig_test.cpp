// Rig: samplers (STEP, LINEAR, CUBICSPLINE) against the glTF Appendix C formulas worked by hand,
// the per-frame contract (refusals write nothing, nothing allocates), and every validate() error.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "support/allocation_counter.h"
#include "support/error_of.h"
#include "vdg/anim/rig.h"

namespace vdg {
namespace {

using vdg::testing::allocationsDuring;
using vdg::testing::errorOf;

constexpr double kTol = 1e-6;  // float outputs of double arithmetic

// One triangle on node 1 (child of node 0, translated by (0, 0, 5)), one morph target moving
// vertex 2 by (0, 1, 0), and one animation with a translation channel on node 0 and a weights
// channel on node 1.
RawRig triangleRig(RigInterpolation mode) {
  RawRig raw;
  raw.source = "r";
  raw.nodes.resize(2);
  raw.nodes[1].parent = 0;
  raw.nodes[1].translation = {0, 0, 5};
  raw.mesh_node = 1;
  raw.mesh.positions = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  raw.mesh.triangles = {0, 1, 2};
  raw.target_positions = {{0, 0, 0, 0, 0, 0, 0, 1, 0}};
  raw.target_normals = {{}};
  raw.default_weights = {0.25};
  RigAnimation anim;
  anim.name = "a";
  RigSampler tr;
  tr.interpolation = mode;
  tr.input = {0, 2};
  RigSampler w = tr;
  if (mode == RigInterpolation::kCubicSpline) {
    // in-tangent, value, out-tangent per keyframe
    tr.output = {0, 0, 0, 0, 0, 0, 1, 0, 0, /**/ 0, 0, 0, 4, 0, 0, 0, 0, 0};
    w.output = {0, 0, 0, /**/ 0, 1, 0};
  } else {
    tr.output = {0, 0, 0, 4, 0, 0};
    w.output = {0, 1};
  }
  anim.samplers = {tr, w};
  anim.channels = {{0, RigPath::kTranslation, 0}, {1, RigPath::kWeights, 1}};
  raw.animations = {anim};
  return raw;
}

TEST(Rig, RestPoseAppliesDefaultWeightsAndNodeTransforms) {
  const Rig rig = Rig::build(triangleRig(RigInterpolation::kLinear));
  std::vector<float> p(9);
  ASSERT_TRUE(rig.evaluate(-1, 0, p));
  EXPECT_EQ(p, (std::vector<float>{0, 0, 5, 1, 0, 5, 0, 1.25f, 5}));
  EXPECT_EQ(rig.duration(-1), 0);
  EXPECT_EQ(rig.duration(0), 2);
  EXPECT_EQ(rig.animationName(0), "a");
  EXPECT_EQ(errorOf([&] { (void)rig.animationName(1); }), "animation 1 out of range (the rig has 1 animations)");
}

TEST(Rig, SamplersFollowAppendixC) {
  for (RigInterpolation mode : {RigInterpolation::kStep, RigInterpolation::kLinear, RigInterpolation::kCubicSpline}) {
    const Rig rig = Rig::build(triangleRig(mode));
    std::vector<float> p(9);
    for (double t : {-1.0, 0.0, 0.5, 1.0, 1.5, 2.0, 3.0}) {
      ASSERT_TRUE(rig.evaluate(0, t, p));
      const double s = std::clamp(t / 2, 0.0, 1.0);
      double x = 0, w = 0;
      if (mode == RigInterpolation::kStep) {
        x = t >= 2 ? 4 : 0, w = t >= 2 ? 1 : 0;
      } else if (mode == RigInterpolation::kLinear) {
        x = 4 * s, w = s;
      } else {
        // Hermite: p0 = 0, m0 = td * 1 (out-tangent 1), p1 = 4, m1 = 0; weights p0 0, p1 1, no tangents.
        const double h10 = s * s * s - 2 * s * s + s, h01 = -2 * s * s * s + 3 * s * s;
        x = 2 * 1 * h10 + 4 * h01;
        w = h01;
      }
      EXPECT_NEAR(p[0], x, kTol) << rigInterpolationName(mode) << " t " << t;
      EXPECT_NEAR(p[7], 1 + w, kTol) << rigInterpolationName(mode) << " t " << t;
      EXPECT_NEAR(p[8], 5, kTol);
    }
  }
}

TEST(Rig, RotationSlerpsTheShortestArcAndSkinsWithInverseBind) {
  // Joint node 0 rotates about z from 0 to 90 degrees; the keyframe at 90 is given as -q (the
  // long way round unless the sampler flips it). The vertex at (1, 0, 0) bound at the joint.
  RawRig raw;
  raw.nodes.resize(2);
  raw.mesh_node = 1;
  raw.mesh.positions = {1, 0, 0, 2, 0, 0, 1, 1, 0};
  raw.mesh.triangles = {0, 1, 2};
  raw.skin = RigSkin{{0}, {Eigen::Matrix4d::Identity()}};
  raw.joints = {0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0};
  raw.weights = {1, 0, 0, 0, 2, 0, 0, 0, 1, 0, 0, 0};  // weights are normalised by build
  const double h = std::sqrt(0.5);
  RigSampler r;
  r.input = {0, 1};
  r.output = {0, 0, 0, 1, 0, 0, static_cast<float>(-h), static_cast<float>(-h)};
  raw.animations = {RigAnimation{"turn", {r}, {{0, RigPath::kRotation, 0}}}};
  const Rig rig = Rig::build(raw);
  std::vector<float> p(9), skin(27);
  for (double t : {0.0, 0.25, 0.5, 1.0}) {
    ASSERT_TRUE(rig.evaluate(0, t, p, {}, skin));
    const double a = t * std::numbers::pi / 2;
    EXPECT_NEAR(p[0], std::cos(a), kTol) << t;
    EXPECT_NEAR(p[1], std::sin(a), kTol) << t;
    EXPECT_NEAR(skin[0], std::cos(a), kTol);
    EXPECT_NEAR(skin[1], std::sin(a), kTol);
    EXPECT_NEAR(skin[3], -std::sin(a), kTol);
  }
}

// nodePose: each node's local T, R (x y z w), S as the channels set them (used to re-sample an
// animation for glTF bakes).
TEST(Rig, NodePoseGivesEachNodesLocalTransformAtATime) {
  const Rig rig = Rig::build(triangleRig(RigInterpolation::kLinear));
  ASSERT_EQ(rig.nodeCount(), 2u);
  std::vector<double> pose(20, -7.0);
  ASSERT_TRUE(rig.nodePose(0, 0.5, pose));
  // Node 0: translation channel lerped to x = 4 * 0.25; node 1 keeps its rest translation.
  EXPECT_EQ(std::vector<double>(pose.begin(), pose.begin() + 10), (std::vector<double>{1, 0, 0, 0, 0, 0, 1, 1, 1, 1}));
  EXPECT_EQ(std::vector<double>(pose.begin() + 10, pose.end()), (std::vector<double>{0, 0, 5, 0, 0, 0, 1, 1, 1, 1}));
  ASSERT_TRUE(rig.nodePose(-1, 0.5, pose));
  EXPECT_EQ(pose[0], 0.0);
  std::vector<double> untouched(20, -7.0), short_pose(19, -7.0);
  EXPECT_FALSE(rig.nodePose(1, 0.5, untouched));
  EXPECT_FALSE(rig.nodePose(0, std::numeric_limits<double>::quiet_NaN(), untouched));
  EXPECT_FALSE(rig.nodePose(0, 0.5, short_pose));
  EXPECT_EQ(untouched, std::vector<double>(20, -7.0));
  EXPECT_EQ(allocationsDuring([&] { (void)rig.nodePose(0, 1.5, pose); }), 0);
}

TEST(Rig, ContractRefusesAndWritesNothingAndNeverAllocates) {
  const Rig rig = Rig::build(triangleRig(RigInterpolation::kCubicSpline));
  std::vector<float> p(9, -7), n(9, -7), s(27, -7), bad(8, -7);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  bool ok = true;
  EXPECT_EQ(allocationsDuring([&] {
              ok = !rig.evaluate(1, 0, p) && ok;
              ok = !rig.evaluate(-2, 0, p) && ok;
              ok = !rig.evaluate(0, nan, p) && ok;
              ok = !rig.evaluate(0, 0, bad) && ok;
              ok = !rig.evaluate(0, 0, p, bad) && ok;
              ok = !rig.evaluate(0, 0, p, n, bad) && ok;
            }),
            0);
  EXPECT_TRUE(ok);
  for (float v : p) EXPECT_EQ(v, -7);
  for (float v : n) EXPECT_EQ(v, -7);
  EXPECT_EQ(allocationsDuring([&] {
              for (int i = 0; i <= 100; ++i) ok = rig.evaluate(0, i * 0.03, p, n, s) && ok;
            }),
            0);
  EXPECT_TRUE(ok);
}

TEST(Rig, ValidateNamesTheElement) {
  auto expectError = [](auto mutate, const std::string& message) {
    RawRig raw = triangleRig(RigInterpolation::kLinear);
    mutate(raw);
    EXPECT_EQ(errorOf([&] { raw.validate(); }), message);
    EXPECT_EQ(errorOf([&] { (void)Rig::build(raw); }), message);
  };
  expectError([](RawRig& r) { r.nodes[1].parent = 5; }, "r: nodes[1]: parent 5 out of range (the rig has 2 nodes)");
  expectError([](RawRig& r) { r.nodes[0].parent = 1; },
              "r: nodes[0]: is its own ancestor (the node hierarchy has a cycle)");
  expectError([](RawRig& r) { r.nodes[0].parent = 0; },
              "r: nodes[0]: is its own ancestor (the node hierarchy has a cycle)");
  expectError([](RawRig& r) { r.nodes[0].translation.x() = NAN; }, "r: nodes[0]: translation is not finite");
  expectError([](RawRig& r) { r.nodes[0].rotation.coeffs().setZero(); },
              "r: nodes[0]: rotation is the zero quaternion");
  expectError([](RawRig& r) { r.mesh_node = 2; }, "r: mesh node 2 out of range (the rig has 2 nodes)");
  expectError([](RawRig& r) { r.mesh.triangles.clear(); }, "r: mesh: has no triangles");
  expectError([](RawRig& r) { r.normals = {0, 0, 1}; }, "r: mesh: NORMAL has 1 entries for 3 vertices");
  expectError([](RawRig& r) { r.target_positions[0].pop_back(); },
              "r: mesh: targets[0]: POSITION has 2 entries for 3 vertices");
  expectError([](RawRig& r) { r.default_weights.clear(); }, "r: mesh: 0 default weights for 1 targets");
  expectError([](RawRig& r) { r.joints = {0}; }, "r: mesh: JOINTS_0 / WEIGHTS_0 without a skin");
  expectError(
      [](RawRig& r) {
        r.skin = RigSkin{{0}, {Eigen::Matrix4d::Identity()}};
        r.joints.assign(12, 0);
        r.weights.assign(12, 0.25f);
        r.joints[5] = 3;
      },
      "r: mesh: vertex 1: joint 3 out of range (the skin has 1 joints)");
  expectError(
      [](RawRig& r) {
        r.skin = RigSkin{{0}, {Eigen::Matrix4d::Identity()}};
        r.joints.assign(12, 0);
        r.weights.assign(12, 0.0f);
      },
      "r: mesh: vertex 0: skin weights sum to 0");
  expectError(
      [](RawRig& r) {
        r.skin = RigSkin{{4}, {Eigen::Matrix4d::Identity()}};
      },
      "r: skin: joints[0]: node 4 out of range (the rig has 2 nodes)");
  expectError(
      [](RawRig& r) {
        r.animations[0].samplers[0].input = {1, 1};
      },
      "r: animations[0]: samplers[0]: input[1]: times must increase strictly");
  expectError(
      [](RawRig& r) {
        r.animations[0].samplers[0].input = {-1, 1};
      },
      "r: animations[0]: samplers[0]: input[0]: time -1.000000 is negative or not finite");
  expectError([](RawRig& r) { r.animations[0].samplers[0].output.pop_back(); },
              "r: animations[0]: samplers[0]: output has 5 values, expected 2 keyframes x 3");
  expectError([](RawRig& r) { r.animations[0].channels[0].node = 9; },
              "r: animations[0]: channels[0]: node 9 out of range (the rig has 2 nodes)");
  expectError([](RawRig& r) { r.animations[0].channels[0].sampler = 9; },
              "r: animations[0]: channels[0]: sampler 9 out of range (the animation has 2)");
  expectError([](RawRig& r) { r.animations[0].channels[1].node = 0; },
              "r: animations[0]: channels[1]: weights of node 0, not the mesh's node");
  expectError([](RawRig& r) { r.nodes[0].matrix = Eigen::Matrix4d::Identity(); },
              "r: animations[0]: channels[0]: translation of node 0, which is given by a matrix");
  expectError([](RawRig& r) { r.nodes.resize(kMaxRigNodes + 1); },
              "r: nodes: 100001 nodes, more than the limit of 100000");
}

}  // namespace
}  // namespace vdg
