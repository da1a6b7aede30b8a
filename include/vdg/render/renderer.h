// Renderer — headless OpenGL NPR renderer (Rademacher 99, section 3.2.4): warm/cool shaded meshes
// with dark silhouettes, rendered offscreen with multisample anti-aliasing and read back as RGBA8.
//
// Context: EGL without any window system. Platforms are tried in this order: Mesa's surfaceless
// platform (EGL_MESA_platform_surfaceless; llvmpipe on a machine without a GPU), the EGL device
// platform (EGL_EXT_platform_device; NVIDIA and Mesa GPU drivers), the default display. An OpenGL
// 4.5 core context is requested, then 3.3 core. GL functions are loaded through libepoxy.
// Setting the environment variable VDG_RENDER_NO_GL=1 makes context creation fail as if no EGL
// display existed (to test the error path); VDG_RENDER_GL=3.3 makes the renderer take its context
// for OpenGL 3.3 (what an older driver gives: to test the GPU blend's error path; drivers may
// give a newer version than asked for, so asking for 3.3 would not do).
//
// Created once (owns the context, programs, framebuffers and buffers); per-frame calls reuse
// buffers and allocate nothing once the largest mesh has been seen. Per-frame calls check their
// input and return false on a violation (see updateMesh); they never throw std::out_of_range. Output is deterministic:
// the same calls give byte-identical images, whatever was drawn before. Not thread-safe; one thread.
//
// Surfaces and materials: addSurface registers a mesh with its SurfaceTopology (vdg/geom/surface.h).
// The GPU draws its render vertices (one per smoothing group and texture coordinate), so seams
// of the file do not show and its hard edges stay hard; silhouettes are found on the welded
// edges, so texture and normal seams are never inked as borders. Faces are drawn in one range
// per material: Cbase = the material's base_color, times the texel (mipmapped, repeating; uv
// origin at the bottom-left) when it has a texture and the mesh has texture coordinates. The hue
// rule of shading.h is applied per material, and per texel for a textured material (the shader
// runs the same rule on base_color x texel). Faces without a material use MeshStyle::color.
//
// Silhouettes: the paper draws the faces that span a silhouette edge a second time as thick back-
// face wireframe, depth-tested against the front faces, and a third time as points to fill the
// cracks between thick edges. Core profiles have no wide lines and no polygon point mode, so the
// same picture is drawn from the silhouette edges themselves (found per frame on the CPU, see
// silhouette.h): each edge becomes a screen-space quad of the requested width (geometry shader)
// and each edge end a round dot of the same diameter (point sprite), which fills the cracks. Both
// are depth-tested (LEQUAL) against the shaded front faces, which are pushed back under them in
// proportion to their depth slope (glPolygonOffset), so the inner half of a line is not buried in
// the faces beside its edge while a hidden outline just under a visible surface stays hidden.
//
// GPU blend (addBlendModel / drawBlendInstances; OpenGL 4.3 compute shaders): many instances of
// one view-dependent model, each blended for its own weights, in one call. The base positions
// and every key's delta (keyPositions - base, dense: keyCount() x #V x 3 floats) are uploaded once
// at set-up; per call only the instances (object matrix, key indices, weights, colour: 112 bytes
// each) are uploaded. Compute passes then, per instance:
//  1. blend: p = object * (base + sum_i w_i (key_i - base)) (section 3.2.3; world space);
//  2. normals per smoothing group, the rule of computeGroupNormals (each face's unnormalised
//     cross product summed over the corners of the group, normalised), gathered through a
//     precomputed list of (group -> faces) so no float atomics are needed;
//  3. edges: facing of each welded edge's two faces against the eye (faceFacing's test, world
//     space), appending silhouette, open-border and crease edges to index lists (one integer
//     atomic counter per list, in an indirect draw command).
// The instanced draw reads the blended positions and normals per render vertex (materials and
// textures as drawMesh), then the edge lists are drawn as drawMesh draws its strokes (quads plus
// round dots, the same programs): the picture equals drawMesh on the CPU-blended mesh within
// rounding. Instances are processed in batches sized so that each batch's buffers fit the
// driver's largest storage block (and at most kBlendBatchBytes in all), so any number of
// instances can be drawn; every batch's strokes lie over its own shaded faces and those of the
// batches before it.
//
// Backdrop (addBackdrop / drawBackdrop): a picture behind the model, such as the drawing that
// vdg studio aligns a key to. The image is uploaded once (RGBA8, mipmapped, linear filtering,
// clamped at its edges) and drawn stretched over a whole viewport, upright: its row 0 (the top
// of the picture, as TextureImage stores it) at the top of the viewport in readPixels' image and
// its column 0 at the left, whatever the aspect of the viewport. Each pixel becomes
// mix(paper, texel, opacity * texel_alpha) (8-bit channels as values in [0, 1], no gamma), and
// the viewport's depth is cleared, so a mesh drawn after lies over the picture.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <string>

