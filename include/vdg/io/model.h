// Opening a model, and opening any input the tools take while saying what it is: a mesh (OBJ, or a
// glTF file without vdg's description), a view-dependent model (a manifest *.vdg.json, or a glTF
// file vdg exported, whose default mesh carries mesh.extras.vdg), static or animated. Every
// subcommand and the language's vdg.load open their inputs here, so they agree on what a file is.
#pragma once

#include <memory>
#include <string>

#include "vdg/geom/tri_mesh.h"
#include "vdg/io/mesh_read_options.h"
#include "vdg/viewdep/animated_model.h"
#include "vdg/viewdep/model.h"

namespace vdg {

// A model from a manifest (*.vdg.json, loadManifest) or from a glTF file vdg exported
// (loadGltfModel), chosen by the extension: .gltf and .glb are glTF, anything else a manifest.
// `options` apply to the base mesh. Throws vdg::Error naming the file.
RawViewDependentModel loadModel(const std::string& path, const MeshReadOptions& options = {});

// Which file format holds an input (by its extension, any letter case).
enum class InputFormat {
  kObj,       // .obj: a mesh
  kGltf,      // .gltf, .glb: a mesh, or a model when vdg exported it
  kManifest,  // anything else: a manifest
};
// What an input is.
enum class InputKind {
  kMesh,           // a plain mesh: no keys
  kModel,          // a static view-dependent model (Rademacher 99)
  kAnimatedModel,  // a view-dependent model on an animated base (Rademacher 99, section 4)
};
const char* inputKindName(InputKind kind);  // "mesh", "model", "animated model"

struct InputType {
  InputFormat format = InputFormat::kManifest;
  InputKind kind = InputKind::kModel;  // kModel for a manifest: whether it is animated needs reading it
};
// What `path` holds, from its extension, and for a glTF file from whether its default mesh carries
// mesh.extras.vdg (gltfHasModel, which reads the file: throws vdg::Error for one that does not load).
// A manifest is reported kModel without being read (openInput tells static from animated).
InputType inputType(const std::string& path);

// Whether openInput builds the run-time model or only reads its description.
enum class InputBuild { kRawOnly, kBuilt };

// An opened input: what it is, and the loaded object(s).
struct OpenedInput {
  InputFormat format = InputFormat::kManifest;
  InputKind kind = InputKind::kMesh;
  TriMesh mesh;               // kMesh: the mesh
  RawViewDependentModel raw;  // kModel, kAnimatedModel: the description as read
  // InputBuild::kBuilt: the model built from `raw` (the one matching `kind`; null otherwise).
  std::shared_ptr<const ViewDependentModel> model;
  std::shared_ptr<const AnimatedViewDependentModel> animated;

  bool isModel() const { return kind != InputKind::kMesh; }
};

// Opens `path` as inputType says: a mesh with readMesh (vdg/io/mesh.h), a model with loadModel,
// built when `build` is kBuilt. `options` apply to the mesh or the model's base. Throws vdg::Error
// naming the file for one that does not load or a model that does not build.
OpenedInput openInput(const std::string& path, const MeshReadOptions& options = {},
                      InputBuild build = InputBuild::kBuilt);

// Opens `path` as a model, for the commands that take models only: loadModel, then built as
// openInput does. An OBJ file is refused with vdg::Error "FILE: an OBJ mesh, not a view-dependent
// model (...)"; a glTF file vdg did not export with loadGltfModel's message.
OpenedInput openModel(const std::string& path, const MeshReadOptions& options = {},
                      InputBuild build = InputBuild::kBuilt);

// (Re)builds the run-time model of an opened model from its `raw` description (after a command
// changed a setting of it, e.g. vdg weights --scheme). Throws vdg::Error as openInput does.
void buildOpenedModel(OpenedInput& in);

}  // namespace vdg
