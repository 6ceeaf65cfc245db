// Event-driven spheres on a plane (chasles/integrate/sphere_events.h) against closed forms
// derived here and against the hybrid engine (Simulate) on the same models.
#include "chasles/integrate/sphere_events.h"

#include <gtest/gtest.h>

#include <fmt/format.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "chasles/analysis/ledger.h"
#include "chasles/dynamics/contact_solve.h"
#include "chasles/error.h"
#include "chasles/integrate/simulate.h"
#include "chasles/mass/shape.h"
#include "chasles/model/forces.h"
#include "reference/balls_on_floor.h"

namespace chasles {
namespace {

constexpr double kG = 9.81;
const reference::Ball kBall{0.17, 0.028575, 0.25, 0.2};

SphereEventOptions Until(double t_end) {
  SphereEventOptions o;
  o.t_end = t_end;
  return o;
}

// Sets ball b at (x, y) on the floor with v and ω in W.
void Place(const Model& m, State& s, int b, double x, double y, const Vec3& v, const Vec3& w) {
  SetBodyPose(m, b, Vec3(x, y, kBall.radius), Quat::Identity(), s);
  SetBodyVelocity(m, b, v, w, s);
}

double RelErr(double a, double b) {
  return std::abs(a - b) / std::max(std::abs(b), 1e-300);
}

// A cue ball rolling at `speed` along x into a triangle of `rows` rows of balls 0.1 mm apart,
// each off its place by up to `jitter` in x and y (seeded; none when 0).
void Rack(const Model& m, State& s, int rows, double speed, double jitter) {
  const double pitch = 2 * kBall.radius + 1e-4;
  std::mt19937_64 rng(2026);
  std::uniform_real_distribution<double> U(-jitter, jitter);
  const auto off = [&] { return jitter > 0.0 ? U(rng) : 0.0; };
  int k = 1;
  for (int row = 0; row < rows; ++row) {
    for (int j = 0; j <= row; ++j) {
      const double x = 1.0 + row * pitch * std::sqrt(3.0) / 2 + off();
      Place(m, s, k++, x, (j - row / 2.0) * pitch + off(), Vec3::Zero(), Vec3::Zero());
    }
  }
  Place(m, s, 0, 0, 0.001, Vec3(speed, 0, 0), Vec3(0, speed / kBall.radius, 0));
}

// No ball below the floor and no two balls overlapping by more than `slack` at any sample.
void ExpectNoOverlap(const std::vector<State>& samples, int n, double slack) {
  for (const State& st : samples) {
    for (int a = 0; a < n; ++a) {
      EXPECT_GE(st.bodies[a].p_WBcm.z(), kBall.radius - slack);
      for (int b = a + 1; b < n; ++b) {
        EXPECT_GE((st.bodies[a].p_WBcm - st.bodies[b].p_WBcm).norm(), 2 * kBall.radius - slack);
      }
    }
  }
}

// Problem 8.26/8.27: set down spinning at w0 about y, centre at rest. Sliding ends at
// t* = 2 R w0 / (7 mu_k g), at x = ½ mu_k g t*², rolling at 2/7 R w0; friction's work is the
// kinetic energy lost, ½ I w0² - ½ (m + I/R²) v².
TEST(SphereEvents, SpinningBallStickTimeAndSpeedExact) {
  const Model m = reference::MakeBallsOnFloor(1, kBall, kG);
  State s = MakeRestState(m);
  const double w0 = 40.0;
  Place(m, s, 0, 0, 0, Vec3::Zero(), Vec3(0, w0, 0));
  const SphereEventResult r = SimulateSphereEvents(m, s, Until(1.0));
  const double t_star = reference::StickTime(kBall, kG, w0);
  const double v = reference::RollingSpeed(kBall, w0);
  ASSERT_EQ(r.contact_events.size(), 2U);
  EXPECT_EQ(r.contact_events[0].to, ContactMode::kSliding);
  EXPECT_EQ(r.contact_events[1].reason, ContactEventReason::kSlipStopped);
  EXPECT_LT(RelErr(r.contact_events[1].t, t_star), 1e-14);
  const BodyState& b = r.final_state.bodies[0];
  EXPECT_LT(RelErr(b.v_WBcm_W.x(), v), 1e-14);
  const double x_star = 0.5 * kBall.mu_k * kG * t_star * t_star;
  EXPECT_LT(RelErr(b.p_WBcm.x(), x_star + v * (1.0 - t_star)), 1e-13);
  const double I = 0.4 * kBall.mass * kBall.radius * kBall.radius;
  const double lost =
      0.5 * I * w0 * w0 - 0.5 * (kBall.mass + I / std::pow(kBall.radius, 2)) * v * v;
  EXPECT_LT(RelErr(-r.energy.friction, lost), 1e-13);
  EXPECT_LT(std::abs(r.energy.residual), 1e-14 * r.energy.initial);
  EXPECT_EQ(r.final_state.contacts[0].mode, ContactMode::kSticking);
  EXPECT_LT(RelErr(r.final_state.contacts[0].friction_work, -lost), 1e-13);
}

// Rolling resistance: a ball rolling at v0 decelerates at a = mu_r g / (1 + I/(m R²)) =
// 5/7 mu_r g and stops at t = v0 / a after v0² / (2 a); the work of the resistance is the
// kinetic energy ½ (m + I/R²) v0². The samples carry the rolling reference, so the contact
// outputs at a sample are the hybrid engine's: N = m g, the moment mu_r m g R against the
// rolling (about -n × v̂), the friction m a that decelerates the centre, its power -mu_r m g v.
TEST(SphereEvents, RollingResistanceStopsAtClosedFormTimeAndDistance) {
  reference::Ball ball = kBall;
  ball.mu_r = 0.01;
  const Model m2 = reference::MakeBallsOnFloor(1, ball, kG);
  State s = MakeRestState(m2);
  const double v0 = 1.3;
  Place(m2, s, 0, 0, 0, Vec3(v0, 0, 0), Vec3(0, v0 / ball.radius, 0));
  SphereEventOptions o = Until(30.0);
  o.output_interval = 1.0;
  const SphereEventResult r = SimulateSphereEvents(m2, s, o);
  const double a = 5.0 / 7.0 * 0.01 * kG;
  const double W = ball.mass * kG;
  for (const State& sample : r.samples) {
    if (!(sample.t > 0.0 && sample.t < v0 / a)) continue;
    const double v = v0 - a * sample.t;
    const ContactPointOutput out = CalcContactOutputs(m2, sample)[0];
    EXPECT_LT(RelErr(out.normal_force, W), 1e-14);
    EXPECT_TRUE(out.rolling_moment_W.isApprox(Vec3(0, -0.01 * W * ball.radius, 0), 1e-14))
        << out.rolling_moment_W.transpose();
    EXPECT_TRUE(out.friction_force_W.isApprox(Vec3(-ball.mass * a, 0, 0), 1e-12))
        << out.friction_force_W.transpose();
    EXPECT_LT(RelErr(out.rolling_power, -0.01 * W * v), 1e-12);
  }
  ASSERT_EQ(r.contact_events.size(), 2U);
  EXPECT_EQ(r.contact_events[1].reason, ContactEventReason::kRollingStopped);
  EXPECT_LT(RelErr(r.contact_events[1].t, v0 / a), 1e-14);
  EXPECT_LT(RelErr(r.final_state.bodies[0].p_WBcm.x(), v0 * v0 / (2 * a)), 1e-14);
  EXPECT_EQ(r.final_state.bodies[0].v_WBcm_W.norm(), 0.0);
  const double I = 0.4 * ball.mass * ball.radius * ball.radius;
  EXPECT_LT(RelErr(-r.energy.rolling, 0.5 * (ball.mass + I / std::pow(ball.radius, 2)) * v0 * v0),
            1e-13);
}

// A head-on hit, frictionless between the balls, restitution e: A rolling at v meets B at rest
// after (d - 2R)/v. Momentum and the energetic law (one slope: Newton's) give
// v_A = v (1 - e)/2, v_B = v (1 + e)/2, the spins unchanged. Each then slides to rolling with
// its angular momentum about the contact point kept, (m + I/R²) v_roll = m v + I ω/R:
// A at (5 v_A + 2 v)/7, B at 5/7 v_B.
TEST(SphereEvents, HeadOnHitThenBothRollAtClosedFormSpeeds) {
  const Model m = reference::MakeBallsOnFloor(2, kBall, kG);
  State s = MakeRestState(m);
  const double v = 2.0, d = 0.5, e = 0.9;
  Place(m, s, 0, 0, 0, Vec3(v, 0, 0), Vec3(0, v / kBall.radius, 0));
  Place(m, s, 1, d, 0, Vec3::Zero(), Vec3::Zero());
  SphereEventOptions o = Until(2.0);
  o.collide_all_pairs = true;
  o.pair_law.restitution = e;
  const SphereEventResult r = SimulateSphereEvents(m, s, o);
  ASSERT_EQ(r.collisions.size(), 1U);
  const SphereCollision& c = r.collisions[0];
  EXPECT_LT(RelErr(c.t, (d - 2 * kBall.radius) / v), 1e-14);
  EXPECT_LT(RelErr(c.approach_speed, v), 1e-13);
  EXPECT_LT(RelErr(c.normal_impulse, kBall.mass * v * (1 + e) / 2), 1e-12);
  const double vA = v * (1 - e) / 2, vB = v * (1 + e) / 2;
  EXPECT_LT(RelErr(r.final_state.bodies[0].v_WBcm_W.x(), (5 * vA + 2 * v) / 7), 1e-12);
  EXPECT_LT(RelErr(r.final_state.bodies[1].v_WBcm_W.x(), 5.0 / 7.0 * vB), 1e-12);
  // The impact's loss: ½ μ (1 - e²) v² with μ = m/2.
  EXPECT_LT(RelErr(-r.energy.impacts, 0.25 * kBall.mass * (1 - e * e) * v * v), 1e-12);
  EXPECT_LT(std::abs(r.energy.residual), 1e-13 * r.energy.initial);
}

// Seeded balls far apart with random velocities and spins (spin about the normal included)
// against the closed form of each: the slip u0 = v0 - R ω0 × n keeps its direction and falls
// at 7/2 mu_k g, so sliding ends at t* = |u0| / (7/2 mu_k g) with v = v0 - mu_k g t* û0.
TEST(SphereEvents, SeededBallsStickWhereTheClosedFormSays) {
  const int n = 30;
  const Model m = reference::MakeBallsOnFloor(n, kBall, kG);
  State s = MakeRestState(m);
  std::mt19937_64 rng(1234);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  std::vector<Vec3> u0(n), v0(n);
  for (int i = 0; i < n; ++i) {
    v0[i] = Vec3(U(rng), U(rng), 0);
    const Vec3 w(40 * U(rng), 40 * U(rng), 40 * U(rng));
    Place(m, s, i, 10.0 * i, 0, v0[i], w);
    u0[i] = v0[i] - kBall.radius * w.cross(Vec3::UnitZ());
  }
  const SphereEventResult r = SimulateSphereEvents(m, s, Until(3.0));
  int stuck = 0;
  for (const ContactEvent& ev : r.contact_events) {
    if (ev.reason != ContactEventReason::kSlipStopped) continue;
    ++stuck;
    const int i = ev.point;
    const double t_star = u0[i].norm() / (3.5 * kBall.mu_k * kG);
    EXPECT_LT(RelErr(ev.t, t_star), 1e-13) << i;
    const Vec3 v = v0[i] - kBall.mu_k * kG * t_star * u0[i].normalized();
    EXPECT_LT((r.final_state.bodies[i].v_WBcm_W - v).norm(), 1e-13 * (1 + v.norm())) << i;
  }
  EXPECT_EQ(stuck, n);
  EXPECT_LT(std::abs(r.energy.residual), 1e-13 * r.energy.initial);
}

// The same balls with every pair listed as a sphere-sphere contact, run by the hybrid engine
// (Dormand-Prince, events located to 1e-12 s) and event-driven: the collisions happen at the
// same times and the final states agree.
TEST(SphereEvents, AgreesWithTheHybridEngineOnACollidingGroup) {
  const int n = 5;
  Model m = reference::MakeBallsOnFloor(n, kBall, kG);
  for (int a = 0; a < n; ++a) {
    for (int b = a + 1; b < n; ++b) {
      ContactSpec c;
      c.name = fmt::format("pair{}_{}", a, b);
      c.shape = ContactShape::kSphereSphere;
      c.body = a;
      c.other_body = b;
      c.radius = c.other_radius = kBall.radius;
      c.restitution = 0.8;
      c.mu_s = c.mu_k = 0.05;
      m.AddContact(c);
    }
  }
  State s = MakeRestState(m);
  // A cue ball rolling into a loose row, the row's balls 1 cm apart, slightly off line.
  Place(m, s, 0, 0, 0, Vec3(1.5, 0.02, 0), Vec3(-0.02 / kBall.radius, 1.5 / kBall.radius, 3.0));
  for (int i = 1; i < n; ++i) {
    Place(m, s, i, 0.3 + (i - 1) * (2 * kBall.radius + 0.01), 0.004 * i, Vec3::Zero(),
          Vec3::Zero());
  }
  const double t_end = 1.5;
  const SphereEventResult r = SimulateSphereEvents(m, s, Until(t_end));
  ASSERT_GE(r.collisions.size(), 3U);
  SimulationOptions so;
  so.t_end = t_end;
  so.output_interval = 0.0;
  so.adaptive.rtol = 1e-12;
  so.adaptive.atol = 1e-14;
  const SimulationResult h = Simulate(m, s, so);
  // The hybrid engine records every point that took part (the floor points under the balls
  // too); the ball-ball points are numbered after the n floor points.
  // Friction between the balls lifts some of them: their landings are plane impacts.
  std::vector<ImpactRecord> pair_impacts, landings;
  for (const ImpactRecord& rec : h.impacts) {
    if (rec.point >= n) pair_impacts.push_back(rec);
    if (rec.point < n && rec.approach_speed > 0.0) landings.push_back(rec);
  }
  ASSERT_EQ(landings.size(), r.plane_impacts.size());
  ASSERT_GE(landings.size(), 3U);
  for (size_t k = 0; k < landings.size(); ++k) {
    EXPECT_EQ(landings[k].point, r.plane_impacts[k].point) << k;
    EXPECT_NEAR(landings[k].t, r.plane_impacts[k].t, 1e-9) << k;
  }
  ASSERT_EQ(pair_impacts.size(), r.collisions.size());
  for (size_t k = 0; k < r.collisions.size(); ++k) {
    EXPECT_NEAR(pair_impacts[k].t, r.collisions[k].t, 1e-9) << k;
    EXPECT_NEAR(pair_impacts[k].normal_impulse, r.collisions[k].normal_impulse,
                1e-8 * r.collisions[k].normal_impulse)
        << k;
  }
  for (int i = 0; i < n; ++i) {
    EXPECT_LT((h.final_state.bodies[i].p_WBcm - r.final_state.bodies[i].p_WBcm).norm(), 1e-8) << i;
    EXPECT_LT((h.final_state.bodies[i].v_WBcm_W - r.final_state.bodies[i].v_WBcm_W).norm(), 1e-8)
        << i;
    // The orientation (Magnus steps of 1e-12 rad, docs/contact.md) and the spin.
    EXPECT_LT(h.final_state.bodies[i].q_WB.angularDistance(r.final_state.bodies[i].q_WB), 1e-8)
        << i;
    EXPECT_LT((h.final_state.bodies[i].w_WB_B - r.final_state.bodies[i].w_WB_B).norm(), 1e-7) << i;
  }
  EXPECT_LT(std::abs(r.energy.residual), 1e-13 * r.energy.initial);
}

// The ledger the states carry (CalcLedgerSample: each plane point's and listed pair's works,
// the unlisted pairs' works and gravity's integrals) balances at every sample, and at the end
// its works are the run's own closed-form sums.
void ExpectLedgerBalances(const Model& m, const State& initial, const SphereEventResult& r) {
  for (const State& st : r.samples) {
    const LedgerSample L = CalcLedgerSample(m, st, initial);
    EXPECT_LT(std::abs(L.energy_residual), 1e-12 * L.energy_scale) << "t = " << st.t;
  }
  const LedgerSample L = CalcLedgerSample(m, r.final_state, initial);
  const double scale = r.energy.initial;
  EXPECT_NEAR(L.contact_impact_work, r.energy.impacts, 1e-12 * scale);
  EXPECT_NEAR(L.contact_friction_work, r.energy.friction, 1e-12 * scale);
  EXPECT_NEAR(L.contact_rolling_work, r.energy.rolling, 1e-12 * scale);
}

// A seeded break: a cue ball into a triangle of 45 balls with 0.1 mm gaps, every pair free to
// collide, friction between the balls (so some hop): the run's energy balance closes to
// round-off, no two balls ever overlap at the samples, and the result is the same run to run.
TEST(SphereEvents, BreakOfFortySixBallsBalancesEnergyAndNeverOverlaps) {
  const int rows = 9, n = rows * (rows + 1) / 2 + 1;
  const Model m = reference::MakeBallsOnFloor(n, kBall, kG);
  State s = MakeRestState(m);
  Rack(m, s, rows, 8.0, 0.0);
  SphereEventOptions o = Until(4.0);
  o.output_interval = 0.05;
  o.collide_all_pairs = true;
  o.pair_law = {0.93, 0.06, 0.06, RestitutionLaw::kEnergetic};
  const SphereEventResult r = SimulateSphereEvents(m, s, o);
  EXPECT_GT(r.collisions.size(), 40U);
  EXPECT_LT(std::abs(r.energy.residual), 1e-12 * r.energy.initial);
  EXPECT_LT(r.energy.friction + r.energy.impacts, 0.0);
  ExpectNoOverlap(r.samples, n, 1e-9);
  ExpectLedgerBalances(m, s, r);
  double lost = 0.0;  // each impact's loss, once per impact
  for (size_t k = 0; k < r.collisions.size(); ++k) {
    const SphereCollision& c = r.collisions[k];
    if (k == 0 || c.t != r.collisions[k - 1].t) lost += c.energy_lost;
  }
  EXPECT_GT(lost, 0.0);
  EXPECT_LE(lost, -r.energy.impacts * (1 + 1e-12));
  const SphereEventResult again = SimulateSphereEvents(m, s, o);
  ASSERT_EQ(again.collisions.size(), r.collisions.size());
  for (int i = 0; i < n; ++i) {
    EXPECT_EQ(again.final_state.bodies[i].p_WBcm, r.final_state.bodies[i].p_WBcm);
  }
}

// The bench's break shot (bench/break_shot_bench.cpp) on 37 balls: a tight rack, 0.1 mm gaps
// and each ball off its place by up to 25 µm (seeded), frictionless ball-ball hits, rolling
// resistance on the cloth. Balls of the rack end up pressed together with almost no force, in
// groups the hybrid engine runs; there a pair point sits where its normal force and its
// relative acceleration are both zero to round-off. The run goes to its end (before, such a
// point was released and landed again at one instant until max_mode_switches), its energy
// balance closes to round-off, and no two balls overlap by more than the touching tolerance.
TEST(SphereEvents, TightRackWithRollingResistanceRunsThroughItsPressingGroups) {
  const reference::Ball ball{0.17, 0.028575, 0.25, 0.2, 0.01};
  const int rows = 8, n = rows * (rows + 1) / 2 + 1;
  const Model m = reference::MakeBallsOnFloor(n, ball, kG);
  State s = MakeRestState(m);
  Rack(m, s, rows, 10.0, 25e-6);
  SphereEventOptions o = Until(3.0);
  o.output_interval = 0.01;
  o.collide_all_pairs = true;
  o.pair_law = {0.93, 0.0, 0.0, RestitutionLaw::kEnergetic};
  const SphereEventResult r = SimulateSphereEvents(m, s, o);
  EXPECT_GT(r.stats.groups, 0);
  EXPECT_GT(r.stats.group_windows, 10);
  EXPECT_LT(std::abs(r.energy.residual), 1e-12 * r.energy.initial);
  ASSERT_EQ(r.samples.back().t, 3.0);
  ExpectNoOverlap(r.samples, n, 2e-9);
  ExpectLedgerBalances(m, s, r);
}

TEST(SphereEvents, RefusesWhatItCannotRun) {
  Model tilted = reference::MakeBallsOnFloor(1, kBall, kG);
  tilted.AddForceElement(std::make_shared<UniformGravity>("wind", Vec3(0.1, 0, 0)));
  EXPECT_NE(SphereEventObstacle(tilted).why.find("tilted"), std::string::npos);
  const Model m = reference::MakeBallsOnFloor(2, kBall, kG);
  EXPECT_TRUE(SphereEventObstacle(m).empty());
  State s = MakeRestState(m);
  Place(m, s, 0, 0, 0, Vec3::Zero(), Vec3::Zero());
  Place(m, s, 1, kBall.radius, 0, Vec3::Zero(), Vec3::Zero());
  try {
    SimulateSphereEvents(m, s, Until(1.0));
    ADD_FAILURE() << "overlap accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("'ball0' and 'ball1' start overlapping"),
              std::string::npos)
        << e.what();
  }
  EXPECT_THROW(SimulateSphereEvents(tilted, s, Until(1.0)), InputError);
}

}  // namespace
}  // namespace chasles

