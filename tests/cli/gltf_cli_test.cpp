// `vdg export` and `vdg bake` as a user runs them: files written, the baked animation against
// `vdg eval`, usage and input errors, and the Khronos glTF validator on every kind of export.
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "io/gltf_test_decoder.h"
#include "support/test_meshes.h"
#include "vdg/anim/rig.h"
#include "vdg/io/gltf.h"

namespace {

namespace fs = std::filesystem;
using vdg::testing::decodeGlb;
using vdg::testing::readAccessor;
using vdg::testing::readText;

// A baked frame against `vdg eval` at that frame's eye: the eye goes through text and float
// storage, and OBJ coordinates are written with 9 significant digits.
constexpr double kBakeVsEvalTol = 1e-4;

struct Result {
  int code;
  std::string out, err;
};

Result runShell(const std::string& cmd_line) {
  vdg::testing::TempDir dir;
  const std::string out = dir.file("out"), err = dir.file("err");
  const std::string cmd = "cd '" VDG_SOURCE_DIR "' && " + cmd_line + " >'" + out + "' 2>'" + err + "'";
  const int status = std::system(cmd.c_str());
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, readText(out), readText(err)};
}

Result run(const std::string& args) { return runShell("'" VDG_BINARY "' " + args); }

const std::string kSpot = "examples/spot/spot.vdg.json";
const std::string kWalk = "examples/walk/walker.vdg.json";
const std::string kWalkWorld = "examples/walk/walker-world.vdg.json";

std::vector<double> objPositions(const std::string& text) {
  std::vector<double> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("v ", 0) != 0) continue;
    std::istringstream l(line.substr(2));
    double x, y, z;
    l >> x >> y >> z;
    out.insert(out.end(), {x, y, z});
  }
  return out;
}

TEST(GltfCli, ExportWritesGlbAndGltfWithTheSameContents) {
  vdg::testing::TempDir dir;
  Result r = run("export " + kSpot + " -o " + dir.file("spot.glb"));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("5 morph targets"), std::string::npos) << r.out;
  EXPECT_EQ(r.err, "");
  r = run("export " + kSpot + " -o " + dir.file("spot.gltf") + " -q");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.out, "");
  const auto glb = decodeGlb(readText(dir.file("spot.glb")));
  const auto gltf = vdg::testing::decodeGltfFile(dir.file("spot.gltf"));
  EXPECT_EQ(gltf.doc.at("buffers").at(0).at("uri"), "spot.bin");
  // The same accessors; the texture in the .glb's buffer, beside the .gltf as a file.
  const auto& glb_prim = glb.doc.at("meshes").at(0).at("primitives").at(0);
  const auto& gltf_prim = gltf.doc.at("meshes").at(0).at("primitives").at(0);
  for (const char* attribute : {"POSITION", "NORMAL", "TEXCOORD_0"})
    EXPECT_EQ(readAccessor(glb, glb_prim.at("attributes").at(attribute)),
              readAccessor(gltf, gltf_prim.at("attributes").at(attribute)))
        << attribute;
  EXPECT_EQ(readAccessor(glb, glb_prim.at("indices")), readAccessor(gltf, gltf_prim.at("indices")));
  EXPECT_EQ(vdg::testing::readVertexIds(glb, glb_prim), vdg::testing::readVertexIds(gltf, gltf_prim));
  EXPECT_EQ(gltf.doc.at("images").at(0).at("uri"), "spot-texture-0.png");
  const auto& view = glb.doc.at("bufferViews").at(glb.doc.at("images").at(0).at("bufferView").get<int>());
  EXPECT_EQ(glb.bin.substr(view.at("byteOffset").get<std::size_t>(), view.at("byteLength").get<std::size_t>()),
            readText(dir.file("spot-texture-0.png")));
  EXPECT_EQ(glb.doc.at("meshes").at(0).at("extras").at("targetNames"),
            nlohmann::json({"front", "left", "right", "back", "top"}));
  EXPECT_EQ(glb.doc.at("meshes").at(0).at("extras").at("vdg").at("version"), 2);  // extras v2 (with "sphere")
  EXPECT_FALSE(glb.doc.contains("animations"));
}

