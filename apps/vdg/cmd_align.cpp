// vdg align MODEL --drawing IMG --points PAIRS.json [--ortho] (-o CAMERA.json | --key NAME)
//
// Solves a key camera from 2D-3D correspondences between a drawing and the base mesh (Rademacher
// 99, 3.1.1): DLT then Levenberg-Marquardt on the reprojection error (see vdg/deform/align.h).
// The drawing is read only for its pixel size. The camera JSON is a manifest key's "camera" object.
#include <stb/stb_image.h>

#include <cstdio>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>

#include "cli.h"
#include "vdg/deform/align.h"
#include "vdg/deform/edits.h"
#include "vdg/geom/error.h"
#include "vdg/io/camera_json.h"
#include "vdg/io/manifest.h"
#include "vdg/io/obj.h"
#include "vdg/viewdep/model.h"

namespace vdg::cli {
namespace {

struct AlignCliOptions {
  std::string model, drawing, points, output, size, key;
  bool ortho = false, json = false;
};

Eigen::Vector2d readVec2(const nlohmann::json& v, const std::string& where) {
  if (!v.is_array() || v.size() != 2 || !v[0].is_number() || !v[1].is_number())
    throw Error(where + " must be [x, y] (pixels)");
  return {v[0].get<double>(), v[1].get<double>()};
}

void readPairs(const std::string& path, const TriMesh& mesh, std::vector<Eigen::Vector3d>& points,
               std::vector<Eigen::Vector2d>& pixels) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path + ": cannot open the point pairs");
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw Error(path + ": invalid JSON: " + e.what());
  }
  const nlohmann::json* pairs = &j;
  if (j.is_object()) {
    if (!j.contains("pairs")) throw Error(path + ": expected {\"pairs\": [...]} or an array of pairs");
    pairs = &j.at("pairs");
  }
  if (!pairs->is_array()) throw Error(path + ": 'pairs' must be an array");
  for (std::size_t i = 0; i < pairs->size(); ++i) {
    const nlohmann::json& p = (*pairs)[i];
    const std::string where = path + ": pairs[" + std::to_string(i) + "]";
    if (!p.is_object() || !p.contains("pixel")) throw Error(where + ": needs 'pixel' and 'vertex' or 'point'");
    for (auto it = p.begin(); it != p.end(); ++it)
      if (it.key() != "pixel" && it.key() != "vertex" && it.key() != "point")
        throw Error(where + ": unknown field '" + it.key() + "'");
    if (p.contains("vertex") == p.contains("point")) throw Error(where + ": give exactly one of 'vertex' or 'point'");
    if (p.contains("vertex")) {
      if (!p["vertex"].is_number_integer()) throw Error(where + ": 'vertex' must be an integer");
      const std::int64_t v = p["vertex"].get<std::int64_t>();
      if (v < 0 || v >= static_cast<std::int64_t>(mesh.vertexCount()))
        throw Error(where + ": 'vertex' = " + std::to_string(v) + " is out of range (the base has " +
                    std::to_string(mesh.vertexCount()) + " vertices)");
      points.emplace_back(mesh.positions[3 * v], mesh.positions[3 * v + 1], mesh.positions[3 * v + 2]);
    } else {
      const nlohmann::json& q = p["point"];
      if (!q.is_array() || q.size() != 3 || !q[0].is_number() || !q[1].is_number() || !q[2].is_number())
        throw Error(where + ": 'point' must be [x, y, z]");
      points.emplace_back(q[0].get<double>(), q[1].get<double>(), q[2].get<double>());
    }
    pixels.push_back(readVec2(p["pixel"], where + ": 'pixel'"));
  }
}

void runAlign(const AlignCliOptions& opt) {
  if (opt.drawing.empty() == opt.size.empty()) throw UsageError("give exactly one of --drawing IMG or --size W,H");
  int width = 0, height = 0;
  if (!opt.drawing.empty()) {
    int channels = 0;
    if (!stbi_info(opt.drawing.c_str(), &width, &height, &channels))
      throw Error(opt.drawing + ": cannot read the drawing's size (" +
                  (stbi_failure_reason() ? stbi_failure_reason() : "unknown format") + ")");
  } else {
    char sep = 0;
    std::istringstream s(opt.size);
    if (!(s >> width >> sep >> height) || sep != ',' || width <= 0 || height <= 0 || !s.eof())
      throw UsageError("--size: expected W,H in pixels, got '" + opt.size + "'");
  }
  if (opt.output.empty() && opt.key.empty()) throw UsageError("give -o CAMERA.json, --key NAME, or both");
  const bool is_obj = opt.model.size() > 4 && opt.model.substr(opt.model.size() - 4) == ".obj";
  if (is_obj && !opt.key.empty()) throw UsageError("--key needs a model manifest, not a mesh");
  RawViewDependentModel raw;
  if (is_obj)
    raw.base = readMesh(opt.model);
  else
    raw = loadManifest(opt.model);
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
  readPairs(opt.points, base, points, pixels);
  AlignOptions options;
  options.ortho = opt.ortho;
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
  } else {
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
  sub->add_option("--size", opt->size, "Drawing size W,H in pixels instead of --drawing");
  sub->add_option("--points", opt->points,
                  "Point pairs JSON: {\"pairs\": [{\"vertex\": I | \"point\": [x,y,z], \"pixel\": [x,y]}, ...]}")
      ->required();
  sub->add_flag("--ortho", opt->ortho, "Solve a parallel (orthographic) camera");
  sub->add_option("-o,--output", opt->output, "Camera JSON to write");
  sub->add_option("--key", opt->key, "Also store the camera in this key of the manifest (its view follows)");
  sub->add_flag("--json", opt->json, "Print the result as JSON");
  sub->callback([opt] { runAlign(*opt); });
}

}  // namespace vdg::cli
