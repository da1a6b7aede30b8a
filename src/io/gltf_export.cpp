// glTF 2.0 output of view-dependent models (see vdg/io/gltf_export.h and docs/gltf-export.md).
//
// Rademacher 99, section 3.2.3: the blended model is base + sum_i w_i (key_i - base); glTF 2.0
// (section 3.7.2.2, morph targets) renders base + sum_i weights[i] * target_i, so the key deltas
// are the targets and a view's weights are the morph weights. The JSON follows the glTF 2.0
// specification; the binary buffer is laid out here.
#include "vdg/io/gltf_export.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <nlohmann/json.hpp>
#include <numbers>
#include <set>

#include "camera_fields.h"
#include "json_reader.h"
#include "vdg/geom/error.h"
#include "vdg/geom/normalize.h"
#include "vdg/io/atomic_file.h"
#include "vdg/io/file_transaction.h"
#include "vdg/version.h"

namespace vdg {
namespace {

static_assert(std::endian::native == std::endian::little, "the glTF buffer is written in the host's byte order");

using OJson = nlohmann::ordered_json;

// glTF constants (glTF 2.0 section 5.1.1 and 5.11.1).
constexpr int kUnsignedByte = 5121, kUnsignedShort = 5123, kUnsignedInt = 5125, kFloat = 5126;
constexpr int kArrayBuffer = 34962, kElementArrayBuffer = 34963;
constexpr int kTriangles = 4;
constexpr std::uint32_t kGlbMagic = 0x46546C67;  // "glTF"
constexpr std::uint32_t kGlbVersion = 2;
constexpr std::uint32_t kChunkJson = 0x4E4F534A;  // "JSON"
constexpr std::uint32_t kChunkBin = 0x004E4942;   // "BIN\0"
// A NORMAL accessor's vectors must be unit length (glTF 2.0 section 3.7.2.1); the validator allows
// a small float error, this is looser than float rounding and far tighter than a wrong normal.
constexpr double kUnitNormalTol = 1e-4;

constexpr std::pair<const char*, Uncovered> kUncoveredNames[] = {
    {"base", Uncovered::Base}, {"cosine", Uncovered::Cosine}, {"cosine2", Uncovered::Cosine2}};

std::size_t pad4(std::size_t n) { return (n + 3) & ~std::size_t{3}; }

// The binary buffer and the bufferViews / accessors describing it.
class BufferBuilder {
 public:
  // Appends `bytes` as a new bufferView (starting on a 4-byte boundary); target 0 = none.
  int addView(const void* bytes, std::size_t size, int target) {
    data_.resize(pad4(data_.size()), '\0');
    OJson view = {{"buffer", 0}, {"byteOffset", data_.size()}, {"byteLength", size}};
    if (target != 0) view["target"] = target;
    data_.append(static_cast<const char*>(bytes), size);
    views_.push_back(std::move(view));
    return static_cast<int>(views_.size()) - 1;
  }
  int addAccessor(OJson accessor) {
    accessors_.push_back(std::move(accessor));
    return static_cast<int>(accessors_.size()) - 1;
  }
  // A float accessor over a new view; min/max when `bounds` (required for POSITION).
  int addFloats(std::span<const float> values, int components, int target, bool bounds) {
    const int view = addView(values.data(), values.size() * sizeof(float), target);
    OJson acc = {{"bufferView", view},
                 {"componentType", kFloat},
                 {"count", values.size() / components},
                 {"type", typeName(components)}};
    if (bounds) addBounds(acc, values, components, false);
    return addAccessor(std::move(acc));
  }
  static const char* typeName(int components) {
    switch (components) {
      case 1:
        return "SCALAR";
      case 2:
        return "VEC2";
      case 3:
        return "VEC3";
      default:
        return "VEC4";
    }
  }
  // min/max per component; `with_zero` includes the zero vector (elements a sparse accessor
  // leaves at their initial zeros).
  static void addBounds(OJson& acc, std::span<const float> values, int components, bool with_zero) {
    std::vector<float> lo(components, std::numeric_limits<float>::infinity()), hi(components, -lo[0]);
    if (with_zero) std::fill(lo.begin(), lo.end(), 0.0f), std::fill(hi.begin(), hi.end(), 0.0f);
    for (std::size_t i = 0; i < values.size(); ++i) {
      const int c = static_cast<int>(i % components);
      lo[c] = std::min(lo[c], values[i]);
      hi[c] = std::max(hi[c], values[i]);
    }
    acc["min"] = OJson::array();
    acc["max"] = OJson::array();
    for (int c = 0; c < components; ++c) {
      acc["min"].push_back(static_cast<double>(lo[c]));
      acc["max"].push_back(static_cast<double>(hi[c]));
    }
  }
  std::string& data() { return data_; }
  OJson& views() { return views_; }
  OJson& accessors() { return accessors_; }

