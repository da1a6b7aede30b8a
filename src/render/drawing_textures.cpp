// View-dependent textures from the reference drawings: Rademacher 99, section 6 (future work), after
// Debevec, Yu and Borshukov 98 (projective texture coordinates from each reference view, blended by
// the view's weights, occlusion from a depth map of each reference view). The blend weights are the
// model's own (section 3.2.2); the contour suppression answers the paper's warning that drawings
// blend badly because of their contour lines.
#include "vdg/render/drawing_textures.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <numbers>
#include <span>
#include <string>

#include "vdg/geom/camera.h"
#include "vdg/geom/error.h"
#include "vdg/geom/text.h"

namespace vdg::render {
namespace {

constexpr std::uint8_t kOpaque = 128;  // alpha from which a pixel belongs to the drawing

void checkImage(const TextureImage& image, const std::string& what) {
  const auto bytes =
      static_cast<std::size_t>(std::max(image.width, 0)) * static_cast<std::size_t>(std::max(image.height, 0)) * 4;
  if (image.width < 1 || image.height < 1)
    throw Error("drawing textures: " + what + ": the image is empty (" + std::to_string(image.width) + "x" +
                std::to_string(image.height) + ")");
  if (image.rgba.size() != bytes)
    throw Error("drawing textures: " + what + ": a " + std::to_string(image.width) + "x" +
                std::to_string(image.height) + " image has " + std::to_string(image.rgba.size()) +
                " bytes of RGBA, not " + std::to_string(bytes));
}

// Calls visit(q) for each 4-neighbour q of pixel p that lies inside a w x h image.
template <class Visit>
void forEachNeighbour(std::size_t p, int w, int h, Visit&& visit) {
  const int x = static_cast<int>(p % static_cast<std::size_t>(w)),
            y = static_cast<int>(p / static_cast<std::size_t>(w));
  const int nx[4] = {x - 1, x + 1, x, x}, ny[4] = {y, y, y - 1, y + 1};
  for (int i = 0; i < 4; ++i)
    if (nx[i] >= 0 && ny[i] >= 0 && nx[i] < w && ny[i] < h)
      visit(static_cast<std::size_t>(ny[i]) * static_cast<std::size_t>(w) + static_cast<std::size_t>(nx[i]));
}

// Fills every `hole` pixel from the nearest non-hole opaque pixel by 4-connected steps through
// holes (breadth-first from all sources at once, sources in row-major order); unreached holes
// become transparent.
void fillHoles(TextureImage& image, const std::vector<std::uint8_t>& hole) {
  const int w = image.width, h = image.height;
  const std::size_t n = hole.size();
  std::vector<std::uint8_t> done(n, 0);
  std::vector<std::size_t> queue;
  queue.reserve(n);
  for (std::size_t p = 0; p < n; ++p)
    if (!hole[p] && image.rgba[p * 4 + 3] >= kOpaque) {
      done[p] = 1;
      queue.push_back(p);
    }
  for (std::size_t head = 0; head < queue.size(); ++head) {
    const std::size_t p = queue[head];
    forEachNeighbour(p, w, h, [&](std::size_t q) {
      if (done[q] || !hole[q]) return;
      done[q] = 1;
      std::copy_n(&image.rgba[p * 4], 4, &image.rgba[q * 4]);
      queue.push_back(q);
    });
  }
  for (std::size_t p = 0; p < n; ++p)
    if (hole[p] && !done[p]) image.rgba[p * 4 + 3] = 0;
}

// Whether two pixels' colours are within kFlatColourStep on every channel.
bool nearColour(const std::uint8_t* a, const std::uint8_t* b) {
  for (int c = 0; c < 3; ++c)
    if (std::abs(static_cast<int>(a[c]) - static_cast<int>(b[c])) > kFlatColourStep) return false;
  return true;
}

// Every region (opaque non-ink pixels joined through 4-neighbours of near colour) takes its
// per-channel median colour.
void flattenRegions(TextureImage& image, const std::vector<std::uint8_t>& ink) {
  const int w = image.width, h = image.height;
  const std::size_t n = ink.size();
  std::vector<std::uint8_t> seen(n, 0);
  std::vector<std::size_t> region;
  for (std::size_t start = 0; start < n; ++start) {
    if (seen[start] || ink[start] || image.rgba[start * 4 + 3] < kOpaque) continue;
    region.clear();
    region.push_back(start);
    seen[start] = 1;
    for (std::size_t head = 0; head < region.size(); ++head) {
      const std::size_t p = region[head];
      forEachNeighbour(p, w, h, [&](std::size_t q) {
        if (seen[q] || ink[q] || image.rgba[q * 4 + 3] < kOpaque || !nearColour(&image.rgba[p * 4], &image.rgba[q * 4]))
          return;
        seen[q] = 1;
        region.push_back(q);
      });
    }
    for (int c = 0; c < 3; ++c) {
      std::array<std::size_t, 256> histogram{};
      for (const std::size_t p : region) ++histogram[image.rgba[p * 4 + static_cast<std::size_t>(c)]];
      const std::size_t middle = (region.size() - 1) / 2;  // the lower median
      std::size_t below = 0;
      int median = 0;
      while (below + histogram[static_cast<std::size_t>(median)] <= middle)
        below += histogram[static_cast<std::size_t>(median++)];
      for (const std::size_t p : region)
        image.rgba[p * 4 + static_cast<std::size_t>(c)] = static_cast<std::uint8_t>(median);
    }
  }
}

// The key shape's depth seen from the key camera: width x height view-axis depths at pixel centres
// (+infinity where nothing is), every triangle rasterised with its depth interpolated as the
// projection makes it (1/depth linear on the screen for a perspective camera, depth for a parallel one).
struct DepthBuffer {
  int width = 0, height = 0;
  std::vector<float> depth;
  std::vector<std::int32_t> triangle;  // the nearest triangle's index at each pixel, -1: none
};

// Whether vertex `v` at pixel (px, py) is seen: one of its own triangles is the nearest surface at a
// pixel within one pixel of it (so a surface seen at a slant, whose depth changes fast between pixel
// centres, still sees its vertices), or its depth is within `tolerance` of the nearest at its pixel.
bool seen(const DepthBuffer& buffer, std::span<const std::int32_t> triangles, std::int32_t v, int px, int py,
          double depth, double tolerance) {
  for (int y = std::max(0, py - 1); y <= std::min(buffer.height - 1, py + 1); ++y)
    for (int x = std::max(0, px - 1); x <= std::min(buffer.width - 1, px + 1); ++x) {
      const std::int32_t t = buffer.triangle[static_cast<std::size_t>(y) * static_cast<std::size_t>(buffer.width) +
                                             static_cast<std::size_t>(x)];
      if (t < 0) continue;
      const auto corner = static_cast<std::size_t>(t) * 3;
      if (triangles[corner] == v || triangles[corner + 1] == v || triangles[corner + 2] == v) return true;
    }
  const float nearest =
      buffer
          .depth[static_cast<std::size_t>(py) * static_cast<std::size_t>(buffer.width) + static_cast<std::size_t>(px)];
  return depth <= static_cast<double>(nearest) + tolerance;
}

// A vertex in the key camera: its pixel position in a w x h picture and its view-axis depth.
struct KeyPoint {
  double x = 0.0, y = 0.0, depth = 0.0;
  bool front = false;  // in front of the eye
};

KeyPoint toKey(const Camera& camera, const CameraFrame& f, double half_x, double half_y, int w, int h, const float* p) {
  const Eigen::Vector3d d = Eigen::Vector3d(p[0], p[1], p[2]) - camera.eye;
  const double x = d.dot(f.right), y = d.dot(f.up), depth = -d.dot(f.back);
  KeyPoint k;
  k.depth = depth;
  k.front = camera.isOrtho() || depth > 0.0;
  const double scale = camera.isOrtho() ? 1.0 : 1.0 / depth;
  k.x = (x * scale / half_x + 1.0) * 0.5 * w;
  k.y = (1.0 - y * scale / half_y) * 0.5 * h;
  return k;
}

void rasterise(DepthBuffer& buffer, std::int32_t index, const KeyPoint& a, const KeyPoint& b, const KeyPoint& c,
               bool ortho) {
  if (!a.front || !b.front || !c.front) return;  // a triangle across the eye's plane is left out
  const double area = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
  if (!(std::abs(area) > 0.0) || !std::isfinite(area)) return;  // degenerate, or a vertex projected to infinity
  // The bounding box, clamped to the buffer in doubles first (a vertex near the eye's plane
  // projects arbitrarily far away, beyond what an int holds).
  const auto clampTo = [](double v, int hi) { return static_cast<int>(std::clamp(v, -1.0, static_cast<double>(hi))); };
  const int x0 = std::max(0, clampTo(std::floor(std::min({a.x, b.x, c.x})), buffer.width));
  const int x1 = std::min(buffer.width - 1, clampTo(std::ceil(std::max({a.x, b.x, c.x})), buffer.width));
  const int y0 = std::max(0, clampTo(std::floor(std::min({a.y, b.y, c.y})), buffer.height));
  const int y1 = std::min(buffer.height - 1, clampTo(std::ceil(std::max({a.y, b.y, c.y})), buffer.height));
  // What is linear on the screen: 1 / depth (perspective) or depth (parallel).
  const double za = ortho ? a.depth : 1.0 / a.depth, zb = ortho ? b.depth : 1.0 / b.depth,
               zc = ortho ? c.depth : 1.0 / c.depth;
  for (int y = y0; y <= y1; ++y)
    for (int x = x0; x <= x1; ++x) {
      const double px = x + 0.5, py = y + 0.5;
      const double l1 = ((c.x - b.x) * (py - b.y) - (c.y - b.y) * (px - b.x)) / area;
      const double l2 = ((a.x - c.x) * (py - c.y) - (a.y - c.y) * (px - c.x)) / area;
      const double l3 = 1.0 - l1 - l2;
      if (l1 < 0.0 || l2 < 0.0 || l3 < 0.0) continue;
      const double z = l1 * za + l2 * zb + l3 * zc;
      const double depth = ortho ? z : 1.0 / z;
      const std::size_t cell =
          static_cast<std::size_t>(y) * static_cast<std::size_t>(buffer.width) + static_cast<std::size_t>(x);
      if (static_cast<float>(depth) < buffer.depth[cell]) {
        buffer.depth[cell] = static_cast<float>(depth);
        buffer.triangle[cell] = index;
      }
    }
}

}  // namespace

void checkDrawingStyle(const DrawingStyle& style) {
  if (!(style.contour_threshold > 0.0f && style.contour_threshold <= 1.0f))
    throw Error("drawing textures: the contour threshold must be a luminance in (0, 1], got " +
                numberText(style.contour_threshold));
  if (style.dilation < 0 || style.dilation > kMaxContourDilation)
    throw Error("drawing textures: the contour dilation must be 0 to " + std::to_string(kMaxContourDilation) +
                " pixels, got " + std::to_string(style.dilation));
}

float drawingLuminance(std::uint8_t r, std::uint8_t g, std::uint8_t b) {
  return static_cast<float>(299 * r + 587 * g + 114 * b) / (1000.0f * 255.0f);
}

std::vector<std::uint8_t> contourMask(const TextureImage& image, float threshold, int dilation) {
  checkImage(image, "contourMask");
  const int w = image.width, h = image.height;
  const std::size_t n = static_cast<std::size_t>(w) * static_cast<std::size_t>(h);
  std::vector<std::uint8_t> dark(n, 0), mask(n, 0);
  for (std::size_t p = 0; p < n; ++p) {
    const std::uint8_t* c = &image.rgba[p * 4];
    dark[p] = c[3] >= kOpaque && drawingLuminance(c[0], c[1], c[2]) < threshold;
  }
  // Dilation by a square: rows first, then columns (separable), each a running window count.
  std::vector<std::uint8_t> rows(n, 0);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      bool any = false;
      for (int dx = std::max(0, x - dilation); dx <= std::min(w - 1, x + dilation) && !any; ++dx)
        any = dark[static_cast<std::size_t>(y) * static_cast<std::size_t>(w) + static_cast<std::size_t>(dx)];
      rows[static_cast<std::size_t>(y) * static_cast<std::size_t>(w) + static_cast<std::size_t>(x)] = any;
    }
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      bool any = false;
      for (int dy = std::max(0, y - dilation); dy <= std::min(h - 1, y + dilation) && !any; ++dy)
        any = rows[static_cast<std::size_t>(dy) * static_cast<std::size_t>(w) + static_cast<std::size_t>(x)];
      mask[static_cast<std::size_t>(y) * static_cast<std::size_t>(w) + static_cast<std::size_t>(x)] = any;
    }
  return mask;
}

