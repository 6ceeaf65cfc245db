// The analysis layer's sweep of runs on Models built in code: each point's StudyDefinition made
// from the parameters' values alone (no scene), against closed forms derived here.

#include "chasles/analysis/study_sweep.h"

#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "chasles/analysis/study.h"
#include "chasles/error.h"
#include "chasles/model/forces.h"
// clang-format off
#include <gtest/gtest.h>
// clang-format on
#include "test_support.h"

namespace chasles {
namespace {

using test::Near;

constexpr double kTol = 1e-12;  // relative: free flight is a quadratic in t, integrated exactly

// A ball (a sphere of mass m, radius r: I = 2/5 m r², Appendix A) thrown straight up at v0
// [m/s] in gravity g [m/s²], run to T = 1 s.
StudyDefinition Throw(double v0, double g) {
  const double m = 0.5, r = 0.1, I = 0.4 * m * r * r;
  StudyDefinition def;
  def.bodies = {{"ball", MassProperties(m, Vec3::Zero(), RotationalInertia(I, I, I))}};
  auto model = std::make_shared<Model>();
  model->AddBody("ball", def.bodies[0].mass_properties);
  model->AddForceElement(std::make_shared<UniformGravity>("gravity", Vec3(0, 0, -g)));
  def.model = model;
  def.initial = MakeRestState(*model);
  def.initial.bodies[0].v_WBcm_W = Vec3(0, 0, v0);
  def.options.t_end = 1.0;
  def.options.output_interval = 0.25;
  def.columns = {{"t", "t", -1, "t", "", -1}, {"ball_z", "position", 0, "z", "", -1}};
  return def;
}

// Over a grid of v0 and g, the height at T and its largest value over the samples:
//   z(T) = v0 T - g T²/2,  max over t = 0, 0.25, ..., 1 s of v0 t - g t²/2,
// and t_end = T. The point's function never sees a scene.
TEST(SimulateSweep, ThrownBallOverSpeedAndGravityMatchesFreeFlight) {
  ParameterGrid grid;
  grid.names = {"v0", "g"};
  grid.units = {"m/s", "m/s^2"};
  grid.start = {1.0, 9.0};
  grid.stop = {5.0, 10.0};
  grid.counts = {3, 2};
  SweepQuantity final_z;
  final_z.kind = SweepQuantity::Kind::kFinal;
  final_z.text = final_z.column = "ball_z";
  SweepQuantity max_z = final_z;
  max_z.kind = SweepQuantity::Kind::kMax;
  SweepQuantity t_end;  // Kind::kTEnd
  t_end.text = "t_end";
  const auto point = [](const std::vector<double>& values) {
    StudySweepPoint p;
    p.values = values;
    p.definition = Throw(values[0], values[1]);
    return p;
  };
  SweepRunOptions options;
  options.jobs = 2;
  const SweepTable t =
      SimulateSweep(grid, {final_z, max_z, t_end}, {"m", "m", "s"}, point, options);
  ASSERT_EQ(t.rows.size(), 6u);
  for (size_t k = 0; k < t.rows.size(); ++k) {
    const std::vector<double> values = grid.Values(static_cast<std::int64_t>(k));
    const double v0 = values[0], g = values[1], T = 1.0;
    ASSERT_EQ(t.rows[k].size(), 5u);
    EXPECT_EQ(t.rows[k][0], v0);
    EXPECT_EQ(t.rows[k][1], g);
    const double scale = v0 * T + g * T * T;
    EXPECT_TRUE(Near(t.rows[k][2], v0 * T - g * T * T / 2, kTol, scale)) << k;
    double highest = 0.0;
    for (int i = 0; i <= 4; ++i) {
      const double s = 0.25 * i;
      highest = std::max(highest, v0 * s - g * s * s / 2);
    }
    EXPECT_TRUE(Near(t.rows[k][3], highest, kTol, scale)) << k;
    EXPECT_EQ(t.rows[k][4], T);
    EXPECT_EQ(t.errors[k], "");
  }
}

// A point whose definition cannot be made (the function throws InputError) is a row with its
// values, NaN quantities and the reason; the others run.
TEST(SimulateSweep, APointWithoutADefinitionIsARowWithItsReason) {
  ParameterGrid grid;
  grid.names = {"v0"};
  grid.units = {"m/s"};
  grid.start = {1.0};
  grid.stop = {3.0};
  grid.counts = {3};
  SweepQuantity final_z;
  final_z.kind = SweepQuantity::Kind::kFinal;
  final_z.text = final_z.column = "ball_z";
  const auto point = [](const std::vector<double>& values) {
    if (values[0] == 2.0) throw InputError("no throw at 2 m/s\nsecond line");
    StudySweepPoint p;
    p.values = values;
    p.definition = Throw(values[0], 9.81);
    return p;
  };
  const SweepTable t = SimulateSweep(grid, {final_z}, {"m"}, point, {});
  ASSERT_EQ(t.rows.size(), 3u);
  EXPECT_EQ(t.rows[1][0], 2.0);
  EXPECT_TRUE(std::isnan(t.rows[1][1]));
  EXPECT_EQ(t.errors[1], "no throw at 2 m/s; second line");
  for (size_t k : {0u, 2u}) {
    const double v0 = t.rows[k][0];
    EXPECT_TRUE(Near(t.rows[k][1], v0 - 9.81 / 2, kTol, v0 + 9.81)) << k;
    EXPECT_EQ(t.errors[k], "");
  }
}

}  // namespace
}  // namespace chasles
