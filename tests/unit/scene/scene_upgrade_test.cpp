// Format versions and the upgrade (docs/scene-format.md, "Changes between versions"): a
// version-1 file is read with the meanings it had, each version-1 spelling a warning at its
// place naming the new one; versions 2 and 3 refuse them naming the new one; a version-1 or -2
// scene with contacts and no integrator runs adaptive (version 3: auto), with a warning;
// UpgradeSceneText edits the text at the nodes' places only, and what it writes reads as the
// old file did.

#include "chasles/scene/scene_upgrade.h"

#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "chasles/scene/scene.h"
#include "chasles/scene/scene_error.h"

namespace chasles {
namespace {

using ::testing::HasSubstr;

// A planar pinned rod with every version-1 spelling, `VERSION` replaced by the version line.
constexpr const char* kOldRod = R"(# comment kept
VERSION
planar: true
bodies:
  - name: rod
    parts: [{shape: planar, mass: 2 kg, inertia_z: 1/6 kg*m^2, center_of_mass: [0.5 m, 0]}]
    initial: {position: [0, 0, 0], velocity: [0 m/s, 0, 0]}   # at rest
gravity: [0, -9.81 m/s^2, 0]
joints:
  - {name: pin, type: revolute, parent: world, child: rod, at: [0, 0, 0 m]}
forces:
  - type: force
    body: rod
    value:
      - 0.5 N
      - 0
      - 0
events:
  - {name: a, when: rod_yaw, crosses: -30 deg, action: record}
  - {name: b, when: 'rod_wz - 1 rad/s + rod_wz', crosses: -2 rad/s, action: record}
  - {name: c, when: "rod_wbz", crosses: -3 rad/s}
)";

std::string WithVersion(const std::string& version) {
  std::string text = kOldRod;
  text.replace(text.find("VERSION"), 7, version);
  return text;
}

TEST(SceneVersions, TheVersionLineSaysHowTheFileIsRead) {
  const char* body = "bodies: [{parts: [{shape: sphere, radius: 1 m, mass: 1 kg}]}]\n";
  EXPECT_EQ(LoadSceneText(std::string("chasles: 3\n") + body, "t.yaml").format_version, 3);
  EXPECT_EQ(LoadSceneText(std::string("chasles: 2\n") + body, "t.yaml").format_version, 2);
  EXPECT_EQ(LoadSceneText(std::string("chasles: 1\n") + body, "t.yaml").format_version, 1);
  // A file without the key is version 1: the format as it was before versions meant anything.
  EXPECT_EQ(LoadSceneText(body, "t.yaml").format_version, 1);
  try {
    LoadSceneText(std::string("chasles: 4\n") + body, "t.yaml");
    FAIL() << "version 4 read";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.line(), 1);
    EXPECT_THAT(e.message(), HasSubstr("format version '4' is not known; this chasles reads "
                                       "versions 1 to 3 (it writes 3"));
  }
}

