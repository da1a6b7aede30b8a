// End-to-end tests of `vdg morph3d` (docs/morph3d.md): run the built binary (VDG_BINARY) on meshes
// written here, check what it writes, that `vdg render` shows the sequences it writes, and that
// bad input and bad usage give one line, their exit status, and leave nothing behind.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <set>
#include <string>

#include "support/test_meshes.h"
#include "vdg/io/camera_json.h"
#include "vdg/io/obj.h"
#include "vdg/morph/mesh_checks.h"

namespace vdg {
namespace {
namespace fs = std::filesystem;

TriMesh scaled(TriMesh m, double s) {
  for (float& p : m.positions) p = static_cast<float>(p * s);
  return m;
}

class Morph3dCli : public ::testing::Test {
 protected:
  void SetUp() override {
    writeObj(dir_.file("small.obj"), testing::uvSphere(24, 48));
    writeObj(dir_.file("large.obj"), scaled(testing::uvSphere(24, 48), 2.0));
    writeObj(dir_.file("torus.obj"), testing::torus(1.0, 0.4, 48, 24));
    TriMesh open = testing::uvSphere();
    open.triangles.erase(open.triangles.begin(), open.triangles.begin() + 3);
    writeObj(dir_.file("open.obj"), open);
  }

  // Runs vdg with `args` in the test's folder; the exit status, stdout in out_, stderr in err_.
  int vdg(const std::string& args) {
    const std::string cmd =
        "cd \"" + dir_.path().string() + "\" && \"" + VDG_BINARY + "\" " + args + " > .stdout 2> .stderr";
    const int status = std::system(cmd.c_str());
    out_ = testing::readText(dir_.file(".stdout"));
    err_ = testing::readText(dir_.file(".stderr"));
    fs::remove(dir_.file(".stdout"));
    fs::remove(dir_.file(".stderr"));
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  }
  std::size_t entries() const {
    std::size_t n = 0;
    for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir_.path())) ++n;
    return n;
  }

  testing::TempDir dir_;
  std::string out_, err_;
};

TEST_F(Morph3dCli, OneInbetweenOfConcentricSpheres) {
  ASSERT_EQ(vdg("morph3d small.obj large.obj --t 0.5 --voxel 0.05 -o half.obj"), 0) << err_;
  EXPECT_EQ(err_, "");
  EXPECT_EQ(out_.rfind("wrote half.obj (", 0), 0u) << out_;
  EXPECT_NE(out_.find("; distance, voxel 0.05)"), std::string::npos) << out_;
  const TriMesh half = readObj(dir_.file("half.obj"));
  EXPECT_NO_THROW(morph::requireClosed(half, "half.obj"));
  double worst = 0;
  for (std::size_t v = 0; v < half.vertexCount(); ++v) {
    const double r = std::hypot(half.positions[v * 3], half.positions[v * 3 + 1], half.positions[v * 3 + 2]);
    worst = std::max(worst, std::abs(r - 1.5));
  }
  EXPECT_LE(worst, 0.05 + 0.01);  // one voxel, plus the UV sphere's chords (1 - cos(pi/48) of r = 2)
  ASSERT_EQ(vdg("morph3d small.obj large.obj --t 0.5 --voxel 0.05 -o quiet.obj --quiet"), 0) << err_;
  EXPECT_EQ(out_ + err_, "");
}

