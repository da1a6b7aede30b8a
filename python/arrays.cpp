// numpy arrays in and out of the vdg module: every array argument is checked for its element kind
// (TypeError for anything but integers and floating-point numbers) and its shape (ValueError naming
// the argument, the shape expected and the shape got) before its values are converted (numpy's
// forcecast: any integer or float dtype becomes float32, float64 or int32 as the API says).
#include <cmath>
#include <cstring>
#include <limits>

#include "binding.h"
#include "vdg/geom/normalize.h"

namespace vdg::python {
namespace {

std::string shapeText(const py::array& a) {
  std::string text = "(";
  for (py::ssize_t i = 0; i < a.ndim(); ++i) text += (i ? ", " : "") + std::to_string(a.shape(i));
  return text + (a.ndim() == 1 ? ",)" : ")");
}

std::string expectedText(py::ssize_t rows, py::ssize_t cols) {
  const std::string r = rows < 0 ? "N" : std::to_string(rows);
  return cols < 0 ? "(" + r + ",)" : "(" + r + ", " + std::to_string(cols) + ")";
}

// numpy.asarray(obj), refusing non-numeric element kinds and wrong shapes. cols < 0 asks for a
// one-dimensional array of `rows` values.
py::array numericArray(py::handle obj, py::ssize_t rows, py::ssize_t cols, const std::string& what) {
  if (obj.is_none()) throw py::type_error(what + ": expected an array of numbers, got None");
  py::array a = py::module_::import("numpy").attr("asarray")(obj);
  const char kind = a.dtype().kind();
  if (kind != 'i' && kind != 'u' && kind != 'f')
    throw py::type_error(what + ": expected an array of numbers, got dtype " + py::str(a.dtype()).cast<std::string>());
  const py::ssize_t ndim = cols < 0 ? 1 : 2;
  const bool ok = a.ndim() == ndim && (rows < 0 || a.shape(0) == rows) && (cols < 0 || a.shape(1) == cols);
  if (!ok) throw py::value_error(what + ": expected shape " + expectedText(rows, cols) + ", got " + shapeText(a));
  return a;
}

template <typename T>
std::vector<T> rowsOf(py::handle obj, py::ssize_t rows, py::ssize_t cols, const std::string& what) {
  const py::array a = numericArray(obj, rows, cols, what);
  const auto values = py::array_t<T, py::array::c_style | py::array::forcecast>::ensure(a);
  if (!values) throw py::type_error(what + ": cannot convert the array's values");
  std::vector<T> out(static_cast<std::size_t>(values.size()));
  if (!out.empty()) std::memcpy(out.data(), values.data(), out.size() * sizeof(T));
  return out;
}

}  // namespace

std::vector<float> floatRows(py::handle obj, py::ssize_t rows, py::ssize_t cols, const std::string& what) {
  return rowsOf<float>(obj, rows, cols, what);
}

std::vector<double> doubleRows(py::handle obj, py::ssize_t rows, py::ssize_t cols, const std::string& what) {
  return rowsOf<double>(obj, rows, cols, what);
}

std::vector<std::int32_t> intRows(py::handle obj, py::ssize_t rows, py::ssize_t cols, const std::string& what) {
  const py::array a = numericArray(obj, rows, cols, what);
  if (a.dtype().kind() == 'f')
    throw py::type_error(what + ": expected integers, got dtype " + py::str(a.dtype()).cast<std::string>());
  const std::vector<std::int64_t> wide = rowsOf<std::int64_t>(a, rows, cols, what);
  std::vector<std::int32_t> out(wide.size());
  for (std::size_t i = 0; i < wide.size(); ++i) {
    if (wide[i] < 0 || wide[i] > std::numeric_limits<std::int32_t>::max())
      throw py::value_error(what + ": value " + std::to_string(wide[i]) + " at flat index " + std::to_string(i) +
                            " is not an index in [0, 2^31)");
    out[i] = static_cast<std::int32_t>(wide[i]);
  }
  return out;
}

Eigen::Vector3d vector3(py::handle obj, const std::string& what) {
  const std::vector<double> v = doubleRows(obj, 3, -1, what);
  const Eigen::Vector3d out(v[0], v[1], v[2]);
  if (!out.allFinite()) throw py::value_error(what + ": expected finite numbers, got a NaN or infinite value");
  return out;
}

Eigen::Vector3d viewVector(py::handle obj, const std::string& what) {
  const Eigen::Vector3d v = vector3(obj, what);
  if (!normalizedOrNone(v)) throw py::value_error(what + ": expected a non-zero direction, got (0, 0, 0)");
  return v;
}

double finiteNumber(py::handle obj, const std::string& what) {
  // Python's int and float, and numpy's scalars (np.float32(1), np.int64(2)); not bool, not arrays.
  const bool number = !PyBool_Check(obj.ptr()) && (PyFloat_Check(obj.ptr()) || PyLong_Check(obj.ptr()) ||
                                                   py::isinstance(obj, py::module_::import("numpy").attr("number")));
  if (!number)
    throw py::type_error(what + ": expected a number, got " + py::str(py::type::of(obj)).cast<std::string>());
  const double value = PyFloat_AsDouble(obj.ptr());
  if (PyErr_Occurred()) throw py::error_already_set();
  if (!std::isfinite(value)) throw py::value_error(what + ": expected a finite number, got " + std::to_string(value));
  return value;
}

long long integerArg(py::handle obj, const std::string& what) {
  const bool integer = !PyBool_Check(obj.ptr()) &&
                       (PyLong_Check(obj.ptr()) || py::isinstance(obj, py::module_::import("numpy").attr("integer")));
  if (!integer) throw py::type_error(what + ": expected an int, got " + py::str(py::type::of(obj)).cast<std::string>());
  PyObject* index = PyNumber_Index(obj.ptr());
  if (index == nullptr) throw py::error_already_set();
  const py::int_ value = py::reinterpret_steal<py::int_>(index);
  int overflow = 0;
  const long long out = PyLong_AsLongLongAndOverflow(value.ptr(), &overflow);
  if (overflow != 0) throw py::value_error(what + ": " + py::repr(value).cast<std::string>() + " is out of range");
  return out;
}

std::string pathArg(py::handle obj, const std::string& what) {
  if (!py::isinstance<py::str>(obj) && !py::hasattr(obj, "__fspath__"))
    throw py::type_error(what + ": expected a str or os.PathLike path, got " +
                         py::str(py::type::of(obj)).cast<std::string>());
  const py::object path = py::module_::import("os").attr("fspath")(obj);
  if (!py::isinstance<py::str>(path)) throw py::type_error(what + ": expected a str path, got bytes");
  return path.cast<std::string>();
}

py::array_t<float> floatArray(const float* data, py::ssize_t rows, py::ssize_t cols) {
  py::array_t<float> out({rows, cols});
  if (rows * cols > 0) std::memcpy(out.mutable_data(), data, static_cast<std::size_t>(rows * cols) * sizeof(float));
  return out;
}

py::array_t<std::int32_t> intArray(const std::int32_t* data, py::ssize_t rows, py::ssize_t cols) {
  py::array_t<std::int32_t> out({rows, cols});
  if (rows * cols > 0)
    std::memcpy(out.mutable_data(), data, static_cast<std::size_t>(rows * cols) * sizeof(std::int32_t));
  return out;
}

py::array_t<double> vectorArray(const Eigen::Vector3d& v) {
  py::array_t<double> out(3);
  for (int i = 0; i < 3; ++i) out.mutable_at(i) = v[i];
  return out;
}

}  // namespace vdg::python
