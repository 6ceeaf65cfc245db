#pragma once
/// @file
/// Sparse solves of the constraint and contact stages (docs/design.md, "Sparse constraint and
/// contact solves"). Each active row touches at most a few bodies, so its Jacobian J and force
/// direction W are stored by body blocks (6 columns each). With M⁻¹ block diagonal,
/// M_b⁻¹ = diag(E/m, I_W⁻¹), I_W⁻¹ = R I_B⁻¹ Rᵀ, the Delassus matrix
///   A = J M⁻¹ Wᵀ,   A_ik = Σ_b J_ib M_b⁻¹ W_kbᵀ   (b over the bodies rows i and k share)
/// has an entry only where two rows share a body: a chain or a pile gives O(n) entries. A is
/// factored by a sparse LDLᵀ with AMD ordering when W = J (symmetric positive semi-definite) and
/// by a sparse LU with COLAMD ordering otherwise (sliding rows, rolling resistance); the
/// symbolic analysis is kept while the rows' body pattern stays (between mode changes), so an
/// evaluation refills the O(n) values and refactors numerically. A pivot at or below 1e-10 of
/// A's largest entry (redundant rows) is reported to the caller. A symmetric singular system
/// then gets the (weighted) least-norm solution sparsely (SolveSparseLeastNorm, iterated
/// Tikhonov with one sparse LDLᵀ); a sliding one, or one that solve gives up on, takes the dense
/// least-norm path.

#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <Eigen/SparseLU>

#include "chasles/model/data.h"
#include "chasles/model/model.h"

