// Actors (Parent 4.8: objects that update themselves every frame and answer messages): state that
// persists from frame to frame, messages delivered in the stated order, a frame range equal to the
// same frames of a full run (the render farm's contract), the instruction budget and the memory
// limit stopping a runaway actor, one clear line for every bad definition; and the bounce
// example's affine squash and stretch (Parent 4.10) keeping the ball's volume.
#include <gtest/gtest.h>

#include <Eigen/LU>
#include <cmath>
#include <cstring>

#include "script/script_fixtures.h"
#include "vdg/geom/camera.h"
#include "vdg/viewdep/model.h"

namespace vdg {
namespace {

using scene::Field;
using testing::errorOf;
using testing::ScriptBench;
using testing::valueAt;

constexpr double kTol = 1e-12;
constexpr double kVolumeTol = 1e-9;  // det of the ball's linear map against r^3 (rounding of sqrt, quats)

scene::Scene build(const script::Shot& shot) { return scene::Scene::build(shot.scene, "test"); }

// Every node's world and object matrices at `frame`.
std::vector<scene::NodeState> statesAt(const scene::Scene& s, double frame) {
  std::vector<scene::NodeState> out(static_cast<std::size_t>(s.nodeCount()));
  EXPECT_TRUE(s.evaluate(frame, out));
  return out;
}

bool sameBits(const std::vector<scene::NodeState>& a, const std::vector<scene::NodeState>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (std::memcmp(a[i].object.data(), b[i].object.data(), sizeof(double) * 16) != 0) return false;
    if (std::memcmp(a[i].color.data(), b[i].color.data(), sizeof(float) * 3) != 0) return false;
    if (a[i].visible != b[i].visible) return false;
  }
  return true;
}

TEST(Actors, StatePersistsFromFrameToFrame) {
  ScriptBench bench;
  const auto shot = bench.run(
      "local box = vdg.group{name = 'box', translation = {0, 7, 0}}\n"
      "vdg.actor{name = 'counter', node = box, state = {n = 0},\n"
      "  update = function(self, frame)\n"
      "    self.state.n = self.state.n + 1\n"
      "    if frame >= 3 then self:set('translation', {self.state.n, frame, 0}) end\n"
      "  end}\n"
      "vdg.render{frames = '2-9'}\n");
  const auto s = build(shot);
  // The actors start at the shot's first frame (2): frame f is the (f - 1)-th update.
  for (int f = 3; f <= 9; ++f)
    EXPECT_EQ(valueAt(s, "box", Field::kTranslation, f), (std::vector<double>{f - 1.0, double(f), 0})) << f;
  // Before the actor first set it, the field has the node's value; between frames it holds (step).
  EXPECT_EQ(valueAt(s, "box", Field::kTranslation, 2), (std::vector<double>{0, 7, 0}));
  EXPECT_EQ(valueAt(s, "box", Field::kTranslation, 5.5), valueAt(s, "box", Field::kTranslation, 5));
  EXPECT_EQ(valueAt(s, "box", Field::kTranslation, 100), valueAt(s, "box", Field::kTranslation, 9));
  // One step track, keys only where the value changed.
  ASSERT_EQ(shot.scene.tracks.size(), 1u);
  EXPECT_EQ(shot.scene.tracks[0].track.name, "box.translation");
  EXPECT_EQ(shot.scene.tracks[0].track.interpolation, anim::Interpolation::kStep);
  EXPECT_EQ(shot.scene.tracks[0].track.keys.size(), 8u);  // frame 2 (the start value) and 3..9
}

TEST(Actors, SelfGetReadsTheValueSetAndOtherNodesAtTheFrame) {
  ScriptBench bench;
  const auto shot = bench.run(
      "local wall = vdg.group{name = 'wall', translation = {10, 0, 0}}\n"
      "vdg.change(wall, 'translation', {-5, 0, 0}, 0, 10)\n"
      "local ball = vdg.group{name = 'ball'}\n"
      "vdg.actor{name = 'ball', node = ball,\n"
      "  update = function(self, frame)\n"
      "    local x = self:get('translation')[1] + 1\n"
      "    if x > vdg.get(wall, 'translation')[1] - 1 then x = 0 end  -- near the wall: back to 0\n"
      "    self:set('translation', {x, 0, 0})\n"
      "    print(frame, x, self:get('translation')[1], vdg.get(wall, 'translation')[1])\n"
      "  end}\n"
      "vdg.render{frames = '0-7'}\n");
  ASSERT_EQ(bench.printed.size(), 8u);
  EXPECT_EQ(bench.printed[0], "0\t1.0\t1.0\t10.0");
  EXPECT_EQ(bench.printed[5], "5\t6.0\t6.0\t7.5");
  EXPECT_EQ(bench.printed[6], "6\t0\t0.0\t7.0");  // 7 > 7.0 - 1: back to 0
  const auto s = build(shot);
  EXPECT_NEAR(valueAt(s, "ball", Field::kTranslation, 7)[0], 1.0, kTol);
}

TEST(Actors, MessagesArriveTheNextFrameInTheOrderSent) {
  ScriptBench bench;
  bench.run(
      "local log = vdg.actor{name = 'log',\n"
      "  receive = function(self, message, sender) print(self.frame, sender.name, message) end}\n"
      "local a = vdg.actor{name = 'a', update = function(self, frame)\n"
      "  if frame == 1 then self:send(log, 'a1'); self:send('log', 'a2') end end,\n"
      "  receive = function(self, message, sender) print(self.frame, 'a got', message, 'from', sender.name) end}\n"
      "vdg.actor{name = 'b', update = function(self, frame)\n"
      "  if frame == 1 then self:send(log, 'b1'); self:send(a, 'b-to-a') end\n"
      "  if frame == 2 then self:send(log, 'b2') end end}\n"
      "a:send(log, 'from the script')\n"
      "vdg.render{frames = '0-4'}\n");
  // The script's message at the first frame; a's and b's of frame 1 at frame 2 in the order sent
  // (a runs before b: defined first); b's message to a (defined before b) waits for frame 2 too.
  const std::vector<std::string> expected = {"0\ta\tfrom the script",     "2\ta\ta1", "2\ta\ta2", "2\tb\tb1",
                                             "2\ta got\tb-to-a\tfrom\tb", "3\tb\tb2"};
  EXPECT_EQ(bench.printed, expected);
}

// The farm's contract: frames 50-60 computed with the actors stopped at 60 (and a second full run)
// give bit-identical states to those frames of a full run, random numbers included.
TEST(Actors, AFrameRangeEqualsTheSameFramesOfAFullRun) {
  const std::string text =
      "local ball = vdg.group{name = 'ball'}\n"
      "local lamp = vdg.node{name = 'lamp', object = vdg.mesh{positions = {0,0,0, 1,0,0, 0,1,0}, triangles = "
      "{1,2,3}}}\n"
      "local lamp_actor = vdg.actor{name = 'lamp', node = lamp, state = {k = 0},\n"
      "  receive = function(self, hit) self.state.k = 1 end,\n"
      "  update = function(self) self:set('color', {self.state.k, 0.5, 0}); self.state.k = self.state.k * 0.7 end}\n"
      "vdg.actor{name = 'ball', node = ball, state = {y = 5, v = 0, x = 0},\n"
      "  update = function(self)\n"
      "    local st = self.state\n"
      "    st.v = st.v - 9.8 / 24; st.y = st.y + st.v / 24; st.x = st.x + math.random() * 0.1\n"
      "    if st.y < 0 then st.y = -st.y; st.v = -0.8 * st.v; self:send(lamp_actor, 'hit') end\n"
      "    self:set('translation', {st.x, st.y, 0})\n"
      "    self:set('rotation', vdg.quat.axis_angle({0, 0, 1}, st.x * 40))\n"
      "  end}\n"
      "vdg.render{frames = '0-120'}\n";
  ScriptBench bench;
  const auto full = build(bench.run(text));
  const auto again = build(bench.run(text));
  auto options = bench.options();
  options.actor_last_frame = 60;
  const auto part = build(script::runScriptText(text, "test.lua", bench.scripts, options));
  int bounces = 0;
  for (int f = 0; f <= 120; ++f) {
    EXPECT_TRUE(sameBits(statesAt(full, f), statesAt(again, f))) << f;
    if (f >= 50 && f <= 60) {
      EXPECT_TRUE(sameBits(statesAt(full, f), statesAt(part, f))) << f;
    }
    if (f > 0 && statesAt(full, f)[1].color[0] == 1.0f) ++bounces;
  }
  EXPECT_GE(bounces, 2);  // the lamp was told, so the messages are part of what was compared
  EXPECT_TRUE(sameBits(statesAt(part, 200), statesAt(full, 60)));  // the range's last frame holds
}

TEST(Actors, TheBudgetStopsARunawayActorNamingIt) {
  ScriptBench bench;
  auto options = bench.options();
  options.instruction_budget = 2'000'000;
  const std::string loop =
      "vdg.actor{name = 'spinner', update = function(self, frame)\n"
      "  if frame == 3 then while true do end end end}\n"
      "vdg.render{frames = '0-10'}\n";
  const std::string e = errorOf([&] { script::runScriptText(loop, "test.lua", bench.scripts, options); });
  EXPECT_EQ(
      e, "test.lua: exceeded its instruction budget (2000000 instructions; endless loop?) (actor 'spinner', frame 3)");
  // pcall inside the actor cannot hold the budget back.
  const std::string caught =
      "vdg.actor{name = 'sly', update = function(self)\n"
      "  for i = 1, 100 do pcall(function() while true do end end) end end}\n"
      "vdg.render{frames = '0-10'}\n";
  EXPECT_EQ(errorOf([&] { script::runScriptText(caught, "test.lua", bench.scripts, options); }),
            "test.lua: exceeded its instruction budget (2000000 instructions; endless loop?) (actor 'sly', frame 0)");
  // Memory: an actor that hoards, and one that floods another with messages.
  options.instruction_budget = 200'000'000;
  options.memory_limit = 8u << 20;
  const std::string hoard =
      "vdg.actor{name = 'hoarder', state = {t = {}}, update = function(self)\n"
      "  for i = 1, 100000 do self.state.t[#self.state.t + 1] = {i} end end}\n"
      "vdg.render{frames = '0-1000'}\n";
  EXPECT_EQ(errorOf([&] { script::runScriptText(hoard, "test.lua", bench.scripts, options); }).substr(0, 47),
            "test.lua: out of memory (limit 8 MiB) (actor 'h");
  const std::string flood =
      "local sink = vdg.actor{name = 'sink', receive = function() end}\n"
      "vdg.actor{name = 'flood', update = function(self) for i = 1, 1e9 do self:send(sink, {i}) end end}\n"
      "vdg.render{frames = '0-10'}\n";
  EXPECT_EQ(errorOf([&] { script::runScriptText(flood, "test.lua", bench.scripts, options); }),
            "test.lua: out of memory (limit 8 MiB) (actor 'flood', frame 0)");
}

TEST(Actors, BadDefinitionsAndUsesAreOneClearLine) {
  struct Case {
    const char* script;
    const char* message;
  };
  const Case cases[] = {
      {"vdg.actor(3)",
       "test.lua:1: vdg.actor: expected a table {name = ..., update = function(self, frame) ... end}, got number"},
      {"vdg.actor{name = 4, update = print}", "test.lua:1: vdg.actor: name: expected a non-empty string, got number"},
      {"vdg.actor{name = 'ball', updte = function() end}",
       "test.lua:1: vdg.actor 'ball': unknown field 'updte' (expected name, node, drives, state, update, receive)"},
      {"vdg.actor{name = 'ball', update = 5}",
       "test.lua:1: vdg.actor 'ball': update: expected a function (self, frame), got number"},
      {"vdg.actor{name = 'ball', receive = {}}",
       "test.lua:1: vdg.actor 'ball': receive: expected a function (self, message, sender), got table"},
      {"vdg.actor{name = 'ball', state = 1, update = print}",
       "test.lua:1: vdg.actor 'ball': state: expected a table, got number"},
      {"vdg.actor{name = 'ball'}",
       "test.lua:1: vdg.actor 'ball': expected an update or a receive function (an actor with neither does nothing)"},
      {"vdg.actor{name = 'ball', update = print}\nvdg.actor{name = 'ball', update = print}",
       "test.lua:2: vdg.actor 'ball': name: an actor named 'ball' already exists"},
      {"vdg.actor{name = 'ball', node = 'ball', update = print}",
       "test.lua:1: vdg.actor 'ball': node: expected a node (vdg.node, vdg.group, vdg.camera), got string"},
      {"local g = vdg.group{name = 'g'}\nvdg.actor{name = 'a', node = g, update = print}\n"
       "vdg.actor{name = 'b', drives = {g}, update = print}",
       "test.lua:3: vdg.actor 'b': drives[1]: node 'g' is already driven by actor 'a' (one actor per node: send it "
       "messages instead)"},
      {"local g = vdg.group{name = 'g'}\nlocal h = vdg.group{name = 'h'}\nvdg.actor{name = 'a', drives = {h, g}, "
       "update = print}\n"
       "vdg.actor{name = 'b', node = g, update = print}",
       "test.lua:4: vdg.actor 'b': node: node 'g' is already driven by actor 'a' (one actor per node: send it messages "
       "instead)"},
      {"local g = vdg.group{name = 'g'}\nvdg.actor{name = 'a', drives = {g, 'h'}, update = print}",
       "test.lua:2: vdg.actor 'a': drives[2]: expected a node (vdg.node, vdg.group, vdg.camera), got string"},
      {"local g = vdg.group{name = 'g'}\nvdg.actor{name = 'a', node = g, drives = {g}, update = print}",
       "test.lua:2: vdg.actor 'a': drives[1]: node 'g' is given twice"},
      // Uses, while the actors run.
      {"local g = vdg.group{name = 'g'}\nvdg.actor{name = 'a', node = g, update = function(self) self:set('colour', 1) "
       "end}\n"
       "vdg.render{}",
       "test.lua:2: actor 'a': set: expected a field name (translation, rotation, scale, color, visible, sharpness, "
       "frame_offset or fov), got colour (actor 'a', frame 1)"},
      {"local g = vdg.group{name = 'g'}\nvdg.actor{name = 'a', node = g, update = function(self) self:set('color', {1, "
       "0, 0}) end}\n"
       "vdg.render{}",
       "test.lua:2: actor 'a': set: node 'g' (a group) has no field 'color' (actor 'a', frame 1)"},
      {"local g = vdg.group{name = 'g'}\nvdg.actor{name = 'a', node = g, update = function(self) self:set('scale', 0) "
       "end}\n"
       "vdg.render{}",
       "test.lua:2: actor 'a': set: g.scale: a scale of 0 is not invertible (actor 'a', frame 1)"},
      {"local g = vdg.group{name = 'g'}\nvdg.set(g, 'translation', {1, 2, 3}, 4)\n"
       "vdg.actor{name = 'a', node = g, update = function(self) self:set('translation', {0, 0, 0}) end}\nvdg.render{}",
       "test.lua:3: actor 'a': set: g.translation already has set/change actions (a field is driven by an actor, a "
       "track "
       "or set/change actions: one of them) (actor 'a', frame 1)"},
      {"local g = vdg.group{name = 'g'}\nlocal h = vdg.group{name = 'h'}\n"
       "vdg.actor{name = 'a', node = g, update = function(self) self:set(h, 'translation', {0, 0, 0}) "
       "end}\nvdg.render{}",
       "test.lua:3: actor 'a': set: node 'h' is not driven by this actor (give it in vdg.actor{node = ...} or drives = "
       "{...}) "
       "(actor 'a', frame 1)"},
      {"local g = vdg.group{name = 'g'}\nvdg.actor{name = 'a', update = function(self) vdg.set(g, 'visible', false) "
       "end}\n"
       "vdg.render{}",
       "test.lua:2: vdg.set: the scene is fixed once the actors run (an actor changes its node with self:set and talks "
       "to "
       "others with self:send) (actor 'a', frame 1)"},
      {"vdg.actor{name = 'a', update = function(self) self:send('nobody', 1) end}\nvdg.render{}",
       "test.lua:1: actor 'a': send: no actor named 'nobody' (actor 'a', frame 1)"},
      {"local mute = vdg.actor{name = 'mute', update = print}\nvdg.actor{name = 'a', update = function(self) "
       "self:send(mute, 1) end}\n"
       "vdg.render{}",
       "test.lua:2: actor 'a': send: actor 'mute' has no receive function (actor 'a', frame 1)"},
      {"vdg.actor{name = 'a', update = function(self) print(os.time()) end}\nvdg.render{}",
       "test.lua:1: os.time: not available while the actors run (their frames must be the same in every run) (actor "
       "'a', frame 1)"},
      {"local a = vdg.actor{name = 'a', update = print}\na.state = {}",
       "test.lua:2: actor 'a': its fields cannot be assigned (keep your own values in self.state)"},
      {"local a = vdg.actor{name = 'a', update = print}\nprint(a.speed)",
       "test.lua:2: actor 'a': no field 'speed' (actors have name, node, state, frame, set, get and send; keep your "
       "own "
       "values in self.state)"},
      {"local g = vdg.group{name = 'g'}\nlocal a = vdg.actor{name = 'a', node = g, update = "
       "print}\na:set('translation', {1, 2, 3})",
       "test.lua:3: actor 'a': set: only while the actors run (in update or receive); give the node its first values "
       "with "
       "vdg.node's fields"},
      {"local g = vdg.group{name = 'g'}\nprint(vdg.get(g, 'translation'))",
       "test.lua:2: vdg.get: only while the actors run (in their update and receive functions)"},
      {"vdg.actor{name = 'a', update = function(self, frame) if frame == 2 then error('boom') end "
       "end}\nvdg.render{frames = '0-5'}",
       "test.lua:1: boom (actor 'a', frame 2)"},
  };
  for (const Case& c : cases) {
    ScriptBench bench;
    const std::string e = bench.errorOfRun(c.script);
    EXPECT_EQ(e, c.message) << c.script;
    EXPECT_EQ(e.find('\n'), std::string::npos) << c.script;
  }
}

// math.random starts from the same seed in every run (the description phase too), and pairs visits
// keys in a fixed order (Lua's own order of string keys changes from run to run): numbers by
// value, then strings bytewise, then false and true.
TEST(Actors, RandomNumbersAndPairsAreTheSameInEveryRun) {
  const std::string text =
      "print(math.random(), math.random(1, 1000000))\n"
      "local t = {true, 'x', [2.5] = 1, [-1] = 1, b = 1, a = 1, aa = 1, B = 1, [true] = 1, [false] = 1, k10 = 1, k9 = "
      "1}\n"
      "local keys = {}\n"
      "for k, v in pairs(t) do keys[#keys + 1] = tostring(k); if k == 'a' then t.b = nil end end\n"
      "print(table.concat(keys, ' '))\n"
      "local proxy = setmetatable({}, {__pairs = function() return function(_, k) if not k then return 1, 'p' end end "
      "end})\n"
      "for k, v in pairs(proxy) do print(k, v) end\n";
  ScriptBench one, two;
  one.run(text);
  two.run(text);
  ASSERT_EQ(one.printed.size(), 3u);
  EXPECT_EQ(one.printed, two.printed);
  // 'b' was removed while the traversal was at 'a': skipped.
  EXPECT_EQ(one.printed[1], "-1 1 2 2.5 B a aa k10 k9 false true");
  EXPECT_EQ(one.printed[2], "1\tp");  // __pairs still decides
}

// The bounce example: the ball stays in the room, squashes at impacts, and its affine squash and
// stretch (Parent 4.10) keeps its volume at every frame: the linear part of ball_spin's object
// matrix is R S R^T Spin with S = diag(1/sqrt(s), s, 1/sqrt(s)), whose determinant is 1.
TEST(Actors, TheBounceExampleKeepsTheBallsVolumeAndSquashesAtImpacts) {
  const std::string path = std::string(VDG_SOURCE_DIR) + "/examples/bounce/bounce.lua";
  script::ScriptOptions options;
  options.print = [](std::string_view) {};
  const script::Shot shot = script::runScript(path, options);
  const auto s = build(shot);
  ASSERT_EQ(shot.renders.size(), 1u);
  const int spin = s.findNode("ball_spin"), ball = s.findNode("ball"), floor = s.findNode("floor");
  ASSERT_GE(spin, 0);
  constexpr double kRadius = 0.6;
  int squashed_frames = 0, floor_flashes = 0;
  for (int f = shot.renders[0].first_frame; f <= shot.renders[0].last_frame; ++f) {
    const auto st = statesAt(s, f);
    const Eigen::Matrix3d m = st[static_cast<std::size_t>(spin)].object.topLeftCorner<3, 3>();
    EXPECT_NEAR(m.determinant(), 1.0, kVolumeTol) << "frame " << f;
    // The singular values are s, 1/sqrt(s), 1/sqrt(s) (the map's scales).
    const Eigen::Vector3d sv = Eigen::JacobiSVD<Eigen::Matrix3d>(m).singularValues();
    const double smallest = sv.minCoeff();
    if (smallest < 0.9) ++squashed_frames;
    EXPECT_TRUE(std::abs(sv[0] - sv[1]) < kVolumeTol || std::abs(sv[1] - sv[2]) < kVolumeTol)
        << "two equal scales across the axis, frame " << f;
    // The ball's centre stays at least its squashed radius above the floor.
    const Eigen::Vector3d centre = st[static_cast<std::size_t>(ball)].world.col(3).head<3>();
    EXPECT_GE(centre.y(), kRadius * smallest - 1e-9) << "frame " << f;
    EXPECT_GE(centre.x(), -4.5 + kRadius * smallest - 1e-9) << "frame " << f;
    if (st[static_cast<std::size_t>(floor)].color[0] > 0.7f) ++floor_flashes;
  }
  EXPECT_GE(squashed_frames, 3);  // several impacts squash the ball
  EXPECT_GE(floor_flashes, 2);    // and the floor was told of them
}

}  // namespace
}  // namespace vdg

