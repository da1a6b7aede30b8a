// Camera navigation of the editor's viewport (vdg studio): the moves an artist makes to lay the
// model over a drawing (Rademacher 99, 3.1.1: "the user ... adjusts the camera until the model
// matches the drawing as closely as possible"). Pure functions of a vdg::Camera; every result has
// eye != target and up orthogonal to the view axis (unit length), so it is always a valid camera.
#pragma once

#include <Eigen/Core>

#include "vdg/geom/camera.h"

namespace vdg::studio {

// Turntable orbit about the target: yaw about the world's +Y axis, then pitch about the camera's
// right axis, clamped so the view never passes the poles (|elevation| <= 89 degrees). The
// eye-target distance is kept.
Camera orbit(const Camera& camera, double yaw_deg, double pitch_deg);
// Moves eye and target together in the image plane so that points at the target's depth follow
// the mouse by `pixels` (x right, y down) in a width x height image.
Camera pan(const Camera& camera, const Eigen::Vector2d& pixels, int width, int height);
// Eye-target distance x factor (> 0); a parallel camera scales its ortho height instead.
Camera dolly(const Camera& camera, double factor);
// Rotation about the view axis by `deg`, counter-clockwise as seen in the image.
Camera roll(const Camera& camera, double deg);
// Keeps the view direction and up, and moves the eye (perspective) or sets the ortho height so
// that the sphere around the box [lo, hi] fills the image of aspect width / height with a margin.
Camera frameBox(const Camera& camera, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, double aspect);
// A camera orthonormalised as above: up made orthogonal to the view axis (the world's +Y, then
// +Z, when it is parallel to it) and of unit length.
Camera normalizedCamera(const Camera& camera);

}  // namespace vdg::studio
