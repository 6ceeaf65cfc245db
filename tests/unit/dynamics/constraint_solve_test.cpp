// The constraint rows of every kind against finite differences of their own definitions, the
// redundant and inconsistent cases of the solve, and the projection.

#include "chasles/dynamics/constraint_solve.h"

#include <cmath>
#include <memory>
#include <numbers>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "chasles/analysis/instantaneous.h"
#include "chasles/dynamics/impulse.h"
#include "chasles/dynamics/newton_euler.h"
#include "chasles/error.h"
#include "chasles/integrate/simulate.h"
#include "chasles/math/quaternion.h"
#include "chasles/math/rotation.h"
#include "chasles/model/constraints.h"
#include "chasles/model/forces.h"
#include "test_support.h"

namespace chasles {
namespace {

using test::Near;
using ::testing::HasSubstr;

MassProperties Box(double m, const Vec3& I) {
  return MassProperties(m, Vec3::Zero(), RotationalInertia::FromMatrix(I.asDiagonal()));
}

// Two bodies in a general configuration (non-principal axes, nothing aligned) with general
// velocities. The constraint rows are functions of (q, u) everywhere, not only on the
// manifold, so their derivatives can be checked at any state.
struct TwoBodies {
  Model model;
  State state;
  TwoBodies() {
    model.AddBody(
        "a", MassProperties(
                 2.0, Vec3(0.1, -0.2, 0.05),
                 RotationalInertia::FromMatrix(
                     (Mat3() << 0.3, 0.02, -0.01, 0.02, 0.4, 0.03, -0.01, 0.03, 0.5).finished())));
    model.AddBody("b", Box(1.5, Vec3(0.2, 0.25, 0.3)));
  }
  void Init() {
    state = MakeRestState(model);
    SetBodyPose(model, 0, Vec3(0.3, -0.1, 0.7),
                Quat(RotationFromEuler("ZYX", Vec3(0.3, -0.4, 0.2))), state);
    SetBodyPose(model, 1, Vec3(0.5, 0.2, 0.4), Quat(RotationFromEuler("ZYX", Vec3(-0.2, 0.5, 0.9))),
                state);
    SetBodyVelocity(model, 0, Vec3(0.4, -0.3, 0.2), Vec3(1.1, -0.7, 0.5), state);
    SetBodyVelocity(model, 1, Vec3(-0.2, 0.6, 0.1), Vec3(-0.4, 0.9, 1.3), state);
    state.t = 0.37;
  }
};

// Moves every body along its current velocity for time eps (u held fixed in W).
State Drift(const State& s, double eps) {
  State out = s;
  for (BodyState& b : out.bodies) {
    const Vec3 w_W = b.q_WB * b.w_WB_B;
    b.p_WBcm += eps * b.v_WBcm_W;
    b.q_WB = (QuatExp(eps * w_W) * b.q_WB).normalized();
    b.w_WB_B = b.q_WB.conjugate() * w_W;
  }
  out.t += eps;
  return out;
}

struct Rows {
  ConstraintEval e;
  Eigen::VectorXd Ju;  // J u over the constraint's rows
};

Rows EvalRows(const Model& model, const Constraint& c, const State& s) {
  Data data = MakeData(model);
  CalcKinematics(model, s, data);
  Rows r;
  c.Evaluate(model, s, data, r.e);
  const int n = c.num_rows();
  r.Ju = Eigen::VectorXd::Zero(n);
  for (int k = 0; k < n; ++k) {
    for (BodyIndex b : {c.parent(), c.child()}) {
      if (b == kWorld) continue;
      const auto i = static_cast<size_t>(b);
      const Eigen::Matrix<double, 1, 6> row =
          b == c.child() ? r.e.J_child.row(k) : r.e.J_parent.row(k);
      r.Ju[k] += row.head<3>().dot(s.bodies[i].v_WBcm_W) + row.tail<3>().dot(data.w_WB_W[i]);
    }
  }
  return r;
}

// Checks, by central differences along the free drift (u̇ = 0):
//  holonomic rows: dg/dt = J u - ∂g/∂t, i.e. J = ∂g/∂x (explicit time dependence
//  `g_t` removed);
//  every row: d(J u - b)/dt = 0 on a constrained motion means J u̇ = c with
//  c = ḃ - J̇ u, so with u̇ = 0: d(J u)/dt = ḃ - c.
void CheckRows(const Model& model, const Constraint& c, const State& s, double b_dot = 0.0,
               double g_t = 0.0, bool check_g = true) {
  const double h = 1e-6;
  const Rows r0 = EvalRows(model, c, s);
  const Rows rp = EvalRows(model, c, Drift(s, h));
  const Rows rm = EvalRows(model, c, Drift(s, -h));
  constexpr double kFd = 1e-7;  // central differences at h = 1e-6
  for (int k = 0; k < c.num_rows(); ++k) {
    const double dJu = (rp.Ju[k] - rm.Ju[k]) / (2 * h);
    EXPECT_TRUE(Near(dJu, b_dot - r0.e.acceleration_rhs[k], kFd, 1.0))
        << c.kind() << " row " << k << " (acceleration right-hand side)";
    if (check_g && r0.e.holonomic[static_cast<size_t>(k)]) {
      const double dg = (rp.e.position_error[k] - rm.e.position_error[k]) / (2 * h);
      EXPECT_TRUE(Near(dg + g_t, r0.Ju[k], kFd, 1.0)) << c.kind() << " row " << k << " (Jacobian)";
    }
  }
}

TEST(ConstraintRows, EveryJointKindMatchesFiniteDifferences) {
  for (JointKind kind : {JointKind::kWeld, JointKind::kRevolute, JointKind::kPrismatic,
                         JointKind::kSpherical, JointKind::kCylindrical, JointKind::kPlanar,
                         JointKind::kPointOnPlane, JointKind::kPointOnLine}) {
    for (BodyIndex parent : {kWorld, BodyIndex{0}}) {
      TwoBodies tb;
      const AttachmentFrame Xp{Vec3(0.2, -0.1, 0.3), RotationFromEuler("ZYX", Vec3(0.1, 0.2, 0.3))};
      const AttachmentFrame Xc{Vec3(-0.1, 0.15, 0.05),
                               RotationFromEuler("ZYX", Vec3(0.5, -0.3, 0.2))};
      const int id = tb.model.AddConstraint(std::make_shared<Joint>("j", kind, parent, Xp, 1, Xc));
      tb.Init();
      SCOPED_TRACE(JointKindName(kind));
      CheckRows(tb.model, tb.model.constraint(id), tb.state);
    }
  }
}

TEST(ConstraintRows, RollingShapesMatchFiniteDifferences) {
  for (RollingShape shape : {RollingShape::kSphere, RollingShape::kCylinder, RollingShape::kDisk}) {
    TwoBodies tb;
    const int id = tb.model.AddConstraint(std::make_shared<RollingContact>(
        "roll", shape, 1, Vec3(0.05, -0.02, 0.01), Vec3(0.2, 0.3, 1.0), 0.4, Vec3(0.1, 0.0, -0.2),
        Vec3(0.1, 0.2, 1.0)));
    tb.Init();
    CheckRows(tb.model, tb.model.constraint(id), tb.state);
  }
}

// On a plane of a moving body (body a, turning and translating): the rows are on the relative
// velocity of the two material points at the contact, and the plane's axes turn with a.
TEST(ConstraintRows, RollingOnAMovingBodyMatchesFiniteDifferences) {
  for (RollingShape shape : {RollingShape::kSphere, RollingShape::kCylinder, RollingShape::kDisk}) {
    TwoBodies tb;
    const int id = tb.model.AddConstraint(std::make_shared<RollingContact>(
        "roll", shape, 0, Vec3(0.1, 0.0, -0.2), Vec3(0.1, 0.2, 1.0), 1, Vec3(0.05, -0.02, 0.01),
        Vec3(0.2, 0.3, 1.0), 0.4));
    tb.Init();
    CheckRows(tb.model, tb.model.constraint(id), tb.state);
  }
}

// Every gear kind, with and without the contact row, on the world and on a moving body, in a
// general configuration (axes not parallel, circles not touching): the rows and their
// velocity-product terms are defined there too.
TEST(ConstraintRows, GearMeshesMatchFiniteDifferences) {
  for (GearKind kind : {GearKind::kExternal, GearKind::kInternal, GearKind::kFace}) {
    for (bool keep_contact : {false, true}) {
      for (BodyIndex parent : {kWorld, BodyIndex{0}}) {
        TwoBodies tb;
        const PitchCircle pc{Vec3(0.2, -0.1, 0.3), Vec3(0.1, -0.2, 1.0), 0.7};
        const PitchCircle cc{Vec3(-0.1, 0.15, 0.05), Vec3(0.3, 0.1, 0.9), 0.25};
        const int id = tb.model.AddConstraint(
            std::make_shared<GearMesh>("mesh", kind, parent, pc, 1, cc, keep_contact));
        tb.Init();
        SCOPED_TRACE(std::string(GearKindName(kind)) + (keep_contact ? " held" : "") +
                     (parent == kWorld ? " on world" : " on body"));
        CheckRows(tb.model, tb.model.constraint(id), tb.state);
      }
    }
  }
}

TEST(ConstraintRows, DriversMatchFiniteDifferences) {
  const TimeFunction f = TimeFunction::Quadratic(0.2, -0.5, 1.7);
  {
    TwoBodies tb;
    const AttachmentFrame Xp{Vec3(0.2, -0.1, 0.3), RotationFromEuler("ZYX", Vec3(0.1, 0.2, 0.3))};
    const AttachmentFrame Xc{Vec3(-0.1, 0.15, 0.05), Mat3::Identity()};
    const int id = tb.model.AddConstraint(
        std::make_shared<PrescribedMotion>("drive", DriverKind::kTranslation, 0, Xp, 1, Xc, f));
    tb.Init();
    // g = d·a - f(t): along the drift dg/dt = J u - ḟ; b = ḟ, ḃ = f̈.
    CheckRows(tb.model, tb.model.constraint(id), tb.state, f.acceleration(0.37), f.rate(0.37));
  }
  {
    TwoBodies tb;
    const AttachmentFrame Xp{Vec3(0.2, -0.1, 0.3), Mat3::Identity()};
    const AttachmentFrame Xc{Vec3(-0.1, 0.15, 0.05), Mat3::Identity()};
    const int id = tb.model.AddConstraint(
        std::make_shared<PrescribedMotion>("turn", DriverKind::kRotation, 0, Xp, 1, Xc, f));
    tb.Init();
    // The angle's Jacobian is exact only with the axes aligned (a revolute joint holds that);
    // here only the acceleration right-hand side is checked.
    CheckRows(tb.model, tb.model.constraint(id), tb.state, f.acceleration(0.37), 0.0, false);
  }
}

// A rod hanging from two coaxial hinges: 10 rows on 6 degrees of freedom (rank 5). The
// least-norm reactions share the load equally; the motion is that of one hinge.
TEST(ConstraintSolve, RedundantHingesGiveLeastNormReactionsAndAWarning) {
  const double m = 2.0, L = 1.2, g = 9.81;
  Model model;
  model.AddBody("rod", Box(m, Vec3(m * L * L / 12, m * L * L / 12, 0.01)));
  model.AddForceElement(std::make_shared<UniformGravity>("g", Vec3(0, -g, 0)));
  State s = MakeRestState(model);
  // Rod along body z, hinges at its top end about world z... use hinge axis x through the
  // top end; the rod hangs along -y, tilted by 0.3 rad about x.
  SetBodyPose(model, 0, Vec3(0, -0.5 * L * std::cos(0.3), -0.5 * L * std::sin(0.3)),
              Quat(RotationFromAxisAngle(Vec3::UnitX(), 0.3)), s);
  const Mat3 R = FrameWithZAxis(Vec3::UnitX());
  for (const double x : {-0.4, 0.4}) {
    const std::string name = x < 0 ? "hinge left" : "hinge right";
    model.AddConstraint(std::make_shared<Joint>(
        name, JointKind::kRevolute, kWorld, AttachmentFrame{Vec3(x, 0, 0), R}, 0,
        AttachmentFrameAtWorldPose(model, s, 0, Vec3(x, 0, 0), R)));
  }
  const InstantaneousSolution sol = SolveInstantaneous(model, s);
  EXPECT_EQ(sol.num_rows, 10);
  EXPECT_EQ(sol.rank, 5);
  // The redundancy, then its indeterminate components (redundancy_test.cpp has the details).
  ASSERT_GE(sol.warnings.size(), 2u);
  EXPECT_THAT(sol.warnings[0], HasSubstr("redundant"));
  EXPECT_THAT(sol.warnings[1], HasSubstr("'hinge left'"));
  // Compound pendulum about its end, angle 0.3 from the vertical: α = -(3g/2L) sin 0.3.
  const double alpha = -1.5 * g / L * std::sin(0.3);
  EXPECT_TRUE(Near(sol.bodies[0].alpha_WB_W.x(), alpha, 1e-12));
  EXPECT_TRUE(test::MatNear(sol.reactions[0].F_Jc_W, sol.reactions[1].F_Jc_W, 1e-10, m * g));
  const Vec3 total = sol.reactions[0].F_Jc_W + sol.reactions[1].F_Jc_W;
  EXPECT_TRUE(
      test::MatNear(total, Vec3(m * sol.bodies[0].a_WBcm_W - m * Vec3(0, -g, 0)), 1e-12, m * g));
  // It also simulates: the projection copes with the rank-deficient rows.
  SimulationOptions o;
  o.t_end = 1.0;
  const SimulationResult r = Simulate(model, s, o);
  Data data = MakeData(model);
  const ConstraintViolation v = CalcConstraintViolation(model, r.final_state, data);
  EXPECT_LT(v.position, 1e-12);
  EXPECT_LT(v.velocity, 1e-12);
}

// The same rod hanging straight down (mass m, length L, its centre at (0, -L/2, 0)) on the two
// hinges, struck at its lower end by J along z. About the hinge axis (chapter 8.5, eq. 8.119)
// (m L²/3) Δω_x = (r_P × J)_x = -L J, so Δω_x = -3 J / (m L) and Δv_cm = 3 J / (2 m) along z;
// eq. 8.118 then gives the supports' impulse R = m Δv_cm - J = J/2 along z, shared equally by
// the two hinges (the weighted least-norm split of the redundant rows, as for the forces).
// ProjectOntoConstraints hands out the velocity step's multipliers and CalcConstraintReactions
// turns them into each hinge's impulse at its point.
TEST(ConstraintSolve, TheProjectionsMultipliersAreTheSupportsImpulses) {
  const double m = 2.0, L = 1.2, J = 0.9;
  Model model;
  model.AddBody("rod", Box(m, Vec3(m * L * L / 12, 0.01, m * L * L / 12)));
  State s = MakeRestState(model);
  SetBodyPose(model, 0, Vec3(0, -L / 2, 0), Quat::Identity(), s);
  const Mat3 R = FrameWithZAxis(Vec3::UnitX());
  for (const double x : {-0.4, 0.4}) {
    model.AddConstraint(
        std::make_shared<Joint>(x < 0 ? "hinge left" : "hinge right", JointKind::kRevolute, kWorld,
                                AttachmentFrame{Vec3(x, 0, 0), R}, 0,
                                AttachmentFrameAtWorldPose(model, s, 0, Vec3(x, 0, 0), R)));
  }
  ApplyImpulseAtWorldPoint(model, 0, Vec3(0, -L, 0), Vec3(0, 0, J), s);
  Data data = MakeData(model);
  Eigen::VectorXd mu;
  ProjectOntoConstraints(model, s, data, {}, &mu);
  ASSERT_EQ(mu.size(), model.num_constraint_rows());
  EXPECT_TRUE(test::MatNear(s.bodies[0].v_WBcm_W, Vec3(0, 0, 1.5 * J / m), 1e-14));
  EXPECT_TRUE(test::MatNear(Vec3(s.bodies[0].q_WB * s.bodies[0].w_WB_B),
                            Vec3(-3 * J / (m * L), 0, 0), 1e-14));
  CalcConstraintRows(model, s, data);
  CalcConstraintReactions(model, s, mu, data);
  for (int c = 0; c < 2; ++c) {
    const ConstraintOutput& o = data.constraints[static_cast<size_t>(c)];
    EXPECT_TRUE(test::MatNear(o.F_Jc_W, Vec3(0, 0, J / 4), 1e-14, J)) << c;
    EXPECT_TRUE(test::MatNear(o.M_Jc_W, Vec3::Zero(), 1e-14, J * L)) << c;
  }
  // On the constraints already (to round-off): no impulse beyond round-off.
  ProjectOntoConstraints(model, s, data, {}, &mu);
  EXPECT_LE(mu.cwiseAbs().maxCoeff(), 1e-14 * J);
  EXPECT_THROW(CalcConstraintReactions(model, s, Eigen::VectorXd::Zero(3), data), UsageError);
}

TEST(ConstraintSolve, InconsistentDriversAreAnInputErrorNamingThem) {
  Model model;
  model.AddBody("cart", Box(3.0, Vec3(1, 1, 1)));
  const AttachmentFrame Xw{Vec3::Zero(), FrameWithZAxis(Vec3::UnitX())};
  const AttachmentFrame Xc{Vec3::Zero(), FrameWithZAxis(Vec3::UnitX())};
  model.AddConstraint(std::make_shared<PrescribedMotion>(
      "push", DriverKind::kTranslation, kWorld, Xw, 0, Xc, TimeFunction::Quadratic(0, 0, 1)));
  model.AddConstraint(std::make_shared<PrescribedMotion>(
      "pull", DriverKind::kTranslation, kWorld, Xw, 0, Xc, TimeFunction::Quadratic(0, 0, 2)));
  const State s = MakeRestState(model);
  try {
    SolveInstantaneous(model, s);
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("'push', 'pull' are inconsistent"));
  }
}

TEST(ConstraintSolve, StateOffTheConstraintsIsRejectedByTheAnalysis) {
  Model model;
  model.AddBody("bob", Box(1.0, Vec3(0.1, 0.1, 0.1)));
  model.AddConstraint(std::make_shared<Joint>("pin", JointKind::kSpherical, kWorld,
                                              AttachmentFrame{Vec3::Zero()}, 0,
                                              AttachmentFrame{Vec3(0, 1, 0)}));
  State s = MakeRestState(model);
  s.bodies[0].p_WBcm = Vec3(0, -1.001, 0);
  try {
    SolveInstantaneous(model, s);
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("violates constraint 'pin'"));
  }
  // Projection brings it back: |p| = 1 and the velocity along the rod removed.
  s.bodies[0].v_WBcm_W = Vec3(0.3, 0.2, 0.0);
  Data data = MakeData(model);
  ProjectOntoConstraints(model, s, data);
  const ConstraintViolation v = CalcConstraintViolation(model, s, data);
  EXPECT_LT(v.position, 1e-13);
  EXPECT_LT(v.velocity, 1e-13);
}

