// Free rigid-body motions with closed-form answers: torque-free axisymmetric precession (also
// in a non-principal body frame), the heavy symmetric top in steady precession, a projectile
// with linear drag, a spring-mass oscillator, and a ground-hit event.

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "chasles/analysis/ledger.h"
#include "chasles/integrate/simulate.h"
#include "chasles/math/quaternion.h"
#include "chasles/math/rotation.h"
#include "chasles/model/forces.h"
#include "chasles/model/model.h"
#include "test_support.h"

namespace chasles {
namespace {

using test::MatNear;
using test::Near;

constexpr double kTol = 1e-8;  // tight-tolerance DP5 against closed forms

SimulationOptions Tight(double t_end, double dt_out) {
  SimulationOptions o;
  o.t_end = t_end;
  o.output_interval = dt_out;
  o.adaptive.rtol = 1e-12;
  o.adaptive.atol = 1e-14;
  return o;
}

// Torque-free axisymmetric body (A = A1 = A2, C = A3): H is fixed in W and the symmetry axis
// e3 turns about it at the constant rate |H| / A (Poinsot; Goldstein 5.6): ω = H/A + κ e3 with
// κ = ω3 (A - C)/A, and ė3 = ω × e3 = (|H|/A) Ĥ × e3.
void CheckTorqueFreePrecession(const Mat3& R_BBp) {
  const double A = 1.5, C = 2.5;
  const Mat3 I_B = Vec3(A, A, C).asDiagonal();
  const Mat3 I_Bp = R_BBp.transpose() * I_B * R_BBp;  // the same body described in frame B'
  Model model;
  model.AddBody("disc", MassProperties(4.0, Vec3::Zero(), RotationalInertia::FromMatrix(I_Bp)));
  const Quat q_WB(RotationFromEuler("ZYX", Vec3(0.3, -0.2, 0.5)));
  const Vec3 w_B(0.7, -0.2, 3.0);
  State s0 = MakeRestState(model);
  s0.bodies[0].q_WB = Quat(q_WB.toRotationMatrix() * R_BBp);
  s0.bodies[0].w_WB_B = R_BBp.transpose() * w_B;
  const Vec3 H_W = q_WB * (I_B * w_B);
  const Vec3 e3_0 = q_WB * Vec3::UnitZ();
  const SimulationResult r = Simulate(model, s0, Tight(5.0, 0.5));
  for (const State& s : r.samples) {
    const Vec3 e3 = s.bodies[0].q_WB * (R_BBp.transpose() * Vec3::UnitZ());
    const Vec3 expected = RotationFromAxisAngle(H_W, H_W.norm() / A * s.t) * e3_0;
    EXPECT_TRUE(MatNear(e3, expected, kTol, 1.0)) << "t = " << s.t;
  }
}

TEST(TorqueFree, AxisymmetricPrecessionRateIsHOverA) {
  CheckTorqueFreePrecession(Mat3::Identity());
}

TEST(TorqueFree, NonPrincipalBodyFrameGivesTheSameWorldMotion) {
  CheckTorqueFreePrecession(RotationFromEuler("ZXZ", Vec3(0.4, 1.1, -0.7)));
}

// Heavy symmetric top about a fixed pivot O, centre of mass at distance l on the axis e3.
// Steady precession at rate Ω about the vertical with tilt θ and axial spin ω3 = e3·ω:
// H_O = A Ω (z - cosθ e3) + C ω3 e3 turns at Ω about z, so dH/dt = Ω (C ω3 - A Ω cosθ) z × e3,
// and it must equal the gravity moment l e3 × (-m g z) = m g l (z × e3):
//   A cosθ Ω² - C ω3 Ω + m g l = 0,   Ω = (C ω3 - sqrt(C² ω3² - 4 A cosθ m g l)) / (2 A cosθ)
// (slow precession). The pivot is modelled exactly with the free-body API: the body's reference
// point sits at O with the inertia about O (A = A_cm + m l²), gravity m g acts at the centre
// of mass point (0, 0, l) and the pivot reaction -m g at O, so the net force is zero and O
// stays put; the moment about O is exactly the top's.
TEST(HeavyTop, SteadyPrecessionRate) {
  const double m = 0.5, l = 0.04, g = 9.81, A = 2e-4 + m * l * l, C = 3e-4;
  const double theta = 0.5, w3 = 120.0;
  const double ct = std::cos(theta);
  const double Omega =
      (C * w3 - std::sqrt(C * C * w3 * w3 - 4 * A * ct * m * g * l)) / (2 * A * ct);
  Model model;
  const BodyIndex top =
      model.AddBody("top", MassProperties(m, Vec3::Zero(), RotationalInertia(A, A, C)));
  model.AddForceElement(AppliedForce::Constant("weight", top, Vec3(0, 0, l), Vec3(0, 0, -m * g),
                                               VectorFrame::kWorld));
  model.AddForceElement(
      AppliedForce::Constant("pivot", top, Vec3::Zero(), Vec3(0, 0, m * g), VectorFrame::kWorld));
  State s0 = MakeRestState(model);
  const Mat3 R0 = RotationFromAxisAngle(Vec3::UnitY(), theta);
  const Vec3 e3 = R0.col(2);
  const Vec3 w_W = Omega * Vec3::UnitZ() + (w3 - Omega * ct) * e3;
  s0.bodies[0].q_WB = Quat(R0);
  s0.bodies[0].w_WB_B = R0.transpose() * w_W;
  const SimulationResult r = Simulate(model, s0, Tight(3.0, 0.25));
  for (const State& s : r.samples) {
    const Vec3 axis = s.bodies[0].q_WB * Vec3::UnitZ();
    const Vec3 expected = RotationFromAxisAngle(Vec3::UnitZ(), Omega * s.t) * e3;
    EXPECT_TRUE(MatNear(axis, expected, kTol, 1.0)) << "t = " << s.t;
    EXPECT_LT(s.bodies[0].p_WBcm.norm(), 1e-12);
  }
}

// m v' = m g - c v: v = v_T + (v0 - v_T) e^{-ct/m}, v_T = m g / c;
// p = p0 + v_T t + (v0 - v_T)(m/c)(1 - e^{-ct/m}).
TEST(Projectile, LinearDragMatchesClosedForm) {
  const double m = 2.0, c = 0.5;
  const Vec3 g(0, 0, -9.81), v0(10, 0, 20), p0(0, 0, 1);
  Model model;
  const BodyIndex ball =
      model.AddBody("ball", MassProperties(m, Vec3::Zero(), RotationalInertia(0.01, 0.01, 0.01)));
  model.AddForceElement(std::make_shared<UniformGravity>("gravity", g));
  model.AddForceElement(std::make_shared<LinearDrag>("air", ball, c, 0.0));
  State s0 = MakeRestState(model);
  s0.bodies[0].p_WBcm = p0;
  s0.bodies[0].v_WBcm_W = v0;
  const SimulationResult r = Simulate(model, s0, Tight(4.0, 0.5));
  const Vec3 vT = m * g / c;
  for (const State& s : r.samples) {
    const double e = std::exp(-c * s.t / m);
    EXPECT_TRUE(MatNear(s.bodies[0].v_WBcm_W, Vec3(vT + (v0 - vT) * e), kTol, 20.0));
    EXPECT_TRUE(MatNear(s.bodies[0].p_WBcm, Vec3(p0 + vT * s.t + (v0 - vT) * (m / c) * (1 - e)),
                        kTol, 20.0));
  }
}

// Without drag z(t) = z0 + vz t - g t²/2 reaches 0 at t* = (vz + sqrt(vz² + 2 g z0)) / g.
TEST(Projectile, GroundHitEventLocatedTo1e10Seconds) {
  const double g = 9.81, z0 = 1.0, vz = 20.0;
  Model model;
  model.AddBody("ball", MassProperties(1.0, Vec3::Zero(), RotationalInertia(0.01, 0.01, 0.01)));
  model.AddForceElement(std::make_shared<UniformGravity>("gravity", Vec3(0, 0, -g)));
  State s0 = MakeRestState(model);
  s0.bodies[0].p_WBcm = Vec3(0, 0, z0);
  s0.bodies[0].v_WBcm_W = Vec3(3, 0, vz);
  SimulationOptions o = Tight(100.0, 0.0);
  o.adaptive.rtol =
      1e-8;  // a quadratic is integrated exactly; the event is found on the interpolant
  o.events.push_back({"ground", [](const Model&, const State& s) { return s.bodies[0].p_WBcm.z(); },
                      EventDirection::kFalling, EventAction::kStop});
  const SimulationResult r = Simulate(model, s0, o);
  const double t_star = (vz + std::sqrt(vz * vz + 2 * g * z0)) / g;
  ASSERT_TRUE(r.stopped_by_event);
  ASSERT_EQ(r.events.size(), 1u);
  EXPECT_NEAR(r.events[0].t, t_star, 1e-10);
  EXPECT_NEAR(r.final_state.t, t_star, 1e-10);
  EXPECT_NEAR(r.final_state.bodies[0].p_WBcm.z(), 0.0, 1e-9);
}

// x(t) = L0 + a cos(ω t), ω = sqrt(k/m): period 2π sqrt(m/k); energy ½ k a².
TEST(SpringMass, PeriodAndEnergy) {
  const double m = 2.0, k = 50.0, L0 = 1.0, a = 0.2;
  Model model;
  const BodyIndex b =
      model.AddBody("mass", MassProperties(m, Vec3::Zero(), RotationalInertia(0.1, 0.1, 0.1)));
  model.AddForceElement(
      std::make_shared<SpringDamper>("spring", b, Vec3::Zero(), kWorld, Vec3::Zero(), L0, k, 0.0));
  State s0 = MakeRestState(model);
  s0.bodies[0].p_WBcm = Vec3(L0 + a, 0, 0);
  const double period = 2 * std::numbers::pi * std::sqrt(m / k);
  SimulationOptions o = Tight(2.5 * period, period / 8);
  // vx goes from + to - once per period, at t = T, 2T (vx = -a ω sin ω t).
  o.events.push_back({"turn", [](const Model&, const State& s) { return s.bodies[0].v_WBcm_W.x(); },
                      EventDirection::kFalling, EventAction::kRecord});
  const SimulationResult r = Simulate(model, s0, o);
  ASSERT_EQ(r.events.size(), 2u);
  EXPECT_NEAR(r.events[0].t, period, 1e-10);
  EXPECT_NEAR(r.events[1].t, 2 * period, 1e-10);
  const double w = std::sqrt(k / m);
  for (const State& s : r.samples) {
    EXPECT_TRUE(Near(s.bodies[0].p_WBcm.x(), L0 + a * std::cos(w * s.t), kTol, 1.0));
    const LedgerSample L = CalcLedgerSample(model, s, s0);
    EXPECT_TRUE(Near(L.mechanical_energy, 0.5 * k * a * a, 1e-10));
  }
}

}  // namespace
}  // namespace chasles
