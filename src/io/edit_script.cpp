// Edit operations, edit scripts and edit logs: the JSON forms of vdg/deform/edits.h
// (docs/deform.md). Every op is read by readOp and written by writeOp, and nowhere else.
#include "vdg/io/edit_script.h"

#include <cstdint>
#include <filesystem>
#include <limits>

#include "camera_fields.h"
#include "edit_fields.h"
#include "json_reader.h"
#include "line_pair_fields.h"
#include "vdg/geom/error.h"
#include "vdg/io/atomic_file.h"
#include "vdg/io/json_text.h"

namespace vdg {

namespace {

using io::Ctx;
using io::Json;
using OJson = nlohmann::ordered_json;

constexpr std::int64_t kMaxIndex = std::numeric_limits<std::int32_t>::max();

constexpr std::pair<const char*, EditKind> kKinds[] = {{"drag", EditKind::kDrag},
                                                       {"push_pull", EditKind::kPushPull},
                                                       {"rotate", EditKind::kRotate},
                                                       {"scale", EditKind::kScale},
                                                       {"displace", EditKind::kDisplace},
                                                       {"ffd", EditKind::kFfd},
                                                       {"squash_stretch", EditKind::kSquashStretch},
                                                       {"affine", EditKind::kAffine},
                                                       {"skeleton", EditKind::kSkeleton},
                                                       {"lines", EditKind::kLines}};
constexpr std::pair<const char*, DistanceMetric> kMetrics[] = {{"euclidean", DistanceMetric::kEuclidean},
                                                               {"edges", DistanceMetric::kEdges},
                                                               {"geodesic", DistanceMetric::kGeodesic}};
constexpr std::pair<const char*, FalloffShape> kShapes[] = {{"power", FalloffShape::kPower},
                                                            {"inverse_power", FalloffShape::kInversePower}};
constexpr std::pair<const char*, PushPullMode> kModes[] = {{"ray", PushPullMode::kAlongRay},
                                                           {"axis", PushPullMode::kAlongAxis}};
constexpr std::pair<const char*, bool> kFrames[] = {{"camera", true}, {"world", false}};
// The named axes of squash_stretch: the camera's right, up and back (towards the eye).
constexpr std::pair<const char*, int> kAxes[] = {{"right", 0}, {"up", 1}, {"view", 2}};

template <typename T, std::size_t N>
const char* nameOf(const std::pair<const char*, T> (&names)[N], T value) {
  for (const auto& [name, v] : names)
    if (v == value) return name;
  return "?";
}

// ---- reading ----------------------------------------------------------------------------------

Eigen::Vector2d vector2(const Json& j, const Ctx& ctx) { return io::vector(j, ctx, 2); }

std::optional<Eigen::Vector3d> optionalVector3(const Json& j, const char* key, const Ctx& ctx) {
  if (!j.contains(key)) return std::nullopt;
  return io::vector3(j.at(key), ctx.key(key));
}

template <typename T, std::size_t N>
T enumOr(const Json& j, const char* key, T fallback, const Ctx& ctx, const std::pair<const char*, T> (&names)[N]) {
  return j.contains(key) ? io::enumValue(j.at(key), ctx.key(key), names) : fallback;
}

std::vector<std::int32_t> vertexList(const Json& j, const Ctx& ctx) {
  std::vector<std::int32_t> out;
  if (!j.contains("vertices")) return out;
  const Json& list = j.at("vertices");
  const Ctx lctx = ctx.key("vertices");
  if (!list.is_array()) lctx.fail("expected an array of vertex indices, got " + io::describe(list));
  if (list.empty()) lctx.fail("must not be empty (leave it out to select every vertex)");
  out.reserve(list.size());
  for (std::size_t i = 0; i < list.size(); ++i)
    out.push_back(static_cast<std::int32_t>(io::integer(list[i], lctx.index(i), 0, kMaxIndex)));
  return out;
}

VertexPick readPick(const Json& j, const Ctx& ctx, double default_power) {
  VertexPick p;
  // The seed: exactly one of an index, a model-space point or a pixel of the key view.
  const int given = static_cast<int>(j.contains("vertex")) + static_cast<int>(j.contains("point")) +
                    static_cast<int>(j.contains("pixel"));
  if (given != 1)
    ctx.fail(given == 0 ? "missing the picked vertex: give 'vertex' (an index), 'point' [x, y, z] (the nearest vertex) "
                          "or 'pixel' [x, y] (the vertex seen there in the key view)"
                        : "give one of 'vertex', 'point' or 'pixel', not several");
  if (j.contains("point"))
    p.point = io::vector3(j.at("point"), ctx.key("point"));
  else if (j.contains("pixel"))
    p.pixel = vector2(j.at("pixel"), ctx.key("pixel"));
  else
    p.vertex = static_cast<std::int32_t>(io::integer(j.at("vertex"), ctx.key("vertex"), 0, kMaxIndex));
  p.falloff.radius = io::number(io::required(j, "radius", ctx), ctx.key("radius"));
  p.falloff.power = io::numberOr(j, "power", default_power, ctx);
  p.falloff.shape = enumOr(j, "falloff", FalloffShape::kPower, ctx, kShapes);
  p.metric = enumOr(j, "distance", DistanceMetric::kEuclidean, ctx, kMetrics);
  return p;
}

// A wire's joints: an array of [x, y, z] (its length is checked by checkSkeletonWire; an array
// longer than any wire is refused before it is read).
std::vector<Eigen::Vector3d> jointList(const Json& j, const char* key, const Ctx& ctx) {
  const Json& list = io::required(j, key, ctx);
  const Ctx lctx = ctx.key(key);
  if (!list.is_array()) lctx.fail("expected an array of joints [x, y, z], got " + io::describe(list));
  if (list.size() > kMaxSkeletonJoints)
    lctx.fail("a wire has at most " + std::to_string(kMaxSkeletonJoints) + " joints, got " +
              std::to_string(list.size()));
  std::vector<Eigen::Vector3d> out;
  out.reserve(list.size());
  for (std::size_t i = 0; i < list.size(); ++i) out.push_back(io::vector3(list[i], lctx.index(i)));
  return out;
}

// An FFD op: the vertices, the lattice's degree and padding, and the control points moved.
FfdOp readFfd(const Json& j, const Ctx& ctx) {
  io::allowKeys(j, ctx, {"op", "vertices", "frame", "degree", "padding", "moves"});
  FfdOp o;
  o.vertices = vertexList(j, ctx);
  o.camera_frame = enumOr(j, "frame", true, ctx, kFrames);
  if (j.contains("degree")) {
    const Json& d = j.at("degree");
    const Ctx dctx = ctx.key("degree");
    if (!d.is_array() || d.size() != 3) dctx.fail("expected 3 integers, got " + io::describe(d));
    for (std::size_t a = 0; a < 3; ++a)
      o.degree[a] = static_cast<int>(io::integer(d[a], dctx.index(a), 1, kMaxFfdDegree));
  }
  o.padding = io::numberOr(j, "padding", o.padding, ctx);
  const Json& moves = io::required(j, "moves", ctx);
  const Ctx mctx = ctx.key("moves");
  if (!moves.is_array()) mctx.fail("expected an array of {\"index\": [i,j,k], \"offset\": [x,y,z]}");
  for (std::size_t m = 0; m < moves.size(); ++m) {
    const Ctx c = mctx.index(m);
    io::allowKeys(moves[m], c, {"index", "offset"});
    FfdMove move;
    const Json& idx = io::required(moves[m], "index", c);
    if (!idx.is_array() || idx.size() != 3) c.key("index").fail("expected 3 integers, got " + io::describe(idx));
    for (std::size_t a = 0; a < 3; ++a)
      move.index[a] = static_cast<int>(io::integer(idx[a], c.key("index").index(a), 0, kMaxFfdDegree));
    move.offset = io::vector3(io::required(moves[m], "offset", c), c.key("offset"));
    o.moves.push_back(move);
  }
  return o;
}

// A lines op: the pairs as a lines file holds them ("src" the model side, "dst" the drawing side)
// and the settings of vdg/deform/feature_lines.h.
LinesOp readLines(const Json& j, const Ctx& ctx) {
  io::allowKeys(j, ctx, {"op", "lines", "a", "b", "p", "falloff_px"});
  LinesOp o;
  for (const LinePair& pair : io::linePairListFrom(io::required(j, "lines", ctx), ctx.key("lines")))
    o.pairs.push_back({pair.src_p, pair.src_q, pair.dst_p, pair.dst_q});
  o.settings.a = io::numberOr(j, "a", o.settings.a, ctx);
  o.settings.b = io::numberOr(j, "b", o.settings.b, ctx);
  o.settings.p = io::numberOr(j, "p", o.settings.p, ctx);
  o.settings.falloff_px = io::numberOr(j, "falloff_px", o.settings.falloff_px, ctx);
  return o;
}

#define VDG_PICK_KEYS "op", "vertex", "point", "pixel", "radius", "power", "falloff", "distance"

EditOp readOpFields(const Json& j, EditKind kind, const Ctx& ctx) {
  switch (kind) {
    case EditKind::kDrag: {
      io::allowKeys(j, ctx, {VDG_PICK_KEYS, "delta", "delta_px"});
      DragOp o;
      o.pick = readPick(j, ctx, 2.0);
      const bool world = j.contains("delta"), px = j.contains("delta_px");
      if (world == px) ctx.fail("give exactly one of 'delta' (world units) or 'delta_px' (pixels)");
      if (world)
        o.delta = vector2(j.at("delta"), ctx.key("delta"));
      else
        o.delta_px = vector2(j.at("delta_px"), ctx.key("delta_px"));
      return o;
    }
    case EditKind::kPushPull: {
      io::allowKeys(j, ctx, {VDG_PICK_KEYS, "amount", "mode"});
      PushPullOp o;
      o.pick = readPick(j, ctx, 2.0);
      o.amount = io::number(io::required(j, "amount", ctx), ctx.key("amount"));
      o.mode = enumOr(j, "mode", PushPullMode::kAlongRay, ctx, kModes);
      return o;
    }
    case EditKind::kRotate: {
      io::allowKeys(j, ctx, {VDG_PICK_KEYS, "angle_deg"});
      RotateOp o;
      o.pick = readPick(j, ctx, 0.0);  // a rigid group by default
      o.angle_deg = io::number(io::required(j, "angle_deg", ctx), ctx.key("angle_deg"));
      return o;
    }
    case EditKind::kScale: {
      io::allowKeys(j, ctx, {VDG_PICK_KEYS, "factor"});
      ScaleOp o;
      o.pick = readPick(j, ctx, 0.0);
      const Json& f = io::required(j, "factor", ctx);
      o.factor =
          f.is_number() ? Eigen::Vector2d::Constant(io::number(f, ctx.key("factor"))) : vector2(f, ctx.key("factor"));
      return o;
    }
    case EditKind::kDisplace: {
      io::allowKeys(j, ctx, {VDG_PICK_KEYS, "offset", "frame"});
      DisplaceOp o;
      o.pick = readPick(j, ctx, 2.0);
      o.offset = io::vector3(io::required(j, "offset", ctx), ctx.key("offset"));
      o.camera_frame = enumOr(j, "frame", false, ctx, kFrames);
      return o;
    }
    case EditKind::kFfd:
      return readFfd(j, ctx);
    case EditKind::kSquashStretch: {
      io::allowKeys(j, ctx, {"op", "vertices", "axis", "frame", "factor", "preserve_volume", "center"});
      SquashStretchOp o;
      o.vertices = vertexList(j, ctx);
      const Json& axis = io::required(j, "axis", ctx);
      if (axis.is_string()) {
        if (j.contains("frame")) ctx.key("frame").fail("only with an axis [x, y, z]: a named axis is the camera's");
        o.camera_frame = true;
        o.axis = Eigen::Vector3d::Unit(io::enumValue(axis, ctx.key("axis"), kAxes));
      } else {
        o.axis = io::vector3(axis, ctx.key("axis"));
        o.camera_frame = enumOr(j, "frame", false, ctx, kFrames);
      }
      o.factor = io::number(io::required(j, "factor", ctx), ctx.key("factor"));
      if (j.contains("preserve_volume"))
        o.preserve_volume = io::boolean(j.at("preserve_volume"), ctx.key("preserve_volume"));
      o.center = optionalVector3(j, "center", ctx);
      return o;
    }
    case EditKind::kAffine: {
      io::allowKeys(j, ctx, {"op", "vertices", "matrix", "translation", "center"});
      AffineOp o;
      o.vertices = vertexList(j, ctx);
      const Json& m = io::required(j, "matrix", ctx);
      const Ctx mctx = ctx.key("matrix");
      if (!m.is_array() || m.size() != 3) mctx.fail("expected 3 rows of 3 numbers, got " + io::describe(m));
      for (std::size_t row = 0; row < 3; ++row)
        o.matrix.row(static_cast<Eigen::Index>(row)) = io::vector3(m[row], mctx.index(row)).transpose();
      if (j.contains("translation")) o.translation = io::vector3(j.at("translation"), ctx.key("translation"));
      o.center = optionalVector3(j, "center", ctx);
      return o;
    }
    case EditKind::kSkeleton: {
      io::allowKeys(j, ctx, {"op", "vertices", "rest", "posed", "radius", "power", "falloff"});
      SkeletonOp o;
      o.vertices = vertexList(j, ctx);
      o.rest = jointList(j, "rest", ctx);
      o.posed = jointList(j, "posed", ctx);
      if (j.contains("radius")) {
        Falloff f;
        f.radius = io::number(j.at("radius"), ctx.key("radius"));
        f.power = io::numberOr(j, "power", 2.0, ctx);
        f.shape = enumOr(j, "falloff", FalloffShape::kPower, ctx, kShapes);
        o.falloff = f;
      } else {
        for (const char* key : {"power", "falloff"})
          if (j.contains(key)) ctx.key(key).fail("only with 'radius' (the falloff's distance from the rest wire)");
      }
      return o;
    }
    case EditKind::kLines:
      return readLines(j, ctx);
  }
  ctx.fail("unknown op");
}

// `ctx` is the op's own position ("'ops'[2]"); messages add the kind: "'ops'[2] (drag).'radius'".
EditOp readOp(const Json& j, const Ctx& ctx) {
  if (!j.is_object()) ctx.fail("expected an object with an \"op\" field, got " + io::describe(j));
  const EditKind kind = io::enumValue(io::required(j, "op", ctx), ctx.key("op"), kKinds);
  const Ctx kctx = ctx.labelled(ctx.path + (ctx.path.empty() ? "" : " ") + "(" + editKindName(kind) + ")");
  EditOp op = readOpFields(j, kind, kctx);
  if (const auto problem = checkEditOp(op))
    Ctx{kctx.where, kctx.path + (kctx.path.empty() ? "" : ".") + problem->field}.fail(problem->message);
  return op;
}

std::vector<EditOp> readOps(const Json& doc, const Ctx& ctx) {
  const Json& ops = io::required(doc, "ops", ctx);
  if (!ops.is_array()) ctx.key("ops").fail("expected an array of operations, got " + io::describe(ops));
  std::vector<EditOp> out;
  out.reserve(ops.size());
  for (std::size_t i = 0; i < ops.size(); ++i) out.push_back(readOp(ops[i], ctx.key("ops").index(i)));
  return out;
}

std::optional<std::array<int, 2>> readImageSize(const Json& doc, const Ctx& ctx) {
  if (!doc.contains("image_size")) return std::nullopt;
  const Json& s = doc.at("image_size");
  const Ctx sctx = ctx.key("image_size");
  if (!s.is_array() || s.size() != 2) sctx.fail("expected [width, height] in pixels, got " + io::describe(s));
  std::array<int, 2> out{};
  for (std::size_t a = 0; a < 2; ++a) out[a] = static_cast<int>(io::integer(s[a], sctx.index(a), 1, kMaxEditImageSide));
  return out;
}

// ---- writing ----------------------------------------------------------------------------------

OJson array(const Eigen::Vector2d& v) { return OJson::array({v.x(), v.y()}); }
OJson array(const Eigen::Vector3d& v) { return OJson::array({v.x(), v.y(), v.z()}); }

void writePick(OJson& j, const VertexPick& p) {
  if (p.point)
    j["point"] = array(*p.point);
  else if (p.pixel)
    j["pixel"] = array(*p.pixel);
  else
    j["vertex"] = p.vertex;
  j["radius"] = p.falloff.radius;
  j["power"] = p.falloff.power;
  j["falloff"] = nameOf(kShapes, p.falloff.shape);
  j["distance"] = nameOf(kMetrics, p.metric);
}

void writeVertices(OJson& j, const std::vector<std::int32_t>& vertices) {
  if (!vertices.empty()) j["vertices"] = vertices;
}

// `at` names the op in messages ("op", "... 'entries'[0].'ops'[1]").
OJson writeOp(const EditOp& op, const std::string& at) {
  if (const auto problem = checkEditOp(op))
    throw Error(at + " (" + editKindName(op) + ")." + problem->field + ": " + problem->message);
  OJson j;
  j["op"] = editKindName(op);
  switch (editKind(op)) {
    case EditKind::kDrag: {
      const auto& o = std::get<DragOp>(op);
      writePick(j, o.pick);
      if (o.delta_px)
        j["delta_px"] = array(*o.delta_px);
      else
        j["delta"] = array(o.delta);
      break;
    }
    case EditKind::kPushPull: {
      const auto& o = std::get<PushPullOp>(op);
      writePick(j, o.pick);
      j["amount"] = o.amount;
      j["mode"] = nameOf(kModes, o.mode);
      break;
    }
    case EditKind::kRotate: {
      const auto& o = std::get<RotateOp>(op);
      writePick(j, o.pick);
      j["angle_deg"] = o.angle_deg;
      break;
    }
    case EditKind::kScale: {
      const auto& o = std::get<ScaleOp>(op);
      writePick(j, o.pick);
      j["factor"] = array(o.factor);
      break;
    }
    case EditKind::kDisplace: {
      const auto& o = std::get<DisplaceOp>(op);
      writePick(j, o.pick);
      j["offset"] = array(o.offset);
      j["frame"] = nameOf(kFrames, o.camera_frame);
      break;
    }
    case EditKind::kFfd: {
      const auto& o = std::get<FfdOp>(op);
      writeVertices(j, o.vertices);
      j["frame"] = nameOf(kFrames, o.camera_frame);
      j["degree"] = o.degree;
      j["padding"] = o.padding;
      j["moves"] = OJson::array();
      for (const FfdMove& m : o.moves) {
        OJson jm;
        jm["index"] = m.index;
        jm["offset"] = array(m.offset);
        j["moves"].push_back(std::move(jm));
      }
      break;
    }
    case EditKind::kSquashStretch: {
      const auto& o = std::get<SquashStretchOp>(op);
      writeVertices(j, o.vertices);
      const char* named = nullptr;
      for (const auto& [name, a] : kAxes)
        if (o.camera_frame && o.axis == Eigen::Vector3d::Unit(a)) named = name;
      if (named) {
        j["axis"] = named;
      } else {
        j["axis"] = array(o.axis);
        j["frame"] = nameOf(kFrames, o.camera_frame);
      }
      j["factor"] = o.factor;
      j["preserve_volume"] = o.preserve_volume;
      if (o.center) j["center"] = array(*o.center);
      break;
    }
    case EditKind::kAffine: {
      const auto& o = std::get<AffineOp>(op);
      writeVertices(j, o.vertices);
      j["matrix"] = OJson::array();
      for (int row = 0; row < 3; ++row) j["matrix"].push_back(array(Eigen::Vector3d(o.matrix.row(row).transpose())));
      j["translation"] = array(o.translation);
      if (o.center) j["center"] = array(*o.center);
      break;
    }
    case EditKind::kSkeleton: {
      const auto& o = std::get<SkeletonOp>(op);
      writeVertices(j, o.vertices);
      for (const auto& [key, joints] : {std::pair{"rest", &o.rest}, std::pair{"posed", &o.posed}}) {
        j[key] = OJson::array();
        for (const Eigen::Vector3d& p : *joints) j[key].push_back(array(p));
      }
      if (o.falloff) {
        j["radius"] = o.falloff->radius;
        j["power"] = o.falloff->power;
        j["falloff"] = nameOf(kShapes, o.falloff->shape);
      }
      break;
    }
    case EditKind::kLines: {
      const auto& o = std::get<LinesOp>(op);
      std::vector<LinePair> pairs;
      for (const FeatureLinePair& p : o.pairs) pairs.push_back({p.model_p, p.model_q, p.drawing_p, p.drawing_q});
      j["lines"] = io::linePairListJson(pairs);
      j["a"] = o.settings.a;
      j["b"] = o.settings.b;
      j["p"] = o.settings.p;
      j["falloff_px"] = o.settings.falloff_px;
      break;
    }
  }
  return j;
}

bool isOriginFileName(const std::string& origin) {
  const std::filesystem::path p(origin);
  return !origin.empty() && p.filename() == p && origin[0] != '.' && origin.ends_with(".obj");
}

}  // namespace

namespace io {

EditLogEntry editLogEntryFrom(const Json& value, const Ctx& ctx) {
  allowKeys(value, ctx, {"camera", "image_size", "ops"});
  EditLogEntry entry;
  entry.camera = cameraFrom(required(value, "camera", ctx), ctx.key("camera"));
  entry.image_size = readImageSize(value, ctx);
  entry.ops = readOps(value, ctx);
  return entry;
}

nlohmann::ordered_json editLogEntryJson(const EditLogEntry& entry, const std::string& at) {
  OJson j;
  j["camera"] = cameraJson(entry.camera);
  if (entry.image_size) j["image_size"] = *entry.image_size;
  j["ops"] = OJson::array();
  for (std::size_t i = 0; i < entry.ops.size(); ++i)
    j["ops"].push_back(writeOp(entry.ops[i], at + ".'ops'[" + std::to_string(i) + "]"));
  return j;
}

}  // namespace io

namespace {

EditScript scriptFrom(const Json& doc, const std::string& source) {
  const Ctx ctx{source, ""};
  io::formatVersion(doc, ctx, "edit scripts", kEditsVersion, kEditsVersion, /*missing=*/kEditsVersion);
  io::allowKeys(doc, ctx, {"version", "camera", "view", "image_size", "ops"});
  EditScript script;
  if (doc.contains("camera") && doc.contains("view")) ctx.fail("give 'camera' or 'view', not both");
  if (doc.contains("camera")) script.camera = io::cameraFrom(doc.at("camera"), ctx.key("camera"));
  if (doc.contains("view")) {
    const Eigen::Vector3d v = io::vector3(doc.at("view"), ctx.key("view"));
    if (!(v.norm() > 0)) ctx.key("view").fail("must be non-zero");
    script.view = v.normalized();
  }
  script.image_size = readImageSize(doc, ctx);
  script.ops = readOps(doc, ctx);
  return script;
}

EditLog logFrom(const Json& doc, const std::string& source) {
  const Ctx ctx{source, ""};
  io::formatVersion(doc, ctx, "edit logs", kEditsVersion, kEditsVersion, /*missing=*/kEditsVersion);
  io::allowKeys(doc, ctx, {"version", "key", "origin", "entries"});
  EditLog log;
  if (doc.contains("key")) log.key = io::string(doc.at("key"), ctx.key("key"));
  if (doc.contains("origin")) {
    log.origin = io::string(doc.at("origin"), ctx.key("origin"));
    if (log.origin != "base" && !isOriginFileName(log.origin))
      ctx.key("origin").fail("expected \"base\" or the file name of a mesh beside the log (NAME.obj, no folder)");
  }
  const Json& entries = io::required(doc, "entries", ctx);
  if (!entries.is_array()) ctx.key("entries").fail("expected an array, got " + io::describe(entries));
  for (std::size_t e = 0; e < entries.size(); ++e)
    log.entries.push_back(io::editLogEntryFrom(entries[e], ctx.key("entries").index(e)));
  return log;
}

}  // namespace

EditScript parseEditScript(const std::string& text, const std::string& source) {
  return scriptFrom(io::parseJson(text, source), source);
}

EditScript readEditScript(const std::string& path) { return scriptFrom(io::readJsonFile(path, "edit script"), path); }

std::string editOpToJson(const EditOp& op) { return writeOp(op, "op").dump(); }

EditOp parseEditOp(const std::string& text, const std::string& source) {
  return readOp(io::parseJson(text, source), Ctx{source, ""});
}

std::string editLogPath(const std::string& key_mesh_path) {
  std::filesystem::path p(key_mesh_path);
  p.replace_extension(".edits.json");
  return p.string();
}

std::string formatEditLog(const EditLog& log) {
  OJson j;
  j["version"] = kEditsVersion;
  j["key"] = log.key;
  j["origin"] = log.origin;
  j["entries"] = OJson::array();
  for (std::size_t e = 0; e < log.entries.size(); ++e)
    j["entries"].push_back(io::editLogEntryJson(
        log.entries[e], "edit log of key '" + log.key + "': 'entries'[" + std::to_string(e) + "]"));
  return compactScalarArrays(j.dump(2)) + "\n";
}

EditLog parseEditLog(const std::string& text, const std::string& source) {
  return logFrom(io::parseJson(text, source), source);
}

EditLog readEditLog(const std::string& path) { return logFrom(io::readJsonFile(path, "edit log"), path); }

void writeEditLog(const std::string& path, const EditLog& log) { writeFileAtomically(path, formatEditLog(log)); }

}  // namespace vdg
