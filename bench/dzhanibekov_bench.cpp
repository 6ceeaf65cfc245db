// Orientation error and cost of integrating the Dzhanibekov body (principal moments
// (1, 2, 3) kg·m², ω₀ = (0.01, 10, 0.01) rad/s, no force) for 100 s, against a plain
// hand-written double RK4 loop at h = 1e-3 s (100,000 steps) timed in the same run.
//
// Reference: the same equations — Euler's equations (chapter eqs. 8.79-8.81) with M = 0 in the body
// frame, q̇ = ½ q ⊗ (0, ω) — integrated in long double (64-bit significand) by classical RK4 at
// h = 1e-4 s (1,000,000 steps; truncation error (1e-4/1e-3)⁴ = 1e-4 of the h = 1e-3 run's) with
// the quaternion renormalised each step. The reference is also run at h = 2e-4 s; the counter
// ref_check is the angle between the two, a bound on the reference's own error (RK4: the
// h = 1e-4 run is 16 times closer than that).
//
// Counters: err_rad = angle between the run's final orientation and the reference's;
// time_ratio = the run's CPU time over the plain loop's (best of three runs of the loop, timed in
// the same process before the first benchmark).

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>

#include <benchmark/benchmark.h>

#include "chasles/integrate/dormand_prince.h"
#include "chasles/integrate/rk4.h"
#include "chasles/model/model.h"
#include "reference/torque_free_top.h"

namespace chasles {
namespace {

using reference::Angle;
using reference::FromState;
using reference::PlainRk4;
using reference::Top;

constexpr double kDuration = 100.0;

const Top<long double>& Reference() {
  static const Top<long double> ref = PlainRk4<long double>(1e-4L, 1000000);
  return ref;
}

// This thread's CPU time [s] (the machine is shared: wall time would count other jobs).
double CpuSeconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

// CPU seconds of one run of the plain double loop, 100,000 steps of 1e-3 s (best of three).
double PlainSeconds() {
  static const double seconds = [] {
    double best = 1e9;
    for (int r = 0; r < 3; ++r) {
      const double t0 = CpuSeconds();
      const Top<double> s = PlainRk4<double>(1e-3, 100000);
      benchmark::DoNotOptimize(s);
      best = std::min(best, CpuSeconds() - t0);
    }
    return best;
  }();
  return seconds;
}

// CPU seconds per iteration of a benchmark loop, from its own clock.
class Clock {
 public:
  void Start() { t0_ = CpuSeconds(); }
  void Stop() {
    total_ += CpuSeconds() - t0_;
    ++runs_;
  }
  double per_run() const { return total_ / runs_; }

 private:
  double t0_ = 0.0;
  double total_ = 0.0;
  int runs_ = 0;
};

void Report(benchmark::State& st, double err, const Clock& clock) {
  st.counters["err_rad"] = err;
  st.counters["time_ratio"] = clock.per_run() / PlainSeconds();
}

void PlainLoop(benchmark::State& st) {
  Reference();
  Top<double> s{};
  Clock clock;
  for (auto _ : st) {
    clock.Start();
    s = PlainRk4<double>(1e-3, 100000);
    benchmark::DoNotOptimize(s);
    clock.Stop();
  }
  Report(st, Angle(Reference(), s), clock);
  st.counters["ref_check"] = Angle(Reference(), PlainRk4<long double>(2e-4L, 500000));
}

// chasles' RK4 (compensated updates) at h = range(0) microseconds.
void ChaslesRk4(benchmark::State& st) {
  Reference();
  const Model m = reference::DzhanibekovModel();
  const double h = static_cast<double>(st.range(0)) * 1e-6;
  const auto n = static_cast<long>(std::lround(kDuration / h));
  State s;
  Clock clock;
  for (auto _ : st) {
    clock.Start();
    s = reference::DzhanibekovStart(m);
    Rk4Integrator rk4(m);
    for (long i = 0; i < n; ++i) rk4.Step(s, h);
    benchmark::DoNotOptimize(s.bodies.data());
    clock.Stop();
  }
  Report(st, Angle(Reference(), FromState(s)), clock);
}

// chasles' Dormand–Prince 5(4) (compensated updates) at rtol = range(0) · 1e-14, atol = rtol/100.
void ChaslesDormandPrince(benchmark::State& st) {
  Reference();
  const Model m = reference::DzhanibekovModel();
  AdaptiveOptions o;
  o.rtol = static_cast<double>(st.range(0)) * 1e-14;
  o.atol = o.rtol * 1e-2;
  State s;
  long steps = 0;
  Clock clock;
  for (auto _ : st) {
    clock.Start();
    DormandPrince5Integrator dp(m, o);
    dp.Initialize(reference::DzhanibekovStart(m));
    while (dp.state().t < kDuration) dp.Step(kDuration);
    s = dp.state();
    steps = dp.stats().steps;
    benchmark::DoNotOptimize(s.bodies.data());
    clock.Stop();
  }
  Report(st, Angle(Reference(), FromState(s)), clock);
  st.counters["steps"] = static_cast<double>(steps);
}

BENCHMARK(PlainLoop)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK(ChaslesRk4)->Arg(1000)->Arg(500)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK(ChaslesDormandPrince)
    ->Arg(100)
    ->Arg(50)
    ->Arg(30)
    ->Arg(10)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3);

}  // namespace
}  // namespace chasles

BENCHMARK_MAIN();
