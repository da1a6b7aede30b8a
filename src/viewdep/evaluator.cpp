// ModelEvaluator: incremental evaluation of sparse keys (Rademacher 99, section 3.2.3; see
// evaluator.h).
#include "vdg/viewdep/evaluator.h"

#include <cstring>

#include "vdg/geom/parallel.h"

namespace vdg {

namespace {

bool active(const ViewWeights& w, int slot) { return w.key[slot] >= 0 && w.weight[slot] != 0.0f; }

// Floats per chunk of the threaded copies (as the model's blend).
constexpr std::size_t kCopyGrain = 3 * 16384;

void copyFloats(const float* from, float* to, std::size_t n) {
  detail::parallelChunks(n, kCopyGrain, [&](std::size_t begin, std::size_t end) {
    std::memcpy(to + begin, from + begin, (end - begin) * sizeof(float));
  });
}

}  // namespace

ModelEvaluator::ModelEvaluator(const ViewDependentModel& model)
    : model_(&model), positions_(model.base().positions), normals_(model.base_normals_) {
  model.requireNoParts("the per-frame evaluator (ModelEvaluator)");
  model.requireViewDirections("the per-frame evaluator (ModelEvaluator)");
  if (model.sphere().settings().scheme == WeightScheme::Rbf) dense_.resize(model.keyCount() + 1);
  weights_.base = 1.0f;
}

bool ModelEvaluator::evaluate(const Eigen::Vector3d& view, double sharpness, int* hint) {
  int local_hint = hint ? *hint : -1;
  if (!dense_.empty()) {  // the rbf scheme: every key weighs, every vertex may move (a full frame)
    if (!model_->denseWeights(view, sharpness, dense_, &local_hint)) return false;
    (void)model_->blendDense(dense_, positions_);  // sizes and weights checked
    (void)computeVertexNormals(model_->surface(), positions_, normals_);
    weights_ = heaviestKeys(dense_);
    full_frame_ = true;
    if (hint) *hint = local_hint;
    return true;
  }
  ViewWeights w;
  if (!model_->weights(view, sharpness, w, &local_hint)) return false;
  if (!apply(w)) return false;  // cannot fail: w comes from the model's sphere
  if (hint) *hint = local_hint;
  return true;
}

bool ModelEvaluator::apply(const ViewWeights& w) {
  const ViewDependentModel& m = *model_;
  if (!m.checkWeights(w)) return false;
  const auto& keys = m.keys_;
  bool dense_now = false, dense_before = false;
  for (int slot = 0; slot < 3; ++slot) {
    if (active(w, slot) && keys[static_cast<std::size_t>(w.key[slot])].dense) dense_now = true;
    if (active(weights_, slot) && keys[static_cast<std::size_t>(weights_.key[slot])].dense) dense_before = true;
  }
  dense_before = dense_before || full_frame_;  // an rbf frame moved more than weights_ lists
  full_frame_ = false;
  if (dense_now) {
    (void)m.blend(w, positions_);  // sizes and weights checked
    (void)computeVertexNormals(m.surface(), positions_, normals_);
    weights_ = w;
    return true;
  }
  const float* base = m.base().positions.data();
  float* p = positions_.data();
  if (dense_before) {
    // Back to the base (positions and its cached normals), then only the sparse keys below.
    copyFloats(base, p, positions_.size());
    copyFloats(m.base_normals_.data(), normals_.data(), normals_.size());
  } else {
    // 1. The previous keys' moved vertices back to the base.
    for (int slot = 0; slot < 3; ++slot) {
      if (!active(weights_, slot)) continue;
      const auto& key = keys[static_cast<std::size_t>(weights_.key[slot])];
      const std::uint32_t* idx = key.indices.data();
      detail::parallelChunks(key.indices.size(), kCopyGrain / 3, [&](std::size_t begin, std::size_t end) {
        for (std::size_t i = begin; i < end; ++i) {
          const std::size_t v = 3 * static_cast<std::size_t>(idx[i]);
          p[v] = base[v];
          p[v + 1] = base[v + 1];
          p[v + 2] = base[v + 2];
        }
      });
    }
  }
  // 2. The current keys' deltas, slot by slot as blend() adds them.
  m.scatterSparse(w, p);
  // 3. Normals around every vertex that moved now or before (each key's list once).
  int done[6];
  int done_count = 0;
  const auto refresh = [&](const ViewWeights& ws, int slot) {
    if (!active(ws, slot)) return;
    const int k = ws.key[slot];
    for (int i = 0; i < done_count; ++i)
      if (done[i] == k) return;
    done[done_count++] = k;
    (void)computeVertexNormalsOf(m.surface(), positions_, keys[static_cast<std::size_t>(k)].normal_vertices,
                                 normals_);  // indices valid by construction
  };
  for (int slot = 0; slot < 3; ++slot) refresh(w, slot);
  if (!dense_before)
    for (int slot = 0; slot < 3; ++slot) refresh(weights_, slot);
  weights_ = w;
  return true;
}

}  // namespace vdg
