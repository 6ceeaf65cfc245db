#pragma once
/// @file
/// What simulate --sweep and mass --sweep share on the command line: their options, the
/// grid's specs, the progress of the runs and the table they print (docs/sweeps.md).

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "chasles/analysis/solve_report.h"
#include "chasles/files/output_set.h"
#include "chasles/report/csv_table.h"
#include "chasles/scene/solve.h"

namespace chasles::cli {

/// The most points of a sweep unless --max-runs says otherwise.
inline constexpr std::int64_t kDefaultMaxRuns = 100'000;

/// --sweep, --quantity, --jobs and --max-runs on `cmd` (`what`: the quantities' help text).
void AddSweepOptions(CLI::App& cmd, std::vector<std::string>& sweep,
                     std::vector<std::string>& quantity, int& jobs, std::int64_t& max_runs,
                     const std::string& what);

/// Each --sweep read (ParseSweep at "command line", "--sweep").
std::vector<SweepSpec> ParseSweeps(const std::vector<std::string>& texts);

/// Adds the table (CSV with `precision`, or JSON for `format` "json") to `out` for `target`
/// (a file or "-") and writes one warning per failed row on standard error ("warning: L = 2,
/// theta0 = 0.5: why"). Returns the number of failed rows.
int AddSweepTable(OutputSet& out, const SweepTable& table, const std::string& format,
                  CsvPrecision precision, const std::string& target);

}  // namespace chasles::cli
