// Skeleton (wire) deformation, Burtnyk and Wein after Parent 4.10 (vdg/deform/skeleton.h): the
// identities, rigid motions, continuity of a bend across the dividing plane, vertices on the wire,
// the contract of apply(), and the `skeleton` edit op (JSON, edit log replay, messages).
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>
#include <random>

#include "support/allocation_counter.h"
#include "support/error_of.h"
#include "support/test_meshes.h"
#include "test_meshes.h"
#include "vdg/deform/edits.h"
#include "vdg/deform/key_edit.h"
#include "vdg/deform/skeleton.h"
#include "vdg/io/edit_script.h"

namespace vdg {
namespace {

using testing::errorOf;
using Joints = std::vector<Eigen::Vector3d>;

// The issue's tolerances. Positions are floats: 1e-6 is a few float ulps at unit size.
constexpr double kUnchangedTolerance = 1e-6;  // an unmoved wire leaves the mesh unchanged
constexpr double kRigidTolerance = 1e-5;      // a rigid wire motion moves the mesh rigidly
constexpr double kOnWireTolerance = 1e-5;     // a vertex on a segment follows it exactly
// Continuity across a dividing plane: two points 2 eps apart, one on each side, stay within
// kContinuityFactor * 2 eps of each other after the bend (the map's local stretch is bounded).
constexpr double kContinuityEps = 1e-4;
constexpr double kContinuityFactor = 4.0;

Eigen::Vector3d vertex(std::span<const float> p, std::size_t v) {
  return Eigen::Vector3d(p[3 * v], p[3 * v + 1], p[3 * v + 2]);
}

double maxDifference(std::span<const float> a, std::span<const float> b) {
  double m = 0;
  for (std::size_t v = 0; v < a.size() / 3; ++v) m = std::max(m, (vertex(a, v) - vertex(b, v)).norm());
  return m;
}

// A closed tube ("cylinder-like mesh") of radius r along +x from x = 0 to x = length: `rings`
// rings of `sides` vertices, triangulated between neighbouring rings.
TriMesh tube(double length, double r, int rings, int sides) {
  TriMesh m;
  for (int k = 0; k < rings; ++k)
    for (int s = 0; s < sides; ++s) {
      const double phi = 2 * std::numbers::pi * s / sides;
      m.positions.insert(m.positions.end(),
                         {static_cast<float>(length * k / (rings - 1)), static_cast<float>(r * std::cos(phi)),
                          static_cast<float>(r * std::sin(phi))});
    }
  for (int k = 0; k + 1 < rings; ++k)
    for (int s = 0; s < sides; ++s) {
      const int a = k * sides + s, b = k * sides + (s + 1) % sides, c = a + sides, d = b + sides;
      m.triangles.insert(m.triangles.end(), {a, b, d, a, d, c});
    }
  return m;
}

std::vector<float> posedCopy(const SkeletonBinding& binding, const Joints& posed, const std::vector<float>& rest) {
  std::vector<float> out = rest;
  EXPECT_TRUE(binding.apply(posed, out));
  return out;
}

// A non-planar wire with several bends, through the unit-sized test meshes.
Joints bentWire() {
  return {{-1.2, -0.3, 0.1}, {-0.4, 0.1, 0.0}, {0.3, -0.1, 0.25}, {0.9, 0.4, -0.2}, {1.4, 0.5, 0.3}};
}

TEST(Skeleton, AStraightWireLeftUnmovedLeavesTheMeshUnchanged) {
  const TriMesh mesh = tube(2.0, 0.3, 21, 12);
  const Joints wire{{0, 0, 0}, {0.7, 0, 0}, {2, 0, 0}};
  const SkeletonBinding binding = bindSkeleton(wire, mesh.positions);
  EXPECT_EQ(binding.coords.size(), mesh.vertexCount());
  EXPECT_LE(maxDifference(posedCopy(binding, wire, mesh.positions), mesh.positions), kUnchangedTolerance);
}

TEST(Skeleton, TheRestWireAsThePosedWireLeavesAnyMeshUnchanged) {
  const Joints wires[] = {bentWire(), {{0, 0, 0}, {1, 0, 0}}, {{0, -1, 0}, {0.1, 0, 0}, {-0.1, 1.1, 0.3}}};
  const TriMesh meshes[] = {testing::uvSphere(16, 24), testing::torus(1.0, 0.4, 24, 12), tube(2, 0.4, 9, 8),
                            test::grid(15, 0.2)};
  for (const Joints& wire : wires)
    for (const TriMesh& mesh : meshes) {
      const SkeletonBinding binding = bindSkeleton(wire, mesh.positions);
      EXPECT_LE(maxDifference(posedCopy(binding, wire, mesh.positions), mesh.positions), kUnchangedTolerance);
    }
}

void expectRigid(const Joints& wire, const Eigen::Matrix3d& R, const Eigen::Vector3d& T, const TriMesh& mesh) {
  Joints posed;
  for (const Eigen::Vector3d& j : wire) posed.push_back(R * j + T);
  const SkeletonBinding binding = bindSkeleton(wire, mesh.positions);
  const std::vector<float> out = posedCopy(binding, posed, mesh.positions);
  double worst = 0;
  for (std::size_t v = 0; v < mesh.vertexCount(); ++v)
    worst = std::max(worst, (vertex(out, v) - (R * vertex(mesh.positions, v) + T)).norm());
  EXPECT_LE(worst, kRigidTolerance);
}

TEST(Skeleton, ARigidMotionOfTheWholeWireMovesTheMeshRigidly) {
  const TriMesh mesh = testing::uvSphere(16, 24);
  std::mt19937 rng(14);
  std::uniform_real_distribution<double> u(-1, 1);
  const Joints bent = bentWire();
  const Eigen::Vector3d d0 = (bent[1] - bent[0]).normalized();
  for (int trial = 0; trial < 8; ++trial) {
    const Eigen::Vector3d T(u(rng), u(rng), u(rng));
    // Translations.
    expectRigid(bent, Eigen::Matrix3d::Identity(), T, mesh);
    // Rotations about an axis perpendicular to the first segment (the minimal rotation of segment
    // 0 is then the motion itself), with a translation.
    Eigen::Vector3d axis = Eigen::Vector3d(u(rng), u(rng), u(rng)).cross(d0).normalized();
    const double angle = 3.0 * u(rng);
    expectRigid(bent, Eigen::AngleAxisd(angle, axis).toRotationMatrix(), T, mesh);
    // Any rotation of a straight wire moves the mesh rigidly too: by the minimal rotation taking the
    // wire's direction to its new one (a roll about the wire is not expressible by joints, and
    // none is invented), about the first joint, which goes to its new place.
    axis = Eigen::Vector3d(u(rng), u(rng), u(rng)).normalized();
    const Joints straight{{-1, 0.2, 0}, {0, 0.1, 0}, {1.5, -0.05, 0}};
    const Eigen::Matrix3d R = Eigen::AngleAxisd(angle, axis).toRotationMatrix();
    const Eigen::Vector3d d = (straight[1] - straight[0]).normalized();
    const Eigen::Matrix3d minimal = Eigen::Quaterniond::FromTwoVectors(d, R * d).toRotationMatrix();
    expectRigid(straight, minimal, R * straight[0] + T - minimal * straight[0], mesh);
  }
}

TEST(Skeleton, ABentWireBendsATubeContinuously) {
  const TriMesh mesh = tube(2.0, 0.3, 41, 16);
  const Joints rest{{0, 0, 0}, {1, 0, 0}, {2, 0, 0}};
  const double bend = 60 * std::numbers::pi / 180;
  const Joints posed{{0, 0, 0}, {1, 0, 0}, {1 + std::cos(bend), std::sin(bend), 0}};
  const SkeletonBinding binding = bindSkeleton(rest, mesh.positions);
  const std::vector<float> out = posedCopy(binding, posed, mesh.positions);

  // The far end turned with the second segment: its ring is the rest ring rotated by 60 degrees
  // about z, at the posed end joint.
  const Eigen::Matrix3d turn = Eigen::AngleAxisd(bend, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  for (std::size_t v = mesh.vertexCount() - 16; v < mesh.vertexCount(); ++v) {
    const Eigen::Vector3d offset = vertex(mesh.positions, v) - rest[2];
    EXPECT_LE((vertex(out, v) - (posed[2] + turn * offset)).norm(), kRigidTolerance) << v;
  }
  // The start ring lies on the start plane, which did not move with segment 0: it stays put.
  for (std::size_t v = 0; v < 16; ++v) EXPECT_LE((vertex(out, v) - vertex(mesh.positions, v)).norm(), kRigidTolerance);

  // Neighbouring vertices stay close: every edge changes length by a bounded factor (the inner side
  // of a 60-degree bend is compressed, the outer stretched, by at most 1/cos(30 deg) plus the wedge).
  double lo = 1e9, hi = 0;
  for (std::size_t t = 0; t < mesh.triangles.size(); t += 3)
    for (int e = 0; e < 3; ++e) {
      const auto a = static_cast<std::size_t>(mesh.triangles[t + e]);
      const auto b = static_cast<std::size_t>(mesh.triangles[t + (e + 1) % 3]);
      const double before = (vertex(mesh.positions, a) - vertex(mesh.positions, b)).norm();
      const double after = (vertex(out, a) - vertex(out, b)).norm();
      lo = std::min(lo, after / before);
      hi = std::max(hi, after / before);
    }
  EXPECT_GT(lo, 0.5);
  EXPECT_LT(hi, 2.0);
  EXPECT_LT(lo, 0.95);  // it did bend: the inner side is compressed...
  EXPECT_GT(hi, 1.05);  // ...and the outer one stretched

  // No vertex jumps across the joint: points just before and just after the bisector plane (bound
  // to the two different cells) land next to each other.
  const Eigen::Vector3d m1 = Eigen::Vector3d::UnitX();  // the rest bisector of a straight joint
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-0.5, 0.5);
  std::vector<float> pairs;
  for (int k = 0; k < 50; ++k) {
    const Eigen::Vector3d q = rest[1] + Eigen::Vector3d(0, u(rng), u(rng));
    for (double side : {-1.0, 1.0}) {
      const Eigen::Vector3d p = q + side * kContinuityEps * m1;
      pairs.insert(pairs.end(), {static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z())});
    }
  }
  const SkeletonBinding across = bindSkeleton(rest, pairs);
  for (std::size_t k = 0; k < pairs.size() / 6; ++k) {
    EXPECT_EQ(across.coords[2 * k].segment, 0);
    EXPECT_EQ(across.coords[2 * k + 1].segment, 1);
  }
  const std::vector<float> moved = posedCopy(across, posed, pairs);
  for (std::size_t k = 0; k < pairs.size() / 6; ++k)
    EXPECT_LE((vertex(moved, 2 * k) - vertex(moved, 2 * k + 1)).norm(), kContinuityFactor * 2 * kContinuityEps) << k;
}

TEST(Skeleton, ContinuityAcrossTheBisectorOfABentRestWire) {
  // The same across the dividing plane of a bent, non-planar rest wire posed into another shape.
  const Joints rest = bentWire();
  Joints posed = rest;
  posed[2] += Eigen::Vector3d(0.2, 0.3, -0.2);
  posed[3] += Eigen::Vector3d(-0.1, 0.4, 0.3);
  posed[4] += Eigen::Vector3d(0.5, -0.2, 0.1);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-0.3, 0.3);
  for (std::size_t k = 1; k + 1 < rest.size(); ++k) {
    const Eigen::Vector3d m =
        ((rest[k] - rest[k - 1]).normalized() + (rest[k + 1] - rest[k]).normalized()).normalized();
    std::vector<float> pairs;
    for (int t = 0; t < 20; ++t) {
      Eigen::Vector3d in_plane(u(rng), u(rng), u(rng));
      in_plane -= in_plane.dot(m) * m;
      for (double side : {-1.0, 1.0}) {
        const Eigen::Vector3d p = rest[k] + in_plane + side * kContinuityEps * m;
        pairs.insert(pairs.end(), {static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z())});
      }
    }
    const SkeletonBinding b = bindSkeleton(rest, pairs);
    const std::vector<float> moved = posedCopy(b, posed, pairs);
    for (std::size_t t = 0; t < pairs.size() / 6; ++t) {
      EXPECT_EQ(b.coords[2 * t].segment + 1, b.coords[2 * t + 1].segment) << "joint " << k;
      EXPECT_LE((vertex(moved, 2 * t) - vertex(moved, 2 * t + 1)).norm(), kContinuityFactor * 2 * kContinuityEps)
          << "joint " << k << " pair " << t;
    }
  }
}

