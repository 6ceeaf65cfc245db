// The frictional contact problem of a time step (chasles/integrate/contact_problem.h) against
// the closed forms of one point and the conditions of Coulomb's law on random coupled problems.
#include "chasles/integrate/contact_problem.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace chasles {
namespace {

// Tolerance on impulses and velocities, relative to their scale (round-off of the solve).
constexpr double kExact = 1e-12;

// A ball of mass m and radius R on a floor: the point's Delassus matrix is diag(1/m, 1/m + R²/I,
// 1/m + R²/I), I = 2/5 m R², i.e. diag(1, 7/2, 7/2)/m.
FrictionalContactProblem Ball(double m, const Eigen::Vector3d& q, double mu) {
  FrictionalContactProblem p;
  Eigen::Matrix3d W = Eigen::Vector3d(1.0, 3.5, 3.5).asDiagonal();
  p.W = (W / m).sparseView();
  p.q = q;
  p.mu = {mu};
  return p;
}

TEST(ContactProblem, BallThatSticks) {
  // Approaching at 1 m/s with slip 0.2 m/s: P_n = m (U_n = 0); stopping the slip needs
  // |P_t| = 0.2 m/3.5 <= mu P_n, so it sticks with U = 0.
  const double m = 0.17, mu = 0.5;
  const auto sol = SolveFrictionalContact(Ball(m, {-1.0, 0.2, 0.0}, mu), {});
  ASSERT_TRUE(sol.converged);
  EXPECT_NEAR(sol.P[0], m, kExact * m);
  EXPECT_NEAR(sol.P[1], -0.2 * m / 3.5, kExact * m);
  EXPECT_NEAR(sol.U.norm(), 0.0, kExact);
  EXPECT_EQ(sol.regimes[0], ContactRegime::kSticking);
}

TEST(ContactProblem, BallThatSlides) {
  // Slip 3 m/s: stopping it needs 3 m/3.5 > mu m, so it slides: P_t = -mu m, U_t = 3 - 3.5 mu.
  const double m = 0.17, mu = 0.5;
  const auto sol = SolveFrictionalContact(Ball(m, {-1.0, 0.0, 3.0}, mu), {});
  ASSERT_TRUE(sol.converged);
  EXPECT_NEAR(sol.P[0], m, kExact * m);
  EXPECT_NEAR(sol.P[2], -mu * m, kExact * m);
  EXPECT_NEAR(sol.U[2], 3.0 - 3.5 * mu, kExact);
  EXPECT_NEAR(sol.U[0], 0.0, kExact);
  EXPECT_EQ(sol.regimes[0], ContactRegime::kSliding);
}

TEST(ContactProblem, SeparatingBallTakesNoImpulse) {
  const auto sol = SolveFrictionalContact(Ball(0.17, {0.5, 1.0, 0.0}, 0.5), {});
  ASSERT_TRUE(sol.converged);
  EXPECT_EQ(sol.P.norm(), 0.0);
  EXPECT_EQ(sol.regimes[0], ContactRegime::kOpen);
}

// Random coupled problems, W = J M⁻¹ Jᵀ of random rows (M = I; rows redundant where 3m
// exceeds the degrees of freedom) and q = J v: the solution satisfies the conditions
// of the file comment of contact_problem.h, checked here directly (not through the residual
// function): P_n >= 0, U_n >= 0, P_n U_n = 0, |P_t| <= mu P_n, and at a sliding point
// P_t = -mu P_n U_t/|U_t|.
TEST(ContactProblem, RandomCoupledProblemsMeetCoulombsLaw) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  for (int trial = 0; trial < 200; ++trial) {
    const int m = 1 + trial % 20, dofs = 6 * (1 + trial % 5);
    Eigen::MatrixXd J(3 * m, dofs);
    for (int i = 0; i < J.rows(); ++i) {
      for (int j = 0; j < dofs; ++j) J(i, j) = U(rng);
    }
    FrictionalContactProblem p;
    const Eigen::MatrixXd W = J * J.transpose();
    p.W = W.sparseView();
    // q = J v (a free velocity): the velocities after are then feasible (v = 0 is).
    Eigen::VectorXd v(dofs);
    for (int j = 0; j < dofs; ++j) v[j] = U(rng);
    p.q = J * v;
    for (int i = 0; i < m; ++i) p.mu.push_back(0.1 + 0.9 * std::abs(U(rng)));
    const auto sol = SolveFrictionalContact(p, {});
    ASSERT_TRUE(sol.converged) << "trial " << trial << " residual " << sol.residual_impulse
                               << " scale " << sol.scale << " newton " << sol.newton_iterations
                               << " sweeps " << sol.sweeps;
    const double Ps = std::max(sol.scale, 1e-300), Us = p.q.cwiseAbs().maxCoeff() + W.norm() * Ps;
    const Eigen::VectorXd Uc = W * sol.P + p.q;
    for (int i = 0; i < m; ++i) {
      const double Pn = sol.P[3 * i], Un = Uc[3 * i];
      const Eigen::Vector2d Pt = sol.P.segment<2>(3 * i + 1), Ut = Uc.segment<2>(3 * i + 1);
      const double mu = p.mu[static_cast<size_t>(i)];
      EXPECT_GE(Pn, -1e-9 * Ps);
      EXPECT_GE(Un, -1e-9 * Us);
      EXPECT_LE(std::abs(Pn * Un), 1e-9 * Ps * Us);
      EXPECT_LE(Pt.norm(), mu * Pn + 1e-9 * Ps);
      if (Ut.norm() > 1e-7 * Us) {
        EXPECT_LE((Pt + mu * Pn * Ut.normalized()).norm(), 1e-9 * Ps) << "trial " << trial;
      }
    }
  }
}

}  // namespace
}  // namespace chasles
