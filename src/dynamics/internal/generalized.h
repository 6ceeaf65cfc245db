#pragma once
/// @file
/// Helpers over the generalised velocity u_b = [v_WBcm_W; w_WB_W] (6 per body) shared by the
/// constraint solve, the contact solve and the contact projection.

#include <vector>

#include <Eigen/Core>

#include "chasles/model/data.h"
#include "chasles/model/model.h"
#include "chasles/model/state.h"

namespace chasles::internal {

/// Y = X M⁻¹ for 6 columns per body.
void TimesMassInverse(const Model& model, const Data& data, const Eigen::MatrixXd& X,
                      Eigen::MatrixXd& Y);
/// Generalised velocity u = [v_WBcm_W; w_WB_W] per body.
void GetVelocity(const Model& model, const State& state, const Data& data, Eigen::VectorXd& u);
/// Writes u back into the state (angular velocity re-expressed in B).
void SetVelocity(const Model& model, const Data& data, const Eigen::VectorXd& u, State& state);
/// Rows of released constraints (Data::row_released) in a system A x = r over the constraint
/// rows first (A = J M⁻¹ Wᵀ; further rows, e.g. contact rows, follow): such a row of J is zero,
/// so A has a zero row and column there; they become x_k = 0 (A_kk = 1, r_k = 0), which keeps
/// the system regular and the multiplier of a slack string at 0.
void HoldReleasedRows(const std::vector<char>& released, Eigen::MatrixXd& A, Eigen::VectorXd& r);
/// Writes the rows of constraint c (Data::constraint_rows, after CalcConstraintRows) into its
/// rows of `J` (num_constraint_rows × 6 num_bodies): its blocks on the parent, the child and
/// any further bodies, in that order; a released constraint's rows are left as they are (zero).
void WriteConstraintBlocks(const Model& model, const Data& data, int c,
                           Eigen::Ref<Eigen::MatrixXd> J);
/// Data::J for a dense consumer (a dense factorisation over the constraint rows): sizes it and
/// fills it from Data::constraint_rows (after CalcConstraintRows; released rows zero) unless
/// it is sized already, entry for entry the matrix MakeData and CalcConstraintRows keep below
/// kSparseMinRows rows. Sized, it is kept current by CalcConstraintRows from then on.
void EnsureDenseJacobian(const Model& model, Data& data);
/// J x over the constraint rows into `out` (num_constraint_rows): below kSparseMinRows rows the
/// dense product with Data::J (MakeData sizes it there: the dense path's numbers), otherwise by
/// each constraint's own blocks in Data::constraint_rows (zero for a released one), O(rows).
void ConstraintJacobianTimes(const Model& model, const Data& data, const Eigen::VectorXd& x,
                             Eigen::Ref<Eigen::VectorXd> out);
/// Total kinetic energy [J].
double KineticEnergy(const Model& model, const State& state);
/// Data::constraints from the constraint multipliers in Data::lambda and the rows in
/// Data::constraint_rows: the child's share of Jᵀλ is a force at Bcm and a moment about Bcm
/// (in W), moved to the joint point J: M_J = M_Bcm - (p_WJ - p_WBcm) × F; also in the
/// child's frame B, and each constraint's power λᵀ J u. Fills Data::u and Data::Ju.
void FillConstraintReactions(const Model& model, const State& state, Data& data);

}  // namespace chasles::internal