namespace chasles {
namespace {

// A plastic hit (e = 0 between the balls) of a ball with strong topspin into a ball at rest:
// after the impact the rear ball's friction drives it on into the front one, so the two press
// together and run as a group on the hybrid engine. The pair force acts through both centres
// at height R, equal and opposite, and the floor forces at the floor: about the floor line the
// pair's angular momentum Σ (m v + I ω / R) is kept, 2.2 m at the start (1 m/s, ω = 3/R,
// I = 2/5 m R²). The two end rolling together, each with (m + I/R²) v = 1.4 m v, so
// v = 2.2 / 2.8 = 11/14 m/s. The whole run agrees with the hybrid engine on the same model.
TEST(SphereEvents, PressingPairRunsAsAGroupAndAgreesWithTheHybridEngine) {
  Model m = reference::MakeBallsOnFloor(2, kBall, kG);
  ContactSpec c;
  c.name = "pair";
  c.shape = ContactShape::kSphereSphere;
  c.body = 0;
  c.other_body = 1;
  c.radius = c.other_radius = kBall.radius;
  c.restitution = 0.0;
  m.AddContact(c);
  State s = MakeRestState(m);
  Place(m, s, 0, 0, 0, Vec3(1.0, 0, 0), Vec3(0, 3.0 / kBall.radius, 0));
  Place(m, s, 1, 0.2, 0, Vec3::Zero(), Vec3::Zero());
  const SphereEventResult r = SimulateSphereEvents(m, s, Until(1.0));
  EXPECT_GE(r.stats.groups, 1);
  SimulationOptions so;
  so.t_end = 1.0;
  so.adaptive.rtol = 1e-11;
  so.adaptive.atol = 1e-13;
  const SimulationResult h = Simulate(m, s, so);
  for (int i = 0; i < 2; ++i) {
    EXPECT_LT((h.final_state.bodies[i].p_WBcm - r.final_state.bodies[i].p_WBcm).norm(), 1e-7) << i;
    EXPECT_LT((h.final_state.bodies[i].v_WBcm_W - r.final_state.bodies[i].v_WBcm_W).norm(), 1e-7)
        << i;
  }
  for (int i = 0; i < 2; ++i) {
    EXPECT_LT(RelErr(r.final_state.bodies[i].v_WBcm_W.x(), 11.0 / 14.0), 1e-9) << i;
  }
  EXPECT_LT(std::abs(r.energy.residual), 1e-8 * r.energy.initial);
}

}  // namespace
}  // namespace chasles

