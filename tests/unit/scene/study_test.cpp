// BuildStudy: a scene's dynamics as Model + initial State + SimulationOptions for Simulate;
// MakeStudyDefinition: a definition whose run builds each Model once, settles the initial
// state on the constraints and brings its errors back at their scene entries.

#include <algorithm>
#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <fmt/format.h>

// Before gtest: <signal.h> (via gtest) defines a macro si_value, a parameter name in units.h.
#include "chasles/analysis/initial_state.h"
#include "chasles/analysis/study.h"
#include "chasles/integrate/simulate.h"
#include "chasles/scene/scene_error.h"
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

/// The 1-based number of the first line of `text` that contains `needle` (0: none).
int LineOf(const std::string& text, const std::string& needle) {
  const size_t at = text.find(needle);
  if (at == std::string::npos) return 0;
  return 1 + static_cast<int>(std::count(text.begin(), text.begin() + static_cast<long>(at), '\n'));
}

/// The SceneError the analysis layer's RunStudy throws for the scene's definition, which is
/// made without one (the engine's errors come from the run, located by the definition); fails
/// the test when it throws none.
SceneError RunError(const Scene& scene) {
  const StudyDefinition definition = MakeStudyDefinition(scene);
  try {
    RunStudy(definition);
  } catch (const SceneError& e) {
    return e;
  }
  ADD_FAILURE() << "expected a SceneError";
  return SceneError("", 0, 0, "", "");
}

// A force whose expression divides by zero stops the run at once; the error points at that
// force's expression, whatever the force is called: a name found nowhere else, or one that is
// part of another force's name (the error carries the element, no message is searched).
TEST(RunStudy, NonFiniteForcePointsAtItsExpressionWhateverItsName) {
  for (const std::string name : {"q9x", "push"}) {
    const std::string text = R"(
bodies:
  - name: block
    parts: [{shape: sphere, radius: 0.1 m, mass: 1 kg}]
forces:
  - {type: force, name: pushing, body: block, value: [1 N, 0 N, 0 N]}
  - type: force
    name: )" + name + R"(
    body: block
    value: [1 N*s / (t - t), 0 N, 0 N]
simulation: {until: 1 s}
)";
    const Scene scene = LoadSceneText(text, "study");
    const SceneSpot& at = scene.dynamics.forces[1].expression_where;
    const SceneError e = RunError(scene);
    EXPECT_EQ(e.line(), LineOf(text, "value: [1 N*s")) << name;
    EXPECT_EQ(e.line(), at.line) << name;
    EXPECT_EQ(e.column(), at.column) << name;
    EXPECT_NE(e.message().find("force element '" + name + "' evaluated to infinite"),
              std::string::npos)
        << e.what();
  }
}

// A rolling contact that cannot be assembled with a weld (the wheel is held 1 m above the
// floor it rolls on) points at the rolling entry, called by a name found nowhere else, by a
// name that is part of the weld's name, or by the wheel body's own name.
TEST(RunStudy, UnassembledConstraintPointsAtItsEntryWhateverItsName) {
  for (const std::string name : {"k2v", "road", "wheel"}) {
    const std::string text = R"(
bodies:
  - name: wheel
    parts: [{shape: disk, radius: 0.3 m, mass: 2 kg, axis: [0, 1, 0]}]
    initial: {position: [0, 0, 1 m]}
joints:
  - {name: roadside, type: weld, parent: world, child: wheel, at: [0, 0, 1 m]}
rolling:
  - {name: )" + name + R"(, body: wheel, shape: disk, radius: 0.3 m, axis: [0, 1, 0],
     plane: {point: [0, 0, 0], normal: [0, 0, 1]}}
simulation: {until: 1 s}
)";
    const Scene scene = LoadSceneText(text, "study");
    const SceneSpot& at = scene.dynamics.constraints.rolling[0].where;
    const SceneError e = RunError(scene);
    EXPECT_EQ(e.line(), LineOf(text, "{name: " + name + ","));
    EXPECT_EQ(e.line(), at.line) << name;
    EXPECT_EQ(e.column(), at.column) << name;
    EXPECT_NE(e.message().find("constraint '" + name + "' cannot be satisfied"), std::string::npos)
        << e.what();
  }
}

