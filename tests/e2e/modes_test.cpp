// chasles modes and chasles balance (docs/modes.md) on the examples: the operating point, the
// modes and the stability changes against closed forms derived here, rigid modes named, a
// sweep through a double eigenvalue without NaN, the browser report's mode motions, and bad
// input refused with exit code 2 and nothing written.

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli_runner.h"
#include "test_support.h"

namespace chasles::test {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kG = 9.80665;  // gravity: standard
// Eigenvalues of a small dense matrix: round-off of a few hundred operations.
constexpr double kTol = 1e-10;

std::string WriteSceneFile(const std::string& name, const std::string& text) {
  const auto path = OutDir("modes") / name;
  std::ofstream(path) << text;
  return path.string();
}

nlohmann::json RunJson(const std::string& args) {
  const CliResult r = RunCli(args + " --format json");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out.find("nan"), std::string::npos);
  return nlohmann::json::parse(r.out);
}

std::vector<const nlohmann::json*> Oscillating(const nlohmann::json& modes) {
  std::vector<const nlohmann::json*> out;
  for (const auto& m : modes) {
    if (!m.at("rigid").get<bool>()) out.push_back(&m);
  }
  return out;
}

// Hostile input: every example, whatever it holds (contacts, events, time-dependent forces,
// motions that are no operating point), gives the modes or a clear error with exit code 2;
// never a crash, never NaN.
TEST(Modes, EveryExampleAnswersOrRefuses) {
  int count = 0;
  for (const auto& entry : std::filesystem::directory_iterator(SourcePath("examples"))) {
    if (entry.path().extension() != ".yaml") continue;
    if (!Sampled(count++)) continue;
    const CliResult r = RunCli("modes " + Quote(entry.path().string()) + " --format json");
    EXPECT_TRUE(r.exit_code == 0 || r.exit_code == 2) << entry.path() << ": " << r.err;
    if (r.exit_code == 2) {
      EXPECT_THAT(r.err, ::testing::HasSubstr("chasles: error: ")) << entry.path();
      EXPECT_TRUE(r.out.empty()) << entry.path();
    }
    EXPECT_EQ(r.out.find("nan"), std::string::npos) << entry.path();
  }
  EXPECT_GE(count, 8);
}

// examples/cylinder-in-trough.yaml: from rest 10° up the side, the equilibrium at the bottom
// (Newton) and the one mode ω² = 2 g / (3 (R - r)), R = 0.4 m, r = 0.05 m (its comment derives
// it); the cylinder's spin about its axis and its slide along the trough are rigid.
TEST(Modes, CylinderInATroughFromTheCli) {
  const nlohmann::json j =
      RunJson("modes " + Quote(SourcePath("examples/cylinder-in-trough.yaml")));
  EXPECT_EQ(j.at("operating_point").at("kind"), "equilibrium");
  EXPECT_LT(j.at("operating_point").at("residual").get<double>(), 1e-12);
  EXPECT_GT(j.at("operating_point").at("iterations").get<int>(), 0);
  const auto modes = Oscillating(j.at("modes"));
  ASSERT_EQ(modes.size(), 1u) << j.at("modes").dump();
  const double w = std::sqrt(2 * kG / (3 * (0.4 - 0.05)));
  EXPECT_NEAR(modes[0]->at("frequency_hz").get<double>(), w / (2 * kPi), kTol * w);
  EXPECT_NEAR(modes[0]->at("eigenvalue").at(1).get<double>(), w, kTol * w);
  EXPECT_TRUE(j.at("stable").get<bool>());
  std::vector<std::string> rigid;
  for (const auto& m : j.at("modes")) {
    if (m.at("rigid").get<bool>()) rigid.push_back(m.at("frees"));
  }
  std::sort(rigid.begin(), rigid.end());
  EXPECT_EQ(rigid, (std::vector<std::string>{"roller.ry", "roller.y"}));
  for (const auto& c : j.at("coordinates")) EXPECT_TRUE(c.contains("unit"));
}