namespace chasles {
namespace {

// Two balls rolling one behind the other, the rear 1e-7 m/s faster (below resting_speed),
// no rolling resistance: nothing presses them together, so the slow approach is an ordinary
// impact (no group): the front ball gains (1 + e)/2 of the difference at once, and the rear
// keeps (1 - e)/2 of it. Their slips after it, below 1e-7 m/s, are under stick_speed, so both
// roll on at those speeds (as the hybrid engine's mode selection does).
TEST(SphereEvents, SlowApproachWithoutPressingIsAnImpact) {
  const Model m = reference::MakeBallsOnFloor(2, kBall, kG);
  State s = MakeRestState(m);
  const double v = 0.5, dv = 1e-7, e = 0.9;
  Place(m, s, 0, 0, 0, Vec3(v + dv, 0, 0), Vec3(0, (v + dv) / kBall.radius, 0));
  Place(m, s, 1, 2 * kBall.radius + 1e-6, 0, Vec3(v, 0, 0), Vec3(0, v / kBall.radius, 0));
  SphereEventOptions o = Until(30.0);
  o.collide_all_pairs = true;
  o.pair_law.restitution = e;
  const SphereEventResult r = SimulateSphereEvents(m, s, o);
  EXPECT_EQ(r.stats.groups, 0);
  ASSERT_EQ(r.collisions.size(), 1U);
  EXPECT_NEAR(r.collisions[0].approach_speed, dv, 1e-15);
  EXPECT_NEAR(r.collisions[0].t, 1e-6 / dv, 1e-6);
  const double vA = v + dv * (1 - e) / 2, vB = v + dv * (1 + e) / 2;
  EXPECT_NEAR(r.final_state.bodies[0].v_WBcm_W.x(), vA, 1e-15);
  EXPECT_NEAR(r.final_state.bodies[1].v_WBcm_W.x(), vB, 1e-15);
}

}  // namespace
}  // namespace chasles

