// End-to-end: the chapter's joint and reaction examples through `chasles solve` (with --sweep)
// and `chasles simulate`, against closed forms derived here and in the examples' comments:
// the rod on an accelerating cart (Section 8.2.2), the disk rolling on a circle with its axle
// pivoting at O (Section 8.3, Example 8.5), a spinning disk carried by a turning shaft
// (Problem 8.31), reactions in the child's frame, and the kinetic energy and momenta `solve`
// reports.

#include <algorithm>
#include <cmath>
#include <filesystem>
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

// `solve` is one linear solve: round-off of its sums, relative.
constexpr double kSolve = 1e-9;
// `simulate` at tolerance 1e-12 to 1e-13 with the constraint projection, relative.
constexpr double kRun = 1e-7;
constexpr double kG = 9.80665;
constexpr double kPi = 3.14159265358979323846;

std::filesystem::path OutDir() {
  return test::OutDir("reactions");
}

// Runs `chasles simulate` and reads its CSV.
std::map<std::string, std::vector<double>> SimulateCsv(const std::string& example,
                                                       const std::string& extra = "") {
  const CliResult r = RunCli("simulate " + Quote(SourcePath(example)) + " --format json --out " +
                             Quote(OutDir().string()) + " " + extra);
  if (r.exit_code != 0) {
    throw std::runtime_error("chasles simulate " + example + " failed: " + r.err);
  }
  return ReadCsv(nlohmann::json::parse(r.out).at("csv").get<std::string>());
}

// `chasles solve --sweep` as a table: the columns by name, one value per swept value.
struct Table {
  std::map<std::string, std::vector<double>> col;
  size_t rows = 0;
};

Table Sweep(const std::string& example, const std::string& sweep) {
  const CliResult r =
      RunCli("solve " + Quote(SourcePath(example)) + " --sweep " + Quote(sweep) + " --format json");
  if (r.exit_code != 0) throw std::runtime_error("chasles solve failed: " + r.err);
  const auto j = nlohmann::json::parse(r.out);
  Table t;
  const auto& names = j.at("columns");
  for (const auto& row : j.at("rows")) {
    for (size_t c = 0; c < names.size(); ++c) {
      t.col[names[c].get<std::string>()].push_back(row.at(c).get<double>());
    }
    ++t.rows;
  }
  return t;
}

double At3(const nlohmann::json& obj, const char* key, int i) {
  return obj.at(key).at(i).get<double>();
}

Vec3 Column3(const Table& t, const std::string& prefix, size_t k) {
  return Vec3(t.col.at(prefix + "x").at(k), t.col.at(prefix + "y").at(k),
              t.col.at(prefix + "z").at(k));
}

// ---- Section 8.2.2: rod pinned to a cart with prescribed acceleration ----------------------
// The scene's values: rod m = 1.2 kg, L = 0.9 m; cart acceleration a = 3 m/s². θ is the
// rod's swing back from the downward vertical, a rotation about +y (θ̇ = ω_y):
//   θ̈ = (3/(2L)) (a cos θ - g sin θ)                  (8.65)
//   θ̇² = (3g/L) ((a/g) sin θ + cos θ - 1)  from rest  (8.68)
struct CartRod {
  double m = 1.2, L = 0.9, a = 3.0;
  double Alpha(double th) const { return 1.5 / L * (a * std::cos(th) - kG * std::sin(th)); }
  double OmegaSquared(double th) const {
    return 3 * kG / L * (a / kG * std::sin(th) + std::cos(th) - 1);
  }
  // Size of θ̈ over the swing, for relative tolerances.
  double AlphaScale() const { return 1.5 / L * std::hypot(a, kG); }
};

