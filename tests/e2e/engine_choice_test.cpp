// End-to-end: `integrator: auto` (docs/contact.md, "Choosing the engine") through the chasles
// program. On every shipped example with contacts or strings that names no integrator (auto is
// the default there) it never switches and gives the event-driven answer bit for bit; on
// examples/contact-cube-tumbles-auto.yaml it switches to time stepping and back, says so, and its
// answer after the switches meets the closed forms in the scene's comments.

#include <cmath>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "cli_runner.h"
#include "test_support.h"

namespace chasles::test {
namespace {

constexpr double kG = 9.80665;
// Event times are located to 1e-12 s each; one summed over a few dozen events is known to this
// absolute tolerance [s].
constexpr double kEventTime = 1e-10;
// A state the event-driven engine's start has projected onto the contacts, and the forces at
// it: round-off relative to the scene's scale.
constexpr double kProjected = 1e-12;

std::string ReadText(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// The scene's text with `integrator: NAME` added to its `simulation` block (block or flow
// style).
std::string WithIntegrator(const std::string& text, const std::string& name) {
  static const std::regex flow(R"(\nsimulation: \{)");
  if (std::regex_search(text, flow)) {
    return std::regex_replace(text, flow, "\nsimulation: {integrator: " + name + ", ");
  }
  const size_t at = text.find("\nsimulation:\n");
  return text.substr(0, at) + "\nsimulation:\n  integrator: " + name + text.substr(at + 12);
}

// The JSON summary without what names the engine or the files: the integrator section and run
// path, the ledger's time-stepping term (auto only), the scene and CSV paths.
nlohmann::json Answer(nlohmann::json j) {
  j.erase("integrator");
  j.erase("run_path");
  j.erase("scene");
  j.erase("csv");
  j.at("ledger").erase("time_stepping_error");
  return j;
}

// Every shipped example with contacts or strings that names no integrator, run as it is (auto,
// the default where there are contacts) and with `integrator: adaptive` (the event-driven
// engine): auto never switches on them, and every number of the CSV and the JSON summary is
// the same, bit for bit (the CSV prints the shortest text that reads back as the same double;
// JSON numbers compare as doubles). A scene with strings and no contacts runs adaptive by
// default, and `integrator: auto` is written into it.
TEST(EngineChoice, AutoGivesTheEventDrivenAnswerBitForBit) {
  const std::filesystem::path out = OutDir("engine_choice");
  int compared = 0;
  for (const auto& entry : std::filesystem::directory_iterator(SourcePath("examples"))) {
    if (entry.path().extension() != ".yaml") continue;
    const std::string text = ReadText(entry.path());
    const bool hybrid = text.find("\ncontacts:") != std::string::npos ||
                        text.find("\nstrings:") != std::string::npos;
    if (!hybrid || text.find("\nsimulation:") == std::string::npos ||
        text.find("integrator:") != std::string::npos) {
      continue;  // no contact run, or an engine the scene names
    }
    // Under the sanitizers every fourth (the ordinary run compares them all).
    if (!Sampled(compared++)) continue;
    const std::string name = entry.path().filename().string();
    const bool contacts = text.find("\ncontacts:") != std::string::npos;
    for (const char* dir : {"adaptive", "auto"}) {
      std::filesystem::create_directories(out / dir);
      std::ofstream(out / dir / name)
          << (std::string(dir) == "adaptive" ? WithIntegrator(text, "adaptive")
              : contacts                     ? text
                                             : WithIntegrator(text, "auto"));
    }
    const nlohmann::json a = SimulateJson((out / "adaptive" / name).string(), out / "adaptive");
    const nlohmann::json b = SimulateJson((out / "auto" / name).string(), out / "auto");
    ASSERT_EQ(b.at("integrator").at("name"), "auto") << name;
    EXPECT_EQ(b.at("integrator").at("auto").at("default").get<bool>(), contacts) << name;
    const nlohmann::json& segments = b.at("integrator").at("segments");
    ASSERT_EQ(segments.size(), 1u) << name << ": " << segments.dump(2);
    EXPECT_EQ(segments[0].at("engine"), "adaptive") << name;
    EXPECT_EQ(Answer(a), Answer(b)) << name;
    const std::string csv = entry.path().stem().string() + ".csv";
    EXPECT_EQ(ReadText(out / "adaptive" / csv), ReadText(out / "auto" / csv)) << name;
  }
  EXPECT_GE(compared, 30);
}

// examples/contact-cube-tumbles-auto.yaml: event-driven until the rocking chatters, time
// stepped, event-driven again at rest and through the kick, with the closed forms of its
// comments: at rest, centre a/2 above the floor, flat, v = 0, N = m g in all, energy m g a/2;
// kicked at t_k with J through the centre, it slides at v0 = J/m until t_k + v0/(mu g), over
// v0²/(2 mu g).
TEST(EngineChoice, TumblingCubeSwitchesToSteppingAndBack) {
  const double m = 1.0, a = 0.2, mu = 0.3, t_k = 1.2, J = 0.6, v0 = J / m;
  const std::filesystem::path out = OutDir("engine_choice_cube");
  const std::string scene = SourcePath("examples/contact-cube-tumbles-auto.yaml");
  const nlohmann::json j = SimulateJson(scene, out, "--strict");
  const nlohmann::json& segments = j.at("integrator").at("segments");
  ASSERT_GE(segments.size(), 3u) << segments.dump(2);
  EXPECT_EQ(segments.front().at("reason"), "start");
  EXPECT_EQ(segments.front().at("t_begin"), 0.0);
  EXPECT_EQ(segments.back().at("t_end"), 1.6);
  for (size_t i = 0; i < segments.size(); ++i) {
    const nlohmann::json& g = segments[i];
    // The engines alternate, each starting where the last ended, for the reason it says.
    EXPECT_EQ(g.at("engine"), i % 2 == 0 ? "adaptive" : "stepping") << i;
    if (i > 0) {
      EXPECT_EQ(g.at("t_begin"), segments[i - 1].at("t_end")) << i;
    }
    if (g.at("engine") == "stepping") {
      EXPECT_EQ(g.at("reason"), "regime changes") << i;
      EXPECT_EQ(g.at("changes"), 8) << i;
      EXPECT_LE(g.at("span").get<double>(), j.at("integrator").at("auto").at("window")) << i;
      EXPECT_GT(g.at("steps"), 0) << i;
      EXPECT_GE(g.at("time_stepping").at("regime_changes"), 1) << i;
    } else if (i > 0) {
      EXPECT_EQ(g.at("reason"), "quiet") << i;
      EXPECT_GE(g.at("quiet").get<double>(), j.at("integrator").at("auto").at("quiet_span")) << i;
    }
  }
  // The step: 1/100 of √(ρ/g), ρ = a/√6 the cube's radius of gyration.
  EXPECT_NEAR(j.at("integrator").at("auto").at("step").get<double>(),
              0.01 * std::sqrt(a / std::sqrt(6.0) / kG), 1e-15);
  // Event-driven again before the kick, and to the end.
  EXPECT_LT(segments.back().at("t_begin").get<double>(), t_k);
  // The kick: the slip stops at t_k + v0/(mu g), all four corners at once.
  int stops = 0;
  for (const auto& e : j.at("contact_events")) {
    if (e.at("reason") != "slip stopped") continue;
    EXPECT_NEAR(e.at("t").get<double>(), t_k + v0 / (mu * kG), kEventTime);
    ++stops;
  }
  EXPECT_EQ(stops, 1);
  // At rest at the end, flat on four corners.
  const auto csv = ReadCsv((out / "contact-cube-tumbles-auto.csv").string());
  const std::vector<double>& t = csv.at("t");
  size_t kick = 0;
  while (!(t[kick] == t_k && csv.at("cube_vx")[kick] > 0.5 * v0)) ++kick;  // just after it
  EXPECT_NEAR(csv.at("cube_x").back() - csv.at("cube_x")[kick], v0 * v0 / (2 * mu * kG),
              1e-9 * v0 * v0 / (2 * mu * kG));
  EXPECT_NEAR(csv.at("cube_z").back(), a / 2, kProjected * a);
  EXPECT_NEAR(csv.at("cube_tilt").back(), 0.0, kProjected);
  EXPECT_LT(std::abs(csv.at("cube_vx").back()), kProjected);
  double N = 0.0;
  for (const auto& c : j.at("final").at("contacts")) N += c.at("normal_force").get<double>();
  EXPECT_NEAR(N, m * kG, kProjected * m * kG);
  EXPECT_NEAR(j.at("ledger").at("energy").get<double>(), m * kG * a / 2, kProjected * m * kG * a);
  // The certificate passed (--strict), and the ledger's residual is time stepping's own term.
  EXPECT_TRUE(j.at("checks").at("passed").get<bool>());
  const double residual = j.at("ledger").at("residual").get<double>();
  EXPECT_NEAR(residual, j.at("ledger").at("time_stepping_error").get<double>(),
              1e-9 * j.at("ledger").at("energy_scale").get<double>());
  // The text report lists each engine's stretch and why it took over.
  const CliResult text =
      RunCli("simulate " + Quote(scene) + " --out " + Quote(out.string()) + " --strict");
  ASSERT_EQ(text.exit_code, 0) << text.err;
  EXPECT_THAT(text.out, ::testing::HasSubstr("Integrator: auto"));
  EXPECT_THAT(text.out, ::testing::HasSubstr("stepping, 8 regime changes within"));
  EXPECT_THAT(text.out, ::testing::HasSubstr("adaptive, no regime change for"));
  EXPECT_THAT(text.out, ::testing::HasSubstr("time stepping's own"));
}

// What `integrator: auto` refuses or cannot do is said: a scene time stepping cannot run (here
// the shipped ladder, auto by default) stays event-driven, and its first segment says why; with
// `ball_collisions` only time stepping finds the pairs, so the pool break with its rolling
// resistance (which time stepping does not model) is refused with both reasons, pointing at
// `integrator: events`.
TEST(EngineChoice, SaysWhyItStaysEventDriven) {
  const std::filesystem::path out = OutDir("engine_choice_stays");
  const nlohmann::json j = SimulateJson(SourcePath("examples/ladder-leaves-wall.yaml"), out);
  EXPECT_TRUE(j.at("integrator").at("auto").at("default").get<bool>());
  const nlohmann::json& segments = j.at("integrator").at("segments");
  ASSERT_EQ(segments.size(), 1u);
  EXPECT_THAT(segments[0].at("stays_event_driven").get<std::string>(),
              ::testing::HasSubstr("events are located on the adaptive integrator's dense output"));
  const std::string pool = ReadText(SourcePath("examples/pool-break.yaml"));
  std::ofstream(out / "pool.yaml")
      << std::regex_replace(pool, std::regex("integrator: events"), "integrator: auto");
  const CliResult r =
      RunCli("simulate " + Quote((out / "pool.yaml").string()) + " --out " + Quote(out.string()));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, ::testing::HasSubstr("pool.yaml:40:5: contacts[0]: integrator auto: every "
                                          "pair of balls may collide (ball_collisions), and only "
                                          "time stepping finds the pairs, which cannot run this "
                                          "scene: contact 'cloth_cue'"));
  EXPECT_THAT(r.err, ::testing::HasSubstr("rolling resistance (mu_r)"));
  EXPECT_THAT(r.err, ::testing::HasSubstr("may name 'integrator: events'"));
}

}  // namespace
}  // namespace chasles::test
