// The named steps of RunStudy and RunStudy itself on Models built in code (no scene file):
// each against a closed form derived here.

#include <cmath>
#include <numbers>
#include <random>
#include <utility>

#include "analysis/internal/study_steps.h"
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
using namespace study_internal;

// A box a x b x c of mass m: I = m/12 (b² + c², a² + c², a² + b²) about its centre.
MassProperties Box(double m, double a, double b, double c) {
  return MassProperties(m, Vec3::Zero(),
                        RotationalInertia(m / 12 * (b * b + c * c), m / 12 * (a * a + c * c),
                                          m / 12 * (a * a + b * b)));
}

// Bodies only (no forces): the builder of a free-body study.
Model FreeBodies(const std::vector<NamedBody>& bodies, const BodyMap&) {
  Model model;
  for (const NamedBody& b : bodies) model.AddBody(b.name, b.mass_properties);
  return model;
}

TEST(ThetaTracker, StaysContinuousOverManyTurns) {
  // θ = θ0 + ω t at a sample spacing with ω Δt < π: the tracker follows every turn.
  const double theta0 = 0.3, omega = 7.0, dt = 0.2;
  ThetaTracker theta({theta0});
  for (int k = 0; k <= 100; ++k) {
    const double t = k * dt, expected = theta0 + omega * t;
    const Mat3 R = Eigen::AngleAxisd(expected, Vec3::UnitZ()).toRotationMatrix();
    EXPECT_TRUE(Near(theta.Advance(0, R, omega, t), expected, 1e-12)) << "t = " << t;
  }
  // At() looks ahead without moving the track: twice the same answer.
  const double t = 101 * dt, expected = theta0 + omega * t;
  const Mat3 R = Eigen::AngleAxisd(expected, Vec3::UnitZ()).toRotationMatrix();
  EXPECT_TRUE(Near(theta.At(0, R, omega, t), expected, 1e-12));
  EXPECT_EQ(theta.At(0, R, omega, t), theta.At(0, R, omega, t));
  EXPECT_FALSE(ThetaTracker({}).active());
}

TEST(StudySteps, ImpulseOffTheCentreChangesBothVelocities) {
  // Δv = J / m and Δω = I⁻¹ (r × J) (impulse-momentum, eqs. 8.126-8.128).
  StudyDefinition def;
  def.bodies = {{"box", Box(2.0, 0.4, 0.2, 0.1)}};
  def.build_model = FreeBodies;
  Segment seg = FirstSegment(def);
  State s = MakeRestState(*seg.model);
  const StudyImpulseSpec impulse{0.0, 0, Vec3(0.2, 0.05, 0.0), Vec3(0.0, 3.0, 1.0),
                                 VectorFrame::kWorld};
  EXPECT_EQ(ApplyStudyImpulse(impulse, seg, s), 0);
  const Vec3 dv = impulse.J / 2.0;
  const Mat3 I = def.bodies[0].mass_properties.I_BBcm_B().matrix();
  const Vec3 dw = I.inverse() * impulse.p_BoP_B.cross(impulse.J);
  EXPECT_TRUE(test::MatNear(s.bodies[0].v_WBcm_W, dv, 1e-14));
  EXPECT_TRUE(test::MatNear(s.bodies[0].w_WB_B, dw, 1e-13));
}

