// A Data belongs to the Model MakeData made it for (data.h): every algorithm taking
// (model, ..., data) refuses a Data made for another Model with a UsageError.

#include "chasles/model/data.h"

#include <utility>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "chasles/dynamics/constraint_solve.h"
#include "chasles/dynamics/contact_solve.h"
#include "chasles/dynamics/newton_euler.h"
#include "chasles/error.h"
#include "chasles/model/constraints.h"
#include "chasles/model/forces.h"
#include "chasles/model/model.h"
#include "test_support.h"

namespace chasles {
namespace {

using testing::HasSubstr;
using testing::ThrowsMessage;

constexpr const char* kOtherModel = "this Data was made for another Model";

// One free body of mass m = 2 kg under uniform gravity g: a = g (eqs. 8.76-8.78, m a = m g).
Model FallingBody(double g) {
  Model m;
  m.AddBody("ball", MassProperties(2.0, Vec3::Zero(), RotationalInertia(1, 1, 1)));
  m.AddForceElement(std::make_shared<UniformGravity>("gravity", Vec3(0, 0, -g)));
  return m;
}

TEST(Data, RefusesAnotherModel) {
  const Model a = FallingBody(9.81);
  const Model b = FallingBody(9.81);  // the same structure, another Model
  Data data = MakeData(a);
  const State s = MakeRestState(b);
  EXPECT_THAT([&] { CalcAccelerations(b, s, data); },
              ThrowsMessage<UsageError>(HasSubstr(kOtherModel)));
  EXPECT_THAT([&] { CalcForces(b, s, data); }, ThrowsMessage<UsageError>(HasSubstr(kOtherModel)));
  EXPECT_THAT([&] { CalcKinematics(b, s, data); },
              ThrowsMessage<UsageError>(HasSubstr("make one with MakeData(model)")));
  // A UsageError is a std::logic_error (a bug in the caller), not an InputError (bad input).
  EXPECT_THROW(CalcAccelerations(b, s, data), std::logic_error);
}

TEST(Data, WorksWithItsModelAndCopiesBelongToIt) {
  const double g = 9.81;
  const Model model = FallingBody(g);
  const State s = MakeRestState(model);
  Data data = MakeData(model);
  CalcAccelerations(model, s, data);
  EXPECT_TRUE(test::MatNear(data.a_WBcm_W[0], Vec3(0, 0, -g), test::kExact));
  Data copy = data;
  copy.a_WBcm_W[0].setZero();
  CalcAccelerations(model, s, copy);
  EXPECT_TRUE(test::MatNear(copy.a_WBcm_W[0], Vec3(0, 0, -g), test::kExact));
}

TEST(Data, ModelCopyIsAnotherModelAndMoveKeepsIt) {
  Model model = FallingBody(1.0);
  const Data data = MakeData(model);
  const Model copy = model;
  EXPECT_NE(copy.id(), model.id());
  Data d1 = data;
  EXPECT_THAT([&] { CalcAccelerations(copy, MakeRestState(copy), d1); },
              ThrowsMessage<UsageError>(HasSubstr(kOtherModel)));
  const std::uint64_t id = model.id();
  const Model moved = std::move(model);
  EXPECT_EQ(moved.id(), id);
  Data d2 = data;
  CalcAccelerations(moved, MakeRestState(moved), d2);
  EXPECT_TRUE(test::MatNear(d2.a_WBcm_W[0], Vec3(0, 0, -1.0), test::kExact));
}

TEST(Data, StaleAfterTheModelGrowsAndUnmadeDataRefused) {
  Model model = FallingBody(1.0);
  Data data = MakeData(model);
  model.AddBody("second", MassProperties(1.0, Vec3::Zero(), RotationalInertia(1, 1, 1)));
  EXPECT_THAT([&] { CalcAccelerations(model, MakeRestState(model), data); },
              ThrowsMessage<UsageError>(HasSubstr(kOtherModel)));
  Data unmade;
  EXPECT_THAT([&] { CalcAccelerations(model, MakeRestState(model), unmade); },
              ThrowsMessage<UsageError>(HasSubstr("this Data was not made by MakeData")));
}

TEST(Data, ConstraintAndContactEntryPointsCheckToo) {
  Model a = FallingBody(1.0);
  a.AddConstraint(std::make_shared<Joint>("pin", JointKind::kSpherical, kWorld,
                                          AttachmentFrame{Vec3::Zero()}, 0,
                                          AttachmentFrame{Vec3::Zero()}));
  Model b = a;
  Data data = MakeData(a);
  State s = MakeRestState(b);
  EXPECT_THAT([&] { ProjectOntoConstraints(b, s, data); },
              ThrowsMessage<UsageError>(HasSubstr(kOtherModel)));
  EXPECT_THAT([&] { SolveContactForces(b, s, data); },
              ThrowsMessage<UsageError>(HasSubstr(kOtherModel)));
}

}  // namespace
}  // namespace chasles
