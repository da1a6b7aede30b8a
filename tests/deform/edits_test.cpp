// Edit scripts, camera JSON and edit logs.
#include <gtest/gtest.h>

#include <filesystem>

#include "test_meshes.h"
#include "vdg/deform/edits.h"
#include "vdg/geom/error.h"
#include "vdg/io/camera_json.h"
#include "vdg/io/edit_script.h"

namespace vdg {
namespace {

Camera frontCamera() {
  Camera c;
  c.eye = {0, 0, 5};
  c.target = {0, 0, 0};
  c.fov_deg = 40;
  return c;
}

std::string errorOf(const std::string& text) {
  try {
    parseEditScript(text, "E.json");
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(EditScript, ParsesEveryOp) {
  const EditScript s = parseEditScript(R"({
    "version": 1, "camera": {"eye": [0,0,5], "target": [0,0,0], "up": [0,1,0], "fov_deg": 40},
    "ops": [
      {"op": "drag", "vertex": 3, "radius": 0.5, "delta": [0.1, 0.0]},
      {"op": "push_pull", "vertex": 3, "radius": 0.5, "amount": -0.1, "mode": "axis"},
      {"op": "rotate", "vertex": 3, "radius": 0.5, "angle_deg": 10},
      {"op": "scale", "vertex": 3, "radius": 0.5, "factor": [1.2, 0.9], "power": 2},
      {"op": "displace", "vertex": 3, "radius": 2, "offset": [0, 0, 0.1], "distance": "edges", "falloff": "inverse_power"},
      {"op": "ffd", "degree": [1, 2, 1], "moves": [{"index": [1, 2, 0], "offset": [0.1, 0, 0]}]},
      {"op": "squash_stretch", "axis": "up", "factor": 1.3},
      {"op": "affine", "matrix": [[1,0,0],[0,1,0],[0,0,1]], "translation": [0, 0.1, 0]}
    ]})",
                                       "E.json");
  ASSERT_EQ(s.ops.size(), 8u);
  EXPECT_TRUE(s.camera.has_value());
  EXPECT_EQ(std::get<PushPullOp>(s.ops[1]).mode, PushPullMode::kAlongAxis);
  EXPECT_EQ(std::get<RotateOp>(s.ops[2]).pick.falloff.power, 0.0);  // rotate: rigid group by default
  EXPECT_EQ(std::get<DisplaceOp>(s.ops[4]).pick.metric, DistanceMetric::kEdges);
  EXPECT_EQ(std::get<FfdOp>(s.ops[5]).moves[0].index[1], 2);
  for (std::size_t i = 0; i < s.ops.size(); ++i) EXPECT_EQ(static_cast<std::size_t>(editKind(s.ops[i])), i);
}

TEST(EditScript, BadOpsNameIndexAndField) {
  EXPECT_EQ(errorOf(R"({"ops": [{"op": "drag", "vertex": 0, "radius": 1, "delta": [0,0]},
                                 {"op": "drag", "vertex": 0, "radius": -1, "delta": [0,0]}]})"),
            "E.json: 'ops'[1] (drag).'radius': must be > 0 and finite, got -1");
  EXPECT_EQ(errorOf(R"({"ops": [{"op": "twist"}]})").substr(0, 47), "E.json: 'ops'[0].'op': unknown value 'twist' (e");
  EXPECT_EQ(
      errorOf(R"({"ops": [{"op": "drag", "vertex": 0, "radius": 1, "delta": [0,0], "colour": 1}]})").substr(0, 50),
      "E.json: 'ops'[0] (drag): unknown key 'colour' (exp");
  EXPECT_EQ(errorOf(R"({"ops": [{"op": "drag", "vertex": -2, "radius": 1, "delta": [0,0]}]})"),
            "E.json: 'ops'[0] (drag).'vertex': expected an integer from 0 to 2147483647, got -2");
  EXPECT_EQ(errorOf(R"({"ops": [{"op": "ffd", "moves": [{"index": [2,0,0], "offset": [0,0,0]}]}]})"),
            "E.json: 'ops'[0] (ffd).'moves'[0].'index': component 0 = 2 is out of range [0, 1]");
  EXPECT_NE(errorOf(R"({"ops": [{"op": "drag", "vertex": 0, "radius": 1}]})").find("exactly one of 'delta'"),
            std::string::npos);
  EXPECT_NE(errorOf("{ not json").find("E.json: not valid JSON"), std::string::npos);
  EXPECT_NE(errorOf(R"({"version": 7, "ops": []})").find("'version'"), std::string::npos);
}

