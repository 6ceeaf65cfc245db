// chasles report RUN.json -o report.html: the browser report of a finished `simulate` run,
// rebuilt from its JSON summary (events, contact-mode changes, impacts, jumps), the CSV it
// names (every sample, and the bodies' poses from its columns) and the scene it names (the
// bodies' parts). The force arrows need the forces at every sample, which only a run made with
// --html records: this report has the replay, the plots and the events, without arrows.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>

#include "chasles/error.h"
#include "chasles/files/input_file.h"
#include "chasles/files/output_set.h"
#include "chasles/report/csv_table.h"
#include "chasles/report/json_input.h"
#include "chasles/report/report_data.h"
#include "chasles/report/result_names.h"
#include "chasles/scene/scene.h"
#include "commands.h"
#include "html_report.h"
#include "scene_args.h"

namespace chasles::cli {

namespace {

/// The run's table from its CSV (chasles/report/csv_table.h: columns by name, their units
/// dropped). Errors name the file, line and column. A run's CSV has no failed rows (those are
/// a sweep's): one is refused with its line and reason rather than drawn as NaN.
void ReadCsv(const std::string& path, size_t max_bytes, StudyResult& r) {
  CsvTable t =
      ReadCsvTable(ReadInputFile(path, "the run's CSV", max_bytes, "--max-input-bytes N"), path);
  for (size_t k = 0; k < t.errors.size(); ++k) {
    if (t.errors[k].empty()) continue;
    throw InputError(fmt::format(
        "{}:{}: the row has no values ({}); a run's CSV has none like it (is this a sweep's "
        "table? chasles plot draws those)",
        path, k + 2, t.errors[k]));
  }
  r.columns = std::move(t.columns);
  r.units = std::move(t.units);
  r.rows = std::move(t.rows);
}

template <typename T>
T Get(const nlohmann::json& j, const char* key, const std::string& where) {
  if (!j.is_object() || !j.contains(key)) {
    throw InputError(
        fmt::format("{}: key '{}' missing (expected a chasles simulate JSON)", where, key));
  }
  try {
    return j.at(key).get<T>();
  } catch (const nlohmann::json::exception& e) {
    throw InputError(fmt::format("{}: key '{}': {}", where, key, e.what()));
  }
}

/// The array under `key` (`required`: it must be there), by reference: a summary's arrays are
/// walked, never copied.
const nlohmann::json& Array(const nlohmann::json& j, const char* key, bool required,
                            const std::string& where) {
  static const nlohmann::json empty = nlohmann::json::array();
  if (!j.contains(key)) {
    if (!required) return empty;
    throw InputError(
        fmt::format("{}: key '{}' missing (expected a chasles simulate JSON)", where, key));
  }
  const nlohmann::json& a = j.at(key);
  if (!a.is_array()) {
    throw InputError(
        fmt::format("{}: key '{}': expected an array, got {}", where, key, a.type_name()));
  }
  return a;
}

/// The events, contact-mode changes, impacts and jumps of the summary.
void ReadTimeline(const nlohmann::json& j, const std::string& json, StudyResult& r) {
  for (const auto& e : Array(j, "events", true, json)) {
    const std::string where = json + ": events";
    StudyEvent ev;
    ev.name = Get<std::string>(e, "name", where);
    ev.t = Get<double>(e, "t", where);
    ev.stopped = e.is_object() && e.contains("stopped") && e.at("stopped").is_boolean() &&
                 e.at("stopped").get<bool>();
    r.events.push_back(ev);
  }
  for (const auto& e : Array(j, "contact_events", false, json)) {
    const std::string where = json + ": contact_events";
    r.contact_events.push_back(
        {Get<double>(e, "t", where), Get<std::string>(e, "point", where),
         Get<std::string>(e, "contact", where),
         ParseStudyContactMode(Get<std::string>(e, "from", where), where + ": from"),
         ParseStudyContactMode(Get<std::string>(e, "to", where), where + ": to"),
         ParseContactEventReason(Get<std::string>(e, "reason", where), where + ": reason")});
  }
  for (const auto& e : Array(j, "impacts", false, json)) {
    const std::string where = json + ": impacts";
    StudyImpact x;
    x.t = Get<double>(e, "t", where);
    x.point = Get<std::string>(e, "point", where);
    x.energy_lost = Get<double>(e, "energy_lost", where);
    r.impacts.push_back(x);
  }
  for (const auto& e : Array(j, "jumps", false, json)) {
    const std::string where = json + ": jumps";
    StudyJump x;
    x.t = Get<double>(e, "t", where);
    x.kind = ParseStudyJumpKind(Get<std::string>(e, "kind", where), where);
    x.description = Get<std::string>(e, "description", where);
    r.jumps.push_back(x);
  }
}

/// Every pose the replay draws is a rotation: each body's quaternion columns have norm 1 (to
/// 1e-6, far looser than any written precision) in every row.
void CheckQuaternions(const Scene& scene, const StudyResult& r, const std::string& csv) {
  constexpr double kUnitTolerance = 1e-6;
  const auto col = [&](const std::string& name) {
    const auto it = std::find(r.columns.begin(), r.columns.end(), name);
    return static_cast<size_t>(it - r.columns.begin());
  };
  for (const SceneBody& b : scene.bodies) {
    const size_t w = col(b.name + "_qw"), x = col(b.name + "_qx"), y = col(b.name + "_qy"),
                 z = col(b.name + "_qz");
    if (std::max({w, x, y, z}) >= r.columns.size()) continue;
    for (size_t k = 0; k < r.rows.size(); ++k) {
      const auto& row = r.rows[k];
      const double n =
          std::sqrt(row[w] * row[w] + row[x] * row[x] + row[y] * row[y] + row[z] * row[z]);
      if (!(std::abs(n - 1.0) <= kUnitTolerance)) {
        throw InputError(fmt::format(
            "{}:{}: body '{}': the quaternion [{}, {}, {}, {}] has norm {:.9g}, not 1; it is not a "
            "rotation the report can draw",
            csv, k + 2, b.name, row[w], row[x], row[y], row[z], n));
      }
    }
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
  cmd->add_option("--max-scene-bytes", args.max_scene_bytes, "Largest scene file read (bytes)")
      ->check(WholeNumber(kMaxWholeNumber));
  cmd->add_option("--max-input-bytes", args.max_input_bytes,
                  "Largest JSON summary or CSV read, in bytes (default 268435456, 256 MiB)")
      ->check(WholeNumber(kMaxWholeNumber));
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
  OutputSet out;
  out.Expect(args.output, "-o");
  const std::string& json = args.run_json;
  const nlohmann::json j = ParseJsonText(
      ReadInputFile(json, "the run's JSON summary", args.max_input_bytes, "--max-input-bytes N"),
      json);
  if (!j.is_object()) {
    throw InputError(fmt::format("{}: expected a JSON object (a chasles simulate summary)", json));
  }
  SceneArgs scene_args;
  scene_args.scene = ResolveBesideJson(Get<std::string>(j, "scene", json), json);
  scene_args.set = args.set;
  scene_args.max_scene_bytes = args.max_scene_bytes;
  if (scene_args.scene.empty()) {
    throw InputError(fmt::format("{}: the run names no scene file", json));
  }
  const Scene scene = LoadScene(scene_args);

  StudyResult r;
  const std::string csv = ResolveBesideJson(Get<std::string>(j, "csv", json), json);
  ReadCsv(csv, args.max_input_bytes, r);
  ReadTimeline(j, json, r);
  // A finished run's files hold columns, not states: the poses the replay draws are read from
  // the table (its origin and quaternion columns, or its centre of mass and orientation), and
  // the data says so ("poses_from": "columns").
  std::vector<std::string> derived;
  std::string page;
  try {
    CheckQuaternions(scene, r, csv);
    ColumnPoses poses = PosesFromColumns(scene, r);
    derived = std::move(poses.derived);
    r.row_poses = std::move(poses.rows);
    page = HtmlReport(SimulationReportData(scene, r, PoseSource::kColumns));
  } catch (const InputError& e) {
    // Which run: the summary and its table, then what is wrong with them.
    throw InputError(fmt::format("the report of {} (table {}, scene {}): {}", json, csv,
                                 scene_args.scene, e.what()));
  }
  if (!derived.empty()) {
    std::printf("note: the poses of %s derived from the centre of mass and orientation columns\n",
                fmt::format("{}", fmt::join(derived, ", ")).c_str());
  }
  out.Add(args.output, std::move(page));
  out.Commit();
  std::printf("Wrote %s (the browser report of %s, %zu samples)\n", args.output.c_str(),
              json.c_str(), r.rows.size());
  return 0;
}

}  // namespace chasles::cli