// A free body at rest, no gravity: nothing to oscillate, every mode rigid and named (the
// linearisation is singular: twelve zero eigenvalues), the verdict stable, no NaN.
TEST(Modes, FreeBodyRigidModesNamed) {
  const std::string scene = WriteSceneFile("modes_free_body.yaml", R"(
chasles: 1
bodies:
  - name: brick
    parts: [{shape: box, size: [0.3 m, 0.2 m, 0.1 m], mass: 2 kg}]
gravity: [0, 0, 0]
)");
  const nlohmann::json j = RunJson("modes " + Quote(scene));
  EXPECT_EQ(j.at("modes").size(), 12u);
  std::vector<std::string> frees;
  for (const auto& m : j.at("modes")) {
    EXPECT_TRUE(m.at("rigid").get<bool>());
    frees.push_back(m.at("frees"));
  }
  std::sort(frees.begin(), frees.end());
  EXPECT_EQ(std::unique(frees.begin(), frees.end()), frees.end()) << "each names its own";
  EXPECT_TRUE(j.at("stable").get<bool>());
  const CliResult text = RunCli("modes " + Quote(scene));
  EXPECT_EQ(text.exit_code, 0) << text.err;
  EXPECT_THAT(text.out, ::testing::HasSubstr("rigid     frees "));
}

// examples/sleeping-top.yaml over its spin: the two tilt roots
// λ = i (I₃ Ω ± √(I₃² Ω² - 4 I₁ m g l)) / (2 I₁) meet at Ω_c² = 4 m g l I₁ / I₃² (a double
// eigenvalue) and the top is stable above it. A grid with Ω_c on it is swept straight through
// the double root: finite values, the verdict changing once, located to 1e-9 (below).
TEST(Modes, SleepingTopSweepThroughTheDoubleRoot) {
  const double rho = 0.04, h = 0.06, m = 0.7, l = h / 2;
  const double I1 = m * (3 * rho * rho + h * h) / 12 + m * l * l, I3 = m * rho * rho / 2;
  const double Wc = std::sqrt(4 * m * kG * l * I1 / (I3 * I3));
  const std::string grid =
      fmt::format("spin={:.17g} rad/s:{:.17g} rad/s:5", Wc - 20.0, Wc + 20.0);  // Wc is point 2
  const nlohmann::json j = RunJson("modes " + Quote(SourcePath("examples/sleeping-top.yaml")) +
                                   " --sweep " + Quote(grid));
  ASSERT_EQ(j.at("points").size(), 5u);
  for (const auto& p : j.at("points")) {
    for (const auto* mode : Oscillating(p.at("modes"))) {
      EXPECT_TRUE(mode->at("eigenvalue").at(0).is_number());
      EXPECT_TRUE(mode->at("eigenvalue").at(1).is_number());
    }
  }
  EXPECT_FALSE(j.at("points").at(0).at("stable").get<bool>());
  EXPECT_TRUE(j.at("points").at(4).at("stable").get<bool>());
  const auto& changes = j.at("stability_changes");
  ASSERT_EQ(changes.size(), 1u) << changes.dump();
  // At a double root the two eigenvalues separate as √(Ω - Ω_c): their computed real parts
  // carry round-off of order ε |A| / separation, which leaves the neutral band (1e-12 |λ|) only
  // from Ω - Ω_c ~ 1e-10 Ω_c on. The threshold is resolved to that, not to the bisection's
  // 1e-12 of the span.
  constexpr double kDoubleRoot = 1e-9;
  EXPECT_NEAR(changes[0].at("value").get<double>(), Wc, kDoubleRoot * Wc);
  EXPECT_EQ(changes[0].at("parameter"), "spin");
  EXPECT_TRUE(changes[0].at("stable_after").get<bool>());
  // Above the threshold: the slow precession and the fast nutation.
  const double W = Wc + 20.0, root = std::sqrt(I3 * I3 * W * W - 4 * I1 * m * kG * l);
  const auto above = Oscillating(j.at("points").at(4).at("modes"));
  ASSERT_EQ(above.size(), 2u);
  const double slow = (I3 * W - root) / (2 * I1), fast = (I3 * W + root) / (2 * I1);
  EXPECT_NEAR(above[0]->at("eigenvalue").at(1).get<double>(), slow, kTol * slow);
  EXPECT_NEAR(above[1]->at("eigenvalue").at(1).get<double>(), fast, kTol * fast);
}

