// The render module's private parts shared by renderer.cpp (drawing) and gpu_blend.cpp (the GPU
// blend's compute passes): GL programs and buffers, and Renderer's state (Renderer::Impl).
#pragma once

#include <epoxy/gl.h>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <numbers>
#include <span>
#include <string>
#include <vector>

#include "gl_context.h"
#include "gl_objects.h"
#include "vdg/render/renderer.h"

namespace vdg::render::detail {

// Links a program from its shader sources (`geometry` may be null); throws vdg::Error "OpenGL:
// cannot compile/link the <what> ..." with the driver's log.
GlProgram link(const char* what, const char* vertex, const char* geometry, const char* fragment);
GlProgram linkCompute(const char* what, const char* source);

// The shading program: drawMesh's, and the GPU blend's instanced draw (whose extra uniforms the
// plain program lacks: their locations are -1, which glUniform ignores).
struct MeshProgram {
  GlProgram program;
  GLint view, proj, base, warm, cool, light_warm, light_cool, ka, k, flat, textured, hue_rule, texture;
  GLint instance_base, vertex_count, group_count, first_instance;
  explicit MeshProgram(GlProgram p) : program(std::move(p)) {
    const GLuint id = program.get();
    view = glGetUniformLocation(id, "u_view");
    proj = glGetUniformLocation(id, "u_proj");
    base = glGetUniformLocation(id, "u_base");
    warm = glGetUniformLocation(id, "u_warm");
    cool = glGetUniformLocation(id, "u_cool");
    light_warm = glGetUniformLocation(id, "u_light_warm");
    light_cool = glGetUniformLocation(id, "u_light_cool");
    ka = glGetUniformLocation(id, "u_ka");
    k = glGetUniformLocation(id, "u_k");
    flat = glGetUniformLocation(id, "u_flat");
    textured = glGetUniformLocation(id, "u_textured");
    hue_rule = glGetUniformLocation(id, "u_hue_rule");
    texture = glGetUniformLocation(id, "u_texture");
    instance_base = glGetUniformLocation(id, "u_instance_base");
    vertex_count = glGetUniformLocation(id, "u_vertex_count");
    group_count = glGetUniformLocation(id, "u_group_count");
    first_instance = glGetUniformLocation(id, "u_first_instance");
  }
};

// A compute program of the GPU blend and the locations of the uniforms its passes set (-1 where
// a pass has none).
struct ComputeProgram {
  GlProgram program;
  GLint vertex_count, group_count, edge_count, first_instance, item_offset, eye, silhouettes, borders, creases,
      cos_crease, capacity;
  explicit ComputeProgram(GlProgram p) : program(std::move(p)) {
    const GLuint id = program.get();
    vertex_count = glGetUniformLocation(id, "u_vertex_count");
    group_count = glGetUniformLocation(id, "u_group_count");
    edge_count = glGetUniformLocation(id, "u_edge_count");
    first_instance = glGetUniformLocation(id, "u_first_instance");
    item_offset = glGetUniformLocation(id, "u_item_offset");
    eye = glGetUniformLocation(id, "u_eye");
    silhouettes = glGetUniformLocation(id, "u_silhouettes");
    borders = glGetUniformLocation(id, "u_borders");
    creases = glGetUniformLocation(id, "u_creases");
    cos_crease = glGetUniformLocation(id, "u_cos_crease");
    capacity = glGetUniformLocation(id, "u_capacity");
  }
};

struct StrokeProgram {
  GlProgram program;
  GLint view, proj, pixel_scale, pull, ortho, point_size, viewport, width, color;
  explicit StrokeProgram(GlProgram p) : program(std::move(p)) {
    const GLuint id = program.get();
    view = glGetUniformLocation(id, "u_view");
    proj = glGetUniformLocation(id, "u_proj");
    pixel_scale = glGetUniformLocation(id, "u_pixel_scale");
    pull = glGetUniformLocation(id, "u_pull");
    ortho = glGetUniformLocation(id, "u_ortho");
    point_size = glGetUniformLocation(id, "u_point_size");
    viewport = glGetUniformLocation(id, "u_viewport");
    width = glGetUniformLocation(id, "u_width");
    color = glGetUniformLocation(id, "u_color");
  }
};

// A material as the GPU draws it: its base colour and its texture (an index into
// GpuMesh::textures, -1: none).
struct GpuMaterial {
  Rgb base{1.0f, 1.0f, 1.0f};
  int texture = -1;
};

// Consecutive triangles of the sorted index buffer with one material (-1: none).
struct DrawRange {
  int material = -1;
  std::size_t first = 0, count = 0;  // in indices (3 per triangle)
};

// Shading draws render vertices (one per smoothing group and texture coordinate); strokes draw
// the mesh's own vertices, which the welded edges index.
struct GpuMesh {
  SurfaceTopology topology;
  bool surface = false;  // from addSurface: empty normals = group normals (else flat)
  std::vector<GpuMaterial> materials;
  std::vector<GlTexture> textures;
  std::vector<DrawRange> ranges;
  std::size_t index_count = 0;
  std::vector<float> positions;                         // #V x 3, this frame's (facing, creases)
  std::vector<float> render_positions, render_normals;  // #R x 3, gathered per frame
  std::vector<float> group_normals;                     // #G x 3
  std::vector<std::uint8_t> front;
  std::vector<std::uint32_t> silhouette, creases;
  bool has_normals = false;
  GlVertexArray vao, stroke_vao;
  GlBuffer position_buffer, normal_buffer, uv_buffer, triangle_buffer, vertex_buffer, stroke_buffer;
};

// Reference drawings of one surface (Renderer::addDrawings): per key, its texture and its render
// vertices' (s, t, q, visible) (no texture and no buffer for a key without a drawing).
struct GpuDrawings {
  int mesh = -1;
  std::vector<GlTexture> textures;
  std::vector<GlBuffer> attributes;
  std::vector<std::uint8_t> present;
};

// The drawing program: the mesh program's uniforms plus the drawings' samplers and weights.
struct DrawingProgram {
  MeshProgram mesh;
  GLint images[3], weights;
  explicit DrawingProgram(GlProgram p) : mesh(std::move(p)) {
    const GLuint id = mesh.program.get();
    images[0] = glGetUniformLocation(id, "u_drawing0");
    images[1] = glGetUniformLocation(id, "u_drawing1");
    images[2] = glGetUniformLocation(id, "u_drawing2");
    weights = glGetUniformLocation(id, "u_drawing_weights");
  }
};

// A view-dependent model for the GPU blend (Renderer::addBlendModel). Set-up buffers are
// uploaded once; the batch buffers grow to the largest batch drawn.
struct GpuBlendModel {
  std::size_t vertex_count = 0, group_count = 0, edge_count = 0, key_count = 0;
  std::vector<GpuMaterial> materials;
  std::vector<GlTexture> textures;
  std::vector<DrawRange> ranges;
  std::size_t index_count = 0;
  std::size_t batch_limit = 1;                 // most instances one batch may hold
  std::size_t batch_capacity = 0;              // instances the batch buffers hold now
  std::size_t last_first = 0, last_count = 0;  // the instances the batch buffers hold results of
  GlVertexArray vao, stroke_vao;
  // Set-up: base #V x 3, deltas #keys x #V x 3, triangles #F x 3, group_start #G + 1 and
  // group_faces (faces per group, one entry per corner), edges #E x (a, b, f0, f1), render
  // vertices' (vertex, group) and uvs, the material-sorted render triangles.
  GlBuffer base, deltas, triangles, group_start, group_faces, edges, refs, uvs, indices;
  // Per batch: positions #B x #V x 3, normals #B x #G x 3, strokes 2 x #E x #B indices, and the
  // two indirect draw commands (silhouettes, creases).
  GlBuffer positions, normals, strokes, commands;
};

inline Eigen::Vector3f toVec(const std::array<float, 3>& a) { return {a[0], a[1], a[2]}; }

// The per-instance record of the GPU blend's storage buffer (std430: the Instance struct of the
// shaders, 112 bytes).
struct GpuInstance {
  float object[16];
  std::int32_t keys[4];
  float weights[4];
  float color[4];
};
static_assert(sizeof(GpuInstance) == 112);

// The depth and culling state of the shaded pass: depth test and write, back faces culled, counter-
// clockwise triangles in front.
// The GL state of the shaded front faces (depth test LESS with writes, back faces culled). With
// strokes to draw over them (widest_stroke_px > 0, the widest stroke's width in pixels), the faces
// are also pushed back by glPolygonOffset in proportion to their depth slope, by as much as a
// face can come towards the eye within half a stroke width of its edge, so a stroke drawn at its
// edge's own depth is not buried in the faces beside it (the paper's thick back-face wireframe
// shows whole). A slope-scaled offset pushes grazing faces (at silhouettes) back a lot and faces
// seen head-on hardly at all, so hidden outlines just under a visible surface (a leg's end inside
// a foot) stay hidden, as a constant pull of the strokes towards the eye would not (docs/render.md).
// The caller disables GL_POLYGON_OFFSET_FILL after the faces.
void frontFacesState(float widest_stroke_px);
// Constant part of that offset, in the depth buffer's smallest steps.
inline constexpr float kStrokeOffsetUnits = 4.0f;

// glBufferData through the copy-write target, which no vertex array records.
void bufferData(const GlBuffer& buffer, std::size_t bytes, const void* data, GLenum usage);

template <class T>
GlBuffer staticBuffer(const std::vector<T>& data) {
  GlBuffer buffer = makeBuffer();
  bufferData(buffer, data.size() * sizeof(T), data.empty() ? nullptr : data.data(), GL_STATIC_DRAW);
  return buffer;
}

// The conditions under which viewMatrix / projectionMatrix are defined (see cameraFrame), checked
// without throwing. viewProblem says which one fails ("the camera's eye is not finite"), for the
// messages of the renderers built on this one; nullptr for a valid View.
const char* viewProblem(const View& v);
bool validView(const View& v);
// The eye point of the facing test: the camera's eye, or for a parallel camera a point far back
// along its view axis.
Eigen::Vector3f facingEye(const Camera& camera);
// The render vertices' texture coordinates (#R x 2; (0, 0) where a corner has none).
std::vector<float> renderUvs(const SurfaceTopology& t, std::span<const float> uvs);
// The materials of `mesh` as the GPU draws them; a texture shared by several materials is
// uploaded once. Throws vdg::Error "<what>: material ...: texture ... exceeds ..." for a texture
// too large.
void uploadMaterials(const TriMesh& mesh, const std::string& what, std::vector<GpuMaterial>& materials,
                     std::vector<GlTexture>& textures);
// The render triangles sorted by material (stable: file order within a material), with one draw
// range per material appended to `ranges`.
std::vector<std::uint32_t> sortedRenderTriangles(const TriMesh& mesh, const SurfaceTopology& topology,
                                                 std::vector<DrawRange>& ranges);

}  // namespace vdg::render::detail

