// Ten balls on a cloth, the cue ball rolling into nine at rest: the scene written with two set
// entries (`body: all` on the cloth, `between: all` for the collisions) runs bitwise as the
// same scene with its 55 contacts written one by one (docs/scene-format.md, "Sets of bodies"),
// on each engine that takes contacts: adaptive (hybrid), events and stepping.

#include <algorithm>
#include <string>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "chasles/scene/scene.h"
#include "chasles/scene/study.h"

namespace chasles {
namespace {

constexpr int kBalls = 10;

// The cue ball (ball1) rolls at 2 m/s (ω = v/R) along x into a 3-3-3 block of balls 1 mm
// apart, slightly off its line so the block scatters.
std::string Balls() {
  std::string text = R"(chasles: 3
parameters:
  R: 28.575 mm
  m: 0.17 kg
  v: 2 m/s
bodies:
  - {name: ball1, parts: [{shape: sphere, radius: R, mass: m}],
     initial: {position: [0, 5 mm, R], velocity: [v, 0, 0], angular_velocity: [0, v/R, 0]}}
)";
  for (int i = 1; i < kBalls; ++i) {
    text += fmt::format(
        "  - {{name: ball{}, parts: [{{shape: sphere, radius: R, mass: m}}], initial: {{position: "
        "[0.3 m + {} * (2*R + 1 mm), {} * (2*R + 1 mm), R]}}}}\n",
        i + 1, (i - 1) / 3, (i - 1) % 3 - 1);
  }
  return text + "gravity: standard\ncontacts:\n";
}

constexpr const char* kCloth =
    "shape: sphere, radius: R, mu_s: 0.25, mu_k: 0.2, plane: {normal: [0, 0, 1]}";
constexpr const char* kKnock = "shape: sphere, radius: R, restitution: 0.9";

std::string WithSets(const std::string& simulation) {
  return Balls() + fmt::format("  - {{name: cloth, body: all, {}}}\n", kCloth) +
         fmt::format("  - {{name: knock, between: all, {}}}\n", kKnock) + simulation;
}

std::string OneByOne(const std::string& simulation) {
  std::string text = Balls();
  for (int i = 1; i <= kBalls; ++i) {
    text += fmt::format("  - {{name: cloth_ball{0}, body: ball{0}, {1}}}\n", i, kCloth);
  }
  for (int a = 1; a <= kBalls; ++a) {
    for (int b = a + 1; b <= kBalls; ++b) {
      text += fmt::format(
          "  - {{name: knock_ball{0}_ball{1}, body: ball{0}, with: ball{1}, other_radius: R, "
          "{2}}}\n",
          a, b, kKnock);
    }
  }
  return text + simulation;
}

// Every row, column, contact event and impact the same to the bit; and the run not vacuous:
// the balls collide.
void ExpectSameRun(const std::string& simulation) {
  const Scene set = LoadSceneText(WithSets(simulation), "sets.yaml");
  const Scene listed = LoadSceneText(OneByOne(simulation), "listed.yaml");
  ASSERT_EQ(set.dynamics.contacts.contacts.size(), size_t{kBalls + kBalls * (kBalls - 1) / 2});
  const StudyResult a = RunStudy(MakeStudyDefinition(set));
  const StudyResult b = RunStudy(MakeStudyDefinition(listed));
  EXPECT_EQ(a.columns, b.columns);
  ASSERT_EQ(a.rows.size(), b.rows.size());
  for (size_t r = 0; r < a.rows.size(); ++r) EXPECT_EQ(a.rows[r], b.rows[r]) << "row " << r;
  ASSERT_EQ(a.contact_events.size(), b.contact_events.size());
  for (size_t k = 0; k < a.contact_events.size(); ++k) {
    EXPECT_EQ(a.contact_events[k].t, b.contact_events[k].t);
    EXPECT_EQ(a.contact_events[k].point, b.contact_events[k].point);
    EXPECT_EQ(a.contact_events[k].to, b.contact_events[k].to);
  }
  ASSERT_EQ(a.impacts.size(), b.impacts.size());
  for (size_t k = 0; k < a.impacts.size(); ++k) {
    EXPECT_EQ(a.impacts[k].t, b.impacts[k].t);
    EXPECT_EQ(a.impacts[k].point, b.impacts[k].point);
    EXPECT_EQ(a.impacts[k].normal_impulse, b.impacts[k].normal_impulse);
  }
  // Every ball of the block leaves its place: struck, directly or through another.
  int moved = 0;
  for (int i = 2; i <= kBalls; ++i) {
    const auto c = std::find(a.columns.begin(), a.columns.end(), fmt::format("ball{}_x", i));
    ASSERT_NE(c, a.columns.end());
    const auto k = static_cast<size_t>(c - a.columns.begin());
    moved += a.rows.back()[k] != a.rows.front()[k];
  }
  EXPECT_EQ(moved, kBalls - 1) << "the cue ball should scatter the whole block";
  EXPECT_EQ(a.ledger.energy, b.ledger.energy);
  EXPECT_EQ(a.integrator, b.integrator);
}

TEST(ContactSets, AdaptiveRunIsTheListedScenesBitForBit) {
  ExpectSameRun(
      "simulation: {until: 0.4 s, output_interval: 10 ms}\n"
      "output: {columns: [position, velocity, angular_velocity, contacts, ledger]}\n");
}

TEST(ContactSets, EventDrivenRunIsTheListedScenesBitForBit) {
  ExpectSameRun(
      "simulation: {until: 1 s, integrator: events, output_interval: 10 ms}\n"
      "output: {columns: [position, velocity, angular_velocity, contacts, ledger]}\n");
}

TEST(ContactSets, TimeSteppedRunIsTheListedScenesBitForBit) {
  ExpectSameRun(
      "simulation: {until: 0.4 s, integrator: stepping, step: 0.5 ms, "
      "output_interval: 10 ms}\n"
      "output: {columns: [position, velocity, angular_velocity, contacts, ledger]}\n");
}

}  // namespace
}  // namespace chasles
