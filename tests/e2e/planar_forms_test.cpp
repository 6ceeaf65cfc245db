// End-to-end: one problem written as a 3-D scene and as a planar scene (`planar: true`) with
// the planar forms of every key (docs/scene-format.md, "Planar scenes"): [x, y] world vectors,
// disk and cylinder contacts without an axis, the angle, its rate and its acceleration as
// `<body>_theta`, `<body>_omega`, `<body>_alpha` in events and columns alike. The answers must
// agree with each other and with closed forms derived here.
//
// The 3-D scenes move in the x-z plane (gravity -z, axes along y); the planar ones in the x-y
// plane (gravity -y, rotation about z). The proper rotation taking the first onto the second
// maps x -> x, z -> y, y -> -z, so a 3-D angular quantity about +y is the planar one about -z
// (omega = -w_y, alpha = -alpha_y) and the 3-D pitch of a rotation about y is -theta.

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

namespace chasles::test {
namespace {

constexpr double kStandardGravity = 9.80665;
constexpr double kPi = 3.14159265358979323846;
// The 3-D and planar scenes are different constraint sets (the planar one adds a plane joint
// per body), so their solves round differently: instantaneous answers agree to round-off
// (kSame of their scale), closed forms hold to kExact.
constexpr double kSame = 1e-12;
constexpr double kExact = 1e-9;

std::filesystem::path OutDir() {
  return test::OutDir("planar_forms");
}

std::string WriteScene(const std::string& name, const std::string& text) {
  const auto path = OutDir() / name;
  std::ofstream(path) << text;
  return path.string();
}

nlohmann::json Solve(const std::string& scene) {
  const CliResult r = RunCli("solve " + Quote(scene) + " --format json");
  if (r.exit_code != 0) throw std::runtime_error("chasles solve " + scene + ": " + r.err);
  return nlohmann::json::parse(r.out);
}

using Columns = std::map<std::string, std::vector<double>>;

struct SimRun {
  nlohmann::json report;
  Columns columns;
};

SimRun Simulate(const std::string& scene, const std::string& columns) {
  const CliResult r = RunCli("simulate " + Quote(scene) + " --format json --out " +
                             Quote(OutDir().string()) + " --columns " + columns);
  if (r.exit_code != 0) throw std::runtime_error("chasles simulate " + scene + ": " + r.err);
  const std::string stem = std::filesystem::path(scene).stem().string();
  return {nlohmann::json::parse(r.out), ReadCsv((OutDir() / (stem + ".csv")).string())};
}

double EventTime(const nlohmann::json& report, const std::string& name) {
  for (const auto& e : report.at("events")) {
    if (e.at("name") == name) return e.at("t").get<double>();
  }
  ADD_FAILURE() << "no event '" << name << "' in " << report.at("events");
  return std::nan("");
}

// --- a cylinder on an incline, as a contact and as a rolling constraint ------------------------
// m = 5 kg, R = 0.1 m, theta = 30 deg, mu_s = 0.25 > tan(theta)/3: it rolls. With the friction
// f up the slope, m a = m g sin(theta) - f and (m R^2/2) a / R = f R give a = (2/3) g sin(theta)
// down the slope (cos(theta), -sin(theta)) in the planar scene, alpha = -a/R (clockwise),
// N = m g cos(theta) and f = m g sin(theta)/3 (Example 8.3). From rest the centre moves
// s = a t^2/2 down the slope and omega = -a t / R.
constexpr double kCylMass = 5.0, kCylRadius = 0.1;
const double kIncline = kPi / 6.0;

TEST(PlanarForms, CylinderContactOnInclineSolveEqualsThreeDAndClosedForm) {
  const auto s = Solve(SourcePath("examples/contact-cylinder-incline.yaml"));
  const auto p = Solve(SourcePath("examples/contact-cylinder-incline-planar.yaml"));
  const double g = kStandardGravity, th = kIncline, m = kCylMass, R = kCylRadius;
  const auto& pb = p.at("bodies").at(0).at("planar");
  const Eigen::Vector3d a3 = ToVec(s.at("bodies").at(0).at("acceleration"));
  const Eigen::Vector3d al3 = ToVec(s.at("bodies").at(0).at("angular_acceleration"));
  EXPECT_NEAR(pb.at("a_x").get<double>(), a3.x(), kSame * g);
  EXPECT_NEAR(pb.at("a_y").get<double>(), a3.z(), kSame * g);
  EXPECT_NEAR(pb.at("alpha").get<double>(), -al3.y(), kSame * g / R);
  const double a = 2.0 / 3.0 * g * std::sin(th);
  EXPECT_NEAR(pb.at("a_x").get<double>(), a * std::cos(th), kExact * g);
  EXPECT_NEAR(pb.at("a_y").get<double>(), -a * std::sin(th), kExact * g);
  EXPECT_NEAR(pb.at("alpha").get<double>(), -a / R, kExact * g / R);
  // Two rim points each; together N = m g cos(theta) and f = m g sin(theta)/3.
  ASSERT_EQ(p.at("contacts").size(), 2u);
  ASSERT_EQ(s.at("contacts").size(), 2u);
  double N = 0.0, f = 0.0;
  for (size_t i = 0; i < 2; ++i) {
    const auto& c = p.at("contacts").at(i);
    EXPECT_EQ(c.at("regime"), "rolls");
    EXPECT_NEAR(c.at("normal_force").get<double>(),
                s.at("contacts").at(i).at("normal_force").get<double>(), kSame * m * g);
    N += c.at("normal_force").get<double>();
    f += c.at("friction_magnitude").get<double>();
  }
  EXPECT_NEAR(N, m * g * std::cos(th), kExact * m * g);
  EXPECT_NEAR(f, m * g * std::sin(th) / 3.0, kExact * m * g);
}

TEST(PlanarForms, CylinderContactOnInclineSimulateEqualsThreeDAndClosedForm) {
  const SimRun s = Simulate(SourcePath("examples/contact-cylinder-incline.yaml"),
                            "position,velocity,angular_velocity,contacts");
  const SimRun p =
      Simulate(SourcePath("examples/contact-cylinder-incline-planar.yaml"), "planar,contacts");
  const Columns &S = s.columns, &P = p.columns;
  ASSERT_GE(P.at("t").size(), 10u);
  ExpectSameColumn(P.at("t"), S.at("t"), 1.0, kSame, "t");
  ExpectSameColumn(P.at("cylinder_x"), S.at("cylinder_x"), 1.0, kSame, "x");
  ExpectSameColumn(P.at("cylinder_y"), S.at("cylinder_z"), 1.0, kSame, "y");
  ExpectSameColumn(P.at("cylinder_vx"), S.at("cylinder_vx"), 1.0, kSame, "vx");
  ExpectSameColumn(P.at("cylinder_vy"), S.at("cylinder_vz"), 1.0, kSame, "vy");
  ExpectSameColumn(P.at("cylinder_omega"), S.at("cylinder_wy"), -1.0, kSame, "omega");
  const double g = kStandardGravity, th = kIncline, R = kCylRadius;
  const double a = 2.0 / 3.0 * g * std::sin(th);
  for (size_t i = 0; i < P.at("t").size(); ++i) {
    SCOPED_TRACE("row " + std::to_string(i));
    const double t = P.at("t")[i], sl = 0.5 * a * t * t;
    EXPECT_NEAR(P.at("cylinder_x")[i], R * std::sin(th) + sl * std::cos(th), kExact * R);
    EXPECT_NEAR(P.at("cylinder_y")[i], R * std::cos(th) - sl * std::sin(th), kExact * R);
    EXPECT_NEAR(P.at("cylinder_omega")[i], -a * t / R, kExact * a / R);
    EXPECT_NEAR(P.at("cylinder_theta")[i], -0.5 * a * t * t / R, kExact);
    EXPECT_NEAR(P.at("cylinder_alpha")[i], -a / R, kExact * a / R);
    EXPECT_EQ(P.at("incline_0_mode")[i], 2.0);  // sticking: rolling
  }
}

TEST(PlanarForms, RollingCylinderSolveEqualsThreeDAndClosedForm) {
  const auto s = Solve(SourcePath("examples/example-8.3-cylinder-incline.yaml"));
  const auto p = Solve(SourcePath("examples/example-8.3-cylinder-incline-planar.yaml"));
  const double g = kStandardGravity, th = kIncline, m = kCylMass, R = kCylRadius;
  const auto& pb = p.at("bodies").at(0).at("planar");
  const Eigen::Vector3d a3 = ToVec(s.at("bodies").at(0).at("acceleration"));
  const Eigen::Vector3d al3 = ToVec(s.at("bodies").at(0).at("angular_acceleration"));
  EXPECT_NEAR(pb.at("a_x").get<double>(), a3.x(), kSame * g);
  EXPECT_NEAR(pb.at("a_y").get<double>(), a3.z(), kSame * g);
  EXPECT_NEAR(pb.at("alpha").get<double>(), -al3.y(), kSame * g / R);
  const double a = 2.0 / 3.0 * g * std::sin(th);
  EXPECT_NEAR(pb.at("alpha").get<double>(), -a / R, kExact * g / R);
  const auto& pr = p.at("reactions").at(0);
  const auto& sr = s.at("reactions").at(0);
  EXPECT_NEAR(pr.at("normal_force").get<double>(), sr.at("normal_force").get<double>(),
              kSame * m * g);
  EXPECT_NEAR(pr.at("normal_force").get<double>(), m * g * std::cos(th), kExact * m * g);
  EXPECT_NEAR(pr.at("friction_magnitude").get<double>(), m * g * std::sin(th) / 3.0,
              kExact * m * g);
}

// --- gears, a driver and pins about z ----------------------------------------------------------
// planetary-gears.yaml turns in the x-y plane already: its planar form gives no axis. With the
// sun driven at w_sun = 10 rad/s, r_s = 5 cm, r_p = 2 cm, d = r_s + r_p and the ring fixed, no
// slip at the pitch points gives the carrier w_c = w_sun r_s / (2 d) and the planet
// w_p = -w_c d / r_p; the carrier's angle is w_c t.
TEST(PlanarForms, PlanetaryGearsEqualThreeDAndClosedForm) {
  const SimRun s =
      Simulate(SourcePath("examples/planetary-gears.yaml"), "position,angular_velocity");
  const SimRun p = Simulate(SourcePath("examples/planetary-gears-planar.yaml"), "planar");
  const Columns &S = s.columns, &P = p.columns;
  ASSERT_EQ(P.at("t").size(), 21u);
  const double w_sun = 10.0, r_s = 0.05, r_p = 0.02, d = r_s + r_p;
  const double w_c = w_sun * r_s / (2.0 * d), w_p = -w_c * d / r_p;
  for (const char* b : {"sun", "carrier", "planet"}) {
    const std::string n = b;
    ExpectSameColumn(P.at(n + "_omega"), S.at(n + "_wz"), 1.0, kSame, n + " omega");
    // Positions to round-off of the scene's size d (the sun's and carrier's stay at ~0).
    for (size_t i = 0; i < P.at("t").size(); ++i) {
      EXPECT_NEAR(P.at(n + "_x")[i], S.at(n + "_x")[i], kSame * d) << n << " row " << i;
      EXPECT_NEAR(P.at(n + "_y")[i], S.at(n + "_y")[i], kSame * d) << n << " row " << i;
    }
  }
  for (size_t i = 0; i < P.at("t").size(); ++i) {
    SCOPED_TRACE("row " + std::to_string(i));
    const double t = P.at("t")[i];
    EXPECT_NEAR(P.at("sun_omega")[i], w_sun, kExact * w_sun);
    EXPECT_NEAR(P.at("carrier_omega")[i], w_c, kExact * w_sun);
    EXPECT_NEAR(P.at("planet_omega")[i], w_p, kExact * w_sun);
    EXPECT_NEAR(P.at("carrier_theta")[i], w_c * t, kExact * w_sun);
    EXPECT_NEAR(P.at("planet_x")[i], d * std::cos(w_c * t), kExact * d);
  }
}

// --- one planar scene, body-frame keys as [x, y] or [x, y, z] --------------------------------
TEST(PlanarForms, BodyFrameKeysReadTheSameWithTwoOrThreeValues) {
  // Part positions, from/to, points, a force's point, a contact's centre and a disk axis
  // [0, 0, 1] (the planar default) give the very same scene as their [x, y] forms.
  const std::string two = R"(
planar: true
bodies:
  - name: arm
    parts:
      - {shape: rod, mass: 1 kg, from: [0, 0], to: [0.8 m, 0]}
      - {shape: disk, mass: 2 kg, radius: 0.1 m, position: [0.8 m, 0]}
      - {shape: custom, mass: 0.5 kg, center_of_mass: [0.2 m, 0.1 m],
         inertia: {Ixx: 0.01 kg*m^2, Iyy: 0.01 kg*m^2, Izz: 0.02 kg*m^2}}
    points: {tip: [0.8 m, 0]}
    initial: {position: [0, 0.1 m], theta: 10 deg}
gravity: standard
joints:
  - {name: pin, type: revolute, parent: world, child: arm, at: [0, 0.1 m]}
forces:
  - {type: force, body: arm, point: [0.4 m, 0], value: [1 N, 2 N]}
contacts:
  - {name: wheel, body: arm, shape: disk, radius: 0.1 m, center: tip, mu_s: 0.5,
     plane: {point: [0, -1 m], normal: [0, 1]}}
)";
  std::string three = two;
  const auto replace = [&](const std::string& a, const std::string& b) {
    const size_t at = three.find(a);
    ASSERT_NE(at, std::string::npos) << a;
    three.replace(at, a.size(), b);
  };
  replace("from: [0, 0], to: [0.8 m, 0]", "from: [0, 0, 0], to: [0.8 m, 0, 0]");
  replace("position: [0.8 m, 0]}", "position: [0.8 m, 0, 0]}");
  replace("center_of_mass: [0.2 m, 0.1 m]", "center_of_mass: [0.2 m, 0.1 m, 0]");
  replace("tip: [0.8 m, 0]", "tip: [0.8 m, 0, 0]");
  replace("point: [0.4 m, 0]", "point: [0.4 m, 0, 0]");
  replace("radius: 0.1 m, center: tip", "radius: 0.1 m, axis: [0, 0, 1], center: tip");
  replace("at: [0, 0.1 m]}", "at: [0, 0.1 m], axis: [0, 0, 1]}");
  const auto a = Solve(WriteScene("two.yaml", two));
  const auto b = Solve(WriteScene("three.yaml", three));
  const auto& pa = a.at("bodies").at(0).at("planar");
  const auto& pb = b.at("bodies").at(0).at("planar");
  for (const char* k : {"a_x", "a_y", "alpha"}) {
    EXPECT_EQ(pa.at(k).get<double>(), pb.at(k).get<double>()) << k;
  }
  EXPECT_EQ(a.at("reactions"), b.at("reactions"));
}

// --- a pendulum with events on its angle, rate and acceleration ---------------------------------
// A slender rod (m = 2 kg, L = 1 m) pinned at one end, released horizontal: I_O = m L^2/3
// (eq. 8.39), so alpha = -3 g cos(theta)/(2 L) and, from energy, omega^2 = -3 g sin(theta)/L
// (theta counterclockwise from +x, falling: omega < 0). At theta = -pi/4:
// omega = -sqrt(3 g sin(pi/4)/L) and alpha = -3 g cos(pi/4)/(2 L): three events watching
// theta, omega and alpha cross these values fire at the same instant. The 3-D scene swings
// in the x-z plane about y; its pitch (Euler ZYX) is -theta and w_y is -omega.
const char* kPendulum3D = R"(
parameters: {m: 2 kg, L: 1 m}
bodies:
  - name: rod
    parts:
      - {shape: custom, mass: m, center_of_mass: [L/2, 0, 0],
         inertia: {Ixx: 1e-4 kg*m^2, Iyy: m*L^2/12, Izz: m*L^2/12}}
gravity: standard
joints:
  - {name: pin, type: revolute, parent: world, child: rod, at: [0, 0, 0], axis: [0, 1, 0]}
events:
  - {name: angle, when: rod_pitch, crosses: 45 deg, direction: rising, action: record}
  - {name: bottom, when: rod_x, crosses: 0 m, direction: falling, action: stop}
simulation: {until: 2 s, tolerance: 1e-12, output_interval: 0.01 s}
)";