namespace vdg::render {

struct Renderer::Impl {
  detail::GlContext context;  // first member: destroyed last
  int width = 0, height = 0, samples = 1;
  std::string info;
  detail::GlFramebuffer ms_fbo, resolve_fbo;
  detail::GlRenderbuffer ms_color, ms_depth, resolve_color;
  std::unique_ptr<detail::MeshProgram> mesh_program;
  std::unique_ptr<detail::StrokeProgram> line_program, dot_program;
  std::vector<std::unique_ptr<detail::GpuMesh>> meshes;
  // GPU blend: created with the first blend model (OpenGL 4.3).
  int gl_version = 0;  // major * 10 + minor
  std::unique_ptr<detail::MeshProgram> blend_program;
  std::unique_ptr<detail::ComputeProgram> blend_compute, normals_compute, edges_compute, crease_start_compute;
  std::vector<std::unique_ptr<detail::GpuBlendModel>> blend_models;
  detail::GlBuffer instance_buffer;
  std::size_t instance_capacity = 0;  // bytes
  std::vector<detail::GpuInstance> instance_staging;
  // Backdrops: the program and its empty vertex array are created with the first one.
  detail::GlProgram backdrop_program;
  GLint backdrop_image = -1, backdrop_paper = -1, backdrop_opacity = -1;
  detail::GlVertexArray backdrop_vao;
  std::vector<detail::GlTexture> backdrops;
  // Reference drawings: the program is created with the first addDrawings.
  std::unique_ptr<detail::DrawingProgram> drawing_program;
  std::vector<std::unique_ptr<detail::GpuDrawings>> drawings;
  detail::GlVertexArray overlay_vao;
  detail::GlBuffer overlay_buffer;
  std::size_t overlay_capacity = 0;
  std::vector<std::uint8_t> row;  // scratch for the vertical flip

