// SceneRenderer — one frame of a scene (vdg/scene/scene.h): every visible object of the hierarchy
// drawn with the NPR style of renderer.h, seen by the scene's active camera (Rademacher 99,
// section 5 and Figure 13; Parent 4.4 and 4.7).
//
// Per frame: Scene::evaluate gives every node's object-to-world transform; each view-dependent
// instance is blended with its own view direction (Scene::instanceView: from the instance's
// centre to the eye, in the instance's object coordinates) and each animated model at its own
// frame; the blended positions are carried into the world on the CPU and drawn with the node's
// colour as Cbase (materials of the object's base mesh on top, unless turned off), so the hue rule
// of shading.h shows per object. An object used by many nodes is registered with the GPU once
// (one SurfaceTopology); its instances are drawn one after another from the same buffers.
//
// Camera: the scene's active camera. A scene without one is framed automatically: looking at the
// box that holds every visible object over the frames [frame_first, frame_last] (each model's
// extent(): its base and every key), from the front and 15 degrees above.
// Clip planes: fitted per frame to the boxes of the objects drawn in that frame.
// A frame depends only on its number and the options: rendered alone or in a sequence, it is the
// same image, byte for byte.
#pragma once

#include <memory>

#include "vdg/geom/camera.h"
#include "vdg/render/image.h"
#include "vdg/render/renderer.h"
#include "vdg/scene/scene.h"

namespace vdg::render {

// The canvas and style shared with FrameOptions are in FrameSettings (renderer.h); a scene's
// canvas is 640 x 360 unless set, and its stroke width follows each object's size on screen
// (StrokeWidthMode::screen: the sphere about the object's box carried into the world, the width
// rounded to 1/4 pixel). With gpu_blend, the visible instances of one static view-dependent model
// are blended, shaded and inked in one call per frame and stroke width (drawBlendInstances;
// thinnest first), after the objects drawn on the CPU; animated models and plain meshes stay on
// the CPU path. The picture equals the CPU path's within rounding wherever objects do not overlap.
// Where they do, the GPU path shades every instance of a call before it inks them, so a nearer
// instance's outline is not covered by a farther one of the same call drawn after it; on the CPU
// path each object is shaded and inked in turn, and a farther object drawn later covers the outer
// half of a nearer one's silhouette stroke.
struct SceneFrameOptions : FrameSettings {
  SceneFrameOptions() {
    width = 640;
    height = 360;
    // A scene's objects lie at many distances (a crowd, Figure 13): their outlines follow their
    // size on screen unless set to fixed (StrokeWidthMode, renderer.h).
    stroke_mode = StrokeWidthMode::screen;
  }
  // The frames a scene without a camera is framed over (see above).
  double frame_first = 0.0, frame_last = 0.0;
};

class SceneRenderer {
 public:
  // `scene` must outlive the renderer. Throws vdg::Error for bad sizes or no GL (see Renderer).
  SceneRenderer(const scene::Scene& scene, const SceneFrameOptions& options);
  ~SceneRenderer();

  int width() const;
  int height() const;
  Renderer& renderer();
  // The number of objects drawn by the last render() (visible nodes holding an object).
  int drawnCount() const;

  // Renders `frame` into `out` and returns the camera used. Throws vdg::Error "scene: frame F:
  // ..." for a non-finite frame or a degenerate camera (eye on its centre of interest), and
  // "render: ... (internal error)" if a call it makes refuses its input (a bug, never bad data).
  Camera render(double frame, Image& out);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace vdg::render