TEST(GltfCli, BakedFramesEqualVdgEvalAtEachFramesCamera) {
  vdg::testing::TempDir dir;
  constexpr int kOrbit = 8;
  const Result r = run("bake " + kSpot + " -o " + dir.file("bake.glb") + " --orbit " + std::to_string(kOrbit) +
                       " --elevation 25 --fps 12 -q");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto g = decodeGlb(readText(dir.file("bake.glb")));
  const auto& prim = g.doc.at("meshes").at(0).at("primitives").at(0);
  const auto base = readAccessor(g, prim.at("attributes").at("POSITION"));
  const auto ids = vdg::testing::readVertexIds(g, prim);
  std::vector<std::vector<double>> deltas;
  for (const auto& t : prim.at("targets")) deltas.push_back(readAccessor(g, t.at("POSITION")));
  const auto& anim = g.doc.at("animations").at(0);
  const auto times = readAccessor(g, anim.at("samplers").at(0).at("input"));
  const auto weights = readAccessor(g, anim.at("samplers").at(0).at("output"));
  const auto eyes = readAccessor(g, anim.at("samplers").at(1).at("output"));
  ASSERT_EQ(times.size(), kOrbit + 1u) << "the whole orbit gets a closing sample";
  EXPECT_NEAR(times.back(), kOrbit / 12.0, 1e-6);
  for (int f : {0, 1, 3, 6}) {
    EXPECT_NEAR(times[f], f / 12.0, 1e-6);
    char eye[128];
    std::snprintf(eye, sizeof eye, "%.9g,%.9g,%.9g", eyes[f * 3], eyes[f * 3 + 1], eyes[f * 3 + 2]);
    const std::string obj = dir.file("eval" + std::to_string(f) + ".obj");
    const Result e = run("eval " + kSpot + " --eye " + eye + " -o " + obj + " -q");
    ASSERT_EQ(e.code, 0) << e.err;
    const auto expected = objPositions(readText(obj));
    // Exported vertex e (the seams split the model's vertices) is model vertex ids[e].
    ASSERT_EQ(ids.size() * 3, base.size());
    for (std::size_t i = 0; i < base.size(); ++i) {
      double p = base[i];
      for (std::size_t k = 0; k < deltas.size(); ++k) p += weights[f * deltas.size() + k] * deltas[k][i];
      const std::size_t model_i = static_cast<std::size_t>(ids[i / 3]) * 3 + i % 3;
      ASSERT_LT(model_i, expected.size());
      ASSERT_NEAR(p, expected[model_i], kBakeVsEvalTol) << "frame " << f << " value " << i;
    }
  }
  // The camera sees the model from render's orbit: frame 0 at azimuth 0 looks along -Z.
  const auto rotations = readAccessor(g, anim.at("samplers").at(2).at("output"));
  EXPECT_GT(eyes[2], 0.0);
  EXPECT_NEAR(rotations[1], 0.0, 1e-6);  // no yaw at azimuth 0: q = (x, 0, 0, w)
}

TEST(GltfCli, BakeFramesRangeStartsAtTimeZeroWithoutAClosingSample) {
  vdg::testing::TempDir dir;
  const Result r = run("bake " + kSpot + " -o " + dir.file("b.gltf") + " --orbit 10 --frames 3-5 --step -q");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto g = vdg::testing::decodeGltfFile(dir.file("b.gltf"));
  const auto& anim = g.doc.at("animations").at(0);
  EXPECT_EQ(anim.at("samplers").at(0).at("interpolation"), "STEP");
  EXPECT_EQ(readAccessor(g, anim.at("samplers").at(0).at("input")), (std::vector<double>{0.0, 1 / 24.0f, 2 / 24.0f}));
}

// An animated bake played by vdg's own glTF reader (vdg::Rig: the morph weights, then the
// skeleton's channels) at each output frame's time, against `vdg eval --frame F --eye` with F the
// animation frame vdg render shows at that output frame.
TEST(GltfCli, AnimatedBakePlayedByTheGltfReaderEqualsVdgEval) {
  for (const std::string& model : {kWalk, kWalkWorld}) {
    vdg::testing::TempDir dir;
    constexpr int kOrbit = 45;  // more output frames than the walk's 40: frame 41 shows walk frame 1
    constexpr double kFps = 12.0;
    const Result r = run("bake " + model + " -o " + dir.file("bake.glb") + " --orbit " + std::to_string(kOrbit) +
                         " --elevation 15 --fps 12 -q");
    ASSERT_EQ(r.code, 0) << r.err;
    const auto g = decodeGlb(readText(dir.file("bake.glb")));
    const auto& anim = g.doc.at("animations").at(0);
    const auto eyes = readAccessor(g, anim.at("samplers").at(1).at("output"));
    const vdg::Rig rig = vdg::Rig::build(vdg::readGltfRig(dir.file("bake.glb")));
    std::vector<float> baked(rig.vertexCount() * 3);
    for (int f : {0, 10, 27, 41}) {
      ASSERT_TRUE(rig.evaluate(0, f / kFps, baked));
      char eye[128];
      std::snprintf(eye, sizeof eye, "%.9g,%.9g,%.9g", eyes[f * 3], eyes[f * 3 + 1], eyes[f * 3 + 2]);
      const std::string obj = dir.file("eval" + std::to_string(f) + ".obj");
      const Result e =
          run("eval " + model + " --frame " + std::to_string(f % 40) + " --eye " + eye + " -o " + obj + " -q");
      ASSERT_EQ(e.code, 0) << e.err;
      const auto expected = objPositions(readText(obj));
      ASSERT_EQ(expected.size(), baked.size());
      for (std::size_t i = 0; i < baked.size(); ++i)
        ASSERT_NEAR(baked[i], expected[i], kBakeVsEvalTol) << model << " frame " << f << " value " << i;
    }
  }
}

