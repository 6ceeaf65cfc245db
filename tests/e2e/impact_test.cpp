// End-to-end: examples/contact-rod-impact.yaml through `chasles simulate`, with the default
// (energetic) restitution law and with `restitution_law: newton` written into a copy of the
// scene. No gravity, so the motion after the impact is free and its kinetic energy constant.

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "cli_runner.h"
#include "test_support.h"

namespace chasles::test {
namespace {

// The example's values.
constexpr double kL = 1.0, kM = 1.0, kVx = 1.0, kVz = 2.0, kE = 0.5;

struct After {
  nlohmann::json json;
  double T = 0.0;  // kinetic energy after [J]
};

// T = ½ m v² + ½ wᵀ I_W w with the slender rod's inertia about G, m L²/12 across the axis;
// w stays along y, across the axis.
After RunRod(const std::string& scene) {
  After a;
  a.json = SimulateJson(scene, OutDir("impact"));
  const auto& b = a.json.at("final").at("bodies").at(0);
  const Eigen::Vector3d v = ToVec(b.at("velocity")), w = ToVec(b.at("angular_velocity"));
  const double I = kM * kL * kL / 12;
  a.T = 0.5 * kM * v.squaredNorm() + 0.5 * I * w.squaredNorm();
  return a;
}

TEST(ImpactE2e, RodImpactReportsItsLawAndTheEnergyItTakes) {
  const After a = RunRod(SourcePath("examples/contact-rod-impact.yaml"));
  const auto& impacts = a.json.at("impacts");
  ASSERT_EQ(impacts.size(), 1u);
  EXPECT_EQ(impacts[0].at("restitution_law").get<std::string>(), "energetic");
  EXPECT_FALSE(impacts[0].contains("frictionless_fallback"));
  // Before: ½ m (v_x² + v_z²), no spin. The energy lost is what the report says.
  const double T0 = 0.5 * kM * (kVx * kVx + kVz * kVz);
  EXPECT_TRUE(Near(impacts[0].at("energy_lost").get<double>(), T0 - a.T, 1e-9));
  EXPECT_GT(T0 - a.T, 0.0);
  EXPECT_TRUE(Near(impacts[0].at("approach_speed").get<double>(), kVz, 1e-9));
}

// Newton's law through the scene key: the lower end leaves the floor at e v_z. Right after the
// impact v_A = v + w × r_A with r_A = -(L/2)(cos 45°, 0, sin 45°) and w along y:
// (w × r_A)_z = -w_y r_A,x = w_y (L/2) cos 45°. The run's final state is later, but with no
// gravity v and w are constant and the rod's angle only turns: v_A,z is read from v and w.
TEST(ImpactE2e, NewtonLawFromTheSceneKey) {
  std::ifstream in(SourcePath("examples/contact-rod-impact.yaml"));
  std::stringstream ss;
  ss << in.rdbuf();
  std::string text = ss.str();
  const std::string from = "restitution_law: energetic";
  const size_t at = text.find(from);
  ASSERT_NE(at, std::string::npos);
  text.replace(at, from.size(), "restitution_law: newton");
  const auto path = OutDir("impact") / "rod-newton.yaml";
  std::ofstream(path) << text;
  const After a = RunRod(path.string());
  const auto& impacts = a.json.at("impacts");
  ASSERT_EQ(impacts.size(), 1u);
  EXPECT_EQ(impacts[0].at("restitution_law").get<std::string>(), "newton");
  const auto& b = a.json.at("final").at("bodies").at(0);
  const Eigen::Vector3d v = ToVec(b.at("velocity")), w = ToVec(b.at("angular_velocity"));
  const double vA_z = v.z() + w.y() * (kL / 2) * std::cos(M_PI / 4);
  EXPECT_TRUE(Near(vA_z, kE * kVz, 1e-9));
}

}  // namespace
}  // namespace chasles::test
