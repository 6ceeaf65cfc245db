// Rolling resistance as a complementarity (chapter 8.3 with a resisting moment at the
// contact): a round body held at rest while the moment it needs is within mu_r N R, rolling
// with mu_r N R against its rolling otherwise, and the events between the two. The closed
// forms are in tests/reference/rolling_resistance.h (derived there); every run's samples are
// checked by the certificate and its ledger closes.

#include <cmath>
#include <numbers>
#include <string>

#include <gtest/gtest.h>

#include "chasles/analysis/certificate.h"
#include "chasles/analysis/ledger.h"
#include "chasles/dynamics/contact_solve.h"
#include "chasles/dynamics/newton_euler.h"
#include "chasles/integrate/simulate.h"
#include "reference/rolling_resistance.h"
#include "test_support.h"

namespace chasles {
namespace {

using test::Near;
using test::RollingBody;
using test::RollingCase;

// Event times are located to 1e-12 s and the motion in each regime is a polynomial in t that
// Dormand-Prince integrates exactly, so times match to this and accelerations to kAccelRel.
constexpr double kEventRel = 1e-9;
constexpr double kAccelRel = 1e-10;

struct RollingRun {
  SimulationResult result;
  Certificate certificate;
  LedgerSample ledger;
};

RollingRun RunCase(const RollingCase& c, double t_end) {
  const Model model = c.BuildModel();
  const State s0 = c.InitialState(model);
  SimulationOptions o;
  o.t_end = t_end;
  o.output_interval = t_end / 8;
  o.adaptive.rtol = 1e-12;
  o.adaptive.atol = 1e-14;
  RollingRun run;
  run.result = Simulate(model, s0, o);
  CertificateBuilder cert;
  for (const State& s : run.result.samples) cert.CheckState(model, s, CheckPhase::kSample);
  run.ledger = CalcLedgerSample(model, run.result.final_state, s0);
  cert.CheckLedger(t_end, run.ledger.energy_residual, run.ledger.energy_scale, CheckPhase::kSample);
  run.certificate = cert.Finish();
  return run;
}

// Velocity along the slope and the contact outputs at the end of a run.
double SlopeVelocity(const RollingCase& c, const State& s) {
  return s.bodies[0].v_WBcm_W.dot(c.x());
}

std::vector<const ContactEvent*> EventsOf(const SimulationResult& r, ContactEventReason why) {
  std::vector<const ContactEvent*> out;
  for (const ContactEvent& e : r.contact_events) {
    if (e.reason == why) out.push_back(&e);
  }
  return out;
}

void ExpectCertified(const RollingRun& run) {
  for (const std::string& m : run.certificate.FailureMessages()) ADD_FAILURE() << m;
  EXPECT_LT(std::abs(run.ledger.energy_residual), 1e-10 * run.ledger.energy_scale);
}

// The ball of the report: 0.4 kg, R 5 cm, mu_s 0.8, mu_k 0.6, mu_r 0.05, at rest on a level
// floor, pushed at its centre by 0.5 N > mu_r m g = 0.196 N: it rolls at once with
// a = (F/m - mu_r g) / (1 + 2/5) = 0.5426 m/s², and rolling resistance does the work
// -mu_r m g x.
TEST(RollingResistance, BallPushedFromRestRollsAgainstTheResistance) {
  RollingCase c;
  c.F0 = 0.5;
  const double a = (c.F0 / c.m - c.mu_r * c.g) / 1.4;
  ASSERT_TRUE(Near(a, 0.54260, 1e-4));
  const double T = 2.0;
  const RollingRun run = RunCase(c, T);
  const State& s = run.result.final_state;
  EXPECT_TRUE(Near(SlopeVelocity(c, s), a * T, kAccelRel));
  EXPECT_FALSE(s.contacts[0].rolling_held);
  EXPECT_EQ(s.contacts[0].mode, ContactMode::kSticking);
  const std::vector<ContactPointOutput> out = CalcContactOutputs(c.BuildModel(), s);
  // The moment mu_r N R against the rolling (ω along +y).
  EXPECT_TRUE(test::MatNear(out[0].rolling_moment_W, Vec3(0, -c.mu_r * c.m * c.g * c.R, 0), 1e-12,
                            c.m * c.g * c.R));
  const double x = a * T * T / 2;
  EXPECT_TRUE(Near(s.contacts[0].rolling_work, -c.mu_r * c.m * c.g * x, kAccelRel));
  ExpectCertified(run);
}

// Below the threshold the contact holds the moment F R and the ball stays at rest.
TEST(RollingResistance, BallPushedBelowTheLimitIsHeld) {
  RollingCase c;
  c.F0 = 0.9 * c.mu_r * c.m * c.g;
  const RollingRun run = RunCase(c, 1.0);
  const State& s = run.result.final_state;
  EXPECT_LT(s.bodies[0].v_WBcm_W.norm(), 1e-14);
  EXPECT_TRUE(s.contacts[0].rolling_held);
  EXPECT_TRUE(EventsOf(run.result, ContactEventReason::kRollingLimit).empty());
  const std::vector<ContactPointOutput> out = CalcContactOutputs(c.BuildModel(), s);
  EXPECT_TRUE(out[0].rolling_held);
  EXPECT_TRUE(Near(out[0].rolling_moment_W.norm(), c.F0 * c.R, 1e-12));
  EXPECT_EQ(s.contacts[0].rolling_work, 0.0);
  ExpectCertified(run);
}

// A ball, a cylinder on its side (both end rims) and a hoop, each pushed from rest by a
// constant force above the limit and by a ramp F = c t, which starts the rolling when
// c t = mu_r m g: then a = (c/m)(t - t_s) / (1 + β) and v(T) = (c/m)(T - t_s)² / (2 (1 + β)).
TEST(RollingResistance, BodiesPushedFromRestByConstantAndRampedForces) {
  for (RollingBody body : {RollingBody::kBall, RollingBody::kCylinder, RollingBody::kHoop}) {
    SCOPED_TRACE(static_cast<int>(body));
    RollingCase constant;
    constant.body = body;
    constant.F0 = 1.5;
    const RollingRun r1 = RunCase(constant, 0.5);
    const double a = (constant.F0 / constant.m - constant.r()) / (1 + constant.beta());
    EXPECT_TRUE(Near(SlopeVelocity(constant, r1.result.final_state), a * 0.5, kAccelRel));
    ExpectCertified(r1);

    RollingCase ramp;
    ramp.body = body;
    ramp.c = 2.0;  // N/s
    const double t_s = ramp.mu_r * ramp.m * ramp.g / ramp.c;
    ASSERT_TRUE(Near(ramp.StartTime(), t_s, 1e-15));
    const double T = 0.5;
    const RollingRun r2 = RunCase(ramp, T);
    const auto starts = EventsOf(r2.result, ContactEventReason::kRollingLimit);
    ASSERT_EQ(starts.size(), 1u);
    EXPECT_TRUE(Near(starts[0]->t, t_s, kEventRel));
    EXPECT_TRUE(starts[0]->held_from);
    EXPECT_FALSE(starts[0]->held_to);
    const double v = ramp.c / ramp.m * (T - t_s) * (T - t_s) / (2 * (1 + ramp.beta()));
    EXPECT_TRUE(Near(SlopeVelocity(ramp, r2.result.final_state), v, kAccelRel));
    ExpectCertified(r2);
  }
}

// A ball rolled up a slope at v0: it decelerates at g (sinθ + mu_r cosθ) / (1 + β) and stops
// at t1 = v0 / that; then it holds if tanθ <= mu_r, else rolls back at
// g (sinθ - mu_r cosθ) / (1 + β).
TEST(RollingResistance, BallRolledUpASlopeStopsThenHoldsOrRollsBack) {
  for (const double tan_theta : {0.03, 0.05, 0.08}) {
    SCOPED_TRACE(tan_theta);
    RollingCase c;
    c.theta = std::atan(tan_theta);
    c.v0 = 0.3;
    const double up = c.g * (std::sin(c.theta) + c.mu_r * std::cos(c.theta)) / 1.4;
    const double t1 = c.v0 / up;
    ASSERT_TRUE(Near(c.StopTime(), t1, 1e-14));
    const double T = 2.5 * t1;
    const RollingRun run = RunCase(c, T);
    const auto stops = EventsOf(run.result, ContactEventReason::kRollingStopped);
    ASSERT_GE(stops.size(), 1u);
    EXPECT_TRUE(Near(stops[0]->t, t1, kEventRel));
    const bool holds = tan_theta <= c.mu_r;
    EXPECT_EQ(stops[0]->held_to, holds);
    const State& s = run.result.final_state;
    if (holds) {
      EXPECT_LT(s.bodies[0].v_WBcm_W.norm(), 1e-12);
      EXPECT_TRUE(s.contacts[0].rolling_held);
    } else {
      const double down = c.g * (std::sin(c.theta) - c.mu_r * std::cos(c.theta)) / 1.4;
      EXPECT_TRUE(Near(SlopeVelocity(c, s), -down * (T - t1), kAccelRel));
      EXPECT_FALSE(s.contacts[0].rolling_held);
    }
    ExpectCertified(run);
  }
}

// A ball thrown along a level floor without spin slides (no rolling resistance while it
// slides: friction mu_k N alone), rolls from t* = β v0 / (mu_k g (1 + β)) at v* = v0/(1 + β),
// decelerates at mu_r g / (1 + β) and comes to rest, held, at t* + v0 / (mu_r g).
TEST(RollingResistance, BallSlidesRollsAndComesToRest) {
  RollingCase c;
  const double v0 = 2.0;
  const double beta = c.beta();
  const Model model = c.BuildModel();
  State s0 = c.InitialState(model);
  s0.bodies[0].v_WBcm_W = Vec3(v0, 0, 0);
  s0.bodies[0].w_WB_B.setZero();
  const double t_roll = beta * v0 / (c.mu_k * c.g * (1 + beta));
  const double t_rest = t_roll + v0 / (c.mu_r * c.g);
  SimulationOptions o;
  o.t_end = 1.2 * t_rest;
  o.output_interval = o.t_end / 10;
  o.adaptive.rtol = 1e-12;
  o.adaptive.atol = 1e-14;
  const SimulationResult r = Simulate(model, s0, o);
  const auto slips = EventsOf(r, ContactEventReason::kSlipStopped);
  const auto stops = EventsOf(r, ContactEventReason::kRollingStopped);
  ASSERT_EQ(slips.size(), 1u);
  ASSERT_EQ(stops.size(), 1u);
  EXPECT_TRUE(Near(slips[0]->t, t_roll, kEventRel));
  EXPECT_TRUE(Near(stops[0]->t, t_rest, kEventRel));
  EXPECT_TRUE(stops[0]->held_to);
  EXPECT_LT(r.final_state.bodies[0].v_WBcm_W.norm(), 1e-12);
  // Energy: the slide takes ½ m v0² β/(1 + β) (Problem 8.27's loss), rolling resistance the
  // rest, ½ m v0²/(1 + β).
  const ContactPointState& p = r.final_state.contacts[0];
  const double E0 = 0.5 * c.m * v0 * v0;
  EXPECT_TRUE(Near(p.friction_work, -E0 * beta / (1 + beta), kEventRel));
  EXPECT_TRUE(Near(p.rolling_work, -E0 / (1 + beta), kEventRel));
  CertificateBuilder cert;
  for (const State& s : r.samples) cert.CheckState(model, s, CheckPhase::kSample);
  const LedgerSample L = CalcLedgerSample(model, r.final_state, s0);
  cert.CheckLedger(o.t_end, L.energy_residual, L.energy_scale, CheckPhase::kSample);
  EXPECT_TRUE(cert.Finish().passed());
  EXPECT_LT(std::abs(L.energy_residual), 1e-10 * L.energy_scale);
}

// The instantaneous choice (what `solve` reports): at the threshold F = mu_r m g the ball is
// held (the motion decides: the rolling it would start has zero acceleration), just above it
// rolls.
TEST(RollingResistance, ModeSelectionAtTheThresholdFromEitherSide) {
  for (const double f : {1.0 - 1e-9, 1.0, 1.0 + 1e-9}) {
    RollingCase c;
    c.F0 = f * c.mu_r * c.m * c.g;
    const Model model = c.BuildModel();
    State s = c.InitialState(model);
    SelectContactModes(model, s);
    EXPECT_EQ(s.contacts[0].rolling_held, f <= 1.0) << f;
    Data d = MakeData(model);
    CalcAccelerations(model, s, d);
    const double a = d.a_WBcm_W[0].dot(c.x());
    // Accelerations to round-off of the problem's scale, g.
    EXPECT_TRUE(Near(a, f <= 1.0 ? 0.0 : c.RollingAcceleration(0.0, 1.0), 1e-12, c.g)) << f;
  }
}

}  // namespace
}  // namespace chasles
