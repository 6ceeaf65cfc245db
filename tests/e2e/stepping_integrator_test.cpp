// End-to-end: `integrator: stepping` (Moreau–Jean time stepping: docs/scene-format.md,
// `simulation`, and docs/contact.md, "Time stepping") through the chasles program, against
// closed forms: the spinning ball of Problems 8.26/8.27, the box held on a slope
// (examples/contact-box-held-on-slope.yaml), and the certificate in the report and the JSON.

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <regex>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "chasles/integrate/time_stepping.h"
#include "cli_runner.h"
#include "reference/balls_on_floor.h"
#include "test_support.h"

namespace chasles::test {
namespace {

constexpr double kG = 9.80665;  // `gravity: standard` [m/s²]
// Round-off of quantities of scale 1 over a run of some thousand steps.
constexpr double kRoundOff = 1e-12;

std::filesystem::path Out() {
  return OutDir("stepping_integrator");
}

std::string WriteScene(const std::string& name, const std::string& text) {
  const auto path = Out() / name;
  std::ofstream(path) << text;
  return path.string();
}

std::string ReadFile(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

std::string ReadExample(const std::string& example) {
  return ReadFile(SourcePath(example));
}

// `text` with its first `from` replaced by `to` (which must be there).
std::string Replace(std::string text, const std::string& from, const std::string& to) {
  const size_t at = text.find(from);
  if (at == std::string::npos) throw std::runtime_error("no '" + from + "' in the scene");
  return text.replace(at, from.size(), to);
}

// Problems 8.26/8.27 (examples/problem-8.26-spinning-ball.yaml) time stepped at h = 1 ms:
// the scheme keeps the angular momentum about the contact line (friction acts at the contact
// point, gravity and the normal impulse through it), so the ball rolls at v* = 2/7 R w0 to
// round-off whatever the step, and friction has taken ½ I w0² - ½ (m + I/R²) v*² (I = 2/5 m R²);
// the slip stops within a step of t* = 25 ms.
TEST(SteppingIntegrator, SpinningBallRollsAtTheClosedFormSpeed) {
  const double h = 1e-3;
  const std::string scene =
      Replace(ReadExample("examples/problem-8.26-spinning-ball.yaml"), "  tolerance: 1e-12\n",
              "  integrator: stepping\n  step: 1 ms\n");
  const nlohmann::json run =
      SimulateJson(WriteScene("spinning_ball.yaml", scene), Out(), "--strict");
  const double R = 9.0 / 8.0 * 0.0254, m = 0.17, w0 = 100 * 2 * std::numbers::pi / 60;
  const double t_star = 0.025, v = 2.0 / 7.0 * R * w0, I = 0.4 * m * R * R;
  const auto& in = run.at("integrator");
  EXPECT_EQ(in.at("name"), "stepping");
  const auto& ts = in.at("time_stepping");
  EXPECT_EQ(ts.at("step").get<double>(), h);
  EXPECT_TRUE(ts.at("tolerance_met").get<bool>());
  const auto& ball = run.at("final").at("bodies")[0];
  EXPECT_TRUE(Near(ToVec(ball.at("velocity")).x(), v, kRoundOff));
  EXPECT_TRUE(Near(ToVec(ball.at("angular_velocity")).y() * R, v, kRoundOff));
  // The certificate: impulses applied exactly, the solver's residual and the ledger.
  const double E0 = ts.at("energy").at("initial").get<double>();
  EXPECT_TRUE(Near(E0, 0.5 * I * w0 * w0 + m * kG * R, kRoundOff));
  const double lost = 0.5 * I * w0 * w0 - 0.5 * (m + I / (R * R)) * v * v;
  EXPECT_TRUE(Near(ts.at("energy").at("friction_impulses").get<double>(), -lost, kRoundOff, E0));
  EXPECT_LE(std::abs(ts.at("energy").at("scheme_error").get<double>()), kRoundOff * E0);
  EXPECT_LE(ts.at("momentum_residual").get<double>(), kRoundOff * m * v);
  EXPECT_LE(ts.at("residual_impulse").get<double>(), kRoundOff * m * R * w0);
  EXPECT_LE(ts.at("max_penetration").get<double>(), kRoundOff * R);
  // One point: separated -> sliding in the first step, sliding -> sticking at t*.
  ASSERT_EQ(ts.at("points").size(), 1u);
  EXPECT_EQ(ts.at("points")[0].at("point"), "floor");
  EXPECT_EQ(ts.at("points")[0].at("regime_changes").get<int>(), 2);
  EXPECT_EQ(ts.at("regime_changes").get<int>(), 2);
  int stops = 0;
  for (const auto& e : run.at("contact_events")) {
    if (e.at("from") != "sliding" || e.at("to") != "sticking") continue;
    ++stops;
    EXPECT_EQ(e.at("reason"), "time step");
    EXPECT_LE(std::abs(e.at("t").get<double>() - t_star), h + kRoundOff);
  }
  EXPECT_EQ(stops, 1);
  EXPECT_TRUE(run.at("checks").at("passed").get<bool>());
  EXPECT_TRUE(Near(run.at("ledger").at("friction_work").get<double>(), -lost, kRoundOff, E0));
}

// examples/contact-box-held-on-slope.yaml: no creep. The box stays where it was set down, to
// 1e-12 m after 10 s, its four corners sticking from the first step on.
TEST(SteppingIntegrator, BoxHeldOnASlopeDoesNotCreep) {
  const nlohmann::json run =
      SimulateJson(SourcePath("examples/contact-box-held-on-slope.yaml"), Out(), "--strict");
  const double mu_s = 0.4, theta = std::atan(0.95 * mu_s), c = 0.06;
  const Eigen::Vector3d p0(-c / 2 * std::sin(theta), 0, c / 2 * std::cos(theta));
  const auto& box = run.at("final").at("bodies")[0];
  EXPECT_LT((ToVec(box.at("center_of_mass")) - p0).norm(), 1e-12);
  EXPECT_LT(ToVec(box.at("velocity")).norm(), 1e-12);
  const auto& ts = run.at("integrator").at("time_stepping");
  EXPECT_EQ(ts.at("regime_changes").get<int>(), 4);
  EXPECT_TRUE(ts.at("tolerance_met").get<bool>());
  EXPECT_TRUE(run.at("checks").at("passed").get<bool>());
}

// The text report names the engine and gives its certificate's lines.
TEST(SteppingIntegrator, TextReportGivesTheCertificate) {
  const CliResult r =
      RunCli("simulate " + Quote(SourcePath("examples/contact-box-held-on-slope.yaml")) +
             " --out " + Quote(Out().string()));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, testing::HasSubstr("Integrator: stepping (Moreau–Jean, step 0.001 s)"));
  for (const char* line :
       {"contact problems' residual at most", "momentum balance to", "gap drift at most",
        "step-doubling error estimate per step", "the scheme's own error"}) {
    EXPECT_THAT(r.out, testing::HasSubstr(line));
  }
}

// The accumulated estimate is said to bound nothing where it exceeds the run's largest speed:
// the break shot (examples/pool-break.yaml without its rolling resistance, under the default
// auto, which time steps it throughout), whose
// rack's collisions share balls within one step, against the head-on collision, where it is a
// small fraction of the speed.
TEST(SteppingIntegrator, SaysWhenTheAccumulatedEstimateBoundsNothing) {
  std::string scene = ReadExample("examples/pool-break.yaml");
  scene = std::regex_replace(scene, std::regex(",? ?mu_r: 0\\.01,?"), ",");
  scene = Replace(scene, "  integrator: events\n", "");  // auto: time stepped throughout
  scene = Replace(scene, "until: 4 s", "until: 0.3 s");
  const std::string flag = "more than the run's largest speed 8 m/s and so no bound here";
  const CliResult broken = RunCli("simulate " + Quote(WriteScene("break.yaml", scene)) + " --out " +
                                  Quote(Out().string()));
  ASSERT_EQ(broken.exit_code, 0) << broken.err;
  EXPECT_THAT(broken.out, testing::HasSubstr(flag));
  const CliResult head_on =
      RunCli("simulate " + Quote(SourcePath("examples/pool-head-on-stepping.yaml")) + " --out " +
             Quote(Out().string()));
  ASSERT_EQ(head_on.exit_code, 0) << head_on.err;
  EXPECT_THAT(head_on.out, testing::HasSubstr("the accumulated velocity error estimated at"));
  EXPECT_THAT(head_on.out, testing::Not(testing::HasSubstr("no bound here")));
}

// A contact that asks for a restitution law other than Newton's is told that time stepping
// applies Newton's law at all touching points at once; every step counts against max_steps.
TEST(SteppingIntegrator, SaysWhichImpactLawItAppliesAndStopsAtTheStepLimit) {
  std::string scene = Replace(ReadExample("examples/pool-head-on-events.yaml"),
                              "  integrator: events\n  ball_collisions: {restitution: e}\n",
                              "  integrator: stepping\n  step: 1 ms\n");
  scene = Replace(scene, "simulation:\n",
                  "  - {name: knock, body: object, shape: sphere, radius: R, with: cue, "
                  "other_radius: R, restitution: e}\nsimulation:\n");
  const std::string path = WriteScene("head_on.yaml", scene);
  const nlohmann::json run = SimulateJson(path, Out());
  ASSERT_EQ(run.at("warnings").size(), 1u);
  EXPECT_THAT(run.at("warnings")[0].get<std::string>(),
              testing::HasSubstr("contact 'knock': time stepping applies Newton's law"));
  const CliResult r =
      RunCli("simulate " + Quote(path) + " --max-steps 20 --out " + Quote(Out().string()));
  EXPECT_EQ(r.exit_code, 2) << r.out;
  EXPECT_THAT(r.err, testing::HasSubstr("--max-steps"));
}

// examples/pool-head-on-stepping.yaml: `ball_collisions` under time stepping, no pair listed.
// Closed forms (the example's comments): after the collision both balls slide, then roll, the
// cue at (5 v_A + 2 v)/7 with v_A = v (1 - e)/2, the object at 5/7 v (1 + e)/2, each final speed
// within 5/7 mu_s g h of them (the collision's step shares the cloth's friction impulses). The
// scene's run is the library's (SimulateTimeStepping with collide_all_pairs) to round-off, and
// the pair's work is in the ledger's impacts.
TEST(SteppingIntegrator, BallCollisionsRunTheLibrarysPairs) {
  const nlohmann::json run =
      SimulateJson(SourcePath("examples/pool-head-on-stepping.yaml"), Out(), "--strict");
  // The one warning: the rows' contact forces do not see the pairs.
  ASSERT_EQ(run.at("warnings").size(), 1u);
  EXPECT_THAT(run.at("warnings")[0].get<std::string>(),
              ::testing::HasSubstr("those of the listed contacts alone"));
  const double v = 2.0, e = 0.93, h = 1e-3, R = 0.028575, d = 0.5;
  const reference::Ball ball{0.17, R, 0.25, 0.2};
  const auto& bodies = run.at("final").at("bodies");
  const double cue = (5 * v * (1 - e) / 2 + 2 * v) / 7, object = 5.0 / 7.0 * v * (1 + e) / 2;
  const double bound = 5.0 / 7.0 * ball.mu_s * kG * h;
  EXPECT_LE(std::abs(ToVec(bodies[0].at("velocity")).x() - cue), bound);
  EXPECT_LE(std::abs(ToVec(bodies[1].at("velocity")).x() - object), bound);
  EXPECT_GT(std::abs(ToVec(bodies[1].at("velocity")).x() - object), 1e-2 * bound);  // a step's
  // The library's run of the same balls.
  const Model model = reference::MakeBallsOnFloor(2, ball, kG);
  State s = MakeRestState(model);
  SetBodyPose(model, 0, Eigen::Vector3d(0, 0, R), Quat::Identity(), s);
  SetBodyVelocity(model, 0, Eigen::Vector3d(v, 0, 0), Eigen::Vector3d(0, v / R, 0), s);
  SetBodyPose(model, 1, Eigen::Vector3d(d, 0, R), Quat::Identity(), s);
  SetBodyVelocity(model, 1, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), s);
  TimeSteppingOptions o;
  o.t_end = 1.0;
  o.step = h;
  o.output_interval = 0.01;
  o.collide_all_pairs = true;
  o.pair_law = {e, 0.0, 0.0, RestitutionLaw::kNewton};
  const TimeSteppingResult r = SimulateTimeStepping(model, s, o);
  for (size_t b = 0; b < 2; ++b) {
    const BodyState& bs = r.final_state.bodies[b];
    EXPECT_LE((ToVec(bodies[b].at("velocity")) - bs.v_WBcm_W).norm(), kRoundOff * v) << b;
    EXPECT_LE((ToVec(bodies[b].at("center_of_mass")) - bs.p_WBcm).norm(), kRoundOff * d) << b;
  }
  const double E0 = r.summary.initial_energy;
  const auto& ts = run.at("integrator").at("time_stepping");
  EXPECT_TRUE(Near(ts.at("regime_changes").get<double>(), r.summary.regime_changes, 0.0));
  EXPECT_TRUE(Near(ts.at("max_penetration").get<double>(), r.summary.max_penetration, 1e-9));
  // The pair's normal impulses' work (the collision's loss) is in the ledger's impacts.
  double impacts = r.final_state.unlisted_contact_work.impact_work;
  for (const ContactPointState& c : r.final_state.contacts) impacts += c.impact_work;
  EXPECT_LT(r.final_state.unlisted_contact_work.impact_work, -0.02);
  EXPECT_TRUE(Near(run.at("ledger").at("impact_work").get<double>(), impacts, kRoundOff, E0));
  EXPECT_TRUE(run.at("checks").at("passed").get<bool>());
}

// A pyramid of four balls on the floor (three touching in a triangle, one in their nest), no
// pair listed: with `ball_collisions` (mu = 0.5) under `integrator: stepping` the broadphase
// finds the six touching pairs and the exact cone holds the pile: nothing moves in 1 s.
// `integrator: auto` time steps it throughout (its event-driven stretches are the adaptive
// engine's, which lets no unlisted pair collide); `integrator: adaptive` is refused, naming the
// engines that can.
TEST(SteppingIntegrator, BallCollisionsHoldAPyramidAtRest) {
  const std::string scene = R"(chasles: 3
parameters:
  R: 0.028575 m
  m: 0.17 kg
  d: 2*R/sqrt(3)
bodies:
  - {name: b1, parts: [{shape: sphere, radius: R, mass: m}], initial: {position: [d, 0, R]}}
  - {name: b2, parts: [{shape: sphere, radius: R, mass: m}], initial: {position: [-d/2, R, R]}}
  - {name: b3, parts: [{shape: sphere, radius: R, mass: m}], initial: {position: [-d/2, -R, R]}}
  - {name: top, parts: [{shape: sphere, radius: R, mass: m}],
     initial: {position: [0, 0, R + sqrt(4*R^2 - d^2)]}}
gravity: standard
contacts:
  - {name: floor, body: all, shape: sphere, radius: R, mu_s: 0.5, mu_k: 0.5,
     plane: {normal: [0, 0, 1]}}
simulation:
  until: 1 s
  integrator: stepping
  step: 1 ms
  ball_collisions: {mu_s: 0.5, mu_k: 0.5}
)";
  const nlohmann::json run = SimulateJson(WriteScene("pyramid.yaml", scene), Out(), "--strict");
  const double R = 0.028575, d = 2 * R / std::sqrt(3.0);
  const Eigen::Vector3d start[4] = {
      {d, 0, R}, {-d / 2, R, R}, {-d / 2, -R, R}, {0, 0, R + std::sqrt(4 * R * R - d * d)}};
  for (size_t b = 0; b < 4; ++b) {
    const auto& body = run.at("final").at("bodies")[b];
    EXPECT_LT((ToVec(body.at("center_of_mass")) - start[b]).norm(), 1e-12) << b;
  }
  const auto& ts = run.at("integrator").at("time_stepping");
  EXPECT_EQ(ts.at("largest_island").get<int>(), 9);  // 3 floor points and the 6 pairs
  EXPECT_TRUE(ts.at("tolerance_met").get<bool>());
  // Under integrator: auto (named, or the default when none is) only time stepping finds the
  // pairs: the run is time stepped throughout, bit for bit the stepping run, and says why.
  const std::string why =
      "every pair of balls may collide (ball_collisions), and only time stepping finds the pairs";
  for (const std::string& integrator : {std::string("  integrator: auto\n"), std::string()}) {
    SCOPED_TRACE(integrator);
    const std::string name = integrator.empty() ? "pyramid_default" : "pyramid_auto";
    const nlohmann::json automatic = SimulateJson(
        WriteScene(name + ".yaml", Replace(scene, "  integrator: stepping\n", integrator)), Out(),
        "--strict");
    EXPECT_EQ(automatic.at("final").at("bodies"), run.at("final").at("bodies"));
    EXPECT_EQ(ReadFile(Out() / (name + ".csv")), ReadFile(Out() / "pyramid.csv"));
    const auto& segments = automatic.at("integrator").at("segments");
    ASSERT_EQ(segments.size(), 1u);
    EXPECT_EQ(segments[0].at("engine"), "stepping");
    EXPECT_EQ(segments[0].at("stays_time_stepped"), why);
    EXPECT_EQ(segments[0].at("time_stepping").at("largest_island").get<int>(), 9);
    EXPECT_TRUE(segments[0].at("time_stepping").at("tolerance_met").get<bool>());
    EXPECT_EQ(automatic.at("run_path").at("reason"), "time stepping throughout: " + why);
  }
  // The adaptive engine cannot: refused at the key, saying which engines can.
  const std::string path =
      WriteScene("pyramid_adaptive.yaml",
                 Replace(scene, "integrator: stepping\n  step: 1 ms\n", "integrator: adaptive\n"));
  const CliResult refused = RunCli("check " + Quote(path));
  EXPECT_EQ(refused.exit_code, 2);
  EXPECT_THAT(refused.err, testing::HasSubstr(":19:20: simulation.ball_collisions"));
  EXPECT_THAT(refused.err,
              testing::HasSubstr("only 'integrator: events', 'stepping' and 'auto' do"));
}

}  // namespace
}  // namespace chasles::test
