// vdg deform MODEL --key NAME --ops EDITS.json [--camera CAMERA.json | --view X,Y,Z] [--dry-run]
// vdg deform MODEL --key NAME --undo
//
// Applies image-plane and attenuated deformations (Rademacher 99, 3.1.2; Parent 4.10) to one key
// of a model, in the key's camera, writes the key mesh and the manifest atomically, and appends the
// run to the key's edit log (KEY.edits.json) so that the key can be rebuilt and undone. Nothing is
// written unless every operation is valid and the updated model validates. See docs/deform.md.
#include <cstdio>
#include <filesystem>
#include <memory>

#include "cli.h"
#include "vdg/deform/edits.h"
#include "vdg/geom/error.h"
#include "vdg/geom/normalize.h"
#include "vdg/io/camera_json.h"
#include "vdg/io/edit_script.h"
#include "vdg/io/manifest.h"
#include "vdg/io/obj.h"
#include "vdg/viewdep/model.h"

namespace vdg::cli {
namespace fs = std::filesystem;

namespace {

// "1 step", "3 steps".
std::string counted(std::size_t n, const char* noun) { return std::to_string(n) + " " + noun + (n == 1 ? "" : "s"); }

struct DeformOptions {
  std::string model, key, ops, camera, view, mesh;
  bool dry_run = false, undo = false, quiet = false;
};

fs::path meshFile(const fs::path& folder, const std::string& mesh_path) {
  return fs::path(mesh_path).is_absolute() ? fs::path(mesh_path) : folder / mesh_path;
}

// A camera for a key known only by its view: parallel, framing the base.
Camera viewCamera(const RawViewDependentModel& raw, const Eigen::Vector3d& view) {
  const Bounds b = computeBounds(raw.base.positions);
  const double size = std::max(static_cast<double>(b.diagonal()), 1e-6);
  return cameraFromView(raw.resolvedCenter(), view, 2.0 * size, 1.1 * size);
}

void replace(std::vector<float>& positions, const std::vector<float>& from) { positions = from; }

TriMesh originMesh(const RawViewDependentModel& raw, const EditLog& log, const fs::path& log_path) {
  if (log.origin == "base") return raw.base;
  TriMesh m = raw.base;
  const TriMesh snapshot = readObj((log_path.parent_path() / log.origin).string());
  if (snapshot.vertexCount() != raw.base.vertexCount())
    throw Error(log_path.string() + ": origin mesh '" + log.origin + "' has " + std::to_string(snapshot.vertexCount()) +
                " vertices, the base has " + std::to_string(raw.base.vertexCount()));
  replace(m.positions, snapshot.positions);
  return m;
}

void runUndo(const DeformOptions& opt, RawViewDependentModel& raw, RawKey& key, const fs::path& folder) {
  const fs::path mesh_path = meshFile(folder, key.mesh_path);
  const fs::path log_path = editLogPath(mesh_path.string());
  if (!fs::exists(log_path)) throw Error("key '" + key.name + "': no edit log " + log_path.string() + " to undo from");
  EditLog log = readEditLog(log_path.string());
  if (log.entries.empty())
    throw Error("key '" + key.name + "': nothing to undo (the edit log " + log_path.string() + " is empty)");
  const std::size_t undone_ops = log.entries.back().ops.size();
  log.entries.pop_back();
  TriMesh rebuilt = originMesh(raw, log, log_path);
  for (std::size_t e = 0; e < log.entries.size(); ++e)
    applyEdits(log.entries[e].camera, rebuilt.triangles, rebuilt.positions, log.entries[e].ops,
               log.entries[e].image_size, log_path.string() + ": entries[" + std::to_string(e) + "]");
  key.mesh.positions = rebuilt.positions;
  raw.validate();
  if (opt.dry_run) {
    std::printf("would undo the last step of key '%s' (%s); %s would remain\n", key.name.c_str(),
                counted(undone_ops, "operation").c_str(), counted(log.entries.size(), "step").c_str());
    return;
  }
  writeObj(mesh_path.string(), key.mesh, "vdg deform: key '" + key.name + "'");
  writeEditLog(log_path.string(), log);
  if (!opt.quiet)
    std::printf("undid the last step of key '%s' (%s); %s remain\n", key.name.c_str(),
                counted(undone_ops, "operation").c_str(), counted(log.entries.size(), "step").c_str());
}

void runDeform(const DeformOptions& opt) {
  RawViewDependentModel raw = loadManifest(opt.model);
  const fs::path folder = fs::path(opt.model).parent_path();
  RawKey* key = nullptr;
  for (RawKey& k : raw.keys)
    if (k.name == opt.key) key = &k;

  if (opt.undo) {
    if (!opt.ops.empty() || !opt.camera.empty() || !opt.view.empty() || !opt.mesh.empty())
      throw UsageError("--undo takes no --ops, --camera, --view or --mesh");
    if (!key) throw Error(opt.model + ": no key named '" + opt.key + "'");
    runUndo(opt, raw, *key, folder);
    return;
  }
  if (opt.ops.empty()) throw UsageError("give --ops EDITS.json (or --undo)");
  const EditScript script = readEditScript(opt.ops);

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
    if (!unit) throw UsageError("--view: the direction must not be zero, got " + shown(opt.view));
    given_view = *unit;
  }
  bool new_key = false;
  if (key) {
    if (given_camera || given_view)
      throw Error("key '" + key->name + "' already has its " + (key->camera ? "camera" : "view") +
                  "; the operations use it (edit the manifest to change it, or leave out the camera/view)");
    if (!opt.mesh.empty()) throw UsageError("--mesh: only for a new key");
  } else {
    if (!given_camera && !given_view)
      throw Error("key '" + opt.key + "' is new: give its camera or view (\"camera\"/\"view\" in " + opt.ops +
                  ", --camera CAMERA.json or --view X,Y,Z)");
    RawKey k;
    k.name = opt.key;
    k.mesh_path = opt.mesh.empty() ? opt.key + ".obj" : opt.mesh;
    k.mesh = raw.base;
    k.camera = given_camera;
    if (given_view) k.view = *given_view;
    const fs::path target = meshFile(folder, k.mesh_path);
    for (const RawKey& other : raw.keys)
      if (fs::exists(target) && fs::exists(meshFile(folder, other.mesh_path)) &&
          fs::equivalent(target, meshFile(folder, other.mesh_path)))
        throw Error("key '" + opt.key + "': mesh " + target.string() + " belongs to key '" + other.name + "'");
    if (fs::exists(target) || fs::exists(editLogPath(target.string())))
      throw Error("key '" + opt.key + "': " + target.string() +
                  " (or its edit log) already exists and is not a key of the model; choose another --mesh");
    raw.keys.push_back(std::move(k));
    key = &raw.keys.back();
    new_key = true;
    raw.resolveViews();
  }
  const Camera camera = key->camera ? *key->camera : viewCamera(raw, key->view);