TEST(SceneVersions, VersionOneSpellingsAreReadAsBeforeWithAWarningEach) {
  const Scene old = LoadSceneText(WithVersion("chasles: 1"), "old.yaml");
  ASSERT_EQ(old.format_version, 1);
  // One warning per use, at its place (1-based line and column), naming the new spelling.
  const std::vector<std::string> expected = {
      "old.yaml:10:64: joints[0].at: version-1 spelling [0, 0, 0 m] of a planar scene's world "
      "vector: write [0, 0]",
      "old.yaml:8:10: gravity: version-1 spelling [0, -9.81 m/s^2, 0] of a planar scene's world "
      "vector: write [0, -9.81 m/s^2]",
      "old.yaml:7:25: bodies[0].initial.position: version-1 spelling [0, 0, 0] of a planar "
      "scene's world vector: write [0, 0]",
      "old.yaml:7:46: bodies[0].initial.velocity: version-1 spelling [0 m/s, 0, 0] of a planar "
      "scene's world vector: write [0 m/s, 0]",
      "old.yaml:15:7: forces[0].value: version-1 spelling [0.5 N, 0, 0] of a planar scene's "
      "world vector: write [0.5 N, 0]",
      "old.yaml:19:21: events[0].when: version-1 name 'rod_yaw' of a planar scene, read as "
      "'rod_theta' (the angle about z, which does not wrap at ±180° as yaw did): write "
      "'rod_theta'",
      "old.yaml:20:22: events[1].when: version-1 name 'rod_wz' of a planar scene, read as "
      "'rod_omega' (the signed angular velocity about z): write 'rod_omega'",
      "old.yaml:20:41: events[1].when: version-1 name 'rod_wz' of a planar scene, read as "
      "'rod_omega' (the signed angular velocity about z): write 'rod_omega'",
      "old.yaml:21:22: events[2].when: version-1 name 'rod_wbz' of a planar scene, read as "
      "'rod_omega' (the signed angular velocity about z): write 'rod_omega'",
  };
  ASSERT_EQ(old.warnings.size(), expected.size());
  for (size_t i = 0; i < expected.size(); ++i) {
    EXPECT_EQ(old.warnings[i], expected[i] + "; chasles upgrade rewrites the file as version 3");
  }
  // Read as the version-2 spellings are: the same values and the same state variables.
  std::string v2 = WithVersion("chasles: 2");
  for (const auto& [from, to] :
       std::vector<std::pair<std::string, std::string>>{{"[0, 0, 0], v", "[0, 0], v"},
                                                        {"[0 m/s, 0, 0]", "[0 m/s, 0]"},
                                                        {"[0, -9.81 m/s^2, 0]", "[0, -9.81 m/s^2]"},
                                                        {"[0, 0, 0 m]", "[0, 0]"},
                                                        {"      - 0\n      - 0\n", "      - 0\n"},
                                                        {"rod_yaw", "rod_theta"},
                                                        {"rod_wz", "rod_omega"},
                                                        {"rod_wz", "rod_omega"},
                                                        {"rod_wbz", "rod_omega"}}) {
    ASSERT_NE(v2.find(from), std::string::npos) << from;
    v2.replace(v2.find(from), from.size(), to);
  }
  const Scene now = LoadSceneText(v2, "new.yaml");
  EXPECT_TRUE(now.warnings.empty());
  EXPECT_EQ(old.dynamics.g_W, now.dynamics.g_W);
  EXPECT_EQ(old.dynamics.constraints.joints[0].p_WJ, now.dynamics.constraints.joints[0].p_WJ);
  ASSERT_EQ(old.dynamics.events.size(), now.dynamics.events.size());
  std::vector<double> state(200);
  for (size_t i = 0; i < state.size(); ++i) state[i] = 0.1 * static_cast<double>(i) - 3.0;
  for (size_t e = 0; e < now.dynamics.events.size(); ++e) {
    EXPECT_EQ(old.dynamics.events[e].when.Evaluate(state),
              now.dynamics.events[e].when.Evaluate(state))
        << e;
  }
}

