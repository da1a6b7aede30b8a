// View-dependent textures from the reference drawings (vdg/render/drawing_textures.h): the projection
// (a vertex the key camera sees lies at its pixel of the drawing; a hidden one is invisible), the
// blend rule (renormalised over the keys that see a fragment, the base's weight to the shading), the
// picture at a key view (the drawing itself where the key sees the surface), the contour suppression
// (no pixel under the threshold is left) and the flat mode, and the errors.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <random>
#include <vector>

#include "support/error_of.h"
#include "test_models.h"
#include "vdg/geom/camera.h"
#include "vdg/geom/error.h"
#include "vdg/render/drawing_textures.h"
#include "vdg/render/model_renderer.h"
#include "vdg/render/renderer.h"

namespace vdg::render {
namespace {

constexpr int kWidth = 96, kHeight = 72;
// Where a vertex lies in the drawing, against geom's project(): double arithmetic both ways, stored
// as float (s, t, q).
constexpr double kPixelTolerance = 1e-3;
// Linear filtering and multisampling of a smooth gradient, in 8-bit levels.
constexpr int kLevelTolerance = 3;
// Fraction of the sphere's projected radius inside which the key-view picture is compared (away from
// the silhouette strokes and the slanted rim).
constexpr double kInnerDisc = 0.6;

// The bumpy sphere with each key given by a camera 4 units away along its view.
RawViewDependentModel cameraModel() {
  RawViewDependentModel raw = bumpyModel();
  for (RawKey& key : raw.keys) {
    Camera c;
    c.eye = key.view.normalized() * 4.0;
    c.target = Eigen::Vector3d::Zero();
    c.up = std::abs(key.view.normalized().y()) > 0.9 ? Eigen::Vector3d::UnitZ() : Eigen::Vector3d::UnitY();
    c.fov_deg = 40.0;
    key.camera = c;
  }
  raw.resolveViews();
  return raw;
}

// A smooth drawing: red across, green down, blue constant, opaque.
TextureImage gradient(int width, int height) {
  TextureImage image;
  image.width = width;
  image.height = height;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      image.rgba.push_back(static_cast<std::uint8_t>(40 + 180 * x / (width - 1)));
      image.rgba.push_back(static_cast<std::uint8_t>(40 + 180 * y / (height - 1)));
      image.rgba.push_back(150);
      image.rgba.push_back(255);
    }
  return image;
}

std::vector<std::shared_ptr<const TextureImage>> allDrawings(std::size_t keys, const TextureImage& image) {
  return std::vector<std::shared_ptr<const TextureImage>>(keys, std::make_shared<const TextureImage>(image));
}

TEST(DrawingTextures, AVertexTheKeyCameraSeesLiesAtItsPixelAndAHiddenOneIsInvisible) {
  const RawViewDependentModel raw = cameraModel();
  const ViewDependentModel model = ViewDependentModel::build(raw);
  const DrawingTextures d = DrawingTextures::build(model, allDrawings(model.keyCount(), gradient(kWidth, kHeight)));
  ASSERT_EQ(d.drawingCount(), 3u);
  for (std::size_t k = 0; k < model.keyCount(); ++k) {
    std::vector<float> key(model.vertexCount() * 3);
    ASSERT_TRUE(model.keyPositions(k, key));
    const Camera& camera = *model.keyCamera(k);
    const Eigen::Vector3d towards_eye = (camera.eye - camera.target).normalized();
    std::size_t seen = 0, hidden = 0;
    for (std::size_t v = 0; v < model.vertexCount(); ++v) {
      const Eigen::Vector3d p(key[v * 3], key[v * 3 + 1], key[v * 3 + 2]);
      const Eigen::Vector2d pixel = project(camera, kWidth, kHeight, p).pixel;
      const Eigen::Vector2d at = d.texCoord(k, v).cwiseProduct(Eigen::Vector2d(kWidth, kHeight));
      EXPECT_NEAR(at.x(), pixel.x(), kPixelTolerance) << "key " << k << " vertex " << v;
      EXPECT_NEAR(at.y(), pixel.y(), kPixelTolerance) << "key " << k << " vertex " << v;
      // The sphere's near cap is seen; its far cap lies behind the near one (occluded).
      const double facing = p.normalized().dot(towards_eye);
      if (facing > 0.5) {
        EXPECT_EQ(d.visibility(k)[v], 1.0f) << "key " << k << " vertex " << v << " faces the camera";
        ++seen;
      } else if (facing < -0.5) {
        EXPECT_EQ(d.visibility(k)[v], 0.0f) << "key " << k << " vertex " << v << " is behind the near side";
        ++hidden;
      }
    }
    EXPECT_GT(seen, 50u);
    EXPECT_GT(hidden, 50u);
  }
}

TEST(DrawingTextures, VerticesOutsideTheDrawingAreInvisible) {
  RawViewDependentModel raw = cameraModel();
  raw.keys[0].camera->fov_deg = 10.0;  // sees only the middle of the sphere
  raw.resolveViews();
  const ViewDependentModel model = ViewDependentModel::build(raw);
  const DrawingTextures d = DrawingTextures::build(model, allDrawings(model.keyCount(), gradient(kWidth, kHeight)));
  std::size_t outside = 0;
  for (std::size_t v = 0; v < model.vertexCount(); ++v) {
    const Eigen::Vector2d uv = d.texCoord(0, v);
    if (uv.x() < 0.0 || uv.x() >= 1.0 || uv.y() < 0.0 || uv.y() >= 1.0) {
      EXPECT_EQ(d.visibility(0)[v], 0.0f) << v;
      ++outside;
    }
  }
  EXPECT_GT(outside, 100u);
}

TEST(DrawingTextures, TheBlendIsRenormalisedOverTheKeysThatSeeAFragment) {
  const std::array<std::array<float, 4>, 3> texels{
      {{1.0f, 0.0f, 0.0f, 1.0f}, {0.0f, 1.0f, 0.0f, 1.0f}, {0.0f, 0.0f, 1.0f, 1.0f}}};
  const Rgb shaded{0.5f, 0.5f, 0.5f};
  // Two keys weigh half each; only the first sees the fragment: its drawing alone.
  Rgb c = blendDrawingColors({0.5f, 0.5f, 0.0f}, 0.0f, texels, {1.0f, 0.0f, 1.0f}, shaded);
  EXPECT_FLOAT_EQ(c[0], 1.0f);
  EXPECT_FLOAT_EQ(c[1], 0.0f);
  // Both see it: the weights as the shape has them.
  c = blendDrawingColors({0.25f, 0.75f, 0.0f}, 0.0f, texels, {1.0f, 1.0f, 1.0f}, shaded);
  EXPECT_FLOAT_EQ(c[0], 0.25f);
  EXPECT_FLOAT_EQ(c[1], 0.75f);
  // Half visible (an interpolated visibility): weighed by it, still summing to one.
  c = blendDrawingColors({0.5f, 0.5f, 0.0f}, 0.0f, texels, {1.0f, 0.5f, 0.0f}, shaded);
  EXPECT_NEAR(c[0], 2.0f / 3.0f, 1e-6f);
  EXPECT_NEAR(c[1], 1.0f / 3.0f, 1e-6f);
  // The base's weight goes to the shading; no key sees it and the base weighs nothing: the shading.
  c = blendDrawingColors({0.5f, 0.0f, 0.0f}, 0.5f, texels, {1.0f, 1.0f, 1.0f}, shaded);
  EXPECT_FLOAT_EQ(c[0], 0.75f);
  EXPECT_FLOAT_EQ(c[2], 0.25f);
  c = blendDrawingColors({0.6f, 0.4f, 0.0f}, 0.0f, texels, {0.0f, 0.0f, 0.0f}, shaded);
  EXPECT_EQ(c, shaded);
  // A transparent texel counts as unseen.
  auto clear = texels;
  clear[0][3] = 0.0f;
  c = blendDrawingColors({0.5f, 0.5f, 0.0f}, 0.0f, clear, {1.0f, 1.0f, 1.0f}, shaded);
  EXPECT_FLOAT_EQ(c[1], 1.0f);
}

TEST(DrawingTextures, AtAKeyViewThePictureIsThatKeysDrawingWhereTheKeySees) {
  const RawViewDependentModel raw = cameraModel();
  const ViewDependentModel model = ViewDependentModel::build(raw);
  const TextureImage drawing = gradient(kWidth, kHeight);
  FrameOptions fo;
  fo.width = kWidth;
  fo.height = kHeight;
  fo.drawings =
      std::make_shared<const DrawingTextures>(DrawingTextures::build(model, allDrawings(model.keyCount(), drawing)));
  ModelRenderer renderer(model, fo);
  for (std::size_t k = 0; k < model.keyCount(); ++k) {
    const Camera& camera = *model.keyCamera(k);
    Image image;
    const ViewWeights w = renderer.render(camera, image);
    const auto slot = std::find(w.key.begin(), w.key.end(), static_cast<int>(k)) - w.key.begin();
    ASSERT_LT(slot, 3) << "key " << k;
    EXPECT_NEAR(w.weight[static_cast<std::size_t>(slot)], 1.0f, 1e-5f);
    const Eigen::Vector2d centre = project(camera, kWidth, kHeight, Eigen::Vector3d::Zero()).pixel;
    const double radius = project(camera, kWidth, kHeight, cameraFrame(camera).up).pixel.y() - centre.y();
    int compared = 0, worst = 0;
    for (int y = 0; y < kHeight; ++y)
      for (int x = 0; x < kWidth; ++x) {
        if ((Eigen::Vector2d(x + 0.5, y + 0.5) - centre).norm() > kInnerDisc * std::abs(radius)) continue;
        for (int c = 0; c < 3; ++c) {
          const auto i = static_cast<std::size_t>((y * kWidth + x) * 4 + c);
          worst = std::max(worst, std::abs(static_cast<int>(image.rgba[i]) - static_cast<int>(drawing.rgba[i])));
        }
        ++compared;
      }
    EXPECT_GT(compared, 200) << "key " << k;
    EXPECT_LE(worst, kLevelTolerance) << "key " << k;
  }
}

// Random colours, then dark lines (below the threshold) across them.
TextureImage inked(int width, int height) {
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> bright(120, 255), dark(0, 40);
  TextureImage image;
  image.width = width;
  image.height = height;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const bool ink = x % 17 == 3 || y % 13 == 5 || x == y;
      for (int c = 0; c < 3; ++c) image.rgba.push_back(static_cast<std::uint8_t>(ink ? dark(rng) : bright(rng)));
      image.rgba.push_back(255);
    }
  return image;
}

