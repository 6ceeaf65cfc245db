#pragma once
/// @file
/// The text report of a scene's run, as `chasles simulate` prints it: the events, impulses and
/// impacts, contact and string mode changes, the final state, reactions and contacts, the
/// energy/work/momentum ledger, the integrator's work, notes, warnings and checks.

#include <string>

#include "chasles/report/text_format.h"
#include "chasles/scene/scene.h"
#include "chasles/scene/study.h"

namespace chasles {

/// The report of run `result` of `scene` in the units `options` asks for; its last line names
/// options.csv_path and options.json_path (no such line when both are empty).
std::string SimulationText(const Scene& scene, const StudyResult& result,
                           const TextOptions& options = {});

/// The CSV and JSON files `chasles simulate` writes for a scene file in a folder ("" is the
/// current folder, "."): <folder>/<scene's stem>.csv and .json.
struct SimulationFiles {
  std::string csv, json;
};
SimulationFiles SimulationFilesIn(const std::string& folder, const std::string& scene_file);

}  // namespace chasles
