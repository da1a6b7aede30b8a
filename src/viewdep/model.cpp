// View-dependent model: validation, build and evaluation (Rademacher 99, sections 3.1-3.2.3).
#include "vdg/viewdep/model.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <set>

#include "extent.h"
#include "key_views.h"
#include "parts.h"
#include "vdg/geom/error.h"
#include "vdg/geom/normalize.h"
#include "vdg/geom/parallel.h"

namespace vdg {

const char* offsetSpaceName(OffsetSpace space) { return space == OffsetSpace::kSkinned ? "skinned" : "world"; }

namespace detail {

KeyViewGroups groupKeyViews(std::span<const Eigen::Vector3d> unit_views) {
  const std::size_t n = unit_views.size();
  // Identical directions first: sort indices by (x, y, z), each run maps to its first index.
  std::vector<std::size_t> order(n);
  for (std::size_t i = 0; i < n; ++i) order[i] = i;
  const auto less = [&](std::size_t a, std::size_t b) {
    const Eigen::Vector3d &u = unit_views[a], &v = unit_views[b];
    if (u.x() != v.x()) return u.x() < v.x();
    if (u.y() != v.y()) return u.y() < v.y();
    if (u.z() != v.z()) return u.z() < v.z();
    return a < b;
  };
  std::sort(order.begin(), order.end(), less);
  std::vector<std::size_t> parent(n);
  std::vector<std::size_t> distinct;  // indices of distinct directions (smallest index of each run)
  for (std::size_t r = 0; r < n;) {
    std::size_t e = r;
    while (e < n && unit_views[order[e]] == unit_views[order[r]]) parent[order[e++]] = order[r];
    distinct.push_back(order[r]);
    r = e;
  }
  std::sort(distinct.begin(), distinct.end());
  const auto find = [&](std::size_t i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  };
  std::vector<Eigen::Vector3d> views;
  views.reserve(distinct.size());
  for (const std::size_t i : distinct) views.push_back(unit_views[i]);
  forEachCloseViewPair(views, ViewSphere::kSameViewRad, [&](std::size_t i, std::size_t j, double) {
    const std::size_t a = find(distinct[i]), b = find(distinct[j]);
    if (a != b) parent[std::max(a, b)] = std::min(a, b);
    return true;
  });
  KeyViewGroups groups;
  groups.group_of_key.assign(n, -1);
  std::vector<int> group_of_root(n, -1);
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t root = find(k);
    if (group_of_root[root] < 0) {
      group_of_root[root] = static_cast<int>(groups.first_key.size());
      groups.first_key.push_back(k);
    }
    groups.group_of_key[k] = group_of_root[root];
  }
  return groups;
}

}  // namespace detail

