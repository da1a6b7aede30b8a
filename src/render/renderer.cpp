// Headless NPR renderer: Rademacher 99, section 3.2.4 (warm/cool lighting; silhouettes after
// Raskar and Cohen 99, drawn from per-frame silhouette edges as screen-space quads plus round
// dots; see renderer.h for why a core profile needs this instead of wide back-face lines).
#include "vdg/render/renderer.h"

#include <epoxy/gl.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <numbers>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "gl_context.h"
#include "gl_objects.h"
#include "shaders.h"
#include "vdg/geom/error.h"
#include "vdg/render/silhouette.h"

namespace vdg::render {
namespace {

GlShader compile(GLenum type, const char* source, const char* what) {
  GlShader shader(glCreateShader(type));
  glShaderSource(shader.get(), 1, &source, nullptr);
  glCompileShader(shader.get());
  GLint ok = 0;
  glGetShaderiv(shader.get(), GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char log[2048] = {};
    glGetShaderInfoLog(shader.get(), sizeof log, nullptr, log);
    throw Error(std::string("OpenGL: cannot compile the ") + what + " shader: " + log);
  }
  return shader;
}

GlProgram link(const char* what, const char* vertex, const char* geometry, const char* fragment) {
  GlProgram program(glCreateProgram());
  GlShader vs = compile(GL_VERTEX_SHADER, vertex, what);
  GlShader fs = compile(GL_FRAGMENT_SHADER, fragment, what);
  GlShader gs;
  glAttachShader(program.get(), vs.get());
  glAttachShader(program.get(), fs.get());
  if (geometry) {
    gs = compile(GL_GEOMETRY_SHADER, geometry, what);
    glAttachShader(program.get(), gs.get());
  }
  glLinkProgram(program.get());
  GLint ok = 0;
  glGetProgramiv(program.get(), GL_LINK_STATUS, &ok);
  if (!ok) {
    char log[2048] = {};
    glGetProgramInfoLog(program.get(), sizeof log, nullptr, log);
    throw Error(std::string("OpenGL: cannot link the ") + what + " program: " + log);
  }
  return program;
}

GlProgram linkCompute(const char* what, const char* source) {
  GlProgram program(glCreateProgram());
  GlShader cs = compile(GL_COMPUTE_SHADER, source, what);
  glAttachShader(program.get(), cs.get());
  glLinkProgram(program.get());
  GLint ok = 0;
  glGetProgramiv(program.get(), GL_LINK_STATUS, &ok);
  if (!ok) {
    char log[2048] = {};
    glGetProgramInfoLog(program.get(), sizeof log, nullptr, log);
    throw Error(std::string("OpenGL: cannot link the ") + what + " program: " + log);
  }
  return program;
}

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

Eigen::Vector3f toVec(const std::array<float, 3>& a) { return {a[0], a[1], a[2]}; }

// The per-instance record of the GPU blend's storage buffer (std430: the Instance struct of the
// shaders, 112 bytes).
struct GpuInstance {
  float object[16];
  std::int32_t keys[4];
  float weights[4];
  float color[4];
};
static_assert(sizeof(GpuInstance) == 112);

// glBufferData through the copy-write target, which no vertex array records.
void bufferData(const GlBuffer& buffer, std::size_t bytes, const void* data, GLenum usage) {
  glBindBuffer(GL_COPY_WRITE_BUFFER, buffer.get());
  glBufferData(GL_COPY_WRITE_BUFFER, static_cast<GLsizeiptr>(std::max<std::size_t>(bytes, 16)), data, usage);
  glBindBuffer(GL_COPY_WRITE_BUFFER, 0);
}

template <class T>
GlBuffer staticBuffer(const std::vector<T>& data) {
  GlBuffer buffer = makeBuffer();
  bufferData(buffer, data.size() * sizeof(T), data.empty() ? nullptr : data.data(), GL_STATIC_DRAW);
  return buffer;
}

std::string megabytes(std::size_t bytes) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f MB", static_cast<double>(bytes) / 1e6);
  return text;
}

// Work groups of 64 items per dispatch, at most this many along x (the minimum every OpenGL 4.3
// driver allows); longer item ranges are dispatched in slices with u_item_offset.
constexpr std::size_t kGroupSize = 64;
constexpr std::size_t kMaxGroups = 65535;

void dispatchItems(const ComputeProgram& p, std::size_t items, std::size_t instances) {
  constexpr std::size_t kSlice = kGroupSize * kMaxGroups;
  for (std::size_t offset = 0; offset < items; offset += kSlice) {
    const std::size_t groups = (std::min(kSlice, items - offset) + kGroupSize - 1) / kGroupSize;
    glUniform1i(p.item_offset, static_cast<GLint>(offset));
    glDispatchCompute(static_cast<GLuint>(groups), static_cast<GLuint>(instances), 1);
  }
}

// The instances' checks of drawBlendInstances and blendInstances.
bool validInstances(const GpuBlendModel& b, std::span<const InstanceBlend> instances) {
  const int keys = static_cast<int>(b.key_count);
  for (const InstanceBlend& instance : instances) {
    if (!instance.object.allFinite()) return false;
    for (std::size_t i = 0; i < 3; ++i) {
      if (!std::isfinite(instance.color[i])) return false;
      const int k = instance.weights.key[i];
      if (k < -1 || k >= keys || !std::isfinite(instance.weights.weight[i])) return false;
    }
  }
  return true;
}

}  // namespace

