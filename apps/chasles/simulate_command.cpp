#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <map>
#include <mutex>
#include <string>
#include <unordered_set>
#include <vector>

#include <fmt/format.h>

#include "certificate_report.h"
#include "chasles/error.h"
#include "chasles/files/output_set.h"
#include "chasles/report/json_report.h"
#include "chasles/report/report_data.h"
#include "chasles/report/simulation_report.h"
#include "chasles/report/simulation_text.h"
#include "chasles/scene/scene.h"
#include "chasles/scene/study.h"
#include "chasles/scene/sweep.h"
#include "chasles/scene/units.h"
#include "cluster.h"
#include "commands.h"
#include "html_report.h"
#include "progress.h"
#include "run_limits.h"
#include "scene_args.h"
#include "sweep_output.h"

namespace chasles::cli {

CLI::App* AddSimulateCommand(CLI::App& app, SimulateArgs& args) {
  CLI::App* cmd = app.add_subcommand(
      "simulate",
      "Integrate the motion of a scene's bodies; write a CSV time series and a JSON summary "
      "(final state, events, energy/work/momentum ledger, integrator statistics)");
  AddSceneArgs(*cmd, args.scene);
  cmd->add_option("--until", args.until, "End time [s], overriding the scene's simulation.until")
      ->check(PositiveFiniteNumber("--until must be a positive time in seconds"));
  cmd->add_option("--out", args.out_dir,
                  "Directory for <scene>.csv and <scene>.json (default: the current directory)");
  cmd->add_option("--format", args.format,
                  "Report on standard output: text (default) or json; a sweep's table: CSV "
                  "(default) or json")
      ->check(CLI::IsMember({"text", "json"}));
  cmd->add_option("--columns", args.columns,
                  "CSV columns or groups, replacing the scene's output.columns, e.g. "
                  "--columns position,euler,energy (groups: docs/scene-format.md, output)")
      ->delimiter(',');
  cmd->add_flag("--strict", args.strict,
                "Exit with code 3 when a check of the certificate fails (the report's Checks "
                "section; otherwise a failed check is only a warning)");
  cmd->add_option("--units", args.units,
                  "Units of the text report: SI, US (in, lb, lbf), or a list such as 'ft,slug' "
                  "(default: the scene's own units; the CSV and JSON are always SI)");
  cmd->add_option("--html", args.html,
                  "Also write the browser report (a 3-D replay with plots, one HTML file) here; "
                  "the CSV then also holds the columns the report plots (ledger, reactions, "
                  "contacts); with --sweep, the quantities plotted against the swept "
                  "parameters");
  cmd->add_option("--precision", args.precision,
                  "Digits of the CSV's numbers: default (the shortest text that reads back as "
                  "the same double) or full (every double with %.17g)")
      ->check(CLI::IsMember({"default", "full"}));
  cmd->add_flag("--full-precision", args.full_precision, "The same as --precision full");
  AddRunLimitOptions(*cmd, args);
  AddSweepOptions(*cmd, args.sweep, args.quantity, args.jobs, args.max_runs,
                  "final(COLUMN), max(COLUMN), min(COLUMN) (over the samples and the events), "
                  "event(NAME) (time of its first firing; event(NAME, k) the k-th), "
                  "event(NAME2) - event(NAME1), or t_end (repeatable)");
  cmd->add_option("--keep-runs", args.keep_runs,
                  "With --sweep, also write each run's CSV and JSON in this folder, named by the "
                  "scene and the parameter values (<scene>_L=0.5_theta0=0.1.csv)");
  cmd->footer(
      "Examples:\n"
      "  chasles simulate examples/dzhanibekov.yaml --out results\n"
      "  chasles simulate examples/dzhanibekov.yaml --html dzhanibekov.html\n"
      "  chasles simulate examples/projectile-drag.yaml --set 'c=0.2 N*s/m' --format json\n"
      "  chasles simulate examples/spring-mass.yaml --until 20\n"
      "  chasles simulate examples/problem-8.26-spinning-ball.yaml --sweep 'mu_k=0.2:0.5:4' "
      "--quantity 'final(ball_vx)' --quantity 'max(floor_f)'\n"
      "Progress goes to standard error: redrawn on a terminal after the first second, one "
      "line every 10 s otherwise (--quiet: none). Scene keys: docs/scene-format.md, section "
      "Dynamics; limits: docs/reliability-limits.md; sweeps: docs/sweeps.md.\n"
      "Exit codes: 0 success, 2 bad input, 3 a check failed (a sweep: or a point failed) with "
      "--strict, 1 internal error.");
  return cmd;
}

namespace {

/// Whether kept runs are named with every parameter value in full (the shortest text that
/// reads back as the same double) rather than with 12 significant digits, as docs/sweeps.md
/// names them: only when two points of the grid would have one name at 12 digits, so that no
/// run's files replace another's.
bool KeptRunNamesInFull(const Scene& base, const std::vector<SweepSpec>& specs,
                        std::int64_t max_runs) {
  const SweepGrid grid = MakeSweepGrid(base, specs, max_runs);
  std::unordered_set<std::string> names;
  for (std::int64_t k = 0; k < grid.parameters.size(); ++k) {
    std::string name;
    for (const double v : grid.parameters.Values(k)) name += fmt::format("_{:.12g}", v);
    if (!names.insert(name).second) return true;
  }
  return false;
}

/// The run at each point of a grid (simulate --sweep): a table of the quantities on standard
/// output, each run's files in --keep-runs when asked.
int RunSimulateSweep(const SimulateArgs& args) {
  if (args.scene.scene.empty()) {
    throw InputError("chasles simulate --sweep needs a scene file (chasles simulate --help)");
  }
  if (!args.out_dir.empty()) {
    throw InputError(
        "--out writes one run's files; with --sweep use --keep-runs DIR for every run's CSV and "
        "JSON");
  }
  // Every target is checked before the first run: the table (standard output), the page and
  // the folder of kept runs.
  OutputSet out;
  out.Expect("-", "the table");
  if (!args.html.empty()) {
    RequireHtmlReport("--html");
    out.Expect(args.html, "--html");
  }
  if (!args.units.empty()) {
    throw InputError("--units sets the text report's units; a sweep's table is in SI");
  }
  const std::vector<SweepSpec> specs = ParseSweeps(args.sweep);
  std::vector<SweepQuantity> quantities;
  for (const std::string& q : args.quantity) {
    quantities.push_back(ParseSweepQuantity(q, "command line", "--quantity"));
  }
  StudySweepOptions options;
  if (!std::isnan(args.until)) options.study.until = args.until;
  ApplyRunLimitOptions(args, options.study);
  options.columns = args.columns;
  SweepRunOptions run_options;
  run_options.jobs = args.jobs;
  // Under mpirun: this rank's points; rank 0 gathers the rows and alone writes (cluster.h).
  const Cluster& cluster = Cluster::Get();
  run_options.share = cluster.share();
  const std::string stem =
      args.scene.scene.empty() ? "demo" : std::filesystem::path(args.scene.scene).stem().string();
  const std::int64_t max_runs = args.max_runs > 0 ? args.max_runs : kDefaultMaxRuns;
  bool names_in_full = false;
  if (!args.keep_runs.empty()) {
    CheckOutputFolder(args.keep_runs, "--keep-runs");
    names_in_full = KeptRunNamesInFull(LoadScene(args.scene), specs, max_runs);
    CreateOutputFolder(args.keep_runs);
  }
  // Warnings of the runs (failed checks), by point, printed in grid order afterwards.
  std::mutex mutex;
  SweepWarnings warnings;
  bool check_failed = false;
  options.on_run = [&](std::int64_t k, const Scene& scene, const StudyResult& r) {
    std::string name = stem;
    for (const SweepSpec& s : specs) {
      for (const auto& [n, q] : scene.parameters) {
        if (n == s.name) {
          name += names_in_full ? fmt::format("_{}={}", n, q.value)
                                : fmt::format("_{}={:.12g}", n, q.value);
        }
      }
    }
    if (!args.keep_runs.empty()) {
      const std::filesystem::path dir = args.keep_runs;
      const std::string csv_path = (dir / (name + ".csv")).string();
      OutputSet files;
      files.Add(csv_path, SimulationCsv(r));
      files.Add((dir / (name + ".json")).string(),
                DumpJson(SimulationJson(
                             r, ReportHeader{scene.file, scene.title, scene.planar, scene.warnings},
                             csv_path),
                         "the JSON summary"));
      files.Commit();
    }
    const std::lock_guard<std::mutex> lock(mutex);
    for (const std::string& w : r.certificate.FailureMessages()) {
      warnings[k].push_back(fmt::format("{}: {}", name, w));
      check_failed = true;
    }
  };
  SweepTable table;
  {
    Progress progress("simulate --sweep", "", args.quiet || cluster.rank() != 0,
                      args.progress_interval);
    run_options.progress = [&progress](std::int64_t done, std::int64_t total) {
      progress.Update(static_cast<double>(done), static_cast<double>(total));
    };
    const SceneStudySweep sweep =
        MakeStudySweep(SceneLoader(args.scene), SceneOptionsFrom(args.scene), specs, quantities,
                       options, max_runs);
    table = SimulateSweep(sweep.grid.parameters, quantities, sweep.units, sweep.point, run_options);
  }
  if (!GatherSweep(&table, &warnings, &check_failed)) return 0;
  for (const auto& [k, list] : warnings) {
    for (const std::string& w : list) std::fprintf(stderr, "warning: %s\n", w.c_str());
  }
  const int failed = AddSweepTable(
      out, table, args.format,
      args.full_precision ? CsvPrecision::kFull : ParseCsvPrecision(args.precision), "-");
  if (!args.html.empty()) {
    out.Add(args.html, HtmlReport(SweepReportData(LoadScene(args.scene), table, "simulate")));
  }
  out.Commit();
  SayWroteHtmlReport(args.html);
  return args.strict && (failed > 0 || check_failed) ? kExitCheckFailed : 0;
}

}  // namespace

int RunSimulate(const SimulateArgs& args) {
  if (!args.sweep.empty()) return RunSimulateSweep(args);
  if (!args.quantity.empty() || !args.keep_runs.empty() || args.jobs > 0 || args.max_runs > 0) {
    throw InputError(fmt::format("{} goes with --sweep", !args.quantity.empty()    ? "--quantity"
                                                         : !args.keep_runs.empty() ? "--keep-runs"
                                                         : args.jobs > 0           ? "--jobs"
                                                                                   : "--max-runs"));
  }
  if (args.scene.scene.empty()) {
    throw InputError("chasles simulate needs a scene file (chasles simulate --help)");
  }
  // Every target is checked before the run: the folder, the CSV, the JSON, the page.
  const SimulationFiles paths = SimulationFilesIn(args.out_dir, args.scene.scene);
  const std::string& csv_path = paths.csv;
  const std::string& json_path = paths.json;
  OutputSet files;
  files.ExpectFolder(args.out_dir.empty() ? "." : args.out_dir, "--out");
  files.Expect(csv_path, "--out");
  files.Expect(json_path, "--out");
  files.Expect("-", "the report");
  if (!args.html.empty()) {
    RequireHtmlReport("--html");
    files.Expect(args.html, "--html");
  }
  Scene scene = LoadScene(args.scene);
  if (!args.columns.empty()) scene.dynamics.columns = SelectColumns(scene, args.columns);
  // Checked before the run, so a mistyped unit does not waste a long simulation.
  const TextOptions text{args.units, csv_path, json_path};
  TextUnits(scene, text);
  StudyOptions options;
  if (!std::isnan(args.until)) {
    if (!(args.until > 0) || !std::isfinite(args.until)) {
      throw InputError(
          fmt::format("--until must be a positive time in seconds, got {}", args.until));
    }
    options.until = args.until;
  }
  ApplyRunLimitOptions(args, options);
  if (!args.html.empty()) {
    // The replay needs every body's pose at every sample (recorded from the states, whatever
    // the columns), the plots the ledger, reaction and contact columns, and the arrows the
    // forces at every sample.
    scene.dynamics.columns = ReportColumns(scene, scene.dynamics.columns);
    options.record_row_snapshots = true;
    options.record_row_poses = true;
  }
  const double t_end =
      std::isfinite(options.until) ? options.until : scene.dynamics.simulation.until;
  StudyResult r;
  {
    Progress progress("simulating", "s", args.quiet, args.progress_interval);
    options.progress = [&](double t) { progress.Update(t, t_end); };
    r = RunStudy(MakeStudyDefinition(scene, options));
  }

  // Every output is made and checked (no non-finite number) before any file appears; then
  // the CSV and the JSON appear together or not at all (output_set.h).
  const std::string csv_text = SimulationCsv(
      r, args.full_precision ? CsvPrecision::kFull : ParseCsvPrecision(args.precision));
  const std::string json_text = DumpJson(
      SimulationJson(r, ReportHeader{scene.file, scene.title, scene.planar, scene.warnings},
                     csv_path),
      "the JSON summary");
  std::string report = args.format == "json" ? json_text : SimulationText(scene, r, text);
  files.Add(csv_path, csv_text);
  files.Add(json_path, json_text);
  if (!args.html.empty()) {
    files.Add(args.html, HtmlReport(SimulationReportData(scene, r)));
    if (args.format != "json") report += fmt::format("Wrote {} (the browser report)\n", args.html);
  }
  files.Add("-", report);
  files.Commit();
  return args.strict && !r.certificate.passed() ? kExitCheckFailed : 0;
}

}  // namespace chasles::cli
