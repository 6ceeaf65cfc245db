#include "chasles/dynamics/impact.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Core>
#include <Eigen/QR>

#include "chasles/dynamics/constraint_solve.h"
#include "chasles/dynamics/lcp.h"
#include "chasles/dynamics/newton_euler.h"
#include "dynamics/internal/contact_geometry.h"

namespace chasles {
namespace {

using Eigen::Matrix2d;
using Eigen::MatrixXd;
using Eigen::Vector2d;
using Eigen::VectorXd;
using internal::ContactPointGeometry;

constexpr double kInf = std::numeric_limits<double>::infinity();

enum class Phase { kCompression, kRestitution };

// One touching point along the impulse. Contact coordinates: rows 3i (n), 3i+1 (t1), 3i+2 (t2).
struct PathPoint {
  int point = -1;
  double mu_s = 0.0, mu_k = 0.0, e = 0.0;
  RestitutionLaw law = RestitutionLaw::kEnergetic;
  bool sticking = false;
  // Slip direction (t1, t2) held when the slip is zero (after a stick-to-slip transition).
  Vector2d s_ref = Vector2d::Zero();
  double v_n0 = 0.0;  // v_n⁻
  // End of compression: normal impulse and work of the normal impulse.
  double P_c = 0.0, W_c = 0.0;
  bool done = false;  // restitution finished (or nothing to restore)
};

// Rates along the common impulse parameter τ: normal impulse rates ρ and dP/dτ.
struct Rates {
  VectorXd rho;        // per point
  VectorXd dP;         // 3 per point
  double sigma = 0.0;  // compression: the remaining plastic impulse ΣQ
  bool solved = true;
  int violation = -1;  // sticking point needing more than mu_s (from Stick())
  Vector2d slide_dir = Vector2d::Zero();
};

// Unit ŝ with (a M + λ I) ŝ = b, λ > 0 (a M SPD 2×2, |M⁻¹ b| / a > 1): the slip direction in
// which the slip velocity grows along itself, dv_t/dτ = b - a M ŝ = λ ŝ (Stronge 2000, 5.3).
// |(a M + λ I)⁻¹ b| decreases in λ from > 1 at 0 to <= 1 at |b|: bisection.
Vector2d SlipOutOfStick(const Matrix2d& M, double a, const Vector2d& b) {
  if (!(a > 0.0) || b.norm() == 0.0) return b.norm() > 0.0 ? Vector2d(b.normalized()) : b;
  double lo = 0.0, hi = b.norm();
  for (int it = 0; it < 200 && hi - lo > 1e-16 * b.norm(); ++it) {
    const double mid = 0.5 * (lo + hi);
    const Vector2d s = (a * M + mid * Matrix2d::Identity()).partialPivLu().solve(b);
    (s.norm() > 1.0 ? lo : hi) = mid;
  }
  return (a * M + hi * Matrix2d::Identity()).partialPivLu().solve(b).normalized();
}

class ImpulsePath {
 public:
  ImpulsePath(const MatrixXd& K, const VectorXd& v0, std::vector<PathPoint> pts, bool friction)
      : K_(K), v0_(v0), pts_(std::move(pts)), friction_(friction) {
    const auto n = static_cast<Eigen::Index>(pts_.size());
    P_ = VectorXd::Zero(3 * n);
    k_scale_ = K.diagonal().maxCoeff();
    W_ = VectorXd::Zero(n);
    for (Eigen::Index i = 0; i < n; ++i) {
      PathPoint& p = pts_[static_cast<size_t>(i)];
      if (!friction_) p.mu_s = p.mu_k = 0.0;
      v_scale_ = std::max({v_scale_, -p.v_n0, v0.segment<2>(3 * i + 1).norm()});
      if (p.v_n0 < 0.0) p_scale_ = std::max(p_scale_, -p.v_n0 / K(3 * i, 3 * i));
    }
    // Slipping points slide, the others stick (frictionless ones slide without friction).
    for (Eigen::Index i = 0; i < n; ++i) {
      PathPoint& p = pts_[static_cast<size_t>(i)];
      p.sticking = p.mu_s > 0.0 && v0.segment<2>(3 * i + 1).norm() <= tiny_v();
    }
  }