struct Renderer::Impl {
  GlContext context;  // first member: destroyed last
  int width = 0, height = 0, samples = 1;
  std::string info;
  GlFramebuffer ms_fbo, resolve_fbo;
  GlRenderbuffer ms_color, ms_depth, resolve_color;
  std::unique_ptr<MeshProgram> mesh_program;
  std::unique_ptr<StrokeProgram> line_program, dot_program;
  std::vector<std::unique_ptr<GpuMesh>> meshes;
  // GPU blend: created with the first blend model (OpenGL 4.3).
  int gl_version = 0;  // major * 10 + minor
  std::unique_ptr<MeshProgram> blend_program;
  std::unique_ptr<ComputeProgram> blend_compute, normals_compute, edges_compute, crease_start_compute;
  std::vector<std::unique_ptr<GpuBlendModel>> blend_models;
  GlBuffer instance_buffer;
  std::size_t instance_capacity = 0;  // bytes
  std::vector<GpuInstance> instance_staging;
  // Backdrops: the program and its empty vertex array are created with the first one.
  GlProgram backdrop_program;
  GLint backdrop_image = -1, backdrop_paper = -1, backdrop_opacity = -1;
  GlVertexArray backdrop_vao;
  std::vector<GlTexture> backdrops;
  GlVertexArray overlay_vao;
  GlBuffer overlay_buffer;
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
  void setShading(const MeshStyle& style, const Rgb& base, bool textured = false, const MeshProgram* program = nullptr,
                  bool instance_base = false) {
    const MeshProgram& p = program ? *program : *mesh_program;
    const bool per_fragment = textured || instance_base;
    const bool hue_per_texel = per_fragment && style.shading.vary_by_hue;
    const ShadingConstants k = per_fragment ? style.shading.k : effectiveConstants(style.shading, base);
    glUniform1i(p.instance_base, instance_base ? 1 : 0);
    const Eigen::Vector3f l1 = toVec(style.shading.light_warm).normalized();
    const Eigen::Vector3f l2 = toVec(style.shading.light_cool).normalized();
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

  void setStroke(const StrokeProgram& p, const View& v, float size, const Rgb& color, float pull_px) {
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

  // Uploads the instances (checked by validInstances), grows `b`'s batch buffers and binds every
  // storage buffer of the passes. Returns the instances per batch.
  std::size_t prepareBlend(GpuBlendModel& b, std::span<const InstanceBlend> instances) {
    const std::size_t count = instances.size();
    instance_staging.resize(count);
    for (std::size_t i = 0; i < count; ++i) {
      const InstanceBlend& in = instances[i];
      GpuInstance& g = instance_staging[i];
      std::copy_n(in.object.data(), 16, g.object);
      for (int s = 0; s < 3; ++s) {
        const int k = in.weights.key[static_cast<std::size_t>(s)];
        const float w = in.weights.weight[static_cast<std::size_t>(s)];
        g.keys[s] = w == 0.0f ? -1 : k;
        g.weights[s] = k < 0 ? 0.0f : w;
        g.color[s] = in.color[static_cast<std::size_t>(s)];
      }
      g.keys[3] = -1;
      g.weights[3] = 0.0f;
      g.color[3] = 1.0f;
    }
    const std::size_t instance_bytes = count * sizeof(GpuInstance);
    glBindBuffer(GL_COPY_WRITE_BUFFER, instance_buffer.get());
    if (instance_bytes > instance_capacity) {
      instance_capacity = std::max(instance_bytes, instance_capacity * 2);
      glBufferData(GL_COPY_WRITE_BUFFER, static_cast<GLsizeiptr>(instance_capacity), nullptr, GL_DYNAMIC_DRAW);
    }
    glBufferSubData(GL_COPY_WRITE_BUFFER, 0, static_cast<GLsizeiptr>(instance_bytes), instance_staging.data());
    glBindBuffer(GL_COPY_WRITE_BUFFER, 0);

    const std::size_t batch = std::min(count, b.batch_limit);
    if (batch > b.batch_capacity) {
      b.batch_capacity = batch;
      bufferData(b.positions, batch * b.vertex_count * 3 * sizeof(float), nullptr, GL_DYNAMIC_COPY);
      bufferData(b.normals, batch * b.group_count * 3 * sizeof(float), nullptr, GL_DYNAMIC_COPY);
      bufferData(b.strokes, batch * b.edge_count * 2 * sizeof(std::uint32_t), nullptr, GL_DYNAMIC_COPY);
    }
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, b.base.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, b.deltas.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, instance_buffer.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, b.positions.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 4, b.triangles.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 5, b.group_start.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 6, b.group_faces.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 7, b.normals.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 8, b.edges.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 9, b.commands.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 10, b.strokes.get());
    return batch;
  }

  // Passes 1 and 2 (blend, group normals) for instances [first, first + in_batch).
  void blendBatch(GpuBlendModel& b, std::size_t first, std::size_t in_batch) {
    // The previous batch's draws read the buffers this batch's passes overwrite.
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    const ComputeProgram& blend = *blend_compute;
    glUseProgram(blend.program.get());
    glUniform1i(blend.vertex_count, static_cast<GLint>(b.vertex_count));
    glUniform1i(blend.first_instance, static_cast<GLint>(first));
    dispatchItems(blend, b.vertex_count, in_batch);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    const ComputeProgram& normals = *normals_compute;
    glUseProgram(normals.program.get());
    glUniform1i(normals.vertex_count, static_cast<GLint>(b.vertex_count));
    glUniform1i(normals.group_count, static_cast<GLint>(b.group_count));
    dispatchItems(normals, b.group_count, in_batch);
    b.last_first = first;
    b.last_count = in_batch;
  }
};

int maxImageSide() {
  GlContext context;
  GLint renderbuffer = 0, texture = 0, viewport[2] = {0, 0};
  glGetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &renderbuffer);
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &texture);
  glGetIntegerv(GL_MAX_VIEWPORT_DIMS, viewport);
  return std::min({static_cast<int>(renderbuffer), static_cast<int>(texture), static_cast<int>(viewport[0]),
                   static_cast<int>(viewport[1]), kMaxImageSize});
}

Renderer::Renderer(const RendererSettings& settings) {
  if (settings.width < 1 || settings.height < 1 || settings.width > kMaxImageSize || settings.height > kMaxImageSize)
    throw Error("render: image size " + std::to_string(settings.width) + "x" + std::to_string(settings.height) +
                " is outside 1x1 .. " + std::to_string(kMaxImageSize) + "x" + std::to_string(kMaxImageSize));
  impl_ = std::make_unique<Impl>();
  Impl& m = *impl_;
  m.width = settings.width;
  m.height = settings.height;
  m.info = std::string(reinterpret_cast<const char*>(glGetString(GL_RENDERER))) + " / " +
           reinterpret_cast<const char*>(glGetString(GL_VERSION)) + " / EGL " + m.context.platform();

  GLint major = 0, minor = 0;
  glGetIntegerv(GL_MAJOR_VERSION, &major);
  glGetIntegerv(GL_MINOR_VERSION, &minor);
  m.gl_version = major * 10 + minor;
  if (const char* cap = std::getenv("VDG_RENDER_GL"); cap && std::strcmp(cap, "3.3") == 0)
    m.gl_version = std::min(m.gl_version, 33);

  GLint max_samples = 1, max_size = 0;
  glGetIntegerv(GL_MAX_SAMPLES, &max_samples);
  glGetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &max_size);
  if (settings.width > max_size || settings.height > max_size)
    throw Error("OpenGL: image size " + std::to_string(settings.width) + "x" + std::to_string(settings.height) +
                " exceeds the driver's limit of " + std::to_string(max_size));
  m.samples = std::clamp(settings.samples, 1, std::max(1, static_cast<int>(max_samples)));

  m.ms_fbo = makeFramebuffer();
  m.ms_color = makeRenderbuffer();
  m.ms_depth = makeRenderbuffer();
  glBindRenderbuffer(GL_RENDERBUFFER, m.ms_color.get());
  glRenderbufferStorageMultisample(GL_RENDERBUFFER, m.samples, GL_RGBA8, m.width, m.height);
  glBindRenderbuffer(GL_RENDERBUFFER, m.ms_depth.get());
  glRenderbufferStorageMultisample(GL_RENDERBUFFER, m.samples, GL_DEPTH_COMPONENT24, m.width, m.height);
  glBindFramebuffer(GL_FRAMEBUFFER, m.ms_fbo.get());
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, m.ms_color.get());
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, m.ms_depth.get());
  if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    throw Error("OpenGL: the driver (" + std::string(reinterpret_cast<const char*>(glGetString(GL_RENDERER))) +
                ") cannot allocate a " + std::to_string(m.width) + "x" + std::to_string(m.height) + " canvas with " +
                std::to_string(m.samples) + (m.samples == 1 ? " sample" : " samples") + " (its limit is " +
                std::to_string(max_size) + " pixels a side, but the memory it allows runs out first); " +
                "try a smaller size" + (m.samples > 1 ? " or fewer samples" : ""));
  m.resolve_fbo = makeFramebuffer();
  m.resolve_color = makeRenderbuffer();
  glBindRenderbuffer(GL_RENDERBUFFER, m.resolve_color.get());
  glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, m.width, m.height);
  glBindFramebuffer(GL_FRAMEBUFFER, m.resolve_fbo.get());
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, m.resolve_color.get());
  if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    throw Error("OpenGL: the resolve framebuffer is incomplete");
  glBindFramebuffer(GL_FRAMEBUFFER, m.ms_fbo.get());

  m.mesh_program = std::make_unique<MeshProgram>(link("mesh", shaders::kMeshVertex, nullptr, shaders::kMeshFragment));
  m.line_program = std::make_unique<StrokeProgram>(
      link("line", shaders::kStrokeVertex, shaders::kLineGeometry, shaders::kLineFragment));
  m.dot_program = std::make_unique<StrokeProgram>(link("dot", shaders::kStrokeVertex, nullptr, shaders::kDotFragment));

  m.overlay_vao = makeVertexArray();
  m.overlay_buffer = makeBuffer();
  glBindVertexArray(m.overlay_vao.get());
  glBindBuffer(GL_ARRAY_BUFFER, m.overlay_buffer.get());
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 0, nullptr);
  glVertexAttrib3f(1, 0.0f, 0.0f, 1.0f);

  glEnable(GL_SCISSOR_TEST);
  glEnable(GL_PROGRAM_POINT_SIZE);
  glEnable(GL_MULTISAMPLE);
  if (const GLenum err = glGetError(); err != GL_NO_ERROR)
    throw Error("OpenGL: error " + std::to_string(err) + " while setting up the renderer");
}

