#include "vdg/io/obj.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "support/error_of.h"
#include "support/test_meshes.h"
#include "vdg/geom/error.h"
#include "vdg/io/atomic_file.h"
#include "vdg/io/mesh.h"

namespace vdg {
namespace {

using testing::errorOf;

TEST(ObjIo, RoundTripIsExact) {
  testing::TempDir dir;
  TriMesh m = testing::uvSphere(7, 9);
  m.positions[4] = 0.1f + 1e-7f;  // a value with a long decimal form
  writeObj(dir.file("a.obj"), m, "hello\nworld");
  const TriMesh back = readObj(dir.file("a.obj"));
  EXPECT_EQ(back.positions, m.positions);
  EXPECT_EQ(back.triangles, m.triangles);
  EXPECT_EQ(testing::readText(dir.file("a.obj")).rfind("# hello\n# world\n", 0), 0u);
}

TEST(ObjIo, PolygonsAreTriangulatedAndUvsKeptWithTheirOwnIndices) {
  testing::TempDir dir;
  testing::writeText(dir.file("quad.obj"),
                     "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
                     "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvt 0.5 0.5\n"
                     "f 1/1 2/2 3/3 4/4\n");
  const TriMesh m = readObj(dir.file("quad.obj"));
  EXPECT_EQ(m.vertexCount(), 4u);
  EXPECT_EQ(m.triangleCount(), 2u);
  EXPECT_EQ(m.uvs.size(), 10u);
  ASSERT_EQ(m.uv_triangles.size(), 6u);
  // Round trip keeps them.
  writeObj(dir.file("out.obj"), m);
  const TriMesh back = readObj(dir.file("out.obj"));
  EXPECT_EQ(back.uv_triangles, m.uv_triangles);
  EXPECT_EQ(back.uvs, m.uvs);
}

// A face of many corners is fanned from its first corner in one pass (n - 2 triangles), not ear
// clipped (O(n^2) to O(n^3)): the counts below are the property; the hostile harness's watchdog is
// the safety net for the time.
TEST(ObjIo, AFaceOfAMillionCornersIsFannedInLinearTime) {
  constexpr std::size_t kCorners = 1000000;
  std::string text = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf";
  text.reserve(text.size() + 2 * kCorners + 1);
  for (std::size_t i = 0; i < kCorners; ++i) text += i % 4 == 0 ? " 1" : i % 4 == 1 ? " 2" : i % 4 == 2 ? " 3" : " 4";
  text += "\n";
  const TriMesh m = parseObj(text, "big.obj");
  ASSERT_EQ(m.triangleCount(), kCorners - 2);
  for (std::size_t f = 0; f < m.triangleCount(); ++f) {
    ASSERT_EQ(m.triangles[3 * f], 0) << "triangle " << f << " is not part of the fan from corner 1";
    ASSERT_EQ(m.triangles[3 * f + 1], static_cast<std::int32_t>((f + 1) % 4));
    ASSERT_EQ(m.triangles[3 * f + 2], static_cast<std::int32_t>((f + 2) % 4));
  }
}

// Up to 16 corners a face is still ear clipped, so a non-convex face keeps its shape; from 17 on it
// is a fan from corner 1 (exact for convex faces).
TEST(ObjIo, SmallFacesAreEarClippedLargeOnesFanned) {
  const auto polygon = [](std::size_t n) {
    std::string text;
    for (std::size_t i = 0; i < n; ++i) {
      const double a = 2 * M_PI * static_cast<double>(i) / static_cast<double>(n);
      text += "v " + std::to_string(std::cos(a)) + " " + std::to_string(std::sin(a)) + " 0\n";
    }
    text += "f";
    for (std::size_t i = 1; i <= n; ++i) text += " " + std::to_string(i);
    return text + "\n";
  };
  for (const std::size_t n : {5u, 16u, 17u, 200u}) {
    const TriMesh m = parseObj(polygon(n), "polygon.obj");
    EXPECT_EQ(m.triangleCount(), n - 2) << n << " corners";
  }
  const TriMesh fanned = parseObj(polygon(17), "polygon.obj");
  for (std::size_t f = 0; f < fanned.triangleCount(); ++f) EXPECT_EQ(fanned.triangles[3 * f], 0);
}

TEST(ObjIo, ReadsTheShippedExampleWithoutReordering) {
  const TriMesh m = readObj(std::string(VDG_SOURCE_DIR) + "/examples/spot/spot.obj");
  EXPECT_EQ(m.vertexCount(), 2930u);
  EXPECT_EQ(m.triangleCount(), 5856u);
  EXPECT_FLOAT_EQ(m.positions[0], 0.348799f);  // first 'v' line of the file
}

TEST(ObjIo, BadInputNamesTheFile) {
  testing::TempDir dir;
  EXPECT_NE(errorOf([&] { readObj(dir.file("missing.obj")); }).find("missing.obj: no such file"), std::string::npos);
  testing::writeText(dir.file("empty.obj"), "v 0 0 0\n");
  EXPECT_NE(errorOf([&] { readObj(dir.file("empty.obj")); }).find("empty.obj: OBJ file has no faces"),
            std::string::npos);
  testing::writeText(dir.file("range.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n");
  const std::string range = errorOf([&] { readObj(dir.file("range.obj")); });
  EXPECT_NE(range.find("range.obj"), std::string::npos) << range;
  EXPECT_NE(errorOf([&] { readMesh(dir.file("x.ply")); }).find("unsupported mesh format '.ply'"), std::string::npos);
}

// Lines a lenient reader turns silently into a different shape: each is an error naming the line.
TEST(ObjIo, StrictLinesNameTheLine) {
  const std::string tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
  const std::pair<std::string, std::string> cases[] = {
      {"v nan 1 1\n" + tri + "f 1 2 3\n", "m.obj:1: vertex 1: coordinate 'nan' is not a finite number"},
      {tri + "v inf 1 1\nf 1 2 3\n", "m.obj:4: vertex 4: coordinate 'inf' is not a finite number"},
      {tri + "v 1 2\nf 1 2 3\n", "m.obj:4: vertex 4: expected 3 coordinates x y z, got 2"},
      {tri + "v 1 2 1e999\nf 1 2 3\n", "m.obj:4: vertex 4: coordinate '1e999' is out of range"},
      {tri + "v 1 2 1e300\nf 1 2 3\n", "m.obj:4: vertex 4: coordinate '1e300' is too large for a float"},
      {tri + "v 1 2 x\nf 1 2 3\n", "m.obj:4: vertex 4: 'x' is not a number"},
      {tri + "f 1 2 99999999999999999999\n", "m.obj:4: face: vertex index '99999999999999999999' is out of range"},
      {tri + "f 1 2 4294967299\n", "m.obj:4: face: vertex index '4294967299' is out of range"},
      {tri + "f 1 2 7\n", "m.obj:4: a face refers to vertex 7 but the file has 3 vertices"},
      {tri + "f 1 2 0\n", "m.obj:4: face: vertex index 0 (OBJ indices start at 1)"},
      {tri + "f 1 2 -4\n", "m.obj:4: face: relative vertex index -4 reaches before the first vertex (3 read so far)"},
      {tri + "f 1 2 3.5\n", "m.obj:4: face: vertex index '3.5' is not a whole number"},
      {tri + "f 1 2\n", "m.obj:4: face: expected at least 3 corners, got 2"},
      {tri + "f 1/1 2/1 3/1\n", "m.obj:4: a face refers to texture coordinate 1 but the file has 0"},
      {tri + "f 1//x 2 3\n", "m.obj:4: face: normal index 'x' is not a whole number"},
      {tri, "m.obj: OBJ file has no faces"},
  };
  for (const auto& [text, expected] : cases) EXPECT_EQ(errorOf([&] { parseObj(text, "m.obj"); }), expected) << text;
}

TEST(ObjIo, RelativeIndicesAndCommentsStillRead) {
  const TriMesh m = parseObj("# a triangle\nv 0 0 0 # origin\nv 1 0 0\nv 0 1 0\r\nf -3 -2 -1\n", "m.obj");
  EXPECT_EQ(m.triangles, (std::vector<std::int32_t>{0, 1, 2}));
}

// tinyobjloader's own number parser overflows on these (an int exponent, a double mantissa); vdg
// reads them as any strict parser would.
TEST(ObjIo, LongExponentsAndMantissasReadAsTheirValues) {
  testing::TempDir dir;
  const std::string zeros(400, '0');
  testing::writeText(dir.file("n.obj"), "v 0e2147483648 1" + zeros + "e-400 -0.000" + zeros +
                                            "25e404\n"
                                            "v 1 0E+0000000000000000000002 0\nv 0 1 0\nf 1 2 3\n");
  const TriMesh m = readObj(dir.file("n.obj"));
  ASSERT_EQ(m.vertexCount(), 3u);
  EXPECT_EQ(m.positions[0], 0.0f);
  EXPECT_EQ(m.positions[1], 1.0f);
  EXPECT_FLOAT_EQ(m.positions[2], -2.5f);
  EXPECT_EQ(m.positions[3], 1.0f);
}

TEST(ObjIo, StatementsVdgDoesNotUseAreIgnored) {
  // Skin weights, tags, lines and points are not read: a huge joint id (once undefined behaviour
  // inside tinyobjloader, found by fuzz_obj) or a tag asking for thousands of values changes nothing.
  const TriMesh m = parseObj(
      "vw 2 1.5E21 2\nt crease 8192/8192/8192 1 2\nl 1 2\np 1\ns 1\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "m.obj");
  EXPECT_EQ(m.vertexCount(), 3u);
  EXPECT_EQ(m.triangles, (std::vector<std::int32_t>{0, 1, 2}));
}

// Material libraries and textures (what is opened, refused and warned about): materials_test.cpp.

TEST(ObjIo, NonRegularFilesAreRefused) {
  EXPECT_EQ(errorOf([] { readObj("/dev/zero"); }), "/dev/zero: is a character device, not a mesh file");
  testing::TempDir dir;
  EXPECT_EQ(errorOf([&] { readMesh(dir.path().string()); }).find("is a folder") != std::string::npos ||
                errorOf([&] { readMesh(dir.path().string()); }).find("unsupported mesh format") != std::string::npos,
            true);
  EXPECT_EQ(errorOf([&] { readMesh(dir.file("UPPER.OBJ")); }), dir.file("UPPER.OBJ") + ": no such file (mesh)");
}

TEST(AtomicFile, MissingFolderIsAClearError) {
  testing::TempDir dir;
  const std::string msg = errorOf([&] { writeObj(dir.file("no/such/folder/a.obj"), testing::uvSphere()); });
  EXPECT_NE(msg.find("a.obj: cannot write file"), std::string::npos) << msg;
}

}  // namespace
}  // namespace vdg
