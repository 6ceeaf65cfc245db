#include "chasles/integrate/contact_problem.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseLU>

// The Alart–Curnier function of the frictional contact problem and its generalised Jacobian.
// With x_i = P_i - ρ_i U_i and the projection Π_i onto the cone section
// {p_n >= 0, |p_t| <= mu p_n} taken as Alart and Curnier do (first the normal part onto
// R+, then the tangential part onto the disc of radius mu max(0, x_n)), F_i = P_i - Π_i(x_i).
// Π is piecewise smooth; one element D_i of its generalised Jacobian:
//   normal:      dΠ_n/dx_n = [x_n > 0];
//   tangential:  inside the disc (|x_t| <= a): dΠ_t/dx_t = I, dΠ_t/dx_n = 0;
//                outside: Π_t = a ŝ, ŝ = x_t/|x_t|: dΠ_t/dx_t = (a/|x_t|)(I - ŝŝᵀ),
//                dΠ_t/dx_n = mu ŝ [x_n > 0].
// With U = W P + q, dx/dP = I - ρ W, so dF/dP = (I - D) + D ρ W (D block diagonal).

namespace chasles {
namespace {

// Regularisation of the Newton matrix: with redundant points (a box on four corners) W is
// singular and so is ρ D W where every point sticks; the step is then taken with H + εI.
// q lies in the range of J, so the step's part that moves U is the regular one and converges;
// the impulses' split along W's null space is left as it comes (the velocities are unique).
constexpr double kRegularisation = 1e-13;
// Armijo's constant and the smallest step of the line search.
constexpr double kArmijo = 1e-4;
constexpr double kSmallestStep = 1.0 / (1 << 20);
// Points up to which the Newton matrix is dense.
constexpr int kDensePoints = 12;

struct Projection {
  Eigen::Vector3d value;
  Eigen::Matrix3d D;
  ContactRegime regime;
};

Projection ProjectOntoCone(const Eigen::Vector3d& x, double mu) {
  Projection out;
  out.D.setZero();
  const double pn = std::max(0.0, x[0]);
  out.value[0] = pn;
  if (x[0] > 0) out.D(0, 0) = 1.0;
  const Eigen::Vector2d xt = x.tail<2>();
  const double a = mu * pn;
  const double nt = xt.norm();
  if (nt <= a) {
    out.value.tail<2>() = xt;
    out.D.block<2, 2>(1, 1).setIdentity();
    out.regime = pn > 0 ? ContactRegime::kSticking : ContactRegime::kOpen;
  } else {
    const Eigen::Vector2d s = xt / nt;
    out.value.tail<2>() = a * s;
    out.D.block<2, 2>(1, 1) = (a / nt) * (Eigen::Matrix2d::Identity() - s * s.transpose());
    if (x[0] > 0) out.D.block<2, 1>(1, 0) = mu * s;
    out.regime = pn > 0 ? ContactRegime::kSliding : ContactRegime::kOpen;
  }
  return out;
}

// Everything the iterations share: ρ per point and the diagonal blocks of W.
struct Setup {
  const FrictionalContactProblem& problem;
  std::vector<double> rho;
  std::vector<Eigen::Matrix3d> diagonal;
  double scale_q = 0.0;  // max ρ_i |q_i| [N·s]
};

Setup MakeSetup(const FrictionalContactProblem& p) {
  const int m = p.num_points();
  Setup s{p, std::vector<double>(static_cast<size_t>(m)),
          std::vector<Eigen::Matrix3d>(static_cast<size_t>(m), Eigen::Matrix3d::Zero()), 0.0};
  for (int c = 0; c < p.W.outerSize(); ++c) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(p.W, c); it; ++it) {
      if (it.row() / 3 == c / 3) {
        s.diagonal[static_cast<size_t>(c / 3)](it.row() % 3, c % 3) = it.value();
      }
    }
  }
  for (int i = 0; i < m; ++i) {
    const auto k = static_cast<size_t>(i);
    const double d = s.diagonal[k].diagonal().maxCoeff();
    s.rho[k] = d > 0 ? 1.0 / d : 1.0;
    s.scale_q = std::max(s.scale_q, s.rho[k] * p.q.segment<3>(3 * i).norm());
  }
  return s;
}

// F at P (with U = W P + q given); returns ½|F|² and fills the residual measures.
double Residual(const Setup& s, const Eigen::VectorXd& P, const Eigen::VectorXd& U,
                Eigen::VectorXd* F, ContactProblemSolution* out) {
  double merit = 0.0, worst = 0.0, worst_velocity = 0.0, scale = s.scale_q;
  for (int i = 0; i < s.problem.num_points(); ++i) {
    const auto k = static_cast<size_t>(i);
    const Eigen::Vector3d f =
        AlartCurnierResidual(P.segment<3>(3 * i), U.segment<3>(3 * i), s.problem.mu[k], s.rho[k]);
    if (F) F->segment<3>(3 * i) = f;
    merit += 0.5 * f.squaredNorm();
    worst = std::max(worst, f.norm());
    worst_velocity = std::max(worst_velocity, f.norm() / s.rho[k]);
    scale = std::max(scale, P.segment<3>(3 * i).norm());
  }
  if (out) {
    out->residual_impulse = worst;
    out->residual_velocity = worst_velocity;
    out->scale = scale;
  }
  return merit;
}

