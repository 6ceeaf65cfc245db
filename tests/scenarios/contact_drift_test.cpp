// Long runs in one contact mode: after every accepted step the state is projected onto the
// active contact rows of the current modes (normal gap rows at position level, all active rows
// at velocity level) together with the constraints, so the gap and the slip of a sticking
// point stay at round-off instead of drifting with the integration error. Compare
// tests/properties/constraint_drift_test.cpp for the joints.

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <numbers>

#include <gtest/gtest.h>

#include "chasles/analysis/ledger.h"
#include "chasles/dynamics/contact_solve.h"
#include "chasles/dynamics/newton_euler.h"
#include "chasles/integrate/dormand_prince.h"
#include "chasles/integrate/simulate.h"
#include "chasles/math/rotation.h"
#include "chasles/model/constraints.h"
#include "chasles/model/forces.h"
#include "chasles/model/model.h"
#include "test_support.h"

namespace chasles {
namespace {

using test::Near;
using test::Repeats;

constexpr double kG = 9.81;
constexpr double kViolation = 1e-9;  // the requirement for long runs [m, m/s]

RotationalInertia Diag(double a, double b, double c) {
  return RotationalInertia::FromMatrix(Vec3(a, b, c).asDiagonal());
}

struct DriftReport {
  double max_gap = 0.0;              // largest |gap| of a point in contact [m]
  double max_normal_velocity = 0.0;  // largest |v_n| of a point in contact [m/s]
  double max_slip = 0.0;             // largest slip speed of a sticking point [m/s]
  double energy_drift = 0.0;         // largest |ledger energy residual| / energy scale
  long steps = 0;
  State final_state;
};

// Largest violations of the active rows of the modes `s` carries.
void AddViolations(const Model& model, const State& s, DriftReport& rep) {
  const std::vector<ContactPointOutput> out = CalcContactOutputs(model, s);
  for (size_t p = 0; p < out.size(); ++p) {
    const ContactMode mode = s.contacts[p].mode;
    if (mode == ContactMode::kSeparated) continue;
    rep.max_gap = std::max(rep.max_gap, std::abs(out[p].gap));
    rep.max_normal_velocity = std::max(rep.max_normal_velocity, std::abs(out[p].normal_velocity));
    if (mode == ContactMode::kSticking) {
      rep.max_slip = std::max(rep.max_slip, out[p].slip_velocity_W.norm());
    }
  }
}

// Dormand-Prince with steps of at most h (the controller takes h throughout for these smooth
// motions) for `steps` accepted steps in the modes SelectContactModes picks at the start;
// violations and the ledger residual sampled every 100 steps at the step ends, which are the
// states the integrator continues from.
DriftReport RunDp(const Model& model, State s, double h, long steps, bool project = true) {
  SelectContactModes(model, s);
  AdaptiveOptions opt;
  opt.max_step = h;
  opt.initial_step = h;
  opt.project_contacts = project;
  DormandPrince5Integrator dp(model, opt);
  dp.Initialize(s);
  const State s0 = dp.state();
  const double E0 = CalcLedgerSample(model, s0, s0).energy_scale;
  DriftReport rep;
  for (long i = 1; i <= steps; ++i) {
    dp.Step(std::numeric_limits<double>::infinity());
    if (i % 100 == 0 || i == steps) {
      AddViolations(model, dp.state(), rep);
      const LedgerSample L = CalcLedgerSample(model, dp.state(), s0);
      rep.energy_drift = std::max(rep.energy_drift, std::abs(L.energy_residual) / E0);
    }
  }
  rep.steps = static_cast<long>(dp.stats().steps);
  rep.final_state = dp.state();
  return rep;
}

void Print(const char* what, const DriftReport& r) {
  std::printf(
      "%s: %ld steps, max |gap| %.3g m, max |v_n| %.3g m/s, max slip %.3g m/s, energy drift "
      "%.3g (relative)\n",
      what, r.steps, r.max_gap, r.max_normal_velocity, r.max_slip, r.energy_drift);
}

// A loaded ball: a sphere of radius R whose centre of mass sits e off the geometric centre,
// with unequal principal moments (Chaplygin's ball with an offset mass), rolling without
// slipping on the floor z = 0. The centre's height oscillates with the tilt of the offset, so
// the gap row is curved and the tangential rows are nonholonomic: both drift without the
// projection. Energy is conserved (rolling does no work).
TEST(ContactDrift, LoadedBallRollsOnTheFloorFor1e5Steps) {
  const double m = 1.5, R = 0.1, e = 0.02;
  Model model;
  model.AddBody("ball", MassProperties(m, Vec3::Zero(),
                                       Diag(0.004 * m * 1.0, 0.005 * m * 1.0, 0.006 * m * 1.0)));
  model.AddForceElement(std::make_shared<UniformGravity>("gravity", Vec3(0, 0, -kG)));
  ContactSpec spec;
  spec.name = "floor";
  spec.shape = ContactShape::kSphere;
  spec.body = 0;
  spec.p_BoC_B = Vec3(0, 0, e);  // geometric centre above Bcm (Bo = Bcm) in B
  spec.radius = R;
  spec.mu_s = 10.0;  // sticks throughout
  spec.mu_k = 9.0;
  model.AddContact(spec);
  State s = MakeRestState(model);
  const Mat3 R_WB = RotationFromAxisAngle(Vec3(1, 2, 0).normalized(), 0.7);
  const Vec3 p_WC(0, 0, R);  // geometric centre on the floor
  SetBodyPose(model, 0, p_WC - R_WB * Vec3(0, 0, e), Quat(R_WB), s);
  // No slip at P = C - R z: v_cm = w × (Bcm - P).
  const Vec3 w(3.0, -2.0, 5.0);
  const Vec3 r_PBcm = s.bodies[0].p_WBcm - (p_WC - R * Vec3::UnitZ());
  SetBodyVelocity(model, 0, w.cross(r_PBcm), w, s);
  const DriftReport r = RunDp(model, s, 1e-4, Repeats(100000));
  Print("loaded ball rolling, DP5 h <= 1e-4 s", r);
  // The same run projected only at mode switches, for comparison (docs/contact.md).
  const DriftReport u = RunDp(model, s, 1e-4, Repeats(100000), false);
  Print("  the same without the projection", u);
  EXPECT_GT(std::max(u.max_normal_velocity, u.max_slip),
            std::max(r.max_normal_velocity, r.max_slip));
  EXPECT_EQ(r.final_state.contacts[0].mode, ContactMode::kSticking);
  EXPECT_LT(r.max_gap, kViolation);
  EXPECT_LT(r.max_normal_velocity, kViolation);
  EXPECT_LT(r.max_slip, kViolation);
  EXPECT_LT(r.energy_drift, 1e-9);
}

// A box on an incline sliding on its four bottom vertices (four redundant normal rows,
// least-norm split of N) for 10 s: a = g (sinθ - mu_k cosθ) down the slope, exactly, since the
// normal forces sum to m g cosθ whatever their split.
TEST(ContactDrift, BoxSlidesOnFourVerticesFor1e5Steps) {
  const double m = 3.0, a = 0.2, b = 0.1, c = 0.05, theta = 0.4, mu_k = 0.2;
  Model model;
  model.AddBody(
      "box", MassProperties(m, Vec3::Zero(),
                            Diag(m * (4 * b * b + 4 * c * c) / 12, m * (4 * a * a + 4 * c * c) / 12,
                                 m * (4 * a * a + 4 * b * b) / 12)));
  model.AddForceElement(std::make_shared<UniformGravity>("gravity", Vec3(0, 0, -kG)));
  const Vec3 n(std::sin(theta), 0, std::cos(theta));      // incline normal
  const Vec3 down(std::cos(theta), 0, -std::sin(theta));  // down the slope
  ContactSpec spec;
  spec.name = "incline";
  spec.shape = ContactShape::kBox;
  spec.body = 0;
  spec.half_extents = Vec3(a, b, c);
  spec.plane_normal_W = n;
  spec.mu_s = 0.25;
  spec.mu_k = mu_k;
  model.AddContact(spec);
  State s = MakeRestState(model);
  // Box z along n, x down the slope, resting on the plane; sliding down at 0.5 m/s.
  const Mat3 R_WB = RotationFromAxisAngle(Vec3::UnitY(), theta);
  ASSERT_LT((R_WB.col(2) - n).norm(), 1e-15);
  const double v0 = 0.5;
  SetBodyPose(model, 0, c * n, Quat(R_WB), s);
  SetBodyVelocity(model, 0, v0 * down, Vec3::Zero(), s);
  const double T = 10.0;
  const long steps = Repeats(100000);
  const DriftReport r = RunDp(model, s, T / 1e5, steps);
  Print("box sliding on 4 vertices, DP5 h <= 1e-4 s", r);
  Print("  the same without the projection", RunDp(model, s, T / 1e5, steps, false));
  for (int k = 0; k < 4; ++k) {
    EXPECT_EQ(r.final_state.contacts[static_cast<size_t>(k)].mode, ContactMode::kSliding) << k;
  }
  EXPECT_LT(r.max_gap, kViolation);
  EXPECT_LT(r.max_normal_velocity, kViolation);
  const double t = r.final_state.t;
  const double v = v0 + kG * (std::sin(theta) - mu_k * std::cos(theta)) * t;
  // Every step adds round-off of a few ulps to a speed that grows linearly.
  const double accumulated_round_off = static_cast<double>(steps) * 1e-16;
  EXPECT_TRUE(Near(r.final_state.bodies[0].v_WBcm_W.dot(down), v, accumulated_round_off));
  EXPECT_LT(r.final_state.bodies[0].w_WB_B.norm(), 1e-12);
  EXPECT_LT(r.energy_drift, 1e-9);
}

// The same box resting on the incline (tanθ < mu_s): twelve sticking rows of rank six. It must
// not creep over 1e5 steps.
TEST(ContactDrift, BoxRestsOnFourVerticesFor1e5Steps) {
  const double m = 3.0, a = 0.2, b = 0.1, c = 0.05, theta = 0.2;
  Model model;
  model.AddBody(
      "box", MassProperties(m, Vec3::Zero(),
                            Diag(m * (4 * b * b + 4 * c * c) / 12, m * (4 * a * a + 4 * c * c) / 12,
                                 m * (4 * a * a + 4 * b * b) / 12)));
  model.AddForceElement(std::make_shared<UniformGravity>("gravity", Vec3(0, 0, -kG)));
  const Vec3 n(std::sin(theta), 0, std::cos(theta));
  ContactSpec spec;
  spec.name = "incline";
  spec.shape = ContactShape::kBox;
  spec.body = 0;
  spec.half_extents = Vec3(a, b, c);
  spec.plane_normal_W = n;
  spec.mu_s = 0.5;
  spec.mu_k = 0.4;
  model.AddContact(spec);
  State s = MakeRestState(model);
  SetBodyPose(model, 0, c * n, Quat(RotationFromAxisAngle(Vec3::UnitY(), theta)), s);
  SetBodyVelocity(model, 0, Vec3::Zero(), Vec3::Zero(), s);
  const DriftReport r = RunDp(model, s, 1e-4, Repeats(100000));
  Print("box resting on 4 vertices on an incline, DP5 h <= 1e-4 s", r);
  for (int k = 0; k < 4; ++k) {
    EXPECT_EQ(r.final_state.contacts[static_cast<size_t>(k)].mode, ContactMode::kSticking) << k;
  }
  EXPECT_LT(r.max_gap, kViolation);
  EXPECT_LT(r.max_normal_velocity, kViolation);
  EXPECT_LT(r.max_slip, kViolation);
  EXPECT_LT((r.final_state.bodies[0].p_WBcm - c * n).norm(), kViolation);
}

// A thin disk (I = m R²/4, m R²/4, m R²/2) rolling steadily in a circle on its rim, leaning
// into the turn by β. Derivation (steady precession Ω about the vertical through the circle's
// centre O; the centre C on a circle of radius ρ; e the disk axis, m the unit vector from the
// contact point P to C): ω = Ω z + s e, rolling v_C = ω × R m = Ω z × (C - O) gives
// ω·e = ρΩ/R; dH_C/dt = (I3 ω·e - I1 Ω sinφ) Ω z × e must equal the moment of the contact
// force (m ρ Ω² towards O, m g up) about C; for the thin disk this leaves
//   Ω² = 4 g tanβ / (6 ρ + R sinβ)
// (β the lean towards O). The run goes through Simulate (the hybrid loop): the disk must stay
// sticking, on its rows to round-off, and on its circle.
TEST(ContactDrift, DiskRollsInACircleOnItsRim) {
  const double m = 1.0, R = 0.3, beta = 0.3, rho = 1.0;
  Model model;
  model.AddBody("disk",
                MassProperties(m, Vec3::Zero(), Diag(m * R * R / 4, m * R * R / 4, m * R * R / 2)));
  model.AddForceElement(std::make_shared<UniformGravity>("gravity", Vec3(0, 0, -kG)));
  ContactSpec spec;
  spec.name = "floor";
  spec.shape = ContactShape::kDiskRim;
  spec.body = 0;
  spec.axis_B = Vec3::UnitZ();
  spec.radius = R;
  spec.mu_s = 2.0;
  spec.mu_k = 1.5;
  model.AddContact(spec);
  // φ = -β in the derivation's frame: axis e = (cosφ, 0, sinφ), m = (-sinφ, 0, cosφ); O at the
  // origin, C = (-ρ, 0, R cosφ), v_C = -ρΩ y.
  const double phi = -beta;
  const double Omega = std::sqrt(4 * kG * std::tan(beta) / (6 * rho + R * std::sin(beta)));
  const Vec3 e(std::cos(phi), 0, std::sin(phi));
  const Vec3 C(-rho, 0, R * std::cos(phi));
  const double spin = rho * Omega / R - Omega * std::sin(phi);
  const Vec3 w = Omega * Vec3::UnitZ() + spin * e;
  State s = MakeRestState(model);
  SetBodyPose(model, 0, C, Quat(FrameWithZAxis(e)), s);
  SetBodyVelocity(model, 0, Vec3(0, -rho * Omega, 0), w, s);
  const double period = 2 * std::numbers::pi / Omega;
  SimulationOptions o;
  const long turns = Repeats(20);
  o.t_end = static_cast<double>(turns) * period;
  o.output_interval = period / 50;
  o.adaptive.max_step = 1e-3;
  DriftReport rep;
  double max_radius_error = 0.0, max_height_error = 0.0;
  State s0;
  o.on_sample = [&](const State& x) {
    if (s0.bodies.empty()) s0 = x;
    AddViolations(model, x, rep);
    const Vec3 p = x.bodies[0].p_WBcm;
    max_radius_error = std::max(max_radius_error, std::abs(std::hypot(p.x(), p.y()) - rho));
    max_height_error = std::max(max_height_error, std::abs(p.z() - C.z()));
    const LedgerSample L = CalcLedgerSample(model, x, s0);
    rep.energy_drift = std::max(rep.energy_drift, std::abs(L.energy_residual) / L.energy_scale);
  };
  o.store_samples = false;
  {
    // The same run projected only at mode switches, for comparison (docs/contact.md).
    SimulationOptions u = o;
    u.adaptive.project_contacts = false;
    DriftReport ur;
    u.on_sample = [&](const State& x) { AddViolations(model, x, ur); };
    Simulate(model, s, u);
    std::printf(
        "  the same without the projection: max |gap| %.3g m, max |v_n| %.3g m/s, max slip %.3g "
        "m/s\n",
        ur.max_gap, ur.max_normal_velocity, ur.max_slip);
  }
  const SimulationResult r = Simulate(model, s, o);
  std::printf(
      "disk rolling in a circle, %ld turns (%lld steps): max |gap| %.3g m, max |v_n| %.3g m/s, "
      "max slip %.3g m/s, energy drift %.3g, circle radius error %.3g m, height error %.3g m\n",
      turns, static_cast<long long>(r.stats.steps), rep.max_gap, rep.max_normal_velocity,
      rep.max_slip, rep.energy_drift, max_radius_error, max_height_error);
  EXPECT_EQ(r.contact_events.size(), 1u);  // the initial mode only
  EXPECT_EQ(r.final_state.contacts[0].mode, ContactMode::kSticking);
  EXPECT_LT(rep.max_gap, kViolation);
  EXPECT_LT(rep.max_normal_velocity, kViolation);
  EXPECT_LT(rep.max_slip, kViolation);
  EXPECT_LT(rep.energy_drift, 1e-9);
  // The steady motion from the closed form: the integration error (rtol 1e-9) is all that
  // moves it off the circle.
  EXPECT_LT(max_radius_error, 1e-6 * rho);
  EXPECT_LT(max_height_error, 1e-6 * R);
}

}  // namespace
}  // namespace chasles
