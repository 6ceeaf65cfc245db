// End-to-end: strings (`strings:`, docs/scene-format.md): the Atwood machine with a massive
// pulley and the yo-yo of examples/, through `chasles solve` (the tensions at the start) and
// `chasles simulate` (the motion from rest). The closed forms are derived here and in the
// examples' comments.

#include <cmath>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "chasles/math/types.h"
#include "cli_runner.h"
#include "test_support.h"

namespace chasles::test {
namespace {

constexpr double kSolve = 1e-9;  // one linear solve: round-off only
constexpr double kRun = 1e-9;    // a run at tolerance 1e-12 over a few hundred steps

const nlohmann::json& Named(const nlohmann::json& list, const std::string& name) {
  for (const auto& x : list) {
    if (x.at("name") == name) return x;
  }
  throw std::runtime_error("nothing named " + name);
}

nlohmann::json Solve(const std::string& example) {
  const CliResult r = RunCli("solve " + Quote(SourcePath(example)) + " --format json --strict");
  if (r.exit_code != 0) throw std::runtime_error(example + ": " + r.err);
  return nlohmann::json::parse(r.out);
}

// examples/atwood-machine.yaml: m1 = 3 kg, m2 = 1.25 kg, pulley M = 2 kg, r = 0.15 m
// (I = M r²/2), g = 9.81. m1 a = m1 g - T1, m2 a = T2 - m2 g, I a/r = (T1 - T2) r give
// a = (m1 - m2) g / (m1 + m2 + I/r²), T1 = m1 (g - a), T2 = m2 (g + a).
TEST(Strings, AtwoodMachineWithAMassivePulley) {
  const double m1 = 3, m2 = 1.25, M = 2, r = 0.15, g = 9.81, t = 0.5;
  const double I = 0.5 * M * r * r;
  const double a = (m1 - m2) * g / (m1 + m2 + I / (r * r));
  const auto s = Solve("examples/atwood-machine.yaml");
  const auto& left = Named(s.at("reactions"), "left");
  const auto& right = Named(s.at("reactions"), "right");
  EXPECT_EQ(left.at("kind"), "string");
  EXPECT_TRUE(Near(left.at("multipliers").at(0).get<double>(), m1 * (g - a), kSolve));
  EXPECT_TRUE(Near(right.at("multipliers").at(0).get<double>(), m2 * (g + a), kSolve));
  // On the pulley (the child): each tension pulls its rim point down.
  EXPECT_TRUE(MatNear(ToVec(left.at("force")), Vec3(0, -m1 * (g - a), 0), kSolve, m1 * g));
  EXPECT_TRUE(MatNear(ToVec(left.at("point")), Vec3(-r, 0, 0), kSolve, r));
  EXPECT_TRUE(Near(Named(s.at("bodies"), "m1").at("acceleration").at(1).get<double>(), -a, kSolve));

  const auto j =
      SimulateJson(SourcePath("examples/atwood-machine.yaml"), OutDir("strings"), "--strict");
  const auto& b = j.at("final").at("bodies");
  const double drop = 0.5 * a * t * t;
  EXPECT_TRUE(Near(Named(b, "m1").at("planar").at("y").get<double>(), -1.0 - drop, kRun));
  EXPECT_TRUE(Near(Named(b, "m2").at("planar").at("y").get<double>(), -0.6 + drop, kRun));
  // The pulley turns counterclockwise with ω = a t / r.
  EXPECT_TRUE(Near(Named(b, "pulley").at("planar").at("omega").get<double>(), a * t / r, kRun));
  const auto& fr = j.at("final").at("reactions");
  EXPECT_TRUE(Near(ToVec(Named(fr, "right").at("force")).y(), -m2 * (g + a), kRun));
}

// examples/yo-yo.yaml: m = 0.2 kg, a disk of R = 3 cm (I = m R²/2), hub r = 8 mm, g = 9.81:
// a = g / (1 + I/(m r²)), T = m g I / (I + m r²); from rest it falls a t²/2 and spins
// clockwise at ω = -a t / r.
TEST(Strings, YoYoFallsOnItsString) {
  const double m = 0.2, R = 0.03, r = 0.008, g = 9.81, t = 0.5;
  const double I = 0.5 * m * R * R;
  const double a = g / (1 + I / (m * r * r));
  const double T = m * g * I / (I + m * r * r);
  const auto s = Solve("examples/yo-yo.yaml");
  const auto& str = Named(s.at("reactions"), "string");
  EXPECT_TRUE(Near(str.at("multipliers").at(0).get<double>(), T, kSolve));
  EXPECT_TRUE(MatNear(ToVec(str.at("force")), Vec3(0, T, 0), kSolve, T));
  const auto j = SimulateJson(SourcePath("examples/yo-yo.yaml"), OutDir("strings"), "--strict");
  const auto& yoyo = Named(j.at("final").at("bodies"), "yoyo").at("planar");
  EXPECT_TRUE(Near(yoyo.at("y").get<double>(), -0.5 * a * t * t, kRun));
  EXPECT_TRUE(Near(yoyo.at("vy").get<double>(), -a * t, kRun));
  EXPECT_TRUE(Near(yoyo.at("omega").get<double>(), -a * t / r, kRun));
  EXPECT_TRUE(Near(yoyo.at("x").get<double>(), 0.0, kRun, r));
}

// A mass m hangs on a string that goes up over a fixed pulley (x-z plane, normal y) and down
// to a point of the world: in equilibrium the tension is m g and nothing moves. The string is
// given from the body to the world, so the loader turns it round (senses flipped); a wrong
// flip would wrap the pulley on its other side and tilt the string.
TEST(Strings, MassHangingOverAPulleyToTheWorldIsInEquilibrium) {
  const double m = 2, g = 9.81;
  const auto file = OutDir("strings") / "hanging.yaml";
  {
    std::ofstream out(file);
    out << "chasles: 1\n"
           "bodies:\n"
           "  - name: m\n"
           "    parts: [{shape: sphere, radius: 3 cm, mass: 2 kg}]\n"
           "    initial: {position: [-10 cm, 0, -1 m]}\n"
           "gravity: 9.81 m/s^2\n"
           "strings:\n"
           "  - name: rope\n"
           "    from: {body: m}\n"
           "    over: [{center: [0, 0, 0], radius: 10 cm, sense: counterclockwise}]\n"
           "    to: {body: world, at: [10 cm, 0, -50 cm]}\n"
           "    normal: [0, 1, 0]\n";
  }
  const CliResult r = RunCli("solve " + Quote(file.string()) + " --format json --strict");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  const auto& rope = Named(j.at("reactions"), "rope");
  EXPECT_TRUE(Near(rope.at("multipliers").at(0).get<double>(), m * g, kSolve));
  EXPECT_TRUE(MatNear(ToVec(rope.at("force")), Vec3(0, 0, m * g), kSolve, m * g));
  EXPECT_TRUE(
      MatNear(ToVec(Named(j.at("bodies"), "m").at("acceleration")), Vec3::Zero(), kSolve, g));
}

}  // namespace
}  // namespace chasles::test
