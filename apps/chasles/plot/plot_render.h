#pragma once
/// @file
/// Drawing a plot with PLplot (svg and pngcairo drivers) into memory, so that the command's
/// output set (chasles/files/output_set.h) writes it like every other file.
///
/// PLplot is guarded where it is fragile: its texts overflow fixed buffers past about 1000
/// characters (and '#' starts an escape, doubling the text), invalid UTF-8 is dropped with a
/// message of its own, and a fatal error calls exit(). So every text is checked first
/// (CheckPlotText), PLplot writes into a memory stream instead of a file name (no '%n' family
/// names, no temporary of its own), its fatal errors come back through its exit handler as an
/// InputError, and its other error messages are collected and refused the same way.

#include <cstddef>
#include <string>
#include <vector>

namespace chasles::cli {

/// The longest label, legend entry or title a plot draws, in bytes.
inline constexpr size_t kMaxPlotTextBytes = 200;
/// The most lines in one plot (Y columns times --by values).
inline constexpr size_t kMaxPlotSeries = 100;
/// The largest plot file drawn.
inline constexpr size_t kMaxPlotBytes = size_t{256} << 20;

/// One line of the plot: its legend text and its points (finite; log10 of the values on log
/// axes).
struct PlotSeries {
  std::string label;
  std::vector<double> x, y;
};

struct PlotSpec {
  std::vector<PlotSeries> series;  // at most kMaxPlotSeries, at least one point in all
  std::string xlabel, ylabel, title;
  bool log = false;  // logarithmic axes (the points are log10 of the values)
  bool png = false;  // PNG (pngcairo), else SVG
};

/// Throws InputError unless `text` is UTF-8 of at most kMaxPlotTextBytes bytes without control
/// characters; `what` names it ("--title", "plot.csv: column 'x'").
void CheckPlotText(const std::string& text, const std::string& what);

/// The plot file's bytes. Every text of `spec` must have passed CheckPlotText. Throws
/// InputError when PLplot reports an error or the file would be larger than kMaxPlotBytes.
std::string RenderPlot(const PlotSpec& spec);

}  // namespace chasles::cli