TEST(DrawingTextures, ContourSuppressionLeavesNoPixelUnderTheThreshold) {
  const TextureImage image = inked(80, 60);
  DrawingStyle style;
  style.mode = DrawingMode::kFillInk;
  style.contour_threshold = 0.3f;
  for (const int dilation : {0, 1, 3}) {
    style.dilation = dilation;
    const TextureImage filled = prepareDrawing(image, style);
    const std::vector<std::uint8_t> mask = contourMask(image, style.contour_threshold, dilation);
    std::size_t ink = 0;
    for (std::size_t p = 0; p < mask.size(); ++p) {
      const std::uint8_t* c = &filled.rgba[p * 4];
      EXPECT_GE(drawingLuminance(c[0], c[1], c[2]), style.contour_threshold) << "pixel " << p;
      EXPECT_EQ(c[3], 255);
      if (mask[p]) {
        ++ink;
      } else {  // what is not ink stays as drawn
        EXPECT_TRUE(std::equal(c, c + 4, &image.rgba[p * 4])) << "pixel " << p;
      }
    }
    EXPECT_GT(ink, 500u);
  }
  // As drawn: unchanged, dark lines and all.
  EXPECT_EQ(prepareDrawing(image, DrawingStyle{}).rgba, image.rgba);
}

TEST(DrawingTextures, TheFlatModeGivesEachRegionOneColour) {
  // Two painted halves split by a vertical ink line; brush noise within each half.
  std::mt19937 rng(3);
  std::uniform_int_distribution<int> noise(-8, 8);  // neighbours differ by less than kFlatColourStep
  TextureImage image;
  image.width = 41;
  image.height = 20;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const bool ink = x == 20;
      const std::array<int, 3> paint = x < 20 ? std::array<int, 3>{200, 120, 80} : std::array<int, 3>{90, 160, 220};
      for (int c = 0; c < 3; ++c)
        image.rgba.push_back(static_cast<std::uint8_t>(ink ? 10 : paint[static_cast<std::size_t>(c)] + noise(rng)));
      image.rgba.push_back(255);
    }
  DrawingStyle style;
  style.mode = DrawingMode::kFlat;
  style.dilation = 0;
  const TextureImage flat = prepareDrawing(image, style);
  const auto at = [&](int x, int y) { return &flat.rgba[static_cast<std::size_t>((y * flat.width + x) * 4)]; };
  for (int y = 0; y < flat.height; ++y)
    for (int x = 0; x < flat.width; ++x) {
      const std::uint8_t* reference = x < 20 ? at(0, 0) : at(40, 0);
      if (x == 20) reference = at(19, y)[0] == at(x, y)[0] ? at(19, y) : at(21, y);  // the ink takes a neighbour's
      EXPECT_TRUE(std::equal(at(x, y), at(x, y) + 4, reference)) << x << ", " << y;
    }
  // The medians stay near the paints.
  EXPECT_NEAR(at(0, 0)[0], 200, 4);
  EXPECT_NEAR(at(40, 0)[2], 220, 4);
  // A sharp change of colour bounds a region as an ink line does: without the line, two regions.
  TextureImage no_line = image;
  for (int y = 0; y < no_line.height; ++y)
    std::copy_n(&image.rgba[static_cast<std::size_t>((y * image.width + 19) * 4)], 4,
                &no_line.rgba[static_cast<std::size_t>((y * image.width + 20) * 4)]);
  const TextureImage two = prepareDrawing(no_line, style);
  EXPECT_TRUE(std::equal(&two.rgba[0], &two.rgba[4], at(0, 0)));
  EXPECT_TRUE(std::equal(&two.rgba[40 * 4], &two.rgba[41 * 4], at(40, 0)));
}

