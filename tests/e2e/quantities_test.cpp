// End-to-end: the quantities `chasles solve` and `chasles simulate` report besides the
// accelerations: ω and v, the velocity and acceleration of a body's named points, dH/dt about
// the centre of mass and about the world origin, and each body's own energy and momenta.
//
// The scene is a free rigid body under gravity alone, so everything has a closed form:
// - the centre of mass falls freely, a_cm = g;
// - no moment acts about the centre of mass, so dH_cm/dt = 0 and Euler's equations
//   (chapter eqs. 8.75-8.81 with zero moments) give α in body axes:
//     I1 α1 = (I2 - I3) ω2 ω3,  I2 α2 = (I3 - I1) ω3 ω1,  I3 α3 = (I1 - I2) ω1 ω2;
// - dH_O/dt = r_cm × m g (the moment of gravity about O, ΣM_O = dH_O/dt, eq. 8.30);
// - a body point P, r = R (p_P - p_cm) in W: v_P = v + ω × r, a_P = g + α × r + ω × (ω × r).

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include "chasles/math/types.h"
#include "cli_runner.h"

namespace chasles::test {
namespace {

// One linear solve or one evaluation: round-off only, relative.
constexpr double kExact = 1e-9;

// The body: mass m, principal moments I (body axes), centre of mass cm_B from the body origin,
// a named point P, placed at p0 turned by 90° about z, moving at v0 with ω0 (body axes).
struct FreeBody {
  const double m = 2.0;
  const Vec3 I{1.0, 2.0, 3.0};
  const Vec3 cm_B{0.1, 0.0, 0.0};
  const Vec3 P_B{0.2, -0.1, 0.4};
  const Vec3 p0{1.0, 2.0, 3.0};
  const Vec3 v0{0.5, -1.0, 2.0};
  const Vec3 w0_B{0.3, -0.7, 1.1};
  const Vec3 g{0.0, 0.0, -9.80665};
  const Mat3 R0 = Eigen::AngleAxisd(M_PI / 2, Vec3::UnitZ()).toRotationMatrix();

