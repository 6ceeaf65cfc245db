// The browser report's data (chasles/report/report_data.h): base64, the parts as drawn, the
// equivalent ellipsoids, a run's columns, exact where the page compares them, and the loops of
// the modes report.

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>
#include <utility>
#include <vector>

// Before gtest: <signal.h> (via gtest) defines a macro si_value, a parameter name in units.h.
#include "chasles/error.h"
#include "chasles/report/report_data.h"
#include "chasles/scene/study.h"
#include "test_paths.h"
// clang-format off
#include <gtest/gtest.h>
// clang-format on

namespace chasles {
namespace {

std::string B64(const std::string& s) {
  return Base64(s.data(), s.size());
}

/// The doubles of a base64 "f8" array.
std::vector<double> DecodeF8(const std::string& text) {
  auto value = [](char c) -> int {
    if (c >= 'A' && c <= 'Z') return c - 'A';
    if (c >= 'a' && c <= 'z') return c - 'a' + 26;
    if (c >= '0' && c <= '9') return c - '0' + 52;
    return c == '+' ? 62 : 63;
  };
  std::vector<unsigned char> bytes;
  for (size_t i = 0; i + 3 < text.size(); i += 4) {
    const int n = (value(text[i]) << 18) | (value(text[i + 1]) << 12) |
                  (text[i + 2] == '=' ? 0 : value(text[i + 2]) << 6) |
                  (text[i + 3] == '=' ? 0 : value(text[i + 3]));
    bytes.push_back(static_cast<unsigned char>(n >> 16));
    if (text[i + 2] != '=') bytes.push_back(static_cast<unsigned char>((n >> 8) & 255));
    if (text[i + 3] != '=') bytes.push_back(static_cast<unsigned char>(n & 255));
  }
  std::vector<double> out(bytes.size() / sizeof(double));
  std::memcpy(out.data(), bytes.data(), out.size() * sizeof(double));
  return out;
}

// RFC 4648, section 10.
TEST(ReportData, Base64TestVectors) {
  EXPECT_EQ(B64(""), "");
  EXPECT_EQ(B64("f"), "Zg==");
  EXPECT_EQ(B64("fo"), "Zm8=");
  EXPECT_EQ(B64("foo"), "Zm9v");
  EXPECT_EQ(B64("foob"), "Zm9vYg==");
  EXPECT_EQ(B64("fooba"), "Zm9vYmE=");
  EXPECT_EQ(B64("foobar"), "Zm9vYmFy");
}

// Legendre's ellipsoid, a_i² = 5 (I_j + I_k − I_i) / (2 m): a uniform solid sphere of radius R
// (I = 2/5 m R²) is its own ellipsoid, a_i = R; a uniform box a × b × c (I_x = m (b² + c²)/12)
// gives a_x² = 5 (2 a²/12) / 2, a_x = a sqrt(5/12); a custom part with I = diag(1, 2, 3) kg m²
// and m = 1 kg gives a = [sqrt(10), sqrt(5), 0] m along x, y, z.
TEST(ReportData, EquivalentEllipsoids) {
  const Scene scene = LoadSceneText(R"(
bodies:
  - name: ball
    parts: [{shape: sphere, radius: 0.3 m, mass: 2 kg}]
  - name: brick
    parts: [{shape: box, size: [0.2 m, 0.4 m, 0.6 m], mass: 5 kg}]
  - name: top
    parts: [{shape: custom, mass: 1 kg, inertia: {Ixx: 1 kg*m^2, Iyy: 2 kg*m^2, Izz: 3 kg*m^2}}]
)",
                                    "ellipsoids");
  const nlohmann::json j = MassReportData(scene);
  EXPECT_EQ(j["kind"], "mass");
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(j["bodies"][0]["ellipsoid"][k].get<double>(), 0.3, 1e-14);
  }
  // Principal moments ascending: I_z ∝ 0.04 + 0.16, I_y ∝ 0.04 + 0.36, I_x ∝ 0.16 + 0.36, so
  // e1 = z (a_z = c sqrt(5/12)), e2 = y, e3 = x.
  const double want[3] = {0.6 * std::sqrt(5.0 / 12), 0.4 * std::sqrt(5.0 / 12),
                          0.2 * std::sqrt(5.0 / 12)};
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(j["bodies"][1]["ellipsoid"][k].get<double>(), want[k], 1e-14);
  }
  const nlohmann::json& e = j["bodies"][2]["parts"][0]["ellipsoid"];
  EXPECT_NEAR(e["semi_axes"][0].get<double>(), std::sqrt(10.0), 1e-14);
  EXPECT_NEAR(e["semi_axes"][1].get<double>(), std::sqrt(5.0), 1e-14);
  EXPECT_NEAR(e["semi_axes"][2].get<double>(), 0.0, 1e-7);
}

