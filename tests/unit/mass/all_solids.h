#pragma once
/// @file
/// The solids of Appendix A with moderate, unequal dimensions, for tests that must hold for
/// every solid shape.

#include <memory>
#include <vector>

#include "chasles/mass/shape.h"

namespace chasles::test {

inline std::vector<std::unique_ptr<Shape>> AllSolids() {
  std::vector<std::unique_ptr<Shape>> v;
  v.push_back(MakeSolidCylinder(0.3, 0.8));
  v.push_back(MakeTube(0.2, 0.3, 0.8));
  v.push_back(MakeSolidSphere(0.3));
  v.push_back(MakeThickSphericalShell(0.2, 0.3));
  v.push_back(MakeSolidHemisphere(0.3));
  v.push_back(MakeSolidCone(0.3, 0.8));
  v.push_back(MakeHollowCone(0.3, 0.8, 0.05));
  v.push_back(MakeHollowCone(0.3, 0.8, 0.05, /*closed=*/true));
  v.push_back(MakeBox(0.5, 0.3, 1.1));
  v.push_back(MakeEllipsoid(0.5, 0.3, 1.1));
  v.push_back(MakeTorus(0.3, 0.1));
  v.push_back(MakeTriangularPrism({0.1, 0.2}, {0.7, 0.3}, {0.2, 0.9}, 0.4));
  return v;
}

}  // namespace chasles::test
