// End-to-end: Problem 8.40, gear A rolling on the fixed gear B (examples/problem-8.40-gear-on-
// fixed-gear.yaml, whose comments reconstruct the geometry and derive the answers), through
// `chasles solve` and `chasles simulate`; a planetary gear set; and a ball on a turntable
// (`rolling: on:`).

#include <cmath>
#include <filesystem>
#include <fstream>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "chasles/math/types.h"
#include "cli_runner.h"
#include "test_support.h"

namespace chasles::test {
namespace {

constexpr double kSolve = 1e-9;  // one linear solve: round-off only
constexpr double kPi = 3.14159265358979323846;

// The example's parameters.
constexpr double kM = 2.0, kR = 0.1, kL = 0.3, kOmega = 3.0;

std::filesystem::path OutDir() {
  return test::OutDir("gears");
}

const nlohmann::json& Named(const nlohmann::json& list, const std::string& name) {
  for (const auto& x : list) {
    if (x.at("name") == name) return x;
  }
  throw std::runtime_error("nothing named " + name);
}

// Closed forms of the example's comments, for the axle at beta above the horizontal (t = 0,
// the axle in the x-z plane): e = (cos b, 0, sin b), n' = (-sin b, 0, cos b).
struct Answers {
  double omega;      // (b) A's spin rate about its axle [rad/s]
  Vec3 a, C;         // A's centre and the contact point [m]
  Vec3 H_cm, H_dot;  // (c), (d) [kg m²/s, N m]
  explicit Answers(double beta) {
    const double c = std::cos(beta), s = std::sin(beta);
    const Vec3 e(c, 0, s), n(-s, 0, c);
    omega = kOmega * (kL * c + kR * s) / kR;
    a = kL * e;
    C = a - kR * n;
    H_cm = kM * kR * kOmega * c / 4 * (-2 * kL * e + kR * n);
    H_dot = -kM * kR * kOmega * kOmega * c / 4 * (2 * kL * c + kR * s) * Vec3::UnitY();
  }
};

// (b), (c), (d) at the instant: the net moment about A's centre of the reactions on A (the
// bearing on the axle and the mesh at C; gravity acts at the centre) is dH_cm/dt, and A's
// angular acceleration is Omega k x w_A, whose y component is Omega w_s cos(beta).
TEST(Gears, Problem840NetMomentOnGearAIsTheRateOfItsAngularMomentum) {
  for (const double beta_deg : {20.0, 0.0, 35.0}) {
    SCOPED_TRACE(beta_deg);
    const double beta = beta_deg * kPi / 180;
    const Answers ans(beta);
    const CliResult r =
        RunCli("solve " + Quote(SourcePath("examples/problem-8.40-gear-on-fixed-gear.yaml")) +
               " --format json --set 'beta=" + std::to_string(beta_deg) + " deg'");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j.at("rank"), j.at("rows"));
    EXPECT_TRUE(j.at("warnings").empty());
    const auto& bearing = Named(j.at("reactions"), "bearing");
    const auto& mesh = Named(j.at("reactions"), "mesh");
    EXPECT_TRUE(MatNear(ToVec(mesh.at("point")), ans.C, kSolve, kL));
    EXPECT_TRUE(MatNear(ToVec(bearing.at("point")), ans.a, kSolve, kL));
    // Moments about A's centre: M_J + (p_J - a) x F_J for each reaction on A.
    Vec3 M_cm = Vec3::Zero();
    for (const auto* x : {&bearing, &mesh}) {
      M_cm += ToVec(x->at("moment")) + (ToVec(x->at("point")) - ans.a).cross(ToVec(x->at("force")));
    }
    const double scale = kM * kR * kOmega * kOmega * kL;
    EXPECT_TRUE(MatNear(M_cm, ans.H_dot, kSolve, scale)) << M_cm.transpose();
    const auto& A = Named(j.at("bodies"), "gearA");
    const Vec3 alpha = ToVec(A.at("angular_acceleration"));
    EXPECT_TRUE(MatNear(alpha, Vec3(0, -kOmega * ans.omega * std::cos(beta), 0), kSolve,
                        kOmega * ans.omega));
    // The mesh force is perpendicular to the radial direction (frictionless teeth): it has no
    // x component at this instant.
    EXPECT_NEAR(ToVec(mesh.at("force")).x(), 0.0, kSolve * kM * 9.81);
  }
}

// A run of 2 s: Omega and omega stay constant, A's centre stays at L from D at the height
// L sin(beta), the contact point's velocity w_A x (C - D) stays zero, and H_cm = I w_A
// matches (c) at every sample (turned with the shaft).
TEST(Gears, Problem840SimulationKeepsTheRatesAndTheContact) {
  const CliResult r =
      RunCli("simulate " + Quote(SourcePath("examples/problem-8.40-gear-on-fixed-gear.yaml")) +
             " --format json --out " + Quote(OutDir().string()));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  const auto csv = ReadCsv(j.at("csv").get<std::string>());
  const double beta = 20 * kPi / 180;
  const Answers ans(beta);
  constexpr double kRun = 1e-9;
  const size_t n = csv.at("t").size();
  ASSERT_GE(n, 20u);
  for (size_t i = 0; i < n; ++i) {
    const double t = csv.at("t")[i];
    const Vec3 w_shaft(csv.at("shaft_wx")[i], csv.at("shaft_wy")[i], csv.at("shaft_wz")[i]);
    const Vec3 w_axle(csv.at("axle_wx")[i], csv.at("axle_wy")[i], csv.at("axle_wz")[i]);
    const Vec3 w_A(csv.at("gearA_wx")[i], csv.at("gearA_wy")[i], csv.at("gearA_wz")[i]);
    const Vec3 p_A(csv.at("gearA_x")[i], csv.at("gearA_y")[i], csv.at("gearA_z")[i]);
    EXPECT_TRUE(MatNear(w_shaft, Vec3(0, 0, kOmega), kRun, kOmega)) << t;
    EXPECT_TRUE(MatNear(w_axle, Vec3(0, 0, kOmega), kRun, kOmega)) << t;
    EXPECT_NEAR((w_A - w_axle).norm(), ans.omega, kRun * ans.omega) << t;
    const Eigen::Matrix3d Rz = Eigen::AngleAxisd(kOmega * t, Vec3::UnitZ()).toRotationMatrix();
    EXPECT_TRUE(MatNear(p_A, Vec3(Rz * ans.a), kRun, kL)) << t;
    const Vec3 C = Rz * ans.C;
    EXPECT_LT(w_A.cross(C).norm(), kRun * kOmega * kL) << t;  // v_C = w_A x (C - D) = 0
    // H_cm = I w_A with the thin disk's moments about its axis e and a diameter.
    const Vec3 e = Rz * ans.a.normalized();
    const Vec3 H = kM * kR * kR * (0.5 * w_A.dot(e) * e + 0.25 * (w_A - w_A.dot(e) * e));
    EXPECT_TRUE(MatNear(H, Vec3(Rz * ans.H_cm), kRun, kM * kR * kL * kOmega)) << t;
  }
  // No work by the mesh and the joints; the motor's work is the energy change (constant
  // kinetic energy and height: zero).
  for (const auto& [name, w] : j.at("ledger").at("work_by_constraint").items()) {
    EXPECT_NEAR(w.get<double>(), 0.0, 1e-8) << name;
  }
}

// The planetary set of examples/planetary-gears.yaml: carrier w_c = w_sun r_s / (2 d), planet
// w_p = -w_sun r_s / (2 r_p) (the example's comments), at every sample of a 2 s run.
TEST(Gears, PlanetaryGearRatios) {
  const CliResult r = RunCli("simulate " + Quote(SourcePath("examples/planetary-gears.yaml")) +
                             " --format json --out " + Quote(OutDir().string()));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  const auto csv = ReadCsv(j.at("csv").get<std::string>());
  const double r_s = 0.05, r_p = 0.02, d = r_s + r_p, w_sun = 10.0;
  const double w_c = w_sun * r_s / (2 * d), w_p = -w_sun * r_s / (2 * r_p);
  ASSERT_GE(csv.at("t").size(), 20u);
  for (size_t i = 0; i < csv.at("t").size(); ++i) {
    const double t = csv.at("t")[i];
    EXPECT_NEAR(csv.at("sun_wz")[i], w_sun, 1e-9 * w_sun) << t;
    EXPECT_NEAR(csv.at("carrier_wz")[i], w_c, 1e-9 * w_sun) << t;
    EXPECT_NEAR(csv.at("planet_wz")[i], w_p, 1e-9 * w_sun) << t;
    EXPECT_NEAR(csv.at("planet_x")[i], d * std::cos(w_c * t), 1e-9 * d) << t;
    EXPECT_NEAR(csv.at("planet_y")[i], d * std::sin(w_c * t), 1e-9 * d) << t;
  }
}

// examples/ball-on-turntable.yaml (`rolling: on: table`): the centre circles at 2 Omega / 7
// about c = p0 + (k x v0)/nu (the example's comments), w_z stays constant.
TEST(Gears, BallOnATurntableFromTheScene) {
  const CliResult r = RunCli("simulate " + Quote(SourcePath("examples/ball-on-turntable.yaml")) +
                             " --format json --out " + Quote(OutDir().string()));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  const auto csv = ReadCsv(j.at("csv").get<std::string>());
  const double Omega = 2.0, R = 0.1, nu = 2 * Omega / 7;
  const Vec3 p0(0.3, 0.1, R), v0(-0.25, 0.5, 0);
  const Vec3 c = p0 + Vec3::UnitZ().cross(v0) / nu;
  ASSERT_GE(csv.at("t").size(), 20u);
  for (size_t i = 0; i < csv.at("t").size(); ++i) {
    const double t = csv.at("t")[i];
    const Eigen::Matrix3d Rz = Eigen::AngleAxisd(nu * t, Vec3::UnitZ()).toRotationMatrix();
    const Vec3 p(csv.at("ball_x")[i], csv.at("ball_y")[i], csv.at("ball_z")[i]);
    EXPECT_TRUE(MatNear(p, Vec3(c + Rz * (p0 - c)), 1e-9, 1.0)) << t;
    EXPECT_NEAR(csv.at("ball_wz")[i], 2.0, 1e-9) << t;
    EXPECT_NEAR(csv.at("table_wz")[i], Omega, 1e-9) << t;
  }
}

}  // namespace
}  // namespace chasles::test