// A cylinder given by from/to: its length is |to − from|, its frame at the midpoint with z
// along to − from (docs/scene-format.md, segments).
TEST(ReportData, PartsAsDrawn) {
  const Scene scene = LoadSceneText(R"(
bodies:
  - name: shaft
    parts: [{shape: cylinder, radius: 0.05 m, mass: 1 kg, from: [0, 0, 0], to: [0, 0.3 m, 0.4 m]}]
)",
                                    "parts");
  const nlohmann::json p = MassReportData(scene)["bodies"][0]["parts"][0];
  EXPECT_EQ(p["shape"], "cylinder");
  EXPECT_NEAR(p["dimensions"]["length"].get<double>(), 0.5, 1e-15);
  EXPECT_NEAR(p["dimensions"]["radius"].get<double>(), 0.05, 1e-15);
  EXPECT_NEAR(p["position"][1].get<double>(), 0.15, 1e-15);
  EXPECT_NEAR(p["position"][2].get<double>(), 0.2, 1e-15);
  // z of the part's frame along (0, 0.6, 0.8): the quaternion q = [w, x, y, z] turns z by the
  // angle φ with cos φ = 0.8 about an axis perpendicular to z and the direction.
  const double w = p["quaternion"][0], x = p["quaternion"][1], y = p["quaternion"][2],
               z = p["quaternion"][3];
  // Third column of R(q): [2(xz + wy), 2(yz − wx), 1 − 2(x² + y²)].
  EXPECT_NEAR(2 * (x * z + w * y), 0.0, 1e-15);
  EXPECT_NEAR(2 * (y * z - w * x), 0.6, 1e-15);
  EXPECT_NEAR(1 - 2 * (x * x + y * y), 0.8, 1e-15);
}

// Free fall from z0 with vz0: z(t) = z0 + vz0 t − g t²/2, exact to round-off in the report's
// f8 pose columns; the pose columns are added to the scene's own; without them the report is
// refused.
TEST(ReportData, RunColumnsExactAndPoseColumnsRequired) {
  Scene scene = LoadSceneText(R"(
bodies:
  - name: ball
    parts: [{shape: sphere, radius: 0.1 m, mass: 1 kg}]
    initial: {position: [0, 0, 2 m], velocity: [0, 0, 3 m/s]}
gravity: [0, 0, -9.81 m/s^2]
output: {columns: [position]}
simulation: {until: 0.5 s, tolerance: 1e-12, output_interval: 0.1 s}
)",
                              "fall");
  const StudyResult plain = RunStudy(MakeStudyDefinition(scene));
  EXPECT_THROW(SimulationReportData(scene, plain), InputError);

  scene.dynamics.columns = ReportColumns(scene, scene.dynamics.columns);
  StudyOptions options;
  options.record_row_snapshots = true;
  const StudyResult r = RunStudy(MakeStudyDefinition(scene, options));
  ASSERT_EQ(r.row_snapshots.size(), r.rows.size());
  const nlohmann::json j = SimulationReportData(scene, r);
  EXPECT_EQ(j["samples"].get<size_t>(), r.rows.size());
  std::vector<double> t, oz, qw;
  for (const auto& c : j["columns"]) {
    if (c["name"] == "t") t = DecodeF8(c["data"]);
    if (c["name"] == "ball_oz") oz = DecodeF8(c["data"]);
    if (c["name"] == "ball_qw") qw = DecodeF8(c["data"]);
    if (c["name"] == "ball_oz") {
      EXPECT_EQ(c["type"], "f8");
    }
    if (c["name"] == "E") {
      EXPECT_EQ(c["group"], "energy");
    }
  }
  ASSERT_EQ(t.size(), r.rows.size());
  ASSERT_EQ(oz.size(), r.rows.size());
  for (size_t i = 0; i < t.size(); ++i) {
    EXPECT_NEAR(oz[i], 2.0 + 3.0 * t[i] - 0.5 * 9.81 * t[i] * t[i], 1e-12);
    EXPECT_EQ(qw[i], 1.0);
  }
  EXPECT_TRUE(j["reactions"].empty());
  EXPECT_TRUE(j["contacts"].empty());
}

