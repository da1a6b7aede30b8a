// One frame of a view-dependent model: Rademacher 99, section 3.2 (locate, weigh, blend, render),
// with the observer panel of Figure 6 (bottom row) and the viewing-sphere diagram of Figure 4.
#include "vdg/render/model_renderer.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <span>
#include <string>
#include <utility>

#include "vdg/geom/error.h"
#include "vdg/geom/normalize.h"
#include "vdg/geom/surface.h"
#include "vdg/geom/text.h"
#include "vdg/render/sphere_inset.h"

#include "renderer_impl.h"

namespace vdg::render {
namespace {

// The renderer's per-frame calls return false on a broken contract; every call here passes sizes
// and views built by this file, so a refusal is a bug of ours, reported as such.
void check(bool ok, const char* what) {
  if (!ok) throw Error(std::string("render: ") + what + " was refused (internal error)");
}

// A draw call's refusal with its reason: a View that cannot be drawn (a camera at an infinite
// distance, clip planes that overflow) names what is wrong with it and what was being drawn.
void checkDraw(bool ok, const char* what, const View& view, const std::string& drawn) {
  if (ok) return;
  const char* problem = detail::viewProblem(view);
  if (!problem) check(ok, what);
  throw Error(std::string("render: ") + drawn + ": " + what + " refused the view: " + problem);
}

constexpr double kDegToRad = std::numbers::pi / 180.0;
constexpr double kFovDeg = 30.0;
constexpr Rgb kBorderColor{0.7f, 0.7f, 0.7f};  // the separator between the panels
constexpr Rgb kCameraMarkColor{0.9f, 0.45f, 0.1f};

void checkSize(int w, int h, const char* what) {
  if (w < 1 || h < 1 || w > kMaxImageSize || h > kMaxImageSize)
    throw Error(std::string("render: ") + what + " " + std::to_string(w) + "x" + std::to_string(h) +
                " is outside 1x1 .. " + std::to_string(kMaxImageSize) + "x" + std::to_string(kMaxImageSize));
}

}  // namespace

Camera orbitCamera(const Eigen::Vector3d& center, double distance, double azimuth_deg, double elevation_deg,
                   double fov_deg) {
  const double az = azimuth_deg * kDegToRad, el = elevation_deg * kDegToRad;
  Camera c;
  c.target = center;
  c.eye = center + distance * Eigen::Vector3d(std::sin(az) * std::cos(el), std::sin(el), std::cos(az) * std::cos(el));
  c.up = Eigen::Vector3d::UnitY();
  c.fov_deg = fov_deg;
  return c;
}

double fitDistance(double radius, double fov_deg, double aspect) {
  const double half_v = 0.5 * fov_deg * kDegToRad;
  const double half = std::min(half_v, std::atan(std::tan(half_v) * std::min(1.0, aspect)));
  return 1.1 * radius / std::sin(half);
}

double projectedDiameter(const Camera& camera, int height, const Eigen::Vector3d& center, double radius) {
  if (camera.isOrtho()) return 2.0 * radius / camera.ortho_height * height;
  const double d = (center - camera.eye).norm();
  if (d <= radius) return std::numeric_limits<double>::infinity();
  // The sphere's angular radius a at distance d: tan a = r / sqrt(d^2 - r^2); its picture at the
  // centre of a view of vertical field fov spans tan a / tan(fov / 2) half-heights.
  const double tan_a = radius / std::sqrt((d - radius) * (d + radius));
  return tan_a / std::tan(0.5 * camera.fov_deg * kDegToRad) * height;
}

float strokeWidthFor(const FrameSettings& s, double diameter_px) {
  if (s.stroke_mode == StrokeWidthMode::fixed) return s.silhouette_width;
  const float hi = std::max(s.stroke_min, s.stroke_max > 0.0f ? s.stroke_max : s.silhouette_width);
  // Rounded to a quarter pixel: the same width for pictures that differ in rounding only (a model
  // and its export), and few distinct widths in a crowd (the GPU blend draws one call per width).
  // The reference: an object spanning half the image's height gets silhouette_width.
  const double w = std::round(4.0 * static_cast<double>(s.silhouette_width) * diameter_px / (0.5 * s.height)) / 4.0;
  if (!(w >= s.stroke_min)) return s.stroke_min;  // NaN (no size) as well
  return static_cast<float>(std::min<double>(w, hi));
}

void checkStrokeRange(const FrameSettings& s) {
  if (s.stroke_mode == StrokeWidthMode::fixed) return;
  if (!(std::isfinite(s.stroke_min) && s.stroke_min > 0.0f) || !std::isfinite(s.stroke_max))
    throw Error("render: the screen stroke width needs a finite minimum > 0 and a finite maximum (got " +
                numberText(s.stroke_min) + " and " + numberText(s.stroke_max) + ")");
}

struct ModelRenderer::Impl {
  const ViewDependentModel* model = nullptr;
  const AnimatedViewDependentModel* animated = nullptr;  // section 4; `model` is then null
  int frame = 0;                                         // of `animated`
  TriMesh plain;                                         // the plain mesh (no model)
  FrameOptions options;
  Renderer renderer;
  int mesh_id = -1;
  int blend_id = -1;                 // options.gpu_blend: the model's GPU blend handle
  int drawings_id = -1;              // options.drawings: their handle in the renderer
  std::vector<float> positions;      // this frame's; the renderer computes the normals per smoothing group
  std::vector<float> dense;          // an rbf model: every key's weight and the base's (keyCount() + 1)
  std::vector<float> screen_points;  // the vertices projected, for the inset's corner (x, y pairs)
  Eigen::Vector3d center = Eigen::Vector3d::Zero();
  double radius = 1.0;
  Camera observer;
  std::optional<SphereInset> inset;  // the viewing-sphere diagram (a view-dependent model)

