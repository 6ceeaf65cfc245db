#include "dynamics/internal/sparse_solve.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>

namespace chasles {

namespace internal {

SparseWorkspace& GetSparseWorkspace(SparseWorkspaceHandle& h) {
  if (!h.ptr) h.ptr = {new SparseWorkspace, [](SparseWorkspace* p) { delete p; }};
  return *h.ptr;
}

void BlockRows::Clear() {
  start.resize(1);
  start[0] = 0;
  body.clear();
  J.clear();
  W.clear();
}

void BlockRows::Add(int b, const Vec6& j, const Vec6& w) {
  body.push_back(b);
  J.push_back(j);
  W.push_back(w);
}

double BlockRows::RowTimes(int i, const Eigen::VectorXd& x) const {
  double s = 0.0;
  for (int k = start[static_cast<size_t>(i)]; k < start[static_cast<size_t>(i) + 1]; ++k) {
    s += J[static_cast<size_t>(k)].dot(x.segment<6>(6 * body[static_cast<size_t>(k)]));
  }
  return s;
}

bool UseSparse(LinearSolver choice, int rows) {
  if (choice == LinearSolver::kDense) return false;
  if (choice == LinearSolver::kSparse) return true;
  return rows >= kSparseMinRows;
}

namespace {

using Triplets = std::vector<Eigen::Triplet<double, int>>;

// Every pair of blocks on one body, (j, w), adds to A(row of j, row of w).
void FindPairs(SparseWorkspace& ws, int nb, const std::vector<int>& row_of) {
  const BlockRows& R = ws.rows;
  const auto nblocks = R.body.size();
  // Blocks by body (counting sort).
  std::vector<int> body_start(static_cast<size_t>(nb) + 1, 0), by_body(nblocks);
  for (int b : R.body) ++body_start[static_cast<size_t>(b) + 1];
  for (size_t b = 0; b < static_cast<size_t>(nb); ++b) body_start[b + 1] += body_start[b];
  std::vector<int> fill(body_start.begin(), body_start.end() - 1);
  for (size_t k = 0; k < nblocks; ++k) {
    by_body[static_cast<size_t>(fill[static_cast<size_t>(R.body[k])]++)] = static_cast<int>(k);
  }
  ws.pair_j.clear(), ws.pair_w.clear();
  for (size_t b = 0; b < static_cast<size_t>(nb); ++b) {
    for (int p = body_start[b]; p < body_start[b + 1]; ++p) {
      for (int q = body_start[b]; q < body_start[b + 1]; ++q) {
        const int j = by_body[static_cast<size_t>(p)], w = by_body[static_cast<size_t>(q)];
        // Symmetric: only the upper triangle of the permuted matrix is stored and formed.
        if (!ws.perm.empty() && ws.perm[static_cast<size_t>(row_of[static_cast<size_t>(j)])] >
                                    ws.perm[static_cast<size_t>(row_of[static_cast<size_t>(w)])])
          continue;
        ws.pair_j.push_back(j), ws.pair_w.push_back(w);
      }
    }
  }
}

// The symbolic part, redone only when the rows' body pattern (or the symmetry) changed: the
// entries of A (every pair of blocks on one body, and the whole diagonal), the AMD ordering of
// the symmetric case, where each product lands, and the factorisation's analysis.
void Analyse(SparseWorkspace& ws, int nb, bool symmetric) {
  const BlockRows& R = ws.rows;
  const int n = R.rows();
  std::vector<int> row_of(R.body.size());
  for (int i = 0; i < n; ++i) {
    for (int k = R.start[static_cast<size_t>(i)]; k < R.start[static_cast<size_t>(i) + 1]; ++k)
      row_of[static_cast<size_t>(k)] = i;
  }
  ws.perm.clear();
  FindPairs(ws, nb, row_of);  // all pairs
  ws.A.resize(n, n);
  Triplets entries;
  for (int i = 0; i < n; ++i) entries.emplace_back(i, i, 1.0);
  for (size_t p = 0; p < ws.pair_j.size(); ++p) {
    entries.emplace_back(row_of[static_cast<size_t>(ws.pair_j[p])],
                         row_of[static_cast<size_t>(ws.pair_w[p])], 1.0);
  }
  ws.A.setFromTriplets(entries.begin(), entries.end());
  if (symmetric) {
    // AMD on A's pattern; new index of row i: perm[i] (P = Pinv⁻¹ as SimplicialLDLT takes it).
    Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> Pinv;
    Eigen::AMDOrdering<int>()(ws.A, Pinv);
    const Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> P = Pinv.inverse();
    ws.perm.assign(P.indices().data(), P.indices().data() + n);
    FindPairs(ws, nb, row_of);  // the upper triangle's pairs
    entries.clear();
    for (int i = 0; i < n; ++i) entries.emplace_back(i, i, 1.0);
    for (size_t p = 0; p < ws.pair_j.size(); ++p) {
      entries.emplace_back(ws.perm[static_cast<size_t>(row_of[static_cast<size_t>(ws.pair_j[p])])],
                           ws.perm[static_cast<size_t>(row_of[static_cast<size_t>(ws.pair_w[p])])],
                           1.0);
    }
    ws.A.setFromTriplets(entries.begin(), entries.end());
  }
  ws.A.makeCompressed();
  const auto index = [&](int i) { return ws.perm.empty() ? i : ws.perm[static_cast<size_t>(i)]; };
  // Slot of (i, k) (before the permutation): column k's row indices are sorted.
  const auto slot = [&](int i, int k) {
    const int* first = ws.A.innerIndexPtr() + ws.A.outerIndexPtr()[index(k)];
    const int* last = ws.A.innerIndexPtr() + ws.A.outerIndexPtr()[index(k) + 1];
    return static_cast<int>(std::lower_bound(first, last, index(i)) - ws.A.innerIndexPtr());
  };
  ws.pair_slot.resize(ws.pair_j.size());
  for (size_t p = 0; p < ws.pair_j.size(); ++p) {
    ws.pair_slot[p] =
        slot(row_of[static_cast<size_t>(ws.pair_j[p])], row_of[static_cast<size_t>(ws.pair_w[p])]);
  }
  ws.hold_slot.clear();
  for (int i = 0; i < n; ++i) {
    if (R.start[static_cast<size_t>(i)] == R.start[static_cast<size_t>(i) + 1])
      ws.hold_slot.push_back(slot(i, i));
  }
  ws.K.resize(0, 0);  // SolveSparseLeastNorm's copy follows the new pattern
  if (symmetric) {
    ws.ldlt.analyzePattern(ws.A);
  } else {
    ws.lu.analyzePattern(ws.A);
  }
  ws.r_perm.resize(n), ws.x_perm.resize(n);
  ws.pattern_start = R.start;
  ws.pattern_body = R.body;
  ws.pattern_symmetric = symmetric;
}

// Smallest |U_jj| of the sparse LU (the diagonal of U is stored in L's supernodes, as
// SparseLU::absDeterminant reads it).
template <class LU>
double MinPivot(const LU& lu, Eigen::Index n) {
  double m = std::numeric_limits<double>::infinity();
  for (Eigen::Index j = 0; j < n; ++j) {
    for (typename LU::SCMatrix::InnerIterator it(lu.matrixL().m_mapL, j); it; ++it) {
      if (it.index() == j) {
        m = std::min(m, std::abs(it.value()));
        break;
      }
    }
  }
  return m;
}

// K = Ã + diag(shift) (the pattern and diagonal slots from Ã, each column's last stored
// entry, made again after a new analysis), factored by ws.ldlt_k.
void FactorShifted(SparseWorkspace& ws, const Eigen::VectorXd& shift) {
  const int n = static_cast<int>(ws.A.rows());
  if (ws.K.nonZeros() != ws.A.nonZeros() || ws.K.rows() != n) {
    ws.K = ws.A;
    ws.diag_slot.resize(static_cast<size_t>(n));
    for (int c = 0; c < n; ++c)
      ws.diag_slot[static_cast<size_t>(c)] = ws.K.outerIndexPtr()[c + 1] - 1;
    ws.ldlt_k.analyzePattern(ws.K);
  }
  std::copy(ws.A.valuePtr(), ws.A.valuePtr() + ws.A.nonZeros(), ws.K.valuePtr());
  for (int c = 0; c < n; ++c) ws.K.valuePtr()[ws.diag_slot[static_cast<size_t>(c)]] += shift[c];
  ws.ldlt_k.FactorizeInPlace(ws.K);
}

// Jacobi scaling S = diag(1 / √(J_i M⁻¹ J_iᵀ)) (1 for a held row), applied to A's values in
// place: the singularity test compares the pivots of S A S, whose diagonal is about 1, so it
// does not depend on units (moment rows against force rows, light against heavy bodies) nor on
// how the system's scales spread along a long chain, only on the rows' dependence.
void ScaleSymmetrically(const Model& model, SparseWorkspace& ws) {
  const BlockRows& R = ws.rows;
  const int n = R.rows();
  ws.scale.resize(n);
  ws.scale_stored.resize(n);
  for (int i = 0; i < n; ++i) {
    double d = 0.0;
    for (int k = R.start[static_cast<size_t>(i)]; k < R.start[static_cast<size_t>(i) + 1]; ++k) {
      const Vec6& j = R.J[static_cast<size_t>(k)];
      const int b = R.body[static_cast<size_t>(k)];
      d += j.head<3>().squaredNorm() / model.body(b).mass() +
           j.tail<3>().dot(ws.I_inv_W[static_cast<size_t>(b)] * j.tail<3>());
    }
    ws.scale[i] = d > 0.0 ? 1.0 / std::sqrt(d) : 1.0;
    ws.scale_stored[ws.perm.empty() ? i : ws.perm[static_cast<size_t>(i)]] = ws.scale[i];
  }
  double* v = ws.A.valuePtr();
  const int* outer = ws.A.outerIndexPtr();
  const int* inner = ws.A.innerIndexPtr();
  for (int c = 0; c < n; ++c) {
    for (int p = outer[c]; p < outer[c + 1]; ++p)
      v[p] *= ws.scale_stored[inner[p]] * ws.scale_stored[c];
  }
}

}  // namespace

bool SolveSparse(const Model& model, const Data& data, bool symmetric, SparseWorkspace& ws,
                 const Eigen::VectorXd& r, Eigen::VectorXd& x) {
  const int nb = model.num_bodies();
  const BlockRows& R = ws.rows;
  const int n = R.rows();
  ws.solved = false;
  ws.singular_symmetric = false;
  ws.least_norm = false;
  ws.least_norm_iterations = 0;
  if (n == 0) {
    x.resize(0);
    return ws.solved = true;
  }
  // M⁻¹ W per block: E/m on the force part, I_W⁻¹ = R I_B⁻¹ Rᵀ on the moment part.
  ws.I_inv_W.resize(static_cast<size_t>(nb));
  for (int b = 0; b < nb; ++b) {
    const auto i = static_cast<size_t>(b);
    ws.I_inv_W[i] = data.R_WB[i] * model.body(b).I_BBcm_B_inverse() * data.R_WB[i].transpose();
  }
  ws.MinvW.resize(R.W.size());
  for (size_t k = 0; k < R.W.size(); ++k) {
    const int b = R.body[k];
    ws.MinvW[k].head<3>() = R.W[k].head<3>() / model.body(b).mass();
    ws.MinvW[k].tail<3>() = ws.I_inv_W[static_cast<size_t>(b)] * R.W[k].tail<3>();
  }
  if (ws.pattern_start != R.start || ws.pattern_body != R.body ||
      ws.pattern_symmetric != symmetric || ws.A.rows() != n)
    Analyse(ws, nb, symmetric);
  // Numeric values (eq. above): A_ik = Σ_b J_ib · (M⁻¹ W)_kb.
  double* v = ws.A.valuePtr();
  std::fill(v, v + ws.A.nonZeros(), 0.0);
  for (size_t p = 0; p < ws.pair_slot.size(); ++p) {
    v[ws.pair_slot[p]] +=
        R.J[static_cast<size_t>(ws.pair_j[p])].dot(ws.MinvW[static_cast<size_t>(ws.pair_w[p])]);
  }
  for (int s : ws.hold_slot) v[s] = 1.0;
  ScaleSymmetrically(model, ws);
  double a_max = 0.0;
  for (Eigen::Index k = 0; k < ws.A.nonZeros(); ++k) a_max = std::max(a_max, std::abs(v[k]));
  if (!(a_max > 0.0)) return false;
  // The system solved is (S A S) y = S r, x = S y (in P's order when symmetric).
  const auto at = [&](int i) { return ws.perm.empty() ? i : ws.perm[static_cast<size_t>(i)]; };
  for (int i = 0; i < n; ++i) ws.r_perm[at(i)] = ws.scale[i] * r[i];
  if (symmetric) {
    // P S A S Pᵀ: LDLᵀ in place (no ordering of its own).
    ws.ldlt.FactorizeInPlace(ws.A);
    if (ws.ldlt.info() != Eigen::Success || !(ws.ldlt.vectorD().minCoeff() > 1e-10 * a_max)) {
      // Positive semi-definite: without pivoting, a dependent row meets a zero pivot (its
      // column below is then zero too) and the factorisation goes on, so the small pivots count
      // the null space; Eigen stops at an exactly zero pivot (count unknown).
      // Eigen stops at an exactly zero pivot (exact copies of rows): then the pivots of
      // S A S + τ I, τ = 1e-13 of the largest entry, count them (adding τ I to a positive
      // semi-definite matrix only raises its pivots, those above 1e-10 stay above, and a zero
      // pivot becomes O(τ)).
      ws.singular_symmetric = true;
      ws.nullity = -1;
      if (ws.ldlt.info() == Eigen::Success) {
        ws.nullity = static_cast<int>((ws.ldlt.vectorD().array() <= 1e-10 * a_max).count());
      } else {
        FactorShifted(ws, Eigen::VectorXd::Constant(n, 1e-13 * a_max));
        if (ws.ldlt_k.info() == Eigen::Success)
          ws.nullity = static_cast<int>((ws.ldlt_k.vectorD().array() <= 1e-10 * a_max).count());
      }
      return false;
    }
    ws.x_perm = ws.ldlt.solve(ws.r_perm);
  } else {
    ws.lu.factorize(ws.A);
    if (ws.lu.info() != Eigen::Success || !(MinPivot(ws.lu, n) > 1e-10 * a_max)) return false;
    ws.x_perm = ws.lu.solve(ws.r_perm);
  }
  x.resize(n);
  for (int i = 0; i < n; ++i) x[i] = ws.scale[i] * ws.x_perm[at(i)];
  return ws.solved = true;
}

namespace {

// out = Ã v, Ã symmetric stored as its upper triangle (ws.A); with `absolute`, |Ã| |v|.
void SymmetricTimes(const Eigen::SparseMatrix<double>& A, const Eigen::VectorXd& v,
                    Eigen::VectorXd& out, bool absolute) {
  const int n = static_cast<int>(A.cols());
  const double* val = A.valuePtr();
  const int* outer = A.outerIndexPtr();
  const int* inner = A.innerIndexPtr();
  out.setZero(n);
  for (int c = 0; c < n; ++c) {
    for (int p = outer[c]; p < outer[c + 1]; ++p) {
      const int i = inner[p];
      const double a = absolute ? std::abs(val[p]) : val[p];
      const double vc = absolute ? std::abs(v[c]) : v[c];
      out[i] += a * vc;
      if (i != c) out[c] += a * (absolute ? std::abs(v[i]) : v[i]);
    }
  }
}

}  // namespace

// The weighted least-norm solution (docs/design.md, "Sparse constraint and contact solves").
// With D the weights, the solutions of A x = r are x = D y with (A D) y = r, equivalently
// (D A D) y = D r (D invertible), and min Σ (x_i / d_i)² is min |y|²: y = T⁺ b with
// T = D A D (symmetric positive semi-definite, singular) and b = D r, consistent.
// Iterated Tikhonov regularisation (the proximal point method on ½ yᵀ T y - bᵀ y):
//   y_0 = 0,   y_{k+1} = y_k + (T + ε I)⁻¹ (b - T y_k).
// In T's eigenbasis (T v = σ v) the error e_k = y_k - T⁺ b obeys e_{k+1} = ε / (σ + ε) e_k:
// the null-space part (σ = 0) stays at its start, zero, and every range part shrinks by
// ε / (σ + ε) per iteration, so y_k → T⁺ b, the least-norm solution, with one factorisation
// of the symmetric positive definite T + ε I reused throughout (Engl, Hanke & Neubauer,
// "Regularization of Inverse Problems", 1996, sec. 5.1). T + ε I is factored in the Jacobi
// scaling A is stored in (Ã = S A S, diagonal 1): with E = D S⁻¹, T = E Ã E and
//   T + ε I = E (Ã + ε E⁻²) E,   K = Ã + ε E⁻²,
// so (T + ε I)⁻¹ v = E⁻¹ K⁻¹ E⁻¹ v; K has Ã's pattern and its AMD analysis. ε = 1e-8 of T's
// largest diagonal entry (each iteration gains a factor 1e-8 / σ_rel on the range), 1e-11 when
// the residual stalls above round-off (a spectrum spread below 1e-8); the null-space part that
// round-off leaves, of order u/ε, is removed afterwards (phase 2 below). One solve of a sticking
// row of spheres: 3 iterations and 3 projected ones.
bool SolveSparseLeastNorm(SparseWorkspace& ws, const Eigen::VectorXd& r, const Eigen::VectorXd* d,
                          Eigen::VectorXd& x) {
  // ε levels (relative to T's largest diagonal entry) and the cleaning passes each needs.
  constexpr double kEpsilon[] = {1e-8, 1e-11};
  constexpr int kPasses[] = {1, 2};
  constexpr int kMaxIterations = 60;
  const int n = ws.rows.rows();
  ws.solved = ws.least_norm = false;  // until this solve converges
  if (!ws.singular_symmetric || ws.A.rows() != n) return false;
  const auto at = [&](int i) { return ws.perm[static_cast<size_t>(i)]; };
  ws.E.resize(n), ws.b.resize(n);
  double e2_max = 0.0;
  for (int i = 0; i < n; ++i) {
    const double di = d != nullptr ? (*d)[i] : 1.0;
    if (!(di > 0.0)) return false;
    ws.E[at(i)] = di / ws.scale[i];
    ws.b[at(i)] = di * r[i];
    e2_max = std::max(e2_max, ws.E[at(i)] * ws.E[at(i)]);
  }
  double eps = 0.0;
  // T v and (T + ε I)⁻¹ v (into `out`; `v` and `out` distinct).
  const auto times_T = [&](const Eigen::VectorXd& v, Eigen::VectorXd& out) {
    ws.v = ws.E.cwiseProduct(v);
    SymmetricTimes(ws.A, ws.v, out, false);
    out.array() *= ws.E.array();
  };
  const auto solve_shifted = [&](const Eigen::VectorXd& v, Eigen::VectorXd& out) {
    ws.v = v.cwiseQuotient(ws.E);
    out = ws.ldlt_k.solve(ws.v);
    out.array() /= ws.E.array();
  };
  // res = b - T y; returns |res|, and in `size` the round-off scale |b| + E |Ã| |E y|.
  double size = 0.0;
  const auto residual = [&]() {
    times_T(ws.y, ws.res);
    ws.res = ws.b - ws.res;
    SymmetricTimes(ws.A, ws.E.cwiseProduct(ws.y), ws.dy, true);
    size = (ws.b.cwiseAbs() + ws.E.cwiseProduct(ws.dy)).maxCoeff();
    return ws.res.cwiseAbs().maxCoeff();
  };
  // Phase 1, iterated Tikhonov until the residual is at round-off of its terms or stops
  // falling. Stopping above round-off means range parts with σ far below ε (T's diagonal
  // spreads over orders of magnitude: the moment rows of slender rods weigh 1/I): ε drops to
  // the next level, refactored, and the iteration goes on from y (whose null part stays).
  // T_jj = E_j² Ã_jj, Ã_jj = 1 (a row with blocks, or a held row): ε = level × max E².
  ws.y.setZero(n);
  int level = 0;
  double res_max = 0.0;
  for (;; ++level) {
    eps = kEpsilon[level] * e2_max;
    FactorShifted(ws, (eps / ws.E.array().square()).matrix());  // K = Ã + ε E⁻²
    if (ws.ldlt_k.info() != Eigen::Success) return false;
    double previous = std::numeric_limits<double>::infinity();
    for (int k = 0;; ++k) {
      res_max = residual();
      if (res_max <= 1e-15 * size || res_max > 0.5 * previous) break;
      if (k == kMaxIterations) return false;
      previous = res_max;
      solve_shifted(ws.res, ws.dy);
      ws.y += ws.dy;
      ++ws.least_norm_iterations;
    }
    if (res_max <= 1e-12 * size || level + 1 == static_cast<int>(std::size(kEpsilon))) break;
  }
  if (res_max > 1e-11 * size) return false;  // inconsistent (or too slow): the dense path
  // Phase 2, the null space cleaned. Round-off puts a null-space part into y: b is consistent
  // only to the round-off of forming r, and each solve errs by u |K| |output| in every
  // direction; (T + ε I)⁻¹ magnifies both by 1/ε on the null space, which T y cannot see.
  // y - ε (T + ε I)⁻¹ y = T (T + ε I)⁻¹ y removes it (σ = 0: factor 0) and scales the range
  // parts by σ / (σ + ε); the lost range parts come back by the projected iteration
  //   y += (T + ε I)⁻¹ T (T + ε I)⁻¹ (b - T y)
  // (range parts: error × ε (2σ + ε) / (σ + ε)²; the null parts of the residual and of the
  // first solve are removed by T, and the corrections are small, so is what they add).
  // (u/ε)^(passes + 1) at most is left of the null-space part.
  bool converged = true;
  for (int pass = 0; pass < kPasses[level] && converged; ++pass) {
    solve_shifted(ws.y, ws.dy);
    ws.y -= eps * ws.dy;
    converged = false;
    double previous_step = std::numeric_limits<double>::infinity();
    for (int k = 0; k < kMaxIterations; ++k) {
      residual();
      solve_shifted(ws.res, ws.dy);
      times_T(ws.dy, ws.res);
      solve_shifted(ws.res, ws.dy);
      ws.y += ws.dy;
      ++ws.least_norm_iterations;
      // Done at round-off of y, or where the steps stop falling (their round-off floor).
      const double step = ws.dy.cwiseAbs().maxCoeff(), y_max = ws.y.cwiseAbs().maxCoeff();
      if (step <= 1e-15 * y_max) {
        converged = true;
        break;
      }
      if (step > 0.5 * previous_step) {
        // At the floor a step is round-off of the solves (noise, undone); above 1e-12 of y the
        // steps fall too slowly: T's spectrum spreads below ε.
        if (step > previous_step) ws.y -= ws.dy;
        converged = std::min(step, previous_step) <= 1e-11 * y_max;
        break;
      }
      previous_step = step;
    }
  }
  // Accepted when consistent: the residual at round-off of its terms (an inconsistent r keeps
  // its part outside T's range).
  converged = converged && residual() <= 1e-11 * size;
  if (!converged) return false;
  x.resize(n);
  for (int i = 0; i < n; ++i) x[i] = (d != nullptr ? (*d)[i] : 1.0) * ws.y[at(i)];
  ws.least_norm = true;
  return ws.solved = true;
}

void AddMinvWTimes(const SparseWorkspace& ws, const Eigen::VectorXd& lambda, Eigen::VectorXd& u) {
  const BlockRows& R = ws.rows;
  for (int i = 0; i < R.rows(); ++i) {
    for (int k = R.start[static_cast<size_t>(i)]; k < R.start[static_cast<size_t>(i) + 1]; ++k) {
      u.segment<6>(6 * R.body[static_cast<size_t>(k)]) +=
          ws.MinvW[static_cast<size_t>(k)] * lambda[i];
    }
  }
}

void ScatterBlocks(const BlockRows& rows, int num_bodies, Eigen::MatrixXd& J, Eigen::MatrixXd* W) {
  const int n = rows.rows();
  J.setZero(n, 6 * num_bodies);
  if (W != nullptr) W->setZero(n, 6 * num_bodies);
  for (int i = 0; i < n; ++i) {
    for (int k = rows.start[static_cast<size_t>(i)]; k < rows.start[static_cast<size_t>(i) + 1];
         ++k) {
      const auto j = static_cast<size_t>(k);
      J.row(i).segment<6>(6 * rows.body[j]) = rows.J[j].transpose();
      if (W != nullptr) W->row(i).segment<6>(6 * rows.body[j]) = rows.W[j].transpose();
    }
  }
}

void AppendConstraintRow(const Model& model, const Data& data, int c, int k, BlockRows& rows) {
  const Constraint& con = model.constraint(c);
  const ConstraintEval& e = data.constraint_rows[static_cast<size_t>(c)];
  if (data.row_released[static_cast<size_t>(model.constraint_row_offset(c))] == 0) {
    if (con.parent() != kWorld) {
      const Vec6 j = e.J_parent.row(k).transpose();
      rows.Add(con.parent(), j, j);
    }
    const Vec6 j = e.J_child.row(k).transpose();
    rows.Add(con.child(), j, j);
    for (int x = 0; x < e.num_extra; ++x) {
      const auto xi = static_cast<size_t>(x);
      const Vec6 jx = e.J_extra[xi].row(k).transpose();
      rows.Add(e.extra_body[xi], jx, jx);
    }
  }
  rows.EndRow();
}

void AppendConstraintRows(const Model& model, const Data& data, BlockRows& rows) {
  for (int c = 0; c < model.num_constraints(); ++c) {
    for (int k = 0; k < model.constraint(c).num_rows(); ++k)
      AppendConstraintRow(model, data, c, k, rows);
  }
}

}  // namespace internal
}  // namespace chasles