TextureImage prepareDrawing(const TextureImage& image, const DrawingStyle& style) {
  checkDrawingStyle(style);
  checkImage(image, "prepareDrawing");
  TextureImage out;
  out.width = image.width;
  out.height = image.height;
  out.rgba = image.rgba;
  if (style.mode == DrawingMode::kAsDrawn) return out;
  const std::vector<std::uint8_t> ink = contourMask(image, style.contour_threshold, style.dilation);
  if (style.mode == DrawingMode::kFlat) flattenRegions(out, ink);
  fillHoles(out, ink);
  return out;
}

Rgb blendDrawingColors(const std::array<float, 3>& weights, float base_weight,
                       const std::array<std::array<float, 4>, 3>& texels, const std::array<float, 3>& visibility,
                       const Rgb& shaded) {
  Rgb sum{0.0f, 0.0f, 0.0f};
  float total = base_weight;
  for (int i = 0; i < 3; ++i) {
    const float a = weights[static_cast<std::size_t>(i)] *
                    std::clamp(visibility[static_cast<std::size_t>(i)], 0.0f, 1.0f) *
                    texels[static_cast<std::size_t>(i)][3];
    for (int c = 0; c < 3; ++c)
      sum[static_cast<std::size_t>(c)] += a * texels[static_cast<std::size_t>(i)][static_cast<std::size_t>(c)];
    total += a;
  }
  if (!(total > 1e-6f)) return shaded;
  Rgb out;
  for (int c = 0; c < 3; ++c)
    out[static_cast<std::size_t>(c)] =
        (sum[static_cast<std::size_t>(c)] + base_weight * shaded[static_cast<std::size_t>(c)]) / total;
  return out;
}

