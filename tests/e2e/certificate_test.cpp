// End-to-end: the certificate ("Checks") of simulate and solve, --strict, contact-mode events
// and the state every event carries.

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>

#include <gtest/gtest.h>

#include "cli_runner.h"
#include "test_support.h"

namespace chasles::test {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kG = 9.80665;      // standard gravity [m/s^2]
constexpr double kInch = 0.0254;    // [m]
constexpr double kEventRel = 1e-9;  // event times and states: located to 1e-12 s

std::filesystem::path Dir() {
  return OutDir("certificate");
}

std::string ReadText(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// The spinning-ball example with `extra` appended (e.g. an events list), as a new scene file.
std::string SpinningBallWith(const std::string& extra, const std::string& name) {
  const std::string text = ReadText(SourcePath("examples/problem-8.26-spinning-ball.yaml"));
  const auto path = Dir() / (name + ".yaml");
  std::ofstream(path) << text << extra;
  return path.string();
}

const nlohmann::json& Check(const nlohmann::json& report, const std::string& name) {
  for (const auto& c : report.at("checks").at("checks")) {
    if (c.at("name") == name) return c;
  }
  throw std::runtime_error("no check " + name);
}

// Problems 8.26/8.27: sliding, friction mu_k m g gives a = mu_k g and
// alpha = -5 mu_k g / (2 R); the slip R w - v vanishes at t* = 2 R w0 / (7 mu_k g). The
// angular momentum about the contact point is conserved (friction and N act there, gravity
// through it): 2/5 m R^2 w0 = m v R + 2/5 m R^2 w with v = R w, so w* = 2/7 w0 and
// v* = 2/7 R w0. The contact-mode event stops the run there; its record carries that state.
TEST(Certificate, ContactModeEventStopsTheSpinningBallAtTStar) {
  const std::string scene = SpinningBallWith(
      "events:\n  - {name: rolls, contact: floor, change: stops_sliding, action: stop}\n",
      "ball-rolls");
  const nlohmann::json j = SimulateJson(scene, Dir());
  const double R = 9.0 / 8.0 * kInch, m = 0.17, w0 = 100 * 2 * kPi / 60, t_s = 0.025;
  const double mu_k = 2 * R * w0 / (7 * kG * t_s);  // the scene's parameter
  const double t_star = 2 * R * w0 / (7 * mu_k * kG);
  EXPECT_TRUE(j.at("stopped_by_event").get<bool>());
  ASSERT_EQ(j.at("events").size(), 1u);
  const nlohmann::json& e = j.at("events").at(0);
  EXPECT_EQ(e.at("name"), "rolls");
  EXPECT_TRUE(e.at("stopped").get<bool>());
  EXPECT_TRUE(Near(e.at("t").get<double>(), t_star, kEventRel));
  EXPECT_TRUE(Near(j.at("t_end").get<double>(), t_star, kEventRel));
  const nlohmann::json& body = e.at("state").at("bodies").at(0);
  EXPECT_TRUE(
      MatNear(ToVec(body.at("velocity")), Eigen::Vector3d(2.0 / 7 * R * w0, 0, 0), kEventRel));
  EXPECT_TRUE(
      MatNear(ToVec(body.at("angular_velocity")), Eigen::Vector3d(0, 2.0 / 7 * w0, 0), kEventRel));
  EXPECT_TRUE(Near(ToVec(body.at("center_of_mass")).z(), R, kEventRel));
  // Rolling on a level floor at constant speed: N = m g, no friction.
  const nlohmann::json& point = e.at("state").at("contacts").at(0);
  EXPECT_EQ(point.at("point"), "floor");
  EXPECT_EQ(point.at("mode"), "sticking");
  EXPECT_TRUE(Near(point.at("normal_force").get<double>(), m * kG, kEventRel));
  EXPECT_LE(ToVec(point.at("friction_force")).norm(), kEventRel * m * kG);
  EXPECT_TRUE(e.at("state").at("reactions").empty());
  // The certificate: every check passes; sliding friction was checked (samples before t*),
  // the cone at and after the transition.
  EXPECT_TRUE(j.at("checks").at("passed").get<bool>()) << j.at("checks").dump(2);
  EXPECT_GT(Check(j, "sliding friction").at("count").get<int>(), 0);
  EXPECT_GT(Check(j, "friction cone").at("count").get<int>(), 0);
  EXPECT_GT(Check(j, "ledger").at("count").get<int>(), 0);
}

// A ball dropped from h0 (lowest point) with restitution e touches down at t0 = sqrt(2 h0 / g)
// (free fall) and leaves at e g t0 upward; the next touch-down is a flight 2 e t0 later. A
// recorded `touches` event fires at each, with the state just after the impact.
TEST(Certificate, TouchesEventsAtTheBouncesOfADroppedBall) {
  std::string text = ReadText(SourcePath("examples/contact-bouncing-ball.yaml"));
  text += "events:\n  - {name: lands, contact: floor, change: touches, action: record}\n";
  const auto path = Dir() / "bounces.yaml";
  std::ofstream(path) << text;
  const nlohmann::json j = SimulateJson(path.string(), Dir());
  const double h0 = 1.0, e = 0.5;
  const double t0 = std::sqrt(2 * h0 / kG);
  const nlohmann::json& events = j.at("events");
  ASSERT_GE(events.size(), 2u);
  EXPECT_EQ(events.at(0).at("name"), "lands");
  EXPECT_FALSE(events.at(0).at("stopped").get<bool>());
  EXPECT_TRUE(Near(events.at(0).at("t").get<double>(), t0, kEventRel));
  EXPECT_TRUE(Near(events.at(1).at("t").get<double>(), t0 * (1 + 2 * e), kEventRel));
  const nlohmann::json& body = events.at(0).at("state").at("bodies").at(0);
  EXPECT_TRUE(Near(ToVec(body.at("velocity")).z(), e * kG * t0, kEventRel));
  EXPECT_EQ(events.at(0).at("state").at("contacts").at(0).at("mode"), "separated");
  EXPECT_TRUE(j.at("checks").at("passed").get<bool>()) << j.at("checks").dump(2);
}

TEST(Certificate, RecordedModeEventsAndTheirStateInTheTextReport) {
  const std::string scene = SpinningBallWith(
      "events:\n  - {name: rolls, contact: floor, change: any, action: record}\n", "ball-any");
  const CliResult r = RunCli("simulate '" + scene + "' --out '" + Dir().string() + "' --strict");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("rolls"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("    ball: position"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("    floor: sticking, N = "), std::string::npos) << r.out;
  // The report ends with the Checks section, one line per check.
  const auto at = r.out.find("\nChecks (all passed");
  ASSERT_NE(at, std::string::npos) << r.out;
  for (const char* name :
       {"friction cone", "sliding friction", "normal force", "gap", "constraint position",
        "constraint velocity", "ledger", "linear momentum balance", "angular momentum balance"}) {
    EXPECT_NE(r.out.find(name, at), std::string::npos) << name;
  }
}

TEST(Certificate, BadModeEventsAreErrorsAtTheirKey) {
  const std::string unknown = SpinningBallWith(
      "events:\n  - {name: x, contact: flor, change: stops_sliding}\n", "bad-contact");
  CliResult r = RunCli("check '" + unknown + "'");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("no contact or contact point is named 'flor'"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("did you mean 'floor'"), std::string::npos) << r.err;
  const std::string change = SpinningBallWith(
      "events:\n  - {name: x, contact: floor, change: stops_slipping}\n", "bad-change");
  r = RunCli("check '" + change + "'");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("unknown mode change 'stops_slipping'"), std::string::npos) << r.err;
  const std::string both = SpinningBallWith(
      "events:\n  - {name: x, contact: floor, change: any, when: ball_z}\n", "bad-both");
  r = RunCli("check '" + both + "'");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("'when' belongs to a crossing event"), std::string::npos) << r.err;
}

// An honest failure: the spring-mass oscillator (w = 20 rad/s) stepped by RK4 at h = 0.05 s,
// w h = 1, far outside its accuracy: the energy k A^2 / 2 = 1 J drifts by a large fraction
// (RK4's amplification per step is 1 - (w h)^6 / 144 + ...), so the ledger residual is far
// above 1e-7 of the energy scale. The forces at each sample are still exact: only the ledger
// fails. --strict turns the warning into exit code 3.
TEST(Certificate, StrictExitsWithThreeWhenACheckFails) {
  std::string text = ReadText(SourcePath("examples/spring-mass.yaml"));
  text = text.substr(0, text.find("events:"));
  text += "simulation: {until: 2 s, integrator: rk4, step: 0.05 s, output_interval: 0.05 s}\n";
  const auto path = Dir() / "coarse-spring.yaml";
  std::ofstream(path) << text;
  const std::string args = "simulate '" + path.string() + "' --out '" + Dir().string() + "'";
  const CliResult strict = RunCli(args + " --strict");
  EXPECT_EQ(strict.exit_code, 3) << strict.err << strict.out;
  EXPECT_NE(strict.out.find("\nChecks (SOME FAILED"), std::string::npos) << strict.out;
  EXPECT_NE(strict.out.find("warning: check 'ledger' failed"), std::string::npos) << strict.out;
  const CliResult lenient = RunCli(args + " --format json");
  ASSERT_EQ(lenient.exit_code, 0) << lenient.err;
  const nlohmann::json j = nlohmann::json::parse(lenient.out);
  EXPECT_FALSE(j.at("checks").at("passed").get<bool>());
  const nlohmann::json& ledger = Check(j, "ledger");
  EXPECT_FALSE(ledger.at("passed").get<bool>());
  EXPECT_GT(ledger.at("worst").get<double>(), ledger.at("tolerance").get<double>());
  EXPECT_TRUE(Check(j, "linear momentum balance").at("passed").get<bool>());
  bool warned = false;
  for (const auto& w : j.at("warnings")) {
    warned = warned || w.get<std::string>().find("check 'ledger' failed") != std::string::npos;
  }
  EXPECT_TRUE(warned) << j.at("warnings").dump();
  // The same scene with the adaptive integrator passes: exit 0 under --strict.
  std::string good = ReadText(SourcePath("examples/spring-mass.yaml"));
  const auto good_path = Dir() / "adaptive-spring.yaml";
  std::ofstream(good_path) << good;
  EXPECT_EQ(RunCli("simulate '" + good_path.string() + "' --out '" + Dir().string() + "' --strict")
                .exit_code,
            0);
}

TEST(Certificate, SolveReportsTheChecks) {
  const std::string scene = SourcePath("examples/example-8.3-cylinder-incline.yaml");
  const CliResult text = RunCli("solve '" + scene + "' --strict");
  EXPECT_EQ(text.exit_code, 0) << text.err;
  EXPECT_NE(text.out.find("\nChecks (all passed"), std::string::npos) << text.out;
  const CliResult json = RunCli("solve '" + scene + "' --format json");
  ASSERT_EQ(json.exit_code, 0) << json.err;
  const nlohmann::json j = nlohmann::json::parse(json.out);
  EXPECT_TRUE(j.at("checks").at("passed").get<bool>());
  EXPECT_EQ(j.at("checks").at("checks").size(), 12u);
  EXPECT_GT(Check(j, "linear momentum balance").at("count").get<int>(), 0);
  EXPECT_GT(Check(j, "constraint velocity").at("count").get<int>(), 0);
  EXPECT_EQ(Check(j, "ledger").at("count").get<int>(), 0);  // no run: not applicable
  EXPECT_EQ(Check(j, "linear impulse balance").at("count").get<int>(), 0);  // no jump
}

}  // namespace
}  // namespace chasles::test
