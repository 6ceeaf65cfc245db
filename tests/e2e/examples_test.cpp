// End-to-end: the chapter's examples as scene files, run through the chasles program, against
// values derived from the physics (formulas written here with their source).

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "cli_runner.h"
#include "test_support.h"

namespace chasles::test {
namespace {

// Results that are exact up to the round-off of a few dozen operations and of unit factors.
constexpr double kTight = 1e-12;

const nlohmann::json& Point(const nlohmann::json& body, const std::string& name) {
  for (const auto& p : body.at("points")) {
    if (p.at("name") == name) return p;
  }
  throw std::runtime_error("no point " + name);
}

TEST(Examples, EveryExampleRuns) {
  int count = 0;
  for (const auto& entry : std::filesystem::directory_iterator(SourcePath("examples"))) {
    if (entry.path().extension() != ".yaml") continue;
    if (!Sampled(count++)) continue;
    for (const char* format : {"text", "json"}) {
      const CliResult r = RunCli("mass '" + entry.path().string() + "' --format " + format);
      EXPECT_EQ(r.exit_code, 0) << entry.path() << ": " << r.err;
      EXPECT_FALSE(r.out.empty()) << entry.path();
      EXPECT_EQ(r.out.find("nan"), std::string::npos) << entry.path();
    }
  }
  EXPECT_GE(count, 8);
}

// Every example with a `simulation:` key also runs through `chasles simulate`, with an
// all-pass certificate under --strict (a failed check would exit 3).
TEST(Examples, EveryDynamicsExampleSimulates) {
  const auto out = std::filesystem::temp_directory_path() /
                   ("chasles_e2e_examples_" + std::to_string(::getpid()));
  int count = 0;
  for (const auto& entry : std::filesystem::directory_iterator(SourcePath("examples"))) {
    if (entry.path().extension() != ".yaml") continue;
    std::ifstream in(entry.path());
    std::stringstream text;
    text << in.rdbuf();
    if (text.str().find("\nsimulation:") == std::string::npos) continue;
    if (!Sampled(count++)) continue;
    for (const char* format : {"text", "json"}) {
      const CliResult r = RunCli("simulate '" + entry.path().string() + "' --format " + format +
                                 " --out '" + out.string() + "' --strict");
      EXPECT_EQ(r.exit_code, 0) << entry.path() << ": " << r.err << r.out;
      EXPECT_FALSE(r.out.empty()) << entry.path();
      EXPECT_EQ(r.out.find("nan"), std::string::npos) << entry.path();
      if (std::string(format) == "json" && r.exit_code != 2) {
        const nlohmann::json j = nlohmann::json::parse(r.out);
        EXPECT_TRUE(j.at("checks").at("passed").get<bool>())
            << entry.path() << ": " << j.at("checks").dump(2);
      }
    }
    const auto csv = out / (entry.path().stem().string() + ".csv");
    EXPECT_TRUE(std::filesystem::exists(csv)) << csv;
  }
  EXPECT_GE(count, 8);
  std::filesystem::remove_all(out);
}

// Example 8.1: z/h = (1 - c q^2) / (2 (1 - c q)), q = h1/h, c = 1 - rho_Al/rho_Pb.
// Every example without a `simulation:` key passes the certificate of `chasles solve` (its
// initial state's accelerations, reactions and contact forces) under --strict.
TEST(Examples, EveryStaticExampleSolvesWithAllChecksPassing) {
  int count = 0;
  for (const auto& entry : std::filesystem::directory_iterator(SourcePath("examples"))) {
    if (entry.path().extension() != ".yaml") continue;
    std::ifstream in(entry.path());
    std::stringstream text;
    text << in.rdbuf();
    if (text.str().find("\nsimulation:") != std::string::npos) continue;
    ++count;
    const CliResult r = RunCli("solve '" + entry.path().string() + "' --format json --strict");
    EXPECT_EQ(r.exit_code, 0) << entry.path() << ": " << r.err << r.out;
    if (r.exit_code == 0 || r.exit_code == 3) {
      const nlohmann::json j = nlohmann::json::parse(r.out);
      EXPECT_TRUE(j.at("checks").at("passed").get<bool>())
          << entry.path() << ": " << j.at("checks").dump(2);
    }
  }
  EXPECT_GE(count, 5);
}

TEST(Examples, Example81CentreOfMassForSeveralHeights) {
  const double c = 1.0 - 2712.0 / 11340.0;
  const double h = 0.20;
  const double R = 0.05;
  for (double q : {0.1, 0.25, 0.5, 0.75, 0.9}) {
    const auto j =
        MassJson("examples/example-8.1-cylinder.yaml", "--set ratio=" + std::to_string(q));
    const auto& body = j.at("bodies").at(0);
    const double z_over_h = ToVec(body.at("center_of_mass")).z() / h;
    EXPECT_TRUE(Near(z_over_h, (1 - c * q * q) / (2 * (1 - c * q)), kTight)) << "h1/h = " << q;
    // Mass: pi R^2 (rho_Al h1 + rho_Pb (h - h1)).
    EXPECT_TRUE(Near(body.at("mass").get<double>(),
                     M_PI * R * R * (2712.0 * q * h + 11340.0 * (1 - q) * h), kTight));
  }
}

// Example 8.2: about O, [I] = m l^2 [[4, 0, 0], [0, 11/3, -1/2], [0, -1/2, 1/3]] (m = l = 1).
TEST(Examples, Example82TwoRodsInertiaAboutO) {
  const auto j = MassJson("examples/example-8.2-two-rods.yaml");
  Mat3 expected;
  expected << 4, 0, 0, 0, 11.0 / 3, -0.5, 0, -0.5, 1.0 / 3;
  EXPECT_TRUE(MatNear(ToMat(Point(j.at("bodies").at(0), "O").at("inertia")), expected, kTight));
  EXPECT_TRUE(Near(j.at("bodies").at(0).at("mass").get<double>(), 3.0, kTight));
}

// Example 8.2 about O: [I_O] = (m l^2 / 6) [[24, 0, 0], [0, 22, -3], [0, -3, 2]] (the chapter's
// tensor). x is a principal axis with I = 4 m l^2; the yz block has trace 4 and determinant
// (22 * 2 - 3 * 3) / 36 = 35/36 (m l^2)^2, so its eigenvalues are 2 -+ sqrt(4 - 35/36)
// = 2 -+ sqrt(109)/6 m l^2. The eigenvector of lambda in the yz block solves
// (11/3 - lambda) y - z/2 = 0: (0, 1/2, 11/3 - lambda) up to length and sign. Radii of gyration
// k = sqrt(I / M) with M = 3 m (eq. 8.19); about the body axes through O sqrt(diag / M).
TEST(Examples, Example82PrincipalMomentsAxesAndRadiiAboutO) {
  const double m = 1.0, l = 1.0, M = 3 * m, ml2 = m * l * l;
  const double r = std::sqrt(109.0) / 6;
  const Vec3 moments((2 - r) * ml2, (2 + r) * ml2, 4 * ml2);
  for (const char* about : {"", " --about '[0, 0, 0]'"}) {
    const auto j = MassJson("examples/example-8.2-two-rods.yaml", about);
    const auto& O = Point(j.at("bodies").at(0), about[0] ? "'[0, 0, 0]'" : "O");
    EXPECT_TRUE(MatNear(ToVec(O.at("principal_moments")), moments, kTight)) << about;
    for (int k = 0; k < 3; ++k) {
      Vec3 e = k == 2 ? Vec3(1, 0, 0) : Vec3(0, 0.5, 11.0 / 3 - moments[k] / ml2);
      e.normalize();
      const Vec3 got = ToVec(O.at("principal_axes").at(k));
      // An axis is a direction: compare up to sign.
      EXPECT_NEAR(std::abs(got.dot(e)), 1.0, kTight) << k;
      EXPECT_NEAR(got.norm(), 1.0, kTight) << k;
    }
    const auto& k = O.at("radii_of_gyration");
    EXPECT_TRUE(MatNear(
        ToVec(k.at("principal_axes")),
        Vec3(std::sqrt(moments[0] / M), std::sqrt(moments[1] / M), std::sqrt(moments[2] / M)),
        kTight));
    EXPECT_TRUE(
        MatNear(ToVec(k.at("body_axes")),
                Vec3(std::sqrt(4 * ml2 / M), std::sqrt(11.0 / 3 * ml2 / M), std::sqrt(ml2 / 3 / M)),
                kTight));
  }
  // The text report gives them too, under the point's inertia.
  const CliResult t = RunCli("mass " + Quote(SourcePath("examples/example-8.2-two-rods.yaml")));
  ASSERT_EQ(t.exit_code, 0) << t.err;
  const std::string after_O = t.out.substr(t.out.find("Inertia about point O"));
  char line[128];
  std::snprintf(line, sizeof line, "    Principal moments   %.7g, %.7g, %.7g kg*m^2", moments[0],
                moments[1], moments[2]);
  EXPECT_THAT(after_O, ::testing::HasSubstr(line));
  EXPECT_THAT(after_O, ::testing::HasSubstr("about the principal axes through the point"));
}

// The plate with a drilled hole: the blank box a x b x t has volume abt and surface area
// 2 (ab + bt + ta); the hole, a cylinder of radius r through the thickness t, volume πr²t and
// surface 2πr² + 2πrt. The body's volume is abt - πr²t; its surface area is not given (its
// parts cut each other's faces), with a note, and null in JSON.
TEST(Examples, PlateWithHoleVolumeAndSurfaceArea) {
  const double a = 0.2, b = 0.12, t = 0.01, r = 0.025;
  const auto j = MassJson("examples/plate-with-hole.yaml");
  const auto& body = j.at("bodies").at(0);
  EXPECT_TRUE(Near(body.at("volume").get<double>(), a * b * t - M_PI * r * r * t, kTight));
  EXPECT_TRUE(body.at("surface_area").is_null());
  EXPECT_THAT(body.at("surface_area_note").get<std::string>(),
              ::testing::HasSubstr("parts may share or cut faces"));
  const auto& blank = body.at("parts").at(0);
  const auto& hole = body.at("parts").at(1);
  EXPECT_TRUE(Near(blank.at("volume").get<double>(), a * b * t, kTight));
  EXPECT_TRUE(Near(blank.at("surface_area").get<double>(), 2 * (a * b + b * t + t * a), kTight));
  EXPECT_TRUE(Near(hole.at("volume").get<double>(), M_PI * r * r * t, kTight));
  EXPECT_TRUE(
      Near(hole.at("surface_area").get<double>(), 2 * M_PI * r * r + 2 * M_PI * r * t, kTight));
  EXPECT_EQ(j.at("units").at("volume"), "m^3");
  // In millimetres: volume in mm^3 (1e9 per m^3).
  const CliResult mm_run = RunCli("mass " + Quote(SourcePath("examples/plate-with-hole.yaml")) +
                                  " --units mm,kg --format json");
  ASSERT_EQ(mm_run.exit_code, 0) << mm_run.err;
  const auto mm = nlohmann::json::parse(mm_run.out);
  EXPECT_TRUE(Near(mm.at("bodies").at(0).at("volume").get<double>(),
                   (a * b * t - M_PI * r * r * t) * 1e9, kTight));
  const CliResult text = RunCli("mass " + Quote(SourcePath("examples/plate-with-hole.yaml")));
  ASSERT_EQ(text.exit_code, 0) << text.err;
  EXPECT_THAT(text.out,
              ::testing::HasSubstr("Surface area        n/a: parts may share or cut faces"));
}

// A body of one part has its part's surface area: a sphere of radius R, 4πR², volume 4πR³/3.
// A custom part has no geometry: volume and area null, with notes.
TEST(Examples, OnePartBodySurfaceAreaAndCustomPartHasNone) {
  const auto dir = OutDir("examples_measures");
  const auto path = dir / "measures.yaml";
  std::ofstream(path) << "chasles: 1\n"
                         "bodies:\n"
                         "  - name: ball\n"
                         "    parts: [{shape: sphere, radius: 3 cm, mass: 1 kg}]\n"
                         "  - name: lump\n"
                         "    parts: [{shape: custom, mass: 1 kg, inertia: {Ixx: 1, Iyy: 1, "
                         "Izz: 1}}]\n";
  const CliResult r = RunCli("mass " + Quote(path.string()) + " --format json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  const double R = 0.03;
  const auto& ball = j.at("bodies").at(0);
  EXPECT_TRUE(Near(ball.at("surface_area").get<double>(), 4 * M_PI * R * R, kTight));
  EXPECT_TRUE(Near(ball.at("volume").get<double>(), 4 * M_PI * R * R * R / 3, kTight));
  const auto& lump = j.at("bodies").at(1);
  EXPECT_TRUE(lump.at("volume").is_null());
  EXPECT_TRUE(lump.at("surface_area").is_null());
  EXPECT_THAT(lump.at("volume_note").get<std::string>(), ::testing::HasSubstr("no geometry"));
  EXPECT_TRUE(lump.at("parts").at(0).at("volume").is_null());
}

// Section 8.3: centre of mass 41/25 r along the axle; about O diag(5, 1/2, 5) m r^2; about the
// centre of mass diag(319/400, 1/2, 319/400) m r^2 (m = 2 kg, r = 0.1 m).
TEST(Examples, Section83DiskAndAxle) {
  const double m = 2, r = 0.1, mr2 = m * r * r;
  const auto j = MassJson("examples/section-8.3-disk-axle.yaml");
  const auto& body = j.at("bodies").at(0);
  EXPECT_TRUE(Near(body.at("mass").get<double>(), 25.0 / 16 * m, kTight));
  EXPECT_TRUE(MatNear(ToVec(body.at("center_of_mass")), Vec3(0, 41.0 / 25 * r, 0), kTight));
  EXPECT_TRUE(MatNear(ToMat(Point(body, "O").at("inertia")),
                      Mat3(Vec3(5 * mr2, 0.5 * mr2, 5 * mr2).asDiagonal()), kTight));
  EXPECT_TRUE(MatNear(ToMat(body.at("inertia_about_center_of_mass")),
                      Mat3(Vec3(319.0 / 400 * mr2, 0.5 * mr2, 319.0 / 400 * mr2).asDiagonal()),
                      kTight));
}

// The demonstration (no command) is the same scene and says so.
TEST(Examples, NoArgumentsRunsTheDemonstration) {
  const CliResult r = RunCli("");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.err, ::testing::HasSubstr("built-in demonstration"));
  EXPECT_THAT(r.out, ::testing::HasSubstr("Disk and axle"));
  EXPECT_THAT(r.out, ::testing::HasSubstr("Principal moments"));
}

// Section 8.5: a cube's inertia about its centre is m a^2 / 6 times the identity, and about a
// corner (eq. 8.29) m a^2 [[2/3, -1/4, -1/4], ...]. The scene is in inches and pounds.
TEST(Examples, Section85Cube) {
  const double a = 6 * 0.0254, m = 10 * 0.45359237;
  const auto j = MassJson("examples/section-8.5-cube.yaml");
  const auto& body = j.at("bodies").at(0);
  EXPECT_TRUE(MatNear(ToMat(body.at("inertia_about_center_of_mass")),
                      Mat3(m * a * a / 6 * Mat3::Identity()), kTight));
  Mat3 corner;
  corner << 2.0 / 3, -0.25, -0.25, -0.25, 2.0 / 3, -0.25, -0.25, -0.25, 2.0 / 3;
  EXPECT_TRUE(
      MatNear(ToMat(Point(body, "corner").at("inertia")), Mat3(m * a * a * corner), kTight));
  EXPECT_TRUE(MatNear(ToMat(body.at("principal_axes")), Mat3::Identity(), 0, 1.0));
  // The same report in the scene's own units: m in lb, a in in.
  const CliResult r =
      RunCli("mass '" + SourcePath("examples/section-8.5-cube.yaml") + "' --format json");
  const auto us = nlohmann::json::parse(r.out);
  EXPECT_EQ(us.at("units").at("inertia"), "lb*in^2");
  EXPECT_TRUE(
      Near(us.at("bodies").at(0).at("inertia_about_center_of_mass").at(0).at(0).get<double>(),
           10.0 * 36 / 6, kTight));
}

// T section: centre of mass 37/14 l above the stem's base, Izz about it 631/294 m l^2.
TEST(Examples, TSection) {
  const double m = 3, l = 0.04;
  const auto j = MassJson("examples/problem-8.1-t-section.yaml");
  const auto& body = j.at("bodies").at(0);
  EXPECT_TRUE(Near(body.at("mass").get<double>(), m, kTight));
  EXPECT_TRUE(MatNear(ToVec(body.at("center_of_mass")), Vec3(0, 37.0 / 14 * l, 0), kTight));
  EXPECT_TRUE(
      Near(ToMat(body.at("inertia_about_center_of_mass"))(2, 2), 631.0 / 294 * m * l * l, kTight));
  // A plate is flat: Izz = Ixx + Iyy (perpendicular-axis theorem).
  const Mat3 I = ToMat(body.at("inertia_about_center_of_mass"));
  EXPECT_TRUE(Near(I(2, 2), I(0, 0) + I(1, 1), kTight));
}

// Bent rod: centre of mass (5/6, 1/2, 1/6) h; about A Iyy = 8/9 m h^2, Ixy = -1/2 m h^2; about
// the centre of mass Iyy = 1/6 m h^2, Ixy = -1/12 m h^2.
TEST(Examples, BentRod) {
  const double m = 0.6, h = 0.25, mh2 = m * h * h;
  const auto j = MassJson("examples/problem-8.7-bent-rod.yaml");
  const auto& body = j.at("bodies").at(0);
  EXPECT_TRUE(MatNear(ToVec(body.at("center_of_mass")), Vec3(5.0 / 6 * h, 0.5 * h, h / 6), kTight));
  const Mat3 IA = ToMat(Point(body, "A").at("inertia"));
  EXPECT_TRUE(Near(IA(1, 1), 8.0 / 9 * mh2, kTight));
  EXPECT_TRUE(Near(IA(0, 1), -0.5 * mh2, kTight));
  const Mat3 Ic = ToMat(body.at("inertia_about_center_of_mass"));
  EXPECT_TRUE(Near(Ic(1, 1), mh2 / 6, kTight));
  EXPECT_TRUE(Near(Ic(0, 1), -mh2 / 12, kTight));
}

// Plate with a hole: mass rho t (a b - pi r^2); centre of mass at -d pi r^2 / (a b - pi r^2).
TEST(Examples, PlateWithHole) {
  const double rho = 7850, a = 0.2, b = 0.12, t = 0.01, r = 0.025, d = 0.05;
  const double area = a * b - M_PI * r * r;
  const auto j = MassJson("examples/plate-with-hole.yaml");
  const auto& body = j.at("bodies").at(0);
  EXPECT_TRUE(Near(body.at("mass").get<double>(), rho * t * area, kTight));
  EXPECT_TRUE(
      MatNear(ToVec(body.at("center_of_mass")), Vec3(-d * M_PI * r * r / area, 0, 0), kTight, a));
  // Izz about the centre of mass: box minus hole, each shifted to it (eq. 8.29).
  const double m_box = rho * a * b * t, m_hole = rho * M_PI * r * r * t;
  const double xc = -d * m_hole / (m_box - m_hole);
  const double Izz = m_box * (a * a + b * b) / 12 + m_box * xc * xc -
                     (m_hole * r * r / 2 + m_hole * (d - xc) * (d - xc));
  EXPECT_TRUE(Near(ToMat(body.at("inertia_about_center_of_mass"))(2, 2), Izz, kTight));
  EXPECT_EQ(body.at("parts").at(1).at("subtractive"), true);
}

// Graded cylinder: rho = rho0 (1 + alpha z/h); centre of mass at alpha h / 12; Izz = m R^2/2;
// Ixx about the centre of mass m (R^2/4 + h^2/12 - alpha^2 h^2/144). The density field is
// integrated numerically to 1e-10.
TEST(Examples, GradedCylinderDensityField) {
  const double R = 0.04, h = 0.3, rho0 = 4000, alpha = 0.8;
  const double m = rho0 * M_PI * R * R * h;
  const auto j = MassJson("examples/graded-cylinder.yaml");
  const auto& body = j.at("bodies").at(0);
  EXPECT_TRUE(Near(body.at("mass").get<double>(), m, 1e-10));
  EXPECT_TRUE(MatNear(ToVec(body.at("center_of_mass")), Vec3(0, 0, alpha * h / 12), 1e-10, h));
  const Mat3 I = ToMat(body.at("inertia_about_center_of_mass"));
  EXPECT_TRUE(Near(I(2, 2), m * R * R / 2, 1e-10));
  EXPECT_TRUE(Near(I(0, 0), m * (R * R / 4 + h * h / 12 - alpha * alpha * h * h / 144), 1e-10));
}

TEST(Cli, HelpExplainsUsageWithExamples) {
  const CliResult top = RunCli("--help");
  EXPECT_EQ(top.exit_code, 0);
  EXPECT_THAT(top.out, ::testing::HasSubstr("mass"));
  EXPECT_THAT(top.out, ::testing::HasSubstr("Examples:"));
  const CliResult mass = RunCli("mass --help");
  EXPECT_EQ(mass.exit_code, 0);
  EXPECT_THAT(mass.out, ::testing::HasSubstr("--units"));
  EXPECT_THAT(mass.out, ::testing::HasSubstr("chasles mass examples/"));
}

TEST(Cli, AboutAndFrameOptions) {
  // Cube about a corner given on the command line equals the scene's named corner.
  const auto j = MassJson("examples/section-8.5-cube.yaml", "--about '[0, 0, 0]'");
  const auto& pts = j.at("bodies").at(0).at("points");
  ASSERT_EQ(pts.size(), 2u);
  EXPECT_TRUE(MatNear(ToMat(pts.at(1).at("inertia")), ToMat(pts.at(0).at("inertia")), kTight));
  // Bent rod in a frame turned 90 degrees about z: Ixx' = Iyy, Iyy' = Ixx, Ixy' = -Ixy.
  const auto k = MassJson("examples/problem-8.7-bent-rod.yaml",
                          "--frame '{rotation: {axis: [0, 0, 1], angle: 90 deg}}'");
  const Mat3 I = ToMat(k.at("bodies").at(0).at("inertia_about_center_of_mass"));
  const Mat3 F = ToMat(k.at("bodies").at(0).at("frame").at("inertia_about_center_of_mass"));
  EXPECT_TRUE(Near(F(0, 0), I(1, 1), kTight));
  EXPECT_TRUE(Near(F(1, 1), I(0, 0), kTight));
  EXPECT_TRUE(Near(F(0, 1), -I(0, 1), kTight));
}

TEST(Cli, OutputFileIsWritten) {
  const auto path = std::filesystem::temp_directory_path() / "chasles_e2e_report.json";
  std::filesystem::remove(path);
  const CliResult r = RunCli("mass '" + SourcePath("examples/section-8.5-cube.yaml") +
                             "' --format json -o '" + path.string() + "'");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(r.out.empty());
  std::ifstream in(path);
  EXPECT_TRUE(nlohmann::json::parse(in).is_object());
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace chasles::test