namespace {

std::string rawKeyName(const RawViewDependentModel& model, std::size_t k) {
  return "key '" + model.keys[k].name + "' (keys[" + std::to_string(k) + "])";
}

std::string keyLabel(const RawViewDependentModel& model, std::size_t k) {
  return model.where() + ": " + rawKeyName(model, k);
}

// validate() without, when `check_view_pairs` is false, the search for two keys with the same
// view: ViewDependentModel::build leaves that to ViewSphere::build, so that it runs once per build.
void validateRaw(const RawViewDependentModel& raw, bool check_view_pairs);

// A skin linear part (column-major 3x3) whose inverse is usable: finite, and a determinant that is
// not tiny next to the product of its column lengths (so a uniform scale of any size is fine).
bool invertibleSkin(const float* m) {
  const Eigen::Matrix3d a = Eigen::Map<const Eigen::Matrix3f>(m).cast<double>();
  if (!a.allFinite()) return false;
  const double scale = a.col(0).norm() * a.col(1).norm() * a.col(2).norm();
  constexpr double kMinRelativeDeterminant = 1e-9;
  return scale > 0.0 && std::abs(a.determinant()) > kMinRelativeDeterminant * scale;
}

// The animation fields (section 4.1) before the keys are looked at.
void validateAnimation(const RawViewDependentModel& raw) {
  if (!raw.animated()) {
    if (!raw.base_frames.empty())
      throw Error(raw.where() + ": base_frames are given but the base is static (no 'base_animation')");
    if (!raw.base_skin.empty())
      throw Error(raw.where() + ": base_skin is given but the base is static (no 'base_animation')");
    if (raw.offsets != OffsetSpace::kWorld)
      throw Error(raw.where() + ": 'offsets': 'skinned' needs an animated, skinned base ('base_animation')");
    return;
  }
  const std::size_t n = raw.base_frames.size(), size = raw.base.positions.size();
  if (n == 0) throw Error(raw.where() + ": the base animation has no frames");
  if (n > kMaxBaseFrames)
    throw Error(raw.where() + ": the base animation has " + std::to_string(n) + " frames; at most " +
                std::to_string(kMaxBaseFrames) + " are allowed");
  for (std::size_t f = 0; f < n; ++f) {
    const std::vector<float>& frame = raw.base_frames[f];
    if (frame.size() != size)
      throw Error(raw.where() + ": base animation frame " + std::to_string(f) + " has " + std::to_string(frame.size()) +
                  " coordinates; expected 3 per vertex of the base (" + std::to_string(size) + ")");
    for (std::size_t i = 0; i < size; ++i)
      if (!std::isfinite(frame[i]))
        throw Error(raw.where() + ": base animation frame " + std::to_string(f) + ": vertex " + std::to_string(i / 3) +
                    " has a non-finite coordinate (NaN or Inf)");
  }
  if (!raw.base_skin.empty()) {
    if (raw.base_skin.size() != n)
      throw Error(raw.where() + ": base_skin has " + std::to_string(raw.base_skin.size()) +
                  " frames but the base animation has " + std::to_string(n));
    for (std::size_t f = 0; f < n; ++f) {
      if (raw.base_skin[f].size() != 3 * size)
        throw Error(raw.where() + ": base_skin frame " + std::to_string(f) + " has " +
                    std::to_string(raw.base_skin[f].size()) + " floats; expected 9 per vertex (" +
                    std::to_string(3 * size) + ")");
      for (std::size_t i = 0; i < 3 * size; ++i)
        if (!std::isfinite(raw.base_skin[f][i]))
          throw Error(raw.where() + ": base_skin frame " + std::to_string(f) + ": vertex " + std::to_string(i / 9) +
                      " has a non-finite skin matrix");
    }
  }
  if (raw.offsets == OffsetSpace::kSkinned && raw.base_skin.empty())
    throw Error(raw.where() + ": 'offsets': 'skinned' needs a skinned base (the base animation has no skin)");
}

// Animated keys, after each was checked alone: views grouped into sphere points; within a group the
// frames must differ; at most kMaxKeyFramesPerView per group; skinned offsets need an invertible
// skin at every key's frame.
void validateAnimatedKeys(const RawViewDependentModel& raw) {
  const std::vector<RawKey>& keys = raw.keys;
  std::vector<Eigen::Vector3d> views;
  views.reserve(keys.size());
  for (const RawKey& key : keys) views.push_back(*normalizedOrNone(key.view));
  const detail::KeyViewGroups groups = detail::groupKeyViews(views);
  std::vector<std::vector<std::size_t>> members(groups.first_key.size());
  for (std::size_t k = 0; k < keys.size(); ++k) members[static_cast<std::size_t>(groups.group_of_key[k])].push_back(k);
  for (std::vector<std::size_t>& group : members) {
    std::sort(group.begin(), group.end(), [&](std::size_t a, std::size_t b) {
      return keys[a].frame != keys[b].frame ? keys[a].frame < keys[b].frame : a < b;
    });
    for (std::size_t i = 1; i < group.size(); ++i)
      if (keys[group[i]].frame == keys[group[i - 1]].frame) {
        const std::size_t k = std::max(group[i], group[i - 1]), j = std::min(group[i], group[i - 1]);
        throw Error(keyLabel(raw, k) + ": same view direction (within 1e-6 rad) and same frame " +
                    std::to_string(keys[k].frame) + " as key '" + keys[j].name + "'");
      }
    if (group.size() > kMaxKeyFramesPerView)
      throw Error(keyLabel(raw, group.front()) + ": its view has " + std::to_string(group.size()) +
                  " key frames; one view may have at most " + std::to_string(kMaxKeyFramesPerView));
  }
  if (raw.offsets != OffsetSpace::kSkinned) return;
  for (std::size_t k = 0; k < keys.size(); ++k) {
    const std::vector<float>& skin = raw.base_skin[static_cast<std::size_t>(keys[k].frame)];
    for (std::size_t v = 0; v < raw.base.vertexCount(); ++v)
      if (!invertibleSkin(&skin[9 * v]))
        throw Error(keyLabel(raw, k) + ": vertex " + std::to_string(v) + ": the skin matrix at frame " +
                    std::to_string(keys[k].frame) + " is singular, so 'offsets': 'skinned' cannot un-skin the offset");
  }
}

}  // namespace