  // Runs compression then restitution; false when the path could not be completed.
  bool Run() {
    for (steps_ = 0; steps_ < kMaxSteps; ++steps_) {
      if (!PrepareStep()) return false;
      if (phase_ == Phase::kRestitution && AllDone()) return true;
      if (!Step()) return false;
    }
    return false;
  }

  const VectorXd& P() const { return P_; }
  const VectorXd& W() const { return W_; }
  const std::vector<PathPoint>& points() const { return pts_; }
  int steps() const { return steps_; }

 private:
  static constexpr int kMaxSteps = 2000;
  static constexpr double kSnap = 1e-13;  // relative residual taken as an event reached
  // Local error per step of the curved pieces, relative to the impulse scale (the estimate is
  // RK4's; the step taken is the extrapolated fifth-order one, much more accurate).
  static constexpr double kStepTol = 1e-9;

  // S⁺ R, rank decided against the scale of K (a tangential block the joints remove entirely
  // is round-off, not a stiff direction).
  MatrixXd PseudoSolve(const MatrixXd& S, const MatrixXd& R) const {
    const double s_max = S.cwiseAbs().maxCoeff();
    if (!(s_max > 1e-12 * k_scale_)) return MatrixXd::Zero(S.cols(), R.cols());
    Eigen::CompleteOrthogonalDecomposition<MatrixXd> cod;
    cod.setThreshold(1e-12 * k_scale_ / s_max);
    cod.compute(S);
    return cod.solve(R);
  }

  // A slip this small counts as stopped: near zero the slip direction of a 3-D slip turns as
  // fast as 1/|v_t|, and following it further costs steps without changing the impulse (the
  // friction impulse changes by at most mu_k times the normal impulse over that stretch,
  // which is of the order of this slip over K).
  double stick_v() const { return 1e-9 * std::max(v_scale_, 1e-300); }
  double tiny_v() const { return kSnap * std::max(v_scale_, 1e-300); }
  Vector2d Slip(const VectorXd& v, Eigen::Index i) const { return v.segment<2>(3 * i + 1); }

  // Restitution target reached (the law's end condition) at point i.
  bool TargetReached(Eigen::Index i, const VectorXd& v) const {
    const PathPoint& p = pts_[static_cast<size_t>(i)];
    switch (p.law) {
      case RestitutionLaw::kNewton:  // v_n⁺ = -e v_n⁻
        return v[3 * i] >= -p.e * std::min(p.v_n0, 0.0) - tiny_v();
      case RestitutionLaw::kPoisson:  // P_n = (1 + e) P_c
        return P_[3 * i] >= (1.0 + p.e) * p.P_c - kSnap * p_scale_;
      case RestitutionLaw::kEnergetic:  // W_n = (1 - e²) W_c (restitution work e² |W_c|)
        return W_[i] >= (1.0 - p.e * p.e) * p.W_c - kSnap * p_scale_ * v_scale_;
    }
    return true;
  }

  bool AllDone() const {
    return std::all_of(pts_.begin(), pts_.end(), [](const PathPoint& p) { return p.done; });
  }

  // Mode and phase bookkeeping at the start of a step.
  bool PrepareStep() {
    const VectorXd v = v0_ + K_ * P_;
    const auto n = static_cast<Eigen::Index>(pts_.size());
    // A sliding point whose slip has reached zero sticks (Stick() may release it again).
    for (Eigen::Index i = 0; i < n; ++i) {
      PathPoint& p = pts_[static_cast<size_t>(i)];
      if (!p.sticking && p.mu_s > 0.0 && Slip(v, i).norm() <= stick_v() &&
          p.s_ref.squaredNorm() == 0.0) {
        p.sticking = true;
      }
    }
    if (phase_ == Phase::kCompression) {
      Rates r = Eval(v, Phase::kCompression, VectorXd());
      if (!r.solved) return false;
      if (r.sigma <= kSnap * p_scale_) {
        // End of compression (v_n >= 0 at every point): Routh's P_c and W_c per point.
        phase_ = Phase::kRestitution;
        for (Eigen::Index i = 0; i < n; ++i) {
          PathPoint& p = pts_[static_cast<size_t>(i)];
          p.P_c = P_[3 * i];
          p.W_c = std::min(W_[i], 0.0);
        }
      }
    }
    if (phase_ == Phase::kRestitution) {
      for (Eigen::Index i = 0; i < n; ++i) {
        PathPoint& p = pts_[static_cast<size_t>(i)];
        if (!p.done && (p.e * p.P_c <= 0.0 || TargetReached(i, v))) p.done = true;
      }
    }
    return true;
  }

