// End-to-end: rolling resistance held and overcome, through `chasles simulate --strict` and
// `chasles solve`, against closed forms derived here.
//
// A round body (mass m, radius R, I = β m R² about its axle: sphere β = 2/5, cylinder 1/2,
// hoop 1) on a plane at θ, pushed along the slope at its centre by F. Rolling resistance is a
// moment of at most mu_r N R at the contact, N = m g cosθ. Per unit mass the push and gravity
// drive it by P = F/m - g sinθ along the slope (x up the slope):
//   held: the friction f = -m P acts R below the centre, so the contact holds the moment
//         m |P| R; it can while |P| <= mu_r g cosθ;
//   rolling at v: m a = m P + f and β m R² α = -f R - sign(v) mu_r N R with a = α R give
//         a = (P - sign(v) mu_r g cosθ) / (1 + β).
// So a body pushed from rest by F > mu_r m g on a level floor rolls at
// a = (F/m - mu_r g)/(1 + β); a ramp F = k t starts it at t_s = mu_r m g / k, after which
// a = k (t - t_s) / (m (1 + β)); rolled up a slope at v0 without push it stops at
// t1 = v0 (1 + β) / (g (sinθ + mu_r cosθ)) and then holds if tanθ <= mu_r, else rolls back at
// g (sinθ - mu_r cosθ) / (1 + β).

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "cli_runner.h"
#include "test_support.h"

