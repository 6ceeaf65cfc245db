// The supports' impulsive reactions and every body's velocity jumps at impulses and impacts
// (chapter 8.5, eqs. 8.118, 8.119), run by RunStudy on Models built here, against closed forms
// derived here or in tests/reference/struck_double_pendulum.h: the struck double pendulum
// (hanging and at a general configuration), a pinned rod hit by a projectile that passes
// through or embeds (the centre of percussion leaves the pin without impulse), a pinned rod
// struck down onto a floor (a contact impact that takes the pin's impulse with it), and a
// rolling sphere struck across (the rolling constraint's friction impulse).

#include <cmath>
#include <memory>
#include <numbers>

#include <gtest/gtest.h>

#include "chasles/analysis/study.h"
#include "chasles/math/rotation.h"
#include "chasles/model/constraints.h"
#include "chasles/model/forces.h"
#include "chasles/model/model.h"
#include "reference/struck_double_pendulum.h"
#include "test_support.h"

namespace chasles {
namespace {

using reference::StruckDoublePendulum;
using test::MatNear;
using test::Near;

// One projection (a dense linear solve) and sums of a few products: round-off only.
constexpr double kImpulse = 1e-12;

Vec3 In3d(const Eigen::Vector2d& v) {
  return Vec3(v.x(), v.y(), 0.0);
}

// A uniform rod along its body x axis from Bo: transverse moments m L²/12 about its centre;
// its own axis gets a tiny moment so that the body is invertible (the joints keep that spin 0).
MassProperties Rod(double m, double L) {
  const double It = m * L * L / 12;
  return MassProperties(m, Vec3(L / 2, 0, 0), RotationalInertia(1e-6 * It, It, It));
}

const StudyReaction& Reaction(const StudyJump& j, const std::string& name) {
  for (const StudyReaction& r : j.reactions) {
    if (r.name == name) return r;
  }
  throw std::runtime_error("no reaction " + name);
}

const BodyImpulseBalance& JumpBody(const StudyJump& j, const std::string& name) {
  for (const BodyImpulseBalance& b : j.bodies) {
    if (b.body == name) return b;
  }
  throw std::runtime_error("no body " + name);
}

const CheckResult& Check(const Certificate& c, const std::string& name) {
  for (const CheckResult& r : c.checks) {
    if (r.name == name) return r;
  }
  throw std::runtime_error("no check " + name);
}

// Both impulse balances were checked at the jump and passed.
void ExpectBalancesChecked(const StudyResult& r) {
  for (const char* name : {"linear impulse balance", "angular impulse balance"}) {
    const CheckResult& c = Check(r.certificate, name);
    EXPECT_GT(c.count, 0) << name;
    EXPECT_TRUE(c.passed()) << name << ": " << c.worst << " against " << c.tolerance;
  }
  for (const std::string& m : r.certificate.FailureMessages()) ADD_FAILURE() << m;
}

// The double pendulum as a 3-D Model: revolute joints about z at O and at the elbow E, each
// rod's frame at its pinned end with x along the rod.
StudyDefinition DoublePendulum(const StruckDoublePendulum& p) {
  StudyDefinition def;
  def.bodies = {{"upper", Rod(p.m1, p.L1)}, {"lower", Rod(p.m2, p.L2)}};
  const Vec3 E = In3d(p.Elbow());
  const auto pose = [p, E](const Model& model) {
    State s = MakeRestState(model);
    SetBodyPose(model, 0, Vec3::Zero(), Quat(RotationFromAxisAngle(Vec3::UnitZ(), p.theta1)), s);
    SetBodyPose(model, 1, E, Quat(RotationFromAxisAngle(Vec3::UnitZ(), p.theta2)), s);
    return s;
  };
  def.build_model = [pose, E](const std::vector<NamedBody>& bodies, const BodyMap&) {
    Model model;
    for (const NamedBody& b : bodies) model.AddBody(b.name, b.mass_properties);
    const State s = pose(model);
    const Mat3 I = Mat3::Identity();
    model.AddConstraint(
        std::make_shared<Joint>("O", JointKind::kRevolute, kWorld, AttachmentFrame{Vec3::Zero()}, 0,
                                AttachmentFrameAtWorldPose(model, s, 0, Vec3::Zero(), I)));
    model.AddConstraint(std::make_shared<Joint>("elbow", JointKind::kRevolute, 0,
                                                AttachmentFrameAtWorldPose(model, s, 0, E, I), 1,
                                                AttachmentFrameAtWorldPose(model, s, 1, E, I)));
    return model;
  };
  def.initial = pose(def.build_model(def.bodies, {}));
  def.options.t_end = 0.01;
  def.options.output_interval = 0.01;
  def.impulses = {{0.0, 1, Vec3(p.s, 0, 0), In3d(p.J), VectorFrame::kWorld}};
  return def;
}

// The jump's pins and bodies against the closed form `a`, to kImpulse of the impulse's size.
void ExpectPendulumJump(const StruckDoublePendulum& p, const StruckDoublePendulum::Answer& a,
                        const StudyJump& j) {
  const double J = p.J.norm();
  // Reactions on the child at each pin: the upper rod at O, the lower one at E; a revolute
  // about z gives no moment impulse about z (nor, here, about x or y).
  EXPECT_TRUE(MatNear(Reaction(j, "O").F_Jc_W, In3d(a.R_O), kImpulse, J));
  EXPECT_TRUE(MatNear(Reaction(j, "elbow").F_Jc_W, In3d(a.R_E), kImpulse, J));
  EXPECT_TRUE(MatNear(Reaction(j, "O").M_Jc_W, Vec3::Zero(), kImpulse, J * p.L1));
  EXPECT_TRUE(MatNear(Reaction(j, "elbow").M_Jc_W, Vec3::Zero(), kImpulse, J * p.L1));
  EXPECT_TRUE(Reaction(j, "elbow").p_WJ.isApprox(In3d(p.Elbow()), 1e-15));
  // The elbow's parent is the upper rod: in its frame (x along the rod) the impulse is R_WPᵀ R_E.
  const Mat3 R_WU = RotationFromAxisAngle(Vec3::UnitZ(), p.theta1);
  EXPECT_TRUE(MatNear(Reaction(j, "elbow").F_Jc_P, R_WU.transpose() * In3d(a.R_E), kImpulse, J));
  const Mat3 R_WL = RotationFromAxisAngle(Vec3::UnitZ(), p.theta2);
  EXPECT_TRUE(MatNear(Reaction(j, "elbow").F_Jc_B, R_WL.transpose() * In3d(a.R_E), kImpulse, J));
  const BodyImpulseBalance& upper = JumpBody(j, "upper");
  const BodyImpulseBalance& lower = JumpBody(j, "lower");
  const double v = J / p.m2, w = J / (p.m2 * p.L2);
  EXPECT_TRUE(MatNear(upper.dv_WBcm_W, In3d(a.dv1), kImpulse, v));
  EXPECT_TRUE(MatNear(lower.dv_WBcm_W, In3d(a.dv2), kImpulse, v));
  EXPECT_TRUE(MatNear(upper.dw_WB_W, Vec3(0, 0, a.w1), kImpulse, w));
  EXPECT_TRUE(MatNear(lower.dw_WB_W, Vec3(0, 0, a.w2), kImpulse, w));
  // Every impulse on the lower rod: the applied one at P and the elbow's share at E.
  ASSERT_EQ(lower.impulses.size(), 2u);
  EXPECT_EQ(lower.impulses[0].source, "applied");
  EXPECT_TRUE(MatNear(lower.impulses[0].J_W, In3d(p.J), kImpulse));
  EXPECT_TRUE(MatNear(lower.impulses[0].p_WP, In3d(p.Elbow() + p.s * p.e2()), kImpulse, p.L1));
  EXPECT_EQ(lower.impulses[1].source, "elbow");
  // The upper rod: the pin's at O and the elbow's opposite at E (Newton's third law).
  ASSERT_EQ(upper.impulses.size(), 2u);
  EXPECT_TRUE(MatNear(upper.impulses[1].J_W, -In3d(a.R_E), kImpulse, J));
}

TEST(ImpulsiveReactions, HangingDoublePendulumStruckAcrossMatchesTheClosedForm) {
  const StruckDoublePendulum p;
  const StruckDoublePendulum::Answer a = p.Hanging();
  // The numbers of examples/double-pendulum-struck.yaml: Δφ̇1 = -9/22 rad/s, Δφ̇2 = 405/44
  // rad/s, R_E = 3/11 N·s, R_O = -3/22 N·s.
  EXPECT_TRUE(Near(a.w1, -9.0 / 22, test::kExact, a.w2));
  EXPECT_TRUE(Near(a.w2, 405.0 / 44, test::kExact));
  EXPECT_TRUE(Near(a.R_E.x(), 3.0 / 11, test::kExact, p.J.x()));
  EXPECT_TRUE(Near(a.R_O.x(), -3.0 / 22, test::kExact, p.J.x()));
  const StudyResult r = RunStudy(DoublePendulum(p));
  ASSERT_EQ(r.jumps.size(), 1u);
  ExpectPendulumJump(p, a, r.jumps[0]);
  // The energy jump is ½ Qᵀ Δφ̇ = ½ J (L1 Δφ̇1 + s Δφ̇2) = 675/88 J.
  EXPECT_TRUE(Near(r.jumps[0].energy_after - r.jumps[0].energy_before, 675.0 / 88, kImpulse));
  ExpectBalancesChecked(r);
}

TEST(ImpulsiveReactions, DoublePendulumAtAGeneralConfigurationMatchesBothRodsBalances) {
  StruckDoublePendulum p;
  p.theta1 = -60 * std::numbers::pi / 180;
  p.theta2 = 25 * std::numbers::pi / 180;
  p.s = 0.3;
  p.J = Eigen::Vector2d(1.5, -2.0);
  const StudyResult r = RunStudy(DoublePendulum(p));
  ASSERT_EQ(r.jumps.size(), 1u);
  ExpectPendulumJump(p, p.Solve(), r.jumps[0]);
  ExpectBalancesChecked(r);
  // The general solution agrees with the hanging closed form where both apply.
  const StruckDoublePendulum hanging;
  const StruckDoublePendulum::Answer g = hanging.Solve(), h = hanging.Hanging();
  EXPECT_TRUE(Near(g.w1, h.w1, 1e-14, h.w2));
  EXPECT_TRUE(Near(g.w2, h.w2, 1e-14));
  EXPECT_TRUE(MatNear(g.R_O, h.R_O, 1e-14, 3.0));
  EXPECT_TRUE(MatNear(g.R_E, h.R_E, 1e-14, 3.0));
}

// The certificate checks what the jump reports: the same bodies pass again, and with the
// elbow's impulse on the lower rod reported 1e-6 N·s off they fail by that much.
TEST(ImpulsiveReactions, ATamperedReportedImpulseFailsTheBalanceCheck) {
  const StruckDoublePendulum p;
  const StudyResult r = RunStudy(DoublePendulum(p));
  ASSERT_EQ(r.jumps.size(), 1u);
  std::vector<BodyImpulseBalance> bodies = r.jumps[0].bodies;
  CertificateBuilder same;
  same.CheckImpulseBalance(r.jumps[0].t, bodies);
  EXPECT_TRUE(same.Finish().passed());
  ASSERT_EQ(bodies[1].body, "lower");
  ASSERT_EQ(bodies[1].impulses[1].source, "elbow");
  bodies[1].impulses[1].J_W.x() += 1e-6;
  CertificateBuilder tampered;
  tampered.CheckImpulseBalance(r.jumps[0].t, bodies);
  const Certificate c = tampered.Finish();
  EXPECT_FALSE(c.passed());
  EXPECT_NEAR(Check(c, "linear impulse balance").worst, 1e-6, 1e-12);
  EXPECT_EQ(Check(c, "linear impulse balance").where, "body 'lower'");
}

// A rod (mass M, length L) pinned at O = 0 about z, lying along x at rest; a bullet (mass m)
// moving along y at speed u hits it at x = d. Angular momentum about O is conserved (the pin's
// impulse has no moment about O).
struct PinnedRodHit {
  double M = 2.0, L = 1.2, m = 0.05, u = 300.0, d = 0.5;
  double I_O() const { return M * L * L / 3; }
  /// Passing through keeping the fraction f: the rod takes J = m (1 - f) u at d, so
  /// I_O ω = J d and the pin gives R = M (L/2) ω - J = J (3 d / (2 L) - 1) along y: zero at the
  /// centre of percussion d = 2L/3.
  double PassThroughPin(double f) const {
    const double J = m * (1 - f) * u;
    return M * L / 2 * (J * d / I_O()) - J;
  }
  /// Embedding: m u d = (I_O + m d²) ω, and the pin's impulse is the momentum after less the
  /// bullet's before, R = (M L/2 + m d) ω - m u: zero at d = 2L/3 too ((M L/2) d = M L²/3).
  double EmbeddingOmega() const { return m * u * d / (I_O() + m * d * d); }
  double EmbeddingPin() const { return (M * L / 2 + m * d) * EmbeddingOmega() - m * u; }

