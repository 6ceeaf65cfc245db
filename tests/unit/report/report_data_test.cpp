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

/// Index of column `name` of a result (a failure when it has none).
size_t ColumnIndex(const std::vector<std::string>& columns, const std::string& name) {
  const auto it = std::find(columns.begin(), columns.end(), name);
  EXPECT_NE(it, columns.end()) << "no column " << name;
  return it == columns.end() ? 0 : static_cast<size_t>(it - columns.begin());
}

/// A tumbling, falling box whose centre of mass is off its frame's origin: a single part at
/// p_BoBcm_B = (0.3, 0.1, 0.2) m. `columns`: its output columns.
Scene TumblingBox(const std::string& columns) {
  return LoadSceneText(R"(
bodies:
  - name: b
    parts: [{shape: box, size: [0.4 m, 0.2 m, 0.1 m], mass: 1 kg, position: [0.3 m, 0.1 m, 0.2 m]}]
    initial: {velocity: [1 m/s, 2 m/s, 3 m/s], angular_velocity: [1 rad/s, 5 rad/s, 0.2 rad/s]}
gravity: standard
output: {columns: [)" + columns +
                           R"(]}
simulation: {until: 1 s, tolerance: 1e-12, output_interval: 0.05 s}
)",
                       "tumbling");
}

/// The data's poses of body k: per sample [ox, oy, oz] and [qw, qx, qy, qz].
std::pair<std::vector<double>, std::vector<double>> DataPoses(const nlohmann::json& j, size_t k) {
  const nlohmann::json& p = j["poses"][k];
  EXPECT_EQ(p["body"].get<size_t>(), k);
  return {DecodeF8(p["origin"]), DecodeF8(p["quaternion"])};
}

// The poses block is the state's: at every sample the origin is Bo = Bcm − R_WB p_BoBcm_B from
// the run's centre of mass and quaternion (the state's own values, as the position and
// quaternion columns give them), for a body turning about all three axes with its centre of
// mass 0.37 m off its origin; the quaternion is the state's. No origin column is asked for.
TEST(ReportData, PosesAreTheStatesOrigin) {
  const Scene scene = TumblingBox("position, quaternion");
  const Vec3 p_BoBcm_B(0.3, 0.1, 0.2);
  ASSERT_NEAR((scene.bodies[0].mass_properties.p_BoBcm_B() - p_BoBcm_B).norm(), 0.0, 1e-15);
  StudyOptions options;
  options.record_row_poses = true;
  const StudyResult r = RunStudy(MakeStudyDefinition(scene, options));
  ASSERT_EQ(r.row_poses.size(), r.rows.size());
  const nlohmann::json j = SimulationReportData(scene, r);
  EXPECT_EQ(j["format"], "chasles-report 2");
  EXPECT_EQ(j["poses_from"], "states");
  ASSERT_EQ(j["poses"].size(), 1u);
  const auto [origin, quaternion] = DataPoses(j, 0);
  const size_t n = r.rows.size();
  ASSERT_EQ(n, 21u);
  ASSERT_EQ(origin.size(), 3 * n);
  ASSERT_EQ(quaternion.size(), 4 * n);
  const auto col = [&](const char* name) { return ColumnIndex(r.columns, name); };
  // A run that turns: the last quaternion is far from the first.
  EXPECT_LT(std::abs(r.rows[n - 1][col("b_qw")]), 0.95);
  constexpr double kTolerance = 1e-12;  // positions of a few metres, to round-off
  for (size_t i = 0; i < n; ++i) {
    const std::vector<double>& row = r.rows[i];
    const Quat q_WB(row[col("b_qw")], row[col("b_qx")], row[col("b_qy")], row[col("b_qz")]);
    const Vec3 p_WBcm(row[col("b_x")], row[col("b_y")], row[col("b_z")]);
    const Vec3 p_WBo = p_WBcm - q_WB.toRotationMatrix() * p_BoBcm_B;
    for (int a = 0; a < 3; ++a) {
      EXPECT_NEAR(origin[3 * i + static_cast<size_t>(a)], p_WBo[a], kTolerance) << "row " << i;
    }
    const double q[4] = {q_WB.w(), q_WB.x(), q_WB.y(), q_WB.z()};
    for (size_t a = 0; a < 4; ++a) {
      EXPECT_NEAR(quaternion[4 * i + a], q[a], kTolerance) << "row " << i;
    }
  }
  // Every column but t is for plotting (f4); nothing is exact by its name.
  for (const auto& c : j["columns"]) EXPECT_EQ(c["type"], c["name"] == "t" ? "f8" : "f4");
}