TEST(StudySteps, EmbeddingConservesMomentumAndKeepsTheProjectileWhereItWas) {
  // A bullet m moving at v along x strikes a block M at rest off its centre line, at height h:
  // linear momentum m v is conserved (V = m v / (m + M)), and the angular momentum about the
  // composite's centre, which was the bullet's (r_p - r_c) × m v, becomes I_c ω.
  const double m = 0.01, M = 2.0, v = 400.0, h = 0.03;
  StudyDefinition def;
  def.bodies = {{"block", Box(M, 0.2, 0.2, 0.2)},
                {"bullet", MassProperties(m, Vec3::Zero(), RotationalInertia(1e-8, 1e-8, 1e-8))}};
  def.build_model = FreeBodies;
  Segment seg = FirstSegment(def);
  State s = MakeRestState(*seg.model);
  s.bodies[1].p_WBcm = Vec3(-0.1, 0.0, h);
  s.bodies[1].v_WBcm_W = Vec3(v, 0, 0);
  const Vec3 p_bullet = s.bodies[1].p_WBcm;
  const int shown = ApplyStudyImpact({0.0, 0, 1, 0.0}, def.build_model, seg, s);
  ASSERT_EQ(seg.model->num_bodies(), 1);
  EXPECT_EQ(shown, 0);
  EXPECT_EQ(seg.model->body(0).name(), "block+bullet");
  EXPECT_TRUE(Near(seg.model->body(0).mass(), m + M, 1e-15));
  EXPECT_TRUE(test::MatNear(s.bodies[0].v_WBcm_W, Vec3(m * v / (m + M), 0, 0), 1e-14));
  // The bullet's user body still sits where it was, now as part of the composite.
  const MappedBodyMotion bullet = CalcMappedBodyMotion(*seg.model, s, seg.map, 1);
  EXPECT_TRUE(test::MatNear(bullet.p_WBcm, p_bullet, 1e-14, 0.1));
  // H about the composite centre: (r_p - r_c) × m v = I_c ω.
  const Vec3 r_c = m * p_bullet / (m + M);
  const Vec3 H = (p_bullet - r_c).cross(Vec3(m * v, 0, 0));
  const Mat3 I_c = seg.model->body(0).I_BBcm_B().matrix();
  EXPECT_TRUE(test::MatNear(I_c * s.bodies[0].w_WB_B, H, 1e-12));
  // A second impact of the same pair is an error.
  EXPECT_THROW(ApplyStudyImpact({0.0, 0, 1, 0.0}, def.build_model, seg, s), InputError);
}

TEST(StudySteps, RandomEmbeddingsConserveLinearAndAngularMomentumAboutTheOrigin) {
  // Seeded: any two spinning, moving bodies that become one keep P = Σ m v and
  // H_O = Σ (p × m v + R I Rᵀ ω) (no external impulse; eqs. 8.126-8.128).
  std::mt19937 rng(12);
  std::uniform_real_distribution<double> u(-1.0, 1.0), pos(0.1, 2.0);
  for (int trial = 0; trial < 50; ++trial) {
    StudyDefinition def;
    def.bodies = {{"target", Box(pos(rng) * 3, pos(rng), pos(rng), pos(rng))},
                  {"projectile", Box(pos(rng), pos(rng), pos(rng), pos(rng))}};
    def.build_model = FreeBodies;
    Segment seg = FirstSegment(def);
    State s = MakeRestState(*seg.model);
    for (BodyState& b : s.bodies) {
      b.p_WBcm = Vec3(u(rng), u(rng), u(rng));
      b.q_WB = Quat(u(rng), u(rng), u(rng), u(rng)).normalized();
      b.v_WBcm_W = Vec3(u(rng), u(rng), u(rng)) * 10;
      b.w_WB_B = Vec3(u(rng), u(rng), u(rng)) * 10;
    }
    const auto momenta = [](const Model& model, const State& st) {
      Vec3 P = Vec3::Zero(), H = Vec3::Zero();
      for (int b = 0; b < model.num_bodies(); ++b) {
        const BodyState& x = st.bodies[static_cast<size_t>(b)];
        const double m = model.body(b).mass();
        const Mat3 R = x.q_WB.toRotationMatrix();
        P += m * x.v_WBcm_W;
        H += x.p_WBcm.cross(m * x.v_WBcm_W) + R * (model.body(b).I_BBcm_B().matrix() * x.w_WB_B);
      }
      return std::pair{P, H};
    };
    const auto [P0, H0] = momenta(*seg.model, s);
    ApplyStudyImpact({0.0, 0, 1, 0.0}, def.build_model, seg, s);
    const auto [P1, H1] = momenta(*seg.model, s);
    EXPECT_TRUE(test::MatNear(P1, P0, 1e-12, P0.norm() + 1)) << "trial " << trial;
    EXPECT_TRUE(test::MatNear(H1, H0, 1e-12, H0.norm() + 1)) << "trial " << trial;
  }
}

