// Rigid rotors: balancing in two planes (analysis/balance.h) against the engine's bearing
// reactions at speed, and whirl on elastic bearings (model/bearing.h) against the closed forms
// of a rigid rotor's forward and backward whirl and its critical speeds.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <Eigen/Eigenvalues>

#include "chasles/analysis/balance.h"
#include "chasles/analysis/initial_state.h"
#include "chasles/analysis/instantaneous.h"
#include "chasles/analysis/modes.h"
#include "chasles/analysis/whirl.h"
#include "chasles/error.h"
#include "chasles/scene/balance.h"
#include "chasles/scene/scene.h"
#include "chasles/scene/scene_error.h"
#include "chasles/scene/study.h"

namespace chasles {
namespace {

/// The scene's study with its initial state settled on the constraints (SettleInitialState),
/// as a run or a solve starts from it.
Study Settled(Study s) {
  std::vector<std::string> warnings;
  s.initial = SettleInitialState(*s.model, s.initial, s.settling, warnings);
  return s;
}

constexpr double kTol = 1e-10;
// Sums of a few products: a few ulps of the largest term.
constexpr double kRoundOff = 1e-14;

// A thin disk (mass m, radius R) on a shaft along z, its centre at (e, 0, z0) and its plane
// tilted by τ about y. About its centre I = R_y(τ) diag(I_d, I_d, I_p) R_y(τ)ᵀ with
// I_d = m R²/4, I_p = m R²/2, so (chapter 8.3's tensor, products -∫xz dm)
//   I_xz = sin τ cos τ (I_p - I_d),
//   U = (m e, 0, 0),  C = -(E - z zᵀ) I z = (-I_xz, 0, 0),  D = C + z0 U,
// and in planes z_A, z_B the corrections u_A = (z_B U - D)/(z_A - z_B),
// u_B = (D - z_A U)/(z_A - z_B), each a mass |u|/r on the x axis (angle 0 or π).
struct TiltedDisk {
  double m = 3.0, R = 0.12, e = 0.0015, z0 = 0.05, tau = 0.02, zA = -0.2, zB = 0.25, r = 0.08;
  double Id() const { return m * R * R / 4; }
  double Ip() const { return m * R * R / 2; }
  double Ixz() const { return std::sin(tau) * std::cos(tau) * (Ip() - Id()); }
};

TEST(Rotor, TiltedEccentricDiskClosedForms) {
  const TiltedDisk d;
  const Mat3 Ry = Eigen::AngleAxisd(d.tau, Vec3::UnitY()).toRotationMatrix();
  const Mat3 I = Ry * Vec3(d.Id(), d.Id(), d.Ip()).asDiagonal() * Ry.transpose();
  RotorAxis axis;
  axis.z_A = d.zA, axis.z_B = d.zB, axis.radius = d.r;
  const double w = 300.0;
  const BalanceReport r = CalcBalance(d.m, Vec3(d.e, 0, d.z0), I, axis, w, 6.3);
  const double U = d.m * d.e, C = -d.Ixz(), D = C + d.z0 * U;
  EXPECT_NEAR(r.static_unbalance_W.x(), U, kTol * U);
  EXPECT_NEAR(r.couple_unbalance_W.x(), C, kTol * std::abs(C));
  const double uA = (d.zB * U - D) / (d.zA - d.zB), uB = (D - d.zA * U) / (d.zA - d.zB);
  EXPECT_NEAR(r.corrections[0].mass, std::abs(uA) / d.r, kTol * std::abs(uA) / d.r);
  EXPECT_NEAR(r.corrections[1].mass, std::abs(uB) / d.r, kTol * std::abs(uB) / d.r);
  EXPECT_NEAR(std::cos(r.corrections[0].angle), uA > 0 ? 1.0 : -1.0, 1e-15);
  EXPECT_NEAR(std::cos(r.corrections[1].angle), uB > 0 ? 1.0 : -1.0, 1e-15);
  for (const BalanceCorrection& c : r.corrections) {  // in (-pi, pi]: -0 along e2 is +pi, not -pi
    EXPECT_GT(c.angle, -std::numbers::pi);
    EXPECT_LE(c.angle, std::numbers::pi);
  }
  // Round-off of the corrections' sums: relative to the largest term, z u.
  const double moments = std::abs(d.zA * uA) + std::abs(d.zB * uB) + std::abs(D);
  EXPECT_LT(r.residual_static, kRoundOff * U);
  EXPECT_LT(r.residual_couple, kRoundOff * moments);
  // ISO 21940-11: U_per = m G/ω with G in mm/s.
  EXPECT_NEAR(r.permissible, d.m * 6.3e-3 / w, 1e-15);
}

// The same disk in a scene, spinning at ω on a spherical bearing at z_A and a radial one at
// z_B (no gravity): the engine's reactions (SolveInstantaneous, the chapter's Euler equations
// with the full tensor) are the bearing forces ω² u of the closed form; with the two
// correction masses added as point masses, they vanish to round-off.
std::string DiskRotorScene(const TiltedDisk& d, double w, const std::string& extra_parts) {
  return fmt::format(R"(
chasles: 1
bodies:
  - name: rotor
    points: {{hub: [0, 0, 0]}}
    parts:
      - {{shape: disk, radius: {R}, mass: {m}, position: [{e}, 0, {z0}],
          rotation: {{axis: [0, 1, 0], angle: {tau}}}}}
{extra}
    initial: {{velocity_point: hub, velocity: [0, 0, 0], angular_velocity: [0, 0, {w}]}}
gravity: [0, 0, 0]
joints:
  - {{name: A, type: spherical, parent: world, child: rotor, at: [0, 0, {zA}]}}
  - {{name: B, type: point_on_line, parent: world, child: rotor, at: [0, 0, {zB}], axis: [0, 0, 1]}}
)",
                     fmt::arg("R", d.R), fmt::arg("m", d.m), fmt::arg("e", d.e),
                     fmt::arg("z0", d.z0), fmt::arg("tau", d.tau), fmt::arg("extra", extra_parts),
                     fmt::arg("w", w), fmt::arg("zA", d.zA), fmt::arg("zB", d.zB));
}

TEST(Rotor, CorrectionZeroesTheBearingReactionsAtSpeed) {
  const TiltedDisk d;
  const double w = 300.0;
  const Study s = Settled(BuildStudy(LoadSceneText(DiskRotorScene(d, w, ""), "rotor.yaml"), 1.0));
  const Model& model = *s.model;
  const BodyState& b = s.initial.bodies[0];
  const Mat3 R = b.q_WB.toRotationMatrix();
  RotorAxis axis;
  axis.z_A = d.zA, axis.z_B = d.zB, axis.radius = d.r;
  const BalanceReport r = CalcBalance(model.body(0).mass(), b.p_WBcm,
                                      R * model.body(0).I_BBcm_B() * R.transpose(), axis, w);
  const InstantaneousSolution before = SolveInstantaneous(model, s.initial);
  const double scale = r.bearing_forces_W[0].norm() + r.bearing_forces_W[1].norm();
  for (int k = 0; k < 2; ++k) {
    const Vec3 F = before.reactions[static_cast<size_t>(k)].F_Jc_W;
    EXPECT_LT((F - r.bearing_forces_W[static_cast<size_t>(k)]).norm(), kTol * scale) << k;
  }
  std::string parts;
  for (const BalanceCorrection& c : r.corrections) {
    parts += fmt::format(
        "      - {{shape: point, mass: {:.17g}, position: [{:.17g}, {:.17g}, {:.17g}]}}\n", c.mass,
        c.p_W.x(), c.p_W.y(), c.p_W.z());
  }
  const Study t =
      Settled(BuildStudy(LoadSceneText(DiskRotorScene(d, w, parts), "rotor.yaml"), 1.0));
  const InstantaneousSolution after = SolveInstantaneous(*t.model, t.initial);
  for (const ReactionReport& rr : after.reactions) {
    EXPECT_LT(rr.F_Jc_W.norm(), 1e-12 * scale) << rr.name;
  }
}

// A rigid rotor (mass m, moments I_t across and I_p about the axis at its centre of mass) on
// two isotropic radial bearings of stiffness k_A, k_B at z_A, z_B from the centre of mass,
// spinning at Ω. With R = X + iY the centre's displacement and φ = θ_y - i θ_x the tilt,
// Euler's equations for small tilts give I_t φ̈ - i I_p Ω φ̇ = Σ z_j F_j, and with
//   K0 = Σ k_j, K1 = Σ k_j z_j, K2 = Σ k_j z_j², R, φ ∝ e^{iωt}:
//   (K0 - m ω²)(K2 - I_t ω² + I_p Ω ω) - K1² = 0,
// a quartic in ω: positive roots whirl forward, negative backward. Its roots from the
// companion matrix, |ω| sorted, are the modes' frequencies. A critical speed has ω = Ω:
//   (K0 - m Ω²)(K2 - (I_t - I_p) Ω²) = K1².
std::vector<double> SignedWhirlRoots(double m, double It, double Ip, double K0, double K1,
                                     double K2, double W) {
  // m It ω⁴ - m Ip Ω ω³ - (m K2 + K0 It) ω² + K0 Ip Ω ω + K0 K2 - K1² = 0
  const double a4 = m * It;
  const double c[4] = {(K0 * K2 - K1 * K1) / a4, K0 * Ip * W / a4, -(m * K2 + K0 * It) / a4,
                       -m * Ip * W / a4};
  Eigen::Matrix4d companion = Eigen::Matrix4d::Zero();
  for (int i = 1; i < 4; ++i) companion(i, i - 1) = 1.0;
  for (int i = 0; i < 4; ++i) companion(i, 3) = -c[i];
  const Eigen::Vector4cd roots = companion.eigenvalues();
  std::vector<double> w;
  for (int i = 0; i < 4; ++i) w.push_back(roots[i].real());
  return w;
}

std::vector<double> WhirlClosedForm(double m, double It, double Ip, double K0, double K1, double K2,
                                    double W) {
  std::vector<double> w = SignedWhirlRoots(m, It, Ip, K0, K1, K2, W);
  for (double& x : w) x = std::abs(x);
  std::sort(w.begin(), w.end());
  return w;
}

struct RotorOnBearings {
  double m = 8.0, rho = 0.05, L = 0.6;  // a solid cylinder along z, centred at z = zc
  double zc = 0.0, zA = -0.25, zB = 0.25, kA = 2e5, kB = 2e5;
  double disk_m = 0.0, disk_R = 0.2, disk_z = 0.0;  // an overhung disk (0: none)
  std::string Scene(double W) const {
    std::string disk;
    if (disk_m > 0) {
      disk = fmt::format("      - {{shape: disk, radius: {}, mass: {}, position: [0, 0, {}]}}\n",
                         disk_R, disk_m, disk_z);
    }
    return fmt::format(R"(
chasles: 1
parameters:
  spin: {W} rad/s
bodies:
  - name: rotor
    parts:
      - {{shape: cylinder, radius: {rho}, length: {L}, mass: {m}, position: [0, 0, {zc}]}}
{disk}    initial: {{angular_velocity: [0, 0, spin]}}
gravity: [0, 0, 0]
forces:
  - {{type: bearing, name: A, body: rotor, at: [0, 0, {zA}], axis: [0, 0, 1], stiffness: {kA} N/m}}
  - {{type: bearing, name: B, body: rotor, at: [0, 0, {zB}], axis: [0, 0, 1], stiffness: {kB} N/m}}
)",
                       fmt::arg("W", W), fmt::arg("rho", rho), fmt::arg("L", L), fmt::arg("m", m),
                       fmt::arg("zc", zc), fmt::arg("disk", disk), fmt::arg("zA", zA),
                       fmt::arg("zB", zB), fmt::arg("kA", kA), fmt::arg("kB", kB));
  }
  // Mass properties about the whole rotor's centre of mass.
  double Mass() const { return m + disk_m; }
  double Zcm() const { return (m * zc + disk_m * disk_z) / Mass(); }
  double Ip() const { return m * rho * rho / 2 + disk_m * disk_R * disk_R / 2; }
  double It() const {
    const double z = Zcm();
    return m * (3 * rho * rho + L * L) / 12 + m * (zc - z) * (zc - z) +
           disk_m * disk_R * disk_R / 4 + disk_m * (disk_z - z) * (disk_z - z);
  }
  double K(int power) const {
    const double a = zA - Zcm(), b = zB - Zcm();
    return kA * std::pow(a, power) + kB * std::pow(b, power);
  }
};

