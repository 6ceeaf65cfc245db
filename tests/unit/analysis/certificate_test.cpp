// The certificate on hand-made data: a ball (mass m, radius R) resting or sliding on a floor
// under gravity g, evaluated by the engine, then one quantity of its Data made wrong on
// purpose. The wrong value must be caught with the right worst value, where and when; the
// engine's own Data must pass.

#include <cmath>
#include <memory>

#include <gtest/gtest.h>

#include "chasles/analysis/certificate.h"
#include "chasles/dynamics/newton_euler.h"
#include "chasles/model/forces.h"
#include "chasles/model/model.h"

namespace chasles {
namespace {

constexpr double kM = 2.0, kR = 0.1, kG = 9.81, kMuS = 0.5, kMuK = 0.3;
// Exact where a check's value is one subtraction of values given here.
constexpr double kExact = 1e-12;

const CheckResult& Find(const Certificate& c, const std::string& name) {
  for (const CheckResult& r : c.checks) {
    if (r.name == name) return r;
  }
  throw std::runtime_error("no check " + name);
}

struct Ball {
  Model model;
  State state;
  Ball(ContactMode mode, const Vec3& v) {
    // Solid sphere: I = 2/5 m R^2 (Appendix A).
    const double I = 0.4 * kM * kR * kR;
    model.AddBody("ball",
                  MassProperties(kM, Vec3::Zero(),
                                 RotationalInertia::FromMatrix(Vec3(I, I, I).asDiagonal())));
    model.AddForceElement(std::make_shared<UniformGravity>("gravity", Vec3(0, 0, -kG)));
    ContactSpec spec;
    spec.name = "floor";
    spec.shape = ContactShape::kSphere;
    spec.body = 0;
    spec.radius = kR;
    spec.mu_s = kMuS;
    spec.mu_k = kMuK;
    model.AddContact(spec);
    state = MakeRestState(model);
    state.t = 0.25;
    SetBodyPose(model, 0, Vec3(0, 0, kR), Quat::Identity(), state);
    SetBodyVelocity(model, 0, v, Vec3::Zero(), state);
    state.contacts.assign(1, ContactPointState{});
    state.contacts[0].mode = mode;
    if (mode == ContactMode::kSliding) state.contacts[0].slip_direction_W = v.normalized();
  }
};

TEST(Certificate, EngineAnswerOfARestingBallPasses) {
  Ball b(ContactMode::kSticking, Vec3::Zero());
  CertificateBuilder builder;
  builder.CheckState(b.model, b.state, CheckPhase::kSample);
  const Certificate c = builder.Finish();
  for (const CheckResult& r : c.checks) EXPECT_TRUE(r.passed()) << r.name << " " << r.worst;
  EXPECT_TRUE(c.passed());
  // N = m g balances the weight: the force scale is m g.
  EXPECT_NEAR(c.force_scale, kM * kG, kExact * kM * kG);
  EXPECT_EQ(Find(c, "friction cone").count, 1);
  EXPECT_EQ(Find(c, "sliding friction").count, 0);  // no sliding point: not applicable
  EXPECT_TRUE(c.FailureMessages().empty());
}

TEST(Certificate, FrictionOutsideTheConeIsCaughtWithItsExcess) {
  Ball b(ContactMode::kSticking, Vec3::Zero());
  Data data = MakeData(b.model);
  CalcAccelerations(b.model, b.state, data);
  // A friction 0.6 m g along x where at most mu_s N = 0.5 m g is possible.
  const Vec3 f(0.6 * kM * kG, 0, 0);
  data.contact_points[0].friction_force_W = f;
  CertificateBuilder builder;
  builder.CheckState(b.model, b.state, data, CheckPhase::kAfterTransition);
  const Certificate c = builder.Finish();
  const CheckResult& cone = Find(c, "friction cone");
  EXPECT_FALSE(cone.passed());
  EXPECT_NEAR(cone.worst, (0.6 - kMuS) * kM * kG, kExact * kM * kG);
  EXPECT_EQ(cone.where, "contact point 'floor'");
  EXPECT_EQ(cone.t, 0.25);
  EXPECT_EQ(cone.phase, CheckPhase::kAfterTransition);
  // The accelerations were not changed: m a = 0 while the forces now sum to f (weight and N
  // cancel), and f at the contact point r = -R e_z has the moment r × f about the centre.
  const CheckResult& lin = Find(c, "linear momentum balance");
  EXPECT_FALSE(lin.passed());
  EXPECT_NEAR(lin.worst, f.norm(), kExact * kM * kG);
  EXPECT_EQ(lin.where, "body 'ball'");
  const CheckResult& ang = Find(c, "angular momentum balance");
  EXPECT_NEAR(ang.worst, kR * f.norm(), kExact * kM * kG * kR);
  EXPECT_FALSE(c.passed());
  EXPECT_EQ(c.FailureMessages().size(), 3u);
  // The others still pass.
  EXPECT_TRUE(Find(c, "normal force").passed());
  EXPECT_TRUE(Find(c, "gap").passed());
}

TEST(Certificate, SlidingFrictionAlongTheSlipIsCaught) {
  const Vec3 v(1.5, 0, 0);
  Ball b(ContactMode::kSliding, v);
  Data data = MakeData(b.model);
  CalcAccelerations(b.model, b.state, data);
  {
    // The engine's answer: f = -mu_k N along the slip.
    CertificateBuilder builder;
    builder.CheckState(b.model, b.state, data, CheckPhase::kSample);
    const Certificate c = builder.Finish();
    EXPECT_TRUE(c.passed());
    EXPECT_EQ(Find(c, "sliding friction").count, 1);
  }
  // Friction pointing with the slip: |f - (-mu_k N s)| = 2 mu_k N = 2 mu_k m g.
  data.contact_points[0].friction_force_W = kMuK * kM * kG * Vec3::UnitX();
  CertificateBuilder builder;
  builder.CheckState(b.model, b.state, data, CheckPhase::kSample);
  const Certificate finished = builder.Finish();
  const CheckResult& r = Find(finished, "sliding friction");
  EXPECT_FALSE(r.passed());
  EXPECT_NEAR(r.worst, 2 * kMuK * kM * kG, kExact * kM * kG);
}

TEST(Certificate, PullingNormalForceAndPenetrationAreCaught) {
  Ball b(ContactMode::kSticking, Vec3::Zero());
  // The ball 1 µm into the floor: gap -1e-6 m.
  b.state.bodies[0].p_WBcm.z() = kR - 1e-6;
  Data data = MakeData(b.model);
  CalcAccelerations(b.model, b.state, data);
  data.contact_points[0].normal_force = -0.5 * kM * kG;
  CertificateBuilder builder;
  builder.CheckState(b.model, b.state, data, CheckPhase::kEvent);
  const Certificate c = builder.Finish();
  const CheckResult& n = Find(c, "normal force");
  EXPECT_FALSE(n.passed());
  EXPECT_NEAR(n.worst, 0.5 * kM * kG, kExact * kM * kG);
  EXPECT_EQ(n.phase, CheckPhase::kEvent);
  const CheckResult& gap = Find(c, "gap");
  EXPECT_FALSE(gap.passed());
  EXPECT_NEAR(gap.worst, 1e-6, 1e-9 * 1e-6 + kExact * kR);
}

TEST(Certificate, LedgerResidualAgainstTheEnergyScale) {
  CertificateTolerances tol;
  CertificateBuilder builder(tol);
  builder.CheckLedger(1.0, 1e-12, 10.0, CheckPhase::kSample);
  builder.CheckLedger(2.0, -1e-3, 10.0, CheckPhase::kSample);
  builder.CheckLedger(3.0, 2e-12, 10.0, CheckPhase::kSample);
  const Certificate finished = builder.Finish();
  const CheckResult& r = Find(finished, "ledger");
  EXPECT_FALSE(r.passed());
  EXPECT_EQ(r.worst, 1e-3);
  EXPECT_EQ(r.tolerance, tol.ledger * 10.0);
  EXPECT_EQ(r.t, 2.0);
  EXPECT_EQ(r.count, 3);
}

// A long run keeps bounded memory (entries far below the worst are dropped as it goes) and
// still reports the worst value, where and when, and the count of every value checked.
TEST(Certificate, LongRunsKeepTheWorstValue) {
  CertificateBuilder builder;
  const int n = 200000;
  for (int i = 0; i < n; ++i) {
    const double residual = i == 123456 ? 1e-3 : 1e-13 * (i % 7);
    builder.CheckLedger(static_cast<double>(i), residual, 10.0, CheckPhase::kSample);
  }
  const Certificate finished = builder.Finish();
  const CheckResult& r = Find(finished, "ledger");
  EXPECT_EQ(r.count, n);
  EXPECT_EQ(r.worst, 1e-3);
  EXPECT_EQ(r.t, 123456.0);
  EXPECT_FALSE(r.passed());
}

// Section 8.5: a cube (mass m, side a) at rest, its frame at a corner, struck at the corner
// (a, 0, 0) by J along y. Impulse-momentum (eqs. 8.118, 8.119): m Δv = J, and about the centre
// (a/2)(1, 1, 1) ΔH = r × J with r = (a/2)(1, -1, -1). The balance made from these passes; one
// with a wrong impulse or an extra moment impulse fails with the error as its worst value.
struct StruckCube {
  double m = 3.0, a = 0.5;
  Vec3 J = Vec3(0, 2, 0);
  BodyImpulseBalance Balance() const {
    BodyImpulseBalance b;
    b.body = "cube";
    b.mass = m;
    b.p_WBcm = Vec3::Constant(a / 2);
    const Vec3 r = Vec3(a, 0, 0) - b.p_WBcm;
    b.dv_WBcm_W = b.v_WBcm_W = J / m;
    b.dH_Bcm_W = b.H_Bcm_W = r.cross(J);
    b.dw_WB_W = b.w_WB_W = b.dH_Bcm_W / (m * a * a / 6);  // I = m a²/6 E (Appendix A)
    b.impulses = {{"applied", Vec3(a, 0, 0), J, Vec3::Zero()}};
    return b;
  }
};

TEST(Certificate, ImpulseBalanceOfAStruckCubePassesAndAWrongImpulseFails) {
  const StruckCube cube;
  CertificateTolerances tol;
  {
    CertificateBuilder builder(tol);
    builder.CheckImpulseBalance(0.1, {cube.Balance()});
    const Certificate c = builder.Finish();
    for (const char* name : {"linear impulse balance", "angular impulse balance"}) {
      EXPECT_EQ(Find(c, name).count, 1) << name;
      EXPECT_TRUE(Find(c, name).passed()) << name;
      EXPECT_LE(Find(c, name).worst, kExact * cube.J.norm()) << name;
    }
    EXPECT_EQ(c.impulse_scale, cube.J.norm());
  }
  // The impulse reported 0.1 % too large: m Δv - J' = -0.001 J.
  BodyImpulseBalance wrong = cube.Balance();
  wrong.impulses[0].J_W *= 1.001;
  CertificateBuilder builder(tol);
  builder.CheckImpulseBalance(0.1, {wrong});
  const Certificate c = builder.Finish();
  const CheckResult& linear = Find(c, "linear impulse balance");
  EXPECT_FALSE(linear.passed());
  EXPECT_NEAR(linear.worst, 0.001 * cube.J.norm(), kExact);
  EXPECT_EQ(linear.where, "body 'cube'");
  EXPECT_EQ(linear.t, 0.1);
  EXPECT_EQ(linear.phase, CheckPhase::kJump);
  EXPECT_FALSE(Find(c, "angular impulse balance").passed());
  EXPECT_FALSE(c.passed());
  // A moment impulse the body did not take: only the angular balance fails, by its size.
  BodyImpulseBalance extra = cube.Balance();
  extra.impulses.push_back({"extra", Vec3::Zero(), Vec3::Zero(), Vec3(0, 0, 1e-4)});
  CertificateBuilder again(tol);
  again.CheckImpulseBalance(0.2, {extra});
  const Certificate e = again.Finish();
  EXPECT_TRUE(Find(e, "linear impulse balance").passed());
  EXPECT_FALSE(Find(e, "angular impulse balance").passed());
  EXPECT_NEAR(Find(e, "angular impulse balance").worst, 1e-4, kExact);
}

}  // namespace
}  // namespace chasles