// The bicycle's weave and capsize speeds (Meijaard et al. 2007, Table 2: 4.29238253634111 and
// 6.02426201538837 m/s) from the command line.
TEST(Modes, BicycleSweepStabilityChanges) {
  const nlohmann::json j = RunJson("modes " + Quote(SourcePath("examples/whipple-bicycle.yaml")) +
                                   " --sweep 'v=0 m/s:10 m/s:11'");
  const auto& c = j.at("stability_changes");
  ASSERT_EQ(c.size(), 2u);
  EXPECT_NEAR(c[0].at("value").get<double>(), 4.29238253634111, 1e-10 * 4.29238253634111);
  EXPECT_EQ(c[0].at("kind"), "oscillatory");
  EXPECT_NEAR(c[1].at("value").get<double>(), 6.02426201538837, 1e-10 * 6.02426201538837);
  EXPECT_EQ(c[1].at("kind"), "divergent");
}

// The sweep's table (--format csv): every eigenvalue of the lean and steer motion, a complex
// pair's both members, so four at every speed (four real ones at rest, a weave pair from
// 1 m/s on), no empty cell; `chasles plot` draws the root locus from it.
TEST(Modes, BicycleRootLocusTable) {
  const CliResult csv = RunCli("modes " + Quote(SourcePath("examples/whipple-bicycle.yaml")) +
                               " --sweep 'v=0 m/s:10 m/s:3' --format csv");
  ASSERT_EQ(csv.exit_code, 0) << csv.err;
  EXPECT_THAT(csv.out, ::testing::StartsWith("v,re_1,im_1,f_1,re_2,im_2,f_2,re_3,im_3,f_3,re_4,"
                                             "im_4,f_4,stable\n"));
  EXPECT_EQ(csv.out.find(",,"), std::string::npos) << csv.out;
#ifdef CHASLES_HAVE_PLOT
  const auto table = OutDir("modes") / "bicycle.csv";
  std::ofstream(table) << csv.out;
  const auto png = OutDir("modes") / "bicycle-root-locus.png";
  const CliResult plot =
      RunCli("plot " + Quote(table.string()) + " v re_1 re_2 re_3 re_4 -o " + Quote(png.string()));
  EXPECT_EQ(plot.exit_code, 0) << plot.err;
  EXPECT_TRUE(std::filesystem::exists(png));
#endif
}

// examples/rotor-on-bearings.yaml's rotor (its comment): a shaft (8 kg, radius 5 cm, length
// 60 cm) and a disk (5 kg, radius 20 cm) at z = 28 cm, about the whole rotor's centre of mass
// z_c; bearings of 3e5 and 1e5 N/m at z = -28 cm and 10 cm, K_n = Σ k_j (z_j - z_c)^n.
struct ExampleRotor {
  static constexpr double ms = 8, rho = 0.05, L = 0.6, md = 5, Rd = 0.2, zd = 0.28;
  double m = ms + md, zc = md * zd / m;
  double It = ms * (3 * rho * rho + L * L) / 12 + ms * zc * zc + md * Rd * Rd / 4 +
              md * (zd - zc) * (zd - zc);
  double Ip = ms * rho * rho / 2 + md * Rd * Rd / 2;
  double kA = 3e5, kB = 1e5, zA = -0.28 - zc, zB = 0.1 - zc;
  double K0 = kA + kB, K1 = kA * zA + kB * zB, K2 = kA * zA * zA + kB * zB * zB;
};

// examples/rotor-on-bearings.yaml over its spin: the critical speeds are the spins at which a
// root ω = Ω of (K0 - m ω²)(K2 - I_t ω² + I_p Ω ω) = K1² (docs/modes.md), i.e. the roots of
// (K0 - m Ω²)(K2 - (I_t - I_p) Ω²) = K1², a quadratic in Ω².
TEST(Modes, RotorCriticalSpeeds) {
  const ExampleRotor r;
  const double m = r.m, It = r.It, Ip = r.Ip, K0 = r.K0, K1 = r.K1, K2 = r.K2;
  // m (It - Ip) x² - (m K2 + K0 (It - Ip)) x + K0 K2 - K1² = 0, x = Ω².
  const double a = m * (It - Ip), b = -(m * K2 + K0 * (It - Ip)), c = K0 * K2 - K1 * K1;
  const double x1 = (-b - std::sqrt(b * b - 4 * a * c)) / (2 * a);
  const double x2 = (-b + std::sqrt(b * b - 4 * a * c)) / (2 * a);
  // Undamped, so that a whirl frequency is |Im λ| exactly.
  const nlohmann::json j = RunJson("modes " + Quote(SourcePath("examples/rotor-on-bearings.yaml")) +
                                   " --set 'damping=0 N*s/m' --sweep 'spin=0 rad/s:400 rad/s:21'");
  std::vector<double> speeds;
  for (const auto& s : j.at("critical_speeds")) speeds.push_back(s.at("speed").get<double>());
  for (const double want : {std::sqrt(x1), std::sqrt(x2)}) {
    if (want > 400) continue;
    EXPECT_TRUE(std::any_of(speeds.begin(), speeds.end(),
                            [&](double s) { return std::abs(s - want) < kTol * want; }))
        << "no critical speed at " << want << " in " << j.at("critical_speeds").dump();
  }
}

