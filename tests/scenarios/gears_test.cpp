// One body rolling on another: a ball on a turntable (rolling on a moving body's plane) and a
// planet gear meshing with a fixed sun or ring gear on a driven carrier (pitch circles rolling
// on each other). Closed forms derived below.

#include <cmath>
#include <memory>

#include <gtest/gtest.h>

#include "chasles/analysis/instantaneous.h"
#include "chasles/dynamics/constraint_solve.h"
#include "chasles/integrate/simulate.h"
#include "chasles/model/constraints.h"
#include "chasles/model/data.h"
#include "chasles/model/forces.h"
#include "chasles/model/model.h"
#include "test_support.h"

namespace chasles {
namespace {

using test::MatNear;
using test::Near;

constexpr double kG = 9.81;

MassProperties Principal(double m, const Vec3& I) {
  return MassProperties(m, Vec3::Zero(), RotationalInertia::FromMatrix(I.asDiagonal()));
}

double KineticEnergy(const Model& model, const State& s) {
  double T = 0.0;
  for (int b = 0; b < model.num_bodies(); ++b) {
    const BodyState& bs = s.bodies[static_cast<size_t>(b)];
    const Mat3 I = model.body(b).I_BBcm_B();
    T +=
        0.5 * model.body(b).mass() * bs.v_WBcm_W.squaredNorm() + 0.5 * bs.w_WB_B.dot(I * bs.w_WB_B);
  }
  return T;
}

SimulationOptions Tight(double t_end) {
  SimulationOptions o;
  o.t_end = t_end;
  o.adaptive.rtol = 1e-12;
  o.adaptive.atol = 1e-14;
  return o;
}

// A solid ball (I = 2/5 m R²) rolling without slipping on a turntable driven at constant Ω
// about the vertical z. With ρ the ball centre's horizontal position and F the table's
// horizontal force on the ball at the contact C = centre - R k:
//   no slip       v + w × (-R k) = Ω k × ρ      (the table's velocity at C)
//   Newton-Euler  m v̇ = F,  I ẇ = (-R k) × F
// Differentiating the first, v̇ - R ẇ × k = Ω k × v, and ẇ × k = -(R/I) F, so
//   v̇ (1 + m R²/I) = Ω k × v,   v̇ = (2/7) Ω k × v:
// the centre circles at the rate ν = 2Ω/7 (a classic result), about the point c with
// p0 - c = -(k × v0)/ν; w_z is constant (no moment about the vertical at C). The driver
// supplies the moment that keeps Ω: the table receives -F at C, so M_z = (p_C × F)·k.
TEST(RollingOnABody, BallOnATurntableCirclesAtTwoSeventhsOfItsRate) {
  const double m = 1.3, R = 0.1, Omega = 2.0;
  Model model;
  const BodyIndex table = model.AddBody("table", Principal(20.0, Vec3(2.0, 2.0, 4.0)));
  const BodyIndex ball = model.AddBody("ball", Principal(m, Vec3::Constant(0.4 * m * R * R)));
  model.AddForceElement(std::make_shared<UniformGravity>("gravity", Vec3(0, 0, -kG)));
  State s = MakeRestState(model);
  const Vec3 rho0(0.3, 0.1, 0.0);
  const Vec3 w0(1.0, -0.5, 2.0);
  const Vec3 v0 = Omega * Vec3::UnitZ().cross(rho0) + R * w0.cross(Vec3::UnitZ());
  SetBodyPose(model, table, Vec3(0, 0, -0.05), Quat::Identity(), s);
  SetBodyPose(model, ball, rho0 + R * Vec3::UnitZ(), Quat::Identity(), s);
  SetBodyVelocity(model, table, Vec3::Zero(), Omega * Vec3::UnitZ(), s);
  SetBodyVelocity(model, ball, v0, w0, s);
  const Mat3 E = Mat3::Identity();
  model.AddConstraint(std::make_shared<Joint>(
      "axle", JointKind::kRevolute, kWorld, AttachmentFrame{Vec3::Zero(), E}, table,
      AttachmentFrameAtWorldPose(model, s, table, Vec3::Zero(), E)));
  const int drive = model.AddConstraint(std::make_shared<PrescribedMotion>(
      "motor", DriverKind::kRotation, kWorld, AttachmentFrame{Vec3::Zero(), E}, table,
      AttachmentFrameAtWorldPose(model, s, table, Vec3::Zero(), E),
      TimeFunction::Quadratic(0.0, Omega, 0.0)));
  // The table's top face z = 0 is 0.05 m above its centre, in its own frame.
  const int roll = model.AddConstraint(
      std::make_shared<RollingContact>("contact", RollingShape::kSphere, table, Vec3(0, 0, 0.05),
                                       Vec3::UnitZ(), ball, Vec3::Zero(), Vec3::UnitZ(), R));

  // The instant: reactions on the ball and on the table.
  const InstantaneousSolution sol = SolveInstantaneous(model, s);
  const double nu = 2.0 * Omega / 7.0;
  const Vec3 F = m * nu * Vec3::UnitZ().cross(v0) + m * kG * Vec3::UnitZ();
  const ReactionReport& c = sol.reactions[static_cast<size_t>(roll)];
  EXPECT_TRUE(MatNear(c.p_WJ, rho0, 1e-14));
  EXPECT_TRUE(MatNear(c.F_Jc_W, F, 1e-12, m * kG));
  EXPECT_TRUE(Near(c.normal_force, m * kG, 1e-12));
  EXPECT_TRUE(MatNear(c.friction_W, Vec3(F - m * kG * Vec3::UnitZ()), 1e-12, m * kG));
  EXPECT_TRUE(Near(sol.reactions[static_cast<size_t>(drive)].lambda[0],
                   rho0.cross(F).dot(Vec3::UnitZ()), 1e-12, m * kG * R));

  // The motion: a circle at rate ν about c.
  const double t_end = 3.0;
  const SimulationResult res = Simulate(model, s, Tight(t_end));
  const Vec3 p0 = rho0 + R * Vec3::UnitZ();
  const Vec3 centre = p0 + Vec3::UnitZ().cross(v0) / nu;
  const Mat3 Rot = Eigen::AngleAxisd(nu * t_end, Vec3::UnitZ()).toRotationMatrix();
  const BodyState& b = res.final_state.bodies[static_cast<size_t>(ball)];
  EXPECT_TRUE(MatNear(b.p_WBcm, Vec3(centre + Rot * (p0 - centre)), 1e-9, 1.0));
  EXPECT_TRUE(MatNear(b.v_WBcm_W, Vec3(Rot * v0), 1e-9, v0.norm()));
  EXPECT_TRUE(Near((b.q_WB * b.w_WB_B).z(), w0.z(), 1e-9, 1.0));
  EXPECT_TRUE(Near((res.final_state.bodies[0].q_WB * res.final_state.bodies[0].w_WB_B).z(), Omega,
                   1e-12, 1.0));
  Data data = MakeData(model);
  const ConstraintViolation v = CalcConstraintViolation(model, res.final_state, data);
  EXPECT_LT(v.position, 1e-12);
  EXPECT_LT(v.velocity, 1e-12);
}

// A planet gear (thin disk, pitch radius r_p) on a carrier pinned at the origin, meshing with
// a fixed sun gear (external, pitch radius r_s) or a fixed ring gear (internal, radius
// r_s + 2 r_p), the planet's centre at d = r_s + r_p. A moment M turns the carrier.
// No slip at the pitch point P = d ∓ r_p along x:
//   sun:  Ω d - ω_p r_p = 0,  ω_p = +Ω d / r_p;   ring: Ω d + ω_p r_p = 0,  ω_p = -Ω d / r_p.
// Energy (the mesh and the pins do no work): T = ½ I_eff Ω²,
//   I_eff = I_c + m_p d² + I_p (d/r_p)²,  so  α = M / I_eff,  T(t) = T0 + M θ(t).
// The mesh force on the planet at P is along y (the common tangent); about the planet's
// centre I_p ω̇_p = ((P - a) × F)_z = ∓ r_p F_y gives F_y = -I_p α d / r_p² in both cases.
TEST(GearMesh, PlanetOnAFixedSunOrRingGear) {
  const double r_s = 0.1, r_p = 0.04, d = r_s + r_p, m_p = 0.5, M = 0.3, Omega0 = 1.5;
  const double I_c = 0.1, I_p = 0.5 * m_p * r_p * r_p;
  for (GearKind kind : {GearKind::kExternal, GearKind::kInternal}) {
    SCOPED_TRACE(GearKindName(kind));
    const double sign = kind == GearKind::kExternal ? 1.0 : -1.0;
    Model model;
    const BodyIndex carrier = model.AddBody("carrier", Principal(2.0, Vec3(0.05, 0.05, I_c)));
    const BodyIndex planet =
        model.AddBody("planet", Principal(m_p, Vec3(0.25, 0.25, 0.5) * m_p * r_p * r_p));
    model.AddForceElement(
        AppliedMoment::Constant("drive", carrier, Vec3(0, 0, M), VectorFrame::kWorld));
    State s = MakeRestState(model);
    const Vec3 a(d, 0, 0);
    SetBodyPose(model, planet, a, Quat::Identity(), s);
    SetBodyVelocity(model, carrier, Vec3::Zero(), Omega0 * Vec3::UnitZ(), s);
    SetBodyVelocity(model, planet, Vec3(0, Omega0 * d, 0), sign * Omega0 * d / r_p * Vec3::UnitZ(),
                    s);
    const Mat3 E = Mat3::Identity();
    model.AddConstraint(std::make_shared<Joint>(
        "main", JointKind::kRevolute, kWorld, AttachmentFrame{Vec3::Zero(), E}, carrier,
        AttachmentFrameAtWorldPose(model, s, carrier, Vec3::Zero(), E)));
    model.AddConstraint(std::make_shared<Joint>(
        "pin", JointKind::kRevolute, carrier, AttachmentFrameAtWorldPose(model, s, carrier, a, E),
        planet, AttachmentFrameAtWorldPose(model, s, planet, a, E)));
    const double r_fixed = kind == GearKind::kExternal ? r_s : r_s + 2 * r_p;
    const int mesh = model.AddConstraint(std::make_shared<GearMesh>(
        "mesh", kind, kWorld, PitchCircle{Vec3::Zero(), Vec3::UnitZ(), r_fixed}, planet,
        PitchCircle{Vec3::Zero(), Vec3::UnitZ(), r_p}, false));

    const double I_eff = I_c + m_p * d * d + I_p * (d / r_p) * (d / r_p);
    const double alpha = M / I_eff;
    const InstantaneousSolution sol = SolveInstantaneous(model, s);
    EXPECT_EQ(sol.rank, sol.num_rows);
    EXPECT_TRUE(MatNear(sol.bodies[0].alpha_WB_W, Vec3(0, 0, alpha), 1e-12, alpha));
    EXPECT_TRUE(
        MatNear(sol.bodies[1].alpha_WB_W, Vec3(0, 0, sign * alpha * d / r_p), 1e-12, alpha));
    const ReactionReport& r = sol.reactions[static_cast<size_t>(mesh)];
    EXPECT_TRUE(MatNear(r.p_WJ, Vec3(d - sign * r_p, 0, 0), 1e-14, 1.0));
    const double F_y = -I_p * alpha * d / (r_p * r_p);
    EXPECT_TRUE(MatNear(r.F_Jc_W, Vec3(0, F_y, 0), 1e-12, std::abs(F_y)));
    EXPECT_TRUE(Near(r.power, 0.0, 1e-12, std::abs(F_y) * Omega0 * d));

    // The motion: Ω(t) = Ω0 + α t, the planet's rate follows it, T = T0 + M θ.
    const double t_end = 2.0;
    const SimulationResult res = Simulate(model, s, Tight(t_end));
    const State& f = res.final_state;
    const double Omega = Omega0 + alpha * t_end;
    const double theta = Omega0 * t_end + 0.5 * alpha * t_end * t_end;
    EXPECT_TRUE(Near((f.bodies[0].q_WB * f.bodies[0].w_WB_B).z(), Omega, 1e-10));
    EXPECT_TRUE(Near((f.bodies[1].q_WB * f.bodies[1].w_WB_B).z(), sign * Omega * d / r_p, 1e-10));
    const double T0 = 0.5 * I_eff * Omega0 * Omega0;
    EXPECT_TRUE(Near(KineticEnergy(model, s), T0, 1e-14));
    EXPECT_TRUE(Near(KineticEnergy(model, f), T0 + M * theta, 1e-10));
    EXPECT_TRUE(
        MatNear(f.bodies[1].p_WBcm, Vec3(d * std::cos(theta), d * std::sin(theta), 0), 1e-10, d));
  }
}

}  // namespace
}  // namespace chasles
