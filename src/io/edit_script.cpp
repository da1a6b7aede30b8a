// Edit scripts, edit logs and camera files: the JSON forms of vdg/deform/edits.h (docs/deform.md).
#include "vdg/io/edit_script.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <numbers>
#include <set>
#include <sstream>

#include "camera_fields.h"
#include "json_reader.h"
#include "vdg/geom/error.h"
#include "vdg/io/atomic_file.h"
#include "vdg/io/json_text.h"
#include "vdg/io/read_file.h"

namespace vdg {

using nlohmann::json;

namespace {

// Reads the fields of one JSON object, naming `where` and the field in every error, and rejects
// fields nobody asked for.
class FieldReader {
 public:
  FieldReader(const json& object, std::string where) : obj_(object), where_(std::move(where)) {
    if (!obj_.is_object()) fail("expected a JSON object");
  }
  [[noreturn]] void fail(const std::string& message) const { throw Error(where_ + ": " + message); }
  [[noreturn]] void failField(const std::string& field, const std::string& message) const {
    throw Error(where_ + ": '" + field + "' " + message);
  }
  bool has(const std::string& field) {
    used_.insert(field);
    return obj_.contains(field);
  }
  const json& get(const std::string& field) {
    if (!has(field)) failField(field, "is missing");
    return obj_.at(field);
  }
  double number(const std::string& field) {
    const json& v = get(field);
    if (!v.is_number() || !std::isfinite(v.get<double>())) failField(field, "must be a finite number");
    return v.get<double>();
  }
  double number(const std::string& field, double fallback) { return has(field) ? number(field) : fallback; }
  std::int64_t integer(const std::string& field) {
    const json& v = get(field);
    if (!v.is_number_integer()) failField(field, "must be an integer, got " + v.dump());
    // An unsigned value above INT64_MAX would wrap to a negative number (18446744073709551615 -> -1).
    if (v.is_number_unsigned() && v.get<std::uint64_t>() > static_cast<std::uint64_t>(INT64_MAX))
      failField(field, "is too large, got " + v.dump());
    return v.get<std::int64_t>();
  }
  bool boolean(const std::string& field, bool fallback) {
    if (!has(field)) return fallback;
    const json& v = obj_.at(field);
    if (!v.is_boolean()) failField(field, "must be true or false");
    return v.get<bool>();
  }
  std::string string(const std::string& field, const std::string& fallback) {
    if (!has(field)) return fallback;
    const json& v = obj_.at(field);
    if (!v.is_string()) failField(field, "must be a string");
    return v.get<std::string>();
  }
  template <int N>
  Eigen::Matrix<double, N, 1> vec(const std::string& field) {
    return vecOf<N>(get(field), field);
  }
  template <int N>
  Eigen::Matrix<double, N, 1> vecOf(const json& v, const std::string& field) const {
    if (!v.is_array() || v.size() != N) failField(field, "must be an array of " + std::to_string(N) + " numbers");
    Eigen::Matrix<double, N, 1> out;
    for (int i = 0; i < N; ++i) {
      if (!v[i].is_number() || !std::isfinite(v[i].get<double>()))
        failField(field, "must be an array of " + std::to_string(N) + " finite numbers");
      out[i] = v[i].get<double>();
    }
    return out;
  }
  void finish() const {
    for (auto it = obj_.begin(); it != obj_.end(); ++it)
      if (!used_.count(it.key())) fail("unknown field '" + it.key() + "'");
  }
  const std::string& where() const { return where_; }

