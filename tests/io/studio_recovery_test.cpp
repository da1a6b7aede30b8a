// Recovery files of vdg studio (vdg/io/studio_recovery.h): round trips for new and existing keys,
// strokes written exactly as edit log entries, and one test per refusal comparing the whole message.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>

#include "support/error_of.h"
#include "support/test_meshes.h"
#include "vdg/geom/error.h"
#include "vdg/io/edit_script.h"
#include "vdg/io/studio_recovery.h"

namespace vdg {
namespace {

using testing::errorOf;

Camera perspective() {
  Camera c;
  c.eye = {0.1, 0.2, 3.0};
  c.target = {0, 0.25, 0};
  c.up = {0, 1, 0};
  c.fov_deg = 1.0 / 3.0 * 100.0;
  return c;
}

Camera ortho() {
  Camera c;
  c.eye = {3, 0, 0};
  c.target = {0, 0, 0};
  c.up = {0, 0, 1};
  c.fov_deg = 0.0;
  c.ortho_height = 2.5;
  return c;
}

std::vector<EditLogEntry> strokes() {
  DragOp drag;
  drag.pick.vertex = 12;
  drag.pick.falloff.radius = 0.15;
  drag.delta_px = Eigen::Vector2d(14.25, -6.0 / 7.0);
  RotateOp rotate;
  rotate.pick.vertex = 3;
  rotate.angle_deg = 12.5;
  FfdOp ffd;
  ffd.degree = {2, 1, 1};
  ffd.moves.push_back({{1, 0, 1}, {0, 0.1, 0}});
  return {EditLogEntry{perspective(), std::array<int, 2>{1024, 768}, {drag}},
          EditLogEntry{ortho(), std::array<int, 2>{640, 480}, {rotate, ffd}}, EditLogEntry{perspective(), {}, {}}};
}

StudioRecovery newKey() {
  StudioRecovery r;
  r.model = "/home/artist/spot/spot.obj";
  r.manifest = "/home/artist/spot/spot.vdg.json";
  r.key = "side \xe2\x9c\x93";
  r.new_key = true;
  r.mesh_path = "keys/side.obj";
  r.key_camera = ortho();
  r.strokes = strokes();
  return r;
}

StudioRecovery existingKey() {
  StudioRecovery r;
  r.model = "/data/spot.vdg.json";
  r.manifest = "/data/spot.vdg.json";
  r.key = "front";
  r.strokes = strokes();
  return r;
}

void expectSameCamera(const Camera& a, const Camera& b) {
  EXPECT_EQ(a.eye, b.eye);
  EXPECT_EQ(a.target, b.target);
  EXPECT_EQ(a.up, b.up);
  EXPECT_EQ(a.isOrtho(), b.isOrtho());
  EXPECT_EQ(a.isOrtho() ? a.ortho_height : a.fov_deg, b.isOrtho() ? b.ortho_height : b.fov_deg);
}

void expectSame(const StudioRecovery& a, const StudioRecovery& b) {
  EXPECT_EQ(a.model, b.model);
  EXPECT_EQ(a.manifest, b.manifest);
  EXPECT_EQ(a.key, b.key);
  EXPECT_EQ(a.new_key, b.new_key);
  EXPECT_EQ(a.mesh_path, b.mesh_path);
  EXPECT_EQ(a.logged, b.logged);
  EXPECT_EQ(a.key_frame, b.key_frame);
  ASSERT_EQ(a.key_camera.has_value(), b.key_camera.has_value());
  if (a.key_camera) expectSameCamera(*a.key_camera, *b.key_camera);
  ASSERT_EQ(a.strokes.size(), b.strokes.size());
  for (std::size_t s = 0; s < a.strokes.size(); ++s) {
    expectSameCamera(a.strokes[s].camera, b.strokes[s].camera);
    EXPECT_EQ(a.strokes[s].image_size, b.strokes[s].image_size);
    ASSERT_EQ(a.strokes[s].ops.size(), b.strokes[s].ops.size());
    for (std::size_t i = 0; i < a.strokes[s].ops.size(); ++i)
      EXPECT_EQ(editOpToJson(a.strokes[s].ops[i]), editOpToJson(b.strokes[s].ops[i])) << s << " " << i;
  }
}

TEST(StudioRecovery, RoundTripsNewAndExistingKeys) {
  StudioRecovery after_log = existingKey();
  after_log.logged = 7;  // the strokes follow the first 7 entries of the key's log
  StudioRecovery at_frame = newKey();
  at_frame.key_frame = 20;  // a new key of an animated model, at frame 20
  EXPECT_NE(formatStudioRecovery(at_frame).find("\"frame\": 20"), std::string::npos);
  for (const StudioRecovery& r :
       {newKey(), existingKey(), after_log, at_frame, StudioRecovery{"/m", "/m", "k", false, "", {}, 0, {}}}) {
    const std::string text = formatStudioRecovery(r);
    const StudioRecovery back = parseStudioRecovery(text, "rec.json");
    expectSame(back, r);
    EXPECT_EQ(formatStudioRecovery(back), text);
  }
}

// The strokes are edit log entries: the same objects an edit log of the same entries holds.
TEST(StudioRecovery, StrokesAreEditLogEntries) {
  const StudioRecovery r = newKey();
  EditLog log;
  log.key = r.key;
  log.entries = r.strokes;
  const auto recovery = nlohmann::json::parse(formatStudioRecovery(r));
  const auto edit_log = nlohmann::json::parse(formatEditLog(log));
  EXPECT_EQ(recovery.at("strokes"), edit_log.at("entries"));
  // A stroke copied from an edit log reads back.
  auto doc = recovery;
  doc["strokes"] = edit_log.at("entries");
  expectSame(parseStudioRecovery(doc.dump(), "rec.json"), r);
}

TEST(StudioRecovery, ReadsFiles) {
  testing::TempDir dir;
  testing::writeText(dir.file("r.json"), formatStudioRecovery(newKey()));
  expectSame(readStudioRecovery(dir.file("r.json")), newKey());
  EXPECT_EQ(errorOf([&] { readStudioRecovery(dir.file("none.json")); }).rfind(dir.file("none.json") + ": ", 0), 0u);
}

TEST(StudioRecovery, EveryRefusalNamesItsKeyPath) {
  const std::string cam = R"({"eye": [0, 0, 3], "target": [0, 0, 0], "fov_deg": 30})";
  const std::string head = R"("version": 1, "model": "/a/m.obj", "manifest": "/a/m.vdg.json", "key": "k", )";
  struct Case {
    std::string text;
    std::string message;
  };
  const Case cases[] = {
      {R"({"model": "/a", "manifest": "/a", "key": "k", "new_key": false, "strokes": []})",
       "REC: missing 'version' (this vdg reads studio recovery files version 1)"},
      {"{" + head + R"("new_key": false, "logged": -1, "strokes": []})",
       "REC: 'logged': expected an integer from 0 to 1000000000, got -1"},
      {R"({"version": 3})", "REC: 'version': this vdg reads studio recovery files version 1, got 3"},
      {"{" + head + R"("new_key": false, "strokes": [], "undo": []})",
       "REC: unknown key 'undo' (expected one of 'version', 'model', 'manifest', 'key', 'new_key', 'mesh', "
       "'key_camera', 'frame', 'logged', 'strokes')"},
      {"{" + head + R"("new_key": false, "frame": 3, "strokes": []})", "REC: 'frame': only with 'new_key': true"},
      {R"({"version": 1, "model": "m.obj", "manifest": "/a", "key": "k", "new_key": false, "strokes": []})",
       "REC: 'model': expected an absolute path, got \"m.obj\""},
      {R"({"version": 1, "model": "/a", "manifest": "", "key": "k", "new_key": false, "strokes": []})",
       "REC: 'manifest': expected an absolute path, got \"\""},
      {R"({"version": 1, "manifest": "/a", "key": "k", "new_key": false, "strokes": []})", "REC: missing key 'model'"},
      {R"({"version": 1, "model": "/a", "manifest": "/a", "key": "", "new_key": false, "strokes": []})",
       "REC: 'key': expected a key name, got an empty string"},
      {R"({"version": 1, "model": "/a", "manifest": "/a", "key": 4, "new_key": false, "strokes": []})",
       "REC: 'key': expected a string, got the number 4"},
      {"{" + head + R"("new_key": "yes", "strokes": []})",
       "REC: 'new_key': expected true or false, got the string \"yes\""},
      {"{" + head + R"("strokes": []})", "REC: missing key 'new_key'"},
      {"{" + head + R"("new_key": false, "mesh": "k.obj", "strokes": []})", "REC: 'mesh': only with 'new_key': true"},
      {"{" + head + R"("new_key": false, "key_camera": )" + cam + R"(, "strokes": []})",
       "REC: 'key_camera': only with 'new_key': true"},
      {"{" + head + R"("new_key": true, "key_camera": )" + cam + R"(, "strokes": []})",
       "REC: missing 'mesh' (required with 'new_key': true)"},
      {"{" + head + R"("new_key": true, "mesh": "k.obj", "strokes": []})",
       "REC: missing 'key_camera' (required with 'new_key': true)"},
      {"{" + head + R"("new_key": true, "mesh": "", "key_camera": )" + cam + R"(, "strokes": []})",
       "REC: 'mesh': expected a mesh file name, got an empty string"},
      {"{" + head + R"("new_key": true, "mesh": "k.obj", "key_camera": {"eye": [0, 0, 3], "target": [0, 0, 0]},
           "strokes": []})",
       "REC: 'key_camera': give exactly one of 'fov_deg' (perspective) or 'ortho_height' (parallel)"},
      {"{" + head + R"("new_key": false})", "REC: missing key 'strokes'"},
      {"{" + head + R"("new_key": false, "strokes": {}})",
       "REC: 'strokes': expected an array of strokes, got an object"},
      {"{" + head + R"("new_key": false, "strokes": [{"ops": []}]})", "REC: 'strokes'[0]: missing key 'camera'"},
      {"{" + head + R"("new_key": false, "strokes": [{"camera": )" + cam + R"(, "ops": [], "tool": "drag"}]})",
       "REC: 'strokes'[0]: unknown key 'tool' (expected one of 'camera', 'image_size', 'ops')"},
      {"{" + head + R"("new_key": false, "strokes": [{"camera": )" + cam + R"(, "ops": []},
           {"camera": {"eye": [0, 0, 3], "target": [0, 0, 0], "fov_deg": 180}, "ops": []}]})",
       "REC: 'strokes'[1].'camera'.'fov_deg': must be in (0, 180) degrees"},
      {"{" + head + R"("new_key": false, "strokes": [{"camera": )" + cam + R"(, "image_size": [0, 5], "ops": []}]})",
       "REC: 'strokes'[0].'image_size'[0]: expected an integer from 1 to 65536, got 0"},
      {"{" + head + R"("new_key": false, "strokes": [{"camera": )" + cam +
           R"(, "ops": [{"op": "drag", "vertex": 1, "radius": -1, "delta": [0, 0]}]}]})",
       "REC: 'strokes'[0].'ops'[0] (drag).'radius': must be > 0 and finite, got -1"},
  };
  for (const Case& c : cases) EXPECT_EQ(errorOf([&] { parseStudioRecovery(c.text, "REC"); }), c.message) << c.text;
}

