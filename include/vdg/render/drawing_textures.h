// View-dependent textures from the reference drawings (Rademacher 99, section 6, future work: "it is
// straightforward to extract texture coordinates from each reference drawing and use view-dependent
// textures [Debevec 98]"; the paper warns that drawings are hard to blend because of their contour
// lines and different shading). docs/drawing-textures.md shows what this gives.
//
// Built once, immutable afterwards (DrawingTextures::build): for every key with a drawing,
//  - the drawing prepared on the CPU (prepareDrawing: as it is, its ink lines filled in, or its
//    colours flattened per region);
//  - per-vertex projective texture coordinates (s, t, q) of the KEY shape (the deformed one) seen by
//    the key camera: the vertex lies at (s/q, t/q) of the drawing, (0, 0) its top-left corner and
//    (1, 1) its bottom-right (the drawing's rows top first, as TextureImage stores them). The
//    renderer interpolates (s, t, q) and divides per fragment, so at the key view the texture is
//    exactly the projection of the drawing onto the key shape (a projective map, not an affine one);
//  - per-vertex visibility: 1 when the vertex is seen by the key camera, 0 when it is hidden or
//    outside the drawing. A depth buffer of the key shape is rendered on the CPU from the key camera
//    at the drawing's resolution (at most kMaxDepthBufferSide a side; depth and nearest triangle at
//    each pixel centre; deterministic, no OpenGL). Seen means: in front of the eye, inside the
//    picture, and either one of the vertex's own triangles is the nearest surface at a pixel within
//    one pixel of it, or the vertex is no farther from the eye than kVisibilityDepthTolerance x the
//    model's extentRadius() beyond the nearest surface at its pixel.
//
// Rendering (Renderer::drawMeshDrawings, ModelRenderer with FrameOptions::drawings) blends the
// drawings of the (up to three) keys of the view with the SAME weights as the shape (section 3.2.2),
// each also weighted by its interpolated visibility and its texel's alpha, and renormalised; the
// base's weight goes to the model's own material/NPR shading, which is also what a fragment no key
// sees shows (blendDrawingColors is the rule, written once on the CPU for the tests; the fragment
// shader repeats it).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include <Eigen/Core>

#include "vdg/geom/material.h"
#include "vdg/render/shading.h"
#include "vdg/viewdep/model.h"

