// integrator: auto (docs/contact.md, "Choosing the engine"), run by RunStudy on Models built
// here: where the event-driven engine's regime changes come faster than the bound the run goes
// on time stepped, and back to events once the contacts are quiet; the answers before, between
// and after the switches against closed forms derived in the comments.

#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "chasles/analysis/study.h"
#include "chasles/error.h"
#include "chasles/integrate/engine_choice.h"
#include "chasles/model/forces.h"
#include "chasles/model/model.h"
#include "test_support.h"

namespace chasles {
namespace {

using test::Near;

constexpr double kG = 9.80665;
// Event times are located to 1e-12 s each; a time summed over a few dozen of them is known to
// this absolute tolerance [s].
constexpr double kEventTime = 1e-10;
// Positions, velocities and forces after the event-driven engine's start has projected the
// state onto the contacts: round-off of the projection, relative to the body's scale.
constexpr double kProjected = 1e-12;

RotationalInertia Diag(double a, double b, double c) {
  return RotationalInertia::FromMatrix(Vec3(a, b, c).asDiagonal());
}

// One body (index 0) under gravity -g z with one contact `spec` against the floor z = 0.
StudyDefinition OnFloor(const std::string& name, const MassProperties& mp, ContactSpec spec,
                        const Vec3& p_WBo, const Quat& q_WB, double t_end) {
  StudyDefinition def;
  def.bodies = {{name, mp}};
  def.build_model = [spec](const std::vector<NamedBody>& bodies, const BodyMap&) {
    Model model;
    model.AddBody(bodies[0].name, bodies[0].mass_properties);
    model.AddForceElement(std::make_shared<UniformGravity>("gravity", Vec3(0, 0, -kG)));
    model.AddContact(spec);
    return model;
  };
  const Model model = def.build_model(def.bodies, {});
  def.initial = MakeRestState(model);
  SetBodyPose(model, 0, p_WBo, q_WB, def.initial);
  def.options.t_end = t_end;
  def.options.output_interval = 0.01;
  def.options.adaptive.rtol = 1e-12;
  def.options.adaptive.atol = 1e-14;
  return def;
}

// A solid ball (I = 2/5 m R²) whose lowest point is h0 above the floor, at rest.
struct BouncingBall {
  double m = 0.5, R = 0.1, h0 = 1.0, e = 0.5, mu = 0.3;
  StudyDefinition Definition(double t_end) const {
    ContactSpec spec;
    spec.name = "floor";
    spec.shape = ContactShape::kSphere;
    spec.body = 0;
    spec.radius = R;
    spec.mu_s = spec.mu_k = mu;
    spec.restitution = e;
    spec.restitution_law = RestitutionLaw::kNewton;
    const double I = 0.4 * m * R * R;
    return OnFloor("ball", MassProperties(m, Vec3::Zero(), Diag(I, I, I)), spec, Vec3(0, 0, R + h0),
                   Quat::Identity(), t_end);
  }
  // Touch-down n (n = 0 the first, after the fall t0 = √(2 h0 / g)): the flight after
  // touch-down j lasts 2 e^(j+1) t0 (the rebound speed e^(j+1) √(2 g h0) up and down again), so
  //   T_n = t0 + 2 t0 Σ_{j=1..n} e^j = t0 + 2 t0 e (1 - e^n) / (1 - e),
  // and the touch-downs accumulate at t∞ = t0 (1 + e) / (1 - e).
  double t0() const { return std::sqrt(2 * h0 / kG); }
  double TouchDown(int n) const { return t0() + 2 * t0() * e * (1 - std::pow(e, n)) / (1 - e); }
  double Rest() const { return t0() * (1 + e) / (1 - e); }
  // The first touch-down n >= 7 with T_n - T_(n-7) within `window`: where auto yields.
  int FirstYield(double window) const {
    int n = 7;
    while (TouchDown(n) - TouchDown(n - 7) > window) ++n;
    return n;
  }
};

// The contacts' normal force on body 0 at the end, summed over its points.
double NormalForce(const StudyResult& r) {
  double N = 0.0;
  for (const StudyContactPoint& c : r.final_contacts) N += c.normal_force;
  return N;
}

// A ball dropped with restitution 0.5 bounces to rest at t∞ (Zeno). With its bounces not summed
// (ContactOptions::accumulate_bounces off) the event-driven engine would locate every one of
// them, ever shorter, and never reach t∞; under auto it yields where 8 touch-downs fall within
// the bound's window of 8 × 2 steps: at the first touch-down n >= 7 with
//   T_n - T_(n-7) = 2 t0 e^(n-6) (1 - e^7) / (1 - e) <= window.
// Up to there every bounce is exact (its approach speed e^n √(2 g h0)); time stepping then takes
// the ball to rest within a few steps of t∞ (Moreau's law: each bounce shorter than a step ends
// in one), and once no regime has changed for the quiet span the event-driven engine takes over
// the ball at rest: v = 0, its centre at R above the floor, N = m g.
TEST(EngineChoice, ZenoBouncesNotSummedSwitchToSteppingAndRest) {
  const BouncingBall ball;
  StudyDefinition def = ball.Definition(2.0);
  def.options.contact.accumulate_bounces = false;
  const Model model = def.build_model(def.bodies, {});
  const double h = DefaultEngineStep(model, def.options.output_interval);
  // The default step: 1/100 of √(ρ / g), ρ = √(2/5) R the ball's radius of gyration.
  EXPECT_TRUE(Near(h, 0.01 * std::sqrt(std::sqrt(0.4) * ball.R / kG), 1e-15));
  def.auto_engine = StudyDefinition::AutoEngine{MakeEngineChoiceRule(h), {}};
  const EngineChoiceRule& rule = def.auto_engine->rule;
  const int n = ball.FirstYield(rule.window);
  const StudyResult r = RunStudy(def);
  ASSERT_EQ(r.segments.size(), 3u);
  const StudyEngineSegment& events = r.segments[0];
  const StudyEngineSegment& stepping = r.segments[1];
  const StudyEngineSegment& rest = r.segments[2];
  EXPECT_EQ(events.engine, StudyEngine::kAdaptive);
  EXPECT_EQ(events.reason, EngineSwitch::kStart);
  EXPECT_EQ(stepping.engine, StudyEngine::kStepping);
  EXPECT_EQ(stepping.reason, EngineSwitch::kRegimeChanges);
  EXPECT_EQ(stepping.changes, 8);
  EXPECT_NEAR(stepping.t_begin, ball.TouchDown(n), kEventTime);
  EXPECT_NEAR(stepping.span, ball.TouchDown(n) - ball.TouchDown(n - 7), kEventTime);
  // Every bounce before the switch, exact: approach speed e^k √(2 g h0), to the event times'
  // error times g.
  ASSERT_EQ(std::count_if(r.impacts.begin(), r.impacts.end(),
                          [&](const StudyImpact& i) { return i.t <= stepping.t_begin; }),
            n + 1);
  for (int k = 0; k <= n; ++k) {
    EXPECT_NEAR(r.impacts[static_cast<size_t>(k)].t, ball.TouchDown(k), kEventTime) << k;
    EXPECT_NEAR(r.impacts[static_cast<size_t>(k)].approach_speed,
                std::pow(ball.e, k) * std::sqrt(2 * kG * ball.h0), kG * kEventTime)
        << k;
  }
  // Time stepping ends the bounces within a few steps of t∞: the last regime change.
  EXPECT_EQ(rest.engine, StudyEngine::kAdaptive);
  EXPECT_EQ(rest.reason, EngineSwitch::kQuiet);
  EXPECT_GE(rest.quiet, rule.quiet_span);
  const double t_last_change = rest.t_begin - rest.quiet;
  EXPECT_NEAR(t_last_change, ball.Rest(), 3 * h);
  EXPECT_TRUE(stepping.tolerance_met);
  // At rest on the floor: v = 0, centre at R, N = m g (the engine's start projected it there).
  ASSERT_EQ(r.final_bodies.size(), 1u);
  const StudyBodyState& b = r.final_bodies[0];
  EXPECT_NEAR(b.p_WBcm.z(), ball.R, kProjected * ball.R);
  EXPECT_LT(b.v_WBcm_W.norm(), kProjected * std::sqrt(kG * ball.R));
  EXPECT_TRUE(Near(NormalForce(r), ball.m * kG, kProjected));
  EXPECT_EQ(r.final_contacts[0].mode.mode, ContactMode::kSticking);
  // The ledger closes once time stepping's own term is taken out; all of m g h0 went into the
  // impacts (the ball ends h0 lower, at rest) and friction took nothing (no slip).
  EXPECT_LT(std::abs(r.ledger.residual - r.ledger.time_stepping_error),
            1e-9 * r.ledger.energy_scale);
  EXPECT_TRUE(
      Near(-r.ledger.impact_work, ball.m * kG * ball.h0 + r.ledger.time_stepping_error, 1e-9));
  EXPECT_EQ(r.ledger.friction_work, 0.0);
  EXPECT_TRUE(r.certificate.passed());
}

// The same ball beside a second one rolling at v0 far away (its own island): the islands run
// apart and count their regime changes apart, so the run switches at the bouncing ball's
// touch-down T_n as alone, the whole model is handed over there and back at once, and the
// rolling ball, which no engine disturbs (no force along the floor, its point sticking with no
// friction), is at x0 + v0 t at the end to round-off.
TEST(EngineChoice, AnIslandThatYieldsHandsOverTheWholeModel) {
  const BouncingBall ball;
  StudyDefinition def = ball.Definition(2.0);
  def.options.contact.accumulate_bounces = false;
  const MassProperties mp = def.bodies[0].mass_properties;
  def.bodies.push_back({"roller", mp});
  def.build_model = [ball, mp](const std::vector<NamedBody>& bodies, const BodyMap&) {
    Model model;
    for (const NamedBody& b : bodies) model.AddBody(b.name, b.mass_properties);
    model.AddForceElement(std::make_shared<UniformGravity>("gravity", Vec3(0, 0, -kG)));
    for (int i = 0; i < 2; ++i) {
      ContactSpec spec;
      spec.name = i == 0 ? "floor" : "floor_roller";
      spec.shape = ContactShape::kSphere;
      spec.body = i;
      spec.radius = ball.R;
      spec.mu_s = spec.mu_k = ball.mu;
      spec.restitution = ball.e;
      model.AddContact(spec);
    }
    return model;
  };
  const Model model = def.build_model(def.bodies, {});
  const double v0 = 0.8, x0 = 5.0;
  State s = MakeRestState(model);
  SetBodyPose(model, 0, Vec3(0, 0, ball.R + ball.h0), Quat::Identity(), s);
  SetBodyPose(model, 1, Vec3(x0, 0, ball.R), Quat::Identity(), s);
  SetBodyVelocity(model, 1, Vec3(v0, 0, 0), Vec3(0, v0 / ball.R, 0), s);
  def.initial = s;
  const double h = DefaultEngineStep(model, def.options.output_interval);
  def.auto_engine = StudyDefinition::AutoEngine{MakeEngineChoiceRule(h), {}};
  const EngineChoiceRule& rule = def.auto_engine->rule;
  const int n = ball.FirstYield(rule.window);
  const StudyResult r = RunStudy(def);
  ASSERT_EQ(r.segments.size(), 3u);
  EXPECT_TRUE(r.islands.split);
  EXPECT_EQ(r.islands.count, 2);
  EXPECT_EQ(r.segments[0].islands, 2);
  EXPECT_EQ(r.segments[2].islands, 2);
  EXPECT_EQ(r.segments[1].engine, StudyEngine::kStepping);
  EXPECT_NEAR(r.segments[1].t_begin, ball.TouchDown(n), kEventTime);
  EXPECT_EQ(r.segments[2].engine, StudyEngine::kAdaptive);
  ASSERT_EQ(r.final_bodies.size(), 2u);
  const StudyBodyState& roller = r.final_bodies[1];
  EXPECT_NEAR(roller.p_WBcm.x(), x0 + v0 * 2.0, kProjected * x0);
  EXPECT_NEAR(roller.v_WBcm_W.x(), v0, kProjected * v0);
  EXPECT_NEAR(r.final_bodies[0].p_WBcm.z(), ball.R, kProjected * ball.R);
  EXPECT_TRUE(r.certificate.passed());
}

// With the bounces summed (the default) the event-driven engine ends the same Zeno sequence in
// closed form: a touch-down that continues a geometric sequence does not count towards the
// bound, so auto never switches and its answer is the event-driven one, bit for bit.
TEST(EngineChoice, SummedBouncesNeverSwitch) {
  const BouncingBall ball;
  StudyDefinition adaptive = ball.Definition(2.0);
  StudyDefinition chosen = adaptive;
  const Model model = chosen.build_model(chosen.bodies, {});
  chosen.auto_engine = StudyDefinition::AutoEngine{
      MakeEngineChoiceRule(DefaultEngineStep(model, chosen.options.output_interval)), {}};
  const StudyResult a = RunStudy(adaptive);
  const StudyResult c = RunStudy(chosen);
  ASSERT_EQ(c.segments.size(), 1u);
  EXPECT_EQ(c.segments[0].engine, StudyEngine::kAdaptive);
  EXPECT_EQ(c.segments[0].t_end, 2.0);
  EXPECT_TRUE(a.segments.empty());
  EXPECT_EQ(a.rows, c.rows);
  ASSERT_EQ(a.impacts.size(), c.impacts.size());
  EXPECT_TRUE(c.impacts.back().accumulation);
  EXPECT_NEAR(c.impacts.back().rest_time, ball.Rest(), kEventTime);
}

// The ball of the Zeno test, at rest after time stepping handed it back, kicked at t_k by a
// horizontal impulse J through its centre: v0 = J / m, no spin. It slides with friction mu m g
// against the slip: v = v0 - mu g τ, ω R = 5/2 mu g τ, until the slip v - ω R is gone at
// τ* = 2 v0 / (7 mu g), then rolls at 5/7 v0 (Problems 8.26-8.27), all event-driven again:
// events -> stepping -> events, and the kick's answer exact.
TEST(EngineChoice, BallKickedAfterSettlingSlidesThenRollsEventDriven) {
  const BouncingBall ball;
  const double t_kick = 1.5, J = 0.35;
  StudyDefinition def = ball.Definition(2.0);
  def.options.contact.accumulate_bounces = false;
  const Model model = def.build_model(def.bodies, {});
  def.auto_engine = StudyDefinition::AutoEngine{
      MakeEngineChoiceRule(DefaultEngineStep(model, def.options.output_interval)), {}};
  def.impulses = {{t_kick, 0, Vec3::Zero(), Vec3(J, 0, 0), VectorFrame::kWorld}};
  const StudyResult r = RunStudy(def);
  ASSERT_EQ(r.segments.size(), 3u);
  EXPECT_EQ(r.segments[1].engine, StudyEngine::kStepping);
  EXPECT_EQ(r.segments[2].engine, StudyEngine::kAdaptive);
  EXPECT_LT(r.segments[2].t_begin, t_kick);
  const double v0 = J / ball.m;
  const double tau = 2 * v0 / (7 * ball.mu * kG);
  const auto slip_stop = std::find_if(
      r.contact_events.begin(), r.contact_events.end(),
      [](const StudyContactEvent& e) { return e.reason == ContactEventReason::kSlipStopped; });
  ASSERT_NE(slip_stop, r.contact_events.end());
  EXPECT_NEAR(slip_stop->t, t_kick + tau, kEventTime);
  const StudyBodyState& b = r.final_bodies[0];
  EXPECT_TRUE(Near(b.v_WBcm_W.x(), 5.0 / 7.0 * v0, 1e-9));
  EXPECT_NEAR(b.w_WB_W.y() * ball.R, 5.0 / 7.0 * v0, 1e-9 * v0);
  // Distance from the kick: v0 τ - ½ mu g τ² sliding, then 5/7 v0 (t_end - t_k - τ) rolling,
  // from where the ball rested (x = 0: a vertical bounce moves nothing sideways).
  const double x =
      v0 * tau - 0.5 * ball.mu * kG * tau * tau + 5.0 / 7.0 * v0 * (2.0 - t_kick - tau);
  EXPECT_NEAR(b.p_WBcm.x(), x, 1e-9 * x);
  EXPECT_TRUE(r.certificate.passed());
}

// A cube dropped tilted onto a floor with friction and restitution 0.5 rocks from edge to edge
// in impacts ever closer together: the event-driven engine makes no progress past an instant
// (it switches modes there until its guard stops it, whatever the guard's count), and
// auto finishes. At the end the cube rests flat on four corners: its centre a/2 above the
// floor, no tilt, v = ω = 0, N = m g in all, and the energy m g (z0 - a/2) gone into the
// impacts and friction.
struct TumblingCube {
  double m = 1.0, a = 0.2, z0 = 0.3, tilt = 10 * std::numbers::pi / 180, mu = 0.3, e = 0.5;
  StudyDefinition Definition(double t_end) const {
    ContactSpec spec;
    spec.name = "floor";
    spec.shape = ContactShape::kBox;
    spec.body = 0;
    spec.half_extents = Vec3::Constant(a / 2);
    spec.mu_s = spec.mu_k = mu;
    spec.restitution = e;
    spec.restitution_law = RestitutionLaw::kNewton;
    const double I = m * a * a / 6;
    return OnFloor("cube", MassProperties(m, Vec3::Zero(), Diag(I, I, I)), spec, Vec3(0, 0, z0),
                   Quat(Eigen::AngleAxisd(tilt, Vec3::UnitX())), t_end);
  }
};

TEST(EngineChoice, TumblingCubeChattersUnderEventsAndRestsUnderAuto) {
  const TumblingCube cube;
  // Event-driven: the guard's count reached at one and the same instant, 2000 switches or 4000.
  double stuck[2] = {0.0, 0.0};
  for (int i = 0; i < 2; ++i) {
    StudyDefinition def = cube.Definition(1.0);
    def.options.contact.max_mode_switches = 2000 * (i + 1);
    try {
      RunStudy(def);
      FAIL() << "the event-driven run should chatter";
    } catch (const InputError& e) {
      const std::string what = e.what();
      ASSERT_THAT(what, ::testing::HasSubstr("the motion chatters"));
      stuck[i] = std::stod(what.substr(what.find("(at t = ") + 8));
    }
  }
  // Twice the switches, no progress: the event-driven run is stuck at one instant.
  EXPECT_LT(stuck[0], 1.0);
  EXPECT_NEAR(stuck[1], stuck[0], 1e-9);
  // Auto: events, then time stepping, ..., events again at rest.
  StudyDefinition def = cube.Definition(1.0);
  const Model model = def.build_model(def.bodies, {});
  def.auto_engine = StudyDefinition::AutoEngine{
      MakeEngineChoiceRule(DefaultEngineStep(model, def.options.output_interval)), {}};
  const StudyResult r = RunStudy(def);
  ASSERT_GE(r.segments.size(), 3u);
  EXPECT_EQ(r.segments[1].engine, StudyEngine::kStepping);
  EXPECT_LE(r.segments[1].t_begin, stuck[0]);
  EXPECT_EQ(r.segments.back().engine, StudyEngine::kAdaptive);
  EXPECT_EQ(r.segments.back().reason, EngineSwitch::kQuiet);
  EXPECT_DOUBLE_EQ(r.t_end, 1.0);
  const StudyBodyState& b = r.final_bodies[0];
  EXPECT_NEAR(b.p_WBcm.z(), cube.a / 2, kProjected * cube.a);
  EXPECT_LT(b.v_WBcm_W.norm(), kProjected * std::sqrt(kG * cube.a));
  EXPECT_LT(b.w_WB_W.norm() * cube.a, kProjected * std::sqrt(kG * cube.a));
  // Flat: the body's z axis along the world's, to round-off.
  EXPECT_NEAR((b.q_WB * Vec3::UnitZ()).dot(Vec3::UnitZ()), 1.0, kProjected);
  EXPECT_TRUE(Near(NormalForce(r), cube.m * kG, kProjected));
  // The energy at rest m g a/2; what the impacts and friction took is the rest of m g z0, apart
  // from time stepping's own term (booked in the residual, not as work).
  EXPECT_TRUE(Near(r.ledger.energy, cube.m * kG * cube.a / 2, kProjected));
  EXPECT_TRUE(Near(r.ledger.dissipated,
                   cube.m * kG * (cube.z0 - cube.a / 2) + r.ledger.time_stepping_error, 1e-9));
  EXPECT_LT(std::abs(r.ledger.residual - r.ledger.time_stepping_error),
            1e-9 * r.ledger.energy_scale);
  EXPECT_TRUE(r.certificate.passed());
}

}  // namespace
}  // namespace chasles
