#pragma once
/// @file
/// Shared declarations of the Python bindings (one Bind... per file, called by module.cpp) and
/// small conversions between chasles' types and numpy.

#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <pybind11/eigen.h>
#include <pybind11/functional.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "chasles/error.h"
#include "chasles/math/types.h"
#include "chasles/scene/scene.h"

namespace chasles::python {

namespace py = pybind11;

void BindErrors(py::module_& m);
void BindMass(py::module_& m);
void BindModel(py::module_& m);
void BindSimulate(py::module_& m);
void BindScene(py::module_& m);
void BindModes(py::module_& m);
void BindBalance(py::module_& m);

/// A loaded scene and where it came from, so that a sweep can load it again with one more
/// override (the Python class Scene).
struct PyScene {
  Scene scene;
  std::string path;  // "" when loaded from text
  std::string text;
  std::string name;
  SceneOptions options;

  Scene Load(const SceneOptions& o) const {
    return path.empty() ? LoadSceneText(text, name, o) : LoadSceneFile(path, o);
  }
};

/// A quaternion as the numpy array [w, x, y, z].
py::array_t<double> QuatArray(const Quat& q);
/// A quaternion from [w, x, y, z] (normalised by the callers that need a unit one).
Quat QuatFrom(const Eigen::Vector4d& wxyz);
/// Rows of equal length as a 2-D numpy array (rows x columns); `columns` gives the width of
/// an empty table.
py::array_t<double> TableArray(const std::vector<std::vector<double>>& rows, size_t columns);

/// A Python callable as a std::function the library may call with the GIL released (the
/// simulation runs so): each call takes the GIL, and the callable is held by a shared pointer
/// whose deleter takes it too, so the C++ side copies and destroys it freely. `convert` turns
/// the C++ arguments into the Python call and its result back.
template <typename R, typename... Args, typename Convert>
std::function<R(Args...)> GilSafe(py::function fn, Convert convert) {
  std::shared_ptr<py::function> f(new py::function(std::move(fn)), [](py::function* p) {
    py::gil_scoped_acquire gil;
    delete p;
  });
  return [f, convert](Args... args) -> R {
    py::gil_scoped_acquire gil;
    return convert(*f, args...);
  };
}

/// What the Python `callable` returned, as T. A value of another type or shape (None, a string,
/// 2 numbers where 3 are needed) raises TypeError naming the callable (its __qualname__) and
/// what it must return (`expected`: "3 numbers [x, y, z]"), instead of pybind11's internal
/// "Unable to cast". Called with the GIL held.
template <typename T>
T CallbackResult(const py::function& callable, const py::object& value, const char* expected) {
  try {
    return value.cast<T>();
  } catch (const py::cast_error&) {
    const py::object name = py::getattr(callable, "__qualname__", py::repr(callable));
    throw py::type_error("the callable " + std::string(py::str(name)) + " must return " + expected +
                         ", got " + std::string(py::repr(value)));
  }
}

/// `v` itself; InputError naming the argument unless every entry is finite (a point, a
/// rotation or a mass given as NaN or an infinity is refused at the boundary, not carried
/// into a result).
template <typename Derived>
const Derived& RequireFinite(const Derived& v, const char* argument) {
  if (!v.allFinite()) {
    throw InputError(std::string(argument) + " must be finite numbers, got " +
                     std::string(py::str(py::cast(Eigen::MatrixXd(v)).attr("tolist")())));
  }
  return v;
}

/// `v` itself; InputError saying that `what` left a double's range unless it is finite (a
/// point 1e200 m away makes m d^2 overflow).
template <typename Derived>
Derived FiniteResult(const Derived& v, const char* what) {
  if (!v.allFinite()) {
    throw InputError(std::string(what) +
                     " is not a finite number (it left the range of a "
                     "double, about 1.8e308): the arguments are too large");
  }
  return v;
}

/// IndexError naming the argument unless 0 <= index < count (a negative index is not counted
/// from the end: a body index is a handle, not a position in a list).
void CheckIndex(int index, int count, const char* argument, const char* count_name);

}  // namespace chasles::python