Renderer::~Renderer() = default;
Renderer::Renderer(Renderer&&) noexcept = default;
Renderer& Renderer::operator=(Renderer&&) noexcept = default;

namespace {

bool finite3(const Eigen::Vector3d& v) { return v.allFinite(); }

// The conditions under which viewMatrix / projectionMatrix are defined (see cameraFrame), checked
// without throwing.
bool validView(const View& v) {
  if (v.viewport.width < 1 || v.viewport.height < 1) return false;
  if (!std::isfinite(v.z_near) || !std::isfinite(v.z_far) || !(v.z_near > 0.0) || !(v.z_far > v.z_near)) return false;
  const Camera& c = v.camera;
  if (!finite3(c.eye) || !finite3(c.target) || !finite3(c.up)) return false;
  if (!std::isfinite(c.ortho_height) || !std::isfinite(c.fov_deg)) return false;
  const Eigen::Vector3d back = c.eye - c.target;
  if (!(back.norm() > 0.0)) return false;
  if (!(c.up.cross(back.normalized()).norm() > 1e-12 * c.up.norm())) return false;
  return c.isOrtho() || (c.fov_deg > 0.0 && c.fov_deg < 180.0);
}

bool positiveFinite(float x) { return std::isfinite(x) && x > 0.0f; }

// The eye point of the facing test: the camera's eye, or for a parallel camera a point far back
// along its view axis.
Eigen::Vector3f facingEye(const Camera& camera) {
  if (!camera.isOrtho()) return camera.eye.cast<float>();
  const Eigen::Vector3d back = (camera.eye - camera.target).normalized();
  return (camera.target + back * (1e6 * std::max(1.0, camera.ortho_height))).cast<float>();
}

}  // namespace

int Renderer::width() const { return impl_->width; }
int Renderer::height() const { return impl_->height; }
int Renderer::samples() const { return impl_->samples; }
std::string Renderer::glInfo() const { return impl_->info; }

namespace {

// Creates the GL objects of `mesh` (its topology, ranges and materials set): the shading VAO over
// render vertices with the material-sorted index buffer, and the stroke VAO over the vertices.
void uploadMesh(GpuMesh& mesh, std::span<const float> render_uvs, std::span<const std::uint32_t> sorted) {
  const SurfaceTopology& t = mesh.topology;
  const std::size_t render_count = t.renderVertexCount();
  mesh.positions.assign(t.vertexCount() * 3, 0.0f);
  mesh.render_positions.assign(render_count * 3, 0.0f);
  mesh.render_normals.assign(render_count * 3, 0.0f);
  mesh.group_normals.assign(t.groupCount() * 3, 0.0f);
  mesh.front.assign(t.triangleCount(), 0);
  mesh.silhouette.reserve(t.edgeCount() * 2);
  mesh.creases.reserve(t.edgeCount() * 2);
  mesh.index_count = sorted.size();
  mesh.vao = makeVertexArray();
  mesh.stroke_vao = makeVertexArray();
  mesh.position_buffer = makeBuffer();
  mesh.normal_buffer = makeBuffer();
  mesh.uv_buffer = makeBuffer();
  mesh.triangle_buffer = makeBuffer();
  mesh.vertex_buffer = makeBuffer();
  mesh.stroke_buffer = makeBuffer();

  glBindVertexArray(mesh.vao.get());
  const auto render_bytes = static_cast<GLsizeiptr>(render_count * 3 * sizeof(float));
  glBindBuffer(GL_ARRAY_BUFFER, mesh.position_buffer.get());
  glBufferData(GL_ARRAY_BUFFER, render_bytes, nullptr, GL_DYNAMIC_DRAW);
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 0, nullptr);
  glBindBuffer(GL_ARRAY_BUFFER, mesh.normal_buffer.get());
  glBufferData(GL_ARRAY_BUFFER, render_bytes, nullptr, GL_DYNAMIC_DRAW);
  glEnableVertexAttribArray(1);
  glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, 0, nullptr);
  glBindBuffer(GL_ARRAY_BUFFER, mesh.uv_buffer.get());
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(render_uvs.size_bytes()), render_uvs.data(), GL_STATIC_DRAW);
  glEnableVertexAttribArray(2);
  glVertexAttribPointer(2, 2, GL_FLOAT, GL_FALSE, 0, nullptr);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, mesh.triangle_buffer.get());
  glBufferData(GL_ELEMENT_ARRAY_BUFFER, static_cast<GLsizeiptr>(sorted.size_bytes()), sorted.data(), GL_STATIC_DRAW);

  glBindVertexArray(mesh.stroke_vao.get());
  glBindBuffer(GL_ARRAY_BUFFER, mesh.vertex_buffer.get());
  glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(t.vertexCount() * 3 * sizeof(float)), nullptr, GL_DYNAMIC_DRAW);
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 0, nullptr);
  // Silhouettes and creases never share an edge: 2 indices an edge hold both lists.
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, mesh.stroke_buffer.get());
  glBufferData(GL_ELEMENT_ARRAY_BUFFER,
               static_cast<GLsizeiptr>(std::max<std::size_t>(1, t.edgeCount() * 2) * sizeof(std::uint32_t)), nullptr,
               GL_DYNAMIC_DRAW);
  glBindVertexArray(0);
}

// The render vertices' texture coordinates (#R x 2; (0, 0) where a corner has none).
std::vector<float> renderUvs(const SurfaceTopology& t, std::span<const float> uvs) {
  std::vector<float> out(t.renderVertexCount() * 2, 0.0f);
  const auto uv = t.renderUv();
  for (std::size_t r = 0; r < uv.size(); ++r) {
    if (uv[r] < 0) continue;
    out[r * 2] = uvs[static_cast<std::size_t>(uv[r]) * 2];
    out[r * 2 + 1] = uvs[static_cast<std::size_t>(uv[r]) * 2 + 1];
  }
  return out;
}

