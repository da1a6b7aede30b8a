// The sandbox: which standard libraries a script sees, and the checked replacements of print,
// load, collectgarbage, setmetatable, io.open and io.lines (see script.h and docs/language.md).
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include "context.h"
#include "vdg/io/read_file.h"

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

// xpcall(f, msgh, ...): Lua runs a message handler where the error is raised, with hooks off, so a
// handler that loops would escape the instruction budget. Here the handler runs after the call has
// unwound, with the hook on; without the debug library a handler cannot look at the failed call's
// stack anyway, so what it can compute is the same.
int luaXpcall(lua_State* L) {
  const int n = lua_gettop(L);
  luaL_checktype(L, 2, LUA_TFUNCTION);
  lua_pushvalue(L, 1);
  for (int i = 3; i <= n; ++i) lua_pushvalue(L, i);
  const int status = lua_pcall(L, n - 2, LUA_MULTRET, 0);
  if (status == LUA_OK) {
    lua_pushboolean(L, 1);
    lua_insert(L, n + 1);
    return lua_gettop(L) - n;
  }
  if (status != LUA_ERRMEM) {  // Lua calls no handler for a memory error either
    lua_pushvalue(L, 2);
    lua_insert(L, n + 1);
    (void)lua_pcall(L, 1, 1, 0);  // an error in the handler: its error value is the result
  }
  lua_pushboolean(L, 0);
  lua_insert(L, n + 1);
  return 2;
}

// open(2) flags of an io.open mode (already validated), without O_TRUNC: truncation waits until
// the opened file has been checked.
int openFlags(const char* mode) {
  const bool plus = std::strchr(mode, '+') != nullptr;
  int flags = O_NONBLOCK | O_NOCTTY | O_CLOEXEC;
  if (mode[0] == 'r') return flags | (plus ? O_RDWR : O_RDONLY);
  flags |= (plus ? O_RDWR : O_WRONLY);
  return mode[0] == 'a' ? flags | O_APPEND : flags;
}

bool sameFile(int fd, const std::string& path) {
  struct stat a {
  }, b{};
  return ::fstat(fd, &a) == 0 && ::stat(path.c_str(), &b) == 0 && a.st_dev == b.st_dev && a.st_ino == b.st_ino;
}

struct Opened {
  int fd = -1;
  int err = 0;  // errno of a failed open (io.open's nil, message, code)
  // Why the sandbox refuses the file (raised), a literal: an Opened lives in a frame that raises
  // with longjmp, so it has nothing to destroy.
  const char* refusal = nullptr;
};
static_assert(std::is_trivially_destructible_v<Opened>);

// Opens `full` (checked by confinedPath) for writing: relative to its folder, which must be the
// output folder or below it once opened, never through a symbolic link as its last component, and
// announcing a file it creates (ScriptOptions::created).
Opened openForWriting(Context& ctx, const std::string& full, const char* mode) {
  Opened o;
  const std::filesystem::path p(full);
  const std::string dir = p.parent_path().string(), name = p.filename().string();
  const int dirfd = ::open(dir.c_str(), O_PATH | O_DIRECTORY | O_CLOEXEC);
  if (dirfd < 0) {
    o.err = errno;
    return o;
  }
  if (!sameFile(dirfd, ctx.output_dir) && !openedBelow(dirfd, dir, ctx.output_dir)) {
    ::close(dirfd);
    o.refusal = "the path leads outside its folder (through a symbolic link)";
    return o;
  }
  const int flags = openFlags(mode) | O_NOFOLLOW;
  o.fd = ::openat(dirfd, name.c_str(), flags);
  if (o.fd < 0 && errno == ENOENT && ctx.created_files >= kMaxCreatedFiles) {
    ::close(dirfd);
    o.refusal = "the script has created 10000 files, the most one run may";
    static_assert(kMaxCreatedFiles == 10000, "the message above names the limit");
    return o;
  }
  if (o.fd < 0 && errno == ENOENT) {
    o.fd = ::openat(dirfd, name.c_str(), flags | O_CREAT | O_EXCL, 0666);
    if (o.fd >= 0) ++ctx.created_files;
    if (o.fd >= 0 && ctx.created) ctx.created(full);
  }
  if (o.fd < 0) o.err = errno;
  if (o.err == ELOOP) o.refusal = "writing through a symbolic link is refused";
  ::close(dirfd);
  return o;
}

