// The editor's viewport picture: the drawing (a backdrop blended over paper), the shape the
// session shows drawn with the NPR shading and silhouettes (Rademacher 99, 3.2.4) or as a
// wireframe, and optionally the viewing-sphere inset (Figure 4) in its bottom-right corner. Drawn
// by a vdg::render::Renderer in its own EGL context into an Image the window shows as a texture.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include <Eigen/Core>

#include "vdg/geom/camera.h"
#include "vdg/geom/material.h"
#include "vdg/geom/tri_mesh.h"
#include "vdg/render/image.h"
#include "vdg/render/renderer.h"
#include "vdg/render/shading.h"
#include "vdg/viewdep/model.h"

namespace vdg::studio::app {

struct ViewportStyle {
  bool show_drawing = true;
  float drawing_opacity = 0.5f;  // [0, 1]
  bool wireframe = false;
  bool sphere_inset = false;
  bool sphere_heat = false;  // the inset shows where to key next (vdg/viewdep/sphere_map.h)
  vdg::render::Rgb paper{0.97f, 0.97f, 0.95f};
};

class ViewportRenderer {
 public:
  // `base` gives the triangles and the surface (materials are not drawn: the editor's model is
  // plain white so that the drawing shows through the comparison). `drawing` may be null.
  ViewportRenderer(const TriMesh& base, const TextureImage* drawing);
  ~ViewportRenderer();

  // The viewing sphere the inset shows (a model built from the session's keys), or none.
  void setSphereModel(std::shared_ptr<const ViewDependentModel> model);
  // The inset's viewport in canvas pixels (valid after render with style.sphere_inset).
  vdg::render::Viewport insetViewport() const;
  // The key whose dot is at canvas pixel `pixel` in the inset, or -1.
  int insetKeyAt(const Eigen::Vector2d& pixel) const;
  bool insetAvailable() const;
  // The suggested next view of the inset's heat map (after a render with style.sphere_heat), or none.
  std::optional<Eigen::Vector3d> suggestedView() const;

  // Renders positions (#V x 3) seen by `camera` into a width x height canvas (recreated when the
  // size changes) and returns it. Throws vdg::Error when the renderer cannot be made.
  const vdg::render::Image& render(int width, int height, const Camera& camera, std::span<const float> positions,
                                   const ViewportStyle& style, double scene_radius);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace vdg::studio::app