  Impl(const FrameOptions& o, int image_width)
      : options(o), renderer(RendererSettings{image_width, o.height, o.samples}) {}

  const TriMesh& base() const { return model ? model->base() : animated ? animated->base() : plain; }
  // What is drawn, for messages (the renderer is not told the file).
  const char* drawn() const {
    return model ? "the view-dependent model" : animated ? "the animated model" : "the mesh";
  }
  bool viewDependent() const { return model || animated; }
  const ViewSphere& sphere() const { return model ? model->sphere() : animated->sphere(); }

  void setup() {
    const TriMesh& mesh = base();
    positions = mesh.positions;
    if (model && model->sphere().settings().scheme == WeightScheme::Rbf) dense.resize(model->keyCount() + 1);
    screen_points.resize(positions.size() / 3 * 2);
    // The GPU blend registers the model itself (below); the CPU path draws a surface.
    if (!(options.gpu_blend && model)) mesh_id = renderer.addSurface(mesh, SurfaceTopology::build(mesh));
    // Frame what will be drawn: a model's extent (the base and every key, at every frame of an
    // animated base), not the base alone, so a key that raises the top stays inside the clip
    // planes and the observer panel.
    if (viewDependent()) {
      center = model ? model->center() : animated->center();
      radius = model ? model->extentRadius() : animated->extentRadius();
    } else {
      const Bounds b = computeBounds(mesh.positions);
      const auto c = b.center();
      center = Eigen::Vector3d(c[0], c[1], c[2]);
      radius = std::max(1e-6, 0.5 * static_cast<double>(b.diagonal()));
    }
    // Coordinates near the float limit give an infinite extent, and no camera can frame it.
    if (!center.allFinite() || !std::isfinite(radius))
      throw Error(std::string("render: ") + drawn() + ": its extent overflows a float (bounding radius " +
                  numberText(radius) + "), so no camera can frame it");
    if (options.silhouette_width <= 0.0f)
      options.silhouette_width = std::max(3.0f, static_cast<float>(options.height) / 100.0f);
    checkStrokeRange(options);
    const double aspect = static_cast<double>(options.width) / options.height;
    observer = options.observer_camera ? *options.observer_camera
                                       : orbitCamera(center, fitDistance(radius, kFovDeg, aspect), 35.0, 25.0, kFovDeg);
    if (options.gpu_blend) {
      if (!model)
        throw Error(std::string("render: the GPU blend (--gpu-blend) takes a static view-dependent model; ") +
                    (animated ? "an animated model (base_animation) is blended on the CPU"
                              : "a plain mesh has no keys to blend"));
      blend_id = renderer.addBlendModel(*model);
    }
    if (options.drawings) addDrawings();
    if (!viewDependent()) {
      check(renderer.updateMesh(mesh_id, positions, {}), "updateMesh");
      return;
    }
    inset.emplace(sphere());
    inset->shading = options.shading;
  }

