// The sparse constraint and contact solves (dynamics/internal/sparse_solve.h) against the
// dense ones and against closed forms: the same system (J M⁻¹ Wᵀ) λ = c - J u̇_free, so both
// must give the same multipliers and accelerations to round-off.

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "chasles/dynamics/constraint_solve.h"
#include "chasles/dynamics/contact_projection.h"
#include "chasles/dynamics/newton_euler.h"
#include "chasles/error.h"
#include "chasles/model/data.h"
#include "dynamics/internal/sparse_solve.h"
#include "reference/solve_scenes.h"
#include "test_support.h"

namespace chasles {
namespace {

using reference::kGravity;
using reference::Scene;

// Everything the stage computes, stacked: λ of the constraints, N and friction of the
// contact points, then u̇ = [a_WBcm_W; ẇ_WB_B] of every body.
struct Answer {
  Eigen::VectorXd lambda, u_dot;
};

// With `sparse_solved` the sparse path must have solved the system itself (not handed a
// singular one to the dense path).
Answer Evaluate(const Scene& s, LinearSolver solver, bool sparse_solved = true) {
  Data data = MakeData(s.model);
  data.linear_solver = solver;
  CalcAccelerations(s.model, s.state, data);
  if (solver == LinearSolver::kSparse) {
    const SparseWorkspaceHandle& h =
        s.model.num_contacts() > 0 ? data.sparse_contacts : data.sparse_constraints;
    EXPECT_TRUE(h.ptr != nullptr && h.ptr->solved == sparse_solved);
  }
  Answer a;
  std::vector<double> l;
  for (const ConstraintOutput& c : data.constraints) {
    for (int k = 0; k < kMaxConstraintRows; ++k) l.push_back(c.lambda[k]);
  }
  for (const ContactPointOutput& p : data.contact_points) {
    l.push_back(p.normal_force);
    for (int k = 0; k < 3; ++k) l.push_back(p.friction_force_W[k]);
  }
  a.lambda = Eigen::Map<Eigen::VectorXd>(l.data(), static_cast<Eigen::Index>(l.size()));
  a.u_dot.resize(6 * s.model.num_bodies());
  for (int b = 0; b < s.model.num_bodies(); ++b) {
    a.u_dot.segment<3>(6 * b) = data.a_WBcm_W[static_cast<size_t>(b)];
    a.u_dot.segment<3>(6 * b + 3) = data.wdot_WB_B[static_cast<size_t>(b)];
  }
  return a;
}

// Sparse and dense agree to 1e-12 of the largest multiplier and of the largest acceleration
// (at least g, the only load: a pile at rest has zero accelerations, met to round-off of g).
void ExpectSame(const Scene& s, bool sparse_solved = true) {
  const Answer dense = Evaluate(s, LinearSolver::kDense);
  const Answer sparse = Evaluate(s, LinearSolver::kSparse, sparse_solved);
  const Answer automatic = Evaluate(s, LinearSolver::kAuto);
  const double f_scale = dense.lambda.cwiseAbs().maxCoeff();
  EXPECT_GT(f_scale, 0.0);
  EXPECT_TRUE(test::MatNear(sparse.lambda, dense.lambda, 1e-10, f_scale));
  EXPECT_TRUE(test::MatNear(sparse.u_dot, dense.u_dot, 1e-12, kGravity));
  EXPECT_TRUE(test::MatNear(automatic.lambda, dense.lambda, 1e-12, f_scale));
  EXPECT_TRUE(test::MatNear(automatic.u_dot, dense.u_dot, 1e-12, kGravity));
}

std::vector<double> RandomIn(int n, double lo, double hi, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(lo, hi);
  std::vector<double> v(static_cast<size_t>(n));
  for (double& x : v) x = u(rng);
  return v;
}

TEST(SparseSolve, RandomChainsAgreeWithTheDenseSolve) {
  std::mt19937 rng(2024);
  for (int n : {3, 12, 40}) {
    for (int trial = 0; trial < 3; ++trial) {
      SCOPED_TRACE(testing::Message() << "n = " << n << ", trial " << trial);
      const Scene s = reference::MakeChain(n, RandomIn(n, 0.2, 5.0, rng), 0.3, &rng);
      ExpectSame(s);
    }
  }
}

// A constant push F along x on the centre of ball 0 (no moment about it).
void Push(Scene& s, double F) {
  s.model.AddForceElement(
      AppliedForce::Constant("push", 0, Vec3::Zero(), Vec3(F, 0, 0), VectorFrame::kWorld));
}

// Sliding floor points: n normal rows and 3 (n - 1) sphere-sphere rows, no redundancy, solved
// sparsely (LU). Sticking everywhere, a row of n >= 3 spheres is statically indeterminate:
// in the plane of the centres each sphere has 3 equilibrium equations (F_x, F_z, M_y) and the
// unknowns are 2 per floor point and 2 per touching pair, 4n - 2 > 3n, so J M⁻¹ Jᵀ is singular
// (n - 2 self-stresses); the sparse LDLᵀ meets the zero pivots and the sparse least-norm solve
// (SolveSparseLeastNorm: unweighted, then weighted by capacity) answers as the dense complete
// orthogonal decomposition does. Two spheres (6 unknowns in the plane, 6 equations) are
// determinate. Some rows are pushed at one end (the weighted split then matters).
TEST(SparseSolve, RandomRowPilesAgreeWithTheDenseSolveStickingAndSliding) {
  std::mt19937 rng(7);
  for (int n : {2, 10, 30, 41}) {
    for (bool sliding : {false, true}) {
      for (double push : {0.0, 0.7}) {
        SCOPED_TRACE(testing::Message()
                     << "n = " << n << (sliding ? ", sliding" : ", sticking") << ", push " << push);
        Scene s = reference::MakeRowPile(n, RandomIn(n, 0.02, 0.1, rng), RandomIn(n, 0.1, 2.0, rng),
                                         sliding);
        if (push > 0.0) Push(s, push);
        ExpectSame(s);
      }
    }
  }
}

// A chain hanging at rest: every link is in equilibrium, F_i - F_{i+1} - m_i g ẑ = 0 with F_i
// the force of joint i on link i (its child) and F_n = 0, so F_i = g Σ_{j>=i} m_j ẑ: each
// joint carries the weight below it. The links' accelerations are zero.
TEST(SparseSolve, HangingChainJointsCarryTheWeightBelow) {
  std::mt19937 rng(99);
  const int n = 120;
  const std::vector<double> m = RandomIn(n, 0.5, 2.0, rng);
  const Scene s = reference::MakeChain(n, m, 0.25);
  Data data = MakeData(s.model);
  data.linear_solver = LinearSolver::kSparse;
  CalcAccelerations(s.model, s.state, data);
  ASSERT_TRUE(data.sparse_constraints.ptr->solved);
  double below = 0.0;
  for (int i = n - 1; i >= 0; --i) {
    below += m[static_cast<size_t>(i)];
    const ConstraintOutput& out = data.constraints[static_cast<size_t>(i)];
    EXPECT_TRUE(test::MatNear(out.F_Jc_W, Vec3(0, 0, kGravity * below), 1e-12)) << "joint " << i;
    EXPECT_LE(data.a_WBcm_W[static_cast<size_t>(i)].norm(), 1e-12 * kGravity);
  }
  EXPECT_EQ(data.constraint_rank, 5 * n);
}

// Redundant rows: the top link of a hanging chain held by two revolute joints on one axis
// (10 rows on its 6 freedoms). J M⁻¹ Jᵀ is singular, so the sparse factorisation meets a zero
// pivot (an exact one: the twin's rows copy the top joint's; the pivots of S A S + τ I give the
// nullity) and the sparse least-norm solve answers as the dense one does: the two joints split the
// load equally (min |λ₁|² + |λ₂|² subject to λ₁ + λ₂ = F gives λ₁ = λ₂ = F/2; they are symmetric
// about the rod), so each carries half the weight of the whole chain, the joints below the weight
// below.
TEST(SparseSolve, RedundantJointsGetTheLeastNormSplit) {
  std::mt19937 rng(5);
  const int n = 30;
  const std::vector<double> m = RandomIn(n, 0.5, 2.0, rng);
  Scene s = reference::MakeChain(n, m, 0.25);
  const Joint& top = dynamic_cast<const Joint&>(s.model.constraint(0));
  s.model.AddConstraint(
      std::make_shared<Joint>("twin", JointKind::kRevolute, kWorld, top.X_PJ(), 0, top.X_CJ()));
  s.state = [&] {
    State st = MakeRestState(s.model);
    st.bodies = s.state.bodies;
    return st;
  }();
  Data data = MakeData(s.model);
  data.linear_solver = LinearSolver::kSparse;
  CalcAccelerations(s.model, s.state, data);
  EXPECT_TRUE(data.sparse_constraints.ptr->solved && data.sparse_constraints.ptr->least_norm);
  EXPECT_EQ(data.sparse_constraints.ptr->nullity, 5);
  double total = 0.0;
  for (double mi : m) total += mi;
  const Vec3 half(0, 0, 0.5 * kGravity * total);
  EXPECT_TRUE(test::MatNear(data.constraints[0].F_Jc_W, half, 1e-12));
  EXPECT_TRUE(test::MatNear(data.constraints[static_cast<size_t>(n)].F_Jc_W, half, 1e-12));
  EXPECT_EQ(data.constraint_rank, 5 * n);
  double below = 0.0;
  for (int i = n - 1; i >= 1; --i) {
    below += m[static_cast<size_t>(i)];
    EXPECT_TRUE(test::MatNear(data.constraints[static_cast<size_t>(i)].F_Jc_W,
                              Vec3(0, 0, kGravity * below), 1e-12))
        << "joint " << i;
  }
}

// Redundant rows that are not exact copies: the top link also held by a spherical joint
// 0.1 m along the hinge's axis, in a turned frame (8 rows on 6 freedoms; the ball joint adds
// no rank: the hinge already holds that point, so the rank stays 5 n and the nullity is 3).
// The slender rods' moment rows weigh 1/I against 1/m for the force rows, so D A D's spectrum
// spreads over some 11 orders of magnitude: ε drops to its second level (1e-11) and either
// solve carries round-off of about u times that spread, 1e-12..1e-11 of the largest
// reaction; the sparse and dense answers agree to 1e-10 of it. Closed form: the links below the
// top carry the weight below them (determinate), the two top joints together carry the whole
// chain, F_0 + F_ball = g Σ m ẑ (the top link's equilibrium, a = 0), and nothing moves.
TEST(SparseSolve, RedundantBallJointAgreesWithTheDenseSolve) {
  std::mt19937 rng(11);
  const int n = 40;
  const std::vector<double> m = RandomIn(n, 0.5, 2.0, rng);
  Scene s = reference::MakeChain(n, m, 0.25);
  const Joint& top = dynamic_cast<const Joint&>(s.model.constraint(0));
  const Vec3 p = top.X_PJ().p_BoJ_B + 0.1 * top.X_PJ().R_BJ.col(2);  // on the hinge's axis
  const Mat3 turned = QuatExp(Vec3(0.3, -0.5, 0.7)).toRotationMatrix();
  s.model.AddConstraint(
      std::make_shared<Joint>("ball", JointKind::kSpherical, kWorld, AttachmentFrame{p, turned}, 0,
                              AttachmentFrameAtWorldPose(s.model, s.state, 0, p, turned)));
  s.state = [&] {
    State st = MakeRestState(s.model);
    st.bodies = s.state.bodies;
    return st;
  }();
  Data sparse = MakeData(s.model), dense = MakeData(s.model);
  sparse.linear_solver = LinearSolver::kSparse;
  dense.linear_solver = LinearSolver::kDense;
  CalcAccelerations(s.model, s.state, sparse);
  CalcAccelerations(s.model, s.state, dense);
  EXPECT_TRUE(sparse.sparse_constraints.ptr->singular_symmetric);
  EXPECT_EQ(sparse.sparse_constraints.ptr->nullity, 3);
  EXPECT_TRUE(sparse.sparse_constraints.ptr->solved && sparse.sparse_constraints.ptr->least_norm);
  EXPECT_EQ(sparse.constraint_rank, dense.constraint_rank);
  EXPECT_EQ(sparse.constraint_rank, 5 * n);
  double total = 0.0;
  for (double mi : m) total += mi;
  const double W = kGravity * total;
  EXPECT_TRUE(
      test::MatNear(sparse.lambda, dense.lambda, 1e-10, sparse.lambda.cwiseAbs().maxCoeff()));
  EXPECT_TRUE(test::MatNear(
      sparse.constraints[0].F_Jc_W + sparse.constraints[static_cast<size_t>(n)].F_Jc_W,
      Vec3(0, 0, W), 1e-12, W));
  double below = 0.0;
  for (int i = n - 1; i >= 1; --i) {
    below += m[static_cast<size_t>(i)];
    EXPECT_TRUE(test::MatNear(sparse.constraints[static_cast<size_t>(i)].F_Jc_W,
                              Vec3(0, 0, kGravity * below), 1e-12, W))
        << "joint " << i;
  }
  // a = 0 to round-off of the reactions that cancel on each link: W over the lightest mass.
  const double m_min = *std::min_element(m.begin(), m.end());
  for (const Vec3& a : sparse.a_WBcm_W) EXPECT_LE(a.norm(), 1e-12 * W / m_min);
}

// An inconsistent system: a hanging chain and a cart driven along x by two drivers that ask
// for different accelerations (1 and 2 m/s²: no reaction satisfies both). The sparse
// factorisation meets the zero pivot, the least-norm iteration cannot bring the residual to
// round-off (r has a part outside the range of J M⁻¹ Jᵀ), so it gives up and the dense path
// answers as it always has: an InputError naming the two drivers.
TEST(SparseSolve, InconsistentDriversFallBackToTheDenseError) {
  std::mt19937 rng(17);
  const int n = 12;
  Scene s = reference::MakeChain(n, RandomIn(n, 0.5, 2.0, rng), 0.25);
  const BodyIndex cart =
      s.model.AddBody("cart", MassProperties(3.0, Vec3::Zero(), RotationalInertia(1.0, 1.0, 1.0)));
  const AttachmentFrame X{Vec3(5, 0, 0), FrameWithZAxis(Vec3::UnitX())};
  const AttachmentFrame Xc{Vec3::Zero(), FrameWithZAxis(Vec3::UnitX())};
  s.model.AddConstraint(std::make_shared<PrescribedMotion>(
      "push", DriverKind::kTranslation, kWorld, X, cart, Xc, TimeFunction::Quadratic(0, 0, 1)));
  s.model.AddConstraint(std::make_shared<PrescribedMotion>(
      "pull", DriverKind::kTranslation, kWorld, X, cart, Xc, TimeFunction::Quadratic(0, 0, 2)));
  State st = MakeRestState(s.model);
  for (int i = 0; i < n; ++i)
    st.bodies[static_cast<size_t>(i)] = s.state.bodies[static_cast<size_t>(i)];
  SetBodyPose(s.model, cart, Vec3(5, 0, 0), Quat::Identity(), st);
  Data data = MakeData(s.model);
  data.linear_solver = LinearSolver::kSparse;
  try {
    CalcAccelerations(s.model, st, data);
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), testing::HasSubstr("'push', 'pull' are inconsistent"));
  }
  EXPECT_TRUE(data.sparse_constraints.ptr->singular_symmetric);
  EXPECT_FALSE(data.sparse_constraints.ptr->solved);
}

