// vdg weights MODEL (--view X,Y,Z | --eye X,Y,Z | --views FILE | --continuity) [--sharpness A]
//                   [--scheme linear|smooth|rbf [--kernel NAME] [--width DEG]] [--json]
//
// Batch mode (--views FILE): FILE is a JSON array whose items are directions [x, y, z] (towards
// the eye, from the model centre), or objects {"view": [x, y, z]} or {"eye": [x, y, z]} (an eye
// position in model space); the output is one JSON array with the --json object of each item, in
// order. One process for thousands of views (the runtime's parity tests use it).
//
// Continuity (--continuity [--step DEG] [--scheme linear|smooth|rbf]): the popping and velocity-jump
// figures of vdg/viewdep/continuity.h along great circles of views (static models; docs/weights.md).
// --scheme overrides the model's weight scheme for this command (to compare them); --kernel and
// --width set the rbf scheme's kernel and width (degrees) and need it (the model's or --scheme's).
// A static model's weights list every key with a weight above 0, in key order (the rbf scheme
// weighs every key, the others at most three).
//
// An animated model (manifest "base_animation") is weighed per key VIEW: its keys that share a view
// are one point of the viewing sphere (Rademacher 99, section 4.1), and the weights do not depend on
// the frame (the frame only decides how that view's key offsets mix in time). JSON:
// {"views": [{"view": [x, y, z], "keys": [names], "frames": [key frames], "weight": w}, ...],
//  "base": w}, listing the views with a weight above 0.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "cli.h"
#include "vdg/geom/error.h"
#include "vdg/io/camera_json.h"
#include "vdg/io/model.h"
#include "vdg/io/read_file.h"
#include "vdg/viewdep/animated_model.h"
#include "vdg/viewdep/continuity.h"
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

[[noreturn]] void refusedEye(const Eigen::Vector3d& eye) {
  throw Error("weights: the model refused eye " + std::to_string(eye.x()) + "," + std::to_string(eye.y()) + "," +
              std::to_string(eye.z()) + " (the model centre, outside the key eyes' hull, has no view direction)");
}

nlohmann::ordered_json animatedJson(const AnimatedViewDependentModel& model, const ViewWeights& w) {
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
  return out;
}

// `dense`: ViewDependentModel::denseWeights' keyCount() + 1 weights (the base last).
nlohmann::ordered_json staticJson(const ViewDependentModel& model, std::span<const float> dense) {
  nlohmann::ordered_json out;
  out["keys"] = nlohmann::ordered_json::object();
  for (std::size_t k = 0; k < model.keyCount(); ++k)
    if (dense[k] > 0.0f) out["keys"][model.keyName(k)] = floatDigits(dense[k]);
  out["base"] = floatDigits(dense.back());
  return out;
}

void printStaticWeights(const ViewDependentModel& model, std::span<const float> dense, bool json) {
  if (json) {
    std::cout << staticJson(model, dense).dump() << "\n";
    return;
  }
  for (std::size_t k = 0; k < model.keyCount(); ++k)
    if (dense[k] > 0.0f) std::printf("  %-20s %.6f\n", model.keyName(k).c_str(), dense[k]);
  std::printf("  %-20s %.6f\n", "(base)", dense.back());
}

