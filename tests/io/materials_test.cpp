// Materials, textures and file normals of the mesh readers: OBJ `vn`, `mtllib`/`usemtl` with MTL
// `newmtl`/`Kd`/`map_Kd`, glTF materials (baseColorFactor, baseColorTexture) and NORMAL, the uv
// origin, the image decoder's limits, and every broken or refused file as ONE warning (or, strict,
// the same line as an error) with the surface falling back.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "support/base64.h"
#include "support/error_of.h"
#include "support/test_meshes.h"
#include "support/tiny_png.h"
#include "vdg/geom/error.h"
#include "vdg/io/gltf.h"
#include "vdg/io/gltf_export.h"
#include "vdg/io/image_file.h"
#include "vdg/io/mesh.h"
#include "vdg/io/model.h"
#include "vdg/io/obj.h"

namespace vdg {
namespace {

namespace fs = std::filesystem;
using testing::errorOf;

// Colours are stored as floats; the values compared were written with at most 7 digits.
constexpr float kColorTol = 1e-6f;
constexpr float kNormalTol = 1e-6f;

const fs::path kGltfData = fs::path(VDG_SOURCE_DIR) / "tests/data/gltf";
const fs::path kSharedGltf = fs::path(VDG_SOURCE_DIR) / "../shared/assets/gltf";

const std::string kTriangle = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\n";

// 2 x 1 RGBA: a red pixel and a half-transparent blue one.
std::string redBluePng() { return testing::tinyPng(2, 1, 4, {255, 0, 0, 255, 0, 0, 255, 128}); }

// Reads with warnings collected.
struct Read {
  TriMesh mesh;
  std::vector<std::string> warnings;
};
Read readWithWarnings(const std::string& path, bool materials = true) {
  Read r;
  MeshReadOptions options;
  options.materials = materials;
  options.warnings = &r.warnings;
  r.mesh = readMesh(path, options);
  return r;
}
std::string strictError(const std::string& path) {
  MeshReadOptions options;
  options.strict = true;
  return errorOf([&] { readMesh(path, options); });
}

// ---------------------------------------------------------------------------------------------
// Images

TEST(ImageFile, PngDecodesToRgbaTopRowFirst) {
  const TextureImage rgba = decodeImage(redBluePng(), "t.png");
  EXPECT_EQ(rgba.width, 2);
  EXPECT_EQ(rgba.height, 1);
  EXPECT_EQ(rgba.rgba, (std::vector<std::uint8_t>{255, 0, 0, 255, 0, 0, 255, 128}));
  // RGB gains an opaque alpha; rows stay top first.
  const TextureImage rgb = decodeImage(testing::tinyPng(1, 2, 3, {10, 20, 30, 40, 50, 60}), "t.png");
  EXPECT_EQ(rgb.rgba, (std::vector<std::uint8_t>{10, 20, 30, 255, 40, 50, 60, 255}));
  EXPECT_EQ(imageFormatOf(redBluePng()), ImageFormat::kPng);
}

TEST(ImageFile, JpegDecodes) {
  const TextureImage jpg = readImageFile((kGltfData / "MorphPrimitivesTest/uv_texture.jpg").string());
  EXPECT_EQ(jpg.width, 512);
  EXPECT_EQ(jpg.height, 512);
  EXPECT_EQ(jpg.rgba.size(), 512u * 512u * 4u);
  for (std::size_t i = 3; i < jpg.rgba.size(); i += 4) ASSERT_EQ(jpg.rgba[i], 255) << "JPEG has no alpha";
}

TEST(ImageFile, OtherFormatsAreRefusedByTheirBytes) {
  EXPECT_EQ(errorOf([] { decodeImage("GIF89a\x01\x00\x01\x00", "t.png"); }),
            "t.png: not a PNG or JPEG file (vdg reads only those)");
  EXPECT_EQ(errorOf([] { decodeImage("", "e.jpg"); }), "e.jpg: not a PNG or JPEG file (vdg reads only those)");
  EXPECT_EQ(errorOf([] { decodeImage("BM\x36\x00\x00\x00", "t.bmp"); }),
            "t.bmp: not a PNG or JPEG file (vdg reads only those)");
}

TEST(ImageFile, SizesOutsideTheLimitsAreRefusedBeforeDecoding) {
  const std::vector<std::uint8_t> pixel{1, 2, 3};
  EXPECT_EQ(errorOf([&] { decodeImage(testing::tinyPng(1, 1, 3, pixel, 100000, 2), "huge.png"); }),
            "huge.png: 100000x2 pixels, outside 1 to 16384 a side");
  EXPECT_EQ(errorOf([&] { decodeImage(testing::tinyPng(1, 1, 3, pixel, 9000, 9000), "big.png"); }),
            "big.png: 9000x9000 pixels, more than the limit of 67108864 pixels");
  ImageLimits small;
  small.max_side = 1;
  EXPECT_EQ(errorOf([&] { decodeImage(redBluePng(), "t.png", small); }), "t.png: 2x1 pixels, outside 1 to 1 a side");
  small = {};
  small.max_file_bytes = 10;
  EXPECT_NE(errorOf([&] { decodeImage(redBluePng(), "t.png", small); }).find("more than the limit of 10"),
            std::string::npos);
}

TEST(ImageFile, BrokenDataGivesTheDecodersReason) {
  const std::string png = redBluePng();
  const std::string cut = png.substr(0, png.size() - 20);  // IDAT cut short
  const std::string message = errorOf([&] { decodeImage(cut, "cut.png"); });
  EXPECT_EQ(message.rfind("cut.png: cannot decode the PNG (", 0), 0u) << message;
  const std::string header_only = png.substr(0, 12);
  EXPECT_EQ(errorOf([&] { decodeImage(header_only, "h.png"); }).rfind("h.png: cannot read the PNG header (", 0), 0u);
}

TEST(ImageFile, FilesAreReadWithTheLimitsOfInputFiles) {
  testing::TempDir dir;
  ASSERT_EQ(::mkfifo(dir.file("fifo.png").c_str(), 0600), 0);
  EXPECT_EQ(errorOf([&] { readImageFile(dir.file("fifo.png"), "texture"); }),
            dir.file("fifo.png") + ": is a FIFO (named pipe), not a texture file");
  EXPECT_EQ(errorOf([&] { readImageFile(dir.file("none.png"), "texture"); }),
            dir.file("none.png") + ": no such file (texture)");
}

// ---------------------------------------------------------------------------------------------
// OBJ normals

TEST(ObjNormals, EveryCornersNormalIsKeptWithItsOwnIndexAndMadeUnit) {
  const TriMesh m = parseObj(
      "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvn 0 0 2\nvn 3 4 0\nvn 0 0 0\n"
      "f 1//1 2//1 3//2\nf 2//3 4//1 3//2\n",
      "n.obj");
  ASSERT_EQ(m.normals.size(), 9u);
  EXPECT_EQ(m.normal_triangles, (std::vector<std::int32_t>{0, 0, 1, 2, 0, 1}));
  EXPECT_NEAR(m.normals[2], 1.0f, kNormalTol);
  EXPECT_NEAR(m.normals[3], 0.6f, kNormalTol);
  EXPECT_NEAR(m.normals[4], 0.8f, kNormalTol);
  EXPECT_EQ(m.normals[6], 0.0f);  // a zero normal has no direction to keep
  EXPECT_EQ(m.normals[8], 0.0f);
  // Huge finite components are scaled without overflowing.
  const TriMesh huge = parseObj("v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 3e38 3e38 0\nf 1//1 2//1 3//1\n", "h.obj");
  EXPECT_NEAR(huge.normals[0], std::sqrt(0.5f), kNormalTol);
  EXPECT_NEAR(huge.normals[1], std::sqrt(0.5f), kNormalTol);
}

TEST(ObjNormals, DroppedWhenACornerHasNone) {
  const TriMesh m = parseObj("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvn 0 0 1\nf 1//1 2//1 3//1\nf 2 4 3\n", "n.obj");
  EXPECT_TRUE(m.normals.empty());
  EXPECT_TRUE(m.normal_triangles.empty());
  EXPECT_EQ(m.triangleCount(), 2u);
}

// ---------------------------------------------------------------------------------------------
// OBJ materials

TEST(ObjMaterials, UsemtlAndMtlGiveColoursAndTexturesInTheOrderOfFirstUse) {
  testing::TempDir dir;
  testing::writeText(dir.file("tex/rb.png"), redBluePng());
  testing::writeText(dir.file("m.mtl"),
                     "# materials\nnewmtl unused\nKd 0 1 0\n\nnewmtl white paint   \nKd 0.25\n"
                     "newmtl Red\nKa 1 1 1\nKd 1 0 0.5  # a comment\nmap_Kd -s 1 1 1 -clamp on -bm 0.5 tex/rb.png\n");
  testing::writeText(dir.file("m.obj"), "mtllib m.mtl\n" + kTriangle +
                                            "f 1/1 2/2 3/3\nusemtl Red\nf 1/1 2/2 3/3\ng part\nf 1/1 2/2 3/3\n"
                                            "usemtl white paint\nf 1/1 2/2 3/3 \nusemtl Red\nf 1/1 2/2 3/3\n");
  const Read r = readWithWarnings(dir.file("m.obj"));
  EXPECT_TRUE(r.warnings.empty()) << r.warnings.front();
  const TriMesh& m = r.mesh;
  ASSERT_EQ(m.materials.size(), 2u);
  EXPECT_EQ(m.face_materials, (std::vector<std::int32_t>{-1, 0, 0, 1, 0}));
  EXPECT_EQ(m.materials[0].name, "Red");
  EXPECT_NEAR(m.materials[0].base_color[0], 1.0f, kColorTol);
  EXPECT_NEAR(m.materials[0].base_color[1], 0.0f, kColorTol);
  EXPECT_NEAR(m.materials[0].base_color[2], 0.5f, kColorTol);
  EXPECT_EQ(m.materials[0].texture_path, "tex/rb.png");
  ASSERT_NE(m.materials[0].texture, nullptr);
  EXPECT_EQ(m.materials[0].texture->rgba, decodeImage(redBluePng(), "x").rgba);
  EXPECT_EQ(m.materials[1].name, "white paint");
  for (float c : m.materials[1].base_color) EXPECT_NEAR(c, 0.25f, kColorTol);  // "Kd r" means r r r
  EXPECT_EQ(m.materials[1].texture, nullptr);
  EXPECT_TRUE(m.materials[1].texture_path.empty());
}

TEST(ObjMaterials, WithoutMaterialsNoFileIsOpened) {
  testing::TempDir dir;
  testing::writeText(dir.file("m.obj"), "mtllib missing.mtl\nusemtl x\n" + kTriangle + "f 1 2 3\n");
  const Read r = readWithWarnings(dir.file("m.obj"), /*materials=*/false);
  EXPECT_TRUE(r.warnings.empty());
  EXPECT_TRUE(r.mesh.materials.empty());
  EXPECT_TRUE(r.mesh.face_materials.empty());
}

TEST(ObjMaterials, ColoursAreClampedAndTheFirstDefinitionWins) {
  testing::TempDir dir;
  testing::writeText(dir.file("a.mtl"), "newmtl m\nKd 2 -1 0.5\nnewmtl m\nKd 0 0 0\n");
  testing::writeText(dir.file("b.mtl"), "newmtl m\nKd 0.1 0.1 0.1\nnewmtl n\nKd spectral d.spd\n");
  testing::writeText(dir.file("m.obj"),
                     "mtllib a.mtl b.mtl\nmtllib a.mtl\n" + kTriangle + "usemtl m\nf 1 2 3\nusemtl n\nf 1 2 3\n");
  const Read r = readWithWarnings(dir.file("m.obj"));
  EXPECT_TRUE(r.warnings.empty());
  ASSERT_EQ(r.mesh.materials.size(), 2u);
  EXPECT_EQ(r.mesh.materials[0].base_color, (std::array<float, 3>{1, 0, 0.5f}));
  EXPECT_EQ(r.mesh.materials[1].base_color, (std::array<float, 3>{1, 1, 1}));  // "Kd spectral" is ignored
}

TEST(ObjMaterials, NumbersTinyobjloaderCannotParseAreRewrittenFirst) {
  // A long exponent overflowed an int inside tinyobjloader's number parser (fuzz_obj's finding);
  // the MTL checker hands it the shortest form of the same value.
  const auto m = parseMtl("newmtl a\nKd 0e2147483648 0e-2147483648 0.1e0000000000000000000001\n", "a.mtl");
  ASSERT_EQ(m.size(), 1u);
  EXPECT_EQ(m[0].base_color, (std::array<float, 3>{0, 0, 1}));
  EXPECT_EQ(errorOf([] { parseMtl("newmtl a\nKd 1e-2147483648 0 0\n", "a.mtl"); }),
            "a.mtl:2: Kd: '1e-2147483648' is out of range");
}

TEST(ObjMaterials, ParseMtlReadsNamesColoursAndTextureNamesAfterTheirOptions) {
  const auto m = parseMtl(
      "Kd 1 1 1\nmap_Kd early.png\nnewmtl a\r\nKd 0.5 0.25 0\r\n"
      "map_Kd -o 0.5 0.5 -mm 0 1 -s 2 -imfchan r my texture.jpg \r\nnewmtl b\nmap_Kd b.png\n",
      "a.mtl");
  ASSERT_EQ(m.size(), 2u);
  EXPECT_EQ(m[0].name, "a");
  EXPECT_EQ(m[0].base_color, (std::array<float, 3>{0.5f, 0.25f, 0}));
  EXPECT_EQ(m[0].texture_path, "my texture.jpg");
  EXPECT_EQ(m[1].texture_path, "b.png");
  EXPECT_EQ(m[1].base_color, (std::array<float, 3>{1, 1, 1}));
}

TEST(ObjMaterials, BrokenMtlLinesAreErrorsOfParseMtl) {
  EXPECT_EQ(errorOf([] { parseMtl("newmtl\n", "a.mtl"); }), "a.mtl:1: newmtl without a material name");
  EXPECT_EQ(errorOf([] { parseMtl("newmtl a\nKd 1 2\n", "a.mtl"); }),
            "a.mtl:2: Kd: expected 1 or 3 numbers (r [g b]), got 2");
  EXPECT_EQ(errorOf([] { parseMtl("newmtl a\nKd\n", "a.mtl"); }),
            "a.mtl:2: Kd: expected 1 or 3 numbers (r [g b]), got none");
  EXPECT_EQ(errorOf([] { parseMtl("newmtl a\nKd 1 x 1\n", "a.mtl"); }), "a.mtl:2: Kd: 'x' is not a number");
  EXPECT_EQ(errorOf([] { parseMtl("newmtl a\nKd 1 nan 1\n", "a.mtl"); }), "a.mtl:2: Kd: 'nan' is not a finite number");
  EXPECT_EQ(errorOf([] { parseMtl("newmtl a\nKd 1e39 0 0\n", "a.mtl"); }),
            "a.mtl:2: Kd: '1e39' is too large for a float");
  EXPECT_EQ(errorOf([] { parseMtl("newmtl a\nmap_Kd -clamp on\n", "a.mtl"); }), "a.mtl:2: map_Kd without a file name");
}

TEST(ObjMaterials, AMissingLibraryIsOneWarningAndTheFacesHaveNoMaterial) {
  testing::TempDir dir;
  testing::writeText(dir.file("m.obj"),
                     "# cube\nmtllib gone.mtl\nusemtl a\n" + kTriangle + "f 1 2 3\nusemtl b\nf 1 2 3\n");
  const Read r = readWithWarnings(dir.file("m.obj"));
  const std::string expected = dir.file("m.obj") + ":2: mtllib: " + dir.file("gone.mtl") +
                               ": no such file (material library); its materials are not used";
  EXPECT_EQ(r.warnings, std::vector<std::string>{expected});
  EXPECT_TRUE(r.mesh.materials.empty());
  EXPECT_TRUE(r.mesh.face_materials.empty());
  EXPECT_EQ(r.mesh.triangleCount(), 2u);
  EXPECT_EQ(strictError(dir.file("m.obj")), expected);
}

TEST(ObjMaterials, ABrokenLibraryIsOneWarningNamingItsLine) {
  testing::TempDir dir;
  testing::writeText(dir.file("m.mtl"), "newmtl a\nKd 1 zero 0\n");
  testing::writeText(dir.file("m.obj"), "mtllib m.mtl\nusemtl a\n" + kTriangle + "f 1 2 3\n");
  const Read r = readWithWarnings(dir.file("m.obj"));
  const std::string expected = dir.file("m.obj") + ":1: mtllib: " + dir.file("m.mtl") +
                               ":2: Kd: 'zero' is not a number; its materials are not used";
  EXPECT_EQ(r.warnings, std::vector<std::string>{expected});
  EXPECT_TRUE(r.mesh.materials.empty());
  EXPECT_EQ(strictError(dir.file("m.obj")), expected);
}

TEST(ObjMaterials, LibrariesOutsideTheFolderOrNotRegularFilesAreRefused) {
  testing::TempDir dir;
  ASSERT_EQ(::mkfifo(dir.file("fifo.mtl").c_str(), 0600), 0);
  testing::writeText(dir.file("m.obj"),
                     "mtllib /dev/zero\nmtllib ../up.mtl\nmtllib http://x/y.mtl\nmtllib fifo.mtl\n"
                     "mtllib dir\\m.mtl\nusemtl a\n" +
                         kTriangle + "f 1 2 3\n");
  const Read r = readWithWarnings(dir.file("m.obj"));
  const std::string obj = dir.file("m.obj");
  const std::string rule = " (material libraries must lie in the OBJ file's folder or below); not read";
  EXPECT_EQ(r.warnings, (std::vector<std::string>{
                            obj + ":1: mtllib '/dev/zero' is an absolute path" + rule,
                            obj + ":2: mtllib '../up.mtl' has a '..' component" + rule,
                            obj + ":3: mtllib 'http://x/y.mtl' has a ':' (a URI scheme or a drive letter)" + rule,
                            obj + ":4: mtllib: " + dir.file("fifo.mtl") +
                                ": is a FIFO (named pipe), not a material library file; its materials are not used",
                            obj + ":5: mtllib 'dir\\m.mtl' has a backslash" + rule}));
  EXPECT_EQ(strictError(dir.file("m.obj")), r.warnings.front());
}

TEST(ObjMaterials, UndefinedNamesAreOneWarning) {
  testing::TempDir dir;
  testing::writeText(dir.file("m.mtl"), "newmtl a\nKd 1 0 0\n");
  testing::writeText(dir.file("m.obj"),
                     "mtllib m.mtl\n" + kTriangle + "usemtl a\nf 1 2 3\nusemtl b\nf 1 2 3\nusemtl c\nf 1 2 3\n");
  const Read r = readWithWarnings(dir.file("m.obj"));
  EXPECT_EQ(r.warnings, std::vector<std::string>{
                            dir.file("m.obj") + ":10: usemtl 'b' (and 1 more names) is defined in no material library; "
                                                "those faces have no material"});
  EXPECT_EQ(r.mesh.face_materials, (std::vector<std::int32_t>{0, -1, -1}));
  testing::writeText(dir.file("n.obj"), "usemtl x\n" + kTriangle + "f 1 2 3\n");
  EXPECT_EQ(
      readWithWarnings(dir.file("n.obj")).warnings,
      std::vector<std::string>{dir.file("n.obj") +
                               ":1: usemtl 'x' without a material library (mtllib); those faces have no material"});
}

TEST(ObjMaterials, TexturesThatCannotBeUsedAreOneWarningEachAndTheColourStays) {
  testing::TempDir dir;
  testing::writeText(dir.file("sub/m.mtl"),
                     "newmtl a\nKd 1 0 0\nmap_Kd gone.png\nnewmtl b\nmap_Kd gone.png\n"
                     "newmtl c\nmap_Kd ../up.png\nnewmtl d\nmap_Kd text.png\n");
  testing::writeText(dir.file("sub/text.png"), "not an image");
  testing::writeText(dir.file("m.obj"),
                     "mtllib sub/m.mtl\n" + kTriangle +
                         "usemtl a\nf 1 2 3\nusemtl b\nf 1 2 3\nusemtl c\nf 1 2 3\nusemtl d\nf 1 2 3\n");
  const Read r = readWithWarnings(dir.file("m.obj"));
  const std::string mtl = dir.file("sub/m.mtl");
  EXPECT_EQ(r.warnings,
            (std::vector<std::string>{
                mtl + ":3: map_Kd: " + dir.file("sub/gone.png") +
                    ": no such file (texture); material 'a' shows its colour alone",
                mtl + ":7: map_Kd '../up.png' has a '..' component (textures must lie in the material library's folder "
                      "or below); material 'c' shows its colour alone",
                mtl + ":9: map_Kd: " + dir.file("sub/text.png") +
                    ": not a PNG or JPEG file (vdg reads only those); material 'd' shows its colour alone"}));
  ASSERT_EQ(r.mesh.materials.size(), 4u);
  EXPECT_EQ(r.mesh.materials[0].base_color, (std::array<float, 3>{1, 0, 0}));
  for (const Material& m : r.mesh.materials) {
    EXPECT_EQ(m.texture, nullptr);
    EXPECT_FALSE(m.texture_path.empty());
  }
  EXPECT_EQ(strictError(dir.file("m.obj")), r.warnings.front());
}

TEST(ObjMaterials, ATextureSharedByMaterialsIsDecodedOnce) {
  testing::TempDir dir;
  testing::writeText(dir.file("rb.png"), redBluePng());
  testing::writeText(dir.file("m.mtl"), "newmtl a\nmap_Kd rb.png\nnewmtl b\nmap_Kd rb.png\n");
  testing::writeText(dir.file("m.obj"), "mtllib m.mtl\n" + kTriangle + "usemtl a\nf 1 2 3\nusemtl b\nf 1 2 3\n");
  const TriMesh m = readObj(dir.file("m.obj"));
  ASSERT_EQ(m.materials.size(), 2u);
  ASSERT_NE(m.materials[0].texture, nullptr);
  EXPECT_EQ(m.materials[0].texture, m.materials[1].texture);
}

TEST(ObjMaterials, ParseObjReadsLibrariesFromTheFolderOfItsSource) {
  testing::TempDir dir;
  testing::writeText(dir.file("m.mtl"), "newmtl a\nKd 0 0 1\n");
  const TriMesh m = parseObj("mtllib m.mtl\nusemtl a\n" + kTriangle + "f 1 2 3\n", dir.file("any.obj"));
  ASSERT_EQ(m.materials.size(), 1u);
  EXPECT_EQ(m.materials[0].base_color, (std::array<float, 3>{0, 0, 1}));
}

TEST(ObjMaterials, TooManyNamesIsAnErrorOfTheObj) {
  std::string text = kTriangle;
  for (std::size_t i = 0; i <= kMaxObjMaterials; ++i) text += "usemtl m" + std::to_string(i) + "\n";
  text += "f 1 2 3\n";
  EXPECT_EQ(errorOf([&] { parseObj(text, "m.obj"); }),
            "m.obj:" + std::to_string(6 + kMaxObjMaterials + 1) + ": usemtl: more than 65536 material names");
}

// ---------------------------------------------------------------------------------------------
// glTF

std::string floats(std::initializer_list<float> values) {
  std::string out;
  for (float f : values) out.append(reinterpret_cast<const char*>(&f), 4);
  return out;
}

// One triangle with NORMAL and TEXCOORD_0, one material; `material` and `images` are JSON.
std::string triangleGltf(const std::string& material, const std::string& images, int texcoord_set = 0) {
  const std::string buffer = floats({0, 0, 0, 1, 0, 0, 0, 1, 0}) + floats({0, 0, 2, 0, 0, 1, 0, 0, 1}) +
                             floats({0.25f, 0.0f, 1.0f, 0.0f, 0.0f, 0.75f});
  return R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
    "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1, "TEXCOORD_)" +
         std::to_string(texcoord_set) + R"(": 2}, "material": 0}]}],
    "materials": [)" +
         material + R"(], "textures": [{"source": 0}], "images": [)" + images + R"(],
    "buffers": [{"byteLength": 96, "uri": "data:application/octet-stream;base64,)" +
         testing::encode64(buffer) + R"("}],
    "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36}, {"buffer": 0, "byteOffset": 36, "byteLength": 36},
                    {"buffer": 0, "byteOffset": 72, "byteLength": 24}],
    "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3"},
                  {"bufferView": 1, "componentType": 5126, "count": 3, "type": "VEC3"},
                  {"bufferView": 2, "componentType": 5126, "count": 3, "type": "VEC2"}]})";
}