 private:
  const json& obj_;
  std::string where_;
  std::set<std::string> used_;
};

std::string fmt(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

std::vector<std::int32_t> vertexList(FieldReader& r, const std::string& field) {
  std::vector<std::int32_t> out;
  if (!r.has(field)) return out;
  const json& v = r.get(field);
  if (!v.is_array()) r.failField(field, "must be an array of vertex indices");
  for (const json& e : v) {
    if (!e.is_number_integer() || e.get<std::int64_t>() < 0 || e.get<std::int64_t>() > INT32_MAX)
      r.failField(field, "must hold vertex indices in [0, " + std::to_string(INT32_MAX) + "], got " + e.dump());
    out.push_back(static_cast<std::int32_t>(e.get<std::int64_t>()));
  }
  if (out.empty()) r.failField(field, "must not be empty (leave it out to select every vertex)");
  return out;
}

EditOp parseOp(const json& j, std::size_t index, const std::string& source) {
  const std::string at = source + ": ops[" + std::to_string(index) + "]";
  if (!j.is_object()) throw Error(at + ": expected a JSON object with an \"op\" field");
  if (!j.contains("op") || !j.at("op").is_string()) throw Error(at + ": 'op' is missing or not a string");
  const std::string name = j.at("op").get<std::string>();
  EditOp op;
  op.json = j.dump();
  static const std::pair<const char*, EditKind> kKinds[] = {{"drag", EditKind::kDrag},
                                                            {"push_pull", EditKind::kPushPull},
                                                            {"rotate", EditKind::kRotate},
                                                            {"scale", EditKind::kScale},
                                                            {"displace", EditKind::kDisplace},
                                                            {"ffd", EditKind::kFfd},
                                                            {"squash_stretch", EditKind::kSquashStretch},
                                                            {"affine", EditKind::kAffine}};
  bool found = false;
  for (const auto& [n, k] : kKinds)
    if (name == n) op.kind = k, found = true;
  if (!found)
    throw Error(at + ": unknown op '" + name +
                "' (expected drag, push_pull, rotate, scale, displace, ffd, squash_stretch or affine)");
  FieldReader r(j, at + " (" + name + ")");
  r.has("op");

  const bool picked = op.kind == EditKind::kDrag || op.kind == EditKind::kPushPull || op.kind == EditKind::kRotate ||
                      op.kind == EditKind::kScale || op.kind == EditKind::kDisplace;
  if (picked) {
    op.vertex = r.integer("vertex");
    if (op.vertex < 0) r.failField("vertex", "must be >= 0, got " + std::to_string(op.vertex));
    op.falloff.radius = r.number("radius");
    if (!(op.falloff.radius > 0)) r.failField("radius", "must be > 0, got " + fmt(op.falloff.radius));
    // The image-plane rotate and scale tools act on a rigid group by default; the others fall off.
    const double default_power = (op.kind == EditKind::kRotate || op.kind == EditKind::kScale) ? 0.0 : 2.0;
    op.falloff.power = r.number("power", default_power);
    if (!(op.falloff.power >= 0)) r.failField("power", "must be >= 0, got " + fmt(op.falloff.power));
    op.falloff.shape = parseFalloffShape(r.string("falloff", "power"), r.where() + ": 'falloff'");
    op.metric = parseDistanceMetric(r.string("distance", "euclidean"), r.where() + ": 'distance'");
  }
  switch (op.kind) {
    case EditKind::kDrag: {
      const bool world = r.has("delta"), px = r.has("delta_px");
      if (world == px) r.fail("give exactly one of 'delta' (world units) or 'delta_px' (pixels)");
      if (world)
        op.delta = r.vec<2>("delta");
      else
        op.delta_px = r.vec<2>("delta_px");
      break;
    }
    case EditKind::kPushPull: {
      op.amount = r.number("amount");
      const std::string mode = r.string("mode", "ray");
      if (mode == "ray")
        op.push_mode = PushPullMode::kAlongRay;
      else if (mode == "axis")
        op.push_mode = PushPullMode::kAlongAxis;
      else
        r.failField("mode", "must be \"ray\" or \"axis\", got \"" + mode + "\"");
      break;
    }
    case EditKind::kRotate:
      op.angle_deg = r.number("angle_deg");
      break;
    case EditKind::kScale: {
      const json& f = r.get("factor");
      if (f.is_number())
        op.factor = Eigen::Vector2d::Constant(f.get<double>());
      else
        op.factor = r.vecOf<2>(f, "factor");
      if (!(op.factor.minCoeff() > 0) || !op.factor.allFinite()) r.failField("factor", "must be > 0, got " + f.dump());
      break;
    }
    case EditKind::kDisplace: {
      op.offset = r.vec<3>("offset");
      const std::string frame = r.string("frame", "world");
      if (frame != "world" && frame != "camera") r.failField("frame", "must be \"world\" or \"camera\"");
      op.camera_frame = frame == "camera";
      break;
    }
    case EditKind::kFfd: {
      op.vertices = vertexList(r, "vertices");
      const std::string frame = r.string("frame", "camera");
      if (frame != "world" && frame != "camera") r.failField("frame", "must be \"world\" or \"camera\"");
      op.camera_frame = frame == "camera";
      if (r.has("degree")) {
        const Eigen::Vector3d d = r.vec<3>("degree");
        for (int a = 0; a < 3; ++a) {
          if (d[a] != std::floor(d[a]) || d[a] < 1 || d[a] > 16)
            r.failField("degree", "must hold three integers in [1, 16], got " + fmt(d[a]));
          op.degree[a] = static_cast<int>(d[a]);
        }
      }
      op.padding = r.number("padding", 0.05);
      if (!(op.padding >= 0)) r.failField("padding", "must be >= 0, got " + fmt(op.padding));
      const json& moves = r.get("moves");
      if (!moves.is_array()) r.failField("moves", "must be an array of {\"index\": [i,j,k], \"offset\": [x,y,z]}");
      for (std::size_t m = 0; m < moves.size(); ++m) {
        FieldReader mr(moves[m], r.where() + ": moves[" + std::to_string(m) + "]");
        const Eigen::Vector3d idx = mr.vec<3>("index");
        FfdMove move;
        for (int a = 0; a < 3; ++a) {
          if (idx[a] != std::floor(idx[a]) || idx[a] < 0 || idx[a] > op.degree[a])
            mr.failField("index", "component " + std::to_string(a) + " = " + fmt(idx[a]) + " is out of range [0, " +
                                      std::to_string(op.degree[a]) + "]");
          move.index[a] = static_cast<int>(idx[a]);
        }
        move.offset = mr.vec<3>("offset");
        mr.finish();
        op.moves.push_back(move);
      }
      break;
    }
    case EditKind::kSquashStretch: {
      op.vertices = vertexList(r, "vertices");
      const json& axis = r.get("axis");
      if (axis.is_string()) {
        const std::string a = axis.get<std::string>();
        op.camera_frame = true;
        if (a == "right")
          op.axis = Eigen::Vector3d::UnitX();
        else if (a == "up")
          op.axis = Eigen::Vector3d::UnitY();
        else if (a == "view")
          op.axis = Eigen::Vector3d::UnitZ();
        else
          r.failField("axis", "must be \"right\", \"up\", \"view\" or [x, y, z], got \"" + a + "\"");
      } else {
        op.camera_frame = false;
        op.axis = r.vecOf<3>(axis, "axis");
        if (!(op.axis.norm() > 0)) r.failField("axis", "must be non-zero");
      }
      op.stretch = r.number("factor");
      if (!(op.stretch > 0)) r.failField("factor", "must be > 0, got " + fmt(op.stretch));
      op.preserve_volume = r.boolean("preserve_volume", true);
      if (r.has("center")) op.center = r.vec<3>("center");
      break;
    }
    case EditKind::kAffine: {
      op.vertices = vertexList(r, "vertices");
      const json& m = r.get("matrix");
      if (!m.is_array() || m.size() != 3) r.failField("matrix", "must be 3 rows of 3 numbers");
      for (int row = 0; row < 3; ++row) op.matrix.row(row) = r.vecOf<3>(m[row], "matrix").transpose();
      if (r.has("translation")) op.translation = r.vec<3>("translation");
      if (r.has("center")) op.center = r.vec<3>("center");
      break;
    }
  }
  r.finish();
  return op;
}

std::string readText(const std::string& path, const std::string& what) {
  return readFileLimited(path, what, kMaxJsonFileBytes);
}

json parseJson(const std::string& text, const std::string& source) { return io::parseJson(text, source); }

Camera cameraFrom(const json& j, const std::string& where) { return io::cameraFrom(j, io::Ctx{where, ""}); }

json cameraJson(const Camera& c) { return json(io::cameraJson(c)); }

std::optional<std::array<int, 2>> imageSize(FieldReader& r, const std::string& field) {
  if (!r.has(field)) return std::nullopt;
  const Eigen::Vector2d s = r.vec<2>(field);
  if (s.x() < 1 || s.y() < 1 || s.x() != std::floor(s.x()) || s.y() != std::floor(s.y()))
    r.failField(field, "must be two positive integers [width, height]");
  return std::array<int, 2>{static_cast<int>(s.x()), static_cast<int>(s.y())};
}

std::vector<EditOp> parseOps(FieldReader& r, const std::string& source) {
  const json& ops = r.get("ops");
  if (!ops.is_array()) r.failField("ops", "must be an array of operations");
  std::vector<EditOp> out;
  for (std::size_t i = 0; i < ops.size(); ++i) out.push_back(parseOp(ops[i], i, source));
  return out;
}

void checkVersion(FieldReader& r) {
  if (!r.has("version")) return;
  const std::int64_t v = r.integer("version");
  if (v != kEditsVersion)
    r.failField("version", "is " + std::to_string(v) + "; this vdg reads version " + std::to_string(kEditsVersion));
}

}  // namespace

EditScript parseEditScript(const std::string& text, const std::string& source) {
  const json j = parseJson(text, source);
  FieldReader r(j, source);
  checkVersion(r);
  EditScript script;
  if (r.has("camera")) script.camera = cameraFrom(r.get("camera"), source + ": camera");
  if (r.has("view")) {
    const Eigen::Vector3d v = r.vec<3>("view");
    if (!(v.norm() > 0)) r.failField("view", "must be non-zero");
    script.view = v.normalized();
  }
  if (script.camera && script.view) r.fail("give 'camera' or 'view', not both");
  script.image_size = imageSize(r, "image_size");
  script.ops = parseOps(r, source);
  r.finish();
  return script;
}

EditScript readEditScript(const std::string& path) { return parseEditScript(readText(path, "edit script"), path); }

std::string editLogPath(const std::string& key_mesh_path) {
  std::filesystem::path p(key_mesh_path);
  p.replace_extension(".edits.json");
  return p.string();
}

EditLog readEditLog(const std::string& path) {
  const json j = parseJson(readText(path, "edit log"), path);
  FieldReader r(j, path);
  checkVersion(r);
  EditLog log;
  log.key = r.string("key", "");
  log.origin = r.string("origin", "base");
  const json& entries = r.get("entries");
  if (!entries.is_array()) r.failField("entries", "must be an array");
  for (std::size_t e = 0; e < entries.size(); ++e) {
    const std::string where = path + ": entries[" + std::to_string(e) + "]";
    FieldReader er(entries[e], where);
    EditLogEntry entry;
    entry.camera = cameraFrom(er.get("camera"), where + ": camera");
    entry.image_size = imageSize(er, "image_size");
    entry.ops = parseOps(er, where);
    er.finish();
    log.entries.push_back(std::move(entry));
  }
  r.finish();
  return log;
}

void writeEditLog(const std::string& path, const EditLog& log) {
  json j;
  j["version"] = kEditsVersion;
  j["key"] = log.key;
  j["origin"] = log.origin;
  j["entries"] = json::array();
  for (const EditLogEntry& e : log.entries) {
    json je;
    je["camera"] = cameraJson(e.camera);
    if (e.image_size) je["image_size"] = {(*e.image_size)[0], (*e.image_size)[1]};
    je["ops"] = json::array();
    for (const EditOp& op : e.ops) je["ops"].push_back(json::parse(op.json));
    j["entries"].push_back(std::move(je));
  }
  const std::string text = compactScalarArrays(j.dump(2)) + "\n";
  writeFileAtomically(path, [&](std::ostream& out) { out << text; });
}

}  // namespace vdg
