// Rolling resistance in both directions over seeded random scenes: a round body (ball,
// spherical shell, cylinder on both end rims, hoop) on a random slope with a random push
// either starts to roll from rest when a ramped push reaches the limit mu_r N R (held → rolling)
// or, rolled at v0 against a constant push, stops and then holds or rolls back (rolling →
// held or rolling the other way). Every regime-change time and the velocity after it against
// the closed forms of tests/reference/rolling_resistance.h.

#include <cmath>
#include <numbers>
#include <random>

#include <gtest/gtest.h>

#include "chasles/integrate/simulate.h"
#include "reference/rolling_resistance.h"
#include "test_support.h"

namespace chasles {
namespace {

using test::Near;
using test::RollingBody;
using test::RollingCase;

// Event times located to 1e-12 s; polynomial motion in each regime, integrated exactly.
constexpr double kEventRel = 1e-9;

SimulationOptions Options(double t_end) {
  SimulationOptions o;
  o.t_end = t_end;
  o.adaptive.rtol = 1e-12;
  o.adaptive.atol = 1e-14;
  return o;
}

const ContactEvent* First(const SimulationResult& r, ContactEventReason why) {
  for (const ContactEvent& e : r.contact_events) {
    if (e.reason == why) return &e;
  }
  return nullptr;
}

int CountOf(const SimulationResult& r, ContactEventReason why) {
  int n = 0;
  for (const ContactEvent& e : r.contact_events) n += e.reason == why ? 1 : 0;
  return n;
}

RollingCase RandomBody(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> U(0.0, 1.0);
  RollingCase c;
  c.body = static_cast<RollingBody>(std::uniform_int_distribution<int>(0, 3)(rng));
  c.m = 0.1 + 4.9 * U(rng);
  c.R = 0.01 + 0.29 * U(rng);
  c.mu_r = 0.005 + 0.095 * U(rng);
  // Friction enough to hold the rolling whatever the push below (|f| < 1.6 N).
  c.mu_s = 3.0, c.mu_k = 2.5;
  c.theta = U(rng) < 0.25 ? 0.0 : 20.0 * std::numbers::pi / 180.0 * U(rng);
  return c;
}

// Held at t = 0 with P(0) inside (-r, r); a ramp takes P to ±r at t_s: one start, then
// a = (c/m)(t - t_s)/(1 + β).
TEST(RollingResistanceProperty, RampedPushStartsTheRollingAtTheLimit) {
  std::mt19937_64 rng(20261128);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  const long n = test::Repeats(500);
  for (long i = 0; i < n; ++i) {
    RollingCase c = RandomBody(rng);
    const double P0 = c.r() * (2.0 * U(rng) - 1.0) * 0.999;
    const double sign = U(rng) < 0.5 ? -1.0 : 1.0;
    const double t_s = 0.05 + 0.95 * U(rng);
    c.F0 = c.m * (P0 + c.g * std::sin(c.theta));
    c.c = c.m * (sign * c.r() - P0) / t_s;
    const double T = t_s + 0.05 + 0.45 * U(rng);
    const Model model = c.BuildModel();
    const SimulationResult r = Simulate(model, c.InitialState(model), Options(T));
    SCOPED_TRACE(::testing::Message() << "case " << i);
    ASSERT_TRUE(r.final_state.contacts[0].mode == ContactMode::kSticking);
    const ContactEvent* start = First(r, ContactEventReason::kRollingLimit);
    ASSERT_NE(start, nullptr);
    EXPECT_EQ(CountOf(r, ContactEventReason::kRollingLimit), 1);
    EXPECT_TRUE(Near(start->t, c.StartTime(), kEventRel));
    EXPECT_TRUE(start->held_from && !start->held_to);
    EXPECT_EQ(CountOf(r, ContactEventReason::kRollingStopped), 0);
    const double v = c.c / c.m * (T - t_s) * (T - t_s) / (2 * (1 + c.beta()));
    EXPECT_TRUE(Near(r.final_state.bodies[0].v_WBcm_W.dot(c.x()), v, kEventRel));
  }
}

// Rolling at v0 against a constant push: stops at t1 = -v0/a; then held if |P| <= r, else
// rolls back with a2 = (P - sign(P) r)/(1 + β).
TEST(RollingResistanceProperty, RollingStopsThenHoldsOrRollsBack) {
  std::mt19937_64 rng(1128);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  const long n = test::Repeats(500);
  int held = 0, back = 0;
  for (long i = 0; i < n; ++i) {
    RollingCase c = RandomBody(rng);
    const double s = U(rng) < 0.5 ? -1.0 : 1.0;
    // P in (-3r, r) rolling up (s = +1), (-r, 3r) rolling down: the rolling decelerates.
    double P = c.r() * (s > 0 ? -3.0 + 4.0 * U(rng) : -1.0 + 4.0 * U(rng));
    if (std::abs(std::abs(P) - c.r()) < 1e-6 * c.r()) P *= 0.9;  // not at the threshold
    c.F0 = c.m * (P + c.g * std::sin(c.theta));
    const double a = (P - s * c.r()) / (1 + c.beta());
    const double t1 = 0.05 + 0.95 * U(rng);
    c.v0 = -a * t1;
    const double T = t1 * (1.5 + U(rng));
    const Model model = c.BuildModel();
    const SimulationResult r = Simulate(model, c.InitialState(model), Options(T));
    SCOPED_TRACE(::testing::Message() << "case " << i);
    const ContactEvent* stop = First(r, ContactEventReason::kRollingStopped);
    ASSERT_NE(stop, nullptr);
    EXPECT_TRUE(Near(stop->t, t1, kEventRel));
    EXPECT_TRUE(Near(c.StopTime(), t1, 1e-12));
    EXPECT_EQ(CountOf(r, ContactEventReason::kRollingStopped), 1);
    EXPECT_EQ(CountOf(r, ContactEventReason::kRollingLimit), 0);
    const double v_end = r.final_state.bodies[0].v_WBcm_W.dot(c.x());
    if (std::abs(P) <= c.r()) {
      ++held;
      EXPECT_TRUE(stop->held_to);
      EXPECT_TRUE(r.final_state.contacts[0].rolling_held);
      EXPECT_LT(std::abs(v_end), 1e-12 * std::abs(c.v0));
    } else {
      ++back;
      EXPECT_FALSE(stop->held_to);
      const double a2 = (P - (P > 0 ? 1.0 : -1.0) * c.r()) / (1 + c.beta());
      EXPECT_TRUE(Near(v_end, a2 * (T - t1), kEventRel));
    }
  }
  // Both outcomes were drawn (P is uniform over 4r, half of it past the limit).
  EXPECT_GT(held, n / 5);
  EXPECT_GT(back, n / 5);
}

}  // namespace
}  // namespace chasles