// `chasles balance` on a rotor held by bearings gives whirl rows: the critical speeds of
// examples/rotor-on-bearings.yaml (undamped), forward where ω = Ω solves
// (K0 - m ω²)(K2 - I_t ω² + I_p Ω ω) = K1², i.e. (K0 - m Ω²)(K2 - (I_t - I_p) Ω²) = K1², and
// backward where ω = -Ω does, (K0 - m Ω²)(K2 - (I_t + I_p) Ω²) = K1²: quadratics in Ω².
TEST(Balance, WhirlRowsAndCriticalSpeedsFromTheCli) {
  const ExampleRotor r;
  const double m = r.m, It = r.It, Ip = r.Ip, K0 = r.K0, K1 = r.K1, K2 = r.K2;
  // The two roots Ω of m J x² - (m K2 + K0 J) x + K0 K2 - K1² = 0 (x = Ω²), J = I_t ∓ I_p.
  const auto roots = [&](double J) {
    const double a = m * J, b = -(m * K2 + K0 * J), c = K0 * K2 - K1 * K1;
    const double d = std::sqrt(b * b - 4 * a * c);
    return std::pair{std::sqrt((-b - d) / (2 * a)), std::sqrt((-b + d) / (2 * a))};
  };
  const auto [f1, f2] = roots(It - Ip);
  const auto [b1, b2] = roots(It + Ip);
  const nlohmann::json j =
      RunJson("balance " + Quote(SourcePath("examples/rotor-on-bearings.yaml")) +
              " --set 'damping=0 N*s/m' --body rotor --planes '-28 cm, 10 cm' --radius '10 cm' "
              "--whirl '0 rad/s:400 rad/s:21'");
  const auto& w = j.at("whirl");
  ASSERT_EQ(w.at("points").size(), 21u);
  EXPECT_EQ(w.at("speeds").at(20).get<double>(), 400.0);
  const std::vector<std::pair<double, std::string>> want = {
      {b1, "backward"}, {f1, "forward"}, {b2, "backward"}, {f2, "forward"}};
  const auto& cs = w.at("critical_speeds");
  ASSERT_EQ(cs.size(), want.size()) << cs.dump();
  for (size_t i = 0; i < want.size(); ++i) {
    EXPECT_NEAR(cs[i].at("speed").get<double>(), want[i].first, kTol * want[i].first);
    EXPECT_EQ(cs[i].at("directions"), nlohmann::json::array({want[i].second})) << cs.dump();
  }
  // A rotor on no bearings has no whirl rows.
  const nlohmann::json none =
      RunJson("balance " + Quote(SourcePath("examples/unbalanced-disk-rotor.yaml")) +
              " --body rotor --planes '-25 cm, 25 cm' --radius '15 cm'");
  EXPECT_TRUE(none.at("whirl").is_null());
}

