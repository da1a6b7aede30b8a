// Opening any input (vdg/io/model.h): what each kind of file is said to be and what is loaded, the
// mesh reader by extension (vdg/io/mesh.h), and the table of versioned formats (vdg/io/formats.h).
#include <gtest/gtest.h>

#include <filesystem>
#include <set>
#include <string>

#include "support/error_of.h"
#include "support/test_meshes.h"
#include "vdg/geom/error.h"
#include "vdg/io/formats.h"
#include "vdg/io/gltf_export.h"
#include "vdg/io/manifest.h"
#include "vdg/io/mesh.h"
#include "vdg/io/model.h"
#include "vdg/io/obj.h"

namespace vdg {
namespace {

using testing::errorOf;

const std::string kTetra = VDG_SOURCE_DIR "/tests/io/formats/tetra.obj";
const std::string kStatic = VDG_SOURCE_DIR "/tests/io/formats/tetra_v1.vdg.json";
const std::string kAnimated = VDG_SOURCE_DIR "/tests/io/formats/tetra_walk_v2.vdg.json";
const std::string kPlainGltf = VDG_SOURCE_DIR "/examples/walk/walker.glb";

TEST(Input, ExtensionsAreReadInAnyLetterCase) {
  EXPECT_TRUE(isObjPath("a/b.OBJ"));
  EXPECT_FALSE(isObjPath("a/obj"));
  EXPECT_TRUE(isGltfPath("x.GlB"));
  EXPECT_TRUE(isGltfPath("x.gltf"));
  EXPECT_FALSE(isGltfPath("x.vdg.json"));
  EXPECT_EQ(errorOf([] { (void)readMesh("m.ply"); }),
            "m.ply: unsupported mesh format '.ply' (expected .obj, .gltf or .glb)");
}

TEST(Input, AnObjIsAMesh) {
  const OpenedInput in = openInput(kTetra);
  EXPECT_EQ(in.format, InputFormat::kObj);
  EXPECT_EQ(in.kind, InputKind::kMesh);
  EXPECT_FALSE(in.isModel());
  EXPECT_EQ(in.mesh.vertexCount(), readObj(kTetra).vertexCount());
  EXPECT_FALSE(in.model);
  EXPECT_FALSE(in.animated);
}

TEST(Input, ManifestsAreStaticOrAnimatedModels) {
  const OpenedInput s = openInput(kStatic);
  EXPECT_EQ(s.format, InputFormat::kManifest);
  EXPECT_EQ(s.kind, InputKind::kModel);
  ASSERT_TRUE(s.model);
  EXPECT_FALSE(s.animated);
  EXPECT_EQ(s.model->keyCount(), 1u);
  EXPECT_EQ(s.raw.keys.at(0).name, "up");

  const OpenedInput a = openInput(kAnimated);
  EXPECT_EQ(a.kind, InputKind::kAnimatedModel);
  ASSERT_TRUE(a.animated);
  EXPECT_FALSE(a.model);
  EXPECT_EQ(a.animated->frameCount(), 3);

  const OpenedInput raw_only = openInput(kAnimated, {}, InputBuild::kRawOnly);
  EXPECT_EQ(raw_only.kind, InputKind::kAnimatedModel);
  EXPECT_FALSE(raw_only.animated);
  EXPECT_TRUE(raw_only.raw.animated());
}

TEST(Input, AGltfFileIsAModelWhenVdgExportedIt) {
  const OpenedInput plain = openInput(kPlainGltf);
  EXPECT_EQ(plain.format, InputFormat::kGltf);
  EXPECT_EQ(plain.kind, InputKind::kMesh);
  EXPECT_GT(plain.mesh.vertexCount(), 0u);

  testing::TempDir dir;
  const std::string exported = dir.file("tetra.glb");
  writeGltfExport(exported, gltfExportInput(ViewDependentModel::build(loadManifest(kStatic))));
  EXPECT_EQ(inputType(exported).kind, InputKind::kModel);
  const OpenedInput model = openInput(exported);
  EXPECT_EQ(model.format, InputFormat::kGltf);
  EXPECT_EQ(model.kind, InputKind::kModel);
  ASSERT_TRUE(model.model);
  EXPECT_EQ(model.model->keyName(0), "up");
}

TEST(Input, ModelCommandsRefuseMeshesClearly) {
  EXPECT_EQ(errorOf([] { (void)openModel(kTetra); }),
            kTetra +
                ": an OBJ mesh, not a view-dependent model (expected a manifest *.vdg.json or a glTF file vdg "
                "exported)");
  // A plain glTF file: the glTF model reader's own message.
  EXPECT_NE(errorOf([] { (void)openModel(kPlainGltf); }).find("not a view-dependent model exported by vdg"),
            std::string::npos);
  EXPECT_EQ(openModel(kStatic).kind, InputKind::kModel);
}

TEST(Input, MissingFilesNameTheFile) {
  EXPECT_EQ(errorOf([] { (void)openInput("no/such.obj"); }).rfind("no/such.obj", 0), 0u);
  EXPECT_EQ(errorOf([] { (void)openInput("no/such.vdg.json"); }).rfind("no/such.vdg.json", 0), 0u);
  EXPECT_EQ(errorOf([] { (void)openInput("no/such.glb"); }).rfind("no/such.glb", 0), 0u);
}

TEST(Input, KindsHaveNames) {
  EXPECT_STREQ(inputKindName(InputKind::kMesh), "mesh");
  EXPECT_STREQ(inputKindName(InputKind::kModel), "model");
  EXPECT_STREQ(inputKindName(InputKind::kAnimatedModel), "animated model");
}

TEST(FileFormats, EveryVersionedFormatIsListedOnceWithADocument) {
  std::set<std::string> names;
  for (const FileFormat& f : fileFormats()) {
    EXPECT_TRUE(names.insert(f.name).second) << f.name << " listed twice";
    EXPECT_GE(f.version, 1) << f.name;
    EXPECT_TRUE(std::filesystem::exists(std::string(VDG_SOURCE_DIR) + "/" + f.doc)) << f.doc;
  }
  EXPECT_EQ(names.count("manifest"), 1u);
  EXPECT_EQ(names.count("glTF extras"), 1u);
}

}  // namespace
}  // namespace vdg