ModalAnalysis RotorModes(const RotorOnBearings& r, double W) {
  const Study s = Settled(BuildStudy(LoadSceneText(r.Scene(W), "rotor.yaml"), 1.0));
  return AnalyseModes(*s.model, FindOperatingPoint(*s.model, s.initial));
}

std::vector<double> WhirlOf(const ModalAnalysis& a) {
  std::vector<double> w;
  for (const Mode& m : a.modes) {
    if (!m.rigid) w.push_back(std::abs(m.eigenvalue.imag()));
  }
  std::sort(w.begin(), w.end());
  return w;
}

void ExpectWhirl(const RotorOnBearings& r, double W) {
  const ModalAnalysis a = RotorModes(r, W);
  const std::vector<double> want =
      WhirlClosedForm(r.Mass(), r.It(), r.Ip(), r.K(0), r.K(1), r.K(2), W);
  const std::vector<double> got = WhirlOf(a);
  ASSERT_EQ(got.size(), 4u) << "spin " << W;
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(got[i], want[i], kTol * want[i]) << "spin " << W;
  EXPECT_TRUE(a.stable);
}

TEST(Rotor, SymmetricRotorWhirlAndCriticalSpeeds) {
  const RotorOnBearings r;
  for (double W : {0.0, 100.0, 400.0, 1000.0}) ExpectWhirl(r, W);
  // Critical speeds: translation Ω² = K0/m (K1 = 0); forward tilt Ω² = K2/(I_t - I_p).
  const double c1 = std::sqrt(r.K(0) / r.Mass()), c2 = std::sqrt(r.K(2) / (r.It() - r.Ip()));
  std::vector<double> grid;
  for (int i = 0; i <= 20; ++i) grid.push_back(20.0 * i);
  const std::vector<CriticalSpeed> cs =
      FindCriticalSpeeds([&](double W) { return RotorModes(r, W); }, grid);
  std::vector<double> speeds;
  for (const CriticalSpeed& c : cs) speeds.push_back(c.speed);
  ASSERT_GE(speeds.size(), 2u);
  for (double want : {c1, c2}) {
    EXPECT_TRUE(std::any_of(speeds.begin(), speeds.end(),
                            [&](double s) { return std::abs(s - want) < kTol * want; }))
        << "no critical speed at " << want;
  }
}

