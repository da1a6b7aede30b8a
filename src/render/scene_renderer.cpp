// One frame of a scene: Rademacher 99, section 5 (Figure 13: several view-dependent objects, each
// blended for its own view of one moving camera), over the hierarchy of Parent 4.7.
#include "vdg/render/scene_renderer.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "vdg/geom/error.h"
#include "vdg/geom/surface.h"
#include "vdg/render/model_renderer.h"

#include "renderer_impl.h"

namespace vdg::render {
namespace {

void check(bool ok, const char* what) {
  if (!ok) throw Error(std::string("render: scene: ") + what + " was refused (internal error)");
}

// A draw call's refusal with its reason when the View is what cannot be drawn (a camera at an
// infinite distance, clip planes that overflow); otherwise a bug of ours.
void checkDraw(bool ok, const char* what, const View& view) {
  if (ok) return;
  const char* problem = detail::viewProblem(view);
  if (!problem) check(ok, what);
  throw Error(std::string("render: scene: ") + what + " refused the view: " + problem);
}

constexpr double kAutoFovDeg = 35.0;
constexpr double kAutoElevationDeg = 15.0;
// At most this many frames are sampled to frame a scene without a camera (evenly, ends included).
constexpr int kMaxFramingSamples = 256;

Bounds boundsOf(const scene::Scene& s, int node) {
  if (const auto* m = s.model(node)) return m->extent();
  if (const auto* a = s.animatedModel(node)) return a->extent();
  if (const auto* mesh = s.mesh(node)) return computeBounds(mesh->positions);
  return {};
}

// Grows [lo, hi] by the eight corners of `b` carried by `m`.
void growBox(const Bounds& b, const Eigen::Matrix4d& m, Eigen::Vector3d& lo, Eigen::Vector3d& hi) {
  for (int c = 0; c < 8; ++c) {
    const Eigen::Vector4d p((c & 1) ? b.max[0] : b.min[0], (c & 2) ? b.max[1] : b.min[1], (c & 4) ? b.max[2] : b.min[2],
                            1.0);
    const Eigen::Vector3d w = (m * p).head<3>();
    lo = lo.cwiseMin(w);
    hi = hi.cwiseMax(w);
  }
}

}  // namespace

struct SceneRenderer::Impl {
  // One object registered with the GPU, shared by every node that holds it.
  struct Object {
    int handle = -1;
    // GPU blend (options.gpu_blend, static view-dependent models only): the renderer's blend
    // model, and this frame's instances, gathered and drawn in one drawBlendInstances call.
    int blend_handle = -1;
    std::vector<InstanceBlend> instances;
    std::vector<std::pair<float, int>> widths;  // screen mode: each instance's stroke width and index
    std::vector<InstanceBlend> sorted;          // the instances in order of stroke width
    Bounds box;
    std::vector<float> local;  // this instance's blended positions, object coordinates
    std::vector<float> world;  // the same carried into the world
  };

  const scene::Scene& scene;
  SceneFrameOptions options;
  Renderer renderer;
  std::vector<int> object_of_node;  // index into objects, -1 for groups and cameras
  std::vector<Object> objects;
  std::vector<scene::NodeState> states;
  std::array<Eigen::Vector3d, kMaxParts + 1> part_views;  // a model with parts (and its rest): each part's view
  Camera auto_camera;
  bool has_auto_camera = false;
  int drawn = 0;