// Every number is range-checked before it is converted or used; the message names the field.
TEST(EditScript, NumbersOutOfRangeNameTheField) {
  const std::pair<const char*, const char*> cases[] = {
      {R"({"image_size": [1e12, 1e12], "ops": []})", "E.json: 'image_size'[0]: expected an integer from 1 to 65536"},
      {R"({"image_size": [0, 10], "ops": []})", "E.json: 'image_size'[0]: expected an integer from 1 to 65536, got 0"},
      {R"({"image_size": [10.5, 10], "ops": []})", "E.json: 'image_size'[0]: expected an integer from 1 to 65536"},
      {R"({"ops": [{"op": "drag", "vertex": 4294967297, "radius": 1, "delta": [0,0]}]})",
       "E.json: 'ops'[0] (drag).'vertex': expected an integer from 0 to 2147483647"},
      {R"({"ops": [{"op": "drag", "vertex": 0, "radius": 1e999, "delta": [0,0]}]})", "E.json: not valid JSON"},
      {R"({"ops": [{"op": "drag", "vertex": 0, "radius": 0, "delta": [0,0]}]})",
       "E.json: 'ops'[0] (drag).'radius': must be > 0 and finite, got 0"},
      {R"({"ops": [{"op": "drag", "vertex": 0, "radius": 1, "power": -1, "delta": [0,0]}]})",
       "E.json: 'ops'[0] (drag).'power': must be >= 0 and finite, got -1"},
      {R"({"ops": [{"op": "scale", "vertex": 0, "radius": 1, "factor": [1, -2]}]})",
       "E.json: 'ops'[0] (scale).'factor': must be > 0 and finite, got [1, -2]"},
      {R"({"ops": [{"op": "ffd", "degree": [1, 17, 1], "moves": []}]})",
       "E.json: 'ops'[0] (ffd).'degree'[1]: expected an integer from 1 to 16, got 17"},
      {R"({"ops": [{"op": "ffd", "padding": -0.5, "moves": []}]})",
       "E.json: 'ops'[0] (ffd).'padding': must be from 0 to 10, got -0.5"},
      {R"({"ops": [{"op": "squash_stretch", "axis": [0, 0, 0], "factor": 2}]})",
       "E.json: 'ops'[0] (squash_stretch).'axis': must be a finite, non-zero vector"},
      {R"({"ops": [{"op": "squash_stretch", "axis": "up", "factor": 0}]})",
       "E.json: 'ops'[0] (squash_stretch).'factor': must be > 0 and finite, got 0"},
      {R"({"ops": [{"op": "affine", "matrix": [[1,0,0],[0,1,0]]}]})",
       "E.json: 'ops'[0] (affine).'matrix': expected 3 rows of 3 numbers, got an array of 2 items"},
      {R"({"ops": [{"op": "affine", "matrix": [[1,0,0],[0,1,0],[0,0,1]], "vertices": [-1]}]})",
       "E.json: 'ops'[0] (affine).'vertices'[0]: expected an integer from 0 to 2147483647, got -1"},
  };
  for (const auto& [text, expected] : cases) {
    const std::string msg = errorOf(text);
    EXPECT_EQ(msg.substr(0, std::string(expected).size()), expected) << text;
  }
}

TEST(EditScript, VertexOutOfRangeNamesOpAndField) {
  const EditScript s = parseEditScript(
      R"({"ops": [{"op": "scale", "vertex": 1, "radius": 1, "factor": 2},
                  {"op": "drag", "vertex": 99, "radius": 1, "delta": [0, 1]}]})",
      "E.json");
  try {
    validateEdits(s.ops, 25, "E.json");
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), "E.json: 'ops'[1] (drag).'vertex': 99 is out of range (the mesh has 25 vertices)");
  }
}