// The writer refuses what the reader would refuse, naming the field.
TEST(StudioRecovery, FormatRefusesWhatCouldNotBeReadBack) {
  auto refusal = [](auto change) {
    StudioRecovery r = newKey();
    change(r);
    return errorOf([&] { formatStudioRecovery(r); });
  };
  EXPECT_EQ(refusal([](StudioRecovery& r) { r.model = "spot.obj"; }),
            "studio recovery: 'model': expected an absolute path, got \"spot.obj\"");
  EXPECT_EQ(refusal([](StudioRecovery& r) { r.key.clear(); }),
            "studio recovery: 'key': expected a key name, got an empty string");
  EXPECT_EQ(refusal([](StudioRecovery& r) { r.key_camera.reset(); }),
            "studio recovery: missing 'key_camera' (required with 'new_key': true)");
  EXPECT_EQ(refusal([](StudioRecovery& r) { r.new_key = false; }),
            "studio recovery: 'mesh': only with 'new_key': true");
  EXPECT_EQ(refusal([](StudioRecovery& r) { r.manifest = "/a/\xff.json"; }),
            "studio recovery: 'manifest': not valid UTF-8");
  EXPECT_EQ(refusal([](StudioRecovery& r) { std::get<DragOp>(r.strokes[0].ops[0]).pick.falloff.radius = -1; }),
            "studio recovery: 'strokes'[0].'ops'[0] (drag).'radius': must be > 0 and finite, got -1");
  EXPECT_EQ(refusal([](StudioRecovery& r) {
              r.strokes[1].camera.eye = r.strokes[1].camera.target;
            }).rfind("studio recovery: 'strokes'[1].'camera': ", 0),
            0u);
}

}  // namespace
}  // namespace vdg