// A mipmapped, linearly filtered RGBA8 texture of `image`, `wrap` (GL_REPEAT, GL_CLAMP_TO_EDGE)
// at its edges.
GlTexture uploadTexture(const TextureImage& image, GLint wrap) {
  GlTexture texture = makeTexture();
  glBindTexture(GL_TEXTURE_2D, texture.get());
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  // Rows go up as stored (top row first, at t = 0). The mesh shader samples at (u, 1 - v), so
  // v = 0 (the uv origin, bottom-left) reads the last row; the backdrop shader has t = 0 at the
  // top of its viewport.
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, image.width, image.height, 0, GL_RGBA, GL_UNSIGNED_BYTE, image.rgba.data());
  glGenerateMipmap(GL_TEXTURE_2D);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, wrap);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, wrap);
  glBindTexture(GL_TEXTURE_2D, 0);
  return texture;
}

// The materials of `mesh` as the GPU draws them; a texture shared by several materials is
// uploaded once. Without texture coordinates no texture can be sampled: the base colour alone.
// Throws vdg::Error "<what>: material ...: texture ... exceeds ..." for a texture too large.
void uploadMaterials(const TriMesh& mesh, const std::string& what, std::vector<GpuMaterial>& materials,
                     std::vector<GlTexture>& textures) {
  GLint max_texture = 0;
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_texture);
  std::map<const TextureImage*, int> uploaded;
  for (const Material& material : mesh.materials) {
    GpuMaterial g;
    g.base = material.base_color;
    if (material.texture && !mesh.uvs.empty()) {
      const TextureImage& image = *material.texture;
      if (image.width > max_texture || image.height > max_texture)
        throw Error(what + ": material '" + material.name + "': texture " + std::to_string(image.width) + "x" +
                    std::to_string(image.height) + " exceeds the OpenGL driver's limit of " +
                    std::to_string(max_texture) + " pixels a side");
      const auto [it, inserted] = uploaded.try_emplace(&image, static_cast<int>(textures.size()));
      if (inserted) textures.push_back(uploadTexture(image, GL_REPEAT));
      g.texture = it->second;
    }
    materials.push_back(g);
  }
}

// The render triangles sorted by material (stable: file order within a material), with one draw
// range per material appended to `ranges`.
std::vector<std::uint32_t> sortedRenderTriangles(const TriMesh& mesh, const SurfaceTopology& topology,
                                                 std::vector<DrawRange>& ranges) {
  const std::size_t faces = mesh.triangleCount();
  std::vector<std::int32_t> order(faces);
  for (std::size_t f = 0; f < faces; ++f) order[f] = static_cast<std::int32_t>(f);
  const auto material_of = [&](std::int32_t f) {
    return mesh.face_materials.empty() ? -1 : mesh.face_materials[static_cast<std::size_t>(f)];
  };
  std::stable_sort(order.begin(), order.end(),
                   [&](std::int32_t a, std::int32_t b) { return material_of(a) < material_of(b); });
  const auto render = topology.renderTriangles();
  std::vector<std::uint32_t> indices;
  indices.reserve(faces * 3);
  for (const std::int32_t f : order) {
    const int material = material_of(f);
    if (ranges.empty() || ranges.back().material != material) ranges.push_back({material, indices.size(), 0});
    for (int c = 0; c < 3; ++c)
      indices.push_back(static_cast<std::uint32_t>(render[static_cast<std::size_t>(f) * 3 + c]));
    ranges.back().count += 3;
  }
  return indices;
}

}  // namespace

int Renderer::addMesh(std::span<const std::int32_t> triangles, std::size_t vertex_count) {
  Impl& m = *impl_;
  if (triangles.size() % 3 != 0)
    throw Error("render: addMesh: " + std::to_string(triangles.size()) + " triangle indices is not a multiple of 3");
  for (std::size_t i = 0; i < triangles.size(); ++i) {
    if (triangles[i] < 0 || static_cast<std::size_t>(triangles[i]) >= vertex_count)
      throw Error("render: addMesh: triangle " + std::to_string(i / 3) + " refers to vertex " +
                  std::to_string(triangles[i]) + ", but the mesh has " + std::to_string(vertex_count) + " vertices");
  }
  m.context.makeCurrent();
  auto mesh = std::make_unique<GpuMesh>();
  mesh->topology = SurfaceTopology::unwelded(triangles, vertex_count);
  const auto render = mesh->topology.renderTriangles();
  const std::vector<std::uint32_t> indices(render.begin(), render.end());
  mesh->ranges.push_back({-1, 0, indices.size()});
  uploadMesh(*mesh, renderUvs(mesh->topology, {}), indices);
  m.meshes.push_back(std::move(mesh));
  return static_cast<int>(m.meshes.size()) - 1;
}

int Renderer::addSurface(const TriMesh& mesh, const SurfaceTopology& topology) {
  Impl& m = *impl_;
  const std::string what = "render: addSurface";
  validateMesh(mesh, what);
  const auto tt = topology.triangles();
  if (topology.vertexCount() != mesh.vertexCount() || topology.triangleCount() != mesh.triangleCount() ||
      !std::equal(tt.begin(), tt.end(), mesh.triangles.begin(), mesh.triangles.end()))
    throw Error(what + ": the topology was built on another mesh (" + std::to_string(topology.vertexCount()) +
                " vertices, " + std::to_string(topology.triangleCount()) + " triangles; the mesh has " +
                std::to_string(mesh.vertexCount()) + " vertices, " + std::to_string(mesh.triangleCount()) +
                " triangles" + (topology.triangleCount() == mesh.triangleCount() ? ", other triangles)" : ")"));
  m.context.makeCurrent();
  auto gpu = std::make_unique<GpuMesh>();
  gpu->topology = topology;
  gpu->surface = true;
  uploadMaterials(mesh, what, gpu->materials, gpu->textures);
  const std::vector<std::uint32_t> indices = sortedRenderTriangles(mesh, topology, gpu->ranges);
  uploadMesh(*gpu, renderUvs(topology, mesh.uvs), indices);
  m.meshes.push_back(std::move(gpu));
  return static_cast<int>(m.meshes.size()) - 1;
}

bool Renderer::updateMesh(int mesh_id, std::span<const float> positions, std::span<const float> normals) {
  Impl& m = *impl_;
  if (mesh_id < 0 || static_cast<std::size_t>(mesh_id) >= m.meshes.size()) return false;
  GpuMesh& mesh = *m.meshes[static_cast<std::size_t>(mesh_id)];
  const std::size_t n = mesh.positions.size();
  if (positions.size() != n || (!normals.empty() && normals.size() != n)) return false;
  // Every check is above: from here on the call succeeds.
  const SurfaceTopology& t = mesh.topology;
  const auto source = t.renderSource();
  std::copy_n(positions.begin(), n, mesh.positions.begin());
  for (std::size_t r = 0; r < source.size(); ++r)
    std::copy_n(&positions[static_cast<std::size_t>(source[r]) * 3], 3, &mesh.render_positions[r * 3]);
  mesh.has_normals = !normals.empty() || mesh.surface;
  if (!normals.empty()) {
    for (std::size_t r = 0; r < source.size(); ++r)
      std::copy_n(&normals[static_cast<std::size_t>(source[r]) * 3], 3, &mesh.render_normals[r * 3]);
  } else if (mesh.surface) {
    (void)computeGroupNormals(t, positions, mesh.group_normals);  // sizes are right by construction
    const auto group = t.renderGroup();
    for (std::size_t r = 0; r < group.size(); ++r)
      std::copy_n(&mesh.group_normals[static_cast<std::size_t>(group[r]) * 3], 3, &mesh.render_normals[r * 3]);
  }
  m.context.makeCurrent();
  const auto render_bytes = static_cast<GLsizeiptr>(mesh.render_positions.size() * sizeof(float));
  glBindBuffer(GL_ARRAY_BUFFER, mesh.vertex_buffer.get());
  glBufferSubData(GL_ARRAY_BUFFER, 0, static_cast<GLsizeiptr>(n * sizeof(float)), positions.data());
  glBindBuffer(GL_ARRAY_BUFFER, mesh.position_buffer.get());
  glBufferSubData(GL_ARRAY_BUFFER, 0, render_bytes, mesh.render_positions.data());
  if (mesh.has_normals) {
    glBindBuffer(GL_ARRAY_BUFFER, mesh.normal_buffer.get());
    glBufferSubData(GL_ARRAY_BUFFER, 0, render_bytes, mesh.render_normals.data());
  }
  return true;
}

