// A break shot on a large table: a cue ball rolling into a triangle of balls, n = 100 to
// 1,000 in all, every pair free to collide, run event-driven (chasles/integrate/sphere_events.h)
// for 10 s of simulated time. Pool balls (R = 28.575 mm, m = 0.17 kg) on cloth (mu_s = 0.25,
// mu_k = 0.2, rolling resistance mu_r = 0.01), ball-ball restitution 0.93, frictionless,
// the rack's balls 0.1 mm apart (each off its place by up to 25 µm), the cue ball at 10 m/s
// rolling.
//
// Time-stepping engines are measured in body-steps per second: bodies × steps / wall time. An
// event-driven run takes no steps; its figure here counts the steps a time-stepping engine
// needs for the same simulated time at 1 ms (the step ODE was measured with), bodies × T / 1 ms,
// so "body-steps/s" = n T / (1 ms × wall time): the same work, in the same units. Counters: the
// impacts, phase changes and pair tests, and the run's own energy balance (its residual relative
// to the initial energy). docs/benchmarks.md, "Break shot".

#include <cmath>
#include <random>

#include <benchmark/benchmark.h>

#include "chasles/error.h"
#include "chasles/integrate/sphere_events.h"
#include "reference/balls_on_floor.h"

namespace chasles {
namespace {

constexpr double kG = 9.80665;
constexpr double kR = 0.028575;
constexpr double kT = 10.0;
constexpr double kStep = 1e-3;

struct Shot {
  Model model;
  State state;
};

Shot MakeShot(int n) {
  const reference::Ball ball{0.17, kR, 0.25, 0.2, 0.01};
  Model model = reference::MakeBallsOnFloor(n, ball, kG);
  State s = MakeRestState(model);
  // A real rack is not a perfect lattice: each ball off its place by up to 25 µm (seeded), so
  // no two hits are exactly simultaneous.
  const double pitch = 2 * kR + 1e-4;
  std::mt19937_64 rng(2026);
  std::uniform_real_distribution<double> jitter(-25e-6, 25e-6);
  int k = 1;
  for (int row = 0; k < n; ++row) {
    for (int j = 0; j <= row && k < n; ++j, ++k) {
      SetBodyPose(model, k,
                  Vec3(1.0 + row * pitch * std::sqrt(3.0) / 2 + jitter(rng),
                       (j - row / 2.0) * pitch + jitter(rng), kR),
                  Quat::Identity(), s);
      SetBodyVelocity(model, k, Vec3::Zero(), Vec3::Zero(), s);
    }
  }
  SetBodyPose(model, 0, Vec3(0, 0.001, kR), Quat::Identity(), s);
  SetBodyVelocity(model, 0, Vec3(10, 0, 0), Vec3(0, 10 / kR, 0), s);
  return {std::move(model), std::move(s)};
}

// n balls on a square lattice 0.16 m apart (each off its place by up to 5 cm), rolling at up to
// 2 m/s in random directions, some with side spin (seeded): a table of balls colliding at
// random.
Shot MakeScatter(int n) {
  Shot shot = MakeShot(n);
  const int side = static_cast<int>(std::ceil(std::sqrt(n)));
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  for (int k = 0; k < n; ++k) {
    const Vec3 p(0.16 * (k % side) + 0.05 * U(rng), 0.16 * (k / side) + 0.05 * U(rng), kR);
    const Vec3 v(2.0 * U(rng), 2.0 * U(rng), 0.0);
    SetBodyPose(shot.model, k, p, Quat::Identity(), shot.state);
    SetBodyVelocity(shot.model, k, v, Vec3(-v.y() / kR, v.x() / kR, 20.0 * U(rng)), shot.state);
  }
  return shot;
}

void Run(benchmark::State& st, const Shot& shot) {
  const int n = shot.model.num_bodies();
  SphereEventOptions o;
  o.t_end = kT;
  o.collide_all_pairs = true;
  o.pair_law = {0.93, 0.0, 0.0, RestitutionLaw::kEnergetic};
  SphereEventResult r;
  for (auto _ : st) {
    try {
      r = SimulateSphereEvents(shot.model, shot.state, o);
    } catch (const InputError& e) {
      st.SkipWithError(e.what());
      return;
    }
    benchmark::DoNotOptimize(r.final_state.bodies.data());
  }
  st.counters["body_steps_per_s"] =
      benchmark::Counter(n * kT / kStep, benchmark::Counter::kIsIterationInvariantRate);
  st.counters["impacts"] = static_cast<double>(r.stats.impacts);
  st.counters["collisions"] = static_cast<double>(r.collisions.size());
  st.counters["landings"] = static_cast<double>(r.plane_impacts.size());
  st.counters["phase_events"] = static_cast<double>(r.stats.phase_events);
  st.counters["pair_tests"] = static_cast<double>(r.stats.pair_tests);
  st.counters["groups"] = static_cast<double>(r.stats.groups);
  st.counters["group_windows"] = static_cast<double>(r.stats.group_windows);
  st.counters["energy_residual"] = std::abs(r.energy.residual) / r.energy.initial;
  st.counters["energy_left"] = r.energy.final / r.energy.initial;
}

void BreakShot(benchmark::State& st) {
  Run(st, MakeShot(static_cast<int>(st.range(0))));
}
void Scattered(benchmark::State& st) {
  Run(st, MakeScatter(static_cast<int>(st.range(0))));
}

BENCHMARK(Scattered)->Arg(100)->Arg(300)->Arg(1000)->Unit(benchmark::kMillisecond);
// Part of the tight rack presses together in groups stepped by the hybrid engine
// (docs/contact.md, "Tight racks"): 0.67 s for 100 balls; at 200 the rack squeezes into groups
// of 70 balls and more whose regimes change hundreds of times per millisecond (a 2 ms window
// takes 42 s), so only 100 is registered.
BENCHMARK(BreakShot)->Arg(100)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace chasles

BENCHMARK_MAIN();
