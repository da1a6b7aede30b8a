// The language's animation semantics, checked through the scene module: SET and CHANGE (Parent
// 4.6), FOR EACH over object sets, tracks (4.9) equal to the anim library's, the hierarchy,
// cameras, vdg.load's instancing and render requests; and every bad argument's clear error.
#include <gtest/gtest.h>

#include <cmath>

#include "script/script_fixtures.h"
#include "vdg/anim/ease.h"
#include "vdg/anim/track.h"

namespace vdg {
namespace {

using scene::Field;
using testing::ScriptBench;
using testing::valueAt;

constexpr double kTol = 1e-12;

scene::Scene build(const script::Shot& shot) { return scene::Scene::build(shot.scene, "test"); }

TEST(Script, SetTakesEffectAtItsFrame) {
  ScriptBench bench;
  const auto shot = bench.run(
      "local box = vdg.group{name = 'box', translation = {1, 2, 3}}\n"
      "vdg.set(box, 'translation', {10, 0, 0}, 5)\n"
      "vdg.set(box, 'scale', 2)\n");
  const auto s = build(shot);
  EXPECT_EQ(valueAt(s, "box", Field::kTranslation, 4.9), (std::vector<double>{1, 2, 3}));
  EXPECT_EQ(valueAt(s, "box", Field::kTranslation, 5), (std::vector<double>{10, 0, 0}));
  EXPECT_EQ(valueAt(s, "box", Field::kScale, 0), (std::vector<double>{2, 2, 2}));
  ASSERT_EQ(shot.scene.actions.size(), 2u);
  EXPECT_EQ(shot.scene.actions[1].from_frame, 0.0);  // frame defaults to 0
}

TEST(Script, ChangeSpreadsItsDeltaOverTheFramesWithItsEase) {
  ScriptBench bench;
  const auto shot = bench.run(
      "local a = vdg.group{name = 'a'}\n"
      "local b = vdg.group{name = 'b'}\n"
      "vdg.change(a, 'translation', {10, 0, 0}, 0, 10)\n"
      "vdg.change(b, 'translation', {10, 0, 0}, 0, 10, vdg.ease.make('sine'))\n"
      "vdg.change(b, 'translation', {0, 4, 0}, 10, 20, vdg.ease.make('parabolic', 0.2, 0.8))\n");
  const auto s = build(shot);
  EXPECT_NEAR(valueAt(s, "a", Field::kTranslation, 5)[0], 5.0, kTol);
  EXPECT_NEAR(valueAt(s, "a", Field::kTranslation, 20)[0], 10.0, kTol);
  EXPECT_NEAR(valueAt(s, "b", Field::kTranslation, 2.5)[0], 10.0 * anim::easeSine(0.25), kTol);
  EXPECT_NEAR(valueAt(s, "b", Field::kTranslation, 13)[1], 4.0 * anim::easeParabolic(0.3, 0.2, 0.8), kTol);
  EXPECT_NEAR(valueAt(s, "b", Field::kTranslation, 13)[0], 10.0, kTol);
}

TEST(Script, SetAndChangeOnObjectSetsAndForEach) {
  ScriptBench bench;
  const auto shot = bench.run(
      "local crowd = {}\n"
      "for i = 1, 4 do crowd[i] = vdg.group{name = 'm' .. i} end\n"
      "vdg.set(crowd, 'visible', false, 3)\n"
      "vdg.for_each(crowd, function(node, i) vdg.set(node, 'translation', {i * 2, 0, 0}) end)\n"
      "vdg.change({crowd[1], crowd[2]}, 'rotation', vdg.quat.axis_angle({0, 1, 0}, 90), 0, 10)\n");
  const auto s = build(shot);
  for (int i = 1; i <= 4; ++i) {
    const std::string name = "m" + std::to_string(i);
    EXPECT_EQ(valueAt(s, name, Field::kTranslation, 1)[0], 2.0 * i);
    EXPECT_EQ(valueAt(s, name, Field::kVisible, 2)[0], 1.0);
    EXPECT_EQ(valueAt(s, name, Field::kVisible, 3)[0], 0.0);
  }
  const auto r = valueAt(s, "m2", Field::kRotation, 10);
  EXPECT_NEAR(r[0], std::cos(M_PI / 4), 1e-9);
  EXPECT_NEAR(r[2], std::sin(M_PI / 4), 1e-9);
  EXPECT_NEAR(valueAt(s, "m3", Field::kRotation, 10)[0], 1.0, kTol);
}

TEST(Script, ATrackThroughTheLanguageEqualsTheLibrarys) {
  ScriptBench bench;
  const auto shot = bench.run(
      "local n = vdg.group{name = 'n'}\n"
      "vdg.track(n, 'translation', {{0, {0, 0, 0}}, {10, {10, 5, 0}, ease = vdg.ease.make('sinusoidal', 0.2, 0.8)},\n"
      "                             {20, {0, 0, 2}}, {30, {5, 5, 5}}}, 'catmull-rom', 'loop')\n");
  anim::RawTrack raw;
  raw.type = anim::TrackType::kVector;
  raw.interpolation = anim::Interpolation::kCatmullRom;
  raw.extrapolation = anim::Extrapolation::kLoop;
  const double keys[4][4] = {{0, 0, 0, 0}, {10, 10, 5, 0}, {20, 0, 0, 2}, {30, 5, 5, 5}};
  for (const auto& k : keys) {
    anim::RawKey key;
    key.time = k[0];
    key.value = Eigen::Vector3d(k[1], k[2], k[3]);
    raw.keys.push_back(key);
  }
  raw.keys[1].ease = anim::Ease::sinusoidal(0.2, 0.8);
  const anim::Track expected = anim::Track::build(raw);
  const auto s = build(shot);
  for (double f : {0.0, 3.3, 10.0, 12.5, 27.0, 41.0, -4.0}) {
    const auto v = valueAt(s, "n", Field::kTranslation, f);
    const Eigen::VectorXd e = expected.at(f);
    ASSERT_EQ(v.size(), 3u);
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(v[static_cast<std::size_t>(i)], e[i], kTol) << "frame " << f;
  }
  ASSERT_EQ(shot.scene.tracks.size(), 1u);
  EXPECT_EQ(shot.scene.tracks[0].track.name, "n.translation");
}

TEST(Script, RotationTracksAndScalarTracks) {
  ScriptBench bench;
  const auto shot = bench.run(
      "local q = vdg.quat.axis_angle({0, 0, 1}, 120)\n"
      "local n = vdg.group{name = 'spin'}\n"
      "vdg.track(n, 'rotation', {{0, vdg.quat.identity()}, {12, q}})\n"
      "local c = vdg.camera{name = 'cam'}\n"
      "vdg.track(c, 'fov', {{0, 30}, {10, 50}}, 'linear')\n");
  const auto s = build(shot);
  const auto r = valueAt(s, "spin", Field::kRotation, 6);
  EXPECT_NEAR(r[0], std::cos(M_PI / 6), 1e-9);
  EXPECT_NEAR(r[3], std::sin(M_PI / 6), 1e-9);
  EXPECT_NEAR(valueAt(s, "cam", Field::kFov, 5)[0], 40.0, kTol);
}

TEST(Script, HierarchyPlacementAndColours) {
  ScriptBench bench;
  const auto shot = bench.run(
      "local sun = vdg.group{name = 'sun'}\n"
      "local orbit = vdg.group{name = 'orbit', parent = sun, rotation = vdg.quat.axis_angle({0, 1, 0}, 90)}\n"
      "local earth = vdg.group{name = 'earth', parent = orbit, translation = {10, 0, 0}, scale = {1, 2, 3}}\n"
      "assert(earth.name == 'earth' and earth.kind == 'group' and tostring(earth) == \"group 'earth'\")\n");
  const auto s = build(shot);
  std::vector<scene::NodeState> states(static_cast<std::size_t>(s.nodeCount()));
  ASSERT_TRUE(s.evaluate(0, states));
  const Eigen::Vector3d earth = states[2].world.block<3, 1>(0, 3);
  EXPECT_NEAR(earth.x(), 0.0, 1e-9);
  EXPECT_NEAR(earth.z(), -10.0, 1e-9);
  EXPECT_EQ(shot.scene.nodes[1].parent, 0);
  EXPECT_EQ(shot.scene.nodes[2].link.scale, Eigen::Vector3d(1, 2, 3));
}

TEST(Script, CamerasWithPathsAndACentreOfInterest) {
  ScriptBench bench;
  const auto shot = bench.run(
      "local target = vdg.group{name = 'target', translation = {0, 1, 0}}\n"
      "local cam = vdg.camera{name = 'cam', fov = 35, look_at = target,\n"
      "  path = {points = {{0, 0, 10}, {10, 0, 0}, {0, 0, -10}}, interpolation = 'catmull-rom',\n"
      "          ease = vdg.ease.make('sine'), start = 1, ['end'] = 48, up = {0, 1, 0}, tilt = 5}}\n"
      "local other = vdg.camera{name = 'other', translation = {0, 0, 5}}\n"
      "vdg.use_camera(cam)\n");
  EXPECT_EQ(shot.scene.camera, "cam");
  const scene::RawNode& cam = shot.scene.nodes[1];
  ASSERT_TRUE(cam.path.has_value());
  EXPECT_EQ(cam.path->start_time, 1.0);
  EXPECT_EQ(cam.path->end_time, 48.0);
  EXPECT_EQ(cam.path->speed.kind(), anim::EaseKind::kSine);
  EXPECT_EQ(cam.path->position.points.size(), 3u);
  EXPECT_EQ(cam.look_at, "target");
  EXPECT_EQ(cam.fov_deg, 35.0);
  ASSERT_TRUE(cam.path->tilt_deg.has_value());
  const auto s = build(shot);
  EXPECT_EQ(s.cameraNode(), 1);
  std::vector<scene::NodeState> states(static_cast<std::size_t>(s.nodeCount()));
  ASSERT_TRUE(s.evaluate(1, states));
  Camera c;
  ASSERT_TRUE(s.camera(1, states, c));
  EXPECT_NEAR((c.eye - Eigen::Vector3d(0, 0, 10)).norm(), 0.0, 1e-6);
}

TEST(Script, LoadInstancesOneObjectPerPath) {
  ScriptBench bench;
  testing::writeText(bench.scripts + "/models/tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  // '..' may climb while the path stays in the folder; the same file is the same object.
  const auto climbed = bench.run(
      "local a = vdg.node{object = vdg.load('models/../models/tri.obj')}\n"
      "local b = vdg.node{object = vdg.load('models/tri.obj')}\n");
  EXPECT_EQ(climbed.scene.meshes.size(), 1u);
  const auto shot2 = bench.run(
      "local m = vdg.load('models/tri.obj')\n"
      "assert(m.kind == 'mesh' and m.path == 'models/tri.obj' and tostring(m) == \"mesh 'models/tri.obj'\")\n"
      "local a = vdg.node{object = m}\n"
      "local b = vdg.node{object = vdg.load('./models/tri.obj')}\n");
  ASSERT_EQ(shot2.scene.meshes.size(), 1u);
  EXPECT_EQ(shot2.scene.nodes[0].object, 0);
  EXPECT_EQ(shot2.scene.nodes[1].object, 0);
  EXPECT_EQ(shot2.scene.nodes[1].kind, scene::ObjectKind::kMesh);
  EXPECT_EQ(shot2.scene.nodes[0].name, "node1");
}

// part_drivers (scene.h, "Part drivers"): a part of a model with parts follows another node.
TEST(Script, PartDriversNameAPartAndANode) {
  ScriptBench bench;
  const std::string spot = std::string(VDG_SOURCE_DIR) + "/examples/spot";
  auto run = [&](const std::string& text) { return script::runScriptText(text, "t.lua", spot, bench.options()); };
  const auto shot =
      run("local muse = vdg.group{name = 'muse', translation = {5, 1, 0}}\n"
          "vdg.node{name = 'cow', object = vdg.load('spot-cubist.vdg.json'), part_drivers = {head = muse}}\n");
  const scene::RawNode& cow = shot.scene.nodes[1];
  ASSERT_EQ(cow.part_drivers.size(), 1u);
  EXPECT_EQ(cow.part_drivers[0].part, "head");
  EXPECT_EQ(cow.part_drivers[0].node, "muse");
  const scene::Scene built = scene::Scene::build(shot.scene);
  EXPECT_EQ(built.findNode("cow"), 1);
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"local m = vdg.group{}\nvdg.node{object = vdg.load('spot-cubist.vdg.json'), part_drivers = {ears = m}}",
       "t.lua:2: vdg.node: part_drivers: the model has no part 'ears' (its parts: head, rest)"},
      {"vdg.node{object = vdg.load('spot-cubist.vdg.json'), part_drivers = {head = 'muse'}}",
       "t.lua:1: vdg.node: part_drivers: expected a node (vdg.node, vdg.group or vdg.camera), got string"},
      {"local m = vdg.group{}\nvdg.node{object = vdg.load('spot.vdg.json'), part_drivers = {head = m}}",
       "t.lua:2: vdg.node: part_drivers: only a view-dependent model with parts ('parts' in its manifest) has part "
       "drivers"},
      {"local m = vdg.group{}\nvdg.node{object = vdg.load('spot-cubist.vdg.json'), part_drivers = {m}}",
       "t.lua:2: vdg.node: part_drivers: expected part names as keys"},
  };
  for (const auto& [text, message] : cases) EXPECT_EQ(testing::errorOf([&] { run(text); }), message) << text;
}

TEST(Script, RenderRequests) {
  ScriptBench bench;
  const auto shot = bench.run(
      "vdg.render{frames = '1-48', size = {320, 200}, out = 'frames/a', samples = 4, background = {0, 0, 0},\n"
      "           silhouette = 2.5, creases = 40}\n"
      "\n"
      "vdg.render{frames = {5, 7}, out = 'b'}\n"
      "vdg.render{frames = 12, out = 'c'}\n");
  ASSERT_EQ(shot.renders.size(), 3u);
  const auto& a = shot.renders[0];
  EXPECT_EQ(a.first_frame, 1);
  EXPECT_EQ(a.last_frame, 48);
  EXPECT_EQ(a.width, 320);
  EXPECT_EQ(a.height, 200);
  EXPECT_EQ(a.out, "frames/a");
  EXPECT_EQ(a.samples, 4);
  EXPECT_EQ(a.background[0], 0.0f);
  EXPECT_EQ(a.silhouette_width, 2.5f);
  EXPECT_EQ(a.crease_angle_deg, 40.0f);
  EXPECT_EQ(a.line, 1);
  EXPECT_EQ(shot.renders[1].first_frame, 5);
  EXPECT_EQ(shot.renders[1].last_frame, 7);
  EXPECT_EQ(shot.renders[1].out, "b");
  EXPECT_EQ(shot.renders[1].line, 4);
  EXPECT_EQ(bench.run("vdg.render{}").renders.at(0).out, ".");  // the default (alone: "." holds every folder)
  EXPECT_EQ(shot.renders[2].first_frame, 12);
  EXPECT_EQ(shot.renders[2].last_frame, 12);
  EXPECT_TRUE(shot.scene.nodes.empty());
}

TEST(Script, PrintGoesToTheSink) {
  ScriptBench bench;
  bench.run("print('ease', vdg.ease.sine(0.5))\nprint(vdg.quat.identity(), vdg.ease.make('sinusoidal', 0.25, 0.75))");
  ASSERT_EQ(bench.printed.size(), 2u);
  EXPECT_EQ(bench.printed[0], "ease\t0.5");
  EXPECT_EQ(bench.printed[1], "quat(1, 0, 0, 0)\tease sinusoidal(t1=0.25, t2=0.75)");
}

TEST(Script, BadArgumentsNameTheFunctionAndLine) {
  ScriptBench bench;
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"vdg.set(1, 'translation', {0, 0, 0})",
       "test.lua:1: vdg.set: argument #1: expected a node (vdg.node, vdg.group or vdg.camera), got number"},
      {"local n = vdg.group{}\nvdg.set(n, 'colour', {1, 0, 0})",
       "test.lua:2: vdg.set: unknown field 'colour' (expected translation, rotation, scale, color, visible, sharpness, "
       "frame_offset or fov)"},
      {"local n = vdg.group{name = 'g'}\nvdg.set(n, 'fov', 30)",
       "test.lua:2: vdg.set: node 'g' (a group) has no field 'fov'"},
      {"local n = vdg.group{}\nvdg.set(n, 'translation', {0, 0})",
       "test.lua:2: vdg.set: value: expected a table of 3 numbers {x, y, z}"},
      {"local n = vdg.group{}\nvdg.set(n, 'scale', 0)", "test.lua:2: vdg.set: value: a scale of 0 is not invertible"},
      {"local n = vdg.group{}\nvdg.set(n, 'rotation', {0, 0, 0, 0})",
       "test.lua:2: vdg.set: value: a zero quaternion is no rotation"},
      {"local n = vdg.group{}\nvdg.change(n, 'translation', {1, 0, 0}, 10, 5)",
       "test.lua:2: vdg.change: the to frame (5.0) comes before the from frame (10.0)"},
      {"local n = vdg.group{}\nvdg.change(n, 'translation', {1, 0, 0}, 0, 5, 'bouncy')",
       "test.lua:2: vdg.change: ease: expected an ease (vdg.ease.make(...), \"linear\" or \"sine\")"},
      {"local n = vdg.group{name = 'n'}\nvdg.set(n, 'translation', {1, 0, 0})\nvdg.track(n, 'translation', {{0, {0, 0, "
       "0}}})",
       "test.lua:3: vdg.track: n.translation already has set/change actions (a field has a track or set/change "
       "actions, not "
       "both)"},
      {"local n = vdg.group{}\nvdg.track(n, 'translation', {{0, {0, 0, 0}}, {0, {1, 0, 0}}})",
       "test.lua:2: vdg.track: track 'group1.translation': 'keys'[1]: 'time' 0 must be greater than the previous key's "
       "0"},
      {"local n = vdg.group{}\nvdg.track(n, 'translation', {{0, {0, 0, 0}}}, 'cubic')",
       "test.lua:2: vdg.track: unknown interpolation 'cubic' (expected step, linear, catmull-rom, "
       "centripetal-catmull-rom, "
       "natural-cubic, parabolic-blending, bezier, slerp or quaternion-curve)"},
      {"vdg.group{name = 'a'}\nvdg.group{name = 'a'}",
       "test.lua:2: vdg.group: name 'a': there is already a node of that name"},
      {"vdg.group{name = 'a.b'}",
       "test.lua:1: vdg.group: name 'a.b': must not contain '.' (it separates node and field in \"node.field\")"},
      {"vdg.node{colour = {1, 0, 0}}",
       "test.lua:1: vdg.node: unknown field 'colour' (expected name, object, parent, translation, rotation, scale, "
       "placement, color, visible, sharpness, frame_offset, part_drivers)"},
      {"vdg.node{color = {2, 0, 0}}", "test.lua:1: vdg.node: color: expected a colour {r, g, b} of numbers in [0, 1]"},
      {"vdg.node{object = {}}", "test.lua:1: vdg.node: object: expected an object from vdg.load, got table"},
      {"vdg.camera{path = {points = {{0, 0, 0}, {1, 0, 0}}}}",
       "test.lua:1: vdg.camera: path: [\"end\"] (the frame the camera arrives) is missing"},
      {"vdg.camera{fov = 200}", "test.lua:1: vdg.camera: fov: expected a field of view in (0, 180) degrees"},
      {"vdg.use_camera(vdg.group{name = 'g'})", "test.lua:1: vdg.use_camera: node 'g' is not a camera"},
      {"vdg.for_each({1}, print)", "test.lua:1: vdg.for_each: object set element 1: expected a node, got number"},
      {"vdg.render{frames = '9-2'}", "test.lua:1: vdg.render: frames: the last frame (2) comes before the first (9)"},
      {"vdg.render{frames = 'all'}",
       "test.lua:1: vdg.render: frames: expected \"first-last\" (e.g. \"1-48\"), got \"all\""},
      {"vdg.render{size = {0, 10}}", "test.lua:1: vdg.render: size[1] (width): expected a whole number in [1, 16384]"},
      {"vdg.render{fps = 24}",
       "test.lua:1: vdg.render: unknown field 'fps' (expected frames, size, out, samples, background, silhouette, "
       "creases)"},
      {"vdg.load('missing.obj')", ""},
  };
  for (const auto& [text, expected] : cases) {
    const std::string error = bench.errorOfRun(text);
    if (expected.empty())
      EXPECT_EQ(error.rfind("test.lua:1: vdg.load: ", 0), 0u) << error;
    else
      EXPECT_EQ(error, expected) << text;
  }
}

}  // namespace
}  // namespace vdg

