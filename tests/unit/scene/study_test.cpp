// BuildStudy: a scene's dynamics as Model + initial State + SimulationOptions for Simulate.

#include <cmath>

// Before gtest: <signal.h> (via gtest) defines a macro si_value, a parameter name in units.h.
#include "chasles/integrate/simulate.h"
#include "chasles/scene/study.h"
// clang-format off
#include <gtest/gtest.h>
// clang-format on
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

}  // namespace
}  // namespace chasles