Eigen::Vector3d RawViewDependentModel::resolvedCenter() const {
  if (center) return *center;
  const auto c = computeBounds(base.positions).center();
  return {c[0], c[1], c[2]};
}

void RawViewDependentModel::resolveViews() {
  const Eigen::Vector3d c = resolvedCenter();
  for (RawKey& key : keys) {
    if (!key.camera && !key.eye) continue;
    const Eigen::Vector3d d = *key.eyePosition() - c;
    // Zero or non-finite differences stay as they are, for validate() to report.
    key.view = normalizedOrNone(d).value_or(d);
  }
}

void RawViewDependentModel::validate() const { validateRaw(*this, true); }

namespace {

// "weights": {"space": "positions"} (vdg/viewdep/key_space.h): every key has an eye; KeySpace::build
// finds coinciding eyes and coplanar eye sets, naming the keys.
void validatePositions(const RawViewDependentModel& raw) {
  if (raw.sphere.scheme != WeightScheme::Linear)
    throw Error(raw.where() + ": the 'positions' weight space takes the 'linear' scheme only, got '" +
                weightSchemeName(raw.sphere.scheme) + "'");
  if (raw.keys.size() > kMaxPositionKeys)
    throw Error(raw.where() + ": " + std::to_string(raw.keys.size()) +
                " keys; the 'positions' weight space takes at most " + std::to_string(kMaxPositionKeys));
  if (!(raw.key_space.falloff >= 0.0) || !std::isfinite(raw.key_space.falloff))
    throw Error(raw.where() + ": 'weights': 'falloff' must be a finite distance >= 0 (0: automatic), got " +
                std::to_string(raw.key_space.falloff));
  for (std::size_t k = 0; k < raw.keys.size(); ++k)
    if (!raw.keys[k].eyePosition())
      throw Error(keyLabel(raw, k) +
                  ": the 'positions' weight space needs the key's eye (a 'camera' or an 'eye'), "
                  "not a 'view' direction");
}

void validateRaw(const RawViewDependentModel& raw, bool check_view_pairs) {
  const std::string& base_path = raw.base_path;
  const TriMesh& base = raw.base;
  const std::vector<RawKey>& keys = raw.keys;
  const double sharpness = raw.sharpness;
  const ViewSphereSettings& sphere = raw.sphere;
  const std::optional<Eigen::Vector3d>& center = raw.center;
  validateMesh(base, raw.where() + ": base mesh" + (base_path.empty() ? std::string() : " '" + base_path + "'"));
  if (keys.size() > kMaxKeys)
    throw Error(raw.where() + ": " + std::to_string(keys.size()) + " keys; a model may have at most " +
                std::to_string(kMaxKeys));
  if (!(sharpness > 0.0) || !std::isfinite(sharpness))
    throw Error(raw.where() + ": 'sharpness' must be a positive number, got " + std::to_string(sharpness));
  if (!(sphere.base_falloff_deg > 0.0 && sphere.base_falloff_deg <= 70.0))
    throw Error(raw.where() + ": 'base_falloff_deg' must be in (0, 70] degrees, got " +
                std::to_string(sphere.base_falloff_deg));
  if (center && !center->allFinite()) throw Error(raw.where() + ": 'center' is not finite");
  validateAnimation(raw);
  std::set<std::string> names;
  for (std::size_t k = 0; k < keys.size(); ++k) {
    const RawKey& key = keys[k];
    const std::string label = keyLabel(raw, k);
    if (key.name.empty()) throw Error(raw.where() + ": keys[" + std::to_string(k) + "] has an empty name");
    if (!names.insert(key.name).second) throw Error(label + ": another key has the same name");
    if (key.mesh.vertexCount() != base.vertexCount())
      throw Error(label + ": mesh has " + std::to_string(key.mesh.vertexCount()) + " vertices but the base has " +
                  std::to_string(base.vertexCount()) + " (a key deformation only moves the base's vertices)");
    if (key.mesh.triangles.size() != base.triangles.size())
      throw Error(label + ": mesh has " + std::to_string(key.mesh.triangleCount()) + " triangles but the base has " +
                  std::to_string(base.triangleCount()) + " (the connectivity must not change)");
    for (std::size_t i = 0; i < base.triangles.size(); ++i) {
      if (key.mesh.triangles[i] != base.triangles[i]) {
        const std::size_t t = i / 3;
        throw Error(label + ": triangle " + std::to_string(t) + " differs from the base's (" +
                    std::to_string(key.mesh.triangles[3 * t]) + " " + std::to_string(key.mesh.triangles[3 * t + 1]) +
                    " " + std::to_string(key.mesh.triangles[3 * t + 2]) + " vs " +
                    std::to_string(base.triangles[3 * t]) + " " + std::to_string(base.triangles[3 * t + 1]) + " " +
                    std::to_string(base.triangles[3 * t + 2]) + "); the connectivity must not change");
      }
    }
    if (raw.animated()) {
      if (key.frame < 0 || static_cast<std::size_t>(key.frame) >= raw.frameCount())
        throw Error(label + ": frame " + std::to_string(key.frame) + " is outside the base animation's frames 0.." +
                    std::to_string(raw.frameCount() - 1));
    } else if (key.frame != 0) {
      throw Error(label + ": frame " + std::to_string(key.frame) +
                  " needs an animated base ('base_animation'); a static base has only frame 0");
    }
    // Animated: the key's offset is measured from the base at the key's frame.
    const std::vector<float>& from =
        raw.animated() ? raw.base_frames[static_cast<std::size_t>(key.frame)] : base.positions;
    for (std::size_t i = 0; i < key.mesh.positions.size(); ++i) {
      if (!std::isfinite(key.mesh.positions[i]))
        throw Error(label + ": vertex " + std::to_string(i / 3) + " has a non-finite coordinate (NaN or Inf)");
      // The key is stored as its offset from the base (a float); it must not overflow.
      if (!std::isfinite(key.mesh.positions[i] - from[i]))
        throw Error(label + ": vertex " + std::to_string(i / 3) +
                    " moves too far from the base's (the offset overflows a float)");
    }
    if (!key.view.allFinite())
      throw Error(label + (key.camera ? ": camera eye is not finite or too far from the model centre"
                                      : ": view direction is not finite"));
    if (!normalizedOrNone(key.view))  // any finite non-zero length works, 1e-300 or 1e300
      throw Error(label + (key.camera ? ": camera eye is at the model centre, so it gives no view direction"
                                      : ": view direction has zero length"));
  }
  detail::validateParts(raw, check_view_pairs);  // parts.cpp; refuses parts on an animated base
  if (raw.animated()) {
    if (raw.key_space.space == WeightSpace::Positions)
      throw Error(raw.where() +
                  ": the 'positions' weight space is not supported for an animated base "
                  "(use \"space\": \"directions\")");
    validateAnimatedKeys(raw);
    return;
  }
  if (raw.key_space.space == WeightSpace::Positions) {
    if (!raw.parts.empty())
      throw Error(raw.where() +
                  ": model parts ('parts') and the 'positions' weight space cannot be combined yet "
                  "(each part weighs a view direction)");
    validatePositions(raw);  // keys may share a direction at different distances
    return;
  }
  if (!check_view_pairs || !raw.parts.empty()) return;  // with parts, views may repeat across parts
  std::vector<Eigen::Vector3d> views;
  views.reserve(keys.size());
  for (const RawKey& key : keys) views.push_back(*normalizedOrNone(key.view));
  forEachCloseViewPair(views, ViewSphere::kSameViewRad, [&](std::size_t k, std::size_t j, double) -> bool {
    throw Error(keyLabel(raw, k) + ": same view direction as key '" + keys[j].name + "' (within 1e-6 rad)");
  });
}

}  // namespace