TEST(Rotor, OverhungGyroscopicDiskWhirl) {
  RotorOnBearings r;
  r.zA = -0.28, r.zB = 0.1, r.kA = 3e5, r.kB = 1e5;
  r.disk_m = 5.0, r.disk_R = 0.2, r.disk_z = 0.28;
  for (double W : {0.0, 150.0, 600.0}) ExpectWhirl(r, W);
}

// The same quartic's real roots, signed: ω > 0 whirls forward (with the spin), ω < 0 backward.
std::vector<double> SignedWhirl(const RotorOnBearings& r, double W) {
  return SignedWhirlRoots(r.Mass(), r.It(), r.Ip(), r.K(0), r.K(1), r.K(2), W);
}

/// CalcWhirl's frequencies [rad/s] in direction `d` at the point `p`, ascending.
std::vector<double> Whirling(const WhirlPoint& p, WhirlDirection d) {
  std::vector<double> out;
  for (const WhirlMode& m : p.modes) {
    if (m.direction == d) out.push_back(std::abs(m.eigenvalue.imag()));
  }
  std::sort(out.begin(), out.end());
  return out;
}

void ExpectDirections(const RotorOnBearings& r, const std::vector<double>& spins) {
  const Study s = Settled(BuildStudy(LoadSceneText(r.Scene(0.0), "rotor.yaml"), 1.0));
  const WhirlMap map = CalcWhirl(*s.model, s.initial, 0, Vec3::UnitZ(), spins);
  ASSERT_EQ(map.points.size(), spins.size());
  for (size_t k = 0; k < spins.size(); ++k) {
    SCOPED_TRACE(fmt::format("spin {} rad/s", spins[k]));
    std::vector<double> fwd, bwd;
    for (const double w : SignedWhirl(r, spins[k])) (w > 0.0 ? fwd : bwd).push_back(std::abs(w));
    std::sort(fwd.begin(), fwd.end()), std::sort(bwd.begin(), bwd.end());
    const WhirlPoint& p = map.points[k];
    EXPECT_DOUBLE_EQ(p.speed, spins[k]);
    if (spins[k] == 0.0) {  // at rest forward and backward are one: no direction
      EXPECT_EQ(Whirling(p, WhirlDirection::kNone).size(), 4u);
      continue;
    }
    const std::vector<double> got_f = Whirling(p, WhirlDirection::kForward),
                              got_b = Whirling(p, WhirlDirection::kBackward);
    ASSERT_EQ(got_f.size(), fwd.size());
    ASSERT_EQ(got_b.size(), bwd.size());
    for (size_t i = 0; i < fwd.size(); ++i) EXPECT_NEAR(got_f[i], fwd[i], kTol * fwd[i]);
    for (size_t i = 0; i < bwd.size(); ++i) EXPECT_NEAR(got_b[i], bwd[i], kTol * bwd[i]);
  }
}

