// Cost of one step per integrator for one free body, and throughput in body-steps per second
// for 10,000 independent bodies under gravity.

#include <benchmark/benchmark.h>
#include <fmt/format.h>

#include "chasles/integrate/dormand_prince.h"
#include "chasles/integrate/energy_momentum.h"
#include "chasles/integrate/rk4.h"
#include "chasles/model/forces.h"
#include "chasles/model/model.h"

namespace chasles {
namespace {

Model MakeBodies(int n) {
  Model m;
  for (int i = 0; i < n; ++i) {
    m.AddBody(fmt::format("b{}", i),
              MassProperties(1.0, Vec3::Zero(), RotationalInertia(1.0, 2.0, 3.0)));
  }
  m.AddForceElement(std::make_shared<UniformGravity>("gravity", Vec3(0, 0, -9.81)));
  return m;
}

State MakeSpinning(const Model& m) {
  State s = MakeRestState(m);
  for (auto& b : s.bodies) b.w_WB_B = Vec3(0.01, 10.0, 0.01);
  return s;
}

template <typename Integrator>
void FixedStep(benchmark::State& st) {
  const int n = static_cast<int>(st.range(0));
  const Model m = MakeBodies(n);
  State s = MakeSpinning(m);
  Integrator integ(m);
  for (auto _ : st) {
    integ.Step(s, 1e-3);
    benchmark::DoNotOptimize(s.bodies.data());
  }
  st.SetItemsProcessed(st.iterations() * n);
}

void DormandPrince(benchmark::State& st) {
  const int n = static_cast<int>(st.range(0));
  const Model m = MakeBodies(n);
  AdaptiveOptions o;
  o.initial_step = 1e-3;
  o.max_step = 1e-3;  // a fixed step length, so the cost per step is comparable
  DormandPrince5Integrator integ(m, o);
  integ.Initialize(MakeSpinning(m));
  double t_end = 0.0;
  for (auto _ : st) {
    t_end += 1e-3;
    integ.Step(t_end);
    benchmark::DoNotOptimize(integ.state().bodies.data());
  }
  st.SetItemsProcessed(st.iterations() * n);
}

BENCHMARK(FixedStep<Rk4Integrator>)->Name("Rk4")->Arg(1)->Arg(10000);
BENCHMARK(DormandPrince)->Name("DormandPrince5")->Arg(1)->Arg(10000);
BENCHMARK(FixedStep<EnergyMomentumIntegrator>)->Name("EnergyMomentum")->Arg(1)->Arg(10000);

}  // namespace
}  // namespace chasles

BENCHMARK_MAIN();
