// The program's output files and options: CSV headers with units, --precision full, and the
// solve command's --units, -o/--out and --format csv.

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "cli_runner.h"

namespace chasles::test {
namespace {

using ::testing::HasSubstr;

constexpr double kPi = 3.14159265358979323846;
const char* const kIncline = "examples/example-8.3-cylinder-incline.yaml";

std::vector<std::string> Split(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream s(line);
  for (std::string cell; std::getline(s, cell, ',');) out.push_back(cell);
  return out;
}

std::string ReadFile(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::uint64_t Bits(double v) {
  return std::bit_cast<std::uint64_t>(v);
}

/// The header and the rows (as text fields) of a CSV.
struct RawCsv {
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;
};

RawCsv ReadRaw(const std::string& text) {
  std::stringstream in(text);
  RawCsv c;
  std::string line;
  std::getline(in, line);
  c.header = Split(line);
  while (std::getline(in, line)) c.rows.push_back(Split(line));
  return c;
}

size_t Index(const RawCsv& c, const std::string& field) {
  for (size_t i = 0; i < c.header.size(); ++i) {
    if (c.header[i] == field) return i;
  }
  ADD_FAILURE() << "no header field " << field;
  return 0;
}

TEST(Outputs, SimulateFullPrecisionReadsBackAsTheJsonFinalStateBitwise) {
  const auto dir = OutDir("outputs_full");
  const nlohmann::json j = SimulateJson(SourcePath("examples/spring-mass.yaml"), dir,
                                        "--quiet --columns position --full-precision");
  const RawCsv c = ReadRaw(ReadFile(j.at("csv").get<std::string>()));
  // Headers: name, one space, the SI unit in brackets; the JSON lists the same units.
  EXPECT_EQ(c.header,
            (std::vector<std::string>{"t [s]", "block_x [m]", "block_y [m]", "block_z [m]"}));
  EXPECT_EQ(j.at("column_units"), nlohmann::json({"s", "m", "m", "m"}));
  ASSERT_GT(c.rows.size(), 2u);
  // Every field is %.17g of the double it reads back as.
  for (const auto& row : c.rows) {
    for (const std::string& f : row)
      EXPECT_EQ(fmt::format("{:.17g}", std::strtod(f.c_str(), nullptr)), f);
  }
  // The last row is the final state: the same bits as the JSON's t_end and centre of mass
  // (nlohmann::json writes a double so that it reads back exactly).
  const auto& last = c.rows.back();
  EXPECT_EQ(Bits(std::strtod(last[Index(c, "t [s]")].c_str(), nullptr)),
            Bits(j.at("t_end").get<double>()));
  const auto& com = j.at("final").at("bodies").at(0).at("center_of_mass");
  for (int k = 0; k < 3; ++k) {
    const std::string field = std::string("block_") + "xyz"[k] + " [m]";
    EXPECT_EQ(Bits(std::strtod(last[Index(c, field)].c_str(), nullptr)),
              Bits(com.at(k).get<double>()))
        << field;
  }
  // The default stays the shortest text that reads back as the same double.
  const nlohmann::json d =
      SimulateJson(SourcePath("examples/spring-mass.yaml"), dir, "--quiet --columns position");
  for (const auto& row : ReadRaw(ReadFile(d.at("csv").get<std::string>())).rows) {
    for (const std::string& f : row)
      EXPECT_EQ(fmt::format("{}", std::strtod(f.c_str(), nullptr)), f);
  }
  const CliResult bad = RunCli("simulate " + Quote(SourcePath("examples/spring-mass.yaml")) +
                               " --out " + Quote(dir.string()) + " --precision most");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_THAT(bad.err, HasSubstr("--precision"));
}

TEST(Outputs, SweepCsvHasNoCommentLineAndFullPrecisionMatchesTheJson) {
  const std::string base =
      "solve " + Quote(SourcePath(kIncline)) + " --quiet --sweep 'theta=10 deg:50 deg:3'";
  const CliResult csv = RunCli(base + " --precision full");
  ASSERT_EQ(csv.exit_code, 0) << csv.err;
  const CliResult json = RunCli(base + " --format json");
  ASSERT_EQ(json.exit_code, 0) << json.err;
  const auto j = nlohmann::json::parse(json.out);
  const RawCsv c = ReadRaw(csv.out);
  // theta is swept in deg, so it is an angle: SI rad; accelerations in m/s^2.
  EXPECT_EQ(c.header.at(0), "theta [rad]");
  EXPECT_EQ(c.header.at(1), "cylinder_ax [m/s^2]");
  EXPECT_EQ(j.at("units"), "SI");
  ASSERT_EQ(c.rows.size(), 3u);
  for (size_t r = 0; r < 3; ++r) {
    for (size_t k = 0; k < c.header.size(); ++k) {
      EXPECT_EQ(Bits(std::strtod(c.rows[r][k].c_str(), nullptr)),
                Bits(j.at("rows").at(r).at(k).get<double>()))
          << c.header[k];
    }
  }
}

TEST(Outputs, SolveUnitsConvertTheTextReport) {
  // Example 8.3: a = (2/3) g sin 30° along the slope; the JSON's SI value divided by the inch
  // (0.0254 m) is what the US report prints, to its 9 significant digits.
  const CliResult json = RunCli("solve " + Quote(SourcePath(kIncline)) + " --format json");
  ASSERT_EQ(json.exit_code, 0) << json.err;
  const auto a = nlohmann::json::parse(json.out).at("bodies").at(0).at("acceleration");
  const CliResult us = RunCli("solve " + Quote(SourcePath(kIncline)) + " --units US");
  ASSERT_EQ(us.exit_code, 0) << us.err;
  EXPECT_THAT(us.out, HasSubstr(fmt::format("a_cm  [{:.9g}, 0, {:.9g}] in/s^2",
                                            a.at(0).get<double>() / 0.0254,
                                            a.at(2).get<double>() / 0.0254)));
  EXPECT_THAT(us.out, HasSubstr("report in US units"));
  // SI: the same value in m/s^2; energies in J.
  const CliResult si = RunCli("solve " + Quote(SourcePath(kIncline)) + " --units SI");
  EXPECT_THAT(si.out, HasSubstr(fmt::format("a_cm  [{:.9g}, 0, {:.9g}] m/s^2",
                                            a.at(0).get<double>(), a.at(2).get<double>())));
  EXPECT_THAT(si.out, HasSubstr("T 0 J"));
  // A moment has the energy's dimension but stays N*m (dH/dt, eq. 8.30).
  EXPECT_THAT(si.out, HasSubstr("dH/dt   [0, "));
  EXPECT_THAT(si.out, ::testing::Not(HasSubstr(" J\n    dH_O/dt")));
  EXPECT_THAT(si.out, HasSubstr("] N*m\n    dH_O/dt"));
  // The scene's own `units: in, lb` by default.
  const CliResult cube = RunCli("solve " + Quote(SourcePath("examples/section-8.5-cube.yaml")));
  ASSERT_EQ(cube.exit_code, 0) << cube.err;
  EXPECT_THAT(cube.out, HasSubstr("report in in, lb units"));
  EXPECT_THAT(cube.out, HasSubstr("in/s^2"));
  // A sweep's table is SI: --units there is refused.
  const CliResult sweep = RunCli("solve " + Quote(SourcePath(kIncline)) +
                                 " --quiet --sweep 'theta=10 deg:50 deg:3' --units US");
  EXPECT_EQ(sweep.exit_code, 2);
  EXPECT_THAT(sweep.err, HasSubstr("--units"));
  const CliResult bad = RunCli("solve " + Quote(SourcePath(kIncline)) + " --units furlong");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_THAT(bad.err, HasSubstr("furlong"));
}

TEST(Outputs, SolveOutWritesTheReportToAFile) {
  const auto dir = OutDir("outputs_solve");
  for (const std::string format : {"text", "json", "csv"}) {
    const std::string path = (dir / ("incline." + format)).string();
    const CliResult out = RunCli("solve " + Quote(SourcePath(kIncline)) + " --format " + format);
    const CliResult file = RunCli("solve " + Quote(SourcePath(kIncline)) + " --format " + format +
                                  " -o " + Quote(path));
    ASSERT_EQ(file.exit_code, 0) << file.err;
    EXPECT_EQ(file.out, "");
    EXPECT_EQ(ReadFile(path), out.out) << format;
  }
  const CliResult sweep = RunCli("solve " + Quote(SourcePath(kIncline)) +
                                 " --quiet --sweep 'theta=10 deg:50 deg:3' --out " +
                                 Quote((dir / "sweep.csv").string()));
  ASSERT_EQ(sweep.exit_code, 0) << sweep.err;
  EXPECT_EQ(ReadRaw(ReadFile(dir / "sweep.csv")).rows.size(), 3u);
  const CliResult bad = RunCli("solve " + Quote(SourcePath(kIncline)) + " -o " +
                               Quote((dir / "no-such-folder" / "x.txt").string()));
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_THAT(bad.err, HasSubstr("no-such-folder"));
  const CliResult format = RunCli("solve " + Quote(SourcePath(kIncline)) + " --format xml");
  EXPECT_EQ(format.exit_code, 2);
}

TEST(Outputs, SolveCsvIsTheOnePointSweepRowWithoutTheParameter) {
  // The one-row table has the sweep's columns after its parameter, and its values are the
  // sweep's at the scene's own theta = 30 deg (a sweep from 30 deg to 30 deg), bitwise with
  // full precision; f/N = tan(theta)/3 for rolling (Example 8.3).
  const CliResult one =
      RunCli("solve " + Quote(SourcePath(kIncline)) + " --format csv --full-precision");
  ASSERT_EQ(one.exit_code, 0) << one.err;
  const CliResult sweep = RunCli("solve " + Quote(SourcePath(kIncline)) +
                                 " --quiet --sweep 'theta=30 deg:30 deg:2' --full-precision");
  ASSERT_EQ(sweep.exit_code, 0) << sweep.err;
  const RawCsv c = ReadRaw(one.out);
  const RawCsv s = ReadRaw(sweep.out);
  ASSERT_EQ(c.rows.size(), 1u);
  ASSERT_EQ(c.header.size() + 1, s.header.size());
  for (size_t k = 0; k < c.header.size(); ++k) {
    EXPECT_EQ(c.header[k], s.header[k + 1]);
    EXPECT_EQ(Bits(std::strtod(c.rows[0][k].c_str(), nullptr)),
              Bits(std::strtod(s.rows[0][k + 1].c_str(), nullptr)))
        << c.header[k];
  }
  const double ratio = std::strtod(c.rows[0][Index(c, "contact_f_over_N")].c_str(), nullptr);
  EXPECT_NEAR(ratio, std::tan(30 * kPi / 180) / 3, 1e-12);
}

}  // namespace
}  // namespace chasles::test

namespace chasles::test {
namespace {

// --html for mass and for a sweep: the page is written and standard error says where (standard
// output stays the report or the table); a build without the report refuses with exit 2.
TEST(Outputs, HtmlReportIsWrittenAndSaid) {
  const auto dir = OutDir("outputs_html");
  const std::string mass_html = (dir / "rods.html").string();
  const CliResult mass = RunCli("mass " + Quote(SourcePath("examples/example-8.2-two-rods.yaml")) +
                                " --format json --html " + Quote(mass_html));
  const std::string sweep_html = (dir / "sweep.html").string();
  const CliResult sweep =
      RunCli("solve " + Quote(SourcePath(kIncline)) +
             " --quiet --sweep 'theta=10 deg:50 deg:3' --html " + Quote(sweep_html));
  if (mass.exit_code == 2) {  // built without the report
    EXPECT_THAT(mass.err, ::testing::HasSubstr("has no browser report"));
    EXPECT_EQ(sweep.exit_code, 2);
    return;
  }
  ASSERT_EQ(mass.exit_code, 0) << mass.err;
  ASSERT_EQ(sweep.exit_code, 0) << sweep.err;
  EXPECT_THAT(mass.err, ::testing::HasSubstr("Wrote " + mass_html + " (the browser report)"));
  EXPECT_THAT(sweep.err, ::testing::HasSubstr("Wrote " + sweep_html + " (the browser report)"));
  // Standard output is still the JSON report alone.
  EXPECT_TRUE(nlohmann::json::parse(mass.out).contains("bodies")) << mass.out;
  EXPECT_THAT(sweep.out, ::testing::StartsWith("theta [rad],"));
  for (const std::string& f : {mass_html, sweep_html}) {
    std::ifstream in(f);
    std::stringstream s;
    s << in.rdbuf();
    EXPECT_THAT(s.str(), ::testing::HasSubstr("id=\"chasles-data\"")) << f;
  }
}

}  // namespace
}  // namespace chasles::test
