// Format versions through the program (docs/scene-format.md, "Changes between versions"):
// `chasles upgrade` shows, writes or checks the rewrite of a version-1 scene; a version-1 scene
// loads with a warning for each old spelling in every report; and an upgraded scene gives the
// same mass, solve and simulate outputs, byte for byte apart from those warnings, as the
// version-1 file it came from: every scene in tests/format_v1 and every example as it was
// before the examples became version 2 (the upgrade changed only their version line); and a
// version-2 scene with contacts, which runs adaptive where version 3 runs auto.

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "cli_runner.h"
#include "test_support.h"

namespace chasles::test {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

std::string ReadText(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

void WriteText(const fs::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

/// `before` with a unified diff applied: each hunk's kept and removed lines must be there.
std::string ApplyDiff(const std::string& before, const std::string& diff) {
  std::vector<std::string> lines, out;
  std::stringstream in(before);
  for (std::string l; std::getline(in, l);) lines.push_back(l);
  std::stringstream d(diff);
  std::string l;
  std::getline(d, l);  // ---
  std::getline(d, l);  // +++
  size_t next = 0;     // first line of `lines` not yet copied
  while (std::getline(d, l)) {
    if (l.rfind("@@ -", 0) == 0) {
      const size_t first = std::stoul(l.substr(4));
      for (; next + 1 < first; ++next) out.push_back(lines.at(next));
      continue;
    }
    if (l[0] == '+') {
      out.push_back(l.substr(1));
    } else {
      EXPECT_EQ(lines.at(next), l.substr(1)) << "diff line: " << l;
      if (l[0] == ' ') out.push_back(l.substr(1));
      ++next;
    }
  }
  for (; next < lines.size(); ++next) out.push_back(lines[next]);
  std::string text;
  for (const std::string& s : out) text += s + "\n";
  return text;
}

fs::path Scratch(const std::string& name) {
  const fs::path dir = OutDir("upgrade") / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

const std::string kOld = "tests/format_v1/pinned-rod-old-spellings.yaml";

TEST(Upgrade, ShowsTheDiffAndWritesNothingWithoutAnOutput) {
  const fs::path dir = Scratch("show");
  const fs::path scene = dir / "rod.yaml";
  fs::copy_file(SourcePath(kOld), scene);
  const std::string before = ReadText(scene);
  const CliResult r = RunCli("upgrade " + Quote(scene.string()));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(ReadText(scene), before);
  EXPECT_THAT(r.out, HasSubstr("--- " + scene.string() + "\n+++ " + scene.string() + "\n"));
  EXPECT_THAT(r.out, HasSubstr("-chasles: 1\n+chasles: 3\n"));
  EXPECT_THAT(r.out, HasSubstr("\n-  - {name: fast, when: 'rod_wz', crosses: -2 rad/s, "
                               "action: record}\n"));
  EXPECT_THAT(r.out, HasSubstr("\n+  - {name: fast, when: 'rod_omega', crosses: -2 rad/s, "
                               "action: record}\n"));
  EXPECT_THAT(r.err, HasSubstr("format version 1 -> 3, 10 changes; nothing written"));
  // The diff is the edit -o writes.
  const CliResult o =
      RunCli("upgrade " + Quote(scene.string()) + " -o " + Quote((dir / "new.yaml").string()));
  ASSERT_EQ(o.exit_code, 0) << o.err;
  EXPECT_EQ(o.out, r.out.substr(0, r.out.find('\n') + 1) + "+++ " + (dir / "new.yaml").string() +
                       r.out.substr(r.out.find('\n', r.out.find('\n') + 1)));
  EXPECT_EQ(ApplyDiff(before, r.out), ReadText(dir / "new.yaml"));
  // What it wrote reads as version 3 without a warning.
  const CliResult check = RunCli("check " + Quote((dir / "new.yaml").string()));
  EXPECT_EQ(check.exit_code, 0) << check.err;
  EXPECT_THAT(check.out, ::testing::Not(HasSubstr("warning")));
}

// The diff is one `patch` applies: hunks far apart, and a last line without a newline.
TEST(Upgrade, TheDiffIsOnePatchApplies) {
  if (std::system("patch --version > /dev/null 2>&1") != 0) GTEST_SKIP() << "no patch program";
  const fs::path dir = Scratch("patch");
  std::string text = "# A pendulum without a version line, its event on the last line.\n\n";
  text +=
      "planar: true\nbodies:\n  - name: bob\n    parts: [{shape: planar, mass: 1 kg, "
      "inertia_z: 0.01 kg*m^2, center_of_mass: [0.3 m, 0]}]\n";
  for (int i = 0; i < 12; ++i) text += "# padding " + std::to_string(i) + "\n";
  text += "gravity: [0, -9.81 m/s^2, 0]\n";
  for (int i = 0; i < 12; ++i) text += "# more padding " + std::to_string(i) + "\n";
  text += "joints: [{name: pin, type: revolute, parent: world, child: bob, at: [0, 0]}]\n";
  text += "events: [{name: swing, when: bob_wz, crosses: -1 rad/s}]";  // no newline
  WriteText(dir / "old.yaml", text);
  const CliResult r = RunCli("upgrade " + Quote((dir / "old.yaml").string()) + " -o " +
                             Quote((dir / "new.yaml").string()));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '@'), 3 * 4) << r.out;  // three hunks
  EXPECT_THAT(r.out, HasSubstr("\n\\ No newline at end of file\n"));
  WriteText(dir / "change.diff", r.out);
  const std::string patched = (dir / "patched.yaml").string();
  ASSERT_EQ(
      std::system(("patch -s -o " + Quote(patched) + " " + Quote((dir / "old.yaml").string()) +
                   " < " + Quote((dir / "change.diff").string()))
                      .c_str()),
      0);
  EXPECT_EQ(ReadText(patched), ReadText(dir / "new.yaml"));
  EXPECT_TRUE(ReadText(dir / "new.yaml").ends_with("when: bob_omega, crosses: -1 rad/s}]"));
}

TEST(Upgrade, InPlaceReplacesTheFileOnceAndCheckSaysWhetherItIsNeeded) {
  const fs::path dir = Scratch("in-place");
  const fs::path scene = dir / "rod.yaml";
  fs::copy_file(SourcePath(kOld), scene);
  const CliResult check = RunCli("upgrade " + Quote(scene.string()) + " --check");
  EXPECT_EQ(check.exit_code, 3) << check.err;
  EXPECT_THAT(check.out, HasSubstr("+chasles: 3\n"));
  EXPECT_THAT(check.err, HasSubstr("format version 1 -> 3"));
  EXPECT_EQ(ReadText(scene), ReadText(SourcePath(kOld)));

  const CliResult r = RunCli("upgrade " + Quote(scene.string()) + " --in-place");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.err, HasSubstr("wrote " + scene.string()));
  EXPECT_EQ(ReadText(scene), ApplyDiff(ReadText(SourcePath(kOld)), r.out));
  // Only the upgraded file is in the folder: no temporary left behind.
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);

