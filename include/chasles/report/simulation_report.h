#pragma once
/// @file
/// The files `chasles simulate` writes, from a run's result (chasles/analysis/study.h): the
/// CSV time series and the JSON summary (final state, events, impulses and impacts, contact
/// mode changes, the energy/work/momentum ledger, integrator statistics, notes, warnings and
/// checks). All values SI, world frame. A program that runs a StudyDefinition itself writes
/// the same files as the command line does (docs/cpp.md, "Writing the program's reports").

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "chasles/analysis/study.h"
#include "chasles/report/csv_table.h"

namespace chasles {

/// What a report says about the problem behind the result (the scene layer fills it from a
/// Scene; a program from its own model).
struct ReportHeader {
  /// The scene file ("" when there is none) and the problem's title.
  std::string scene_file, title;
  /// A planar problem: bodies and reactions carry a "planar" block (x, y, theta, vx, vy,
  /// omega; Fx, Fy, Mz).
  bool planar = false;
  /// Warnings listed before the run's own (e.g. the scene's).
  std::vector<std::string> warnings;
};

/// The CSV time series (chasles/report/csv_table.h): a header of the column names with their
/// units ("t [s]", "car_x [m]"; result.units, none when it is empty), then one line per row,
/// each value the shortest text that reads back as the same double, or with kFull every value
/// %.17g. Throws InputError naming the column and row of a value that is not finite
/// (CheckFiniteTable, "the CSV time series").
std::string SimulationCsv(const StudyResult& result,
                          CsvPrecision precision = CsvPrecision::kDefault);

/// The bodies, reactions and contact points of one instant: {"bodies": [...], "reactions":
/// [...]} and "contacts" when there are contact points.
nlohmann::json SnapshotJson(const StudySnapshot& snapshot, bool planar);

/// The JSON summary; `csv_path` is recorded under "csv". The warnings are the header's, the
/// run's and one per failed check. Check it with DumpJson (chasles/report/json_report.h) before
/// writing it.
nlohmann::json SimulationJson(const StudyResult& result, const ReportHeader& header,
                              const std::string& csv_path);

}  // namespace chasles
