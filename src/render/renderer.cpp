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

#include "renderer_impl.h"
#include "shaders.h"
#include "vdg/geom/error.h"
#include "vdg/render/silhouette.h"

namespace vdg::render {
using namespace detail;  // the module's internals (renderer_impl.h, gl_objects.h, shaders.h)

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

}  // namespace

namespace detail {

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

void frontFacesState(float widest_stroke_px) {
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  glEnable(GL_CULL_FACE);
  glCullFace(GL_BACK);
  glFrontFace(GL_CCW);
  if (widest_stroke_px > 0.0f) {
    // A stroke's pixels lie at most half its width from its edge, in any screen direction: a face
    // there comes towards the eye by at most sqrt(2) x its largest depth slope per pixel (the
    // slope glPolygonOffset scales) times that distance; one pixel more covers the line's
    // antialiased fringe. The units term absorbs the rounding between the two rasterisations.
    glEnable(GL_POLYGON_OFFSET_FILL);
    glPolygonOffset(std::numbers::sqrt2_v<float> * 0.5f * widest_stroke_px + 1.0f, kStrokeOffsetUnits);
  } else {
    glDisable(GL_POLYGON_OFFSET_FILL);
  }
}

void bufferData(const GlBuffer& buffer, std::size_t bytes, const void* data, GLenum usage) {
  glBindBuffer(GL_COPY_WRITE_BUFFER, buffer.get());
  glBufferData(GL_COPY_WRITE_BUFFER, static_cast<GLsizeiptr>(std::max<std::size_t>(bytes, 16)), data, usage);
  glBindBuffer(GL_COPY_WRITE_BUFFER, 0);
}

}  // namespace detail

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

namespace detail {

bool finite3(const Eigen::Vector3d& v) { return v.allFinite(); }

// The conditions under which viewMatrix / projectionMatrix are defined (see cameraFrame), checked
// without throwing.
const char* viewProblem(const View& v) {
  if (v.viewport.width < 1 || v.viewport.height < 1) return "the viewport is empty";
  if (!std::isfinite(v.z_near) || !std::isfinite(v.z_far)) return "the clip planes are not finite";
  if (!(v.z_near > 0.0) || !(v.z_far > v.z_near)) return "the clip planes are not 0 < near < far";
  const Camera& c = v.camera;
  if (!finite3(c.eye)) return "the camera's eye is not finite";
  if (!finite3(c.target)) return "the camera's target is not finite";
  if (!finite3(c.up)) return "the camera's up vector is not finite";
  if (!std::isfinite(c.ortho_height) || !std::isfinite(c.fov_deg)) return "the camera's field of view is not finite";
  const Eigen::Vector3d back = c.eye - c.target;
  if (!(back.norm() > 0.0)) return "the camera's eye and target are the same point";
  if (!(c.up.cross(back.normalized()).norm() > 1e-12 * c.up.norm()))
    return "the camera's up vector is parallel to its view";
  if (!c.isOrtho() && !(c.fov_deg > 0.0 && c.fov_deg < 180.0)) return "the camera's field of view is not in (0, 180)";
  return nullptr;
}

bool validView(const View& v) { return viewProblem(v) == nullptr; }

bool positiveFinite(float x) { return std::isfinite(x) && x > 0.0f; }

// The eye point of the facing test: the camera's eye, or for a parallel camera a point far back
// along its view axis.
Eigen::Vector3f facingEye(const Camera& camera) {
  if (!camera.isOrtho()) return camera.eye.cast<float>();
  const Eigen::Vector3d back = (camera.eye - camera.target).normalized();
  return (camera.target + back * (1e6 * std::max(1.0, camera.ortho_height))).cast<float>();
}

}  // namespace detail

int Renderer::width() const { return impl_->width; }
int Renderer::height() const { return impl_->height; }
int Renderer::samples() const { return impl_->samples; }
std::string Renderer::glInfo() const { return impl_->info; }

namespace detail {

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

}  // namespace detail

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
  return m.drawSurface(*m.meshes[static_cast<std::size_t>(mesh_id)], view, style, nullptr, nullptr);
}

