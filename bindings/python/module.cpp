// The extension module chasles._chasles: errors and conversions shared by the bindings; the
// rest is bound layer by layer in bind_*.cpp. The package chasles (chasles/__init__.py) adds
// the pure-Python conveniences (tables, pandas).

#include <cstring>
#include <filesystem>

#include "bindings.h"
#include "chasles/error.h"
#include "chasles/math/quaternion.h"
#include "chasles/scene/scene_error.h"

namespace chasles::python {

py::array_t<double> QuatArray(const Quat& q) {
  const Eigen::Vector4d v = QuatToWxyz(q);
  py::array_t<double> a(4);
  for (int i = 0; i < 4; ++i) a.mutable_at(i) = v[i];
  return a;
}

Quat QuatFrom(const Eigen::Vector4d& wxyz) {
  return QuatFromWxyz(wxyz[0], wxyz[1], wxyz[2], wxyz[3]);
}

py::array_t<double> TableArray(const std::vector<std::vector<double>>& rows, size_t columns) {
  const size_t n = rows.size();
  const size_t m = rows.empty() ? columns : rows.front().size();
  py::array_t<double> a({n, m});
  auto v = a.mutable_unchecked<2>();
  for (size_t i = 0; i < n; ++i) {
    if (rows[i].size() != m) throw std::runtime_error("rows of a table differ in length");
    std::memcpy(v.mutable_data(static_cast<py::ssize_t>(i), 0), rows[i].data(), m * sizeof(double));
  }
  return a;
}

void BindErrors(py::module_& m) {
  // InputError is a ValueError (bad input), SceneError and LimitError are InputErrors. They
  // are Python classes created here; the translator fills their attributes.
  py::object value_error = py::reinterpret_borrow<py::object>(PyExc_ValueError);
  py::object type = py::reinterpret_borrow<py::object>(reinterpret_cast<PyObject*>(&PyType_Type));
  py::dict input_ns;
  input_ns["__doc__"] =
      "Bad input: a physical or geometric value that cannot be right (a negative mass, an "
      "invalid inertia, an open mesh in solid mode). The message names the value, the rule and "
      "the fix. Attributes file, line, column and key are set for errors in a scene (SceneError) "
      "and are None otherwise.";
  input_ns["__module__"] = "chasles";
  input_ns["file"] = py::none();
  input_ns["line"] = py::none();
  input_ns["column"] = py::none();
  input_ns["key"] = py::none();
  input_ns["message"] = py::none();
  py::object input_error = type("InputError", py::make_tuple(value_error), input_ns);
  py::dict scene_ns;
  scene_ns["__doc__"] =
      "Bad input in a scene: str(e) reads 'FILE:LINE:COL: KEY: MESSAGE'. Attributes: file, "
      "line and column (1-based; 0 when unknown), key (the path of the offending key, e.g. "
      "'bodies[0].parts[1].radius') and message (without the location).";
  scene_ns["__module__"] = "chasles";
  py::object scene_error = type("SceneError", py::make_tuple(input_error), scene_ns);
  py::dict limit_ns;
  limit_ns["__doc__"] =
      "A run reached a limit on its work (steps, rows, wall time, smallest step). Attribute "
      "limit: 'steps', 'rows', 'time' or 'min_step'.";
  limit_ns["__module__"] = "chasles";
  py::object limit_error = type("LimitError", py::make_tuple(input_error), limit_ns);
  m.attr("InputError") = input_error;
  m.attr("SceneError") = scene_error;
  m.attr("LimitError") = limit_error;

  // Held for the life of the interpreter (the module keeps them too).
  static PyObject* input_type = input_error.inc_ref().ptr();
  static PyObject* scene_type = scene_error.inc_ref().ptr();
  static PyObject* limit_type = limit_error.inc_ref().ptr();
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const SceneError& e) {
      py::object x = py::reinterpret_borrow<py::object>(scene_type)(e.what());
      x.attr("file") = e.file();
      x.attr("line") = e.line();
      x.attr("column") = e.column();
      x.attr("key") = e.key();
      x.attr("message") = e.message();
      PyErr_SetObject(scene_type, x.ptr());
    } catch (const LimitError& e) {
      static const char* const names[] = {"steps", "rows", "time", "min_step"};
      py::object x = py::reinterpret_borrow<py::object>(limit_type)(e.what());
      x.attr("limit") = names[static_cast<int>(e.limit())];
      x.attr("message") = std::string(e.what());
      PyErr_SetObject(limit_type, x.ptr());
    } catch (const InputError& e) {
      py::object x = py::reinterpret_borrow<py::object>(input_type)(e.what());
      x.attr("message") = std::string(e.what());
      PyErr_SetObject(input_type, x.ptr());
    } catch (const std::filesystem::filesystem_error& e) {
      // A path the file system refuses (an empty one, one too long): bad input, as the
      // program's exit 2, not pybind11's RuntimeError.
      py::object x = py::reinterpret_borrow<py::object>(input_type)(e.what());
      x.attr("message") = std::string(e.what());
      PyErr_SetObject(input_type, x.ptr());
    }
  });
}

}  // namespace chasles::python

PYBIND11_MODULE(_chasles, m) {
  m.doc() =
      "chasles: rigid-body kinetics (mass properties, instantaneous solve, simulation) from "
      "Python. Everything is SI; vectors and matrices are numpy arrays; quaternions are "
      "[w, x, y, z]. Import the package `chasles`, not this extension.";
  chasles::python::BindErrors(m);
  chasles::python::BindMass(m);
  chasles::python::BindModel(m);
  chasles::python::BindSimulate(m);
  chasles::python::BindScene(m);
  chasles::python::BindModes(m);
  chasles::python::BindBalance(m);
}
