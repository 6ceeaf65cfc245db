// simulate --sweep and mass --sweep (docs/sweeps.md): grids of parameters, quantities of each
// run against closed forms derived here, failed points as rows with their reason, the same
// bytes for any number of threads, each run's own files, and bad input refused with exit 2.

#include <sys/wait.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <boost/math/special_functions/ellint_1.hpp>
#include <nlohmann/json.hpp>

#include "cli_runner.h"
#include "test_paths.h"
#include "test_support.h"

namespace chasles::test {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kG = 9.80665;  // gravity: standard
constexpr double kRun = 1e-9;   // runs at tolerance 1e-12, events located to 1e-12 s
constexpr double kInch = 0.0254;

std::filesystem::path Dir() {
  static const std::filesystem::path dir = OutDir("sweeps");
  return dir;
}

std::string WriteScene(const std::string& name, const std::string& text) {
  const auto path = Dir() / (name + ".yaml");
  std::ofstream(path) << text;
  return path.string();
}

// A planar pendulum: a bob of mass m and central moment m r^2 on a massless arm of length L
// pinned at the origin, released from rest at theta0 from the downward vertical. `event`
// watches the bob's x; samples every `interval`.
std::string Pendulum(const std::string& name, const std::string& event, const std::string& until,
                     const std::string& interval = "0.01 s") {
  return WriteScene(name, R"(chasles: 1
title: pendulum
planar: true
parameters:
  m: 1.5 kg
  L: 1 m
  r: 0.05 m
  theta0: 30 deg
bodies:
  - name: bob
    parts:
      - {shape: planar, mass: m, inertia_z: m*r^2, center_of_mass: [L*sin(theta0), -L*cos(theta0)]}
gravity: standard
joints:
  - {name: pin, type: revolute, parent: world, child: bob, at: [0, 0]}
events:
  - )" + event + R"(
simulation:
  until: )" + until + R"(
  tolerance: 1e-12
  output_interval: )" + interval +
                              R"(
output:
  columns: [planar]
)");
}

// The sweep table as JSON: rows by column name, and the errors.
struct Table {
  std::vector<std::map<std::string, nlohmann::json>> rows;
  std::vector<nlohmann::json> errors;
};

Table ParseTable(const std::string& text) {
  const auto j = nlohmann::json::parse(text);
  Table t;
  for (size_t r = 0; r < j.at("rows").size(); ++r) {
    std::map<std::string, nlohmann::json> row;
    for (size_t c = 0; c < j.at("columns").size(); ++c) {
      row[j.at("columns")[c].get<std::string>()] = j.at("rows")[r][c];
    }
    t.rows.push_back(row);
    t.errors.push_back(j.contains("errors") ? j.at("errors")[r] : nlohmann::json());
  }
  return t;
}

// The physical pendulum about the pin: I_O theta'' = -m g L sin(theta) with I_O = m k^2 + m L^2
// (k the radius of gyration about the centre of mass; parallel axes, eq. 8.39), so
// w0^2 = g L / (k^2 + L^2). From rest at theta0, energy gives
// theta'^2 = 2 w0^2 (cos theta - cos theta0), and the time to the bottom (a quarter period) is
//   T/4 = K(k) / w0,  k = sin(theta0 / 2)   (K: the complete elliptic integral of the first
// kind, modulus k). At the bottom the bob moves at v = L theta' = L w0 sqrt(2 (1 - cos theta0))
// in -x.
double W0(double L, double k2) {
  return std::sqrt(kG * L / (k2 + L * L));
}
double QuarterPeriod(double L, double theta0, double k2 = 0.05 * 0.05) {
  return boost::math::ellint_1(std::sin(theta0 / 2)) / W0(L, k2);
}

