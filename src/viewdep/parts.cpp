// Per-part key sets (docs/weights.md, "Per-part key sets"): a model's vertices split into
// parts, each with its own keys and driving view, blended smoothly across the parts' borders.
//
// Each part is Rademacher's view-dependent model (Rademacher 99, sections 3.1-3.2) restricted to
// its keys; the parts are joined by per-vertex masks m_p, a partition of unity, so that with the
// blend written with offsets (3.2.3: the weights sum to 1, so sum_i w_i v^i = base + sum_i w_i
// (v^i - base)) the model evaluates
//   p(v) = base(v) + sum_p m_p(v) sum_{k in p} w_pk(view_p) (key_k(v) - base(v)).
// Each vertex is then still a convex combination of the base and the keys (m_p w_pk >= 0, summing
// to at most 1), so extent() holds. One region following one view and another region another is
// the "cubist" rendering of Chaudhuri, Kalra and Banerjee ("A system for view-dependent animation",
// Eurographics 2004), who drive view-dependent deformations of parts by several cameras.
//
// The masks fall off with the Euclidean distance from each part's selection (a smoothstep over the
// part's border). Euclidean rather than geodesic: the copies of a vertex along a texture or
// material seam (split in the OBJ file, at the same position) get the same mask, so the blend
// opens no crack at a seam, and the falloff also reaches pieces that are not connected to the
// selection (an eye, a separate horn) as a painter's brush does.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <map>
#include <set>
#include <unordered_map>

#include "parts.h"
#include "vdg/geom/error.h"
#include "vdg/geom/normalize.h"