void Renderer::clear(const Rgb& color, const Viewport* viewport) {
  Impl& m = *impl_;
  m.context.makeCurrent();
  glBindFramebuffer(GL_FRAMEBUFFER, m.ms_fbo.get());
  View full;
  full.viewport = viewport ? *viewport : Viewport{0, 0, m.width, m.height};
  m.setView(full);
  glDepthMask(GL_TRUE);
  glClearColor(color[0], color[1], color[2], 1.0f);
  glClearDepth(1.0);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
}

bool Renderer::drawMesh(int mesh_id, const View& view, const MeshStyle& style) {
  Impl& m = *impl_;
  if (mesh_id < 0 || static_cast<std::size_t>(mesh_id) >= m.meshes.size() || !validView(view)) return false;
  GpuMesh& mesh = *m.meshes[static_cast<std::size_t>(mesh_id)];
  m.context.makeCurrent();
  glBindFramebuffer(GL_FRAMEBUFFER, m.ms_fbo.get());
  m.setView(view);

  // Pass 1: shaded front faces (back faces culled), one draw per material range.
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  glEnable(GL_CULL_FACE);
  glCullFace(GL_BACK);
  glFrontFace(GL_CCW);
  glUseProgram(m.mesh_program->program.get());
  m.setMatrices(m.mesh_program->view, m.mesh_program->proj, view);
  MeshStyle shaded = style;
  shaded.flat = style.flat || !mesh.has_normals;
  glBindVertexArray(mesh.vao.get());
  glActiveTexture(GL_TEXTURE0);
  const auto draw = [](std::size_t first, std::size_t count) {
    glDrawElements(GL_TRIANGLES, static_cast<GLsizei>(count), GL_UNSIGNED_INT,
                   reinterpret_cast<const void*>(first * sizeof(std::uint32_t)));
  };
  if (!style.materials) {
    m.setShading(shaded, style.color);
    draw(0, mesh.index_count);
  } else {
    for (const DrawRange& range : mesh.ranges) {
      const GpuMaterial* material =
          range.material >= 0 ? &mesh.materials[static_cast<std::size_t>(range.material)] : nullptr;
      const bool textured = material && material->texture >= 0;
      m.setShading(shaded, material ? material->base : style.color, textured);
      glBindTexture(GL_TEXTURE_2D, textured ? mesh.textures[static_cast<std::size_t>(material->texture)].get() : 0);
      draw(range.first, range.count);
    }
    glBindTexture(GL_TEXTURE_2D, 0);
  }
  glDisable(GL_CULL_FACE);
  const float crease_width = style.crease_width > 0.0f ? style.crease_width : 0.5f * style.silhouette_width;
  const bool want_creases = style.crease_angle_deg > 0.0f && crease_width > 0.0f;
  if (style.silhouette_width <= 0.0f && !want_creases) {
    glBindVertexArray(0);
    return true;
  }

  // Pass 2: silhouette edges (one face towards the eye, the other away), open borders and
  // creases, found on the CPU on the welded surface.
  const Eigen::Vector3f eye = facingEye(view.camera);
  faceFacing(mesh.positions, mesh.topology.triangles(), eye, mesh.front);
  if (style.silhouette_width > 0.0f)
    silhouetteEdges(mesh.topology, mesh.front, style.borders, mesh.silhouette);
  else
    mesh.silhouette.clear();
  if (want_creases)
    creaseEdges(mesh.topology, mesh.positions, mesh.front, style.crease_angle_deg, mesh.creases);
  else
    mesh.creases.clear();
  if (mesh.silhouette.empty() && mesh.creases.empty()) {
    glBindVertexArray(0);
    return true;
  }
  glBindVertexArray(mesh.stroke_vao.get());
  const std::size_t silhouette_bytes = mesh.silhouette.size() * sizeof(std::uint32_t);
  glBufferSubData(GL_ELEMENT_ARRAY_BUFFER, 0, static_cast<GLsizeiptr>(silhouette_bytes), mesh.silhouette.data());
  glBufferSubData(GL_ELEMENT_ARRAY_BUFFER, static_cast<GLintptr>(silhouette_bytes),
                  static_cast<GLsizeiptr>(mesh.creases.size() * sizeof(std::uint32_t)), mesh.creases.data());
  glDepthFunc(GL_LEQUAL);
  glDepthMask(GL_FALSE);
  // Each list as thick lines, then round dots at the edge ends to fill the cracks between thick
  // edges (the paper's points). Creases first: silhouettes lie on top where they meet.
  const auto strokes = [&](std::size_t first, std::size_t count, float width) {
    if (count == 0) return;
    const void* offset = reinterpret_cast<const void*>(first * sizeof(std::uint32_t));
    const float pull = style.silhouette_pull * width;
    glUseProgram(m.line_program->program.get());
    m.setStroke(*m.line_program, view, width, style.silhouette_color, pull);
    glDrawElements(GL_LINES, static_cast<GLsizei>(count), GL_UNSIGNED_INT, offset);
    glEnable(GL_SAMPLE_ALPHA_TO_COVERAGE);
    glUseProgram(m.dot_program->program.get());
    m.setStroke(*m.dot_program, view, width, style.silhouette_color, pull);
    glDrawElements(GL_POINTS, static_cast<GLsizei>(count), GL_UNSIGNED_INT, offset);
    glDisable(GL_SAMPLE_ALPHA_TO_COVERAGE);
  };
  strokes(mesh.silhouette.size(), mesh.creases.size(), crease_width);
  strokes(0, mesh.silhouette.size(), style.silhouette_width);
  glDepthMask(GL_TRUE);
  glBindVertexArray(0);
  return true;
}

bool Renderer::drawTriangles(std::span<const float> positions, const View& view, const MeshStyle& style) {
  Impl& m = *impl_;
  if (positions.size() % 9 != 0 || !validView(view)) return false;
  if (positions.empty()) return true;
  m.context.makeCurrent();
  glBindFramebuffer(GL_FRAMEBUFFER, m.ms_fbo.get());
  m.setView(view);
  m.uploadOverlay(positions);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  glDisable(GL_CULL_FACE);
  glUseProgram(m.mesh_program->program.get());
  m.setMatrices(m.mesh_program->view, m.mesh_program->proj, view);
  MeshStyle flat = style;
  flat.flat = true;
  m.setShading(flat, style.color);
  glDrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(positions.size() / 3));
  glBindVertexArray(0);
  return true;
}

