#include "chasles/report/solve_json.h"

#include <cmath>
#include <limits>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "chasles/error.h"
#include "chasles/report/json_report.h"

namespace chasles {
namespace {

using ::testing::StartsWith;

/// A disk rolling down an incline at angle 30°, made by hand: a = (2/3) g sin θ along the
/// slope (eq. 8.50 for a uniform disk, I = ½ m r²), the friction it needs f = (1/3) m g sin θ
/// against N = m g cos θ, so f/N = (1/3) tan θ; and a block sliding on the floor with N = 10 N
/// and friction (3, 4, 0) N, so |f| = 5 N and |f|/N = 0.5.
SolveReport HandMade(bool planar) {
  const double g = 9.81, m = 2.0, theta = M_PI / 6;
  const double a = 2.0 / 3.0 * g * std::sin(theta);
  SolveReport s;
  s.planar = planar;
  BodyAccelerationReport b;
  b.name = "disk";
  b.a_WBcm_W = Vec3(a * std::cos(theta), -a * std::sin(theta), 0);
  b.alpha_WB_W = Vec3(0, 0, -a / 0.1);
  b.alpha_WB_B = b.alpha_WB_W;
  s.solution.bodies = {b};
  ReactionReport r;
  r.name = "rolling";
  r.kind = "rolling disk";
  r.is_rolling = true;
  r.normal_force = m * g * std::cos(theta);
  r.friction_W = Vec3(m * g * std::sin(theta) / 3.0, 0, 0);
  r.friction_needed = std::tan(theta) / 3.0;
  r.F_Jc_W = Vec3(1, 2, 0);
  r.M_Jc_W = Vec3(0, 0, 0.25);
  r.lambda = {1.0, 2.0};
  s.solution.reactions = {r};
  s.mu_s = {0.4};
  BodyMotionReport motion;
  motion.name = "disk";
  motion.T_trans = 1.5;
  motion.T_rot = 0.75;
  s.motion = {motion};
  s.total = motion;
  s.total.name = "";
  ContactPointReport c;
  c.point = "floor";
  c.contact = "floor";
  c.out.mode = ContactMode::kSliding;
  c.out.normal_force = 10.0;
  c.out.friction_force_W = Vec3(3, 4, 0);
  c.mu_s = 0.6;
  c.mu_k = 0.5;
  s.contacts = {c};
  s.solution.rank = 2;
  s.solution.num_rows = 2;
  return s;
}

TEST(SolveJson, HasThePlanarBlocksOnlyWhenPlanar) {
  const nlohmann::json j = SolveJson(HandMade(false));
  EXPECT_FALSE(j["planar"].get<bool>());
  EXPECT_FALSE(j["bodies"][0].contains("planar"));
  EXPECT_FALSE(j["reactions"][0].contains("planar"));

  const SolveReport s = HandMade(true);
  const nlohmann::json p = SolveJson(s);
  EXPECT_TRUE(p["planar"].get<bool>());
  const Vec3& a = s.solution.bodies[0].a_WBcm_W;
  EXPECT_EQ(p["bodies"][0]["planar"],
            nlohmann::json(
                {{"a_x", a.x()}, {"a_y", a.y()}, {"alpha", s.solution.bodies[0].alpha_WB_W.z()}}));
  EXPECT_EQ(p["reactions"][0]["planar"], nlohmann::json({{"Fx", 1.0}, {"Fy", 2.0}, {"Mz", 0.25}}));
}

TEST(SolveJson, RollingReactionAndSlidingContactCarryTheirFriction) {
  const SolveReport s = HandMade(false);
  const nlohmann::json j = SolveJson(s);
  const nlohmann::json& r = j["reactions"][0];
  const double theta = M_PI / 6;
  EXPECT_DOUBLE_EQ(r["friction_needed"].get<double>(), std::tan(theta) / 3.0);
  EXPECT_EQ(r["mu_s"].get<double>(), 0.4);
  // tan 30° / 3 = 0.19 <= mu_s = 0.4: it rolls.
  EXPECT_TRUE(r["rolls"].get<bool>());
  EXPECT_EQ(r["multipliers"], nlohmann::json({1.0, 2.0}));
  const nlohmann::json& c = j["contacts"][0];
  EXPECT_EQ(c["mode"], "sliding");
  EXPECT_EQ(c["regime"], "slides");
  EXPECT_EQ(c["friction_magnitude"].get<double>(), 5.0);
  EXPECT_EQ(c["friction_needed"].get<double>(), 0.5);
  // T = T_trans + T_rot.
  EXPECT_EQ(j["energy_momentum"]["bodies"][0]["kinetic_energy"].get<double>(), 2.25);
  EXPECT_EQ(j["energy_momentum"]["bodies"][0]["name"], "disk");
  EXPECT_FALSE(j["energy_momentum"]["total"].contains("name"));
  EXPECT_EQ(j["rank"], 2);
  EXPECT_EQ(j["rows"], 2);
  EXPECT_TRUE(j["checks"]["passed"].get<bool>());
}

TEST(SolveJson, WithoutMuSARollingReactionSaysNothingAboutRolling) {
  SolveReport s = HandMade(false);
  s.mu_s = {std::numeric_limits<double>::quiet_NaN()};
  const nlohmann::json r = SolveJson(s)["reactions"][0];
  EXPECT_FALSE(r.contains("mu_s"));
  EXPECT_FALSE(r.contains("rolls"));
  EXPECT_TRUE(r.contains("friction_needed"));
}

TEST(SolveJson, ANonFiniteValueIsRefusedByItsKeyPathAndBody) {
  SolveReport s = HandMade(false);
  s.solution.bodies[0].a_WBcm_W.z() = std::numeric_limits<double>::infinity();
  try {
    DumpJson(SolveJson(s), "the solve report");
    FAIL() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(),
                StartsWith("the solve report: bodies[0].acceleration[2] (body 'disk') is inf"));
  }
}

SweepTable TwoValues() {
  SweepTable t;
  t.parameter = "theta";
  t.columns = {"theta", "disk_ax", "a,b"};
  t.units = {"", "m/s^2", ""};
  t.rows = {{0.0, 0.1, 1.0 / 3.0}, {0.5, -2.0, 1e-20}};
  return t;
}

TEST(SweepCsv, PrintsTheNamesWithUnitsQuotedWhereNeededAndTwelveSignificantDigits) {
  // 1/3 to 12 significant digits is 0.333333333333; 0.1 prints as 0.1. No comment line: the
  // header comes first, a pure number without brackets.
  EXPECT_EQ(SweepCsv(TwoValues()),
            "theta,disk_ax [m/s^2],\"a,b\"\n"
            "0,0.1,0.333333333333\n"
            "0.5,-2,1e-20\n");
}

TEST(SweepCsv, FullPrecisionWritesSeventeenDigitsThatReadBackBitwise) {
  // %.17g: 1/3 is 0.33333333333333331, 0.1 is 0.10000000000000001; strtod gives back the
  // same bits.
  const SweepTable t = TwoValues();
  const std::string text = SweepCsv(t, CsvPrecision::kFull);
  EXPECT_EQ(text,
            "theta,disk_ax [m/s^2],\"a,b\"\n"
            "0,0.10000000000000001,0.33333333333333331\n"
            "0.5,-2,9.9999999999999995e-21\n");
  const CsvTable back = ReadCsvTable(text, "sweep.csv");
  EXPECT_EQ(back.columns, t.columns);
  EXPECT_EQ(back.units, t.units);
  EXPECT_EQ(back.rows, t.rows);
}

TEST(SweepCsv, RefusesANonFiniteValueByColumnAndRow) {
  SweepTable t = TwoValues();
  t.rows[0][1] = std::numeric_limits<double>::quiet_NaN();
  try {
    SweepCsv(t);
    FAIL() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), StartsWith("the sweep table: column 'disk_ax' of row 1 is nan"));
  }
}

TEST(SweepJson, HoldsTheParameterColumnsAndRows) {
  const SweepTable t = TwoValues();
  EXPECT_EQ(SweepJson(t), nlohmann::json({{"parameter", "theta"},
                                          {"units", "SI"},
                                          {"columns", t.columns},
                                          {"column_units", t.units},
                                          {"rows", t.rows}}));
  EXPECT_EQ(DumpJson(SweepJson(t), "r").substr(0, 21), "{\n  \"column_units\": [");
}

}  // namespace
}  // namespace chasles
