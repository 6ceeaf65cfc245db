// Contacts: the spinning ball of Problems 8.26/8.27 set down on a floor (sliding ends at
// t* = 2 R w0 / (7 mu_k g), then it rolls at v = 2/7 R w0), run
//  - event-driven: the engine's hybrid Simulate, the stick event located on the Dormand-Prince
//    dense output;
//  - fixed-step: the engine's own RK4 on the same Model, the way time-stepping engines treat
//    friction: the mode is held over each step and switched at the end of the step in which
//    the slip changed sign (the velocities then projected onto rolling by the contact impulse,
//    SelectContactModes), so the stick time is found to within one step;
// and many spinning balls on one floor, event-driven, to show how the cost grows with the
// number of bodies when one global integrator restarts at every event; and n balls dropped on
// the floor and bouncing (restitution 0.5), event-driven against fixed-step RK4 with the
// impact resolved at the end of the step that went through the floor, impact times and
// speeds against the closed form, n = 10, 100, 1,000; and 1,000 spinning balls as islands (each
// ball its own hybrid system) against 1,000 one-ball runs timed in the same benchmark.
// Benchmarks never assert; the errors are counters. Results and the commands:
// docs/benchmarks.md.

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <random>
#include <vector>

#include <benchmark/benchmark.h>
#include <fmt/format.h>

#include "chasles/dynamics/contact_solve.h"
#include "chasles/dynamics/newton_euler.h"
#include "chasles/error.h"
#include "chasles/integrate/rk4.h"
#include "chasles/integrate/simulate.h"
#include "chasles/integrate/time_stepping.h"
#include "chasles/model/contact.h"
#include "chasles/model/data.h"
#include "chasles/model/forces.h"
#include "chasles/model/model.h"
#include "reference/balls_on_floor.h"