TEST(Skeleton, VerticesOnTheSegmentFollowItExactly) {
  const Joints rest = bentWire();
  const Joints posed{{0, 0, 0}, {0.5, 0.5, 0.1}, {0.6, 1.4, 0.0}, {-0.2, 1.9, 0.4}, {-0.3, 2.5, 1.5}};
  std::vector<float> points;
  std::vector<Eigen::Vector3d> expected;
  for (std::size_t i = 0; i + 1 < rest.size(); ++i)
    for (double t : {0.0, 0.1, 0.37, 0.5, 0.9, 1.0}) {
      const Eigen::Vector3d p = rest[i] + t * (rest[i + 1] - rest[i]);
      points.insert(points.end(), {static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z())});
      expected.push_back(posed[i] + t * (posed[i + 1] - posed[i]));
    }
  // Beyond the ends, on the end segments' lines: they keep their distance past the end joint.
  const Eigen::Vector3d d0 = (rest[1] - rest[0]).normalized(), e0 = (posed[1] - posed[0]).normalized();
  const Eigen::Vector3d dn = (rest[4] - rest[3]).normalized(), en = (posed[4] - posed[3]).normalized();
  for (const auto& [p, q] : {std::pair{Eigen::Vector3d(rest[0] - 0.3 * d0), Eigen::Vector3d(posed[0] - 0.3 * e0)},
                             std::pair{Eigen::Vector3d(rest[4] + 0.2 * dn), Eigen::Vector3d(posed[4] + 0.2 * en)}}) {
    points.insert(points.end(), {static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z())});
    expected.push_back(q);
  }
  const SkeletonBinding binding = bindSkeleton(rest, points);
  const std::vector<float> out = posedCopy(binding, posed, points);
  for (std::size_t v = 0; v < expected.size(); ++v)
    EXPECT_LE((vertex(out, v) - expected[v]).norm(), kOnWireTolerance) << v;
}