// The poses derived from the centre of mass and orientation equal the recorded origin and
// quaternion columns: Bo = Bcm − R_WB p_BoBcm_B, here with the centre of mass off the body
// origin (a part at (0.3, 0.1, 0.2) m) and a spinning, tumbling body (3-D), and a planar body
// turning about z.
TEST(ReportData, PosesDerivedFromCentreOfMassAndOrientation) {
  for (const bool planar : {false, true}) {
    const std::string text = planar ? R"(
planar: true
bodies:
  - name: b
    parts: [{shape: sphere, radius: 0.1 m, mass: 1 kg, position: [0.3 m, 0.1 m]}]
    initial: {velocity: [1 m/s, 2 m/s], omega: 3 rad/s}
gravity: standard
output: {columns: [planar, origin, quaternion]}
simulation: {until: 1 s, tolerance: 1e-12, output_interval: 0.05 s}
)"
                                    : R"(
bodies:
  - name: b
    parts: [{shape: box, size: [0.4 m, 0.2 m, 0.1 m], mass: 1 kg, position: [0.3 m, 0.1 m, 0.2 m]}]
    initial: {velocity: [1 m/s, 2 m/s, 3 m/s], angular_velocity: [1 rad/s, 5 rad/s, 0.2 rad/s]}
gravity: standard
output: {columns: [position, origin, quaternion]}
simulation: {until: 1 s, tolerance: 1e-12, output_interval: 0.05 s}
)";
    const Scene scene = LoadSceneText(text, "poses");
    const StudyResult full = RunStudy(MakeStudyDefinition(scene));
    // The same run without the origin (and, planar, without the quaternion) columns.
    StudyResult r = full;
    std::vector<size_t> keep;
    r.columns.clear();
    r.units.clear();
    for (size_t c = 0; c < full.columns.size(); ++c) {
      const std::string& n = full.columns[c];
      const bool origin = n == "b_ox" || n == "b_oy" || n == "b_oz";
      const bool quaternion = n.rfind("b_q", 0) == 0;
      if (origin || (planar && quaternion)) continue;
      keep.push_back(c);
      r.columns.push_back(n);
      if (c < full.units.size()) r.units.push_back(full.units[c]);
    }
    for (size_t i = 0; i < full.rows.size(); ++i) {
      r.rows[i].clear();
      for (size_t c : keep) r.rows[i].push_back(full.rows[i][c]);
    }
    EXPECT_EQ(CompletePoseColumns(scene, r), std::vector<std::string>{"b"}) << planar;
    const auto find = [](const std::vector<std::string>& cols, const std::string& n) {
      for (size_t c = 0; c < cols.size(); ++c) {
        if (cols[c] == n) return c;
      }
      ADD_FAILURE() << "no column " << n;
      return size_t{0};
    };
    for (const char* s : {"b_ox", "b_oy", "b_oz", "b_qw", "b_qx", "b_qy", "b_qz"}) {
      const size_t a = find(full.columns, s), b = find(r.columns, s);
      for (size_t i = 0; i < full.rows.size(); ++i) {
        EXPECT_NEAR(r.rows[i][b], full.rows[i][a], 1e-12)
            << s << " row " << i << " planar " << planar;
      }
    }
    // Nothing to add a second time; a body without orientation columns stays without.
    EXPECT_TRUE(CompletePoseColumns(scene, r).empty());
  }
}

// The loop of a decaying oscillation (ModesReportData; docs/report.md, "Modes"): the weave of
// examples/whipple-bicycle.yaml, λ = σ + iω with σ < 0, runs from t = 0 until the amplitude
// e^{σt} has fallen to a tenth, T = ln 10 / |σ|, cut down to whole periods P = 2π/ω and to at
// most five: at 5 m/s (σ = -0.775 1/s, ω = 4.46 1/s, Table 2 of Meijaard et al. 2007) two
// periods; at 4.4 m/s, just above the weave speed 4.29 m/s, σ is small and the loop five periods.
TEST(ReportData, ModesLoopADecayingOscillationOverWholePeriods) {
  for (const auto& [speed, periods] : {std::pair{"5 m/s", 2.0}, std::pair{"4.4 m/s", 5.0}}) {
    SceneOptions options;
    options.parameter_overrides = {{"v", speed}};
    const Scene scene =
        LoadSceneFile(std::string(test::SourceDir()) + "/examples/whipple-bicycle.yaml", options);
    const nlohmann::json data =
        ModesReportData(scene, AnalyseOperatingPointModes(MakeModesDefinition(scene)));
    const nlohmann::json* weave = nullptr;
    for (const nlohmann::json& m : data.at("modes")) {
      if (m.at("eigenvalue").at(1).get<double>() > 0.0) weave = &m;
    }
    ASSERT_NE(weave, nullptr) << speed;
    const double sigma = weave->at("eigenvalue").at(0).get<double>();
    const double period = 2.0 * std::acos(-1.0) / weave->at("eigenvalue").at(1).get<double>();
    EXPECT_LT(sigma, 0.0);
    EXPECT_EQ(weave->at("shown"), "decaying oscillation");
    EXPECT_EQ(weave->at("periods").get<double>(), periods) << speed;
    EXPECT_EQ(std::min(std::floor(std::log(10.0) / -sigma / period), 5.0), periods) << speed;
    EXPECT_EQ(weave->at("loop").at(0).get<double>(), 0.0);
    EXPECT_NEAR(weave->at("loop").at(1).get<double>(), periods * period, 1e-12 * period);
  }
}

}  // namespace
}  // namespace chasles
