// vdg render MODEL -o DIR|OUT.mp4|OUT.gif [--orbit N | --camera FILE [--count N]] [--frames A-B] [--observer] ...
//
// Renders a view-dependent model (a manifest or a glTF file vdg exported) or a plain mesh headless with the NPR
// renderer, one PNG per frame (DIR/frame_0000.png ...), the camera going once around the model in N frames, or
// given by a file: a camera file (io/camera_json.h) holds one fixed camera, a camera path (an animation spec
// {"camera_path": ...}, io/anim_json.h) moves the camera over [start_time, end_time], frame i of --count N at
// time start + (end - start) * i / (N - 1). A frame's image depends only on its number and the options, so
// --frames ranges can be split across machines and give byte-identical frames.
//
// Framing fits what will be drawn: the base and every key (of an animated model at every frame), so a
// key that raises the model's top stays in the frame (ViewDependentModel::extentRadius()).
//
// An animated model (manifest "base_animation", M frames) advances one animation frame per output
// frame: output frame f shows animation frame f mod M when the animation loops, min(f, M - 1)
// (the last pose held) when it does not. The frame depends only on f, so ranges stay
// byte-identical. --hold-frame F shows animation frame F in every output frame instead (the
// paper's Figure 10: one moment of the animation seen from a moving camera); --base-only draws
// the base without key deformations (Figure 11, against the view-dependent Figure 12).
//
// Surfaces: seams of the mesh are welded (never inked), true holes are inked unless --no-borders,
// --creases DEG inks sharp edges, and the mesh's materials and textures colour it unless
// --no-materials (docs/render.md: the paper's equation per material and per texel).
//
// --drawing-textures blends the keys' reference drawings (the manifest's "drawing", version 5) over the
// model as view-dependent textures with the shape's weights (vdg/render/drawing_textures.h,
// docs/drawing-textures.md); --drawing-mode fill-ink or flat prepares each drawing first
// (--contour-threshold, --contour-dilation).
//
// --gpu-blend blends the model, computes its normals and finds its silhouettes on the GPU
// (Renderer::addBlendModel; OpenGL 4.3), for static view-dependent models; the frames equal the
// CPU path's within rounding.
#include <sys/stat.h>
#include <unistd.h>
#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "camera_file.h"
#include "cli.h"
#include "orbit_options.h"
#include "vdg/anim/camera_path.h"
#include "vdg/geom/error.h"
#include "vdg/geom/text.h"
#include "vdg/io/anim_json.h"
#include "vdg/io/atomic_file.h"
#include "vdg/io/camera_json.h"
#include "vdg/io/mesh.h"
#include "vdg/io/model.h"
#include "vdg/io/read_file.h"
#include "vdg/render/model_renderer.h"
#include "vdg/viewdep/animated_model.h"
#include "video.h"

