// Contact with Coulomb friction, regime changes and impacts (chapter 8.3, Problems 8.18,
// 8.26, 8.27): closed forms derived in the comments, compared with the hybrid simulation.

#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>
#include <random>
#include <string>

#include <gtest/gtest.h>

#include "chasles/analysis/ledger.h"
#include "chasles/dynamics/contact_solve.h"
#include "chasles/dynamics/newton_euler.h"
#include "chasles/integrate/rk4.h"
#include "chasles/integrate/simulate.h"
#include "chasles/model/forces.h"
#include "chasles/model/model.h"
#include "test_support.h"

namespace chasles {
namespace {

using test::Near;

constexpr double kG = 9.81;
// Event times are located to 1e-10 s and the dynamics in each mode are exact, so times and
// speeds of order 1 match the closed forms to this relative tolerance.
constexpr double kEventRel = 1e-9;

RotationalInertia Diag(double a, double b, double c) {
  return RotationalInertia::FromMatrix(Vec3(a, b, c).asDiagonal());
}

SimulationOptions TightOptions(double t_end) {
  SimulationOptions o;
  o.t_end = t_end;
  o.adaptive.rtol = 1e-12;
  o.adaptive.atol = 1e-14;
  return o;
}

const ContactEvent* FindEvent(const SimulationResult& r, int point, ContactEventReason why) {
  for (const ContactEvent& e : r.contact_events) {
    if (e.point == point && e.reason == why) return &e;
  }
  return nullptr;
}

// A body on the floor z = 0 with gravity -g z.
struct FloorScene {
  Model model;
  void AddGravity() {
    model.AddForceElement(std::make_shared<UniformGravity>("gravity", Vec3(0, 0, -kG)));
  }
  // A uniform ball (I = 2/5 m R²) as body 0 under gravity, and the spec of its sphere contact
  // with the floor (the caller sets the coefficients and adds it).
  ContactSpec AddBall(double m, double R, const std::string& contact) {
    const double I = 0.4 * m * R * R;
    model.AddBody("ball", MassProperties(m, Vec3::Zero(), Diag(I, I, I)));
    AddGravity();
    ContactSpec spec;
    spec.name = contact;
    spec.shape = ContactShape::kSphere;
    spec.body = 0;
    spec.radius = R;
    return spec;
  }
};

// ---------------------------------------------------------------------------------------
// Problems 8.26/8.27: a ball set down spinning (w0 about y, no velocity). Sliding friction
// mu_k m g acts along +x: v = mu_k g t; I ẇ = -mu_k m g R with I = 2/5 m R² gives
// w = w0 - 5 mu_k g t/(2R). Slip v - R w... reaches zero (v = R w) at t* = 2 R w0/(7 mu_k g),
// with v* = 2/7 R w0; then rolling without slip, no friction, constant kinetic energy.
TEST(ContactScenario, SpinningBallStopsSlidingAtTStar) {
  const double m = 0.17, R = 0.028575, w0 = 40.0, mu_k = 0.2, mu_s = 0.25;
  FloorScene sc;
  ContactSpec spec = sc.AddBall(m, R, "table");
  spec.mu_s = mu_s;
  spec.mu_k = mu_k;
  sc.model.AddContact(spec);
  State s0 = MakeRestState(sc.model);
  SetBodyPose(sc.model, 0, Vec3(0, 0, R), Quat::Identity(), s0);
  SetBodyVelocity(sc.model, 0, Vec3::Zero(), Vec3(0, w0, 0), s0);
  const double t_star = 2.0 * R * w0 / (7.0 * mu_k * kG);
  const double v_star = 2.0 / 7.0 * R * w0;
  SimulationOptions o = TightOptions(2.0 * t_star);
  o.output_interval = t_star / 10;
  const SimulationResult r = Simulate(sc.model, s0, o);
  ASSERT_EQ(r.contact_events.front().to, ContactMode::kSliding);
  const ContactEvent* stop = FindEvent(r, 0, ContactEventReason::kSlipStopped);
  ASSERT_NE(stop, nullptr);
  EXPECT_EQ(stop->to, ContactMode::kSticking);
  EXPECT_TRUE(Near(stop->t, t_star, kEventRel));
  const State& sf = r.final_state;
  EXPECT_TRUE(Near(sf.bodies[0].v_WBcm_W.x(), v_star, kEventRel));
  // After t*: rolling, friction zero, kinetic energy constant (7/10 m v*²).
  const std::vector<ContactPointOutput> out = CalcContactOutputs(sc.model, sf);
  EXPECT_LT(out[0].friction_force_W.norm(), 1e-9 * m * kG);
  EXPECT_TRUE(Near(out[0].normal_force, m * kG, 1e-12));
  const LedgerSample L = CalcLedgerSample(sc.model, sf, r.samples.front());
  const double T_star = 0.7 * m * v_star * v_star;
  EXPECT_TRUE(Near(L.kinetic_translational + L.kinetic_rotational, T_star, kEventRel));
  // Ledger: the energy lost is the friction work, E0 - E = -W_f, to round-off.
  const double T0 = 0.5 * 0.4 * m * R * R * w0 * w0;
  EXPECT_TRUE(Near(L.contact_friction_work, T_star - T0, kEventRel));
  EXPECT_LT(std::abs(L.energy_residual), 1e-10 * L.energy_scale);
  EXPECT_GT(L.dissipated, 0.0);
}

// Problem 8.18: a thin disk (I = ½ m R² about its axis) set upright on its rim with spin w0.
// Sliding: a = mu_k g, α = -2 mu_k g / R; slip ends at v = R w: t* = R w0/(3 mu_k g),
// v* = R w0 / 3.
TEST(ContactScenario, ThinDiskSetDownWithSpin) {
  const double m = 0.3, R = 0.0254, w0 = 92.0 * 2.0 * std::numbers::pi, mu_k = 0.5;
  FloorScene sc;
  sc.model.AddBody(
      "disk",
      MassProperties(m, Vec3::Zero(), Diag(0.25 * m * R * R, 0.25 * m * R * R, 0.5 * m * R * R)));
  sc.AddGravity();
  ContactSpec spec;
  spec.name = "rim";
  spec.shape = ContactShape::kDiskRim;
  spec.body = 0;
  spec.radius = R;
  spec.axis_B = Vec3::UnitZ();
  spec.mu_s = mu_k;
  spec.mu_k = mu_k;
  sc.model.AddContact(spec);
  State s0 = MakeRestState(sc.model);
  // Body z (the axle) along world y: rotate +90° about x.
  const Quat q(Eigen::AngleAxisd(-std::numbers::pi / 2, Vec3::UnitX()));
  SetBodyPose(sc.model, 0, Vec3(0, 0, R), q, s0);
  SetBodyVelocity(sc.model, 0, Vec3::Zero(), Vec3(0, w0, 0), s0);
  const double t_star = R * w0 / (3.0 * mu_k * kG);
  // While sliding: a = mu_k g along +x, α = -2 mu_k g / R about y.
  {
    State s = s0;
    SelectContactModes(sc.model, s);
    ASSERT_EQ(s.contacts[0].mode, ContactMode::kSliding);
    Data d = MakeData(sc.model);
    CalcAccelerations(sc.model, s, d);
    EXPECT_TRUE(Near(d.a_WBcm_W[0].x(), mu_k * kG, 1e-12));
    EXPECT_TRUE(Near((d.R_WB[0] * d.wdot_WB_B[0]).y(), -2.0 * mu_k * kG / R, 1e-12));
  }
  const SimulationResult r = Simulate(sc.model, s0, TightOptions(1.5 * t_star));
  const ContactEvent* stop = FindEvent(r, 0, ContactEventReason::kSlipStopped);
  ASSERT_NE(stop, nullptr);
  EXPECT_TRUE(Near(stop->t, t_star, kEventRel));
  EXPECT_TRUE(Near(r.final_state.bodies[0].v_WBcm_W.x(), R * w0 / 3.0, kEventRel));
}

// A solid cylinder (two end rims) on an incline of angle θ: rolling needs friction
// f = m g sinθ/3 against N = m g cosθ, so it rolls when tanθ <= 3 mu_s (a = 2/3 g sinθ) and
// otherwise slides with a = g (sinθ - mu_k cosθ). Both sides of the threshold.
TEST(ContactScenario, CylinderOnInclineRollSlideThreshold) {
  const double m = 2.0, R = 0.1, L = 0.2, mu_s = 0.2, mu_k = 0.15;
  for (const double factor : {1.0 - 1e-6, 1.0 + 1e-6}) {
    const double theta = std::atan(3.0 * mu_s * factor);
    const Vec3 n(std::sin(theta), std::cos(theta), 0);      // incline normal (gravity -y)
    const Vec3 down(std::cos(theta), -std::sin(theta), 0);  // down the slope
    Model model;
    const double It = m * (3 * R * R + L * L) / 12;
    model.AddBody("cylinder", MassProperties(m, Vec3::Zero(), Diag(It, It, 0.5 * m * R * R)));
    model.AddForceElement(std::make_shared<UniformGravity>("gravity", Vec3(0, -kG, 0)));
    ContactSpec spec;
    spec.name = "incline";
    spec.shape = ContactShape::kCylinder;
    spec.body = 0;
    spec.radius = R;
    spec.length = L;
    spec.plane_normal_W = n;
    spec.mu_s = mu_s;
    spec.mu_k = mu_k;
    model.AddContact(spec);
    State s = MakeRestState(model);
    SetBodyPose(model, 0, R * n, Quat::Identity(), s);
    SelectContactModes(model, s);
    Data d = MakeData(model);
    CalcAccelerations(model, s, d);
    const double a = d.a_WBcm_W[0].dot(down);
    if (factor < 1.0) {
      EXPECT_EQ(s.contacts[0].mode, ContactMode::kSticking) << factor;
      EXPECT_EQ(s.contacts[1].mode, ContactMode::kSticking) << factor;
      EXPECT_TRUE(Near(a, 2.0 / 3.0 * kG * std::sin(theta), 1e-12));
    } else {
      EXPECT_EQ(s.contacts[0].mode, ContactMode::kSliding) << factor;
      EXPECT_EQ(s.contacts[1].mode, ContactMode::kSliding) << factor;
      EXPECT_TRUE(Near(a, kG * (std::sin(theta) - mu_k * std::cos(theta)), 1e-12));
    }
  }
}

// A box resting on the floor: four vertices press, the other four are apart. The four are
// redundant; the least-norm split is m g / 4 each, no friction.
TEST(ContactScenario, BoxRestsOnFourVerticesLeastNorm) {
  const double m = 3.0, a = 0.2, b = 0.1, c = 0.05;
  FloorScene sc;
  sc.model.AddBody(
      "box", MassProperties(m, Vec3::Zero(),
                            Diag(m * (4 * b * b + 4 * c * c) / 12, m * (4 * a * a + 4 * c * c) / 12,
                                 m * (4 * a * a + 4 * b * b) / 12)));
  sc.AddGravity();
  ContactSpec spec;
  spec.name = "floor";
  spec.shape = ContactShape::kBox;
  spec.body = 0;
  spec.half_extents = Vec3(a, b, c);
  spec.mu_s = 0.5;
  spec.mu_k = 0.4;
  sc.model.AddContact(spec);
  State s = MakeRestState(sc.model);
  SetBodyPose(sc.model, 0, Vec3(0, 0, c), Quat::Identity(), s);
  SelectContactModes(sc.model, s);
  const std::vector<ContactPointOutput> out = CalcContactOutputs(sc.model, s);
  for (int k = 0; k < 8; ++k) {
    const bool bottom = (k & 4) == 0;
    EXPECT_EQ(s.contacts[static_cast<size_t>(k)].mode,
              bottom ? ContactMode::kSticking : ContactMode::kSeparated)
        << k;
    EXPECT_TRUE(
        Near(out[static_cast<size_t>(k)].normal_force, bottom ? m * kG / 4 : 0.0, 1e-12, m * kG))
        << k;
    EXPECT_LT(out[static_cast<size_t>(k)].friction_force_W.norm(), 1e-12 * m * kG);
  }
  // It stays there: no event over a second, the position does not move.
  const SimulationResult r = Simulate(sc.model, s, TightOptions(1.0));
  EXPECT_EQ(r.contact_events.size(), 8u);  // the initial modes only
  EXPECT_LT((r.final_state.bodies[0].p_WBcm - Vec3(0, 0, c)).norm(), 1e-12);
}

// A rod leaning on a frictionless wall (x = 0) and floor (y = 0), released from rest at angle
// θ to the floor. With the rod's angle as coordinate, T = ½ (m L²/4 + I) θ̇², V = m g L/2 sinθ:
// θ̈ = -(m g L/2) cosθ / (m L²/4 + I); the wall pushes N_w = m ẍ = -m L/2 sinθ θ̈ and the floor
// N_f = m g + m ÿ = m g + m L/2 cosθ θ̈. Both contacts are chosen together (LCP).
TEST(ContactScenario, RodOnFloorAndWall) {
  const double m = 1.5, L = 2.0, r = 0.01, theta = 1.0;
  const double I = m * L * L / 12 + m * r * r / 4;
  Model model;
  // Rod along body x.
  model.AddBody("rod", MassProperties(m, Vec3::Zero(), Diag(0.5 * m * r * r, I, I)));
  model.AddForceElement(std::make_shared<UniformGravity>("gravity", Vec3(0, -kG, 0)));
  ContactSpec floor;
  floor.name = "floor";
  floor.shape = ContactShape::kPointSet;
  floor.body = 0;
  floor.points_B = {Vec3(0.5 * L, 0, 0)};
  floor.plane_normal_W = Vec3::UnitY();
  ContactSpec wall = floor;
  wall.name = "wall";
  wall.points_B = {Vec3(-0.5 * L, 0, 0)};
  wall.plane_normal_W = Vec3::UnitX();
  model.AddContact(floor);
  model.AddContact(wall);
  State s = MakeRestState(model);
  // Rod from the wall point (0, L sinθ) to the floor point (L cosθ, 0): body x along
  // (cosθ, -sinθ), a rotation by -θ about z.
  SetBodyPose(model, 0, Vec3(0.5 * L * std::cos(theta), 0.5 * L * std::sin(theta), 0),
              Quat(Eigen::AngleAxisd(-theta, Vec3::UnitZ())), s);
  SelectContactModes(model, s);
  EXPECT_NE(s.contacts[0].mode, ContactMode::kSeparated);
  EXPECT_NE(s.contacts[1].mode, ContactMode::kSeparated);
  const std::vector<ContactPointOutput> out = CalcContactOutputs(model, s);
  const double theta_dd = -(m * kG * L / 2 * std::cos(theta)) / (m * L * L / 4 + I);
  EXPECT_TRUE(Near(out[0].normal_force, m * kG + m * L / 2 * std::cos(theta) * theta_dd, 1e-12));
  EXPECT_TRUE(Near(out[1].normal_force, -m * L / 2 * std::sin(theta) * theta_dd, 1e-12));
}

// A ball dropped from h0 with restitution e: approach speeds e^n √(2 g h0), so rebound heights
// e^(2n) h0; the bounces accumulate to rest at t∞ = √(2h0/g) (1+e)/(1-e) (first fall plus
// flights 2 e^n √(2h0/g)). The energy lost is the impact dissipation.
TEST(ContactScenario, BouncingBallHeightsAndTimeToRest) {
  const double m = 0.05, R = 0.02, h0 = 1.0, e = 0.6;
  FloorScene sc;
  ContactSpec spec = sc.AddBall(m, R, "floor");
  spec.mu_s = 0.3;
  spec.mu_k = 0.3;
  spec.restitution = e;
  sc.model.AddContact(spec);
  State s0 = MakeRestState(sc.model);
  SetBodyPose(sc.model, 0, Vec3(0, 0, R + h0), Quat::Identity(), s0);
  const double t_fall = std::sqrt(2 * h0 / kG);
  const double t_rest = t_fall * (1 + e) / (1 - e);
  const SimulationResult r = Simulate(sc.model, s0, TightOptions(t_rest + 1.0));
  ASSERT_GE(r.impacts.size(), 3u);
  const double v0 = std::sqrt(2 * kG * h0);
  // Every touch-down is located to the event tolerance (1e-12 s), so an approach speed carries
  // an absolute error of order g times the accumulated event errors: relative 1e-9 while the
  // bounces are large, an absolute 1e-10 s × g for the small ones (about 25 bounces here).
  const double dv = kG * 1e-10;
  for (size_t n = 0; n < r.impacts.size(); ++n) {
    const double v = r.impacts[n].approach_speed;
    const double v_n = std::pow(e, n) * v0;
    EXPECT_NEAR(v, v_n, std::max(kEventRel * v_n, dv)) << n;
    // Rebound height of bounce n: (e v)²/(2g) = e^(2(n+1)) h0.
    EXPECT_NEAR(e * e * v * v / (2 * kG), std::pow(e, 2.0 * (n + 1)) * h0,
                std::max(kEventRel, 2 * dv / v_n) * std::pow(e, 2.0 * (n + 1)) * h0)
        << n;
  }
  EXPECT_GE(r.impacts.size(), 20u);
  const ImpactRecord& last = r.impacts.back();
  ASSERT_TRUE(last.accumulation);
  EXPECT_TRUE(Near(last.accumulation_time, t_rest, kEventRel));
  EXPECT_EQ(r.final_state.contacts[0].mode, ContactMode::kSticking);
  const LedgerSample L = CalcLedgerSample(sc.model, r.final_state, s0);
  EXPECT_TRUE(Near(L.contact_impact_work, -m * kG * h0, 1e-9));
  EXPECT_LT(std::abs(L.energy_residual), 1e-10 * L.energy_scale);
}

// Impacts never create energy: random bodies, orientations, velocities, e and mu hitting the
// floor at a box vertex.
TEST(ContactScenario, ImpactsNeverCreateEnergy) {
  std::mt19937 rng(12345);
  std::uniform_real_distribution<double> U(-1.0, 1.0), P(0.0, 1.0);
  for (int trial = 0; trial < 300; ++trial) {
    const double m = 0.5 + P(rng);
    const Vec3 h(0.05 + 0.2 * P(rng), 0.05 + 0.2 * P(rng), 0.05 + 0.2 * P(rng));
    Model model;
    model.AddBody("box", MassProperties(m, Vec3::Zero(),
                                        Diag(m * (h.y() * h.y() + h.z() * h.z()) / 3,
                                             m * (h.x() * h.x() + h.z() * h.z()) / 3,
                                             m * (h.x() * h.x() + h.y() * h.y()) / 3)));
    ContactSpec spec;
    spec.name = "floor";
    spec.shape = ContactShape::kPointSet;
    spec.body = 0;
    spec.points_B = {h};
    spec.mu_s = 1.5 * P(rng);
    spec.mu_k = spec.mu_s * P(rng);
    spec.restitution = P(rng);
    model.AddContact(spec);
    State s = MakeRestState(model);
    const Quat q = Quat(Eigen::Vector4d(U(rng), U(rng), U(rng), U(rng)).normalized());
    SetBodyPose(model, 0, Vec3::Zero(), q, s);
    // Put the vertex on the floor.
    const Vec3 p_vertex = s.bodies[0].p_WBcm + q * h;
    s.bodies[0].p_WBcm.z() -= p_vertex.z();
    s.bodies[0].v_WBcm_W = Vec3(U(rng), U(rng), U(rng)) * 3.0;
    s.bodies[0].w_WB_B = Vec3(U(rng), U(rng), U(rng)) * 10.0;
    const ImpactResult ir = ResolveImpacts(model, s);
    EXPECT_LE(ir.kinetic_energy_after, ir.kinetic_energy_before * (1 + 1e-12)) << trial;
    // After the impact the vertex does not approach the floor.
    Data d = MakeData(model);
    CalcAccelerations(model, s, d);
    EXPECT_GE(d.contact_points[0].normal_velocity, -1e-9) << trial;
  }
}

// Rolling resistance: a ball rolling at v0 on a level floor with moment mu_r N R against the
// rolling. Rolling, m v̇ = -f, I ẇ = f R - mu_r m g R with v = R w: (I + m R²) ẇ = -mu_r m g R,
// v̇ = -5/7 mu_r g; it stops at t = 7 v0 / (5 mu_r g).
TEST(ContactScenario, RollingResistanceStopsABall) {
  const double m = 0.2, R = 0.03, v0 = 0.5, mu_r = 0.01;
  FloorScene sc;
  ContactSpec spec = sc.AddBall(m, R, "floor");
  spec.mu_s = 0.5;
  spec.mu_k = 0.4;
  spec.mu_r = mu_r;
  sc.model.AddContact(spec);
  State s0 = MakeRestState(sc.model);
  SetBodyPose(sc.model, 0, Vec3(0, 0, R), Quat::Identity(), s0);
  // Rolling along +x: w = v0/R about +y.
  SetBodyVelocity(sc.model, 0, Vec3(v0, 0, 0), Vec3(0, v0 / R, 0), s0);
  const double t_stop = 7 * v0 / (5 * mu_r * kG);
  const SimulationResult r = Simulate(sc.model, s0, TightOptions(1.2 * t_stop));
  const ContactEvent* stop = FindEvent(r, 0, ContactEventReason::kRollingStopped);
  ASSERT_NE(stop, nullptr);
  EXPECT_TRUE(Near(stop->t, t_stop, kEventRel));
  EXPECT_LT(r.final_state.bodies[0].v_WBcm_W.norm(), 1e-9 * v0);
  const LedgerSample L = CalcLedgerSample(sc.model, r.final_state, s0);
  EXPECT_TRUE(Near(L.contact_rolling_work, -0.7 * m * v0 * v0, kEventRel));
  EXPECT_LT(std::abs(L.energy_residual), 1e-10 * L.energy_scale);
}

}  // namespace
// A fixed-step integrator steps the modes the state carries: a ball spinning on the floor
// (sliding) keeps its height and gains speed at exactly mu_k g over RK4 steps (the friction is
// constant in the mode, so RK4 is exact here), instead of falling through the floor.
TEST(ContactScenario, Rk4StepsTheCarriedModes) {
  const double m = 0.17, R = 0.028575, mu_k = 0.35;
  FloorScene sc;
  ContactSpec spec = sc.AddBall(m, R, "floor");
  spec.mu_s = 0.5;
  spec.mu_k = mu_k;
  sc.model.AddContact(spec);
  State s = MakeRestState(sc.model);
  SetBodyPose(sc.model, 0, Vec3(0, 0, R), Quat::Identity(), s);
  SetBodyVelocity(sc.model, 0, Vec3::Zero(), Vec3(0, 100.0, 0), s);
  SelectContactModes(sc.model, s);
  ASSERT_EQ(s.contacts[0].mode, ContactMode::kSliding);
  Rk4Integrator rk4(sc.model);
  const double h = 1e-3;
  for (int i = 0; i < 10; ++i) rk4.Step(s, h);
  EXPECT_EQ(s.contacts[0].mode, ContactMode::kSliding);
  EXPECT_NEAR(s.bodies[0].p_WBcm.z(), R, 1e-12);
  EXPECT_TRUE(Near(s.bodies[0].v_WBcm_W.x(), mu_k * kG * 10 * h, 1e-12));
}

}  // namespace chasles
