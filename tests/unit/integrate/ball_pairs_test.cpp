// Every pair of balls under time stepping (TimeSteppingOptions::collide_all_pairs): the
// broadphase (ball_pairs.h) against the brute-force test of all pairs, and the pairs it finds in
// the scheme against closed forms derived here and against the same model with every pair
// listed.
#include "chasles/integrate/ball_pairs.h"

#include <gtest/gtest.h>

#include <fmt/format.h>

#include <cmath>
#include <random>

#include "chasles/error.h"
#include "chasles/integrate/time_stepping.h"
#include "reference/balls_on_floor.h"
#include "test_support.h"

namespace chasles {
namespace {

constexpr double kG = 9.81;
constexpr double kRoundOff = 1e-12;

// Seeded random spheres in a 0.4 m box (radii 5 to 30 mm, every tenth radius 0: not a ball) and
// a few far outside it: the grid's pairs are exactly the brute-force test's, in its order.
TEST(BallPairs, BroadphaseFindsExactlyTheBruteForcePairs) {
  for (unsigned seed = 1; seed <= 5; ++seed) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> x(0.0, 0.4), r(0.005, 0.03);
    const int n = 200;
    std::vector<Vec3> c(n);
    std::vector<double> radius(n);
    for (int i = 0; i < n; ++i) {
      c[static_cast<size_t>(i)] = Vec3(x(rng), x(rng), x(rng));
      radius[static_cast<size_t>(i)] = i % 10 == 9 ? 0.0 : r(rng);
    }
    c[0] = Vec3(1e6, -3e5, 2.0);  // far away, and a neighbour overlapping it there
    c[1] = c[0] + Vec3(0.9 * (radius[0] + radius[1]), 0, 0);
    c[2] = Vec3(-1e17, 1e17, 0.5);
    for (const double reach : {0.0, 1e-9, 0.01}) {
      std::vector<std::pair<int, int>> brute;
      for (int i = 0; i < n; ++i) {
        for (int j = i + 1; j < n; ++j) {
          const auto a = static_cast<size_t>(i), b = static_cast<size_t>(j);
          if (radius[a] <= 0.0 || radius[b] <= 0.0) continue;
          const double d = radius[a] + radius[b] + reach;
          if ((c[a] - c[b]).squaredNorm() <= d * d) brute.push_back({i, j});
        }
      }
      const std::vector<std::pair<int, int>> grid = FindSpherePairs(c, radius, reach);
      EXPECT_EQ(grid, brute) << "seed " << seed << ", reach " << reach;
      EXPECT_GT(brute.size(), 30u) << "seed " << seed;  // the test sees pairs at all
      if (reach == 0.0) {
        EXPECT_EQ(grid.front(), std::make_pair(0, 1));
      }
    }
  }
  EXPECT_TRUE(FindSpherePairs({Vec3::Zero(), Vec3::Zero()}, {0.0, 0.0}, 1.0).empty());
}

// Balls: the bodies with a sphere contact centred at their centre of mass.
TEST(BallPairs, BallsAreTheBodiesWithACentredSphere) {
  const reference::Ball ball{0.17, 0.028575, 0.2, 0.2};
  Model model = reference::MakeBallsOnFloor(2, ball, kG);
  const int box =
      model.AddBody("box", MassProperties(1.0, Vec3::Zero(), RotationalInertia(1, 1, 1)));
  ContactSpec off;  // a sphere off the centre of mass: not a ball
  off.name = "knob";
  off.shape = ContactShape::kSphere;
  off.body = box;
  off.radius = 0.01;
  off.p_BoC_B = Vec3(0.1, 0, 0);
  model.AddContact(off);
  EXPECT_EQ(BallRadii(model), (std::vector<double>{ball.radius, ball.radius, 0.0}));
  ContactSpec other = off;
  other.name = "bigger";
  other.body = 0;
  other.p_BoC_B = Vec3::Zero();
  other.radius = 2 * ball.radius;
  model.AddContact(other);
  EXPECT_THROW(BallRadii(model), InputError);
}

// Equal free balls (no gravity, no friction), radius R, mass m.
Model FreeBalls(int n, double R, double m) {
  Model model;
  const double I = 0.4 * m * R * R;
  for (int i = 0; i < n; ++i) {
    model.AddBody(fmt::format("ball{}", i),
                  MassProperties(m, Vec3::Zero(), RotationalInertia(I, I, I)));
  }
  return model;
}

TimeSteppingOptions Pairs(double t_end, double h, int n, double R, double e) {
  TimeSteppingOptions o;
  o.t_end = t_end;
  o.step = h;
  o.collide_all_pairs = true;
  o.pair_law.restitution = e;
  o.ball_radii.assign(static_cast<size_t>(n), R);
  return o;
}

// Head-on: A at v into B at rest, e. Newton's law and the momentum balance in the step of the
// impact: v_A' = v (1 - e)/2, v_B' = v (1 + e)/2; then both fly apart (no other pair).
TEST(BallPairs, HeadOnPairTakesNewtonsLaw) {
  const double R = 0.03, m = 0.2, v = 1.5;
  const Model model = FreeBalls(2, R, m);
  for (const double e : {0.0, 0.5, 0.93, 1.0}) {
    State s = MakeRestState(model);
    SetBodyPose(model, 0, Vec3::Zero(), Quat::Identity(), s);
    SetBodyPose(model, 1, Vec3(2 * R + 0.1, 0, 0), Quat::Identity(), s);
    SetBodyVelocity(model, 0, Vec3(v, 0, 0), Vec3::Zero(), s);
    TimeSteppingOptions o = Pairs(0.2, 1e-3, 2, R, e);
    o.store_steps = true;
    const TimeSteppingResult r = SimulateTimeStepping(model, s, o);
    const Vec3 vA = r.final_state.bodies[0].v_WBcm_W, vB = r.final_state.bodies[1].v_WBcm_W;
    EXPECT_NEAR(vA.x(), v * (1 - e) / 2, kRoundOff * v) << "e = " << e;
    EXPECT_NEAR(vB.x(), v * (1 + e) / 2, kRoundOff * v) << "e = " << e;
    EXPECT_EQ(vA.tail<2>().norm() + vB.tail<2>().norm(), 0.0);
    EXPECT_LE((m * (vA + vB) - m * Vec3(v, 0, 0)).norm(), kRoundOff * m * v);
    EXPECT_LE(r.summary.max_momentum_residual, kRoundOff * m * v);
    // The collision is seen: one step with an active point, the impulse's work the energy lost.
    int touching = 0;
    for (const TimeSteppingStep& c : r.steps) touching += c.active_points > 0;
    EXPECT_GE(touching, 1);
    const double lost = 0.5 * m * v * v - 0.5 * m * (vA.squaredNorm() + vB.squaredNorm());
    EXPECT_NEAR(r.final_state.unlisted_contact_work.impact_work, -lost, kRoundOff * m * v * v);
    EXPECT_NEAR(r.summary.work_normal, -lost, kRoundOff * m * v * v);
    EXPECT_TRUE(r.tolerance_met);
  }
}

// Oblique and frictionless: B touching A at 40° off A's path, A at v. One step of h (no error
// estimate): the impulse is along the normal at the step's midpoint, n = (p_A + h/2 v - p_B)
// normalised, so each ball's velocity across n is unchanged and the normal relative velocity
// turns to -e times itself; the spins stay zero.
TEST(BallPairs, ObliqueFrictionlessPairKeepsTheTangentialVelocities) {
  const double R = 0.03, m = 0.2, v = 1.5, h = 1e-3, th = 40 * M_PI / 180;
  const Model model = FreeBalls(2, R, m);
  for (const double e : {0.0, 0.7}) {
    State s = MakeRestState(model);
    const Vec3 vA0(v, 0, 0);
    SetBodyPose(model, 0, Vec3::Zero(), Quat::Identity(), s);
    SetBodyPose(model, 1, 2 * R * Vec3(std::cos(th), std::sin(th), 0), Quat::Identity(), s);
    SetBodyVelocity(model, 0, vA0, Vec3::Zero(), s);
    TimeSteppingOptions o = Pairs(h, h, 2, R, e);
    o.error_estimate = false;
    const TimeSteppingResult r = SimulateTimeStepping(model, s, o);
    const Vec3 n = (s.bodies[0].p_WBcm + 0.5 * h * vA0 - s.bodies[1].p_WBcm).normalized();
    const Vec3 vA = r.final_state.bodies[0].v_WBcm_W, vB = r.final_state.bodies[1].v_WBcm_W;
    const auto across = [&](const Vec3& u) { return Vec3(u - n * n.dot(u)); };
    EXPECT_LE((across(vA) - across(vA0)).norm(), kRoundOff * v) << "e = " << e;
    EXPECT_LE(across(vB).norm(), kRoundOff * v) << "e = " << e;
    EXPECT_NEAR(n.dot(vA - vB), -e * n.dot(vA0), kRoundOff * v) << "e = " << e;
    EXPECT_LE((vA + vB - vA0).norm(), kRoundOff * v);
    EXPECT_EQ(r.final_state.bodies[0].w_WB_B.norm() + r.final_state.bodies[1].w_WB_B.norm(), 0.0);
  }
}

// Newton's cradle of 3 to 5 touching balls, the first arriving at v, under Moreau's law (all
// touching pairs at once; the same as the listed pairs' test in time_stepping_test.cpp): every
// touching pair presses, so v_2 - v_1 = e v and v_2 = ... = v_n, with the momentum
// m v = m (v_1 + (n - 1) v_2): v_1 = (1 - (n - 1) e) v / n, the others (1 + e) v / n, every
// impulse positive (P_k,k+1 = m v (1 + e)(n - k)/n). e = 1 keeps the energy, but the motion is
// not the sequential one a cradle shows (v_1 = ... = 0, v_n = v).
TEST(BallPairs, NewtonsCradleUnderMoreausSimultaneousLaw) {
  const double R = 0.02, m = 0.1, v = 1.0;
  for (int n = 3; n <= 5; ++n) {
    for (const double e : {0.0, 0.5, 1.0}) {
      const Model model = FreeBalls(n, R, m);
      State s = MakeRestState(model);
      for (int i = 0; i < n; ++i) {
        SetBodyPose(model, i, Vec3(2 * R * i, 0, 0), Quat::Identity(), s);
        SetBodyVelocity(model, i, Vec3(i == 0 ? v : 0.0, 0, 0), Vec3::Zero(), s);
      }
      const TimeSteppingResult r = SimulateTimeStepping(model, s, Pairs(0.01, 1e-3, n, R, e));
      const auto vx = [&](int i) {
        return r.final_state.bodies[static_cast<size_t>(i)].v_WBcm_W.x();
      };
      EXPECT_NEAR(vx(0), (1 - (n - 1) * e) * v / n, kRoundOff * v) << n << " balls, e = " << e;
      for (int i = 1; i < n; ++i) {
        EXPECT_NEAR(vx(i), (1 + e) * v / n, kRoundOff * v) << n << " balls, e = " << e;
      }
    }
  }
}

// A pyramid of four balls on the floor (three touching in a triangle, one nested on them), with
// friction between the balls and with the floor: at rest it stays at rest (the exact cone
// holds it; no creep), its six touching pairs found by the broadphase.
TEST(BallPairs, PyramidAtRestStaysAtRest) {
  const reference::Ball ball{0.17, 0.028575, 0.5, 0.5};
  const Model model = reference::MakeBallsOnFloor(4, ball, kG);
  State s = MakeRestState(model);
  const double R = ball.radius, d = 2 * R / std::sqrt(3.0);  // circumradius of the triangle
  for (int i = 0; i < 3; ++i) {
    const double a = 2 * M_PI * i / 3;
    SetBodyPose(model, i, Vec3(d * std::cos(a), d * std::sin(a), R), Quat::Identity(), s);
  }
  SetBodyPose(model, 3, Vec3(0, 0, R + std::sqrt(4 * R * R - d * d)), Quat::Identity(), s);
  for (int i = 0; i < 4; ++i) SetBodyVelocity(model, i, Vec3::Zero(), Vec3::Zero(), s);
  TimeSteppingOptions o;
  o.t_end = 1.0;
  o.step = 1e-3;
  o.collide_all_pairs = true;
  o.pair_law = {0.0, 0.5, 0.5, RestitutionLaw::kNewton};
  o.store_steps = true;
  const TimeSteppingResult r = SimulateTimeStepping(model, s, o);
  double moved = 0.0;
  for (size_t k = 0; k < 4; ++k) {
    moved = std::max(moved, (r.final_state.bodies[k].p_WBcm - s.bodies[k].p_WBcm).norm());
  }
  EXPECT_LT(moved, 1e-12);
  // 3 floor points and the 6 pairs (the three at the base touch too), one island.
  EXPECT_EQ(r.steps.back().active_points, 9);
  EXPECT_EQ(r.steps.back().islands, 1);
  EXPECT_TRUE(r.tolerance_met);
}

// A rack broken by a cue ball (frictionless between the balls, e = 0.93, on cloth): with
// collide_all_pairs the pairs come from the broadphase, each built as a listed sphere-sphere
// contact is and taking its place among the active points in the same order, so the run is
// bit for bit that of the model with every pair listed (and on two threads); a listed pair keeps
// its own contact.
TEST(BallPairs, PairsRunAsTheListedPairsDo) {
  const reference::Ball ball{0.17, 0.028575, 0.2, 0.2};
  const int n = 10;
  const double R = ball.radius, e = 0.93;
  Model bare = reference::MakeBallsOnFloor(n, ball, kG);
  Model listed = bare;
  reference::AddSpherePairs(listed, n, R, e);
  State s = MakeRestState(bare);
  reference::SetRack(bare, n, R, 7, s);
  TimeSteppingOptions o;
  o.t_end = 0.3;
  o.step = 1e-3;
  TimeSteppingOptions p = o;
  p.collide_all_pairs = true;
  p.pair_law = {e, 0.0, 0.0, RestitutionLaw::kNewton};
  State s_listed = s;
  s_listed.contacts.clear();
  const TimeSteppingResult a = SimulateTimeStepping(listed, s_listed, o);
  const TimeSteppingResult b = SimulateTimeStepping(bare, s, p);
  for (size_t i = 0; i < static_cast<size_t>(n); ++i) {
    EXPECT_EQ(a.final_state.bodies[i].p_WBcm, b.final_state.bodies[i].p_WBcm) << i;
    EXPECT_EQ(a.final_state.bodies[i].v_WBcm_W, b.final_state.bodies[i].v_WBcm_W) << i;
    EXPECT_EQ(a.final_state.bodies[i].w_WB_B, b.final_state.bodies[i].w_WB_B) << i;
  }
  EXPECT_EQ(a.summary.regime_changes, b.summary.regime_changes);
  EXPECT_EQ(a.summary.max_penetration, b.summary.max_penetration);
  EXPECT_EQ(a.summary.max_gap_drift, b.summary.max_gap_drift);
  EXPECT_EQ(a.summary.accumulated_velocity_error, b.summary.accumulated_velocity_error);
  EXPECT_EQ(a.summary.work_normal, b.summary.work_normal);
  EXPECT_GT(a.summary.regime_changes, 10);  // the break happened
  double listed_work = 0.0;
  for (size_t q = static_cast<size_t>(n); q < a.final_state.contacts.size(); ++q) {
    listed_work += a.final_state.contacts[q].impact_work;
  }
  EXPECT_NEAR(b.final_state.unlisted_contact_work.impact_work, listed_work,
              kRoundOff * std::abs(listed_work));

  // On two threads over the islands: the same bits (the pair points' warm starts and regimes
  // are per point, written by their island alone).
  TimeSteppingOptions threads = p;
  threads.threads = 2;
  const TimeSteppingResult t2 = SimulateTimeStepping(bare, s, threads);
  for (size_t i = 0; i < static_cast<size_t>(n); ++i) {
    EXPECT_EQ(b.final_state.bodies[i].p_WBcm, t2.final_state.bodies[i].p_WBcm) << i;
    EXPECT_EQ(b.final_state.bodies[i].v_WBcm_W, t2.final_state.bodies[i].v_WBcm_W) << i;
  }
  EXPECT_EQ(b.summary.accumulated_velocity_error, t2.summary.accumulated_velocity_error);

  // A pair listed in the model keeps its own contact: the pairs run equals the listed run when
  // the listed model is given collide_all_pairs too (nothing left for the broadphase).
  TimeSteppingOptions both = p;
  const TimeSteppingResult c = SimulateTimeStepping(listed, s_listed, both);
  for (size_t i = 0; i < static_cast<size_t>(n); ++i) {
    EXPECT_EQ(a.final_state.bodies[i].v_WBcm_W, c.final_state.bodies[i].v_WBcm_W) << i;
  }
  EXPECT_EQ(c.final_state.unlisted_contact_work.impact_work, 0.0);
}

TEST(BallPairs, RefusesBadCoefficientsAndRadii) {
  const Model model = FreeBalls(2, 0.03, 0.2);
  State s = MakeRestState(model);
  SetBodyPose(model, 1, Vec3(1, 0, 0), Quat::Identity(), s);
  TimeSteppingOptions o = Pairs(0.01, 1e-3, 2, 0.03, 1.5);
  EXPECT_THROW(SimulateTimeStepping(model, s, o), InputError);
  o = Pairs(0.01, 1e-3, 2, 0.03, 0.5);
  o.ball_radii = {0.03};
  EXPECT_THROW(SimulateTimeStepping(model, s, o), InputError);
  o.ball_radii = {0.03, -1.0};
  EXPECT_THROW(SimulateTimeStepping(model, s, o), InputError);
}

}  // namespace
}  // namespace chasles