TEST(CartRodSection822, SolveSweepFollowsEqs865And868) {
  const CartRod cr;
  const Table t = Sweep("examples/section-8.2.2-cart-rod.yaml", "theta=0 deg:30 deg:7");
  ASSERT_EQ(t.rows, 7u);
  for (size_t k = 0; k < t.rows; ++k) {
    const double theta = 5.0 * static_cast<double>(k) * kPi / 180;
    ASSERT_NEAR(t.col.at("theta")[k], theta, 1e-15);
    EXPECT_NEAR(t.col.at("rod_aly")[k], cr.Alpha(theta), kSolve * cr.AlphaScale()) << theta;
    // The cart accelerates at a whatever the rod does.
    EXPECT_NEAR(t.col.at("cart_ax")[k], cr.a, kSolve * cr.a);
    // ω from the rod's angular momentum about its centre, H_y = (m L²/12) θ̇ (the state the
    // scene builds from eq. 8.68), and its kinetic energy about the fixed-at-this-instant pin
    // (the cart starts at rest): T = ½ I_O θ̇² with I_O = m L²/3.
    const double w = t.col.at("rod_Hy")[k] / (cr.m * cr.L * cr.L / 12);
    EXPECT_NEAR(w * w, cr.OmegaSquared(theta), kSolve * 3 * kG / cr.L) << theta;
    const double T = 0.5 * (cr.m * cr.L * cr.L / 3) * cr.OmegaSquared(theta);
    EXPECT_NEAR(t.col.at("rod_T")[k], T, kSolve * (1 + T)) << theta;
    EXPECT_NEAR(t.col.at("T")[k], T, kSolve * (1 + T)) << theta;
    EXPECT_NEAR(t.col.at("cart_T")[k], 0.0, kSolve);
  }
}

TEST(CartRodSection822, SimulationFollowsEqs865And868AtEveryRow) {
  const CartRod cr;
  const auto csv = SimulateCsv("examples/section-8.2.2-cart-rod.yaml");
  const size_t n = csv.at("t").size();
  ASSERT_GE(n, 200u);
  double theta_max = 0.0;
  for (size_t i = 0; i < n; ++i) {
    // A rotation about y only: ZYX pitch is θ (|θ| < 90°), roll and yaw stay 0.
    const double theta = csv.at("rod_pitch")[i];
    theta_max = std::max(theta_max, theta);
    EXPECT_NEAR(csv.at("rod_aly")[i], cr.Alpha(theta), kRun * cr.AlphaScale())
        << "t = " << csv.at("t")[i];
    const double w = csv.at("rod_wy")[i];
    EXPECT_NEAR(w * w, cr.OmegaSquared(theta), kRun * 3 * kG / cr.L) << "t = " << csv.at("t")[i];
    EXPECT_NEAR(csv.at("cart_x")[i], 0.5 * cr.a * csv.at("t")[i] * csv.at("t")[i], kRun);
  }
  // It swings out to where θ̇ = 0 again: θ = 2 atan(a/g).
  EXPECT_NEAR(theta_max, 2 * std::atan(cr.a / kG), 2e-3);
}

// The rail, the pin and the driver all act at the cart's origin: when the cart has travelled,
// their points still coincide up to round-off, and the redundancy analysis at the end of the
// run must see the same rank as at the start (11 rows: the rail's 5, the pin's 5, the driver's
// 1; rank 10), not a spread of 1e-16 m that weighs the moments by 1e16.
TEST(CartRodSection822, RedundancyAtTheEndOfTheRunIsTheSameAsAtTheStart) {
  const CliResult r =
      RunCli("simulate " + Quote(SourcePath("examples/section-8.2.2-cart-rod.yaml")) +
             " --format json --out " + Quote(OutDir().string()));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  bool found = false;
  for (const auto& w : j.at("warnings")) {
    const std::string text = w.get<std::string>();
    if (text.find("the constraints are redundant") == std::string::npos) continue;
    found = true;
    EXPECT_NE(text.find("(11 rows, rank 10)"), std::string::npos) << text;
    EXPECT_NE(text.find("mechanism's length 0.2074 m"), std::string::npos) << text;
  }
  EXPECT_TRUE(found);
}

