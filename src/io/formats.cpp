#include "vdg/io/formats.h"

#include "vdg/io/anim_json.h"
#include "vdg/io/blob_files.h"
#include "vdg/io/camera_json.h"
#include "vdg/io/gltf_export.h"
#include "vdg/io/manifest.h"
#include "vdg/io/morph_files.h"
#include "vdg/io/studio_events.h"
#include "vdg/io/studio_recovery.h"

namespace vdg {
namespace {

constexpr FileFormat kFormats[] = {
    {"manifest", "docs/model-format.md", kManifestVersion},
    {"glTF extras", "docs/gltf-export.md", kGltfExtrasVersion},
    {"animation spec", "docs/anim.md", anim::kAnimSpecVersion},
    {"camera file", "docs/render.md", kCameraFileVersion},
    {"morph grid", "docs/morph-files.md", kMorphGridVersion},
    {"morph lines", "docs/morph-files.md", kMorphLinesVersion},
    {"key drawings", "docs/morph-files.md", kKeyDrawingsVersion},
    {"blob file", "docs/implicit.md", kBlobFileVersion},
    {"input script", "docs/studio-files.md", kInputScriptVersion},
    {"studio recovery", "docs/studio-files.md", kStudioRecoveryVersion},
};

}  // namespace

std::span<const FileFormat> fileFormats() { return kFormats; }

}  // namespace vdg
