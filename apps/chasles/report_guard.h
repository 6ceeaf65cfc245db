#pragma once
/// @file
/// The last check before a report leaves the program: no number that is not finite is ever
/// printed or written with exit 0. Every command builds its JSON form (which holds every value
/// the text shows) and passes it here first, so the error names the quantity by its JSON key
/// path; the text formatting helpers and the CSV writer refuse a non-finite value as well.

#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

namespace chasles::cli {

/// Throws InputError naming the first non-finite number's key path in `j`
/// ("bodies[0].points[1].inertia[0][0]") and why such a value arises.
void CheckFiniteJson(const nlohmann::json& j, std::string_view report);

/// CheckFiniteJson, then the text (indent 2, newline at the end). Text that is not UTF-8 (a
/// file name on the command line) is written with U+FFFD in its place, never an exception.
std::string DumpJson(const nlohmann::json& j, std::string_view report);

/// Throws InputError naming the column and the row if a cell of the table is not finite.
void CheckFiniteTable(const std::vector<std::string>& columns,
                      const std::vector<std::vector<double>>& rows, std::string_view report);

/// `v`, or an InputError saying that `what` is not finite.
double Finite(double v, std::string_view what);

}  // namespace chasles::cli
