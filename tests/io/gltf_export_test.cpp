// glTF export: the file's structure (decoded by an independent reader, gltf_test_decoder.h), the
// round trip through mesh.extras.vdg, sparse targets, uvs, the camera bake, and every bad input.
#include "vdg/io/gltf_export.h"

#include "vdg/io/camera_json.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <functional>
#include <numbers>

#include "gltf_test_decoder.h"
#include "support/error_of.h"
#include "support/test_meshes.h"
#include "vdg/io/gltf.h"
#include "vdg/io/image_file.h"

namespace vdg {
namespace {

using testing::DecodedGltf;
using testing::errorOf;
using testing::readAccessor;
using testing::toFloats;

// The issue's round-trip bound on positions; float storage of deltas loses far less.
constexpr double kRoundTripTol = 1e-4;
// Baked weights are floats: a blend of float weights and float deltas.
constexpr double kBakeTol = 1e-5;
constexpr double kQuatTol = 1e-6;

// A sphere with keys that push different regions outwards; `moved` limits a key to a few vertices.
RawViewDependentModel sphereModel(Uncovered uncovered = Uncovered::Base, double sharpness = 1.0) {
  RawViewDependentModel raw;
  raw.base = testing::uvSphere(8, 12);
  const std::size_t n = raw.base.vertexCount();
  const auto key = [&](const std::string& name, const Eigen::Vector3d& dir, double amount) {
    RawKey k;
    k.name = name;
    k.mesh = raw.base;
    k.view = dir;
    for (std::size_t v = 0; v < n; ++v) {
      Eigen::Vector3d p(k.mesh.positions[v * 3], k.mesh.positions[v * 3 + 1], k.mesh.positions[v * 3 + 2]);
      const double s = std::max(0.0, p.dot(dir.normalized()));
      p *= 1.0 + amount * s * s;
      for (int c = 0; c < 3; ++c) k.mesh.positions[v * 3 + c] = static_cast<float>(p[c]);
    }
    return k;
  };
  raw.keys.push_back(key("front", {0, 0, 1}, 0.5));
  raw.keys.push_back(key("side", {1, 0.2, 0}, 0.3));
  Camera cam;
  cam.eye = {0.1, 4, 0.3};
  cam.target = {0, 0, 0};
  cam.up = {0, 0, -1};
  cam.fov_deg = 35;
  RawKey top = key("top", {0, 1, 0}, 0.4);
  top.camera = cam;
  raw.keys.push_back(top);
  raw.sharpness = sharpness;
  raw.sphere.uncovered = uncovered;
  raw.center = Eigen::Vector3d(0.01, -0.02, 0.0);
  raw.resolveViews();
  return raw;
}

// Base mesh and target deltas as decoded from the file, and the mesh's extras as text.
struct DecodedModel {
  TriMesh base;
  std::vector<std::vector<float>> deltas;
  std::string extras;
};

DecodedModel decodeModel(const DecodedGltf& g) {
  DecodedModel out;
  const auto& prim = g.doc.at("meshes").at(0).at("primitives").at(0);
  out.base.positions = toFloats(readAccessor(g, prim.at("attributes").at("POSITION")));
  for (double i : readAccessor(g, prim.at("indices"))) out.base.triangles.push_back(static_cast<std::int32_t>(i));
  if (prim.contains("targets"))
    for (const auto& t : prim.at("targets")) out.deltas.push_back(toFloats(readAccessor(g, t.at("POSITION"))));
  out.extras = g.doc.at("meshes").at(0).at("extras").dump();
  return out;
}

std::vector<Eigen::Vector3d> testViews() {
  return {{0, 0, 1}, {1, 0.2, 0}, {0.3, 0.9, 0.2}, {0.5, 0.5, 0.7}, {-1, 0.1, -0.3}, {0, -1, 0.01}, {0.7, -0.2, 0.6}};
}

void expectSameEvaluation(const ViewDependentModel& a, const ViewDependentModel& b, double tol) {
  ASSERT_EQ(a.vertexCount(), b.vertexCount());
  std::vector<float> pa(a.vertexCount() * 3), pb(pa.size());
  for (const Eigen::Vector3d& view : testViews()) {
    ASSERT_TRUE(a.evaluate(view, 0.0, pa));
    ASSERT_TRUE(b.evaluate(view, 0.0, pb));
    for (std::size_t i = 0; i < pa.size(); ++i)
      ASSERT_NEAR(pa[i], pb[i], tol) << "view " << view.transpose() << " i " << i;
  }
}

ViewDependentModel roundTrip(const DecodedGltf& g) {
  const DecodedModel d = decodeModel(g);
  return ViewDependentModel::build(rawModelFromGltfExtras(d.extras, d.base, d.deltas, "test.glb"));
}

TEST(GltfExport, GlbHasTheSpecifiedLayout) {
  const auto model = ViewDependentModel::build(sphereModel());
  GltfExportReport report;
  const std::string bytes = gltfToGlb(gltfExportInput(model), "t.glb", &report);
  EXPECT_EQ(bytes.size() % 4, 0u);
  EXPECT_EQ(report.bytes, bytes.size());
  const DecodedGltf g = testing::decodeGlb(bytes);
  EXPECT_EQ(g.doc.at("asset").at("version"), "2.0");
  EXPECT_EQ(g.doc.at("buffers").at(0).at("byteLength").get<std::size_t>(), g.bin.size());
  EXPECT_FALSE(g.doc.at("buffers").at(0).contains("uri"));
  for (const auto& view : g.doc.at("bufferViews")) {
    EXPECT_EQ(view.at("byteOffset").get<std::size_t>() % 4, 0u);
    EXPECT_LE(view.at("byteOffset").get<std::size_t>() + view.at("byteLength").get<std::size_t>(), g.bin.size());
  }
  const auto& mesh = g.doc.at("meshes").at(0);
  const auto& prim = mesh.at("primitives").at(0);
  EXPECT_EQ(prim.at("targets").size(), 3u);
  EXPECT_EQ(mesh.at("weights"), nlohmann::json({0.0, 0.0, 0.0}));
  EXPECT_EQ(mesh.at("extras").at("targetNames"), nlohmann::json({"front", "side", "top"}));
  EXPECT_EQ(g.doc.at("accessors").at(prim.at("indices").get<int>()).at("componentType"), 5123);
  // The base decodes to the model's base exactly.
  const DecodedModel d = decodeModel(g);
  EXPECT_EQ(d.base.positions, model.base().positions);
  EXPECT_EQ(d.base.triangles, model.base().triangles);
  // POSITION accessors carry exact min/max (the validator checks them against the data).
  std::vector<int> position_accessors{prim.at("attributes").at("POSITION").get<int>()};
  for (const auto& t : prim.at("targets")) position_accessors.push_back(t.at("POSITION"));
  for (int a : position_accessors) {
    const auto values = readAccessor(g, a);
    const auto& acc = g.doc.at("accessors").at(a);
    for (int c = 0; c < 3; ++c) {
      double lo = values[c], hi = values[c];
      for (std::size_t i = c; i < values.size(); i += 3) lo = std::min(lo, values[i]), hi = std::max(hi, values[i]);
      EXPECT_EQ(acc.at("min").at(c).get<double>(), lo);
      EXPECT_EQ(acc.at("max").at(c).get<double>(), hi);
    }
  }
  // NORMAL: unit vectors.
  const auto normals = readAccessor(g, prim.at("attributes").at("NORMAL"));
  for (std::size_t v = 0; v < normals.size() / 3; ++v)
    EXPECT_NEAR(Eigen::Vector3d(normals[v * 3], normals[v * 3 + 1], normals[v * 3 + 2]).norm(), 1.0, 1e-6);
}

TEST(GltfExport, RoundTripEvaluatesLikeTheModel) {
  for (const Uncovered mode : {Uncovered::Base, Uncovered::Cosine, Uncovered::Cosine2}) {
    const auto model = ViewDependentModel::build(sphereModel(mode, 2.5));
    const auto back = roundTrip(testing::decodeGlb(gltfToGlb(gltfExportInput(model), "t.glb")));
    EXPECT_EQ(back.sphere().settings().uncovered, mode);
    EXPECT_EQ(back.sharpness(), 2.5);
    EXPECT_EQ(back.center(), model.center());
    EXPECT_EQ(back.keyName(1), "side");
    ASSERT_TRUE(back.keyCamera(2).has_value());
    EXPECT_EQ(back.keyCamera(2)->eye, model.keyCamera(2)->eye);
    // Views are written as the sphere holds them (unit); normalising again moves them by an ulp at most.
    EXPECT_LT((back.keyView(2) - model.keyView(2)).norm(), 1e-15);
    expectSameEvaluation(model, back, kRoundTripTol);
  }
}

TEST(GltfExport, GltfWithExternalBufferRoundTrips) {
  testing::TempDir dir;
  const auto model = ViewDependentModel::build(sphereModel());
  const std::string path = dir.file("out.gltf");
  const GltfExportReport report = writeGltfExport(path, gltfExportInput(model));
  ASSERT_TRUE(std::filesystem::exists(dir.file("out.bin")));
  EXPECT_FALSE(std::filesystem::exists(dir.file(".vdg-journal")));
  const DecodedGltf g = testing::decodeGltfFile(path);
  EXPECT_EQ(g.doc.at("buffers").at(0).at("uri"), "out.bin");
  EXPECT_EQ(g.doc.at("buffers").at(0).at("byteLength").get<std::size_t>(), g.bin.size());
  EXPECT_EQ(report.bytes, std::filesystem::file_size(path) + g.bin.size());
  expectSameEvaluation(model, roundTrip(g), kRoundTripTol);
  // A .glb of the same model holds the same buffer.
  writeGltfExport(dir.file("out.glb"), gltfExportInput(model));
  EXPECT_EQ(testing::decodeGlb(testing::readText(dir.file("out.glb"))).bin, g.bin);
}

TEST(GltfExport, TargetsAreSparseExactlyWhenThatIsSmaller) {
  RawViewDependentModel raw = sphereModel();
  // "front" moves one vertex only; "side" (every vertex with a positive x) and "top" stay as they are.
  raw.keys[0].mesh = raw.base;
  raw.keys[0].mesh.positions[3 * 5 + 1] += 0.25f;
  RawKey still = raw.keys[1];
  still.name = "still";
  still.mesh = raw.base;
  still.view = {0, 0, -1};
  raw.keys.push_back(still);
  const auto model = ViewDependentModel::build(raw);
  GltfExportInput input = gltfExportInput(model);
  // A target that moves every vertex must stay dense.
  for (float& d : input.targets[1].deltas) d += 0.01f;
  GltfExportReport report;
  const DecodedGltf g = testing::decodeGlb(gltfToGlb(input, "t.glb", &report));
  const auto& targets = g.doc.at("meshes").at(0).at("primitives").at(0).at("targets");
  const auto accessor = [&](int t) { return g.doc.at("accessors").at(targets.at(t).at("POSITION").get<int>()); };
  EXPECT_TRUE(accessor(0).contains("sparse"));
  EXPECT_EQ(accessor(0).at("sparse").at("count"), 1);
  EXPECT_EQ(accessor(0).at("sparse").at("indices").at("componentType"), 5121);  // 86 vertices fit a byte
  EXPECT_FALSE(accessor(0).contains("bufferView"));
  EXPECT_FALSE(accessor(1).contains("sparse"));
  EXPECT_TRUE(accessor(3).contains("sparse"));  // moves nothing: one zero entry
  EXPECT_EQ(accessor(3).at("min"), nlohmann::json({0.0, 0.0, 0.0}));
  EXPECT_EQ(report.sparse_targets, 3u);  // front, top (about half the sphere), still
  // Decoded deltas equal the input's, sparse or dense.
  for (std::size_t t = 0; t < input.targets.size(); ++t)
    EXPECT_EQ(toFloats(readAccessor(g, targets.at(t).at("POSITION"))), input.targets[t].deltas) << t;
  // The sparse target's bounds include the zeros of the vertices it leaves alone.
  EXPECT_EQ(accessor(0).at("min"), nlohmann::json({0.0, 0.0, 0.0}));
  EXPECT_EQ(accessor(0).at("max").at(1).get<double>(), static_cast<double>(input.targets[0].deltas[3 * 5 + 1]));
}

TEST(GltfExport, LargeMeshesUseUnsignedIntIndicesAndShortSparseIndices) {
  // 70000 unshared vertices: indices past 65534 need UNSIGNED_INT.
  GltfExportInput input;
  constexpr int kTris = 70002 / 3;
  for (int t = 0; t < kTris; ++t) {
    const float x = static_cast<float>(t);
    input.base.positions.insert(input.base.positions.end(), {x, 0, 0, x + 1, 0, 0, x, 1, 0});
    input.base.triangles.insert(input.base.triangles.end(), {3 * t, 3 * t + 1, 3 * t + 2});
  }
  GltfTarget target;
  target.name = "k";
  target.view = {0, 0, 1};
  target.deltas.assign(input.base.positions.size(), 0.0f);
  target.deltas[3 * 69000 + 2] = 1.0f;
  input.targets.push_back(target);
  const DecodedGltf g = testing::decodeGlb(gltfToGlb(input, "t.glb"));
  const auto& prim = g.doc.at("meshes").at(0).at("primitives").at(0);
  EXPECT_EQ(g.doc.at("accessors").at(prim.at("indices").get<int>()).at("componentType"), 5125);
  const auto idx = readAccessor(g, prim.at("indices"));
  EXPECT_EQ(idx.back(), 3.0 * kTris - 1);
  const auto& t = g.doc.at("accessors").at(prim.at("targets").at(0).at("POSITION").get<int>());
  EXPECT_EQ(t.at("sparse").at("indices").at("componentType"), 5125);  // 70002 vertices need 32 bits
  EXPECT_EQ(toFloats(readAccessor(g, prim.at("targets").at(0).at("POSITION"))), target.deltas);
}

// A unit square of two triangles with one uv per vertex, and a target moving vertex 1.
GltfExportInput squareInput() {
  GltfExportInput input;
  input.base.positions = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0};
  input.base.triangles = {0, 1, 2, 2, 1, 3};
  input.base.uvs = {0, 0, 1, 0, 0, 1, 1, 1};
  input.base.uv_triangles = {0, 1, 2, 2, 1, 3};
  GltfTarget target;
  target.name = "k";
  target.view = {0, 0, 1};
  target.deltas = {0, 0, 0, 0, 0, 0.5f, 0, 0, 0, 0, 0, 0};
  input.targets.push_back(target);
  return input;
}

TEST(GltfExport, UvsAreWrittenAndSeamsSplitWithTheSameDeltas) {
  GltfExportInput input = squareInput();
  GltfExportReport report;
  DecodedGltf g = testing::decodeGlb(gltfToGlb(input, "t.glb", &report));
  EXPECT_TRUE(report.uvs_written);
  EXPECT_EQ(report.split_vertices, 0u);
  const auto& attrs = g.doc.at("meshes").at(0).at("primitives").at(0).at("attributes");
  // glTF's uv origin is the top-left corner: v becomes 1 - v.
  EXPECT_EQ(readAccessor(g, attrs.at("TEXCOORD_0")), (std::vector<double>{0, 1, 1, 1, 0, 0, 1, 0}));
  EXPECT_EQ(testing::readVertexIds(g, g.doc.at("meshes").at(0).at("primitives").at(0)), (std::vector<int>{0, 1, 2, 3}));
  // A seam: vertex 1 has uv (1, 0) in the first triangle and (0.5, 0.5) in the second; it is split
  // into exported vertex 4 with vertex 1's position and target delta.
  input.base.uvs.insert(input.base.uvs.end(), {0.5f, 0.5f});
  input.base.uv_triangles = {0, 1, 2, 2, 4, 3};
  g = testing::decodeGlb(gltfToGlb(input, "t.glb", &report));
  EXPECT_TRUE(report.uvs_written);
  EXPECT_EQ(report.split_vertices, 1u);
  const auto& prim = g.doc.at("meshes").at(0).at("primitives").at(0);
  EXPECT_EQ(readAccessor(g, prim.at("attributes").at("TEXCOORD_0")),
            (std::vector<double>{0, 1, 1, 1, 0, 0, 1, 0, 0.5, 0.5}));
  EXPECT_EQ(readAccessor(g, prim.at("indices")), (std::vector<double>{0, 1, 2, 2, 4, 3}));
  EXPECT_EQ(testing::readVertexIds(g, prim), (std::vector<int>{0, 1, 2, 3, 1}));
  const auto positions = readAccessor(g, prim.at("attributes").at("POSITION"));
  const auto deltas = readAccessor(g, prim.at("targets").at(0).at("POSITION"));
  ASSERT_EQ(positions.size(), 15u);
  for (int c = 0; c < 3; ++c) {
    EXPECT_EQ(positions[12 + c], positions[3 + c]);
    EXPECT_EQ(deltas[12 + c], deltas[3 + c]);
  }
  // Read back: welded to the model's 4 vertices in order, each corner keeping its uv.
  const RawRig rig = parseGltfRig(gltfToGlb(input, "t.glb"), "t.glb");
  EXPECT_EQ(rig.mesh.positions, input.base.positions);
  EXPECT_EQ(rig.mesh.triangles, input.base.triangles);
  ASSERT_EQ(rig.target_positions.size(), 1u);
  EXPECT_EQ(rig.target_positions[0], input.targets[0].deltas);
  for (std::size_t c = 0; c < 6; ++c)
    for (int k = 0; k < 2; ++k)
      EXPECT_NEAR(rig.mesh.uvs[static_cast<std::size_t>(rig.mesh.uv_triangles[c]) * 2 + k],
                  input.base.uvs[static_cast<std::size_t>(input.base.uv_triangles[c]) * 2 + k], 1e-7)
          << "corner " << c;
}

TEST(GltfExport, BaseFrameTargetsAreSplitLikeTheKeys) {
  GltfExportInput input = squareInput();
  input.base.uvs.insert(input.base.uvs.end(), {0.5f, 0.5f});
  input.base.uv_triangles = {0, 1, 2, 2, 4, 3};
  GltfBaseAnimation ba;
  ba.frame_count = 2;
  ba.frame_deltas = {{0, 0, 0, 0.25f, 0, 0, 0, 0, 0, 0, 0, 0}};  // frame 1 moves vertex 1
  input.base_animation = ba;
  input.offsets = OffsetSpace::kWorld;
  // An animated input carries its sphere (extras v2): the one key view, keyed at frame 0.
  const Eigen::Vector3d key_view = input.targets[0].view;
  input.view_sphere = gltfViewSphere(ViewSphere::build(std::span(&key_view, 1)));
  input.view_sphere->time = {GltfViewTime{{0}, {0.0}}};
  const DecodedGltf g = testing::decodeGlb(gltfToGlb(input, "t.glb"));
  const auto& prim = g.doc.at("meshes").at(0).at("primitives").at(0);
  ASSERT_EQ(prim.at("targets").size(), 2u);  // the key, then base frame 1
  const auto frame = readAccessor(g, prim.at("targets").at(1).at("POSITION"));
  ASSERT_EQ(frame.size(), 15u);
  for (int c = 0; c < 3; ++c) EXPECT_EQ(frame[12 + c], frame[3 + c]) << c;  // exported vertex 4 is vertex 1
  EXPECT_EQ(frame[3], 0.25);
}

TEST(GltfExport, AVertexMapThatDoesNotMatchIsRefusedByTheReader) {
  GltfExportInput input = squareInput();
  input.base.uvs.insert(input.base.uvs.end(), {0.5f, 0.5f});
  input.base.uv_triangles = {0, 1, 2, 2, 4, 3};
  const std::string glb = gltfToGlb(input, "t.glb");
  const DecodedGltf g = testing::decodeGlb(glb);
  const auto& prim = g.doc.at("meshes").at(0).at("primitives").at(0);
  const auto& a = g.doc.at("accessors").at(prim.at("attributes").at("_VDG_VERTEX").get<int>());
  const std::size_t json_length = testing::u32At(glb, 12);
  const std::size_t view_at =
      20 + json_length + 8 +
      g.doc.at("bufferViews").at(a.at("bufferView").get<int>()).at("byteOffset").get<std::size_t>();
  // Exported vertex 4 (the copy of model vertex 1) named as another vertex, or out of range.
  const auto withId = [&](std::uint16_t id) {
    std::string bytes = glb;
    std::memcpy(&bytes[view_at + 4 * 4], &id, 2);
    return errorOf([&] { (void)parseGltfRig(bytes, "t.glb"); });
  };
  EXPECT_NE(withId(3).find("t.glb: meshes[0]: vertex 4 (_VDG_VERTEX 3) lies elsewhere than vertex 3"),
            std::string::npos)
      << withId(3);
  EXPECT_NE(withId(9).find("t.glb: meshes[0]: _VDG_VERTEX[4] = 9"), std::string::npos) << withId(9);
}

// Display sRGB to linear, the inverse of the reader's encoding (IEC 61966-2-1), for the expectations.
double linearOf(double c) { return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4); }

