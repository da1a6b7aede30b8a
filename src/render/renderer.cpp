// Headless NPR renderer: Rademacher 99, section 3.2.4 (warm/cool lighting; silhouettes after
// Raskar and Cohen 99, drawn from per-frame silhouette edges as screen-space quads plus round
// dots; see renderer.h for why a core profile needs this instead of wide back-face lines).
#include "vdg/render/renderer.h"

#include <epoxy/gl.h>

#include <algorithm>
#include <cmath>
#include <cstring>
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

struct MeshProgram {
  GlProgram program;
  GLint view, proj, base, warm, cool, light_warm, light_cool, ka, k, flat;
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

struct GpuMesh {
  std::vector<std::int32_t> triangles;
  std::size_t vertex_count = 0;
  EdgeTopology topology;
  std::vector<float> positions;  // this frame's, for the facing test
  std::vector<std::uint8_t> front;
  std::vector<std::uint32_t> silhouette;
  bool has_normals = false;
  GlVertexArray vao;
  GlBuffer position_buffer, normal_buffer, triangle_buffer, silhouette_buffer;
};

Eigen::Vector3f toVec(const std::array<float, 3>& a) { return {a[0], a[1], a[2]}; }

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

  void setShading(const MeshStyle& style) {
    const MeshProgram& p = *mesh_program;
    const ShadingConstants k = effectiveConstants(style.shading, style.color);
    const Eigen::Vector3f l1 = toVec(style.shading.light_warm).normalized();
    const Eigen::Vector3f l2 = toVec(style.shading.light_cool).normalized();
    glUniform3fv(p.base, 1, style.color.data());
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

}  // namespace

int Renderer::width() const { return impl_->width; }
int Renderer::height() const { return impl_->height; }
int Renderer::samples() const { return impl_->samples; }
std::string Renderer::glInfo() const { return impl_->info; }

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
  mesh->triangles.assign(triangles.begin(), triangles.end());
  mesh->vertex_count = vertex_count;
  mesh->topology = buildEdgeTopology(triangles, vertex_count);
  mesh->positions.assign(vertex_count * 3, 0.0f);
  mesh->front.assign(triangles.size() / 3, 0);
  mesh->silhouette.reserve(mesh->topology.edgeCount() * 2);
  mesh->vao = makeVertexArray();
  mesh->position_buffer = makeBuffer();
  mesh->normal_buffer = makeBuffer();
  mesh->triangle_buffer = makeBuffer();
  mesh->silhouette_buffer = makeBuffer();
  glBindVertexArray(mesh->vao.get());
  const auto bytes = static_cast<GLsizeiptr>(vertex_count * 3 * sizeof(float));
  glBindBuffer(GL_ARRAY_BUFFER, mesh->position_buffer.get());
  glBufferData(GL_ARRAY_BUFFER, bytes, nullptr, GL_DYNAMIC_DRAW);
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 0, nullptr);
  glBindBuffer(GL_ARRAY_BUFFER, mesh->normal_buffer.get());
  glBufferData(GL_ARRAY_BUFFER, bytes, nullptr, GL_DYNAMIC_DRAW);
  glEnableVertexAttribArray(1);
  glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, 0, nullptr);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, mesh->triangle_buffer.get());
  glBufferData(GL_ELEMENT_ARRAY_BUFFER, static_cast<GLsizeiptr>(triangles.size_bytes()), triangles.data(),
               GL_STATIC_DRAW);
  glBindVertexArray(0);
  glBindBuffer(GL_COPY_WRITE_BUFFER, mesh->silhouette_buffer.get());
  glBufferData(
      GL_COPY_WRITE_BUFFER,
      static_cast<GLsizeiptr>(std::max<std::size_t>(1, mesh->topology.edgeCount() * 2) * sizeof(std::uint32_t)),
      nullptr, GL_DYNAMIC_DRAW);
  m.meshes.push_back(std::move(mesh));
  return static_cast<int>(m.meshes.size()) - 1;
}

bool Renderer::updateMesh(int mesh_id, std::span<const float> positions, std::span<const float> normals) {
  Impl& m = *impl_;
  if (mesh_id < 0 || static_cast<std::size_t>(mesh_id) >= m.meshes.size()) return false;
  GpuMesh& mesh = *m.meshes[static_cast<std::size_t>(mesh_id)];
  const std::size_t n = mesh.positions.size();
  if (positions.size() != n || (!normals.empty() && normals.size() != n)) return false;
  m.context.makeCurrent();
  std::copy_n(positions.begin(), n, mesh.positions.begin());
  glBindBuffer(GL_ARRAY_BUFFER, mesh.position_buffer.get());
  glBufferSubData(GL_ARRAY_BUFFER, 0, static_cast<GLsizeiptr>(n * sizeof(float)), positions.data());
  mesh.has_normals = !normals.empty();
  if (mesh.has_normals) {
    glBindBuffer(GL_ARRAY_BUFFER, mesh.normal_buffer.get());
    glBufferSubData(GL_ARRAY_BUFFER, 0, static_cast<GLsizeiptr>(n * sizeof(float)), normals.data());
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

  // Pass 1: shaded front faces (back faces culled).
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
  m.setShading(shaded);
  glBindVertexArray(mesh.vao.get());
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, mesh.triangle_buffer.get());
  glDrawElements(GL_TRIANGLES, static_cast<GLsizei>(mesh.triangles.size()), GL_UNSIGNED_INT, nullptr);
  glDisable(GL_CULL_FACE);
  if (style.silhouette_width <= 0.0f) return true;

  // Pass 2: silhouette edges (one face towards the eye, the other away), found on the CPU.
  Eigen::Vector3f eye = view.camera.eye.cast<float>();
  if (view.camera.isOrtho()) {
    const Eigen::Vector3d back = (view.camera.eye - view.camera.target).normalized();
    eye = (view.camera.target + back * (1e6 * std::max(1.0, view.camera.ortho_height))).cast<float>();
  }
  faceFacing(mesh.positions, mesh.triangles, eye, mesh.front);
  silhouetteEdges(mesh.topology, mesh.front, mesh.silhouette);
  if (mesh.silhouette.empty()) return true;
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, mesh.silhouette_buffer.get());
  glBufferSubData(GL_ELEMENT_ARRAY_BUFFER, 0, static_cast<GLsizeiptr>(mesh.silhouette.size() * sizeof(std::uint32_t)),
                  mesh.silhouette.data());
  glDepthFunc(GL_LEQUAL);
  glDepthMask(GL_FALSE);
  const float width = style.silhouette_width;
  const float pull = style.silhouette_pull * width;
  glUseProgram(m.line_program->program.get());
  m.setStroke(*m.line_program, view, width, style.silhouette_color, pull);
  glDrawElements(GL_LINES, static_cast<GLsizei>(mesh.silhouette.size()), GL_UNSIGNED_INT, nullptr);
  // Pass 3: round dots at the edge ends fill the cracks between thick edges (the paper's points).
  glEnable(GL_SAMPLE_ALPHA_TO_COVERAGE);
  glUseProgram(m.dot_program->program.get());
  m.setStroke(*m.dot_program, view, width, style.silhouette_color, pull);
  glDrawElements(GL_POINTS, static_cast<GLsizei>(mesh.silhouette.size()), GL_UNSIGNED_INT, nullptr);
  glDisable(GL_SAMPLE_ALPHA_TO_COVERAGE);
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
  m.setShading(flat);
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