TEST_F(Morph3dCli, ASequenceThatVdgRenderShowsFrameByFrame) {
  ASSERT_EQ(vdg("morph3d small.obj torus.obj --count 3 -o seq"), 0) << err_;
  // One progress line per frame on stderr, the summary on stdout.
  EXPECT_EQ(err_, "vdg morph3d: frame 1/3 (t = 0): seq/frame_0000.obj, " +
                      std::to_string(readObj(dir_.file("seq/frame_0000.obj")).triangleCount()) +
                      " triangles\nvdg morph3d: frame 2/3 (t = 0.5): seq/frame_0001.obj, " +
                      std::to_string(readObj(dir_.file("seq/frame_0001.obj")).triangleCount()) +
                      " triangles\nvdg morph3d: frame 3/3 (t = 1): seq/frame_0002.obj, " +
                      std::to_string(readObj(dir_.file("seq/frame_0002.obj")).triangleCount()) + " triangles\n");
  EXPECT_EQ(out_.rfind("wrote 3 frames to seq (distance, voxel ", 0), 0u) << out_;
  const TriMesh first = readObj(dir_.file("seq/frame_0000.obj")), last = readObj(dir_.file("seq/frame_0002.obj"));
  EXPECT_EQ(morph::eulerCharacteristic(first), 2);
  EXPECT_EQ(morph::eulerCharacteristic(last), 0);
  // Different connectivity in every frame: no manifest, a camera for every frame.
  EXPECT_FALSE(fs::exists(dir_.file("seq/morph.vdg.json")));
  const Camera camera = readCameraFile(dir_.file("seq/camera.json"));
  EXPECT_GT((camera.eye - camera.target).norm(), 2.0);
  for (const char* frame : {"frame_0000", "frame_0002"}) {
    ASSERT_EQ(vdg(std::string("render seq/") + frame + ".obj --camera seq/camera.json --size 64x64 -o png_" + frame +
                  " --quiet"),
              0)
        << err_;
    EXPECT_GT(fs::file_size(dir_.file(std::string("png_") + frame + "/frame_0000.png")), 100u);
  }
}

TEST_F(Morph3dCli, SphericalSequenceIsOneConnectivityThatVdgRenderPlaysAsAnAnimatedModel) {
  writeObj(dir_.file("box.obj"), testing::closedBox(-1, -0.6f, -0.8f, 1, 0.6f, 0.8f));
  ASSERT_EQ(vdg("morph3d small.obj box.obj --method spherical --count 3 -o sph --quiet"), 0) << err_;
  EXPECT_EQ(out_ + err_, "");
  const TriMesh first = readObj(dir_.file("sph/frame_0000.obj")), last = readObj(dir_.file("sph/frame_0002.obj"));
  EXPECT_EQ(first.triangles, last.triangles);
  // t = 1 is the box: every vertex on its surface (one face coordinate at +-extent).
  for (std::size_t v = 0; v < last.vertexCount(); ++v) {
    const float x = last.positions[v * 3], y = last.positions[v * 3 + 1], z = last.positions[v * 3 + 2];
    const float face = std::max({std::abs(x) / 1.0f, std::abs(y) / 0.6f, std::abs(z) / 0.8f});
    ASSERT_NEAR(face, 1.0f, 1e-5f) << "vertex " << v;
  }
  ASSERT_TRUE(fs::exists(dir_.file("sph/morph.vdg.json")));
  ASSERT_EQ(vdg("render sph/morph.vdg.json --camera sph/camera.json --count 3 --size 64x64 -o sph_png --quiet"), 0)
      << err_;
  for (const char* png : {"frame_0000.png", "frame_0001.png", "frame_0002.png"})
    EXPECT_GT(fs::file_size(dir_.file(std::string("sph_png/") + png)), 100u) << png;
  // A torus is not genus 0.
  EXPECT_EQ(vdg("morph3d small.obj torus.obj --method spherical --t 0.5 -o x.obj"), 1);
  EXPECT_EQ(err_.rfind("vdg: error: torus.obj: is not a single genus-0 surface", 0), 0u) << err_;
}

