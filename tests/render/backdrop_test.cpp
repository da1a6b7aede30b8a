// The backdrop image of the renderer (Renderer::addBackdrop / drawBackdrop, renderer.h): upright
// in the image readPixels returns (the picture's first row at the top, its first column at the
// left), stretched over the viewport, colour = mix(paper, texel, opacity * alpha), the viewport's
// depth cleared so a mesh drawn after lies over it; the per-frame contract (every invalid input
// returns false and leaves every pixel as it was) and the set-up errors.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "support/error_of.h"
#include "support/test_meshes.h"
#include "vdg/geom/material.h"
#include "vdg/render/renderer.h"

namespace vdg::render {
namespace {

constexpr int kWidth = 64, kHeight = 48;
// 8-bit rounding of the blend and of linear filtering between equal texels.
constexpr int kLevelTolerance = 2;
// Pixels kept away from a colour edge of a stretched image (linear filtering blends across it).
constexpr int kEdgeMargin = 4;
const Rgb kCleared{0.2f, 0.6f, 0.3f};
const Rgb kPaper{0.95f, 0.93f, 0.88f};

using Rgba = std::array<std::uint8_t, 4>;
constexpr Rgba kRed{255, 0, 0, 255}, kGreen{0, 255, 0, 255}, kBlue{0, 0, 255, 255}, kYellow{255, 255, 0, 255};

TextureImage solid(int width, int height, const Rgba& c) {
  TextureImage image;
  image.width = width;
  image.height = height;
  for (int i = 0; i < width * height; ++i) image.rgba.insert(image.rgba.end(), c.begin(), c.end());
  return image;
}

// Quadrants as the picture is stored (row 0 at the top): red top-left, green top-right, blue
// bottom-left, yellow bottom-right.
TextureImage quadrants(int width, int height) {
  TextureImage image = solid(width, height, kRed);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const bool right = x >= width / 2, bottom = y >= height / 2;
      const Rgba& c = bottom ? (right ? kYellow : kBlue) : (right ? kGreen : kRed);
      std::copy(c.begin(), c.end(), image.rgba.begin() + (static_cast<std::ptrdiff_t>(y) * width + x) * 4);
    }
  return image;
}

int level(float c) { return static_cast<int>(std::lround(c * 255.0f)); }

// Largest channel difference between pixel (x, y) and the 8-bit colour `c`.
int channelError(const Image& img, int x, int y, const std::array<int, 3>& c) {
  const std::uint8_t* p = img.pixel(x, y);
  int e = 0;
  for (int i = 0; i < 3; ++i) e = std::max(e, std::abs(static_cast<int>(p[i]) - c[static_cast<std::size_t>(i)]));
  return e;
}
std::array<int, 3> levels(const Rgb& c) { return {level(c[0]), level(c[1]), level(c[2])}; }
std::array<int, 3> levels(const Rgba& c) { return {c[0], c[1], c[2]}; }

// mix(paper, texel, a) in 8-bit levels (the expected colour of a blended pixel).
std::array<int, 3> mixed(const Rgb& paper, const Rgba& texel, float a) {
  std::array<int, 3> out{};
  for (std::size_t i = 0; i < 3; ++i) out[i] = level(paper[i] * (1.0f - a) + texel[i] / 255.0f * a);
  return out;
}

class Backdrop : public ::testing::Test {
 protected:
  Backdrop() : renderer_(RendererSettings{kWidth, kHeight, 4}) {}
  Image read() {
    Image img;
    renderer_.readPixels(img);
    return img;
  }
  Renderer renderer_;
};

// Checks that the viewport `vp` of `img` shows the quadrants upright (away from the edges
// between them) and that everything outside it is still kCleared.
void expectQuadrants(const Image& img, const Viewport& vp) {
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      const bool inside = x >= vp.x && x < vp.x + vp.width && y >= vp.y && y < vp.y + vp.height;
      if (!inside) {
        ASSERT_LE(channelError(img, x, y, levels(kCleared)), kLevelTolerance) << x << ", " << y;
        continue;
      }
      const int dx = x - vp.x, dy = y - vp.y;
      if (std::abs(2 * dx + 1 - vp.width) < 2 * kEdgeMargin || std::abs(2 * dy + 1 - vp.height) < 2 * kEdgeMargin)
        continue;
      const bool right = 2 * dx >= vp.width, bottom = 2 * dy >= vp.height;
      const Rgba& c = bottom ? (right ? kYellow : kBlue) : (right ? kGreen : kRed);
      ASSERT_LE(channelError(img, x, y, levels(c)), kLevelTolerance) << x << ", " << y;
    }
}