ViewDependentModel ViewDependentModel::build(const RawViewDependentModel& raw) {
  if (raw.animated())
    throw Error(raw.where() +
                ": has an animated base ('base_animation'); build it as an AnimatedViewDependentModel "
                "(vdg/viewdep/animated_model.h)");
  validateRaw(raw, false);  // ViewSphere::build below finds coinciding views, naming the keys
  if (raw.keys.empty()) throw Error(raw.where() + ": the model has no keys (add at least one key deformation)");
  ViewDependentModel model;
  model.base_ = raw.base;
  model.surface_ = SurfaceTopology::build(model.base_);
  model.center_ = raw.resolvedCenter();
  model.sharpness_ = raw.sharpness;
  std::vector<Eigen::Vector3d> views;
  std::vector<std::string> labels;
  for (std::size_t k = 0; k < raw.keys.size(); ++k) {
    views.push_back(raw.keys[k].view);
    labels.push_back(rawKeyName(raw, k));
  }
  if (raw.parts.empty()) {  // with parts, each part has a sphere of its own (buildParts)
    try {
      if (raw.key_space.space == WeightSpace::Positions) {
        std::vector<Eigen::Vector3d> eyes;
        for (const RawKey& key : raw.keys) eyes.push_back(*key.eyePosition());  // validateRaw checked them
        model.key_space_ = KeySpace::build(eyes, model.center_, raw.sphere, raw.key_space.falloff, labels);
        model.sphere_ = model.key_space_->sphere();
      } else {
        model.sphere_ = ViewSphere::build(views, raw.sphere, labels);
      }
    } catch (const Error& e) {
      throw Error(raw.where() + ": " + e.what());
    }
  }
  const std::size_t nv = raw.base.vertexCount();
  if (raw.parts.empty())
    model.storeDeltas(raw, {}, {});
  else
    model.buildParts(raw, labels);  // the part spheres and the masked deltas (parts.cpp)
  // Cached for ModelEvaluator: the base's normals, and per sparse key the vertices whose normal a
  // move of that key can change.
  model.base_normals_.resize(3 * nv);
  (void)computeVertexNormals(model.surface_, model.base_.positions, model.base_normals_);  // sizes right
  model.findNormalVertices();
  // Every blend is a convex combination of the base and the keys (see extent() in the header).
  detail::ExtentBuilder extent(model.center_);
  extent.add(raw.base.positions);
  for (const RawKey& raw_key : raw.keys) extent.add(raw_key.mesh.positions);
  model.extent_ = extent.box();
  model.extent_radius_ = extent.radius();
  return model;
}