TEST_F(Morph3dCli, MinkowskiOfTwoBoxesIsTheBoxOfInterpolatedExtents) {
  writeObj(dir_.file("a.obj"), testing::closedBox(0, 0, 0, 1, 1, 1));
  writeObj(dir_.file("b.obj"), testing::closedBox(2, 0, 0, 5, 1, 2));
  ASSERT_EQ(vdg("morph3d a.obj b.obj --method minkowski --t 0.5 -o m.obj"), 0) << err_;
  EXPECT_EQ(out_.rfind("wrote m.obj (", 0), 0u) << out_;
  const TriMesh m = readObj(dir_.file("m.obj"));
  EXPECT_NO_THROW(morph::requireClosed(m, "m.obj"));
  // Extents (1, 1, 1) and (3, 1, 2) -> (2, 1, 1.5), centred between (0.5, 0.5, 0.5) and (3.5, 0.5, 1).
  const Bounds box = computeBounds(m.positions);
  const float expected_min[3] = {1.0f, 0.0f, 0.0f}, expected_max[3] = {3.0f, 1.0f, 1.5f};
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(box.min[k], expected_min[k], 1e-5f) << k;
    EXPECT_NEAR(box.max[k], expected_max[k], 1e-5f) << k;
  }
}

TEST_F(Morph3dCli, SlicesOfConcentricSpheresMeetHalfWayAndKeepOneConnectivity) {
  ASSERT_EQ(vdg("morph3d small.obj large.obj --method slices --axis y --slices 24 --count 3 -o sl --quiet"), 0) << err_;
  const TriMesh first = readObj(dir_.file("sl/frame_0000.obj")), mid = readObj(dir_.file("sl/frame_0001.obj"));
  EXPECT_EQ(first.triangles, mid.triangles);
  EXPECT_NO_THROW(morph::requireClosed(mid, "mid"));
  // Spheres of radius 1 and 2 about the origin: every lofted point at radius 1.5 half way, up to the
  // chords of the 48-segment input spheres the contours are cut from.
  constexpr double kChordTolerance = 0.01;
  for (std::size_t v = 0; v < mid.vertexCount(); ++v) {
    const double r = std::hypot(mid.positions[v * 3], mid.positions[v * 3 + 1], mid.positions[v * 3 + 2]);
    ASSERT_NEAR(r, 1.5, 1.5 * kChordTolerance) << "vertex " << v;
  }
  EXPECT_TRUE(fs::exists(dir_.file("sl/morph.vdg.json")));
  EXPECT_EQ(vdg("morph3d small.obj large.obj --t 0.5 --slices 8 -o x.obj"), 2);
  EXPECT_EQ(err_, "vdg: morph3d: --slices: only for --method slices, not distance (see vdg morph3d --help)\n");
}

