// Small meshes and temporary folders for tests (header-only; tests link it as they like).
#pragma once

#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "vdg/geom/tri_mesh.h"

namespace vdg::testing {

// A UV sphere of radius 1 around the origin: (rings - 1) * segments + 2 vertices.
inline TriMesh uvSphere(int rings = 8, int segments = 12) {
  TriMesh m;
  m.positions.insert(m.positions.end(), {0.0f, 1.0f, 0.0f});
  for (int r = 1; r < rings; ++r) {
    const double theta = M_PI * r / rings;
    for (int s = 0; s < segments; ++s) {
      const double phi = 2.0 * M_PI * s / segments;
      m.positions.insert(m.positions.end(),
                         {static_cast<float>(std::sin(theta) * std::cos(phi)), static_cast<float>(std::cos(theta)),
                          static_cast<float>(-std::sin(theta) * std::sin(phi))});
    }
  }
  m.positions.insert(m.positions.end(), {0.0f, -1.0f, 0.0f});
  const int south = 1 + (rings - 1) * segments;
  auto ring = [&](int r, int s) { return 1 + (r - 1) * segments + (s % segments); };
  for (int s = 0; s < segments; ++s) m.triangles.insert(m.triangles.end(), {0, ring(1, s), ring(1, s + 1)});
  for (int r = 1; r + 1 < rings; ++r)
    for (int s = 0; s < segments; ++s) {
      m.triangles.insert(m.triangles.end(), {ring(r, s), ring(r + 1, s), ring(r + 1, s + 1)});
      m.triangles.insert(m.triangles.end(), {ring(r, s), ring(r + 1, s + 1), ring(r, s + 1)});
    }
  for (int s = 0; s < segments; ++s)
    m.triangles.insert(m.triangles.end(), {ring(rings - 1, s), south, ring(rings - 1, s + 1)});
  return m;
}

// An axis-aligned box [min, max] as a closed mesh: 8 shared vertices, 12 triangles wound
// counter-clockwise seen from outside.
inline TriMesh closedBox(float x0, float y0, float z0, float x1, float y1, float z1) {
  TriMesh m;
  for (int i = 0; i < 8; ++i)
    m.positions.insert(m.positions.end(), {(i & 1) ? x1 : x0, (i & 2) ? y1 : y0, (i & 4) ? z1 : z0});
  m.triangles = {0, 2, 3, 0, 3, 1, 4, 5, 7, 4, 7, 6, 0, 1, 5, 0, 5, 4,
                 2, 6, 7, 2, 7, 3, 0, 4, 6, 0, 6, 2, 1, 3, 7, 1, 7, 5};
  return m;
}

// A torus about the y axis: ring radius R, tube radius r; rings x sides vertices (genus 1).
inline TriMesh torus(double R = 1.0, double r = 0.4, int rings = 32, int sides = 16) {
  TriMesh m;
  for (int i = 0; i < rings; ++i) {
    const double u = 2.0 * M_PI * i / rings;
    for (int j = 0; j < sides; ++j) {
      const double v = 2.0 * M_PI * j / sides;
      const double d = R + r * std::cos(v);
      m.positions.insert(m.positions.end(), {static_cast<float>(d * std::cos(u)), static_cast<float>(r * std::sin(v)),
                                             static_cast<float>(-d * std::sin(u))});
    }
  }
  auto at = [&](int i, int j) { return (i % rings) * sides + (j % sides); };
  for (int i = 0; i < rings; ++i)
    for (int j = 0; j < sides; ++j) {
      m.triangles.insert(m.triangles.end(), {at(i, j), at(i + 1, j), at(i + 1, j + 1)});
      m.triangles.insert(m.triangles.end(), {at(i, j), at(i + 1, j + 1), at(i, j + 1)});
    }
  return m;
}

// A unit cube ([-1, 1]^3) as exporters write it: 24 vertices (each face its own four), with the
// face normals as file normals (TriMesh::normals, one per vertex), so its edges are hard.
inline TriMesh splitCube() {
  TriMesh m;
  const float n[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  for (int f = 0; f < 6; ++f) {
    const int axis = f / 2;
    const float sign = n[f][axis];
    const int u = (axis + 1) % 3, w = (axis + 2) % 3;
    const float corners[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
    for (const auto& c : corners) {
      float p[3];
      p[axis] = sign;
      p[u] = c[0];
      p[w] = c[1] * sign;  // keeps the winding counter-clockwise seen from outside
      m.positions.insert(m.positions.end(), {p[0], p[1], p[2]});
      m.normals.insert(m.normals.end(), {n[f][0], n[f][1], n[f][2]});
    }
    const int b = f * 4;
    m.triangles.insert(m.triangles.end(), {b, b + 1, b + 2, b, b + 2, b + 3});
  }
  m.normal_triangles = m.triangles;
  return m;
}

// uvSphere() with the meridian at s = 0 duplicated, as a texture seam: the copies have their own
// texture coordinates (u = 1 instead of 0) and the same positions; no file normals.
inline TriMesh seamSphere(int rings = 8, int segments = 12) {
  TriMesh m = uvSphere(rings, segments);
  const auto nv = static_cast<std::int32_t>(m.vertexCount());
  // uvs: one per vertex (the copies' included), so a vertex's uv index is its own index.
  for (std::int32_t v = 0; v < nv; ++v) {
    const float x = m.positions[v * 3], y = m.positions[v * 3 + 1], z = m.positions[v * 3 + 2];
    float u = static_cast<float>(std::atan2(-z, x) / (2.0 * M_PI));
    if (u < 0.0f) u += 1.0f;
    if (u > 0.999f) u = 0.0f;
    m.uvs.insert(m.uvs.end(), {u, 0.5f + y * 0.5f});
  }
  std::vector<std::int32_t> copy(static_cast<std::size_t>(nv), -1);
  m.uv_triangles = m.triangles;
  for (std::size_t f = 0; f < m.triangleCount(); ++f) {
    // A triangle touching the seam from the last segment (it has a corner with u > 0.5) uses the copies.
    bool wraps = false;
    for (int c = 0; c < 3; ++c) wraps = wraps || m.uvs[static_cast<std::size_t>(m.triangles[f * 3 + c]) * 2] > 0.5f;
    if (!wraps) continue;
    for (int c = 0; c < 3; ++c) {
      const auto v = m.triangles[f * 3 + c];
      const float x = m.positions[v * 3], z = m.positions[v * 3 + 2];
      if (std::abs(z) > 1e-6f || x <= 0.0f) continue;  // only the meridian at s = 0
      if (copy[v] < 0) {
        copy[v] = static_cast<std::int32_t>(m.vertexCount());
        m.positions.insert(m.positions.end(), {m.positions[v * 3], m.positions[v * 3 + 1], m.positions[v * 3 + 2]});
        m.uvs.insert(m.uvs.end(), {1.0f, m.uvs[static_cast<std::size_t>(v) * 2 + 1]});
      }
      m.triangles[f * 3 + c] = copy[v];
      m.uv_triangles[f * 3 + c] = copy[v];
    }
  }
  return m;
}

// A fresh empty folder under the system temp folder, removed when the object dies.
class TempDir {
 public:
  TempDir() {
    std::random_device rd;
    path_ = std::filesystem::temp_directory_path() / ("vdg-test-" + std::to_string(rd()) + std::to_string(rd()));
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  std::string file(const std::string& name) const { return (path_ / name).string(); }
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

inline void writeText(const std::string& path, const std::string& text) {
  std::filesystem::create_directories(std::filesystem::path(path).parent_path());
  std::ofstream(path, std::ios::binary) << text;
}

inline std::string readText(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

}  // namespace vdg::testing
