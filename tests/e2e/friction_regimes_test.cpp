// End-to-end: stick -> slip transitions under forces that grow, for a box, a solid cylinder, a
// solid sphere and a thin hoop pushed through the centre of mass on a level floor, and a
// cylinder on an incline tilted slowly past tan θ = 3 μs. The closed forms are derived here.
//
// A round body (mass m, radius R, I = β m R² about its axle: cylinder β = 1/2, sphere 2/5,
// hoop 1) pushed through its centre by F(t) = k t rolls while the friction it needs is within
// the cone: m a = F - f, β m R² α = f R, a = α R give a = F / (m (1 + β)) and
// f = F β / (1 + β) (eqs. 8.49-8.51 with a force in place of gravity's component). It starts to
// slide when f = μs m g:  t* = μs m g (1 + β) / (β k). Afterwards the contact slips forward
// and kinetic friction μk m g acts backward: m a = k t - μk m g, β m R² α = μk m g R. So
//   v(t) = k t*² / (2 m (1 + β)) + k (t² - t*²) / (2 m) - μk g (t - t*),
//   ω(t) = v(t*) / R + μk g (t - t*) / (β R).
// A box (no rolling) sticks until k t = μs m g and then a = (k t - μk m g) / m.
// On an incline of angle θ a cylinder rolls with f = m g sin θ / 3 and N = m g cos θ: it
// slides once tan θ = 3 μs (Example 8.3), whatever the rate at which θ grows.

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <ostream>
#include <string>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "cli_runner.h"
#include "test_support.h"

