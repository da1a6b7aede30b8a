// vdg run SCRIPT.lua [--frames A-B] [-o DIR] [--root DIR] [--cpu-seconds N] [--gpu-blend] [--quiet]
//
// Runs an animation script (the animation language of Parent 4.6 and 4.8 on Lua 5.4, see
// docs/language.md): the script builds a scene (objects, hierarchy, cameras, SET/CHANGE actions,
// tracks) and asks for renders with render{...}; then every requested frame is rendered with the
// NPR renderer into DIR/OUT/frame_NNNN.png (OUT the request's `out`, DIR the -o folder).
// The script runs once, before any frame is drawn, and only describes the animation: a frame's
// image depends on nothing but the scene and its number, so --frames A-B renders exactly the same
// bytes as the same frames of a full run, and ranges can be split across machines.
// The script runs in a child process (script/child_process.h) whose CPU time is limited while the
// script runs (--cpu-seconds); the child then renders, and this process ends as it ends.
// --gpu-blend blends the scene's static view-dependent models on the GPU, every instance of a
// model in one call (SceneFrameOptions::gpu_blend; OpenGL 4.3); the images equal the CPU path's
// within rounding.
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <string>

#include "cli.h"
#include "vdg/geom/error.h"
#include "vdg/io/atomic_file.h"
#include "vdg/render/image.h"
#include "vdg/render/scene_renderer.h"
#include "vdg/scene/scene.h"
#include "vdg/script/child_process.h"
#include "vdg/script/script.h"