TEST(Skeleton, AVertexInSeveralCellsTakesTheNearestSegment) {
  // A U: the two arms' cells overlap deep inside it, beyond where the bisector planes cross.
  const Joints u{{0, 2, 0}, {0, 0, 0}, {0.4, 0, 0}, {0.4, 2, 0}};
  const std::vector<float> points{0.1f, 1.5f, 0.0f, 0.3f, 1.5f, 0.0f, 0.2f, -0.5f, 0.0f};
  const SkeletonBinding b = bindSkeleton(u, points);
  ASSERT_EQ(b.coords.size(), 3u);
  EXPECT_EQ(b.coords[0].segment, 0);  // nearer the left arm
  EXPECT_EQ(b.coords[1].segment, 2);  // nearer the right arm
  EXPECT_EQ(b.coords[2].segment, 1);  // below the bottom: its cell alone
}

TEST(Skeleton, FalloffKeepsFarVerticesAndSelectionKeepsOthers) {
  const TriMesh mesh = test::grid(21, 0.1);  // [-1, 1]^2 in z = 0
  const Joints rest{{-0.5, 0, 0}, {0.5, 0, 0}};
  const Joints posed{{-0.5, 0, 0.2}, {0.5, 0, 0.2}};
  Falloff f;
  f.radius = 0.45;
  const SkeletonBinding b = bindSkeleton(rest, mesh.positions, {}, f);
  const std::vector<float> out = posedCopy(b, posed, mesh.positions);
  for (std::size_t v = 0; v < mesh.vertexCount(); ++v) {
    const Eigen::Vector3d p = vertex(mesh.positions, v);
    const double d = distanceToSegment(p, rest[0], rest[1]);
    const double moved = (vertex(out, v) - p).norm();
    if (d >= f.radius)
      EXPECT_EQ(moved, 0.0) << v;
    else
      EXPECT_NEAR(moved, 0.2 * falloffWeight(f, d), 1e-6) << v;
  }
  const std::vector<std::int32_t> selection{0, 220, 230};
  const SkeletonBinding s = bindSkeleton(rest, mesh.positions, selection);
  const std::vector<float> sel = posedCopy(s, posed, mesh.positions);
  std::size_t moved = 0;
  for (std::size_t v = 0; v < mesh.vertexCount(); ++v) moved += vertex(sel, v) != vertex(mesh.positions, v);
  EXPECT_EQ(moved, 3u);
}

