// The where-to-key map as pixels: the PNG's layout (vdg/render/sphere_map_image.h) and the sphere
// inset's heat map (SphereInset::setHeat).
#include "vdg/render/sphere_map_image.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <vector>

#include "support/test_meshes.h"
#include "vdg/render/renderer.h"
#include "vdg/render/sphere_inset.h"

namespace vdg::render {
namespace {

constexpr int kLevelTol = 40;  // colour levels per channel: anti-aliasing at a dot's centre

// A sphere with keys on the five axes other than -Y, each bulging towards its view.
ViewDependentModel model() {
  RawViewDependentModel raw;
  raw.base = testing::uvSphere(8, 12);
  const std::vector<Eigen::Vector3d> views{Eigen::Vector3d::UnitX(), -Eigen::Vector3d::UnitX(),
                                           Eigen::Vector3d::UnitY(), Eigen::Vector3d::UnitZ(),
                                           -Eigen::Vector3d::UnitZ()};
  for (const Eigen::Vector3d& v : views) {
    RawKey key;
    key.name = "k" + std::to_string(raw.keys.size());
    key.mesh = raw.base;
    key.view = v;
    for (std::size_t i = 0; i < key.mesh.vertexCount(); ++i)
      for (int c = 0; c < 3; ++c) key.mesh.positions[3 * i + c] += 0.1f * static_cast<float>(v[c]);
    raw.keys.push_back(std::move(key));
  }
  return ViewDependentModel::build(raw);
}

bool near(const std::uint8_t* p, const std::array<std::uint8_t, 3>& c) {
  for (int k = 0; k < 3; ++k)
    if (std::abs(static_cast<int>(p[k]) - c[k]) > kLevelTol) return false;
  return true;
}

double luminance(const std::array<std::uint8_t, 3>& c) { return 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]; }

TEST(SphereMapImage, HeatColoursBrightenWithNeed) {
  double last = -1;
  for (int i = 0; i <= 20; ++i) {
    const double l = luminance(heatColour(i / 20.0));
    EXPECT_GT(l, last) << i;
    last = l;
  }
  EXPECT_EQ(heatColour(-1), heatColour(0));
  EXPECT_EQ(heatColour(2), heatColour(1));
  EXPECT_EQ(heatColour(std::nan("")), heatColour(0));
}

TEST(SphereMapImage, LayoutKeysAndSuggestion) {
  const SphereMap map = computeSphereMap(model(), {.width = 360, .height = 180});
  const Image img = sphereMapImage(map);
  ASSERT_EQ(img.width, 360);
  ASSERT_EQ(img.height, 180 + kSphereMapLegendHeight);
  for (const Eigen::Vector3d& k : map.keys) {
    const int cell = map.cellOf(k);
    EXPECT_TRUE(near(img.pixel(cell % 360, cell / 360), {255, 255, 255})) << "a white key dot at " << k.transpose();
  }
  const int s = map.cellOf(map.suggested);
  EXPECT_TRUE(near(img.pixel(s % 360, s / 360), {0, 230, 255})) << "the cyan cross at the suggestion";
  EXPECT_LT(map.suggested.y(), -0.9) << "the gap around -Y";
  // The legend's bar runs from need 0 to 1, left to right.
  const int bar_y = 180 + 8;
  EXPECT_TRUE(near(img.pixel(12, bar_y), heatColour(0.0)));
  EXPECT_TRUE(near(img.pixel(347, bar_y), heatColour(1.0)));
}

// The inset with the heat map: seen from near the suggested view, its cyan dot is where the
// suggestion projects, and the sphere around it shows the heat colours.
TEST(SphereMapImage, InsetHeatMap) {
  const ViewDependentModel m = model();
  const SphereMap map = computeSphereMap(m, {.width = 180, .height = 90});
  SphereInset inset(m.sphere());
  EXPECT_FALSE(inset.hasHeat());
  inset.setHeat(&map);
  EXPECT_TRUE(inset.hasHeat());
  Renderer r(RendererSettings{256, 256, 4});
  ViewWeights w;
  const Eigen::Vector3d view = (map.suggested + Eigen::Vector3d(0.6, 0.0, 0.3)).normalized();
  ASSERT_TRUE(m.weights(view, 0.0, w));
  ASSERT_TRUE(inset.draw(r, {0, 0, 256, 256}, view, w));
  Image img;
  r.readPixels(img);
  const Viewport panel = SphereInset::panel({0, 0, 256, 256});
  const auto at = project(inset.camera(), panel.width, panel.height, map.suggested).pixel;
  EXPECT_TRUE(near(img.pixel(panel.x + static_cast<int>(at.x()), panel.y + static_cast<int>(at.y())), {0, 230, 255}));
  int heat = 0;
  for (int b = 0; b < SphereInset::kHeatBins; ++b)
    for (int y = 0; y < 256; ++y)
      for (int x = 0; x < 256; ++x)
        heat += near(img.pixel(x, y), heatColour((b + 0.5) / SphereInset::kHeatBins)) ? 1 : 0;
  EXPECT_GT(heat, 2000) << "heat dots over the visible half";
  if (const char* out = std::getenv("VDG_SPHERE_HEAT_PNG")) writePng(out, img);
  inset.setHeat(nullptr);
  EXPECT_FALSE(inset.hasHeat());
}

}  // namespace
}  // namespace vdg::render