namespace vdg {
namespace {

// Keys at distances in a scene (examples/spot/dolly.lua, docs/weights.md): the camera flies from
// beyond the wide front key in to the close-up's eye; the instance's eye (Scene::instanceEye, in
// the model's frame) weighs the model, so the weights move from the wide key to the close-up
// without a jump and end on the close-up alone.
TEST(Actors, TheDollyExampleTurnsTheWideKeyIntoTheCloseUp) {
  constexpr double kWeightTol = 1e-5;
  constexpr double kMaxFrameChange = 0.25;  // 25 frames from wide to close: no frame takes a pop
  const std::string path = std::string(VDG_SOURCE_DIR) + "/examples/spot/dolly.lua";
  script::ScriptOptions options;
  options.print = [](std::string_view) {};
  const script::Shot shot = script::runScript(path, options);
  const auto s = build(shot);
  const int cow = s.findNode("spot");
  ASSERT_GE(cow, 0);
  const ViewDependentModel* model = s.model(cow);
  ASSERT_NE(model, nullptr);
  ASSERT_EQ(model->weightSpace(), WeightSpace::Positions);
  std::size_t front = 0, close = 0;
  for (std::size_t k = 0; k < model->keyCount(); ++k) {
    if (model->keyName(k) == "front") front = k;
    if (model->keyName(k) == "front-close") close = k;
  }
  std::vector<float> w(model->keyCount() + 1), previous;
  for (int f = shot.renders[0].first_frame; f <= shot.renders[0].last_frame; ++f) {
    const auto st = statesAt(s, f);
    Camera camera;
    ASSERT_TRUE(s.camera(f, st, camera));
    Eigen::Vector3d eye;
    ASSERT_TRUE(s.instanceEye(cow, st[static_cast<std::size_t>(cow)], camera.eye, eye));
    ASSERT_TRUE(model->denseWeightsAtEye(eye, 0.0, w)) << "frame " << f;
    for (std::size_t k = 0; k < previous.size(); ++k) {
      EXPECT_LT(std::abs(w[k] - previous[k]), kMaxFrameChange) << "frame " << f;
    }
    previous = w;
  }
  EXPECT_NEAR(w[close], 1.0, kWeightTol);  // the last frame is at the close-up's eye
  EXPECT_EQ(w[front], 0.0f);
}

}  // namespace
}  // namespace vdg
