// The scene loader read directly (no program): how values, units, placements and masses in a
// scene become mass properties. Expected values are Appendix-A formulas written here.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "chasles/scene/scene.h"
#include "chasles/scene/scene_error.h"
#include "test_support.h"

namespace chasles {
namespace {

using test::kExact;
using test::MatNear;
using test::Near;
using ::testing::HasSubstr;

const MassProperties& Body0(const Scene& s) {
  return s.bodies.at(0).mass_properties;
}

TEST(SceneLoader, BareNumbersTakeTheScenesUnits) {
  // 2 lb sphere of radius 3 in: I = 2/5 m r^2.
  const Scene s = LoadSceneText(R"(
units: in, lb
bodies:
  - parts: [{shape: sphere, radius: 3, mass: 2}]
)",
                                "t.yaml");
  const double m = 2 * 0.45359237, r = 3 * 0.0254;
  EXPECT_TRUE(Near(Body0(s).mass(), m, kExact));
  EXPECT_TRUE(Near(Body0(s).I_BBcm_B().Ixx(), 0.4 * m * r * r, kExact));
  EXPECT_EQ(s.bodies[0].name, "body 1");
  EXPECT_EQ(s.units, "in, lb");
}

TEST(SceneLoader, ParametersInAnyOrderAndOverrides) {
  const char* text = R"(
parameters:
  L: 2*half
  half: 0.5 m
  m: 3 kg
bodies:
  - parts: [{shape: rod, length: L, mass: m}]
)";
  const Scene s = LoadSceneText(text, "t.yaml");
  EXPECT_TRUE(Near(Body0(s).I_BBcm_B().Ixx(), 3.0 * 1.0 / 12, kExact));
  SceneOptions o;
  o.parameter_overrides = {{"half", "1 m"}};
  const Scene t = LoadSceneText(text, "t.yaml", o);
  EXPECT_TRUE(Near(Body0(t).I_BBcm_B().Ixx(), 3.0 * 4.0 / 12, kExact));
  ASSERT_EQ(t.parameters.size(), 3u);
}

TEST(SceneLoader, FromToPlacesAxialShapes) {
  // A rod from the origin to (0, 0, 2): centre at z = 1, about the origin Ixx = m L^2 / 3.
  const Scene s = LoadSceneText(R"(
bodies:
  - parts: [{shape: rod, mass: 3 kg, from: [0, 0, 0], to: [0, 0, 2 m]}]
)",
                                "t.yaml");
  EXPECT_TRUE(MatNear(Body0(s).p_BoBcm_B(), Vec3(0, 0, 1), kExact));
  EXPECT_TRUE(Near(Body0(s).CalcInertiaAbout(Vec3::Zero()).Ixx(), 3.0 * 4 / 3, kExact));
  // A cone from its base centre to its apex: centroid a quarter of the way up.
  const Scene c = LoadSceneText(R"(
bodies:
  - parts: [{shape: cone, radius: 1 m, mass: 1 kg, from: [0, 0, 0], to: [4 m, 0, 0]}]
)",
                                "t.yaml");
  EXPECT_TRUE(MatNear(Body0(c).p_BoBcm_B(), Vec3(1, 0, 0), kExact, 1.0));
}

TEST(SceneLoader, OrientationsAgree) {
  // The same cylinder turned so its axis lies along x, four ways: Ixx = m R^2 / 2.
  const double m = 2, R = 0.3, h = 1.2;
  for (const char* orientation : {"axis: [1, 0, 0]", "rotation: {axis: [0, 1, 0], angle: 90 deg}",
                                  "euler: {sequence: ZYX, angles: [0, 90 deg, 0]}",
                                  "quaternion: [0.7071067811865476, 0, 0.7071067811865476, 0]"}) {
    const Scene s = LoadSceneText(std::string(R"(
bodies:
  - parts:
      - shape: cylinder
        radius: 0.3 m
        length: 1.2 m
        mass: 2 kg
        )") + orientation + "\n",
                                  "t.yaml");
    const Mat3 expected =
        Vec3(m * R * R / 2, m * (3 * R * R + h * h) / 12, m * (3 * R * R + h * h) / 12)
            .asDiagonal();
    EXPECT_TRUE(MatNear(Body0(s).I_BBcm_B().matrix(), expected, 1e-15)) << orientation;
  }
}