// A row of equal spheres resting on the floor and touching: the neighbours' centres are level,
// so the sphere-sphere normals are horizontal. The rows are redundant (see above); of the
// forces that hold the row, N_i = m g at every floor point plus any self-stress, the least-norm
// one has no self-stress: N_i = m g, nothing between the spheres, no friction, a = 0.
TEST(SparseSolve, RestingRowOfSpheresStandsOnTheFloor) {
  const int n = 60;
  const double R = 0.05, m = 0.3;
  const Scene s =
      reference::MakeRowPile(n, std::vector<double>(n, R), std::vector<double>(n, m), false);
  Data data = MakeData(s.model);
  data.linear_solver = LinearSolver::kSparse;
  CalcAccelerations(s.model, s.state, data);
  EXPECT_TRUE(data.sparse_contacts.ptr->solved && data.sparse_contacts.ptr->least_norm);
  const double W = m * kGravity;
  for (int p = 0; p < s.model.num_contact_points(); ++p) {
    const ContactPointOutput& out = data.contact_points[static_cast<size_t>(p)];
    EXPECT_TRUE(test::Near(out.normal_force, p < n ? W : 0.0, 1e-12, W)) << "point " << p;
    EXPECT_LE(out.friction_force_W.norm(), 1e-12 * W) << "point " << p;
  }
  for (const Vec3& a : data.a_WBcm_W) EXPECT_LE(a.norm(), 1e-12 * kGravity);
}