TEST(Skeleton, ApplyChecksItsContractAndWritesNothingOnAViolation) {
  const TriMesh mesh = tube(2.0, 0.3, 5, 6);
  const Joints rest{{0, 0, 0}, {1, 0, 0}, {2, 0, 0}};
  const SkeletonBinding binding = bindSkeleton(rest, mesh.positions);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const Joints bad[] = {
      {{0, 0, 0}, {1, 0, 0}},                        // joint count differs from the rest wire
      {{0, 0, 0}, {1, nan, 0}, {2, 0, 0}},           // not finite
      {{0, 0, 0}, {1, 0, 0}, {1, 0, 0}},             // repeated joint
      {{0, 0, 0}, {1, 0, 0}, {0, 0.01, 0}},          // folds back (179 degrees)
      {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {3, 0, 0}},  // too many
  };
  for (const Joints& posed : bad) {
    std::vector<float> out(mesh.positions.size(), 7.0f);
    EXPECT_FALSE(binding.apply(posed, out));
    EXPECT_EQ(out, std::vector<float>(mesh.positions.size(), 7.0f));
  }
  std::vector<float> short_out(mesh.positions.size() - 3, 7.0f);
  EXPECT_FALSE(binding.apply(rest, short_out));
  EXPECT_EQ(short_out, std::vector<float>(mesh.positions.size() - 3, 7.0f));
}