// vdg's own export is a model for every command that takes one; a plain glTF mesh is not.
TEST(GltfCli, ExportedGlbIsAModelForEvalInfoAndExport) {
  vdg::testing::TempDir dir;
  ASSERT_EQ(run("export " + kWalk + " -q -o " + dir.file("w.glb")).code, 0);
  // Exported again from the glTF itself.
  ASSERT_EQ(run("export " + dir.file("w.glb") + " -q -o " + dir.file("w2.gltf")).code, 0);
  for (const std::string& source : {dir.file("w.glb"), dir.file("w2.gltf")})
    for (int frame : {4, 30}) {
      const std::string args = " --frame " + std::to_string(frame) + " --view 0.4,0.2,1 -q -o ";
      ASSERT_EQ(run("eval " + kWalk + args + dir.file("a.obj")).code, 0);
      const Result e = run("eval " + source + args + dir.file("b.obj"));
      ASSERT_EQ(e.code, 0) << e.err;
      const auto a = objPositions(readText(dir.file("a.obj"))), b = objPositions(readText(dir.file("b.obj")));
      ASSERT_EQ(a.size(), b.size());
      for (std::size_t i = 0; i < a.size(); ++i) ASSERT_NEAR(a[i], b[i], kBakeVsEvalTol) << source << " " << i;
    }
  const Result info = run("info " + dir.file("w.glb"));
  ASSERT_EQ(info.code, 0) << info.err;
  EXPECT_NE(info.out.find("view-dependent model (mesh.extras.vdg)"), std::string::npos) << info.out;
  EXPECT_NE(info.out.find("40 frames at 24 fps, loop"), std::string::npos) << info.out;
  const Result plain = run("eval examples/walk/walker.glb --frame 0 --view 0,0,1 -o " + dir.file("c.obj"));
  EXPECT_EQ(plain.code, 1);
  EXPECT_NE(plain.err.find("plain mesh, not a view-dependent model"), std::string::npos) << plain.err;
  const Result plain_info = run("info examples/walk/walker.glb");
  EXPECT_EQ(plain_info.code, 0);
  EXPECT_EQ(plain_info.out.find("view-dependent model"), std::string::npos) << plain_info.out;
}

// `vdg info --json` on a glTF model vdg exported: the model's description, as for its manifest.
TEST(GltfCli, InfoJsonDescribesAnExportedModelAsItsManifestDoes) {
  vdg::testing::TempDir dir;
  for (const std::string& manifest : {kSpot, kWalk}) {
    const std::string glb = dir.file("m.glb");
    ASSERT_EQ(run("export " + manifest + " -q -o " + glb).code, 0);
    const Result from_manifest = run("info --json " + manifest), from_gltf = run("info --json " + glb);
    ASSERT_EQ(from_manifest.code, 0) << from_manifest.err;
    ASSERT_EQ(from_gltf.code, 0) << from_gltf.err;
    const auto a = nlohmann::json::parse(from_manifest.out), b = nlohmann::json::parse(from_gltf.out);
    EXPECT_EQ(b.at("model"), glb);
    for (const char* field : {"vertices", "triangles", "sharpness", "uncovered", "hull_triangles"})
      EXPECT_EQ(a.at(field), b.at(field)) << manifest << ": " << field;
    ASSERT_EQ(a.contains("keys"), b.contains("keys")) << manifest;
    if (a.contains("keys")) {
      ASSERT_EQ(a.at("keys").size(), b.at("keys").size()) << manifest;
      for (std::size_t k = 0; k < a.at("keys").size(); ++k)
        EXPECT_EQ(a.at("keys")[k].at("name"), b.at("keys")[k].at("name")) << manifest << " key " << k;
    }
  }
  // A plain glTF mesh is no model: --json stays a usage error there.
  EXPECT_EQ(run("info --json examples/walk/walker.glb").code, 2);
}

