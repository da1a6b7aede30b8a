// Small meshes and temporary folders for tests (header-only; tests link it as they like).
#pragma once

#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>

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
