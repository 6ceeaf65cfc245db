// BuildStudy: a scene's dynamics as Model + initial State + SimulationOptions for Simulate;
// MakeStudyDefinition: a definition whose run builds each Model once.

#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

// Before gtest: <signal.h> (via gtest) defines a macro si_value, a parameter name in units.h.
#include "chasles/analysis/study.h"
#include "chasles/integrate/simulate.h"
#include "chasles/scene/study.h"
// clang-format off
#include <gtest/gtest.h>
// clang-format on
#include "test_paths.h"
#include "test_support.h"

namespace chasles {
namespace {

// Spring-mass with a state-dependent applied force f = -k2 (x - L0) added to a spring k1:
// the total stiffness is k1 + k2, so the period is 2 pi sqrt(m / (k1 + k2)).
TEST(BuildStudy, StateDependentForceAndEventsReachSimulate) {
  const Scene scene = LoadSceneText(R"(
bodies:
  - name: block
    parts: [{shape: box, size: [4 cm, 4 cm, 4 cm], mass: 2 kg}]
    initial: {position: [0.55 m, 0, 0]}
forces:
  - {type: spring, from: {body: block}, to: {world: [0, 0, 0]}, rest_length: 0.5 m, stiffness: 500 N/m}
  - {type: force, body: block, value: [-300 N/m * (block_x - 0.5 m), 0, 0]}
events:
  - {name: turn, when: block_vx, direction: falling, action: stop}
simulation: {until: 5 s, tolerance: 1e-12}
)",
                                    "study");
  const Study study = BuildStudy(scene);
  ASSERT_EQ(study.model->num_bodies(), 1);
  ASSERT_EQ(study.model->num_force_elements(), 2);
  const SimulationResult r = Simulate(*study.model, study.initial, study.options);
  ASSERT_TRUE(r.stopped_by_event);
  EXPECT_NEAR(r.final_state.t, 2 * M_PI * std::sqrt(2.0 / 800.0), 1e-9);
}

// The definition carries the Model it checked its inputs on, and the run starts on it: the
// ModelBuilder is called only for the composite body after an embedding. The bullet of
// examples/bullet-embeds-in-block.yaml (m = 0.02 kg at v = 400 m/s into a block of M = 2 kg)
// leaves the composite at v_c = m v / (M + m) = 400/101 m/s (conservation of momentum).
TEST(MakeStudyDefinition, ARunBuildsEachModelOnce) {
  const Scene scene =
      LoadSceneFile(std::string(test::SourceDir()) + "/examples/bullet-embeds-in-block.yaml");
  StudyDefinition def = MakeStudyDefinition(scene);
  ASSERT_NE(def.model, nullptr);
  EXPECT_EQ(def.model->num_bodies(), 2);
  const auto builds = std::make_shared<int>(0);
  const ModelBuilder build = def.build_model;
  def.build_model = [build, builds](const std::vector<NamedBody>& bodies, const BodyMap& map) {
    ++*builds;
    return build(bodies, map);
  };
  const StudyResult r = RunStudy(def);
  EXPECT_EQ(*builds, 1);  // the composite's Model after the impact, and no other
  ASSERT_EQ(r.final_bodies.size(), 1u);
  const double v_c = 0.02 * 400.0 / 2.02;
  EXPECT_NEAR(r.final_bodies[0].v_WBcm_W.y(), v_c, 1e-12 * v_c);
  // Without an embedding no Model is built by the run at all.
  StudyDefinition free_flight = MakeStudyDefinition(LoadSceneText(R"(
bodies:
  - name: ball
    parts: [{shape: sphere, radius: 1 cm, mass: 1 kg}]
simulation: {until: 1 s}
)",
                                                                  "ball"));
  free_flight.build_model = [builds](const std::vector<NamedBody>&, const BodyMap&) -> Model {
    ++*builds;
    throw std::logic_error("built again");
  };
  EXPECT_NO_THROW(RunStudy(free_flight));
  EXPECT_EQ(*builds, 1);
}

}  // namespace
}  // namespace chasles
