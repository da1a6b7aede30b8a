// Running a script: the Lua state with a counting allocator (the memory limit) and a count hook
// (the instruction budget), one protected call that opens the sandbox and the vdg module and runs
// the chunk, and the translation of its outcome into a Shot or one vdg::Error.
#include "vdg/script/script.h"

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>

#include "context.h"
#include "vdg/io/read_file.h"

namespace vdg::script {
namespace {

using detail::Context;

// lua_Alloc: counts every block and refuses growth beyond the limit (Lua then raises its memory
// error, LUA_ERRMEM). Shrinking never fails, as Lua requires.
void* allocate(void* ud, void* ptr, std::size_t osize, std::size_t nsize) {
  auto* ctx = static_cast<Context*>(ud);
  const std::size_t old = ptr ? osize : 0;
  if (nsize == 0) {
    std::free(ptr);
    ctx->lua_bytes -= old;
    return nullptr;
  }
  if (nsize > old) {
    const std::size_t used = ctx->lua_bytes + ctx->cxx_bytes;
    if (nsize - old > ctx->memory_limit || used > ctx->memory_limit - (nsize - old)) {
      ctx->out_of_memory = true;
      return nullptr;
    }
  }
  void* grown = std::realloc(ptr, nsize);
  if (!grown) {
    if (nsize <= old) return ptr;  // keep the larger block
    ctx->out_of_memory = true;
    return nullptr;
  }
  ctx->lua_bytes = ctx->lua_bytes - old + nsize;
  return grown;
}

// Count hook: every hook_interval instructions. Once the budget is spent it raises on every
// instruction (sticky), so a script's pcall cannot hold the error back for long. Lua runs a message
// handler with hooks off, so the sandbox's xpcall runs its handler after the call instead (see
// sandbox.cpp): no script code runs where this hook cannot reach it.
void countHook(lua_State* L, lua_Debug*) {
  Context& ctx = detail::contextOf(L);
  ctx.executed += ctx.hook_interval;
  if (ctx.executed >= ctx.budget || ctx.budget_exceeded) {
    if (!ctx.budget_exceeded) {
      ctx.budget_exceeded = true;
      lua_sethook(L, countHook, LUA_MASKCOUNT, 1);
    }
    lua_pushliteral(L, "instruction budget exceeded");
    lua_error(L);
  }
}

struct Chunk {
  const char* text;
  std::size_t size;
  const char* name;  // "=" + chunk name
};

// The protected body: libraries, the vdg module, the script.
int protectedMain(lua_State* L) {
  const auto* chunk = static_cast<const Chunk*>(lua_touserdata(L, 1));
  lua_settop(L, 0);
  detail::openSandbox(L);
  lua_newtable(L);
  const int vdg = lua_gettop(L);
  detail::openMath(L, vdg);
  detail::openScene(L, vdg);
  detail::openActors(L, vdg);
  // Registered as a loaded module too, so that messages name functions "vdg.set" and so on.
  luaL_getsubtable(L, LUA_REGISTRYINDEX, LUA_LOADED_TABLE);
  lua_pushvalue(L, vdg);
  lua_setfield(L, -2, "vdg");
  lua_pop(L, 1);
  lua_setglobal(L, "vdg");
  if (luaL_loadbufferx(L, chunk->text, chunk->size, chunk->name, "t") != LUA_OK) return lua_error(L);
  lua_call(L, 0, 0);
  detail::runActors(L);  // the actors, frame by frame, after the script has described the shot
  return 0;
}

std::string mib(std::size_t bytes) {
  char text[64];
  std::snprintf(text, sizeof text, "%.6g", static_cast<double>(bytes) / (1024.0 * 1024.0));
  return text;
}

// The message of a failed run (the error object on top of the stack), without raising: only
// lua_type, lua_tolstring on strings and lua_tonumberx.
std::string failureMessage(lua_State* L, int status, const Context& ctx) {
  const std::string& name = ctx.chunk_name;
  if (ctx.budget_exceeded)
    return name + ": exceeded its instruction budget (" + std::to_string(ctx.budget) + " instructions; endless loop?)";
  std::string message;
  const int type = lua_type(L, -1);
  if (type == LUA_TSTRING) {
    std::size_t size = 0;
    const char* text = lua_tolstring(L, -1, &size);
    message.assign(text, size);
  } else if (type == LUA_TNUMBER) {
    int is_integer = 0;
    const lua_Integer i = lua_tointegerx(L, -1, &is_integer);
    if (is_integer) {
      message = std::to_string(i);
    } else {
      char text[64];
      std::snprintf(text, sizeof text, "%.14g", lua_tonumberx(L, -1, nullptr));
      message = text;
    }
  } else {
    return name + ": the script raised an error value that is not a string (a " + lua_typename(L, type) + ")";
  }
  const bool memory_message =
      message == "not enough memory" || (message.size() > 19 && message.ends_with(": not enough memory"));
  if (status == LUA_ERRMEM || (ctx.out_of_memory && memory_message))
    return name + ": out of memory (limit " + mib(ctx.memory_limit) + " MiB)";
  // Lua names the chunk by at most LUA_IDSIZE - 1 bytes of its name: give the whole name back.
  const std::string shown = name.substr(0, LUA_IDSIZE - 1) + ":";
  if (message.compare(0, shown.size(), shown) == 0) return name + ":" + message.substr(shown.size());
  return name + ": " + message;
}

// The message of a failed run, naming the actor whose function was running, if any.
std::string failure(lua_State* L, int status, const Context& ctx) {
  std::string message = failureMessage(L, status, ctx);
  if (ctx.current_actor >= 0 && static_cast<std::size_t>(ctx.current_actor) < ctx.actors.size())
    message += " (actor '" + ctx.actors[static_cast<std::size_t>(ctx.current_actor)].name + "', frame " +
               std::to_string(ctx.frame) + ")";
  return message;
}

struct StateCloser {
  lua_State* L;
  ~StateCloser() { lua_close(L); }
};

}  // namespace

Shot runScriptText(std::string_view text, const std::string& chunk_name, const std::string& script_dir,
                   const ScriptOptions& options) {
  namespace fs = std::filesystem;
  if (options.instruction_budget < 1)
    throw Error(chunk_name + ": instruction budget must be at least 1, got " +
                std::to_string(options.instruction_budget));
  if (options.write_limit < 0)
    throw Error(chunk_name + ": the write limit must be >= 0 bytes, got " + std::to_string(options.write_limit));
  if (options.memory_limit < kMinMemoryLimit)
    throw Error(chunk_name + ": memory limit must be at least " + mib(kMinMemoryLimit) + " MiB, got " +
                std::to_string(options.memory_limit) + " bytes");
  Context ctx;
  ctx.chunk_name = chunk_name;
  std::error_code ec;
  ctx.script_dir = fs::canonical(script_dir.empty() ? "." : script_dir, ec).string();
  if (ec) throw Error(chunk_name + ": script folder '" + script_dir + "': " + ec.message());
  ctx.read_root = ctx.script_dir;
  if (!options.read_root.empty()) {
    ctx.read_root = fs::canonical(options.read_root, ec).string();
    if (ec) throw Error(chunk_name + ": read root '" + options.read_root + "': " + ec.message());
    if (ctx.script_dir != ctx.read_root &&
        ctx.script_dir.compare(0, ctx.read_root.size() + 1, ctx.read_root + "/") != 0)
      throw Error(chunk_name + ": the script is not inside its read root '" + options.read_root + "'");
  }
  // Absolute first: weakly_canonical keeps a relative path relative while none of it exists, and
  // the checks compare it with the absolute paths of the folder once it does.
  const fs::path output = fs::absolute(options.output_dir.empty() ? "." : options.output_dir, ec);
  if (!ec) {
    // "shots/" that does not exist yet stays "/abs/shots/" through weakly_canonical (an existing one
    // loses the slash); the sandbox compares paths with "folder/" prefixes, so the slash must go.
    fs::path folder = fs::weakly_canonical(output, ec);
    if (!folder.has_filename() && folder.has_relative_path()) folder = folder.parent_path();
    ctx.output_dir = folder.string();
  }
  if (ec) throw Error(chunk_name + ": output folder '" + options.output_dir + "': " + ec.message());
  ctx.budget = options.instruction_budget;
  ctx.hook_interval = static_cast<int>(std::min<std::int64_t>(options.instruction_budget, 1000));
  ctx.memory_limit = options.memory_limit;
  ctx.write_limit = options.write_limit;
  ctx.print = options.print;
  ctx.created = options.created;
  ctx.actor_last_frame = options.actor_last_frame;

  lua_State* L = lua_newstate(allocate, &ctx);
  if (!L) throw Error(chunk_name + ": out of memory (limit " + mib(ctx.memory_limit) + " MiB)");
  const StateCloser closer{L};
  *static_cast<Context**>(lua_getextraspace(L)) = &ctx;
  lua_sethook(L, countHook, LUA_MASKCOUNT, ctx.hook_interval);

  const std::string lua_name = "=" + chunk_name;
  Chunk chunk{text.data(), text.size(), lua_name.c_str()};
  // Every file the script's loads reach (buffers, images, material libraries, a manifest's meshes)
  // obeys the read root, not only the path given to vdg.load.
  const ScopedReadRoot confinement(ctx.read_root);
  lua_pushcfunction(L, protectedMain);
  lua_pushlightuserdata(L, &chunk);
  const int status = lua_pcall(L, 1, 0, 0);
  if (status != LUA_OK) throw Error(failure(L, status, ctx));

  Shot shot;
  shot.script_path = chunk_name;
  shot.renders = std::move(ctx.renders);
  if (!ctx.scene.nodes.empty()) ctx.scene.validate(chunk_name);
  shot.scene = std::move(ctx.scene);
  return shot;
}

Shot runScript(const std::string& path, const ScriptOptions& options) {
  const std::string text = readFileLimited(path, "script", kMaxJsonFileBytes);
  const std::string folder = std::filesystem::path(path).parent_path().string();
  return runScriptText(text, path, folder.empty() ? "." : folder, options);
}

}  // namespace vdg::script
