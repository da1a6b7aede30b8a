// The model manifest *.vdg.json (format documented in docs/model-format.md).
#include "vdg/io/manifest.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <span>

#include "camera_fields.h"
#include "json_reader.h"
#include "model_names.h"
#include "vdg/geom/error.h"
#include "vdg/io/atomic_file.h"
#include "vdg/io/gltf.h"
#include "vdg/io/image_file.h"
#include "vdg/io/json_text.h"
#include "vdg/io/mesh.h"
#include "vdg/io/read_file.h"

namespace vdg {
namespace {

namespace fs = std::filesystem;
using io::Ctx;
using io::Json;

// Key meshes and later frames of a sequence share the base's materials: only the base reads them.
constexpr MeshReadOptions kGeometryOnly{false, false, nullptr};

TriMesh readReferencedMesh(const fs::path& folder, const std::string& relative, const std::string& where,
                           const MeshReadOptions& options = kGeometryOnly) {
  const fs::path path = fs::path(relative).is_absolute() ? fs::path(relative) : folder / relative;
  try {
    return readMesh(path.string(), options);
  } catch (const Error& e) {
    throw Error(where + ": " + e.what());
  }
}

// The frame numbers an OBJ sequence may use, and the most memory its frames may take together
// (positions only; a frame of a million vertices may have about 178 frames).
constexpr std::int64_t kMaxSequenceNumber = 999'999'999;
constexpr std::size_t kMaxBaseAnimationBytes = std::size_t{2} << 30;
constexpr double kMaxFps = 1000.0;

BaseAnimationSpec parseBaseAnimation(const Json& j, const Ctx& ctx) {
  io::allowKeys(j, ctx, {"obj_sequence", "frames", "gltf", "animation", "fps", "mesh", "loop"});
  BaseAnimationSpec spec;
  const bool sequence = j.contains("obj_sequence"), gltf = j.contains("gltf");
  if (sequence == gltf)
    ctx.fail("give exactly one of 'obj_sequence' (\"walk/frame_%03d.obj\") or 'gltf' (a .gltf or .glb file)");
  if (sequence) {
    for (const char* field : {"animation", "fps", "mesh"})
      if (j.contains(field)) ctx.key(field).fail("applies to a 'gltf' base, not to an 'obj_sequence'");
    spec.obj_sequence = io::string(j.at("obj_sequence"), ctx.key("obj_sequence"));
    io::withContext(ctx.key("obj_sequence"), [&] { checkSequencePattern(spec.obj_sequence); });
    const Ctx frames = ctx.key("frames");
    const Json& range = io::required(j, "frames", ctx);
    if (!range.is_array() || range.size() != 2)
      frames.fail("expected [first, last] (two file numbers), got " + io::describe(range));
    spec.first = static_cast<int>(io::integer(range[0], frames.index(0), 0, kMaxSequenceNumber));
    spec.last = static_cast<int>(io::integer(range[1], frames.index(1), 0, kMaxSequenceNumber));
    if (spec.last < spec.first)
      frames.fail("the last frame " + std::to_string(spec.last) + " comes before the first " +
                  std::to_string(spec.first));
    if (static_cast<std::size_t>(spec.last - spec.first) + 1 > kMaxBaseFrames)
      frames.fail(std::to_string(static_cast<std::int64_t>(spec.last) - spec.first + 1) +
                  " frames; a base animation may have at most " + std::to_string(kMaxBaseFrames));
  } else {
    if (j.contains("frames"))
      ctx.key("frames").fail("applies to an 'obj_sequence' base; a 'gltf' base takes 'animation' and 'fps'");
    spec.gltf = io::string(j.at("gltf"), ctx.key("gltf"));
    if (spec.gltf.empty()) ctx.key("gltf").fail("expected a .gltf or .glb file name, got an empty string");
    if (j.contains("animation"))
      spec.animation = static_cast<int>(io::integer(j.at("animation"), ctx.key("animation"), 0, 1'000'000));
    if (j.contains("fps")) {
      spec.fps = io::number(j.at("fps"), ctx.key("fps"));
      if (!(spec.fps > 0.0 && spec.fps <= kMaxFps))
        ctx.key("fps").fail("expected frames per second in (0, " + std::to_string(static_cast<int>(kMaxFps)) +
                            "], got " + io::describe(j.at("fps")));
    }
    if (j.contains("mesh")) spec.mesh = io::string(j.at("mesh"), ctx.key("mesh"));
  }
  if (j.contains("loop")) spec.loop = io::boolean(j.at("loop"), ctx.key("loop"));
  return spec;
}

// Reads every frame of an OBJ-sequence base into model.base (frame 0: topology, uvs, positions)
// and model.base_frames.
void loadObjSequence(RawViewDependentModel& model, const fs::path& folder, const std::string& path,
                     const MeshReadOptions& options) {
  const BaseAnimationSpec& spec = *model.base_animation;
  const std::size_t count = static_cast<std::size_t>(spec.last - spec.first) + 1;
  std::string first_name;
  for (std::size_t i = 0; i < count; ++i) {
    const std::string name = sequenceFileName(spec.obj_sequence, spec.first + static_cast<int>(i));
    TriMesh frame = readReferencedMesh(folder, name, path + ": base_animation frame " + std::to_string(i),
                                       i == 0 ? options : kGeometryOnly);
    if (i == 0) {
      first_name = name;
      const std::size_t bytes = frame.positions.size() * sizeof(float);
      if (bytes > 0 && count > kMaxBaseAnimationBytes / bytes)
        throw Error(path + ": base_animation: " + std::to_string(count) + " frames of " +
                    std::to_string(frame.vertexCount()) + " vertices exceed the limit of " +
                    std::to_string(kMaxBaseAnimationBytes >> 20) + " MiB of positions");
      model.base_frames.reserve(count);
      model.base = std::move(frame);
      model.base_frames.push_back(model.base.positions);
      continue;
    }
    const std::string label = path + ": base_animation frame " + std::to_string(i) + " (" + name + ")";
    if (frame.vertexCount() != model.base.vertexCount())
      throw Error(label + ": " + std::to_string(frame.vertexCount()) + " vertices but frame 0 (" + first_name +
                  ") has " + std::to_string(model.base.vertexCount()) + "; every frame must have the same topology");
    if (frame.triangles != model.base.triangles)
      throw Error(label + ": its triangles differ from frame 0's (" + first_name +
                  "); every frame must have the same topology");
    model.base_frames.push_back(std::move(frame.positions));
  }
}

// A glTF animated base (paper section 4.1 with a skinned or morphed base): the selected mesh's
// animation sampled at frame i = time i / fps, i = 0 .. N-1 with N = round(duration * fps) + 1, or
// round(duration * fps) with "loop" (the cycle's last sample would repeat its first). For skinned
// offsets the per-vertex skin linear parts are kept too (Rig::evaluate's out_skin).
void loadGltfBaseAnimation(RawViewDependentModel& model, const fs::path& folder, const std::string& path,
                           const MeshReadOptions& options) {
  const BaseAnimationSpec& spec = *model.base_animation;
  const fs::path file = fs::path(spec.gltf).is_absolute() ? fs::path(spec.gltf) : folder / spec.gltf;
  const std::string where = path + ": base_animation.gltf";
  Rig rig = [&] {
    try {
      return Rig::build(readGltfRig(file.string(), GltfSelect{spec.mesh}, options));
    } catch (const Error& e) {
      throw Error(where + ": " + e.what());
    }
  }();
  if (spec.animation >= static_cast<int>(rig.animationCount()))
    throw Error(path + ": base_animation.animation: " + std::to_string(spec.animation) + " is out of range (" +
                spec.gltf + " has " + std::to_string(rig.animationCount()) + " animation" +
                (rig.animationCount() == 1 ? "" : "s") + ")");
  const double samples = std::round(rig.duration(spec.animation) * spec.fps);
  const double frames = spec.loop ? std::max(samples, 1.0) : samples + 1.0;
  if (!(frames <= static_cast<double>(kMaxBaseFrames)))
    throw Error(path + ": base_animation: " + std::to_string(rig.duration(spec.animation)) + " s at " +
                std::to_string(spec.fps) + " fps is more than " + std::to_string(kMaxBaseFrames) + " frames");
  const auto count = static_cast<std::size_t>(frames);
  const bool keep_skin = model.offsets == OffsetSpace::kSkinned;
  const std::size_t bytes_per_frame = rig.vertexCount() * (keep_skin ? 12 : 3) * sizeof(float);
  if (bytes_per_frame > 0 && count > kMaxBaseAnimationBytes / bytes_per_frame)
    throw Error(path + ": base_animation: " + std::to_string(count) + " frames of " +
                std::to_string(rig.vertexCount()) + " vertices exceed the limit of " +
                std::to_string(kMaxBaseAnimationBytes >> 20) + " MiB of sampled frames");
  model.base = rig.mesh();
  model.base_frames.assign(count, std::vector<float>(rig.vertexCount() * 3));
  if (keep_skin) model.base_skin.assign(count, std::vector<float>(rig.vertexCount() * 9));
  for (std::size_t i = 0; i < count; ++i) {
    const std::span<float> skin = keep_skin ? std::span<float>(model.base_skin[i]) : std::span<float>();
    if (!rig.evaluate(spec.animation, static_cast<double>(i) / spec.fps, model.base_frames[i], {}, skin))
      throw Error(where + ": frame " + std::to_string(i) + " could not be evaluated (internal error)");
  }
  model.base.positions = model.base_frames.front();
}

// "parts" (version 4): the raw parts; the checks that need the base and the keys are validate()'s.
void parseParts(const Json& parts, const Ctx& ctx, RawViewDependentModel& model) {
  if (!parts.is_array()) ctx.fail("expected an array of {name, select, border, keys, view}");
  if (parts.size() > kMaxParts)
    ctx.fail("has " + std::to_string(parts.size()) + " parts, more than the limit of " + std::to_string(kMaxParts));
  for (std::size_t p = 0; p < parts.size(); ++p) {
    const Json& entry = parts[p];
    Ctx pctx = ctx.index(p);
    io::allowKeys(entry, pctx, {"name", "select", "border", "keys", "view"});
    RawPart part;
    part.name = io::string(io::required(entry, "name", pctx), pctx.key("name"));
    pctx = pctx.labelled("part '" + part.name + "' (parts[" + std::to_string(p) + "])");
    const Json& select = io::required(entry, "select", pctx);
    const Ctx sctx = pctx.key("select");
    if (!select.is_object() || select.size() != 1)
      sctx.fail("expected one of {\"vertices\": [...]}, {\"material\": \"NAME\"} or {\"weights\": \"FILE\" | [...]}");
    io::allowKeys(select, sctx, {"vertices", "material", "weights"});
    if (select.contains("vertices")) {
      part.select = RawPart::Select::kVertices;
      const Json& list = select.at("vertices");
      if (!list.is_array()) sctx.key("vertices").fail("expected an array of vertex indices");
      for (std::size_t i = 0; i < list.size(); ++i)
        part.vertices.push_back(
            static_cast<std::int32_t>(io::integer(list[i], sctx.key("vertices").index(i), 0, INT32_MAX)));
    } else if (select.contains("material")) {
      part.select = RawPart::Select::kMaterial;
      part.material = io::string(select.at("material"), sctx.key("material"));
    } else {
      part.select = RawPart::Select::kWeights;
      const Json& weights = select.at("weights");
      if (weights.is_string()) {
        part.mask_path = weights.get<std::string>();
        if (part.mask_path.empty()) sctx.key("weights").fail("expected a mask file name, got an empty string");
      } else {
        if (!weights.is_array()) sctx.key("weights").fail("expected a mask file name or an array of numbers in [0, 1]");
        for (std::size_t i = 0; i < weights.size(); ++i)
          part.mask.push_back(static_cast<float>(io::number(weights[i], sctx.key("weights").index(i))));
      }
    }
    if (entry.contains("border")) part.border = io::number(entry.at("border"), pctx.key("border"));
    const Json& keys = io::required(entry, "keys", pctx);
    if (!keys.is_array()) pctx.key("keys").fail("expected an array of key names");
    for (std::size_t i = 0; i < keys.size(); ++i) part.keys.push_back(io::string(keys[i], pctx.key("keys").index(i)));
    if (entry.contains("view")) part.view = io::vector3(entry.at("view"), pctx.key("view"));
    model.parts.push_back(std::move(part));
  }
}

// A key's "drawing" (version 5): a file name, on a key given by its camera (the drawing is what
// that camera saw).
void parseKeyDrawing(const Json& j, const Ctx& ctx, int version, bool has_camera, bool has_view, RawKey& key) {
  if (version < 5) ctx.fail("needs manifest version 5 (this file says \"version\": " + std::to_string(version) + ")");
  if (!has_camera)
    ctx.fail("needs the key's 'camera' (the viewpoint the drawing was made from); this key is given by " +
             std::string(has_view ? "'view'" : "'eye'"));
  key.drawing_path = io::string(j, ctx);
  if (key.drawing_path.empty()) ctx.fail("expected a PNG or JPEG file name, got an empty string");
}

// A key's reference drawing (version 5), decoded with the image reader's limits; the message names
// the manifest, the key and the file ("M: key 'front' (keys[0]): drawing 'f.png': ...").
std::shared_ptr<const TextureImage> readDrawing(const fs::path& folder, const RawKey& key, std::size_t k,
                                                const std::string& manifest) {
  const fs::path file =
      fs::path(key.drawing_path).is_absolute() ? fs::path(key.drawing_path) : folder / key.drawing_path;
  try {
    return std::make_shared<const TextureImage>(readImageFile(file.string(), "drawing"));
  } catch (const Error& e) {
    throw Error(manifest + ": key '" + key.name + "' (keys[" + std::to_string(k) + "]): drawing '" + key.drawing_path +
                "': " + e.what());
  }
}

// A part's mask file: one number per vertex, separated by white space.
std::vector<float> readMaskFile(const fs::path& folder, const std::string& relative, const std::string& where) {
  const fs::path path = fs::path(relative).is_absolute() ? fs::path(relative) : folder / relative;
  const std::string text = readFileLimited(path.string(), where + ": mask", kMaxJsonFileBytes);
  std::vector<float> mask;
  const char* at = text.c_str();
  const char* end = at + text.size();
  while (true) {
    while (at < end && std::isspace(static_cast<unsigned char>(*at))) ++at;
    if (at >= end) break;
    char* next = nullptr;
    const double value = std::strtod(at, &next);
    if (next == at || (next < end && !std::isspace(static_cast<unsigned char>(*next))) || !std::isfinite(value))
      throw Error(where + ": mask file '" + relative + "': value " + std::to_string(mask.size()) +
                  " is not a finite number");
    mask.push_back(static_cast<float>(value));
    at = next;
  }
  return mask;
}

}  // namespace

std::string sequenceFileName(const std::string& pattern, int number) {
  checkSequencePattern(pattern);
  const std::size_t percent = pattern.find('%');
  std::size_t end = percent + 1;
  int width = 0;
  while (pattern[end] >= '0' && pattern[end] <= '9') width = 10 * width + (pattern[end++] - '0');
  std::string digits = std::to_string(number);
  if (number >= 0 && digits.size() < static_cast<std::size_t>(width))
    digits.insert(0, static_cast<std::size_t>(width) - digits.size(), '0');
  return pattern.substr(0, percent) + digits + pattern.substr(end + 1);
}

void checkSequencePattern(const std::string& pattern) {
  const std::size_t percent = pattern.find('%');
  const auto bad = [&](const std::string& why) {
    throw Error("expected a file pattern with one %d or %0Nd (\"walk/frame_%03d.obj\"), got '" +
                (pattern.size() > 60 ? pattern.substr(0, 60) + "..." : pattern) + "': " + why);
  };
  if (percent == std::string::npos) bad("it has no %d");
  std::size_t end = percent + 1;
  if (end < pattern.size() && pattern[end] == '0') {
    ++end;
    const std::size_t digits = end;
    while (end < pattern.size() && pattern[end] >= '0' && pattern[end] <= '9') ++end;
    if (end == digits || end - digits > 1 || pattern[digits] == '0')
      bad("the width of %0Nd must be one digit from 1 to 9");
  }
  if (end >= pattern.size() || pattern[end] != 'd') bad("the only conversion allowed is %d or %0Nd");
  if (pattern.find('%', end + 1) != std::string::npos) bad("it has more than one %");
}

RawViewDependentModel parseManifest(const std::string& text, const std::string& source) {
  const Json doc = io::parseJson(text, source);
  const Ctx top{source, ""};
  const int version = io::formatVersion(doc, top, "model manifests", 1, kManifestVersion);
  if (version == 1) {
    for (const char* field : {"base_animation", "offsets"})
      if (doc.is_object() && doc.contains(field))
        top.key(field).fail("needs manifest version 2 (this file says \"version\": 1)");
    io::allowKeys(doc, top,
                  {"version", "base", "keys", "sharpness", "uncovered", "base_falloff_deg", "center", "comment"});
  } else {
    if (version == 2 && doc.is_object() && doc.contains("weights"))
      top.key("weights").fail("needs manifest version 3 (this file says \"version\": 2)");
    if (version < 4 && doc.is_object() && doc.contains("parts"))
      top.key("parts").fail("needs manifest version 4 (this file says \"version\": " + std::to_string(version) + ")");
    io::allowKeys(doc, top,
                  {"version", "base", "base_animation", "offsets", "keys", "sharpness", "uncovered", "base_falloff_deg",
                   "center", "comment", "weights", "parts"});
  }

  RawViewDependentModel model;
  model.source = source;
  const bool has_base = doc.contains("base"), has_animation = doc.contains("base_animation");
  if (has_base && has_animation)
    top.fail("give exactly one of 'base' (a mesh file) or 'base_animation' (an animated base), not both");
  if (!has_base && !has_animation)
    top.fail(version == 1 ? "missing 'base' (the base mesh file)"
                          : "missing 'base' (the base mesh file) or 'base_animation' (an animated base)");
  if (has_base) {
    model.base_path = io::string(doc.at("base"), top.key("base"));
    if (model.base_path.empty()) top.key("base").fail("expected a mesh file name, got an empty string");
  } else {
    model.base_animation = parseBaseAnimation(doc.at("base_animation"), top.key("base_animation"));
  }
  if (doc.contains("offsets")) {
    model.offsets = io::enumValue(doc.at("offsets"), top.key("offsets"), io::kOffsetSpaceNames);
    if (!has_animation && model.offsets == OffsetSpace::kSkinned)
      top.key("offsets").fail("'skinned' needs an animated, skinned base ('base_animation')");
  }
  if (doc.contains("comment")) model.comment = io::string(doc.at("comment"), top.key("comment"));
  if (doc.contains("sharpness")) model.sharpness = io::number(doc.at("sharpness"), top.key("sharpness"));
  if (doc.contains("uncovered"))
    model.sphere.uncovered = io::enumValue(doc.at("uncovered"), top.key("uncovered"), io::kUncoveredNames);
  if (doc.contains("base_falloff_deg"))
    model.sphere.base_falloff_deg = io::number(doc.at("base_falloff_deg"), top.key("base_falloff_deg"));
  if (doc.contains("center")) model.center = io::vector3(doc.at("center"), top.key("center"));
  if (doc.contains("weights")) {
    const Json& weights = doc.at("weights");
    const Ctx ctx = top.key("weights");
    if (!weights.is_object()) ctx.fail("expected an object {\"scheme\": \"linear\" | \"smooth\" | \"rbf\", ...}");
    io::allowKeys(weights, ctx, {"scheme", "kernel", "width", "space", "falloff"});
    for (const char* v4 : {"space", "falloff"})
      if (weights.contains(v4) && version < 4)
        ctx.key(v4).fail("needs manifest version 4 (this file says \"version\": " + std::to_string(version) + ")");
    if (weights.contains("space"))
      model.key_space.space = io::enumValue(weights.at("space"), ctx.key("space"), io::kWeightSpaceNames);
    if (weights.contains("falloff")) {
      if (model.key_space.space != WeightSpace::Positions)
        ctx.key("falloff").fail("is a setting of the 'positions' space only");
      model.key_space.falloff = io::number(weights.at("falloff"), ctx.key("falloff"));
      if (!(model.key_space.falloff > 0.0))
        ctx.key("falloff").fail("expected a distance > 0 (model units; leave it out for the automatic one), got " +
                                std::to_string(model.key_space.falloff));
    }
    if (weights.contains("scheme"))
      model.sphere.scheme = io::enumValue(weights.at("scheme"), ctx.key("scheme"), io::kWeightSchemeNames);
    for (const char* rbf_only : {"kernel", "width"})
      if (weights.contains(rbf_only) && model.sphere.scheme != WeightScheme::Rbf)
        ctx.key(rbf_only).fail("is a setting of the 'rbf' scheme only");
    if (weights.contains("kernel"))
      model.sphere.rbf_kernel = io::enumValue(weights.at("kernel"), ctx.key("kernel"), io::kRbfKernelNames);
    if (weights.contains("width")) {
      model.sphere.rbf_width_deg = io::number(weights.at("width"), ctx.key("width"));
      if (!(model.sphere.rbf_width_deg > 0.0 && model.sphere.rbf_width_deg <= 180.0))
        ctx.key("width").fail("expected degrees in (0, 180], got " + std::to_string(model.sphere.rbf_width_deg));
    }
  }

  if (!doc.contains("keys") || !doc.at("keys").is_array())
    top.fail("missing 'keys' (an array of {mesh, view | camera, name})");
  const Json& keys = doc.at("keys");
  if (keys.size() > kMaxKeys)
    top.key("keys").fail("has " + std::to_string(keys.size()) + " keys, more than the limit of " +
                         std::to_string(kMaxKeys));
  for (std::size_t k = 0; k < keys.size(); ++k) {
    const Json& entry = keys[k];
    Ctx ctx = top.key("keys").index(k);
    io::allowKeys(entry, ctx, {"name", "mesh", "view", "camera", "eye", "frame", "drawing"});
    RawKey key;
    key.mesh_path = io::string(io::required(entry, "mesh", ctx), ctx.key("mesh"));
    if (key.mesh_path.empty()) ctx.key("mesh").fail("expected a mesh file name, got an empty string");
    key.name = entry.contains("name") ? io::string(entry.at("name"), ctx.key("name"))
                                      : fs::path(key.mesh_path).stem().string();
    ctx = ctx.labelled("key '" + key.name + "' (keys[" + std::to_string(k) + "])");
    if (entry.contains("frame")) {
      if (!has_animation) ctx.fail("'frame' needs an animated base model ('base_animation', manifest version 2)");
      key.frame = static_cast<int>(
          io::integer(entry.at("frame"), ctx.key("frame"), 0, static_cast<std::int64_t>(kMaxBaseFrames) - 1));
    }
    const bool has_view = entry.contains("view"), has_camera = entry.contains("camera"),
               has_eye = entry.contains("eye");
    if (int(has_view) + int(has_camera) + int(has_eye) != 1)
      ctx.fail("give exactly one of 'view' [x, y, z], 'eye' [x, y, z] or 'camera' {eye, target, ...}");
    if (has_eye && version < 4)
      ctx.key("eye").fail("needs manifest version 4 (this file says \"version\": " + std::to_string(version) + ")");
    if (has_eye) key.eye = io::vector3(entry.at("eye"), ctx.key("eye"));
    if (has_view) key.view = io::vector3(entry.at("view"), ctx.key("view"));
    if (has_camera) key.camera = io::cameraFrom(entry.at("camera"), ctx.key("camera"));
    if (entry.contains("drawing"))
      parseKeyDrawing(entry.at("drawing"), ctx.key("drawing"), version, has_camera, has_view, key);
    model.keys.push_back(std::move(key));
  }
  if (doc.contains("parts")) parseParts(doc.at("parts"), top.key("parts"), model);
  return model;
}

RawViewDependentModel loadManifest(const std::string& path, const MeshReadOptions& options) {
  RawViewDependentModel model = parseManifest(readFileLimited(path, "model", kMaxJsonFileBytes), path);
  const fs::path folder = fs::path(path).parent_path();
  if (!model.base_animation)
    model.base = readReferencedMesh(folder, model.base_path, path + ": base", options);
  else if (!model.base_animation->obj_sequence.empty())
    loadObjSequence(model, folder, path, options);
  else
    loadGltfBaseAnimation(model, folder, path, options);
  for (std::size_t k = 0; k < model.keys.size(); ++k) {
    RawKey& key = model.keys[k];
    key.mesh =
        readReferencedMesh(folder, key.mesh_path, path + ": key '" + key.name + "' (keys[" + std::to_string(k) + "])");
    if (!key.drawing_path.empty()) key.drawing = readDrawing(folder, key, k, path);
  }
  for (std::size_t p = 0; p < model.parts.size(); ++p) {
    RawPart& part = model.parts[p];
    if (!part.mask_path.empty())
      part.mask =
          readMaskFile(folder, part.mask_path, path + ": part '" + part.name + "' (parts[" + std::to_string(p) + "])");
  }
  model.resolveViews();
  model.validate();
  return model;
}

namespace {

nlohmann::ordered_json partsJson(const std::vector<RawPart>& parts) {
  nlohmann::ordered_json out = nlohmann::ordered_json::array();
  for (const RawPart& part : parts) {
    nlohmann::ordered_json entry;
    entry["name"] = part.name;
    if (part.select == RawPart::Select::kVertices)
      entry["select"]["vertices"] = part.vertices;
    else if (part.select == RawPart::Select::kMaterial)
      entry["select"]["material"] = part.material;
    else if (!part.mask_path.empty())
      entry["select"]["weights"] = part.mask_path;  // the file is kept as it is, as the meshes are
    else
      entry["select"]["weights"] = part.mask;
    if (part.border != 0.0) entry["border"] = part.border;
    entry["keys"] = part.keys;
    if (part.view) entry["view"] = {part.view->x(), part.view->y(), part.view->z()};
    out.push_back(std::move(entry));
  }
  return out;
}

}  // namespace

std::string formatManifest(const RawViewDependentModel& model) {
  nlohmann::ordered_json doc;
  // The oldest version that holds the model, so that older vdgs still read linear models.
  const bool needs_v4 =
      !model.parts.empty() || model.key_space.space == WeightSpace::Positions ||
      std::any_of(model.keys.begin(), model.keys.end(), [](const RawKey& k) { return k.eye.has_value(); });
  const bool needs_v5 =
      std::any_of(model.keys.begin(), model.keys.end(), [](const RawKey& k) { return !k.drawing_path.empty(); });
  doc["version"] = needs_v5 ? 5 : needs_v4 ? 4 : model.sphere.scheme == WeightScheme::Linear ? 2 : 3;
  if (!model.comment.empty()) doc["comment"] = model.comment;
  if (model.base_animation) {
    const BaseAnimationSpec& spec = *model.base_animation;
    nlohmann::ordered_json animation;
    if (!spec.obj_sequence.empty()) {
      animation["obj_sequence"] = spec.obj_sequence;
      animation["frames"] = {spec.first, spec.last};
    } else {
      animation["gltf"] = spec.gltf;
      animation["animation"] = spec.animation;
      animation["fps"] = spec.fps;
      if (!spec.mesh.empty()) animation["mesh"] = spec.mesh;
    }
    if (spec.loop) animation["loop"] = true;
    doc["base_animation"] = std::move(animation);
    doc["offsets"] = offsetSpaceName(model.offsets);
  } else {
    doc["base"] = model.base_path;
  }
  if (model.center) doc["center"] = {model.center->x(), model.center->y(), model.center->z()};
  doc["sharpness"] = model.sharpness;
  doc["uncovered"] = uncoveredName(model.sphere.uncovered);
  if (model.sphere.base_falloff_deg != ViewSphereSettings{}.base_falloff_deg)
    doc["base_falloff_deg"] = model.sphere.base_falloff_deg;
  if (model.sphere.scheme != WeightScheme::Linear) doc["weights"] = {{"scheme", weightSchemeName(model.sphere.scheme)}};
  if (model.sphere.scheme == WeightScheme::Rbf) {
    doc["weights"]["kernel"] = rbfKernelName(model.sphere.rbf_kernel);
    doc["weights"]["width"] = model.sphere.rbf_width_deg;
  }
  if (model.key_space.space == WeightSpace::Positions) {
    doc["weights"]["space"] = weightSpaceName(model.key_space.space);
    if (model.key_space.falloff > 0.0) doc["weights"]["falloff"] = model.key_space.falloff;
  }
  nlohmann::ordered_json keys = nlohmann::ordered_json::array();
  for (const RawKey& key : model.keys) {
    nlohmann::ordered_json entry;
    entry["name"] = key.name;
    entry["mesh"] = key.mesh_path;
    if (model.base_animation) entry["frame"] = key.frame;
    if (key.camera)
      entry["camera"] = io::cameraJson(*key.camera);
    else if (key.eye)
      entry["eye"] = {key.eye->x(), key.eye->y(), key.eye->z()};
    else
      entry["view"] = {key.view.x(), key.view.y(), key.view.z()};
    if (!key.drawing_path.empty()) entry["drawing"] = key.drawing_path;
    keys.push_back(std::move(entry));
  }
  doc["keys"] = std::move(keys);
  if (!model.parts.empty()) doc["parts"] = partsJson(model.parts);
  return compactScalarArrays(doc.dump(2)) + "\n";
}

void saveManifest(const std::string& path, const RawViewDependentModel& model) {
  writeFileAtomically(path, formatManifest(model));
}

}  // namespace vdg
