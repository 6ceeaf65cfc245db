// chasles plot: the SVG's axis labels and one line per series, the PNG's pixels, bad input.
// Built with the plot command only (PLplot found: CHASLES_HAVE_PLOT).

#ifdef CHASLES_HAVE_PLOT

#include <png.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "cli_runner.h"

namespace chasles::test {
namespace {

using ::testing::HasSubstr;

std::string ReadFile(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

/// The SVG's text with the character references (&#xHH;) PLplot's svg driver writes decoded,
/// one string per <tspan>.
std::vector<std::string> SvgTexts(const std::string& svg) {
  std::vector<std::string> out;
  const std::regex tspan("<tspan[^>]*>([^<]*)</tspan>");
  for (auto it = std::sregex_iterator(svg.begin(), svg.end(), tspan); it != std::sregex_iterator();
       ++it) {
    const std::string raw = (*it)[1];
    std::string text;
    for (size_t i = 0; i < raw.size(); ++i) {
      if (raw.compare(i, 3, "&#x") == 0) {
        const size_t end = raw.find(';', i);
        text += static_cast<char>(std::strtol(raw.substr(i + 3, end - i - 3).c_str(), nullptr, 16));
        i = end;
      } else {
        text += raw[i];
      }
    }
    out.push_back(text);
  }
  return out;
}

bool Has(const std::vector<std::string>& texts, const std::string& text) {
  return std::find(texts.begin(), texts.end(), text) != texts.end();
}

/// The number of points of each polyline drawn in `colour` ("#1F77B4"), smallest first.
std::vector<size_t> PolylinePoints(const std::string& svg, const std::string& colour) {
  std::vector<size_t> out;
  const std::regex line("<polyline[^>]*stroke=\"" + colour + "\"[^>]*points=\"([^\"]*)\"");
  for (auto it = std::sregex_iterator(svg.begin(), svg.end(), line); it != std::sregex_iterator();
       ++it) {
    std::stringstream points((*it)[1].str());
    size_t n = 0;
    for (std::string p; points >> p;) ++n;
    out.push_back(n);
  }
  std::sort(out.begin(), out.end());
  return out;
}

struct PlotRun {
  std::filesystem::path dir, json, csv;
  size_t rows = 0;
};

const PlotRun& SpringMass() {
  static const PlotRun run = [] {
    PlotRun r;
    r.dir = OutDir("plot");
    const auto j = SimulateJson(SourcePath("examples/spring-mass.yaml"), r.dir, "--quiet");
    r.json = r.dir / "spring-mass.json";
    r.csv = j.at("csv").get<std::string>();
    r.rows = ReadCsv(r.csv.string()).at("t").size();
    return r;
  }();
  return run;
}

TEST(Plot, SvgHasTheAxisLabelsWithUnitsALegendAndOneLinePerSeries) {
  const PlotRun& run = SpringMass();
  const auto svg_path = run.dir / "spring.svg";
  const CliResult r =
      RunCli("plot " + Quote(run.json.string()) + " t block_x E -o " + Quote(svg_path.string()));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string svg = ReadFile(svg_path);
  ASSERT_THAT(svg, HasSubstr("<svg"));
  const std::vector<std::string> texts = SvgTexts(svg);
  // The x axis label and the legend's entries, names with their units from the CSV header.
  EXPECT_TRUE(Has(texts, "t [s]")) << "t [s]";
  EXPECT_TRUE(Has(texts, "block_x [m]")) << "block_x [m]";
  EXPECT_TRUE(Has(texts, "E [J]")) << "E [J]";
  // Each series in its own colour: one line through every row, plus its legend sample (2
  // points).
  for (const std::string colour : {"#1F77B4", "#D62728"}) {
    EXPECT_EQ(PolylinePoints(svg, colour), (std::vector<size_t>{2, run.rows})) << colour;
  }
  EXPECT_TRUE(PolylinePoints(svg, "#2CA02C").empty());  // no third series
}

TEST(Plot, PngHasTheSignatureAndTheSeriesColours) {
  const PlotRun& run = SpringMass();
  const auto png_path = run.dir / "spring.png";
  const CliResult r =
      RunCli("plot " + Quote(run.csv.string()) + " t block_x E -o " + Quote(png_path.string()));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string bytes = ReadFile(png_path);
  ASSERT_GE(bytes.size(), 8u);
  EXPECT_EQ(bytes.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  ASSERT_TRUE(png_image_begin_read_from_memory(&image, bytes.data(), bytes.size()));
  image.format = PNG_FORMAT_RGB;
  std::vector<unsigned char> pixels(PNG_IMAGE_SIZE(image));
  ASSERT_TRUE(png_image_finish_read(&image, nullptr, pixels.data(), 0, nullptr));
  EXPECT_EQ(image.width, 960u);
  EXPECT_EQ(image.height, 640u);
  // Pixels of the first two series' colours (31, 119, 180) and (214, 39, 40), and of the
  // black axes: the image is not blank.
  size_t blue = 0, red = 0, black = 0;
  for (size_t i = 0; i + 2 < pixels.size(); i += 3) {
    const int R = pixels[i], G = pixels[i + 1], B = pixels[i + 2];
    blue += R == 31 && G == 119 && B == 180;
    red += R == 214 && G == 39 && B == 40;
    black += R == 0 && G == 0 && B == 0;
  }
  EXPECT_GT(blue, 100u);
  EXPECT_GT(red, 100u);
  EXPECT_GT(black, 100u);
}

TEST(Plot, ASweepTablePlots) {
  const auto dir = OutDir("plot_sweep");
  const auto csv = dir / "sweep.csv";
  const CliResult s =
      RunCli("solve " + Quote(SourcePath("examples/example-8.3-cylinder-incline.yaml")) +
             " --quiet --sweep 'theta=10 deg:50 deg:9' -o " + Quote(csv.string()));
  ASSERT_EQ(s.exit_code, 0) << s.err;
  const CliResult r = RunCli("plot " + Quote(csv.string()) + " theta contact_N -o " +
                             Quote((dir / "sweep.svg").string()));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string svg = ReadFile(dir / "sweep.svg");
  EXPECT_TRUE(Has(SvgTexts(svg), "theta [rad]")) << "theta [rad]";
  EXPECT_TRUE(Has(SvgTexts(svg), "contact_N [N]")) << "contact_N [N]";
  EXPECT_EQ(PolylinePoints(svg, "#1F77B4"), (std::vector<size_t>{2, 9}));
}

// A grid sweep plotted with --by: one line per value of the other parameter, labelled with it;
// a failed point (empty values, its reason in the "error" column) is left out and said.
TEST(Plot, ByDrawsOneLinePerValueAndFailedPointsAreLeftOut) {
  const auto dir = OutDir("plot");
  const auto csv = dir / "grid.csv";
  std::ofstream(csv) << "L [m],theta0 [rad],event(bottom) [s],error\n"
                        "0.5,0.1,0.36,\n0.5,0.2,0.37,\n0.5,0.3,0.38,\n"
                        "1,0.1,0.5,\n1,0.2,,\"the event 'bottom' did not fire\"\n1,0.3,0.52,\n";
  const CliResult r = RunCli("plot " + Quote(csv.string()) + " theta0 'event(bottom)' --by L -o " +
                             Quote((dir / "grid.svg").string()));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.err, HasSubstr("1 failed point(s) of the sweep left out"));
  const std::string svg = ReadFile(dir / "grid.svg");
  const std::vector<std::string> texts = SvgTexts(svg);
  EXPECT_TRUE(Has(texts, "theta0 [rad]")) << "theta0 [rad]";
  EXPECT_TRUE(Has(texts, "event(bottom) [s], L = 0.5 m")) << "L = 0.5";
  EXPECT_TRUE(Has(texts, "event(bottom) [s], L = 1 m")) << "L = 1";
  // L = 0.5 m: three points; L = 1 m: two (one failed); each with its legend sample.
  EXPECT_EQ(PolylinePoints(svg, "#1F77B4"), (std::vector<size_t>{2, 3}));
  EXPECT_EQ(PolylinePoints(svg, "#D62728"), (std::vector<size_t>{2, 2}));
  const CliResult bad =
      RunCli("plot " + Quote(csv.string()) + " theta0 'event(bottom)' --by M -o " +
             Quote((dir / "grid2.svg").string()));
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_THAT(bad.err, HasSubstr("no column 'M'"));
}

// --log: both axes base-10 logarithmic; a point with a value <= 0 has no logarithm and is left
// out with a note (here the dense column's n = 1000, not timed).
TEST(Plot, LogDrawsLogLogAxesAndLeavesOutPointsThatAreNotPositive) {
  const auto dir = OutDir("plot");
  const auto csv = dir / "cost.csv";
  std::ofstream(csv) << "n,sparse [s],dense [s]\n10,1e-5,1e-3\n100,1e-4,1\n1000,1e-3,0\n";
  const CliResult r = RunCli("plot " + Quote(csv.string()) + " n sparse dense --log -o " +
                             Quote((dir / "cost.svg").string()));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.err, HasSubstr("1 point(s) not positive left out of the log-log plot"));
  const std::string svg = ReadFile(dir / "cost.svg");
  // sparse: three points; dense: two (n = 1000 not timed); each with its legend sample.
  EXPECT_EQ(PolylinePoints(svg, "#1F77B4"), (std::vector<size_t>{2, 3}));
  EXPECT_EQ(PolylinePoints(svg, "#D62728"), (std::vector<size_t>{2, 2}));
}

TEST(Plot, AMissingColumnOrABadFileIsBadInput) {
  const PlotRun& run = SpringMass();
  const std::string out = Quote((run.dir / "x.svg").string());
  const CliResult missing = RunCli("plot " + Quote(run.json.string()) + " t block_w -o " + out);
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_THAT(missing.err, HasSubstr("no column 'block_w'; columns: t, block_x, block_y"));
  EXPECT_FALSE(std::filesystem::exists(run.dir / "x.svg"));
  const CliResult ext = RunCli("plot " + Quote(run.json.string()) + " t block_x -o " +
                               Quote((run.dir / "x.gif").string()));
  EXPECT_EQ(ext.exit_code, 2);
  EXPECT_THAT(ext.err, HasSubstr(".svg or .png"));
  const CliResult one = RunCli("plot " + Quote(run.json.string()) + " t -o " + out);
  EXPECT_EQ(one.exit_code, 2);
  const CliResult nofile =
      RunCli("plot " + Quote((run.dir / "none.csv").string()) + " t block_x -o " + out);
  EXPECT_EQ(nofile.exit_code, 2);
  EXPECT_THAT(nofile.err, HasSubstr("none.csv"));
}

}  // namespace
}  // namespace chasles::test

#endif  // CHASLES_HAVE_PLOT