bool Renderer::drawMeshDrawings(int mesh_id, int drawings_id, const View& view, const MeshStyle& style,
                                const ViewWeights& weights) {
  Impl& m = *impl_;
  if (mesh_id < 0 || static_cast<std::size_t>(mesh_id) >= m.meshes.size() || !validView(view)) return false;
  if (drawings_id < 0 || static_cast<std::size_t>(drawings_id) >= m.drawings.size()) return false;
  const GpuDrawings& d = *m.drawings[static_cast<std::size_t>(drawings_id)];
  if (d.mesh != mesh_id || !std::isfinite(weights.base)) return false;
  for (int i = 0; i < 3; ++i) {
    const int key = weights.key[static_cast<std::size_t>(i)];
    if (key < -1 || key >= static_cast<int>(d.present.size()) ||
        !std::isfinite(weights.weight[static_cast<std::size_t>(i)]))
      return false;
  }
  return m.drawSurface(*m.meshes[static_cast<std::size_t>(mesh_id)], view, style, &d, &weights);
}

int Renderer::addDrawings(int mesh_id, const DrawingTextures& drawings) {
  Impl& m = *impl_;
  const std::string what = "render: addDrawings: ";
  if (mesh_id < 0 || static_cast<std::size_t>(mesh_id) >= m.meshes.size() ||
      !m.meshes[static_cast<std::size_t>(mesh_id)]->surface)
    throw Error(what + "mesh " + std::to_string(mesh_id) + " is not a surface of this renderer (addSurface)");
  const GpuMesh& mesh = *m.meshes[static_cast<std::size_t>(mesh_id)];
  const SurfaceTopology& t = mesh.topology;
  if (drawings.vertexCount() != t.vertexCount())
    throw Error(what + "the drawings were built for " + std::to_string(drawings.vertexCount()) +
                " vertices; the mesh has " + std::to_string(t.vertexCount()));
  m.context.makeCurrent();
  if (!m.drawing_program)
    m.drawing_program =
        std::make_unique<DrawingProgram>(link("drawing", shaders::kDrawingVertex, nullptr, shaders::kDrawingFragment));
  GLint max_texture = 0;
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_texture);
  auto gpu = std::make_unique<GpuDrawings>();
  gpu->mesh = mesh_id;
  gpu->textures.resize(drawings.keyCount());
  gpu->attributes.resize(drawings.keyCount());
  gpu->present.assign(drawings.keyCount(), 0);
  const auto source = t.renderSource();
  std::vector<float> gathered(source.size() * 4);
  for (std::size_t k = 0; k < drawings.keyCount(); ++k) {
    if (!drawings.hasDrawing(k)) continue;
    const TextureImage& image = drawings.image(k);
    if (image.width > max_texture || image.height > max_texture)
      throw Error(what + "key " + std::to_string(k) + "'s drawing (" + std::to_string(image.width) + "x" +
                  std::to_string(image.height) + ") exceeds the OpenGL driver's limit of " +
                  std::to_string(max_texture) + " pixels a side");
    const auto stq = drawings.projective(k);
    const auto visible = drawings.visibility(k);
    for (std::size_t r = 0; r < source.size(); ++r) {
      const auto v = static_cast<std::size_t>(source[r]);
      std::copy_n(&stq[v * 3], 3, &gathered[r * 4]);
      gathered[r * 4 + 3] = visible[v];
    }
    gpu->textures[k] = uploadTexture(image, GL_CLAMP_TO_EDGE);
    gpu->attributes[k] = staticBuffer(gathered);
    gpu->present[k] = 1;
  }
  m.drawings.push_back(std::move(gpu));
  return static_cast<int>(m.drawings.size()) - 1;
}

