// End-to-end: strings (`strings:`, docs/scene-format.md): the Atwood machine with a massive
// pulley and the yo-yo of examples/, through `chasles solve` (the tensions at the start) and
// `chasles simulate` (the motion from rest). The closed forms are derived here and in the
// examples' comments.

#include <cmath>
#include <cstdio>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <boost/math/quadrature/gauss_kronrod.hpp>

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

nlohmann::json Simulate(const std::string& file) {
  const auto out = OutDir("strings");
  const CliResult r =
      RunCli("simulate " + Quote(file) + " --format json --strict --out " + Quote(out.string()));
  if (r.exit_code != 0) throw std::runtime_error(file + ": " + r.err);
  return nlohmann::json::parse(r.out);
}

// examples/string-pendulum-goes-slack.yaml: m = 0.3 kg, l = 0.8 m, v0² = 3.5 g l. The tension
// T = m (v²/l + g cos φ) with v² = v0² - 2 g l (1 - cos φ) vanishes at cos φ_s = (2 g l - v0²) /
// (3 g l) = -1/2, reached at t_s = ∫₀^φs l dφ / v(φ); the flight on the parabola meets the
// circle again after τ = 4 v_s sin φ_s / g (|p(τ)|² - l² = τ³ (v_s·g + g² τ / 4), v_s
// tangential and v_s² = -g l cos φ_s), where the plastic snap takes ½ m v_r².
TEST(Strings, PendulumOnAStringGoesSlackAndSnapsTaut) {
  const double m = 0.3, l = 0.8, g = 9.81, v0 = std::sqrt(3.5 * g * l);
  const double cos_s = (2 * g * l - v0 * v0) / (3 * g * l), phi_s = std::acos(cos_s);
  const double vs = std::sqrt(-g * l * cos_s);
  const double t_s = boost::math::quadrature::gauss_kronrod<double, 61>::integrate(
      [&](double phi) { return l / std::sqrt(v0 * v0 - 2 * g * l * (1 - std::cos(phi))); }, 0.0,
      phi_s, 15, 1e-15);
  const double tau = 4 * vs * std::sin(phi_s) / g;
  const Vec3 p_s(l * std::sin(phi_s), -l * cos_s, 0), v_s = vs * Vec3(cos_s, std::sin(phi_s), 0);
  const Vec3 p = p_s + v_s * tau + 0.5 * Vec3(0, -g, 0) * tau * tau;
  const double v_r = (v_s + Vec3(0, -g, 0) * tau).dot(p / l);
  const auto j = Simulate(SourcePath("examples/string-pendulum-goes-slack.yaml"));
  const auto& ev = j.at("string_events");
  ASSERT_EQ(ev.size(), 3u) << ev.dump();
  EXPECT_EQ(ev[0].at("reason"), "initial");
  EXPECT_EQ(ev[0].at("to"), "taut");
  EXPECT_EQ(ev[1].at("reason"), "went slack");
  EXPECT_EQ(ev[1].at("to"), "slack");
  EXPECT_TRUE(Near(ev[1].at("t").get<double>(), t_s, kRun));
  EXPECT_EQ(ev[2].at("reason"), "snapped taut");
  EXPECT_EQ(ev[2].at("from"), "slack");
  EXPECT_EQ(ev[2].at("to"), "taut");
  EXPECT_TRUE(Near(ev[2].at("t").get<double>(), t_s + tau, kRun));
  EXPECT_TRUE(Near(ev[2].at("approach_speed").get<double>(), v_r, 1e-8));
  EXPECT_TRUE(Near(ev[2].at("impulse").get<double>(), m * v_r, 1e-8));
  EXPECT_TRUE(Near(ev[2].at("energy_lost").get<double>(), 0.5 * m * v_r * v_r, 1e-8));
  const auto& L = j.at("ledger");
  EXPECT_TRUE(Near(L.at("impact_work").get<double>(), -0.5 * m * v_r * v_r, 1e-8));
  EXPECT_TRUE(Near(L.at("dissipated").get<double>(), 0.5 * m * v_r * v_r, 1e-8));
}