TEST(SceneLoader, ThinShapesFromDensity) {
  // Steel disk of radius 0.1 m and thickness 2 mm: m = rho pi R^2 t.
  const Scene disk = LoadSceneText(R"(
bodies:
  - parts: [{shape: disk, radius: 0.1 m, material: steel, thickness: 2 mm}]
)",
                                   "t.yaml");
  EXPECT_TRUE(Near(Body0(disk).mass(), 7850 * M_PI * 0.01 * 0.002, kExact));
  // Ring of 0.5 kg/m: m = lambda 2 pi R.
  const Scene ring = LoadSceneText(R"(
bodies:
  - parts: [{shape: ring, radius: 0.2 m, linear_density: 0.5 kg/m}]
)",
                                   "t.yaml");
  EXPECT_TRUE(Near(Body0(ring).mass(), 0.5 * 2 * M_PI * 0.2, kExact));
  EXPECT_TRUE(Near(Body0(ring).I_BBcm_B().Izz(), Body0(ring).mass() * 0.04, kExact));
}

TEST(SceneLoader, CustomPartWithProducts) {
  const Scene s = LoadSceneText(R"(
bodies:
  - parts:
      - shape: custom
        mass: 2 kg
        center_of_mass: [0.1 m, 0, 0]
        inertia: {Ixx: 1 kg*m^2, Iyy: 2 kg*m^2, Izz: 2.5 kg*m^2, Ixy: -0.1 kg*m^2}
)",
                                "t.yaml");
  EXPECT_TRUE(Near(Body0(s).I_BBcm_B().Ixy(), -0.1, kExact));
  EXPECT_TRUE(MatNear(Body0(s).p_BoBcm_B(), Vec3(0.1, 0, 0), kExact));
}

TEST(SceneLoader, DensityFieldEqualsConstantDensity) {
  // A "field" that is constant gives the constant-density result (to the cubature's 1e-10).
  const char* field = R"(
bodies:
  - parts: [{shape: torus, major_radius: 0.3 m, minor_radius: 0.1 m, density: "2700 kg/m^3 + 0 kg/m^4 * x"}]
)";
  const char* constant = R"(
bodies:
  - parts: [{shape: torus, major_radius: 0.3 m, minor_radius: 0.1 m, density: 2700 kg/m^3}]
)";
  const MassProperties a = Body0(LoadSceneText(field, "t.yaml"));
  const MassProperties b = Body0(LoadSceneText(constant, "t.yaml"));
  EXPECT_TRUE(Near(a.mass(), b.mass(), 1e-10));
  EXPECT_TRUE(MatNear(a.I_BBcm_B().matrix(), b.I_BBcm_B().matrix(), 1e-10));
}

TEST(SceneLoader, GravityAsAMagnitudePointsDown) {
  // A magnitude g points along -z (down); in a planar scene along -y. 32.2 ft/s^2 is
  // 32.2 * 0.3048 m/s^2 exactly.
  const char* body = "bodies:\n  - parts: [{shape: sphere, radius: 1 cm, mass: 1 kg}]\n";
  const Scene s = LoadSceneText(std::string("gravity: 32.2 ft/s^2\n") + body, "t.yaml");
  EXPECT_TRUE(s.dynamics.has_gravity);
  EXPECT_TRUE(MatNear(s.dynamics.g_W, Vec3(0, 0, -32.2 * 0.3048), kExact));
  const Scene p = LoadSceneText(
      "planar: true\ngravity: 9.81\nbodies:\n  - parts: [{shape: planar, mass: 1 kg, "
      "inertia_z: 1 kg*m^2}]\n",
      "t.yaml");
  EXPECT_TRUE(MatNear(p.dynamics.g_W, Vec3(0, -9.81, 0), kExact));
  // The same as the vector form.
  const Scene v = LoadSceneText(std::string("gravity: [0, 0, -32.2 ft/s^2]\n") + body, "t.yaml");
  EXPECT_EQ(v.dynamics.g_W, s.dynamics.g_W);
}