TEST(GltfMaterials, FactorIsEncodedToSrgbTextureDecodedUvsFlippedNormalsKept) {
  testing::TempDir dir;
  testing::writeText(dir.file("rb.png"), redBluePng());
  testing::writeText(dir.file("t.gltf"),
                     triangleGltf(R"({"name": "paint", "pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.002, 1, 1],
                                       "baseColorTexture": {"index": 0}}})",
                                  R"({"uri": "rb.png"})"));
  const Read r = readWithWarnings(dir.file("t.gltf"));
  EXPECT_TRUE(r.warnings.empty()) << r.warnings.front();
  const TriMesh& m = r.mesh;
  ASSERT_EQ(m.materials.size(), 1u);
  EXPECT_EQ(m.face_materials, std::vector<std::int32_t>{0});
  EXPECT_EQ(m.materials[0].name, "paint");
  // sRGB encoding (IEC 61966-2-1): 0.5 -> 1.055 * 0.5^(1/2.4) - 0.055; the linear segment below 0.0031308.
  EXPECT_NEAR(m.materials[0].base_color[0], 1.055 * std::pow(0.5, 1 / 2.4) - 0.055, kColorTol);
  EXPECT_NEAR(m.materials[0].base_color[1], 12.92 * 0.002, kColorTol);
  EXPECT_NEAR(m.materials[0].base_color[2], 1.0f, kColorTol);
  ASSERT_NE(m.materials[0].texture, nullptr);
  EXPECT_EQ(m.materials[0].texture->width, 2);
  EXPECT_EQ(m.materials[0].texture_path, "rb.png");
  // TEXCOORD_0 (0.25, 0), (1, 0), (0, 0.75) with glTF's top-left origin: v' = 1 - v.
  EXPECT_EQ(m.uvs, (std::vector<float>{0.25f, 1.0f, 1.0f, 1.0f, 0.0f, 0.25f}));
  EXPECT_EQ(m.uv_triangles, m.triangles);
  EXPECT_EQ(m.normal_triangles, m.triangles);
  ASSERT_EQ(m.normals.size(), 9u);
  EXPECT_NEAR(m.normals[2], 1.0f, kNormalTol);  // posed and normalised
  // The rig holds the same (uvs flipped once, materials).
  const RawRig rig = readGltfRig(dir.file("t.gltf"));
  EXPECT_EQ(rig.mesh.uvs, m.uvs);
  EXPECT_EQ(rig.mesh.materials.size(), 1u);
}