TEST(GltfExport, MaterialsArePrimitivesWithLinearColoursAndTheirTextures) {
  GltfExportInput input = squareInput();
  auto texture = std::make_shared<TextureImage>();
  texture->width = 2, texture->height = 1;
  texture->rgba = {255, 0, 0, 255, 0, 0, 255, 255};
  Material red{"red", {0.5f, 0.25f, 1.0f}, "red.png", texture};
  input.base.materials = {red};
  input.base.face_materials = {-1, 0};  // the first triangle has no material
  GltfExportReport report;
  const std::string glb = gltfToGlb(input, "t.glb", &report);
  const DecodedGltf g = testing::decodeGlb(glb);
  EXPECT_EQ(report.materials, 2u);
  EXPECT_EQ(report.images, 1u);
  const auto& prims = g.doc.at("meshes").at(0).at("primitives");
  ASSERT_EQ(prims.size(), 2u);
  EXPECT_EQ(readAccessor(g, prims.at(0).at("indices")), (std::vector<double>{0, 1, 2}));
  EXPECT_EQ(readAccessor(g, prims.at(1).at("indices")), (std::vector<double>{2, 1, 3}));
  const auto& plain = g.doc.at("materials").at(prims.at(0).at("material").get<int>());
  EXPECT_EQ(plain.at("pbrMetallicRoughness").at("metallicFactor"), 0.0);
  EXPECT_FALSE(plain.at("pbrMetallicRoughness").contains("baseColorFactor"));  // white
  EXPECT_TRUE(plain.at("extras").at("vdg").at("plain").get<bool>());
  const auto& mat = g.doc.at("materials").at(prims.at(1).at("material").get<int>());
  EXPECT_EQ(mat.at("name"), "red");
  const auto factor = mat.at("pbrMetallicRoughness").at("baseColorFactor");
  constexpr double kColourTol = 1e-12;
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(factor.at(c).get<double>(), linearOf(red.base_color[c]), kColourTol);
  EXPECT_EQ(mat.at("pbrMetallicRoughness").at("metallicFactor"), 0.0);
  // The texture: the pixels encoded as PNG (it has no file bytes) in a bufferView.
  const int tex = mat.at("pbrMetallicRoughness").at("baseColorTexture").at("index");
  const auto& image = g.doc.at("images").at(g.doc.at("textures").at(tex).at("source").get<int>());
  EXPECT_EQ(image.at("mimeType"), "image/png");
  const auto& view = g.doc.at("bufferViews").at(image.at("bufferView").get<int>());
  const TextureImage decoded = decodeImage(
      g.bin.substr(view.at("byteOffset").get<std::size_t>(), view.at("byteLength").get<std::size_t>()), "png");
  EXPECT_EQ(decoded.rgba, texture->rgba);
  // Read back: the same faces with the same material, the plain one none; colour to 1e-6.
  const RawRig rig = parseGltfRig(glb, "t.glb");
  ASSERT_EQ(rig.mesh.materials.size(), 1u);
  EXPECT_EQ(rig.mesh.face_materials, input.base.face_materials);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(rig.mesh.materials[0].base_color[c], red.base_color[c], 1e-6);
  ASSERT_TRUE(rig.mesh.materials[0].texture);
  EXPECT_EQ(rig.mesh.materials[0].texture->rgba, texture->rgba);
}

