// Compressed glTF exports (vdg/io/gltf_compress.h): the file's layout (KHR_mesh_quantization on one
// grid dequantised by the mesh node, EXT_meshopt_compression with a fallback buffer), vdg reading
// them back as the same model within the grid's error, and malformed compressed input refused with
// one line naming the file and the bufferView.
#include "vdg/io/gltf_compress.h"

#include <gtest/gtest.h>

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "gltf_compress_pass.h"
#include "gltf_test_decoder.h"
#include "support/error_of.h"
#include "support/test_meshes.h"
#include "vdg/anim/rig.h"
#include "vdg/io/gltf.h"
#include "vdg/io/gltf_export.h"
#include "vdg/io/manifest.h"
#include "vdg/io/model.h"
#include "vdg/viewdep/animated_model.h"
#include "vdg/viewdep/model.h"

namespace vdg {
namespace {

using testing::errorOf;

const std::string kSpot = VDG_SOURCE_DIR "/examples/spot/spot.vdg.json";
const std::string kWalk = VDG_SOURCE_DIR "/examples/walk/walker.vdg.json";
const std::string kWalkWorld = VDG_SOURCE_DIR "/examples/walk/walker-world.vdg.json";

// A normalized SHORT holds q / 32767: a position is off by half a step of the grid's scale.
constexpr double kShortSteps = 32767.0;
// A normalized BYTE normal is off by half of 1/127 per component.
constexpr double kNormalTol = 1.0 / 127.0;
// Float arithmetic of the blend on a model of unit size (kRoundTripTol of the float exports).
constexpr double kFloatTol = 1e-5;
// An animated model's float round trip (skin re-applied in floats; gltf_model_io_test.cpp).
constexpr double kAnimatedFloatTol = 1e-4;

std::vector<Eigen::Vector3d> testViews() {
  return {{0, 0, 1}, {1, 0.1, 0}, {0.6, 0.3, 0.7}, {-0.8, 0.2, -0.5}, {0.2, -0.9, 0.3}};
}

nlohmann::json fileJson(const std::string& path) {
  const std::string bytes = testing::readText(path);
  if (bytes.compare(0, 4, "glTF") == 0) return testing::decodeGlb(bytes).doc;
  return nlohmann::json::parse(bytes);
}

bool lists(const nlohmann::json& doc, const char* key, const char* ext) {
  return doc.contains(key) && std::find(doc[key].begin(), doc[key].end(), ext) != doc[key].end();
}

// Half a grid step (model units) of a quantised export: scale / 32767 / 2.
double halfStep(const nlohmann::json& doc) {
  const auto& dq = doc.at("meshes").at(0).at("extras").at("vdg").at("dequantize");
  return dq.at("scale").at(0).get<double>() / kShortSteps / 2.0;
}

GltfExportInput withCompression(GltfExportInput in, GltfCompression c) {
  in.compression = c;
  return in;
}

TEST(GltfCompress, NamesParse) {
  for (const GltfCompression c : {GltfCompression::kNone, GltfCompression::kQuantize, GltfCompression::kMeshopt})
    EXPECT_EQ(gltfCompressionFromName(gltfCompressionName(c)), c);
  EXPECT_FALSE(gltfCompressionFromName("draco"));
}

TEST(GltfCompress, QuantizedLayoutFollowsTheExtension) {
  testing::TempDir dir;
  const ViewDependentModel model = ViewDependentModel::build(loadManifest(kSpot));
  writeGltfExport(dir.file("q.glb"), withCompression(gltfExportInput(model), GltfCompression::kQuantize));
  const nlohmann::json doc = fileJson(dir.file("q.glb"));
  EXPECT_TRUE(lists(doc, "extensionsUsed", "KHR_mesh_quantization"));
  EXPECT_TRUE(lists(doc, "extensionsRequired", "KHR_mesh_quantization"));
  EXPECT_FALSE(lists(doc, "extensionsUsed", "EXT_meshopt_compression"));
  const auto& node = doc.at("nodes").at(0);
  const auto& dq = doc.at("meshes").at(0).at("extras").at("vdg").at("dequantize");
  EXPECT_EQ(node.at("translation"), dq.at("offset"));
  EXPECT_EQ(node.at("scale"), dq.at("scale"));
  EXPECT_EQ(dq.at("scale").at(0), dq.at("scale").at(2));  // one uniform grid
  const auto& prim = doc.at("meshes").at(0).at("primitives").at(0);
  const auto& pos = doc.at("accessors").at(prim.at("attributes").at("POSITION").get<std::size_t>());
  EXPECT_EQ(pos.at("componentType"), 5122);
  EXPECT_TRUE(pos.at("normalized").get<bool>());
  // The grid holds the base exactly: its extreme component reaches +-32767.
  double extreme = 0;
  for (int c = 0; c < 3; ++c)
    extreme = std::max({extreme, std::abs(pos.at("min").at(c).get<double>()), pos.at("max").at(c).get<double>()});
  EXPECT_LE(extreme, kShortSteps);
  const auto& normal = doc.at("accessors").at(prim.at("attributes").at("NORMAL").get<std::size_t>());
  EXPECT_EQ(normal.at("componentType"), 5120);
  for (const auto& t : prim.at("targets"))
    EXPECT_EQ(doc.at("accessors").at(t.at("POSITION").get<std::size_t>()).at("componentType"), 5122);
  // Every vertex attribute element on a 4-byte boundary.
  for (const auto& v : doc.at("bufferViews"))
    if (v.value("target", 0) == 34962) {
      EXPECT_EQ(v.value("byteStride", 4) % 4, 0);
    }
}

TEST(GltfCompress, MeshoptLayoutKeepsAFallbackBufferWithoutData) {
  testing::TempDir dir;
  const ViewDependentModel model = ViewDependentModel::build(loadManifest(kSpot));
  writeGltfExport(dir.file("m.gltf"), withCompression(gltfExportInput(model), GltfCompression::kMeshopt));
  const nlohmann::json doc = fileJson(dir.file("m.gltf"));
  EXPECT_TRUE(lists(doc, "extensionsRequired", "EXT_meshopt_compression"));
  EXPECT_TRUE(lists(doc, "extensionsRequired", "KHR_mesh_quantization"));
  ASSERT_EQ(doc.at("buffers").size(), 2u);
  EXPECT_FALSE(doc["buffers"][1].contains("uri"));
  EXPECT_TRUE(doc["buffers"][1]["extensions"]["EXT_meshopt_compression"]["fallback"].get<bool>());
  std::size_t compressed = 0, attributes = 0, triangles = 0;
  for (const auto& v : doc.at("bufferViews")) {
    if (!v.contains("extensions")) continue;
    const auto& e = v["extensions"]["EXT_meshopt_compression"];
    ++compressed;
    EXPECT_EQ(v.at("buffer"), 1);
    EXPECT_EQ(e.at("buffer"), 0);
    EXPECT_EQ(e.at("count").get<std::size_t>() * e.at("byteStride").get<std::size_t>(),
              v.at("byteLength").get<std::size_t>());
    attributes += e.at("mode") == "ATTRIBUTES";
    triangles += e.at("mode") == "TRIANGLES";
    if (e.at("mode") == "ATTRIBUTES") {
      EXPECT_EQ(e.at("byteStride").get<int>() % 4, 0);
    }
  }
  EXPECT_EQ(triangles, 1u);
  EXPECT_GE(attributes, 7u);  // POSITION, NORMAL, 5 targets
  EXPECT_GE(compressed, attributes + triangles);
}

// Reads `path` back and compares the model with `model` at every test view.
void expectStaticRoundTrip(const ViewDependentModel& model, const std::string& path, double tol) {
  const ViewDependentModel back = ViewDependentModel::build(loadModel(path));
  ASSERT_EQ(back.vertexCount(), model.vertexCount());
  std::vector<float> pa(model.vertexCount() * 3), pb(pa.size());
  for (const Eigen::Vector3d& view : testViews()) {
    ASSERT_TRUE(model.evaluate(view.normalized(), 0.0, pa));
    ASSERT_TRUE(back.evaluate(view.normalized(), 0.0, pb));
    double worst = 0;
    for (std::size_t i = 0; i < pa.size(); ++i) worst = std::max(worst, std::abs(double(pa[i]) - pb[i]));
    EXPECT_LE(worst, tol) << path << " view " << view.transpose();
  }
}

TEST(GltfCompress, StaticExportsReadBackWithinTheGrid) {
  testing::TempDir dir;
  const ViewDependentModel model = ViewDependentModel::build(loadManifest(kSpot));
  for (const GltfCompression c : {GltfCompression::kQuantize, GltfCompression::kMeshopt})
    for (const char* ext : {".glb", ".gltf"}) {
      const std::string path = dir.file(std::string(gltfCompressionName(c)) + ext);
      writeGltfExport(path, withCompression(gltfExportInput(model), c));
      // Base and key each within half a step: a blend (weights summing to at most 1) within two.
      expectStaticRoundTrip(model, path, 2 * halfStep(fileJson(path)) + kFloatTol);
    }
}

// The bytes of the images a .glb embeds in bufferViews.
std::size_t embeddedImageBytes(const std::string& path) {
  const nlohmann::json doc = fileJson(path);
  std::size_t n = 0;
  if (doc.contains("images"))
    for (const auto& image : doc["images"])
      if (image.contains("bufferView"))
        n += doc.at("bufferViews").at(image["bufferView"].get<std::size_t>()).at("byteLength").get<std::size_t>();
  return n;
}

// Compression shrinks the geometry; the embedded texture (a PNG, already compressed) is copied as it
// is, so the ratios hold for the file less its image bytes, which must be the same in all three.
TEST(GltfCompress, CompressedExportsAreSmaller) {
  testing::TempDir dir;
  const ViewDependentModel model = ViewDependentModel::build(loadManifest(kSpot));
  std::size_t bytes[3], images[3];
  for (const GltfCompression c : {GltfCompression::kNone, GltfCompression::kQuantize, GltfCompression::kMeshopt}) {
    const int k = static_cast<int>(c);
    const std::string path = dir.file(std::string(gltfCompressionName(c)) + ".glb");
    bytes[k] = writeGltfExport(path, withCompression(gltfExportInput(model), c)).bytes;
    images[k] = embeddedImageBytes(path);
    ASSERT_LT(images[k], bytes[k]);
  }
  EXPECT_GT(images[0], 0u);  // the textured Spot embeds its texture
  EXPECT_EQ(images[1], images[0]);
  EXPECT_EQ(images[2], images[0]);
  const std::size_t geometry[3] = {bytes[0] - images[0], bytes[1] - images[1], bytes[2] - images[2]};
  EXPECT_LT(geometry[1], geometry[0] * 2 / 3);
  EXPECT_LT(geometry[2], geometry[1] * 3 / 4);
}

TEST(GltfCompress, NormalsComeBackWithinAByteStep) {
  testing::TempDir dir;
  const ViewDependentModel model = ViewDependentModel::build(loadManifest(kSpot));
  writeGltfExport(dir.file("f.glb"), gltfExportInput(model));
  writeGltfExport(dir.file("m.glb"), withCompression(gltfExportInput(model), GltfCompression::kMeshopt));
  const RawRig a = readGltfRig(dir.file("f.glb")), b = readGltfRig(dir.file("m.glb"));
  ASSERT_EQ(a.mesh.normals.size(), b.mesh.normals.size());
  ASSERT_FALSE(a.mesh.normals.empty());
  double worst = 0;
  for (std::size_t i = 0; i < a.mesh.normals.size(); ++i)
    worst = std::max(worst, std::abs(double(a.mesh.normals[i]) - b.mesh.normals[i]));
  EXPECT_LE(worst, kNormalTol);
  // A generic reader places the mesh by its node: the dequantised base is the model's base.
  const TriMesh placed = readGltfMesh(dir.file("m.glb"));
  const double tol = halfStep(fileJson(dir.file("m.glb"))) + kFloatTol;
  for (std::size_t i = 0; i < placed.positions.size(); ++i)
    ASSERT_NEAR(placed.positions[i], model.base().positions[i], tol) << i;
}

// Half a step of the grid of `in` as the writer chooses it: the largest of the base's half extents
// and of the targets' delta components, / 32767 / 2 (vdg/io/gltf_compress.h).
double gridHalfStep(const GltfExportInput& in) {
  double s = 0;
  for (int c = 0; c < 3; ++c) {
    double lo = INFINITY, hi = -INFINITY;
    for (std::size_t i = c; i < in.base.positions.size(); i += 3)
      lo = std::min<double>(lo, in.base.positions[i]), hi = std::max<double>(hi, in.base.positions[i]);
    s = std::max(s, (hi - lo) / 2);
  }
  for (const GltfTarget& t : in.targets)
    for (float x : t.deltas) s = std::max(s, std::abs(double(x)));
  if (in.base_animation)
    for (const auto& f : in.base_animation->frame_deltas)
      for (float x : f) s = std::max(s, std::abs(double(x)));
  return s / kShortSteps / 2;
}

void expectAnimatedRoundTrip(const std::string& manifest, const std::string& path, GltfCompression c, bool skinned) {
  const RawViewDependentModel raw = loadManifest(manifest);
  const AnimatedViewDependentModel model = AnimatedViewDependentModel::build(raw);
  std::optional<RawRig> rig;
  if (!raw.base_animation->gltf.empty()) rig = readBaseRig(raw);
  const GltfExportInput input = withCompression(gltfExportInput(model, raw, rig ? &*rig : nullptr), c);
  writeGltfExport(path, input);
  const nlohmann::json doc = fileJson(path);
  const auto& vdg = doc.at("meshes").at(0).at("extras").at("vdg");
  const auto& prim = doc.at("meshes").at(0).at("primitives").at(0);
  EXPECT_EQ(doc.at("accessors").at(prim.at("attributes").at("POSITION").get<std::size_t>()).at("componentType"), 5122);
  // A skinned mesh ignores its node's transform: the dequantisation is folded into the inverse
  // bind matrices instead, and the model space stays the file's (no dequantize).
  EXPECT_EQ(vdg.contains("dequantize"), !skinned) << path;
  if (!skinned) {
    EXPECT_NEAR(halfStep(doc), gridHalfStep(input), 1e-12);
  }
  // Frame k of a "frames" base is POSITION plus its frame target, a key adds its own: three half
  // steps; skinning turns the error vector (its largest component grows by sqrt(3) at most).
  const double tol = 3 * (skinned ? std::sqrt(3.0) : 1.0) * gridHalfStep(input) + kAnimatedFloatTol;
  const AnimatedViewDependentModel back = AnimatedViewDependentModel::build(loadModel(path));
  ASSERT_EQ(back.frameCount(), model.frameCount());
  std::vector<float> pa(model.vertexCount() * 3), pb(pa.size());
  for (int f : {0, 10, 23, 30})
    for (const Eigen::Vector3d& view : testViews()) {
      ASSERT_TRUE(model.evaluate(f, view.normalized(), 0.0, pa));
      ASSERT_TRUE(back.evaluate(f, view.normalized(), 0.0, pb));
      double worst = 0;
      for (std::size_t i = 0; i < pa.size(); ++i) worst = std::max(worst, std::abs(double(pa[i]) - pb[i]));
      ASSERT_LE(worst, tol) << path << " frame " << f << " view " << view.transpose();
    }
}

TEST(GltfCompress, AnimatedExportsReadBackWithinTheGrid) {
  testing::TempDir dir;
  expectAnimatedRoundTrip(kWalk, dir.file("skin-q.glb"), GltfCompression::kQuantize, true);
  expectAnimatedRoundTrip(kWalk, dir.file("skin-m.gltf"), GltfCompression::kMeshopt, true);
  expectAnimatedRoundTrip(kWalkWorld, dir.file("frames-m.glb"), GltfCompression::kMeshopt, false);
}

// A document as the materials work writes it: two primitives with their own POSITION, indices
// (8- and 16-bit), TEXCOORD_0 (one in [0, 1], one not), the custom `_VDG_VERTEX` attribute in the
// exporter's two layouts (unsigned shorts with byteStride 4, floats above 65536 model vertices: glTF
// 2.0 section 3.7.2.1 allows no UNSIGNED_INT there), one morph target each, and an image in a
// bufferView.
struct Handmade {
  nlohmann::ordered_json doc;
  std::string bin;
  std::vector<float> positions;  // both primitives' POSITION, in order
  std::string image = std::string("\x89PNG\r\n\x1a\n-not-really-", 21);

