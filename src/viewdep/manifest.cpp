// The model manifest *.vdg.json (format documented in docs/model-format.md).
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "vdg/geom/atomic_file.h"
#include "vdg/geom/error.h"
#include "vdg/geom/json_text.h"
#include "vdg/geom/obj_io.h"
#include "vdg/viewdep/model.h"

namespace vdg {
namespace {

using nlohmann::json;
namespace fs = std::filesystem;

// nlohmann's messages start with "[json.exception.type_error.302] "; keep what follows.
std::string cleanJsonMessage(const std::string& what) {
  const auto close = what.find("] ");
  return close == std::string::npos ? what : what.substr(close + 2);
}

void checkFields(const json& object, const std::set<std::string>& allowed, const std::string& where) {
  for (const auto& [name, value] : object.items()) {
    if (!allowed.count(name)) {
      std::string list;
      for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
      throw Error(where + ": unknown field '" + name + "' (expected one of: " + list + ")");
    }
  }
}

double number(const json& value, const std::string& where) {
  if (!value.is_number()) throw Error(where + ": expected a number, got " + std::string(value.type_name()));
  const double v = value.get<double>();
  if (!std::isfinite(v)) throw Error(where + ": number is not finite");
  return v;
}

Eigen::Vector3d vec3(const json& value, const std::string& where) {
  if (!value.is_array() || value.size() != 3) throw Error(where + ": expected an array of 3 numbers [x, y, z]");
  return {number(value[0], where + "[0]"), number(value[1], where + "[1]"), number(value[2], where + "[2]")};
}

std::string string(const json& value, const std::string& where) {
  if (!value.is_string()) throw Error(where + ": expected a string, got " + std::string(value.type_name()));
  return value.get<std::string>();
}

Camera parseCamera(const json& value, const std::string& where) {
  if (!value.is_object()) throw Error(where + ": expected an object {eye, target, up, fov_deg | ortho_height}");
  checkFields(value, {"eye", "target", "up", "fov_deg", "ortho_height"}, where);
  Camera camera;
  if (!value.contains("eye")) throw Error(where + ": missing 'eye'");
  camera.eye = vec3(value["eye"], where + ".eye");
  if (!value.contains("target")) throw Error(where + ": missing 'target'");
  camera.target = vec3(value["target"], where + ".target");
  if (value.contains("up")) camera.up = vec3(value["up"], where + ".up");
  const bool has_fov = value.contains("fov_deg"), has_ortho = value.contains("ortho_height");
  if (has_fov == has_ortho)
    throw Error(where + ": give exactly one of 'fov_deg' (perspective) or 'ortho_height' (parallel)");
  if (has_fov) {
    camera.fov_deg = number(value["fov_deg"], where + ".fov_deg");
    if (!(camera.fov_deg > 0.0 && camera.fov_deg < 180.0)) throw Error(where + ".fov_deg: must be in (0, 180) degrees");
  } else {
    camera.ortho_height = number(value["ortho_height"], where + ".ortho_height");
    if (!(camera.ortho_height > 0.0)) throw Error(where + ".ortho_height: must be positive");
  }
  try {
    (void)cameraFrame(camera);
  } catch (const Error& e) {
    throw Error(where + ": " + e.what());
  }
  return camera;
}

json cameraJson(const Camera& camera) {
  json j;
  j["eye"] = {camera.eye.x(), camera.eye.y(), camera.eye.z()};
  j["target"] = {camera.target.x(), camera.target.y(), camera.target.z()};
  j["up"] = {camera.up.x(), camera.up.y(), camera.up.z()};
  if (camera.isOrtho())
    j["ortho_height"] = camera.ortho_height;
  else
    j["fov_deg"] = camera.fov_deg;
  return j;
}

Uncovered parseUncovered(const json& value, const std::string& where) {
  const std::string s = string(value, where);
  if (s == "base") return Uncovered::Base;
  if (s == "cosine") return Uncovered::Cosine;
  if (s == "cosine2") return Uncovered::Cosine2;
  throw Error(where + ": unknown value '" + s + "' (expected \"base\", \"cosine\" or \"cosine2\")");
}

TriMesh readReferencedMesh(const fs::path& folder, const std::string& relative, const std::string& where) {
  const fs::path path = fs::path(relative).is_absolute() ? fs::path(relative) : folder / relative;
  try {
    return readMesh(path.string());
  } catch (const Error& e) {
    throw Error(where + ": " + e.what());
  }
}

}  // namespace

Camera parseCameraJson(const std::string& text, const std::string& where) {
  json doc;
  try {
    doc = json::parse(text);
  } catch (const json::exception& e) {
    throw Error(where + ": not valid JSON: " + cleanJsonMessage(e.what()));
  }
  return parseCamera(doc, where);
}

std::string cameraToJson(const Camera& camera) { return cameraJson(camera).dump(); }

RawViewDependentModel loadManifest(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path + ": cannot open model file (no such file?)");
  json doc;
  try {
    doc = json::parse(in);
  } catch (const json::exception& e) {
    throw Error(path + ": not valid JSON: " + cleanJsonMessage(e.what()));
  }
  if (!doc.is_object()) throw Error(path + ": expected a JSON object at the top level");
  checkFields(doc, {"version", "base", "keys", "sharpness", "uncovered", "base_falloff_deg", "center", "comment"},
              path);
  if (!doc.contains("version"))
    throw Error(path + ": missing 'version' (this vdg reads version " + std::to_string(kManifestVersion) + ")");
  if (!doc["version"].is_number_integer() || doc["version"].get<int>() != kManifestVersion)
    throw Error(path + ": 'version' is " + doc["version"].dump() + ", but this vdg reads version " +
                std::to_string(kManifestVersion));

