// Private to the script module: the state one script run shares with its Lua C functions, and the
// rules that keep C++ and Lua's error handling apart.
//
// WHY THE RULES. Debian's liblua5.4 is compiled as C: lua_error (and every API function that can
// fail: luaL_check*, lua_getfield, lua_pushstring when memory runs out, ...) leaves by longjmp.
// A longjmp that skips a C++ frame holding a live object with a non-trivial destructor is
// undefined behaviour, and a C++ exception that reaches a Lua (C) frame is too. So every vdg C
// function has three phases:
//   1. READ: check the arguments with the raising API (luaL_check*, luaL_error, lua_getfield,
//      ...). Locals are trivially destructible only (numbers, pointers, fixed-size Eigen values,
//      anim::Ease); nothing here can throw a C++ exception.
//   2. BUILD: inside guarded(): any C++ (containers, strings, anim/io/scene calls that throw
//      vdg::Error). It may call only the NON-RAISING Lua functions: lua_type, lua_rawlen,
//      lua_rawgeti, lua_rawget with a key already on the stack (lua_pushvalue), lua_tonumberx,
//      lua_tointegerx, lua_toboolean, lua_tolstring on a value that IS a string, lua_touserdata, lua_getmetatable,
//      lua_topointer, lua_pop / lua_settop (no to-be-closed slots), and only with stack space
//      reserved in phase 1. A C++ exception is caught there and its message kept in
//      Context::error.
//   3. ANSWER: after guarded() returned (its C++ objects are gone): raise the kept message, or
//      push the results (raising API allowed again; only trivially destructible locals live).
// Data that outlives a call lives in the Context (owned by runScriptText, a frame above the
// lua_pcall, so no longjmp crosses it).
// Re-entrancy: reading arguments uses raw access only (no metamethods run), and scripts cannot
// install __gc metamethods (setmetatable refuses them; every metatable vdg and io hand out is
// locked with __metatable), so no script code can run inside phases 1-2 of another call.
#pragma once

extern "C" {
#include <lauxlib.h>
#include <lua.h>
#include <lualib.h>
}

#include <array>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "vdg/anim/curve.h"
#include "vdg/anim/ease.h"
#include "vdg/geom/error.h"
#include "vdg/scene/scene.h"
#include "vdg/script/script.h"

namespace vdg::script::detail {

// What vdg.load returned: an index into the RawScene's meshes, models or animated_models.
struct ObjectRef {
  scene::ObjectKind kind = scene::ObjectKind::kMesh;
  int index = -1;
  std::string path;  // as the script gave it
};

struct Context {
  // Inputs.
  std::string chunk_name;  // SCRIPT in messages
  std::string script_dir;  // canonical
  std::string read_root;   // canonical; the script_dir or a folder above it (ScriptOptions::read_root)
  std::string output_dir;  // weakly canonical
  std::int64_t budget = 0;
  std::size_t memory_limit = 0;
  std::int64_t write_limit = 0;  // ScriptOptions::write_limit
  std::function<void(std::string_view)> print;
  std::function<void(const std::string&)> created;  // ScriptOptions::created

  // Accounting.
  std::int64_t executed = 0;  // instructions, in steps of hook_interval
  int hook_interval = 1;
  bool budget_exceeded = false;
  std::size_t lua_bytes = 0;
  std::size_t cxx_bytes = 0;   // the scene being built, estimated
  bool out_of_memory = false;  // an allocation or a charge was refused
  std::int64_t written = 0;    // bytes given to f:write, against write_limit
  int created_files = 0;       // files io.open created, against kMaxCreatedFiles

  // What the script builds.
  scene::RawScene scene;
  std::vector<RenderRequest> renders;
  std::vector<ObjectRef> objects;             // one per distinct vdg.load path
  std::map<std::string, int> object_by_path;  // canonical path -> objects index
  std::map<std::string, int, std::less<>> node_by_name;
  // Per node and field: 0 untouched, 1 has actions, 2 has a track.
  std::vector<std::array<std::uint8_t, scene::kFieldCount>> driven;
  int next_auto_name = 1;