TEST_F(Backdrop, TopHalfRedBottomHalfBlueAppearsSo) {
  TextureImage image = solid(10, 8, kRed);
  for (std::size_t i = image.rgba.size() / 2; i < image.rgba.size(); i += 4) {  // rows 4..7: blue
    image.rgba[i] = 0;
    image.rgba[i + 2] = 255;
  }
  const int h = renderer_.addBackdrop(image);
  renderer_.clear(kCleared);
  ASSERT_TRUE(renderer_.drawBackdrop(h, {0, 0, kWidth, kHeight}, 1.0f, kPaper));
  const Image img = read();
  for (int x = 0; x < kWidth; ++x) {
    for (int y = 0; y < kHeight / 2 - kEdgeMargin; ++y)
      ASSERT_LE(channelError(img, x, y, levels(kRed)), kLevelTolerance) << x << ", " << y;
    for (int y = kHeight / 2 + kEdgeMargin; y < kHeight; ++y)
      ASSERT_LE(channelError(img, x, y, levels(kBlue)), kLevelTolerance) << x << ", " << y;
  }
}

TEST_F(Backdrop, QuadrantsUprightAndStretchedOverTheViewport) {
  const int h = renderer_.addBackdrop(quadrants(16, 12));
  for (const Viewport vp : {Viewport{0, 0, kWidth, kHeight}, Viewport{9, 5, 40, 30}, Viewport{30, 20, 34, 28}}) {
    renderer_.clear(kCleared);
    ASSERT_TRUE(renderer_.drawBackdrop(h, vp, 1.0f, kPaper));
    expectQuadrants(read(), vp);
  }
}

TEST_F(Backdrop, OneToOneViewportShowsEveryTexel) {
  // Random texels, an image exactly the viewport's size: pixel (x, y) of the viewport is texel
  // (x, y) of the picture (row 0 at the top).
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> byte(0, 255);
  TextureImage image = solid(27, 19, kRed);
  for (std::size_t i = 0; i < image.rgba.size(); ++i)
    image.rgba[i] = i % 4 == 3 ? 255 : static_cast<std::uint8_t>(byte(rng));
  const int h = renderer_.addBackdrop(image);
  const Viewport vp{11, 6, image.width, image.height};
  renderer_.clear(kCleared);
  ASSERT_TRUE(renderer_.drawBackdrop(h, vp, 1.0f, kPaper));
  const Image img = read();
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const std::uint8_t* t = &image.rgba[(static_cast<std::size_t>(y) * image.width + x) * 4];
      ASSERT_LE(channelError(img, vp.x + x, vp.y + y, {t[0], t[1], t[2]}), kLevelTolerance) << x << ", " << y;
    }
}

TEST_F(Backdrop, OpacityAndAlphaMixPaperAndImage) {
  const Rgba texel{30, 200, 90, 255};
  const Rgba translucent{30, 200, 90, 102};  // alpha 0.4
  const int opaque = renderer_.addBackdrop(solid(4, 4, texel));
  const int clear = renderer_.addBackdrop(solid(4, 4, translucent));
  EXPECT_EQ(opaque, 0);
  EXPECT_EQ(clear, 1);
  const Viewport vp{0, 0, kWidth, kHeight};
  const struct {
    int handle;
    float opacity;
    std::array<int, 3> expected;
  } cases[] = {
      {opaque, 0.0f, levels(kPaper)},
      {opaque, 1.0f, levels(texel)},
      {opaque, 0.5f, mixed(kPaper, texel, 0.5f)},
      {opaque, 0.25f, mixed(kPaper, texel, 0.25f)},
      {clear, 1.0f, mixed(kPaper, translucent, 102.0f / 255.0f)},
      {clear, 0.5f, mixed(kPaper, translucent, 0.5f * 102.0f / 255.0f)},
      {clear, 0.0f, levels(kPaper)},
  };
  for (const auto& c : cases) {
    renderer_.clear(kCleared);
    ASSERT_TRUE(renderer_.drawBackdrop(c.handle, vp, c.opacity, kPaper));
    const Image img = read();
    for (int y = 0; y < kHeight; y += 7)
      for (int x = 0; x < kWidth; x += 5)
        ASSERT_LE(channelError(img, x, y, c.expected), kLevelTolerance)
            << "backdrop " << c.handle << " opacity " << c.opacity << " at " << x << ", " << y;
  }
}

