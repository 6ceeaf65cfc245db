// Impacts with friction by integrating the impulse (Routh's incremental method) under the
// three restitution hypotheses. Closed forms and an independent planar piecewise-linear
// integration are derived here; no gravity (the impulse acts over an instant).

#include <cmath>
#include <functional>
#include <numbers>

#include <gtest/gtest.h>

#include "chasles/analysis/momentum.h"
#include "chasles/dynamics/impact.h"
#include "chasles/model/model.h"
#include "test_support.h"

namespace chasles {
namespace {

using test::Near;

constexpr RestitutionLaw kLaws[] = {RestitutionLaw::kNewton, RestitutionLaw::kPoisson,
                                    RestitutionLaw::kEnergetic};

RotationalInertia Diag(double a, double b, double c) {
  return RotationalInertia::FromMatrix(Vec3(a, b, c).asDiagonal());
}

// Solid sphere, I = 2/5 m R² (Appendix A).
MassProperties Ball(double m, double R) {
  const double I = 0.4 * m * R * R;
  return MassProperties(m, Vec3::Zero(), Diag(I, I, I));
}

double Kinetic(const Model& model, const State& s) {
  return CalcTranslationalKineticEnergy(model, s) + CalcRotationalKineticEnergy(model, s);
}

// ---------------------------------------------------------------------------------------
// Independent planar reference. One contact point, tangential coordinate t (in the plane of
// motion) and normal n; the point's velocity is linear in the impulse (Routh 1905, § 184):
//   v_t = v_t⁻ + K_tt P_t + K_tn P_n,   v_n = v_n⁻ + K_nt P_t + K_nn P_n.
// Along P_n: sliding with slip sign s, dP_t = -mu_k s dP_n; sticking, dv_t = 0 needs
// dP_t/dP_n = -K_tn/K_tt, allowed when |K_tn/K_tt| <= mu_s, else the slip starts (reverses)
// with s = sign(K_tn) (then dv_t/dP_n = K_tn - mu_k K_tt s has the sign s). Every piece has
// constant rates, so v is linear and W_n = ∫ v_n dP_n quadratic along it. Compression ends at
// v_n = 0; restitution ends at v_n = -e v_n⁻ (Newton), P_n = (1 + e) P_c (Poisson), or
// W_n = (1 - e²) W_c (Stronge: restitution work e² |W_c|).
struct Planar {
  double P_t = 0, P_n = 0, v_t = 0, v_n = 0, W_n = 0, W_t = 0, P_c = 0, W_c = 0;
  bool sticking = false;
};

Planar RouthPlanar(double Ktt, double Ktn, double Knn, double vt0, double vn0, double mu_s,
                   double mu_k, double e, RestitutionLaw law) {
  Planar x;
  x.v_t = vt0, x.v_n = vn0;
  double s = vt0 > 0 ? 1.0 : -1.0;
  bool compression = true;
  for (int piece = 0; piece < 10; ++piece) {
    double dPt;
    if (x.sticking) {
      dPt = -Ktn / Ktt;
      if (std::abs(dPt) > mu_s) x.sticking = false, s = Ktn > 0 ? 1.0 : -1.0, dPt = -mu_k * s;
    } else {
      dPt = -mu_k * s;
    }
    const double dvt = Ktt * dPt + Ktn, dvn = Ktn * dPt + Knn;
    // Distance in P_n to the next event.
    double d = 1e300;
    int event = 0;  // 1 slip stops, 2 compression ends, 3 restitution ends
    if (!x.sticking && s * dvt < 0 && std::abs(x.v_t) > 0)
      d = std::abs(x.v_t) / -(s * dvt), event = 1;
    double d2;
    if (compression) {
      d2 = -x.v_n / dvn;
    } else if (law == RestitutionLaw::kNewton) {
      d2 = (-e * vn0 - x.v_n) / dvn;
    } else if (law == RestitutionLaw::kPoisson) {
      d2 = (1 + e) * x.P_c - x.P_n;
    } else {
      // v_n d + ½ dvn d² = (1 - e²) W_c - W_n.
      const double w = (1 - e * e) * x.W_c - x.W_n;
      d2 = (-x.v_n + std::sqrt(x.v_n * x.v_n + 2 * dvn * w)) / dvn;
    }
    if (d2 <= d) d = d2, event = compression ? 2 : 3;
    x.W_n += x.v_n * d + 0.5 * dvn * d * d;
    x.W_t += dPt * (x.v_t * d + 0.5 * dvt * d * d);
    x.v_t += dvt * d, x.v_n += dvn * d;
    x.P_t += dPt * d, x.P_n += d;
    if (event == 1) x.v_t = 0, x.sticking = true;
    if (event == 2) x.v_n = 0, compression = false, x.P_c = x.P_n, x.W_c = x.W_n;
    if (event == 3) return x;
  }
  ADD_FAILURE() << "the planar reference did not finish";
  return x;
}

// ---------------------------------------------------------------------------------------
// The rod: uniform, L = 1 m, m = 1 kg, I = m L²/12 about its centre; it falls without spin at
// 45° (body x axis along d = (cos 45°, 0, sin 45°)) with v = (1, 0, -2) m/s (dropped from
// rest at h = 2²/(2 g) ≈ 0.204 m while sliding at 1 m/s), its lower end A on the floor:
// e = 0.5, mu = 0.3. With r = A - G = -(L/2) d = (-a, 0, -a), a = L/(2√2), an impulse
// (P_x, P_z) at A gives Δv = P/m and Δw_y = (r × P)_y / I = a (P_z - P_x)/I, so A's velocity
// (v_x - a w, v_z + a w) changes by
//   K = [[1/m + a²/I, -a²/I], [-a²/I, 1/m + a²/I]] = [[2.5, -1.5], [-1.5, 2.5]].
// Sliding forward the slip falls at 1.5 + 0.3·2.5 = 2.25 per unit P_n and stops at
// P_n = 1/2.25, before compression ends (v_n = -2 + 2.95 P_n); sticking needs
// |K_tn/K_tt| = 0.6 > mu, so the slip reverses.
struct RodCase {
  double m = 1.0, L = 1.0, mu = 0.3, e = 0.5, vx = 1.0, vz = 2.0;
};

TEST(Impact, RodAtFortyFiveDegreesUnderEachLaw) {
  const RodCase c;
  const double I = c.m * c.L * c.L / 12, a = c.L / (2 * std::sqrt(2.0));
  const double Ktt = 1 / c.m + a * a / I, Ktn = -a * a / I;
  for (const RestitutionLaw law : kLaws) {
    Model model;
    model.AddBody("rod", MassProperties(c.m, Vec3::Zero(), Diag(0.0, I, I)));
    ContactSpec spec;
    spec.name = "floor";
    spec.shape = ContactShape::kPointSet;
    spec.body = 0;
    spec.points_B = {Vec3(-c.L / 2, 0, 0)};
    spec.mu_s = spec.mu_k = c.mu;
    spec.restitution = c.e;
    spec.restitution_law = law;
    model.AddContact(spec);
    State s = MakeRestState(model);
    const Quat q(Eigen::AngleAxisd(-std::numbers::pi / 4, Vec3::UnitY()));
    SetBodyPose(model, 0, Vec3(a, 0, a), q, s);
    SetBodyVelocity(model, 0, Vec3(c.vx, 0, -c.vz), Vec3::Zero(), s);
    const double T0 = Kinetic(model, s);
    const ImpactResult r = ResolveImpacts(model, s);
    ASSERT_EQ(r.impulses.size(), 1u);
    EXPECT_FALSE(r.frictionless_fallback);
    EXPECT_EQ(r.impulses[0].law, law);

    const Planar x = RouthPlanar(Ktt, Ktn, Ktt, c.vx, -c.vz, c.mu, c.mu, c.e, law);
    ASSERT_FALSE(x.sticking) << "the slip reverses (needs mu >= 0.6 to stick)";
    ASSERT_LT(x.v_t, 0.0);
    // After: w = a (P_n - P_t)/I; A's slip v_t; kinetic energy from v = v⁻ + P/m and w.
    const double w1 = a * (x.P_n - x.P_t) / I;
    const Vec3 v1(c.vx + x.P_t / c.m, 0, -c.vz + x.P_n / c.m);
    const double T1 = 0.5 * c.m * v1.squaredNorm() + 0.5 * I * w1 * w1;
    const char* name = RestitutionLawName(law);
    EXPECT_TRUE(Near(s.bodies[0].w_WB_B.y(), w1, 1e-9)) << name;
    EXPECT_LE(std::abs(s.bodies[0].w_WB_B.x()) + std::abs(s.bodies[0].w_WB_B.z()), 1e-12);
    EXPECT_TRUE(Near(s.bodies[0].v_WBcm_W.x(), v1.x(), 1e-9)) << name;
    EXPECT_TRUE(Near(s.bodies[0].v_WBcm_W.z(), v1.z(), 1e-9)) << name;
    // A's velocity after (slip backwards and the rebound).
    const Vec3 r_A = -(c.L / 2) * (q * Vec3::UnitX());
    const Vec3 vA = s.bodies[0].v_WBcm_W + (q * s.bodies[0].w_WB_B).cross(r_A);
    EXPECT_TRUE(Near(vA.x(), x.v_t, 1e-9)) << name;
    EXPECT_TRUE(Near(vA.z(), x.v_n, 1e-9)) << name;
    // Energy lost: the work of the impulse, -(W_n + W_t), equals T0 - T1.
    EXPECT_TRUE(Near(T0 - T1, -(x.W_n + x.W_t), 1e-12));
    EXPECT_TRUE(Near(r.kinetic_energy_before - r.kinetic_energy_after, T0 - T1, 1e-9)) << name;
    EXPECT_TRUE(Near(r.impulses[0].compression_impulse, x.P_c, 1e-9)) << name;
    EXPECT_TRUE(Near(r.impulses[0].compression_work, x.W_c, 1e-9)) << name;
    EXPECT_TRUE(Near(r.impulses[0].normal_impulse, x.P_n, 1e-9)) << name;
    // Each law's own end condition.
    if (law == RestitutionLaw::kNewton) {
      EXPECT_TRUE(Near(vA.z(), c.e * c.vz, 1e-9));
    }
    if (law == RestitutionLaw::kPoisson) {
      EXPECT_TRUE(Near(x.P_n, (1 + c.e) * x.P_c, 1e-12));
    }
    if (law == RestitutionLaw::kEnergetic) {
      EXPECT_TRUE(Near(r.impulses[0].normal_work, (1 - c.e * c.e) * x.W_c, 1e-9));
    }
  }
}

// The laws differ here (v_n(P_n) has two slopes in compression and a third in restitution),
// and none gains energy.
TEST(Impact, RodLawsDifferAndNoneGainsEnergy) {
  const RodCase c;
  const double I = c.m * c.L * c.L / 12, a = c.L / (2 * std::sqrt(2.0));
  const double Ktt = 1 / c.m + a * a / I, Ktn = -a * a / I;
  const Planar n = RouthPlanar(Ktt, Ktn, Ktt, c.vx, -c.vz, c.mu, c.mu, c.e, kLaws[0]);
  const Planar p = RouthPlanar(Ktt, Ktn, Ktt, c.vx, -c.vz, c.mu, c.mu, c.e, kLaws[1]);
  const Planar g = RouthPlanar(Ktt, Ktn, Ktt, c.vx, -c.vz, c.mu, c.mu, c.e, kLaws[2]);
  EXPECT_GT(std::abs(n.P_n - p.P_n), 1e-3);
  EXPECT_GT(std::abs(n.P_n - g.P_n), 1e-3);
  for (const Planar& x : {n, p, g}) EXPECT_LT(x.W_n + x.W_t, 0.0);
}

// ---------------------------------------------------------------------------------------
// A solid ball (I = 2/5 m R²) hitting the floor obliquely with spin w about y. The contact
// point C = G - R z has v_C = (v_x - R w, v_z); an impulse (P_t, P_n) at C gives
// Δv_C = (P_t/m + R² P_t/I, P_n/m) = (7/2 P_t/m, P_n/m): K is diagonal, so the normal
// impulse is P_n = (1 + e) m |v_z| under every law, and the slip stops during the impulse iff
// (2/7) |v_C,x| <= mu_k (1 + e) |v_z|; then it sticks (needs no friction) with
// P_t = -(2/7) m v_C,x, else P_t = -mu_k P_n sign(v_C,x). After: v_x' = v_x + P_t/m,
// w' = w - R P_t / I (Δw_y = (r × P)_y / I = -R P_t / I).
void BallWithSpin(double w, bool expect_stop) {
  const double m = 0.2, R = 0.05, vx = 2.0, vz = 3.0, mu = 0.25, e = 0.7;
  const double I = 0.4 * m * R * R;
  const double vc = vx - R * w;
  const double Pn = (1 + e) * m * vz;
  const bool stops = 2.0 / 7.0 * std::abs(vc) <= mu * (1 + e) * vz;
  ASSERT_EQ(stops, expect_stop) << "the test's numbers no longer select the case";
  const double Pt = stops ? -2.0 / 7.0 * m * vc : -mu * Pn * (vc > 0 ? 1 : -1);
  for (const RestitutionLaw law : kLaws) {
    Model model;
    model.AddBody("ball", MassProperties(m, Vec3::Zero(), Diag(I, I, I)));
    ContactSpec spec;
    spec.name = "floor";
    spec.shape = ContactShape::kSphere;
    spec.body = 0;
    spec.radius = R;
    spec.mu_s = spec.mu_k = mu;
    spec.restitution = e;
    spec.restitution_law = law;
    model.AddContact(spec);
    State s = MakeRestState(model);
    SetBodyPose(model, 0, Vec3(0, 0, R), Quat::Identity(), s);
    SetBodyVelocity(model, 0, Vec3(vx, 0, -vz), Vec3(0, w, 0), s);
    const ImpactResult r = ResolveImpacts(model, s);
    ASSERT_EQ(r.impulses.size(), 1u);
    EXPECT_EQ(r.impulses[0].sticking, stops);
    EXPECT_TRUE(Near(r.impulses[0].normal_impulse, Pn, 1e-9));
    EXPECT_TRUE(Near(s.bodies[0].v_WBcm_W.x(), vx + Pt / m, 1e-9));
    EXPECT_TRUE(Near(s.bodies[0].v_WBcm_W.z(), -vz + Pn / m, 1e-9));
    EXPECT_TRUE(Near(s.bodies[0].w_WB_B.y(), w - R * Pt / I, 1e-9, std::abs(w)));
    const double slip = s.bodies[0].v_WBcm_W.x() - R * s.bodies[0].w_WB_B.y();
    EXPECT_TRUE(Near(slip, stops ? 0.0 : vc + 3.5 * Pt / m, 1e-9, std::abs(vc)));
  }
}

TEST(Impact, BallWithTopspinStopsSlipping) {
  BallWithSpin(30.0, true);
}
TEST(Impact, BallWithBackspinKeepsSlipping) {
  BallWithSpin(-60.0, false);
}

// ---------------------------------------------------------------------------------------
// Collinear impacts, where v_n(P_n) has one slope and no friction acts: v_n = v_n⁻ + P_n/m_eff,
// so P_c = m_eff |v_n⁻|, W_c = -½ m_eff v_n⁻², and Newton (v_n⁺ = e |v_n⁻|), Poisson
// (P = (1 + e) P_c) and Stronge (W_r = e² |W_c|, i.e. ½ m_eff v_n⁺² = e² ½ m_eff v_n⁻²) all
// give P_n = (1 + e) m_eff |v_n⁻| and the loss ½ m_eff (1 - e²) v_n⁻².
TEST(Impact, CollinearImpactsAgreeUnderAllLaws) {
  // A ball dropped without spin (m_eff = m).
  const double m = 0.3, R = 0.04, v = 2.5, e = 0.6;
  for (const RestitutionLaw law : kLaws) {
    Model model;
    const double I = 0.4 * m * R * R;
    model.AddBody("ball", MassProperties(m, Vec3::Zero(), Diag(I, I, I)));
    ContactSpec spec;
    spec.name = "floor";
    spec.shape = ContactShape::kSphere;
    spec.body = 0;
    spec.radius = R;
    spec.mu_s = spec.mu_k = 0.4;
    spec.restitution = e;
    spec.restitution_law = law;
    model.AddContact(spec);
    State s = MakeRestState(model);
    SetBodyPose(model, 0, Vec3(0, 0, R), Quat::Identity(), s);
    SetBodyVelocity(model, 0, Vec3(0, 0, -v), Vec3::Zero(), s);
    const ImpactResult r = ResolveImpacts(model, s);
    ASSERT_EQ(r.impulses.size(), 1u);
    EXPECT_TRUE(Near(s.bodies[0].v_WBcm_W.z(), e * v, 1e-12));
    EXPECT_TRUE(Near(r.impulses[0].normal_impulse, (1 + e) * m * v, 1e-12));
    EXPECT_TRUE(Near(r.kinetic_energy_before - r.kinetic_energy_after,
                     0.5 * m * (1 - e * e) * v * v, 1e-12));
  }
  // Two spheres head-on (m_eff = m1 m2/(m1 + m2)).
  const double m1 = 1.5, m2 = 0.7, R1 = 0.1, R2 = 0.05, v1 = 2.0, v2 = -0.5;
  const double mu = m1 * m2 / (m1 + m2);
  for (const RestitutionLaw law : kLaws) {
    Model model;
    model.AddBody("a", Ball(m1, R1));
    model.AddBody("b", Ball(m2, R2));
    ContactSpec spec;
    spec.name = "hit";
    spec.shape = ContactShape::kSphereSphere;
    spec.body = 1;
    spec.radius = R2;
    spec.other_body = 0;
    spec.other_radius = R1;
    spec.mu_s = spec.mu_k = 0.3;
    spec.restitution = e;
    spec.restitution_law = law;
    model.AddContact(spec);
    State s = MakeRestState(model);
    SetBodyPose(model, 1, Vec3(R1 + R2, 0, 0), Quat::Identity(), s);
    SetBodyVelocity(model, 0, Vec3(v1, 0, 0), Vec3::Zero(), s);
    SetBodyVelocity(model, 1, Vec3(v2, 0, 0), Vec3::Zero(), s);
    const ImpactResult r = ResolveImpacts(model, s);
    ASSERT_EQ(r.impulses.size(), 1u);
    EXPECT_TRUE(Near(r.impulses[0].normal_impulse, mu * (1 + e) * (v1 - v2), 1e-12));
    EXPECT_TRUE(Near(s.bodies[1].v_WBcm_W.x() - s.bodies[0].v_WBcm_W.x(), e * (v1 - v2), 1e-12));
    EXPECT_TRUE(Near(r.kinetic_energy_before - r.kinetic_energy_after,
                     0.5 * mu * (1 - e * e) * (v1 - v2) * (v1 - v2), 1e-12));
  }
}

}  // namespace
}  // namespace chasles