  // Normal impulse rates ρ and dP/dτ at velocities v, the modes frozen. Compression: ρ is the
  // unit direction of the plastic impulse Q (0 <= Q ⟂ v_n + A Q >= 0 over the points not
  // moving apart). Restitution: the unfinished points drive with fixed shares of e_i P_c,i,
  // the others (not moving apart) take what keeps them from approaching (an LCP).
  // `s0` (2 per point) holds the slip directions of the step's start (a slip that crosses
  // zero inside a stage keeps it).
  Rates Eval(const VectorXd& v, Phase phase, const VectorXd& s0) const {
    const auto n = static_cast<Eigen::Index>(pts_.size());
    // Force directions: column i = n_i - mu_k ŝ_i (sliding); tangent columns of sticking points.
    std::vector<Eigen::Index> stick;
    MatrixXd C = MatrixXd::Zero(3 * n, n);
    for (Eigen::Index i = 0; i < n; ++i) {
      const PathPoint& p = pts_[static_cast<size_t>(i)];
      C(3 * i, i) = 1.0;
      if (p.sticking) {
        stick.push_back(i);
        continue;
      }
      const Vector2d s = SlipDirectionAt(v, i, s0);
      C.block<2, 1>(3 * i + 1, i) = -p.mu_k * s;
    }
    const auto m = static_cast<Eigen::Index>(stick.size());
    MatrixXd T = MatrixXd::Zero(3 * n, 2 * m);
    for (Eigen::Index j = 0; j < m; ++j) {
      T(3 * stick[static_cast<size_t>(j)] + 1, 2 * j) = 1.0;
      T(3 * stick[static_cast<size_t>(j)] + 2, 2 * j + 1) = 1.0;
    }
    // Sticking: Tᵀ K (C ρ + T x) = 0  =>  x = X ρ, X = -(Tᵀ K T)⁺ Tᵀ K C; dP = (C + T X) ρ.
    MatrixXd X = MatrixXd::Zero(2 * m, n);
    if (m > 0) {
      X = -PseudoSolve(T.transpose() * K_ * T, T.transpose() * K_ * C);
    }
    const MatrixXd D = C + T * X;
    const MatrixXd KD = K_ * D;
    MatrixXd A(n, n);
    for (Eigen::Index i = 0; i < n; ++i) A.row(i) = KD.row(3 * i);
    Rates r;
    r.rho = VectorXd::Zero(n);
    // Points taking part in the LCP: not moving apart.
    std::vector<Eigen::Index> lcp, drive;
    for (Eigen::Index i = 0; i < n; ++i) {
      const PathPoint& p = pts_[static_cast<size_t>(i)];
      if (phase == Phase::kRestitution && !p.done) {
        drive.push_back(i);
      } else if (v[3 * i] <= tiny_v()) {
        lcp.push_back(i);
      }
    }
    const auto nl = static_cast<Eigen::Index>(lcp.size());
    MatrixXd All(nl, nl);
    VectorXd q(nl);
    for (Eigen::Index a = 0; a < nl; ++a) {
      for (Eigen::Index b = 0; b < nl; ++b) All(a, b) = A(lcp[size_t(a)], lcp[size_t(b)]);
    }
    if (phase == Phase::kCompression) {
      for (Eigen::Index a = 0; a < nl; ++a) q[a] = std::min(v[3 * lcp[size_t(a)]], 0.0);
      if (nl > 0) {
        const LcpResult res = SolveLcpOrFrictionless(All, q, lcp);
        if (!res.solved) return r.solved = false, r;
        for (Eigen::Index a = 0; a < nl; ++a) r.rho[lcp[size_t(a)]] = std::max(res.z[a], 0.0);
      }
      r.sigma = r.rho.sum();
      if (r.sigma > 0.0) r.rho /= r.sigma;
    } else {
      double wsum = 0.0;
      for (const Eigen::Index i : drive) {
        const PathPoint& p = pts_[static_cast<size_t>(i)];
        r.rho[i] = p.e * p.P_c;
        wsum += r.rho[i];
      }
      if (wsum > 0.0) r.rho /= wsum;
      if (nl > 0) {
        for (Eigen::Index a = 0; a < nl; ++a) q[a] = A.row(lcp[size_t(a)]).dot(r.rho);
        const LcpResult res = SolveLcpOrFrictionless(All, q, lcp);
        if (!res.solved) return r.solved = false, r;
        for (Eigen::Index a = 0; a < nl; ++a) r.rho[lcp[size_t(a)]] = std::max(res.z[a], 0.0);
      }
    }
    r.dP = D * r.rho;
    // Friction check of the sticking points: |x_j| <= mu_s ρ_j; the worst excess slides.
    double worst = 0.0;
    for (Eigen::Index j = 0; j < m; ++j) {
      const Eigen::Index i = stick[static_cast<size_t>(j)];
      const PathPoint& p = pts_[static_cast<size_t>(i)];
      const Vector2d x = X.block(2 * j, 0, 2, n) * r.rho;
      const double excess = x.norm() - p.mu_s * r.rho[i];
      if (excess > 1e-12 * std::max(x.norm(), r.rho[i]) && excess > worst) {
        worst = excess, r.violation = static_cast<int>(i);
        // Slip rate without the point's own friction: b = dv_t + K_tt x = K_tt x (dv_t = 0).
        const Matrix2d Ktt = K_.block<2, 2>(3 * i + 1, 3 * i + 1);
        r.slide_dir = SlipOutOfStick(Ktt, p.mu_k * r.rho[i], Vector2d(-Ktt * x));
      }
    }
    return r;
  }