bool Renderer::drawLines(std::span<const float> segments, const View& view, float width, const Rgb& color,
                         bool depth_test, float pull) {
  Impl& m = *impl_;
  if (segments.size() % 6 != 0 || !validView(view) || !positiveFinite(width) || !std::isfinite(pull)) return false;
  if (segments.empty()) return true;
  m.beginOverlay(view, segments, depth_test);
  const auto count = static_cast<GLsizei>(segments.size() / 3 / 2 * 2);
  const float pull_px = depth_test ? pull : 0.0f;
  glUseProgram(m.line_program->program.get());
  m.setStroke(*m.line_program, view, width, color, pull_px);
  glDrawArrays(GL_LINES, 0, count);
  m.drawRoundDots(view, count, width, color, pull_px);  // round joints between segments
  m.endOverlay();
  return true;
}

bool Renderer::drawDots(std::span<const float> points, const View& view, float diameter, const Rgb& color,
                        bool depth_test, float pull) {
  Impl& m = *impl_;
  if (points.size() % 3 != 0 || !validView(view) || !positiveFinite(diameter) || !std::isfinite(pull)) return false;
  if (points.empty()) return true;
  m.beginOverlay(view, points, depth_test);
  m.drawRoundDots(view, static_cast<GLsizei>(points.size() / 3), diameter, color, depth_test ? pull : 0.0f);
  m.endOverlay();
  return true;
}

int Renderer::addBackdrop(const TextureImage& image) {
  Impl& m = *impl_;
  const std::string what = "render: addBackdrop: ";
  const std::string size = std::to_string(image.width) + "x" + std::to_string(image.height);
  if (image.width < 1 || image.height < 1) throw Error(what + "the image is empty (" + size + ")");
  const std::size_t bytes = static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height) * 4;
  if (image.rgba.size() != bytes)
    throw Error(what + "a " + size + " image has " + std::to_string(image.rgba.size()) + " bytes of RGBA, not " +
                std::to_string(bytes));
  m.context.makeCurrent();
  GLint max_texture = 0;
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_texture);
  if (image.width > max_texture || image.height > max_texture)
    throw Error(what + "the image (" + size + ") exceeds the OpenGL driver's limit of " + std::to_string(max_texture) +
                " pixels a side");
  if (!m.backdrop_program.get()) {
    m.backdrop_program = link("backdrop", shaders::kBackdropVertex, nullptr, shaders::kBackdropFragment);
    m.backdrop_image = glGetUniformLocation(m.backdrop_program.get(), "u_image");
    m.backdrop_paper = glGetUniformLocation(m.backdrop_program.get(), "u_paper");
    m.backdrop_opacity = glGetUniformLocation(m.backdrop_program.get(), "u_opacity");
    m.backdrop_vao = makeVertexArray();
  }
  // Errors left by earlier calls are not this upload's (each call clears one error flag).
  for (int flag = 0; flag < 8 && glGetError() != GL_NO_ERROR; ++flag) {
  }
  GlTexture texture = uploadTexture(image, GL_CLAMP_TO_EDGE);
  if (const GLenum err = glGetError(); err != GL_NO_ERROR)
    throw Error(what + "the OpenGL driver cannot store the image (" + size + "; error " + std::to_string(err) + ")");
  m.backdrops.push_back(std::move(texture));
  return static_cast<int>(m.backdrops.size()) - 1;
}

bool Renderer::drawBackdrop(int handle, const Viewport& viewport, float opacity, const Rgb& paper) {
  Impl& m = *impl_;
  if (handle < 0 || static_cast<std::size_t>(handle) >= m.backdrops.size()) return false;
  if (viewport.width < 1 || viewport.height < 1) return false;
  if (!(opacity >= 0.0f && opacity <= 1.0f)) return false;
  if (!std::all_of(paper.begin(), paper.end(), [](float c) { return std::isfinite(c); })) return false;
  m.context.makeCurrent();
  glBindFramebuffer(GL_FRAMEBUFFER, m.ms_fbo.get());
  View full;
  full.viewport = viewport;
  m.setView(full);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);
  glUseProgram(m.backdrop_program.get());
  glUniform1i(m.backdrop_image, 0);
  glUniform3fv(m.backdrop_paper, 1, paper.data());
  glUniform1f(m.backdrop_opacity, opacity);
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, m.backdrops[static_cast<std::size_t>(handle)].get());
  glBindVertexArray(m.backdrop_vao.get());
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glBindVertexArray(0);
  glBindTexture(GL_TEXTURE_2D, 0);
  // The picture lies behind whatever is drawn next.
  glDepthMask(GL_TRUE);
  glClearDepth(1.0);
  glClear(GL_DEPTH_BUFFER_BIT);
  return true;
}

