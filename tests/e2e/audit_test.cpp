// chasles audit as a user runs it: exit codes, the JSON, --fix and its round trip, hostile
// files, the MJCF and SDF versions of the shared robots, and Debian's MuJoCo on the files
// before and after the fix.

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli_runner.h"
#include "test_paths.h"
#include "test_support.h"

namespace chasles::test {
namespace {

namespace fs = std::filesystem;

ScratchFolders& Scratch() {
  static ScratchFolders folders;
  return folders;
}

fs::path ScratchDir(const std::string& name) {
  const fs::path dir =
      fs::temp_directory_path() / ("chasles-audit-e2e-" + std::to_string(::getpid())) / name;
  fs::create_directories(dir);
  Scratch().Add(dir.parent_path());
  return dir;
}

std::string Shared() {
  const fs::path p = fs::path(chasles::test::SourceDir()) / ".." / "shared" / "robots";
  return fs::is_directory(p) ? fs::canonical(p).string() : "";
}

std::string ReadText(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

/// --package options for the SDF versions' model:// URIs.
std::string Packages(const std::string& shared) {
  return " --package example-robot-data=" + Quote(shared + "/example-robot-data") +
         " --package ur_description=" + Quote(shared + "/compas_fab/robot_library/ur_description");
}

TEST(AuditCli, HostileFilesExitTwoWithFileAndLine) {
  const std::map<std::string, std::string> expected = {
      {"unclosed.urdf", "unclosed.urdf:5: malformed XML"},
      {"entities.urdf", "entities.urdf:3: an entity declaration"},
      {"escape.urdf",
       "escape.urdf:6: mesh URI 'package://escape/../../../../../etc/passwd' "
       "climbs out of its package"},
      {"device.urdf",
       "device.urdf:6: mesh URI 'file:///dev/zero' cannot be read: it points "
       "into /dev"},
      {"cycle.urdf", "cycle.urdf:8: the joints form a cycle"},
      {"cycle.sdf", "cycle.sdf:4: the poses of frame 'f1' form a cycle"},
      {"nan.urdf", "nan.urdf:6: <inertia ixx>: NaN is not a finite number"},
      {"huge.urdf", "huge.urdf:5: <origin xyz>: 1e308 0 0 is not a finite number"},
      {"huge-count.urdf", "huge-count.dae:4: <float_array count=\"1000000000\"> holds 9 numbers"},
      {"deep.xml", "deep.xml:3: elements nested deeper than 200 levels"},
      {"include.xml", "include.xml:2: <include> is not read"},
      {"unknown-link.urdf", "unknown-link.urdf:6: joint 'j' child: no link named 'nowhere'"},
  };
  for (const auto& [file, message] : expected) {
    const CliResult r = RunCli("audit " + Quote(SourcePath("tests/bad_input/robots/" + file)));
    EXPECT_EQ(r.exit_code, 2) << file << ": " << r.err;
    EXPECT_NE(r.err.find(message), std::string::npos) << file << ": " << r.err;
  }
}

TEST(AuditCli, PublishedDefectsJsonFixAndRoundTrip) {
  const std::string shared = Shared();
  if (shared.empty())
    GTEST_SKIP() << "../shared/robots is absent: the published robots are not audited";
  const std::string abb =
      shared + "/compas_fab/robot_library/abb_irb4600_40_255/urdf/robot_description.urdf";
  const std::string ur5 = shared + "/example-robot-data/robots/ur_description/urdf/ur5_robot.urdf";
  const fs::path out = ScratchDir("fixed");
  const CliResult r = RunCli("audit " + Quote(abb) + " " + Quote(ur5) +
                             " --format json --fix --out " + Quote(out.string()));
  ASSERT_EQ(r.exit_code, 3) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  ASSERT_EQ(j["files"].size(), 2u);
  const nlohmann::json& abb_links = j["files"][0]["links"];
  EXPECT_EQ(j["files"][0]["format"], "URDF");
  EXPECT_EQ(abb_links[0]["name"], "base_link");
  EXPECT_EQ(abb_links[0]["findings"][0]["code"], "not_positive_definite");
  EXPECT_EQ(abb_links[0]["findings"][0]["severity"], "error");
  EXPECT_TRUE(abb_links[0]["findings"][0]["fix"].contains("inertia"));
  EXPECT_EQ(abb_links[0]["given"]["mass"], 120.0);
  for (const nlohmann::json& link : j["files"][1]["links"]) {
    if (link["name"] != "wrist_1_link") continue;
    EXPECT_EQ(link["computed"]["source"], "visual");
    EXPECT_EQ(link["computed"]["method"], "exact closed mesh");
    bool radius = false;
    for (const nlohmann::json& f : link["findings"])
      radius = radius || f["code"] == "radius_of_gyration";
    EXPECT_TRUE(radius);
  }
  EXPECT_TRUE(j["robot"].contains("center_of_mass"));
  ASSERT_EQ(j["fixed"].size(), 2u);
  // The fixed files: only inertial numbers and comments changed, and no error left.
  const std::string fixed_ur5 = ReadText(out / "ur5_robot.urdf");
  EXPECT_NE(fixed_ur5.find("<!-- chasles audit: "), std::string::npos);
  const CliResult again = RunCli("audit " + Quote((out / "robot_description.urdf").string()) + " " +
                                 Quote((out / "ur5_robot.urdf").string()) + Packages(shared));
  EXPECT_EQ(again.exit_code, 0) << again.out << again.err;
  // Never over the input.
  const CliResult over =
      RunCli("audit " + Quote(ur5) + " --fix --out " + Quote(fs::path(ur5).parent_path().string()));
  EXPECT_EQ(over.exit_code, 2);
  EXPECT_NE(over.err.find("would be written over the input"), std::string::npos) << over.err;
}

TEST(AuditCli, BrowserReportDrawsLinksAndListsFindings) {
  const std::string shared = Shared();
  if (shared.empty()) GTEST_SKIP() << "../shared/robots is absent";
  const fs::path html = ScratchDir("html") / "ur5.html";
  const std::string ur5 = shared + "/example-robot-data/robots/ur_description/urdf/ur5_robot.urdf";
  const CliResult r = RunCli("audit " + Quote(ur5) + " --html " + Quote(html.string()));
  if (r.err.find("has no browser report") != std::string::npos) {
    GTEST_SKIP() << "this build has no browser report (node and report/'s packages)";
  }
  EXPECT_EQ(r.exit_code, 3) << r.err;
  const std::string page = ReadText(html);
  const std::string tag = "id=\"chasles-data\">";
  const std::size_t begin = page.find(tag) + tag.size();
  const nlohmann::json data =
      nlohmann::json::parse(page.substr(begin, page.find("</script>", begin) - begin));
  // The findings, per link with its line and body; the links drawn (the seven with a valid
  // inertial) from their Collada visuals, with the geometry's ellipsoid.
  EXPECT_EQ(data["kind"], "mass");
  ASSERT_EQ(data["audit"].size(), 1u);
  EXPECT_EQ(data["audit"][0]["errors"], 9);
  bool wrist = false;
  for (const nlohmann::json& l : data["audit"][0]["links"]) {
    if (l["name"] == "ee_link") {
      EXPECT_TRUE(l["body"].is_null());  // zero mass: listed, not drawn
      EXPECT_EQ(l["findings"][0]["code"], "zero_mass");
    }
    if (l["name"] != "wrist_1_link") continue;
    wrist = true;
    EXPECT_EQ(l["line"], 153);
    EXPECT_EQ(l["findings"][0]["code"], "com_outside_geometry");
    EXPECT_EQ(l["findings"][0]["severity"], "error");
    const nlohmann::json& b = data["bodies"][l["body"].get<std::size_t>()];
    EXPECT_EQ(b["name"], "wrist_1_link");
    EXPECT_EQ(b["mass"], 1.219);
    EXPECT_EQ(b["computed"]["source"], "visual");
    EXPECT_EQ(b["computed"]["ellipsoid"]["semi_axes"].size(), 3u);
    bool mesh = false;
    for (const nlohmann::json& p : b["parts"]) mesh = mesh || p.contains("mesh");
    EXPECT_TRUE(mesh);  // its Collada visual, drawn
  }
  EXPECT_EQ(data["bodies"].size(), 7u);
  EXPECT_TRUE(wrist);
  // The exit codes stay the audit's: 0 for the fixed file, 2 (and no page) for a hostile one.
  const fs::path fixed = ScratchDir("html-fixed");
  ASSERT_EQ(RunCli("audit " + Quote(ur5) + " --fix --out " + Quote(fixed.string())).exit_code, 3);
  const CliResult clean =
      RunCli("audit " + Quote((fixed / "ur5_robot.urdf").string()) + Packages(shared) + " --html " +
             Quote((fixed / "a.html").string()));
  EXPECT_EQ(clean.exit_code, 0) << clean.err;
  EXPECT_TRUE(fs::exists(fixed / "a.html"));
  const CliResult bad =
      RunCli("audit " + Quote(SourcePath("tests/bad_input/robots/unclosed.urdf")) + " --html " +
             Quote((fixed / "b.html").string()));
  EXPECT_EQ(bad.exit_code, 2) << bad.err;
  EXPECT_FALSE(fs::exists(fixed / "b.html"));
}

// A box link of 2 kg, 0.4 x 0.2 x 0.1 m (Appendix A: I_x = m (b² + c²)/12 and its cyclic
// forms), its inertial as the closed form: the given and computed principal moments ascending,
// the radii of gyration k_i = √(I_i / m) (eq. 8.19), no finding, exit 0.
TEST(AuditCli, JsonGivesPrincipalMomentsAndRadiiOfGyration) {
  const fs::path urdf = ScratchDir("box") / "box.urdf";
  std::ofstream(urdf) << R"(<robot name="box"><link name="b"><inertial><mass value="2"/>
<inertia ixx="0.008333333333333333" iyy="0.028333333333333335" izz="0.03333333333333333"
 ixy="0" ixz="0" iyz="0"/></inertial>
<visual><geometry><box size="0.4 0.2 0.1"/></geometry></visual></link></robot>)";
  const CliResult r = RunCli("audit " + Quote(urdf.string()) + " --format json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json link = nlohmann::json::parse(r.out)["files"][0]["links"][0];
  EXPECT_TRUE(link["findings"].empty()) << link.dump();
  const double m = 2.0, a = 0.4, b = 0.2, c = 0.1;
  const double moments[3] = {m * (b * b + c * c) / 12, m * (a * a + c * c) / 12,
                             m * (a * a + b * b) / 12};
  for (const char* which : {"given", "computed"}) {
    const nlohmann::json& v = link[which];
    for (int i = 0; i < 3; ++i) {
      EXPECT_TRUE(test::Near(v["principal_moments"][i].get<double>(), moments[i], 1e-12)) << which;
      EXPECT_TRUE(
          test::Near(v["radii_of_gyration"][i].get<double>(), std::sqrt(moments[i] / m), 1e-12))
          << which;
      EXPECT_TRUE(test::Near(std::abs(v["principal_axes"][i][i].get<double>()), 1.0, 1e-12))
          << which;
    }
  }
}

// Every robot of the shared folder in URDF, and its MJCF and SDF versions (tests/robots), read
// and audited without an input error (its time recorded as a property).
TEST(AuditCli, EveryRobotInEveryFormat) {
  const std::string shared = Shared();
  if (shared.empty()) GTEST_SKIP() << "../shared/robots is absent: the robots are not audited";
  std::string files;
  for (const auto& e : fs::recursive_directory_iterator(shared)) {
    if (e.path().extension() == ".urdf") files += " " + Quote(e.path().string());
  }
  for (const char* dir : {"tests/robots/mjcf", "tests/robots/sdf"}) {
    for (const auto& e : fs::directory_iterator(SourcePath(dir)))
      files += " " + Quote(e.path().string());
  }
  const auto t0 = std::chrono::steady_clock::now();
  const CliResult r = RunCli("audit" + files + Packages(shared) + " --format json");
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  ASSERT_EQ(r.exit_code, 3) << r.err;  // the published defects
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["files"].size(), 10u + 10u + 10u);
  std::map<std::string, int> formats;
  for (const nlohmann::json& f : j["files"]) ++formats[f["format"].get<std::string>()];
  EXPECT_EQ(formats["URDF"], 10);
  EXPECT_EQ(formats["MJCF"], 10);
  EXPECT_EQ(formats["SDF"], 10);
  // Recorded, not asserted: the speed is bench/audit_bench.cpp's (docs/audit.md), and a loaded
  // machine must not fail a test of correctness.
  RecordProperty("seconds", std::to_string(seconds));
  // The UR5's wrists in its SDF version, where the meshes resolve through --package.
  for (const nlohmann::json& f : j["files"]) {
    if (f["path"].get<std::string>().find("sdf/ur5.sdf") == std::string::npos) continue;
    for (const nlohmann::json& link : f["links"]) {
      if (link["name"] != "wrist_1_link") continue;
      bool radius = false;
      for (const nlohmann::json& x : link["findings"])
        radius = radius || x["code"] == "radius_of_gyration";
      EXPECT_TRUE(radius) << link.dump();
    }
  }
}

/// The URDF without the elements that hold meshes (MuJoCo 2.2 reads no Collada).
std::string StripMeshes(const std::string& urdf) {
  static const std::regex mesh(
      R"(<(visual|collision)\b[^>]*>((?!</\1>)[\s\S])*?<mesh\b((?!</\1>)[\s\S])*</\1>)");
  return std::regex_replace(urdf, mesh, "");
}

/// True when Debian's MuJoCo compiles `file` (its compile sample prints "Error" otherwise).
bool MuJoCoCompiles(const fs::path& file, std::string* log) {
  const fs::path out = file.parent_path() / (file.stem().string() + "-compiled.xml");
  const std::string command =
      "mujoco-compile " + Quote(file.string()) + " " + Quote(out.string()) + " 2>&1";
  FILE* pipe = ::popen(command.c_str(), "r");
  std::array<char, 4096> buffer;
  size_t n;
  log->clear();
  while ((n = std::fread(buffer.data(), 1, buffer.size(), pipe)) > 0) log->append(buffer.data(), n);
  ::pclose(pipe);
  return log->find("Error") == std::string::npos && fs::exists(out);
}

TEST(AuditCli, MuJoCoCompilesWhatItRefusedOnceFixed) {
  const std::string shared = Shared();
  if (shared.empty()) GTEST_SKIP() << "../shared/robots is absent";
  if (std::system("command -v mujoco-compile >/dev/null 2>&1") != 0) {
    GTEST_SKIP() << "Debian's MuJoCo (libmujoco-samples: mujoco-compile) is not installed";
  }
  const fs::path dir = ScratchDir("mujoco");
  // The ABB as URDF (meshes taken out) and as MJCF (tests/robots/mjcf).
  const std::string urdf = StripMeshes(ReadText(
      shared + "/compas_fab/robot_library/abb_irb4600_40_255/urdf/robot_description.urdf"));
  std::ofstream(dir / "abb.urdf") << urdf;
  fs::copy_file(SourcePath("tests/robots/mjcf/abb_irb4600.xml"), dir / "abb.xml");
  for (const char* file : {"abb.urdf", "abb.xml"}) {
    std::string log;
    EXPECT_FALSE(MuJoCoCompiles(dir / file, &log)) << file << " compiled before the fix";
    const CliResult r = RunCli("audit " + Quote((dir / file).string()) + " --fix --out " +
                               Quote((dir / "fixed").string()));
    EXPECT_EQ(r.exit_code, 3) << r.err;
    EXPECT_TRUE(MuJoCoCompiles(dir / "fixed" / file, &log)) << file << ": " << log;
  }
}

}  // namespace
}  // namespace chasles::test