TEST(GltfCli, BadUsageAndBadInput) {
  vdg::testing::TempDir dir;
  EXPECT_EQ(run("export " + kSpot + " -o " + dir.file("x.obj")).code, 2);
  EXPECT_EQ(run("export " + kSpot).code, 2);
  EXPECT_EQ(run("bake " + kSpot + " -o " + dir.file("x.glb") + " --fps 0").code, 2);
  EXPECT_EQ(run("bake " + kSpot + " -o " + dir.file("x.glb") + " --orbit 4 --frames 2-4").code, 2);
  EXPECT_EQ(run("bake " + kSpot + " -o " + dir.file("x.glb") + " --size 0x1").code, 2);
  const Result r = run("export " + dir.file("missing.vdg.json") + " -o " + dir.file("x.glb"));
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("missing.vdg.json"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir.file("x.glb")));
  EXPECT_EQ(run("export " + kSpot + " -o " + dir.file("no/such/dir/x.gltf")).code, 1);
}

// A model whose base has one uv per vertex and more than 65535 vertices (so TEXCOORD_0, 32-bit
// indices and 32-bit sparse indices are all written), with a dense and a sparse key.
std::string writeGridModel(const vdg::testing::TempDir& dir) {
  constexpr int kSide = 260;  // 67600 vertices
  std::ostringstream base, dense, sparse, faces;
  for (int j = 0; j < kSide; ++j)
    for (int i = 0; i < kSide; ++i) {
      const double x = i / double(kSide - 1), y = j / double(kSide - 1);
      base << "v " << x << " " << y << " 0\n";
      dense << "v " << x << " " << y << " " << 0.1 * std::sin(6 * x) << "\n";
      sparse << "v " << x << " " << y << " " << (i == 7 && j == 250 ? 0.3 : 0.0) << "\n";
      faces << "vt " << x << " " << y << "\n";
    }
  for (int j = 0; j + 1 < kSide; ++j)
    for (int i = 0; i + 1 < kSide; ++i) {
      const int a = j * kSide + i + 1, b = a + 1, c = a + kSide, d = c + 1;
      faces << "f " << a << "/" << a << " " << b << "/" << b << " " << d << "/" << d << "\n";
      faces << "f " << a << "/" << a << " " << d << "/" << d << " " << c << "/" << c << "\n";
    }
  vdg::testing::writeText(dir.file("grid/base.obj"), base.str() + faces.str());
  vdg::testing::writeText(dir.file("grid/dense.obj"), dense.str() + faces.str());
  vdg::testing::writeText(dir.file("grid/sparse.obj"), sparse.str() + faces.str());
  vdg::testing::writeText(dir.file("grid/grid.vdg.json"),
                          R"({"version": 1, "base": "base.obj", "uncovered": "cosine", "keys": [
                             {"mesh": "dense.obj", "view": [0, 0, 1]}, {"mesh": "sparse.obj", "view": [1, 0, 1]}]})");
  return dir.file("grid/grid.vdg.json");
}

// A model on examples/meshes/teapot-parts.obj (five materials, faces interleaved between body and
// handle) with one key moving its first vertex.
std::string writeTeapotPartsModel(const vdg::testing::TempDir& dir) {
  fs::create_directories(dir.file("teapot"));
  const fs::path meshes = fs::path(VDG_SOURCE_DIR) / "examples/meshes";
  fs::copy_file(meshes / "teapot-parts.mtl", dir.file("teapot/teapot-parts.mtl"));
  const std::string obj = readText((meshes / "teapot-parts.obj").string());
  vdg::testing::writeText(dir.file("teapot/base.obj"), obj);
  const std::size_t v = obj.find("\nv ") + 1;
  vdg::testing::writeText(dir.file("teapot/key.obj"),
                          obj.substr(0, v) + "v 0 9 0\n" + obj.substr(obj.find('\n', v) + 1));
  vdg::testing::writeText(dir.file("teapot/teapot.vdg.json"),
                          R"({"version": 2, "base": "base.obj", "keys": [{"name": "up", "mesh": "key.obj",
                             "view": [0, 0, 1]}]})");
  return dir.file("teapot/teapot.vdg.json");
}

