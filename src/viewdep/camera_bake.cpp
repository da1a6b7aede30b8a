#include "vdg/viewdep/camera_bake.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <string>

#include "vdg/geom/error.h"
#include "vdg/geom/normalize.h"

namespace vdg {
namespace {

// The camera half of a bake, shared by static and animated models: times, the camera node's
// translations and rotations, clip planes. `fill(s, camera, weights_row)` writes sample s's
// weights (target_count floats, zeroed) for `camera`; it throws for a camera it cannot weigh.
template <class Fill>
CameraPathBake bakeCameras(std::span<const Camera> cameras, double fps, double aspect, bool close_loop,
                           const Eigen::Vector3d& center, double radius, std::size_t target_count, Fill fill) {
  if (cameras.empty()) throw Error("bake: no cameras");
  if (!std::isfinite(fps) || fps <= 0.0) throw Error("bake: the frame rate must be finite and > 0");
  if (!std::isfinite(aspect) || aspect <= 0.0) throw Error("bake: the aspect ratio must be finite and > 0");
  CameraPathBake bake;
  const std::size_t samples = cameras.size() + (close_loop ? 1 : 0);
  bake.times.resize(samples);
  bake.weights.assign(samples * target_count, 0.0f);
  bake.translations.resize(samples * 3);
  bake.rotations.resize(samples * 4);
  double near_distance = std::numeric_limits<double>::infinity(), far_distance = 0.0;
  Eigen::Quaterniond previous = Eigen::Quaterniond::Identity();
  for (std::size_t s = 0; s < samples; ++s) {
    const std::size_t i = s % cameras.size();
    const Camera& camera = cameras[i];
    const std::string label = "bake: camera " + std::to_string(i);
    if (camera.isOrtho()) throw Error(label + ": glTF bakes perspective cameras only");
    if (camera.fov_deg != cameras[0].fov_deg) throw Error(label + ": every camera must have the same field of view");
    fill(s, camera, bake.weights.data() + s * target_count);
    const CameraFrame frame = cameraFrame(camera);  // throws for a degenerate camera
    Eigen::Matrix3d rotation;
    rotation << frame.right, frame.up, frame.back;
    Eigen::Quaterniond q(rotation);
    q.normalize();
    if (s > 0 && q.dot(previous) < 0.0) q.coeffs() = -q.coeffs();
    previous = q;
    for (int c = 0; c < 3; ++c) bake.translations[s * 3 + c] = static_cast<float>(camera.eye[c]);
    bake.rotations[s * 4 + 0] = static_cast<float>(q.x());
    bake.rotations[s * 4 + 1] = static_cast<float>(q.y());
    bake.rotations[s * 4 + 2] = static_cast<float>(q.z());
    bake.rotations[s * 4 + 3] = static_cast<float>(q.w());
    bake.times[s] = static_cast<float>(static_cast<double>(s) / fps);
    const double d = (camera.eye - center).norm();
    near_distance = std::min(near_distance, d);
    far_distance = std::max(far_distance, d);
  }
  // The clip planes hold the model's bounding sphere from every camera (a camera inside it gets a
  // near plane at a thousandth of its distance).
  bake.znear = std::max(near_distance - 1.5 * radius, 1e-3 * near_distance);
  bake.zfar = far_distance + 1.5 * radius;
  if (!(bake.znear > 0.0)) bake.znear = 1e-6;
  if (!(bake.zfar > bake.znear)) bake.zfar = 2.0 * bake.znear;
  bake.yfov_rad = cameras[0].fov_deg * std::numbers::pi / 180.0;
  bake.aspect = aspect;
  return bake;
}

[[noreturn]] void noView(std::size_t camera) {
  throw Error("bake: camera " + std::to_string(camera) +
              ": no view direction (the eye is at the model centre, or the sharpness is not > 0)");
}

}  // namespace

CameraPathBake bakeCameraPath(const ViewDependentModel& model, std::span<const Camera> cameras, double fps,
                              double aspect, double sharpness, bool close_loop) {
  model.requireNoParts("the camera-path bake (vdg bake)");
  model.requireViewDirections("the camera bake (vdg bake; its glTF weighs view directions)");
  const std::size_t keys = model.keyCount();
  const bool rbf = model.sphere().settings().scheme == WeightScheme::Rbf;
  std::vector<float> dense(rbf ? keys + 1 : 0);  // the rbf scheme weighs every key
  // The clip planes hold what the model draws: the base and every key (extentRadius()).
  return bakeCameras(cameras, fps, aspect, close_loop, model.center(), model.extentRadius(), keys,
                     [&](std::size_t s, const Camera& camera, float* weights) {
                       const Eigen::Vector3d view = model.viewFromEye(camera.eye);
                       if (rbf) {
                         if (view.isZero() || !model.denseWeights(view, sharpness, dense)) noView(s % cameras.size());
                         for (std::size_t k = 0; k < keys; ++k) weights[k] += dense[k];
                         return;
                       }
                       ViewWeights w;
                       if (view.isZero() || !model.weights(view, sharpness, w)) noView(s % cameras.size());
                       for (int slot = 0; slot < 3; ++slot)
                         if (w.key[slot] >= 0) weights[static_cast<std::size_t>(w.key[slot])] += w.weight[slot];
                     });
}

CameraPathBake bakeAnimatedCameraPath(const AnimatedViewDependentModel& model, std::span<const Camera> cameras,
                                      int first_frame, double fps, double aspect, double sharpness, bool close_loop,
                                      bool base_frame_targets) {
  const int n = model.frameCount();
  const auto animationFrame = [&](std::size_t s) {
    const long f = static_cast<long>(first_frame) + static_cast<long>(s);
    return model.loop() ? static_cast<int>(f % n) : static_cast<int>(std::min<long>(f, n - 1));
  };
  std::size_t keys = 0;
  for (std::size_t i = 0; i < model.viewCount(); ++i) keys += model.keyFrames(i).size();
  const std::size_t target_count = keys + (base_frame_targets ? static_cast<std::size_t>(n - 1) : 0);
  const double radius = model.extentRadius();  // every frame of the base and every view's pose on it
  std::vector<double> coefficients;
  CameraPathBake bake =
      bakeCameras(cameras, fps, aspect, close_loop, model.center(), radius, target_count,
                  [&](std::size_t s, const Camera& camera, float* weights) {
                    const std::optional<Eigen::Vector3d> view = normalizedOrNone(camera.eye - model.center());
                    ViewWeights w;
                    if (!view || !model.weights(*view, sharpness, w)) noView(s % cameras.size());
                    const int frame = animationFrame(s);
                    for (int slot = 0; slot < 3; ++slot) {
                      if (w.key[slot] < 0) continue;
                      const auto v = static_cast<std::size_t>(w.key[slot]);
                      coefficients.assign(model.keyFrames(v).size(), 0.0);
                      if (!model.timeCoefficients(v, frame, coefficients))
                        throw Error("bake: time coefficients (internal error)");
                      for (std::size_t j = 0; j < coefficients.size(); ++j)
                        weights[model.keyIndex(v, j)] += static_cast<float>(w.weight[slot] * coefficients[j]);
                    }
                    if (base_frame_targets && frame > 0) weights[keys + static_cast<std::size_t>(frame) - 1] = 1.0f;
                  });
  for (std::size_t s = 0; s < bake.times.size(); ++s) bake.frames.push_back(animationFrame(s));
  return bake;
}

}  // namespace vdg
