// Threads inside one run: the islands of a hybrid run on a pool (SimulationOptions::threads)
// and the free-body batch split into blocks (FreeBodyBatch::Advance's `threads`). Both must
// give bitwise the one-thread result; built with ThreadSanitizer too (scripts/test.sh --tsan),
// which checks that the threads share nothing they write.

#include <cstring>
#include <memory>
#include <random>

#include <fmt/format.h>

#include "chasles/integrate/free_body_batch.h"
#include "chasles/integrate/simulate.h"
#include "chasles/model/contact.h"
#include "chasles/model/forces.h"
#include "chasles/model/model.h"
// clang-format off
#include <gtest/gtest.h>
// clang-format on

namespace chasles {
namespace {

bool SameBits(const State& a, const State& b) {
  if (a.t != b.t || a.bodies.size() != b.bodies.size()) return false;
  for (size_t i = 0; i < a.bodies.size(); ++i) {
    const BodyState &x = a.bodies[i], &y = b.bodies[i];
    if (std::memcmp(x.p_WBcm.data(), y.p_WBcm.data(), sizeof(double) * 3) != 0 ||
        std::memcmp(x.v_WBcm_W.data(), y.v_WBcm_W.data(), sizeof(double) * 3) != 0 ||
        std::memcmp(x.w_WB_B.data(), y.w_WB_B.data(), sizeof(double) * 3) != 0 ||
        std::memcmp(x.q_WB.coeffs().data(), y.q_WB.coeffs().data(), sizeof(double) * 4) != 0) {
      return false;
    }
  }
  return true;
}

// Six balls set down spinning on a floor, each at its own spin (its own stick time
// t* = 2 R w0 / (7 mu_k g), Problem 8.26): six islands, six stick events.
TEST(ParallelIslands, TwoThreadsGiveTheOneThreadRunBitwise) {
  constexpr double kR = 0.03, kMass = 0.2, kMuK = 0.3, kG = 9.81;
  Model m;
  const double I = 0.4 * kMass * kR * kR;
  for (int i = 0; i < 6; ++i) {
    const int b = m.AddBody(fmt::format("ball{}", i),
                            MassProperties(kMass, Vec3::Zero(), RotationalInertia(I, I, I)));
    ContactSpec c;
    c.name = fmt::format("floor{}", i);
    c.shape = ContactShape::kSphere;
    c.body = b;
    c.radius = kR;
    c.mu_s = 0.5;
    c.mu_k = kMuK;
    m.AddContact(c);
  }
  m.AddForceElement(std::make_shared<UniformGravity>("gravity", Vec3(0, 0, -kG)));
  State s = MakeRestState(m);
  for (int i = 0; i < 6; ++i) {
    SetBodyPose(m, i, Vec3(0, i, kR), Quat::Identity(), s);
    SetBodyVelocity(m, i, Vec3::Zero(), Vec3(0, 10.0 * (1 + 0.2 * i), 0), s);
  }
  SimulationOptions o;
  o.t_end = 2 * 2 * kR * 20.0 / (7 * kMuK * kG);
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
    EXPECT_TRUE(SameBits(one.samples[k], two.samples[k]));
  EXPECT_TRUE(SameBits(one.final_state, two.final_state));
  ASSERT_EQ(one.contact_events.size(), two.contact_events.size());
  for (size_t k = 0; k < one.contact_events.size(); ++k) {
    EXPECT_EQ(std::memcmp(&one.contact_events[k].t, &two.contact_events[k].t, sizeof(double)), 0);
    EXPECT_EQ(one.contact_events[k].point, two.contact_events[k].point);
  }
}

// 300 seeded free bodies advanced in one block and in two.
TEST(ParallelIslands, FreeBodyBatchInTwoBlocksGivesOneBlockBitwise) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Model m;
  for (int b = 0; b < 300; ++b) {
    m.AddBody(fmt::format("b{}", b),
              MassProperties(1.0 + u(rng), Vec3::Zero(),
                             RotationalInertia(1.0 + u(rng), 1.0 + u(rng), 1.0 + u(rng))));
  }
  m.AddForceElement(std::make_shared<UniformGravity>("gravity", Vec3(0, 0, -9.81)));
  State s = MakeRestState(m);
  for (auto& b : s.bodies) {
    b.v_WBcm_W = Vec3(u(rng), u(rng), u(rng));
    b.w_WB_B = Vec3(u(rng) - 0.5, 10 * u(rng), u(rng) - 0.5);
  }
  for (FreeBodyStepper stepper : {FreeBodyStepper::kRk4, FreeBodyStepper::kSplitting}) {
    FreeBodyBatch one(m), two(m);
    one.Load(s);
    two.Load(s);
    one.Advance(stepper, 1e-3, 200, 1);
    two.Advance(stepper, 1e-3, 200, 2);
    State a = s, b = s;
    one.Store(a);
    two.Store(b);
    EXPECT_TRUE(SameBits(a, b));
  }
}

}  // namespace
}  // namespace chasles