  RawViewDependentModel model;
  model.source = path;
  const fs::path folder = fs::path(path).parent_path();
  if (!doc.contains("base")) throw Error(path + ": missing 'base' (the base mesh file)");
  model.base_path = string(doc["base"], path + ": 'base'");
  model.base = readReferencedMesh(folder, model.base_path, path + ": base");
  if (doc.contains("sharpness")) model.sharpness = number(doc["sharpness"], path + ": 'sharpness'");
  if (doc.contains("uncovered")) model.sphere.uncovered = parseUncovered(doc["uncovered"], path + ": 'uncovered'");
  if (doc.contains("base_falloff_deg"))
    model.sphere.base_falloff_deg = number(doc["base_falloff_deg"], path + ": 'base_falloff_deg'");
  if (doc.contains("center")) model.center = vec3(doc["center"], path + ": 'center'");

  if (!doc.contains("keys") || !doc["keys"].is_array())
    throw Error(path + ": missing 'keys' (an array of {mesh, view | camera, name})");
  const json& keys = doc["keys"];
  for (std::size_t k = 0; k < keys.size(); ++k) {
    const json& entry = keys[k];
    std::string where = path + ": keys[" + std::to_string(k) + "]";
    if (!entry.is_object()) throw Error(where + ": expected an object {mesh, view | camera, name}");
    checkFields(entry, {"name", "mesh", "view", "camera", "frame"}, where);
    RawKey key;
    if (!entry.contains("mesh")) throw Error(where + ": missing 'mesh'");
    key.mesh_path = string(entry["mesh"], where + ".mesh");
    key.name =
        entry.contains("name") ? string(entry["name"], where + ".name") : fs::path(key.mesh_path).stem().string();
    where = path + ": key '" + key.name + "' (keys[" + std::to_string(k) + "])";
    if (entry.contains("frame"))
      throw Error(where + ": 'frame' needs an animated base model, which this version of vdg does not read yet");
    const bool has_view = entry.contains("view"), has_camera = entry.contains("camera");
    if (has_view == has_camera)
      throw Error(where + ": give exactly one of 'view' [x, y, z] or 'camera' {eye, target, ...}");
    if (has_view) key.view = vec3(entry["view"], where + ".view");
    if (has_camera) key.camera = parseCamera(entry["camera"], where + ".camera");
    key.mesh = readReferencedMesh(folder, key.mesh_path, where);
    model.keys.push_back(std::move(key));
  }
  model.resolveViews();
  model.validate();
  return model;
}

void saveManifest(const std::string& path, const RawViewDependentModel& model) {
  nlohmann::ordered_json doc;
  doc["version"] = kManifestVersion;
  doc["base"] = model.base_path;
  if (model.center) doc["center"] = {model.center->x(), model.center->y(), model.center->z()};
  doc["sharpness"] = model.sharpness;
  doc["uncovered"] = uncoveredName(model.sphere.uncovered);
  if (model.sphere.base_falloff_deg != ViewSphereSettings{}.base_falloff_deg)
    doc["base_falloff_deg"] = model.sphere.base_falloff_deg;
  nlohmann::ordered_json keys = nlohmann::ordered_json::array();
  for (const RawKey& key : model.keys) {
    nlohmann::ordered_json entry;
    entry["name"] = key.name;
    entry["mesh"] = key.mesh_path;
    if (key.camera)
      entry["camera"] = cameraJson(*key.camera);
    else
      entry["view"] = {key.view.x(), key.view.y(), key.view.z()};
    keys.push_back(std::move(entry));
  }
  doc["keys"] = std::move(keys);
  const std::string text = compactScalarArrays(doc.dump(2)) + "\n";
  writeFileAtomically(path, [&](std::ostream& out) { out << text; });
}

}  // namespace vdg
