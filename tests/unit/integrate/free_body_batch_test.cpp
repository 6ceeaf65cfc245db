// The structure-of-arrays batch of free bodies (chasles/integrate/free_body_batch.h) against
// closed forms: the torque-free axisymmetric top (both steppers, with their orders), the
// splitting's invariants, exact translation, agreement with Rk4Integrator, thread count.

#include "chasles/integrate/free_body_batch.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "chasles/error.h"
#include "chasles/integrate/rk4.h"
#include "chasles/integrate/simulate.h"
#include "chasles/math/rotation.h"
#include "chasles/model/constraints.h"
#include "chasles/model/forces.h"
#include "chasles/model/model.h"
#include "reference/torque_free_top.h"
#include "test_support.h"

namespace chasles {
namespace {

using test::kEps;

/// Random unit quaternion (normalised 4-vector of normals: uniform on SO(3)).
Quat RandomQuat(std::mt19937_64& rng) {
  std::normal_distribution<double> n;
  return Quat(n(rng), n(rng), n(rng), n(rng)).normalized();
}

/// n bodies with random masses, principal moments (triangle inequality kept) and, when
/// `rotated`, principal axes not along B's; random pose, velocity and generic spin; gravity g.
Model RandomBodies(int n, std::mt19937_64& rng, bool rotated, const Vec3& g, State* state) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Model m;
  for (int b = 0; b < n; ++b) {
    const double I1 = 1.0 + u(rng), I2 = 1.0 + u(rng), I3 = 1.0 + u(rng);  // I₁ + I₂ > 2 > I₃
    RotationalInertia I(I1, I2, I3);
    if (rotated) I = I.ReExpressedIn(RandomQuat(rng).toRotationMatrix());
    m.AddBody(fmt::format("b{}", b), MassProperties(0.5 + u(rng), Vec3::Zero(), I));
  }
  m.AddForceElement(std::make_shared<UniformGravity>("gravity", g));
  *state = MakeRestState(m);
  for (int b = 0; b < n; ++b) {
    SetBodyPose(m, b, Vec3(u(rng), u(rng), u(rng)) * 10.0, RandomQuat(rng), *state);
    BodyState& s = state->bodies[static_cast<size_t>(b)];
    s.v_WBcm_W = Vec3(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5) * 4.0;
    s.w_WB_B = Vec3(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5) * 6.0;
  }
  return m;
}

/// Angle of the rotation between two unit quaternions [rad].
double Angle(const Quat& a, const Quat& b) {
  return a.angularDistance(b);
}

// Axisymmetric top, I₁ = I₂ = A, I₃ = C, no moment. Euler's equations (eqs. 8.79-8.81) give ω₃
// constant and ω̇₁ = −Ω ω₂, ω̇₂ = Ω ω₁ with Ω = (C − A) ω₃/A: (ω₁, ω₂) turns about the symmetry
// axis at Ω. The orientation: ω_B = L_B/A + (1/C − 1/A) L₃ e₃ = L_B/A − Ω e₃, a spin |L|/A
// about the fixed L_W composed with a spin −Ω about the body's e₃, which commute along the
// motion: R(t) = Rot(L̂_W, |L| t/A) R₀ Rot(e₃, −Ω t).
struct TopRun {
  double w_error, q_error;
};

TopRun RunTop(FreeBodyStepper stepper, double h, double T) {
  constexpr double A = 1.0, C = 1.7;
  Model m;
  m.AddBody("top", MassProperties(2.0, Vec3::Zero(), RotationalInertia(A, A, C)));
  State s = MakeRestState(m);
  const Quat q0 = Quat(RotationFromAxisAngle(Vec3(1, 2, 3).normalized(), 0.7));
  const Vec3 w0(0.8, -0.5, 5.0);
  s.bodies[0].q_WB = q0;
  s.bodies[0].w_WB_B = w0;
  s.bodies[0].v_WBcm_W = Vec3::Zero();
  FreeBodyBatch batch(m);
  batch.Load(s);
  const auto steps = static_cast<long long>(std::llround(T / h));
  batch.Advance(stepper, h, steps);
  batch.Store(s);
  const double Omega = (C - A) * w0.z() / A;
  const Vec3 w_ref(w0.x() * std::cos(Omega * T) - w0.y() * std::sin(Omega * T),
                   w0.x() * std::sin(Omega * T) + w0.y() * std::cos(Omega * T), w0.z());
  const Vec3 L_W = q0 * Vec3(A * w0.x(), A * w0.y(), C * w0.z());
  const Quat q_ref = Quat(RotationFromAxisAngle(L_W.normalized(), L_W.norm() * T / A)) * q0 *
                     Quat(RotationFromAxisAngle(Vec3::UnitZ(), -Omega * T));
  return {(s.bodies[0].w_WB_B - w_ref).norm() / w0.norm(), Angle(s.bodies[0].q_WB, q_ref)};
}

/// Options of a fixed-step run with h = 1 ms, sampled every `output_interval` to `t_end` [s].
SimulationOptions FixedStep(IntegratorKind kind, double output_interval, double t_end) {
  SimulationOptions o;
  o.integrator = kind;
  o.fixed_step = 1e-3;
  o.output_interval = output_interval;
  o.t_end = t_end;
  return o;
}

// Halving h divides the error by 2^p: 16 for RK4, 4 for the second-order splitting. The
// ratios are taken where the error is far above round-off and h|ω| small (0.05 to 0.0125).
TEST(FreeBodyBatch, AxisymmetricTopConvergesWithTheOrderOfEachStepper) {
  constexpr double T = 2.0;
  for (const auto& [stepper, order] :
       {std::pair{FreeBodyStepper::kRk4, 4}, std::pair{FreeBodyStepper::kSplitting, 2}}) {
    const TopRun e1 = RunTop(stepper, 0.01, T);
    const TopRun e2 = RunTop(stepper, 0.005, T);
    const TopRun e3 = RunTop(stepper, 0.0025, T);
    const double expected = std::pow(2.0, order);
    for (const auto& [a, b] :
         {std::pair{e1.w_error, e2.w_error}, std::pair{e2.w_error, e3.w_error},
          std::pair{e1.q_error, e2.q_error}, std::pair{e2.q_error, e3.q_error}}) {
      std::printf("order %d: error %.3g -> %.3g, ratio %.3f\n", order, a, b, a / b);
      EXPECT_GT(a / b, 0.9 * expected) << "order " << order << ": " << a << " -> " << b;
      EXPECT_LT(a / b, 1.1 * expected) << "order " << order << ": " << a << " -> " << b;
    }
    // And they converge to the closed form: RK4 at h ω = 0.0125 is within 1e-8, the splitting
    // within 1e-3 (its error constant is about (hω)²/12 per unit angle).
    EXPECT_LT(e3.w_error, order == 4 ? 1e-8 : 1e-3);
    EXPECT_LT(e3.q_error, order == 4 ? 1e-8 : 1e-3);
  }
}

// Each sub-flow of the splitting turns L (body frame) and the body by the same orthogonal
// rotation, so L_W = R_WP L_P is unchanged and |q| is reset once per step: both hold to
// round-off at every step (a few ulps per step, checked step by step against the previous
// one). The energy is that of a modified Hamiltonian: it oscillates, without drift.
TEST(FreeBodyBatch, SplittingKeepsAngularMomentumAndQuaternionNormAndEnergyDoesNotDrift) {
  std::mt19937_64 rng(7);
  State s;
  const Model m = RandomBodies(4, rng, true, Vec3::Zero(), &s);
  FreeBodyBatch batch(m);
  batch.Load(s);
  const auto L_W = [&](const State& st, int b) {
    const Body& body = m.body(b);
    const BodyState& x = st.bodies[static_cast<size_t>(b)];
    return Vec3(x.q_WB * (body.I_BBcm_B() * x.w_WB_B));
  };
  const auto energy = [&](const State& st, int b) {
    const BodyState& x = st.bodies[static_cast<size_t>(b)];
    return 0.5 * x.w_WB_B.dot(m.body(b).I_BBcm_B() * x.w_WB_B);
  };
  constexpr double h = 0.01;
  constexpr int n = 20000;  // 200 s, many periods of the free motion (|ω| ≈ 3 rad/s)
  std::vector<Vec3> L_prev;
  std::vector<double> E0, first(4, 0.0), last(4, 0.0);
  for (int b = 0; b < 4; ++b) L_prev.push_back(L_W(s, b)), E0.push_back(energy(s, b));
  for (int k = 1; k <= n; ++k) {
    batch.Advance(FreeBodyStepper::kSplitting, h, 1);
    State x = s;
    batch.Store(x);
    for (int b = 0; b < 4; ++b) {
      const Vec3 L = L_W(x, b);
      ASSERT_LE((L - L_prev[static_cast<size_t>(b)]).norm(), 16 * kEps * L.norm()) << k;
      L_prev[static_cast<size_t>(b)] = L;
      ASSERT_LE(std::abs(x.bodies[static_cast<size_t>(b)].q_WB.norm() - 1.0), 4 * kEps);
      const double dE = std::abs(energy(x, b) / E0[static_cast<size_t>(b)] - 1.0);
      if (k <= n / 10) first[static_cast<size_t>(b)] = std::max(first[static_cast<size_t>(b)], dE);
      if (k > n - n / 10) last[static_cast<size_t>(b)] = std::max(last[static_cast<size_t>(b)], dE);
    }
  }
  for (int b = 0; b < 4; ++b) {
    // Bounded oscillation: the last tenth of the run strays little further than the first tenth
    // did, and both are O((hω)²). A drift linear in t would have grown at least ninefold between
    // the two windows (t ≤ 20 s against t ≥ 180 s); the oscillation of the modified energy is
    // quasi-periodic, so each window's largest value depends on the phases it happens to
    // sample, and on the rounding: 1.72 times the first window's for body 1 as clang compiles
    // the batch, under 1.5 as GCC does. Three times separates the two cases with room.
    EXPECT_LE(last[static_cast<size_t>(b)], 3.0 * first[static_cast<size_t>(b)]) << b;
    EXPECT_LT(first[static_cast<size_t>(b)], 1e-3) << b;
  }
}

// Under uniform gravity p = p₀ + v₀ t + ½ g t², v = v₀ + g t (eqs. 8.76-8.78 with F = m g): both
// steppers take it exactly; only the rounding of the sums remains.
TEST(FreeBodyBatch, TranslationUnderUniformGravityIsExact) {
  std::mt19937_64 rng(11);
  const Vec3 g(0.3, -1.2, -9.81);
  State s0;
  const Model m = RandomBodies(50, rng, false, g, &s0);
  for (const FreeBodyStepper stepper : {FreeBodyStepper::kRk4, FreeBodyStepper::kSplitting}) {
    FreeBodyBatch batch(m);
    batch.Load(s0);
    constexpr double h = 1e-3;
    constexpr long long n = 1000;
    batch.Advance(stepper, h, n);
    State s = s0;
    batch.Store(s);
    const double t = h * n;
    EXPECT_TRUE(test::Near(s.t, t, 1e-14));
    for (size_t b = 0; b < s.bodies.size(); ++b) {
      const BodyState& a = s0.bodies[b];
      const Vec3 p = a.p_WBcm + a.v_WBcm_W * t + 0.5 * g * t * t;
      const Vec3 v = a.v_WBcm_W + g * t;
      EXPECT_TRUE(test::MatNear(s.bodies[b].p_WBcm, p, 1e-12, 1.0)) << b;
      EXPECT_TRUE(test::MatNear(s.bodies[b].v_WBcm_W, v, 1e-12, 1.0)) << b;
    }
  }
}

// The batch's RK4 is the engine's RK4 (same stages, same step) on the same equations; the two
// differ only in rounding: the order of the operations in Euler's equations (the engine uses
// the inverse tensor), the closed-form translation, the principal-frame conversion of a
// rotated body (a few ulps once), and the engine's compensated updates. Each is a few ulps per
// step, so after n = 1000 steps the states agree to about n · 4 ε ≈ 1e-12 relative at most
// (the free motion does not amplify them exponentially). Measured with GCC 12: 1.9e-16 for
// bodies whose principal axes are B's, 2.4e-15 for rotated ones (both carry compensation).
TEST(FreeBodyBatch, Rk4AgreesWithTheEngineRk4) {
  for (const bool rotated : {false, true}) {
    std::mt19937_64 rng(rotated ? 5 : 3);
    State s0;
    const Model m = RandomBodies(20, rng, rotated, Vec3(0, 0, -9.81), &s0);
    State engine = s0, batched = s0;
    Rk4Integrator rk4(m);
    constexpr double h = 1e-3;
    constexpr int n = 1000;
    for (int k = 0; k < n; ++k) rk4.Step(engine, h);
    FreeBodyBatch batch(m);
    batch.Load(s0);
    batch.Advance(FreeBodyStepper::kRk4, h, n);
    batch.Store(batched);
    const double tol = n * 4 * kEps;
    double worst = 0.0;
    for (size_t b = 0; b < s0.bodies.size(); ++b) {
      const BodyState &e = engine.bodies[b], &x = batched.bodies[b];
      worst =
          std::max({worst, Angle(x.q_WB, e.q_WB), (x.w_WB_B - e.w_WB_B).norm() / e.w_WB_B.norm(),
                    (x.p_WBcm - e.p_WBcm).norm() / std::max(1.0, e.p_WBcm.norm())});
      EXPECT_TRUE(test::MatNear(x.p_WBcm, e.p_WBcm, tol, 1.0)) << b;
      EXPECT_TRUE(test::MatNear(x.v_WBcm_W, e.v_WBcm_W, tol, 1.0)) << b;
      EXPECT_LT(Angle(x.q_WB, e.q_WB), tol) << b;
      EXPECT_TRUE(test::MatNear(x.w_WB_B, e.w_WB_B, tol)) << b;
    }
    std::printf("%s principal axes: largest relative difference from the engine %.3g\n",
                rotated ? "rotated" : "body-frame", worst);
  }
}

// The batch's RK4 carries the rounding of its updates from step to step like Rk4Integrator
// (compensated sums; the quaternion's compensation across its renormalisation, the rounding of
// q_i/|q| found exactly by Dekker's product): on the Dzhanibekov flip (tests/reference,
// I = 1, 2, 3, ω₀ = (0.01, 10, 0.01) rad/s), 10 s at h = 1e-3, it ends as close to the same
// method run in long double as the engine does (rk4_test.cpp: below 2e-11 rad, where a plain
// double loop is 1.85e-9 rad away), so its accuracy per step and over the run is the engine's.
TEST(FreeBodyBatch, Rk4RoundOffIsCompensatedLikeTheEngine) {
  constexpr double h = 1e-3;
  constexpr long n = 10000;
  const reference::Top<long double> ref = reference::PlainRk4<long double>(h, n);
  const double plain = reference::Angle(ref, reference::PlainRk4<double>(h, n));
  const Model m = reference::DzhanibekovModel();
  State s = reference::DzhanibekovStart(m);
  FreeBodyBatch batch(m);
  batch.Load(s);
  batch.Advance(FreeBodyStepper::kRk4, h, n);
  batch.Store(s);
  const double batched = reference::Angle(ref, reference::FromState(s));
  std::printf("orientation round-off after 10 s: plain %.3g rad, batch %.3g rad\n", plain, batched);
  EXPECT_LT(batched, 2e-11);
  EXPECT_LT(50.0 * batched, plain);
}

// Bodies are independent and each is computed by the same operations whatever block, tile or
// call it falls in: 2 threads, 1 thread, and one step per call give the same bits.
TEST(FreeBodyBatch, ThreadCountAndCallSplitDoNotChangeTheBits) {
  std::mt19937_64 rng(23);
  State s0;
  const Model m = RandomBodies(1000, rng, true, Vec3(0, 0, -9.81), &s0);
  for (const FreeBodyStepper stepper : {FreeBodyStepper::kRk4, FreeBodyStepper::kSplitting}) {
    FreeBodyBatch one(m), two(m), stepwise(m);
    one.Load(s0), two.Load(s0), stepwise.Load(s0);
    one.Advance(stepper, 1e-3, 50, 1);
    two.Advance(stepper, 1e-3, 50, 2);
    for (int k = 0; k < 50; ++k) stepwise.Advance(stepper, 1e-3, 1, 1);
    State a = s0, b = s0, c = s0;
    one.Store(a), two.Store(b), stepwise.Store(c);
    for (size_t i = 0; i < s0.bodies.size(); ++i) {
      for (const State* x : {&b, &c}) {
        const BodyState &p = a.bodies[i], &r = x->bodies[i];
        ASSERT_TRUE(p.p_WBcm == r.p_WBcm && p.v_WBcm_W == r.v_WBcm_W &&
                    p.q_WB.coeffs() == r.q_WB.coeffs() && p.w_WB_B == r.w_WB_B)
            << i;
      }
    }
  }
}

// Simulate with fixed-step RK4 on a model of free bodies under gravity takes the batch (its
// stats say so) and gives the samples and the force ledger of the engine's RK4 on the same
// grid, to round-off. The ledger's closed forms (work m g·Δp, impulse M g t, angular impulse
// ∫ Σ m p × g dt) are exact for the quadratic p(t), as is RK4's quadrature of them.
TEST(FreeBodyBatch, SimulateTakesTheBatchAndAgreesWithTheGenericPath) {
  std::mt19937_64 rng(31);
  State s0;
  Model m = RandomBodies(30, rng, true, Vec3(0, 0.5, -9.81), &s0);
  m.AddForceElement(std::make_shared<UniformGravity>("second gravity", Vec3(1.0, 0, 0)));
  s0.force_integrals.resize(2);
  const SimulationResult r = Simulate(m, s0, FixedStep(IntegratorKind::kRk4, 0.1, 0.5));
  EXPECT_TRUE(r.stats.free_body_batch);
  EXPECT_EQ(r.stats.steps, 500);
  ASSERT_EQ(r.samples.size(), 6u);
  State e = s0;
  Rk4Integrator rk4(m);
  const double tol = 500 * 4 * kEps;
  for (size_t k = 1; k < r.samples.size(); ++k) {
    for (int i = 0; i < 100; ++i) rk4.Step(e, 1e-3);
    const State& x = r.samples[k];
    EXPECT_TRUE(test::Near(x.t, e.t, 1e-15));
    for (size_t b = 0; b < e.bodies.size(); ++b) {
      EXPECT_TRUE(test::MatNear(x.bodies[b].p_WBcm, e.bodies[b].p_WBcm, tol, 1.0));
      EXPECT_TRUE(test::MatNear(x.bodies[b].v_WBcm_W, e.bodies[b].v_WBcm_W, tol, 1.0));
      EXPECT_LT(Angle(x.bodies[b].q_WB, e.bodies[b].q_WB), tol);
      EXPECT_TRUE(test::MatNear(x.bodies[b].w_WB_B, e.bodies[b].w_WB_B, tol));
    }
    for (size_t f = 0; f < 2; ++f) {
      const ForceIntegrals &a = x.force_integrals[f], &c = e.force_integrals[f];
      const double scale = 10.0 * std::abs(c.work) + 10.0;
      EXPECT_TRUE(test::Near(a.work, c.work, tol, scale)) << f;
      EXPECT_EQ(a.work_nonconservative, 0.0);
      EXPECT_TRUE(test::MatNear(a.linear_impulse_W, c.linear_impulse_W, tol, scale)) << f;
      EXPECT_TRUE(test::MatNear(a.angular_impulse_Wo_W, c.angular_impulse_Wo_W, tol, scale)) << f;
    }
  }
}

// Simulate's batch path keeps the bodies in the batch from output to output: on a grid whose
// step h = 2⁻¹⁰ s divides the output interval 50 h exactly (no shortening), its samples are
// the batch's own Advance bit for bit, for both steppers, on one thread (each tile of bodies
// loaded as its first step reaches it) and on two (all loaded first); the gravity ledger,
// whose sums are taken as the bodies are loaded and stored, is the same bit for bit on both.
TEST(FreeBodyBatch, SimulateIsTheBatchBitForBit) {
  std::mt19937_64 rng(5);
  State s0;
  const Model m = RandomBodies(150, rng, true, Vec3(0.2, 0, -9.81), &s0);
  const double h = std::ldexp(1.0, -10);
  for (const IntegratorKind kind : {IntegratorKind::kRk4, IntegratorKind::kSplitting}) {
    SimulationOptions o = FixedStep(kind, 50 * h, 200 * h);
    o.fixed_step = h;
    std::vector<SimulationResult> runs;
    for (const int threads : {1, 2}) {
      o.threads = threads;
      runs.push_back(Simulate(m, s0, o));
      const SimulationResult& r = runs.back();
      ASSERT_EQ(r.samples.size(), 5u);
      EXPECT_EQ(r.stats.steps, 200);
      FreeBodyBatch batch(m);
      batch.Load(s0);
      State e = s0;
      for (size_t k = 1; k < r.samples.size(); ++k) {
        batch.Advance(
            kind == IntegratorKind::kRk4 ? FreeBodyStepper::kRk4 : FreeBodyStepper::kSplitting, h,
            50);
        batch.Store(e);
        const State& x = r.samples[k];
        EXPECT_EQ(x.t, static_cast<double>(k) * 50 * h);
        for (size_t b = 0; b < e.bodies.size(); ++b) {
          const BodyState &p = x.bodies[b], &q = e.bodies[b];
          ASSERT_TRUE(p.p_WBcm == q.p_WBcm && p.v_WBcm_W == q.v_WBcm_W &&
                      p.q_WB.coeffs() == q.q_WB.coeffs() && p.w_WB_B == q.w_WB_B)
              << threads << " " << k << " " << b;
        }
      }
    }
    for (size_t k = 0; k < runs[0].samples.size(); ++k) {
      const ForceIntegrals &a = runs[0].samples[k].force_integrals[0],
                           &b = runs[1].samples[k].force_integrals[0];
      EXPECT_TRUE(a.work == b.work && a.linear_impulse_W == b.linear_impulse_W &&
                  a.angular_impulse_Wo_W == b.angular_impulse_Wo_W)
          << k;
    }
    EXPECT_NE(runs[0].final_state.force_integrals[0].work, 0.0);
  }
}

// The `splitting` integrator is the batch's splitting stepper on the fixed grid: Simulate's
// samples are the batch advanced by hand, to round-off (the grid cuts each output stretch
// t_k+1 − t_k into equal steps, which differ from 1e-3 s in the last bits). Gravity's ledger is
// the closed form for the splitting's exact translation, p(t) = p₀ + v₀t + ½gt²: its work is
// Σ m g·(p(t) − p₀) and its impulse M g t, so the translational energy balances exactly (to
// round-off): ½ m |v|² − ½ m |v₀|² = work.
TEST(FreeBodyBatch, SplittingIntegratorIsTheBatchOnTheFixedGridWithAnExactGravityLedger) {
  std::mt19937_64 rng(47);
  State s0;
  const Vec3 g(0.3, -0.2, -9.81);
  const Model m = RandomBodies(20, rng, true, g, &s0);
  const SimulationResult r = Simulate(m, s0, FixedStep(IntegratorKind::kSplitting, 0.05, 0.2));
  EXPECT_TRUE(r.stats.free_body_batch);
  EXPECT_EQ(r.stats.steps, 200);
  ASSERT_EQ(r.samples.size(), 5u);
  FreeBodyBatch batch(m);
  batch.Load(s0);
  State e = s0;
  double M = 0.0, work = 0.0, ke0 = 0.0, ke = 0.0;
  for (int b = 0; b < m.num_bodies(); ++b) M += m.body(b).mass();
  for (size_t k = 1; k < r.samples.size(); ++k) {
    for (int i = 0; i < 50; ++i) batch.Advance(FreeBodyStepper::kSplitting, 1e-3, 1);
    batch.Store(e);
    const State& x = r.samples[k];
    work = 0.0;
    ke0 = 0.0;
    ke = 0.0;
    for (size_t b = 0; b < e.bodies.size(); ++b) {
      const double tol = 200 * 8 * kEps;
      EXPECT_TRUE(test::MatNear(x.bodies[b].p_WBcm, e.bodies[b].p_WBcm, tol, 1.0)) << k << b;
      EXPECT_TRUE(test::MatNear(x.bodies[b].v_WBcm_W, e.bodies[b].v_WBcm_W, tol, 1.0)) << k << b;
      EXPECT_LT(Angle(x.bodies[b].q_WB, e.bodies[b].q_WB), tol) << k << " " << b;
      EXPECT_TRUE(test::MatNear(x.bodies[b].w_WB_B, e.bodies[b].w_WB_B, tol, 1.0)) << k << b;
      const double mb = m.body(static_cast<int>(b)).mass();
      work += mb * g.dot(x.bodies[b].p_WBcm - s0.bodies[b].p_WBcm);
      ke0 += 0.5 * mb * s0.bodies[b].v_WBcm_W.squaredNorm();
      ke += 0.5 * mb * x.bodies[b].v_WBcm_W.squaredNorm();
    }
    const ForceIntegrals& fi = x.force_integrals[0];
    EXPECT_TRUE(test::Near(fi.work, work, 1e-12, ke0)) << k;
    EXPECT_TRUE(test::Near(ke - ke0, work, 1e-12, ke0)) << k;
    EXPECT_TRUE(test::MatNear(fi.linear_impulse_W, M * g * x.t, 1e-12)) << k;
  }
}

// Any other model is refused by name before a step is taken.
TEST(FreeBodyBatch, SplittingIntegratorRefusesAModelTheBatchCannotStep) {
  Model m;
  m.AddBody("a", MassProperties(1.0, Vec3::Zero(), RotationalInertia(1, 2, 3)));
  m.AddForceElement(std::make_shared<CentralGravity>("sun", 1.0, Vec3(5, 0, 0)));
  State s = MakeRestState(m);
  s.force_integrals.resize(1);
  SimulationOptions o;
  o.integrator = IntegratorKind::kSplitting;
  o.fixed_step = 1e-3;
  o.t_end = 0.1;
  try {
    Simulate(m, s, o);
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(),
                 "the splitting integrator steps free bodies under uniform gravity only, and "
                 "force element 'sun' is not uniform gravity; choose rk4 or the adaptive "
                 "integrator");
  }
}

