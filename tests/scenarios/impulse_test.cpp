// Impulsive motion (chapter 8.5): the struck cube, a bullet embedding in a free rod, a
// meteorite embedding in a shuttle (Problems 8.51/8.52 style) and one passing through a
// probe (Problems 8.47/8.48 style).

#include <cmath>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "chasles/dynamics/impulse.h"
#include "chasles/error.h"
#include "chasles/math/rotation.h"
#include "chasles/model/model.h"
#include "test_support.h"

namespace chasles {
namespace {

using test::kExact;
using test::MatNear;
using test::Near;

// Section 8.5: cube of side a, mass m, body frame at a corner with edges along x, y, z (so the
// centre of mass is (a/2)(1, 1, 1) and I_cm = m a²/6 E, Appendix A). The impulse F Δt j at the
// corner (a, 0, 0), r = (a/2)(1, -1, -1) from the centre: H = r × F Δt j = (a F Δt/2)(i + k)
// (eq. 8.128-8.129), so w = 3 F Δt/(m a) (i + k) (eq. 8.132) and v = F Δt/m j (eq. 8.126).
// (The corner (a, 0, a) would give (a F Δt/2)(k - i) instead.)
TEST(Impulse, CubeStruckAtCorner) {
  const double m = 3.0, a = 0.5, FDt = 2.0;
  Model model;
  const BodyIndex cube = model.AddBody(
      "cube", MassProperties(m, Vec3(a / 2, a / 2, a / 2),
                             RotationalInertia(m * a * a / 6, m * a * a / 6, m * a * a / 6)));
  State s = MakeRestState(model);
  SetBodyPose(model, cube, Vec3::Zero(), Quat::Identity(), s);
  ApplyImpulse(model, cube, Vec3(a, 0, 0), Vec3(0, FDt, 0), s);
  EXPECT_TRUE(MatNear(s.bodies[0].v_WBcm_W, Vec3(0, FDt / m, 0), kExact));
  EXPECT_TRUE(MatNear(s.bodies[0].w_WB_B, Vec3(3 * FDt / (m * a), 0, 3 * FDt / (m * a)), kExact));
}

// Bullet (mass m, speed u along y) embeds at distance d from the centre of a free rod (mass M,
// length L, radius r, axis x) at rest. The combined centre is at c = m d/(M + m) on the axis.
// Momentum: v = m u/(M + m) j. Angular momentum about the combined centre: only the bullet's,
// m (d - c) u k. Inertia about it (parallel axes): I_z = M(3r² + L²)/12 + M c² + m (d - c)².
TEST(Impact, BulletEmbedsInFreeRod) {
  const double M = 1.5, L = 1.2, r = 0.01, m = 0.02, u = 300.0, d = 0.4;
  BodyMotion rod;
  rod.mass_properties = MassProperties(
      M, Vec3::Zero(),
      RotationalInertia(M * r * r / 2, M * (3 * r * r + L * L) / 12, M * (3 * r * r + L * L) / 12));
  BodyMotion bullet;
  bullet.mass_properties = MassProperties::PointMass(m, Vec3::Zero());
  bullet.p_WBcm = Vec3(d, 0, 0);
  bullet.v_WBcm_W = Vec3(0, u, 0);
  const EmbeddingResult e = CalcEmbedding(rod, bullet);
  const double c = m * d / (M + m);
  const double Iz = M * (3 * r * r + L * L) / 12 + M * c * c + m * (d - c) * (d - c);
  const double w = m * (d - c) * u / Iz;
  const double v = m * u / (M + m);
  EXPECT_TRUE(MatNear(e.composite.v_WBcm_W, Vec3(0, v, 0), kExact, v));
  EXPECT_TRUE(MatNear(e.composite.w_WB_W, Vec3(0, 0, w), kExact, w));
  EXPECT_TRUE(MatNear(e.composite.p_WBcm, Vec3(c, 0, 0), kExact, c));
  EXPECT_TRUE(Near(e.composite.mass_properties.mass(), M + m, kExact));
  EXPECT_TRUE(Near(e.kinetic_energy_before, 0.5 * m * u * u, kExact));
  const double after = 0.5 * (M + m) * v * v + 0.5 * Iz * w * w;
  EXPECT_TRUE(Near(e.kinetic_energy_lost, 0.5 * m * u * u - after, 1e-12));
  EXPECT_GT(e.kinetic_energy_lost, 0.0);
}

// Problems 8.51/8.52 style: shuttle (mass M, inertia I_s about its centre, principal) moving
// with v_s = v i, not rotating; a meteorite of mass m with v_m = v/2 k embeds at
// r_m = 2ℓ i + ℓ k from the shuttle's centre. Combined centre c = m r_m/(M + m);
// v' = (M v_s + m v_m)/(M + m); H_c = M (0 - c) × v_s + m (r_m - c) × v_m;
// I_c = I_s + M (|c|² E - c cᵀ) + m (|r_m - c|² E - (r_m - c)(r_m - c)ᵀ); w = I_c⁻¹ H_c.
TEST(Impact, MeteoriteEmbedsInShuttle) {
  const double M = 1000.0, m = 10.0, v = 100.0, l = 2.0;
  const Mat3 I_s = Vec3(M * l * l, 4 * M * l * l, 4 * M * l * l).asDiagonal();
  BodyMotion shuttle;
  shuttle.mass_properties = MassProperties(M, Vec3::Zero(), RotationalInertia::FromMatrix(I_s));
  shuttle.R_WB = RotationFromAxisAngle(Vec3(1, 2, 3), 0.0);  // identity
  shuttle.v_WBcm_W = Vec3(v, 0, 0);
  BodyMotion meteorite;
  meteorite.mass_properties = MassProperties::PointMass(m, Vec3::Zero());
  const Vec3 rm(2 * l, 0, l), vs(v, 0, 0), vm(0, 0, v / 2);
  meteorite.p_WBcm = rm;
  meteorite.v_WBcm_W = vm;
  const EmbeddingResult e = CalcEmbedding(shuttle, meteorite);
  const Vec3 c = m * rm / (M + m);
  const Vec3 rc = rm - c;
  const Mat3 E = Mat3::Identity();
  const Mat3 I_c = I_s + M * (c.squaredNorm() * E - c * c.transpose()) +
                   m * (rc.squaredNorm() * E - rc * rc.transpose());
  const Vec3 H_c = M * (-c).cross(vs) + m * rc.cross(vm);
  const Vec3 w = I_c.inverse() * H_c;
  EXPECT_TRUE(MatNear(e.composite.w_WB_W, w, 1e-13));
  EXPECT_TRUE(MatNear(e.composite.v_WBcm_W, Vec3((M * vs + m * vm) / (M + m)), kExact));
  // Energy: what is lost is the relative motion's share, ½ μ |v_m - v_s|² minus the spin-up.
  const double mu = M * m / (M + m);
  EXPECT_TRUE(Near(e.kinetic_energy_lost, 0.5 * mu * (vm - vs).squaredNorm() - 0.5 * w.dot(I_c * w),
                   1e-12));
}

// Problem 8.48 style: probe mass M, principal radii of gyration (9/8 R, 5/4 R, R); meteorite
// m with v0 = v j hits at r_A = 6R i + ½R k and leaves with 3/4 of its speed. Impulse on the
// probe J = m v/4 j; ΔH = r_A × J = (-R J/2, 0, 6 R J), so
// w = (-(m v/8) R / (M (9R/8)²), 0, (3/2) m v R / (M R²)) = (-8 m v/(81 M R), 0, 3 m v/(2 M R)).
TEST(Impact, MeteoritePassesThroughProbe) {
  const double M = 500.0, R = 1.5, m = 0.1, v = 2000.0;
  Model model;
  const BodyIndex probe = model.AddBody(
      "probe", MassProperties(M, Vec3::Zero(),
                              RotationalInertia(M * std::pow(9 * R / 8, 2),
                                                M * std::pow(5 * R / 4, 2), M * R * R)));
  State s = MakeRestState(model);
  const PassThroughResult p =
      ApplyPassThrough(model, probe, Vec3(6 * R, 0, R / 2), m, Vec3(0, v, 0), 0.75, s);
  EXPECT_TRUE(MatNear(p.impulse_W, Vec3(0, m * v / 4, 0), kExact));
  EXPECT_TRUE(MatNear(s.bodies[0].w_WB_B,
                      Vec3(-8 * m * v / (81 * M * R), 0, 3 * m * v / (2 * M * R)), kExact));
  EXPECT_TRUE(MatNear(s.bodies[0].v_WBcm_W, Vec3(0, m * v / (4 * M), 0), kExact));
  EXPECT_THAT([&] { ApplyPassThrough(model, probe, Vec3::Zero(), m, Vec3(0, v, 0), 1.5, s); },
              testing::ThrowsMessage<InputError>(testing::HasSubstr("must be in [0, 1]")));
}

}  // namespace
}  // namespace chasles
