// chasles report RUN.json -o report.html: the browser report of a finished `simulate` run,
// rebuilt from its JSON summary (events, contact-mode changes, impacts, jumps), the CSV it
// names (every sample) and the scene it names (the bodies' parts). The force arrows need the
// forces at every sample, which only a run made with --html records: this report has the
// replay, the plots and the events, without arrows.

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>

#include "chasles/error.h"
#include "chasles/io/atomic_file.h"
#include "chasles/io/csv_table.h"
#include "chasles/scene/report_data.h"
#include "chasles/scene/scene.h"
#include "commands.h"
#include "html_report.h"
#include "scene_args.h"

namespace chasles::cli {

namespace {

/// The run's table from its CSV (chasles/io/csv_table.h: columns by name, their units
/// dropped). Errors name the file, line and column.
void ReadCsv(const std::string& path, StudyResult& r) {
  CsvTable t = ReadCsvTable(ReadTextFile(path, "the run's CSV"), path);
  r.columns = std::move(t.columns);
  r.units = std::move(t.units);
  r.rows = std::move(t.rows);
}

template <typename T>
T Get(const nlohmann::json& j, const char* key, const std::string& where) {
  if (!j.contains(key)) {
    throw InputError(
        fmt::format("{}: key '{}' missing (expected a chasles simulate JSON)", where, key));
  }
  try {
    return j.at(key).get<T>();
  } catch (const nlohmann::json::exception& e) {
    throw InputError(fmt::format("{}: key '{}': {}", where, key, e.what()));
  }
}

}  // namespace

CLI::App* AddReportCommand(CLI::App& app, ReportArgs& args) {
  CLI::App* cmd = app.add_subcommand(
      "report",
      "Write the browser report (3-D replay and plots, one HTML file) of a finished simulate "
      "run, from its JSON summary, the CSV and the scene it names");
  cmd->add_option("RUN", args.run_json, "The run's JSON summary (chasles simulate --out DIR)")
      ->required();
  cmd->add_option("-o,--output", args.output, "The HTML file to write")->required();
  cmd->add_option("--set", args.set,
                  "NAME=EXPRESSION: the scene parameters the run was given with --set "
                  "(one per --set; repeat --set for each)")
      ->type_name("NAME=EXPR")
      ->allow_extra_args(false)
      ->delimiter('\0');  // an expression may contain commas and brackets: keep it whole
  cmd->add_option("--max-scene-bytes", args.max_scene_bytes, "Largest scene file read (bytes)");
  cmd->footer(
      "Example:\n"
      "  chasles simulate examples/pendulum.yaml --out results\n"
      "  chasles report results/pendulum.json -o pendulum.html\n"
      "The CSV must hold every body's pose: its origin and quaternion columns, or its centre "
      "of mass and orientation to derive them from (position and quaternion; a planar "
      "scene's default x, y and theta). Otherwise add those output groups, or run simulate "
      "with --html, which writes the report with force arrows directly. docs/report.md.\n"
      "Exit codes: 0 success, 2 bad input, 1 internal error.");
  return cmd;
}

int RunReport(const ReportArgs& args) {
  RequireHtmlReport("chasles report");
  const std::string text = ReadTextFile(args.run_json, "the run's JSON summary");
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    throw InputError(fmt::format("{}: not JSON: {}", args.run_json, e.what()));
  }
  if (!j.is_object()) {
    throw InputError(
        fmt::format("{}: expected a JSON object (a chasles simulate summary)", args.run_json));
  }
  SceneArgs scene_args;
  scene_args.scene = ResolveBesideJson(Get<std::string>(j, "scene", args.run_json), args.run_json);
  scene_args.set = args.set;
  scene_args.max_scene_bytes = args.max_scene_bytes;
  if (scene_args.scene.empty()) {
    throw InputError(fmt::format("{}: the run names no scene file", args.run_json));
  }
  const Scene scene = LoadScene(scene_args);

  StudyResult r;
  ReadCsv(ResolveBesideJson(Get<std::string>(j, "csv", args.run_json), args.run_json), r);
  for (const auto& e : Get<nlohmann::json>(j, "events", args.run_json)) {
    StudyEvent ev;
    ev.name = Get<std::string>(e, "name", args.run_json + ": events");
    ev.t = Get<double>(e, "t", args.run_json + ": events");
    ev.stopped = e.value("stopped", false);
    r.events.push_back(ev);
  }
  for (const auto& e : j.value("contact_events", nlohmann::json::array())) {
    const std::string where = args.run_json + ": contact_events";
    r.contact_events.push_back(
        {Get<double>(e, "t", where), Get<std::string>(e, "point", where),
         Get<std::string>(e, "contact", where), Get<std::string>(e, "from", where),
         Get<std::string>(e, "to", where), Get<std::string>(e, "reason", where)});
  }
  for (const auto& e : j.value("impacts", nlohmann::json::array())) {
    const std::string where = args.run_json + ": impacts";
    StudyImpact x;
    x.t = Get<double>(e, "t", where);
    x.point = Get<std::string>(e, "point", where);
    x.energy_lost = Get<double>(e, "energy_lost", where);
    r.impacts.push_back(x);
  }
  for (const auto& e : j.value("jumps", nlohmann::json::array())) {
    const std::string where = args.run_json + ": jumps";
    StudyJump x;
    x.t = Get<double>(e, "t", where);
    x.kind = Get<std::string>(e, "kind", where);
    x.description = Get<std::string>(e, "description", where);
    r.jumps.push_back(x);
  }
  // The poses the replay draws, from the centre of mass and orientation columns when the run
  // has no origin columns (the default columns of a planar scene and of many 3-D ones).
  const std::vector<std::string> derived = CompletePoseColumns(scene, r);
  if (!derived.empty()) {
    std::printf("note: the poses of %s derived from the centre of mass and orientation columns\n",
                fmt::format("{}", fmt::join(derived, ", ")).c_str());
  }
  WriteFileAtomically(args.output, HtmlReport(SimulationReportData(scene, r)));
  std::printf("Wrote %s (the browser report of %s, %zu samples)\n", args.output.c_str(),
              args.run_json.c_str(), r.rows.size());
  return 0;
}

}  // namespace chasles::cli
