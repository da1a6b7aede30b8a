// JSON form of the anim module's authoring objects (docs/anim.md). Parsing only: every value is
// checked here for its JSON type and shape, with errors naming the key path; the mathematical
// validation (times increasing, parameters in range) is done by the builders and re-prefixed here.
#include "vdg/io/anim_json.h"

#include <cmath>
#include <initializer_list>
#include <numbers>

#include "json_reader.h"
#include "vdg/geom/error.h"
#include "vdg/io/read_file.h"

namespace vdg::anim {
namespace {

using io::allowKeys;
using io::Ctx;
using io::enumValue;
using io::number;
using io::numberOr;
using io::string;
using io::vector;
using io::vector3;
using io::withContext;
using Json = io::Json;

constexpr std::pair<const char*, CurveKind> kCurveKinds[] = {
    {"linear", CurveKind::kLinear},
    {"catmull-rom", CurveKind::kCatmullRom},
    {"centripetal-catmull-rom", CurveKind::kCentripetalCatmullRom},
    {"natural-cubic", CurveKind::kNaturalCubic},
    {"parabolic-blending", CurveKind::kParabolicBlending},
    {"bezier", CurveKind::kBezier},
};
constexpr std::pair<const char*, Interpolation> kInterpolations[] = {
    {"step", Interpolation::kStep},
    {"linear", Interpolation::kLinear},
    {"catmull-rom", Interpolation::kCatmullRom},
    {"centripetal-catmull-rom", Interpolation::kCentripetalCatmullRom},
    {"natural-cubic", Interpolation::kNaturalCubic},
    {"parabolic-blending", Interpolation::kParabolicBlending},
    {"bezier", Interpolation::kBezier},
    {"slerp", Interpolation::kSlerp},
    {"quaternion-curve", Interpolation::kQuaternionCurve},
};
constexpr std::pair<const char*, TrackType> kTrackTypes[] = {
    {"scalar", TrackType::kScalar}, {"vector", TrackType::kVector}, {"rotation", TrackType::kRotation}};
constexpr std::pair<const char*, Extrapolation> kExtrapolations[] = {{"clamp", Extrapolation::kClamp},
                                                                     {"loop", Extrapolation::kLoop}};
constexpr std::pair<const char*, ViewMode> kViewModes[] = {{"center", ViewMode::kCenterOfInterest},
                                                           {"tangent", ViewMode::kAlongTangent},
                                                           {"target-path", ViewMode::kMovingTarget}};
constexpr std::pair<const char*, ArcLengthMethod> kArcMethods[] = {{"table", ArcLengthMethod::kTable},
                                                                   {"adaptive", ArcLengthMethod::kAdaptive}};

// The ease object's own keys; `j` may hold other keys when `strict` is false (an ease inside a key).
Ease easeFrom(const Json& j, const Ctx& ctx) {
  if (j.is_string()) {  // shorthand "sine" / "linear"
    const std::string s = j.get<std::string>();
    if (s == "linear") return Ease::linear();
    if (s == "sine") return Ease::sine();
    ctx.fail("'" + s + "' needs parameters: use an object {\"ease\": \"" + s + "\", ...}");
  }
  allowKeys(j, ctx, {"ease", "t1", "t2", "a", "b"});
  if (!j.contains("ease")) ctx.fail("missing key 'ease'");
  const std::string kind = string(j.at("ease"), ctx.key("ease"));
  if (kind == "linear" || kind == "sine") {
    for (const char* k : {"t1", "t2", "a", "b"}) {
      if (j.contains(k)) ctx.fail(std::string("'") + k + "' is not a parameter of the " + kind + " ease");
    }
    return kind == "linear" ? Ease::linear() : Ease::sine();
  }
  if (kind == "sinusoidal") {
    for (const char* k : {"a", "b"}) {
      if (j.contains(k)) ctx.fail(std::string("'") + k + "' is not a parameter of the sinusoidal ease (use t1, t2)");
    }
    if (!j.contains("t1") || !j.contains("t2")) ctx.fail("the sinusoidal ease needs 't1' and 't2'");
    const double t1 = number(j.at("t1"), ctx.key("t1")), t2 = number(j.at("t2"), ctx.key("t2"));
    return withContext(ctx, [&] { return Ease::sinusoidal(t1, t2); });
  }
  if (kind == "parabolic") {
    for (const char* k : {"t1", "t2"}) {
      if (j.contains(k)) ctx.fail(std::string("'") + k + "' is not a parameter of the parabolic ease (use a, b)");
    }
    if (!j.contains("a") || !j.contains("b")) ctx.fail("the parabolic ease needs 'a' and 'b'");
    const double a = number(j.at("a"), ctx.key("a")), b = number(j.at("b"), ctx.key("b"));
    return withContext(ctx, [&] { return Ease::parabolic(a, b); });
  }
  ctx.key("ease").fail("unknown ease '" + kind + "' (expected 'linear', 'sine', 'sinusoidal' or 'parabolic')");
}

std::optional<ArcLengthOptions> arcLengthFrom(const Json& j, const Ctx& ctx) {
  if (j.is_boolean()) return j.get<bool>() ? std::optional<ArcLengthOptions>(ArcLengthOptions{}) : std::nullopt;
  allowKeys(j, ctx, {"method", "samples", "tolerance"});
  ArcLengthOptions o;
  if (j.contains("method")) o.method = enumValue(j.at("method"), ctx.key("method"), kArcMethods);
  if (j.contains("samples")) {
    o.table_samples = static_cast<int>(io::integer(j.at("samples"), ctx.key("samples"), 2, 10'000'000));
  }
  o.tolerance = numberOr(j, "tolerance", o.tolerance, ctx);
  if (!(o.tolerance > 0.0 && o.tolerance < 1.0)) ctx.key("tolerance").fail("expected a number in (0, 1)");
  return o;
}

// Curve fields of `j` ("curve", "points", "times"); other keys are checked by the caller.
RawCurve curveFrom(const Json& j, const Ctx& ctx) {
  RawCurve c;
  if (!j.contains("curve")) ctx.fail("missing key 'curve'");
  c.kind = enumValue(j.at("curve"), ctx.key("curve"), kCurveKinds);
  if (!j.contains("points")) ctx.fail("missing key 'points'");
  const Json& pts = j.at("points");
  const Ctx pctx = ctx.key("points");
  if (!pts.is_array()) pctx.fail("expected an array of points");
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const long dim = c.points.empty() ? 0 : static_cast<long>(c.points[0].size());
    c.points.push_back(vector(pts[i], pctx.index(i), dim));
  }
  if (j.contains("times")) {
    const Json& ts = j.at("times");
    if (!ts.is_array()) ctx.key("times").fail("expected an array of numbers");
    for (std::size_t i = 0; i < ts.size(); ++i) c.times.push_back(number(ts[i], ctx.key("times").index(i)));
  }
  c.validate(ctx.prefix());
  return c;
}

RawCurve curveObject(const Json& j, const Ctx& ctx) {
  allowKeys(j, ctx, {"curve", "points", "times"});
  return curveFrom(j, ctx);
}

RawTrack trackFrom(const Json& j, const Ctx& ctx) {
  allowKeys(j, ctx, {"name", "type", "interpolation", "extrapolation", "keys"});
  RawTrack t;
  if (j.contains("name")) t.name = string(j.at("name"), ctx.key("name"));
  if (j.contains("interpolation"))
    t.interpolation = enumValue(j.at("interpolation"), ctx.key("interpolation"), kInterpolations);
  if (j.contains("extrapolation"))
    t.extrapolation = enumValue(j.at("extrapolation"), ctx.key("extrapolation"), kExtrapolations);
  if (!j.contains("keys")) ctx.fail("missing key 'keys'");
  const Json& keys = j.at("keys");
  const Ctx kctx = ctx.key("keys");
  if (!keys.is_array() || keys.empty()) kctx.fail("expected a non-empty array of keys");
  // Type: given, or inferred from the interpolation and the first value.
  if (j.contains("type")) {
    t.type = enumValue(j.at("type"), ctx.key("type"), kTrackTypes);
  } else if (t.interpolation == Interpolation::kSlerp || t.interpolation == Interpolation::kQuaternionCurve) {
    t.type = TrackType::kRotation;
  } else {
    const Json& k0 = keys[0];
    t.type =
        k0.is_object() && k0.contains("value") && k0.at("value").is_array() ? TrackType::kVector : TrackType::kScalar;
  }
  long dim = t.type == TrackType::kRotation ? 4 : t.type == TrackType::kScalar ? 1 : 0;
  for (std::size_t i = 0; i < keys.size(); ++i) {
    const Ctx c = kctx.index(i);
    const Json& k = keys[i];
    allowKeys(k, c, {"time", "value", "ease", "in", "out", "fixed_deg", "axis", "angle_deg"});
    RawKey key;
    if (!k.contains("time")) c.fail("missing key 'time'");
    key.time = number(k.at("time"), c.key("time"));
    if (t.type == TrackType::kRotation) {
      // A quaternion "value": [w, x, y, z], or "fixed_deg": [x, y, z], or "axis" + "angle_deg".
      const int forms = k.contains("value") + k.contains("fixed_deg") + (k.contains("axis") || k.contains("angle_deg"));
      if (forms != 1)
        c.fail("give exactly one of 'value' [w, x, y, z], 'fixed_deg' [x, y, z], or 'axis' + 'angle_deg'");
      Quaternion q;
      if (k.contains("value")) {
        const Eigen::VectorXd v = vector(k.at("value"), c.key("value"), 4);
        if (!(v.norm() > 0.0)) c.key("value").fail("a rotation quaternion must not be zero");
        q = Quaternion(v[0], v[1], v[2], v[3]);
      } else if (k.contains("fixed_deg")) {
        q = fixedAnglesToQuaternion(vector3(k.at("fixed_deg"), c.key("fixed_deg")) * (std::numbers::pi / 180.0));
      } else {
        if (!k.contains("axis") || !k.contains("angle_deg")) c.fail("'axis' and 'angle_deg' go together");
        const Eigen::Vector3d axis = vector3(k.at("axis"), c.key("axis"));
        if (!(axis.norm() > 0.0)) c.key("axis").fail("the rotation axis must not be zero");
        q = axisAngleToQuaternion(axis, number(k.at("angle_deg"), c.key("angle_deg")) * (std::numbers::pi / 180.0));
      }
      key.value = Eigen::Vector4d(q.w(), q.x(), q.y(), q.z());
    } else {
      for (const char* r : {"fixed_deg", "axis", "angle_deg"}) {
        if (k.contains(r)) c.fail(std::string("'") + r + "' is only used by rotation tracks");
      }
      if (!k.contains("value")) c.fail("missing key 'value'");
      const Json& v = k.at("value");
      if (t.type == TrackType::kScalar) {
        if (v.is_array()) {
          key.value = vector(v, c.key("value"), 1);
        } else {
          key.value = Eigen::VectorXd::Constant(1, number(v, c.key("value")));
        }
      } else {
        key.value = vector(v, c.key("value"), dim);
        dim = key.value.size();
      }
    }
    if (k.contains("ease")) key.ease = easeFrom(k.at("ease"), c.key("ease"));
    if (k.contains("in")) key.in_handle = vector(k.at("in"), c.key("in"), dim);
    if (k.contains("out")) key.out_handle = vector(k.at("out"), c.key("out"), dim);
    t.keys.push_back(std::move(key));
  }
  t.validate(ctx.prefix());
  return t;
}

RawCameraPath cameraPathFrom(const Json& j, const Ctx& ctx) {
  allowKeys(j, ctx,
            {"position", "arc_length", "speed", "start_time", "end_time", "view", "center", "target_path", "up", "tilt",
             "fov_deg", "ortho_height"});
  RawCameraPath p;
  if (!j.contains("position")) ctx.fail("missing key 'position'");
  p.position = curveObject(j.at("position"), ctx.key("position"));
  if (j.contains("arc_length")) {
    const auto o = arcLengthFrom(j.at("arc_length"), ctx.key("arc_length"));
    if (o) p.arc_length = *o;
  }
  if (j.contains("speed")) p.speed = easeFrom(j.at("speed"), ctx.key("speed"));
  p.start_time = numberOr(j, "start_time", p.start_time, ctx);
  p.end_time = numberOr(j, "end_time", p.end_time, ctx);
  if (j.contains("view")) p.view = enumValue(j.at("view"), ctx.key("view"), kViewModes);
  if (j.contains("center")) p.center = vector3(j.at("center"), ctx.key("center"));
  if (j.contains("target_path")) p.target_path = curveObject(j.at("target_path"), ctx.key("target_path"));
  if (j.contains("up")) p.up = vector3(j.at("up"), ctx.key("up"));
  if (j.contains("tilt")) p.tilt_deg = trackFrom(j.at("tilt"), ctx.key("tilt"));
  p.fov_deg = numberOr(j, "fov_deg", p.fov_deg, ctx);
  p.ortho_height = numberOr(j, "ortho_height", p.ortho_height, ctx);
  return p;
}

}  // namespace

