#include <gtest/gtest.h>

#include <cmath>

#include "support/test_meshes.h"
#include "vdg/geom/error.h"
#include "vdg/io/image_file.h"
#include "vdg/io/manifest.h"
#include "vdg/io/obj.h"
#include "vdg/viewdep/model.h"

namespace vdg {
namespace {

using Eigen::Vector3d;

// A folder with base.obj, a.obj and b.obj (a, b: moved copies of the base) and a manifest.
class ManifestTest : public ::testing::Test {
 protected:
  void SetUp() override {
    base_ = testing::uvSphere(6, 8);
    writeObj(dir_.file("base.obj"), base_);
    TriMesh a = base_, b = base_;
    a.positions[1] += 0.25f;
    b.positions[4] -= 0.25f;
    writeObj(dir_.file("a.obj"), a);
    writeObj(dir_.file("b.obj"), b);
  }
  std::string write(const std::string& json) {
    const std::string path = dir_.file("m.vdg.json");
    testing::writeText(path, json);
    return path;
  }
  std::string loadError(const std::string& json) {
    const std::string path = write(json);
    try {
      loadManifest(path);
    } catch (const Error& e) {
      return e.what();
    }
    return "(no error)";
  }
  testing::TempDir dir_;
  TriMesh base_;
};

constexpr const char* kGood = R"({
  "version": 1, "base": "base.obj", "sharpness": 1.5, "uncovered": "cosine2",
  "keys": [
    {"mesh": "a.obj", "view": [0, 0, 2]},
    {"name": "side", "mesh": "b.obj", "camera": {"eye": [3, 0, 0], "target": [0, 0, 0], "fov_deg": 30}}
  ]})";

TEST_F(ManifestTest, LoadsKeysViewsAndSettings) {
  const RawViewDependentModel raw = loadManifest(write(kGood));
  ASSERT_EQ(raw.keys.size(), 2u);
  EXPECT_EQ(raw.keys[0].name, "a");  // default: the mesh file's stem
  EXPECT_EQ(raw.keys[1].name, "side");
  EXPECT_DOUBLE_EQ(raw.sharpness, 1.5);
  EXPECT_EQ(raw.sphere.uncovered, Uncovered::Cosine2);
  // A camera key's view is normalize(eye - centre); the centre is the base's bounding-box centre.
  const Vector3d c = raw.resolvedCenter();
  EXPECT_NEAR((raw.keys[1].view - (Vector3d(3, 0, 0) - c).normalized()).norm(), 0.0, 1e-12);
  ASSERT_TRUE(raw.keys[1].camera.has_value());
  EXPECT_DOUBLE_EQ(raw.keys[1].camera->fov_deg, 30.0);
}

TEST_F(ManifestTest, SaveKeepsTheComment) {
  RawViewDependentModel raw = loadManifest(write(kGood));
  raw.comment = "drawn by A. Artist, sheet 3";
  saveManifest(dir_.file("copy.vdg.json"), raw);
  EXPECT_EQ(loadManifest(dir_.file("copy.vdg.json")).comment, raw.comment);
}

TEST_F(ManifestTest, ParsingReadsNoMesh) {
  // parseManifest checks the document alone: the meshes it names need not exist.
  const RawViewDependentModel raw = parseManifest(
      R"({"version": 1, "base": "nowhere/base.obj", "keys": [{"mesh": "nowhere/a.obj", "view": [0, 0, 2]}]})", "doc");
  EXPECT_EQ(raw.base_path, "nowhere/base.obj");
  ASSERT_EQ(raw.keys.size(), 1u);
  EXPECT_EQ(raw.keys[0].name, "a");
  EXPECT_EQ(raw.base.vertexCount(), 0u);
}

TEST_F(ManifestTest, SaveThenLoadGivesTheSameModel) {
  RawViewDependentModel raw = loadManifest(write(kGood));
  raw.center = Vector3d(0.1, 0.2, 0.3);
  raw.resolveViews();  // camera keys measure their view from the new centre
  saveManifest(dir_.file("copy.vdg.json"), raw);
  const RawViewDependentModel back = loadManifest(dir_.file("copy.vdg.json"));
  ASSERT_EQ(back.keys.size(), raw.keys.size());
  EXPECT_EQ(back.sphere.uncovered, raw.sphere.uncovered);
  EXPECT_EQ(back.sharpness, raw.sharpness);
  ASSERT_TRUE(back.center.has_value());
  for (std::size_t k = 0; k < raw.keys.size(); ++k) {
    EXPECT_EQ(back.keys[k].name, raw.keys[k].name);
    EXPECT_NEAR((back.keys[k].view.normalized() - raw.keys[k].view.normalized()).norm(), 0.0, 1e-12);
    EXPECT_EQ(back.keys[k].mesh.positions, raw.keys[k].mesh.positions);
  }
}