namespace chasles {
namespace {

// A ball that starts touching the plane and moving into it at v lands at once: with
// restitution e (no spin, so no friction impulse) it leaves at e v and lands again after the
// flight 2 e v / g, at e² v.
TEST(SphereEvents, BallStartingIntoThePlaneBouncesAtOnce) {
  reference::Ball ball = kBall;
  ball.restitution = 0.5;
  const Model m = reference::MakeBallsOnFloor(1, ball, kG);
  State s = MakeRestState(m);
  const double v = 1.0, e = 0.5;
  Place(m, s, 0, 0, 0, Vec3(0, 0, -v), Vec3::Zero());
  const SphereEventResult r = SimulateSphereEvents(m, s, Until(0.15));
  ASSERT_GE(r.plane_impacts.size(), 2U);
  EXPECT_EQ(r.plane_impacts[0].t, 0.0);
  EXPECT_LT(RelErr(r.plane_impacts[0].approach_speed, v), 1e-14);
  EXPECT_LT(RelErr(r.plane_impacts[1].t, 2 * e * v / kG), 1e-14);
  EXPECT_LT(RelErr(r.plane_impacts[1].approach_speed, e * v), 1e-14);
  EXPECT_TRUE(r.warnings.empty());
}

// A slip within stick_speed is taken as rolling, and the run says so; an exact roll is not
// reported.
TEST(SphereEvents, SlipWithinStickSpeedIsRollingAndSaidSo) {
  const Model m = reference::MakeBallsOnFloor(2, kBall, kG);
  State s = MakeRestState(m);
  Place(m, s, 0, 0, 0, Vec3(1.0, 0, 0), Vec3(0, 1.0 / kBall.radius, 0));
  Place(m, s, 1, 1, 0, Vec3(1.0 + 5e-7, 0, 0), Vec3(0, 1.0 / kBall.radius, 0));
  const SphereEventResult r = SimulateSphereEvents(m, s, Until(0.5));
  ASSERT_EQ(r.warnings.size(), 1U);
  EXPECT_NE(r.warnings[0].find("body 'ball1': its slip of 5e-07 m/s"), std::string::npos)
      << r.warnings[0];
  EXPECT_EQ(r.contact_events[1].to, ContactMode::kSticking);
  EXPECT_EQ(r.final_state.bodies[1].v_WBcm_W.x(), 1.0 + 5e-7);
}

TEST(SphereEvents, RefusesAbsurdOptions) {
  const Model m = reference::MakeBallsOnFloor(2, kBall, kG);
  State s = MakeRestState(m);
  Place(m, s, 0, 0, 0, Vec3::Zero(), Vec3::Zero());
  Place(m, s, 1, 1, 0, Vec3::Zero(), Vec3::Zero());
  SphereEventOptions o = Until(std::numeric_limits<double>::infinity());
  EXPECT_THROW(SimulateSphereEvents(m, s, o), InputError);
  o = Until(1.0);
  o.output_interval = std::nan("");
  EXPECT_THROW(SimulateSphereEvents(m, s, o), InputError);
  o = Until(1.0);
  o.collide_all_pairs = true;
  o.pair_law.restitution = 1.5;
  try {
    SimulateSphereEvents(m, s, o);
    ADD_FAILURE() << "restitution 1.5 accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("pair_law"), std::string::npos) << e.what();
  }
  State nan_state = s;
  nan_state.bodies[0].v_WBcm_W.x() = std::nan("");
  EXPECT_THROW(SimulateSphereEvents(m, nan_state, Until(1.0)), InputError);
}

}  // namespace
}  // namespace chasles