// Two spherical joints that hold a body's point at two world points 1 m apart: no
// configuration satisfies both.
TEST(ConstraintSolve, ConstraintsThatCannotBeAssembledAreNamed) {
  Model model;
  model.AddBody("bob", Box(1.0, Vec3(0.1, 0.1, 0.1)));
  model.AddConstraint(std::make_shared<Joint>("here", JointKind::kSpherical, kWorld,
                                              AttachmentFrame{Vec3::Zero()}, 0,
                                              AttachmentFrame{Vec3::Zero()}));
  model.AddConstraint(std::make_shared<Joint>("there", JointKind::kSpherical, kWorld,
                                              AttachmentFrame{Vec3(1, 0, 0)}, 0,
                                              AttachmentFrame{Vec3::Zero()}));
  State s = MakeRestState(model);
  Data data = MakeData(model);
  EXPECT_THAT([&] { ProjectOntoConstraints(model, s, data); },
              ::testing::ThrowsMessage<InputError>(HasSubstr("cannot be satisfied")));
}

TEST(ConstraintModel, BadInputIsNamed) {
  Model model;
  model.AddBody("b", Box(1.0, Vec3(1, 1, 1)));
  EXPECT_THAT(
      [&] {
        model.AddConstraint(std::make_shared<Joint>("j", JointKind::kRevolute, 0,
                                                    AttachmentFrame{Vec3::Zero()}, 3,
                                                    AttachmentFrame{Vec3::Zero()}));
      },
      ::testing::ThrowsMessage<InputError>(HasSubstr("acts on body index 3")));
  EXPECT_THAT(
      [] {
        Joint("j", JointKind::kRevolute, kWorld,
              AttachmentFrame{Vec3::Zero(), 2.0 * Mat3::Identity()}, 0,
              AttachmentFrame{Vec3::Zero()});
      },
      ::testing::ThrowsMessage<InputError>(HasSubstr("not a right-handed orthonormal set")));
  EXPECT_THAT(
      [] {
        RollingContact("r", RollingShape::kDisk, 0, Vec3::Zero(), Vec3::UnitZ(), -1.0, Vec3::Zero(),
                       Vec3::UnitY());
      },
      ::testing::ThrowsMessage<InputError>(HasSubstr("rolling radius is -1 m")));
  EXPECT_THAT(
      [] {
        Joint("j", JointKind::kWeld, 0, AttachmentFrame{Vec3::Zero()}, 0,
              AttachmentFrame{Vec3::Zero()});
      },
      ::testing::ThrowsMessage<InputError>(HasSubstr("parent and child are the same body")));
}

}  // namespace
}  // namespace chasles