// ---- Section 8.3 and Example 8.5: disk rolling on a circle, axle pivoting at O -------------
// The scene's values m = 2 kg, r = 0.1 m: total mass 25/16 m, centre 41/25 r from O.
//   N = ½ m Ω² r + (41/32) m g                              (8.109)
//   R = -(41/16) m Ω² r j + ((9/32) m g - ½ m Ω² r) k       (8.111)
// at t = 0 with the axle along +y.
struct RollingDisk {
  double m = 2.0, r = 0.1;
  double N(double W) const { return 0.5 * m * W * W * r + 41.0 / 32 * m * kG; }
  Vec3 R(double W) const {
    return Vec3(0, -41.0 / 16 * m * W * W * r, 9.0 / 32 * m * kG - 0.5 * m * W * W * r);
  }
  // H_O = [I_O] ω with [I_O] = diag(5, 1/2, 5) m r² (eq. 8.96) and ω = Ω (k - 2 j).
  Vec3 H_O(double W) const { return m * r * r * W * Vec3(0, -1, 5); }
  double Scale(double W) const { return m * (kG + W * W * r); }
};

TEST(RollingDiskSection83, SolveGivesNAndRAtSeveralPrecessionRates) {
  const RollingDisk d;
  const Table t = Sweep("examples/section-8.3-rolling-disk.yaml", "Omega=1 rad/s:10 rad/s:4");
  ASSERT_EQ(t.rows, 4u);
  for (size_t k = 0; k < t.rows; ++k) {
    const double W = 1.0 + 3.0 * static_cast<double>(k);
    ASSERT_NEAR(t.col.at("Omega")[k], W, 1e-14);
    const double scale = d.Scale(W);
    // The floor's force on the assembly (through A, vertical) and the pivot's at O.
    EXPECT_NEAR(t.col.at("floor_Fz")[k], d.N(W), kSolve * scale) << "Omega = " << W;
    EXPECT_NEAR(t.col.at("floor_Fx")[k], 0.0, kSolve * scale);
    EXPECT_NEAR(t.col.at("floor_Fy")[k], 0.0, kSolve * scale);
    const Vec3 R = Column3(t, "pivot_F", k);
    EXPECT_LT((R - d.R(W)).norm(), kSolve * scale)
        << "Omega = " << W << ": R = " << R.transpose() << ", expected " << d.R(W).transpose();
    EXPECT_NEAR(Column3(t, "pivot_M", k).norm(), 0.0, kSolve * scale * d.r);
    // Example 8.5, moments about O with the reported forces and angular momentum:
    //   r_OA × N k + r_OG × (-(25/16) m g k) = dH_O/dt = Ω k × H_O.
    const Vec3 H_O = Column3(t, "assembly_HO", k);
    EXPECT_LT((H_O - d.H_O(W)).norm(), kSolve * d.H_O(W).norm()) << "Omega = " << W;
    const Vec3 M_O = Vec3(0, 2 * d.r, 0).cross(Vec3(0, 0, t.col.at("floor_Fz")[k])) +
                     Vec3(0, 41.0 / 25 * d.r, 0).cross(Vec3(0, 0, -25.0 / 16 * d.m * kG));
    EXPECT_LT((M_O - Vec3(0, 0, W).cross(H_O)).norm(), kSolve * scale * d.r);
    // T = ½ ωᵀ [I_O] ω = ½ m r² (½ (2Ω)² + 5 Ω²) = (7/2) m r² Ω²: all rotational about O,
    // split into ½ m v_G² and the rest about G.
    const double T = 3.5 * d.m * d.r * d.r * W * W;
    EXPECT_NEAR(t.col.at("T")[k], T, kSolve * T);
    const double T_trans = 0.5 * 25.0 / 16 * d.m * std::pow(41.0 / 25 * d.r * W, 2);
    EXPECT_NEAR(t.col.at("T_trans")[k], T_trans, kSolve * T);
    EXPECT_NEAR(t.col.at("T_rot")[k], T - T_trans, kSolve * T);
  }
}

