// Aligning a key camera to a drawing from point correspondences (Rademacher 99, section 3.1.1 and
// its future work: "non-linear methods might prove useful").
//
// Input: N >= 6 pairs of a 3D point X_k (model space, usually on the base mesh) and the pixel x_k
// where the drawing shows it (x right, y down, (0, 0) the top-left corner of a width x height image).
// Output: the vdg::Camera that minimises the reprojection error sum_k |project(X_k) - x_k|^2.
//
// The camera model is what vdg::Camera can represent: square pixels, principal point at the image
// centre, no skew or lens distortion, and either
//   perspective  7 parameters: eye (3), rotation (3), vertical field of view; or
//   parallel     6 parameters: rotation (3), image-plane position of the eye (2), ortho height;
//                the eye's distance along the view axis is not observable and is set so that the
//                target is the points' centroid (the eye lies 2 x their radius + 1 behind it).
// Method: (1) the direct linear transform (Hartley-normalised, SVD) for the 3x4 projective matrix
// (perspective) or the 2x4 affine matrix (parallel); (2) decomposition: RQ of the left 3x3 block
// into K R, eye = -M^-1 p4, focal length = mean of K's diagonal (skew and principal offset are
// dropped); for the affine matrix, the nearest scaled orthonormal rows; (3) Levenberg-Marquardt on
// the reprojection error over the parameters above (rotation as an incremental axis-angle, focal
// length / ortho height as a logarithm). With exact correspondences the camera is recovered to
// about 1e-9 relative.
#pragma once

#include <span>
#include <vector>

#include <Eigen/Core>

#include "vdg/geom/camera.h"

namespace vdg {

struct AlignOptions {
  bool ortho = false;        // solve a parallel camera
  int max_iterations = 200;  // Levenberg-Marquardt iterations
};

struct AlignResult {
  Camera camera;
  double rms_px = 0;      // root-mean-square reprojection error after refinement, pixels
  double max_px = 0;      // largest reprojection error, pixels
  double dlt_rms_px = 0;  // the same for the decomposed DLT camera before refinement
  int iterations = 0;
};

// Throws vdg::Error for fewer than 6 pairs, a non-positive image size, non-finite input, all
// points collinear or coplanar ("degenerate"), or points that end up behind the camera.
AlignResult alignCamera(std::span<const Eigen::Vector3d> points, std::span<const Eigen::Vector2d> pixels, int width,
                        int height, const AlignOptions& options = {});

// Reprojection errors |project(camera, X_k) - x_k| in pixels, #N.
std::vector<double> reprojectionErrors(const Camera& camera, std::span<const Eigen::Vector3d> points,
                                       std::span<const Eigen::Vector2d> pixels, int width, int height);

}  // namespace vdg
