// Sparse mode selection (internal::SelectContactModes with LinearSolver::kSparse: the plan's
// LCP by principal pivoting through the sparse factorisation, docs/design.md, "Sparse mode
// selection") against the dense path (the Schur complement and Lemke's method) and against
// closed forms: the same modes, and the same forces in them to round-off.

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "chasles/dynamics/contact_projection.h"
#include "chasles/dynamics/contact_solve.h"
#include "chasles/dynamics/newton_euler.h"
#include "chasles/model/data.h"
#include "chasles/model/forces.h"
#include "dynamics/internal/mode_selection.h"
#include "reference/solve_scenes.h"
#include "test_support.h"

namespace chasles {
namespace {

using reference::kGravity;
using reference::Scene;

struct Selected {
  State state;
  std::vector<ContactModeChange> changes;
  internal::ModeSelectionStats stats;
  std::vector<ContactPointOutput> out;  // the contact stage in the chosen modes
};

Selected Select(const Scene& s, LinearSolver solver) {
  Selected r;
  r.state = s.state;
  r.changes = internal::SelectContactModes(s.model, r.state, {}, {}, nullptr, solver);
  r.stats = internal::LastModeSelectionStats();
  r.out = CalcContactOutputs(s.model, r.state);
  return r;
}

std::vector<double> RandomIn(int n, double lo, double hi, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(lo, hi);
  std::vector<double> v(static_cast<size_t>(n));
  for (double& x : v) x = u(rng);
  return v;
}

// A row of n spheres (random radii and masses) newly touching (all points separated in the
// state), each moving sideways at a random v_y: half of them rolling on the floor (w_x =
// -v_y / R: no slip there), the others sliding; the sphere-sphere points slip where the
// neighbours' contact points move apart sideways. With `lift`, a few balls are pulled up by
// more than their weight (their floor points must leave) and the first is pushed along x.
Scene RandomRow(int n, bool lift, std::mt19937& rng) {
  const std::vector<double> R = RandomIn(n, 0.02, 0.1, rng), m = RandomIn(n, 0.1, 2.0, rng);
  Scene s = reference::MakeRowPile(n, R, m, false);
  std::uniform_real_distribution<double> u(-0.5, 0.5);
  std::bernoulli_distribution half(0.5), few(0.1);
  for (int i = 0; i < n; ++i) {
    const double vy = u(rng);
    const double wx = half(rng) ? -vy / R[static_cast<size_t>(i)] : 0.0;
    SetBodyVelocity(s.model, i, Vec3(0, vy, 0), Vec3(wx, 0, 0), s.state);
    if (lift && few(rng)) {
      s.model.AddForceElement(AppliedForce::Constant(
          "lift" + std::to_string(i), i, Vec3::Zero(),
          Vec3(0, 0, 1.5 * m[static_cast<size_t>(i)] * kGravity), VectorFrame::kWorld));
    }
  }
  if (lift) {
    s.model.AddForceElement(
        AppliedForce::Constant("push", 0, Vec3::Zero(), Vec3(0.8, 0, 0), VectorFrame::kWorld));
  }
  for (ContactPointState& ps : s.state.contacts) ps = ContactPointState{};
  return s;
}

// Same modes (and slip directions to round-off), the same forces in them to 1e-9 of the
// largest force, the same projected velocities to 1e-9 of the largest speed.
void ExpectSameSelection(const Scene& s, const Selected& sparse, const Selected& dense) {
  double f_scale = 0.0, v_scale = 0.0;
  for (const ContactPointOutput& o : dense.out) {
    f_scale = std::max({f_scale, std::abs(o.normal_force), o.friction_force_W.norm()});
  }
  for (const BodyState& b : dense.state.bodies) v_scale = std::max(v_scale, b.v_WBcm_W.norm());
  ASSERT_GT(f_scale, 0.0);
  for (int p = 0; p < s.model.num_contact_points(); ++p) {
    SCOPED_TRACE(testing::Message() << "point " << s.model.contact_point_name(p));
    const auto i = static_cast<size_t>(p);
    ASSERT_EQ(sparse.state.contacts[i].mode, dense.state.contacts[i].mode);
    EXPECT_TRUE(test::MatNear(sparse.state.contacts[i].slip_direction_W,
                              dense.state.contacts[i].slip_direction_W, 1e-9, 1.0));
    EXPECT_NEAR(sparse.out[i].normal_force, dense.out[i].normal_force, 1e-9 * f_scale);
    EXPECT_TRUE(test::MatNear(sparse.out[i].friction_force_W, dense.out[i].friction_force_W, 1e-9,
                              f_scale));
  }
  for (size_t b = 0; b < dense.state.bodies.size(); ++b) {
    EXPECT_TRUE(test::MatNear(sparse.state.bodies[b].v_WBcm_W, dense.state.bodies[b].v_WBcm_W, 1e-9,
                              v_scale));
  }
}

// Seeded random rows: some floor and sphere-sphere points stick, some slide, and (with the
// pulls) some leave; the sparse path must solve every plan itself (no dense fallback) and
// choose what the dense path chooses.
TEST(SparseModeSelection, RandomRowsChooseTheDenseModesAndForces) {
  std::mt19937 rng(31);
  int pivots = 0, sliding = 0, sticking = 0, separated = 0;
  for (int n : {10, 30, 41}) {
    for (bool lift : {false, true}) {
      for (int trial = 0; trial < 3; ++trial) {
        SCOPED_TRACE(testing::Message()
                     << "n = " << n << (lift ? ", pulled" : "") << ", trial " << trial);
        const Scene s = RandomRow(n, lift, rng);
        const Selected dense = Select(s, LinearSolver::kDense);
        const Selected sparse = Select(s, LinearSolver::kSparse);
        EXPECT_EQ(dense.stats.sparse_solves, 0);
        EXPECT_GT(sparse.stats.sparse_solves, 0);
        EXPECT_EQ(sparse.stats.dense_solves, 0);
        pivots += sparse.stats.sparse_pivots;
        ExpectSameSelection(s, sparse, dense);
        for (const ContactPointState& ps : dense.state.contacts) {
          sliding += ps.mode == ContactMode::kSliding;
          sticking += ps.mode == ContactMode::kSticking;
          separated += ps.mode == ContactMode::kSeparated;
        }
      }
    }
  }
  // The rows exercise every mode, and the pulled ones the pivoting.
  EXPECT_GT(sliding, 0);
  EXPECT_GT(sticking, 0);
  EXPECT_GT(separated, 0);
  EXPECT_GT(pivots, 0);
}

// A random zig-zag chain of n links at rest (MakeChain: random directions, axes and inertias),
// the far end of every fourth link (`every`) touching a plane of its own (random normal tilted up
// to 60° from ẑ, mu_s 0.5, mu_k 0.4): the plan's bilateral rows are the 5 n joint rows and the
// tangents of the sticking ends. Gravity decides which ends press, which stick and which slide.
Scene ChainOnPlanes(int n, std::mt19937& rng, int every = 4) {
  Scene s = reference::MakeChain(n, RandomIn(n, 0.2, 3.0, rng), 0.3, &rng);
  for (BodyState& b : s.state.bodies) b.v_WBcm_W.setZero(), b.w_WB_B.setZero();
  std::uniform_real_distribution<double> tilt(0.0, 1.0);
  Vec3 top = Vec3::Zero();  // joint i at the top of link i; its far end 2 p_cm - top
  for (int i = 0; i < n; ++i) {
    const BodyState& b = s.state.bodies[static_cast<size_t>(i)];
    const Vec3 end = 2.0 * b.p_WBcm - top;
    top = end;
    if (i % every != every - 1) continue;
    ContactSpec c;
    c.name = "end" + std::to_string(i);
    c.shape = ContactShape::kPointSet;
    c.body = i;
    c.points_B = {b.q_WB.toRotationMatrix().transpose() * (end - b.p_WBcm)};
    c.plane_point_W = end;
    c.plane_normal_W = (Vec3::UnitZ() + tilt(rng) * reference::RandomUnit(rng)).normalized();
    c.mu_s = 0.5;
    c.mu_k = 0.4;
    s.model.AddContact(c);
  }
  s.state.contacts.assign(static_cast<size_t>(s.model.num_contact_points()), ContactPointState{});
  return s;
}

// Seeded random chains with their ends on planes: the joint rows go through the plan's sparse
// solve with the contact rows; same modes and forces as the dense path, and the same joint
// reactions in the chosen modes.
TEST(SparseModeSelection, RandomChainsOnPlanesChooseTheDenseModesAndForces) {
  std::mt19937 rng(17);
  int modes[3] = {0, 0, 0};
  for (int n : {8, 20, 40}) {
    for (int trial = 0; trial < 3; ++trial) {
      SCOPED_TRACE(testing::Message() << "n = " << n << ", trial " << trial);
      const Scene s = ChainOnPlanes(n, rng);
      const Selected dense = Select(s, LinearSolver::kDense);
      const Selected sparse = Select(s, LinearSolver::kSparse);
      EXPECT_GT(sparse.stats.sparse_solves, 0);
      EXPECT_EQ(sparse.stats.dense_solves, 0);
      ExpectSameSelection(s, sparse, dense);
      Data dd = MakeData(s.model), ds = MakeData(s.model);
      CalcAccelerations(s.model, dense.state, dd);
      CalcAccelerations(s.model, sparse.state, ds);
      double f_scale = 0.0;
      for (const ConstraintOutput& c : dd.constraints) f_scale = std::max(f_scale, c.F_Jc_W.norm());
      for (size_t j = 0; j < dd.constraints.size(); ++j) {
        EXPECT_TRUE(
            test::MatNear(ds.constraints[j].F_Jc_W, dd.constraints[j].F_Jc_W, 1e-9, f_scale));
      }
      for (const ContactPointState& ps : dense.state.contacts) ++modes[static_cast<int>(ps.mode)];
    }
  }
  EXPECT_GT(modes[static_cast<int>(ContactMode::kSeparated)], 0);
  EXPECT_GT(modes[static_cast<int>(ContactMode::kSticking)], 0);
  EXPECT_GT(modes[static_cast<int>(ContactMode::kSliding)], 0);
}

// Below kSparseMinRows plan rows, kAuto is the dense path exactly (bit for bit).
TEST(SparseModeSelection, SmallRowsKeepTheDensePathExactly) {
  std::mt19937 rng(5);
  for (int trial = 0; trial < 4; ++trial) {
    const Scene s = RandomRow(4, trial % 2 == 1, rng);
    const Selected automatic = Select(s, LinearSolver::kAuto);
    const Selected dense = Select(s, LinearSolver::kDense);
    EXPECT_EQ(automatic.stats.sparse_solves, 0);
    for (size_t p = 0; p < s.state.contacts.size(); ++p) {
      EXPECT_EQ(automatic.state.contacts[p].mode, dense.state.contacts[p].mode);
      EXPECT_EQ(automatic.state.contacts[p].friction_work, dense.state.contacts[p].friction_work);
    }
    for (size_t b = 0; b < s.state.bodies.size(); ++b) {
      EXPECT_EQ(automatic.state.bodies[b].v_WBcm_W, dense.state.bodies[b].v_WBcm_W);
      EXPECT_EQ(automatic.state.bodies[b].w_WB_B, dense.state.bodies[b].w_WB_B);
    }
  }
}

// Closed forms at n = 300 (sparse only: dense takes seconds here). A level row of equal
// spheres set down at rest: every point sticks, N = m g at each floor point and nothing
// between the spheres (the least-norm answer of the indeterminate row). The row set down
// moving sideways at 1 m/s (along y): the floor points slide with N = m g and friction
// -mu_k m g ŷ; the sphere-sphere points stick and carry nothing (the friction spins every
// sphere alike about x, which moves the touching points of neighbours alike).
TEST(SparseModeSelection, LargeRowsMeetTheClosedForms) {
  const int n = 300;
  const double m = 0.17, R = 0.028575, W = m * kGravity;
  for (bool sideways : {false, true}) {
    SCOPED_TRACE(sideways ? "sideways" : "at rest");
    Scene s =
        reference::MakeRowPile(n, std::vector<double>(n, R), std::vector<double>(n, m), false);
    for (int i = 0; sideways && i < n; ++i) {
      SetBodyVelocity(s.model, i, Vec3(0, 1, 0), Vec3::Zero(), s.state);
    }
    for (ContactPointState& ps : s.state.contacts) ps = ContactPointState{};
    const Selected sel = Select(s, LinearSolver::kAuto);
    EXPECT_GT(sel.stats.sparse_solves, 0);
    EXPECT_EQ(sel.stats.dense_solves, 0);
    for (int p = 0; p < s.model.num_contact_points(); ++p) {
      SCOPED_TRACE(testing::Message() << "point " << s.model.contact_point_name(p));
      const auto i = static_cast<size_t>(p);
      const bool floor = p < n;
      ASSERT_EQ(sel.state.contacts[i].mode,
                floor && sideways ? ContactMode::kSliding : ContactMode::kSticking);
      EXPECT_NEAR(sel.out[i].normal_force, floor ? W : 0.0, 1e-9 * W);
      const Vec3 f = floor && sideways ? Vec3(0, -0.3 * W, 0) : Vec3::Zero();
      EXPECT_TRUE(test::MatNear(sel.out[i].friction_force_W, f, 1e-9, W));
    }
  }
}

// The row moving lengthwise (1 m/s along x, n = 30): the floor friction spins the spheres
// alike about y, so neighbours' touching points part vertically; carrying no normal force,
// every sphere-sphere point starts to slip (one per pass: the largest excess first). Both
// paths take the same n passes to the same modes and forces.
TEST(SparseModeSelection, LengthwiseRowStartsSlippingAtEveryTouchAsDense) {
  const int n = 30;
  Scene s = reference::MakeRowPile(n, std::vector<double>(n, 0.028575),
                                   std::vector<double>(n, 0.17), true);
  for (ContactPointState& ps : s.state.contacts) ps = ContactPointState{};
  const Selected dense = Select(s, LinearSolver::kDense);
  const Selected sparse = Select(s, LinearSolver::kSparse);
  EXPECT_EQ(sparse.stats.sparse_solves, dense.stats.dense_solves);
  EXPECT_EQ(sparse.stats.dense_solves, 0);
  for (const ContactPointState& ps : sparse.state.contacts) {
    EXPECT_EQ(ps.mode, ContactMode::kSliding);
  }
  ExpectSameSelection(s, sparse, dense);
}

// The hanging chain of n rods (1 kg, 0.25 m) at rest on a frictionless wall
// (reference::MakeChainOnWall, also bench/solve_bench.cpp's): 5 n joint rows and one normal row.
Scene ChainOnWall(int n) {
  return reference::MakeChainOnWall(n, std::vector<double>(static_cast<size_t>(n), 1.0), 0.25);
}

// The chain of 60 rods on the wall (300 joint rows): the end stays on the wall (sliding,
// frictionless) with no force, and each joint carries the weight of the rods below it. Every
// plan solve is sparse, and neither Data of the selection sizes the dense Data::J (nor does the
// dense selection, whose plan solves copy the rows from their blocks), nor the contact stage
// or the projection onto the chosen modes; a chain of 4 rods (20 rows) has it from MakeData.
TEST(SparseModeSelection, LargeChainOnAWallMeetsTheClosedFormsWithoutTheDenseJacobian) {
  const int n = 60;
  const double W = 1.0 * kGravity;  // one rod's weight
  const Scene s = ChainOnWall(n);
  const Selected sel = Select(s, LinearSolver::kAuto);
  EXPECT_GT(sel.stats.sparse_solves, 0);
  EXPECT_EQ(sel.stats.dense_solves, 0);
  EXPECT_FALSE(sel.stats.dense_jacobian);
  ASSERT_EQ(sel.state.contacts[0].mode, ContactMode::kSliding);
  EXPECT_LE(std::abs(sel.out[0].normal_force), 1e-12 * W);
  EXPECT_LE(sel.out[0].friction_force_W.norm(), 1e-12 * W);
  Data data = MakeData(s.model);
  EXPECT_EQ(data.J.size(), 0);
  CalcAccelerations(s.model, sel.state, data);
  for (int i = 0; i < n; ++i) {
    EXPECT_TRUE(test::MatNear(data.constraints[static_cast<size_t>(i)].F_Jc_W,
                              Vec3(0, 0, W * (n - i)), 1e-12))
        << "joint " << i;
  }
  State projected = sel.state;
  ProjectOntoContactModes(s.model, projected, data);
  for (const BodyState& b : projected.bodies) EXPECT_LE(b.v_WBcm_W.norm(), 1e-12);
  EXPECT_EQ(data.J.size(), 0);
  const Selected dense = Select(s, LinearSolver::kDense);
  EXPECT_GT(dense.stats.dense_solves, 0);
  EXPECT_FALSE(dense.stats.dense_jacobian);
  EXPECT_EQ(dense.state.contacts[0].mode, ContactMode::kSliding);
  EXPECT_TRUE(Select(ChainOnWall(4), LinearSolver::kAuto).stats.dense_jacobian);
}

// The chain of 8 links with the end of every link on its plane (ChainOnPlanes with every = 1:
// 40 joint rows and 24 contact rows on 48 velocities, heavily redundant): the sparse path's
// normal forces are consistent, no end accelerating into its plane (a_n >= 0, to round-off of
// g) and every pressing end held there (a_n = 0). (The dense path separates every end here
// while they accelerate into their planes at 0.6 to 10 m/s²: Lemke's method on the Schur
// complement through S⁺ of a singular S does not resolve this case; docs/design.md.)
TEST(SparseModeSelection, OverconstrainedChainGetsConsistentNormalForces) {
  std::mt19937 rng(17);
  const int n = 8;
  const Scene s = ChainOnPlanes(n, rng, 1);
  const Selected sel = Select(s, LinearSolver::kSparse);
  Data d = MakeData(s.model);
  CalcAccelerations(s.model, sel.state, d);
  int pressing = 0;
  for (int i = 0; i < n; ++i) {
    SCOPED_TRACE(testing::Message() << "end " << i);
    const auto k = static_cast<size_t>(i);
    const Mat3 R = sel.state.bodies[k].q_WB.toRotationMatrix();
    const Contact& con = s.model.contact(i);
    const Vec3 r = R * con.spec().points_B[0];
    const double a_n = con.n_W().dot(d.a_WBcm_W[k] + (R * d.wdot_WB_B[k]).cross(r));
    EXPECT_GE(a_n, -1e-12 * kGravity);
    if (sel.state.contacts[k].mode != ContactMode::kSeparated) {
      ++pressing;
      EXPECT_GE(sel.out[k].normal_force, 0.0);
      EXPECT_LE(std::abs(a_n), 1e-12 * kGravity);
    }
  }
  EXPECT_GT(pressing, 0);
}

}  // namespace
}  // namespace chasles