TEST(FreeBodyBatch, RefusesModelsItCannotStepAndNamesWhy) {
  Model m;
  m.AddBody("a", MassProperties(1.0, Vec3::Zero(), RotationalInertia(1, 2, 3)));
  m.AddBody("rod", MassProperties(1.0, Vec3::Zero(), RotationalInertia(0, 1, 1)));
  const ModelObstacle rod = FreeBodyBatchObstacle(m);
  EXPECT_EQ(rod.why, "body 'rod' has a zero principal moment (a particle or a slender rod)");
  ASSERT_TRUE(rod.element.has_value());
  EXPECT_EQ(rod.element->kind, ErrorElement::Kind::kBody);
  EXPECT_EQ(rod.element->index, 1);
  Model n;
  n.AddBody("a", MassProperties(1.0, Vec3::Zero(), RotationalInertia(1, 2, 3)));
  n.AddForceElement(std::make_shared<CentralGravity>("sun", 1.0, Vec3(5, 0, 0)));
  const ModelObstacle sun = FreeBodyBatchObstacle(n);
  EXPECT_EQ(sun.why, "force element 'sun' is not uniform gravity");
  ASSERT_TRUE(sun.element.has_value());
  EXPECT_EQ(sun.element->kind, ErrorElement::Kind::kForceElement);
  EXPECT_EQ(sun.element->index, 0);
  try {
    FreeBodyBatch batch(n);
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(),
                 "the free-body batch cannot step this model: force element 'sun' is not "
                 "uniform gravity");
  }
}

}  // namespace
}  // namespace chasles