TEST(GltfExport, AGltfWritesItsImagesBesideItInOneTransaction) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "vdg_gltf_images_test";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  GltfExportInput input = squareInput();
  auto texture = std::make_shared<TextureImage>();
  texture->width = 1, texture->height = 1;
  texture->rgba = {10, 20, 30, 255};
  texture->file_bytes = encodePng(*texture, "t");
  input.base.materials = {Material{"m", {1, 1, 1}, "m.png", texture}};
  input.base.face_materials = {0, 0};
  const GltfExportReport report = writeGltfExport((dir / "out.gltf").string(), input);
  ASSERT_EQ(report.files.size(), 1u);
  EXPECT_EQ(report.files[0], (dir / "out-texture-0.png").string());
  EXPECT_EQ(testing::readText(report.files[0]), texture->file_bytes);  // the file's bytes as they are
  const DecodedGltf g = testing::decodeGltfFile((dir / "out.gltf").string());
  EXPECT_EQ(g.doc.at("images").at(0).at("uri"), "out-texture-0.png");
  EXPECT_EQ(g.doc.at("meshes").at(0).at("primitives").size(), 1u);
  const TriMesh back = readGltfRig((dir / "out.gltf").string()).mesh;
  ASSERT_EQ(back.materials.size(), 1u);
  ASSERT_TRUE(back.materials[0].texture);
  EXPECT_EQ(back.materials[0].texture->rgba, texture->rgba);
  // Without side files (gltfToJson with no image list) the image is a data: URI.
  std::string bin;
  const auto doc = nlohmann::json::parse(gltfToJson(input, "t.gltf", "t.bin", bin));
  EXPECT_EQ(doc.at("images").at(0).at("uri").get<std::string>().rfind("data:image/png;base64,", 0), 0u);
  std::filesystem::remove_all(dir);
}

