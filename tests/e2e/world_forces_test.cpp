// End-to-end: forces whose line of action is fixed in the world (docs/scene-format.md,
// `forces`): a force of fixed world direction at a body point, a force at a world-fixed point,
// a cable to a fixed winch; and `gravity` given as a magnitude. The closed forms are derived
// here and in the examples' comments.

#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "chasles/math/types.h"
#include "cli_runner.h"
#include "test_support.h"

namespace chasles::test {
namespace {

// A run at tolerance 1e-12 over a few hundred steps: its answers are met to 1e-9 relative.
constexpr double kRun = 1e-9;

nlohmann::json RunExample(const std::string& example, const std::string& extra = "") {
  return SimulateJson(SourcePath(example), OutDir("world-forces"), "--strict " + extra);
}

Vec3 V(const nlohmann::json& j) {
  return ToVec(j);
}

// examples/pinned-rod-world-force.yaml: a rod (m, L) on a pin, pushed at its centre by F along
// +x (fixed world direction) under gravity 9.81 along -z. With θ from the downward vertical,
// the force's potential -F (L/2) sin θ and gravity's -m g (L/2) cos θ give
//   ½ I_O ω² = F (L/2) sin θ - m g (L/2)(1 - cos θ),  I_O = m L²/3,
// so from rest it swings to θ_max = 2 atan(F/(m g)) and stops there (the event 'top').
TEST(WorldForces, PinnedRodSwingsToTwiceTheEquilibriumAngle) {
  const double m = 2, L = 1, F = 5, g = 9.81;
  const auto j = RunExample("examples/pinned-rod-world-force.yaml");
  ASSERT_TRUE(j.at("stopped_by_event").get<bool>());
  ASSERT_EQ(j.at("events").at(0).at("name"), "top");
  const Vec3 c = V(j.at("final").at("bodies").at(0).at("center_of_mass"));
  const double theta = std::atan2(c.x(), -c.z());
  EXPECT_NEAR(theta, 2 * std::atan(F / (m * g)), kRun * theta);
  EXPECT_NEAR(c.norm(), L / 2, kRun * L);
  // The force's work W = ∫F·v dt = F Δx_cm (its line of action keeps its direction).
  const double W = j.at("ledger").at("work_by_force").at("push").get<double>();
  EXPECT_NEAR(W, F * c.x(), kRun * F * L);
  // At rest at θ_max the pin holds the rod: rod at rest, the pin's force along the rod is
  // the pull m g cos θ + F sin θ... checked through Newton's law on the whole rod instead:
  // with ω = 0, m a_cm = F x̂ - m g ẑ + R and a_cm = α × r_cm, I_O α = F (L/2) cos θ -
  // m g (L/2) sin θ (moments about the pin, y pointing so that +α raises the rod).
  const double alpha =
      (F * L / 2 * std::cos(theta) - m * g * L / 2 * std::sin(theta)) / (m * L * L / 3);
  // a_cm = α (L/2) (cos θ, 0, sin θ): the direction of increasing θ.
  const Vec3 a_cm = alpha * L / 2 * Vec3(std::cos(theta), 0, std::sin(theta));
  const Vec3 R = m * a_cm - Vec3(F, 0, -m * g);
  const Vec3 R_run = V(j.at("final").at("reactions").at(0).at("force"));
  EXPECT_TRUE(MatNear(R_run, R, kRun)) << R_run.transpose();
}

// The same scene at the equilibrium angle tan θ_e = F / (m g) (`chasles solve`): no angular
// acceleration, and the pin balances the two forces: R = (-F, 0, m g).
TEST(WorldForces, PinnedRodEquilibriumAngleBalancesThePush) {
  const double m = 2, F = 5, g = 9.81;
  const CliResult r = RunCli("solve " + Quote(SourcePath("examples/pinned-rod-world-force.yaml")) +
                             " --format json --set 'theta_0=atan(5/(2*9.81))'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  const auto& body = j.at("bodies").at(0);
  EXPECT_NEAR(V(body.at("angular_acceleration")).norm(), 0.0, kRun * g);
  const Vec3 R = V(j.at("reactions").at(0).at("force"));
  EXPECT_TRUE(MatNear(R, Vec3(-F, 0, m * g), kRun)) << R.transpose();
}

// examples/wheel-pushed-at-fixed-point.yaml: a disk (m, R) on a frictionless axle pushed by F
// along +x at the world-fixed point (0, 0, R): the moment about the axle stays R F, so
// α = R F / (m R²/2), ω(t) = α t, and the force's work F R θ = ½ I ω² (its power is F·v of
// the material point at the top, F R ω).
TEST(WorldForces, ForceAtAWorldPointKeepsItsMoment) {
  const double m = 3, R = 0.2, F = 4, t = 2;
  const double I = m * R * R / 2, alpha = R * F / I, w = alpha * t;
  const auto j = RunExample("examples/wheel-pushed-at-fixed-point.yaml");
  const Vec3 w_run = V(j.at("final").at("bodies").at(0).at("angular_velocity"));
  EXPECT_NEAR(w_run.y(), w, kRun * w);
  EXPECT_NEAR(j.at("ledger").at("work_by_force").at("push").get<double>(), 0.5 * I * w * w,
              kRun * 0.5 * I * w * w);
  EXPECT_NEAR(j.at("ledger").at("kinetic_rotational").get<double>(), 0.5 * I * w * w,
              kRun * 0.5 * I * w * w);
}

// examples/cable-to-winch.yaml: a ball (m) pulled towards the origin with tension T, started
// at (d, 0, 0) with velocity (0, v0, 0). Central force: m r × v = m d v0 ẑ throughout, and
// ½ m v² + T |r| = ½ m v0² + T d; the event stops it at |r| = d/2.
TEST(WorldForces, CableToAWinchIsACentralForce) {
  const double m = 0.5, d = 2, v0 = 1.5, T = 3;
  const auto j = RunExample("examples/cable-to-winch.yaml");
  ASSERT_TRUE(j.at("stopped_by_event").get<bool>());
  ASSERT_EQ(j.at("events").at(0).at("name"), "near");
  const auto& b = j.at("final").at("bodies").at(0);
  const Vec3 r = V(b.at("center_of_mass")), v = V(b.at("velocity"));
  EXPECT_NEAR(r.norm(), d / 2, kRun * d);
  EXPECT_TRUE(MatNear(m * r.cross(v), Vec3(0, 0, m * d * v0), kRun));
  const double E0 = 0.5 * m * v0 * v0 + T * d;
  EXPECT_NEAR(0.5 * m * v.squaredNorm() + T * r.norm(), E0, kRun * E0);
  // The cable's work is -T Δ|r| = T d / 2.
  EXPECT_NEAR(j.at("ledger").at("work_by_force").at("cable").get<double>(), T * d / 2,
              kRun * T * d);
}

}  // namespace
}  // namespace chasles::test