// examples/unbalanced-disk-rotor.yaml (its comment): U = m_d e for the disk 0.2 mm off the
// axis (the shaft is on it), its own couple -sin τ cos τ (I_p - I_d) about x, so about O
// D = C_d + z_d U and about the rotor's centre of mass (z_cm = m_d z_d / m) C = D - z_cm U;
// the corrections u_A = (z_B U - D)/(z_A - z_B), u_B = (D - z_A U)/(z_A - z_B), and after
// them nothing left; ISO 21940-11: U_per = m G/ω.
TEST(Balance, UnbalancedDiskFromTheCli) {
  const double md = 5, Rd = 0.2, e = 0.2e-3, zd = 0.1, tau = 0.5 * kPi / 180, r = 0.15;
  const double zA = -0.25, zB = 0.25, w = 3000 * 2 * kPi / 60, mass = md + 1.5;
  const double U = md * e, Cd = -std::sin(tau) * std::cos(tau) * (md * Rd * Rd / 4);
  const double D = Cd + zd * U, C = D - md * zd / mass * U;
  const double uA = (zB * U - D) / (zA - zB), uB = (D - zA * U) / (zA - zB);
  const nlohmann::json j =
      RunJson("balance " + Quote(SourcePath("examples/unbalanced-disk-rotor.yaml")) +
              " --body rotor --planes '-25 cm, 25 cm' --radius '15 cm' --speed '3000 rpm' "
              "--grade 6.3");
  EXPECT_NEAR(j.at("mass").get<double>(), mass, 1e-12 * mass);
  EXPECT_NEAR(j.at("static_unbalance").get<double>(), U, kTol * U);
  EXPECT_NEAR(j.at("couple_unbalance").get<double>(), std::abs(C), kTol * std::abs(C));
  const auto& c = j.at("corrections");
  EXPECT_NEAR(c[0].at("mass").get<double>(), std::abs(uA) / r, kTol * std::abs(uA) / r);
  EXPECT_NEAR(c[1].at("mass").get<double>(), std::abs(uB) / r, kTol * std::abs(uB) / r);
  EXPECT_LT(j.at("residual_after").at("static").get<double>(), 1e-15);
  EXPECT_NEAR(j.at("permissible").at("total").get<double>(), mass * 6.3e-3 / w,
              1e-12 * mass * 6.3e-3 / w);
  const Eigen::Vector3d F = ToVec(j.at("bearing_reactions").at("before").at("A"));
  EXPECT_NEAR(F.norm(), w * w * std::abs(uA), kTol * w * w * std::abs(uA));
  EXPECT_LT(ToVec(j.at("bearing_reactions").at("after").at("A")).norm(), 1e-12 * F.norm());
}

// A mesh part's unbalance is that of the same part built from a primitive: a box
// 0.2 × 0.1 × 0.05 m of 3 kg, 1.5 mm off the axis and tilted by 2° about y, as a closed
// triangle mesh (its integrals are exact: divergence theorem) and as `shape: box`. The static
// and couple unbalance and the corrections agree to round-off.
TEST(Balance, MeshPartEqualsThePrimitive) {
  const double a = 0.1, b = 0.05, c = 0.025;  // half sizes
  std::string obj;
  for (int i = 0; i < 8; ++i) {
    obj += fmt::format("v {} {} {}\n", i & 1 ? a : -a, i & 2 ? b : -b, i & 4 ? c : -c);
  }
  // Two outward triangles per face of the cube of vertices 1..8 (bit 0: x, 1: y, 2: z).
  obj +=
      "f 1 3 4\nf 1 4 2\nf 5 6 8\nf 5 8 7\nf 1 2 6\nf 1 6 5\n"
      "f 3 7 8\nf 3 8 4\nf 1 5 7\nf 1 7 3\nf 2 4 8\nf 2 8 6\n";
  const auto mesh = OutDir("modes") / "box.obj";
  std::ofstream(mesh) << obj;
  const std::string place =
      "mass: 3 kg, position: [1.5 mm, 0, 4 cm], rotation: {axis: [0, 1, 0], angle: 2 deg}";
  const std::string scene = "chasles: 1\nbodies:\n  - name: rotor\n    parts:\n      - {";
  const std::string as_mesh =
      WriteSceneFile("mesh_rotor.yaml",
                     scene + "shape: mesh, unit: m, file: " + mesh.string() + ", " + place + "}\n");
  const std::string as_box = WriteSceneFile(
      "box_rotor.yaml", scene + "shape: box, size: [0.2 m, 0.1 m, 0.05 m], " + place + "}\n");
  const std::string args = " --body rotor --planes '-10 cm, 15 cm' --radius '6 cm'";
  const nlohmann::json m = RunJson("balance " + Quote(as_mesh) + args);
  const nlohmann::json p = RunJson("balance " + Quote(as_box) + args);
  for (const char* key : {"mass", "static_unbalance", "couple_unbalance"}) {
    const double want = p.at(key).get<double>();
    EXPECT_NEAR(m.at(key).get<double>(), want, 1e-12 * want) << key;
  }
  EXPECT_GT(p.at("couple_unbalance").get<double>(), 0.0);
  for (int k = 0; k < 2; ++k) {
    const double want = p.at("corrections").at(k).at("mass").get<double>();
    EXPECT_NEAR(m.at("corrections").at(k).at("mass").get<double>(), want, 1e-12 * want) << k;
    EXPECT_NEAR(m.at("corrections").at(k).at("angle").get<double>(),
                p.at("corrections").at(k).at("angle").get<double>(), 1e-12);
  }
}

