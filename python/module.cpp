// The Python module `vdg`: view-dependent models (Rademacher, SIGGRAPH 99) from Python, numpy
// arrays in and out (docs/python.md). The classes and functions are declared here with their
// docstrings; the work is in arrays.cpp, model.cpp, build.cpp and files.cpp (binding.h).
#include <pybind11/stl.h>

#include <string>
#include <vector>

#include "binding.h"
#include "vdg/geom/error.h"
#include "vdg/version.h"

namespace vdg::python {
namespace {

py::object cameraOrNone(const std::optional<Camera>& camera) { return camera ? py::cast(*camera) : py::none(); }

void bindCamera(py::module_& m) {
  py::class_<Camera>(m, "Camera", R"(A key camera: eye, target and up in model space (right-handed, Y up).

Perspective with a vertical field of view fov_deg in (0, 180) when ortho_height is 0, parallel
(orthographic) with that visible height when ortho_height > 0. A key made from a camera takes its
view direction from the eye: normalize(eye - model centre).)")
      .def(py::init([](py::handle eye, py::handle target, py::handle up, double fov_deg, double ortho_height) {
             return makeCamera(eye, target, up, fov_deg, ortho_height);
           }),
           py::arg("eye"), py::arg("target"), py::arg("up") = py::make_tuple(0.0, 1.0, 0.0), py::arg("fov_deg") = 40.0,
           py::arg("ortho_height") = 0.0,
           "Camera(eye, target, up=(0, 1, 0), fov_deg=40.0, ortho_height=0.0). Raises ValueError for a wrong "
           "shape, a non-finite value or a field of view outside (0, 180); vdg.Error when eye == target or up "
           "lies along the view axis.")
      .def_property_readonly(
          "eye", [](const Camera& c) { return vectorArray(c.eye); }, "Eye position, (3,) float64.")
      .def_property_readonly(
          "target", [](const Camera& c) { return vectorArray(c.target); }, "Point looked at, (3,) float64.")
      .def_property_readonly(
          "up", [](const Camera& c) { return vectorArray(c.up); }, "Up direction, (3,) float64.")
      .def_property_readonly(
          "fov_deg", [](const Camera& c) { return c.fov_deg; }, "Vertical field of view (degrees).")
      .def_property_readonly(
          "ortho_height", [](const Camera& c) { return c.ortho_height; },
          "0 for perspective, else the visible height of a parallel camera.")
      .def("__repr__", [](const Camera& c) {
        return "<vdg.Camera eye=(" + std::to_string(c.eye.x()) + ", " + std::to_string(c.eye.y()) + ", " +
               std::to_string(c.eye.z()) + ")>";
      });
}

void bindKey(py::module_& m) {
  py::class_<Key>(m, "Key", R"(A key deformation (Rademacher 99, section 3.1): the base's vertices moved,
seen from a key view, at a frame of an animated base (section 4; 0 for a static base).)")
      .def(py::init(&makeKey), py::arg("name"), py::arg("positions"), py::arg("view") = py::none(),
           py::arg("camera") = py::none(), py::arg("frame") = 0,
           "Key(name, positions, view=None, camera=None, frame=0): positions (V, 3); a view direction (3,) "
           "towards the eye, or a vdg.Camera whose eye gives it once the model is built. Raises ValueError "
           "for a wrong shape, a zero or non-finite view, neither view nor camera, a negative frame; TypeError "
           "for non-numeric arrays.")
      .def_readonly("name", &Key::name, "The key's name (unique within a model).")
      .def_property_readonly(
          "positions",
          [](const Key& k) {
            return floatArray(k.positions.data(), static_cast<py::ssize_t>(k.positions.size() / 3), 3);
          },
          "The key mesh's positions, (V, 3) float32 (a copy).")
      .def_property_readonly(
          "view", [](const Key& k) { return vectorArray(k.view); },
          "Unit key view direction (towards the eye), (3,) float64.")
      .def_readonly("frame", &Key::frame, "Frame of the base animation the key deforms (0 when static).")
      .def_property_readonly(
          "camera", [](const Key& k) { return cameraOrNone(k.camera); },
          "The key camera, or None for a key given by its view.")
      .def("__repr__", [](const Key& k) {
        return "<vdg.Key '" + k.name + "': " + std::to_string(k.positions.size() / 3) + " vertices, frame " +
               std::to_string(k.frame) + ">";
      });
  py::class_<SphereView>(m, "ViewSphere", R"(The viewing sphere (section 3.2.1): unit points, the key
views first, then dummy base points (uncovered="base"), triangulated by their convex hull.)")
      .def_property_readonly(
          "points",
          [](const SphereView& s) {
            py::array_t<double> out({static_cast<py::ssize_t>(s.points.size() / 3), py::ssize_t{3}});
            std::copy(s.points.begin(), s.points.end(), out.mutable_data());
            return out;
          },
          "(P, 3) float64 unit directions.")
      .def_readonly("key_points", &SphereView::key_points,
                    "How many of the points are key views (the rest are dummy base points).")
      .def_property_readonly(
          "triangles",
          [](const SphereView& s) {
            return intArray(s.triangles.data(), static_cast<py::ssize_t>(s.triangles.size() / 3), 3);
          },
          "(H, 3) int32 hull triangles, indices into points.");
}

void bindModelProperties(py::class_<Model>& c) {
  c.def_property_readonly("animated", &Model::isAnimated, "Whether the base is animated (section 4).")
      .def_property_readonly("vertex_count", &Model::vertexCount, "Vertices of the base.")
      .def_property_readonly(
          "frame_count", [](const Model& m) { return m.raw.frameCount(); },
          "Frames of the base animation (1 when static).")
      .def_property_readonly(
          "loop", [](const Model& m) { return m.animated && m.animated->loop(); },
          "Whether the base animation is a cycle.")
      .def_property_readonly(
          "center", [](const Model& m) { return vectorArray(m.center()); },
          "The centre views are measured from, (3,) float64.")
      .def_property_readonly(
          "sharpness", [](const Model& m) { return m.raw.sharpness; }, "The model's sharpness alpha (section 3.2.2).")
      .def_property_readonly(
          "uncovered", [](const Model& m) { return uncoveredName(m.raw.sphere.uncovered); },
          "'base', 'cosine' or 'cosine2' (section 3.3).")
      .def_property_readonly(
          "scheme", [](const Model& m) { return weightSchemeName(m.raw.sphere.scheme); },
          "The weight scheme: 'linear' (the paper's barycentric blend), 'smooth' (C1) or 'rbf' (radial basis "
          "functions over every key, with the manifest's kernel and width; docs/weights.md).")
      .def_property_readonly(
          "kernel",
          [](const Model& m) -> py::object {
            if (m.raw.sphere.scheme != WeightScheme::Rbf) return py::none();
            return py::str(rbfKernelName(m.raw.sphere.rbf_kernel));
          },
          "The rbf scheme's kernel ('gaussian', 'inverse-multiquadric' or 'wendland'); None for another scheme.")
      .def_property_readonly(
          "width",
          [](const Model& m) -> py::object {
            if (m.raw.sphere.scheme != WeightScheme::Rbf) return py::none();
            return py::float_(m.raw.sphere.rbf_width_deg);
          },
          "The rbf scheme's kernel width (degrees); None for another scheme.")
      .def_property_readonly(
          "parts",
          [](const Model& m) {
            std::vector<std::string> names;
            for (const RawPart& part : m.raw.parts) names.push_back(part.name);
            return names;
          },
          "The names of the model's parts (manifest 'parts', per-part key sets; docs/weights.md), without the "
          "implicit 'rest'; empty for a model without parts. weights() of a model with parts returns {'parts': "
          "[{'name', 'view', 'keys', 'base'}, ...]}.")
      .def_property_readonly(
          "base_falloff_deg", [](const Model& m) { return m.raw.sphere.base_falloff_deg; },
          "Angle beyond every key where dummy base points go (uncovered='base').")
      .def_property_readonly(
          "offsets", [](const Model& m) { return offsetSpaceName(m.raw.offsets); },
          "'world' or 'skinned': the space of an animated model's key offsets.")
      .def_property_readonly(
          "comment", [](const Model& m) { return m.raw.comment; }, "The manifest's comment.")
      .def_property_readonly(
          "source", [](const Model& m) { return m.source; }, "The file it was loaded from, or ''.")
      .def_property_readonly(
          "base",
          [](const Model& m) {
            return floatArray(m.raw.base.positions.data(), static_cast<py::ssize_t>(m.vertexCount()), 3);
          },
          "Base positions, (V, 3) float32 (frame 0 of an animated base).")
      .def_property_readonly(
          "triangles",
          [](const Model& m) {
            return intArray(m.raw.base.triangles.data(), static_cast<py::ssize_t>(m.raw.base.triangleCount()), 3);
          },
          "Triangles, (T, 3) int32.")
      .def_property_readonly("uvs", &modelUvs,
                             "Per-vertex texture coordinates, (V, 2) float32, or None (no uvs, or a seam that "
                             "gives one vertex two).")
      .def_property_readonly("corner_uvs", &modelCornerUvs,
                             "Texture coordinates per triangle corner, (T, 3, 2) float32, or None without uvs "
                             "(what a mesh with seams needs; Blender's uv layers are per corner).")
      .def_property_readonly("materials", &modelMaterials,
                             "The base's materials: a list of dicts {'name', 'base_color' (display sRGB r, g, b), "
                             "'texture_path', 'texture' (the PNG or JPEG file's bytes, or None)}.")
      .def_property_readonly("face_materials", &modelFaceMaterials,
                             "Each triangle's material index, (T,) int32 (-1: none), or None without materials.")
      .def_property_readonly("base_frames", &modelBaseFrames, "(F, V, 3) float32 base frames, or None when static.")
      .def_property_readonly("keys", &modelKeys, "The keys (list of vdg.Key) in the model's order.")
      .def_property_readonly("sphere", &modelSphere, "The viewing sphere (vdg.ViewSphere).");
}

void bindModelMethods(py::class_<Model>& c) {
  c.def(
       "view_from_eye", [](const Model& m, py::handle eye) { return vectorArray(modelViewFromEye(m, eye)); },
       py::arg("eye"), "normalize(eye - center): the view direction of an eye position. ValueError at the centre.")
      .def("weights", &modelWeights, py::arg("view"), py::arg("sharpness") = py::none(), py::arg("frame") = py::none(),
           R"(Blending weights of a view direction (towards the eye), as `vdg weights --json`.

Static: {"keys": {name: w for every key}, "base": w}. Animated, frame None: {"views": [{"view",
"keys", "frames", "weight"}, ...], "base": w} (the key views with weight > 0); animated with a frame
(any finite float): {"keys": {name: view weight x time coefficient}, "base": w}. sharpness None
means the model's own. ValueError for a zero or non-finite view or a sharpness <= 0.)")
      .def("weights_from_eye", &modelWeightsFromEye, py::arg("eye"), py::arg("sharpness") = py::none(),
           py::arg("frame") = py::none(),
           "weights(view_from_eye(eye), sharpness, frame); a 'positions' model (keys at distances) weighs the eye "
           "itself, as `vdg weights --eye`.")
      .def("evaluate", &modelEvaluate, py::arg("view"), py::arg("frame") = py::none(),
           py::arg("sharpness") = py::none(),
           "(positions, normals), each (V, 3) float32: the blended mesh at a view (as `vdg eval`) and its "
           "normals. An animated model needs frame (an int in [0, frame_count)); a static one takes None or 0.")
      .def("time_coefficients", &modelTimeCoefficients, py::arg("view_index"), py::arg("frame"),
           "Animated models: the cardinal time coefficients (m,) of the key frames of view view_index at a "
           "frame (section 4.2); the view's offset there is their weighted sum of its key offsets.")
      .def("save_manifest", &saveManifest, py::arg("path"), py::arg("mesh_folder") = "keys",
           "Writes the manifest at path and its meshes (base.obj, one OBJ per key, an animated base's "
           "base_NNNN.obj sequence) under mesh_folder beside it, all in one step: all or nothing.")
      .def("export_gltf", &exportGltf, py::arg("path"), py::arg("compress") = "none",
           py::arg("max_targets") = py::none(),
           "Writes a .glb or .gltf exactly as `vdg export` (compress: 'none', 'quantize', 'meshopt'); returns "
           "the files written.")
      .def("__repr__", &modelRepr);
}

void bindFunctions(py::module_& m) {
  m.def("load", &loadModel, py::arg("path"),
        "Opens a manifest (*.vdg.json) or a glTF file vdg exported as a vdg.Model. Raises vdg.Error with "
        "vdg's message for a missing or invalid file, an OBJ mesh or a plain glTF.");
  m.def(
      "build",
      [](py::object base, py::object triangles, py::object keys, double sharpness, std::string uncovered,
         double base_falloff_deg, py::object center, py::object frames, bool loop, double fps, py::object uvs,
         std::string comment, py::object corner_uvs, py::object materials, py::object face_materials,
         std::string scheme, py::object kernel, py::object width) {
        BuildArgs args;
        args.base = std::move(base);
        args.triangles = std::move(triangles);
        args.keys = std::move(keys);
        args.sharpness = sharpness;
        args.uncovered = std::move(uncovered);
        args.base_falloff_deg = base_falloff_deg;
        args.center = std::move(center);
        args.frames = std::move(frames);
        args.loop = loop;
        args.fps = fps;
        args.uvs = std::move(uvs);
        args.comment = std::move(comment);
        args.corner_uvs = std::move(corner_uvs);
        args.materials = std::move(materials);
        args.face_materials = std::move(face_materials);
        args.scheme = std::move(scheme);
        args.kernel = std::move(kernel);
        args.width = std::move(width);
        return buildModel(args);
      },
      py::arg("base"), py::arg("triangles"), py::arg("keys"), py::kw_only(), py::arg("sharpness") = 1.0,
      py::arg("uncovered") = "base", py::arg("base_falloff_deg") = 60.0, py::arg("center") = py::none(),
      py::arg("frames") = py::none(), py::arg("loop") = false, py::arg("fps") = 24.0, py::arg("uvs") = py::none(),
      py::arg("comment") = "", py::arg("corner_uvs") = py::none(), py::arg("materials") = py::none(),
      py::arg("face_materials") = py::none(), py::arg("scheme") = "linear", py::arg("kernel") = py::none(),
      py::arg("width") = py::none(),
      R"(A model from arrays: base (V, 3), triangles (T, 3), keys (vdg.Key or dicts {"name",
"positions", "view" or "camera", "frame"}). frames (F, V, 3) makes an animated model (section 4; base
must be frames[0] or None). Texture coordinates per vertex (uvs, (V, 2)) or per corner (corner_uvs,
(T, 3, 2)); materials (dicts {"name", "base_color" display RGB in [0, 1], "texture" PNG or JPEG
bytes, "texture_path"}) with face_materials ((T,) indices, -1 none), both or neither. scheme: the weight
scheme, 'linear' (the paper's), 'smooth' (C1) or 'rbf' (every key; docs/weights.md), whose kernel ('gaussian',
the default, 'inverse-multiquadric' or 'wendland') and width (degrees, default 60) are kernel and width (None: the
defaults; refused for another scheme). Raises vdg.Error with vdg's validation message for an invalid model
(duplicate names or views, non-finite coordinates, key frames out of range ...).)");
}

}  // namespace

}  // namespace vdg::python

PYBIND11_MODULE(vdg, m) {
  using namespace vdg::python;  // NOLINT: the module body names the binding functions
  m.doc() = "View-dependent geometry (Rademacher, SIGGRAPH 99): load, evaluate, build and save vdg models.";
  m.attr("__version__") = vdg::versionString();
  py::register_exception<vdg::Error>(m, "Error", PyExc_Exception);
  bindCamera(m);
  bindKey(m);
  py::class_<Model> model(m, "Model", "A view-dependent model, static or on an animated base (vdg.load, vdg.build).");
  bindModelProperties(model);
  bindModelMethods(model);
  bindFunctions(m);
}
