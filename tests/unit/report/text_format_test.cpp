#include "chasles/report/text_format.h"

#include <cmath>
#include <limits>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "chasles/error.h"

namespace chasles {
namespace {

using ::testing::HasSubstr;

const UnitSystem kSI = UnitSystem::Parse("SI");
const UnitSystem kUS = UnitSystem::Parse("US");

TEST(CleanRoundOff, AtMostTheThresholdTimesTheScaleIsZero) {
  // |x| <= threshold * scale: 1e-12 of a scale of 1 is round-off, twice that is not.
  EXPECT_EQ(CleanRoundOff(1e-12, 1.0), 0.0);
  EXPECT_EQ(CleanRoundOff(-1e-12, 1.0), 0.0);
  EXPECT_EQ(CleanRoundOff(2e-12, 1.0), 2e-12);
  EXPECT_EQ(CleanRoundOff(2e-12, 1.0, kMassRoundOff), 2e-12);
  EXPECT_EQ(CleanRoundOff(1e-13, 1.0, kMassRoundOff), 0.0);
  // No scale: only an exact zero is round-off.
  EXPECT_EQ(CleanRoundOff(1e-300, 0.0), 1e-300);
}

TEST(Show, EachReportKeepsItsOwnThreshold) {
  // 5e-13 beside 1 N: round-off for simulate and solve (1e-12), a value for mass (1e-13).
  const Vec3 f(1.0, 5e-13, 0.0);
  EXPECT_EQ((Show{kSI})(f, kForce), "[1, 0, 0] N");
  EXPECT_EQ((Show{kSI, 9, kMassRoundOff})(f, kForce), "[1, 5e-13, 0] N");
}

TEST(Show, ANegativeZeroPrintsAsZero) {
  EXPECT_EQ((Show{kSI})(-0.0, kForce), "0 N");
  EXPECT_EQ((Show{kSI})(-1.0 * 0.0, kDimensionless), "0");
  EXPECT_EQ((Show{kSI}).Energy(-0.0), "0 J");
}

TEST(Show, ComponentsBesideTheScaleOfTheirKindAreRoundOff) {
  const Show show{kSI};
  // The example of the header: a student reads [2.83, 0, -1.63], not [2.83, -2.5e-32, -1.63].
  EXPECT_EQ(show(Vec3(2.83, -2.5e-32, -1.63), kAcceleration), "[2.83, 0, -1.63] m/s^2");
  // A small vector beside a large one of its kind (the scale) is round-off as a whole ...
  EXPECT_EQ(show(Vec3(1e-13, 0.0, 0.0), kForce, Angular::kNo, 1.0), "[0, 0, 0] N");
  // ... and by itself keeps its digits.
  EXPECT_EQ(show(Vec3(1e-13, 0.0, 0.0), kForce), "[1e-13, 0, 0] N");
  // The in-plane components of a planar scene's vector; z does not enter their scale.
  EXPECT_EQ(show.Xy(Vec3(3.0, 1e-11, 1e9), kVelocity), "[3, 1e-11] m/s");
  EXPECT_EQ(show.InPlane(true, Vec3(3.0, 4.0, 0.0), kLength), "[3, 4] m");
  EXPECT_EQ(show.InPlane(false, Vec3(3.0, 4.0, 0.0), kLength), "[3, 4, 0] m");
}

TEST(Show, ConvertsFromSIWithItsDigits) {
  // 1 m = 1/0.0254 in = 39.37007874... in (the inch is 25.4 mm exactly).
  EXPECT_EQ((Show{kUS})(1.0, kLength), "39.3700787 in");
  EXPECT_EQ((Show{kUS, 7})(1.0, kLength), "39.37008 in");
  EXPECT_EQ((Show{kSI}).Time(2.5), "2.5 s");
  // An energy is a moment's dimension; in SI it is named the joule.
  EXPECT_EQ((Show{kSI}).Energy(2.0), "2 J");
  EXPECT_EQ((Show{kSI})(2.0, kMoment), "2 N*m");
  EXPECT_EQ((Show{kSI}).Num(std::acos(-1.0), kRate, Angular::kYes), "3.14159265");
}

TEST(Show, AValueThatIsNotFiniteNamesItsReport) {
  const Show show{kSI, 9, kRunRoundOff, "a value of the test report"};
  try {
    show(std::numeric_limits<double>::quiet_NaN(), kForce);
    ADD_FAILURE() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("a value of the test report"));
  }
}

TEST(TitleLine, TheTitleWithItsFileOrTheFileAlone) {
  Scene scene;
  scene.file = "a.yaml";
  EXPECT_EQ(TitleLine(scene), "a.yaml\n");
  scene.title = "A wheel";
  EXPECT_EQ(TitleLine(scene), "A wheel (a.yaml)\n");
}

TEST(TextUnits, TheOptionsUnitsElseTheScenes) {
  Scene scene;
  scene.units = "US";
  EXPECT_EQ(TextUnits(scene, TextOptions{}).spec(), "US");
  TextOptions options;
  options.units = "mm,g";
  EXPECT_EQ(TextUnits(scene, options).spec(), "mm,g");
}

}  // namespace
}  // namespace chasles