#include "vdg/geom/camera.h"
#include "vdg/geom/material.h"
#include "vdg/geom/surface.h"
#include "vdg/geom/tri_mesh.h"
#include "vdg/render/drawing_textures.h"
#include "vdg/render/image.h"
#include "vdg/render/shading.h"
#include "vdg/viewdep/model.h"

namespace vdg::render {

// GPU blend: the most bytes of per-batch buffers (blended positions, normals, edge lists) one
// drawBlendInstances call allocates; more instances are drawn in several batches.
inline constexpr std::size_t kBlendBatchBytes = std::size_t{256} << 20;

// Largest canvas side accepted, in pixels.
inline constexpr int kMaxImageSize = 16384;

// Largest canvas side this machine's OpenGL driver reports: the smallest of GL_MAX_RENDERBUFFER_SIZE,
// GL_MAX_TEXTURE_SIZE and both GL_MAX_VIEWPORT_DIMS, and at most kMaxImageSize. Creates (and
// destroys) a context for the query; throws vdg::Error "EGL: ..." as Renderer does without GL.
// A driver may still fail to allocate a canvas below this limit when it needs more memory than
// the driver allows (llvmpipe: about 8192x8192 with 4 samples); Renderer then says so.
int maxImageSide();

struct RendererSettings {
  int width = 512, height = 512;  // canvas size in pixels, each in [1, kMaxImageSize]
  int samples = 8;                // MSAA samples; clamped to the driver's maximum; 1 = none
};

// A rectangle of the canvas in pixels, (x, y) = top-left corner, y down (image convention).
struct Viewport {
  int x = 0, y = 0, width = 0, height = 0;
};

// Where a draw call lands and how it projects: a camera, a viewport and the clip planes
// (distances along the view axis, 0 < z_near < z_far).
struct View {
  Viewport viewport;
  Camera camera;
  double z_near = 0.1, z_far = 100.0;
};

// How the frame renderers choose each object's silhouette stroke width.
//  - fixed: every object gets silhouette_width pixels (the paper's thick wireframe, section 3.2.4);
//  - screen: the width follows the object's size on screen, as a draftsman's line does, so that
//    small and distant figures are not swamped by their outlines: an object whose bounding sphere
//    spans D pixels of an image H pixels tall gets silhouette_width * D / (H / 2) pixels, rounded
//    to a quarter pixel and clamped to [stroke_min, stroke_max] (strokeWidthFor). An object
//    spanning half the frame's height or more gets the fixed width (the default maximum), so a
//    framed model looks as in the fixed mode; one twice as far (half the size) half of it, down to
//    the minimum.
enum class StrokeWidthMode { fixed, screen };

// What the frame renderers (ModelRenderer, SceneRenderer) take alike: the canvas and the style
// of the whole frame. FrameOptions and SceneFrameOptions add their own fields to it.
struct FrameSettings : RendererSettings {
  Rgb background{0.97f, 0.97f, 0.95f};  // light, as in the paper's figures
  ShadingParams shading;
  float silhouette_width = 0.0f;  // stroke width in pixels; 0: max(3, height / 100)
  StrokeWidthMode stroke_mode = StrokeWidthMode::fixed;
  float stroke_min = 1.0f;        // screen mode: the thinnest stroke, pixels (> 0)
  float stroke_max = 0.0f;        // screen mode: the thickest stroke, pixels; <= 0: silhouette_width
  bool borders = true;            // ink the true open borders (holes) of the surfaces
  float crease_angle_deg = 0.0f;  // ink edges sharper than this (degrees, half the stroke width); <= 0: none
  // The objects' materials and textures (per-material Cbase, hue rule per material and per
  // texel); false: the frame's base colour everywhere.
  bool materials = true;
  // Draw view-dependent models as their base (no key deformations, every view weighs the base
  // fully): the paper's comparison of a conventional model with the view-dependent one (Figures
  // 11 and 12), and a baseline for benchmarks.
  bool base_only = false;
  // Blend static view-dependent models on the GPU (Renderer::addBlendModel, OpenGL 4.3): the same
  // picture within rounding; a renderer throws vdg::Error "OpenGL: the GPU blend ... needs OpenGL
  // 4.3 ..." on an older driver (see each renderer for what stays on the CPU).
  bool gpu_blend = false;
};

// The diameter in pixels of the picture of a sphere (`center`, `radius` > 0, world units) seen by
// `camera` in a viewport `height` pixels tall: for a perspective camera 2 r' / tan(fov / 2) *
// height / 2, where r' = radius / sqrt(d^2 - radius^2) is the tangent of the sphere's angular
// radius at distance d from the eye (its picture at the centre of the view); for a parallel camera
// 2 radius / ortho_height * height. An eye inside the sphere gives +infinity; a sphere behind the
// eye is measured as if in front (its size, not its visibility).
double projectedDiameter(const Camera& camera, int height, const Eigen::Vector3d& center, double radius);

// The stroke width, in pixels, of an object whose bounding sphere spans `diameter_px` pixels, by
// `s.stroke_mode` (see StrokeWidthMode). `s.silhouette_width` must be resolved (> 0); a stroke_max
// <= 0 means silhouette_width, and a stroke_max below stroke_min is raised to it.
float strokeWidthFor(const FrameSettings& s, double diameter_px);
// Throws vdg::Error "render: the screen stroke width needs ..." when in screen mode stroke_min is
// not finite and > 0 or stroke_max is not finite (the frame renderers' constructors call it).
void checkStrokeRange(const FrameSettings& s);

struct MeshStyle {
  Rgb color{1.0f, 1.0f, 1.0f};  // Cbase of faces without a material (of every face when !materials)
  ShadingParams shading;
  bool flat = false;              // per-face normals instead of the mesh's vertex normals
  float silhouette_width = 3.0f;  // pixels; <= 0 draws no silhouettes (and no borders)
  Rgb silhouette_color{0.06f, 0.06f, 0.08f};
  // True open borders (edges of the welded surface with one face: holes, not seams) are drawn
  // with the silhouettes, as the paper's wireframe pass would.
  bool borders = true;
  // Creases: edges between two front faces whose normals differ by more than this angle
  // (degrees), drawn in silhouette_color; <= 0 (or not finite): none.
  float crease_angle_deg = 0.0f;
  float crease_width = 0.0f;  // pixels; <= 0: half the silhouette width
  // The mesh's materials and textures (addSurface); false: `color` everywhere, untextured.
  bool materials = true;
};

// One instance of a blended model (drawBlendInstances).
struct InstanceBlend {
  Eigen::Matrix4f object = Eigen::Matrix4f::Identity();  // object -> world (affine, finite)
  ViewWeights weights;          // from the model's sphere: key indices in [-1, keyCount()), finite weights
  Rgb color{1.0f, 1.0f, 1.0f};  // Cbase of faces without a material (of every face when !materials)
};

class Renderer {
 public:
  // Creates the EGL context and the framebuffers. Throws vdg::Error: "EGL: ..." when no display
  // or context can be had, "OpenGL: ..." when a shader fails or the driver cannot allocate the
  // canvas (the message gives the size, the samples and the driver), "render: ..." for a size
  // outside [1, kMaxImageSize].
  explicit Renderer(const RendererSettings& settings);
  ~Renderer();
  Renderer(Renderer&&) noexcept;
  Renderer& operator=(Renderer&&) noexcept;