TEST(StudySteps, PassThroughGivesTheTargetTheMomentumLost) {
  // Keeping a fraction e of its velocity, the projectile gives m v (1 - e) to the target.
  const double m = 0.02, M = 3.0, v = 300.0, e = 0.25;
  StudyDefinition def;
  def.bodies = {{"block", Box(M, 0.2, 0.2, 0.2)},
                {"shot", MassProperties(m, Vec3::Zero(), RotationalInertia(1e-8, 1e-8, 1e-8))}};
  def.build_model = FreeBodies;
  Segment seg = FirstSegment(def);
  State s = MakeRestState(*seg.model);
  s.bodies[1].v_WBcm_W = Vec3(v, 0, 0);
  EXPECT_EQ(ApplyStudyImpact({0.0, 0, 1, e}, def.build_model, seg, s), 0);
  EXPECT_TRUE(Near(s.bodies[0].v_WBcm_W.x(), m * v * (1 - e) / M, 1e-14));
  EXPECT_TRUE(Near(s.bodies[1].v_WBcm_W.x(), e * v, 1e-15));
}

TEST(StudySteps, RowsAndTheClosedSegmentBookTheWorkOfAConstantForce) {
  // A free body pushed by a constant F from rest: x = F t² / (2 m), v = F t / m, and the work
  // W = F x = ½ m v² (the ledger's W_nc) with a zero residual for the exact state.
  const double m = 4.0, F = 6.0, t = 1.5;
  const auto build = [F](const std::vector<NamedBody>& bodies, const BodyMap&) {
    Model model;
    model.AddBody(bodies[0].name, bodies[0].mass_properties);
    model.AddForceElement(
        AppliedForce::Constant("push", 0, Vec3::Zero(), Vec3(F, 0, 0), VectorFrame::kWorld));
    return model;
  };
  StudyDefinition def;
  def.bodies = {{"box", Box(m, 0.1, 0.1, 0.1)}};
  def.build_model = build;
  Segment seg = FirstSegment(def);
  LedgerCarry carry;
  carry.segment_initial = MakeRestState(*seg.model);
  State s = carry.segment_initial;
  s.t = t;
  const double x = F * t * t / (2 * m), v = F * t / m;
  s.bodies[0].p_WBcm = Vec3(x, 0, 0);
  s.bodies[0].v_WBcm_W = Vec3(v, 0, 0);
  s.force_integrals[0].work_nonconservative = F * x;  // what the integrator carries
  ThetaTracker theta({});
  RowMaker rows({{"t", "t", -1, "t", "", -1},
                 {"box_x", "position", 0, "x", "", -1},
                 {"box_vx", "velocity", 0, "vx", "", -1},
                 {"box_ax", "acceleration", 0, "ax", "", -1},
                 {"T", "energy", -1, "T", "", -1},
                 {"W_push", "work", -1, "W", "push", -1},
                 {"Px", "momentum", -1, "Px", "", -1}},
                theta);
  const std::vector<double> row = rows.Row(*seg.model, seg.map, s, carry);
  ASSERT_EQ(row.size(), 7u);
  EXPECT_EQ(row[0], t);
  EXPECT_TRUE(Near(row[1], x, 1e-15));
  EXPECT_TRUE(Near(row[2], v, 1e-15));
  EXPECT_TRUE(Near(row[3], F / m, 1e-15));
  EXPECT_TRUE(Near(row[4], 0.5 * m * v * v, 1e-15));
  EXPECT_TRUE(Near(row[5], F * x, 1e-15));
  EXPECT_TRUE(Near(row[6], m * v, 1e-15));
  CloseSegment(*seg.model, s, carry);
  EXPECT_TRUE(Near(carry.work_nc, F * x, 1e-15));
  EXPECT_TRUE(Near(carry.work_by_force.at("push"), F * x, 1e-15));
  EXPECT_TRUE(Near(carry.residual, 0.0, 1e-15, F * x));
  EXPECT_THROW(RowMaker({{"box_q", "position", 0, "nonsense", "", -1}}, theta), InputError);
}

