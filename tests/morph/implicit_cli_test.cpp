// End-to-end tests of `vdg implicit`: run the built binary (VDG_BINARY) on blob files written here,
// check the meshes and sequences it writes (closed, components), that `vdg render` draws a frame of
// a sequence with the sequence's camera, and that bad input writes nothing. Also the BLOBS.json
// parser's refusals, as whole messages.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "support/error_of.h"
#include "vdg/io/blob_files.h"
#include "vdg/io/camera_json.h"
#include "vdg/io/obj.h"
#include "vdg/morph/implicit.h"
#include "vdg/morph/mesh_checks.h"
#include "vdg/morph/polygonise.h"

namespace vdg {
namespace {
namespace fs = std::filesystem;
using testing::errorOf;

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}
void spit(const fs::path& p, const std::string& text) { std::ofstream(p, std::ios::binary) << text; }

// Two soft objects that meet at frame 10 and part again by frame 20.
constexpr const char* kTwoBlobs = R"({"version": 1, "threshold": 0.5, "frames": [0, 20], "voxel": 0.08,
  "primitives": [
    {"kind": "wyvill", "radius": 1,
     "center": {"interpolation": "catmull-rom", "keys": [{"time": 0, "value": [-1.5, 0, 0]},
                {"time": 10, "value": [-0.6, 0, 0]}, {"time": 20, "value": [-1.5, 0, 0]}]}},
    {"kind": "soft", "radius": 1, "strength": {"keys": [{"time": 0, "value": 1}, {"time": 20, "value": 1.1}]},
     "center": {"interpolation": "catmull-rom", "keys": [{"time": 0, "value": [1.5, 0, 0]},
                {"time": 10, "value": [0.6, 0, 0]}, {"time": 20, "value": [1.5, 0, 0]}]}}]})";

class ImplicitCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("vdg_implicit_cli_" + std::to_string(::getpid()) + "_" +
                                        std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    spit(dir_ / "two.json", kTwoBlobs);
  }
  void TearDown() override { fs::remove_all(dir_); }

  // Runs vdg with `args`; returns the exit status; stdout in out_, stderr in err_.
  int vdg(const std::string& args) {
    const std::string out = (dir_ / "out.txt").string(), err = (dir_ / "err.txt").string();
    const std::string cmd = std::string("cd \"") + dir_.string() + "\" && \"" + VDG_BINARY + "\" " + args + " > \"" +
                            out + "\" 2> \"" + err + "\"";
    const int status = std::system(cmd.c_str());
    out_ = slurp(out);
    err_ = slurp(err);
    fs::remove(out);
    fs::remove(err);
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  }
  std::vector<std::string> listing() const {
    std::vector<std::string> names;
    for (const auto& e : fs::recursive_directory_iterator(dir_)) names.push_back(fs::relative(e.path(), dir_).string());
    std::sort(names.begin(), names.end());
    return names;
  }

  fs::path dir_;
  std::string out_, err_;
};

TEST_F(ImplicitCli, OneFrameApartAndFused) {
  ASSERT_EQ(vdg("implicit two.json -o a.obj"), 0) << err_;
  EXPECT_NE(out_.find("wrote a.obj: "), std::string::npos) << out_;
  EXPECT_NE(out_.find(", 2 components (voxel 0.08)"), std::string::npos) << out_;
  const TriMesh apart = readObj((dir_ / "a.obj").string());
  morph::requireClosed(apart, "a.obj");
  EXPECT_EQ(morph::connectedComponents(apart), 2u);

  ASSERT_EQ(vdg("implicit two.json -o b.obj --frame 10 --voxel 0.05 --quiet"), 0) << err_;
  EXPECT_EQ(out_, "");
  EXPECT_EQ(err_, "");
  const TriMesh fused = readObj((dir_ / "b.obj").string());
  morph::requireClosed(fused, "b.obj");
  EXPECT_EQ(morph::connectedComponents(fused), 1u);
  EXPECT_NE(slurp(dir_ / "b.obj").find("# vdg implicit: frame 10, voxel 0.05 of two.json"), std::string::npos);
}

