#include "chasles/mass/mass_properties.h"

#include <cmath>

#include <fmt/format.h>

#include "chasles/error.h"

namespace chasles {

MassProperties::MassProperties()
    : mass_(std::numeric_limits<double>::quiet_NaN()),
      p_BoBcm_B_(Vec3::Constant(std::numeric_limits<double>::quiet_NaN())) {}

MassProperties::MassProperties(double mass, const Vec3& p_BoBcm_B,
                               const RotationalInertia& I_BBcm_B)
    : mass_(mass), p_BoBcm_B_(p_BoBcm_B), I_BBcm_B_(I_BBcm_B) {}

MassProperties MassProperties::Zero() {
  return MassProperties(0.0, Vec3::Zero(), RotationalInertia::Zero());
}

MassProperties MassProperties::PointMass(double mass, const Vec3& p_BoP_B) {
  return MassProperties(mass, p_BoP_B, RotationalInertia::Zero());
}

RotationalInertia MassProperties::CalcInertiaAbout(const Vec3& p_BoP_B) const {
  return I_BBcm_B_.ShiftFromCenterOfMass(mass_, p_BoBcm_B_ - p_BoP_B);
}

MassProperties MassProperties::ExpressedInParent(const Mat3& R_BP, const Vec3& p_BoPo_B) const {
  return MassProperties(mass_, p_BoPo_B + R_BP * p_BoBcm_B_, I_BBcm_B_.ReExpressedIn(R_BP));
}

MassProperties MassProperties::operator+(const MassProperties& o) const {
  if (mass_ == 0.0) return o;
  if (o.mass_ == 0.0) return *this;
  const double m = mass_ + o.mass_;
  // A total this close to zero relative to the parts means the cut-outs remove (almost) all
  // the material: there is no body left to have a centre of mass.
  if (!(m > 1e-12 * (std::abs(mass_) + std::abs(o.mass_)))) {
    throw InputError(fmt::format(
        "the parts add up to a mass of {:.6g} kg (from {:.6g} kg and {:.6g} kg); subtractive "
        "parts cannot remove more material than the body has",
        m, mass_, o.mass_));
  }
  // Eq. 8.4 written relative to this part's centre so that parts far from B's origin lose no
  // digits: the offsets of each centre from the combined one come from their difference alone.
  const Vec3 delta = o.p_BoBcm_B_ - p_BoBcm_B_;
  const Vec3 d_this = -(o.mass_ / m) * delta;  // this centre relative to the combined one
  const Vec3 d_other = (mass_ / m) * delta;    // the other centre relative to the combined one
  const Vec3 c = p_BoBcm_B_ - d_this;
  const RotationalInertia I = I_BBcm_B_.ShiftFromCenterOfMass(mass_, d_this) +
                              o.I_BBcm_B_.ShiftFromCenterOfMass(o.mass_, d_other);
  return MassProperties(m, c, I);
}

MassProperties MassProperties::Negated() const {
  return MassProperties(-mass_, p_BoBcm_B_, I_BBcm_B_ * -1.0);
}

void MassProperties::Validate(std::string_view what) const {
  if (!std::isfinite(mass_) || !(mass_ > 0.0)) {
    throw InputError(
        fmt::format("{}: mass is {:.6g} kg; a body needs a positive, finite mass", what, mass_));
  }
  if (!p_BoBcm_B_.allFinite()) {
    throw InputError(fmt::format("{}: the centre of mass is not a finite point", what));
  }
  I_BBcm_B_.Validate(what);
}

}  // namespace chasles