  Impl(const scene::Scene& s, const SceneFrameOptions& o)
      : scene(s), options(o), renderer(RendererSettings{o.width, o.height, o.samples}) {
    if (options.silhouette_width <= 0.0f)
      options.silhouette_width = std::max(3.0f, static_cast<float>(options.height) / 100.0f);
    checkStrokeRange(options);
    std::map<const void*, int> known;
    const int n = scene.nodeCount();
    object_of_node.assign(n, -1);
    states.resize(n);
    for (int i = 0; i < n; ++i) {
      const TriMesh* base = nullptr;
      const SurfaceTopology* topology = nullptr;
      const void* key = nullptr;
      if (const auto* m = scene.model(i)) {
        base = &m->base(), topology = &m->surface(), key = m;
      } else if (const auto* a = scene.animatedModel(i)) {
        base = &a->base(), topology = &a->surface(), key = a;
      } else if (const auto* mesh = scene.mesh(i)) {
        base = mesh, key = mesh;
      } else {
        continue;
      }
      auto [it, fresh] = known.try_emplace(key, static_cast<int>(objects.size()));
      if (fresh) {
        Object obj;
        if (const auto* m = scene.model(i); m && options.gpu_blend) {
          m->requireThreeKeyWeights("the GPU blend (--gpu-blend; the CPU blend evaluates it)");
          obj.blend_handle = renderer.addBlendModel(*m);
        } else {
          obj.handle = topology ? renderer.addSurface(*base, *topology)
                                : renderer.addSurface(*base, SurfaceTopology::build(*base));
          obj.local = base->positions;
          obj.world.resize(base->positions.size());
        }
        obj.box = boundsOf(scene, i);
        objects.push_back(std::move(obj));
      }
      object_of_node[i] = it->second;
    }
    // Room for every node of a blend model, so that frames allocate nothing on the CPU side.
    std::vector<std::size_t> nodes_of(objects.size(), 0);
    for (int i = 0; i < n; ++i)
      if (object_of_node[i] >= 0) ++nodes_of[static_cast<std::size_t>(object_of_node[i])];
    for (std::size_t k = 0; k < objects.size(); ++k)
      if (objects[k].blend_handle >= 0) {
        objects[k].instances.reserve(nodes_of[k]);
        objects[k].widths.reserve(nodes_of[k]);
        objects[k].sorted.reserve(nodes_of[k]);
      }
    if (scene.cameraNode() < 0) frameAutomatically();
  }

  // The box of every visible object at `frame` (false when nothing is drawn).
  bool worldBox(double frame, Eigen::Vector3d& lo, Eigen::Vector3d& hi) {
    check(scene.evaluate(frame, states), "evaluate");
    lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
    hi = -lo;
    bool any = false;
    for (std::size_t i = 0; i < states.size(); ++i) {
      if (object_of_node[i] < 0 || !states[i].visible) continue;
      growBox(objects[object_of_node[i]].box, states[i].object, lo, hi);
      any = true;
    }
    return any;
  }

  void frameAutomatically() {
    const double a = options.frame_first, b = std::max(options.frame_first, options.frame_last);
    const int samples = static_cast<int>(std::clamp(std::floor(b - a) + 1.0, 1.0, double(kMaxFramingSamples)));
    Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
    for (int k = 0; k < samples; ++k) {
      const double f = samples == 1 ? a : a + (b - a) * k / (samples - 1);
      Eigen::Vector3d l, h;
      if (worldBox(f, l, h)) lo = lo.cwiseMin(l), hi = hi.cwiseMax(h);
    }
    if (!lo.allFinite()) lo = hi = Eigen::Vector3d::Zero();
    const Eigen::Vector3d center = 0.5 * (lo + hi);
    const double radius = std::max(1e-6, 0.5 * (hi - lo).norm());
    const double aspect = static_cast<double>(options.width) / options.height;
    auto_camera = orbitCamera(center, fitDistance(radius, kAutoFovDeg, aspect), 0.0, kAutoElevationDeg, kAutoFovDeg);
    has_auto_camera = true;
  }

  // The stroke width of node `i` (StrokeWidthMode): by the picture of the sphere about its box
  // (base and keys: the model's extent) carried into the world. strokeWidthFor rounds it to a
  // quarter pixel, so the GPU blend draws the instances of one width in one call.
  float strokeWidth(const Camera& camera, std::size_t i) const {
    if (options.stroke_mode == StrokeWidthMode::fixed) return options.silhouette_width;
    const Bounds& b = objects[static_cast<std::size_t>(object_of_node[i])].box;
    const Eigen::Matrix4d& m = states[i].object;
    const auto c = b.center();
    const Eigen::Vector3d center = (m * Eigen::Vector4d(c[0], c[1], c[2], 1.0)).head<3>();
    const Eigen::Matrix3d linear = m.topLeftCorner<3, 3>();
    const double scale = linear.colwise().norm().maxCoeff();  // the largest stretch of a rotation and scale
    const double radius = std::max(1e-12, 0.5 * static_cast<double>(b.diagonal()) * scale);
    return strokeWidthFor(options, projectedDiameter(camera, options.height, center, radius));
  }