DrawingTextures DrawingTextures::build(const ViewDependentModel& model,
                                       std::span<const std::shared_ptr<const TextureImage>> drawings,
                                       const DrawingStyle& style) {
  checkDrawingStyle(style);
  if (drawings.size() != model.keyCount())
    throw Error("drawing textures: " + std::to_string(drawings.size()) + " drawings for a model of " +
                std::to_string(model.keyCount()) + " keys (give one entry per key, null for none)");
  DrawingTextures out;
  out.vertex_count_ = model.vertexCount();
  out.layers_.resize(model.keyCount());
  const std::size_t nv = model.vertexCount();
  std::vector<float> key_positions(nv * 3);
  const std::span<const std::int32_t> triangles = model.base().triangles;
  const double tolerance = kVisibilityDepthTolerance * model.extentRadius();
  for (std::size_t k = 0; k < model.keyCount(); ++k) {
    if (!drawings[k]) continue;
    const std::string what = "key '" + model.keyName(k) + "'";
    const std::optional<Camera>& camera = model.keyCamera(k);
    if (!camera)
      throw Error("drawing textures: " + what + " has a drawing but no camera (the viewpoint it was drawn from)");
    checkImage(*drawings[k], what);
    const CameraFrame frame = cameraFrame(*camera);
    if (!model.keyPositions(k, key_positions))
      throw Error("drawing textures: " + what + ": keyPositions refused (internal error)");
    Layer& layer = out.layers_[k];
    layer.image = std::make_shared<const TextureImage>(prepareDrawing(*drawings[k], style));
    // The depth buffer: the drawing's size, scaled down to kMaxDepthBufferSide a side.
    const TextureImage& image = *layer.image;
    const double shrink = std::min(1.0, static_cast<double>(kMaxDepthBufferSide) / std::max(image.width, image.height));
    DepthBuffer buffer;
    buffer.width = std::max(1, static_cast<int>(std::lround(image.width * shrink)));
    buffer.height = std::max(1, static_cast<int>(std::lround(image.height * shrink)));
    buffer.depth.assign(static_cast<std::size_t>(buffer.width) * static_cast<std::size_t>(buffer.height),
                        std::numeric_limits<float>::infinity());
    buffer.triangle.assign(buffer.depth.size(), -1);
    const double aspect = static_cast<double>(image.width) / image.height;
    const double half_y =
        camera->isOrtho() ? 0.5 * camera->ortho_height : std::tan(camera->fov_deg * std::numbers::pi / 360.0);
    const double half_x = half_y * aspect;
    std::vector<KeyPoint> points(nv);
    for (std::size_t v = 0; v < nv; ++v)
      points[v] = toKey(*camera, frame, half_x, half_y, buffer.width, buffer.height, &key_positions[v * 3]);
    for (std::size_t t = 0; t + 2 < triangles.size(); t += 3)
      rasterise(buffer, static_cast<std::int32_t>(t / 3), points[static_cast<std::size_t>(triangles[t])],
                points[static_cast<std::size_t>(triangles[t + 1])], points[static_cast<std::size_t>(triangles[t + 2])],
                camera->isOrtho());
    layer.stq.assign(nv * 3, 0.0f);
    layer.visible.assign(nv, 0.0f);
    for (std::size_t v = 0; v < nv; ++v) {
      const KeyPoint& p = points[v];
      if (!p.front) continue;
      // (s, t, q) = q (u, v, 1) with (u, v) the place in the drawing and q the depth (1 for a
      // parallel camera): linear in the vertex's position, so interpolating them and dividing
      // per fragment projects the drawing exactly.
      const double q = camera->isOrtho() ? 1.0 : p.depth;
      const double u = p.x / buffer.width, t = p.y / buffer.height;
      layer.stq[v * 3] = static_cast<float>(u * q);
      layer.stq[v * 3 + 1] = static_cast<float>(t * q);
      layer.stq[v * 3 + 2] = static_cast<float>(q);
      if (!(u >= 0.0 && u < 1.0 && t >= 0.0 && t < 1.0)) continue;
      layer.visible[v] = seen(buffer, triangles, static_cast<std::int32_t>(v), static_cast<int>(p.x),
                              static_cast<int>(p.y), p.depth, tolerance)
                             ? 1.0f
                             : 0.0f;
    }
  }
  return out;
}

