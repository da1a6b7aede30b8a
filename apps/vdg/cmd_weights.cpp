// vdg weights MODEL (--view X,Y,Z | --eye X,Y,Z) [--sharpness A] [--json]
//
// An animated model (manifest "base_animation") is weighed per key VIEW: its keys that share a view
// are one point of the viewing sphere (Rademacher 99, section 4.1), and the weights do not depend on
// the frame (the frame only decides how that view's key offsets mix in time). JSON:
// {"views": [{"view": [x, y, z], "keys": [names], "frames": [key frames], "weight": w}, ...],
//  "base": w}, listing the views with a weight above 0.
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "cli.h"
#include "vdg/geom/error.h"
#include "vdg/io/model.h"
#include "vdg/viewdep/animated_model.h"
#include "view_options.h"

namespace vdg::cli {
namespace {
// Weights are floats; print the digits a float holds, not the noise of its double widening.
double floatDigits(float w) {
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "%.7g", static_cast<double>(w));
  return std::strtod(buffer, nullptr);
}

[[noreturn]] void refused(const Eigen::Vector3d& view) {
  throw Error("weights: the model refused view " + std::to_string(view.x()) + "," + std::to_string(view.y()) + "," +
              std::to_string(view.z()) + " (internal error)");
}

void animatedWeights(const AnimatedViewDependentModel& model, const ViewOptions& options, bool json) {
  const Eigen::Vector3d view = options.resolve(model.center());
  ViewWeights w;
  if (!model.weights(view, options.sharpness, w)) refused(view);  // a unit view; sharpness > 0
  if (json) {
    nlohmann::ordered_json out;
    out["views"] = nlohmann::ordered_json::array();
    for (int k = 0; k < 3; ++k) {
      if (w.key[k] < 0 || w.weight[k] <= 0.0f) continue;
      const auto i = static_cast<std::size_t>(w.key[k]);
      const Eigen::Vector3d& d = model.viewDirection(i);
      nlohmann::ordered_json names = nlohmann::ordered_json::array();
      for (std::size_t j = 0; j < model.keyFrames(i).size(); ++j) names.push_back(model.keyName(i, j));
      out["views"].push_back({{"view", {d.x(), d.y(), d.z()}},
                              {"keys", names},
                              {"frames", std::vector<int>(model.keyFrames(i).begin(), model.keyFrames(i).end())},
                              {"weight", floatDigits(w.weight[k])}});
    }
    out["base"] = floatDigits(w.base);
    std::cout << out.dump() << "\n";
    return;
  }
  std::printf("view (%.6f, %.6f, %.6f)  (the weights of key views; they do not depend on the frame)\n", view.x(),
              view.y(), view.z());
  for (int k = 0; k < 3; ++k) {
    if (w.key[k] < 0 || w.weight[k] <= 0.0f) continue;
    const auto i = static_cast<std::size_t>(w.key[k]);
    const Eigen::Vector3d& d = model.viewDirection(i);
    std::string keys;
    for (std::size_t j = 0; j < model.keyFrames(i).size(); ++j)
      keys += (j ? ", " : "") + model.keyName(i, j) + " (frame " + std::to_string(model.keyFrames(i)[j]) + ")";
    std::printf("  view (%7.4f, %7.4f, %7.4f)  %.6f  keys %s\n", d.x(), d.y(), d.z(), w.weight[k], keys.c_str());
  }
  std::printf("  %-20s %.6f\n", "(base)", w.base);
}
}  // namespace

void addWeightsCommand(CLI::App& app) {
  struct Options {
    std::string model;
    ViewOptions view;
    bool json = false;
  };
  auto opt = std::make_shared<Options>();
  CLI::App* sub = app.add_subcommand(
      "weights", "Blending weights of the keys (and the base) at one view; of the key views for an animated model");
  sub->add_option("MODEL", opt->model, "Model manifest (*.vdg.json), or a glTF model vdg exported")->required();
  opt->view.add(*sub);
  sub->add_flag("--json", opt->json, "Print one JSON object {\"keys\": {name: w, ...}, \"base\": w}");
  sub->callback([opt] {
    const OpenedInput input = openModel(opt->model);
    if (input.animated) {
      animatedWeights(*input.animated, opt->view, opt->json);
      return;
    }
    const ViewDependentModel& model = *input.model;
    const Eigen::Vector3d view = opt->view.resolve(model);
    ViewWeights w;
    if (!model.weights(view, opt->view.sharpness, w)) refused(view);  // a unit view; sharpness > 0
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
