#pragma once
/// @file
/// The constraint solve (chapter 8.2-8.3 with Lagrange multipliers). With the generalised
/// velocity of each body u_b = [v_WBcm_W; w_WB_W] the Newton–Euler equations read
///   M u̇ = f + Jᵀλ,   M_b = diag(m E, I_W),  I_W = R I_BBcm_B Rᵀ,
///   f_b = [ΣF_W; ΣM_Bcm_W - w_W × (I_W w_W)]
/// (ẇ_W = R ẇ_B exactly, so this is the body-frame Euler equation rotated into W). With the
/// acceleration-level rows J u̇ = c, the Schur complement of the KKT system
/// [M Jᵀ; J 0][u̇; -λ] = [f; c] gives
///   (J M⁻¹ Jᵀ) λ = c - J u̇_free,   u̇ = u̇_free + M⁻¹ Jᵀ λ,   u̇_free = M⁻¹ f
/// (M⁻¹ is block diagonal and known, u̇_free is the unconstrained Newton–Euler answer).
/// λ's moments are about each Bcm and expressed in W. The system is solved by LDLᵀ; when it
/// is singular (redundant constraints, e.g. two coaxial hinges) the least-norm multipliers
/// come from a complete orthogonal decomposition (or, on the sparse path, from the same
/// least-norm problem solved sparsely: docs/design.md) and Data::constraint_rank says so; when no
/// multipliers satisfy it (inconsistent constraints) an InputError names the constraints.
///
/// Drift: integrating u̇ lets g(q) and J u - b wander by the truncation error. After every
/// accepted step the integrators project the state back (ProjectOntoConstraints): positions
/// by Gauss–Newton with the same Jacobians, δx = -M⁻¹Gᵀ(G M⁻¹Gᵀ)⁺ g (the mass-weighted
/// closest point, so the correction does not favour light bodies), then velocities by
/// δu = -M⁻¹Jᵀ(J M⁻¹Jᵀ)⁺(J u - b) (exact in one step: the rows are linear in u). No
/// Baumgarte terms: they change the dynamics and need tuning.

#include "chasles/model/data.h"
#include "chasles/model/model.h"
#include "chasles/model/state.h"

namespace chasles {

/// Fills Data::constraint_rows, J, velocity_rhs, acceleration_rhs and position_error at
/// `state` (needs the kinematics stage, CalcKinematics).
void CalcConstraintRows(const Model& model, const State& state, Data& data);

/// The constraint stage (called by CalcAccelerations for models with constraints): takes the
/// free accelerations in Data, solves for λ, and overwrites Data::a_WBcm_W and
/// Data::wdot_WB_B with the constrained ones; fills Data::lambda, Data::constraints and
/// Data::constraint_rank. Throws InputError for inconsistent constraints.
void SolveConstraintForces(const Model& model, const State& state, Data& data);

struct ConstraintViolation {
  /// Largest |g| of the holonomic rows [m, or dimensionless for axis rows].
  double position = 0.0;
  /// Largest |J u - b| over all rows [m/s or rad/s].
  double velocity = 0.0;
  /// Constraint with the largest violation of either kind (-1 when there are none).
  int worst = -1;
};

/// How far `state` is from the constraint manifold (fills the kinematics stage and the rows).
ConstraintViolation CalcConstraintViolation(const Model& model, const State& state, Data& data);

struct ProjectionOptions {
  /// Stop the Gauss–Newton iteration when every holonomic |g| is below this [m].
  double position_tolerance = 1e-13;
  /// Most Gauss–Newton iterations per projection.
  int max_iterations = 6;
  /// A position error still above this after max_iterations is an InputError (the
  /// constraints cannot be assembled) [m].
  double assembly_tolerance = 1e-8;
};

/// Projects `state` onto the constraint manifold: positions (Gauss–Newton, mass-weighted),
/// then velocities (exact). Leaves models without constraints unchanged. Throws InputError
/// naming the constraint when the positions cannot be assembled.
///
/// With `velocity_impulse` given it receives the multipliers μ of the velocity step, one per
/// constraint row, signed as the constraint stage's λ: du = M⁻¹ Jᵀ μ. At an impulsive instant
/// this step is the ideal supports' response (chapter 8.5, eqs. 8.118-8.119 with the supports'
/// impulse Jᵀ μ on the right: M du = Jᵀ μ with J (u + du) = b), so μ are the supports'
/// impulsive reactions [N·s or N·m·s per row]; zero when the velocities were on the
/// constraints already. CalcConstraintReactions turns them into each constraint's reaction.
void ProjectOntoConstraints(const Model& model, State& state, Data& data,
                            const ProjectionOptions& options = {},
                            Eigen::VectorXd* velocity_impulse = nullptr);

/// Sets Data::lambda to `lambda` (one multiplier per constraint row) and fills Data::constraints
/// from it at `state`, as the constraint stage does from its own λ: each constraint's share of
/// Jᵀλ on its child, moved to the joint point, in W and in the child's frame, and its power
/// λᵀ J u. For multipliers found elsewhere, such as the velocity impulse of
/// ProjectOntoConstraints (the reactions are then impulses: N·s and N·m·s). Needs the rows at
/// `state` (CalcKinematics, then CalcConstraintRows).
void CalcConstraintReactions(const Model& model, const State& state, const Eigen::VectorXd& lambda,
                             Data& data);

}  // namespace chasles