std::size_t DrawingTextures::drawingCount() const {
  return static_cast<std::size_t>(
      std::count_if(layers_.begin(), layers_.end(), [](const Layer& l) { return l.image != nullptr; }));
}

const DrawingTextures::Layer& DrawingTextures::layer(std::size_t key, bool need_drawing) const {
  if (key >= layers_.size())
    throw Error("drawing textures: key " + std::to_string(key) + " out of range (the model has " +
                std::to_string(layers_.size()) + " keys)");
  if (need_drawing && !layers_[key].image)
    throw Error("drawing textures: key " + std::to_string(key) + " has no drawing");
  return layers_[key];
}

bool DrawingTextures::hasDrawing(std::size_t key) const { return layer(key, false).image != nullptr; }
const TextureImage& DrawingTextures::image(std::size_t key) const { return *layer(key, true).image; }
std::span<const float> DrawingTextures::projective(std::size_t key) const { return layer(key, true).stq; }
std::span<const float> DrawingTextures::visibility(std::size_t key) const { return layer(key, true).visible; }

Eigen::Vector2d DrawingTextures::texCoord(std::size_t key, std::size_t vertex) const {
  const Layer& l = layer(key, true);
  if (vertex >= vertex_count_)
    throw Error("drawing textures: vertex " + std::to_string(vertex) + " out of range (the model has " +
                std::to_string(vertex_count_) + " vertices)");
  const double q = l.stq[vertex * 3 + 2];
  if (!(q > 0.0)) return Eigen::Vector2d::Constant(std::numeric_limits<double>::quiet_NaN());
  return {l.stq[vertex * 3] / q, l.stq[vertex * 3 + 1] / q};
}

}  // namespace vdg::render