 private:
  std::string data_;
  OJson views_ = OJson::array(), accessors_ = OJson::array();
};

// A morph target attribute (#V x 3 deltas) as a dense accessor, or as a sparse one (only the
// vertices that move, over implicit zeros) when that takes fewer bytes. Returns the accessor and
// sets `sparse`.
int addDeltaAccessor(BufferBuilder& b, std::span<const float> deltas, bool bounds, bool& sparse) {
  const std::size_t v_count = deltas.size() / 3;
  std::vector<std::uint32_t> moved;
  for (std::size_t v = 0; v < v_count; ++v)
    if (deltas[v * 3] != 0.0f || deltas[v * 3 + 1] != 0.0f || deltas[v * 3 + 2] != 0.0f)
      moved.push_back(static_cast<std::uint32_t>(v));
  // sparse.count must be >= 1: a target that moves nothing lists vertex 0 with a zero delta.
  if (moved.empty()) moved.push_back(0);
  const int index_size = v_count <= 256 ? 1 : v_count <= 65536 ? 2 : 4;
  const std::size_t sparse_bytes = pad4(moved.size() * index_size) + moved.size() * 12;
  const std::size_t dense_bytes = v_count * 12;
  sparse = sparse_bytes < dense_bytes;
  if (!sparse) return b.addFloats(deltas, 3, kArrayBuffer, bounds);

  std::vector<float> values;
  values.reserve(moved.size() * 3);
  for (std::uint32_t v : moved) values.insert(values.end(), deltas.begin() + v * 3, deltas.begin() + v * 3 + 3);
  std::string index_bytes(moved.size() * index_size, '\0');
  for (std::size_t i = 0; i < moved.size(); ++i) {
    if (index_size == 1) index_bytes[i] = static_cast<char>(moved[i]);
    if (index_size == 2) {
      const auto x = static_cast<std::uint16_t>(moved[i]);
      std::memcpy(&index_bytes[i * 2], &x, 2);
    }
    if (index_size == 4) std::memcpy(&index_bytes[i * 4], &moved[i], 4);
  }
  const int index_view = b.addView(index_bytes.data(), index_bytes.size(), 0);
  const int value_view = b.addView(values.data(), values.size() * sizeof(float), 0);
  const int component = index_size == 1 ? kUnsignedByte : index_size == 2 ? kUnsignedShort : kUnsignedInt;
  OJson acc = {{"componentType", kFloat},
               {"count", v_count},
               {"type", "VEC3"},
               {"sparse",
                {{"count", moved.size()},
                 {"indices", {{"bufferView", index_view}, {"componentType", component}}},
                 {"values", {{"bufferView", value_view}}}}}};
  if (bounds) BufferBuilder::addBounds(acc, values, 3, moved.size() < v_count);
  return b.addAccessor(std::move(acc));
}

bool allFinite(std::span<const float> values) {
  return std::all_of(values.begin(), values.end(), [](float x) { return std::isfinite(x); });
}

void validateInput(const GltfExportInput& in, const std::string& where) {
  const auto fail = [&](const std::string& what) { throw Error(where + ": " + what); };
  const std::size_t v_count = in.base.vertexCount();
  if (v_count == 0 || in.base.triangleCount() == 0) fail("the base mesh has no vertices or no triangles");
  validateMesh(in.base, where + ": base");
  if (v_count > std::numeric_limits<std::uint32_t>::max()) fail("the base mesh has too many vertices for glTF");
  if (!in.normals.empty()) {
    if (in.normals.size() != in.base.positions.size())
      fail("normals: expected " + std::to_string(v_count) + " x 3 floats, got " + std::to_string(in.normals.size()));
    for (std::size_t v = 0; v < v_count; ++v) {
      const double len = Eigen::Vector3d(in.normals[v * 3], in.normals[v * 3 + 1], in.normals[v * 3 + 2]).norm();
      if (!(std::abs(len - 1.0) <= kUnitNormalTol))
        fail("normals: vertex " + std::to_string(v) + " is not unit length");
    }
  }
  std::set<std::string> names;
  for (std::size_t t = 0; t < in.targets.size(); ++t) {
    const GltfTarget& target = in.targets[t];
    const std::string label = "target " + std::to_string(t) + " '" + target.name + "'";
    if (target.name.empty()) fail("target " + std::to_string(t) + " has no name");
    if (!names.insert(target.name).second) fail(label + ": the name is used twice");
    if (target.deltas.size() != in.base.positions.size())
      fail(label + ": expected " + std::to_string(v_count) + " x 3 deltas, got " +
           std::to_string(target.deltas.size()));
    if (!allFinite(target.deltas)) fail(label + ": a delta is not finite");
    if (!target.normal_deltas.empty() && (in.normals.empty() || target.normal_deltas.size() != in.normals.size()))
      fail(label + ": normal deltas need base normals and " + std::to_string(v_count) + " x 3 floats");
    if (!allFinite(target.normal_deltas)) fail(label + ": a normal delta is not finite");
    if (!target.view.allFinite() || !normalizedOrNone(target.view)) fail(label + ": the view is zero or not finite");
    if (target.frame < 0) fail(label + ": the frame is negative");
  }
  if (!std::isfinite(in.sharpness) || in.sharpness <= 0.0) fail("the sharpness must be finite and > 0");
  if (!in.center.allFinite()) fail("the centre is not finite");
  if (in.base_animation &&
      (in.base_animation->frame_count < 1 || !std::isfinite(in.base_animation->fps) || in.base_animation->fps <= 0.0))
    fail("base animation: expected frame_count >= 1 and fps > 0");
  if (in.bake) {
    const GltfBakedAnimation& bake = *in.bake;
    const std::size_t n = bake.times.size();
    if (n == 0) fail("bake: no sample times");
    if (!allFinite(bake.times)) fail("bake: a time is not finite");
    for (std::size_t i = 1; i < n; ++i)
      if (!(bake.times[i] > bake.times[i - 1]))
        fail("bake: times are not strictly increasing at sample " + std::to_string(i));
    if (in.targets.empty()) fail("bake: the model has no morph targets to animate");
    if (bake.weights.size() != n * in.targets.size())
      fail("bake: expected " + std::to_string(n) + " x " + std::to_string(in.targets.size()) + " weights, got " +
           std::to_string(bake.weights.size()));
    if (!allFinite(bake.weights)) fail("bake: a weight is not finite");
    if (!bake.translations.empty()) {
      if (bake.translations.size() != n * 3 || bake.rotations.size() != n * 4)
        fail("bake: expected " + std::to_string(n) + " camera translations and rotations");
      if (!allFinite(bake.translations) || !allFinite(bake.rotations)) fail("bake: a camera value is not finite");
      if (!(bake.yfov_rad > 0.0 && bake.yfov_rad < std::numbers::pi) || !(bake.aspect > 0.0) ||
          !std::isfinite(bake.aspect) || !(bake.znear > 0.0) || !(bake.zfar > bake.znear) || !std::isfinite(bake.zfar))
        fail("bake: expected 0 < yfov < pi, aspect > 0 and 0 < znear < zfar");
    }
  }
}

OJson vec3Json(const Eigen::Vector3d& v) { return OJson::array({v.x(), v.y(), v.z()}); }

// The view-dependent description (mesh.extras.vdg; docs/schema/vdg-gltf-extras.schema.json).
OJson vdgExtras(const GltfExportInput& in) {
  OJson vdg = {{"version", kGltfExtrasVersion},
               {"sharpness", in.sharpness},
               {"uncovered", uncoveredName(in.sphere.uncovered)},
               {"base_falloff_deg", in.sphere.base_falloff_deg},
               {"center", vec3Json(in.center)},
               {"offsets", gltfOffsetModeName(in.offsets)}};
  if (in.base_animation) {
    OJson anim = {{"frame_count", in.base_animation->frame_count},
                  {"fps", in.base_animation->fps},
                  {"loop", in.base_animation->loop}};
    if (in.base_animation->animation >= 0) anim["animation"] = in.base_animation->animation;
    vdg["animation"] = anim;
  }
  OJson keys = OJson::array();
  for (const GltfTarget& t : in.targets) {
    OJson key = {{"name", t.name}, {"view", vec3Json(t.view)}, {"frame", t.frame}};
    if (t.camera) key["camera"] = io::cameraJson(*t.camera);
    keys.push_back(std::move(key));
  }
  vdg["keys"] = std::move(keys);
  return vdg;
}

// Per-vertex uvs when every corner of a vertex has the same uv (glTF attributes are per vertex),
// v flipped to glTF's top-left origin; nullopt and a note otherwise.
std::optional<std::vector<float>> perVertexUvs(const TriMesh& base, std::string& note) {
  if (base.uvs.empty() || base.uv_triangles.empty()) return std::nullopt;
  const std::size_t v_count = base.vertexCount();
  std::vector<float> uv(v_count * 2, 0.0f);
  std::vector<char> seen(v_count, 0);
  for (std::size_t c = 0; c < base.triangles.size(); ++c) {
    const auto v = static_cast<std::size_t>(base.triangles[c]);
    const auto t = static_cast<std::size_t>(base.uv_triangles[c]);
    const float u = base.uvs[t * 2], w = 1.0f - base.uvs[t * 2 + 1];
    if (!seen[v]) {
      uv[v * 2] = u, uv[v * 2 + 1] = w, seen[v] = 1;
    } else if (uv[v * 2] != u || uv[v * 2 + 1] != w) {
      note = "TEXCOORD_0 not written: vertex " + std::to_string(v) +
             " has different uvs on different triangles (a seam), and glTF keeps one uv per vertex; "
             "splitting vertices would change the model's vertex count";
      return std::nullopt;
    }
  }
  return uv;
}

struct Built {
  OJson doc;
  std::string bin;
};

Built build(const GltfExportInput& in, const std::string& where, GltfExportReport* report) {
  validateInput(in, where);
  GltfExportReport rep;
  BufferBuilder b;
  const std::size_t v_count = in.base.vertexCount();

  OJson attributes = OJson::object();
  attributes["POSITION"] = b.addFloats(in.base.positions, 3, kArrayBuffer, true);
  if (!in.normals.empty()) attributes["NORMAL"] = b.addFloats(in.normals, 3, kArrayBuffer, false);
  if (const auto uvs = perVertexUvs(in.base, rep.note)) {
    attributes["TEXCOORD_0"] = b.addFloats(*uvs, 2, kArrayBuffer, false);
    rep.uvs_written = true;
  }
  // Indices: unsigned short when every index fits below 65535 (the largest value of the type is
  // the primitive restart value, which glTF forbids), else unsigned int.
  int indices = -1;
  if (v_count <= 65535) {
    std::vector<std::uint16_t> idx(in.base.triangles.begin(), in.base.triangles.end());
    const int view = b.addView(idx.data(), idx.size() * 2, kElementArrayBuffer);
    indices = b.addAccessor(
        {{"bufferView", view}, {"componentType", kUnsignedShort}, {"count", idx.size()}, {"type", "SCALAR"}});
  } else {
    std::vector<std::uint32_t> idx(in.base.triangles.begin(), in.base.triangles.end());
    const int view = b.addView(idx.data(), idx.size() * 4, kElementArrayBuffer);
    indices = b.addAccessor(
        {{"bufferView", view}, {"componentType", kUnsignedInt}, {"count", idx.size()}, {"type", "SCALAR"}});
  }

  OJson targets = OJson::array(), names = OJson::array();
  for (const GltfTarget& t : in.targets) {
    bool sparse = false;
    OJson target = {{"POSITION", addDeltaAccessor(b, t.deltas, true, sparse)}};
    rep.sparse_targets += sparse ? 1 : 0;
    if (!t.normal_deltas.empty()) {
      bool normal_sparse = false;
      target["NORMAL"] = addDeltaAccessor(b, t.normal_deltas, false, normal_sparse);
    }
    targets.push_back(std::move(target));
    names.push_back(t.name);
  }

  OJson primitive = {{"attributes", attributes}, {"indices", indices}, {"mode", kTriangles}};
  if (!in.targets.empty()) primitive["targets"] = targets;
  OJson mesh = {{"name", in.mesh_name}, {"primitives", OJson::array({primitive})}};
  if (!in.targets.empty()) mesh["weights"] = std::vector<double>(in.targets.size(), 0.0);
  mesh["extras"] = {{"targetNames", names}, {"vdg", vdgExtras(in)}};

  OJson doc;
  doc["asset"] = {{"version", "2.0"}, {"generator", std::string("vdg ") + versionString()}};
  doc["scene"] = 0;
  OJson nodes = OJson::array({OJson{{"name", in.mesh_name}, {"mesh", 0}}});
  OJson scene_nodes = OJson::array({0});

  if (in.bake) {
    const GltfBakedAnimation& bake = *in.bake;
    const char* interpolation = bake.step ? "STEP" : "LINEAR";
    const int times = b.addFloats(bake.times, 1, 0, true);
    const int weights = b.addFloats(bake.weights, 1, 0, false);
    OJson samplers = OJson::array({OJson{{"input", times}, {"interpolation", interpolation}, {"output", weights}}});
    OJson channels = OJson::array({OJson{{"sampler", 0}, {"target", {{"node", 0}, {"path", "weights"}}}}});
    if (!bake.translations.empty()) {
      const int camera_node = static_cast<int>(nodes.size());
      OJson node = {{"name", "camera"}, {"camera", 0}};
      node["translation"] = {bake.translations[0], bake.translations[1], bake.translations[2]};
      node["rotation"] = {bake.rotations[0], bake.rotations[1], bake.rotations[2], bake.rotations[3]};
      nodes.push_back(std::move(node));
      scene_nodes.push_back(camera_node);
      doc["cameras"] = OJson::array({OJson{
          {"name", "camera"},
          {"type", "perspective"},
          {"perspective",
           {{"yfov", bake.yfov_rad}, {"aspectRatio", bake.aspect}, {"znear", bake.znear}, {"zfar", bake.zfar}}}}});
      const int translations = b.addFloats(bake.translations, 3, 0, false);
      const int rotations = b.addFloats(bake.rotations, 4, 0, false);
      samplers.push_back({{"input", times}, {"interpolation", interpolation}, {"output", translations}});
      samplers.push_back({{"input", times}, {"interpolation", interpolation}, {"output", rotations}});
      channels.push_back({{"sampler", 1}, {"target", {{"node", camera_node}, {"path", "translation"}}}});
      channels.push_back({{"sampler", 2}, {"target", {{"node", camera_node}, {"path", "rotation"}}}});
    }
    OJson animation = {{"name", bake.name}, {"channels", channels}, {"samplers", samplers}};
    if (!bake.description.empty()) animation["extras"] = {{"vdg", {{"bake", bake.description}}}};
    doc["animations"] = OJson::array({animation});
  }
  doc["scenes"] = OJson::array({OJson{{"nodes", scene_nodes}}});
  doc["nodes"] = std::move(nodes);
  doc["meshes"] = OJson::array({mesh});
  b.data().resize(pad4(b.data().size()), '\0');
  doc["buffers"] = OJson::array({OJson{{"byteLength", b.data().size()}}});
  doc["bufferViews"] = std::move(b.views());
  doc["accessors"] = std::move(b.accessors());
  if (report) *report = rep;
  return {std::move(doc), std::move(b.data())};
}

void appendU32(std::string& out, std::uint32_t x) {
  char bytes[4];
  std::memcpy(bytes, &x, 4);
  out.append(bytes, 4);
}

}  // namespace

const char* gltfOffsetModeName(GltfOffsetMode mode) { return mode == GltfOffsetMode::kSkinned ? "skinned" : "world"; }

GltfExportInput gltfExportInput(const ViewDependentModel& model) {
  GltfExportInput in;
  in.base = model.base();
  const std::size_t n = in.base.positions.size();
  const auto normalsOf = [&](std::span<const float> positions, std::vector<float>& out) {
    out.assign(n, 0.0f);
    if (!computeVertexNormals(positions, in.base.triangles, out)) throw Error("model: cannot compute the normals");
    for (std::size_t v = 0; v < n / 3; ++v)
      if (out[v * 3] == 0.0f && out[v * 3 + 1] == 0.0f && out[v * 3 + 2] == 0.0f) out[v * 3 + 1] = 1.0f;
  };
  normalsOf(in.base.positions, in.normals);
  std::vector<float> key(n), key_normals;
  for (std::size_t k = 0; k < model.keyCount(); ++k) {
    if (!model.keyPositions(k, key)) throw Error("model: cannot read key " + std::to_string(k));
    GltfTarget t;
    t.name = model.keyName(k);
    t.view = model.keyView(k);
    t.camera = model.keyCamera(k);
    t.deltas.resize(n);
    for (std::size_t i = 0; i < n; ++i) t.deltas[i] = key[i] - in.base.positions[i];
    normalsOf(key, key_normals);
    t.normal_deltas.resize(n);
    for (std::size_t i = 0; i < n; ++i) t.normal_deltas[i] = key_normals[i] - in.normals[i];
    in.targets.push_back(std::move(t));
  }
  in.sharpness = model.sharpness();
  in.sphere = model.sphere().settings();
  in.center = model.center();
  return in;
}

GltfBakedAnimation bakeCameraPath(const ViewDependentModel& model, std::span<const Camera> cameras, double fps,
                                  double aspect, double sharpness, bool close_loop) {
  if (cameras.empty()) throw Error("bake: no cameras");
  if (!std::isfinite(fps) || fps <= 0.0) throw Error("bake: the frame rate must be finite and > 0");
  if (!std::isfinite(aspect) || aspect <= 0.0) throw Error("bake: the aspect ratio must be finite and > 0");
  GltfBakedAnimation bake;
  const std::size_t keys = model.keyCount();
  const std::size_t samples = cameras.size() + (close_loop ? 1 : 0);
  bake.times.resize(samples);
  bake.weights.assign(samples * keys, 0.0f);
  bake.translations.resize(samples * 3);
  bake.rotations.resize(samples * 4);
  double radius = 0.0;
  const TriMesh& base = model.base();
  for (std::size_t v = 0; v < base.vertexCount(); ++v)
    radius = std::max(
        radius,
        (Eigen::Vector3d(base.positions[v * 3], base.positions[v * 3 + 1], base.positions[v * 3 + 2]) - model.center())
            .norm());
  double near_distance = std::numeric_limits<double>::infinity(), far_distance = 0.0;
  Eigen::Quaterniond previous = Eigen::Quaterniond::Identity();
  for (std::size_t s = 0; s < samples; ++s) {
    const std::size_t i = s % cameras.size();
    const Camera& camera = cameras[i];
    const std::string label = "bake: camera " + std::to_string(i);
    if (camera.isOrtho()) throw Error(label + ": glTF bakes perspective cameras only");
    if (camera.fov_deg != cameras[0].fov_deg) throw Error(label + ": every camera must have the same field of view");
    const Eigen::Vector3d view = model.viewFromEye(camera.eye);
    ViewWeights w;
    if (view.isZero() || !model.weights(view, sharpness, w))
      throw Error(label + ": no view direction (the eye is at the model centre, or the sharpness is not > 0)");
    for (int slot = 0; slot < 3; ++slot)
      if (w.key[slot] >= 0) bake.weights[s * keys + static_cast<std::size_t>(w.key[slot])] += w.weight[slot];
    const CameraFrame frame = cameraFrame(camera);  // throws for a degenerate camera
    Eigen::Matrix3d rotation;
    rotation << frame.right, frame.up, frame.back;
    Eigen::Quaterniond q(rotation);
    q.normalize();
    if (s > 0 && q.dot(previous) < 0.0) q.coeffs() = -q.coeffs();
    previous = q;
    for (int c = 0; c < 3; ++c) bake.translations[s * 3 + c] = static_cast<float>(camera.eye[c]);
    bake.rotations[s * 4 + 0] = static_cast<float>(q.x());
    bake.rotations[s * 4 + 1] = static_cast<float>(q.y());
    bake.rotations[s * 4 + 2] = static_cast<float>(q.z());
    bake.rotations[s * 4 + 3] = static_cast<float>(q.w());
    bake.times[s] = static_cast<float>(static_cast<double>(s) / fps);
    const double d = (camera.eye - model.center()).norm();
    near_distance = std::min(near_distance, d);
    far_distance = std::max(far_distance, d);
  }
  // The clip planes hold the model's bounding sphere from every camera (a camera inside it gets a
  // near plane at a thousandth of its distance).
  bake.znear = std::max(near_distance - 1.5 * radius, 1e-3 * near_distance);
  bake.zfar = far_distance + 1.5 * radius;
  if (!(bake.znear > 0.0)) bake.znear = 1e-6;
  if (!(bake.zfar > bake.znear)) bake.zfar = 2.0 * bake.znear;
  bake.yfov_rad = cameras[0].fov_deg * std::numbers::pi / 180.0;
  bake.aspect = aspect;
  return bake;
}

std::string gltfToGlb(const GltfExportInput& input, const std::string& where, GltfExportReport* report) {
  Built built = build(input, where, report);
  built.doc["buffers"][0].erase("uri");
  std::string json = built.doc.dump(-1, ' ', false, OJson::error_handler_t::replace);
  json.resize(pad4(json.size()), ' ');
  const std::size_t total = 12 + 8 + json.size() + 8 + built.bin.size();
  if (total > std::numeric_limits<std::uint32_t>::max())
    throw Error(where + ": the model is too large for a .glb file (4 GiB)");
  std::string out;
  out.reserve(total);
  appendU32(out, kGlbMagic);
  appendU32(out, kGlbVersion);
  appendU32(out, static_cast<std::uint32_t>(total));
  appendU32(out, static_cast<std::uint32_t>(json.size()));
  appendU32(out, kChunkJson);
  out += json;
  appendU32(out, static_cast<std::uint32_t>(built.bin.size()));
  appendU32(out, kChunkBin);
  out += built.bin;
  if (report) report->bytes = out.size();
  return out;
}

std::string gltfToJson(const GltfExportInput& input, const std::string& where, const std::string& bin_uri,
                       std::string& bin, GltfExportReport* report) {
  Built built = build(input, where, report);
  built.doc["buffers"][0]["uri"] = bin_uri;
  std::string json = built.doc.dump(1, ' ', false, OJson::error_handler_t::replace);
  json += '\n';
  bin = std::move(built.bin);
  if (report) report->bytes = json.size() + bin.size();
  return json;
}

GltfExportReport writeGltfExport(const std::string& path, const GltfExportInput& input) {
  namespace fs = std::filesystem;
  const fs::path p(path);
  std::string ext = p.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  GltfExportReport report;
  if (ext == ".glb") {
    writeFileAtomically(path, gltfToGlb(input, path, &report));
    return report;
  }
  if (ext != ".gltf") throw Error(path + ": expected a .glb or .gltf file name");
  // The buffer's URI is a file name only, so the pair can be moved together.
  const std::string bin_name = p.stem().string() + ".bin";
  std::string bin;
  std::string json = gltfToJson(input, path, bin_name, bin, &report);
  const fs::path folder = p.parent_path();
  const std::string folder_name = folder.empty() ? "." : folder.string();
  const FolderLock lock(folder_name);
  const std::string journal = (fs::path(folder_name) / ".vdg-journal").string();
  (void)recoverFileTransaction(journal);
  FileTransaction transaction(journal);
  transaction.write((folder / bin_name).string(), std::move(bin));
  transaction.write(path, std::move(json));
  transaction.commit();
  return report;
}

RawViewDependentModel rawModelFromGltfExtras(std::string_view mesh_extras_json, const TriMesh& base,
                                             std::span<const std::vector<float>> target_deltas,
                                             const std::string& where) {
  const io::Json extras = io::parseJson(mesh_extras_json, where + ": mesh extras");
  const io::Ctx top{where + ": mesh extras", ""};
  if (!extras.is_object()) top.fail("expected an object, got " + io::describe(extras));
  if (!extras.contains("vdg")) top.fail("no 'vdg' description: this glTF file was not exported by vdg");
  const io::Json& names = io::required(extras, "targetNames", top);
  if (!names.is_array()) top.key("targetNames").fail("expected an array of names, got " + io::describe(names));
  const io::Json& vdg = extras.at("vdg");
  const io::Ctx ctx = top.key("vdg");
  io::allowKeys(vdg, ctx,
                {"version", "sharpness", "uncovered", "base_falloff_deg", "center", "offsets", "keys", "animation"});
  io::formatVersion(vdg, ctx, "view-dependent glTF extras", 1, kGltfExtrasVersion);
  if (vdg.contains("animation"))
    ctx.key("animation").fail("an animated view-dependent model; this vdg reads static ones only");
  RawViewDependentModel raw;
  raw.source = where;
  raw.base = base;
  raw.sharpness = io::number(io::required(vdg, "sharpness", ctx), ctx.key("sharpness"));
  raw.sphere.uncovered = io::enumValue(io::required(vdg, "uncovered", ctx), ctx.key("uncovered"), kUncoveredNames);
  raw.sphere.base_falloff_deg = io::number(io::required(vdg, "base_falloff_deg", ctx), ctx.key("base_falloff_deg"));
  raw.center = io::vector3(io::required(vdg, "center", ctx), ctx.key("center"));
  const std::string offsets = io::string(io::required(vdg, "offsets", ctx), ctx.key("offsets"));
  if (offsets != "world")
    ctx.key("offsets").fail("expected \"world\" for a static model, got " + io::describe(vdg.at("offsets")));
  const io::Json& keys = io::required(vdg, "keys", ctx);
  if (!keys.is_array()) ctx.key("keys").fail("expected an array, got " + io::describe(keys));
  if (keys.size() != target_deltas.size())
    ctx.key("keys").fail("describes " + std::to_string(keys.size()) + " keys, but the mesh has " +
                         std::to_string(target_deltas.size()) + " morph targets");
  if (names.size() != keys.size())
    top.key("targetNames")
        .fail("has " + std::to_string(names.size()) + " names for " + std::to_string(keys.size()) + " morph targets");
  for (std::size_t k = 0; k < keys.size(); ++k) {
    const io::Ctx kc = ctx.key("keys").index(k);
    const io::Json& key = keys[k];
    io::allowKeys(key, kc, {"name", "view", "frame", "camera"});
    RawKey rk;
    rk.name = io::string(io::required(key, "name", kc), kc.key("name"));
    const std::string target_name = io::string(names[k], top.key("targetNames").index(k));
    if (target_name != rk.name)
      kc.key("name").fail("differs from targetNames[" + std::to_string(k) + "] " + io::describe(names[k]));
    rk.view = io::vector3(io::required(key, "view", kc), kc.key("view"));
    if (key.contains("frame") && io::integer(key.at("frame"), kc.key("frame"), 0, std::numeric_limits<int>::max()) != 0)
      kc.key("frame").fail("a key at frame > 0 belongs to an animated model; this vdg reads static ones only");
    if (key.contains("camera")) rk.camera = io::cameraFrom(key.at("camera"), kc.key("camera"));
    if (target_deltas[k].size() != base.positions.size())
      kc.fail("morph target " + std::to_string(k) + " has " + std::to_string(target_deltas[k].size()) +
              " delta values, expected " + std::to_string(base.positions.size()));
    rk.mesh.triangles = base.triangles;
    rk.mesh.positions = base.positions;
    for (std::size_t i = 0; i < rk.mesh.positions.size(); ++i) rk.mesh.positions[i] += target_deltas[k][i];
    raw.keys.push_back(std::move(rk));
  }
  raw.validate();
  return raw;
}

}  // namespace vdg
