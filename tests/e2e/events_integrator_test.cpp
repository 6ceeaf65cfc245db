// End-to-end: `integrator: events` (balls on a table, event-driven: docs/scene-format.md,
// `simulation`) through the chasles program, against the closed forms of
// examples/pool-head-on-events.yaml, against the adaptive integrator on the same scene, over
// a sweep, and with the scenes it must refuse.

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "cli_runner.h"
#include "test_support.h"

namespace chasles::test {
namespace {

constexpr double kG = 9.80665;  // `gravity: standard` [m/s²]
constexpr double kR = 0.028575, kMuK = 0.2, kE = 0.93;

std::filesystem::path Out() {
  return OutDir("events_integrator");
}

std::string WriteScene(const std::string& name, const std::string& text) {
  const auto path = Out() / name;
  std::ofstream(path) << text;
  return path.string();
}

std::string ReadExample(const std::string& example) {
  std::ifstream in(SourcePath(example));
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// `text` with its first `from` replaced by `to` (which must be there).
std::string Replace(std::string text, const std::string& from, const std::string& to) {
  const size_t at = text.find(from);
  if (at == std::string::npos) throw std::runtime_error("no '" + from + "' in the scene");
  return text.replace(at, from.size(), to);
}

const nlohmann::json& Body(const nlohmann::json& final_state, const std::string& name) {
  for (const auto& b : final_state.at("bodies")) {
    if (b.at("name") == name) return b;
  }
  throw std::runtime_error("no body " + name);
}

// The times at which `point` went from mode `from` to `to`.
std::vector<double> Changes(const nlohmann::json& run, const std::string& point,
                            const std::string& from, const std::string& to) {
  std::vector<double> t;
  for (const auto& e : run.at("contact_events")) {
    if (e.at("point") == point && e.at("from") == from && e.at("to") == to) {
      t.push_back(e.at("t").get<double>());
    }
  }
  return t;
}

// The times of the contact changes of `point` with `reason`.
std::vector<double> Times(const nlohmann::json& run, const std::string& point,
                          const std::string& reason) {
  std::vector<double> t;
  for (const auto& e : run.at("contact_events")) {
    if (e.at("point") == point && e.at("reason") == reason) t.push_back(e.at("t").get<double>());
  }
  return t;
}

// The example's closed forms (derived in its comments): rolling at v = 2 m/s the cue ball
// meets the object ball at t1 = (d - 2R)/v; then v_A = v (1 - e)/2, v_B = v (1 + e)/2; both
// slips are v (1 + e)/2 and stop together after 2 v_B / (7 mu_k g), A rolling at
// (5 v_A + 2 v)/7 and B at 5/7 v_B. The kinetic energy lost in the hit is
// ½ (m/2) (1 - e²) v².
TEST(EventsIntegrator, HeadOnExampleMatchesTheClosedForms) {
  const nlohmann::json run = SimulateJson(SourcePath("examples/pool-head-on-events.yaml"), Out());
  const double v = 2.0, d = 0.5, m = 0.17;
  const double t1 = (d - 2 * kR) / v, vA = v * (1 - kE) / 2, vB = v * (1 + kE) / 2;
  const double t2 = t1 + 2 * vB / (7 * kMuK * kG);
  EXPECT_EQ(run.at("integrator").at("name"), "events");
  const auto& ed = run.at("integrator").at("event_driven");
  EXPECT_EQ(ed.at("collisions").get<int>(), 1);
  EXPECT_EQ(ed.at("pressing_groups").get<int>(), 0);
  EXPECT_LT(std::abs(ed.at("energy").at("residual").get<double>()), 1e-15);
  ASSERT_EQ(run.at("impacts").size(), 1u);
  const auto& hit = run.at("impacts")[0];
  EXPECT_EQ(hit.at("point"), "cue | object");
  EXPECT_TRUE(Near(hit.at("t").get<double>(), t1, 1e-15));
  EXPECT_TRUE(Near(hit.at("approach_speed").get<double>(), v, 1e-14));
  EXPECT_TRUE(Near(hit.at("energy_lost").get<double>(), 0.25 * m * (1 - kE * kE) * v * v, 1e-13));
  for (const char* point : {"cloth_cue", "cloth_object"}) {
    SCOPED_TRACE(point);
    ASSERT_EQ(Times(run, point, "collision").size(), 1u);
    EXPECT_TRUE(Near(Times(run, point, "collision")[0], t1, 1e-15));
    ASSERT_EQ(Times(run, point, "slip stopped").size(), 1u);
    EXPECT_TRUE(Near(Times(run, point, "slip stopped")[0], t2, 1e-14));
  }
  const auto& fin = run.at("final");
  EXPECT_TRUE(Near(ToVec(Body(fin, "cue").at("velocity")).x(), (5 * vA + 2 * v) / 7, 1e-14));
  EXPECT_TRUE(Near(ToVec(Body(fin, "object").at("velocity")).x(), 5.0 / 7.0 * vB, 1e-14));
  // The run's checks: the ledger (impacts and friction from the states) closes at every row.
  EXPECT_TRUE(run.at("checks").at("passed").get<bool>());
  const auto& ledger = run.at("ledger");
  EXPECT_TRUE(
      Near(ledger.at("impact_work").get<double>(), -0.25 * m * (1 - kE * kE) * v * v, 1e-13));
}

// The same scene with the pair listed as a contact and the adaptive integrator (events located
// on the dense output to 1e-12 s) gives the same collision, slip stops and final speeds.
TEST(EventsIntegrator, AgreesWithTheAdaptiveIntegratorOnTheSameScene) {
  const std::string example = ReadExample("examples/pool-head-on-events.yaml");
  std::string adaptive =
      Replace(example, "  integrator: events\n  ball_collisions: {restitution: e}\n",
              "  tolerance: 1e-12\n");
  adaptive = Replace(adaptive, "simulation:\n",
                     "  - {name: knock, body: object, shape: sphere, radius: R, with: cue, "
                     "other_radius: R, restitution: e}\nsimulation:\n");
  const nlohmann::json events =
      SimulateJson(SourcePath("examples/pool-head-on-events.yaml"), Out());
  const nlohmann::json hybrid = SimulateJson(WriteScene("head_on_adaptive.yaml", adaptive), Out());
  EXPECT_NE(hybrid.at("integrator").at("name"), "events");
  ASSERT_EQ(hybrid.at("impacts").size(), 1u);
  EXPECT_TRUE(Near(hybrid.at("impacts")[0].at("t").get<double>(),
                   events.at("impacts")[0].at("t").get<double>(), 1e-11));
  for (const char* point : {"cloth_cue", "cloth_object"}) {
    SCOPED_TRACE(point);
    // (The adaptive integrator names one of the two simultaneous stops a re-selection.)
    const auto a = Changes(events, point, "sliding", "sticking");
    const auto b = Changes(hybrid, point, "sliding", "sticking");
    ASSERT_EQ(a.size(), 1u);
    ASSERT_EQ(b.size(), 1u);
    EXPECT_TRUE(Near(b[0], a[0], 1e-10));
  }
  for (const char* body : {"cue", "object"}) {
    SCOPED_TRACE(body);
    const auto& x = Body(events.at("final"), body);
    const auto& y = Body(hybrid.at("final"), body);
    EXPECT_TRUE(MatNear(ToVec(y.at("velocity")), ToVec(x.at("velocity")), 1e-10));
    EXPECT_TRUE(MatNear(ToVec(y.at("center_of_mass")), ToVec(x.at("center_of_mass")), 1e-10));
  }
}

// A sweep over the cue ball's speed: the object ball ends rolling at 5/7 v (1 + e)/2.
TEST(EventsIntegrator, SweepsOverTheCueBallsSpeed) {
  const CliResult r = RunCli("simulate " + Quote(SourcePath("examples/pool-head-on-events.yaml")) +
                             " --sweep 'v=1 m/s:3 m/s:3' --quantity 'final(object_vx)' "
                             "--format json --quiet");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  ASSERT_EQ(j.at("rows").size(), 3u);
  for (size_t k = 0; k < 3; ++k) {
    const double v = 1.0 + static_cast<double>(k);
    EXPECT_TRUE(Near(j.at("rows")[k][1].get<double>(), 5.0 / 7.0 * v * (1 + kE) / 2, 1e-14));
  }
}

// What the event-driven path cannot run is refused with exit code 2, at the line of the key
// that asks for it (or of the element that does not fit), saying what to do instead.
TEST(EventsIntegrator, RefusesWhatItCannotRun) {
  const std::string example = ReadExample("examples/pool-head-on-events.yaml");
  struct Case {
    std::string name, scene, where, says;
  };
  const std::vector<Case> cases = {
      {"collisions_on_the_adaptive_engine",
       Replace(example, "  integrator: events\n", "  integrator: adaptive\n"), "ball_collisions",
       "only 'integrator: events', 'stepping' and 'auto' do"},
      {"step", Replace(example, "  integrator: events\n", "  integrator: events\n  step: 1 ms\n"),
       "step", "takes no steps"},
      {"scene_event", example + "events:\n  - {name: half, when: cue_x, crosses: 0.25 m}\n",
       "events", "integrator: adaptive"},
      {"box",
       Replace(example, "shape: sphere, radius: R, mu_s: 0.25, mu_k: mu_k,\n     plane",
               "shape: box, size: [R, R, R], mu_s: 0.25, mu_k: mu_k,\n     plane"),
       "cloth_cue", "balls on a table only"},
      {"spring",
       example + "forces:\n  - {name: tie, type: spring, from: {body: cue}, to: "
                 "{body: object}, stiffness: 10 N/m, rest_length: 0.5 m}\n",
       "tie", "not uniform gravity"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    const std::string path = WriteScene(c.name + ".yaml", c.scene);
    const CliResult r = RunCli("simulate " + Quote(path) + " --out " + Quote(Out().string()));
    EXPECT_EQ(r.exit_code, 2) << r.out << r.err;
    EXPECT_THAT(r.err, testing::HasSubstr(c.says));
    EXPECT_THAT(r.err, testing::HasSubstr(c.where));
    EXPECT_FALSE(std::filesystem::exists(Out() / (c.name + ".csv")));
  }
}

// The work limits hold: every event (and every pressing-group step) counts against max_steps,
// and the run stops at the limit with exit code 2, at the `simulation` key, writing nothing.
TEST(EventsIntegrator, StopsAtTheStepLimit) {
  const std::string scene = WriteScene("break.yaml", ReadExample("examples/pool-break.yaml"));
  const CliResult r =
      RunCli("simulate " + Quote(scene) + " --max-steps 20 --out " + Quote(Out().string()));
  EXPECT_EQ(r.exit_code, 2) << r.out;
  EXPECT_THAT(r.err, testing::HasSubstr("limit of 20 steps (events, and the pressing groups'"));
  EXPECT_THAT(r.err, testing::HasSubstr("--max-steps"));
  EXPECT_FALSE(std::filesystem::exists(Out() / "break.csv"));
}

}  // namespace
}  // namespace chasles::test
