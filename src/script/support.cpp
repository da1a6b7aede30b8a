// Shared helpers of the Lua bindings: argument readers, handles, error raising, confined paths.
// See context.h for the phase rules every function here follows.
#include <cmath>
#include <cstring>
#include <filesystem>

#include "context.h"

namespace vdg::script::detail {

Context& contextOf(lua_State* L) { return **static_cast<Context**>(lua_getextraspace(L)); }

void raiseKept(lua_State* L, const char* function) {
  Context& ctx = contextOf(L);
  if (ctx.error.empty()) {  // the message itself could not be copied: memory ran out
    lua_pushliteral(L, "not enough memory");
    lua_error(L);
  }
  // Messages of the anim and scene builders already start with the `where` they were given.
  const std::size_t n = std::strlen(function);
  if (ctx.error.compare(0, n, function) == 0 && ctx.error.compare(n, 2, ": ") == 0)
    luaL_error(L, "%s", ctx.error.c_str());
  luaL_error(L, "%s: %s", function, ctx.error.c_str());
  std::abort();  // not reached: luaL_error does not return
}

void charge(lua_State* L, std::size_t bytes) {
  Context& ctx = contextOf(L);
  const std::size_t used = ctx.lua_bytes + ctx.cxx_bytes;
  if (bytes > ctx.memory_limit || used > ctx.memory_limit - bytes) {
    ctx.out_of_memory = true;
    lua_pushliteral(L, "not enough memory");
    lua_error(L);
  }
  ctx.cxx_bytes += bytes;
}

const char* readNumber(lua_State* L, int idx, double* out) {
  int is_number = 0;
  const double v = lua_tonumberx(L, idx, &is_number);
  if (!is_number || lua_type(L, idx) != LUA_TNUMBER) return "expected a number";
  if (!std::isfinite(v)) return "expected a finite number";
  *out = v;
  return nullptr;
}

const char* readVector(lua_State* L, int idx, int n, double* out) {
  if (lua_type(L, idx) != LUA_TTABLE)
    return n == 3 ? "expected a table of 3 numbers {x, y, z}" : "expected a table of numbers";
  if (lua_rawlen(L, idx) != static_cast<lua_Unsigned>(n))
    return n == 3   ? "expected a table of 3 numbers {x, y, z}"
           : n == 4 ? "expected a table of 4 numbers"
                    : "expected a table of numbers of the field's size";
  for (int i = 0; i < n; ++i) {
    lua_rawgeti(L, idx, i + 1);
    const char* why = readNumber(L, lua_gettop(L), &out[i]);
    lua_pop(L, 1);
    if (why) return "expected finite numbers in the table";
  }
  return nullptr;
}

const char* readQuaternion(lua_State* L, int idx, double out[4]) {
  Context& ctx = contextOf(L);
  if (const QuatValue* q = toUserdata<QuatValue>(L, idx, ctx.mt_quat)) {
    out[0] = q->w, out[1] = q->x, out[2] = q->y, out[3] = q->z;
  } else if (lua_type(L, idx) == LUA_TTABLE && lua_rawlen(L, idx) == 4) {
    if (readVector(L, idx, 4, out)) return "expected a quaternion or {w, x, y, z} of finite numbers";
  } else {
    return "expected a quaternion (vdg.quat...) or {w, x, y, z}";
  }
  if (out[0] == 0 && out[1] == 0 && out[2] == 0 && out[3] == 0) return "a zero quaternion is no rotation";
  return nullptr;
}

const char* readColor(lua_State* L, int idx, double out[3]) {
  if (readVector(L, idx, 3, out)) return "expected a colour {r, g, b} of numbers in [0, 1]";
  for (int i = 0; i < 3; ++i)
    if (out[i] < 0 || out[i] > 1) return "expected a colour {r, g, b} of numbers in [0, 1]";
  return nullptr;
}

const char* readScale(lua_State* L, int idx, double out[3]) {
  if (lua_type(L, idx) == LUA_TNUMBER) {
    if (const char* why = readNumber(L, idx, &out[0])) return why;
    out[1] = out[2] = out[0];
  } else if (readVector(L, idx, 3, out)) {
    return "expected a scale: a number or {sx, sy, sz}";
  }
  for (int i = 0; i < 3; ++i)
    if (out[i] == 0) return "a scale of 0 is not invertible";
  return nullptr;
}

const char* readFieldValue(lua_State* L, int idx, scene::Field field, double out[4]) {
  switch (field) {
    case scene::Field::kTranslation:
      return readVector(L, idx, 3, out);
    case scene::Field::kRotation:
      return readQuaternion(L, idx, out);
    case scene::Field::kScale:
      return readScale(L, idx, out);
    case scene::Field::kColor:
      return readColor(L, idx, out);
    case scene::Field::kVisible:
      if (lua_type(L, idx) == LUA_TBOOLEAN) {
        out[0] = lua_toboolean(L, idx) ? 1.0 : 0.0;
        return nullptr;
      }
      return readNumber(L, idx, out) ? "expected true, false or a number" : nullptr;
    case scene::Field::kFov:
      if (readNumber(L, idx, out) || !(out[0] > 0 && out[0] < 180))
        return "expected a field of view in (0, 180) degrees";
      return nullptr;
    case scene::Field::kSharpness:
    case scene::Field::kFrameOffset:
      return readNumber(L, idx, out);
  }
  return "unknown field";
}

const char* readFieldDelta(lua_State* L, int idx, scene::Field field, double out[4]) {
  switch (field) {
    case scene::Field::kRotation:
      return readQuaternion(L, idx, out);
    case scene::Field::kTranslation:
    case scene::Field::kColor:
      return readVector(L, idx, 3, out);
    case scene::Field::kScale:
      if (lua_type(L, idx) == LUA_TNUMBER) {
        if (const char* why = readNumber(L, idx, &out[0])) return why;
        out[1] = out[2] = out[0];
        return nullptr;
      }
      return readVector(L, idx, 3, out) ? "expected a number or {dx, dy, dz}" : nullptr;
    case scene::Field::kVisible:
    case scene::Field::kSharpness:
    case scene::Field::kFrameOffset:
    case scene::Field::kFov:
      return readNumber(L, idx, out);
  }
  return "unknown field";
}

const char* readEase(lua_State* L, int idx, anim::Ease* out) {
  Context& ctx = contextOf(L);
  if (const anim::Ease* e = toUserdata<anim::Ease>(L, idx, ctx.mt_ease)) {
    *out = *e;
    return nullptr;
  }
  if (lua_type(L, idx) == LUA_TSTRING) {
    const char* name = lua_tolstring(L, idx, nullptr);
    if (std::strcmp(name, "linear") == 0) {
      *out = anim::Ease::linear();
      return nullptr;
    }
    if (std::strcmp(name, "sine") == 0) {
      *out = anim::Ease::sine();
      return nullptr;
    }
  }
  return "expected an ease (vdg.ease.make(...), \"linear\" or \"sine\")";
}

int checkNode(lua_State* L, int idx, const char* function, const char* what) {
  const NodeHandle* h = toUserdata<NodeHandle>(L, idx, contextOf(L).mt_node);
  if (!h)
    luaL_error(L, "%s: %s: expected a node (vdg.node, vdg.group or vdg.camera), got %s", function, what,
               luaL_typename(L, idx));
  return h->node;
}

void pushNode(lua_State* L, int node) {
  auto* h = static_cast<NodeHandle*>(lua_newuserdatauv(L, sizeof(NodeHandle), 0));
  h->node = node;
  luaL_setmetatable(L, "vdg.node");
}

void pushQuat(lua_State* L, const double wxyz[4]) {
  auto* q = static_cast<QuatValue*>(lua_newuserdatauv(L, sizeof(QuatValue), 0));
  q->w = wxyz[0], q->x = wxyz[1], q->y = wxyz[2], q->z = wxyz[3];
  luaL_setmetatable(L, "vdg.quat");
}

void pushNumbers(lua_State* L, const double* v, int n) {
  lua_createtable(L, n, 0);
  for (int i = 0; i < n; ++i) {
    lua_pushnumber(L, v[i]);
    lua_rawseti(L, -2, i + 1);
  }
}

void checkKeys(lua_State* L, int idx, const char* function, const char* const* allowed, bool array) {
  const lua_Unsigned length = array ? lua_rawlen(L, idx) : 0;
  lua_pushnil(L);
  while (lua_next(L, idx) != 0) {
    lua_pop(L, 1);  // the value
    int is_integer = 0;
    const lua_Integer i = lua_type(L, -1) == LUA_TNUMBER ? lua_tointegerx(L, -1, &is_integer) : 0;
    bool known = is_integer && i >= 1 && static_cast<lua_Unsigned>(i) <= length;
    if (lua_type(L, -1) == LUA_TSTRING) {
      const char* key = lua_tolstring(L, -1, nullptr);
      for (const char* const* a = allowed; *a; ++a) known = known || std::strcmp(key, *a) == 0;
    }
    if (!known) {
      luaL_Buffer b;
      luaL_buffinit(L, &b);
      for (const char* const* a = allowed; *a; ++a) {
        if (a != allowed) luaL_addstring(&b, ", ");
        luaL_addstring(&b, *a);
      }
      luaL_pushresult(&b);
      if (lua_type(L, -2) == LUA_TSTRING)
        luaL_error(L, "%s: unknown field '%s' (expected %s)", function, lua_tostring(L, -2), lua_tostring(L, -1));
      luaL_error(L, "%s: unexpected %s key in the table (expected the fields %s)", function, luaL_typename(L, -2),
                 lua_tostring(L, -1));
    }
  }
}

bool curveKindFromName(const char* name, anim::CurveKind* out) {
  for (anim::CurveKind k :
       {anim::CurveKind::kLinear, anim::CurveKind::kCatmullRom, anim::CurveKind::kCentripetalCatmullRom,
        anim::CurveKind::kNaturalCubic, anim::CurveKind::kParabolicBlending, anim::CurveKind::kBezier})
    if (std::strcmp(name, anim::curveKindName(k)) == 0) {
      *out = k;
      return true;
    }
  return false;
}

const void* lockedMetatable(lua_State* L, const char* name, const luaL_Reg* methods) {
  luaL_newmetatable(L, name);
  luaL_setfuncs(L, methods, 0);
  lua_pushliteral(L, "locked");
  lua_setfield(L, -2, "__metatable");
  const void* address = lua_topointer(L, -1);
  lua_pop(L, 1);
  return address;
}

int field(lua_State* L, int idx, const char* key) {
  lua_pushstring(L, key);
  lua_rawget(L, idx);
  return lua_gettop(L);
}

std::string confinedPath(const std::string& base, std::string_view rel, const char* what, const std::string& from) {
  namespace fs = std::filesystem;
  const std::string shown(rel);
  auto refuse = [&](const std::string& why) { throw Error(std::string(what) + " '" + shown + "': " + why); };
  if (rel.empty()) refuse("an empty path");
  if (rel.find('\0') != std::string_view::npos) refuse("a path with a NUL byte");
  if (rel.front() == '/') refuse("absolute paths are refused (give a path relative to the folder)");
  if (rel.find('\\') != std::string_view::npos) refuse("backslashes are refused");
  auto inside = [&](const std::string& r) { return r == base || r.compare(0, base.size() + 1, base + "/") == 0; };
  if (from.empty()) {
    std::size_t start = 0;
    while (start <= rel.size()) {
      const std::size_t end = std::min(rel.find('/', start), rel.size());
      if (rel.substr(start, end - start) == "..")
        refuse("'..' components are refused (the path must stay in its folder)");
      start = end + 1;
    }
  }
  const fs::path full = fs::path(from.empty() ? base : from) / fs::path(shown);
  if (!from.empty() && !inside(full.lexically_normal().string()))
    refuse("the path leads outside the folder the script may read (" + base + "; see vdg run --root)");
  std::error_code ec;
  const fs::path resolved = fs::weakly_canonical(full, ec);
  if (ec) refuse("cannot resolve the path: " + ec.message());
  if (!inside(resolved.string())) refuse("the path leads outside its folder (through a symbolic link)");
  // A dangling symbolic link as the last component: writing would create its target elsewhere.
  if (fs::is_symlink(fs::symlink_status(full, ec)) && !fs::exists(full, ec))
    refuse("a symbolic link that points nowhere is refused");
  return full.lexically_normal().string();
}

}  // namespace vdg::script::detail
