// Limits on a run's work (docs/reliability-limits.md): each stops the run with exit 2, at the
// scene line of its key (or of `simulation:`), naming the limit and how to raise it, and
// writes no output; progress goes to standard error off a terminal, and --quiet silences it.

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "cli_runner.h"

namespace chasles::test {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

std::filesystem::path Dir() {
  return OutDir("limits");
}

// A ball falling under gravity for 10 s; `simulation:` is line 6, its keys from line 7 on.
std::string WriteBall(const std::string& name, const std::string& extra_keys = "") {
  const std::filesystem::path p = Dir() / (name + ".yaml");
  std::ofstream(p) << "gravity: standard\n"                                       // 1
                      "bodies:\n"                                                 // 2
                      "  - name: ball\n"                                          // 3
                      "    parts: [{shape: sphere, radius: 1 cm, mass: 1 kg}]\n"  // 4
                      "    initial: {velocity: [1 m/s, 0, 20 m/s]}\n"             // 5
                      "simulation:\n"                                             // 6
                      "  until: 10 s\n"                                           // 7
                   << extra_keys;                                                 // 8...
  return p.string();
}

struct Timed {
  CliResult r;
  double seconds;
};

Timed RunTimed(const std::string& args) {
  const auto start = std::chrono::steady_clock::now();
  CliResult r = RunCli(args);
  return {r, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()};
}

void ExpectStopped(const Timed& t, const std::string& stem) {
  EXPECT_EQ(t.r.exit_code, 2) << t.r.err;
  EXPECT_THAT(t.r.err, HasSubstr("chasles: error: "));
  EXPECT_THAT(t.r.err, Not(HasSubstr("internal error")));
  EXPECT_TRUE(t.r.out.empty());
  EXPECT_FALSE(std::filesystem::exists(Dir() / (stem + ".csv")));
  EXPECT_FALSE(std::filesystem::exists(Dir() / (stem + ".json")));
  EXPECT_LT(t.seconds, 30.0) << "a limit must end the run promptly";
}

std::string Sim(const std::string& scene, const std::string& extra) {
  return "simulate " + Quote(scene) + " --quiet --out " + Quote(Dir().string()) + " " + extra;
}

TEST(Limits, MaxStepsFlagStopsTheRunAtTheSimulationKey) {
  const std::string scene = WriteBall("steps_flag");
  const Timed t = RunTimed(Sim(scene, "--max-steps 3"));
  ExpectStopped(t, "steps_flag");
  EXPECT_THAT(t.r.err, HasSubstr(scene + ":6:1: simulation: the run reached the limit of 3 "
                                         "integration steps at t = "));
  EXPECT_THAT(t.r.err, HasSubstr("raise the limit with --max-steps or 'max_steps:' under "
                                 "'simulation:'"));
}

TEST(Limits, MaxStepsKeyStopsTheRunAtItsLine) {
  const std::string scene = WriteBall("steps_key", "  max_steps: 3\n");
  const Timed t = RunTimed(Sim(scene, ""));
  ExpectStopped(t, "steps_key");
  EXPECT_THAT(t.r.err, HasSubstr(scene + ":8:3: simulation.max_steps: the run reached the "
                                         "limit of 3 integration steps"));
}

TEST(Limits, TimeoutStopsTheRun) {
  const std::string scene = WriteBall("timeout_key", "  timeout: 1e-9 s\n");
  const Timed t = RunTimed(Sim(scene, ""));
  ExpectStopped(t, "timeout_key");
  EXPECT_THAT(t.r.err, HasSubstr(scene + ":8:3: simulation.timeout: the run reached its "
                                         "wall-time limit of 1e-09 s"));
  EXPECT_THAT(t.r.err, HasSubstr("--timeout or 'timeout:'"));
  // The flag replaces the key: 0 turns the limit off, and the 10 s of free fall finish.
  const CliResult off = RunCli(Sim(scene, "--timeout 0"));
  EXPECT_EQ(off.exit_code, 0) << off.err;
}

// Rows from the grid: 10 s every 0.05 s (200 intervals by default) are 201 grid rows plus the
// final one, 202 > 100, so the run is refused before it starts, at `simulation:`.
TEST(Limits, MaxRowsFlagRefusesTheRunUpFront) {
  const std::string scene = WriteBall("rows_flag");
  const Timed t = RunTimed(Sim(scene, "--max-rows 100"));
  ExpectStopped(t, "rows_flag");
  EXPECT_THAT(t.r.err, HasSubstr(scene + ":6:1: simulation: the run would write 202 output "
                                         "rows (a span of 10 s every 0.05 s), more than the "
                                         "limit of 100 rows"));
  EXPECT_THAT(t.r.err, HasSubstr("--max-rows or 'max_rows:'"));
  const CliResult enough = RunCli(Sim(scene, "--max-rows 202"));
  EXPECT_EQ(enough.exit_code, 0) << enough.err;
}

// A force that jumps by 1000 N within 1e-12 s at t = 0.5 s: error control shrinks the step
// towards the jump's width, below the 1 ms the scene allows.
TEST(Limits, AnAdaptiveStepBelowMinStepStopsTheRunAtTheKey) {
  const std::filesystem::path p = Dir() / "min_step.yaml";
  std::ofstream(p) << "bodies:\n"
                      "  - name: block\n"
                      "    parts: [{shape: sphere, radius: 1 cm, mass: 1 kg}]\n"
                      "forces:\n"
                      "  - type: force\n"
                      "    name: kick\n"
                      "    body: block\n"
                      "    value: ['min(1, max(0, (t/s - 0.5) * 1e12)) * 1000 N', 0 N, 0 N]\n"
                      "simulation:\n"
                      "  until: 1 s\n"
                      "  tolerance: 1e-12\n"
                      "  min_step: 1 ms\n";
  const Timed t = RunTimed(Sim(p.string(), ""));
  ExpectStopped(t, "min_step");
  EXPECT_THAT(t.r.err, HasSubstr(p.string() + ":12:3: simulation.min_step: the adaptive step "
                                              "fell below the smallest step 0.001 s at t = "));
  EXPECT_THAT(t.r.err, HasSubstr("lower the limit with --min-step or 'min_step:'"));
}

// k = 1e20 N/m on a free 1 kg body anchored to the world: ω = √(k/m) = 1e10 rad/s; an explicit
// step must stay below ~4/ω, so 1 s needs ≥ span ω / 4 = 2.5e9 steps > the limit: refused at
// the spring's entry (line 6, column 5) without a step taken.
TEST(Limits, AVeryStiffSpringIsRefusedAtItsEntry) {
  const std::filesystem::path p = Dir() / "stiff.yaml";
  std::ofstream(p)
      << "bodies:\n"
         "  - name: block\n"
         "    parts: [{shape: sphere, radius: 1 cm, mass: 1 kg}]\n"
         "    initial: {position: [1.01 m, 0, 0]}\n"
         "forces:\n"
         "  - {type: spring, name: wire, from: {body: block}, to: {world: [0, 0, 0]},\n"
         "     rest_length: 1 m, stiffness: 1e20 N/m}\n"
         "simulation: {until: 1 s}\n";
  const double omega = std::sqrt(1e20 / 1.0), steps = 1.0 * omega / 4.0;
  const Timed t = RunTimed(Sim(p.string(), ""));
  ExpectStopped(t, "stiff");
  EXPECT_THAT(t.r.err, HasSubstr(p.string() + ":6:5: forces[0]: spring 'wire' is too stiff"));
  EXPECT_THAT(t.r.err, HasSubstr(fmt::format("needs at least {:.3g} steps", steps)));
  EXPECT_THAT(t.r.err, HasSubstr("--max-steps or 'max_steps:'"));
}

TEST(Limits, BadFlagValuesAreExit2) {
  const std::string scene = WriteBall("flags");
  for (const char* flag : {"--timeout -1", "--min-step 0", "--max-steps -5",
                           "--progress-interval 0", "--timeout nan"}) {
    const CliResult r = RunCli(Sim(scene, flag));
    EXPECT_EQ(r.exit_code, 2) << flag << ": " << r.err;
    EXPECT_THAT(r.err, Not(HasSubstr("internal error"))) << flag;
  }
}

// Off a terminal (the test captures standard error) progress comes as whole lines, here every
// microsecond; --quiet and the default 10 s interval print none for this sub-second run.
TEST(Progress, LinesOffATerminalAndQuiet) {
  const std::string scene = WriteBall("progress");
  const std::string base = "simulate " + Quote(scene) + " --out " + Quote(Dir().string());
  const CliResult lines = RunCli(base + " --progress-interval 1e-6");
  EXPECT_EQ(lines.exit_code, 0) << lines.err;
  EXPECT_THAT(lines.err, HasSubstr("chasles: simulating: t = "));
  EXPECT_THAT(lines.err, HasSubstr(" s of 10 s ("));
  EXPECT_THAT(lines.err, Not(HasSubstr("\r")));
  EXPECT_THAT(lines.out, Not(HasSubstr("simulating")));
  const CliResult quiet = RunCli(base + " --progress-interval 1e-6 --quiet");
  EXPECT_EQ(quiet.exit_code, 0);
  EXPECT_EQ(quiet.err, "");
  const CliResult normal = RunCli(base);
  EXPECT_EQ(normal.exit_code, 0);
  EXPECT_EQ(normal.err, "");
}

TEST(Progress, SolveSweepReportsAndIsLimited) {
  const std::string scene = SourcePath("examples/example-8.3-cylinder-incline.yaml");
  const std::string sweep = " --sweep 'theta=10 deg:50 deg:5'";
  const CliResult lines = RunCli("solve " + Quote(scene) + sweep + " --progress-interval 1e-6");
  EXPECT_EQ(lines.exit_code, 0) << lines.err;
  EXPECT_THAT(lines.err, HasSubstr("chasles: solve --sweep: 1 of 5 ( 20%)"));
  const CliResult quiet =
      RunCli("solve " + Quote(scene) + sweep + " --progress-interval 1e-6 --quiet");
  EXPECT_EQ(quiet.err, "");
  const CliResult limited = RunCli("solve " + Quote(scene) + sweep + " --max-rows 3");
  EXPECT_EQ(limited.exit_code, 2);
  EXPECT_THAT(limited.err, HasSubstr("COUNT 5 is more than the limit of 3 rows"));
}

}  // namespace
}  // namespace chasles::test