// The same motion with the axle a slender rod of its own (a zero moment about OA) on the
// spherical pivot and the disk on a revolute about it: the floor's force on the disk is N and
// the pivot's force on the axle R, exactly as for the lumped assembly (eq. 8.109, 8.111).
TEST(RollingDiskSection83, AxleAsItsOwnRodGivesTheSameNAndR) {
  const RollingDisk d;
  const Table t =
      Sweep("examples/section-8.3-disk-and-axle-bodies.yaml", "Omega=1 rad/s:10 rad/s:4");
  ASSERT_EQ(t.rows, 4u);
  for (size_t k = 0; k < t.rows; ++k) {
    const double W = 1.0 + 3.0 * static_cast<double>(k);
    const double scale = d.Scale(W);
    EXPECT_NEAR(t.col.at("floor_Fz")[k], d.N(W), kSolve * scale) << "Omega = " << W;
    EXPECT_NEAR(t.col.at("floor_Fx")[k], 0.0, kSolve * scale);
    EXPECT_NEAR(t.col.at("floor_Fy")[k], 0.0, kSolve * scale);
    const Vec3 R = Column3(t, "pivot_F", k);
    EXPECT_LT((R - d.R(W)).norm(), kSolve * scale)
        << "Omega = " << W << ": R = " << R.transpose() << ", expected " << d.R(W).transpose();
  }
}

TEST(RollingDiskSection83, SimulationKeepsTheSteadyMotion) {
  const RollingDisk d;
  const double W = 4.0;  // the scene's Omega
  const auto csv = SimulateCsv("examples/section-8.3-rolling-disk.yaml");
  const size_t n = csv.at("t").size();
  ASSERT_GE(n, 50u);
  for (size_t i = 0; i < n; ++i) {
    const double t = csv.at("t")[i];
    EXPECT_NEAR(csv.at("floor_Fz")[i], d.N(W), kRun * d.Scale(W)) << "t = " << t;
    // The axle turns at Ω about z and stays horizontal; the spin keeps -2Ω.
    EXPECT_NEAR(csv.at("assembly_wz")[i], W, kRun * W) << "t = " << t;
    EXPECT_NEAR(csv.at("assembly_z")[i], 0.0, kRun * d.r);
    EXPECT_NEAR(std::hypot(csv.at("assembly_x")[i], csv.at("assembly_y")[i]), 41.0 / 25 * d.r,
                kRun * d.r);
    // In the assembly's frame B (which spins with the disk about the axle, B's y axis) the
    // pivot force keeps its component along the axle, -(41/16) m Ω² r, and its size across it,
    // |(9/32) m g - ½ m Ω² r|.
    const Vec3 R_B(csv.at("pivot_Fx_B")[i], csv.at("pivot_Fy_B")[i], csv.at("pivot_Fz_B")[i]);
    EXPECT_NEAR(R_B.y(), d.R(W).y(), kRun * d.Scale(W)) << "t = " << t;
    EXPECT_NEAR(std::hypot(R_B.x(), R_B.z()), std::abs(d.R(W).z()), kRun * d.Scale(W));
  }
}