TEST(Balance, BadOptionsAreInputErrors) {
  const std::string scene = Quote(SourcePath("examples/unbalanced-disk-rotor.yaml"));
  for (const auto& [args, expect] : std::vector<std::pair<std::string, std::string>>{
           {"--body rotor --planes '10 cm, 10 cm' --radius '5 cm'", "they must differ"},
           {"--body rotor --planes '10 cm' --radius '5 cm'", "is not two positions"},
           {"--body rotor --planes '-1 cm, 1 cm' --radius '5 kg'", "is not a length"},
           {"--body rotor --planes '-1 cm, 1 cm' --radius '5 cm' --grade 6.3", "--speed"},
           {"--body wheel --planes '-1 cm, 1 cm' --radius '5 cm'", "wheel"},
           {"--body rotor --planes '-1 cm, 1 cm' --radius '5 cm' --whirl '0 rpm:1 rpm:3'",
            "no bearing element holds 'rotor'"},
       }) {
    const CliResult r = RunCli("balance " + scene + " " + args);
    EXPECT_EQ(r.exit_code, 2) << args << ": " << r.err;
    EXPECT_THAT(r.err, ::testing::HasSubstr(expect)) << args;
    EXPECT_TRUE(r.out.empty()) << args;
  }
  const std::string held = Quote(SourcePath("examples/rotor-on-bearings.yaml")) +
                           " --body rotor --planes '-28 cm, 10 cm' --radius '10 cm' ";
  for (const auto& [args, expect] : std::vector<std::pair<std::string, std::string>>{
           {"--whirl '0 rpm:100 rpm'", "is not three fields"},
           {"--whirl '0 rpm:100 rpm:1'", "needs 2 to 1,000 points"},
           {"--whirl '0 rpm:100 rpm:x'", "has no whole number of points"},
           {"--whirl '100 rpm:0 rpm:5'", "needs 0 <= A < B"},
           {"--whirl '0 m:1 m:5'", "is not an angular speed"},
       }) {
    const CliResult r = RunCli("balance " + held + args);
    EXPECT_EQ(r.exit_code, 2) << args << ": " << r.err;
    EXPECT_THAT(r.err, ::testing::HasSubstr(expect)) << args;
    EXPECT_TRUE(r.out.empty()) << args;
  }
}

/// The report data a page embeds (<script type="application/json" id="chasles-data">).
nlohmann::json PageData(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  const std::string page = text.str();
  const std::string open = "<script type=\"application/json\" id=\"chasles-data\">";
  const size_t from = page.find(open);
  if (from == std::string::npos) return nullptr;
  const size_t to = page.find("</script>", from);
  std::string json = page.substr(from + open.size(), to - from - open.size());
  for (size_t at = json.find("<\\/"); at != std::string::npos; at = json.find("<\\/", at)) {
    json.erase(at + 1, 1);  // the page writes "</" as "<\/" inside a script
  }
  return nlohmann::json::parse(json);
}

/// The files in `dir` (to show that nothing, not even a temporary, was left).
std::vector<std::string> FilesIn(const std::filesystem::path& dir) {
  std::vector<std::string> out;
  for (const auto& e : std::filesystem::directory_iterator(dir)) out.push_back(e.path().string());
  return out;
}