TEST_F(Morph3dCli, SheetsOfABoxAndASphereAreExactAtTheEndsAndPlayAsOneConnectivity) {
  writeObj(dir_.file("box.obj"), testing::closedBox(-1, -0.6f, -0.8f, 1, 0.6f, 0.8f));
  ASSERT_EQ(vdg("morph3d box.obj small.obj --method sheets --count 3 -o sh"), 0) << err_;
  EXPECT_EQ(out_, "wrote 3 frames to sh (sheets); camera.json, morph.vdg.json (one connectivity)\n");
  const TriMesh first = readObj(dir_.file("sh/frame_0000.obj")), mid = readObj(dir_.file("sh/frame_0001.obj"));
  const TriMesh last = readObj(dir_.file("sh/frame_0002.obj"));
  EXPECT_EQ(first.triangles, last.triangles);
  for (const TriMesh* m : {&first, &mid, &last}) {
    EXPECT_NO_THROW(morph::requireClosed(*m, "frame"));
    EXPECT_EQ(morph::eulerCharacteristic(*m), 2);
  }
  // t = 0 is the box (every vertex on a face of it), t = 1 the sphere (every vertex on a triangle
  // of the 48-segment UV sphere, within its chords of the unit sphere).
  for (std::size_t v = 0; v < first.vertexCount(); ++v) {
    const float x = first.positions[v * 3], y = first.positions[v * 3 + 1], z = first.positions[v * 3 + 2];
    ASSERT_NEAR(std::max({std::abs(x) / 1.0f, std::abs(y) / 0.6f, std::abs(z) / 0.8f}), 1.0f, 1e-5f) << v;
    const double r = std::hypot(last.positions[v * 3], last.positions[v * 3 + 1], last.positions[v * 3 + 2]);
    ASSERT_NEAR(r, 1.0, 0.005) << v;
  }
  ASSERT_TRUE(fs::exists(dir_.file("sh/morph.vdg.json")));
  ASSERT_EQ(vdg("render sh/morph.vdg.json --camera sh/camera.json --count 3 --size 64x64 -o sh_png --quiet"), 0)
      << err_;
  EXPECT_GT(fs::file_size(dir_.file("sh_png/frame_0001.png")), 100u);
  // --axis chooses the way the front sheet faces; --slices is the slices method's only.
  ASSERT_EQ(vdg("morph3d box.obj small.obj --method sheets --axis x --t 0.5 -o x.obj --quiet"), 0) << err_;
  EXPECT_EQ(vdg("morph3d box.obj small.obj --method sheets --slices 4 --t 0.5 -o x.obj"), 2);
  EXPECT_EQ(err_, "vdg: morph3d: --slices: only for --method slices, not sheets (see vdg morph3d --help)\n");
  EXPECT_EQ(vdg("morph3d box.obj small.obj --axis x --t 0.5 -o x.obj"), 2);
  EXPECT_EQ(err_, "vdg: morph3d: --axis: only for --method slices or sheets, not distance (see vdg morph3d --help)\n");
  // A torus is not genus 0.
  EXPECT_EQ(vdg("morph3d small.obj torus.obj --method sheets --t 0.5 -o y.obj"), 1);
  EXPECT_EQ(err_,
            "vdg: error: torus.obj: is not one genus-0 surface (Euler characteristic 0, 1 part); the sheet morph needs "
            "a mesh like a sphere\n");
  EXPECT_FALSE(fs::exists(dir_.file("y.obj")));
}

// The volume and area a closed mesh's triangles enclose.
std::pair<double, double> volumeAndArea(const TriMesh& m) {
  double volume = 0, area = 0;
  for (std::size_t f = 0; f < m.triangleCount(); ++f) {
    const float* p = &m.positions[static_cast<std::size_t>(m.triangles[f * 3]) * 3];
    const float* q = &m.positions[static_cast<std::size_t>(m.triangles[f * 3 + 1]) * 3];
    const float* r = &m.positions[static_cast<std::size_t>(m.triangles[f * 3 + 2]) * 3];
    const Eigen::Vector3d a(p[0], p[1], p[2]), b(q[0], q[1], q[2]), c(r[0], r[1], r[2]);
    volume += a.dot(b.cross(c)) / 6.0;
    area += (b - a).cross(c - a).norm() / 2.0;
  }
  return {volume, area};
}

TEST_F(Morph3dCli, SheetsOfSpotTheCowAndASphereAreExactAtBothEndsEitherWayRound) {
  // Spot (5856 triangles, genus 0) and a sphere (2208), a real mesh with legs, ears and horns: both
  // orders give both ends exactly (every vertex of each mesh a common vertex, the same volume and
  // area: nothing folds over).
  const fs::path spot = fs::path(VDG_SOURCE_DIR) / "../shared/assets/models/spot/spot_triangulated.obj";
  if (!fs::exists(spot)) GTEST_SKIP() << spot << " is not there";
  TriMesh cow = readObj(spot.string());
  cow.uvs.clear();
  cow.uv_triangles.clear();
  cow.normals.clear();
  cow.normal_triangles.clear();
  writeObj(dir_.file("spot.obj"), cow);
  constexpr double kRelative = 1e-5;  // float positions
  for (const char* order : {"spot.obj small.obj", "small.obj spot.obj"}) {
    SCOPED_TRACE(order);
    for (const char* t : {"0", "1"}) {
      ASSERT_EQ(vdg(std::string("morph3d ") + order + " --method sheets --t " + t + " -o end.obj --quiet"), 0) << err_;
      const TriMesh end = readObj(dir_.file("end.obj"));
      const bool is_spot = (std::string(order).rfind("spot", 0) == 0) == (std::string(t) == "0");
      const TriMesh original = is_spot ? cow : testing::uvSphere(24, 48);
      EXPECT_NO_THROW(morph::requireClosed(end, "end.obj"));
      const auto [volume, area] = volumeAndArea(end);
      const auto [want_volume, want_area] = volumeAndArea(original);
      EXPECT_NEAR(volume, want_volume, kRelative * want_volume) << t;
      EXPECT_NEAR(area, want_area, kRelative * want_area) << t;
      std::set<std::array<float, 3>> corners;
      for (std::size_t v = 0; v < end.vertexCount(); ++v)
        corners.insert({end.positions[v * 3], end.positions[v * 3 + 1], end.positions[v * 3 + 2]});
      for (std::size_t v = 0; v < original.vertexCount(); ++v)
        ASSERT_TRUE(
            corners.count({original.positions[v * 3], original.positions[v * 3 + 1], original.positions[v * 3 + 2]}))
            << "vertex " << v;
    }
  }
}

