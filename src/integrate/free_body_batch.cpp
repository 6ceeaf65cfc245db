#include "chasles/integrate/free_body_batch.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>

#include <fmt/format.h>
#include <Eigen/Eigenvalues>

#include "chasles/error.h"
#include "chasles/integrate/parallel.h"
#include "chasles/model/forces.h"
#include "chasles/model/model.h"
#include "chasles/model/state.h"
#include "integrate/internal/compensated.h"
#include "integrate/internal/free_body_run.h"
#include "integrate/internal/ode.h"

// The loop after it has no dependence between iterations (each body's arrays are its own): the
// compilers may vectorise it without checking for overlap. Each compiler has its own spelling.
#if defined(__clang__)
#define CHASLES_INDEPENDENT_ITERATIONS _Pragma("clang loop vectorize(assume_safety)")
#else
#define CHASLES_INDEPENDENT_ITERATIONS _Pragma("GCC ivdep")
#endif

namespace chasles {
namespace {

/// Bodies per tile: a tile is advanced through all the steps of one Advance call before the
/// next, so its 26 state and compensation arrays (13 kB) stay in the first-level cache.
constexpr int kTile = 64;

/// The arrays of one stretch of bodies, restrict-qualified so that the loops vectorise: the 13
/// state coordinates (p, q, v, ω), their compensations c (RK4 only), moments and coefficients.
struct Arrays {
  double* __restrict y[13];
  double* __restrict c[13];
  const double* __restrict I1, * __restrict I2, * __restrict I3;
  const double* __restrict a1, * __restrict a2, * __restrict a3;
};
enum : int { kPx = 0, kVx = 3, kQw = 6, kWx = 10 };

/// y ← y + d with compensation c (Knuth's TwoSum, internal/compensated.h): branch-free, so the
/// loops below vectorise with it.
using internal::CompensatedAdd;

/// a·b = p + e exactly, p = fl(a b) (Dekker's TwoProduct with Veltkamp's splitting, exact without
/// a fused multiply-add, which the baseline x86-64 target does not have; Higham §4.3).
inline double ProductError(double a, double b, double p) {
  constexpr double kSplit = 134217729.0;  // 2^27 + 1
  const double ta = kSplit * a, tb = kSplit * b;
  const double ah = ta - (ta - a), al = a - ah;
  const double bh = tb - (tb - b), bl = b - bh;
  return ((ah * bh - p) + ah * bl + al * bh) + al * bl;
}

/// Body i's compensation c_j: 0 when kFresh (the first step after the compensation starts
/// again: it is written, not read, so it needs no zeroing before).
template <bool kFresh>
inline double Carried(const Arrays& s, int j, int i) {
  return kFresh ? 0.0 : s.c[j][i];
}

/// Translation under uniform gravity, exact: p ← p + h v + ½h² g, v ← v + h g (a quadratic in
/// t; RK4 is exact on it as well, eqs. 8.76-8.78 with F = m g), with compensated updates.
template <bool kFresh>
inline void TranslateCompensated(const Arrays& s, int i, double h, const double hg[3],
                                 const double hhg[3]) {
  for (int j = 0; j < 3; ++j) {
    double cp = Carried<kFresh>(s, kPx + j, i), cv = Carried<kFresh>(s, kVx + j, i);
    CompensatedAdd(s.y[kPx + j][i], h * s.y[kVx + j][i] + hhg[j], cp);
    CompensatedAdd(s.y[kVx + j][i], hg[j], cv);
    s.c[kPx + j][i] = cp, s.c[kVx + j][i] = cv;
  }
}

/// Right-hand side of the rotation: q̇ = ½ q ⊗ (0, ω) and Euler's equations in the principal
/// frame without moment, ω̇₁ = a₁ ω₂ω₃ (cyclic), a₁ = (I₂ − I₃)/I₁ (eqs. 8.79-8.81).
inline void Rhs(const double q[4], const double w[3], double a1, double a2, double a3, double dq[4],
                double dw[3]) {
  dq[0] = 0.5 * (-q[1] * w[0] - q[2] * w[1] - q[3] * w[2]);
  dq[1] = 0.5 * (q[0] * w[0] + q[2] * w[2] - q[3] * w[1]);
  dq[2] = 0.5 * (q[0] * w[1] - q[1] * w[2] + q[3] * w[0]);
  dq[3] = 0.5 * (q[0] * w[2] + q[1] * w[1] - q[2] * w[0]);
  dw[0] = a1 * w[1] * w[2];
  dw[1] = a2 * w[2] * w[0];
  dw[2] = a3 * w[0] * w[1];
}

/// q ← q/|q| (once per step).
inline void Normalize(double q[4]) {
  const double s = 1.0 / std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
  q[0] *= s, q[1] *= s, q[2] *= s, q[3] *= s;
}

/// One RK4 step of the bodies [b, e): y₁ = y₀ + (h/6)(k₁ + 2(k₂ + k₃) + k₄) on (q, ω), the
/// stages as in Rk4Integrator, added with compensation as there, then q renormalised with its
/// compensation carried across (internal/compensated.h, NormalizeCompensated):
/// c ← s (c − q̂ (q̂·c)) + e, s = 1/|q|, q̂ = fl(q s), e the rounding of each q_i s.
template <bool kFresh>
void StepRk4(const Arrays& s, int b, int e, double h, const double hg[3], const double hhg[3]) {
  const double h2 = 0.5 * h, h6 = h / 6.0;
  CHASLES_INDEPENDENT_ITERATIONS
  for (int i = b; i < e; ++i) {
    TranslateCompensated<kFresh>(s, i, h, hg, hhg);
    double q0[4], w0[3], cq[4], cw[3];
    for (int j = 0; j < 4; ++j) q0[j] = s.y[kQw + j][i], cq[j] = Carried<kFresh>(s, kQw + j, i);
    for (int j = 0; j < 3; ++j) w0[j] = s.y[kWx + j][i], cw[j] = Carried<kFresh>(s, kWx + j, i);
    const double a1 = s.a1[i], a2 = s.a2[i], a3 = s.a3[i];
    double k1q[4], k1w[3], k2q[4], k2w[3], k3q[4], k3w[3], k4q[4], k4w[3], q[4], w[3];
    Rhs(q0, w0, a1, a2, a3, k1q, k1w);
    for (int j = 0; j < 4; ++j) q[j] = q0[j] + h2 * k1q[j];
    for (int j = 0; j < 3; ++j) w[j] = w0[j] + h2 * k1w[j];
    Rhs(q, w, a1, a2, a3, k2q, k2w);
    for (int j = 0; j < 4; ++j) q[j] = q0[j] + h2 * k2q[j];
    for (int j = 0; j < 3; ++j) w[j] = w0[j] + h2 * k2w[j];
    Rhs(q, w, a1, a2, a3, k3q, k3w);
    for (int j = 0; j < 4; ++j) q[j] = q0[j] + h * k3q[j];
    for (int j = 0; j < 3; ++j) w[j] = w0[j] + h * k3w[j];
    Rhs(q, w, a1, a2, a3, k4q, k4w);
    for (int j = 0; j < 4; ++j) {
      q[j] = q0[j];
      CompensatedAdd(q[j], h6 * (k1q[j] + 2.0 * (k2q[j] + k3q[j]) + k4q[j]), cq[j]);
    }
    for (int j = 0; j < 3; ++j) {
      w[j] = w0[j];
      CompensatedAdd(w[j], h6 * (k1w[j] + 2.0 * (k2w[j] + k3w[j]) + k4w[j]), cw[j]);
    }
    const double r = 1.0 / std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    double qn[4], err[4];
    for (int j = 0; j < 4; ++j) qn[j] = q[j] * r, err[j] = ProductError(q[j], r, qn[j]);
    const double dot = qn[0] * cq[0] + qn[1] * cq[1] + qn[2] * cq[2] + qn[3] * cq[3];
    for (int j = 0; j < 4; ++j) {
      s.y[kQw + j][i] = qn[j];
      s.c[kQw + j][i] = r * (cq[j] - qn[j] * dot) + err[j];
    }
    for (int j = 0; j < 3; ++j) s.y[kWx + j][i] = w[j], s.c[kWx + j][i] = cw[j];
  }
}

/// The exact flow for a time τ of H_k = L_k²/2I_k alone, with the Cayley angle. L_k, hence
/// ω_k = L_k/I_k, is constant; the body turns about its axis e_k and, since L_W = R_WP L is
/// constant, L turns the other way in P: L̇ = L × ω_k e_k, i.e. for (k, i, j) cyclic
///   L̇_i = ω_k L_j,  L̇_j = −ω_k L_i,   q̇ = ½ q ⊗ (0, ω_k e_k).
/// Over τ the angle is φ = ω_k τ; we take φ = 2 atan(ω_k τ/2) instead (the exact flow of the
/// modified H̃_k = (2/τ) ∫ atan(τ L_k/2I_k) dL_k = H_k + O(τ²), so still a Poisson map that
/// keeps |L| and L_W): with t = tan(φ/2) = ω_k τ/2,
///   cos φ = (1 − t²)/(1 + t²),  sin φ = 2t/(1 + t²),  L_i ← c L_i + s L_j,  L_j ← c L_j − s L_i,
///   q ← q ⊗ (1, t e_k)  (= √(1 + t²) · q ⊗ (cos φ/2, sin φ/2 e_k); the norm is reset once per
///   step).
/// The Cayley angle is odd in τ, so each sub-flow's inverse is the same flow for −τ and the
/// symmetric composition below is second order.
inline void RotateAbout(int k, double tau, double q[4], double L[3], const double invI[3]) {
  const int i = (k + 1) % 3, j = (k + 2) % 3;
  const double t = 0.5 * tau * L[k] * invI[k];
  const double d = 1.0 / (1.0 + t * t);
  const double c = (1.0 - t * t) * d, sn = 2.0 * t * d;
  const double Li = L[i], Lj = L[j];
  L[i] = c * Li + sn * Lj;
  L[j] = c * Lj - sn * Li;
  // q ⊗ (1, t e_k): (w, v) ⊗ (1, t e_k) = (w − t v_k, v + t w e_k + t v × e_k).
  const double w = q[0], v[3] = {q[1], q[2], q[3]};
  q[0] = w - t * v[k];
  q[1 + k] = v[k] + t * w;
  q[1 + i] = v[i] + t * v[j];  // (v × e_k)_i = v_j
  q[1 + j] = v[j] - t * v[i];  // (v × e_k)_j = −v_i
}

/// One splitting step of the bodies [b, e): translation exact, its increments added with
/// compensation (a plain p += h v + ½h²g loses up to half an ulp of p per step, 5e-7 m after 10⁴
/// steps of 1e-3 s at 10⁶ m); rotation by the flows of axis 1 for h/2, axis 2 for h/2, axis 3
/// for h, axis 2 for h/2, axis 1 for h/2 (symmetric, second order), q renormalised once. The
/// rotation is not compensated: |q| and |L| are reset or kept by the map itself.
template <bool kFresh>
void StepSplitting(const Arrays& s, int b, int e, double h, const double hg[3],
                   const double hhg[3]) {
  const double h2 = 0.5 * h;
  CHASLES_INDEPENDENT_ITERATIONS
  for (int i = b; i < e; ++i) {
    TranslateCompensated<kFresh>(s, i, h, hg, hhg);
    const double I[3] = {s.I1[i], s.I2[i], s.I3[i]};
    const double invI[3] = {1.0 / I[0], 1.0 / I[1], 1.0 / I[2]};
    double q[4], L[3];
    for (int j = 0; j < 4; ++j) q[j] = s.y[kQw + j][i];
    for (int j = 0; j < 3; ++j) L[j] = I[j] * s.y[kWx + j][i];
    RotateAbout(0, h2, q, L, invI);
    RotateAbout(1, h2, q, L, invI);
    RotateAbout(2, h, q, L, invI);
    RotateAbout(1, h2, q, L, invI);
    RotateAbout(0, h2, q, L, invI);
    Normalize(q);
    for (int j = 0; j < 4; ++j) s.y[kQw + j][i] = q[j];
    for (int j = 0; j < 3; ++j) s.y[kWx + j][i] = L[j] * invI[j];
  }
}

/// A body's principal moments (I₁, I₂, I₃) [kg·m²] and principal frame P: R_BP's columns the
/// eigenvectors of its inertia (det +1), or P = B when the inertia is diagonal in B.
struct Principal {
  Vec3 moments;
  Quat q_BP = Quat::Identity();
  bool is_B = true;
};

/// PrincipalOf for an inertia I that is not diagonal in B: R_BP's columns its eigenvectors.
Principal RotatedPrincipalOf(const Mat3& I) {
  Eigen::SelfAdjointEigenSolver<Mat3> eig(I);
  Mat3 R_BP = eig.eigenvectors();
  if (R_BP.determinant() < 0.0) R_BP.col(2) = -R_BP.col(2);
  return {eig.eigenvalues(), Quat(R_BP).normalized(), false};
}

inline Principal PrincipalOf(const Body& body) {
  const Mat3& I = body.I_BBcm_B();
  if (I(0, 1) == 0.0 && I(0, 2) == 0.0 && I(1, 2) == 0.0) return {I.diagonal()};
  return RotatedPrincipalOf(I);
}

/// Body `b`'s moments and Euler coefficients a₁ = (I₂ − I₃)/I₁ and cyclic into the arrays.
inline void SetMoments(const Vec3& m, size_t b, double* I1, double* I2, double* I3, double* a1,
                       double* a2, double* a3) {
  I1[b] = m[0], I2[b] = m[1], I3[b] = m[2];
  a1[b] = (m[1] - m[2]) / m[0];
  a2[b] = (m[2] - m[0]) / m[1];
  a3[b] = (m[0] - m[1]) / m[2];
}

/// A body's motion as the 13 coordinates of the arrays (p, v, q_WP, w_WP_P), q_BP null when
/// P = B (no conversion): q_WP = q_WB ⊗ q_BP, w_WP_P = R_BPᵀ w_WB_B.
inline void ToPrincipal(const BodyState& s, const Quat* q_BP, double* const y[13], size_t b) {
  Quat q = s.q_WB;
  Vec3 w = s.w_WB_B;
  if (q_BP != nullptr) {
    q = s.q_WB * *q_BP;
    w = q_BP->conjugate() * s.w_WB_B;
  }
  const double v[13] = {s.p_WBcm.x(),   s.p_WBcm.y(), s.p_WBcm.z(), s.v_WBcm_W.x(), s.v_WBcm_W.y(),
                        s.v_WBcm_W.z(), q.w(),        q.x(),        q.y(),          q.z(),
                        w.x(),          w.y(),        w.z()};
  for (size_t j = 0; j < 13; ++j) y[j][b] = v[j];
}

/// The inverse of ToPrincipal: q_WB = q_WP ⊗ q_BPᵀ, w_WB_B = R_BP w_WP_P.
inline void FromPrincipal(const double* const y[13], size_t b, const Quat* q_BP, BodyState& s) {
  s.p_WBcm = Vec3(y[0][b], y[1][b], y[2][b]);
  s.v_WBcm_W = Vec3(y[3][b], y[4][b], y[5][b]);
  s.q_WB = Quat(y[6][b], y[7][b], y[8][b], y[9][b]);
  s.w_WB_B = Vec3(y[10][b], y[11][b], y[12][b]);
  if (q_BP != nullptr) {
    s.q_WB = s.q_WB * q_BP->conjugate();
    s.w_WB_B = *q_BP * s.w_WB_B;
  }
}

/// The total of the model's UniformGravity elements (FreeBodyBatchObstacle empty).
Vec3 TotalGravity(const Model& model) {
  Vec3 g = Vec3::Zero();
  for (int e = 0; e < model.num_force_elements(); ++e) {
    g += static_cast<const UniformGravity&>(model.force_element(e)).g_W();
  }
  return g;
}

/// The compensation's bookkeeping: whether it belongs to the state, and to which stepper.
struct Compensation {
  bool& valid;
  FreeBodyStepper& stepper;
};

/// The blocks of bodies that `threads` threads take: one per thread, at least a tile each.
int BlockCount(int threads, int n) {
  return std::clamp(threads, 1, std::max(1, n / kTile));
}

/// FreeBodyBatch::Advance on the arrays `s` of n bodies under gravity g_W, the batch's time t
/// and its compensation's bookkeeping `comp`; prepare(b, e) is called for each tile of bodies
/// [b, e) before its first step (by the thread that steps it; in order when BlockCount is 1).
template <class Prepare>
void AdvanceArrays(const Arrays& s, int n, const Vec3& g_W, FreeBodyStepper stepper, double h,
                   long long steps, int threads, Compensation comp, double& t,
                   const Prepare& prepare) {
  if (!(h > 0.0) || !std::isfinite(h)) {
    throw InputError(fmt::format("batch step is {:.6g} s; it must be a positive time step", h));
  }
  if (steps <= 0 || n == 0) return;
  const double hg[3] = {h * g_W.x(), h * g_W.y(), h * g_W.z()};
  const double hh = 0.5 * h * h;
  const double hhg[3] = {hh * g_W.x(), hh * g_W.y(), hh * g_W.z()};
  // The compensation belongs to the stepper that made it (the splitting carries only the
  // translation's): it starts from zero after a Load or a change of stepper, each tile's first
  // step taking it as zero (StepRk4<true>, StepSplitting<true>) and writing it.
  const bool restart = !comp.valid || stepper != comp.stepper;
  comp.valid = true;
  comp.stepper = stepper;
  // Bodies [b, e), tile by tile, each tile through all the steps: every body's arithmetic is
  // the same whatever the tiles and blocks, so the result does not depend on them.
  const auto run = [&](int b, int e) {
    for (int t0 = b; t0 < e; t0 += kTile) {
      const int t1 = std::min(e, t0 + kTile);
      prepare(t0, t1);
      for (long long k = 0; k < steps; ++k) {
        const bool fresh = restart && k == 0;
        if (stepper == FreeBodyStepper::kRk4) {
          (fresh ? StepRk4<true> : StepRk4<false>)(s, t0, t1, h, hg, hhg);
        } else {
          (fresh ? StepSplitting<true> : StepSplitting<false>)(s, t0, t1, h, hg, hhg);
        }
      }
    }
  };
  const int nt = BlockCount(threads, n);
  if (nt == 1) {
    run(0, n);
  } else {
    // nt blocks, taken by as many threads as the system starts (parallel.h).
    const int per = (n + nt - 1) / nt;
    std::atomic<int> next{0};
    RunOnThreads(nt, [&] {
      for (int k; (k = next++) < nt;) run(std::min(n, k * per), std::min(n, (k + 1) * per));
    });
  }
  // The time as a fixed grid would count it: t₀ + k h, one rounding per step.
  for (long long k = 0; k < steps; ++k) t += h;
  // A body whose motion is no longer finite (an overflowing spin): stop with it named.
  for (size_t b = 0; b < static_cast<size_t>(n); ++b) {
    double sum = 0.0;
    for (size_t j = 0; j < 13; ++j) sum += s.y[j][b];
    if (!std::isfinite(sum)) {
      throw InputError(
          fmt::format("body {} of the free-body batch became non-finite at t = {:.9g} s", b, t));
    }
  }
}

}  // namespace

ModelObstacle FreeBodyBatchObstacle(const Model& model) {
  if (model.num_constraints() > 0) return {"the model has constraints", {}};
  if (model.num_contacts() > 0) return {"the model has contacts", {}};
  for (int e = 0; e < model.num_force_elements(); ++e) {
    if (dynamic_cast<const UniformGravity*>(&model.force_element(e)) == nullptr) {
      return {
          fmt::format("force element '{}' is not uniform gravity", model.force_element(e).name()),
          ErrorElement{ErrorElement::Kind::kForceElement, e}};
    }
  }
  for (int b = 0; b < model.num_bodies(); ++b) {
    if (model.body(b).num_zero_moments() > 0) {
      return {fmt::format("body '{}' has a zero principal moment (a particle or a slender rod)",
                          model.body(b).name()),
              ErrorElement{ErrorElement::Kind::kBody, b}};
    }
  }
  return {};
}

FreeBodyBatch::FreeBodyBatch(const Model& model) : n_(model.num_bodies()), g_W_(Vec3::Zero()) {
  const ModelObstacle obstacle = FreeBodyBatchObstacle(model);
  if (!obstacle.empty()) {
    throw InputError(fmt::format("the free-body batch cannot step this model: {}", obstacle.why),
                     obstacle.element);
  }
  g_W_ = TotalGravity(model);
  const auto n = static_cast<size_t>(n_);
  for (auto* v : {&mass_, &I1_, &I2_, &I3_, &a1_, &a2_, &a3_}) v->resize(n);
  for (int j = 0; j < 13; ++j) {
    y_[static_cast<size_t>(j)].assign(n, std::numeric_limits<double>::quiet_NaN());
    c_[static_cast<size_t>(j)].resize(n);  // zeroed by the first Advance
  }
  q_BP_.assign(n, Quat::Identity());
  principal_is_B_.assign(n, 1);
  for (size_t b = 0; b < n; ++b) {
    const Body& body = model.body(static_cast<int>(b));
    mass_[b] = body.mass();
    const Principal p = PrincipalOf(body);
    q_BP_[b] = p.q_BP;
    principal_is_B_[b] = p.is_B ? 1 : 0;
    SetMoments(p.moments, b, I1_.data(), I2_.data(), I3_.data(), a1_.data(), a2_.data(),
               a3_.data());
  }
}

void FreeBodyBatch::Load(const State& state) {
  if (static_cast<int>(state.bodies.size()) != n_) {
    throw UsageError(
        fmt::format("a state of {} bodies loaded into a batch of {}", state.bodies.size(), n_));
  }
  t_ = state.t;
  // The compensation belongs to the state it was accumulated with: start it again.
  compensation_valid_ = false;
  double* y[13];
  for (size_t j = 0; j < 13; ++j) y[j] = y_[j].data();
  for (size_t b = 0; b < static_cast<size_t>(n_); ++b) {
    ToPrincipal(state.bodies[b], principal_is_B_[b] ? nullptr : &q_BP_[b], y, b);
  }
}

void FreeBodyBatch::Store(State& state) const {
  state.t = t_;
  state.bodies.resize(static_cast<size_t>(n_));
  const double* y[13];
  for (size_t j = 0; j < 13; ++j) y[j] = y_[j].data();
  for (size_t b = 0; b < static_cast<size_t>(n_); ++b) {
    FromPrincipal(y, b, principal_is_B_[b] ? nullptr : &q_BP_[b], state.bodies[b]);
  }
}

void FreeBodyBatch::Advance(FreeBodyStepper stepper, double h, long long steps, int threads) {
  Arrays s{};
  for (size_t j = 0; j < 13; ++j) s.y[j] = y_[j].data(), s.c[j] = c_[j].data();
  s.I1 = I1_.data(), s.I2 = I2_.data(), s.I3 = I3_.data();
  s.a1 = a1_.data(), s.a2 = a2_.data(), s.a3 = a3_.data();
  AdvanceArrays(s, n_, g_W_, stepper, h, steps, threads,
                {compensation_valid_, compensated_stepper_}, t_, [](int, int) {});
}

// ---------------------------------------------------------------------------------------
namespace internal {

namespace {
/// FreeBodyRunBatch's columns, n each: 13 coordinates, 13 compensations, I₁, I₂, I₃, a₁, a₂,
/// a₃, m, and q_BP's coefficients (x, y, z, w; written only for a body whose principal frame
/// is not B).
constexpr size_t kRunColumns = 37;
enum : size_t { kRunC = 13, kRunI1 = 26, kRunA1 = 29, kRunMass = 32, kRunQ = 33 };
}  // namespace

FreeBodyRunBatch::FreeBodyRunBatch(const Model& model, const State& initial)
    : model_(model),
      initial_(initial),
      n_(model.num_bodies()),
      g_W_(TotalGravity(model)),
      t_(initial.t),
      // new T[]: not filled; every entry is written before it is read.
      columns_(new double[kRunColumns * static_cast<size_t>(model.num_bodies())]),
      principal_is_B_(new bool[static_cast<size_t>(model.num_bodies())]) {}

double* FreeBodyRunBatch::Column(size_t j) const {
  return columns_.get() + j * static_cast<size_t>(n_);
}

void FreeBodyRunBatch::LoadBodies(int b, int e) {
  double* y[13];
  for (size_t j = 0; j < 13; ++j) y[j] = Column(j);
  double *I1 = Column(kRunI1), *I2 = Column(kRunI1 + 1), *I3 = Column(kRunI1 + 2);
  double* mass = Column(kRunMass);
  // The ledger's sums, in the body order (the bodies come here in order), in locals that the
  // stores into the arrays cannot alias.
  double M = mass_;
  Vec3 S = sum_mp_, P = sum_mv_;
  for (auto i = static_cast<size_t>(b); i < static_cast<size_t>(e); ++i) {
    const Body& body = model_.body(static_cast<int>(i));
    const Principal p = PrincipalOf(body);
    I1[i] = p.moments[0], I2[i] = p.moments[1], I3[i] = p.moments[2];
    principal_is_B_[i] = p.is_B;
    if (!p.is_B) {
      for (size_t j = 0; j < 4; ++j)
        Column(kRunQ + j)[i] = p.q_BP.coeffs()[static_cast<Eigen::Index>(j)];
    }
    const BodyState& s = initial_.bodies[i];
    ToPrincipal(s, p.is_B ? nullptr : &p.q_BP, y, i);
    const double m = body.mass();
    mass[i] = m;
    M += m;
    S += m * s.p_WBcm;
    P += m * s.v_WBcm_W;
  }
  mass_ = M;
  sum_mp_ = S;
  sum_mv_ = P;
  // The Euler coefficients as SetMoments takes them, in a loop of their own that vectorises.
  double *a1 = Column(kRunA1), *a2 = Column(kRunA1 + 1), *a3 = Column(kRunA1 + 2);
  CHASLES_INDEPENDENT_ITERATIONS
  for (int i = b; i < e; ++i) {
    a1[i] = (I2[i] - I3[i]) / I1[i];
    a2[i] = (I3[i] - I1[i]) / I2[i];
    a3[i] = (I1[i] - I2[i]) / I3[i];
  }
}

void FreeBodyRunBatch::Load() {
  if (!loaded_) LoadBodies(0, n_);
  loaded_ = true;
}

void FreeBodyRunBatch::Advance(FreeBodyStepper stepper, double h, long long steps, int threads) {
  Arrays s{};
  for (size_t j = 0; j < 13; ++j) s.y[j] = Column(j), s.c[j] = Column(kRunC + j);
  s.I1 = Column(kRunI1), s.I2 = Column(kRunI1 + 1), s.I3 = Column(kRunI1 + 2);
  s.a1 = Column(kRunA1), s.a2 = Column(kRunA1 + 1), s.a3 = Column(kRunA1 + 2);
  // One thread takes the tiles in order: each is loaded as its first step reaches it, while it
  // is in cache. Otherwise all are loaded first, in order (the ledger's sums).
  const bool by_tile = !loaded_ && steps > 0 && BlockCount(threads, n_) == 1;
  if (!by_tile) Load();
  AdvanceArrays(s, n_, g_W_, stepper, h, steps, threads,
                {compensation_valid_, compensated_stepper_}, t_, [&](int b, int e) {
                  if (by_tile) LoadBodies(b, e);
                });
  loaded_ = true;
}

void FreeBodyRunBatch::Store(State& state, bool sums) {
  Load();
  const auto n = static_cast<size_t>(n_);
  const double* y[13];
  for (size_t j = 0; j < 13; ++j) y[j] = Column(j);
  const double* mass = Column(kRunMass);
  // A state without bodies gets them here, each written once (a resize would fill them first).
  const bool fresh = state.bodies.size() != n;
  if (fresh) {
    state.bodies.clear();
    state.bodies.reserve(n);
  }
  Vec3 S = Vec3::Zero(), P = Vec3::Zero();
  for (size_t b = 0; b < n; ++b) {
    Quat q_BP;
    if (!principal_is_B_[b]) {
      for (size_t j = 0; j < 4; ++j)
        q_BP.coeffs()[static_cast<Eigen::Index>(j)] = Column(kRunQ + j)[b];
    }
    BodyState s;
    FromPrincipal(y, b, principal_is_B_[b] ? nullptr : &q_BP, s);
    if (sums) {
      S += mass[b] * s.p_WBcm;
      P += mass[b] * s.v_WBcm_W;
    }
    if (fresh) {
      state.bodies.push_back(s);
    } else {
      state.bodies[b] = s;
    }
  }
  if (sums) sum_mp_ = S, sum_mv_ = P;
}

}  // namespace internal

FreeBodyBatchIntegrator::FreeBodyBatchIntegrator(const Model& model, FreeBodyStepper stepper)
    : model_(model), stepper_(stepper), batch_(model) {
  for (int e = 0; e < model.num_force_elements(); ++e) {
    element_g_W_.push_back(static_cast<const UniformGravity&>(model.force_element(e)).g_W());
  }
  for (int b = 0; b < model.num_bodies(); ++b) mass_ += model.body(b).mass();
  stats_.free_body_batch = true;
}

void FreeBodyBatchIntegrator::Step(State& state, double h) {
  if (!(h > 0.0) || !std::isfinite(h)) {
    throw InputError(fmt::format("the step is {:.6g} s; it must be a positive time step", h));
  }
  // The force ledger of each gravity element g_e, exact for p(τ) = p₀ + v₀τ + ½gτ² (g the
  // total; RK4 integrates these polynomials exactly too, and the splitting's translation is
  // this closed form), with S = Σ m p₀, P = Σ m v₀, M = Σ m:
  //   work       ∫ Σ m g_e·v dτ = g_e·(h P + ½h² M g),
  //   impulse    ∫ Σ m g_e dτ = h M g_e,
  //   angular    ∫ Σ m p × g_e dτ = (h S + ½h² P + ⅙h³ M g) × g_e  (about Wo).
  Vec3 S = Vec3::Zero(), P = Vec3::Zero();
  for (int b = 0; b < model_.num_bodies(); ++b) {
    const BodyState& s = state.bodies[static_cast<size_t>(b)];
    S += model_.body(b).mass() * s.p_WBcm;
    P += model_.body(b).mass() * s.v_WBcm_W;
  }
  const Vec3& g = batch_.g_W();
  const Vec3 dS = h * P + (0.5 * h * h * mass_) * g;
  const Vec3 S_int = h * S + (0.5 * h * h) * P + (h * h * h / 6.0 * mass_) * g;
  // The time as Rk4Integrator adds it: compensated, carried while the grid hands back the time
  // this step left.
  if (state.t != t_end_) c_t_ = 0.0;
  double t_new = state.t;
  internal::CompensatedAdd(t_new, h, c_t_);
  // The batch keeps its principal-frame state between steps while it is handed back the state
  // it produced (the grid changes only t), so a rotated body is converted once, not per step.
  bool same = carried_;
  for (size_t b = 0; same && b < state.bodies.size(); ++b) {
    const BodyState &x = state.bodies[b], &y = last_[b];
    same = x.p_WBcm == y.p_WBcm && x.q_WB.coeffs() == y.q_WB.coeffs() && x.v_WBcm_W == y.v_WBcm_W &&
           x.w_WB_B == y.w_WB_B;
  }
  if (!same) batch_.Load(state);
  batch_.Advance(stepper_, h, 1);
  batch_.Store(state);
  last_ = state.bodies;
  carried_ = true;
  state.t = t_new;
  t_end_ = t_new;
  for (size_t e = 0; e < element_g_W_.size(); ++e) {
    ForceIntegrals& fi = state.force_integrals[e];
    const Vec3& ge = element_g_W_[e];
    fi.work += ge.dot(dS);
    fi.linear_impulse_W += (h * mass_) * ge;
    fi.angular_impulse_Wo_W += S_int.cross(ge);
  }
  internal::CheckFiniteState(model_, state);
  ++stats_.steps;
  stats_.function_evaluations += stepper_ == FreeBodyStepper::kRk4 ? 4 : 1;
}

}  // namespace chasles
