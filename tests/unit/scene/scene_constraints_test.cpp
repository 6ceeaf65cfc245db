// Scene keys `joints`, `rolling`, `drivers`: values read with units, defaults, and the
// constraints BuildStudy adds to the Model (attachment frames from world poses at the initial
// configuration).

#include <cmath>

#include <fmt/format.h>

// Before gtest: <signal.h> (via gtest) defines a macro si_value, a parameter name in units.h.
#include "chasles/analysis/initial_state.h"
#include "chasles/analysis/instantaneous.h"
#include "chasles/model/string_constraint.h"
#include "chasles/scene/scene.h"
#include "chasles/scene/scene_error.h"
#include "chasles/scene/study.h"
// clang-format off
#include <gmock/gmock.h>
#include <gtest/gtest.h>
// clang-format on
#include "test_support.h"

namespace chasles {
namespace {

/// The scene's study with its initial state settled on the constraints (SettleInitialState),
/// as a run or a solve starts from it.
Study Settled(Study s) {
  std::vector<std::string> warnings;
  s.initial = SettleInitialState(*s.model, s.initial, s.settling, warnings);
  return s;
}

constexpr double kPi = 3.14159265358979323846;

TEST(SceneConstraints, ReadsValuesWithUnitsAndDefaults) {
  const Scene scene = LoadSceneText(R"(
bodies:
  - name: arm
    parts: [{shape: box, size: [1 m, 0.1 m, 0.1 m], mass: 1 kg}]
  - name: wheel
    parts: [{shape: disk, radius: 20 cm, mass: 2 kg}]
joints:
  - {type: revolute, parent: world, child: arm, at: [10 cm, 0, 0], axis: [0, 0, 2]}
  - {name: hub, type: weld, parent: arm, child: wheel, at: [0.5 m, 0, 0]}
rolling:
  - {body: wheel, shape: disk, radius: 20 cm, axis: [0, 0, 1], mu_s: 0.4,
     plane: {normal: [0, 0, 3]}}
drivers:
  - {type: rotation, parent: world, child: arm, at: [10 cm, 0, 0], axis: [0, 0, 1],
     value: {position: 90 deg, velocity: 2 rad/s, acceleration: 3 rad/s^2}}
)",
                                    "constraints");
  const SceneConstraints& c = scene.dynamics.constraints;
  ASSERT_EQ(c.joints.size(), 2u);
  EXPECT_EQ(c.joints[0].name, "joint1");
  EXPECT_EQ(c.joints[0].kind, JointKind::kRevolute);
  EXPECT_EQ(c.joints[0].parent, kWorld);
  EXPECT_EQ(c.joints[0].child, 0);
  EXPECT_NEAR(c.joints[0].p_WJ.x(), 0.1, 1e-15);
  EXPECT_EQ(c.joints[0].axis_W, Vec3(0, 0, 1));  // normalised
  EXPECT_EQ(c.joints[1].name, "hub");
  EXPECT_EQ(c.joints[1].parent, 0);
  EXPECT_EQ(c.joints[1].axis_W, Vec3::UnitZ());  // default for a weld
  ASSERT_EQ(c.rolling.size(), 1u);
  EXPECT_EQ(c.rolling[0].name, "rolling1");
  EXPECT_EQ(c.rolling[0].shape, RollingShape::kDisk);
  EXPECT_DOUBLE_EQ(c.rolling[0].radius, 0.2);
  EXPECT_DOUBLE_EQ(c.rolling[0].mu_s, 0.4);
  EXPECT_EQ(c.rolling[0].plane_normal_W, Vec3::UnitZ());
  ASSERT_EQ(c.drivers.size(), 1u);
  EXPECT_EQ(c.drivers[0].name, "driver1");
  EXPECT_EQ(c.drivers[0].kind, DriverKind::kRotation);
  EXPECT_NEAR(c.drivers[0].f0, kPi / 2, 1e-15);
  EXPECT_DOUBLE_EQ(c.drivers[0].f1, 2.0);
  EXPECT_DOUBLE_EQ(c.drivers[0].f2, 3.0);
  EXPECT_THAT(c.names(), ::testing::ElementsAre("joint1", "hub", "rolling1", "driver1"));
}

TEST(SceneConstraints, ADriverValueOfTheWrongDimensionIsAnError) {
  try {
    LoadSceneText(R"(
bodies:
  - name: block
    parts: [{shape: box, size: [1 m, 1 m, 1 m], mass: 1 kg}]
drivers:
  - {type: translation, parent: world, child: block, at: [0, 0, 0], axis: [1, 0, 0],
     value: {velocity: 2 rad/s}}
)",
                  "driver");
    FAIL() << "expected a SceneError";
  } catch (const SceneError& e) {
    EXPECT_THAT(e.what(), ::testing::HasSubstr("drivers[0].value.velocity"));
  }
}