// ---- Problem 8.31: spinning disk on a housing carried by a turning shaft -------------------
// The scene's values m = 1.5 kg, R = 0.12 m, β = 60°, Ω = 60 rpm; I3 = m R²/2, I1 = m R²/4.
//   M_A = -[(I3 - I1) Ω² sin β cos β + I3 Ω ω_s sin β] y'   (the shaft's y axis)
TEST(DiskOnRotatingShaftProblem831, SolveGivesTheSupportMoment) {
  const double m = 1.5, R = 0.12, beta = kPi / 3, W = 2 * kPi;
  const double I3 = m * R * R / 2, I1 = m * R * R / 4;
  const auto M = [&](double ws) {
    return -((I3 - I1) * W * W * std::sin(beta) * std::cos(beta) + I3 * W * ws * std::sin(beta));
  };
  const Table t =
      Sweep("examples/problem-8.31-disk-on-rotating-shaft.yaml", "omega_s=0 rpm:600 rpm:4");
  ASSERT_EQ(t.rows, 4u);
  for (size_t k = 0; k < t.rows; ++k) {
    const double ws = 200.0 * static_cast<double>(k) * 2 * kPi / 60;
    ASSERT_NEAR(t.col.at("omega_s")[k], ws, 1e-12);
    const double scale = I3 * W * (W + ws);
    const Vec3 M_A = Column3(t, "plate_M", k);
    EXPECT_NEAR(M_A.y(), M(ws), kSolve * scale) << "omega_s = " << ws;
    EXPECT_NEAR(M_A.x(), 0.0, kSolve * scale);
    EXPECT_NEAR(M_A.z(), 0.0, kSolve * scale);
    EXPECT_LT(Column3(t, "plate_F", k).norm(), kSolve * scale / R);
    // The motors hold constant rates against no moment about their axes.
    EXPECT_NEAR(t.col.at("motor_Mx")[k], 0.0, kSolve * scale);
    // The housing's weld passes the disk's load on: the same moment (about O; no force).
    EXPECT_NEAR(t.col.at("mount_My")[k], M(ws), kSolve * scale);
  }
}

TEST(DiskOnRotatingShaftProblem831, SupportMomentIsConstantInTheShaftFrame) {
  const double m = 1.5, R = 0.12, beta = kPi / 3, W = 2 * kPi, ws = 10 * kPi;
  const double I3 = m * R * R / 2, I1 = m * R * R / 4;
  const double M =
      -((I3 - I1) * W * W * std::sin(beta) * std::cos(beta) + I3 * W * ws * std::sin(beta));
  const auto csv = SimulateCsv("examples/problem-8.31-disk-on-rotating-shaft.yaml");
  for (size_t i = 0; i < csv.at("t").size(); ++i) {
    const double t = csv.at("t")[i];
    const Vec3 M_B(csv.at("plate_Mx_B")[i], csv.at("plate_My_B")[i], csv.at("plate_Mz_B")[i]);
    EXPECT_LT((M_B - Vec3(0, M, 0)).norm(), kRun * std::abs(M)) << "t = " << t;
    // In W it turns with the shaft: (0, M cos Ωt, M sin Ωt).
    const Vec3 M_W(csv.at("plate_Mx")[i], csv.at("plate_My")[i], csv.at("plate_Mz")[i]);
    EXPECT_LT((M_W - M * Vec3(0, std::cos(W * t), std::sin(W * t))).norm(), kRun * std::abs(M))
        << "t = " << t;
  }
}

