#include "chasles/mass/shape.h"

#include <cmath>

#include <fmt/format.h>

#include "chasles/error.h"

namespace chasles {

std::string Shape::Describe() const {
  std::string out(kind());
  out += " (";
  bool first = true;
  for (const ShapeDimension& d : dimensions()) {
    if (!first) out += ", ";
    first = false;
    out += fmt::format("{} {:.6g} m", d.name, d.value);
  }
  if (closed()) out += ", closed";
  out += ")";
  return out;
}

MassProperties Shape::CalcMassProperties(double mass) const {
  if (!(std::isfinite(mass) && mass > 0.0)) {
    throw InputError(fmt::format("{}: mass {:.6g} kg must be positive and finite", kind(), mass));
  }
  // Uniform density: the centre of mass is the centroid and the inertia scales with the mass.
  return MassProperties(mass, CalcCentroid(), CalcUnitInertia() * mass);
}

void Shape::MapUnitCube(const Vec3& /*u*/, Vec3* /*p_S*/, double* /*jacobian*/) const {
  const char* what = measure() == Measure::kLength ? "a curve" : "a surface";
  throw InputError(fmt::format(
      "{}: a thin shape is {} with no volume, so a density per unit volume cannot be integrated "
      "over it; give it a mass, or model it as a solid of finite thickness",
      kind(), what));
}

}  // namespace chasles
