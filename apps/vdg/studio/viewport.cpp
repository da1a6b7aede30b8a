#include "viewport.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <utility>

#include "vdg/geom/error.h"
#include "vdg/geom/surface.h"
#include "vdg/render/sphere_inset.h"
#include "vdg/viewdep/sphere_map.h"

namespace vdg::studio::app {

namespace {

using vdg::render::Image;
using vdg::render::Renderer;
using vdg::render::Rgb;
using vdg::render::Viewport;

}  // namespace

struct ViewportRenderer::Impl {
  TriMesh base;
  SurfaceTopology topology;
  const TextureImage* drawing = nullptr;
  std::unique_ptr<Renderer> renderer;
  int mesh = -1;
  int backdrop = -1;
  std::vector<std::pair<std::int32_t, std::int32_t>> edges;  // unique edges, for the wireframe
  std::vector<float> segments;
  Image image;
  std::shared_ptr<const ViewDependentModel> sphere_model;
  std::unique_ptr<vdg::render::SphereInset> inset;
  Viewport inset_viewport;
  std::optional<vdg::SphereMap> heat;  // computed when the heat map is first shown for this model
};

ViewportRenderer::ViewportRenderer(const TriMesh& base, const TextureImage* drawing) : impl_(std::make_unique<Impl>()) {
  impl_->base = base;
  // The editor shows the paper's plain NPR shading (white Cbase), the clearest over a drawing: the
  // mesh's materials and textures are left out.
  impl_->base.materials.clear();
  impl_->base.face_materials.clear();
  impl_->topology = SurfaceTopology::build(impl_->base);
  impl_->drawing = drawing;
  std::set<std::pair<std::int32_t, std::int32_t>> unique;
  const auto& t = base.triangles;
  for (std::size_t f = 0; f + 2 < t.size(); f += 3)
    for (int c = 0; c < 3; ++c) {
      std::int32_t a = t[f + c], b = t[f + (c + 1) % 3];
      if (a > b) std::swap(a, b);
      unique.insert({a, b});
    }
  impl_->edges.assign(unique.begin(), unique.end());
}

ViewportRenderer::~ViewportRenderer() = default;

void ViewportRenderer::setSphereModel(std::shared_ptr<const ViewDependentModel> model) {
  impl_->sphere_model = std::move(model);
  impl_->inset.reset();
  impl_->heat.reset();
  if (impl_->sphere_model) impl_->inset = std::make_unique<vdg::render::SphereInset>(impl_->sphere_model->sphere());
}

bool ViewportRenderer::insetAvailable() const { return impl_->inset != nullptr; }

std::optional<Eigen::Vector3d> ViewportRenderer::suggestedView() const {
  if (!impl_->heat) return std::nullopt;
  return impl_->heat->suggested;
}

Viewport ViewportRenderer::insetViewport() const { return impl_->inset_viewport; }

int ViewportRenderer::insetKeyAt(const Eigen::Vector2d& pixel) const {
  if (impl_->inset && impl_->inset_viewport.width > 0) return impl_->inset->keyAt(impl_->inset_viewport, pixel);
  return -1;
}

const Image& ViewportRenderer::render(int width, int height, const Camera& camera, std::span<const float> positions,
                                      const ViewportStyle& style, double scene_radius) {
  Impl& m = *impl_;
  if (!m.renderer || m.renderer->width() != width || m.renderer->height() != height) {
    m.renderer.reset();
    m.renderer = std::make_unique<Renderer>(vdg::render::RendererSettings{width, height, 4});
    m.mesh = m.renderer->addSurface(m.base, m.topology);
    m.backdrop = m.drawing != nullptr ? m.renderer->addBackdrop(*m.drawing) : -1;
  }
  Renderer& r = *m.renderer;
  if (!r.updateMesh(m.mesh, positions, {})) throw Error("studio: the viewport refused the mesh (internal error)");

  vdg::render::View view;
  view.viewport = {0, 0, width, height};
  view.camera = camera;
  const double distance = (camera.eye - camera.target).norm();
  const double radius = std::max(scene_radius, 1e-6);
  view.z_far = distance + 4.0 * radius;
  view.z_near = std::max(view.z_far * 1e-4, distance - 4.0 * radius);

  r.clear(style.paper);
  const bool drawing = m.drawing != nullptr && style.show_drawing;
  if (drawing && !r.drawBackdrop(m.backdrop, view.viewport, style.drawing_opacity, style.paper))
    throw Error("studio: the viewport refused the drawing (internal error)");
  if (style.wireframe) {
    m.segments.resize(m.edges.size() * 6);
    for (std::size_t e = 0; e < m.edges.size(); ++e)
      for (int c = 0; c < 3; ++c) {
        m.segments[e * 6 + c] = positions[static_cast<std::size_t>(m.edges[e].first) * 3 + c];
        m.segments[e * 6 + 3 + c] = positions[static_cast<std::size_t>(m.edges[e].second) * 3 + c];
      }
    if (!r.drawLines(m.segments, view, 1.0f, Rgb{0.15f, 0.2f, 0.45f}, false))
      throw Error("studio: the viewport refused the wireframe (internal error)");
  } else {
    vdg::render::MeshStyle mesh_style;
    mesh_style.silhouette_width = std::max(2.0f, static_cast<float>(height) / 250.0f);
    if (!r.drawMesh(m.mesh, view, mesh_style)) throw Error("studio: the viewport refused the camera (internal error)");
  }
  m.inset_viewport = {};
  if (style.sphere_inset && m.inset) {
    const int side = std::max(64, std::min(width, height) / 4);
    m.inset_viewport = {width - side, height - side, side, side};
    // The heat map: a coarse map (a fraction of a second for Spot), once per model of the keys.
    constexpr int kHeatWidth = 180, kHeatHeight = 90;
    if (style.sphere_heat && !m.heat) m.heat = vdg::computeSphereMap(*m.sphere_model, {kHeatWidth, kHeatHeight});
    if (style.sphere_heat != m.inset->hasHeat()) m.inset->setHeat(style.sphere_heat ? &*m.heat : nullptr);
    const Eigen::Vector3d dir = (camera.eye - m.sphere_model->center()).normalized();
    ViewWeights w;
    if (m.sphere_model->weights(dir, 0.0, w)) (void)m.inset->draw(r, m.inset_viewport, dir, w);
  }
  r.readPixels(m.image);
  return m.image;
}

}  // namespace vdg::studio::app
