// A program that reads a model and evaluates it, linked against vdg::io_model alone (see
// CMakeLists.txt here: neither OpenVDB nor CGAL, GMP or MPFR may reach its link). It writes a
// tetrahedron, a key that raises its top vertex and a manifest naming both into a scratch folder,
// opens the manifest with openInput and checks the blend at the key's view (Rademacher 99,
// section 3.2). Exit status 0 when all holds.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include <unistd.h>

#include "vdg/io/manifest.h"
#include "vdg/io/model.h"
#include "vdg/io/obj.h"

namespace {

constexpr float kPositionTol = 1e-6f;  // float rounding of base + w * (key - base)

}  // namespace

int main() {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / ("vdg-model-consumer-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  vdg::TriMesh base;
  base.positions = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
  base.triangles = {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3};
  vdg::TriMesh up = base;
  up.positions[3 * 3 + 2] = 2.0f;  // seen from +Z, the top vertex is twice as high
  vdg::writeObj((dir / "base.obj").string(), base);
  vdg::writeObj((dir / "up.obj").string(), up);
  vdg::RawViewDependentModel raw;
  raw.base_path = "base.obj";
  raw.base = base;
  vdg::RawKey key;
  key.name = "up";
  key.mesh_path = "up.obj";
  key.mesh = up;
  key.view = Eigen::Vector3d(0, 0, 1);
  raw.keys = {key};
  const std::string manifest = (dir / "m.vdg.json").string();
  vdg::saveManifest(manifest, raw);

  const vdg::OpenedInput input = vdg::openInput(manifest);
  bool ok = input.kind == vdg::InputKind::kModel && input.format == vdg::InputFormat::kManifest && input.model;
  if (ok) {
    std::vector<float> positions(3 * input.model->vertexCount());
    ok = input.model->evaluate(Eigen::Vector3d(0, 0, 1), 0.0, positions) &&
         std::fabs(positions[3 * 3 + 2] - 2.0f) <= kPositionTol;
  }
  fs::remove_all(dir);
  if (!ok) {
    std::fprintf(stderr, "vdg_model_consumer: the manifest did not open as the model written\n");
    return 1;
  }
  std::printf("vdg_model_consumer: opened %s (a %s) and evaluated it\n", manifest.c_str(),
              vdg::inputKindName(input.kind));
  return 0;
}
