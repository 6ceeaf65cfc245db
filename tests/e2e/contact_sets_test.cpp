// End-to-end: contact entries that name sets of bodies (docs/scene-format.md, "Sets of
// bodies") through the chasles program: examples/pool-rack-sets.yaml against its closed form
// and against the same scene with its 66 contacts written one by one (the same CSV to the
// byte), a 1,000-ball scene with one set entry, and the set too large to list.

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "cli_runner.h"
#include "test_support.h"

namespace chasles::test {
namespace {

constexpr double kR = 0.028575, kY0 = 0.005, kX0 = 1.0, kV = 4.0;  // the example's values

std::filesystem::path Out() {
  return OutDir("contact_sets");
}

std::string ReadFile(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

std::string WriteScene(const std::string& name, const std::string& text) {
  const auto path = Out() / name;
  std::ofstream(path) << text;
  return path.string();
}

// The example with its two set entries replaced by the 11 cloth and 55 pair entries they stand
// for, written one by one in the order and with the names the sets give.
std::string ListedExample() {
  std::string text = ReadFile(SourcePath("examples/pool-rack-sets.yaml"));
  const size_t from = text.find("contacts:\n");
  const size_t to = text.find("simulation:\n");
  std::vector<std::string> balls = {"cue"};
  for (int i = 1; i <= 10; ++i) balls.push_back(fmt::format("ball{}", i));
  std::string contacts = "contacts:\n";
  for (const std::string& b : balls) {
    contacts += fmt::format(
        "  - {{name: cloth_{0}, body: {0}, shape: sphere, radius: R, mu_s: 0.25, mu_k: 0.2, "
        "plane: {{normal: [0, 0, 1]}}}}\n",
        b);
  }
  for (size_t a = 0; a < balls.size(); ++a) {
    for (size_t b = a + 1; b < balls.size(); ++b) {
      contacts += fmt::format(
          "  - {{name: knock_{0}_{1}, body: {0}, with: {1}, shape: sphere, radius: R, "
          "other_radius: R, restitution: 0.93}}\n",
          balls[a], balls[b]);
    }
  }
  return text.replace(from, to - from, contacts);
}

TEST(ContactSets, RackExampleMeetsItsClosedFormAndTheListedScene) {
  const std::filesystem::path set_out = Out() / "set", listed_out = Out() / "listed";
  std::filesystem::create_directories(set_out);
  std::filesystem::create_directories(listed_out);
  const nlohmann::json run = SimulateJson(SourcePath("examples/pool-rack-sets.yaml"), set_out);
  // The cue ball keeps v (rolling, no rolling resistance) until it is 2 R from the apex ball:
  // t1 = (x0 - sqrt((2 R)^2 - y0^2)) / v.
  const double t1 = (kX0 - std::sqrt(4 * kR * kR - kY0 * kY0)) / kV;
  const nlohmann::json& first = run.at("impacts").at(0);
  EXPECT_EQ(first.at("point"), "knock_cue_ball1");
  EXPECT_TRUE(Near(first.at("t").get<double>(), t1, 1e-12));
  EXPECT_GE(run.at("impacts").size(), 10u);

  const std::string listed = WriteScene("pool-rack-sets.yaml", ListedExample());
  const nlohmann::json same = SimulateJson(listed, listed_out);
  EXPECT_EQ(ReadFile((set_out / "pool-rack-sets.csv").string()),
            ReadFile((listed_out / "pool-rack-sets.csv").string()));
  for (const char* key : {"impacts", "contact_events", "final", "ledger", "integrator"}) {
    EXPECT_EQ(run.at(key), same.at(key)) << key;
  }
}

// `count` balls in a square grid on a plane, one set entry for the cloth, and `extra` after it.
std::string ManyBalls(int count, const std::string& extra) {
  std::string text = "chasles: 3\nparameters: {R: 28.575 mm}\nbodies:\n";
  const int side = static_cast<int>(std::ceil(std::sqrt(count)));
  for (int i = 0; i < count; ++i) {
    text += fmt::format(
        "  - {{name: ball{}, parts: [{{shape: sphere, radius: R, mass: 0.17 kg}}], initial: "
        "{{position: [{} m, {} m, R]{}}}}}\n",
        i + 1, 0.07 * (i % side), 0.07 * (i / side),
        i == 0 ? ", velocity: [2 m/s, 0.3 m/s, 0]" : "");
  }
  return text + "gravity: standard\ncontacts:\n" +
         "  - {name: cloth, body: all, shape: sphere, radius: R, mu_s: 0.25, mu_k: 0.2, plane: "
         "{normal: [0, 0, 1]}}\n" +
         extra;
}

TEST(ContactSets, AThousandBallsWithOneSetEntry) {
  const std::string scene =
      WriteScene("thousand.yaml", ManyBalls(1000,
                                            "simulation: {until: 0.2 s, integrator: events, "
                                            "ball_collisions: {restitution: 0.9}}\n"));
  const CliResult check = RunCli("check " + Quote(scene));
  EXPECT_EQ(check.exit_code, 0) << check.err;
  EXPECT_THAT(check.out, ::testing::HasSubstr("ok (1000 bodies, 1000 parts"));
  const nlohmann::json run = SimulateJson(scene, Out(), "--columns t");
  ASSERT_EQ(run.at("final").at("contacts").size(), 1000u);
  EXPECT_EQ(run.at("final").at("contacts").at(999).at("point"), "cloth_ball1000");

  // Every pair of the thousand listed would be 499,500 contacts: refused at `between`, pointing
  // to ball_collisions.
  const std::string pairs = WriteScene(
      "pairs.yaml", ManyBalls(1000, "  - {name: knock, between: all, shape: sphere, radius: R}\n"));
  const CliResult refused = RunCli("check " + Quote(pairs));
  EXPECT_EQ(refused.exit_code, 2);
  EXPECT_THAT(refused.err, ::testing::HasSubstr(
                               pairs + ":1007:28: contacts[1].between: the set stands for 499500 "
                                       "contacts (1000 bodies, every pair), more than the 20000"));
  EXPECT_THAT(refused.err, ::testing::HasSubstr("'ball_collisions' lets every pair collide"));
}

}  // namespace
}  // namespace chasles::test