void animatedWeights(const AnimatedViewDependentModel& model, const ViewOptions& options, bool json) {
  const Eigen::Vector3d view = options.resolve(model.center());
  ViewWeights w;
  if (!model.weights(view, options.sharpness, w)) refused(view);  // a unit view; sharpness > 0
  if (json) {
    std::cout << animatedJson(model, w).dump() << "\n";
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

// A model with parts: each part's driving view and the weights of its keys and the base.
// JSON: {"parts": [{"name": N, "view": [x, y, z], "keys": {name: w, ...}, "base": w}, ...]}.
void partWeights(const ViewDependentModel& model, const std::vector<Eigen::Vector3d>& views, double sharpness,
                 bool json) {
  nlohmann::ordered_json out{{"parts", nlohmann::ordered_json::array()}};
  for (std::size_t p = 0; p < model.partCount(); ++p) {
    const std::span<const std::size_t> keys = model.partKeys(p);
    std::vector<float> w(keys.size() + 1);
    if (!model.partWeights(p, views[p], sharpness, w)) refused(views[p]);  // a unit view; sharpness > 0
    nlohmann::ordered_json part{{"name", model.partName(p)},
                                {"view", {views[p].x(), views[p].y(), views[p].z()}},
                                {"keys", nlohmann::ordered_json::object()}};
    for (std::size_t i = 0; i < keys.size(); ++i)
      if (w[i] > 0.0f) part["keys"][model.keyName(keys[i])] = floatDigits(w[i]);
    part["base"] = floatDigits(w.back());
    if (!json) {
      std::printf("part %s (%zu vertices), view (%.6f, %.6f, %.6f)\n", model.partName(p).c_str(),
                  model.partVertexCount(p), views[p].x(), views[p].y(), views[p].z());
      for (std::size_t i = 0; i < keys.size(); ++i)
        if (w[i] > 0.0f) std::printf("  %-20s %.6f\n", model.keyName(keys[i]).c_str(), w[i]);
      std::printf("  %-20s %.6f\n", "(base)", w.back());
    }
    out["parts"].push_back(std::move(part));
  }
  if (json) std::cout << out.dump() << "\n";
}

// A positions model (key_space.h): the --views file holds eyes.
void batchEyeWeights(const ViewDependentModel& model, const std::string& path, double sharpness) {
  nlohmann::ordered_json out = nlohmann::ordered_json::array();
  int hint = -1;
  std::vector<float> dense(model.keyCount() + 1);
  for (const Eigen::Vector3d& eye :
       parseEyeList(readFileLimited(path, "views file", kMaxJsonFileBytes), path + ": --views")) {
    if (!model.denseWeightsAtEye(eye, sharpness, dense, &hint)) refusedEye(eye);
    out.push_back(staticJson(model, dense));
  }
  std::cout << out.dump() << "\n";
}

void batchWeights(const OpenedInput& input, const std::string& path, double sharpness) {
  if (input.model && input.model->weightSpace() == WeightSpace::Positions)
    return batchEyeWeights(*input.model, path, sharpness);
  if (input.model) input.model->requireNoParts("vdg weights --views (give one --view per call)");
  const Eigen::Vector3d center = input.animated ? input.animated->center() : input.model->center();
  nlohmann::ordered_json out = nlohmann::ordered_json::array();
  int hint = -1;
  const std::vector<Eigen::Vector3d> views =
      parseViewList(readFileLimited(path, "views file", kMaxJsonFileBytes), path + ": --views", center);
  std::vector<float> dense(input.model ? input.model->keyCount() + 1 : 0);
  for (const Eigen::Vector3d& view : views) {
    ViewWeights w;
    if (input.animated) {
      if (!input.animated->weights(view, sharpness, w, &hint)) refused(view);
      out.push_back(animatedJson(*input.animated, w));
    } else {
      if (!input.model->denseWeights(view, sharpness, dense, &hint)) refused(view);
      out.push_back(staticJson(*input.model, dense));
    }
  }
  std::cout << out.dump() << "\n";
}
// --scheme, --kernel and --width over the model's own settings; the rbf settings need the rbf
// scheme (the model's or --scheme's), else a usage error.
void overrideWeightScheme(ViewSphereSettings& sphere, const std::string& scheme, const std::string& kernel,
                          double width_deg) {
  if (!scheme.empty())
    sphere.scheme = scheme == "rbf"      ? WeightScheme::Rbf
                    : scheme == "smooth" ? WeightScheme::Smooth
                                         : WeightScheme::Linear;
  if ((!kernel.empty() || width_deg > 0.0) && sphere.scheme != WeightScheme::Rbf)
    throw UsageError("--kernel, --width: settings of the rbf scheme; this model's weights are '" +
                     std::string(weightSchemeName(sphere.scheme)) + "' (add --scheme rbf)");
  if (!kernel.empty())
    sphere.rbf_kernel = kernel == "wendland"               ? RbfKernel::Wendland
                        : kernel == "inverse-multiquadric" ? RbfKernel::InverseMultiquadric
                                                           : RbfKernel::Gaussian;
  if (width_deg > 0.0) sphere.rbf_width_deg = width_deg;
}

void continuityReport(const OpenedInput& input, const std::string& path, const ContinuitySettings& settings,
                      bool json) {
  if (input.animated)
    throw UsageError("--continuity: " + quotedText(path) + " is animated; --continuity measures static models");
  const ContinuityReport r = measureContinuity(*input.model, settings);
  const ViewSphereSettings& sphere = input.model->sphere().settings();
  const bool rbf = sphere.scheme == WeightScheme::Rbf;
  if (json) {
    nlohmann::ordered_json doc{{"scheme", weightSchemeName(sphere.scheme)}};
    if (rbf) {
      doc["kernel"] = rbfKernelName(sphere.rbf_kernel);
      doc["width"] = sphere.rbf_width_deg;
    }
    doc.update(nlohmann::ordered_json{{"step_deg", settings.step_deg},
                                      {"paths", r.paths},
                                      {"samples", r.samples},
                                      {"size", r.size},
                                      {"popping", r.popping},
                                      {"velocity_jump", r.velocity_jump},
                                      {"weight_speed", r.weight_speed},
                                      {"weight_jump", r.weight_jump}});
    std::cout << doc.dump() << "\n";
    return;
  }
  char buffer[96];
  std::snprintf(buffer, sizeof(buffer), " (%s, width %g degrees)", rbfKernelName(sphere.rbf_kernel),
                sphere.rbf_width_deg);
  const std::string scheme = weightSchemeName(sphere.scheme) + std::string(rbf ? buffer : "");
  std::printf("weights        %s, %zu great circles of views, a sample every %g degrees\n", scheme.c_str(), r.paths,
              settings.step_deg);
  std::printf("popping        %.5f of the model's size per degree (the fastest vertex)\n", r.popping);
  std::printf("velocity jump  %.6f per degree (the largest change of a vertex's speed between samples)\n",
              r.velocity_jump);
  std::printf("weights speed  %.5f per degree, jump %.6f per degree\n", r.weight_speed, r.weight_jump);
}
}  // namespace

void addWeightsCommand(CLI::App& app) {
  struct Options {
    std::string model;
    ViewOptions view;
    bool json = false;
    std::string views;
    std::string scheme, kernel;
    double width_deg = 0.0;
    bool continuity = false;
    ContinuitySettings continuity_settings;
  };
  auto opt = std::make_shared<Options>();
  CLI::App* sub = app.add_subcommand(
      "weights", "Blending weights of the keys (and the base) at one view; of the key views for an animated model");
  sub->add_option("MODEL", opt->model, "Model manifest (*.vdg.json), or a glTF model vdg exported")->required();
  opt->view.add(*sub);
  sub->add_flag("--json", opt->json, "Print one JSON object {\"keys\": {name: w, ...}, \"base\": w}");
  sub->add_option("--views", opt->views,
                  "Batch: a JSON file with an array of directions [x,y,z] (or {\"view\": [x,y,z]}, {\"eye\": "
                  "[x,y,z]}); prints a JSON array with the --json object of each, in order")
      ->excludes("--view")
      ->excludes("--eye");
  sub->add_option("--scheme", opt->scheme, "Weigh with this scheme instead of the model's (docs/weights.md)")
      ->check(CLI::IsMember({"linear", "smooth", "rbf"}));
  sub->add_option("--kernel", opt->kernel, "The rbf scheme's kernel (default: the model's, else gaussian)")
      ->check(CLI::IsMember({"gaussian", "inverse-multiquadric", "wendland"}));
  sub->add_option("--width", opt->width_deg, "The rbf scheme's kernel width in degrees, in (0, 180]")
      ->check(positiveNumber(180.0));
  auto* continuity = sub->add_flag("--continuity", opt->continuity,
                                   "Measure how smoothly the model changes along great circles of views: popping "
                                   "(the fastest vertex per degree) and velocity jumps (docs/weights.md)");
  continuity->excludes("--view")->excludes("--eye")->excludes("--views");
  sub->add_option("--step", opt->continuity_settings.step_deg, "--continuity: degrees between samples (default 0.1)")
      ->check(positiveNumber(10.0))
      ->needs(continuity);
  sub->callback([opt] {
    const bool rbf_settings = !opt->kernel.empty() || opt->width_deg > 0.0;
    const bool rebuild = !opt->scheme.empty() || rbf_settings;
    OpenedInput input = openModel(opt->model, {}, rebuild ? InputBuild::kRawOnly : InputBuild::kBuilt);
    if (rebuild) {
      overrideWeightScheme(input.raw.sphere, opt->scheme, opt->kernel, opt->width_deg);
      buildOpenedModel(input);
    }
    if (opt->continuity) {
      opt->continuity_settings.sharpness = opt->view.sharpness;
      continuityReport(input, opt->model, opt->continuity_settings, opt->json);
      return;
    }
    if (!opt->views.empty()) {
      batchWeights(input, opt->views, opt->view.sharpness);
      return;
    }
    if (input.animated) {
      animatedWeights(*input.animated, opt->view, opt->json);
      return;
    }
    const ViewDependentModel& model = *input.model;
    std::vector<float> dense(model.keyCount() + 1);
    if (model.weightSpace() == WeightSpace::Positions) {
      const Eigen::Vector3d eye = opt->view.resolveEye();
      if (!model.denseWeightsAtEye(eye, opt->view.sharpness, dense)) refusedEye(eye);
      if (!opt->json) std::printf("eye (%.6f, %.6f, %.6f)\n", eye.x(), eye.y(), eye.z());
      printStaticWeights(model, dense, opt->json);
      return;
    }
    const Eigen::Vector3d view = opt->view.resolve(model);
    if (model.hasParts() || !opt->view.part_views.empty()) {
      partWeights(model, opt->view.resolveParts(model, view), opt->view.sharpness, opt->json);
      return;
    }
    if (!model.denseWeights(view, opt->view.sharpness, dense)) refused(view);  // a unit view; sharpness > 0
    if (!opt->json) std::printf("view (%.6f, %.6f, %.6f)\n", view.x(), view.y(), view.z());
    printStaticWeights(model, dense, opt->json);
  });
}

}  // namespace vdg::cli