TEST(GltfMaterials, DataUriImagesAreDecoded) {
  testing::TempDir dir;
  testing::writeText(dir.file("t.gltf"),
                     triangleGltf(R"({"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}})",
                                  R"({"uri": "data:image/png;base64,)" + testing::encode64(redBluePng()) + R"("})"));
  const Read r = readWithWarnings(dir.file("t.gltf"));
  EXPECT_TRUE(r.warnings.empty()) << r.warnings.front();
  ASSERT_EQ(r.mesh.materials.size(), 1u);
  EXPECT_EQ(r.mesh.materials[0].name, "materials[0]");
  EXPECT_EQ(r.mesh.materials[0].base_color, (std::array<float, 3>{1, 1, 1}));
  ASSERT_NE(r.mesh.materials[0].texture, nullptr);
  EXPECT_EQ(r.mesh.materials[0].texture->rgba, decodeImage(redBluePng(), "x").rgba);
}

TEST(GltfMaterials, TexturesThatCannotBeUsedAreWarnings) {
  testing::TempDir dir;
  const std::string textured = R"({"name": "m", "pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}})";
  auto warningsOf = [&](const std::string& gltf) {
    testing::writeText(dir.file("t.gltf"), gltf);
    const Read r = readWithWarnings(dir.file("t.gltf"));
    EXPECT_EQ(r.mesh.materials.size(), 1u);
    EXPECT_EQ(r.mesh.materials.empty() ? nullptr : r.mesh.materials[0].texture, nullptr);
    return r.warnings;
  };
  const std::string at = dir.file("t.gltf") + ": materials[0]: baseColorTexture: ";
  const std::string tail = "; material 'm' shows its colour alone";
  EXPECT_EQ(warningsOf(triangleGltf(textured, R"({"uri": "gone.png"})")),
            std::vector<std::string>{at + dir.file("gone.png") + ": no such file (texture)" + tail});
  EXPECT_EQ(warningsOf(triangleGltf(textured, R"({"uri": "/etc/passwd"})")),
            std::vector<std::string>{at +
                                     "'/etc/passwd' is an absolute path (images must lie in the glTF file's folder "
                                     "or below)" +
                                     tail});
  EXPECT_EQ(warningsOf(triangleGltf(textured, R"({"uri": "%2e%2e/x.png"})")),
            std::vector<std::string>{at +
                                     "'../x.png' has a '..' component (images must lie in the glTF file's folder "
                                     "or below)" +
                                     tail});
  EXPECT_EQ(warningsOf(triangleGltf(
                R"({"name": "m", "pbrMetallicRoughness": {"baseColorTexture": {"index": 0, "texCoord": 1}}})",
                R"({"uri": "gone.png"})", 1)),
            (std::vector<std::string>{at + "uses TEXCOORD_1; vdg maps textures by TEXCOORD_0 only" + tail}));
  EXPECT_EQ(warningsOf(triangleGltf(R"({"name": "m", "pbrMetallicRoughness": {"baseColorTexture": {"index": 5}}})",
                                    R"({"uri": "gone.png"})")),
            std::vector<std::string>{at + "texture 5 out of range (the file has 1)" + tail});
  MeshReadOptions strict;
  strict.strict = true;
  testing::writeText(dir.file("t.gltf"), triangleGltf(textured, R"({"uri": "gone.png"})"));
  EXPECT_EQ(errorOf([&] { readGltfMesh(dir.file("t.gltf"), {}, strict); }),
            at + dir.file("gone.png") + ": no such file (texture)" + tail);
}

