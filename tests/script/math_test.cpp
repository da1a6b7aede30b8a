// The maths bindings give the anim module's numbers: Parent's three ease functions, ease objects,
// curves with arc length, quaternions.
#include <gtest/gtest.h>

#include <cmath>

#include "script/script_fixtures.h"
#include "vdg/anim/arc_length.h"
#include "vdg/anim/curve.h"
#include "vdg/anim/ease.h"
#include "vdg/anim/rotation.h"

namespace vdg {
namespace {

using testing::ScriptBench;

// Evaluates a Lua expression that gives numbers, through print, with full precision.
std::vector<double> numbers(const std::string& expression) {
  ScriptBench bench;
  bench.run("local r = {" + expression + "}\nfor i = 1, #r do print(string.format('%.17g', r[i])) end");
  std::vector<double> out;
  for (const std::string& line : bench.printed) out.push_back(std::stod(line));
  return out;
}

constexpr double kTol = 1e-12;

TEST(ScriptMath, EaseFunctionsAreTheLibrarys) {
  for (double t : {0.0, 0.1, 0.35, 0.5, 0.9, 1.0}) {
    const std::string ts = std::to_string(t);
    const auto v = numbers("vdg.ease.sine(" + ts + "), vdg.ease.sinusoidal(" + ts + ", 0.2, 0.7), vdg.ease.parabolic(" +
                           ts + ", 0.3, 0.6), vdg.ease.make('sinusoidal', 0.2, 0.7)(" + ts +
                           "), vdg.ease.make('sine'):eval(" + ts + ")");
    ASSERT_EQ(v.size(), 5u);
    const double tt = std::stod(ts);
    EXPECT_NEAR(v[0], anim::easeSine(tt), kTol);
    EXPECT_NEAR(v[1], anim::easeSinusoidal(tt, 0.2, 0.7), kTol);
    EXPECT_NEAR(v[2], anim::easeParabolic(tt, 0.3, 0.6), kTol);
    EXPECT_NEAR(v[3], v[1], kTol);
    EXPECT_NEAR(v[4], v[0], kTol);
  }
  ScriptBench bench;
  EXPECT_EQ(bench.errorOfRun("\nvdg.ease.sinusoidal(0.5, 0.8, 0.2)").rfind("test.lua:2: vdg.ease.sinusoidal: ", 0), 0u);
  EXPECT_EQ(bench.errorOfRun("vdg.ease.make('bounce')"),
            "test.lua:1: vdg.ease.make: unknown ease 'bounce' (expected linear, sine, sinusoidal or parabolic)");
  EXPECT_EQ(bench.errorOfRun("vdg.ease.make('parabolic')"),
            "test.lua:1: vdg.ease.make: the parabolic ease takes two parameters (a, b: vdg.ease.make(\"parabolic\", "
            "0.2, 0.8))");
  EXPECT_EQ(bench.errorOfRun("vdg.ease.sine(0/0)"), "test.lua:1: vdg.ease.sine: argument #1 must be a finite number");
}

TEST(ScriptMath, CurvesAndArcLengthAreTheLibrarys) {
  anim::RawCurve raw;
  raw.kind = anim::CurveKind::kCatmullRom;
  raw.points = {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 2, 0), Eigen::Vector3d(3, 2, 1), Eigen::Vector3d(4, 0, 0)};
  const auto arc = anim::ArcLengthCurve::build(anim::Curve::build(raw));
  const std::string c =
      "vdg.curve{points = {{0, 0, 0}, {1, 2, 0}, {3, 2, 1}, {4, 0, 0}}, interpolation = 'catmull-rom'}";
  const auto v = numbers("(function() local c = " + c +
                         " local p = c:eval(1.5) local q = c:at_length(2) local a, b = c:range()"
                         " return p[1], p[2], p[3], c:length(), q[1], q[2], q[3], a, b end)()");
  ASSERT_EQ(v.size(), 9u);
  const Eigen::VectorXd p = arc.curve().at(1.5);
  EXPECT_NEAR(v[0], p[0], kTol);
  EXPECT_NEAR(v[1], p[1], kTol);
  EXPECT_NEAR(v[2], p[2], kTol);
  EXPECT_NEAR(v[3], arc.totalLength(), kTol);
  std::vector<double> q(3);
  ASSERT_TRUE(arc.evaluateAtDistance(2.0, q));
  EXPECT_NEAR(v[4], q[0], kTol);
  EXPECT_NEAR(v[5], q[1], kTol);
  EXPECT_NEAR(v[6], q[2], kTol);
  EXPECT_EQ(v[7], 0.0);
  EXPECT_EQ(v[8], 3.0);
  ScriptBench bench;
  EXPECT_EQ(bench.errorOfRun("vdg.curve{points = {{0, 0}, {1, 0, 0}}}"),
            "test.lua:1: vdg.curve: points[2] has 3 coordinates, points[1] has 2");
  EXPECT_EQ(
      bench.errorOfRun("vdg.curve{points = {{0, 0}, {1, 1}}, times = {0, 0}}").rfind("test.lua:1: vdg.curve: ", 0), 0u);
  EXPECT_EQ(bench.errorOfRun("vdg.curve{point = {}}"),
            "test.lua:1: vdg.curve: unknown field 'point' (expected points, times, interpolation)");
}

TEST(ScriptMath, QuaternionsAreTheLibrarys) {
  const auto v = numbers(
      "(function() local a = vdg.quat.axis_angle({0, 1, 0}, 90) local b = vdg.quat.axis_angle({1, 0, 0}, 60)"
      " local s = vdg.quat.slerp(a, b, 0.3) local r = a:rotate({1, 0, 0}) local m = a * b"
      " return s.w, s.x, s.y, s.z, r[1], r[2], r[3], m.w, m.x, m.y, m.z end)()");
  ASSERT_EQ(v.size(), 11u);
  const anim::Quaternion a = anim::axisAngleToQuaternion(Eigen::Vector3d::UnitY(), M_PI / 2);
  const anim::Quaternion b = anim::axisAngleToQuaternion(Eigen::Vector3d::UnitX(), M_PI / 3);
  const anim::Quaternion s = anim::slerp(a, b, 0.3);
  EXPECT_NEAR(v[0], s.w(), kTol);
  EXPECT_NEAR(v[1], s.x(), kTol);
  EXPECT_NEAR(v[2], s.y(), kTol);
  EXPECT_NEAR(v[3], s.z(), kTol);
  EXPECT_NEAR(v[4], 0.0, kTol);
  EXPECT_NEAR(v[6], -1.0, kTol);  // +X turned 90 degrees about +Y is -Z
  const anim::Quaternion m = anim::multiply(a, b);
  EXPECT_NEAR(v[7], m.w(), kTol);
  EXPECT_NEAR(v[8], m.x(), kTol);
  EXPECT_NEAR(v[9], m.y(), kTol);
  EXPECT_NEAR(v[10], m.z(), kTol);
  ScriptBench bench;
  EXPECT_EQ(bench.errorOfRun("vdg.quat.new(0, 0, 0, 0)"), "test.lua:1: vdg.quat.new: a zero quaternion is no rotation");
  EXPECT_EQ(bench.errorOfRun("local q = vdg.quat.identity()\nlocal y = q.yaw"),
            "test.lua:2: quaternion: no field 'yaw' (w, x, y, z, rotate, normalized, inverse)");
  EXPECT_EQ(bench.errorOfRun("vdg.quat.slerp({1, 0, 0}, vdg.quat.identity(), 0.5)"),
            "test.lua:1: vdg.quat.slerp: argument #1: expected a quaternion (vdg.quat...) or {w, x, y, z}");
}

}  // namespace
}  // namespace vdg
