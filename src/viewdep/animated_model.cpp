// Animated view-dependent model: offsets interpolated over time per key view with natural (or
// periodic) cubic splines, then blended per frame (Rademacher 99, sections 4.1-4.2, then 3.2.3).
// The spline formulas are the usual second-derivative form (e.g. Parent, Computer Animation,
// appendix B.5; Press et al., Numerical Recipes, 3.3): on [t_j, t_j+1] with h = t_j+1 - t_j,
// A = (t_j+1 - t) / h and B = 1 - A,
//   S(t) = A y_j + B y_j+1 + ((A^3 - A) M_j + (B^3 - B) M_j+1) h^2 / 6,
// and the second derivatives M solve
//   h_k-1 M_k-1 + 2 (h_k-1 + h_k) M_k + h_k M_k+1 = 6 ((y_k+1 - y_k) / h_k - (y_k - y_k-1) / h_k-1)
// for the interior knots with M = 0 at both ends (natural), or for every knot cyclically with the
// cycle's wrap interval h_m-1 = t_0 + N - t_m-1 (periodic). M is linear in y: M = S y, and S
// (m x m) is what each view keeps, so the cardinal coefficients of any frame are exact.
#include "vdg/viewdep/animated_model.h"

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>

#include "extent.h"
#include "key_views.h"
#include "vdg/geom/error.h"
#include "vdg/geom/normalize.h"

namespace vdg {
namespace {

[[noreturn]] void throwOutOfRange(const char* what, std::size_t index, std::size_t count, const char* plural) {
  throw Error(std::string(what) + " " + std::to_string(index) + " out of range (the model has " +
              std::to_string(count) + " " + plural + ")");
}

// The second-derivative table S (m x m, row-major) of knots `t` (strictly increasing).
std::vector<double> secondDerivativeTable(const std::vector<int>& t, bool loop, int period) {
  const std::size_t m = t.size();
  std::vector<double> table(m * m, 0.0);
  if (m < 2 || (!loop && m < 3)) return table;  // constant, or the straight line of two points
  std::vector<double> h(m);
  for (std::size_t k = 0; k + 1 < m; ++k) h[k] = t[k + 1] - t[k];
  h[m - 1] = loop ? static_cast<double>(t[0] + period - t[m - 1]) : 0.0;
  // Unknowns: M_1..M_m-2 (natural) or M_0..M_m-1 (periodic); row r is the equation of knot k.
  const std::size_t first = loop ? 0 : 1, last = loop ? m - 1 : m - 2, n = last - first + 1;
  Eigen::MatrixXd lhs = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(n));
  Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(m));
  for (std::size_t k = first; k <= last; ++k) {
    const auto r = static_cast<Eigen::Index>(k - first);
    const std::size_t prev = (k + m - 1) % m, next = (k + 1) % m;
    const double hp = h[prev], hn = h[k];
    lhs(r, r) += 2.0 * (hp + hn);
    if (loop || k > 1) lhs(r, static_cast<Eigen::Index>(prev - first)) += hp;
    if (loop || k + 1 < m - 1) lhs(r, static_cast<Eigen::Index>(next - first)) += hn;
    rhs(r, static_cast<Eigen::Index>(next)) += 6.0 / hn;
    rhs(r, static_cast<Eigen::Index>(k)) -= 6.0 / hn + 6.0 / hp;
    rhs(r, static_cast<Eigen::Index>(prev)) += 6.0 / hp;
  }
  const Eigen::MatrixXd solved = lhs.partialPivLu().solve(rhs);
  for (std::size_t k = first; k <= last; ++k)
    for (std::size_t j = 0; j < m; ++j)
      table[k * m + j] = solved(static_cast<Eigen::Index>(k - first), static_cast<Eigen::Index>(j));
  return table;
}

}  // namespace