TEST_F(ManifestTest, EveryValidationErrorNamesTheFileAndTheKey) {
  struct Case {
    std::string json;
    std::string expected;
  };
  const std::vector<Case> cases = {
      {"{", "m.vdg.json: not valid JSON"},
      {"[]", "m.vdg.json: expected a JSON object"},
      {R"({"base": "base.obj", "keys": []})", "m.vdg.json: missing 'version'"},
      {R"({"version": 6, "base": "base.obj", "keys": []})",
       "m.vdg.json: 'version': this vdg reads model manifests versions 1 to 5, got 6"},
      {R"({"version": 1, "base": "base.obj", "keys": [], "colour": 1})", "m.vdg.json: unknown key 'colour'"},
      {R"({"version": 1, "base": "nope.obj", "keys": []})", "m.vdg.json: base: "},
      {R"({"version": 1, "base": "base.obj", "keys": [{"mesh": "missing.obj", "view": [0,0,1]}]})",
       "key 'missing' (keys[0]): "},
      {R"({"version": 1, "base": "base.obj", "keys": [{"mesh": "a.obj", "view": [0,0,1], "weight": 2}]})",
       "'keys'[0]: unknown key 'weight'"},
      {R"({"version": 1, "base": "base.obj", "keys": [{"mesh": "a.obj", "view": [0,0,0]}]})",
       "key 'a' (keys[0]): view direction has zero length"},
      {R"({"version": 1, "base": "base.obj", "keys": [{"mesh": "a.obj", "view": [0,0,1]}, {"mesh": "b.obj", "view": [0,0,3]}]})",
       "key 'b' (keys[1]): same view direction as key 'a'"},
      {R"({"version": 1, "base": "base.obj", "keys": [{"mesh": "a.obj", "view": [0,0,1]}, {"name": "a", "mesh": "b.obj", "view": [0,1,0]}]})",
       "another key has the same name"},
      {R"({"version": 1, "base": "base.obj", "keys": [{"mesh": "a.obj"}]})", "give exactly one of 'view'"},
      {R"({"version": 1, "base": "base.obj", "keys": [{"mesh": "a.obj", "view": [0,1]}]})",
       "key 'a' (keys[0]).'view': expected 3 numbers, got an array of 2 items"},
      {R"({"version": 1, "base": "base.obj", "keys": [{"mesh": "a.obj", "camera": {"eye": [0,0,3], "target": [0,0,0]}}]})",
       "give exactly one of 'fov_deg' (perspective) or 'ortho_height'"},
      {R"({"version": 1, "base": "base.obj", "keys": [{"mesh": "a.obj", "camera": {"eye": [0,0,0], "target": [0,0,0], "ortho_height": 2}}]})",
       "eye and target are the same point"},
      {R"({"version": 1, "base": "base.obj", "keys": [{"mesh": "a.obj", "camera": {"eye": [0,0,3], "fov_deg": 30}}]})",
       "key 'a' (keys[0]).'camera': missing key 'target'"},
      {R"({"version": 1, "base": "base.obj", "uncovered": "nearest", "keys": [{"mesh": "a.obj", "view": [0,0,1]}]})",
       "'uncovered': unknown value 'nearest'"},
      {R"({"version": 1, "base": "base.obj", "sharpness": 0, "keys": [{"mesh": "a.obj", "view": [0,0,1]}]})",
       "'sharpness' must be a positive number"},
      {R"({"version": 1, "base": "base.obj", "keys": [{"mesh": "a.obj", "view": [0,0,1], "frame": 3}]})",
       "'frame' needs an animated base model"},
      {R"({"version": 4294967297, "base": "base.obj", "keys": []})",
       "m.vdg.json: 'version': this vdg reads model manifests versions 1 to 5, got 4294967297"},
      {R"({"version": 3, "base": "base.obj", "weights": {"space": "positions"}, "keys": []})",
       "'weights'.'space': needs manifest version 4"},
      {R"({"version": 3, "base": "base.obj", "keys": [{"mesh": "a.obj", "eye": [0,0,3]}]})",
       "key 'a' (keys[0]).'eye': needs manifest version 4"},
      {R"({"version": 4, "base": "base.obj", "weights": {"space": "distances"}, "keys": []})",
       "'space': unknown value 'distances'"},
      {R"({"version": 4, "base": "base.obj", "weights": {"falloff": 2}, "keys": []})",
       "'falloff': is a setting of the 'positions' space only"},
      {R"({"version": 4, "base": "base.obj", "keys": [{"mesh": "a.obj", "eye": [0,0,3], "view": [0,0,1]}]})",
       "give exactly one of 'view' [x, y, z], 'eye' [x, y, z] or 'camera'"},
      {R"({"version": 4, "base": "base.obj", "weights": {"space": "positions"}, "keys": [{"mesh": "a.obj", "eye": [0,0,3]}, {"mesh": "b.obj", "view": [0,1,0]}]})",
       "key 'b' (keys[1]): the 'positions' weight space needs the key's eye (a 'camera' or an 'eye')"},
      {"{\"version\": " + std::string(70'000, '[') + std::string(70'000, ']') + "}",
       "m.vdg.json: JSON nested deeper than 64 levels"},
      {R"({"version": 1, "base": "", "keys": []})", "m.vdg.json: 'base': expected a mesh file name"},
      {R"({"version": 1, "base": "base.obj", "keys": [{"mesh": "a.obj", "view": [1e400, 0, 0]}]})",
       "m.vdg.json: not valid JSON"},
  };
  for (const Case& c : cases) {
    const std::string message = loadError(c.json);
    EXPECT_NE(message.find(c.expected), std::string::npos) << "expected '" << c.expected << "' in '" << message << "'";
    EXPECT_NE(message.find("m.vdg.json"), std::string::npos) << message;
  }
}

// Per-part key sets (manifest version 4, docs/weights.md): parts load, save and load again, a mask
// file is read beside the manifest, and every bad part is refused naming the part and what is wrong.
TEST_F(ManifestTest, PartsLoadSaveAndRefuseBadInput) {
  std::string mask;
  for (std::size_t v = 0; v < base_.vertexCount(); ++v) mask += v % 2 ? "0.5\n" : "1 ";
  testing::writeText(dir_.file("mask.txt"), mask);
  const std::string keys = R"("keys": [{"mesh": "a.obj", "view": [0,0,1]}, {"mesh": "b.obj", "view": [0,0,1]}])";
  const auto manifest = [&](const std::string& parts) {
    return R"({"version": 4, "base": "base.obj", )" + keys + R"(, "parts": )" + parts + "}";
  };
  const RawViewDependentModel raw = loadManifest(write(manifest(
      R"([{"name": "top", "select": {"vertices": [0, 1, 2]}, "border": 0.5, "keys": ["a"], "view": [1, 0, 0]},
          {"name": "painted", "select": {"weights": "mask.txt"}, "keys": ["b"]}])")));
  ASSERT_EQ(raw.parts.size(), 2u);
  EXPECT_EQ(raw.parts[0].vertices, (std::vector<std::int32_t>{0, 1, 2}));
  EXPECT_EQ(raw.parts[0].border, 0.5);
  ASSERT_TRUE(raw.parts[0].view.has_value());
  ASSERT_EQ(raw.parts[1].mask.size(), base_.vertexCount());
  EXPECT_EQ(raw.parts[1].mask[1], 0.5f);
  saveManifest(dir_.file("copy.vdg.json"), raw);
  EXPECT_NE(testing::readText(dir_.file("copy.vdg.json")).find("\"version\": 4"), std::string::npos);
  const RawViewDependentModel back = loadManifest(dir_.file("copy.vdg.json"));
  ASSERT_EQ(back.parts.size(), 2u);
  EXPECT_EQ(back.parts[0].keys, raw.parts[0].keys);
  EXPECT_EQ(back.parts[1].mask_path, "mask.txt");
  EXPECT_EQ(back.parts[1].mask, raw.parts[1].mask);
  // Keys of different parts may share a view; the model builds.
  EXPECT_EQ(ViewDependentModel::build(back).partCount(), 3u);

  const std::string v = std::to_string(base_.vertexCount());
  const std::vector<std::pair<std::string, std::string>> cases = {
      {R"([{"name": "p", "select": {"vertices": [0]}, "keys": ["c"]}])", "part 'p' (parts[0]): unknown key 'c'"},
      {R"([{"name": "p", "select": {"vertices": [0]}, "keys": ["a"]}, {"name": "q", "select": {"vertices": [1]}, "keys": ["a"]}])",
       "part 'q' (parts[1]): key 'a' already belongs to part 'p'"},
      {R"([{"name": "p", "select": {"vertices": [0, )" + v + R"(]}, "keys": ["a"]}])",
       "part 'p' (parts[0]): vertex " + v + " is out of range"},
      {R"([{"name": "p", "select": {"material": "skin"}, "keys": ["a"]}])", "the base has no material 'skin'"},
      {R"([{"name": "p", "select": {"weights": [2]}, "keys": ["a"]}])", "the mask has 1 values but the base has"},
      {R"([{"name": "p", "select": {"weights": "missing.txt"}, "keys": ["a"]}])", "part 'p' (parts[0]): mask"},
      {R"([{"name": "p", "select": {"vertices": [0]}, "border": -1, "keys": ["a"]}])", "'border' must be a finite"},
      {R"([{"name": "p", "select": {"vertices": [0]}, "keys": []}])", "part 'p' (parts[0]): has no keys"},
      {R"([{"name": "rest", "select": {"vertices": [0]}, "keys": ["a"]}])", "the name 'rest' is the implicit part"},
      {R"([{"name": "p", "select": {"vertices": [0]}, "keys": ["a"], "view": [0, 0, 0]}])",
       "the driving 'view' must be a finite, non-zero direction"},
      {R"([{"name": "p", "select": {"vertices": [0], "material": "x"}, "keys": ["a"]}])", "'select': expected one of"},
      {R"([{"name": "p", "select": {"vertices": [0]}, "keys": ["a"], "colour": 1}])", "unknown key 'colour'"},
      {R"([{"name": "p", "select": {"vertices": [-1]}, "keys": ["a"]}])", "'vertices'[0]"},
  };
  for (const auto& [parts, expected] : cases) {
    const std::string message = loadError(manifest(parts));
    EXPECT_NE(message.find(expected), std::string::npos) << "expected '" << expected << "' in '" << message << "'";
    EXPECT_NE(message.find("m.vdg.json"), std::string::npos) << message;
  }
  // Mask values outside [0, 1], from a file.
  std::string bad = "0.5 1.5";
  for (std::size_t i = 2; i < base_.vertexCount(); ++i) bad += " 0";
  testing::writeText(dir_.file("bad.txt"), bad);
  EXPECT_NE(loadError(manifest(R"([{"name": "p", "select": {"weights": "bad.txt"}, "keys": ["a"]}])"))
                .find("part 'p' (parts[0]): vertex 1: mask value 1.500000 is outside [0, 1]"),
            std::string::npos);
  testing::writeText(dir_.file("bad.txt"), "0.5 x");
  EXPECT_NE(loadError(manifest(R"([{"name": "p", "select": {"weights": "bad.txt"}, "keys": ["a"]}])"))
                .find("mask file 'bad.txt': value 1 is not a finite number"),
            std::string::npos);
  // Version 3 does not know parts; keys of one part must not share a view.
  EXPECT_NE(loadError(R"({"version": 3, "base": "base.obj", "keys": [], "parts": []})")
                .find("'parts': needs manifest version 4"),
            std::string::npos);
  EXPECT_NE(loadError(manifest(R"([{"name": "p", "select": {"vertices": [0]}, "keys": ["a", "b"]}])"))
                .find("part 'p' (parts[0]): key 'b' has the same view direction as key 'a'"),
            std::string::npos);
}

// Keys at distances (manifest version 4): a close-up and a wide shot from one direction, by "eye"
// and by "camera"; the model builds, saves as version 4 and loads back the same.
TEST_F(ManifestTest, PositionsSpaceLoadsSavesAndBuilds) {
  TriMesh c = base_, d = base_;
  c.positions[7] += 0.5f;
  d.positions[10] -= 0.5f;
  writeObj(dir_.file("c.obj"), c);
  writeObj(dir_.file("d.obj"), d);
  const std::string path = write(R"({
    "version": 4, "base": "base.obj", "center": [0, 0, 0], "weights": {"space": "positions", "falloff": 2.5},
    "keys": [
      {"name": "wide", "mesh": "a.obj", "eye": [0, 0, 8]},
      {"name": "close", "mesh": "b.obj", "camera": {"eye": [0, 0, 3], "target": [0, 0, 0], "fov_deg": 40}},
      {"name": "left", "mesh": "c.obj", "eye": [-6, 0, 4]},
      {"name": "top", "mesh": "d.obj", "eye": [0, 6, 4]}
    ]})");
  const RawViewDependentModel raw = loadManifest(path);
  EXPECT_EQ(raw.key_space.space, WeightSpace::Positions);
  EXPECT_DOUBLE_EQ(raw.key_space.falloff, 2.5);
  ASSERT_TRUE(raw.keys[0].eye.has_value());
  EXPECT_NEAR((raw.keys[0].view - Vector3d::UnitZ()).norm(), 0.0, 1e-12);
  const ViewDependentModel model = ViewDependentModel::build(raw);
  EXPECT_EQ(model.weightSpace(), WeightSpace::Positions);
  EXPECT_EQ(model.keySpace()->directionCount(), 3u);  // wide and close share +z
  saveManifest(dir_.file("copy.vdg.json"), raw);
  EXPECT_NE(testing::readText(dir_.file("copy.vdg.json")).find("\"version\": 4"), std::string::npos);
  const RawViewDependentModel back = loadManifest(dir_.file("copy.vdg.json"));
  EXPECT_EQ(back.key_space.space, WeightSpace::Positions);
  EXPECT_DOUBLE_EQ(back.key_space.falloff, 2.5);
  ASSERT_TRUE(back.keys[0].eye.has_value());
  EXPECT_EQ(*back.keys[0].eye, *raw.keys[0].eye);
  ASSERT_TRUE(back.keys[1].camera.has_value());
  // Three eyes in a plane are no tetrahedron: build() refuses, naming the space.
  RawViewDependentModel flat = raw;
  flat.keys.pop_back();
  try {
    (void)ViewDependentModel::build(flat);
    ADD_FAILURE() << "expected a refusal";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("at least 4 keys"), std::string::npos) << e.what();
  }
}