TEST(SceneVersions, VersionTwoRefusesTheOldSpellingsNamingTheNewOnes) {
  const auto message = [](const std::string& text) {
    try {
      LoadSceneText(text, "new.yaml");
    } catch (const SceneError& e) {
      return fmt::format("{}:{}: {}", e.line(), e.column(), e.message());
    }
    return std::string("loaded");
  };
  const std::string rod = R"(chasles: 2
planar: true
bodies:
  - name: rod
    parts: [{shape: planar, mass: 2 kg, inertia_z: 1/6 kg*m^2, center_of_mass: [0.5 m, 0]}]
joints:
  - {name: pin, type: revolute, parent: world, child: rod, at: AT}
events:
  - {name: e, when: WHEN, crosses: 0}
)";
  const auto scene = [&](const std::string& at, const std::string& when) {
    std::string text = rod;
    text.replace(text.find("AT"), 2, at);
    text.replace(text.find("WHEN"), 4, when);
    return text;
  };
  EXPECT_EQ(message(scene("[0.5 m, 2 m, 0]", "rod_theta")),
            "7:64: the joint point (world): a planar scene moves in the x-y plane; give [x, y] "
            "(two values), not [x, y, z]: write [0.5 m, 2 m] ([x, y, 0] is the version-1 "
            "spelling)");
  EXPECT_EQ(message(scene("[0, 0]", "2 * rod_wz")),
            "9:25: 'rod_wz' is the version-1 name of 'rod_omega' in a planar scene (the signed "
            "angular velocity about z); write 'rod_omega'");
  EXPECT_EQ(message(scene("[0, 0]", "rod_yaw")),
            "9:21: 'rod_yaw' is the version-1 name of 'rod_theta' in a planar scene (the angle "
            "about z, which does not wrap at ±180° as yaw did); write 'rod_theta'");
  // A 3-D name with no planar counterpart stays refused in every version, with the list.
  for (const char* version : {"chasles: 1", "chasles: 2", "chasles: 3"}) {
    std::string text = scene("[0, 0]", "rod_tilt");
    text.replace(0, 10, version);
    EXPECT_THAT(message(text), HasSubstr("'rod_tilt' is a 3-D state variable; a planar scene's "
                                         "body variables are rod_x, rod_y, rod_theta"));
  }
  // Version 1 reads [x, y, 0] only: a third value that is not 0 is refused.
  std::string off = scene("[0, 0, 1 mm]", "rod_theta");
  off.replace(0, 10, "chasles: 1");
  EXPECT_EQ(message(off),
            "7:64: the joint point (world): a planar scene moves in the x-y plane; give [x, y] "
            "(two values), not [x, y, z]: out-of-plane components have no place in a planar "
            "problem");
}

TEST(SceneUpgrade, EditsTheTextWhereTheOldSpellingsStand) {
  const SceneUpgrade u = UpgradeSceneText(WithVersion("chasles: 1"), "old.yaml");
  EXPECT_EQ(u.from_version, 1);
  EXPECT_EQ(u.before, WithVersion("chasles: 1"));
  // Comments, quotes, layout and key order stay; only the spellings change.
  EXPECT_EQ(u.text, R"(# comment kept
chasles: 3
planar: true
bodies:
  - name: rod
    parts: [{shape: planar, mass: 2 kg, inertia_z: 1/6 kg*m^2, center_of_mass: [0.5 m, 0]}]
    initial: {position: [0, 0], velocity: [0 m/s, 0]}   # at rest
gravity: [0, -9.81 m/s^2]
joints:
  - {name: pin, type: revolute, parent: world, child: rod, at: [0, 0]}
forces:
  - type: force
    body: rod
    value:
      - 0.5 N
      - 0
events:
  - {name: a, when: rod_theta, crosses: -30 deg, action: record}
  - {name: b, when: 'rod_omega - 1 rad/s + rod_omega', crosses: -2 rad/s, action: record}
  - {name: c, when: "rod_omega", crosses: -3 rad/s}
)");
  ASSERT_EQ(u.changes.size(), 10u);
  EXPECT_EQ(u.changes[0], "old.yaml:2:10: chasles: chasles: 1 -> chasles: 3");
  EXPECT_EQ(u.changes[9], "old.yaml:21:22: events[2].when: 'rod_wbz' -> 'rod_omega'");
  // Upgrading again changes nothing.
  const SceneUpgrade again = UpgradeSceneText(u.text, "new.yaml");
  EXPECT_FALSE(again.changed());
  EXPECT_EQ(again.text, u.text);
}