bool Converged(const ContactProblemSolution& sol, double tolerance) {
  return sol.residual_impulse <= tolerance * sol.scale;
}

// Blocks D_i ρ_i of the generalised Jacobian at P (U given).
void JacobianBlocks(const Setup& s, const Eigen::VectorXd& P, const Eigen::VectorXd& U,
                    std::vector<Eigen::Matrix3d>& D) {
  for (int i = 0; i < s.problem.num_points(); ++i) {
    const auto k = static_cast<size_t>(i);
    const Eigen::Vector3d x = P.segment<3>(3 * i) - s.rho[k] * U.segment<3>(3 * i);
    D[k] = ProjectOntoCone(x, s.problem.mu[k]).D;
  }
}

// W with each of its nonzero 3×3 blocks stored whole (structural zeros kept), and the diagonal
// blocks: the pattern of every Newton matrix H = (I - D) + ρ D W of the problem, whatever the
// regimes (D block diagonal). So H is filled in place at each iteration and the sparse LU
// analyses its pattern once per solve, not once per iteration.
Eigen::SparseMatrix<double> BlockPattern(const Eigen::SparseMatrix<double>& W) {
  const auto n = static_cast<int>(W.rows());
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(static_cast<size_t>(3 * W.nonZeros() + 9 * (n / 3)));
  std::vector<int> last_block(static_cast<size_t>(n / 3), -1);  // per row block: last column block
  const auto add_block = [&](int i, int j) {
    if (last_block[static_cast<size_t>(i)] == j) return;
    last_block[static_cast<size_t>(i)] = j;
    for (int c = 0; c < 3; ++c) {
      for (int r = 0; r < 3; ++r) t.emplace_back(3 * i + r, 3 * j + c, 0.0);
    }
  };
  for (int j = 0; j < n / 3; ++j) {
    add_block(j, j);
    for (int c = 3 * j; c < 3 * j + 3; ++c) {
      for (Eigen::SparseMatrix<double>::InnerIterator it(W, c); it; ++it) {
        add_block(static_cast<int>(it.row()) / 3, j);
        t.emplace_back(it.row(), c, it.value());
      }
    }
  }
  Eigen::SparseMatrix<double> pattern(n, n);
  pattern.setFromTriplets(t.begin(), t.end());  // duplicates summed: W's values, zeros elsewhere
  pattern.makeCompressed();
  return pattern;
}

// The Newton matrices H = (I - D) + ρ D W (+ εI) of one solve (D block diagonal, one 3×3 block
// per point) and their factorisations: dense up to kDensePoints points, else sparse with W's
// block pattern (BlockPattern), filled in place at each iteration, its pattern analysed by the
// sparse LU once.
class NewtonMatrix {
 public:
  explicit NewtonMatrix(const Setup& s) : s_(s), n_(3 * s.problem.num_points()) {
    if (n_ <= 3 * kDensePoints) {
      Wd_ = Eigen::MatrixXd(s.problem.W);
      Hd_.resize(n_, n_);
    } else {
      pattern_ = BlockPattern(s.problem.W);
      H_ = pattern_;
    }
  }

  // H at the blocks D: block row i is ρ_i D_i W's block row i, plus I(1 + ε) - D_i on the
  // diagonal.
  void Fill(const std::vector<Eigen::Matrix3d>& D) {
    if (dense()) {
      for (int i = 0; i < n_ / 3; ++i) {
        const auto k = static_cast<size_t>(i);
        Hd_.middleRows<3>(3 * i).noalias() = s_.rho[k] * (D[k] * Wd_.middleRows<3>(3 * i));
        Hd_.block<3, 3>(3 * i, 3 * i) += Diagonal(D[k]);
      }
      return;
    }
    // Column c of block column j holds runs of three rows, one per block W_ij.
    const int* outer = pattern_.outerIndexPtr();
    const int* rows = pattern_.innerIndexPtr();
    const double* w = pattern_.valuePtr();
    double* h = H_.valuePtr();
    for (int c = 0; c < n_; ++c) {
      for (int k = outer[c]; k < outer[c + 1]; k += 3) {
        const auto i = static_cast<size_t>(rows[k] / 3);
        Eigen::Vector3d col = s_.rho[i] * (D[i] * Eigen::Vector3d(w[k], w[k + 1], w[k + 2]));
        if (static_cast<int>(i) == c / 3) col += Diagonal(D[i]).col(c % 3);
        h[k] = col[0], h[k + 1] = col[1], h[k + 2] = col[2];
      }
    }
  }

