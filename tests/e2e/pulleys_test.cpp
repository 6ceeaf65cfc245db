// End-to-end: pulleys carried by bodies (`over: [{body: ...}]`), a string pulled by hand on a
// drum (`type: string_pull`) and the chapter's cable-on-hub problems 8.49 and 8.50, through
// `chasles solve` (forces at the start) and `chasles simulate` (the motion, the event time).
// Every closed form is derived here from the equations of motion (and in the examples'
// comments).

#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "chasles/math/types.h"
#include "cli_runner.h"
#include "test_support.h"

namespace chasles::test {
namespace {

constexpr double kSolve = 1e-9;  // one linear solve: round-off only
constexpr double kRun = 1e-9;    // a run at tolerance 1e-12
constexpr double kFoot = 0.3048, kPound = 0.45359237;

const nlohmann::json& Named(const nlohmann::json& list, const std::string& name) {
  for (const auto& x : list) {
    if (x.at("name") == name) return x;
  }
  throw std::runtime_error("nothing named " + name);
}

nlohmann::json Solve(const std::string& example, const std::string& extra = "") {
  const CliResult r =
      RunCli("solve " + Quote(SourcePath(example)) + " --format json --strict " + extra);
  if (r.exit_code != 0) throw std::runtime_error(example + ": " + r.err);
  return nlohmann::json::parse(r.out);
}

double Y(const nlohmann::json& v) {
  return v.at(1).get<double>();
}

// examples/movable-pulley.yaml: m1 = 1.5 kg on the free end, m2 = 2 kg on the movable pulley,
// g = 9.81. The string's length 2 (y_f - y2) + (y_f - y1) + arcs is constant: a1 = -2 a2; the
// loop holds the block's pulley with 2T: m1 a1 = T - m1 g, m2 a2 = 2T - m2 g, so
// a2 = (2 m1 - m2) g / (4 m1 + m2), T = 3 m1 m2 g / (4 m1 + m2).
TEST(Pulleys, MovablePulleyCarriedByTheHangingBlock) {
  const double m1 = 1.5, m2 = 2.0, g = 9.81, t = 0.5;
  const double a2 = (2 * m1 - m2) * g / (4 * m1 + m2);
  const double T = 3 * m1 * m2 * g / (4 * m1 + m2);
  const auto s = Solve("examples/movable-pulley.yaml");
  EXPECT_TRUE(Near(Y(Named(s.at("bodies"), "m2").at("acceleration")), a2, kSolve));
  EXPECT_TRUE(Near(Y(Named(s.at("bodies"), "m1").at("acceleration")), -2 * a2, kSolve));
  const auto& rope = Named(s.at("reactions"), "rope");
  EXPECT_TRUE(Near(rope.at("multipliers").at(0).get<double>(), T, kSolve));
  // On m1 (the child) the string pulls up with T at its end.
  EXPECT_TRUE(MatNear(ToVec(rope.at("force")), Vec3(0, T, 0), kSolve, T));

  const auto j =
      SimulateJson(SourcePath("examples/movable-pulley.yaml"), OutDir("pulleys"), "--strict");
  const auto& b = j.at("final").at("bodies");
  const double rise = 0.5 * a2 * t * t;
  EXPECT_TRUE(Near(Named(b, "m2").at("planar").at("y").get<double>(), -1.5 + rise, kRun));
  EXPECT_TRUE(Near(Named(b, "m1").at("planar").at("y").get<double>(), -1.0 - 2 * rise, kRun));
  EXPECT_TRUE(Near(Named(b, "m2").at("planar").at("vy").get<double>(), a2 * t, kRun));
}

// examples/spool-pulled-by-string.yaml: m = 2 kg, R = 0.1 m, r = 0.05 m, k = 0.07 m, P = 5 N,
// the string leaving the hub's underside at θ. With a along +x, f the friction along +x and
// α = -a/R (rolling):
//   m a = P cos θ + f,   m k² α = r P + R f   (the string's moment about the centre is r P:
//   its line passes at r from the centre; the friction's is R f)
// ⇒ a = P (cos θ - r/R) / (m (1 + k²/R²)),  f = m a - P cos θ,  N = m g - P sin θ.
// Below θ_c = acos(r/R) = 60° it rolls towards the pull, above it away.
TEST(Pulleys, SpoolPulledByAStringRollsEitherWayOfTheCriticalAngle) {
  const double m = 2, R = 0.1, r = 0.05, k = 0.07, P = 5, g = 9.81;
  for (const double deg : {30.0, 75.0}) {
    const double th = deg * std::acos(-1.0) / 180;
    const double a = P * (std::cos(th) - r / R) / (m * (1 + k * k / (R * R)));
    const double f = m * a - P * std::cos(th);
    const auto s = Solve("examples/spool-pulled-by-string.yaml",
                         "--set 'theta=" + std::to_string(deg) + " deg'");
    const auto& spool = Named(s.at("bodies"), "spool");
    const double ax = ToVec(spool.at("acceleration")).x();
    EXPECT_TRUE(Near(ax, a, kSolve)) << deg;
    EXPECT_EQ(ax > 0, deg < 60) << deg;  // which way it rolls
    EXPECT_TRUE(Near(ToVec(spool.at("angular_acceleration")).z(), -a / R, kSolve)) << deg;
    const auto& floor = Named(s.at("reactions"), "floor");
    EXPECT_TRUE(Near(ToVec(floor.at("force")).x(), f, kSolve, P)) << deg;
    EXPECT_TRUE(Near(ToVec(floor.at("force")).y(), m * g - P * std::sin(th), kSolve)) << deg;
  }
  // The run: from rest x = a t²/2 and ω = -a t / R after t = 1 s.
  const double th = std::acos(-1.0) / 6;
  const double a = P * (std::cos(th) - r / R) / (m * (1 + k * k / (R * R)));
  const auto j = SimulateJson(SourcePath("examples/spool-pulled-by-string.yaml"), OutDir("pulleys"),
                              "--strict");
  const auto& spool = Named(j.at("final").at("bodies"), "spool").at("planar");
  EXPECT_TRUE(Near(spool.at("x").get<double>(), 0.5 * a, kRun));
  EXPECT_TRUE(Near(spool.at("omega").get<double>(), -a / R, kRun));
}

// Problems 8.49 and 8.50: a wheel (M, R, radius of gyration k) with a hub of radius ρ rolls
// without sliding; a cable leaves the hub's top horizontally, runs over a fixed frictionless
// massless pulley and down to a block m. v the centre's velocity (+x, towards the pulley),
// ω = -v/R counterclockwise, the hub's top moves at v (1 + ρ/R) = β v and the block goes down
// at β v. Impulse and momentum over [0, t] with the constant tension T and friction f (+x):
//   M (v - v0) = (T + f) t,  M k² (ω - ω0) = (R f - ρ T) t,  m β (v - v0) = (m g - T) t.
// With a = (v - v0)/t the second is -M k² a / R = R f - ρ T; adding the first times R:
// M a (1 + k²/R²) = β T, and the third T = m (g - β a):
//   a = m g β / (M (1 + k²/R²) + m β²),  T = m (g - β a),  f = M a - T,
// and from counterclockwise ω_i (v0 = -ω_i R) to clockwise ω_f (v = ω_f R):
//   t = (ω_i + ω_f) R / a.
struct HubProblem {
  std::string example;
  double M, m, R, rho, k, g, w_i, w_f;
  double t_book;  // the closed form worked by hand for part (c)
};

void CheckHubProblem(const HubProblem& p) {
  const double beta = 1 + p.rho / p.R;
  const double a = p.m * p.g * beta / (p.M * (1 + p.k * p.k / (p.R * p.R)) + p.m * beta * beta);
  const double T = p.m * (p.g - beta * a);
  const double f = p.M * a - T;
  const double t = (p.w_i + p.w_f) * p.R / a;
  EXPECT_TRUE(Near(t, p.t_book, 1e-12)) << p.example;
  const auto s = Solve(p.example);
  EXPECT_TRUE(Near(ToVec(Named(s.at("bodies"), "wheel").at("acceleration")).x(), a, kSolve));
  EXPECT_TRUE(Near(Y(Named(s.at("bodies"), "block").at("acceleration")), -beta * a, kSolve));
  const auto& cable = Named(s.at("reactions"), "cable");
  EXPECT_TRUE(Near(cable.at("multipliers").at(0).get<double>(), T, kSolve)) << p.example;
  EXPECT_TRUE(Near(ToVec(Named(s.at("reactions"), "floor").at("force")).x(), f, kSolve, T));

  const auto j = SimulateJson(SourcePath(p.example), OutDir("pulleys"), "--strict");
  EXPECT_TRUE(j.at("stopped_by_event").get<bool>()) << p.example;
  ASSERT_EQ(j.at("events").size(), 1u);
  const auto& e = j.at("events").at(0);
  EXPECT_EQ(e.at("name"), "reversed");
  EXPECT_TRUE(Near(e.at("t").get<double>(), t, kRun)) << p.example;
  const auto& wheel = Named(j.at("final").at("bodies"), "wheel").at("planar");
  EXPECT_TRUE(Near(wheel.at("omega").get<double>(), -p.w_f, kRun));
  EXPECT_TRUE(Near(wheel.at("vx").get<double>(), p.w_f * p.R, kRun));
}

// 8.49 (c): Mg = 150 lb, mg = 50 lb, R = 2 ft, ρ = k = R/2, ω = 5 /s both ways,
// g = 32.2 ft/s²: β = 3/2, a = 1.5 m g / (1.25 M + 2.25 m) = 75 g / 300 = g/4,
// t = 2 ω R / a = 8 ω R / g = 80 ft/s / 32.2 ft/s².
TEST(Pulleys, Problem849WheelPulledBackByACableOnItsHub) {
  const double R = 2 * kFoot, g = 32.2 * kFoot;
  CheckHubProblem({"examples/problem-8.49-wheel-cable-hub.yaml", 150 * kPound, 50 * kPound, R,
                   R / 2, R / 2, g, 5, 5, 80.0 / 32.2});
}

// 8.50 (c): M = 75 kg, m = 25 kg, R = 1 m, ρ = k = 2R/3, ω_i = 10 /s, ω_f = 6 /s, g = 9.81:
// β = 5/3, a = 15 m g / (13 M + 25 m) = 375 g / 1600, t = 16 / a.
TEST(Pulleys, Problem850WheelPulledBackByACableOnItsHub) {
  const double g = 9.81;
  CheckHubProblem({"examples/problem-8.50-wheel-cable-hub.yaml", 75, 25, 1, 2.0 / 3, 2.0 / 3, g, 10,
                   6, 16 / (375 * g / 1600)});
}

}  // namespace
}  // namespace chasles::test
