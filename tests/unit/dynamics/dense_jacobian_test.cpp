// The dense constraint Jacobian Data::J exists only where a dense solve reads it: MakeData sizes
// it below kSparseMinRows rows, a dense consumer (internal::EnsureDenseJacobian) above, and
// CalcConstraintRows keeps it current once sized. The matrix is the same, entry for entry,
// however it was made; the sparse paths and the residuals leave it empty.

#include <array>
#include <memory>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "chasles/dynamics/constraint_residual.h"
#include "chasles/dynamics/constraint_solve.h"
#include "chasles/dynamics/newton_euler.h"
#include "chasles/dynamics/redundancy.h"
#include "chasles/math/quaternion.h"
#include "chasles/model/constraints.h"
#include "chasles/model/data.h"
#include "dynamics/internal/generalized.h"
#include "dynamics/internal/sparse_solve.h"
#include "reference/solve_scenes.h"
#include "test_support.h"

namespace chasles {
namespace {

using reference::kGravity;
using reference::Scene;

// The rows by body blocks scattered into a dense matrix: J as the sparse path sees it.
Eigen::MatrixXd ScatteredRows(const Scene& s, const Data& data) {
  internal::BlockRows rows;
  internal::AppendConstraintRows(s.model, data, rows);
  Eigen::MatrixXd J;
  internal::ScatterBlocks(rows, s.model.num_bodies(), J);
  return J;
}

// A copy of `s.state` with every body moved and turned a little (seeded): the joints' rows
// change value at the same bodies.
State Perturbed(const Scene& s, std::mt19937& rng) {
  State st = s.state;
  for (BodyState& b : st.bodies) {
    b.p_WBcm += 0.01 * reference::RandomUnit(rng);
    b.q_WB = (QuatExp(0.05 * reference::RandomUnit(rng)) * b.q_WB).normalized();
  }
  return st;
}

// 7 links, 35 rows: MakeData sizes J (rows × 6 n, zero), and after CalcConstraintRows it holds
// the rows the sparse path sees, bit for bit.
TEST(DenseJacobian, SmallModelsGetItFromMakeData) {
  const int n = 7;
  const Scene s = reference::MakeChain(n, std::vector<double>(n, 1.0), 0.25);
  ASSERT_LT(s.model.num_constraint_rows(), kSparseMinRows);
  Data data = MakeData(s.model);
  ASSERT_EQ(data.J.rows(), 5 * n);
  ASSERT_EQ(data.J.cols(), 6 * n);
  EXPECT_TRUE(data.J.isZero(0.0));
  CalcAccelerations(s.model, s.state, data);
  EXPECT_TRUE(data.J == ScatteredRows(s, data));
}

// 10 links, 50 rows: MakeData leaves J empty, and the sparse solve, the residuals and the
// projection onto the contact modes (none active: the joints' projection) of a state that
// needs none leave it so. The hanging chain's joints carry the weight below them; one link
// pushed sideways at 1 m/s breaks the velocity rows of the joints above and below it by
// 1 m/s.
TEST(DenseJacobian, LargeModelsLeaveItEmptyOnTheSparsePath) {
  const int n = 10;
  const double m = 1.0;
  Scene s = reference::MakeChain(n, std::vector<double>(n, m), 0.25);
  ASSERT_GE(s.model.num_constraint_rows(), kSparseMinRows);
  Data data = MakeData(s.model);
  EXPECT_EQ(data.J.size(), 0);
  EXPECT_EQ(data.JMinv.size(), 0);
  CalcAccelerations(s.model, s.state, data);
  EXPECT_EQ(data.J.size(), 0);
  for (int i = 0; i < n; ++i) {
    EXPECT_TRUE(test::MatNear(data.constraints[static_cast<size_t>(i)].F_Jc_W,
                              Vec3(0, 0, kGravity * m * (n - i)), 1e-12))
        << "joint " << i;
  }
  const ConstraintViolation still = CalcConstraintViolation(s.model, s.state, data);
  EXPECT_EQ(still.velocity, 0.0);
  EXPECT_EQ(data.J.size(), 0);
  const int pushed = 4;
  SetBodyVelocity(s.model, pushed, Vec3(0, 1, 0), Vec3::Zero(), s.state);
  const ConstraintViolation v = CalcConstraintViolation(s.model, s.state, data);
  EXPECT_TRUE(test::Near(v.velocity, 1.0, test::kExact));
  EXPECT_TRUE(v.worst == pushed || v.worst == pushed + 1) << v.worst;
  const std::vector<ConstraintResidual> bad = FindConstraintViolations(
      s.model, s.state, data, CalcConstraintScales(s.model, s.state, data));
  ASSERT_EQ(bad.size(), 2u);
  EXPECT_EQ(bad[0].constraint, pushed);
  EXPECT_EQ(bad[1].constraint, pushed + 1);
  EXPECT_TRUE(test::Near(bad[0].velocity_linear, 1.0, test::kExact));
  EXPECT_EQ(data.J.size(), 0);
}

// The blockwise product J x (40 rows and more) against the dense J of a copy of the Data, on a
// random chain at a random vector x; and the dense J, sized by EnsureDenseJacobian, is the
// scattered rows entry for entry.
TEST(DenseJacobian, BlockwiseProductsMatchTheDenseOne) {
  std::mt19937 rng(41);
  const int n = 12;
  std::uniform_real_distribution<double> u(0.5, 2.0);
  std::vector<double> masses(n);
  for (double& mass : masses) mass = u(rng);
  const Scene s = reference::MakeChain(n, masses, 0.3, &rng);
  Data data = MakeData(s.model);
  CalcKinematics(s.model, s.state, data);
  CalcConstraintRows(s.model, s.state, data);
  ASSERT_EQ(data.J.size(), 0);
  Eigen::VectorXd x = Eigen::VectorXd::Random(6 * n);
  Eigen::VectorXd blockwise(5 * n);
  internal::ConstraintJacobianTimes(s.model, data, x, blockwise);
  Data dense = data;
  internal::EnsureDenseJacobian(s.model, dense);
  ASSERT_EQ(dense.J.rows(), 5 * n);
  EXPECT_TRUE(dense.J == ScatteredRows(s, data));
  const Eigen::VectorXd product = dense.J * x;
  const double scale = (dense.J.cwiseAbs() * x.cwiseAbs()).maxCoeff();
  EXPECT_TRUE(test::MatNear(blockwise, product, test::kExact, scale));
}

// A solve forced dense on a large model sizes J (the hanging chain's joints still carry the
// weight below them); CalcConstraintRows then keeps it current: after evaluations at two other
// states it is exactly the J that EnsureDenseJacobian makes afresh at the last one.
TEST(DenseJacobian, ADenseSolveSizesItAndTheRowsKeepItCurrent) {
  const int n = 10;
  const double m = 1.0;
  const Scene s = reference::MakeChain(n, std::vector<double>(n, m), 0.25);
  Data data = MakeData(s.model);
  data.linear_solver = LinearSolver::kDense;
  CalcAccelerations(s.model, s.state, data);
  ASSERT_EQ(data.J.rows(), 5 * n);
  ASSERT_EQ(data.J.cols(), 6 * n);
  for (int i = 0; i < n; ++i) {
    EXPECT_TRUE(test::MatNear(data.constraints[static_cast<size_t>(i)].F_Jc_W,
                              Vec3(0, 0, kGravity * m * (n - i)), 1e-12))
        << "joint " << i;
  }
  std::mt19937 rng(7);
  State last;
  for (int k = 0; k < 2; ++k) {
    last = Perturbed(s, rng);
    CalcAccelerations(s.model, last, data);
  }
  Data fresh = MakeData(s.model);
  CalcKinematics(s.model, last, fresh);
  CalcConstraintRows(s.model, last, fresh);
  internal::EnsureDenseJacobian(s.model, fresh);
  EXPECT_TRUE(data.J == fresh.J);
  EXPECT_TRUE(fresh.J == ScatteredRows(s, fresh));
}

// The hanging chain of 8 rods (40 rows) and beside it a door on two coaxial hinges
// (tests/unit/dynamics/redundancy_test.cpp's door: 1 m wide, 2 m tall, 30 kg, the hinges 0.2 m
// from its edges on the line x = 3 m, y = 0, turning at 1 rad/s): 50 rows.
Scene ChainAndDoor() {
  const int n = 8;
  Scene s = reference::MakeChain(n, std::vector<double>(n, 1.0), 0.25);
  const double m = 30.0, w = 1.0, t = 0.04, H = 2.0, e = 0.2;
  const RotationalInertia I(m * (t * t + H * H) / 12, m * (w * w + H * H) / 12,
                            m * (w * w + t * t) / 12);
  const BodyIndex door = s.model.AddBody("door", MassProperties(m, Vec3(w / 2, 0, H / 2), I));
  State st = MakeRestState(s.model);
  for (int i = 0; i < n; ++i)
    st.bodies[static_cast<size_t>(i)] = s.state.bodies[static_cast<size_t>(i)];
  const Vec3 p0(3, 0, 0);
  SetBodyPose(s.model, door, p0, Quat::Identity(), st);
  SetBodyVelocity(s.model, door, Vec3::Zero(), Vec3(0, 0, 1.0), st);
  const Mat3 R_WJ = FrameWithZAxis(Vec3::UnitZ());
  for (const auto& [name, z] : {std::pair{"top", H - e}, std::pair{"bottom", e}}) {
    const Vec3 p = p0 + Vec3(0, 0, z);
    s.model.AddConstraint(
        std::make_shared<Joint>(name, JointKind::kRevolute, kWorld, AttachmentFrame{p, R_WJ}, door,
                                AttachmentFrameAtWorldPose(s.model, st, door, p, R_WJ)));
  }
  s.state = st;
  return s;
}

// The redundancy analysis (a dense eigendecomposition) of a large model from a fresh Data
// (J empty until the analysis sizes it) is the analysis from a Data whose J a dense solve
// sized and kept, bit for bit. Closed form: the chain's 40 rows are independent, the door's
// two hinges leave 5 of their 10 rows dependent (the axial split, and per transverse direction
// a force pair and the two moments with 2 equilibrium conditions), in 3 groups.
TEST(DenseJacobian, TheRedundancyOfALargeModelIsTheDensePathsOne) {
  const Scene s = ChainAndDoor();
  ASSERT_EQ(s.model.num_constraint_rows(), 50);
  Data fresh = MakeData(s.model);
  ASSERT_EQ(fresh.J.size(), 0);
  const Redundancy a = AnalyseRedundancy(s.model, s.state, fresh);
  EXPECT_EQ(fresh.J.rows(), 50);
  Data dense = MakeData(s.model);
  dense.linear_solver = LinearSolver::kDense;
  CalcAccelerations(s.model, s.state, dense);
  ASSERT_EQ(dense.J.rows(), 50);
  const Redundancy b = AnalyseRedundancy(s.model, s.state, dense);
  EXPECT_TRUE(fresh.J == dense.J);
  EXPECT_EQ(a.rows, 50);
  EXPECT_EQ(a.rank, 45);
  ASSERT_EQ(a.groups.size(), 3u);
  int dims = 0;
  for (const IndeterminateGroup& g : a.groups) dims += g.dimension;
  EXPECT_EQ(dims, 5);
  EXPECT_EQ(b.rank, a.rank);
  EXPECT_EQ(b.length, a.length);
  ASSERT_EQ(b.groups.size(), a.groups.size());
  for (size_t g = 0; g < a.groups.size(); ++g) {
    EXPECT_EQ(b.groups[g].dimension, a.groups[g].dimension);
    EXPECT_EQ(b.groups[g].null_combination, a.groups[g].null_combination);
    ASSERT_EQ(b.groups[g].components.size(), a.groups[g].components.size());
    for (size_t k = 0; k < a.groups[g].components.size(); ++k) {
      EXPECT_EQ(b.groups[g].components[k].constraint, a.groups[g].components[k].constraint);
      EXPECT_EQ(b.groups[g].components[k].axis, a.groups[g].components[k].axis);
      EXPECT_EQ(b.groups[g].components[k].moment, a.groups[g].components[k].moment);
    }
  }
  ASSERT_EQ(b.changes.size(), a.changes.size());
  for (size_t c = 0; c < a.changes.size(); ++c) {
    EXPECT_EQ(b.changes[c].constraint, a.changes[c].constraint);
    EXPECT_EQ(b.changes[c].kept, a.changes[c].kept);
  }
  // The door's supports are what the door alone gets: top keeps its forces, bottom its two
  // transverse ones.
  ASSERT_EQ(a.changes.size(), 2u);
  EXPECT_EQ(a.changes[0].constraint, 8);
  EXPECT_EQ(a.changes[0].kept, (std::array<bool, 6>{true, true, true, false, false, false}));
  EXPECT_EQ(a.changes[1].kept, (std::array<bool, 6>{true, true, false, false, false, false}));
}

}  // namespace
}  // namespace chasles
