// Throughput of the structure-of-arrays free-body batch (chasles/integrate/free_body_batch.h)
// on 10,000 bodies with moments of inertia differing per body, generic spin and uniform
// gravity, in body-steps per second, against a plain reference loop timed in the same run: an
// array of per-body structs stepped by a hand-written RK4 (the same equations, q renormalised
// once per step), and the engine's Rk4Integrator. Errors are reported as counters (benchmarks
// never assert): the largest |q| − 1 and the largest relative change of |L_W| over the run.
// SimulateRk4 times Simulate's run of the same bodies beside the batch's Advance.

#include <cmath>
#include <random>
#include <vector>

#include <benchmark/benchmark.h>
#include <fmt/format.h>

#include "chasles/integrate/free_body_batch.h"
#include "chasles/integrate/rk4.h"
#include "chasles/integrate/run_path.h"
#include "chasles/integrate/simulate.h"
#include "chasles/model/forces.h"
#include "chasles/model/model.h"

namespace chasles {
namespace {

constexpr double kH = 1e-3;

/// n bodies: moments 1 + U(0, 1), 1.5 + U(0, 1), 2 + U(0, 0.5) kg·m² (valid), spin (0.3, 10, 0.2)
/// rad/s scaled per body, random orientation, under g = (0, 0, −9.81) m/s².
Model MakeBodies(int n, State* s) {
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Model m;
  for (int i = 0; i < n; ++i) {
    m.AddBody(fmt::format("b{}", i),
              MassProperties(1.0 + u(rng), Vec3::Zero(),
                             RotationalInertia(1.0 + u(rng), 1.5 + u(rng), 2.0 + 0.5 * u(rng))));
  }
  m.AddForceElement(std::make_shared<UniformGravity>("gravity", Vec3(0, 0, -9.81)));
  *s = MakeRestState(m);
  std::normal_distribution<double> g;
  for (auto& b : s->bodies) {
    b.q_WB = Quat(g(rng), g(rng), g(rng), g(rng)).normalized();
    b.w_WB_B = Vec3(0.3, 10.0, 0.2) * (0.5 + u(rng));
    b.v_WBcm_W = Vec3(u(rng), u(rng), u(rng));
  }
  return m;
}

/// Largest |q| − 1 and relative change of |L_W| between two states of the same model.
void ErrorCounters(benchmark::State& st, const Model& m, const State& a, const State& b) {
  double qn = 0.0, dl = 0.0;
  for (int i = 0; i < m.num_bodies(); ++i) {
    const BodyState &x = a.bodies[static_cast<size_t>(i)], &y = b.bodies[static_cast<size_t>(i)];
    const Mat3& I = m.body(i).I_BBcm_B();
    const double L0 = (I * x.w_WB_B).norm(), L1 = (I * y.w_WB_B).norm();
    qn = std::max(qn, std::abs(y.q_WB.norm() - 1.0));
    dl = std::max(dl, std::abs(L1 / L0 - 1.0));
  }
  st.counters["q_norm_error"] = qn;
  st.counters["L_rel_change"] = dl;
}

/// Batch: `steps_per_call` steps per Advance (1: the whole array swept once per step; more:
/// tile by tile through all the calls' steps).
void Batch(benchmark::State& st, FreeBodyStepper stepper) {
  const int n = static_cast<int>(st.range(0));
  const long long steps = st.range(1);
  const int threads = static_cast<int>(st.range(2));
  State s0;
  const Model m = MakeBodies(n, &s0);
  FreeBodyBatch batch(m);
  batch.Load(s0);
  for (auto _ : st) {
    batch.Advance(stepper, kH, steps, threads);
    benchmark::ClobberMemory();
  }
  st.SetItemsProcessed(st.iterations() * n * steps);
  State s = s0;
  batch.Store(s);
  ErrorCounters(st, m, s0, s);
}

/// The plain reference loop: the same RK4 (Euler's equations in the principal frame,
/// q̇ = ½ q ⊗ (0, ω), exact translation), written directly over an array of structs.
struct PlainBody {
  double p[3], v[3], q[4], w[3], a[3];
};

inline void PlainRhs(const double* q, const double* w, const double* a, double* dq, double* dw) {
  dq[0] = 0.5 * (-q[1] * w[0] - q[2] * w[1] - q[3] * w[2]);
  dq[1] = 0.5 * (q[0] * w[0] + q[2] * w[2] - q[3] * w[1]);
  dq[2] = 0.5 * (q[0] * w[1] - q[1] * w[2] + q[3] * w[0]);
  dq[3] = 0.5 * (q[0] * w[2] + q[1] * w[1] - q[2] * w[0]);
  dw[0] = a[0] * w[1] * w[2];
  dw[1] = a[1] * w[2] * w[0];
  dw[2] = a[2] * w[0] * w[1];
}

void PlainLoop(benchmark::State& st) {
  const int n = static_cast<int>(st.range(0));
  State s0;
  const Model m = MakeBodies(n, &s0);
  std::vector<PlainBody> bodies(static_cast<size_t>(n));
  for (int i = 0; i < n; ++i) {
    const BodyState& x = s0.bodies[static_cast<size_t>(i)];
    const Vec3 I = m.body(i).I_BBcm_B().diagonal();
    PlainBody& b = bodies[static_cast<size_t>(i)];
    b = {{x.p_WBcm.x(), x.p_WBcm.y(), x.p_WBcm.z()},
         {x.v_WBcm_W.x(), x.v_WBcm_W.y(), x.v_WBcm_W.z()},
         {x.q_WB.w(), x.q_WB.x(), x.q_WB.y(), x.q_WB.z()},
         {x.w_WB_B.x(), x.w_WB_B.y(), x.w_WB_B.z()},
         {(I[1] - I[2]) / I[0], (I[2] - I[0]) / I[1], (I[0] - I[1]) / I[2]}};
  }
  const double g[3] = {0.0, 0.0, -9.81}, h = kH;
  for (auto _ : st) {
    for (PlainBody& b : bodies) {
      for (int j = 0; j < 3; ++j) {
        b.p[j] += h * b.v[j] + 0.5 * h * h * g[j];
        b.v[j] += h * g[j];
      }
      double k1q[4], k1w[3], k2q[4], k2w[3], k3q[4], k3w[3], k4q[4], k4w[3], q[4], w[3];
      PlainRhs(b.q, b.w, b.a, k1q, k1w);
      for (int j = 0; j < 4; ++j) q[j] = b.q[j] + 0.5 * h * k1q[j];
      for (int j = 0; j < 3; ++j) w[j] = b.w[j] + 0.5 * h * k1w[j];
      PlainRhs(q, w, b.a, k2q, k2w);
      for (int j = 0; j < 4; ++j) q[j] = b.q[j] + 0.5 * h * k2q[j];
      for (int j = 0; j < 3; ++j) w[j] = b.w[j] + 0.5 * h * k2w[j];
      PlainRhs(q, w, b.a, k3q, k3w);
      for (int j = 0; j < 4; ++j) q[j] = b.q[j] + h * k3q[j];
      for (int j = 0; j < 3; ++j) w[j] = b.w[j] + h * k3w[j];
      PlainRhs(q, w, b.a, k4q, k4w);
      for (int j = 0; j < 4; ++j) b.q[j] += h / 6 * (k1q[j] + 2 * (k2q[j] + k3q[j]) + k4q[j]);
      for (int j = 0; j < 3; ++j) b.w[j] += h / 6 * (k1w[j] + 2 * (k2w[j] + k3w[j]) + k4w[j]);
      const double r =
          std::sqrt(b.q[0] * b.q[0] + b.q[1] * b.q[1] + b.q[2] * b.q[2] + b.q[3] * b.q[3]);
      for (double& c : b.q) c /= r;
    }
    benchmark::DoNotOptimize(bodies.data());
    benchmark::ClobberMemory();
  }
  st.SetItemsProcessed(st.iterations() * n);
}

/// The engine's Rk4Integrator on the same bodies (one step per iteration).
void EngineRk4(benchmark::State& st) {
  const int n = static_cast<int>(st.range(0));
  State s;
  const Model m = MakeBodies(n, &s);
  Rk4Integrator integ(m);
  for (auto _ : st) {
    integ.Step(s, kH);
    benchmark::DoNotOptimize(s.bodies.data());
  }
  st.SetItemsProcessed(st.iterations() * n);
}

/// Simulate on the same bodies with the fixed-step RK4 (the free-body batch path, run_path.h),
/// `steps` steps of kH from the same start per iteration, first and last state only: everything
/// a run adds to the batch's Advance (validation, the batch's set-up, Load and Store, the
/// gravity ledger). Compare with Batch/Rk4 at the same steps.
void SimulateRk4(benchmark::State& st) {
  const int n = static_cast<int>(st.range(0));
  const long long steps = st.range(1);
  State s0;
  const Model m = MakeBodies(n, &s0);
  SimulationOptions o;
  o.integrator = IntegratorKind::kRk4;
  o.fixed_step = kH;
  o.t_end = static_cast<double>(steps) * kH;
  o.output_interval = 0.0;
  o.store_samples = false;
  o.threads = static_cast<int>(st.range(2));
  SimulationResult r;
  for (auto _ : st) {
    r = Simulate(m, s0, o);
    benchmark::DoNotOptimize(r.final_state.bodies.data());
  }
  st.SetItemsProcessed(st.iterations() * n * steps);
  st.counters["free_body_batch"] = r.run_path.path == RunPath::kFreeBodyBatch ? 1.0 : 0.0;
  ErrorCounters(st, m, s0, r.final_state);
}

BENCHMARK(PlainLoop)->Name("PlainRk4Loop")->Arg(10000);
BENCHMARK(EngineRk4)->Name("EngineRk4")->Arg(10000);
BENCHMARK_CAPTURE(Batch, Rk4, FreeBodyStepper::kRk4)
    ->Args({10000, 1, 1})
    ->Args({10000, 10, 1})
    ->Args({10000, 100, 1});
BENCHMARK(SimulateRk4)->Args({10000, 10, 1})->Args({10000, 100, 1});
BENCHMARK_CAPTURE(Batch, Splitting, FreeBodyStepper::kSplitting)
    ->Args({10000, 1, 1})
    ->Args({10000, 10, 1});
// Two threads: wall-clock time (the CPU time counts the calling thread only).
BENCHMARK_CAPTURE(Batch, Rk4, FreeBodyStepper::kRk4)->Args({10000, 10, 2})->UseRealTime();
BENCHMARK_CAPTURE(Batch, Splitting, FreeBodyStepper::kSplitting)
    ->Args({10000, 10, 2})
    ->UseRealTime();

}  // namespace
}  // namespace chasles

BENCHMARK_MAIN();
