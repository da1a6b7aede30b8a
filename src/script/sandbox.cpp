// The sandbox: which standard libraries a script sees, and the checked replacements of print,
// load, collectgarbage, setmetatable, io.open and io.lines (see script.h and docs/language.md).
#include <cstdio>
#include <cstring>

#include "context.h"

namespace vdg::script::detail {
namespace {

// print(...): tostring of each argument, tab-separated, to ScriptOptions::print or stdout.
int luaPrint(lua_State* L) {
  const int n = lua_gettop(L);
  luaL_Buffer b;
  luaL_buffinit(L, &b);
  for (int i = 1; i <= n; ++i) {
    if (i > 1) luaL_addchar(&b, '\t');
    luaL_tolstring(L, i, nullptr);
    luaL_addvalue(&b);
  }
  luaL_pushresult(&b);
  std::size_t size = 0;
  const char* line = lua_tolstring(L, -1, &size);
  Context& ctx = contextOf(L);
  if (!guarded(ctx, [&] {
        if (ctx.print) {
          ctx.print(std::string_view(line, size));
        } else {
          std::fwrite(line, 1, size, stdout);
          std::fputc('\n', stdout);
        }
      }))
    raiseKept(L, "print");
  return 0;
}

// load(chunk [, chunkname [, mode [, env]]]): text chunks only, whatever mode says.
int luaLoadText(lua_State* L) {
  lua_settop(L, 4);
  lua_pushliteral(L, "t");
  lua_replace(L, 3);
  lua_pushvalue(L, lua_upvalueindex(1));
  lua_insert(L, 1);
  lua_call(L, 4, LUA_MULTRET);
  return lua_gettop(L);
}

// collectgarbage("count") only: a script may watch its memory, not steer the collector.
int luaCollectGarbage(lua_State* L) {
  const char* option = luaL_optstring(L, 1, "count");
  if (std::strcmp(option, "count") != 0)
    return luaL_error(L, "collectgarbage: only collectgarbage(\"count\") is available in vdg scripts, not '%s'",
                      option);
  lua_pushnumber(L, static_cast<double>(lua_gc(L, LUA_GCCOUNT, 0)) + lua_gc(L, LUA_GCCOUNTB, 0) / 1024.0);
  return 1;
}

// setmetatable(t, mt) without __gc: finalizers would run script code inside any allocation.
int luaSetMetatable(lua_State* L) {
  if (lua_type(L, 2) == LUA_TTABLE) {
    lua_pushliteral(L, "__gc");
    if (lua_rawget(L, 2) != LUA_TNIL)
      return luaL_error(L, "setmetatable: __gc metamethods (finalizers) are not available in vdg scripts");
    lua_pop(L, 1);
  }
  lua_settop(L, 2);
  lua_pushvalue(L, lua_upvalueindex(1));
  lua_insert(L, 1);
  lua_call(L, 2, 1);
  return 1;
}

bool isWriteMode(const char* mode) { return std::strpbrk(mode, "wa+") != nullptr; }

// io.open(path [, mode]): reads relative to the script's folder, writes relative to the output
// folder, both confined there. Upvalue 1: the real io.open.
int luaIoOpen(lua_State* L) {
  lua_settop(L, 2);
  std::size_t size = 0;
  const char* path = luaL_checklstring(L, 1, &size);
  const char* mode = luaL_optstring(L, 2, "r");
  // The modes Lua's io.open takes (r, w or a, an optional +, an optional b).
  bool valid_mode = false;
  for (const char* m : {"r", "w", "a", "r+", "w+", "a+", "rb", "wb", "ab", "r+b", "w+b", "a+b"})
    valid_mode = valid_mode || std::strcmp(mode, m) == 0;
  if (!valid_mode)
    return luaL_error(L, "io.open: invalid mode '%s' (expected r, w, a, r+, w+, a+, each with an optional b)", mode);
  const bool write = isWriteMode(mode);
  Context& ctx = contextOf(L);
  if (!guarded(ctx, [&] {
        ctx.text = write ? confinedPath(ctx.output_dir, std::string_view(path, size), "writing")
                         : confinedPath(ctx.read_root, std::string_view(path, size), "reading", ctx.script_dir);
      }))
    raiseKept(L, "io.open");
  lua_pushvalue(L, lua_upvalueindex(1));
  lua_pushlstring(L, ctx.text.data(), ctx.text.size());
  lua_pushstring(L, mode);
  lua_call(L, 2, LUA_MULTRET);
  return lua_gettop(L) - 2;
}

// io.lines(path, ...): read-only, under the script's folder. Upvalue 1: the real io.lines.
int luaIoLines(lua_State* L) {
  std::size_t size = 0;
  const char* path = luaL_checklstring(L, 1, &size);
  Context& ctx = contextOf(L);
  if (!guarded(ctx, [&] {
        ctx.text = confinedPath(ctx.read_root, std::string_view(path, size), "reading", ctx.script_dir);
      }))
    raiseKept(L, "io.lines");
  lua_pushlstring(L, ctx.text.data(), ctx.text.size());
  lua_replace(L, 1);
  const int n = lua_gettop(L);
  lua_pushvalue(L, lua_upvalueindex(1));
  lua_insert(L, 1);
  lua_call(L, n, LUA_MULTRET);
  return lua_gettop(L);
}

// Copies field `name` of the table at -1 into the table at `to`.
void copyField(lua_State* L, int from, int to, const char* name) {
  lua_getfield(L, from, name);
  lua_setfield(L, to, name);
}

}  // namespace

void openSandbox(lua_State* L) {
  luaL_requiref(L, LUA_GNAME, luaopen_base, 1);
  luaL_requiref(L, LUA_STRLIBNAME, luaopen_string, 1);
  luaL_requiref(L, LUA_TABLIBNAME, luaopen_table, 1);
  luaL_requiref(L, LUA_MATHLIBNAME, luaopen_math, 1);
  luaL_requiref(L, LUA_UTF8LIBNAME, luaopen_utf8, 1);
  lua_settop(L, 0);

  lua_pushglobaltable(L);
  const int g = lua_gettop(L);
  for (const char* name : {"dofile", "loadfile", "require"}) {
    lua_pushnil(L);
    lua_setfield(L, g, name);
  }
  lua_pushcfunction(L, luaPrint);
  lua_setfield(L, g, "print");
  lua_getfield(L, g, "load");
  lua_pushcclosure(L, luaLoadText, 1);
  lua_setfield(L, g, "load");
  lua_pushcfunction(L, luaCollectGarbage);
  lua_setfield(L, g, "collectgarbage");
  lua_getfield(L, g, "setmetatable");
  lua_pushcclosure(L, luaSetMetatable, 1);
  lua_setfield(L, g, "setmetatable");
  // string.dump makes binary chunks (which load refuses anyway).
  lua_getfield(L, g, LUA_STRLIBNAME);
  lua_pushnil(L);
  lua_setfield(L, -2, "dump");
  lua_pop(L, 1);

  // os: the clock and the calendar only.
  luaL_requiref(L, LUA_OSLIBNAME, luaopen_os, 0);
  const int real_os = lua_gettop(L);
  lua_createtable(L, 0, 3);
  for (const char* name : {"clock", "time", "date"}) copyField(L, real_os, lua_gettop(L), name);
  lua_setfield(L, g, LUA_OSLIBNAME);
  lua_pop(L, 1);

  // io: checked open and lines, and io.type; file handles keep their methods. The handle
  // metatable is locked so that no script can give handles a Lua finalizer.
  luaL_requiref(L, LUA_IOLIBNAME, luaopen_io, 0);
  const int real_io = lua_gettop(L);
  lua_createtable(L, 0, 3);
  const int io = lua_gettop(L);
  lua_getfield(L, real_io, "open");
  lua_pushcclosure(L, luaIoOpen, 1);
  lua_setfield(L, io, "open");
  lua_getfield(L, real_io, "lines");
  lua_pushcclosure(L, luaIoLines, 1);
  lua_setfield(L, io, "lines");
  copyField(L, real_io, io, "type");
  lua_setfield(L, g, LUA_IOLIBNAME);
  lua_pop(L, 1);
  luaL_getmetatable(L, LUA_FILEHANDLE);
  lua_pushliteral(L, "locked");
  lua_setfield(L, -2, "__metatable");
  lua_pop(L, 1);
  // The standard library's own registry of loaded modules keeps the real io and os: scripts
  // cannot reach the registry (no debug library), and the names help error messages.
  lua_settop(L, 0);
}

}  // namespace vdg::script::detail