TEST(EditScript, ApplyReportsMovedVertices) {
  TriMesh m = test::grid(5, 0.25);
  const EditScript s = parseEditScript(
      R"({"ops": [{"op": "drag", "vertex": 12, "radius": 0.3, "delta": [0.1, 0.0]},
                  {"op": "affine", "matrix": [[1,0,0],[0,1,0],[0,0,1]]}]})",
      "E.json");
  const auto reports = applyEdits(frontCamera(), m.triangles, m.positions, s.ops);
  ASSERT_EQ(reports.size(), 2u);
  EXPECT_EQ(reports[0].moved, 5u);  // the centre and its 4 axis neighbours at 0.25 < 0.3
  EXPECT_NEAR(reports[0].max_displacement, 0.1, 1e-6);
  EXPECT_EQ(reports[1].moved, 0u);
}

TEST(EditScript, PixelDeltaNeedsImageSize) {
  TriMesh m = test::grid(5, 0.25);
  const EditScript s =
      parseEditScript(R"({"ops": [{"op": "drag", "vertex": 12, "radius": 0.3, "delta_px": [10, 0]}]})", "E.json");
  EXPECT_THROW(applyEdits(frontCamera(), m.triangles, m.positions, s.ops), Error);
  const auto reports = applyEdits(frontCamera(), m.triangles, m.positions, s.ops, std::array<int, 2>{100, 100});
  EXPECT_EQ(reports[0].moved, 5u);
}

// A pick's seed named by a point (the nearest vertex) or by a pixel of the key view (the vertex
// seen there, vdg/deform/pick.h) moves exactly what the same seed named by its index moves.
TEST(EditScript, PicksByPointAndByPixelMoveWhatTheIndexMoves) {
  const TriMesh grid = test::grid(5, 0.25);
  const std::array<int, 2> size{100, 100};
  const Eigen::Vector2d px = project(frontCamera(), size[0], size[1], Eigen::Vector3d::Zero()).pixel;  // vertex 12
  auto moved = [&](const std::string& seed) {
    TriMesh m = grid;
    const EditScript s =
        parseEditScript(R"({"ops": [{"op": "drag", )" + seed + R"(, "radius": 0.3, "delta": [0.1, 0.05]},
                    {"op": "rotate", )" +
                            seed + R"(, "radius": 0.6, "angle_deg": 15}]})",
                        "E.json");
    applyEdits(frontCamera(), m.triangles, m.positions, s.ops, size);
    return m.positions;
  };
  const auto by_index = moved(R"("vertex": 12)");
  EXPECT_NE(by_index, grid.positions);
  EXPECT_EQ(moved(R"("point": [0.02, -0.03, 0.1])"), by_index);
  EXPECT_EQ(moved(R"("pixel": [)" + std::to_string(px.x() + 1) + ", " + std::to_string(px.y() - 1) + "]"), by_index);
  // Round trip: the canonical form keeps the point or pixel (a log replays it to the same vertex).
  const EditScript s =
      parseEditScript(R"({"ops": [{"op": "drag", "pixel": [50, 50], "radius": 0.3, "delta": [0, 1]}]})", "E.json");
  const EditOp back = parseEditOp(editOpToJson(s.ops[0]), "op");
  EXPECT_EQ(std::get<DragOp>(back).pick.pixel, Eigen::Vector2d(50, 50));
  EXPECT_EQ(editOpToJson(s.ops[0]).find("\"vertex\""), std::string::npos) << editOpToJson(s.ops[0]);
}