namespace chasles::test {
namespace {

// Event times and forces: the events are located to 1e-12 s.
constexpr double kEvent = 1e-9;
constexpr double kG = 9.80665;  // `gravity: standard` [m/s²]
constexpr double kPi = 3.14159265358979323846;

struct RunOut {
  nlohmann::json json;
  std::map<std::string, std::vector<double>> csv;
};

RunOut SimulateText(const std::string& name, const std::string& text) {
  const std::filesystem::path dir = OutDir("friction-regimes");
  const std::filesystem::path file = dir / (name + ".yaml");
  std::ofstream(file) << text;
  RunOut r;
  // --strict: a run whose certificate fails exits 3, and SimulateJson throws.
  r.json = SimulateJson(file.string(), dir, "--strict");
  r.csv = ReadCsv(r.json.at("csv").get<std::string>());
  return r;
}

// Time of the first change of `point` from sticking to sliding.
double SlipStart(const RunOut& r, const std::string& point) {
  for (const auto& e : r.json.at("contact_events")) {
    if (e.at("point") == point && e.at("from") == "sticking" && e.at("to") == "sliding") {
      return e.at("t").get<double>();
    }
  }
  throw std::runtime_error("no slip start of " + point);
}

// Every change after the start (the initial modes left out).
int ChangesAfterStart(const RunOut& r) {
  int n = 0;
  for (const auto& e : r.json.at("contact_events")) n += e.at("reason") != "initial";
  return n;
}

struct Round {
  std::string name, part, contact;
  double beta;
  int points;  // contact points the shape touches with
};

void PrintTo(const Round& r, std::ostream* os) {
  *os << r.name;
}

// m = 10 kg, R = 0.1 m, μs = 0.3, μk = 0.25, F = 20 t N, run to 2 t*.
class RoundBodyRampTest : public ::testing::TestWithParam<Round> {};

TEST_P(RoundBodyRampTest, RollsThenSlidesAtTheClosedFormInstant) {
  const Round& b = GetParam();
  const double m = 10.0, R = 0.1, mu_s = 0.3, mu_k = 0.25, k = 20.0;
  const double t_star = mu_s * m * kG * (1.0 + b.beta) / (b.beta * k);
  const double t_end = 1.5 * t_star;
  const std::string scene = fmt::format(R"(chasles: 1
title: "ramped push: {0}"
bodies:
  - name: body
    parts: [{1}]
    initial: {{position: [0, 0, 0.1 m]}}
gravity: standard
forces:
  - {{type: force, name: push, body: body, value: [t/s * {4} N, 0, 0]}}
contacts:
  - {{name: floor, body: body, {2}, mu_s: 0.3, mu_k: 0.25, plane: {{point: [0, 0, 0], normal: [0, 0, 1]}}}}
simulation: {{until: {3:.17g} s, tolerance: 1e-12, output_interval: {3:.17g} s}}
output:
  columns: [velocity, angular_velocity, contacts]
)",
                                        b.name, b.part, b.contact, t_end, k);
  const RunOut r = SimulateText("ramp-" + b.name, scene);
  const std::string p0 = b.points == 1 ? "floor" : "floor_0";
  EXPECT_NEAR(SlipStart(r, p0), t_star, kEvent * t_star) << b.name;
  // Once, and for good: every point starts to slip at t* and nothing changes after.
  EXPECT_EQ(ChangesAfterStart(r), b.points) << b.name;
  // The final state against the closed forms.
  const auto& vx = r.csv.at("body_vx");
  const auto& wy = r.csv.at("body_wy");
  const double v_star = k * t_star * t_star / (2.0 * m * (1.0 + b.beta));
  const double v =
      v_star + k * (t_end * t_end - t_star * t_star) / (2.0 * m) - mu_k * kG * (t_end - t_star);
  const double w = v_star / R + mu_k * kG * (t_end - t_star) / (b.beta * R);
  EXPECT_NEAR(vx.back(), v, kEvent * v) << b.name;
  EXPECT_NEAR(wy.back(), w, kEvent * w) << b.name;
  // Kinetic friction at the end: μk N at each point, N summing to m g.
  double N = 0.0, f = 0.0;
  for (int i = 0; i < b.points; ++i) {
    const std::string p = b.points == 1 ? "floor" : fmt::format("floor_{}", i);
    N += r.csv.at(p + "_N").back();
    f += r.csv.at(p + "_f").back();
  }
  EXPECT_NEAR(N, m * kG, kEvent * m * kG) << b.name;
  EXPECT_NEAR(f, mu_k * m * kG, kEvent * m * kG) << b.name;
}

INSTANTIATE_TEST_SUITE_P(
    Shapes, RoundBodyRampTest,
    ::testing::Values(
        Round{"cylinder",
              "{shape: cylinder, radius: 0.1 m, length: 0.2 m, axis: [0, 1, 0], mass: 10 kg}",
              "shape: cylinder, radius: 0.1 m, length: 0.2 m, axis: [0, 1, 0]", 0.5, 2},
        Round{"sphere", "{shape: sphere, radius: 0.1 m, mass: 10 kg}",
              "shape: sphere, radius: 0.1 m", 0.4, 1},
        Round{"hoop", "{shape: ring, radius: 0.1 m, axis: [0, 1, 0], mass: 10 kg}",
              "shape: disk, radius: 0.1 m, axis: [0, 1, 0]", 1.0, 1}),
    [](const ::testing::TestParamInfo<Round>& info) { return info.param.name; });

TEST(FrictionRegimes, BoxOnFourCornersBreaksLooseWhenThePushReachesMuSMg) {
  // Four coplanar corners share the friction by their capacity, so all four reach their cones
  // together at k t = μs m g, and slide from then on with a = (k t - μk m g) / m.
  const double m = 10.0, mu_s = 0.3, mu_k = 0.25, k = 20.0;
  const double t_star = mu_s * m * kG / k;  // 1.4709975 s
  const double t_end = 2.0;
  const RunOut r = SimulateText("ramp-box", R"(chasles: 1
title: "ramped push: box"
bodies:
  - name: box
    parts: [{shape: box, size: [0.4 m, 0.2 m, 0.2 m], mass: 10 kg}]
    initial: {position: [0, 0, 0.1 m]}
gravity: standard
forces:
  - {type: force, name: push, body: box, value: [t/s * 20 N, 0, 0]}
contacts:
  - {name: floor, body: box, shape: box, size: [0.4 m, 0.2 m, 0.2 m], mu_s: 0.3, mu_k: 0.25,
     plane: {point: [0, 0, 0], normal: [0, 0, 1]}}
simulation: {until: 2 s, tolerance: 1e-12, output_interval: 0.5 s}
output:
  columns: [velocity, angular_velocity, contacts]
)");
  for (int i = 0; i < 4; ++i) {
    EXPECT_NEAR(SlipStart(r, fmt::format("floor_{}", i)), t_star, kEvent * t_star) << i;
  }
  EXPECT_EQ(ChangesAfterStart(r), 4);
  const double v = k * (t_end * t_end - t_star * t_star) / (2.0 * m) - mu_k * kG * (t_end - t_star);
  EXPECT_NEAR(r.csv.at("box_vx").back(), v, kEvent * v);
  EXPECT_NEAR(r.csv.at("box_vy").back(), 0.0, kEvent * v);
  EXPECT_NEAR(r.csv.at("box_wz").back(), 0.0, kEvent);
  // While sticking each corner carries friction in proportion to its normal force: at
  // t = 1 s all four are at the same fraction k t / (μs m g) of their cones.
  const auto& t = r.csv.at("t");
  size_t i1 = 0;
  while (t[i1] < 1.0 - 1e-12) ++i1;
  for (int i = 0; i < 4; ++i) {
    const std::string p = fmt::format("floor_{}", i);
    EXPECT_NEAR(r.csv.at(p + "_f")[i1] / (mu_s * r.csv.at(p + "_N")[i1]), k * 1.0 / (mu_s * m * kG),
                1e-12)
        << p;
  }
}

TEST(FrictionRegimes, CylinderOnAnInclineTiltedPastTanThetaEqualsThreeMuS) {
  // The incline is a level floor with gravity turned slowly: the force m g (sin θ, 0,
  // -cos θ) with θ = θ0 + Ω t. The cylinder rolls until tan θ = 3 μs.
  const double mu_s = 0.2, theta0 = 0.3, rate = 0.05;  // [rad], [rad/s]
  const double theta_star = std::atan(3.0 * mu_s);
  const double t_star = (theta_star - theta0) / rate;
  const RunOut r = SimulateText("tilting-incline", fmt::format(R"(chasles: 1
title: "cylinder on an incline tilted slowly"
parameters:
  m: 10 kg
  g: 9.80665 m/s^2
  theta0: {0:.17g}
  rate: {1:.17g}
bodies:
  - name: cyl
    parts: [{{shape: cylinder, radius: 0.1 m, length: 0.2 m, axis: [0, 1, 0], mass: m}}]
    initial: {{position: [0, 0, 0.1 m]}}
forces:
  - {{type: force, name: weight, body: cyl,
     value: [m*g*sin(theta0 + rate*t/s), 0, -m*g*cos(theta0 + rate*t/s)]}}
contacts:
  - {{name: incline, body: cyl, shape: cylinder, radius: 0.1 m, length: 0.2 m, axis: [0, 1, 0],
     mu_s: 0.2, mu_k: 0.15, plane: {{point: [0, 0, 0], normal: [0, 0, 1]}}}}
simulation: {{until: {2:.17g} s, tolerance: 1e-12, output_interval: 0.5 s}}
output:
  columns: [velocity, contacts]
)",
                                                               theta0, rate, t_star + 1.0));
  EXPECT_NEAR(SlipStart(r, "incline_0"), t_star, kEvent * t_star);
  EXPECT_NEAR(SlipStart(r, "incline_1"), t_star, kEvent * t_star);
  EXPECT_EQ(ChangesAfterStart(r), 2);
}

