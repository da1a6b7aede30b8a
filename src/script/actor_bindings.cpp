// Actors (Parent, Computer Animation, section 4.8: the animation languages after the scripted ones,
// Hewitt's actors and message passing as taken up by ASAS): objects with their own state that
// update themselves every frame and answer messages, so that animation can be conditional and
// reactive ("if the ball is near the wall, bounce").
//
//   vdg.actor{...} (while the script runs) --> records: C++ (Context::actors) + Lua (registry)
//   runActors (after the script): for each frame from the shot's first, in frame order:
//     1. every actor's inbox takes the messages sent before this frame (during the last frame,
//        or by the script);
//     2. each actor in the order defined: receive(self, message, sender) for each of its
//        messages in the order they were sent, then update(self, frame);
//     3. each field an actor set gets a key at this frame when its value changed.
//   The keys become step tracks of the scene: the Shot stays plain data, and a frame's values
//   depend only on the frames before it, so any frame range renders what a full run renders.
// See context.h for the phase rules every C function here follows.
#include <algorithm>
#include <cstring>

#include "context.h"

namespace vdg::script::detail {
namespace {

using scene::Field;

constexpr const char* kActorsKey = "vdg.actors";  // registry: the records, actor i at i + 1

// A record's slots (a Lua table per actor).
enum Slot { kHandle = 1, kState, kUpdate, kReceive, kNext, kInbox };

struct ActorHandle {
  int actor = -1;
};
static_assert(std::is_trivially_destructible_v<ActorHandle>);

const char* const kActorKeys[] = {"name", "node", "drives", "state", "update", "receive", nullptr};
const char* const kNoKeys[] = {nullptr};

// The actor of handle `idx` (phase 1; raises naming `function`).
int checkActor(lua_State* L, int idx, const char* function, const char* what) {
  const ActorHandle* h = toUserdata<ActorHandle>(L, idx, contextOf(L).mt_actor);
  if (!h)
    luaL_error(L, "%s: %s: expected an actor (what vdg.actor returns), got %s", function, what, luaL_typename(L, idx));
  return h->actor;
}

const char* actorName(lua_State* L, int actor) {
  return contextOf(L).actors[static_cast<std::size_t>(actor)].name.c_str();
}

// Pushes the record of `actor` (the registry list at `list`).
void pushRecord(lua_State* L, int list, int actor) { lua_rawgeti(L, list, actor + 1); }

// A field name at `idx` (phase 1).
Field checkFieldName(lua_State* L, int idx, const char* actor, const char* function) {
  const char* name = lua_type(L, idx) == LUA_TSTRING ? lua_tostring(L, idx) : nullptr;
  const std::optional<Field> field = name ? scene::fieldFromName(name) : std::nullopt;
  if (!field)
    luaL_error(L,
               "actor '%s': %s: expected a field name (translation, rotation, scale, color, visible, sharpness, "
               "frame_offset or fov), got %s",
               actor, function, name ? name : luaL_typename(L, idx));
  return *field;
}

// Checks that the actors run and that `node` has `field` (phase 1); `label` names the caller.
void checkReadable(lua_State* L, int node, Field field, const char* label) {
  const Context& ctx = contextOf(L);
  if (!ctx.acting || !ctx.stage)
    luaL_error(L, "%s: only while the actors run (in their update and receive functions)", label);
  const scene::RawNode& n = ctx.scene.nodes[static_cast<std::size_t>(node)];
  if (!scene::hasField(n.kind, field))
    luaL_error(L, "%s: node '%s' (a %s) has no field '%s'", label, n.name.c_str(), scene::objectKindName(n.kind),
               scene::fieldName(field));
}

// Pushes `field` of `node` at the current frame: the value an actor set, or the scene's (its
// initial value, track or actions). Phase 1 (checked by checkReadable).
void pushField(lua_State* L, int node, Field field) {
  const Context& ctx = contextOf(L);
  double value[4] = {0, 0, 0, 0};
  const int dim = scene::fieldDimension(field);
  const int channel = ctx.channel_of_node[static_cast<std::size_t>(node)][static_cast<std::size_t>(field)];
  if (channel >= 0) {
    std::copy_n(ctx.channels[static_cast<std::size_t>(channel)].current, dim, value);
  } else if (!ctx.stage->fieldValue(node, field, ctx.frame, std::span<double>(value, static_cast<std::size_t>(dim)))) {
    luaL_error(L, "get: node '%s': field '%s' cannot be evaluated",
               ctx.scene.nodes[static_cast<std::size_t>(node)].name.c_str(), scene::fieldName(field));
  }
  if (field == Field::kRotation) {
    pushQuat(L, value);
  } else if (field == Field::kVisible) {
    lua_pushboolean(L, value[0] > 0.5);
  } else if (dim == 1) {
    lua_pushnumber(L, value[0]);
  } else {
    pushNumbers(L, value, dim);
  }
}

// ---- vdg.actor{...} ----

// The optional function at `idx` (phase 1).
void checkFunction(lua_State* L, int idx, const char* label, const char* key, const char* signature) {
  if (!lua_isnil(L, idx) && lua_type(L, idx) != LUA_TFUNCTION)
    luaL_error(L, "%s: %s: expected a function%s, got %s", label, key, signature, luaL_typename(L, idx));
}

// A node an actor drives (-1: none), checked (phase 1); `what` names the key.
int checkActorNode(lua_State* L, int idx, const char* label, const char* what) {
  if (lua_isnil(L, idx)) return -1;
  const Context& ctx = contextOf(L);
  const NodeHandle* h = toUserdata<NodeHandle>(L, idx, ctx.mt_node);
  if (!h)
    luaL_error(L, "%s: %s: expected a node (vdg.node, vdg.group, vdg.camera), got %s", label, what,
               luaL_typename(L, idx));
  const auto n = static_cast<std::size_t>(h->node);
  if (n < ctx.actor_of_node.size() && ctx.actor_of_node[n] >= 0)
    luaL_error(L, "%s: %s: node '%s' is already driven by actor '%s' (one actor per node: send it messages instead)",
               label, what, ctx.scene.nodes[n].name.c_str(), actorName(L, ctx.actor_of_node[n]));
  return h->node;
}

// vdg.actor's drives = {node, ...}: checked (phase 1), the count returned. Each node once, none the
// actor's own node or another actor's.
int checkDrives(lua_State* L, int idx, int node, const char* label) {
  if (lua_isnil(L, idx)) return 0;
  if (lua_type(L, idx) != LUA_TTABLE)
    luaL_error(L, "%s: drives: expected a list of nodes, got %s", label, luaL_typename(L, idx));
  checkKeys(L, idx, label, kNoKeys, true);
  const int count = static_cast<int>(lua_rawlen(L, idx));
  for (int i = 1; i <= count; ++i) {
    lua_rawgeti(L, idx, i);
    const int value = lua_gettop(L);
    const char* what = lua_pushfstring(L, "drives[%d]", i);
    const int n = checkActorNode(L, value, label, what);
    if (n < 0) luaL_error(L, "%s: %s: expected a node, got nil", label, what);
    lua_pop(L, 2);
    bool repeated = n == node;
    for (int j = 1; j < i && !repeated; ++j) {
      lua_rawgeti(L, idx, j);
      repeated = static_cast<NodeHandle*>(lua_touserdata(L, -1))->node == n;
      lua_pop(L, 1);
    }
    if (repeated)
      luaL_error(L, "%s: drives[%d]: node '%s' is given twice", label, i,
                 contextOf(L).scene.nodes[static_cast<std::size_t>(n)].name.c_str());
  }
  return count;
}

// vdg.actor{name =, node =, drives =, state =, update = function(self, frame), receive = function(self,
// message, sender)} -> actor handle.
int luaActor(lua_State* L) {
  refuseWhileActing(L, "vdg.actor");
  luaL_checkstack(L, 16, "vdg.actor");
  if (lua_type(L, 1) != LUA_TTABLE)
    return luaL_error(L, "vdg.actor: expected a table {name = ..., update = function(self, frame) ... end}, got %s",
                      luaL_typename(L, 1));
  lua_settop(L, 1);
  Context& ctx = contextOf(L);
  // The name first: every later message names the actor.
  const int name_idx = field(L, 1, "name");  // 2
  if (lua_isnil(L, name_idx)) {
    lua_pop(L, 1);
    lua_pushfstring(L, "actor%d", static_cast<int>(ctx.actors.size()) + 1);
  } else if (lua_type(L, name_idx) != LUA_TSTRING || lua_rawlen(L, name_idx) == 0) {
    return luaL_error(L, "vdg.actor: name: expected a non-empty string, got %s", luaL_typename(L, name_idx));
  }
  const char* name = lua_tostring(L, 2);
  if (std::strlen(name) != lua_rawlen(L, 2)) return luaL_error(L, "vdg.actor: name: a name has no NUL character");
  const char* label = lua_pushfstring(L, "vdg.actor '%s'", name);  // 3
  checkKeys(L, 1, label, kActorKeys);
  if (ctx.actor_by_name.find(std::string_view(name)) != ctx.actor_by_name.end())
    return luaL_error(L, "%s: name: an actor named '%s' already exists", label, name);
  const int node = checkActorNode(L, field(L, 1, "node"), label, "node");  // 4
  const int drives = field(L, 1, "drives");                                // 5
  const int drive_count = checkDrives(L, drives, node, label);
  const int state = field(L, 1, "state");  // 6
  if (lua_isnil(L, state)) {
    lua_newtable(L);
    lua_replace(L, state);
  } else if (lua_type(L, state) != LUA_TTABLE) {
    return luaL_error(L, "%s: state: expected a table, got %s", label, luaL_typename(L, state));
  }
  const int update = field(L, 1, "update");  // 7
  checkFunction(L, update, label, "update", " (self, frame)");
  const int receive = field(L, 1, "receive");  // 8
  checkFunction(L, receive, label, "receive", " (self, message, sender)");
  if (lua_isnil(L, update) && lua_isnil(L, receive))
    return luaL_error(L, "%s: expected an update or a receive function (an actor with neither does nothing)", label);
  const std::size_t nodes = ctx.scene.nodes.size(), known = ctx.actor_of_node.size();
  charge(L, sizeof(Context::Actor) + 2 * lua_rawlen(L, 2) + 128 + sizeof(int) * (nodes > known ? nodes - known : 0));

  // The record, and its slot in the registry list (allocated now, so that filling it later cannot fail).
  const int actor = static_cast<int>(ctx.actors.size());
  lua_createtable(L, kInbox, 0);
  const int record = lua_gettop(L);
  auto* handle = static_cast<ActorHandle*>(lua_newuserdatauv(L, sizeof(ActorHandle), 0));
  handle->actor = actor;
  luaL_setmetatable(L, "vdg.actor");
  lua_pushvalue(L, -1);
  lua_rawseti(L, record, kHandle);  // the handle stays on top: the result
  lua_pushvalue(L, state);
  lua_rawseti(L, record, kState);
  lua_pushvalue(L, update);
  lua_rawseti(L, record, kUpdate);
  lua_pushvalue(L, receive);
  lua_rawseti(L, record, kReceive);
  lua_newtable(L);
  lua_rawseti(L, record, kNext);
  lua_getfield(L, LUA_REGISTRYINDEX, kActorsKey);
  const int list = lua_gettop(L);
  lua_pushboolean(L, 0);
  lua_rawseti(L, list, actor + 1);
  const bool receives = !lua_isnil(L, receive);
  if (!guarded(ctx, [&] {
        Context::Actor a;
        a.name = name;
        a.node = node;
        a.receives = receives;
        ctx.actors.reserve(ctx.actors.size() + 1);
        if (ctx.actor_of_node.size() < ctx.scene.nodes.size()) ctx.actor_of_node.resize(ctx.scene.nodes.size(), -1);
        ctx.actor_by_name.emplace(a.name, actor);
        ctx.actors.push_back(std::move(a));
        if (node >= 0) ctx.actor_of_node[static_cast<std::size_t>(node)] = actor;
      }))
    raiseKept(L, "vdg.actor");
  for (int i = 1; i <= drive_count; ++i) {  // actor_of_node holds every node now: no allocation
    lua_rawgeti(L, drives, i);
    ctx.actor_of_node[static_cast<std::size_t>(static_cast<NodeHandle*>(lua_touserdata(L, -1))->node)] = actor;
    lua_pop(L, 1);
  }
  lua_pushvalue(L, record);
  lua_rawseti(L, list, actor + 1);  // replaces the slot: no allocation
  lua_pop(L, 1);
  return 1;
}

// ---- the handle: self.name, self.node, self.state, self.frame, self:set, self:get, self:send ----

// self:send(target, message): target an actor or an actor's name; delivered at the next frame.
int actorSend(lua_State* L) {
  Context& ctx = contextOf(L);
  luaL_checkstack(L, 8, "send");
  const int from = checkActor(L, 1, "send", "self");
  const char* from_name = actorName(L, from);
  int to = -1;
  if (lua_type(L, 2) == LUA_TSTRING) {
    const auto it = ctx.actor_by_name.find(std::string_view(lua_tostring(L, 2)));
    if (it == ctx.actor_by_name.end())
      return luaL_error(L, "actor '%s': send: no actor named '%s'", from_name, lua_tostring(L, 2));
    to = it->second;
  } else {
    const ActorHandle* h = toUserdata<ActorHandle>(L, 2, ctx.mt_actor);
    if (!h)
      return luaL_error(L, "actor '%s': send: target: expected an actor or an actor's name, got %s", from_name,
                        luaL_typename(L, 2));
    to = h->actor;
  }
  Context::Actor& target = ctx.actors[static_cast<std::size_t>(to)];
  if (!target.receives)
    return luaL_error(L, "actor '%s': send: actor '%s' has no receive function", from_name, target.name.c_str());
  lua_settop(L, 3);  // the message: any value (nil too)
  lua_getfield(L, LUA_REGISTRYINDEX, kActorsKey);
  pushRecord(L, lua_gettop(L), to);
  lua_rawgeti(L, -1, kNext);
  const int next = lua_gettop(L);
  lua_pushvalue(L, 3);
  lua_rawseti(L, next, 2 * target.pending + 1);
  lua_pushvalue(L, 1);
  lua_rawseti(L, next, 2 * target.pending + 2);
  ++target.pending;  // only once both are stored (a failed store raises before)
  return 0;
}

// The value a field has before any actor sets it (its node's initial value: a field an actor
// drives has neither track nor actions).
void initialValue(const Context& ctx, int node, Field field, double* out) {
  const int dim = scene::fieldDimension(field);
  if (!ctx.stage->fieldValue(node, field, ctx.first_frame, std::span<double>(out, static_cast<std::size_t>(dim))))
    std::fill_n(out, dim, 0.0);  // not reached: the field was checked
}

// Bytes a recorded key costs, once a track key (charged when recorded).
std::size_t keyBytes(Field field) {
  return sizeof(anim::RawKey) + 2 * sizeof(double) * static_cast<std::size_t>(scene::fieldDimension(field) + 1) + 32;
}

// The channel of `field` of `node` for actor `actor` (creates it, with a key at the shot's first
// frame when the actor starts driving the field later). Phase 1 + 2.
int channelOf(lua_State* L, int actor, int node, Field field) {
  Context& ctx = contextOf(L);
  const Context::Actor& a = ctx.actors[static_cast<std::size_t>(actor)];
  int& slot = ctx.channel_of_node[static_cast<std::size_t>(node)][static_cast<std::size_t>(field)];
  if (slot >= 0) return slot;
  const scene::RawNode& n = ctx.scene.nodes[static_cast<std::size_t>(node)];
  const int driven = ctx.driven[static_cast<std::size_t>(node)][static_cast<std::size_t>(field)];
  if (driven != 0)
    luaL_error(L,
               "actor '%s': set: %s.%s already has %s (a field is driven by an actor, a track or set/change actions: "
               "one of them)",
               a.name.c_str(), n.name.c_str(), scene::fieldName(field), driven == 2 ? "a track" : "set/change actions");
  charge(L, sizeof(Context::Channel) + keyBytes(field));
  const int index = static_cast<int>(ctx.channels.size());
  if (!guarded(ctx, [&] {
        Context::Channel c;
        c.node = node;
        c.field = field;
        initialValue(ctx, node, field, c.current);
        if (ctx.frame > ctx.first_frame) {
          c.times.push_back(ctx.first_frame);
          c.values.insert(c.values.end(), c.current, c.current + scene::fieldDimension(field));
        }
        ctx.channels.push_back(std::move(c));
      }))
    raiseKept(L, "set");
  slot = index;
  ctx.driven[static_cast<std::size_t>(node)][static_cast<std::size_t>(field)] = 3;
  return index;
}

// self:set(field, value) or self:set(node, field, value): a field of the actor's node (or of a
// node it drives), from this frame on (until set again).
int actorSet(lua_State* L) {
  Context& ctx = contextOf(L);
  const int actor = checkActor(L, 1, "set", "self");
  const Context::Actor& a = ctx.actors[static_cast<std::size_t>(actor)];
  const char* name = a.name.c_str();
  if (!ctx.acting)
    return luaL_error(L,
                      "actor '%s': set: only while the actors run (in update or receive); give the node its first "
                      "values with vdg.node's fields",
                      name);
  int node = a.node;
  if (lua_type(L, 2) == LUA_TUSERDATA) {  // self:set(node, field, value)
    node = checkNode(L, 2, "set", "node");
    lua_remove(L, 2);
    if (ctx.actor_of_node[static_cast<std::size_t>(node)] != actor)
      return luaL_error(
          L,
          "actor '%s': set: node '%s' is not driven by this actor (give it in vdg.actor{node = ...} or drives = {...})",
          name, ctx.scene.nodes[static_cast<std::size_t>(node)].name.c_str());
  } else if (node < 0) {
    return luaL_error(
        L, "actor '%s': set: the actor has no node (vdg.actor{node = ...}); name one: self:set(node, field, value)",
        name);
  }
  const Field field = checkFieldName(L, 2, name, "set");
  const scene::RawNode& n = ctx.scene.nodes[static_cast<std::size_t>(node)];
  if (!scene::hasField(n.kind, field))
    return luaL_error(L, "actor '%s': set: node '%s' (a %s) has no field '%s'", name, n.name.c_str(),
                      scene::objectKindName(n.kind), scene::fieldName(field));
  double value[4];
  if (const char* why = readFieldValue(L, 3, field, value))
    return luaL_error(L, "actor '%s': set: %s.%s: %s", name, n.name.c_str(), scene::fieldName(field), why);
  const int channel = channelOf(L, actor, node, field);
  std::copy_n(value, scene::fieldDimension(field), ctx.channels[static_cast<std::size_t>(channel)].current);
  return 0;
}

// self:get(field): the actor's node's field now.
int actorGet(lua_State* L) {
  const Context& ctx = contextOf(L);
  const int actor = checkActor(L, 1, "get", "self");
  const Context::Actor& a = ctx.actors[static_cast<std::size_t>(actor)];
  if (a.node < 0)
    return luaL_error(L, "actor '%s': get: the actor has no node (use vdg.get(node, field))", a.name.c_str());
  const Field field = checkFieldName(L, 2, a.name.c_str(), "get");
  checkReadable(L, a.node, field, lua_pushfstring(L, "actor '%s': get", a.name.c_str()));
  pushField(L, a.node, field);
  return 1;
}

// vdg.get(node, field): any node's field now (while the actors run).
int luaGet(lua_State* L) {
  const int node = checkNode(L, 1, "vdg.get", "argument #1");
  const char* name = luaL_checkstring(L, 2);
  const std::optional<Field> field = scene::fieldFromName(name);
  if (!field) return luaL_error(L, "vdg.get: unknown field '%s'", name);
  checkReadable(L, node, *field, "vdg.get");
  pushField(L, node, *field);
  return 1;
}

int actorIndex(lua_State* L) {
  Context& ctx = contextOf(L);
  const int actor = checkActor(L, 1, "actor", "self");
  const char* key = luaL_checkstring(L, 2);
  const Context::Actor& a = ctx.actors[static_cast<std::size_t>(actor)];
  if (std::strcmp(key, "name") == 0) {
    lua_pushlstring(L, a.name.data(), a.name.size());
  } else if (std::strcmp(key, "node") == 0) {
    if (a.node < 0)
      lua_pushnil(L);
    else
      pushNode(L, a.node);
  } else if (std::strcmp(key, "state") == 0) {
    lua_getfield(L, LUA_REGISTRYINDEX, kActorsKey);
    pushRecord(L, lua_gettop(L), actor);
    lua_rawgeti(L, -1, kState);
  } else if (std::strcmp(key, "frame") == 0) {
    if (ctx.acting)
      lua_pushinteger(L, ctx.frame);
    else
      lua_pushnil(L);
  } else if (std::strcmp(key, "set") == 0) {
    lua_pushcfunction(L, actorSet);
  } else if (std::strcmp(key, "get") == 0) {
    lua_pushcfunction(L, actorGet);
  } else if (std::strcmp(key, "send") == 0) {
    lua_pushcfunction(L, actorSend);
  } else {
    return luaL_error(L,
                      "actor '%s': no field '%s' (actors have name, node, state, frame, set, get and send; keep "
                      "your own values in self.state)",
                      a.name.c_str(), key);
  }
  return 1;
}

int actorNewIndex(lua_State* L) {
  const int actor = checkActor(L, 1, "actor", "self");
  return luaL_error(L, "actor '%s': its fields cannot be assigned (keep your own values in self.state)",
                    actorName(L, actor));
}

int actorToString(lua_State* L) {
  const int actor = checkActor(L, 1, "tostring", "argument #1");
  lua_pushfstring(L, "actor '%s'", actorName(L, actor));
  return 1;
}

// ---- running ----

// Step 1 and 2 of a frame (see the top of the file). `list` is the registry list of records.
void stepFrame(lua_State* L, int list) {
  Context& ctx = contextOf(L);
  const int count = static_cast<int>(ctx.actors.size());
  for (int i = 0; i < count; ++i) {  // 1: the inboxes take what was sent before this frame
    Context::Actor& a = ctx.actors[static_cast<std::size_t>(i)];
    if (a.pending == 0) continue;
    pushRecord(L, list, i);
    lua_rawgeti(L, -1, kNext);
    lua_rawseti(L, -2, kInbox);
    lua_newtable(L);
    lua_rawseti(L, -2, kNext);
    lua_pop(L, 1);
    a.delivering = a.pending;
    a.pending = 0;
  }
  for (int i = 0; i < count; ++i) {  // 2: messages in the order sent, then update
    ctx.current_actor = i;
    // Each actor's step counts as an instruction, so that even actors that do nothing cannot run
    // through an unbounded number of frames outside the budget.
    if (++ctx.executed >= ctx.budget || ctx.budget_exceeded) {
      ctx.budget_exceeded = true;
      luaL_error(L, "instruction budget exceeded");
    }
    pushRecord(L, list, i);
    const int record = lua_gettop(L);
    const int delivering = ctx.actors[static_cast<std::size_t>(i)].delivering;
    if (delivering > 0) {
      lua_rawgeti(L, record, kInbox);
      const int inbox = lua_gettop(L);
      for (int k = 0; k < delivering; ++k) {
        lua_rawgeti(L, record, kReceive);
        lua_rawgeti(L, record, kHandle);
        lua_rawgeti(L, inbox, 2 * k + 1);
        lua_rawgeti(L, inbox, 2 * k + 2);
        lua_call(L, 3, 0);
      }
      lua_pop(L, 1);
      lua_pushnil(L);
      lua_rawseti(L, record, kInbox);
      ctx.actors[static_cast<std::size_t>(i)].delivering = 0;
    }
    if (lua_rawgeti(L, record, kUpdate) == LUA_TFUNCTION) {
      lua_rawgeti(L, record, kHandle);
      lua_pushinteger(L, ctx.frame);
      lua_call(L, 2, 0);
    } else {
      lua_pop(L, 1);
    }
    lua_pop(L, 1);
  }
  ctx.current_actor = -1;
}

// Step 3: a key for every driven field whose value changed (or that has none yet).
void recordFrame(lua_State* L) {
  Context& ctx = contextOf(L);
  for (Context::Channel& c : ctx.channels) {
    const auto dim = static_cast<std::size_t>(scene::fieldDimension(c.field));
    if (!c.times.empty() && std::equal(c.current, c.current + dim, c.values.end() - static_cast<std::ptrdiff_t>(dim)))
      continue;
    charge(L, keyBytes(c.field));
    if (!guarded(ctx, [&] {
          c.times.push_back(ctx.frame);
          c.values.insert(c.values.end(), c.current, c.current + dim);
        }))
      raiseKept(L, "actors");
  }
}

// The recorded keys as the scene's step tracks (phase 2).
void addTracks(Context& ctx) {
  for (const Context::Channel& c : ctx.channels) {
    const int dim = scene::fieldDimension(c.field);
    scene::RawFieldTrack t;
    t.node = c.node;
    t.field = c.field;
    t.track.name = ctx.scene.nodes[static_cast<std::size_t>(c.node)].name + "." + scene::fieldName(c.field);
    t.track.type = c.field == Field::kRotation ? anim::TrackType::kRotation
                   : dim == 1                  ? anim::TrackType::kScalar
                                               : anim::TrackType::kVector;
    t.track.interpolation = anim::Interpolation::kStep;
    t.track.keys.resize(c.times.size());
    for (std::size_t k = 0; k < c.times.size(); ++k) {
      t.track.keys[k].time = c.times[k];
      t.track.keys[k].value = Eigen::Map<const Eigen::VectorXd>(&c.values[k * static_cast<std::size_t>(dim)], dim);
    }
    ctx.scene.tracks.push_back(std::move(t));
  }
  ctx.channels.clear();
}

}  // namespace

void refuseWhileActing(lua_State* L, const char* function) {
  if (contextOf(L).acting)
    luaL_error(L,
               "%s: the scene is fixed once the actors run (an actor changes its node with self:set and talks to "
               "others with self:send)",
               function);
}

void runActors(lua_State* L) {
  Context& ctx = contextOf(L);
  if (ctx.actors.empty() || ctx.renders.empty()) return;
  int first = ctx.renders.front().first_frame, last = ctx.renders.front().last_frame;
  for (const RenderRequest& r : ctx.renders) {
    first = std::min(first, r.first_frame);
    last = std::max(last, r.last_frame);
  }
  if (ctx.actor_last_frame) last = std::min(last, *ctx.actor_last_frame);
  // The scene without the actors: what self:get and vdg.get read of the fields no actor drives.
  if (!ctx.scene.nodes.empty() &&
      !guarded(ctx, [&] { ctx.stage.emplace(scene::Scene::build(ctx.scene, ctx.chunk_name)); })) {
    if (ctx.error.empty()) luaL_error(L, "not enough memory");
    luaL_error(L, "%s", ctx.error.c_str());
  }
  luaL_checkstack(L, 16, "actors");
  lua_getfield(L, LUA_REGISTRYINDEX, kActorsKey);
  const int list = lua_gettop(L);
  if (!guarded(ctx, [&] {
        ctx.actor_of_node.resize(ctx.scene.nodes.size(), -1);
        std::array<int, scene::kFieldCount> none{};
        none.fill(-1);
        ctx.channel_of_node.assign(ctx.scene.nodes.size(), none);
      }))
    raiseKept(L, "actors");
  ctx.acting = true;
  ctx.first_frame = first;
  for (long long f = first; f <= last; ++f) {
    ctx.frame = static_cast<int>(f);
    stepFrame(L, list);
    recordFrame(L);
  }
  lua_pop(L, 1);
  if (!guarded(ctx, [&] { addTracks(ctx); })) raiseKept(L, "actors");
  ctx.stage.reset();
}

void openActors(lua_State* L, int vdg) {
  Context& ctx = contextOf(L);
  lua_newtable(L);
  lua_setfield(L, LUA_REGISTRYINDEX, kActorsKey);
  const luaL_Reg functions[] = {{"actor", luaActor}, {"get", luaGet}, {nullptr, nullptr}};
  lua_pushvalue(L, vdg);
  luaL_setfuncs(L, functions, 0);
  lua_pop(L, 1);
  const luaL_Reg meta[] = {
      {"__index", actorIndex}, {"__newindex", actorNewIndex}, {"__tostring", actorToString}, {nullptr, nullptr}};
  ctx.mt_actor = lockedMetatable(L, "vdg.actor", meta);
}

}  // namespace vdg::script::detail