// The poses do not depend on the columns: a run asked for the energy alone gives the page the
// same poses as the origin and quaternion columns of the same run, and renaming every column
// changes no pose. A run that recorded no poses is refused.
TEST(ReportData, PosesWhateverTheColumns) {
  StudyOptions options;
  options.record_row_poses = true;
  const Scene with_poses = TumblingBox("origin, quaternion");
  const Scene energy = TumblingBox("energy");
  const StudyResult a = RunStudy(MakeStudyDefinition(with_poses, options));
  StudyResult b = RunStudy(MakeStudyDefinition(energy, options));
  for (const std::string& c : b.columns) {
    EXPECT_EQ(c.find("b_"), std::string::npos) << c;
  }
  ASSERT_EQ(a.rows.size(), b.rows.size());
  const nlohmann::json j = SimulationReportData(energy, b);
  const auto [origin, quaternion] = DataPoses(j, 0);
  const auto col = [&](const char* name) { return ColumnIndex(a.columns, name); };
  constexpr double kTolerance = 1e-15;  // the same run: the same doubles
  for (size_t i = 0; i < a.rows.size(); ++i) {
    const std::vector<double>& row = a.rows[i];
    EXPECT_NEAR(origin[3 * i], row[col("b_ox")], kTolerance);
    EXPECT_NEAR(origin[3 * i + 1], row[col("b_oy")], kTolerance);
    EXPECT_NEAR(origin[3 * i + 2], row[col("b_oz")], kTolerance);
    EXPECT_NEAR(quaternion[4 * i], row[col("b_qw")], kTolerance);
    EXPECT_NEAR(quaternion[4 * i + 1], row[col("b_qx")], kTolerance);
    EXPECT_NEAR(quaternion[4 * i + 2], row[col("b_qy")], kTolerance);
    EXPECT_NEAR(quaternion[4 * i + 3], row[col("b_qz")], kTolerance);
  }
  // The run with the pose columns under other names: the same poses, to the bit.
  StudyResult renamed = a;
  const nlohmann::json before = SimulationReportData(with_poses, a)["poses"];
  for (std::string& c : renamed.columns) {
    if (c != "t") c = "E";  // a column of the scene's run, so that its unit is found
  }
  EXPECT_EQ(SimulationReportData(with_poses, renamed)["poses"], before);

  const StudyResult plain = RunStudy(MakeStudyDefinition(with_poses));
  EXPECT_TRUE(plain.row_poses.empty());
  try {
    SimulationReportData(with_poses, plain);
    ADD_FAILURE() << "a run without poses was drawn";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("the run recorded 0 of 21 rows for 1 bodies"),
              std::string::npos)
        << e.what();
  }
}

// `chasles report` of a finished run's table (PosesFromColumns): the origin derived from the
// centre of mass and orientation, Bo = Bcm − R_WB p_BoBcm_B, equals the run's own origin and
// quaternion columns, here with the centre of mass off the body origin (a part at (0.3, 0.1,
// 0.2) m) and a spinning, tumbling body (3-D), and a planar body turning about z (from θ); a
// table with the origin columns gives them as they are; a table without orientation is refused.
TEST(ReportData, PosesFromColumnsOfAFinishedRun) {
  for (const bool planar : {false, true}) {
    const Scene scene = planar ? LoadSceneText(R"(
planar: true
bodies:
  - name: b
    parts: [{shape: sphere, radius: 0.1 m, mass: 1 kg, position: [0.3 m, 0.1 m]}]
    initial: {velocity: [1 m/s, 2 m/s], omega: 3 rad/s}
gravity: standard
output: {columns: [planar, origin, quaternion]}
simulation: {until: 1 s, tolerance: 1e-12, output_interval: 0.05 s}
)",
                                               "poses")
                               : TumblingBox("position, origin, quaternion");
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
    const ColumnPoses derived = PosesFromColumns(scene, r);
    EXPECT_EQ(derived.derived, std::vector<std::string>{"b"}) << planar;
    const ColumnPoses read = PosesFromColumns(scene, full);
    EXPECT_TRUE(read.derived.empty());
    ASSERT_EQ(derived.rows.size(), full.rows.size());
    ASSERT_EQ(read.rows.size(), full.rows.size());
    const auto col = [&](const char* name) { return ColumnIndex(full.columns, name); };
    for (size_t i = 0; i < full.rows.size(); ++i) {
      const std::vector<double>& row = full.rows[i];
      const double want[7] = {row[col("b_ox")], row[col("b_oy")], row[col("b_oz")],
                              row[col("b_qw")], row[col("b_qx")], row[col("b_qy")],
                              row[col("b_qz")]};
      for (const ColumnPoses* poses : {&derived, &read}) {
        ASSERT_EQ(poses->rows[i].size(), 1u);
        const StudyBodyPose& p = poses->rows[i][0];
        const double got[7] = {p.p_WBo.x(), p.p_WBo.y(), p.p_WBo.z(), p.q_WB.w(),
                               p.q_WB.x(),  p.q_WB.y(),  p.q_WB.z()};
        for (size_t k = 0; k < 7; ++k) {
          EXPECT_NEAR(got[k], want[k], 1e-12) << k << " row " << i << " planar " << planar;
        }
      }
    }
    StudyResult with_poses = r;
    with_poses.row_poses = derived.rows;
    EXPECT_EQ(SimulationReportData(scene, with_poses, PoseSource::kColumns)["poses_from"],
              "columns");

    // Without any orientation the pose cannot be made.
    StudyResult bare = r;
    bare.columns = {"t", "E"};
    for (auto& row : bare.rows) row.resize(2);
    try {
      PosesFromColumns(scene, bare);
      ADD_FAILURE() << "a table without poses was read";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("the report needs the pose of body 'b'"),
                std::string::npos)
          << e.what();
    }
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
