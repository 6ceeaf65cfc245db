// End-to-end: planar scenes (`planar: true`, chapter 8.2 eqs. 8.34-8.43) run through
// `chasles solve` and `chasles simulate`, against the 3-D scene of the same problem and against
// closed forms derived here.
//
// The 3-D examples move in the x-z plane (gravity -z, hinge axis y); the planar ones in the
// x-y plane (gravity -y, rotation about z). The proper rotation that takes the first onto the
// second maps x -> x, z -> y, y -> -z, so a 3-D angular quantity about +y is the planar one
// about -z: omega = -w_y, alpha = -alpha_y, Mz = -M_y, while Fx = F_x and Fy = F_z.

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "cli_runner.h"
#include "test_support.h"

namespace chasles::test {
namespace {

// The two scenes are different constraint sets, so their solves round differently: the
// instantaneous answers agree to 1e-9 of their scale, the runs (tolerance 1e-12, a few hundred
// steps, event located to 1e-10 s) to 1e-7.
constexpr double kSolve = 1e-9;
constexpr double kRun = 1e-7;
constexpr double kStandardGravity = 9.80665;
constexpr double kPi = 3.14159265358979323846;

std::filesystem::path OutDir() {
  return test::OutDir("planar");
}

nlohmann::json Solve(const std::string& scene) {
  const CliResult r = RunCli("solve " + Quote(scene) + " --format json");
  if (r.exit_code != 0) throw std::runtime_error("chasles solve " + scene + ": " + r.err);
  return nlohmann::json::parse(r.out);
}

using Columns = std::map<std::string, std::vector<double>>;

Columns Simulate(const std::string& scene, const std::string& columns) {
  const CliResult r = RunCli("simulate " + Quote(scene) + " --format json --out " +
                             Quote(OutDir().string()) + " --columns " + columns);
  if (r.exit_code != 0) throw std::runtime_error("chasles simulate " + scene + ": " + r.err);
  const std::string stem = std::filesystem::path(scene).stem().string();
  return ReadCsv((OutDir() / (stem + ".csv")).string());
}

std::string Planar(const std::string& name) {
  return SourcePath("examples/" + name);
}

// --- pinned rod ------------------------------------------------------------------------------
// m = 2 kg, L = 1 m, pinned at one end, released horizontal. I_O = m L^2/3 (eq. 8.39), so
// alpha = -(m g L/2) cos(theta) / I_O = -3 g cos(theta) / (2 L) and, from energy,
// omega^2 = -3 g sin(theta) / L. At release a_cm = (0, -3g/4), F = (0, m g/4).
// The centre of mass moves on the circle: a_n = omega^2 L/2 towards the pin, a_t = alpha L/2,
// so the pin force is F = m a_cm - m g: at the bottom (theta = -pi/2) F_y = m g + m omega^2 L/2
// = 5 m g / 2.
constexpr double kRodMass = 2.0, kRodLength = 1.0;

TEST(Planar, PinnedRodSolveEqualsThreeDAndClosedForm) {
  const auto p = Solve(Planar("pinned-rod-planar.yaml"));
  const auto s = Solve(SourcePath("examples/pinned-rod.yaml"));
  ASSERT_TRUE(p.at("planar").get<bool>());
  const auto& pb = p.at("bodies").at(0).at("planar");
  const Eigen::Vector3d a3 = ToVec(s.at("bodies").at(0).at("acceleration"));
  const Eigen::Vector3d al3 = ToVec(s.at("bodies").at(0).at("angular_acceleration"));
  const double g = kStandardGravity, L = kRodLength, m = kRodMass;
  const double a_scale = g, F_scale = m * g;
  EXPECT_NEAR(pb.at("a_x").get<double>(), a3.x(), kSolve * a_scale);
  EXPECT_NEAR(pb.at("a_y").get<double>(), a3.z(), kSolve * a_scale);
  EXPECT_NEAR(pb.at("alpha").get<double>(), -al3.y(), kSolve * a_scale / L);
  const auto& pr = p.at("reactions").at(0).at("planar");
  const Eigen::Vector3d F3 = ToVec(s.at("reactions").at(0).at("force"));
  const Eigen::Vector3d M3 = ToVec(s.at("reactions").at(0).at("moment"));
  EXPECT_NEAR(pr.at("Fx").get<double>(), F3.x(), kSolve * F_scale);
  EXPECT_NEAR(pr.at("Fy").get<double>(), F3.z(), kSolve * F_scale);
  EXPECT_NEAR(pr.at("Mz").get<double>(), -M3.y(), kSolve * F_scale * L);
  // Closed forms at release (theta = 0).
  EXPECT_NEAR(pb.at("alpha").get<double>(), -3.0 * g / (2.0 * L), kSolve * g / L);
  EXPECT_NEAR(pb.at("a_x").get<double>(), 0.0, kSolve * g);
  EXPECT_NEAR(pb.at("a_y").get<double>(), -0.75 * g, kSolve * g);
  EXPECT_NEAR(pr.at("Fx").get<double>(), 0.0, kSolve * F_scale);
  EXPECT_NEAR(pr.at("Fy").get<double>(), m * g / 4.0, kSolve * F_scale);
  EXPECT_NEAR(pr.at("Mz").get<double>(), 0.0, kSolve * F_scale * L);
  // The plane constraints add no redundant row (rank = rows) and so no warning; the pin
  // reports only its own reaction.
  EXPECT_EQ(p.at("rank").get<int>(), p.at("rows").get<int>());
  EXPECT_TRUE(p.at("warnings").empty()) << p.at("warnings");
  EXPECT_EQ(p.at("reactions").size(), 1u);
  EXPECT_EQ(p.at("reactions").at(0).at("kind"), "planar revolute");
}

// A plane motion's momenta: P in the plane and H about z (eqs. 8.34-8.38). The ledger gives
// those; the zero components are there only when asked by name (momentum_3d). About the pin
// O, H_O = I_O omega with I_O = m L^2/3 (eq. 8.39); P = m v_cm.
TEST(Planar, LedgerMomentaAreThoseOfAPlaneMotion) {
  const Columns p = Simulate(Planar("pinned-rod-planar.yaml"), "planar,ledger");
  for (const char* absent : {"Pz", "Hx", "Hy", "HOx", "HOy"})
    EXPECT_EQ(p.count(absent), 0u) << absent;
  const double m = 2.0, L = 1.0;
  for (size_t i = 0; i < p.at("t").size(); ++i) {
    const double w = p.at("rod_omega")[i];
    EXPECT_TRUE(Near(p.at("HOz")[i], m * L * L / 3 * w, 1e-9)) << i;
    EXPECT_TRUE(Near(p.at("Px")[i], m * p.at("rod_vx")[i], 1e-12)) << i;
    EXPECT_TRUE(Near(p.at("Py")[i], m * p.at("rod_vy")[i], 1e-12)) << i;
  }
  const Columns all = Simulate(Planar("pinned-rod-planar.yaml"), "momentum_3d");
  for (const char* name : {"Pz", "Hx", "Hy", "HOx", "HOy"}) {
    for (double v : all.at(name)) EXPECT_EQ(v, 0.0) << name;
  }
}

TEST(Planar, PinnedRodSimulateEqualsThreeDAndClosedForm) {
  const Columns p = Simulate(Planar("pinned-rod-planar.yaml"), "planar,reactions");
  const Columns s = Simulate(SourcePath("examples/pinned-rod.yaml"),
                             "position,angular_velocity,angular_acceleration,reactions");
  ASSERT_GE(p.at("t").size(), 40u);
  ExpectSameColumn(p.at("t"), s.at("t"), 1.0, kRun, "t");
  ExpectSameColumn(p.at("rod_x"), s.at("rod_x"), 1.0, kRun, "x");
  ExpectSameColumn(p.at("rod_y"), s.at("rod_z"), 1.0, kRun, "y");
  ExpectSameColumn(p.at("rod_omega"), s.at("rod_wy"), -1.0, kRun, "omega");
  ExpectSameColumn(p.at("rod_alpha"), s.at("rod_aly"), -1.0, kRun, "alpha");
  ExpectSameColumn(p.at("pin_Fx"), s.at("pin_Fx"), 1.0, kRun, "Fx");
  ExpectSameColumn(p.at("pin_Fy"), s.at("pin_Fz"), 1.0, kRun, "Fy");
  ExpectSameColumn(p.at("pin_Mz"), s.at("pin_My"), -1.0, kRun, "Mz");
  // Planar columns only: no z, no 3-D reaction components by default.
  EXPECT_EQ(p.count("rod_z"), 0u);
  EXPECT_EQ(p.count("pin_Fz"), 0u);

  const double g = kStandardGravity, L = kRodLength, m = kRodMass;
  const auto& th = p.at("rod_theta");
  for (size_t i = 0; i < th.size(); ++i) {
    SCOPED_TRACE("row " + std::to_string(i));
    EXPECT_NEAR(p.at("rod_x")[i], 0.5 * L * std::cos(th[i]), kRun * L);
    EXPECT_NEAR(p.at("rod_y")[i], 0.5 * L * std::sin(th[i]), kRun * L);
    EXPECT_NEAR(p.at("rod_alpha")[i], -3.0 * g * std::cos(th[i]) / (2.0 * L), kRun * g / L);
    const double w = p.at("rod_omega")[i];
    EXPECT_NEAR(w * w, -3.0 * g * std::sin(th[i]) / L, kRun * 3.0 * g / L);
  }
  // Stopped at the bottom: theta = -pi/2 (continuous from 0), the pin pulls with 5 m g / 2.
  EXPECT_NEAR(th.back(), -kPi / 2.0, kRun);
  EXPECT_NEAR(p.at("pin_Fy").back(), 2.5 * m * g, kRun * m * g);
  EXPECT_NEAR(p.at("pin_Fx").back(), 0.0, kRun * m * g);
}

// --- Example 8.4 ladder ----------------------------------------------------------------------
// m = 10 kg, L = 2 m, phi0 = 30 deg; theta = phi (the angle from the vertical).
// x_cm = (L/2) sin(theta), y_cm = (L/2) cos(theta); energy with I about the instantaneous
// centre m L^2/3: omega^2 = (3 g / L)(cos(phi0) - cos(theta)); moments about the instantaneous
// centre: alpha = (3 g / (2 L)) sin(theta); then N_A = m x_cm'', N_B = m g + m y_cm'':
//   N_A = (3/4) m g sin(theta) (3 cos(theta) - 2 cos(phi0)),
//   N_B = m g (1 - (3/4)(1 - 3 cos^2(theta) + 2 cos(theta) cos(phi0))).
constexpr double kLadderMass = 10.0, kLadderLength = 2.0;
const double kPhi0 = 30.0 * kPi / 180.0;

double WallForce(double theta) {
  return 0.75 * kLadderMass * kStandardGravity * std::sin(theta) *
         (3.0 * std::cos(theta) - 2.0 * std::cos(kPhi0));
}
double FloorForce(double theta) {
  const double c = std::cos(theta), c0 = std::cos(kPhi0);
  return kLadderMass * kStandardGravity * (1.0 - 0.75 * (1.0 - 3.0 * c * c + 2.0 * c * c0));
}

TEST(Planar, LadderSolveEqualsThreeDAndClosedForm) {
  const auto p = Solve(Planar("example-8.4-sliding-ladder-planar.yaml"));
  const auto s = Solve(SourcePath("examples/example-8.4-sliding-ladder.yaml"));
  const double g = kStandardGravity, L = kLadderLength, m = kLadderMass;
  const auto& pb = p.at("bodies").at(0).at("planar");
  const Eigen::Vector3d a3 = ToVec(s.at("bodies").at(0).at("acceleration"));
  const Eigen::Vector3d al3 = ToVec(s.at("bodies").at(0).at("angular_acceleration"));
  EXPECT_NEAR(pb.at("a_x").get<double>(), a3.x(), kSolve * g);
  EXPECT_NEAR(pb.at("a_y").get<double>(), a3.z(), kSolve * g);
  EXPECT_NEAR(pb.at("alpha").get<double>(), -al3.y(), kSolve * g / L);
  const auto& wall = p.at("reactions").at(0).at("planar");
  const auto& floor = p.at("reactions").at(1).at("planar");
  const Eigen::Vector3d Fw = ToVec(s.at("reactions").at(0).at("force"));
  const Eigen::Vector3d Ff = ToVec(s.at("reactions").at(1).at("force"));
  EXPECT_NEAR(wall.at("Fx").get<double>(), Fw.x(), kSolve * m * g);
  EXPECT_NEAR(wall.at("Fy").get<double>(), Fw.z(), kSolve * m * g);
  EXPECT_NEAR(floor.at("Fx").get<double>(), Ff.x(), kSolve * m * g);
  EXPECT_NEAR(floor.at("Fy").get<double>(), Ff.z(), kSolve * m * g);
  // Closed forms at release (theta = phi0).
  EXPECT_NEAR(pb.at("alpha").get<double>(), 1.5 * g / L * std::sin(kPhi0), kSolve * g / L);
  EXPECT_NEAR(wall.at("Fx").get<double>(), WallForce(kPhi0), kSolve * m * g);
  EXPECT_NEAR(floor.at("Fy").get<double>(), FloorForce(kPhi0), kSolve * m * g);
  EXPECT_TRUE(p.at("warnings").empty()) << p.at("warnings");
  EXPECT_EQ(p.at("rank").get<int>(), p.at("rows").get<int>());
}

TEST(Planar, LadderSimulateEqualsThreeDAndClosedForm) {
  const Columns p = Simulate(Planar("example-8.4-sliding-ladder-planar.yaml"), "planar,reactions");
  const Columns s =
      Simulate(SourcePath("examples/example-8.4-sliding-ladder.yaml"), "position,tilt,reactions");
  ASSERT_GE(p.at("t").size(), 40u);
  ExpectSameColumn(p.at("t"), s.at("t"), 1.0, kRun, "t");
  ExpectSameColumn(p.at("ladder_x"), s.at("ladder_x"), 1.0, kRun, "x");
  ExpectSameColumn(p.at("ladder_y"), s.at("ladder_z"), 1.0, kRun, "y");
  ExpectSameColumn(p.at("ladder_theta"), s.at("ladder_tilt"), 1.0, kRun, "theta");
  ExpectSameColumn(p.at("wall_Fx"), s.at("wall_Fx"), 1.0, kRun, "N_A");
  ExpectSameColumn(p.at("floor_Fy"), s.at("floor_Fz"), 1.0, kRun, "N_B");

  const double g = kStandardGravity, L = kLadderLength, m = kLadderMass;
  const auto& th = p.at("ladder_theta");
  for (size_t i = 0; i < th.size(); ++i) {
    SCOPED_TRACE("row " + std::to_string(i));
    EXPECT_NEAR(p.at("ladder_x")[i], 0.5 * L * std::sin(th[i]), kRun * L);
    EXPECT_NEAR(p.at("ladder_y")[i], 0.5 * L * std::cos(th[i]), kRun * L);
    const double w = p.at("ladder_omega")[i];
    EXPECT_NEAR(w * w, 3.0 * g / L * (std::cos(kPhi0) - std::cos(th[i])), kRun * g / L);
    EXPECT_NEAR(p.at("ladder_alpha")[i], 1.5 * g / L * std::sin(th[i]), kRun * g / L);
    EXPECT_NEAR(p.at("wall_Fx")[i], WallForce(th[i]), kRun * m * g);
    EXPECT_NEAR(p.at("floor_Fy")[i], FloorForce(th[i]), kRun * m * g);
  }
  // The ladder leaves the wall where N_A = 0: cos(theta) = (2/3) cos(phi0).
  EXPECT_NEAR(th.back(), std::acos(2.0 / 3.0 * std::cos(kPhi0)), kRun);
}

// --- theta over many turns, 3-D columns on request, a chain without redundancy -----------------
std::string WriteScene(const std::string& name, const std::string& text) {
  const auto path = OutDir() / name;
  std::ofstream(path) << text;
  return path.string();
}

TEST(Planar, ThetaIsContinuousOverManyTurns) {
  // A free disk spinning at omega = 40 rad/s for 3 s (19 turns), sampled every 0.1 s (four
  // radians a sample): theta = theta0 + omega t exactly, never wrapped to (-pi, pi].
  const std::string scene = WriteScene("spinner.yaml", R"(
planar: true
bodies:
  - name: wheel
    parts: [{shape: disk, radius: 0.2 m, mass: 1 kg}]
    initial: {position: [1 m, 2 m], theta: 170 deg, velocity: [0.5 m/s, 0], omega: 40 rad/s}
simulation: {until: 3 s, tolerance: 1e-12, output_interval: 0.1 s}
)");
  const Columns c = Simulate(scene, "planar,quaternion");
  const double theta0 = 170.0 * kPi / 180.0;
  ASSERT_EQ(c.at("t").size(), 31u);
  for (size_t i = 0; i < c.at("t").size(); ++i) {
    const double t = c.at("t")[i];
    EXPECT_NEAR(c.at("wheel_theta")[i], theta0 + 40.0 * t, 1e-8 * 120.0) << "t = " << t;
    EXPECT_NEAR(c.at("wheel_x")[i], 1.0 + 0.5 * t, 1e-9);
    EXPECT_NEAR(c.at("wheel_y")[i], 2.0, 1e-9);
    EXPECT_NEAR(c.at("wheel_omega")[i], 40.0, 1e-8);
    // The 3-D columns stay available: q = (cos(theta/2), 0, 0, sin(theta/2)) up to sign.
    EXPECT_NEAR(std::abs(c.at("wheel_qz")[i]), std::abs(std::sin(0.5 * (theta0 + 40.0 * t))), 1e-7);
  }
  EXPECT_GT(c.at("wheel_theta").back(), 19.0 * 2.0 * kPi);
}

TEST(Planar, DoublePendulumHasNoRedundantRows) {
  // Two rods pinned in a chain: 2 + 2 in-plane pin rows and 3 + 3 plane rows, all independent
  // (the 3-D revolutes would give 5 + 5 rows and, with the plane, 6 redundant ones).
  const std::string scene = WriteScene("double.yaml", R"(
planar: true
bodies:
  - name: upper
    parts: [{shape: planar, mass: 1 kg, inertia_z: 1/12 kg*m^2, center_of_mass: [0.5 m, 0]}]
  - name: lower
    parts: [{shape: rod, length: 1 m, mass: 1 kg, axis: [1, 0, 0], position: [0.5 m, 0, 0]}]
    initial: {position: [1 m, 0]}
gravity: standard
joints:
  - {name: top, type: revolute, parent: world, child: upper, at: [0, 0]}
  - {name: elbow, type: revolute, parent: upper, child: lower, at: [1 m, 0]}
)");
  const auto j = Solve(scene);
  EXPECT_EQ(j.at("rows").get<int>(), 10);
  EXPECT_EQ(j.at("rank").get<int>(), 10);
  EXPECT_TRUE(j.at("warnings").empty()) << j.at("warnings");
  // Released horizontal from rest; both rods have m = 1 kg, L = 1 m, I = m L^2/12. Lagrange
  // with the angles theta1, theta2 from the horizontal: at rest and horizontal the centre of
  // the lower rod moves with L theta1' + (L/2) theta2', so
  //   T = 1/2 [(m L^2/3 + m L^2) theta1'^2 + m L^2 theta1' theta2' + (m L^2/3) theta2'^2],
  //   V = m g (L/2) sin(theta1) + m g (L sin(theta1) + (L/2) sin(theta2)),
  //   [4/3 1/2; 1/2 1/3] [a1; a2] = -(g/L) [3/2; 1/2],  det = 4/9 - 1/4 = 7/36,
  //   a1 = -(g/L)(3/2 * 1/3 - 1/2 * 1/2)/det = -9 g/(7 L),  a2 = +3 g/(7 L).
  const double g = kStandardGravity;
  const double a1 = -9.0 * g / 7.0;
  const double a2 = 3.0 * g / 7.0;
  EXPECT_NEAR(j.at("bodies").at(0).at("planar").at("alpha").get<double>(), a1, kSolve * g);
  EXPECT_NEAR(j.at("bodies").at(1).at("planar").at("alpha").get<double>(), a2, kSolve * g);
}

TEST(Planar, SliderAndWheelOnAnInclineMatchClosedForms) {
  // On a 30 deg incline falling towards +x (direction u = (cos, -sin)): a block on a
  // frictionless planar prismatic slides with a = g sin(th) along u and the support pushes
  // with N = m g cos(th); a solid cylinder (I = m R^2/2) rolling without slipping has
  // a = (2/3) g sin(th), alpha = -a/R (clockwise), N = m g cos(th), f = m g sin(th)/3.
  // The wheel touches the plane: its point is the centre (0, 1 m) less R along the normal.
  const std::string scene = WriteScene("incline.yaml", R"(
planar: true
parameters:
  th: 30 deg
bodies:
  - name: block
    parts: [{shape: planar, mass: 2 kg, inertia_z: 0.1 kg*m^2}]
  - name: wheel
    parts: [{shape: cylinder, radius: 0.1 m, length: 0.05 m, mass: 3 kg}]
    initial: {position: [0, 1 m]}
gravity: standard
joints:
  - {name: slide, type: prismatic, parent: world, child: block, at: [0, 0],
     axis: [cos(th), -sin(th)]}
rolling:
  - {name: roll, body: wheel, radius: 0.1 m,
     plane: {point: [-sin(th) * 0.1 m, 1 m - cos(th) * 0.1 m], normal: [sin(th), cos(th)]},
     mu_s: 0.5}
)");
  const auto j = Solve(scene);
  const double g = kStandardGravity, th = kPi / 6.0, R = 0.1;
  const auto& block = j.at("bodies").at(0).at("planar");
  const auto& wheel = j.at("bodies").at(1).at("planar");
  EXPECT_NEAR(block.at("a_x").get<double>(), g * std::sin(th) * std::cos(th), kSolve * g);
  EXPECT_NEAR(block.at("a_y").get<double>(), -g * std::sin(th) * std::sin(th), kSolve * g);
  EXPECT_NEAR(block.at("alpha").get<double>(), 0.0, kSolve * g);
  const double a = 2.0 / 3.0 * g * std::sin(th);
  EXPECT_NEAR(wheel.at("a_x").get<double>(), a * std::cos(th), kSolve * g);
  EXPECT_NEAR(wheel.at("a_y").get<double>(), -a * std::sin(th), kSolve * g);
  EXPECT_NEAR(wheel.at("alpha").get<double>(), -a / R, kSolve * g / R);
  const auto& slide = j.at("reactions").at(0).at("planar");
  EXPECT_NEAR(std::hypot(slide.at("Fx").get<double>(), slide.at("Fy").get<double>()),
              2.0 * g * std::cos(th), kSolve * 2.0 * g);
  const auto& roll = j.at("reactions").at(1);
  EXPECT_NEAR(roll.at("normal_force").get<double>(), 3.0 * g * std::cos(th), kSolve * 3.0 * g);
  EXPECT_NEAR(roll.at("friction_magnitude").get<double>(), g * std::sin(th), kSolve * 3.0 * g);
  EXPECT_EQ(j.at("rank").get<int>(), j.at("rows").get<int>());
  EXPECT_TRUE(j.at("warnings").empty()) << j.at("warnings");
}

}  // namespace
}  // namespace chasles::test
