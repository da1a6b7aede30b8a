// vdg eval MODEL (--view X,Y,Z | --eye X,Y,Z) [--sharpness A] [--frame F] -o OUT.obj
//
// --frame F picks the frame of an animated model (manifest "base_animation", frames 0..N-1); it is
// required for an animated model and refused (usage error) for a static one.
#include <cstdio>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "cli.h"
#include "vdg/geom/error.h"
#include "vdg/io/model.h"
#include "vdg/io/obj.h"
#include "vdg/viewdep/animated_model.h"
#include "view_options.h"

namespace vdg::cli {
namespace {

std::string viewText(const Eigen::Vector3d& view) {
  return std::to_string(view.x()) + " " + std::to_string(view.y()) + " " + std::to_string(view.z());
}

// Blends a static model at `view` into `out` (the base's size) and returns its weights as text
// (" NAME=W ... base=W"): every key the view weighs, all of them for the rbf scheme.
// Blends a positions model at `eye` (key_space.h) into `out` and returns its weights as text.
std::string evalEyeWeights(const ViewDependentModel& model, const Eigen::Vector3d& eye, double sharpness,
                           TriMesh& out) {
  std::vector<float> dense(model.keyCount() + 1);
  if (!model.denseWeightsAtEye(eye, sharpness, dense) || !model.blendDense(dense, out.positions))
    throw Error("eval: the model refused eye " + viewText(eye) +
                " (the model centre lies outside the key eyes' hull and has no direction)");
  std::string text;
  for (std::size_t k = 0; k < model.keyCount(); ++k)
    if (dense[k] != 0.0f) text += " " + model.keyName(k) + "=" + std::to_string(dense[k]);
  return text + " base=" + std::to_string(dense.back());
}

std::string evalStaticWeights(const ViewDependentModel& model, const Eigen::Vector3d& view, double sharpness,
                              TriMesh& out) {
  const auto refused = [&] {
    throw Error("eval: the model refused view " + std::to_string(view.x()) + "," + std::to_string(view.y()) + "," +
                std::to_string(view.z()) + " (internal error)");
  };
  std::vector<float> dense(model.keyCount() + 1);
  // resolve() gave a unit view, the sharpness is checked positive and `out` has the base's size.
  if (model.sphere().settings().scheme == WeightScheme::Rbf) {
    if (!model.denseWeights(view, sharpness, dense) || !model.blendDense(dense, out.positions)) refused();
  } else {
    ViewWeights w;
    if (!model.weights(view, sharpness, w) || !model.blend(w, out.positions)) refused();
    for (int k = 0; k < 3; ++k)
      if (w.key[k] >= 0) dense[static_cast<std::size_t>(w.key[k])] += w.weight[k];
    dense.back() = w.base;
  }
  std::string text;
  for (std::size_t k = 0; k < model.keyCount(); ++k)
    if (dense[k] != 0.0f) text += " " + model.keyName(k) + "=" + std::to_string(dense[k]);
  return text + " base=" + std::to_string(dense.back());
}

// A model with parts: evaluates with one driving view per part into `out` and returns, per part,
// "\npart NAME view X Y Z weights: NAME=W ... base=W".
std::string evalPartWeights(const ViewDependentModel& model, const std::vector<Eigen::Vector3d>& views,
                            double sharpness, TriMesh& out) {
  if (!model.evaluateParts(views, sharpness, out.positions))
    throw Error("eval: the model refused its part views (internal error)");
  std::string text;
  for (std::size_t p = 0; p < model.partCount(); ++p) {
    const std::span<const std::size_t> keys = model.partKeys(p);
    std::vector<float> w(keys.size() + 1);
    if (!model.partWeights(p, views[p], sharpness, w))
      throw Error("eval: the model refused a part view (internal error)");
    text += "\npart " + model.partName(p) + " view " + viewText(views[p]) + " weights:";
    for (std::size_t i = 0; i < keys.size(); ++i)
      if (w[i] != 0.0f) text += " " + model.keyName(keys[i]) + "=" + std::to_string(w[i]);
    text += " base=" + std::to_string(w.back());
  }
  return text;
}

}  // namespace

void addEvalCommand(CLI::App& app) {
  struct Options {
    std::string model;
    ViewOptions view;
    std::string output;
    int frame = -1;
    bool quiet = false;
  };
  auto opt = std::make_shared<Options>();
  CLI::App* sub =
      app.add_subcommand("eval", "Write the blended mesh for one view (same vertices and faces as the base)");
  sub->add_option("MODEL", opt->model, "Model manifest (*.vdg.json), or a glTF model vdg exported")->required();
  opt->view.add(*sub);
  sub->add_option("--frame", opt->frame, "Frame of an animated model (0 .. its frame count - 1)")
      ->check(wholeNumber(0, static_cast<long>(kMaxBaseFrames) - 1));
  sub->add_option("-o,--output", opt->output, "Output mesh (.obj)")->required();
  sub->add_flag("-q,--quiet", opt->quiet, "Print nothing on success");
  sub->callback([opt] {
    if (!hasExtension(opt->output, ".obj"))
      throw UsageError("-o: expected an .obj file name, got " + quotedText(opt->output));
    const OpenedInput input = openModel(opt->model);
    TriMesh out;
    std::string header = "vdg eval " + opt->model;
    ViewWeights w;
    if (input.animated) {
      const AnimatedViewDependentModel& model = *input.animated;
      const int n = model.frameCount();
      if (opt->frame < 0)
        throw UsageError("--frame: " + quotedText(opt->model) + " is animated (" + std::to_string(n) +
                         " frames); give --frame F with F in 0.." + std::to_string(n - 1));
      if (opt->frame >= n)
        throw UsageError("--frame: expected a frame in 0.." + std::to_string(n - 1) + " (the model has " +
                         std::to_string(n) + " frames), got " + std::to_string(opt->frame));
      const Eigen::Vector3d view = opt->view.resolve(model.center());
      out = model.base();
      // resolve() gives a unit view, the sharpness is checked positive, the frame is in range and
      // `out` has the base's size.
      if (!model.weights(view, opt->view.sharpness, w) ||
          !model.evaluate(opt->frame, view, opt->view.sharpness, out.positions))
        throw Error("eval: the model refused view " + viewText(view) + " at frame " + std::to_string(opt->frame) +
                    " (internal error)");
      header += "\nframe " + std::to_string(opt->frame) + "\nview " + viewText(view) + "\nweights:";
      for (int k = 0; k < 3; ++k)
        if (w.key[k] >= 0)
          header +=
              " view of " + model.keyName(static_cast<std::size_t>(w.key[k]), 0) + "=" + std::to_string(w.weight[k]);
    } else {
      if (opt->frame >= 0)
        throw UsageError("--frame: " + quotedText(opt->model) +
                         " is not animated (no 'base_animation'); --frame applies to animated models only");
      const ViewDependentModel& model = *input.model;
      out = model.base();
      if (model.weightSpace() == WeightSpace::Positions) {
        const Eigen::Vector3d eye = opt->view.resolveEye();
        header += "\neye " + viewText(eye) + "\nweights:" + evalEyeWeights(model, eye, opt->view.sharpness, out);
        writeObj(opt->output, out, header);
        if (!opt->quiet)
          std::printf("wrote %s (%zu vertices, %zu triangles)\n", opt->output.c_str(), out.vertexCount(),
                      out.triangleCount());
        return;
      }
      const Eigen::Vector3d view = opt->view.resolve(model);
      if (model.hasParts() || !opt->view.part_views.empty())
        header += "\nview " + viewText(view) +
                  evalPartWeights(model, opt->view.resolveParts(model, view), opt->view.sharpness, out);
      else
        header += "\nview " + viewText(view) + "\nweights:" + evalStaticWeights(model, view, opt->view.sharpness, out);
    }
    if (input.animated) header += " base=" + std::to_string(w.base);
    writeObj(opt->output, out, header);
    if (!opt->quiet)
      std::printf("wrote %s (%zu vertices, %zu triangles)\n", opt->output.c_str(), out.vertexCount(),
                  out.triangleCount());
  });
}

}  // namespace vdg::cli