// A rod of length L (a box L x c x c, mass m) pinned at its end by a revolute joint about y,
// its centre of mass given the velocity [0, 0, -u] and no angular velocity: not a motion the pin
// allows. The run starts from the nearest consistent state, mass-weighted: the pin leaves
// ω = ω ŷ and v = ω × r = [0, 0, -ω L/2] (r = [L/2, 0, 0]), and the least
// m |Δv|² + I_yy ω² over ω (I_yy = m (L² + c²)/12 about the centre, Appendix A) is at
//   ω = (L/2) u / ((L² + c²)/12 + L²/4).
// The settling is the analysis layer's, at the start of RunStudy: the definition keeps the
// state as given, and the run's warnings name each changed value.
TEST(RunStudy, ProjectsTheInitialStateOntoThePinMassWeighted) {
  const double L = 1.0, c = 0.04, u = 1.0;
  const Scene scene = LoadSceneText(R"(
bodies:
  - name: rod
    parts: [{shape: box, size: [1 m, 4 cm, 4 cm], mass: 2 kg}]
    initial: {position: [0.5 m, 0, 0], velocity: [0, 0, -1 m/s]}
joints:
  - {name: pin, type: revolute, parent: world, child: rod, at: [0, 0, 0], axis: [0, 1, 0]}
project_initial: true
simulation: {until: 0.1 s, output_interval: 0.1 s}
)",
                                    "pin.yaml");
  const StudyDefinition def = MakeStudyDefinition(scene);
  ASSERT_TRUE(def.settle_initial.has_value());
  EXPECT_TRUE(def.settle_initial->project);
  EXPECT_TRUE(def.initial.bodies[0].v_WBcm_W == Vec3(0, 0, -u));  // as given
  std::vector<std::string> warnings;
  const State settled = SettleInitialState(*def.model, def.initial, *def.settle_initial, warnings);
  const double w = (L / 2) * u / ((L * L + c * c) / 12 + L * L / 4);
  const BodyState& b = settled.bodies[0];
  EXPECT_TRUE(test::MatNear(b.q_WB * b.w_WB_B, Vec3(0, w, 0), 1e-12));
  EXPECT_TRUE(test::MatNear(b.v_WBcm_W, Vec3(0, 0, -w * L / 2), 1e-12));
  EXPECT_TRUE(test::MatNear(b.p_WBcm, Vec3(L / 2, 0, 0), 1e-12));
  const std::vector<std::string> expected = {
      fmt::format("initial state projected onto the constraints: body 'rod': velocity of its "
                  "centre of mass [0, 0, -1] m/s -> [0, 0, {:.6g}] m/s",
                  -w * L / 2),
      fmt::format("initial state projected onto the constraints: body 'rod': angular velocity "
                  "[0, 0, 0] rad/s -> [0, {:.6g}, 0] rad/s",
                  w)};
  EXPECT_EQ(warnings, expected);
  // The run settles the same way, with the same warnings.
  const StudyResult r = RunStudy(def);
  EXPECT_EQ(r.warnings, expected);
}

// Without `project_initial: true` the same state is an error at the body's `initial` entry,
// thrown by the run (the definition is made), with what to give.
TEST(RunStudy, AnInitialStateOffThePinIsAnErrorAtItsInitialEntry) {
  const std::string text = R"(
bodies:
  - name: rod
    parts: [{shape: box, size: [1 m, 4 cm, 4 cm], mass: 2 kg}]
    initial: {position: [0.5 m, 0, 0], velocity: [0, 0, -1 m/s]}
joints:
  - {name: pin, type: revolute, parent: world, child: rod, at: [0, 0, 0], axis: [0, 1, 0]}
simulation: {until: 0.1 s, output_interval: 0.1 s}
)";
  const Scene scene = LoadSceneText(text, "pin.yaml");
  const SceneSpot& at = scene.dynamics.initial[0].where;
  const SceneError e = RunError(scene);
  EXPECT_EQ(e.file(), "pin.yaml");
  EXPECT_EQ(e.line(), LineOf(text, "initial: {position"));
  EXPECT_EQ(e.line(), at.line);
  EXPECT_EQ(e.column(), at.column);
  EXPECT_EQ(e.key(), at.key);
  EXPECT_NE(e.message().find("the initial state violates the constraints"), std::string::npos)
      << e.what();
  EXPECT_NE(e.message().find("revolute 'pin' (body 'rod')"), std::string::npos) << e.what();
}

}  // namespace
}  // namespace chasles
