#pragma once
/// @file
/// Data: a workspace of derived, recomputable quantities for one Model. Each field says which
/// step fills it. Make it once with MakeData and reuse it: the hot loops never allocate.

#include <vector>

#include "chasles/math/types.h"

namespace chasles {

class Model;

/// What one force element did at the evaluated state (filled by CalcForces).
struct ForceElementOutput {
  /// Power of all its forces and moments on all bodies [W].
  double power = 0.0;
  /// Power of its non-conservative part [W] (equal to `power` unless it has a potential).
  double power_nonconservative = 0.0;
  /// Sum of its forces, in W [N].
  Vec3 force_W = Vec3::Zero();
  /// Sum of the moments of its forces about the world origin plus its pure moments, in W [N·m].
  Vec3 moment_Wo_W = Vec3::Zero();
};

struct Data {
  // --- Position and velocity stage: CalcKinematics(model, state, data) ---
  /// Rotation matrix of each body, R_WB (from the normalised quaternion).
  std::vector<Mat3> R_WB;
  /// Angular velocity of each body, expressed in W [rad/s].
  std::vector<Vec3> w_WB_W;

  // --- Force stage: CalcForces(model, state, data) ---
  /// Resultant force on each body, in W [N].
  std::vector<Vec3> F_Bcm_W;
  /// Resultant moment about each body's centre of mass, in W [N·m].
  std::vector<Vec3> M_Bcm_W;
  /// Per force element (Model order).
  std::vector<ForceElementOutput> elements;

  // --- Acceleration stage: CalcAccelerations(model, state, data) ---
  /// Acceleration of each centre of mass, in W [m/s²].
  std::vector<Vec3> a_WBcm_W;
  /// Angular acceleration of each body, expressed in B [rad/s²].
  std::vector<Vec3> wdot_WB_B;
};

/// A Data sized for `model`.
Data MakeData(const Model& model);

}  // namespace chasles