// The shipped examples/pendulum.yaml: a ball of radius r = 5 cm, k^2 = (2/5) r^2.
TEST(SimulateSweep, PendulumQuarterPeriodOverLengthAndAmplitude) {
  const double k2 = 0.4 * 0.05 * 0.05;
  const CliResult r = RunCli("simulate " + Quote(SourcePath("examples/pendulum.yaml")) +
                             " --sweep 'L=0.5 m:2 m:3' --sweep 'theta0=10 deg:70 deg:4' "
                             "--quantity 'event(bottom)' --quantity 'min(ball_vx)' "
                             "--quantity t_end --format json --quiet");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Table t = ParseTable(r.out);
  ASSERT_EQ(t.rows.size(), 12u);
  for (size_t k = 0; k < t.rows.size(); ++k) {
    // Grid order: the last parameter varies fastest.
    const double L = 0.5 + 0.75 * static_cast<double>(k / 4);
    const double theta0 = (10.0 + 20.0 * static_cast<double>(k % 4)) * kPi / 180;
    const auto& row = t.rows[k];
    EXPECT_TRUE(t.errors[k].is_null()) << t.errors[k];
    EXPECT_TRUE(Near(row.at("L").get<double>(), L, 1e-15));
    EXPECT_TRUE(Near(row.at("theta0").get<double>(), theta0, 1e-15));
    const double tq = QuarterPeriod(L, theta0, k2);
    EXPECT_TRUE(Near(row.at("event(bottom)").get<double>(), tq, kRun)) << L << " " << theta0;
    EXPECT_TRUE(Near(row.at("t_end").get<double>(), tq, kRun));
    // The fastest swing is at the bottom, the event's state (between samples).
    const double v = L * W0(L, k2) * std::sqrt(2 * (1 - std::cos(theta0)));
    EXPECT_TRUE(Near(row.at("min(ball_vx)").get<double>(), -v, kRun)) << L << " " << theta0;
  }
}

// A full period from event times: the bob crosses x = 0 every half period, so the third
// crossing minus the first is T = 4 K(k) / w0.
TEST(SimulateSweep, PeriodAsDifferenceOfEventTimes) {
  const std::string scene = Pendulum(
      "pendulum_record", "{name: bottom, when: bob_x, crosses: 0 m, action: record}", "3.2 s");
  const CliResult r = RunCli("simulate " + Quote(scene) +
                             " --sweep 'L=0.5 m:1.5 m:3' --quantity 'event(bottom, 3) - "
                             "event(bottom)' --quantity 'max(bob_x)' --format json --quiet");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Table t = ParseTable(r.out);
  ASSERT_EQ(t.rows.size(), 3u);
  const double theta0 = 30 * kPi / 180;
  for (size_t k = 0; k < 3; ++k) {
    const double L = 0.5 + 0.5 * static_cast<double>(k);
    EXPECT_TRUE(Near(t.rows[k].at("event(bottom,3)-event(bottom)").get<double>(),
                     4 * QuarterPeriod(L, theta0), kRun));
    // Released from rest at the largest x: L sin(theta0) (the initial sample).
    EXPECT_TRUE(Near(t.rows[k].at("max(bob_x)").get<double>(), L * std::sin(theta0), kRun));
  }
}

// Extremes see the events' states: with samples 0.25 s apart the lowest sample of the bob
// misses the bottom, but the recorded crossings of x = 0 are there, at y = -L exactly; and the
// speed there is the largest, L w0 sqrt(2 (1 - cos theta0)) (energy, as above).
TEST(SimulateSweep, ExtremesIncludeTheEventStates) {
  const std::string scene =
      Pendulum("pendulum_coarse", "{name: bottom, when: bob_x, crosses: 0 m, action: record}",
               "2 s", "0.25 s");
  const CliResult r = RunCli("simulate " + Quote(scene) +
                             " --sweep 'L=0.5 m:1.5 m:3' --quantity 'min(bob_y)' --quantity "
                             "'max(bob_omega)' --set 'theta0=50 deg' --format json --quiet");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Table t = ParseTable(r.out);
  ASSERT_EQ(t.rows.size(), 3u);
  const double theta0 = 50 * kPi / 180;
  for (size_t k = 0; k < 3; ++k) {
    const double L = 0.5 + 0.5 * static_cast<double>(k);
    const double w0 = W0(L, 0.05 * 0.05);
    EXPECT_TRUE(Near(t.rows[k].at("min(bob_y)").get<double>(), -L, kRun)) << L;
    EXPECT_TRUE(Near(t.rows[k].at("max(bob_omega)").get<double>(),
                     w0 * std::sqrt(2 * (1 - std::cos(theta0))), kRun))
        << L;
  }
}