  StudyDefinition Definition(double exit_fraction) const {
    StudyDefinition def;
    def.bodies = {{"rod", Rod(M, L)}, {"bullet", MassProperties::PointMass(m, Vec3::Zero())}};
    // The pin holds the rod's Bo, where ever the rod's user body sits (an embedding makes it
    // part of the composite, whose frame is the rod's).
    def.build_model = [](const std::vector<NamedBody>& bodies, const BodyMap& map) {
      Model model;
      for (const NamedBody& b : bodies) model.AddBody(b.name, b.mass_properties);
      const BodyPlacement& rod = map.place.empty() ? BodyPlacement{} : map.place[0];
      model.AddConstraint(std::make_shared<Joint>(
          "pin", JointKind::kRevolute, kWorld, AttachmentFrame{Vec3::Zero()}, rod.model_body,
          AttachmentFrame{map.place.empty() ? Vec3::Zero() : map.PointInModelBody(0, Vec3::Zero()),
                          rod.R_MB}));
      return model;
    };
    const Model model = def.build_model(def.bodies, {});
    def.initial = MakeRestState(model);
    SetBodyPose(model, 0, Vec3::Zero(), Quat::Identity(), def.initial);  // Bo at the pin
    SetBodyPose(model, 1, Vec3(d, 0, 0), Quat::Identity(), def.initial);
    SetBodyVelocity(model, 1, Vec3(0, u, 0), Vec3::Zero(), def.initial);
    def.options.t_end = 0.001;
    def.options.output_interval = 0.001;
    def.impacts = {{0.0, 0, 1, exit_fraction}};
    return def;
  }
};

TEST(ImpulsiveReactions, PassThroughAPinnedRodGivesThePinItsClosedFormImpulse) {
  for (const double d_over_L : {0.25, 2.0 / 3, 0.9}) {
    PinnedRodHit h;
    h.d = d_over_L * h.L;
    const double f = 0.4, J = h.m * (1 - f) * h.u;
    const StudyResult r = RunStudy(h.Definition(f));
    ASSERT_EQ(r.jumps.size(), 1u);
    const StudyJump& j = r.jumps[0];
    EXPECT_EQ(j.kind, StudyJumpKind::kPassThrough);
    EXPECT_TRUE(MatNear(Reaction(j, "pin").F_Jc_W, Vec3(0, h.PassThroughPin(f), 0), kImpulse, J))
        << "d = " << h.d;
    if (d_over_L == 2.0 / 3) {
      EXPECT_LT(Reaction(j, "pin").F_Jc_W.norm(), kImpulse * J) << "centre of percussion";
    }
    // The rod turns about the pin; the bullet loses (1 - f) of its velocity and takes -J.
    EXPECT_TRUE(MatNear(JumpBody(j, "rod").dw_WB_W, Vec3(0, 0, J * h.d / h.I_O()), kImpulse,
                        J / (h.M * h.L)));
    EXPECT_TRUE(
        MatNear(JumpBody(j, "bullet").dv_WBcm_W, Vec3(0, -(1 - f) * h.u, 0), kImpulse, h.u));
    ASSERT_EQ(JumpBody(j, "bullet").impulses.size(), 1u);
    EXPECT_TRUE(MatNear(JumpBody(j, "bullet").impulses[0].J_W, Vec3(0, -J, 0), kImpulse));
    ExpectBalancesChecked(r);
  }
}

TEST(ImpulsiveReactions, EmbeddingInAPinnedRodGivesThePinItsClosedFormImpulse) {
  for (const double d_over_L : {0.3, 2.0 / 3, 1.0}) {
    PinnedRodHit h;
    h.d = d_over_L * h.L;
    const double P = h.m * h.u;
    const StudyResult r = RunStudy(h.Definition(0.0));
    ASSERT_EQ(r.jumps.size(), 1u);
    const StudyJump& j = r.jumps[0];
    EXPECT_EQ(j.kind, StudyJumpKind::kEmbedding);
    EXPECT_TRUE(MatNear(Reaction(j, "pin").F_Jc_W, Vec3(0, h.EmbeddingPin(), 0), kImpulse, P))
        << "d = " << h.d;
    if (d_over_L == 2.0 / 3) {
      EXPECT_LT(Reaction(j, "pin").F_Jc_W.norm(), kImpulse * P) << "centre of percussion";
    }
    // One body after: the composite turning about the pin; its Δ is the pin's doing, measured
    // from the two bodies' momentum as one free body: M_c Δv = R.
    ASSERT_EQ(j.bodies.size(), 1u);
    const BodyImpulseBalance& c = j.bodies[0];
    EXPECT_EQ(c.body, "rod+bullet");
    EXPECT_TRUE(MatNear(c.w_WB_W, Vec3(0, 0, h.EmbeddingOmega()), kImpulse));
    EXPECT_TRUE(MatNear(c.mass * c.dv_WBcm_W, Vec3(0, h.EmbeddingPin(), 0), kImpulse, P));
    ExpectBalancesChecked(r);
  }
}

// A rod (mass M, length L) pinned at O = 0 about y lies along x with its free end on a floor
// (a plastic contact point at x = L), under gravity; an impulse J straight down at x = d. The
// pin turns the rod down, the end strikes the floor and stops: at rest after, so the floor's
// impulse N and the pin's R (both up) balance J (gravity gives no impulse in an instant):
// N L = J d about O, R = J - N = J (1 - d/L).
TEST(ImpulsiveReactions, AContactImpactAtTheJumpTakesThePinsShareWithIt) {
  const double M = 1.5, L = 0.8, J = 2.0, d = 0.3;
  StudyDefinition def;
  def.bodies = {{"rod", Rod(M, L)}};
  def.build_model = [L](const std::vector<NamedBody>& bodies, const BodyMap&) {
    Model model;
    model.AddBody(bodies[0].name, bodies[0].mass_properties);
    model.AddForceElement(std::make_shared<UniformGravity>("gravity", Vec3(0, 0, -9.81)));
    const Mat3 R_WJ =
        RotationFromAxisAngle(Vec3::UnitX(), -std::numbers::pi / 2);  // J's z along W's y
    model.AddConstraint(std::make_shared<Joint>("pin", JointKind::kRevolute, kWorld,
                                                AttachmentFrame{Vec3::Zero(), R_WJ}, 0,
                                                AttachmentFrame{Vec3::Zero(), R_WJ}));
    ContactSpec floor;
    floor.name = "floor";
    floor.shape = ContactShape::kPointSet;
    floor.body = 0;
    floor.points_B = {Vec3(L, 0, 0)};
    floor.mu_s = 0.5;
    floor.mu_k = 0.4;
    model.AddContact(floor);
    return model;
  };
  const Model model = def.build_model(def.bodies, {});
  def.initial = MakeRestState(model);
  SetBodyPose(model, 0, Vec3::Zero(), Quat::Identity(), def.initial);  // Bo at the pin
  def.options.t_end = 0.01;
  def.options.output_interval = 0.01;
  def.impulses = {{0.0, 0, Vec3(d, 0, 0), Vec3(0, 0, -J), VectorFrame::kWorld}};
  const StudyResult r = RunStudy(def);
  ASSERT_EQ(r.jumps.size(), 1u);
  const StudyJump& j = r.jumps[0];
  EXPECT_TRUE(MatNear(Reaction(j, "pin").F_Jc_W, Vec3(0, 0, J * (1 - d / L)), kImpulse, J));
  // The impact is the run's and the jump's; the rod is at rest after.
  ASSERT_EQ(j.impacts.size(), 1u);
  EXPECT_TRUE(
      Near(r.impacts[static_cast<size_t>(j.impacts[0])].normal_impulse, J * d / L, kImpulse));
  const BodyImpulseBalance& rod = j.bodies[0];
  EXPECT_TRUE(MatNear(rod.v_WBcm_W, Vec3::Zero(), kImpulse, J / M));
  EXPECT_TRUE(MatNear(rod.w_WB_W, Vec3::Zero(), kImpulse, J / (M * L)));
  // Every impulse on it: the applied one, the floor's at the end, the pin's.
  ASSERT_EQ(rod.impulses.size(), 3u);
  EXPECT_EQ(rod.impulses[1].source, "contact 'floor'");
  EXPECT_TRUE(MatNear(rod.impulses[1].J_W, Vec3(0, 0, J * d / L), kImpulse, J));
  EXPECT_TRUE(MatNear(rod.impulses[1].p_WP, Vec3(L, 0, 0), kImpulse, L));
  ExpectBalancesChecked(r);
}

// A solid sphere (mass m, radius R, I = k m R², k = 2/5) rolling without slipping on the floor
// z = 0, at rest, struck along x at the height h above the contact point C. About C (the
// rolling constraint's impulse acts there) (I + m R²) Δω = J h, Δv = R Δω, so the floor's
// friction impulse is F = m Δv - J = J (h / ((1 + k) R) - 1) along x, zero at h = 7R/5 (the
// sphere's centre of percussion), and its normal impulse is zero.
TEST(ImpulsiveReactions, StruckRollingSphereGetsTheFloorsFrictionImpulse) {
  const double m = 0.17, R = 0.028, k = 0.4, J = 0.5;
  for (const double h_over_R : {0.5, 1.4, 1.9}) {
    const double h = h_over_R * R;
    StudyDefinition def;
    def.bodies = {
        {"ball", MassProperties(m, Vec3::Zero(),
                                RotationalInertia(k * m * R * R, k * m * R * R, k * m * R * R))}};
    def.build_model = [R](const std::vector<NamedBody>& bodies, const BodyMap&) {
      Model model;
      model.AddBody(bodies[0].name, bodies[0].mass_properties);
      model.AddConstraint(std::make_shared<RollingContact>("roll", RollingShape::kSphere, 0,
                                                           Vec3::Zero(), Vec3::UnitZ(), R,
                                                           Vec3::Zero(), Vec3::UnitZ()));
      return model;
    };
    const Model model = def.build_model(def.bodies, {});
    def.initial = MakeRestState(model);
    SetBodyPose(model, 0, Vec3(0, 0, R), Quat::Identity(), def.initial);
    def.options.t_end = 0.01;
    def.options.output_interval = 0.01;
    // The point struck, from the centre: h - R above it.
    def.impulses = {{0.0, 0, Vec3(-std::sqrt(R * R - (h - R) * (h - R)), 0, h - R), Vec3(J, 0, 0),
                     VectorFrame::kWorld}};
    const StudyResult r = RunStudy(def);
    ASSERT_EQ(r.jumps.size(), 1u);
    const StudyReaction& roll = Reaction(r.jumps[0], "roll");
    const double F = J * (h / ((1 + k) * R) - 1);
    EXPECT_TRUE(MatNear(roll.F_Jc_W, Vec3(F, 0, 0), kImpulse, J)) << "h = " << h;
    EXPECT_TRUE(Near(roll.normal_force, 0.0, kImpulse, J));
    EXPECT_TRUE(MatNear(roll.friction_W, Vec3(F, 0, 0), kImpulse, J));
    const double w = J * h / ((1 + k) * m * R * R);
    EXPECT_TRUE(MatNear(r.jumps[0].bodies[0].dv_WBcm_W, Vec3(w * R, 0, 0), kImpulse, J / m));
    ExpectBalancesChecked(r);
  }
}

}  // namespace
}  // namespace chasles
