// vdg.ease, vdg.quat and vdg.curve: the animation mathematics of the anim module, exposed so that
// a script can compute with (and print) what it animates with (Parent, Computer Animation,
// sections 4.1-4.3). See context.h for the phase rules every function here follows.
#include <cmath>
#include <cstring>
#include <memory>

#include "context.h"
#include "vdg/anim/arc_length.h"
#include "vdg/anim/curve.h"
#include "vdg/anim/rotation.h"

namespace vdg::script::detail {
namespace {

double checkFinite(lua_State* L, int arg, const char* function) {
  const double v = luaL_checknumber(L, arg);
  if (!std::isfinite(v)) luaL_error(L, "%s: argument #%d must be a finite number", function, arg);
  return v;
}

// ---- ease ----

// The three ease functions of Parent 4.2 as plain functions of t.
int easeSine(lua_State* L) {
  lua_pushnumber(L, anim::easeSine(checkFinite(L, 1, "vdg.ease.sine")));
  return 1;
}

int easeTwoParameters(lua_State* L, anim::EaseKind kind, const char* function) {
  const double t = checkFinite(L, 1, function), p1 = checkFinite(L, 2, function), p2 = checkFinite(L, 3, function);
  double value = 0;
  Context& ctx = contextOf(L);
  if (!guarded(ctx, [&] {
        value = kind == anim::EaseKind::kSinusoidal ? anim::easeSinusoidal(t, p1, p2) : anim::easeParabolic(t, p1, p2);
      }))
    raiseKept(L, function);
  lua_pushnumber(L, value);
  return 1;
}
int easeSinusoidal(lua_State* L) { return easeTwoParameters(L, anim::EaseKind::kSinusoidal, "vdg.ease.sinusoidal"); }
int easeParabolic(lua_State* L) { return easeTwoParameters(L, anim::EaseKind::kParabolic, "vdg.ease.parabolic"); }

// vdg.ease.make(kind [, p1, p2]) -> ease object.
int easeMake(lua_State* L) {
  const char* kind = luaL_checkstring(L, 1);
  anim::Ease ease;
  const bool two = std::strcmp(kind, "sinusoidal") == 0 || std::strcmp(kind, "parabolic") == 0;
  if (!two && std::strcmp(kind, "linear") != 0 && std::strcmp(kind, "sine") != 0)
    return luaL_error(L, "vdg.ease.make: unknown ease '%s' (expected linear, sine, sinusoidal or parabolic)", kind);
  if (!two && lua_gettop(L) > 1) return luaL_error(L, "vdg.ease.make: the %s ease takes no parameters", kind);
  double p1 = 0, p2 = 1;
  if (two) {
    if (lua_gettop(L) != 3)
      return luaL_error(L, "vdg.ease.make: the %s ease takes two parameters (%s)", kind,
                        kind[0] == 's' ? "t1, t2: vdg.ease.make(\"sinusoidal\", 0.2, 0.8)"
                                       : "a, b: vdg.ease.make(\"parabolic\", 0.2, 0.8)");
    p1 = checkFinite(L, 2, "vdg.ease.make");
    p2 = checkFinite(L, 3, "vdg.ease.make");
  }
  Context& ctx = contextOf(L);
  if (!guarded(ctx, [&] {
        if (std::strcmp(kind, "linear") == 0)
          ease = anim::Ease::linear();
        else if (std::strcmp(kind, "sine") == 0)
          ease = anim::Ease::sine();
        else if (std::strcmp(kind, "sinusoidal") == 0)
          ease = anim::Ease::sinusoidal(p1, p2);
        else
          ease = anim::Ease::parabolic(p1, p2);
      }))
    raiseKept(L, "vdg.ease.make");
  auto* e = static_cast<anim::Ease*>(lua_newuserdatauv(L, sizeof(anim::Ease), 0));
  *e = ease;
  luaL_setmetatable(L, "vdg.ease");
  return 1;
}

const anim::Ease& checkEase(lua_State* L, int idx, const char* function) {
  const auto* e = toUserdata<anim::Ease>(L, idx, contextOf(L).mt_ease);
  if (!e) luaL_error(L, "%s: expected an ease object (vdg.ease.make)", function);
  return *e;
}

// e(t) and e:eval(t).
int easeEval(lua_State* L) {
  const anim::Ease& e = checkEase(L, 1, "ease:eval");
  lua_pushnumber(L, e.evaluate(checkFinite(L, 2, "ease:eval")));
  return 1;
}

int easeToString(lua_State* L) {
  const anim::Ease& e = checkEase(L, 1, "tostring");
  Context& ctx = contextOf(L);
  if (!guarded(ctx, [&] { ctx.text = "ease " + e.describe(); })) raiseKept(L, "tostring");
  lua_pushlstring(L, ctx.text.data(), ctx.text.size());
  return 1;
}

// ---- quaternions ----

anim::Quaternion quatOf(const double q[4]) { return anim::Quaternion(q[0], q[1], q[2], q[3]); }
void pushQuaternion(lua_State* L, const anim::Quaternion& q) {
  const double v[4] = {q.w(), q.x(), q.y(), q.z()};
  pushQuat(L, v);
}

void checkQuat(lua_State* L, int idx, const char* function, double out[4]) {
  if (const char* why = readQuaternion(L, idx, out)) luaL_error(L, "%s: argument #%d: %s", function, idx, why);
}

int quatNew(lua_State* L) {
  double q[4];
  for (int i = 0; i < 4; ++i) q[i] = checkFinite(L, i + 1, "vdg.quat.new");
  if (q[0] == 0 && q[1] == 0 && q[2] == 0 && q[3] == 0)
    return luaL_error(L, "vdg.quat.new: a zero quaternion is no rotation");
  pushQuat(L, q);
  return 1;
}

int quatIdentity(lua_State* L) {
  const double q[4] = {1, 0, 0, 0};
  pushQuat(L, q);
  return 1;
}

// vdg.quat.axis_angle({x, y, z}, degrees): Parent 4.3, Rot(axis, theta).
int quatAxisAngle(lua_State* L) {
  double axis[3];
  if (readVector(L, 1, 3, axis)) return luaL_error(L, "vdg.quat.axis_angle: argument #1: expected an axis {x, y, z}");
  if (axis[0] == 0 && axis[1] == 0 && axis[2] == 0) return luaL_error(L, "vdg.quat.axis_angle: the axis is zero");
  const double degrees = checkFinite(L, 2, "vdg.quat.axis_angle");
  pushQuaternion(L, anim::axisAngleToQuaternion(Eigen::Vector3d(axis[0], axis[1], axis[2]), degrees * M_PI / 180.0));
  return 1;
}

// vdg.quat.slerp(a, b, t): shortest-arc spherical linear interpolation (Parent 4.3).
int quatSlerp(lua_State* L) {
  double a[4], b[4];
  checkQuat(L, 1, "vdg.quat.slerp", a);
  checkQuat(L, 2, "vdg.quat.slerp", b);
  const double t = checkFinite(L, 3, "vdg.quat.slerp");
  pushQuaternion(L, anim::slerp(quatOf(a).normalized(), quatOf(b).normalized(), t));
  return 1;
}

const QuatValue& checkQuatSelf(lua_State* L, const char* function) {
  const auto* q = toUserdata<QuatValue>(L, 1, contextOf(L).mt_quat);
  if (!q) luaL_error(L, "%s: expected a quaternion (call it as q:%s(...))", function, std::strchr(function, ':') + 1);
  return *q;
}

// q:rotate({x, y, z}) -> {x', y', z'}: q v q^-1 (Parent 4.3, in our column-vector convention).
int quatRotate(lua_State* L) {
  const QuatValue& q = checkQuatSelf(L, "quat:rotate");
  double v[3];
  if (readVector(L, 2, 3, v)) return luaL_error(L, "quat:rotate: expected a vector {x, y, z}");
  const double wxyz[4] = {q.w, q.x, q.y, q.z};
  const Eigen::Vector3d r = anim::rotate(quatOf(wxyz), Eigen::Vector3d(v[0], v[1], v[2]));
  const double out[3] = {r.x(), r.y(), r.z()};
  pushNumbers(L, out, 3);
  return 1;
}

int quatNormalized(lua_State* L) {
  const QuatValue& q = checkQuatSelf(L, "quat:normalized");
  const double wxyz[4] = {q.w, q.x, q.y, q.z};
  pushQuaternion(L, quatOf(wxyz).normalized());
  return 1;
}

int quatInverse(lua_State* L) {
  const QuatValue& q = checkQuatSelf(L, "quat:inverse");
  const double wxyz[4] = {q.w, q.x, q.y, q.z};
  pushQuaternion(L, anim::inverse(quatOf(wxyz)));
  return 1;
}

// a * b: the rotation b, then a (Parent 4.3's product in our convention).
int quatMul(lua_State* L) {
  double a[4], b[4];
  checkQuat(L, 1, "quaternion *", a);
  checkQuat(L, 2, "quaternion *", b);
  pushQuaternion(L, anim::multiply(quatOf(a), quatOf(b)));
  return 1;
}

int quatIndex(lua_State* L) {
  const QuatValue& q = checkQuatSelf(L, "quat:index");
  const char* key = luaL_checkstring(L, 2);
  if (key[0] != '\0' && key[1] == '\0') {
    switch (key[0]) {
      case 'w':
        lua_pushnumber(L, q.w);
        return 1;
      case 'x':
        lua_pushnumber(L, q.x);
        return 1;
      case 'y':
        lua_pushnumber(L, q.y);
        return 1;
      case 'z':
        lua_pushnumber(L, q.z);
        return 1;
    }
  }
  lua_getfield(L, lua_upvalueindex(1), key);  // methods
  if (lua_isnil(L, -1))
    return luaL_error(L, "quaternion: no field '%s' (w, x, y, z, rotate, normalized, inverse)", key);
  return 1;
}

int quatToString(lua_State* L) {
  const QuatValue& q = checkQuatSelf(L, "quat:tostring");
  char text[160];
  std::snprintf(text, sizeof text, "quat(%.9g, %.9g, %.9g, %.9g)", q.w, q.x, q.y, q.z);
  lua_pushstring(L, text);
  return 1;
}

// ---- curves ----

// The userdata holds a pointer (trivially destructible); __gc deletes what it points to.
struct CurveBox {
  anim::ArcLengthCurve* curve = nullptr;
};

int curveGc(lua_State* L) {
  auto* box = static_cast<CurveBox*>(lua_touserdata(L, 1));
  delete box->curve;
  box->curve = nullptr;
  return 0;
}

const char* const kCurveKeys[] = {"points", "times", "interpolation", nullptr};

// vdg.curve{points = {{x, y, z}, ...}, times = {...}, interpolation = "catmull-rom"}.
int curveNew(lua_State* L) {
  luaL_checktype(L, 1, LUA_TTABLE);
  checkKeys(L, 1, "vdg.curve", kCurveKeys);
  const int points = field(L, 1, "points");
  const int times = field(L, 1, "times");
  const int interpolation = field(L, 1, "interpolation");
  anim::CurveKind kind = anim::CurveKind::kCatmullRom;
  if (!lua_isnil(L, interpolation)) {
    const char* name = lua_type(L, interpolation) == LUA_TSTRING ? lua_tostring(L, interpolation) : "";
    if (!curveKindFromName(name, &kind))
      return luaL_error(
          L,
          "vdg.curve: interpolation: expected linear, catmull-rom, centripetal-catmull-rom, natural-cubic, "
          "parabolic-blending or bezier");
  }
  if (lua_type(L, points) != LUA_TTABLE)
    return luaL_error(L, "vdg.curve: points: expected a list of points {{x, y, z}, ...}");
  const lua_Unsigned n = lua_rawlen(L, points);
  int dimension = 0;
  luaL_checkstack(L, 4, "vdg.curve");
  for (lua_Unsigned i = 1; i <= n; ++i) {
    lua_rawgeti(L, points, static_cast<lua_Integer>(i));
    const int p = lua_gettop(L);
    const lua_Unsigned d = lua_type(L, p) == LUA_TTABLE ? lua_rawlen(L, p) : 0;
    if (d < 1 || d > anim::kMaxCurveDimension)
      return luaL_error(L, "vdg.curve: points[%d]: expected a point: a table of 1 to %d numbers", static_cast<int>(i),
                        anim::kMaxCurveDimension);
    if (dimension == 0) dimension = static_cast<int>(d);
    if (static_cast<int>(d) != dimension)
      return luaL_error(L, "vdg.curve: points[%d] has %d coordinates, points[1] has %d", static_cast<int>(i),
                        static_cast<int>(d), dimension);
    double coords[anim::kMaxCurveDimension];
    if (readVector(L, p, dimension, coords))
      return luaL_error(L, "vdg.curve: points[%d]: expected finite numbers", static_cast<int>(i));
    lua_pop(L, 1);
  }
  lua_Unsigned time_count = 0;
  if (!lua_isnil(L, times)) {
    if (lua_type(L, times) != LUA_TTABLE) return luaL_error(L, "vdg.curve: times: expected a list of numbers");
    time_count = lua_rawlen(L, times);
    for (lua_Unsigned i = 1; i <= time_count; ++i) {
      double t;
      lua_rawgeti(L, times, static_cast<lua_Integer>(i));
      if (readNumber(L, lua_gettop(L), &t))
        return luaL_error(L, "vdg.curve: times[%d]: expected a finite number", static_cast<int>(i));
      lua_pop(L, 1);
    }
  }
  charge(L, (n * static_cast<lua_Unsigned>(dimension) + time_count) * 64 + 1024);
  auto* box = static_cast<CurveBox*>(lua_newuserdatauv(L, sizeof(CurveBox), 0));
  box->curve = nullptr;
  luaL_setmetatable(L, "vdg.curve");
  Context& ctx = contextOf(L);
  if (!guarded(ctx, [&] {
        anim::RawCurve raw;
        raw.kind = kind;
        raw.points.reserve(n);
        for (lua_Unsigned i = 1; i <= n; ++i) {
          lua_rawgeti(L, points, static_cast<lua_Integer>(i));
          Eigen::VectorXd point(dimension);
          for (int j = 0; j < dimension; ++j) {
            lua_rawgeti(L, -1, j + 1);
            point[j] = lua_tonumberx(L, -1, nullptr);
            lua_pop(L, 1);
          }
          lua_pop(L, 1);
          raw.points.push_back(std::move(point));
        }
        for (lua_Unsigned i = 1; i <= time_count; ++i) {
          lua_rawgeti(L, times, static_cast<lua_Integer>(i));
          raw.times.push_back(lua_tonumberx(L, -1, nullptr));
          lua_pop(L, 1);
        }
        const anim::Curve curve = anim::Curve::build(raw, "vdg.curve");
        box->curve = new anim::ArcLengthCurve(anim::ArcLengthCurve::build(curve, {}, "vdg.curve"));
      }))
    raiseKept(L, "vdg.curve");
  return 1;
}

const anim::ArcLengthCurve& checkCurve(lua_State* L, const char* function) {
  const auto* box = toUserdata<CurveBox>(L, 1, contextOf(L).mt_curve);
  if (!box || !box->curve)
    luaL_error(L, "%s: expected a curve (call it as c:%s(...))", function, std::strchr(function, ':') + 1);
  return *box->curve;
}

void pushCurvePoint(lua_State* L, const anim::ArcLengthCurve& c, bool at_length, double s) {
  double out[anim::kMaxCurveDimension];
  const std::span<double> span(out, static_cast<std::size_t>(c.curve().dimension()));
  const bool ok = at_length ? c.evaluateAtDistance(s, span) : c.curve().evaluate(s, span);
  if (!ok) luaL_error(L, "curve: evaluation failed");  // not reached: s is finite, the span sized
  pushNumbers(L, out, c.curve().dimension());
}

// c:eval(t): the point at curve parameter t (key times; clamped).
int curveEval(lua_State* L) {
  const anim::ArcLengthCurve& c = checkCurve(L, "curve:eval");
  pushCurvePoint(L, c, false, checkFinite(L, 2, "curve:eval"));
  return 1;
}

// c:length(): the arc length (adaptive Gauss-Kronrod, Parent 4.1).
int curveLength(lua_State* L) {
  lua_pushnumber(L, checkCurve(L, "curve:length").totalLength());
  return 1;
}

// c:at_length(s): the point at distance s from the start (clamped to [0, length]).
int curveAtLength(lua_State* L) {
  const anim::ArcLengthCurve& c = checkCurve(L, "curve:at_length");
  pushCurvePoint(L, c, true, checkFinite(L, 2, "curve:at_length"));
  return 1;
}

// c:range(): first and last key time.
int curveRange(lua_State* L) {
  const anim::ArcLengthCurve& c = checkCurve(L, "curve:range");
  lua_pushnumber(L, c.curve().startTime());
  lua_pushnumber(L, c.curve().endTime());
  return 2;
}

int curveToString(lua_State* L) {
  const anim::ArcLengthCurve& c = checkCurve(L, "curve:tostring");
  lua_pushfstring(L, "curve %s (%d coordinates, %d segments)", anim::curveKindName(c.curve().kind()),
                  c.curve().dimension(), c.curve().segmentCount());
  return 1;
}

}  // namespace

void openMath(lua_State* L, int vdg) {
  Context& ctx = contextOf(L);

  const luaL_Reg ease_functions[] = {{"sine", easeSine},
                                     {"sinusoidal", easeSinusoidal},
                                     {"parabolic", easeParabolic},
                                     {"make", easeMake},
                                     {nullptr, nullptr}};
  luaL_newlib(L, ease_functions);
  lua_setfield(L, vdg, "ease");
  const luaL_Reg ease_meta[] = {{"__call", easeEval}, {"__tostring", easeToString}, {nullptr, nullptr}};
  ctx.mt_ease = lockedMetatable(L, "vdg.ease", ease_meta);
  luaL_getmetatable(L, "vdg.ease");
  lua_newtable(L);
  lua_pushcfunction(L, easeEval);
  lua_setfield(L, -2, "eval");
  lua_setfield(L, -2, "__index");
  lua_pop(L, 1);

  const luaL_Reg quat_functions[] = {{"new", quatNew},
                                     {"identity", quatIdentity},
                                     {"axis_angle", quatAxisAngle},
                                     {"slerp", quatSlerp},
                                     {nullptr, nullptr}};
  luaL_newlib(L, quat_functions);
  lua_setfield(L, vdg, "quat");
  const luaL_Reg quat_meta[] = {{"__mul", quatMul}, {"__tostring", quatToString}, {nullptr, nullptr}};
  ctx.mt_quat = lockedMetatable(L, "vdg.quat", quat_meta);
  luaL_getmetatable(L, "vdg.quat");
  const luaL_Reg quat_methods[] = {
      {"rotate", quatRotate}, {"normalized", quatNormalized}, {"inverse", quatInverse}, {nullptr, nullptr}};
  luaL_newlib(L, quat_methods);
  lua_pushcclosure(L, quatIndex, 1);
  lua_setfield(L, -2, "__index");
  lua_pop(L, 1);

  lua_pushcfunction(L, curveNew);
  lua_setfield(L, vdg, "curve");
  const luaL_Reg curve_meta[] = {{"__gc", curveGc}, {"__tostring", curveToString}, {nullptr, nullptr}};
  ctx.mt_curve = lockedMetatable(L, "vdg.curve", curve_meta);
  luaL_getmetatable(L, "vdg.curve");
  const luaL_Reg curve_methods[] = {{"eval", curveEval},
                                    {"length", curveLength},
                                    {"at_length", curveAtLength},
                                    {"range", curveRange},
                                    {nullptr, nullptr}};
  luaL_newlib(L, curve_methods);
  lua_setfield(L, -2, "__index");
  lua_pop(L, 1);
}

}  // namespace vdg::script::detail