// Problems 8.26/8.27 (--until 0.2 s: the example's 60 ms ends before t* for mu_k = 0.1): a ball
// spinning at w0 set on a floor slides; friction mu_k m g gives a = mu_k g and alpha = -5 mu_k g /
// (2 R), so v = mu_k g t and R w = R w0 - 5 mu_k g t / 2, and the slip R w - v closes at t* = 2 R
// w0 / (7 mu_k g), with v* = (2/7) R w0.
TEST(SimulateSweep, SpinningBallStopsSlidingOverMu) {
  std::ifstream in(SourcePath("examples/problem-8.26-spinning-ball.yaml"));
  std::stringstream text;
  text << in.rdbuf();
  const std::string scene =
      WriteScene("spinning", text.str() +
                                 "events:\n  - {name: rolls, contact: floor, change: "
                                 "stops_sliding, action: stop}\n");
  const CliResult r = RunCli("simulate " + Quote(scene) +
                             " --sweep 'mu_k=0.1:0.4:4' --quantity 'event(rolls)' --quantity "
                             "'final(ball_vx)' --until 0.2 --format json --quiet");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Table t = ParseTable(r.out);
  ASSERT_EQ(t.rows.size(), 4u);
  const double R = 9.0 / 8.0 * kInch, w0 = 100 * 2 * kPi / 60;
  for (size_t k = 0; k < 4; ++k) {
    const double mu = 0.1 + 0.1 * static_cast<double>(k);
    EXPECT_TRUE(Near(t.rows[k].at("mu_k").get<double>(), mu, 1e-15));
    EXPECT_TRUE(Near(t.rows[k].at("event(rolls)").get<double>(), 2 * R * w0 / (7 * mu * kG), kRun));
    EXPECT_TRUE(Near(t.rows[k].at("final(ball_vx)").get<double>(), 2.0 / 7.0 * R * w0, kRun));
  }
}

// Each run is independent and the rows are in grid order: one thread or two, the same bytes.
TEST(SimulateSweep, JobsGiveIdenticalBytes) {
  const std::string scene = Pendulum(
      "pendulum_jobs", "{name: bottom, when: bob_x, crosses: 0 m, direction: falling}", "5 s");
  const std::string args = "simulate " + Quote(scene) +
                           " --sweep 'L=0.5 m:2 m:4' --sweep 'theta0=10 deg:60 deg:3' "
                           "--quantity 'event(bottom)' --quantity 'max(bob_omega)' --quiet";
  const CliResult one = RunCli(args + " --jobs 1");
  const CliResult two = RunCli(args + " --jobs 2");
  const CliResult three = RunCli(args + " --jobs 3 --format json");
  ASSERT_EQ(one.exit_code, 0) << one.err;
  ASSERT_EQ(two.exit_code, 0) << two.err;
  ASSERT_EQ(three.exit_code, 0) << three.err;
  EXPECT_EQ(one.out, two.out);
  EXPECT_EQ(ParseTable(three.out).rows.size(), 12u);
  // The CSV: the header (parameters, quantities with their SI units, error), 12 rows.
  std::stringstream lines(one.out);
  std::string line;
  std::getline(lines, line);
  EXPECT_EQ(line, "L [m],theta0 [rad],event(bottom) [s],max(bob_omega) [rad/s],error");
  int rows = 0;
  while (std::getline(lines, line)) ++rows;
  EXPECT_EQ(rows, 12);
}

