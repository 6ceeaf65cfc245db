// Reactions of supports (chapter 8.2-8.3: "what force does the support exert?") from the
// constraint solve, against closed forms derived here: pendulum tension, a pinned rod released
// from horizontal, a slider on a frictionless incline, a rod sliding on a wall and a floor
// (Example 8.4), a rod pinned to a cart with prescribed acceleration (Section 8.2.2), and a
// tilted disk on a shaft turned at constant rate (Problem 8.31).

#include <cmath>
#include <memory>
#include <numbers>

#include <gtest/gtest.h>

#include "chasles/analysis/instantaneous.h"
#include "chasles/dynamics/constraint_solve.h"
#include "chasles/integrate/simulate.h"
#include "chasles/math/rotation.h"
#include "chasles/model/constraints.h"
#include "chasles/model/forces.h"
#include "chasles/model/model.h"
#include "test_support.h"

namespace chasles {
namespace {

using test::MatNear;
using test::Near;

constexpr double kG = 9.81;
constexpr double kSolve = 1e-12;  // one dense linear solve: round-off only
const Vec3 kGravity(0, -kG, 0);

MassProperties Diagonal(double m, const Vec3& I) {
  return MassProperties(m, Vec3::Zero(), RotationalInertia::FromMatrix(I.asDiagonal()));
}
// A slender rod along its body x axis: transverse moments m L²/12; its own axis gets a tiny
// moment so the body is invertible (a planar joint or the motion keeps that spin zero).
MassProperties SlenderRod(double m, double L) {
  const double It = m * L * L / 12.0;
  return Diagonal(m, Vec3(1e-6 * It, It, It));
}

Quat RotZ(double angle) {
  return Quat(RotationFromAxisAngle(Vec3::UnitZ(), angle));
}

// A bob on a massless rod of length L (point-like: a small sphere) through the bottom at
// speed v. Radial Newton: T - m g = m v²/L (the tangential acceleration is zero there).
TEST(SupportReaction, PendulumTensionAtTheBottomIsMgPlusMv2OverL) {
  const double m = 1.3, L = 0.8, v = 2.1, r = 0.01;
  Model model;
  model.AddBody("bob", Diagonal(m, Vec3::Constant(0.4 * m * r * r)));
  model.AddForceElement(std::make_shared<UniformGravity>("gravity", kGravity));
  State s = MakeRestState(model);
  SetBodyPose(model, 0, Vec3(0, -L, 0), Quat::Identity(), s);
  SetBodyVelocity(model, 0, Vec3(v, 0, 0), Vec3(0, 0, v / L), s);  // ω ẑ × (0, -L, 0) = (ωL, 0, 0)
  model.AddConstraint(std::make_shared<Joint>(
      "pivot", JointKind::kRevolute, kWorld, AttachmentFrame{Vec3::Zero()}, 0,
      AttachmentFrameAtWorldPose(model, s, 0, Vec3::Zero(), Mat3::Identity())));
  const InstantaneousSolution sol = SolveInstantaneous(model, s);
  const double T = m * kG + m * v * v / L;
  EXPECT_TRUE(MatNear(sol.reactions[0].F_Jc_W, Vec3(0, T, 0), kSolve));
  EXPECT_TRUE(MatNear(sol.reactions[0].M_Jc_W, Vec3::Zero(), kSolve, T * L));
  // In the bob's frame (identity here) the same force; the joint does no work.
  EXPECT_TRUE(MatNear(sol.reactions[0].F_Jc_B, Vec3(0, T, 0), kSolve));
  EXPECT_TRUE(Near(sol.reactions[0].power, 0.0, kSolve, T * v));
  EXPECT_TRUE(MatNear(sol.bodies[0].a_WBcm_W, Vec3(0, v * v / L, 0), kSolve, kG));
}

// A slender rod pinned at one end, released from horizontal. About the pivot:
// (m L²/3) α = m g L/2 → α = 3g/(2L); a_cm = α L/2 = 3g/4 downward, so the pivot pushes up
// with R = m g - m (3g/4) = m g/4 (and no horizontal force: ω = 0).
TEST(SupportReaction, PinnedRodReleasedFromHorizontal) {
  const double m = 2.4, L = 1.5;
  Model model;
  model.AddBody("rod", SlenderRod(m, L));
  model.AddForceElement(std::make_shared<UniformGravity>("gravity", kGravity));
  State s = MakeRestState(model);
  SetBodyPose(model, 0, Vec3(L / 2, 0, 0), Quat::Identity(), s);
  model.AddConstraint(std::make_shared<Joint>("pin", JointKind::kRevolute, kWorld,
                                              AttachmentFrame{Vec3::Zero()}, 0,
                                              AttachmentFrame{Vec3(-L / 2, 0, 0)}));
  const InstantaneousSolution sol = SolveInstantaneous(model, s);
  EXPECT_TRUE(MatNear(sol.bodies[0].alpha_WB_W, Vec3(0, 0, -1.5 * kG / L), kSolve));
  EXPECT_TRUE(MatNear(sol.reactions[0].F_Jc_W, Vec3(0, m * kG / 4, 0), kSolve));
  EXPECT_TRUE(MatNear(sol.reactions[0].M_Jc_W, Vec3::Zero(), kSolve, m * kG * L));
}

// A block on a frictionless guide down an incline of angle θ: m a = m g sin θ along the
// slope, N = m g cos θ normal to it, and no moment (gravity acts at the centre of mass, which
// is the joint point). The same for a prismatic guide, a cylindrical one (free to turn about
// the guide) and a bead on a wire (point on a line).
TEST(SupportReaction, SliderOnAnInclinedGuide) {
  const double m = 3.0, theta = 0.5;
  const Vec3 down(std::cos(theta), -std::sin(theta), 0), n(std::sin(theta), std::cos(theta), 0);
  for (JointKind kind : {JointKind::kPrismatic, JointKind::kCylindrical, JointKind::kPointOnLine}) {
    Model model;
    model.AddBody("block", Diagonal(m, Vec3(0.1, 0.2, 0.15)));
    model.AddForceElement(std::make_shared<UniformGravity>("gravity", kGravity));
    State s = MakeRestState(model);
    SetBodyPose(model, 0, Vec3(0.2, 0.3, 0), Quat::Identity(), s);
    SetBodyVelocity(model, 0, 1.7 * down, Vec3::Zero(), s);
    const Mat3 R = FrameWithZAxis(down);
    model.AddConstraint(
        std::make_shared<Joint>("guide", kind, kWorld, AttachmentFrame{Vec3(0.2, 0.3, 0), R}, 0,
                                AttachmentFrameAtWorldPose(model, s, 0, Vec3(0.2, 0.3, 0), R)));
    const InstantaneousSolution sol = SolveInstantaneous(model, s);
    SCOPED_TRACE(JointKindName(kind));
    EXPECT_TRUE(MatNear(sol.bodies[0].a_WBcm_W, kG * std::sin(theta) * down, kSolve, kG));
    EXPECT_TRUE(MatNear(sol.bodies[0].alpha_WB_W, Vec3::Zero(), kSolve, kG));
    EXPECT_TRUE(MatNear(sol.reactions[0].F_Jc_W, m * kG * std::cos(theta) * n, kSolve));
    EXPECT_TRUE(MatNear(sol.reactions[0].M_Jc_W, Vec3::Zero(), kSolve, m * kG));
    EXPECT_TRUE(Near(sol.reactions[0].power, 0.0, kSolve, m * kG * 1.7));
  }
}

// Example 8.4: a slender rod (mass m, length L) with end A on a frictionless wall (x = 0) and
// end B on a frictionless floor (y = 0), in the x-y plane; θ is its angle from the wall
// (vertical). Derivation: the centre G = (L/2)(sin θ, cos θ); with no friction and no
// other forces, energy from rest at θ0:
//   T = ½ m (L/2)² θ̇² + ½ (m L²/12) θ̇² = (m L²/6) θ̇² = m g (L/2)(cos θ0 - cos θ)
//   θ̇² = (3g/L)(cos θ0 - cos θ),   θ̈ = (3g/(2L)) sin θ.
// Newton on G: N_A = m ẍ_G = m (L/2)(cos θ θ̈ - sin θ θ̇²) = (3mg/4) sin θ (3 cos θ - 2 cos θ0),
//              N_B = m g + m ÿ_G = m g [1/4 + (9/4) cos² θ - (3/2) cos θ cos θ0].
// At rest (θ = θ0) these are the chapter's N_A = (3/4) m g sin θ0 cos θ0 and
// N_B = m g - (3/4) m g sin² θ0. N_A = 0 when cos θ = (2/3) cos θ0: the rod leaves the wall.
struct Ladder {
  double m = 1.7, L = 2.0, theta0 = 0.4;
  Model model;
  State Build(double theta) {
    model = Model();
    model.AddBody("rod", SlenderRod(m, L));
    model.AddForceElement(std::make_shared<UniformGravity>("gravity", kGravity));
    State s = MakeRestState(model);
    // Body x from B (floor end) to A (wall end): direction (-sin θ, cos θ), angle π/2 + θ.
    SetBodyPose(model, 0, 0.5 * L * Vec3(std::sin(theta), std::cos(theta), 0),
                RotZ(std::numbers::pi / 2 + theta), s);
    const double theta_dot = std::sqrt(3 * kG / L * (std::cos(theta0) - std::cos(theta)));
    SetBodyVelocity(model, 0, 0.5 * L * theta_dot * Vec3(std::cos(theta), -std::sin(theta), 0),
                    Vec3(0, 0, theta_dot), s);
    model.AddConstraint(
        std::make_shared<Joint>("wall", JointKind::kPointOnPlane, kWorld,
                                AttachmentFrame{Vec3::Zero(), FrameWithZAxis(Vec3::UnitX())}, 0,
                                AttachmentFrame{Vec3(L / 2, 0, 0)}));
    model.AddConstraint(
        std::make_shared<Joint>("floor", JointKind::kPointOnPlane, kWorld,
                                AttachmentFrame{Vec3::Zero(), FrameWithZAxis(Vec3::UnitY())}, 0,
                                AttachmentFrame{Vec3(-L / 2, 0, 0)}));
    // Keeps the motion in the x-y plane (and the rod's own spin zero); carries no load.
    model.AddConstraint(std::make_shared<Joint>(
        "plane", JointKind::kPlanar, kWorld, AttachmentFrame{Vec3::Zero()}, 0,
        AttachmentFrameAtWorldPose(model, s, 0, s.bodies[0].p_WBcm, Mat3::Identity())));
    return s;
  }
  double NA(double th) const {
    return 0.75 * m * kG * std::sin(th) * (3 * std::cos(th) - 2 * std::cos(theta0));
  }
  double NB(double th) const {
    const double c = std::cos(th);
    return m * kG * (0.25 + 2.25 * c * c - 1.5 * c * std::cos(theta0));
  }
};

TEST(SupportReaction, RodSlidingOnWallAndFloorExample84) {
  Ladder ladder;
  for (const double theta : {ladder.theta0, 0.6, 0.9}) {
    const State s = ladder.Build(theta);
    const InstantaneousSolution sol = SolveInstantaneous(ladder.model, s);
    const double scale = ladder.m * kG;
    EXPECT_TRUE(Near(sol.bodies[0].alpha_WB_W.z(), 1.5 * kG / ladder.L * std::sin(theta), 1e-11))
        << "theta = " << theta;
    EXPECT_TRUE(MatNear(sol.reactions[0].F_Jc_W, Vec3(ladder.NA(theta), 0, 0), 1e-11, scale));
    EXPECT_TRUE(MatNear(sol.reactions[1].F_Jc_W, Vec3(0, ladder.NB(theta), 0), 1e-11, scale));
    EXPECT_TRUE(MatNear(sol.reactions[2].F_Jc_W, Vec3::Zero(), 1e-11, scale));
    for (const ReactionReport& r : sol.reactions) {
      EXPECT_TRUE(Near(r.power, 0.0, 1e-11, scale * std::sqrt(kG * ladder.L))) << r.name;
    }
  }
}

TEST(SupportReaction, RodLeavesTheWallWhereCosThetaIsTwoThirdsCosTheta0) {
  Ladder ladder;
  const State s0 = ladder.Build(ladder.theta0);
  SimulationOptions o;
  o.t_end = 5.0;
  o.adaptive.rtol = 1e-12;
  o.adaptive.atol = 1e-14;
  EventSpec leaves;
  leaves.name = "wall reaction zero";
  leaves.direction = EventDirection::kFalling;
  leaves.g = [&](const Model&, const State& s) {
    return SolveInstantaneous(ladder.model, s, {1e-7}).reactions[0].F_Jc_W.x();
  };
  o.events.push_back(leaves);
  const SimulationResult r = Simulate(ladder.model, s0, o);
  ASSERT_TRUE(r.stopped_by_event);
  const Vec3 x_B = r.final_state.bodies[0].q_WB * Vec3::UnitX();  // (-sin θ, cos θ, 0)
  const double theta = std::atan2(-x_B.x(), x_B.y());
  EXPECT_TRUE(Near(std::cos(theta), 2.0 / 3.0 * std::cos(ladder.theta0), 1e-8));
}

// Section 8.2.2: a slender rod (mass m, length L) pinned at its top end to a cart that is
// driven with constant acceleration a along x. θ is the angle the rod swings back from the
// downward vertical (tip at pivot + L(-sin θ, -cos θ)). About the accelerating pivot, with
// the inertial force -m a at G (the chapter's eq. 8.64 with ℓ = L/2):
//   (m L²/3) θ̈ = m (L/2)(a cos θ - g sin θ)  →  θ̈ = (3/(2L))(a cos θ - g sin θ)  (8.65)
//   θ̇² = (3g/L)((a/g) sin θ + cos θ - 1)  from rest at θ = 0                    (8.68)
// The driver pushes the cart (mass M) and, through the pin, the rod's horizontal motion:
//   F = M a + m ẍ_G,   ẍ_G = a - (L/2)(cos θ θ̈ - sin θ θ̇²).
struct CartRod {
  double M = 5.0, m = 1.2, L = 0.9, a = 3.0;
  Model model;
  State Build(double theta, double t) {
    model = Model();
    model.AddBody("cart", Diagonal(M, Vec3(0.5, 0.6, 0.7)));
    model.AddBody("rod", SlenderRod(m, L));
    model.AddForceElement(std::make_shared<UniformGravity>("gravity", kGravity));
    State s = MakeRestState(model);
    s.t = t;
    const double x = 0.5 * a * t * t, V = a * t;
    SetBodyPose(model, 0, Vec3(x, 0, 0), Quat::Identity(), s);
    SetBodyVelocity(model, 0, Vec3(V, 0, 0), Vec3::Zero(), s);
    const double theta_dot =
        theta == 0.0 ? 0.0
                     : std::sqrt(3 * kG / L * (a / kG * std::sin(theta) + std::cos(theta) - 1));
    const Vec3 e(-std::sin(theta), -std::cos(theta), 0);  // pivot to tip
    SetBodyPose(model, 1, Vec3(x, 0, 0) + 0.5 * L * e, RotZ(std::atan2(e.y(), e.x())), s);
    // ω_z = -θ̇ (θ grows clockwise seen from +z); v_G = v_pivot + ω × (L/2) e.
    const Vec3 w(0, 0, -theta_dot);
    SetBodyVelocity(model, 1, Vec3(V, 0, 0) + w.cross(0.5 * L * e), w, s);
    const Mat3 Rx = FrameWithZAxis(Vec3::UnitX());
    model.AddConstraint(std::make_shared<Joint>(
        "rail", JointKind::kPrismatic, kWorld, AttachmentFrame{Vec3::Zero(), Rx}, 0,
        AttachmentFrameAtWorldPose(model, s, 0, Vec3(x, 0, 0), Rx)));
    model.AddConstraint(std::make_shared<PrescribedMotion>(
        "drive", DriverKind::kTranslation, kWorld, AttachmentFrame{Vec3::Zero(), Rx}, 0,
        AttachmentFrame{Vec3::Zero(), Mat3::Identity()}, TimeFunction::Quadratic(0, 0, a)));
    model.AddConstraint(std::make_shared<Joint>("pin", JointKind::kRevolute, 0,
                                                AttachmentFrame{Vec3::Zero()}, 1,
                                                AttachmentFrame{Vec3(-L / 2, 0, 0)}));
    return s;
  }
  double Alpha(double th) const { return 1.5 / L * (a * std::cos(th) - kG * std::sin(th)); }
  double OmegaSquared(double th) const {
    return 3 * kG / L * (a / kG * std::sin(th) + std::cos(th) - 1);
  }
  double DriverForce(double th) const {
    const double xdd_G = a - 0.5 * L * (std::cos(th) * Alpha(th) - std::sin(th) * OmegaSquared(th));
    return M * a + m * xdd_G;
  }
};

TEST(SupportReaction, RodOnAnAcceleratingCartSection822) {
  CartRod cr;
  for (const double theta : {0.0, 0.2, 0.45}) {
    const State s = cr.Build(theta, 0.7);
    const InstantaneousSolution sol = SolveInstantaneous(cr.model, s);
    // θ̈ = -ω̇_z.
    EXPECT_TRUE(Near(-sol.bodies[1].alpha_WB_W.z(), cr.Alpha(theta), 1e-11, cr.a / cr.L))
        << "theta = " << theta;
    ASSERT_EQ(sol.reactions[1].lambda.size(), 1u);
    EXPECT_TRUE(Near(sol.reactions[1].lambda[0], cr.DriverForce(theta), 1e-11)) << theta;
    EXPECT_TRUE(MatNear(sol.bodies[0].a_WBcm_W, Vec3(cr.a, 0, 0), 1e-12, cr.a));
    // The driver's power is its force times the cart's speed; the joints do no work.
    EXPECT_TRUE(Near(sol.reactions[1].power, cr.DriverForce(theta) * cr.a * 0.7, 1e-11));
    EXPECT_TRUE(Near(sol.reactions[2].power, 0.0, 1e-11, cr.DriverForce(theta) * cr.a));
  }
}

TEST(SupportReaction, RodOnAnAcceleratingCartFollowsEq868) {
  CartRod cr;
  const State s0 = cr.Build(0.0, 0.0);
  SimulationOptions o;
  o.t_end = 1.0;
  o.output_interval = 0.1;
  o.adaptive.rtol = 1e-11;
  o.adaptive.atol = 1e-13;
  const SimulationResult r = Simulate(cr.model, s0, o);
  Data data = MakeData(cr.model);
  for (const State& s : r.samples) {
    const Vec3 e = s.bodies[1].q_WB * Vec3::UnitX();  // (-sin θ, -cos θ)
    const double theta = std::atan2(-e.x(), -e.y());
    const double w = s.bodies[1].w_WB_B.z();
    EXPECT_TRUE(Near(w * w, cr.OmegaSquared(theta), 1e-8, 3 * kG / cr.L)) << "t = " << s.t;
    EXPECT_TRUE(Near(s.bodies[0].p_WBcm.x(), 0.5 * cr.a * s.t * s.t, 1e-9, 1.0));
    // Samples come from the dense output, projected back onto the constraints.
    const ConstraintViolation v = CalcConstraintViolation(cr.model, s, data);
    EXPECT_LT(v.position, 1e-13) << "t = " << s.t;
    EXPECT_LT(v.velocity, 1e-13) << "t = " << s.t;
  }
}

// Problem 8.31: a thin disk (mass m, radius R: I1 = m R²/4 about a diameter, I3 = m R²/2
// about its axis) fixed at its centre to a shaft turned at constant rate Ω about z, the
// disk's axis tilted by β from the shaft. Its angular momentum H = I Ω ẑ turns with the shaft,
// so the bearing must supply M = Ω ẑ × H (Euler's equation in W with ω̇ = 0):
//   |M| = (I3 - I1) Ω² sin β cos β, perpendicular to the plane of ẑ and the disk's axis,
// and the drive supplies no moment about the shaft.
TEST(SupportReaction, TiltedDiskOnARotatingShaftProblem831) {
  const double m = 2.0, R = 0.3, Omega = 12.0, beta = 0.25;
  const double I1 = m * R * R / 4, I3 = m * R * R / 2;
  Model model;
  model.AddBody("disk", Diagonal(m, Vec3(I1, I1, I3)));
  model.AddForceElement(std::make_shared<UniformGravity>("gravity", kGravity));
  State s = MakeRestState(model);
  SetBodyPose(model, 0, Vec3::Zero(), Quat(RotationFromAxisAngle(Vec3::UnitX(), beta)), s);
  SetBodyVelocity(model, 0, Vec3::Zero(), Vec3(0, 0, Omega), s);
  model.AddConstraint(std::make_shared<Joint>(
      "bearing", JointKind::kRevolute, kWorld, AttachmentFrame{Vec3::Zero()}, 0,
      AttachmentFrameAtWorldPose(model, s, 0, Vec3::Zero(), Mat3::Identity())));
  model.AddConstraint(std::make_shared<PrescribedMotion>(
      "motor", DriverKind::kRotation, kWorld, AttachmentFrame{Vec3::Zero()}, 0,
      AttachmentFrameAtWorldPose(model, s, 0, Vec3::Zero(), Mat3::Identity()),
      TimeFunction::Quadratic(0, Omega, 0)));
  const double M_expected = (I3 - I1) * Omega * Omega * std::sin(beta) * std::cos(beta);
  auto check = [&](const State& st) {
    const InstantaneousSolution sol = SolveInstantaneous(model, st);
    const Vec3 axis = st.bodies[0].q_WB * Vec3::UnitZ();
    const Vec3 dir = Vec3::UnitZ().cross(axis).normalized();
    // H_W = R I_B Rᵀ Ω ẑ; the sign of M follows from Ω ẑ × H.
    const Mat3 Rm = st.bodies[0].q_WB.toRotationMatrix();
    const Vec3 H = Rm * Vec3(I1, I1, I3).asDiagonal() * Rm.transpose() * Vec3(0, 0, Omega);
    const Vec3 M = Vec3(0, 0, Omega).cross(H);
    EXPECT_TRUE(Near(M.norm(), M_expected, 1e-12));
    EXPECT_TRUE(MatNear(sol.reactions[0].M_Jc_W, M, 1e-11, M_expected)) << "t = " << st.t;
    EXPECT_TRUE(Near(std::abs(sol.reactions[0].M_Jc_W.dot(dir)), M_expected, 1e-11));
    EXPECT_TRUE(Near(sol.reactions[1].lambda[0], 0.0, 1e-11, M_expected));
    EXPECT_TRUE(MatNear(sol.reactions[0].F_Jc_W, Vec3(0, m * kG, 0), 1e-11));
  };
  check(s);
  SimulationOptions o;
  o.t_end = 0.7;
  o.adaptive.rtol = 1e-11;
  o.adaptive.atol = 1e-13;
  const SimulationResult r = Simulate(model, s, o);
  check(r.final_state);
  EXPECT_TRUE(MatNear(Vec3(r.final_state.bodies[0].q_WB * r.final_state.bodies[0].w_WB_B),
                      Vec3(0, 0, Omega), 1e-9));
}

// A conical pendulum on a spherical joint: a small sphere (mass m) at distance L from the
// pivot, the string at angle α from the downward vertical, going round a horizontal circle of
// radius ρ = L sin α. Vertical balance T cos α = m g, radial T sin α = m v²/ρ give
// T = m g / cos α and v² = g L sin α tan α; the whole body turns at Ω = v/ρ about z, and a
// sphere's spin adds no moment (I w is parallel to w).
TEST(SupportReaction, ConicalPendulumOnASphericalJoint) {
  const double m = 0.9, L = 1.1, alpha = 0.6, r = 0.02;
  const double rho = L * std::sin(alpha), v = std::sqrt(kG * L * std::sin(alpha) * std::tan(alpha));
  Model model;
  model.AddBody("bob", Diagonal(m, Vec3::Constant(0.4 * m * r * r)));
  model.AddForceElement(std::make_shared<UniformGravity>("gravity", kGravity));
  State s = MakeRestState(model);
  // Gravity along -y, so the circle lies in a plane y = const: the bob at (ρ, -L cos α, 0)
  // moving along -z, the body turning at Ω = (v/ρ) ŷ (Ω ŷ × ρ x̂ = -Ωρ ẑ).
  SetBodyPose(model, 0, Vec3(rho, -L * std::cos(alpha), 0), Quat::Identity(), s);
  SetBodyVelocity(model, 0, Vec3(0, 0, -v), Vec3(0, v / rho, 0), s);
  model.AddConstraint(std::make_shared<Joint>(
      "ball", JointKind::kSpherical, kWorld, AttachmentFrame{Vec3::Zero()}, 0,
      AttachmentFrameAtWorldPose(model, s, 0, Vec3::Zero(), Mat3::Identity())));
  const InstantaneousSolution sol = SolveInstantaneous(model, s);
  const double T = m * kG / std::cos(alpha);
  const Vec3 to_pivot = -s.bodies[0].p_WBcm.normalized();
  EXPECT_TRUE(MatNear(sol.reactions[0].F_Jc_W, T * to_pivot, kSolve));
  EXPECT_TRUE(MatNear(sol.bodies[0].a_WBcm_W, Vec3(-v * v / rho, 0, 0), kSolve, kG));
  EXPECT_TRUE(MatNear(sol.bodies[0].alpha_WB_W, Vec3::Zero(), kSolve, kG / L));
}

// A weld: a uniform rod (m1, L) pinned at its top end, with a small block (m2, moment I2
// about its centre) welded at its lower end, released at φ from the downward vertical. As
// one compound pendulum about the pin: I_O φ̈ = -(m1 L/2 + m2 L) g sin φ,
// I_O = m1 L²/3 + m2 L² + I2. The weld then carries the block's Newton–Euler load:
// F = m2 (a_2 - g) and, about the block's centre, M = I2 φ̈ ẑ.
TEST(SupportReaction, WeldedBlockMovesWithTheRod) {
  const double m1 = 1.5, L = 1.2, m2 = 0.8, I2 = 0.004, phi = 0.7;
  Model model;
  model.AddBody("rod", SlenderRod(m1, L));
  model.AddBody("block", Diagonal(m2, Vec3(I2, I2, I2)));
  model.AddForceElement(std::make_shared<UniformGravity>("gravity", kGravity));
  State s = MakeRestState(model);
  const Vec3 e(std::sin(phi), -std::cos(phi), 0);   // pin to lower end
  const Quat q = RotZ(phi - std::numbers::pi / 2);  // body x along e
  SetBodyPose(model, 0, 0.5 * L * e, q, s);
  SetBodyPose(model, 1, L * e, q, s);
  model.AddConstraint(std::make_shared<Joint>("pin", JointKind::kRevolute, kWorld,
                                              AttachmentFrame{Vec3::Zero()}, 0,
                                              AttachmentFrame{Vec3(-L / 2, 0, 0)}));
  model.AddConstraint(std::make_shared<Joint>("weld", JointKind::kWeld, 0,
                                              AttachmentFrame{Vec3(L / 2, 0, 0)}, 1,
                                              AttachmentFrame{Vec3::Zero()}));
  const InstantaneousSolution sol = SolveInstantaneous(model, s);
  const double I_O = m1 * L * L / 3 + m2 * L * L + I2;
  const double phi_dd = -(m1 * L / 2 + m2 * L) * kG * std::sin(phi) / I_O;
  EXPECT_TRUE(Near(sol.bodies[0].alpha_WB_W.z(), phi_dd, 1e-11));
  EXPECT_TRUE(Near(sol.bodies[1].alpha_WB_W.z(), phi_dd, 1e-11));
  const Vec3 a2 = Vec3(0, 0, phi_dd).cross(L * e);
  EXPECT_TRUE(MatNear(sol.bodies[1].a_WBcm_W, a2, 1e-11, kG));
  EXPECT_TRUE(MatNear(sol.reactions[1].F_Jc_W, m2 * (a2 - kGravity), 1e-11, m2 * kG));
  EXPECT_TRUE(MatNear(sol.reactions[1].M_Jc_W, Vec3(0, 0, I2 * phi_dd), 1e-10, m2 * kG * L));
}

}  // namespace
}  // namespace chasles