const char* kPendulumPlanar = R"(
planar: true
parameters: {m: 2 kg, L: 1 m, gn: 9.80665 m/s^2}
bodies:
  - name: rod
    parts: [{shape: planar, mass: m, inertia_z: m*L^2/12, center_of_mass: [L/2, 0]}]
gravity: standard
joints:
  - {name: pin, type: revolute, parent: world, child: rod, at: [0, 0]}
events:
  - {name: angle, when: rod_theta, crosses: -45 deg, direction: falling, action: record}
  - {name: rate, when: rod_omega, crosses: -sqrt(3*gn*sin(45 deg)/L),
     direction: falling, action: record}
  - {name: acceleration, when: rod_alpha, crosses: -3*gn*cos(45 deg)/(2*L),
     direction: rising, action: record}
  - {name: bottom, when: rod_theta, crosses: -90 deg, direction: falling, action: stop}
simulation: {until: 2 s, tolerance: 1e-12, output_interval: 0.01 s}
)";

TEST(PlanarForms, PendulumEventsOnThetaOmegaAlphaMatchThreeDAndClosedForms) {
  const SimRun s =
      Simulate(WriteScene("pendulum3d.yaml", kPendulum3D), "position,angular_velocity");
  const SimRun p = Simulate(WriteScene("pendulum.yaml", kPendulumPlanar), "planar");
  const double t_angle = EventTime(p.report, "angle");
  // One instant, whichever name watches it; the same as the 3-D scene's pitch event.
  EXPECT_NEAR(EventTime(p.report, "rate"), t_angle, kExact * t_angle);
  EXPECT_NEAR(EventTime(p.report, "acceleration"), t_angle, kExact * t_angle);
  EXPECT_NEAR(EventTime(s.report, "angle"), t_angle, kExact * t_angle);
  EXPECT_NEAR(EventTime(s.report, "bottom"), EventTime(p.report, "bottom"), kExact * t_angle);
  ASSERT_TRUE(p.report.at("stopped_by_event").get<bool>());
  // The columns carry the names the events read: theta ends at -pi/2 and omega is signed.
  const Columns& P = p.columns;
  const double g = kStandardGravity, L = 1.0;
  EXPECT_NEAR(P.at("rod_theta").back(), -kPi / 2.0, kExact);
  EXPECT_NEAR(P.at("rod_omega").back(), -std::sqrt(3.0 * g / L), kExact * std::sqrt(g / L));
  EXPECT_NEAR(P.at("rod_alpha").back(), 0.0, kExact * g / L);
  ExpectSameColumn(P.at("rod_omega"), s.columns.at("rod_wy"), -1.0, kExact, "omega");
}

