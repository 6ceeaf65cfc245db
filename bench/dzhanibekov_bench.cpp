// Orientation error and cost of integrating the Dzhanibekov body (principal moments
// (1, 2, 3) kg·m², ω₀ = (0.01, 10, 0.01) rad/s, no force) for 100 s, against a plain
// hand-written double RK4 loop at h = 1e-3 s (100,000 steps) timed in the same run.
//
// Reference: the same equations — Euler's equations (chapter eq. 8.62) with M = 0 in the body
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

namespace chasles {
namespace {

constexpr double kI[3] = {1.0, 2.0, 3.0};
constexpr double kW0[3] = {0.01, 10.0, 0.01};
constexpr double kDuration = 100.0;

template <typename T>
struct Top {
  T y[7];  // ω (3), q (w, x, y, z)
};

template <typename T>
Top<T> Derivative(const Top<T>& s) {
  const T* w = s.y;
  const T* q = s.y + 3;
  const T I0 = kI[0], I1 = kI[1], I2 = kI[2];
  Top<T> d;
  d.y[0] = (I1 - I2) * w[1] * w[2] / I0;
  d.y[1] = (I2 - I0) * w[2] * w[0] / I1;
  d.y[2] = (I0 - I1) * w[0] * w[1] / I2;
  d.y[3] = T(-0.5) * (q[1] * w[0] + q[2] * w[1] + q[3] * w[2]);
  d.y[4] = T(0.5) * (q[0] * w[0] + q[2] * w[2] - q[3] * w[1]);
  d.y[5] = T(0.5) * (q[0] * w[1] + q[3] * w[0] - q[1] * w[2]);
  d.y[6] = T(0.5) * (q[0] * w[2] + q[1] * w[1] - q[2] * w[0]);
  return d;
}

template <typename T>
Top<T> PlainRk4(T h, long n) {
  Top<T> s{{T(kW0[0]), T(kW0[1]), T(kW0[2]), T(1), T(0), T(0), T(0)}};
  const auto axpy = [](const Top<T>& a, T c, const Top<T>& k) {
    Top<T> r;
    for (int i = 0; i < 7; ++i) r.y[i] = a.y[i] + c * k.y[i];
    return r;
  };
  for (long step = 0; step < n; ++step) {
    const Top<T> k1 = Derivative(s);
    const Top<T> k2 = Derivative(axpy(s, h / 2, k1));
    const Top<T> k3 = Derivative(axpy(s, h / 2, k2));
    const Top<T> k4 = Derivative(axpy(s, h, k3));
    for (int i = 0; i < 7; ++i) s.y[i] += h / 6 * (k1.y[i] + 2 * (k2.y[i] + k3.y[i]) + k4.y[i]);
    const T norm = std::sqrt(s.y[3] * s.y[3] + s.y[4] * s.y[4] + s.y[5] * s.y[5] + s.y[6] * s.y[6]);
    for (int i = 3; i < 7; ++i) s.y[i] /= norm;
  }
  return s;
}

template <typename A, typename B>
double Angle(const Top<A>& ra, const Top<B>& rb) {
  long double a[4], b[4];
  for (int i = 0; i < 4; ++i) a[i] = ra.y[3 + i], b[i] = rb.y[3 + i];
  const long double w = a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + a[3] * b[3];
  const long double x = a[0] * b[1] - a[1] * b[0] - a[2] * b[3] + a[3] * b[2];
  const long double y = a[0] * b[2] + a[1] * b[3] - a[2] * b[0] - a[3] * b[1];
  const long double z = a[0] * b[3] - a[1] * b[2] + a[2] * b[1] - a[3] * b[0];
  return static_cast<double>(2 * std::atan2(std::sqrt(x * x + y * y + z * z), std::fabs(w)));
}

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

Top<double> FromState(const State& s) {
  const BodyState& b = s.bodies[0];
  return {
      {b.w_WB_B.x(), b.w_WB_B.y(), b.w_WB_B.z(), b.q_WB.w(), b.q_WB.x(), b.q_WB.y(), b.q_WB.z()}};
}

Model Body() {
  Model m;
  m.AddBody("top", MassProperties(1.0, Vec3::Zero(), RotationalInertia(kI[0], kI[1], kI[2])));
  return m;
}

State Start(const Model& m) {
  State s = MakeRestState(m);
  s.bodies[0].w_WB_B = Vec3(kW0[0], kW0[1], kW0[2]);
  return s;
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
  const Model m = Body();
  const double h = static_cast<double>(st.range(0)) * 1e-6;
  const auto n = static_cast<long>(std::lround(kDuration / h));
  State s;
  Clock clock;
  for (auto _ : st) {
    clock.Start();
    s = Start(m);
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
  const Model m = Body();
  AdaptiveOptions o;
  o.rtol = static_cast<double>(st.range(0)) * 1e-14;
  o.atol = o.rtol * 1e-2;
  State s;
  long steps = 0;
  Clock clock;
  for (auto _ : st) {
    clock.Start();
    DormandPrince5Integrator dp(m, o);
    dp.Initialize(Start(m));
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
