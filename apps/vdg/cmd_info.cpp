// vdg info MODEL [--json] | vdg info MESH.obj [--json] | vdg info FILE.gltf|FILE.glb
// vdg info MODEL --sphere-map OUT.png [--size WxH] [--frame F] [--json]      (where to key next)
// vdg info MODEL --check-intersections [--samples N] [--frames A-B] [--json] (no vertex through the mesh)
//
// An animated model (manifest "base_animation") is described by its base animation (source,
// frames, fps, loop, offsets) and its key views, each with its keys and their key frames. A mesh
// (and a model's base, and a glTF file's default mesh) is described with its materials (name,
// base colour, texture and whether it loaded) and whether the file gave normals; problems with
// material libraries and textures are printed as "warning: ..." lines on stderr.
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <limits>
#include <memory>
#include <nlohmann/json.hpp>
#include <numbers>
#include <optional>
#include <span>

#include "cli.h"
#include "vdg/geom/error.h"
#include "vdg/io/gltf.h"
#include "vdg/io/gltf_export.h"
#include "vdg/io/gltf_interactivity.h"
#include "vdg/io/mesh.h"
#include "vdg/io/model.h"
#include "vdg/render/sphere_map_image.h"
#include "vdg/viewdep/animated_model.h"
#include "vdg/viewdep/intersection_check.h"
#include "vdg/viewdep/model.h"
#include "vdg/viewdep/sphere_map.h"