namespace chasles {
namespace {

// A solid ball (I = 2/5 m R²) rolling at v0 catches a hollow one (I = 2/3 m R², same m and R)
// at rest; the hit is plastic. Derivation (k = 1 + I/(m R²): 7/5 solid, 5/3 hollow; a rolling
// ball pushed by P through its centre has a = (P/m - mu_r g)/k):
//  - approach: rolling, a_r = mu_r g / (7/5); the hit at v_h = sqrt(v0² - 2 a_r d).
//  - hit: both at v_h/2 (equal masses, e = 0, frictionless, no floor impulse).
//  - both sliding, pressed by P = mu_k m g: a = 0; the solid's slip -v_h/2 rises at
//    5/2 mu_k g (ω̇ = -mu_k g R m/I) and is gone at t_A = v_h/(5 mu_k g); the hollow's, v_h/2,
//    falls at 3/2 mu_k g, to v_h/5 at t_A.
//  - the solid rolls, pushing the sliding hollow (no rolling resistance while sliding): equal
//    accelerations, (-P/m - mu_r g) / (7/5) = P/m - mu_k g, give P/m = (7 mu_k - 5 mu_r) g / 12 and
//    a = -5 (mu_k + mu_r) g / 12; the hollow's slip falls at 3/2 mu_k g - a and is gone after τ2.
//  - both roll: the solid slows at 5/7 mu_r g, the hollow at 3/5 mu_r g, so they part and the
//    hollow one leaves the group on its closed-form chain; each stops after v2 / (its rate).
// With `row` > 0, that many balls rest in a line beside the path, 0.1 mm from it, every pair
// free to collide: the pair passes them without a touch, so nothing above changes. `windows`:
// the number of the group's hybrid runs. With `output` > 0 the run is sampled that often: each
// sample brings the group to its time, cutting the window there (run on from its last
// checkpoint), and the samples in the pressed phase lie on its closed form.
void ExpectSolidPushesHollow(double v0, double x_b, double mu_k, double mu_r, int row = 0,
                             long* windows = nullptr, double output = 0.0) {
  SCOPED_TRACE(fmt::format("v0 = {}, x_b = {}, mu_k = {}, mu_r = {}, row = {}, output = {}", v0,
                           x_b, mu_k, mu_r, row, output));
  const double m = 0.17, R = 0.028575, mu_s = 1.25 * mu_k, g = kG;
  std::vector<reference::Ball> balls{{m, R, mu_s, mu_k, mu_r, 0.0, 0.4},
                                     {m, R, mu_s, mu_k, mu_r, 0.0, 2.0 / 3.0}};
  balls.resize(static_cast<size_t>(2 + row), balls[0]);
  Model model = reference::MakeBallsOnFloor(balls, g);
  ContactSpec pair;
  pair.name = "pair";
  pair.shape = ContactShape::kSphereSphere;
  pair.body = 0;
  pair.other_body = 1;
  pair.radius = pair.other_radius = R;
  model.AddContact(pair);
  State s = MakeRestState(model);
  SetBodyPose(model, 0, Vec3(0, 0, R), Quat::Identity(), s);
  SetBodyVelocity(model, 0, Vec3(v0, 0, 0), Vec3(0, v0 / R, 0), s);
  SetBodyPose(model, 1, Vec3(x_b, 0, R), Quat::Identity(), s);
  for (int k = 0; k < row; ++k) {
    SetBodyPose(model, 2 + k, Vec3(x_b + k * (2 * R + 1e-3), 2 * R + 1e-4, R), Quat::Identity(), s);
  }
  const double a_r = mu_r * g / 1.4, d = x_b - 2 * R;
  const double v_h = std::sqrt(v0 * v0 - 2 * a_r * d);
  const double t_h = (v0 - v_h) / a_r;
  const double t_a = v_h / (5 * mu_k * g);
  const double a2 = -5 * (mu_k + mu_r) * g / 12;
  const double tau2 = 0.2 * v_h / (1.5 * mu_k * g - a2);
  const double v2 = 0.5 * v_h + a2 * tau2;
  const double t2 = t_h + t_a + tau2;
  const double x2 = x_b + 0.5 * v_h * (t_a + tau2) + 0.5 * a2 * tau2 * tau2;  // the hollow's
  const double rate_solid = mu_r * g * 5 / 7, rate_hollow = mu_r * g * 3 / 5;
  SphereEventOptions o = Until(t2 + v2 / rate_hollow + 1.0);
  o.collide_all_pairs = row > 0;  // plastic and frictionless, as the listed pair
  o.output_interval = output;
  const SphereEventResult r = SimulateSphereEvents(model, s, o);
  if (windows != nullptr) *windows = r.stats.group_windows;
  // Pressed and both sliding (a = 0): each at v_h/2, the hollow one at x_b + v_h/2 (t - t_h).
  int pressed_samples = 0;
  for (const State& sample : r.samples) {
    if (!(sample.t > t_h && sample.t < t_h + t_a)) continue;
    ++pressed_samples;
    const double x = x_b + 0.5 * v_h * (sample.t - t_h);
    EXPECT_LT(RelErr(sample.bodies[1].p_WBcm.x(), x), 1e-10) << "t = " << sample.t;
    EXPECT_LT(RelErr(sample.bodies[0].p_WBcm.x(), x - 2 * R), 1e-10) << "t = " << sample.t;
    EXPECT_LT(RelErr(sample.bodies[1].v_WBcm_W.x(), 0.5 * v_h), 1e-10) << "t = " << sample.t;
  }
  if (output > 0.0) {
    EXPECT_GE(pressed_samples, static_cast<int>(t_a / output) - 1);
  }

  EXPECT_GE(r.stats.groups, 1);
  for (int k = 0; k < row; ++k) {
    EXPECT_EQ(r.final_state.bodies[static_cast<size_t>(2 + k)].p_WBcm,
              s.bodies[static_cast<size_t>(2 + k)].p_WBcm);
  }
  for (const SphereCollision& c : r.collisions) EXPECT_LT(std::max(c.body_a, c.body_b), 2);
  // Slip stops: the solid's (after the hit) at t_h + t_a, the hollow's at t2; rolling stops at
  // t2 + v2 / rate for each.
  std::vector<double> slip[2], stop[2];
  for (const ContactEvent& e : r.contact_events) {
    if (e.point > 1 || e.t <= t_h) continue;
    if (e.reason == ContactEventReason::kSlipStopped) slip[e.point].push_back(e.t);
    if (e.reason == ContactEventReason::kRollingStopped) stop[e.point].push_back(e.t);
  }
  ASSERT_EQ(slip[0].size(), 1u);
  ASSERT_EQ(slip[1].size(), 1u);
  EXPECT_LT(RelErr(slip[0][0], t_h + t_a), 1e-10);  // located by the hybrid engine
  EXPECT_LT(RelErr(slip[1][0], t2), 1e-10);
  ASSERT_EQ(stop[0].size(), 1u);
  ASSERT_EQ(stop[1].size(), 1u);
  EXPECT_LT(RelErr(stop[0][0], t2 + v2 / rate_solid), 1e-10);
  EXPECT_LT(RelErr(stop[1][0], t2 + v2 / rate_hollow), 1e-10);
  // Where they come to rest.
  const State& f = r.final_state;
  EXPECT_LT(RelErr(f.bodies[1].p_WBcm.x(), x2 + v2 * v2 / (2 * rate_hollow)), 1e-10);
  EXPECT_LT(RelErr(f.bodies[0].p_WBcm.x(), x2 - 2 * R + v2 * v2 / (2 * rate_solid)), 1e-10);
  EXPECT_EQ(f.bodies[0].v_WBcm_W.norm(), 0.0);
  EXPECT_EQ(f.bodies[1].v_WBcm_W.norm(), 0.0);
  EXPECT_LT(std::abs(r.energy.residual), 1e-9 * r.energy.initial);
}

TEST(SphereEvents, PressedPairPartsAndTheLeaverRollsOnInClosedForm) {
  ExpectSolidPushesHollow(1.0, 0.2, 0.2, 0.01);
}

// The group's windows end where its members may actually reach another ball (stop events on
// the outside balls' chains), not where a bound on their speed could: the row 0.1 mm beside
// the path cuts none of them. (A bound of v_h/2 or more would end a window every 0.2 ms or
// sooner over the 0.15 s the pair presses.)
TEST(SphereEvents, PressedPairPassesARowOfBallsBesideItsPathUntouched) {
  long alone = 0, beside_row = 0;
  ExpectSolidPushesHollow(1.0, 0.2, 0.2, 0.01, 0, &alone);
  ExpectSolidPushesHollow(1.0, 0.2, 0.2, 0.01, 12, &beside_row);
  EXPECT_EQ(beside_row, alone);
  EXPECT_LE(alone, 12);
}

// Sampled every 5 ms, the group is brought to each sample's time and its window cut there;
// the cut run goes on from its last checkpoint (the window's own samples) to the cut, and the
// run keeps every closed form above (slip and rolling stops, resting places) to 1e-10 with
// more windows than unsampled.
TEST(SphereEvents, PressedPairSampledOftenKeepsItsClosedForms) {
  long unsampled = 0, sampled = 0;
  ExpectSolidPushesHollow(1.0, 0.2, 0.2, 0.01, 0, &unsampled);
  ExpectSolidPushesHollow(1.0, 0.2, 0.2, 0.01, 0, &sampled, 0.005);
  EXPECT_GT(sampled, unsampled);
}

// The same closed forms over seeded speeds, distances and coefficients (mu_r < 7/5 mu_k keeps
// the solid pushing; mu_s = 1.25 mu_k holds the rolling solid, whose friction needs
// (mu_k - 5 mu_r)/6 of its weight).
TEST(SphereEvents, SeededPressedPairsPartWhereTheClosedFormSays) {
  std::mt19937_64 rng(31);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  for (int k = 0; k < 20; ++k) {
    const double v0 = 0.5 + 2.5 * U(rng), x_b = 0.1 + 0.4 * U(rng);
    const double mu_k = 0.1 + 0.3 * U(rng), mu_r = 0.002 + 0.028 * U(rng);
    ExpectSolidPushesHollow(v0, x_b, mu_k, mu_r);
  }
}

}  // namespace
}  // namespace chasles
