#pragma once
/// @file
/// Kinetic energy and momenta of a model's bodies at one state (chapter 8.4, 8.5).

#include "chasles/model/model.h"
#include "chasles/model/state.h"

namespace chasles {

/// Translational kinetic energy Σ ½ m |v_Bcm|² (eq. 8.115) [J].
double CalcTranslationalKineticEnergy(const Model& model, const State& state);
/// Rotational kinetic energy Σ ½ w_Bᵀ I_Bcm w_B (eq. 8.115) [J].
double CalcRotationalKineticEnergy(const Model& model, const State& state);
/// Linear momentum Σ m v_Bcm, in W [kg·m/s].
Vec3 CalcLinearMomentum(const Model& model, const State& state);
/// Centre of mass of all bodies, in W [m].
Vec3 CalcSystemCenterOfMass(const Model& model, const State& state);
/// Angular momentum about the world point p_WQ, Σ [R I_Bcm w_B + (p_Bcm - p_Q) × m v_Bcm], in W
/// [kg·m²/s].
Vec3 CalcAngularMomentum(const Model& model, const State& state, const Vec3& p_WQ);

}  // namespace chasles
