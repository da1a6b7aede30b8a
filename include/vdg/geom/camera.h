// Camera — a pinhole (perspective) or parallel (orthographic) camera, as used for key viewpoints,
// render cameras and drawing alignment.
//
// Conventions: right-handed, Y up; the camera looks from `eye` towards `target`; `up` need not be
// orthogonal to the view axis (it is orthogonalised) but must not be parallel to it.
// Perspective when ortho_height == 0: vertical field of view fov_deg in (0, 180).
// Parallel when ortho_height > 0: the visible image height in world units.
// Image coordinates are pixels with (0, 0) at the top-left corner, x right, y down, for an image of
// width x height pixels; aspect = width / height.
#pragma once

#include <Eigen/Core>

namespace vdg {

struct Camera {
  Eigen::Vector3d eye{0, 0, 5};
  Eigen::Vector3d target{0, 0, 0};
  Eigen::Vector3d up{0, 1, 0};
  double fov_deg = 40.0;
  double ortho_height = 0.0;

  bool isOrtho() const { return ortho_height > 0.0; }
};

// Orthonormal camera frame: right, up, and back (= -forward), as the columns of the rotation.
struct CameraFrame {
  Eigen::Vector3d right, up, back;
};
// Throws vdg::Error when eye == target, up is zero or parallel to the view axis, or a vector is
// not finite (or eye - target overflows). Any finite magnitudes work otherwise (robust
// normalisation, vdg/geom/normalize.h): an eye 1e200 away still gives the right frame.
CameraFrame cameraFrame(const Camera& camera);

// World -> camera (OpenGL convention: camera looks down -Z).
Eigen::Matrix4d viewMatrix(const Camera& camera);
// Camera -> clip space (OpenGL convention, depth in [-1, 1]).
Eigen::Matrix4d projectionMatrix(const Camera& camera, double aspect, double z_near, double z_far);

// World point -> pixel (x right, y down) and depth along the view axis (positive in front).
struct Projected {
  Eigen::Vector2d pixel;
  double depth;
};
Projected project(const Camera& camera, int width, int height, const Eigen::Vector3d& world);
// Pixel and view-axis depth -> world point. Inverse of project().
Eigen::Vector3d unproject(const Camera& camera, int width, int height, const Eigen::Vector2d& pixel, double depth);

}  // namespace vdg