TEST(Skeleton, ApplyAllocatesNothing) {
  const TriMesh mesh = testing::uvSphere(16, 24);
  const Joints rest = bentWire();
  Joints posed = rest;
  posed[3] += Eigen::Vector3d(0.1, 0.2, 0.3);
  const SkeletonBinding binding = bindSkeleton(rest, mesh.positions);
  std::vector<float> out = mesh.positions;
  bool ok = false;
  EXPECT_EQ(testing::allocationsDuring([&] { ok = binding.apply(posed, out); }), 0);
  EXPECT_TRUE(ok);
}

TEST(Skeleton, BadWiresNameTheJoint) {
  const double inf = std::numeric_limits<double>::infinity();
  const std::vector<float> points{0, 0, 0};
  EXPECT_EQ(errorOf([&] {
              bindSkeleton(Joints{{0, 0, 0}}, points);
            }),
            "skeleton: a wire needs at least 2 joints, got 1");
  EXPECT_EQ(errorOf([&] {
              bindSkeleton(Joints{{0, 0, 0}, {1, 0, 0}, {1, 0, 0}}, points);
            }),
            "skeleton: joint 2: is the same point as joint 1 (consecutive joints must differ)");
  EXPECT_EQ(errorOf([&] {
              bindSkeleton(Joints{{0, 0, 0}, {inf, 0, 0}}, points);
            }),
            "skeleton: joint 1: must hold finite numbers");
  EXPECT_EQ(errorOf([&] {
              bindSkeleton(Joints{{0, 0, 0}, {1, 0, 0}, {0, 0, 0}}, points);
            }),
            "skeleton: joint 1: the wire bends by 180 degrees there; bends must stay below 170 (at 180 it folds "
            "back on itself and the dividing plane is undefined)");
  EXPECT_EQ(errorOf([&] {
              bindSkeleton(Joints{{0, 0, 0}, {1, 0, 0}}, points, std::vector<std::int32_t>{1});
            }),
            "skeleton: vertex 1 is out of range (the mesh has 1 vertices)");
  EXPECT_EQ(errorOf([&] { bindSkeleton(Joints(kMaxSkeletonJoints + 1, Eigen::Vector3d::Zero()), points); }),
            "skeleton: a wire has at most 256 joints, got 257");
}

// ---- the edit op ------------------------------------------------------------------------------

SkeletonOp bendOp() {
  SkeletonOp op;
  op.rest = {{-0.8, 0, 0}, {0, 0, 0}, {0.8, 0, 0}};
  op.posed = {{-0.8, 0, 0}, {0, 0, 0}, {0.4, 0.5, 0.3}};
  return op;
}

Camera frontCamera() {
  Camera c;
  c.eye = {0, 0, 5};
  c.target = {0, 0, 0};
  c.fov_deg = 40;
  return c;
}