  // Edit a copy; nothing is written unless every operation succeeds.
  std::vector<float> positions = key->mesh.positions;
  const auto reports = applyEdits(camera, key->mesh.triangles, positions, script.ops, script.image_size, opt.ops);
  if (!opt.quiet || opt.dry_run) {
    for (std::size_t i = 0; i < reports.size(); ++i)
      std::printf("ops[%zu] %-14s moves %zu vertices, at most %.6g\n", i, editKindName(script.ops[i].kind),
                  reports[i].moved, reports[i].max_displacement);
  }
  const std::vector<float> before = key->mesh.positions;
  key->mesh.positions = positions;
  raw.validate();
  if (opt.dry_run) {
    std::printf("dry run: %s key '%s' not written\n", new_key ? "new" : "existing", key->name.c_str());
    return;
  }

  const fs::path mesh_path = meshFile(folder, key->mesh_path);
  const fs::path log_path = editLogPath(mesh_path.string());
  EditLog log;
  bool write_snapshot = false;
  fs::path snapshot_path;
  if (!new_key && fs::exists(log_path)) {
    log = readEditLog(log_path.string());
  } else {
    log.key = key->name;
    if (!new_key && before != raw.base.positions) {
      // A key made outside vdg deform: keep its current shape as the log's origin.
      snapshot_path = mesh_path.parent_path() / (mesh_path.stem().string() + ".origin.obj");
      log.origin = snapshot_path.filename().string();
      write_snapshot = true;
    }
  }
  log.entries.push_back({camera, script.image_size, script.ops});

  if (write_snapshot) {
    TriMesh snapshot = key->mesh;
    snapshot.positions = before;
    writeObj(snapshot_path.string(), snapshot, "vdg deform: key '" + key->name + "' before its first logged edit");
  }
  writeObj(mesh_path.string(), key->mesh, "vdg deform: key '" + key->name + "'");
  writeEditLog(log_path.string(), log);
  if (new_key) saveManifest(opt.model, raw);
  if (!opt.quiet)
    std::printf("wrote key '%s' to %s (%s in %s)\n", key->name.c_str(), mesh_path.string().c_str(),
                counted(log.entries.size(), "step").c_str(), log_path.filename().string().c_str());
}

}  // namespace

void addDeformCommand(CLI::App& app) {
  auto opt = std::make_shared<DeformOptions>();
  CLI::App* sub = app.add_subcommand(
      "deform", "Deform a key of a model in its key camera (drag, push/pull, rotate, scale, displace, FFD)");
  sub->add_option("MODEL", opt->model, "Model manifest (*.vdg.json)")->required();
  sub->add_option("--key", opt->key, "Name of the key to edit (a new key starts from the base)")->required();
  sub->add_option("--ops", opt->ops, "Edit script EDITS.json (see docs/deform.md)");
  sub->add_option("--camera", opt->camera, "Key camera JSON for a new key (as written by 'vdg align')");
  sub->add_option("--view", opt->view, "View direction X,Y,Z for a new key without a camera");
  sub->add_option("--mesh", opt->mesh, "Mesh path for a new key, relative to the manifest (default KEY.obj)");
  sub->add_flag("--dry-run", opt->dry_run, "Report what each operation moves; write nothing");
  sub->add_flag("--undo", opt->undo, "Undo the key's last logged step (rebuilds it from its edit log)");
  sub->add_flag("-q,--quiet", opt->quiet, "Print nothing on success");
  sub->callback([opt] { runDeform(*opt); });
}

}  // namespace vdg::cli
