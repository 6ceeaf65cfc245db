// End-to-end: scenes with joints, rolling contacts and drivers run through `chasles simulate`,
// against closed forms derived in the tests (and in the examples' comments). The examples use
// integrator tolerance 1e-12; the answers below are met to 1e-7 relative or better.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "chasles/math/types.h"
#include "cli_runner.h"

namespace chasles::test {
namespace {

// A run at tolerance 1e-12 over a few hundred steps, with the constraint projection.
constexpr double kRun = 1e-7;
constexpr double kStandardGravity = 9.80665;
constexpr double kPi = 3.14159265358979323846;

std::filesystem::path OutDir() {
  return test::OutDir("joints");
}

nlohmann::json Simulate(const std::string& example, const std::string& extra = "") {
  return SimulateJson(SourcePath(example), OutDir(), extra);
}

const nlohmann::json& Named(const nlohmann::json& list, const std::string& name) {
  for (const auto& x : list) {
    if (x.at("name") == name) return x;
  }
  throw std::runtime_error("nothing named " + name);
}

double At(const nlohmann::json& v, size_t i) {
  return v.at(i).get<double>();
}

// A ratio as the report prints it (6 significant digits).
std::string RatioText(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "f/N = %.6g", v);
  return buf;
}

// Example 8.6: from rest down a height h, v / sqrt(2 g h) = 1 / sqrt(1 + k²/R²) (energy with
// no work at the rolling contact), k the radius of gyration about the centre.
TEST(Joints, Example86RollingDownAnInclineReachesTheEnergySpeed) {
  const auto j = Simulate("examples/example-8.6-rolling-race.yaml");
  const double g = kStandardGravity, theta = kPi / 6, R = 0.1;
  const struct {
    const char* body;
    double k2_over_R2;  // sphere 2/5, solid cylinder 1/2, hoop 1
  } cases[] = {{"sphere", 0.4}, {"cylinder", 0.5}, {"hoop", 1.0}};
  for (const auto& c : cases) {
    const auto& b = Named(j.at("final").at("bodies"), c.body);
    // Started with the centre at R n, n = (sin θ, 0, cos θ).
    const double h = R * std::cos(theta) - At(b.at("center_of_mass"), 2);
    const Vec3 v(At(b.at("velocity"), 0), At(b.at("velocity"), 1), At(b.at("velocity"), 2));
    ASSERT_GT(h, 0.5) << c.body;
    const double expected = 1.0 / std::sqrt(1.0 + c.k2_over_R2);
    EXPECT_NEAR(v.norm() / std::sqrt(2 * g * h), expected, kRun * expected) << c.body;
    // Rolling: w = v / R about the cross-slope axis y.
    EXPECT_NEAR(At(b.at("angular_velocity"), 1), v.norm() / R, kRun * v.norm() / R) << c.body;
  }
  EXPECT_NEAR(1.0 / std::sqrt(1.4), std::sqrt(5.0 / 7.0), 1e-15);  // the sphere's sqrt(5/7)

  // The plane's reaction: N = m g cos θ along n, friction m g sin θ (k²/R²)/(1 + k²/R²) up
  // the slope u = (-cos θ, 0, sin θ); for the sphere f/N = (2/7) tan θ.
  const Vec3 n(std::sin(theta), 0, std::cos(theta)), u(-std::cos(theta), 0, std::sin(theta));
  const double m = 1.0;
  for (const auto& c : cases) {
    const auto& r = Named(j.at("final").at("reactions"), std::string(c.body) + "_contact");
    const Vec3 F(At(r.at("force"), 0), At(r.at("force"), 1), At(r.at("force"), 2));
    const double N = m * g * std::cos(theta);
    const double f = m * g * std::sin(theta) * c.k2_over_R2 / (1 + c.k2_over_R2);
    EXPECT_NEAR(F.dot(n), N, kRun * N) << c.body;
    EXPECT_NEAR(F.dot(u), f, kRun * N) << c.body;
    EXPECT_NEAR(F.y(), 0.0, kRun * N) << c.body;
  }
  // Rolling contacts do no work: the ledger balances with zero constraint work.
  for (const auto& [name, w] : j.at("ledger").at("work_by_constraint").items()) {
    EXPECT_NEAR(w.get<double>(), 0.0, 1e-9) << name;
  }
  EXPECT_LT(std::abs(j.at("ledger").at("relative_residual").get<double>()), 1e-9);
}

// Slender rod pinned at one end, released from horizontal: I_O = m L²/3, so
// α = m g (L/2) / I_O = 3 g / (2 L) and the pin pushes up with m g - m α L/2 = m g / 4; at the
// bottom w² = 3 g / L and the pin pulls up with m g + m w² L/2 = 5 m g / 2.
TEST(Joints, PinnedRodReleasedFromHorizontal) {
  const auto j = Simulate("examples/pinned-rod.yaml");
  const double g = kStandardGravity, m = 2.0, L = 1.0;
  const auto csv = ReadCsv(j.at("csv").get<std::string>());
  // At release (the first row).
  EXPECT_NEAR(csv.at("rod_aly").front(), 3 * g / (2 * L), kRun * g);
  EXPECT_NEAR(csv.at("pin_Fz").front(), m * g / 4, kRun * m * g);
  EXPECT_NEAR(csv.at("pin_Fx").front(), 0.0, kRun * m * g);
  // Along the swing (angle β below horizontal from the centre's position): the pin force,
  // from m a_cm = F + m g with α = (3g/2L) cos β and w² = (3g/L) sin β:
  //   radial (towards the pin) F_r = m w² L/2 + m g sin β = (5/2) m g sin β,
  //   tangential F_t = m g cos β - m α L/2 = m g cos β / 4.
  for (size_t i = 0; i < csv.at("t").size(); ++i) {
    const double x = csv.at("rod_x")[i], z = csv.at("rod_z")[i];
    const double beta = std::atan2(-z, x);
    const Vec3 e_r(-x, 0, -z);  // from the centre towards the pin
    const Vec3 r_hat = e_r.normalized();
    const Vec3 t_hat(std::sin(beta), 0, std::cos(beta));  // perpendicular, upward at release
    const Vec3 F(csv.at("pin_Fx")[i], csv.at("pin_Fy")[i], csv.at("pin_Fz")[i]);
    EXPECT_NEAR(F.dot(r_hat), 2.5 * m * g * std::sin(beta), kRun * m * g)
        << "t = " << csv.at("t")[i];
    EXPECT_NEAR(F.dot(t_hat), m * g * std::cos(beta) / 4, kRun * m * g) << "t = " << csv.at("t")[i];
  }
  // The run stops at the bottom.
  ASSERT_EQ(j.at("events").size(), 1u);
  const auto& r = Named(j.at("final").at("reactions"), "pin");
  EXPECT_EQ(r.at("kind"), "revolute");
  EXPECT_NEAR(At(r.at("force"), 2), 2.5 * m * g, kRun * m * g);
  EXPECT_NEAR(At(r.at("force"), 0), 0.0, kRun * m * g);
  const auto& b = Named(j.at("final").at("bodies"), "rod");
  EXPECT_NEAR(At(b.at("angular_velocity"), 1), std::sqrt(3 * g / L), kRun * std::sqrt(g / L));
}

// Example 8.4: ladder on a frictionless wall and floor, released from rest at φ0 = 30° from the
// vertical. N_A = (3/4) m g sin φ (3 cos φ - 2 cos φ0), N_B = m g (1 - (3/4)(1 - 3 cos² φ +
// 2 cos φ cos φ0)); the ladder leaves the wall (N_A = 0) at cos φ = (2/3) cos φ0.
TEST(Joints, Example84LadderLeavesTheWallWhereNormalForceVanishes) {
  const auto j = Simulate("examples/example-8.4-sliding-ladder.yaml");
  const double g = kStandardGravity, m = 10.0, phi0 = kPi / 6;
  const double c0 = std::cos(phi0);
  const double phi_leave = std::acos(2.0 / 3.0 * c0);
  EXPECT_NEAR(phi_leave * 180 / kPi, 54.7356103172453, 1e-9);
  const auto csv = ReadCsv(j.at("csv").get<std::string>());
  ASSERT_GT(csv.at("t").size(), 20u);
  for (size_t i = 0; i < csv.at("t").size(); ++i) {
    const double phi = csv.at("ladder_tilt")[i];
    const double NA = 0.75 * m * g * std::sin(phi) * (3 * std::cos(phi) - 2 * c0);
    const double NB =
        m * g * (1 - 0.75 * (1 - 3 * std::cos(phi) * std::cos(phi) + 2 * std::cos(phi) * c0));
    EXPECT_NEAR(csv.at("wall_Fx")[i], NA, kRun * m * g) << "t = " << csv.at("t")[i];
    EXPECT_NEAR(csv.at("floor_Fz")[i], NB, kRun * m * g) << "t = " << csv.at("t")[i];
    EXPECT_NEAR(csv.at("wall_Fz")[i], 0.0, kRun * m * g);  // frictionless
    EXPECT_NEAR(csv.at("floor_Fx")[i], 0.0, kRun * m * g);
  }
  // The event on the wall's reaction (wall_Fx crossing zero) stops the run at φ_leave, where
  // N_B = m g / 4.
  ASSERT_EQ(j.at("events").size(), 1u);
  EXPECT_TRUE(j.at("stopped_by_event").get<bool>());
  EXPECT_EQ(j.at("events")[0].at("name"), "leaves wall");
  const auto& q = Named(j.at("final").at("bodies"), "ladder").at("quaternion");
  // q = (cos(-φ/2), 0, sin(-φ/2), 0) up to sign: φ = 2 acos(|qw|).
  EXPECT_NEAR(2 * std::acos(std::abs(At(q, 0))), phi_leave, kRun);
  const auto& wall = Named(j.at("final").at("reactions"), "wall");
  const auto& floor = Named(j.at("final").at("reactions"), "floor");
  EXPECT_NEAR(At(wall.at("force"), 0), 0.0, kRun * m * g);
  EXPECT_NEAR(At(floor.at("force"), 2), m * g / 4, kRun * m * g);
  // Frictionless supports do no work.
  EXPECT_NEAR(j.at("ledger").at("work_by_constraint").at("wall").get<double>(), 0.0, 1e-9);
  EXPECT_NEAR(j.at("ledger").at("work_by_constraint").at("floor").get<double>(), 0.0, 1e-9);
}

// A driver's work is the energy it supplies: a block lifted by a translation driver at
// constant acceleration a from rest: after t, W = m (g + a) (a t²/2) and the driver force is
// m (g + a) (chapter 8.2: Newton's second law along the driven axis).
TEST(Joints, TranslationDriverSuppliesForceAndWork) {
  const auto dir = OutDir();
  const auto scene = dir / "lift.yaml";
  {
    std::ofstream out(scene);
    out << "bodies:\n"
           "  - name: block\n"
           "    parts: [{shape: box, size: [0.1 m, 0.1 m, 0.1 m], mass: 3 kg}]\n"
           "gravity: standard\n"
           "drivers:\n"
           "  - {name: lift, type: translation, parent: world, child: block, at: [0, 0, 0],\n"
           "     axis: [0, 0, 1], value: {position: 0 m, velocity: 0 m/s, acceleration: 2 "
           "m/s^2}}\n"
           "simulation: {until: 1.5 s, tolerance: 1e-12}\n"
           "output: {columns: [position, reactions, work]}\n";
  }
  const CliResult r =
      RunCli("simulate " + Quote(scene.string()) + " --format json --out " + Quote(dir.string()));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  const double m = 3.0, g = kStandardGravity, a = 2.0, t = 1.5;
  const auto& b = Named(j.at("final").at("bodies"), "block");
  EXPECT_NEAR(At(b.at("center_of_mass"), 2), a * t * t / 2, kRun);
  const auto& lift = Named(j.at("final").at("reactions"), "lift");
  EXPECT_NEAR(At(lift.at("force"), 2), m * (g + a), kRun * m * g);
  const double W = m * (g + a) * a * t * t / 2;
  EXPECT_NEAR(j.at("ledger").at("work_by_constraint").at("lift").get<double>(), W, kRun * W);
  EXPECT_LT(std::abs(j.at("ledger").at("relative_residual").get<double>()), 1e-9);
}

// A rotation driver spins a disk (I = m R²/2 about its axis) on a revolute joint at constant
// angular acceleration α from rest: it supplies the moment I α, and its work after t is the
// kinetic energy I (α t)² / 2 (eq. 8.116 with the work-energy principle).
TEST(Joints, RotationDriverSuppliesMomentAndWork) {
  const auto dir = OutDir();
  const auto scene = dir / "spin.yaml";
  {
    std::ofstream out(scene);
    out << "bodies:\n"
           "  - name: disk\n"
           "    parts: [{shape: disk, radius: 0.2 m, mass: 4 kg}]\n"
           "joints:\n"
           "  - {name: axle, type: revolute, parent: world, child: disk, at: [0, 0, 0],\n"
           "     axis: [0, 0, 1]}\n"
           "drivers:\n"
           "  - {name: motor, type: rotation, parent: world, child: disk, at: [0, 0, 0],\n"
           "     axis: [0, 0, 1], value: {acceleration: 3 rad/s^2}}\n"
           "simulation: {until: 2 s, tolerance: 1e-12}\n";
  }
  const CliResult r =
      RunCli("simulate " + Quote(scene.string()) + " --format json --out " + Quote(dir.string()));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  const double m = 4.0, R = 0.2, alpha = 3.0, t = 2.0;
  const double I = m * R * R / 2;
  const auto& motor = Named(j.at("final").at("reactions"), "motor");
  EXPECT_NEAR(At(motor.at("moment"), 2), I * alpha, kRun * I * alpha);
  const auto& b = Named(j.at("final").at("bodies"), "disk");
  EXPECT_NEAR(At(b.at("angular_velocity"), 2), alpha * t, kRun * alpha * t);
  const double W = I * (alpha * t) * (alpha * t) / 2;
  EXPECT_NEAR(j.at("ledger").at("work_by_constraint").at("motor").get<double>(), W, kRun * W);
  EXPECT_NEAR(j.at("ledger").at("work_by_constraint").at("axle").get<double>(), 0.0, kRun * W);
}

// An impulse J across the free end of a pinned rod at rest (no gravity): the pin's impulsive
// reaction leaves the rod turning about the pin with I_O w = L J, I_O = m L²/3 (angular
// impulse-momentum about the pin, chapter 8.5), so w = 3 J / (m L) and the kinetic energy
// jumps by I_O w² / 2 = 3 J² / (2 m).
TEST(Joints, ImpulseOnAPinnedRodTurnsItAboutThePin) {
  const auto dir = OutDir();
  const auto scene = dir / "struck-rod.yaml";
  {
    std::ofstream out(scene);
    out << "bodies:\n"
           "  - name: rod\n"
           "    parts:\n"
           "      - {shape: custom, mass: 2 kg, center_of_mass: [0.5 m, 0, 0],\n"
           "         inertia: {Ixx: 1e-4 kg*m^2, Iyy: 2 kg*(1 m)^2/12, Izz: 2 kg*(1 m)^2/12}}\n"
           "joints:\n"
           "  - {name: pin, type: revolute, parent: world, child: rod, at: [0, 0, 0],\n"
           "     axis: [0, 1, 0]}\n"
           "impulses:\n"
           "  - {time: 0.1 s, body: rod, point: [1 m, 0, 0], value: [0, 0, 0.5 N*s]}\n"
           "simulation: {until: 0.3 s, tolerance: 1e-12}\n";
  }
  const CliResult r =
      RunCli("simulate " + Quote(scene.string()) + " --format json --out " + Quote(dir.string()));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  const double m = 2.0, L = 1.0, J = 0.5;
  const double w = 3 * J / (m * L);
  ASSERT_EQ(j.at("jumps").size(), 1u);
  const double dE = j.at("jumps")[0].at("energy_change").get<double>();
  EXPECT_NEAR(dE, 3 * J * J / (2 * m), 1e-12);
  const auto& b = Named(j.at("final").at("bodies"), "rod");
  // r × J about the pin is along -y.
  EXPECT_NEAR(At(b.at("angular_velocity"), 1), -w, kRun * w);
  EXPECT_NEAR(std::hypot(At(b.at("velocity"), 0), At(b.at("velocity"), 2)), w * L / 2,
              kRun * w * L);
}

// The simulation holds rolling whatever friction it takes, and says when more than mu_s N was
// needed: for the cylinder of Example 8.3, f/N = tan θ / 3, under mu_s = 0.25 at 30° and over
// it at 40° (0.27970).
TEST(Joints, SimulateSaysWhenRollingNeedsMoreFrictionThanMuS) {
  const auto ok = Simulate("examples/example-8.3-cylinder-incline.yaml");
  EXPECT_TRUE(ok.at("notes").empty()) << ok.at("notes").dump();
  const auto steep = Simulate("examples/example-8.3-cylinder-incline.yaml", "--set 'theta=40 deg'");
  ASSERT_EQ(steep.at("notes").size(), 1u);
  const std::string note = steep.at("notes")[0].get<std::string>();
  EXPECT_THAT(note, ::testing::HasSubstr("would slip"));
  EXPECT_THAT(note, ::testing::HasSubstr(RatioText(std::tan(40 * kPi / 180) / 3)));
}

TEST(Joints, ReactionColumnsAreNamedByConstraint) {
  const auto j = Simulate("examples/pinned-rod.yaml");
  std::ifstream in(j.at("csv").get<std::string>());
  std::string header;
  std::getline(in, header);
  EXPECT_THAT(header,
              ::testing::HasSubstr(
                  "pin_Fx [N],pin_Fy [N],pin_Fz [N],pin_Mx [N*m],pin_My [N*m],pin_Mz [N*m]"));
  EXPECT_THAT(header, ::testing::HasSubstr("W_pin"));
}

// Example 8.3: a solid cylinder rolling down an incline at θ = 30°: a = (2/3) g sin θ,
// friction f = m g sin θ / 3, N = m g cos θ, so rolling needs f/N = tan θ / 3 = 0.19245.
TEST(Solve, Example83CylinderOnAnInclineNeedsTanThetaOverThreeFriction) {
  const CliResult r =
      RunCli("solve " + Quote(SourcePath("examples/example-8.3-cylinder-incline.yaml")) +
             " --format json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  const double g = kStandardGravity, m = 5.0, theta = kPi / 6;
  constexpr double kSolve = 1e-9;  // one linear solve: round-off only
  const auto& c = Named(j.at("reactions"), "contact");
  EXPECT_NEAR(c.at("friction_needed").get<double>(), std::tan(theta) / 3,
              kSolve * std::tan(theta) / 3);
  EXPECT_NEAR(c.at("friction_needed").get<double>(), 0.19245008972987526, kSolve);
  EXPECT_NEAR(c.at("friction_magnitude").get<double>(), m * g * std::sin(theta) / 3,
              kSolve * m * g);
  EXPECT_NEAR(c.at("normal_force").get<double>(), m * g * std::cos(theta), kSolve * m * g);
  EXPECT_EQ(c.at("mu_s").get<double>(), 0.25);
  EXPECT_TRUE(c.at("rolls").get<bool>());
  const auto& b = Named(j.at("bodies"), "cylinder");
  const Vec3 a(At(b.at("acceleration"), 0), At(b.at("acceleration"), 1),
               At(b.at("acceleration"), 2));
  EXPECT_NEAR(a.norm(), 2.0 / 3.0 * g * std::sin(theta), kSolve * g);
  // Along the slope, down: (cos θ, 0, -sin θ).
  EXPECT_NEAR(a.x() * std::cos(theta) - a.z() * std::sin(theta), 2.0 / 3.0 * g * std::sin(theta),
              kSolve * g);
}

TEST(Solve, SweepTabulatesOverAParameterRange) {
  const CliResult r =
      RunCli("solve " + Quote(SourcePath("examples/example-8.3-cylinder-incline.yaml")) +
             " --sweep 'theta=10 deg:50 deg:5' --format json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  const auto& cols = j.at("columns");
  size_t ratio = cols.size();
  for (size_t i = 0; i < cols.size(); ++i) {
    if (cols[i] == "contact_f_over_N") ratio = i;
  }
  ASSERT_LT(ratio, cols.size());
  ASSERT_EQ(j.at("rows").size(), 5u);
  for (size_t k = 0; k < 5; ++k) {
    const auto& row = j.at("rows")[k];
    const double theta = (10.0 + 10.0 * static_cast<double>(k)) * kPi / 180;
    EXPECT_NEAR(At(row, 0), theta, 1e-15);
    EXPECT_NEAR(At(row, ratio), std::tan(theta) / 3, 1e-9);
  }
  // The text table has a header (names with their SI units, a pure number bare) and one line
  // per value.
  const CliResult t =
      RunCli("solve " + Quote(SourcePath("examples/example-8.3-cylinder-incline.yaml")) +
             " --sweep 'theta=10 deg:50 deg:5'");
  ASSERT_EQ(t.exit_code, 0) << t.err;
  EXPECT_THAT(t.out, ::testing::HasSubstr("theta [rad],cylinder_ax [m/s^2]"));
  EXPECT_EQ(std::count(t.out.begin(), t.out.end(), '\n'), 6);
}

TEST(Solve, BadSweepIsAClearError) {
  const CliResult r =
      RunCli("solve " + Quote(SourcePath("examples/example-8.3-cylinder-incline.yaml")) +
             " --sweep 'theta=10 deg:50 deg'");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, ::testing::HasSubstr("NAME=START:STOP:COUNT"));
  const CliResult u =
      RunCli("solve " + Quote(SourcePath("examples/example-8.3-cylinder-incline.yaml")) +
             " --sweep 'thetta=10 deg:50 deg:3'");
  EXPECT_EQ(u.exit_code, 2);
  EXPECT_THAT(u.err, ::testing::HasSubstr("thetta"));
}

}  // namespace
}  // namespace chasles::test
