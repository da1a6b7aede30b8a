// ModelEvaluator: one instance of a ViewDependentModel evaluated frame after frame, touching only
// what changed since the previous frame (after ozz-animation's sampling context: the immutable
// model is shared, the evaluator holds one instance's per-frame state).
//
// Rademacher 99, section 3.2.3: v = base + sum_i w_i (v^i - base). When every key that is active
// now or was active in the previous frame is sparse (ViewDependentModel stores a key sparse when it
// moves at most half of the vertices), the evaluator
//   1. resets the previous frame's keys' moved vertices to the base,
//   2. adds the current keys' weighted deltas (slot order, as ViewDependentModel::blend does), and
//   3. recomputes the normals only at the vertices whose normal those keys can change (the model
//      lists them per key at build: the homes of the one-ring of the moved vertices and the
//      vertices copying them); every other normal is the base's, cached by the model.
// A frame whose keys move a few percent of the vertices then costs what they move. Otherwise
// (a dense key now or before) it evaluates everything, threaded, like ViewDependentModel::evaluate.
// Either way positions() and normals() equal what ViewDependentModel::evaluate would write for the
// same weights (bit for bit: the same float operations in the same order, slot by slot).
// A model with the rbf weight scheme weighs every key at every view: evaluate() then blends every
// key (ViewDependentModel::blendDense) and recomputes every normal, as ViewDependentModel::evaluate
// does, and weights() reports the three heaviest keys (heaviestKeys, view_sphere.h); apply() takes
// three-key weights for any model.
#pragma once

#include <span>
#include <vector>

#include <Eigen/Core>

#include "vdg/viewdep/model.h"

namespace vdg {

class ModelEvaluator {
 public:
  // Allocates #V x 3 positions and normals and starts at the base (weights(): every slot unused,
  // base weight 1; positions the base's, normals the base's). `model` must outlive the evaluator.
  explicit ModelEvaluator(const ViewDependentModel& model);

  // Per-frame contract (model.h): same as ViewDependentModel::evaluate (view, sharpness <= 0 for
  // the model's own, hint -1 or a triangle of model().sphere()); positions and normals are always
  // computed. On a violation it returns false and nothing changed (positions, normals, weights,
  // *hint); no throw, no operator-new allocation (the first call with a large model starts TBB's
  // worker threads, whose set-up is TBB's own).
  [[nodiscard]] bool evaluate(const Eigen::Vector3d& view, double sharpness, int* hint = nullptr);
  // The same with weights given; checked as ViewDependentModel::blend checks them (a slot's key
  // index >= keyCount() or < -1, a non-finite weight).
  [[nodiscard]] bool apply(const ViewWeights& w);

  std::span<const float> positions() const { return positions_; }  // #V x 3
  std::span<const float> normals() const { return normals_; }      // #V x 3, unit or (0, 0, 0)
  const ViewWeights& weights() const { return weights_; }          // of the last successful call (see above)
  const ViewDependentModel& model() const { return *model_; }

 private:
  const ViewDependentModel* model_;
  std::vector<float> positions_, normals_;
  std::vector<float> dense_;  // an rbf model: every key's weight and the base's (keyCount() + 1)
  ViewWeights weights_;
  bool full_frame_ = false;  // the last frame was an rbf frame: every vertex may differ from the base
};

}  // namespace vdg