TEST(GltfMaterials, SampleWithTwoMaterialsSharingAJpeg) {
  // MorphPrimitivesTest: primitives 'red' and 'green', both textured by uv_texture.jpg.
  const Read r = readWithWarnings((kGltfData / "MorphPrimitivesTest/MorphPrimitivesTest.gltf").string());
  EXPECT_TRUE(r.warnings.empty()) << r.warnings.front();
  ASSERT_EQ(r.mesh.materials.size(), 2u);
  EXPECT_EQ(r.mesh.materials[0].name, "red");
  EXPECT_EQ(r.mesh.materials[0].base_color, (std::array<float, 3>{1, 0, 0}));
  EXPECT_EQ(r.mesh.materials[1].base_color, (std::array<float, 3>{0, 1, 0}));
  ASSERT_NE(r.mesh.materials[0].texture, nullptr);
  EXPECT_EQ(r.mesh.materials[0].texture, r.mesh.materials[1].texture);  // one image, decoded once
  EXPECT_EQ(r.mesh.materials[0].texture->width, 512);
  EXPECT_EQ(r.mesh.face_materials.size(), r.mesh.triangleCount());
  EXPECT_FALSE(r.mesh.normals.empty());
  // Without its texture: one warning for the one image, both materials keep their colours.
  testing::TempDir dir;
  for (const char* f : {"MorphPrimitivesTest.gltf", "MorphPrimitivesTest.bin"})
    fs::copy_file(kGltfData / "MorphPrimitivesTest" / f, dir.path() / f);
  const Read bare = readWithWarnings(dir.file("MorphPrimitivesTest.gltf"));
  EXPECT_EQ(bare.warnings, std::vector<std::string>{dir.file("MorphPrimitivesTest.gltf") +
                                                    ": materials[0]: baseColorTexture: " + dir.file("uv_texture.jpg") +
                                                    ": no such file (texture); material 'red' shows its colour alone"});
  ASSERT_EQ(bare.mesh.materials.size(), 2u);
  EXPECT_EQ(bare.mesh.materials[1].base_color, (std::array<float, 3>{0, 1, 0}));
}