int Renderer::addBlendModel(const ViewDependentModel& model) {
  Impl& m = *impl_;
  const std::string what = "render: addBlendModel";
  m.context.makeCurrent();
  if (m.gl_version < 43)
    throw Error("OpenGL: the GPU blend (--gpu-blend) needs OpenGL 4.3 (the driver gives " +
                std::to_string(m.gl_version / 10) + "." + std::to_string(m.gl_version % 10) + ", " +
                reinterpret_cast<const char*>(glGetString(GL_RENDERER)) + ")");
  if (!m.blend_program) {
    std::string fragment = shaders::kMeshFragment;
    fragment.replace(fragment.find("330"), 3, "430");
    m.blend_program =
        std::make_unique<MeshProgram>(link("blend mesh", shaders::kBlendVertex, nullptr, fragment.c_str()));
    m.blend_compute = std::make_unique<ComputeProgram>(linkCompute("blend", shaders::kBlendCompute));
    m.normals_compute = std::make_unique<ComputeProgram>(linkCompute("blend normals", shaders::kNormalsCompute));
    m.edges_compute = std::make_unique<ComputeProgram>(linkCompute("blend edges", shaders::kEdgesCompute));
    m.crease_start_compute =
        std::make_unique<ComputeProgram>(linkCompute("blend crease start", shaders::kCreaseStartCompute));
    m.instance_buffer = makeBuffer();
  }
  const TriMesh& mesh = model.base();
  const SurfaceTopology& t = model.surface();
  auto gpu = std::make_unique<GpuBlendModel>();
  GpuBlendModel& b = *gpu;
  b.vertex_count = t.vertexCount();
  b.group_count = t.groupCount();
  b.edge_count = t.edgeCount();
  b.key_count = model.keyCount();

  // Sizes against the driver's largest storage block; the batch size from the per-instance bytes.
  GLint64 max_block = 0;
  glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &max_block);
  GLint max_groups_y = 0;
  glGetIntegeri_v(GL_MAX_COMPUTE_WORK_GROUP_COUNT, 1, &max_groups_y);
  const auto block = static_cast<std::size_t>(std::max<GLint64>(max_block, 1));
  const std::size_t delta_bytes = b.key_count * b.vertex_count * 3 * sizeof(float);
  if (delta_bytes > block)
    throw Error(what + ": the key deltas (" + std::to_string(b.key_count) + " keys x " +
                std::to_string(b.vertex_count) + " vertices) take " + megabytes(delta_bytes) +
                ", more than the OpenGL driver's largest storage block (" + megabytes(block) + ")");
  const std::size_t largest = std::max({b.vertex_count * 3 * sizeof(float), b.group_count * 3 * sizeof(float),
                                        b.edge_count * 2 * sizeof(std::uint32_t), std::size_t{1}});
  if (largest > block)
    throw Error(what + ": one instance's blended positions, normals or edge lists take " + megabytes(largest) +
                ", more than the OpenGL driver's largest storage block (" + megabytes(block) + ")");
  const std::size_t per_instance =
      (b.vertex_count + b.group_count) * 3 * sizeof(float) + b.edge_count * 2 * sizeof(std::uint32_t);
  b.batch_limit =
      std::max<std::size_t>(1, std::min({block / largest, kBlendBatchBytes / std::max<std::size_t>(per_instance, 1),
                                         static_cast<std::size_t>(std::max<GLint>(max_groups_y, 1))}));

  // Key deltas: each key's full mesh minus the base (dense), keyCount() x #V x 3.
  const std::size_t n = b.vertex_count * 3;
  std::vector<float> deltas(b.key_count * n);
  for (std::size_t k = 0; k < b.key_count; ++k) {
    const std::span<float> d(deltas.data() + k * n, n);
    if (!model.keyPositions(k, d)) throw Error(what + ": key " + std::to_string(k) + " (internal error)");
    for (std::size_t i = 0; i < n; ++i) d[i] -= mesh.positions[i];
  }
  // Faces per smoothing group (one entry per corner in the group), as offsets and a list.
  const auto corner_groups = t.cornerGroups();
  std::vector<std::int32_t> group_start(b.group_count + 1, 0), group_faces(corner_groups.size());
  for (const std::int32_t g : corner_groups) ++group_start[static_cast<std::size_t>(g) + 1];
  for (std::size_t g = 0; g < b.group_count; ++g) group_start[g + 1] += group_start[g];
  std::vector<std::int32_t> fill(group_start.begin(), group_start.end() - 1);
  for (std::size_t c = 0; c < corner_groups.size(); ++c)
    group_faces[static_cast<std::size_t>(fill[static_cast<std::size_t>(corner_groups[c])]++)] =
        static_cast<std::int32_t>(c / 3);
  std::vector<std::int32_t> edges(b.edge_count * 4);
  for (std::size_t e = 0; e < b.edge_count; ++e) {
    edges[e * 4] = t.edgeVertices()[e * 2];
    edges[e * 4 + 1] = t.edgeVertices()[e * 2 + 1];
    edges[e * 4 + 2] = t.edgeFaces()[e * 2];
    edges[e * 4 + 3] = t.edgeFaces()[e * 2 + 1];
  }
  std::vector<std::int32_t> refs(t.renderVertexCount() * 2);
  for (std::size_t r = 0; r < t.renderVertexCount(); ++r) {
    refs[r * 2] = t.renderSource()[r];
    refs[r * 2 + 1] = t.renderGroup()[r];
  }
  uploadMaterials(mesh, what, b.materials, b.textures);
  const std::vector<std::uint32_t> indices = sortedRenderTriangles(mesh, t, b.ranges);
  b.index_count = indices.size();

  b.base = staticBuffer(mesh.positions);
  b.deltas = staticBuffer(deltas);
  b.triangles = staticBuffer(std::vector<std::int32_t>(t.triangles().begin(), t.triangles().end()));
  b.group_start = staticBuffer(group_start);
  b.group_faces = staticBuffer(group_faces);
  b.edges = staticBuffer(edges);
  b.refs = staticBuffer(refs);
  b.uvs = staticBuffer(renderUvs(t, mesh.uvs));
  b.indices = staticBuffer(indices);
  b.positions = makeBuffer();
  b.normals = makeBuffer();
  b.strokes = makeBuffer();
  b.commands = makeBuffer();
  bufferData(b.commands, 10 * sizeof(std::uint32_t), nullptr, GL_DYNAMIC_DRAW);

  b.vao = makeVertexArray();
  glBindVertexArray(b.vao.get());
  glBindBuffer(GL_ARRAY_BUFFER, b.refs.get());
  glEnableVertexAttribArray(0);
  glVertexAttribIPointer(0, 2, GL_INT, 0, nullptr);
  glBindBuffer(GL_ARRAY_BUFFER, b.uvs.get());
  glEnableVertexAttribArray(2);
  glVertexAttribPointer(2, 2, GL_FLOAT, GL_FALSE, 0, nullptr);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, b.indices.get());
  // Strokes: the batch's blended positions as vertices, the edge lists as indices.
  b.stroke_vao = makeVertexArray();
  glBindVertexArray(b.stroke_vao.get());
  glBindBuffer(GL_ARRAY_BUFFER, b.positions.get());
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 0, nullptr);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, b.strokes.get());
  glBindVertexArray(0);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
  if (const GLenum err = glGetError(); err != GL_NO_ERROR)
    throw Error("OpenGL: error " + std::to_string(err) + " while uploading a blend model (" + megabytes(delta_bytes) +
                " of key deltas)");
  m.blend_models.push_back(std::move(gpu));
  return static_cast<int>(m.blend_models.size()) - 1;
}