namespace vdg {
namespace {

std::string partLabel(const RawViewDependentModel& raw, std::size_t p) {
  return raw.where() + ": part '" + raw.parts[p].name + "' (parts[" + std::to_string(p) + "])";
}

void validateSelection(const RawViewDependentModel& raw, std::size_t p) {
  const RawPart& part = raw.parts[p];
  const std::string label = partLabel(raw, p);
  const std::size_t nv = raw.base.vertexCount();
  if (!std::isfinite(part.border) || part.border < 0.0)
    throw Error(label + ": 'border' must be a finite distance >= 0, got " + std::to_string(part.border));
  switch (part.select) {
    case RawPart::Select::kVertices:
      if (part.vertices.empty()) throw Error(label + ": selects no vertices (an empty vertex list)");
      for (const std::int32_t v : part.vertices)
        if (v < 0 || static_cast<std::size_t>(v) >= nv)
          throw Error(label + ": vertex " + std::to_string(v) + " is out of range (the base has " + std::to_string(nv) +
                      " vertices)");
      break;
    case RawPart::Select::kMaterial: {
      const auto& materials = raw.base.materials;
      if (std::none_of(materials.begin(), materials.end(), [&](const Material& m) { return m.name == part.material; }))
        throw Error(label + ": the base has no material '" + part.material + "'");
      break;
    }
    case RawPart::Select::kWeights:
      if (part.border != 0.0)
        throw Error(label + ": 'border' applies to vertex and material selections; a painted mask is its own border");
      if (part.mask.size() != nv)
        throw Error(label + ": the mask has " + std::to_string(part.mask.size()) + " values but the base has " +
                    std::to_string(nv) + " vertices");
      for (std::size_t v = 0; v < nv; ++v)
        if (!(part.mask[v] >= 0.0f && part.mask[v] <= 1.0f))
          throw Error(label + ": vertex " + std::to_string(v) + ": mask value " + std::to_string(part.mask[v]) +
                      " is outside [0, 1]");
      break;
  }
}

// The selected vertices of a vertex or material part.
std::vector<std::size_t> selectedVertices(const RawViewDependentModel& raw, const RawPart& part) {
  std::vector<std::uint8_t> chosen(raw.base.vertexCount(), 0);
  if (part.select == RawPart::Select::kVertices) {
    for (const std::int32_t v : part.vertices) chosen[static_cast<std::size_t>(v)] = 1;
  } else {
    const TriMesh& base = raw.base;
    for (std::size_t t = 0; t < base.face_materials.size(); ++t) {
      const std::int32_t m = base.face_materials[t];
      if (m < 0 || base.materials[static_cast<std::size_t>(m)].name != part.material) continue;
      for (std::size_t c = 0; c < 3; ++c) chosen[static_cast<std::size_t>(base.triangles[3 * t + c])] = 1;
    }
  }
  std::vector<std::size_t> out;
  for (std::size_t v = 0; v < chosen.size(); ++v)
    if (chosen[v]) out.push_back(v);
  return out;
}

// s(v) = 1 - S(d / border), S(t) = 3t^2 - 2t^3, d the distance to the nearest selected vertex,
// found through a uniform grid of cell h >= border over the selection (27 cells per vertex). A
// zero border keeps 1 on the selection and at the same positions, 0 elsewhere.
std::vector<float> selectionWeights(const RawViewDependentModel& raw, const RawPart& part) {
  const std::vector<float>& pos = raw.base.positions;
  const std::size_t nv = raw.base.vertexCount();
  const std::vector<std::size_t> selected = selectedVertices(raw, part);
  const Bounds box = computeBounds(pos);
  double extent = 0.0;
  for (int c = 0; c < 3; ++c) extent = std::max(extent, static_cast<double>(box.max[c] - box.min[c]));
  // At most 2^20 cells a side, so that a cell's coordinates pack into 21 bits each.
  constexpr double kMaxCellsPerSide = 1 << 20;
  const double h = std::max({part.border, extent / kMaxCellsPerSide, 1e-30});
  const auto cell = [&](std::size_t v, int c) {
    return static_cast<std::int64_t>(std::floor((pos[3 * v + c] - box.min[c]) / h));
  };
  const auto pack = [](std::int64_t x, std::int64_t y, std::int64_t z) {
    return static_cast<std::uint64_t>(((x + 1) << 42) | ((y + 1) << 21) | (z + 1));
  };
  std::unordered_map<std::uint64_t, std::vector<std::size_t>> grid;
  for (const std::size_t v : selected) grid[pack(cell(v, 0), cell(v, 1), cell(v, 2))].push_back(v);
  std::vector<float> s(nv, 0.0f);
  for (std::size_t v = 0; v < nv; ++v) {
    const std::int64_t x = cell(v, 0), y = cell(v, 1), z = cell(v, 2);
    double best = part.border * part.border;
    bool at_selection = false;
    for (std::int64_t dx = -1; dx <= 1; ++dx)
      for (std::int64_t dy = -1; dy <= 1; ++dy)
        for (std::int64_t dz = -1; dz <= 1; ++dz) {
          if (x + dx < 0 || y + dy < 0 || z + dz < 0) continue;
          const auto it = grid.find(pack(x + dx, y + dy, z + dz));
          if (it == grid.end()) continue;
          for (const std::size_t u : it->second) {
            double d2 = 0.0;
            for (int c = 0; c < 3; ++c) {
              const double d = static_cast<double>(pos[3 * u + c]) - pos[3 * v + c];
              d2 += d * d;
            }
            at_selection = at_selection || d2 == 0.0;
            best = std::min(best, d2);
          }
        }
    if (at_selection) {
      s[v] = 1.0f;
    } else if (part.border > 0.0 && best < part.border * part.border) {
      const double t = std::sqrt(best) / part.border;
      s[v] = static_cast<float>(1.0 - t * t * (3.0 - 2.0 * t));
    }
  }
  return s;
}

}  // namespace

namespace detail {

namespace {
// Two keys of one part with the same view (within kSameViewRad) cannot share its sphere.
void checkPartViews(const std::string& label, std::span<const std::string> keys,
                    std::span<const Eigen::Vector3d> views) {
  forEachCloseViewPair(views, ViewSphere::kSameViewRad, [&](std::size_t i, std::size_t j, double) -> bool {
    throw Error(label + ": key '" + keys[i] + "' has the same view direction as key '" + keys[j] +
                "' (within 1e-6 rad)");
  });
}
}  // namespace

void validateParts(const RawViewDependentModel& raw, bool check_view_pairs) {
  if (raw.parts.empty()) return;
  if (raw.animated())
    throw Error(raw.where() + ": model parts ('parts') are not supported with an animated base ('base_animation')");
  if (raw.parts.size() > kMaxParts)
    throw Error(raw.where() + ": " + std::to_string(raw.parts.size()) + " parts; a model may have at most " +
                std::to_string(kMaxParts));
  std::map<std::string, std::size_t> key_index;
  for (std::size_t k = 0; k < raw.keys.size(); ++k) key_index.emplace(raw.keys[k].name, k);
  std::map<std::string, std::size_t> owner;  // key name -> part
  std::set<std::string> names;
  for (std::size_t p = 0; p < raw.parts.size(); ++p) {
    const RawPart& part = raw.parts[p];
    const std::string label = partLabel(raw, p);
    if (part.name.empty()) throw Error(raw.where() + ": parts[" + std::to_string(p) + "] has an empty name");
    if (part.name == kRestPartName)
      throw Error(label + ": the name '" + std::string(kRestPartName) +
                  "' is the implicit part of the vertices outside every part");
    if (!names.insert(part.name).second) throw Error(label + ": another part has the same name");
    validateSelection(raw, p);
    if (part.keys.empty()) throw Error(label + ": has no keys (give the names of its keys in 'keys')");
    std::vector<Eigen::Vector3d> views;
    for (const std::string& key : part.keys) {
      if (!key_index.count(key)) throw Error(label + ": unknown key '" + key + "'");
      const auto [it, fresh] = owner.emplace(key, p);
      if (!fresh)
        throw Error(label + ": key '" + key + "' already belongs to part '" + raw.parts[it->second].name +
                    "' (a key belongs to at most one part)");
      views.push_back(*normalizedOrNone(raw.keys[key_index[key]].view));
    }
    if (part.view && (!part.view->allFinite() || !normalizedOrNone(*part.view)))
      throw Error(label + ": the driving 'view' must be a finite, non-zero direction");
    if (check_view_pairs) checkPartViews(label, part.keys, views);
  }
  if (!check_view_pairs) return;
  std::vector<std::string> rest;  // the keys of no part drive the rest
  std::vector<Eigen::Vector3d> views;
  for (const RawKey& key : raw.keys)
    if (!owner.count(key.name)) {
      rest.push_back(key.name);
      views.push_back(*normalizedOrNone(key.view));
    }
  checkPartViews(raw.where() + ": part '" + kRestPartName + "' (the keys of no part)", rest, views);
}

}  // namespace detail

std::vector<std::vector<float>> computePartMasks(const RawViewDependentModel& raw) {
  if (raw.parts.empty()) return {};
  const std::size_t nv = raw.base.vertexCount(), np = raw.parts.size();
  std::vector<std::vector<float>> masks(np + 1);
  for (std::size_t p = 0; p < np; ++p) {
    const RawPart& part = raw.parts[p];
    masks[p] = part.select == RawPart::Select::kWeights ? part.mask : selectionWeights(raw, part);
  }
  std::vector<float>& rest = masks[np];
  rest.assign(nv, 0.0f);
  for (std::size_t v = 0; v < nv; ++v) {
    double sum = 0.0;
    for (std::size_t p = 0; p < np; ++p) sum += masks[p][v];
    // m_p = s_p / max(1, sum): overlapping parts share a vertex; the rest takes what is left.
    if (sum > 1.0)
      for (std::size_t p = 0; p < np; ++p) masks[p][v] = static_cast<float>(masks[p][v] / sum);
    double taken = 0.0;
    for (std::size_t p = 0; p < np; ++p) taken += masks[p][v];
    rest[v] = static_cast<float>(std::clamp(1.0 - taken, 0.0, 1.0));
  }
  return masks;
}

void ViewDependentModel::buildParts(const RawViewDependentModel& raw, std::span<const std::string> labels) {
  const std::vector<std::vector<float>> masks = computePartMasks(raw);
  const std::size_t np = raw.parts.size();
  std::map<std::string, std::size_t> key_index;
  for (std::size_t k = 0; k < raw.keys.size(); ++k) key_index.emplace(raw.keys[k].name, k);
  std::vector<std::size_t> part_of_key(raw.keys.size(), np);
  parts_.resize(np + 1);
  for (std::size_t p = 0; p < np; ++p) {
    parts_[p].name = raw.parts[p].name;
    if (raw.parts[p].view) parts_[p].view = normalizedOrNone(*raw.parts[p].view);
    for (const std::string& key : raw.parts[p].keys) {
      parts_[p].keys.push_back(key_index.at(key));
      part_of_key[key_index.at(key)] = p;
    }
  }
  parts_[np].name = kRestPartName;
  for (std::size_t k = 0; k < raw.keys.size(); ++k)
    if (part_of_key[k] == np) parts_[np].keys.push_back(k);
  for (std::size_t p = 0; p <= np; ++p) {
    Part& part = parts_[p];
    part.vertex_count =
        static_cast<std::size_t>(std::count_if(masks[p].begin(), masks[p].end(), [](float m) { return m > 0.0f; }));
    if (part.keys.empty()) continue;
    std::vector<Eigen::Vector3d> views;
    std::vector<std::string> part_labels;
    for (const std::size_t k : part.keys) {
      views.push_back(raw.keys[k].view);
      part_labels.push_back(labels[k]);
    }
    try {
      part.sphere = ViewSphere::build(views, raw.sphere, part_labels);
    } catch (const Error& e) {
      throw Error(raw.where() + ": part '" + part.name + "': " + e.what());
    }
  }
  storeDeltas(raw, masks, part_of_key);
}

void ViewDependentModel::requireNoParts(const std::string& where) const {
  if (parts_.empty()) return;
  throw Error("model parts ('parts') are not supported by " + where +
              ": it weighs one key set for the whole mesh (vdg weights, eval, info, the CPU blend of vdg run scenes "
              "and the Python "
              "module evaluate parts)");
}

namespace {
[[noreturn]] void throwPartOutOfRange(std::size_t part, std::size_t count) {
  throw Error("part " + std::to_string(part) + " out of range (the model has " + std::to_string(count) + " parts)");
}
}  // namespace

const std::string& ViewDependentModel::partName(std::size_t part) const {
  if (part >= parts_.size()) throwPartOutOfRange(part, parts_.size());
  return parts_[part].name;
}

std::span<const std::size_t> ViewDependentModel::partKeys(std::size_t part) const {
  if (part >= parts_.size()) throwPartOutOfRange(part, parts_.size());
  return parts_[part].keys;
}

const std::optional<Eigen::Vector3d>& ViewDependentModel::partView(std::size_t part) const {
  if (part >= parts_.size()) throwPartOutOfRange(part, parts_.size());
  return parts_[part].view;
}

std::size_t ViewDependentModel::partVertexCount(std::size_t part) const {
  if (part >= parts_.size()) throwPartOutOfRange(part, parts_.size());
  return parts_[part].vertex_count;
}

bool ViewDependentModel::partViews(const Eigen::Vector3d& view, std::span<Eigen::Vector3d> out) const {
  if (out.size() != parts_.size()) return false;
  for (std::size_t p = 0; p < parts_.size(); ++p) out[p] = parts_[p].view.value_or(view);
  return true;
}

bool ViewDependentModel::partWeights(std::size_t part, const Eigen::Vector3d& view, double sharpness,
                                     std::span<float> out) const {
  if (part >= parts_.size() || !std::isfinite(sharpness)) return false;
  const Part& pt = parts_[part];
  if (out.size() != pt.keys.size() + 1 || !view.allFinite() || !normalizedOrNone(view)) return false;
  if (!pt.sphere) {
    out[0] = 1.0f;
    return true;
  }
  return pt.sphere->denseWeights(view, sharpness > 0.0 ? sharpness : sharpness_, out);
}

void ViewDependentModel::addKey(std::size_t k, float weight, float* out) const {
  if (weight == 0.0f) return;
  const Key& key = keys_[k];
  if (key.dense) {
    const auto n = static_cast<Eigen::Index>(base_.positions.size());
    Eigen::Map<Eigen::ArrayXf>(out, n) += weight * Eigen::Map<const Eigen::ArrayXf>(key.deltas.data(), n);
    return;
  }
  ViewWeights one;
  one.key[0] = static_cast<int>(k);
  one.weight[0] = weight;
  scatterSparse(one, out);
}

// p(v) = base(v) + sum_p m_p(v) sum_{k in p} w_pk(view_p) (key_k(v) - base(v)) (Rademacher 99,
// 3.2.3, per part; the masks are already in the stored deltas).
bool ViewDependentModel::evaluateParts(std::span<const Eigen::Vector3d> views, double sharpness,
                                       std::span<float> out_positions, std::span<float> out_normals) const {
  if (parts_.empty() || views.size() != parts_.size() || !std::isfinite(sharpness)) return false;
  if (out_positions.size() != base_.positions.size()) return false;
  if (!out_normals.empty() && out_normals.size() != base_.positions.size()) return false;
  for (const Eigen::Vector3d& view : views)
    if (!view.allFinite() || !normalizedOrNone(view)) return false;
  const double alpha = sharpness > 0.0 ? sharpness : sharpness_;
  std::memcpy(out_positions.data(), base_.positions.data(), base_.positions.size() * sizeof(float));
  for (std::size_t p = 0; p < parts_.size(); ++p) {
    const Part& part = parts_[p];
    if (!part.sphere) continue;
    if (part.sphere->settings().scheme == WeightScheme::Rbf) {  // every key of the part, on the stack
      std::array<float, ViewSphere::kRbfMaxKeys + 1> buffer;
      const std::span<float> dense(buffer.data(), part.keys.size() + 1);
      // Cannot fail: the view and sharpness are checked above, the size is the sphere's.
      if (!part.sphere->denseWeights(views[p], alpha, dense)) return false;
      for (std::size_t i = 0; i < part.keys.size(); ++i) addKey(part.keys[i], dense[i], out_positions.data());
      continue;
    }
    ViewWeights w;
    if (!part.sphere->weights(views[p], alpha, w)) return false;  // cannot fail, as above
    for (int slot = 0; slot < 3; ++slot)
      if (w.key[slot] >= 0)
        addKey(part.keys[static_cast<std::size_t>(w.key[slot])], w.weight[slot], out_positions.data());
  }
  return out_normals.empty() || computeVertexNormals(surface_, out_positions, out_normals);
}

}  // namespace vdg
