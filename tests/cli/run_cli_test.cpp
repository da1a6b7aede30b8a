// `vdg run SCRIPT.lua` as a user runs it: frames written where asked, a frame rendered alone equal
// byte for byte to the same frame of a full run, hostile scripts stopped with one clear line and
// no effect outside the output folder, and the shipped example scripts running.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "cli/run_vdg.h"
#include "support/test_meshes.h"

namespace {

namespace fs = std::filesystem;
using vdg::testing::readText;
using vdg::testing::Result;
using vdg::testing::runVdg;

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

void writeText(const std::string& path, const std::string& text) { std::ofstream(path, std::ios::binary) << text; }

// A small scene built in the language: a tetrahedron mesh made from numbers, two instances, one
// spinning, a fixed camera; frames 0-5 rendered at 64x48 into OUT/shot.
const char* kTetraScene = R"(
local tet = vdg.mesh{positions = {1, 1, 1, -1, -1, 1, -1, 1, -1, 1, -1, -1},
                     triangles = {1, 3, 2, 1, 2, 4, 1, 4, 3, 2, 3, 4}}
local a = vdg.node{name = "a", object = tet, translation = {-1.5, 0, 0}, color = {0.9, 0.3, 0.2}}
vdg.node{name = "b", object = tet, translation = {1.5, 0, 0}, color = {0.2, 0.4, 0.9}}
vdg.change(a, "rotation", vdg.quat.axis_angle({0, 1, 0}, 90), 0, 5, "sine")
vdg.camera{name = "cam", translation = {0, 1, 7}, fov = 45}
vdg.render{frames = "0-5", size = {64, 48}, out = "shot"}
)";

TEST(RunCli, FramesAreWrittenAndARangeEqualsTheSameFramesOfAFullRun) {
  vdg::testing::TempDir dir;
  const std::string script = dir.file("tetra.lua");
  writeText(script, kTetraScene);
  Result r = runVdg("run '" + script + "' -o '" + dir.file("full") + "' --quiet");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.out, "");
  for (int f = 0; f <= 5; ++f)
    EXPECT_TRUE(fs::exists(dir.file("full/shot/frame_000" + std::to_string(f) + ".png"))) << f;

  r = runVdg("run '" + script + "' -o '" + dir.file("part") + "' --frames 3-4");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(contains(r.out, "wrote 2 frames")) << r.out;
  for (const char* name : {"frame_0003.png", "frame_0004.png"})
    EXPECT_EQ(readText(dir.file(std::string("part/shot/") + name)),
              readText(dir.file(std::string("full/shot/") + name)))
        << name;
  EXPECT_FALSE(fs::exists(dir.file("part/shot/frame_0002.png")));
  EXPECT_FALSE(fs::exists(dir.file("part/shot/frame_0005.png")));
  // The spin shows: frames 0 and 5 differ.
  EXPECT_NE(readText(dir.file("full/shot/frame_0000.png")), readText(dir.file("full/shot/frame_0005.png")));
}

TEST(RunCli, AFrameRangeOutsideTheScriptsIsAUsageError) {
  vdg::testing::TempDir dir;
  const std::string script = dir.file("tetra.lua");
  writeText(script, kTetraScene);
  const Result r = runVdg("run '" + script + "' -o '" + dir.file("out") + "' --frames 100-200");
  EXPECT_EQ(r.code, 2);
  EXPECT_TRUE(contains(r.err, "--frames '100-200': the script renders frames 0-5, none of them in the range")) << r.err;
  EXPECT_FALSE(fs::exists(dir.file("out/shot")));
}

struct Hostile {
  const char* name;
  const char* text;
  const char* message;
};

TEST(RunCli, HostileScriptsStopWithOneClearLineAndTouchNothingOutside) {
  const Hostile cases[] = {
      {"loop", "while true do end", "loop.lua: exceeded its instruction budget"},
      {"memory", "local t = {} for i = 1, 1e9 do t[i] = string.rep('x', 1000) .. i end", "memory.lua: out of memory"},
      {"execute", "os.execute('touch /tmp/vdg-run-test-pwned')", "execute.lua:1:"},
      {"passwd", "local f = io.open('/etc/passwd') print(f:read('a'))", "passwd.lua:1:"},
      {"escape", "local f = io.open('../escaped.txt', 'w') f:write('x') f:close()", "escape.lua:1:"},
      {"syntax", "vdg.node{name = }", "syntax.lua:1:"},
  };
  for (const Hostile& c : cases) {
    vdg::testing::TempDir dir;
    fs::create_directories(dir.file("scripts"));
    const std::string script = dir.file(std::string("scripts/") + c.name + ".lua");
    writeText(script, c.text);
    const Result r = runVdg("run '" + script + "' -o '" + dir.file("out") + "'");
    EXPECT_EQ(r.code, 1) << c.name << ": " << r.err;
    EXPECT_TRUE(contains(r.err, c.message)) << c.name << ": " << r.err;
    EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << c.name << ": one line: " << r.err;
    EXPECT_FALSE(fs::exists(dir.file("escaped.txt"))) << c.name;
    EXPECT_FALSE(fs::exists(dir.file("scripts/escaped.txt"))) << c.name;
  }
  EXPECT_FALSE(fs::exists("/tmp/vdg-run-test-pwned"));
}

TEST(RunCli, AMissingScriptIsOneLine) {
  const Result r = runVdg("run /nonexistent/scene.lua");
  EXPECT_EQ(r.code, 1);
  EXPECT_TRUE(contains(r.err, "/nonexistent/scene.lua")) << r.err;
}

// The shipped examples load and render (frame 0 of each, small); their full sequences are what
// `make demo` renders.
TEST(RunCli, TheExampleScriptsRun) {
  vdg::testing::TempDir dir;
  for (const char* example :
       {"figure13/figure13.lua", "crowd/crowd.lua", "solar/solar.lua", "bounce/bounce.lua", "spot/cubist.lua"}) {
    const Result r = runVdg(std::string("run examples/") + example + " --root examples --frames 0 --quiet -o '" +
                            dir.file("out") + "'");
    EXPECT_EQ(r.code, 0) << example << ": " << r.err;
  }
  for (const char* frame : {"out/figure13/frame_0000.png", "out/crowd/frame_0000.png", "out/solar/frame_0000.png",
                            "out/bounce/frame_0000.png", "out/cubist/frame_0000.png"})
    EXPECT_TRUE(fs::exists(dir.file(frame))) << frame;
}

}  // namespace

// "-o shots/" names a folder that does not exist yet with a trailing slash (as the README writes
// it): the output sandbox takes it for the same folder as "shots", not for a way out of it.
TEST(RunCli, AnOutputFolderWithATrailingSlashThatDoesNotExistYetIsUsed) {
  vdg::testing::TempDir dir;
  const std::string script = dir.file("tetra.lua");
  writeText(script, kTetraScene);
  const Result r = runVdg("run '" + script + "' -o '" + dir.file("shots") + "/' --frames 0 -q");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.out, "");  // -q, like every subcommand's
  EXPECT_TRUE(fs::exists(dir.file("shots/shot/frame_0000.png")));
}