std::vector<Camera> orbit(const ViewDependentModel& model, int frames) {
  std::vector<Camera> cams;
  for (int f = 0; f < frames; ++f) {
    const double az = 2.0 * std::numbers::pi * f / frames, el = 0.35;
    Camera c;
    c.target = model.center();
    c.eye = c.target + 5.0 * Eigen::Vector3d(std::sin(az) * std::cos(el), std::sin(el), std::cos(az) * std::cos(el));
    c.fov_deg = 30.0;
    cams.push_back(c);
  }
  return cams;
}

TEST(GltfExport, BakedWeightsReproduceTheBlendAtEverySample) {
  const auto model = ViewDependentModel::build(sphereModel(Uncovered::Base, 1.5));
  const auto cams = orbit(model, 12);
  GltfExportInput input = gltfExportInput(model);
  input.bake = gltfBakedAnimation(bakeCameraPath(model, cams, 24.0, 1.5, 0.0, true), input);
  const DecodedGltf g = testing::decodeGlb(gltfToGlb(input, "t.glb"));
  const DecodedModel d = decodeModel(g);
  const auto& anim = g.doc.at("animations").at(0);
  ASSERT_EQ(anim.at("channels").size(), 3u);
  EXPECT_EQ(anim.at("channels").at(0).at("target").at("path"), "weights");
  EXPECT_EQ(anim.at("samplers").at(0).at("interpolation"), "LINEAR");
  const auto times = readAccessor(g, anim.at("samplers").at(0).at("input"));
  const auto weights = readAccessor(g, anim.at("samplers").at(0).at("output"));
  const auto translations = readAccessor(g, anim.at("samplers").at(1).at("output"));
  const auto rotations = readAccessor(g, anim.at("samplers").at(2).at("output"));
  ASSERT_EQ(times.size(), cams.size() + 1);  // the closing sample
  const std::size_t keys = model.keyCount();
  ASSERT_EQ(weights.size(), times.size() * keys);
  std::vector<float> expected(model.vertexCount() * 3);
  for (std::size_t s = 0; s < times.size(); ++s) {
    const Camera& cam = cams[s % cams.size()];
    EXPECT_NEAR(times[s], s / 24.0, 1e-6);
    ASSERT_TRUE(model.evaluate(model.viewFromEye(cam.eye), 0.0, expected));
    for (std::size_t i = 0; i < expected.size(); ++i) {
      double p = d.base.positions[i];
      for (std::size_t k = 0; k < keys; ++k) p += weights[s * keys + k] * d.deltas[k][i];
      ASSERT_NEAR(p, expected[i], kBakeTol) << "sample " << s << " value " << i;
    }
    // The camera node: at the eye, its -Z towards the target, +Y on the up side.
    const Eigen::Vector3d eye(translations[s * 3], translations[s * 3 + 1], translations[s * 3 + 2]);
    EXPECT_NEAR((eye - cam.eye).norm(), 0.0, 1e-5);
    const Eigen::Quaterniond q(rotations[s * 4 + 3], rotations[s * 4], rotations[s * 4 + 1], rotations[s * 4 + 2]);
    EXPECT_NEAR(q.norm(), 1.0, kQuatTol);
    const Eigen::Vector3d forward = q.normalized() * Eigen::Vector3d(0, 0, -1);
    EXPECT_NEAR((forward - (cam.target - cam.eye).normalized()).norm(), 0.0, 1e-5);
    EXPECT_GT((q.normalized() * Eigen::Vector3d::UnitY()).y(), 0.0);
    if (s > 0) {
      const Eigen::Vector4d a(rotations[s * 4], rotations[s * 4 + 1], rotations[s * 4 + 2], rotations[s * 4 + 3]);
      const Eigen::Vector4d b(rotations[s * 4 - 4], rotations[s * 4 - 3], rotations[s * 4 - 2], rotations[s * 4 - 1]);
      EXPECT_GE(a.dot(b), 0.0) << "consecutive rotations in one hemisphere";
    }
  }
  const auto& cam = g.doc.at("cameras").at(0).at("perspective");
  EXPECT_NEAR(cam.at("yfov").get<double>(), 30.0 * std::numbers::pi / 180.0, 1e-12);
  EXPECT_EQ(cam.at("aspectRatio").get<double>(), 1.5);
  EXPECT_LT(cam.at("znear").get<double>(), 5.0 - 1.0);
  EXPECT_GT(cam.at("zfar").get<double>(), 5.0 + 1.0);
  // Still the model: the bake reads back as the same view-dependent model.
  expectSameEvaluation(model, roundTrip(g), kRoundTripTol);
}

TEST(GltfExport, BakeOptions) {
  const auto model = ViewDependentModel::build(sphereModel());
  const auto cams = orbit(model, 5);
  GltfExportInput input = gltfExportInput(model);
  input.bake = gltfBakedAnimation(bakeCameraPath(model, cams, 10.0, 1.0, 7.0, false), input);
  input.bake->step = true;
  input.bake->translations.clear();
  const DecodedGltf g = testing::decodeGlb(gltfToGlb(input, "t.glb"));
  const auto& anim = g.doc.at("animations").at(0);
  EXPECT_EQ(anim.at("channels").size(), 1u);
  EXPECT_EQ(anim.at("samplers").at(0).at("interpolation"), "STEP");
  EXPECT_FALSE(g.doc.contains("cameras"));
  EXPECT_EQ(readAccessor(g, anim.at("samplers").at(0).at("input")).size(), 5u);
  // Sharpness 7 (not the model's 1) is what the weights carry.
  ViewWeights w;
  ASSERT_TRUE(model.weights(model.viewFromEye(cams[2].eye), 7.0, w));
  const auto weights = readAccessor(g, anim.at("samplers").at(0).at("output"));
  for (int slot = 0; slot < 3; ++slot)
    if (w.key[slot] >= 0) {
      EXPECT_FLOAT_EQ(weights[2 * 3 + w.key[slot]], w.weight[slot]);
    }
}