  // Actors (Parent 4.8; actor_bindings.cpp): defined by vdg.actor while the script runs, stepped
  // frame by frame after it (runActors). Their Lua values (functions, state, inboxes) live in a
  // registry table; here is what C++ needs to run them and to record what they drive.
  struct Actor {
    std::string name;
    int node = -1;          // its node (self.node), or -1; it may drive more (vdg.actor's drives)
    int pending = 0;        // messages sent to it, for the next frame
    int delivering = 0;     // messages it receives in this frame
    bool receives = false;  // has a receive function
  };
  // One field an actor drives: its value now and the keys recorded so far (a step track).
  struct Channel {
    int node = -1;
    scene::Field field = scene::Field::kTranslation;
    double current[4] = {0, 0, 0, 0};
    std::vector<double> times;
    std::vector<double> values;  // times.size() x fieldDimension(field)
  };
  std::vector<Actor> actors;
  std::map<std::string, int, std::less<>> actor_by_name;
  std::vector<int> actor_of_node;  // per node: the actor that drives it, or -1 (sized by vdg.actor)
  std::vector<Channel> channels;
  std::vector<std::array<int, scene::kFieldCount>> channel_of_node;  // per node and field, or -1 (runActors)
  std::optional<int> actor_last_frame;                               // ScriptOptions::actor_last_frame
  std::optional<scene::Scene> stage;  // the scene without the actors, for reading other fields
  bool acting = false;                // the actors are running: the scene is fixed
  int current_actor = -1;             // the actor whose function runs (messages), or -1
  int first_frame = 0;                // the shot's first frame (the actors' first)
  int frame = 0;                      // the frame the actors are at

  // Metatables (registry-owned, alive as long as the state), compared by address.
  const void* mt_node = nullptr;
  const void* mt_object = nullptr;
  const void* mt_quat = nullptr;
  const void* mt_ease = nullptr;
  const void* mt_curve = nullptr;
  const void* mt_actor = nullptr;

