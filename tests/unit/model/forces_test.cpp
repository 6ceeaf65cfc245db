// Force elements whose line of action is fixed in the world (a force at a world point, a cable
// to a fixed winch) and the torque across a joint: resultants, moments and power against
// hand-derived values at random states (seeded), each to round-off.

#include "chasles/model/forces.h"

#include <random>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "chasles/dynamics/newton_euler.h"
#include "chasles/error.h"
#include "chasles/model/data.h"
#include "chasles/model/model.h"
#include "chasles/model/state.h"
#include "test_support.h"

namespace chasles {
namespace {

using ::testing::HasSubstr;

MassProperties Brick() {
  return MassProperties(2.0, Vec3(0.1, -0.2, 0.05), RotationalInertia(0.3, 0.4, 0.5, 0, 0, 0));
}

// A state with a random pose and velocities (the unit quaternion from a normal sample).
void Randomize(State& s, std::mt19937& rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  for (BodyState& b : s.bodies) {
    b.p_WBcm = Vec3(n(rng), n(rng), n(rng));
    b.q_WB = Quat(n(rng), n(rng), n(rng), n(rng)).normalized();
    b.v_WBcm_W = Vec3(n(rng), n(rng), n(rng));
    b.w_WB_B = Vec3(n(rng), n(rng), n(rng));
  }
}

// A force at a world point P acts on the material point at P: moment (p_WP - p_WBcm) × F about
// Bcm, power F·(v_Bcm + w × (p_WP - p_WBcm)).
TEST(Forces, ForceAtAWorldPointActsOnTheMaterialPointThere) {
  std::mt19937 rng(17);
  for (int trial = 0; trial < 20; ++trial) {
    Model m;
    const BodyIndex b = m.AddBody("b", Brick());
    const Vec3 p_WP(0.3, -1.2, 0.7), F(2.0, -1.0, 0.5);
    m.AddForceElement(std::make_shared<AppliedForce>(
        "f", b, p_WP, VectorFrame::kWorld, [F](const Model&, const State&) { return F; },
        VectorFrame::kWorld));
    State s = MakeRestState(m);
    Randomize(s, rng);
    Data d = MakeData(m);
    CalcAccelerations(m, s, d);
    const Vec3 r = p_WP - s.bodies[0].p_WBcm;
    const Vec3 w_W = s.bodies[0].q_WB * s.bodies[0].w_WB_B;
    EXPECT_TRUE(test::MatNear(d.F_Bcm_W[0], F, test::kExact));
    EXPECT_TRUE(test::MatNear(d.M_Bcm_W[0], r.cross(F), test::kExact, 10.0));
    EXPECT_TRUE(test::Near(d.elements[0].power, F.dot(s.bodies[0].v_WBcm_W + w_W.cross(r)),
                           test::kExact, 10.0));
  }
}

// A cable from body point P to world point Q: F = T (Q - P)/|Q - P|, whatever the pose.
TEST(Forces, CablePullsAlongTheLineToTheWinch) {
  std::mt19937 rng(5);
  for (int trial = 0; trial < 20; ++trial) {
    Model m;
    const BodyIndex b = m.AddBody("b", Brick());
    const Vec3 p_BoP_B(0.4, 0.1, -0.3), p_WQ(2.0, 1.0, -0.5);
    const double T = 7.5;
    m.AddForceElement(std::make_shared<CableForce>("c", b, p_BoP_B, p_WQ,
                                                   [T](const Model&, const State&) { return T; }));
    State s = MakeRestState(m);
    Randomize(s, rng);
    Data d = MakeData(m);
    CalcAccelerations(m, s, d);
    const Mat3 R = s.bodies[0].q_WB.toRotationMatrix();
    const Vec3 r = R * (p_BoP_B - Brick().p_BoBcm_B());
    const Vec3 u = (p_WQ - s.bodies[0].p_WBcm - r).normalized();
    EXPECT_TRUE(test::MatNear(d.F_Bcm_W[0], T * u, test::kExact));
    EXPECT_TRUE(test::MatNear(d.M_Bcm_W[0], r.cross(T * u), test::kExact, T));
  }
  Model m;
  const BodyIndex b = m.AddBody("b", Brick());
  m.AddForceElement(std::make_shared<CableForce>("c", b, Vec3::Zero(), Vec3(5, 0, 0),
                                                 [](const Model&, const State&) { return -1.0; }));
  State s = MakeRestState(m);
  Data d = MakeData(m);
  try {
    CalcAccelerations(m, s, d);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("a cable can only pull"));
  }
}

// A string pulled by hand off a drum (axis a, centre c, radius r): it leaves the drum at the
// point T where the drum's tangent in its sense s is the pull's in-plane direction d̂_p, i.e.
// ρ = T - c with |ρ| = r, ρ·a = 0 and s (a × ρ)/r = d̂_p (counterclockwise about a is a × ρ).
// The force is P d (d the full unit direction, its axial part kept), its moment about Bcm
// (T - p_cm) × P d and its power P d·(v + ω × (T - p_cm)). Random 3D states, a tilted drum
// axis and a direction off the drum's plane.
TEST(Forces, StringPullActsWhereTheStringLeavesTheDrum) {
  std::mt19937 rng(12);
  for (int trial = 0; trial < 20; ++trial) {
    for (const int sense : {1, -1}) {
      Model m;
      const BodyIndex b = m.AddBody("spool", Brick());
      const Vec3 p_BoC_B(0.1, -0.2, 0.05), axis_B(0.3, -0.2, 1.0), d_W(0.8, 0.5, -0.3);
      const double r = 0.07, P = 4.5;
      const auto pull = std::make_shared<StringPull>("hand", b, p_BoC_B, axis_B, r, sense, d_W,
                                                     [P](const Model&, const State&) { return P; });
      m.AddForceElement(pull);
      State s = MakeRestState(m);
      Randomize(s, rng);
      Data d = MakeData(m);
      CalcAccelerations(m, s, d);
      const Mat3 R = s.bodies[0].q_WB.toRotationMatrix();
      const Vec3 a = (R * axis_B).normalized();
      const Vec3 c = s.bodies[0].p_WBcm + R * (p_BoC_B - Brick().p_BoBcm_B());
      const Vec3 u = d_W.normalized();
      const Vec3 u_p = (u - a * a.dot(u)).normalized();
      const Vec3 T = pull->CalcTangentPoint(m, s, d);
      const Vec3 rho = T - c;
      EXPECT_TRUE(test::Near(rho.norm(), r, test::kExact));
      EXPECT_TRUE(test::Near(rho.dot(a), 0.0, test::kExact, r));
      EXPECT_TRUE(test::MatNear(sense * a.cross(rho) / r, u_p, test::kExact, 1.0)) << sense;
      const Vec3 arm = T - s.bodies[0].p_WBcm;
      EXPECT_TRUE(test::MatNear(d.F_Bcm_W[0], P * u, test::kExact));
      EXPECT_TRUE(test::MatNear(d.M_Bcm_W[0], arm.cross(P * u), test::kExact, P));
      const Vec3 v_T = s.bodies[0].v_WBcm_W + (R * s.bodies[0].w_WB_B).cross(arm);
      EXPECT_TRUE(test::Near(d.elements[0].power, P * u.dot(v_T), test::kExact, P));
    }
  }
  const auto P = [](const Model&, const State&) { return 1.0; };
  const Vec3 z = Vec3::UnitZ(), x = Vec3::UnitX();
  EXPECT_THROW(StringPull("h", 0, Vec3::Zero(), z, 0.0, 1, x, P), InputError);
  EXPECT_THROW(StringPull("h", 0, Vec3::Zero(), z, 0.1, 2, x, P), InputError);
  EXPECT_THROW(StringPull("h", 0, Vec3::Zero(), Vec3::Zero(), 0.1, 1, x, P), InputError);
  EXPECT_THROW(StringPull("h", 0, Vec3::Zero(), z, 0.1, 1, Vec3::Zero(), P), InputError);
  // Pulling along the axis, or pushing, stops the evaluation.
  for (const auto& [dir, tension] : {std::pair{z, 1.0}, std::pair{x, -1.0}}) {
    Model m;
    const BodyIndex b = m.AddBody("spool", Brick());
    const double T = tension;
    m.AddForceElement(std::make_shared<StringPull>("h", b, Vec3::Zero(), z, 0.1, 1, dir,
                                                   [T](const Model&, const State&) { return T; }));
    State s = MakeRestState(m);
    Data d = MakeData(m);
    try {
      CalcAccelerations(m, s, d);
      FAIL();
    } catch (const InputError& e) {
      EXPECT_THAT(e.what(), HasSubstr(tension < 0 ? "can only pull" : "along the drum's axis"));
    }
  }
}

// A joint torque: +tau a on the child, -tau a on the parent (no net moment on the pair), a
// turning with the parent; power tau a·(w_child - w_parent).
TEST(Forces, JointTorqueIsEqualAndOppositeAcrossTheJoint) {
  std::mt19937 rng(11);
  for (int trial = 0; trial < 20; ++trial) {
    Model m;
    const BodyIndex p = m.AddBody("car", Brick());
    const BodyIndex c = m.AddBody("wheel", Brick());
    const Vec3 axis_P(0.0, 2.0, 0.0);  // any length: normalised
    const double tau = -3.25;
    m.AddForceElement(std::make_shared<JointTorque>(
        "drive", p, c, axis_P, [tau](const Model&, const State&) { return tau; }));
    State s = MakeRestState(m);
    Randomize(s, rng);
    Data d = MakeData(m);
    CalcAccelerations(m, s, d);
    const Vec3 a_W = s.bodies[0].q_WB * Vec3(0, 1, 0);
    const Vec3 w_p = s.bodies[0].q_WB * s.bodies[0].w_WB_B;
    const Vec3 w_c = s.bodies[1].q_WB * s.bodies[1].w_WB_B;
    EXPECT_TRUE(test::MatNear(d.M_Bcm_W[1], tau * a_W, test::kExact));
    EXPECT_TRUE(test::MatNear(d.M_Bcm_W[0], -tau * a_W, test::kExact));
    EXPECT_TRUE(test::MatNear(d.F_Bcm_W[0] + d.F_Bcm_W[1], Vec3::Zero(), test::kExact, 10.0));
    EXPECT_TRUE(test::MatNear(d.elements[0].moment_Wo_W, Vec3::Zero(), test::kExact, 10.0));
    EXPECT_TRUE(test::Near(d.elements[0].power, tau * a_W.dot(w_c - w_p), test::kExact, 10.0));
  }
  EXPECT_THROW(
      JointTorque("t", 0, 0, Vec3::UnitY(), [](const Model&, const State&) { return 1.0; }),
      InputError);
  EXPECT_THROW(
      JointTorque("t", kWorld, 0, Vec3::Zero(), [](const Model&, const State&) { return 1.0; }),
      InputError);
}

}  // namespace
}  // namespace chasles
