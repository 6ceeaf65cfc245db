// Properties of the free-body dynamics: the work-energy and impulse-momentum ledger closes,
// RK4 converges with order 4 and Dormand–Prince with order 5, and runs are deterministic.

#include <cmath>
#include <cstring>

#include <gtest/gtest.h>

#include "chasles/analysis/ledger.h"
#include "chasles/dynamics/newton_euler.h"
#include "chasles/integrate/dormand_prince.h"
#include "chasles/integrate/rk4.h"
#include "chasles/integrate/simulate.h"
#include "chasles/math/rotation.h"
#include "chasles/model/forces.h"
#include "chasles/model/model.h"
#include "test_support.h"

namespace chasles {
namespace {

// Two bodies with non-principal inertia, gravity, a spring-damper between them, a spring to
// the world, drag, a time-varying force at a body point and a body-fixed moment.
Model MakeBusyModel() {
  Model model;
  const BodyIndex a = model.AddBody(
      "a",
      MassProperties(2.0, Vec3(0.1, 0, 0), RotationalInertia(0.3, 0.4, 0.5, 0.02, -0.01, 0.03)));
  const BodyIndex b =
      model.AddBody("b", MassProperties(1.0, Vec3::Zero(), RotationalInertia(0.1, 0.2, 0.25)));
  model.AddForceElement(std::make_shared<UniformGravity>("gravity", Vec3(0, 0, -9.81)));
  model.AddForceElement(std::make_shared<SpringDamper>("link", a, Vec3(0.2, 0.1, 0), b,
                                                       Vec3(0, 0, 0.1), 0.5, 80.0, 0.7));
  model.AddForceElement(std::make_shared<SpringDamper>("hanger", a, Vec3(0, 0, 0.2), kWorld,
                                                       Vec3(0, 0, 1.0), 0.8, 150.0, 0.3));
  model.AddForceElement(std::make_shared<LinearDrag>("air", b, 0.4, 0.01));
  model.AddForceElement(std::make_shared<AppliedForce>(
      "push", b, Vec3(0.05, 0, 0),
      [](const Model&, const State& s) { return Vec3(std::sin(3 * s.t), 0.5, std::cos(2 * s.t)); },
      VectorFrame::kBody));
  model.AddForceElement(AppliedMoment::Constant("motor", a, Vec3(0, 0, 0.2), VectorFrame::kBody));
  return model;
}

State MakeBusyState(const Model& model) {
  State s = MakeRestState(model);
  SetBodyPose(model, 0, Vec3(0, 0, 0.2), Quat(RotationFromEuler("ZYX", Vec3(0.1, 0.2, 0.3))), s);
  SetBodyPose(model, 1, Vec3(0.3, 0.2, -0.3), Quat::Identity(), s);
  SetBodyVelocity(model, 0, Vec3(0.5, 0, 0), Vec3(0.3, -2.0, 1.0), s);
  SetBodyVelocity(model, 1, Vec3(0, -0.4, 0.2), Vec3(5.0, 0.1, 0.2), s);
  return s;
}

TEST(Ledger, ClosesWithSpringsDragAndAppliedForces) {
  const Model model = MakeBusyModel();
  const State s0 = MakeBusyState(model);
  SimulationOptions o;
  o.t_end = 5.0;
  o.output_interval = 0.1;
  o.adaptive.rtol = 1e-12;
  o.adaptive.atol = 1e-14;
  const SimulationResult r = Simulate(model, s0, o);
  double max_rel = 0.0;
  for (const State& s : r.samples) {
    const LedgerSample L = CalcLedgerSample(model, s, s0);
    max_rel = std::max(max_rel, std::abs(L.energy_residual) / L.energy_scale);
    const double P_scale = 1.0 + L.linear_momentum_W.norm();
    EXPECT_LT(L.momentum_residual_W.norm(), 1e-9 * P_scale) << "t = " << s.t;
    EXPECT_LT(L.angular_momentum_residual_W.norm(), 1e-9 * (1.0 + L.angular_momentum_Wo_W.norm()));
  }
  EXPECT_LT(max_rel, 1e-9);
  const LedgerSample end = CalcLedgerSample(model, r.final_state, s0);
  EXPECT_GT(end.dissipated, 0.0);  // dampers and drag removed energy
  EXPECT_EQ(end.forces[0].name, "gravity");
  // Gravity is conservative: its work is minus the change of its potential.
  EXPECT_TRUE(test::Near(end.forces[0].work,
                         -(end.forces[0].potential_energy -
                           CalcLedgerSample(model, s0, s0).forces[0].potential_energy),
                         1e-9, end.energy_scale));
}

// Error at t = 1 s against a tight Dormand–Prince reference for n steps.
template <typename StepFn>
double ErrorWithSteps(const Model& model, const State& s0, const State& ref, int n, StepFn step) {
  State s = s0;
  step(s, 1.0 / n, n);
  double e = 0.0;
  for (size_t i = 0; i < s.bodies.size(); ++i) {
    e = std::max(e, (s.bodies[i].p_WBcm - ref.bodies[i].p_WBcm).norm());
    e = std::max(e, (s.bodies[i].w_WB_B - ref.bodies[i].w_WB_B).norm());
    e = std::max(e, (s.bodies[i].q_WB.coeffs() - ref.bodies[i].q_WB.coeffs()).norm());
  }
  (void)model;
  return e;
}

State Reference(const Model& model, const State& s0) {
  SimulationOptions o;
  o.t_end = 1.0;
  o.adaptive.rtol = 1e-14;
  o.adaptive.atol = 1e-16;
  return Simulate(model, s0, o).final_state;
}

TEST(Convergence, Rk4IsFourthOrder) {
  const Model model = MakeBusyModel();
  const State s0 = MakeBusyState(model);
  const State ref = Reference(model, s0);
  auto rk4 = [&](State& s, double h, int n) {
    Rk4Integrator integ(model);
    for (int i = 0; i < n; ++i) integ.Step(s, h);
  };
  const double e1 = ErrorWithSteps(model, s0, ref, 100, rk4);
  const double e2 = ErrorWithSteps(model, s0, ref, 200, rk4);
  const double order = std::log2(e1 / e2);
  EXPECT_NEAR(order, 4.0, 0.25) << e1 << " " << e2;
}

TEST(Convergence, DormandPrinceIsFifthOrder) {
  const Model model = MakeBusyModel();
  const State s0 = MakeBusyState(model);
  const State ref = Reference(model, s0);
  auto dp5 = [&](State& s, double h, int n) {
    DormandPrince5Integrator integ(model, AdaptiveOptions{});
    integ.Initialize(s);
    for (int i = 0; i < n; ++i) integ.StepFixed(h);
    s = integ.state();
  };
  const double e1 = ErrorWithSteps(model, s0, ref, 50, dp5);
  const double e2 = ErrorWithSteps(model, s0, ref, 100, dp5);
  const double order = std::log2(e1 / e2);
  EXPECT_NEAR(order, 5.0, 0.3) << e1 << " " << e2;
}

// Field by field: BodyState has alignment padding that memcmp would read.
template <typename T>
bool SameBits(const T& a, const T& b) {
  return std::memcmp(a.data(), b.data(), sizeof(double) * static_cast<size_t>(a.size())) == 0;
}

bool BitwiseEqual(const State& a, const State& b) {
  if (std::memcmp(&a.t, &b.t, sizeof(double)) != 0 || a.bodies.size() != b.bodies.size()) {
    return false;
  }
  for (size_t i = 0; i < a.bodies.size(); ++i) {
    const BodyState &x = a.bodies[i], &y = b.bodies[i];
    if (!SameBits(x.p_WBcm, y.p_WBcm) || !SameBits(x.q_WB.coeffs(), y.q_WB.coeffs()) ||
        !SameBits(x.v_WBcm_W, y.v_WBcm_W) || !SameBits(x.w_WB_B, y.w_WB_B)) {
      return false;
    }
  }
  for (size_t i = 0; i < a.force_integrals.size(); ++i) {
    const ForceIntegrals &x = a.force_integrals[i], &y = b.force_integrals[i];
    if (std::memcmp(&x.work, &y.work, sizeof(double)) != 0 ||
        std::memcmp(&x.work_nonconservative, &y.work_nonconservative, sizeof(double)) != 0 ||
        !SameBits(x.linear_impulse_W, y.linear_impulse_W) ||
        !SameBits(x.angular_impulse_Wo_W, y.angular_impulse_Wo_W)) {
      return false;
    }
  }
  return true;
}

TEST(Determinism, SameInputGivesBitwiseSameOutput) {
  const Model model = MakeBusyModel();
  const State s0 = MakeBusyState(model);
  for (IntegratorKind kind :
       {IntegratorKind::kDormandPrince5, IntegratorKind::kRk4, IntegratorKind::kEnergyMomentum}) {
    SimulationOptions o;
    o.integrator = kind;
    o.t_end = 2.0;
    o.output_interval = 0.1;
    o.fixed_step = 1e-3;
    const SimulationResult r1 = Simulate(model, s0, o);
    const SimulationResult r2 = Simulate(model, s0, o);
    ASSERT_EQ(r1.samples.size(), r2.samples.size());
    for (size_t i = 0; i < r1.samples.size(); ++i) {
      EXPECT_TRUE(BitwiseEqual(r1.samples[i], r2.samples[i])) << static_cast<int>(kind) << " " << i;
    }
    EXPECT_EQ(r1.stats.function_evaluations, r2.stats.function_evaluations);
  }
}

TEST(QuaternionNorm, StaysUnitForEveryIntegrator) {
  const Model model = MakeBusyModel();
  const State s0 = MakeBusyState(model);
  for (IntegratorKind kind :
       {IntegratorKind::kDormandPrince5, IntegratorKind::kRk4, IntegratorKind::kEnergyMomentum}) {
    SimulationOptions o;
    o.integrator = kind;
    o.t_end = 3.0;
    o.output_interval = 0.5;
    o.fixed_step = 1e-2;
    for (const State& s : Simulate(model, s0, o).samples) {
      for (const BodyState& b : s.bodies) EXPECT_NEAR(b.q_WB.norm(), 1.0, 4e-16);
    }
  }
}

}  // namespace
}  // namespace chasles
