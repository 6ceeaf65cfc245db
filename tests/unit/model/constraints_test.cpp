// Constraint building blocks: joint frames, attachment at a world pose, and the validation of
// constraint input.

#include "chasles/model/constraints.h"

#include <memory>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "chasles/dynamics/newton_euler.h"
#include "chasles/error.h"
#include "chasles/math/rotation.h"
#include "chasles/model/data.h"
#include "chasles/model/model.h"
#include "chasles/model/state.h"
#include "test_support.h"

namespace chasles {
namespace {

using test::kExact;
using test::MatNear;
using ::testing::HasSubstr;

TEST(FrameWithZAxis, IsARightHandedFrameWithTheGivenZ) {
  for (const Vec3& axis : {Vec3(0, 0, 2), Vec3(1, 0, 0), Vec3(0.3, -1.2, 0.7)}) {
    const Mat3 R = FrameWithZAxis(axis);
    EXPECT_TRUE(MatNear(Mat3(R.transpose() * R), Mat3::Identity(), kExact));
    EXPECT_NEAR(R.determinant(), 1.0, kExact);
    EXPECT_TRUE(MatNear(Vec3(R.col(2)), Vec3(axis.normalized()), kExact));
  }
  EXPECT_THAT([] { FrameWithZAxis(Vec3::Zero()); },
              ::testing::ThrowsMessage<InputError>(HasSubstr("axis direction is zero")));
}

// A frame attached at a world pose coincides with that pose: every row of a weld between the
// world frame and the attached frame has zero position error.
TEST(AttachmentFrameAtWorldPose, CoincidesWithThePoseItWasMadeFrom) {
  Model model;
  model.AddBody("b", MassProperties(2.0, Vec3(0.1, 0.2, -0.3),
                                    RotationalInertia::FromMatrix(Vec3(1, 2, 2.5).asDiagonal())));
  State s = MakeRestState(model);
  SetBodyPose(model, 0, Vec3(0.4, -0.2, 1.0), Quat(RotationFromEuler("ZYX", Vec3(0.3, 0.2, -0.5))),
              s);
  const Vec3 p_WJ(1.0, 0.5, -0.25);
  const Mat3 R_WJ = RotationFromEuler("ZYX", Vec3(-0.7, 0.1, 0.4));
  const Joint weld("w", JointKind::kWeld, kWorld, AttachmentFrame{p_WJ, R_WJ}, 0,
                   AttachmentFrameAtWorldPose(model, s, 0, p_WJ, R_WJ));
  Data data = MakeData(model);
  CalcKinematics(model, s, data);
  ConstraintEval e;
  weld.Evaluate(model, s, data, e);
  EXPECT_TRUE(MatNear(e.position_error, ConstraintEval::Column::Zero(), kExact, 1.0));
  EXPECT_TRUE(MatNear(e.p_WJ, p_WJ, kExact));
}

TEST(Constraints, InputIsValidated) {
  Model model;
  model.AddBody("b",
                MassProperties(1.0, Vec3::Zero(), RotationalInertia::FromMatrix(Mat3::Identity())));
  model.AddConstraint(std::make_shared<Joint>("j", JointKind::kSpherical, kWorld,
                                              AttachmentFrame{Vec3::Zero()}, 0,
                                              AttachmentFrame{Vec3::Zero()}));
  EXPECT_THAT(
      [&] {
        model.AddConstraint(std::make_shared<Joint>("j", JointKind::kSpherical, kWorld,
                                                    AttachmentFrame{Vec3::Zero()}, 0,
                                                    AttachmentFrame{Vec3::Zero()}));
      },
      ::testing::ThrowsMessage<InputError>(HasSubstr("constraint 'j' is defined twice")));
  EXPECT_THAT(
      [] {
        Joint("k", JointKind::kRevolute, 0, AttachmentFrame{Vec3::Zero()}, kWorld,
              AttachmentFrame{Vec3::Zero()});
      },
      ::testing::ThrowsMessage<InputError>(HasSubstr("the child is the world")));
  EXPECT_THAT(
      [] {
        Joint("k", JointKind::kRevolute, kWorld, AttachmentFrame{}, 0,
              AttachmentFrame{Vec3::Zero()});
      },
      ::testing::ThrowsMessage<InputError>(HasSubstr("non-finite origin")));
  EXPECT_THAT(
      [] {
        PrescribedMotion("d", DriverKind::kTranslation, kWorld, AttachmentFrame{Vec3::Zero()}, 0,
                         AttachmentFrame{Vec3::Zero()}, TimeFunction{});
      },
      ::testing::ThrowsMessage<InputError>(HasSubstr("needs f(t), its rate and its acceleration")));
  EXPECT_EQ(model.FindConstraint("j"), 0);
  EXPECT_THAT([&] { model.FindConstraint("x"); },
              ::testing::ThrowsMessage<InputError>(HasSubstr("the constraints are: j")));
  EXPECT_EQ(model.num_constraint_rows(), 3);
}

TEST(GearMesh, InputIsValidated) {
  const PitchCircle sun{Vec3::Zero(), Vec3::UnitZ(), 0.1};
  EXPECT_THAT(
      [&] {
        GearMesh("m", GearKind::kExternal, kWorld, sun, 0,
                 PitchCircle{Vec3(0.14, 0, 0), Vec3::UnitZ(), 0.0}, false);
      },
      ::testing::ThrowsMessage<InputError>(
          HasSubstr("gear mesh 'm': the child pitch radius is 0 m; it must be a positive length")));
  EXPECT_THAT(
      [&] {
        GearMesh("m", GearKind::kInternal, kWorld, sun, 0,
                 PitchCircle{Vec3(0.14, 0, 0), Vec3::UnitZ(), 0.2}, false);
      },
      ::testing::ThrowsMessage<InputError>(HasSubstr("smaller than the ring's")));
  EXPECT_THAT(
      [&] {
        GearMesh("m", GearKind::kExternal, kWorld, sun, 0,
                 PitchCircle{Vec3(0.14, 0, 0), Vec3::Zero(), 0.04}, false);
      },
      ::testing::ThrowsMessage<InputError>(HasSubstr("the child gear's axis is zero")));
  // A face gear's parent needs no radius; the rows count the contact row.
  const GearMesh face("f", GearKind::kFace, kWorld, PitchCircle{Vec3::Zero(), Vec3::UnitZ()}, 0,
                      PitchCircle{Vec3(0.3, 0, 0.1), Vec3::UnitX(), 0.1}, true);
  EXPECT_EQ(face.num_rows(), 2);
  EXPECT_EQ(face.kind(), "face gear mesh");
}

}  // namespace
}  // namespace chasles