  for (const char* flags : {"--in-place", "--check", ""}) {
    const CliResult again = RunCli("upgrade " + Quote(scene.string()) + " " + flags);
    EXPECT_EQ(again.exit_code, 0) << flags << again.err;
    EXPECT_TRUE(again.out.empty()) << flags;
    EXPECT_THAT(again.err, HasSubstr("is format version 3 already; nothing to change"));
  }
}

TEST(Upgrade, BadInputExitsTwoAndWritesNothing) {
  const fs::path dir = Scratch("bad");
  const fs::path scene = dir / "rod.yaml";
  fs::copy_file(SourcePath(kOld), scene);
  const auto expect_bad = [&](const std::string& args, const std::string& says) {
    const CliResult r = RunCli("upgrade " + args);
    EXPECT_EQ(r.exit_code, 2) << args << ": " << r.err;
    EXPECT_THAT(r.err, HasSubstr(says)) << args;
    EXPECT_TRUE(r.out.empty()) << args;
  };
  expect_bad(Quote(scene.string()) + " --in-place -o " + Quote((dir / "x.yaml").string()),
             "excludes");
  expect_bad(Quote(scene.string()) + " --check --in-place", "excludes");
  expect_bad(Quote(scene.string()) + " -o " + Quote((dir / "no" / "x.yaml").string()), "no");
  expect_bad(Quote((dir / "missing.yaml").string()), "missing.yaml");
  WriteText(dir / "v4.yaml", "chasles: 4\nbodies: [{parts: [{shape: point, mass: 1 kg}]}]\n");
  expect_bad(Quote((dir / "v4.yaml").string()),
             "format version '4' is not known; this chasles reads versions 1 to 3");
  WriteText(dir / "broken.yaml", "chasles: 1\nbodies: [{parts: [{shape: sphere, mass: 1 kg}]}]\n");
  expect_bad(Quote((dir / "broken.yaml").string()), "needs the key 'radius'");
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 3);
  EXPECT_EQ(ReadText(scene), ReadText(SourcePath(kOld)));
}

