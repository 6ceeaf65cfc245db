#include "chasles/model/body.h"

#include <fmt/format.h>

#include "chasles/error.h"

namespace chasles {

Body::Body(std::string name, const MassProperties& mp)
    : name_(std::move(name)), mass_properties_(mp) {
  const std::string what = fmt::format("body '{}'", name_);
  mp.Validate(what);
  mass_ = mp.mass();
  p_BoBcm_B_ = mp.p_BoBcm_B();
  I_BBcm_B_ = mp.I_BBcm_B().matrix();
  // Validate() accepts a zero principal moment (the slender-rod limit); the Euler equations
  // need I⁻¹, so a free body must have all three moments positive.
  const double I_min = mp.I_BBcm_B().CalcPrincipalAxes().moments.minCoeff();
  if (!(I_min > 1e-12 * I_BBcm_B_.trace())) {
    throw InputError(fmt::format(
        "{}: smallest principal moment of inertia is {:.6g} kg·m² (trace {:.6g}); a free body "
        "needs all three positive to have a defined spin: give the rod or plate a thickness",
        what, I_min, I_BBcm_B_.trace()));
  }
  I_inv_ = I_BBcm_B_.inverse();
}

}  // namespace chasles