  void addDrawings() {
    const DrawingTextures& d = *options.drawings;
    if (!model || options.gpu_blend)
      throw Error(std::string("render: drawing textures take a static view-dependent model blended on the CPU, not ") +
                  (options.gpu_blend ? "the GPU blend (--gpu-blend)"
                   : animated        ? "an animated model"
                                     : "a plain mesh"));
    if (d.keyCount() != model->keyCount() || d.vertexCount() != model->vertexCount())
      throw Error("render: drawing textures built for " + std::to_string(d.keyCount()) + " keys and " +
                  std::to_string(d.vertexCount()) + " vertices; the model has " + std::to_string(model->keyCount()) +
                  " keys and " + std::to_string(model->vertexCount()) + " vertices");
    drawings_id = renderer.addDrawings(mesh_id, d);
  }

  // The model's vertices projected into the main view (x, y pixel pairs in screen_points, points
  // behind the eye left out): of the base for a static model (the GPU blend path has no blended
  // positions on the CPU, and both paths must place the inset alike), of this frame's pose for an
  // animated one. No allocation: screen_points has room for every vertex from the set-up on.
  std::span<const float> projectedPoints(const Camera& camera) {
    const double aspect = static_cast<double>(options.width) / options.height;
    const double d = (camera.eye - center).norm();
    const Eigen::Matrix4d to_clip =
        projectionMatrix(camera, aspect, std::max(0.01 * radius, d - 2.0 * radius), d + 2.0 * radius) *
        viewMatrix(camera);
    const std::vector<float>& p = model ? model->base().positions : positions;
    screen_points.resize(p.size() / 3 * 2);
    std::size_t n = 0;
    for (std::size_t v = 0; v + 2 < p.size(); v += 3) {
      const Eigen::Vector4d c = to_clip * Eigen::Vector4d(p[v], p[v + 1], p[v + 2], 1.0);
      if (!(c.w() > 0.0)) continue;
      screen_points[n++] = static_cast<float>((c.x() / c.w() + 1.0) * 0.5 * options.width);
      screen_points[n++] = static_cast<float>((1.0 - c.y() / c.w()) * 0.5 * options.height);
    }
    return std::span<const float>(screen_points).first(n);
  }

