// End-to-end: the dynamics examples run through `chasles simulate`, against closed-form
// answers derived here (formulas with their sources). Tolerances follow from the integrator
// tolerance 1e-12 of the examples: 1e-8 relative for states after many steps, tighter where
// the answer comes from one impulse.

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <boost/math/special_functions/ellint_1.hpp>
#include <boost/math/special_functions/jacobi_elliptic.hpp>

#include "cli_runner.h"
#include "test_support.h"

namespace chasles::test {
namespace {

// Error of a run at integrator tolerance 1e-12 over hundreds to thousands of steps.
constexpr double kRun = 1e-8;
// Impulse-momentum answers: a handful of operations, no integration.
constexpr double kJump = 1e-12;
constexpr double kStandardGravity = 9.80665;

std::filesystem::path OutDir() {
  return test::OutDir("simulate");
}

nlohmann::json Simulate(const std::string& example, const std::string& extra = "") {
  return SimulateJson(SourcePath(example), OutDir(), extra);
}

const nlohmann::json& FinalBody(const nlohmann::json& j, size_t i = 0) {
  return j.at("final").at("bodies").at(i);
}

// Dzhanibekov: I = (1, 2, 3) kg m², w0 = (0.01, 10, 0.01) rad/s. Closed form of Euler's
// equations (Landau & Lifshitz, Mechanics, §37), for H² > 2T I2:
//   w1 = A1 cn τ, w2 = A2 sn τ, w3 = A3 dn τ, τ = λ t + τ0,
//   A1² = (2T I3 - H²)/(I1 (I3 - I1)), A2² = (2T I3 - H²)/(I2 (I3 - I2)),
//   A3² = (H² - 2T I1)/(I3 (I3 - I1)), λ² = (I3 - I2)(H² - 2T I1)/(I1 I2 I3),
//   k² = (I2 - I1)(2T I3 - H²)/((I3 - I2)(H² - 2T I1)), τ0 = F(atan2(w2/A2, w1/A1), k).
struct Dzhanibekov {
  double I1 = 1, I2 = 2, I3 = 3;
  Vec3 w0{0.01, 10.0, 0.01};
  double A1, A2, A3, lambda, k, tau0;
  Dzhanibekov() {
    const Vec3& w = w0;
    const double T2 = I1 * w[0] * w[0] + I2 * w[1] * w[1] + I3 * w[2] * w[2];
    const double H2 = I1 * I1 * w[0] * w[0] + I2 * I2 * w[1] * w[1] + I3 * I3 * w[2] * w[2];
    A1 = std::sqrt((T2 * I3 - H2) / (I1 * (I3 - I1)));
    A2 = std::sqrt((T2 * I3 - H2) / (I2 * (I3 - I2)));
    A3 = std::sqrt((H2 - T2 * I1) / (I3 * (I3 - I1)));
    lambda = std::sqrt((I3 - I2) * (H2 - T2 * I1) / (I1 * I2 * I3));
    k = std::sqrt((I2 - I1) * (T2 * I3 - H2) / ((I3 - I2) * (H2 - T2 * I1)));
    tau0 = boost::math::ellint_1(k, std::atan2(w[1] / A2, w[0] / A1));
  }
  Vec3 Omega(double t) const {
    double cn = 0, dn = 0;
    const double sn = boost::math::jacobi_elliptic(k, lambda * t + tau0, &cn, &dn);
    return {A1 * cn, A2 * sn, A3 * dn};
  }
  // sn τ falls through zero at τ = 2K(k) (it is positive on (0, 2K)).
  double FirstFlipTime() const { return (2 * boost::math::ellint_1(k) - tau0) / lambda; }
};

TEST(Simulate, DzhanibekovFollowsTheEllipticSolution) {
  const Dzhanibekov ref;
  const auto j = Simulate("examples/dzhanibekov.yaml");
  const Vec3 w = ToVec(FinalBody(j).at("angular_velocity_body"));
  const Vec3 expected = ref.Omega(10.0);
  for (int i = 0; i < 3; ++i) EXPECT_TRUE(Near(w[i], expected[i], kRun, 10.0)) << i;
  ASSERT_GE(j.at("events").size(), 1u);
  EXPECT_EQ(j.at("events").at(0).at("name"), "flip");
  EXPECT_NEAR(j.at("events").at(0).at("t").get<double>(), ref.FirstFlipTime(), kRun);
  // Torque-free: T and the angular momentum are constant (T = ½ Σ I w² = 100.0002 J).
  const double T0 = 0.5 * (1 * 1e-4 + 2 * 100 + 3 * 1e-4);
  EXPECT_TRUE(Near(j.at("ledger").at("energy").get<double>(), T0, 1e-10));
  EXPECT_TRUE(
      MatNear(ToVec(j.at("ledger").at("angular_momentum_cm")), Vec3(0.01, 20, 0.03), 1e-10, 20.0));
}

// Axisymmetric body, no moment: w3 const, (w1, w2) = w⊥ (cos Ωb t, sin Ωb t), Ωb = (J - I) w3/I
// (Euler's equations with I1 = I2 = I). Disk: I = m(3R² + h²)/12, J = m R²/2 (Appendix A).
TEST(Simulate, TorqueFreeDiskPrecessesAtTheBodyRate) {
  const double m = 1, R = 0.1, h = 0.02, w3 = 20, wp = 2, t = 2;
  const double I = m * (3 * R * R + h * h) / 12, J = m * R * R / 2;
  const double Wb = (J - I) * w3 / I;
  const auto j = Simulate("examples/torque-free-precession.yaml");
  EXPECT_TRUE(MatNear(ToVec(FinalBody(j).at("angular_velocity_body")),
                      Vec3(wp * std::cos(Wb * t), wp * std::sin(Wb * t), w3), kRun, w3));
  // The world angular momentum stays I w⊥ x + J w3 z (the initial one; orientation identity).
  EXPECT_TRUE(MatNear(ToVec(j.at("ledger").at("angular_momentum_origin")), Vec3(I * wp, 0, J * w3),
                      kRun, J * w3));
}

// Linear drag, k = c/m: z(t) = z0 + (vz0 + g/k)(1 - e^(-kt))/k - g t/k, x(t) = vx0 (1 - e^(-kt))/k.
// Heavy symmetric top (examples/heavy-top.yaml): a cone of mass m, radius R, height h on its tip,
// l = 3h/4, A = 3/20 m R^2 + 3/80 m h^2 + m l^2, C = 3/10 m R^2 about the tip. Steady precession
// at tilt theta and axial spin w3 needs A cos(theta) W^2 - C w3 W + m g l = 0 (slow root).
// The axis must then turn about the vertical at W with the tilt unchanged.
TEST(Simulate, HeavyTopPrecessesSteadily) {
  const double m = 0.5, R = 0.03, h = 0.08, g = 9.80665, l = 0.75 * h;
  const double A = 3.0 / 20 * m * R * R + 3.0 / 80 * m * h * h + m * l * l;
  const double C = 3.0 / 10 * m * R * R;
  const double theta = 0.5, w3 = 600, ct = std::cos(theta);
  const double W = (C * w3 - std::sqrt(C * C * w3 * w3 - 4 * A * ct * m * g * l)) / (2 * A * ct);
  const auto j = Simulate("examples/heavy-top.yaml");
  const double t = j.at("t_end").get<double>();
  const auto q = FinalBody(j).at("quaternion");
  const Quat q_WB(q.at(0).get<double>(), q.at(1).get<double>(), q.at(2).get<double>(),
                  q.at(3).get<double>());
  const Vec3 axis = q_WB * Vec3::UnitZ();
  const Vec3 expected(std::sin(theta) * std::cos(W * t), std::sin(theta) * std::sin(W * t), ct);
  EXPECT_TRUE(MatNear(axis, expected, kRun, 1.0));
  // The tip stays at the origin and the spin about the axis stays w3.
  EXPECT_TRUE(MatNear(ToVec(FinalBody(j).at("center_of_mass")), Vec3::Zero(), 0, 1e-12));
  EXPECT_TRUE(Near(ToVec(FinalBody(j).at("angular_velocity_body")).z(), w3, kRun));
}

TEST(Simulate, ProjectileWithDragMatchesTheClosedFormAndStopsAtTheGround) {
  const double m = 0.5, c = 0.1, k = c / m, g = kStandardGravity, z0 = 2, vx0 = 15, vz0 = 12;
  auto z = [&](double t) { return z0 + (vz0 + g / k) * (1 - std::exp(-k * t)) / k - g * t / k; };
  auto vz = [&](double t) { return (vz0 + g / k) * std::exp(-k * t) - g / k; };
  auto x = [&](double t) { return vx0 * (1 - std::exp(-k * t)) / k; };
  double t_hit = 2.5;  // Newton's method on z(t) = 0 from near the root
  for (int i = 0; i < 50; ++i) t_hit -= z(t_hit) / vz(t_hit);
  // Apex: vz = 0 at t = ln(1 + k vz0/g)/k.
  const double t_apex = std::log(1 + k * vz0 / g) / k;

  const auto j = Simulate("examples/projectile-drag.yaml");
  EXPECT_TRUE(j.at("stopped_by_event").get<bool>());
  ASSERT_EQ(j.at("events").size(), 2u);
  EXPECT_EQ(j.at("events").at(0).at("name"), "apex");
  EXPECT_NEAR(j.at("events").at(0).at("t").get<double>(), t_apex, 1e-9);
  EXPECT_EQ(j.at("events").at(1).at("name"), "ground");
  EXPECT_NEAR(j.at("events").at(1).at("t").get<double>(), t_hit, 1e-9);
  EXPECT_NEAR(j.at("t_end").get<double>(), t_hit, 1e-9);
  EXPECT_TRUE(Near(ToVec(FinalBody(j).at("center_of_mass")).x(), x(t_hit), kRun));
  // Every CSV row on the closed form.
  const auto csv = ReadCsv(j.at("csv").get<std::string>());
  ASSERT_GT(csv.at("t").size(), 40u);
  for (size_t i = 0; i < csv.at("t").size(); ++i) {
    const double t = csv.at("t")[i];
    EXPECT_TRUE(Near(csv.at("ball_x")[i], x(t), kRun, 10.0)) << t;
    EXPECT_TRUE(Near(csv.at("ball_z")[i], z(t), kRun, 10.0)) << t;
  }
  // Drag removed energy, and the ledger balances.
  EXPECT_LT(j.at("ledger").at("work_by_force").at("air").get<double>(), 0.0);
  EXPECT_LT(std::abs(j.at("ledger").at("relative_residual").get<double>()), 1e-9);
}

// m x'' = -k (x - L0): period 2π sqrt(m/k), energy ½ k A².
TEST(Simulate, SpringMassPeriodAndEnergy) {
  const double m = 2, k = 800, A = 0.05;
  const double period = 2 * M_PI * std::sqrt(m / k);
  const auto j = Simulate("examples/spring-mass.yaml");
  const auto& ev = j.at("events");
  ASSERT_EQ(ev.size(), 6u);  // turning points at P, 2P, ... 6P within 2 s
  for (size_t i = 0; i < ev.size(); ++i) {
    EXPECT_NEAR(ev.at(i).at("t").get<double>(), (i + 1) * period, 1e-9) << i;
  }
  EXPECT_TRUE(Near(j.at("ledger").at("energy").get<double>(), 0.5 * k * A * A, kRun));
}

// Section 8.5: v = F dt/m j, w = 3 F dt/(m a) (i + k).
TEST(Simulate, Section85CubeStruckAtACorner) {
  const double lb = 0.45359237, in = 0.0254, lbf = lb * kStandardGravity;
  const double m = 10 * lb, a = 6 * in, J = 2 * lbf;
  const auto j = Simulate("examples/section-8.5-cube-struck.yaml");
  ASSERT_EQ(j.at("jumps").size(), 1u);
  const auto& jump = j.at("jumps").at(0);
  EXPECT_TRUE(MatNear(ToVec(jump.at("velocity_after")), Vec3(0, J / m, 0), kJump, J / m));
  const double w = 3 * J / (m * a);
  EXPECT_TRUE(MatNear(ToVec(jump.at("angular_velocity_after")), Vec3(w, 0, w), kJump, w));
  // Isotropic inertia: w stays constant.
  EXPECT_TRUE(MatNear(ToVec(FinalBody(j).at("angular_velocity")), Vec3(w, 0, w), kRun, w));
  // Energy given by the impulse: ½ m v² + ½ (m a²/6) |w|².
  const double E = 0.5 * m * (J / m) * (J / m) + 0.5 * m * a * a / 6 * 2 * w * w;
  EXPECT_TRUE(Near(jump.at("energy_after").get<double>(), E, kJump));
}

// Bullet embeds: momentum about the composite centre of mass (see the example's comment).
TEST(Simulate, BulletEmbedsInAFreeBlock) {
  // The bullet is a particle: no (2/5) m r² of its own in I_c.
  const double M = 2, a = 0.3, b = 0.1, m = 0.02, v = 400, d = 0.1;
  const double vc = m * v / (M + m), e = m * d / (M + m);
  const double Ic = M * (a * a + b * b) / 12 + M * e * e + m * (d - e) * (d - e);
  const double w = (d - e) * m * v / Ic;
  const double lost = 0.5 * m * v * v - 0.5 * (M + m) * vc * vc - 0.5 * Ic * w * w;
  const auto j = Simulate("examples/bullet-embeds-in-block.yaml");
  ASSERT_EQ(j.at("jumps").size(), 1u);
  const auto& jump = j.at("jumps").at(0);
  EXPECT_EQ(jump.at("kind"), "embedding");
  EXPECT_TRUE(MatNear(ToVec(jump.at("velocity_after")), Vec3(0, vc, 0), kJump, vc));
  EXPECT_TRUE(MatNear(ToVec(jump.at("angular_velocity_after")), Vec3(0, 0, w), kJump, w));
  EXPECT_TRUE(Near(-jump.at("energy_change").get<double>(), lost, kJump));
  ASSERT_EQ(j.at("final").at("bodies").size(), 1u);
  EXPECT_EQ(FinalBody(j).at("name"), "block+bullet");
  EXPECT_TRUE(Near(FinalBody(j).at("mass").get<double>(), M + m, kJump));
  // Free afterwards: the composite's centre of mass moves uniformly from (e, 0, 0) at 0.01 s.
  EXPECT_TRUE(MatNear(ToVec(FinalBody(j).at("center_of_mass")), Vec3(e, vc * 0.49, 0), kRun, 1.0));
}

// Pass-through: J = m (1 - f) v at (d, 0, 0): v_block = J/M, w_z = d J / I_z.
TEST(Simulate, BulletPassesThroughAFreeBlock) {
  const double M = 2, a = 0.3, b = 0.1, m = 0.02, v = 400, d = 0.1, f = 0.4;
  const double J = m * (1 - f) * v, Iz = M * (a * a + b * b) / 12;
  const auto j = Simulate("examples/bullet-passes-through-block.yaml");
  const auto& jump = j.at("jumps").at(0);
  EXPECT_EQ(jump.at("kind"), "pass-through");
  EXPECT_TRUE(MatNear(ToVec(jump.at("velocity_after")), Vec3(0, J / M, 0), kJump, J / M));
  EXPECT_TRUE(
      MatNear(ToVec(jump.at("angular_velocity_after")), Vec3(0, 0, d * J / Iz), kJump, d * J / Iz));
  const double lost = 0.5 * m * v * v * (1 - f * f) - 0.5 * M * (J / M) * (J / M) -
                      0.5 * Iz * (d * J / Iz) * (d * J / Iz);
  EXPECT_TRUE(Near(-jump.at("energy_change").get<double>(), lost, kJump));
  EXPECT_TRUE(MatNear(ToVec(FinalBody(j, 1).at("velocity")), Vec3(0, f * v, 0), kJump, v));
  // Momentum is conserved through the impact: P = m v j throughout.
  EXPECT_TRUE(
      MatNear(ToVec(j.at("ledger").at("linear_momentum")), Vec3(0, m * v, 0), kJump, m * v));
}

// Work-energy balance (chapter 8.4): E - E0 = W_nc; residual < 1e-9 of the energy scale.
TEST(Simulate, LedgerBalancesWithSpringsDragAndAppliedLoads) {
  const auto j = Simulate("examples/ledger-springs-drag.yaml");
  const auto& L = j.at("ledger");
  EXPECT_LT(std::abs(L.at("relative_residual").get<double>()), 1e-9);
  double sum = 0;
  for (const auto& [name, w] : L.at("work_by_force").items()) sum += w.get<double>();
  EXPECT_TRUE(Near(sum, L.at("work_nonconservative").get<double>(), 1e-12, 10.0));
  EXPECT_NEAR(L.at("energy").get<double>() - L.at("energy_initial").get<double>() -
                  L.at("work_nonconservative").get<double>(),
              L.at("residual").get<double>(), 1e-12 * L.at("energy_scale").get<double>());
  // The damper and the drag only dissipate; the spring 'hanger' has no non-conservative part.
  EXPECT_LT(L.at("work_by_force").at("link").get<double>(), 0.0);
  EXPECT_LT(L.at("work_by_force").at("air").get<double>(), 0.0);
  EXPECT_EQ(L.at("work_by_force").at("hanger").get<double>(), 0.0);
  EXPECT_TRUE(Near(L.at("dissipated").get<double>(),
                   -(L.at("work_by_force").at("link").get<double>() +
                     L.at("work_by_force").at("air").get<double>()),
                   1e-12, 10.0));
}

TEST(SimulateCli, WritesCsvAndJsonAndAReport) {
  const auto dir = OutDir();
  const CliResult r = RunCli("simulate '" + SourcePath("examples/spring-mass.yaml") +
                             "' --until 0.5 --out '" + dir.string() + "'");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, ::testing::HasSubstr("Events"));
  EXPECT_THAT(r.out, ::testing::HasSubstr("balance residual"));
  EXPECT_THAT(r.out, ::testing::HasSubstr("Integrator: adaptive"));
  EXPECT_TRUE(r.err.empty()) << "no progress display when stderr is not a terminal: " << r.err;
  const auto csv = ReadCsv((dir / "spring-mass.csv").string());
  EXPECT_NEAR(csv.at("t").back(), 0.5, 1e-15);
  EXPECT_EQ(csv.at("t").size(), 51u);  // 0, 0.01, ..., 0.5
  std::ifstream in(dir / "spring-mass.json");
  const auto j = nlohmann::json::parse(in);
  EXPECT_EQ(j.at("t_end").get<double>(), 0.5);
  EXPECT_EQ(r.out.find("nan"), std::string::npos);
}

TEST(SimulateCli, ColumnsFromTheCommandLine) {
  const auto dir = OutDir();
  const CliResult r = RunCli("simulate " + Quote(SourcePath("examples/spring-mass.yaml")) +
                             " --out " + Quote(dir.string()) + " --columns position,energy");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::ifstream csv(dir / "spring-mass.csv");
  std::string header;
  std::getline(csv, header);
  // Name, one space, the SI unit in brackets (docs/scene-format.md, "Output").
  EXPECT_EQ(header,
            "t [s],block_x [m],block_y [m],block_z [m],T_trans [J],T_rot [J],T [J],V [J],E [J]");
  const CliResult bad = RunCli("simulate " + Quote(SourcePath("examples/spring-mass.yaml")) +
                               " --out " + Quote(dir.string()) + " --columns postion");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_THAT(bad.err, ::testing::HasSubstr("did you mean 'position'"));
}

TEST(SimulateCli, TextReportInTheScenesUnits) {
  // The cube example is written in inches and pounds: its report follows, the JSON stays SI.
  const auto dir = OutDir();
  const std::string cube = Quote(SourcePath("examples/section-8.5-cube-struck.yaml"));
  const CliResult us = RunCli("simulate " + cube + " --out " + Quote(dir.string()));
  ASSERT_EQ(us.exit_code, 0) << us.err;
  EXPECT_THAT(us.out, ::testing::HasSubstr("lbf*in"));
  EXPECT_THAT(us.out, ::testing::HasSubstr("in/s"));
  const CliResult si = RunCli("simulate " + cube + " --out " + Quote(dir.string()) + " --units SI");
  EXPECT_THAT(si.out, ::testing::HasSubstr(" J "));
  const CliResult bad =
      RunCli("simulate " + cube + " --out " + Quote(dir.string()) + " --units furlong");
  EXPECT_EQ(bad.exit_code, 2);
}

TEST(SimulateCli, HelpAndErrors) {
  const CliResult help = RunCli("simulate --help");
  EXPECT_EQ(help.exit_code, 0);
  EXPECT_THAT(help.out, ::testing::HasSubstr("--until"));
  EXPECT_THAT(help.out, ::testing::HasSubstr("chasles simulate examples/"));
  // A scene without an end time.
  const CliResult none = RunCli("simulate '" + SourcePath("examples/section-8.5-cube.yaml") +
                                "' --out '" + OutDir().string() + "'");
  EXPECT_EQ(none.exit_code, 2);
  EXPECT_THAT(none.err, ::testing::HasSubstr("no end time"));
  const CliResult bad = RunCli("simulate '" + SourcePath("examples/spring-mass.yaml") +
                               "' --until -1 --out '" + OutDir().string() + "'");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_THAT(bad.err, ::testing::HasSubstr("--until must be a positive time"));
}

// A force that has no value below z = 0 (the square root of a negative number) on a fixed-step
// integrator: the run stops at the first NaN with the force named at its expression (line 7,
// column 39: the value) and writes no output.
TEST(SimulateCli, DivergingRunStopsWithTheForceNamed) {
  const auto dir = OutDir();
  const auto scene = dir / "diverge.yaml";
  std::ofstream(scene) << "bodies:\n"
                          "  - name: probe\n"
                          "    parts: [{shape: sphere, radius: 1 cm, mass: 1 kg}]\n"
                          "    initial: {position: [0, 0, 1 m], velocity: [0, 0, -1 m/s]}\n"
                          "gravity: standard\n"
                          "forces:\n"
                          "  - {type: force, body: probe, value: [0, 0, sqrt(probe_z / m) * 1 N]}\n"
                          "simulation: {until: 3 s, integrator: rk4, step: 0.25 s}\n";
  const CliResult r = RunCli("simulate '" + scene.string() + "' --out '" + dir.string() + "'");
  EXPECT_EQ(r.exit_code, 2) << r.out;
  EXPECT_THAT(r.err, ::testing::HasSubstr(scene.string() +
                                          ":7:39: forces[0].value: the "
                                          "expression of force element 'force 1' produced a "
                                          "non-finite value"));
  EXPECT_THAT(r.err, ::testing::HasSubstr("force element 'force 1' evaluated to NaN at t = "));
  EXPECT_FALSE(std::filesystem::exists(dir / "diverge.csv"));
}

// One free box, thrown and spinning, under standard gravity alone.
constexpr const char* kSpinningBoxUnderGravity =
    "bodies:\n"
    "  - name: box\n"
    "    parts: [{shape: box, size: [0.1 m, 0.2 m, 0.3 m], mass: 1 kg}]\n"
    "    initial: {velocity: [1 m/s, 0, 5 m/s], angular_velocity: [1, 7, 0.5]}\n"
    "gravity: standard\n";

// A scene of free bodies under gravity alone stepped by rk4 takes the free-body batch and the
// report says so; a force other than gravity sends it down the general path, without the note.
TEST(SimulateCli, Rk4OnFreeBodiesUnderGravityNamesTheFreeBodyBatch) {
  const auto dir = OutDir();
  const std::string bodies = kSpinningBoxUnderGravity;
  const std::string sim = "simulation: {until: 1 s, integrator: rk4, step: 1 ms}\n";
  const std::string note = "stepped by the free-body batch";
  const auto free = dir / "free.yaml";
  std::ofstream(free) << bodies << sim;
  const CliResult a = RunCli("simulate '" + free.string() + "' --out '" + dir.string() + "'");
  EXPECT_EQ(a.exit_code, 0) << a.err;
  EXPECT_THAT(a.out, ::testing::HasSubstr(note));
  const auto pushed = dir / "pushed.yaml";
  std::ofstream(pushed) << bodies << "forces:\n  - {type: force, body: box, value: [0, 1 N, 0]}\n"
                        << sim;
  const CliResult b = RunCli("simulate '" + pushed.string() + "' --out '" + dir.string() + "'");
  EXPECT_EQ(b.exit_code, 0) << b.err;
  EXPECT_THAT(b.out, ::testing::Not(::testing::HasSubstr(note)));
}

// The JSON summary names the run path (ChooseRunPath, docs/contact.md "Run paths") of each
// kind of scene: a free body (smooth), a ball bouncing on a floor (auto, the default for a
// scene with contacts; hybrid under integrator: adaptive, one body, one island), balls on a
// table (event-driven spheres), a box held on a slope time stepped, the tumbling cube under
// integrator: auto, and free bodies under gravity stepped by rk4 (free-body batch); the text
// report has the same line.
TEST(SimulateCli, TheSummaryNamesTheRunPath) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"examples/dzhanibekov.yaml", "smooth"},
      {"examples/contact-bouncing-ball.yaml", "auto"},
      {"examples/pool-head-on-events.yaml", "event-driven spheres"},
      {"examples/contact-box-held-on-slope.yaml", "time stepping"},
      {"examples/contact-cube-tumbles-auto.yaml", "auto"}};
  for (const auto& [example, path] : cases) {
    const nlohmann::json j = Simulate(example);
    EXPECT_EQ(j.at("run_path").at("path"), path) << example;
    EXPECT_FALSE(j.at("run_path").at("reason").get<std::string>().empty()) << example;
  }
  const auto dir = OutDir();
  const auto free = dir / "run-path-free.yaml";
  std::ofstream(free) << kSpinningBoxUnderGravity
                      << "simulation: {until: 0.1 s, integrator: rk4, step: 1 ms}\n";
  const nlohmann::json j = SimulateJson(free.string(), dir);
  EXPECT_EQ(j.at("run_path").at("path"), "free-body batch");
  EXPECT_THAT(j.at("run_path").at("reason").get<std::string>(),
              ::testing::HasSubstr("free bodies under uniform gravity alone"));
  const CliResult text = RunCli("simulate '" + free.string() + "' --out '" + dir.string() + "'");
  EXPECT_THAT(text.out, ::testing::HasSubstr("Run path: free-body batch: free bodies under "
                                             "uniform gravity alone, stepped by RK4"));
  // The bouncing ball under integrator: adaptive: the hybrid path, one body, one island.
  std::ifstream in(SourcePath("examples/contact-bouncing-ball.yaml"));
  std::string ball((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ball.replace(ball.find("\nsimulation:\n"), 13, "\nsimulation:\n  integrator: adaptive\n");
  std::ofstream(dir / "run-path-ball.yaml") << ball;
  const nlohmann::json h = SimulateJson((dir / "run-path-ball.yaml").string(), dir);
  EXPECT_EQ(h.at("run_path").at("path"), "hybrid");
  EXPECT_THAT(h.at("run_path").at("reason").get<std::string>(),
              ::testing::HasSubstr("the bodies form one island"));
}

// `integrator: splitting` runs the batch's symplectic splitting and says so; a scene it cannot
// step is refused with exit 2, naming what does not qualify, and writes nothing.
TEST(SimulateCli, SplittingIntegratorRunsFreeBodiesAndRefusesOtherScenes) {
  const auto dir = OutDir();
  const std::string bodies = kSpinningBoxUnderGravity;
  const std::string sim = "simulation: {until: 1 s, integrator: splitting, step: 1 ms}\n";
  const auto free = dir / "split.yaml";
  std::ofstream(free) << bodies << sim;
  const CliResult a = RunCli("simulate '" + free.string() + "' --out '" + dir.string() + "'");
  EXPECT_EQ(a.exit_code, 0) << a.err;
  EXPECT_THAT(a.out, ::testing::HasSubstr("Integrator: symplectic splitting (fixed step, free "
                                          "bodies): 1000 steps"));
  EXPECT_THAT(a.out, ::testing::Not(::testing::HasSubstr("the same RK4")));
  const auto pushed = dir / "split-pushed.yaml";
  std::ofstream(pushed) << bodies << "forces:\n  - {type: force, body: box, value: [0, 1 N, 0]}\n"
                        << sim;
  const CliResult b = RunCli("simulate '" + pushed.string() + "' --out '" + dir.string() + "'");
  EXPECT_EQ(b.exit_code, 2);
  EXPECT_THAT(b.err, ::testing::HasSubstr(pushed.string() + ":7:5: forces[0]: "));
  EXPECT_THAT(b.err, ::testing::HasSubstr("the splitting integrator steps free bodies under "
                                          "uniform gravity only, and force element 'force 1' is "
                                          "not uniform gravity"));
  EXPECT_FALSE(std::filesystem::exists(dir / "split-pushed.csv"));
}

}  // namespace
}  // namespace chasles::test
