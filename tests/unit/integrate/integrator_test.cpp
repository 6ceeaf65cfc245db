// The Integrator interface that Simulate drives, for each kind MakeIntegrator builds. A body
// falling from rest under uniform gravity g with initial velocity v0 has
//   z(t) = z0 + v0 t - ½ g t²,   v(t) = v0 - g t,
// a quadratic that RK4, the energy-momentum scheme (midpoint for a constant force) and the
// Dormand–Prince steps and its order-4 dense output all reproduce to round-off, so the
// tolerances below are round-off sized and any error in the step grid or the time bookkeeping
// shows.

#include "chasles/integrate/integrator.h"

#include <cmath>
#include <memory>

#include <gtest/gtest.h>

#include "chasles/error.h"
#include "chasles/integrate/simulate.h"
#include "chasles/model/forces.h"
#include "chasles/model/model.h"

namespace chasles {
namespace {

constexpr double kG = 9.81;  // [m/s²]
constexpr double kV0 = 3.0;  // upward speed at t = 0 [m/s]
constexpr double kZ0 = 2.0;  // height at t = 0 [m]

Model FallingBody() {
  Model m;
  m.AddBody("body", MassProperties(2.0, Vec3::Zero(), RotationalInertia(0.1, 0.2, 0.3)));
  m.AddForceElement(std::make_shared<UniformGravity>("gravity", Vec3(0, 0, -kG)));
  return m;
}

State Start(const Model& m) {
  State s = MakeRestState(m);
  s.bodies[0].p_WBcm = Vec3(0, 0, kZ0);
  s.bodies[0].v_WBcm_W = Vec3(0, 0, kV0);
  return s;
}

double Height(double t) {
  return kZ0 + kV0 * t - 0.5 * kG * t * t;
}
double Speed(double t) {
  return kV0 - kG * t;
}

class EveryKind : public testing::TestWithParam<IntegratorKind> {};

TEST_P(EveryKind, LandsOnTheLimitAndMatchesTheParabola) {
  const Model m = FallingBody();
  SimulationOptions o;
  o.integrator = GetParam();
  o.t_end = 1.0;
  o.output_interval = 0.1;
  o.fixed_step = 0.03;  // shortened to 0.1 / 4 = 0.025 on the output grid
  std::unique_ptr<Integrator> integ = MakeIntegrator(m, o, 0.0);
  integ->Initialize(Start(m));
  EXPECT_DOUBLE_EQ(integ->t(), 0.0);
  int steps = 0;
  while (integ->t() < 0.3) {
    integ->Step(0.3);
    ++steps;
    EXPECT_LE(integ->t(), 0.3);
    EXPECT_LT(integ->t_previous(), integ->t());
  }
  EXPECT_EQ(integ->t(), 0.3);  // exactly: the last step lands on the limit
  if (GetParam() != IntegratorKind::kDormandPrince5) {
    EXPECT_EQ(steps, 12);  // ceil(0.3 / 0.025)
    EXPECT_EQ(integ->stats().steps, 12);
    EXPECT_FALSE(integ->has_dense_output());
  } else {
    EXPECT_TRUE(integ->has_dense_output());
  }
  const BodyState& b = integ->state().bodies[0];
  EXPECT_NEAR(b.p_WBcm.z(), Height(0.3), 1e-14 * kZ0);
  EXPECT_NEAR(b.v_WBcm_W.z(), Speed(0.3), 1e-14 * kV0);
  EXPECT_EQ(b.p_WBcm.x(), 0.0);
}

TEST_P(EveryKind, InterpolatesWhereItCan) {
  const Model m = FallingBody();
  SimulationOptions o;
  o.integrator = GetParam();
  o.t_end = 1.0;
  o.fixed_step = 0.05;
  std::unique_ptr<Integrator> integ = MakeIntegrator(m, o, 0.0);
  integ->Initialize(Start(m));
  integ->Step(1.0);
  const double t0 = integ->t_previous(), t1 = integ->t();
  State out;
  integ->Interpolate(t1, out);
  EXPECT_EQ(out.t, t1);
  EXPECT_EQ(out.bodies[0].p_WBcm, integ->state().bodies[0].p_WBcm);
  integ->Interpolate(t0, out);
  EXPECT_EQ(out.t, t0);
  EXPECT_NEAR(out.bodies[0].p_WBcm.z(), Height(t0), 1e-14 * kZ0);
  const double mid = 0.5 * (t0 + t1);
  if (integ->has_dense_output()) {
    integ->Interpolate(mid, out);
    EXPECT_NEAR(out.bodies[0].p_WBcm.z(), Height(mid), 1e-14 * kZ0);
    EXPECT_NEAR(out.bodies[0].v_WBcm_W.z(), Speed(mid), 1e-14 * kV0);
  } else {
    EXPECT_THROW(integ->Interpolate(mid, out), UsageError);
  }
}

// Compensated updates (src/integrate/internal/compensated.h) on a body far from the origin:
// no force, p₀ = 10⁶ m, v = 0.1 m/s, so p(t) = p₀ + v t exactly, and every method is exact for
// this linear motion: what is left is round-off. With h = 1e-3 s each increment h v = 1e-4 m
// is 858,993.46 units in the last place of 10⁶ (ulp = 2⁻³³ m = 1.16e-10 m); a plain y += h v
// drops the 0.46 ulp every step, the same way, so after 10⁴ steps p would be 0.46 · 10⁴ ulp =
// 5.3e-7 m short. Compensated, the running sum is exact to within a few ulp of p.
TEST_P(EveryKind, CompensatedUpdatesKeepAFarDriftExact) {
  Model m;
  m.AddBody("body", MassProperties(2.0, Vec3::Zero(), RotationalInertia(0.1, 0.2, 0.3)));
  State s = MakeRestState(m);
  const double p0 = 1e6, v = 0.1, t_end = 10.0;
  s.bodies[0].p_WBcm = Vec3(p0, 0, 0);
  s.bodies[0].v_WBcm_W = Vec3(v, 0, 0);
  SimulationOptions o;
  o.integrator = GetParam();
  o.t_end = t_end;
  o.fixed_step = 1e-3;
  o.adaptive.initial_step = 1e-3;
  o.adaptive.max_step = 1e-3;
  std::unique_ptr<Integrator> integ = MakeIntegrator(m, o, 0.0);
  integ->Initialize(s);
  while (integ->t() < t_end) integ->Step(t_end);
  EXPECT_EQ(integ->t(), t_end);
  EXPECT_GE(integ->stats().steps, 10000);
  const double ulp = std::nextafter(p0, 2 * p0) - p0;
  EXPECT_NEAR(integ->state().bodies[0].p_WBcm.x(), p0 + v * t_end, 4 * ulp);
}

INSTANTIATE_TEST_SUITE_P(Integrator, EveryKind,
                         testing::Values(IntegratorKind::kDormandPrince5, IntegratorKind::kRk4,
                                         IntegratorKind::kEnergyMomentum,
                                         IntegratorKind::kSplitting),
                         [](const testing::TestParamInfo<IntegratorKind>& info) {
                           switch (info.param) {
                             case IntegratorKind::kDormandPrince5:
                               return std::string("dormand_prince");
                             case IntegratorKind::kRk4:
                               return std::string("rk4");
                             case IntegratorKind::kEnergyMomentum:
                               return std::string("energy_momentum");
                             case IntegratorKind::kSplitting:
                               return std::string("splitting");
                           }
                           return std::string();
                         });

// A fixed grid re-plans when the limit changes: a stretch of 0.1 s with a nominal 0.03 s
// takes ceil(0.1 / 0.03) = 4 steps of 0.025 s; the next stretch to 0.17 s (0.07 s) takes
// ceil(0.07 / 0.03) = 3 steps of 0.07 / 3 s.
TEST(FixedGrid, ReplansEachStretchIntoEqualSteps) {
  const Model m = FallingBody();
  SimulationOptions o;
  o.integrator = IntegratorKind::kRk4;
  o.t_end = 1.0;
  o.fixed_step = 0.03;
  o.output_interval = 0.03;  // the step is already a divisor: no shortening
  std::unique_ptr<Integrator> integ = MakeIntegrator(m, o, 0.0);
  integ->Initialize(Start(m));
  for (int i = 0; i < 4; ++i) integ->Step(0.1);
  EXPECT_EQ(integ->t(), 0.1);
  integ->Step(0.17);
  EXPECT_NEAR(integ->t() - 0.1, 0.07 / 3.0, 1e-16);
  integ->Step(0.17);
  integ->Step(0.17);
  EXPECT_EQ(integ->t(), 0.17);
  EXPECT_EQ(integ->stats().steps, 7);
  EXPECT_THROW(integ->Step(0.17), UsageError);  // no step backwards or of zero length
  EXPECT_NEAR(integ->state().bodies[0].p_WBcm.z(), Height(0.17), 1e-14 * kZ0);
}

TEST(FixedGrid, RefusesAStepThatIsNotPositive) {
  const Model m = FallingBody();
  SimulationOptions o;
  o.integrator = IntegratorKind::kRk4;
  o.t_end = 1.0;
  for (double h : {0.0, -1e-3, std::nan("")}) {
    o.fixed_step = h;
    EXPECT_THROW(MakeIntegrator(m, o, 0.0), InputError) << h;
  }
}

TEST(IntegratorName, NamesEveryKind) {
  EXPECT_STREQ(IntegratorName(IntegratorKind::kDormandPrince5), "adaptive Dormand-Prince 5(4)");
  EXPECT_STREQ(IntegratorName(IntegratorKind::kRk4), "RK4 (fixed step)");
  EXPECT_STREQ(IntegratorName(IntegratorKind::kEnergyMomentum), "energy-momentum (fixed step)");
  EXPECT_STREQ(IntegratorName(IntegratorKind::kSplitting),
               "symplectic splitting (fixed step, free bodies)");
}

}  // namespace
}  // namespace chasles
