// Strings over pulleys and drums (model/string_constraint.h): the row against finite
// differences of the length function at seeded random states, and the tension and motion of
// the Atwood machine, the yo-yo and the spool against closed forms derived here.

#include "chasles/model/string_constraint.h"

#include <cmath>
#include <memory>
#include <numbers>
#include <random>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "chasles/analysis/certificate.h"
#include "chasles/analysis/instantaneous.h"
#include "chasles/dynamics/constraint_solve.h"
#include "chasles/dynamics/newton_euler.h"
#include "chasles/error.h"
#include "chasles/integrate/simulate.h"
#include "chasles/math/quaternion.h"
#include "chasles/math/rotation.h"
#include "chasles/model/constraints.h"
#include "chasles/model/forces.h"
#include "test_support.h"

namespace chasles {
namespace {

using test::Near;
using ::testing::HasSubstr;

MassProperties Box(double m, const Vec3& I) {
  return MassProperties(m, Vec3::Zero(), RotationalInertia::FromMatrix(I.asDiagonal()));
}

// Two bodies with general inertia and a centre of mass off the body origin.
Model TwoBodies() {
  Model model;
  model.AddBody(
      "a", MassProperties(
               1.5, Vec3(0.1, -0.2, 0.05),
               RotationalInertia::FromMatrix(
                   (Mat3() << 0.3, 0.02, -0.01, 0.02, 0.4, 0.03, -0.01, 0.03, 0.5).finished())));
  model.AddBody("b", Box(2.5, Vec3(0.2, 0.25, 0.3)));
  return model;
}

struct Evaluated {
  ConstraintEval e;
  double length = 0.0;  // free length L
  double Ju = 0.0;
  // Per end, the angle ψ of its leaving point on its drum about n from the body-fixed
  // direction R_WB x_B (0 for a point end).
  double psi[2] = {0.0, 0.0};
};

// The row on body b: the parent's, the child's, an extra body's (a pulley it carries), or 0.
Eigen::Matrix<double, 1, 6> RowOn(const StringConstraint& s, const ConstraintEval& e, int b) {
  if (b == s.parent()) return e.J_parent.row(0);
  if (b == s.child()) return e.J_child.row(0);
  for (int k = 0; k < e.num_extra; ++k) {
    if (e.extra_body[static_cast<size_t>(k)] == b) return e.J_extra[static_cast<size_t>(k)].row(0);
  }
  return Eigen::Matrix<double, 1, 6>::Zero();
}

Evaluated Eval(const Model& model, const StringConstraint& s, const State& state) {
  Data data = MakeData(model);
  CalcKinematics(model, state, data);
  Evaluated r;
  s.Evaluate(model, state, data, r.e);
  const StringPath path = s.CalcPath(model, state, data);
  r.length = path.length;
  for (int side = 0; side < 2; ++side) {
    const StringEnd& end = side == 0 ? s.end_a() : s.end_b();
    if (end.radius == 0.0) continue;
    const auto i = static_cast<size_t>(end.body);
    const Vec3 c = state.bodies[i].p_WBcm +
                   data.R_WB[i] * model.body(end.body).PointFromCenterOfMass(end.p_BoP_B);
    const Vec3 rho = (side == 0 ? path.points.front() : path.points.back()) - c;
    const Vec3 u0 = data.R_WB[i] * Vec3::UnitX();
    r.psi[side] = std::atan2(Vec3::UnitZ().dot(u0.cross(rho)), u0.dot(rho));
  }
  for (int b = 0; b < model.num_bodies(); ++b) {
    const BodyState& bs = state.bodies[static_cast<size_t>(b)];
    Eigen::Matrix<double, 6, 1> u;
    u << bs.v_WBcm_W, bs.q_WB * bs.w_WB_B;
    r.Ju += RowOn(s, r.e, b).dot(u);
  }
  return r;
}

// Displaces body b by x = [δp; δθ] (δθ a rotation about W's axes, q ← exp(δθ) q).
State Displace(const State& s, int b, const Eigen::Matrix<double, 6, 1>& x) {
  State out = s;
  BodyState& bs = out.bodies[static_cast<size_t>(b)];
  bs.p_WBcm += x.head<3>();
  bs.q_WB = (QuatExp(x.tail<3>()) * bs.q_WB).normalized();
  return out;
}

// Moves every body along its current velocity for time eps (u held fixed in W).
State Drift(const State& s, double eps) {
  State out = s;
  for (BodyState& b : out.bodies) {
    const Vec3 w_W = b.q_WB * b.w_WB_B;
    b.p_WBcm += eps * b.v_WBcm_W;
    b.q_WB = (QuatExp(eps * w_W) * b.q_WB).normalized();
    b.w_WB_B = b.q_WB.conjugate() * w_W;
  }
  out.t += eps;
  return out;
}

// The string's material length is the free length L plus the length W wound on the drums,
// so the slack is g = const - L - W. On a drum the wound part runs from the leaving point T
// (at angle ψ on the drum, measured in the body) onwards in the string's sense: at end B,
// where the string goes on in sense s_B, W_B = s_B r_B (ψ0 - ψ); at end A, where it comes off
// in sense s_A, W_A = s_A r_A (ψ - ψ0). ψ changes both when the body turns and when moving it
// shifts the tangent point round the drum. So J (per body coordinate j) = -∂(L + W)/∂x_j,
// checked by central differences (error O(ε²) ~ 1e-10 of the terms), and c = -J̇u by central
// differences along a drift with u held fixed. The tests run in the plane z = 0 (n = z) where
// there are circles.
void CheckRow(const Model& model, const StringConstraint& s, const State& state) {
  const Evaluated e0 = Eval(model, s, state);
  const double eps = 1e-5;
  // Every body of the model: the ends' bodies, the bodies carrying pulleys, and the others
  // (whose row must be zero).
  for (int body = 0; body < model.num_bodies(); ++body) {
    const Eigen::Matrix<double, 1, 6> J = RowOn(s, e0.e, body);
    for (int j = 0; j < 6; ++j) {
      Eigen::Matrix<double, 6, 1> x = Eigen::Matrix<double, 6, 1>::Zero();
      x[j] = eps;
      const Evaluated p = Eval(model, s, Displace(state, body, x));
      const Evaluated m = Eval(model, s, Displace(state, body, -x));
      double dW = 0.0;
      for (int k = 0; k < 2; ++k) {
        const StringEnd& ek = k == 0 ? s.end_a() : s.end_b();
        const double dpsi = std::remainder(p.psi[k] - m.psi[k], 2 * std::numbers::pi);
        dW += (k == 0 ? 1.0 : -1.0) * ek.sense * ek.radius * dpsi;
      }
      const double expected = -(p.length - m.length + dW) / (2 * eps);
      EXPECT_TRUE(Near(J(0, j), expected, 1e-8, 1.0)) << s.name() << " body " << body << " j " << j;
    }
  }
  const double h = 1e-5;
  const double Jdot_u =
      (Eval(model, s, Drift(state, h)).Ju - Eval(model, s, Drift(state, -h)).Ju) / (2 * h);
  EXPECT_TRUE(Near(e0.e.acceleration_rhs[0], -Jdot_u, 1e-7, 1.0)) << s.name();
  if (!s.has_drum()) {
    EXPECT_TRUE(e0.e.holonomic[0]);
    EXPECT_TRUE(Near(e0.e.position_error[0], s.length() - e0.length, test::kExact, 1.0));
  } else {
    EXPECT_FALSE(e0.e.holonomic[0]);
  }
}

// A general 3D state: random poses and velocities.
State RandomState(const Model& model, std::mt19937& rng, bool planar) {
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  State s = MakeRestState(model);
  for (int b = 0; b < model.num_bodies(); ++b) {
    BodyState& bs = s.bodies[static_cast<size_t>(b)];
    if (planar) {
      // In the plane z = 0 turning about z: the regime of strings with circles.
      // Body a's centre of mass is 0.05 above Bo along B's z: its points with z = 0 in B lie
      // in the plane z = 0.
      bs.p_WBcm = Vec3(U(rng), U(rng), b == 0 ? 0.05 : 0.0);
      bs.q_WB = Quat(RotationFromAxisAngle(Vec3::UnitZ(), 3 * U(rng)));
      bs.v_WBcm_W = Vec3(U(rng), U(rng), 0.0);
      bs.w_WB_B = bs.q_WB.conjugate() * Vec3(0, 0, 2 * U(rng));
    } else {
      bs.p_WBcm = Vec3(U(rng), U(rng), U(rng));
      bs.q_WB = Quat(RotationFromEuler("ZYX", Vec3(3 * U(rng), U(rng), 3 * U(rng))));
      bs.v_WBcm_W = Vec3(U(rng), U(rng), U(rng));
      bs.w_WB_B = Vec3(2 * U(rng), 2 * U(rng), 2 * U(rng));
    }
  }
  s.bodies[1].p_WBcm += Vec3(3.0, 0.0, 0.0);  // keep the ends apart
  return s;
}

TEST(String, RowMatchesFiniteDifferencesOfTheLengthAtRandomStates) {
  const Model model = TwoBodies();
  std::mt19937 rng(20261124);
  const Vec3 n = Vec3::UnitZ();
  for (int trial = 0; trial < 5; ++trial) {
    // Point to point in 3D, ends off the centres of mass.
    const State s3 = RandomState(model, rng, false);
    const StringConstraint direct("direct", StringEnd{0, Vec3(0.2, 0.1, -0.3), 0.0, 1}, {},
                                  StringEnd{1, Vec3(-0.1, 0.3, 0.2), 0.0, 1}, n, 3.0);
    CheckRow(model, direct, s3);
    // Planar: over two pulleys (one each way round) between points, and between drums (one
    // off the centre of mass).
    const State s2 = RandomState(model, rng, true);
    const std::vector<StringPulley> pulleys = {{Vec3(0.8, 2.5, 0.0), 0.3, -1},
                                               {Vec3(2.4, 2.2, 0.0), 0.2, -1}};
    const StringConstraint over("over", StringEnd{0, Vec3(0.2, 0.1, 0.0), 0.0, 1}, pulleys,
                                StringEnd{1, Vec3(-0.1, 0.3, 0.0), 0.0, 1}, n, 6.0);
    CheckRow(model, over, s2);
    for (const int sa : {1, -1}) {
      for (const int sb : {1, -1}) {
        const StringConstraint drums("drums", StringEnd{0, Vec3(0.1, -0.2, 0.0), 0.25, sa}, pulleys,
                                     StringEnd{1, Vec3(0.05, 0.1, 0.0), 0.15, sb}, n, 6.0);
        CheckRow(model, drums, s2);
        const StringConstraint bare("bare drums", StringEnd{0, Vec3(0.1, -0.2, 0.0), 0.25, sa}, {},
                                    StringEnd{1, Vec3(0.05, 0.1, 0.0), 0.15, sb}, n, 6.0);
        CheckRow(model, bare, s2);
      }
    }
  }
}

// Pulleys carried by bodies: the row on every body (the ends' bodies, the bodies carrying
// pulleys, and the untouched ones, whose row must be zero) against finite differences of the
// length, and J̇u along a drift. Three bodies in the plane z = 0, turned a little about z and
// moving at random: a movable block (body c) below the two ends carries a pulley the string
// loops under, then the string goes over a fixed pulley and down to a drum on body b. In the
// second string end A is tied to the block itself, which also carries a pulley (the row on
// the parent body gets both terms).
TEST(String, PulleysOnBodiesMatchFiniteDifferencesOfTheLength) {
  Model model = TwoBodies();
  model.AddBody("c", Box(0.8, Vec3(0.05, 0.06, 0.07)));
  std::mt19937 rng(20261125);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  const Vec3 n = Vec3::UnitZ();
  for (int trial = 0; trial < 4; ++trial) {
    State s = MakeRestState(model);
    const Vec3 base[3] = {Vec3(0, 0, 0.05), Vec3(3, 0, 0), Vec3(1.5, -2, 0)};
    for (int b = 0; b < 3; ++b) {
      BodyState& bs = s.bodies[static_cast<size_t>(b)];
      bs.p_WBcm = base[b] + 0.3 * Vec3(U(rng), U(rng), 0.0);
      bs.q_WB = Quat(RotationFromAxisAngle(Vec3::UnitZ(), 0.3 * U(rng)));
      bs.v_WBcm_W = Vec3(U(rng), U(rng), 0.0);
      bs.w_WB_B = bs.q_WB.conjugate() * Vec3(0, 0, 2 * U(rng));
    }
    // Down to the block's pulley and round its underside (counterclockwise about z), up over
    // the fixed pulley (clockwise) and down to b's drum.
    const StringPulley block{Vec3(0.1, -0.05, 0.0), 0.25, 1, 2};
    const StringPulley fixed{Vec3(3.2, 2.0, 0.0), 0.2, -1, kWorld};
    for (const int sb : {1, -1}) {
      const StringConstraint movable("movable", StringEnd{0, Vec3(0.2, 0.1, 0.0), 0.0, 1},
                                     {block, fixed}, StringEnd{1, Vec3(0.05, 0.1, 0.0), 0.15, sb},
                                     n, 8.0);
      CheckRow(model, movable, s);
      EXPECT_EQ(Eval(model, movable, s).e.num_extra, 1);
    }
    // From a hook on the block up over a fixed pulley, down round the block's pulley, up over
    // the second fixed pulley to b.
    const StringConstraint tackle(
        "tackle", StringEnd{2, Vec3(-0.4, 0.3, 0.0), 0.0, 1},
        {StringPulley{Vec3(1.0, 1.5, 0.0), 0.2, -1, kWorld}, block, fixed},
        StringEnd{1, Vec3(0.05, 0.1, 0.0), 0.0, 1}, n, 12.0);
    CheckRow(model, tackle, s);
    EXPECT_EQ(Eval(model, tackle, s).e.num_extra, 0);
  }
}

// A single movable pulley (massless, radius r2) carrying m2: the string is tied to the
// ceiling, runs down round the pulley's underside, up over a fixed pulley (radius r1) and down
// to m1; every strand vertical. With y1, y2 the heights, the length 2 (y_f - y2) + (y_f - y1)
// + arcs is constant, so a1 = -2 a2; the pulley is pulled up by the two strands 2T:
//   m1 a1 = T - m1 g,  m2 a2 = 2 T - m2 g  ⇒  a2 = (2 m1 - m2) g / (4 m1 + m2),
//   T = 3 m1 m2 g / (4 m1 + m2).
TEST(String, MovablePulleyHalvesTheHangingMassesMotion) {
  const double m1 = 1.5, m2 = 2.0, r1 = 0.1, r2 = 0.15, g = 9.81;
  Model model;
  model.AddBody("m1", Box(m1, Vec3(0.01, 0.01, 0.01)));
  model.AddBody("m2", Box(m2, Vec3(0.02, 0.02, 0.02)));
  model.AddForceElement(std::make_shared<UniformGravity>("g", Vec3(0, -g, 0)));
  State s = MakeRestState(model);
  const double xf = r2 + r1, yf = 0.0;  // the fixed pulley's centre
  s.bodies[0].p_WBcm = Vec3(r2 + 2 * r1, -1.0, 0);
  s.bodies[1].p_WBcm = Vec3(0, -1.5, 0);
  const double L = (-0.2 - (-1.5)) + std::numbers::pi * r2 + (yf - (-1.5)) + std::numbers::pi * r1 +
                   (yf - (-1.0));
  model.AddConstraint(std::make_shared<StringConstraint>(
      "rope", StringEnd{kWorld, Vec3(-r2, -0.2, 0), 0.0, 1},
      std::vector<StringPulley>{{Vec3::Zero(), r2, 1, 1}, {Vec3(xf, yf, 0), r1, -1, kWorld}},
      StringEnd{0, Vec3::Zero(), 0.0, 1}, Vec3::UnitZ(), L));
  const double a2 = (2 * m1 - m2) * g / (4 * m1 + m2);
  const double T = 3 * m1 * m2 * g / (4 * m1 + m2);
  Data data = MakeData(model);
  EXPECT_LT(CalcConstraintViolation(model, s, data).position, 1e-12);
  const InstantaneousSolution sol = SolveInstantaneous(model, s);
  EXPECT_TRUE(Near(sol.bodies[1].a_WBcm_W.y(), a2, 1e-12));
  EXPECT_TRUE(Near(sol.bodies[0].a_WBcm_W.y(), -2 * a2, 1e-12));
  EXPECT_TRUE(Near(sol.reactions[0].lambda[0], T, 1e-12));
  // The pulley's body feels T (e_out - e_in) = 2 T up: its free-body balance holds.
  EXPECT_TRUE(Near(m2 * sol.bodies[1].a_WBcm_W.y(), 2 * T - m2 * g, 1e-12, m2 * g));
  CertificateBuilder builder;
  builder.CheckState(model, s, CheckPhase::kSolve);
  const Certificate c = builder.Finish();
  for (const CheckResult& r : c.checks) EXPECT_TRUE(r.passed()) << r.name << " " << r.worst;
  SimulationOptions o;
  o.t_end = 0.4;
  o.adaptive.rtol = 1e-12;
  const SimulationResult res = Simulate(model, s, o);
  const double rise = 0.5 * a2 * o.t_end * o.t_end;
  EXPECT_TRUE(Near(res.final_state.bodies[1].p_WBcm.y(), -1.5 + rise, 1e-9));
  EXPECT_TRUE(Near(res.final_state.bodies[0].p_WBcm.y(), -1.0 - 2 * rise, 1e-9));
  EXPECT_LT(CalcConstraintViolation(model, res.final_state, data).position, 1e-12);
}

// The free length of a known path: a string from (-r, -a) up to a pulley of radius r at the
// origin, over its top (half a turn, clockwise about z) and down to (r, -b): L = a + π r + b.
TEST(String, LengthOverAPulleyIsTheSegmentsPlusTheArc) {
  Model model;
  model.AddBody("m1", Box(1.0, Vec3(0.1, 0.1, 0.1)));
  model.AddBody("m2", Box(1.0, Vec3(0.1, 0.1, 0.1)));
  const double r = 0.2, a = 1.1, b = 0.7;
  State s = MakeRestState(model);
  s.bodies[0].p_WBcm = Vec3(-r, -a, 0);
  s.bodies[1].p_WBcm = Vec3(r, -b, 0);
  const StringConstraint str("rope", StringEnd{0, Vec3::Zero(), 0.0, 1},
                             {StringPulley{Vec3::Zero(), r, -1}},
                             StringEnd{1, Vec3::Zero(), 0.0, 1}, Vec3::UnitZ(), 1.0);
  Data data = MakeData(model);
  CalcKinematics(model, s, data);
  const StringPath p = str.CalcPath(model, s, data);
  EXPECT_TRUE(Near(p.length, a + std::numbers::pi * r + b, 1e-14));
  EXPECT_TRUE(test::MatNear(p.e_A, Vec3(0, 1, 0), 1e-14, 1.0));
  EXPECT_TRUE(test::MatNear(p.e_B, Vec3(0, 1, 0), 1e-14, 1.0));
}

// Atwood machine over a pulley of radius r and moment of inertia I on a fixed axle, gripping
// the string without slip: modelled as two strings wound on the pulley (one per side, each
// with its own tension). With m1 going down at a and the pulley turning at α = a / r:
//   m1 a = m1 g - T1,  m2 a = T2 - m2 g,  I a / r = (T1 - T2) r
//   ⇒ a = (m1 - m2) g / (m1 + m2 + I/r²),  T1 = m1 (g - a),  T2 = m2 (g + a).
TEST(String, AtwoodMachineWithAMassivePulley) {
  const double m1 = 3.0, m2 = 1.25, M = 2.0, r = 0.15, g = 9.81;
  const double I = 0.5 * M * r * r;
  Model model;
  const int p = model.AddBody("pulley", Box(M, Vec3(0.25 * M * r * r, 0.25 * M * r * r, I)));
  const int b1 = model.AddBody("m1", Box(m1, Vec3(0.01, 0.01, 0.01)));
  const int b2 = model.AddBody("m2", Box(m2, Vec3(0.01, 0.01, 0.01)));
  model.AddForceElement(std::make_shared<UniformGravity>("g", Vec3(0, -g, 0)));
  State s = MakeRestState(model);
  s.bodies[1].p_WBcm = Vec3(-r, -1.0, 0);
  s.bodies[2].p_WBcm = Vec3(r, -0.6, 0);
  const Mat3 R = Mat3::Identity();
  model.AddConstraint(std::make_shared<Joint>("axle", JointKind::kRevolute, kWorld,
                                              AttachmentFrame{Vec3::Zero(), R}, p,
                                              AttachmentFrame{Vec3::Zero(), R}));
  // Each string runs from its mass up to the rim: on the left it arrives going up (+y) at
  // (-r, 0), with the centre at T + s r z × y = T - s r x: s = -1; on the right s = +1.
  const Vec3 n = Vec3::UnitZ();
  model.AddConstraint(std::make_shared<StringConstraint>(
      "left", StringEnd{b1, Vec3::Zero(), 0.0, 1}, std::vector<StringPulley>{},
      StringEnd{p, Vec3::Zero(), r, -1}, n, 1.0));
  model.AddConstraint(std::make_shared<StringConstraint>(
      "right", StringEnd{b2, Vec3::Zero(), 0.0, 1}, std::vector<StringPulley>{},
      StringEnd{p, Vec3::Zero(), r, 1}, n, 0.6));
  const double a = (m1 - m2) * g / (m1 + m2 + I / (r * r));
  const InstantaneousSolution sol = SolveInstantaneous(model, s);
  EXPECT_TRUE(Near(sol.bodies[1].a_WBcm_W.y(), -a, 1e-12));
  EXPECT_TRUE(Near(sol.bodies[2].a_WBcm_W.y(), a, 1e-12));
  // m1's side of the rim (-r, 0) moves down: ω_z ẑ × (-r x̂) = -r ω_z ŷ, counterclockwise.
  EXPECT_TRUE(Near(sol.bodies[0].alpha_WB_W.z(), a / r, 1e-12));
  EXPECT_EQ(sol.reactions[1].kind, "string");
  EXPECT_TRUE(Near(sol.reactions[1].lambda[0], m1 * (g - a), 1e-12));
  EXPECT_TRUE(Near(sol.reactions[2].lambda[0], m2 * (g + a), 1e-12));
  // The reaction on the child (the pulley) is the tension along the string, down at its rim.
  EXPECT_TRUE(test::MatNear(sol.reactions[1].F_Jc_W, Vec3(0, -m1 * (g - a), 0), 1e-12, m1 * g));
  // Run it: from rest, m1 falls a t²/2 (the string rows are velocity-level: a drum).
  SimulationOptions o;
  o.t_end = 0.5;
  o.adaptive.rtol = 1e-12;
  const SimulationResult res = Simulate(model, s, o);
  const double drop = 0.5 * a * o.t_end * o.t_end;
  EXPECT_TRUE(Near(res.final_state.bodies[1].p_WBcm.y(), -1.0 - drop, 1e-9));
  EXPECT_TRUE(Near(res.final_state.bodies[2].p_WBcm.y(), -0.6 + drop, 1e-9));
}

// Atwood machine over a massless frictionless pulley fixed in the world: one string, one
// tension, a = (m1 - m2) g / (m1 + m2), T = 2 m1 m2 g / (m1 + m2); the row is holonomic.
TEST(String, AtwoodMachineOverAFixedPulleyIsOneHolonomicString) {
  const double m1 = 2.0, m2 = 0.5, r = 0.1, g = 9.81;
  Model model;
  model.AddBody("m1", Box(m1, Vec3(0.01, 0.01, 0.01)));
  model.AddBody("m2", Box(m2, Vec3(0.01, 0.01, 0.01)));
  model.AddForceElement(std::make_shared<UniformGravity>("g", Vec3(0, -g, 0)));
  State s = MakeRestState(model);
  s.bodies[0].p_WBcm = Vec3(-r, -1.0, 0);
  s.bodies[1].p_WBcm = Vec3(r, -0.5, 0);
  const double L = 1.0 + std::numbers::pi * r + 0.5;
  model.AddConstraint(std::make_shared<StringConstraint>(
      "rope", StringEnd{0, Vec3::Zero(), 0.0, 1}, std::vector<StringPulley>{{Vec3::Zero(), r, -1}},
      StringEnd{1, Vec3::Zero(), 0.0, 1}, Vec3::UnitZ(), L));
  const double a = (m1 - m2) * g / (m1 + m2);
  const InstantaneousSolution sol = SolveInstantaneous(model, s);
  EXPECT_TRUE(Near(sol.bodies[0].a_WBcm_W.y(), -a, 1e-12));
  EXPECT_TRUE(Near(sol.bodies[1].a_WBcm_W.y(), a, 1e-12));
  EXPECT_TRUE(Near(sol.reactions[0].lambda[0], 2 * m1 * m2 * g / (m1 + m2), 1e-12));
  SimulationOptions o;
  o.t_end = 0.4;
  o.adaptive.rtol = 1e-12;
  const SimulationResult res = Simulate(model, s, o);
  const double drop = 0.5 * a * o.t_end * o.t_end;
  EXPECT_TRUE(Near(res.final_state.bodies[0].p_WBcm.y(), -1.0 - drop, 1e-9));
  Data data = MakeData(model);
  EXPECT_LT(CalcConstraintViolation(model, res.final_state, data).position, 1e-12);
  // The certificate's balances: each mass feels T along its own end of the string (the pulley
  // takes the rest), so every body's Newton-Euler residual is round-off.
  CertificateBuilder builder;
  builder.CheckState(model, s, CheckPhase::kSolve);
  const Certificate c = builder.Finish();
  for (const CheckResult& r : c.checks) EXPECT_TRUE(r.passed()) << r.name << " " << r.worst;
}

// Yo-yo (mass m, I about its axis) falling on a string tied to the ceiling and wound on its
// hub of radius r: the hub's point on the string is at rest, v = ω r, so
//   m a = m g - T,  I a / r = T r  ⇒  a = g / (1 + I/(m r²)),  T = m g I / (I + m r²).
// The hub's point on the string (-r, 0) is at rest: -v ŷ + ω_z ẑ × (-r x̂) = 0 gives
// ω_z = -v/r (clockwise). Moving, the row's velocity terms vanish (that point is at rest and
// the string stays vertical), so the same holds.
TEST(String, YoYoFallsOnItsString) {
  const double m = 0.2, R = 0.03, r = 0.008, g = 9.81;
  const double I = 0.5 * m * R * R;
  Model model;
  model.AddBody("yoyo", Box(m, Vec3(0.25 * m * R * R, 0.25 * m * R * R, I)));
  model.AddForceElement(std::make_shared<UniformGravity>("g", Vec3(0, -g, 0)));
  State s = MakeRestState(model);
  // String from the ceiling point (-r, 1) down to the hub's left side: arriving going down
  // (-y) with the centre at T + s r z × (-y) = T + s r x: s = +1.
  model.AddConstraint(std::make_shared<StringConstraint>(
      "string", StringEnd{kWorld, Vec3(-r, 1.0, 0), 0.0, 1}, std::vector<StringPulley>{},
      StringEnd{0, Vec3::Zero(), r, 1}, Vec3::UnitZ(), 1.0));
  const double a = g / (1 + I / (m * r * r));
  const double T = m * g * I / (I + m * r * r);
  for (const double v : {0.0, 1.7}) {
    SetBodyVelocity(model, 0, Vec3(0, -v, 0), Vec3(0, 0, -v / r), s);
    const InstantaneousSolution sol = SolveInstantaneous(model, s);
    EXPECT_TRUE(Near(sol.bodies[0].a_WBcm_W.y(), -a, 1e-12)) << v;
    EXPECT_TRUE(Near(sol.bodies[0].alpha_WB_W.z(), -a / r, 1e-12)) << v;
    EXPECT_TRUE(Near(sol.reactions[0].lambda[0], T, 1e-12)) << v;
  }
  SetBodyVelocity(model, 0, Vec3::Zero(), Vec3::Zero(), s);
  SimulationOptions o;
  o.t_end = 0.3;
  o.adaptive.rtol = 1e-12;
  const SimulationResult res = Simulate(model, s, o);
  EXPECT_TRUE(Near(res.final_state.bodies[0].p_WBcm.y(), -0.5 * a * o.t_end * o.t_end, 1e-9));
  EXPECT_TRUE(Near(res.final_state.bodies[0].v_WBcm_W.y(), -a * o.t_end, 1e-9));
}

// Spool (mass m, I, outer radius R rolling on a rough floor, hub radius r) pulled by a string
// that leaves the bottom of the hub at angle θ above the horizontal towards +x. The string's
// other end is a bead (m_p) on a frictionless rod along the string, pulled outwards by F.
// With a the spool's acceleration along +x and rolling α = a / R (about -z):
// (ω_z = -v/R). About z the string's moment is (ρ × T u)_z = T r and the friction f x at
// (0, -R) gives R f, so
//   m a = T cos θ + f,   -I a / R = T r + R f   ⇒   a (m + I/R²) = T (cos θ - r/R) = T k;
// the string's leaving point moves along it at a k, so the bead: m_p a k = F - T. Then
//   a = F k / (M + m_p k²),  T = F M / (M + m_p k²),  M = m + I/R²,
// and the spool rolls towards the pull when cos θ > r/R, away from it when cos θ < r/R.
TEST(String, SpoolRollsTowardsThePullBelowTheCriticalAngle) {
  const double m = 1.2, R = 0.1, r = 0.06, I = 0.7 * m * R * R, mp = 0.3, F = 4.0;
  const double theta_c = std::acos(r / R);
  for (const double theta : {theta_c - 0.3, theta_c + 0.3}) {
    Model model;
    const int spool = model.AddBody("spool", Box(m, Vec3(0.4 * m * R * R, 0.4 * m * R * R, I)));
    const int bead = model.AddBody("bead", Box(mp, Vec3(1e-3, 1e-3, 1e-3)));
    const Vec3 u(std::cos(theta), std::sin(theta), 0);
    const Vec3 rho = r * Vec3(std::sin(theta), -std::cos(theta), 0);  // centre to the leaving point
    const Vec3 p_spool(0, R, 0);
    const Vec3 p_bead = p_spool + rho + 0.8 * u;
    model.AddConstraint(std::make_shared<RollingContact>("floor", RollingShape::kCylinder, spool,
                                                         Vec3::Zero(), Vec3::UnitZ(), R,
                                                         Vec3::Zero(), Vec3::UnitY()));
    const Mat3 Ru = FrameWithZAxis(u);
    model.AddConstraint(std::make_shared<Joint>("rod", JointKind::kPrismatic, kWorld,
                                                AttachmentFrame{p_bead, Ru}, bead,
                                                AttachmentFrame{Vec3::Zero(), Ru}));
    model.AddForceElement(
        AppliedForce::Constant("pull", bead, Vec3::Zero(), F * u, VectorFrame::kWorld));
    // The string leaves the hub's underside going along u, the centre on its left
    // (counterclockwise about z): c = T + s r z × u with z × u = -ρ / r and c - T = -ρ: s = +1.
    model.AddConstraint(std::make_shared<StringConstraint>(
        "string", StringEnd{spool, Vec3::Zero(), r, 1}, std::vector<StringPulley>{},
        StringEnd{bead, Vec3::Zero(), 0.0, 1}, Vec3::UnitZ(), 0.8));
    State s = MakeRestState(model);
    s.bodies[0].p_WBcm = p_spool;
    s.bodies[1].p_WBcm = p_bead;
    const double k = std::cos(theta) - r / R, Mst = m + I / (R * R);
    const double a = F * k / (Mst + mp * k * k);
    const double T = F * Mst / (Mst + mp * k * k);
    const InstantaneousSolution sol = SolveInstantaneous(model, s);
    EXPECT_TRUE(Near(sol.bodies[0].a_WBcm_W.x(), a, 1e-10, F / m)) << theta;
    EXPECT_TRUE(Near(sol.bodies[0].alpha_WB_W.z(), -a / R, 1e-10, F / (m * R))) << theta;
    EXPECT_TRUE(Near(sol.reactions[2].lambda[0], T, 1e-10)) << theta;
    EXPECT_EQ(a > 0, theta < theta_c);  // which way it rolls
    // Friction on the spool: f = m a - T cos θ.
    EXPECT_TRUE(Near(sol.reactions[0].F_Jc_W.x(), m * a - T * std::cos(theta), 1e-10, F)) << theta;
  }
}

// A string wound on a drum cannot go slack (its slack is not tracked: the drum's angle is known
// only modulo a turn), so a yo-yo pushed up its string by an upward gravity is refused, naming
// the string. (Strings tied to points go slack instead: constraint_modes_test.cpp.)
TEST(String, NegativeTensionOnADrumSaysTheStringWouldGoSlack) {
  const double r = 0.008;
  Model model;
  model.AddBody("yoyo", Box(0.2, Vec3(1e-4, 1e-4, 1e-4)));
  model.AddForceElement(std::make_shared<UniformGravity>("up", Vec3(0, 9.81, 0)));
  State s = MakeRestState(model);
  model.AddConstraint(std::make_shared<StringConstraint>(
      "tether", StringEnd{kWorld, Vec3(-r, 1, 0), 0.0, 1}, std::vector<StringPulley>{},
      StringEnd{0, Vec3::Zero(), r, 1}, Vec3::UnitZ(), 1.0));
  EXPECT_FALSE(model.constraint(0).can_release());
  try {
    SolveInstantaneous(model, s);
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("string 'tether' would go slack"));
    EXPECT_THAT(e.what(), HasSubstr("drum"));
  }
}

TEST(String, BadInputIsRefused) {
  const Vec3 n = Vec3::UnitZ();
  const StringEnd a{kWorld, Vec3::Zero(), 0.0, 1};
  EXPECT_THROW(StringConstraint("s", a, {}, StringEnd{0, Vec3::Zero(), -0.1, 1}, n, 1.0),
               InputError);
  EXPECT_THROW(StringConstraint("s", a, {}, StringEnd{0, Vec3::Zero(), 0.1, 2}, n, 1.0),
               InputError);
  EXPECT_THROW(
      StringConstraint("s", a, {{Vec3::Zero(), 0.0, 1}}, StringEnd{0, Vec3::Zero()}, n, 1.0),
      InputError);
  // Pulleys on more bodies than a constraint's rows can hold.
  std::vector<StringPulley> many;
  for (int b = 1; b <= ConstraintEval::kMaxExtraBodies + 1; ++b) {
    many.push_back({Vec3::Zero(), 0.1, 1, b});
  }
  EXPECT_THROW(StringConstraint("s", a, many, StringEnd{0, Vec3::Zero()}, n, 1.0), InputError);
  EXPECT_THROW(StringConstraint("s", a, {}, StringEnd{0, Vec3::Zero()}, Vec3::Zero(), 1.0),
               InputError);
  EXPECT_THROW(StringConstraint("s", a, {}, StringEnd{0, Vec3::Zero()}, n, 0.0), InputError);
  // A point mass has no drum to wind on.
  Model model;
  model.AddBody("p",
                MassProperties(1.0, Vec3::Zero(), RotationalInertia::FromMatrix(Mat3::Zero())));
  try {
    model.AddConstraint(std::make_shared<StringConstraint>(
        "s", a, std::vector<StringPulley>{}, StringEnd{0, Vec3::Zero(), 0.1, 1}, n, 1.0));
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("point mass"));
  }
}

}  // namespace
}  // namespace chasles
