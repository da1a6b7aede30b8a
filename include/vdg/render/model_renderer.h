// ModelRenderer — one frame of a view-dependent model (Rademacher 99, section 3.2): evaluate the
// model for the camera's view direction, render it with the NPR style, and optionally add
//  - the observer panel (Figure 6, bottom row): the same blended model seen from a fixed,
//    independent camera, in a bluish colour, to the right of the main view, so the 3D distortion
//    is visible;
//  - the viewing-sphere inset (Figure 4): key viewpoints as dots (dummy base points as small hollow
//    grey dots), the hull triangulation in wireframe, the active triangle filled green with its
//    keys in red, and the current view as a blue marker with its ray from the centre
//    (SphereInset, sphere_inset.h).
//
// The mesh is drawn as a surface (SurfaceTopology of the base, Renderer::addSurface): seams of
// the file are welded for silhouettes and normals, and its hard edges (vertices split with
// different file normals) stay hard in every blend, since the renderer recomputes the normals
// from the blended positions per smoothing group.
//
// The image is width x height (main view), or 2*width x height with the observer panel.
// Rendering is deterministic: a frame depends only on the camera and the options.
#pragma once

#include <memory>
#include <optional>

#include "vdg/geom/camera.h"
#include "vdg/geom/tri_mesh.h"
#include "vdg/render/drawing_textures.h"
#include "vdg/render/image.h"
#include "vdg/render/renderer.h"
#include "vdg/viewdep/animated_model.h"
#include "vdg/viewdep/model.h"

namespace vdg::render {

// The canvas and style shared with SceneFrameOptions are in FrameSettings (renderer.h): width and
// height (the main view, each in [1, kMaxImageSize]), samples, background, shading, strokes,
// materials (the observer panel never uses them), base_only and gpu_blend (for an animated model
// or a plain mesh the renderer throws vdg::Error: the GPU blend takes static view-dependent models).
struct FrameOptions : FrameSettings {
  bool observer = false;                   // add the observer panel (doubles the width)
  bool sphere = false;                     // add the viewing-sphere inset (bottom-right of the main view)
  double sharpness = 0.0;                  // alpha of section 3.2.2; <= 0: the model's own
  Rgb color{1.0f, 1.0f, 1.0f};             // Cbase of faces without a material (white, as in the paper)
  Rgb observer_color{0.55f, 0.68f, 1.0f};  // Cbase in the observer panel (bluish, Figure 6),
                                           // lit with the warm light at a quarter (k2 * 0.25)
  bool flat = false;                       // per-face shading (hard-edged models such as the building)
  // The observer panel's camera; default: 35 degrees to the right of and 25 above the model's
  // front (+Z), at the distance that fits the sphere about the model's centre holding the base and
  // every key (extentRadius(); a plain mesh: its bounding box's sphere).
  std::optional<Camera> observer_camera;
  // The reference drawings as view-dependent textures (drawing_textures.h), built on this model:
  // the main view blends the drawings of the view's keys over the shading with the shape's weights
  // (Renderer::drawMeshDrawings; the observer panel stays plain). A static model blended on the CPU
  // only: the renderer throws vdg::Error "render: drawing textures ..." for an animated model, a
  // plain mesh, the GPU blend, or drawings built for another key or vertex count.
  std::shared_ptr<const DrawingTextures> drawings;
};

// A camera on an orbit around `center`: azimuth about +Y measured from +Z towards +X (0 = front),
// elevation above the XZ plane (|elevation| < 90), looking at the centre with +Y up.
Camera orbitCamera(const Eigen::Vector3d& center, double distance, double azimuth_deg, double elevation_deg,
                   double fov_deg);
// Distance at which a sphere of `radius` fits a perspective view of vertical field of view fov_deg
// and aspect width/height, with a 10% margin.
double fitDistance(double radius, double fov_deg, double aspect);

class ModelRenderer {
 public:
  // `model` must outlive the renderer. Throws vdg::Error for bad sizes or no GL (see Renderer).
  ModelRenderer(const ViewDependentModel& model, const FrameOptions& options);
  // An animated model (section 4), drawn at frame 0 until setFrame(); `model` must outlive the
  // renderer. The clip planes and the observer camera fit its extent over all its frames (the
  // base and every view's pose: AnimatedViewDependentModel::extentRadius()).
  ModelRenderer(const AnimatedViewDependentModel& model, const FrameOptions& options);
  // A plain mesh (no view dependence, no sphere inset); the mesh is copied.
  ModelRenderer(const TriMesh& mesh, const FrameOptions& options);
  ~ModelRenderer();

  int imageWidth() const;
  int imageHeight() const;
  Renderer& renderer();
  const TriMesh& baseMesh() const;
  // The animation frame the next render() calls draw, for an animated model: in [0, frameCount()),
  // else vdg::Error "render: frame F out of range (the model has N frames)". Other renderers
  // accept only 0.
  void setFrame(int frame);

  // Renders the frame seen by `camera` into `out`. Returns the blending weights used (all-base
  // for a plain mesh, and for an eye at the model's centre, which has no view direction). A model
  // with the rbf weight scheme is blended over every key (ViewDependentModel::blendDense); the
  // returned weights are then its three heaviest keys, with the base's and the other keys' weight
  // together as `base`, and no triangle.
  // Throws vdg::Error for a degenerate camera (see cameraFrame), and "render: ... (internal
  // error)" if an evaluation or draw call it makes refuses its input (a bug, never bad data).
  ViewWeights render(const Camera& camera, Image& out);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace vdg::render