namespace vdg {
namespace {

// A script file: runScript reads it and names it in messages; the numbers of Parent 4.7.
TEST(Script, SunEarthMoonFromAFile) {
  testing::ScriptBench bench;
  const std::string path = std::string(VDG_SOURCE_DIR) + "/tests/script/data/sun_earth_moon.lua";
  const script::Shot shot = script::runScript(path, bench.options());
  EXPECT_EQ(shot.script_path, path);
  ASSERT_EQ(bench.printed, std::vector<std::string>{"earth orbit 10.0, moon orbit 2.0"});
  ASSERT_EQ(shot.renders.size(), 1u);
  EXPECT_EQ(shot.renders[0].last_frame, 364);
  const auto s = scene::Scene::build(shot.scene, "test");
  std::vector<scene::NodeState> states(static_cast<std::size_t>(s.nodeCount()));
  // Day 7: the moon a quarter round the earth (90 degrees), the earth 7/365 of its orbit.
  ASSERT_TRUE(s.evaluate(7, states));
  const double a = 2 * M_PI * 7 / 365;
  const Eigen::Vector3d earth = states[static_cast<std::size_t>(s.findNode("earth"))].world.block<3, 1>(0, 3);
  EXPECT_NEAR(earth.x(), 10 * std::cos(a), 1e-9);
  EXPECT_NEAR(earth.z(), -10 * std::sin(a), 1e-9);
  const Eigen::Vector3d moon = states[static_cast<std::size_t>(s.findNode("moon"))].world.block<3, 1>(0, 3);
  const double m = a + M_PI / 2;
  EXPECT_NEAR((moon - earth).x(), 2 * std::cos(m), 1e-9);
  EXPECT_NEAR((moon - earth).z(), -2 * std::sin(m), 1e-9);
}

}  // namespace
}  // namespace vdg

