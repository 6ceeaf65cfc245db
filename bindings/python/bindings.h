#pragma once
/// @file
/// Shared declarations of the Python bindings (one Bind... per file, called by module.cpp) and
/// small conversions between chasles' types and numpy.

#include <string>
#include <vector>

#include <pybind11/eigen.h>
#include <pybind11/functional.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "chasles/math/types.h"

namespace chasles::python {

namespace py = pybind11;

void BindErrors(py::module_& m);
void BindMass(py::module_& m);
void BindModel(py::module_& m);
void BindSimulate(py::module_& m);
void BindScene(py::module_& m);

/// A quaternion as the numpy array [w, x, y, z].
py::array_t<double> QuatArray(const Quat& q);
/// A quaternion from [w, x, y, z] (normalised by the callers that need a unit one).
Quat QuatFrom(const Eigen::Vector4d& wxyz);
/// Rows of equal length as a 2-D numpy array (rows x columns); `columns` gives the width of
/// an empty table.
py::array_t<double> TableArray(const std::vector<std::vector<double>>& rows, size_t columns);

}  // namespace chasles::python
