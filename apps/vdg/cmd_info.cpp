// vdg info MODEL [--json] | vdg info FILE.gltf|FILE.glb
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <numbers>

#include "cli.h"
#include "vdg/geom/error.h"
#include "vdg/io/gltf.h"
#include "vdg/io/gltf_export.h"
#include "vdg/io/manifest.h"
#include "vdg/viewdep/animated_model.h"
#include "vdg/viewdep/model.h"

namespace vdg::cli {
namespace {

// Things an artist should know about a model that still loads. Each kind of per-key or per-pair
// warning is listed at most kMaxListed times, then summed up in one line: a model with thousands
// of keys must not print (or hold) a warning for every pair.
std::vector<std::string> modelWarnings(const ViewDependentModel& model) {
  std::vector<std::string> warnings;
  constexpr double kCloseKeysDeg = 5.0;  // keys closer than this make abrupt transitions
  constexpr double kLowCoverage = 0.25;  // below this, most views show the plain base model
  constexpr std::size_t kMaxListed = 20;
  // Counting stops here: past a million close pairs the exact number says nothing more.
  constexpr std::size_t kMaxCounted = 1000000;
  std::size_t unmoved = 0;
  for (std::size_t k = 0; k < model.keyCount(); ++k) {
    if (model.keyMovedCount(k) != 0) continue;
    if (++unmoved <= kMaxListed)
      warnings.push_back("key '" + model.keyName(k) + "' moves no vertex (it is identical to the base)");
  }
  if (unmoved > kMaxListed)
    warnings.push_back("... and " + std::to_string(unmoved - kMaxListed) + " more keys that move no vertex");
  // Close pairs through a grid on the sphere (O(n log n) plus the pairs counted), not all n^2 pairs.
  const auto views = model.sphere().points().first(model.keyCount());
  std::size_t close = 0;
  forEachCloseViewPair(views, kCloseKeysDeg * std::numbers::pi / 180.0,
                       [&](std::size_t k, std::size_t j, double angle) {
                         if (++close <= kMaxListed) {
                           const double deg = angle * 180.0 / std::numbers::pi;
                           warnings.push_back("keys '" + model.keyName(j) + "' and '" + model.keyName(k) +
                                              "' are only " + std::to_string(deg).substr(0, 4) +
                                              " degrees apart: the blend between them will be abrupt");
                         }
                         return close < kMaxCounted;
                       });
  if (close > kMaxListed)
    warnings.push_back("... and " + std::string(close >= kMaxCounted ? "at least " : "") +
                       std::to_string(close - kMaxListed) + " more close pairs of keys");
  if (model.sphere().coveredFraction() < kLowCoverage)
    warnings.push_back("real keys cover only " +
                       std::to_string(static_cast<int>(std::lround(100 * model.sphere().coveredFraction()))) +
                       "% of the viewing sphere; elsewhere the model blends towards the base");
  return warnings;
}

bool isGltf(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext == ".gltf" || ext == ".glb";
}

}  // namespace

void addInfoCommand(CLI::App& app) {
  struct Options {
    std::string model;
    bool json = false;
  };
  auto opt = std::make_shared<Options>();
  CLI::App* sub =
      app.add_subcommand("info",
                         "Describe a view-dependent model (mesh, keys, viewing-sphere hull, warnings) or a glTF file "
                         "(meshes, morph targets, skins, animations)");
  sub->add_option("MODEL", opt->model, "Model manifest (*.vdg.json), or a glTF 2.0 file (*.gltf, *.glb)")->required();
  sub->add_flag("--json", opt->json, "Print one JSON object instead of text");
  sub->callback([opt] {
    // A glTF file vdg exported (mesh.extras.vdg) is described as a model too.
    if (isGltf(opt->model)) {
      if (opt->json) throw UsageError("--json: only for models, not for glTF files");
      std::fputs(describeGltf(opt->model).c_str(), stdout);
      bool gltf_model = false;
      try {
        gltf_model = gltfHasModel(opt->model);
      } catch (const Error&) {
        // describeGltf read it; a file it describes but that is no model stays a description.
      }
      if (!gltf_model) return;
      std::printf("\nview-dependent model (mesh.extras.vdg):\n");
    }
    const RawViewDependentModel raw = loadModel(opt->model);
    if (raw.animated()) {
      const AnimatedViewDependentModel model = AnimatedViewDependentModel::build(raw);
      std::printf("model      %s\n", opt->model.c_str());
      std::printf("base       animated: %d frames%s, %zu vertices, %zu triangles, offsets %s\n", model.frameCount(),
                  model.loop() ? " (loop)" : "", model.vertexCount(), model.base().triangleCount(),
                  offsetSpaceName(model.offsetSpace()));
      std::printf("sharpness  %g\n", model.sharpness());
      std::printf("key views  %zu\n", model.viewCount());
      for (std::size_t v = 0; v < model.viewCount(); ++v) {
        const auto& d = model.viewDirection(v);
        std::printf("  view (%7.4f, %7.4f, %7.4f)  key frames:", d.x(), d.y(), d.z());
        for (std::size_t j = 0; j < model.keyFrames(v).size(); ++j)
          std::printf(" %d (%s)", model.keyFrames(v)[j], model.keyName(v, j).c_str());
        std::printf("\n");
      }
      return;
    }
    const ViewDependentModel model = ViewDependentModel::build(raw);
    const ViewSphere& sphere = model.sphere();
    const std::size_t dummies = sphere.points().size() - sphere.keyCount();
    const auto warnings = modelWarnings(model);
    if (opt->json) {
      nlohmann::ordered_json out;
      out["model"] = opt->model;
      out["base"] = raw.base_path;
      out["vertices"] = model.vertexCount();
      out["triangles"] = model.base().triangleCount();
      out["center"] = {model.center().x(), model.center().y(), model.center().z()};
      out["sharpness"] = model.sharpness();
      out["uncovered"] = uncoveredName(sphere.settings().uncovered);
      out["keys"] = nlohmann::ordered_json::array();
      for (std::size_t k = 0; k < model.keyCount(); ++k) {
        const auto& v = model.keyView(k);
        out["keys"].push_back({{"name", model.keyName(k)},
                               {"mesh", raw.keys[k].mesh_path},
                               {"view", {v.x(), v.y(), v.z()}},
                               {"moved_vertices", model.keyMovedCount(k)}});
      }
      out["dummy_base_keys"] = dummies;
      out["hull_triangles"] = sphere.triangles().size();
      out["covered_fraction"] = sphere.coveredFraction();
      out["warnings"] = warnings;
      std::cout << out.dump(2) << "\n";
      return;
    }
    std::printf("model      %s\n", opt->model.c_str());
    std::printf("base       %s: %zu vertices, %zu triangles\n", raw.base_path.c_str(), model.vertexCount(),
                model.base().triangleCount());
    std::printf("centre     (%.4g, %.4g, %.4g)\n", model.center().x(), model.center().y(), model.center().z());
    std::printf("sharpness  %g\n", model.sharpness());
    std::printf("uncovered  %s\n", uncoveredName(sphere.settings().uncovered));
    std::printf("keys       %zu\n", model.keyCount());
    for (std::size_t k = 0; k < model.keyCount(); ++k) {
      const auto& v = model.keyView(k);
      std::printf("  %-16s view (%7.4f, %7.4f, %7.4f)  moves %zu vertices  (%s)\n", model.keyName(k).c_str(), v.x(),
                  v.y(), v.z(), model.keyMovedCount(k), raw.keys[k].mesh_path.c_str());
    }
    std::printf("hull       %zu triangles, %zu dummy base keys\n", sphere.triangles().size(), dummies);
    std::printf("coverage   %.1f%% of the viewing sphere lies in triangles of real keys\n",
                100.0 * sphere.coveredFraction());
    for (const auto& w : warnings) std::printf("warning: %s\n", w.c_str());
  });
}

}  // namespace vdg::cli
