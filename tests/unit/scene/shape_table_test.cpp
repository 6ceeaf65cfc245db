// The round shells and the hollow cone read from scene text: their keys (`closed`, a cone's
// `thickness`), their mass sources (areal density, or thickness with a density) and their
// errors. The closed forms are derived in tests/unit/mass/round_shells_test.cpp; here they are
// restated with the scene's numbers.

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "chasles/scene/scene.h"
#include "chasles/scene/scene_error.h"
#include "test_support.h"

namespace chasles {
namespace {

using std::numbers::pi;
using test::MatNear;
using test::Near;
using ::testing::HasSubstr;

// Closed forms against the loader's unit conversions and sums: a few dozen roundings.
constexpr double kClosedForm = 1e-12;

const ScenePart& Part0(const Scene& s) {
  return s.bodies.at(0).parts.at(0);
}

Scene Load(const std::string& parts) {
  return LoadSceneText("bodies:\n  - parts:\n      - " + parts + "\n", "t.yaml");
}

// The message of the SceneError loading `parts` gives, or "" when it loads.
std::string ErrorOf(const std::string& parts) {
  try {
    Load(parts);
  } catch (const SceneError& e) {
    return e.what();
  }
  return "";
}

TEST(ShapeTable, ConicalShellTakesAnArealDensityOrAThickness) {
  // R 30 cm, h 40 cm: slant s = 50 cm, lateral area π R s, base π R².
  const double R = 0.3, h = 0.4, s = 0.5;
  const Scene open =
      Load("{shape: conical_shell, radius: 30 cm, height: 40 cm, areal_density: 2 kg/m^2}");
  const MassProperties& mp = open.bodies.at(0).mass_properties;
  EXPECT_TRUE(Near(mp.mass(), 2 * pi * R * s, kClosedForm));
  EXPECT_TRUE(MatNear(mp.p_BoBcm_B(), Vec3(0, 0, h / 3), kClosedForm, h));
  EXPECT_TRUE(Near(mp.I_BBcm_B().Izz(), mp.mass() * R * R / 2, kClosedForm));
  EXPECT_TRUE(Near(mp.I_BBcm_B().Ixx(), mp.mass() * (R * R / 4 + h * h / 18), kClosedForm));
  EXPECT_TRUE(Near(Part0(open).surface_area, pi * R * s, kClosedForm));
  EXPECT_EQ(Part0(open).volume, 0.0);
  // Steel sheet 2 mm thick, closed by its base: ρ t π R (s + R).
  const Scene closed = Load(
      "{shape: conical_shell, radius: 30 cm, height: 40 cm, closed: true, material: steel, "
      "thickness: 2 mm}");
  EXPECT_TRUE(Near(closed.bodies.at(0).mass_properties.mass(), 7850 * 0.002 * pi * R * (s + R),
                   kClosedForm));
  EXPECT_TRUE(Near(Part0(closed).surface_area, pi * R * (s + R), kClosedForm));
  // From the base centre to the apex: the centroid a third of the way up, along x here.
  const Scene placed =
      Load("{shape: conical_shell, radius: 30 cm, mass: 1 kg, from: [0, 0, 0], to: [40 cm, 0, 0]}");
  EXPECT_TRUE(
      MatNear(placed.bodies.at(0).mass_properties.p_BoBcm_B(), Vec3(h / 3, 0, 0), kClosedForm, h));
}

// The cone with a wall: the cone minus the inner cone, open (inner radius R - t s/h, height
// h - t s/R, on the same base) or closed (inner base at z = t, height h - t s/R - t, radius in
// proportion).
TEST(ShapeTable, ConeWithThicknessIsHollow) {
  const double R = 0.3, h = 0.4, s = 0.5, t = 0.01, rho = 2700;
  const double V = pi * R * R * h / 3;
  const double ho = h - t * s / R, hc = h - t * s / R - t;
  const double k_open = ho / h, k_closed = hc / h;  // the inner cones in proportion
  const Scene open =
      Load("{shape: cone, radius: 30 cm, height: 40 cm, thickness: 1 cm, material: aluminium}");
  EXPECT_TRUE(Near(Part0(open).volume, V * (1 - std::pow(k_open, 3)), kClosedForm));
  EXPECT_TRUE(Near(open.bodies.at(0).mass_properties.mass(), rho * V * (1 - std::pow(k_open, 3)),
                   kClosedForm));
  EXPECT_TRUE(Near(Part0(open).surface_area,
                   pi * R * s * (1 + k_open * k_open) + pi * R * R * (1 - k_open * k_open),
                   kClosedForm));
  const Scene closed = Load(
      "{shape: cone, radius: 30 cm, height: 40 cm, thickness: 1 cm, closed: true, density: 2700 "
      "kg/m^3}");
  EXPECT_TRUE(Near(closed.bodies.at(0).mass_properties.mass(),
                   rho * V * (1 - std::pow(k_closed, 3)), kClosedForm));
  EXPECT_TRUE(
      Near(Part0(closed).surface_area, pi * R * (R + s) * (1 + k_closed * k_closed), kClosedForm));
  // The dimensions the report draws include the wall and the switch.
  const auto& dims = Part0(closed).geometry.dimensions;
  EXPECT_NE(std::find(dims.begin(), dims.end(),
                      std::pair<std::string, std::vector<double>>("thickness", {t})),
            dims.end());
  EXPECT_NE(std::find(dims.begin(), dims.end(),
                      std::pair<std::string, std::vector<double>>("closed", {1.0})),
            dims.end());
  // A solid cone is unchanged: volume π R² h / 3.
  EXPECT_TRUE(Near(Part0(Load("{shape: cone, radius: 30 cm, height: 40 cm, mass: 1 kg}")).volume, V,
                   kClosedForm));
}

TEST(ShapeTable, OtherRoundShellsLoad) {
  const double R = 0.2, h = 0.5, r = 0.05;
  EXPECT_TRUE(Near(Load("{shape: hemispherical_shell, radius: 20 cm, areal_density: 1 kg/m^2}")
                       .bodies.at(0)
                       .mass_properties.mass(),
                   2 * pi * R * R, kClosedForm));
  EXPECT_TRUE(Near(Load("{shape: hemispherical_shell, radius: 20 cm, closed: yes, areal_density: "
                        "1 kg/m^2}")
                       .bodies.at(0)
                       .mass_properties.mass(),
                   3 * pi * R * R, kClosedForm));
  EXPECT_TRUE(Near(Load("{shape: cylindrical_shell, radius: 20 cm, length: 50 cm, closed: true, "
                        "areal_density: 1 kg/m^2}")
                       .bodies.at(0)
                       .mass_properties.mass(),
                   2 * pi * R * h + 2 * pi * R * R, kClosedForm));
  EXPECT_TRUE(Near(Load("{shape: toroidal_shell, major_radius: 20 cm, minor_radius: 5 cm, "
                        "areal_density: 1 kg/m^2}")
                       .bodies.at(0)
                       .mass_properties.mass(),
                   4 * pi * pi * R * r, kClosedForm));
}

TEST(ShapeTable, WallAndSwitchErrorsNameTheKeyAndTheRule) {
  // R 30 cm, h 40 cm: the open wall must be thinner than R h / s = 24 cm, the closed one than
  // R h / (R + s) = 15 cm.
  EXPECT_THAT(ErrorOf("{shape: cone, radius: 30 cm, height: 40 cm, thickness: 24 cm, mass: 1 kg}"),
              HasSubstr("cone: thickness 0.24 m must be smaller than 0.24 m"));
  EXPECT_THAT(ErrorOf("{shape: cone, radius: 30 cm, height: 40 cm, thickness: 20 cm, closed: "
                      "true, mass: 1 kg}"),
              HasSubstr("the radius of the sphere inscribed in the cone"));
  EXPECT_THAT(ErrorOf("{shape: cone, radius: 30 cm, height: 40 cm, thickness: -1 cm, mass: 1 kg}"),
              HasSubstr("the thickness (wall thickness of a hollow cone, normal to its side) must "
                        "be positive"));
  EXPECT_THAT(ErrorOf("{shape: cone, radius: 30 cm, height: 40 cm, closed: true, mass: 1 kg}"),
              HasSubstr("'closed' is for a hollow cone: give its wall 'thickness' too"));
  EXPECT_THAT(
      ErrorOf("{shape: conical_shell, radius: 30 cm, height: 40 cm, closed: 2, mass: 1 kg}"),
      HasSubstr("'closed' is a switch: expected true or false (true adds the base disk), got the "
                "value '2'"));
  EXPECT_THAT(ErrorOf("{shape: conical_shell, radius: 30 cm, mass: 1 kg}"), HasSubstr("height"));
  EXPECT_THAT(ErrorOf("{shape: conical_shell, radius: 30 cm, height: 40 cm, material: steel}"),
              HasSubstr("a conical_shell is a thin sheet (an area, no volume): give 'thickness'"));
  EXPECT_THAT(ErrorOf("{shape: cone, radius: 30 cm, height: 40 cm, thickness: 1 cm, "
                      "areal_density: 2 kg/m^2}"),
              HasSubstr("'areal_density' does not fit a cone: use 'density'"));
  EXPECT_THAT(ErrorOf("{shape: sphere, radius: 30 cm, thickness: 1 cm, material: steel}"),
              HasSubstr("'thickness' is for thin sheets"));
  EXPECT_THAT(ErrorOf("{shape: toroidal_shell, major_radius: 30 cm, minor_radius: 30 cm, "
                      "mass: 1 kg}"),
              HasSubstr("minor radius 0.3 m must be smaller than major radius 0.3 m"));
}

}  // namespace
}  // namespace chasles