// Forward and backward whirl told apart by the modes' shapes (analysis/whirl.h) against the
// signs of the quartic's roots. The symmetric rotor's translation (K1 = 0) whirls at
// √(K0/m) both ways at every spin: a repeated eigenvalue whose eigenspace the whirl form splits.
TEST(Rotor, WhirlDirectionsAgainstTheQuarticsSigns) {
  ExpectDirections(RotorOnBearings{}, {0.0, 100.0, 400.0, 1000.0});
  RotorOnBearings overhung;
  overhung.zA = -0.28, overhung.zB = 0.1, overhung.kA = 3e5, overhung.kB = 1e5;
  overhung.disk_m = 5.0, overhung.disk_R = 0.2, overhung.disk_z = 0.28;
  ExpectDirections(overhung, {0.0, 150.0, 600.0});
}

// Seeded random rotors (shaft mass, length, bearing places and stiffnesses, an overhung disk)
// at seeded spins: every whirl frequency and its direction against the quartic's signed roots.
TEST(Rotor, SeededRandomRotorsWhirlInTheQuarticsDirections) {
  std::mt19937_64 rng(20261128);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int k = 0; k < 6; ++k) {
    RotorOnBearings r;
    r.m = 2.0 + 10.0 * u(rng), r.L = 0.3 + 0.6 * u(rng);
    r.zA = -0.5 * r.L * (0.3 + 0.7 * u(rng)), r.zB = 0.5 * r.L * (0.3 + 0.7 * u(rng));
    r.kA = 1e4 * std::pow(100.0, u(rng)), r.kB = 1e4 * std::pow(100.0, u(rng));
    r.disk_m = 5.0 * u(rng), r.disk_R = 0.1 + 0.2 * u(rng), r.disk_z = 0.5 * r.L * u(rng);
    SCOPED_TRACE(fmt::format("rotor {}", k));
    ExpectDirections(r, {0.0, 50.0 + 500.0 * u(rng), 800.0 + 1000.0 * u(rng)});
  }
}