namespace chasles::test {
namespace {

constexpr double kG = 9.80665;  // `gravity: standard` [m/s²]
// Event times (located to 1e-12 s) and forces; accelerations (exact in each regime).
constexpr double kEvent = 1e-9;
constexpr double kAccel = 1e-10;

struct RunOut {
  nlohmann::json json;
  std::map<std::string, std::vector<double>> csv;
};

std::filesystem::path WriteScene(const std::string& name, const std::string& text) {
  const std::filesystem::path file = OutDir("rolling-resistance") / (name + ".yaml");
  std::ofstream(file) << text;
  return file;
}

RunOut Simulate(const std::string& name, const std::string& text) {
  const std::filesystem::path file = WriteScene(name, text);
  RunOut r;
  // --strict: a run whose certificate fails exits 3, and SimulateJson throws.
  r.json = SimulateJson(file.string(), file.parent_path(), "--strict");
  r.csv = ReadCsv(r.json.at("csv").get<std::string>());
  return r;
}

nlohmann::json Solve(const std::string& name, const std::string& text) {
  const CliResult r =
      RunCli("solve " + Quote(WriteScene(name, text).string()) + " --format json --strict");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  return nlohmann::json::parse(r.out);
}

// The contact events of `reason`, in time order.
std::vector<nlohmann::json> Events(const RunOut& r, const std::string& reason) {
  std::vector<nlohmann::json> out;
  for (const auto& e : r.json.at("contact_events")) {
    if (e.at("reason") == reason) out.push_back(e);
  }
  return out;
}

void ExpectLedgerClosed(const RunOut& r) {
  EXPECT_LT(std::abs(r.json.at("ledger").at("relative_residual").get<double>()), 1e-10);
}

struct Round {
  std::string name, part, contact;
  double beta;
};

const Round kBall{"ball", "{shape: sphere, radius: R, mass: m}", "shape: sphere, radius: R", 0.4};
const Round kCylinder{"cylinder",
                      "{shape: cylinder, radius: R, length: 2*R, axis: [0, 1, 0], mass: m}",
                      "shape: cylinder, radius: R, length: 2*R, axis: [0, 1, 0]", 0.5};
const Round kHoop{"hoop", "{shape: ring, radius: R, axis: [0, 1, 0], mass: m}",
                  "shape: disk, radius: R, axis: [0, 1, 0]", 1.0};

// A scene of body `b` (m 0.4 kg, R 5 cm, mu_s 0.8, mu_k 0.6, mu_r 0.05) on a plane at
// `theta` [rad] about y, pushed along the slope by `push` (an expression in N, of t), started
// at `v0` [m/s] along the slope (rolling) or with `initial` given, run to `until` [s].
std::string Scene(const Round& b, double theta, const std::string& push, double v0, double until,
                  const std::string& initial = "") {
  const double s = std::sin(theta), c = std::cos(theta);
  const std::string init =
      !initial.empty() ? initial
                       : fmt::format(
                             "{{position: [{0:.17g}*R, 0, {1:.17g}*R], velocity: [{2:.17g} m/s, 0, "
                             "{3:.17g} m/s], angular_velocity: [0, {4:.17g} m/s / R, 0]}}",
                             -s, c, v0 * c, v0 * s, v0);
  return fmt::format(R"(chasles: 1
title: "rolling resistance: {0}"
parameters:
  m: 0.4 kg
  R: 5 cm
bodies:
  - name: body
    parts: [{1}]
    initial: {2}
gravity: standard
forces:
  - {{type: force, name: push, body: body, value: [{3:.17g} * ({4}), 0, {5:.17g} * ({4})]}}
contacts:
  - {{name: floor, body: body, {6}, mu_s: 0.8, mu_k: 0.6, mu_r: 0.05,
     plane: {{point: [0, 0, 0], normal: [{7:.17g}, 0, {8:.17g}]}}}}
simulation: {{until: {9:.17g} s, tolerance: 1e-12, output_interval: {10:.17g} s}}
output:
  columns: [velocity, angular_velocity, contacts, ledger]
)",
                     b.name, b.part, init, c, push, s, b.contact, -s, c, until, until / 4);
}

// Velocity along the slope from the CSV's last row.
double SlopeVelocity(const RunOut& r, double theta) {
  return r.csv.at("body_vx").back() * std::cos(theta) +
         r.csv.at("body_vz").back() * std::sin(theta);
}

// The ball of the report: pushed at its centre by 0.5 N on a level floor, it must accelerate at
// (5/7)(F/m - mu_r g) = 0.5426 m/s² (without the resistance it would be 0.8929 m/s²).
TEST(RollingResistanceE2e, BallPushedFromRestRollsAgainstTheResistance) {
  const double m = 0.4, R = 0.05, mu_r = 0.05, F = 0.5, T = 2.0;
  const double a = (F / m - mu_r * kG) / 1.4;
  const RunOut r = Simulate("ball-pushed", Scene(kBall, 0.0, "0.5 N", 0.0, T));
  EXPECT_NEAR(SlopeVelocity(r, 0.0), a * T, kAccel * a * T);
  // The work of rolling resistance: -mu_r m g x, x = a T²/2.
  const double W = -mu_r * m * kG * a * T * T / 2;
  EXPECT_NEAR(r.json.at("ledger").at("rolling_work").get<double>(), W, kAccel * std::abs(W));
  ExpectLedgerClosed(r);
  // solve gives the same acceleration, and the moment mu_r N R against the rolling.
  const nlohmann::json s = Solve("ball-pushed", Scene(kBall, 0.0, "0.5 N", 0.0, T));
  EXPECT_NEAR(s.at("bodies")[0].at("acceleration")[0].get<double>(), a, kAccel * a);
  const nlohmann::json& c = s.at("contacts")[0];
  EXPECT_EQ(c.at("regime"), "rolls");
  EXPECT_FALSE(c.at("rolling_held").get<bool>());
  EXPECT_NEAR(c.at("rolling_moment")[1].get<double>(), -mu_r * m * kG * R, kEvent * m * kG * R);
}

// Pushed by a ramp F = k t, a ball, a cylinder on both end rims and a hoop are held until
// k t_s = mu_r m g, then roll with a = k (t - t_s) / (m (1 + β)).
TEST(RollingResistanceE2e, RampedPushStartsTheRollingAtMuRmg) {
  const double m = 0.4, mu_r = 0.05, k = 2.0, T = 0.5;
  const double t_s = mu_r * m * kG / k;
  for (const Round& b : {kBall, kCylinder, kHoop}) {
    SCOPED_TRACE(b.name);
    const RunOut r = Simulate("ramp-" + b.name, Scene(b, 0.0, "t * 2 N/s", 0.0, T));
    const auto starts = Events(r, "rolling resistance limit");
    ASSERT_FALSE(starts.empty());
    for (const auto& e : starts) {
      EXPECT_NEAR(e.at("t").get<double>(), t_s, kEvent * t_s);
      EXPECT_EQ(e.at("from"), "sticking, rolling held");
      EXPECT_EQ(e.at("to"), "sticking");
    }
    const double v = k * (T - t_s) * (T - t_s) / (2 * m * (1 + b.beta));
    EXPECT_NEAR(SlopeVelocity(r, 0.0), v, kAccel * v);
    ExpectLedgerClosed(r);
  }
}

// Rolled up a slope at 0.3 m/s: stops at t1, then holds (tanθ = 0.03, 0.05 <= mu_r) or rolls
// back (tanθ = 0.08).
TEST(RollingResistanceE2e, BallRolledUpASlopeStopsThenHoldsOrRollsBack) {
  const double mu_r = 0.05, v0 = 0.3, beta = 0.4;
  for (const double tan_theta : {0.03, 0.05, 0.08}) {
    SCOPED_TRACE(tan_theta);
    const double th = std::atan(tan_theta);
    const double up = kG * (std::sin(th) + mu_r * std::cos(th)) / (1 + beta);
    const double t1 = v0 / up, T = 2.5 * t1;
    const RunOut r = Simulate(fmt::format("slope-{}", tan_theta), Scene(kBall, th, "0 N", v0, T));
    const auto stops = Events(r, "rolling stopped");
    ASSERT_EQ(stops.size(), 1u);
    EXPECT_NEAR(stops[0].at("t").get<double>(), t1, kEvent * t1);
    if (tan_theta <= mu_r) {
      EXPECT_EQ(stops[0].at("to"), "sticking, rolling held");
      EXPECT_LT(std::abs(SlopeVelocity(r, th)), 1e-12);
      // Held: the moment m g R sinθ, within mu_r m g R cosθ.
      const nlohmann::json s = Solve("held", Scene(kBall, th, "0 N", 0.0, T));
      const nlohmann::json& c = s.at("contacts")[0];
      EXPECT_EQ(c.at("regime"), "rolling held");
      const double M = 0.4 * kG * 0.05 * std::sin(th);
      EXPECT_NEAR(c.at("rolling_moment")[1].get<double>(), M, kEvent * M);
    } else {
      EXPECT_EQ(stops[0].at("to"), "sticking");
      const double down = kG * (std::sin(th) - mu_r * std::cos(th)) / (1 + beta);
      EXPECT_NEAR(SlopeVelocity(r, th), -down * (T - t1), kAccel * down * T);
    }
    ExpectLedgerClosed(r);
  }
}

// Thrown along a level floor at v0 without spin: slides (friction mu_k m g alone), rolls from
// t* = β v0 / (mu_k g (1 + β)) at v0 / (1 + β), and rests, held, at t* + v0 / (mu_r g).
TEST(RollingResistanceE2e, BallSlidesRollsAndComesToRest) {
  const double v0 = 2.0, mu_k = 0.6, mu_r = 0.05, beta = 0.4;
  const double t_roll = beta * v0 / (mu_k * kG * (1 + beta));
  const double t_rest = t_roll + v0 / (mu_r * kG);
  const RunOut r =
      Simulate("slide-roll-rest", Scene(kBall, 0.0, "0 N", 0.0, 1.2 * t_rest,
                                        "{position: [0, 0, R], velocity: [2 m/s, 0, 0]}"));
  const auto slips = Events(r, "slip stopped");
  const auto stops = Events(r, "rolling stopped");
  ASSERT_EQ(slips.size(), 1u);
  ASSERT_EQ(stops.size(), 1u);
  EXPECT_NEAR(slips[0].at("t").get<double>(), t_roll, kEvent * t_roll);
  EXPECT_NEAR(stops[0].at("t").get<double>(), t_rest, kEvent * t_rest);
  EXPECT_EQ(stops[0].at("to"), "sticking, rolling held");
  EXPECT_LT(std::abs(SlopeVelocity(r, 0.0)), 1e-12);
  // The slide takes ½ m v0² β/(1 + β), rolling resistance the rest.
  const double E0 = 0.5 * 0.4 * v0 * v0;
  const nlohmann::json& L = r.json.at("ledger");
  EXPECT_NEAR(L.at("friction_work").get<double>(), -E0 * beta / (1 + beta), kEvent * E0);
  EXPECT_NEAR(L.at("rolling_work").get<double>(), -E0 / (1 + beta), kEvent * E0);
  ExpectLedgerClosed(r);
}

}  // namespace
}  // namespace chasles::test
