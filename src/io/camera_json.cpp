#include "vdg/io/camera_json.h"

#include "camera_fields.h"
#include "vdg/geom/normalize.h"
#include "vdg/io/atomic_file.h"
#include "vdg/io/json_text.h"
#include "vdg/io/read_file.h"

namespace vdg {
namespace io {

Camera cameraFrom(const Json& value, const Ctx& ctx, const char* also_allowed) {
  if (!value.is_object())
    ctx.fail("expected an object {eye, target, up, fov_deg | ortho_height}, got " + describe(value));
  if (also_allowed)
    allowKeys(value, ctx, {"eye", "target", "up", "fov_deg", "ortho_height", also_allowed});
  else
    allowKeys(value, ctx, {"eye", "target", "up", "fov_deg", "ortho_height"});
  Camera camera;
  camera.eye = vector3(required(value, "eye", ctx), ctx.key("eye"));
  camera.target = vector3(required(value, "target", ctx), ctx.key("target"));
  if (value.contains("up")) camera.up = vector3(value.at("up"), ctx.key("up"));
  const bool has_fov = value.contains("fov_deg"), has_ortho = value.contains("ortho_height");
  if (has_fov == has_ortho) ctx.fail("give exactly one of 'fov_deg' (perspective) or 'ortho_height' (parallel)");
  if (has_fov) {
    camera.fov_deg = number(value.at("fov_deg"), ctx.key("fov_deg"));
    if (!(camera.fov_deg > 0.0 && camera.fov_deg < 180.0)) ctx.key("fov_deg").fail("must be in (0, 180) degrees");
  } else {
    camera.fov_deg = 0.0;
    camera.ortho_height = number(value.at("ortho_height"), ctx.key("ortho_height"));
    if (!(camera.ortho_height > 0.0)) ctx.key("ortho_height").fail("must be positive");
  }
  withContext(ctx, [&] { return cameraFrame(camera); });
  return camera;
}

nlohmann::ordered_json cameraJson(const Camera& camera) {
  nlohmann::ordered_json j;
  j["eye"] = {camera.eye.x(), camera.eye.y(), camera.eye.z()};
  j["target"] = {camera.target.x(), camera.target.y(), camera.target.z()};
  j["up"] = {camera.up.x(), camera.up.y(), camera.up.z()};
  if (camera.isOrtho())
    j["ortho_height"] = camera.ortho_height;
  else
    j["fov_deg"] = camera.fov_deg;
  return j;
}

}  // namespace io

Camera parseCameraJson(const std::string& text, const std::string& where) {
  return io::cameraFrom(io::parseJson(text, where), io::Ctx{where, ""});
}

std::string cameraToJson(const Camera& camera) { return io::cameraJson(camera).dump(); }

Camera readCameraFile(const std::string& path) {
  const io::Json doc = io::readJsonFile(path, "camera");
  const io::Ctx ctx{path, ""};
  io::formatVersion(doc, ctx, "camera files", 1, kCameraFileVersion, /*missing=*/1);
  return io::cameraFrom(doc, ctx, "version");
}

void writeCameraFile(const std::string& path, const Camera& camera) {
  nlohmann::ordered_json j;
  j["version"] = kCameraFileVersion;
  j.update(io::cameraJson(camera));
  const std::string text = compactScalarArrays(j.dump(2)) + "\n";
  writeFileAtomically(path, [&](std::ostream& out) { out << text; });
}

std::vector<Eigen::Vector3d> parseViewList(const std::string& text, const std::string& where,
                                           const Eigen::Vector3d& center) {
  const io::Json doc = io::parseJson(text, where);
  const io::Ctx top{where, ""};
  if (!doc.is_array()) top.fail("expected an array of views [x, y, z], got " + io::describe(doc));
  std::vector<Eigen::Vector3d> views;
  views.reserve(doc.size());
  for (std::size_t i = 0; i < doc.size(); ++i) {
    const io::Ctx ctx = top.index(i);
    const io::Json& item = doc[i];
    bool eye = false;
    Eigen::Vector3d v;
    if (item.is_object()) {
      io::allowKeys(item, ctx, {"view", "eye"});
      eye = item.contains("eye");
      if (eye == item.contains("view")) ctx.fail("expected one of 'view' or 'eye'");
      v = io::vector3(item.at(eye ? "eye" : "view"), ctx.key(eye ? "eye" : "view"));
    } else {
      v = io::vector3(item, ctx);
    }
    const Eigen::Vector3d d = eye ? Eigen::Vector3d(v - center) : v;
    const std::optional<Eigen::Vector3d> unit = d.allFinite() ? normalizedOrNone(d) : std::nullopt;
    if (!unit) ctx.fail(eye ? "the eye is at the model centre (or too far from it)" : "the view direction is zero");
    views.push_back(*unit);
  }
  return views;
}

std::vector<Eigen::Vector3d> parseEyeList(const std::string& text, const std::string& where) {
  const io::Json doc = io::parseJson(text, where);
  const io::Ctx top{where, ""};
  if (!doc.is_array()) top.fail("expected an array of eyes {\"eye\": [x, y, z]}, got " + io::describe(doc));
  std::vector<Eigen::Vector3d> eyes;
  eyes.reserve(doc.size());
  for (std::size_t i = 0; i < doc.size(); ++i) {
    const io::Ctx ctx = top.index(i);
    const io::Json& item = doc[i];
    if (!item.is_object() || !item.contains("eye"))
      ctx.fail("the model weighs eye positions ('positions' space): expected {\"eye\": [x, y, z]}, not a direction");
    io::allowKeys(item, ctx, {"eye"});
    const Eigen::Vector3d eye = io::vector3(item.at("eye"), ctx.key("eye"));
    if (!eye.allFinite()) ctx.key("eye").fail("expected finite numbers");
    eyes.push_back(eye);
  }
  return eyes;
}

}  // namespace vdg