namespace vdg::cli {
namespace {

// Things an artist should know about a model that still loads, from its viewing sphere (the first
// `count` points are the key views, named by `name(i)`) and each key's count of moved vertices.
// Each kind of per-key or per-pair warning is listed at most kMaxListed times, then summed up in
// one line: a model with thousands of keys must not print (or hold) a warning for every pair.
// Close pairs read "PAIR_PREFIX'name(j)' and 'name(k)' are only ...".
template <typename ViewName>
std::vector<std::string> sphereWarnings(const ViewSphere& sphere, std::size_t count, const std::string& pair_prefix,
                                        ViewName name, const std::vector<std::string>& unmoved_keys) {
  std::vector<std::string> warnings;
  constexpr double kLowCoverage = 0.25;  // below this, most views show the plain base model
  constexpr std::size_t kMaxListed = 20;
  // Counting stops here: past a million close pairs the exact number says nothing more.
  constexpr std::size_t kMaxCounted = 1000000;
  for (std::size_t k = 0; k < std::min(unmoved_keys.size(), kMaxListed); ++k)
    warnings.push_back("key '" + unmoved_keys[k] + "' moves no vertex (it is identical to the base)");
  if (unmoved_keys.size() > kMaxListed)
    warnings.push_back("... and " + std::to_string(unmoved_keys.size() - kMaxListed) +
                       " more keys that move no vertex");
  // Nearly the same direction (viewdep decides: kNearlySameViewDeg), found through a grid on the
  // sphere (O(n log n) plus the pairs counted), not all n^2 pairs.
  std::vector<NearlySameViewPair> pairs;
  const std::size_t close = nearlySameViewPairs(sphere.points().first(count), kMaxListed, kMaxCounted, pairs);
  for (const NearlySameViewPair& p : pairs)
    warnings.push_back(pair_prefix + "'" + name(p.j) + "' and '" + name(p.i) + "' are only " +
                       std::to_string(p.angle_deg).substr(0, 4) +
                       " degrees apart (a near-degenerate hull triangle): the weights flip between them, so the "
                       "blend will be abrupt");
  if (close > kMaxListed)
    warnings.push_back("... and " + std::string(close >= kMaxCounted ? "at least " : "") +
                       std::to_string(close - kMaxListed) + " more close pairs of keys");
  if (sphere.coveredFraction() < kLowCoverage)
    warnings.push_back("real keys cover only " +
                       std::to_string(static_cast<int>(std::lround(100 * sphere.coveredFraction()))) +
                       "% of the viewing sphere; elsewhere the model blends towards the base");
  return warnings;
}

// A model just started (a manifest with no keys yet): its base, and the command that adds a key.
void describeKeyless(const std::string& path, const RawViewDependentModel& raw, bool json) {
  const std::string next = "add the first key with 'vdg deform " + path +
                           " --key NAME --view X,Y,Z --ops EDITS.json' or in 'vdg studio " + path +
                           "' (docs/tutorial.md)";
  if (json) {
    nlohmann::ordered_json out;
    out["model"] = path;
    out["base"] = raw.base_path;
    out["vertices"] = raw.base.vertexCount();
    out["triangles"] = raw.base.triangleCount();
    out["keys"] = nlohmann::ordered_json::array();
    out["warnings"] = {"the model has no keys: " + next};
    std::printf("%s\n", out.dump(2).c_str());
    return;
  }
  std::printf("model      %s\n", path.c_str());
  std::printf("base       %s: %zu vertices, %zu triangles\n", raw.base_path.c_str(), raw.base.vertexCount(),
              raw.base.triangleCount());
  std::printf("keys       0\n");
  std::printf("warning: the model has no keys (it shows its base from every view): %s\n", next.c_str());
}

std::vector<std::string> modelWarnings(const ViewDependentModel& model) {
  std::vector<std::string> unmoved;
  for (std::size_t k = 0; k < model.keyCount(); ++k)
    if (model.keyMovedCount(k) == 0) unmoved.push_back(model.keyName(k));
  return sphereWarnings(
      model.sphere(), model.keyCount(), "keys ", [&](std::size_t k) { return model.keyName(k); }, unmoved);
}

// Vertices whose offset (from the base at the key's frame) exceeds kMovedRel times the base's
// size (its bounding-box diagonal at frame 0). Unlike a static key, an animated key is compared
// with a base that vdg poses itself (skinning a glTF, say), and a key posed by another tool
// matches that pose only to float rounding: those differences are not moves.
constexpr double kMovedRel = 1e-5;
std::size_t movedCount(std::span<const float> offsets, double base_size) {
  const double threshold = kMovedRel * base_size;
  std::size_t moved = 0;
  for (std::size_t v = 0; 3 * v + 2 < offsets.size(); ++v)
    if (std::abs(offsets[3 * v]) > threshold || std::abs(offsets[3 * v + 1]) > threshold ||
        std::abs(offsets[3 * v + 2]) > threshold)
      ++moved;
  return moved;
}

double boundingDiagonal(std::span<const float> positions) {
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (std::size_t v = 0; 3 * v + 2 < positions.size(); ++v) {
    const Eigen::Vector3d p(positions[3 * v], positions[3 * v + 1], positions[3 * v + 2]);
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  return positions.empty() ? 0.0 : (hi - lo).norm();
}

// "front_f10, front_f30": the keys of one view of an animated model.
std::string viewKeys(const AnimatedViewDependentModel& model, std::size_t view) {
  std::string names;
  for (std::size_t j = 0; j < model.keyFrames(view).size(); ++j) names += (j ? ", " : "") + model.keyName(view, j);
  return names;
}

// Where an animated base comes from, in words: "glTF walker.glb, animation 0" or "OBJ sequence
// walk/f_%03d.obj, files 2..7".
std::string baseSource(const BaseAnimationSpec& spec) {
  if (!spec.gltf.empty())
    return "glTF " + spec.gltf + ", animation " + std::to_string(spec.animation) +
           (spec.mesh.empty() ? std::string() : ", mesh or node '" + spec.mesh + "'");
  return "OBJ sequence " + spec.obj_sequence + ", files " + std::to_string(spec.first) + ".." +
         std::to_string(spec.last);
}

// A float as the double with its shortest decimal form (0.2f as 0.2, not 0.20000000298023224).
double shortest(float value) {
  char buffer[32];
  const auto end = std::to_chars(buffer, buffer + sizeof(buffer), value).ptr;
  double out = value;
  std::from_chars(buffer, end, out);
  return out;
}

// Triangles per material of `mesh` (index k), and those without one at the end.
std::vector<std::size_t> materialTriangles(const TriMesh& mesh) {
  std::vector<std::size_t> count(mesh.materials.size() + 1, 0);
  for (std::size_t f = 0; f < mesh.triangleCount(); ++f) {
    const int k = f < mesh.face_materials.size() ? mesh.face_materials[f] : -1;
    ++count[k < 0 ? mesh.materials.size() : static_cast<std::size_t>(k)];
  }
  return count;
}

// The JSON fields of a mesh's surface (vdg info --json): file normals and materials.
void addSurfaceFields(const TriMesh& mesh, nlohmann::ordered_json& out) {
  out["file_normals"] = !mesh.normals.empty();
  const auto triangles = materialTriangles(mesh);
  nlohmann::ordered_json materials = nlohmann::ordered_json::array();
  for (std::size_t k = 0; k < mesh.materials.size(); ++k) {
    const Material& m = mesh.materials[k];
    nlohmann::ordered_json j;
    j["name"] = m.name;
    j["base_color"] = {shortest(m.base_color[0]), shortest(m.base_color[1]), shortest(m.base_color[2])};
    j["texture"] = m.texture_path.empty() ? nlohmann::ordered_json() : nlohmann::ordered_json(m.texture_path);
    j["texture_loaded"] = m.texture != nullptr;
    if (m.texture) j["texture_size"] = {m.texture->width, m.texture->height};
    j["triangles"] = triangles[k];
    materials.push_back(std::move(j));
  }
  out["materials"] = std::move(materials);
}

// The same as text lines.
void printSurface(const TriMesh& mesh) {
  std::printf("normals    %s\n", mesh.normals.empty() ? "none in the file (derived from the positions)"
                                                      : "from the file (they say which edges are hard)");
  const auto triangles = materialTriangles(mesh);
  std::printf("materials  %zu", mesh.materials.size());
  if (!mesh.materials.empty() && triangles.back() > 0)
    std::printf(" (%zu triangle%s without one)", triangles.back(), triangles.back() == 1 ? "" : "s");
  std::printf("\n");
  for (std::size_t k = 0; k < mesh.materials.size(); ++k) {
    const Material& m = mesh.materials[k];
    std::printf("  %-16s colour (%.3f, %.3f, %.3f), %zu triangle%s", ("'" + m.name + "'").c_str(), m.base_color[0],
                m.base_color[1], m.base_color[2], triangles[k], triangles[k] == 1 ? "" : "s");
    if (!m.texture_path.empty()) {
      if (m.texture)
        std::printf(", texture %s (%dx%d)", m.texture_path.c_str(), m.texture->width, m.texture->height);
      else
        std::printf(", texture %s (not loaded)", m.texture_path.c_str());
    }
    std::printf("\n");
  }
}

// Reads a mesh with its materials, printing the read's warnings on stderr.
TriMesh readMeshWarning(const std::string& path, std::vector<std::string>& warnings) {
  MeshReadOptions options;
  options.warnings = &warnings;
  TriMesh mesh = readMesh(path, options);
  for (const auto& w : warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
  return mesh;
}

// vdg info MESH.obj: the mesh alone.
void describeMesh(const std::string& path, bool json) {
  std::vector<std::string> warnings;
  const TriMesh mesh = readMeshWarning(path, warnings);
  if (json) {
    nlohmann::ordered_json out;
    out["mesh"] = path;
    out["vertices"] = mesh.vertexCount();
    out["triangles"] = mesh.triangleCount();
    out["uvs"] = !mesh.uvs.empty();
    addSurfaceFields(mesh, out);
    out["warnings"] = warnings;
    std::cout << out.dump(2) << "\n";
    return;
  }
  std::printf("mesh       %s: %zu vertices, %zu triangles\n", path.c_str(), mesh.vertexCount(), mesh.triangleCount());
  std::printf("uvs        %s\n",
              mesh.uvs.empty() ? "none" : (std::to_string(mesh.uvs.size() / 2) + " texture coordinates").c_str());
  printSurface(mesh);
}

// vdg info on an animated model (Rademacher 99, section 4): the base animation, and the key views
// with their key frames (each view is one point of the viewing sphere).
// The JSON fields static and animated models share (vdg info --json).
template <class Model>
void addShapeFields(const Model& model, nlohmann::ordered_json& out) {
  out["vertices"] = model.vertexCount();
  out["triangles"] = model.base().triangleCount();
  out["center"] = {model.center().x(), model.center().y(), model.center().z()};
  out["sharpness"] = model.sharpness();
  out["uncovered"] = uncoveredName(model.sphere().settings().uncovered);
  const ViewSphereSettings& sphere = model.sphere().settings();
  out["weights"] = weightSchemeName(sphere.scheme);
  if (sphere.scheme == WeightScheme::Rbf) {
    out["rbf_kernel"] = rbfKernelName(sphere.rbf_kernel);
    out["rbf_width_deg"] = sphere.rbf_width_deg;
  }
  addSurfaceFields(model.base(), out);
}

// The viewing sphere's fields that close both models' JSON, then the document itself.
void printWithSphereFields(const ViewSphere& sphere, const std::vector<std::string>& warnings,
                           nlohmann::ordered_json& out) {
  out["dummy_base_keys"] = sphere.points().size() - sphere.keyCount();
  out["hull_triangles"] = sphere.triangles().size();
  out["covered_fraction"] = sphere.coveredFraction();
  out["warnings"] = warnings;
  std::cout << out.dump(2) << "\n";
}

// The morph targets a glTF export of the model needs (`keys` targets, plus `frames` base frames of a
// "world"-offset animated model) and the engines whose cap that exceeds (docs/gltf-export.md,
// "Target count").
nlohmann::ordered_json exportTargetsJson(std::size_t keys, std::size_t frames) {
  nlohmann::ordered_json exceeds = nlohmann::ordered_json::array();
  for (const MorphTargetCap& cap : kMorphTargetCaps)
    if (keys + frames > cap.targets) exceeds.push_back(cap.engine);
  return {{"count", keys + frames}, {"keys", keys}, {"base_frames", frames}, {"exceeds", exceeds}};
}

void printExportTargets(std::size_t keys, std::size_t frames) {
  const std::size_t count = keys + frames;
  std::string parts =
      frames > 0 ? " (" + std::to_string(keys) + " keys + " + std::to_string(frames) + " base frames)" : std::string();
  const std::string over = morphTargetCapsExceeded(count);
  std::printf("export     %zu morph target%s in glTF%s; %s\n", count, count == 1 ? "" : "s", parts.c_str(),
              over.empty() ? "within every engine's cap (Bevy 64, three.js and Filament 256)"
                           : ("more than " + over + " take").c_str());
}

// The size of the KHR_interactivity graph `vdg export --interactivity` writes for the model
// (docs/interactivity.md), and its --json form.
InteractivitySize interactivityGraphSize(const ViewDependentModel& model) {
  InteractivitySize size;
  (void)interactivityGraphJson(interactivityInput(model), &size);
  return size;
}
// The rbf scheme's kernel and width after its name (" (gaussian, width 60 degrees; not exported)"),
// nothing for the other schemes.
std::string infoRbfSettingsText(const ViewSphere& sphere) {
  const ViewSphereSettings& s = sphere.settings();
  if (s.scheme != WeightScheme::Rbf) return "";
  char buffer[128];
  std::snprintf(buffer, sizeof(buffer), " (%s, width %g degrees; every key weighs; not exported to glTF)",
                rbfKernelName(s.rbf_kernel), s.rbf_width_deg);
  return buffer;
}

// The graph repeats the paper's linear weights only (kInteractivitySchemeRefusal).
// A positions model has no graph either: the graph weighs view directions (key_space.h).
bool linearWeights(const ViewDependentModel& model) {
  return model.sphere().settings().scheme == WeightScheme::Linear && model.weightSpace() == WeightSpace::Directions;
}

// vdg info --json: "space", and for a positions model its tetrahedra, hull faces and falloff.
void addSpaceFields(const ViewDependentModel& model, nlohmann::ordered_json& out) {
  out["space"] = weightSpaceName(model.weightSpace());
  if (const KeySpace* space = model.keySpace()) {
    out["tetrahedra"] = space->tetrahedronCount();
    out["hull_faces"] = space->hullFaceCount();
    out["falloff"] = space->falloff();
  }
}

// "directions", or "positions: T tetrahedra, F hull faces, D directions, falloff X" (key_space.h).
std::string weightSpaceText(const ViewDependentModel& model) {
  const KeySpace* space = model.keySpace();
  if (!space) return "directions";
  char buffer[160];
  std::snprintf(buffer, sizeof(buffer), "positions: %zu tetrahedra, %zu hull faces, %zu directions, falloff %g",
                space->tetrahedronCount(), space->hullFaceCount(), space->directionCount(), space->falloff());
  return buffer;
}
nlohmann::ordered_json interactivityJson(const ViewDependentModel& model) {
  const InteractivitySize size = interactivityGraphSize(model);
  return {{"nodes", size.nodes}, {"declarations", size.declarations}, {"types", size.types}, {"ops", size.ops}};
}

// The KHR_interactivity graph of a glTF file, if it has one; a malformed one is a warning (the file
// may come from another tool, and the rest of it is still described).
void printInteractivityOfFile(const std::string& path) {
  try {
    if (InteractivitySize graph; interactivitySizeOfGltfFile(path, graph))
      std::printf("KHR_interactivity: %s\n", interactivitySizeText(graph).c_str());
  } catch (const Error& e) {
    std::fprintf(stderr, "warning: %s\n", e.what());
  }
}

// "  (FILE)" after a key read from a mesh file; nothing for a key stored in a glTF model.
std::string meshNote(const std::string& mesh_path) { return mesh_path.empty() ? "" : "  (" + mesh_path + ")"; }
// "  drawing FILE (WxH)" after a key with a reference drawing (docs/drawing-textures.md).
std::string drawingNote(const RawKey& key) {
  if (!key.drawing) return "";
  return "  drawing " + key.drawing_path + " (" + std::to_string(key.drawing->width) + "x" +
         std::to_string(key.drawing->height) + ")";
}

// A static model's keys for --json: name, mesh file, unit view and moved vertices of each.
nlohmann::ordered_json keysJson(const ViewDependentModel& model, const RawViewDependentModel& raw) {
  nlohmann::ordered_json keys = nlohmann::ordered_json::array();
  for (std::size_t k = 0; k < model.keyCount(); ++k) {
    const auto& v = model.keyView(k);
    keys.push_back({{"name", model.keyName(k)},
                    {"mesh", raw.keys[k].mesh_path},
                    {"view", {v.x(), v.y(), v.z()}},
                    {"moved_vertices", model.keyMovedCount(k)}});
    if (!raw.keys[k].drawing_path.empty()) keys.back()["drawing"] = raw.keys[k].drawing_path;
  }
  return keys;
}
// vdg info on a model with parts (per-part key sets, docs/weights.md): the keys, then each part's
// vertices, keys and driving view. Nothing is exported (the glTF extras weigh one key set).
void describeParts(const std::string& path, const RawViewDependentModel& raw, const ViewDependentModel& model,
                   bool json) {
  const auto viewOf = [&](std::size_t p) {
    const auto& v = model.partView(p);
    return v ? nlohmann::ordered_json{v->x(), v->y(), v->z()} : nlohmann::ordered_json("main");
  };
  if (json) {
    nlohmann::ordered_json out;
    out["model"] = path;
    out["base"] = raw.base_path;
    out["weights"] = weightSchemeName(raw.sphere.scheme);
    out["export_targets"] = nullptr;
    addShapeFields(model, out);
    out["keys"] = keysJson(model, raw);
    out["parts"] = nlohmann::ordered_json::array();
    for (std::size_t p = 0; p < model.partCount(); ++p) {
      nlohmann::ordered_json keys = nlohmann::ordered_json::array();
      for (const std::size_t k : model.partKeys(p)) keys.push_back(model.keyName(k));
      out["parts"].push_back(
          {{"name", model.partName(p)}, {"vertices", model.partVertexCount(p)}, {"keys", keys}, {"view", viewOf(p)}});
    }
    std::cout << out.dump(2) << "\n";
    return;
  }
  std::printf("model      %s\n", path.c_str());
  std::printf("base       %s: %zu vertices, %zu triangles\n", raw.base_path.c_str(), model.vertexCount(),
              model.base().triangleCount());
  printSurface(model.base());
  std::printf("centre     (%.4g, %.4g, %.4g)\n", model.center().x(), model.center().y(), model.center().z());
  std::printf("sharpness  %g\n", model.sharpness());
  std::printf("uncovered  %s\n", uncoveredName(raw.sphere.uncovered));
  std::printf("weights    %s, per part\n", weightSchemeName(raw.sphere.scheme));
  std::printf("keys       %zu\n", model.keyCount());
  for (std::size_t k = 0; k < model.keyCount(); ++k) {
    const auto& v = model.keyView(k);
    std::printf("  %-16s view (%7.4f, %7.4f, %7.4f)  moves %zu vertices%s\n", model.keyName(k).c_str(), v.x(), v.y(),
                v.z(), model.keyMovedCount(k), meshNote(raw.keys[k].mesh_path).c_str());
  }
  std::printf("parts      %zu (the last holds the vertices and keys of no part)\n", model.partCount());
  for (std::size_t p = 0; p < model.partCount(); ++p) {
    std::string keys;
    for (const std::size_t k : model.partKeys(p)) keys += (keys.empty() ? "" : ", ") + model.keyName(k);
    const auto& v = model.partView(p);
    char view[96];
    if (v)
      std::snprintf(view, sizeof(view), "view (%.4f, %.4f, %.4f)", v->x(), v->y(), v->z());
    else
      std::snprintf(view, sizeof(view), "the main view");
    std::printf("  %-16s %zu vertices, follows %s, keys: %s\n", model.partName(p).c_str(), model.partVertexCount(p),
                view, keys.empty() ? "none (the base)" : keys.c_str());
  }
  std::printf("export     none: glTF extras weigh one key set for the whole mesh (docs/weights.md)\n");
}

void describeAnimated(const std::string& path, const RawViewDependentModel& raw,
                      const AnimatedViewDependentModel& model, bool json) {
  const BaseAnimationSpec& spec = *raw.base_animation;
  const bool gltf = !spec.gltf.empty();
  const ViewSphere& sphere = model.sphere();
  const std::size_t dummies = sphere.points().size() - sphere.keyCount();
  const double size = boundingDiagonal(model.base().positions);
  std::vector<std::string> unmoved;
  for (std::size_t i = 0; i < model.viewCount(); ++i)
    for (std::size_t j = 0; j < model.keyFrames(i).size(); ++j)
      if (movedCount(model.offsets(i, j), size) == 0) unmoved.push_back(model.keyName(i, j));
  const auto warnings = sphereWarnings(
      sphere, model.viewCount(), "the views of keys ", [&](std::size_t i) { return viewKeys(model, i); }, unmoved);
  if (json) {
    nlohmann::ordered_json out;
    out["model"] = path;
    nlohmann::ordered_json animation;
    if (gltf) {
      animation["gltf"] = spec.gltf;
      animation["animation"] = spec.animation;
      if (!spec.mesh.empty()) animation["mesh"] = spec.mesh;
      animation["fps"] = spec.fps;
    } else {
      animation["obj_sequence"] = spec.obj_sequence;
      animation["files"] = {spec.first, spec.last};
    }
    animation["frames"] = model.frameCount();
    animation["loop"] = model.loop();
    animation["skinned"] = model.skinned();
    out["base_animation"] = animation;
    out["offsets"] = offsetSpaceName(model.offsetSpace());
    out["export_targets"] = exportTargetsJson(raw.keys.size(), gltfTargetCount(model) - raw.keys.size());
    addShapeFields(model, out);
    out["views"] = nlohmann::ordered_json::array();
    for (std::size_t i = 0; i < model.viewCount(); ++i) {
      const auto& v = model.viewDirection(i);
      nlohmann::ordered_json keys = nlohmann::ordered_json::array();
      for (std::size_t j = 0; j < model.keyFrames(i).size(); ++j)
        keys.push_back({{"name", model.keyName(i, j)},
                        {"mesh", raw.keys[model.keyIndex(i, j)].mesh_path},
                        {"frame", model.keyFrames(i)[j]},
                        {"moved_vertices", movedCount(model.offsets(i, j), size)}});
      out["views"].push_back({{"view", {v.x(), v.y(), v.z()}}, {"keys", keys}});
    }
    printWithSphereFields(sphere, warnings, out);
    return;
  }
  std::printf("model      %s\n", path.c_str());
  std::printf("base       %s: %zu vertices, %zu triangles%s\n", baseSource(spec).c_str(), model.vertexCount(),
              model.base().triangleCount(), model.skinned() ? ", skinned" : "");
  std::string frames = std::to_string(model.frameCount()) + " frames";
  if (gltf) {
    char fps[64];
    std::snprintf(fps, sizeof(fps), " at %g fps", spec.fps);
    frames += fps;
  }
  std::printf("animation  %s, %s\n", frames.c_str(),
              model.loop() ? "loop (periodic time splines)" : "no loop (offsets held outside the key frames)");
  printSurface(model.base());
  std::printf("offsets    %s\n", offsetSpaceName(model.offsetSpace()));
  std::printf("centre     (%.4g, %.4g, %.4g)\n", model.center().x(), model.center().y(), model.center().z());
  std::printf("sharpness  %g\n", model.sharpness());
  std::printf("uncovered  %s\n", uncoveredName(sphere.settings().uncovered));
  std::printf("weights    %s\n", weightSchemeName(sphere.settings().scheme));
  std::printf("views      %zu (%zu keys)\n", model.viewCount(), raw.keys.size());
  for (std::size_t i = 0; i < model.viewCount(); ++i) {
    const auto& v = model.viewDirection(i);
    std::printf("  view (%7.4f, %7.4f, %7.4f)\n", v.x(), v.y(), v.z());
    for (std::size_t j = 0; j < model.keyFrames(i).size(); ++j)
      std::printf("    %-16s frame %-5d moves %zu vertices%s\n", model.keyName(i, j).c_str(), model.keyFrames(i)[j],
                  movedCount(model.offsets(i, j), size), meshNote(raw.keys[model.keyIndex(i, j)].mesh_path).c_str());
  }
  std::printf("hull       %zu triangles, %zu dummy base keys\n", sphere.triangles().size(), dummies);
  std::printf("coverage   %.1f%% of the viewing sphere lies in triangles of real keys\n",
              100.0 * sphere.coveredFraction());
  printExportTargets(raw.keys.size(), gltfTargetCount(model) - raw.keys.size());
  for (const auto& w : warnings) std::printf("warning: %s\n", w.c_str());
}

// vdg info MODEL --sphere-map OUT.png: where to key next (vdg/viewdep/sphere_map.h), the map as an
// image and its statistics on stdout (text, or JSON with --json).
struct SphereMapRequest {
  std::string output, size = "360x180";
  int frame = -1;
};

nlohmann::ordered_json directionJson(const Eigen::Vector3d& d) {
  return {{"view", {d.x(), d.y(), d.z()}},
          {"longitude_deg", SphereMap::longitudeDeg(d)},
          {"latitude_deg", SphereMap::latitudeDeg(d)}};
}

void reportSphereMap(const std::string& path, const SphereMapRequest& request, int frame, const SphereMap& map,
                     bool json) {
  const auto cell = static_cast<std::size_t>(map.suggested_cell);
  const Eigen::Vector3d& s = map.suggested;
  if (json) {
    nlohmann::ordered_json out;
    out["model"] = path;
    out["sphere_map"] = request.output;
    if (frame >= 0) out["frame"] = frame;
    out["size"] = {map.width, map.height};
    out["max_nearest_key_deg"] = map.max_nearest_deg;
    out["mean_nearest_key_deg"] = map.mean_nearest_deg;
    out["max_speed"] = map.max_speed;
    out["max_speed_at"] = directionJson(map.max_speed_view);
    out["uncovered_fraction"] = map.uncovered_fraction;
    nlohmann::ordered_json suggested = directionJson(s);
    suggested["need"] = map.need[cell];
    suggested["nearest_key_deg"] = map.nearest_key_deg[cell];
    suggested["speed"] = map.speed[cell];
    suggested["base_weight"] = map.uncovered[cell];
    out["suggested"] = suggested;
    std::cout << out.dump(2) << "\n";
    return;
  }
  std::printf("sphere map  %s: %dx%d cells (longitude x latitude, Y up, +Z at the centre) over a %d-pixel legend%s\n",
              request.output.c_str(), map.width, map.height, render::kSphereMapLegendHeight,
              frame >= 0 ? (", frame " + std::to_string(frame)).c_str() : "");
  std::printf(
      "colour     need 0 (dark blue) .. 0.5 (red) .. 1 (pale yellow); white dots: keys; cyan ring: suggested\n");
  std::printf("need       %g nearest-key angle / its max + %g base weight + %g speed / its max\n", kNeedAngleWeight,
              kNeedUncoveredWeight, kNeedSpeedWeight);
  std::printf("nearest    key angle: max %.1f deg, mean %.1f deg\n", map.max_nearest_deg, map.mean_nearest_deg);
  std::printf("speed      max %.4g model radii per degree at (%.3f, %.3f, %.3f)\n", map.max_speed,
              map.max_speed_view.x(), map.max_speed_view.y(), map.max_speed_view.z());
  std::printf("uncovered  %.1f%% of the sphere shows some base (weight > %g)\n", 100.0 * map.uncovered_fraction,
              kUncoveredWeight);
  std::printf(
      "suggested  view %.4f,%.4f,%.4f (longitude %.1f, latitude %.1f): need %.3f, nearest key %.1f deg, "
      "speed %.4g, base weight %.3f\n",
      s.x(), s.y(), s.z(), SphereMap::longitudeDeg(s), SphereMap::latitudeDeg(s), map.need[cell],
      map.nearest_key_deg[cell], map.speed[cell], map.uncovered[cell]);
}

void writeSphereMap(const std::string& path, const SphereMapRequest& request, bool json) {
  if (!hasExtension(request.output, ".png"))
    throw UsageError("--sphere-map: expected a .png file name, got " + quotedText(request.output));
  const ImageSize size = parseImageSize(request.size, 'x', kMaxSphereMapSide, "--size");
  if (isObjPath(path)) throw UsageError("--sphere-map: " + quotedText(path) + " is a mesh, not a model");
  const RawViewDependentModel described = openModel(path, {}, InputBuild::kRawOnly).raw;
  if (described.keys.empty()) throw Error(quotedText(path) + ": the model has no keys, so there is no map to draw");
  const OpenedInput input = openModel(path);
  SphereMapSettings settings;
  settings.width = size.width;
  settings.height = size.height;
  SphereMap map;
  if (input.animated) {
    const int n = input.animated->frameCount();
    if (request.frame >= n)
      throw UsageError("--frame: expected a frame in 0.." + std::to_string(n - 1) + " (the model has " +
                       std::to_string(n) + " frames), got " + std::to_string(request.frame));
    settings.frame = std::max(0, request.frame);
    map = computeSphereMap(*input.animated, settings);
  } else {
    if (request.frame >= 0)
      throw UsageError("--frame: " + quotedText(path) + " is not animated; --frame applies to animated models only");
    map = computeSphereMap(*input.model, settings);
  }
  render::writePng(request.output, render::sphereMapImage(map));
  reportSphereMap(path, request, input.animated ? settings.frame : -1, map, json);
}

// vdg info MODEL --check-intersections: the views (and frames) where the blend passes through
// itself and the base does not (vdg/viewdep/intersection_check.h). Exit status 0 with the report
// whatever it finds: it is a description, like the warnings above.
struct IntersectionRequest {
  bool check = false;
  int samples = 200;
  std::string frames;
};

// The key (static) or the keys of the view (animated) that a checked view is, or "".
std::string keyOfView(const OpenedInput& input, const IntersectingView& v) {
  if (v.key < 0) return "";
  const auto k = static_cast<std::size_t>(v.key);
  return input.animated ? viewKeys(*input.animated, k) : input.model->keyName(k);
}

std::string viewLabel(const OpenedInput& input, const IntersectingView& v) {
  if (v.key < 0) return "";
  return input.animated ? " (the view of " + keyOfView(input, v) + ")" : " (key '" + keyOfView(input, v) + "')";
}

void printIntersections(const std::string& path, const OpenedInput& input, const IntersectionReport& report,
                        bool json) {
  if (json) {
    nlohmann::ordered_json out;
    out["model"] = path;
    out["views_checked"] = report.views_checked;
    out["base_pairs"] = report.base_pairs;
    nlohmann::ordered_json views = nlohmann::ordered_json::array();
    for (const IntersectingView& v : report.views) {
      nlohmann::ordered_json j = {{"view", {v.view.x(), v.view.y(), v.view.z()}}, {"frame", v.frame}};
      if (v.key >= 0) j["key"] = keyOfView(input, v);
      j["new_pairs"] = v.new_pairs;
      j["example"] = {v.example.first, v.example.second};
      views.push_back(std::move(j));
    }
    out["views"] = views;
    out["worst"] = report.worst;
    std::cout << out.dump(2) << "\n";
    return;
  }
  std::printf("checked    %zu views%s for triangles passing through each other (not sharing a vertex)\n",
              report.views_checked, input.animated ? " x frames" : "");
  std::printf("base       %zu intersecting pair%s of its own (not reported below)\n", report.base_pairs,
              report.base_pairs == 1 ? "" : "s");
  std::printf("new        %zu view%s where the blend intersects itself and the base does not\n", report.views.size(),
              report.views.size() == 1 ? "" : "s");
  constexpr std::size_t kMaxListed = 20;  // text lists this many views; --json lists every one
  for (std::size_t i = 0; i < std::min(report.views.size(), kMaxListed); ++i) {
    const IntersectingView& v = report.views[i];
    std::printf("  view %.4f,%.4f,%.4f frame %d: %zu new pair%s (e.g. triangles %d and %d)%s\n", v.view.x(), v.view.y(),
                v.view.z(), v.frame, v.new_pairs, v.new_pairs == 1 ? "" : "s", v.example.first, v.example.second,
                viewLabel(input, v).c_str());
  }
  if (report.views.size() > kMaxListed)
    std::printf("  ... and %zu more (--json lists every one)\n", report.views.size() - kMaxListed);
  if (report.worst >= 0) {
    const IntersectingView& w = report.views[static_cast<std::size_t>(report.worst)];
    std::printf("worst      view %.4f,%.4f,%.4f frame %d: %zu new pairs%s\n", w.view.x(), w.view.y(), w.view.z(),
                w.frame, w.new_pairs, viewLabel(input, w).c_str());
  }
}

void checkModelIntersections(const std::string& path, const IntersectionRequest& request, bool json) {
  if (isObjPath(path)) throw UsageError("--check-intersections: " + quotedText(path) + " is a mesh, not a model");
  const RawViewDependentModel described = openModel(path, {}, InputBuild::kRawOnly).raw;
  if (described.keys.empty()) throw Error(quotedText(path) + ": the model has no keys, so there is nothing to check");
  const OpenedInput input = openModel(path);
  IntersectionCheckSettings settings;
  settings.samples = request.samples;
  IntersectionReport report;
  if (input.animated) {
    const AnimatedViewDependentModel& model = *input.animated;
    const int n = model.frameCount();
    if (!request.frames.empty()) {
      const FrameRange range = parseFrameRange(request.frames, "--frames");
      const int last = range.last < range.first ? n - 1 : range.last;
      if (range.first < 0 || last >= n)
        throw UsageError("--frames: expected frames in 0.." + std::to_string(n - 1) + ", got " +
                         quotedText(request.frames));
      for (int f = range.first; f <= last; ++f) settings.frames.push_back(f);
    } else {  // the frames that have keys
      for (std::size_t v = 0; v < model.viewCount(); ++v)
        for (int f : model.keyFrames(v)) settings.frames.push_back(f);
      std::sort(settings.frames.begin(), settings.frames.end());
      settings.frames.erase(std::unique(settings.frames.begin(), settings.frames.end()), settings.frames.end());
    }
    report = checkIntersections(model, settings);
  } else {
    if (!request.frames.empty())
      throw UsageError("--frames: " + quotedText(path) + " is not animated; --frames applies to animated models only");
    report = checkIntersections(*input.model, settings);
  }
  printIntersections(path, input, report, json);
}

// --sphere-map and --check-intersections with the options that refine them.
void addWhereToKeyOptions(CLI::App& sub, SphereMapRequest& map, IntersectionRequest& check) {
  auto* map_option = sub.add_option("--sphere-map", map.output,
                                    "Write where to key next as an equirectangular PNG (need = nearest-key angle, "
                                    "shape speed and uncovered base; keys and the suggested view marked) and print "
                                    "the suggested view and statistics (docs/where-to-key.md)");
  sub.add_option("--size", map.size, "Cells of the --sphere-map, WxH (default 360x180)")
      ->check(imageSize('x', kMaxSphereMapSide))
      ->needs(map_option);
  sub.add_option("--frame", map.frame, "Frame of an animated model for --sphere-map (default 0)")
      ->check(wholeNumber(0, static_cast<long>(kMaxBaseFrames) - 1))
      ->needs(map_option);
  auto* check_option = sub.add_flag(
      "--check-intersections", check.check,
      "Report the views (key views and --samples directions over the sphere; frames of an animated model) where "
      "the blended mesh passes through itself and the base does not, and the worst one; exit status 0 with the "
      "report (docs/where-to-key.md)");
  sub.add_option("--samples", check.samples,
                 "Sphere directions for --check-intersections besides the key views (default 200)")
      ->check(wholeNumber(0, kMaxIntersectionSamples))
      ->needs(check_option);
  sub.add_option("--frames", check.frames,
                 "Frames A-B (or N) of an animated model for --check-intersections (default: the frames with keys)")
      ->needs(check_option);
  check_option->excludes(map_option);
}

// `vdg info FILE.gltf|glb`: the file's description (text), then, for a glTF vdg exported
// (mesh.extras.vdg), whether the model's description should follow (true).
bool describeGltfFile(const std::string& path, bool json) {
  bool gltf_model = false;
  try {
    gltf_model = inputType(path).kind != InputKind::kMesh;
  } catch (const Error&) {
    // describeGltf reads it below; a file it describes but that is no model stays a description.
  }
  if (json && !gltf_model) throw UsageError("--json: only for models, not for glTF files");
  if (json) return true;
  std::fputs(describeGltf(path).c_str(), stdout);
  printInteractivityOfFile(path);
  // The default mesh's surface (a file without a mesh has none to describe).
  std::optional<TriMesh> mesh;
  std::vector<std::string> warnings;
  try {
    mesh = readMeshWarning(path, warnings);
  } catch (const Error&) {
  }
  if (mesh) {
    std::printf("default mesh: %zu vertices, %zu triangles\n", mesh->vertexCount(), mesh->triangleCount());
    printSurface(*mesh);
  }
  if (!gltf_model) return false;
  std::printf("\nview-dependent model (mesh.extras.vdg):\n");
  return true;
}

}  // namespace

void addInfoCommand(CLI::App& app) {
  struct Options {
    std::string model;
    bool json = false;
    SphereMapRequest sphere_map;
    IntersectionRequest intersections;
  };
  auto opt = std::make_shared<Options>();
  CLI::App* sub =
      app.add_subcommand("info",
                         "Describe a view-dependent model (mesh, keys, viewing-sphere hull, warnings), a mesh (*.obj: "
                         "materials, textures, normals) or a glTF file (meshes, morph targets, skins, animations, the "
                         "default mesh's materials)");
  sub->add_option("MODEL", opt->model,
                  "Model manifest (*.vdg.json), a mesh (*.obj), or a glTF 2.0 file (*.gltf, *.glb)")
      ->required();
  sub->add_flag("--json", opt->json, "Print one JSON object instead of text");
  addWhereToKeyOptions(*sub, opt->sphere_map, opt->intersections);
  sub->callback([opt] {
    if (opt->intersections.check) {
      checkModelIntersections(opt->model, opt->intersections, opt->json);
      return;
    }
    if (!opt->sphere_map.output.empty()) {
      writeSphereMap(opt->model, opt->sphere_map, opt->json);
      return;
    }
    if (isObjPath(opt->model)) {
      describeMesh(opt->model, opt->json);
      return;
    }
    // A glTF file vdg exported (mesh.extras.vdg) is described as a model too.
    if (isGltfPath(opt->model) && !describeGltfFile(opt->model, opt->json)) return;
    // A model without keys has nothing to build yet: say how to make its first key.
    const RawViewDependentModel described = openModel(opt->model, {}, InputBuild::kRawOnly).raw;
    if (described.keys.empty()) {
      describeKeyless(opt->model, described, opt->json);
      return;
    }
    const OpenedInput input = openModel(opt->model);
    const RawViewDependentModel& raw = input.raw;
    if (input.animated) {
      describeAnimated(opt->model, raw, *input.animated, opt->json);
      return;
    }
    const ViewDependentModel& model = *input.model;
    if (model.hasParts()) {
      describeParts(opt->model, raw, model, opt->json);
      return;
    }
    const ViewSphere& sphere = model.sphere();
    const std::size_t dummies = sphere.points().size() - sphere.keyCount();
    const auto warnings = modelWarnings(model);
    if (opt->json) {
      nlohmann::ordered_json out;
      out["model"] = opt->model;
      out["base"] = raw.base_path;
      out["export_targets"] = exportTargetsJson(model.keyCount(), 0);
      out["interactivity"] = linearWeights(model) ? interactivityJson(model) : nlohmann::ordered_json(nullptr);
      addShapeFields(model, out);
      addSpaceFields(model, out);
      out["keys"] = keysJson(model, raw);
      printWithSphereFields(sphere, warnings, out);
      return;
    }
    std::printf("model      %s\n", opt->model.c_str());
    std::printf("base       %s: %zu vertices, %zu triangles\n", raw.base_path.c_str(), model.vertexCount(),
                model.base().triangleCount());
    printSurface(model.base());
    std::printf("centre     (%.4g, %.4g, %.4g)\n", model.center().x(), model.center().y(), model.center().z());
    std::printf("sharpness  %g\n", model.sharpness());
    std::printf("uncovered  %s\n", uncoveredName(sphere.settings().uncovered));
    std::printf("weights    %s%s\n", weightSchemeName(sphere.settings().scheme), infoRbfSettingsText(sphere).c_str());
    std::printf("space      %s\n", weightSpaceText(model).c_str());
    std::printf("keys       %zu\n", model.keyCount());
    for (std::size_t k = 0; k < model.keyCount(); ++k) {
      const auto& v = model.keyView(k);
      std::printf("  %-16s view (%7.4f, %7.4f, %7.4f)  moves %zu vertices%s%s\n", model.keyName(k).c_str(), v.x(),
                  v.y(), v.z(), model.keyMovedCount(k), meshNote(raw.keys[k].mesh_path).c_str(),
                  drawingNote(raw.keys[k]).c_str());
    }
    std::printf("hull       %zu triangles, %zu dummy base keys\n", sphere.triangles().size(), dummies);
    std::printf("coverage   %.1f%% of the viewing sphere lies in triangles of real keys\n",
                100.0 * sphere.coveredFraction());
    printExportTargets(model.keyCount(), 0);
    std::printf("graph      KHR_interactivity (vdg export --interactivity): %s\n",
                linearWeights(model) ? interactivitySizeText(interactivityGraphSize(model)).c_str()
                                     : "none (the graph weighs the linear scheme of view directions only)");
    for (const auto& w : warnings) std::printf("warning: %s\n", w.c_str());
  });
}

}  // namespace vdg::cli
