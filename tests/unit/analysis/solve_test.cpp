// The instantaneous problem of a Model at a state (chasles/analysis/solve.h), against closed
// forms: a spinning ball in flight and a ball resting on the floor.

#include "chasles/analysis/solve.h"

#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "chasles/error.h"
#include "chasles/model/contact.h"
#include "chasles/model/forces.h"
#include "chasles/model/model.h"

namespace chasles {
namespace {

constexpr double kG = 9.81, kM = 2.0, kR = 0.1;
// Exact sums and products of a few terms: round-off of the largest value.
constexpr double kTol = 1e-14;

/// A solid sphere (I = 2/5 m R², Appendix A) under gravity, optionally on the floor.
std::shared_ptr<Model> BallModel(bool floor) {
  auto model = std::make_shared<Model>();
  const double I = 0.4 * kM * kR * kR;
  model->AddBody("ball", MassProperties(kM, Vec3::Zero(),
                                        RotationalInertia::FromMatrix(Vec3(I, I, I).asDiagonal())));
  model->AddForceElement(std::make_shared<UniformGravity>("gravity", Vec3(0, 0, -kG)));
  if (floor) {
    ContactSpec spec;
    spec.name = "floor";
    spec.shape = ContactShape::kSphere;
    spec.body = 0;
    spec.radius = kR;
    spec.mu_s = 0.5;
    spec.mu_k = 0.4;
    model->AddContact(spec);
  }
  return model;
}

// In flight at v = (1, 0, 0) m/s spinning at w = 3 rad/s about z: a = g, and the point P at
// r = (R, 0, 0) from the centre moves at v + w × r = (1, wR, 0) with a + w × (w × r) =
// (-w² R, 0, -g) (chapter 8, rigid-body kinematics); T = m v²/2 + I w²/2.
TEST(SolveAtState, ASpinningBallInFlight) {
  const std::shared_ptr<Model> model = BallModel(false);
  const double w = 3.0;
  SolveDefinition def;
  def.model = model;
  def.initial = MakeRestState(*model);
  SetBodyPose(*model, 0, Vec3(0, 0, 1), Quat::Identity(), def.initial);
  SetBodyVelocity(*model, 0, Vec3(1, 0, 0), Vec3(0, 0, w), def.initial);
  def.points = {{{"rim", Vec3(kR, 0, 0)}}};
  def.warnings = {"given first"};
  const SolveReport s = SolveAtState(def);
  ASSERT_EQ(s.motion.size(), 1u);
  const BodyMotionReport& m = s.motion[0];
  EXPECT_NEAR((s.solution.bodies[0].a_WBcm_W - Vec3(0, 0, -kG)).norm(), 0.0, kTol * kG);
  ASSERT_EQ(m.points.size(), 1u);
  EXPECT_EQ(m.points[0].name, "rim");
  EXPECT_NEAR((m.points[0].v_WP_W - Vec3(1, w * kR, 0)).norm(), 0.0, kTol);
  EXPECT_NEAR((m.points[0].a_WP_W - Vec3(-w * w * kR, 0, -kG)).norm(), 0.0, kTol * kG);
  EXPECT_NEAR(m.T_trans, 0.5 * kM, kTol);
  EXPECT_NEAR(m.T_rot, 0.5 * 0.4 * kM * kR * kR * w * w, kTol);
  EXPECT_TRUE(s.solution.reactions.empty());
  EXPECT_TRUE(s.mu_s.empty());
  ASSERT_FALSE(s.solution.warnings.empty());
  EXPECT_EQ(s.solution.warnings.front(), "given first");
  EXPECT_TRUE(s.certificate.passed());
  EXPECT_THROW(SolveAtState(SolveDefinition{}), InputError);
}

// At rest on the floor the ball presses with N = m g and sticks with no friction; its
// point is labelled as the definition says, else by the Model.
TEST(SolveAtState, ABallRestingOnTheFloor) {
  SolveDefinition def;
  def.model = BallModel(true);
  def.initial = MakeRestState(*def.model);
  SetBodyPose(*def.model, 0, Vec3(0, 0, kR), Quat::Identity(), def.initial);
  const SolveReport unnamed = SolveAtState(def);
  ASSERT_EQ(unnamed.contacts.size(), 1u);
  EXPECT_EQ(unnamed.contacts[0].point, def.model->contact_point_name(0));
  def.contact_point_labels = {"floor/ball"};
  const SolveReport s = SolveAtState(def);
  ASSERT_EQ(s.contacts.size(), 1u);
  EXPECT_EQ(s.contacts[0].point, "floor/ball");
  EXPECT_EQ(s.contacts[0].contact, "floor");
  EXPECT_EQ(s.contacts[0].out.mode, ContactMode::kSticking);
  EXPECT_NEAR(s.contacts[0].out.normal_force, kM * kG, kTol * kM * kG);
  EXPECT_NEAR(s.contacts[0].out.friction_force_W.norm(), 0.0, kTol * kM * kG);
  EXPECT_NEAR(s.solution.bodies[0].a_WBcm_W.norm(), 0.0, kTol * kG);
  EXPECT_EQ(s.contacts[0].mu_s, 0.5);
}

}  // namespace
}  // namespace chasles
