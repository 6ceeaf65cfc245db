#include "dynamics/internal/sparse_solve.h"

#include <algorithm>
#include <cmath>
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
    if (ws.ldlt.info() != Eigen::Success || !(ws.ldlt.vectorD().minCoeff() > 1e-10 * a_max))
      return false;
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

void AddMinvWTimes(const SparseWorkspace& ws, const Eigen::VectorXd& lambda, Eigen::VectorXd& u) {
  const BlockRows& R = ws.rows;
  for (int i = 0; i < R.rows(); ++i) {
    for (int k = R.start[static_cast<size_t>(i)]; k < R.start[static_cast<size_t>(i) + 1]; ++k) {
      u.segment<6>(6 * R.body[static_cast<size_t>(k)]) +=
          ws.MinvW[static_cast<size_t>(k)] * lambda[i];
    }
  }
}

void AppendConstraintRows(const Model& model, const Data& data, BlockRows& rows) {
  for (int c = 0; c < model.num_constraints(); ++c) {
    const Constraint& con = model.constraint(c);
    const ConstraintEval& e = data.constraint_rows[static_cast<size_t>(c)];
    const int o = model.constraint_row_offset(c);
    const bool released = data.row_released[static_cast<size_t>(o)] != 0;
    for (int k = 0; k < con.num_rows(); ++k) {
      if (!released) {
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
  }
}

}  // namespace internal
}  // namespace chasles
