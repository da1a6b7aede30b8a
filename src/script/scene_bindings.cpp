// The scene half of the vdg module: vdg.load, vdg.node / group / camera, vdg.use_camera,
// vdg.set / change (Parent 4.6's SET and CHANGE), vdg.for_each (FOR EACH over object sets),
// vdg.track (Parent 4.9's key-frame tracks) and vdg.render. Each call adds to the RawScene of the
// run (scene::RawScene: nodes, actions, tracks). See context.h for the phase rules.
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>

#include "context.h"
#include "vdg/anim/camera_path.h"
#include "vdg/io/model.h"

namespace vdg::script::detail {
namespace {

using scene::Field;
using scene::ObjectKind;

int scriptLine(lua_State* L) {
  lua_Debug ar;
  if (lua_getstack(L, 1, &ar) && lua_getinfo(L, "l", &ar)) return ar.currentline;
  return 0;
}

// A string argument: pointer and length into the Lua string (alive while it is on the stack).
struct Text {
  const char* data = nullptr;
  std::size_t size = 0;
  std::string_view view() const { return {data, size}; }
};

// ---- vdg.render ----

// Whether folder `a` is `b` or one holds the other (lexically normal relative paths; "." holds all).
bool overlapping(const std::string& a, const std::string& b) {
  if (a == b || a == "." || b == ".") return true;
  const auto holds = [](const std::string& outer, const std::string& inner) {
    return inner.size() > outer.size() && inner.compare(0, outer.size(), outer) == 0 && inner[outer.size()] == '/';
  };
  return holds(a, b) || holds(b, a);
}

// Refuses an `out` folder that is the folder of an earlier render request or lies inside it (or
// holds it), as written and as resolved through symbolic links: the frames would overwrite each
// other, or one sequence would hold another's.
void checkOwnFolder(const Context& ctx, const std::string& out) {
  std::error_code ec;
  const auto resolved = [&](const std::string& rel) {
    const std::filesystem::path full =
        std::filesystem::weakly_canonical(std::filesystem::path(ctx.output_dir) / rel, ec);
    std::string text = ec ? std::string() : full.lexically_relative(ctx.output_dir).string();
    if (text.size() > 1 && text.back() == '/') text.pop_back();
    return text;
  };
  const std::string real = resolved(out);
  for (const RenderRequest& r : ctx.renders) {
    const std::string other = resolved(r.out);
    if (overlapping(out, r.out) || (!real.empty() && !other.empty() && overlapping(real, other)))
      throw Error("out '" + out + "' overlaps the out '" + r.out + "' of the render call at line " +
                  std::to_string(r.line) +
                  " (each vdg.render needs a folder of its own, not the same as another's or "
                  "inside it)");
  }
}

// ---- vdg.load ----

// vdg.load(path) -> object: a mesh (.obj, plain glTF), a view-dependent model (manifest, vdg
// glTF) or an animated model; the same path gives the same object (instancing).
int luaLoad(lua_State* L) {
  refuseWhileActing(L, "vdg.load");
  Text path;
  path.data = luaL_checklstring(L, 1, &path.size);
  const int line = scriptLine(L);
  Context& ctx = contextOf(L);
  int object = -1;
  std::size_t bytes = 0;
  if (!guarded(ctx, [&] {
        const std::string full = confinedPath(ctx.read_root, path.view(), "model", ctx.script_dir);
        const std::string key = std::filesystem::weakly_canonical(full).string();
        if (auto it = ctx.object_by_path.find(key); it != ctx.object_by_path.end()) {
          object = it->second;
          return;
        }
        std::vector<std::string> warnings;
        MeshReadOptions read;
        read.warnings = &warnings;
        ObjectRef ref;
        ref.path.assign(path.data, path.size);
        OpenedInput in = openInput(full, read);
        if (in.kind == InputKind::kMesh) {
          auto mesh = std::make_shared<TriMesh>(std::move(in.mesh));
          bytes = mesh->positions.size() * 4 + mesh->triangles.size() * 4;
          ref.kind = ObjectKind::kMesh;
          ref.index = static_cast<int>(ctx.scene.meshes.size());
          ctx.scene.meshes.push_back(std::move(mesh));
        } else {
          const RawViewDependentModel& raw = in.raw;
          bytes = raw.base.positions.size() * 4 * (raw.keys.size() + raw.base_frames.size() + 2) +
                  raw.base.triangles.size() * 4;
          if (in.animated) {
            ref.kind = ObjectKind::kAnimatedModel;
            ref.index = static_cast<int>(ctx.scene.animated_models.size());
            ctx.scene.animated_models.push_back(std::move(in.animated));
          } else {
            ref.kind = ObjectKind::kModel;
            ref.index = static_cast<int>(ctx.scene.models.size());
            ctx.scene.models.push_back(std::move(in.model));
          }
        }
        object = static_cast<int>(ctx.objects.size());
        ctx.objects.push_back(std::move(ref));
        ctx.object_by_path.emplace(key, object);
        for (const std::string& w : warnings) {
          const std::string message = ctx.chunk_name + ":" + std::to_string(line) + ": warning: " + w;
          if (ctx.print)
            ctx.print(message);
          else
            std::fprintf(stderr, "%s\n", message.c_str());
        }
      }))
    raiseKept(L, "vdg.load");
  if (bytes) charge(L, bytes);
  auto* h = static_cast<ObjectHandle*>(lua_newuserdatauv(L, sizeof(ObjectHandle), 0));
  h->object = object;
  luaL_setmetatable(L, "vdg.object");
  return 1;
}

// vdg.mesh{positions = {x1, y1, z1, ...}, triangles = {a1, b1, c1, ...}} -> object: a mesh made
// by the script (indices count from 1, as Lua lists and OBJ faces do). Each call is a new object.
int luaMesh(lua_State* L) {
  refuseWhileActing(L, "vdg.mesh");
  luaL_checktype(L, 1, LUA_TTABLE);
  static const char* const kKeys[] = {"positions", "triangles", nullptr};
  checkKeys(L, 1, "vdg.mesh", kKeys);
  const int p = field(L, 1, "positions");
  const int t = field(L, 1, "triangles");
  if (!lua_istable(L, p)) return luaL_error(L, "vdg.mesh: positions: expected a list of numbers x, y, z, ...");
  if (!lua_istable(L, t)) return luaL_error(L, "vdg.mesh: triangles: expected a list of vertex numbers a, b, c, ...");
  const lua_Unsigned np = lua_rawlen(L, p), nt = lua_rawlen(L, t);
  if (np < 9 || np % 3 != 0)
    return luaL_error(L, "vdg.mesh: positions: expected 3 numbers per vertex and at least 3 vertices, got %d numbers",
                      static_cast<int>(std::min<lua_Unsigned>(np, 1u << 30)));
  if (nt < 3 || nt % 3 != 0)
    return luaL_error(L, "vdg.mesh: triangles: expected 3 vertex numbers per triangle and at least one, got %d",
                      static_cast<int>(std::min<lua_Unsigned>(nt, 1u << 30)));
  charge(L, static_cast<std::size_t>(np + nt) * 4);
  luaL_checkstack(L, 2, "vdg.mesh");
  const int line = scriptLine(L);
  Context& ctx = contextOf(L);
  int object = -1;
  if (!guarded(ctx, [&] {
        auto mesh = std::make_shared<TriMesh>();
        mesh->positions.reserve(np);
        mesh->triangles.reserve(nt);
        for (lua_Unsigned i = 1; i <= np; ++i) {
          lua_rawgeti(L, p, static_cast<lua_Integer>(i));
          int ok = 0;
          const double v = lua_tonumberx(L, -1, &ok);
          lua_pop(L, 1);
          if (!ok || !std::isfinite(v) || std::abs(v) > 1e30)
            throw Error("positions[" + std::to_string(i) + "]: expected a finite number");
          mesh->positions.push_back(static_cast<float>(v));
        }
        const lua_Unsigned nv = np / 3;
        for (lua_Unsigned i = 1; i <= nt; ++i) {
          lua_rawgeti(L, t, static_cast<lua_Integer>(i));
          int ok = 0;
          const lua_Integer v = lua_tointegerx(L, -1, &ok);
          lua_pop(L, 1);
          if (!ok || v < 1 || static_cast<lua_Unsigned>(v) > nv)
            throw Error("triangles[" + std::to_string(i) + "]: expected a vertex number in [1, " + std::to_string(nv) +
                        "]");
          mesh->triangles.push_back(static_cast<std::int32_t>(v - 1));
        }
        validateMesh(*mesh, "mesh");
        ObjectRef ref;
        ref.kind = ObjectKind::kMesh;
        ref.index = static_cast<int>(ctx.scene.meshes.size());
        ref.path = "vdg.mesh at line " + std::to_string(line);
        ctx.scene.meshes.push_back(std::move(mesh));
        object = static_cast<int>(ctx.objects.size());
        ctx.objects.push_back(std::move(ref));
      }))
    raiseKept(L, "vdg.mesh");
  auto* h = static_cast<ObjectHandle*>(lua_newuserdatauv(L, sizeof(ObjectHandle), 0));
  h->object = object;
  luaL_setmetatable(L, "vdg.object");
  return 1;
}

// ---- nodes ----

// Everything a node call gives, read in phase 1 (trivially destructible).
struct NodeSpec {
  ObjectKind kind = ObjectKind::kGroup;
  Text name;
  int parent = -1;
  int object = -1;                                        // index into RawScene's list of its kind
  double link[10] = {0, 0, 0, 1, 0, 0, 0, 1, 1, 1};       // translation, rotation (w x y z), scale
  double placement[10] = {0, 0, 0, 1, 0, 0, 0, 1, 1, 1};  // the same
  double color[3] = {1, 1, 1};
  bool visible = true;
  double sharpness = 0, frame_offset = 0;
  double fov = 40, ortho = 0;
  int look_at = -1;
  // Part drivers (vdg.node's part_drivers = {PART = node, ...}): part names (alive while the table
  // is on the stack) and driving nodes.
  int driver_count = 0;
  Text driver_part[kMaxParts + 1];  // at most every part and the rest
  int driver_node[kMaxParts + 1] = {};
  // Camera path, slots on the stack (0: none).
  int path_points = 0, path_times = 0, path_tilt = 0;
  anim::CurveKind path_kind = anim::CurveKind::kCatmullRom;
  anim::Ease path_ease;
  double path_start = 0, path_end = 0;
  bool path_tangent = false;
  double path_center[3] = {0, 0, 0}, path_up[3] = {0, 1, 0};
};

void checked(lua_State* L, const char* why, const char* function, const char* what) {
  if (why) luaL_error(L, "%s: %s: %s", function, what, why);
}

// translation / rotation / scale of `table` into t[0..9].
void readTransform(lua_State* L, int table, const char* function, double t[10]) {
  int v = field(L, table, "translation");
  if (!lua_isnil(L, v)) checked(L, readVector(L, v, 3, t), function, "translation");
  v = field(L, table, "rotation");
  if (!lua_isnil(L, v)) checked(L, readQuaternion(L, v, t + 3), function, "rotation");
  v = field(L, table, "scale");
  if (!lua_isnil(L, v)) checked(L, readScale(L, v, t + 7), function, "scale");
}

const char* const kPathKeys[] = {"points", "times", "interpolation", "ease", "start", "end", "view",
                                 "center", "up",    "tilt",          nullptr};

void readPath(lua_State* L, int path, NodeSpec& spec) {
  const char* f = "vdg.camera";
  if (lua_type(L, path) != LUA_TTABLE) luaL_error(L, "%s: path: expected a table {points = ..., [\"end\"] = ...}", f);
  checkKeys(L, path, "vdg.camera: path", kPathKeys);
  spec.path_points = field(L, path, "points");
  const lua_Unsigned n = lua_type(L, spec.path_points) == LUA_TTABLE ? lua_rawlen(L, spec.path_points) : 0;
  if (n < 2) luaL_error(L, "%s: path.points: expected a list of at least 2 points {{x, y, z}, ...}", f);
  for (lua_Unsigned i = 1; i <= n; ++i) {
    double p[3];
    lua_rawgeti(L, spec.path_points, static_cast<lua_Integer>(i));
    if (readVector(L, lua_gettop(L), 3, p))
      luaL_error(L, "%s: path.points[%d]: expected {x, y, z} of finite numbers", f, static_cast<int>(i));
    lua_pop(L, 1);
  }
  spec.path_times = field(L, path, "times");
  if (lua_isnil(L, spec.path_times)) {
    spec.path_times = 0;
  } else {
    if (lua_type(L, spec.path_times) != LUA_TTABLE) luaL_error(L, "%s: path.times: expected a list of numbers", f);
    for (lua_Unsigned i = 1; i <= lua_rawlen(L, spec.path_times); ++i) {
      double t;
      lua_rawgeti(L, spec.path_times, static_cast<lua_Integer>(i));
      if (readNumber(L, lua_gettop(L), &t))
        luaL_error(L, "%s: path.times[%d]: expected a finite number", f, static_cast<int>(i));
      lua_pop(L, 1);
    }
  }
  int v = field(L, path, "interpolation");
  if (!lua_isnil(L, v) && (lua_type(L, v) != LUA_TSTRING || !curveKindFromName(lua_tostring(L, v), &spec.path_kind)))
    luaL_error(L,
               "%s: path.interpolation: expected linear, catmull-rom, centripetal-catmull-rom, natural-cubic, "
               "parabolic-blending or bezier",
               f);
  v = field(L, path, "ease");
  if (!lua_isnil(L, v)) checked(L, readEase(L, v, &spec.path_ease), f, "path.ease");
  v = field(L, path, "start");
  if (!lua_isnil(L, v)) checked(L, readNumber(L, v, &spec.path_start), f, "path.start");
  v = field(L, path, "end");
  if (lua_isnil(L, v)) luaL_error(L, "%s: path: [\"end\"] (the frame the camera arrives) is missing", f);
  checked(L, readNumber(L, v, &spec.path_end), f, "path[\"end\"]");
  if (!(spec.path_end > spec.path_start)) luaL_error(L, "%s: path: [\"end\"] must come after start", f);
  v = field(L, path, "view");
  if (!lua_isnil(L, v)) {
    const char* view = lua_type(L, v) == LUA_TSTRING ? lua_tostring(L, v) : "";
    if (std::strcmp(view, "tangent") == 0)
      spec.path_tangent = true;
    else if (std::strcmp(view, "center") != 0)
      luaL_error(L, "%s: path.view: expected \"center\" or \"tangent\"", f);
  }
  v = field(L, path, "center");
  if (!lua_isnil(L, v)) checked(L, readVector(L, v, 3, spec.path_center), f, "path.center");
  v = field(L, path, "up");
  if (!lua_isnil(L, v)) checked(L, readVector(L, v, 3, spec.path_up), f, "path.up");
  spec.path_tilt = field(L, path, "tilt");
  if (lua_isnil(L, spec.path_tilt)) {
    spec.path_tilt = 0;
  } else if (lua_type(L, spec.path_tilt) == LUA_TNUMBER) {
    double t;
    checked(L, readNumber(L, spec.path_tilt, &t), f, "path.tilt");
  } else if (lua_type(L, spec.path_tilt) == LUA_TTABLE && lua_rawlen(L, spec.path_tilt) >= 1) {
    for (lua_Unsigned i = 1; i <= lua_rawlen(L, spec.path_tilt); ++i) {
      double key[2];
      lua_rawgeti(L, spec.path_tilt, static_cast<lua_Integer>(i));
      if (readVector(L, lua_gettop(L), 2, key))
        luaL_error(L, "%s: path.tilt[%d]: expected {frame, degrees}", f, static_cast<int>(i));
      lua_pop(L, 1);
    }
  } else {
    luaL_error(L, "%s: path.tilt: expected degrees, or keys {{frame, degrees}, ...}", f);
  }
}

const char* const kNodeKeys[] = {"name",  "object",  "parent",    "translation",  "rotation",     "scale", "placement",
                                 "color", "visible", "sharpness", "frame_offset", "part_drivers", nullptr};
const char* const kGroupKeys[] = {"name", "parent", "translation", "rotation", "scale", "visible", nullptr};
const char* const kCameraKeys[] = {"name",  "parent", "translation", "rotation", "fov",
                                   "ortho", "path",   "look_at",     nullptr};
const char* const kPlacementKeys[] = {"translation", "rotation", "scale", nullptr};

// part_drivers = {PART = node, ...} of vdg.node on a model with parts (Scene's "Part drivers").
void readPartDrivers(lua_State* L, int table, const char* f, NodeSpec& spec) {
  Context& ctx = contextOf(L);
  const ViewDependentModel* model =
      spec.kind == ObjectKind::kModel ? ctx.scene.models[static_cast<std::size_t>(spec.object)].get() : nullptr;
  if (!model || !model->hasParts())
    luaL_error(L, "%s: part_drivers: only a view-dependent model with parts ('parts' in its manifest) has part drivers",
               f);
  if (lua_type(L, table) != LUA_TTABLE) luaL_error(L, "%s: part_drivers: expected a table {PART = node, ...}", f);
  lua_pushnil(L);
  while (lua_next(L, table)) {
    if (lua_type(L, -2) != LUA_TSTRING) luaL_error(L, "%s: part_drivers: expected part names as keys", f);
    std::size_t size = 0;
    const char* name = lua_tolstring(L, -2, &size);
    std::size_t part = 0;
    while (part < model->partCount() && model->partName(part) != std::string_view(name, size)) ++part;
    if (part == model->partCount()) {
      std::string names;
      for (std::size_t p = 0; p < model->partCount(); ++p) names += (p ? ", " : "") + model->partName(p);
      luaL_error(L, "%s: part_drivers: the model has no part '%s' (its parts: %s)", f, name, names.c_str());
    }
    const int node = checkNode(L, -1, f, "part_drivers");
    spec.driver_part[spec.driver_count] = Text{name, size};  // the key lives in the table
    spec.driver_node[spec.driver_count++] = node;
    lua_pop(L, 1);
  }
}

// Phase 1 of vdg.node / group / camera.
void readNode(lua_State* L, ObjectKind kind, const char* f, NodeSpec& spec) {
  Context& ctx = contextOf(L);
  luaL_checktype(L, 1, LUA_TTABLE);
  luaL_checkstack(L, 60, f);
  checkKeys(L, 1, f, kind == ObjectKind::kCamera ? kCameraKeys : kind == ObjectKind::kGroup ? kGroupKeys : kNodeKeys);
  if (ctx.scene.nodes.size() >= static_cast<std::size_t>(scene::kMaxSceneNodes))
    luaL_error(L, "%s: a scene holds at most %d nodes", f, scene::kMaxSceneNodes);
  spec.kind = kind;
  int v = field(L, 1, "name");
  if (!lua_isnil(L, v)) {
    if (lua_type(L, v) != LUA_TSTRING) luaL_error(L, "%s: name: expected a string", f);
    spec.name.data = lua_tolstring(L, v, &spec.name.size);
    if (spec.name.size == 0) luaL_error(L, "%s: name: must not be empty", f);
    if (std::memchr(spec.name.data, '.', spec.name.size) || std::memchr(spec.name.data, '\0', spec.name.size))
      luaL_error(L, "%s: name '%s': must not contain '.' (it separates node and field in \"node.field\")", f,
                 spec.name.data);
    if (ctx.node_by_name.find(spec.name.view()) != ctx.node_by_name.end())
      luaL_error(L, "%s: name '%s': there is already a node of that name", f, spec.name.data);
  }
  if (kind == ObjectKind::kMesh) {  // vdg.node: the kind comes from the object (none: a group)
    spec.kind = ObjectKind::kGroup;
    v = field(L, 1, "object");
    if (!lua_isnil(L, v)) {
      const ObjectHandle* h = toUserdata<ObjectHandle>(L, v, ctx.mt_object);
      if (!h) luaL_error(L, "%s: object: expected an object from vdg.load, got %s", f, luaL_typename(L, v));
      spec.kind = ctx.objects[static_cast<std::size_t>(h->object)].kind;
      spec.object = ctx.objects[static_cast<std::size_t>(h->object)].index;
    }
  }
  v = field(L, 1, "parent");
  if (!lua_isnil(L, v)) spec.parent = checkNode(L, v, f, "parent");
  readTransform(L, 1, f, spec.link);
  v = field(L, 1, "placement");
  if (!lua_isnil(L, v)) {
    if (lua_type(L, v) != LUA_TTABLE)
      luaL_error(L, "%s: placement: expected {translation = ..., rotation = ..., scale = ...}", f);
    checkKeys(L, v, "vdg.node: placement", kPlacementKeys);
    readTransform(L, v, f, spec.placement);
  }
  v = field(L, 1, "color");
  if (!lua_isnil(L, v)) checked(L, readColor(L, v, spec.color), f, "color");
  v = field(L, 1, "visible");
  if (!lua_isnil(L, v)) {
    double value;
    checked(L, readFieldValue(L, v, Field::kVisible, &value), f, "visible");
    spec.visible = value > 0.5;
  }
  v = field(L, 1, "sharpness");
  if (!lua_isnil(L, v)) {
    if (spec.kind != ObjectKind::kModel && spec.kind != ObjectKind::kAnimatedModel)
      luaL_error(L, "%s: sharpness: only view-dependent models have a sharpness", f);
    checked(L, readNumber(L, v, &spec.sharpness), f, "sharpness");
  }
  v = field(L, 1, "frame_offset");
  if (!lua_isnil(L, v)) {
    if (spec.kind != ObjectKind::kAnimatedModel)
      luaL_error(L, "%s: frame_offset: only animated models have a frame offset", f);
    checked(L, readNumber(L, v, &spec.frame_offset), f, "frame_offset");
  }
  v = field(L, 1, "part_drivers");
  if (!lua_isnil(L, v)) readPartDrivers(L, v, f, spec);
  if (kind == ObjectKind::kCamera) {
    v = field(L, 1, "fov");
    if (!lua_isnil(L, v)) checked(L, readFieldValue(L, v, Field::kFov, &spec.fov), f, "fov");
    v = field(L, 1, "ortho");
    if (!lua_isnil(L, v) && (readNumber(L, v, &spec.ortho) || spec.ortho < 0))
      luaL_error(L, "%s: ortho: expected the height of a parallel projection (> 0), or 0", f);
    v = field(L, 1, "look_at");
    if (!lua_isnil(L, v)) spec.look_at = checkNode(L, v, f, "look_at");
    v = field(L, 1, "path");
    if (!lua_isnil(L, v)) readPath(L, v, spec);
  }
  charge(L, sizeof(scene::RawNode) + 256 + 64 * static_cast<std::size_t>(spec.driver_count) +
                (spec.path_points ? 4096 + 64 * lua_rawlen(L, spec.path_points) : 0));
}

anim::Quaternion quat(const double* wxyz) { return anim::Quaternion(wxyz[0], wxyz[1], wxyz[2], wxyz[3]); }

scene::Transform transformOf(const double t[10]) {
  scene::Transform out;
  out.translation = Eigen::Vector3d(t[0], t[1], t[2]);
  out.rotation = quat(t + 3).normalized();
  out.scale = Eigen::Vector3d(t[7], t[8], t[9]);
  return out;
}

// Phase 2 for a camera path: reads the slots phase 1 checked (non-raising calls only).
anim::RawCameraPath buildPath(lua_State* L, const NodeSpec& spec) {
  anim::RawCameraPath raw;
  raw.position.kind = spec.path_kind;
  const lua_Unsigned n = lua_rawlen(L, spec.path_points);
  for (lua_Unsigned i = 1; i <= n; ++i) {
    double p[3];
    lua_rawgeti(L, spec.path_points, static_cast<lua_Integer>(i));
    (void)readVector(L, lua_gettop(L), 3, p);
    lua_pop(L, 1);
    raw.position.points.push_back(Eigen::Vector3d(p[0], p[1], p[2]));
  }
  if (spec.path_times)
    for (lua_Unsigned i = 1; i <= lua_rawlen(L, spec.path_times); ++i) {
      lua_rawgeti(L, spec.path_times, static_cast<lua_Integer>(i));
      raw.position.times.push_back(lua_tonumberx(L, -1, nullptr));
      lua_pop(L, 1);
    }
  raw.speed = spec.path_ease;
  raw.start_time = spec.path_start;
  raw.end_time = spec.path_end;
  raw.view = spec.path_tangent ? anim::ViewMode::kAlongTangent : anim::ViewMode::kCenterOfInterest;
  raw.center = Eigen::Vector3d(spec.path_center[0], spec.path_center[1], spec.path_center[2]);
  raw.up = Eigen::Vector3d(spec.path_up[0], spec.path_up[1], spec.path_up[2]);
  raw.fov_deg = spec.fov;
  raw.ortho_height = spec.ortho;
  if (spec.path_tilt) {
    anim::RawTrack tilt;
    tilt.name = "tilt";
    tilt.type = anim::TrackType::kScalar;
    if (lua_type(L, spec.path_tilt) == LUA_TNUMBER) {
      anim::RawKey key;
      key.time = spec.path_start;
      key.value = Eigen::VectorXd::Constant(1, lua_tonumberx(L, spec.path_tilt, nullptr));
      tilt.keys.push_back(std::move(key));
    } else {
      for (lua_Unsigned i = 1; i <= lua_rawlen(L, spec.path_tilt); ++i) {
        double kv[2];
        lua_rawgeti(L, spec.path_tilt, static_cast<lua_Integer>(i));
        (void)readVector(L, lua_gettop(L), 2, kv);
        lua_pop(L, 1);
        anim::RawKey key;
        key.time = kv[0];
        key.value = Eigen::VectorXd::Constant(1, kv[1]);
        tilt.keys.push_back(std::move(key));
      }
    }
    raw.tilt_deg = std::move(tilt);
  }
  return raw;
}

int makeNode(lua_State* L, ObjectKind kind, const char* f) {
  refuseWhileActing(L, f);
  NodeSpec spec;
  readNode(L, kind, f, spec);
  Context& ctx = contextOf(L);
  int index = -1;
  if (!guarded(ctx, [&] {
        scene::RawNode node;
        if (spec.name.data) {
          node.name.assign(spec.name.data, spec.name.size);
        } else {
          const char* stem = spec.kind == ObjectKind::kCamera  ? "camera"
                             : spec.kind == ObjectKind::kGroup ? "group"
                                                               : "node";
          do node.name = stem + std::to_string(ctx.next_auto_name++);
          while (ctx.node_by_name.count(node.name));
        }
        node.parent = spec.parent;
        node.kind = spec.kind;
        node.object = spec.object;
        node.placement = transformOf(spec.placement);
        node.link = transformOf(spec.link);
        for (int i = 0; i < 3; ++i) node.color[i] = static_cast<float>(spec.color[i]);
        node.visible = spec.visible;
        node.sharpness = spec.sharpness;
        node.frame_offset = spec.frame_offset;
        node.fov_deg = spec.fov;
        node.ortho_height = spec.ortho;
        if (spec.look_at >= 0) node.look_at = ctx.scene.nodes[static_cast<std::size_t>(spec.look_at)].name;
        for (int d = 0; d < spec.driver_count; ++d)
          node.part_drivers.push_back({std::string(spec.driver_part[d].view()),
                                       ctx.scene.nodes[static_cast<std::size_t>(spec.driver_node[d])].name});
        if (spec.path_points) {
          node.path = buildPath(L, spec);
          (void)anim::CameraPath::build(*node.path, "path");  // its errors now, with the script line
        }
        index = static_cast<int>(ctx.scene.nodes.size());
        ctx.node_by_name.emplace(node.name, index);
        ctx.driven.emplace_back();
        ctx.scene.nodes.push_back(std::move(node));
      }))
    raiseKept(L, f);
  pushNode(L, index);
  return 1;
}

// vdg.node{...}: a node with an object (or none: a group).
int luaNode(lua_State* L) { return makeNode(L, ObjectKind::kMesh, "vdg.node"); }
int luaGroup(lua_State* L) { return makeNode(L, ObjectKind::kGroup, "vdg.group"); }
int luaCamera(lua_State* L) { return makeNode(L, ObjectKind::kCamera, "vdg.camera"); }

// vdg.use_camera(camera): the active camera.
int useCamera(lua_State* L) {
  refuseWhileActing(L, "vdg.use_camera");
  Context& ctx = contextOf(L);
  const int n = checkNode(L, 1, "vdg.use_camera", "argument #1");
  if (ctx.scene.nodes[static_cast<std::size_t>(n)].kind != ObjectKind::kCamera)
    luaL_error(L, "vdg.use_camera: node '%s' is not a camera",
               ctx.scene.nodes[static_cast<std::size_t>(n)].name.c_str());
  if (!guarded(ctx, [&] { ctx.scene.camera = ctx.scene.nodes[static_cast<std::size_t>(n)].name; }))
    raiseKept(L, "vdg.use_camera");
  return 0;
}

// ---- set / change / track ----

Field checkField(lua_State* L, int idx, const char* f) {
  const char* name = luaL_checkstring(L, idx);
  for (int i = 0; i < scene::kFieldCount; ++i)
    if (std::strcmp(name, scene::fieldName(static_cast<Field>(i))) == 0) return static_cast<Field>(i);
  luaL_error(
      L,
      "%s: unknown field '%s' (expected translation, rotation, scale, color, visible, sharpness, frame_offset or fov)",
      f, name);
  return Field::kTranslation;
}

// The nodes of argument `idx` (a node or a list of nodes), each checked for `field`; returns the
// count. `state` is what the field must not already be driven by (2: a track) plus what it
// becomes.
int checkTargets(lua_State* L, int idx, Field field, const char* f, bool track) {
  refuseWhileActing(L, f);  // set, change and track describe the scene
  Context& ctx = contextOf(L);
  auto check = [&](int node) {
    const scene::RawNode& n = ctx.scene.nodes[static_cast<std::size_t>(node)];
    if (!scene::hasField(n.kind, field))
      luaL_error(L, "%s: node '%s' (a %s) has no field '%s'", f, n.name.c_str(), scene::objectKindName(n.kind),
                 scene::fieldName(field));
    const int driven = ctx.driven[static_cast<std::size_t>(node)][static_cast<std::size_t>(field)];
    if (driven == 2)
      luaL_error(L, "%s: %s.%s already has a track (a field has a track or set/change actions, not both)", f,
                 n.name.c_str(), scene::fieldName(field));
    if (track && driven == 1)
      luaL_error(L, "%s: %s.%s already has set/change actions (a field has a track or set/change actions, not both)", f,
                 n.name.c_str(), scene::fieldName(field));
  };
  if (lua_type(L, idx) == LUA_TTABLE) {
    const int n = static_cast<int>(lua_rawlen(L, idx));
    for (int i = 1; i <= n; ++i) {
      lua_rawgeti(L, idx, i);
      const NodeHandle* h = toUserdata<NodeHandle>(L, lua_gettop(L), ctx.mt_node);
      if (!h) luaL_error(L, "%s: object set element %d: expected a node, got %s", f, i, luaL_typename(L, -1));
      check(h->node);
      lua_pop(L, 1);
    }
    return n;
  }
  check(checkNode(L, idx, f, "argument #1"));
  return 1;
}

// The i-th target (1-based) of argument idx (phase 2, non-raising).
int target(lua_State* L, int idx, int i) {
  if (lua_type(L, idx) != LUA_TTABLE) return static_cast<NodeHandle*>(lua_touserdata(L, idx))->node;
  lua_rawgeti(L, idx, i);
  const int node = static_cast<NodeHandle*>(lua_touserdata(L, -1))->node;
  lua_pop(L, 1);
  return node;
}

int addActions(lua_State* L, scene::RawAction::Kind kind) {
  const bool set = kind == scene::RawAction::Kind::kSet;
  const char* f = set ? "vdg.set" : "vdg.change";
  luaL_checkstack(L, 8, f);
  const Field field_id = checkField(L, 2, f);
  const int count = checkTargets(L, 1, field_id, f, false);
  double value[4];
  checked(L, set ? readFieldValue(L, 3, field_id, value) : readFieldDelta(L, 3, field_id, value), f,
          set ? "value" : "delta");
  double from = 0, to = 0;
  anim::Ease ease;
  if (set) {
    if (!lua_isnoneornil(L, 4)) checked(L, readNumber(L, 4, &from), f, "frame");
    to = from;
  } else {
    checked(L, readNumber(L, 4, &from), f, "from frame");
    checked(L, readNumber(L, 5, &to), f, "to frame");
    if (to < from) luaL_error(L, "%s: the to frame (%f) comes before the from frame (%f)", f, to, from);
    if (!lua_isnoneornil(L, 6)) checked(L, readEase(L, 6, &ease), f, "ease");
  }
  Context& ctx = contextOf(L);
  if (ctx.scene.actions.size() + static_cast<std::size_t>(count) > static_cast<std::size_t>(scene::kMaxSceneActions))
    luaL_error(L, "%s: a scene holds at most %d set/change actions", f, scene::kMaxSceneActions);
  charge(L, static_cast<std::size_t>(count) * (sizeof(scene::RawAction) + 64));
  if (!guarded(ctx, [&] {
        for (int i = 1; i <= count; ++i) {
          scene::RawAction action;
          action.kind = kind;
          action.node = target(L, 1, i);
          action.field = field_id;
          action.value = Eigen::Map<const Eigen::VectorXd>(value, scene::fieldDimension(field_id));
          action.from_frame = from;
          action.to_frame = to;
          action.ease = ease;
          ctx.driven[static_cast<std::size_t>(action.node)][static_cast<std::size_t>(field_id)] = 1;
          ctx.scene.actions.push_back(std::move(action));
        }
      }))
    raiseKept(L, f);
  return 0;
}

// vdg.set(obj_or_set, field, value [, frame = 0]): SET (Parent 4.6): from `frame` on, the field is value.
int luaSet(lua_State* L) { return addActions(L, scene::RawAction::Kind::kSet); }
// vdg.change(obj_or_set, field, delta, from, to [, ease]): CHANGE (Parent 4.6): adds delta spread
// over [from, to] by the ease.
int luaChange(lua_State* L) { return addActions(L, scene::RawAction::Kind::kChange); }

const anim::Interpolation kInterpolations[] = {
    anim::Interpolation::kStep,           anim::Interpolation::kLinear,
    anim::Interpolation::kCatmullRom,     anim::Interpolation::kCentripetalCatmullRom,
    anim::Interpolation::kNaturalCubic,   anim::Interpolation::kParabolicBlending,
    anim::Interpolation::kBezier,         anim::Interpolation::kSlerp,
    anim::Interpolation::kQuaternionCurve};

const char* const kKeyKeys[] = {"ease", "in", "out", nullptr};

// vdg.track(obj_or_set, field, keys, interpolation [, extrapolation]) with keys
// {{frame, value [, ease = e] [, ["in"] = handle, out = handle]}, ...} (Parent 4.9).
int luaTrack(lua_State* L) {
  const char* f = "vdg.track";
  luaL_checkstack(L, 24, f);
  const Field field_id = checkField(L, 2, f);
  const int count = checkTargets(L, 1, field_id, f, true);
  const int dimension = scene::fieldDimension(field_id);
  luaL_checktype(L, 3, LUA_TTABLE);
  anim::Interpolation interpolation =
      field_id == Field::kRotation ? anim::Interpolation::kSlerp : anim::Interpolation::kLinear;
  if (!lua_isnoneornil(L, 4)) {
    const char* name = luaL_checkstring(L, 4);
    bool found = false;
    for (anim::Interpolation i : kInterpolations)
      if (std::strcmp(name, anim::interpolationName(i)) == 0) interpolation = i, found = true;
    if (!found)
      luaL_error(
          L,
          "%s: unknown interpolation '%s' (expected step, linear, catmull-rom, centripetal-catmull-rom, natural-cubic, "
          "parabolic-blending, bezier, slerp or quaternion-curve)",
          f, name);
  }
  anim::Extrapolation extrapolation = anim::Extrapolation::kClamp;
  if (!lua_isnoneornil(L, 5)) {
    const char* name = luaL_checkstring(L, 5);
    if (std::strcmp(name, "loop") == 0)
      extrapolation = anim::Extrapolation::kLoop;
    else if (std::strcmp(name, "clamp") != 0)
      luaL_error(L, "%s: unknown extrapolation '%s' (expected clamp or loop)", f, name);
  }
  lua_settop(L, 5);
  // The keys' field names, pushed once so that phase 2 can look them up without allocating.
  lua_pushliteral(L, "ease");  // 6
  lua_pushliteral(L, "in");    // 7
  lua_pushliteral(L, "out");   // 8
  const int n = static_cast<int>(lua_rawlen(L, 3));
  if (n < 1) luaL_error(L, "%s: keys: expected a list of keys {{frame, value}, ...}", f);
  for (int i = 1; i <= n; ++i) {
    lua_rawgeti(L, 3, i);
    const int key = lua_gettop(L);
    double time, value[4];
    if (lua_type(L, key) != LUA_TTABLE || lua_rawlen(L, key) != 2)
      luaL_error(L, "%s: keys[%d]: expected {frame, value [, ease = ...]}", f, i);
    checkKeys(L, key, "vdg.track: key", kKeyKeys, true);
    lua_rawgeti(L, key, 1);
    if (readNumber(L, lua_gettop(L), &time)) luaL_error(L, "%s: keys[%d]: the frame must be a finite number", f, i);
    lua_rawgeti(L, key, 2);
    if (const char* why = readFieldValue(L, lua_gettop(L), field_id, value))
      luaL_error(L, "%s: keys[%d]: value: %s", f, i, why);
    lua_pushvalue(L, 6);
    if (lua_rawget(L, key) != LUA_TNIL) {
      anim::Ease e;
      if (const char* why = readEase(L, lua_gettop(L), &e)) luaL_error(L, "%s: keys[%d]: ease: %s", f, i, why);
    }
    for (int h = 7; h <= 8; ++h) {
      lua_pushvalue(L, h);
      if (lua_rawget(L, key) != LUA_TNIL) {
        double handle[4];
        if (interpolation != anim::Interpolation::kBezier)
          luaL_error(L, "%s: keys[%d]: handles (in, out) need the bezier interpolation", f, i);
        if (const char* why = readVector(L, lua_gettop(L), dimension, handle))
          luaL_error(L, "%s: keys[%d]: handle: %s", f, i, why);
      }
    }
    lua_settop(L, 8);
  }
  Context& ctx = contextOf(L);
  charge(L, static_cast<std::size_t>(count) * (static_cast<std::size_t>(n) * (sizeof(anim::RawKey) + 96) + 512));
  if (!guarded(ctx, [&] {
        anim::RawTrack raw;
        raw.type = field_id == Field::kRotation ? anim::TrackType::kRotation
                   : dimension == 1             ? anim::TrackType::kScalar
                                                : anim::TrackType::kVector;
        raw.interpolation = interpolation;
        raw.extrapolation = extrapolation;
        for (int i = 1; i <= n; ++i) {
          lua_rawgeti(L, 3, i);
          const int key = lua_gettop(L);
          anim::RawKey k;
          double value[4];
          lua_rawgeti(L, key, 1);
          k.time = lua_tonumberx(L, -1, nullptr);
          lua_rawgeti(L, key, 2);
          (void)readFieldValue(L, lua_gettop(L), field_id, value);
          k.value = Eigen::Map<const Eigen::VectorXd>(value, dimension);
          lua_pushvalue(L, 6);
          if (lua_rawget(L, key) != LUA_TNIL) {
            anim::Ease e;
            (void)readEase(L, lua_gettop(L), &e);
            k.ease = e;
          }
          for (int h = 7; h <= 8; ++h) {
            lua_pushvalue(L, h);
            if (lua_rawget(L, key) != LUA_TNIL) {
              double handle[4];
              (void)readVector(L, lua_gettop(L), dimension, handle);
              Eigen::VectorXd v = Eigen::Map<const Eigen::VectorXd>(handle, dimension);
              if (h == 7)
                k.in_handle.emplace(std::move(v));
              else
                k.out_handle.emplace(std::move(v));
            }
          }
          lua_settop(L, 8);
          raw.keys.push_back(std::move(k));
        }
        for (int i = 1; i <= count; ++i) {
          const int node = target(L, 1, i);
          raw.name = ctx.scene.nodes[static_cast<std::size_t>(node)].name + "." + scene::fieldName(field_id);
          (void)anim::Track::build(raw, "vdg.track");  // its errors now, with the script line
          scene::RawFieldTrack t;
          t.node = node;
          t.field = field_id;
          t.track = raw;
          ctx.scene.tracks.push_back(std::move(t));
          ctx.driven[static_cast<std::size_t>(node)][static_cast<std::size_t>(field_id)] = 2;
        }
      }))
    raiseKept(L, f);
  return 0;
}

// vdg.for_each(set, fn): fn(node, index) for each node of the set, in order (FOR EACH, Parent 4.6).
int forEach(lua_State* L) {
  Context& ctx = contextOf(L);
  luaL_checktype(L, 1, LUA_TTABLE);
  luaL_checktype(L, 2, LUA_TFUNCTION);
  const int n = static_cast<int>(lua_rawlen(L, 1));
  for (int i = 1; i <= n; ++i) {
    lua_rawgeti(L, 1, i);
    if (!toUserdata<NodeHandle>(L, lua_gettop(L), ctx.mt_node))
      luaL_error(L, "vdg.for_each: object set element %d: expected a node, got %s", i, luaL_typename(L, -1));
    lua_pop(L, 1);
  }
  for (int i = 1; i <= n; ++i) {
    lua_pushvalue(L, 2);
    lua_rawgeti(L, 1, i);
    lua_pushinteger(L, i);
    lua_call(L, 2, 0);
  }
  return 0;
}

// ---- render ----

int checkInteger(lua_State* L, int idx, const char* f, const char* what, lua_Integer low, lua_Integer high) {
  int ok = 0;
  const lua_Integer v = lua_tointegerx(L, idx, &ok);
  if (!ok || lua_type(L, idx) != LUA_TNUMBER || v < low || v > high)
    luaL_error(L, "%s: %s: expected a whole number in [%I, %I]", f, what, low, high);
  return static_cast<int>(v);
}

const char* const kRenderKeys[] = {"frames", "size", "out", "samples", "background", "silhouette", "creases", nullptr};

// vdg.render{frames = {a, b} | "a-b" | a, size = {w, h}, out = "dir", samples =, background =,
// silhouette =, creases =}.
int luaRender(lua_State* L) {
  refuseWhileActing(L, "vdg.render");
  const char* f = "vdg.render";
  luaL_checktype(L, 1, LUA_TTABLE);
  luaL_checkstack(L, 30, f);
  checkKeys(L, 1, f, kRenderKeys);
  RenderRequest defaults;
  int first = defaults.first_frame, last = defaults.last_frame, width = defaults.width, height = defaults.height;
  int samples = defaults.samples;
  double background[3] = {defaults.background[0], defaults.background[1], defaults.background[2]};
  double silhouette = 0, creases = 0;
  constexpr lua_Integer kMaxFrame = 1000000000;
  int v = field(L, 1, "frames");
  if (lua_type(L, v) == LUA_TNUMBER) {
    first = last = checkInteger(L, v, f, "frames", 0, kMaxFrame);
  } else if (lua_type(L, v) == LUA_TTABLE) {
    if (lua_rawlen(L, v) != 2) luaL_error(L, "%s: frames: expected {first, last}", f);
    lua_rawgeti(L, v, 1);
    first = checkInteger(L, lua_gettop(L), f, "frames[1]", 0, kMaxFrame);
    lua_rawgeti(L, v, 2);
    last = checkInteger(L, lua_gettop(L), f, "frames[2]", 0, kMaxFrame);
  } else if (lua_type(L, v) == LUA_TSTRING) {
    const char* s = lua_tostring(L, v);
    char* end = nullptr;
    const long a = std::strtol(s, &end, 10);
    const bool dash = end != s && *end == '-' && end[1] >= '0' && end[1] <= '9';
    const long b = dash ? std::strtol(end + 1, &end, 10) : -1;
    if (!dash || *end != '\0' || s[0] < '0' || s[0] > '9' || a > kMaxFrame || b > kMaxFrame)
      luaL_error(L, "%s: frames: expected \"first-last\" (e.g. \"1-48\"), got \"%s\"", f, s);
    first = static_cast<int>(a), last = static_cast<int>(b);
  } else if (!lua_isnil(L, v)) {
    luaL_error(L, "%s: frames: expected {first, last}, \"first-last\" or a frame number", f);
  }
  if (last < first) luaL_error(L, "%s: frames: the last frame (%d) comes before the first (%d)", f, last, first);
  if (last - first >= kMaxRenderFrames) luaL_error(L, "%s: frames: at most %d frames per render", f, kMaxRenderFrames);
  v = field(L, 1, "size");
  if (!lua_isnil(L, v)) {
    if (lua_type(L, v) != LUA_TTABLE || lua_rawlen(L, v) != 2) luaL_error(L, "%s: size: expected {width, height}", f);
    lua_rawgeti(L, v, 1);
    width = checkInteger(L, lua_gettop(L), f, "size[1] (width)", 1, kMaxImageSide);
    lua_rawgeti(L, v, 2);
    height = checkInteger(L, lua_gettop(L), f, "size[2] (height)", 1, kMaxImageSide);
  }
  v = field(L, 1, "samples");
  if (!lua_isnil(L, v)) samples = checkInteger(L, v, f, "samples", 1, kMaxSamples);
  v = field(L, 1, "background");
  if (!lua_isnil(L, v)) checked(L, readColor(L, v, background), f, "background");
  v = field(L, 1, "silhouette");
  if (!lua_isnil(L, v) && (readNumber(L, v, &silhouette) || silhouette < 0 || silhouette > 1000))
    luaL_error(L, "%s: silhouette: expected a line width in pixels in [0, 1000] (0: automatic)", f);
  v = field(L, 1, "creases");
  if (!lua_isnil(L, v) && (readNumber(L, v, &creases) || creases < 0 || creases > 180))
    luaL_error(L, "%s: creases: expected a crease angle in [0, 180] degrees", f);
  const int out = field(L, 1, "out");
  Text out_text{".", 1};
  if (!lua_isnil(L, out)) {
    if (lua_type(L, out) != LUA_TSTRING)
      luaL_error(L, "%s: out: expected a folder name (relative to the output folder)", f);
    out_text.data = lua_tolstring(L, out, &out_text.size);
  }
  const int line = scriptLine(L);
  Context& ctx = contextOf(L);
  if (ctx.renders.size() >= 10000) luaL_error(L, "%s: at most 10000 render calls", f);
  if (!guarded(ctx, [&] {
        (void)confinedPath(ctx.output_dir, out_text.view(), "out");
        RenderRequest r;
        r.first_frame = first, r.last_frame = last, r.width = width, r.height = height, r.samples = samples;
        r.out = std::filesystem::path(std::string(out_text.view())).lexically_normal().string();
        if (r.out.size() > 1 && r.out.back() == '/') r.out.pop_back();
        checkOwnFolder(ctx, r.out);
        for (int i = 0; i < 3; ++i) r.background[i] = static_cast<float>(background[i]);
        r.silhouette_width = static_cast<float>(silhouette);
        r.crease_angle_deg = static_cast<float>(creases);
        r.line = line;
        ctx.renders.push_back(std::move(r));
      }))
    raiseKept(L, f);
  return 0;
}

// ---- handles ----

int nodeIndex(lua_State* L) {
  Context& ctx = contextOf(L);
  const int n = checkNode(L, 1, "node", "self");
  const char* key = luaL_checkstring(L, 2);
  const scene::RawNode& node = ctx.scene.nodes[static_cast<std::size_t>(n)];
  if (std::strcmp(key, "name") == 0) {
    lua_pushlstring(L, node.name.data(), node.name.size());
  } else if (std::strcmp(key, "kind") == 0) {
    lua_pushstring(L, scene::objectKindName(node.kind));
  } else {
    return luaL_error(
        L, "node '%s': no field '%s' (nodes have name and kind; animate fields with vdg.set, vdg.change, vdg.track)",
        node.name.c_str(), key);
  }
  return 1;
}

int nodeToString(lua_State* L) {
  Context& ctx = contextOf(L);
  const int n = checkNode(L, 1, "tostring", "argument #1");
  const scene::RawNode& node = ctx.scene.nodes[static_cast<std::size_t>(n)];
  lua_pushfstring(L, "%s '%s'", scene::objectKindName(node.kind), node.name.c_str());
  return 1;
}

const ObjectRef& checkObject(lua_State* L) {
  Context& ctx = contextOf(L);
  const ObjectHandle* h = toUserdata<ObjectHandle>(L, 1, ctx.mt_object);
  if (!h) luaL_error(L, "expected an object from vdg.load");
  return ctx.objects[static_cast<std::size_t>(h->object)];
}

int objectIndex(lua_State* L) {
  const ObjectRef& ref = checkObject(L);
  const char* key = luaL_checkstring(L, 2);
  if (std::strcmp(key, "kind") == 0) {
    lua_pushstring(L, scene::objectKindName(ref.kind));
  } else if (std::strcmp(key, "path") == 0) {
    lua_pushlstring(L, ref.path.data(), ref.path.size());
  } else {
    return luaL_error(L, "object '%s': no field '%s' (objects have kind and path)", ref.path.c_str(), key);
  }
  return 1;
}

int objectToString(lua_State* L) {
  const ObjectRef& ref = checkObject(L);
  lua_pushfstring(L, "%s '%s'", scene::objectKindName(ref.kind), ref.path.c_str());
  return 1;
}

}  // namespace

void openScene(lua_State* L, int vdg) {
  Context& ctx = contextOf(L);
  const luaL_Reg functions[] = {{"load", luaLoad},     {"mesh", luaMesh},     {"node", luaNode},
                                {"group", luaGroup},   {"camera", luaCamera}, {"use_camera", useCamera},
                                {"set", luaSet},       {"change", luaChange}, {"track", luaTrack},
                                {"for_each", forEach}, {"render", luaRender}, {nullptr, nullptr}};
  lua_pushvalue(L, vdg);
  luaL_setfuncs(L, functions, 0);
  lua_pop(L, 1);
  const luaL_Reg node_meta[] = {{"__index", nodeIndex}, {"__tostring", nodeToString}, {nullptr, nullptr}};
  ctx.mt_node = lockedMetatable(L, "vdg.node", node_meta);
  const luaL_Reg object_meta[] = {{"__index", objectIndex}, {"__tostring", objectToString}, {nullptr, nullptr}};
  ctx.mt_object = lockedMetatable(L, "vdg.object", object_meta);
}

}  // namespace vdg::script::detail
