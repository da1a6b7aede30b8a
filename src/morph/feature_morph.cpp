// Feature-based morphing — Parent, Computer Animation, section 4.10 ("Feature-Based Morphing"),
// after T. Beier and S. Neely, "Feature-Based Image Metamorphosis", SIGGRAPH 1992, section 3.
//
// Pairs of feature lines establish the correspondence. For an output pixel X and a line PQ in the
// output (the `to` lines) with its partner P'Q' in the input (the `from` lines):
//   u  = (X - P) . (Q - P) / |Q - P|^2                    (position along the line, 0..1 on it)
//   v  = (X - P) . perp(Q - P) / |Q - P|                   (signed distance from the line, pixels)
//   X' = P' + u (Q' - P') + v perp(Q' - P') / |Q' - P'|    (the same place relative to P'Q')
// perp(d) = (-d_y, d_x), the same rotation for both lines. With several pairs each gives a
// displacement D_i = X'_i - X, weighted by
//   weight_i = (length_i^p / (a + dist_i))^b,
// length_i = |Q - P| and dist_i the distance from X to the segment PQ: |v| for 0 <= u <= 1, else
// the distance to the nearer endpoint (P for u < 0, Q for u > 1). Then
//   X' = X + sum_i w_i D_i / sum_i w_i,
// and the output pixel takes the input's colour at X' (bilinear, clamped at the border). For a
// morph the lines are interpolated with t (endpoints, linearly), both images warped onto them and
// cross-dissolved (Parent 4.10: "Feature line positions are interpolated based on the
// interpolation parameter").
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

#include "morph_2d_internal.h"
#include "vdg/geom/error.h"
#include "vdg/geom/parallel.h"
#include "vdg/geom/text.h"
#include "vdg/morph/image_morph.h"