  int add(const void* bytes, std::size_t size, int target) {
    bin.resize((bin.size() + 3) & ~std::size_t{3}, '\0');
    nlohmann::ordered_json v = {{"buffer", 0}, {"byteOffset", bin.size()}, {"byteLength", size}};
    if (target) v["target"] = target;
    bin.append(static_cast<const char*>(bytes), size);
    doc["bufferViews"].push_back(v);
    return static_cast<int>(doc["bufferViews"].size()) - 1;
  }
  int accessor(int view, int component, std::size_t count, const char* type) {
    doc["accessors"].push_back({{"bufferView", view}, {"componentType", component}, {"count", count}, {"type", type}});
    return static_cast<int>(doc["accessors"].size()) - 1;
  }
  int floats(const std::vector<float>& v, const char* type, int n, bool bounds) {
    const int a = accessor(add(v.data(), v.size() * 4, 34962), 5126, v.size() / n, type);
    if (bounds) {
      std::vector<float> lo(n, 1e30f), hi(n, -1e30f);
      for (std::size_t i = 0; i < v.size(); ++i)
        lo[i % n] = std::min(lo[i % n], v[i]), hi[i % n] = std::max(hi[i % n], v[i]);
      doc["accessors"][a]["min"] = lo;
      doc["accessors"][a]["max"] = hi;
    }
    return a;
  }

