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
#include <random>
#include <vector>

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

// The pair of the file comment, forward speed v, the leader's drift d and rolling resistance
// mu_r: modes chosen by SelectContactModes, contact outputs, and the closed-form pair force
// P = m/2 (mu_r g v/√(v² + d²) - 7/5 d²/(2R)) (pressing when positive, parting otherwise).
struct PairCase {
  State s;
  std::vector<ContactPointOutput> out;
  double P;
};

PairCase RunPair(double v, double d, double mu_r) {
  Model m;
  const int a = AddBall(m, "chaser", 0.0);
  const int b = AddBall(m, "leader", mu_r);
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
  const Vec3 v_a(v, 0.0, 0.0), v_b(v, d, 0.0);
  SetBodyPose(m, a, Vec3(0, 0, kR), Quat::Identity(), s);
  SetBodyPose(m, b, Vec3(2 * kR, 0, kR), Quat::Identity(), s);
  SetBodyVelocity(m, a, v_a, Vec3(-v_a.y(), v_a.x(), 0) / kR, s);
  SetBodyVelocity(m, b, v_b, Vec3(-v_b.y(), v_b.x(), 0) / kR, s);
  SelectContactModes(m, s);
  EXPECT_EQ(m.contact_point_name(2), "pair");
  const double c = d * d / (2 * kR);
  const double P = kM / 2 * (mu_r * kG * v / std::hypot(v, d) - 1.4 * c);
  return {s, CalcContactOutputs(m, s), P};
}

TEST(ModeSelection, RollingResistanceThatPressesTwoBallsTogetherIsInThePlan) {
  const PairCase r = RunPair(1.0, 0.01, kMuR);
  EXPECT_NE(r.s.contacts[2].mode, ContactMode::kSeparated);
  EXPECT_NEAR(r.out[2].normal_force, r.P, 1e-9 * r.P);
  // Both floors carry the weight and keep rolling (sticking).
  for (int f = 0; f < 2; ++f) {
    EXPECT_EQ(r.s.contacts[static_cast<size_t>(f)].mode, ContactMode::kSticking);
    EXPECT_NEAR(r.out[static_cast<size_t>(f)].normal_force, kM * kG, 1e-12 * kM * kG);
  }
}

// Seeded speeds, drifts and coefficients on both sides of P = 0: where P > 0 the point is in
// contact with that force, where P < 0 it parts (no force, and the drift opens the gap).
TEST(ModeSelection, SeededPairsPressOrPartAsTheClosedFormSays) {
  std::mt19937 rng(8);
  std::uniform_real_distribution<double> V(0.2, 3.0), D(0.0, 0.1), MU(0.002, 0.03);
  int pressing = 0, parting = 0;
  for (int k = 0; k < 60; ++k) {
    const double v = V(rng), d = D(rng), mu_r = MU(rng);
    const PairCase r = RunPair(v, d, mu_r);
    if (std::abs(r.P) < 1e-5) continue;  // within round-off of the switch: either is right
    if (r.P > 0.0) {
      ++pressing;
      EXPECT_NE(r.s.contacts[2].mode, ContactMode::kSeparated) << v << " " << d << " " << mu_r;
      EXPECT_NEAR(r.out[2].normal_force, r.P, 1e-9 * r.P) << v << " " << d << " " << mu_r;
    } else {
      ++parting;
      EXPECT_EQ(r.s.contacts[2].mode, ContactMode::kSeparated) << v << " " << d << " " << mu_r;
      EXPECT_EQ(r.out[2].normal_force, 0.0);
    }
  }
  EXPECT_GT(pressing, 10);
  EXPECT_GT(parting, 10);
}

}  // namespace
}  // namespace chasles