TEST(SceneLoader, GravityMagnitudeMustBePositiveAcceleration) {
  const char* body = "bodies:\n  - parts: [{shape: sphere, radius: 1 cm, mass: 1 kg}]\n";
  for (const char* g : {"-9.81 m/s^2", "0 m/s^2", "9.81 m/s", "9.81 N"}) {
    try {
      LoadSceneText(std::string("gravity: ") + g + "\n" + body, "t.yaml");
      ADD_FAILURE() << g;
    } catch (const SceneError& e) {
      EXPECT_EQ(e.line(), 1) << g;
      EXPECT_EQ(e.key(), "gravity") << g;
    }
  }
}

TEST(SceneLoader, ErrorsCarryPosition) {
  try {
    LoadSceneText("bodies:\n  - parts:\n      - {shape: sphere, radius: 2 kg, mass: 1 kg}\n",
                  "t.yaml");
    FAIL();
  } catch (const SceneError& e) {
    EXPECT_EQ(e.line(), 3);
    EXPECT_EQ(e.column(), 33);  // the first character of "2 kg"
    EXPECT_EQ(e.key(), "bodies[0].parts[0].radius");
    EXPECT_THAT(e.message(), HasSubstr("expected length"));
  }
}

// A mapping's keys are checked in file order: the second of a repeated key, and an unknown key
// (with the known ones and a suggestion), each point at that key with its path.
TEST(SceneLoader, RepeatedAndUnknownKeysPointAtTheKey) {
  try {
    LoadSceneText(
        "bodies:\n  - parts:\n      - {shape: sphere, radius: 2 m, mass: 1 kg, "
        "radius: 3 m}\n",
        "t.yaml");
    FAIL() << "loaded";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.line(), 3);
    EXPECT_EQ(e.column(), 50);  // the second "radius"
    EXPECT_EQ(e.key(), "bodies[0].parts[0].radius");
    EXPECT_EQ(e.message(), "key 'radius' appears twice");
  }
  try {
    LoadSceneText(
        "bodies:\n  - name: a\n    parts: [{shape: sphere, radius: 2 m, mass: 1 kg}]\n"
        "    intial: {position: [0 m, 0 m, 0 m]}\n",
        "t.yaml");
    FAIL() << "loaded";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.line(), 4);
    EXPECT_EQ(e.column(), 5);
    EXPECT_EQ(e.key(), "bodies[0].intial");
    EXPECT_THAT(e.message(), HasSubstr("unknown key 'intial' (did you mean 'initial'?) in a body; "
                                       "known keys: name, "));
  }
}

// A density field written with a function after the unit: "1000 kg/m^3 * exp(z/R)" is
// (1000 kg/m^3) * exp(z/R). A box a x b x c centred on its origin has the mass
//   M = rho0 a b integral_{-c/2}^{c/2} exp(z/R) dz = 2 rho0 a b R sinh(c/(2R)),
// met to the cubature's tolerance (1e-10 relative).
TEST(SceneLoader, ADensityFieldWithAFunctionAfterItsUnit) {
  const Scene s = LoadSceneText(R"(
parameters:
  R: 0.5 m
bodies:
  - parts: [{shape: box, size: [1 m, 2 m, 0.4 m], density: 1000 kg/m^3 * exp(z/R)}]
)",
                                "t.yaml");
  const double M = 2 * 1000.0 * 1.0 * 2.0 * 0.5 * std::sinh(0.4 / (2 * 0.5));
  EXPECT_TRUE(Near(Body0(s).mass(), M, 1e-9));
}

// A parameter named like a unit, after a unit and '*', is read as the unit; the error that
// follows says so and how to write the product.
TEST(SceneLoader, AParameterReadAsAUnitIsNamedInTheError) {
  try {
    LoadSceneText(R"(
parameters:
  h: 2
bodies:
  - parts: [{shape: sphere, radius: 3 cm * h, mass: 1 kg}]
)",
                  "t.yaml");
    FAIL() << "loaded";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.line(), 5);
    EXPECT_EQ(e.message(),
              "expected length for the radius, got length*time; 'h' after '3 cm *' was read as "
              "the unit h (a name after a unit and '*' continues the unit, even when a parameter "
              "or variable has that name); to use the parameter 'h' write (3 cm) * h");
  }
}

}  // namespace
}  // namespace chasles