namespace detail {

// Binds each slot's drawing (texture unit 1 + slot, vertex attribute 3 + slot) and sets the slot
// weights; a slot with no key or a key without a drawing gets weight 0 and a constant attribute.
void bindDrawings(const DrawingProgram& p, const GpuDrawings& d, const ViewWeights& w) {
  float weights[4] = {0.0f, 0.0f, 0.0f, w.base};
  for (int i = 0; i < 3; ++i) {
    const auto slot = static_cast<std::size_t>(i);
    const int key = w.key[slot];
    const bool on = key >= 0 && d.present[static_cast<std::size_t>(key)];
    const auto location = static_cast<GLuint>(3 + i);
    glActiveTexture(static_cast<GLenum>(GL_TEXTURE1 + i));
    glBindTexture(GL_TEXTURE_2D, on ? d.textures[static_cast<std::size_t>(key)].get() : 0);
    glUniform1i(p.images[slot], 1 + i);
    if (on) {
      glBindBuffer(GL_ARRAY_BUFFER, d.attributes[static_cast<std::size_t>(key)].get());
      glEnableVertexAttribArray(location);
      glVertexAttribPointer(location, 4, GL_FLOAT, GL_FALSE, 0, nullptr);
      weights[slot] = w.weight[slot];
    } else {
      glDisableVertexAttribArray(location);
      glVertexAttrib4f(location, 0.0f, 0.0f, 0.0f, 0.0f);
    }
  }
  glUniform4fv(p.weights, 1, weights);
  glActiveTexture(GL_TEXTURE0);
}

void unbindDrawings() {
  for (int i = 0; i < 3; ++i) {
    glDisableVertexAttribArray(static_cast<GLuint>(3 + i));
    glActiveTexture(static_cast<GLenum>(GL_TEXTURE1 + i));
    glBindTexture(GL_TEXTURE_2D, 0);
  }
  glActiveTexture(GL_TEXTURE0);
}

}  // namespace detail

bool Renderer::Impl::drawSurface(GpuMesh& mesh, const View& view, const MeshStyle& style, const GpuDrawings* layers,
                                 const ViewWeights* weights) {
  Impl& m = *this;
  m.context.makeCurrent();
  glBindFramebuffer(GL_FRAMEBUFFER, m.ms_fbo.get());
  m.setView(view);

  const float crease_width = style.crease_width > 0.0f ? style.crease_width : 0.5f * style.silhouette_width;
  const bool want_creases = style.crease_angle_deg > 0.0f && crease_width > 0.0f;
  const float widest_stroke = std::max(std::max(style.silhouette_width, 0.0f), want_creases ? crease_width : 0.0f);

  // Pass 1: shaded front faces (back faces culled), one draw per material range, pushed back under
  // the strokes of pass 2 (frontFacesState).
  frontFacesState(widest_stroke);
  const MeshProgram& program = layers ? m.drawing_program->mesh : *m.mesh_program;
  glUseProgram(program.program.get());
  m.setMatrices(program.view, program.proj, view);
  MeshStyle shaded = style;
  shaded.flat = style.flat || !mesh.has_normals;
  glBindVertexArray(mesh.vao.get());
  if (layers) bindDrawings(*m.drawing_program, *layers, *weights);
  glActiveTexture(GL_TEXTURE0);
  const auto draw = [](std::size_t first, std::size_t count) {
    glDrawElements(GL_TRIANGLES, static_cast<GLsizei>(count), GL_UNSIGNED_INT,
                   reinterpret_cast<const void*>(first * sizeof(std::uint32_t)));
  };
  if (!style.materials) {
    m.setShading(shaded, style.color, false, &program);
    draw(0, mesh.index_count);
  } else {
    for (const DrawRange& range : mesh.ranges) {
      const GpuMaterial* material =
          range.material >= 0 ? &mesh.materials[static_cast<std::size_t>(range.material)] : nullptr;
      const bool textured = material && material->texture >= 0;
      m.setShading(shaded, material ? material->base : style.color, textured, &program);
      glBindTexture(GL_TEXTURE_2D, textured ? mesh.textures[static_cast<std::size_t>(material->texture)].get() : 0);
      draw(range.first, range.count);
    }
    glBindTexture(GL_TEXTURE_2D, 0);
  }
  if (layers) unbindDrawings();
  glDisable(GL_CULL_FACE);
  glDisable(GL_POLYGON_OFFSET_FILL);
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
  const auto strokes = [&](std::size_t first, std::size_t count, float line_width) {
    if (count == 0) return;
    const void* offset = reinterpret_cast<const void*>(first * sizeof(std::uint32_t));
    glUseProgram(m.line_program->program.get());
    m.setStroke(*m.line_program, view, line_width, style.silhouette_color, 0.0f);
    glDrawElements(GL_LINES, static_cast<GLsizei>(count), GL_UNSIGNED_INT, offset);
    glEnable(GL_SAMPLE_ALPHA_TO_COVERAGE);
    glUseProgram(m.dot_program->program.get());
    m.setStroke(*m.dot_program, view, line_width, style.silhouette_color, 0.0f);
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

void Renderer::finish() {
  impl_->context.makeCurrent();
  glFinish();
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
