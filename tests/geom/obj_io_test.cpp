#include "vdg/geom/obj_io.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "support/test_meshes.h"
#include "vdg/geom/atomic_file.h"
#include "vdg/geom/error.h"

namespace vdg {
namespace {

std::string errorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

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

TEST(AtomicFile, FailureLeavesTheOldFileUntouched) {
  testing::TempDir dir;
  const std::string path = dir.file("keep.txt");
  testing::writeText(path, "original");
  EXPECT_THROW(writeFileAtomically(path,
                                   [](std::ostream& out) {
                                     out << "half";
                                     throw Error("interrupted");
                                   }),
               Error);
  EXPECT_EQ(testing::readText(path), "original");
  // No temporary file is left behind.
  int files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir.path())) {
    (void)entry;
    ++files;
  }
  EXPECT_EQ(files, 1);
}

TEST(AtomicFile, MissingFolderIsAClearError) {
  testing::TempDir dir;
  const std::string msg = errorOf([&] { writeObj(dir.file("no/such/folder/a.obj"), testing::uvSphere()); });
  EXPECT_NE(msg.find("a.obj: cannot write file"), std::string::npos) << msg;
}

}  // namespace
}  // namespace vdg
