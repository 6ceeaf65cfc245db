// chasles plot RUN.json|RUN.csv|SWEEP.csv X Y [Y...] -o plot.svg|plot.png: columns of a table
// the program wrote, drawn by PLplot (plot_render.h): axes labelled with the columns' names
// and units from the CSV header (chasles/report/csv_table.h), one line per Y column, a legend.
// Built only when PLplot is found (CMake option CHASLES_PLOT).

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "chasles/error.h"
#include "chasles/files/input_file.h"
#include "chasles/files/output_set.h"
#include "chasles/report/csv_table.h"
#include "chasles/report/json_input.h"
#include "commands.h"
#include "plot/plot_render.h"
#include "scene_args.h"

// Under LeakSanitizer (the sanitizer build, scripts/test.sh --sanitize): fontconfig's cache
// (pngcairo's fonts) and PLplot's driver loader (libltdl) keep their memory until exit by
// design; the program's own allocations are still checked. Unused in other builds.
extern "C" const char* __lsan_default_suppressions() {
  return "leak:libfontconfig.so\nleak:libltdl.so\n";
}

namespace chasles::cli {

namespace {

/// The CSV to plot: the file itself, or for a run's JSON summary the CSV it names under "csv"
/// (as written when it exists, else beside the JSON, as `chasles report` finds it).
std::string CsvPath(const std::string& input, size_t max_bytes) {
  if (std::filesystem::path(input).extension() != ".json") return input;
  const nlohmann::json j = ParseJsonText(
      ReadInputFile(input, "the run's JSON summary", max_bytes, "--max-input-bytes N"), input);
  if (!j.is_object() || !j.contains("csv") || !j.at("csv").is_string()) {
    throw InputError(fmt::format(
        "{}: key 'csv' missing (expected a chasles simulate JSON summary naming its CSV)", input));
  }
  return ResolveBesideJson(j.at("csv").get<std::string>(), input);
}

/// "name [unit]" of column `c`, as the CSV header has it, checked as a plot's text.
std::string Label(const CsvTable& t, size_t c, const std::string& csv) {
  std::string label = CsvHeaderField(t.columns[c], t.units[c]);
  const std::string shown =
      t.columns[c].size() > 40 ? t.columns[c].substr(0, 40) + "..." : t.columns[c];
  CheckPlotText(label, fmt::format("{}: the label of column '{}'", csv, shown));
  return label;
}

/// The values of column `by` in the rows plotted, in the order the table first has them; at
/// most kMaxPlotSeries / `lines` of them.
std::vector<double> Groups(const CsvTable& t, const std::vector<size_t>& rows, size_t by,
                           size_t lines, const std::string& option) {
  std::vector<double> groups;
  for (const size_t r : rows) {
    if (std::find(groups.begin(), groups.end(), t.rows[r][by]) != groups.end()) continue;
    groups.push_back(t.rows[r][by]);
    if (groups.size() * lines > kMaxPlotSeries) {
      throw InputError(
          fmt::format("{} {}: more than {} lines to draw ({} Y column(s) times the "
                      "values of '{}'); a plot has at most {} lines",
                      option, t.columns[by], kMaxPlotSeries, lines, t.columns[by], kMaxPlotSeries));
    }
  }
  return groups;
}

}  // namespace

CLI::App* AddPlotCommand(CLI::App& app, PlotArgs& args) {
  CLI::App* cmd = app.add_subcommand(
      "plot",
      "Plot columns of a run's or a sweep's table (one line per Y column, axes labelled with "
      "the columns' units, a legend) to an SVG or PNG file");
  cmd->add_option("TABLE", args.input,
                  "A run's JSON summary (its CSV is plotted), a run's CSV or a sweep's CSV")
      ->required();
  cmd->add_option("COLUMNS", args.columns, "X then one or more Y columns, by name (e.g. t car_x)")
      ->required()
      ->expected(2, -1);
  cmd->add_option("-o,--output", args.output, "The plot to write: FILE.svg or FILE.png")
      ->required();
  cmd->add_option("--title", args.title, "A title above the plot (default: none)");
  cmd->add_flag("--log", args.log,
                "Both axes logarithmic (base 10); points with x <= 0 or y <= 0 are left out "
                "(e.g. a cost curve of time against size)");
  cmd->add_option("--max-input-bytes", args.max_input_bytes,
                  "Largest table or summary read, in bytes (default 268435456, 256 MiB)")
      ->check(WholeNumber(kMaxWholeNumber));
  cmd->add_option("--by", args.by,
                  "One line per value of this column (e.g. a grid sweep's other parameter), "
                  "labelled with the value in the legend");
  cmd->footer(
      "Examples:\n"
      "  chasles simulate examples/spring-mass.yaml --out results\n"
      "  chasles plot results/spring-mass.json t block_z -o block.svg\n"
      "  chasles solve examples/example-8.3-cylinder-incline.yaml --sweep 'theta=10 deg:50 "
      "deg:9' -o sweep.csv\n"
      "  chasles plot sweep.csv theta contact_N contact_f -o forces.png\n"
      "  chasles simulate examples/pendulum.yaml --sweep 'L=0.5 m:2 m:4' --sweep "
      "'theta0=10 deg:60 deg:6' --quantity 'event(bottom)' > grid.csv\n"
      "  chasles plot grid.csv theta0 'event(bottom)' --by L -o quarter-period.svg\n"
      "Exit codes: 0 success, 2 bad input (a column that does not exist: the message lists the "
      "columns), 1 internal error.");
  return cmd;
}

int RunPlot(const PlotArgs& args) {
  const std::string ext = std::filesystem::path(args.output).extension().string();
  if (ext != ".svg" && ext != ".png") {
    throw InputError(fmt::format("-o {}: expected a file ending in .svg or .png", args.output));
  }
  OutputSet out;
  out.Expect(args.output, "-o");
  PlotSpec spec;
  spec.png = ext == ".png";
  spec.log = args.log;
  spec.title = args.title;
  CheckPlotText(spec.title, "--title");
  const std::string csv = CsvPath(args.input, args.max_input_bytes);
  const CsvTable t = ReadCsvTable(
      ReadInputFile(csv, "the table to plot", args.max_input_bytes, "--max-input-bytes N"), csv);
  const size_t x = CsvColumnIndex(t, args.columns[0], csv);
  std::vector<size_t> ys;
  for (size_t i = 1; i < args.columns.size(); ++i) {
    ys.push_back(CsvColumnIndex(t, args.columns[i], csv));
  }
  if (ys.size() > kMaxPlotSeries) {
    throw InputError(
        fmt::format("{} Y columns: a plot has at most {} lines", ys.size(), kMaxPlotSeries));
  }
  // A sweep's values that are missing (empty: a failed point, or a quantity its run could not
  // give; the "error" column says why) are left out, point by point.
  std::vector<size_t> rows;
  size_t missing = 0;
  for (size_t r = 0; r < t.rows.size(); ++r) {
    bool some = false;
    for (size_t y : ys) {
      const bool given = std::isfinite(t.rows[r][x]) && std::isfinite(t.rows[r][y]);
      some = some || given;
      missing += given ? 0 : 1;
    }
    if (some) rows.push_back(r);
  }
  if (rows.empty()) throw InputError(fmt::format("{}: the table has no rows to plot", csv));
  if (missing > 0) {
    std::fprintf(stderr, "note: %s: %zu failed point(s) of the sweep left out of the plot\n",
                 csv.c_str(), missing);
  }
  // The series: one per Y column, or with --by one per Y column and value of that column (in
  // the order the table first has it), labelled "Y [unit], BY = value".
  std::vector<double> groups = {0.0};
  size_t by = 0;
  if (!args.by.empty()) {
    by = CsvColumnIndex(t, args.by, csv);
    groups = Groups(t, rows, by, ys.size(), "--by");
  }
  size_t left_out = 0, points = 0;
  for (size_t y : ys) {
    for (double g : groups) {
      PlotSeries s;
      s.label = Label(t, y, csv);
      if (!args.by.empty()) {
        s.label += fmt::format(", {} = {:.6g}{}", t.columns[by], g,
                               t.units[by].empty() ? "" : " " + t.units[by]);
        CheckPlotText(s.label, fmt::format("{}: the legend entry of column '{}' by '{}'", csv,
                                           args.columns[1], args.by));
      }
      for (size_t r : rows) {
        if (!args.by.empty() && t.rows[r][by] != g) continue;
        if (!std::isfinite(t.rows[r][y])) continue;  // counted in `missing`
        // A logarithmic axis has no place for x <= 0 or y <= 0: such points are left out.
        if (args.log && !(t.rows[r][x] > 0.0 && t.rows[r][y] > 0.0)) {
          ++left_out;
          continue;
        }
        s.x.push_back(args.log ? std::log10(t.rows[r][x]) : t.rows[r][x]);
        s.y.push_back(args.log ? std::log10(t.rows[r][y]) : t.rows[r][y]);
      }
      points += s.x.size();
      spec.series.push_back(std::move(s));
    }
  }
  if (left_out > 0) {
    std::fprintf(stderr, "note: %s: %zu point(s) not positive left out of the log-log plot\n",
                 csv.c_str(), left_out);
  }
  if (points == 0) {
    throw InputError(fmt::format(
        "{}: no point has x > 0 and y > 0, so none can be drawn on --log axes (plot without "
        "--log)",
        csv));
  }
  // The Y axis: the column's label for one, "[unit]" for several of one unit, else the legend.
  spec.ylabel = Label(t, ys[0], csv);
  for (size_t y : ys) {
    if (t.units[y] != t.units[ys[0]]) spec.ylabel.clear();
  }
  if (!spec.ylabel.empty() && ys.size() > 1) {
    spec.ylabel = t.units[ys[0]].empty() ? "" : "[" + t.units[ys[0]] + "]";
  }
  spec.xlabel = Label(t, x, csv);
  out.Add(args.output, RenderPlot(spec));
  out.Commit();
  std::printf("Wrote %s (%zu series, %zu points in all, from %s)\n", args.output.c_str(),
              spec.series.size(), points, csv.c_str());
  return 0;
}

}  // namespace chasles::cli
