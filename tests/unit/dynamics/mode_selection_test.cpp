// SelectContactModes plans the normal forces with the force law the contact stage integrates.
//
// Two balls rolling on a floor, touching, with equal forward speed 1 m/s; the leader also drifts
// sideways at 0.01 m/s and has rolling resistance mu_r, the chaser none. A ball rolling without
// slip under a horizontal force F through its centre accelerates at F / (7/5 m) (I = 2/5 m R²),
// and rolling resistance (moment -mu_r N R ŵ_r) acts as the force -mu_r m g v̂ there (chapter
// 8.3). With the pair's normal force P along n = x̂:
//   chaser:  7/5 m a_A = -P,
//   leader:  7/5 m a_B = P - mu_r m g v̂_x,   v̂_x = 1/√(1 + 0.01²).
// The gap |d| - 2R keeps its zero while g̈ = n·(a_B - a_A) + |ḋ_⊥|²/|d| = 0, with
// |ḋ_⊥|²/|d| = c = 0.01²/(2R) (the sideways drift turns n), so
//   P = m/2 (mu_r g v̂_x - 7/5 c) > 0:
// the rolling resistance presses the pair together although, without it, the drift alone would
// part them (c > 0). A plan that left the moment out would call the point parting and the
// integrator would find it pressing at once: a contact switching mode at one instant.

#include <cmath>
#include <memory>

#include <gtest/gtest.h>

#include "chasles/dynamics/contact_solve.h"
#include "chasles/model/forces.h"
#include "chasles/model/model.h"

namespace chasles {
namespace {

constexpr double kM = 0.17, kR = 0.028575, kG = 9.80665, kMuR = 0.01;

int AddBall(Model& m, const char* name, double mu_r) {
  const double I = 0.4 * kM * kR * kR;
  const int b = m.AddBody(name, MassProperties(kM, Vec3::Zero(), RotationalInertia(I, I, I)));
  ContactSpec c;
  c.name = std::string(name) + " floor";
  c.shape = ContactShape::kSphere;
  c.body = b;
  c.radius = kR;
  c.mu_s = 0.25;
  c.mu_k = 0.2;
  c.mu_r = mu_r;
  m.AddContact(c);
  return b;
}

TEST(ModeSelection, RollingResistanceThatPressesTwoBallsTogetherIsInThePlan) {
  Model m;
  const int a = AddBall(m, "chaser", 0.0);
  const int b = AddBall(m, "leader", kMuR);
  ContactSpec pair;
  pair.name = "pair";
  pair.shape = ContactShape::kSphereSphere;
  pair.body = a;
  pair.other_body = b;
  pair.radius = pair.other_radius = kR;
  m.AddContact(pair);
  m.AddForceElement(std::make_shared<UniformGravity>("gravity", Vec3(0, 0, -kG)));
  State s = MakeRestState(m);
  // Rolling without slip: v = ω × R ẑ, so ω = (-v_y, v_x, 0) / R.
  const Vec3 v_a(1.0, 0.0, 0.0), v_b(1.0, 0.01, 0.0);
  SetBodyPose(m, a, Vec3(0, 0, kR), Quat::Identity(), s);
  SetBodyPose(m, b, Vec3(2 * kR, 0, kR), Quat::Identity(), s);
  SetBodyVelocity(m, a, v_a, Vec3(-v_a.y(), v_a.x(), 0) / kR, s);
  SetBodyVelocity(m, b, v_b, Vec3(-v_b.y(), v_b.x(), 0) / kR, s);

  SelectContactModes(m, s);
  const int p = m.num_contact_points() - 1;  // the pair's one point
  ASSERT_EQ(m.contact_point_name(p), "pair");
  EXPECT_NE(s.contacts[static_cast<size_t>(p)].mode, ContactMode::kSeparated);
  const std::vector<ContactPointOutput> out = CalcContactOutputs(m, s);
  const double c = 0.01 * 0.01 / (2 * kR);
  const double P = kM / 2 * (kMuR * kG / std::sqrt(1.0 + 0.01 * 0.01) - 1.4 * c);
  EXPECT_NEAR(out[static_cast<size_t>(p)].normal_force, P, 1e-9 * P);
  // Both floors carry the weight and keep rolling (sticking).
  for (int f = 0; f < 2; ++f) {
    EXPECT_EQ(s.contacts[static_cast<size_t>(f)].mode, ContactMode::kSticking);
    EXPECT_NEAR(out[static_cast<size_t>(f)].normal_force, kM * kG, 1e-12 * kM * kG);
  }
}

}  // namespace
}  // namespace chasles