  // The Newton step, H Δ = -F (lambda = 0), or the Levenberg–Marquardt step
  // (HᵀH + λI) Δ = -HᵀF, a descent direction of ½|F|² wherever HᵀF ≠ 0 (Yamashita & Fukushima,
  // Computing Suppl. 15, 2001, with λ ~ |F|: quadratic convergence under a local error bound,
  // which holds where the solution set is not isolated, as with redundant points). False when
  // the factorisation fails.
  bool Step(const Eigen::VectorXd& F, double lambda, Eigen::VectorXd& step) {
    if (dense()) {
      if (lambda == 0.0) {
        step = Eigen::PartialPivLU<Eigen::MatrixXd>(Hd_).solve(-F);
      } else {
        Eigen::MatrixXd A = Hd_.transpose() * Hd_;
        A.diagonal().array() += lambda;
        step = A.ldlt().solve(-(Hd_.transpose() * F));
      }
      return step.allFinite();
    }
    if (lambda == 0.0) {
      if (!analysed_) {
        lu_.analyzePattern(H_);
        analysed_ = true;
      }
      lu_.factorize(H_);
      if (lu_.info() != Eigen::Success) return false;
      step = lu_.solve(-F);
    } else {
      Eigen::SparseMatrix<double> A = H_.transpose() * H_;
      Eigen::SparseMatrix<double> I(n_, n_);
      I.setIdentity();
      A += lambda * I;
      Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(A);
      if (ldlt.info() != Eigen::Success) return false;
      step = ldlt.solve(-(H_.transpose() * F));
    }
    return step.allFinite();
  }

  // F·(H step): the slope of ½|F|² along the step.
  double Slope(const Eigen::VectorXd& F, const Eigen::VectorXd& step) const {
    return dense() ? F.dot(Hd_ * step) : F.dot(H_ * step);
  }

 private:
  bool dense() const { return n_ <= 3 * kDensePoints; }
  static Eigen::Matrix3d Diagonal(const Eigen::Matrix3d& D) {
    return Eigen::Matrix3d::Identity() * (1.0 + kRegularisation) - D;
  }

  const Setup& s_;
  int n_;
  Eigen::MatrixXd Wd_, Hd_;
  Eigen::SparseMatrix<double> pattern_, H_;
  Eigen::SparseLU<Eigen::SparseMatrix<double>> lu_;
  bool analysed_ = false;
};

// Backtracking along `step` from P; false when no step length decreases ½|F|² by Armijo's rule.
bool LineSearch(const Setup& s, const ContactProblemSettings& settings, const Eigen::VectorXd& P,
                const Eigen::VectorXd& step, double merit, double slope, Eigen::VectorXd& P_try,
                Eigen::VectorXd& U_try) {
  for (double alpha = 1.0; alpha >= kSmallestStep; alpha *= 0.5) {
    P_try = P + alpha * step;
    U_try = s.problem.W * P_try + s.problem.q;
    ContactProblemSolution trial;
    const double merit_try = Residual(s, P_try, U_try, nullptr, &trial);
    if (merit_try <= merit + kArmijo * alpha * slope || Converged(trial, settings.tolerance)) {
      return true;
    }
  }
  return false;
}

// Generalised Newton with a backtracking line search on ½|F|². Returns when converged, when
// the iterations run out, or when no step along the Newton direction decreases the merit.
void Newton(const Setup& s, const ContactProblemSettings& settings, int max_iterations,
            Eigen::VectorXd& P, Eigen::VectorXd& U, ContactProblemSolution& sol) {
  const auto m = static_cast<size_t>(s.problem.num_points());
  std::vector<Eigen::Matrix3d> D(m);
  Eigen::VectorXd F(P.size()), step, P_try, U_try;
  double merit = Residual(s, P, U, &F, &sol);
  std::optional<NewtonMatrix> H;  // made at the first iteration, if there is one
  while (!Converged(sol, settings.tolerance) && sol.newton_iterations < max_iterations) {
    ++sol.newton_iterations;
    if (!H) H.emplace(s);
    JacobianBlocks(s, P, U, D);
    H->Fill(D);
    // Newton first (slope -2 merit: the step solves the linearisation); where it does not
    // descend, Levenberg–Marquardt steps with growing λ.
    bool moved = H->Step(F, 0.0, step) &&
                 LineSearch(s, settings, P, step, merit, -2.0 * merit, P_try, U_try);
    const double relative = std::sqrt(2.0 * merit) / std::max(sol.scale, 1e-300);
    for (double lambda = std::max(relative, 1e-12); !moved && lambda < 1e6; lambda *= 100.0) {
      if (!H->Step(F, lambda, step)) continue;
      const double slope = H->Slope(F, step);
      moved = slope < 0 && LineSearch(s, settings, P, step, merit, slope, P_try, U_try);
    }
    if (!moved) return;
    P.swap(P_try);
    U.swap(U_try);
    merit = Residual(s, P, U, &F, &sol);
  }
}

