// One Model shared by several threads: a Model is immutable once built and its callbacks (the
// scene's expression forces and events) keep nothing mutable, so runs in parallel threads give
// bitwise the single-thread results. Also built with ThreadSanitizer (scripts/test.sh --tsan).

#include <cstring>
#include <thread>
#include <vector>

#include "chasles/analysis/initial_state.h"
#include "chasles/analysis/study.h"
#include "chasles/integrate/simulate.h"
#include "chasles/scene/scene.h"
#include "chasles/scene/study.h"
#include "threads/same_bits.h"
// clang-format off
#include <gtest/gtest.h>
// clang-format on

namespace chasles {
namespace {

/// The scene's study with its initial state settled on the constraints (SettleInitialState),
/// as a run or a solve starts from it.
Study Settled(Study s) {
  std::vector<std::string> warnings;
  s.initial = SettleInitialState(*s.model, s.initial, s.settling, warnings);
  return s;
}

// A pendulum on a revolute joint pushed by a state-dependent expression force, with an event
// that reads a reaction: every kind of callback a scene compiles, evaluated from every thread.
constexpr const char* kScene = R"(
bodies:
  - name: rod
    parts: [{shape: box, size: [1 m, 4 cm, 4 cm], mass: 2 kg}]
    initial: {position: [0.5 m, 0, 0]}
joints:
  - {name: pivot, type: revolute, parent: world, child: rod, at: [0, 0, 0], axis: [0, 1, 0]}
forces:
  - {type: force, body: rod, point: [0.5 m, 0, 0], value: [0, 0, (-3 N) * cos(rod_wy * 1 s)]}
events:
  - {name: swing, when: rod_z, crosses: -0.4 m, direction: falling, action: record}
simulation: {until: 2 s, tolerance: 1e-10, output_interval: 0.1 s}
)";

TEST(SharedModel, SimulateInFourThreadsMatchesOneThreadBitwise) {
  const Scene scene = LoadSceneText(kScene, "shared");
  const Study study = Settled(BuildStudy(scene));
  const SimulationResult reference = Simulate(*study.model, study.initial, study.options);
  ASSERT_FALSE(reference.events.empty());
  constexpr int kThreads = 4;
  std::vector<SimulationResult> results(kThreads);
  std::vector<std::thread> threads;
  for (int i = 0; i < kThreads; ++i) {
    threads.emplace_back([&, i] {
      results[static_cast<size_t>(i)] = Simulate(*study.model, study.initial, study.options);
    });
  }
  for (std::thread& t : threads) t.join();
  for (const SimulationResult& r : results) {
    EXPECT_TRUE(test::SameBits(r.final_state, reference.final_state));
    ASSERT_EQ(r.events.size(), reference.events.size());
    for (size_t e = 0; e < r.events.size(); ++e) EXPECT_EQ(r.events[e].t, reference.events[e].t);
    EXPECT_EQ(r.stats.steps, reference.stats.steps);
  }
}

TEST(SharedModel, RunStudyOfOneDefinitionInFourThreadsMatchesOneThreadBitwise) {
  const Scene scene = LoadSceneText(kScene, "shared");
  const StudyDefinition definition = MakeStudyDefinition(scene);
  const StudyResult reference = RunStudy(definition);
  constexpr int kThreads = 4;
  std::vector<StudyResult> results(kThreads);
  std::vector<std::thread> threads;
  for (int i = 0; i < kThreads; ++i) {
    threads.emplace_back([&, i] { results[static_cast<size_t>(i)] = RunStudy(definition); });
  }
  for (std::thread& t : threads) t.join();
  for (const StudyResult& r : results) {
    ASSERT_EQ(r.rows.size(), reference.rows.size());
    for (size_t k = 0; k < r.rows.size(); ++k) {
      ASSERT_EQ(r.rows[k].size(), reference.rows[k].size());
      EXPECT_EQ(std::memcmp(r.rows[k].data(), reference.rows[k].data(),
                            sizeof(double) * r.rows[k].size()),
                0)
          << "row " << k;
    }
    EXPECT_EQ(r.ledger.residual, reference.ledger.residual);
    ASSERT_EQ(r.final_reactions.size(), 1u);
    EXPECT_EQ(r.final_reactions[0].F_Jc_W, reference.final_reactions[0].F_Jc_W);
  }
}

}  // namespace
}  // namespace chasles
