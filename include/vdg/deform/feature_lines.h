// Deformation from feature lines: Beier and Neely's feature-based image warp (SIGGRAPH 92) lifted
// to 3D, the paper's future work ("adapt standard image morphing techniques such as [Beie92]",
// Rademacher 99, section 6). The artist pairs a line where a feature is on the model's image in the
// key view (the model side, P -> Q) with the line where the drawing has it (the drawing side,
// P' -> Q'), both in pixels of the key camera's width x height image (x right, y down). Each vertex
// is moved across the image plane at its own view depth (as the image-plane drag does,
// vdg/deform/image_plane.h) to the pixel the warp maps its projection to.
//
// The warp (Beier and Neely 92, section 3.3, "multiple pairs of lines", in the forward direction:
// model -> drawing): for a pixel X and pair i, with u along P->Q (0 at P, 1 at Q) and v the signed
// distance from the line in pixels,
//   u = (X - P).(Q - P) / |Q - P|^2,    v = (X - P).perp(Q - P) / |Q - P|,
//   X'_i = P' + u (Q' - P') + v perp(Q' - P') / |Q' - P'|,      D_i = X'_i - X,
//   dist_i = |v| for u in [0, 1], else the distance to the nearer endpoint,
//   weight_i = (|Q - P|^p / (a + dist_i))^b,
//   X' = X + s(d) sum_i weight_i D_i / sum_i weight_i,
// with s(d) = (1 - d / falloff_px)^2 for d = min_i dist_i below falloff_px, else 0 (Rademacher's
// drag falloff, section 3.1.2, on the image-plane distance): vertices farther than falloff_px from
// every model-side line stay where they are (bit for bit), and the warp fades to nothing there
// instead of jumping. A pair whose two lines are identical has D_i = 0 exactly, so identical pairs
// change nothing (bit for bit).
//
// Visibility: every vertex is moved by its projection, front and back faces alike. A drawing's line
// is an outline: the hidden back of a limb at the same pixels moves with the front, so the limb
// keeps its thickness and the mesh does not tear at the silhouette. Vertices at or behind the eye
// (view depth <= 0, perspective only) stay put.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "vdg/geom/camera.h"

namespace vdg {

// One pair, in pixels of the key camera's image (x right, y down).
struct FeatureLinePair {
  Eigen::Vector2d model_p{0, 0}, model_q{0, 0};      // where the feature is on the model's image
  Eigen::Vector2d drawing_p{0, 0}, drawing_q{0, 0};  // where the drawing has it
  bool operator==(const FeatureLinePair&) const = default;
};

// Beier and Neely's weight parameters (their defaults; `vdg morph --lines` uses the same) and the
// falloff distance.
struct FeatureLineSettings {
  double a = 1.0;            // pixels, in (0, 1e6]: keeps the weight finite on a line
  double b = 2.0;            // in [0, 16]: how fast a line's weight falls off with distance
  double p = 0.5;            // in [0, 1]: how much longer lines count
  double falloff_px = 64.0;  // pixels, > 0 and finite: beyond it from every line nothing moves
  bool operator==(const FeatureLineSettings&) const = default;
};

inline constexpr double kMaxFeatureLineA = 1e6;
inline constexpr double kMaxFeatureLineB = 16.0;
inline constexpr double kMaxFeatureLinePixel = 1e7;        // |x|, |y| of every endpoint, pixels
inline constexpr double kMinFeatureLinePixels = 1e-6;      // shorter lines are refused (no direction)
inline constexpr std::size_t kMaxFeatureLinePairs = 1024;  // the warp costs #V x pairs; hand-drawn sets are far smaller

// What is out of range: `field` is the JSON form's key path ("'a'", "'lines'[2].'src'"), `message`
// what is wrong. Nothing when the pairs (1..kMaxFeatureLinePairs of them) and settings are valid.
struct FeatureLineProblem {
  std::string field;
  std::string message;
};
std::optional<FeatureLineProblem> checkFeatureLines(std::span<const FeatureLinePair> pairs,
                                                    const FeatureLineSettings& settings);

// The warped pixel's motion (pixels) for a pixel X, as the formula above; zero beyond the falloff.
// Preconditions: checkFeatureLines() passes. Allocates nothing.
Eigen::Vector2d featureLineMotion(const Eigen::Vector2d& pixel, std::span<const FeatureLinePair> pairs,
                                  const FeatureLineSettings& settings);

// Moves every vertex of `positions` (#V x 3, in place) whose projection in `camera`'s width x
// height image moves under the warp: it goes to the warped pixel at its own view depth
// (unproject(project(x) + motion, depth)). Returns how many vertices moved. Preconditions:
// checkFeatureLines() passes, width, height >= 1.
std::size_t warpByFeatureLines(const Camera& camera, int width, int height, std::span<float> positions,
                               std::span<const FeatureLinePair> pairs, const FeatureLineSettings& settings);

// The mesh's silhouette in the key view, projected: segments (pixels) of the edges between a
// front-facing and a back-facing triangle, and of the open border's edges of front-facing ones.
struct PixelSegment {
  Eigen::Vector2d a, b;
};
std::vector<PixelSegment> projectedSilhouette(const Camera& camera, int width, int height,
                                              std::span<const float> positions,
                                              std::span<const std::int32_t> triangles);

// Snapping (optional): each model-side endpoint moves to the nearest point of the projected
// silhouette, so the artist draws only the drawing's line (give the drawing line on both sides, or
// a rough model line). A pair whose snapped ends coincide keeps its model side as given. With no
// silhouette the pairs are returned as given.
std::vector<FeatureLinePair> snapToSilhouette(std::span<const FeatureLinePair> pairs,
                                              std::span<const PixelSegment> silhouette);

}  // namespace vdg