AnimatedViewDependentModel AnimatedViewDependentModel::build(const RawViewDependentModel& raw) {
  if (!raw.animated())
    throw Error(raw.where() + ": the base is not animated (no 'base_animation'); build it as a ViewDependentModel");
  raw.validate();
  if (raw.keys.empty()) throw Error(raw.where() + ": the model has no keys (add at least one key deformation)");
  AnimatedViewDependentModel model;
  model.base_ = raw.base;
  model.surface_ = SurfaceTopology::build(model.base_);
  model.base_frames_ = raw.base_frames;
  model.base_skin_ = raw.base_skin;
  model.center_ = raw.resolvedCenter();
  model.sharpness_ = raw.sharpness;
  model.loop_ = raw.base_animation->loop;
  model.offsets_space_ = raw.offsets;
  const int period = static_cast<int>(raw.base_frames.size());

  std::vector<Eigen::Vector3d> unit;
  unit.reserve(raw.keys.size());
  for (const RawKey& key : raw.keys) unit.push_back(*normalizedOrNone(key.view));  // validate() checked
  const detail::KeyViewGroups groups = detail::groupKeyViews(unit);
  model.views_.resize(groups.first_key.size());
  std::vector<Eigen::Vector3d> directions;
  std::vector<std::string> labels;
  for (std::size_t g = 0; g < groups.first_key.size(); ++g) {
    const std::size_t k = groups.first_key[g];
    model.views_[g].direction = unit[k];
    directions.push_back(unit[k]);
    labels.push_back("view of key '" + raw.keys[k].name + "' (keys[" + std::to_string(k) + "])");
  }
  if (raw.sphere.scheme == WeightScheme::Rbf)
    throw Error(raw.where() +
                ": the 'rbf' weight scheme is not supported for an animated base (use 'linear' or 'smooth')");
  try {
    model.sphere_ = ViewSphere::build(directions, raw.sphere, labels);
  } catch (const Error& e) {
    throw Error(raw.where() + ": " + e.what());
  }
  for (std::size_t k = 0; k < raw.keys.size(); ++k)
    model.views_[static_cast<std::size_t>(groups.group_of_key[k])].key_indices.push_back(k);

  const std::size_t size = raw.base.positions.size(), nv = raw.base.vertexCount();
  for (View& view : model.views_) {
    std::sort(view.key_indices.begin(), view.key_indices.end(),
              [&](std::size_t a, std::size_t b) { return raw.keys[a].frame < raw.keys[b].frame; });
    view.offsets.resize(view.key_indices.size() * size);
    for (std::size_t j = 0; j < view.key_indices.size(); ++j) {
      const RawKey& key = raw.keys[view.key_indices[j]];
      const auto f = static_cast<std::size_t>(key.frame);
      view.frames.push_back(key.frame);
      view.names.push_back(key.name);
      const std::vector<float>& from = raw.base_frames[f];
      float* o = &view.offsets[j * size];
      if (raw.offsets == OffsetSpace::kWorld) {
        for (std::size_t i = 0; i < size; ++i) o[i] = key.mesh.positions[i] - from[i];
        continue;
      }
      // Skinned: un-skin the offset at its key frame (validate() checked L_v is invertible).
      for (std::size_t v = 0; v < nv; ++v) {
        const Eigen::Matrix3d l = Eigen::Map<const Eigen::Matrix3f>(&raw.base_skin[f][9 * v]).cast<double>();
        const Eigen::Vector3d d(double(key.mesh.positions[3 * v]) - from[3 * v],
                                double(key.mesh.positions[3 * v + 1]) - from[3 * v + 1],
                                double(key.mesh.positions[3 * v + 2]) - from[3 * v + 2]);
        const Eigen::Vector3d rest = l.partialPivLu().solve(d);
        for (int c = 0; c < 3; ++c) o[3 * v + static_cast<std::size_t>(c)] = static_cast<float>(rest[c]);
      }
    }
    view.second = secondDerivativeTable(view.frames, model.loop_, period);
  }
  // At frame f a blend is a convex combination of base(f) and each view's full pose at f (see
  // extent() in the header): the pose of view i is the blend with weight 1 on i.
  detail::ExtentBuilder extent(model.center_);
  std::vector<float> pose(size);
  for (int f = 0; f < period; ++f) {
    const auto fi = static_cast<std::size_t>(f);
    extent.add(model.base_frames_[fi]);
    const std::span<const float> skin =
        model.base_skin_.empty() ? std::span<const float>() : std::span<const float>(model.base_skin_[fi]);
    for (std::size_t v = 0; v < model.views_.size(); ++v) {
      ViewWeights w;
      w.key[0] = static_cast<int>(v);
      w.weight[0] = 1.0f;
      model.blendPosed(f, model.base_frames_[fi], skin, w, pose);
      extent.add(pose);
    }
  }
  model.extent_ = extent.box();
  model.extent_radius_ = extent.radius();
  return model;
}

const Eigen::Vector3d& AnimatedViewDependentModel::viewDirection(std::size_t view) const {
  if (view >= views_.size()) throwOutOfRange("view", view, views_.size(), "views");
  return views_[view].direction;
}

std::span<const int> AnimatedViewDependentModel::keyFrames(std::size_t view) const {
  if (view >= views_.size()) throwOutOfRange("view", view, views_.size(), "views");
  return views_[view].frames;
}