// The same row pushed along x at ball 0 by F, everything sticking. The row cannot move (each
// ball can only turn about its floor point, and the sticking sphere-sphere points lock the
// turns of neighbours against each other), so a = 0 and the whole row is in equilibrium:
// Σ_floor f = -F x̂ and Σ_floor N = n m g (the sphere-sphere forces are internal). How the
// push spreads along the row is indeterminate: the weighted least-norm split is checked
// against the dense complete orthogonal decomposition (ExpectSame), not against a closed form
// (the self-stresses couple the floor's friction with the sphere-sphere compression, so the
// split is not F/n per ball: it decays along the row).
TEST(SparseSolve, PushedRowOfSpheresHoldsThePushAtTheFloor) {
  for (int n : {45, 90}) {
    SCOPED_TRACE(testing::Message() << "n = " << n);
    const double R = 0.04, m = 0.5, F = 0.8;
    Scene s =
        reference::MakeRowPile(n, std::vector<double>(n, R), std::vector<double>(n, m), false);
    Push(s, F);
    Data data = MakeData(s.model);
    data.linear_solver = LinearSolver::kSparse;
    CalcAccelerations(s.model, s.state, data);
    EXPECT_TRUE(data.sparse_contacts.ptr->least_norm);
    Vec3 f_sum = Vec3::Zero();
    double N_sum = 0.0;
    for (int p = 0; p < n; ++p) {
      const ContactPointOutput& out = data.contact_points[static_cast<size_t>(p)];
      f_sum += out.friction_force_W;
      N_sum += out.normal_force;
    }
    const double W = m * kGravity;
    EXPECT_TRUE(test::MatNear(f_sum, Vec3(-F, 0, 0), 1e-12, F));
    EXPECT_TRUE(test::Near(N_sum, n * W, 1e-12));
    for (const Vec3& a : data.a_WBcm_W) EXPECT_LE(a.norm(), 1e-12 * kGravity);
    ExpectSame(s);
  }
}

