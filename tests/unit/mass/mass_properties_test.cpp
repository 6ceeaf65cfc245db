#include "chasles/mass/mass_properties.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "chasles/error.h"
#include "chasles/math/rotation.h"
#include "test_support.h"

namespace chasles {
namespace {

using test::kExact;
using test::MatNear;
using test::Near;

// Solid box a x b x c of mass m centred at the origin (Appendix A).
MassProperties Box(double m, double a, double b, double c, const Vec3& centre = Vec3::Zero()) {
  return MassProperties(m, centre,
                        RotationalInertia(m * (b * b + c * c) / 12, m * (a * a + c * c) / 12,
                                          m * (a * a + b * b) / 12));
}

TEST(MassProperties, DefaultIsNaN) {
  EXPECT_TRUE(std::isnan(MassProperties().mass()));
}

TEST(MassProperties, BoxSplitIntoEightEqualsWhole) {
  const double m = 8.0, a = 0.4, b = 0.6, c = 1.0;
  MassProperties sum = MassProperties::Zero();
  for (int i = 0; i < 8; ++i) {
    const Vec3 centre((i & 1 ? 1 : -1) * a / 4, (i & 2 ? 1 : -1) * b / 4, (i & 4 ? 1 : -1) * c / 4);
    sum = sum + Box(m / 8, a / 2, b / 2, c / 2, centre);
  }
  const MassProperties whole = Box(m, a, b, c);
  EXPECT_TRUE(Near(sum.mass(), m, kExact));
  EXPECT_TRUE(MatNear(sum.p_BoBcm_B(), Vec3::Zero(), kExact, 1.0));
  EXPECT_TRUE(MatNear(sum.I_BBcm_B().matrix(), whole.I_BBcm_B().matrix(), kExact));
}

TEST(MassProperties, SubtractingAPartGivesTheRest) {
  // A box with one octant removed, then the octant added back: the whole box again.
  const double m = 8.0, a = 0.4, b = 0.6, c = 1.0;
  const MassProperties octant = Box(m / 8, a / 2, b / 2, c / 2, Vec3(a / 4, b / 4, c / 4));
  const MassProperties rest = Box(m, a, b, c) + octant.Negated();
  EXPECT_TRUE(Near(rest.mass(), 7.0, kExact));
  // Centre of mass of the rest: -(1/7) of the octant's moment.
  EXPECT_TRUE(MatNear(rest.p_BoBcm_B(), Vec3(-a / 28, -b / 28, -c / 28), kExact));
  const MassProperties back = rest + octant;
  EXPECT_TRUE(MatNear(back.I_BBcm_B().matrix(), Box(m, a, b, c).I_BBcm_B().matrix(), 1e-14));
}

TEST(MassProperties, RemovingEverythingIsAnError) {
  const MassProperties box = Box(1, 1, 1, 1);
  EXPECT_THROW(box + box.Negated(), InputError);
  EXPECT_THROW(box + Box(2, 1, 1, 1).Negated(), InputError);
}

TEST(MassProperties, ExpressedInParentMovesAndRotates) {
  // A rod of length L along its own z axis, laid along the parent's y axis with its centre
  // at (0, L/2, 0): inertia about the parent origin is m L²/3 about x and z.
  const double m = 2, L = 3;
  const MassProperties rod(m, Vec3::Zero(), RotationalInertia(m * L * L / 12, m * L * L / 12, 0));
  const MassProperties placed =
      rod.ExpressedInParent(RotationTakingZTo(Vec3::UnitY()), Vec3(0, L / 2, 0));
  const RotationalInertia I_O = placed.CalcInertiaAbout(Vec3::Zero());
  EXPECT_TRUE(
      MatNear(I_O.matrix(), RotationalInertia(m * L * L / 3, 0, m * L * L / 3).matrix(), kExact));
}

TEST(MassProperties, FarFromOriginKeepsDigits) {
  // Offsets of 1/16 m are exact at 1e4 m, so any lost digit is the combination's fault.
  const Vec3 far(1e4, -2e4, 3e4);
  const MassProperties a = Box(1, 0.125, 0.2, 0.3, far + Vec3(0.0625, 0, 0));
  const MassProperties b = Box(1, 0.125, 0.2, 0.3, far - Vec3(0.0625, 0, 0));
  const MassProperties ab = a + b;
  EXPECT_TRUE(MatNear(ab.I_BBcm_B().matrix(), Box(2, 0.25, 0.2, 0.3).I_BBcm_B().matrix(), kExact));
  EXPECT_TRUE(MatNear(ab.p_BoBcm_B(), far, kExact));
}

TEST(MassProperties, ValidateNamesTheProblem) {
  try {
    MassProperties(-1, Vec3::Zero(), RotationalInertia(1, 1, 1)).Validate("body 'arm'");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), ::testing::HasSubstr("body 'arm': mass is -1 kg"));
  }
}

}  // namespace
}  // namespace chasles