// A block of mass M at rest gets an impulse J along y at t = 0.2 s, then at t = 0.5 s a bullet
// m moving at v along x embeds at its centre: it reaches x = 0 at y = (J / M) (0.5 - 0.2) s, so
// the composite does not turn. Free bodies, no YAML.
constexpr double kBlockM = 2.0, kBulletM = 0.01, kBulletV = 400.0, kImpulseJ = 3.0;
StudyDefinition BulletIntoPushedBlock() {
  const double m = kBulletM, M = kBlockM, v = kBulletV, J = kImpulseJ;
  StudyDefinition def;
  def.bodies = {{"block", Box(M, 0.2, 0.2, 0.2)},
                {"bullet", MassProperties(m, Vec3::Zero(), RotationalInertia(1e-8, 1e-8, 1e-8))}};
  def.build_model = FreeBodies;
  def.initial = MakeRestState(FreeBodies(def.bodies, {}));
  def.initial.bodies[1].p_WBcm = Vec3(-200.0, J / M * 0.3, 0.0);
  def.initial.bodies[1].v_WBcm_W = Vec3(v, 0, 0);
  def.options.t_end = 1.0;
  def.options.output_interval = 0.1;
  def.impulses = {{0.2, 0, Vec3::Zero(), Vec3(0, J, 0), VectorFrame::kWorld}};
  def.impacts = {{0.5, 0, 1, 0.0}};
  return def;
}

TEST(RunStudy, ImpulseThenEmbeddingOnFreeBodiesMatchesMomentumAndTheLedger) {
  // Without YAML: a block at rest gets an impulse J along y at t = 0.2 s, then at t = 0.5 s a
  // bullet moving along x embeds at its centre. Momentum: P = m v e_x + J e_y after the
  // embedding, and the composite moves at V = P / (m + M); the energy jumps are ½ J² / M at
  // the impulse and ½ (m + M) V² - (½ m v² + ½ M (J/M)²) at the plastic embedding.
  const double m = kBulletM, M = kBlockM, v = kBulletV, J = kImpulseJ;
  StudyDefinition def = BulletIntoPushedBlock();
  def.columns = {{"t", "t", -1, "t", "", -1}, {"Py", "momentum", -1, "Py", "", -1}};
  const StudyResult r = RunStudy(def);
  ASSERT_EQ(r.jumps.size(), 2u);
  EXPECT_EQ(r.jumps[0].kind, StudyJumpKind::kImpulse);
  EXPECT_EQ(r.jumps[1].kind, StudyJumpKind::kEmbedding);
  EXPECT_EQ(r.jumps[1].description, "bullet embeds in block");
  EXPECT_TRUE(Near(r.jumps[0].energy_after - r.jumps[0].energy_before, 0.5 * J * J / M, 1e-12));
  // The plastic loss of the embedding: ½ m v² + ½ M Vy² before, ½ (m + M) |V|² after.
  const double Vy = J / M;
  const double before = 0.5 * m * v * v + 0.5 * M * Vy * Vy;
  const Vec3 V(m * v / (m + M), J / (m + M), 0);
  EXPECT_TRUE(Near(r.jumps[1].energy_after - r.jumps[1].energy_before,
                   0.5 * (m + M) * V.squaredNorm() - before, 1e-12));
  ASSERT_EQ(r.final_bodies.size(), 1u);
  EXPECT_TRUE(test::MatNear(r.final_bodies[0].v_WBcm_W, V, 1e-12));
  EXPECT_TRUE(Near(r.ledger.residual, 0.0, 1e-12, r.ledger.energy_scale));
  EXPECT_TRUE(Near(r.ledger.jumps, r.ledger.energy - r.ledger.energy_initial, 1e-12,
                   r.ledger.energy_scale));
  // The rows: Py = 0 up to the impulse, J after; at t = 0.2 s the grid sample just before the
  // jump and the jump's own row just after it.
  bool jumped = false;
  for (const std::vector<double>& row : r.rows) {
    EXPECT_TRUE(Near(row[1], jumped ? J : 0.0, 1e-12, J)) << "t = " << row[0];
    if (std::abs(row[0] - 0.2) < 1e-12) jumped = true;
  }
  EXPECT_TRUE(jumped);
  EXPECT_EQ(r.rows.size(), 11u + 2u);
  EXPECT_TRUE(r.certificate.passed());
}

