// Recovery files of `vdg studio` (vdg/io/studio_recovery.h, docs/studio-files.md). The key camera
// and the strokes use the camera and edit log entry JSON of camera_json.cpp and edit_script.cpp;
// the writer checks its text by reading it back, so it never writes a file the reader refuses.
#include "vdg/io/studio_recovery.h"

#include <filesystem>

#include "camera_fields.h"
#include "edit_fields.h"
#include "json_reader.h"
#include "vdg/geom/error.h"
#include "vdg/io/json_text.h"

namespace vdg {

namespace {

using io::Ctx;
using io::Json;
using OJson = nlohmann::ordered_json;

std::string absolutePath(const Json& doc, const char* key, const Ctx& ctx) {
  const Ctx kctx = ctx.key(key);
  const std::string path = io::string(io::required(doc, key, ctx), kctx);
  if (path.empty() || !std::filesystem::path(path).is_absolute())
    kctx.fail("expected an absolute path, got \"" + (path.size() > 40 ? path.substr(0, 40) + "..." : path) + "\"");
  return path;
}

StudioRecovery recoveryFrom(const Json& doc, const std::string& source) {
  const Ctx ctx{source, ""};
  io::formatVersion(doc, ctx, "studio recovery files", kStudioRecoveryVersion, kStudioRecoveryVersion);
  io::allowKeys(doc, ctx,
                {"version", "model", "manifest", "key", "new_key", "mesh", "key_camera", "frame", "logged", "strokes"});
  StudioRecovery r;
  r.model = absolutePath(doc, "model", ctx);
  r.manifest = absolutePath(doc, "manifest", ctx);
  r.key = io::string(io::required(doc, "key", ctx), ctx.key("key"));
  if (r.key.empty()) ctx.key("key").fail("expected a key name, got an empty string");
  r.new_key = io::boolean(io::required(doc, "new_key", ctx), ctx.key("new_key"));
  for (const char* field : {"mesh", "key_camera"}) {
    if (r.new_key && !doc.contains(field))
      ctx.fail(std::string("missing '") + field + "' (required with 'new_key': true)");
    if (!r.new_key && doc.contains(field)) ctx.key(field).fail("only with 'new_key': true");
  }
  if (r.new_key) {
    r.mesh_path = io::string(doc.at("mesh"), ctx.key("mesh"));
    if (r.mesh_path.empty()) ctx.key("mesh").fail("expected a mesh file name, got an empty string");
    r.key_camera = io::cameraFrom(doc.at("key_camera"), ctx.key("key_camera"));
    if (doc.contains("frame"))
      r.key_frame = static_cast<int>(io::integer(doc.at("frame"), ctx.key("frame"), 0, kMaxRecoveryFrame));
  } else if (doc.contains("frame")) {
    ctx.key("frame").fail("only with 'new_key': true");
  }
  if (doc.contains("logged"))
    r.logged = static_cast<std::size_t>(io::integer(doc.at("logged"), ctx.key("logged"), 0, kMaxLoggedEntries));
  const Json& strokes = io::required(doc, "strokes", ctx);
  if (!strokes.is_array()) ctx.key("strokes").fail("expected an array of strokes, got " + io::describe(strokes));
  r.strokes.reserve(strokes.size());
  for (std::size_t s = 0; s < strokes.size(); ++s)
    r.strokes.push_back(io::editLogEntryFrom(strokes[s], ctx.key("strokes").index(s)));
  return r;
}

}  // namespace

std::string formatStudioRecovery(const StudioRecovery& r) {
  const std::string where = "studio recovery";
  const Ctx ctx{where, ""};
  OJson j;
  j["version"] = kStudioRecoveryVersion;
  j["model"] = r.model;
  j["manifest"] = r.manifest;
  j["key"] = r.key;
  j["new_key"] = r.new_key;
  if (r.new_key || !r.mesh_path.empty()) j["mesh"] = r.mesh_path;
  if (r.key_camera) j["key_camera"] = io::cameraJson(*r.key_camera);
  if (r.new_key && r.key_frame != 0) j["frame"] = r.key_frame;
  if (r.logged > 0) j["logged"] = r.logged;
  j["strokes"] = OJson::array();
  for (std::size_t s = 0; s < r.strokes.size(); ++s)
    j["strokes"].push_back(io::editLogEntryJson(r.strokes[s], where + ": 'strokes'[" + std::to_string(s) + "]"));
  std::string text;
  try {
    text = compactScalarArrays(j.dump(2)) + "\n";  // strict: a string that is not UTF-8 throws
  } catch (const OJson::exception&) {
    for (const char* field : {"model", "manifest", "key", "mesh"}) {
      try {
        if (j.contains(field)) (void)j[field].dump();
      } catch (const OJson::exception&) {
        ctx.key(field).fail("not valid UTF-8");
      }
    }
    ctx.fail("holds a string that is not valid UTF-8");
  }
  // The reader's rules are the only ones: what it refuses is refused here, naming the field.
  recoveryFrom(io::parseJson(text, where), where);
  return text;
}

StudioRecovery parseStudioRecovery(const std::string& text, const std::string& source) {
  return recoveryFrom(io::parseJson(text, source), source);
}

StudioRecovery readStudioRecovery(const std::string& path) {
  return recoveryFrom(io::readJsonFile(path, "studio recovery file"), path);
}

}  // namespace vdg
