// vdg.Model's queries: the blending weights of a view (Rademacher 99, section 3.2: the view's
// triangle of the key views' hull on the viewing sphere, its sharpened barycentric weights), the
// evaluated mesh (3.2.3), and for an animated base the key frames' time coefficients (section 4.2).
// The numbers are the library's own: the same calls `vdg weights` and `vdg eval` make.
#include <cmath>
#include <span>
#include <vector>

#include "binding.h"
#include "vdg/geom/error.h"
#include "vdg/geom/normalize.h"
#include "vdg/viewdep/view_sphere.h"

namespace vdg::python {
namespace {

[[noreturn]] void refused(const char* what) {
  throw Error(std::string(what) + ": the model refused its arguments (internal error)");
}

ViewWeights viewWeights(const Model& m, const Eigen::Vector3d& view, double sharpness) {
  ViewWeights w;
  const bool ok = m.animated ? m.animated->weights(view, sharpness, w) : m.model->weights(view, sharpness, w);
  if (!ok) refused("weights");
  return w;
}

// Every key's name with 0.0, in the model's order (a dict keeps insertion order).
py::dict zeroKeys(const Model& m) {
  py::dict keys;
  for (const RawKey& key : m.raw.keys) keys[py::str(key.name)] = 0.0;
  return keys;
}

// `vdg weights --json` of an animated model: the key views with a weight above 0.
py::dict animatedViews(const AnimatedViewDependentModel& model, const ViewWeights& w) {
  py::list views;
  for (int k = 0; k < 3; ++k) {
    if (w.key[k] < 0 || w.weight[k] <= 0.0f) continue;
    const auto i = static_cast<std::size_t>(w.key[k]);
    const Eigen::Vector3d& d = model.viewDirection(i);
    py::list names, frames;
    for (std::size_t j = 0; j < model.keyFrames(i).size(); ++j) {
      names.append(model.keyName(i, j));
      frames.append(model.keyFrames(i)[j]);
    }
    py::dict entry;
    entry["view"] = py::make_tuple(d.x(), d.y(), d.z());
    entry["keys"] = names;
    entry["frames"] = frames;
    entry["weight"] = static_cast<double>(w.weight[k]);
    views.append(entry);
  }
  py::dict out;
  out["views"] = views;
  out["base"] = static_cast<double>(w.base);
  return out;
}

// Shape-key values at a (fractional) frame: view weight x the key frame's time coefficient.
py::dict animatedKeysAt(const Model& m, const ViewWeights& w, double frame) {
  const AnimatedViewDependentModel& model = *m.animated;
  py::dict keys = zeroKeys(m);
  std::vector<double> c;
  for (int k = 0; k < 3; ++k) {
    if (w.key[k] < 0) continue;
    const auto i = static_cast<std::size_t>(w.key[k]);
    c.assign(model.keyFrames(i).size(), 0.0);
    if (!model.timeCoefficients(i, frame, c)) refused("weights");
    for (std::size_t j = 0; j < c.size(); ++j)
      keys[py::str(model.keyName(i, j))] = static_cast<double>(w.weight[k]) * c[j];
  }
  py::dict out;
  out["keys"] = keys;
  out["base"] = static_cast<double>(w.base);
  return out;
}

// The frame argument of evaluate(): None or 0 for a static model, an int in range when animated.
int evaluateFrame(const Model& m, py::handle frame) {
  const int n = m.animated ? m.animated->frameCount() : 1;
  if (frame.is_none()) {
    if (m.animated)
      throw py::value_error("frame: the model is animated (" + std::to_string(n) +
                            " frames); give frame=F with F in 0.." + std::to_string(n - 1));
    return 0;
  }
  const long long f = integerArg(frame, "frame");
  if (!m.animated && f != 0)
    throw py::value_error("frame: the model is not animated; frame applies to animated models only, got " +
                          std::to_string(f));
  if (f < 0 || f >= n)
    throw py::value_error("frame: expected a frame in 0.." + std::to_string(n - 1) + " (the model has " +
                          std::to_string(n) + " frames), got " + std::to_string(f));
  return static_cast<int>(f);
}

}  // namespace

// Keys at distances (vdg/viewdep/key_space.h) weigh eye positions; the module's views are directions.
void requirePython(const ViewDependentModel& model) {
  if (model.weightSpace() == WeightSpace::Positions)
    throw py::value_error(
        "the 'positions' weight space is not supported by the Python module: it weighs view directions and the "
        "model weighs eye positions (use Model.weights_from_eye, or vdg eval --eye)");
}

double sharpnessArg(py::handle sharpness) {
  if (sharpness.is_none()) return 0.0;
  const double a = finiteNumber(sharpness, "sharpness");
  if (a <= 0.0) throw py::value_error("sharpness: expected a number > 0, got " + std::to_string(a));
  return a;
}

// A model with parts, as `vdg weights --json`: {"parts": [{"name", "view", "keys", "base"}, ...]},
// each part weighed at its driving view (its fixed view, or `view`).
py::dict partWeights(const ViewDependentModel& model, const Eigen::Vector3d& view, double sharpness) {
  std::vector<Eigen::Vector3d> views(model.partCount());
  if (!model.partViews(view, views)) refused("weights");
  py::list parts;
  for (std::size_t p = 0; p < model.partCount(); ++p) {
    const std::span<const std::size_t> keys = model.partKeys(p);
    std::vector<float> w(keys.size() + 1);
    if (!model.partWeights(p, views[p], sharpness, w)) refused("weights");
    py::dict names;
    for (std::size_t i = 0; i < keys.size(); ++i)
      if (w[i] != 0.0f) names[py::str(model.keyName(keys[i]))] = static_cast<double>(w[i]);
    py::dict part;
    part["name"] = model.partName(p);
    part["view"] = py::make_tuple(views[p].x(), views[p].y(), views[p].z());
    part["keys"] = names;
    part["base"] = static_cast<double>(w.back());
    parts.append(part);
  }
  py::dict out;
  out["parts"] = parts;
  return out;
}

// {"keys": {name: weight, ...}, "base": weight} of a static model's dense weights (every key, the
// base last): every key listed, as zeroKeys() does, with the non-zero weights filled in.
py::dict denseWeightsDict(const Model& m, std::span<const float> dense) {
  py::dict keys = zeroKeys(m);
  for (std::size_t k = 0; k < m.model->keyCount(); ++k)
    if (dense[k] != 0.0f) keys[py::str(m.model->keyName(k))] = static_cast<double>(dense[k]);
  py::dict out;
  out["keys"] = keys;
  out["base"] = static_cast<double>(dense.back());
  return out;
}

py::dict modelWeights(const Model& m, py::handle view, py::handle sharpness, py::handle frame) {
  const Eigen::Vector3d v = viewVector(view, "view");
  const double a = sharpnessArg(sharpness);
  std::optional<double> at;
  if (!frame.is_none()) at = finiteNumber(frame, "frame");
  if (m.animated) {
    const ViewWeights w = viewWeights(m, v, a);
    return at ? animatedKeysAt(m, w, *at) : animatedViews(*m.animated, w);
  }
  if (at && *at != 0.0)
    throw py::value_error("frame: the model is not animated; frame applies to animated models only");
  requirePython(*m.model);
  if (m.model->hasParts()) return partWeights(*m.model, v, a);
  std::vector<float> dense(m.model->keyCount() + 1);  // every scheme's weights, the rbf's over every key
  if (!m.model->denseWeights(v, a, dense)) refused("weights");
  return denseWeightsDict(m, dense);
}

// weights(view_from_eye(eye)); a positions model (keys at distances, key_space.h) weighs the eye
// itself, as `vdg weights --eye`.
py::dict modelWeightsFromEye(const Model& m, py::handle eye, py::handle sharpness, py::handle frame) {
  if (!m.model || m.model->weightSpace() != WeightSpace::Positions)
    return modelWeights(m, vectorArray(modelViewFromEye(m, eye)), sharpness, frame);
  const Eigen::Vector3d e = vector3(eye, "eye");
  const double a = sharpnessArg(sharpness);
  if (!frame.is_none() && finiteNumber(frame, "frame") != 0.0)
    throw py::value_error("frame: the model is not animated; frame applies to animated models only");
  std::vector<float> dense(m.model->keyCount() + 1);
  if (!m.model->denseWeightsAtEye(e, a, dense))
    throw py::value_error("eye: the model centre lies outside the key eyes' hull and gives no view direction");
  return denseWeightsDict(m, dense);
}

py::tuple modelEvaluate(const Model& m, py::handle view, py::handle frame, py::handle sharpness) {
  const Eigen::Vector3d v = viewVector(view, "view");
  const int f = evaluateFrame(m, frame);
  const double a = sharpnessArg(sharpness);
  const auto n = static_cast<py::ssize_t>(m.vertexCount());
  py::array_t<float> positions({n, py::ssize_t{3}}), normals({n, py::ssize_t{3}});
  const std::span<float> p(positions.mutable_data(), static_cast<std::size_t>(3 * n));
  const std::span<float> q(normals.mutable_data(), static_cast<std::size_t>(3 * n));
  if (m.model) requirePython(*m.model);
  bool ok = false;
  {
    // The evaluation touches no Python object: other Python threads run meanwhile.
    const py::gil_scoped_release release;
    ok = m.animated ? m.animated->evaluate(f, v, a, p, q) : m.model->evaluate(v, a, p, q);
  }
  if (!ok) refused("evaluate");
  return py::make_tuple(positions, normals);
}

py::array_t<double> modelTimeCoefficients(const Model& m, py::handle view_index, py::handle frame) {
  if (!m.animated)
    throw py::value_error("time_coefficients: the model is not animated (time coefficients are of animated bases)");
  const long long i = integerArg(view_index, "view_index");
  const auto views = static_cast<long long>(m.animated->viewCount());
  if (i < 0 || i >= views)
    throw py::value_error("view_index: expected a view in 0.." + std::to_string(views - 1) + ", got " +
                          std::to_string(i));
  const double f = finiteNumber(frame, "frame");
  const auto view = static_cast<std::size_t>(i);
  py::array_t<double> out(static_cast<py::ssize_t>(m.animated->keyFrames(view).size()));
  if (!m.animated->timeCoefficients(view, f,
                                    std::span<double>(out.mutable_data(), static_cast<std::size_t>(out.size()))))
    refused("time_coefficients");
  return out;
}

Eigen::Vector3d modelViewFromEye(const Model& m, py::handle eye) {
  const Eigen::Vector3d e = vector3(eye, "eye");
  const std::optional<Eigen::Vector3d> v = normalizedOrNone(e - m.center());
  if (!v) throw py::value_error("eye: the eye is at the model's centre; it gives no view direction");
  return *v;
}

py::list modelKeys(const Model& m) {
  py::list keys;
  for (const RawKey& raw : m.raw.keys) {
    Key key;
    key.name = raw.name;
    key.positions = raw.mesh.positions;
    key.view = normalizedOrNone(raw.view).value_or(raw.view);
    key.frame = raw.frame;
    key.camera = raw.camera;
    keys.append(py::cast(std::move(key)));
  }
  return keys;
}

SphereView modelSphere(const Model& m) {
  const ViewSphere& sphere = m.sphere();
  SphereView out;
  for (const Eigen::Vector3d& p : sphere.points()) out.points.insert(out.points.end(), {p.x(), p.y(), p.z()});
  out.key_points = sphere.keyCount();
  for (const std::array<int, 3>& t : sphere.triangles()) out.triangles.insert(out.triangles.end(), t.begin(), t.end());
  return out;
}

// Per-vertex texture coordinates: when every corner of a vertex uses the same (u, v) (an OBJ whose
// uv indices follow its vertex indices, or seams that do not split a vertex's coordinates).
py::object modelUvs(const Model& m) {
  const TriMesh& base = m.raw.base;
  if (base.uvs.empty() || base.uv_triangles.size() != base.triangles.size()) return py::none();
  const std::size_t n = base.vertexCount();
  std::vector<float> uvs(2 * n, 0.0f);
  std::vector<std::int32_t> from(n, -1);
  for (std::size_t c = 0; c < base.triangles.size(); ++c) {
    const auto v = static_cast<std::size_t>(base.triangles[c]);
    const std::int32_t t = base.uv_triangles[c];
    if (from[v] >= 0 &&
        (base.uvs[2 * static_cast<std::size_t>(from[v])] != base.uvs[2 * static_cast<std::size_t>(t)] ||
         base.uvs[2 * static_cast<std::size_t>(from[v]) + 1] != base.uvs[2 * static_cast<std::size_t>(t) + 1]))
      return py::none();  // a seam splits this vertex's coordinates
    from[v] = t;
    uvs[2 * v] = base.uvs[2 * static_cast<std::size_t>(t)];
    uvs[2 * v + 1] = base.uvs[2 * static_cast<std::size_t>(t) + 1];
  }
  return floatArray(uvs.data(), static_cast<py::ssize_t>(n), 2);
}

py::object modelCornerUvs(const Model& m) {
  const TriMesh& base = m.raw.base;
  if (base.uvs.empty() || base.uv_triangles.size() != base.triangles.size()) return py::none();
  const auto corners = static_cast<py::ssize_t>(base.uv_triangles.size());
  py::array_t<float> out({corners / 3, py::ssize_t{3}, py::ssize_t{2}});
  float* data = out.mutable_data();
  for (std::size_t c = 0; c < base.uv_triangles.size(); ++c) {
    const auto t = static_cast<std::size_t>(base.uv_triangles[c]);
    data[2 * c] = base.uvs[2 * t];
    data[2 * c + 1] = base.uvs[2 * t + 1];
  }
  return out;
}

py::object modelFaceMaterials(const Model& m) {
  const TriMesh& base = m.raw.base;
  if (base.face_materials.empty()) return py::none();
  py::array_t<std::int32_t> out(static_cast<py::ssize_t>(base.face_materials.size()));
  std::copy(base.face_materials.begin(), base.face_materials.end(), out.mutable_data());
  return out;
}

py::list modelMaterials(const Model& m) {
  py::list out;
  for (const Material& material : m.raw.base.materials) {
    py::dict d;
    d["name"] = material.name;
    d["base_color"] = py::make_tuple(material.base_color[0], material.base_color[1], material.base_color[2]);
    d["texture_path"] = material.texture_path;
    if (material.texture && !material.texture->file_bytes.empty())
      d["texture"] = py::bytes(material.texture->file_bytes);
    else
      d["texture"] = py::none();
    out.append(std::move(d));
  }
  return out;
}

py::object modelBaseFrames(const Model& m) {
  if (!m.animated) return py::none();
  const auto frames = static_cast<py::ssize_t>(m.animated->frameCount());
  const auto n = static_cast<py::ssize_t>(m.vertexCount());
  py::array_t<float> out({frames, n, py::ssize_t{3}});
  for (int f = 0; f < frames; ++f) {
    const std::span<const float> p = m.animated->baseFrame(f);
    std::copy(p.begin(), p.end(), out.mutable_data() + static_cast<std::size_t>(f) * p.size());
  }
  return out;
}

std::string modelRepr(const Model& m) {
  std::string name = m.source;
  if (const std::size_t slash = name.find_last_of('/'); slash != std::string::npos) name = name.substr(slash + 1);
  const std::string what = name.empty() ? std::string("<vdg.Model (built): ") : "<vdg.Model '" + name + "': ";
  return what + std::to_string(m.vertexCount()) + " vertices, " + std::to_string(m.raw.keys.size()) + " keys, " +
         (m.animated ? "animated, " + std::to_string(m.animated->frameCount()) + " frames" : std::string("static")) +
         ">";
}

}  // namespace vdg::python