  ~Impl() { context.makeCurrent(); }

  void setView(const View& v) {
    const Viewport& vp = v.viewport;
    const int gl_y = height - vp.y - vp.height;
    glViewport(vp.x, gl_y, vp.width, vp.height);
    glScissor(vp.x, gl_y, vp.width, vp.height);
  }

  void setMatrices(GLint view_loc, GLint proj_loc, const View& v) {
    const double aspect = static_cast<double>(v.viewport.width) / std::max(1, v.viewport.height);
    const Eigen::Matrix4f view = viewMatrix(v.camera).cast<float>();
    const Eigen::Matrix4f proj = projectionMatrix(v.camera, aspect, v.z_near, v.z_far).cast<float>();
    glUniformMatrix4fv(view_loc, 1, GL_FALSE, view.data());
    glUniformMatrix4fv(proj_loc, 1, GL_FALSE, proj.data());
  }

  // Uniforms of the lighting equation for a surface of colour `base`. A textured surface gets the
  // caller's constants and the shader applies the hue rule per texel (to base x texel).
  // With `instance_base` (the GPU blend's faces without a material) Cbase is each instance's
  // colour, so the hue rule runs in the shader as for a texel.
  void setShading(const MeshStyle& style, const Rgb& base, bool textured = false,
                  const detail::MeshProgram* program = nullptr, bool instance_base = false) {
    const detail::MeshProgram& p = program ? *program : *mesh_program;
    const bool per_fragment = textured || instance_base;
    const bool hue_per_texel = per_fragment && style.shading.vary_by_hue;
    const ShadingConstants k = per_fragment ? style.shading.k : effectiveConstants(style.shading, base);
    glUniform1i(p.instance_base, instance_base ? 1 : 0);
    const Eigen::Vector3f l1 = detail::toVec(style.shading.light_warm).normalized();
    const Eigen::Vector3f l2 = detail::toVec(style.shading.light_cool).normalized();
    glUniform3fv(p.base, 1, base.data());
    glUniform1i(p.textured, textured ? 1 : 0);
    glUniform1i(p.hue_rule, hue_per_texel ? 1 : 0);
    glUniform1i(p.texture, 0);
    glUniform3fv(p.warm, 1, style.shading.warm.data());
    glUniform3fv(p.cool, 1, style.shading.cool.data());
    glUniform3fv(p.light_warm, 1, l1.data());
    glUniform3fv(p.light_cool, 1, l2.data());
    glUniform1f(p.ka, style.shading.ka);
    glUniform4f(p.k, k.k1, k.k2, k.k3, k.k4);
    glUniform1i(p.flat, style.flat ? 1 : 0);
  }

