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

}  // namespace
}  // namespace chasles