bool Renderer::drawBlendInstances(int handle, std::span<const InstanceBlend> instances, const View& view,
                                  const MeshStyle& style) {
  Impl& m = *impl_;
  if (handle < 0 || static_cast<std::size_t>(handle) >= m.blend_models.size() || !validView(view)) return false;
  GpuBlendModel& b = *m.blend_models[static_cast<std::size_t>(handle)];
  if (!validInstances(b, instances)) return false;
  // Every check is above: from here on the call succeeds.
  if (instances.empty()) return true;
  m.context.makeCurrent();
  const std::size_t count = instances.size();
  const std::size_t batch = m.prepareBlend(b, instances);

  const float crease_width = style.crease_width > 0.0f ? style.crease_width : 0.5f * style.silhouette_width;
  const bool want_silhouettes = style.silhouette_width > 0.0f;
  const bool want_creases =
      std::isfinite(style.crease_angle_deg) && style.crease_angle_deg > 0.0f && crease_width > 0.0f;
  const bool want_strokes = (want_silhouettes || want_creases) && b.edge_count > 0;
  const auto cos_crease = static_cast<float>(
      std::cos(std::min(static_cast<double>(style.crease_angle_deg), 180.0) * std::numbers::pi / 180.0));
  const Eigen::Vector3f eye = facingEye(view.camera);

  glBindFramebuffer(GL_FRAMEBUFFER, m.ms_fbo.get());
  m.setView(view);
  const auto capacity = static_cast<GLuint>(b.batch_capacity * b.edge_count * 2);
  // Indirect draw commands {count, instances, first index, base vertex, base instance}: the
  // silhouettes' list grows from index 0, the creases' down from `capacity`.
  const std::array<GLuint, 10> reset{0, 1, 0, 0, 0, 0, 1, capacity, 0, 0};

  for (std::size_t first = 0; first < count; first += batch) {
    const std::size_t in_batch = std::min(batch, count - first);
    m.blendBatch(b, first, in_batch);
    if (want_strokes) {
      glBindBuffer(GL_COPY_WRITE_BUFFER, b.commands.get());
      glBufferSubData(GL_COPY_WRITE_BUFFER, 0, sizeof reset, reset.data());
      glBindBuffer(GL_COPY_WRITE_BUFFER, 0);
      const ComputeProgram& edges = *m.edges_compute;
      glUseProgram(edges.program.get());
      glUniform1i(edges.vertex_count, static_cast<GLint>(b.vertex_count));
      glUniform1i(edges.edge_count, static_cast<GLint>(b.edge_count));
      glUniform3fv(edges.eye, 1, eye.data());
      glUniform1i(edges.silhouettes, want_silhouettes ? 1 : 0);
      glUniform1i(edges.borders, style.borders ? 1 : 0);
      glUniform1i(edges.creases, want_creases ? 1 : 0);
      glUniform1f(edges.cos_crease, cos_crease);
      glUniform1ui(edges.capacity, capacity);
      dispatchItems(edges, b.edge_count, in_batch);
      if (want_creases) {
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
        glUseProgram(m.crease_start_compute->program.get());
        glUniform1ui(m.crease_start_compute->capacity, capacity);
        glDispatchCompute(1, 1, 1);
      }
    }
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_VERTEX_ATTRIB_ARRAY_BARRIER_BIT | GL_ELEMENT_ARRAY_BARRIER_BIT |
                    GL_COMMAND_BARRIER_BIT);

    // Shaded front faces of every instance of the batch, one instanced draw per material range.
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glEnable(GL_CULL_FACE);
    glCullFace(GL_BACK);
    glFrontFace(GL_CCW);
    const MeshProgram& p = *m.blend_program;
    glUseProgram(p.program.get());
    m.setMatrices(p.view, p.proj, view);
    glUniform1i(p.vertex_count, static_cast<GLint>(b.vertex_count));
    glUniform1i(p.group_count, static_cast<GLint>(b.group_count));
    glUniform1i(p.first_instance, static_cast<GLint>(first));
    glBindVertexArray(b.vao.get());
    glActiveTexture(GL_TEXTURE0);
    const auto draw = [&](std::size_t offset, std::size_t indices) {
      glDrawElementsInstanced(GL_TRIANGLES, static_cast<GLsizei>(indices), GL_UNSIGNED_INT,
                              reinterpret_cast<const void*>(offset * sizeof(std::uint32_t)),
                              static_cast<GLsizei>(in_batch));
    };
    if (!style.materials) {
      m.setShading(style, style.color, false, &p, true);
      draw(0, b.index_count);
    } else {
      for (const DrawRange& range : b.ranges) {
        const GpuMaterial* material =
            range.material >= 0 ? &b.materials[static_cast<std::size_t>(range.material)] : nullptr;
        const bool textured = material && material->texture >= 0;
        m.setShading(style, material ? material->base : style.color, textured, &p, material == nullptr);
        glBindTexture(GL_TEXTURE_2D, textured ? b.textures[static_cast<std::size_t>(material->texture)].get() : 0);
        draw(range.first, range.count);
      }
      glBindTexture(GL_TEXTURE_2D, 0);
    }
    glDisable(GL_CULL_FACE);
    if (!want_strokes) continue;

    // Creases, then silhouettes and borders: thick lines, then round dots at the edge ends.
    glBindVertexArray(b.stroke_vao.get());
    glBindBuffer(GL_DRAW_INDIRECT_BUFFER, b.commands.get());
    glDepthFunc(GL_LEQUAL);
    glDepthMask(GL_FALSE);
    const auto strokes = [&](std::size_t command, float width) {
      const void* offset = reinterpret_cast<const void*>(command * 5 * sizeof(GLuint));
      const float pull = style.silhouette_pull * width;
      glUseProgram(m.line_program->program.get());
      m.setStroke(*m.line_program, view, width, style.silhouette_color, pull);
      glDrawElementsIndirect(GL_LINES, GL_UNSIGNED_INT, offset);
      glEnable(GL_SAMPLE_ALPHA_TO_COVERAGE);
      glUseProgram(m.dot_program->program.get());
      m.setStroke(*m.dot_program, view, width, style.silhouette_color, pull);
      glDrawElementsIndirect(GL_POINTS, GL_UNSIGNED_INT, offset);
      glDisable(GL_SAMPLE_ALPHA_TO_COVERAGE);
    };
    if (want_creases) strokes(1, crease_width);
    if (want_silhouettes) strokes(0, style.silhouette_width);
    glDepthMask(GL_TRUE);
    glBindBuffer(GL_DRAW_INDIRECT_BUFFER, 0);
  }
  glBindVertexArray(0);
  return true;
}

bool Renderer::blendInstances(int handle, std::span<const InstanceBlend> instances) {
  Impl& m = *impl_;
  if (handle < 0 || static_cast<std::size_t>(handle) >= m.blend_models.size()) return false;
  GpuBlendModel& b = *m.blend_models[static_cast<std::size_t>(handle)];
  if (!validInstances(b, instances)) return false;
  if (instances.empty()) return true;
  m.context.makeCurrent();
  const std::size_t batch = m.prepareBlend(b, instances);
  for (std::size_t first = 0; first < instances.size(); first += batch)
    m.blendBatch(b, first, std::min(batch, instances.size() - first));
  return true;
}

void Renderer::finish() {
  impl_->context.makeCurrent();
  glFinish();
}

bool Renderer::readBlendInstance(int handle, std::size_t instance, std::span<float> positions,
                                 std::span<float> group_normals) {
  Impl& m = *impl_;
  if (handle < 0 || static_cast<std::size_t>(handle) >= m.blend_models.size()) return false;
  const GpuBlendModel& b = *m.blend_models[static_cast<std::size_t>(handle)];
  if (instance < b.last_first || instance >= b.last_first + b.last_count) return false;
  if (positions.size() != b.vertex_count * 3 || group_normals.size() != b.group_count * 3) return false;
  m.context.makeCurrent();
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  const std::size_t local = instance - b.last_first;
  glBindBuffer(GL_COPY_READ_BUFFER, b.positions.get());
  glGetBufferSubData(GL_COPY_READ_BUFFER, static_cast<GLintptr>(local * positions.size_bytes()),
                     static_cast<GLsizeiptr>(positions.size_bytes()), positions.data());
  glBindBuffer(GL_COPY_READ_BUFFER, b.normals.get());
  glGetBufferSubData(GL_COPY_READ_BUFFER, static_cast<GLintptr>(local * group_normals.size_bytes()),
                     static_cast<GLsizeiptr>(group_normals.size_bytes()), group_normals.data());
  glBindBuffer(GL_COPY_READ_BUFFER, 0);
  return true;
}

void Renderer::readPixels(Image& out) {
  Impl& m = *impl_;
  m.context.makeCurrent();
  glDisable(GL_SCISSOR_TEST);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, m.ms_fbo.get());
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, m.resolve_fbo.get());
  glBlitFramebuffer(0, 0, m.width, m.height, 0, 0, m.width, m.height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, m.resolve_fbo.get());
  glEnable(GL_SCISSOR_TEST);
  out.width = m.width;
  out.height = m.height;
  const std::size_t stride = static_cast<std::size_t>(m.width) * 4;
  out.rgba.resize(stride * static_cast<std::size_t>(m.height));
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, m.width, m.height, GL_RGBA, GL_UNSIGNED_BYTE, out.rgba.data());
  glBindFramebuffer(GL_FRAMEBUFFER, m.ms_fbo.get());
  if (const GLenum err = glGetError(); err != GL_NO_ERROR)
    throw Error("OpenGL: error " + std::to_string(err) + " while reading the image back");
  // OpenGL rows run bottom-up; images top-down.
  m.row.resize(stride);
  for (int y = 0; y < m.height / 2; ++y) {
    std::uint8_t* a = &out.rgba[static_cast<std::size_t>(y) * stride];
    std::uint8_t* b = &out.rgba[static_cast<std::size_t>(m.height - 1 - y) * stride];
    std::memcpy(m.row.data(), a, stride);
    std::memcpy(a, b, stride);
    std::memcpy(b, m.row.data(), stride);
  }
  for (std::size_t i = 3; i < out.rgba.size(); i += 4) out.rgba[i] = 255;
}

}  // namespace vdg::render