// ---- Reactions in the child's frame -----------------------------------------------------
// The pinned rod (examples/pinned-rod.yaml): at every row the B-frame columns are the W-frame
// reaction turned into the rod's frame, F_B = R_WBᵀ F_W (R_WB from the quaternion columns).
TEST(ReactionsInBodyFrame, AreTheWorldReactionTurnedIntoTheChildFrame) {
  const auto csv = SimulateCsv("examples/pinned-rod.yaml", "--columns quaternion,reactions");
  const double mg = 2.0 * kG;
  ASSERT_GE(csv.at("t").size(), 10u);
  for (size_t i = 0; i < csv.at("t").size(); ++i) {
    const Eigen::Quaterniond q(csv.at("rod_qw")[i], csv.at("rod_qx")[i], csv.at("rod_qy")[i],
                               csv.at("rod_qz")[i]);
    const Mat3 R_WB = q.normalized().toRotationMatrix();
    for (const char* what : {"F", "M"}) {
      const std::string p = std::string("pin_") + what;
      const Vec3 W(csv.at(p + "x")[i], csv.at(p + "y")[i], csv.at(p + "z")[i]);
      const Vec3 B(csv.at(p + "x_B")[i], csv.at(p + "y_B")[i], csv.at(p + "z_B")[i]);
      // The CSV prints 17 significant digits; the quaternion is unit to round-off.
      EXPECT_LT((B - R_WB.transpose() * W).norm(), 1e-12 * (mg + W.norm()))
          << what << " at t = " << csv.at("t")[i];
    }
  }
  // The rod's frame has x along the rod: at release (horizontal) the pin holds it up with
  // m g / 4 (examples/pinned-rod.yaml), along B's z as along W's z.
  EXPECT_NEAR(csv.at("pin_Fz_B").front(), mg / 4, kRun * mg);
}

// ---- Reactions in the parent's frame -----------------------------------------------------
// Problem 8.31's bearing holds the disk in the housing, its parent, which turns with the shaft
// at Ω about x. The bearing supplies the disk's whole dH/dt about O (the spin driver supplies
// none about the disk's axis e, which is perpendicular to y'; O does not move, so no force):
// in the housing's frame the moment is constant, (0, M, 0) with
// M = -[(I3 - I1) Ω² sin β cos β + I3 Ω ω_s sin β] (the example's comments), while in W it
// turns with the shaft. At every row the P-frame columns are the W-frame reaction turned into
// the housing's frame, R_WPᵀ F_W, and the child-frame ones turned from the disk's frame into
// the housing's, R_PC F_B = R_WPᵀ R_WC F_B; for the plate, a joint to the world, P is W.
TEST(ReactionsInParentFrame, BearingMomentIsConstantInTheHousingFrame) {
  const double m = 1.5, R = 0.12, beta = kPi / 3, W = 2 * kPi, ws = 10 * kPi;
  const double I3 = m * R * R / 2, I1 = m * R * R / 4;
  const double M =
      -((I3 - I1) * W * W * std::sin(beta) * std::cos(beta) + I3 * W * ws * std::sin(beta));
  const auto csv = SimulateCsv("examples/problem-8.31-disk-on-rotating-shaft.yaml",
                               "--columns quaternion,reactions");
  const auto vec = [&](const std::string& prefix, const std::string& suffix, size_t i) {
    return Vec3(csv.at(prefix + "x" + suffix)[i], csv.at(prefix + "y" + suffix)[i],
                csv.at(prefix + "z" + suffix)[i]);
  };
  const auto rotation = [&](const std::string& body, size_t i) {
    const Eigen::Quaterniond q(csv.at(body + "_qw")[i], csv.at(body + "_qx")[i],
                               csv.at(body + "_qy")[i], csv.at(body + "_qz")[i]);
    return Mat3(q.normalized().toRotationMatrix());
  };
  ASSERT_GE(csv.at("t").size(), 10u);
  for (size_t i = 0; i < csv.at("t").size(); ++i) {
    const double t = csv.at("t")[i];
    const Mat3 R_WP = rotation("housing", i), R_WC = rotation("disk", i);
    for (const char* what : {"F", "M"}) {
      const std::string p = std::string("bearing_") + what;
      const Vec3 P = vec(p, "_P", i), B = vec(p, "_B", i), in_W = vec(p, "", i);
      // The CSV prints 17 significant digits; the quaternions are unit to round-off.
      EXPECT_LT((P - R_WP.transpose() * in_W).norm(), 1e-12 * std::abs(M)) << what << " t = " << t;
      EXPECT_LT((P - R_WP.transpose() * R_WC * B).norm(), 1e-12 * std::abs(M))
          << what << " t = " << t;
      const std::string plate = std::string("plate_") + what;
      EXPECT_EQ(vec(plate, "_P", i), vec(plate, "", i)) << what << " t = " << t;
    }
    EXPECT_LT((vec("bearing_M", "_P", i) - Vec3(0, M, 0)).norm(), kRun * std::abs(M))
        << "t = " << t;
    EXPECT_LT(vec("bearing_F", "_P", i).norm(), kRun * std::abs(M) / R) << "t = " << t;
  }
  // `solve` gives it too, in the JSON (at t = 0 the housing's frame is W's).
  const CliResult r =
      RunCli("solve " + Quote(SourcePath("examples/problem-8.31-disk-on-rotating-shaft.yaml")) +
             " --format json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  for (const auto& x : j.at("reactions")) {
    if (x.at("name") != "bearing") continue;
    EXPECT_LT((ToVec(x.at("moment_parent")) - Vec3(0, M, 0)).norm(), kSolve * std::abs(M));
  }
}

