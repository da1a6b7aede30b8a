// vdg align MODEL --drawing IMG --points PAIRS.json [--ortho] (-o CAMERA.json | --key NAME)
//
// Solves a key camera from 2D-3D correspondences between a drawing and the base mesh (Rademacher
// 99, 3.1.1): DLT then Levenberg-Marquardt on the reprojection error (see vdg/deform/align.h).
// The drawing is read only for its pixel size. The camera JSON is a manifest key's "camera" object.
#include <stb/stb_image.h>

#include <cstdio>
#include <memory>
#include <nlohmann/json.hpp>

#include "cli.h"
#include "vdg/deform/align.h"
#include "vdg/deform/edits.h"
#include "vdg/geom/error.h"
#include "vdg/io/camera_json.h"
#include "vdg/io/manifest.h"
#include "vdg/io/mesh.h"
#include "vdg/io/point_pairs.h"
#include "vdg/io/read_file.h"
#include "vdg/morph/budget.h"
#include "vdg/viewdep/model.h"

namespace vdg::cli {
namespace {

struct AlignCliOptions {
  std::string model, drawing, points, output, size, key;
  bool ortho = false, json = false, quiet = false;
  double budget = morph::kDefaultBudget;
};

// The work (operations, vdg/morph/budget.h) of alignCamera: the DLT's 12 x 12 normal equations per
// pair, then per Levenberg-Marquardt iteration every pair's residual for the central-difference
// Jacobian (2 x 7 parameters) and for up to 20 damped steps.
double alignCost(std::size_t pairs, const AlignOptions& options) {
  constexpr double kDltPerPair = 144, kResidualsPerIteration = 2 * 7 + 20;
  return static_cast<double>(pairs) * (kDltPerPair + options.max_iterations * kResidualsPerIteration);
}

// Drawings larger than this a side are refused (a scan at 600 dpi of an A0 sheet is about 28000).
constexpr int kMaxDrawingSide = 65536;

// The pixel size of a drawing, read from its header only.
ImageSize drawingSize(const std::string& path) {
  checkInputFile(path, "drawing");
  int width = 0, height = 0, channels = 0;
  if (!stbi_info(path.c_str(), &width, &height, &channels))
    throw Error(path + ": cannot read the drawing's size (" +
                (stbi_failure_reason() ? stbi_failure_reason() : "unknown format") + ")");
  if (width < 1 || height < 1 || width > kMaxDrawingSide || height > kMaxDrawingSide)
    throw Error(path + ": the drawing claims to be " + std::to_string(width) + "x" + std::to_string(height) +
                " pixels; vdg reads drawings of 1 to " + std::to_string(kMaxDrawingSide) + " pixels a side");
  return {width, height};
}

void runAlign(const AlignCliOptions& opt) {
  if (opt.drawing.empty() == opt.size.empty()) throw UsageError("give exactly one of --drawing IMG or --size WxH");
  if (opt.output.empty() && opt.key.empty()) throw UsageError("give -o CAMERA.json, --key NAME, or both");
  const bool is_obj = hasExtension(opt.model, ".obj");
  if (is_obj && !opt.key.empty()) throw UsageError("--key needs a model manifest, not a mesh");
  const ImageSize size =
      opt.drawing.empty() ? parseImageSize(opt.size, 'x', kMaxDrawingSide, "--size") : drawingSize(opt.drawing);
  const int width = size.width, height = size.height;
  RawViewDependentModel raw;
  if (is_obj)
    raw.base = readMesh(opt.model);
  else
    raw = loadManifest(opt.model);
  if (raw.animated())
    throw Error(opt.model +
                ": vdg align works on static models, and this one has an animated base ('base_animation'); align "
                "against the base posed at the key's frame as a mesh (vdg align FRAME.obj ... -o CAMERA.json)");
  const TriMesh& base = raw.base;
  RawKey* key = nullptr;
  if (!opt.key.empty()) {
    for (RawKey& k : raw.keys)
      if (k.name == opt.key) key = &k;
    if (!key)
      throw Error(opt.model + ": no key named '" + opt.key +
                  "' (make it first, for instance with vdg deform --key NAME --camera CAMERA.json)");
  }
  std::vector<Eigen::Vector3d> points;
  std::vector<Eigen::Vector2d> pixels;
  for (const PointPair& pair : readPointPairs(opt.points, base.vertexCount())) {
    if (pair.vertex) {
      const auto v = static_cast<std::size_t>(*pair.vertex);
      points.emplace_back(base.positions[3 * v], base.positions[3 * v + 1], base.positions[3 * v + 2]);
    } else {
      points.push_back(pair.point);
    }
    pixels.push_back(pair.pixel);
  }
  AlignOptions options;
  options.ortho = opt.ortho;
  morph::checkBudget(
      alignCost(points.size(), options), opt.budget, opt.points,
      std::to_string(points.size()) + " pairs x up to " + std::to_string(options.max_iterations) + " iterations",
      "give --budget N to allow more, or fewer pairs");
  const AlignResult r = alignCamera(points, pixels, width, height, options);
  if (key) {
    // The key's view follows its new camera (normalize(eye - centre)); everything is checked
    // before the manifest is replaced.
    key->camera = r.camera;
    raw.resolveViews();
    raw.validate();
  }
  if (!opt.output.empty()) writeCameraFile(opt.output, r.camera);
  if (key) saveManifest(opt.model, raw);
  if (opt.json) {
    nlohmann::json out;
    out["camera"] = nlohmann::json::parse(cameraToJson(r.camera));
    out["rms_px"] = r.rms_px;
    out["max_px"] = r.max_px;
    out["dlt_rms_px"] = r.dlt_rms_px;
    out["pairs"] = points.size();
    out["image_size"] = {width, height};
    std::printf("%s\n", out.dump(2).c_str());
  } else if (!opt.quiet) {
    std::printf("aligned %s camera from %zu pairs on a %dx%d drawing: RMS error %.4g px (max %.4g px; DLT %.4g px)\n",
                r.camera.isOrtho() ? "parallel" : "perspective", points.size(), width, height, r.rms_px, r.max_px,
                r.dlt_rms_px);
    if (!opt.output.empty()) std::printf("wrote %s\n", opt.output.c_str());
    if (key) std::printf("stored the camera in key '%s' of %s\n", key->name.c_str(), opt.model.c_str());
  }
}

}  // namespace

void addAlignCommand(CLI::App& app) {
  auto opt = std::make_shared<AlignCliOptions>();
  CLI::App* sub =
      app.add_subcommand("align", "Solve a key camera from point pairs between a drawing and the base mesh");
  sub->add_option("MODEL", opt->model, "Model manifest (*.vdg.json; its base mesh is used) or a mesh (.obj)")
      ->required();
  sub->add_option("--drawing", opt->drawing, "The drawing (PNG, JPEG, ...), read for its pixel size");
  sub->add_option("--size", opt->size,
                  "Drawing size WxH in pixels instead of --drawing (the old W,H is accepted for this version, "
                  "with a deprecation note)")
      ->transform(oldCommaSize())
      ->check(imageSize('x', kMaxDrawingSide));
  sub->add_option("--points", opt->points,
                  "Point pairs JSON: {\"pairs\": [{\"vertex\": I | \"point\": [x,y,z], \"pixel\": [x,y]}, ...]}")
      ->required();
  sub->add_flag("--ortho", opt->ortho, "Solve a parallel (orthographic) camera");
  sub->add_option("-o,--output", opt->output, "Camera JSON to write");
  sub->add_option("--key", opt->key, "Also store the camera in this key of the manifest (its view follows)");
  sub->add_flag("--json", opt->json, "Print the result as JSON");
  sub->add_option("--budget", opt->budget,
                  "Refuse, before solving, work estimated above N operations (default 2e9; each pair costs about "
                  "7000 residuals: a million pairs is refused)")
      ->check(positiveNumber(morph::kMaxBudget));
  sub->add_flag("-q,--quiet", opt->quiet, "Print nothing on success");
  sub->callback([opt] { runAlign(*opt); });
}

}  // namespace vdg::cli
