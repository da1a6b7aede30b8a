// Hostile scripts: each ends with one clear vdg::Error naming the script (and line), and nothing
// appears outside the output folder.
#include <gtest/gtest.h>

#include <filesystem>

#include "script/script_fixtures.h"

namespace vdg {
namespace {

using testing::ScriptBench;
namespace fs = std::filesystem;

// Runs `text` as hostile.lua and returns its error, checking that nothing outside out/ changed.
std::string hostile(ScriptBench& bench, const std::string& text, script::ScriptOptions options) {
  const auto before = bench.outsideOutput();
  const std::string error =
      testing::errorOf([&] { script::runScriptText(text, "hostile.lua", bench.scripts, options); });
  EXPECT_EQ(bench.outsideOutput(), before) << "the script changed files outside the output folder";
  return error;
}
std::string hostile(ScriptBench& bench, const std::string& text) { return hostile(bench, text, bench.options()); }

TEST(ScriptSandbox, EndlessLoopEndsWithTheBudgetMessage) {
  ScriptBench bench;
  auto options = bench.options();
  options.instruction_budget = 100000;
  EXPECT_EQ(hostile(bench, "while true do end", options),
            "hostile.lua: exceeded its instruction budget (100000 instructions; endless loop?)");
}

TEST(ScriptSandbox, PcallCannotHoldBackTheBudget) {
  ScriptBench bench;
  auto options = bench.options();
  options.instruction_budget = 100000;
  EXPECT_EQ(hostile(bench,
                    "while true do pcall(function() while true do end end) end\n"
                    "local function f() return f() end",
                    options),
            "hostile.lua: exceeded its instruction budget (100000 instructions; endless loop?)");
  EXPECT_EQ(hostile(bench,
                    "local ok = false\nrepeat ok = xpcall(function() while true do end end, function(e) return e end) "
                    "until false",
                    options),
            "hostile.lua: exceeded its instruction budget (100000 instructions; endless loop?)");
}

TEST(ScriptSandbox, HugeAllocationsEndWithTheMemoryMessage) {
  ScriptBench bench;
  auto options = bench.options();
  options.memory_limit = std::size_t{16} << 20;
  EXPECT_EQ(hostile(bench, "local s = string.rep('x', 1 << 30)", options), "hostile.lua: out of memory (limit 16 MiB)");
  EXPECT_EQ(hostile(bench, "local s = ('x'):rep(1 << 20) .. ('y'):rep(1 << 24)", options),
            "hostile.lua: out of memory (limit 16 MiB)");
  EXPECT_EQ(hostile(bench, "local t = {}\nfor i = 1, 1e9 do t[i] = i end", options),
            "hostile.lua: out of memory (limit 16 MiB)");
  // Caught by the script's pcall and raised again as a string: still the memory message.
  EXPECT_EQ(hostile(bench, "local ok, e = pcall(string.rep, 'x', 1 << 30)\nassert(not ok)\nerror(e, 0)", options),
            "hostile.lua: out of memory (limit 16 MiB)");
  // The scene the script builds counts too.
  EXPECT_EQ(
      hostile(bench, "local n = vdg.group{}\nfor i = 1, 1e7 do vdg.set(n, 'translation', {i, 0, 0}, i) end", options),
      "hostile.lua: out of memory (limit 16 MiB)");
}

TEST(ScriptSandbox, NoOsExecuteAndNoProcesses) {
  ScriptBench bench;
  EXPECT_EQ(hostile(bench, "os.execute('touch " + bench.dir.file("pwned") + "')"),
            "hostile.lua:1: attempt to call a nil value (field 'execute')");
  EXPECT_EQ(hostile(bench, "\nio.popen('ls')"), "hostile.lua:2: attempt to call a nil value (field 'popen')");
  EXPECT_EQ(hostile(bench, "os.remove('x')"), "hostile.lua:1: attempt to call a nil value (field 'remove')");
  EXPECT_EQ(hostile(bench, "os.exit(3)"), "hostile.lua:1: attempt to call a nil value (field 'exit')");
  EXPECT_FALSE(fs::exists(bench.dir.file("pwned")));
  bench.run(
      "assert(os.getenv == nil and os.tmpname == nil and os.rename == nil and io.tmpfile == nil)\n"
      "assert(io.write == nil and io.read == nil and io.input == nil and io.output == nil)\n"
      "assert(type(os.clock()) == 'number' and type(os.time()) == 'number' and type(os.date()) == 'string')");
}

TEST(ScriptSandbox, AReadRootAboveTheScriptFolderWidensWhatItMayRead) {
  ScriptBench bench;
  fs::create_directories(bench.dir.file("shared"));
  testing::writeText(bench.dir.file("shared/tri.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  const std::string load = "vdg.node{object = vdg.load('../shared/tri.obj')}";
  EXPECT_NE(bench.errorOfRun(load).find("leads outside the folder the script may read"), std::string::npos);
  bench.read_root = bench.dir.path().string();
  EXPECT_EQ(bench.run(load).scene.meshes.size(), 1u);
  // Still nothing above the root, and writes still only below the output folder.
  EXPECT_NE(bench.errorOfRun("local f = io.open('../../x.txt')").find("leads outside the folder the script may read"),
            std::string::npos);
  EXPECT_NE(bench.errorOfRun("local f = io.open('../shared/x.txt', 'w')").find("'..' components are refused"),
            std::string::npos);
  // A root that does not hold the script is refused.
  bench.read_root = bench.dir.file("shared");
  EXPECT_NE(bench.errorOfRun("local x = 1").find("is not inside its read root"), std::string::npos);
}

TEST(ScriptSandbox, ReadingOutsideTheScriptFolderIsRefused) {
  ScriptBench bench;
  EXPECT_EQ(
      hostile(bench, "local f = io.open('/etc/passwd')"),
      "hostile.lua:1: io.open: reading '/etc/passwd': absolute paths are refused (give a path relative to the folder)");
  EXPECT_EQ(hostile(bench, "for l in io.lines('../../../../etc/passwd') do end"),
            "hostile.lua:1: io.lines: reading '../../../../etc/passwd': the path leads outside the folder the script "
            "may read (" +
                fs::canonical(bench.scripts).string() + "; see vdg run --root)");
  EXPECT_EQ(
      hostile(bench, "vdg.load('/etc/passwd')"),
      "hostile.lua:1: vdg.load: model '/etc/passwd': absolute paths are refused (give a path relative to the folder)");
  // Through a symbolic link in the script folder.
  fs::create_symlink("/etc", bench.scripts + "/etc");
  EXPECT_EQ(
      hostile(bench, "local f = io.open('etc/passwd')"),
      "hostile.lua:1: io.open: reading 'etc/passwd': the path leads outside its folder (through a symbolic link)");
  // A file of the script's folder reads.
  testing::writeText(bench.scripts + "/data.txt", "42\n");
  bench.run(
      "local f = assert(io.open('data.txt'))\nassert(f:read('n') == 42)\nf:close()\n"
      "for l in io.lines('data.txt') do assert(l == '42') end");
}

TEST(ScriptSandbox, WritingOutsideTheOutputFolderIsRefused) {
  ScriptBench bench;
  fs::create_directories(bench.dir.file("outside"));
  EXPECT_EQ(hostile(bench, "io.open('" + bench.dir.file("outside/x.txt") + "', 'w')"),
            "hostile.lua:1: io.open: writing '" + bench.dir.file("outside/x.txt") +
                "': absolute paths are refused (give a path relative to the folder)");
  EXPECT_EQ(
      hostile(bench, "io.open('../outside/x.txt', 'w')"),
      "hostile.lua:1: io.open: writing '../outside/x.txt': '..' components are refused (the path must stay in its "
      "folder)");
  EXPECT_EQ(hostile(bench, "io.open('a/../../x.txt', 'a+')"),
            "hostile.lua:1: io.open: writing 'a/../../x.txt': '..' components are refused (the path must stay in its "
            "folder)");
  // Symbolic links in the output folder that lead out of it: to a folder, and dangling.
  fs::create_symlink(bench.dir.file("outside"), bench.out + "/link");
  EXPECT_EQ(
      hostile(bench, "io.open('link/x.txt', 'w')"),
      "hostile.lua:1: io.open: writing 'link/x.txt': the path leads outside its folder (through a symbolic link)");
  fs::create_symlink(bench.dir.file("outside/new.txt"), bench.out + "/dangling");
  EXPECT_EQ(hostile(bench, "io.open('dangling', 'w')"),
            "hostile.lua:1: io.open: writing 'dangling': a symbolic link that points nowhere is refused");
  EXPECT_EQ(hostile(bench, "io.open('x.txt', 'rw')"),
            "hostile.lua:1: io.open: invalid mode 'rw' (expected r, w, a, r+, w+, a+, each with an optional b)");
  EXPECT_TRUE(fs::is_empty(bench.dir.file("outside")));
  // Inside the output folder, writing works (relative to it, not to the script's folder).
  bench.run("local f = assert(io.open('ok.txt', 'w'))\nf:write('fine')\nf:close()");
  EXPECT_EQ(testing::readText(bench.out + "/ok.txt"), "fine");
  EXPECT_FALSE(fs::exists(bench.scripts + "/ok.txt"));
  // vdg.render's folder must stay inside too.
  EXPECT_EQ(
      hostile(bench, "vdg.render{out = '../frames'}"),
      "hostile.lua:1: vdg.render: out '../frames': '..' components are refused (the path must stay in its folder)");
  EXPECT_EQ(hostile(bench, "vdg.render{out = 'link'}"),
            "hostile.lua:1: vdg.render: out 'link': the path leads outside its folder (through a symbolic link)");
}

// An output folder named with a trailing slash that does not exist yet ("shots/") is the folder
// itself: render folders inside it are accepted, not taken for a way out through a link.
TEST(ScriptSandbox, AnOutputFolderWithATrailingSlashThatDoesNotExistYetHoldsItsRenders) {
  ScriptBench bench;
  script::ScriptOptions options = bench.options();
  options.output_dir = bench.dir.file("shots") + "/";
  EXPECT_NO_THROW(script::runScriptText("vdg.render{out = 'frames'}", "ok.lua", bench.scripts, options));
  options.output_dir = bench.dir.file("shots/deeper") + "/";
  EXPECT_NO_THROW(script::runScriptText("vdg.render{out = 'frames'}", "ok.lua", bench.scripts, options));
}

TEST(ScriptSandbox, NoModulesNoDebugNoBinaryChunks) {
  ScriptBench bench;
  bench.run(
      "assert(require == nil and package == nil and debug == nil and loadfile == nil and dofile == nil)\n"
      "assert(string.dump == nil and coroutine == nil)\n"
      "local f, e = load('\\27Lua\\84\\0\\25\\147', 'bin', 'b')\n"
      "assert(f == nil and e:find('binary chunk'), e)\n"
      "assert(load('return 1 + 1')() == 2)\n"
      "assert(collectgarbage('count') > 0)");
  EXPECT_EQ(hostile(bench, "require('os')"), "hostile.lua:1: attempt to call a nil value (global 'require')");
  EXPECT_EQ(hostile(bench, "collectgarbage('stop')"),
            "hostile.lua:1: collectgarbage: only collectgarbage(\"count\") is available in vdg scripts, not 'stop'");
  EXPECT_EQ(hostile(bench, "setmetatable({}, {__gc = function() end})"),
            "hostile.lua:1: setmetatable: __gc metamethods (finalizers) are not available in vdg scripts");
  EXPECT_EQ(hostile(bench, "getmetatable(io.open('x', 'w')).__gc = print"),
            "hostile.lua:1: attempt to index a string value");
  // A binary chunk as the script itself.
  EXPECT_EQ(hostile(bench, std::string("\x1bLua\x54\x00", 6)),
            "hostile.lua: attempt to load a binary chunk (mode is 't')");
}

TEST(ScriptSandbox, ErrorValuesThatAreNotStrings) {
  ScriptBench bench;
  EXPECT_EQ(hostile(bench, "error({})"),
            "hostile.lua: the script raised an error value that is not a string (a table)");
  EXPECT_EQ(hostile(bench, "error(setmetatable({}, {__tostring = function() while true do end end}))"),
            "hostile.lua: the script raised an error value that is not a string (a table)");
  EXPECT_EQ(hostile(bench, "error()"), "hostile.lua: the script raised an error value that is not a string (a nil)");
  EXPECT_EQ(hostile(bench, "error(42)"), "hostile.lua: 42");
  EXPECT_EQ(hostile(bench, "error(vdg.quat.identity())"),
            "hostile.lua: the script raised an error value that is not a string (a userdata)");
}

TEST(ScriptSandbox, MessagesNameTheScriptAndLine) {
  ScriptBench bench;
  EXPECT_EQ(hostile(bench, "local x = 1\nx = x +"), "hostile.lua:2: unexpected symbol near <eof>");
  EXPECT_EQ(hostile(bench, "\n\nerror('boom')"), "hostile.lua:3: boom");
  EXPECT_EQ(hostile(bench, "\nlocal t = nil\nprint(t.x)"), "hostile.lua:3: attempt to index a nil value (local 't')");
  // A long name is given back whole (Lua itself keeps only LUA_IDSIZE - 1 bytes of it).
  const std::string long_name = std::string(100, 'd') + "/shot.lua";
  EXPECT_EQ(bench.errorOfRun("\nerror('boom')", long_name), long_name + ":2: boom");
  EXPECT_EQ(bench.errorOfRun("while true do end", long_name).rfind(long_name + ": exceeded", 0), 0u);
}

TEST(ScriptSandbox, OptionsOutOfRange) {
  ScriptBench bench;
  auto options = bench.options();
  options.instruction_budget = 0;
  EXPECT_EQ(testing::errorOf([&] { script::runScriptText("", "s.lua", bench.scripts, options); }),
            "s.lua: instruction budget must be at least 1, got 0");
  options = bench.options();
  options.memory_limit = 1000;
  EXPECT_EQ(testing::errorOf([&] { script::runScriptText("", "s.lua", bench.scripts, options); }),
            "s.lua: memory limit must be at least 1 MiB, got 1000 bytes");
  EXPECT_EQ(testing::errorOf([&] {
              script::runScript(bench.scripts + "/missing.lua");
            }).rfind(bench.scripts + "/missing.lua: ", 0),
            0u);
}

}  // namespace
}  // namespace vdg
