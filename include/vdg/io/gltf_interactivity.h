// The view-dependent weights as a KHR_interactivity behaviour graph (docs/interactivity.md): what
// `vdg export --interactivity` adds to a static model's glTF so that an engine implementing the
// extension (Babylon.js 9) sets the morph weights from its active camera with no vdg code.
//
// The graph repeats ViewSphere::weightsByScan (vdg/viewdep/view_sphere.h) and web/vdg-three.js's
// vdgWeights on every tick, from the same numbers mesh.extras.vdg v2 carries:
//  1. event/onTick; pointer/get /extensions/KHR_interactivity/activeCamera/position (float3, glTF
//     scene space).
//  2. Into the model's space: the inverse of the mesh node's /nodes/{node}/globalMatrix (so an
//     engine that moves the node is followed), then the node's own transform as exported
//     (node_offset, node_scale: --compress quantize's dequantisation); v = normalize(eye - centre).
//  3. Per hull triangle t: cone coordinates l = (r0.v, r1.v, r2.v) with the rows r of the written
//     inverse; inside_t = min(l) >= -kGraphInsideTol. A chain of math/select (triangle 0
//     outermost) keeps the first triangle that holds v, its l and its corners' morph targets
//     (a float3 of target indices, -1 for a dummy base point). Triangles of three dummy points are
//     left out: a view in one falls to the chain's end, which gives every target 0 as they would.
//  4. Cosine modes: when no triangle holds v, the nearest boundary arc or isolated key (the scan
//     order and strict ">" of view_sphere.cpp's falloff) gives the slot weights and the factor
//     f = max(0, cos) (cosine) or its square (cosine2); base mode's chain ends in the base (no
//     target).
//  5. w = max(l, 0); sharpened relative to the largest, (w_i / w_max)^a / sum (skipped for a = 1,
//     then w / sum); times f.
//  6. Per morph target k: weight_k = w . saturate(1 - |corners - k|) (1 where a corner is target k).
//     When the eye is not at the centre (|eye - centre|^2 > 0; a NaN camera fails too: the last
//     weights stay), one flow/sequence runs a variable/set of every weight (the value graph is
//     evaluated once per tick) and then, per target, pointer/set /nodes/{node}/weights/{k} from a
//     variable/get.
// Animated models (key frames over time) are not supported: interactivityInput refuses them.
#pragma once

#include <cstddef>
#include <map>
#include <string>
#include <string_view>

#include <Eigen/Core>

#include "vdg/io/gltf_export.h"
#include "vdg/viewdep/model.h"
#include "vdg/viewdep/view_sphere.h"

namespace vdg {

// Cone coordinates down to -kGraphInsideTol still count as inside (view_sphere.cpp's kInsideTol).
inline constexpr double kGraphInsideTol = 1e-9;
// An arc's projection counts when 1 - (v.n)^2 exceeds this (view_sphere.cpp's falloff()).
inline constexpr double kGraphArcMinC2 = 1e-24;

// Why an animated model gets no graph (after "WHERE: --interactivity: ").
inline constexpr const char* kInteractivityAnimatedRefusal =
    "animated models (key frames over time) are not supported; export a static model (docs/interactivity.md, "
    "\"Limits\")";

// Why a model whose weights are not linear gets no graph (after "WHERE: --interactivity: ").
inline constexpr const char* kInteractivitySchemeRefusal =
    "the graph weighs the keys with the linear scheme only; this model's weights are not (\"smooth\" or \"rbf\"; "
    "export it without "
    "--interactivity, or with \"weights\": {\"scheme\": \"linear\"}; docs/weights.md)";

// What the graph is built from: exactly the export's extras v2 sphere and settings.
struct InteractivityInput {
  GltfViewSphere sphere;  // static: view_targets[i] = {i}
  Uncovered uncovered = Uncovered::Base;
  double sharpness = 1.0;
  Eigen::Vector3d center = Eigen::Vector3d::Zero();
  std::size_t targets = 0;  // morph targets of the mesh
  int node = 0;             // glTF node that holds the mesh
  // That node's own transform as exported (translation and scale: --compress quantize's
  // dequantisation; none otherwise): model space = node_offset + node_scale * node space.
  Eigen::Vector3d node_offset = Eigen::Vector3d::Zero();
  Eigen::Vector3d node_scale = Eigen::Vector3d::Ones();
};

// The input of a static export (`in.view_sphere` as written, or built from the targets as the writer
// does). Throws vdg::Error "WHERE: --interactivity: ..." for an animated model (named as not
// supported) or a sphere whose view_targets are not one target per key view.
InteractivityInput interactivityInput(const GltfExportInput& in, const std::string& where);
// Its first check alone (what the writer does before anything else): throws for an animated model.
void checkInteractivitySupported(const GltfExportInput& in, const std::string& where);

// How large a graph is.
struct InteractivitySize {
  std::size_t nodes = 0;
  std::size_t declarations = 0;
  std::size_t types = 0;
  std::map<std::string, std::size_t> ops;  // node count per operation ("math/dot": 120, ...)
};

// The KHR_interactivity extension object as JSON text: {"graphs": [one graph], "graph": 0}.
// `size` (optional) receives its size.
std::string interactivityGraphJson(const InteractivityInput& input, InteractivitySize* size = nullptr);

// The size of the KHR_interactivity graph(s) in a glTF document's JSON text (the .gltf file, or a
// .glb's JSON chunk); false when it has no KHR_interactivity extension. Throws vdg::Error naming
// `where` for text that is not JSON or a graph that is not an object with "nodes" and
// "declarations" arrays.
bool interactivitySizeOfGltfJson(std::string_view json_text, const std::string& where, InteractivitySize& size);

// The same for a glTF file (.gltf, or .glb: its JSON chunk). Throws vdg::Error "PATH: ..." for a
// file that cannot be read or parsed.
bool interactivitySizeOfGltfFile(const std::string& path, InteractivitySize& size);

// The graph input of a built static model, as its export would carry it (one target per key).
InteractivityInput interactivityInput(const ViewDependentModel& model);

// One line for `vdg info`: "N nodes, D declarations, T types (K math/dot, ...)".
std::string interactivitySizeText(const InteractivitySize& size);

}  // namespace vdg
