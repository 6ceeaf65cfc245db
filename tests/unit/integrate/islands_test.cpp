// Islands of the hybrid run: n spinning balls set down on a floor (Problems 8.26/8.27), each
// its own island with its own integrator and stick event; the partition by joints and
// sphere-sphere contacts; bitwise-equal results for 1 and 2 threads; a user event that stops
// the whole run; settling the contacts island by island against the whole problem.

#include "chasles/integrate/islands.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "chasles/dynamics/contact_solve.h"
#include "chasles/error.h"
#include "chasles/integrate/simulate.h"
#include "chasles/model/constraints.h"
#include "chasles/model/contact.h"
#include "chasles/model/forces.h"
#include "chasles/model/model.h"
#include "reference/balls_on_floor.h"
#include "test_support.h"

namespace chasles {
namespace {

using test::Near;
using testing::HasSubstr;

constexpr double kG = 9.81;
constexpr double kR = 0.03;
constexpr double kMass = 0.2;
constexpr double kMuK = 0.3;
constexpr double kW0 = 10.0;  // [rad/s]

constexpr reference::Ball kBall{kMass, kR, 0.5, kMuK};

// Problems 8.26/8.27 (tests/reference/balls_on_floor.h): sliding ends at t* = 2 R w0 /
// (7 mu_k g), then the ball rolls at 2/7 R w0.
double TStar(double w0) {
  return reference::StickTime(kBall, kG, w0);
}
double RollingSpeed(double w0) {
  return reference::RollingSpeed(kBall, w0);
}

Model MakeBalls(int n) {
  return reference::MakeBallsOnFloor(n, kBall, kG);
}

// Ball i at y = i m, resting on the floor, spinning at spins[i] about y.
State SetDown(const Model& m, const std::vector<double>& spins) {
  State s = MakeRestState(m);
  for (size_t i = 0; i < spins.size(); ++i) {
    const int b = static_cast<int>(i);
    SetBodyPose(m, b, Vec3(0, static_cast<double>(i), kR), Quat::Identity(), s);
    SetBodyVelocity(m, b, Vec3::Zero(), Vec3(0, spins[i], 0), s);
  }
  return s;
}

std::vector<double> Spins(int n) {
  std::vector<double> w(static_cast<size_t>(n));
  for (int i = 0; i < n; ++i) w[static_cast<size_t>(i)] = kW0 * (1.0 + 0.37 * i);
  return w;
}

SimulationOptions Options(double t_end) {
  SimulationOptions o;
  o.t_end = t_end;
  o.output_interval = t_end / 8.0;
  o.adaptive.rtol = 1e-12;
  o.adaptive.atol = 1e-14;
  return o;
}

// Each ball's slide-to-stick time against t*, and its final speed against 2/7 R w0.
void ExpectClosedForms(const SimulationResult& r, const std::vector<double>& spins) {
  std::vector<int> sticks(spins.size(), 0);
  for (const ContactEvent& e : r.contact_events) {
    if (e.from != ContactMode::kSliding || e.to != ContactMode::kSticking) continue;
    const double w0 = spins[static_cast<size_t>(e.point)];
    EXPECT_TRUE(Near(e.t, TStar(w0), 1e-9)) << "ball " << e.point;
    ++sticks[static_cast<size_t>(e.point)];
  }
  for (size_t i = 0; i < spins.size(); ++i) {
    EXPECT_EQ(sticks[i], 1) << "ball " << i;
    const Vec3& v = r.final_state.bodies[i].v_WBcm_W;
    EXPECT_TRUE(Near(v.x(), RollingSpeed(spins[i]), 1e-9)) << "ball " << i;
  }
}

TEST(Islands, SpinningBallsStickAtTheirOwnTimes) {
  const int n = 6;
  const std::vector<double> spins = Spins(n);
  const Model m = MakeBalls(n);
  const SimulationOptions o = Options(2.0 * TStar(spins.back()));
  const SimulationResult r = Simulate(m, SetDown(m, spins), o);
  EXPECT_TRUE(r.islands.split) << r.islands.reason;
  EXPECT_EQ(r.islands.count, n);
  ASSERT_EQ(r.islands.stats.size(), static_cast<size_t>(n));
  ExpectClosedForms(r, spins);
  // The merged records are in time order, with the n initial modes first.
  for (int p = 0; p < n; ++p) {
    EXPECT_EQ(r.contact_events[static_cast<size_t>(p)].reason, ContactEventReason::kInitial);
    EXPECT_EQ(r.contact_events[static_cast<size_t>(p)].point, p);
  }
  for (size_t k = static_cast<size_t>(n) + 1; k < r.contact_events.size(); ++k) {
    EXPECT_LE(r.contact_events[k - 1].t, r.contact_events[k].t);
  }
  // Every ball slides first, then rolls: samples on the common output grid, full States.
  ASSERT_EQ(r.samples.size(), 9u);  // the initial state, 7 output times, the final state
  for (size_t k = 0; k < r.samples.size(); ++k) {
    const State& s = r.samples[k];
    EXPECT_TRUE(
        Near(s.t, k == 9 ? o.t_end : static_cast<double>(k) * o.output_interval, 1e-15, o.t_end));
    ASSERT_EQ(s.bodies.size(), static_cast<size_t>(n));
    for (size_t i = 0; i < spins.size(); ++i) {
      // v(t) = mu_k g t while sliding, 2/7 R w0 after.
      const double v = std::min(kMuK * kG * s.t, RollingSpeed(spins[i]));
      EXPECT_TRUE(Near(s.bodies[i].v_WBcm_W.x(), v, 1e-9, RollingSpeed(spins[i])));
    }
  }
}

TEST(Islands, AgreeWithTheOneSystemRun) {
  const int n = 4;
  const std::vector<double> spins = Spins(n);
  const Model m = MakeBalls(n);
  SimulationOptions o = Options(2.0 * TStar(spins.back()));
  const SimulationResult split = Simulate(m, SetDown(m, spins), o);
  o.islands = false;
  const SimulationResult whole = Simulate(m, SetDown(m, spins), o);
  EXPECT_TRUE(split.islands.split);
  EXPECT_FALSE(whole.islands.split);
  EXPECT_EQ(whole.islands.count, n);
  EXPECT_EQ(whole.islands.reason, "islands turned off");
  ExpectClosedForms(whole, spins);
  ASSERT_EQ(split.contact_events.size(), whole.contact_events.size());
  for (size_t k = 0; k < split.contact_events.size(); ++k) {
    const ContactEvent &a = split.contact_events[k], &b = whole.contact_events[k];
    EXPECT_EQ(a.point, b.point);
    EXPECT_EQ(a.from, b.from);
    EXPECT_EQ(a.to, b.to);
    EXPECT_EQ(a.reason, b.reason);
    EXPECT_NEAR(a.t, b.t, 4 * o.event_time_tolerance);
  }
  // Motion piecewise polynomial of degree <= 2 (constant accelerations): both runs are exact
  // up to round-off and the event tolerance, so the samples agree to 1e-9 of the scales
  // (speed R w0, position 1 m).
  ASSERT_EQ(split.samples.size(), whole.samples.size());
  for (size_t k = 0; k < split.samples.size(); ++k) {
    EXPECT_EQ(split.samples[k].t, whole.samples[k].t);
    for (size_t i = 0; i < spins.size(); ++i) {
      const BodyState &a = split.samples[k].bodies[i], &b = whole.samples[k].bodies[i];
      EXPECT_TRUE(test::MatNear(a.p_WBcm, b.p_WBcm, 1e-9, 1.0));
      EXPECT_TRUE(test::MatNear(a.v_WBcm_W, b.v_WBcm_W, 1e-9, kR * spins[i]));
      EXPECT_TRUE(test::MatNear(a.w_WB_B, b.w_WB_B, 1e-9, spins[i]));
      EXPECT_EQ(split.samples[k].contacts[i].mode, whole.samples[k].contacts[i].mode);
    }
  }
  // Gravity's work is summed over the islands: zero for balls that stay on the floor.
  EXPECT_TRUE(Near(split.final_state.force_integrals[0].work, 0.0, 1e-12, 1.0));
  // Its linear impulse is -m g t per ball.
  EXPECT_TRUE(Near(split.final_state.force_integrals[0].linear_impulse_W.z(),
                   -n * kMass * kG * o.t_end, 1e-12));
}

void ExpectBitwiseEqual(const State& a, const State& b) {
  ASSERT_EQ(a.t, b.t);
  ASSERT_EQ(a.bodies.size(), b.bodies.size());
  for (size_t i = 0; i < a.bodies.size(); ++i) {
    EXPECT_TRUE(a.bodies[i].p_WBcm == b.bodies[i].p_WBcm);
    EXPECT_TRUE(a.bodies[i].q_WB.coeffs() == b.bodies[i].q_WB.coeffs());
    EXPECT_TRUE(a.bodies[i].v_WBcm_W == b.bodies[i].v_WBcm_W);
    EXPECT_TRUE(a.bodies[i].w_WB_B == b.bodies[i].w_WB_B);
  }
  ASSERT_EQ(a.contacts.size(), b.contacts.size());
  for (size_t p = 0; p < a.contacts.size(); ++p) {
    EXPECT_EQ(a.contacts[p].mode, b.contacts[p].mode);
    EXPECT_EQ(a.contacts[p].friction_work, b.contacts[p].friction_work);
  }
  ASSERT_EQ(a.force_integrals.size(), b.force_integrals.size());
  for (size_t f = 0; f < a.force_integrals.size(); ++f) {
    EXPECT_EQ(a.force_integrals[f].work, b.force_integrals[f].work);
    EXPECT_TRUE(a.force_integrals[f].linear_impulse_W == b.force_integrals[f].linear_impulse_W);
  }
}

TEST(Islands, OneAndTwoThreadsAreBitwiseEqual) {
  const int n = 7;
  const std::vector<double> spins = Spins(n);
  const Model m = MakeBalls(n);
  SimulationOptions o = Options(2.0 * TStar(spins.back()));
  int steps_seen = 0;
  o.on_step = [&](double) { ++steps_seen; };  // called one at a time, from either thread
  const SimulationResult one = Simulate(m, SetDown(m, spins), o);
  const int steps_one = steps_seen;
  steps_seen = 0;
  o.threads = 2;
  const SimulationResult two = Simulate(m, SetDown(m, spins), o);
  EXPECT_EQ(steps_seen, steps_one);
  EXPECT_EQ(steps_one, one.stats.steps);
  ASSERT_EQ(one.samples.size(), two.samples.size());
  for (size_t k = 0; k < one.samples.size(); ++k)
    ExpectBitwiseEqual(one.samples[k], two.samples[k]);
  ExpectBitwiseEqual(one.final_state, two.final_state);
  ASSERT_EQ(one.contact_events.size(), two.contact_events.size());
  for (size_t k = 0; k < one.contact_events.size(); ++k) {
    EXPECT_EQ(one.contact_events[k].t, two.contact_events[k].t);
    EXPECT_EQ(one.contact_events[k].point, two.contact_events[k].point);
  }
  EXPECT_EQ(one.stats.function_evaluations, two.stats.function_evaluations);
}

TEST(Islands, AnEventInOneIslandLeavesAnotherAlone) {
  // Ball 0 alone, then beside a ball whose stick event falls inside ball 0's sliding, then
  // beside one that sticks later: ball 0's island takes the same steps every time.
  const Model one = MakeBalls(1);
  const Model two = MakeBalls(2);
  const SimulationOptions o = Options(3.0 * TStar(kW0));
  const SimulationResult alone = Simulate(one, SetDown(one, {kW0}), o);
  const SimulationResult early = Simulate(two, SetDown(two, {kW0, 0.5 * kW0}), o);
  const SimulationResult late = Simulate(two, SetDown(two, {kW0, 1.5 * kW0}), o);
  EXPECT_EQ(alone.islands.reason, "the bodies form one island");
  ASSERT_TRUE(early.islands.split);
  ASSERT_TRUE(late.islands.split);
  EXPECT_EQ(early.islands.stats[0].steps, alone.stats.steps);
  EXPECT_EQ(late.islands.stats[0].steps, alone.stats.steps);
  EXPECT_EQ(early.islands.stats[0].function_evaluations, alone.stats.function_evaluations);
  EXPECT_EQ(late.islands.stats[0].function_evaluations, alone.stats.function_evaluations);
  EXPECT_EQ(early.stats.steps, early.islands.stats[0].steps + early.islands.stats[1].steps);
}

/// A sphere-sphere contact "pair" between balls a and b.
void AddSpherePair(Model& m, BodyIndex a, BodyIndex b) {
  ContactSpec c;
  c.name = "pair";
  c.shape = ContactShape::kSphereSphere;
  c.body = a;
  c.radius = kR;
  c.other_body = b;
  c.other_radius = kR;
  m.AddContact(c);
}

TEST(Islands, PartitionFollowsJointsContactsAndSprings) {
  Model m = MakeBalls(6);
  // 0-1 touch as spheres, 2-3 are hinged, 4-5 tied by a spring; the floor links nothing.
  AddSpherePair(m, 0, 1);
  m.AddConstraint(std::make_shared<Joint>("hinge", JointKind::kRevolute, 2,
                                          AttachmentFrame{Vec3::Zero()}, 3,
                                          AttachmentFrame{Vec3(0, 0, 0.1)}));
  m.AddForceElement(
      std::make_shared<SpringDamper>("spring", 4, Vec3::Zero(), 5, Vec3::Zero(), 1.0, 10.0, 0.0));
  const IslandPartition p = FindIslands(m);
  ASSERT_EQ(p.bodies.size(), 3u);
  EXPECT_EQ(p.bodies[0], (std::vector<BodyIndex>{0, 1}));
  EXPECT_EQ(p.bodies[1], (std::vector<BodyIndex>{2, 3}));
  EXPECT_EQ(p.bodies[2], (std::vector<BodyIndex>{4, 5}));
  EXPECT_EQ(p.island_of_body, (std::vector<int>{0, 0, 1, 1, 2, 2}));
  EXPECT_EQ(IslandObstacle(m), "");
  // A force given by a user function may read any body: the model runs as one system.
  m.AddForceElement(std::make_shared<AppliedForce>(
      "push", 0, Vec3::Zero(), [](const Model&, const State&) { return Vec3::Zero(); },
      VectorFrame::kWorld));
  EXPECT_THAT(IslandObstacle(m), HasSubstr("'push'"));
}

TEST(Islands, ASpherePairRunsAsOneIsland) {
  // Balls 0 and 1 side by side, touching (sphere-sphere contact), both sliding the same way;
  // ball 2 apart: two islands, the pair one of them.
  Model m = MakeBalls(3);
  AddSpherePair(m, 0, 1);
  State s = SetDown(m, {kW0, kW0, 2 * kW0});
  SetBodyPose(m, 1, Vec3(0, 2 * kR, kR), Quat::Identity(), s);
  const SimulationResult r = Simulate(m, s, Options(TStar(kW0) / 2));
  ASSERT_TRUE(r.islands.split);
  EXPECT_EQ(r.islands.bodies, (std::vector<std::vector<BodyIndex>>{{0, 1}, {2}}));
  // Equal spins, no force between them: each slides as alone, v = mu_k g t.
  for (int b = 0; b < 3; ++b) {
    EXPECT_TRUE(Near(r.final_state.bodies[static_cast<size_t>(b)].v_WBcm_W.x(),
                     kMuK * kG * r.final_state.t, 1e-9));
  }
}

TEST(Islands, AUserStopEventStopsTheWholeRun) {
  const int n = 3;
  const std::vector<double> spins = Spins(n);
  const Model m = MakeBalls(n);
  SimulationOptions o = Options(2.0 * TStar(spins.back()));
  const double t_stop = 0.5 * TStar(spins[0]);  // every ball still sliding
  o.events.push_back({"stop", [t_stop](const Model&, const State& s) { return s.t - t_stop; },
                      EventDirection::kRising, EventAction::kStop});
  const SimulationResult r = Simulate(m, SetDown(m, spins), o);
  EXPECT_FALSE(r.islands.split);
  EXPECT_EQ(r.islands.reason, "user events are functions of the whole state");
  ASSERT_TRUE(r.stopped_by_event);
  EXPECT_NEAR(r.final_state.t, t_stop, o.event_time_tolerance);
  for (size_t i = 0; i < spins.size(); ++i) {
    // Sliding: v = mu_k g t, w = w0 - 5 mu_k g t / (2 R).
    EXPECT_TRUE(Near(r.final_state.bodies[i].v_WBcm_W.x(), kMuK * kG * t_stop, 1e-9));
    EXPECT_TRUE(
        Near(r.final_state.bodies[i].w_WB_B.y(), spins[i] - 2.5 * kMuK * kG * t_stop / kR, 1e-9));
  }
}

TEST(Islands, OnTransitionRunsAsOneSystem) {
  const Model m = MakeBalls(2);
  SimulationOptions o = Options(TStar(kW0));
  int transitions = 0;
  o.on_transition = [&](const State& before, const State& after) {
    EXPECT_EQ(before.bodies.size(), 2u);
    EXPECT_EQ(after.bodies.size(), 2u);
    ++transitions;
  };
  const SimulationResult r = Simulate(m, SetDown(m, {2 * kW0, 0.5 * kW0}), o);
  EXPECT_FALSE(r.islands.split);
  EXPECT_THAT(r.islands.reason, HasSubstr("on_transition"));
  EXPECT_EQ(transitions, 1);  // ball 1 sticks at t*(w0/2) < t_end; ball 0 does not
  o.on_transition = nullptr;
  o.threads = 0;
  EXPECT_THROW(Simulate(m, SetDown(m, {kW0, kW0}), o), InputError);
}

// The island form of on_transition: one call per island with its view (its Model, its initial
// state and the global index of each of its bodies, forces and points), and each island's
// transitions checked on its own states; on_transition is not called.
TEST(Islands, IslandTransitionChecksEachIslandOnItsOwnStates) {
  const Model m = MakeBalls(2);
  SimulationOptions o = Options(TStar(kW0));
  o.threads = 2;
  o.on_transition = [](const State&, const State&) { ADD_FAILURE() << "whole-model check"; };
  std::mutex mutex;
  std::vector<std::vector<BodyIndex>> bodies(2);
  std::vector<std::vector<int>> points(2);
  std::vector<int> transitions(2, 0);
  o.island_transition = [&](const IslandView& v) -> TransitionCheck {
    const std::lock_guard<std::mutex> lock(mutex);
    const auto i = static_cast<size_t>(v.island);
    bodies[i] = v.bodies;
    points[i] = v.points;
    EXPECT_EQ(v.model->num_bodies(), 1);
    EXPECT_EQ(v.initial->bodies.size(), 1u);
    EXPECT_EQ(v.forces, std::vector<int>{0});  // gravity, in every island
    return [&transitions, i](const State& before, const State& after) {
      EXPECT_EQ(before.bodies.size(), 1u);
      EXPECT_EQ(after.bodies.size(), 1u);
      ++transitions[i];
    };
  };
  const SimulationResult r = Simulate(m, SetDown(m, {2 * kW0, 0.5 * kW0}), o);
  EXPECT_TRUE(r.islands.split) << r.islands.reason;
  EXPECT_EQ(bodies, (std::vector<std::vector<BodyIndex>>{{0}, {1}}));
  EXPECT_EQ(points, (std::vector<std::vector<int>>{{0}, {1}}));
  // Ball 1 sticks at t*(w0/2) < t_end; ball 0 does not.
  EXPECT_EQ(transitions, (std::vector<int>{0, 1}));
}

// SettleContactsByIsland against the one problem over the whole Model: balls and a pair and a
// dumbbell of balls, each its own island, some driven into the floor (impacts), some sliding,
// one at rest (sticking). The problems are block-diagonal over the islands and every slip here
// stays in the x-z plane (straight impulse paths, integrated exactly), so the two answers agree
// to round-off: velocities, impulses and energies to 1e-12, modes and the changes exactly.
TEST(Islands, SettlingIslandByIslandAgreesWithTheWholeProblem) {
  reference::Ball bouncy = kBall;
  bouncy.restitution = 0.5;
  Model m =
      reference::MakeBallsOnFloor({bouncy, kBall, kBall, kBall, kBall, kBall, kBall, kBall}, kG);
  AddSpherePair(m, 4, 5);
  m.AddConstraint(std::make_shared<Joint>("link", JointKind::kSpherical, 6,
                                          AttachmentFrame{Vec3(0, 0.05, 0)}, 7,
                                          AttachmentFrame{Vec3(0, -0.05, 0)}));
  State s = SetDown(m, std::vector<double>(8, 0.0));
  SetBodyPose(m, 5, Vec3(2 * kR, 4, kR), Quat::Identity(), s);
  SetBodyPose(m, 6, Vec3(0, 6, kR), Quat::Identity(), s);
  SetBodyPose(m, 7, Vec3(0, 6.1, kR), Quat::Identity(), s);
  const double v_drop = 1.0;                                         // [m/s]
  SetBodyVelocity(m, 0, Vec3(0, 0, -v_drop), Vec3(0, kW0, 0), s);    // bounces, spinning
  SetBodyVelocity(m, 1, Vec3(0.3, 0, -v_drop), Vec3(0, kW0, 0), s);  // lands slipping
  SetBodyVelocity(m, 2, Vec3(1.0, 0, 0), Vec3::Zero(), s);           // slides
  SetBodyVelocity(m, 4, Vec3(0.5, 0, 0), Vec3::Zero(), s);           // strikes ball 5
  SetBodyVelocity(m, 6, Vec3(0.5, 0, -0.2), Vec3::Zero(), s);        // the dumbbell lands
  SetBodyVelocity(m, 7, Vec3(0.5, 0, -0.2), Vec3::Zero(), s);
  State whole = s;
  const ImpactResult impacts = ResolveImpacts(m, whole);
  ModeSelectionNotes notes;
  const std::vector<ContactModeChange> changes = SelectContactModes(m, whole, {}, {}, &notes);
  State split = s;
  const ContactSettling settled = SettleContactsByIsland(m, split);
  EXPECT_EQ(settled.islands, 6);
  EXPECT_TRUE(notes.jams.empty());
  EXPECT_TRUE(settled.jams.empty());
  // Ball 0 (sphere: the normal impulse turns nothing) leaves at e v_drop; ball 2 slides, ball 3
  // sticks at rest.
  EXPECT_TRUE(Near(split.bodies[0].v_WBcm_W.z(), bouncy.restitution * v_drop, 1e-12));
  EXPECT_EQ(split.contacts[0].mode, ContactMode::kSeparated);
  EXPECT_EQ(split.contacts[2].mode, ContactMode::kSliding);
  EXPECT_EQ(split.contacts[3].mode, ContactMode::kSticking);
  // The motion: speeds on the scale of v_drop, spins on kW0.
  for (size_t b = 0; b < s.bodies.size(); ++b) {
    EXPECT_TRUE(test::MatNear(split.bodies[b].v_WBcm_W, whole.bodies[b].v_WBcm_W, 1e-12, v_drop))
        << "body " << b;
    EXPECT_TRUE(test::MatNear(split.bodies[b].w_WB_B, whole.bodies[b].w_WB_B, 1e-12, kW0))
        << "body " << b;
  }
  // Each point's mode and slip direction, and the work booked: per island here, shared over
  // the whole Model there, so their totals agree.
  double work_whole = 0.0, work_split = 0.0;
  for (size_t p = 0; p < s.contacts.size(); ++p) {
    EXPECT_EQ(split.contacts[p].mode, whole.contacts[p].mode) << "point " << p;
    EXPECT_EQ(split.contacts[p].rolling_held, whole.contacts[p].rolling_held) << "point " << p;
    EXPECT_TRUE(test::MatNear(split.contacts[p].slip_direction_W,
                              whole.contacts[p].slip_direction_W, 1e-12, 1.0));
    work_whole += whole.contacts[p].impact_work + whole.contacts[p].friction_work;
    work_split += split.contacts[p].impact_work + split.contacts[p].friction_work;
  }
  const double energy_scale = kMass * v_drop * v_drop;
  EXPECT_TRUE(Near(work_split, work_whole, 1e-12, energy_scale));
  // The same changes, in the same order.
  ASSERT_EQ(settled.changes.size(), changes.size());
  for (size_t k = 0; k < changes.size(); ++k) {
    EXPECT_EQ(settled.changes[k].point, changes[k].point);
    EXPECT_EQ(settled.changes[k].from, changes[k].from);
    EXPECT_EQ(settled.changes[k].to, changes[k].to);
    EXPECT_EQ(settled.changes[k].held_from, changes[k].held_from);
    EXPECT_EQ(settled.changes[k].held_to, changes[k].held_to);
  }
  // The same impulses at the same points: balls 0 and 1, the pair (its floor points and its
  // sphere-sphere point) and the dumbbell's two points.
  std::vector<ContactImpulse> by_island;
  double energy_change = 0.0;
  for (const ImpactResult& r : settled.impacts) {
    EXPECT_FALSE(r.frictionless_fallback);
    by_island.insert(by_island.end(), r.impulses.begin(), r.impulses.end());
    energy_change += r.kinetic_energy_after - r.kinetic_energy_before;
  }
  EXPECT_TRUE(Near(energy_change, impacts.kinetic_energy_after - impacts.kinetic_energy_before,
                   1e-12, energy_scale));
  std::stable_sort(
      by_island.begin(), by_island.end(),
      [](const ContactImpulse& a, const ContactImpulse& b) { return a.point < b.point; });
  ASSERT_EQ(by_island.size(), impacts.impulses.size());
  EXPECT_GE(by_island.size(), 5u);
  const double impulse_scale = kMass * v_drop;
  for (size_t k = 0; k < by_island.size(); ++k) {
    const ContactImpulse &a = by_island[k], &b = impacts.impulses[k];
    EXPECT_EQ(a.point, b.point);
    EXPECT_TRUE(Near(a.normal_impulse, b.normal_impulse, 1e-12, impulse_scale)) << a.point;
    EXPECT_TRUE(test::MatNear(a.impulse_W, b.impulse_W, 1e-12, impulse_scale)) << a.point;
    EXPECT_TRUE(Near(a.approach_speed, b.approach_speed, 1e-12, v_drop)) << a.point;
    EXPECT_EQ(a.sticking, b.sticking) << a.point;
  }
}

}  // namespace
}  // namespace chasles