TEST(GltfCli, MaterialsArePrimitivesAndComeBackOnTheSameVertices) {
  vdg::testing::TempDir dir;
  const std::string teapot = writeTeapotPartsModel(dir);
  Result r = run("export " + teapot + " -q -o " + dir.file("t.glb"));
  ASSERT_EQ(r.code, 0) << r.err;
  const auto g = decodeGlb(readText(dir.file("t.glb")));
  const auto& prims = g.doc.at("meshes").at(0).at("primitives");
  ASSERT_EQ(prims.size(), 5u);  // body, handle, spout, knob, lid
  std::set<std::string> names;
  for (const auto& p : prims) {
    const auto& m = g.doc.at("materials").at(p.at("material").get<int>());
    names.insert(m.at("name").get<std::string>());
    EXPECT_EQ(m.at("pbrMetallicRoughness").at("metallicFactor"), 0.0);
    EXPECT_EQ(p.at("attributes"), prims.at(0).at("attributes"));  // one shared vertex list
  }
  EXPECT_EQ(names, (std::set<std::string>{"body", "handle", "spout", "knob", "lid"}));
  // Read back and exported again: the same vertices in the same order, the same materials.
  r = run("export " + dir.file("t.glb") + " -q -o " + dir.file("t2.glb"));
  ASSERT_EQ(r.code, 0) << r.err;
  const auto g2 = decodeGlb(readText(dir.file("t2.glb")));
  const auto& p2 = g2.doc.at("meshes").at(0).at("primitives");
  EXPECT_EQ(readAccessor(g2, p2.at(0).at("attributes").at("POSITION")),
            readAccessor(g, prims.at(0).at("attributes").at("POSITION")));
  EXPECT_EQ(vdg::testing::readVertexIds(g2, p2.at(0)), vdg::testing::readVertexIds(g, prims.at(0)));
  EXPECT_EQ(g2.doc.at("materials"), g.doc.at("materials"));
  for (std::size_t i = 0; i < prims.size(); ++i)
    EXPECT_EQ(readAccessor(g2, p2.at(i).at("indices")), readAccessor(g, prims.at(i).at("indices"))) << i;
}

TEST(GltfCli, TheTargetCountIsToldAndMaxTargetsRefusesAnExportOverIt) {
  vdg::testing::TempDir dir;
  Result r = run("info " + kWalkWorld + " --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto info = nlohmann::json::parse(r.out).at("export_targets");
  EXPECT_EQ(info.at("count"), 43);  // 4 keys + 39 base frames of 40
  EXPECT_EQ(info.at("base_frames"), 39);
  EXPECT_EQ(info.at("exceeds"), nlohmann::json::array());
  r = run("info " + kWalk);  // skinned offsets: the skin plays the base, no frame targets
  EXPECT_NE(r.out.find("export     4 morph targets in glTF; within every engine's cap"), std::string::npos) << r.out;
  r = run("export " + kWalkWorld + " --max-targets 42 -o " + dir.file("w.glb"));
  EXPECT_EQ(r.code, 1);
  EXPECT_EQ(r.err,
            "vdg: error: " + kWalkWorld +
                ": the export needs 43 morph targets (4 keys + 39 base frames), more than --max-targets 42; a "
                "\"world\"-offset animated model needs one target per base frame: use fewer frames, \"skinned\" "
                "offsets on a skinned glTF base (written with its skin, no frame targets), or raise --max-targets\n");
  EXPECT_FALSE(fs::exists(dir.file("w.glb")));
  r = run("bake " + kSpot + " --orbit 4 --max-targets 4 -o " + dir.file("b.glb"));
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("needs 5 morph targets (5 keys), more than --max-targets 4; use fewer keys"), std::string::npos)
      << r.err;
  EXPECT_FALSE(fs::exists(dir.file("b.glb")));
  r = run("export " + kWalkWorld + " --max-targets 43 -o " + dir.file("w.glb"));
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("43 morph targets"), std::string::npos) << r.out;
}

// The validator: $VDG_GLTF_VALIDATOR (a command taking files), else scripts/validate-gltf when it,
// node and the validator package are there. Empty when none is.
std::string validatorCommand() {
  if (const char* v = std::getenv("VDG_GLTF_VALIDATOR"); v && *v) return v;
  const fs::path script = fs::path(VDG_SOURCE_DIR) / "scripts/validate-gltf";
  const bool package = fs::exists(fs::path(VDG_SOURCE_DIR) / "tools/gltf-validator/node_modules/gltf-validator");
  if (!fs::exists(script) || !package || runShell("command -v node").code != 0) return "";
  return "'" + script.string() + "'";
}

