// Continuity figures of a model's blend along camera paths (see vdg/viewdep/continuity.h).
#include "vdg/viewdep/continuity.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "vdg/geom/error.h"

namespace vdg {
namespace {

using Eigen::Vector3d;

// Unit normals of the great circles to walk: a Fibonacci lattice (evenly spread), then one circle
// through each key view (its normal perpendicular to the key and tilted off the coordinate axes,
// so that the circle crosses the triangulation rather than running along a symmetry plane).
std::vector<Vector3d> circleNormals(const ViewDependentModel& model, const ContinuitySettings& s) {
  std::vector<Vector3d> normals;
  const double golden = std::numbers::pi * (3.0 - std::sqrt(5.0));
  for (int i = 0; i < s.circles; ++i) {
    const double y = 1.0 - (i + 0.5) * 2.0 / s.circles;
    const double r = std::sqrt(std::max(0.0, 1.0 - y * y));
    normals.emplace_back(r * std::cos(golden * i), y, r * std::sin(golden * i));
  }
  if (s.through_keys) {
    const Vector3d tilt = Vector3d(0.31, 0.83, 0.47).normalized();
    for (std::size_t k = 0; k < model.keyCount(); ++k) {
      Vector3d n = model.keyView(k).cross(tilt);
      if (n.norm() < 1e-6) n = model.keyView(k).cross(Vector3d::UnitX());
      normals.push_back(n.normalized());
    }
  }
  return normals;
}

// Dense weights over the keys and the base.
void denseWeights(const ViewWeights& w, std::vector<double>& out) {
  std::fill(out.begin(), out.end(), 0.0);
  for (int k = 0; k < 3; ++k)
    if (w.key[k] >= 0) out[static_cast<std::size_t>(w.key[k])] += w.weight[k];
  out.back() += w.base;
}

// Rolling state of one path: the last three samples' positions and weights.
struct PathState {
  std::vector<float> x[3];
  std::vector<double> w[3];
  std::vector<float> dense;  // the rbf scheme's weights of the newest sample
  int filled = 0;
};

void walkCircle(const ViewDependentModel& model, const Vector3d& normal, const ContinuitySettings& s, PathState& state,
                ContinuityReport& report) {
  const Vector3d a = normal.unitOrthogonal(), b = normal.cross(a);
  const int steps = static_cast<int>(std::ceil(360.0 / s.step_deg));
  const double step_rad = s.step_deg * std::numbers::pi / 180.0;
  const double scale = 1.0 / (s.step_deg * report.size);
  const bool rbf = model.sphere().settings().scheme == WeightScheme::Rbf;
  state.filled = 0;
  int hint = -1;
  for (int n = 0; n <= steps + 1; ++n) {
    const double angle = n * step_rad;
    const Vector3d view = std::cos(angle) * a + std::sin(angle) * b;
    std::rotate(std::begin(state.x), std::begin(state.x) + 2, std::end(state.x));  // newest into x[0]
    std::rotate(std::begin(state.w), std::begin(state.w) + 2, std::end(state.w));
    if (rbf) {  // weights over every key (view_sphere.h, "Weight schemes")
      if (!model.denseWeights(view, s.sharpness, state.dense, &hint) || !model.blendDense(state.dense, state.x[0]))
        throw Error("continuity: the model refused a view on its path (internal error)");
      std::copy(state.dense.begin(), state.dense.end(), state.w[0].begin());
    } else {
      ViewWeights w;
      if (!model.weights(view, s.sharpness, w, &hint) || !model.blend(w, state.x[0]))
        throw Error("continuity: the model refused a view on its path (internal error)");
      denseWeights(w, state.w[0]);
    }
    ++report.samples;
    state.filled = std::min(state.filled + 1, 3);
    if (state.filled < 2) continue;
    double speed = 0.0, weight_speed = 0.0;
    for (std::size_t i = 0; i < state.x[0].size(); i += 3) {
      const double dx = state.x[0][i] - state.x[1][i], dy = state.x[0][i + 1] - state.x[1][i + 1],
                   dz = state.x[0][i + 2] - state.x[1][i + 2];
      speed = std::max(speed, dx * dx + dy * dy + dz * dz);
    }
    for (std::size_t k = 0; k < state.w[0].size(); ++k) weight_speed += std::abs(state.w[0][k] - state.w[1][k]);
    report.popping = std::max(report.popping, std::sqrt(speed) * scale);
    report.weight_speed = std::max(report.weight_speed, weight_speed / s.step_deg);
    if (state.filled < 3) continue;
    double jump = 0.0, weight_jump = 0.0;
    for (std::size_t i = 0; i < state.x[0].size(); ++i) {
      const double d = static_cast<double>(state.x[0][i]) - 2.0 * state.x[1][i] + state.x[2][i];
      jump = std::max(jump, std::abs(d));
    }
    for (std::size_t k = 0; k < state.w[0].size(); ++k)
      weight_jump += std::abs(state.w[0][k] - 2.0 * state.w[1][k] + state.w[2][k]);
    report.velocity_jump = std::max(report.velocity_jump, jump * scale);
    report.weight_jump = std::max(report.weight_jump, weight_jump / s.step_deg);
  }
}

}  // namespace

ContinuityReport measureContinuity(const ViewDependentModel& model, const ContinuitySettings& s) {
  model.requireNoParts("the continuity figures (vdg weights --continuity)");
  model.requireViewDirections("the continuity measure (it walks great circles of view directions)");
  if (!(s.step_deg > 0.0 && s.step_deg <= 10.0))
    throw Error("continuity: the step must be in (0, 10] degrees, got " + std::to_string(s.step_deg));
  if (s.circles < 1 || s.circles > 10000)
    throw Error("continuity: the number of circles must be in [1, 10000], got " + std::to_string(s.circles));
  if (!std::isfinite(s.sharpness)) throw Error("continuity: the sharpness must be finite");
  ContinuityReport report;
  report.size = 2.0 * model.extentRadius();
  PathState state;
  for (int i = 0; i < 3; ++i) {
    state.x[i].assign(3 * model.vertexCount(), 0.0f);
    state.w[i].assign(model.keyCount() + 1, 0.0);
  }
  state.dense.assign(model.keyCount() + 1, 0.0f);
  for (const Vector3d& normal : circleNormals(model, s)) {
    walkCircle(model, normal, s, state, report);
    ++report.paths;
  }
  return report;
}

}  // namespace vdg
