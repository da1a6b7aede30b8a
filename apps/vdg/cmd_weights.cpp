// vdg weights MODEL (--view X,Y,Z | --eye X,Y,Z) [--sharpness A] [--json]
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "cli.h"
#include "vdg/geom/error.h"
#include "vdg/io/gltf_export.h"
#include "vdg/io/manifest.h"
#include "view_options.h"

namespace vdg::cli {
namespace {
// Weights are floats; print the digits a float holds, not the noise of its double widening.
double floatDigits(float w) {
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "%.7g", static_cast<double>(w));
  return std::strtod(buffer, nullptr);
}
}  // namespace

void addWeightsCommand(CLI::App& app) {
  struct Options {
    std::string model;
    ViewOptions view;
    bool json = false;
  };
  auto opt = std::make_shared<Options>();
  CLI::App* sub = app.add_subcommand("weights", "Blending weights of the keys (and the base) at one view");
  sub->add_option("MODEL", opt->model, "Model manifest (*.vdg.json), or a glTF model vdg exported")->required();
  opt->view.add(*sub);
  sub->add_flag("--json", opt->json, "Print one JSON object {\"keys\": {name: w, ...}, \"base\": w}");
  sub->callback([opt] {
    const ViewDependentModel model = ViewDependentModel::build(loadModel(opt->model));
    const Eigen::Vector3d view = opt->view.resolve(model);
    ViewWeights w;
    if (!model.weights(view, opt->view.sharpness, w))  // resolve() gives a unit view; sharpness > 0
      throw Error("weights: the model refused view " + std::to_string(view.x()) + "," + std::to_string(view.y()) + "," +
                  std::to_string(view.z()) + " (internal error)");
    if (opt->json) {
      nlohmann::ordered_json out;
      out["keys"] = nlohmann::ordered_json::object();
      for (int k = 0; k < 3; ++k)
        if (w.key[k] >= 0 && w.weight[k] > 0.0f)
          out["keys"][model.keyName(static_cast<std::size_t>(w.key[k]))] = floatDigits(w.weight[k]);
      out["base"] = floatDigits(w.base);
      std::cout << out.dump() << "\n";
      return;
    }
    std::printf("view (%.6f, %.6f, %.6f)\n", view.x(), view.y(), view.z());
    for (int k = 0; k < 3; ++k)
      if (w.key[k] >= 0 && w.weight[k] > 0.0f)
        std::printf("  %-20s %.6f\n", model.keyName(static_cast<std::size_t>(w.key[k])).c_str(), w.weight[k]);
    std::printf("  %-20s %.6f\n", "(base)", w.base);
  });
}

}  // namespace vdg::cli