  // A blend model's instances, drawn in groups of one stroke width, thinnest first (in screen
  // mode the farthest and smallest, so a nearer instance's outline is drawn after them).
  void drawBlendObject(Object& obj, const View& view, MeshStyle& style) {
    if (options.stroke_mode == StrokeWidthMode::fixed) {
      checkDraw(renderer.drawBlendInstances(obj.blend_handle, obj.instances, view, style), "drawBlendInstances", view);
      return;
    }
    std::sort(obj.widths.begin(), obj.widths.end());
    obj.sorted.clear();
    for (const auto& [w, k] : obj.widths) obj.sorted.push_back(obj.instances[static_cast<std::size_t>(k)]);
    for (std::size_t a = 0; a < obj.widths.size();) {
      std::size_t b = a + 1;
      while (b < obj.widths.size() && obj.widths[b].first == obj.widths[a].first) ++b;
      style.silhouette_width = obj.widths[a].first;
      const std::span<const InstanceBlend> group(obj.sorted.data() + a, b - a);
      checkDraw(renderer.drawBlendInstances(obj.blend_handle, group, view, style), "drawBlendInstances", view);
      a = b;
    }
  }

  Camera render(double frame, Image& out) {
    if (!std::isfinite(frame)) throw Error("scene: frame is not a finite number");
    check(scene.evaluate(frame, states), "evaluate");
    Camera camera = auto_camera;
    if (!has_auto_camera && !scene.camera(frame, states, camera))
      throw Error("scene: frame " + std::to_string(frame) + ": the camera is degenerate (its eye is on its centre " +
                  "of interest, or its node's transform cannot be inverted)");

    // Clip planes around what this frame draws.
    const CameraFrame cf = cameraFrame(camera);
    const Eigen::Vector3d forward = -cf.back;
    double z_min = std::numeric_limits<double>::infinity(), z_max = 0.0;
    for (std::size_t i = 0; i < states.size(); ++i) {
      if (object_of_node[i] < 0 || !states[i].visible) continue;
      Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
      growBox(objects[object_of_node[i]].box, states[i].object, lo, hi);
      for (int c = 0; c < 8; ++c) {
        const Eigen::Vector3d p((c & 1) ? hi.x() : lo.x(), (c & 2) ? hi.y() : lo.y(), (c & 4) ? hi.z() : lo.z());
        const double z = (p - camera.eye).dot(forward);
        z_min = std::min(z_min, z);
        z_max = std::max(z_max, z);
      }
    }
    View view;
    view.viewport = {0, 0, options.width, options.height};
    view.camera = camera;
    if (camera.isOrtho()) {  // the eye may sit inside the scene: planes on both sides of it
      const double span = std::max({1e-3, std::abs(z_min), std::abs(z_max)});
      view.z_near = 1e-3 * span;
      view.z_far = std::isfinite(z_max) ? std::max(z_max * 1.05, 2 * view.z_near) : 100.0;
    } else {
      const double far = std::isfinite(z_max) && z_max > 0 ? z_max * 1.05 : 100.0;
      view.z_far = far;
      view.z_near = std::clamp(std::isfinite(z_min) ? z_min * 0.9 : 0.1, far * 1e-4, far * 0.5);
    }

    renderer.clear(options.background);
    MeshStyle style;
    style.shading = options.shading;
    style.silhouette_width = options.silhouette_width;
    style.borders = options.borders;
    style.crease_angle_deg = options.crease_angle_deg;
    style.materials = options.materials;
    drawn = 0;
    for (Object& obj : objects) {
      obj.instances.clear();
      obj.widths.clear();
    }
    for (std::size_t i = 0; i < states.size(); ++i) {
      const int o = object_of_node[i];
      if (o < 0 || !states[i].visible) continue;
      Object& obj = objects[o];
      const scene::NodeState& st = states[i];
      const int node = static_cast<int>(i);
      Eigen::Vector3d dir;
      const bool has_view = !options.base_only && scene.instanceView(node, st, camera.eye, dir);
      if (obj.blend_handle >= 0) {  // GPU blend: weights here, the blend in drawBlendInstances
        InstanceBlend instance;
        instance.object = st.object.cast<float>();
        instance.color = st.color;
        instance.weights.base = 1.0f;
        if (has_view) check(scene.model(node)->weights(dir, st.sharpness, instance.weights), "weights");
        obj.widths.emplace_back(strokeWidth(camera, i), static_cast<int>(obj.instances.size()));
        obj.instances.push_back(instance);
        ++drawn;
        continue;
      }
      if (const auto* m = scene.model(node)) {
        Eigen::Vector3d local_eye;  // keys at distances weigh the eye position (key_space.h)
        if (has_view && m->weightSpace() == WeightSpace::Positions)
          check(scene.instanceEye(node, st, camera.eye, local_eye) &&
                    m->evaluateAtEye(local_eye, st.sharpness, obj.local),
                "evaluate");
        else if (has_view && m->hasParts())  // each part at its own view (driven by a node or the camera)
          check(scene.instancePartViews(node, frame, states, camera.eye, {part_views.data(), m->partCount()}) &&
                    m->evaluateParts({part_views.data(), m->partCount()}, st.sharpness, obj.local),
                "evaluate");
        else if (has_view)
          check(m->evaluate(dir, st.sharpness, obj.local), "evaluate");
        else
          std::copy(m->base().positions.begin(), m->base().positions.end(), obj.local.begin());
      } else if (const auto* a = scene.animatedModel(node)) {
        if (has_view) {
          check(a->evaluate(st.model_frame, dir, st.sharpness, obj.local), "evaluate");
        } else {
          const auto base = a->baseFrame(st.model_frame);
          std::copy(base.begin(), base.end(), obj.local.begin());
        }
      } else {
        const auto& p = scene.mesh(node)->positions;
        std::copy(p.begin(), p.end(), obj.local.begin());
      }
      const Eigen::Matrix4d& m = st.object;
      for (std::size_t v = 0; v + 2 < obj.local.size(); v += 3) {
        const Eigen::Vector3d p(obj.local[v], obj.local[v + 1], obj.local[v + 2]);
        const Eigen::Vector3d w = m.topLeftCorner<3, 3>() * p + m.topRightCorner<3, 1>();
        obj.world[v] = static_cast<float>(w.x());
        obj.world[v + 1] = static_cast<float>(w.y());
        obj.world[v + 2] = static_cast<float>(w.z());
      }
      check(renderer.updateMesh(obj.handle, obj.world, {}), "updateMesh");
      style.color = st.color;
      style.silhouette_width = strokeWidth(camera, i);
      checkDraw(renderer.drawMesh(obj.handle, view, style), "drawMesh", view);
      ++drawn;
    }
    for (Object& obj : objects)
      if (obj.blend_handle >= 0 && !obj.instances.empty()) drawBlendObject(obj, view, style);
    renderer.readPixels(out);
    return camera;
  }
};

SceneRenderer::SceneRenderer(const scene::Scene& scene, const SceneFrameOptions& options)
    : impl_(std::make_unique<Impl>(scene, options)) {}
SceneRenderer::~SceneRenderer() = default;

int SceneRenderer::width() const { return impl_->options.width; }
int SceneRenderer::height() const { return impl_->options.height; }
Renderer& SceneRenderer::renderer() { return impl_->renderer; }
int SceneRenderer::drawnCount() const { return impl_->drawn; }
Camera SceneRenderer::render(double frame, Image& out) { return impl_->render(frame, out); }

}  // namespace vdg::render
