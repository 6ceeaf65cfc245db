#pragma once
/// @file
/// A free rigid body of a Model. The user states its mass properties in its own frame B with
/// origin Bo (e.g. a CAD frame). Internally the dynamics work at the centre of mass Bcm with
/// B's axes unchanged, so the inertia tensor is kept full: a non-principal body frame is as
/// correct as a principal one (the gyroscopic term w x (I w) uses the full tensor).

#include <string>

#include "chasles/mass/mass_properties.h"
#include "chasles/math/types.h"

namespace chasles {

/// Index of a body in its Model (0, 1, ...). kWorld stands for the fixed world frame where a
/// force element connects a body to the ground.
using BodyIndex = int;
inline constexpr BodyIndex kWorld = -1;

class Body {
 public:
  /// Validates `mass_properties` (positive mass, physically valid inertia) and requires an
  /// invertible inertia: a free body with a zero principal moment (an ideal slender rod) has
  /// no defined spin about that axis, so it cannot be simulated. Throws InputError.
  Body(std::string name, const MassProperties& mass_properties);

  /// Name used in messages and reports.
  const std::string& name() const { return name_; }
  /// Mass properties as given, in B about Bo's frame [kg, m, kg·m²].
  const MassProperties& mass_properties() const { return mass_properties_; }
  /// Mass [kg].
  double mass() const { return mass_; }
  /// Position of the centre of mass from Bo, in B [m].
  const Vec3& p_BoBcm_B() const { return p_BoBcm_B_; }
  /// Inertia about the centre of mass, expressed in B (full tensor) [kg·m²].
  const Mat3& I_BBcm_B() const { return I_BBcm_B_; }
  /// Inverse of I_BBcm_B, precomputed [1/(kg·m²)].
  const Mat3& I_BBcm_B_inverse() const { return I_inv_; }
  /// A point given from Bo in B, re-expressed from the centre of mass: p_BcmP_B [m].
  Vec3 PointFromCenterOfMass(const Vec3& p_BoP_B) const { return p_BoP_B - p_BoBcm_B_; }

 private:
  std::string name_;
  MassProperties mass_properties_;
  double mass_;
  Vec3 p_BoBcm_B_;
  Mat3 I_BBcm_B_;
  Mat3 I_inv_;
};

}  // namespace chasles