// The projection after a step (ProjectOntoContactModes) solves the same kind of system, G M⁻¹ Gᵀ
// λ = r, for the mass-weighted correction δ = -M⁻¹ Gᵀ λ; δ is unique even where λ is not (the
// sticking row's redundant rows), so the sparse and the dense paths must give the same state.
// Rows of 20 and 60 spheres, sliding and sticking on the floor (39 to 119 position rows and
// 77 to 357 velocity rows), each centre and velocity off by up to 1e-9 (seeded): both paths
// take the violations to round-off and agree on the corrected state.
TEST(SparseSolve, ProjectionAgreesWithTheDenseOne) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> off(-1e-9, 1e-9);
  for (const int n : {20, 60}) {
    for (const bool sliding : {false, true}) {
      SCOPED_TRACE(testing::Message() << "n = " << n << (sliding ? ", sliding" : ", sticking"));
      const double R = 0.03;
      Scene s = reference::MakeRowPile(n, std::vector<double>(n, R), std::vector<double>(n, 0.2),
                                       sliding);
      for (BodyState& b : s.state.bodies) {
        b.p_WBcm += Vec3(off(rng), off(rng), off(rng));
        b.v_WBcm_W += Vec3(off(rng), off(rng), off(rng));
        b.w_WB_B += Vec3(off(rng), off(rng), off(rng)) / R;
      }
      State projected[2] = {s.state, s.state};
      for (const int sparse : {0, 1}) {
        Data data = MakeData(s.model);
        data.linear_solver = sparse ? LinearSolver::kSparse : LinearSolver::kDense;
        ProjectOntoContactModes(s.model, projected[sparse], data);
        const ContactViolation v = CalcContactViolation(s.model, projected[sparse], data);
        EXPECT_LT(v.gap, 1e-15) << "sparse " << sparse;
        EXPECT_LT(v.normal_velocity, 1e-15) << "sparse " << sparse;
        EXPECT_LT(v.slip, 1e-15) << "sparse " << sparse;
        // Sliding on the floor the rows are independent and the sparse LDLᵀ solves them; the
        // sticking row's are redundant (n - 2 self-stresses), where the sparse least-norm
        // iteration may stop short of its round-off test and hand the system to the dense path.
        if (sparse && sliding) {
          EXPECT_TRUE(data.contact_projection.sparse_velocity.ptr->solved);
        }
      }
      // The corrections are about 1e-9; the two paths agree to 1e-6 of that.
      for (int b = 0; b < n; ++b) {
        const BodyState &x = projected[1].bodies[static_cast<size_t>(b)],
                        &y = projected[0].bodies[static_cast<size_t>(b)];
        EXPECT_LE((x.p_WBcm - y.p_WBcm).norm(), 1e-15) << "body " << b;
        EXPECT_LE((x.v_WBcm_W - y.v_WBcm_W).norm(), 1e-15) << "body " << b;
        EXPECT_LE(R * (x.w_WB_B - y.w_WB_B).norm(), 1e-15) << "body " << b;
      }
    }
  }
}

// The symbolic analysis is kept while the pattern stays: a second evaluation at another state
// with the same modes reuses it (the pattern's storage is not remade).
TEST(SparseSolve, SymbolicAnalysisIsReusedWhileTheModesStay) {
  std::mt19937 rng(3);
  const int n = 40;
  Scene s = reference::MakeChain(n, RandomIn(n, 0.5, 2.0, rng), 0.3, &rng);
  Data data = MakeData(s.model);
  data.linear_solver = LinearSolver::kSparse;
  CalcAccelerations(s.model, s.state, data);
  const internal::SparseWorkspace& ws = *data.sparse_constraints.ptr;
  const int* slots = ws.pair_slot.data();
  const double* values = ws.A.valuePtr();
  s.state.bodies[3].w_WB_B += Vec3(0.1, -0.2, 0.3);
  CalcAccelerations(s.model, s.state, data);
  EXPECT_EQ(ws.pair_slot.data(), slots);
  EXPECT_EQ(ws.A.valuePtr(), values);
  EXPECT_TRUE(ws.solved);
}

}  // namespace
}  // namespace chasles
