// Image-plane deformation tools for making a key deformation from a drawing (Rademacher 99,
// section 3.1.2): the mesh is edited as seen through the key camera, parallel to its image plane.
//
// Every tool takes per-vertex weights w in [0, 1] (see falloff.h: (1 - d/r)^2 for the paper's
// drag) and moves vertex i by w[i] times the full edit. Positions are #V x 3 floats, edited in
// place; weights are #V doubles; vertices with w = 0 are not touched (bit-for-bit).
//
// Camera space here is the key camera's orthonormal frame (cameraFrame(): right, up, back): x along
// right, y along up, depth along the view axis (forward = -back), all in world units. "Depth" is
// the view-axis depth that project() reports. The drag, rotate and scale tools keep every vertex's
// depth exactly (the paper: "the vertices' Z-distances from the camera remain unchanged") for both
// perspective and parallel cameras.
#pragma once

#include <span>

#include <Eigen/Core>

#include "vdg/geom/camera.h"

namespace vdg {

// Drag: vertex i moves by w[i] * (delta.x * right + delta.y * up). `delta` is a world-space vector in
// the image plane, in world units along the camera's right and up axes: the motion of the picked
// vertex (w = 1). To turn a mouse drag in pixels into `delta`, use imagePlaneDelta().
void dragInImagePlane(const Camera& camera, std::span<float> positions, std::span<const double> weights,
                      const Eigen::Vector2d& delta);

// World-space image-plane motion (along right, up) that moves a point at view-axis depth `depth`
// by `pixel_delta` pixels (x right, y down) in a width x height image. For a parallel camera the
// depth is ignored. Exact: project(p + delta) = project(p) + pixel_delta for a point at that depth.
Eigen::Vector2d imagePlaneDelta(const Camera& camera, int width, int height, double depth,
                                const Eigen::Vector2d& pixel_delta);

enum class PushPullMode {
  kAlongRay,   // each vertex slides along its ray from the eye: its pixel does not move (default)
  kAlongAxis,  // each vertex moves along the view axis (same direction for all vertices)
};

// Push (amount > 0, away from the camera) or pull (amount < 0, towards it): vertex i's view-axis
// depth changes by exactly w[i] * amount (world units). For a parallel camera both modes are the
// same. kAlongRay never moves a vertex through the eye: its new depth is kept >= 1e-3 * its depth.
void pushPull(const Camera& camera, std::span<float> positions, std::span<const double> weights, double amount,
              PushPullMode mode = PushPullMode::kAlongRay);

// Rotation in the image plane about the axis through `pivot` along the view axis, by w[i] * angle
// (radians, counter-clockwise as seen in the image). Depths unchanged.
void rotateInImagePlane(const Camera& camera, std::span<float> positions, std::span<const double> weights,
                        const Eigen::Vector3d& pivot, double angle_rad);

// Scale in the image plane about `pivot`: the camera-space x and y offsets from the pivot are
// multiplied by 1 + w[i] * (factor - 1) (per axis). Depths unchanged.
void scaleInImagePlane(const Camera& camera, std::span<float> positions, std::span<const double> weights,
                       const Eigen::Vector3d& pivot, const Eigen::Vector2d& factor);

// Parent 4.10 vertex displacement: vertex i moves by w[i] * offset (a world-space vector).
void displaceVertices(std::span<float> positions, std::span<const double> weights, const Eigen::Vector3d& offset);

}  // namespace vdg