TEST(GltfCli, EveryKindOfExportPassesTheKhronosValidator) {
  const std::string validator = validatorCommand();
  if (validator.empty()) {
    const char* required = std::getenv("VDG_REQUIRE_GLTF_VALIDATOR");
    if (required && std::string(required) == "1")
      FAIL() << "VDG_REQUIRE_GLTF_VALIDATOR=1 but the glTF validator is not installed (scripts/install-deps "
                "installs node and tools/gltf-validator)";
    GTEST_SKIP() << "the Khronos glTF validator is not installed (scripts/validate-gltf, node, "
                    "tools/gltf-validator/node_modules); set VDG_REQUIRE_GLTF_VALIDATOR=1 to make this a failure";
  }
  vdg::testing::TempDir dir;
  const std::string grid = writeGridModel(dir);
  const std::string teapot = writeTeapotPartsModel(dir);
  const std::vector<std::pair<std::string, std::string>> exports = {
      {"export " + kSpot, "spot.glb"},                                   // sparse targets, 16-bit indices
      {"export " + kSpot, "spot.gltf"},                                  // external buffer
      {"export examples/building/building.vdg.json", "building.glb"},    // a dense target
      {"export " + grid, "grid.glb"},                                    // uvs, 32-bit indices
      {"bake " + kSpot + " --orbit 12", "bake.glb"},                     // LINEAR weights + camera
      {"bake " + grid + " --orbit 5 --frames 1-3 --step", "bake.gltf"},  // STEP, external buffer
      {"export " + kWalk, "walk-skin.glb"},                              // skin, joints, copied samplers
      {"export " + kWalkWorld, "walk-frames.gltf"},                      // base frames as targets
      {"bake " + kWalk + " --orbit 8", "walk-skin-bake.glb"},            // weights + skeleton + camera
      {"bake " + kWalkWorld + " --orbit 6 --frames 2-5 --step", "walk-frames-bake.glb"},
      {"bake " + kSpot + " --camera examples/spot/swoop.camera.json --count 8", "swoop-bake.glb"},  // a path
      {"export examples/spot/spot-rbf.vdg.json", "spot-rbf.glb"},               // extras v4: the rbf interpolation
      {"bake examples/spot/spot-rbf.vdg.json --orbit 6", "spot-rbf-bake.glb"},  // every key weighed
      {"export " + teapot, "teapot.glb"},                                       // five materials, no texture
      {"export " + teapot, "teapot.gltf"},  // the textured spot.gltf writes its image beside it
      // A KHR_interactivity graph (docs/interactivity.md): base mode with dummies, cosine arcs, one key.
      {"export " + kSpot + " --interactivity", "spot-graph.glb"},
      {"export examples/figure13/head/head.vdg.json --interactivity", "head-graph.gltf"},
      {"export examples/building/building.vdg.json --interactivity", "building-graph.glb"}};
  std::string files;
  for (const auto& [args, name] : exports) {
    const Result r = run(args + " -q -o " + dir.file(name));
    ASSERT_EQ(r.code, 0) << args << ": " << r.err;
    files += " '" + dir.file(name) + "'";
  }
  const auto grid_doc = decodeGlb(readText(dir.file("grid.glb"))).doc;
  EXPECT_TRUE(grid_doc.at("meshes").at(0).at("primitives").at(0).at("attributes").contains("TEXCOORD_0"));
  // No error and no warning (--strict) for scripts/validate-gltf; infos and hints are allowed.
  const Result v = runShell(validator + (std::getenv("VDG_GLTF_VALIDATOR") ? "" : " --strict") + files);
  EXPECT_EQ(v.code, 0) << v.out << v.err;
}

