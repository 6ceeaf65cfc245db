#include "chasles/mass/materials.h"

#include <algorithm>
#include <set>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "chasles/error.h"

namespace chasles {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

TEST(Materials, HandbookDensities) {
  // Typical room-temperature values [kg/m³] (CRC Handbook of Chemistry and Physics).
  const std::pair<const char*, double> expected[] = {
      {"steel", 7850},      {"stainless_steel", 8000},
      {"cast_iron", 7200},  {"aluminium", 2700},
      {"lead", 11340},      {"copper", 8960},
      {"brass", 8500},      {"bronze", 8800},
      {"titanium", 4506},   {"gold", 19300},
      {"silver", 10490},    {"zinc", 7140},
      {"nickel", 8908},     {"tungsten", 19250},
      {"magnesium", 1738},  {"concrete", 2400},
      {"glass", 2500},      {"water", 1000},
      {"ice", 917},         {"oak", 750},
      {"pine", 500},        {"balsa", 160},
      {"rubber", 1100},     {"nylon", 1150},
      {"abs", 1050},        {"pla", 1240},
      {"acrylic", 1180},    {"polycarbonate", 1200},
      {"polyethylene", 950}};
  for (const auto& [name, rho] : expected) {
    SCOPED_TRACE(name);
    ASSERT_TRUE(FindMaterialDensity(name).has_value());
    EXPECT_EQ(*FindMaterialDensity(name), rho);
    EXPECT_EQ(LookUpMaterialDensity(name), rho);
  }
}

TEST(Materials, SpellingsAndSeparatorsAreEquivalent) {
  EXPECT_EQ(FindMaterialDensity("aluminum"), FindMaterialDensity("aluminium"));
  EXPECT_EQ(FindMaterialDensity("Aluminum"), 2700.0);
  EXPECT_EQ(FindMaterialDensity("Stainless Steel"), 8000.0);
  EXPECT_EQ(FindMaterialDensity("stainless-steel"), 8000.0);
  EXPECT_EQ(FindMaterialDensity("  STAINLESS__steel "), 8000.0);
  EXPECT_EQ(FindMaterialDensity("Cast Iron"), 7200.0);
  EXPECT_EQ(FindMaterialDensity("HDPE"), 950.0);
  EXPECT_EQ(FindMaterialDensity("PMMA"), 1180.0);
  EXPECT_EQ(FindMaterialDensity("carbon fiber"), FindMaterialDensity("carbon_fibre"));
  EXPECT_EQ(NormalizeMaterialName(" Stainless - Steel "), "stainless_steel");
  EXPECT_FALSE(FindMaterialDensity("unobtainium").has_value());
  EXPECT_FALSE(FindMaterialDensity("").has_value());
}

TEST(Materials, TableIsConsistent) {
  // Every name (canonical or alias) is unique, already normalised, and the density positive.
  std::set<std::string> seen;
  for (const Material& m : Materials()) {
    EXPECT_GT(m.density, 0.0);
    EXPECT_EQ(NormalizeMaterialName(m.name), m.name);
    EXPECT_TRUE(seen.insert(std::string(m.name)).second) << m.name;
    for (std::string_view a : m.aliases) {
      EXPECT_EQ(NormalizeMaterialName(a), a);
      EXPECT_TRUE(seen.insert(std::string(a)).second) << a;
    }
  }
  const std::vector<std::string> names = MaterialNames();
  EXPECT_EQ(names.size(), seen.size());
  EXPECT_TRUE(std::is_sorted(names.begin(), names.end()));
  EXPECT_TRUE(std::find(names.begin(), names.end(), "aluminum") != names.end());
}

TEST(Materials, SuggestsTheClosestName) {
  EXPECT_EQ(SuggestMaterialName("stell"), "steel");         // one letter dropped
  EXPECT_EQ(SuggestMaterialName("aluminim"), "aluminium");  // one letter dropped
  EXPECT_EQ(SuggestMaterialName("Titanum"), "titanium");    // case ignored
  EXPECT_EQ(SuggestMaterialName("coppre"), "copper");       // neighbours swapped
  EXPECT_EQ(SuggestMaterialName("stainles steel"), "stainless_steel");
  EXPECT_EQ(SuggestMaterialName("unobtainium"), "");  // nothing plausible
  EXPECT_EQ(SuggestMaterialName(""), "");
}

TEST(Materials, UnknownNameErrorSuggestsAndLists) {
  try {
    LookUpMaterialDensity("stell");
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("unknown material 'stell'; did you mean 'steel'?"));
    EXPECT_THAT(e.what(), HasSubstr("Known materials: steel, stainless_steel"));
    EXPECT_THAT(e.what(), HasSubstr("or give a density in kg/m^3 instead"));
  }
  try {
    LookUpMaterialDensity("unobtainium");
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("unknown material 'unobtainium'. Known materials:"));
    EXPECT_THAT(e.what(), Not(HasSubstr("did you mean")));
  }
}

}  // namespace
}  // namespace chasles