// The critical speeds with their directions: translation Ω² = K0/m both ways (K1 = 0), the
// tilt forward where I_t Ω² - I_p Ω² = K2 and backward where I_t Ω² + I_p Ω² = K2 (ω = ±Ω
// in K2 - I_t ω² + I_p Ω ω = 0).
TEST(Rotor, CriticalSpeedsWithTheirDirections) {
  const RotorOnBearings r;
  const Study s = Settled(BuildStudy(LoadSceneText(r.Scene(0.0), "rotor.yaml"), 1.0));
  std::vector<double> grid;
  for (int i = 0; i <= 20; ++i) grid.push_back(20.0 * i);
  const WhirlMap map = CalcWhirl(*s.model, s.initial, 0, Vec3::UnitZ(), grid);
  const double both = std::sqrt(r.K(0) / r.Mass());
  const double fwd = std::sqrt(r.K(2) / (r.It() - r.Ip()));
  const double bwd = std::sqrt(r.K(2) / (r.It() + r.Ip()));
  ASSERT_EQ(map.critical_speeds.size(), 3u);
  using D = WhirlDirection;
  const std::vector<std::pair<double, std::vector<D>>> want = {
      {both, {D::kForward, D::kBackward}}, {bwd, {D::kBackward}}, {fwd, {D::kForward}}};
  for (size_t i = 0; i < want.size(); ++i) {
    EXPECT_NEAR(map.critical_speeds[i].speed, want[i].first, kTol * want[i].first);
    EXPECT_EQ(map.critical_speeds[i].directions, want[i].second) << "at " << want[i].first;
  }
}