TEST(DrawingTextures, BadInputIsOneClearError) {
  const RawViewDependentModel raw = cameraModel();
  const ViewDependentModel model = ViewDependentModel::build(raw);
  const auto image = std::make_shared<const TextureImage>(gradient(8, 8));
  EXPECT_EQ(testing::errorOf([&] { (void)DrawingTextures::build(model, allDrawings(2, *image)); }),
            "drawing textures: 2 drawings for a model of 3 keys (give one entry per key, null for none)");
  RawViewDependentModel no_camera = cameraModel();
  no_camera.keys[1].camera.reset();
  const ViewDependentModel plain = ViewDependentModel::build(no_camera);
  EXPECT_EQ(testing::errorOf([&] { (void)DrawingTextures::build(plain, allDrawings(3, *image)); }),
            "drawing textures: key 'right' has a drawing but no camera (the viewpoint it was drawn from)");
  TextureImage broken = *image;
  broken.rgba.pop_back();
  std::vector<std::shared_ptr<const TextureImage>> drawings(3);
  drawings[2] = std::make_shared<const TextureImage>(broken);
  EXPECT_EQ(testing::errorOf([&] { (void)DrawingTextures::build(model, drawings); }),
            "drawing textures: key 'top': a 8x8 image has 255 bytes of RGBA, not 256");
  DrawingStyle style;
  style.contour_threshold = 0.0f;
  EXPECT_EQ(testing::errorOf([&] { checkDrawingStyle(style); }),
            "drawing textures: the contour threshold must be a luminance in (0, 1], got 0");
  style.contour_threshold = 0.5f;
  style.dilation = kMaxContourDilation + 1;
  EXPECT_EQ(testing::errorOf([&] { (void)prepareDrawing(*image, style); }),
            "drawing textures: the contour dilation must be 0 to 64 pixels, got 65");
  // Keys without drawings are fine; their accessors say so.
  const DrawingTextures none = DrawingTextures::build(model, std::vector<std::shared_ptr<const TextureImage>>(3));
  EXPECT_EQ(none.drawingCount(), 0u);
  EXPECT_EQ(testing::errorOf([&] { (void)none.image(0); }), "drawing textures: key 0 has no drawing");
  EXPECT_EQ(testing::errorOf([&] { (void)none.hasDrawing(3); }),
            "drawing textures: key 3 out of range (the model has 3 keys)");
  // The renderer takes them for the CPU blend of a static model only.
  FrameOptions fo;
  fo.width = fo.height = 16;
  fo.drawings = std::make_shared<const DrawingTextures>(DrawingTextures::build(model, allDrawings(3, *image)));
  EXPECT_EQ(testing::errorOf([&] { ModelRenderer r(model.base(), fo); }),
            "render: drawing textures take a static view-dependent model blended on the CPU, not a plain mesh");
}

