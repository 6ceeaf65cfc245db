// Contacts: the spinning ball of Problems 8.26/8.27 set down on a floor (sliding ends at
// t* = 2 R w0 / (7 mu_k g), then it rolls at v = 2/7 R w0), run
//  - event-driven: the engine's hybrid Simulate, the stick event located on the Dormand-Prince
//    dense output;
//  - fixed-step: the engine's own RK4 on the same Model, the way time-stepping engines treat
//    friction: the mode is held over each step and switched at the end of the step in which
//    the slip changed sign (the velocities then projected onto rolling by the contact impulse,
//    SelectContactModes), so the stick time is found to within one step;
// and many spinning balls on one floor, event-driven, to show how the cost grows with the
// number of bodies when one global integrator restarts at every event. Benchmarks never
// assert; the errors are counters. Results and the commands: docs/benchmarks.md.

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include <benchmark/benchmark.h>
#include <fmt/format.h>

#include "chasles/dynamics/contact_solve.h"
#include "chasles/dynamics/newton_euler.h"
#include "chasles/error.h"
#include "chasles/integrate/rk4.h"
#include "chasles/integrate/simulate.h"
#include "chasles/model/contact.h"
#include "chasles/model/data.h"
#include "chasles/model/forces.h"
#include "chasles/model/model.h"

namespace chasles {
namespace {

constexpr double kG = 9.80665;
constexpr double kR = 0.028575;  // 9/8 in
constexpr double kMass = 0.17;
constexpr double kMuK = 0.35;
constexpr double kW0 = 100 * 2 * M_PI / 60;  // 100 rpm

// Problem 8.26: sliding friction mu_k m g gives v̇ = mu_k g and ẇ = -5 mu_k g / (2 R); the
// slip R w - v falls at 7/2 mu_k g and reaches zero at t* = 2 R w0 / (7 mu_k g).
double TStar(double w0) {
  return 2 * kR * w0 / (7 * kMuK * kG);
}
// Problem 8.27: the angular momentum about the contact point, I w0 = (I + m R²) v / R, is kept
// (friction acts at that point), so the ball rolls on at v = 2/7 R w0.
double RollingSpeed(double w0) {
  return 2.0 / 7.0 * kR * w0;
}

Model MakeBalls(int n) {
  Model m;
  const double I = 0.4 * kMass * kR * kR;
  for (int i = 0; i < n; ++i) {
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
  return m;
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

}  // namespace
}  // namespace chasles

// The runs with 100 balls and more take seconds to minutes (the contact solve is one dense
// system over all bodies, docs/contact.md "Limits"), too long for the CI's smoke run: they are
// registered only when CHASLES_CONTACT_BENCH_LARGE is set.
int main(int argc, char** argv) {
  if (std::getenv("CHASLES_CONTACT_BENCH_LARGE") != nullptr) {
    benchmark::RegisterBenchmark("SpinningBalls", chasles::SpinningBalls)
        ->Args({100, 0})
        ->Args({100, 1})
        ->Args({200, 1})
        ->Args({1000, 0})
        ->Unit(benchmark::kMillisecond)
        ->Iterations(1);
  }
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
