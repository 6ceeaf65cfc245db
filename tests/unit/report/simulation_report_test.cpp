#include "chasles/report/simulation_report.h"

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "chasles/error.h"
#include "chasles/report/json_report.h"

namespace chasles {
namespace {

using ::testing::StartsWith;

/// Splits a line at commas outside quotes, undoing the quoting (RFC 4180).
std::vector<std::string> SplitCsvLine(const std::string& line) {
  std::vector<std::string> out(1);
  bool quoted = false;
  for (size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted && c == '"' && i + 1 < line.size() && line[i + 1] == '"') {
      out.back() += '"';
      ++i;
    } else if (c == '"') {
      quoted = !quoted;
    } else if (c == ',' && !quoted) {
      out.emplace_back();
    } else {
      out.back() += c;
    }
  }
  return out;
}

StudyResult TwoRows() {
  StudyResult r;
  r.columns = {"t", "x,y", "say \"hi\""};
  r.units = {"s", "m", ""};
  r.rows = {{0.0, 0.1, 1.0 / 3.0}, {0.5, -2.5e-8, 1e21}};
  return r;
}

TEST(SimulationCsv, QuotesNamesThatNeedItAndWritesShortestRoundTripNumbers) {
  // 0.1, 1/3, -2.5e-8 and 1e21 in their shortest decimal form that reads back as the same
  // double: 0.1 has none shorter than "0.1", 1/3 needs 16 significant digits.
  // The header: name, one space, the unit in brackets; a pure number without brackets.
  EXPECT_EQ(SimulationCsv(TwoRows()),
            "t [s],\"x,y [m]\",\"say \"\"hi\"\"\"\n"
            "0,0.1,0.3333333333333333\n"
            "0.5,-2.5e-08,1e+21\n");
}

TEST(SimulationCsv, EveryFieldReadsBackAsTheSameValue) {
  const StudyResult r = TwoRows();
  std::istringstream in(SimulationCsv(r));
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(SplitCsvLine(line), (std::vector<std::string>{"t [s]", "x,y [m]", "say \"hi\""}));
  for (const auto& row : r.rows) {
    ASSERT_TRUE(std::getline(in, line));
    const std::vector<std::string> fields = SplitCsvLine(line);
    ASSERT_EQ(fields.size(), row.size());
    for (size_t i = 0; i < row.size(); ++i) EXPECT_EQ(std::stod(fields[i]), row[i]) << fields[i];
  }
}

TEST(SimulationCsv, FullPrecisionReadsBackBitwise) {
  // Seeded random doubles over many magnitudes: each %.17g field reads back (strtod) as the
  // same bits, and the header's names and units come back apart.
  StudyResult r;
  r.columns = {"t", "a", "b"};
  r.units = {"s", "m/s^2", ""};
  std::mt19937_64 gen(12345);
  std::uniform_real_distribution<double> mant(-1.0, 1.0);
  std::uniform_int_distribution<int> exp(-30, 30);
  for (int i = 0; i < 200; ++i) {
    r.rows.push_back({i * 0.1, std::ldexp(mant(gen), exp(gen)), std::ldexp(mant(gen), exp(gen))});
  }
  const CsvTable back = ReadCsvTable(SimulationCsv(r, CsvPrecision::kFull), "run.csv");
  EXPECT_EQ(back.columns, r.columns);
  EXPECT_EQ(back.units, r.units);
  ASSERT_EQ(back.rows.size(), r.rows.size());
  for (size_t i = 0; i < r.rows.size(); ++i) {
    for (size_t c = 0; c < 3; ++c) {
      EXPECT_EQ(std::bit_cast<std::uint64_t>(back.rows[i][c]),
                std::bit_cast<std::uint64_t>(r.rows[i][c]));
    }
  }
}

TEST(SimulationCsv, WithoutUnitsTheHeaderIsTheBareNames) {
  StudyResult r = TwoRows();
  r.units.clear();
  EXPECT_THAT(SimulationCsv(r), StartsWith("t,\"x,y\",\"say \"\"hi\"\"\"\n"));
}

TEST(SimulationCsv, RefusesANonFiniteValueByColumnAndRow) {
  StudyResult r = TwoRows();
  r.rows[1][1] = std::numeric_limits<double>::infinity();
  try {
    SimulationCsv(r);
    FAIL() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), StartsWith("the CSV time series: column 'x,y' of row 2 is inf"));
  }
}