namespace chasles {
namespace {

constexpr double kG = 9.80665;
constexpr double kR = 0.028575;  // 9/8 in
constexpr double kMass = 0.17;
constexpr double kMuK = 0.35;
constexpr double kW0 = 100 * 2 * M_PI / 60;  // 100 rpm

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

// Spin of ball i about y: w0 (1 + i/n) when `spread` (every ball its own t*, so n separate
// stick events), w0 for all otherwise (all stick at the same instant: one event).
double SpinOf(int i, int n, bool spread) {
  return spread ? kW0 * (1 + double(i) / n) : kW0;
}

// Ball i spins about y, 1 m apart along y, resting on the floor z = 0.
State MakeSpinningBalls(const Model& m, int n, bool spread) {
  State s = MakeRestState(m);
  for (int i = 0; i < n; ++i) {
    SetBodyPose(m, i, Vec3(0, i, kR), Quat::Identity(), s);
    SetBodyVelocity(m, i, Vec3::Zero(), Vec3(0, SpinOf(i, n, spread), 0), s);
  }
  return s;
}

SimulationOptions EventDrivenOptions(double t_end) {
  SimulationOptions o;
  o.t_end = t_end;
  o.adaptive.rtol = 1e-12;
  o.adaptive.atol = 1e-14;
  o.store_samples = false;
  // (a)-(c) measure the one global hybrid system (every event restarts it for all bodies);
  // (d) the islands.
  o.islands = false;
  return o;
}

// --- (a) one ball -------------------------------------------------------------------------

void SpinningBallEventDriven(benchmark::State& st) {
  const Model m = MakeBalls(1);
  const State s0 = MakeSpinningBalls(m, 1, false);
  const SimulationOptions o = EventDrivenOptions(2 * TStar(kW0));
  double t_event = NAN, v_end = NAN;
  IntegratorStats stats;
  for (auto _ : st) {
    try {
      const SimulationResult r = Simulate(m, s0, o);
      for (const ContactEvent& e : r.contact_events) {
        if (e.to == ContactMode::kSticking && e.from == ContactMode::kSliding) t_event = e.t;
      }
      v_end = r.final_state.bodies[0].v_WBcm_W.norm();
      stats = r.stats;
      benchmark::DoNotOptimize(r.final_state.bodies.data());
    } catch (const InputError& e) {
      st.SkipWithError(e.what());
      return;
    }
  }
  st.counters["t_star_rel_error"] = std::abs(t_event - TStar(kW0)) / TStar(kW0);
  st.counters["v_end_rel_error"] = std::abs(v_end - RollingSpeed(kW0)) / RollingSpeed(kW0);
  st.counters["steps"] = static_cast<double>(stats.steps);
  st.counters["evaluations"] = static_cast<double>(stats.function_evaluations);
}
BENCHMARK(SpinningBallEventDriven)->Unit(benchmark::kMicrosecond);

// The same Model stepped by RK4 at h = 10^-k s. The sliding mode's friction keeps its
// direction over the step (the mode's reference slip direction), so the slip runs past zero
// inside the step; at the end of that step the ball is switched to rolling: the slip is
// checked from the state (v_C = v + w × (-R n), no extra evaluation) and SelectContactModes,
// allowed to stick at any slip up to the overshoot of one step (7/2 mu_k g h), projects the
// velocities onto the rolling constraint with the contact impulse (which keeps the angular
// momentum about the contact point, as in Problem 8.27).
void SpinningBallFixedStepRk4(benchmark::State& st) {
  const double h = std::pow(10.0, -static_cast<double>(st.range(0)));
  const Model m = MakeBalls(1);
  const double t_end = 2 * TStar(kW0);
  const auto n_steps = static_cast<long>(std::ceil(t_end / h - 1e-9));
  ContactTolerances tol;
  tol.stick_speed = 4.0 * kMuK * kG * h;  // > 7/2 mu_k g h, the largest overshoot
  State s0 = MakeSpinningBalls(m, 1, false);
  SelectContactModes(m, s0);  // sliding, against the initial slip
  Rk4Integrator rk4(m);
  double t_event = NAN, v_end = NAN;
  for (auto _ : st) {
    State s = s0;
    for (long i = 0; i < n_steps; ++i) {
      rk4.Step(s, h);
      ContactPointState& cs = s.contacts[0];
      if (cs.mode != ContactMode::kSliding) continue;
      const BodyState& b = s.bodies[0];
      const Vec3 w_W = b.q_WB * b.w_WB_B;
      const Vec3 v_C = b.v_WBcm_W + w_W.cross(Vec3(0, 0, -kR));
      if (v_C.dot(cs.slip_direction_W) <= 0.0) {
        SelectContactModes(m, s, tol);
        if (cs.mode == ContactMode::kSticking) t_event = s.t;
      }
    }
    v_end = s.bodies[0].v_WBcm_W.norm();
    benchmark::DoNotOptimize(s.bodies.data());
  }
  st.counters["t_star_rel_error"] = std::abs(t_event - TStar(kW0)) / TStar(kW0);
  st.counters["t_star_error_over_h"] = (t_event - TStar(kW0)) / h;
  st.counters["v_end_rel_error"] = std::abs(v_end - RollingSpeed(kW0)) / RollingSpeed(kW0);
  st.counters["steps"] = static_cast<double>(n_steps);
  st.counters["evaluations"] = static_cast<double>(4 * n_steps);
}
BENCHMARK(SpinningBallFixedStepRk4)->DenseRange(3, 6)->Unit(benchmark::kMicrosecond);

// --- (b) many balls -----------------------------------------------------------------------

// n balls, event-driven to after the last stick, range(1) = 1: every ball its own t* (n
// events, n restarts of the one global integrator); 0: all the same t* (one event). Time per
// simulated second, events per second and the worst t* error as counters.
void SpinningBalls(benchmark::State& st) {
  const int n = static_cast<int>(st.range(0));
  const bool spread = st.range(1) != 0;
  const Model m = MakeBalls(n);
  const State s0 = MakeSpinningBalls(m, n, spread);
  const double t_end = 2.1 * TStar(kW0);
  SimulationOptions o = EventDrivenOptions(t_end);
  o.adaptive.rtol = 1e-10;
  o.adaptive.atol = 1e-12;
  double worst = 0;
  size_t stick_events = 0;
  IntegratorStats stats;
  for (auto _ : st) {
    try {
      const SimulationResult r = Simulate(m, s0, o);
      stick_events = 0;
      for (const ContactEvent& e : r.contact_events) {
        if (e.to != ContactMode::kSticking || e.from != ContactMode::kSliding) continue;
        ++stick_events;
        const double t = TStar(SpinOf(e.point, n, spread));
        worst = std::max(worst, std::abs(e.t - t) / t);
      }
      stats = r.stats;
    } catch (const InputError& e) {
      st.SkipWithError(e.what());
      return;
    }
  }
  st.counters["stick_events"] = static_cast<double>(stick_events);
  st.counters["worst_t_star_rel_error"] = worst;
  st.counters["steps"] = static_cast<double>(stats.steps);
  st.counters["evaluations"] = static_cast<double>(stats.function_evaluations);
  st.counters["simulated_s"] = t_end;
  // Wall (CPU) seconds per simulated second: the inverse of simulated seconds per second.
  st.counters["cpu_s_per_simulated_s"] = benchmark::Counter(
      t_end, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}
BENCHMARK(SpinningBalls)
    ->ArgsProduct({{10, 30, 60}, {0, 1}})
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);

// One evaluation of the equations of motion (CalcAccelerations: the contact solve of every
// point, here all sliding) for n balls: the unit of work of both the steps and the restarts.
void SlidingBallsEvaluation(benchmark::State& st) {
  const int n = static_cast<int>(st.range(0));
  const Model m = MakeBalls(n);
  State s = MakeSpinningBalls(m, n, true);
  SelectContactModes(m, s);
  Data data = MakeData(m);
  for (auto _ : st) {
    CalcAccelerations(m, s, data);
    benchmark::DoNotOptimize(data.contact_points.data());
  }
  st.counters["bodies"] = n;
}
BENCHMARK(SlidingBallsEvaluation)->RangeMultiplier(10)->Range(1, 1000);

// The work of one restart beyond the integrator's own: the mode selection of every point
// (SelectContactModes: the normal LCP and the friction checks over all touching points), here
// for n sliding balls of which one has just stopped slipping.
void SlidingBallsModeSelection(benchmark::State& st) {
  const int n = static_cast<int>(st.range(0));
  const Model m = MakeBalls(n);
  State s0 = MakeSpinningBalls(m, n, true);
  SelectContactModes(m, s0);
  // Ball 0 rolling (v = R w): it is tried as sticking.
  SetBodyVelocity(m, 0, Vec3(RollingSpeed(kW0), 0, 0), Vec3(0, RollingSpeed(kW0) / kR, 0), s0);
  for (auto _ : st) {
    State s = s0;
    benchmark::DoNotOptimize(SelectContactModes(m, s).size());
  }
  st.counters["bodies"] = n;
}
BENCHMARK(SlidingBallsModeSelection)->Arg(10)->Arg(30)->Arg(100)->Unit(benchmark::kMicrosecond);

// --- (c) bouncing balls ------------------------------------------------------------------

// n independent balls (R = 2 cm, one sphere-floor contact each, e = 0.5, mu 0.3) dropped from
// rest at staggered heights. While a ball is airborne its point is separated (no rows), so an
// evaluation is O(n) and the contact solve stays empty except at an impact.
constexpr double kBounceR = 0.02;
constexpr double kBounceMass = 0.1;
constexpr double kBounceE = 0.5;
constexpr double kBounceMu = 0.3;
// Drop heights of the lowest point, h_i in [kHLow, kHHigh]. Why not 0.5 m to 1.5 m: with the
// impact times below, ball i accumulates at t_inf = 3 t_0(h_i) (e = 0.5) and makes its third
// impact at 2.5 t_0(h_i); every ball bouncing at least twice before any accumulates needs
// 2.5 t_0(h_max) < 3 t_0(h_min), i.e. h_max / h_min < (6/5)² = 1.44.
constexpr double kHLow = 1.0;
constexpr double kHHigh = 1.4;

// Closed form. The lowest point falls from rest at h: z_C(t) = h - g t²/2 reaches the floor at
// t_0 = sqrt(2 h / g) with speed v_0 = g t_0 = sqrt(2 g h). Newton's law sends the ball up at
// e v_k after impact k; a ballistic flight launched at u lands after 2 u / g with speed u. So
// impact k has approach speed v_k = e^k v_0, the flight before it lasts 2 e^k v_0 / g =
// 2 e^k t_0, and t_k = t_0 (1 + 2 sum_{j=1..k} e^j) = t_0 (1 + 2 e (1 - e^k) / (1 - e)); the
// impacts accumulate at t_inf = t_0 (1 + e) / (1 - e).
double DropTime(double h) {
  return std::sqrt(2 * h / kG);
}
double ImpactTime(double h, int k) {
  return DropTime(h) * (1 + 2 * kBounceE * (1 - std::pow(kBounceE, k)) / (1 - kBounceE));
}
double ImpactSpeed(double h, int k) {
  return std::pow(kBounceE, k) * std::sqrt(2 * kG * h);
}
// h_i spread evenly (offset by half a spacing) so that no two first impacts coincide; later
// impacts c_k t_0(h_i) of different balls meet only by accident (and would then be one
// two-point impact of independent bodies, still exact).
double DropHeight(int i, int n) {
  return kHLow + (kHHigh - kHLow) * (i + 0.5) / n;
}
// The run's end: midway between the highest ball's third impact and the lowest ball's
// accumulation, so every ball bounces 3 to 7 times (the lowest's last flight is 7 ms, far from
// the accumulation threshold of 1e-6 s).
double BounceEndTime() {
  return 0.5 * (ImpactTime(kHHigh, 2) + DropTime(kHLow) * (1 + kBounceE) / (1 - kBounceE));
}
// A short window for the CI's default set: up to the first impact of the ball a third of the
// way up (the lowest third of the balls touch down once each), to show the cost per event at
// n = 1,000 in a few seconds; the full run is 10 times as many events.
double BounceShortEndTime() {
  return DropTime(kHLow + (kHHigh - kHLow) / 3);
}
double BounceEndTime(int64_t window) {
  return window == 0 ? BounceEndTime() : BounceShortEndTime();
}

Model MakeBouncingBalls(int n) {
  Model m;
  const double I = 0.4 * kBounceMass * kBounceR * kBounceR;
  for (int i = 0; i < n; ++i) {
    const int b = m.AddBody(fmt::format("ball{}", i),
                            MassProperties(kBounceMass, Vec3::Zero(), RotationalInertia(I, I, I)));
    ContactSpec c;
    c.name = fmt::format("floor{}", i);
    c.shape = ContactShape::kSphere;
    c.body = b;
    c.radius = kBounceR;
    c.mu_s = kBounceMu;
    c.mu_k = kBounceMu;
    c.restitution = kBounceE;
    m.AddContact(c);
  }
  m.AddForceElement(std::make_shared<UniformGravity>("gravity", Vec3(0, 0, -kG)));
  return m;
}

// Ball i at x = 0.1 i m (apart; independent anyway), at rest with its lowest point at h_i.
State MakeDroppedBalls(const Model& m, int n) {
  State s = MakeRestState(m);
  for (int i = 0; i < n; ++i) {
    SetBodyPose(m, i, Vec3(0.1 * i, 0, DropHeight(i, n) + kBounceR), Quat::Identity(), s);
    SetBodyVelocity(m, i, Vec3::Zero(), Vec3::Zero(), s);
  }
  return s;
}

// Impacts of every ball checked against the closed form, in the order they happen: the k-th
// impact of ball i against t_k(h_i), v_k(h_i).
struct BounceErrors {
  explicit BounceErrors(int n) : n_(n), count_(static_cast<size_t>(n), 0) {}
  void Add(int ball, double t, double approach_speed) {
    const double h = DropHeight(ball, n_);
    const int k = count_[static_cast<size_t>(ball)]++;
    ++impacts;
    t_error = std::max(t_error, std::abs(t - ImpactTime(h, k)));
    if (k == 0) t_error_first = std::max(t_error_first, std::abs(t - ImpactTime(h, k)));
    v_rel_error =
        std::max(v_rel_error, std::abs(approach_speed - ImpactSpeed(h, k)) / ImpactSpeed(h, k));
  }
  // Impacts the closed form has in [0, t_end].
  static long Expected(int n, double t_end) {
    long c = 0;
    for (int i = 0; i < n; ++i) {
      for (int k = 0; ImpactTime(DropHeight(i, n), k) <= t_end; ++k) ++c;
    }
    return c;
  }
  int n_;
  std::vector<int> count_;
  long impacts = 0;
  // Fixed step only: impulses of balls that had not come back above the floor since their
  // previous impact (not a touch-down, not in the closed form), see below.
  long below_floor = 0;
  // Largest time error over all impacts and over the first impacts only (the later ones
  // inherit the errors of the earlier bounces).
  double t_error = 0, t_error_first = 0, v_rel_error = 0;
};

void SetBounceCounters(benchmark::State& st, int n, double t_end, const BounceErrors& err) {
  st.counters["balls"] = n;
  st.counters["simulated_s"] = t_end;
  st.counters["impacts"] = static_cast<double>(err.impacts);
  st.counters["impacts_expected"] = static_cast<double>(BounceErrors::Expected(n, t_end));
  st.counters["impacts_per_s"] =
      benchmark::Counter(static_cast<double>(err.impacts), benchmark::Counter::kIsRate);
  st.counters["max_t_error_s"] = err.t_error;
  st.counters["max_v_rel_error"] = err.v_rel_error;
  st.counters["impacts_below_floor"] = static_cast<double>(err.below_floor);
  st.counters["cpu_s_per_simulated_s"] = benchmark::Counter(
      t_end, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

// Event-driven: Simulate locates every touch-down on the dense output (1e-12 s), resolves the
// impact there, re-selects the modes of all points and restarts the one global integrator.
// range(1) = 0: the full run to BounceEndTime(); 1: the short window.
void BouncingBallsEventDriven(benchmark::State& st) {
  const int n = static_cast<int>(st.range(0));
  const Model m = MakeBouncingBalls(n);
  const State s0 = MakeDroppedBalls(m, n);
  const double t_end = BounceEndTime(st.range(1));
  const SimulationOptions o = EventDrivenOptions(t_end);
  BounceErrors err(n);
  IntegratorStats stats;
  long accumulations = 0;
  for (auto _ : st) {
    try {
      const SimulationResult r = Simulate(m, s0, o);
      err = BounceErrors(n);
      accumulations = 0;
      for (const ImpactRecord& rec : r.impacts) {
        err.Add(rec.point, rec.t, rec.approach_speed);
        accumulations += rec.accumulation ? 1 : 0;
      }
      stats = r.stats;
      benchmark::DoNotOptimize(r.final_state.bodies.data());
    } catch (const InputError& e) {
      st.SkipWithError(e.what());
      return;
    }
  }
  SetBounceCounters(st, n, t_end, err);
  st.counters["accumulations"] = static_cast<double>(accumulations);
  st.counters["steps"] = static_cast<double>(stats.steps);
  st.counters["evaluations"] = static_cast<double>(stats.function_evaluations);
}
BENCHMARK(BouncingBallsEventDriven)
    ->Args({10, 0})
    ->Args({100, 0})
    ->Args({100, 1})
    ->Args({1000, 1})
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);

// Fixed step, the way a time-stepping engine treats impacts: RK4 at h = 10^-range(1) s on the
// same Model (every point separated: free flight), and at the end of each step in which a
// ball's gap went negative while it approaches the floor, ResolveImpacts on that state (the
// ball slightly inside the floor, its approach speed the one it has there). The impact time
// is the end of that step, so it is late by up to h; the ball leaves from below the floor, so
// the later flights carry errors of order h too. After the impulse the ball moves away and
// stays separated (no mode selection needed). A slow ball can fail to climb back out: its
// rebound e v from the depth d ~ v h below the floor does not lift it by d when (e v)² < 2 g d,
// so it comes down again still below the floor and is struck again (a time-stepping engine
// without position correction sinks such a ball). Those impulses, of balls whose gap was
// already negative at the step's start, are counted as impacts_below_floor and are not
// compared with the closed form; only touch-downs (gap >= 0 at the step's start) are.
void BouncingBallsFixedStepRk4(benchmark::State& st) {
  const int n = static_cast<int>(st.range(0));
  const double h = std::pow(10.0, -static_cast<double>(st.range(1)));
  const Model m = MakeBouncingBalls(n);
  State s0 = MakeDroppedBalls(m, n);
  SelectContactModes(m, s0);  // all separated
  const double t_end = BounceEndTime();
  const auto n_steps = static_cast<long>(std::ceil(t_end / h - 1e-9));
  Rk4Integrator rk4(m);
  BounceErrors err(n);
  std::vector<double> gap_start(static_cast<size_t>(n));
  for (auto _ : st) {
    State s = s0;
    err = BounceErrors(n);
    for (long j = 0; j < n_steps; ++j) {
      for (int i = 0; i < n; ++i) {
        gap_start[static_cast<size_t>(i)] = s.bodies[static_cast<size_t>(i)].p_WBcm.z() - kBounceR;
      }
      rk4.Step(s, h);
      bool touched = false;
      for (const BodyState& b : s.bodies) {
        touched = touched || (b.p_WBcm.z() - kBounceR < 0.0 && b.v_WBcm_W.z() < 0.0);
      }
      if (!touched) continue;
      for (const ContactImpulse& ci : ResolveImpacts(m, s).impulses) {
        if (gap_start[static_cast<size_t>(ci.point)] < 0.0) {
          ++err.below_floor;
        } else {
          err.Add(ci.point, s.t, ci.approach_speed);
        }
      }
    }
    benchmark::DoNotOptimize(s.bodies.data());
  }
  SetBounceCounters(st, n, t_end, err);
  st.counters["max_t_error_over_h"] = err.t_error / h;
  st.counters["max_first_t_error_over_h"] = err.t_error_first / h;
  st.counters["steps"] = static_cast<double>(n_steps);
  st.counters["evaluations"] = static_cast<double>(4 * n_steps);
}
BENCHMARK(BouncingBallsFixedStepRk4)
    ->Args({10, 3})
    ->Args({10, 4})
    ->Args({10, 5})
    ->Args({100, 3})
    ->Args({100, 4})
    ->Args({1000, 3})
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);

// --- (d) islands ----------------------------------------------------------------------------

// n spinning balls, each its own w0 = w0 (1 + i/n) (n separate stick events), event-driven to
// 2 t* of the fastest: Simulate splits them into n islands (range(1) threads). The reference,
// timed in the same run, is the plain loop of n one-ball Simulates to the same end time; the
// ratio of the two is a counter (the acceptance: within 1.5).
void SpinningBallsIslands(benchmark::State& st) {
  using Clock = std::chrono::steady_clock;
  const int n = static_cast<int>(st.range(0));
  const Model m = MakeBalls(n);
  const State s0 = MakeSpinningBalls(m, n, true);
  SimulationOptions o = EventDrivenOptions(2 * TStar(SpinOf(n - 1, n, true)));
  o.islands = true;
  o.threads = static_cast<int>(st.range(1));
  const Model one = MakeBalls(1);
  std::vector<State> singles;
  for (int i = 0; i < n; ++i) {
    State s = MakeSpinningBalls(one, 1, false);
    SetBodyVelocity(one, 0, Vec3::Zero(), Vec3(0, SpinOf(i, n, true), 0), s);
    singles.push_back(s);
  }
  double worst = 0, v_worst = 0, seconds = 0, reference_seconds = 0;
  std::int64_t stick_events = 0, islands = 0;
  for (auto _ : st) {
    try {
      const Clock::time_point t0 = Clock::now();
      const SimulationResult r = Simulate(m, s0, o);
      const Clock::time_point t1 = Clock::now();
      SimulationOptions o1 = o;
      o1.threads = 1;
      for (const State& s : singles) benchmark::DoNotOptimize(Simulate(one, s, o1).stats.steps);
      st.SetIterationTime(std::chrono::duration<double>(t1 - t0).count());
      seconds += std::chrono::duration<double>(t1 - t0).count();
      reference_seconds += std::chrono::duration<double>(Clock::now() - t1).count();
      stick_events = 0;
      for (const ContactEvent& e : r.contact_events) {
        if (e.to != ContactMode::kSticking || e.from != ContactMode::kSliding) continue;
        ++stick_events;
        const double t = TStar(SpinOf(e.point, n, true));
        worst = std::max(worst, std::abs(e.t - t) / t);
      }
      for (int i = 0; i < n; ++i) {
        const double v = RollingSpeed(SpinOf(i, n, true));
        v_worst = std::max(
            v_worst,
            std::abs(r.final_state.bodies[static_cast<size_t>(i)].v_WBcm_W.norm() - v) / v);
      }
      islands = r.islands.split ? r.islands.count : 1;
    } catch (const InputError& e) {
      st.SkipWithError(e.what());
      return;
    }
  }
  st.counters["islands"] = static_cast<double>(islands);
  st.counters["stick_events"] = static_cast<double>(stick_events);
  st.counters["worst_t_star_rel_error"] = worst;
  st.counters["worst_v_end_rel_error"] = v_worst;
  st.counters["cost_over_n_one_ball_runs"] = seconds / reference_seconds;
}
BENCHMARK(SpinningBallsIslands)
    ->Args({1000, 1})
    ->Args({1000, 2})
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3);

// Time stepping over islands on threads: n pyramids of four balls (three touching in a
// triangle, one nested on them; friction 0.5 everywhere, each pyramid's six pairs listed) set
// 0.5 mm above the floor, 0.2 s at 1 ms with the step-doubling estimate. Every pyramid is an
// island at every step, so the contact problems share out over the threads; the run is bitwise
// the same for any number (tests/unit/integrate/time_stepping_test.cpp). Counter: body-steps
// per second of wall time (n × 4 × 200 steps).
void SteppingPiles(benchmark::State& st) {
  const int piles = static_cast<int>(st.range(0));
  const reference::Ball ball{0.17, 0.028575, 0.5, 0.5};
  Model m = reference::MakeBallsOnFloor(4 * piles, ball, 9.81);
  for (int k = 0; k < piles; ++k) {
    for (int i = 0; i < 4; ++i) {
      for (int j = i + 1; j < 4; ++j) {
        ContactSpec c;
        c.name = fmt::format("pile{}_pair{}{}", k, i, j);
        c.shape = ContactShape::kSphereSphere;
        c.body = 4 * k + i;
        c.other_body = 4 * k + j;
        c.radius = c.other_radius = ball.radius;
        c.mu_s = c.mu_k = 0.5;
        m.AddContact(c);
      }
    }
  }
  State s = MakeRestState(m);
  const double R = ball.radius, d = 2 * R / std::sqrt(3.0), lift = 0.5e-3;
  const int side = static_cast<int>(std::ceil(std::sqrt(piles)));
  for (int k = 0; k < piles; ++k) {
    const Vec3 c(0.2 * (k % side), 0.2 * (k / side), 0.0);
    for (int i = 0; i < 3; ++i) {
      const double a = 2 * M_PI * i / 3;
      SetBodyPose(m, 4 * k + i, c + Vec3(d * std::cos(a), d * std::sin(a), R + lift),
                  Quat::Identity(), s);
    }
    SetBodyPose(m, 4 * k + 3, c + Vec3(0, 0, R + lift + std::sqrt(4 * R * R - d * d)),
                Quat::Identity(), s);
    for (int i = 0; i < 4; ++i) SetBodyVelocity(m, 4 * k + i, Vec3::Zero(), Vec3::Zero(), s);
  }
  TimeSteppingOptions o;
  o.t_end = 0.2;
  o.step = 1e-3;
  o.threads = static_cast<int>(st.range(1));
  o.store_samples = false;
  double penetration = 0.0;
  for (auto _ : st) {
    const TimeSteppingResult r = SimulateTimeStepping(m, s, o);
    penetration = r.summary.max_penetration;
  }
  st.counters["body_steps_per_s"] = benchmark::Counter(
      4.0 * piles * 200.0 * static_cast<double>(st.iterations()), benchmark::Counter::kIsRate);
  st.counters["max_penetration_m"] = penetration;
}
BENCHMARK(SteppingPiles)
    ->Args({100, 1})
    ->Args({100, 2})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

// The peers' sphere grid, time stepped with every pair of balls able to collide
// (TimeSteppingOptions::collide_all_pairs, no pair listed): n solid spheres of R = 0.1 m and
// 1 kg in columns on a square grid 0.25 m apart, layers 0.25 m apart from z = 0.2 m up (each
// sphere off its place by up to 2 cm across, seeded), dropped at rest onto the floor and onto
// each other; friction mu = 0.5 between the spheres and with the floor, restitution 0; 1 s at
// h = 1 ms on one thread, arg 1 the step-doubling estimate (1: three contact solves per step and
// the accumulated error estimate; 0: one). Counter: body-steps per CPU second (n × 1000 per
// run) and its ratio to ODE's 0.94 M; the run's certificate.
void SteppingSphereGrid(benchmark::State& st) {
  const int n = static_cast<int>(st.range(0));
  const reference::Ball ball{1.0, 0.1, 0.5, 0.5};
  const Model m = reference::MakeBallsOnFloor(n, ball, 9.81);
  State s = MakeRestState(m);
  const int side = n >= 1000 ? 10 : 5;
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> jitter(-0.02, 0.02);
  for (int i = 0; i < n; ++i) {
    const int layer = i / (side * side), k = i % (side * side);
    const Vec3 p(0.25 * (k % side) + jitter(rng), 0.25 * (k / side) + jitter(rng),
                 0.2 + 0.25 * layer);
    SetBodyPose(m, i, p, Quat::Identity(), s);
    SetBodyVelocity(m, i, Vec3::Zero(), Vec3::Zero(), s);
  }
  TimeSteppingOptions o;
  o.t_end = 1.0;
  o.step = 1e-3;
  o.store_samples = false;
  o.error_estimate = st.range(1) != 0;
  o.collide_all_pairs = true;
  o.pair_law = {0.0, 0.5, 0.5, RestitutionLaw::kNewton};
  TimeSteppingSummary c;
  for (auto _ : st) c = SimulateTimeStepping(m, s, o).summary;
  const double rate = static_cast<double>(n) * 1000.0;
  st.counters["body_steps_per_s"] =
      benchmark::Counter(rate * static_cast<double>(st.iterations()), benchmark::Counter::kIsRate);
  st.counters["x_ODE"] = benchmark::Counter(rate * static_cast<double>(st.iterations()) / 0.94e6,
                                            benchmark::Counter::kIsRate);
  st.counters["max_residual_Ns"] = c.max_residual_impulse;
  st.counters["max_residual_m_per_s"] = c.max_residual_velocity;
  st.counters["max_penetration_m"] = c.max_penetration;
  st.counters["accumulated_dv_m_per_s"] = c.accumulated_velocity_error;
  st.counters["largest_problem"] = c.largest_island;
}
BENCHMARK(SteppingSphereGrid)
    ->Args({100, 1})
    ->Args({100, 0})
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);

}  // namespace
}  // namespace chasles

