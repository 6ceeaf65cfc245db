// End-to-end: contact examples for shapes and mechanisms beyond the chapter's problems (two
// spheres colliding, a box sliding to rest, a capsule starting to roll, a coin dropped on a
// table), events that read contact quantities, and `chasles solve` on scenes with contacts.
// Closed forms are derived in the examples' comments and written again here.

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <string>

#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <boost/math/quadrature/gauss_kronrod.hpp>

#include "cli_runner.h"
#include "test_support.h"

namespace chasles::test {
namespace {

// Event times and values at events (located to 1e-12 s, exact dynamics in each mode).
constexpr double kEvent = 1e-9;
// Instantaneous solves: one linear solve, exact to round-off.
constexpr double kSolve = 1e-12;
constexpr double kG = 9.80665;  // `gravity: standard` [m/s²]
constexpr double kPi = 3.14159265358979323846;

std::filesystem::path OutDir() {
  return test::OutDir("contact_extras");
}

struct RunResult {
  nlohmann::json json;
  std::map<std::string, std::vector<double>> csv;
};

RunResult Simulate(const std::string& scene_path, const std::string& extra = "") {
  RunResult run;
  run.json = SimulateJson(scene_path, OutDir(), extra);
  run.csv = ReadCsv(run.json.at("csv").get<std::string>());
  return run;
}

RunResult SimulateExample(const std::string& example, const std::string& extra = "") {
  return Simulate(SourcePath(example), extra);
}

// Writes `text` as a scene file in the output folder.
std::string WriteScene(const std::string& name, const std::string& text) {
  const auto path = OutDir() / name;
  std::ofstream(path) << text;
  return path.string();
}

// `chasles solve EXAMPLE EXTRA --format json`, parsed.
nlohmann::json Solve(const std::string& example, const std::string& extra = "") {
  std::string args = "solve ";
  args += Quote(SourcePath(example));
  args += " " + extra + " --format json";
  const CliResult r = RunCli(args);
  if (r.exit_code != 0) throw std::runtime_error("chasles solve failed: " + r.err);
  return nlohmann::json::parse(r.out);
}

const nlohmann::json& Body(const nlohmann::json& final_state, const std::string& name) {
  for (const auto& b : final_state.at("bodies")) {
    if (b.at("name") == name) return b;
  }
  throw std::runtime_error("no body " + name);
}

const nlohmann::json& ContactPoint(const nlohmann::json& solve, const std::string& point) {
  for (const auto& c : solve.at("contacts")) {
    if (c.at("point") == point) return c;
  }
  throw std::runtime_error("no contact point " + point);
}

// The first contact event with `reason`.
const nlohmann::json& FirstEvent(const RunResult& run, const std::string& reason) {
  for (const auto& e : run.json.at("contact_events")) {
    if (e.at("reason") == reason) return e;
  }
  throw std::runtime_error("no contact event " + reason);
}

void ExpectLedgerBalances(const RunResult& run) {
  const auto& L = run.json.at("ledger");
  EXPECT_LE(std::abs(L.at("residual").get<double>()), kEvent * L.at("energy_scale").get<double>())
      << L.dump(2);
}

// ---------------------------------------------------------------------------------------
// examples/contact-spheres-head-on.yaml: v1' and v2' from Newton's law and momentum, the loss
// ½ μ (1 - e²)(v1 - v2)², touch-down at gap / (v1 - v2).
TEST(ContactExtras, SpheresHeadOn) {
  const double m1 = 1.5, m2 = 0.7, v1 = 2.0, v2 = -0.5, gap = 0.3;
  for (const double e : {0.6, 1.0, 0.0}) {
    const RunResult run =
        SimulateExample("examples/contact-spheres-head-on.yaml", "--set e=" + std::to_string(e));
    const double mu = m1 * m2 / (m1 + m2);
    const auto& impacts = run.json.at("impacts");
    ASSERT_EQ(impacts.size(), 1u) << e;
    EXPECT_TRUE(Near(impacts[0].at("t").get<double>(), gap / (v1 - v2), kEvent));
    EXPECT_TRUE(Near(impacts[0].at("approach_speed").get<double>(), v1 - v2, kEvent));
    const double dT = 0.5 * mu * (1 - e * e) * (v1 - v2) * (v1 - v2);
    const double T0 = 0.5 * m1 * v1 * v1 + 0.5 * m2 * v2 * v2;
    EXPECT_NEAR(impacts[0].at("energy_lost").get<double>(), dT, kEvent * T0) << e;
    EXPECT_NEAR(run.json.at("ledger").at("impact_work").get<double>(), -dT, kEvent * T0);
    const double v1p = (m1 * v1 + m2 * v2 - m2 * e * (v1 - v2)) / (m1 + m2);
    const double v2p = (m1 * v1 + m2 * v2 + m1 * e * (v1 - v2)) / (m1 + m2);
    const auto& fin = run.json.at("final");
    EXPECT_NEAR(ToVec(Body(fin, "big").at("velocity")).x(), v1p, kEvent * v1) << e;
    EXPECT_NEAR(ToVec(Body(fin, "small").at("velocity")).x(), v2p, kEvent * v1) << e;
    // Momentum is the same in every row.
    const auto& c = run.csv;
    for (size_t i = 0; i < c.at("t").size(); ++i) {
      EXPECT_NEAR(c.at("Px")[i], m1 * v1 + m2 * v2, kEvent * m1 * v1);
    }
    ExpectLedgerBalances(run);
  }
}

// examples/contact-box-slides-to-rest.yaml: stops at t = v0/(mu_k g) after v0²/(2 mu_k g).
TEST(ContactExtras, BoxSlidesToRest) {
  const RunResult run = SimulateExample("examples/contact-box-slides-to-rest.yaml");
  const double m = 2, v0 = 3, mu_k = 0.4;
  const double t_stop = v0 / (mu_k * kG), d = v0 * v0 / (2 * mu_k * kG);
  const auto& stop = FirstEvent(run, "slip stopped");
  EXPECT_TRUE(Near(stop.at("t").get<double>(), t_stop, kEvent)) << stop.dump();
  const auto& box = Body(run.json.at("final"), "box");
  EXPECT_TRUE(Near(ToVec(box.at("center_of_mass")).x(), d, kEvent));
  EXPECT_NEAR(ToVec(box.at("velocity")).norm(), 0.0, kEvent * v0);
  // While sliding: x = v0 t - ½ mu_k g t², v = v0 - mu_k g t; on the floor (z = c/2).
  const auto& c = run.csv;
  for (size_t i = 0; i < c.at("t").size(); ++i) {
    const double t = std::min(c.at("t")[i], t_stop);
    EXPECT_NEAR(c.at("box_x")[i], v0 * t - 0.5 * mu_k * kG * t * t, 1e-7 * d) << t;
    EXPECT_NEAR(c.at("box_vx")[i], v0 - mu_k * kG * t, 1e-7 * v0) << t;
    EXPECT_NEAR(c.at("box_z")[i], 0.1, 1e-9) << t;
  }
  EXPECT_TRUE(
      Near(run.json.at("ledger").at("friction_work").get<double>(), -0.5 * m * v0 * v0, kEvent));
  ExpectLedgerBalances(run);
}

// examples/contact-capsule-slides-then-rolls.yaml: v = v0 - mu_k g t, w = mu_k m g R t / I;
// v = R w at t* = v0/(mu_k g (1 + m R²/I)), v* = v0/(1 + I/(m R²)).
TEST(ContactExtras, CapsuleSlidesThenRolls) {
  const RunResult run = SimulateExample("examples/contact-capsule-slides-then-rolls.yaml");
  const double R = 0.05, L = 0.2, rho = 1000, v0 = 2, mu_k = 0.25;
  const double m_c = rho * kPi * R * R * L, m_h = rho * 2.0 / 3.0 * kPi * R * R * R;
  const double m = m_c + 2 * m_h;
  const double I = 0.5 * m_c * R * R + 2 * 0.4 * m_h * R * R;  // about the axis (Appendix A)
  const double k = 1 + m * R * R / I;
  const double t_star = v0 / (mu_k * kG * k), v_star = v0 / (1 + I / (m * R * R));
  for (const char* p : {"floor_0", "floor_1"}) {
    bool found = false;
    for (const auto& e : run.json.at("contact_events")) {
      // One rim's slip stops; the other switches with it at the re-selection.
      if (e.at("point") == p && e.at("to") == "sticking") {
        EXPECT_TRUE(Near(e.at("t").get<double>(), t_star, kEvent)) << p;
        EXPECT_EQ(e.at("to"), "sticking");
        found = true;
        break;
      }
    }
    EXPECT_TRUE(found) << p;
  }
  const auto& cap = Body(run.json.at("final"), "capsule");
  EXPECT_TRUE(Near(ToVec(cap.at("velocity")).x(), v_star, kEvent));
  // Rolling along +x about +y: v = R w_y.
  EXPECT_TRUE(Near(ToVec(cap.at("angular_velocity")).y(), v_star / R, kEvent));
  const double W = 0.5 * m * v0 * v0 - 0.5 * (m + I / (R * R)) * v_star * v_star;
  EXPECT_TRUE(Near(run.json.at("ledger").at("friction_work").get<double>(), -W, kEvent));
  ExpectLedgerBalances(run);
}

// examples/contact-coin-drop.yaml, flat: the eight ring points land together at sqrt(2h/g),
// the plastic impact takes m g h, the coin rests with its centre T/2 above the table.
TEST(ContactExtras, CoinDroppedFlatStopsAtOnce) {
  const RunResult run = SimulateExample("examples/contact-coin-drop.yaml");
  const double m = 0.005, h = 0.05, T = 0.002;
  const auto& impacts = run.json.at("impacts");
  ASSERT_GE(impacts.size(), 1u);
  double lost = 0.0;
  for (const auto& x : impacts) {
    EXPECT_TRUE(Near(x.at("t").get<double>(), std::sqrt(2 * h / kG), kEvent));
    EXPECT_TRUE(Near(x.at("approach_speed").get<double>(), std::sqrt(2 * kG * h), kEvent));
    lost += x.at("energy_lost").get<double>();
  }
  EXPECT_TRUE(Near(lost, m * kG * h, kEvent));  // the impacts' losses add up to the ledger's
  EXPECT_TRUE(Near(run.json.at("ledger").at("impact_work").get<double>(), -m * kG * h, kEvent));
  const auto& coin = Body(run.json.at("final"), "coin");
  EXPECT_NEAR(ToVec(coin.at("center_of_mass")).z(), T / 2, kEvent * h);
  EXPECT_NEAR(ToVec(coin.at("velocity")).norm(), 0.0, 1e-12);
  ExpectLedgerBalances(run);
}

// Tilted: it lands on one rim point, rocks down and settles flat; everything it had above the
// rest position went to impacts and friction.
TEST(ContactExtras, CoinDroppedTiltedSettlesFlat) {
  const double m = 0.005, h = 0.05, T = 0.002, R = 0.012, tilt = 20 * kPi / 180;
  const RunResult run = SimulateExample("examples/contact-coin-drop.yaml", "--set 'tilt=20 deg'");
  const auto& impacts = run.json.at("impacts");
  ASSERT_GE(impacts.size(), 1u);
  // The first impact: one rim point at sqrt(2 g h).
  EXPECT_TRUE(Near(impacts[0].at("t").get<double>(), std::sqrt(2 * h / kG), kEvent));
  const auto& coin = Body(run.json.at("final"), "coin");
  EXPECT_NEAR(ToVec(coin.at("center_of_mass")).z(), T / 2, 1e-9);
  EXPECT_NEAR(ToVec(coin.at("velocity")).norm(), 0.0, 1e-9);
  EXPECT_NEAR(ToVec(coin.at("angular_velocity")).norm(), 0.0, 1e-7);
  const double z0 = h + R * std::sin(tilt) + T / 2 * std::cos(tilt);
  const auto& L = run.json.at("ledger");
  const double dissipated = L.at("impact_work").get<double>() + L.at("friction_work").get<double>();
  EXPECT_NEAR(-dissipated, m * kG * (z0 - T / 2), 1e-9 * m * kG * z0);
  ExpectLedgerBalances(run);
}

// ---------------------------------------------------------------------------------------
// Events reading contact quantities. A ball set down spinning (w0 about y, no velocity) slides:
// v = mu_k g t, w = w0 - 5 mu_k g t/(2R), so the contact point slips at
// |v - R w| = R w0 - (7/2) mu_k g t, which falls through s1 at t1 = (R w0 - s1)/(3.5 mu_k g).
TEST(ContactExtras, EventStopsWhenTheSlipFallsBelowAValue) {
  const double R = 0.05, w0 = 20, mu_k = 0.2, s1 = 0.4;
  const std::string scene = WriteScene("slip_event.yaml", R"(chasles: 1
parameters: {R: 0.05 m, w0: 20 rad/s}
bodies:
  - name: ball
    parts: [{shape: sphere, radius: R, mass: 1 kg}]
    initial: {position: [0, 0, R], angular_velocity: [0, w0, 0]}
gravity: standard
contacts:
  - {name: floor, body: ball, shape: sphere, radius: R, mu_s: 0.3, mu_k: 0.2,
     plane: {normal: [0, 0, 1]}}
events:
  - {name: slowed, when: floor_slip, crosses: 0.4 m/s, direction: falling}
simulation: {until: 1 s, tolerance: 1e-12}
output: {columns: [velocity, contacts]}
)");
  const RunResult run = Simulate(scene);
  const double t1 = (R * w0 - s1) / (3.5 * mu_k * kG);
  ASSERT_EQ(run.json.at("events").size(), 1u);
  EXPECT_TRUE(Near(run.json.at("events")[0].at("t").get<double>(), t1, kEvent));
  EXPECT_TRUE(run.json.at("stopped_by_event").get<bool>());
  EXPECT_TRUE(
      Near(ToVec(Body(run.json.at("final"), "ball").at("velocity")).x(), mu_k * kG * t1, kEvent));
  EXPECT_TRUE(Near(run.csv.at("floor_slip").back(), s1, kEvent));
}

// A car on frictionless wheels towed by F = k t at the rear contact point (road level): with
// a = F/M and no pitch, moments about the centre of mass give N_r lr - N_f lf - h F = 0 and
// N_r + N_f = M g, so N_r = (M g lf + h F)/L. It reaches N* at t = (N* L - M g lf)/(h k).
TEST(ContactExtras, EventStopsWhenTheRearNormalForceReachesAValue) {
  const double M = 1000, h = 0.5, lf = 1.2, lr = 1.5, k = 10000, N_star = 5000, L = lf + lr;
  const std::string scene = WriteScene("normal_event.yaml", R"(chasles: 1
parameters: {M: 1000 kg, h: 0.5 m, lf: 1.2 m, lr: 1.5 m}
bodies:
  - name: car
    points: {rear_wheel: [-lr, 0, -h], front_wheel: [lf, 0, -h]}
    parts: [{shape: box, size: [4 m, 1.8 m, 1.2 m], mass: M}]
    initial: {position: [0, 0, h], velocity: [1 m/s, 0, 0]}
gravity: standard
joints:
  - {name: plane_of_motion, type: planar, parent: world, child: car, at: [0, 0, h],
     axis: [0, 1, 0]}
contacts:
  - {name: rear, body: car, shape: points, points: [rear_wheel], plane: {normal: [0, 0, 1]}}
  - {name: front, body: car, shape: points, points: [front_wheel], plane: {normal: [0, 0, 1]}}
forces:
  - {type: force, name: tow, body: car, point: rear_wheel, value: [t/s * 10000 N, 0, 0]}
events:
  - {name: rear loaded, when: rear_N, crosses: 5000 N, direction: rising}
simulation: {until: 1 s, tolerance: 1e-12}
output: {columns: [velocity, acceleration, contacts]}
)");
  const RunResult run = Simulate(scene);
  const double t1 = (N_star * L - M * kG * lf) / (h * k);
  ASSERT_EQ(run.json.at("events").size(), 1u);
  EXPECT_TRUE(Near(run.json.at("events")[0].at("t").get<double>(), t1, kEvent));
  // Along the way N_r = (M g lf + h k t)/L and N_f = M g - N_r.
  const auto& c = run.csv;
  for (size_t i = 0; i < c.at("t").size(); ++i) {
    const double t = c.at("t")[i];
    EXPECT_NEAR(c.at("rear_N")[i], (M * kG * lf + h * k * t) / L, kEvent * M * kG) << t;
    EXPECT_NEAR(c.at("front_N")[i], M * kG - (M * kG * lf + h * k * t) / L, kEvent * M * kG);
  }
  EXPECT_NEAR(c.at("rear_N").back(), N_star, kEvent * M * kG);
}

// ---------------------------------------------------------------------------------------
// chasles solve on a scene with contacts: the cylinder on an incline rolls when
// tan(theta) <= 3 mu_s (f/N = tan(theta)/3 per rim, a = 2/3 g sin(theta)) and slides otherwise
// (f = mu_k N, a = g (sin(theta) - mu_k cos(theta))); N = m g cos(theta)/2 on each end rim.
void ExpectIncline(double theta, const std::vector<std::string>& names,
                   const std::vector<double>& row) {
  const double m = 5, mu_s = 0.25, mu_k = 0.2;
  auto col = [&](const std::string& n) {
    for (size_t i = 0; i < names.size(); ++i) {
      if (names[i] == n) return row.at(i);
    }
    throw std::runtime_error("no column " + n);
  };
  const bool rolls = std::tan(theta) <= 3 * mu_s;
  const double N = m * kG * std::cos(theta) / 2;
  const double a =
      rolls ? 2.0 / 3.0 * kG * std::sin(theta) : kG * (std::sin(theta) - mu_k * std::cos(theta));
  for (const char* p : {"incline_0", "incline_1"}) {
    const std::string s = p;
    EXPECT_EQ(col(s + "_mode"), rolls ? 2.0 : 1.0) << theta;
    EXPECT_NEAR(col(s + "_N"), N, kSolve * m * kG) << theta;
    EXPECT_NEAR(col(s + "_f"), rolls ? m * kG * std::sin(theta) / 6 : mu_k * N, kSolve * m * kG);
    EXPECT_NEAR(col(s + "_f_over_N"), rolls ? std::tan(theta) / 3 : mu_k, 1e-11) << theta;
  }
  // Down the slope d = (cos, 0, -sin).
  EXPECT_NEAR(col("cylinder_ax"), a * std::cos(theta), kSolve * kG) << theta;
  EXPECT_NEAR(col("cylinder_az"), -a * std::sin(theta), kSolve * kG) << theta;
}

TEST(ContactExtras, SolveSweepsTheInclineAcrossTheRollSlideThreshold) {
  const nlohmann::json j =
      Solve("examples/contact-cylinder-incline.yaml", "--sweep 'theta=30 deg:40 deg:11'");
  const auto names = j.at("columns").get<std::vector<std::string>>();
  int rolling = 0, sliding = 0;
  for (const auto& r : j.at("rows")) {
    const auto row = r.get<std::vector<double>>();
    ExpectIncline(row[0], names, row);
    (std::tan(row[0]) <= 0.75 ? rolling : sliding)++;
  }
  EXPECT_EQ(rolling, 7);  // 30..36 deg; tan(36.87 deg) = 0.75
  EXPECT_EQ(sliding, 4);
  // Either side of tan(theta) = 3 mu_s, within 1e-9 and 1e-11 of it: the cone test is at
  // round-off level (1e-12 relative) and symmetric, so a threshold found by bisection on the
  // regime is the closed-form one to 1e-11.
  const double theta_c = std::atan(0.75);
  for (const double f : {1 - 1e-9, 1 + 1e-9, 1 - 1e-11, 1 + 1e-11}) {
    char set[80];
    std::snprintf(set, sizeof set, " --set 'theta=%.17g'", theta_c * f);
    const nlohmann::json s = Solve("examples/contact-cylinder-incline.yaml", set);
    const auto& p = ContactPoint(s, "incline_0");
    EXPECT_EQ(p.at("mode"), f < 1 ? "sticking" : "sliding");
    EXPECT_EQ(p.at("regime"), f < 1 ? "rolls" : "slides");
    EXPECT_EQ(p.at("mu_s").get<double>(), 0.25);
  }
}

// The rear-wheel-drive car (Problem 8.12, wheels as bodies) at its initial state: the rear
// wheel turns faster than it rolls, so its tyre slides with f = mu N_r forward,
// a = mu g lf/(L - mu h), N_r = M (g lf + a h)/L; the front (mu = 0) slides without friction.
TEST(ContactExtras, SolveReportsTheCarsTraction) {
  const nlohmann::json j = Solve("examples/problem-8.12-rear-wheel-drive-wheels.yaml");
  const double M = 1805, h = 1, lf = 1.20, lr = 1.67, mu = 0.8, L = lf + lr;
  const double a = mu * kG * lf / (L - mu * h);
  const double N_r = M * (kG * lf + a * h) / L;
  const auto& rear = ContactPoint(j, "rear");
  EXPECT_EQ(rear.at("mode"), "sliding");
  EXPECT_EQ(rear.at("regime"), "slides");
  EXPECT_NEAR(rear.at("normal_force").get<double>(), N_r, kSolve * M * kG);
  EXPECT_NEAR(ToVec(rear.at("friction")).x(), mu * N_r, kSolve * M * kG);
  EXPECT_NEAR(rear.at("friction_needed").get<double>(), mu, kSolve);
  const auto& front = ContactPoint(j, "front");
  EXPECT_NEAR(front.at("normal_force").get<double>(), M * kG - N_r, kSolve * M * kG);
  EXPECT_NEAR(front.at("friction_magnitude").get<double>(), 0.0, kSolve * M * kG);
  EXPECT_NEAR(ToVec(j.at("bodies")[0].at("acceleration")).x(), a, kSolve * kG);

  const CliResult text =
      RunCli("solve '" + SourcePath("examples/problem-8.12-rear-wheel-drive-wheels.yaml") + "'");
  ASSERT_EQ(text.exit_code, 0) << text.err;
  EXPECT_THAT(text.out, ::testing::HasSubstr("Contacts (modes chosen at the initial state"));
  EXPECT_THAT(text.out, ::testing::HasSubstr("rear: slides (sliding)"));
  const CliResult rolls =
      RunCli("solve '" + SourcePath("examples/contact-cylinder-incline.yaml") + "'");
  ASSERT_EQ(rolls.exit_code, 0) << rolls.err;
  EXPECT_THAT(rolls.out, ::testing::HasSubstr("incline_0: rolls (sticking)"));
  EXPECT_THAT(rolls.out, ::testing::HasSubstr("against mu_s = 0.25"));
}

// ---------------------------------------------------------------------------------------
// examples/ladder-leaves-wall.yaml: Example 8.4's ladder (a slender rod, m, L, from rest at
// phi0 from the vertical) on frictionless contacts at the wall and the floor, run past the
// angle where the wall lets go. φ is the tilt from the vertical.
// Phase 1 (both ends touching): the centre of mass moves on the circle of radius L/2 about
// the corner, so T = ½ (m L²/3) φ'² and energy gives φ'² = (3 g / L)(cos φ0 - cos φ);
// m ẍ_cm = N_A with x_cm = (L/2) sin φ gives N_A = (3/4) m g sin φ (3 cos φ - 2 cos φ0),
// zero at cos φ1 = (2/3) cos φ0, reached at t1 = ∫ dφ / φ' from φ0 to φ1 (an integrable
// 1/sqrt singularity at φ0: tanh-sinh quadrature).
// Phase 2 (the floor alone; no horizontal force): v_x = (L/2) cos φ1 φ1' stays, and with
// z_cm = (L/2) cos φ energy gives
//   φ'² = (g L (cos φ0 - cos φ) - v_x²) / (L² (1/12 + sin² φ / 4)),
// and its time derivative φ'' = ((g / (2 L)) sin φ - (sin φ cos φ / 4) φ'²) / (1/12 + sin² φ/4);
// the floor pushes N_B = m (g + z̈_cm) = m (g - (L/2)(cos φ φ'² + sin φ φ'')). The stop at
// φ = 85° comes at t1 + ∫ dφ / φ' from φ1 to 85°.
// The example's 30° and seeded random starting angles and lengths.
class LadderLeavesTheWall : public ::testing::TestWithParam<int> {};

TEST_P(LadderLeavesTheWall, AndSlidesOnTheFloor) {
  std::mt19937 rng(static_cast<unsigned>(GetParam()));
  const double m = 10.0, g = kG, phi_stop = 85 * kPi / 180;
  double L = 2.0, phi0 = kPi / 6;
  if (GetParam() > 0) {
    L = std::uniform_real_distribution<double>(0.5, 5.0)(rng);
    phi0 = std::uniform_real_distribution<double>(0.05, 1.2)(rng);
  }
  const RunResult run =
      SimulateExample("examples/ladder-leaves-wall.yaml",
                      fmt::format("--set 'L={:.17g} m' --set 'phi0={:.17g} rad'", L, phi0));
  const double c0 = std::cos(phi0);
  const double phi1 = std::acos(2.0 / 3.0 * c0);
  const double w1 = std::sqrt(3 * g / L * (c0 - std::cos(phi1)));
  const double vx = 0.5 * L * std::cos(phi1) * w1;
  // cos φ0 - cos φ = 2 sin((φ + φ0)/2) sin((φ - φ0)/2): no cancellation next to φ0.
  auto rate1 = [&](double phi) {
    return std::sqrt(3 * g / L * 2 * std::sin((phi + phi0) / 2) *
                     std::max(0.0, std::sin((phi - phi0) / 2)));
  };
  auto rate2 = [&](double phi) {
    const double s = std::sin(phi);
    return std::sqrt((g * L * (c0 - std::cos(phi)) - vx * vx) / (L * L * (1.0 / 12 + s * s / 4)));
  };
  // With φ = φ0 + u² the integrand 2u / φ' is smooth (finite at u = 0); φ' is written in u
  // (cos φ0 - cos φ = 2 sin(φ0 + u²/2) sin(u²/2)) so that u² is not lost next to φ0.
  const double t1 = boost::math::quadrature::gauss_kronrod<double, 61>::integrate(
      [&](double u) {
        if (u == 0.0) return 2.0 / std::sqrt(3 * g / L * std::sin(phi0));
        return 2 * u / std::sqrt(3 * g / L * 2 * std::sin(phi0 + u * u / 2) * std::sin(u * u / 2));
      },
      0.0, std::sqrt(phi1 - phi0), 10, 1e-14);
  const double t2 =
      t1 + boost::math::quadrature::gauss_kronrod<double, 61>::integrate(
               [&](double phi) { return 1.0 / rate2(phi); }, phi1, phi_stop, 10, 1e-14);
  // The wall lets go at t1 (a lift-off, the only mode change), the run stops at 85°.
  const auto& off = FirstEvent(run, "lift-off");
  EXPECT_EQ(off.at("point"), "wall");
  EXPECT_TRUE(Near(off.at("t").get<double>(), t1, kEvent)) << t1;
  EXPECT_EQ(run.json.at("contact_events").size(), 3u);  // two initial, one lift-off
  ASSERT_TRUE(run.json.at("stopped_by_event").get<bool>());
  EXPECT_TRUE(Near(run.json.at("events")[0].at("t").get<double>(), t2, kEvent)) << t2;
  const auto& c = run.csv;
  int phase2 = 0;
  for (size_t i = 0; i < c.at("t").size(); ++i) {
    const double t = c.at("t")[i], phi = c.at("ladder_tilt")[i];
    const double w = -c.at("ladder_wy")[i];  // the tilt grows by a turn about -y
    EXPECT_NEAR(c.at("ladder_z")[i], 0.5 * L * std::cos(phi), kEvent * L) << t;
    EXPECT_NEAR(c.at("floor_gap")[i], 0.0, kEvent * L) << t;
    if (t < t1) {
      EXPECT_NEAR(w, rate1(phi), kEvent * w1) << t;
      EXPECT_NEAR(c.at("wall_N")[i], 0.75 * m * g * std::sin(phi) * (3 * std::cos(phi) - 2 * c0),
                  kEvent * m * g)
          << t;
      continue;
    }
    ++phase2;
    const double s = std::sin(phi), co = std::cos(phi);
    const double w2 = rate2(phi);
    const double a2 = (g / (2 * L) * s - s * co / 4 * w2 * w2) / (1.0 / 12 + s * s / 4);
    EXPECT_NEAR(c.at("ladder_vx")[i], vx, kEvent * vx) << t;
    EXPECT_NEAR(w, w2, kEvent * w1) << t;
    EXPECT_EQ(c.at("wall_N")[i], 0.0) << t;
    EXPECT_GT(c.at("wall_gap")[i], 0.0) << t;
    EXPECT_NEAR(c.at("floor_N")[i], m * (g - 0.5 * L * (co * w2 * w2 + s * a2)), kEvent * m * g)
        << t;
  }
  EXPECT_GT(phase2, 5);
  ExpectLedgerBalances(run);
}

INSTANTIATE_TEST_SUITE_P(ContactExtras, LadderLeavesTheWall, ::testing::Values(0, 1, 2, 3));

}  // namespace
}  // namespace chasles::test
