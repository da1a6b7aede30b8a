// vdg bake MODEL -o OUT.glb|OUT.gltf [--orbit N | --camera FILE [--count N]] [--frames A-B] [--fps F]
//          [camera options of render]
//
// The export of `vdg export` plus one animation for the camera path of `vdg render`: at the time
// of output frame f (f / fps seconds, counted from the first frame baked) the morph weights are
// exactly the view-dependent weights of frame f's camera, and an animated camera node is that
// camera, so a glTF viewer playing the animation through that camera shows what `vdg render`
// draws at each frame (docs/gltf-export.md, "Baked camera paths").
#include <algorithm>
#include <cstdio>
#include <limits>
#include <memory>
#include <vector>

#include "camera_file.h"
#include "cli.h"
#include "orbit_options.h"
#include "vdg/geom/error.h"
#include "vdg/io/gltf_export.h"
#include "vdg/io/model.h"
#include "vdg/render/renderer.h"
#include "vdg/viewdep/animated_model.h"

namespace vdg::cli {

void writeGltfForCli(const std::string& output, const GltfExportInput& input, bool quiet);  // cmd_export.cpp
void checkGltfOutput(const std::string& output);                                            // cmd_export.cpp
GltfExportInput exportInputForCli(const OpenedInput& input);                                // cmd_export.cpp
void checkOutputIsNotInput(const std::string& output, const std::string& model, const OpenedInput& input);  // idem
void addMaxTargetsOption(CLI::App& sub, std::size_t& max_targets);                                          // idem

namespace {

constexpr double kMaxFps = 1000.0;

struct BakeOptions : CameraOptions {
  std::string model, output, size = "512x512";
  double fps = 24.0, sharpness = 0.0;
  bool step = false, quiet = false;
  std::size_t max_targets = std::numeric_limits<std::size_t>::max();
};

void run(const BakeOptions& opt) {
  checkGltfOutput(opt.output);
  const ImageSize size = parseImageSize(opt.size, 'x', render::kMaxImageSize, "--size");
  const FrameRange range = opt.range();
  FrameCameras file_cameras;
  if (!opt.camera_file.empty()) {
    checkInputFile(opt.camera_file, "camera");
    file_cameras.load(opt.camera_file, opt.count);
  }
  const OpenedInput opened = openModel(opt.model);
  checkOutputIsNotInput(opt.output, opt.model, opened);
  const double aspect = static_cast<double>(size.width) / size.height;
  // The whole orbit closes on itself: one more sample, frame 0 again, lets a looping viewer play it
  // without a seam.
  const bool whole_orbit = opt.camera_file.empty() && opt.camera.frames.empty() && opt.camera.orbit > 1;
  // Frame f's camera: --camera FILE's, or the orbit's about the model's centre.
  auto camera = [&](int f, const Eigen::Vector3d& center, double distance) {
    return file_cameras.fromFile() ? file_cameras.at(f) : opt.camera.camera(f, center, distance);
  };
  GltfExportInput input = exportInputForCli(opened);
  checkMaxTargets(input, opt.max_targets, opt.model);
  std::vector<Camera> cameras;
  if (opened.model) {
    const ViewDependentModel& model = *opened.model;
    // As vdg render: the distance fits the base and every key (ViewDependentModel::extentRadius()).
    const double distance = opt.camera.cameraDistance(model.extentRadius(), aspect);
    for (int f = range.first; f <= range.last; ++f) cameras.push_back(camera(f, model.center(), distance));
    input.bake = gltfBakedAnimation(bakeCameraPath(model, cameras, opt.fps, aspect, opt.sharpness, whole_orbit), input);
  } else {
    // As vdg render: the camera distance holds every frame of the base and every view's pose on it;
    // output frame f shows animation frame f mod N (loop) or min(f, N - 1).
    const AnimatedViewDependentModel& model = *opened.animated;
    const double distance = opt.camera.cameraDistance(model.extentRadius(), aspect);
    for (int f = range.first; f <= range.last; ++f) cameras.push_back(camera(f, model.center(), distance));
    const bool frame_targets = input.base_animation->mode == GltfBaseMode::kFrames;
    input.bake = gltfBakedAnimation(
        bakeAnimatedCameraPath(model, cameras, range.first, opt.fps, aspect, opt.sharpness, whole_orbit, frame_targets),
        input);
  }
  input.bake->step = opt.step;
  const std::string path =
      opt.camera_file.empty() ? "orbit " + std::to_string(opt.camera.orbit) : "camera " + opt.camera_file;
  input.bake->description = "vdg bake: " + path + " frames " + std::to_string(range.first) + "-" +
                            std::to_string(range.last) + " at " + std::to_string(opt.fps) + " fps" +
                            (whole_orbit ? ", closed loop" : "");
  writeGltfForCli(opt.output, input, opt.quiet);
}

}  // namespace

void addBakeCommand(CLI::App& app) {
  auto opt = std::make_shared<BakeOptions>();
  CLI::App* sub = app.add_subcommand(
      "bake",
      "Export the model as glTF 2.0 with an animation: the morph weights and the camera of vdg render's camera path");
  sub->add_option("MODEL", opt->model, "Model manifest (*.vdg.json), or a glTF model vdg exported")->required();
  sub->add_option("-o,--output", opt->output, "Output OUT.glb, or OUT.gltf with its buffer in OUT.bin beside it")
      ->required();
  opt->add(*sub,
           "Camera file (one fixed camera) or camera path ({\"camera_path\": ...}, docs/anim.md) "
           "instead of the orbit, as vdg render --camera");
  sub->add_option("--size", opt->size, "Image size WxH whose aspect ratio the camera gets (default 512x512)")
      ->check(imageSize('x', render::kMaxImageSize));
  sub->add_option("--frames", opt->camera.frames,
                  "Bake only frames A-B (or N) of the orbit (or of --count), 0 <= A <= B < --orbit");
  sub->add_option("--fps", opt->fps, "Frames per second of the animation (default 24)")->check(positiveNumber(kMaxFps));
  sub->add_option("--sharpness", opt->sharpness, "Blend sharpness alpha (default: the model's own)")
      ->check(positiveNumber());
  sub->add_flag("--step", opt->step,
                "STEP interpolation: hold each frame's weights and camera (default LINEAR: blend between frames)");
  sub->add_flag("-q,--quiet", opt->quiet, "Print nothing on success");
  addMaxTargetsOption(*sub, opt->max_targets);
  sub->callback([opt, sub] {
    opt->noteGiven(*sub);
    run(*opt);
  });
}

}  // namespace vdg::cli
