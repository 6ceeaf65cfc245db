// Spinning balls set down on a floor (Problems 8.26/8.27, examples/problem-8.26-spinning-ball.yaml)
// through the scene's study, as `chasles simulate` runs them with `integrator: adaptive` (the
// default before scene format version 3): the balls share no element but gravity, so the run
// splits them into islands although the certificate checks every contact transition (each
// island its own, docs/contact.md "Islands").
//
// Ball i (radius R, mass m, I = 2/5 m R²) is set down with its centre at rest spinning at w_i
// about y. Its contact point then slides at v - w R < 0 along x, so kinetic friction mu_k m g
// acts along +x at the contact point: m v̇ = mu_k m g and, about the centre, I ẇ = -R mu_k m g,
// ẇ = -5 mu_k g / (2 R). The slip w R - v falls at (5/2 + 1) mu_k g = 7/2 mu_k g from w_i R, so
// it stops at t*_i = 2 R w_i / (7 mu_k g), where the ball starts to roll.

#include <cmath>
#include <map>
#include <string>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "chasles/analysis/study.h"
#include "chasles/integrate/run_path.h"
#include "chasles/scene/scene.h"
#include "chasles/scene/study.h"

namespace chasles {
namespace {

constexpr int kBalls = 12;
constexpr double kR = 9.0 / 8.0 * 0.0254;  // 9/8 in [m]
constexpr double kG = 9.80665;             // [m/s²]
constexpr double kMuK = 0.2;
// Spin of ball i [rad/s]: 100 rpm times (1 + i / n), each ball its own t*.
double Spin(int i) {
  return 100.0 * 2.0 * M_PI / 60.0 * (1.0 + double(i) / kBalls);
}
double TStar(int i) {
  return 2.0 * kR * Spin(i) / (7.0 * kMuK * kG);
}

// The scene: one contact entry for all balls (`body: all`).
std::string SceneText() {
  std::string text = fmt::format(R"(chasles: 3
parameters:
  R: 9/8 in
  m: 0.17 kg
bodies:
)");
  for (int i = 0; i < kBalls; ++i) {
    text += fmt::format(
        "  - {{name: ball{}, parts: [{{shape: sphere, radius: R, mass: m}}], initial: {{position: "
        "[0, {} m, R], angular_velocity: [0, {:.17g} rad/s, 0]}}}}\n",
        i, i, Spin(i));
  }
  return text + fmt::format(R"(gravity: standard
contacts:
  - {{name: floor, body: all, shape: sphere, radius: R, mu_s: 0.5, mu_k: {},
     plane: {{point: [0, 0, 0], normal: [0, 0, 1]}}}}
simulation:
  integrator: adaptive
  until: 90 ms  # past the last t* (84 ms)
  tolerance: 1e-12
  output_interval: 1 ms
output:
  columns: [position, velocity, angular_velocity, energy, contacts, ledger]
)",
                            kMuK);
}

StudyResult RunBalls(const Scene& scene, int threads) {
  StudyDefinition def = MakeStudyDefinition(scene);
  def.options.threads = threads;
  return RunStudy(def);
}

TEST(SpinningBallsIslands, TheStudyRunsIslandsWithEveryTransitionChecked) {
  const Scene scene = LoadSceneText(SceneText(), "spinning-balls.yaml");
  const StudyResult r = RunBalls(scene, 1);
  EXPECT_EQ(r.run_path.path, RunPath::kIslands) << r.run_path.reason;
  EXPECT_EQ(r.run_path.islands, kBalls);
  ASSERT_TRUE(r.islands.split) << r.islands.reason;
  for (const std::string& m : r.certificate.FailureMessages()) ADD_FAILURE() << m;
  // Every transition checked: the ledger at every row, and twice (before, after) at every
  // contact event after the start (one slip stop per ball).
  long long ledger = 0;
  for (const CheckResult& c : r.certificate.checks) {
    if (c.name == "ledger") ledger = c.count;
  }
  EXPECT_EQ(ledger, static_cast<long long>(r.rows.size()) + 2 * kBalls);
  // t* of each ball from the event log, to 1e-9 of its closed form (the event is located to
  // 1e-12 s, the integration at tolerance 1e-12).
  constexpr double kRel = 1e-9;
  std::map<std::string, int> stops;
  for (const StudyContactEvent& e : r.contact_events) {
    if (e.reason != ContactEventReason::kSlipStopped) continue;
    int i = -1;
    for (int b = 0; b < kBalls; ++b) {
      if (e.point == fmt::format("floor_ball{}", b)) i = b;
    }
    ASSERT_GE(i, 0) << e.point;
    ++stops[e.point];
    EXPECT_NEAR(e.t, TStar(i), kRel * TStar(i)) << e.point;
  }
  EXPECT_EQ(stops.size(), size_t{kBalls});
  for (const auto& [point, n] : stops) EXPECT_EQ(n, 1) << point;
}

// The same rows, events and certificate for one and two threads, to the bit.
TEST(SpinningBallsIslands, OneAndTwoThreadsGiveTheSameBits) {
  const Scene scene = LoadSceneText(SceneText(), "spinning-balls.yaml");
  const StudyResult a = RunBalls(scene, 1);
  const StudyResult b = RunBalls(scene, 2);
  ASSERT_EQ(a.rows.size(), b.rows.size());
  for (size_t k = 0; k < a.rows.size(); ++k) EXPECT_EQ(a.rows[k], b.rows[k]) << "row " << k;
  ASSERT_EQ(a.contact_events.size(), b.contact_events.size());
  for (size_t k = 0; k < a.contact_events.size(); ++k) {
    EXPECT_EQ(a.contact_events[k].t, b.contact_events[k].t);
    EXPECT_EQ(a.contact_events[k].point, b.contact_events[k].point);
  }
  ASSERT_EQ(a.certificate.checks.size(), b.certificate.checks.size());
  for (size_t c = 0; c < a.certificate.checks.size(); ++c) {
    const CheckResult &x = a.certificate.checks[c], &y = b.certificate.checks[c];
    EXPECT_EQ(x.count, y.count) << x.name;
    EXPECT_EQ(x.worst, y.worst) << x.name;
    EXPECT_EQ(x.tolerance, y.tolerance) << x.name;
    EXPECT_EQ(x.where, y.where) << x.name;
    EXPECT_EQ(x.t, y.t) << x.name;
  }
}

}  // namespace
}  // namespace chasles