  // The inset in a corner of the main view: a square of 28% of its shorter side (at least 48
  // pixels) inside a one-pixel frame, a margin of 1/20 of that from the corner; the bottom-right
  // corner unless the model's picture reaches further into it than into another
  // (insetPlacement: by the projected vertices in each corner).
  void drawSphereInset(const Eigen::Vector3d& view, const ViewWeights& w, const Camera& camera) {
    const int side = std::max(48, static_cast<int>(0.28 * std::min(options.width, options.height)));
    const int margin = std::max(2, side / 20);
    const Viewport main{0, 0, options.width, options.height};
    const Viewport area = insetPlacement(main, side + 2, margin - 1, projectedPoints(camera));
    check(inset->draw(renderer, area, view, w), "SphereInset::draw");
  }
};

ModelRenderer::ModelRenderer(const ViewDependentModel& model, const FrameOptions& options) {
  model.requireNoParts("the renderer (vdg render, studio)");
  model.requireViewDirections("the renderer (vdg render, studio)");
  if (options.gpu_blend) model.requireThreeKeyWeights("the GPU blend (--gpu-blend; the CPU blend evaluates it)");
  checkSize(options.width, options.height, "image size");
  const int image_width = options.observer ? options.width * 2 : options.width;
  checkSize(image_width, options.height, "image size with the observer panel");
  impl_ = std::make_unique<Impl>(options, image_width);
  impl_->model = &model;
  impl_->setup();
}

ModelRenderer::ModelRenderer(const AnimatedViewDependentModel& model, const FrameOptions& options) {
  checkSize(options.width, options.height, "image size");
  const int image_width = options.observer ? options.width * 2 : options.width;
  checkSize(image_width, options.height, "image size with the observer panel");
  impl_ = std::make_unique<Impl>(options, image_width);
  impl_->animated = &model;
  impl_->setup();
}

ModelRenderer::ModelRenderer(const TriMesh& mesh, const FrameOptions& options) {
  checkSize(options.width, options.height, "image size");
  const int image_width = options.observer ? options.width * 2 : options.width;
  checkSize(image_width, options.height, "image size with the observer panel");
  validateMesh(mesh, "render mesh");
  impl_ = std::make_unique<Impl>(options, image_width);
  impl_->plain = mesh;
  impl_->options.sphere = false;
  impl_->setup();
}

ModelRenderer::~ModelRenderer() = default;

int ModelRenderer::imageWidth() const { return impl_->renderer.width(); }
int ModelRenderer::imageHeight() const { return impl_->renderer.height(); }
Renderer& ModelRenderer::renderer() { return impl_->renderer; }
const TriMesh& ModelRenderer::baseMesh() const { return impl_->base(); }

void ModelRenderer::setFrame(int frame) {
  const int count = impl_->animated ? impl_->animated->frameCount() : 1;
  if (frame < 0 || frame >= count)
    throw Error("render: frame " + std::to_string(frame) + " out of range (the model has " + std::to_string(count) +
                " frame" + (count == 1 ? "" : "s") + ")");
  impl_->frame = frame;
}

ViewWeights ModelRenderer::render(const Camera& camera, Image& out) {
  Impl& m = *impl_;
  (void)cameraFrame(camera);  // throws vdg::Error naming a degenerate camera (eye == target, ...)
  const FrameOptions& o = m.options;
  ViewWeights w;
  w.base = 1.0f;
  Eigen::Vector3d view = Eigen::Vector3d::UnitZ();
  if (m.model) {
    // Section 3.2.1: the view direction is the ray from the eye through the model's centre
    // (for a parallel camera, the reversed viewing axis).
    view = camera.isOrtho() ? Eigen::Vector3d((camera.eye - camera.target).normalized())
                            : m.model->viewFromEye(camera.eye);
    const bool viewed = !o.base_only && view.allFinite() && view.norm() > 0.0;
    if (viewed && !m.dense.empty()) {  // the rbf scheme: every key weighs (view_sphere.h)
      check(m.model->denseWeights(view, o.sharpness, m.dense), "denseWeights");
      w = heaviestKeys(m.dense);
    } else if (viewed) {
      check(m.model->weights(view, o.sharpness, w), "weights");
    } else {  // the base only, or the eye at the model's centre (no view direction): the base model
      w = ViewWeights{};
      w.base = 1.0f;
    }
    if (m.blend_id < 0) {
      if (viewed && !m.dense.empty())
        check(m.model->blendDense(m.dense, m.positions), "blendDense");
      else
        check(m.model->blend(w, m.positions), "blend");
      check(m.renderer.updateMesh(m.mesh_id, m.positions, {}), "updateMesh");
    }
  } else if (m.animated) {
    // Section 4.1: the same per frame, on the animated base at frame m.frame.
    view = camera.isOrtho()
               ? Eigen::Vector3d((camera.eye - camera.target).normalized())
               : normalizedOrNone(Eigen::Vector3d(camera.eye - m.center)).value_or(Eigen::Vector3d::Zero());
    if (!o.base_only && view.allFinite() && view.norm() > 0.0) {
      check(m.animated->weights(view, o.sharpness, w), "weights");
      check(m.animated->evaluate(m.frame, view, o.sharpness, m.positions), "evaluate");
    } else {  // the base only, or the eye at the model's centre: the base at this frame
      w = ViewWeights{};
      w.base = 1.0f;
      const auto frame = m.animated->baseFrame(m.frame);
      std::copy(frame.begin(), frame.end(), m.positions.begin());
    }
    check(m.renderer.updateMesh(m.mesh_id, m.positions, {}), "updateMesh");
  }

  m.renderer.clear(o.background);
  MeshStyle style;
  style.color = o.color;
  style.shading = o.shading;
  style.flat = o.flat;
  // Screen mode: the stroke follows the picture of the sphere holding everything the model draws.
  style.silhouette_width = strokeWidthFor(o, projectedDiameter(camera, o.height, m.center, m.radius));
  style.borders = o.borders;
  style.crease_angle_deg = o.crease_angle_deg;
  style.materials = o.materials;
  // Clip planes around the sphere that holds everything the model draws (twice its radius: room
  // for the observer panel's camera mark at 1.5 radii).
  auto clip = [&](View& v) {
    const double d = (v.camera.eye - m.center).norm();
    v.z_near = std::max(0.01 * m.radius, d - 2.0 * m.radius);
    v.z_far = d + 2.0 * m.radius;
  };
  // The mesh as the CPU blended it, or blended on the GPU (one instance, in model space).
  InstanceBlend instance;
  instance.weights = w;
  const auto draw = [&](const View& v, const MeshStyle& s, bool with_drawings = false) {
    if (with_drawings && m.drawings_id >= 0) {
      checkDraw(m.renderer.drawMeshDrawings(m.mesh_id, m.drawings_id, v, s, w), "drawMeshDrawings", v, m.drawn());
      return;
    }
    if (m.blend_id < 0) {
      checkDraw(m.renderer.drawMesh(m.mesh_id, v, s), "drawMesh", v, m.drawn());
      return;
    }
    instance.color = s.color;
    checkDraw(m.renderer.drawBlendInstances(m.blend_id, {&instance, 1}, v, s), "drawBlendInstances", v, m.drawn());
  };
  View main;
  main.viewport = {0, 0, o.width, o.height};
  main.camera = camera;
  clip(main);
  draw(main, style, true);

  if (o.observer) {
    View obs;
    obs.viewport = {o.width, 0, o.width, o.height};
    obs.camera = m.observer;
    clip(obs);
    MeshStyle observer_style = style;
    observer_style.color = o.observer_color;
    observer_style.materials = false;
    observer_style.silhouette_width = strokeWidthFor(o, projectedDiameter(m.observer, o.height, m.center, m.radius));
    observer_style.shading.vary_by_hue = false;
    observer_style.shading.k = effectiveConstants(o.shading, o.observer_color);
    observer_style.shading.k.k2 *= 0.25f;
    draw(obs, observer_style);
    // Where the main camera is: a short orange ray from the centre towards its eye.
    std::array<float, 6> ray;
    const Eigen::Vector3d tip = m.center + view * (1.5 * m.radius);
    const Eigen::Vector3d root = m.center + view * (1.05 * m.radius);
    for (int i = 0; i < 3; ++i) {
      ray[i] = static_cast<float>(root[i]);
      ray[3 + i] = static_cast<float>(tip[i]);
    }
    checkDraw(m.renderer.drawLines(ray, obs, std::max(1.5f, o.silhouette_width), kCameraMarkColor, true), "drawLines",
              obs, m.drawn());
    check(m.renderer.drawDots(std::span<const float>(ray).subspan(3), obs, 3.0f * std::max(1.5f, o.silhouette_width),
                              kCameraMarkColor, true),
          "drawDots");
    // A thin separator between the two panels.
    const Viewport sep{o.width, 0, std::max(1, o.width / 256), o.height};
    m.renderer.clear(kBorderColor, &sep);
  }
  if (o.sphere && m.viewDependent()) m.drawSphereInset(view, w, camera);
  m.renderer.readPixels(out);
  return w;
}

}  // namespace vdg::render