// Opens `full` for io.open or io.lines and checks the opened file: a regular file (a FIFO or a
// device would block or never end), below its folder (the read root, or the output folder for
// writes) as opened, and for writes a file with no other hard link. Then truncates for "w".
Opened openChecked(Context& ctx, const std::string& full, const char* mode) {
  const bool write = isWriteMode(mode);
  Opened o;
  if (write) {
    o = openForWriting(ctx, full, mode);
  } else if ((o.fd = ::open(full.c_str(), openFlags(mode))) < 0) {
    o.err = errno;
  }
  if (o.fd < 0) return o;
  struct stat info {};
  if (::fstat(o.fd, &info) != 0 || !S_ISREG(info.st_mode))
    o.refusal = S_ISFIFO(info.st_mode) ? "a FIFO (named pipe) is refused (regular files only)"
                                       : "not a regular file (a folder or a device is refused)";
  else if (!write && !openedBelow(o.fd, full, ctx.read_root))
    o.refusal = "the path leads outside its folder (through a symbolic link)";
  else if (write && info.st_nlink > 1)
    o.refusal = "a file with another hard link is refused for writing";
  else if (mode[0] == 'w' && ::ftruncate(o.fd, 0) != 0)
    o.err = errno;
  if (o.refusal || o.err) {
    ::close(o.fd);
    o.fd = -1;
  } else {
    ::fcntl(o.fd, F_SETFL, ::fcntl(o.fd, F_GETFL) & ~O_NONBLOCK);
  }
  return o;
}

// The longest text Lua writes for a number ("%.14g" of a float, "%lld" of an integer).
constexpr std::int64_t kLongestNumberText = 32;

// f:write(...) counted against ScriptOptions::write_limit before anything is written (a number
// counts as the longest text Lua writes for one). Upvalue 1: the handle's real write method.
int luaFileWrite(lua_State* L) {
  std::int64_t bytes = 0;
  for (int i = 2, n = lua_gettop(L); i <= n; ++i) {
    std::size_t size = 0;
    if (lua_type(L, i) == LUA_TSTRING) (void)lua_tolstring(L, i, &size);
    bytes += lua_type(L, i) == LUA_TNUMBER ? kLongestNumberText : static_cast<std::int64_t>(size);
  }
  Context& ctx = contextOf(L);
  if (bytes > ctx.write_limit - ctx.written)
    return luaL_error(L, "write: the script's files would hold more than its write limit of %I bytes",
                      static_cast<lua_Integer>(ctx.write_limit));
  ctx.written += bytes;
  lua_pushvalue(L, lua_upvalueindex(1));
  lua_insert(L, 1);
  lua_call(L, lua_gettop(L) - 1, LUA_MULTRET);
  return lua_gettop(L);
}

int closeStream(lua_State* L) {
  auto* p = static_cast<luaL_Stream*>(luaL_checkudata(L, 1, LUA_FILEHANDLE));
  const int ok = std::fclose(p->f) == 0;
  return luaL_fileresult(L, ok, nullptr);
}

// Opens the file named by the string at `path_index` for io.open or io.lines (`function`, in
// messages): reads relative to the script's folder, writes relative to the output folder, both
// confined there and checked on the opened file (openChecked). Pushes a file handle (1 result), or
// nil, message, code (3) as Lua's io.open does; raises the sandbox's refusals.
int pushOpened(lua_State* L, int path_index, const char* mode, const char* function) {
  std::size_t size = 0;
  const char* path = luaL_checklstring(L, path_index, &size);
  const bool write = isWriteMode(mode);
  const char* verb = write ? "writing" : "reading";
  // The handle first: once the file is open, nothing may raise before it owns the descriptor.
  auto* stream = static_cast<luaL_Stream*>(lua_newuserdatauv(L, sizeof(luaL_Stream), 0));
  stream->f = nullptr;
  stream->closef = nullptr;  // not yet a file: the handle's __gc leaves it alone
  luaL_setmetatable(L, LUA_FILEHANDLE);
  Context& ctx = contextOf(L);
  Opened o;
  if (!guarded(ctx, [&] {
        ctx.text = write ? confinedPath(ctx.output_dir, std::string_view(path, size), verb)
                         : confinedPath(ctx.read_root, std::string_view(path, size), verb, ctx.script_dir);
        o = openChecked(ctx, ctx.text, mode);
        if (o.refusal) throw Error(std::string(verb) + " '" + std::string(path, size) + "': " + o.refusal);
      }))
    raiseKept(L, function);
  if (o.fd >= 0 && !(stream->f = ::fdopen(o.fd, mode))) {
    o.err = errno;
    ::close(o.fd);
  }
  if (!stream->f) {
    errno = o.err;
    return luaL_fileresult(L, 0, ctx.text.c_str());
  }
  stream->closef = closeStream;
  return 1;
}

// io.open(path [, mode]): see pushOpened.
int luaIoOpen(lua_State* L) {
  lua_settop(L, 2);
  const char* mode = luaL_optstring(L, 2, "r");
  // The modes Lua's io.open takes (r, w or a, an optional +, an optional b).
  bool valid_mode = false;
  for (const char* m : {"r", "w", "a", "r+", "w+", "a+", "rb", "wb", "ab", "r+b", "w+b", "a+b"})
    valid_mode = valid_mode || std::strcmp(mode, m) == 0;
  if (!valid_mode)
    return luaL_error(L, "io.open: invalid mode '%s' (expected r, w, a, r+, w+, a+, each with an optional b)", mode);
  return pushOpened(L, 1, mode, "io.open");
}

