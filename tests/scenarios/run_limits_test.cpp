// Runs that cannot go on stop at once and say why: a non-finite force is named with the time
// it appeared (every integrator), the step hook sees every accepted step, and an adaptive step
// below the smallest one is a LimitError.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "chasles/error.h"
#include "chasles/integrate/simulate.h"
#include "chasles/model/forces.h"
#include "chasles/model/model.h"

namespace chasles {
namespace {

// A 2 kg sphere of radius 0.1 m (I = 2/5 m r²), free, pushed by `force`.
Model PushedBody(VectorFunction force) {
  Model model;
  const double m = 2.0, I = 0.4 * m * 0.01;
  model.AddBody("block", MassProperties(m, Vec3::Zero(), RotationalInertia(I, I, I)));
  model.AddForceElement(
      std::make_shared<AppliedForce>("push", 0, Vec3::Zero(), force, VectorFrame::kWorld));
  return model;
}

// F = 1 N until t = 0.25 s, then NaN (a force with no value there, e.g. sqrt of a negative).
Vec3 NanAfterQuarterSecond(const Model&, const State& s) {
  return s.t < 0.25 ? Vec3(1.0, 0.0, 0.0) : Vec3(std::numeric_limits<double>::quiet_NaN(), 0, 0);
}

class NonFiniteForce : public ::testing::TestWithParam<IntegratorKind> {};

TEST_P(NonFiniteForce, StopsTheRunNamingTheForceAndTheTime) {
  const Model model = PushedBody(NanAfterQuarterSecond);
  SimulationOptions o;
  o.integrator = GetParam();
  o.t_end = 1.0;
  o.output_interval = 0.1;
  o.fixed_step = 0.01;
  o.adaptive.max_step = 0.05;
  try {
    Simulate(model, MakeRestState(model), o);
    FAIL() << "a NaN force must stop the run";
  } catch (const LimitError& e) {
    FAIL() << "a NaN is not a limit: " << e.what();
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_THAT(what, ::testing::HasSubstr("force element 'push' evaluated to NaN at t = "));
    // The first evaluation at or after 0.25 s (before it the force is finite): within one
    // step, at most 0.05 s (the adaptive max_step; the fixed steps are 0.01 s).
    const auto at = what.find("at t = ") + 7;
    const double t = std::stod(what.substr(at));
    EXPECT_GE(t, 0.25);
    EXPECT_LE(t, 0.25 + 0.05);
  }
}

INSTANTIATE_TEST_SUITE_P(Integrators, NonFiniteForce,
                         ::testing::Values(IntegratorKind::kDormandPrince5, IntegratorKind::kRk4,
                                           IntegratorKind::kEnergyMomentum));

// RK4 with h = 0.01 s over 1 s and output every 0.1 s: exactly span / h = 100 accepted steps,
// each reported once, at t = k h.
TEST(StepHook, SeesEveryFixedStep) {
  const Model model = PushedBody([](const Model&, const State&) { return Vec3(1.0, 0.0, 0.0); });
  SimulationOptions o;
  o.integrator = IntegratorKind::kRk4;
  o.t_end = 1.0;
  o.output_interval = 0.1;
  o.fixed_step = 0.01;
  int calls = 0;
  double last = 0.0;
  o.on_step = [&](double t) {
    ++calls;
    EXPECT_GT(t, last);
    EXPECT_NEAR(t, 0.01 * calls, 1e-12);
    last = t;
  };
  const SimulationResult r = Simulate(model, MakeRestState(model), o);
  EXPECT_EQ(calls, 100);
  EXPECT_EQ(r.stats.steps, 100);
}

// The adaptive hook is called once per accepted step (stats().steps), and throwing from it
// stops the run there.
TEST(StepHook, CountsAdaptiveStepsAndCanStopTheRun) {
  const Model model =
      PushedBody([](const Model&, const State& s) { return Vec3(std::sin(s.t), 0, 0); });
  SimulationOptions o;
  o.t_end = 2.0;
  std::int64_t calls = 0;
  o.on_step = [&](double) { ++calls; };
  const SimulationResult r = Simulate(model, MakeRestState(model), o);
  EXPECT_EQ(calls, r.stats.steps);
  o.on_step = [&](double t) {
    if (t > 1.0) throw LimitError(LimitError::Limit::kSteps, "enough");
  };
  EXPECT_THROW(Simulate(model, MakeRestState(model), o), LimitError);
}

// A force that jumps by 1000 N within 1e-12 s at t = 0.5 s: error control shrinks the step
// towards the width of the jump; with a smallest step of 1 ms the run stops there with a
// LimitError (kMinStep) before t = 0.5 s + 1 ms.
TEST(MinStep, AnAdaptiveStepBelowItIsALimitError) {
  const Model model = PushedBody([](const Model&, const State& s) {
    return Vec3(1000.0 * std::clamp((s.t - 0.5) * 1e12, 0.0, 1.0), 0.0, 0.0);
  });
  SimulationOptions o;
  o.t_end = 1.0;
  o.adaptive.rtol = 1e-12;
  o.adaptive.min_step = 1e-3;
  try {
    Simulate(model, MakeRestState(model), o);
    FAIL() << "the jump needs steps below 1 ms";
  } catch (const LimitError& e) {
    EXPECT_EQ(e.limit(), LimitError::Limit::kMinStep);
    EXPECT_THAT(e.what(), ::testing::HasSubstr("fell below the smallest step 0.001 s"));
  }
}

}  // namespace
}  // namespace chasles