  void setStroke(const detail::StrokeProgram& p, const View& v, float size, const Rgb& color, float pull_px) {
    setMatrices(p.view, p.proj, v);
    const double h = std::max(1, v.viewport.height);
    if (v.camera.isOrtho()) {
      glUniform2f(p.pixel_scale, 0.0f, static_cast<float>(v.camera.ortho_height / h));
    } else {
      glUniform2f(p.pixel_scale, static_cast<float>(2.0 * std::tan(v.camera.fov_deg * std::numbers::pi / 360.0) / h),
                  0.0f);
    }
    glUniform1f(p.pull, pull_px);
    glUniform1i(p.ortho, v.camera.isOrtho() ? 1 : 0);
    glUniform1f(p.point_size, size);
    glUniform2f(p.viewport, static_cast<float>(v.viewport.width), static_cast<float>(v.viewport.height));
    glUniform1f(p.width, size);
    glUniform3fv(p.color, 1, color.data());
  }

  void uploadOverlay(std::span<const float> data) {
    glBindVertexArray(overlay_vao.get());
    glBindBuffer(GL_ARRAY_BUFFER, overlay_buffer.get());
    const std::size_t bytes = data.size_bytes();
    if (bytes > overlay_capacity) {
      overlay_capacity = std::max(bytes, overlay_capacity * 2);
      glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(overlay_capacity), nullptr, GL_DYNAMIC_DRAW);
    }
    glBufferSubData(GL_ARRAY_BUFFER, 0, static_cast<GLsizeiptr>(bytes), data.data());
  }

  // Common set-up of the overlay passes (lines, dots): target, view, data, depth state.
  void beginOverlay(const View& v, std::span<const float> data, bool depth_test) {
    context.makeCurrent();
    glBindFramebuffer(GL_FRAMEBUFFER, ms_fbo.get());
    setView(v);
    uploadOverlay(data);
    if (depth_test) {
      glEnable(GL_DEPTH_TEST);
      glDepthFunc(GL_LEQUAL);
    } else {
      glDisable(GL_DEPTH_TEST);
    }
    glDepthMask(GL_FALSE);
  }

  // Round dots of `diameter` pixels at the first `count` overlay points (alpha-to-coverage edges).
  void drawRoundDots(const View& v, GLsizei count, float diameter, const Rgb& color, float pull_px) {
    glEnable(GL_SAMPLE_ALPHA_TO_COVERAGE);
    glUseProgram(dot_program->program.get());
    setStroke(*dot_program, v, diameter, color, pull_px);
    glDrawArrays(GL_POINTS, 0, count);
    glDisable(GL_SAMPLE_ALPHA_TO_COVERAGE);
  }

  void endOverlay() {
    glDepthMask(GL_TRUE);
    glBindVertexArray(0);
  }

  // drawMesh's passes on `mesh` (a checked handle and View), with the drawings `layers` blended
  // over the shading by `weights` when not null (drawMeshDrawings, checked too).
  bool drawSurface(detail::GpuMesh& mesh, const View& view, const MeshStyle& style, const detail::GpuDrawings* layers,
                   const ViewWeights* weights);

  // The GPU blend's passes (gpu_blend.cpp). Uploads the instances (checked by validInstances),
  // grows `b`'s batch buffers and binds every storage buffer of the passes; returns the instances
  // per batch.
  std::size_t prepareBlend(detail::GpuBlendModel& b, std::span<const InstanceBlend> instances);
  // Passes 1 and 2 (blend, group normals) for instances [first, first + in_batch).
  void blendBatch(detail::GpuBlendModel& b, std::size_t first, std::size_t in_batch);
};

}  // namespace vdg::render
