// vdg implicit BLOBS.json -o OUT.obj [--frame F] [--voxel S]
// vdg implicit BLOBS.json --frames A-B -o DIR [--voxel S]
//
// Polygonises blobby objects, soft objects and metaballs (Parent 4.11; vdg/morph/implicit.h for
// the field functions, vdg/io/blob_files.h and docs/implicit.md for BLOBS.json) into a closed
// triangle mesh. One frame goes to an OBJ file; a sequence goes into a folder as
// DIR/frame_NNNN.obj (NNNN the frame number), with DIR/camera.json (one fixed camera framing every
// frame, so that `vdg render DIR/frame_NNNN.obj --camera DIR/camera.json` frames the whole
// sequence alike) and DIR/sequence.json (what was written). The topology changes from frame to
// frame (blobs fuse and split), so the frames are separate meshes, not a model's
// `base_animation` (which needs one vertex count).
//
// Every frame's grid is checked against the voxel budget before anything is computed, and a
// sequence is staged beside its targets and renamed into place only when every frame has been
// polygonised: a failure writes nothing. One voxel size serves every frame of a sequence (the
// file's "voxel", --voxel, or the default over the union of the frames' bounds), so the surface
// does not shimmer from frame to frame.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli.h"
#include "vdg/geom/camera.h"
#include "vdg/geom/error.h"
#include "vdg/geom/text.h"
#include "vdg/io/atomic_file.h"
#include "vdg/io/blob_files.h"
#include "vdg/io/camera_json.h"
#include "vdg/io/obj.h"
#include "vdg/morph/budget.h"
#include "vdg/morph/implicit.h"
#include "vdg/morph/polygonise.h"