// The scene's balance (scene/balance.h: the options read as the command line writes them,
// analysis/balance.h's AnalyseRotorBalance at the settled initial pose) is the closed form of
// the tilted eccentric disk; held by joints, not bearings, it has no whirl rows.
TEST(Rotor, SceneBalanceIsTheClosedForm) {
  const TiltedDisk d;
  const Scene scene = LoadSceneText(DiskRotorScene(d, 300.0, ""), "rotor.yaml");
  BalanceOptions options;
  options.body = "rotor";
  options.planes = fmt::format("{} m, {} m", d.zA, d.zB);
  options.radius = fmt::format("{} m", d.r);
  options.speed = "300 rad/s";
  options.grade = 6.3;
  const RotorBalance b = AnalyseRotorBalance(MakeBalanceDefinition(scene, options));
  const double U = d.m * d.e, C = -d.Ixz(), D = C + d.z0 * U;
  const double uA = (d.zB * U - D) / (d.zA - d.zB), uB = (D - d.zA * U) / (d.zA - d.zB);
  EXPECT_EQ(b.body, "rotor");
  EXPECT_NEAR(b.balance.static_unbalance_W.x(), U, kTol * U);
  EXPECT_NEAR(b.balance.couple_unbalance_W.x(), C, kTol * std::abs(C));
  EXPECT_NEAR(b.balance.corrections[0].mass, std::abs(uA) / d.r, kTol * std::abs(uA) / d.r);
  EXPECT_NEAR(b.balance.corrections[1].mass, std::abs(uB) / d.r, kTol * std::abs(uB) / d.r);
  EXPECT_NEAR(b.balance.bearing_forces_W[0].norm(), 300.0 * 300.0 * std::abs(uA),
              kTol * 300.0 * 300.0 * std::abs(uA));
  EXPECT_NEAR(b.balance.permissible, d.m * 6.3e-3 / 300.0, 1e-15);
  EXPECT_FALSE(b.whirl.has_value());
  // Whirl spins asked of a rotor no bearing holds: an error at the option.
  options.whirl = "0 rpm:100 rpm:3";
  try {
    MakeBalanceDefinition(scene, options);
    ADD_FAILURE() << "no error";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.key(), "--whirl");
  }
}

// CalcRotorWhirl's spins: 21 from 0 to twice the speed, or without one to twice the highest
// whirl frequency at rest (the quartic's largest root at Ω = 0); given spins as they are; no
// rows for a rotor no bearing holds, and an error when spins are asked of it.
TEST(Rotor, RotorWhirlChoosesItsSpins) {
  const RotorOnBearings r;
  const Study s = Settled(BuildStudy(LoadSceneText(r.Scene(0.0), "rotor.yaml"), 1.0));
  const std::optional<WhirlMap> at =
      CalcRotorWhirl(*s.model, s.initial, 0, Vec3::UnitZ(), {}, 150.0);
  ASSERT_TRUE(at.has_value());
  ASSERT_EQ(at->points.size(), 21u);
  for (size_t k = 0; k < 21; ++k) EXPECT_EQ(at->points[k].speed, 15.0 * static_cast<double>(k));
  const std::optional<WhirlMap> rest =
      CalcRotorWhirl(*s.model, s.initial, 0, Vec3::UnitZ(), {}, std::nan(""));
  ASSERT_TRUE(rest.has_value());
  ASSERT_EQ(rest->points.size(), 21u);
  const double top = WhirlClosedForm(r.Mass(), r.It(), r.Ip(), r.K(0), r.K(1), r.K(2), 0.0)[3];
  EXPECT_NEAR(rest->points[20].speed, 2.0 * top, kTol * 2.0 * top);
  const std::optional<WhirlMap> given =
      CalcRotorWhirl(*s.model, s.initial, 0, Vec3::UnitZ(), WhirlSpeedGrid(10.0, 30.0, 3), 150.0);
  ASSERT_TRUE(given.has_value());
  ASSERT_EQ(given->points.size(), 3u);
  EXPECT_EQ(given->points[1].speed, 20.0);
  EXPECT_EQ(given->points[2].speed, 30.0);
  const Study free = Settled(
      BuildStudy(LoadSceneText(DiskRotorScene(TiltedDisk{}, 300.0, ""), "rotor.yaml"), 1.0));
  EXPECT_FALSE(CalcRotorWhirl(*free.model, free.initial, 0, Vec3::UnitZ(), {}, 150.0));
  EXPECT_THROW(CalcRotorWhirl(*free.model, free.initial, 0, Vec3::UnitZ(), {0.0, 1.0}, 150.0),
               InputError);
}

}  // namespace
}  // namespace chasles
