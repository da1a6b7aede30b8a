// SphereInset — the viewing-sphere diagram of Rademacher 99, Figure 4: the key viewpoints as dark
// dots (dummy base points as small hollow grey dots), the hull triangulation in wireframe (in the
// cosine modes also the arcs bounding the covered region), the triangle the current view falls in
// filled green with its three corners in red, and the current view as a blue marker with its ray
// from the centre. An equator and a front meridian in light grey give the orientation.
//
// ModelRenderer draws it in a corner of the main view (FrameOptions::sphere): the bottom-right one
// unless the model's picture reaches into it more than into another (insetPlacement); vdg studio
// draws it as a panel and picks keys on it (keyAt).
//
// Built once from a ViewSphere (its points, triangles and arcs are copied: the sphere need not
// outlive the inset). draw() is a per-frame call: it reuses its buffers (they reach their size
// in the constructor) and follows the Renderer's per-frame contract (checked on entry, false with
// nothing drawn on a violation, no throw).
//
// The inset camera looks at the unit sphere from 30 degrees to the side of and 20 degrees above
// the current view (elevation clamped to [-70, 70] degrees), so the active triangle faces the
// viewer while the sphere's turning stays readable; it is a perspective camera of 30 degrees
// vertical field of view at the distance that fits a sphere of radius 1.15 into the panel.
#pragma once

#include <array>
#include <span>
#include <vector>

#include <Eigen/Core>

#include "vdg/geom/camera.h"
#include "vdg/render/renderer.h"
#include "vdg/render/shading.h"
#include "vdg/viewdep/sphere_map.h"
#include "vdg/viewdep/view_sphere.h"

namespace vdg::render {

// Where ModelRenderer puts the inset so that it hides as little of the model as it can: a square
// of `side` pixels, `margin` pixels from a corner of the view (`view`, canvas pixels), in the
// corner whose square holds the fewest of `points` (the model's vertices projected: x, y pairs in
// canvas pixels, x right, y down); between corners holding as many, the one whose square overlaps
// the points' bounding box least (a large face with no vertex in the corner still covers it);
// then in the order bottom-right (the paper's Figure 4 layout), bottom-left, top-right, top-left.
// A square larger than the view is placed at the view's origin. Pure, no allocation.
Viewport insetPlacement(const Viewport& view, int side, int margin, std::span<const float> points);

class SphereInset {
 public:
  // Builds the static geometry of the diagram (wireframe, guide circles, key and dummy dots).
  explicit SphereInset(const ViewSphere& sphere);

  // Lights and light colours of the hull's shading (ka and k1..k4 are the inset's own: a
  // diagram, mostly its own colours, lightly shaded). ModelRenderer sets FrameOptions::shading.
  ShadingParams shading;

  // The inset camera of the last draw() (the sphere is centred at the origin, radius 1); before
  // any draw, the camera for the view +Z and a square panel.
  const Camera& camera() const { return camera_; }

  // Draws the diagram into `viewport` (canvas pixels, y down): its outer one-pixel frame in grey,
  // the rest (the panel) cleared in white with its depth, then the diagram seen by the inset
  // camera for `view` (direction towards the eye, any finite length; the marker is drawn at
  // `view` and its ray runs from the centre to 1.25 `view`, so a unit view puts it on the sphere;
  // a zero view, as ModelRenderer passes for an eye at the model's centre, is accepted). `w` are
  // the view's weights on this sphere: w.triangle (filled, its corners in red) in [-1,
  // triangles()); when it is -1, the keys w.key[i] >= 0 with w.weight[i] > 0 are drawn in red.
  // The panel keeps the aspect of the viewport (the sphere fits its shorter side); lines and dots
  // scale with that side (1 px per 120 px, at least 1 px).
  // Per-frame contract (false, nothing drawn): a viewport narrower or lower than 3 pixels, a
  // non-finite view, w.triangle outside [-1, triangles()), a key index outside [-1, keyCount()).
  [[nodiscard]] bool draw(Renderer& r, const Viewport& viewport, const Eigen::Vector3d& view, const ViewWeights& w);

  // The real key (index into the sphere's keys, < keyCount(); dummies never) whose dot, as the
  // last draw() into `viewport` placed it with camera(), is nearest to `pixel`, among the keys
  // within radius_px of it (distance to the dot's centre) on the visible half of the sphere: keys p
  // with (eye - p) . p > 0, i.e. in front of the sphere's outline as the inset camera sees it.
  // `pixel` is in canvas coordinates, x right, y down, (0, 0) the top-left corner of the canvas
  // (pixel (i, j) covers [i, i + 1) x [j, j + 1)). Returns -1 when no key qualifies, and for a
  // viewport draw() would refuse, a non-finite pixel or a radius that is not finite and >= 0.
  // Pure, no allocation, no throw. Ties go to the lower index.
  int keyAt(const Viewport& viewport, const Eigen::Vector2d& pixel, double radius_px = 10.0) const;

  // The "where to key next" heat map on the sphere (vdg/viewdep/sphere_map.h; vdg studio's toggle):
  // kHeatSamples dots spread evenly over the sphere, each coloured by the need of its map cell
  // (heatColour of sphere_map_image.h, in kHeatBins steps), and the suggested view as a cyan dot,
  // drawn over the hull by every draw() until setHeat(nullptr). Not per-frame: it builds buffers.
  static constexpr int kHeatSamples = 2500;
  static constexpr int kHeatBins = 8;
  void setHeat(const SphereMap* map);
  bool hasHeat() const { return !heat_suggested_.empty(); }

  // The panel of `viewport` (without its frame) in which the diagram is drawn and projected.
  static Viewport panel(const Viewport& viewport);

 private:
  std::vector<Eigen::Vector3d> points_;  // the sphere's points: keys first, then dummies
  std::size_t key_count_ = 0;
  std::vector<std::array<int, 3>> triangles_;
  Camera camera_;
  // Static parts, built once; per-frame parts in reused buffers (#N x 3 floats).
  std::vector<float> wire_, guide_, key_dots_, dummy_dots_;
  std::vector<float> hull_rest_, active_tri_, active_dots_, view_ray_, view_dot_;
  std::array<std::vector<float>, kHeatBins> heat_dots_;  // per need bin, #N x 3
  std::vector<float> heat_suggested_;
};

}  // namespace vdg::render