namespace vdg::render {

// A vertex is visible when its depth from the key camera exceeds the depth buffer's at its pixel
// by at most this fraction of the model's extentRadius() (the buffer samples pixel centres, so a
// vertex's own surface may be a little nearer there; 1% of the model's size is a few pixels' worth
// of depth on a surface seen at a slant, far less than the gap between two layers of a body).
inline constexpr double kVisibilityDepthTolerance = 0.01;
// Largest side of the CPU depth buffer; a larger drawing is sampled by a proportionally smaller buffer.
inline constexpr int kMaxDepthBufferSide = 2048;
// The flat mode's regions grow through neighbouring pixels whose channels differ by at most this
// many 8-bit levels: shading and brush noise (small steps) are flattened, a painted patch's edge (a
// large step) bounds a region as an ink line does.
inline constexpr int kFlatColourStep = 24;
// Largest contour dilation, in pixels.
inline constexpr int kMaxContourDilation = 64;

// How a drawing is prepared before it is projected (prepareDrawing).
enum class DrawingMode {
  kAsDrawn,  // the drawing as it is (its ink lines blend into ghost lines between keys)
  kFillInk,  // contour suppression: ink pixels filled from the nearest non-ink colour
  kFlat,     // flat colour: each region between ink lines takes its median colour, ink filled
};

struct DrawingStyle {
  DrawingMode mode = DrawingMode::kAsDrawn;
  // Ink: opaque pixels (alpha >= 128) of luminance below this threshold (drawingLuminance, in
  // (0, 1]), grown by `dilation` pixels (a square of side 2 x dilation + 1 about each; [0,
  // kMaxContourDilation]) to take the lines' anti-aliased fringes too.
  float contour_threshold = 0.3f;
  int dilation = 1;
};

// Throws vdg::Error "drawing textures: ..." naming the option for a threshold outside (0, 1] (NaN
// included) or a dilation outside [0, kMaxContourDilation].
void checkDrawingStyle(const DrawingStyle& style);

// Luminance of an 8-bit RGB pixel in [0, 1]: (299 R + 587 G + 114 B) / (1000 x 255) (Rec. 601).
float drawingLuminance(std::uint8_t r, std::uint8_t g, std::uint8_t b);

// The ink mask of `image` (width x height bytes, 1 = ink): opaque pixels darker than `threshold`,
// dilated by `dilation` pixels. Expects a checked style's values and an image whose rgba holds
// width x height x 4 bytes (else vdg::Error).
std::vector<std::uint8_t> contourMask(const TextureImage& image, float threshold, int dilation);

// The drawing as `style` prepares it (a copy; file_bytes cleared):
//  - kAsDrawn: unchanged;
//  - kFillInk: every ink pixel (contourMask) takes the colour and alpha of the nearest opaque
//    non-ink pixel, nearest by 4-connected steps through ink (a breadth-first fill from every such
//    pixel at once, the first to arrive winning, in row-major order of the sources); ink that no
//    such pixel reaches becomes transparent (alpha 0). So no filled pixel is darker than the
//    threshold: each copies a pixel that was not;
//  - kFlat: the opaque non-ink pixels fall into regions, joined through 4-neighbours whose colours
//    differ by at most kFlatColourStep a channel (the image as drawn, before any pixel changes); every
//    pixel of a region takes the region's per-channel median colour (the lower median for an even
//    count), then the ink is filled as for kFillInk. A painted area, bounded by ink lines or by a
//    sharp change of colour, becomes one flat colour.
// Throws vdg::Error as checkDrawingStyle and for an rgba that does not hold width x height x 4 bytes.
TextureImage prepareDrawing(const TextureImage& image, const DrawingStyle& style);

// The colour of a fragment (the rule the renderer's fragment shader follows): with the slot
// weights w_i (the view's key weights, 0 for an empty slot or a key without a drawing), the base's
// weight w_b, the drawings' texels (premultiplied by nothing: rgb and alpha in [0, 1]) and the
// interpolated visibilities v_i in [0, 1], and `shaded` the model's own shading there,
//   a_i = w_i v_i alpha_i,   colour = (sum_i a_i rgb_i + w_b shaded) / (sum_i a_i + w_b),
// or `shaded` when sum_i a_i + w_b <= 1e-6 (no key sees the fragment and the base has no weight).
Rgb blendDrawingColors(const std::array<float, 3>& weights, float base_weight,
                       const std::array<std::array<float, 4>, 3>& texels, const std::array<float, 3>& visibility,
                       const Rgb& shaded);

class DrawingTextures {
 public:
  // `drawings` has one entry per key of `model` (null: the key has no drawing); every key with a
  // drawing needs a camera (model.keyCamera). The images are prepared with `style`. Throws
  // vdg::Error "drawing textures: ..." for another count, a key with a drawing but no camera
  // (naming the key), an empty image or one whose rgba does not match its size (naming the key),
  // and as checkDrawingStyle. A model without drawings builds (every key without one).
  static DrawingTextures build(const ViewDependentModel& model,
                               std::span<const std::shared_ptr<const TextureImage>> drawings,
                               const DrawingStyle& style = {});

  std::size_t keyCount() const { return layers_.size(); }
  std::size_t vertexCount() const { return vertex_count_; }
  // Keys with a drawing.
  std::size_t drawingCount() const;
  // The accessors below take a key index < keyCount() (else vdg::Error "drawing textures: key K out
  // of range (the model has N keys)"); image(), projective() and visibility() need hasDrawing(key)
  // (else vdg::Error naming the key).
  bool hasDrawing(std::size_t key) const;
  // The prepared drawing.
  const TextureImage& image(std::size_t key) const;
  // #V x 3: (s, t, q) per vertex (q > 0 for a vertex in front of the key camera, else 0).
  std::span<const float> projective(std::size_t key) const;
  // #V: 1 seen by the key camera, 0 not.
  std::span<const float> visibility(std::size_t key) const;
  // (s/q, t/q) of `vertex`: where it lies in the drawing, in [0, 1]^2 inside it ((0, 0) top-left);
  // (NaN, NaN) for a vertex at or behind the eye. The drawing's pixel is this times (width, height).
  Eigen::Vector2d texCoord(std::size_t key, std::size_t vertex) const;

 private:
  struct Layer {
    std::shared_ptr<const TextureImage> image;  // null: no drawing
    std::vector<float> stq, visible;
  };
  const Layer& layer(std::size_t key, bool need_drawing) const;
  std::vector<Layer> layers_;
  std::size_t vertex_count_ = 0;
};

}  // namespace vdg::render
