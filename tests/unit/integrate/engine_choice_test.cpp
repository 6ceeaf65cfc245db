// The rule of integrator: auto (chasles/integrate/engine_choice.h) and the two ways a run hands
// over: the hybrid run yields where its regime changes come faster than the bound
// (ContactOptions::yield_changes), time stepping ends where no regime has changed for the quiet
// span (TimeSteppingOptions::quiet_span).
#include "chasles/integrate/engine_choice.h"

#include <cmath>
#include <memory>
#include <random>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "chasles/error.h"
#include "chasles/integrate/simulate.h"
#include "chasles/integrate/time_stepping.h"
#include "chasles/model/forces.h"
#include "reference/balls_on_floor.h"
#include "test_support.h"

namespace chasles {
namespace {

using test::Near;

constexpr double kG = 9.81;
// A sum of a few products of doubles of scale 1.
constexpr double kRoundOff = 1e-15;
// Event times are located to 1e-12 s each; a time summed over a few dozen is known to this [s].
constexpr double kEventTime = 1e-10;

// The rule for step h: 8 changes within 8 × 2 steps, back after as long without one.
TEST(EngineChoiceRule, BoundAndQuietSpanFromTheStep) {
  const double h = 1e-3;
  const EngineChoiceRule rule = MakeEngineChoiceRule(h);
  EXPECT_EQ(rule.step, h);
  EXPECT_EQ(rule.changes, 8);
  EXPECT_TRUE(Near(rule.window, 16 * h, kRoundOff));
  EXPECT_TRUE(Near(rule.quiet_span, 16 * h, kRoundOff));
  for (const double bad : {0.0, -1e-3, std::nan(""), HUGE_VAL}) {
    EXPECT_THROW(MakeEngineChoiceRule(bad), InputError) << bad;
  }
}

// h = 1/100 √(ρ / g) with ρ = √(I_max / m) the smallest radius of gyration of the bodies with
// contacts: a solid ball's is √(2/5) R; of two balls the smaller one's counts.
TEST(EngineChoiceRule, DefaultStepFromTheSmallestBodyAndGravity) {
  const reference::Ball big{1.0, 0.1, 0.3, 0.3}, small{0.2, 0.02, 0.3, 0.3};
  const Model one = reference::MakeBallsOnFloor(1, big, kG);
  EXPECT_TRUE(
      Near(DefaultEngineStep(one, 0.01), 0.01 * std::sqrt(std::sqrt(0.4) * 0.1 / kG), kRoundOff));
  const Model two = reference::MakeBallsOnFloor({big, small}, kG);
  EXPECT_TRUE(
      Near(DefaultEngineStep(two, 0.01), 0.01 * std::sqrt(std::sqrt(0.4) * 0.02 / kG), kRoundOff));
  // Without gravity: a tenth of the output interval; with neither, no step to derive.
  const Model weightless = reference::MakeBallsOnFloor(1, big, 0.0);
  EXPECT_EQ(DefaultEngineStep(weightless, 0.01), 1e-3);
  EXPECT_THROW(DefaultEngineStep(weightless, 0.0), InputError);
}

// The yield tests' run: 2 s, rows every 0.01 s, tolerance 1e-12, bounces not summed, `rule`'s
// bound.
SimulationOptions YieldOptions(const EngineChoiceRule& rule) {
  SimulationOptions o;
  o.t_end = 2.0;
  o.output_interval = 0.01;
  o.adaptive.rtol = 1e-12;
  o.adaptive.atol = 1e-14;
  o.contact.accumulate_bounces = false;
  o.contact.yield_changes = rule.changes;
  o.contact.yield_window = rule.window;
  return o;
}

// Touch-down n of a ball dropped from h0 with restitution e, T_n = t0 + 2 t0 e (1 - e^n)/(1 - e)
// with t0 = √(2 h0 / g), and the first n >= 7 with T_n - T_(n-7) within `window`.
double TouchDown(double h0, double e, int n) {
  const double t0 = std::sqrt(2 * h0 / kG);
  return t0 + 2 * t0 * e * (1 - std::pow(e, n)) / (1 - e);
}
int FirstYield(double h0, double e, double window) {
  int n = 7;
  while (TouchDown(h0, e, n) - TouchDown(h0, e, n - 7) > window) ++n;
  return n;
}

// A ball dropped from h0 with restitution e and its bounces not summed: touch-down n at
// T_n = t0 + 2 t0 e (1 - e^n)/(1 - e), t0 = √(2 h0 / g). The run yields at the first n >= 7
// with T_n - T_(n-7) <= the window, at the state just after that touch-down, which is not a
// sample.
TEST(HybridYield, YieldsAtTheTouchDownThatExceedsTheBound) {
  const double h0 = 1.0, e = 0.5;
  reference::Ball ball{0.5, 0.1, 0.3, 0.3};
  ball.restitution = e;
  const Model model = reference::MakeBallsOnFloor(1, ball, kG);
  State s = MakeRestState(model);
  SetBodyPose(model, 0, Vec3(0, 0, ball.radius + h0), Quat::Identity(), s);
  const EngineChoiceRule rule = MakeEngineChoiceRule(1e-3);
  SimulationOptions o = YieldOptions(rule);
  const auto touch_down = [&](int n) { return TouchDown(h0, e, n); };
  const int n = FirstYield(h0, e, rule.window);
  const SimulationResult r = Simulate(model, s, o);
  ASSERT_TRUE(r.yielded.has_value());
  EXPECT_EQ(r.yielded->changes, 8);
  EXPECT_EQ(r.yielded->where, "floor0");
  EXPECT_NEAR(r.yielded->t_last, touch_down(n), kEventTime);
  EXPECT_NEAR(r.yielded->t_first, touch_down(n - 7), kEventTime);
  EXPECT_EQ(r.final_state.t, r.yielded->t_last);
  EXPECT_LT(r.samples.back().t, r.final_state.t);
  EXPECT_EQ(r.impacts.size(), static_cast<size_t>(n + 1));
  // Just after the touch-down: rebounding at e times the approach speed e^n √(2 g h0).
  EXPECT_NEAR(r.final_state.bodies[0].v_WBcm_W.z(), std::pow(e, n + 1) * std::sqrt(2 * kG * h0),
              kG * kEventTime);
  // The same bounces summed in closed form do not count: the run reaches its end.
  o.contact.accumulate_bounces = true;
  const SimulationResult summed = Simulate(model, s, o);
  EXPECT_FALSE(summed.yielded.has_value());
  EXPECT_EQ(summed.final_state.t, 2.0);
  EXPECT_TRUE(summed.impacts.back().accumulation);
}

// A run that may yield still runs its islands separately, each counting its own regime
// changes, and hands the whole model over at once: ball 0 bounces (e = 1/2, bounces not summed)
// and yields at touch-down n as alone (the test above); ball 1, its own island, slides from v0
// and rolls from t_s = 2 v0 / (7 mu g) on at 5/7 v0, x = v0 t_s - mu g t_s² / 2 + 5/7 v0 (t - t_s).
// Its island ran on past the yield, and is run again to end there: the result is the one
// system's (islands = false, which yields at the same touch-down: ball 1's one change lies far
// outside the window) to the events' tolerance.
TEST(HybridYield, IslandsRunSeparatelyAndHandOverTogether) {
  const double h0 = 1.0, e = 0.5, v0 = 1.0;
  reference::Ball bouncer{0.5, 0.1, 0.3, 0.3}, slider{0.5, 0.1, 0.3, 0.3};
  bouncer.restitution = e;
  const Model model = reference::MakeBallsOnFloor({bouncer, slider}, kG);
  State s = MakeRestState(model);
  SetBodyPose(model, 0, Vec3(0, 0, bouncer.radius + h0), Quat::Identity(), s);
  SetBodyPose(model, 1, Vec3(5, 0, slider.radius), Quat::Identity(), s);
  SetBodyVelocity(model, 1, Vec3(v0, 0, 0), Vec3::Zero(), s);
  const EngineChoiceRule rule = MakeEngineChoiceRule(1e-3);
  SimulationOptions o = YieldOptions(rule);
  const auto touch_down = [&](int n) { return TouchDown(h0, e, n); };
  const int n = FirstYield(h0, e, rule.window);
  const SimulationResult r = Simulate(model, s, o);
  EXPECT_EQ(r.islands.count, 2);
  EXPECT_TRUE(r.islands.split);
  ASSERT_TRUE(r.yielded.has_value());
  EXPECT_EQ(r.yielded->where, "floor0");
  EXPECT_NEAR(r.yielded->t_last, touch_down(n), kEventTime);
  EXPECT_EQ(r.final_state.t, r.yielded->t_last);
  EXPECT_EQ(r.impacts.size(), static_cast<size_t>(n + 1));
  EXPECT_NEAR(r.final_state.bodies[0].v_WBcm_W.z(), std::pow(e, n + 1) * std::sqrt(2 * kG * h0),
              kG * kEventTime);
  // Ball 1 at the hand-over, in closed form.
  const double mu_g = slider.mu_k * kG, t_s = 2 * v0 / (7 * mu_g), t = r.final_state.t;
  const BodyState& b1 = r.final_state.bodies[1];
  EXPECT_NEAR(b1.v_WBcm_W.x(), 5.0 / 7.0 * v0, 1e-12);
  EXPECT_NEAR(b1.p_WBcm.x(), 5 + v0 * t_s - 0.5 * mu_g * t_s * t_s + 5.0 / 7.0 * v0 * (t - t_s),
              1e-9);
  // The samples are the grid times before the hand-over, every island's at the same times.
  const size_t grid = static_cast<size_t>(std::floor(t / o.output_interval)) + 1;
  ASSERT_EQ(r.samples.size(), grid);
  EXPECT_LT(r.samples.back().t, t);
  // The same run as one system.
  SimulationOptions one = o;
  one.islands = false;
  const SimulationResult w = Simulate(model, s, one);
  EXPECT_FALSE(w.islands.split);
  ASSERT_TRUE(w.yielded.has_value());
  EXPECT_NEAR(w.yielded->t_last, r.yielded->t_last, kEventTime);
  ASSERT_EQ(w.samples.size(), r.samples.size());
  for (size_t k = 0; k < r.samples.size(); ++k) {
    EXPECT_NEAR(w.samples[k].t, r.samples[k].t, kRoundOff);
    for (size_t b = 0; b < 2; ++b) {
      EXPECT_NEAR((w.samples[k].bodies[b].p_WBcm - r.samples[k].bodies[b].p_WBcm).norm(), 0.0, 1e-9)
          << "sample " << k << ", ball " << b;
    }
  }
  for (size_t b = 0; b < 2; ++b) {
    EXPECT_NEAR((w.final_state.bodies[b].v_WBcm_W - r.final_state.bodies[b].v_WBcm_W).norm(), 0.0,
                kG * kEventTime);
  }
  o.contact.yield_window = -1.0;
  EXPECT_THROW(Simulate(model, s, o), InputError);
}

// Seeded: three balls dropped from random heights h_i in U(0.3, 2) m (e = 1/2, bounces not
// summed), each its own island. Each island counts its own touch-downs, so the run yields at the
// earliest of the balls' own yield instants T_(n_i)(h_i), and every other ball is handed over
// where its bounces put it then: after touch-down k (T_k <= t < T_(k+1)) at height
// u_k τ - g τ²/2 with speed u_k - g τ, τ = t - T_k, u_k = e^(k+1) √(2 g h) (before the first,
// h - g t²/2 falling at g t).
TEST(HybridYield, SeededDropsHandOverAtTheEarliestIslandsYield) {
  const double e = 0.5;
  const EngineChoiceRule rule = MakeEngineChoiceRule(1e-3);
  for (const unsigned seed : {1u, 2u, 3u, 4u, 5u}) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> height(0.3, 2.0);
    reference::Ball ball{0.5, 0.1, 0.3, 0.3};
    ball.restitution = e;
    const Model model = reference::MakeBallsOnFloor(3, ball, kG);
    State s = MakeRestState(model);
    std::vector<double> h(3);
    double t_y = HUGE_VAL;
    for (int i = 0; i < 3; ++i) {
      h[static_cast<size_t>(i)] = height(rng);
      SetBodyPose(model, i, Vec3(3.0 * i, 0, ball.radius + h[static_cast<size_t>(i)]),
                  Quat::Identity(), s);
      const double h_i = h[static_cast<size_t>(i)];
      t_y = std::min(t_y, TouchDown(h_i, e, FirstYield(h_i, e, rule.window)));
    }
    SimulationOptions o = YieldOptions(rule);
    o.t_end = 3.0;
    const SimulationResult r = Simulate(model, s, o);
    ASSERT_TRUE(r.islands.split) << seed;
    ASSERT_TRUE(r.yielded.has_value()) << seed;
    EXPECT_NEAR(r.final_state.t, t_y, kEventTime) << seed;
    const double t = r.final_state.t;
    for (int i = 0; i < 3; ++i) {
      const double h_i = h[static_cast<size_t>(i)];
      double z = h_i - 0.5 * kG * t * t, vz = -kG * t;
      // (The yielding ball is handed over just after its touch-down, located to kEventTime.)
      for (int k = 0; TouchDown(h_i, e, k) <= t + kEventTime; ++k) {
        const double tau = t - TouchDown(h_i, e, k);
        const double u = std::pow(e, k + 1) * std::sqrt(2 * kG * h_i);
        z = u * tau - 0.5 * kG * tau * tau;
        vz = u - kG * tau;
      }
      const BodyState& b = r.final_state.bodies[static_cast<size_t>(i)];
      EXPECT_NEAR(b.p_WBcm.z() - ball.radius, z, 1e-9) << seed << ", ball " << i;
      EXPECT_NEAR(b.v_WBcm_W.z(), vz, kG * kEventTime) << seed << ", ball " << i;
    }
  }
}

// A ball set down touching the floor at rest: the first step finds it touching (sticking, a
// regime change from the separated mode it was given), none after. With a quiet span of 10.5
// steps the run ends after step 12, the first to end 10.5 steps or more after step 1's change.
TEST(SteppingQuiet, EndsAfterTheQuietSpan) {
  const reference::Ball ball{0.5, 0.1, 0.3, 0.3};
  const Model model = reference::MakeBallsOnFloor(1, ball, kG);
  State s = MakeRestState(model);
  SetBodyPose(model, 0, Vec3(0, 0, ball.radius), Quat::Identity(), s);
  const double h = 1e-3;
  TimeSteppingOptions o;
  o.t_end = 1.0;
  o.step = h;
  o.quiet_span = 10.5 * h;
  const TimeSteppingResult r = SimulateTimeStepping(model, s, o);
  EXPECT_TRUE(r.quiet);
  EXPECT_EQ(r.summary.steps, 12);
  EXPECT_TRUE(Near(r.last_regime_change, h, kRoundOff));
  EXPECT_TRUE(Near(r.final_state.t, 12 * h, kRoundOff));
  EXPECT_EQ(r.final_state.contacts[0].mode, ContactMode::kSticking);
  // The final state is not a sample: only the initial one was taken.
  ASSERT_EQ(r.samples.size(), 1u);
  // Continuing a quiet stretch (quiet_from at the last change): the first step ends it.
  o.quiet_from = r.final_state.t - 11 * h;
  const TimeSteppingResult next = SimulateTimeStepping(model, r.final_state, o);
  EXPECT_TRUE(next.quiet);
  EXPECT_EQ(next.summary.steps, 1);
  o.quiet_span = 0.0;
  EXPECT_THROW(SimulateTimeStepping(model, s, o), InputError);
}

}  // namespace
}  // namespace chasles
