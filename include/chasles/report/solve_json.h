#pragma once
/// @file
/// What `chasles solve` prints, from the analysis layer's results (chasles/analysis/
/// solve_report.h): the solve's JSON report, and a sweep's table as JSON and as CSV text. All
/// values SI, world frame.

#include <string>

#include <nlohmann/json.hpp>

#include "chasles/analysis/solve_report.h"
#include "chasles/report/csv_table.h"

namespace chasles {

/// The solve's report: "t", "bodies" (accelerations), "reactions" (forces, moments,
/// multipliers, power; for rolling the normal force, friction, f/N and against mu_s whether it
/// rolls), "energy_momentum" (per body and total), "contacts" (mode, regime, forces, slip,
/// gap), "planar", "rank", "rows", "warnings" (the solve's and one per failed check) and
/// "checks". Bodies and reactions carry a "planar" block (a_x, a_y, alpha; Fx, Fy, Mz) only
/// when the report is planar. Check it with DumpJson (chasles/report/json_report.h) before
/// writing it.
nlohmann::json SolveJson(const SolveReport& report);

/// {"parameter": name, "units": "SI", "columns": [...], "column_units": [...], "rows":
/// [[...], ...]}: one row per value of the parameter (per point of a grid), every value SI;
/// with "parameters" (a grid's names) when the table has them, and with "errors" (per row the
/// reason its run failed, or null) when its rows can fail, a failed row's values then null.
nlohmann::json SweepJson(const SweepTable& table);

/// The table as the program prints it (chasles/report/csv_table.h): the header of the column
/// names with their SI units ("theta", "cylinder_ax [m/s^2]"), then one line per value (per
/// point of a grid, the last parameter varying fastest), each number with 12 significant
/// digits, or with kFull %.17g. When its rows can fail (SweepTable::errors), a last column
/// "error": the reason, with the failed row's values as empty fields. Throws InputError naming
/// the column and row of a value of a row that ran that is not finite (CheckFiniteTable, "the
/// sweep table").
std::string SweepCsv(const SweepTable& table, CsvPrecision precision = CsvPrecision::kDefault);

/// One solve as a one-row table: the columns of a sweep after its parameter
/// (SolutionTableRow's names with their SI units), the values with 12 significant digits, or
/// with kFull %.17g. Throws InputError naming the column of a value that is not finite
/// (CheckFiniteTable, "the solve table").
std::string SolveCsv(const SolveReport& report, CsvPrecision precision = CsvPrecision::kDefault);

}  // namespace chasles