TEST(GltfMaterials, GlbBufferViewImagesAndPngSamples) {
  const fs::path glb = kSharedGltf / "MorphPrimitivesTest/MorphPrimitivesTest.glb";
  const fs::path stress = kSharedGltf / "MorphStressTest/MorphStressTest.gltf";
  if (!fs::exists(glb) || !fs::exists(stress)) GTEST_SKIP() << kSharedGltf << " is not there";
  const Read r = readWithWarnings(glb.string());
  EXPECT_TRUE(r.warnings.empty()) << r.warnings.front();
  ASSERT_EQ(r.mesh.materials.size(), 2u);
  ASSERT_NE(r.mesh.materials[0].texture, nullptr);
  EXPECT_EQ(r.mesh.materials[0].texture->width, 512);
  EXPECT_EQ(r.mesh.materials[0].texture_path.rfind("images[0] (bufferView", 0), 0u);
  // MorphStressTest: 'Base' textured by TinyGrid.png (its occlusion texture uses TEXCOORD_1 and
  // is not read), 'TestMaterial' by ColorSwatches.png.
  const Read s = readWithWarnings(stress.string());
  EXPECT_TRUE(s.warnings.empty()) << s.warnings.front();
  ASSERT_EQ(s.mesh.materials.size(), 2u);
  for (const Material& m : s.mesh.materials) {
    ASSERT_NE(m.texture, nullptr) << m.name;
    EXPECT_EQ(m.base_color, (std::array<float, 3>{1, 1, 1}));
  }
  EXPECT_EQ(s.mesh.materials[0].texture_path, "TinyGrid.png");
  EXPECT_EQ(s.mesh.materials[1].texture_path, "ColorSwatches.png");
}