TEST(GltfExport, NamesThatAreNotUtf8AreWrittenWithReplacementCharacters) {
  GltfExportInput input = gltfExportInput(ViewDependentModel::build(sphereModel()));
  input.targets[0].name = "bad\xff";
  const DecodedGltf g = testing::decodeGlb(gltfToGlb(input, "t.glb"));
  EXPECT_EQ(g.doc.at("meshes").at(0).at("extras").at("targetNames").at(0), "bad\xef\xbf\xbd");
}

TEST(GltfExport, SamplesThatDoNotMatchTheTargetsAreRefused) {
  const auto model = ViewDependentModel::build(sphereModel());
  GltfExportInput input = gltfExportInput(model);
  CameraPathBake samples = bakeCameraPath(model, orbit(model, 3), 24, 1, 0, false);
  samples.weights.pop_back();
  EXPECT_EQ(errorOf([&] { (void)gltfBakedAnimation(samples, input); }),
            "bake: the samples' weights do not match the export input's 3 targets");
}

TEST(GltfExport, BadInputsAreRefused) {
  const auto model = ViewDependentModel::build(sphereModel());
  const GltfExportInput good = gltfExportInput(model);
  const auto refused = [&](const std::function<void(GltfExportInput&)>& change) {
    GltfExportInput in = good;
    change(in);
    return errorOf([&] { (void)gltfToGlb(in, "out.glb"); });
  };
  EXPECT_EQ(refused([](auto& in) { in.base = TriMesh{}; }), "out.glb: the base mesh has no vertices or no triangles");
  EXPECT_EQ(refused([](auto& in) { in.base.triangles[4] = 1000; }).rfind("out.glb: base", 0), 0u);
  EXPECT_EQ(refused([](auto& in) { in.normals.pop_back(); }), "out.glb: normals: expected 86 x 3 floats, got 257");
  EXPECT_EQ(refused([](auto& in) { in.normals[3] = 2; }), "out.glb: normals: vertex 1 is not unit length");
  EXPECT_EQ(refused([](auto& in) { in.targets[1].name = ""; }), "out.glb: target 1 has no name");
  EXPECT_EQ(refused([](auto& in) { in.targets[2].name = "front"; }),
            "out.glb: target 2 'front': the name is used twice");
  EXPECT_EQ(refused([](auto& in) { in.targets[0].deltas.resize(3); }),
            "out.glb: target 0 'front': expected 86 x 3 deltas, got 3");
  EXPECT_EQ(refused([](auto& in) { in.targets[0].deltas[7] = NAN; }),
            "out.glb: target 0 'front': a delta is not finite");
  EXPECT_EQ(refused([](auto& in) { in.targets[0].normal_deltas.resize(6); }),
            "out.glb: target 0 'front': normal deltas need base normals and 86 x 3 floats");
  EXPECT_EQ(refused([](auto& in) { in.targets[0].view = Eigen::Vector3d::Zero(); }),
            "out.glb: target 0 'front': the view is zero or not finite");
  EXPECT_EQ(refused([](auto& in) { in.targets[0].frame = -1; }), "out.glb: target 0 'front': the frame is negative");
  EXPECT_EQ(refused([](auto& in) { in.sharpness = 0; }), "out.glb: the sharpness must be finite and > 0");
  EXPECT_EQ(refused([](auto& in) { in.center.x() = INFINITY; }), "out.glb: the centre is not finite");
  EXPECT_EQ(refused([](auto& in) {
              in.base_animation = GltfBaseAnimation{};
              in.base_animation->frame_count = 0;
            }),
            "out.glb: base animation: expected frame_count >= 1 and fps > 0");
  const auto cams = orbit(model, 3);
  const GltfBakedAnimation bake = gltfBakedAnimation(bakeCameraPath(model, cams, 24, 1, 0, false), good);
  EXPECT_EQ(refused([&](auto& in) { in.bake = bake, in.bake->times.clear(); }), "out.glb: bake: no sample times");
  EXPECT_EQ(refused([&](auto& in) { in.bake = bake, in.bake->times[2] = in.bake->times[1]; }),
            "out.glb: bake: times are not strictly increasing at sample 2");
  EXPECT_EQ(refused([&](auto& in) { in.bake = bake, in.bake->weights.pop_back(); }),
            "out.glb: bake: expected 3 x 3 weights, got 8");
  EXPECT_EQ(refused([&](auto& in) { in.bake = bake, in.bake->weights[0] = NAN; }),
            "out.glb: bake: a weight is not finite");
  EXPECT_EQ(refused([&](auto& in) { in.bake = bake, in.bake->rotations.pop_back(); }),
            "out.glb: bake: expected 3 camera translations and rotations");
  EXPECT_EQ(refused([&](auto& in) { in.bake = bake, in.bake->znear = 0; }),
            "out.glb: bake: expected 0 < yfov < pi, aspect > 0 and 0 < znear < zfar");
  EXPECT_EQ(refused([&](auto& in) { in.bake = bake, in.targets.clear(); }),
            "out.glb: bake: the model has no morph targets to animate");
  EXPECT_EQ(refused([](auto& in) { in.view_sphere->view_targets[0] = {1}; }),
            "out.glb: view sphere: every key target must belong to exactly one view (internal error)");
  EXPECT_EQ(refused([](auto& in) { in.view_sphere->inverses.pop_back(); }),
            "out.glb: view sphere: one inverse per triangle (internal error)");
  testing::TempDir dir;
  EXPECT_EQ(errorOf([&] { writeGltfExport(dir.file("out.obj"), good); }),
            dir.file("out.obj") + ": expected a .glb or .gltf file name");
}

// A model's exported mesh extras, and what the reader says of them after an edit.
struct ExtrasEdit {
  DecodedModel d;
  nlohmann::json good;
  explicit ExtrasEdit(const ViewDependentModel& model)
      : d(decodeModel(testing::decodeGlb(gltfToGlb(gltfExportInput(model), "t.glb")))),
        good(nlohmann::json::parse(d.extras)) {}
  // The reader's message for the extras after `change` ("" when it reads them).
  std::string refused(const std::function<void(nlohmann::json&)>& change) const {
    nlohmann::json e = good;
    change(e);
    return errorOf([&] { (void)rawModelFromGltfExtras(e.dump(), d.base, d.deltas, "m.glb"); });
  }
};