TEST(EditScript, BadPointsAndPixelsNameOpAndField) {
  EXPECT_EQ(errorOf(R"({"ops": [{"op": "drag", "vertex": 1, "point": [0, 0, 0], "radius": 1, "delta": [0, 0]}]})"),
            "E.json: 'ops'[0] (drag): give one of 'vertex', 'point' or 'pixel', not several");
  EXPECT_EQ(errorOf(R"({"ops": [{"op": "drag", "radius": 1, "delta": [0, 0]}]})").substr(0, 50),
            "E.json: 'ops'[0] (drag): missing the picked vertex");
  EXPECT_NE(errorOf(R"({"ops": [{"op": "drag", "point": [0, 0], "radius": 1, "delta": [0, 0]}]})"), "");
  EXPECT_NE(errorOf(R"({"ops": [{"op": "drag", "pixel": [0, "a"], "radius": 1, "delta": [0, 0]}]})"), "");
  TriMesh m = test::grid(5, 0.25);
  const EditScript no_size =
      parseEditScript(R"({"ops": [{"op": "drag", "pixel": [50, 50], "radius": 0.3, "delta": [0, 1]}]})", "E.json");
  try {
    applyEdits(frontCamera(), m.triangles, m.positions, no_size.ops, std::nullopt, "E.json");
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()),
              "E.json: 'ops'[0] (drag).'pixel': needs the drawing's size: give \"image_size\": [w, h]");
  }
  const EditScript miss =
      parseEditScript(R"({"ops": [{"op": "push_pull", "pixel": [2, 2], "radius": 0.3, "amount": 1}]})", "E.json");
  try {
    applyEdits(frontCamera(), m.triangles, m.positions, miss.ops, std::array<int, 2>{100, 100}, "E.json");
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()),
              "E.json: 'ops'[0] (push_pull).'pixel': [2, 2] sees no front face of the mesh in the key camera (its ray "
              "misses the model)");
  }
}

TEST(CameraJson, RoundTripAndErrors) {
  Camera c = frontCamera();
  c.eye = {0.1, 0.2, 4.3};
  const Camera back = parseCameraJson(cameraToJson(c), "c.json");
  EXPECT_EQ(back.eye, c.eye);
  EXPECT_EQ(back.fov_deg, c.fov_deg);
  c.ortho_height = 2.5;
  EXPECT_EQ(parseCameraJson(cameraToJson(c), "c.json").ortho_height, 2.5);
  EXPECT_THROW(parseCameraJson(R"({"eye":[0,0,1],"target":[0,0,1],"fov_deg":40})", "c.json"), Error);
  EXPECT_THROW(parseCameraJson(R"({"eye":[0,0,1],"target":[0,0,0],"fov_deg":200})", "c.json"), Error);
  EXPECT_THROW(parseCameraJson(R"({"eye":[0,0,1],"target":[0,0,0]})", "c.json"), Error);
}

TEST(EditLog, RoundTripAndReplayIsDeterministic) {
  const auto dir = std::filesystem::temp_directory_path() / "vdg_deform_editlog_test";
  std::filesystem::create_directories(dir);
  const TriMesh base = test::grid(7, 0.2);
  EditLog log;
  log.key = "k";
  const EditScript s1 =
      parseEditScript(R"({"ops": [{"op": "drag", "vertex": 24, "radius": 0.5, "delta": [0.1, 0.05]}]})", "a");
  const EditScript s2 = parseEditScript(
      R"({"ops": [{"op": "displace", "vertex": 10, "radius": 0.6, "offset": [0, 0, 0.2], "distance": "geodesic"}]})",
      "b");
  log.entries.push_back({frontCamera(), std::nullopt, s1.ops});
  log.entries.push_back({frontCamera(), std::array<int, 2>{64, 48}, s2.ops});
  TriMesh direct = base;
  for (const auto& e : log.entries) applyEdits(e.camera, direct.triangles, direct.positions, e.ops, e.image_size);
  const std::string path = editLogPath((dir / "k.obj").string());
  EXPECT_EQ(std::filesystem::path(path).filename(), "k.edits.json");
  writeEditLog(path, log);
  const EditLog read = readEditLog(path);
  ASSERT_EQ(read.entries.size(), 2u);
  EXPECT_EQ(read.key, "k");
  TriMesh replayed = base;
  for (const auto& e : read.entries) applyEdits(e.camera, replayed.triangles, replayed.positions, e.ops, e.image_size);
  EXPECT_EQ(replayed.positions, direct.positions);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace vdg