// Every report of a version-1 scene carries its old-spelling warnings (text and JSON).
TEST(Upgrade, VersionOneWarningsAreInEveryReport) {
  const std::string scene = Quote(SourcePath(kOld));
  const std::string expected =
      "pinned-rod-old-spellings.yaml:21:64: joints[0].at: version-1 "
      "spelling [0, 0, 0 m] of a planar scene's world vector: write "
      "[0, 0]; chasles upgrade rewrites the file as version 3";
  for (const std::string& command : {std::string("mass"), std::string("solve"),
                                     "simulate --out " + Quote(Scratch("warnings").string())}) {
    const CliResult text = RunCli(command + " " + scene);
    ASSERT_EQ(text.exit_code, 0) << command << text.err;
    EXPECT_THAT(text.out, HasSubstr("warning: " + SourcePath(kOld) + ":21:64:")) << command;
    EXPECT_THAT(text.out, HasSubstr(expected)) << command;
    const CliResult json = RunCli(command + " " + scene + " --format json");
    ASSERT_EQ(json.exit_code, 0) << command << json.err;
    const nlohmann::json warnings = nlohmann::json::parse(json.out).at("warnings");
    const auto has = [&](const std::string& what) {
      for (const auto& w : warnings) {
        if (w.get<std::string>().find(what) != std::string::npos) return true;
      }
      return false;
    };
    EXPECT_TRUE(has(expected)) << command << warnings.dump();
    EXPECT_TRUE(has("version-1 name 'rod_wbz' of a planar scene, read as 'rod_omega'")) << command;
  }
}

// A version-2 scene with contacts and no integrator runs adaptive with a warning; as version 3
// it runs auto, which says that it is the default, and gives the same rows bit for bit where it
// never switches (the bouncing ball sums its bounces in closed form); the upgrade keeps
// adaptive, written out.
TEST(Upgrade, AVersionTwoSceneWithContactsKeepsAdaptiveAndVersionThreeRunsAuto) {
  const fs::path dir = Scratch("default-integrator");
  std::string v3 = ReadText(SourcePath("examples/contact-bouncing-ball.yaml"));
  ASSERT_EQ(v3.find("integrator"), std::string::npos);
  std::string v2 = v3;
  v2.replace(v2.find("\nchasles: 3\n"), 12, "\nchasles: 2\n");
  WriteText(dir / "v2.yaml", v2);
  WriteText(dir / "v3.yaml", v3);
  const auto simulate = [&](const std::string& name, const std::string& format) {
    return RunCli("simulate " + Quote((dir / name).string()) + " --quiet --out " +
                  Quote(dir.string()) + " --format " + format);
  };
  const CliResult old = simulate("v2.yaml", "text");
  ASSERT_EQ(old.exit_code, 0) << old.err;
  EXPECT_THAT(old.out, HasSubstr("Integrator: adaptive Dormand-Prince 5(4)"));
  EXPECT_THAT(old.out, HasSubstr("v2.yaml:21:1: simulation: a version-2 scene with contacts that "
                                 "names no integrator runs 'adaptive' (version 3 runs 'auto' "
                                 "there"));
  const std::string old_csv = ReadText(dir / "v2.csv");
  const CliResult now = simulate("v3.yaml", "text");
  ASSERT_EQ(now.exit_code, 0) << now.err;
  EXPECT_THAT(now.out, HasSubstr("Integrator: auto, the default for a scene with contacts ("));
  EXPECT_THAT(now.out, HasSubstr("  0 s to 2 s: adaptive, start\n"));
  EXPECT_THAT(now.out, ::testing::Not(HasSubstr("warning")));
  EXPECT_EQ(ReadText(dir / "v3.csv"), old_csv);
  const CliResult json = simulate("v3.yaml", "json");
  ASSERT_EQ(json.exit_code, 0) << json.err;
  EXPECT_TRUE(
      nlohmann::json::parse(json.out).at("integrator").at("auto").at("default").get<bool>());
  const CliResult up = RunCli("upgrade " + Quote((dir / "v2.yaml").string()) + " -o " +
                              Quote((dir / "up.yaml").string()));
  ASSERT_EQ(up.exit_code, 0) << up.err;
  EXPECT_THAT(up.out, HasSubstr("-chasles: 2\n+chasles: 3\n"));
  EXPECT_THAT(up.out, HasSubstr("\n simulation:\n+  integrator: adaptive\n   until: 2 s\n"));
  const CliResult kept = simulate("up.yaml", "text");
  ASSERT_EQ(kept.exit_code, 0) << kept.err;
  EXPECT_THAT(kept.out, HasSubstr("Integrator: adaptive Dormand-Prince 5(4)"));
  EXPECT_THAT(kept.out, ::testing::Not(HasSubstr("warning")));
  EXPECT_EQ(ReadText(dir / "up.csv"), old_csv);
}