void ViewDependentModel::storeDeltas(const RawViewDependentModel& raw, std::span<const std::vector<float>> masks,
                                     std::span<const std::size_t> part_of_key) {
  const std::size_t nv = raw.base.vertexCount();
  for (std::size_t k = 0; k < raw.keys.size(); ++k) {
    const RawKey& raw_key = raw.keys[k];
    Key key;
    key.name = raw_key.name;
    key.camera = raw_key.camera;
    key.view = *normalizedOrNone(raw_key.view);  // validated non-zero and finite
    // With parts, the key's delta is its part's mask times its offset (parts.cpp).
    const float* mask = masks.empty() ? nullptr : masks[part_of_key[k]].data();
    const auto delta = [&](std::size_t i) {
      const float d = raw_key.mesh.positions[i] - raw.base.positions[i];
      return mask ? mask[i / 3] * d : d;
    };
    std::vector<std::uint32_t> moved;
    for (std::size_t v = 0; v < nv; ++v) {
      const float* b = &raw.base.positions[3 * v];
      const float* p = &raw_key.mesh.positions[3 * v];
      const bool moves = mask ? (delta(3 * v) != 0.0f || delta(3 * v + 1) != 0.0f || delta(3 * v + 2) != 0.0f)
                              : (b[0] != p[0] || b[1] != p[1] || b[2] != p[2]);
      if (moves) moved.push_back(static_cast<std::uint32_t>(v));
    }
    key.moved_count = moved.size();
    // Sparse storage pays an index per moved vertex; past half the vertices dense is cheaper.
    key.dense = moved.size() * 2 > nv;
    if (key.dense) {
      key.deltas.resize(3 * nv);
      for (std::size_t i = 0; i < 3 * nv; ++i) key.deltas[i] = delta(i);
    } else {
      key.indices = std::move(moved);
      key.deltas.reserve(3 * key.indices.size());
      for (const std::uint32_t v : key.indices)
        for (std::size_t c = 0; c < 3; ++c) key.deltas.push_back(delta(3 * v + c));
    }
    keys_.push_back(std::move(key));
  }
}

