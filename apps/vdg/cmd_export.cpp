// vdg export MODEL -o OUT.glb|OUT.gltf
//
// Writes a view-dependent model as glTF 2.0 (docs/gltf-export.md): the base mesh with one morph
// target per key, and the view-dependent description in mesh.extras.vdg, so that vdg reads the
// file back as the same model and other tools see the keys as named morph targets. An animated
// model gets one target per (key view, key frame) and its base animation: the skin for
// "skinned" offsets, the sampled base frames as morph targets otherwise (docs/gltf-export.md).
// --interactivity adds the weights as a KHR_interactivity graph (docs/interactivity.md).
#include <cstdio>
#include <filesystem>
#include <limits>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

#include "cli.h"
#include "compress_option.h"
#include "vdg/geom/error.h"
#include "vdg/io/atomic_file.h"
#include "vdg/io/gltf_export.h"
#include "vdg/io/gltf_interactivity.h"
#include "vdg/io/model.h"

namespace vdg::cli {

// Shared with cmd_bake.cpp: checks the output name, writes, and tells the user what was written.
void writeGltfForCli(const std::string& output, const GltfExportInput& input, bool quiet) {
  const GltfExportReport report = writeGltfExport(output, input);
  if (!report.note.empty()) std::fprintf(stderr, "vdg: note: %s\n", report.note.c_str());
  const std::size_t targets = gltfTargetCount(input);
  if (const std::string over = morphTargetCapsExceeded(targets); !over.empty())
    std::fprintf(stderr, "vdg: note: %zu morph targets, more than %s take (docs/gltf-export.md, \"Target count\")\n",
                 targets, over.c_str());
  if (quiet) return;
  std::printf("wrote %s (%zu vertices, %zu triangles, %zu morph target%s, %zu sparse; %zu bytes)\n", output.c_str(),
              input.base.vertexCount(), input.base.triangleCount(), targets, targets == 1 ? "" : "s",
              report.sparse_targets, report.bytes);
  for (const std::string& file : report.files) std::printf("wrote %s\n", file.c_str());
}

// Shared with cmd_bake.cpp: --max-targets (docs/gltf-export.md, "Target count").
void addMaxTargetsOption(CLI::App& sub, std::size_t& max_targets) {
  sub.add_option("--max-targets", max_targets,
                 "Refuse an export that needs more than N morph targets (engines cap them: Bevy 64, three.js and "
                 "Filament about 256)");
}

GltfExportInput exportInputForCli(const OpenedInput& input) {
  if (input.model) return gltfExportInput(*input.model);
  const RawViewDependentModel& raw = input.raw;
  std::optional<RawRig> rig;
  if (!raw.base_animation->gltf.empty()) rig = readBaseRig(raw);
  return gltfExportInput(*input.animated, raw, rig ? &*rig : nullptr);
}

// Shared with cmd_bake.cpp: refuses an output that is one of the model's own files under any name
// (the same device and inode: the model itself, a hard or symbolic link to its base or a key mesh),
// as OUT.gltf or as the OUT.bin written beside it.
void checkOutputIsNotInput(const std::string& output, const std::string& model, const OpenedInput& input) {
  namespace fs = std::filesystem;
  const fs::path folder = fs::path(model).parent_path();
  std::vector<std::pair<std::string, std::string>> inputs = {{model, "the model " + model}};
  auto add = [&](const std::string& path, const std::string& what) {
    if (!path.empty()) inputs.emplace_back((folder / path).string(), what + " " + (folder / path).string());
  };
  add(input.raw.base_path, "its base mesh");
  for (const RawKey& key : input.raw.keys) add(key.mesh_path, "the mesh of its key '" + key.name + "'");
  if (input.raw.base_animation) add(input.raw.base_animation->gltf, "its base animation");
  std::vector<std::pair<std::string, std::string>> outputs = {{output, "-o " + output}};
  if (hasExtension(output, ".gltf")) {
    const fs::path bin = fs::path(output).parent_path() / (fs::path(output).stem().string() + ".bin");
    outputs.emplace_back(bin.string(), "-o " + output + ": its buffer " + bin.string());
  }
  for (const auto& [out, out_what] : outputs)
    for (const auto& [in, in_what] : inputs)
      if (isSameFile(out, in))
        throw Error(out_what + " is the same file as " + in_what + "; vdg does not write over its input");
}

void checkGltfOutput(const std::string& output) {
  if (!hasGltfExtension(output)) throw UsageError("-o: expected a .glb or .gltf file name, got " + quotedText(output));
}

void addExportCommand(CLI::App& app) {
  struct Options {
    std::string model, output;
    bool quiet = false;
    bool interactivity = false;
    std::size_t max_targets = std::numeric_limits<std::size_t>::max();
    CompressOption compress;
  };
  auto opt = std::make_shared<Options>();
  CLI::App* sub = app.add_subcommand(
      "export", "Write the model as glTF 2.0: the base mesh with one morph target per key (docs/gltf-export.md)");
  sub->add_option("MODEL", opt->model, "Model manifest (*.vdg.json), or a glTF model vdg exported")->required();
  sub->add_option("-o,--output", opt->output, "Output OUT.glb, or OUT.gltf with its buffer in OUT.bin beside it")
      ->required();
  opt->compress.add(*sub);
  sub->add_flag("--interactivity", opt->interactivity,
                "Add the weights as a KHR_interactivity graph, so that an engine implementing it (Babylon.js 9) "
                "follows the camera with no vdg code; static models only (docs/interactivity.md)");
  sub->add_flag("-q,--quiet", opt->quiet, "Print nothing on success");
  addMaxTargetsOption(*sub, opt->max_targets);
  sub->callback([opt] {
    checkGltfOutput(opt->output);
    const OpenedInput input = openModel(opt->model);
    if (opt->interactivity && input.animated)
      throw Error(opt->model + ": --interactivity: " + kInteractivityAnimatedRefusal);
    if (opt->interactivity && input.raw.sphere.scheme != WeightScheme::Linear)
      throw Error(opt->model + ": --interactivity: " + kInteractivitySchemeRefusal);
    checkOutputIsNotInput(opt->output, opt->model, input);
    GltfExportInput export_input = exportInputForCli(input);
    export_input.compression = opt->compress.value();
    export_input.interactivity = opt->interactivity;
    checkMaxTargets(export_input, opt->max_targets, opt->model);
    writeGltfForCli(opt->output, export_input, opt->quiet);
  });
}

}  // namespace vdg::cli