  Handmade() {
    doc = {{"asset", {{"version", "2.0"}}},
           {"scene", 0},
           {"scenes", {{{"nodes", {0}}}}},
           {"nodes", {{{"mesh", 0}}}},
           {"bufferViews", nlohmann::ordered_json::array()},
           {"accessors", nlohmann::ordered_json::array()}};
    nlohmann::ordered_json prims = nlohmann::ordered_json::array();
    const std::vector<std::vector<float>> pos = {{0, 0, 0, 2, 0, 0, 0, 1, 0}, {2, 0, 0, 2, 1, 0.5f, 0, 1, 0}};
    const std::vector<std::vector<float>> uvs = {{0, 0, 1, 0, 0, 1}, {0, 0, 1.5f, 0, 0, 1}};
    const std::vector<float> delta = {0, 0, 0.25f, 0, 0, 0, 0, -0.5f, 0};
    const std::uint8_t i8[3] = {0, 1, 2};
    const std::uint16_t i16[3] = {0, 1, 2};
    for (int p = 0; p < 2; ++p) {
      positions.insert(positions.end(), pos[p].begin(), pos[p].end());
      // Each exported vertex its own model vertex (0..5): the reader welds nothing.
      const std::uint16_t short_ids[6] = {0, 0, 1, 0, 2, 0};
      const float float_ids[3] = {3.0f, 4.0f, 5.0f};
      int ids = 0;
      if (p == 0) {
        ids = accessor(add(short_ids, sizeof short_ids, 34962), 5123, 3, "SCALAR");
        doc["bufferViews"][doc["accessors"][ids]["bufferView"].get<std::size_t>()]["byteStride"] = 4;
      } else {
        ids = accessor(add(float_ids, sizeof float_ids, 34962), 5126, 3, "SCALAR");
      }
      nlohmann::ordered_json attributes = {{"POSITION", floats(pos[p], "VEC3", 3, true)},
                                           {"TEXCOORD_0", floats(uvs[p], "VEC2", 2, false)},
                                           {"_VDG_VERTEX", ids}};
      const int indices =
          p == 0 ? accessor(add(i8, 3, 34963), 5121, 3, "SCALAR") : accessor(add(i16, 6, 34963), 5123, 3, "SCALAR");
      prims.push_back({{"attributes", attributes},
                       {"indices", indices},
                       {"targets", {{{"POSITION", floats(delta, "VEC3", 3, true)}}}}});
    }
    doc["meshes"] = {{{"primitives", prims}, {"weights", {0.0}}}};
    doc["images"] = {{{"bufferView", add(image.data(), image.size(), 0)}, {"mimeType", "image/png"}}};
    bin.resize((bin.size() + 3) & ~std::size_t{3}, '\0');
    doc["buffers"] = {{{"byteLength", bin.size()}}};
  }
};

std::string glbOf(const nlohmann::ordered_json& doc, const std::string& bin) {
  std::string json = doc.dump();
  json.resize((json.size() + 3) & ~std::size_t{3}, ' ');
  std::string out;
  const auto u32 = [&](std::uint32_t x) { out.append(reinterpret_cast<const char*>(&x), 4); };
  u32(0x46546C67);
  u32(2);
  u32(static_cast<std::uint32_t>(28 + json.size() + bin.size()));
  u32(static_cast<std::uint32_t>(json.size()));
  u32(0x4E4F534A);
  out += json;
  u32(static_cast<std::uint32_t>(bin.size()));
  u32(0x004E4942);
  return out + bin;
}

TEST(GltfCompress, SeveralPrimitivesCustomAttributesAndImages) {
  testing::TempDir dir;
  for (const GltfCompression c : {GltfCompression::kQuantize, GltfCompression::kMeshopt}) {
    Handmade h;
    nlohmann::ordered_json doc = h.doc;
    std::string bin = h.bin;
    compressGltf(doc, bin, c, "hand.glb");
    const std::string path = dir.file(std::string(gltfCompressionName(c)) + ".glb");
    testing::writeText(path, glbOf(doc, bin));
    // Placed by its node, the mesh is where the float one is, within half a step.
    const double scale = doc["nodes"][0]["scale"][0].get<double>();
    EXPECT_EQ(scale, 1.0);  // the largest half extent (x: 0..2)
    const TriMesh placed = readGltfMesh(path);
    ASSERT_EQ(placed.positions.size(), h.positions.size());
    for (std::size_t i = 0; i < h.positions.size(); ++i)
      EXPECT_NEAR(placed.positions[i], h.positions[i], scale / kShortSteps / 2 + kFloatTol) << i;
    const auto& prims = doc["meshes"][0]["primitives"];
    for (int p = 0; p < 2; ++p) {
      const auto& custom = doc["accessors"][prims[p]["attributes"]["_VDG_VERTEX"].get<std::size_t>()];
      EXPECT_EQ(custom["componentType"], p == 0 ? 5123 : 5126);  // kept in a type the spec allows
      EXPECT_FALSE(custom.contains("normalized"));
      if (p == 0) {
        EXPECT_EQ(doc["bufferViews"][custom["bufferView"].get<std::size_t>()]["byteStride"], 4);
      }
      const auto& uv = doc["accessors"][prims[p]["attributes"]["TEXCOORD_0"].get<std::size_t>()];
      EXPECT_EQ(uv["componentType"], p == 0 ? 5123 : 5126);  // 1.5 does not fit a normalized value
    }
    // The image's bytes are where its bufferView says, untouched and uncompressed.
    const auto& view = doc["bufferViews"][doc["images"][0]["bufferView"].get<std::size_t>()];
    EXPECT_FALSE(view.contains("extensions"));
    EXPECT_EQ(bin.substr(view["byteOffset"].get<std::size_t>(), view["byteLength"].get<std::size_t>()), h.image);
    if (c == GltfCompression::kQuantize) {
      // Without meshopt the custom attribute's bytes are read as they are.
      const auto& custom = doc["accessors"][prims[1]["attributes"]["_VDG_VERTEX"].get<std::size_t>()];
      const auto& cv = doc["bufferViews"][custom["bufferView"].get<std::size_t>()];
      float ids[3];
      std::memcpy(ids, bin.data() + cv["byteOffset"].get<std::size_t>(), 12);
      EXPECT_EQ(ids[0], 3.0f);
      EXPECT_EQ(ids[2], 5.0f);
    }
  }
}

// The meshopt .gltf of a small model with its JSON edited by `edit`, read by vdg: the error.
std::string editedMeshoptError(const std::function<void(nlohmann::json&)>& edit);

// The first bufferView of that file in mode ATTRIBUTES and the one in mode TRIANGLES (the exporter
// writes the shared vertex attributes first, then each material primitive's indices).
struct MeshoptViews {
  std::size_t attributes = 0, triangles = 0;
  bool found_attributes = false, found_triangles = false;
};

MeshoptViews meshoptViews() {
  MeshoptViews found;
  (void)editedMeshoptError([&](nlohmann::json& d) {
    for (std::size_t i = 0; i < d["bufferViews"].size(); ++i) {
      if (!d["bufferViews"][i].contains("extensions")) continue;
      const auto& mode = d["bufferViews"][i]["extensions"]["EXT_meshopt_compression"]["mode"];
      if (mode == "ATTRIBUTES" && !found.found_attributes) found.attributes = i, found.found_attributes = true;
      if (mode == "TRIANGLES" && !found.found_triangles) found.triangles = i, found.found_triangles = true;
    }
    d["extensionsRequired"].push_back("KHR_draco_mesh_compression");  // editedMeshoptError wants an error
  });
  return found;
}

std::string editedMeshoptError(const std::function<void(nlohmann::json&)>& edit) {
  testing::TempDir dir;
  RawViewDependentModel raw;
  raw.base = testing::uvSphere(4, 6);
  RawKey key;
  key.name = "front";
  key.mesh = raw.base;
  key.mesh.positions[0] += 0.25f;
  key.view = {0, 0, 1};
  raw.keys.push_back(key);
  raw.resolveViews();
  const ViewDependentModel model = ViewDependentModel::build(raw);
  writeGltfExport(dir.file("m.gltf"), withCompression(gltfExportInput(model), GltfCompression::kMeshopt));
  nlohmann::json doc = fileJson(dir.file("m.gltf"));
  edit(doc);
  testing::writeText(dir.file("m.gltf"), doc.dump());
  const std::string e = errorOf([&] { (void)loadModel(dir.file("m.gltf")); });
  return e.substr(e.find("m.gltf"));
}

nlohmann::json& ext(nlohmann::json& doc, std::size_t view) {
  return doc["bufferViews"][view]["extensions"]["EXT_meshopt_compression"];
}

// `error` starts with `head` (the decoder's own code may follow).
::testing::AssertionResult startsWith(const std::string& error, const std::string& head) {
  if (error.compare(0, head.size(), head) == 0) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "'" << error << "' does not start with '" << head << "'";
}

TEST(GltfCompress, MalformedMeshoptIsOneLineNamingTheBufferView) {
  const MeshoptViews views = meshoptViews();
  ASSERT_TRUE(views.found_attributes);
  ASSERT_TRUE(views.found_triangles);
  const std::size_t a = views.attributes, t = views.triangles;
  const std::string e = "m.gltf: bufferViews[" + std::to_string(t) + "]: EXT_meshopt_compression: ";
  const std::string ea = "m.gltf: bufferViews[" + std::to_string(a) + "]: EXT_meshopt_compression: ";
  EXPECT_TRUE(startsWith(editedMeshoptError([&](nlohmann::json& d) { ext(d, a)["byteLength"] = 3; }),
                         ea + "the ATTRIBUTES data does not decode (meshoptimizer error"));
  EXPECT_TRUE(startsWith(editedMeshoptError([&](nlohmann::json& d) { ext(d, t)["byteLength"] = 3; }),
                         e + "the TRIANGLES data does not decode (meshoptimizer error"));
  EXPECT_TRUE(
      startsWith(editedMeshoptError([&](nlohmann::json& d) { ext(d, t)["count"] = ext(d, t)["count"].get<int>() + 3; }),
                 e + "count "));
  EXPECT_EQ(editedMeshoptError([&](nlohmann::json& d) { ext(d, t)["mode"] = "LINES"; }),
            e + "mode 'LINES' is not ATTRIBUTES, TRIANGLES or INDICES");
  EXPECT_EQ(editedMeshoptError([&](nlohmann::json& d) { ext(d, a)["byteStride"] = 6; }),
            ea + "byteStride 6 is not allowed in mode ATTRIBUTES (a multiple of 4 up to 256)");
  EXPECT_TRUE(startsWith(editedMeshoptError([&](nlohmann::json& d) { ext(d, t)["byteOffset"] = 1 << 30; }),
                         e + "bytes 1073741824 + "));
  EXPECT_EQ(editedMeshoptError([&](nlohmann::json& d) { ext(d, t)["buffer"] = 1; }),
            e + "buffer 1 is a fallback buffer without data");
  EXPECT_EQ(editedMeshoptError([&](nlohmann::json& d) { ext(d, t)["filter"] = "QUATERNION"; }),
            e + "filter 'QUATERNION' does not apply to mode TRIANGLES, byteStride 2");
  EXPECT_EQ(editedMeshoptError([&](nlohmann::json& d) { d["bufferViews"][t].erase("extensions"); }),
            "m.gltf: bufferViews[" + std::to_string(t) +
                "]: lies in fallback buffer 1, which has no data, and is not compressed");
  EXPECT_EQ(
      editedMeshoptError([](nlohmann::json& d) { d["extensionsRequired"].push_back("KHR_draco_mesh_compression"); }),
      "m.gltf: extensionsRequired: 'KHR_draco_mesh_compression' is an extension vdg does not implement");
}

}  // namespace
}  // namespace vdg