// A sphere (mass m, radius r, I = 2/5 m r²) hinged about y at a point a distance d from its
// centre along +x, released at rest; the body is turned 90° about z and placed away from the
// origin so that the attachment frames differ from W. About the pin (eq. 8.29):
//   α_y = -m g d / (I + m d²); a_cm,z = -α_y d, so the pin pushes up with
//   F_z = m g + m a_cm,z = m g I / (I + m d²).
TEST(SceneConstraints, BuildStudyPlacesTheJointAtTheWorldPoint) {
  const Scene scene = LoadSceneText(R"(
bodies:
  - name: bob
    parts: [{shape: sphere, radius: 0.1 m, mass: 3 kg}]
    initial: {position: [1 m, 2 m, 3 m], rotation: {axis: [0, 0, 1], angle: 90 deg}}
gravity: [0, 0, -9.8 m/s^2]
joints:
  - {name: pin, type: revolute, parent: world, child: bob, at: [1.4 m, 2 m, 3 m],
     axis: [0, 1, 0]}
simulation: {until: 1 s}
)",
                                    "pendulum");
  const Study study = Settled(BuildStudy(scene));
  ASSERT_EQ(study.model->num_constraints(), 1);
  EXPECT_EQ(study.model->constraint(0).name(), "pin");
  EXPECT_EQ(study.model->constraint(0).kind(), "revolute");
  const InstantaneousSolution s = SolveInstantaneous(*study.model, study.initial);
  const double m = 3, r = 0.1, d = 0.4, g = 9.8;
  const double I = 0.4 * m * r * r;
  const double alpha = -m * g * d / (I + m * d * d);
  EXPECT_NEAR(s.bodies[0].alpha_WB_W.y(), alpha, 1e-12 * std::abs(alpha));
  EXPECT_NEAR(s.bodies[0].alpha_WB_W.x(), 0.0, 1e-12 * std::abs(alpha));
  ASSERT_EQ(s.reactions.size(), 1u);
  EXPECT_NEAR(s.reactions[0].p_WJ.x(), 1.4, 1e-12);
  EXPECT_NEAR(s.reactions[0].F_Jc_W.z(), m * g * I / (I + m * d * d), 1e-12 * m * g);
  EXPECT_NEAR(s.reactions[0].F_Jc_W.x(), 0.0, 1e-12 * m * g);
}

// A planar yo-yo (examples/yo-yo.yaml) whose disk sits 1 cm off the plane along z: the offset
// plays no part in plane motion, so the string's drum, at the centre of mass by default, is its
// projection on the plane, z = 0, and the yo-yo falls as the flat one does. Its hub (radius r)
// rolls down the string, v = omega r, so m a = m g - T and I a / r = T r give
//   a = g / (1 + I/(m r^2)),  I = m R^2/2 (a cylinder about its axis; Appendix A).
TEST(SceneConstraints, APlanarStringsDrumIsTheCentreOfMassInThePlane) {
  const double R = 0.03, r = 0.008, g = 9.81;  // m = 0.2 kg cancels
  for (const char* offset : {"0", "1 cm"}) {
    const Scene scene = LoadSceneText(fmt::format(R"(
planar: true
bodies:
  - name: yoyo
    parts: [{{shape: cylinder, radius: 3 cm, length: 2 cm, mass: 0.2 kg, position: [0, 0, {}]}}]
gravity: 9.81 m/s^2
strings:
  - name: string
    from: {{body: world, at: [-8 mm, 1 m]}}
    to: {{body: yoyo, radius: 8 mm, sense: counterclockwise}}
)",
                                                  offset),
                                      "yoyo.yaml");
    const Study study = Settled(BuildStudy(scene, 1.0));
    const auto& string = dynamic_cast<const StringConstraint&>(study.model->constraint(0));
    // The drum's centre in B: the centre of mass's x and y, in the plane z = 0.
    EXPECT_EQ(string.end_b().p_BoP_B, Vec3::Zero()) << offset;
    const InstantaneousSolution s = SolveInstantaneous(*study.model, study.initial);
    const double a = g / (1 + R * R / (2 * r * r));
    EXPECT_NEAR(s.bodies[0].a_WBcm_W.y(), -a, 1e-12 * g) << offset;
  }
}

// In 3-D the ends of a string with a drum must lie in the plane normal to 'normal'; an end
// left at its body's centre of mass off that plane is named, with what to give.
TEST(SceneConstraints, AStringOffItsPlaneNamesThePointAndWhatToGive) {
  const Scene scene = LoadSceneText(R"(
bodies:
  - name: spool
    parts: [{shape: cylinder, radius: 3 cm, length: 2 cm, mass: 0.2 kg}]
    initial: {position: [0, 0, 5 cm]}
strings:
  - name: string
    from: {body: world, at: [-8 mm, 1 m, 0]}
    to: {body: spool, radius: 8 mm, sense: counterclockwise}
)",
                                    "spool.yaml");
  try {
    BuildStudy(scene, 1.0);
    FAIL() << "built";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), ::testing::HasSubstr(
                              "but the 'to' end's drum centre (no 'at': its body's centre of "
                              "mass) at [0, 0, 0.05] is 0.05 m off the plane through the 'from' "
                              "end's point; give the points in one plane ('at' of an end, "
                              "'center' of a pulley), or set 'normal'"));
  }
}

}  // namespace
}  // namespace chasles
