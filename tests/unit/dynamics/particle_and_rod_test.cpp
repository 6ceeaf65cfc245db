// Particles (all three principal moments zero) and slender rods (one zero moment) as bodies of
// their own (docs/design.md, "Particles and slender bodies"), against closed forms derived here.

#include <cmath>
#include <memory>
#include <numbers>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "chasles/analysis/instantaneous.h"
#include "chasles/analysis/momentum.h"
#include "chasles/dynamics/redundancy.h"
#include "chasles/error.h"
#include "chasles/integrate/simulate.h"
#include "chasles/math/rotation.h"
#include "chasles/model/constraints.h"
#include "chasles/model/forces.h"
#include "test_support.h"

namespace chasles {
namespace {

using test::Near;
using ::testing::HasSubstr;

constexpr double kG = 9.81;

// A slender rod along body z about its centre: I = diag(m L²/12, m L²/12, 0).
MassProperties Rod(double m, double L) {
  const double I = m * L * L / 12.0;
  return MassProperties(m, Vec3::Zero(), RotationalInertia(I, I, 0.0));
}

TEST(ParticleAndRod, BodyCountsItsZeroMoments) {
  const Body particle("p", MassProperties::PointMass(0.3, Vec3(1, 2, 3)));
  EXPECT_TRUE(particle.is_particle());
  EXPECT_EQ(particle.num_zero_moments(), 3);
  EXPECT_TRUE(particle.I_BBcm_B_inverse().isZero(0.0));
  const Body rod("r", Rod(2.0, 1.5));
  EXPECT_EQ(rod.num_zero_moments(), 1);
  // I⁺ = (E - z zᵀ) / (m L²/12) and the free-rotation projector E - z zᵀ.
  const double I = 2.0 * 1.5 * 1.5 / 12.0;
  EXPECT_TRUE(test::MatNear(rod.I_BBcm_B_inverse(), Mat3(Vec3(1 / I, 1 / I, 0).asDiagonal()), 1e-15,
                            1 / I));
  EXPECT_TRUE(test::MatNear(rod.free_rotation_B(), Mat3(Vec3(1, 1, 0).asDiagonal()), 1e-15, 1));
}

// Free fall: p(t) = p0 + v0 t + ½ g t², v(t) = v0 + g t (a quadratic: the Runge-Kutta steps are
// exact to round-off). The orientation stays, ω = 0.
TEST(ParticleAndRod, FreeParticleFollowsAParabola) {
  const double m = 0.3, t = 0.7;
  Model model;
  model.AddBody("stone", MassProperties::PointMass(m, Vec3::Zero()));
  model.AddForceElement(std::make_shared<UniformGravity>("g", Vec3(0, 0, -kG)));
  State s = MakeRestState(model);
  const Vec3 v0(1.5, -0.5, 4.0);
  SetBodyVelocity(model, 0, v0, Vec3::Zero(), s);
  SimulationOptions o;
  o.t_end = t;
  const SimulationResult r = Simulate(model, s, o);
  const BodyState& b = r.final_state.bodies[0];
  const Vec3 p = v0 * t + 0.5 * Vec3(0, 0, -kG) * t * t;
  EXPECT_TRUE(test::MatNear(b.p_WBcm, p, 1e-12, p.norm()));
  EXPECT_TRUE(test::MatNear(b.v_WBcm_W, v0 + Vec3(0, 0, -kG) * t, 1e-12, v0.norm()));
  EXPECT_EQ(b.w_WB_B, Vec3::Zero());
  EXPECT_TRUE(b.q_WB.isApprox(Quat::Identity(), 1e-15));
}

// A particle on a spring (k, rest length L0) to a fixed point: m ẍ = -k (x - L0), so
// ẍ = -(k/m) A at the stretch A (ω² = k/m exactly) and the period is 2π sqrt(m/k): after one
// period the particle is back at rest at its start.
TEST(ParticleAndRod, ParticleOnASpringHasPeriodTwoPiSqrtMOverK) {
  const double m = 0.5, k = 200.0, L0 = 0.1, A = 0.02;
  Model model;
  model.AddBody("bob", MassProperties::PointMass(m, Vec3::Zero()));
  model.AddForceElement(
      std::make_shared<SpringDamper>("spring", 0, Vec3::Zero(), kWorld, Vec3::Zero(), L0, k, 0.0));
  State s = MakeRestState(model);
  SetBodyPose(model, 0, Vec3(L0 + A, 0, 0), Quat::Identity(), s);
  const InstantaneousSolution sol = SolveInstantaneous(model, s);
  EXPECT_TRUE(Near(sol.bodies[0].a_WBcm_W.x(), -k / m * A, 1e-12));
  EXPECT_EQ(sol.bodies[0].alpha_WB_W, Vec3::Zero());
  SimulationOptions o;
  o.t_end = 2 * std::numbers::pi * std::sqrt(m / k);
  o.adaptive.rtol = 1e-13;
  o.adaptive.atol = 1e-16;
  const SimulationResult r = Simulate(model, s, o);
  EXPECT_TRUE(Near(r.final_state.bodies[0].p_WBcm.x(), L0 + A, 1e-9));
  EXPECT_NEAR(r.final_state.bodies[0].v_WBcm_W.x(), 0.0, 1e-9 * A * std::sqrt(k / m));
}

// A particle held at its own position by a spherical joint: the joint carries its weight, m g.
TEST(ParticleAndRod, ParticleOnAFixedPointCarriesItsWeight) {
  const double m = 0.25;
  Model model;
  model.AddBody("bob", MassProperties::PointMass(m, Vec3(0.1, 0, 0)));
  model.AddForceElement(std::make_shared<UniformGravity>("g", Vec3(0, 0, -kG)));
  State s = MakeRestState(model);
  SetBodyPose(model, 0, Vec3(1, 2, 3), Quat::Identity(), s);
  model.AddConstraint(std::make_shared<Joint>(
      "pin", JointKind::kSpherical, kWorld, AttachmentFrame{Vec3(1.1, 2, 3)}, 0,
      AttachmentFrameAtWorldPose(model, s, 0, Vec3(1.1, 2, 3), Mat3::Identity())));
  const InstantaneousSolution sol = SolveInstantaneous(model, s);
  EXPECT_TRUE(test::MatNear(sol.reactions[0].F_Jc_W, Vec3(0, 0, m * kG), 1e-12, m * kG));
  EXPECT_NEAR(sol.bodies[0].a_WBcm_W.norm(), 0.0, 1e-12 * kG);
}

// A particle has no rotation to carry a joint point away from it, and cannot roll.
TEST(ParticleAndRod, JointAwayFromAParticleIsAnInputError) {
  Model model;
  model.AddBody("bob", MassProperties::PointMass(1.0, Vec3::Zero()));
  try {
    model.AddConstraint(std::make_shared<Joint>("hinge", JointKind::kRevolute, kWorld,
                                                AttachmentFrame{Vec3(0, 0, 1)}, 0,
                                                AttachmentFrame{Vec3(0, 0, 1)}));
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("'hinge': body 'bob' is a point mass"));
  }
  EXPECT_THROW(model.AddConstraint(std::make_shared<RollingContact>(
                   "roll", RollingShape::kSphere, 0, Vec3::Zero(), Vec3::UnitZ(), 0.1,
                   Vec3(0, 0, -0.1), Vec3::UnitZ())),
               InputError);
}

// Rod pinned at one end about the horizontal y axis, released from horizontal at rest, gravity
// -z. At θ below the horizontal, energy gives (1/2)(m L²/3) θ̇² = m g (L/2) sin θ:
//   θ̇² = 3 g sin θ / L,   θ̈ = (3 g / 2L) cos θ   (moments about the pin: (m L²/3) θ̈ = m g L/2 cos
//   θ)
// With the centre at r = (L/2)(cos θ, 0, -sin θ) and ω = θ̇ y: a = θ̈ y × r - θ̇² r, and the pin's
// force is R = m a - m g. At the bottom (θ = π/2): R = m g + m (L/2)(3g/L) = (5/2) m g upward.
TEST(ParticleAndRod, SlenderRodPinnedAtOneEnd) {
  const double m = 1.2, L = 0.8;
  for (const double th : {0.0, 0.4, 1.1, std::numbers::pi / 2}) {
    Model model;
    model.AddBody("rod", Rod(m, L));
    model.AddForceElement(std::make_shared<UniformGravity>("g", Vec3(0, 0, -kG)));
    State s = MakeRestState(model);
    const Vec3 u(std::cos(th), 0, -std::sin(th));  // from the pin along the rod
    const Vec3 r = 0.5 * L * u;
    const double thd = std::sqrt(3 * kG * std::sin(th) / L);
    const double thdd = 1.5 * kG / L * std::cos(th);
    SetBodyPose(model, 0, r, Quat::FromTwoVectors(Vec3::UnitZ(), u), s);
    SetBodyVelocity(model, 0, Vec3(thd * Vec3::UnitY().cross(r)), Vec3(0, thd, 0), s);
    const Mat3 R = FrameWithZAxis(Vec3::UnitY());
    model.AddConstraint(std::make_shared<Joint>(
        "pin", JointKind::kRevolute, kWorld, AttachmentFrame{Vec3::Zero(), R}, 0,
        AttachmentFrameAtWorldPose(model, s, 0, Vec3::Zero(), R)));
    const InstantaneousSolution sol = SolveInstantaneous(model, s);
    EXPECT_TRUE(Near(sol.bodies[0].alpha_WB_W.y(), thdd, 1e-12)) << th;
    EXPECT_NEAR(sol.bodies[0].alpha_WB_W.x(), 0.0, 1e-12 * kG / L);
    EXPECT_NEAR(sol.bodies[0].alpha_WB_W.z(), 0.0, 1e-12 * kG / L);
    const Vec3 a = thdd * Vec3::UnitY().cross(r) - thd * thd * r;
    const Vec3 F = m * a - m * Vec3(0, 0, -kG);
    EXPECT_TRUE(test::MatNear(sol.reactions[0].F_Jc_W, F, 1e-12, m * kG)) << th;
    if (th == std::numbers::pi / 2) {
      EXPECT_TRUE(Near(sol.reactions[0].F_Jc_W.z(), 2.5 * m * kG, 1e-12));
    }
  }
}

// The pin's moment about the rod's own axis acts on no inertia: the redundancy analysis finds
// exactly that one component undetermined (the other four rows are independent) and names the
// rod as its cause; a rod with a small made-up moment about its axis instead has no redundancy.
TEST(ParticleAndRod, PinMomentAboutTheRodAxisIsUndeterminedBecauseOfTheRod) {
  for (const double own : {0.0, 1e-4}) {
    Model model;
    const double m = 1.2, L = 0.8, I = m * L * L / 12.0;
    model.AddBody("rod", MassProperties(m, Vec3::Zero(), RotationalInertia(I, I, own)));
    State s = MakeRestState(model);
    const Vec3 u(1, 0, 0);  // the rod lies along x, pinned at its end about y
    SetBodyPose(model, 0, 0.5 * L * u, Quat::FromTwoVectors(Vec3::UnitZ(), u), s);
    const Mat3 R = FrameWithZAxis(Vec3::UnitY());
    model.AddConstraint(std::make_shared<Joint>(
        "pin", JointKind::kRevolute, kWorld, AttachmentFrame{Vec3::Zero(), R}, 0,
        AttachmentFrameAtWorldPose(model, s, 0, Vec3::Zero(), R)));
    Data data = MakeData(model);
    const Redundancy r = AnalyseRedundancy(model, s, data);
    if (own > 0.0) {
      EXPECT_EQ(r.rank, r.rows);
      EXPECT_TRUE(DescribeRedundancy(model, r).empty());
      continue;
    }
    EXPECT_EQ(r.rows, 5);
    EXPECT_EQ(r.rank, 4);
    ASSERT_EQ(r.groups.size(), 1u);
    ASSERT_EQ(r.groups[0].components.size(), 1u);
    const ReactionComponent& c = r.groups[0].components[0];
    EXPECT_TRUE(c.moment);
    EXPECT_EQ(c.frozen_spin_body, 0);
    // The component's axis is the rod's: x of the joint frame along the rod.
    const Vec3 a_W = data.constraint_rows[0].R_WJ.col(c.axis);
    EXPECT_NEAR(std::abs(a_W.dot(u)), 1.0, 1e-12);
    const std::vector<std::string> text = DescribeRedundancy(model, r);
    // The headline, the undetermined moment with its cause, the determinate alternative.
    ASSERT_EQ(text.size(), 3u);
    EXPECT_THAT(text[1], HasSubstr("'pin' x moment: not determined at all (about the own axis "
                                   "of 'rod', a slender body"));
  }
}

// A free rod turning with ω ⊥ its axis: H = I⊥ ω is parallel to ω, so the Euler equations
// (8.79-8.81, with the zero moment) give ω̇ = 0 and the rod turns uniformly about the fixed
// ω: its axis u(t) is u(0) turned by |ω| t about ω. Energy and angular momentum stay.
TEST(ParticleAndRod, FreeRodTumblesUniformlyKeepingHAndEnergy) {
  const double m = 0.7, L = 2.0;
  Model model;
  model.AddBody("rod", Rod(m, L));
  State s = MakeRestState(model);
  const Quat q0(RotationFromEuler("ZYX", Vec3(0.3, -0.5, 0.8)));
  const Vec3 u0 = q0 * Vec3::UnitZ();
  const Vec3 w = 3.0 * u0.cross(Vec3(0.2, 0.9, -0.4)).normalized();
  SetBodyPose(model, 0, Vec3(1, 0, 0), q0, s);
  SetBodyVelocity(model, 0, Vec3(0.1, 0.2, 0.3), w, s);
  const Vec3 H0 = CalcAngularMomentum(model, s, Vec3::Zero());
  const double T0 = CalcRotationalKineticEnergy(model, s);
  EXPECT_TRUE(Near(T0, 0.5 * (m * L * L / 12) * w.squaredNorm(), 1e-14));
  SimulationOptions o;
  o.t_end = 2.5;
  const SimulationResult r = Simulate(model, s, o);
  const State& f = r.final_state;
  EXPECT_TRUE(test::MatNear(CalcAngularMomentum(model, f, Vec3::Zero()), H0, 1e-12, H0.norm()));
  EXPECT_TRUE(Near(CalcRotationalKineticEnergy(model, f), T0, 1e-12));
  EXPECT_NEAR(f.bodies[0].w_WB_B.z(), 0.0, 1e-15 * w.norm());  // no spin about the rod
  const Vec3 u = Eigen::AngleAxisd(w.norm() * o.t_end, w.normalized()) * u0;
  EXPECT_TRUE(test::MatNear(f.bodies[0].q_WB * Vec3::UnitZ(), u, 1e-9, 1.0));
}

// A rod (length L) sliding down a frictionless wall (x = 0) and floor (y = 0), gravity -y, at
// angle θ to the floor, released at rest at θ0. Centre (L/2)(cos θ, sin θ); energy:
//   (m L²/6) θ̇² = m g (L/2)(sin θ0 - sin θ)  ->  θ̇² = (3g/L)(sin θ0 - sin θ),
//   θ̈ = -(3g/2L) cos θ.
// The wall pushes N_w = m ẍ with ẍ = (L/2)(-sin θ θ̈ - cos θ θ̇²) = (3g/4) cos θ (3 sin θ - 2 sin
// θ0), zero at sin θ = (2/3) sin θ0 (from the vertical: cos φ = (2/3) cos φ0): the rod leaves the
// wall there. The floor pushes N_f = m g + m ÿ, ÿ = (L/2)(cos θ θ̈ - sin θ θ̇²).
// Both contacts are point_on_plane joints, which can pull: the instant the wall's push
// reaches zero is where a unilateral wall would let go.
TEST(ParticleAndRod, RodAgainstWallAndFloorLeavesTheWallAtTwoThirds) {
  const double m = 1.5, L = 2.0, th0 = 1.2;
  const double th_leave = std::asin(2.0 / 3.0 * std::sin(th0));
  for (const double th : {1.1, 0.9, th_leave, 0.5}) {
    Model model;
    model.AddBody("ladder", Rod(m, L));
    model.AddForceElement(std::make_shared<UniformGravity>("g", Vec3(0, -kG, 0)));
    State s = MakeRestState(model);
    const Vec3 top(0, L * std::sin(th), 0), bottom(L * std::cos(th), 0, 0);
    const Vec3 c = 0.5 * (top + bottom);
    const double thd = -std::sqrt(3 * kG / L * (std::sin(th0) - std::sin(th)));  // falling
    const double thdd = -1.5 * kG / L * std::cos(th);
    SetBodyPose(model, 0, c, Quat::FromTwoVectors(Vec3::UnitZ(), (top - bottom) / L), s);
    const Vec3 v = 0.5 * L * thd * Vec3(-std::sin(th), std::cos(th), 0);
    SetBodyVelocity(model, 0, v, Vec3(0, 0, -thd), s);  // the rod's direction turns at -θ̇
    model.AddConstraint(std::make_shared<Joint>(
        "wall", JointKind::kPointOnPlane, kWorld,
        AttachmentFrame{Vec3::Zero(), FrameWithZAxis(Vec3::UnitX())}, 0,
        AttachmentFrameAtWorldPose(model, s, 0, top, FrameWithZAxis(Vec3::UnitX()))));
    model.AddConstraint(std::make_shared<Joint>(
        "floor", JointKind::kPointOnPlane, kWorld,
        AttachmentFrame{Vec3::Zero(), FrameWithZAxis(Vec3::UnitY())}, 0,
        AttachmentFrameAtWorldPose(model, s, 0, bottom, FrameWithZAxis(Vec3::UnitY()))));
    const InstantaneousSolution sol = SolveInstantaneous(model, s);
    const double xdd = 0.75 * kG * std::cos(th) * (3 * std::sin(th) - 2 * std::sin(th0));
    const double ydd = 0.5 * L * (std::cos(th) * thdd - std::sin(th) * thd * thd);
    EXPECT_NEAR(sol.bodies[0].alpha_WB_W.z(), -thdd, 1e-12 * kG / L) << th;
    EXPECT_NEAR(sol.reactions[0].F_Jc_W.x(), m * xdd, 1e-12 * m * kG) << th;
    EXPECT_TRUE(Near(sol.reactions[1].F_Jc_W.y(), m * kG + m * ydd, 1e-12)) << th;
    if (th == th_leave) {
      EXPECT_NEAR(sol.reactions[0].F_Jc_W.x(), 0.0, 1e-12 * m * kG);
    }
  }
}

}  // namespace
}  // namespace chasles
