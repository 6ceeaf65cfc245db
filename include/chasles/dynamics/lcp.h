#pragma once
/// @file
/// The linear complementarity problem: find z with
///   w = A z + q,   w >= 0,   z >= 0,   wᵀz = 0,
/// solved by Lemke's complementary pivoting (Cottle, Pang & Stone, The Linear Complementarity
/// Problem, 1992, sec. 4.4) on the small dense systems of contact mode selection and impacts.

#include <Eigen/Core>

namespace chasles {

struct LcpResult {
  /// The solution z (size of q).
  Eigen::VectorXd z;
  /// w = A z + q.
  Eigen::VectorXd w;
  /// True when Lemke's method ended with a complementary solution (false: ray termination,
  /// the problem has no solution Lemke can find, or the pivot limit was reached).
  bool solved = false;
  /// Number of pivots taken.
  int pivots = 0;
};

/// Solves the LCP (A, q) by Lemke's method with the covering vector of ones. For a positive
/// semi-definite (or copositive-plus) A a solvable problem is always solved. `tolerance`
/// scales the pivot and ratio tests (relative to the largest |A|, |q|).
LcpResult SolveLcp(const Eigen::MatrixXd& A, const Eigen::VectorXd& q, double tolerance = 1e-12);

}  // namespace chasles