TEST(SkeletonOp, AppliesAsTheBindingDoesAndRoundTripsThroughTheEditLog) {
  const TriMesh base = test::grid(17, 0.1);
  SkeletonOp bend = bendOp();
  SkeletonOp faded = bendOp();
  faded.falloff = Falloff{0.5, 1.5, FalloffShape::kInversePower};
  faded.vertices = {0, 5, 100, 144, 150};
  const std::vector<EditOp> ops{bend, faded};

  std::vector<float> direct = base.positions;
  ASSERT_TRUE(bindSkeleton(bend.rest, direct).apply(bend.posed, direct));
  std::vector<float> applied = base.positions;
  const auto reports = applyEdits(frontCamera(), base.triangles, applied, std::span<const EditOp>(ops.data(), 1));
  EXPECT_EQ(applied, direct);
  EXPECT_GT(reports[0].moved, 0u);

  for (const EditOp& op : ops) {
    const std::string text = editOpToJson(op);
    EXPECT_EQ(editOpToJson(parseEditOp(text, "op")), text);
  }
  EXPECT_EQ(editOpToJson(EditOp{bend}), R"({"op":"skeleton","rest":[[-0.8,0.0,0.0],[0.0,0.0,0.0],[0.8,0.0,0.0]],)"
                                        R"("posed":[[-0.8,0.0,0.0],[0.0,0.0,0.0],[0.4,0.5,0.3]]})");

  EditLog log;
  log.key = "k";
  log.entries.push_back({frontCamera(), std::nullopt, ops});
  const std::vector<float> replayed = replayEditLog(base, log, "log");
  const EditLog read = parseEditLog(formatEditLog(log), "k.edits.json");
  EXPECT_EQ(replayEditLog(base, read, "k.edits.json"), replayed);
  EXPECT_EQ(formatEditLog(read), formatEditLog(log));
  EXPECT_NE(replayed, base.positions);
}

std::string scriptError(const std::string& op) {
  return errorOf([&] { parseEditScript(R"({"ops": [)" + op + "]}", "E.json"); });
}

TEST(SkeletonOp, BadInputNamesTheKeyAndIndex) {
  EXPECT_EQ(scriptError(R"({"op": "skeleton", "rest": [[0,0,0]], "posed": [[0,0,0]]})"),
            "E.json: 'ops'[0] (skeleton).'rest': a wire needs at least 2 joints, got 1");
  EXPECT_EQ(scriptError(R"({"op": "skeleton", "rest": [[0,0,0],[1,0,0],[2,0,0]], "posed": [[0,0,0],[1,0,0],[1,0,0]]})"),
            "E.json: 'ops'[0] (skeleton).'posed'[2]: is the same point as joint 1 (consecutive joints must differ)");
  EXPECT_EQ(scriptError(R"({"op": "skeleton", "rest": [[0,0,0],[1,0,0],[2,0,0]], "posed": [[0,0,0],[1,0,0]]})"),
            "E.json: 'ops'[0] (skeleton).'posed': has 2 joints, 'rest' has 3 (each rest joint needs its posed "
            "position)");
  // JSON holds no NaN or infinity: an overflowing number is refused by the parser, at its place.
  EXPECT_EQ(
      scriptError(R"({"op": "skeleton", "rest": [[0,0,0],[1e999,0,0]], "posed": [[0,0,0],[1,0,0]]})").substr(0, 41),
      "E.json: not valid JSON: number overflow p");
  EXPECT_EQ(scriptError(R"({"op": "skeleton", "rest": [[1e308,0,0],[-1e308,0,0]], "posed": [[0,0,0],[1,0,0]]})"),
            "E.json: 'ops'[0] (skeleton).'rest'[1]: is too far from joint 0 (their distance overflows)");
  EXPECT_EQ(scriptError(R"({"op": "skeleton", "rest": [[0,0,0],[1,0,0]], "posed": [[0,0,0],[1,0,0]], "power": 2})"),
            "E.json: 'ops'[0] (skeleton).'power': only with 'radius' (the falloff's distance from the rest wire)");
  EXPECT_EQ(scriptError(R"({"op": "skeleton", "rest": [[0,0,0],[1,0,0]], "posed": [[0,0,0],[1,0,0]], "radius": 0})"),
            "E.json: 'ops'[0] (skeleton).'radius': must be > 0 and finite, got 0");
  EXPECT_EQ(scriptError(R"({"op": "skeleton", "rest": [[0,0,0],[1,0,0]]})"),
            "E.json: 'ops'[0] (skeleton): missing key 'posed'");
  const std::vector<EditOp> out_of_range{SkeletonOp{{7}, {{0, 0, 0}, {1, 0, 0}}, {{0, 0, 0}, {1, 0, 0}}, {}}};
  EXPECT_EQ(errorOf([&] { validateEdits(out_of_range, 5, "E.json"); }),
            "E.json: 'ops'[0] (skeleton).'vertices': 7 is out of range (the mesh has 5 vertices)");
}

}  // namespace
}  // namespace vdg