// Renderer::addDrawings refuses what it cannot use at set-up; drawMeshDrawings keeps the per-frame
// contract: every invalid input returns false and leaves the canvas as it was.
TEST(DrawingTextures, TheRendererChecksItsInput) {
  const RawViewDependentModel raw = cameraModel();
  const ViewDependentModel model = ViewDependentModel::build(raw);
  const DrawingTextures d = DrawingTextures::build(model, allDrawings(model.keyCount(), gradient(16, 16)));
  Renderer renderer(RendererSettings{32, 32, 1});
  const int plain = renderer.addMesh(model.base().triangles, model.vertexCount());
  EXPECT_EQ(testing::errorOf([&] { (void)renderer.addDrawings(plain, d); }),
            "render: addDrawings: mesh 0 is not a surface of this renderer (addSurface)");
  const TriMesh small = uvSphere(4, 6);
  const int other = renderer.addSurface(small, SurfaceTopology::build(small));
  EXPECT_EQ(testing::errorOf([&] { (void)renderer.addDrawings(other, d); }),
            "render: addDrawings: the drawings were built for " + std::to_string(model.vertexCount()) +
                " vertices; the mesh has " + std::to_string(small.vertexCount()));
  const int mesh = renderer.addSurface(model.base(), model.surface());
  const int drawings = renderer.addDrawings(mesh, d);
  ASSERT_TRUE(renderer.updateMesh(mesh, model.base().positions, {}));
  View view;
  view.viewport = {0, 0, 32, 32};
  view.camera = *model.keyCamera(0);
  view.z_near = 1.0;
  view.z_far = 10.0;
  ViewWeights w;
  w.key = {0, 1, -1};
  w.weight = {0.5f, 0.5f, 0.0f};
  renderer.clear({0.1f, 0.2f, 0.3f});
  Image before, after;
  renderer.readPixels(before);
  ViewWeights bad_key = w, bad_weight = w;
  bad_key.key[2] = 3;
  bad_weight.weight[1] = std::numeric_limits<float>::quiet_NaN();
  View bad_view = view;
  bad_view.z_near = 0.0;
  EXPECT_FALSE(renderer.drawMeshDrawings(mesh, drawings + 1, view, MeshStyle{}, w));
  EXPECT_FALSE(renderer.drawMeshDrawings(other, drawings, view, MeshStyle{}, w));
  EXPECT_FALSE(renderer.drawMeshDrawings(mesh, drawings, view, MeshStyle{}, bad_key));
  EXPECT_FALSE(renderer.drawMeshDrawings(mesh, drawings, view, MeshStyle{}, bad_weight));
  EXPECT_FALSE(renderer.drawMeshDrawings(mesh, drawings, bad_view, MeshStyle{}, w));
  renderer.readPixels(after);
  EXPECT_EQ(before.rgba, after.rgba);
  EXPECT_TRUE(renderer.drawMeshDrawings(mesh, drawings, view, MeshStyle{}, w));
  renderer.readPixels(after);
  EXPECT_NE(before.rgba, after.rgba);
}

}  // namespace
}  // namespace vdg::render
