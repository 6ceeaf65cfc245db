// ResolveImpacts on models with joints (the collision matrix uses the constrained inverse
// mass), ResolvePlasticImpact, and the law names.

#include <cmath>
#include <memory>

#include <gtest/gtest.h>

#include "chasles/dynamics/impact.h"
#include "chasles/model/constraints.h"
#include "chasles/model/model.h"
#include "test_support.h"

namespace chasles {
namespace {

using test::Near;

// A slender rod (m, L; I = m L²/12 across, about G) pinned at the origin by a hinge about z,
// lying along +x; its tip T = (L, 0, 0) touches the plane y = 0 (normal +y) and moves at
// ω ẑ × (L, 0, 0) = (0, ω L, 0) with ω < 0. About the pivot I_O = m L²/3, so a normal
// impulse P at T gives I_O Δω = L P and Δv_T,y = L² P / I_O = 3 P / m: the tip's effective
// mass is m/3 (a free rod's tip would have m/4: the hinge's reaction impulse is part of the
// answer). The hinge also removes the tangential freedom of T (along the rod and along z), so
// no friction impulse arises. Every law: P = (1 + e) (m/3) |ω| L, ω⁺ = -e ω.
Model PinnedRod(double m, double L, double e, RestitutionLaw law, State& s) {
  Model model;
  const double It = m * L * L / 12;
  model.AddBody(
      "rod", MassProperties(m, Vec3::Zero(),
                            RotationalInertia::FromMatrix(Vec3(1e-6 * It, It, It).asDiagonal())));
  // The hinge is placed from the rod's pose (body at rest along +x).
  model.AddConstraint(std::make_shared<Joint>("pin", JointKind::kRevolute, kWorld,
                                              AttachmentFrame{Vec3::Zero()}, 0,
                                              AttachmentFrame{Vec3(-L / 2, 0, 0)}));
  ContactSpec c;
  c.name = "stop";
  c.shape = ContactShape::kPointSet;
  c.body = 0;
  c.points_B = {Vec3(L / 2, 0, 0)};
  c.plane_normal_W = Vec3::UnitY();
  c.mu_s = c.mu_k = 0.5;
  c.restitution = e;
  c.restitution_law = law;
  model.AddContact(c);
  s = MakeRestState(model);
  SetBodyPose(model, 0, Vec3(L / 2, 0, 0), Quat::Identity(), s);
  return model;
}

TEST(ResolveImpacts, PinnedRodUsesTheConstrainedInverseMass) {
  const double m = 1.2, L = 0.9, w = -3.0, e = 0.4;
  for (const RestitutionLaw law :
       {RestitutionLaw::kNewton, RestitutionLaw::kPoisson, RestitutionLaw::kEnergetic}) {
    State s;
    const Model model = PinnedRod(m, L, e, law, s);
    SetBodyVelocity(model, 0, Vec3(0, w * L / 2, 0), Vec3(0, 0, w), s);
    const ImpactResult r = ResolveImpacts(model, s);
    ASSERT_EQ(r.impulses.size(), 1u);
    EXPECT_FALSE(r.frictionless_fallback);
    EXPECT_TRUE(Near(r.impulses[0].normal_impulse, (1 + e) * m / 3 * std::abs(w) * L, 1e-12));
    EXPECT_LE(r.impulses[0].impulse_W.cross(Vec3::UnitY()).norm(),
              1e-12 * r.impulses[0].normal_impulse);
    EXPECT_TRUE(Near(s.bodies[0].w_WB_B.z(), -e * w, 1e-12));
    // The pivot stays at rest: v_G = ω⁺ × (L/2, 0, 0).
    EXPECT_TRUE(test::MatNear(s.bodies[0].v_WBcm_W, Vec3(0, -e * w * L / 2, 0), 1e-12));
    // Energy: ½ I_O ω² (1 - e²) lost.
    const double I_O = m * L * L / 3;
    EXPECT_TRUE(Near(r.kinetic_energy_before - r.kinetic_energy_after,
                     0.5 * I_O * w * w * (1 - e * e), 1e-12));
  }
}

// ResolvePlasticImpact: e = 0 at the point, the tip stops (ω⁺ = 0) under any law.
TEST(ResolveImpacts, PlasticImpactStopsThePoint) {
  State s;
  const Model model = PinnedRod(1.0, 1.0, 0.8, RestitutionLaw::kEnergetic, s);
  SetBodyVelocity(model, 0, Vec3(0, -1.0, 0), Vec3(0, 0, -2.0), s);
  const ImpactResult r = ResolvePlasticImpact(model, s, 0);
  ASSERT_EQ(r.impulses.size(), 1u);
  EXPECT_LE(std::abs(s.bodies[0].w_WB_B.z()), 1e-12);
  EXPECT_TRUE(Near(r.impulses[0].normal_impulse, r.impulses[0].compression_impulse, 1e-12));
}

// No approaching point: nothing happens.
TEST(ResolveImpacts, SeparatingPointTakesNoImpulse) {
  State s;
  const Model model = PinnedRod(1.0, 1.0, 0.8, RestitutionLaw::kEnergetic, s);
  SetBodyVelocity(model, 0, Vec3(0, 1.0, 0), Vec3(0, 0, 2.0), s);
  const State before = s;
  const ImpactResult r = ResolveImpacts(model, s);
  EXPECT_TRUE(r.impulses.empty());
  EXPECT_EQ(s.bodies[0].w_WB_B, before.bodies[0].w_WB_B);
  EXPECT_EQ(r.kinetic_energy_before, r.kinetic_energy_after);
}

TEST(RestitutionLaw, Names) {
  EXPECT_STREQ(RestitutionLawName(RestitutionLaw::kEnergetic), "energetic");
  EXPECT_STREQ(RestitutionLawName(RestitutionLaw::kNewton), "newton");
  EXPECT_STREQ(RestitutionLawName(RestitutionLaw::kPoisson), "poisson");
  EXPECT_EQ(ContactSpec{}.restitution_law, RestitutionLaw::kEnergetic);
}

}  // namespace
}  // namespace chasles