TEST(SceneUpgrade, AFileWithoutAVersionGetsTheLineBeforeItsFirstKey) {
  const char* body = "bodies: [{parts: [{shape: sphere, radius: 1 m, mass: 1 kg}]}]\n";
  EXPECT_EQ(UpgradeSceneText(std::string("# a sphere\n\n") + body, "t.yaml").text,
            std::string("# a sphere\n\nchasles: 3\n") + body);
  EXPECT_EQ(UpgradeSceneText(R"({bodies: [{parts: [{shape: point, mass: 1 kg}]}]})", "t.yaml").text,
            R"({chasles: 3, bodies: [{parts: [{shape: point, mass: 1 kg}]}]})");
  // A quoted version keeps its quotes, a byte-order mark stays, CR LF line ends stay.
  EXPECT_EQ(UpgradeSceneText(std::string("chasles: '1'\n") + body, "t.yaml").text,
            std::string("chasles: '3'\n") + body);
  EXPECT_EQ(UpgradeSceneText(std::string("\xEF\xBB\xBF"
                                         "chasles: 1\n") +
                                 body,
                             "t.yaml")
                .text,
            std::string("\xEF\xBB\xBF"
                        "chasles: 3\n") +
                body);
  EXPECT_EQ(
      UpgradeSceneText("# a point\r\nbodies: [{parts: [{shape: point, mass: 1 kg}]}]\r\n", "t.yaml")
          .text,
      "# a point\r\nchasles: 3\r\nbodies: [{parts: [{shape: point, mass: 1 kg}]}]\r\n");
}

// Version 3's one change: a scene with contacts that names no integrator runs auto. A version-1
// or -2 file keeps adaptive, with a warning at `simulation` (line 1 without one), and its
// upgrade writes `integrator: adaptive` where the file's layout has it: a line of the block
// mapping indented as its keys, an entry of a flow mapping, or a section at the end.
constexpr const char* kBallOnFloor = R"(VERSION
bodies:
  - name: ball
    parts: [{shape: sphere, radius: 0.1 m, mass: 1 kg}]
    initial: {position: [0, 0, 1 m]}
gravity: [0, 0, -9.81 m/s^2]
contacts:
  - {name: floor, body: ball, shape: sphere, radius: 0.1 m, mu_s: 0.5, mu_k: 0.4,
     plane: {point: [0, 0, 0], normal: [0, 0, 1]}}
SIMULATION)";

std::string BallOnFloor(const std::string& version, const std::string& simulation) {
  std::string text = kBallOnFloor;
  text.replace(text.find("VERSION"), 7, version);
  text.replace(text.find("SIMULATION"), 10, simulation);
  return text;
}

TEST(SceneVersions, AScenesDefaultIntegratorWithContactsIsAutoFromVersionThree) {
  const std::string block = "simulation:\n    until: 1 s  # a comment\n    tolerance: 1e-9\n";
  const Scene v3 = LoadSceneText(BallOnFloor("chasles: 3", block), "new.yaml");
  EXPECT_TRUE(v3.dynamics.simulation.auto_engine);
  EXPECT_TRUE(v3.dynamics.simulation.auto_by_default);
  EXPECT_TRUE(v3.warnings.empty());
  for (const char* version : {"chasles: 2", "chasles: 1"}) {
    const Scene old = LoadSceneText(BallOnFloor(version, block), "old.yaml");
    EXPECT_FALSE(old.dynamics.simulation.auto_engine) << version;
    ASSERT_EQ(old.warnings.size(), 1u) << version;
    EXPECT_EQ(old.warnings[0],
              fmt::format("old.yaml:10:1: simulation: a version-{} scene with contacts that names "
                          "no integrator runs 'adaptive' (version 3 runs 'auto' there: "
                          "event-driven while the contacts' regimes change slowly, time stepped "
                          "while they chatter); write 'integrator: adaptive' to keep that; "
                          "chasles upgrade rewrites the file as version 3",
                          version[9]));
  }
  // A named integrator is kept in every version, and a scene without contacts is not touched.
  for (const char* version : {"chasles: 2", "chasles: 3"}) {
    const Scene named = LoadSceneText(
        BallOnFloor(version, "simulation: {until: 1 s, integrator: adaptive}\n"), "t.yaml");
    EXPECT_FALSE(named.dynamics.simulation.auto_engine);
    EXPECT_TRUE(named.warnings.empty());
  }
  std::string free = BallOnFloor("chasles: 2", block);
  free.erase(free.find("contacts:"), free.find("simulation:") - free.find("contacts:"));
  const Scene no_contacts = LoadSceneText(free, "t.yaml");
  EXPECT_FALSE(no_contacts.dynamics.simulation.auto_engine);
  EXPECT_TRUE(no_contacts.warnings.empty());
}

