// Sampling a view-dependent model along a camera path: at each sample, the weights the model gives
// the view from that camera's eye (Rademacher 99, section 3.2; for an animated model, section 4, the
// weight of each key view times its key frames' time coefficients), and the camera itself as a
// translation and a rotation. What a file format (vdg's glTF bake, vdg/io/gltf_export.h) plays back
// as morph weights and an animated camera.
#pragma once

#include <span>
#include <vector>

#include "vdg/geom/camera.h"
#include "vdg/viewdep/animated_model.h"
#include "vdg/viewdep/model.h"

namespace vdg {

// A sampled camera path. Sample s is at time s / fps.
struct CameraPathBake {
  std::vector<float> times;    // seconds, strictly increasing, at least one
  std::vector<float> weights;  // times.size() x #targets (row per time)
  // The camera: a perspective camera looking down its own -Z with +Y up (empty translations: none).
  std::vector<float> translations;    // times.size() x 3 (the eye)
  std::vector<float> rotations;       // times.size() x 4, unit quaternions x y z w
  double yfov_rad = 0.5;              // in (0, pi)
  double aspect = 1.0;                // width / height, > 0
  double znear = 0.01, zfar = 100.0;  // 0 < znear < zfar: the model's bounding sphere from every camera
  std::vector<int> frames;            // animated models: the animation frame of each sample; else empty
};

// Bakes a camera path: for each camera (all perspective, the same field of view; sample i at time
// i / fps, plus, when `close_loop`, one more sample at cameras.size() / fps equal to sample 0, so a
// looping viewer plays the cycle without a seam), the model's weights for the view from that
// camera's eye (viewFromEye; `sharpness` <= 0: the model's own), one per key in key order, and the
// camera's translation and rotation. Consecutive rotations are given the same hemisphere (q or -q),
// so a slerp never turns the long way. `aspect` = width / height. Throws vdg::Error "bake: ..." for
// no cameras, an orthographic camera, a degenerate camera frame, an eye at the model centre, fps or
// aspect not finite or <= 0.
CameraPathBake bakeCameraPath(const ViewDependentModel& model, std::span<const Camera> cameras, double fps,
                              double aspect, double sharpness, bool close_loop);

// The same over an animated model: output sample s (s = 0 .. cameras.size() - 1, plus the closing
// sample) shows animation frame F = (first_frame + s) mod N when the model loops, min(first_frame +
// s, N - 1) when not (frames[s]). One weight per key (keyIndex(view, key frame) order): the weight
// of the key of (view i, key frame j) is w_i(view of the camera) * c_ij(F) (timeCoefficients), so
// base(F) + sum of weight x offset is the model at F. With `base_frame_targets`, frames 1..N-1 of
// the base follow the keys as targets of their own, and base frame F's gets weight 1. Throws as
// bakeCameraPath.
CameraPathBake bakeAnimatedCameraPath(const AnimatedViewDependentModel& model, std::span<const Camera> cameras,
                                      int first_frame, double fps, double aspect, double sharpness, bool close_loop,
                                      bool base_frame_targets);

}  // namespace vdg