// --html on examples/cylinder-in-trough.yaml: the page's data carries the one oscillation with
// the rolling kinematics of the closed form (δp = r δθ_y x, the test of CalcBodyModeShapes in
// tests/unit/analysis), scaled so that the largest excursion |δp| + ρ|δθ| is 10 % of the
// scene's size, with ρ² = tr(I_cm)/(2m) = (r²/2 + 2 (r²/4 + len²/12))/2 for the solid cylinder
// (m r²/2 about its axis, m (3r² + len²)/12 across), over one period 2π/ω of the neutral
// oscillation; the rigid modes are listed and not animated.
TEST(Modes, HtmlReportAnimatesTheRollingMode) {
  const double r = 0.05, len = 0.1, R = 0.4;
  const auto dir = OutDir("modes_html");
  const std::string html = (dir / "trough.html").string();
  const CliResult run = RunCli("modes " + Quote(SourcePath("examples/cylinder-in-trough.yaml")) +
                               " --html " + Quote(html));
  if (run.exit_code == 2) {  // built without the report
    EXPECT_THAT(run.err, ::testing::HasSubstr("has no browser report"));
    return;
  }
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_THAT(run.err, ::testing::HasSubstr("Wrote " + html + " (the browser report)"));
  EXPECT_THAT(run.out, ::testing::HasSubstr("Verdict: stable"));  // standard output unchanged
  const nlohmann::json data = PageData(html);
  ASSERT_TRUE(data.is_object());
  EXPECT_EQ(data.at("kind"), "modes");
  const auto moving = Oscillating(data.at("modes"));
  ASSERT_EQ(moving.size(), 1u);
  const nlohmann::json& mode = *moving[0];
  ASSERT_TRUE(mode.at("animated").get<bool>());
  const auto vec = [](const nlohmann::json& v) {
    return Eigen::Vector3d(v.at(0).get<double>(), v.at(1).get<double>(), v.at(2).get<double>());
  };
  const nlohmann::json& body = mode.at("bodies").at(0);
  const Eigen::Vector3d dp = vec(body.at("dp").at("re")), dtheta = vec(body.at("dtheta").at("re"));
  EXPECT_LT(vec(body.at("dp").at("im")).norm() + vec(body.at("dtheta").at("im")).norm(),
            kTol * dp.norm());
  EXPECT_NEAR(dp.x() / dtheta.y(), r, kTol * r);
  const double rho = std::sqrt((r * r / 2 + 2 * (r * r / 4 + len * len / 12)) / 2);
  const double size = data.at("amplitude").at("scene_size").get<double>();
  EXPECT_NEAR(dp.norm() + rho * dtheta.norm(), 0.1 * size, kTol * size);
  // The scene's size: the centre of mass and the contact point r below it, plus 2ρ.
  EXPECT_NEAR(size, r + 2 * rho, kTol * size);
  const double w = std::sqrt(2 * kG / (3 * (R - r)));
  EXPECT_EQ(mode.at("shown"), "oscillation");
  EXPECT_EQ(mode.at("loop").at(0).get<double>(), 0.0);
  EXPECT_NEAR(mode.at("loop").at(1).get<double>(), 2 * kPi / w, kTol * 2 * kPi / w);
  int rigid = 0;
  for (const auto& m : data.at("modes")) {
    if (!m.at("rigid").get<bool>()) continue;
    ++rigid;
    EXPECT_FALSE(m.at("animated").get<bool>());
    EXPECT_FALSE(m.contains("bodies"));
  }
  EXPECT_EQ(rigid, 2);
}

// --html to a place no file can be made, with a sweep, or for a scene that has no operating
// point: exit code 2, the reason named, and nothing written, neither the page nor the -o report.
TEST(Modes, HtmlReportBadInputLeavesNothing) {
  const auto dir = OutDir("modes_html_bad");
  const std::string report = Quote((dir / "modes.txt").string());
  const std::string trough = Quote(SourcePath("examples/cylinder-in-trough.yaml"));
  // A block falling freely: no static equilibrium anywhere.
  const std::string falling = Quote(WriteSceneFile(
      "falling_block.yaml",
      "chasles: 3\nbodies:\n  - name: block\n    parts: [{shape: box, size: [0.1, 0.2, 0.3], "
      "mass: 2}]\ngravity: standard\n"));
  const std::string page = Quote((dir / "modes.html").string());
  for (const auto& [args, expect] : std::vector<std::pair<std::string, std::string>>{
           {trough + " --html " + Quote((dir / "no-such-folder" / "m.html").string()),
            "no-such-folder"},
           {trough + " --html " + Quote(dir.string()), "--html"},
           {trough + " --sweep 'R=30 cm:50 cm:3' --html " + page, "leave out --sweep"},
           {falling + " --html " + page, "no static equilibrium"},
       }) {
    const CliResult r = RunCli("modes " + args + " -o " + report);
    EXPECT_EQ(r.exit_code, 2) << args << ": " << r.err;
    if (r.exit_code == 2 && r.err.find("has no browser report") != std::string::npos) continue;
    EXPECT_THAT(r.err, ::testing::HasSubstr(expect)) << args;
    EXPECT_TRUE(r.out.empty()) << args;
    const std::vector<std::string> left = FilesIn(dir);
    EXPECT_TRUE(left.empty()) << args << ": left " << (left.empty() ? "" : left[0]);
  }
}

}  // namespace
}  // namespace chasles::test