// A moved vertex m changes the area-weighted normal of every triangle at m, so the normals of the
// homes of those triangles' corners, and the vertices copying those homes. The triangles at m are
// among those its home gathers (homeTriangles() of vertexHome()[m], a superset when seam copies of
// m carry other triangles), so the list may hold a few vertices more than needed, never fewer.
void ViewDependentModel::findNormalVertices() {
  const std::size_t nv = base_.vertexCount();
  const auto home = surface_.vertexHome();
  const auto off = surface_.homeTriangleOffsets();
  const auto ids = surface_.homeTriangles();
  const auto tris = surface_.triangles();
  // The vertices copying each home (a small CSR over surface_.copiedVertices()).
  std::vector<std::int32_t> copy_offsets(nv + 1, 0), copies(surface_.copiedVertices().size());
  for (const std::int32_t v : surface_.copiedVertices())
    ++copy_offsets[static_cast<std::size_t>(home[static_cast<std::size_t>(v)]) + 1];
  for (std::size_t h = 0; h < nv; ++h) copy_offsets[h + 1] += copy_offsets[h];
  {
    std::vector<std::int32_t> next(copy_offsets.begin(), copy_offsets.end() - 1);
    for (const std::int32_t v : surface_.copiedVertices())
      copies[static_cast<std::size_t>(next[static_cast<std::size_t>(home[static_cast<std::size_t>(v)])]++)] = v;
  }
  std::vector<std::uint8_t> marked(nv, 0);
  std::vector<std::int32_t> homes;
  for (Key& key : keys_) {
    if (key.dense) continue;
    homes.clear();
    for (const std::uint32_t m : key.indices) {
      const auto h = static_cast<std::size_t>(home[m]);
      for (auto i = off[h]; i < off[h + 1]; ++i)
        for (std::size_t c = 0; c < 3; ++c) {
          const std::int32_t corner_home =
              home[static_cast<std::size_t>(tris[3 * static_cast<std::size_t>(ids[static_cast<std::size_t>(i)]) + c])];
          if (!marked[static_cast<std::size_t>(corner_home)]) {
            marked[static_cast<std::size_t>(corner_home)] = 1;
            homes.push_back(corner_home);
          }
        }
    }
    key.normal_vertices = homes;
    for (const std::int32_t h : homes) {
      marked[static_cast<std::size_t>(h)] = 0;
      const auto hs = static_cast<std::size_t>(h);
      key.normal_vertices.insert(key.normal_vertices.end(), copies.begin() + copy_offsets[hs],
                                 copies.begin() + copy_offsets[hs + 1]);
    }
    std::sort(key.normal_vertices.begin(), key.normal_vertices.end());  // ascending: memory order
    key.normal_vertices.shrink_to_fit();
  }
}

Eigen::Vector3d ViewDependentModel::viewFromEye(const Eigen::Vector3d& eye) const {
  return normalizedOrNone(Eigen::Vector3d(eye - center_)).value_or(Eigen::Vector3d::Zero());
}

namespace {
[[noreturn]] void throwKeyOutOfRange(std::size_t key, std::size_t count) {
  throw Error("key " + std::to_string(key) + " out of range (the model has " + std::to_string(count) + " keys)");
}
}  // namespace

const std::string& ViewDependentModel::keyName(std::size_t key) const {
  if (key >= keys_.size()) throwKeyOutOfRange(key, keys_.size());
  return keys_[key].name;
}

const Eigen::Vector3d& ViewDependentModel::keyView(std::size_t key) const {
  if (key >= keys_.size()) throwKeyOutOfRange(key, keys_.size());
  return keys_[key].view;
}

const std::optional<Camera>& ViewDependentModel::keyCamera(std::size_t key) const {
  if (key >= keys_.size()) throwKeyOutOfRange(key, keys_.size());
  return keys_[key].camera;
}

std::size_t ViewDependentModel::keyMovedCount(std::size_t key) const {
  if (key >= keys_.size()) throwKeyOutOfRange(key, keys_.size());
  return keys_[key].moved_count;
}

bool ViewDependentModel::weights(const Eigen::Vector3d& view, double sharpness, ViewWeights& out, int* hint) const {
  if (!std::isfinite(sharpness) || !parts_.empty() || key_space_) return false;  // parts and eyes weigh otherwise
  return sphere_.weights(view, sharpness > 0.0 ? sharpness : sharpness_, out, hint);
}

bool ViewDependentModel::checkWeights(const ViewWeights& w) const {
  for (int slot = 0; slot < 3; ++slot) {
    if (w.key[slot] < -1 || w.key[slot] >= static_cast<int>(keys_.size())) return false;
    if (!std::isfinite(w.weight[slot])) return false;
  }
  return true;
}