namespace vdg::morph {
namespace {

using Eigen::Vector2d;

Vector2d perp(const Vector2d& d) { return {-d.y(), d.x()}; }

std::string pointText(const Vector2d& p) { return "(" + numberText(p.x(), 10) + ", " + numberText(p.y(), 10) + ")"; }

void validateLine(const FeatureLine& line, const std::string& where) {
  if (!line.p.allFinite() || !line.q.allFinite()) throw Error(where + ": an endpoint is not finite");
  if (std::max(line.p.cwiseAbs().maxCoeff(), line.q.cwiseAbs().maxCoeff()) > kMaxMorphCoordinate)
    throw Error(where + ": from " + pointText(line.p) + " to " + pointText(line.q) + " reaches farther than " +
                numberText(kMaxMorphCoordinate, 10) + " pixels from the origin in x or y");
  if (!((line.q - line.p).norm() >= kMinFeatureLineLength))
    throw Error(where + ": has zero length (from " + pointText(line.p) + " to " + pointText(line.q) +
                "); a feature line needs two endpoints at least " + numberText(kMinFeatureLineLength, 10) +
                " pixels apart");
}

// Per-line constants of the output line PQ and its input partner P'Q'.
struct LinePair {
  Vector2d p, d;                       // P, Q - P
  double inverse_length2;              // 1 / |Q - P|^2
  double inverse_length;               // 1 / |Q - P|
  double strength;                     // length^p
  Vector2d p_from, d_from, perp_from;  // P', Q' - P', perp(Q' - P') / |Q' - P'|
};

// w^b without pow for the usual exponents.
double power(double w, double b) {
  if (b == 2) return w * w;
  if (b == 1) return w;
  if (b == 0) return 1;
  return std::pow(w, b);
}

}  // namespace

void validateFeatureParams(const FeatureParams& params, const std::string& what) {
  if (!(std::isfinite(params.a) && params.a > 0))
    throw Error(what + ": a = " + numberText(params.a, 10) + " must be finite and > 0 (pixels)");
  if (!(std::isfinite(params.b) && params.b >= 0))
    throw Error(what + ": b = " + numberText(params.b, 10) + " must be finite and >= 0");
  if (!(params.p >= 0 && params.p <= 1))
    throw Error(what + ": p = " + numberText(params.p, 10) + " must lie in [0, 1]");
}

void validateFeatureLines(std::span<const FeatureLine> src, std::span<const FeatureLine> dst, const std::string& what) {
  if (src.size() != dst.size())
    throw Error(what + ": " + std::to_string(src.size()) + " source lines but " + std::to_string(dst.size()) +
                " destination lines (they come in pairs)");
  for (std::size_t i = 0; i < src.size(); ++i) validateLine(src[i], what + ": source line " + std::to_string(i));
  for (std::size_t i = 0; i < dst.size(); ++i) validateLine(dst[i], what + ": destination line " + std::to_string(i));
}

Image featureWarp(const Image& image, std::span<const FeatureLine> from, std::span<const FeatureLine> to,
                  const FeatureParams& params) {
  validateImage(image, "feature warp: image");
  validateFeatureLines(from, to, "feature warp");
  validateFeatureParams(params, "feature warp");
  bool identical = true;
  for (std::size_t i = 0; i < from.size(); ++i) identical = identical && from[i].p == to[i].p && from[i].q == to[i].q;
  if (identical) return image;  // every X' = X: the image itself, bit for bit
  std::vector<LinePair> pairs(from.size());
  for (std::size_t i = 0; i < from.size(); ++i) {
    LinePair& l = pairs[i];
    l.p = to[i].p;
    l.d = to[i].q - to[i].p;
    const double length = l.d.norm();
    l.inverse_length2 = 1.0 / l.d.squaredNorm();
    l.inverse_length = 1.0 / length;
    l.strength = std::pow(length, params.p);
    l.p_from = from[i].p;
    l.d_from = from[i].q - from[i].p;
    l.perp_from = perp(l.d_from) / l.d_from.norm();
  }
  Image out{.width = image.width, .height = image.height, .rgba = std::vector<float>(image.rgba.size())};
  vdg::detail::parallelChunks(static_cast<std::size_t>(image.height), 8, [&](std::size_t begin, std::size_t end) {
    for (std::size_t row = begin; row < end; ++row) {
      const int y = static_cast<int>(row);
      for (int x = 0; x < image.width; ++x) {
        const Vector2d X(x + 0.5, y + 0.5);
        Vector2d displacement_sum(0, 0);
        double weight_sum = 0;
        for (const LinePair& l : pairs) {
          const Vector2d px = X - l.p;
          const double u = px.dot(l.d) * l.inverse_length2;
          const double v = px.dot(perp(l.d)) * l.inverse_length;
          const Vector2d source = l.p_from + u * l.d_from + v * l.perp_from;
          double dist;
          if (u < 0)
            dist = px.norm();
          else if (u > 1)
            dist = (X - (l.p + l.d)).norm();
          else
            dist = std::abs(v);
          const double weight = power(l.strength / (params.a + dist), params.b);
          displacement_sum += weight * (source - X);
          weight_sum += weight;
        }
        const Vector2d source = weight_sum > 0 ? Vector2d(X + displacement_sum / weight_sum) : X;
        detail::sampleBilinear(image, source.x(), source.y(), out.pixel(x, y));
      }
    }
  });
  return out;
}

Image featureMorph(const Image& src, const Image& dst, std::span<const FeatureLine> src_lines,
                   std::span<const FeatureLine> dst_lines, double t, const FeatureParams& params) {
  validateImage(src, "feature morph: source image");
  validateImage(dst, "feature morph: destination image");
  if (src.width != dst.width || src.height != dst.height)
    throw Error("feature morph: the images differ in size (" + std::to_string(src.width) + " x " +
                std::to_string(src.height) + " and " + std::to_string(dst.width) + " x " + std::to_string(dst.height) +
                ")");
  validateFeatureLines(src_lines, dst_lines, "feature morph");
  validateFeatureParams(params, "feature morph");
  if (!std::isfinite(t)) throw Error("feature morph: t is not finite");
  // The inbetween lines: endpoints interpolated linearly with t (exact at t = 0 and 1).
  std::vector<FeatureLine> lines(src_lines.size());
  for (std::size_t i = 0; i < lines.size(); ++i) {
    lines[i].p = (1 - t) * src_lines[i].p + t * dst_lines[i].p;
    lines[i].q = (1 - t) * src_lines[i].q + t * dst_lines[i].q;
    if (!((lines[i].q - lines[i].p).norm() >= kMinFeatureLineLength))
      throw Error("feature morph: line " + std::to_string(i) + " collapses to a point at t = " + numberText(t, 10) +
                  " (its source and destination lines point in opposite directions)");
  }
  // An image whose dissolve weight is 0 is not warped (t = 0 gives src, t = 1 dst, exactly).
  if (t == 0) return src;
  if (t == 1) return dst;
  return crossDissolve(featureWarp(src, src_lines, lines, params), featureWarp(dst, dst_lines, lines, params), t);
}

double featureWarpCost(int width, int height, std::size_t lines) {
  return static_cast<double>(std::max(width, 0)) * static_cast<double>(std::max(height, 0)) *
         std::max(static_cast<double>(lines), 1.0);
}

double featureMorphCost(int width, int height, std::size_t lines) {
  return 2 * featureWarpCost(width, height, lines) +
         static_cast<double>(std::max(width, 0)) * static_cast<double>(std::max(height, 0));
}

}  // namespace vdg::morph