// A directions model saves as before (version 2 for the linear scheme, no "space").
TEST_F(ManifestTest, DirectionsModelsSaveAsBefore) {
  const RawViewDependentModel raw = loadManifest(write(kGood));
  saveManifest(dir_.file("copy.vdg.json"), raw);
  const std::string text = testing::readText(dir_.file("copy.vdg.json"));
  EXPECT_NE(text.find("\"version\": 2"), std::string::npos) << text;
  EXPECT_EQ(text.find("space"), std::string::npos) << text;
}

// Version 5: a key's reference drawing is decoded beside its mesh, written back only when a key has
// one (the writer keeps the oldest version that holds the model), and every bad drawing is one line
// naming the manifest, the key and the file.
TEST_F(ManifestTest, DrawingsLoadSaveAndRefuseBadInput) {
  TextureImage image;
  image.width = 3;
  image.height = 2;
  image.rgba.assign(3 * 2 * 4, 200);
  image.rgba[0] = 10;  // the top-left pixel's red
  testing::writeText(dir_.file("side.png"), encodePng(image, "side.png"));
  testing::writeText(dir_.file("not-an-image.png"), "hello");
  const std::string camera = R"("camera": {"eye": [3, 0, 0], "target": [0, 0, 0], "fov_deg": 30})";
  const auto manifest = [&](int version, const std::string& key_extra) {
    return R"({"version": )" + std::to_string(version) +
           R"(, "base": "base.obj", "keys": [{"mesh": "a.obj", "view": [0, 0, 2]}, {"name": "side", "mesh": "b.obj", )" +
           key_extra + "}]}";
  };
  const RawViewDependentModel raw = loadManifest(write(manifest(5, camera + R"(, "drawing": "side.png")")));
  ASSERT_EQ(raw.keys.size(), 2u);
  EXPECT_EQ(raw.keys[0].drawing, nullptr);
  EXPECT_TRUE(raw.keys[0].drawing_path.empty());
  EXPECT_EQ(raw.keys[1].drawing_path, "side.png");
  ASSERT_NE(raw.keys[1].drawing, nullptr);
  EXPECT_EQ(raw.keys[1].drawing->width, 3);
  EXPECT_EQ(raw.keys[1].drawing->height, 2);
  EXPECT_EQ(raw.keys[1].drawing->rgba[0], 10);
  // Saved as version 5 with the path as written; read back, the same drawing.
  saveManifest(dir_.file("copy.vdg.json"), raw);
  const std::string text = testing::readText(dir_.file("copy.vdg.json"));
  EXPECT_NE(text.find("\"version\": 5"), std::string::npos) << text;
  EXPECT_NE(text.find("\"drawing\": \"side.png\""), std::string::npos) << text;
  const RawViewDependentModel again = loadManifest(dir_.file("copy.vdg.json"));
  ASSERT_NE(again.keys[1].drawing, nullptr);
  EXPECT_EQ(again.keys[1].drawing->rgba, raw.keys[1].drawing->rgba);
  // Without a drawing the same model is written as before (version 2).
  RawViewDependentModel plain = raw;
  plain.keys[1].drawing_path.clear();
  plain.keys[1].drawing.reset();
  EXPECT_NE(formatManifest(plain).find("\"version\": 2"), std::string::npos);

  const std::vector<std::pair<std::string, std::string>> cases = {
      {manifest(4, camera + R"(, "drawing": "side.png")"),
       "m.vdg.json: key 'side' (keys[1]).'drawing': needs manifest version 5 (this file says \"version\": 4)"},
      {manifest(5, R"("view": [1, 0, 0], "drawing": "side.png")"),
       "m.vdg.json: key 'side' (keys[1]).'drawing': needs the key's 'camera' (the viewpoint the drawing was made "
       "from); this key is given by 'view'"},
      {manifest(5, R"("eye": [3, 0, 0], "drawing": "side.png")"), "this key is given by 'eye'"},
      {manifest(5, camera + R"(, "drawing": 7)"), "m.vdg.json: key 'side' (keys[1]).'drawing': expected a string"},
      {manifest(5, camera + R"(, "drawing": "")"),
       "m.vdg.json: key 'side' (keys[1]).'drawing': expected a PNG or JPEG file name, got an empty string"},
      {manifest(5, camera + R"(, "drawing": "missing.png")"),
       "m.vdg.json: key 'side' (keys[1]): drawing 'missing.png': "},
      {manifest(5, camera + R"(, "drawing": "not-an-image.png")"),
       "m.vdg.json: key 'side' (keys[1]): drawing 'not-an-image.png': "},
  };
  for (const auto& [json, expected] : cases) {
    const std::string message = loadError(json);
    EXPECT_NE(message.find(expected), std::string::npos) << "expected: " << expected << "\ngot: " << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
  EXPECT_NE(loadError(manifest(5, camera + R"(, "drawing": "not-an-image.png")")).find("PNG"), std::string::npos);
}

TEST_F(ManifestTest, AModelWithoutKeysLoadsButDoesNotBuild) {
  const RawViewDependentModel raw = loadManifest(write(R"({"version": 1, "base": "base.obj", "keys": []})"));
  EXPECT_TRUE(raw.keys.empty());
  try {
    ViewDependentModel::build(raw);
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("m.vdg.json: the model has no keys"), std::string::npos) << e.what();
  }
}

