// The orbiting camera of `vdg render` and `vdg bake`: --orbit N frames for one turn around the
// model, starting at --azimuth, at --elevation and --distance (default: fit the model), with a
// vertical field of view --fov, and an optional --frames A-B range. Frame f's camera depends only
// on f and the options (docs/render.md), so both commands see the same camera at the same frame.
#pragma once

#include <algorithm>
#include <span>
#include <string>

#include <Eigen/Core>

#include "cli.h"
#include "vdg/geom/camera.h"
#include "vdg/geom/tri_mesh.h"
#include "vdg/render/model_renderer.h"

namespace vdg::cli {

struct OrbitOptions {
  // Option ranges (checked at parse time by the validators in cli.h; see docs/render.md).
  static constexpr long kMaxOrbitFrames = 1000000;
  // Beyond these the camera frame cannot be computed in double precision (the eye-target distance
  // overflows, or a near-zero field of view fits the model at an overflowing distance).
  static constexpr double kMaxDistance = 1e15;
  static constexpr double kMinFovDeg = 0.01, kMaxFovDeg = 179.99;

  std::string frames;
  int orbit = 1;
  double azimuth = 0.0, elevation = 15.0, distance = 0.0, fov = 30.0;

  void add(CLI::App& sub) {
    sub.add_option("--orbit", orbit, "Frames for one turn of the camera around the model (default 1)")
        ->check(wholeNumber(1, kMaxOrbitFrames));
    sub.add_option("--azimuth", azimuth, "Camera azimuth of frame 0 in degrees, from +Z towards +X (default 0)")
        ->check(finiteNumber());
    sub.add_option("--elevation", elevation, "Camera elevation in degrees (default 15)")->check(openRange(-90.0, 90.0));
    sub.add_option("--distance", distance, "Camera distance from the model centre (default: fit the model)")
        ->check(positiveNumber(kMaxDistance));
    sub.add_option("--fov", fov, "Vertical field of view in degrees (default 30)")
        ->check(numberIn({kMinFovDeg, End::kClosed, kMaxFovDeg, End::kClosed}));
  }

  // The frames asked for: --frames A-B, or the whole orbit. Throws UsageError for a range outside it.
  FrameRange range() const {
    FrameRange r{0, orbit - 1};
    if (!frames.empty()) {
      r = parseFrameRange(frames, "--frames");
      if (r.last >= orbit)
        throw UsageError("--frames: expected frames within 0-" + std::to_string(orbit - 1) + " (--orbit " +
                         std::to_string(orbit) + "), got " + quotedText(frames));
    }
    return r;
  }

  // Radius of the bounding sphere of `mesh` about `center` (at least 1e-6).
  static double radiusAbout(std::span<const float> positions, const Eigen::Vector3d& center) {
    double radius = 0.0;
    for (std::size_t v = 0; v < positions.size() / 3; ++v)
      radius = std::max(
          radius, (Eigen::Vector3d(positions[v * 3], positions[v * 3 + 1], positions[v * 3 + 2]) - center).norm());
    return std::max(radius, 1e-6);
  }

  // The camera distance: --distance, or the distance that fits a sphere of `radius` in the view.
  double cameraDistance(double radius, double aspect) const {
    return distance > 0.0 ? distance : render::fitDistance(radius, fov, aspect);
  }

  // The camera of frame `f` looking at `center` from `camera_distance`.
  Camera camera(int f, const Eigen::Vector3d& center, double camera_distance) const {
    return render::orbitCamera(center, camera_distance, azimuth + 360.0 * f / orbit, elevation, fov);
  }
};

}  // namespace vdg::cli
