#pragma once
/// @file
/// Linearisation about an operating point on the constraint manifold (docs/modes.md).
///
/// In maximal coordinates each body's perturbation is x_b = [δp; δθ; δv; δω] (δθ a small
/// rotation about W's axes, R = exp(δθ) R₀; δω in W), in the frame that moves with the steady
/// motion's generator ξ (operating_point.h). The equations M u̇ = f + Aᵀλ with the rows
/// A(q) u = 0 and the holonomic g(q) = 0 are linearised as a descriptor system
///   δq̇ = K δq + δu                                  (K = -∂(ξ·q)/∂q)
///   M₀ δu̇ = -∂r/∂q δq - ∂r/∂u δu - M₀ (ω_ξ ×) δu + A₀ᵀ δλ,   r = M(q) u̇₀ - f(q, u) - A(q)ᵀλ₀
///   G δq = 0,   A₀ δu + ∂(A(q) u₀)/∂q δq = 0
/// whose Jacobians are exact (forward-mode dual numbers over the equations written once,
/// analysis/internal/linear_kernels.h). The constraints leave a subspace z = V w of dimension
/// m + p (m minimal coordinates, p independent speeds; p < m with nonholonomic rolling); the
/// differential equations restricted to it, solved for ẇ and δλ by least squares (exactly:
/// they are consistent), give ẇ = A_w w. The state is then expressed in named coordinates of
/// the scene — joint angles and slides first, then bodies' rotations and positions — chosen
/// greedily to be independent on the subspace: x = [coordinates; speeds], ẋ = A x.

#include <limits>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "chasles/analysis/operating_point.h"

namespace chasles {

/// A named coordinate of the reduced state.
struct LinearCoordinate {
  /// "steer" (a joint's angle or slide), "frame.rx" (a body's small rotation about W's x),
  /// "frame.x" (its centre of mass's position), "system.x" (the whole system's centre of mass,
  /// first when nothing ties it to the world); a speed is named "d(steer)/dt", the rate of its
  /// coordinate.
  std::string name;
  /// "rad", "m", "rad/s" or "m/s".
  std::string unit;
};

struct Linearization {
  /// ẋ = A x, x = [coordinates; speeds] [SI].
  Eigen::MatrixXd A;
  /// The m minimal coordinates and the p independent speeds.
  std::vector<LinearCoordinate> coordinates, speeds;
  /// Maximal perturbation (12 per body, see the file comment) of a unit value of each entry of
  /// x (12 n × (m + p)).
  Eigen::MatrixXd basis;
  /// Relative residual of the least-squares solve of the reduced equations (round-off for a
  /// true operating point and consistent constraints).
  double consistency = 0.0;
  /// With LinearizeOptions::finite_difference_check: the largest difference between A's
  /// columns and central differences (step 1e-6) of the engine's own accelerations
  /// (CalcAccelerations, not the kernels), relative to the largest column; NaN when not asked.
  double finite_difference_check = std::numeric_limits<double>::quiet_NaN();
};

struct LinearizeOptions {
  bool finite_difference_check = false;
};

/// Linearises `model` about `op`. Throws InputError naming an element the linearisation does
/// not handle (forces given as functions, gears, strings, drivers, unilateral contacts) and
/// for bodies without rotational inertia.
Linearization Linearize(const Model& model, const OperatingPoint& op,
                        const LinearizeOptions& options = {});

}  // namespace chasles
