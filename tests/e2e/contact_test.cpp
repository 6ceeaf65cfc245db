// End-to-end: the contact examples (examples/problem-8.*.yaml, examples/contact-*.yaml) run
// through `chasles simulate`, against the closed forms derived in docs/contact-examples.md and
// written again here. Event times and speeds at events: relative 1e-9; simulated trajectories
// (integrator tolerance 1e-12): relative 1e-7; ledger balance to 1e-9 of the energy scale.

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "cli_runner.h"
#include "test_support.h"

namespace chasles::test {
namespace {

// Event times and the speeds at them (located to 1e-10 s, exact dynamics in each mode).
constexpr double kEvent = 1e-9;
// Values read along a simulated trajectory at tolerance 1e-12.
constexpr double kRun = 1e-7;
constexpr double kG = 9.80665;  // standard gravity, the scenes' `gravity: standard` [m/s²]
constexpr double kPi = 3.14159265358979323846;
constexpr double kInch = 0.0254;
constexpr double kPound = 0.45359237;

struct RunResult {
  nlohmann::json json;
  std::map<std::string, std::vector<double>> csv;
};

std::filesystem::path OutDir() {
  return test::OutDir("contact");
}

// Runs an example with `chasles simulate --format json`; a failed run fails the test.
RunResult Simulate(const std::string& example, const std::string& extra) {
  RunResult run;
  run.json = SimulateJson(SourcePath(example), OutDir(), extra);
  run.csv = ReadCsv(run.json.at("csv").get<std::string>());
  return run;
}

// The first mode change of `point` into `to` (the mode timeline).
const nlohmann::json& FirstChange(const RunResult& run, const std::string& point,
                                  const std::string& to) {
  for (const auto& e : run.json.at("contact_events")) {
    if (e.at("point") == point && e.at("to") == to && e.at("from") != to) return e;
  }
  throw std::runtime_error("no change of " + point + " to " + to);
}

const nlohmann::json& InitialMode(const RunResult& run, const std::string& point) {
  for (const auto& e : run.json.at("contact_events")) {
    if (e.at("point") == point && e.at("reason") == "initial") return e;
  }
  throw std::runtime_error("no initial mode of " + point);
}

const nlohmann::json& FinalBody(const RunResult& run) {
  return run.json.at("final").at("bodies").at(0);
}

void ExpectLedgerBalances(const RunResult& run) {
  const auto& L = run.json.at("ledger");
  EXPECT_LE(std::abs(L.at("residual").get<double>()), kEvent * L.at("energy_scale").get<double>())
      << L.dump(2);
}

// Problems 8.26/8.27 (docs/contact-examples.md): t* = 2 R w0 / (7 mu_k g) = 25 ms by the
// scene's choice of mu_k; v* = (2/7) R w0, w* = (2/7) w0; afterwards no friction, constant
// kinetic energy; friction work -(1/7) m R^2 w0^2.
TEST(Contact, SpinningBallStopsSlidingAtTStar) {
  const RunResult run = Simulate("examples/problem-8.26-spinning-ball.yaml", "");
  const double R = 9.0 / 8.0 * kInch, m = 0.17, w0 = 100 * 2 * kPi / 60;
  const double mu_k = 2 * R * w0 / (7 * kG * 0.025);
  const double t_star = 2 * R * w0 / (7 * mu_k * kG);
  EXPECT_EQ(InitialMode(run, "floor").at("to"), "sliding");
  const auto& stick = FirstChange(run, "floor", "sticking");
  EXPECT_TRUE(Near(stick.at("t").get<double>(), t_star, kEvent)) << stick.dump();
  EXPECT_EQ(stick.at("reason"), "slip stopped");
  const auto& body = FinalBody(run);
  EXPECT_TRUE(Near(ToVec(body.at("velocity")).x(), 2.0 / 7.0 * R * w0, kEvent));
  EXPECT_TRUE(Near(ToVec(body.at("angular_velocity")).y(), 2.0 / 7.0 * w0, kEvent));
  const auto& c = run.csv;
  const double T_after = 2.0 / 35.0 * m * R * R * w0 * w0;
  for (size_t i = 0; i < c.at("t").size(); ++i) {
    const double t = c.at("t")[i];
    if (t < t_star) {
      // While sliding: v = mu_k g t, w = w0 - 5 mu_k g t / (2R), friction mu_k m g.
      EXPECT_TRUE(Near(c.at("ball_vx")[i], mu_k * kG * t, kRun)) << t;
      EXPECT_TRUE(Near(c.at("ball_wy")[i], w0 - 2.5 * mu_k * kG * t / R, kRun)) << t;
      if (t > 0) {
        EXPECT_TRUE(Near(c.at("floor_f")[i], mu_k * m * kG, kRun)) << t;
      }
    } else if (t > t_star + 1e-6) {
      EXPECT_LE(c.at("floor_f")[i], kEvent * m * kG) << t;
      EXPECT_EQ(c.at("floor_mode")[i], 2.0) << t;
      EXPECT_TRUE(Near(c.at("T")[i], T_after, kEvent)) << t;
    }
  }
  EXPECT_TRUE(Near(run.json.at("ledger").at("friction_work").get<double>(),
                   -m * R * R * w0 * w0 / 7, kEvent));
  ExpectLedgerBalances(run);
}

// Problem 8.18: a = mu_k g, alpha = -2 mu_k g / R, t* = R w0 / (3 mu_k g), v* = R w0 / 3.
TEST(Contact, ThinDiskStopsSlidingAtTStar) {
  const RunResult run = Simulate("examples/problem-8.18-thin-disk.yaml", "");
  const double R = kInch, mu_k = 0.5, w0 = 92 * 2 * kPi;
  const double t_star = R * w0 / (3 * mu_k * kG);
  const auto& stick = FirstChange(run, "floor", "sticking");
  EXPECT_TRUE(Near(stick.at("t").get<double>(), t_star, kEvent));
  EXPECT_TRUE(Near(ToVec(FinalBody(run).at("velocity")).x(), R * w0 / 3, kEvent));
  const auto& c = run.csv;
  for (size_t i = 0; i < c.at("t").size(); ++i) {
    const double t = c.at("t")[i];
    if (t >= t_star) break;
    EXPECT_TRUE(Near(c.at("disk_vx")[i], mu_k * kG * t, kRun)) << t;
    EXPECT_TRUE(Near(c.at("disk_wy")[i], w0 - 2 * mu_k * kG * t / R, kRun)) << t;
  }
  ExpectLedgerBalances(run);
}

// A cylinder on an incline rolls when tan(theta) <= 3 mu_s (a = 2/3 g sin(theta)), otherwise
// slides with a = g (sin(theta) - mu_k cos(theta)).
TEST(Contact, CylinderOnInclineRollsOrSlidesAtTheThreshold) {
  const double mu_s = 0.25, mu_k = 0.2, t_end = 0.5;
  const double theta_c = std::atan(3 * mu_s);
  for (const double factor : {1 - 1e-6, 1 + 1e-6, 30.0 / (theta_c * 180 / kPi)}) {
    const double theta = theta_c * factor;
    char set[64];
    std::snprintf(set, sizeof set, "--set 'theta=%.17g'", theta);
    const RunResult run = Simulate("examples/contact-cylinder-incline.yaml", set);
    const bool rolls = std::tan(theta) <= 3 * mu_s;
    for (const char* p : {"incline_0", "incline_1"}) {
      EXPECT_EQ(InitialMode(run, p).at("to"), rolls ? "sticking" : "sliding") << theta;
    }
    const double a =
        rolls ? 2.0 / 3.0 * kG * std::sin(theta) : kG * (std::sin(theta) - mu_k * std::cos(theta));
    // Speed along the slope d = (cos, 0, -sin) at the end.
    const Vec3 v = ToVec(FinalBody(run).at("velocity"));
    EXPECT_TRUE(Near(v.x() * std::cos(theta) - v.z() * std::sin(theta), a * t_end, kRun)) << theta;
    if (!rolls) {
      // alpha = 2 mu_k g cos(theta) / R about +y.
      EXPECT_TRUE(Near(ToVec(FinalBody(run).at("angular_velocity")).y(),
                       2 * mu_k * kG * std::cos(theta) / 0.1 * t_end, kRun));
    }
    ExpectLedgerBalances(run);
  }
}

// Problems 8.15/8.16: rolling, f = F (R - 2h)/(3R) backward, a = 2 F (R + h)/(3 m R).
TEST(Contact, ForceAboveTheCentreOfARollingDisk) {
  const double R = 0.2, m = 2.0, F = 5.0;
  for (const double h : {0.05, 0.1, 0.15}) {
    const RunResult run = Simulate("examples/problem-8.15-disk-force-above-centre.yaml",
                                   "--set 'h=" + std::to_string(h) + " m'");
    EXPECT_EQ(InitialMode(run, "floor").at("to"), "sticking");
    const auto& c = run.csv;
    const double f = F * (R - 2 * h) / (3 * R);
    const double a = 2 * F * (R + h) / (3 * m * R);
    for (size_t i = 0; i < c.at("t").size(); ++i) {
      EXPECT_NEAR(c.at("floor_f")[i], std::abs(f), kEvent * F) << h;
      EXPECT_TRUE(Near(c.at("disk_ax")[i], a, kRun)) << h;
      EXPECT_TRUE(Near(c.at("floor_N")[i], m * kG, kRun)) << h;
    }
    ExpectLedgerBalances(run);
  }
}

// Problem 8.17: F = 100 N, h = 0.05 m needs f = 25 N > mu_s m g: it slides forward with
// a = (F - mu_k m g)/m and alpha_y = 2 (h F + mu_k m g R)/(m R^2).
TEST(Contact, ForceAboveTheCentreSlides) {
  const RunResult run =
      Simulate("examples/problem-8.15-disk-force-above-centre.yaml", "--set 'F=100 N'");
  const double R = 0.2, m = 2.0, F = 100, h = 0.05, mu_k = 0.4;
  EXPECT_EQ(InitialMode(run, "floor").at("to"), "sliding");
  const auto& c = run.csv;
  for (size_t i = 1; i < c.at("t").size(); ++i) {
    EXPECT_TRUE(Near(c.at("disk_ax")[i], (F - mu_k * m * kG) / m, kRun));
    EXPECT_TRUE(Near(c.at("disk_aly")[i], 2 * (h * F + mu_k * m * kG * R) / (m * R * R), kRun));
  }
  ExpectLedgerBalances(run);
}

// Problems 8.19-8.21: f = F (2R - 5h)/(7R): zero at h = 2R/5, F/14 at h = R/2 (forward),
// 3F/35 at h = 7R/25; a = 5 F (R + h)/(7 m R).
TEST(Contact, CueStrikeHeight) {
  const double R = 0.028575, m = 0.17, F = 10;
  for (const double ratio : {2.0 / 5.0, 0.5, 7.0 / 25.0}) {
    const RunResult run = Simulate("examples/problem-8.19-cue-strike.yaml",
                                   "--set 'h=" + std::to_string(ratio) + "*R'");
    const double h = std::stod(std::to_string(ratio)) * R;
    const double f = F * (2 * R - 5 * h) / (7 * R);
    const auto& c = run.csv;
    EXPECT_EQ(InitialMode(run, "table").at("to"), "sticking");
    for (size_t i = 0; i < c.at("t").size(); ++i) {
      EXPECT_NEAR(c.at("table_f")[i], std::abs(f), kEvent * F) << ratio;
      EXPECT_TRUE(Near(c.at("ball_ax")[i], 5 * F * (R + h) / (7 * m * R), kRun)) << ratio;
    }
    if (ratio == 2.0 / 5.0) {
      EXPECT_LE(std::abs(run.json.at("ledger").at("friction_work").get<double>()), 1e-12);
    }
    ExpectLedgerBalances(run);
  }
}

// Problem 8.14: a = -mu g, N_r = M g (lf - mu h)/L, N_f = M g (lr + mu h)/L, f = mu N each;
// the car stops at t = v0 / (mu g).
TEST(Contact, BrakingWithWeightTransfer) {
  const RunResult run = Simulate("examples/problem-8.14-braking.yaml", "");
  const double M = 1805, h = 1, lf = 1.20, lr = 1.47, mu = 0.8, L = lf + lr, W = M * kG;
  const auto& c = run.csv;
  EXPECT_TRUE(Near(c.at("car_ax")[0], -mu * kG, kEvent));
  EXPECT_NEAR(c.at("rear_N")[0], W * (lf - mu * h) / L, kEvent * W);
  EXPECT_NEAR(c.at("front_N")[0], W * (lr + mu * h) / L, kEvent * W);
  EXPECT_NEAR(c.at("rear_f")[0], mu * W * (lf - mu * h) / L, kEvent * W);
  EXPECT_NEAR(c.at("front_f")[0], mu * W * (lr + mu * h) / L, kEvent * W);
  EXPECT_TRUE(
      Near(FirstChange(run, "front", "sticking").at("t").get<double>(), 20 / (mu * kG), kEvent));
  // All the kinetic energy goes to friction.
  EXPECT_TRUE(
      Near(run.json.at("ledger").at("friction_work").get<double>(), -0.5 * M * 400, kEvent));
  ExpectLedgerBalances(run);
}

// Problem 8.13: with m = M (lf - mu h)/(2 mu h - lf) on the roof the rear wheels unload; a
// heavier box lifts them.
TEST(Contact, BrakingWithABoxOnTheRoof) {
  const double M = 4043 * kPound, h = 39 * kInch, lf = 47 * kInch, mu = 0.8;
  const double m = M * (lf - mu * h) / (2 * mu * h - lf);
  EXPECT_TRUE(Near(m / kPound, 4043 * 15.8 / 15.4, 1e-12));
  {
    const RunResult run = Simulate("examples/problem-8.13-braking-box-on-roof.yaml", "--set k=0.9");
    // N_r = ((M + m) g lf - mu g h (M + 2m)) / L at 0.9 m.
    const double mb = 0.9 * m, L = lf + 66 * kInch;
    EXPECT_NEAR(run.csv.at("rear_N")[0], ((M + mb) * lf - mu * h * (M + 2 * mb)) * kG / L,
                kEvent * (M + mb) * kG);
  }
  {
    const RunResult run = Simulate("examples/problem-8.13-braking-box-on-roof.yaml", "");
    EXPECT_NEAR(run.csv.at("rear_N")[0], 0.0, kEvent * (M + m) * kG);
  }
  {
    const RunResult run =
        Simulate("examples/problem-8.13-braking-box-on-roof.yaml", "--set k=1.05");
    EXPECT_EQ(InitialMode(run, "rear").at("to"), "separated");
  }
}

// A bouncing ball: impacts at t_n = t0 (1 + 2 (e - e^n)/(1 - e)), approach speeds e^(n-1) v0
// (rebound heights e^(2n) h0), rest at T = t0 (1 + e)/(1 - e) (the sum of the bounces the last,
// plastic impact stands for); all of m g h0 goes to impacts.
TEST(Contact, BouncingBallHeightsAndTimeToRest) {
  const RunResult run = Simulate("examples/contact-bouncing-ball.yaml", "");
  const double h0 = 1, e = 0.5, m = 0.5;
  const double t0 = std::sqrt(2 * h0 / kG), v0 = std::sqrt(2 * kG * h0);
  const auto& impacts = run.json.at("impacts");
  ASSERT_GE(impacts.size(), 3u);
  for (size_t k = 0; k < impacts.size(); ++k) {
    const auto& x = impacts[k];
    const double n = static_cast<double>(k + 1);
    if (x.at("accumulation").get<bool>()) {
      // The impact that ends the sequence is the n-th; the bounces it stands for end at T.
      EXPECT_TRUE(
          Near(x.at("t").get<double>(), t0 * (1 + 2 * (e - std::pow(e, n)) / (1 - e)), kEvent));
      EXPECT_TRUE(Near(x.at("rest_time").get<double>(), t0 * (1 + e) / (1 - e), kEvent));
      EXPECT_EQ(k + 1, impacts.size());
      break;
    }
    EXPECT_TRUE(
        Near(x.at("t").get<double>(), t0 * (1 + 2 * (e - std::pow(e, n)) / (1 - e)), kEvent))
        << n;
    const double v = std::pow(e, n - 1) * v0;
    // Touch-downs are located to 1e-12 s: small bounces' speeds carry g times that error.
    EXPECT_NEAR(x.at("approach_speed").get<double>(), v, std::max(kEvent * v, kG * 1e-10)) << n;
    // Rebound height from the measured approach speed: (e v)^2 / (2 g) = e^(2n) h0.
    const double v_measured = x.at("approach_speed").get<double>();
    EXPECT_NEAR(std::pow(e * v_measured, 2) / (2 * kG), std::pow(e, 2 * n) * h0,
                std::max(kEvent, 2 * kG * 1e-10 / v) * std::pow(e, 2 * n) * h0)
        << n;
  }
  const auto& L = run.json.at("ledger");
  EXPECT_TRUE(Near(L.at("impact_work").get<double>(), -m * kG * h0, kEvent));
  EXPECT_EQ(L.at("friction_work").get<double>(), 0.0);
  EXPECT_EQ(run.json.at("final").at("contacts").at(0).at("mode"), "sticking");
  ExpectLedgerBalances(run);
}

// The text report prints the mode timeline and the contact ledger lines.
TEST(Contact, TextReportShowsTheTimelineAndTheLedger) {
  const CliResult r = RunCli("simulate '" + SourcePath("examples/problem-8.26-spinning-ball.yaml") +
                             "' --out '" + OutDir().string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, ::testing::HasSubstr("Contact modes (time, contact point: from -> to, why)"));
  EXPECT_THAT(r.out, ::testing::HasSubstr("floor: sliding -> sticking (slip stopped)"));
  EXPECT_THAT(r.out, ::testing::HasSubstr("friction (sliding)"));
}

// A bounce keeps the point's mode (touch-down, apart again at once): the line says so.
TEST(Contact, TextReportSaysABouncedPointStaysSeparated) {
  const CliResult r = RunCli("simulate '" + SourcePath("examples/contact-spheres-head-on.yaml") +
                             "' --out '" + OutDir().string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, ::testing::HasSubstr("knock: stays separated (touch-down)"));
}

}  // namespace
}  // namespace chasles::test