/// The report with its warnings taken out, and the scratch folder's name made `to`'s.
std::string WithoutWarnings(const std::string& json, const std::string& from,
                            const std::string& to) {
  std::string text = json;
  for (size_t at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size())) {
    text.replace(at, from.size(), to);
  }
  nlohmann::json j = nlohmann::json::parse(text);
  j.erase("warnings");
  return j.dump(1);
}

struct Outputs {
  int mass = -1, solve = -1, simulate = -1;
  std::string mass_json, solve_json, simulate_json, csv;
};

/// mass, solve and simulate of `scene` (in its folder `dir`) as JSON, and the run's CSV.
Outputs Run(const fs::path& dir, const std::string& extra) {
  const std::string scene = Quote((dir / "s.yaml").string());
  Outputs o;
  const CliResult mass = RunCli("mass " + scene + " --format json");
  const CliResult solve = RunCli("solve " + scene + " --format json");
  const CliResult sim = RunCli("simulate " + scene + " --format json --quiet --out " +
                               Quote(dir.string()) + " " + extra);
  o.mass = mass.exit_code;
  o.solve = solve.exit_code;
  o.simulate = sim.exit_code;
  o.mass_json = mass.exit_code == 0 ? mass.out : mass.err;
  o.solve_json = solve.exit_code == 0 ? solve.out : solve.err;
  o.simulate_json = sim.exit_code == 0 ? sim.out : sim.err;
  o.csv = ReadText(dir / "s.csv");
  return o;
}

/// Upgrades the version-1 `text` and checks that both give the same outputs.
void ExpectSameOutputs(const std::string& name, const std::string& text, const std::string& extra) {
  SCOPED_TRACE(name);
  const fs::path a = Scratch("old-" + name), b = Scratch("new-" + name);
  WriteText(a / "s.yaml", text);
  // A mesh part's file is found beside the scene.
  fs::create_directory_symlink(SourcePath("examples/meshes"), a / "meshes");
  fs::create_directory_symlink(SourcePath("examples/meshes"), b / "meshes");
  const CliResult up =
      RunCli("upgrade " + Quote((a / "s.yaml").string()) + " -o " + Quote((b / "s.yaml").string()));
  ASSERT_EQ(up.exit_code, 0) << up.err;
  ASSERT_THAT(up.out, HasSubstr("+chasles: 3\n"));
  const Outputs old = Run(a, extra), now = Run(b, extra);
  EXPECT_EQ(old.mass, now.mass);
  EXPECT_EQ(old.solve, now.solve);
  EXPECT_EQ(old.simulate, now.simulate);
  EXPECT_EQ(old.csv, now.csv);
  const std::string from = a.string(), to = b.string();
  if (old.mass == 0) {
    EXPECT_EQ(WithoutWarnings(old.mass_json, from, to), WithoutWarnings(now.mass_json, to, to));
  }
  if (old.solve == 0) {
    EXPECT_EQ(WithoutWarnings(old.solve_json, from, to), WithoutWarnings(now.solve_json, to, to));
  }
  if (old.simulate == 0) {
    EXPECT_EQ(WithoutWarnings(old.simulate_json, from, to),
              WithoutWarnings(now.simulate_json, to, to));
  }
}

// The version-1 scenes kept in tests/format_v1, run to their end.
TEST(Upgrade, VersionOneScenesGiveTheSameOutputsUpgraded) {
  int count = 0;
  for (const auto& entry : fs::directory_iterator(SourcePath("tests/format_v1"))) {
    if (entry.path().extension() != ".yaml") continue;
    ++count;
    ExpectSameOutputs(entry.path().stem().string(), ReadText(entry.path()), "");
  }
  EXPECT_GE(count, 10);
}

// Every example as it was in version 1 (its version line was all the upgrades changed, and the
// upgrade to version 3 writes `integrator: adaptive` into a scene with contacts that named
// none), the runs cut to 50 ms.
TEST(Upgrade, EveryExampleAsVersionOneGivesTheSameOutputsUpgraded) {
  int count = 0;
  for (const auto& entry : fs::directory_iterator(SourcePath("examples"))) {
    if (entry.path().extension() != ".yaml") continue;
    // The version line, which may be the first.
    std::string text = "\n" + ReadText(entry.path());
    const size_t at = text.find("\nchasles: 3\n");
    ASSERT_NE(at, std::string::npos) << entry.path() << " is not version 3";
    text.replace(at, 12, "\nchasles: 1\n");
    text.erase(0, 1);
    if (!Sampled(count++)) continue;
    ExpectSameOutputs(entry.path().stem().string(), text, "--until 0.05");
  }
  EXPECT_GE(count, 60);
}

}  // namespace
}  // namespace chasles::test
