#pragma once
/// @file
/// What `chasles solve` prints, from the analysis layer's results (chasles/analysis/
/// solve_report.h): the solve's JSON report, and a sweep's table as JSON and as CSV text. All
/// values SI, world frame.

#include <string>

#include <nlohmann/json.hpp>

#include "chasles/analysis/solve_report.h"

namespace chasles {

/// The solve's report: "t", "bodies" (accelerations), "reactions" (forces, moments,
/// multipliers, power; for rolling the normal force, friction, f/N and against mu_s whether it
/// rolls), "energy_momentum" (per body and total), "contacts" (mode, regime, forces, slip,
/// gap), "planar", "rank", "rows", "warnings" (the solve's and one per failed check) and
/// "checks". Bodies and reactions carry a "planar" block (a_x, a_y, alpha; Fx, Fy, Mz) only
/// when the report is planar. Check it with DumpJson (chasles/io/json_report.h) before
/// writing it.
nlohmann::json SolveJson(const SolveReport& report);

/// {"parameter": name, "columns": [...], "rows": [[...], ...]}; with "parameters" (a grid's
/// names) when the table has them, and with "errors" (per row the reason its run failed, or
/// null) when its rows can fail, a failed row's values then null.
nlohmann::json SweepJson(const SweepTable& table);

/// The table as the program prints it: a comment line "# NAME swept (SI values); one row per
/// value" (a grid: "per combination"), the column names (quoted when they hold a comma, a
/// quote or a newline), then one line per value, each number with 12 significant digits.
/// When its rows can fail (SweepTable::errors), a last column "error": the reason, with the
/// failed row's values as empty fields. Throws InputError naming the column and row of a value
/// of a row that ran that is not finite (CheckFiniteTable, "the sweep table").
std::string SweepCsv(const SweepTable& table);

}  // namespace chasles