namespace vdg {
namespace {

TEST(Script, MeshesMadeByTheScriptCountVerticesFromOne) {
  testing::ScriptBench bench;
  const auto shot = bench.run(
      "local tri = vdg.mesh{positions = {0, 0, 0, 1, 0, 0, 0, 1, 0}, triangles = {1, 2, 3}}\n"
      "assert(tri.kind == 'mesh')\n"
      "vdg.node{name = 'a', object = tri}\n"
      "vdg.node{name = 'b', object = vdg.mesh{positions = {0, 0, 0, 1, 0, 0, 0, 1, 0}, triangles = {1, 3, 2}}}\n");
  ASSERT_EQ(shot.scene.meshes.size(), 2u);  // each call is a new object
  EXPECT_EQ(shot.scene.meshes[0]->triangles, (std::vector<std::int32_t>{0, 1, 2}));
  EXPECT_EQ(shot.scene.meshes[1]->triangles, (std::vector<std::int32_t>{0, 2, 1}));
  EXPECT_EQ(shot.scene.meshes[0]->positions[3], 1.0f);
  EXPECT_EQ(bench.errorOfRun("vdg.mesh{positions = {0, 0, 0, 1, 0, 0, 0, 1, 0}, triangles = {1, 2, 4}}"),
            "test.lua:1: vdg.mesh: triangles[3]: expected a vertex number in [1, 3]");
  EXPECT_EQ(bench.errorOfRun("vdg.mesh{positions = {0, 0, 0, 1, 0, 0, 0, 1, 0}, triangles = {0, 1, 2}}"),
            "test.lua:1: vdg.mesh: triangles[1]: expected a vertex number in [1, 3]");
  EXPECT_EQ(bench.errorOfRun("vdg.mesh{positions = {0, 0, 0, 1, 0, 0, 0, 1, 0/0}, triangles = {1, 2, 3}}"),
            "test.lua:1: vdg.mesh: positions[9]: expected a finite number");
  EXPECT_EQ(bench.errorOfRun("vdg.mesh{positions = {0, 0, 0, 1, 0}, triangles = {1, 2, 3}}"),
            "test.lua:1: vdg.mesh: positions: expected 3 numbers per vertex and at least 3 vertices, got 5 numbers");
  EXPECT_EQ(bench.errorOfRun("vdg.mesh{positions = {0, 0, 0, 1, 0, 0, 0, 1, 0}, triangle = {1, 2, 3}}")
                .find("test.lua:1: vdg.mesh: unknown field 'triangle'"),
            0u);
}

}  // namespace
}  // namespace vdg
