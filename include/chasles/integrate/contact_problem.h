#pragma once
/// @file
/// The frictional contact problem of one time step (docs/contact.md, "Time stepping"): at m
/// contact points with local frames (n, t1, t2), find the impulses P_i = (P_n, P_t1, P_t2)
/// [N·s] and the relative velocities U_i = (U_n, U_t1, U_t2) [m/s] with
///   U = W P + q,
///   0 <= P_n ⟂ U_n >= 0,                                  (unilateral, velocity level)
///   |P_t| <= mu P_n, and U_t = 0 or P_t = -mu P_n U_t/|U_t|  (Coulomb's cone, maximum
///                                                         dissipation),
/// W = J M⁻¹ Jᵀ the Delassus matrix (symmetric, positive semidefinite, 3 rows per point: n,
/// t1, t2), q the velocities without contact impulses (with a restitution shift on U_n). It is
/// solved as the zero of the Alart–Curnier function (Alart & Curnier, Comput. Methods Appl.
/// Mech. Eng. 92, 1991), per point with ρ_i = 1 / (largest diagonal entry of W_ii):
///   F_n = P_n - max(0, P_n - ρ U_n),
///   F_t = P_t - proj_{disc(mu max(0, P_n - ρ U_n))}(P_t - ρ U_t),
/// F = 0 exactly when the conditions above hold. F is piecewise smooth (strongly semismooth),
/// so the generalised Newton method converges locally quadratically (Qi & Sun, Math. Program.
/// 58, 1993); a backtracking line search on ½|F|² makes it descend, and where the Newton step
/// makes no progress the block Gauss–Seidel method with each point's own problem solved exactly
/// takes over. The residual actually reached is returned, in N·s (max |F_i|) and in m/s
/// (max |F_i| / ρ_i): the caller says whether it meets its tolerance.

#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

namespace chasles {

struct FrictionalContactProblem {
  /// Delassus matrix W = J M⁻¹ Jᵀ, 3 rows per point (n, t1, t2) [1/kg].
  Eigen::SparseMatrix<double> W;
  /// Velocities without contact impulses, 3 per point [m/s].
  Eigen::VectorXd q;
  /// Coulomb coefficient per point (>= 0).
  std::vector<double> mu;

  int num_points() const { return static_cast<int>(mu.size()); }
};

struct ContactProblemSettings {
  /// Stop when max |F_i| <= tolerance × the impulse scale (max over points of |P_i| and
  /// ρ_i |q_i|).
  double tolerance = 1e-12;
  /// Newton iterations before the Gauss–Seidel sweeps take over.
  int max_newton_iterations = 30;
  /// Gauss–Seidel sweeps at most.
  int max_sweeps = 2000;
};

/// Regime of one point in a solution: apart (P = 0, U_n >= 0), sticking (|P_t| < mu P_n,
/// U_t = 0) or sliding (|P_t| = mu P_n, U_t against P_t).
enum class ContactRegime { kOpen, kSticking, kSliding };

struct ContactProblemSolution {
  /// Impulses [N·s] and relative velocities U = W P + q [m/s], 3 per point.
  Eigen::VectorXd P, U;
  /// The residual reached: max_i |F_i| [N·s], and max_i |F_i| / ρ_i [m/s].
  double residual_impulse = 0.0;
  double residual_velocity = 0.0;
  /// Impulse scale the tolerance is relative to [N·s].
  double scale = 0.0;
  /// Newton iterations and Gauss–Seidel sweeps taken.
  int newton_iterations = 0;
  int sweeps = 0;
  /// Whether the residual met the tolerance.
  bool converged = false;
  /// Regime of each point.
  std::vector<ContactRegime> regimes;
};

/// Solves `problem` from `warm_start` (3 per point, or empty for zero impulses).
ContactProblemSolution SolveFrictionalContact(const FrictionalContactProblem& problem,
                                              const Eigen::VectorXd& warm_start,
                                              const ContactProblemSettings& settings = {});

/// The Alart–Curnier residual of (P, U) at point `i` with ρ = `rho` (F_i above) [N·s].
Eigen::Vector3d AlartCurnierResidual(const Eigen::Vector3d& P, const Eigen::Vector3d& U, double mu,
                                     double rho);

}  // namespace chasles
