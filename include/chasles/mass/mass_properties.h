#pragma once
/// @file
/// Mass properties of a body or a part: mass, centre of mass and inertia about the centre of
/// mass, all expressed in the body's (or part's) own frame B. They combine (composite bodies,
/// eqs. 8.4-8.6 and 8.29) and subtract (holes, cut-outs).

#include <limits>
#include <string_view>

#include "chasles/mass/rotational_inertia.h"
#include "chasles/math/types.h"

namespace chasles {

class MassProperties {
 public:
  /// NaN everywhere, so that a value never set shows.
  MassProperties();
  /// `mass` [kg], centre of mass `p_BoBcm_B` [m] and `I_BBcm_B` [kg·m²] about it, all in B.
  /// A negative mass is allowed here (a subtractive part); Validate() a finished body.
  MassProperties(double mass, const Vec3& p_BoBcm_B, const RotationalInertia& I_BBcm_B);

  static MassProperties Zero();
  static MassProperties PointMass(double mass, const Vec3& p_BoP_B);

  /// Mass [kg].
  double mass() const { return mass_; }
  /// Position of the centre of mass from B's origin, expressed in B [m].
  const Vec3& p_BoBcm_B() const { return p_BoBcm_B_; }
  /// Inertia about the centre of mass, expressed in B [kg·m²].
  const RotationalInertia& I_BBcm_B() const { return I_BBcm_B_; }

  /// Inertia about the point P (position p_BoP_B from B's origin), expressed in B (eq. 8.29).
  RotationalInertia CalcInertiaAbout(const Vec3& p_BoP_B) const;

  /// These properties belong to a part whose frame P sits at p_BoPo_B in B, rotated by R_BP;
  /// returns them expressed in B.
  MassProperties ExpressedInParent(const Mat3& R_BP, const Vec3& p_BoPo_B) const;

  /// Sum of two mass distributions (a composite body). The result's centre of mass is the
  /// mass-weighted mean (eq. 8.4); its inertia is each part's shifted to it (eq. 8.29).
  /// Either side may have negative mass (a hole); throws InputError when the total mass is
  /// zero or negative, since no centre of mass exists then.
  MassProperties operator+(const MassProperties& other) const;
  /// The same distribution with negative mass: adding it removes material.
  MassProperties Negated() const;

  /// Throws InputError ("<what>: ...") unless mass > 0 and finite, the centre of mass is
  /// finite and the inertia is physically valid.
  void Validate(std::string_view what) const;

 private:
  double mass_;
  Vec3 p_BoBcm_B_;
  RotationalInertia I_BBcm_B_;
};

}  // namespace chasles