TEST(GltfExport, BadExtrasAreRefusedByTheReader) {
  const auto model = ViewDependentModel::build(sphereModel());
  const ExtrasEdit extras(model);
  const DecodedModel& d = extras.d;
  const auto refused = [&](const std::function<void(nlohmann::json&)>& change) { return extras.refused(change); };
  EXPECT_EQ(refused([](auto&) {}), "");
  EXPECT_EQ(errorOf([&] {
              (void)rawModelFromGltfExtras("{", d.base, d.deltas, "m.glb");
            }).rfind("m.glb: mesh extras: not valid JSON", 0),
            0u);
  EXPECT_EQ(refused([](auto& e) { e = 3; }), "m.glb: mesh extras: expected an object, got the number 3");
  EXPECT_EQ(refused([](auto& e) { e.erase("vdg"); }),
            "m.glb: mesh extras: no 'vdg' description: this glTF file was not exported by vdg");
  EXPECT_EQ(refused([](auto& e) { e.erase("targetNames"); }), "m.glb: mesh extras: missing key 'targetNames'");
  EXPECT_EQ(refused([](auto& e) { e["vdg"]["version"] = 5; }).rfind("m.glb: mesh extras: 'vdg'.'version': ", 0), 0u);
  EXPECT_NE(refused([](auto& e) { e["vdg"]["version"] = 5; }).find("got 5"), std::string::npos);
  EXPECT_EQ(refused([](auto& e) {
              e["vdg"]["weights"] = {{"scheme", "smooth"}};
            }),
            "m.glb: mesh extras: 'vdg'.'weights': needs extras version 3");
  EXPECT_NE(refused([](auto& e) {
              e["vdg"]["version"] = 3;
              e["vdg"]["weights"] = {{"scheme", "cubic"}};
            }).find("'vdg'.'weights'.'scheme': unknown value 'cubic'"),
            std::string::npos);
  EXPECT_EQ(
      refused([](auto& e) { e["vdg"]["colour"] = 2; }).rfind("m.glb: mesh extras: 'vdg': unknown key 'colour'", 0), 0u);
  EXPECT_EQ(refused([](auto& e) {
              e["vdg"]["animation"] = {{"frame_count", 1}, {"fps", 24}, {"loop", false}, {"base", "frames"}};
              e["vdg"]["version"] = 1;  // a v2 file would first miss the animated model's 'time'
              e["vdg"].erase("sphere");
            }),
            "m.glb: mesh extras: 'vdg'.'animation': an animated view-dependent model needs its file's skin and "
            "animation; read it with loadGltfModel");
  EXPECT_EQ(refused([](auto& e) {
              e["vdg"]["animation"] = {{"frame_count", 40}};
            }),
            "m.glb: mesh extras: 'vdg'.'animation': missing key 'fps'");
  EXPECT_EQ(refused([](auto& e) { e["vdg"]["keys"][1]["frame"] = 10; }),
            "m.glb: mesh extras: 'vdg'.'keys'[1].'frame': a key at frame > 0 belongs to an animated model, but 'vdg' "
            "has no 'animation'");
  EXPECT_EQ(refused([](auto& e) { e["vdg"]["offsets"] = "skinned"; }),
            "m.glb: mesh extras: 'vdg'.'offsets': expected \"world\" for a static model, got the string \"skinned\"");
  EXPECT_EQ(refused([](auto& e) { e["vdg"]["keys"].erase(2); }),
            "m.glb: mesh extras: 'vdg'.'keys': describes 2 keys, but the mesh has 3 morph targets");
  EXPECT_EQ(refused([](auto& e) { e["targetNames"].erase(2); }),
            "m.glb: mesh extras: 'targetNames': has 2 names for 3 morph targets");
  EXPECT_EQ(refused([](auto& e) { e["targetNames"][1] = "other"; }),
            "m.glb: mesh extras: 'vdg'.'keys'[1].'name': differs from targetNames[1] the string \"other\"");
  EXPECT_EQ(refused([](auto& e) { e["vdg"]["keys"][0]["view"] = "up"; }),
            "m.glb: mesh extras: 'vdg'.'keys'[0].'view': expected 3 numbers, got the string \"up\"");
  EXPECT_EQ(
      refused([](auto& e) { e["vdg"]["uncovered"] = "none"; }).rfind("m.glb: mesh extras: 'vdg'.'uncovered': ", 0), 0u);
  EXPECT_EQ(refused([](auto& e) { e["vdg"]["sharpness"] = -1; }).rfind("m.glb: ", 0), 0u);
  EXPECT_NE(refused([](auto& e) { e["vdg"]["sharpness"] = -1; }), "");
  std::vector<std::vector<float>> short_deltas = d.deltas;
  short_deltas[1].pop_back();
  EXPECT_EQ(errorOf([&] { (void)rawModelFromGltfExtras(d.extras, d.base, short_deltas, "m.glb"); }),
            "m.glb: mesh extras: 'vdg'.'keys'[1]: morph target 1 has 257 delta values, expected 258");
}

// An rbf model (docs/weights.md, "The rbf scheme") of the test sphere's keys.
RawViewDependentModel rbfSphereModel(Uncovered uncovered, RbfKernel kernel) {
  RawViewDependentModel raw = sphereModel(uncovered, 2.5);
  raw.sphere.scheme = WeightScheme::Rbf;
  raw.sphere.rbf_kernel = kernel;
  raw.sphere.rbf_width_deg = 75.0;
  return raw;
}

// Extras v4 (docs/gltf-export.md): an rbf model writes its kernel and width and exactly the solved
// interpolation; the written coefficients interpolate the keys (one-hot at each key view, to the
// solve's rounding), and the file reads back into the same weights at every view.
TEST(GltfExport, ExtrasV4CarryTheRbfInterpolation) {
  constexpr double kInterpolationTol = 1e-9;  // the saddle system's solution, well conditioned
  for (const Uncovered mode : {Uncovered::Base, Uncovered::Cosine, Uncovered::Cosine2}) {
    for (const RbfKernel kernel : {RbfKernel::Gaussian, RbfKernel::InverseMultiquadric, RbfKernel::Wendland}) {
      SCOPED_TRACE(std::string(uncoveredName(mode)) + " " + rbfKernelName(kernel));
      const auto model = ViewDependentModel::build(rbfSphereModel(mode, kernel));
      const ViewSphere& sphere = model.sphere();
      const DecodedModel d = decodeModel(testing::decodeGlb(gltfToGlb(gltfExportInput(model), "t.glb")));
      const nlohmann::json vdg = nlohmann::json::parse(d.extras).at("vdg");
      EXPECT_EQ(vdg.at("version"), 4);
      EXPECT_EQ(vdg.at("weights"),
                nlohmann::json({{"scheme", "rbf"}, {"kernel", rbfKernelName(kernel)}, {"width", 75.0}}));
      const nlohmann::json& rbf = vdg.at("sphere").at("rbf");
      EXPECT_EQ(rbf.at("chord2").get<double>(), sphere.rbfChord2());
      const std::size_t outputs = sphere.keyCount() + 1, points = sphere.points().size();
      ASSERT_EQ(rbf.at("coefficients").size(), points + 1);
      for (std::size_t r = 0; r <= points; ++r) {
        ASSERT_EQ(rbf.at("coefficients")[r].size(), outputs);
        for (std::size_t o = 0; o < outputs; ++o)
          EXPECT_EQ(rbf.at("coefficients")[r][o].get<double>(), sphere.rbfCoefficients()[r * outputs + o]);
      }
      // r_o(x_i) = b_o + sum_j c_oj g(|x_i - x_j|^2 / chord2) is 1 for i's own output, 0 for the others.
      for (std::size_t i = 0; i < points; ++i) {
        for (std::size_t o = 0; o < outputs; ++o) {
          double r = rbf.at("coefficients")[0][o].get<double>();
          for (std::size_t j = 0; j < points; ++j) {
            const double q = (sphere.points()[i] - sphere.points()[j]).squaredNorm() / sphere.rbfChord2();
            const double s = std::sqrt(q);
            const double g = kernel == RbfKernel::Gaussian              ? std::exp(-q)
                             : kernel == RbfKernel::InverseMultiquadric ? 1.0 / std::sqrt(1.0 + q)
                             : s >= 1.0                                 ? 0.0
                                                                        : std::pow(1.0 - s, 4) * (4.0 * s + 1.0);
            r += rbf.at("coefficients")[j + 1][o].get<double>() * g;
          }
          const std::size_t own = sphere.isDummy(static_cast<int>(i)) ? outputs - 1 : i;
          EXPECT_NEAR(r, o == own ? 1.0 : 0.0, kInterpolationTol) << "point " << i << " output " << o;
        }
      }
      const auto again = ViewDependentModel::build(rawModelFromGltfExtras(d.extras, d.base, d.deltas, "t.glb"));
      EXPECT_EQ(again.sphere().settings().scheme, WeightScheme::Rbf);
      std::vector<float> expected(outputs), read(outputs);
      for (const Eigen::Vector3d& view : testViews()) {
        ASSERT_TRUE(model.sphere().denseWeights(view, 1.7, expected));
        ASSERT_TRUE(again.sphere().denseWeights(view, 1.7, read));
        EXPECT_EQ(expected, read);
      }
    }
  }
  // The older versions stay as they were: a linear model writes version 2, a smooth one 3, neither "rbf".
  RawViewDependentModel smooth = sphereModel();
  smooth.sphere.scheme = WeightScheme::Smooth;
  for (const auto& [raw, version] : {std::pair{sphereModel(), 2}, std::pair{smooth, 3}}) {
    const auto model = ViewDependentModel::build(raw);
    const nlohmann::json vdg =
        nlohmann::json::parse(decodeModel(testing::decodeGlb(gltfToGlb(gltfExportInput(model), "t.glb"))).extras)
            .at("vdg");
    EXPECT_EQ(vdg.at("version"), version);
    EXPECT_FALSE(vdg.at("sphere").contains("rbf"));
    EXPECT_FALSE(vdg.contains("weights") && vdg.at("weights").contains("kernel"));
  }
}

