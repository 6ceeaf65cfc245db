// Torque-free rotation near the intermediate axis (the Dzhanibekov flip): principal moments
// (1, 2, 3) kg·m², w0 = (0.01, 10, 0.01) rad/s.

#include <cmath>

#include <gtest/gtest.h>
#include <boost/math/special_functions/ellint_1.hpp>
#include <boost/math/special_functions/jacobi_elliptic.hpp>

#include "chasles/integrate/energy_momentum.h"
#include "chasles/integrate/simulate.h"
#include "chasles/model/model.h"
#include "test_support.h"

namespace chasles {
namespace {

using test::Near;

constexpr double I1 = 1, I2 = 2, I3 = 3;
const Vec3 kW0(0.01, 10.0, 0.01);

Model MakeModel() {
  Model m;
  m.AddBody("T-handle", MassProperties(1.0, Vec3::Zero(), RotationalInertia(I1, I2, I3)));
  return m;
}

// Closed-form solution of Euler's equations (Landau & Lifshitz, Mechanics, §37).
// I1 ω1' = (I2 - I3) ω2 ω3, I2 ω2' = (I3 - I1) ω3 ω1, I3 ω3' = (I1 - I2) ω1 ω2.
// With 2T = Σ I_i ω_i² and H² = Σ I_i² ω_i² conserved, and I1 < I2 < I3, H² > 2T I2 (the motion
// circulates around the axis 3 side of the separatrix, so ω3 never changes sign):
//   ω1 = A1 cn(τ, k),  ω2 = A2 sn(τ, k),  ω3 = A3 dn(τ, k),   τ = λ t + τ0,
//   A1² = (2T I3 - H²) / (I1 (I3 - I1)),  A2² = (2T I3 - H²) / (I2 (I3 - I2)),
//   A3² = (H² - 2T I1) / (I3 (I3 - I1)),
//   λ² = (I3 - I2)(H² - 2T I1) / (I1 I2 I3),  k² = (I2 - I1)(2T I3 - H²) / ((I3 - I2)(H² - 2T I1)).
// Check by differentiation: ω1' = -A1 λ sn dn and (I2 - I3) A2 A3 / I1 = -A1 λ (the squares of
// both sides agree by the definitions above), likewise for ω2, ω3 (dn' = -k² sn cn).
// The phase τ0 puts t = 0 at the initial condition: sn τ0 = ω2(0)/A2, cn τ0 = ω1(0)/A1, i.e.
// τ0 = F(φ0, k) with φ0 = atan2(ω2(0)/A2, ω1(0)/A1) (am τ0 = φ0). ω3(0) > 0 here.
Vec3 AnalyticOmega(double t) {
  const Vec3& w = kW0;
  const double T2 = I1 * w[0] * w[0] + I2 * w[1] * w[1] + I3 * w[2] * w[2];
  const double H2 = I1 * I1 * w[0] * w[0] + I2 * I2 * w[1] * w[1] + I3 * I3 * w[2] * w[2];
  EXPECT_GT(H2, T2 * I2);  // the case derived above
  const double A1 = std::sqrt((T2 * I3 - H2) / (I1 * (I3 - I1)));
  const double A2 = std::sqrt((T2 * I3 - H2) / (I2 * (I3 - I2)));
  const double A3 = std::sqrt((H2 - T2 * I1) / (I3 * (I3 - I1)));
  const double lambda = std::sqrt((I3 - I2) * (H2 - T2 * I1) / (I1 * I2 * I3));
  const double k = std::sqrt((I2 - I1) * (T2 * I3 - H2) / ((I3 - I2) * (H2 - T2 * I1)));
  const double phi0 = std::atan2(w[1] / A2, w[0] / A1);
  const double tau0 = boost::math::ellint_1(k, phi0);
  double cn = 0, dn = 0;
  const double sn = boost::math::jacobi_elliptic(k, lambda * t + tau0, &cn, &dn);
  return {A1 * cn, A2 * sn, A3 * dn};
}

TEST(Dzhanibekov, AnalyticSolutionMatchesInitialCondition) {
  const Vec3 w = AnalyticOmega(0.0);
  for (int i = 0; i < 3; ++i) EXPECT_TRUE(Near(w[i], kW0[i], 1e-12, 10.0)) << i;
}

TEST(Dzhanibekov, AdaptiveMatchesJacobiEllipticSolution) {
  const Model model = MakeModel();
  State s0 = MakeRestState(model);
  s0.bodies[0].w_WB_B = kW0;
  SimulationOptions opt;
  opt.t_end = 10.0;
  opt.output_interval = 0.25;
  opt.adaptive.rtol = 1e-13;
  opt.adaptive.atol = 1e-15;
  const SimulationResult r = Simulate(model, s0, opt);
  ASSERT_EQ(r.samples.size(), 41u);
  // The flip happens: ω2 changes sign within 10 s.
  double min_w2 = 1e9;
  for (const State& s : r.samples) {
    const Vec3 expected = AnalyticOmega(s.t);
    min_w2 = std::min(min_w2, s.bodies[0].w_WB_B[1]);
    for (int i = 0; i < 3; ++i) {
      EXPECT_TRUE(Near(s.bodies[0].w_WB_B[i], expected[i], 1e-8, 10.0))
          << "t=" << s.t << " i=" << i;
    }
  }
  EXPECT_LT(min_w2, -9.0);
}

TEST(Dzhanibekov, EnergyMomentumIntegratorConservesEnergyAndMomentumOverAMillionSteps) {
  const Model model = MakeModel();
  State s = MakeRestState(model);
  s.bodies[0].w_WB_B = kW0;
  const Mat3 I = model.body(0).I_BBcm_B();
  auto energy = [&](const State& x) {
    return 0.5 * x.bodies[0].w_WB_B.dot(I * x.bodies[0].w_WB_B);
  };
  auto H_W = [&](const State& x) { return Vec3(x.bodies[0].q_WB * (I * x.bodies[0].w_WB_B)); };
  const double E0 = energy(s);
  const Vec3 H0 = H_W(s);
  EnergyMomentumIntegrator integ(model);
  constexpr int kSteps = 1'000'000;
  for (int n = 0; n < kSteps; ++n) integ.Step(s, 1e-2);
  EXPECT_TRUE(Near(energy(s), E0, 1e-12));
  EXPECT_TRUE(Near(H_W(s).norm(), H0.norm(), 1e-12));
  // The world angular momentum vector itself is conserved, not only its length.
  EXPECT_LT((H_W(s) - H0).norm(), 1e-12 * H0.norm());
  EXPECT_TRUE(Near(s.bodies[0].q_WB.norm(), 1.0, 1e-15));
  EXPECT_TRUE(Near(s.t, 1e4, 1e-10));  // 1e6 additions of 0.01
}

}  // namespace
}  // namespace chasles
