#include "vdg/geom/tri_mesh.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "vdg/geom/error.h"

namespace vdg {
namespace {

// Normals only need directions, so the edges may be scaled by any positive factor. Float edge
// cross products overflow once coordinates pass about 1e19 (and their squared lengths already
// near 1e9 on high-valence vertices), and underflow for coordinates near 1e-19. Meshes whose
// largest |coordinate| lies outside [2^-20, 2^20] are therefore scaled by a power of two that
// brings it to [1/2, 1) (exact: no rounding); all other meshes are left bit-for-bit as they are.
float normalScale(std::span<const float> positions) {
  float largest = 0.0f;
  for (const float p : positions) largest = std::max(largest, std::abs(p));  // NaN is skipped
  if (!(largest > 0.0f) || !std::isfinite(largest)) return 1.0f;
  if (largest >= 0x1p-20f && largest <= 0x1p20f) return 1.0f;
  return std::ldexp(1.0f, std::min(-std::ilogb(largest) - 1, 127));  // 2^127: subnormal inputs
}

}  // namespace

std::array<float, 3> Bounds::center() const {
  return {(min[0] + max[0]) * 0.5f, (min[1] + max[1]) * 0.5f, (min[2] + max[2]) * 0.5f};
}

float Bounds::diagonal() const {
  // In double: float squares overflow for extents past about 1e19.
  const double dx = double(max[0]) - min[0], dy = double(max[1]) - min[1], dz = double(max[2]) - min[2];
  return static_cast<float>(std::sqrt(dx * dx + dy * dy + dz * dz));
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
  const float scale = normalScale(positions);
  for (std::size_t t = 0; t < triangles.size(); t += 3) {
    const std::size_t a = 3 * static_cast<std::size_t>(triangles[t]);
    const std::size_t b = 3 * static_cast<std::size_t>(triangles[t + 1]);
    const std::size_t c = 3 * static_cast<std::size_t>(triangles[t + 2]);
    const float e1x = positions[b] * scale - positions[a] * scale,
                e1y = positions[b + 1] * scale - positions[a + 1] * scale,
                e1z = positions[b + 2] * scale - positions[a + 2] * scale;
    const float e2x = positions[c] * scale - positions[a] * scale,
                e2y = positions[c + 1] * scale - positions[a + 1] * scale,
                e2z = positions[c + 2] * scale - positions[a + 2] * scale;
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
  if (mesh.normals.size() % 3 != 0) throw Error(what + ": normal array is not a multiple of 3");
  if (!mesh.normal_triangles.empty() && mesh.normal_triangles.size() != mesh.triangles.size())
    throw Error(what + ": normal triangles (" + std::to_string(mesh.normal_triangles.size() / 3) +
                ") do not match the triangles (" + std::to_string(mesh.triangleCount()) + ")");
  if (mesh.normal_triangles.empty() != mesh.normals.empty())
    throw Error(what + ": normals and normal triangles must be given together");
  for (std::size_t i = 0; i < mesh.normal_triangles.size(); ++i) {
    const auto t = mesh.normal_triangles[i];
    if (t < 0 || static_cast<std::size_t>(t) >= mesh.normals.size() / 3)
      throw Error(what + ": triangle " + std::to_string(i / 3) + " refers to normal " + std::to_string(t) +
                  ", but the mesh has " + std::to_string(mesh.normals.size() / 3));
  }
  for (std::size_t i = 0; i < mesh.normals.size(); ++i) {
    if (!std::isfinite(mesh.normals[i]))
      throw Error(what + ": normal " + std::to_string(i / 3) + " has a non-finite component (NaN or Inf)");
  }
  if (!mesh.face_materials.empty() && mesh.face_materials.size() != mesh.triangleCount())
    throw Error(what + ": " + std::to_string(mesh.face_materials.size()) + " face materials for " +
                std::to_string(mesh.triangleCount()) + " triangles");
  for (std::size_t f = 0; f < mesh.face_materials.size(); ++f) {
    const auto m = mesh.face_materials[f];
    if (m < -1 || (m >= 0 && static_cast<std::size_t>(m) >= mesh.materials.size()))
      throw Error(what + ": triangle " + std::to_string(f) + " refers to material " + std::to_string(m) +
                  ", but the mesh has " + std::to_string(mesh.materials.size()));
  }
  for (const Material& m : mesh.materials) {
    for (const float c : m.base_color)
      if (!(c >= 0.0f && c <= 1.0f))
        throw Error(what + ": material '" + m.name + "': base colour component outside [0, 1]");
    if (m.texture && (m.texture->width < 1 || m.texture->height < 1 ||
                      m.texture->rgba.size() !=
                          static_cast<std::size_t>(m.texture->width) * static_cast<std::size_t>(m.texture->height) * 4))
      throw Error(what + ": material '" + m.name + "': texture pixels do not match its size");
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