// examples/block-thrown-up-on-a-string.yaml: m = 2 kg on l = 1.5 m, thrown up at v0 = 1.2 m/s,
// restitution e = 0.5: slack at once, then snaps at t_k = (2 v0/g)(1 + e + ... + e^(k-1)) with
// approach speed e^(k-1) v0, impulse m (1 + e) e^(k-1) v0 and ½ m (e^(k-1) v0)² (1 - e²) lost.
TEST(Strings, BlockThrownUpOnAStringRebounds) {
  const double m = 2, v0 = 1.2, g = 9.81, e = 0.5;
  const auto j = Simulate(SourcePath("examples/block-thrown-up-on-a-string.yaml"));
  const auto& ev = j.at("string_events");
  ASSERT_EQ(ev.size(), 4u) << ev.dump();
  EXPECT_EQ(ev[0].at("reason"), "initial");  // opening at once: slack from the start
  EXPECT_EQ(ev[0].at("to"), "slack");
  double t = 0.0, v = v0, lost = 0.0;
  for (size_t k = 1; k < 4; ++k) {
    t += 2 * v / g;
    EXPECT_EQ(ev[k].at("reason"), "snapped taut");
    EXPECT_EQ(ev[k].at("to"), "slack");
    EXPECT_TRUE(Near(ev[k].at("t").get<double>(), t, kRun)) << k;
    EXPECT_TRUE(Near(ev[k].at("approach_speed").get<double>(), v, kRun)) << k;
    EXPECT_TRUE(Near(ev[k].at("impulse").get<double>(), m * (1 + e) * v, kRun)) << k;
    EXPECT_TRUE(Near(ev[k].at("energy_lost").get<double>(), 0.5 * m * v * v * (1 - e * e), kRun));
    lost += 0.5 * m * v * v * (1 - e * e);
    v *= e;
  }
  EXPECT_TRUE(Near(j.at("ledger").at("dissipated").get<double>(), lost, kRun));
}

// examples/movable-pulley.yaml with the block m2 (carrying the pulley) thrown up at v0 and m1 at
// rest: the length L = 2 (y_f - y2) + (y_f - y1) + arcs changes at -2 v2 - v1 = -2 v0, so the
// string is slack at once and both fall freely; the slack g = 2 (y2 - y20) + (y1 - y10) =
// 2 v0 t - (3/2) g t² closes again at t* = 4 v0 / (3 g), at the rate 2 v0. The plastic snap
// is an impulse P (tension) with m2 Δv2 = 2 P, m1 Δv1 = P and 2 Δv2 + Δv1 = 2 v0:
// P = 2 v0 / (4/m2 + 1/m1), taking ½ (2 v0)² / (4/m2 + 1/m1). Then taut: a2 = g/8.
TEST(Strings, MovablePulleyThrownUpGoesSlackAndSnapsTaut) {
  const double m1 = 1.5, m2 = 2, g = 9.81, v0 = 1.0;
  std::ifstream in(SourcePath("examples/movable-pulley.yaml"));
  std::stringstream ss;
  ss << in.rdbuf();
  std::string text = ss.str();
  const std::string from = "initial: {position: [0, -1.5 m]}";
  const size_t at = text.find(from);
  ASSERT_NE(at, std::string::npos);
  text.replace(at, from.size(), "initial: {position: [0, -1.5 m], velocity: [0, 1 m/s]}");
  const auto path = OutDir("strings") / "movable-pulley-thrown-up.yaml";
  std::ofstream(path) << text;
  const auto j = Simulate(path.string());
  const double t_star = 4 * v0 / (3 * g), k = 4 / m2 + 1 / m1;
  const auto& ev = j.at("string_events");
  ASSERT_EQ(ev.size(), 2u) << ev.dump();
  EXPECT_EQ(ev[0].at("reason"), "initial");
  EXPECT_EQ(ev[0].at("to"), "slack");
  EXPECT_EQ(ev[1].at("reason"), "snapped taut");
  EXPECT_EQ(ev[1].at("to"), "taut");
  EXPECT_TRUE(Near(ev[1].at("t").get<double>(), t_star, kRun));
  EXPECT_TRUE(Near(ev[1].at("approach_speed").get<double>(), 2 * v0, kRun));
  EXPECT_TRUE(Near(ev[1].at("impulse").get<double>(), 2 * v0 / k, kRun));
  EXPECT_TRUE(Near(ev[1].at("energy_lost").get<double>(), 0.5 * 4 * v0 * v0 / k, kRun));
  // After the snap (t = 0.5 s): v2 = v0 - g t* + 2P/m2 + (g/8)(t - t*), v1 from a1 = -2 a2.
  const double P = 2 * v0 / k, t = 0.5;
  const double v2 = v0 - g * t_star + 2 * P / m2 + g / 8 * (t - t_star);
  const double v1 = -g * t_star + P / m1 - g / 4 * (t - t_star);
  const auto& fin = j.at("final").at("bodies");
  EXPECT_NEAR(Named(fin, "m2").at("velocity")[1].get<double>(), v2, kRun * v0);
  EXPECT_NEAR(Named(fin, "m1").at("velocity")[1].get<double>(), v1, kRun * v0);
}