  // Euler's equations with no moment: α in body axes.
  Vec3 AlphaB(const Vec3& w) const {
    return Vec3((I[1] - I[2]) * w[1] * w[2] / I[0], (I[2] - I[0]) * w[2] * w[0] / I[1],
                (I[0] - I[1]) * w[0] * w[1] / I[2]);
  }
  // The size of I α and ω × I ω, against which dH/dt = 0 is round-off.
  double MomentScale(const Vec3& w) const { return w.cross(Vec3(I.asDiagonal() * w)).norm(); }
};

std::string WriteScene() {
  const auto path = OutDir("quantities") / "free-body.yaml";
  std::ofstream(path) << R"(chasles: 1
title: "Free body under gravity"
parameters:
  m: 2 kg
bodies:
  - name: box
    points:
      P: [0.2, -0.1, 0.4]
    parts:
      - shape: custom
        mass: m
        center_of_mass: [0.1, 0, 0]
        inertia: {Ixx: 1 kg*m^2, Iyy: 2 kg*m^2, Izz: 3 kg*m^2}
    initial:
      position: [1, 2, 3]
      rotation: {axis: [0, 0, 1], angle: 90 deg}
      velocity: [0.5, -1, 2]
      angular_velocity: [0.3, -0.7, 1.1]
      angular_velocity_frame: body
gravity: standard
simulation:
  until: 0.5 s
  tolerance: 1e-12
  output_interval: 0.1 s
)";
  return path.string();
}

bool VecNear(const Vec3& got, const Vec3& want, double scale) {
  return (got - want).norm() <= kExact * scale;
}

TEST(SolveQuantities, PointsAndAngularMomentumRate) {
  const FreeBody b;
  const std::string scene = WriteScene();
  const CliResult r = RunCli("solve " + Quote(scene) + " --format json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  const auto& k = j.at("kinematics").at(0);
  const Vec3 w = b.R0 * b.w0_B;
  const Vec3 alpha = b.R0 * b.AlphaB(b.w0_B);
  const Vec3 p_cm = b.p0 + b.R0 * b.cm_B;
  EXPECT_TRUE(VecNear(ToVec(k.at("angular_velocity")), w, w.norm()));
  EXPECT_TRUE(VecNear(ToVec(k.at("velocity")), b.v0, b.v0.norm()));
  EXPECT_TRUE(VecNear(ToVec(k.at("acceleration")), b.g, b.g.norm()));
  EXPECT_TRUE(VecNear(ToVec(k.at("angular_acceleration")), alpha, alpha.norm()));
  const Vec3 r_P = b.R0 * (b.P_B - b.cm_B);
  const Vec3 v_P = b.v0 + w.cross(r_P);
  const Vec3 a_P = b.g + alpha.cross(r_P) + w.cross(w.cross(r_P));
  const auto& P = k.at("points").at(0);
  EXPECT_EQ(P.at("name"), "P");
  EXPECT_TRUE(VecNear(ToVec(P.at("position")), p_cm + r_P, p_cm.norm()));
  EXPECT_TRUE(VecNear(ToVec(P.at("velocity")), v_P, v_P.norm()));
  EXPECT_TRUE(VecNear(ToVec(P.at("acceleration")), a_P, a_P.norm()));
  // No moment about the centre of mass: dH_cm/dt = 0 (each of I α and ω × I ω is not).
  EXPECT_LE(ToVec(k.at("angular_momentum_rate_cm")).norm(), kExact * b.MomentScale(b.w0_B));
  const Vec3 dHO = p_cm.cross(b.m * b.g);
  EXPECT_TRUE(VecNear(ToVec(k.at("angular_momentum_rate_origin")), dHO, dHO.norm()));
  const auto& em = j.at("energy_momentum");
  EXPECT_TRUE(
      VecNear(ToVec(em.at("bodies").at(0).at("angular_momentum_rate_origin")), dHO, dHO.norm()));
  // One body: the system's rates are the body's.
  EXPECT_TRUE(VecNear(ToVec(em.at("total").at("angular_momentum_rate_origin")), dHO, dHO.norm()));
  EXPECT_LE(ToVec(em.at("total").at("angular_momentum_rate_cm")).norm(),
            kExact * b.MomentScale(b.w0_B));

  // The text report names them.
  const CliResult text = RunCli("solve " + Quote(scene));
  ASSERT_EQ(text.exit_code, 0) << text.err;
  EXPECT_THAT(text.out, ::testing::HasSubstr("point P at ["));
  EXPECT_THAT(text.out, ::testing::HasSubstr("dH_O/dt ["));

  // The sweep table carries the same values, named as the simulation's columns.
  const CliResult sweep =
      RunCli("solve " + Quote(scene) + " --sweep 'm=2 kg:4 kg:2' --format json");
  ASSERT_EQ(sweep.exit_code, 0) << sweep.err;
  const auto t = nlohmann::json::parse(sweep.out);
  std::map<std::string, double> row0;
  for (size_t c = 0; c < t.at("columns").size(); ++c) {
    row0[t.at("columns")[c].get<std::string>()] = t.at("rows")[0][c].get<double>();
  }
  const auto col3 = [&](const std::string& prefix) {
    return Vec3(row0.at(prefix + "x"), row0.at(prefix + "y"), row0.at(prefix + "z"));
  };
  EXPECT_TRUE(VecNear(col3("box_v"), b.v0, b.v0.norm()));
  EXPECT_TRUE(VecNear(col3("box_w"), w, w.norm()));
  EXPECT_TRUE(VecNear(col3("box_P_v"), v_P, v_P.norm()));
  EXPECT_TRUE(VecNear(col3("box_P_a"), a_P, a_P.norm()));
  EXPECT_TRUE(VecNear(col3("box_dHO"), dHO, dHO.norm()));
  EXPECT_LE(col3("box_dH").norm(), kExact * b.MomentScale(b.w0_B));
  EXPECT_TRUE(VecNear(col3("dHO"), dHO, dHO.norm()));
}

// At every sample of a run: the point columns, dH/dt and the body's own momenta and energy
// against the closed forms evaluated at that sample's own state (its quaternion, v and ω).
TEST(SimulateQuantities, PointColumnsAngularMomentumRateAndBodyMomenta) {
  const FreeBody b;
  const std::string scene = WriteScene();
  const auto summary = SimulateJson(
      scene, OutDir("quantities"),
      "--columns position,quaternion,velocity,angular_velocity,point_velocity,point_acceleration,"
      "angular_momentum_rate,angular_momentum_rate_origin,body_energy,body_momentum,"
      "body_angular_momentum,body_angular_momentum_origin");
  const auto csv = ReadCsv(summary.at("csv").get<std::string>());
  const size_t rows = csv.at("t").size();
  ASSERT_GE(rows, 5u);
  const auto at3 = [&](const std::string& prefix, size_t i) {
    return Vec3(csv.at(prefix + "x").at(i), csv.at(prefix + "y").at(i), csv.at(prefix + "z").at(i));
  };
  const Mat3 I = b.I.asDiagonal();
  for (size_t i = 0; i < rows; ++i) {
    const Mat3 R =
        Quat(csv.at("box_qw")[i], csv.at("box_qx")[i], csv.at("box_qy")[i], csv.at("box_qz")[i])
            .normalized()
            .toRotationMatrix();
    const Vec3 p_cm = at3("box_", i), v = at3("box_v", i), w = at3("box_w", i);
    const Vec3 w_B = R.transpose() * w;
    const Vec3 alpha = R * b.AlphaB(w_B);
    const Vec3 r = R * (b.P_B - b.cm_B);
    const Vec3 v_P = v + w.cross(r);
    const Vec3 a_P = b.g + alpha.cross(r) + w.cross(w.cross(r));
    // The CSV holds 12 significant digits: its own values agree to about 1e-11.
    EXPECT_TRUE(VecNear(at3("box_P_v", i), v_P, v_P.norm())) << "row " << i;
    EXPECT_TRUE(VecNear(at3("box_P_a", i), a_P, a_P.norm())) << "row " << i;
    EXPECT_LE(at3("box_dH", i).norm(), kExact * b.MomentScale(w_B)) << "row " << i;
    const Vec3 dHO = p_cm.cross(b.m * b.g);
    EXPECT_TRUE(VecNear(at3("box_dHO", i), dHO, dHO.norm())) << "row " << i;
    EXPECT_TRUE(VecNear(at3("box_P", i), b.m * v, b.m * v.norm())) << "row " << i;
    const Vec3 H = R * I * w_B;
    EXPECT_TRUE(VecNear(at3("box_H", i), H, H.norm())) << "row " << i;
    const Vec3 HO = H + p_cm.cross(b.m * v);
    EXPECT_TRUE(VecNear(at3("box_HO", i), HO, HO.norm())) << "row " << i;
    const double T_trans = 0.5 * b.m * v.squaredNorm(), T_rot = 0.5 * w_B.dot(I * w_B);
    EXPECT_NEAR(csv.at("box_T_trans")[i], T_trans, kExact * T_trans) << "row " << i;
    EXPECT_NEAR(csv.at("box_T_rot")[i], T_rot, kExact * T_rot) << "row " << i;
    EXPECT_NEAR(csv.at("box_T")[i], T_trans + T_rot, kExact * (T_trans + T_rot)) << "row " << i;
  }
}

}  // namespace
}  // namespace chasles::test
