// vdg export MODEL -o OUT.glb|OUT.gltf
//
// Writes a view-dependent model as glTF 2.0 (docs/gltf-export.md): the base mesh with one morph
// target per key, and the view-dependent description in mesh.extras.vdg, so that vdg reads the
// file back as the same model and other tools see the keys as named morph targets. An animated
// model gets one target per (key view, key frame) and its base animation: the skin for
// "skinned" offsets, the sampled base frames as morph targets otherwise (docs/gltf-export.md).
#include <cstdio>
#include <memory>
#include <optional>

#include "cli.h"
#include "vdg/geom/error.h"
#include "vdg/io/gltf_export.h"
#include "vdg/io/model.h"

namespace vdg::cli {

// Shared with cmd_bake.cpp: checks the output name, writes, and tells the user what was written.
void writeGltfForCli(const std::string& output, const GltfExportInput& input, bool quiet) {
  const GltfExportReport report = writeGltfExport(output, input);
  if (!report.note.empty()) std::fprintf(stderr, "vdg: note: %s\n", report.note.c_str());
  if (!quiet)
    std::printf("wrote %s (%zu vertices, %zu triangles, %zu morph target%s, %zu sparse; %zu bytes)\n", output.c_str(),
                input.base.vertexCount(), input.base.triangleCount(), input.targets.size(),
                input.targets.size() == 1 ? "" : "s", report.sparse_targets, report.bytes);
}

GltfExportInput exportInputForCli(const OpenedInput& input) {
  if (input.model) return gltfExportInput(*input.model);
  const RawViewDependentModel& raw = input.raw;
  std::optional<RawRig> rig;
  if (!raw.base_animation->gltf.empty()) rig = readBaseRig(raw);
  return gltfExportInput(*input.animated, raw, rig ? &*rig : nullptr);
}

void checkGltfOutput(const std::string& output) {
  if (!hasGltfExtension(output)) throw UsageError("-o: expected a .glb or .gltf file name, got " + quotedText(output));
}

void addExportCommand(CLI::App& app) {
  struct Options {
    std::string model, output;
    bool quiet = false;
  };
  auto opt = std::make_shared<Options>();
  CLI::App* sub = app.add_subcommand(
      "export", "Write the model as glTF 2.0: the base mesh with one morph target per key (docs/gltf-export.md)");
  sub->add_option("MODEL", opt->model, "Model manifest (*.vdg.json), or a glTF model vdg exported")->required();
  sub->add_option("-o,--output", opt->output, "Output OUT.glb, or OUT.gltf with its buffer in OUT.bin beside it")
      ->required();
  sub->add_flag("-q,--quiet", opt->quiet, "Print nothing on success");
  sub->callback([opt] {
    checkGltfOutput(opt->output);
    writeGltfForCli(opt->output, exportInputForCli(openModel(opt->model)), opt->quiet);
  });
}

}  // namespace vdg::cli
