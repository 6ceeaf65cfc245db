#pragma once
/// @file
/// Unit-quaternion helpers for orientation integration. Quaternions are written (w, x, y, z)
/// whenever chasles reads or prints them; `Quat` (Eigen) stores them differently in memory and
/// that order never leaves this layer. `q_AB` rotates vectors expressed in B into A, like R_AB.

#include <Eigen/Core>

#include "chasles/math/types.h"

namespace chasles {

/// Quaternion from its components in (w, x, y, z) order (not normalised).
Quat QuatFromWxyz(double w, double x, double y, double z);
/// Components of `q` in (w, x, y, z) order.
Eigen::Vector4d QuatToWxyz(const Quat& q);

/// Exponential map: the unit quaternion of a rotation by |v| [rad] about v/|v|,
/// (cos(|v|/2), sin(|v|/2) v/|v|). Accurate for small |v| (series below 1e-4 rad).
Quat QuatExp(const Vec3& rotation_vector);
/// Inverse of QuatExp on the short way round: the rotation vector [rad] with angle in [0, pi].
Vec3 QuatLog(const Quat& q);

/// Cayley map: the unit quaternion (1, g)/sqrt(1 + |g|²) of the rotation whose Gibbs vector
/// is g = tan(angle/2) axis. Its matrix is (E - [g]x)^-1 (E + [g]x).
Quat QuatFromGibbs(const Vec3& g);

/// Orientation after holding the body-frame angular velocity `w_WB_B` [rad/s] constant for
/// `dt` [s]: q_WB(t + dt) = q_WB(t) ⊗ exp(w_WB_B dt). Exact for constant body-frame angular
/// velocity; the result is renormalised so that the norm never drifts.
Quat IntegrateBodyAngularVelocity(const Quat& q_WB, const Vec3& w_WB_B, double dt);

/// Time derivative of q_WB for body-frame angular velocity w_WB_B: q̇ = ½ q ⊗ (0, w).
/// Both in (w, x, y, z) order; `q` need not be unit (the map is linear in q).
Eigen::Vector4d QuatDerivativeWxyz(const Eigen::Vector4d& q_wxyz, const Vec3& w_WB_B);

}  // namespace chasles