namespace chasles {
namespace {

// ---------------------------------------------------------------------------------------
// A 3-D slip that turns: a body (diagonal inertia, tilted) strikes the floor at a point r
// from G while sliding obliquely. Δv_C = P/m + (I_W⁻¹ (r × P)) × r, so
//   K = E/m - [r]× I_W⁻¹ [r]×,
// and while sliding dv/dP_n = K (ẑ - mu ŝ), ŝ = v_t/|v_t| (turns: K_tt is not isotropic and
// K_tn ≠ 0), dW_n/dP_n = v_z. The reference integrates this with fixed RK4 steps (h = 1e-4
// of the impulse scale: error ~ h⁴) and finds each event by bisection on the last step:
// compression ends at v_z = 0, restitution (energetic) at W_n = (1 - e²) W_c. The slip is
// large enough not to stop (checked).
TEST(Impact, TurningSlipIn3dAgainstAFineReference) {
  const double m = 1.3, mu = 0.2, e = 0.6;
  const Vec3 I_diag(0.1, 0.2, 0.25), r_B(0.2, -0.1, -0.3);
  const Quat q = Quat(Eigen::AngleAxisd(0.4, Vec3(1, 2, 3).normalized()));
  const Vec3 w0(1.0, -2.0, 0.5), vC0(2.0, 1.0, -1.5);
  const Mat3 R = q.toRotationMatrix();
  const Vec3 r = R * r_B;
  const Mat3 I_W = R * I_diag.asDiagonal() * R.transpose();
  auto cross = [](const Vec3& a) {
    Mat3 X;
    X << 0, -a.z(), a.y(), a.z(), 0, -a.x(), -a.y(), a.x(), 0;
    return X;
  };
  const Mat3 K = Mat3::Identity() / m - cross(r) * I_W.inverse() * cross(r);
  // Reference: y = (v_C, W_n), parameter P_n.
  using Y = Eigen::Vector4d;
  auto f = [&](const Y& y) {
    const Vec3 v = y.head<3>();
    const Vec3 s = Vec3(v.x(), v.y(), 0).normalized();
    Y d;
    d.head<3>() = K * (Vec3::UnitZ() - mu * s);
    d[3] = v.z();
    return d;
  };
  auto rk4 = [&](const Y& y, double h) {
    const Y k1 = f(y), k2 = f(y + 0.5 * h * k1), k3 = f(y + 0.5 * h * k2), k4 = f(y + h * k3);
    return Y(y + h / 6 * (k1 + 2 * k2 + 2 * k3 + k4));
  };
  // Advances y until g(y) >= 0, the last step bisected to the crossing; returns P_n added.
  const double h = 1e-4 * vC0.norm() / K(2, 2);
  auto run_to = [&](Y& y, const std::function<double(const Y&)>& g) {
    double P = 0;
    for (int i = 0; i < 1000000; ++i) {
      const Y next = rk4(y, h);
      if (g(next) < 0) {
        y = next, P += h;
        EXPECT_GT(Vec3(y.x(), y.y(), 0).norm(), 0.1) << "the slip must not stop";
        continue;
      }
      double lo = 0, hi = h;
      for (int k = 0; k < 200; ++k) (g(rk4(y, 0.5 * (lo + hi))) < 0 ? lo : hi) = 0.5 * (lo + hi);
      y = rk4(y, hi);
      return P + hi;
    }
    ADD_FAILURE() << "no event";
    return P;
  };
  Y y;
  y << vC0, 0.0;
  double Pn = run_to(y, [](const Y& x) { return x.z(); });
  const double Wc = y[3];
  Pn += run_to(y, [&](const Y& x) { return x[3] - (1 - e * e) * Wc; });
  const Vec3 vC1 = y.head<3>();

  Model model;
  model.AddBody(
      "body", MassProperties(m, Vec3::Zero(), RotationalInertia::FromMatrix(I_diag.asDiagonal())));
  ContactSpec spec;
  spec.name = "floor";
  spec.shape = ContactShape::kPointSet;
  spec.body = 0;
  spec.points_B = {r_B};
  spec.mu_s = spec.mu_k = mu;
  spec.restitution = e;
  model.AddContact(spec);
  State s = MakeRestState(model);
  SetBodyPose(model, 0, Vec3(0, 0, -r.z()), q, s);
  SetBodyVelocity(model, 0, vC0 - w0.cross(r), w0, s);
  const ImpactResult res = ResolveImpacts(model, s);
  ASSERT_EQ(res.impulses.size(), 1u);
  EXPECT_FALSE(res.impulses[0].sticking);
  const Vec3 w1 = q * s.bodies[0].w_WB_B;
  const Vec3 vC = s.bodies[0].v_WBcm_W + w1.cross(r);
  EXPECT_TRUE(test::MatNear(vC, vC1, 1e-9)) << vC.transpose() << " vs " << vC1.transpose();
  EXPECT_TRUE(Near(res.impulses[0].normal_impulse, Pn, 1e-9));
  EXPECT_TRUE(Near(res.impulses[0].compression_work, Wc, 1e-9));
  // The slip direction turned: the final slip is not parallel to the initial one.
  const Vec3 t0 = Vec3(vC0.x(), vC0.y(), 0).normalized(),
             t1 = Vec3(vC1.x(), vC1.y(), 0).normalized();
  EXPECT_LT(t0.dot(t1), 1 - 1e-3);
}

}  // namespace
}  // namespace chasles