  int width() const;
  int height() const;
  int samples() const;         // the MSAA sample count in use
  std::string glInfo() const;  // "GL_RENDERER / GL_VERSION / EGL platform"

  // Registers a mesh of `vertex_count` vertices and #F x 3 triangles. Builds its edge topology.
  // Returns its handle (0, 1, 2, ... in order of registration). Set-up, not per-frame: throws
  // vdg::Error "render: addMesh: ..." naming the triangle for a size that is not a multiple of 3
  // or an index outside [0, vertex_count).
  // Its topology is SurfaceTopology::unwelded (every vertex its own surface point: each open
  // edge of the index buffer is a border), it has no materials, and updateMesh's empty normals
  // mean flat shading.
  int addMesh(std::span<const std::int32_t> triangles, std::size_t vertex_count);

  // Registers a mesh as a surface: `topology` built on it (SurfaceTopology::build(mesh)), its
  // texture coordinates and its materials, whose textures are uploaded here (mipmapped,
  // repeating). Only the triangles, uvs and materials are read (positions come with updateMesh).
  // Returns its handle, numbered with addMesh's. Set-up, not per-frame: throws vdg::Error
  // "render: addSurface: ..." for a mesh validateMesh refuses, a topology built on another mesh
  // (vertex or triangle counts, or triangles, differ) and a texture larger than the driver allows.
  int addSurface(const TriMesh& mesh, const SurfaceTopology& topology);