TEST(RunStudy, RowPosesFollowEveryUserBodyThroughAnEmbedding) {
  // The run of the test above, its poses recorded: a block of mass M at rest gets J along y at
  // t = 0.2 s (then moves at J / M), and a bullet m at v along x embeds at its centre at
  // t = 0.5 s, where both are at (0, 0.3 J / M, 0); the composite then moves at
  // V = (m v, J, 0) / (m + M) without turning. Both user bodies keep a pose of their own at
  // every row, the Model having one body after the embedding; each frame's origin is its centre
  // of mass and no body turns.
  const double m = kBulletM, M = kBlockM, v = kBulletV, J = kImpulseJ;
  StudyDefinition def = BulletIntoPushedBlock();
  def.columns = {{"t", "t", -1, "t", "", -1}};
  def.record_row_poses = true;
  const StudyResult r = RunStudy(def);
  ASSERT_EQ(r.row_poses.size(), r.rows.size());
  const Vec3 meet(0, J / M * 0.3, 0);
  const Vec3 V = Vec3(m * v, J, 0) / (m + M);
  for (size_t i = 0; i < r.rows.size(); ++i) {
    const double t = r.rows[i][0];
    ASSERT_EQ(r.row_poses[i].size(), 2u) << "t = " << t;
    // The rows at a jump's time are the state after it (the grid's sample at t = 0.2 s, just
    // before the impulse, has the block at rest there too).
    const Vec3 block = t <= 0.2   ? Vec3::Zero()
                       : t <= 0.5 ? Vec3(0, J / M * (t - 0.2), 0)
                                  : Vec3(meet + V * (t - 0.5));
    const Vec3 bullet = t < 0.5 ? Vec3(def.initial.bodies[1].p_WBcm + Vec3(v * t, 0, 0)) : block;
    EXPECT_TRUE(test::MatNear(r.row_poses[i][0].p_WBo, block, 1e-12, 1.0)) << "t = " << t;
    EXPECT_TRUE(test::MatNear(r.row_poses[i][1].p_WBo, bullet, 1e-12, 200.0)) << "t = " << t;
    for (const StudyBodyPose& p : r.row_poses[i]) {
      // To round-off: the bullet strikes the centre to the last bits of a 200 m flight, which
      // leaves the composite a turn of order 1e-15 rad.
      EXPECT_TRUE(test::MatNear(p.q_WB.coeffs(), Quat::Identity().coeffs(), 1e-12, 1.0));
      EXPECT_GE(p.q_WB.w(), 0.0);
    }
  }
}

TEST(RunStudy, AStepLimitIsALimitError) {
  StudyDefinition def;
  def.bodies = {{"box", Box(1.0, 0.1, 0.1, 0.1)}};
  def.build_model = FreeBodies;
  def.initial = MakeRestState(FreeBodies(def.bodies, {}));
  def.options.t_end = 1.0;
  def.options.output_interval = 0.5;
  def.options.integrator = IntegratorKind::kRk4;
  def.options.fixed_step = 1e-3;
  def.limits.max_steps = 10;
  try {
    RunStudy(def);
    FAIL() << "no LimitError";
  } catch (const LimitError& e) {
    EXPECT_EQ(e.limit(), LimitError::Limit::kSteps);
  }
}

}  // namespace
}  // namespace chasles
