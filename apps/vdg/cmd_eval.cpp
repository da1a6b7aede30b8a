// vdg eval MODEL (--view X,Y,Z | --eye X,Y,Z) [--sharpness A] -o OUT.obj
#include <cstdio>
#include <memory>

#include "cli.h"
#include "vdg/geom/error.h"
#include "vdg/io/manifest.h"
#include "vdg/io/obj.h"
#include "view_options.h"

namespace vdg::cli {

void addEvalCommand(CLI::App& app) {
  struct Options {
    std::string model;
    ViewOptions view;
    std::string output;
    bool quiet = false;
  };
  auto opt = std::make_shared<Options>();
  CLI::App* sub =
      app.add_subcommand("eval", "Write the blended mesh for one view (same vertices and faces as the base)");
  sub->add_option("MODEL", opt->model, "Model manifest (*.vdg.json)")->required();
  opt->view.add(*sub);
  sub->add_option("-o,--output", opt->output, "Output mesh (.obj)")->required();
  sub->add_flag("-q,--quiet", opt->quiet, "Print nothing on success");
  sub->callback([opt] {
    if (!hasExtension(opt->output, ".obj"))
      throw UsageError("-o: expected an .obj file name, got " + shown(opt->output));
    const ViewDependentModel model = ViewDependentModel::build(loadManifest(opt->model));
    const Eigen::Vector3d view = opt->view.resolve(model);
    ViewWeights w;
    TriMesh out = model.base();
    // resolve() gives a unit view, the sharpness is checked positive and `out` has the base's size.
    if (!model.weights(view, opt->view.sharpness, w) || !model.blend(w, out.positions))
      throw Error("eval: the model refused view " + std::to_string(view.x()) + "," + std::to_string(view.y()) + "," +
                  std::to_string(view.z()) + " (internal error)");
    std::string header = "vdg eval " + opt->model + "\nview " + std::to_string(view.x()) + " " +
                         std::to_string(view.y()) + " " + std::to_string(view.z()) + "\nweights:";
    for (int k = 0; k < 3; ++k)
      if (w.key[k] >= 0)
        header += " " + model.keyName(static_cast<std::size_t>(w.key[k])) + "=" + std::to_string(w.weight[k]);
    header += " base=" + std::to_string(w.base);
    writeObj(opt->output, out, header);
    if (!opt->quiet)
      std::printf("wrote %s (%zu vertices, %zu triangles)\n", opt->output.c_str(), out.vertexCount(),
                  out.triangleCount());
  });
}

}  // namespace vdg::cli