TEST(PlanarForms, ThetaInExpressionsPassesPi) {
  // A free disk turning at omega = 40 rad/s from theta0 = 170 deg: theta = theta0 + omega t,
  // continuous through pi (where atan2 would wrap to -pi), so an event at theta0 + 6 rad fires
  // at t = 6/40 s and one at theta0 - 1 rad (never reached) does not. In expressions theta is
  // exact within one turn of theta0 (docs/scene-format.md): the run ends at 40 t = 6.2 < 2 pi.
  const std::string scene = WriteScene("spin.yaml", R"(
planar: true
bodies:
  - name: wheel
    parts: [{shape: disk, radius: 0.2 m, mass: 1 kg}]
    initial: {theta: 170 deg, omega: 40 rad/s}
events:
  - {name: six, when: wheel_theta - 170 deg, crosses: 6, direction: rising, action: record}
  - {name: back, when: wheel_theta - 170 deg, crosses: -1, action: record}
simulation: {until: 0.155 s, tolerance: 1e-12, output_interval: 0.01 s}
)");
  const SimRun r = Simulate(scene, "planar");
  ASSERT_EQ(r.report.at("events").size(), 1u) << r.report.at("events");
  EXPECT_NEAR(EventTime(r.report, "six"), 6.0 / 40.0, 1e-11);
}

