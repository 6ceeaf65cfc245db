#include "chasles/scene/units.h"

#include <cmath>
#include <numbers>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "chasles/error.h"
#include "chasles/scene/expression.h"
#include "test_support.h"

namespace chasles {
namespace {

using test::kExact;
using test::Near;
using ::testing::ElementsAre;
using ::testing::HasSubstr;

constexpr double kPi = std::numbers::pi;
// Exact definitions (NIST SP 811 appendix B; 1959 international yard and pound; standard
// gravity 9.80665 m/s^2).
constexpr double kIn = 0.0254;
constexpr double kFt = 0.3048;
constexpr double kLb = 0.45359237;
constexpr double kGn = 9.80665;

double Factor(const char* name) {
  const std::optional<Quantity> q = LookupUnit(name);
  EXPECT_TRUE(q.has_value()) << name;
  return q ? q->value : std::nan("");
}

Dimension DimOf(const char* name) {
  return LookupUnit(name).value().dim;
}

TEST(Dimension, AlgebraAndEquality) {
  const Dimension force{1, 1, -2};
  EXPECT_EQ(kMass * kLength / kTime.Pow(2), force);
  EXPECT_EQ(force / kMass, (Dimension{1, 0, -2}));
  EXPECT_EQ(kLength.Pow(-3), (Dimension{-3, 0, 0}));
  EXPECT_TRUE(kDimensionless.IsDimensionless());
  EXPECT_FALSE(kLength == kMass);
}

TEST(Dimension, Describe) {
  EXPECT_EQ(kLength.Describe(), "length");
  EXPECT_EQ(kMass.Describe(), "mass");
  EXPECT_EQ(kTime.Describe(), "time");
  EXPECT_EQ(kDimensionless.Describe(), "dimensionless (angle, ratio)");
  EXPECT_EQ((Dimension{-3, 1, 0}).Describe(), "density (mass/length^3)");
  EXPECT_EQ((Dimension{1, 1, -2}).Describe(), "force (mass*length/time^2)");
  EXPECT_EQ((Dimension{2, 1, 0}).Describe(), "moment of inertia (mass*length^2)");
  EXPECT_EQ((Dimension{0, 0, -1}).Describe(), "angular velocity (1/time)");
  EXPECT_EQ((Dimension{1, 0, -1}).Describe(), "velocity (length/time)");
  EXPECT_EQ((Dimension{1, 0, -2}).Describe(), "acceleration (length/time^2)");
  EXPECT_EQ((Dimension{2, 1, -2}).Describe(), "torque or energy (mass*length^2/time^2)");
  EXPECT_EQ((Dimension{-1, 1, 0}).Describe(), "linear density (mass/length)");
  EXPECT_EQ((Dimension{-2, 1, 0}).Describe(), "areal density (mass/length^2)");
  EXPECT_EQ((Dimension{0, 1, -2}).Describe(), "stiffness (mass/time^2)");
  EXPECT_EQ((Dimension{-1, 1, -2}).Describe(), "pressure or stress (mass/(length*time^2))");
  // No name: the formula alone.
  EXPECT_EQ((Dimension{4, 1, 0}).Describe(), "mass*length^4");
}

TEST(Units, LengthFactorsAreExact) {
  EXPECT_EQ(Factor("m"), 1.0);
  EXPECT_TRUE(Near(Factor("mm"), 1e-3, kExact));
  EXPECT_TRUE(Near(Factor("cm"), 1e-2, kExact));
  EXPECT_TRUE(Near(Factor("km"), 1e3, kExact));
  EXPECT_TRUE(Near(Factor("um"), 1e-6, kExact));
  EXPECT_EQ(Factor("in"), kIn);
  EXPECT_TRUE(Near(Factor("ft"), kFt, kExact));
  EXPECT_TRUE(Near(Factor("yd"), 0.9144, kExact));
  EXPECT_TRUE(Near(Factor("mi"), 1609.344, kExact));
  for (const char* u : {"m", "mm", "cm", "km", "um", "in", "ft", "yd", "mi"}) {
    EXPECT_EQ(DimOf(u), kLength) << u;
  }
}

TEST(Units, MassFactorsAreExact) {
  EXPECT_EQ(Factor("kg"), 1.0);
  EXPECT_TRUE(Near(Factor("g"), 1e-3, kExact));
  EXPECT_TRUE(Near(Factor("mg"), 1e-6, kExact));
  EXPECT_EQ(Factor("t"), 1000.0);
  EXPECT_EQ(Factor("lb"), kLb);
  EXPECT_EQ(Factor("lbm"), kLb);
  EXPECT_TRUE(Near(Factor("oz"), 0.028349523125, kExact));  // lb/16
  // slug = lbf*s^2/ft = 0.45359237*9.80665/0.3048 kg = 14.593902937206364... kg.
  EXPECT_TRUE(Near(Factor("slug"), 14.593902937206364, 1e-15));
  for (const char* u : {"kg", "g", "mg", "t", "lb", "lbm", "oz", "slug"}) {
    EXPECT_EQ(DimOf(u), kMass) << u;
  }
}

TEST(Units, TimeForceEnergyFactors) {
  EXPECT_EQ(Factor("s"), 1.0);
  EXPECT_TRUE(Near(Factor("ms"), 1e-3, kExact));
  EXPECT_TRUE(Near(Factor("us"), 1e-6, kExact));
  EXPECT_EQ(Factor("min"), 60.0);
  EXPECT_EQ(Factor("h"), 3600.0);
  const Dimension force{1, 1, -2};
  EXPECT_EQ(Factor("N"), 1.0);
  EXPECT_EQ(Factor("kN"), 1000.0);
  EXPECT_TRUE(Near(Factor("lbf"), 4.4482216152605, kExact));  // lb * g_n, exact
  EXPECT_TRUE(Near(Factor("kip"), 4448.2216152605, kExact));
  EXPECT_TRUE(Near(Factor("dyn"), 1e-5, kExact));
  for (const char* u : {"N", "kN", "lbf", "kip", "dyn"}) EXPECT_EQ(DimOf(u), force) << u;
  EXPECT_EQ(DimOf("J"), (Dimension{2, 1, -2}));
  EXPECT_EQ(Factor("kJ"), 1000.0);
  EXPECT_EQ(DimOf("W"), (Dimension{2, 1, -3}));
  EXPECT_EQ(DimOf("Pa"), (Dimension{-1, 1, -2}));
  EXPECT_TRUE(Near(Factor("L"), 1e-3, kExact));
  EXPECT_EQ(DimOf("L"), (Dimension{3, 0, 0}));
}

TEST(Units, AnglesAreDimensionlessAndACycleIsARevolution) {
  EXPECT_EQ(Factor("rad"), 1.0);
  EXPECT_TRUE(Near(Factor("deg"), kPi / 180, kExact));
  EXPECT_TRUE(Near(Factor("rev"), 2 * kPi, kExact));
  EXPECT_TRUE(DimOf("deg").IsDimensionless());
  EXPECT_TRUE(Near(Factor("rpm"), 2 * kPi / 60, kExact));
  EXPECT_EQ(DimOf("rpm"), (Dimension{0, 0, -1}));
  EXPECT_TRUE(Near(Factor("cps"), 2 * kPi, kExact));
  // rev/s composes to the same as cps.
  const Quantity rev_per_s = ParseUnitSuffix("rev/s");
  EXPECT_TRUE(Near(rev_per_s.value, Factor("cps"), kExact));
  EXPECT_EQ(rev_per_s.dim, DimOf("cps"));
}

TEST(Units, NamesAreCaseSensitiveAndSuggested) {
  EXPECT_FALSE(LookupUnit("KG").has_value());
  EXPECT_FALSE(LookupUnit("Hz").has_value());
  EXPECT_FALSE(LookupUnit("").has_value());
  EXPECT_THAT(SuggestUnitNames("KG"), ElementsAre("kg"));
  EXPECT_THAT(SuggestUnitNames("slg"), ElementsAre("slug"));
  EXPECT_TRUE(SuggestUnitNames("furlong").empty());
}

TEST(UnitSystem, SIDefaultsNameForceAndTorque) {
  const UnitSystem si;
  EXPECT_EQ(si.FormatUnit({2, 1, 0}), "kg*m^2");
  EXPECT_EQ(si.FormatUnit({-3, 1, 0}), "kg/m^3");
  EXPECT_EQ(si.FormatUnit({1, 1, -2}), "N");
  EXPECT_EQ(si.FormatUnit({2, 1, -2}), "N*m");
  EXPECT_EQ(si.FormatUnit({0, 1, -2}), "N/m");
  EXPECT_EQ(si.FormatUnit({1, 0, -1}), "m/s");
  EXPECT_EQ(si.FormatUnit({1, 1, -1}), "kg*m/s");
  EXPECT_EQ(si.FormatUnit({0, 0, -1}, Angular::kYes), "rad/s");
  EXPECT_EQ(si.FormatUnit({0, 0, -1}), "1/s");
  EXPECT_EQ(si.FormatUnit(kDimensionless), "");
  EXPECT_EQ(si.FromSI(2.5, {2, 1, 0}), 2.5);
  EXPECT_EQ(UnitSystem::Parse("SI").FormatUnit({1, 1, -2}), "N");
}

TEST(UnitSystem, USUsesInchPoundMassAndPoundForce) {
  const UnitSystem us = UnitSystem::Parse("US");
  EXPECT_EQ(us.FormatUnit({2, 1, 0}), "lb*in^2");
  EXPECT_EQ(us.FormatUnit({-3, 1, 0}), "lb/in^3");
  EXPECT_EQ(us.FormatUnit({1, 1, -2}), "lbf");
  EXPECT_EQ(us.FormatUnit({2, 1, -2}), "lbf*in");
  EXPECT_EQ(us.FormatUnit({1, 0, -2}), "in/s^2");
  // 1 kg*m^2 = 1/(0.45359237 * 0.0254^2) lb*in^2 = 3417.17... lb*in^2.
  EXPECT_TRUE(Near(us.FromSI(1.0, {2, 1, 0}), 1.0 / (kLb * kIn * kIn), kExact));
  // 1 N = 1/(0.45359237*9.80665) lbf.
  EXPECT_TRUE(Near(us.FromSI(1.0, {1, 1, -2}), 1.0 / (kLb * kGn), kExact));
  EXPECT_TRUE(Near(us.ToSI(us.FromSI(7.25, {2, 1, -2}), {2, 1, -2}), 7.25, kExact));
}

TEST(UnitSystem, ListedBaseUnitsAndCoherentForces) {
  const UnitSystem mm_g = UnitSystem::Parse("mm,g");
  EXPECT_EQ(mm_g.FormatUnit({2, 1, 0}), "g*mm^2");
  EXPECT_TRUE(Near(mm_g.FromSI(1.0, {2, 1, 0}), 1e9, kExact));  // 1 kg m^2 = 1e3 g * 1e6 mm^2
  // g*mm/s^2 is 1e-6 N: no named force is coherent with it, so it is composed.
  EXPECT_EQ(mm_g.FormatUnit({1, 1, -2}), "g*mm/s^2");
  EXPECT_EQ(mm_g.FormatUnit({1, 0, -1}), "mm/s");  // time stays SI
  // slug*ft/s^2 is exactly one lbf (the slug's definition).
  const UnitSystem ft_slug = UnitSystem::Parse("ft,slug");
  EXPECT_EQ(ft_slug.FormatUnit({1, 1, -2}), "lbf");
  EXPECT_EQ(ft_slug.FormatUnit({2, 1, -2}), "lbf*ft");
  EXPECT_EQ(ft_slug.FormatUnit({2, 1, 0}), "slug*ft^2");
  EXPECT_EQ(UnitSystem::Parse("cm,g").FormatUnit({1, 1, -2}), "dyn");
  EXPECT_EQ(UnitSystem::Parse("in,lb,s,kip").FormatUnit({2, 1, -2}), "kip*in");
  // Pounds of mass bring pound-force: energy in lbf*in, exactly 0.0254 * 4.4482216152605 J.
  const UnitSystem in_lb = UnitSystem::Parse("in,lb");
  EXPECT_EQ(in_lb.FormatUnit({2, 1, -2}), "lbf*in");
  EXPECT_TRUE(Near(in_lb.ToSI(1.0, {2, 1, -2}), 0.0254 * 0.45359237 * 9.80665, kExact));
  EXPECT_EQ(in_lb.FormatUnit({2, 1, 0}), "lb*in^2");
}

TEST(UnitSystem, AnglesAndAngularVelocities) {
  const UnitSystem sys = UnitSystem::Parse("US,deg,rpm");
  EXPECT_EQ(sys.FormatUnit(kDimensionless, Angular::kYes), "deg");
  EXPECT_TRUE(Near(sys.FromSI(kPi / 2, kDimensionless, Angular::kYes), 90.0, kExact));
  EXPECT_EQ(sys.FormatUnit({0, 0, -1}, Angular::kYes), "rpm");
  EXPECT_TRUE(Near(sys.FromSI(2 * kPi, {0, 0, -1}, Angular::kYes), 60.0, kExact));
  EXPECT_EQ(sys.FormatUnit({0, 0, -2}, Angular::kYes), "deg/s^2");
  // A ratio stays a pure number; angular momentum carries no angle unit.
  EXPECT_EQ(sys.FormatUnit(kDimensionless), "");
  EXPECT_EQ(sys.FormatUnit({2, 1, -1}, Angular::kYes), "lb*in^2/s");
  const UnitSystem deg_only = UnitSystem::Parse("deg");
  EXPECT_EQ(deg_only.FormatUnit({0, 0, -1}, Angular::kYes), "deg/s");
}

TEST(UnitSystem, EveryFormattedUnitParsesBackToItsFactor) {
  // Consistency: value * factor(FormatUnit(dim)) == SI value, for the printed string.
  const Dimension dims[] = {{1, 0, 0},  {0, 1, 0},  {0, 0, 1},  {2, 1, 0},  {-3, 1, 0},
                            {1, 1, -2}, {2, 1, -2}, {0, 1, -2}, {1, 0, -2}, {-1, 1, -2},
                            {2, 1, -3}, {1, 1, -1}, {2, 1, -1}, {0, 1, -1}, {0, 0, -1}};
  for (const char* spec : {"SI", "US", "mm,g", "ft,slug", "cm,g,ms", "km,t,h,kN"}) {
    const UnitSystem sys = UnitSystem::Parse(spec);
    for (const Dimension& d : dims) {
      const std::string unit = sys.FormatUnit(d);
      const Quantity q = ParseUnitSuffix(unit);
      EXPECT_EQ(q.dim, d) << spec << " " << unit;
      EXPECT_TRUE(Near(sys.FromSI(q.value, d), 1.0, kExact)) << spec << " " << unit;
    }
  }
}

TEST(UnitSystem, SpecErrorsNameTheTokenAndListAcceptedNames) {
  try {
    UnitSystem::Parse("mm,furlong");
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("unknown unit 'furlong'"));
    EXPECT_THAT(e.what(), HasSubstr("accepted: SI, US"));
    EXPECT_THAT(e.what(), HasSubstr("slug"));
  }
  EXPECT_THROW(UnitSystem::Parse(""), InputError);
  try {
    UnitSystem::Parse("mm,cm");
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("two length units 'mm' and 'cm'"));
  }
  try {
    UnitSystem::Parse("ftt");
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("did you mean 'ft'"));
  }
  try {
    UnitSystem::Parse("Pa");
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("'Pa' cannot be a base unit"));
  }
}

}  // namespace
}  // namespace chasles
