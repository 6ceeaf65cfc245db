// Rolling without slipping down an incline (chapter 8.3): the friction the rolling needs
// (Example 8.3) and the speed after a drop h (Example 8.6), for a sphere, a cylinder, an
// upright disk and a hoop.

#include <cmath>
#include <memory>
#include <numbers>

#include <gtest/gtest.h>

#include "chasles/analysis/instantaneous.h"
#include "chasles/integrate/simulate.h"
#include "chasles/model/constraints.h"
#include "chasles/model/forces.h"
#include "chasles/model/model.h"
#include "test_support.h"

namespace chasles {
namespace {

using test::MatNear;
using test::Near;

constexpr double kG = 9.81;
const double kTheta = std::numbers::pi / 6;                // 30°
const Vec3 kN(std::sin(kTheta), std::cos(kTheta), 0);      // the incline's upward normal
const Vec3 kDown(std::cos(kTheta), -std::sin(kTheta), 0);  // down the slope

struct Roller {
  const char* name;
  RollingShape shape;
  double k2_over_R2;  // (radius of gyration about the axis / R)²
  Vec3 I_over_mR2;    // principal moments / (m R²), axis along body z
};

// Sphere 2/5; solid cylinder 1/2 (length 2R: transverse (3R² + (2R)²)/12 = 7/12 m R²);
// thin disk 1/2 (diameter 1/4); hoop 1 (diameter 1/2).
const Roller kRollers[] = {
    {"sphere", RollingShape::kSphere, 0.4, Vec3(0.4, 0.4, 0.4)},
    {"cylinder", RollingShape::kCylinder, 0.5, Vec3(7.0 / 12, 7.0 / 12, 0.5)},
    {"disk", RollingShape::kDisk, 0.5, Vec3(0.25, 0.25, 0.5)},
    {"hoop", RollingShape::kDisk, 1.0, Vec3(0.5, 0.5, 1.0)},
};

// A body of mass m, radius R on the incline through the origin, at rest, axis along world z.
struct Incline {
  double m = 2.5, R = 0.2;
  Model model;
  State Build(const Roller& r) {
    model = Model();
    model.AddBody(
        r.name,
        MassProperties(m, Vec3::Zero(),
                       RotationalInertia::FromMatrix((m * R * R * r.I_over_mR2).asDiagonal())));
    model.AddForceElement(std::make_shared<UniformGravity>("gravity", Vec3(0, -kG, 0)));
    model.AddConstraint(std::make_shared<RollingContact>("incline", r.shape, 0, Vec3::Zero(),
                                                         Vec3::UnitZ(), R, Vec3::Zero(), kN));
    State s = MakeRestState(model);
    SetBodyPose(model, 0, R * kN, Quat::Identity(), s);
    return s;
  }
};

// Example 8.3 generalised: along the slope m a = m g sin θ - f, about the centre
// m k² α = f R, and rolling a = α R give
//   a = g sin θ / (1 + k²/R²),  f = m g sin θ (k²/R²)/(1 + k²/R²),  N = m g cos θ.
// For the cylinder (k²/R² = 1/2): a = (2/3) g sin θ, f = m g sin θ / 3, and the least
// friction coefficient that keeps it rolling is f/N = tan θ / 3 = 0.19245 at 30°.
TEST(Rolling, FrictionNeededOnAnInclineExample83) {
  for (const Roller& r : kRollers) {
    Incline inc;
    const State s = inc.Build(r);
    const InstantaneousSolution sol = SolveInstantaneous(inc.model, s);
    const double k2 = r.k2_over_R2;
    const double a = kG * std::sin(kTheta) / (1 + k2);
    const double f = inc.m * kG * std::sin(kTheta) * k2 / (1 + k2);
    const double N = inc.m * kG * std::cos(kTheta);
    EXPECT_TRUE(MatNear(sol.bodies[0].a_WBcm_W, a * kDown, 1e-12, kG)) << r.name;
    EXPECT_TRUE(MatNear(sol.bodies[0].alpha_WB_W, Vec3(0, 0, -a / inc.R), 1e-12, kG / inc.R))
        << r.name;
    const ReactionReport& c = sol.reactions[0];
    ASSERT_TRUE(c.is_rolling);
    EXPECT_TRUE(Near(c.normal_force, N, 1e-12)) << r.name;
    EXPECT_TRUE(MatNear(c.friction_W, -f * kDown, 1e-12, N)) << r.name;
    EXPECT_TRUE(Near(c.friction_needed, std::tan(kTheta) * k2 / (1 + k2), 1e-12)) << r.name;
    // The reaction acts at the contact point, so its moment about that point is zero.
    EXPECT_TRUE(MatNear(c.p_WJ, Vec3::Zero(), 1e-15, inc.R));
    EXPECT_TRUE(MatNear(c.M_Jc_W, Vec3::Zero(), 1e-12, N * inc.R)) << r.name;
  }
  Incline inc;
  const State s = inc.Build(kRollers[1]);
  EXPECT_NEAR(SolveInstantaneous(inc.model, s).reactions[0].friction_needed, 0.19245, 5e-6);
}

// Example 8.6: from rest down a height h, energy (rolling friction does no work):
//   m g h = ½ m v² (1 + k²/R²)  →  v / √(2 g h) = √(1 / (1 + k²/R²)):
//   sphere √(5/7), cylinder and disk √(2/3), hoop √(1/2).
TEST(Rolling, SpeedAfterADropExample86) {
  const double h = 0.75;
  for (const Roller& r : kRollers) {
    Incline inc;
    const State s0 = inc.Build(r);
    SimulationOptions o;
    o.t_end = 10.0;
    o.adaptive.rtol = 1e-12;
    o.adaptive.atol = 1e-14;
    EventSpec drop;
    drop.name = "dropped h";
    drop.direction = EventDirection::kRising;
    drop.g = [&](const Model&, const State& s) {
      return (s0.bodies[0].p_WBcm.y() - s.bodies[0].p_WBcm.y()) - h;
    };
    o.events.push_back(drop);
    const SimulationResult res = Simulate(inc.model, s0, o);
    ASSERT_TRUE(res.stopped_by_event) << r.name;
    const double v = res.final_state.bodies[0].v_WBcm_W.norm();
    EXPECT_TRUE(Near(v / std::sqrt(2 * kG * h), std::sqrt(1 / (1 + r.k2_over_R2)), 1e-7)) << r.name;
    // Still rolling along the slope, on the plane.
    EXPECT_TRUE(MatNear(res.final_state.bodies[0].v_WBcm_W, v * kDown, 1e-9)) << r.name;
    EXPECT_NEAR((res.final_state.bodies[0].p_WBcm).dot(kN), inc.R, 1e-12) << r.name;
  }
  EXPECT_NEAR(std::sqrt(1 / (1 + 0.4)), std::sqrt(5.0 / 7.0), 1e-15);
}

}  // namespace
}  // namespace chasles
