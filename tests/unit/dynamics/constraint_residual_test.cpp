// Constraint residuals by unit against the state's scales: round-off passes, a real
// violation is found with its size.

#include "chasles/dynamics/constraint_residual.h"

#include <memory>

#include <gtest/gtest.h>

#include "chasles/model/constraints.h"
#include "test_support.h"

namespace chasles {
namespace {

// A rod (m, L) pinned at the origin about y, its centre of mass at (L/2, 0, 0), turning at w:
// on the joint, v_cm = w j x (L/2) i = -(w L/2) k.
struct PinnedRod {
  static constexpr double m = 2.0, L = 1.5, w = 3.0;
  Model model;
  State state;
  PinnedRod() {
    model.AddBody("rod", MassProperties(m, Vec3(L / 2, 0, 0),
                                        RotationalInertia(1e-4, m * L * L / 12, m * L * L / 12)));
    state = MakeRestState(model);
    SetBodyPose(model, 0, Vec3::Zero(), Quat::Identity(), state);
    SetBodyVelocity(model, 0, Vec3::Zero(), Vec3(0, w, 0), state);
    const Mat3 R = FrameWithZAxis(Vec3::UnitY());
    model.AddConstraint(std::make_shared<Joint>(
        "pin", JointKind::kRevolute, kWorld, AttachmentFrame{Vec3::Zero(), R}, 0,
        AttachmentFrameAtWorldPose(model, state, 0, Vec3::Zero(), R)));
  }
};

TEST(ConstraintResidual, ScalesAreTheStatesOwn) {
  PinnedRod rod;
  Data data = MakeData(rod.model);
  const ConstraintScales s = CalcConstraintScales(rod.model, rod.state, data);
  // Length: the centre's distance L/2 = 0.75 m exceeds the radius of gyration
  // sqrt(tr I / m) = sqrt(2 L²/12 + 5e-5) = 0.61 m; velocity: |v_cm| = w L/2 = |w| L_s.
  EXPECT_NEAR(s.length, PinnedRod::L / 2, 1e-15);
  EXPECT_NEAR(s.velocity, PinnedRod::w * PinnedRod::L / 2, 1e-15);
}

TEST(ConstraintResidual, RoundOffIsNotAViolationButARealOneIsWithItsSizeAndUnit) {
  PinnedRod rod;
  Data data = MakeData(rod.model);
  const ConstraintScales s = CalcConstraintScales(rod.model, rod.state, data);
  EXPECT_TRUE(FindConstraintViolations(rod.model, rod.state, data, s).empty());
  // A few ulps of the velocity scale: still round-off.
  State near = rod.state;
  near.bodies[0].v_WBcm_W.x() += 1e-14 * s.velocity;
  EXPECT_TRUE(FindConstraintViolations(rod.model, near, data, s).empty());
  // The centre of mass at rest while the rod turns: the pin point would move at
  // |w x (0 - r_cm)| = w L/2 along +z; a velocity residual in m/s, no position residual.
  State off = rod.state;
  off.bodies[0].v_WBcm_W.setZero();
  const auto v = FindConstraintViolations(rod.model, off, data, s);
  ASSERT_EQ(v.size(), 1u);
  EXPECT_EQ(v[0].constraint, 0);
  EXPECT_TRUE(v[0].velocity_violated);
  EXPECT_FALSE(v[0].position_violated);
  EXPECT_NEAR(v[0].velocity_linear, PinnedRod::w * PinnedRod::L / 2, 1e-15);
  EXPECT_NEAR(v[0].velocity_angular, 0.0, 1e-15);
  // Spinning about x as well: the axis rows' residual is an angular velocity [rad/s].
  State tilt = rod.state;
  tilt.bodies[0].w_WB_B.x() = 0.5;
  const auto t = FindConstraintViolations(rod.model, tilt, data, s);
  ASSERT_EQ(t.size(), 1u);
  EXPECT_NEAR(t[0].velocity_angular, 0.5, 1e-15);
}

}  // namespace
}  // namespace chasles
