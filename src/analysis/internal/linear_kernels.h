#pragma once
/// @file
/// The equations of motion of a Model written once over a scalar type T (double, or Dual for
/// the exact first derivatives of analysis/linearize.h): at a configuration q and velocity u
/// perturbed from a base state by x = [δq; δu] (per body δq = [δp_WBcm; δθ_W],
/// R = (E + [δθ]×) R₀, exact to first order, which is all a Dual carries; δu = [δv; δω_W]):
///   A(q)      the constraint rows on u = [v_WBcm_W; w_WB_W] (docs/constraints.md), built from
///             the same three primitives as the engine's rows: a material point's velocity
///             along a direction, a relative angular velocity along a direction;
///   f(q, u)   the generalised applied force [ΣF_W; ΣM_Bcm_W - w × (I_W w)];
///   M(q) u̇₀  the inertia times a fixed acceleration u̇₀ (M = diag(m E, R I_B Rᵀ)).
/// Only the elements whose equations are written here can be linearised; the others are
/// refused by name (CheckLinearisable).

#include <string>
#include <vector>

#include <Eigen/Core>

#include "chasles/model/model.h"
#include "chasles/model/state.h"

namespace chasles::internal {

template <class T>
using V3 = Eigen::Matrix<T, 3, 1>;
template <class T>
using M3 = Eigen::Matrix<T, 3, 3>;
template <class T>
using VecX = Eigen::Matrix<T, Eigen::Dynamic, 1>;
template <class T>
using MatX = Eigen::Matrix<T, Eigen::Dynamic, Eigen::Dynamic>;

/// The base state the perturbations start from, with its inertial accelerations (SI).
struct LinearBase {
  std::vector<Vec3> p, v, w_W, a, alpha_W;
  std::vector<Mat3> R;
};

/// Throws InputError naming the first force element or constraint whose equations are not
/// written here (and the bodies that have no rotational inertia).
void CheckLinearisable(const Model& model);

/// The kernels' outputs at one perturbation.
template <class T>
struct KernelOutput {
  MatX<T> A;    ///< rows × 6n
  VecX<T> f;    ///< 6n
  VecX<T> Mud;  ///< 6n: M(q) u̇₀
};

/// Evaluates A, f and M u̇₀ at base + x (x of size 12n, see the file comment).
template <class T>
void EvaluateKernels(const Model& model, const LinearBase& base, const VecX<T>& x,
                     KernelOutput<T>& out);

}  // namespace chasles::internal
