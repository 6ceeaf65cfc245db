#include "chasles/report/certificate_json.h"

#include <gtest/gtest.h>

namespace chasles {
namespace {

// A certificate passes when no check's worst value is above its tolerance
// (CheckResult::passed); a check that applied to nothing (count 0) passes and has no place,
// time or phase.
TEST(CertificateJson, ListsEveryCheckWithWhereAndWhenOnlyForThoseThatApplied) {
  Certificate c;
  c.force_scale = 10.0;
  c.moment_scale = 2.0;
  c.length_scale = 0.5;
  c.velocity_scale = 3.0;
  c.energy_scale = 7.0;
  c.impulse_scale = 4.0;
  c.angular_impulse_scale = 1.5;
  CheckResult applied;
  applied.name = "gap";
  applied.description = "penetration";
  applied.unit = "m";
  applied.count = 4;
  applied.worst = 2e-9;
  applied.tolerance = 1e-9;
  applied.where = "floor";
  applied.t = 0.25;
  applied.phase = CheckPhase::kEvent;
  CheckResult idle;
  idle.name = "friction cone";
  idle.unit = "N";
  c.checks = {applied, idle};

  const nlohmann::json j = CertificateJson(c);
  EXPECT_FALSE(j["passed"].get<bool>());  // 2e-9 > 1e-9
  EXPECT_EQ(j["scales"], nlohmann::json({{"force", 10.0},
                                         {"moment", 2.0},
                                         {"length", 0.5},
                                         {"velocity", 3.0},
                                         {"energy", 7.0},
                                         {"impulse", 4.0},
                                         {"angular_impulse", 1.5}}));
  ASSERT_EQ(j["checks"].size(), 2u);
  const nlohmann::json& a = j["checks"][0];
  EXPECT_EQ(a["name"], "gap");
  EXPECT_TRUE(a["applies"].get<bool>());
  EXPECT_FALSE(a["passed"].get<bool>());
  EXPECT_EQ(a["count"], 4);
  EXPECT_EQ(a["worst"].get<double>(), 2e-9);
  EXPECT_EQ(a["where"], "floor");
  EXPECT_EQ(a["t"].get<double>(), 0.25);
  EXPECT_EQ(a["phase"], CheckPhaseName(CheckPhase::kEvent));
  const nlohmann::json& b = j["checks"][1];
  EXPECT_FALSE(b["applies"].get<bool>());
  EXPECT_TRUE(b["passed"].get<bool>());
  EXPECT_FALSE(b.contains("where"));
  EXPECT_FALSE(b.contains("t"));
  EXPECT_FALSE(b.contains("phase"));
}

}  // namespace
}  // namespace chasles
