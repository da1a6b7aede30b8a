#include "vdg/geom/tri_mesh.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "vdg/geom/error.h"

namespace vdg {

std::array<float, 3> Bounds::center() const {
  return {(min[0] + max[0]) * 0.5f, (min[1] + max[1]) * 0.5f, (min[2] + max[2]) * 0.5f};
}

float Bounds::diagonal() const {
  const float dx = max[0] - min[0], dy = max[1] - min[1], dz = max[2] - min[2];
  return std::sqrt(dx * dx + dy * dy + dz * dz);
}

Bounds computeBounds(std::span<const float> positions) {
  Bounds b;
  if (positions.size() < 3) return b;
  b.min = b.max = {positions[0], positions[1], positions[2]};
  for (std::size_t i = 0; i + 2 < positions.size(); i += 3) {
    for (int c = 0; c < 3; ++c) {
      b.min[c] = std::min(b.min[c], positions[i + c]);
      b.max[c] = std::max(b.max[c], positions[i + c]);
    }
  }
  return b;
}

bool computeVertexNormals(std::span<const float> positions, std::span<const std::int32_t> triangles,
                          std::span<float> normals) {
  if (positions.size() % 3 != 0 || normals.size() != positions.size() || triangles.size() % 3 != 0) return false;
  const auto vertex_count = static_cast<std::int64_t>(positions.size() / 3);
  for (const std::int32_t v : triangles)
    if (v < 0 || v >= vertex_count) return false;
  std::fill(normals.begin(), normals.end(), 0.0f);
  for (std::size_t t = 0; t < triangles.size(); t += 3) {
    const std::size_t a = 3 * static_cast<std::size_t>(triangles[t]);
    const std::size_t b = 3 * static_cast<std::size_t>(triangles[t + 1]);
    const std::size_t c = 3 * static_cast<std::size_t>(triangles[t + 2]);
    const float e1x = positions[b] - positions[a], e1y = positions[b + 1] - positions[a + 1],
                e1z = positions[b + 2] - positions[a + 2];
    const float e2x = positions[c] - positions[a], e2y = positions[c + 1] - positions[a + 1],
                e2z = positions[c + 2] - positions[a + 2];
    const float nx = e1y * e2z - e1z * e2y, ny = e1z * e2x - e1x * e2z, nz = e1x * e2y - e1y * e2x;
    for (const std::size_t v : {a, b, c}) {
      normals[v] += nx;
      normals[v + 1] += ny;
      normals[v + 2] += nz;
    }
  }
  for (std::size_t v = 0; v < normals.size(); v += 3) {
    const float len =
        std::sqrt(normals[v] * normals[v] + normals[v + 1] * normals[v + 1] + normals[v + 2] * normals[v + 2]);
    if (len > 0.0f) {
      const float inv = 1.0f / len;
      normals[v] *= inv;
      normals[v + 1] *= inv;
      normals[v + 2] *= inv;
    }
  }
  return true;
}

void validateMesh(const TriMesh& mesh, const std::string& what) {
  if (mesh.positions.size() % 3 != 0) throw Error(what + ": position array is not a multiple of 3");
  if (mesh.triangles.size() % 3 != 0) throw Error(what + ": triangle array is not a multiple of 3");
  const std::size_t nv = mesh.vertexCount();
  if (nv == 0) throw Error(what + ": mesh has no vertices");
  if (mesh.triangles.empty()) throw Error(what + ": mesh has no triangles");
  if (mesh.uvs.size() % 2 != 0) throw Error(what + ": texture coordinate array is not a multiple of 2");
  if (!mesh.uv_triangles.empty() && mesh.uv_triangles.size() != mesh.triangles.size())
    throw Error(what + ": texture triangles (" + std::to_string(mesh.uv_triangles.size() / 3) +
                ") do not match the triangles (" + std::to_string(mesh.triangleCount()) + ")");
  for (std::size_t i = 0; i < mesh.uv_triangles.size(); ++i) {
    const auto t = mesh.uv_triangles[i];
    if (t < 0 || static_cast<std::size_t>(t) >= mesh.uvs.size() / 2)
      throw Error(what + ": triangle " + std::to_string(i / 3) + " refers to texture coordinate " + std::to_string(t) +
                  ", but the mesh has " + std::to_string(mesh.uvs.size() / 2));
  }
  for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
    if (!std::isfinite(mesh.positions[i]))
      throw Error(what + ": vertex " + std::to_string(i / 3) + " has a non-finite coordinate (NaN or Inf)");
  }
  for (std::size_t i = 0; i < mesh.triangles.size(); ++i) {
    const auto v = mesh.triangles[i];
    if (v < 0 || static_cast<std::size_t>(v) >= nv)
      throw Error(what + ": triangle " + std::to_string(i / 3) + " refers to vertex " + std::to_string(v) +
                  ", but the mesh has " + std::to_string(nv) + " vertices");
  }
}

}  // namespace vdg