TEST(GltfExport, BadRbfExtrasAreRefusedByTheReader) {
  const auto model = ViewDependentModel::build(rbfSphereModel(Uncovered::Base, RbfKernel::Gaussian));
  const ExtrasEdit extras(model);
  const auto refused = [&](const std::function<void(nlohmann::json&)>& change) { return extras.refused(change); };
  const std::size_t rows = model.sphere().points().size() + 1;
  EXPECT_EQ(refused([](auto&) {}), "");
  EXPECT_EQ(refused([](auto& e) { e["vdg"]["version"] = 3; }),
            "m.glb: mesh extras: 'vdg'.'weights'.'scheme': 'rbf' needs extras version 4");
  EXPECT_EQ(refused([](auto& e) { e["vdg"]["weights"].erase("kernel"); }),
            "m.glb: mesh extras: 'vdg'.'weights': missing key 'kernel'");
  EXPECT_NE(refused([](auto& e) {
              e["vdg"]["weights"]["kernel"] = "cubic";
            }).find("m.glb: mesh extras: 'vdg'.'weights'.'kernel': unknown value 'cubic'"),
            std::string::npos);
  EXPECT_EQ(refused([](auto& e) { e["vdg"]["weights"].erase("width"); }),
            "m.glb: mesh extras: 'vdg'.'weights': missing key 'width'");
  EXPECT_EQ(refused([](auto& e) { e["vdg"]["weights"]["width"] = 0; }),
            "m.glb: mesh extras: 'vdg'.'weights'.'width': expected an angle in (0, 180] degrees, got the number 0");
  EXPECT_EQ(refused([](auto& e) { e["vdg"]["weights"]["width"] = 200; }),
            "m.glb: mesh extras: 'vdg'.'weights'.'width': expected an angle in (0, 180] degrees, got the number 200");
  EXPECT_EQ(refused([](auto& e) { e["vdg"]["weights"]["scheme"] = "smooth"; }),
            "m.glb: mesh extras: 'vdg'.'weights'.'kernel': belongs to the 'rbf' scheme only");
  EXPECT_EQ(refused([](auto& e) {
              e["vdg"]["weights"] = {{"scheme", "smooth"}};
            }),
            "m.glb: mesh extras: 'vdg'.'sphere'.'rbf': belongs to the 'rbf' weight scheme only");
  EXPECT_EQ(refused([](auto& e) { e["vdg"]["sphere"].erase("rbf"); }),
            "m.glb: mesh extras: 'vdg'.'sphere': missing key 'rbf'");
  EXPECT_EQ(refused([](auto& e) { e["vdg"]["sphere"]["rbf"] = 1; }),
            "m.glb: mesh extras: 'vdg'.'sphere'.'rbf': expected an object {\"chord2\": ..., \"coefficients\": ...}, "
            "got the number 1");
  EXPECT_NE(refused([](auto& e) {
              e["vdg"]["sphere"]["rbf"]["scale"] = 1;
            }).find("m.glb: mesh extras: 'vdg'.'sphere'.'rbf': unknown key 'scale'"),
            std::string::npos);
  EXPECT_EQ(refused([](auto& e) { e["vdg"]["sphere"]["rbf"]["chord2"] = -1; }),
            "m.glb: mesh extras: 'vdg'.'sphere'.'rbf'.'chord2': expected a squared chord in (0, 4], got the number -1");
  EXPECT_EQ(refused([](auto& e) { e["vdg"]["sphere"]["rbf"]["coefficients"].erase(0); }),
            "m.glb: mesh extras: 'vdg'.'sphere'.'rbf'.'coefficients': expected " + std::to_string(rows) +
                " rows (the constants, then one per point), got an array of " + std::to_string(rows - 1) + " items");
  EXPECT_NE(refused([](auto& e) {
              e["vdg"]["sphere"]["rbf"]["coefficients"][2].erase(0);
            }).find("m.glb: mesh extras: 'vdg'.'sphere'.'rbf'.'coefficients'[2]: "),
            std::string::npos);
  EXPECT_NE(refused([](auto& e) {
              e["vdg"]["sphere"]["rbf"]["coefficients"][1][0] = "x";
            }).find("m.glb: mesh extras: 'vdg'.'sphere'.'rbf'.'coefficients'[1]"),
            std::string::npos);
}

// Extras v2 (docs/gltf-export.md): "sphere" is exactly the built ViewSphere, so a runtime that
// repeats view_sphere.cpp's query on it finds the model's triangle and weights.
TEST(GltfExport, ExtrasV2CarryTheSphereAsBuilt) {
  // Inverses are written as doubles (17 digits): they invert their corners to double rounding.
  constexpr double kInverseTol = 1e-12;
  constexpr double kInsideTol = 1e-9;  // view_sphere.cpp's tolerance for "inside a triangle"
  for (const Uncovered mode : {Uncovered::Base, Uncovered::Cosine, Uncovered::Cosine2}) {
    const auto model = ViewDependentModel::build(sphereModel(mode, 2.5));
    const ViewSphere& sphere = model.sphere();
    const DecodedModel d = decodeModel(testing::decodeGlb(gltfToGlb(gltfExportInput(model), "t.glb")));
    const nlohmann::json vdg = nlohmann::json::parse(d.extras).at("vdg");
    EXPECT_EQ(vdg.at("version"), 2);
    EXPECT_FALSE(vdg.contains("time"));
    const nlohmann::json& s = vdg.at("sphere");
    ASSERT_EQ(s.at("points").size(), sphere.points().size());
    for (std::size_t i = 0; i < sphere.points().size(); ++i)
      for (int c = 0; c < 3; ++c) EXPECT_EQ(s.at("points")[i][c].get<double>(), sphere.points()[i][c]);
    EXPECT_EQ(s.at("views"), 3);
    EXPECT_EQ(s.at("view_targets"), nlohmann::json::parse("[[0], [1], [2]]"));
    EXPECT_EQ(s.at("arcs").size(), sphere.boundaryArcs().size());
    EXPECT_EQ(s.at("isolated").size(), sphere.isolatedKeys().size());
    ASSERT_EQ(s.at("triangles").size(), sphere.triangles().size());
    ASSERT_EQ(s.at("inverses").size(), sphere.triangles().size());
    if (mode == Uncovered::Base) {
      EXPECT_GT(s.at("points").size(), 3u);  // dummy base points
    }
    std::vector<Eigen::Matrix3d> inverses;
    for (std::size_t t = 0; t < sphere.triangles().size(); ++t) {
      Eigen::Matrix3d m, corners;
      for (int k = 0; k < 9; ++k) m(k / 3, k % 3) = s.at("inverses")[t][k].get<double>();
      for (int k = 0; k < 3; ++k) corners.col(k) = sphere.points()[s.at("triangles")[t][k].get<std::size_t>()];
      EXPECT_LT((m * corners - Eigen::Matrix3d::Identity()).norm(), kInverseTol) << "triangle " << t;
      inverses.push_back(m);
    }
    // The model's triangle of a view contains it under the written inverse.
    for (const Eigen::Vector3d& view : testViews()) {
      ViewWeights w;
      ASSERT_TRUE(model.weights(view.normalized(), 0.0, w));
      if (w.triangle < 0) continue;
      EXPECT_GE((inverses[static_cast<std::size_t>(w.triangle)] * view.normalized()).minCoeff(), -kInsideTol);
    }
  }
}

