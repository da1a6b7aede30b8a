// The animation language: Lua 5.4 scripts that build a scene (Parent, Computer Animation, sections
// 4.6 and 4.8: an animation language with the host language's variables, expressions, functions
// and loops, and the text's SET / CHANGE / FOR EACH semantics on top). The language itself, every
// function with an example, the sandbox and its limits are documented in docs/language.md.
//
//   script text --runScript--> Shot { scene::RawScene, render requests }
//
// Actors (Parent 4.8, vdg.actor): objects with their own state and per-frame functions that send
// each other messages. The script only defines them; after it has run they are stepped, frame by
// frame from the shot's first frame (see ScriptOptions::actor_last_frame), in the order defined,
// and what they set becomes step tracks of the scene (one key per integer frame where the value
// changed). So a Shot is still plain data, and any frame range renders what a full run renders.
// math.random is seeded the same way in every run, pairs visits keys in a fixed order (numbers,
// strings, booleans sorted; Lua's own order changes from run to run), and os.clock, os.time and
// os.date are refused while the actors run (their frames must not depend on when or where they run).
//
// The script runs in a sandbox (docs/language.md, "Sandbox"):
//  - libraries: the base library without dofile, loadfile, require; `load` of text chunks only;
//    collectgarbage("count") only; setmetatable refuses __gc metamethods; string (without
//    string.dump), table, math, utf8; os.clock, os.time and os.date only; no package, debug,
//    coroutine or native modules;
//  - files: io.open / io.lines and vdg.load READ below ScriptOptions::read_root (default: the
//    script's folder; paths relative to the script's folder), and io.open WRITES below
//    ScriptOptions::output_dir (paths relative to it, no ".."); absolute paths, backslashes and
//    paths or symbolic links that lead outside are refused. While the script runs a
//    vdg::ScopedReadRoot holds the read root, so every file a load reaches (glTF buffers and
//    images, material libraries, textures, a manifest's meshes) obeys it too. io.open and io.lines
//    check the file they opened: regular files only (a FIFO or a device is refused), below the
//    folder as opened, never written through a symbolic link or a second hard link;
//  - an instruction budget (a count hook; pcall cannot catch its error for long: once spent,
//    every further instruction raises it again; xpcall runs its message handler after the call,
//    where the hook reaches it) and a memory limit (a counting allocator; the scene the script
//    builds is charged to the same limit).
// Lua pattern matching (string.find / match / gmatch / gsub) runs inside one C call that the
// instruction budget cannot interrupt: the backstop for it (and for any other CPU the budget does
// not see) is the CPU-time limit of the child process vdg run runs scripts in (child_process.h).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "vdg/scene/scene.h"

namespace vdg::script {

// One vdg.render{...} call of the script (what to render; the script module renders nothing).
struct RenderRequest {
  int first_frame = 1, last_frame = 1;  // inclusive, 0 <= first <= last
  int width = 640, height = 360;        // pixels, 1..kMaxImageSide
  // Folder relative to the output dir (a checked relative path: no "..", not absolute); frames are
  // written as out/frame_NNNN.png (4 digits, more if needed) by the renderer.
  std::string out = ".";
  int samples = 8;  // 1..kMaxSamples
  std::array<float, 3> background{0.97f, 0.97f, 0.95f};
  float silhouette_width = 0;  // pixels; 0: automatic
  float crease_angle_deg = 0;  // [0, 180]; 0: the renderer's default
  int line = 0;                // script line of the render{} call (messages)
};

inline constexpr int kMaxImageSide = 16384;
inline constexpr int kMaxSamples = 64;
inline constexpr int kMaxRenderFrames = 1000000;  // last - first + 1

struct Shot {
  scene::RawScene scene;  // validated (RawScene::validate) when it has nodes; empty otherwise
  std::vector<RenderRequest> renders;
  std::string script_path;  // as given (the name messages use)
};

struct ScriptOptions {
  std::string output_dir = ".";                   // where render{} outputs go and where io.open may write
  std::int64_t instruction_budget = 200'000'000;  // Lua VM instructions (lua_sethook count), >= 1
  std::size_t memory_limit = 512u << 20;          // bytes (Lua allocations + the scene built), >= kMinMemoryLimit
  std::function<void(std::string_view)> print;    // receives each print() line (no newline); null: stdout
  // Bytes the script's file handles may write in all (f:write), >= 0: a loop of writes cannot fill
  // the disk. io.open creates at most kMaxCreatedFiles files.
  std::int64_t write_limit = std::int64_t{1} << 30;
  // Called with the absolute path of each file io.open has just created (vdg run
  // removes them when the run fails); null: nobody is told.
  std::function<void(const std::string&)> created;
  // The folder below which the script may read (io.open / io.lines reads, vdg.load), relative paths
  // being relative to the script's folder and free to climb with ".." while they stay below it;
  // empty: the script's own folder. It must hold the script.
  std::string read_root;
  // Actors (vdg.actor, Parent 4.8) run from the shot's first frame (the smallest first frame of the
  // script's render requests) to its last (the largest last frame), whatever range is rendered
  // afterwards. A value here stops them after this frame instead: a caller that renders only
  // frames up to B (vdg run --frames A-B) can pass B, and every frame <= B is still exactly what a
  // full run gives (a frame depends only on the frames before it); later frames hold frame B's
  // values. std::nullopt: the whole shot.
  std::optional<int> actor_last_frame;
};

inline constexpr std::size_t kMinMemoryLimit = std::size_t{1} << 20;
inline constexpr int kMaxCreatedFiles = 10000;  // files io.open may create in one run

// Runs the script at `path` (read with io's bounded reader, kMaxJsonFileBytes) and returns what it
// built. Its folder is the script folder (vdg.load, io.open reads). Throws vdg::Error:
//   "SCRIPT:LINE: message"   syntax and run-time errors, bad arguments to vdg functions (naming
//                            the function: "SCRIPT:12: vdg.set: ..."), sandbox refusals;
//   "SCRIPT: exceeded its instruction budget (N instructions; endless loop?)";
//   "SCRIPT: out of memory (limit N MiB)";
//   "SCRIPT: the script raised an error value that is not a string (a table)";
//   errors raised while an actor's function runs (any of the above) end with
//                            " (actor 'NAME', frame F)";
//   "SCRIPT: node 'x': ..." (and the rest of RawScene::validate) for a scene that does not validate;
//   "SCRIPT: ..." for a file that cannot be read, and for options out of range.
// SCRIPT is `path` as given.
Shot runScript(const std::string& path, const ScriptOptions& options = {});

// The same for script text: `chunk_name` names it in messages (SCRIPT above), `script_dir` is its
// folder (must exist).
Shot runScriptText(std::string_view text, const std::string& chunk_name, const std::string& script_dir,
                   const ScriptOptions& options = {});

}  // namespace vdg::script
