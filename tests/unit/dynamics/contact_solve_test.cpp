// The contact stage in the integrator's hot path: once the workspace has the size of the
// current modes, evaluating the accelerations allocates nothing (sliding rows, redundant rows
// solved least-norm, rolling resistance), and the least-norm solve gives Eigen's numbers.
//
// Allocations are counted by interposing malloc in this test program (Eigen and operator new
// both allocate through it). Not under AddressSanitizer, which owns malloc.

#include <cmath>
#include <cstddef>
#include <cstdlib>
#include <memory>
#include <random>

#include <gtest/gtest.h>
#include <Eigen/QR>

#include "chasles/dynamics/contact_projection.h"
#include "chasles/dynamics/contact_solve.h"
#include "chasles/dynamics/newton_euler.h"
#include "chasles/model/forces.h"
#include "chasles/model/model.h"
#include "dynamics/internal/contact_geometry.h"
#include "reference/solve_scenes.h"
#include "test_support.h"

#define CHASLES_COUNT_MALLOC (!CHASLES_TEST_ASAN)

#if CHASLES_COUNT_MALLOC
namespace {
bool g_counting = false;
long g_allocations = 0;
}  // namespace
extern "C" void* __libc_malloc(std::size_t size);
extern "C" void* malloc(std::size_t size) {
  if (g_counting) ++g_allocations;
  return __libc_malloc(size);
}
#endif

