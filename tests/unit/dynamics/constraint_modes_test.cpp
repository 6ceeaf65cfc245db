// Strings that go slack and snap taut (dynamics/constraint_modes.h, docs/constraints.md
// "Strings that go slack"): a particle on a string whirled in a vertical circle, a block on a
// string thrown up (plastic and with restitution) and the taut/slack choice of one instant,
// each against closed forms derived here.

#include "chasles/dynamics/constraint_modes.h"

#include <cmath>
#include <memory>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>
#include <boost/math/quadrature/gauss_kronrod.hpp>

#include "chasles/analysis/instantaneous.h"
#include "chasles/analysis/ledger.h"
#include "chasles/integrate/simulate.h"
#include "chasles/model/forces.h"
#include "chasles/model/string_constraint.h"
#include "test_support.h"

namespace chasles {
namespace {

using test::Near;

constexpr double kG = 9.81;

// A particle (a point mass) of mass m on a string of length l from the world point O = 0, in
// the x-y plane, gravity -y; restitution e of the string's snap.
struct Tether {
  Model model;
  State s;
};

Tether MakeTether(double m, double l, double e, const Vec3& p, const Vec3& v) {
  Tether t;
  t.model.AddBody("bob",
                  MassProperties(m, Vec3::Zero(), RotationalInertia::FromMatrix(Mat3::Zero())));
  t.model.AddForceElement(std::make_shared<UniformGravity>("g", Vec3(0, -kG, 0)));
  t.s = MakeRestState(t.model);
  t.s.bodies[0].p_WBcm = p;
  t.s.bodies[0].v_WBcm_W = v;
  auto string = std::make_shared<StringConstraint>(
      "string", StringEnd{kWorld, Vec3::Zero(), 0.0, 1}, std::vector<StringPulley>{},
      StringEnd{0, Vec3::Zero(), 0.0, 1}, Vec3::UnitZ(), l);
  string->set_restitution(e);
  t.model.AddConstraint(string);
  return t;
}

SimulationOptions Tight(double t_end) {
  SimulationOptions o;
  o.t_end = t_end;
  o.adaptive.rtol = 1e-12;
  o.adaptive.atol = 1e-12;
  return o;
}

// Vertical circle: the particle starts at the bottom with horizontal speed v0, 2 g l < v0² <
// 5 g l. Energy: v² = v0² - 2 g l (1 - cos φ) (φ from the bottom); radially
// T = m (v²/l + g cos φ), zero where cos φ_s = (2 g l - v0²) / (3 g l), with v_s² = -g l cos φ_s.
// It gets there at t_s = ∫₀^φs l dφ / v(φ) (a smooth integrand: Gauss-Kronrod to round-off).
// Then it flies on the parabola p(τ) = p_s + v_s τ + ½ g τ², and
//   |p|² - l² = 2 (p_s·v_s) τ + (v_s² + p_s·g) τ² + (v_s·g) τ³ + ¼ g² τ⁴ = τ³ (v_s·g + ¼ g² τ)
// since p_s·v_s = 0 (tangential) and v_s² + p_s·g = v_s² + g l cos φ_s = 0 (T = 0): the string
// is taut again at τ* = -4 (v_s·g) / g², the root of the last factor. The plastic snap keeps
// only the tangential velocity; the kinetic energy lost is ½ m (v·r̂)².
TEST(ConstraintModes, PendulumGoesSlackFliesAndSnapsTaut) {
  const double m = 0.3, l = 0.8, v0 = std::sqrt(3.5 * kG * l);
  Tether t = MakeTether(m, l, 0.0, Vec3(0, -l, 0), Vec3(v0, 0, 0));
  const double cos_s = (2 * kG * l - v0 * v0) / (3 * kG * l);  // -1/2: φ_s = 120°
  const double phi_s = std::acos(cos_s);
  const double vs = std::sqrt(-kG * l * cos_s);
  const auto inv_speed = [&](double phi) {
    return l / std::sqrt(v0 * v0 - 2 * kG * l * (1 - std::cos(phi)));
  };
  const double t_s = boost::math::quadrature::gauss_kronrod<double, 61>::integrate(
      inv_speed, 0.0, phi_s, 15, 1e-15);
  const Vec3 p_s(l * std::sin(phi_s), -l * cos_s, 0);
  const Vec3 v_s = vs * Vec3(cos_s, std::sin(phi_s), 0);  // counterclockwise tangent
  const Vec3 g(0, -kG, 0);
  const double tau = -4 * v_s.dot(g) / g.squaredNorm();
  const Vec3 p_snap = p_s + v_s * tau + 0.5 * g * tau * tau;
  const Vec3 v_in = v_s + g * tau;
  const Vec3 r_hat = p_snap / l;
  const double v_radial = v_in.dot(r_hat);  // > 0: moving out, closing the slack
  const Vec3 v_out = v_in - v_radial * r_hat;
  ASSERT_GT(v_radial, 0.0);

  std::vector<State> after;
  SimulationOptions o = Tight(t_s + tau + 1e-3);
  o.on_transition = [&](const State&, const State& a) { after.push_back(a); };
  const SimulationResult r = Simulate(t.model, t.s, o);
  ASSERT_GE(r.constraint_events.size(), 3u);
  const ConstraintEvent& start = r.constraint_events[0];
  EXPECT_EQ(start.reason, ConstraintEventReason::kInitial);
  EXPECT_EQ(start.to, ConstraintMode::kEngaged);
  const ConstraintEvent& slack = r.constraint_events[1];
  EXPECT_EQ(slack.reason, ConstraintEventReason::kWentSlack);
  EXPECT_EQ(slack.to, ConstraintMode::kReleased);
  EXPECT_TRUE(Near(slack.t, t_s, 1e-9));
  const ConstraintEvent& snap = r.constraint_events[2];
  EXPECT_EQ(snap.reason, ConstraintEventReason::kSnappedTaut);
  EXPECT_TRUE(Near(snap.t, t_s + tau, 1e-9));
  EXPECT_TRUE(Near(snap.approach_speed, v_radial, 1e-8));
  EXPECT_TRUE(Near(snap.impulse, m * v_radial, 1e-8));
  EXPECT_TRUE(Near(snap.energy_lost, 0.5 * m * v_radial * v_radial, 1e-8));
  ASSERT_EQ(after.size(), 2u);
  // The slack point: angle φ_s from the bottom, speed v_s.
  const Vec3 p1 = after[0].bodies[0].p_WBcm;
  EXPECT_TRUE(Near(std::atan2(p1.x(), -p1.y()), phi_s, 1e-9));
  EXPECT_TRUE(Near(after[0].bodies[0].v_WBcm_W.norm(), vs, 1e-9));
  // The snap: on the circle where the parabola meets it, tangential velocity only.
  EXPECT_TRUE(test::MatNear(after[1].bodies[0].p_WBcm, p_snap, 1e-9, l));
  EXPECT_TRUE(test::MatNear(after[1].bodies[0].v_WBcm_W, v_out, 1e-8, v0));
  // The energy lost is in the ledger as dissipated at impacts; the balance closes.
  const LedgerSample L = CalcLedgerSample(t.model, r.final_state, t.s);
  EXPECT_TRUE(Near(-L.constraint_impact_work, 0.5 * m * v_radial * v_radial, 1e-8));
  EXPECT_TRUE(Near(L.dissipated, 0.5 * m * v_radial * v_radial, 1e-8));
  EXPECT_LT(std::abs(L.energy_residual), 1e-9 * L.energy_scale);
}

// A block hanging at rest on a string of length l, thrown up with v0: the string slackens at
// once (its slack opens at v0), the block flies up and falls back, and the string is taut
// again when the block returns, at t = 2 v0 / g, arriving at v0. Plastic: at rest after, the
// impulse m v0 and ½ m v0² lost; then the string holds it (T = m g). With restitution e it
// rebounds at e v0 (impulse m (1 + e) v0, ½ m v0² (1 - e²) lost) and is back at
// 2 v0/g + 2 e v0/g.
TEST(ConstraintModes, BlockThrownUpSlackensAndSnapsTaut) {
  const double m = 2.0, l = 1.5, v0 = 1.2;
  for (const double e : {0.0, 0.5}) {
    Tether t = MakeTether(m, l, e, Vec3(0, -l, 0), Vec3(0, v0, 0));
    const double t1 = 2 * v0 / kG, t2 = t1 + 2 * e * v0 / kG;
    const double t_end = e > 0.0 ? t2 + 0.3 * e * v0 / kG : t1 + 0.2;
    std::vector<State> after;
    SimulationOptions o = Tight(t_end);
    o.on_transition = [&](const State&, const State& a) { after.push_back(a); };
    const SimulationResult r = Simulate(t.model, t.s, o);
    ASSERT_EQ(r.constraint_events.size(), e > 0.0 ? 3u : 2u) << e;
    EXPECT_EQ(r.constraint_events[0].reason, ConstraintEventReason::kInitial);
    EXPECT_EQ(r.constraint_events[0].from, ConstraintMode::kEngaged);
    EXPECT_EQ(r.constraint_events[0].to, ConstraintMode::kReleased);
    const ConstraintEvent& snap = r.constraint_events[1];
    EXPECT_EQ(snap.reason, ConstraintEventReason::kSnappedTaut);
    EXPECT_TRUE(Near(snap.t, t1, 1e-9)) << e;
    EXPECT_TRUE(Near(snap.approach_speed, v0, 1e-9));
    EXPECT_TRUE(Near(snap.impulse, m * (1 + e) * v0, 1e-9));
    EXPECT_TRUE(Near(snap.energy_lost, 0.5 * m * v0 * v0 * (1 - e * e), 1e-9));
    EXPECT_EQ(snap.to, e > 0.0 ? ConstraintMode::kReleased : ConstraintMode::kEngaged);
    EXPECT_TRUE(Near(after[0].bodies[0].v_WBcm_W.y(), e * v0, 1e-9, v0));
    if (e > 0.0) {
      EXPECT_TRUE(Near(r.constraint_events[2].t, t2, 1e-9));
      EXPECT_TRUE(Near(r.constraint_events[2].approach_speed, e * v0, 1e-9));
    } else {
      // Held at rest by the string afterwards.
      EXPECT_TRUE(Near(r.final_state.bodies[0].p_WBcm.y(), -l, 1e-12, l));
      EXPECT_TRUE(Near(r.final_state.bodies[0].v_WBcm_W.y(), 0.0, 1e-9, v0));
      const InstantaneousSolution sol = SolveInstantaneous(t.model, r.final_state);
      EXPECT_EQ(sol.reactions[0].mode, ConstraintMode::kEngaged);
      EXPECT_TRUE(Near(sol.reactions[0].lambda[0], m * kG, 1e-9));
    }
    const LedgerSample L = CalcLedgerSample(t.model, r.final_state, t.s);
    const double lost = 0.5 * m * v0 * v0 * (1 - e * e) * (e > 0.0 ? 1 + e * e : 1.0);
    EXPECT_TRUE(Near(L.dissipated, lost, 1e-8)) << e;
    EXPECT_LT(std::abs(L.energy_residual), 1e-9 * L.energy_scale);
  }
}

// One instant: the particle on the circle at angle φ from the bottom with speed v. Taut, the
// tension is T = m (v²/l + g cos φ); the complementarity picks taut when that is >= 0 and
// slack (T = 0, the slack's acceleration g̈ = -(v²/l + g cos φ) > 0) when it is < 0. Both
// sides of the boundary v² = -g l cos φ, 1e-6 apart.
TEST(ConstraintModes, SolveChoosesTautOrSlackByTheSignOfTheTension) {
  const double m = 0.7, l = 1.1, phi = 2.0;  // above the horizontal: cos φ < 0
  const double v_b = std::sqrt(-kG * l * std::cos(phi));
  for (const double k : {1.0 + 1e-6, 1.0 - 1e-6}) {
    const double v = k * v_b;
    const Vec3 p(l * std::sin(phi), -l * std::cos(phi), 0);
    const Vec3 u = v * Vec3(std::cos(phi), std::sin(phi), 0);
    Tether t = MakeTether(m, l, 0.0, p, u);
    const InstantaneousSolution sol = SolveInstantaneous(t.model, t.s);
    const double T = m * (v * v / l + kG * std::cos(phi));
    if (T > 0.0) {
      EXPECT_EQ(sol.reactions[0].mode, ConstraintMode::kEngaged);
      EXPECT_TRUE(Near(sol.reactions[0].lambda[0], T, 1e-7));
      // Centripetal: a = -(v²/l) r̂ + tangential gravity.
      EXPECT_TRUE(Near(sol.bodies[0].a_WBcm_W.dot(p / l), -v * v / l, 1e-9));
    } else {
      EXPECT_EQ(sol.reactions[0].mode, ConstraintMode::kReleased);
      EXPECT_EQ(sol.reactions[0].lambda[0], 0.0);
      EXPECT_TRUE(test::MatNear(sol.bodies[0].a_WBcm_W, Vec3(0, -kG, 0), 1e-15, kG));
    }
  }
  // Longer than the path: slack whatever the forces.
  Tether loose = MakeTether(m, l, 0.0, Vec3(0, -0.5 * l, 0), Vec3::Zero());
  const InstantaneousSolution sol = SolveInstantaneous(loose.model, loose.s);
  EXPECT_EQ(sol.reactions[0].mode, ConstraintMode::kReleased);
  EXPECT_TRUE(Near(sol.reactions[0].gap, 0.5 * l, 1e-15));
}

// Two strings, an LCP: a particle at rest at p = (0, -h) hangs from A = (-a, 0) and B = (a, 0)
// (taut, s = √(a² + h²)) in a gravity g⃗ = (gx, -g) that pulls it towards +x. With e_A, e_B the
// unit vectors from the particle to the anchors, equilibrium T_A e_A + T_B e_B = -m g⃗ gives
//   T_A + T_B = m g s / h,   T_B - T_A = -m gx s / a,
// so T_B = (m s / 2)(g/h - gx/a) < 0 once gx > a g / h: then B is slack and A alone holds it,
// T_A = -m g⃗·e_A = m (gx a + g h) / s, and the particle starts on the circle about A with
// a = g⃗ + T_A e_A / m; B's slack then opens (g̈_B = a·e_B > 0). Both sides of gx = a g / h.
TEST(ConstraintModes, TwoStringsShareTheLoadOrOneGoesSlack) {
  const double m = 1.3, a = 0.4, h = 0.9, g = kG, s = std::hypot(a, h);
  for (const double k : {1.0 - 1e-6, 1.0 + 1e-6}) {
    const double gx = k * a * g / h;
    Model model;
    model.AddBody("bob",
                  MassProperties(m, Vec3::Zero(), RotationalInertia::FromMatrix(Mat3::Zero())));
    model.AddForceElement(std::make_shared<UniformGravity>("g", Vec3(gx, -g, 0)));
    State st = MakeRestState(model);
    st.bodies[0].p_WBcm = Vec3(0, -h, 0);
    for (const double x : {-a, a}) {
      model.AddConstraint(std::make_shared<StringConstraint>(
          x < 0 ? "A" : "B", StringEnd{kWorld, Vec3(x, 0, 0), 0.0, 1}, std::vector<StringPulley>{},
          StringEnd{0, Vec3::Zero(), 0.0, 1}, Vec3::UnitZ(), s));
    }
    const InstantaneousSolution sol = SolveInstantaneous(model, st);
    const double TB = 0.5 * m * s * (g / h - gx / a);
    if (TB >= 0.0) {
      EXPECT_EQ(sol.reactions[0].mode, ConstraintMode::kEngaged);
      EXPECT_EQ(sol.reactions[1].mode, ConstraintMode::kEngaged);
      EXPECT_TRUE(Near(sol.reactions[1].lambda[0], TB, 1e-9, m * g));
      EXPECT_TRUE(Near(sol.reactions[0].lambda[0], m * g * s / h - TB, 1e-9));
      EXPECT_TRUE(test::MatNear(sol.bodies[0].a_WBcm_W, Vec3::Zero(), 1e-12, g));
    } else {
      const Vec3 eA = Vec3(-a, h, 0) / s, eB = Vec3(a, h, 0) / s;
      const double TA = m * (gx * a + g * h) / s;
      EXPECT_EQ(sol.reactions[0].mode, ConstraintMode::kEngaged);
      EXPECT_EQ(sol.reactions[1].mode, ConstraintMode::kReleased);
      EXPECT_TRUE(Near(sol.reactions[0].lambda[0], TA, 1e-9));
      EXPECT_EQ(sol.reactions[1].lambda[0], 0.0);
      const Vec3 acc = Vec3(gx, -g, 0) + TA * eA / m;
      EXPECT_TRUE(test::MatNear(sol.bodies[0].a_WBcm_W, acc, 1e-9, g));
      EXPECT_GT(acc.dot(eB), 0.0);
    }
  }
}

}  // namespace
}  // namespace chasles
