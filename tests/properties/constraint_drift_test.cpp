// Long runs with constraints: the projection after each step keeps the constraint violation
// at round-off (no Baumgarte terms), ideal joints and rolling do no work (the power of the
// constraint forces is zero), and so the energy ledger closes with the force elements alone.

#include <cmath>
#include <cstdio>
#include <memory>
#include <numbers>

#include <gtest/gtest.h>

#include "chasles/analysis/ledger.h"
#include "chasles/dynamics/constraint_solve.h"
#include "chasles/dynamics/newton_euler.h"
#include "chasles/error.h"
#include "chasles/integrate/rk4.h"
#include "chasles/integrate/simulate.h"
#include "chasles/math/rotation.h"
#include "chasles/model/constraints.h"
#include "chasles/model/forces.h"
#include "test_support.h"

namespace chasles {
namespace {

constexpr double kG = 9.81;
constexpr double kViolation = 1e-9;  // the requirement for long runs [m, m/s]

MassProperties Diagonal(double m, const Vec3& I) {
  return MassProperties(m, Vec3::Zero(), RotationalInertia::FromMatrix(I.asDiagonal()));
}

struct RunReport {
  double max_position = 0.0, max_velocity = 0.0, max_power = 0.0, energy_drift = 0.0;
  double ledger_residual = 0.0;
};

// RK4 with projection for `steps` steps of `h`; samples violation and constraint power every
// 100 steps; energy drift relative to the energy scale from the ledger.
RunReport RunRk4(const Model& model, State s, double h, long steps) {
  Data data = MakeData(model);
  ProjectOntoConstraints(model, s, data);
  const State s0 = s;
  Rk4Integrator rk4(model);
  RunReport rep;
  const double E0 = CalcLedgerSample(model, s0, s0).energy_scale;
  for (long i = 1; i <= steps; ++i) {
    rk4.Step(s, h);
    if (i % 100 == 0 || i == steps) {
      const ConstraintViolation v = CalcConstraintViolation(model, s, data);
      rep.max_position = std::max(rep.max_position, v.position);
      rep.max_velocity = std::max(rep.max_velocity, v.velocity);
      CalcAccelerations(model, s, data);
      double p = 0.0;
      for (const ConstraintOutput& c : data.constraints) p += std::abs(c.power);
      rep.max_power = std::max(rep.max_power, p);
      const LedgerSample L = CalcLedgerSample(model, s, s0);
      rep.energy_drift = std::max(rep.energy_drift, std::abs(L.energy_residual) / E0);
    }
  }
  rep.ledger_residual = CalcLedgerSample(model, s, s0).energy_residual / E0;
  return rep;
}

// Two uniform rods (masses m1, m2, lengths L1, L2) hinged to the world and to each other
// about z, released from 1 and 2 rad off the downward vertical: a chaotic motion, 10 s.
TEST(ConstraintDrift, DoublePendulumStaysOnTheConstraintsFor1e5Steps) {
  const double m1 = 1.0, m2 = 0.7, L1 = 1.0, L2 = 0.8;
  Model model;
  model.AddBody("upper", Diagonal(m1, Vec3(0.01, m1 * L1 * L1 / 12, m1 * L1 * L1 / 12)));
  model.AddBody("lower", Diagonal(m2, Vec3(0.01, m2 * L2 * L2 / 12, m2 * L2 * L2 / 12)));
  model.AddForceElement(std::make_shared<UniformGravity>("gravity", Vec3(0, -kG, 0)));
  State s = MakeRestState(model);
  const double a1 = 1.0, a2 = 2.0;  // from the downward vertical
  const Vec3 e1(std::sin(a1), -std::cos(a1), 0), e2(std::sin(a2), -std::cos(a2), 0);
  // Body x along each rod, from its upper end to its lower end.
  SetBodyPose(model, 0, 0.5 * L1 * e1,
              Quat(RotationFromAxisAngle(Vec3::UnitZ(), a1 - std::numbers::pi / 2)), s);
  SetBodyPose(model, 1, L1 * e1 + 0.5 * L2 * e2,
              Quat(RotationFromAxisAngle(Vec3::UnitZ(), a2 - std::numbers::pi / 2)), s);
  model.AddConstraint(std::make_shared<Joint>("shoulder", JointKind::kRevolute, kWorld,
                                              AttachmentFrame{Vec3::Zero()}, 0,
                                              AttachmentFrame{Vec3(-L1 / 2, 0, 0)}));
  model.AddConstraint(std::make_shared<Joint>("elbow", JointKind::kRevolute, 0,
                                              AttachmentFrame{Vec3(L1 / 2, 0, 0)}, 1,
                                              AttachmentFrame{Vec3(-L2 / 2, 0, 0)}));
  const long steps = test::Repeats(100000);
  const RunReport r = RunRk4(model, s, 1e-4, steps);
  std::printf(
      "double pendulum, RK4 h = 1e-4 s, %ld steps: max |g| %.3g m, max |J u| %.3g m/s, "
      "max |constraint power| %.3g W, energy drift %.3g (relative)\n",
      steps, r.max_position, r.max_velocity, r.max_power, r.energy_drift);
  EXPECT_LT(r.max_position, kViolation);
  EXPECT_LT(r.max_velocity, kViolation);
  EXPECT_LT(r.max_power, 1e-9 * m1 * kG * std::sqrt(kG * L1));
  EXPECT_LT(r.energy_drift, 1e-9);
  EXPECT_LT(std::abs(r.ledger_residual), 1e-9);  // the ledger closes without the joints
}

// A thin disk (R = 0.3 m) rolling on its rim on the floor z = 0, tilted, spinning and
// turning: the nonholonomic rows and the tilted-rim geometry over 1e5 steps.
TEST(ConstraintDrift, RollingDiskStaysOnTheConstraintsFor1e5Steps) {
  const double m = 1.0, R = 0.3;
  Model model;
  model.AddBody("coin", Diagonal(m, Vec3(m * R * R / 4, m * R * R / 4, m * R * R / 2)));
  model.AddForceElement(std::make_shared<UniformGravity>("gravity", Vec3(0, 0, -kG)));
  model.AddConstraint(std::make_shared<RollingContact>("floor", RollingShape::kDisk, 0,
                                                       Vec3::Zero(), Vec3::UnitZ(), R, Vec3::Zero(),
                                                       Vec3::UnitZ()));
  State s = MakeRestState(model);
  const Mat3 R_WB = RotationFromAxisAngle(Vec3::UnitY(), std::numbers::pi / 2 + 0.3);
  const Vec3 e = R_WB.col(2), n = Vec3::UnitZ();
  const Vec3 u = n - n.dot(e) * e;
  const Vec3 mdir = u.normalized();  // centre minus contact point, over R
  SetBodyPose(model, 0, Vec3(0, 0, R * u.norm()), Quat(R_WB), s);
  const Vec3 w = 12.0 * e + 1.5 * n;
  SetBodyVelocity(model, 0, -w.cross(-R * mdir), w, s);  // contact point at rest
  const long steps = test::Repeats(100000);
  const RunReport r = RunRk4(model, s, 1e-4, steps);
  std::printf(
      "rolling disk, RK4 h = 1e-4 s, %ld steps: max |g| %.3g m, max |J u| %.3g m/s, "
      "max |constraint power| %.3g W, energy drift %.3g (relative)\n",
      steps, r.max_position, r.max_velocity, r.max_power, r.energy_drift);
  EXPECT_LT(r.max_position, kViolation);
  EXPECT_LT(r.max_velocity, kViolation);
  EXPECT_LT(r.max_power, 1e-9 * m * kG * R * 12.0);
  EXPECT_LT(r.energy_drift, 1e-9);
  EXPECT_LT(std::abs(r.ledger_residual), 1e-9);
}

TEST(ConstraintDrift, EnergyMomentumIntegratorRefusesConstraints) {
  Model model;
  model.AddBody("b", Diagonal(1.0, Vec3(1, 1, 1)));
  model.AddConstraint(std::make_shared<Joint>("pin", JointKind::kSpherical, kWorld,
                                              AttachmentFrame{Vec3::Zero()}, 0,
                                              AttachmentFrame{Vec3::Zero()}));
  SimulationOptions o;
  o.integrator = IntegratorKind::kEnergyMomentum;
  o.t_end = 1.0;
  EXPECT_THROW(Simulate(model, MakeRestState(model), o), InputError);
}

// A driven system: a cart pushed with constant acceleration a carries a pendulum. The driver
// does work, the joints none; the ledger closes with the driver's work counted:
// ΔT + ΔV = W_driver. Cross-check: W_driver = ∫ F v dt must equal ΔT + ΔV computed from
// the states alone.
TEST(ConstraintLedger, DriverWorkClosesTheEnergyBalance) {
  const double M = 4.0, m = 1.0, L = 0.7, a = 2.5;
  Model model;
  model.AddBody("cart", Diagonal(M, Vec3(0.3, 0.3, 0.3)));
  model.AddBody("bob", Diagonal(m, Vec3(0.01, m * L * L / 12, m * L * L / 12)));
  model.AddForceElement(std::make_shared<UniformGravity>("gravity", Vec3(0, -kG, 0)));
  State s = MakeRestState(model);
  SetBodyPose(model, 1, Vec3(0, -L / 2, 0),
              Quat(RotationFromAxisAngle(Vec3::UnitZ(), -std::numbers::pi / 2)), s);
  const Mat3 Rx = FrameWithZAxis(Vec3::UnitX());
  model.AddConstraint(std::make_shared<Joint>("rail", JointKind::kPrismatic, kWorld,
                                              AttachmentFrame{Vec3::Zero(), Rx}, 0,
                                              AttachmentFrame{Vec3::Zero(), Rx}));
  model.AddConstraint(std::make_shared<PrescribedMotion>(
      "drive", DriverKind::kTranslation, kWorld, AttachmentFrame{Vec3::Zero(), Rx}, 0,
      AttachmentFrame{Vec3::Zero()}, TimeFunction::Quadratic(0, 0, a)));
  model.AddConstraint(std::make_shared<Joint>("pin", JointKind::kRevolute, 0,
                                              AttachmentFrame{Vec3::Zero()}, 1,
                                              AttachmentFrame{Vec3(-L / 2, 0, 0)}));
  SimulationOptions o;
  o.t_end = 2.0;
  o.adaptive.rtol = 1e-11;
  o.adaptive.atol = 1e-13;
  const SimulationResult r = Simulate(model, s, o);
  const LedgerSample L0 = CalcLedgerSample(model, r.final_state, s);
  const double scale = L0.energy_scale;
  std::printf(
      "driven pendulum, DP5 2 s: driver work %.9g J, joints %.3g J, %.3g J, energy "
      "residual %.3g (relative)\n",
      L0.constraints[1].work, L0.constraints[0].work, L0.constraints[2].work,
      L0.energy_residual / scale);
  EXPECT_GT(L0.constraints[1].work, 0.1 * scale);  // the driver really works
  EXPECT_LT(std::abs(L0.constraints[0].work), 1e-9 * scale);
  EXPECT_LT(std::abs(L0.constraints[2].work), 1e-9 * scale);
  EXPECT_LT(std::abs(L0.energy_residual), 1e-9 * scale);
}

}  // namespace
}  // namespace chasles
