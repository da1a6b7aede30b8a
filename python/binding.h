// The Python module `vdg` (pybind11): the shared declarations of its source files.
//
//   arrays.cpp   numpy arrays in and out: shape and dtype checks (ValueError, TypeError)
//   model.cpp    vdg.Model: properties, weights, evaluate, the view sphere, time coefficients
//   build.cpp    vdg.Camera, vdg.Key and vdg.build (a model from arrays)
//   files.cpp    vdg.load, Model.save_manifest, Model.export_gltf
//   module.cpp   the module itself: classes, functions, docstrings, vdg.Error
//
// The API is docs/python.md's. Every vdg::Error becomes vdg.Error with vdg's one-line message; a
// wrong shape or an out-of-range argument raises ValueError, a wrong type TypeError (thrown here as
// pybind11::value_error and pybind11::type_error). Nothing is evaluated with unchecked input: the
// library's per-frame functions refuse (return false) what these checks let through, and that
// refusal is reported as vdg.Error "... (internal error)".
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "vdg/geom/camera.h"
#include "vdg/viewdep/animated_model.h"
#include "vdg/viewdep/model.h"

namespace vdg::python {

namespace py = pybind11;

// ---- arrays.cpp ----
// `obj` as a C-contiguous float32 array of shape (rows, cols) (rows < 0: any number of rows),
// copied into a vector (row-major). Raises TypeError naming `what` for an object that is not an
// array of numbers (strings, objects, complex numbers), ValueError for a wrong shape.
std::vector<float> floatRows(py::handle obj, py::ssize_t rows, py::ssize_t cols, const std::string& what);
// The same for float64 values.
std::vector<double> doubleRows(py::handle obj, py::ssize_t rows, py::ssize_t cols, const std::string& what);
// An integer array of shape (rows, cols) whose values fit an int32 (ValueError otherwise).
std::vector<std::int32_t> intRows(py::handle obj, py::ssize_t rows, py::ssize_t cols, const std::string& what);
// A 3-vector (shape (3,)) of finite float64 values (ValueError for NaN or infinity).
Eigen::Vector3d vector3(py::handle obj, const std::string& what);
// A view direction: a 3-vector that is finite and not zero (ValueError naming `what`).
Eigen::Vector3d viewVector(py::handle obj, const std::string& what);
// A finite float (TypeError for a non-number, ValueError for NaN or infinity).
double finiteNumber(py::handle obj, const std::string& what);
// An integer (TypeError for anything that is not an int or a numpy integer; bool is refused).
long long integerArg(py::handle obj, const std::string& what);
// A path: str or os.PathLike (TypeError otherwise).
std::string pathArg(py::handle obj, const std::string& what);

// Arrays out: new numpy arrays owning a copy of the data, shaped (rows, cols).
py::array_t<float> floatArray(const float* data, py::ssize_t rows, py::ssize_t cols);
py::array_t<std::int32_t> intArray(const std::int32_t* data, py::ssize_t rows, py::ssize_t cols);
py::array_t<double> vectorArray(const Eigen::Vector3d& v);

// ---- the objects ----
// A key as Python sees it (vdg.Key): what a RawKey holds without its mesh file name.
struct Key {
  std::string name;
  std::vector<float> positions;                    // #V x 3
  Eigen::Vector3d view = Eigen::Vector3d::Zero();  // unit; from the camera when the key has one
  int frame = 0;
  std::optional<Camera> camera;
};

// The viewing sphere's points and hull (vdg.ViewSphere), copied from the built model.
struct SphereView {
  std::vector<double> points;  // P x 3
  std::size_t key_points = 0;
  std::vector<std::int32_t> triangles;  // H x 3
};

// vdg.Model: the raw description (what saving and exporting need) and the built run-time model,
// static or animated (exactly one of `model`, `animated` is set).
struct Model {
  RawViewDependentModel raw;
  std::shared_ptr<const ViewDependentModel> model;
  std::shared_ptr<const AnimatedViewDependentModel> animated;
  std::string source;  // the file it was loaded from, or ""

  bool isAnimated() const { return animated != nullptr; }
  std::size_t vertexCount() const { return raw.base.vertexCount(); }
  Eigen::Vector3d center() const { return animated ? animated->center() : model->center(); }
  const ViewSphere& sphere() const { return animated ? animated->sphere() : model->sphere(); }
};

// ---- model.cpp ----
py::dict modelWeights(const Model& m, py::handle view, py::handle sharpness, py::handle frame);
py::dict modelWeightsFromEye(const Model& m, py::handle eye, py::handle sharpness, py::handle frame);
py::tuple modelEvaluate(const Model& m, py::handle view, py::handle frame, py::handle sharpness);
py::array_t<double> modelTimeCoefficients(const Model& m, py::handle view_index, py::handle frame);
Eigen::Vector3d modelViewFromEye(const Model& m, py::handle eye);
py::list modelKeys(const Model& m);
SphereView modelSphere(const Model& m);
py::object modelUvs(const Model& m);
// Texture coordinates per triangle corner, (T, 3, 2) float32, or None: what a seam cannot lose.
py::object modelCornerUvs(const Model& m);
// The base's material per triangle, (T,) int32 (-1: none), or None without materials.
py::object modelFaceMaterials(const Model& m);
// The base's materials: dicts {"name", "base_color" (display sRGB r, g, b), "texture_path",
// "texture" (the PNG or JPEG file's bytes, or None)}.
py::list modelMaterials(const Model& m);
py::object modelBaseFrames(const Model& m);
std::string modelRepr(const Model& m);
// The sharpness argument: None -> 0 (the model's own), else finite and > 0 (ValueError).
double sharpnessArg(py::handle sharpness);

// ---- build.cpp ----
Camera makeCamera(py::handle eye, py::handle target, py::handle up, double fov_deg, double ortho_height);
Key makeKey(const std::string& name, py::handle positions, py::handle view, py::handle camera, py::handle frame);
// vdg.build's keyword arguments, as Python passed them.
struct BuildArgs {
  py::object base, triangles, keys, center, frames, uvs, corner_uvs, materials, face_materials;
  double sharpness = 1.0, base_falloff_deg = 60.0, fps = 24.0;
  std::string uncovered = "base", comment;
  std::string scheme = "linear";
  py::object kernel, width;  // None, or the rbf scheme's kernel name and width (degrees)
  bool loop = false;
};
Model buildModel(const BuildArgs& args);
// Builds the run-time model from m.raw (validating it): sets m.model or m.animated.
void buildRuntime(Model& m);

// ---- files.cpp ----
Model loadModel(py::handle path);
void saveManifest(const Model& m, py::handle path, const std::string& mesh_folder);
py::list exportGltf(const Model& m, py::handle path, const std::string& compress, py::handle max_targets);

}  // namespace vdg::python
