// The KHR_interactivity graph of a static view-dependent export (see the header and
// docs/interactivity.md). Every node is a core operation of the extension; values are float,
// float3, float4, float4x4 or bool. The graph is data only: the engine evaluates it on each tick.
#include "vdg/io/gltf_interactivity.h"

#include <nlohmann/json.hpp>

#include <Eigen/Geometry>

#include <cstdint>
#include <cstdio>
#include <cstring>
#include <utility>
#include <vector>

#include "vdg/geom/error.h"
#include "vdg/io/read_file.h"

namespace vdg {
namespace {

using OJson = nlohmann::ordered_json;
using Eigen::Vector3d;

constexpr const char* kCameraPointer = "/extensions/KHR_interactivity/activeCamera/position";

// Builds one graph: its types, declarations (one per operation) and nodes.
class GraphBuilder {
 public:
  int type(const std::string& signature) { return indexOf(types_, type_index_, signature, "signature"); }
  // Adds a node of operation `op`; returns its index.
  int node(const std::string& op, OJson values = OJson::object(), OJson configuration = OJson::object()) {
    OJson n = {{"declaration", indexOf(declarations_, declaration_index_, op, "op")}};
    if (!configuration.empty()) n["configuration"] = std::move(configuration);
    if (!values.empty()) n["values"] = std::move(values);
    nodes_.push_back(std::move(n));
    ++size_.ops[op];
    return static_cast<int>(nodes_.size()) - 1;
  }
  // The value output `socket` of node `n`.
  static OJson out(int n, const char* socket = "value") { return {{"node", n}, {"socket", socket}}; }
  OJson f(double x) { return {{"type", type("float")}, {"value", OJson::array({x})}}; }
  OJson f4(const Eigen::Vector4d& v) {
    return {{"type", type("float4")}, {"value", OJson::array({v.x(), v.y(), v.z(), v.w()})}};
  }
  OJson f3(const Vector3d& v) { return {{"type", type("float3")}, {"value", OJson::array({v.x(), v.y(), v.z()})}}; }
  // Operation `op` on inputs a (and b, c): its "value" output.
  OJson call(const std::string& op, OJson a) { return out(node(op, {{"a", std::move(a)}})); }
  OJson call(const std::string& op, OJson a, OJson b) {
    return out(node(op, {{"a", std::move(a)}, {"b", std::move(b)}}));
  }
  OJson select(OJson condition, OJson a, OJson b) {
    return out(node("math/select", {{"condition", std::move(condition)}, {"a", std::move(a)}, {"b", std::move(b)}}));
  }
  OJson combine3(const OJson& x, const OJson& y, const OJson& z) {
    return out(node("math/combine3", {{"a", x}, {"b", y}, {"c", z}}));
  }
  // A float variable with initial value x; returns its index.
  int variable(double x) {
    variables_.push_back({{"type", type("float")}, {"value", OJson::array({x})}});
    return static_cast<int>(variables_.size()) - 1;
  }
  void setFlow(int from, const std::string& socket, int to) {
    nodes_[from]["flows"][socket] = {{"node", to}, {"socket", "in"}};
  }

  OJson finish(InteractivitySize* size) {
    size_.nodes = nodes_.size();
    size_.declarations = declarations_.size();
    size_.types = types_.size();
    if (size) *size = size_;
    // No empty "variables" or "events": the specification wants such arrays non-empty when present.
    OJson graph = {{"types", types_}};
    if (!variables_.empty()) graph["variables"] = variables_;
    graph["declarations"] = declarations_;
    graph["nodes"] = nodes_;
    return {{"graphs", OJson::array({std::move(graph)})}, {"graph", 0}};
  }