  // Lemke's method may find no solution when sliding friction makes A unsymmetric (a
  // Painlevé-type case); the rates are then taken from the frictionless normal block of K,
  // positive semi-definite, which Lemke always solves. The rates stay >= 0 and act only at
  // points not moving apart, so the energy argument of docs/contact.md still holds.
  LcpResult SolveLcpOrFrictionless(const MatrixXd& A, const VectorXd& q,
                                   const std::vector<Eigen::Index>& pts) const {
    LcpResult res = SolveLcp(A, q);
    if (res.solved) return res;
    const auto nl = static_cast<Eigen::Index>(pts.size());
    MatrixXd Kn(nl, nl);
    for (Eigen::Index a = 0; a < nl; ++a) {
      for (Eigen::Index b = 0; b < nl; ++b) Kn(a, b) = K_(3 * pts[size_t(a)], 3 * pts[size_t(b)]);
    }
    return SolveLcp(Kn, q);
  }

  Vector2d SlipDirectionAt(const VectorXd& v, Eigen::Index i, const VectorXd& s0) const {
    const Vector2d vt = Slip(v, i);
    const PathPoint& p = pts_[static_cast<size_t>(i)];
    const Vector2d ref = s0.size() > 0 ? Vector2d(s0.segment<2>(2 * i)) : p.s_ref;
    const double m = vt.norm();
    if (m > tiny_v() && (ref.squaredNorm() == 0.0 || vt.dot(ref) > 0.0)) return vt / m;
    return ref.squaredNorm() > 0.0 ? ref : Vector2d::Zero();
  }

