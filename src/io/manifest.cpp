// The model manifest *.vdg.json (format documented in docs/model-format.md).
#include "vdg/io/manifest.h"

#include <filesystem>

#include "camera_fields.h"
#include "json_reader.h"
#include "vdg/geom/error.h"
#include "vdg/io/atomic_file.h"
#include "vdg/io/json_text.h"
#include "vdg/io/obj.h"
#include "vdg/io/read_file.h"

namespace vdg {
namespace {

namespace fs = std::filesystem;
using io::Ctx;
using io::Json;

constexpr std::pair<const char*, Uncovered> kUncoveredModes[] = {
    {"base", Uncovered::Base}, {"cosine", Uncovered::Cosine}, {"cosine2", Uncovered::Cosine2}};

TriMesh readReferencedMesh(const fs::path& folder, const std::string& relative, const std::string& where) {
  const fs::path path = fs::path(relative).is_absolute() ? fs::path(relative) : folder / relative;
  try {
    return readMesh(path.string());
  } catch (const Error& e) {
    throw Error(where + ": " + e.what());
  }
}

}  // namespace

RawViewDependentModel parseManifest(const std::string& text, const std::string& source) {
  const Json doc = io::parseJson(text, source);
  const Ctx top{source, ""};
  io::formatVersion(doc, top, "model manifests", 1, kManifestVersion);
  io::allowKeys(doc, top,
                {"version", "base", "keys", "sharpness", "uncovered", "base_falloff_deg", "center", "comment"});

  RawViewDependentModel model;
  model.source = source;
  if (!doc.contains("base")) top.fail("missing 'base' (the base mesh file)");
  model.base_path = io::string(doc.at("base"), top.key("base"));
  if (model.base_path.empty()) top.key("base").fail("expected a mesh file name, got an empty string");
  if (doc.contains("comment")) model.comment = io::string(doc.at("comment"), top.key("comment"));
  if (doc.contains("sharpness")) model.sharpness = io::number(doc.at("sharpness"), top.key("sharpness"));
  if (doc.contains("uncovered"))
    model.sphere.uncovered = io::enumValue(doc.at("uncovered"), top.key("uncovered"), kUncoveredModes);
  if (doc.contains("base_falloff_deg"))
    model.sphere.base_falloff_deg = io::number(doc.at("base_falloff_deg"), top.key("base_falloff_deg"));
  if (doc.contains("center")) model.center = io::vector3(doc.at("center"), top.key("center"));

  if (!doc.contains("keys") || !doc.at("keys").is_array())
    top.fail("missing 'keys' (an array of {mesh, view | camera, name})");
  const Json& keys = doc.at("keys");
  if (keys.size() > kMaxKeys)
    top.key("keys").fail("has " + std::to_string(keys.size()) + " keys, more than the limit of " +
                         std::to_string(kMaxKeys));
  for (std::size_t k = 0; k < keys.size(); ++k) {
    const Json& entry = keys[k];
    Ctx ctx = top.key("keys").index(k);
    io::allowKeys(entry, ctx, {"name", "mesh", "view", "camera", "frame"});
    RawKey key;
    key.mesh_path = io::string(io::required(entry, "mesh", ctx), ctx.key("mesh"));
    if (key.mesh_path.empty()) ctx.key("mesh").fail("expected a mesh file name, got an empty string");
    key.name = entry.contains("name") ? io::string(entry.at("name"), ctx.key("name"))
                                      : fs::path(key.mesh_path).stem().string();
    ctx = ctx.labelled("key '" + key.name + "' (keys[" + std::to_string(k) + "])");
    if (entry.contains("frame"))
      ctx.fail("'frame' needs an animated base model, which this version of vdg does not read yet");
    const bool has_view = entry.contains("view"), has_camera = entry.contains("camera");
    if (has_view == has_camera) ctx.fail("give exactly one of 'view' [x, y, z] or 'camera' {eye, target, ...}");
    if (has_view) key.view = io::vector3(entry.at("view"), ctx.key("view"));
    if (has_camera) key.camera = io::cameraFrom(entry.at("camera"), ctx.key("camera"));
    model.keys.push_back(std::move(key));
  }
  return model;
}

RawViewDependentModel loadManifest(const std::string& path) {
  RawViewDependentModel model = parseManifest(readFileLimited(path, "model", kMaxJsonFileBytes), path);
  const fs::path folder = fs::path(path).parent_path();
  model.base = readReferencedMesh(folder, model.base_path, path + ": base");
  for (std::size_t k = 0; k < model.keys.size(); ++k) {
    RawKey& key = model.keys[k];
    key.mesh =
        readReferencedMesh(folder, key.mesh_path, path + ": key '" + key.name + "' (keys[" + std::to_string(k) + "])");
  }
  model.resolveViews();
  model.validate();
  return model;
}

std::string formatManifest(const RawViewDependentModel& model) {
  nlohmann::ordered_json doc;
  doc["version"] = kManifestVersion;
  if (!model.comment.empty()) doc["comment"] = model.comment;
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
      entry["camera"] = io::cameraJson(*key.camera);
    else
      entry["view"] = {key.view.x(), key.view.y(), key.view.z()};
    keys.push_back(std::move(entry));
  }
  doc["keys"] = std::move(keys);
  return compactScalarArrays(doc.dump(2)) + "\n";
}

void saveManifest(const std::string& path, const RawViewDependentModel& model) {
  writeFileAtomically(path, formatManifest(model));
}

}  // namespace vdg