// `chasles solve` chooses taut or slack: a particle on a string at φ = 120° from the bottom
// moving along the circle at v needs T = m (v²/l + g cos φ), >= 0 only for v² >= g l / 2. Just
// above that the string is taut with that tension, just below slack (T = 0, free fall).
TEST(Strings, SolveSaysWhetherTheStringIsTautOrSlack) {
  const double m = 0.3, l = 0.8, g = 9.81;
  for (const double k : {1.0 + 1e-6, 1.0 - 1e-6}) {
    const auto file = OutDir("strings") / "boundary.yaml";
    char k_text[32];
    std::snprintf(k_text, sizeof k_text, "%.17g", k);
    {
      std::ofstream out(file);
      out << "chasles: 1\n"
             "parameters: {l: 0.8 m, g: 9.81 m/s^2, k: "
          << k_text
          << "}\n"
             "bodies:\n"
             "  - name: bob\n"
             "    parts: [{shape: point, mass: 0.3 kg, position: [0, 0, 0]}]\n"
             "    initial: {position: [l*sin(120 deg), -l*cos(120 deg), 0],\n"
             "              velocity: [k*sqrt(g*l/2)*cos(120 deg), k*sqrt(g*l/2)*sin(120 deg), "
             "0]}\n"
             "gravity: [0, -g, 0]\n"
             "strings:\n"
             "  - {name: string, from: {body: world, at: [0, 0, 0]}, to: {body: bob}}\n";
    }
    const CliResult r = RunCli("solve " + Quote(file.string()) + " --format json --strict");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    const auto& s = Named(j.at("reactions"), "string");
    const double v2 = k * k * g * l / 2;
    const double T = m * (v2 / l + g * std::cos(2 * std::numbers::pi / 3));
    if (k > 1.0) {
      EXPECT_EQ(s.at("mode"), "taut");
      EXPECT_TRUE(Near(s.at("tension").get<double>(), T, 1e-6));
    } else {
      EXPECT_EQ(s.at("mode"), "slack");
      EXPECT_EQ(s.at("tension").get<double>(), 0.0);
      EXPECT_TRUE(MatNear(ToVec(Named(j.at("bodies"), "bob").at("acceleration")), Vec3(0, -g, 0),
                          kSolve, g));
    }
    const CliResult text = RunCli("solve " + Quote(file.string()));
    EXPECT_THAT(text.out, ::testing::HasSubstr(k > 1.0 ? "taut: tension" : "slack: tension"));
  }
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
  // Turned round so that the world is its first end: said, not silent.
  ASSERT_TRUE(j.contains("warnings"));
  EXPECT_THAT(j.at("warnings").dump(), ::testing::HasSubstr("string 'rope' is given from body 'm' "
                                                            "to the world"));
}

}  // namespace
}  // namespace chasles::test