  // One step: rates (switching over-loaded sticking points to sliding), the largest step to
  // the next event (linear prediction: exact on the straight pieces of a planar impact), RK4
  // with step doubling for the curved pieces of a 3-D slip.
  bool Step() {
    const auto n = static_cast<Eigen::Index>(pts_.size());
    VectorXd v = v0_ + K_ * P_;
    Rates r;
    for (int guard = 0;; ++guard) {
      r = Eval(v, phase_, VectorXd());
      if (!r.solved || guard > 2 * static_cast<int>(n) + 2) return false;
      if (r.violation < 0) break;
      PathPoint& p = pts_[static_cast<size_t>(r.violation)];
      p.sticking = false;
      p.s_ref = r.slide_dir;
    }
    // Slip directions of the step's start.
    VectorXd s0 = VectorXd::Zero(2 * n);
    for (Eigen::Index i = 0; i < n; ++i) {
      if (!pts_[static_cast<size_t>(i)].sticking) s0.segment<2>(2 * i) = SlipDirectionAt(v, i, {});
    }
    for (Eigen::Index i = 0; i < n; ++i) {
      // A slip grown from zero along s_ref no longer needs it.
      PathPoint& p = pts_[static_cast<size_t>(i)];
      if (Slip(v, i).norm() > tiny_v()) p.s_ref.setZero();
    }
    const VectorXd dv = K_ * r.dP;
    double h = phase_ == Phase::kCompression ? r.sigma : kInf;
    for (Eigen::Index i = 0; i < n; ++i) {
      const PathPoint& p = pts_[static_cast<size_t>(i)];
      const double vn = v[3 * i], an = dv[3 * i], rho = r.rho[i];
      // Slip reaching zero.
      if (!p.sticking) {
        const Vector2d vt = Slip(v, i);
        const double a = s0.segment<2>(2 * i).dot(dv.segment<2>(3 * i + 1));
        if (vt.norm() > stick_v() && a < 0.0) h = std::min(h, vt.norm() / -a);
      }
      // A point moving apart coming back to v_n = 0.
      const bool driving = phase_ == Phase::kRestitution && !p.done;
      if (!driving && vn > tiny_v() && an < 0.0) h = std::min(h, vn / -an);
      if (!driving) continue;
      // The restitution law's end.
      switch (p.law) {
        case RestitutionLaw::kNewton: {
          const double target = -p.e * std::min(p.v_n0, 0.0);
          if (an > 0.0) h = std::min(h, (target - vn) / an);
          break;
        }
        case RestitutionLaw::kPoisson:
          if (rho > 0.0) h = std::min(h, ((1.0 + p.e) * p.P_c - P_[3 * i]) / rho);
          break;
        case RestitutionLaw::kEnergetic: {
          // W(h) = W + ρ (v_n h + ½ a_n h²) = (1 - e²) W_c: the smallest positive root.
          const double d = ((1.0 - p.e * p.e) * p.W_c - W_[i]) / std::max(rho, 1e-300);
          const double disc = vn * vn + 2.0 * an * d;
          if (rho > 0.0 && disc >= 0.0) {
            const double den = vn + std::sqrt(disc);
            if (den > 0.0) h = std::min(h, 2.0 * d / den);
          }
          break;
        }
      }
    }
    h = std::min(h, h_acc_);
    if (!(h < kInf)) h = p_scale_;
    h = std::max(h, 0.0);
    // Accuracy: step doubling of RK4 (exact, error 0, on straight pieces) with Richardson
    // extrapolation.
    for (int tries = 0; tries < 60; ++tries) {
      VectorXd P1 = P_, W1 = W_, P2 = P_, W2 = W_;
      const bool ok1 = Rk4(P1, W1, h, s0, r.rho);
      const bool ok2 = Rk4(P2, W2, 0.5 * h, s0, r.rho) && Rk4(P2, W2, 0.5 * h, s0, r.rho);
      if (!ok1 || !ok2) return false;
      const double err = (P1 - P2).cwiseAbs().maxCoeff() / std::max(p_scale_, 1e-300);
      if (err <= kStepTol || h <= 1e-15 * p_scale_) {
        // Richardson extrapolation of the two RK4 answers (fifth order).
        P_ = P2 + (P2 - P1) / 15.0, W_ = W2 + (W2 - W1) / 15.0;
        h_acc_ = err > 0.0 ? std::min(4.0 * h, 0.9 * h * std::pow(kStepTol / err, 0.2)) : kInf;
        h_acc_ = std::max(h_acc_, 1e-12 * p_scale_);
        return true;
      }
      h *= std::max(0.2, 0.9 * std::pow(kStepTol / err, 0.2));
    }
    return false;
  }

  // One RK4 step of dP/dτ, dW_i/dτ = v_n,i ρ_i with the modes frozen.
  bool Rk4(VectorXd& P, VectorXd& W, double h, const VectorXd& s0, const VectorXd& rho0) const {
    const auto n = static_cast<Eigen::Index>(pts_.size());
    auto f = [&](const VectorXd& Pc, VectorXd& dP, VectorXd& dW) {
      const VectorXd v = v0_ + K_ * Pc;
      Rates r = Eval(v, phase_, s0);
      if (!r.solved) return false;
      // At the very end of compression Q vanishes and its direction is undefined: keep the
      // step's start direction.
      if (phase_ == Phase::kCompression && !(r.sigma > 1e-9 * std::max(p_scale_, 1e-300))) {
        r.rho = rho0;
        r.dP = DirectionsFor(v, s0, rho0);
      }
      dP = r.dP;
      dW.resize(n);
      for (Eigen::Index i = 0; i < n; ++i) dW[i] = v[3 * i] * r.rho[i];
      return true;
    };
    VectorXd k1, k2, k3, k4, l1, l2, l3, l4;
    if (!f(P, k1, l1) || !f(P + 0.5 * h * k1, k2, l2) || !f(P + 0.5 * h * k2, k3, l3) ||
        !f(P + h * k3, k4, l4)) {
      return false;
    }
    P += h / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
    W += h / 6.0 * (l1 + 2.0 * l2 + 2.0 * l3 + l4);
    return true;
  }

