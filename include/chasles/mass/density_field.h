#pragma once
/// @file
/// Mass properties of a solid whose density varies from point to point (eq. 8.6 and the
/// inertia integrals of eq. 8.16 with dm = rho dV), for instance a graded or layered part.

#include <functional>
#include <limits>

#include "chasles/mass/mass_properties.h"
#include "chasles/mass/shape.h"
#include "chasles/math/types.h"

namespace chasles {

/// What IntegrateDensity did.
struct DensityIntegrationReport {
  /// Estimated relative error of the result (mass relative to the mass, first moments to
  /// mass times the radius of gyration, second moments to their trace) [-].
  double estimated_relative_error = std::numeric_limits<double>::quiet_NaN();
  /// Number of times the density was evaluated.
  long evaluations = 0;
  /// Number of sub-boxes of the unit cube the final estimate was summed over.
  int regions = 0;
};

/// Mass properties, in the solid's frame S, of the density field `rho` [kg/m³] (a function of
/// the point p_S [m]) over the volume of `solid`: the mass, the centre of mass and the
/// inertia about it, from the ten integrals ∫ rho {1, x, y, z, xx, yy, zz, xy, xz, yz} dV.
///
/// The integrals are taken over the solid's unit-cube map (Shape::MapUnitCube) by adaptive
/// cubature until the estimated relative error is at most `rel_tol` (1e-14 <= rel_tol < 1).
/// Smooth fields converge fast; a density that jumps across a surface that is not a
/// coordinate surface of the map converges slowly: split such a part into pieces instead.
///
/// Throws InputError when the solid is thin, when rho is negative or not finite at a point
/// where it is evaluated (naming the point), when the total mass is zero, or when the
/// tolerance is not reached within the evaluation budget (naming what was reached).
/// `report`, when given, receives the estimated error and the work done.
MassProperties IntegrateDensity(const Shape& solid,
                                const std::function<double(const Vec3& p_S)>& rho,
                                double rel_tol = 1e-10, DensityIntegrationReport* report = nullptr);

}  // namespace chasles
