// The pieces of a sweep (chasles/scene/sweep.h): the grid's order and values, the quantities'
// grammar and values.

#include "chasles/scene/sweep.h"

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "chasles/error.h"
#include "chasles/scene/scene.h"
#include "chasles/scene/scene_error.h"

namespace chasles {
namespace {

constexpr const char* kScene = R"(chasles: 1
parameters:
  a: 2 m
  b: 30 deg
  c: 5
bodies:
  - name: box
    parts: [{shape: box, size: [a, 1 m, 1 m], mass: 1 kg}]
)";

TEST(SweepGrid, LastParameterVariesFastestAndValuesAreEvenlySpaced) {
  const Scene scene = LoadSceneText(kScene, "grid.yaml");
  const SweepGrid grid =
      MakeSweepGrid(scene, {ParseSweep("a=1 m:3 m:3"), ParseSweep("b=0 deg:90 deg:4")}, 100);
  ASSERT_EQ(grid.parameters.size(), 12);
  EXPECT_EQ(grid.parameters.units[0], "m");
  EXPECT_EQ(grid.parameters.units[1], "rad");  // swept in deg: an angle, its column SI rad
  // Point k = 4 i_a + i_b.
  for (std::int64_t k = 0; k < grid.parameters.size(); ++k) {
    const std::vector<int> i = grid.parameters.Indices(k);
    EXPECT_EQ(i[0], k / 4);
    EXPECT_EQ(i[1], k % 4);
    const std::vector<double> v = grid.parameters.Values(k);
    EXPECT_EQ(grid.parameters.PointOf(v), k);
    // START + (STOP - START) i / (COUNT - 1), with 90 deg = pi/2 rad.
    EXPECT_DOUBLE_EQ(v[0], 1.0 + i[0]);
    EXPECT_NEAR(v[1], 3.14159265358979323846 / 2 * i[1] / 3, 1e-15);
    // The loaded scene's values are the grid's.
    const Scene at = LoadSceneText(kScene, "grid.yaml", grid.PointOptions({}, v));
    EXPECT_EQ(at.parameters[0].second.value, v[0]);
    EXPECT_EQ(at.parameters[1].second.value, v[1]);
  }
  EXPECT_THROW(MakeSweepGrid(scene, {ParseSweep("a=1 m:3 m:11"), ParseSweep("c=0:1:10")}, 100),
               SceneError);
  EXPECT_THROW(MakeSweepGrid(scene, {ParseSweep("a=1 s:3 m:3")}, 100), SceneError);
  EXPECT_THROW(MakeSweepGrid(scene, {ParseSweep("d=1:3:3")}, 100), SceneError);
}

TEST(SweepGrid, AParameterIsAnAngleWhenItsEndsAreWrittenInAngleUnits) {
  // A pure number carries an angle only by its unit: START or STOP in rad, deg, rev, rpm or
  // cps; "rpm" makes 1/time an angular velocity.
  EXPECT_EQ(SweepParameterUnit(ParseSweep("b=0 deg:1:3"), kDimensionless), "rad");
  EXPECT_EQ(SweepParameterUnit(ParseSweep("b=0:0.5*rev:3"), kDimensionless), "rad");
  EXPECT_EQ(SweepParameterUnit(ParseSweep("c=0:1:3"), kDimensionless), "");
  EXPECT_EQ(SweepParameterUnit(ParseSweep("c=0:degree_of_x:3"), kDimensionless), "");
  EXPECT_EQ(SweepParameterUnit(ParseSweep("w=0 rpm:10 rpm:3"), Dimension{0, 0, -1}), "rad/s");
  EXPECT_EQ(SweepParameterUnit(ParseSweep("f=0/s:10/s:3"), Dimension{0, 0, -1}), "1/s");
}

TEST(SweepQuantity, ReadsEachForm) {
  using Kind = SweepQuantity::Kind;
  EXPECT_EQ(ParseSweepQuantity("t_end").kind, Kind::kTEnd);
  const SweepQuantity f = ParseSweepQuantity(" max( ball_vx ) ");
  EXPECT_EQ(f.kind, Kind::kMax);
  EXPECT_EQ(f.column, "ball_vx");
  EXPECT_EQ(f.text, "max(ball_vx)");
  const SweepQuantity e = ParseSweepQuantity("event(leaves wall, 2)");
  EXPECT_EQ(e.kind, Kind::kEvent);
  EXPECT_EQ(e.event, "leaves wall");
  EXPECT_EQ(e.k, 2);
  const SweepQuantity d = ParseSweepQuantity("event(starts-rolling, 3) - event(lift-off)");
  EXPECT_EQ(d.kind, Kind::kEventDifference);
  EXPECT_EQ(d.event, "starts-rolling");
  EXPECT_EQ(d.k, 3);
  EXPECT_EQ(d.event2, "lift-off");
  EXPECT_EQ(d.k2, 1);
  for (const char* bad : {"final()", "max(a,b)", "event()", "event(a,0)", "event(a,x)",
                          "event(a)-event(b)-event(c)", "t", "final(a)-event(b)", "sum(x)"}) {
    EXPECT_THROW(ParseSweepQuantity(bad), SceneError) << bad;
  }
}

TEST(SweepQuantity, ValuesOfARun) {
  StudyResult r;
  r.columns = {"t", "x"};
  r.rows = {{0.0, 1.0}, {1.0, 3.0}, {2.0, 2.0}};
  r.t_end = 2.0;
  // An event between samples, lower than any of them.
  r.events.push_back({"low", 0.5, false, {}, {0.5, -4.0}});
  r.events.push_back({"low", 1.5, false, {}, {1.5, 5.0}});
  EXPECT_EQ(SweepQuantityValue(r, ParseSweepQuantity("final(x)")), 2.0);
  EXPECT_EQ(SweepQuantityValue(r, ParseSweepQuantity("min(x)")), -4.0);
  EXPECT_EQ(SweepQuantityValue(r, ParseSweepQuantity("max(x)")), 5.0);
  EXPECT_EQ(SweepQuantityValue(r, ParseSweepQuantity("event(low,2)-event(low)")), 1.0);
  EXPECT_EQ(SweepQuantityValue(r, ParseSweepQuantity("t_end")), 2.0);
  EXPECT_THROW(SweepQuantityValue(r, ParseSweepQuantity("event(low, 3)")), InputError);
  EXPECT_THROW(SweepQuantityValue(r, ParseSweepQuantity("final(y)")), InputError);
}

// A quantity a run cannot give leaves only its own cell empty. A ball dropped from rest at
// height h falls z = h - g t^2/2, so it reaches the ground at sqrt(2 h / g) and stands at
// h - g T^2/2 when the run ends at T = 1 s: dropped from 5 m or 9 m it has not landed by then
// (sqrt(2 h/g) > 1 s), and only event(ground) is missing from those rows.
TEST(SimulateSweep, AQuantityThatCannotBeHadLeavesOnlyItsCellEmpty) {
  const char* text = R"(
parameters:
  h: 1 m
bodies:
  - name: ball
    parts: [{shape: sphere, radius: 1 cm, mass: 1 kg}]
    initial: {position: [0, 0, h]}
gravity: [0, 0, -9.81 m/s^2]
events:
  - {name: ground, when: ball_z, crosses: 0 m, direction: falling, action: record}
simulation: {until: 1 s, tolerance: 1e-12}
)";
  const auto load = [text](const SceneOptions& o) { return LoadSceneText(text, "drop.yaml", o); };
  const std::vector<SweepQuantity> quantities = {ParseSweepQuantity("event(ground)"),
                                                 ParseSweepQuantity("final(ball_z)")};
  const SceneStudySweep sweep =
      MakeStudySweep(load, {}, {ParseSweep("h=1 m:9 m:3")}, quantities, {}, 100);
  SweepRunOptions options;
  options.jobs = 1;
  const SweepTable t =
      SimulateSweep(sweep.grid.parameters, quantities, sweep.units, sweep.point, options);
  const double g = 9.81, T = 1.0;
  ASSERT_EQ(t.rows.size(), 3u);
  ASSERT_EQ(t.errors.size(), 3u);
  EXPECT_EQ(t.columns, (std::vector<std::string>{"h", "event(ground)", "final(ball_z)"}));
  for (size_t i = 0; i < 3; ++i) {
    const double h = 1.0 + 4.0 * static_cast<double>(i);
    // Free fall is a quadratic in t, which the integrator follows to round-off.
    EXPECT_NEAR(t.rows[i][2], h - g * T * T / 2, 1e-12 * h) << h;
    if (i == 0) {
      EXPECT_NEAR(t.rows[i][1], std::sqrt(2 * h / g), 1e-12) << h;
      EXPECT_EQ(t.errors[i], "");
    } else {
      EXPECT_TRUE(std::isnan(t.rows[i][1])) << h;
      EXPECT_EQ(t.errors[i],
                "event(ground): event 'ground' fired 0 times by the run's end at t = 1 s; "
                "event(ground, 1) needs 1")
          << h;
    }
  }
}

}  // namespace
}  // namespace chasles