TEST(SceneUpgrade, AVersionTwoSceneWithContactsKeepsAdaptiveWrittenOut) {
  const std::string block = "simulation:\n    until: 1 s  # a comment\n    tolerance: 1e-9\n";
  const SceneUpgrade u = UpgradeSceneText(BallOnFloor("chasles: 2", block), "old.yaml");
  EXPECT_EQ(u.from_version, 2);
  EXPECT_EQ(u.text, BallOnFloor("chasles: 3",
                                "simulation:\n    integrator: adaptive\n    until: "
                                "1 s  # a comment\n    tolerance: 1e-9\n"));
  ASSERT_EQ(u.changes.size(), 2u);
  EXPECT_EQ(u.changes[0], "old.yaml:1:10: chasles: chasles: 2 -> chasles: 3");
  EXPECT_EQ(u.changes[1],
            "old.yaml:10:1: simulation: integrator: adaptive added (what a scene with contacts "
            "that names none ran before version 3, which runs auto there)");
  const Scene now = LoadSceneText(u.text, "new.yaml");
  EXPECT_FALSE(now.dynamics.simulation.auto_engine);
  EXPECT_TRUE(now.warnings.empty());
  // A flow mapping gets an entry; a file without `simulation` gets one at its end, ended as
  // its lines are (with a line end added where the last line has none).
  EXPECT_EQ(
      UpgradeSceneText(BallOnFloor("chasles: 2", "simulation: {until: 1 s}\n"), "t.yaml").text,
      BallOnFloor("chasles: 3", "simulation: {integrator: adaptive, until: 1 s}\n"));
  EXPECT_EQ(UpgradeSceneText(BallOnFloor("chasles: 2", ""), "t.yaml").text,
            BallOnFloor("chasles: 3", "simulation:\n  integrator: adaptive\n"));
  std::string crlf = BallOnFloor("chasles: 1", "");
  for (size_t at = crlf.find('\n'); at != std::string::npos; at = crlf.find('\n', at + 2)) {
    crlf.replace(at, 1, "\r\n");
  }
  crlf.resize(crlf.size() - 2);  // no line end after the last line
  std::string expected = BallOnFloor("chasles: 3", "simulation:\r\n  integrator: adaptive\r\n");
  for (size_t at = expected.find('\n'); at != std::string::npos; at = expected.find('\n', at + 2)) {
    if (expected[at - 1] != '\r') expected.replace(at, 1, "\r\n");
  }
  EXPECT_EQ(UpgradeSceneText(crlf, "t.yaml").text, expected);
  // `simulation:` with no keys cannot take the entry in place: the user is told what to write.
  try {
    UpgradeSceneText(BallOnFloor("chasles: 2", "simulation: {}\n"), "t.yaml");
    FAIL() << "rewritten";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.line(), 10);
    EXPECT_THAT(e.message(), HasSubstr("add 'integrator: adaptive' to 'simulation' by hand"));
  }
}

TEST(SceneUpgrade, AnOldSpellingAnEditCannotReachIsAnErrorSayingWhatToWrite) {
  // An escaped character in a double-quoted value: the name's bytes are not the value's.
  std::string text = WithVersion("chasles: 1");
  text.replace(text.find("\"rod_wbz\""), 9, R"("rod_\x77bz")");
  try {
    UpgradeSceneText(text, "old.yaml");
    FAIL() << "rewritten";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.line(), 21);
    EXPECT_THAT(e.message(), HasSubstr("cannot be rewritten in place"));
    EXPECT_THAT(e.message(), HasSubstr("write 'rod_omega' in place of 'rod_wbz' here"));
  }
}

}  // namespace
}  // namespace chasles
