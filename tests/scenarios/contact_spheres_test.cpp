// Body-body contact of two spheres (ContactShape::kSphereSphere): central and oblique impacts
// with Newton's restitution and Coulomb friction, and three spheres in a row hit at once (the
// simultaneous-impact LCP). Closed forms derived in the comments; no gravity.

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "chasles/analysis/momentum.h"
#include "chasles/dynamics/contact_solve.h"
#include "chasles/integrate/simulate.h"
#include "chasles/model/model.h"
#include "test_support.h"

namespace chasles {
namespace {

using test::Near;

// Impulses are one linear solve: exact to round-off of the problem's scale.
constexpr double kImpulseRel = 1e-12;
// Event times are located to 1e-12 s; speeds are exact in free flight.
constexpr double kEventRel = 1e-9;

MassProperties Ball(double m, double R) {
  const double I = 0.4 * m * R * R;  // solid sphere, Appendix A
  return MassProperties(m, Vec3::Zero(), RotationalInertia::FromMatrix(Vec3(I, I, I).asDiagonal()));
}

// Sphere on `body` (radius R) against the sphere on `other` (radius R_o), both centred at the
// bodies' centres of mass.
ContactSpec SphereSphere(const std::string& name, BodyIndex body, double R, BodyIndex other,
                         double R_o, double mu_s, double mu_k, double e) {
  ContactSpec c;
  c.name = name;
  c.shape = ContactShape::kSphereSphere;
  c.body = body;
  c.radius = R;
  c.other_body = other;
  c.other_radius = R_o;
  c.mu_s = mu_s;
  c.mu_k = mu_k;
  c.restitution = e;
  return c;
}

double Kinetic(const Model& model, const State& s) {
  return CalcTranslationalKineticEnergy(model, s) + CalcRotationalKineticEnergy(model, s);
}

// ---------------------------------------------------------------------------------------
// (a) Head-on impact, velocities along the line of centres x. Newton's law on the relative
// normal velocity, v2' - v1' = -e (v2 - v1), with m1 v1' + m2 v2' = m1 v1 + m2 v2, gives
//   v1' = (m1 v1 + m2 v2 - m2 e (v1 - v2)) / (m1 + m2),
//   v2' = (m1 v1 + m2 v2 + m1 e (v1 - v2)) / (m1 + m2),
// and the kinetic energy lost ΔT = ½ μ (1 - e²) (v1 - v2)², μ = m1 m2 / (m1 + m2).
TEST(ContactSpheres, HeadOnImpactWithRestitution) {
  const double m1 = 1.5, m2 = 0.7, R1 = 0.1, R2 = 0.05, v1 = 2.0, v2 = -0.5;
  for (const double e : {0.0, 0.4, 1.0}) {
    Model model;
    model.AddBody("a", Ball(m1, R1));
    model.AddBody("b", Ball(m2, R2));
    // The contact is on b against a: its normal points from a towards b (+x).
    model.AddContact(SphereSphere("hit", 1, R2, 0, R1, 0.3, 0.3, e));
    State s = MakeRestState(model);
    SetBodyPose(model, 0, Vec3::Zero(), Quat::Identity(), s);
    SetBodyPose(model, 1, Vec3(R1 + R2, 0, 0), Quat::Identity(), s);
    SetBodyVelocity(model, 0, Vec3(v1, 0, 0), Vec3::Zero(), s);
    SetBodyVelocity(model, 1, Vec3(v2, 0, 0), Vec3::Zero(), s);
    const Vec3 P0 = CalcLinearMomentum(model, s);
    const double T0 = Kinetic(model, s);
    const ImpactResult r = ResolveImpacts(model, s);
    ASSERT_EQ(r.impulses.size(), 1u);
    const double mu = m1 * m2 / (m1 + m2);
    const double v1p = (m1 * v1 + m2 * v2 - m2 * e * (v1 - v2)) / (m1 + m2);
    const double v2p = (m1 * v1 + m2 * v2 + m1 * e * (v1 - v2)) / (m1 + m2);
    const double scale = std::abs(v1) + std::abs(v2);
    EXPECT_NEAR(s.bodies[0].v_WBcm_W.x(), v1p, kImpulseRel * scale) << e;
    EXPECT_NEAR(s.bodies[1].v_WBcm_W.x(), v2p, kImpulseRel * scale) << e;
    EXPECT_NEAR(r.impulses[0].approach_speed, v1 - v2, kImpulseRel * scale);
    // Impulse on b: m2 (v2' - v2) = μ (1 + e)(v1 - v2).
    EXPECT_TRUE(Near(r.impulses[0].normal_impulse, mu * (1 + e) * (v1 - v2), kImpulseRel));
    // Momentum exactly; no spin from a central impact.
    EXPECT_LE((CalcLinearMomentum(model, s) - P0).norm(), kImpulseRel * (m1 + m2) * scale);
    EXPECT_EQ(s.bodies[0].w_WB_B.norm(), 0.0);
    EXPECT_EQ(s.bodies[1].w_WB_B.norm(), 0.0);
    const double dT = 0.5 * mu * (1 - e * e) * (v1 - v2) * (v1 - v2);
    EXPECT_NEAR(T0 - Kinetic(model, s), dT, kImpulseRel * T0) << e;
    EXPECT_NEAR(r.kinetic_energy_before - r.kinetic_energy_after, dT, kImpulseRel * T0);
    EXPECT_FALSE(r.frictionless_fallback);
  }
}

// The same collision run by the hybrid simulation: the spheres start apart, the touch-down is
// located at t_c = gap / (v1 - v2), the impact gives the velocities above and the spheres
// separate; the ledger books ΔT as impact work.
TEST(ContactSpheres, HeadOnCollisionSimulated) {
  const double m1 = 1.5, m2 = 0.7, R1 = 0.1, R2 = 0.05, v1 = 2.0, v2 = -0.5, e = 0.6;
  const double gap = 0.3;
  Model model;
  model.AddBody("a", Ball(m1, R1));
  model.AddBody("b", Ball(m2, R2));
  model.AddContact(SphereSphere("hit", 1, R2, 0, R1, 0.3, 0.3, e));
  State s = MakeRestState(model);
  SetBodyPose(model, 1, Vec3(R1 + R2 + gap, 0, 0), Quat::Identity(), s);
  SetBodyVelocity(model, 0, Vec3(v1, 0, 0), Vec3::Zero(), s);
  SetBodyVelocity(model, 1, Vec3(v2, 0, 0), Vec3::Zero(), s);
  SimulationOptions o;
  o.t_end = 0.5;
  o.adaptive.rtol = 1e-12;
  o.adaptive.atol = 1e-14;
  const SimulationResult r = Simulate(model, s, o);
  ASSERT_EQ(r.impacts.size(), 1u);
  EXPECT_TRUE(Near(r.impacts[0].t, gap / (v1 - v2), kEventRel));
  const double mu = m1 * m2 / (m1 + m2);
  EXPECT_TRUE(
      Near(r.impacts[0].energy_lost, 0.5 * mu * (1 - e * e) * (v1 - v2) * (v1 - v2), kEventRel));
  const double v1p = (m1 * v1 + m2 * v2 - m2 * e * (v1 - v2)) / (m1 + m2);
  const double v2p = (m1 * v1 + m2 * v2 + m1 * e * (v1 - v2)) / (m1 + m2);
  EXPECT_TRUE(Near(r.final_state.bodies[0].v_WBcm_W.x(), v1p, kEventRel));
  EXPECT_TRUE(Near(r.final_state.bodies[1].v_WBcm_W.x(), v2p, kEventRel));
  EXPECT_EQ(r.final_state.contacts[0].mode, ContactMode::kSeparated);
}

// ---------------------------------------------------------------------------------------
// (b) Oblique impact with friction. Sphere 1 (body, radius R1) hits sphere 2 (other, radius
// R2); n is the unit line of centres from 2 towards 1, the contact arms are r1 = -R1 n and
// r2 = +R2 n, and P (on 1; -P on 2) = P_n n + P_t. With I_i = 2/5 m_i R_i²:
//   Δv1 = P/m1, Δv2 = -P/m2, Δw1 = (r1 × P)/I1, Δw2 = -(r2 × P)/I2.
// Relative velocity of the contact points, v_rel = v1 + w1 × r1 - v2 - w2 × r2, changes by
//   normal:     Δv_n = P_n / μ                             (μ = m1 m2/(m1 + m2)),
//   tangential: Δv_t = P_t (1/m1 + 1/m2) + R1²/I1 P_t + R2²/I2 P_t = (7/2) P_t / μ
// ((n × P_t) × n = P_t for P_t ⊥ n). The parts decouple: every restitution law gives
// P_n = -(1 + e) μ v_n. Integrating the impulse (Routh), the slip falls along itself at
// (7/2) mu_k / μ per unit P_n while sliding, so it stops within the impulse iff
//   (2/7)|v_t| <= mu_k (1 + e)|v_n|,
// and then sticks (keeping v_t = 0 needs no friction): P_t = -(2/7) μ v_t. Otherwise it
// slides throughout: P_t = -mu_k P_n v_t/|v_t|.
// Impulses act at the contact point C on both bodies equal and opposite: total momentum and
// total angular momentum about C are conserved, and the kinetic energy never increases.
void ObliqueImpact(double phi, bool expect_sticking) {
  const double m1 = 1.0, m2 = 2.5, R1 = 0.1, R2 = 0.15, v = 3.0, mu_s = 0.3, mu_k = 0.2, e = 0.5;
  Model model;
  model.AddBody("one", Ball(m1, R1));
  model.AddBody("two", Ball(m2, R2));
  model.AddContact(SphereSphere("hit", 0, R1, 1, R2, mu_s, mu_k, e));
  // Sphere 2 ahead of sphere 1 along d = (cos phi, sin phi, 0); sphere 1 moves along +x with
  // a spin about z and a spin about the line of centres; sphere 2 spins about y.
  const Vec3 d(std::cos(phi), std::sin(phi), 0.0);
  State s = MakeRestState(model);
  const Vec3 w1(0.3, -0.2, 4.0), w2(0.0, 2.0, 0.0), v1(v, 0, 0), v2(0.1, 0, 0);
  SetBodyPose(model, 1, (R1 + R2) * d, Quat::Identity(), s);
  SetBodyVelocity(model, 0, v1, w1, s);
  SetBodyVelocity(model, 1, v2, w2, s);
  const Vec3 n = -d, r1 = -R1 * n, r2 = R2 * n;
  const Vec3 p_WC = R1 * d;  // the contact point
  const Vec3 v_rel = v1 + w1.cross(r1) - v2 - w2.cross(r2);
  const double v_n = v_rel.dot(n);
  const Vec3 v_t = v_rel - v_n * n;
  ASSERT_LT(v_n, 0.0);
  const double mu = m1 * m2 / (m1 + m2);
  const double Pn = -(1 + e) * mu * v_n;
  const bool sticks = 2.0 / 7.0 * v_t.norm() <= mu_k * (1 + e) * std::abs(v_n);
  ASSERT_EQ(sticks, expect_sticking) << "the test's geometry no longer selects the regime";
  const Vec3 Pt = sticks ? Vec3(-2.0 / 7.0 * mu * v_t) : Vec3(-mu_k * Pn * v_t.normalized());
  const Vec3 P = Pn * n + Pt;
  const double I1 = 0.4 * m1 * R1 * R1, I2 = 0.4 * m2 * R2 * R2;

  const Vec3 P0 = CalcLinearMomentum(model, s);
  const Vec3 H0 = CalcAngularMomentum(model, s, p_WC);
  const double T0 = Kinetic(model, s);
  const ImpactResult r = ResolveImpacts(model, s);
  ASSERT_EQ(r.impulses.size(), 1u);
  EXPECT_EQ(r.impulses[0].sticking, sticks);
  EXPECT_FALSE(r.frictionless_fallback);
  // Impulse on sphere 1 (the contact's body).
  EXPECT_LE((r.impulses[0].impulse_W - P).norm(), kImpulseRel * P.norm());
  const double vs = v + w1.norm() * R1;  // velocity scale
  EXPECT_LE((s.bodies[0].v_WBcm_W - (v1 + P / m1)).norm(), kImpulseRel * vs);
  EXPECT_LE((s.bodies[1].v_WBcm_W - (v2 - P / m2)).norm(), kImpulseRel * vs);
  EXPECT_LE((s.bodies[0].w_WB_B - (w1 + r1.cross(P) / I1)).norm(), kImpulseRel * vs / R1);
  EXPECT_LE((s.bodies[1].w_WB_B - (w2 - r2.cross(P) / I2)).norm(), kImpulseRel * vs / R1);
  // Spin generated about z (the axis normal to the plane of n and v_t's main part).
  EXPECT_GT(std::abs(s.bodies[0].w_WB_B.z() - w1.z()), 0.1);
  // Conservation and dissipation.
  EXPECT_LE((CalcLinearMomentum(model, s) - P0).norm(), kImpulseRel * (m1 + m2) * vs);
  EXPECT_LE((CalcAngularMomentum(model, s, p_WC) - H0).norm(),
            kImpulseRel * (m1 + m2) * vs * (R1 + R2));
  const double T1 = Kinetic(model, s);
  EXPECT_LE(T1, T0);
  // With sticking the loss is ½ μ (1 - e²) v_n² + ½ (2/7) μ |v_t|² (normal and tangential
  // parts decouple for two spheres: the inverse mass along n is 1/μ, along t 7/(2μ)).
  if (sticks) {
    const double dT =
        0.5 * mu * (1 - e * e) * v_n * v_n + 0.5 * (2.0 / 7.0) * mu * v_t.squaredNorm();
    EXPECT_NEAR(T0 - T1, dT, kImpulseRel * T0);
  }
  // After the impact the contact points separate along n at e |v_n|, and a sticking impact
  // leaves no slip.
  const Vec3 r1n = -R1 * n, r2n = R2 * n;
  const Vec3 v_rel1 = s.bodies[0].v_WBcm_W + s.bodies[0].w_WB_B.cross(r1n) - s.bodies[1].v_WBcm_W -
                      s.bodies[1].w_WB_B.cross(r2n);
  EXPECT_NEAR(v_rel1.dot(n), -e * v_n, kImpulseRel * vs);
  if (sticks) {
    EXPECT_LE((v_rel1 - v_rel1.dot(n) * n).norm(), kImpulseRel * vs);
  }
}

TEST(ContactSpheres, ObliqueImpactSticks) {
  ObliqueImpact(30.0 * std::numbers::pi / 180.0, true);
}

TEST(ContactSpheres, ObliqueImpactSlides) {
  ObliqueImpact(70.0 * std::numbers::pi / 180.0, false);
}

// ---------------------------------------------------------------------------------------
// (c) Three equal spheres in a row along x, touching: sphere 1 moves at v into 2 and 3 at
// rest. The engine resolves both contacts in one impulse LCP: contact A (1-2) approaches and
// wants a separation speed >= e v, contact B (2-3) rests and wants >= 0. With impulses P_A
// (on 2 from 1) and P_B (on 3 from 2):
//   v1' = v - P_A/m, v2' = (P_A - P_B)/m, v3' = P_B/m,
//   A: v2' - v1' = e v,  B: v3' - v2' = 0  (both pressing)
// => P_A = 2 P_B, P_B = m v (1 + e)/3, so
//   v1' = v (1 - 2e)/3,  v2' = v3' = v (1 + e)/3.
// The alternative with P_B = 0 gives v3' - v2' = -v (1 + e)/2 < 0: not a solution, so this one
// is the LCP's unique answer (the Delassus matrix [[2, -1], [-1, 2]]/m is positive definite).
// This is the simultaneous law, not a Newton's cradle: with e = 1 sphere 1 bounces back at v/3
// and 2 and 3 leave together at 2v/3 (kinetic energy is still conserved: 1/9 + 4/9 + 4/9 = 1);
// a real cradle's impulse travels through the row as a sequence of two-body impacts.
TEST(ContactSpheres, ThreeSpheresInARowTakeOneImpulseLcp) {
  const double m = 0.2, R = 0.025, v = 1.5;
  for (const double e : {0.0, 0.5, 1.0}) {
    Model model;
    for (const char* name : {"s1", "s2", "s3"}) model.AddBody(name, Ball(m, R));
    // A on 2 against 1, B on 3 against 2: normals +x.
    model.AddContact(SphereSphere("A", 1, R, 0, R, 0.5, 0.5, e));
    model.AddContact(SphereSphere("B", 2, R, 1, R, 0.5, 0.5, e));
    State s = MakeRestState(model);
    for (int b = 0; b < 3; ++b) {
      SetBodyPose(model, b, Vec3(2 * R * b, 0, 0), Quat::Identity(), s);
    }
    SetBodyVelocity(model, 0, Vec3(v, 0, 0), Vec3::Zero(), s);
    const double T0 = Kinetic(model, s);
    const ImpactResult r = ResolveImpacts(model, s);
    ASSERT_EQ(r.impulses.size(), 2u) << e;
    EXPECT_NEAR(s.bodies[0].v_WBcm_W.x(), v * (1 - 2 * e) / 3, kImpulseRel * v) << e;
    EXPECT_NEAR(s.bodies[1].v_WBcm_W.x(), v * (1 + e) / 3, kImpulseRel * v) << e;
    EXPECT_NEAR(s.bodies[2].v_WBcm_W.x(), v * (1 + e) / 3, kImpulseRel * v) << e;
    EXPECT_NEAR(r.impulses[0].normal_impulse, 2 * m * v * (1 + e) / 3, kImpulseRel * m * v);
    EXPECT_NEAR(r.impulses[1].normal_impulse, m * v * (1 + e) / 3, kImpulseRel * m * v);
    EXPECT_NEAR(CalcLinearMomentum(model, s).x(), m * v, kImpulseRel * m * v);
    // T' = ½ m v² ((1 - 2e)² + 2 (1 + e)²)/9 (= T0 at e = 1).
    const double T1 = 0.5 * m * v * v * ((1 - 2 * e) * (1 - 2 * e) + 2 * (1 + e) * (1 + e)) / 9;
    EXPECT_NEAR(Kinetic(model, s), T1, kImpulseRel * T0) << e;
    EXPECT_LE(Kinetic(model, s), T0 * (1 + kImpulseRel));
  }
}

}  // namespace
}  // namespace chasles
