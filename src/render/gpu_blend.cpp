// The GPU blend (Rademacher 99, section 3.2.3, on the GPU): compute passes blend the key deltas of
// many instances of a view-dependent model into per-instance positions (pass 1), group normals
// (pass 2) and silhouette and crease edge lists (pass 3), then instanced and indirect draws shade
// and stroke them. Set-up of the model's buffers (addBlendModel), the passes, the draws and the
// read-back for tests; renderer.cpp holds the rest of the renderer.
#include <epoxy/gl.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

#include "renderer_impl.h"
#include "shaders.h"
#include "vdg/geom/error.h"
#include "vdg/render/renderer.h"

namespace vdg::render {
using namespace detail;  // the module's internals (renderer_impl.h, gl_objects.h, shaders.h)

namespace {

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

// Checks `b`'s buffers against the driver's largest storage block (vdg::Error naming `what`) and
// sets the batch size from the per-instance bytes; returns the bytes of the key deltas.
std::size_t sizeBatches(GpuBlendModel& b, const std::string& what) {
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
  return delta_bytes;
}

// The instanced draw's vertex array (render vertices' (vertex, group) and uvs, the sorted
// triangles) and the strokes' (the batch's blended positions as vertices, the edge lists as
// indices).
void makeVertexArrays(GpuBlendModel& b) {
  b.vao = makeVertexArray();
  glBindVertexArray(b.vao.get());
  glBindBuffer(GL_ARRAY_BUFFER, b.refs.get());
  glEnableVertexAttribArray(0);
  glVertexAttribIPointer(0, 2, GL_INT, 0, nullptr);
  glBindBuffer(GL_ARRAY_BUFFER, b.uvs.get());
  glEnableVertexAttribArray(2);
  glVertexAttribPointer(2, 2, GL_FLOAT, GL_FALSE, 0, nullptr);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, b.indices.get());
  b.stroke_vao = makeVertexArray();
  glBindVertexArray(b.stroke_vao.get());
  glBindBuffer(GL_ARRAY_BUFFER, b.positions.get());
  glEnableVertexAttribArray(0);
  glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 0, nullptr);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, b.strokes.get());
  glBindVertexArray(0);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
}

}  // namespace

// Uploads the instances (checked by validInstances), grows `b`'s batch buffers and binds every
// storage buffer of the passes. Returns the instances per batch.
std::size_t Renderer::Impl::prepareBlend(GpuBlendModel& b, std::span<const InstanceBlend> instances) {
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
void Renderer::Impl::blendBatch(GpuBlendModel& b, std::size_t first, std::size_t in_batch) {
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

  const std::size_t delta_bytes = sizeBatches(b, what);

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

  makeVertexArrays(b);
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
    frontFacesState(want_strokes
                        ? std::max(want_silhouettes ? style.silhouette_width : 0.0f, want_creases ? crease_width : 0.0f)
                        : 0.0f);
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
    glDisable(GL_POLYGON_OFFSET_FILL);
    if (!want_strokes) continue;

    // Creases, then silhouettes and borders: thick lines, then round dots at the edge ends.
    glBindVertexArray(b.stroke_vao.get());
    glBindBuffer(GL_DRAW_INDIRECT_BUFFER, b.commands.get());
    glDepthFunc(GL_LEQUAL);
    glDepthMask(GL_FALSE);
    const auto strokes = [&](std::size_t command, float width) {
      const void* offset = reinterpret_cast<const void*>(command * 5 * sizeof(GLuint));
      glUseProgram(m.line_program->program.get());
      m.setStroke(*m.line_program, view, width, style.silhouette_color, 0.0f);
      glDrawElementsIndirect(GL_LINES, GL_UNSIGNED_INT, offset);
      glEnable(GL_SAMPLE_ALPHA_TO_COVERAGE);
      glUseProgram(m.dot_program->program.get());
      m.setStroke(*m.dot_program, view, width, style.silhouette_color, 0.0f);
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

}  // namespace vdg::render