void ViewDependentModel::scatterSparse(const ViewWeights& w, float* out) const {
  for (int slot = 0; slot < 3; ++slot) {
    const int k = w.key[slot];
    const float weight = w.weight[slot];
    if (k < 0 || weight == 0.0f) continue;
    const Key& key = keys_[static_cast<std::size_t>(k)];
    if (key.dense) continue;
    const float* d = key.deltas.data();
    const std::uint32_t* idx = key.indices.data();
    // A key's indices are distinct, so its chunks write disjoint vertices.
    detail::parallelChunks(key.indices.size(), kBlendGrain / 3, [&](std::size_t begin, std::size_t end) {
      for (std::size_t i = begin; i < end; ++i) {
        float* v = out + 3 * static_cast<std::size_t>(idx[i]);
        v[0] += weight * d[3 * i];
        v[1] += weight * d[3 * i + 1];
        v[2] += weight * d[3 * i + 2];
      }
    });
  }
}

// Section 3.2.3: v = sum_i w_i v^i, written as base + sum_i w_i (v^i - base) because the weights,
// base included, sum to 1. Only the moved vertices of sparse keys are touched.
bool ViewDependentModel::blend(const ViewWeights& w, std::span<float> out) const {
  const std::size_t n = base_.positions.size();
  if (out.size() != n || !checkWeights(w)) return false;
  // Dense keys are fused into one pass over the base (one read of each array, one write),
  // vectorised (Eigen array maps) and split over TBB's threads in chunks of kBlendGrain floats;
  // sparse keys then scatter their moved vertices.
  const float* dense_delta[3] = {nullptr, nullptr, nullptr};
  float dense_weight[3] = {0.0f, 0.0f, 0.0f};
  int dense_count = 0;
  for (int slot = 0; slot < 3; ++slot) {
    const int k = w.key[slot];
    if (k < 0 || w.weight[slot] == 0.0f) continue;
    const Key& key = keys_[static_cast<std::size_t>(k)];
    if (key.dense) {
      dense_delta[dense_count] = key.deltas.data();
      dense_weight[dense_count++] = w.weight[slot];
    }
  }
  const float* b = base_.positions.data();
  float* o = out.data();
  using Array = Eigen::Map<Eigen::ArrayXf>;
  using ConstArray = Eigen::Map<const Eigen::ArrayXf>;
  detail::parallelChunks(n, kBlendGrain, [&](std::size_t begin, std::size_t end) {
    const auto len = static_cast<Eigen::Index>(end - begin);
    Array dst(o + begin, len);
    const ConstArray base(b + begin, len);
    switch (dense_count) {
      case 0:
        std::memcpy(o + begin, b + begin, (end - begin) * sizeof(float));
        break;
      case 1:
        dst = base + dense_weight[0] * ConstArray(dense_delta[0] + begin, len);
        break;
      case 2:
        dst = base + dense_weight[0] * ConstArray(dense_delta[0] + begin, len) +
              dense_weight[1] * ConstArray(dense_delta[1] + begin, len);
        break;
      default:
        dst = base + dense_weight[0] * ConstArray(dense_delta[0] + begin, len) +
              dense_weight[1] * ConstArray(dense_delta[1] + begin, len) +
              dense_weight[2] * ConstArray(dense_delta[2] + begin, len);
        break;
    }
  });
  scatterSparse(w, o);
  return true;
}

bool ViewDependentModel::denseWeights(const Eigen::Vector3d& view, double sharpness, std::span<float> out,
                                      int* hint) const {
  if (!std::isfinite(sharpness) || !parts_.empty() || key_space_) return false;  // parts and eyes weigh otherwise
  return sphere_.denseWeights(view, sharpness > 0.0 ? sharpness : sharpness_, out, hint);
}

// Section 3.2.3 over every key (the rbf scheme's blend): base + sum_k w_k (v^k - base).
bool ViewDependentModel::blendDense(std::span<const float> weights, std::span<float> out) const {
  const std::size_t n = base_.positions.size();
  if (out.size() != n || weights.size() != keys_.size() + 1) return false;
  for (const float w : weights)
    if (!std::isfinite(w)) return false;
  std::memcpy(out.data(), base_.positions.data(), n * sizeof(float));
  Eigen::Map<Eigen::ArrayXf> dst(out.data(), static_cast<Eigen::Index>(n));
  for (std::size_t k = 0; k < keys_.size(); ++k) {
    if (weights[k] == 0.0f) continue;
    if (keys_[k].dense) {
      dst += weights[k] * Eigen::Map<const Eigen::ArrayXf>(keys_[k].deltas.data(), static_cast<Eigen::Index>(n));
      continue;
    }
    ViewWeights one;
    one.key[0] = static_cast<int>(k);
    one.weight[0] = weights[k];
    scatterSparse(one, out.data());
  }
  return true;
}