// A quantity a run cannot give leaves its own field empty, with the reason, and the row's
// other quantities are the run's: here the longer pendulum does not reach the bottom by
// --until (T/4 = 0.36 s for L = 0.5 m, 0.72 s for L = 2 m), and its run still ends at
// t_end = 0.5 s.
TEST(SimulateSweep, FailedPointIsARowWithItsReason) {
  const std::string scene = Pendulum(
      "pendulum_fail", "{name: bottom, when: bob_x, crosses: 0 m, direction: falling}", "5 s");
  const std::string args = "simulate " + Quote(scene) +
                           " --sweep 'L=0.5 m:2 m:2' --quantity 'event(bottom)' --quantity "
                           "t_end --until 0.5 --quiet";
  const CliResult csv = RunCli(args);
  ASSERT_EQ(csv.exit_code, 0) << csv.err;
  EXPECT_THAT(csv.out, ::testing::HasSubstr("\n2,,0.5,\"event(bottom): event 'bottom' fired 0 "
                                            "times by the run's end at t = 0.5 s; "
                                            "event(bottom, 1) needs 1\"\n"));
  EXPECT_THAT(csv.err,
              ::testing::HasSubstr("warning: L = 2: event(bottom): event 'bottom' fired 0 times"));
  const CliResult json = RunCli(args + " --format json");
  ASSERT_EQ(json.exit_code, 0) << json.err;
  const Table t = ParseTable(json.out);
  ASSERT_EQ(t.rows.size(), 2u);
  EXPECT_TRUE(t.errors[0].is_null());
  EXPECT_TRUE(
      Near(t.rows[0].at("event(bottom)").get<double>(), QuarterPeriod(0.5, 30 * kPi / 180), kRun));
  EXPECT_EQ(t.rows[1].at("L").get<double>(), 2.0);
  EXPECT_TRUE(t.rows[1].at("event(bottom)").is_null());
  EXPECT_EQ(t.rows[1].at("t_end").get<double>(), 0.5);
  EXPECT_THAT(t.errors[1].get<std::string>(), ::testing::HasSubstr("fired 0 times"));
  // --strict: a failed row exits 3.
  EXPECT_EQ(RunCli(args + " --strict").exit_code, 3);
}

// --keep-runs: each run's CSV and JSON, named by the parameter values; the JSON's event time
// is the table's.
TEST(SimulateSweep, KeepRunsWritesEachRunsFiles) {
  const std::string scene =
      Pendulum("keep", "{name: bottom, when: bob_x, crosses: 0 m, direction: falling}", "5 s");
  const auto dir = Dir() / "kept";
  std::filesystem::remove_all(dir);
  const CliResult r = RunCli("simulate " + Quote(scene) +
                             " --sweep 'L=0.5 m:1 m:2' --quantity 'event(bottom)' --format json "
                             "--quiet --keep-runs " +
                             Quote(dir.string()));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Table t = ParseTable(r.out);
  for (const std::string L : {"0.5", "1"}) {
    const auto csv = dir / ("keep_L=" + L + ".csv");
    const auto json = dir / ("keep_L=" + L + ".json");
    ASSERT_TRUE(std::filesystem::exists(csv)) << csv;
    ASSERT_TRUE(std::filesystem::exists(json)) << json;
    std::ifstream in(json);
    const auto summary = nlohmann::json::parse(in);
    const double t_event = summary.at("events").at(0).at("t").get<double>();
    EXPECT_TRUE(Near(t_event, t.rows[L == "1" ? 1 : 0].at("event(bottom)").get<double>(), 1e-15));
    EXPECT_TRUE(Near(t_event, QuarterPeriod(std::stod(L), 30 * kPi / 180), kRun));
    EXPECT_GT(ReadCsv(csv.string()).at("bob_x").size(), 10u);
  }
}