  // Per-frame calls follow the contract of every vdg evaluation function (after ozz-animation's
  // jobs): sizes, handles and values are checked on entry; a violation returns false and has
  // changed nothing (no GPU buffer, no canvas pixel, no GL state the next call depends on); no
  // throw. Unlike the evaluation functions they may allocate (buffers grow to the largest data
  // seen), so a check failing is never an out-of-memory question but always a caller's bug.
  // A View is valid when its viewport has width, height >= 1, 0 < z_near < z_far (finite), and
  // its camera has finite eye, target and up, eye != target, up not parallel to the view axis and
  // (perspective) fov_deg in (0, 180).

  // Uploads this frame's positions (#V x 3) and normals (#V x 3, or empty). Empty normals mean,
  // for a surface (addSurface), normals computed from the positions per smoothing group
  // (computeGroupNormals: seams smooth, the file's hard edges kept), and for a mesh from addMesh
  // flat shading. Given normals are used per vertex (every render vertex takes its vertex's).
  // Violations: `mesh` not a handle from addMesh or addSurface; positions.size() != 3 *
  // vertex_count; normals neither empty nor positions.size().
  [[nodiscard]] bool updateMesh(int mesh, std::span<const float> positions, std::span<const float> normals);

  // Fills the whole canvas (viewport == nullptr) or one viewport with `color`, and clears depth.
  void clear(const Rgb& color, const Viewport* viewport = nullptr);
  // Shaded mesh (back faces culled), its creases and its silhouettes (and open borders) as seen
  // from view.camera. Violations: a bad handle, an invalid View.
  [[nodiscard]] bool drawMesh(int mesh, const View& view, const MeshStyle& style);
  // Overlays, for diagrams such as the viewing sphere:
  //  triangles #3N x 3 positions, shaded flat with `style` (no silhouettes, both sides drawn);
  //  line segments #2N x 3 positions (pairs), `width` pixels, round joints;
  //  dots #N x 3 positions, `diameter` pixels.
  // With depth_test, lines and dots are pulled towards the eye by `pull` pixels' worth of depth.
  // Empty input draws nothing (true). Violations: a size that is not a multiple of 9 / 6 / 3, an
  // invalid View, a width or diameter that is not finite or not > 0, a non-finite pull.
  [[nodiscard]] bool drawTriangles(std::span<const float> positions, const View& view, const MeshStyle& style);
  [[nodiscard]] bool drawLines(std::span<const float> segments, const View& view, float width, const Rgb& color,
                               bool depth_test, float pull = 1.0f);
  [[nodiscard]] bool drawDots(std::span<const float> points, const View& view, float diameter, const Rgb& color,
                              bool depth_test, float pull = 1.0f);

  // GPU blend (see the top of this file). Registers a static view-dependent model: its base
  // surface (model.surface()), materials and textures as addSurface, and its key deltas, uploaded
  // once (keyCount() x #V x 12 bytes of GPU memory, plus the topology). The model is not kept.
  // Returns a handle numbered apart from addMesh's (0, 1, 2, ... in order). Set-up, not per-frame:
  // throws vdg::Error "OpenGL: the GPU blend (--gpu-blend) needs OpenGL 4.3 (the driver gives
  // X)" on an older context, "render: addBlendModel: ..." when the deltas or one instance's
  // buffers exceed the driver's largest storage block, and as addSurface for its textures.
  int addBlendModel(const ViewDependentModel& model);

