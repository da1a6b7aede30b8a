// Builds a tiny view-dependent model in memory — a tetrahedron and two keys — against an installed
// vdg, evaluates it and checks the blend (Rademacher 99, section 3.2): at a key's own view the
// model is that key, seen from where no key is it is the base. Exit status 0 when all holds.
#include <cmath>
#include <cstdio>
#include <cstring>
#include <vector>

#include "vdg/version.h"
#include "vdg/viewdep/model.h"

namespace {

constexpr float kPositionTol = 1e-6f;  // float rounding of base + w * (key - base)

bool near(float value, float expected, const char* what) {
  if (std::fabs(value - expected) <= kPositionTol) return true;
  std::fprintf(stderr, "vdg_consumer: %s is %g, expected %g\n", what, value, expected);
  return false;
}

}  // namespace

int main() {
  if (std::strcmp(vdg::versionString(), VDG_VERSION_STRING) != 0 || vdg::kVersionMajor != VDG_VERSION_MAJOR) {
    std::fprintf(stderr, "vdg_consumer: version.h disagrees with itself\n");
    return 1;
  }

  vdg::RawViewDependentModel raw;
  raw.base.positions = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
  raw.base.triangles = {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3};
  vdg::RawKey side;
  side.name = "side";
  side.mesh = raw.base;
  side.mesh.positions[3 * 3 + 2] = 2.0f;  // seen from +X, the top vertex is twice as high
  side.view = Eigen::Vector3d(1, 0, 0);
  vdg::RawKey front;
  front.name = "front";
  front.mesh = raw.base;
  front.mesh.positions[3 * 1 + 0] = 1.5f;  // seen from +Z, the +X vertex reaches further
  front.view = Eigen::Vector3d(0, 0, 1);
  raw.keys = {side, front};

  const vdg::ViewDependentModel model = vdg::ViewDependentModel::build(raw);
  std::vector<float> positions(3 * model.vertexCount());
  std::vector<float> normals(positions.size());

  bool ok = true;
  model.evaluate(Eigen::Vector3d(1, 0, 0), 0.0, positions, normals);
  ok &= near(positions[3 * 3 + 2], 2.0f, "top vertex z seen from the side key");
  ok &= near(positions[3 * 1 + 0], 1.0f, "+X vertex x seen from the side key");
  model.evaluate(Eigen::Vector3d(0, 0, 1), 0.0, positions, normals);
  ok &= near(positions[3 * 1 + 0], 1.5f, "+X vertex x seen from the front key");
  model.evaluate(Eigen::Vector3d(-1, -1, -1), 0.0, positions, normals);  // far from both keys
  ok &= near(positions[3 * 3 + 2], 1.0f, "top vertex z seen from behind");
  ok &= near(positions[3 * 1 + 0], 1.0f, "+X vertex x seen from behind");
  if (!ok) return 1;
  std::printf("vdg_consumer: vdg %s, %zu keys, blend checked\n", vdg::versionString(), model.keyCount());
  return 0;
}