namespace vdg::cli {
namespace {

namespace fs = std::filesystem;

struct RenderOptions : CameraOptions {
  std::string model, output, size = "512x512", color, background;
  int samples = 8;
  double sharpness = 0.0, line_width = 0.0, creases = 0.0;
  std::string line_width_mode = "screen";             // fixed | screen (render::StrokeWidthMode)
  double line_width_min = 0.0, line_width_max = 0.0;  // 0: not given
  bool observer = false, sphere = false, flat = false, quiet = false, base_only = false;
  bool no_borders = false, no_materials = false, strict = false, gpu_blend = false;
  int hold_frame = -1;  // -1: advance one animation frame per output frame
  bool drawing_textures = false;
  std::string drawing_mode = "as-drawn";  // as-drawn | fill-ink | flat (render::DrawingMode)
  double contour_threshold = render::DrawingStyle{}.contour_threshold;
  int contour_dilation = render::DrawingStyle{}.dilation;
};

// Option ranges (checked at parse time by the validators in cli.h; see docs/render.md; the
// camera's are in orbit_options.h).
constexpr int kMaxSamples = 64;           // the driver caps it further
constexpr double kMaxLineWidth = 1000.0;  // pixels
constexpr double kMaxCreaseDeg = 180.0;   // no two faces' normals are further apart
constexpr int kDriverQuerySide = 4096;    // larger canvases are checked against the driver's limit

// The canvas is twice as wide with the observer panel; both sides must fit the OpenGL driver.
void checkCanvas(const std::string& size_text, const render::FrameOptions& fo) {
  const int canvas_width = fo.observer ? 2 * fo.width : fo.width;
  const std::string observer = fo.observer ? " (with --observer the canvas is twice as wide)" : "";
  if (canvas_width > render::kMaxImageSize)
    throw UsageError("--size: expected a width in [1, " + std::to_string(render::kMaxImageSize / 2) +
                     "] with --observer (the canvas is twice as wide), got " + quotedText(size_text));
  if (std::max(canvas_width, fo.height) <= kDriverQuerySide) return;
  const int limit = render::maxImageSide();
  if (canvas_width > limit || fo.height > limit)
    throw UsageError("--size: this machine's OpenGL driver draws at most " + std::to_string(limit) + " pixels a side" +
                     observer + ", got " + quotedText(size_text));
}

render::Rgb parseColor(const std::string& text, const std::string& option) {
  const Eigen::Vector3d v = parseVec3(text, option);
  if (v.minCoeff() < 0.0 || v.maxCoeff() > 1.0)
    throw UsageError(option + ": expected R,G,B with each channel in [0, 1], got " + quotedText(text));
  return {static_cast<float>(v.x()), static_cast<float>(v.y()), static_cast<float>(v.z())};
}

// The renderer's settings from the command line. Numeric options were range-checked while parsing
// (addRenderCommand); what is left here needs several options together, or the OpenGL driver.
render::FrameOptions frameOptions(const RenderOptions& opt) {
  render::FrameOptions fo;
  const ImageSize size = parseImageSize(opt.size, 'x', render::kMaxImageSize, "--size");
  fo.width = size.width;
  fo.height = size.height;
  fo.samples = opt.samples;
  fo.observer = opt.observer;
  fo.sphere = opt.sphere;
  fo.sharpness = opt.sharpness;
  fo.flat = opt.flat;
  fo.base_only = opt.base_only;
  fo.silhouette_width = static_cast<float>(opt.line_width);
  fo.stroke_mode = opt.line_width_mode == "fixed" ? render::StrokeWidthMode::fixed : render::StrokeWidthMode::screen;
  if (fo.stroke_mode == render::StrokeWidthMode::fixed && (opt.line_width_min > 0.0 || opt.line_width_max > 0.0))
    throw UsageError(std::string(opt.line_width_min > 0.0 ? "--line-width-min" : "--line-width-max") +
                     ": only with --line-width-mode screen (a fixed width has no range)");
  if (opt.line_width_min > 0.0) fo.stroke_min = static_cast<float>(opt.line_width_min);
  fo.stroke_max = static_cast<float>(opt.line_width_max);
  if (opt.line_width_max > 0.0 && opt.line_width_max < fo.stroke_min)
    throw UsageError("--line-width-max: expected at least --line-width-min (" + numberText(fo.stroke_min) + "), got " +
                     numberText(opt.line_width_max));
  fo.crease_angle_deg = static_cast<float>(opt.creases);
  fo.borders = !opt.no_borders;
  fo.materials = !opt.no_materials;
  fo.gpu_blend = opt.gpu_blend;
  if (!opt.color.empty()) fo.color = parseColor(opt.color, "--color");
  if (!opt.background.empty()) fo.background = parseColor(opt.background, "--background");
  return fo;
}

// The model, a manifest or a glTF file vdg exported (mesh.extras.vdg), or a plain mesh (OBJ, glTF).
// Material and texture problems (of the mesh, or of a model's base): one "warning: ..." line each,
// the surface falls back to its base colour (or --color); --strict makes them errors.
// --no-materials opens no material library or texture.
OpenedInput openRendered(const RenderOptions& opt) {
  checkInputFile(opt.model, isObjPath(opt.model) || isGltfPath(opt.model) ? "mesh" : "model");
  std::vector<std::string> warnings;
  MeshReadOptions read;
  read.materials = !opt.no_materials;
  read.strict = opt.strict;
  read.warnings = &warnings;
  OpenedInput input = openInput(opt.model, read);
  for (const std::string& w : warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
  const AnimatedViewDependentModel* animated = input.animated.get();
  if (opt.hold_frame >= 0 && !animated)
    throw UsageError("--hold-frame: " + opt.model + " is not an animated model (no 'base_animation')");
  if (animated && opt.hold_frame >= animated->frameCount())
    throw UsageError("--hold-frame: expected a frame in [0, " + std::to_string(animated->frameCount() - 1) + "] (" +
                     opt.model + " has " + std::to_string(animated->frameCount()) + " frames), got " +
                     std::to_string(opt.hold_frame));
  if (opt.gpu_blend && !input.model)
    throw UsageError("--gpu-blend: " + opt.model + " is " +
                     (animated ? "an animated model (base_animation), which is blended on the CPU"
                               : "a plain mesh, with no keys to blend") +
                     "; the GPU blend takes static view-dependent models");
  return input;
}

// --drawing-textures: the keys' drawings (raw keys matched to the built model's by name), prepared
// and projected. The options that shape them need --drawing-textures.
std::shared_ptr<const render::DrawingTextures> drawingTextures(const RenderOptions& opt, const OpenedInput& input) {
  const bool shaped = opt.drawing_mode != "as-drawn" ||
                      opt.contour_threshold != render::DrawingStyle{}.contour_threshold ||
                      opt.contour_dilation != render::DrawingStyle{}.dilation;
  if (!opt.drawing_textures) {
    if (shaped) throw UsageError("--drawing-mode, --contour-threshold and --contour-dilation need --drawing-textures");
    return nullptr;
  }
  if (!input.model)
    throw UsageError("--drawing-textures: " + opt.model + " is " +
                     (input.animated ? "an animated model; drawing textures take a static model"
                                     : "a plain mesh, with no key drawings"));
  if (opt.gpu_blend)
    throw UsageError("--drawing-textures: not with --gpu-blend (the drawings are blended on the CPU path)");
  const ViewDependentModel& model = *input.model;
  std::vector<std::shared_ptr<const TextureImage>> drawings(model.keyCount());
  for (std::size_t k = 0; k < model.keyCount(); ++k)
    for (const RawKey& key : input.raw.keys)
      if (key.name == model.keyName(k)) drawings[k] = key.drawing;
  if (std::none_of(drawings.begin(), drawings.end(), [](const auto& d) { return d != nullptr; }))
    throw UsageError("--drawing-textures: " + opt.model + " has no key with a 'drawing' (manifest version 5)");
  render::DrawingStyle style;
  style.mode = opt.drawing_mode == "flat"       ? render::DrawingMode::kFlat
               : opt.drawing_mode == "fill-ink" ? render::DrawingMode::kFillInk
                                                : render::DrawingMode::kAsDrawn;
  style.contour_threshold = static_cast<float>(opt.contour_threshold);
  style.dilation = opt.contour_dilation;
  return std::make_shared<const render::DrawingTextures>(render::DrawingTextures::build(model, drawings, style));
}

// Where the orbit turns and how far it must stay: the centre, and the radius of the sphere about it
// holding what will be drawn (the base and every key; of an animated model, at every frame), so
// that a key that raises the top stays in the frame.
struct Framing {
  Eigen::Vector3d center;
  double radius = 0.0;
};

Framing framing(const OpenedInput& input) {
  if (input.model) return {input.model->center(), input.model->extentRadius()};
  if (input.animated) return {input.animated->center(), input.animated->extentRadius()};
  const auto bc = computeBounds(input.mesh.positions).center();
  const Eigen::Vector3d center(bc[0], bc[1], bc[2]);
  return {center, OrbitOptions::radiusAbout(input.mesh.positions, center)};
}

void run(const RenderOptions& opt) {
  render::FrameOptions fo = frameOptions(opt);
  const FrameRange range = opt.range();
  checkCanvas(opt.size, fo);

  const bool video = isVideoPath(opt.output);
  if (video) requireFfmpeg("-o " + opt.output, "write PNG frames with -o DIR");

  FrameCameras cameras;
  if (!opt.camera_file.empty()) {
    checkInputFile(opt.camera_file, "camera");
    cameras.load(opt.camera_file, opt.count);
  }

  const OpenedInput input = openRendered(opt);
  fo.drawings = drawingTextures(opt, input);
  const AnimatedViewDependentModel* animated = input.animated.get();
  if (!input.isModel()) fo.sphere = false;
  const Framing frame = framing(input);
  const double aspect = static_cast<double>(fo.width) / fo.height;
  const double distance = opt.camera.cameraDistance(frame.radius, aspect);
  fo.observer_camera = render::orbitCamera(frame.center, render::fitDistance(frame.radius, opt.camera.fov, aspect),
                                           opt.camera.azimuth + 35.0, 25.0, opt.camera.fov);
  const std::unique_ptr<render::ModelRenderer> renderer =
      input.model ? std::make_unique<render::ModelRenderer>(*input.model, fo)
      : animated  ? std::make_unique<render::ModelRenderer>(*animated, fo)
                  : std::make_unique<render::ModelRenderer>(input.mesh, fo);

  // Frames go to DIR, or for a video to a scratch folder beside it.
  const fs::path out_dir = video ? fs::path(opt.output + ".frames") : fs::path(opt.output);
  std::error_code ec;
  makeOutputFolder(out_dir.string(), ec);  // removed again when the run fails
  if (ec || !fs::is_directory(out_dir)) throw Error("-o " + out_dir.string() + ": cannot create the folder");

  Progress progress("render", range.last - range.first + 1, opt.quiet);
  render::Image image;
  char name[32];
  for (int f = range.first; f <= range.last; ++f) {
    if (animated) {  // one animation frame per output frame, or the held one (see the top of this file)
      const int count = animated->frameCount();
      renderer->setFrame(opt.hold_frame >= 0 ? opt.hold_frame : animated->loop() ? f % count : std::min(f, count - 1));
    }
    renderer->render(cameras.fromFile() ? cameras.at(f) : opt.camera.camera(f, frame.center, distance), image);
    std::snprintf(name, sizeof name, "frame_%04d.png", f);
    render::writePng((out_dir / name).string(), image);
    progress.step(f - range.first + 1);
  }
  progress.finish();

  if (video) {
    encodeVideo("-o " + opt.output, opt.output, {out_dir.string(), range.first, range.last - range.first + 1});
    fs::remove_all(out_dir, ec);
  }
  if (!opt.quiet)
    std::printf("wrote %d frame%s (%dx%d) to %s\n", range.last - range.first + 1, range.last > range.first ? "s" : "",
                renderer->imageWidth(), renderer->imageHeight(), opt.output.c_str());
}

}  // namespace

void addRenderCommand(CLI::App& app) {
  auto opt = std::make_shared<RenderOptions>();
  CLI::App* sub = app.add_subcommand(
      "render",
      "Render a view-dependent model (or a plain mesh) headless: NPR shading and silhouettes, one PNG a frame");
  sub->add_option("MODEL", opt->model,
                  "Model manifest (*.vdg.json), a glTF model vdg exported, or a plain mesh (.obj, .gltf, .glb)")
      ->required();
  sub->add_option("-o,--output", opt->output, "Output folder for frame_NNNN.png, or OUT.mp4 / OUT.gif (needs ffmpeg)")
      ->required();
  opt->add(*sub,
           "Camera file (one fixed camera; vdg align writes them) or camera path "
           "({\"camera_path\": ...}, docs/anim.md) instead of the orbit");
  sub->add_option("--size", opt->size,
                  "Image size WxH of the main view, each side in [1, " + std::to_string(render::kMaxImageSize) +
                      "] and within the OpenGL driver's limits (default 512x512)")
      ->check(imageSize('x', render::kMaxImageSize));
  sub->add_option("--frames", opt->camera.frames,
                  "Render only frames A-B (or N) of the orbit (or of --count), 0 <= A <= B < --orbit");
  sub->add_flag("--observer", opt->observer, "Add the model seen from a fixed observer camera, to the right");
  sub->add_flag("--sphere", opt->sphere, "Add an inset of the viewing sphere (keys, hull, active triangle, view)");
  sub->add_option("--sharpness", opt->sharpness, "Blend sharpness alpha (default: the model's own)")
      ->check(positiveNumber());
  sub->add_option("--color", opt->color,
                  "Base colour R,G,B in [0,1] of surfaces without a material (all with --no-materials; default 1,1,1)");
  sub->add_option("--background", opt->background, "Background colour R,G,B in [0,1] (default 0.97,0.97,0.95)");
  sub->add_flag("--flat", opt->flat, "Flat (per-face) shading, for hard-edged models");
  sub->add_option("--hold-frame", opt->hold_frame,
                  "Animated models: show this animation frame in every output frame (default: advance one a frame)")
      ->check(wholeNumber(0, static_cast<long>(kMaxBaseFrames) - 1));
  sub->add_flag("--base-only", opt->base_only,
                "Draw the base model without its key deformations (to compare with the view-dependent model)");
  sub->add_option("--line-width", opt->line_width,
                  "Silhouette stroke width in pixels (default: max(3, height/100)); with --line-width-mode screen, "
                  "the width of a model whose bounding sphere spans half the image's height or more")
      ->check(positiveNumber(kMaxLineWidth));
  sub->add_option("--line-width-mode", opt->line_width_mode,
                  "screen: the stroke follows the model's size on screen (--line-width times its bounding "
                  "sphere's picture over half the image height, within --line-width-min/max); fixed: --line-width "
                  "always (default screen)")
      ->check(CLI::IsMember({"fixed", "screen"}));
  sub->add_option("--line-width-min", opt->line_width_min, "Screen mode: the thinnest stroke in pixels (default 1)")
      ->check(positiveNumber(kMaxLineWidth));
  sub->add_option("--line-width-max", opt->line_width_max,
                  "Screen mode: the thickest stroke in pixels (default: --line-width, or its default)")
      ->check(positiveNumber(kMaxLineWidth));
  sub->add_option("--creases", opt->creases,
                  "Ink creases: edges whose faces' normals differ by more than DEG degrees, in (0, 180] "
                  "(half the stroke width; default: none)")
      ->check(positiveNumber(kMaxCreaseDeg));
  sub->add_flag("--no-borders", opt->no_borders,
                "Do not ink the open borders (holes) of the surface; texture and normal seams are never inked");
  sub->add_flag("--no-materials", opt->no_materials,
                "Ignore the mesh's materials and textures: --color everywhere (default: each material's colour, "
                "times its texture)");
  sub->add_flag("--strict", opt->strict,
                "A missing or broken material library or texture of the mesh (or of a model's base) is an error "
                "(default: a warning, and the surface shows its base colour)");
  sub->add_flag("--gpu-blend", opt->gpu_blend,
                "Blend, shade and ink on the GPU (compute shaders; needs OpenGL 4.3): the same picture within "
                "rounding; static view-dependent models only");
  sub->add_flag("--drawing-textures", opt->drawing_textures,
                "Blend the keys' reference drawings (a key's \"drawing\" in the manifest) over the model as "
                "view-dependent textures, with the shape's weights; where no key sees the surface, the usual shading");
  sub->add_option("--drawing-mode", opt->drawing_mode,
                  "With --drawing-textures: as-drawn (the drawings as they are), fill-ink (ink lines filled from the "
                  "nearest colours, so they do not blend into ghost lines) or flat (each region between ink lines "
                  "in its median colour, ink filled) (default as-drawn)")
      ->check(CLI::IsMember({"as-drawn", "fill-ink", "flat"}));
  sub->add_option("--contour-threshold", opt->contour_threshold,
                  "fill-ink and flat: pixels darker than this luminance in (0, 1] are ink (default 0.3)")
      ->check(positiveNumber(1.0));
  sub->add_option("--contour-dilation", opt->contour_dilation,
                  "fill-ink and flat: grow the ink by N pixels, 0 to " + std::to_string(render::kMaxContourDilation) +
                      ", to take the lines' soft edges too (default 1)")
      ->check(wholeNumber(0, render::kMaxContourDilation));
  sub->add_option("--samples", opt->samples, "Multisample anti-aliasing samples (default 8, capped by the driver)")
      ->check(wholeNumber(1, kMaxSamples));
  sub->add_flag("-q,--quiet", opt->quiet, "No progress bar and no summary line");
  sub->callback([opt, sub] {
    opt->noteGiven(*sub);
    run(*opt);
  });
}

}  // namespace vdg::cli
