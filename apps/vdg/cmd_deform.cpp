// vdg deform MODEL --key NAME --ops EDITS.json [--camera CAMERA.json | --view X,Y,Z] [--dry-run]
// vdg deform MODEL --key NAME --lines PAIRS.json --size WxH [--snap-silhouette] [--lines-falloff PX]
// vdg deform MODEL --key NAME --undo
// vdg deform ANIMATED_MODEL --frame F --key NAME ... (a key at (frame, view), Rademacher 99, section 4)
//
// Applies image-plane and attenuated deformations (Rademacher 99, 3.1.2; Parent 4.10) to one key
// of a model, in the key's camera, and appends the run to the key's edit log (KEY.edits.json) so
// that the key can be rebuilt and undone. The rules live in the deform library
// (vdg/deform/key_edit.h); this file loads the files, calls it, and writes the key mesh, the edit
// log and the manifest as ONE transaction (vdg/io/file_transaction.h): all of them or none, and an
// interrupted step is completed or rolled back by the next run on the model. See docs/deform.md.
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <vector>

#include "cli.h"
#include "vdg/deform/edits.h"
#include "vdg/deform/feature_lines.h"
#include "vdg/deform/key_edit.h"
#include "vdg/geom/error.h"
#include "vdg/geom/normalize.h"
#include "vdg/io/camera_json.h"
#include "vdg/io/edit_script.h"
#include "vdg/io/file_transaction.h"
#include "vdg/io/line_pairs.h"
#include "vdg/io/manifest.h"
#include "vdg/io/obj.h"
#include "vdg/io/read_file.h"
#include "vdg/viewdep/model.h"

