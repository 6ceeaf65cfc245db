// End-to-end: the supports' impulsive reactions and every body's velocity jumps at an impulse
// or an impact, in `chasles simulate`'s text report and JSON summary, against closed forms
// derived in the tests: the struck double pendulum of examples/double-pendulum-struck.yaml
// (tests/reference/struck_double_pendulum.h: impulse-momentum of each rod, eqs. 8.118, 8.119)
// and a pinned rod that a bullet passes through (chapter 8.5: no pin impulse at the centre of
// percussion).

#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "cli_runner.h"
#include "reference/struck_double_pendulum.h"
#include "test_support.h"

namespace chasles::test {
namespace {

using reference::StruckDoublePendulum;

// One projection (a linear solve) in the run, and the JSON's shortest round-trip numbers.
constexpr double kImpulse = 1e-12;
constexpr double kPi = 3.14159265358979323846;

const std::string kExample = "examples/double-pendulum-struck.yaml";

std::filesystem::path Out() {
  return OutDir("impulsive_reactions");
}

const nlohmann::json& Named(const nlohmann::json& list, const std::string& name) {
  for (const auto& x : list) {
    if (x.at("name") == name) return x;
  }
  throw std::runtime_error("nothing named " + name);
}

Eigen::Vector2d Xy(const nlohmann::json& v) {
  return {v.at(0).get<double>(), v.at(1).get<double>()};
}

// A value as the text report prints it (9 significant digits; a zero as 0).
std::string Text(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.9g", v + 0.0);
  return buf;
}

// The jump's pins and rods in the JSON against the closed form, to kImpulse of the impulse J.
void ExpectPendulumJson(const StruckDoublePendulum& p, const StruckDoublePendulum::Answer& a,
                        const nlohmann::json& jump) {
  const double J = p.J.norm();
  const auto& O = Named(jump.at("reactions"), "O");
  const auto& E = Named(jump.at("reactions"), "elbow");
  EXPECT_TRUE(MatNear(Xy(O.at("impulse")), a.R_O, kImpulse, J)) << O.dump();
  EXPECT_TRUE(MatNear(Xy(E.at("impulse")), a.R_E, kImpulse, J)) << E.dump();
  // The planar block: Jx, Jy and the moment impulse about z (none at a pin).
  EXPECT_TRUE(Near(O.at("planar").at("Jx").get<double>(), a.R_O.x(), kImpulse, J));
  EXPECT_TRUE(Near(E.at("planar").at("Jy").get<double>(), a.R_E.y(), kImpulse, J));
  EXPECT_TRUE(Near(E.at("planar").at("Mz").get<double>(), 0.0, kImpulse, J * p.L1));
  const auto& upper = Named(jump.at("bodies"), "upper");
  const auto& lower = Named(jump.at("bodies"), "lower");
  const double v = J / p.m2, w = J / (p.m2 * p.L2);
  EXPECT_TRUE(MatNear(Xy(upper.at("velocity_change")), a.dv1, kImpulse, v));
  EXPECT_TRUE(MatNear(Xy(lower.at("velocity_change")), a.dv2, kImpulse, v));
  EXPECT_TRUE(Near(upper.at("planar").at("domega").get<double>(), a.w1, kImpulse, w));
  EXPECT_TRUE(Near(lower.at("planar").at("domega").get<double>(), a.w2, kImpulse, w));
  // Each body's balance from the JSON alone: m Δv = ΣJ and ΔH_cm = Σ (r × J + M).
  for (const auto& b : jump.at("bodies")) {
    const double m = b.at("mass").get<double>();
    const Eigen::Vector3d c = ToVec(b.at("center_of_mass"));
    Eigen::Vector3d P = Eigen::Vector3d::Zero(), H = Eigen::Vector3d::Zero();
    for (const auto& i : b.at("impulses")) {
      const Eigen::Vector3d Ji = ToVec(i.at("impulse"));
      P += Ji;
      H += (ToVec(i.at("point")) - c).cross(Ji) + ToVec(i.at("moment_impulse"));
    }
    EXPECT_TRUE(MatNear(Eigen::Vector3d(m * ToVec(b.at("velocity_change"))), P, kImpulse, J));
    EXPECT_TRUE(MatNear(ToVec(b.at("angular_momentum_change")), H, kImpulse, J * p.L1));
  }
}

void ExpectImpulseChecksPassed(const nlohmann::json& j) {
  for (const char* name : {"linear impulse balance", "angular impulse balance"}) {
    const auto& c = Named(j.at("checks").at("checks"), name);
    EXPECT_TRUE(c.at("applies").get<bool>()) << name;
    EXPECT_TRUE(c.at("passed").get<bool>()) << c.dump();
  }
  EXPECT_TRUE(j.at("checks").at("passed").get<bool>());
}

TEST(ImpulsiveReactionsE2e, HangingDoublePendulumJsonGivesBothPinsAndBothRods) {
  const auto j = SimulateJson(SourcePath(kExample), Out());
  ASSERT_EQ(j.at("jumps").size(), 1u);
  const StruckDoublePendulum p;  // the example's values
  ExpectPendulumJson(p, p.Hanging(), j.at("jumps")[0]);
  ExpectImpulseChecksPassed(j);
  // The CSV keeps its columns; the jump's row is there (t = 0 twice: before and after).
  EXPECT_EQ(j.at("jumps")[0].at("impacts").size(), 0u);
}

TEST(ImpulsiveReactionsE2e, HangingDoublePendulumTextPrintsThePinImpulsesAndJumps) {
  const CliResult r =
      RunCli("simulate " + Quote(SourcePath(kExample)) + " --out " + Quote(Out().string()));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const StruckDoublePendulum p;
  const StruckDoublePendulum::Answer a = p.Hanging();
  // Every printed digit: R_O = -3/22, R_E = 3/11 N·s; Δω1 = -9/22, Δω2 = 405/44 rad/s.
  EXPECT_THAT(r.out,
              ::testing::HasSubstr("    impulsive reactions (on the child at the joint "
                                   "point)\n      O at [0, 0] m: impulse [" +
                                   Text(a.R_O.x()) + ", 0] kg*m/s, moment impulse 0 kg*m^2/s\n"));
  EXPECT_THAT(r.out, ::testing::HasSubstr("      elbow at [0, -1] m: impulse [" + Text(a.R_E.x()) +
                                          ", 0] kg*m/s, moment impulse 0 kg*m^2/s\n"));
  EXPECT_THAT(r.out, ::testing::HasSubstr("      upper: dv [" + Text(a.dv1.x()) +
                                          ", 0] m/s, domega " + Text(a.w1) + " rad/s\n"));
  EXPECT_THAT(r.out, ::testing::HasSubstr("      lower: dv [" + Text(a.dv2.x()) +
                                          ", 0] m/s, domega " + Text(a.w2) + " rad/s\n"));
  EXPECT_THAT(r.out, ::testing::HasSubstr("linear impulse balance"));
}

TEST(ImpulsiveReactionsE2e, DoublePendulumAtAGeneralConfigurationMatchesBothRodsBalances) {
  const auto j = SimulateJson(SourcePath(kExample), Out(),
                              "--set 'theta1=-60 deg' --set 'theta2=25 deg' --set 's=0.3 m'");
  ASSERT_EQ(j.at("jumps").size(), 1u);
  StruckDoublePendulum p;
  p.theta1 = -60 * kPi / 180;
  p.theta2 = 25 * kPi / 180;
  p.s = 0.3;
  ExpectPendulumJson(p, p.Solve(), j.at("jumps")[0]);
  ExpectImpulseChecksPassed(j);
  // The elbow's impulse in the parent's (upper rod's) frame: R_WUᵀ R_E.
  const Eigen::Vector2d R_E = p.Solve().R_E;
  const Eigen::Vector2d in_upper(std::cos(p.theta1) * R_E.x() + std::sin(p.theta1) * R_E.y(),
                                 -std::sin(p.theta1) * R_E.x() + std::cos(p.theta1) * R_E.y());
  EXPECT_TRUE(MatNear(Xy(Named(j.at("jumps")[0].at("reactions"), "elbow").at("impulse_parent")),
                      in_upper, kImpulse, p.J.norm()));
}

// A rod (mass M = 2 kg, length L = 1.2 m) pinned at the origin about z, at rest along x; a
// bullet (m = 0.05 kg) moving along y at u = 300 m/s passes through it at x = d keeping
// f = 0.4 of its velocity. The rod takes J = m (1 - f) u at d: I_O ω = J d with I_O = M L²/3,
// and impulse-momentum of the rod gives the pin's impulse on it along y,
// R = M (L/2) ω - J = J (3 d / (2 L) - 1), which vanishes at the centre of percussion 2L/3.
TEST(ImpulsiveReactionsE2e, PassThroughAPinnedRodGivesThePinItsClosedFormImpulse) {
  const auto scene = Out() / "pinned-rod-bullet.yaml";
  {
    std::ofstream out(scene);
    out << "chasles: 1\n"
           "parameters:\n"
           "  len: 1.2 m\n"
           "  d: 0.5 m\n"
           "bodies:\n"
           "  - name: rod\n"
           "    parts:\n"
           "      - {shape: custom, mass: 2 kg, center_of_mass: [len/2, 0, 0],\n"
           "         inertia: {Ixx: 1e-6 kg*m^2, Iyy: 2 kg*len^2/12, Izz: 2 kg*len^2/12}}\n"
           "  - name: bullet\n"
           "    parts: [{shape: sphere, radius: 2 mm, mass: 0.05 kg}]\n"
           "    initial: {position: [d, 0, 0], velocity: [0, 300 m/s, 0]}\n"
           "joints:\n"
           "  - {name: pin, type: revolute, parent: world, child: rod, at: [0, 0, 0],\n"
           "     axis: [0, 0, 1]}\n"
           "impacts:\n"
           "  - {time: 0 s, target: rod, projectile: bullet, exit_fraction: 0.4}\n"
           "simulation: {until: 0.001 s, tolerance: 1e-12}\n";
  }
  const double M = 2.0, L = 1.2, m = 0.05, u = 300.0, f = 0.4, J = m * (1 - f) * u;
  for (const double d : {0.5, 2 * L / 3, 0.9 * L}) {
    const std::string set = "--set 'd=" + Text(d) + " m'";
    const auto j = SimulateJson(scene.string(), Out(), set);
    ASSERT_EQ(j.at("jumps").size(), 1u);
    const auto& pin = Named(j.at("jumps")[0].at("reactions"), "pin");
    const double w = J * d / (M * L * L / 3);
    const double R = M * L / 2 * w - J;
    EXPECT_TRUE(MatNear(ToVec(pin.at("impulse")), Eigen::Vector3d(0, R, 0), kImpulse, J))
        << "d = " << d << ": " << pin.dump();
    EXPECT_TRUE(Near(R, J * (3 * d / (2 * L) - 1), 1e-14, J));
    // The world is the pin's parent: its frame is W.
    EXPECT_EQ(pin.at("impulse_parent"), pin.at("impulse"));
    const auto& rod = Named(j.at("jumps")[0].at("bodies"), "rod");
    EXPECT_TRUE(Near(ToVec(rod.at("angular_velocity_change")).z(), w, kImpulse));
    ExpectImpulseChecksPassed(j);
    // The text prints the pin's impulse with every digit the closed form has.
    const CliResult text =
        RunCli("simulate " + Quote(scene.string()) + " --out " + Quote(Out().string()) + " " + set);
    ASSERT_EQ(text.exit_code, 0) << text.err;
    EXPECT_THAT(text.out,
                ::testing::HasSubstr("      pin at [0, 0, 0] m: impulse [0, " +
                                     Text(std::abs(R) <= 1e-12 * J ? 0.0 : R) + ", 0] kg*m/s"))
        << "d = " << d;
  }
}

}  // namespace
}  // namespace chasles::test
