#pragma once
/// @file
/// The last check before a report leaves the program or the library: no number that is not
/// finite is ever printed or written. Every report is built in its JSON form (which holds every
/// value its text shows) and passes it here first, so the error names the quantity by its JSON
/// key path; the CSV writers and the text formatting refuse a non-finite value as well. Also
/// the JSON form of a vector and a matrix, as every report writes them.

#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "chasles/math/types.h"

namespace chasles {

/// Throws InputError naming the first non-finite number's key path in `j`
/// ("bodies[0].points[1].inertia[0][0]", with the body's name when the path starts in
/// "bodies[i]" and that body has one) and why such a value arises. `report` starts the
/// message ("the solve report").
void CheckFiniteJson(const nlohmann::json& j, std::string_view report);

/// CheckFiniteJson, then the text (indent 2, newline at the end). Text that is not UTF-8 (a
/// file name on the command line) is written with U+FFFD in its place, never an exception.
std::string DumpJson(const nlohmann::json& j, std::string_view report);

/// Throws InputError naming the column and the row (from 1) if a cell of the table is not
/// finite.
void CheckFiniteTable(const std::vector<std::string>& columns,
                      const std::vector<std::vector<double>>& rows, std::string_view report);

/// `v`, or an InputError saying that `what` is not finite.
double Finite(double v, std::string_view what);

/// [x, y, z].
nlohmann::json VecJson(const Vec3& v);

/// Rows: [[m00, m01, m02], [m10, m11, m12], [m20, m21, m22]].
nlohmann::json MatJson(const Mat3& m);

}  // namespace chasles