  // The message of the last C++ exception caught by guarded(), and scratch text for phase 3.
  std::string error;
  std::string text;
};

Context& contextOf(lua_State* L);

// Runs `f` (phase 2). Returns false when it threw; the message is in ctx.error.
template <typename F>
bool guarded(Context& ctx, F&& f) {
  try {
    f();
    return true;
  } catch (const std::exception& e) {
    try {
      ctx.error = e.what();
    } catch (...) {
      ctx.error.clear();
    }
  } catch (...) {
    ctx.error.clear();
  }
  if (ctx.error.empty()) ctx.out_of_memory = true;  // only a failed copy of the message lands here
  return false;
}

// Phase 3 after a failed guarded(): raises "WHERE: FUNCTION: message" (WHERE = the calling
// script line). Never returns.
[[noreturn]] void raiseKept(lua_State* L, const char* function);

// Charges `bytes` of C++ memory (the scene) to the memory limit; raises the out-of-memory error
// when it would pass the limit. Phase 1 only.
void charge(lua_State* L, std::size_t bytes);

// ---- non-raising readers (phases 1 and 2) ----
// Each returns nullptr on success, else a short static reason. `idx` must be absolute.

const char* readNumber(lua_State* L, int idx, double* out);         // a finite number
const char* readVector(lua_State* L, int idx, int n, double* out);  // a table of n finite numbers
const char* readQuaternion(lua_State* L, int idx, double out[4]);   // quat userdata or {w,x,y,z}, non-zero
const char* readColor(lua_State* L, int idx, double out[3]);        // 3 numbers in [0, 1]
const char* readScale(lua_State* L, int idx, double out[3]);        // number or 3 numbers, non-zero
// The value of `field` (scene::fieldDimension numbers; rotations as w, x, y, z; visible also
// true/false).
const char* readFieldValue(lua_State* L, int idx, scene::Field field, double out[4]);
// A CHANGE's delta of `field`: the same shapes, any finite numbers (a rotation: non-zero).
const char* readFieldDelta(lua_State* L, int idx, scene::Field field, double out[4]);
// An ease: an ease userdata, or the name "linear" or "sine".
const char* readEase(lua_State* L, int idx, anim::Ease* out);

template <typename T>
T* toUserdata(lua_State* L, int idx, const void* metatable) {
  if (lua_type(L, idx) != LUA_TUSERDATA || !lua_getmetatable(L, idx)) return nullptr;
  const bool same = lua_topointer(L, -1) == metatable;
  lua_pop(L, 1);
  return same ? static_cast<T*>(lua_touserdata(L, idx)) : nullptr;
}

// Userdata payloads (trivially destructible, except through the boxed pointer of curves).
struct NodeHandle {
  int node = -1;
};
struct ObjectHandle {
  int object = -1;
};
struct QuatValue {
  double w = 1, x = 0, y = 0, z = 0;
};
static_assert(std::is_trivially_destructible_v<anim::Ease>);
static_assert(std::is_trivially_destructible_v<QuatValue>);

// Node handle at `idx` (phase 1; raises a type error naming argument `arg` of `function`).
int checkNode(lua_State* L, int idx, const char* function, const char* what);
// Pushes a new node handle / quaternion.
void pushNode(lua_State* L, int node);
void pushQuat(lua_State* L, const double wxyz[4]);
// Pushes a table {v[0], ..., v[n-1]}.
void pushNumbers(lua_State* L, const double* v, int n);

// Checks that every key of the table at `idx` is one of `allowed` (null-terminated), or with
// `array`, an index 1..#t; raises "FUNCTION: unknown field 'KEY' (expected a, b, c)".
void checkKeys(lua_State* L, int idx, const char* function, const char* const* allowed, bool array = false);
// The curve kind named `name` ("linear", "catmull-rom", ...: anim::curveKindName); false for any
// other name.
bool curveKindFromName(const char* name, anim::CurveKind* out);
// A metatable registered as `name` with the given metamethods, locked (`__metatable`, so scripts
// can neither read nor replace it); returns its address (Context::mt_*). Phase 1.
const void* lockedMetatable(lua_State* L, const char* name, const luaL_Reg* methods);
// Pushes t[key] (raw) of the table at idx and returns its absolute index (phase 1).
int field(lua_State* L, int idx, const char* key);

// Registration of the libraries (sandbox.cpp, math_bindings.cpp, scene_bindings.cpp). Each expects
// the `vdg` table on top of the stack where it says so.
void openSandbox(lua_State* L);          // globals: base, string, table, math, utf8, io, os (checked)
void openMath(lua_State* L, int vdg);    // vdg.ease, vdg.quat, vdg.curve
void openScene(lua_State* L, int vdg);   // vdg.load, node, group, camera, set, change, track, ...
void openActors(lua_State* L, int vdg);  // vdg.actor, vdg.get
// Runs the actors the script defined, frame by frame from the shot's first frame, and adds the
// fields they drove to the scene as step tracks (actor_bindings.cpp). Called after the chunk, in
// the same protected call (budget and memory limit hold).
void runActors(lua_State* L);
// Raises "FUNCTION: the scene is fixed once the actors run (...)" while they run (phase 1): the
// functions that describe the scene call it first.
void refuseWhileActing(lua_State* L, const char* function);

// A path for `rel` under `base` (canonical folder) that stays there: refuses an empty path, a NUL,
// an absolute path, a backslash, and a path whose existing part leads outside `base` through
// symbolic links (or ends in a dangling one). Without `from`, `rel` is relative to `base` and has no
// ".." component (writes); with `from` (a folder below `base`: the script's, for reads under the
// read root) it is relative to `from` and may climb with ".." as long as it stays below `base`.
// Throws vdg::Error "WHAT 'PATH': why" (phase 2).
std::string confinedPath(const std::string& base, std::string_view rel, const char* what, const std::string& from = {});

}  // namespace vdg::script::detail