// ---- Energy and momenta in the `solve` report ----------------------------------------------
// The pinned rod at release is at rest: T = 0, p = 0. The cart and rod at θ = 20°: the text
// report lists T, p, H and H_O per body and for all bodies.
TEST(SolveEnergyMomentum, JsonAndTextReportThem) {
  const CartRod cr;
  const double theta = 20 * kPi / 180;
  const CliResult r = RunCli("solve " + Quote(SourcePath("examples/section-8.2.2-cart-rod.yaml")) +
                             " --set 'theta=20 deg' --format json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  const auto& em = j.at("energy_momentum");
  ASSERT_EQ(em.at("bodies").size(), 2u);
  const auto& rod = em.at("bodies")[1];
  ASSERT_EQ(rod.at("name"), "rod");
  // The rod turns about the pin (at rest at t = 0, at the origin) at θ̇ about +y: its centre
  // G = (L/2)(-sin θ, 0, -cos θ) moves at v = θ̇ ŷ × G, p = m v, H about G = (m L²/12) θ̇ ŷ,
  // H_O = I_O θ̇ ŷ = (m L²/3) θ̇ ŷ, T = ½ I_O θ̇², of which ½ m v² = ½ m (L/2)² θ̇².
  const double w = std::sqrt(cr.OmegaSquared(theta));
  const Vec3 G = 0.5 * cr.L * Vec3(-std::sin(theta), 0, -std::cos(theta));
  const Vec3 p = cr.m * Vec3(0, w, 0).cross(G);
  EXPECT_LT((ToVec(rod.at("linear_momentum")) - p).norm(), kSolve * p.norm());
  EXPECT_NEAR(At3(rod, "angular_momentum_cm", 1), cr.m * cr.L * cr.L / 12 * w, kSolve);
  EXPECT_NEAR(At3(rod, "angular_momentum_origin", 1), cr.m * cr.L * cr.L / 3 * w, kSolve);
  const double T = 0.5 * cr.m * cr.L * cr.L / 3 * w * w;
  EXPECT_NEAR(rod.at("kinetic_energy").get<double>(), T, kSolve * T);
  EXPECT_NEAR(rod.at("kinetic_translational").get<double>(),
              0.5 * cr.m * 0.25 * cr.L * cr.L * w * w, kSolve * T);
  EXPECT_NEAR(em.at("total").at("kinetic_energy").get<double>(), T, kSolve * T);
  const CliResult text =
      RunCli("solve " + Quote(SourcePath("examples/section-8.2.2-cart-rod.yaml")) +
             " --set 'theta=20 deg'");
  ASSERT_EQ(text.exit_code, 0) << text.err;
  EXPECT_THAT(text.out, ::testing::HasSubstr("Kinetic energy and momenta"));
  EXPECT_THAT(text.out, ::testing::HasSubstr("all bodies"));
  EXPECT_THAT(text.out, ::testing::HasSubstr("H_O ["));
}

}  // namespace
}  // namespace chasles::test
