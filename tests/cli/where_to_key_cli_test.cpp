// vdg info --sphere-map and --check-intersections as a user runs them (docs/where-to-key.md).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "cli/run_vdg.h"

namespace {

using vdg::testing::runVdg;
const std::string kSpot = "examples/spot/spot.vdg.json";
const std::string kWalker = "examples/walk/walker.vdg.json";
constexpr int kLegend = 30;  // vdg/render/sphere_map_image.h: kSphereMapLegendHeight
constexpr double kUnitTol = 1e-6;

int lines(const std::string& s) { return static_cast<int>(std::count(s.begin(), s.end(), '\n')); }

// Width and height from a PNG's IHDR.
std::pair<int, int> pngSize(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::string head(24, '\0');
  in.read(head.data(), 24);
  auto be = [&](int at) {
    int v = 0;
    for (int k = 0; k < 4; ++k) v = (v << 8) | static_cast<unsigned char>(head[at + k]);
    return v;
  };
  return {be(16), be(20)};
}

TEST(WhereToKeyCli, SphereMapOnSpot) {
  vdg::testing::TempDir dir;
  const std::string png = dir.file("map.png");
  const auto r = runVdg("info " + kSpot + " --sphere-map '" + png + "' --size 180x90");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(pngSize(png), std::make_pair(180, 90 + kLegend));
  EXPECT_NE(r.out.find("suggested  view "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("need       0.6 nearest-key angle"), std::string::npos) << "the score is stated";

  const auto j = runVdg("info " + kSpot + " --sphere-map '" + png + "' --size 90x45 --json");
  ASSERT_EQ(j.code, 0) << j.err;
  const auto doc = nlohmann::json::parse(j.out);
  EXPECT_EQ(doc["size"], nlohmann::json({90, 45}));
  const auto& s = doc["suggested"];
  const double x = s["view"][0], y = s["view"][1], z = s["view"][2];
  EXPECT_NEAR(std::sqrt(x * x + y * y + z * z), 1.0, kUnitTol);
  EXPECT_GE(s["need"].get<double>(), 0.0);
  EXPECT_LE(s["need"].get<double>(), 1.0);
  EXPECT_LE(s["nearest_key_deg"].get<double>(), doc["max_nearest_key_deg"].get<double>());
  EXPECT_GT(doc["max_nearest_key_deg"].get<double>(), 0.0);
  EXPECT_GE(doc["uncovered_fraction"].get<double>(), 0.0);
  EXPECT_LE(doc["uncovered_fraction"].get<double>(), 1.0);
  EXPECT_GT(doc["max_speed"].get<double>(), 0.0) << "Spot's keys move vertices";
}

TEST(WhereToKeyCli, SphereMapOfAnAnimatedModelAtAFrame) {
  vdg::testing::TempDir dir;
  const auto r = runVdg("info " + kWalker + " --sphere-map '" + dir.file("w.png") + "' --size 72x36 --frame 10 --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto doc = nlohmann::json::parse(r.out);
  EXPECT_EQ(doc["frame"], 10);
  EXPECT_GT(doc["max_speed"].get<double>(), 0.0) << "the walker's keys at frame 10 move vertices";
  EXPECT_EQ(pngSize(dir.file("w.png")), std::make_pair(72, 36 + kLegend));
}

// Bad options: exit 2 (usage) or 1 (a file), one line on stderr, no image written.
TEST(WhereToKeyCli, BadOptionsGiveOneLine) {
  vdg::testing::TempDir dir;
  const std::string png = " --sphere-map '" + dir.file("m.png") + "'";
  for (const std::string& args :
       {kSpot + png + " --size 0x5", kSpot + png + " --size 5", kSpot + png + " --frame 3",
        kWalker + png + " --frame 999", kSpot + " --sphere-map '" + dir.file("m.txt") + "'", kSpot + " --size 10x10",
        kSpot + " --frame 2", kSpot + " --samples 5", kSpot + " --check-intersections --frames 3",
        kSpot + " --check-intersections" + png, kWalker + " --check-intersections --frames 5-999",
        kSpot + " --check-intersections --samples -4", "examples/spot/spot.obj" + png}) {
    const auto r = runVdg("info " + args);
    EXPECT_EQ(r.code, 2) << args << ": " << r.err;
    EXPECT_EQ(lines(r.err), 1) << args << ": " << r.err;
    EXPECT_FALSE(std::ifstream(dir.file("m.png")).good()) << args;
  }
  const auto r = runVdg("info " + kSpot + " --sphere-map '" + dir.file("no/such/folder/m.png") + "'");
  EXPECT_EQ(r.code, 1) << r.err;
  EXPECT_EQ(lines(r.err), 1) << r.err;
}

// Spot: whatever it reports, the report is consistent, and it is fast (200 views of 5,856 triangles).
TEST(WhereToKeyCli, IntersectionsOnSpot) {
  const auto info = nlohmann::json::parse(runVdg("info " + kSpot + " --json").out);
  const auto r = runVdg("info " + kSpot + " --check-intersections --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto doc = nlohmann::json::parse(r.out);
  EXPECT_EQ(doc["views_checked"].get<std::size_t>(), 200 + info["keys"].size());
  std::size_t most = 0;
  for (const auto& v : doc["views"]) {
    EXPECT_GT(v["new_pairs"].get<std::size_t>(), 0u);
    EXPECT_LT(v["example"][0].get<int>(), v["example"][1].get<int>());
    most = std::max(most, v["new_pairs"].get<std::size_t>());
  }
  if (doc["views"].empty()) {
    EXPECT_EQ(doc["worst"], -1);
  } else {
    EXPECT_EQ(doc["views"][doc["worst"].get<std::size_t>()]["new_pairs"].get<std::size_t>(), most);
  }
  const auto text = runVdg("info " + kSpot + " --check-intersections --samples 20");
  ASSERT_EQ(text.code, 0) << text.err;
  EXPECT_NE(text.out.find("checked    25 views"), std::string::npos) << text.out;
}

// Two sheets 0.3 apart (y = 0 and y = 0.3), n x n quads each, as OBJ text; `push` lowers the
// upper sheet's middle through the lower one.
std::string sheetsObj(bool push) {
  constexpr int n = 8;
  std::string obj;
  for (int s = 0; s < 2; ++s)
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i) {
        const double x = -1.0 + 2.0 * i / n, z = -1.0 + 2.0 * j / n;
        const double y = s == 0 ? 0.0 : (push && x * x + z * z < 0.3 ? -0.2 : 0.3);
        obj += "v " + std::to_string(x) + " " + std::to_string(y) + " " + std::to_string(z) + "\n";
      }
  for (int s = 0; s < 2; ++s)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const int a = 1 + s * (n + 1) * (n + 1) + j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
        obj += "f " + std::to_string(a) + " " + std::to_string(c) + " " + std::to_string(b) + "\n";
        obj += "f " + std::to_string(b) + " " + std::to_string(c) + " " + std::to_string(d) + "\n";
      }
  return obj;
}

// A key that pushes a sheet through another: reported at its view (named), the worst view near it;
// the clean key's view is not reported.
TEST(WhereToKeyCli, IntersectionsOfAPushedSheet) {
  vdg::testing::TempDir dir;
  vdg::testing::writeText(dir.file("base.obj"), sheetsObj(false));
  vdg::testing::writeText(dir.file("push.obj"), sheetsObj(true));
  vdg::testing::writeText(dir.file("m.vdg.json"), R"({"version": 2, "base": "base.obj", "keys": [
    {"name": "push", "mesh": "push.obj", "view": [0, 0, 1]},
    {"name": "clean", "mesh": "base.obj", "view": [0, 0, -1]}]})");
  const auto text = runVdg("info '" + dir.file("m.vdg.json") + "' --check-intersections --samples 50");
  ASSERT_EQ(text.code, 0) << text.err;
  EXPECT_NE(text.out.find("base       0 intersecting pairs"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("(key 'push')"), std::string::npos) << text.out;
  EXPECT_EQ(text.out.find("(key 'clean')"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("\nworst      view "), std::string::npos) << text.out;
  const auto doc = nlohmann::json::parse(
      runVdg("info '" + dir.file("m.vdg.json") + "' --check-intersections --samples 50 --json").out);
  ASSERT_GE(doc["worst"].get<int>(), 0);
  const auto& worst = doc["views"][doc["worst"].get<std::size_t>()];
  EXPECT_GT(worst["view"][2].get<double>(), 0.8) << "near the pushed key's view +Z";
  for (const auto& v : doc["views"]) EXPECT_GT(v["view"][2].get<double>(), 0.0) << v.dump();
}

// The walker at its key frames: its base already intersects itself (limbs through the body), which
// is not reported; every reported view is at a key frame.
TEST(WhereToKeyCli, IntersectionsOfAnAnimatedModel) {
  const auto r = runVdg("info " + kWalker + " --check-intersections --samples 10 --json");
  ASSERT_EQ(r.code, 0) << r.err;
  const auto doc = nlohmann::json::parse(r.out);
  for (const auto& v : doc["views"]) EXPECT_TRUE(v["frame"] == 10 || v["frame"] == 30) << v.dump();
  const auto one =
      nlohmann::json::parse(runVdg("info " + kWalker + " --check-intersections --samples 10 --frames 7 --json").out);
  for (const auto& v : one["views"]) EXPECT_EQ(v["frame"], 7);
}

}  // namespace