// Painlevé: a rod (m = 1 kg, length L = 1 m, radius r = 1 cm) standing at θ = 60° on one end,
// translating at speed v, with mu = 1.5 at the end A. With N on A alone the effective normal
// mass is (1/m)(1 + 3 cos²θ ∓ 3 mu sinθ cosθ) (slender-rod limit; the sign with the slip
// direction): for the end sliding backward (v < 0 here) it is negative, 1 + 0.75 - 1.949 < 0, and
// with gravity pulling A down no N >= 0 is consistent. chasles jams A: the impulse at A that
// stops it leaves the rod turning about A with its angular momentum about A,
// H_A = m (L/2) sinθ |v|, so the energy lost is T0 - H_A² / (2 I_A), I_A = m (3 r² + L²)/12 +
// m L²/4. Sliding forward the forces are consistent and nothing is jammed.
std::string PainleveRod(double v) {
  return fmt::format(R"yaml(chasles: 1
title: "rod sliding on its end (Painlevé)"
parameters:
  l: 0.5 m
  theta: 60 deg
bodies:
  - name: rod
    parts: [{{shape: cylinder, radius: 1 cm, from: [0, 0, 0], to: [2*l*cos(theta), 0, 2*l*sin(theta)], mass: 1 kg}}]
    initial: {{velocity: [{} m/s, 0, 0]}}
gravity: standard
contacts:
  - {{name: floor, body: rod, shape: points, points: [[0, 0, 0]], mu_s: 1.5, mu_k: 1.5,
     plane: {{point: [0, 0, 0], normal: [0, 0, 1]}}}}
simulation: {{until: 0.1 s, integrator: adaptive, tolerance: 1e-12, output_interval: 0.05 s}}
)yaml",
                     v);
}

TEST(FrictionRegimes, PainleveRodIsJammedWithAWarningAndTheEnergyInTheLedger) {
  const double m = 1.0, L = 1.0, r = 0.01, theta = kPi / 3.0, v = 2.0;
  const RunOut run = SimulateText("painleve-backward", PainleveRod(-v));
  const double T0 = 0.5 * m * v * v;
  const double H = m * 0.5 * L * std::sin(theta) * v;
  const double I_A = m * (3 * r * r + L * L) / 12.0 + m * L * L / 4.0;
  const double lost = T0 - H * H / (2.0 * I_A);
  ASSERT_EQ(run.json.at("impacts").size(), 1u);
  const auto& jam = run.json.at("impacts")[0];
  EXPECT_TRUE(jam.at("jam").get<bool>());
  EXPECT_EQ(jam.at("t").get<double>(), 0.0);
  EXPECT_NEAR(jam.at("energy_lost").get<double>(), lost, 1e-12 * T0);
  ASSERT_EQ(run.json.at("warnings").size(), 1u);
  EXPECT_NE(run.json.at("warnings")[0].get<std::string>().find("Painlevé"), std::string::npos);
  // The ledger starts from the state as given: the jam's loss is in it.
  const auto& ledger = run.json.at("ledger");
  EXPECT_NEAR(ledger.at("impact_work").get<double>(), -lost, 1e-12 * T0);
  EXPECT_NEAR(ledger.at("dissipated").get<double>(), lost, 1e-9 * T0);
  EXPECT_LT(std::abs(ledger.at("relative_residual").get<double>()), 1e-12);
  // Sliding forward the forces are consistent: no jam, no warning.
  const RunOut fwd = SimulateText("painleve-forward", PainleveRod(v));
  EXPECT_TRUE(fwd.json.at("impacts").empty());
  EXPECT_TRUE(fwd.json.at("warnings").empty());
}

}  // namespace
}  // namespace chasles::test
