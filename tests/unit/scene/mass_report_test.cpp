#include "chasles/scene/mass_report.h"

#include <cmath>
#include <string>

#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include "test_support.h"

namespace chasles {
namespace {

using test::kExact;
using test::Near;

// A slender rod of mass m = 3 kg from the origin to (0, 0, L = 2 m), with a named point O at
// the origin. About its centre Ixx = Iyy = m L² / 12 = 1 kg·m², Izz = 0; about O (parallel
// axes, eq. 8.29, d = L/2 along z) Ixx = Iyy = m L² / 3 = 4 kg·m².
const char* const kRod = R"(
title: a rod
parameters:
  m: 3 kg
bodies:
  - name: rod
    points:
      O: [0, 0, 0]
    parts: [{name: bar, shape: rod, mass: m, from: [0, 0, 0], to: [0, 0, 2 m]}]
)";

double At(const nlohmann::json& m, int i, int j) {
  return m[static_cast<size_t>(i)][static_cast<size_t>(j)].get<double>();
}

TEST(MassReportJson, ReportsInTheUnitsAskedFor) {
  const Scene scene = LoadSceneText(kRod, "rod.yaml");
  const nlohmann::json j = MassReportJson(scene, UnitSystem::Parse("mm,g"));
  EXPECT_EQ(j["scene"], "rod.yaml");
  EXPECT_EQ(j["title"], "a rod");
  EXPECT_EQ(j["units"]["length"], "mm");
  EXPECT_EQ(j["units"]["mass"], "g");
  EXPECT_EQ(j["inertia_convention"], kInertiaConvention);
  EXPECT_EQ(j["parameters"]["m"]["value_si"].get<double>(), 3.0);
  const nlohmann::json& b = j["bodies"][0];
  EXPECT_EQ(b["name"], "rod");
  // 3 kg = 3000 g; the centre at z = 1 m = 1000 mm; 1 kg·m² = 1e3 g · 1e6 mm² = 1e9 g·mm².
  EXPECT_TRUE(Near(b["mass"].get<double>(), 3000.0, kExact));
  EXPECT_TRUE(Near(b["center_of_mass"][2].get<double>(), 1000.0, kExact));
  EXPECT_TRUE(Near(At(b["inertia_about_center_of_mass"], 0, 0), 1e9, kExact));
  ASSERT_EQ(b["points"].size(), 1u);
  EXPECT_EQ(b["points"][0]["name"], "O");
  EXPECT_TRUE(Near(At(b["points"][0]["inertia"], 0, 0), 4e9, kExact));
  EXPECT_FALSE(b.contains("frame"));
  ASSERT_EQ(b["parts"].size(), 1u);
  EXPECT_EQ(b["parts"][0]["name"], "bar");
  EXPECT_EQ(b["parts"][0]["mass_source"], "mass");
}

TEST(MassReportJson, AddsExtraPointsAfterTheBodysOwnAndTheRotatedFrame) {
  const Scene scene = LoadSceneText(kRod, "rod.yaml");
  // The far end (0, 0, L): by symmetry the same inertia as about O.
  const std::vector<MassReportPoint> extra = {{"end", Vec3(0, 0, 2)}};
  // F turned 90° about x from B: the rod's axis z_B is y_F, so I_F = diag(1, 0, 1) kg·m².
  const Mat3 R_BF = Eigen::AngleAxisd(M_PI / 2, Vec3::UnitX()).toRotationMatrix();
  const nlohmann::json j = MassReportJson(scene, UnitSystem::Parse("SI"), extra, R_BF);
  const nlohmann::json& b = j["bodies"][0];
  ASSERT_EQ(b["points"].size(), 2u);
  EXPECT_EQ(b["points"][1]["name"], "end");
  EXPECT_TRUE(Near(At(b["points"][1]["inertia"], 1, 1), 4.0, kExact));
  const nlohmann::json& I_F = b["frame"]["inertia_about_center_of_mass"];
  EXPECT_TRUE(Near(At(I_F, 0, 0), 1.0, kExact));
  EXPECT_TRUE(Near(At(I_F, 1, 1), 0.0, kExact, 1.0));
  EXPECT_TRUE(Near(At(I_F, 2, 2), 1.0, kExact));
}

TEST(MassReportPoints, ListsTheBodysPointsThenTheExtraOnes) {
  const Scene scene = LoadSceneText(kRod, "rod.yaml");
  const auto points = MassReportPoints(scene.bodies[0], {{"P", Vec3(1, 2, 3)}});
  ASSERT_EQ(points.size(), 2u);
  EXPECT_EQ(points[0].name, "O");
  EXPECT_EQ(points[1].name, "P");
  EXPECT_EQ(points[1].p_BoP_B, Vec3(1, 2, 3));
}

}  // namespace
}  // namespace chasles
