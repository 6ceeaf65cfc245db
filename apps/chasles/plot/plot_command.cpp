// chasles plot RUN.json|RUN.csv|SWEEP.csv X Y [Y...] -o plot.svg|plot.png: columns of a table
// the program wrote, drawn by PLplot (svg and pngcairo drivers): axes labelled with the
// columns' names and units from the CSV header (chasles/io/csv_table.h), one line per Y
// column, a legend. Built only when PLplot is found (CMake option CHASLES_PLOT).

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <plplot.h>
#include <unistd.h>
#include <nlohmann/json.hpp>

#include "chasles/error.h"
#include "chasles/io/atomic_file.h"
#include "chasles/io/csv_table.h"
#include "chasles/io/output_set.h"
#include "commands.h"
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
std::string CsvPath(const std::string& input) {
  if (std::filesystem::path(input).extension() != ".json") return input;
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(ReadTextFile(input, "the run's JSON summary"));
  } catch (const nlohmann::json::parse_error& e) {
    throw InputError(fmt::format("{}: not JSON: {}", input, e.what()));
  }
  if (!j.is_object() || !j.contains("csv") || !j.at("csv").is_string()) {
    throw InputError(fmt::format(
        "{}: key 'csv' missing (expected a chasles simulate JSON summary naming its CSV)", input));
  }
  return ResolveBesideJson(j.at("csv").get<std::string>(), input);
}

/// PLplot reads '#' as the start of an escape sequence; "##" is a literal '#'.
std::string PlText(const std::string& s) {
  std::string out;
  for (char c : s) out += c == '#' ? std::string("##") : std::string(1, c);
  return out;
}

/// "name [unit]" of column `c`, as the CSV header has it.
std::string Label(const CsvTable& t, size_t c) {
  return CsvHeaderField(t.columns[c], t.units[c]);
}

/// One line of the plot: its legend text and its points.
struct Series {
  std::string label;
  std::vector<double> x, y;
};

/// The axis range of values, widened when they are all equal (PLplot needs a span), with 3 %
/// margins.
void Range(const std::vector<const std::vector<double>*>& values, double& lo, double& hi) {
  lo = std::numeric_limits<double>::infinity();
  hi = -lo;
  for (const auto* v : values) {
    for (double x : *v) {
      lo = std::min(lo, x);
      hi = std::max(hi, x);
    }
  }
  if (!(hi > lo)) {
    const double pad = lo == 0.0 ? 1.0 : 0.5 * std::abs(lo);
    lo -= pad;
    hi += pad;
    return;
  }
  const double m = 0.03 * (hi - lo);
  lo -= m;
  hi += m;
}

// Series colours (cmap0 entries 2...): distinct on white, as in common plotting palettes.
constexpr int kPalette[][3] = {{31, 119, 180},  {214, 39, 40}, {44, 160, 44},   {255, 127, 14},
                               {148, 103, 189}, {140, 86, 75}, {227, 119, 194}, {127, 127, 127},
                               {188, 189, 34},  {23, 190, 207}};
constexpr int kColours = sizeof(kPalette) / sizeof(kPalette[0]);