bool ViewDependentModel::denseWeightsAtEye(const Eigen::Vector3d& eye, double sharpness, std::span<float> out,
                                           int* hint) const {
  if (!std::isfinite(sharpness)) return false;
  if (key_space_) return key_space_->weights(eye, sharpness > 0.0 ? sharpness : sharpness_, out, hint);
  const Eigen::Vector3d view = viewFromEye(eye);
  return !view.isZero() && denseWeights(view, sharpness, out, hint);
}

bool ViewDependentModel::evaluateAtEye(const Eigen::Vector3d& eye, double sharpness, std::span<float> out_positions,
                                       std::span<float> out_normals, int* hint) const {
  if (!key_space_ && keys_.size() > ViewSphere::kRbfMaxKeys) {  // a three-key scheme (rbf has <= 256 keys)
    const Eigen::Vector3d view = viewFromEye(eye);
    return !view.isZero() && evaluate(view, sharpness, out_positions, out_normals, hint);
  }
  if (out_positions.size() != base_.positions.size()) return false;
  if (!out_normals.empty() && out_normals.size() != base_.positions.size()) return false;
  static_assert(kMaxPositionKeys <= ViewSphere::kRbfMaxKeys);
  std::array<float, ViewSphere::kRbfMaxKeys + 1> buffer;
  const std::span<float> dense(buffer.data(), keys_.size() + 1);
  int local_hint = hint ? *hint : -1;
  if (!denseWeightsAtEye(eye, sharpness, dense, &local_hint)) return false;
  if (!blendDense(dense, out_positions)) return false;  // cannot fail: the weights come from this model
  if (!out_normals.empty() && !computeVertexNormals(surface_, out_positions, out_normals)) return false;
  if (hint) *hint = local_hint;
  return true;
}

void ViewDependentModel::requireViewDirections(const std::string& where) const {
  if (!key_space_) return;
  throw Error("the 'positions' weight space is not supported by " + where +
              ": it weighs view directions and a positions model weighs eye positions (vdg weights, eval and run "
              "and Python's weights_from_eye evaluate it)");
}

void ViewDependentModel::requireThreeKeyWeights(const std::string& where) const {
  requireNoParts(where);
  requireViewDirections(where);
  if (sphere_.settings().scheme != WeightScheme::Rbf) return;
  throw Error("the 'rbf' weight scheme is not supported by " + where +
              ": it blends at most three keys per view and rbf weighs every key (use 'linear' or 'smooth' there; "
              "vdg weights and the Python module evaluate rbf)");
}

bool ViewDependentModel::keyPositions(std::size_t key, std::span<float> out) const {
  if (key >= keys_.size()) return false;
  ViewWeights w;
  w.key[0] = static_cast<int>(key);
  w.weight[0] = 1.0f;
  return blend(w, out);
}

bool ViewDependentModel::evaluate(const Eigen::Vector3d& view, double sharpness, std::span<float> out_positions,
                                  std::span<float> out_normals, int* hint) const {
  // Every check happens before the first write: sizes here, view/sharpness/hint in a trial
  // weights() on a local hint, which is only stored once everything has succeeded.
  if (out_positions.size() != base_.positions.size()) return false;
  if (!out_normals.empty() && out_normals.size() != base_.positions.size()) return false;
  if (!parts_.empty()) {  // one driving view per part, on the stack (at most kMaxParts + 1)
    std::array<Eigen::Vector3d, kMaxParts + 1> buffer;
    const std::span<Eigen::Vector3d> views(buffer.data(), parts_.size());
    return partViews(view, views) && evaluateParts(views, sharpness, out_positions, out_normals);
  }
  int local_hint = hint ? *hint : -1;
  if (sphere_.settings().scheme == WeightScheme::Rbf) {  // every key: dense weights on the stack
    std::array<float, ViewSphere::kRbfMaxKeys + 1> buffer;
    const std::span<float> dense(buffer.data(), keys_.size() + 1);
    if (!denseWeights(view, sharpness, dense, &local_hint)) return false;
    if (!blendDense(dense, out_positions)) return false;  // cannot fail: the weights come from this sphere
  } else {
    ViewWeights w;
    if (!weights(view, sharpness, w, &local_hint)) return false;
    if (!blend(w, out_positions)) return false;  // cannot fail: w comes from this model's sphere
  }
  if (!out_normals.empty() && !computeVertexNormals(surface_, out_positions, out_normals)) return false;
  if (hint) *hint = local_hint;
  return true;
}

}  // namespace vdg