namespace vdg::cli {
namespace {

namespace fs = std::filesystem;

// The largest grid one frame may use (1 GiB at kBytesPerVoxel).
constexpr std::size_t kMaxVoxels = std::size_t{1} << 27;

struct ImplicitOptions {
  std::string input, output, frames;
  double frame = 0, voxel = 0, budget = morph::kDefaultBudget;
  bool frame_given = false, quiet = false;
};

// "frame_0012.obj"
std::string frameName(int frame) {
  char name[32];
  std::snprintf(name, sizeof name, "frame_%04d.obj", frame);
  return name;
}

std::string header(const ImplicitOptions& opt, double frame, double h) {
  char line[160];
  std::snprintf(line, sizeof line, "vdg implicit: frame %.6g, voxel %.6g", frame, h);
  return line + std::string(" of ") + fs::path(opt.input).filename().string();
}

// A fixed camera (field of view 30 degrees, from +Z raised 15 degrees, as vdg render's default
// orbit) whose view holds the sphere around `box` with a 10% margin.
Camera framingCamera(const Eigen::AlignedBox3d& box) {
  const Eigen::Vector3d centre = box.center();
  const double radius = std::max(0.5 * box.diagonal().norm(), 1e-6);
  const double fov = 30.0, elevation = 15.0 * M_PI / 180.0;
  const double distance = 1.1 * radius / std::sin(0.5 * fov * M_PI / 180.0);
  Camera c;
  c.target = centre;
  c.eye = centre + distance * Eigen::Vector3d(0, std::sin(elevation), std::cos(elevation));
  c.up = Eigen::Vector3d(0, 1, 0);
  c.fov_deg = fov;
  return c;
}

Eigen::AlignedBox3d meshBox(const TriMesh& mesh) {
  Eigen::AlignedBox3d box;
  for (std::size_t v = 0; v < mesh.vertexCount(); ++v)
    box.extend(Eigen::Vector3d(mesh.positions[3 * v], mesh.positions[3 * v + 1], mesh.positions[3 * v + 2]));
  return box;
}

// The work of the frames up to `upto` already passes --budget (vdg/morph/budget.h): refused before
// any frame is polygonised. Every primitive is evaluated at every voxel of its support box, so many
// primitives over one spot, a fine voxel or many frames multiply the work.
[[noreturn]] void refuseWork(const ImplicitOptions& opt, const std::vector<double>& frames, double work, double upto) {
  // The frames not yet estimated are taken to cost what the first ones did on average.
  const double done = upto - frames.front() + 1;
  const auto total = static_cast<double>(frames.size());
  const std::string detail = frames.size() == 1
                                 ? "the primitives' fields at every voxel of their supports"
                                 : std::to_string(frames.size()) + " frames, from the first " +
                                       std::to_string(static_cast<long>(done)) + (done == 1 ? "" : " on average");
  morph::checkBudget(work * total / done, opt.budget, opt.input, detail,
                     "give --budget N to allow more, or a larger --voxel, fewer primitives or fewer frames");
  throw Error(opt.input + ": work past the budget");  // not reached: checkBudget throws
}

// The voxel size of every frame (the option's, the file's, or the default over the union of the
// frames' bounds), once every frame's grid has passed the voxel limit and the frames' work
// together has passed --budget: nothing is computed before. `model` is a pose of `animation`.
double checkFrames(const ImplicitOptions& opt, const BlobFile& file, const morph::BlobAnimation& animation,
                   const std::vector<double>& frames, morph::BlobModel& model) {
  // Posing every primitive at every frame (twice, below) is work too.
  const double posing = 2.0 * static_cast<double>(frames.size()) * static_cast<double>(animation.primitiveCount());
  morph::checkBudget(
      posing, opt.budget, opt.input,
      std::to_string(animation.primitiveCount()) + " primitives posed at " + std::to_string(frames.size()) + " frames",
      "give --budget N to allow more, or fewer frames");
  // One voxel size for every frame, then every frame's grid checked before any work.
  Eigen::AlignedBox3d all;
  for (double f : frames) {
    if (!animation.evaluate(f, model)) throw Error(opt.input + ": cannot evaluate frame " + numberText(f));
    all.extend(model.bounds());
  }
  const double h = opt.voxel > 0 ? opt.voxel : file.voxel_size > 0 ? file.voxel_size : morph::defaultVoxelSize(all);
  if (all.isEmpty()) throw Error(opt.input + ": no primitive adds to the field, so there is no surface");
  double work = 0;
  for (double f : frames) {
    if (!animation.evaluate(f, model)) throw Error(opt.input + ": cannot evaluate frame " + numberText(f));
    if (!model.bounds().isEmpty())
      morph::checkVoxelBudget(
          model.bounds(), h, kMaxVoxels,
          opt.input + (!opt.frames.empty() ? ": frame " + std::to_string(static_cast<long>(f)) : std::string()));
    work += morph::polygoniseCost(model, h);
    if (work > opt.budget) refuseWork(opt, frames, work, f);
  }
  return h;
}

void runImplicit(const ImplicitOptions& opt) {
  const bool sequence = !opt.frames.empty();
  if (sequence && opt.frame_given) throw UsageError("--frame and --frames exclude each other");
  if (!sequence && !hasExtension(opt.output, ".obj"))
    throw UsageError("-o: expected an OBJ file (.obj) for one frame, got " + quotedText(opt.output) +
                     "; give --frames A-B to write a sequence into a folder");
  FrameRange range;
  if (sequence) {
    range = parseFrameRange(opt.frames, "--frames");
    if (static_cast<long>(range.last) - range.first + 1 > kMaxBlobFrames)
      throw UsageError("--frames: at most " + std::to_string(kMaxBlobFrames) + " frames, got " +
                       quotedText(opt.frames));
  }

  const BlobFile file = readBlobFile(opt.input);
  const morph::BlobAnimation animation = morph::BlobAnimation::build(file.animation, opt.input);
  std::vector<double> frames;
  if (sequence) {
    for (long f = range.first; f <= range.last; ++f) frames.push_back(static_cast<double>(f));
  } else {
    frames.push_back(opt.frame_given ? opt.frame : static_cast<double>(animation.firstFrame()));
  }

  morph::BlobModel model = animation.modelAt(frames.front());
  const double h = checkFrames(opt, file, animation, frames, model);

  if (!sequence) {
    if (!animation.evaluate(frames.front(), model)) throw Error(opt.input + ": cannot evaluate the frame");
    const TriMesh mesh = morph::polygonise(model, {.voxel_size = h, .max_voxels = kMaxVoxels}, opt.input);
    if (mesh.triangles.empty())
      throw Error(opt.input + ": the field reaches the threshold " + numberText(animation.threshold()) +
                  " nowhere at frame " + numberText(frames.front()) + ": no surface");
    writeObj(opt.output, mesh, header(opt, frames.front(), h));
    if (!opt.quiet)
      std::printf("wrote %s: %zu vertices, %zu triangles, %zu component%s (voxel %.6g)\n", opt.output.c_str(),
                  mesh.vertexCount(), mesh.triangleCount(), morph::connectedComponents(mesh),
                  morph::connectedComponents(mesh) == 1 ? "" : "s", h);
    return;
  }

  // Sequence: the folder (made when missing), every frame staged, then all renamed into place.
  const fs::path dir(opt.output);
  std::error_code ec;
  if (fs::exists(fs::symlink_status(dir, ec)) && !fs::is_directory(dir, ec))
    throw Error(opt.output + ": exists and is not a folder");
  const bool made_dir = !fs::exists(dir, ec);
  if (made_dir && !makeOutputFolder(dir.string(), ec))
    throw Error(opt.output + ": cannot make the folder: " + ec.message());
  std::vector<StagedFile> staged;
  try {
    Progress progress("implicit", static_cast<long>(frames.size()), opt.quiet);
    Eigen::AlignedBox3d drawn;
    nlohmann::json list = nlohmann::json::array();
    for (std::size_t i = 0; i < frames.size(); ++i) {
      const int f = static_cast<int>(frames[i]);
      if (!animation.evaluate(frames[i], model)) throw Error(opt.input + ": cannot evaluate frame " + numberText(f));
      const TriMesh mesh = morph::polygonise(model, {.voxel_size = h, .max_voxels = kMaxVoxels},
                                             opt.input + ": frame " + std::to_string(f));
      if (mesh.triangles.empty())
        throw Error(opt.input + ": frame " + std::to_string(f) + ": the field reaches the threshold " +
                    numberText(animation.threshold()) + " nowhere: no surface");
      drawn.extend(meshBox(mesh));
      staged.emplace_back((dir / frameName(f)).string(), formatObj(mesh, header(opt, frames[i], h)));
      list.push_back({{"frame", f},
                      {"file", frameName(f)},
                      {"vertices", mesh.vertexCount()},
                      {"triangles", mesh.triangleCount()},
                      {"components", morph::connectedComponents(mesh)}});
      progress.step(static_cast<long>(i + 1));
    }
    progress.finish();
    const Camera camera = framingCamera(drawn);
    nlohmann::json camera_json = nlohmann::json::parse(cameraToJson(camera));
    camera_json["version"] = kCameraFileVersion;
    staged.emplace_back((dir / "camera.json").string(), camera_json.dump(2) + "\n");
    const nlohmann::json manifest = {{"version", 1},
                                     {"source", fs::path(opt.input).filename().string()},
                                     {"frames", {range.first, range.last}},
                                     {"pattern", "frame_%04d.obj"},
                                     {"voxel", h},
                                     {"camera", "camera.json"},
                                     {"render", "vdg render DIR/frame_NNNN.obj --camera DIR/camera.json -o OUT"},
                                     {"files", list}};
    staged.emplace_back((dir / "sequence.json").string(), manifest.dump(2) + "\n");
    for (StagedFile& s : staged) s.commit();
  } catch (...) {
    staged.clear();  // removes the temporary files
    if (made_dir) fs::remove(dir, ec);
    throw;
  }
  if (!opt.quiet)
    std::printf("wrote %zu frames to %s (%s ... %s, camera.json, sequence.json; voxel %.6g)\n", frames.size(),
                opt.output.c_str(), frameName(range.first).c_str(), frameName(range.last).c_str(), h);
}

}  // namespace

void addImplicitCommand(CLI::App& app) {
  auto opt = std::make_shared<ImplicitOptions>();
  CLI::App* sub = app.add_subcommand(
      "implicit", "Polygonise blobby objects, soft objects and metaballs (BLOBS.json) into closed meshes");
  sub->add_option("BLOBS", opt->input, "Blob file BLOBS.json (see docs/implicit.md)")->required();
  sub->add_option("-o,--output", opt->output, "OBJ file for one frame, or a folder with --frames")->required();
  sub->add_option("--frame", opt->frame, "The frame to polygonise (default: the file's first frame)")
      ->check(finiteNumber())
      ->each([opt](const std::string&) { opt->frame_given = true; });
  sub->add_option("--frames", opt->frames,
                  "Write frames A-B (or N) into the folder -o as frame_NNNN.obj, with camera.json and sequence.json");
  sub->add_option("--voxel", opt->voxel, "Voxel size in model units (default: the file's, else the extent / 96)")
      ->check(positiveNumber(1e15));
  sub->add_option("--budget", opt->budget,
                  "Refuse, before any frame is polygonised, work estimated above N operations (default 2e9: "
                  "seconds to about a minute; each frame costs its grid plus every primitive at every voxel of its "
                  "support; docs/implicit.md, 'Budgets')")
      ->check(positiveNumber(morph::kMaxBudget));
  sub->add_flag("-q,--quiet", opt->quiet, "Print nothing on success (no progress either)");
  sub->callback([opt] { runImplicit(*opt); });
}

}  // namespace vdg::cli