  // dP for given normal rates (used only when the compression LCP has run out).
  VectorXd DirectionsFor(const VectorXd& v, const VectorXd& s0, const VectorXd& rho) const {
    // Same construction as Eval with ρ given.
    const auto n = static_cast<Eigen::Index>(pts_.size());
    VectorXd dP = VectorXd::Zero(3 * n);
    std::vector<Eigen::Index> stick;
    for (Eigen::Index i = 0; i < n; ++i) {
      const PathPoint& p = pts_[static_cast<size_t>(i)];
      dP[3 * i] = rho[i];
      if (p.sticking) {
        stick.push_back(i);
      } else {
        dP.segment<2>(3 * i + 1) = -p.mu_k * rho[i] * SlipDirectionAt(v, i, s0);
      }
    }
    if (!stick.empty()) {
      const auto m = static_cast<Eigen::Index>(stick.size());
      MatrixXd T = MatrixXd::Zero(3 * n, 2 * m);
      for (Eigen::Index j = 0; j < m; ++j) {
        T(3 * stick[static_cast<size_t>(j)] + 1, 2 * j) = 1.0;
        T(3 * stick[static_cast<size_t>(j)] + 2, 2 * j + 1) = 1.0;
      }
      dP += T * VectorXd(-PseudoSolve(T.transpose() * K_ * T, T.transpose() * K_ * dP));
    }
    return dP;
  }