StudyResult OneBodyRun() {
  StudyResult r;
  r.columns = {"t", "x"};
  r.rows = {{0.0, 1.0}};
  r.t_end = 2.0;
  StudyBodyState b;
  b.name = "disk";
  b.mass = 3.0;
  b.p_WBcm = Vec3(1, 2, 0);
  b.v_WBcm_W = Vec3(0.5, -0.25, 0);
  b.w_WB_W = Vec3(0, 0, 4);
  b.w_WB_B = Vec3(0, 0, 4);
  b.theta = 0.75;
  r.final_bodies = {b};
  ReactionReport x;
  x.name = "pin";
  x.kind = "revolute";
  x.F_Jc_W = Vec3(1, 29.43, 0);
  x.M_Jc_W = Vec3(0, 0, -0.5);
  r.final_reactions = {x};
  r.ledger.energy_scale = 10.0;
  r.ledger.residual = 1e-11;
  r.ledger.work_by_force = {{"drag", -0.25}};
  r.warnings = {"the run's own"};
  r.integrator = IntegratorKind::kRk4;
  return r;
}

TEST(SimulationJson, CarriesTheHeaderAndThePlanarBlocksOnlyWhenPlanar) {
  const StudyResult r = OneBodyRun();
  ReportHeader header{"spin.yaml", "A spinning disk", false, {"from the scene"}};
  nlohmann::json j = SimulationJson(r, header, "out/spin.csv");
  EXPECT_EQ(j["scene"], "spin.yaml");
  EXPECT_EQ(j["title"], "A spinning disk");
  EXPECT_EQ(j["units"], "SI");
  EXPECT_EQ(j["csv"], "out/spin.csv");
  EXPECT_EQ(j["columns"], nlohmann::json({"t", "x"}));
  EXPECT_EQ(j["t_end"].get<double>(), 2.0);
  EXPECT_EQ(j["final"]["t"].get<double>(), 2.0);
  EXPECT_FALSE(j["planar"].get<bool>());
  EXPECT_FALSE(j["final"]["bodies"][0].contains("planar"));
  EXPECT_FALSE(j["final"]["reactions"][0].contains("planar"));
  // No contact points: no "contacts" key in a snapshot.
  EXPECT_FALSE(j["final"].contains("contacts"));
  // The header's warnings come before the run's.
  EXPECT_EQ(j["warnings"], nlohmann::json({"from the scene", "the run's own"}));
  // relative_residual = residual / energy_scale.
  EXPECT_DOUBLE_EQ(j["ledger"]["relative_residual"].get<double>(), 1e-11 / 10.0);
  EXPECT_EQ(j["ledger"]["work_by_force"]["drag"].get<double>(), -0.25);
  EXPECT_EQ(j["integrator"]["name"], "RK4 (fixed step)");

  header.planar = true;
  j = SimulationJson(r, header, "out/spin.csv");
  EXPECT_TRUE(j["planar"].get<bool>());
  const nlohmann::json& p = j["final"]["bodies"][0]["planar"];
  // The planar state is (x, y) of the centre of mass, theta, (vx, vy) and omega about z.
  EXPECT_EQ(
      p,
      nlohmann::json(
          {{"x", 1.0}, {"y", 2.0}, {"theta", 0.75}, {"vx", 0.5}, {"vy", -0.25}, {"omega", 4.0}}));
  EXPECT_EQ(j["final"]["reactions"][0]["planar"],
            nlohmann::json({{"Fx", 1.0}, {"Fy", 29.43}, {"Mz", -0.5}}));
}

TEST(SimulationJson, AJumpRecordsItsEnergyChange) {
  StudyResult r = OneBodyRun();
  StudyJump jump;
  jump.kind = StudyJumpKind::kImpulse;
  jump.t = 0.5;
  jump.energy_before = 4.0;
  jump.energy_after = 1.5;
  r.jumps = {jump};
  const nlohmann::json j = SimulationJson(r, {}, "");
  EXPECT_EQ(j["jumps"][0]["energy_change"].get<double>(), 1.5 - 4.0);
}

TEST(SimulationJson, ANonFiniteValueIsRefusedByItsKeyPath) {
  StudyResult r = OneBodyRun();
  r.final_bodies[0].v_WBcm_W.y() = std::numeric_limits<double>::quiet_NaN();
  const nlohmann::json j = SimulationJson(r, {}, "");
  try {
    DumpJson(j, "the JSON summary");
    FAIL() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), StartsWith("the JSON summary: final.bodies[0].velocity[1] is nan"));
  }
}

}  // namespace
}  // namespace chasles