TEST(GltfExport, HandMadeStaticInputsGetTheirSphereFromTheTargets) {
  GltfExportInput input = gltfExportInput(ViewDependentModel::build(sphereModel(Uncovered::Cosine)));
  const nlohmann::json built = nlohmann::json::parse(decodeModel(testing::decodeGlb(gltfToGlb(input, "t.glb"))).extras);
  input.view_sphere.reset();
  const nlohmann::json derived =
      nlohmann::json::parse(decodeModel(testing::decodeGlb(gltfToGlb(input, "t.glb"))).extras);
  // Targets whose views cannot make a sphere are refused naming the file.
  GltfExportInput twice = input;
  twice.targets[1].view = twice.targets[0].view;
  EXPECT_EQ(errorOf([&] { (void)gltfToGlb(twice, "t.glb"); }),
            "t.glb: key 1: same view direction as key 0 (within 1e-6 rad)");
  // The same sphere: the targets' views are the model's unit views, normalised again (an ulp).
  constexpr double kUlpTol = 1e-14;
  const nlohmann::json& a = derived.at("vdg").at("sphere");
  const nlohmann::json& b = built.at("vdg").at("sphere");
  for (const char* exact : {"views", "triangles", "arcs", "isolated", "view_targets"})
    EXPECT_EQ(a.at(exact), b.at(exact));
  for (const char* close : {"points", "inverses"}) {
    ASSERT_EQ(a.at(close).size(), b.at(close).size());
    for (std::size_t i = 0; i < a.at(close).size(); ++i)
      for (std::size_t c = 0; c < a.at(close)[i].size(); ++c)
        EXPECT_NEAR(a.at(close)[i][c].get<double>(), b.at(close)[i][c].get<double>(), kUlpTol) << close << i;
  }
}

// Version 1 files (no "sphere") are still read: vdg re-derives the sphere from the keys.
TEST(GltfExport, ExtrasV1AreStillRead) {
  const auto model = ViewDependentModel::build(sphereModel(Uncovered::Cosine2, 1.5));
  const DecodedModel d = decodeModel(testing::decodeGlb(gltfToGlb(gltfExportInput(model), "t.glb")));
  nlohmann::json v1 = nlohmann::json::parse(d.extras);
  v1["vdg"].erase("sphere");
  v1["vdg"]["version"] = 1;
  const auto back = ViewDependentModel::build(rawModelFromGltfExtras(v1.dump(), d.base, d.deltas, "v1.glb"));
  expectSameEvaluation(model, back, kRoundTripTol);
  // A v1 file carries no sphere, and a v2 file must.
  v1["vdg"]["version"] = 2;
  EXPECT_EQ(errorOf([&] { (void)rawModelFromGltfExtras(v1.dump(), d.base, d.deltas, "v2.glb"); }),
            "v2.glb: mesh extras: 'vdg': missing key 'sphere'");
}

TEST(GltfExport, MalformedExtrasV2AreRefusedNamingTheField) {
  const auto model = ViewDependentModel::build(sphereModel());
  const ExtrasEdit extras(model);
  const auto refused = [&](const std::function<void(nlohmann::json&)>& change) { return extras.refused(change); };
  const std::string at = "m.glb: mesh extras: 'vdg'.'sphere'";
  EXPECT_EQ(refused([](auto&) {}), "");
  EXPECT_EQ(refused([](auto& e) { e["vdg"]["sphere"] = 1; }), at + ": expected an object, got the number 1");
  EXPECT_EQ(refused([](auto& e) { e["vdg"]["sphere"].erase("inverses"); }), at + ": missing key 'inverses'");
  EXPECT_EQ(refused([](auto& e) {
              e["vdg"]["sphere"]["points"][1] = {0, 2, 0};
            }),
            at + ".'points'[1]: expected a unit direction");
  EXPECT_EQ(refused([](auto& e) { e["vdg"]["sphere"]["views"] = 2; }), at + ".'views': 2 key views for 3 keys");
  EXPECT_EQ(
      refused([](auto& e) { e["vdg"]["sphere"]["triangles"][0][1] = 1000; }).rfind(at + ".'triangles'[0][1]: ", 0), 0u);
  EXPECT_EQ(refused([](auto& e) {
              e["vdg"]["sphere"]["triangles"][0] = {0, 1};
            }),
            at + ".'triangles'[0]: expected 3 indices, got an array of 2 items");
  EXPECT_EQ(refused([](auto& e) { e["vdg"]["sphere"]["inverses"].erase(0); }).rfind(at + ".'inverses': expected ", 0),
            0u);
  EXPECT_EQ(refused([](auto& e) {
              e["vdg"]["sphere"]["inverses"][2] = {1, 2, 3};
            }).rfind(at + ".'inverses'[2]: ", 0),
            0u);
  EXPECT_EQ(refused([](auto& e) { e["vdg"]["sphere"]["arcs"] = {{0, 99}}; }).rfind(at + ".'arcs'[0][1]: ", 0), 0u);
  EXPECT_EQ(refused([](auto& e) { e["vdg"]["sphere"]["isolated"] = {5}; }).rfind(at + ".'isolated'[0]: ", 0), 0u);
  EXPECT_EQ(refused([](auto& e) { e["vdg"]["sphere"]["view_targets"][1] = {0}; }),
            at + ".'view_targets'[1]: target 0 belongs to two views");
  EXPECT_EQ(refused([](auto& e) { e["vdg"]["sphere"]["view_targets"].erase(2); }).rfind(at + ".'view_targets': ", 0),
            0u);
  EXPECT_EQ(refused([](auto& e) { e["vdg"]["time"] = nlohmann::json::array(); }),
            "m.glb: mesh extras: 'vdg'.'time': only an animated model has time tables");
  EXPECT_EQ(refused([](auto& e) {
              e["vdg"]["dequantize"] = {{"scale", {1, 1, 1}}};
            }),
            "m.glb: mesh extras: 'vdg'.'dequantize': missing key 'offset'");
  EXPECT_EQ(refused([](auto& e) { e["vdg"]["dequantize"] = {{"scale", {1, 1, 1}}, {"offset", {0, 0, 0}}}; }), "");
}

// The views list of `vdg weights --views` (vdg/io/camera_json.h), which runtimes' parity tests use.
TEST(ViewList, DirectionsViewsAndEyesBecomeUnitViews) {
  const Eigen::Vector3d center(1, 2, 3);
  const auto views =
      parseViewList(R"([[0, 0, 2], {"view": [1e-300, 0, 0]}, {"eye": [1, 2, 13]}, [3, 4, 0]])", "v.json", center);
  ASSERT_EQ(views.size(), 4u);
  EXPECT_EQ(views[0], Eigen::Vector3d(0, 0, 1));
  EXPECT_EQ(views[1], Eigen::Vector3d(1, 0, 0));
  EXPECT_EQ(views[2], Eigen::Vector3d(0, 0, 1));  // eye - centre
  EXPECT_EQ(views[3], Eigen::Vector3d(0.6, 0.8, 0));
  EXPECT_TRUE(parseViewList("[]", "v.json", center).empty());
  const auto error = [&](const std::string& text) {
    return errorOf([&] { (void)parseViewList(text, "v.json", center); });
  };
  EXPECT_EQ(error("{}"), "v.json: expected an array of views [x, y, z], got an object");
  EXPECT_EQ(error("[[0, 0]]"), "v.json: [0]: expected 3 numbers, got an array of 2 items");
  EXPECT_EQ(error("[[0, 0, 1], [0, 0, 0]]"), "v.json: [1]: the view direction is zero");
  EXPECT_EQ(error(R"([{"eye": [1, 2, 3]}])"), "v.json: [0]: the eye is at the model centre (or too far from it)");
  EXPECT_EQ(error(R"([{"eye": [1, 2, 3], "view": [0, 0, 1]}])"), "v.json: [0]: expected one of 'view' or 'eye'");
  EXPECT_EQ(error(R"([{"look": [0, 0, 1]}])").rfind("v.json: [0]: unknown key 'look'", 0), 0u);
  EXPECT_EQ(error("[[0, 0, 1e999]]").rfind("v.json: ", 0), 0u);
  EXPECT_EQ(error("[[").rfind("v.json: not valid JSON", 0), 0u);
}

}  // namespace
}  // namespace vdg