// One point's own problem, the others' impulses fixed: U_i = W_ii P_i + q_i' (q_i' = U_i -
// W_ii P_i), solved by the same Newton iteration on three unknowns.
Eigen::Vector3d SolvePoint(const Setup& s, int i, const Eigen::Vector3d& P0,
                           const Eigen::Vector3d& q_local) {
  const auto k = static_cast<size_t>(i);
  FrictionalContactProblem local;
  local.W = s.diagonal[k].sparseView();
  local.q = q_local;
  local.mu = {s.problem.mu[k]};
  const Setup ls = MakeSetup(local);
  ContactProblemSettings settings;
  settings.tolerance = 1e-15;
  settings.max_newton_iterations = 50;
  Eigen::VectorXd P = P0, U = s.diagonal[k] * P0 + q_local;
  ContactProblemSolution sol;
  Newton(ls, settings, settings.max_newton_iterations, P, U, sol);
  return P;
}

// Block Gauss–Seidel sweeps (Jean's non-smooth contact dynamics), U kept equal to W P + q by
// adding W's columns of each point times its change.
void GaussSeidel(const Setup& s, const ContactProblemSettings& settings, int max_sweeps,
                 Eigen::VectorXd& P, Eigen::VectorXd& U, ContactProblemSolution& sol) {
  const int m = s.problem.num_points();
  Residual(s, P, U, nullptr, &sol);
  while (!Converged(sol, settings.tolerance) && sol.sweeps < max_sweeps) {
    ++sol.sweeps;
    for (int i = 0; i < m; ++i) {
      const Eigen::Vector3d Pi = P.segment<3>(3 * i);
      const Eigen::Vector3d q_local = U.segment<3>(3 * i) - s.diagonal[static_cast<size_t>(i)] * Pi;
      const Eigen::Vector3d change = SolvePoint(s, i, Pi, q_local) - Pi;
      if (change.isZero(0.0)) continue;
      P.segment<3>(3 * i) += change;
      for (int c = 0; c < 3; ++c) {
        for (Eigen::SparseMatrix<double>::InnerIterator it(s.problem.W, 3 * i + c); it; ++it) {
          U[it.row()] += it.value() * change[c];
        }
      }
    }
    U = s.problem.W * P + s.problem.q;  // no drift of the running sums
    Residual(s, P, U, nullptr, &sol);
  }
}

}  // namespace

Eigen::Vector3d AlartCurnierResidual(const Eigen::Vector3d& P, const Eigen::Vector3d& U, double mu,
                                     double rho) {
  return P - ProjectOntoCone(P - rho * U, mu).value;
}

ContactProblemSolution SolveFrictionalContact(const FrictionalContactProblem& problem,
                                              const Eigen::VectorXd& warm_start,
                                              const ContactProblemSettings& settings) {
  const int m = problem.num_points();
  const Setup s = MakeSetup(problem);
  ContactProblemSolution sol;
  Eigen::VectorXd P = Eigen::VectorXd::Zero(3 * m);
  if (warm_start.size() == 3 * m) {
    // Start inside the cone: a warm start from another configuration may lie outside it.
    for (int i = 0; i < m; ++i) {
      P.segment<3>(3 * i) =
          ProjectOntoCone(warm_start.segment<3>(3 * i), problem.mu[static_cast<size_t>(i)]).value;
    }
  }
  Eigen::VectorXd U = problem.W * P + problem.q;
  // Newton from the start; where it stalls (a stationary point of ½|F|² that is no solution),
  // Gauss–Seidel sweeps move away from it, and Newton finishes from where they end.
  Newton(s, settings, settings.max_newton_iterations, P, U, sol);
  if (!Converged(sol, settings.tolerance)) {
    GaussSeidel(s, settings, settings.max_sweeps, P, U, sol);
    Newton(s, settings, 2 * settings.max_newton_iterations, P, U, sol);
  }
  sol.converged = Converged(sol, settings.tolerance);
  sol.regimes.resize(static_cast<size_t>(m));
  for (int i = 0; i < m; ++i) {
    const auto k = static_cast<size_t>(i);
    sol.regimes[k] =
        ProjectOntoCone(P.segment<3>(3 * i) - s.rho[k] * U.segment<3>(3 * i), problem.mu[k]).regime;
  }
  sol.P = std::move(P);
  sol.U = std::move(U);
  return sol;
}

}  // namespace chasles