TEST_F(ManifestTest, KeysMustKeepTheBaseConnectivity) {
  TriMesh fewer = testing::uvSphere(5, 8);
  writeObj(dir_.file("fewer.obj"), fewer);
  EXPECT_NE(loadError(R"({"version": 1, "base": "base.obj", "keys": [{"mesh": "fewer.obj", "view": [0,0,1]}]})")
                .find("key 'fewer' (keys[0]): mesh has " + std::to_string(fewer.vertexCount()) +
                      " vertices but the base has " + std::to_string(base_.vertexCount())),
            std::string::npos);
  TriMesh flipped = base_;
  std::swap(flipped.triangles[4], flipped.triangles[5]);
  writeObj(dir_.file("flipped.obj"), flipped);
  EXPECT_NE(loadError(R"({"version": 1, "base": "base.obj", "keys": [{"mesh": "flipped.obj", "view": [0,0,1]}]})")
                .find("key 'flipped' (keys[0]): triangle 1 differs from the base's"),
            std::string::npos);
}

TEST_F(ManifestTest, NonFiniteKeyCoordinatesAreRejected) {
  RawViewDependentModel raw = loadManifest(write(kGood));
  raw.keys[1].mesh.positions[3 * 5 + 2] = std::numeric_limits<float>::infinity();
  try {
    raw.validate();
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("key 'side' (keys[1]): vertex 5 has a non-finite coordinate"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace vdg
