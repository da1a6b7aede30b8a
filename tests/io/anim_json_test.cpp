// Tests of the JSON form (docs/anim.md): every example parses, every invalid input names the key.
#include <gtest/gtest.h>

#include "vdg/geom/error.h"
#include "vdg/io/anim_json.h"

namespace vdg::anim {
namespace {

constexpr double kTol = 1e-12;

TEST(AnimJson, Ease) {
  EXPECT_EQ(parseEase(R"({"ease": "sine"})", "e.json").kind(), EaseKind::kSine);
  const Ease s = parseEase(R"({"ease": "sinusoidal", "t1": 0.2, "t2": 0.8})", "e.json");
  EXPECT_EQ(s.kind(), EaseKind::kSinusoidal);
  EXPECT_NEAR(s(0.5), easeSinusoidal(0.5, 0.2, 0.8), kTol);
  const AnimSpec spec = parseAnimSpec(R"({"ease": "parabolic", "a": 0.2, "b": 0.8})", "e.json");
  EXPECT_EQ(spec.kind, AnimSpec::Kind::kEase);
  EXPECT_EQ(spec.ease.kind(), EaseKind::kParabolic);
}

TEST(AnimJson, CurveAndTrack) {
  const AnimSpec c = parseAnimSpec(
      R"({"curve": "catmull-rom", "points": [[0,0,0],[1,1,0],[2,0,0]], "times": [0, 1, 3], "arc_length": true})",
      "c.json");
  EXPECT_EQ(c.kind, AnimSpec::Kind::kCurve);
  EXPECT_EQ(c.curve.points.size(), 3u);
  ASSERT_TRUE(c.arc_length.has_value());
  EXPECT_EQ(c.arc_length->method, ArcLengthMethod::kAdaptive);
  const AnimSpec t = parseAnimSpec(R"({"track": {"name": "spin", "interpolation": "slerp", "extrapolation": "loop",
      "keys": [{"time": 0, "value": [1, 0, 0, 0]}, {"time": 1, "axis": [0, 1, 0], "angle_deg": 90, "ease": "sine"},
               {"time": 2, "fixed_deg": [0, 180, 0], "ease": {"ease": "parabolic", "a": 0.1, "b": 0.9}}]}})",
                                   "t.json");
  EXPECT_EQ(t.track.type, TrackType::kRotation);
  EXPECT_EQ(t.track.extrapolation, Extrapolation::kLoop);
  const Track track = Track::build(t.track);
  EXPECT_TRUE(sameRotation(track.rotationAt(1.0), axisAngleToQuaternion(Eigen::Vector3d::UnitY(), M_PI / 2), 1e-12));
  const AnimSpec v = parseAnimSpec(R"({"track": {"interpolation": "bezier", "keys": [
      {"time": 0, "value": [0, 0], "out": [0, 1]}, {"time": 2, "value": [1, 0], "in": [1, 1]}]}})",
                                   "v.json");
  EXPECT_EQ(v.track.type, TrackType::kVector);
  EXPECT_EQ(Track::build(v.track).dimension(), 2);
  const AnimSpec s = parseAnimSpec(R"({"track": {"keys": [{"time": 0, "value": 1}, {"time": 1, "value": 3}]}})", "s");
  EXPECT_NEAR(Track::build(s.track).scalarAt(0.5), 2.0, kTol);
  const AnimSpec cam = parseAnimSpec(R"({"camera_path": {"position": {"curve": "catmull-rom",
      "points": [[5,1,0],[0,1,5],[-5,1,0]]}, "speed": {"ease": "sine"}, "view": "tangent", "end_time": 4,
      "tilt": {"keys": [{"time": 0, "value": 0}, {"time": 4, "value": 30}]}}})",
                                     "cam.json");
  EXPECT_EQ(cam.kind, AnimSpec::Kind::kCameraPath);
  EXPECT_NO_THROW(CameraPath::build(cam.camera_path));
}

void expectError(const std::string& text, const std::string& message) {
  try {
    parseAnimSpec(text, "spec.json");
    FAIL() << message;
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), message);
  }
}

