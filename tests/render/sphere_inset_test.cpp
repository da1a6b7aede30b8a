// The viewing-sphere diagram (SphereInset, sphere_inset.h): keyAt finds each key on the visible
// half where draw() put its dot (checked against the drawn image too), nothing far from every
// dot, never a key behind the sphere's outline, never a dummy; draw()'s per-frame contract.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <numbers>
#include <random>
#include <vector>

#include "support/allocation_counter.h"
#include "support/random_direction.h"
#include "vdg/render/sphere_inset.h"

namespace vdg::render {
namespace {

constexpr int kCanvas = 256;
// Colour of a drawn dot's centre: a key (dark), an active key (red) or the view marker (blue),
// each within this many levels per channel (anti-aliasing, shading of nothing: dots are flat).
constexpr int kDotTolerance = 40;
constexpr double kPickRadius = 10.0;

// Twelve keys spread over the sphere (an icosahedron's vertices) minus three around -Y, so that
// the base mode adds dummies there.
ViewSphere testSphere() {
  const double g = (1.0 + std::sqrt(5.0)) / 2.0;
  std::vector<Eigen::Vector3d> dirs;
  for (const double a : {-1.0, 1.0})
    for (const double b : {-g, g}) {
      dirs.emplace_back(0, a, b);
      dirs.emplace_back(a, b, 0);
      dirs.emplace_back(b, 0, a);
    }
  std::erase_if(dirs, [](const Eigen::Vector3d& d) { return d.normalized().y() < -0.5; });
  ViewSphereSettings settings;
  settings.base_falloff_deg = 40.0;
  return ViewSphere::build(dirs, settings);
}

std::array<int, 3> levels(const Rgb& c) {
  return {static_cast<int>(std::lround(c[0] * 255)), static_cast<int>(std::lround(c[1] * 255)),
          static_cast<int>(std::lround(c[2] * 255))};
}

bool near(const Image& img, const Eigen::Vector2d& pixel, const Rgb& c) {
  const std::uint8_t* p = img.pixel(static_cast<int>(pixel.x()), static_cast<int>(pixel.y()));
  const auto l = levels(c);
  for (std::size_t i = 0; i < 3; ++i)
    if (std::abs(static_cast<int>(p[i]) - l[i]) > kDotTolerance) return false;
  return true;
}

class SphereInsetTest : public ::testing::Test {
 protected:
  SphereInsetTest() : sphere_(testSphere()), inset_(sphere_), renderer_(RendererSettings{kCanvas, kCanvas, 4}) {}

  // The canvas position of point `p` as drawn in `vp` by the last draw().
  Eigen::Vector2d dotPixel(const Viewport& vp, const Eigen::Vector3d& p) const {
    const Viewport panel = SphereInset::panel(vp);
    return Eigen::Vector2d(panel.x, panel.y) + project(inset_.camera(), panel.width, panel.height, p).pixel;
  }
  bool visible(const Eigen::Vector3d& p) const { return (inset_.camera().eye - p).dot(p) > 0.0; }