TEST_F(Backdrop, AMeshDrawnAfterItLiesOverIt) {
  const TriMesh sphere = testing::uvSphere(12, 16);
  const int mesh = renderer_.addMesh(sphere.triangles, sphere.vertexCount());
  ASSERT_TRUE(renderer_.updateMesh(mesh, sphere.positions, {}));
  const int h = renderer_.addBackdrop(solid(8, 8, kBlue));
  View view;
  view.viewport = {0, 0, kWidth, kHeight};
  view.camera.eye = Eigen::Vector3d(0, 0, 4);
  view.z_near = 1.0;
  view.z_far = 10.0;
  MeshStyle style;
  style.silhouette_width = 0.0f;

  // Reference: the mesh on a cleared canvas.
  renderer_.clear(kCleared);
  ASSERT_TRUE(renderer_.drawMesh(mesh, view, style));
  const Image plain = read();
  // The mesh drawn first (its depth in the buffer), then the backdrop, then the mesh again at
  // the same depth: it shows only if the backdrop cleared the depth.
  renderer_.clear(kCleared);
  ASSERT_TRUE(renderer_.drawMesh(mesh, view, style));
  ASSERT_TRUE(renderer_.drawBackdrop(h, view.viewport, 1.0f, kPaper));
  ASSERT_TRUE(renderer_.drawMesh(mesh, view, style));
  const Image over = read();
  // Pixels the mesh covers in the reference, and those inside its outline (all four neighbours
  // covered too: no anti-aliased edge).
  const auto covered = [&](int x, int y) { return channelError(plain, x, y, levels(kCleared)) > kLevelTolerance; };
  const auto interior = [&](int x, int y) {
    return x > 0 && y > 0 && x + 1 < kWidth && y + 1 < kHeight && covered(x, y) && covered(x - 1, y) &&
           covered(x + 1, y) && covered(x, y - 1) && covered(x, y + 1);
  };
  int mesh_pixels = 0;
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      if (interior(x, y)) {
        ++mesh_pixels;
        const std::uint8_t* p = plain.pixel(x, y);
        ASSERT_LE(channelError(over, x, y, {p[0], p[1], p[2]}), kLevelTolerance) << x << ", " << y;
      } else if (!covered(x, y)) {
        ASSERT_LE(channelError(over, x, y, levels(kBlue)), kLevelTolerance) << x << ", " << y;
      }
    }
  EXPECT_GT(mesh_pixels, kWidth * kHeight / 10);
}

TEST_F(Backdrop, ContractViolationsDrawNothing) {
  const int h = renderer_.addBackdrop(quadrants(8, 8));
  renderer_.clear(kCleared);
  ASSERT_TRUE(renderer_.drawBackdrop(h, {4, 4, 20, 20}, 0.7f, kPaper));
  const Image before = read();
  const float kNaN = std::numeric_limits<float>::quiet_NaN();
  const float kInf = std::numeric_limits<float>::infinity();
  const Viewport good{0, 0, kWidth, kHeight};
  struct Case {
    const char* what;
    int handle;
    Viewport viewport;
    float opacity;
    Rgb paper;
  };
  const Case cases[] = {
      {"handle -1", -1, good, 1.0f, kPaper},
      {"handle past the last", h + 1, good, 1.0f, kPaper},
      {"zero width", h, {0, 0, 0, kHeight}, 1.0f, kPaper},
      {"zero height", h, {0, 0, kWidth, 0}, 1.0f, kPaper},
      {"negative width", h, {10, 10, -5, 10}, 1.0f, kPaper},
      {"opacity below 0", h, good, -0.01f, kPaper},
      {"opacity above 1", h, good, 1.01f, kPaper},
      {"opacity NaN", h, good, kNaN, kPaper},
      {"opacity infinite", h, good, kInf, kPaper},
      {"paper NaN", h, good, 0.5f, {0.5f, kNaN, 0.5f}},
      {"paper infinite", h, good, 0.5f, {kInf, 0.5f, 0.5f}},
  };
  for (const Case& c : cases) {
    EXPECT_FALSE(renderer_.drawBackdrop(c.handle, c.viewport, c.opacity, c.paper)) << c.what;
    const Image after = read();
    EXPECT_EQ(after.rgba, before.rgba) << c.what;
  }
  // A refused call left no state behind: the same valid call gives the same picture.
  renderer_.clear(kCleared);
  ASSERT_TRUE(renderer_.drawBackdrop(h, {4, 4, 20, 20}, 0.7f, kPaper));
  EXPECT_EQ(read().rgba, before.rgba);
}

TEST_F(Backdrop, SetUpErrorsNameTheProblem) {
  using testing::errorOf;
  EXPECT_EQ(errorOf([&] { renderer_.addBackdrop(TextureImage{}); }), "render: addBackdrop: the image is empty (0x0)");
  TextureImage no_rows = solid(4, 1, kRed);
  no_rows.height = 0;
  EXPECT_EQ(errorOf([&] { renderer_.addBackdrop(no_rows); }), "render: addBackdrop: the image is empty (4x0)");
  TextureImage short_data = solid(4, 3, kRed);
  short_data.rgba.pop_back();
  EXPECT_EQ(errorOf([&] { renderer_.addBackdrop(short_data); }),
            "render: addBackdrop: a 4x3 image has 47 bytes of RGBA, not 48");
  const TextureImage wide = solid(1 << 17, 1, kRed);  // wider than any driver's textures
  const std::string message = errorOf([&] { renderer_.addBackdrop(wide); });
  EXPECT_EQ(message.rfind("render: addBackdrop: the image (131072x1) exceeds the OpenGL driver's limit of ", 0), 0u)
      << message;
  // Nothing was registered by the refused calls: the next handle is 0.
  EXPECT_EQ(renderer_.addBackdrop(solid(2, 2, kRed)), 0);
}

}  // namespace
}  // namespace vdg::render