  // Blends, shades and inks every instance of blend model `handle` (see the top of this file)
  // as drawMesh would draw each instance's CPU blend transformed by its object matrix: back
  // faces culled, creases, silhouettes and open borders as `style` says. style.color is not
  // used: each instance's `color` takes its place. An empty span draws nothing (true). Per-frame
  // contract as above; violations: a bad handle, an invalid View, an instance with a non-finite
  // object matrix or colour, a key index outside [-1, keyCount()) or a non-finite weight.
  // Allocates GPU buffers when a call needs more than any before (up to kBlendBatchBytes).
  [[nodiscard]] bool drawBlendInstances(int handle, std::span<const InstanceBlend> instances, const View& view,
                                        const MeshStyle& style);

  // Passes 1 and 2 only (blend and group normals; see the top of this file), batch by batch as
  // drawBlendInstances runs them, drawing nothing: for timing the blend (with finish()) and for
  // readBlendInstance. Per-frame contract as drawBlendInstances (no View).
  [[nodiscard]] bool blendInstances(int handle, std::span<const InstanceBlend> instances);
  // Waits until the GPU has carried out every call so far (glFinish), for timing.
  void finish();

  // For tests and debugging (not per-frame): reads back the blended positions (#V x 3, world
  // space) and smoothing-group normals (#G x 3, G = model.surface().groupCount()) of
  // instances[instance] of the last drawBlendInstances or blendInstances call on `handle`.
  // Returns false, having written nothing, for a bad handle, an instance outside that call's last
  // batch (every instance is in it when the call fit one batch), or spans of other sizes.
  [[nodiscard]] bool readBlendInstance(int handle, std::size_t instance, std::span<float> positions,
                                       std::span<float> group_normals);

  // Backdrop (see the top of this file). Uploads `image` (width x height RGBA8, row 0 at the top
  // of the picture) and returns its handle: 0, 1, 2, ... in order, numbered apart from meshes and
  // blend models. The image is not kept. Set-up, not per-frame: throws vdg::Error "render:
  // addBackdrop: ..." for an empty image (a side < 1), one whose rgba does not hold width x height
  // x 4 bytes, and one larger than the driver's textures allow (GL_MAX_TEXTURE_SIZE a side) or
  // than its memory allows.
  int addBackdrop(const TextureImage& image);
  // Fills `viewport` with `paper` blended with backdrop `handle` stretched over the whole
  // viewport: colour = mix(paper, texel, opacity * texel_alpha); opacity 0 gives the paper, 1 the
  // picture where it is opaque. Clears the viewport's depth (the canvas outside the viewport is
  // untouched). Per-frame contract as above; violations: a bad handle, a viewport with width or
  // height < 1, an opacity outside [0, 1] (NaN included), a paper channel that is not finite.
  [[nodiscard]] bool drawBackdrop(int handle, const Viewport& viewport, float opacity, const Rgb& paper);

  // Reference drawings as view-dependent textures (vdg/render/drawing_textures.h). Uploads every
  // key's prepared drawing (RGBA8, mipmapped, linear, clamped at its edges) and its per-vertex (s, t,
  // q, visible), gathered per render vertex of surface `mesh` (from addSurface), and returns a
  // handle (0, 1, 2, ... in order, numbered apart from the others). Set-up, not per-frame: throws
  // vdg::Error "render: addDrawings: ..." for a handle that is not a surface's, drawings built for
  // another vertex count, and a drawing larger than the driver's textures allow.
  int addDrawings(int mesh, const DrawingTextures& drawings);
  // drawMesh with the drawings of `weights`' keys blended over the shading (blendDrawingColors: each
  // slot's key weight, times the fragment's interpolated visibility and the texel's alpha,
  // renormalised with the base's weight, which goes to the shading). Silhouettes and creases as
  // drawMesh. Per-frame contract as drawMesh; violations also: `drawings` not a handle of
  // addDrawings for this mesh, a key index outside [-1, keyCount()) or a weight that is not finite.
  [[nodiscard]] bool drawMeshDrawings(int mesh, int drawings, const View& view, const MeshStyle& style,
                                      const ViewWeights& weights);

  // Resolves the multisampled canvas into `out` (resized on first use; alpha = 255).
  void readPixels(Image& out);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace vdg::render