TEST(AnimJson, ErrorsNameTheKey) {
  expectError(
      "{",
      "spec.json: not valid JSON at line 1, column 2: object key - unexpected end of input; expected string literal");
  expectError("[]", "spec.json: expected an object with 'ease', 'curve', 'track' or 'camera_path'");
  expectError(R"({"ease": "sine", "curve": "linear"})",
              "spec.json: expected exactly one of the keys 'ease', 'curve', 'track', 'camera_path'");
  expectError(R"({"ease": "bounce"})",
              "spec.json: 'ease': unknown ease 'bounce' (expected 'linear', 'sine', 'sinusoidal' or 'parabolic')");
  expectError(R"({"ease": "sinusoidal", "t1": 0.9, "t2": 0.1})",
              "spec.json: sinusoidal ease: t1 = 0.9 must not exceed t2 = 0.1");
  expectError(R"({"ease": "sinusoidal", "t1": 0.2})", "spec.json: the sinusoidal ease needs 't1' and 't2'");
  expectError(R"({"ease": "sinusoidal", "t1": "x", "t2": 0.5})",
              "spec.json: 't1': expected a number, got the string \"x\"");
  expectError(R"({"ease": "parabolic", "a": 0.2, "b": 0.8, "t1": 0})",
              "spec.json: 't1' is not a parameter of the parabolic ease (use a, b)");
  expectError(R"({"ease": "sine", "speed": 2})",
              "spec.json: unknown key 'speed' (expected one of 'ease', 't1', 't2', 'a', 'b')");
  expectError(R"({"curve": "catmull-rom", "points": [[0,0,0],[1,1,1],[2,2]]})",
              "spec.json: 'points'[2]: expected 3 numbers, got an array of 2 items");
  expectError(R"({"curve": "spline", "points": [[0],[1]]})",
              "spec.json: 'curve': unknown value 'spline' (expected one of 'linear', 'catmull-rom', "
              "'centripetal-catmull-rom', 'natural-cubic', 'parabolic-blending', 'bezier')");
  expectError(R"({"curve": "linear", "points": [[0],[1]], "times": [0, "a"]})",
              "spec.json: 'times'[1]: expected a number, got the string \"a\"");
  expectError(R"({"curve": "linear", "points": [[0],[1]], "times": [1, 0]})",
              "spec.json: 'times'[1]: key times must strictly increase (1 then 0)");
  expectError(R"({"curve": "linear", "points": [[0],[1]], "arc_length": {"method": "table", "samples": 1}})",
              "spec.json: 'arc_length'.'samples': expected an integer from 2 to 10000000, got 1");
  expectError(R"({"curve": "linear"})", "spec.json: missing key 'points'");
  expectError(R"({"track": {"keys": [{"time": 0, "value": [1, 2]}, {"time": 1, "value": [1]}]}})",
              "spec.json: 'track'.'keys'[1].'value': expected 2 numbers, got an array of 1 item");
  expectError(R"({"track": {"keys": [{"time": 0}]}})", "spec.json: 'track'.'keys'[0]: missing key 'value'");
  expectError(R"({"track": {"keys": [{"time": 0, "value": 1, "ease": {"ease": "sinusoidal", "t1": 2, "t2": 3}}]}})",
              "spec.json: 'track'.'keys'[0].'ease': sinusoidal ease: t1 = 2 is outside [0, 1]");
  expectError(R"({"track": {"interpolation": "slerp", "keys": [{"time": 0, "value": [1, 0, 0]}]}})",
              "spec.json: 'track'.'keys'[0].'value': expected 4 numbers, got an array of 3 items");
  expectError(R"({"track": {"name": "a", "keys": [{"time": 1, "value": 0}, {"time": 0, "value": 1}]}})",
              "spec.json: 'track': track 'a': 'keys'[1]: 'time' 0 must be greater than the previous key's 1");
  expectError(R"({"track": {"keys": [], "interp": "linear"}})",
              "spec.json: 'track': unknown key 'interp' (expected one of 'name', 'type', 'interpolation', "
              "'extrapolation', 'keys')");
  expectError(R"({"camera_path": {"position": {"curve": "linear", "points": [[0,0,0],[1,0,0]]}, "view": "up"}})",
              "spec.json: 'camera_path'.'view': unknown value 'up' (expected one of 'center', 'tangent', "
              "'target-path')");
}

TEST(AnimJson, MissingFile) {
  try {
    loadAnimSpec("/nonexistent/spec.json");
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), "/nonexistent/spec.json: no such file (animation spec)");
  }
}

}  // namespace
}  // namespace vdg::anim
