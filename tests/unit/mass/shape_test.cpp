#include "chasles/mass/shape.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <memory>
#include <numbers>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "chasles/error.h"
#include "chasles/math/rotation.h"
#include "test_support.h"
#include "unit/mass/all_solids.h"

namespace chasles {
namespace {

using test::AllSolids;

using std::numbers::pi;
using test::kExact;
using test::MatNear;
using test::Near;
using ::testing::HasSubstr;

// Compares a shape's measure, centroid and unit inertia with values from Appendix A.
void ExpectShape(const Shape& s, Shape::Measure measure, double size, const Vec3& centroid,
                 const RotationalInertia& unit_inertia, double scale) {
  SCOPED_TRACE(s.Describe());
  EXPECT_EQ(s.measure(), measure);
  EXPECT_TRUE(Near(s.CalcMeasure(), size, kExact));
  EXPECT_TRUE(MatNear(s.CalcCentroid(), centroid, kExact, scale));
  EXPECT_TRUE(MatNear(s.CalcUnitInertia().matrix(), unit_inertia.matrix(), kExact));
  EXPECT_EQ(s.CalcUnitInertia().CheckPhysicallyValid(), "");
  // Uniform mass m: properties scale with m and sit at the centroid.
  const double m = 3.5;
  const MassProperties mp = s.CalcMassProperties(m);
  EXPECT_EQ(mp.mass(), m);
  EXPECT_TRUE(MatNear(mp.I_BBcm_B().matrix(), m * unit_inertia.matrix(), kExact));
}

TEST(Shape, ThinShapesMatchAppendixA) {
  const double L = 1.3, R = 0.4, a = 0.6, b = 0.2, h = 0.9;
  using M = Shape::Measure;
  // Slender rod: I = m L²/12 about a perpendicular axis through the centre, 0 about its own.
  ExpectShape(*MakeSlenderRod(L), M::kLength, L, Vec3::Zero(),
              RotationalInertia(L * L / 12, L * L / 12, 0), L);
  // Hoop: Izz = m R², diametral m R²/2.
  ExpectShape(*MakeThinRing(R), M::kLength, 2 * pi * R, Vec3::Zero(),
              RotationalInertia(R * R / 2, R * R / 2, R * R), R);
  // Thin disk: Izz = m R²/2, diametral m R²/4.
  ExpectShape(*MakeThinDisk(R), M::kArea, pi * R * R, Vec3::Zero(),
              RotationalInertia(R * R / 4, R * R / 4, R * R / 2), R);
  // Thin plate a x b: Ixx = m b²/12, Iyy = m a²/12, Izz = m (a² + b²)/12.
  ExpectShape(*MakeThinPlate(a, b), M::kArea, a * b, Vec3::Zero(),
              RotationalInertia(b * b / 12, a * a / 12, (a * a + b * b) / 12), a);
  // Thin cylindrical shell: Izz = m R², Ixx = m R²/2 + m h²/12.
  ExpectShape(*MakeThinCylindricalShell(R, h), M::kArea, 2 * pi * R * h, Vec3::Zero(),
              RotationalInertia(R * R / 2 + h * h / 12, R * R / 2 + h * h / 12, R * R), R);
  // Thin spherical shell: I = (2/3) m R².
  ExpectShape(*MakeThinSphericalShell(R), M::kArea, 4 * pi * R * R, Vec3::Zero(),
              RotationalInertia(2 * R * R / 3, 2 * R * R / 3, 2 * R * R / 3), R);
}

TEST(Shape, SolidsOfRevolutionMatchAppendixA) {
  const double R = 0.3, Ri = 0.2, h = 0.8, r = 0.1;
  using M = Shape::Measure;
  // Solid cylinder: Izz = m R²/2, Ixx = m (3R² + h²)/12.
  ExpectShape(*MakeSolidCylinder(R, h), M::kVolume, pi * R * R * h, Vec3::Zero(),
              RotationalInertia((3 * R * R + h * h) / 12, (3 * R * R + h * h) / 12, R * R / 2), R);
  // Thick tube: Izz = m (Ro² + Ri²)/2, Ixx = m (3 (Ro² + Ri²) + h²)/12.
  const double s = R * R + Ri * Ri;
  ExpectShape(*MakeTube(Ri, R, h), M::kVolume, pi * (R * R - Ri * Ri) * h, Vec3::Zero(),
              RotationalInertia((3 * s + h * h) / 12, (3 * s + h * h) / 12, s / 2), R);
  // Solid sphere: (2/5) m R².
  ExpectShape(*MakeSolidSphere(R), M::kVolume, 4 * pi * std::pow(R, 3) / 3, Vec3::Zero(),
              RotationalInertia(0.4 * R * R, 0.4 * R * R, 0.4 * R * R), R);
  // Thick spherical shell: (2/5) m (Ro⁵ - Ri⁵)/(Ro³ - Ri³).
  const double Is = 0.4 * (std::pow(R, 5) - std::pow(Ri, 5)) / (std::pow(R, 3) - std::pow(Ri, 3));
  ExpectShape(*MakeThickSphericalShell(Ri, R), M::kVolume,
              4 * pi * (std::pow(R, 3) - std::pow(Ri, 3)) / 3, Vec3::Zero(),
              RotationalInertia(Is, Is, Is), R);
  // Hemisphere: centroid 3R/8 above the flat face; Ixx = Iyy = (83/320) m R², Izz = (2/5) m R².
  ExpectShape(*MakeSolidHemisphere(R), M::kVolume, 2 * pi * std::pow(R, 3) / 3,
              Vec3(0, 0, 3 * R / 8),
              RotationalInertia(83 * R * R / 320, 83 * R * R / 320, 0.4 * R * R), R);
  // Cone: centroid h/4 above the base; Izz = (3/10) m R², Ixx = (3/20) m R² + (3/80) m h².
  const double Ic = 3 * R * R / 20 + 3 * h * h / 80;
  ExpectShape(*MakeSolidCone(R, h), M::kVolume, pi * R * R * h / 3, Vec3(0, 0, h / 4),
              RotationalInertia(Ic, Ic, 3 * R * R / 10), h);
  // Torus: V = 2 pi² R r²; Izz = m (R² + (3/4) r²), Ixx = m (R²/2 + (5/8) r²).
  ExpectShape(
      *MakeTorus(R, r), M::kVolume, 2 * pi * pi * R * r * r, Vec3::Zero(),
      RotationalInertia(R * R / 2 + 5 * r * r / 8, R * R / 2 + 5 * r * r / 8, R * R + 0.75 * r * r),
      R);
}

TEST(Shape, BoxAndEllipsoidMatchAppendixA) {
  const double a = 0.5, b = 0.3, c = 1.1;
  using M = Shape::Measure;
  // Box: Ixx = m (b² + c²)/12, ...
  ExpectShape(*MakeBox(a, b, c), M::kVolume, a * b * c, Vec3::Zero(),
              RotationalInertia((b * b + c * c) / 12, (a * a + c * c) / 12, (a * a + b * b) / 12),
              c);
  // Ellipsoid: V = (4/3) pi a b c; Ixx = m (b² + c²)/5, ...
  ExpectShape(*MakeEllipsoid(a, b, c), M::kVolume, 4 * pi * a * b * c / 3, Vec3::Zero(),
              RotationalInertia((b * b + c * c) / 5, (a * a + c * c) / 5, (a * a + b * b) / 5), c);
}

// Surface areas: a solid's whole boundary, a surface shape's own area, 0 for curves.
TEST(Shape, SurfaceAreasMatchTheirClosedForms) {
  const double R = 0.3, Ri = 0.1, h = 0.7, a = 0.4, b = 0.5, c = 0.9, r = 0.05;
  EXPECT_EQ(MakeSlenderRod(h)->CalcSurfaceArea(), 0.0);
  EXPECT_EQ(MakeThinRing(R)->CalcSurfaceArea(), 0.0);
  EXPECT_TRUE(Near(MakeThinDisk(R)->CalcSurfaceArea(), pi * R * R, kExact));
  EXPECT_TRUE(Near(MakeThinPlate(a, b)->CalcSurfaceArea(), a * b, kExact));
  EXPECT_TRUE(Near(MakeThinCylindricalShell(R, h)->CalcSurfaceArea(), 2 * pi * R * h, kExact));
  EXPECT_TRUE(Near(MakeThinSphericalShell(R)->CalcSurfaceArea(), 4 * pi * R * R, kExact));
  // Cylinder: two ends πR² and the side 2πRh.
  EXPECT_TRUE(
      Near(MakeSolidCylinder(R, h)->CalcSurfaceArea(), 2 * pi * R * R + 2 * pi * R * h, kExact));
  // Tube: outer and inner walls, two annuli.
  EXPECT_TRUE(Near(MakeTube(Ri, R, h)->CalcSurfaceArea(),
                   2 * pi * R * h + 2 * pi * Ri * h + 2 * pi * (R * R - Ri * Ri), kExact));
  EXPECT_TRUE(Near(MakeSolidSphere(R)->CalcSurfaceArea(), 4 * pi * R * R, kExact));
  EXPECT_TRUE(Near(MakeThickSphericalShell(Ri, R)->CalcSurfaceArea(),
                   4 * pi * R * R + 4 * pi * Ri * Ri, kExact));
  // Hemisphere: half the sphere 2πR² and the flat disk πR².
  EXPECT_TRUE(Near(MakeSolidHemisphere(R)->CalcSurfaceArea(), 3 * pi * R * R, kExact));
  // Cone: base πR² and lateral πR times the slant height sqrt(R² + h²).
  EXPECT_TRUE(Near(MakeSolidCone(R, h)->CalcSurfaceArea(),
                   pi * R * R + pi * R * std::sqrt(R * R + h * h), kExact));
  EXPECT_TRUE(Near(MakeBox(a, b, c)->CalcSurfaceArea(), 2 * (a * b + b * c + c * a), kExact));
  // Torus (Pappus): the tube's circumference 2πr times the path 2πR of its centre.
  EXPECT_TRUE(Near(MakeTorus(R, r)->CalcSurfaceArea(), 4 * pi * pi * R * r, kExact));
  // Prism on the 3-4-5 right triangle: two ends of area 6 and sides (3 + 4 + 5) h.
  EXPECT_TRUE(Near(MakeTriangularPrism({1, 1}, {4, 1}, {1, 5}, h)->CalcSurfaceArea(),
                   2 * 6.0 + 12.0 * h, kExact));
}

// The ellipsoid (Legendre's formula, incomplete elliptic integrals) against the closed forms:
// the sphere 4πa²; a spheroid with equatorial radius a and polar semi-axis c,
//   oblate (c < a), e² = 1 - c²/a²:  S = 2πa² (1 + (1 - e²) atanh(e) / e),
//   prolate (c > a), e² = 1 - a²/c²: S = 2πa² (1 + c asin(e) / (a e)),
// with the semi-axes given in every order; and the degenerate limit c -> 0 of a flat
// ellipsoid, twice the ellipse's area 2πab.
TEST(Shape, EllipsoidSurfaceAreaMatchesSphereAndSpheroids) {
  const double a = 0.7;
  EXPECT_TRUE(Near(MakeEllipsoid(a, a, a)->CalcSurfaceArea(), 4 * pi * a * a, kExact));
  for (double c : {0.1, 0.35, 0.69}) {
    const double e = std::sqrt(1 - c * c / (a * a));
    const double S = 2 * pi * a * a * (1 + (1 - e * e) * std::atanh(e) / e);
    EXPECT_TRUE(Near(MakeEllipsoid(a, a, c)->CalcSurfaceArea(), S, kExact)) << "oblate c " << c;
    EXPECT_TRUE(Near(MakeEllipsoid(c, a, a)->CalcSurfaceArea(), S, kExact)) << "oblate c " << c;
  }
  for (double c : {0.71, 1.4, 7.0}) {
    const double e = std::sqrt(1 - a * a / (c * c));
    const double S = 2 * pi * a * a * (1 + c * std::asin(e) / (a * e));
    EXPECT_TRUE(Near(MakeEllipsoid(a, a, c)->CalcSurfaceArea(), S, kExact)) << "prolate c " << c;
    EXPECT_TRUE(Near(MakeEllipsoid(a, c, a)->CalcSurfaceArea(), S, kExact)) << "prolate c " << c;
  }
  const double b = 0.4;
  EXPECT_TRUE(Near(EllipsoidSurfaceArea(a, b, 1e-9), 2 * pi * a * b, 1e-8));
  // Between its inscribed and circumscribed spheres' areas, and the same in every order.
  const double S = EllipsoidSurfaceArea(a, b, 0.2);
  EXPECT_GT(S, 4 * pi * 0.2 * 0.2);
  EXPECT_LT(S, 4 * pi * a * a);
  EXPECT_TRUE(Near(EllipsoidSurfaceArea(0.2, a, b), S, kExact));
}

TEST(Shape, RightTrianglePrismMatchesTextbookSecondMoments) {
  // Right triangle with legs a (x) and b (y) at the corner (x0, y0): area ab/2, centroid
  // (x0 + a/3, y0 + b/3); about the centroid ∫ y'² dA = a b³/36, ∫ x'² dA = a³ b/36 and
  // ∫ x'y' dA = -a² b²/72 (standard tables). Per unit mass (divide by ab/2): b²/18, a²/18,
  // -ab/36; the tensor entry Ixy = -∫ x'y' dm = +ab/36.
  const double a = 0.6, b = 0.4, h = 0.25, x0 = 1.5, y0 = -2.0;
  const auto prism = MakeTriangularPrism({x0, y0}, {x0 + a, y0}, {x0, y0 + b}, h);
  EXPECT_EQ(prism->kind(), "triangular_prism");
  ExpectShape(*prism, Shape::Measure::kVolume, a * b / 2 * h, Vec3(x0 + a / 3, y0 + b / 3, 0),
              RotationalInertia(b * b / 18 + h * h / 12, a * a / 18 + h * h / 12,
                                (a * a + b * b) / 18, a * b / 36),
              2.0);
}

TEST(Shape, EquilateralPrismHasPolarMomentOfATriangle) {
  // Equilateral triangle of side s: polar moment about the centroid J = (√3/48) s⁴ over area
  // (√3/4) s², i.e. s²/12 per unit mass, split equally between x and y, no product.
  const double s = 0.7, h = 0.3;
  const double hgt = s * std::sqrt(3.0) / 2;
  const auto prism = MakeTriangularPrism({0, 0}, {s, 0}, {s / 2, hgt}, h);
  const double I = s * s / 24 + h * h / 12;
  EXPECT_TRUE(MatNear(prism->CalcUnitInertia().matrix(),
                      RotationalInertia(I, I, s * s / 12).matrix(), kExact));
}

TEST(Shape, BoxIsTwoTriangularPrisms) {
  // Cut the box a x b x c along the diagonal of its xy face: the two prisms add up to the box
  // (checks the products of inertia, which cancel only in the sum).
  const double a = 0.8, b = 0.5, c = 0.3, rho = 1200;
  const Eigen::Vector2d p00(-a / 2, -b / 2), p10(a / 2, -b / 2), p11(a / 2, b / 2),
      p01(-a / 2, b / 2);
  const auto t1 = MakeTriangularPrism(p00, p10, p11, c);
  const auto t2 = MakeTriangularPrism(p00, p11, p01, c);
  const MassProperties sum = t1->CalcMassProperties(rho * t1->CalcMeasure()) +
                             t2->CalcMassProperties(rho * t2->CalcMeasure());
  const auto box = MakeBox(a, b, c);
  const MassProperties whole = box->CalcMassProperties(rho * a * b * c);
  EXPECT_TRUE(Near(sum.mass(), whole.mass(), kExact));
  EXPECT_TRUE(MatNear(sum.p_BoBcm_B(), Vec3::Zero(), kExact, a));
  EXPECT_TRUE(MatNear(sum.I_BBcm_B().matrix(), whole.I_BBcm_B().matrix(), kExact));
  // Each half alone has a product of inertia (its mass leans along the diagonal).
  EXPECT_GT(std::abs(t1->CalcUnitInertia().Ixy()), 1e-3 * a * b);
}

TEST(Shape, BoxSplitIntoEightBoxesIsTheWhole) {
  const double a = 0.4, b = 0.6, c = 1.0, rho = 7850;
  MassProperties sum = MassProperties::Zero();
  const auto octant = MakeBox(a / 2, b / 2, c / 2);
  for (int i = 0; i < 8; ++i) {
    const Vec3 centre((i & 1 ? 1 : -1) * a / 4, (i & 2 ? 1 : -1) * b / 4, (i & 4 ? 1 : -1) * c / 4);
    sum = sum + octant->CalcMassProperties(rho * octant->CalcMeasure())
                    .ExpressedInParent(Mat3::Identity(), centre);
  }
  const MassProperties whole = MakeBox(a, b, c)->CalcMassProperties(rho * a * b * c);
  EXPECT_TRUE(Near(sum.mass(), whole.mass(), kExact));
  EXPECT_TRUE(MatNear(sum.p_BoBcm_B(), Vec3::Zero(), kExact, c));
  EXPECT_TRUE(MatNear(sum.I_BBcm_B().matrix(), whole.I_BBcm_B().matrix(), kExact));
}

TEST(Shape, CylinderSplitIntoLayersIsTheWhole) {
  const double R = 0.25, h = 1.2, rho = 2700;
  const int n = 7;
  const auto layer = MakeSolidCylinder(R, h / n);
  MassProperties sum = MassProperties::Zero();
  for (int k = 0; k < n; ++k) {
    const double z = -h / 2 + (k + 0.5) * h / n;
    sum = sum + layer->CalcMassProperties(rho * layer->CalcMeasure())
                    .ExpressedInParent(Mat3::Identity(), Vec3(0, 0, z));
  }
  const auto whole = MakeSolidCylinder(R, h);
  const MassProperties expected = whole->CalcMassProperties(rho * whole->CalcMeasure());
  EXPECT_TRUE(Near(sum.mass(), expected.mass(), kExact));
  EXPECT_TRUE(MatNear(sum.p_BoBcm_B(), Vec3::Zero(), kExact, h));
  EXPECT_TRUE(MatNear(sum.I_BBcm_B().matrix(), expected.I_BBcm_B().matrix(), kExact));
}

// Uniform-density mass properties of a shape.
MassProperties Uniform(const Shape& s, double rho) {
  return s.CalcMassProperties(rho * s.CalcMeasure());
}

TEST(Shape, ThickShellIsSphereMinusSphere) {
  const double Ri = 0.17, Ro = 0.3, rho = 8960;
  const MassProperties diff =
      Uniform(*MakeSolidSphere(Ro), rho) + Uniform(*MakeSolidSphere(Ri), rho).Negated();
  const MassProperties shell = Uniform(*MakeThickSphericalShell(Ri, Ro), rho);
  EXPECT_TRUE(Near(diff.mass(), shell.mass(), kExact));
  EXPECT_TRUE(MatNear(diff.I_BBcm_B().matrix(), shell.I_BBcm_B().matrix(), kExact));
}

TEST(Shape, TubeIsCylinderMinusCylinder) {
  const double Ri = 0.05, Ro = 0.08, h = 0.6, rho = 7850;
  const MassProperties diff =
      Uniform(*MakeSolidCylinder(Ro, h), rho) + Uniform(*MakeSolidCylinder(Ri, h), rho).Negated();
  const MassProperties tube = Uniform(*MakeTube(Ri, Ro, h), rho);
  EXPECT_TRUE(Near(diff.mass(), tube.mass(), 1e-14));
  EXPECT_TRUE(MatNear(diff.I_BBcm_B().matrix(), tube.I_BBcm_B().matrix(), 1e-14));
}

TEST(Shape, ThinShellsAreLimitsOfThickOnes) {
  // Wall thickness t = 1e-7 R: the unit inertias differ from the thin limit by O(t/R).
  const double R = 0.4, h = 0.9, t = 1e-7 * R;
  const double kLimit = 1e-6;
  EXPECT_TRUE(MatNear(MakeTube(R - t, R, h)->CalcUnitInertia().matrix(),
                      MakeThinCylindricalShell(R, h)->CalcUnitInertia().matrix(), kLimit));
  EXPECT_TRUE(MatNear(MakeThickSphericalShell(R - t, R)->CalcUnitInertia().matrix(),
                      MakeThinSphericalShell(R)->CalcUnitInertia().matrix(), kLimit));
  // Volume / thickness tends to the shell's area, with no cancellation at t/R = 1e-7.
  EXPECT_TRUE(Near(MakeTube(R - t, R, h)->CalcMeasure() / t,
                   MakeThinCylindricalShell(R, h)->CalcMeasure(), kLimit));
  EXPECT_TRUE(Near(MakeThickSphericalShell(R - t, R)->CalcMeasure() / t,
                   MakeThinSphericalShell(R)->CalcMeasure(), kLimit));
  // A short cylinder is a thin disk; a thin cylinder is a slender rod.
  EXPECT_TRUE(MatNear(MakeSolidCylinder(R, 1e-7 * R)->CalcUnitInertia().matrix(),
                      MakeThinDisk(R)->CalcUnitInertia().matrix(), kLimit));
  EXPECT_TRUE(MatNear(MakeSolidCylinder(1e-7 * h, h)->CalcUnitInertia().matrix(),
                      MakeSlenderRod(h)->CalcUnitInertia().matrix(), kLimit));
  // A flat box is a plate; a torus with a thin tube is a ring.
  EXPECT_TRUE(MatNear(MakeBox(0.3, 0.2, 1e-7)->CalcUnitInertia().matrix(),
                      MakeThinPlate(0.3, 0.2)->CalcUnitInertia().matrix(), kLimit));
  EXPECT_TRUE(MatNear(MakeTorus(R, 1e-7 * R)->CalcUnitInertia().matrix(),
                      MakeThinRing(R)->CalcUnitInertia().matrix(), kLimit));
}

TEST(Shape, TwoHemispheresMakeASphere) {
  const double R = 0.35, rho = 1000;
  const auto hemi = MakeSolidHemisphere(R);
  const MassProperties up = Uniform(*hemi, rho);
  // The second half turned over (half a turn about x) with its flat face on the first's.
  const MassProperties down =
      up.ExpressedInParent(RotationFromAxisAngle(Vec3::UnitX(), pi), Vec3::Zero());
  const MassProperties sum = up + down;
  const MassProperties sphere = Uniform(*MakeSolidSphere(R), rho);
  EXPECT_TRUE(Near(sum.mass(), sphere.mass(), kExact));
  EXPECT_TRUE(MatNear(sum.p_BoBcm_B(), Vec3::Zero(), kExact, R));
  EXPECT_TRUE(MatNear(sum.I_BBcm_B().matrix(), sphere.I_BBcm_B().matrix(), kExact));
}

TEST(Shape, UnitCubeMapJacobianIsTheDeterminant) {
  // J must equal |det ∂p/∂u|, checked by central differences at scattered interior points.
  const double step = 1e-6;
  for (const auto& s : AllSolids()) {
    SCOPED_TRACE(s->kind());
    for (int n = 0; n < 20; ++n) {
      const Vec3 u(0.05 + 0.9 * std::fmod(0.37 * n + 0.11, 1.0),
                   0.05 + 0.9 * std::fmod(0.61 * n + 0.23, 1.0),
                   0.05 + 0.9 * std::fmod(0.83 * n + 0.47, 1.0));
      Mat3 D;
      for (int k = 0; k < 3; ++k) {
        Vec3 pp, pm;
        double J = 0;
        s->MapUnitCube(u + step * Vec3::Unit(k), &pp, &J);
        s->MapUnitCube(u - step * Vec3::Unit(k), &pm, &J);
        D.col(k) = (pp - pm) / (2 * step);
      }
      Vec3 p;
      double J = 0;
      s->MapUnitCube(u, &p, &J);
      EXPECT_TRUE(Near(J, std::abs(D.determinant()), 1e-7));
    }
  }
}

TEST(Shape, UnitCubeMapStaysInsideTheSolid) {
  // Spot checks with each solid's own inside test.
  const auto sphere = MakeSolidSphere(0.3);
  const auto cone = MakeSolidCone(0.3, 0.8);
  const auto torus = MakeTorus(0.3, 0.1);
  for (int n = 0; n < 50; ++n) {
    const Vec3 u(std::fmod(0.37 * n, 1.0), std::fmod(0.61 * n + 0.2, 1.0),
                 std::fmod(0.83 * n + 0.4, 1.0));
    Vec3 p;
    double J = 0;
    sphere->MapUnitCube(u, &p, &J);
    EXPECT_LE(p.norm(), 0.3 * (1 + kExact));
    cone->MapUnitCube(u, &p, &J);
    EXPECT_LE(std::hypot(p.x(), p.y()), 0.3 * (1 - p.z() / 0.8) + kExact);
    torus->MapUnitCube(u, &p, &J);
    EXPECT_LE(std::hypot(std::hypot(p.x(), p.y()) - 0.3, p.z()), 0.1 * (1 + kExact));
    // The hollow cone's wall: inside the cone (R 0.3, h 0.8, slant s), and no further than t
    // from its side (R h - h ρ - R z)/s, or, closed, from its base z.
    const double s = std::hypot(0.3, 0.8), t = 0.05;
    for (bool closed : {false, true}) {
      MakeHollowCone(0.3, 0.8, t, closed)->MapUnitCube(u, &p, &J);
      const double to_side = (0.3 * 0.8 - 0.8 * std::hypot(p.x(), p.y()) - 0.3 * p.z()) / s;
      EXPECT_GE(to_side, -kExact);
      EXPECT_GE(p.z(), -kExact);
      EXPECT_LE(closed ? std::min(to_side, p.z()) : to_side, t * (1 + kExact));
    }
  }
}

TEST(Shape, ThinShapesHaveNoUnitCubeMap) {
  Vec3 p;
  double J = 0;
  try {
    MakeThinDisk(0.2)->MapUnitCube(Vec3::Constant(0.5), &p, &J);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("disk: a thin shape is a surface with no volume"));
  }
  EXPECT_FALSE(MakeSlenderRod(1)->is_solid());
  EXPECT_TRUE(MakeSolidCone(1, 1)->is_solid());
}

// The InputError message of `make`, or "" when it does not throw.
std::string ErrorOf(const std::function<void()>& make) {
  try {
    make();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(Shape, BadDimensionsAreNamed) {
  EXPECT_THAT(ErrorOf([] { MakeTube(0.05, 0.04, 1); }),
              HasSubstr("tube: inner radius 0.05 m must be smaller than outer radius 0.04 m"));
  EXPECT_THAT(ErrorOf([] { MakeSolidCylinder(-0.1, 1); }),
              HasSubstr("cylinder: radius -0.1 m must be positive and finite"));
  EXPECT_THAT(ErrorOf([] { MakeSolidCone(0.1, std::nan("")); }),
              HasSubstr("cone: height nan m must be positive and finite"));
  EXPECT_THAT(ErrorOf([] { MakeBox(1, 0, 1); }), HasSubstr("box: size along y 0 m"));
  EXPECT_THAT(ErrorOf([] { MakeTorus(0.1, 0.1); }),
              HasSubstr("torus: minor radius 0.1 m must be smaller than major radius 0.1 m"));
  EXPECT_THAT(ErrorOf([] { MakeThickSphericalShell(0.3, 0.2); }),
              HasSubstr("inner radius 0.3 m must be smaller than outer radius 0.2 m"));
  EXPECT_THAT(ErrorOf([] { MakeSlenderRod(INFINITY); }), HasSubstr("rod: length inf m"));
  EXPECT_THAT(ErrorOf([] {
                MakeTriangularPrism({0, 0}, {1, 1}, {2, 2}, 1);
              }),
              HasSubstr("triangular_prism: the vertices (0, 0), (1, 1), (2, 2) m are collinear"));
  EXPECT_THAT(ErrorOf([] {
                MakeTriangularPrism({0, 0}, {1, 0}, {0, 1}, -1);
              }),
              HasSubstr("triangular_prism: length -1 m must be positive"));
  EXPECT_THAT(ErrorOf([] { MakeSolidSphere(1)->CalcMassProperties(-2); }),
              HasSubstr("sphere: mass -2 kg must be positive and finite"));
  EXPECT_EQ(ErrorOf([] { MakeTube(0.04, 0.05, 1); }), "");
}

TEST(Shape, DescribeListsTheDimensions) {
  EXPECT_EQ(MakeTube(0.04, 0.05, 1)->Describe(),
            "tube (inner_radius 0.04 m, outer_radius 0.05 m, length 1 m)");
  EXPECT_EQ(MakeSolidCylinder(0.1, 0.5)->kind(), "cylinder");
}

}  // namespace
}  // namespace chasles