namespace vdg::cli {
namespace fs = std::filesystem;

namespace {

// The journal of `vdg deform` transactions, one per model folder.
constexpr const char* kJournalName = ".vdg-journal";

// "1 step", "3 steps".
std::string counted(std::size_t n, const char* noun) { return std::to_string(n) + " " + noun + (n == 1 ? "" : "s"); }

struct DeformOptions {
  std::string model, key, ops, camera, view, mesh;
  std::optional<int> frame;  // --frame: the base animation's frame of the key
  bool dry_run = false, undo = false, quiet = false;
  std::string lines, size;  // --lines PAIRS.json in pixels of a --size WxH image
  bool snap_silhouette = false;
  double lines_falloff = 0;  // --lines-falloff PX; 0: not given (FeatureLineSettings' default)
};

fs::path meshFile(const fs::path& folder, const std::string& mesh_path) {
  return fs::path(mesh_path).is_absolute() ? fs::path(mesh_path) : folder / mesh_path;
}

bool sameFile(const fs::path& a, const fs::path& b) {
  std::error_code ec;
  if (fs::exists(a, ec) && fs::exists(b, ec)) return fs::equivalent(a, b, ec);
  return fs::absolute(a, ec).lexically_normal() == fs::absolute(b, ec).lexically_normal();
}

// A key whose mesh file another key also uses cannot be deformed alone.
void checkMeshNotShared(const RawViewDependentModel& raw, const RawKey& key, const fs::path& folder) {
  const fs::path mine = meshFile(folder, key.mesh_path);
  for (const RawKey& other : raw.keys)
    if (&other != &key && sameFile(mine, meshFile(folder, other.mesh_path)))
      throw Error("key '" + key.name + "' shares its mesh file " + mine.string() + " with key '" + other.name +
                  "': a deformation would change both; give each key its own mesh file in the manifest");
}

// The files a step on this model may have written beneath its folder, which the recovery of an
// interrupted step may complete: each key's mesh, edit log and snapshot as the manifest names them
// now (keys/front.obj); none when it does not parse (loading it reports why).
std::vector<std::string> keyFilesOf(const std::string& model, const fs::path& folder) {
  std::vector<std::string> files;
  try {
    const RawViewDependentModel raw = parseManifest(readFileLimited(model, "model", kMaxJsonFileBytes), model);
    for (const RawKey& key : raw.keys) {
      const fs::path mesh = meshFile(folder, key.mesh_path);
      files.push_back(mesh.string());
      files.push_back(editLogPath(mesh.string()));
      files.push_back((mesh.parent_path() / (mesh.stem().string() + ".origin.obj")).string());
    }
  } catch (const Error&) {
  }
  return files;
}

// What a step on `key` must leave alone, registered with the transaction so that no write lands on
// it through another name (a hard or symbolic link, compared by device and inode): the base mesh,
// every other key's mesh, edit log and snapshot, the manifest unless the step writes it, and the
// run's own edit script and camera.
void protectInputs(FileTransaction& transaction, const RawViewDependentModel& raw, const RawKey& key,
                   const fs::path& folder, const DeformOptions& opt, bool writes_manifest) {
  transaction.protect(meshFile(folder, raw.base_path).string(),
                      "the base mesh " + meshFile(folder, raw.base_path).string());
  for (const RawKey& other : raw.keys) {
    if (&other == &key) continue;
    const fs::path mesh = meshFile(folder, other.mesh_path);
    const std::string whose = "key '" + other.name + "'";
    transaction.protect(mesh.string(), "the mesh of " + whose + " " + mesh.string());
    transaction.protect(editLogPath(mesh.string()), "the edit log of " + whose + " " + editLogPath(mesh.string()));
    const fs::path snapshot = mesh.parent_path() / (mesh.stem().string() + ".origin.obj");
    transaction.protect(snapshot.string(), "the snapshot of " + whose + " " + snapshot.string());
  }
  if (!writes_manifest) transaction.protect(opt.model, "the manifest " + opt.model);
  if (!opt.ops.empty()) transaction.protect(opt.ops, "the edit script " + opt.ops);
  if (!opt.camera.empty()) transaction.protect(opt.camera, "the camera file " + opt.camera);
  if (!opt.lines.empty()) transaction.protect(opt.lines, "the line pairs " + opt.lines);
}

// --lines: one "lines" op after the script's ops (vdg/deform/feature_lines.h), in pixels of the
// --size image (or the script's image_size); with --snap-silhouette its model side is snapped to
// the silhouette of the key as it is before this step, in its edit camera.
void appendLinesOp(const DeformOptions& opt, const RawViewDependentModel& raw, const RawKey& key, EditScript& script) {
  if (!opt.size.empty()) {
    const ImageSize size = parseImageSize(opt.size, 'x', kMaxEditImageSide, "--size");
    if (script.image_size && *script.image_size != std::array<int, 2>{size.width, size.height})
      throw UsageError("--size: " + opt.ops + " already gives another \"image_size\"");
    script.image_size = std::array<int, 2>{size.width, size.height};
  }
  if (!script.image_size) throw UsageError("--lines: give --size WxH, the drawing's size in pixels");
  const LinePairsFile file = readLinePairs(opt.lines);
  LinesOp op;
  op.settings = {file.a, file.b, file.p, opt.lines_falloff > 0 ? opt.lines_falloff : op.settings.falloff_px};
  for (const LinePair& pair : file.pairs) op.pairs.push_back({pair.src_p, pair.src_q, pair.dst_p, pair.dst_q});
  if (auto problem = checkFeatureLines(op.pairs, op.settings))
    throw Error(opt.lines + ": " + problem->field + ": " + problem->message);
  if (opt.snap_silhouette) {
    const auto [w, h] = *script.image_size;
    const auto silhouette = projectedSilhouette(keyEditCamera(raw, key), w, h, key.mesh.positions, raw.base.triangles);
    op.pairs = snapToSilhouette(op.pairs, silhouette);
  }
  script.ops.push_back(std::move(op));
}

// "key 'front': its mesh front.obj", naming a file the step writes.
std::string keyFile(const RawKey& key, const char* role, const fs::path& path) {
  return "key '" + key.name + "': its " + role + " " + path.string();
}

// What the key's log replays from: the base posed at the key's frame, or the log's snapshot.
TriMesh originMesh(const RawViewDependentModel& raw, const RawKey& key, const EditLog& log, const fs::path& log_path) {
  if (log.origin == "base") return posedBase(raw, key.frame);
  TriMesh m = raw.base;
  const TriMesh snapshot = readObj((log_path.parent_path() / log.origin).string());
  if (snapshot.vertexCount() != raw.base.vertexCount())
    throw Error(log_path.string() + ": origin mesh '" + log.origin + "' has " + std::to_string(snapshot.vertexCount()) +
                " vertices, the base has " + std::to_string(raw.base.vertexCount()));
  m.positions = snapshot.positions;
  return m;
}

void runUndo(const DeformOptions& opt, RawViewDependentModel& raw, RawKey& key, const fs::path& folder,
             FileTransaction& transaction) {
  const fs::path mesh_path = meshFile(folder, key.mesh_path);
  const fs::path log_path = editLogPath(mesh_path.string());
  if (!fs::exists(log_path)) throw Error("key '" + key.name + "': no edit log " + log_path.string() + " to undo from");
  EditLog log = readEditLog(log_path.string());
  if (log.entries.empty())
    throw Error("key '" + key.name + "': nothing to undo (the edit log " + log_path.string() + " is empty)");
  const std::size_t undone_ops = log.entries.back().ops.size();
  key.mesh.positions = undoLastStep(originMesh(raw, key, log, log_path), log, log_path.string());
  raw.validate();
  if (opt.dry_run) {
    std::printf("would undo the last step of key '%s' (%s); %s would remain\n", key.name.c_str(),
                counted(undone_ops, "operation").c_str(), counted(log.entries.size(), "step").c_str());
    return;
  }
  protectInputs(transaction, raw, key, folder, opt, false);
  transaction.write(mesh_path.string(), formatObj(key.mesh, "vdg deform: key '" + key.name + "'"),
                    keyFile(key, "mesh", mesh_path));
  transaction.write(log_path.string(), formatEditLog(log), keyFile(key, "edit log", log_path));
  transaction.commit();
  if (!opt.quiet)
    std::printf("undid the last step of key '%s' (%s); %s remain\n", key.name.c_str(),
                counted(undone_ops, "operation").c_str(), counted(log.entries.size(), "step").c_str());
}

// --frame against the model (section 4: an animated model's key is made at a frame of its base
// animation): in range; 0 (or left out) for a static model; required for a new key of an animated
// model; for an existing key, its own frame (or left out).
void checkFrameOption(const DeformOptions& opt, const RawViewDependentModel& raw, const RawKey* existing) {
  if (opt.frame) {
    const int f = *opt.frame;
    if (!raw.animated() && f != 0)
      throw Error("--frame " + std::to_string(f) + ": " + opt.model +
                  " has a static base (no 'base_animation'), whose only frame is 0");
    if (f < 0 || static_cast<std::size_t>(f) >= raw.frameCount())
      throw Error("--frame " + std::to_string(f) + ": outside the base animation of " + opt.model + " (frames 0.." +
                  std::to_string(raw.frameCount() - 1) + ")");
    if (existing && existing->frame != f)
      throw Error("--frame " + std::to_string(f) + ": key '" + existing->name + "' is the key of frame " +
                  std::to_string(existing->frame) + " (leave out --frame, or name a new key)");
  } else if (raw.animated() && !existing && !opt.undo) {
    throw UsageError("--frame: " + opt.model + " has an animated base; give the frame of the new key '" + opt.key +
                     "' (0.." + std::to_string(raw.frameCount() - 1) + ")");
  }
}

void runDeform(const DeformOptions& opt) {
  const fs::path folder = fs::path(opt.model).parent_path();
  const std::string journal = (folder / kJournalName).string();
  const FolderLock lock(folder.empty() ? "." : folder.string());  // one deform at a time per folder
  if (const auto recovered = recoverFileTransaction(journal, keyFilesOf(opt.model, folder)))
    std::fprintf(stderr, "vdg deform: %s: %s\n", folder.empty() ? "." : folder.string().c_str(), recovered->c_str());
  FileTransaction transaction(journal);

  RawViewDependentModel raw = loadManifest(opt.model);
  std::size_t key_index = raw.keys.size();
  for (std::size_t k = 0; k < raw.keys.size(); ++k)
    if (raw.keys[k].name == opt.key) key_index = k;
  const bool new_key = key_index == raw.keys.size();
  checkFrameOption(opt, raw, new_key ? nullptr : &raw.keys[key_index]);

  if (opt.undo) {
    if (!opt.ops.empty() || !opt.camera.empty() || !opt.view.empty() || !opt.mesh.empty() || !opt.lines.empty())
      throw UsageError("--undo takes no --ops, --lines, --camera, --view or --mesh");
    if (new_key) throw Error(opt.model + ": no key named '" + opt.key + "'");
    checkMeshNotShared(raw, raw.keys[key_index], folder);
    runUndo(opt, raw, raw.keys[key_index], folder, transaction);
    return;
  }
  if (opt.ops.empty() && opt.lines.empty()) throw UsageError("give --ops EDITS.json or --lines PAIRS.json (or --undo)");
  if (opt.lines.empty() && (!opt.size.empty() || opt.snap_silhouette || opt.lines_falloff > 0))
    throw UsageError("--size, --snap-silhouette and --lines-falloff go with --lines PAIRS.json");
  EditScript script = opt.ops.empty() ? EditScript{} : readEditScript(opt.ops);

  // The camera of this run: the key's own, or for a new key the one given here.
  std::optional<Camera> given_camera = script.camera;
  std::optional<Eigen::Vector3d> given_view = script.view;
  if (!opt.camera.empty()) {
    if (given_camera || given_view) throw UsageError("--camera: " + opt.ops + " already gives a camera or view");
    given_camera = readCameraFile(opt.camera);
  }
  if (!opt.view.empty()) {
    if (given_camera || given_view) throw UsageError("--view: a camera or view is already given");
    // (parseDirection's check, written out: assigning its result here trips GCC 12's
    // -Wmaybe-uninitialized on the optionals at -O2.)
    const std::optional<Eigen::Vector3d> unit = normalizedOrNone(parseVec3(opt.view, "--view"));
    if (!unit) throw UsageError("--view: the direction must not be zero, got " + quotedText(opt.view));
    given_view = *unit;
  }
  if (!new_key) {
    const RawKey& key = raw.keys[key_index];
    if (given_camera || given_view)
      throw Error("key '" + key.name + "' already has its " + (key.camera ? "camera" : "view") +
                  "; the operations use it (edit the manifest to change it, or leave out the camera/view)");
    if (!opt.mesh.empty()) throw UsageError("--mesh: only for a new key");
    checkMeshNotShared(raw, key, folder);
  } else {
    checkKeyName(opt.key);
    if (!given_camera && !given_view)
      throw Error("key '" + opt.key + "' is new: give its camera or view (\"camera\"/\"view\" in " + opt.ops +
                  ", --camera CAMERA.json or --view X,Y,Z)");
    key_index = addKey(raw, {opt.key, opt.mesh, given_camera, given_view, opt.frame.value_or(0)});
    const fs::path target = meshFile(folder, raw.keys[key_index].mesh_path);
    for (const RawKey& other : raw.keys)
      if (&other != &raw.keys[key_index] && sameFile(target, meshFile(folder, other.mesh_path)))
        throw Error("key '" + opt.key + "': mesh " + target.string() + " belongs to key '" + other.name + "'");
    if (fs::exists(fs::symlink_status(target)) || fs::exists(fs::symlink_status(editLogPath(target.string()))))
      throw Error("key '" + opt.key + "': " + target.string() +
                  " (or its edit log) already exists and is not a key of the model; choose another --mesh");
  }

  RawKey& key = raw.keys[key_index];
  if (!opt.lines.empty()) appendLinesOp(opt, raw, key, script);
  const fs::path mesh_path = meshFile(folder, key.mesh_path);
  const fs::path log_path = editLogPath(mesh_path.string());
  const fs::path snapshot_path = mesh_path.parent_path() / (mesh_path.stem().string() + ".origin.obj");
  // The log this step extends; a key made outside vdg deform starts one from a snapshot of its shape.
  const bool has_log = !new_key && fs::exists(log_path);
  EditLog log = has_log ? readEditLog(log_path.string()) : startEditLog(raw, key, snapshot_path.filename().string());
  const TriMesh before = key.mesh;
  // The files of this step: registered first without contents, so that a write that would land on
  // another file of the model is refused before anything is computed or printed.
  const bool writes_snapshot = !has_log && log.origin != "base";
  auto stage = [&](std::string mesh_text, std::string log_text, std::string snapshot_text, std::string manifest) {
    if (writes_snapshot)
      transaction.write(snapshot_path.string(), std::move(snapshot_text), keyFile(key, "snapshot", snapshot_path));
    transaction.write(mesh_path.string(), std::move(mesh_text), keyFile(key, "mesh", mesh_path));
    transaction.write(log_path.string(), std::move(log_text), keyFile(key, "edit log", log_path));
    if (new_key) transaction.write(opt.model, std::move(manifest), "the manifest " + opt.model);
  };
  protectInputs(transaction, raw, key, folder, opt, new_key);
  stage({}, {}, {}, {});
  transaction.check();

  const auto reports =
      deformKey(raw, key_index, log, script.ops, script.image_size, opt.ops.empty() ? opt.lines : opt.ops);
  if (!opt.quiet || opt.dry_run) {
    for (std::size_t i = 0; i < reports.size(); ++i)
      std::printf("ops[%zu] %-14s moves %zu vertices, at most %.6g\n", i, editKindName(script.ops[i]), reports[i].moved,
                  reports[i].max_displacement);
  }
  if (opt.dry_run) {
    std::printf("dry run: %s key '%s' not written\n", new_key ? "new" : "existing", key.name.c_str());
    return;
  }

  stage(formatObj(key.mesh, "vdg deform: key '" + key.name + "'"), formatEditLog(log),
        writes_snapshot ? formatObj(before, "vdg deform: key '" + key.name + "' before its first logged edit") : "",
        new_key ? formatManifest(raw) : "");
  transaction.commit();
  if (!opt.quiet)
    std::printf("wrote key '%s' to %s (%s in %s)\n", key.name.c_str(), mesh_path.string().c_str(),
                counted(log.entries.size(), "step").c_str(), log_path.filename().string().c_str());
}

}  // namespace

void addDeformCommand(CLI::App& app) {
  auto opt = std::make_shared<DeformOptions>();
  CLI::App* sub = app.add_subcommand(
      "deform", "Deform a key of a model in its key camera (drag, push/pull, rotate, scale, displace, FFD, skeleton)");
  sub->add_option("MODEL", opt->model, "Model manifest (*.vdg.json)")->required();
  sub->add_option("--key", opt->key, "Name of the key to edit (a new key starts from the base)")->required();
  sub->add_option("--ops", opt->ops, "Edit script EDITS.json (see docs/deform.md)");
  sub->add_option("--camera", opt->camera, "Key camera JSON for a new key (as written by 'vdg align')");
  sub->add_option("--view", opt->view, "View direction X,Y,Z for a new key without a camera");
  sub->add_option("--mesh", opt->mesh, "Mesh path for a new key, relative to the manifest (default KEY.obj)");
  sub->add_option("--frame", opt->frame,
                  "Animated model: the base animation's frame of the key (required for a new key; the base is "
                  "posed there and the key stored as the manifest's (frame, view) key)");
  sub->add_option("--lines", opt->lines,
                  "Feature-line pairs PAIRS.json (as 'vdg morph --lines': \"src\" on the model's image, \"dst\" on "
                  "the drawing), applied after --ops as one \"lines\" op: Beier-Neely's warp in the image plane");
  sub->add_option("--size", opt->size, "With --lines: the drawing's size WxH in pixels (the lines' image)");
  sub->add_flag("--snap-silhouette", opt->snap_silhouette,
                "With --lines: snap each model-side endpoint to the key's silhouette in its camera");
  sub->add_option("--lines-falloff", opt->lines_falloff,
                  "With --lines: pixels from every model-side line beyond which nothing moves (default 64)")
      ->check(positiveNumber());
  sub->add_flag("--dry-run", opt->dry_run, "Report what each operation moves; write nothing");
  sub->add_flag("--undo", opt->undo, "Undo the key's last logged step (rebuilds it from its edit log)");
  sub->add_flag("-q,--quiet", opt->quiet, "Print nothing on success");
  sub->callback([opt] { runDeform(*opt); });
}

}  // namespace vdg::cli