// ---------------------------------------------------------------------------------------------
// Models: the base carries the materials; key meshes are read for their geometry only.

TEST(ModelMaterials, OnlyTheBaseReadsMaterialsAndItsWarningsReachTheCaller) {
  testing::TempDir dir;
  const std::string faces = "f 1/1 2/2 3/3\n";
  testing::writeText(dir.file("base.obj"), "mtllib base.mtl\n" + kTriangle + "usemtl red\n" + faces);
  testing::writeText(dir.file("base.mtl"), "newmtl red\nKd 1 0 0\nmap_Kd missing.png\n");
  // The key names a library that does not exist: it is never opened, so it warns nothing.
  testing::writeText(dir.file("key.obj"),
                     "mtllib nowhere.mtl\nv 0 0 0.5\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\n"
                     "usemtl red\n" +
                         faces);
  testing::writeText(dir.file("m.vdg.json"), R"({"version": 2, "base": "base.obj", "keys": [
      {"name": "k", "mesh": "key.obj", "view": [0, 0, 1]}]})");
  std::vector<std::string> warnings;
  MeshReadOptions options;
  options.warnings = &warnings;
  const RawViewDependentModel model = loadModel(dir.file("m.vdg.json"), options);
  ASSERT_EQ(model.base.materials.size(), 1u);
  EXPECT_NEAR(model.base.materials[0].base_color[0], 1.0f, kColorTol);
  EXPECT_TRUE(model.keys[0].mesh.materials.empty());
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("missing.png"), std::string::npos) << warnings[0];
  options.strict = true;
  EXPECT_NE(errorOf([&] { (void)loadModel(dir.file("m.vdg.json"), options); }).find("missing.png"), std::string::npos);
}

}  // namespace
}  // namespace vdg