namespace chasles::internal {

using Vec6 = Eigen::Matrix<double, 6, 1>;

/// Active rows by body blocks: row i has the blocks [start[i], start[i+1]); block k is on body
/// `body[k]` with Jacobian J[k] and force direction W[k] ([force; moment] columns of that
/// body). A row without blocks (a released string) is held at x_i = 0 (A_ii = 1).
struct BlockRows {
  std::vector<int> start{0};
  std::vector<int> body;
  std::vector<Vec6> J, W;
  /// Empties the rows, keeping the storage.
  void Clear();
  int rows() const { return static_cast<int>(start.size()) - 1; }
  void Add(int b, const Vec6& j, const Vec6& w);
  void EndRow() { start.push_back(static_cast<int>(body.size())); }
  /// J_i x for the 6-per-body vector x.
  double RowTimes(int i, const Eigen::VectorXd& x) const;
};

/// Eigen's SimplicialLDLT whose numeric factorisation reads A itself: A is stored ordered (AMD
/// applied at assembly) as its upper triangle, which is what the factorisation works on, so the
/// ordered copy SimplicialLDLT::factorize makes (an allocation per call) is not needed.
class InPlaceLDLT : public Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Upper,
                                                 Eigen::NaturalOrdering<int>> {
 public:
  void FactorizeInPlace(const Eigen::SparseMatrix<double>& A) {
    this->template factorize_preordered<true>(A);
  }
};

/// Workspace of one sparse stage (kept in Data; copies start empty).
struct SparseWorkspace {
  BlockRows rows;
  /// M⁻¹ W per block, and each body's I_W⁻¹.
  std::vector<Vec6> MinvW;
  std::vector<Mat3> I_inv_W;
  /// The pattern the symbolic analysis was made for (copies of rows.start and rows.body, and
  /// whether it was for the symmetric factorisation).
  std::vector<int> pattern_start, pattern_body;
  bool pattern_symmetric = false;
  /// Products A(row of block j, row of block w) += J[j]·(M⁻¹W)[w] go to A.valuePtr()[slot].
  std::vector<int> pair_j, pair_w, pair_slot;
  /// Slots of the diagonal entries of rows without blocks.
  std::vector<int> hold_slot;
  /// Symmetric case: A holds the upper triangle of P A Pᵀ, row i of A being row perm[i] of
  /// P A Pᵀ (AMD ordering, applied here so that the factorisation works in place); otherwise
  /// A itself (the LU orders its columns).
  Eigen::SparseMatrix<double> A;
  std::vector<int> perm;
  /// Jacobi scales S of the rows (ScaleSymmetrically), in row order and in A's order.
  Eigen::VectorXd scale, scale_stored;
  /// S r and the solution y of (S A S) y = S r, in A's order.
  Eigen::VectorXd r_perm, x_perm;
  InPlaceLDLT ldlt;
  Eigen::SparseLU<Eigen::SparseMatrix<double>, Eigen::COLAMDOrdering<int>> lu;
  /// Whether the last solve succeeded (false: singular, solved by the dense path).
  bool solved = false;
  /// Set by SolveSparse when the symmetric factorisation met a pivot at or below 1e-10 of the
  /// largest entry (A holds S A S, ready for SolveSparseLeastNorm); `nullity` is the number of
  /// such pivots (-1 when the factorisation stopped at an exact zero).
  bool singular_symmetric = false;
  int nullity = -1;
  /// SolveSparseLeastNorm: K = S A S + ε E⁻² (same pattern as A) and the slots of its
  /// diagonal, its own LDLᵀ, E = D S⁻¹ in A's order, the vectors of the iteration; whether
  /// the last least-norm solve converged and in how many iterations (summed over the unweighted
  /// and the weighted solve of one evaluation).
  Eigen::SparseMatrix<double> K;
  std::vector<int> diag_slot;
  InPlaceLDLT ldlt_k;
  Eigen::VectorXd E, b, y, res, dy, v;
  bool least_norm = false;
  int least_norm_iterations = 0;
};

/// The workspace behind `handle` (made on first use).
SparseWorkspace& GetSparseWorkspace(SparseWorkspaceHandle& handle);

/// Whether a stage with `rows` active rows takes the sparse path under `choice`.
bool UseSparse(LinearSolver choice, int rows);

/// Solves (J M⁻¹ Wᵀ) x = r for the rows in ws.rows (fills ws.MinvW). Returns false, leaving x
/// unspecified, when a pivot shows A singular: at or below 1e-10 of the largest entry of
/// S A S, S the Jacobi scaling diag(1 / √(J_i M⁻¹ J_iᵀ)).
bool SolveSparse(const Model& model, const Data& data, bool symmetric, SparseWorkspace& ws,
                 const Eigen::VectorXd& r, Eigen::VectorXd& x);

/// After SolveSparse(symmetric = true) returned false with ws.singular_symmetric: the weighted
/// least-norm solution of the consistent singular system A x = r, min Σ (x_i / d_i)², x = D y
/// with y the least-norm solution of (D A D) y = D r (`d` null: D = I). Returns false, leaving
/// x unspecified, when the iteration does not reach the round-off of r within its cap (an
/// inconsistent r, or a spectrum too spread for ε): the dense path then answers.
bool SolveSparseLeastNorm(SparseWorkspace& ws, const Eigen::VectorXd& r, const Eigen::VectorXd* d,
                          Eigen::VectorXd& x);

/// u += M⁻¹ Wᵀ λ from the blocks (after SolveSparse, which filled ws.MinvW).
void AddMinvWTimes(const SparseWorkspace& ws, const Eigen::VectorXd& lambda, Eigen::VectorXd& u);

/// The rows as dense matrices (rows × 6 n_bodies): J into `J`, and W into `W` when not null.
void ScatterBlocks(const BlockRows& rows, int num_bodies, Eigen::MatrixXd& J,
                   Eigen::MatrixXd* W = nullptr);

/// Appends row k of constraint c (Data::constraint_rows, after CalcConstraintRows) to `rows`,
/// W = J; a released constraint's row has no blocks.
void AppendConstraintRow(const Model& model, const Data& data, int c, int k, BlockRows& rows);

/// Appends the rows of every constraint (Data::constraint_rows, after CalcConstraintRows) to
/// `rows`, W = J; released constraints get rows without blocks.
void AppendConstraintRows(const Model& model, const Data& data, BlockRows& rows);

}  // namespace chasles::internal