// The spinning runs with 100 balls and more take seconds to minutes (the contact solve is one
// dense system over all bodies, docs/contact.md "Limits"); the full event-driven bouncing run
// of 1,000 balls and the fixed-step ones with 100 balls at 10 us and 1,000 balls at 0.1 ms and
// 10 us take seconds to a minute: too long for the CI's smoke run, they are registered only
// when CHASLES_CONTACT_BENCH_LARGE is set.
int main(int argc, char** argv) {
  if (std::getenv("CHASLES_CONTACT_BENCH_LARGE") != nullptr) {
    benchmark::RegisterBenchmark("SteppingSphereGrid", chasles::SteppingSphereGrid)
        ->Args({1000, 1})
        ->Args({1000, 0})
        ->Unit(benchmark::kMillisecond)
        ->Iterations(1);
    benchmark::RegisterBenchmark("SpinningBalls", chasles::SpinningBalls)
        ->Args({100, 0})
        ->Args({100, 1})
        ->Args({200, 1})
        ->Args({1000, 0})
        ->Unit(benchmark::kMillisecond)
        ->Iterations(1);
    benchmark::RegisterBenchmark("BouncingBallsEventDriven", chasles::BouncingBallsEventDriven)
        ->Args({1000, 0})
        ->Unit(benchmark::kMillisecond)
        ->Iterations(1);
    benchmark::RegisterBenchmark("BouncingBallsFixedStepRk4", chasles::BouncingBallsFixedStepRk4)
        ->Args({100, 5})
        ->Args({1000, 4})
        ->Args({1000, 5})
        ->Unit(benchmark::kMillisecond)
        ->Iterations(1);
  }
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