/// Draws the series into `file` with PLplot's driver `device` ("svg" or "pngcairo"), the axes
/// labelled `xlabel` and `ylabel`.
void Render(const std::vector<Series>& series, const std::string& xlabel, const std::string& ylabel,
            const std::string& device, const std::string& file, const std::string& title,
            bool log) {
  plsdev(device.c_str());
  plsfnam(file.c_str());
  plspage(0.0, 0.0, 960, 640, 0, 0);
  // cmap0: 0 white background, 1 black axes and text, then the series colours.
  plscmap0n(2 + kColours + 1);
  plscol0(0, 255, 255, 255);
  plscol0(1, 0, 0, 0);
  for (int i = 0; i < kColours; ++i) plscol0(2 + i, kPalette[i][0], kPalette[i][1], kPalette[i][2]);
  plscol0a(2 + kColours, 255, 255, 255, 0.85);  // the legend's background
  plinit();
  plcol0(1);
  std::vector<const std::vector<double>*> xs, ys;
  for (const Series& s : series) {
    xs.push_back(&s.x);
    ys.push_back(&s.y);
  }
  double x0, x1, y0, y1;
  Range(xs, x0, x1);
  Range(ys, y0, y1);
  // Log axes: PLplot draws log10 of the values with its logarithmic axis labels (axis = 30).
  plenv(x0, x1, y0, y1, 0, log ? 30 : 0);
  pllab(PlText(xlabel).c_str(), PlText(ylabel).c_str(), PlText(title).c_str());
  for (size_t i = 0; i < series.size(); ++i) {
    plcol0(2 + static_cast<int>(i % kColours));
    plwidth(2.0);
    plline(static_cast<PLINT>(series[i].x.size()), series[i].x.data(), series[i].y.data());
  }
  plwidth(1.0);
  // The legend: one line sample and label per series, top right inside the box.
  const auto n = static_cast<PLINT>(series.size());
  std::vector<PLINT> opt(n, PL_LEGEND_LINE), colours(n), styles(n, 1), zero(n, 0),
      text_colours(n, 1), symbol_numbers(n, 0);
  std::vector<PLFLT> widths(n, 2.0), scales(n, 1.0);
  std::vector<std::string> text;
  std::vector<const char*> text_p, symbols(n, "");
  for (PLINT i = 0; i < n; ++i) {
    colours[i] = 2 + i % kColours;
    text.push_back(PlText(series[i].label));
  }
  for (const auto& s : text) text_p.push_back(s.c_str());
  PLFLT w = 0, h = 0;
  pllegend(&w, &h, PL_LEGEND_BACKGROUND | PL_LEGEND_BOUNDING_BOX,
           PL_POSITION_TOP | PL_POSITION_RIGHT | PL_POSITION_INSIDE, 0.02, 0.02, 0.08, 2 + kColours,
           1, 1, 0, 0, n, opt.data(), 1.0, 0.8, 2.0, 0.0, text_colours.data(), text_p.data(),
           nullptr, nullptr, nullptr, nullptr, colours.data(), styles.data(), widths.data(),
           zero.data(), scales.data(), symbol_numbers.data(), symbols.data());
  plend();
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
  CheckOutputTarget(args.output);
  const std::string csv = CsvPath(args.input);
  const CsvTable t = ReadCsvTable(ReadTextFile(csv, "the table to plot"), csv);
  const size_t x = CsvColumnIndex(t, args.columns[0], csv);
  std::vector<size_t> ys;
  for (size_t i = 1; i < args.columns.size(); ++i) {
    ys.push_back(CsvColumnIndex(t, args.columns[i], csv));
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
    groups.clear();
    for (size_t r : rows) {
      if (std::find(groups.begin(), groups.end(), t.rows[r][by]) == groups.end()) {
        groups.push_back(t.rows[r][by]);
      }
    }
  }
  std::vector<Series> series;
  size_t left_out = 0;
  for (size_t y : ys) {
    for (double g : groups) {
      Series s;
      s.label = Label(t, y);
      if (!args.by.empty()) {
        s.label += fmt::format(", {} = {:.6g}{}", t.columns[by], g,
                               t.units[by].empty() ? "" : " " + t.units[by]);
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
      series.push_back(std::move(s));
    }
  }
  if (left_out > 0) {
    std::fprintf(stderr, "note: %s: %zu point(s) not positive left out of the log-log plot\n",
                 csv.c_str(), left_out);
  }
  // The Y axis: the column's label for one, "[unit]" for several of one unit, else the legend.
  std::string ylabel = Label(t, ys[0]);
  for (size_t y : ys) {
    if (t.units[y] != t.units[ys[0]]) ylabel.clear();
  }
  if (!ylabel.empty() && ys.size() > 1) {
    ylabel = t.units[ys[0]].empty() ? "" : "[" + t.units[ys[0]] + "]";
  }
  // PLplot writes to a named file: a temporary beside the target, then moved into place whole.
  const std::string temp = fmt::format("{}.plot-{}.tmp", args.output, ::getpid());
  try {
    Render(series, Label(t, x), ylabel, ext == ".svg" ? "svg" : "pngcairo", temp, args.title,
           args.log);
    const std::string bytes = ReadTextFile(temp, "the plot just drawn");
    WriteFileAtomically(args.output, bytes);
  } catch (...) {
    std::filesystem::remove(temp);
    throw;
  }
  std::filesystem::remove(temp);
  std::printf("Wrote %s (%zu series, %zu points in all, from %s)\n", args.output.c_str(),
              series.size(), t.rows.size() * ys.size() - missing - left_out, csv.c_str());
  return 0;
}

}  // namespace chasles::cli
