// Synthesises "reference drawings" for the spot example's keys, for the view-dependent textures of
// docs/drawing-textures.md (Rademacher 99, section 6, future work). There are no hand drawings of
// Spot, so each drawing is made, honestly, by rendering the key's own shape from its key camera with
// vdg's renderer and repainting the picture in a hand-painted manner:
//  - the colours (Spot's texture, the warm/cool shading) mixed with a tint of the key's own, so that
//    every drawing looks different (as different artists' or days' drawings would), and flattened to
//    a few levels per channel (flat colour regions);
//  - dark ink contours: the renderer's silhouettes and creases, drawn thick;
//  - the paper around the cow transparent.
//
// Usage: vdg_make_spot_drawings SPOT.vdg.json OUT_DIR
// Reads the spot model (its five keys given by views), gives every key a camera on its view
// (kDistance from the centre, kFovDeg), writes OUT_DIR/drawings/KEY.png (kSize x kSize) and
// OUT_DIR/spot-drawings.vdg.json (version 5: the keys by camera, each with its drawing). The paths in
// the manifest are those of SPOT.vdg.json, so OUT_DIR is its folder. Deterministic on one machine
// (the renderer's pictures are; llvmpipe gives the committed ones).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <string>

#include "vdg/geom/error.h"
#include "vdg/io/manifest.h"
#include "vdg/render/image.h"
#include "vdg/render/model_renderer.h"
#include "vdg/viewdep/model.h"

namespace {

constexpr int kSize = 512;
constexpr double kDistance = 3.2;  // model units from the centre (Spot is about 2 long)
constexpr double kFovDeg = 40.0;
constexpr int kLevels = 4;              // levels per channel of the painted colours
constexpr float kInkLuminance = 0.22f;  // darker rendered pixels are ink, kept black
constexpr double kTintAmount = 0.45;    // how much of the key's tint goes into its colours
const vdg::render::Rgb kPaper{1.0f, 1.0f, 1.0f};

// One tint per key, in the order of spot.vdg.json (front, left, right, back, top).
constexpr std::array<std::array<double, 3>, 5> kTints{
    {{1.00, 0.62, 0.35}, {0.40, 0.70, 1.00}, {0.55, 0.90, 0.45}, {0.95, 0.45, 0.75}, {1.00, 0.90, 0.35}}};

// The rendered picture repainted: paper -> transparent, ink -> near black, the rest tinted and
// flattened to kLevels levels.
vdg::render::Image paint(const vdg::render::Image& shot, const std::array<double, 3>& tint) {
  vdg::render::Image out = shot;
  for (int y = 0; y < shot.height; ++y)
    for (int x = 0; x < shot.width; ++x) {
      const std::uint8_t* c = shot.pixel(x, y);
      std::uint8_t* o = out.pixel(x, y);
      const bool paper = c[0] >= 252 && c[1] >= 252 && c[2] >= 252;
      const float luminance = (299.0f * c[0] + 587.0f * c[1] + 114.0f * c[2]) / (1000.0f * 255.0f);
      if (paper) {
        o[0] = o[1] = o[2] = 255;
        o[3] = 0;
      } else if (luminance < kInkLuminance) {
        o[0] = 24;
        o[1] = 20;
        o[2] = 30;
        o[3] = 255;
      } else {
        for (int i = 0; i < 3; ++i) {
          const double mixed = (1.0 - kTintAmount) * c[i] / 255.0 + kTintAmount * tint[static_cast<std::size_t>(i)];
          const double level = std::round(std::clamp(mixed, 0.0, 1.0) * (kLevels - 1)) / (kLevels - 1);
          // Paint never reaches the ink's darkness: levels span [0.3, 1].
          o[i] = static_cast<std::uint8_t>(std::lround(255.0 * (0.3 + 0.7 * level)));
        }
        o[3] = 255;
      }
    }
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: %s SPOT.vdg.json OUT_DIR\n", argv[0]);
    return 2;
  }
  try {
    const std::string out_dir = argv[2];
    std::filesystem::create_directories(out_dir + "/drawings");
    vdg::RawViewDependentModel raw = vdg::loadManifest(argv[1]);
    if (raw.keys.size() != kTints.size())
      throw vdg::Error(std::string(argv[1]) + ": expected the spot example's 5 keys, got " +
                       std::to_string(raw.keys.size()));
    const Eigen::Vector3d centre = raw.resolvedCenter();
    raw.center = centre;
    raw.comment =
        "Spot with a reference drawing per key (docs/drawing-textures.md). The drawings are SYNTHESISED by "
        "make_spot_drawings: each key's shape rendered from its key camera and repainted (tinted flat colours, ink "
        "contours); no hand drawings of Spot exist";
    for (vdg::RawKey& key : raw.keys) {
      vdg::Camera camera;
      const Eigen::Vector3d view = key.view.normalized();
      camera.eye = centre + kDistance * view;
      camera.target = centre;
      camera.up = std::abs(view.y()) > 0.9 ? Eigen::Vector3d(0, 0, -1) : Eigen::Vector3d::UnitY();
      camera.fov_deg = kFovDeg;
      key.camera = camera;
      key.drawing_path = "drawings/" + key.name + ".png";
    }
    raw.resolveViews();
    raw.validate();
    const vdg::ViewDependentModel model = vdg::ViewDependentModel::build(raw);
    vdg::render::FrameOptions fo;
    fo.width = fo.height = kSize;
    fo.background = kPaper;
    fo.silhouette_width = 5.0f;
    fo.stroke_mode = vdg::render::StrokeWidthMode::fixed;
    fo.crease_angle_deg = 55.0f;
    vdg::render::ModelRenderer renderer(model, fo);
    for (std::size_t k = 0; k < model.keyCount(); ++k) {
      vdg::render::Image shot;
      renderer.render(*model.keyCamera(k), shot);
      vdg::render::writePng(out_dir + "/" + raw.keys[k].drawing_path, paint(shot, kTints[k]));
    }
    vdg::saveManifest(out_dir + "/spot-drawings.vdg.json", raw);
    std::printf("wrote %s/spot-drawings.vdg.json and %zu drawings\n", out_dir.c_str(), raw.keys.size());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "make_spot_drawings: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
