#include "chasles/model/body.h"

#include <algorithm>

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
  // Validate() accepts zero principal moments (the slender-rod and point-mass limits). With
  // principal axes e_k and moments I_k, I⁺ = Σ_{I_k > 0} e_k e_kᵀ / I_k and the projector onto
  // the rotations with inertia P = Σ_{I_k > 0} e_k e_kᵀ (docs/design.md). A zero moment puts
  // all the mass on a line through Bcm (I_k = Σ m d_k², d_k the distance from axis k), so the
  // count is 0, 1 or 3: two zero moments force the third to 0 too.
  const PrincipalAxes pa = mp.I_BBcm_B().CalcPrincipalAxes();
  const double I_max = pa.moments.maxCoeff();
  // Zero to rounding: of the moments, and of the parallel-axis shift m |p_BoBcm|² that moved a
  // point mass given off Bo to its own centre.
  const double zero = 1e-12 * std::max(I_max, mass_ * p_BoBcm_B_.squaredNorm());
  I_inv_.setZero();
  P_free_.setZero();
  num_zero_moments_ = 0;
  for (int k = 0; k < 3; ++k) {
    const Vec3 e = pa.axes.col(k);
    if (pa.moments[k] > zero) {
      I_inv_ += e * e.transpose() / pa.moments[k];
      P_free_ += e * e.transpose();
    } else {
      ++num_zero_moments_;
    }
  }
  if (num_zero_moments_ == 2) {
    // Only through rounding of a degenerate tensor; a physical one has 0, 1 or 3.
    throw InputError(fmt::format(
        "{}: two principal moments of inertia are zero and the third is {:.6g} kg·m², which no "
        "mass distribution has; give the inertia of a rod (one zero moment) or a point mass",
        what, I_max));
  }
  if (num_zero_moments_ == 0) I_inv_ = I_BBcm_B_.inverse();
}

}  // namespace chasles