// io.lines(path, ...): read-only, under the read root, through pushOpened's checks; returns the
// handle's lines iterator and the handle as the loop's to-be-closed value (as Lua 5.4's io.lines).
int luaIoLines(lua_State* L) {
  const int n = lua_gettop(L);
  if (pushOpened(L, 1, "r", "io.lines") != 1) return luaL_error(L, "%s", lua_tostring(L, -2));
  const int file = lua_gettop(L);
  lua_getfield(L, file, "lines");
  lua_pushvalue(L, file);
  for (int i = 2; i <= n; ++i) lua_pushvalue(L, i);
  lua_call(L, n, 1);  // the iterator
  lua_pushnil(L);
  lua_pushnil(L);
  lua_pushvalue(L, file);
  return 4;
}

// os.clock, os.time, os.date (upvalue 1 the real one, 2 its name): refused while the actors run,
// whose frames must come out the same in every run, on every machine (Parent 4.8 actors; a render
// farm replays them for every frame range).
int luaOsOutsideActors(lua_State* L) {
  if (contextOf(L).acting)
    return luaL_error(L, "os.%s: not available while the actors run (their frames must be the same in every run)",
                      lua_tostring(L, lua_upvalueindex(2)));
  const int n = lua_gettop(L);
  lua_pushvalue(L, lua_upvalueindex(1));
  lua_insert(L, 1);
  lua_call(L, n, LUA_MULTRET);
  return lua_gettop(L);
}

// ---- pairs in a fixed order ----
// Lua's pairs follows the table's hash layout, and Lua seeds its string hashes from the clock and
// an address: the order of string keys changes from run to run. An actor that sums in that order
// would give a farm node's frames other bits than a full run's. So pairs visits the keys sorted:
// numbers by value, then strings bytewise, then false, true; keys of other types (tables,
// functions, userdata: no order survives a run) come last, in Lua's order.

int keyRank(lua_State* L, int idx) {
  switch (lua_type(L, idx)) {
    case LUA_TNUMBER:
      return 0;
    case LUA_TSTRING:
      return 1;
    case LUA_TBOOLEAN:
      return 2;
    default:
      return 3;
  }
}

// Whether key a comes before key b (non-raising: numbers compare without metamethods).
bool keyBefore(lua_State* L, int a, int b) {
  const int ra = keyRank(L, a), rb = keyRank(L, b);
  if (ra != rb) return ra < rb;
  if (ra == 0) {
    int ia = 0, ib = 0;
    const lua_Integer xa = lua_tointegerx(L, a, &ia), xb = lua_tointegerx(L, b, &ib);
    if (ia && ib) return xa < xb;
    return lua_tonumberx(L, a, nullptr) < lua_tonumberx(L, b, nullptr);
  }
  if (ra == 1) {
    std::size_t na = 0, nb = 0;
    const char* sa = lua_tolstring(L, a, &na);
    const char* sb = lua_tolstring(L, b, &nb);
    const int c = std::memcmp(sa, sb, std::min(na, nb));
    return c < 0 || (c == 0 && na < nb);
  }
  if (ra == 2) return !lua_toboolean(L, a) && lua_toboolean(L, b);
  return false;
}

// The iterator: upvalues the table, the sorted keys, the next position. A key assigned nil during
// the traversal is skipped; one added is not visited (Lua leaves both undefined).
int sortedNext(lua_State* L) {
  for (;;) {
    const lua_Integer i = lua_tointegerx(L, lua_upvalueindex(3), nullptr) + 1;
    lua_pushinteger(L, i);
    lua_replace(L, lua_upvalueindex(3));
    if (lua_rawgeti(L, lua_upvalueindex(2), i) == LUA_TNIL) return 1;  // done: nil
    lua_pushvalue(L, -1);
    if (lua_rawget(L, lua_upvalueindex(1)) != LUA_TNIL) return 2;  // key, value
    lua_pop(L, 2);                                                 // removed meanwhile: skip it
  }
}

