#pragma once
/// @file
/// Newton–Euler equations of free rigid bodies (chapter 8.3): for every body
///   m a_Bcm = ΣF                            (eqs. 8.76-8.78)
///   I ẇ + w × (I w) = ΣM_Bcm                (Euler's equations, eqs. 8.75-8.81, in B)
/// with the full inertia tensor I about Bcm in B (non-principal frames included), solved with
/// its precomputed inverse. The three stages fill the Data fields named after them.

#include "chasles/model/data.h"
#include "chasles/model/model.h"
#include "chasles/model/state.h"

namespace chasles {

/// Position/velocity stage: Data::R_WB and Data::w_WB_W.
void CalcKinematics(const Model& model, const State& state, Data& data);

/// Force stage (needs the kinematics stage): Data::F_Bcm_W, Data::M_Bcm_W, Data::elements.
void CalcForces(const Model& model, const State& state, Data& data);

/// All three stages: kinematics, forces, then Data::a_WBcm_W and Data::wdot_WB_B; for a model
/// with constraints also the constraint stage (SolveConstraintForces in constraint_solve.h),
/// so the accelerations are the constrained ones and Data::constraints holds the reactions.
void CalcAccelerations(const Model& model, const State& state, Data& data);

/// Body-frame angular acceleration from Euler's equations with the full tensor:
/// ẇ = I⁻¹ (M_B - w × (I w)) [rad/s²].
Vec3 CalcEulerAngularAcceleration(const Mat3& I_BBcm_B, const Mat3& I_inverse, const Vec3& w_WB_B,
                                  const Vec3& M_Bcm_B);

}  // namespace chasles
