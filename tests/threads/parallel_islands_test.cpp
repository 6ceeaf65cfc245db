// Threads inside one run: the islands of a hybrid run on a pool (SimulationOptions::threads),
// the free-body batch split into blocks (FreeBodyBatch::Advance's `threads`, and Simulate's
// free-body path), and time stepping's islands (TimeSteppingOptions::threads). Each must give
// bitwise the one-thread result; built with ThreadSanitizer too (scripts/test.sh --tsan), which
// checks that the threads share nothing they write.

#include <cstring>
#include <memory>
#include <random>

#include <fmt/format.h>

#include "chasles/integrate/free_body_batch.h"
#include "chasles/integrate/simulate.h"
#include "chasles/integrate/time_stepping.h"
#include "chasles/model/forces.h"
#include "chasles/model/model.h"
#include "reference/balls_on_floor.h"
#include "threads/same_bits.h"
// clang-format off
#include <gtest/gtest.h>
// clang-format on

namespace chasles {
namespace {

constexpr double kG = 9.81;
constexpr reference::Ball kBall{0.2, 0.03, 0.5, 0.3};

// Six balls set down spinning on a floor, each at its own spin: six islands.
Model SpinningBalls(State& s) {
  Model m = reference::MakeBallsOnFloor(6, kBall, kG);
  s = MakeRestState(m);
  for (int i = 0; i < 6; ++i) {
    SetBodyPose(m, i, Vec3(0, i, kBall.radius), Quat::Identity(), s);
    SetBodyVelocity(m, i, Vec3::Zero(), Vec3(0, 10.0 * (1 + 0.2 * i), 0), s);
  }
  return m;
}

// Six balls set down spinning on a floor, each at its own spin (its own stick time
// t* = 2 R w0 / (7 mu_k g), Problem 8.26): six islands, six stick events.
TEST(ParallelIslands, TwoThreadsGiveTheOneThreadRunBitwise) {
  State s;
  const Model m = SpinningBalls(s);
  SimulationOptions o;
  o.t_end = 2 * reference::StickTime(kBall, kG, 20.0);
  o.output_interval = o.t_end / 8;
  o.adaptive.rtol = 1e-10;
  o.threads = 1;
  const SimulationResult one = Simulate(m, s, o);
  o.threads = 2;
  const SimulationResult two = Simulate(m, s, o);
  ASSERT_TRUE(one.islands.split);
  EXPECT_EQ(one.islands.count, 6);
  ASSERT_EQ(one.samples.size(), two.samples.size());
  for (size_t k = 0; k < one.samples.size(); ++k)
    EXPECT_TRUE(test::SameBits(one.samples[k], two.samples[k]));
  EXPECT_TRUE(test::SameBits(one.final_state, two.final_state));
  ASSERT_EQ(one.contact_events.size(), two.contact_events.size());
  for (size_t k = 0; k < one.contact_events.size(); ++k) {
    EXPECT_EQ(std::memcmp(&one.contact_events[k].t, &two.contact_events[k].t, sizeof(double)), 0);
    EXPECT_EQ(one.contact_events[k].point, two.contact_events[k].point);
  }
}

// 300 seeded free bodies under gravity, spinning generically.
Model SeededFreeBodies(State& s) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Model m;
  for (int b = 0; b < 300; ++b) {
    m.AddBody(fmt::format("b{}", b),
              MassProperties(1.0 + u(rng), Vec3::Zero(),
                             RotationalInertia(1.0 + u(rng), 1.0 + u(rng), 1.0 + u(rng))));
  }
  m.AddForceElement(std::make_shared<UniformGravity>("gravity", Vec3(0, 0, -9.81)));
  s = MakeRestState(m);
  for (auto& b : s.bodies) {
    b.v_WBcm_W = Vec3(u(rng), u(rng), u(rng));
    b.w_WB_B = Vec3(u(rng) - 0.5, 10 * u(rng), u(rng) - 0.5);
  }
  return m;
}

// The bodies advanced in one block and in two.
TEST(ParallelIslands, FreeBodyBatchInTwoBlocksGivesOneBlockBitwise) {
  State s;
  const Model m = SeededFreeBodies(s);
  for (FreeBodyStepper stepper : {FreeBodyStepper::kRk4, FreeBodyStepper::kSplitting}) {
    FreeBodyBatch one(m), two(m);
    one.Load(s);
    two.Load(s);
    one.Advance(stepper, 1e-3, 200, 1);
    two.Advance(stepper, 1e-3, 200, 2);
    State a = s, b = s;
    one.Store(a);
    two.Store(b);
    EXPECT_TRUE(test::SameBits(a, b));
  }
}

// Simulate's free-body path (each tile of bodies loaded, stepped and stored by its thread) on
// one thread and on two.
TEST(ParallelIslands, SimulateOfFreeBodiesOnTwoThreadsGivesOneThreadBitwise) {
  State s;
  const Model m = SeededFreeBodies(s);
  SimulationOptions o;
  o.integrator = IntegratorKind::kRk4;
  o.fixed_step = 1e-3;
  o.t_end = 0.2;
  o.output_interval = 0.05;
  o.threads = 1;
  const SimulationResult one = Simulate(m, s, o);
  o.threads = 2;
  const SimulationResult two = Simulate(m, s, o);
  EXPECT_EQ(one.run_path.path, RunPath::kFreeBodyBatch);
  ASSERT_EQ(one.samples.size(), two.samples.size());
  for (size_t k = 0; k < one.samples.size(); ++k)
    EXPECT_TRUE(test::SameBits(one.samples[k], two.samples[k]));
  EXPECT_TRUE(test::SameBits(one.final_state, two.final_state));
}

// Time stepping's islands on one thread and on two: six balls spinning on a floor, one island
// each at every step.
TEST(ParallelIslands, TimeSteppingOnTwoThreadsGivesOneThreadBitwise) {
  State s;
  const Model m = SpinningBalls(s);
  TimeSteppingOptions o;
  o.t_end = 0.05;
  o.step = 1e-3;
  o.output_interval = 0.01;
  o.threads = 1;
  const TimeSteppingResult one = SimulateTimeStepping(m, s, o);
  o.threads = 2;
  const TimeSteppingResult two = SimulateTimeStepping(m, s, o);
  EXPECT_TRUE(one.tolerance_met);
  EXPECT_EQ(one.summary.largest_island, 1);
  ASSERT_EQ(one.samples.size(), two.samples.size());
  for (size_t k = 0; k < one.samples.size(); ++k)
    EXPECT_TRUE(test::SameBits(one.samples[k], two.samples[k]));
  EXPECT_TRUE(test::SameBits(one.final_state, two.final_state));
}

}  // namespace
}  // namespace chasles