namespace vdg::cli {
namespace {

namespace fs = std::filesystem;

struct RunOptions {
  std::string script, output = ".", frames, root;
  bool quiet = false, gpu_blend = false;
  int cpu_seconds = script::kDefaultCpuSeconds;
};

// The parent's side of the script's child process: the child's end becomes this process's end (its
// exit status, or death by the same signal), and a failed run's files made by io.open are removed.
void finishParent(const script::ChildOutcome& child, const RunOptions& opt) {
  if (child.end == script::ChildEnd::kExited && child.code == 0) return;
  for (const std::string& path : child.created) {
    std::error_code ec;
    if (fs::is_regular_file(fs::symlink_status(path, ec))) fs::remove(path, ec);
  }
  if (child.end == script::ChildEnd::kCpuExceeded)
    throw Error(opt.script + ": exceeded its CPU-time budget (" + std::to_string(opt.cpu_seconds) +
                " s of CPU; an endless computation such as a runaway pattern match? see vdg run --cpu-seconds)");
  if (child.end == script::ChildEnd::kSignaled) {
    std::signal(child.code, SIG_DFL);
    std::raise(child.code);
    throw Exit{128 + child.code};
  }
  throw Exit{child.code};  // the child has said why on stderr
}

void run(const RunOptions& opt) {
  FrameRange only;
  if (!opt.frames.empty()) only = parseFrameRange(opt.frames, "--frames");

  // The script runs in a child process (this command again) under a CPU-time limit, the backstop
  // of the instruction budget; the child goes on to render with the limits lifted, and this
  // process ends as it ends.
  if (!script::inLimitedChild()) {
    script::ProcessLimits limits;
    limits.cpu_seconds = opt.cpu_seconds;
    return finishParent(script::runLimitedChild(limits, script::thisProgramArguments()), opt);
  }

  script::ScriptOptions so;
  so.output_dir = opt.output;
  so.read_root = opt.root;
  so.created = script::announceCreated;
  // Actors need only be stepped up to the last frame rendered (every earlier frame is what a full
  // run gives; script.h, ScriptOptions::actor_last_frame).
  if (!opt.frames.empty()) so.actor_last_frame = only.last;
  const script::Shot shot = script::runScript(opt.script, so);
  script::liftLimits();
  if (shot.renders.empty()) {
    if (!opt.quiet) std::printf("%s asked for no frames (it has no render{...} call)\n", opt.script.c_str());
    return;
  }

  // Which frames of which request: each request's range, cut to --frames.
  long total = 0;
  std::vector<std::pair<int, int>> ranges;
  for (const auto& r : shot.renders) {
    int a = r.first_frame, b = r.last_frame;
    if (!opt.frames.empty()) {
      a = std::max(a, only.first);
      b = only.last >= only.first ? std::min(b, only.last) : b;
    }
    ranges.emplace_back(a, b);
    if (b >= a) total += b - a + 1;
  }
  if (total == 0) {
    std::string asked;
    for (const auto& r : shot.renders)
      asked += (asked.empty() ? "" : ", ") + std::to_string(r.first_frame) + "-" + std::to_string(r.last_frame);
    throw UsageError("--frames " + quotedText(opt.frames) + ": the script renders frames " + asked +
                     ", none of them in the range");
  }

  const scene::Scene scene = scene::Scene::build(shot.scene, opt.script);

  Progress progress("run", total, opt.quiet);
  long done = 0;
  render::Image image;
  char name[32];
  for (std::size_t k = 0; k < shot.renders.size(); ++k) {
    const script::RenderRequest& r = shot.renders[k];
    const auto [a, b] = ranges[k];
    if (b < a) continue;
    const fs::path dir = fs::path(opt.output) / r.out;
    std::error_code ec;
    makeOutputFolder(dir.string(), ec);  // removed again when the run fails
    if (ec || !fs::is_directory(dir))
      throw Error(opt.script + ":" + std::to_string(r.line) + ": render: cannot create the folder " + dir.string());
    render::SceneFrameOptions fo;
    fo.width = r.width;
    fo.height = r.height;
    fo.samples = r.samples;
    fo.background = r.background;
    fo.silhouette_width = r.silhouette_width;
    fo.crease_angle_deg = r.crease_angle_deg;
    // A scene without a camera is framed over the request's frames, never over --frames: a frame
    // rendered alone must equal the same frame of a full run.
    fo.frame_first = r.first_frame;
    fo.frame_last = r.last_frame;
    fo.gpu_blend = opt.gpu_blend;
    render::SceneRenderer renderer(scene, fo);
    for (int f = a; f <= b; ++f) {
      renderer.render(f, image);
      std::snprintf(name, sizeof name, "frame_%04d.png", f);
      render::writePng((dir / name).string(), image);
      progress.step(++done);
    }
  }
  progress.finish();
  if (!opt.quiet) std::printf("wrote %ld frame%s to %s\n", total, total == 1 ? "" : "s", opt.output.c_str());
}

}  // namespace

void addRunCommand(CLI::App& app) {
  auto opt = std::make_shared<RunOptions>();
  CLI::App* sub = app.add_subcommand(
      "run", "Run an animation script (Lua, see docs/language.md): build a scene and render the frames it asks for");
  sub->add_option("SCRIPT", opt->script, "The script (SCRIPT.lua)")->required();
  sub->add_option("-o,--output", opt->output,
                  "Output folder (default: the current folder); render{out=...} folders are made inside it, and "
                  "the script may write files only below it");
  sub->add_option("--frames", opt->frames,
                  "Render only frames A-B (or frame N) of what the script asks for; the images are byte-identical "
                  "to the same frames of a full run");
  sub->add_option("--root", opt->root,
                  "Folder the script may read below (its models and files; default: the script's own folder); "
                  "it must hold the script");
  sub->add_flag("--gpu-blend", opt->gpu_blend,
                "Blend the view-dependent models on the GPU, all instances of a model at once (needs OpenGL 4.3); "
                "animated models and plain meshes stay on the CPU");
  sub->add_option("--cpu-seconds", opt->cpu_seconds,
                  "CPU time the script may use while it runs and loads its models, in seconds (default " +
                      std::to_string(script::kDefaultCpuSeconds) +
                      "); the script runs in a child process killed past it, rendering is not limited")
      ->check(CLI::Range(1, script::kMaxCpuSeconds));
  sub->add_flag("-q,--quiet", opt->quiet, "No progress bar and no summary line");
  sub->callback([opt] { run(*opt); });
}

}  // namespace vdg::cli