TEST(PlanarForms, AlphaOfALaterBodyWithAForceReadingItsState) {
  // Two free disks, no gravity. The second, b (m = 1 kg, R = 0.2 m: I = m R^2/2 = 0.02 kg m^2),
  // moves at vx = 1 m/s, so b_x = t, and carries the moment M = 2 N*m/m * b_x = 2 t N*m:
  // alpha = M/I = 100 t, omega = 50 t^2, theta = (50/3) t^3. alpha reaches 50 rad/s^2 and
  // omega 12.5 rad/s together at t = 0.5 s, where theta = 50/24 rad.
  const std::string scene = WriteScene("two_disks.yaml", R"(
planar: true
bodies:
  - name: a
    parts: [{shape: disk, radius: 0.1 m, mass: 1 kg}]
  - name: b
    parts: [{shape: disk, radius: 0.2 m, mass: 1 kg}]
    initial: {velocity: [1 m/s, 0]}
forces:
  - {type: moment, body: b, value: 2 N*m/m * b_x}
events:
  - {name: alpha, when: b_alpha, crosses: 50 rad/s^2, direction: rising, action: record}
  - {name: omega, when: b_omega, crosses: 12.5 rad/s, direction: rising}
simulation: {until: 1 s, tolerance: 1e-12, output_interval: 0.1 s}
)");
  const SimRun r = Simulate(scene, "planar");
  EXPECT_NEAR(EventTime(r.report, "alpha"), 0.5, kExact);
  EXPECT_NEAR(EventTime(r.report, "omega"), 0.5, kExact);
  EXPECT_NEAR(r.columns.at("b_theta").back(), 50.0 / 24.0, kExact);
  EXPECT_NEAR(r.columns.at("b_alpha").back(), 50.0, kExact * 50.0);
  EXPECT_NEAR(r.columns.at("a_omega").back(), 0.0, kExact);
}

}  // namespace
}  // namespace chasles::test
