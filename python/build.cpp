// vdg.Camera, vdg.Key and vdg.build: a view-dependent model from numpy arrays (Rademacher 99,
// section 3.1: a base mesh, key deformations and their key views; section 4.1: keys at frames of an
// animated base). The arrays become a RawViewDependentModel, which the library validates and builds
// exactly as it does a manifest's (RawViewDependentModel::validate's messages become vdg.Error).
#include <cmath>

#include "binding.h"
#include "vdg/geom/error.h"
#include "vdg/geom/normalize.h"
#include "vdg/io/image_file.h"
#include "vdg/io/manifest.h"
#include "vdg/viewdep/view_sphere.h"

namespace vdg::python {
namespace {

Camera cameraFromDict(const py::dict& d, const std::string& what) {
  for (const auto& item : d) {
    const std::string field = py::str(item.first).cast<std::string>();
    if (field != "eye" && field != "target" && field != "up" && field != "fov_deg" && field != "ortho_height")
      throw py::value_error(what + ": unknown field '" + field + "' (expected eye, target, up, fov_deg, ortho_height)");
  }
  if (!d.contains("eye") || !d.contains("target")) throw py::value_error(what + ": needs 'eye' and 'target'");
  const py::object up = d.contains("up") ? py::object(d["up"]) : py::object(py::make_tuple(0.0, 1.0, 0.0));
  const double fov = d.contains("fov_deg") ? finiteNumber(d["fov_deg"], what + ".fov_deg") : 40.0;
  const double ortho = d.contains("ortho_height") ? finiteNumber(d["ortho_height"], what + ".ortho_height") : 0.0;
  return makeCamera(d["eye"], d["target"], up, fov, ortho);
}

// A key given as a vdg.Key or as a dict {"name", "positions", "view" or "camera", "frame"}.
Key keyFrom(py::handle item, std::size_t index) {
  const std::string what = "keys[" + std::to_string(index) + "]";
  if (py::isinstance<Key>(item)) return item.cast<Key>();
  if (!py::isinstance<py::dict>(item))
    throw py::type_error(what + ": expected a vdg.Key or a dict, got " +
                         py::str(py::type::of(item)).cast<std::string>());
  const py::dict d = py::reinterpret_borrow<py::dict>(item);
  for (const auto& entry : d) {
    const std::string field = py::str(entry.first).cast<std::string>();
    if (field != "name" && field != "positions" && field != "view" && field != "camera" && field != "frame")
      throw py::value_error(what + ": unknown field '" + field + "' (expected name, positions, view, camera, frame)");
  }
  if (!d.contains("name") || !py::isinstance<py::str>(d["name"])) throw py::type_error(what + ": 'name' must be a str");
  if (!d.contains("positions")) throw py::value_error(what + ": needs 'positions'");
  py::object camera = py::none();
  if (d.contains("camera")) {
    camera = d["camera"];
    if (py::isinstance<py::dict>(camera))
      camera = py::cast(cameraFromDict(py::reinterpret_borrow<py::dict>(camera), what + ".camera"));
  }
  return makeKey(d["name"].cast<std::string>(), d["positions"],
                 d.contains("view") ? py::object(d["view"]) : py::object(py::none()), camera,
                 d.contains("frame") ? py::object(d["frame"]) : py::object(py::int_(0)));
}

Uncovered uncoveredFrom(const std::string& name) {
  for (const Uncovered u : {Uncovered::Base, Uncovered::Cosine, Uncovered::Cosine2})
    if (name == uncoveredName(u)) return u;
  throw py::value_error("uncovered: expected 'base', 'cosine' or 'cosine2', got '" + name + "'");
}

WeightScheme schemeFrom(const std::string& name) {
  for (const WeightScheme w : {WeightScheme::Linear, WeightScheme::Smooth, WeightScheme::Rbf})
    if (name == weightSchemeName(w)) return w;
  throw py::value_error("scheme: expected 'linear', 'smooth' or 'rbf', got '" + name + "'");
}

// The rbf scheme's kernel and width (None: the defaults); refused for another scheme.
void setRbfSettings(ViewSphereSettings& sphere, const py::object& kernel, const py::object& width) {
  if (sphere.scheme != WeightScheme::Rbf) {
    if (!kernel.is_none() || !width.is_none())
      throw py::value_error("kernel, width: settings of the 'rbf' scheme only");
    return;
  }
  if (!kernel.is_none()) {
    const std::string name = kernel.cast<std::string>();
    bool known = false;
    for (const RbfKernel k : {RbfKernel::Gaussian, RbfKernel::InverseMultiquadric, RbfKernel::Wendland})
      if (name == rbfKernelName(k)) sphere.rbf_kernel = k, known = true;
    if (!known)
      throw py::value_error("kernel: expected 'gaussian', 'inverse-multiquadric' or 'wendland', got '" + name + "'");
  }
  if (!width.is_none()) {
    const double degrees = width.cast<double>();
    if (!(degrees > 0.0 && degrees <= 180.0))
      throw py::value_error("width: expected degrees in (0, 180], got " + std::to_string(degrees));
    sphere.rbf_width_deg = degrees;
  }
}

// The animated base of build(frames=...): frames[0] is the base; saved as an OBJ sequence.
void setFrames(RawViewDependentModel& raw, const BuildArgs& args, const std::vector<float>& base) {
  const py::array a = py::module_::import("numpy").attr("asarray")(args.frames);
  const auto n = static_cast<py::ssize_t>(base.size() / 3);
  if (a.ndim() != 3 || a.shape(0) < 1 || a.shape(1) != n || a.shape(2) != 3)
    throw py::value_error("frames: expected shape (F, " + std::to_string(n) + ", 3) with F >= 1, got " +
                          py::str(a.attr("shape")).cast<std::string>());
  const std::vector<float> all = floatRows(a.attr("reshape")(-1, 3), -1, 3, "frames");
  const auto frame_count = static_cast<std::size_t>(a.shape(0));
  if (frame_count > kMaxBaseFrames)
    throw py::value_error("frames: at most " + std::to_string(kMaxBaseFrames) + " frames, got " +
                          std::to_string(frame_count));
  const std::size_t size = base.size();
  if (!std::equal(base.begin(), base.end(), all.begin()))
    throw py::value_error("base: differs from frames[0]; an animated model's base is its first frame");
  if (!std::isfinite(args.fps) || args.fps <= 0.0)
    throw py::value_error("fps: expected a number > 0, got " + std::to_string(args.fps));
  BaseAnimationSpec spec;
  spec.obj_sequence = "base_%04d.obj";  // save_manifest writes the sequence under its mesh folder
  spec.first = 0;
  spec.last = static_cast<int>(frame_count) - 1;
  spec.fps = args.fps;
  spec.loop = args.loop;
  raw.base_animation = spec;
  for (std::size_t f = 0; f < frame_count; ++f)
    raw.base_frames.emplace_back(all.begin() + static_cast<std::ptrdiff_t>(f * size),
                                 all.begin() + static_cast<std::ptrdiff_t>((f + 1) * size));
}

}  // namespace

Camera makeCamera(py::handle eye, py::handle target, py::handle up, double fov_deg, double ortho_height) {
  Camera camera;
  camera.eye = vector3(eye, "eye");
  camera.target = vector3(target, "target");
  camera.up = vector3(up, "up");
  camera.fov_deg = fov_deg;
  camera.ortho_height = ortho_height;
  if (!std::isfinite(fov_deg) || !(fov_deg > 0.0 && fov_deg < 180.0))
    throw py::value_error("fov_deg: expected a field of view in (0, 180) degrees, got " + std::to_string(fov_deg));
  if (!std::isfinite(ortho_height) || ortho_height < 0.0)
    throw py::value_error("ortho_height: expected 0 (perspective) or a height > 0, got " +
                          std::to_string(ortho_height));
  cameraFrame(camera);  // throws vdg::Error for eye == target or an up along the view axis
  return camera;
}

Key makeKey(const std::string& name, py::handle positions, py::handle view, py::handle camera, py::handle frame) {
  Key key;
  key.name = name;
  const std::string what = "key '" + name + "'";
  key.positions = floatRows(positions, -1, 3, what + ": positions");
  if (view.is_none() && camera.is_none()) throw py::value_error(what + ": give a view or a camera");
  if (!camera.is_none()) {
    if (!py::isinstance<Camera>(camera))
      throw py::type_error(what + ": camera must be a vdg.Camera, got " +
                           py::str(py::type::of(camera)).cast<std::string>());
    key.camera = camera.cast<Camera>();
  }
  // A camera's key view is normalize(eye - centre), known when the model is built (its centre).
  const Eigen::Vector3d v = view.is_none() ? key.camera->eye : viewVector(view, what + ": view");
  key.view = normalizedOrNone(v).value_or(Eigen::Vector3d::UnitZ());
  const long long f = integerArg(frame, what + ": frame");
  if (f < 0 || f >= static_cast<long long>(kMaxBaseFrames))
    throw py::value_error(what + ": frame: expected a frame >= 0, got " + std::to_string(f));
  key.frame = static_cast<int>(f);
  return key;
}

void buildRuntime(Model& m) {
  if (m.raw.animated())
    m.animated = std::make_shared<const AnimatedViewDependentModel>(AnimatedViewDependentModel::build(m.raw));
  else
    m.model = std::make_shared<const ViewDependentModel>(ViewDependentModel::build(m.raw));
}

namespace {
// corner_uvs (T, 3, 2) into base.uvs / uv_triangles (one uv per corner).
void setCornerUvs(TriMesh& base, py::handle corner_uvs) {
  const py::array a = py::module_::import("numpy").attr("asarray")(corner_uvs);
  const auto t = static_cast<py::ssize_t>(base.triangleCount());
  if (a.ndim() != 3 || a.shape(0) != t || a.shape(1) != 3 || a.shape(2) != 2)
    throw py::value_error("corner_uvs: expected shape (" + std::to_string(t) +
                          ", 3, 2) (one (u, v) per triangle corner)");
  base.uvs = floatRows(a.attr("reshape")(-1, 2), 3 * t, 2, "corner_uvs");
  for (float value : base.uvs)
    if (!std::isfinite(value)) throw py::value_error("corner_uvs: expected finite values");
  base.uv_triangles.resize(base.triangles.size());
  for (std::size_t c = 0; c < base.uv_triangles.size(); ++c) base.uv_triangles[c] = static_cast<std::int32_t>(c);
}

// One of vdg.build's materials: a dict {"name", "base_color", "texture", "texture_path"}.
Material materialFrom(py::handle item, std::size_t index) {
  const std::string what = "materials[" + std::to_string(index) + "]";
  if (!py::isinstance<py::dict>(item)) throw py::type_error(what + ": expected a dict");
  const py::dict d = py::reinterpret_borrow<py::dict>(item);
  Material m;
  m.name = d.contains("name") ? py::str(d["name"]).cast<std::string>() : "material" + std::to_string(index);
  if (d.contains("base_color")) {
    const std::vector<double> c = doubleRows(d["base_color"], 3, -1, what + ".base_color");
    for (std::size_t k = 0; k < 3; ++k) {
      if (!(c[k] >= 0.0 && c[k] <= 1.0))
        throw py::value_error(what + ".base_color: expected display RGB values in [0, 1]");
      m.base_color[k] = static_cast<float>(c[k]);
    }
  }
  if (d.contains("texture") && !d["texture"].is_none()) {
    if (!py::isinstance<py::bytes>(d["texture"]))
      throw py::type_error(what + ".texture: expected the bytes of a PNG or JPEG file, or None");
    const std::string bytes = d["texture"].cast<std::string>();
    auto image = std::make_shared<TextureImage>(decodeImage(bytes, what + ".texture"));
    image->file_bytes = bytes;
    m.texture_path = imageFormatOf(bytes) == ImageFormat::kPng ? "texture.png" : "texture.jpg";
    m.texture = std::move(image);
  }
  if (d.contains("texture_path") && !d["texture_path"].is_none() && m.texture)
    m.texture_path = py::str(d["texture_path"]).cast<std::string>();
  return m;
}

// materials and face_materials into the base (both or neither).
void setMaterials(TriMesh& base, py::handle materials, py::handle face_materials) {
  if (materials.is_none() != face_materials.is_none())
    throw py::value_error("materials, face_materials: give both or neither");
  if (materials.is_none()) return;
  if (!py::isinstance<py::list>(materials) && !py::isinstance<py::tuple>(materials))
    throw py::type_error("materials: expected a list of dicts");
  std::size_t index = 0;
  for (const py::handle item : materials) base.materials.push_back(materialFrom(item, index++));
  // Integers of any width, -1 allowed (intRows takes indices >= 0): checked as int64 first.
  const py::array a = py::module_::import("numpy").attr("asarray")(face_materials);
  const auto t_count = static_cast<py::ssize_t>(base.triangleCount());
  if (a.dtype().kind() != 'i' && a.dtype().kind() != 'u')
    throw py::type_error("face_materials: expected integers, got dtype " + py::str(a.dtype()).cast<std::string>());
  if (a.ndim() != 1 || a.shape(0) != t_count)
    throw py::value_error("face_materials: expected shape (" + std::to_string(t_count) + ",)");
  const auto values = py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>::ensure(a);
  if (!values) throw py::type_error("face_materials: cannot convert the array's values");
  for (py::ssize_t t = 0; t < t_count; ++t) {
    const std::int64_t v = values.data()[t];
    if (v < -1 || v >= static_cast<std::int64_t>(base.materials.size()))
      throw py::value_error("face_materials[" + std::to_string(t) + "]: expected -1 (none) or a material index below " +
                            std::to_string(base.materials.size()) + ", got " + std::to_string(v));
    base.face_materials.push_back(static_cast<std::int32_t>(v));
  }
}
}  // namespace

Model buildModel(const BuildArgs& args) {
  Model m;
  RawViewDependentModel& raw = m.raw;
  const bool animated = !args.frames.is_none();
  py::object base_obj = args.base;
  if (base_obj.is_none() && animated) base_obj = py::module_::import("numpy").attr("asarray")(args.frames)[py::int_(0)];
  raw.base.positions = floatRows(base_obj, -1, 3, "base");
  const auto n = static_cast<py::ssize_t>(raw.base.vertexCount());
  raw.base.triangles = intRows(args.triangles, -1, 3, "triangles");
  if (!args.uvs.is_none()) {
    raw.base.uvs = floatRows(args.uvs, n, 2, "uvs");
    raw.base.uv_triangles = raw.base.triangles;
  }
  if (!args.corner_uvs.is_none()) {
    if (!args.uvs.is_none()) throw py::value_error("uvs, corner_uvs: give one of them, not both");
    setCornerUvs(raw.base, args.corner_uvs);
  }
  setMaterials(raw.base, args.materials, args.face_materials);
  validateMesh(raw.base, "build: base");
  raw.sharpness = args.sharpness;
  raw.sphere.uncovered = uncoveredFrom(args.uncovered);
  raw.sphere.scheme = schemeFrom(args.scheme);
  setRbfSettings(raw.sphere, args.kernel, args.width);
  raw.sphere.base_falloff_deg = args.base_falloff_deg;
  if (!args.center.is_none()) raw.center = vector3(args.center, "center");
  raw.comment = args.comment;
  if (animated) setFrames(raw, args, raw.base.positions);
  if (!py::isinstance<py::list>(args.keys) && !py::isinstance<py::tuple>(args.keys))
    throw py::type_error("keys: expected a list of vdg.Key or dict");
  std::size_t index = 0;
  for (const py::handle item : args.keys) {
    const Key key = keyFrom(item, index++);
    if (key.positions.size() != raw.base.positions.size())
      throw py::value_error("key '" + key.name + "': positions: expected shape (" + std::to_string(n) +
                            ", 3) (the base's vertices), got (" + std::to_string(key.positions.size() / 3) + ", 3)");
    RawKey r;
    r.name = key.name;
    r.mesh = raw.base;
    r.mesh.positions = key.positions;
    r.view = key.view;
    r.camera = key.camera;
    r.frame = key.frame;
    raw.keys.push_back(std::move(r));
  }
  raw.resolveViews();
  buildRuntime(m);  // validates: names, views, frames, finite coordinates (vdg::Error)
  return m;
}

}  // namespace vdg::python