namespace chasles {
namespace {

constexpr double kG = 9.81;

// Allocations made by `f`.
template <typename F>
long CountAllocations(F&& f) {
#if CHASLES_COUNT_MALLOC
  g_allocations = 0;
  g_counting = true;
  f();
  g_counting = false;
  return g_allocations;
#else
  f();
  return 0;
#endif
}

RotationalInertia Diag(double a, double b, double c) {
  return RotationalInertia::FromMatrix(Vec3(a, b, c).asDiagonal());
}

// A box on the floor on its four bottom vertices, in `mode`, moving with `v` (slip along x
// when sliding), with rolling resistance on an extra sphere when `mu_r` > 0.
struct BoxScene {
  Model model;
  State state;
  BoxScene(ContactMode mode, const Vec3& v) {
    const double m = 3.0, a = 0.2, b = 0.1, c = 0.05;
    model.AddBody("box", MassProperties(m, Vec3::Zero(),
                                        Diag(m * (4 * b * b + 4 * c * c) / 12,
                                             m * (4 * a * a + 4 * c * c) / 12,
                                             m * (4 * a * a + 4 * b * b) / 12)));
    model.AddForceElement(std::make_shared<UniformGravity>("gravity", Vec3(0, 0, -kG)));
    ContactSpec spec;
    spec.name = "floor";
    spec.shape = ContactShape::kBox;
    spec.body = 0;
    spec.half_extents = Vec3(a, b, c);
    spec.mu_s = 0.5;
    spec.mu_k = 0.4;
    model.AddContact(spec);
    state = MakeRestState(model);
    SetBodyPose(model, 0, Vec3(0, 0, c), Quat::Identity(), state);
    SetBodyVelocity(model, 0, v, Vec3::Zero(), state);
    state.contacts.assign(8, ContactPointState{});
    for (int k = 0; k < 4; ++k) {
      state.contacts[static_cast<size_t>(k)].mode = mode;
      if (mode == ContactMode::kSliding)
        state.contacts[static_cast<size_t>(k)].slip_direction_W = Vec3::UnitX();
    }
  }
};

TEST(ContactSolve, SlidingOnRedundantRowsDoesNotAllocate) {
  BoxScene sc(ContactMode::kSliding, Vec3(1.0, 0, 0));
  Data data = MakeData(sc.model);
  CalcAccelerations(sc.model, sc.state, data);  // sizes the workspace for these modes
  const Vec3 a0 = data.a_WBcm_W[0];
  const long n = CountAllocations([&] {
    for (int i = 0; i < 10; ++i) CalcAccelerations(sc.model, sc.state, data);
  });
  EXPECT_EQ(n, 0);
  // Four sliding points share m g (least-norm) and friction mu_k m g decelerates the box.
  EXPECT_NEAR(a0.x(), -0.4 * kG, 1e-12 * kG);
  EXPECT_NEAR(a0.z(), 0.0, 1e-12 * kG);
}

TEST(ContactSolve, StickingOnRedundantRowsDoesNotAllocate) {
  BoxScene sc(ContactMode::kSticking, Vec3::Zero());
  Data data = MakeData(sc.model);
  CalcAccelerations(sc.model, sc.state, data);
  const long n = CountAllocations([&] {
    for (int i = 0; i < 10; ++i) CalcAccelerations(sc.model, sc.state, data);
  });
  EXPECT_EQ(n, 0);
  for (int k = 0; k < 4; ++k) {
    EXPECT_NEAR(data.contact_points[static_cast<size_t>(k)].normal_force, 3.0 * kG / 4,
                1e-12 * 3.0 * kG);
  }
}

// The sparse path (LinearSolver::kSparse, dynamics/internal/sparse_solve.h): once the pattern
// of the active rows is analysed, an evaluation refills and refactors in place (LDLᵀ of the
// AMD-ordered upper triangle). A chain of 30 hinged links: the sparse stage allocates no more
// than the dense one at the same state (the evaluation's one allocation is outside the solve:
// the dense path has it too).
TEST(ContactSolve, SparseConstraintStageAllocatesNoMoreThanTheDenseOne) {
  const int n = 30;
  const reference::Scene chain = reference::MakeChain(n, std::vector<double>(n, 1.0), 0.25);
  long allocations[2] = {0, 0};
  for (int sparse : {0, 1}) {
    Data data = MakeData(chain.model);
    data.linear_solver = sparse ? LinearSolver::kSparse : LinearSolver::kDense;
    CalcAccelerations(chain.model, chain.state, data);  // sizes, analyses the pattern
    allocations[sparse] = CountAllocations([&] {
      for (int i = 0; i < 10; ++i) CalcAccelerations(chain.model, chain.state, data);
    });
    // Statics: the top joint carries the whole chain.
    EXPECT_NEAR(data.constraints[0].F_Jc_W.z(), n * kG, 1e-12 * n * kG);
  }
  EXPECT_LE(allocations[1], allocations[0]);
}

TEST(ContactSolve, ProjectionDoesNotAllocateOnceSized) {
  BoxScene sc(ContactMode::kSticking, Vec3::Zero());
  sc.state.bodies[0].p_WBcm.z() += 1e-10;  // off the rows a little
  sc.state.bodies[0].v_WBcm_W = Vec3(1e-10, 0, -1e-10);
  Data data = MakeData(sc.model);
  State s = sc.state;
  ProjectOntoContactModes(sc.model, s, data);  // sizes the projection workspace
  const ContactViolation v = CalcContactViolation(sc.model, s, data);
  EXPECT_LT(v.gap, 1e-15);
  EXPECT_LT(v.normal_velocity, 1e-15);
  EXPECT_LT(v.slip, 1e-15);
  s = sc.state;
  const long n = CountAllocations([&] { ProjectOntoContactModes(sc.model, s, data); });
  EXPECT_EQ(n, 0);
}

// The least-norm paths against Eigen's CompleteOrthogonalDecomposition::solve, the minimum-norm
// solution of A x = r. A symmetric semidefinite A goes through its pivoted LDLᵀ's null space,
// any other singular A through the decomposition step by step: both agree with it to round-off
// (relative 1e-12 of |x|), and so does the weighted split, min Σ (x_i / D_i)², against the
// decomposition of A D (x = D y, y its minimum-norm solution).
TEST(ContactSolve, LeastNormSolveMatchesEigen) {
  std::mt19937 rng(20261129);
  std::uniform_real_distribution<double> u(-1.0, 1.0), pos(0.2, 3.0);
  for (int trial = 0; trial < 50; ++trial) {
    const int n = 2 + trial % 11, rank = 1 + trial % (n - 1);
    Eigen::MatrixXd B(n, rank);
    for (Eigen::Index i = 0; i < B.size(); ++i) B.data()[i] = u(rng);
    const Eigen::MatrixXd A = B * B.transpose();  // n x n of the given rank, A ⪰ 0
    Eigen::VectorXd y(n), D(n);
    for (int i = 0; i < n; ++i) y[i] = u(rng), D[i] = pos(rng);
    const Eigen::VectorXd r = A * y;
    Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod;
    cod.setThreshold(1e-10);  // before compute: the Z reflectors are built for this rank
    cod.compute(A);
    ASSERT_EQ(cod.rank(), rank);
    const Eigen::VectorXd expected = cod.solve(r);
    const Eigen::MatrixXd AD = A * D.asDiagonal();
    cod.compute(AD);
    const Eigen::VectorXd expected_weighted = D.asDiagonal() * cod.solve(r);
    for (bool symmetric : {true, false}) {
      SCOPED_TRACE(testing::Message() << "trial " << trial << (symmetric ? " LDLT" : " COD"));
      ContactWorkspace ws;
      Eigen::VectorXd x, xw;
      EXPECT_TRUE(internal::SolveSquare(A, r, symmetric, ws, x));
      EXPECT_TRUE(internal::SolveSquare(A, r, symmetric, ws, xw, &D));
      EXPECT_LE((x - expected).norm(), 1e-12 * expected.norm());
      EXPECT_LE((xw - expected_weighted).norm(), 1e-12 * expected_weighted.norm());
      EXPECT_LE((A * xw - r).norm(), 1e-12 * r.norm());
      // The decomposition's route repeats Eigen's steps: the same numbers, bit for bit.
      if (!symmetric) {
        EXPECT_TRUE(x == expected);
      }
    }
  }
}

// The rank decision against Eigen's CompleteOrthogonalDecomposition (threshold 1e-10 of its
// largest pivot) on A = U diag(s) Uᵀ ⪰ 0, U a seeded random orthogonal matrix, n from 2 to 60,
// every rank from 1 to n - 1. The rank used (the null space's when the LDLᵀ decided, else the
// decomposition's) is COD's in every case, for A and for the weighted A D. Where the rank is
// clear (kept s in [1e-3, 1], dropped s = 0, so κ <= 1e3 bounds the round-off of both answers
// by 1e3 ε) the LDLᵀ decides and both solutions agree with COD's to 1e-12 relative. Nearly
// singular cases put one kept or one dropped s at 1e-10 · 10^(±e), e from 0.3 to 6: nearer
// than kRankMargin (1e3) the decomposition decides, farther the LDLᵀ does.
TEST(ContactSolve, LeastNormRankDecisionMatchesEigen) {
  std::mt19937 rng(29112026);
  std::uniform_real_distribution<double> u(-1.0, 1.0), pos(0.2, 3.0), expo(-3.0, 0.0);
  const double near_exponents[] = {0.0, 0.3, 1.0, 2.0, 4.0, 6.0, -0.3, -1.0, -2.0, -4.0, -6.0};
  int decided_by_ldlt_near = 0, clear_cases = 0, regular = 0;
  for (int trial = 0; trial < 240; ++trial) {
    const int n = 2 + trial % 59, rank = 1 + (7 * trial) % (n - 1);
    const double e = near_exponents[trial % 11];
    Eigen::MatrixXd G(n, n);
    for (Eigen::Index i = 0; i < G.size(); ++i) G.data()[i] = u(rng);
    const Eigen::MatrixXd U = Eigen::HouseholderQR<Eigen::MatrixXd>(G).householderQ();
    Eigen::VectorXd s = Eigen::VectorXd::Zero(n), y(n), D(n);
    for (int i = 0; i < rank; ++i) s[i] = i == 0 ? 1.0 : std::pow(10.0, expo(rng));
    // e > 0: the smallest kept s 10^e above the threshold; e < 0: a dropped one 10^|e| below.
    if (e > 0.0) s[rank - 1] = 1e-10 * std::pow(10.0, e);
    if (e < 0.0) s[rank] = 1e-10 * std::pow(10.0, e);
    const bool clear = e == 0.0;
    const Eigen::MatrixXd A = U * s.asDiagonal() * U.transpose();
    for (int i = 0; i < n; ++i) y[i] = u(rng), D[i] = pos(rng);
    const Eigen::VectorXd r = A * y;
    Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod, cod_weighted;
    cod.setThreshold(1e-10);
    cod.compute(A);
    cod_weighted.setThreshold(1e-10);
    Eigen::MatrixXd AD = A;
    for (int j = 0; j < n; ++j) AD.col(j) *= D[j];  // the columns scaled as SolveSquare does
    cod_weighted.compute(AD);
    SCOPED_TRACE(testing::Message() << "trial " << trial << ", n " << n << ", rank " << rank
                                    << ", e " << e << ", COD rank " << cod.rank());
    ContactWorkspace ws;
    Eigen::VectorXd x, xw;
    // The regular solve's gate, unchanged (every pivot of Eigen's LDLT above 1e-10 max |a_ij|),
    // may pass a dropped s just under COD's threshold: no least-norm solve then, as before.
    const bool least_norm = internal::SolveSquare(A, r, true, ws, x);
    if (!least_norm) {
      ASSERT_FALSE(clear);
      ++regular;
      continue;
    }
    const bool by_ldlt = ws.null_ready;
    EXPECT_EQ(by_ldlt ? n - ws.null_rank : ws.cod.rank(), cod.rank());
    ASSERT_TRUE(internal::SolveSquare(A, r, true, ws, xw, &D));
    EXPECT_EQ(ws.null_ready ? n - ws.null_rank : ws.cod.rank(), cod_weighted.rank());
    if (clear) {
      ++clear_cases;
      EXPECT_TRUE(by_ldlt);
      EXPECT_EQ(cod.rank(), rank);
      const Eigen::VectorXd expected = cod.solve(r);
      const Eigen::VectorXd expected_weighted = D.asDiagonal() * cod_weighted.solve(r);
      EXPECT_LE((x - expected).norm(), 1e-12 * expected.norm());
      EXPECT_LE((xw - expected_weighted).norm(), 1e-12 * expected_weighted.norm());
    } else if (by_ldlt) {
      ++decided_by_ldlt_near;
    }
  }
  EXPECT_GT(clear_cases, 20);
  EXPECT_GT(decided_by_ldlt_near, 20);  // the LDLᵀ's own decisions near the threshold, checked
  EXPECT_LE(regular, 5);
}

}  // namespace
}  // namespace chasles