const std::string& AnimatedViewDependentModel::keyName(std::size_t view, std::size_t j) const {
  if (view >= views_.size()) throwOutOfRange("view", view, views_.size(), "views");
  if (j >= views_[view].names.size()) throwOutOfRange("key frame", j, views_[view].names.size(), "key frames there");
  return views_[view].names[j];
}

std::size_t AnimatedViewDependentModel::keyIndex(std::size_t view, std::size_t j) const {
  if (view >= views_.size()) throwOutOfRange("view", view, views_.size(), "views");
  if (j >= views_[view].key_indices.size())
    throwOutOfRange("key frame", j, views_[view].key_indices.size(), "key frames there");
  return views_[view].key_indices[j];
}

std::span<const float> AnimatedViewDependentModel::offsets(std::size_t view, std::size_t j) const {
  if (view >= views_.size()) throwOutOfRange("view", view, views_.size(), "views");
  if (j >= views_[view].frames.size()) throwOutOfRange("key frame", j, views_[view].frames.size(), "key frames there");
  const std::size_t size = base_.positions.size();
  return std::span<const float>(views_[view].offsets).subspan(j * size, size);
}

std::span<const double> AnimatedViewDependentModel::secondDerivatives(std::size_t view) const {
  if (view >= views_.size()) throwOutOfRange("view", view, views_.size(), "views");
  return views_[view].second;
}

std::span<const float> AnimatedViewDependentModel::baseFrame(int frame) const {
  if (frame < 0 || frame >= frameCount())
    throwOutOfRange("frame", static_cast<std::size_t>(std::max(frame, 0)), base_frames_.size(), "frames");
  return base_frames_[static_cast<std::size_t>(frame)];
}

std::span<const float> AnimatedViewDependentModel::baseSkin(int frame) const {
  if (frame < 0 || frame >= frameCount())
    throwOutOfRange("frame", static_cast<std::size_t>(std::max(frame, 0)), base_frames_.size(), "frames");
  if (base_skin_.empty()) return {};
  return base_skin_[static_cast<std::size_t>(frame)];
}

// Section 4.2: the cardinal coefficients of `frame` (finite; checked by the callers).
void AnimatedViewDependentModel::coefficients(const View& view, double frame, double* out) const {
  const std::vector<int>& t = view.frames;
  const std::size_t m = t.size();
  std::fill(out, out + m, 0.0);
  if (m == 1) {
    out[0] = 1.0;
    return;
  }
  const double period = static_cast<double>(base_frames_.size());
  double x = frame;
  std::size_t j = 0;  // segment [t_j, t_j+1], t_m = t_0 + period when looping
  if (loop_) {
    double u = std::fmod(frame - t[0], period);
    if (u < 0.0) u += period;
    if (u >= period) u = 0.0;  // fmod rounding of a tiny negative value
    x = t[0] + u;
    while (j + 1 < m && x >= t[j + 1]) ++j;
  } else {
    if (x <= t[0]) {  // hold the first key frame's offset
      out[0] = 1.0;
      return;
    }
    if (x >= t[m - 1]) {  // hold the last one's
      out[m - 1] = 1.0;
      return;
    }
    // Binary search: the last knot <= x (m - 2 at most).
    j = static_cast<std::size_t>(
            std::upper_bound(t.begin(), t.end(), x, [](double a, int b) { return a < static_cast<double>(b); }) -
            t.begin()) -
        1;
  }
  const std::size_t next = (j + 1) % m;
  const double t1 = j + 1 < m ? static_cast<double>(t[j + 1]) : static_cast<double>(t[0]) + period;
  const double h = t1 - t[j];
  const double a = (t1 - x) / h, b = 1.0 - a;
  const double ca = (a * a * a - a) * h * h / 6.0, cb = (b * b * b - b) * h * h / 6.0;
  out[j] += a;
  out[next] += b;
  const double* sj = &view.second[j * m];
  const double* sn = &view.second[next * m];
  for (std::size_t k = 0; k < m; ++k) out[k] += ca * sj[k] + cb * sn[k];
}

bool AnimatedViewDependentModel::timeCoefficients(std::size_t view, double frame, std::span<double> out) const {
  if (view >= views_.size() || !std::isfinite(frame) || out.size() != views_[view].frames.size()) return false;
  coefficients(views_[view], frame, out.data());
  return true;
}

bool AnimatedViewDependentModel::weights(const Eigen::Vector3d& view, double sharpness, ViewWeights& out,
                                         int* hint) const {
  if (!std::isfinite(sharpness)) return false;
  return sphere_.weights(view, sharpness > 0.0 ? sharpness : sharpness_, out, hint);
}

