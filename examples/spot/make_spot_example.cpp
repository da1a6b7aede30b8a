// Builds the spot example: key deformations of Keenan Crane's cow "Spot" (public domain, see
// LICENSE-spot.txt), in the spirit of a model sheet where each drawing exaggerates what that view
// shows best: ears flared from the front, a longer snout and tail from the side, a rounder rump
// from behind, horns raised from above.
//
// Usage: vdg_make_spot_example SPOT.obj OUT_DIR
// Writes OUT_DIR/keys/*.obj, OUT_DIR/spot.vdg.json and OUT_DIR/spot-dolly.vdg.json (keys at
// distances, docs/weights.md: the same five keys as wide shots, plus a front close-up). Deterministic: the same input
// gives byte-identical output (tests/examples checks the committed files against it).
//
// Each edit is the paper's drag tool (Rademacher 99, 3.1.2) in 3D: the vertices within distance r
// of a picked point move by delta * (1 - d/r)^2; or the same falloff applied to a scaling.
#include <array>
#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <string>
#include <vector>

#include "vdg/geom/error.h"
#include "vdg/io/manifest.h"
#include "vdg/io/obj.h"
#include "vdg/viewdep/model.h"

namespace {

using Vec = std::array<double, 3>;

double falloff(const vdg::TriMesh& mesh, std::size_t v, const Vec& centre, double radius) {
  const double dx = mesh.positions[3 * v] - centre[0], dy = mesh.positions[3 * v + 1] - centre[1],
               dz = mesh.positions[3 * v + 2] - centre[2];
  const double d = std::sqrt(dx * dx + dy * dy + dz * dz);
  if (d >= radius) return 0.0;
  const double s = 1.0 - d / radius;
  return s * s;
}

void drag(vdg::TriMesh& mesh, const Vec& centre, double radius, const Vec& delta) {
  const vdg::TriMesh before = mesh;
  for (std::size_t v = 0; v < mesh.vertexCount(); ++v) {
    const double f = falloff(before, v, centre, radius);
    for (int c = 0; c < 3; ++c) mesh.positions[3 * v + c] += static_cast<float>(f * delta[c]);
  }
}

// Scales about `centre` by factor (per axis), blended in with the same falloff.
void swell(vdg::TriMesh& mesh, const Vec& centre, double radius, const Vec& factor) {
  const vdg::TriMesh before = mesh;
  for (std::size_t v = 0; v < mesh.vertexCount(); ++v) {
    const double f = falloff(before, v, centre, radius);
    for (int c = 0; c < 3; ++c) {
      const double p = before.positions[3 * v + c];
      mesh.positions[3 * v + c] = static_cast<float>(p + f * (factor[c] - 1.0) * (p - centre[c]));
    }
  }
}

struct KeySpec {
  std::string name;
  Vec view;
};

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: %s SPOT.obj OUT_DIR\n", argv[0]);
    return 2;
  }
  try {
    const std::string out_dir = argv[2];
    std::filesystem::create_directories(out_dir + "/keys");
    const vdg::TriMesh base = vdg::readObj(argv[1]);
    // Spot faces -Z (snout at z = -0.67), stands on -Y, horns at y = 0.95, ears at x = +-0.47.
    const Vec left_ear{-0.47, 0.71, -0.20}, right_ear{0.47, 0.71, -0.20};
    const Vec left_horn{-0.177, 0.95, -0.26}, right_horn{0.177, 0.95, -0.26};

    vdg::RawViewDependentModel model;
    model.base_path = "spot.obj";
    model.base = base;
    auto add_key = [&](const std::string& name, const Vec& view, auto&& edit) {
      vdg::RawKey key;
      key.name = name;
      key.mesh_path = "keys/" + name + ".obj";
      key.mesh = base;
      edit(key.mesh);
      key.view = Eigen::Vector3d(view[0], view[1], view[2]);
      vdg::writeObj(out_dir + "/" + key.mesh_path, key.mesh, "spot key '" + name + "' (made by make_spot_example)");
      model.keys.push_back(std::move(key));
    };
    add_key("front", {0.0, 0.15, -1.0}, [&](vdg::TriMesh& m) {  // ears flare out and up
      drag(m, left_ear, 0.30, {-0.20, 0.12, 0.0});
      drag(m, right_ear, 0.30, {0.20, 0.12, 0.0});
      drag(m, left_horn, 0.14, {-0.04, 0.10, 0.0});
      drag(m, right_horn, 0.14, {0.04, 0.10, 0.0});
    });
    add_key("left", {-1.0, 0.10, 0.0}, [&](vdg::TriMesh& m) {  // longer snout, perkier tail
      drag(m, {0.0, 0.30, -0.669}, 0.38, {0.0, -0.06, -0.22});
      drag(m, {0.0, -0.08, 1.049}, 0.30, {0.0, 0.14, 0.16});
    });
    add_key("right", {1.0, 0.10, 0.0}, [&](vdg::TriMesh& m) {  // horns swept back, ears droop
      drag(m, left_horn, 0.20, {0.0, 0.06, 0.22});
      drag(m, right_horn, 0.20, {0.0, 0.06, 0.22});
      drag(m, left_ear, 0.25, {-0.05, -0.14, 0.0});
      drag(m, right_ear, 0.25, {0.05, -0.14, 0.0});
    });
    add_key("back", {0.0, 0.20, 1.0}, [&](vdg::TriMesh& m) {  // a rounder, wider rump
      swell(m, {0.0, 0.05, 0.65}, 0.55, {1.30, 1.12, 1.05});
    });
    add_key("top", {0.0, 1.0, 0.15}, [&](vdg::TriMesh& m) {  // tall horns, wide back
      drag(m, left_horn, 0.16, {-0.03, 0.16, 0.0});
      drag(m, right_horn, 0.16, {0.03, 0.16, 0.0});
      swell(m, {0.0, 0.35, 0.35}, 0.60, {1.22, 1.0, 1.0});
    });
    model.validate();
    vdg::saveManifest(out_dir + "/spot.vdg.json", model);
    // Keys at distances: the five keys drawn from wide shots kWideDistance from the centre, and a
    // front close-up at kCloseDistance. A close camera enlarges the snout and shrinks the ears
    // (the dolly's perspective exaggeration); the close-up drawing tones the snout down and keeps
    // the front key's flared ears a little larger, so the dolly in reads as the same cow.
    constexpr double kWideDistance = 4.0, kCloseDistance = 1.6;
    vdg::RawViewDependentModel dolly = model;
    dolly.comment =
        "Spot with keys at distances (docs/weights.md, 'Keys at distances'): the keys of spot.vdg.json as wide shots, "
        "and a front close-up with its own distortion; weighed by the eye position";
    dolly.key_space.space = vdg::WeightSpace::Positions;
    const Eigen::Vector3d centre = model.resolvedCenter();
    dolly.center = centre;
    for (vdg::RawKey& key : dolly.keys) key.eye = centre + kWideDistance * key.view.normalized();
    add_key("front-close", {0.0, 0.15, -1.0}, [&](vdg::TriMesh& m) {  // snout pulled in, ears flared
      drag(m, {0.0, 0.30, -0.669}, 0.40, {0.0, 0.0, 0.14});
      drag(m, left_ear, 0.30, {-0.28, 0.16, 0.0});
      drag(m, right_ear, 0.30, {0.28, 0.16, 0.0});
    });
    vdg::RawKey close = model.keys.back();
    close.eye = centre + kCloseDistance * close.view.normalized();
    dolly.keys.push_back(std::move(close));
    dolly.resolveViews();
    dolly.validate();
    vdg::saveManifest(out_dir + "/spot-dolly.vdg.json", dolly);
    std::printf("wrote %s/spot.vdg.json, spot-dolly.vdg.json and %zu keys\n", out_dir.c_str(), dolly.keys.size());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "make_spot_example: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