TEST_F(Morph3dCli, BadInputIsOneLineExitOneAndLeavesNothing) {
  const std::size_t before = entries();
  EXPECT_EQ(vdg("morph3d open.obj large.obj --t 0.5 -o x.obj"), 1);
  EXPECT_EQ(err_, "vdg: error: open.obj: is not closed: edge (0, 2) borders a hole (one triangle only)\n");
  EXPECT_EQ(vdg("morph3d small.obj open.obj --count 4 -o seq"), 1);
  EXPECT_EQ(err_, "vdg: error: open.obj: is not closed: edge (0, 2) borders a hole (one triangle only)\n");
  EXPECT_EQ(vdg("morph3d small.obj missing.obj --t 0.5 -o x.obj"), 1);
  EXPECT_EQ(err_.rfind("vdg: error: missing.obj: ", 0), 0u) << err_;
  EXPECT_EQ(vdg("morph3d small.obj large.obj --t 0.5 --voxel 0.0001 -o x.obj"), 1);
  EXPECT_EQ(err_.rfind("vdg: error: small.obj and large.obj: the distance volumes at voxel size 0.0001 need ", 0), 0u)
      << err_;
  EXPECT_NE(err_.find("; use a --voxel of at least "), std::string::npos) << err_;
  EXPECT_EQ(entries(), before);
}

TEST_F(Morph3dCli, BadUsageIsExitTwo) {
  const std::size_t before = entries();
  for (const char* args :
       {"morph3d small.obj large.obj --t 1.5 -o x.obj", "morph3d small.obj large.obj --t -0.1 -o x.obj",
        "morph3d small.obj large.obj --t nan -o x.obj", "morph3d small.obj large.obj --t 0.5 --method cubes -o x.obj",
        "morph3d small.obj large.obj --t 0.5 --count 3 -o x", "morph3d small.obj large.obj -o x.obj",
        "morph3d small.obj large.obj --count 1 -o x", "morph3d small.obj large.obj --t 0.5 -o x.png",
        "morph3d small.obj large.obj --t 0.5 --voxel 0 -o x.obj",
        "morph3d small.obj large.obj --t 0.5 --method minkowski --voxel 0.1 -o x.obj"}) {
    SCOPED_TRACE(args);
    EXPECT_EQ(vdg(args), 2);
    EXPECT_EQ(err_.find('\n'), err_.size() - 1) << err_;
  }
  EXPECT_EQ(vdg("morph3d small.obj large.obj --t 0.5 --count 3 -o x"), 2);
  EXPECT_EQ(err_, "vdg: morph3d: --t and --count exclude each other: give one (see vdg morph3d --help)\n");
  EXPECT_EQ(entries(), before);
  ASSERT_EQ(vdg("morph3d --help"), 0);
  EXPECT_NE(out_.find("--method"), std::string::npos);
}

}  // namespace
}  // namespace vdg