TEST_F(ImplicitCli, SequenceWithCameraAndManifestThatRenderDraws) {
  ASSERT_EQ(vdg("implicit two.json --frames 8-12 -o seq -q"), 0) << err_;
  const std::vector<std::string> expected = {"seq",
                                             "seq/camera.json",
                                             "seq/frame_0008.obj",
                                             "seq/frame_0009.obj",
                                             "seq/frame_0010.obj",
                                             "seq/frame_0011.obj",
                                             "seq/frame_0012.obj",
                                             "seq/sequence.json",
                                             "two.json"};
  EXPECT_EQ(listing(), expected);
  for (int f = 8; f <= 12; ++f) {
    const TriMesh m =
        readObj((dir_ / "seq" / ("frame_00" + std::string(f < 10 ? "0" : "") + std::to_string(f) + ".obj")).string());
    morph::requireClosed(m, "frame");
  }
  const nlohmann::json manifest = nlohmann::json::parse(slurp(dir_ / "seq/sequence.json"));
  EXPECT_EQ(manifest.at("frames"), nlohmann::json::array({8, 12}));
  EXPECT_EQ(manifest.at("files").size(), 5u);
  EXPECT_EQ(manifest.at("files")[2].at("components"), 1);
  EXPECT_EQ(manifest.at("voxel"), 0.08);
  const Camera camera = readCameraFile((dir_ / "seq/camera.json").string());
  EXPECT_EQ(camera.fov_deg, 30.0);

  // vdg render accepts a frame with the sequence's camera.
  ASSERT_EQ(vdg("render seq/frame_0010.obj --camera seq/camera.json --size 64x64 -o png -q"), 0) << err_;
  EXPECT_TRUE(fs::is_regular_file(dir_ / "png/frame_0000.png"));
  EXPECT_GT(fs::file_size(dir_ / "png/frame_0000.png"), 100u);
}

TEST_F(ImplicitCli, BadInputWritesNothing) {
  const std::vector<std::string> before = listing();
  // Too many voxels in one frame of the sequence: refused before anything is written.
  EXPECT_EQ(vdg("implicit two.json --frames 0-20 --voxel 0.001 -o seq"), 1);
  EXPECT_EQ(err_,
            // Frame 0: blobs of radius 1 at x = -1.5 and 1.5: (5000 + 5) x (2000 + 5)^2 voxels, 8 bytes each.
            "vdg: error: two.json: frame 0: the grid needs 20120225125 voxels (about 153505 MiB) at voxel size 0.001; "
            "use a --voxel of at least 0.00537\n");
  EXPECT_EQ(listing(), before);
  spit(dir_ / "neg.json",
       R"({"version": 1, "threshold": 0.5, "primitives": [{"kind": "wyvill", "center": [0, 0, 0], "radius": -1}]})");
  EXPECT_EQ(vdg("implicit neg.json -o a.obj"), 1);
  EXPECT_EQ(err_, "vdg: error: neg.json: 'primitives'[0].'radius': expected a number > 0, got -1\n");
  spit(
      dir_ / "weak.json",
      R"({"version": 1, "threshold": 0.5, "primitives": [{"kind": "wyvill", "center": [0, 0, 0], "radius": 1, "strength": 0.3}]})");
  EXPECT_EQ(vdg("implicit weak.json -o a.obj"), 1);
  EXPECT_EQ(err_, "vdg: error: weak.json: the field reaches the threshold 0.5 nowhere at frame 0: no surface\n");
  EXPECT_FALSE(fs::exists(dir_ / "a.obj"));
}

TEST_F(ImplicitCli, BadUsage) {
  EXPECT_EQ(vdg("implicit two.json -o out"), 2);
  EXPECT_EQ(err_,
            "vdg: implicit: -o: expected an OBJ file (.obj) for one frame, got 'out'; give --frames A-B to write a "
            "sequence into a folder (see vdg implicit --help)\n");
  EXPECT_EQ(vdg("implicit two.json -o a.obj --frame 2 --frames 1-3"), 2);
  EXPECT_EQ(err_, "vdg: implicit: --frame and --frames exclude each other (see vdg implicit --help)\n");
  EXPECT_EQ(vdg("implicit two.json -o a.obj --voxel 0"), 2);
  EXPECT_NE(err_.find("--voxel"), std::string::npos) << err_;
  EXPECT_EQ(vdg("implicit --help"), 0);
  EXPECT_NE(out_.find("--frames"), std::string::npos);
}

// ---- BLOBS.json refusals -------------------------------------------------------------------

std::string refusal(const std::string& text) {
  return errorOf([&] { (void)parseBlobFile(text, "b.json"); });
}

TEST(BlobFile, ReadsConstantsAndTracks) {
  const BlobFile f = parseBlobFile(kTwoBlobs, "b.json");
  EXPECT_EQ(f.voxel_size, 0.08);
  EXPECT_EQ(f.animation.primitives.size(), 2u);
  EXPECT_EQ(f.animation.primitives[1].kind, morph::FieldKind::kWyvill);
  EXPECT_EQ(f.animation.last_frame, 20);
  // Without "frames": the span of the keys.
  const BlobFile g = parseBlobFile(R"({"version": 1, "threshold": 1, "primitives": [{"kind": "metaball",
      "center": [0, 0, 0], "radius": {"keys": [{"time": 2.5, "value": 1}, {"time": 7.2, "value": 2}]}},
      {"kind": "blobby", "center": [1, 0, 0], "radius": 1, "blobbiness": 2}]})",
                                   "b.json");
  EXPECT_EQ(g.animation.first_frame, 2);
  EXPECT_EQ(g.animation.last_frame, 8);
  EXPECT_EQ(g.animation.primitives[0].kind, morph::FieldKind::kNishimura);
  EXPECT_EQ(g.animation.primitives[1].blobbiness, 2.0);
  EXPECT_EQ(g.voxel_size, 0.0);
}