// A solid cylinder of mass m, radius R, height h along z: I_zz = m R^2 / 2 and about a
// transverse axis through the centre I_xx = m (3 R^2 + h^2) / 12; the centre of mass at h/2.
TEST(MassSweep, CylinderInertiaOverRadius) {
  const std::string scene = WriteScene("cylinder", R"(chasles: 1
parameters:
  R: 5 cm
  h: 20 cm
  m: 3 kg
bodies:
  - name: cyl
    parts:
      - {shape: cylinder, radius: R, from: [0, 0, 0], to: [0, 0, h], mass: m}
)");
  const CliResult r = RunCli("mass " + Quote(scene) +
                             " --sweep 'R=1 cm:9 cm:5' --sweep 'h=10 cm:30 cm:3' --quantity Izz "
                             "--quantity cyl.Ixx --quantity center_of_mass_z --quantity mass "
                             "--quantity k3 --format json --quiet");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Table t = ParseTable(r.out);
  ASSERT_EQ(t.rows.size(), 15u);
  const double m = 3;
  for (size_t k = 0; k < 15; ++k) {
    const double R = (1 + 2 * static_cast<double>(k / 3)) / 100;
    const double h = (10 + 10 * static_cast<double>(k % 3)) / 100;
    const auto& row = t.rows[k];
    EXPECT_TRUE(Near(row.at("R").get<double>(), R, 1e-15));
    EXPECT_TRUE(Near(row.at("Izz").get<double>(), m * R * R / 2, 1e-12));
    EXPECT_TRUE(Near(row.at("cyl.Ixx").get<double>(), m * (3 * R * R + h * h) / 12, 1e-12));
    EXPECT_TRUE(Near(row.at("center_of_mass_z").get<double>(), h / 2, 1e-12));
    EXPECT_TRUE(Near(row.at("mass").get<double>(), m, 1e-15));
    // k3: the radius of gyration about the principal axis of the largest moment.
    const double I3 = std::max(m * R * R / 2, m * (3 * R * R + h * h) / 12);
    EXPECT_TRUE(Near(row.at("k3").get<double>(), std::sqrt(I3 / m), 1e-12));
  }
  // Bad input at one point (a negative radius) is that row's error, named at its scene entry.
  const CliResult bad =
      RunCli("mass " + Quote(scene) + " --sweep 'R=-1 cm:1 cm:2' --quantity Izz --quiet");
  ASSERT_EQ(bad.exit_code, 0) << bad.err;
  EXPECT_THAT(bad.out, ::testing::HasSubstr("radius must be positive"));
  EXPECT_THAT(bad.out, ::testing::HasSubstr("\n0.01,0.00015,\n"));
}

// A mass property the report does not give (the volume of a body with a `custom` part) leaves
// only its own field empty: the mass, m, is there in every row.
TEST(MassSweep, AQuantityTheReportDoesNotGiveLeavesOnlyItsFieldEmpty) {
  const std::string scene = WriteScene("custom", R"(parameters:
  m: 2 kg
bodies:
  - name: block
    parts:
      - {shape: custom, mass: m, inertia: {Ixx: 1 kg*m^2, Iyy: 1 kg*m^2, Izz: 1 kg*m^2}}
)");
  const CliResult r = RunCli("mass " + Quote(scene) +
                             " --sweep 'm=1 kg:3 kg:3' --quantity volume --quantity mass "
                             "--format json --quiet");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Table t = ParseTable(r.out);
  ASSERT_EQ(t.rows.size(), 3u);
  for (size_t k = 0; k < 3; ++k) {
    EXPECT_TRUE(t.rows[k].at("volume").is_null()) << k;
    EXPECT_EQ(t.rows[k].at("mass").get<double>(), 1.0 + static_cast<double>(k)) << k;
    EXPECT_THAT(t.errors[k].get<std::string>(), ::testing::HasSubstr("volume: not given")) << k;
  }
}

// Progress on standard error: runs done of the total (off a terminal, one line per interval).
TEST(Sweep, ProgressCountsRuns) {
  const std::string scene = Pendulum(
      "pendulum_progress", "{name: bottom, when: bob_x, crosses: 0 m, direction: falling}", "5 s");
  const std::string args = "simulate " + Quote(scene) +
                           " --sweep 'L=0.5 m:2 m:4' --quantity 'event(bottom)' --jobs 2 "
                           "--progress-interval 1e-9";
  const CliResult lines = RunCli(args);
  ASSERT_EQ(lines.exit_code, 0) << lines.err;
  EXPECT_THAT(lines.err, ::testing::HasSubstr("chasles: simulate --sweep: 4 of 4 (100%)"));
  EXPECT_EQ(RunCli(args + " --quiet").err, "");
  const CliResult mass = RunCli("mass " + Quote(scene) +
                                " --sweep 'r=1 cm:2 cm:3' --quantity Izz --progress-interval 1e-9");
  ASSERT_EQ(mass.exit_code, 0) << mass.err;
  EXPECT_THAT(mass.err, ::testing::HasSubstr("chasles: mass --sweep: 3 of 3 (100%)"));
}

