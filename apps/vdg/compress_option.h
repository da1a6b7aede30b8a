// --compress none|quantize|meshopt of `vdg export` and `vdg bake` (vdg/io/gltf_compress.h,
// docs/gltf-export.md): one place for its parsing and help text.
#pragma once

#include <string>

#include "cli.h"
#include "vdg/io/gltf_compress.h"

namespace vdg::cli {

struct CompressOption {
  std::string name = "none";

  void add(CLI::App& sub) {
    sub.add_option("--compress", name,
                   "Smaller output: none (default), quantize (KHR_mesh_quantization) or meshopt "
                   "(EXT_meshopt_compression, quantised first); docs/gltf-export.md")
        ->check(CLI::IsMember({"none", "quantize", "meshopt"}));
  }
  GltfCompression value() const { return gltfCompressionFromName(name).value_or(GltfCompression::kNone); }
};

}  // namespace vdg::cli