// vdg export --interactivity (docs/interactivity.md): the graph is in the file, `vdg info` reports
// it, `vdg info MODEL` says how large it would be, and an animated model is refused in one line
// naming what is not supported, with nothing written.
TEST(GltfCli, InteractivityExportIsReportedAndAnimatedModelsAreRefused) {
  vdg::testing::TempDir dir;
  Result r = run("export " + kSpot + " --interactivity -o " + dir.file("spot.glb"));
  ASSERT_EQ(r.code, 0) << r.err;
  const auto doc = decodeGlb(readText(dir.file("spot.glb"))).doc;
  EXPECT_EQ(doc.at("extensionsUsed"), nlohmann::json({"KHR_interactivity"}));
  EXPECT_FALSE(doc.contains("extensionsRequired"));
  const std::size_t nodes = doc.at("extensions").at("KHR_interactivity").at("graphs").at(0).at("nodes").size();
  r = run("info " + dir.file("spot.glb"));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("KHR_interactivity: " + std::to_string(nodes) + " nodes"), std::string::npos) << r.out;
  r = run("info " + kSpot);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(
      r.out.find("graph      KHR_interactivity (vdg export --interactivity): " + std::to_string(nodes) + " nodes"),
      std::string::npos)
      << r.out;
  r = run("info " + kSpot + " --json");
  EXPECT_EQ(nlohmann::json::parse(r.out).at("interactivity").at("nodes"), nodes);
  // A plain export has no graph, and info says nothing of one.
  ASSERT_EQ(run("export " + kSpot + " -q -o " + dir.file("plain.glb")).code, 0);
  EXPECT_EQ(run("info " + dir.file("plain.glb")).out.find("KHR_interactivity:"), std::string::npos);
  // --compress keeps the graph.
  ASSERT_EQ(run("export " + kSpot + " --interactivity --compress quantize -q -o " + dir.file("q.glb")).code, 0);
  EXPECT_TRUE(decodeGlb(readText(dir.file("q.glb"))).doc.at("extensions").contains("KHR_interactivity"));
  for (const std::string& model : {kWalk, kWalkWorld}) {
    r = run("export " + model + " --interactivity -o " + dir.file("walk.glb"));
    EXPECT_EQ(r.code, 1) << r.err;
    EXPECT_EQ(r.err, "vdg: error: " + model +
                         ": --interactivity: animated models (key frames over time) are not supported; export a "
                         "static model (docs/interactivity.md, \"Limits\")\n");
    EXPECT_FALSE(fs::exists(dir.file("walk.glb")));
  }
  EXPECT_EQ(run("bake " + kSpot + " --orbit 4 --interactivity -o " + dir.file("b.glb")).code, 2);  // export only
}

// --compress quantize|meshopt (vdg/io/gltf_compress.h) on every kind of export: no error and no
// warning from the validator (it checks KHR_mesh_quantization's types, strides and bounds; it
// cannot decode EXT_meshopt_compression and says so as an info), and vdg reads each file again.
TEST(GltfCli, CompressedExportsPassTheKhronosValidator) {
  const std::string validator = validatorCommand();
  if (validator.empty()) GTEST_SKIP() << "the Khronos glTF validator is not installed (scripts/validate-gltf)";
  vdg::testing::TempDir dir;
  const std::string grid = writeGridModel(dir);
  EXPECT_EQ(run("export " + kSpot + " -o " + dir.file("x.glb") + " --compress draco").code, 2);
  // Each kind in each compression once, .glb and .gltf (external buffer, fallback buffer) both.
  const std::vector<std::pair<std::string, std::string>> exports = {
      {"export " + kSpot, "spot-quantize.glb"},  // sparse targets, 16-bit indices
      {"export " + kSpot, "spot-quantize.gltf"},
      {"export " + kSpot, "spot-meshopt.glb"},
      {"export " + kSpot, "spot-meshopt.gltf"},
      {"export " + grid, "grid-quantize.glb"},  // uvs, 32-bit indices, a sparse and a dense key
      {"export " + grid, "grid-meshopt.glb"},
      {"bake " + kSpot + " --orbit 12", "bake-meshopt.glb"},  // weights + camera
      {"export " + kWalk, "walk-skin-quantize.glb"},          // skinned: float positions
      {"export " + kWalk, "walk-skin-meshopt.gltf"},
      {"export " + kWalkWorld, "walk-frames-quantize.gltf"},  // base frames as targets
      {"export " + kWalkWorld, "walk-frames-meshopt.glb"},
      {"bake " + kWalk + " --orbit 8", "walk-skin-bake-quantize.glb"},  // weights + skeleton + camera
      {"bake " + kWalkWorld + " --orbit 6 --step", "walk-frames-bake-meshopt.glb"}};
  std::string files;
  for (const auto& [args, name] : exports) {
    const std::string compression = name.find("meshopt") != std::string::npos ? "meshopt" : "quantize";
    const Result r = run(args + " -q --compress " + compression + " -o " + dir.file(name));
    ASSERT_EQ(r.code, 0) << args << ": " << r.err;
    files += " '" + dir.file(name) + "'";
    const Result info = run("info " + dir.file(name));
    EXPECT_EQ(info.code, 0) << name << ": " << info.err;
  }
  const Result v = runShell(validator + files);
  EXPECT_EQ(v.code, 0) << v.out << v.err;
  for (const auto& [args, name] : exports)
    EXPECT_NE(v.out.find(name + ": 0 errors, 0 warnings"), std::string::npos) << name << "\n" << v.out;
}

}  // namespace