TEST(Sweep, BadInputExitsTwoWithAClearMessage) {
  const std::string scene = Pendulum(
      "pendulum_bad", "{name: bottom, when: bob_x, crosses: 0 m, direction: falling}", "5 s");
  const std::string sim = "simulate " + Quote(scene) + " --quiet ";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {sim + "--sweep 'L=0.5 m:2 m' --quantity t_end", "expected NAME=START:STOP:COUNT"},
      {sim + "--sweep 'L=0.5 m:2 m:1' --quantity t_end", "COUNT must be a whole number >= 2"},
      {sim + "--sweep 'Lx=0.5 m:2 m:2' --quantity t_end", "no parameter 'Lx'"},
      {sim + "--sweep 'L=0.5 kg:2 m:2' --quantity t_end", "has dimension mass"},
      {sim + "--sweep 'L=1 m:2 m:2' --sweep 'L=1 m:2 m:2' --quantity t_end", "swept twice"},
      {sim + "--sweep 'L=1 m:2 m:2' --quantity 'foo(x)'", "expected final(COLUMN)"},
      {sim + "--sweep 'L=1 m:2 m:2' --quantity 'max(nope)'", "unknown column 'nope'"},
      {sim + "--sweep 'L=1 m:2 m:2' --quantity 'max(planar)'", "is a group of columns"},
      {sim + "--sweep 'L=1 m:2 m:2' --quantity 'event(top)'", "no event 'top'"},
      {sim + "--sweep 'L=1 m:2 m:2' --quantity 'event(bottom, 0)'", "expected final(COLUMN)"},
      {sim + "--sweep 'L=1 m:2 m:2'", "needs at least one --quantity"},
      {sim + "--quantity t_end", "--quantity goes with --sweep"},
      {sim + "--sweep 'L=1 m:2 m:2' --quantity t_end --columns bob_x,nope",
       "unknown column 'nope'"},
      {sim + "--sweep 'L=1 m:2 m:2' --quantity t_end --out results", "--keep-runs"},
      {sim + "--sweep 'L=1 m:2 m:10' --sweep 'theta0=0:1:10' --quantity t_end --max-runs 50",
       "more points than the limit of 50 runs; raise the limit with --max-runs N"},
      {"mass " + Quote(scene) + " --sweep 'L=1 m:2 m:2' --quantity Iqq", "unknown quantity 'Iqq'"},
      {"mass " + Quote(scene) + " --sweep 'L=1 m:2 m:2' --quantity nobody.Izz", "no body 'nobody'"},
  };
  for (const auto& [args, message] : cases) {
    const CliResult r = RunCli(args);
    EXPECT_EQ(r.exit_code, 2) << args << "\n" << r.err;
    EXPECT_THAT(r.err, ::testing::HasSubstr(message)) << args;
  }
}

TEST(Sweep, AThousandJobsUnderAnAddressSpaceLimitRunOnTheThreadsThatStart) {
  // 1000 thread stacks (8 MiB each) do not fit in 1 GB of address space: the threads that
  // cannot start are not an error, the others share the work.
  if (test::kAddressSanitizer) {
    GTEST_SKIP() << "AddressSanitizer maps terabytes of shadow memory: no address-space limit "
                    "leaves it room to start";
  }
  const std::filesystem::path dir = OutDir("sweeps_limit");
  const std::string command = "ulimit -v 1000000 && '" + std::string(chasles::test::CliPath()) +
                              "' simulate " + Quote(SourcePath("examples/spring-mass.yaml")) +
                              " --until 0.05 --quiet --sweep 'k=100 N/m:1000 N/m:50' --quantity "
                              "'max(block_x)' --jobs ";
  const std::filesystem::path limited = dir / "limited.csv", reference = dir / "reference.csv";
  const int status =
      std::system((command + "1000 > '" + limited.string() + "' 2>/dev/null").c_str());
  ASSERT_EQ(std::system((command + "1 > '" + reference.string() + "'").c_str()), 0);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << status;
  const auto read = [](const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
  };
  EXPECT_EQ(read(limited), read(reference));
  EXPECT_THAT(read(reference), ::testing::HasSubstr("k [N/m]"));
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace chasles::test
