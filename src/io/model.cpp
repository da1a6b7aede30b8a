#include "vdg/io/model.h"

#include "vdg/geom/error.h"
#include "vdg/io/gltf_export.h"
#include "vdg/io/manifest.h"
#include "vdg/io/mesh.h"

namespace vdg {

RawViewDependentModel loadModel(const std::string& path, const MeshReadOptions& options) {
  return isGltfPath(path) ? loadGltfModel(path, options) : loadManifest(path, options);
}

const char* inputKindName(InputKind kind) {
  switch (kind) {
    case InputKind::kMesh:
      return "mesh";
    case InputKind::kModel:
      return "model";
    case InputKind::kAnimatedModel:
      return "animated model";
  }
  return "?";
}

InputType inputType(const std::string& path) {
  if (isObjPath(path)) return {InputFormat::kObj, InputKind::kMesh};
  if (isGltfPath(path)) return {InputFormat::kGltf, gltfHasModel(path) ? InputKind::kModel : InputKind::kMesh};
  return {InputFormat::kManifest, InputKind::kModel};
}

namespace {

OpenedInput openAsModel(const std::string& path, InputFormat format, const MeshReadOptions& options, InputBuild build) {
  OpenedInput in;
  in.format = format;
  in.kind = InputKind::kModel;
  in.raw = loadModel(path, options);
  if (in.raw.animated()) in.kind = InputKind::kAnimatedModel;
  if (build == InputBuild::kBuilt) buildOpenedModel(in);
  return in;
}

}  // namespace

void buildOpenedModel(OpenedInput& in) {
  in.model.reset();
  in.animated.reset();
  if (in.raw.animated())
    in.animated = std::make_shared<const AnimatedViewDependentModel>(AnimatedViewDependentModel::build(in.raw));
  else
    in.model = std::make_shared<const ViewDependentModel>(ViewDependentModel::build(in.raw));
}

OpenedInput openInput(const std::string& path, const MeshReadOptions& options, InputBuild build) {
  const InputType type = inputType(path);
  if (type.kind != InputKind::kMesh) return openAsModel(path, type.format, options, build);
  OpenedInput in;
  in.format = type.format;
  in.kind = InputKind::kMesh;
  in.mesh = readMesh(path, options);
  return in;
}

OpenedInput openModel(const std::string& path, const MeshReadOptions& options, InputBuild build) {
  if (isObjPath(path))
    throw Error(path +
                ": an OBJ mesh, not a view-dependent model (expected a manifest *.vdg.json or a glTF "
                "file vdg exported)");
  return openAsModel(path, isGltfPath(path) ? InputFormat::kGltf : InputFormat::kManifest, options, build);
}

}  // namespace vdg