 private:
  static int indexOf(OJson& list, std::map<std::string, int>& index, const std::string& name, const char* key) {
    const auto [it, added] = index.emplace(name, static_cast<int>(list.size()));
    if (added) list.push_back({{key, name}});
    return it->second;
  }
  OJson types_ = OJson::array(), declarations_ = OJson::array(), nodes_ = OJson::array();
  OJson variables_ = OJson::array();
  std::map<std::string, int> type_index_, declaration_index_;
  InteractivitySize size_;
};

// Target index of sphere point p as a float (-1: a dummy base point, no target).
double targetOf(const InteractivityInput& in, int p) {
  return p < static_cast<int>(in.sphere.views) ? static_cast<double>(in.sphere.view_targets[p][0]) : -1.0;
}

// What the triangle chain or the falloff hands on: slot weights, slot targets, the factor f.
struct Slots {
  OJson weights, corners, factor;
};

// Step 3: the first triangle that holds v (index order), or `fallback`.
Slots triangleChain(GraphBuilder& g, const InteractivityInput& in, const OJson& v, Slots fallback) {
  const auto& s = in.sphere;
  for (std::size_t i = s.triangles.size(); i-- > 0;) {
    const auto& t = s.triangles[i];
    const Vector3d corners(targetOf(in, t[0]), targetOf(in, t[1]), targetOf(in, t[2]));
    // A triangle of three dummy base points gives every target 0, as the chain's end does (base mode):
    // left out, so that a model with few keys does not pay for the dummies' part of the hull.
    if (corners.maxCoeff() < 0.0) continue;
    const Eigen::Matrix3d& m = s.inverses[i];
    OJson l[3];
    for (int r = 0; r < 3; ++r) l[r] = g.call("math/dot", g.f3(m.row(r).transpose()), v);
    const OJson lower = g.call("math/min", g.call("math/min", l[0], l[1]), l[2]);
    const OJson inside = g.call("math/ge", lower, g.f(-kGraphInsideTol));
    fallback.weights = g.select(inside, g.combine3(l[0], l[1], l[2]), fallback.weights);
    fallback.corners = g.select(inside, g.f3(corners), fallback.corners);
    if (!fallback.factor.is_null()) fallback.factor = g.select(inside, g.f(1.0), fallback.factor);
  }
  return fallback;
}

// The running nearest feature of the falloff: its cosine and slots.
struct Nearest {
  OJson cosine, weights, corners;
};

void consider(GraphBuilder& g, Nearest& best, const OJson& cosine, const OJson& weights, const OJson& corners) {
  const OJson better = g.call("math/gt", cosine, best.cosine);
  best.cosine = g.select(better, cosine, best.cosine);
  best.weights = g.select(better, weights, best.weights);
  best.corners = g.select(better, corners, best.corners);
}

// Step 4: the nearest boundary arc or isolated key (view_sphere.cpp's falloff(), its scan order).
Slots falloff(GraphBuilder& g, const InteractivityInput& in, const OJson& v) {
  const auto& s = in.sphere;
  const Vector3d first(1.0, 0.0, 0.0);
  Nearest best{g.f(-2.0), g.f3(Vector3d::Zero()), g.f3(Vector3d::Constant(-1.0))};
  for (const int k : s.isolated)
    consider(g, best, g.call("math/dot", g.f3(s.points[k]), v), g.f3(first), g.f3(Vector3d(targetOf(in, k), -1, -1)));
  for (const auto& arc : s.arcs) {
    const Vector3d& a = s.points[arc[0]];
    const Vector3d& b = s.points[arc[1]];
    const Vector3d n = a.cross(b).normalized();
    const OJson h = g.call("math/dot", g.f3(n), v);
    const OJson c2 = g.call("math/sub", g.f(1.0), g.call("math/mul", h, h));
    const OJson la = g.call("math/dot", g.f3(b.cross(n)), v);
    const OJson lb = g.call("math/dot", g.f3(n.cross(a)), v);
    const OJson sum = g.call("math/add", la, lb);
    const OJson valid = g.call(
        "math/and", g.call("math/and", g.call("math/gt", c2, g.f(kGraphArcMinC2)), g.call("math/gt", sum, g.f(0.0))),
        g.call("math/and", g.call("math/ge", la, g.f(0.0)), g.call("math/ge", lb, g.f(0.0))));
    const OJson on_arc = g.combine3(g.call("math/div", la, sum), g.call("math/div", lb, sum), g.f(0.0));
    // Not on the arc: its ends, a then b (b only when strictly nearer, as two strict comparisons give).
    const OJson ca = g.call("math/dot", g.f3(a), v), cb = g.call("math/dot", g.f3(b), v);
    const OJson b_nearer = g.call("math/gt", cb, ca);
    const OJson end_corners =
        g.select(b_nearer, g.f3(Vector3d(targetOf(in, arc[1]), -1, -1)), g.f3(Vector3d(targetOf(in, arc[0]), -1, -1)));
    consider(g, best, g.select(valid, g.call("math/sqrt", c2), g.select(b_nearer, cb, ca)),
             g.select(valid, on_arc, g.f3(first)),
             g.select(valid, g.f3(Vector3d(targetOf(in, arc[0]), targetOf(in, arc[1]), -1)), end_corners));
  }
  OJson factor = g.call("math/max", best.cosine, g.f(0.0));
  if (in.uncovered == Uncovered::Cosine2) factor = g.call("math/mul", factor, factor);
  return {best.weights, best.corners, factor};
}

// Step 5: max(w, 0) sharpened relative to the largest, normalised, times the factor.
OJson finalWeights(GraphBuilder& g, const InteractivityInput& in, const Slots& slots) {
  OJson w = g.call("math/max", slots.weights, g.f3(Vector3d::Zero()));
  if (in.sharpness != 1.0) {
    // The components by dot products with the axes (Babylon.js 9 refuses math/extract3 of a float3).
    OJson part[3];
    for (int c = 0; c < 3; ++c) part[c] = g.call("math/dot", w, g.f3(Vector3d::Unit(c)));
    const OJson largest = g.call("math/max", g.call("math/max", part[0], part[1]), part[2]);
    w = g.call("math/pow", g.call("math/div", w, g.combine3(largest, largest, largest)),
               g.f3(Vector3d::Constant(in.sharpness)));
  }
  const OJson sum = g.call("math/dot", w, g.f3(Vector3d::Ones()));
  const OJson scale = g.call("math/div", slots.factor.is_null() ? g.f(1.0) : slots.factor, sum);
  return g.call("math/mul", w, g.combine3(scale, scale, scale));
}

// Step 2: the camera position carried into the model's space. glTF scene space to the mesh node's
// space by the inverse of its global matrix (math/transform of (x, y, z, 1)), then to the model's
// space by the node's own transform as exported (the dequantisation of --compress quantize:
// offset + scale * p; nothing otherwise). Components come from dot products with the axes
// (Babylon.js 9 refuses math/extract3 and math/extract4 of a typed input).
OJson modelEye(GraphBuilder& g, const InteractivityInput& in) {
  const int camera = g.node("pointer/get", OJson::object(),
                            {{"pointer", {{"value", OJson::array({kCameraPointer})}}},
                             {"type", {{"value", OJson::array({g.type("float3")})}}}});
  const std::string pointer = "/nodes/" + std::to_string(in.node) + "/globalMatrix";
  const int global = g.node(
      "pointer/get", OJson::object(),
      {{"pointer", {{"value", OJson::array({pointer})}}}, {"type", {{"value", OJson::array({g.type("float4x4")})}}}});
  const OJson position = GraphBuilder::out(camera);
  OJson c[3];
  for (int k = 0; k < 3; ++k) c[k] = g.call("math/dot", position, g.f3(Vector3d::Unit(k)));
  const OJson homogeneous =
      GraphBuilder::out(g.node("math/combine4", {{"a", c[0]}, {"b", c[1]}, {"c", c[2]}, {"d", g.f(1.0)}}));
  const OJson local = g.call("math/transform", homogeneous, g.call("math/inverse", GraphBuilder::out(global)));
  for (int k = 0; k < 3; ++k) c[k] = g.call("math/dot", local, g.f4(Eigen::Vector4d::Unit(k)));
  OJson p = g.combine3(c[0], c[1], c[2]);
  if (in.node_scale != Vector3d::Ones()) p = g.call("math/mul", p, g.f3(in.node_scale));
  if (in.node_offset != Vector3d::Zero()) p = g.call("math/add", p, g.f3(in.node_offset));
  return p;
}

// Step 6. The tick goes through a flow/branch on `valid` (an eye away from the centre; a NaN camera
// fails it too), so such a frame keeps the last weights, as vdg-three does. Then one flow/sequence
// runs one variable/set that stores every target's weight (the value graph is evaluated once: an
// engine may evaluate it again for each flow node that reads it) and a pointer/set per target
// from a variable/get. The sequence's output sockets are zero-padded numbers, so their code point
// order is: the variable/set, then the targets in order. Flows only point to later nodes.
void setWeights(GraphBuilder& g, const InteractivityInput& in, int tick, const OJson& valid, const OJson& weights,
                const OJson& corners) {
  OJson stored = OJson::object(), variables = OJson::array();
  for (std::size_t k = 0; k < in.targets; ++k) {
    const OJson distance = g.call("math/abs", g.call("math/sub", corners, g.f3(Vector3d::Constant(double(k)))));
    const OJson match = g.call("math/saturate", g.call("math/sub", g.f3(Vector3d::Ones()), distance));
    const int variable = g.variable(0.0);
    stored[std::to_string(variable)] = g.call("math/dot", weights, match);
    variables.push_back(variable);
  }
  const int branch = g.node("flow/branch", {{"condition", valid}});
  g.setFlow(tick, "out", branch);
  const int sequence = g.node("flow/sequence");
  g.setFlow(branch, "true", sequence);
  const std::size_t digits = std::to_string(in.targets).size();
  auto socket = [&](std::size_t i) {
    const std::string index = std::to_string(i);
    return std::string(digits - index.size(), '0') + index;
  };
  const int set_all = g.node("variable/set", std::move(stored), {{"variables", {{"value", variables}}}});
  g.setFlow(sequence, socket(0), set_all);
  for (std::size_t k = 0; k < in.targets; ++k) {
    const int get = g.node("variable/get", OJson::object(), {{"variable", {{"value", OJson::array({variables[k]})}}}});
    const std::string pointer = "/nodes/" + std::to_string(in.node) + "/weights/" + std::to_string(k);
    const int set = g.node(
        "pointer/set", {{"value", GraphBuilder::out(get)}},
        {{"pointer", {{"value", OJson::array({pointer})}}}, {"type", {{"value", OJson::array({g.type("float")})}}}});
    g.setFlow(sequence, socket(k + 1), set);
  }
}

}  // namespace

void checkInteractivitySupported(const GltfExportInput& in, const std::string& where) {
  if (in.base_animation || (in.view_sphere && !in.view_sphere->time.empty()))
    throw Error(where + ": --interactivity: " + kInteractivityAnimatedRefusal);
  if (in.sphere.scheme != WeightScheme::Linear)
    throw Error(where + ": --interactivity: " + kInteractivitySchemeRefusal);
}

InteractivityInput interactivityInput(const GltfExportInput& in, const std::string& where) {
  const std::string what = where + ": --interactivity: ";
  checkInteractivitySupported(in, where);
  InteractivityInput out;
  if (in.view_sphere) {
    out.sphere = *in.view_sphere;
  } else {
    std::vector<Vector3d> views;
    for (const GltfTarget& t : in.targets) views.push_back(t.view);
    out.sphere = gltfViewSphere(ViewSphere::build(views, in.sphere));
  }
  for (const auto& targets : out.sphere.view_targets)
    if (targets.size() != 1) throw Error(what + "every key view must have exactly one morph target");
  out.uncovered = in.sphere.uncovered;
  out.sharpness = in.sharpness;
  out.center = in.center;
  out.targets = gltfTargetCount(in);
  out.node = 0;
  return out;
}

std::string interactivityGraphJson(const InteractivityInput& in, InteractivitySize* size) {
  GraphBuilder g;
  g.type("float");
  g.type("float3");
  g.type("bool");
  const int tick = g.node("event/onTick");
  const OJson eye = g.call("math/sub", modelEye(g, in), g.f3(in.center));
  const OJson v = g.call("math/normalize", eye);
  Slots fallback;
  if (in.uncovered == Uncovered::Base) {  // unreachable: the hull with its dummies encloses the centre
    fallback = {g.f3(Vector3d::Ones()), g.f3(Vector3d::Constant(-1.0)), OJson()};
  } else {
    fallback = falloff(g, in, v);
  }
  const Slots chosen = triangleChain(g, in, v, fallback);
  const OJson weights = finalWeights(g, in, chosen);
  setWeights(g, in, tick, g.call("math/gt", g.call("math/dot", eye, eye), g.f(0.0)), weights, chosen.corners);
  return g.finish(size).dump();
}

bool interactivitySizeOfGltfJson(std::string_view json_text, const std::string& where, InteractivitySize& size) {
  const OJson doc = OJson::parse(json_text, nullptr, false);
  if (doc.is_discarded() || !doc.is_object()) throw Error(where + ": the glTF JSON does not parse");
  if (!doc.contains("extensions") || !doc["extensions"].is_object() || !doc["extensions"].contains("KHR_interactivity"))
    return false;
  const OJson& ext = doc["extensions"]["KHR_interactivity"];
  if (!ext.is_object() || !ext.contains("graphs") || !ext["graphs"].is_array())
    throw Error(where + ": extensions.KHR_interactivity has no \"graphs\" array");
  size = {};
  for (const OJson& graph : ext["graphs"]) {
    if (!graph.is_object() || !graph.contains("nodes") || !graph["nodes"].is_array() ||
        !graph.contains("declarations") || !graph["declarations"].is_array())
      throw Error(where + ": a KHR_interactivity graph without \"nodes\" and \"declarations\" arrays");
    const OJson& declarations = graph["declarations"];
    size.nodes += graph["nodes"].size();
    size.declarations += declarations.size();
    if (graph.contains("types") && graph["types"].is_array()) size.types += graph["types"].size();
    for (const OJson& node : graph["nodes"]) {
      std::string op = "?";
      if (node.is_object() && node.contains("declaration") && node["declaration"].is_number_unsigned()) {
        const std::size_t d = node["declaration"].get<std::size_t>();
        if (d < declarations.size() && declarations[d].is_object() && declarations[d].contains("op") &&
            declarations[d]["op"].is_string())
          op = declarations[d]["op"].get<std::string>();
      }
      ++size.ops[op];
    }
  }
  return true;
}

bool interactivitySizeOfGltfFile(const std::string& path, InteractivitySize& size) {
  const std::string bytes = readFileLimited(path, "glTF file", kMaxMeshFileBytes);
  std::string_view json = bytes;
  if (json.size() >= 20 && json.substr(0, 4) == "glTF") {  // a .glb: its first chunk
    std::uint32_t length = 0;
    std::memcpy(&length, bytes.data() + 12, 4);
    json = json.substr(20, std::min<std::size_t>(length, json.size() - 20));
  }
  return interactivitySizeOfGltfJson(json, path, size);
}

InteractivityInput interactivityInput(const ViewDependentModel& model) {
  InteractivityInput in;
  in.sphere = gltfViewSphere(model.sphere());
  in.uncovered = model.sphere().settings().uncovered;
  in.sharpness = model.sharpness();
  in.center = model.center();
  in.targets = model.keyCount();
  return in;
}

std::string interactivitySizeText(const InteractivitySize& size) {
  std::string text = std::to_string(size.nodes) + " nodes, " + std::to_string(size.declarations) + " declarations, " +
                     std::to_string(size.types) + " types (";
  bool first = true;
  for (const auto& [op, count] : size.ops) {
    text += (first ? "" : ", ") + std::to_string(count) + " " + op;
    first = false;
  }
  return text + ")";
}

}  // namespace vdg
