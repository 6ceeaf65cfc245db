// chasles solve: the instantaneous problem of chapter 8.2-8.3 at a scene's initial state —
// every body's acceleration and every constraint's reaction ("what force does the support
// exert?"), and for rolling the friction it needs against mu_s. Scenes with contacts get their
// modes chosen first (SelectContactModes: which points press, stick or slide) and a report per
// contact point. With --sweep, the same over a range of one parameter, as a table.

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "certificate_report.h"
#include "chasles/error.h"
#include "chasles/files/output_set.h"
#include "chasles/report/json_report.h"
#include "chasles/report/report_data.h"
#include "chasles/report/solve_json.h"
#include "chasles/report/solve_text.h"
#include "chasles/scene/scene.h"
#include "chasles/scene/scene_error.h"
#include "chasles/scene/solve.h"
#include "chasles/scene/study.h"
#include "cluster.h"
#include "commands.h"
#include "html_report.h"
#include "progress.h"
#include "scene_args.h"

namespace chasles::cli {

CLI::App* AddSolveCommand(CLI::App& app, SolveArgs& args) {
  CLI::App* cmd = app.add_subcommand(
      "solve",
      "Solve the instantaneous problem at a scene's initial state: every body's acceleration, "
      "every joint's reaction, the friction rolling needs, each contact point's mode, normal "
      "and friction force (chapter 8.2-8.3)");
  AddSceneArgs(*cmd, args.scene);
  cmd->add_option("--html", args.html,
                  "Also write the browser report here: the configuration with the force arrows "
                  "of the solved instant (one HTML file); with --sweep, every column plotted "
                  "against the swept parameter");
  cmd->add_option("--sweep", args.sweep,
                  "Repeat over a parameter range: NAME=START:STOP:COUNT (START and STOP are "
                  "expressions with units, e.g. 'theta=0 deg:60 deg:7'); prints a table");
  cmd->add_option("--format", args.format,
                  "text (default; with --sweep the CSV table), json, or csv (one row of the "
                  "solved quantities, the columns of a sweep after its parameter)")
      ->check(CLI::IsMember({"text", "json", "csv"}));
  cmd->add_option("--units", args.units,
                  "Units of the text report: SI, US (in, lb, lbf), or a list such as 'ft,slug' "
                  "(default: the scene's own units; JSON and CSV are always SI)");
  cmd->add_option("-o,--out,--output", args.output,
                  "Write the report (or the sweep's table) to this file instead of standard "
                  "output; the file appears complete or not at all");
  cmd->add_option("--precision", args.precision,
                  "Digits of a CSV's numbers: default (12 significant digits) or full (every "
                  "double with %.17g, reads back bitwise)")
      ->check(CLI::IsMember({"default", "full"}));
  cmd->add_flag("--full-precision", args.full_precision, "The same as --precision full");
  cmd->add_flag("--strict", args.strict,
                "Exit with code 3 when a check of the answer fails (the report's Checks section; "
                "otherwise a failed check is only a warning)");
  cmd->add_option("--max-rows", args.max_rows,
                  "Most values of a sweep (its rows; default 1000000); a larger COUNT is refused")
      ->check(WholeNumber(kMaxWholeNumber));
  cmd->add_flag("--quiet", args.quiet,
                "No progress of a sweep on standard error (otherwise: redrawn on a terminal, one "
                "line every 10 s off it)");
  cmd->add_option("--progress-interval", args.progress_interval,
                  "Seconds between progress lines when standard error is not a terminal "
                  "(default 10)");
  cmd->footer(
      "Examples:\n"
      "  chasles solve examples/example-8.3-cylinder-incline.yaml\n"
      "  chasles solve examples/example-8.3-cylinder-incline.yaml --sweep 'theta=10 deg:50 "
      "deg:5'\n"
      "  chasles solve examples/example-8.3-cylinder-incline.yaml --units US -o incline.txt\n"
      "  chasles solve examples/example-8.3-cylinder-incline.yaml --format csv --full-precision\n"
      "Scene keys: docs/scene-format.md, section Joints, rolling and drivers.\n"
      "Exit codes: 0 success, 2 bad input, 3 a check failed with --strict, 1 internal error.");
  return cmd;
}

int RunSolve(const SolveArgs& args) {
  if (args.scene.scene.empty()) {
    throw InputError("chasles solve needs a scene file (chasles solve --help)");
  }
  const CsvPrecision precision =
      args.full_precision ? CsvPrecision::kFull : ParseCsvPrecision(args.precision);
  // Every target is checked before the solve, so a mistyped path does not waste a long sweep.
  OutputSet out;
  out.Expect(ReportTarget(args.output), "-o");
  if (!args.html.empty()) {
    RequireHtmlReport("--html");
    out.Expect(args.html, "--html");
  }
  if (args.sweep.empty()) {
    const Scene scene = LoadScene(args.scene);
    // Checked before the solve: a mistyped unit is bad input (exit 2).
    TextOptions text;
    text.units = args.units;
    TextUnits(scene, text);
    const SolveReport s = SolveAtState(MakeSolveDefinition(scene));
    // Every value of the JSON and the text is checked by name first (DumpJson, SolveText).
    std::string report;
    if (args.format == "json") report = DumpJson(SolveJson(s), "the solve report");
    if (args.format == "csv") report = SolveCsv(s, precision);
    if (args.format == "text") report = SolveText(scene, s, text);
    if (!args.html.empty()) out.Add(args.html, HtmlReport(SolveReportData(scene, s)));
    out.Add(ReportTarget(args.output), std::move(report));
    out.Commit();
    SayWroteHtmlReport(args.html);
    return args.strict && !s.certificate.passed() ? kExitCheckFailed : 0;
  }
  if (!args.units.empty()) {
    throw InputError("--units sets the units of the text report; a sweep's table is SI");
  }
  const SweepSpec sweep = ParseSweep(args.sweep, "command line", "--sweep");
  const std::int64_t max_rows = args.max_rows > 0 ? args.max_rows : kDefaultMaxRows;
  if (sweep.count > max_rows) {
    throw SceneError("command line", 0, 0, "--sweep",
                     fmt::format("COUNT {} is more than the limit of {} rows; raise the limit "
                                 "with --max-rows",
                                 sweep.count, max_rows));
  }
  if (!(args.progress_interval > 0) || !std::isfinite(args.progress_interval)) {
    throw InputError(fmt::format("--progress-interval must be a positive time in seconds, got {}",
                                 args.progress_interval));
  }
  // Under mpirun: this rank's values; rank 0 gathers the rows and alone writes (cluster.h).
  Cluster& cluster = Cluster::Get();
  Progress progress("solve --sweep", "", args.quiet || cluster.rank() != 0, args.progress_interval);
  SolveSweepOptions options;
  options.share = cluster.share();
  options.progress = [&progress, &cluster](int k, int count) {
    cluster.set_point(k);  // where this rank stopped, if the solve fails
    progress.Update(k, count);
  };
  // A failed check of one value: a warning on standard error (the table stays a table); under
  // mpirun kept with the value's row and printed by rank 0 in order.
  SweepWarnings warnings;
  options.on_solution = [&](int k, double value, const SolveReport& s) {
    for (const std::string& w : s.certificate.FailureMessages()) {
      if (cluster.distributed()) {
        warnings[k].push_back(fmt::format("{} = {:.12g}: {}", sweep.name, value, w));
      } else {
        std::fprintf(stderr, "warning: %s = %.12g: %s\n", sweep.name.c_str(), value, w.c_str());
      }
    }
  };
  const auto load = SceneLoader(args.scene);
  const SceneOptions scene_options = SceneOptionsFrom(args.scene);
  const std::string unit = SolveSweepUnit(load, scene_options, sweep);
  SweepTable table = SolveSweep(
      sweep.name, unit, sweep.count,
      [&](int k) { return MakeSolveSweepPoint(load, scene_options, sweep, k); }, options);
  bool check_failed = false;
  if (!GatherSweep(&table, &warnings, &check_failed)) return 0;
  if (cluster.distributed()) {
    for (const std::string& w : table.warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
  }
  CheckFiniteTable(table.columns, table.rows, "the sweep table");
  const std::string text = args.format == "json" ? DumpJson(SweepJson(table), "the sweep table")
                                                 : SweepCsv(table, precision);
  out.Add(ReportTarget(args.output), text);
  if (!args.html.empty()) {
    out.Add(args.html, HtmlReport(SweepReportData(LoadScene(args.scene), table, "solve")));
  }
  out.Commit();
  SayWroteHtmlReport(args.html);
  return args.strict && table.failed ? kExitCheckFailed : 0;
}

}  // namespace chasles::cli