  ViewSphere sphere_;
  SphereInset inset_;
  Renderer renderer_;
};

// ---------------------------------------------------------------------------------------------
// Placement in the main view (insetPlacement): the corner the model's picture leaves free.

TEST(InsetPlacement, TheCornerWithTheFewestModelPointsBottomRightFirst) {
  const Viewport view{0, 0, 400, 300};
  constexpr int kSide = 100, kMargin = 5;
  auto at = [&](const std::vector<float>& points) {
    const Viewport v = insetPlacement(view, kSide, kMargin, points);
    return std::array<int, 4>{v.x, v.y, v.width, v.height};
  };
  const std::array<int, 4> bottom_right{295, 195, 100, 100}, bottom_left{5, 195, 100, 100}, top_right{295, 5, 100, 100},
      top_left{5, 5, 100, 100};
  // Points inside each corner's square.
  const std::vector<float> in_br{300, 200, 390, 290}, in_bl{10, 200, 100, 290}, in_tr{300, 10, 390, 100},
      in_tl{10, 10, 100, 100};
  auto join = [](std::initializer_list<std::vector<float>> parts) {
    std::vector<float> out;
    for (const auto& p : parts) out.insert(out.end(), p.begin(), p.end());
    return out;
  };
  EXPECT_EQ(at({}), bottom_right) << "no model";
  EXPECT_EQ(at({200, 150, 150, 120, 250, 180}), bottom_right) << "a centred model";
  EXPECT_EQ(at(in_br), bottom_left) << "the model in the bottom-right corner";
  EXPECT_EQ(at(join({in_br, in_bl})), top_right);
  EXPECT_EQ(at(join({in_br, in_bl, in_tr})), top_left);
  EXPECT_EQ(at(join({in_br, in_bl, in_tr, in_tl})), bottom_right) << "every corner alike";
  EXPECT_EQ(at(join({in_br, in_br, in_bl, in_tr, in_tl})), bottom_left) << "the fewest points";
  // No point in any corner, but the points' box (a large face) covers the bottom-right one.
  EXPECT_EQ(at({150, 150, 400, 300}), bottom_left);
  EXPECT_EQ(at({0, 0, 400, 300}), bottom_right) << "the box covers every corner alike";
  // An offset view (the main view need not start at the canvas origin).
  const Viewport moved = insetPlacement(Viewport{50, 10, 400, 300}, kSide, kMargin, {});
  EXPECT_EQ((std::array<int, 4>{moved.x, moved.y, moved.width, moved.height}),
            (std::array<int, 4>{345, 205, 100, 100}));
  // A square larger than the view: at the view's origin.
  const Viewport big = insetPlacement(Viewport{0, 0, 40, 30}, kSide, kMargin, {});
  EXPECT_EQ((std::array<int, 4>{big.x, big.y, big.width, big.height}), (std::array<int, 4>{0, 0, 100, 100}));
}

TEST_F(SphereInsetTest, EachVisibleKeyIsFoundAtItsDot) {
  ASSERT_GT(sphere_.points().size(), sphere_.keyCount()) << "the test sphere should have dummies";
  std::mt19937 rng(3);
  int front_total = 0, back_total = 0;
  for (const Viewport vp : {Viewport{0, 0, kCanvas, kCanvas}, Viewport{20, 31, 200, 150}, Viewport{40, 10, 120, 230}}) {
    for (int trial = 0; trial < 4; ++trial) {
      const Eigen::Vector3d view = testing::randomDirection(rng);
      ViewWeights w;
      ASSERT_TRUE(sphere_.weights(view, 1.0, w));
      renderer_.clear({0.5f, 0.5f, 0.5f});
      ASSERT_TRUE(inset_.draw(renderer_, vp, view, w));
      Image img;
      renderer_.readPixels(img);
      const auto pts = sphere_.points();
      for (std::size_t k = 0; k < sphere_.keyCount(); ++k) {
        const Eigen::Vector2d px = dotPixel(vp, pts[k]);
        if (!visible(pts[k])) {
          ++back_total;
          EXPECT_NE(inset_.keyAt(vp, px, kPickRadius), static_cast<int>(k)) << "back key " << k;
          continue;
        }
        ++front_total;
        EXPECT_EQ(inset_.keyAt(vp, px, kPickRadius), static_cast<int>(k)) << "key " << k;
        // The drawn image agrees: a dot (key, active key or the view marker over it) is there.
        EXPECT_TRUE(near(img, px, {0.15f, 0.15f, 0.18f}) || near(img, px, {0.85f, 0.1f, 0.1f}) ||
                    near(img, px, {0.1f, 0.3f, 0.9f}))
            << "no dot drawn at key " << k << " (" << px.transpose() << ")";
        // A click a little off the centre still picks it (the keys' dots are far apart).
        EXPECT_EQ(inset_.keyAt(vp, px + Eigen::Vector2d(2.0, -1.5), kPickRadius), static_cast<int>(k)) << "key " << k;
      }
    }
  }
  EXPECT_GT(front_total, 0);
  EXPECT_GT(back_total, 0);
}

TEST_F(SphereInsetTest, KeyAtIsTheNearestVisibleKeyWithinTheRadius) {
  // Brute force over pixels of the viewport and beyond: keyAt is -1 exactly when no visible
  // key's dot is within the radius, otherwise the nearest one; dummies are never returned.
  const Viewport vp{10, 20, 180, 160};
  const Eigen::Vector3d view = Eigen::Vector3d(0.3, 0.4, 1.0).normalized();
  ViewWeights w;
  ASSERT_TRUE(sphere_.weights(view, 1.0, w));
  ASSERT_TRUE(inset_.draw(renderer_, vp, view, w));
  const auto pts = sphere_.points();
  int found = 0, none = 0;
  for (double y = 0.5; y < kCanvas; y += 3.0)
    for (double x = 0.5; x < kCanvas; x += 3.0) {
      const Eigen::Vector2d px(x, y);
      int nearest = -1;
      double best = kPickRadius;
      for (std::size_t k = 0; k < sphere_.keyCount(); ++k) {
        if (!visible(pts[k])) continue;
        const double d = (dotPixel(vp, pts[k]) - px).norm();
        if (d <= best) {
          nearest = static_cast<int>(k);
          best = d;
        }
      }
      const int got = inset_.keyAt(vp, px, kPickRadius);
      ASSERT_EQ(got, nearest) << px.transpose();
      (got >= 0 ? found : none) += 1;
    }
  EXPECT_GT(found, 0);
  EXPECT_GT(none, found);  // most of the canvas is far from every dot
  // Far from any dot: the panel's corner and a point off the canvas.
  EXPECT_EQ(inset_.keyAt(vp, {vp.x + 2.0, vp.y + 2.0}), -1);
  EXPECT_EQ(inset_.keyAt(vp, {-500.0, 1e4}), -1);
}

TEST_F(SphereInsetTest, ABackKeyIsNotReturnedEvenWithAHugeRadius) {
  const Viewport vp{0, 0, kCanvas, kCanvas};
  const Eigen::Vector3d view(0, 0, 1);
  ViewWeights w;
  ASSERT_TRUE(sphere_.weights(view, 1.0, w));
  ASSERT_TRUE(inset_.draw(renderer_, vp, view, w));
  const auto pts = sphere_.points();
  for (std::size_t k = 0; k < sphere_.keyCount(); ++k) {
    if (visible(pts[k])) continue;
    const int got = inset_.keyAt(vp, dotPixel(vp, pts[k]), 1e6);
    ASSERT_GE(got, 0);
    EXPECT_TRUE(visible(pts[static_cast<std::size_t>(got)])) << "back key " << k << " gave " << got;
  }
}

TEST_F(SphereInsetTest, CameraFollowsTheView) {
  const Camera before = inset_.camera();
  const Viewport vp{0, 0, 100, 100};
  ViewWeights w;
  ASSERT_TRUE(sphere_.weights(Eigen::Vector3d(0, 0, 1), 1.0, w));
  ASSERT_TRUE(inset_.draw(renderer_, vp, Eigen::Vector3d(0, 0, 1), w));
  EXPECT_LT((inset_.camera().eye - before.eye).norm(), 1e-12);  // the camera before any draw: view +Z
  ASSERT_TRUE(sphere_.weights(Eigen::Vector3d(1, 0, 0), 1.0, w));
  ASSERT_TRUE(inset_.draw(renderer_, vp, Eigen::Vector3d(1, 0, 0), w));
  // 30 degrees beyond the view's azimuth, 20 degrees above it: the view faces the camera.
  const Eigen::Vector3d eye_dir = inset_.camera().eye.normalized();
  EXPECT_NEAR(eye_dir.dot(Eigen::Vector3d(1, 0, 0)),
              std::cos(30 * std::numbers::pi / 180) * std::cos(20 * std::numbers::pi / 180), 1e-9);
  EXPECT_NEAR(eye_dir.y(), std::sin(20 * std::numbers::pi / 180), 1e-9);
}

TEST_F(SphereInsetTest, ContractViolationsDrawNothing) {
  const Viewport vp{30, 40, 120, 100};
  const Eigen::Vector3d view(0, 0, 1);
  ViewWeights good;
  ASSERT_TRUE(sphere_.weights(view, 1.0, good));
  renderer_.clear({0.5f, 0.5f, 0.5f});
  ASSERT_TRUE(inset_.draw(renderer_, vp, view, good));
  const Camera camera = inset_.camera();
  Image before;
  renderer_.readPixels(before);
  const double kNaN = std::numeric_limits<double>::quiet_NaN();
  const int triangles = static_cast<int>(sphere_.triangles().size());
  const int keys = static_cast<int>(sphere_.keyCount());
  struct Case {
    const char* what;
    Viewport viewport;
    Eigen::Vector3d view;
    ViewWeights w;
  };
  const auto with = [&](auto change) {
    ViewWeights w = good;
    change(w);
    return w;
  };
  const Case cases[] = {
      {"2 pixels wide", {30, 40, 2, 100}, view, good},
      {"2 pixels high", {30, 40, 120, 2}, view, good},
      {"negative width", {30, 40, -120, 100}, view, good},
      {"NaN view", vp, Eigen::Vector3d(0, kNaN, 1), good},
      {"infinite view", vp, Eigen::Vector3d(std::numeric_limits<double>::infinity(), 0, 1), good},
      {"triangle past the last", vp, view, with([&](ViewWeights& w) { w.triangle = triangles; })},
      {"triangle -2", vp, view, with([](ViewWeights& w) { w.triangle = -2; })},
      {"a dummy as key", vp, view, with([&](ViewWeights& w) { w.key[1] = keys; })},
      {"key -2", vp, view, with([](ViewWeights& w) { w.key[2] = -2; })},
  };
  for (const Case& c : cases) {
    EXPECT_FALSE(inset_.draw(renderer_, c.viewport, c.view, c.w)) << c.what;
    Image after;
    renderer_.readPixels(after);
    EXPECT_EQ(after.rgba, before.rgba) << c.what;
    EXPECT_EQ(inset_.camera().eye, camera.eye) << c.what;
  }
  // A zero view (an eye at the model's centre) is drawn.
  EXPECT_TRUE(inset_.draw(renderer_, vp, Eigen::Vector3d::Zero(), ViewWeights{}));
  // keyAt refuses quietly.
  const Eigen::Vector2d centre(vp.x + vp.width / 2.0, vp.y + vp.height / 2.0);
  EXPECT_EQ(inset_.keyAt({30, 40, 2, 100}, centre, 1e6), -1);
  EXPECT_EQ(inset_.keyAt(vp, {kNaN, 50.0}, 1e6), -1);
  EXPECT_EQ(inset_.keyAt(vp, centre, -1.0), -1);
  EXPECT_EQ(inset_.keyAt(vp, centre, kNaN), -1);
  EXPECT_GE(inset_.keyAt(vp, centre, 1e6), 0);
}

TEST_F(SphereInsetTest, PerFrameCallsAllocateNothingOnceWarm) {
  const Viewport vp{0, 0, 160, 160};
  const Eigen::Vector3d view = Eigen::Vector3d(0.2, -0.3, 1.0).normalized();
  ViewWeights w;
  ASSERT_TRUE(sphere_.weights(view, 1.0, w));
  ASSERT_TRUE(inset_.draw(renderer_, vp, view, w));  // the renderer's buffers grow here
  EXPECT_EQ(testing::allocationsDuring([&] { EXPECT_TRUE(inset_.draw(renderer_, vp, view, w)); }), 0);
  EXPECT_EQ(testing::allocationsDuring([&] { (void)inset_.keyAt(vp, {80.0, 80.0}); }), 0);
}

}  // namespace
}  // namespace vdg::render
