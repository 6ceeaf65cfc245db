#pragma once
/// @file
/// A free rigid body of a Model. The user states its mass properties in its own frame B with
/// origin Bo (e.g. a CAD frame). Internally the dynamics work at the centre of mass Bcm with
/// B's axes unchanged, so the inertia tensor is kept full: a non-principal body frame is as
/// correct as a principal one (the gyroscopic term w x (I w) uses the full tensor).
///
/// Bodies with zero principal moments are exact, not thickened (docs/design.md, "Particles and
/// slender bodies"). A zero moment means all the mass lies on a line through Bcm (a slender rod,
/// points on a line): then the other two moments are equal, I = I⊥ (E - a aᵀ) with a the line's
/// direction. The spin a·w is not a degree of freedom: the mass matrix has no row for it, I⁺
/// (the Moore–Penrose pseudo-inverse, (E - a aᵀ)/I⊥) stands for I⁻¹ everywhere, so a·w keeps
/// its initial value, which must be 0. All three moments zero is a particle: I⁺ = 0 and w = 0.

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
  /// Validates `mass_properties` (positive mass, physically valid inertia). Principal moments
  /// below 1e-12 of the largest one count as zero (rounding of a point-mass sum). Throws
  /// InputError.
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
  /// Inverse of I_BBcm_B, precomputed [1/(kg·m²)]; the pseudo-inverse I⁺ when a principal
  /// moment is zero (it maps onto the rotations that have inertia, and the spin about a
  /// zero-moment axis to 0).
  const Mat3& I_BBcm_B_inverse() const { return I_inv_; }
  /// Number of principal moments that are zero: 0 (a rigid body), 1 (mass on a line: a slender
  /// rod) or 3 (a particle).
  int num_zero_moments() const { return num_zero_moments_; }
  /// Whether all the mass is at one point (no rotational inertia).
  bool is_particle() const { return num_zero_moments_ == 3; }
  /// Projector onto the angular velocities that are degrees of freedom, in B: E, E - a aᵀ, or 0.
  const Mat3& free_rotation_B() const { return P_free_; }
  /// A point given from Bo in B, re-expressed from the centre of mass: p_BcmP_B [m].
  Vec3 PointFromCenterOfMass(const Vec3& p_BoP_B) const { return p_BoP_B - p_BoBcm_B_; }

 private:
  std::string name_;
  MassProperties mass_properties_;
  double mass_;
  Vec3 p_BoBcm_B_;
  Mat3 I_BBcm_B_;
  Mat3 I_inv_;
  Mat3 P_free_;
  int num_zero_moments_ = 0;
};

}  // namespace chasles