// Section 4.1 then 3.2.3: p = base(f) + sum_i w_i T_v o_i(f), with o_i(f) = sum_j c_ij(f) o_ij.
void AnimatedViewDependentModel::blendPosed(double frame, std::span<const float> base_positions,
                                            std::span<const float> base_skin, const ViewWeights& w,
                                            std::span<float> out) const {
  constexpr std::size_t kMaxTerms = 3 * kMaxKeyFramesPerView;
  std::array<const float*, kMaxTerms> term_offsets;
  std::array<float, kMaxTerms> term_factors;
  std::array<double, kMaxKeyFramesPerView> coef;
  std::size_t terms = 0;
  const std::size_t size = base_.positions.size();
  for (int slot = 0; slot < 3; ++slot) {
    if (w.key[slot] < 0 || w.weight[slot] == 0.0f) continue;
    const View& view = views_[static_cast<std::size_t>(w.key[slot])];
    coefficients(view, frame, coef.data());
    for (std::size_t j = 0; j < view.frames.size(); ++j) {
      if (coef[j] == 0.0) continue;
      term_offsets[terms] = &view.offsets[j * size];
      term_factors[terms++] = static_cast<float>(static_cast<double>(w.weight[slot]) * coef[j]);
    }
  }
  const float* b = base_positions.data();
  float* o = out.data();
  if (terms == 0) {
    std::memcpy(o, b, size * sizeof(float));
    return;
  }
  const bool skinned = offsets_space_ == OffsetSpace::kSkinned;
  const std::size_t nv = base_.vertexCount();
  for (std::size_t v = 0; v < nv; ++v) {
    float d[3] = {0.0f, 0.0f, 0.0f};
    for (std::size_t t = 0; t < terms; ++t) {
      const float* src = term_offsets[t] + 3 * v;
      const float f = term_factors[t];
      d[0] += f * src[0];
      d[1] += f * src[1];
      d[2] += f * src[2];
    }
    if (skinned) {  // T_v = L_v(f), column-major
      const float* l = &base_skin[9 * v];
      const float x = l[0] * d[0] + l[3] * d[1] + l[6] * d[2];
      const float y = l[1] * d[0] + l[4] * d[1] + l[7] * d[2];
      const float z = l[2] * d[0] + l[5] * d[1] + l[8] * d[2];
      d[0] = x;
      d[1] = y;
      d[2] = z;
    }
    o[3 * v] = b[3 * v] + d[0];
    o[3 * v + 1] = b[3 * v + 1] + d[1];
    o[3 * v + 2] = b[3 * v + 2] + d[2];
  }
}

bool AnimatedViewDependentModel::evaluatePosed(double frame, std::span<const float> base_positions,
                                               std::span<const float> base_skin, const Eigen::Vector3d& view,
                                               double sharpness, std::span<float> out_positions,
                                               std::span<float> out_normals, int* hint) const {
  // Every check happens before the first write (as ViewDependentModel::evaluate).
  const std::size_t size = base_.positions.size();
  if (!std::isfinite(frame)) return false;
  if (base_positions.size() != size) return false;
  if (offsets_space_ == OffsetSpace::kSkinned ? base_skin.size() != 3 * size
                                              : !base_skin.empty() && base_skin.size() != 3 * size)
    return false;
  if (out_positions.size() != size) return false;
  if (!out_normals.empty() && out_normals.size() != size) return false;
  int local_hint = hint ? *hint : -1;
  ViewWeights w;
  if (!weights(view, sharpness, w, &local_hint)) return false;
  blendPosed(frame, base_positions, base_skin, w, out_positions);
  if (!out_normals.empty() && !computeVertexNormals(surface_, out_positions, out_normals)) return false;
  if (hint) *hint = local_hint;
  return true;
}

bool AnimatedViewDependentModel::evaluate(int frame, const Eigen::Vector3d& view, double sharpness,
                                          std::span<float> out_positions, std::span<float> out_normals,
                                          int* hint) const {
  if (frame < 0 || frame >= frameCount()) return false;
  const auto f = static_cast<std::size_t>(frame);
  const std::span<const float> skin =
      offsets_space_ == OffsetSpace::kSkinned ? std::span<const float>(base_skin_[f]) : std::span<const float>();
  return evaluatePosed(static_cast<double>(frame), base_frames_[f], skin, view, sharpness, out_positions, out_normals,
                       hint);
}

}  // namespace vdg
