// Cost of one step per integrator for one free body, and throughput in body-steps per second
// for 10,000 independent bodies under gravity; cost of one constrained RK4 step (solve and
// projection) for a chain of n hinged links.

#include <cmath>

#include <benchmark/benchmark.h>
#include <fmt/format.h>

#include "chasles/integrate/dormand_prince.h"
#include "chasles/integrate/energy_momentum.h"
#include "chasles/integrate/rk4.h"
#include "chasles/math/rotation.h"
#include "chasles/model/constraints.h"
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

// A chain of n uniform links (1 kg, 0.5 m) hinged about z, hanging at 0.3 rad from the
// vertical: 5 n constraint rows.
void HingedChainRk4(benchmark::State& st) {
  const int n = static_cast<int>(st.range(0));
  const double L = 0.5;
  Model m;
  for (int i = 0; i < n; ++i) {
    m.AddBody(fmt::format("link{}", i),
              MassProperties(1.0, Vec3::Zero(), RotationalInertia(0.01, L * L / 12, L * L / 12)));
  }
  m.AddForceElement(std::make_shared<UniformGravity>("gravity", Vec3(0, -9.81, 0)));
  State s = MakeRestState(m);
  const Vec3 e(std::sin(0.3), -std::cos(0.3), 0);
  for (int i = 0; i < n; ++i) {
    SetBodyPose(m, i, (i + 0.5) * L * e,
                Quat(RotationFromAxisAngle(Vec3::UnitZ(), 0.3 - 1.5707963267948966)), s);
    m.AddConstraint(std::make_shared<Joint>(
        fmt::format("hinge{}", i), JointKind::kRevolute, i == 0 ? kWorld : i - 1,
        AttachmentFrame{i == 0 ? Vec3::Zero() : Vec3(L / 2, 0, 0)}, i,
        AttachmentFrame{Vec3(-L / 2, 0, 0)}));
  }
  Rk4Integrator integ(m);
  for (auto _ : st) {
    integ.Step(s, 1e-3);
    benchmark::DoNotOptimize(s.bodies.data());
  }
  st.SetItemsProcessed(st.iterations());
}

BENCHMARK(FixedStep<Rk4Integrator>)->Name("Rk4")->Arg(1)->Arg(10000);
BENCHMARK(DormandPrince)->Name("DormandPrince5")->Arg(1)->Arg(10000);
BENCHMARK(FixedStep<EnergyMomentumIntegrator>)->Name("EnergyMomentum")->Arg(1)->Arg(10000);
BENCHMARK(HingedChainRk4)->Arg(2)->Arg(10);

}  // namespace
}  // namespace chasles

BENCHMARK_MAIN();
