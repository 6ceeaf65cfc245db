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