Ease parseEase(std::string_view json_text, const std::string& where) {
  return easeFrom(io::parseJson(json_text, where), Ctx{where, ""});
}

RawCurve parseCurve(std::string_view json_text, const std::string& where) {
  const Json j = io::parseJson(json_text, where);
  const Ctx ctx{where, ""};
  allowKeys(j, ctx, {"curve", "points", "times", "arc_length"});
  return curveFrom(j, ctx);
}

RawTrack parseTrack(std::string_view json_text, const std::string& where) {
  return trackFrom(io::parseJson(json_text, where), Ctx{where, ""});
}

RawCameraPath parseCameraPath(std::string_view json_text, const std::string& where) {
  return cameraPathFrom(io::parseJson(json_text, where), Ctx{where, ""});
}

AnimSpec parseAnimSpec(std::string_view json_text, const std::string& where) {
  Json j = io::parseJson(json_text, where);
  const Ctx ctx{where, ""};
  if (!j.is_object()) ctx.fail("expected an object with 'ease', 'curve', 'track' or 'camera_path'");
  // Specs written before the format was versioned have no "version": they are version 1.
  io::formatVersion(j, ctx, "animation specs", 1, kAnimSpecVersion, /*missing=*/1);
  j.erase("version");
  const int kinds = j.contains("ease") + j.contains("curve") + j.contains("track") + j.contains("camera_path");
  if (kinds != 1) ctx.fail("expected exactly one of the keys 'ease', 'curve', 'track', 'camera_path'");
  AnimSpec spec;
  if (j.contains("ease")) {
    spec.kind = AnimSpec::Kind::kEase;
    spec.ease = easeFrom(j, ctx);
  } else if (j.contains("curve")) {
    spec.kind = AnimSpec::Kind::kCurve;
    allowKeys(j, ctx, {"curve", "points", "times", "arc_length"});
    spec.curve = curveFrom(j, ctx);
    if (j.contains("arc_length")) spec.arc_length = arcLengthFrom(j.at("arc_length"), ctx.key("arc_length"));
  } else if (j.contains("track")) {
    spec.kind = AnimSpec::Kind::kTrack;
    allowKeys(j, ctx, {"track"});
    spec.track = trackFrom(j.at("track"), ctx.key("track"));
  } else {
    spec.kind = AnimSpec::Kind::kCameraPath;
    allowKeys(j, ctx, {"camera_path"});
    spec.camera_path = cameraPathFrom(j.at("camera_path"), ctx.key("camera_path"));
  }
  return spec;
}

AnimSpec loadAnimSpec(const std::string& path) {
  return parseAnimSpec(readFileLimited(path, "animation spec", kMaxJsonFileBytes), path);
}

}  // namespace vdg::anim
