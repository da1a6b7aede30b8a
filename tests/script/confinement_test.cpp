// The sandbox's files and limits beyond the paths a script names: every file a load reaches obeys
// the read root (vdg::ScopedReadRoot), io.open and io.lines check the file they opened, xpcall's
// handler runs under the budget, render requests write folders of their own, and the child process
// vdg run runs scripts in is killed past its CPU time (script/child_process.h).
#include <sys/stat.h>
#include <unistd.h>

#include <csignal>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "script/script_fixtures.h"
#include "vdg/io/read_file.h"
#include "vdg/script/child_process.h"

namespace vdg {
namespace {

using testing::ScriptBench;
using testing::writeText;
namespace fs = std::filesystem;

// A one-triangle glTF file whose positions are in the external buffer `uri` (36 bytes).
std::string triangleGltf(const std::string& uri) {
  return R"({"asset": {"version": "2.0"}, "buffers": [{"uri": ")" + uri +
         R"(", "byteLength": 36}], "bufferViews": [{"buffer": 0, "byteLength": 36}],
  "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                 "min": [0, 0, 0], "max": [1, 1, 0]}],
  "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}], "nodes": [{"mesh": 0}],
  "scenes": [{"nodes": [0]}], "scene": 0})";
}

std::string triangleBytes() {
  const float v[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  return std::string(reinterpret_cast<const char*>(v), sizeof v);
}

std::string errorWith(ScriptBench& bench, const std::string& text) { return bench.errorOfRun(text, "s.lua"); }

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

TEST(ScriptConfinement, AGltfBufferThatLinksOutOfTheRootIsRefused) {
  ScriptBench bench;
  writeText(bench.scripts + "/t.gltf", triangleGltf("t.bin"));
  writeText(bench.scripts + "/t.bin", triangleBytes());
  EXPECT_EQ(bench.run("vdg.node{object = vdg.load('t.gltf')}").scene.meshes.size(), 1u);

  writeText(bench.dir.file("outside.bin"), triangleBytes());
  writeText(bench.scripts + "/l.gltf", triangleGltf("link.bin"));
  fs::create_symlink(bench.dir.file("outside.bin"), bench.scripts + "/link.bin");
  const std::string root = fs::canonical(bench.scripts).string();
  EXPECT_EQ(errorWith(bench, "vdg.load('l.gltf')"), "s.lua:1: vdg.load: " + root + "/l.gltf: buffers: " + root +
                                                        "/link.bin: the glTF buffer leads outside the read root '" +
                                                        root + "'");
  // With the root widened above it, the same file loads.
  bench.read_root = bench.dir.path().string();
  EXPECT_EQ(bench.run("vdg.node{object = vdg.load('l.gltf')}").scene.meshes.size(), 1u);
  EXPECT_EQ(currentReadRoot(), "");  // the root ends with the script
}

TEST(ScriptConfinement, AnObjMaterialLibraryOrTextureOutsideTheRootIsRefusedNotWarned) {
  ScriptBench bench;
  writeText(bench.dir.file("secret.mtl"), "newmtl red\nKd 1 0 0\n");
  fs::create_symlink(bench.dir.file("secret.mtl"), bench.scripts + "/m.mtl");
  writeText(bench.scripts + "/tri.obj", "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl red\nf 1 2 3\n");
  const std::string error = errorWith(bench, "vdg.load('tri.obj')");
  EXPECT_TRUE(contains(error, "tri.obj:1: mtllib: ")) << error;
  EXPECT_TRUE(contains(error, "m.mtl: the material library leads outside the read root")) << error;
  EXPECT_TRUE(bench.printed.empty());  // no warning quoting the file

  writeText(bench.scripts + "/t.mtl", "newmtl red\nKd 1 0 0\nmap_Kd tex.png\n");
  fs::copy_file(VDG_SOURCE_DIR "/tests/hostile/inputs/drawing.png", bench.dir.file("tex.png"));
  fs::create_symlink(bench.dir.file("tex.png"), bench.scripts + "/tex.png");
  writeText(bench.scripts + "/tex.obj", "mtllib t.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nusemtl red\nf 1 2 3\n");
  const std::string texture = errorWith(bench, "vdg.load('tex.obj')");
  EXPECT_TRUE(contains(texture, "t.mtl:3: map_Kd: ")) << texture;
  EXPECT_TRUE(contains(texture, "tex.png: the texture leads outside the read root")) << texture;
}

TEST(ScriptConfinement, IoOpenAndLinesRefuseFifosAndDevices) {
  ScriptBench bench;
  ASSERT_EQ(::mkfifo((bench.scripts + "/pipe").c_str(), 0600), 0);
  EXPECT_EQ(errorWith(bench, "local f = io.open('pipe')"),
            "s.lua:1: io.open: reading 'pipe': a FIFO (named pipe) is refused (regular files only)");
  EXPECT_EQ(errorWith(bench, "for l in io.lines('pipe') do end"),
            "s.lua:1: io.lines: reading 'pipe': a FIFO (named pipe) is refused (regular files only)");
  ASSERT_EQ(::mkfifo((bench.out + "/pipe").c_str(), 0600), 0);
  EXPECT_EQ(errorWith(bench, "local f = io.open('pipe', 'r+')"),
            "s.lua:1: io.open: writing 'pipe': a FIFO (named pipe) is refused (regular files only)");
  EXPECT_EQ(errorWith(bench, "local f = io.open('pipe', 'a+')"),
            "s.lua:1: io.open: writing 'pipe': a FIFO (named pipe) is refused (regular files only)");
  fs::create_directories(bench.scripts + "/folder");
  EXPECT_EQ(errorWith(bench, "local f = io.open('folder')"),
            "s.lua:1: io.open: reading 'folder': not a regular file (a folder or a device is refused)");
  // A file that is not there is io.open's usual nil, message, code.
  bench.run("local f, e, code = io.open('none.txt')\nassert(f == nil and e:find('No such file') and code == 2)");
}

TEST(ScriptConfinement, IoOpenWritesNeitherThroughLinksNorIntoHardLinks) {
  ScriptBench bench;
  writeText(bench.dir.file("outside.txt"), "keep");
  fs::create_hard_link(bench.dir.file("outside.txt"), bench.out + "/hard.txt");
  EXPECT_EQ(errorWith(bench, "io.open('hard.txt', 'w')"),
            "s.lua:1: io.open: writing 'hard.txt': a file with another hard link is refused for writing");
  EXPECT_EQ(testing::readText(bench.dir.file("outside.txt")), "keep");
  writeText(bench.out + "/real.txt", "real");
  fs::create_symlink("real.txt", bench.out + "/inner-link.txt");
  EXPECT_EQ(errorWith(bench, "io.open('inner-link.txt', 'a')"),
            "s.lua:1: io.open: writing 'inner-link.txt': writing through a symbolic link is refused");
  // Plain writes, appends and reads back work; each created file is announced.
  std::vector<std::string> created;
  auto options = bench.options();
  options.created = [&](const std::string& path) { created.push_back(path); };
  script::runScriptText(
      "local f = assert(io.open('new.txt', 'w'))\nf:write('a')\nf:close()\n"
      "f = assert(io.open('new.txt', 'a'))\nf:write('b')\nf:close()\n"
      "f = assert(io.open('new.txt', 'r+'))\nassert(f:read('a') == 'ab')\nf:close()\n"
      "f = assert(io.open('real.txt', 'w'))\nf:write('x')\nf:close()",
      "s.lua", bench.scripts, options);
  EXPECT_EQ(created, std::vector<std::string>{fs::weakly_canonical(bench.out).string() + "/new.txt"});
}

TEST(ScriptConfinement, IoLinesReadsLinesAndFormats) {
  ScriptBench bench;
  writeText(bench.scripts + "/n.txt", "1 2\n3\n");
  bench.run(
      "local s = 0\nfor a in io.lines('n.txt', 'n') do s = s + a end\nassert(s == 6, s)\n"
      "local lines = {}\nfor l in io.lines('n.txt') do lines[#lines + 1] = l end\n"
      "assert(#lines == 2 and lines[1] == '1 2')");
}

TEST(ScriptConfinement, AnXpcallHandlerCannotEscapeTheBudget) {
  ScriptBench bench;
  auto options = bench.options();
  options.instruction_budget = 100000;
  const std::string budget = "s.lua: exceeded its instruction budget (100000 instructions; endless loop?)";
  EXPECT_EQ(testing::errorOf([&] {
              script::runScriptText("xpcall(error, function() while true do end end)", "s.lua", bench.scripts, options);
            }),
            budget);
  EXPECT_EQ(testing::errorOf([&] {
              script::runScriptText("while true do xpcall(function() while true do end end, print) end", "s.lua",
                                    bench.scripts, options);
            }),
            budget);
  // xpcall still returns what Lua's does.
  bench.run(
      "local ok, a, b = xpcall(function(x) return x, 2 end, print, 1)\nassert(ok and a == 1 and b == 2)\n"
      "local ok2, e = xpcall(error, function(m) return 'handled ' .. m end, 'boom', 0)\n"
      "assert(not ok2 and e == 'handled boom', e)\n"
      "local ok3, e3 = xpcall(error, function() error('again', 0) end, 'x')\nassert(not ok3 and e3 == 'again')");
  EXPECT_NE(bench.errorOfRun("xpcall(print)").find("bad argument #2 to 'xpcall'"), std::string::npos);
}

TEST(ScriptConfinement, RenderRequestsWriteFoldersOfTheirOwn) {
  ScriptBench bench;
  const std::string overlap = " (each vdg.render needs a folder of its own, not the same as another's or inside it)";
  EXPECT_EQ(errorWith(bench, "vdg.render{out = 'a'}\nvdg.render{frames = 2, out = 'a/'}"),
            "s.lua:2: vdg.render: out 'a' overlaps the out 'a' of the render call at line 1" + overlap);
  EXPECT_EQ(errorWith(bench, "vdg.render{out = 'a/b'}\nvdg.render{out = 'a'}"),
            "s.lua:2: vdg.render: out 'a' overlaps the out 'a/b' of the render call at line 1" + overlap);
  EXPECT_EQ(errorWith(bench, "vdg.render{}\nvdg.render{out = 'x'}"),
            "s.lua:2: vdg.render: out 'x' overlaps the out '.' of the render call at line 1" + overlap);
  fs::create_directories(bench.out + "/real");
  fs::create_directory_symlink("real", bench.out + "/alias");
  EXPECT_EQ(errorWith(bench, "vdg.render{out = 'real'}\nvdg.render{out = 'alias/sub'}"),
            "s.lua:2: vdg.render: out 'alias/sub' overlaps the out 'real' of the render call at line 1" + overlap);
  EXPECT_EQ(bench.run("vdg.render{out = 'a'}\nvdg.render{out = 'ab'}\nvdg.render{out = 'b/a'}").renders.size(), 3u);
}

// The child process: this test program again, running one of the DISABLED_ bodies below (which
// ctest does not run on their own), with its end reported as it happened.
script::ChildOutcome runBody(const std::string& body, int cpu_seconds) {
  script::ProcessLimits limits;
  limits.cpu_seconds = cpu_seconds;
  return script::runLimitedChild(
      limits, {script::thisProgramArguments().at(0), "--gtest_filter=ScriptChildProcess.DISABLED_" + body,
               "--gtest_also_run_disabled_tests"});
}

TEST(ScriptChildProcess, DISABLED_AnnounceAndExit3) {
  if (!script::inLimitedChild()) GTEST_SKIP() << "runs as a child of ReportsExitStatusSignalAndAnnouncedFiles";
  script::announceCreated("/a/b.txt");
  script::announceCreated("c d");
  script::liftLimits();
  script::announceCreated("after");  // after liftLimits: nobody listens
  ::_exit(3);
}

TEST(ScriptChildProcess, DISABLED_Terminate) {
  if (!script::inLimitedChild()) GTEST_SKIP();
  std::signal(SIGTERM, SIG_DFL);
  std::raise(SIGTERM);
}

TEST(ScriptChildProcess, DISABLED_PatternMatch) {
  if (!script::inLimitedChild()) GTEST_SKIP();
  (void)script::runScriptText("local s = string.rep('a', 3000)\nreturn s:find(string.rep('.-', 12) .. 'b')", "p.lua",
                              ".");
}

TEST(ScriptChildProcess, ReportsExitStatusSignalAndAnnouncedFiles) {
  EXPECT_FALSE(script::inLimitedChild());
  script::ChildOutcome child = runBody("AnnounceAndExit3", 30);
  EXPECT_EQ(child.end, script::ChildEnd::kExited);
  EXPECT_EQ(child.code, 3);
  EXPECT_EQ(child.created, (std::vector<std::string>{"/a/b.txt", "c d"}));
  child = runBody("Terminate", 30);
  EXPECT_EQ(child.end, script::ChildEnd::kSignaled);
  EXPECT_EQ(child.code, SIGTERM);
  EXPECT_EQ(testing::errorOf([&] { (void)runBody("Terminate", 0); }),
            "the CPU-time limit must be 1 to 1000000 seconds, got 0");
}

// The backstop: Lua pattern matching runs inside one C call, where no instruction budget reaches
// it; the CPU-time limit ends it.
TEST(ScriptChildProcess, APatternMatchPastTheCpuLimitIsKilled) {
  constexpr double kCpuLimit = 1;
  constexpr double kCpuAccountingTol = 0.25;  // rusage and the kernel's limit tick count CPU time apart
  const script::ChildOutcome child = runBody("PatternMatch", static_cast<int>(kCpuLimit));
  EXPECT_EQ(child.end, script::ChildEnd::kCpuExceeded);
  EXPECT_GE(child.cpu_seconds, kCpuLimit - kCpuAccountingTol);
}

// A loop of writes cannot fill the disk: every f:write is counted against the write limit before
// it writes, and io.open creates at most kMaxCreatedFiles files.
TEST(ScriptConfinement, WritesAreCountedAgainstTheWriteLimit) {
  ScriptBench bench;
  bench.write_limit = 100;
  bench.run("local f = io.open('a.txt', 'w') f:write(string.rep('x', 60), 'y') f:write(7) f:close()");
  EXPECT_EQ(fs::file_size(bench.out + "/a.txt"), 62u);
  EXPECT_EQ(errorWith(bench, "local f = io.open('b.txt', 'w') f:write(string.rep('x', 101))"),
            "s.lua:1: write: the script's files would hold more than its write limit of 100 bytes");
  EXPECT_TRUE(fs::is_empty(bench.out + "/b.txt") || !fs::exists(bench.out + "/b.txt"));
  // The limit is for the whole run, over every handle.
  EXPECT_EQ(
      errorWith(bench, "for i = 1, 3 do local f = io.open('c' .. i, 'w') f:write(string.rep('x', 40)) f:close() end"),
      "s.lua:1: write: the script's files would hold more than its write limit of 100 bytes");
}

TEST(ScriptConfinement, IoOpenCreatesAtMostTheFileLimit) {
  ScriptBench bench;
  EXPECT_EQ(errorWith(bench, "for i = 1, " + std::to_string(script::kMaxCreatedFiles + 1) +
                                 " do io.open('f' .. i, 'w'):close() end"),
            "s.lua:1: io.open: writing 'f10001': the script has created 10000 files, the most one run may");
  // Files that exist already are opened again without counting.
  bench.run("for i = 1, 3 do io.open('f1', 'w'):close() end");
}

}  // namespace
}  // namespace vdg
