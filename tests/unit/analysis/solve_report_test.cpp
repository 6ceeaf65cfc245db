#include "chasles/analysis/solve_report.h"

#include <algorithm>
#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace chasles {
namespace {

ContactPointReport Point(ContactMode mode, bool round) {
  ContactPointReport c;
  c.out.mode = mode;
  c.round = round;
  c.out.normal_force = 8.0;
  c.out.friction_force_W = Vec3(0, 6, 0);  // |f| = 6 N
  c.out.friction_needed = 0.25;
  return c;
}

TEST(ContactPointReport, RegimeNamesWhatThePointDoes) {
  EXPECT_EQ(Point(ContactMode::kSticking, true).Regime(), "rolls");
  EXPECT_EQ(Point(ContactMode::kSticking, false).Regime(), "sticks");
  EXPECT_EQ(Point(ContactMode::kSliding, true).Regime(), "slides");
  EXPECT_EQ(Point(ContactMode::kSeparated, false).Regime(), "separated");
}

TEST(ContactPointReport, FrictionRatioIsTheNeededRatioWhenStickingAndFOverNWhenSliding) {
  EXPECT_EQ(Point(ContactMode::kSticking, true).FrictionRatio(), 0.25);
  // Sliding: |f| / N = 6 / 8.
  EXPECT_EQ(Point(ContactMode::kSliding, false).FrictionRatio(), 6.0 / 8.0);
  EXPECT_EQ(Point(ContactMode::kSeparated, false).FrictionRatio(), 0.0);
}

TEST(SolutionTableRow, PlanarRowsHoldAxAyAlphaAndFxFyMz) {
  SolveReport s;
  s.planar = true;
  BodyAccelerationReport b;
  b.name = "bar";
  b.a_WBcm_W = Vec3(1, 2, 3);
  b.alpha_WB_W = Vec3(4, 5, 6);
  s.solution.bodies = {b};
  ReactionReport r;
  r.name = "pin";
  r.F_Jc_W = Vec3(7, 8, 9);
  r.M_Jc_W = Vec3(10, 11, 12);
  s.solution.reactions = {r};
  s.motion = {BodyMotionReport{}};
  s.motion[0].name = "bar";
  std::vector<std::string> names, units;
  std::vector<double> values;
  SolutionTableRow(s, &names, &units, &values);
  ASSERT_EQ(names.size(), values.size());
  ASSERT_EQ(units.size(), values.size());
  const auto at = [&](const std::string& n) {
    for (size_t i = 0; i < names.size(); ++i) {
      if (names[i] == n) return values[i];
    }
    ADD_FAILURE() << "no column " << n;
    return 0.0;
  };
  EXPECT_EQ(names[0], "bar_ax");
  EXPECT_EQ(at("bar_ax"), 1.0);
  EXPECT_EQ(at("bar_ay"), 2.0);
  EXPECT_EQ(at("bar_alpha"), 6.0);
  EXPECT_EQ(at("pin_Fx"), 7.0);
  EXPECT_EQ(at("pin_Fy"), 8.0);
  EXPECT_EQ(at("pin_Mz"), 12.0);
  EXPECT_EQ(units[0], "m/s^2");
  // Planar: per body v_x, v_y, omega, dH_z/dt about the centre of mass and about O (5), per
  // body T_trans, T_rot, T, P_x, P_y, H_z, HO_z (7: the other momentum components of a plane
  // motion are zero), then the same for the total with its dH_z/dt and dH_Oz/dt (7 + 2).
  EXPECT_EQ(names.size(), 3u + 5u + 7u + 7u + 2u + 3u);
  for (const char* absent : {"bar_Pz", "bar_Hx", "bar_Hy", "bar_HOx", "bar_HOy", "Pz", "Hx"}) {
    EXPECT_EQ(std::find(names.begin(), names.end(), absent), names.end()) << absent;
  }
  s.motion[0].v_WBcm_W = Vec3(13, 14, 15);
  s.motion[0].w_WB_W = Vec3(16, 17, 18);
  s.motion[0].Hdot_cm = Vec3(19, 20, 21);
  s.motion[0].Hdot_O = Vec3(22, 23, 24);
  s.total.Hdot_cm = Vec3(25, 26, 27);
  s.total.Hdot_O = Vec3(28, 29, 30);
  names.clear(), units.clear(), values.clear();
  SolutionTableRow(s, &names, &units, &values);
  EXPECT_EQ(at("bar_vx"), 13.0);
  EXPECT_EQ(at("bar_vy"), 14.0);
  EXPECT_EQ(at("bar_omega"), 18.0);
  EXPECT_EQ(at("bar_dHz"), 21.0);
  EXPECT_EQ(at("bar_dHOz"), 24.0);
  EXPECT_EQ(at("dHz"), 27.0);
  EXPECT_EQ(at("dHOz"), 30.0);
}

}  // namespace
}  // namespace chasles