  const MatrixXd& K_;
  const VectorXd& v0_;
  std::vector<PathPoint> pts_;
  bool friction_;
  VectorXd P_, W_;
  Phase phase_ = Phase::kCompression;
  double v_scale_ = 0.0, p_scale_ = 0.0;
  double k_scale_ = 0.0;  // largest diagonal entry of K
  double h_acc_ = kInf;
  int steps_ = 0;
};

ImpactResult ImpactsImpl(const Model& model, State& state, const ContactTolerances& tol,
                         int plastic_point) {
  ImpactResult res;
  const int np = model.num_contact_points();
  if (state.contacts.size() != static_cast<size_t>(np)) {
    state.contacts.assign(static_cast<size_t>(np), ContactPointState{});
  }
  Data data = MakeData(model);
  CalcKinematics(model, state, data);
  const int ncr = model.num_constraint_rows();
  if (model.num_constraints() > 0) CalcConstraintRows(model, state, data);
  res.kinetic_energy_before = res.kinetic_energy_after = internal::KineticEnergy(model, state);
  // Touching points not moving apart take part; at least one must approach.
  std::vector<ContactPointGeometry> geo;
  std::vector<PathPoint> pts;
  bool any = false;
  for (int p = 0; p < np; ++p) {
    const ContactPointGeometry g = internal::CalcContactPointGeometry(model, state, data, p);
    if (g.gap > tol.gap || g.v_n > tol.resting_speed) continue;
    if (g.v_n < -tol.resting_speed) any = true;
    const Contact& con = model.contact(model.contact_of_point(p));
    PathPoint pp;
    pp.point = p;
    pp.mu_s = con.mu_s();
    pp.mu_k = con.mu_k();
    pp.e = p == plastic_point ? 0.0 : con.restitution();
    pp.law = con.restitution_law();
    pp.v_n0 = g.v_n;
    geo.push_back(g);
    pts.push_back(pp);
  }
  if (!any) return res;
  // Contact rows J (n, t1, t2 per point) and the constrained inverse mass applied to Jᵀ:
  //   Y = M_c⁻¹ Jᵀ = M⁻¹Jᵀ - M⁻¹Gᵀ (G M⁻¹ Gᵀ)⁺ G M⁻¹ Jᵀ   (G: the constraint rows),
  // the velocity change of an impulse P with the joints' reaction impulses eliminated;
  // K = J Y is the Delassus (collision) matrix.
  const int nb = model.num_bodies();
  const auto n = static_cast<Eigen::Index>(pts.size());
  MatrixXd J = MatrixXd::Zero(3 * n, 6 * nb);
  for (Eigen::Index i = 0; i < n; ++i) {
    const ContactPointGeometry& g = geo[static_cast<size_t>(i)];
    g.SetRow(g.n, J.row(3 * i));
    g.SetRow(g.t1, J.row(3 * i + 1));
    g.SetRow(g.t2, J.row(3 * i + 2));
  }
  MatrixXd JMi;
  internal::TimesMassInverse(model, data, J, JMi);
  MatrixXd Y = JMi.transpose();
  if (ncr > 0) {
    internal::EnsureDenseJacobian(model, data);  // G for the dense decomposition below
    MatrixXd GMi;
    internal::TimesMassInverse(model, data, data.J, GMi);
    Eigen::CompleteOrthogonalDecomposition<MatrixXd> cod;
    cod.setThreshold(1e-10);
    cod.compute(data.J * GMi.transpose());
    Y -= GMi.transpose() * cod.solve(MatrixXd(data.J * Y));
  }
  MatrixXd K = J * Y;
  K = 0.5 * (K + K.transpose());
  VectorXd u;
  internal::GetVelocity(model, state, data, u);
  const VectorXd v0 = J * u;

  const double T0 = res.kinetic_energy_before;
  const auto energy_after = [&](const VectorXd& P) {
    State s = state;
    internal::SetVelocity(model, data, u + Y * P, s);
    return internal::KineticEnergy(model, s);
  };
  ImpulsePath with_friction(K, v0, pts, true);
  ImpulsePath frictionless(K, v0, pts, false);
  const ImpulsePath* chosen = &with_friction;
  const bool ran = with_friction.Run();
  if (!ran || energy_after(with_friction.P()) > T0 * (1.0 + 1e-12)) {
    // Newton's or Poisson's law with friction raised the energy, or the path failed (an
    // unreachable velocity target): the frictionless impulse instead, flagged.
    res.frictionless_fallback = true;
    chosen = &frictionless;
    if (!frictionless.Run()) return res;
  }
  const ImpulsePath& path = *chosen;
  res.steps = path.steps();
  const VectorXd& P = path.P();
  internal::SetVelocity(model, data, u + Y * P, state);
  res.kinetic_energy_after = internal::KineticEnergy(model, state);
  // Impulses per point and the energy change, shared by normal impulse.
  const double dT = res.kinetic_energy_after - res.kinetic_energy_before;
  double Pn_sum = 0.0;
  for (Eigen::Index i = 0; i < n; ++i) Pn_sum += std::max(0.0, P[3 * i]);
  for (Eigen::Index i = 0; i < n; ++i) {
    const PathPoint& pp = path.points()[static_cast<size_t>(i)];
    const ContactPointGeometry& g = geo[static_cast<size_t>(i)];
    const double Pn = P[3 * i];
    if (!(Pn > 0.0)) continue;
    ContactImpulse ci;
    ci.point = pp.point;
    ci.approach_speed = std::max(0.0, -pp.v_n0);
    ci.normal_impulse = Pn;
    ci.compression_impulse = pp.P_c;
    ci.compression_work = pp.W_c;
    ci.normal_work = path.W()[i];
    ci.impulse_W = Pn * g.n + P[3 * i + 1] * g.t1 + P[3 * i + 2] * g.t2;
    ci.sticking = pp.sticking && pp.mu_s > 0.0;
    ci.law = pp.law;
    res.impulses.push_back(ci);
    if (Pn_sum > 0.0) state.contacts[static_cast<size_t>(pp.point)].impact_work += dT * Pn / Pn_sum;
  }
  return res;
}

}  // namespace

ImpactResult ResolveImpacts(const Model& model, State& state, const ContactTolerances& tol) {
  return ImpactsImpl(model, state, tol, -1);
}

ImpactResult ResolvePlasticImpact(const Model& model, State& state, int point,
                                  const ContactTolerances& tol) {
  return ImpactsImpl(model, state, tol, point);
}

}  // namespace chasles