namespace {

// The extras of an export, and of a model with a camera key, against docs/schema (version 2, and 4 of
// the rbf example, which needs its kernel, width and interpolation; an
// animated export without its "time" or sphere fails it; the version 1 schema still describes a
// version 1 description; needs python3's jsonschema; skipped without it).
TEST(GltfCli, ExtrasFollowTheirJsonSchema) {
  if (runShell("python3 -c 'import jsonschema'").code != 0) GTEST_SKIP() << "python3 jsonschema is not installed";
  vdg::testing::TempDir dir;
  vdg::testing::writeText(dir.file("m/m.vdg.json"),
                          R"({"version": 1, "base": ")" VDG_SOURCE_DIR R"(/examples/spot/spot.obj", "keys": [
        {"mesh": ")" VDG_SOURCE_DIR R"(/examples/spot/keys/front.obj", "view": [0, 0, -1]},
        {"mesh": ")" VDG_SOURCE_DIR R"(/examples/spot/keys/top.obj",
         "camera": {"eye": [0, 5, 0.1], "target": [0, 0, 0], "fov_deg": 30}}]})");
  ASSERT_EQ(run("export " + dir.file("m/m.vdg.json") + " -q -o " + dir.file("m.gltf")).code, 0);
  ASSERT_EQ(run("bake " + kSpot + " -q --orbit 3 -o " + dir.file("b.gltf")).code, 0);
  ASSERT_EQ(run("export " + kWalk + " -q -o " + dir.file("w.gltf")).code, 0);
  ASSERT_EQ(run("bake " + kWalkWorld + " -q --orbit 3 -o " + dir.file("ww.gltf")).code, 0);
  ASSERT_EQ(run("export " VDG_SOURCE_DIR "/examples/spot/spot-rbf.vdg.json -q -o " + dir.file("r.gltf")).code, 0);
  const std::string check =
      "python3 -c 'import json, sys, jsonschema\n"
      "schema = json.load(open(sys.argv[1]))\n"
      "jsonschema.Draft202012Validator.check_schema(schema)\n"
      "for f in sys.argv[2:]:\n"
      "    jsonschema.validate(json.load(open(f))[\"meshes\"][0][\"extras\"], schema)\n"
      "def refused(change):\n"
      "    bad = json.load(open(sys.argv[4]))[\"meshes\"][0][\"extras\"]\n"
      "    change(bad[\"vdg\"])\n"
      "    try:\n"
      "        jsonschema.validate(bad, schema)\n"
      "        sys.exit(3)\n"
      "    except jsonschema.ValidationError:\n"
      "        pass\n"
      "refused(lambda v: v.update(uncovered=\"nowhere\"))\n"
      "refused(lambda v: v.pop(\"sphere\"))\n"
      "refused(lambda v: v.pop(\"time\"))\n"
      "refused(lambda v: v[\"sphere\"][\"inverses\"].append([1, 2]))\n"
      "refused(lambda v: v.update(version=1))\n"
      "def refused_rbf(change):\n"
      "    bad = json.load(open(sys.argv[6]))[\"meshes\"][0][\"extras\"]\n"
      "    change(bad[\"vdg\"])\n"
      "    try:\n"
      "        jsonschema.validate(bad, schema)\n"
      "        sys.exit(4)\n"
      "    except jsonschema.ValidationError:\n"
      "        pass\n"
      "refused_rbf(lambda v: v[\"sphere\"].pop(\"rbf\"))\n"
      "refused_rbf(lambda v: v[\"weights\"].pop(\"kernel\"))\n"
      "refused_rbf(lambda v: v.update(version=3))\n"
      "v1 = json.load(open(sys.argv[1].replace(\"extras.schema\", \"extras-v1.schema\")))\n"
      "jsonschema.Draft202012Validator.check_schema(v1)\n"
      "old = json.load(open(sys.argv[2]))[\"meshes\"][0][\"extras\"]\n"
      "old[\"vdg\"].update(version=1)\n"
      "old[\"vdg\"].pop(\"sphere\")\n"
      "jsonschema.validate(old, v1)\n"
      "' docs/schema/vdg-gltf-extras.schema.json '" +
      dir.file("m.gltf") + "' '" + dir.file("b.gltf") + "' '" + dir.file("w.gltf") + "' '" + dir.file("ww.gltf") +
      "' '" + dir.file("r.gltf") + "'";
  const Result r = runShell(check);
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_NE(readText(dir.file("m.gltf")).find("\"camera\""), std::string::npos);
}

}  // namespace