TEST(BlobFile, RefusesWithWholeMessages) {
  const std::string head = R"({"version": 1, "threshold": 0.5, "primitives": [)";
  EXPECT_EQ(refusal(R"({"version": 1, "primitives": [{"kind": "wyvill", "center": [0, 0, 0], "radius": 1}]})"),
            "b.json: missing key 'threshold'");
  EXPECT_EQ(refusal(head + R"({"kind": "wyvill", "radius": 1}]})"), "b.json: 'primitives'[0]: missing key 'center'");
  EXPECT_EQ(refusal(head + R"({"kind": "wyvill", "center": [0, 0, 0], "radius": -2}]})"),
            "b.json: 'primitives'[0].'radius': expected a number > 0, got -2");
  EXPECT_EQ(
      refusal(
          head +
          R"({"kind": "wyvill", "center": [0, 0, 0], "radius": {"keys": [{"time": 0, "value": 1}, {"time": 5, "value": 0}]}}]})"),
      "b.json: 'primitives'[0].'radius'.'keys'[1].'value': expected a number > 0, got 0");
  EXPECT_EQ(refusal(head + R"({"kind": "gauss", "center": [0, 0, 0], "radius": 1}]})"),
            "b.json: 'primitives'[0].'kind': unknown value 'gauss' (expected one of 'blinn', 'blobby', 'wyvill', "
            "'soft', 'nishimura', 'metaball')");
  EXPECT_EQ(refusal(R"({"version": 1, "threshold": 0, "primitives": []})"),
            "b.json: 'threshold': expected a number > 0, got 0");
  EXPECT_EQ(refusal(R"({"version": 1, "threshold": -0.5, "primitives": []})"),
            "b.json: 'threshold': expected a number > 0, got -0.5");
  EXPECT_EQ(refusal(R"({"version": 1, "threshold": 0.5, "primitives": []})"),
            "b.json: 'primitives': expected a non-empty array of primitives, got an array of 0 items");
  EXPECT_EQ(refusal(head + R"({"kind": "wyvill", "center": [0, 0, 0], "radius": 1, "blobbiness": 2}]})"),
            "b.json: 'primitives'[0].'blobbiness': only a 'blinn' primitive has a blobbiness");
  EXPECT_EQ(refusal(head + R"({"kind": "wyvill", "center": {"keys": [{"time": 0, "value": 1}]}, "radius": 1}]})"),
            "b.json: 'primitives'[0].'center': expected a track of 3 numbers, got a scalar track");
  EXPECT_EQ(refusal(R"({"version": 2, "threshold": 0.5, "primitives": []})"),
            "b.json: 'version': this vdg reads blob files version 1, got 2");
  EXPECT_EQ(refusal(R"({"threshold": 0.5, "primitives": []})"),
            "b.json: missing 'version' (this vdg reads blob files version 1)");
  EXPECT_EQ(
      refusal(
          R"({"version": 1, "threshold": 0.5, "frames": [5, 2], "primitives": [{"kind": "wyvill", "center": [0, 0, 0], "radius": 1}]})"),
      "b.json: 'frames': the first frame 5 is after the last 2");
  EXPECT_EQ(
      refusal(
          R"({"version": 1, "threshold": 0.5, "voxel": 0.01, "primitives": [{"kind": "wyvill", "centre": [0, 0, 0], "radius": 1}]})")
          .substr(0, 48),
      "b.json: 'primitives'[0]: unknown key 'centre' (e");
}

// Too many voxels: the file's voxel size, checked as vdg implicit does before polygonising.
TEST(BlobFile, TooManyVoxelsNamesTheFile) {
  const BlobFile f = parseBlobFile(
      R"({"version": 1, "threshold": 0.5, "voxel": 0.001, "primitives": [{"kind": "wyvill", "center": [0, 0, 0], "radius": 1}]})",
      "b.json");
  const morph::BlobModel m = morph::BlobAnimation::build(f.animation).modelAt(0);
  EXPECT_EQ(errorOf([&] { (void)morph::polygonise(m, {.voxel_size = f.voxel_size}, "b.json"); }),
            // (2000 + 1 + 4)^3 voxels, 8 bytes each; at 0.00396: (506 + 5)^3 = 133432831 <= 2^27.
            "b.json: the grid needs 8060150125 voxels (about 61494 MiB) at voxel size 0.001; use a --voxel of at least "
            "0.00396");
}

}  // namespace
}  // namespace vdg
