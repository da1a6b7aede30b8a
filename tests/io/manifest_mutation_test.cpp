// Mutated manifests and OBJ files are parsed or rejected with vdg::Error, never anything worse.
#include <gtest/gtest.h>

#include "support/mutate.h"
#include "support/test_meshes.h"
#include "vdg/geom/error.h"
#include "vdg/io/manifest.h"
#include "vdg/io/obj.h"
#include "vdg/viewdep/model.h"

namespace vdg {
namespace {

constexpr int kMutants = 1500;
// Many mutants (a changed number, added whitespace) are still valid. A parser that rejected
// everything would pass the crash checks below; these floors make that fail.
// Measured (seeds 1234 and 99): 68 of the 1500 manifests (4.5%) load, 242 of the 1500 OBJ
// files (16%); the floors are about half of that.
constexpr double kMinLoadedManifestFraction = 0.02;
constexpr double kMinLoadedObjFraction = 0.08;

const char* kManifest = R"({
  "version": 1, "base": "base.obj", "sharpness": 1.5, "uncovered": "cosine", "center": [0, 0.1, 0],
  "keys": [
    {"name": "a", "mesh": "a.obj", "view": [0, 0, 1]},
    {"name": "b", "mesh": "b.obj", "camera": {"eye": [3, 0, 0], "target": [0, 0, 0], "up": [0, 1, 0], "fov_deg": 30}},
    {"name": "c", "mesh": "c.obj", "camera": {"eye": [0, 3, 1], "target": [0, 0, 0], "ortho_height": 2}}
  ]})";

// The base and three key meshes kManifest names, written into `dir`.
void writeMeshes(testing::TempDir& dir) {
  const TriMesh base = testing::uvSphere(4, 6);
  writeObj(dir.file("base.obj"), base);
  for (const char* name : {"a.obj", "b.obj", "c.obj"}) {
    TriMesh key = base;
    key.positions[4] += 0.2f;
    writeObj(dir.file(name), key);
  }
}

// Loads, builds and evaluates the manifest `text` (written into `dir`); throws what they throw,
// returns what evaluate returns.
bool loadAndEvaluate(testing::TempDir& dir, const std::string& text) {
  testing::writeText(dir.file("m.vdg.json"), text);
  const ViewDependentModel model = ViewDependentModel::build(loadManifest(dir.file("m.vdg.json")));
  std::vector<float> out(3 * model.vertexCount());
  return model.evaluate(Eigen::Vector3d(0.3, 0.4, 0.5), 0.0, out);
}

const char* kObj =
    "# quad and triangle\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0.5 0.5 1\n"
    "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvn 0 0 1\n"
    "f 1/1/1 2/2/1 3/3/1 4/4/1\nf 1 2 5\nf -1 -2 -3\n";

TEST(Robustness, UnmutatedManifestAndObjLoad) {
  testing::TempDir dir;
  writeMeshes(dir);
  bool evaluated = false;
  EXPECT_NO_THROW(evaluated = loadAndEvaluate(dir, kManifest));
  EXPECT_TRUE(evaluated);
  testing::writeText(dir.file("m.obj"), kObj);
  EXPECT_NO_THROW(validateMesh(readObj(dir.file("m.obj")), "m.obj"));
}

TEST(Robustness, MutatedManifestsLoadOrFailCleanly) {
  testing::TempDir dir;
  writeMeshes(dir);
  testing::Mutator mutator(1234);
  int loaded = 0;
  for (int i = 0; i < kMutants; ++i) {
    const std::string text = mutator.mutate(kManifest);
    try {
      EXPECT_TRUE(loadAndEvaluate(dir, text)) << "mutant " << i;
      ++loaded;
    } catch (const Error&) {
    } catch (const std::exception& e) {
      FAIL() << "mutant " << i << " threw a non-vdg exception: " << e.what() << "\n" << text;
    }
  }
  EXPECT_GE(loaded, kMinLoadedManifestFraction * kMutants) << "only " << loaded << " of " << kMutants << " loaded";
}

TEST(Robustness, MutatedObjFilesLoadOrFailCleanly) {
  testing::TempDir dir;
  testing::Mutator mutator(99);
  int loaded = 0;
  for (int i = 0; i < kMutants; ++i) {
    const std::string text = mutator.mutate(kObj);
    testing::writeText(dir.file("m.obj"), text);
    try {
      const TriMesh m = readObj(dir.file("m.obj"));
      validateMesh(m, "m.obj");
      ++loaded;
    } catch (const Error&) {
    } catch (const std::exception& e) {
      FAIL() << "mutant " << i << " threw a non-vdg exception: " << e.what() << "\n" << text;
    }
  }
  EXPECT_GE(loaded, kMinLoadedObjFraction * kMutants) << "only " << loaded << " of " << kMutants << " loaded";
}

}  // namespace
}  // namespace vdg
