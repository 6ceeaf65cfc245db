#include "chasles/dynamics/lcp.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace chasles {

// Lemke's method (Cottle, Pang & Stone 1992, sec. 4.4): with the artificial variable z0 and
// covering vector d = 1, the tableau [I  -A  -d | q] holds w - A z - d z0 = q. Start with z0 =
// -min q (all w >= 0), then pivot complementary pairs in with the minimum-ratio test until z0
// leaves the basis. Own code rather than a library: the systems are tiny (a few contacts),
// dense, and solved only at events, so the exact pivoting of a tableau is the simplest sure
// thing.
LcpResult SolveLcp(const Eigen::MatrixXd& A, const Eigen::VectorXd& q, double tolerance) {
  const Eigen::Index n = q.size();
  LcpResult r;
  r.z = Eigen::VectorXd::Zero(n);
  r.w = q;
  if (n == 0 || q.minCoeff() >= 0.0) {
    r.solved = true;
    return r;
  }
  const double scale = std::max({1.0, A.cwiseAbs().maxCoeff(), q.cwiseAbs().maxCoeff()});
  const double eps = tolerance * scale;
  // Columns: w_0..w_{n-1}, z_0..z_{n-1}, z0 (index 2n); right-hand side kept separately.
  const Eigen::Index cols = 2 * n + 1;
  Eigen::MatrixXd T(n, cols);
  T.leftCols(n).setIdentity();
  T.middleCols(n, n) = -A;
  T.col(2 * n).setConstant(-1.0);
  Eigen::VectorXd rhs = q;
  std::vector<Eigen::Index> basis(static_cast<size_t>(n));
  for (Eigen::Index i = 0; i < n; ++i) basis[static_cast<size_t>(i)] = i;  // w basic
  auto pivot = [&](Eigen::Index row, Eigen::Index col) {
    const double p = T(row, col);
    T.row(row) /= p;
    rhs[row] /= p;
    for (Eigen::Index i = 0; i < n; ++i) {
      if (i == row) continue;
      const double f = T(i, col);
      if (f != 0.0) {
        T.row(i) -= f * T.row(row);
        rhs[i] -= f * rhs[row];
      }
    }
    basis[static_cast<size_t>(row)] = col;
    ++r.pivots;
  };
  // z0 enters; the row with the most negative q leaves.
  Eigen::Index row = 0;
  q.minCoeff(&row);
  Eigen::Index leaving = basis[static_cast<size_t>(row)];
  pivot(row, 2 * n);
  const int max_pivots = 50 * static_cast<int>(n) + 50;
  while (r.pivots < max_pivots) {
    // The complement of the variable that just left enters.
    const Eigen::Index entering = leaving < n ? leaving + n : leaving - n;
    // Minimum-ratio test over rows with a positive entry in the entering column; ties go to
    // the row holding z0 (ends the method), then to the smallest index (lexicographic enough
    // for the small, well-scaled systems here).
    Eigen::Index best = -1;
    double best_ratio = std::numeric_limits<double>::infinity();
    for (Eigen::Index i = 0; i < n; ++i) {
      const double a = T(i, entering);
      if (a <= eps) continue;
      const double ratio = std::max(rhs[i], 0.0) / a;
      const bool z0_row = basis[static_cast<size_t>(i)] == 2 * n;
      if (ratio < best_ratio - eps || (ratio <= best_ratio + eps && z0_row && best >= 0 &&
                                       basis[static_cast<size_t>(best)] != 2 * n)) {
        best = i;
        best_ratio = ratio;
      }
    }
    if (best < 0) return r;  // ray termination
    leaving = basis[static_cast<size_t>(best)];
    pivot(best, entering);
    if (leaving == 2 * n) {
      r.solved = true;
      break;
    }
  }
  if (!r.solved) return r;
  Eigen::VectorXd x = Eigen::VectorXd::Zero(cols);
  for (Eigen::Index i = 0; i < n; ++i) x[basis[static_cast<size_t>(i)]] = std::max(rhs[i], 0.0);
  r.z = x.segment(n, n);
  r.w = A * r.z + q;
  return r;
}

}  // namespace chasles