// pairs(t): t's keys in the order above (a table with __pairs, or another value, as Lua's pairs).
int luaPairs(lua_State* L) {
  if (lua_type(L, 1) != LUA_TTABLE || luaL_getmetafield(L, 1, "__pairs") != LUA_TNIL) {
    lua_settop(L, 1);
    lua_pushvalue(L, lua_upvalueindex(1));
    lua_insert(L, 1);
    lua_call(L, 1, 3);
    return 3;
  }
  lua_settop(L, 1);
  lua_newtable(L);  // 2: the keys, in Lua's order
  lua_Integer n = 0;
  lua_pushnil(L);
  while (lua_next(L, 1) != 0) {
    lua_pop(L, 1);
    lua_pushvalue(L, -1);
    lua_rawseti(L, 2, ++n);
  }
  // The sort's work counts against the instruction budget (n log2 n comparisons).
  Context& ctx = contextOf(L);
  const auto count = static_cast<std::int64_t>(n);
  ctx.executed += count * (1 + static_cast<std::int64_t>(std::log2(static_cast<double>(count) + 1)));
  if (ctx.executed >= ctx.budget || ctx.budget_exceeded) {
    ctx.budget_exceeded = true;
    return luaL_error(L, "instruction budget exceeded");
  }
  auto* order =
      static_cast<lua_Integer*>(lua_newuserdatauv(L, sizeof(lua_Integer) * static_cast<std::size_t>(n + 1), 0));
  for (lua_Integer i = 0; i < n; ++i) order[i] = i + 1;
  luaL_checkstack(L, 4, "pairs");
  std::sort(order, order + n, [&](lua_Integer a, lua_Integer b) {
    lua_rawgeti(L, 2, a);
    lua_rawgeti(L, 2, b);
    const bool before = keyBefore(L, -2, -1);
    lua_pop(L, 2);
    return before;
  });
  lua_createtable(L, static_cast<int>(std::min<lua_Integer>(n, 1 << 20)), 0);  // 4: the keys, sorted
  for (lua_Integer i = 0; i < n; ++i) {
    lua_rawgeti(L, 2, order[i]);
    lua_rawseti(L, 4, i + 1);
  }
  lua_pushvalue(L, 1);
  lua_pushvalue(L, 4);
  lua_pushinteger(L, 0);
  lua_pushcclosure(L, sortedNext, 3);
  return 1;
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
  lua_pushcfunction(L, luaXpcall);
  lua_setfield(L, g, "xpcall");
  lua_getfield(L, g, "pairs");
  lua_pushcclosure(L, luaPairs, 1);
  lua_setfield(L, g, "pairs");
  lua_pushcfunction(L, luaCollectGarbage);
  lua_setfield(L, g, "collectgarbage");
  lua_getfield(L, g, "setmetatable");
  lua_pushcclosure(L, luaSetMetatable, 1);
  lua_setfield(L, g, "setmetatable");
  // math.random starts from the same seed in every run (Lua seeds it from the clock and an
  // address): a script, and its actors, give the same frames wherever they run.
  lua_getfield(L, g, LUA_MATHLIBNAME);
  lua_getfield(L, -1, "randomseed");
  lua_pushinteger(L, 0);
  lua_call(L, 1, 0);
  lua_pop(L, 1);
  // string.dump makes binary chunks (which load refuses anyway).
  lua_getfield(L, g, LUA_STRLIBNAME);
  lua_pushnil(L);
  lua_setfield(L, -2, "dump");
  lua_pop(L, 1);

  // os: the clock and the calendar only.
  luaL_requiref(L, LUA_OSLIBNAME, luaopen_os, 0);
  const int real_os = lua_gettop(L);
  lua_createtable(L, 0, 3);
  for (const char* name : {"clock", "time", "date"}) {
    lua_getfield(L, real_os, name);
    lua_pushstring(L, name);
    lua_pushcclosure(L, luaOsOutsideActors, 2);
    lua_setfield(L, -2, name);
  }
  lua_setfield(L, g, LUA_OSLIBNAME);
  lua_pop(L, 1);

  // io: checked open and lines, and io.type; file handles keep their methods. The handle
  // metatable is locked so that no script can give handles a Lua finalizer.
  luaL_requiref(L, LUA_IOLIBNAME, luaopen_io, 0);
  const int real_io = lua_gettop(L);
  lua_createtable(L, 0, 3);
  const int io = lua_gettop(L);
  lua_pushcfunction(L, luaIoOpen);
  lua_setfield(L, io, "open");
  lua_pushcfunction(L, luaIoLines);
  lua_setfield(L, io, "lines");
  copyField(L, real_io, io, "type");
  lua_setfield(L, g, LUA_IOLIBNAME);
  lua_pop(L, 1);
  luaL_getmetatable(L, LUA_FILEHANDLE);
  lua_getfield(L, -1, "__index");  // the handles' methods: write is counted
  lua_getfield(L, -1, "write");
  lua_pushcclosure(L, luaFileWrite, 1);
  lua_setfield(L, -2, "write");
  lua_pop(L, 1);
  lua_pushliteral(L, "locked");
  lua_setfield(L, -2, "__metatable");
  lua_pop(L, 1);
  // The standard library's own registry of loaded modules keeps the real io and os: scripts
  // cannot reach the registry (no debug library), and the names help error messages.
  lua_settop(L, 0);
}

}  // namespace vdg::script::detail
