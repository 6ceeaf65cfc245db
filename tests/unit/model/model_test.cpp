#include "chasles/model/model.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "chasles/dynamics/newton_euler.h"
#include "chasles/error.h"
#include "chasles/model/forces.h"
#include "test_support.h"

namespace chasles {
namespace {

using testing::HasSubstr;
using testing::ThrowsMessage;

MassProperties Unit() {
  return MassProperties(1.0, Vec3::Zero(), RotationalInertia(1, 1, 1));
}

TEST(Model, RejectsDuplicateBodyAndUnknownIndex) {
  Model m;
  m.AddBody("a", Unit());
  EXPECT_THAT([&] { m.AddBody("a", Unit()); },
              ThrowsMessage<InputError>(HasSubstr("body 'a' is defined twice")));
  EXPECT_THAT([&] { m.AddForceElement(std::make_shared<LinearDrag>("d", 3, 1.0, 0.0)); },
              ThrowsMessage<InputError>(HasSubstr("acts on body index 3")));
  EXPECT_THAT([&] { m.FindBody("b"); }, ThrowsMessage<InputError>(HasSubstr("the bodies are: a")));
}

// The name table (NameIndex) keeps duplicate detection and FindBody exact for many bodies: a
// repeat of any earlier name is refused with the same message as before, whichever body it
// repeats, and the refused body leaves the model as it was.
TEST(Model, RefusesDuplicatesAmongManyBodiesWithTheSameMessage) {
  Model m;
  const int n = 5000;
  for (int i = 0; i < n; ++i) EXPECT_EQ(m.AddBody("b" + std::to_string(i), Unit()), i);
  for (int i : {0, 1, 2499, n - 1}) {
    const std::string name = "b" + std::to_string(i);
    EXPECT_THAT([&] { m.AddBody(name, Unit()); },
                ThrowsMessage<InputError>(testing::StrEq(
                    "body '" + name + "' is defined twice; give each body its own name")));
    EXPECT_EQ(m.FindBody(name), i);
  }
  EXPECT_EQ(m.num_bodies(), n);
  // A body refused for its mass properties does not take its name.
  EXPECT_THROW(m.AddBody("bad", MassProperties(1.0, Vec3::Zero(), RotationalInertia(0, 0, 1))),
               InputError);
  EXPECT_EQ(m.AddBody("bad", Unit()), n);
  // A copy keeps the table; the names of force elements are checked the same way.
  const Model copy = m;
  EXPECT_EQ(copy.FindBody("b4321"), 4321);
  m.AddForceElement(std::make_shared<LinearDrag>("d", 0, 1.0, 0.0));
  EXPECT_THAT([&] { m.AddForceElement(std::make_shared<LinearDrag>("d", 1, 1.0, 0.0)); },
              ThrowsMessage<InputError>(testing::StrEq(
                  "force element 'd' is defined twice; give each force element its own name")));
  EXPECT_EQ(m.FindForceElement("d"), 0);
  EXPECT_THAT([&] { m.FindForceElement("e"); },
              ThrowsMessage<InputError>(HasSubstr("the force elements are: d")));
}

TEST(Model, TakesSlenderRodsAndPointMassesRejectsNegativeStiffness) {
  Model m;
  // A rod (one zero moment) and a point mass (three) are bodies; a tensor with two zero moments
  // and a positive third is no mass distribution (the triangle inequality I_3 <= I_1 + I_2).
  const BodyIndex rod =
      m.AddBody("rod", MassProperties(1.0, Vec3::Zero(), RotationalInertia(0, 1, 1)));
  const BodyIndex point =
      m.AddBody("point", MassProperties(1.0, Vec3::Zero(), RotationalInertia(0, 0, 0)));
  EXPECT_EQ(m.body(rod).num_zero_moments(), 1);
  EXPECT_FALSE(m.body(rod).is_particle());
  EXPECT_EQ(m.body(point).num_zero_moments(), 3);
  EXPECT_TRUE(m.body(point).is_particle());
  EXPECT_THROW(
      m.AddBody("impossible", MassProperties(1.0, Vec3::Zero(), RotationalInertia(0, 0, 1))),
      InputError);
  EXPECT_THAT(
      [&] { SpringDamper("s", 0, Vec3::Zero(), kWorld, Vec3::Zero(), 1.0, -5.0, 0.0); },
      ThrowsMessage<InputError>(HasSubstr("stiffness is -5 N/m; it must be a finite number >= 0")));
}

// Euler's equations with a full tensor: for a non-principal frame the gyroscopic term
// w × (I w) must use the products of inertia. With M = 0, ẇ = -I⁻¹ (w × I w).
TEST(NewtonEuler, FullTensorGyroscopicTerm) {
  const RotationalInertia I(2.0, 3.0, 4.0, 0.1, -0.2, 0.3);
  Model m;
  m.AddBody("b", MassProperties(2.0, Vec3::Zero(), I));
  State s = MakeRestState(m);
  s.bodies[0].w_WB_B = Vec3(1.0, -2.0, 0.5);
  Data d = MakeData(m);
  CalcAccelerations(m, s, d);
  const Vec3 w = s.bodies[0].w_WB_B;
  const Vec3 expected = -I.matrix().inverse() * w.cross(I.matrix() * w);
  EXPECT_TRUE(test::MatNear(d.wdot_WB_B[0], expected, test::kExact));
}

TEST(Forces, SpringPowerSplitsIntoConservativeAndDamperParts) {
  Model m;
  const BodyIndex b = m.AddBody("b", Unit());
  const double k = 10, c = 2, L0 = 1;
  m.AddForceElement(
      std::make_shared<SpringDamper>("s", b, Vec3::Zero(), kWorld, Vec3::Zero(), L0, k, c));
  State s = MakeRestState(m);
  s.bodies[0].p_WBcm = Vec3(1.5, 0, 0);
  s.bodies[0].v_WBcm_W = Vec3(0.3, 0, 0);
  Data d = MakeData(m);
  CalcAccelerations(m, s, d);
  // L = 1.5, L̇ = 0.3: tension k(L - L0) + c L̇ pulls the body back; P = -tension L̇.
  const double tension = k * 0.5 + c * 0.3;
  EXPECT_TRUE(test::MatNear(d.F_Bcm_W[0], Vec3(-tension, 0, 0), test::kExact));
  EXPECT_TRUE(test::Near(d.elements[0].power, -tension * 0.3, test::kExact));
  EXPECT_TRUE(test::Near(d.elements[0].power_nonconservative, -c * 0.3 * 0.3, test::kExact));
  EXPECT_TRUE(
      test::Near(m.force_element(0).CalcPotentialEnergy(m, s), 0.5 * k * 0.25, test::kExact));
}

}  // namespace
}  // namespace chasles
