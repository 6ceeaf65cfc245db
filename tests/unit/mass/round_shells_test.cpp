// Thin shells of revolution (conical, hemispherical, toroidal, closed cylindrical) and the
// hollow cone, against closed forms derived here, against differences of solids, and against
// fine triangle meshes of the same surfaces.

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <numbers>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "chasles/error.h"
#include "chasles/mass/mesh_mass.h"
#include "chasles/mass/shape.h"
#include "chasles/math/rotation.h"
#include "test_support.h"

namespace chasles {
namespace {

using std::numbers::pi;
using test::MatNear;
using test::Near;
using ::testing::HasSubstr;

// Closed forms evaluated two ways (here and in the library) agree to the round-off of a few
// dozen operations; differences of two solids lose at most a digit more.
constexpr double kClosedForm = 1e-12;
// A wall 1e-7 of the size thick differs from its thin-shell limit by O(t/R).
constexpr double kThinLimit = 1e-6;

// Mass properties of a uniform distribution over a shape: `per_measure` per unit area or
// volume.
MassProperties Uniform(const Shape& s, double per_measure) {
  return s.CalcMassProperties(per_measure * s.CalcMeasure());
}

// Compares mass, centre of mass (against `length`) and central inertia.
void ExpectSame(const MassProperties& got, const MassProperties& want, double tol, double length) {
  EXPECT_TRUE(Near(got.mass(), want.mass(), tol));
  EXPECT_TRUE(MatNear(got.p_BoBcm_B(), want.p_BoBcm_B(), tol, length));
  EXPECT_TRUE(MatNear(got.I_BBcm_B().matrix(), want.I_BBcm_B().matrix(), tol));
}

Mat3 Diag(double xx, double yy, double zz) {
  return Vec3(xx, yy, zz).asDiagonal();
}

// The lateral surface of a cone, measured from the apex along a generator by ℓ in [0, s]
// (s = √(R² + h²) the slant height): the hoop there has radius ρ = R ℓ/s, lies h ℓ/s below
// the apex, and has area 2π ρ dℓ, so dA ∝ ℓ dℓ and the mean of ℓⁿ over the surface is
// ∫ ℓⁿ⁺¹ dℓ / ∫ ℓ dℓ = 2 sⁿ/(n + 2). Hence A = π R s; the centroid 2h/3 below the apex (h/3
// above the base); ⟨ρ²⟩ = R²/2 (Izz = m R²/2); ⟨depth²⟩ = h²/2. A hoop gives ρ²/2 about a
// diameter, so about a transverse axis through the apex I = m (R²/4 + h²/2); through the
// centroid m (R²/4 + h²/2 - 4h²/9) = m (R²/4 + h²/18); through the base centre
// m (R²/4 + h²/18 + h²/9) = m (R²/4 + h²/6).
TEST(RoundShells, OpenConicalShellMatchesItsClosedForms) {
  const double R = 0.3, h = 0.8, sigma = 12.5;  // areal density [kg/m²]
  const double s = std::sqrt(R * R + h * h);
  const double m = sigma * pi * R * s;
  const auto shell = MakeThinConicalShell(R, h);
  EXPECT_EQ(shell->kind(), "conical_shell");
  EXPECT_EQ(shell->measure(), Shape::Measure::kArea);
  EXPECT_FALSE(shell->closed());
  EXPECT_TRUE(Near(shell->CalcMeasure(), pi * R * s, kClosedForm));
  EXPECT_TRUE(Near(shell->CalcSurfaceArea(), pi * R * s, kClosedForm));
  const MassProperties mp = Uniform(*shell, sigma);
  EXPECT_TRUE(Near(mp.mass(), m, kClosedForm));
  EXPECT_TRUE(MatNear(mp.p_BoBcm_B(), Vec3(0, 0, h / 3), kClosedForm, h));
  const double Ic = m * (R * R / 4 + h * h / 18);
  EXPECT_TRUE(MatNear(mp.I_BBcm_B().matrix(), Diag(Ic, Ic, m * R * R / 2), kClosedForm));
  const double Iapex = m * (R * R / 4 + h * h / 2);
  EXPECT_TRUE(MatNear(mp.CalcInertiaAbout(Vec3(0, 0, h)).matrix(),
                      Diag(Iapex, Iapex, m * R * R / 2), kClosedForm));
  const double Ibase = m * (R * R / 4 + h * h / 6);
  EXPECT_TRUE(MatNear(mp.CalcInertiaAbout(Vec3::Zero()).matrix(), Diag(Ibase, Ibase, m * R * R / 2),
                      kClosedForm));
  EXPECT_EQ(mp.I_BBcm_B().CheckPhysicallyValid(), "");
}

// Closed: the lateral surface (area A_L = π R s, centroid h/3) and the base disk (A_B = π R²,
// at z = 0; Izz = m R²/2, Ixx = m R²/4 about its centre), one areal density σ. Mass
// σ π R (s + R); centroid z_c = (h/3) A_L / (A_L + A_B) = s h / (3 (s + R)). Both pieces have
// Izz = m R²/2, so the whole does. About a transverse axis through the base centre the pieces
// add: σ A_L (R²/4 + h²/6) + σ A_B R²/4 = m (R²/4 + s h² / (6 (s + R))); the parallel-axis
// theorem (eq. 8.29) moves it to the centroid (- m z_c²) and on to the apex (+ m (h - z_c)²).
TEST(RoundShells, ClosedConicalShellMatchesItsClosedForms) {
  const double R = 0.45, h = 0.35, sigma = 3.0;
  const double s = std::sqrt(R * R + h * h);
  const double m = sigma * pi * R * (s + R);
  const double zc = s * h / (3 * (s + R));
  const auto shell = MakeThinConicalShell(R, h, /*closed=*/true);
  EXPECT_TRUE(shell->closed());
  EXPECT_THAT(shell->Describe(), HasSubstr("conical_shell (radius 0.45 m, height 0.35 m, closed)"));
  EXPECT_TRUE(Near(shell->CalcSurfaceArea(), pi * R * s + pi * R * R, kClosedForm));
  const MassProperties mp = Uniform(*shell, sigma);
  EXPECT_TRUE(Near(mp.mass(), m, kClosedForm));
  EXPECT_TRUE(MatNear(mp.p_BoBcm_B(), Vec3(0, 0, zc), kClosedForm, h));
  const double Izz = m * R * R / 2;
  const double Ibase = m * (R * R / 4 + s * h * h / (6 * (s + R)));
  const double Ic = Ibase - m * zc * zc;
  const double Iapex = Ic + m * (h - zc) * (h - zc);
  EXPECT_TRUE(MatNear(mp.I_BBcm_B().matrix(), Diag(Ic, Ic, Izz), kClosedForm));
  EXPECT_TRUE(
      MatNear(mp.CalcInertiaAbout(Vec3::Zero()).matrix(), Diag(Ibase, Ibase, Izz), kClosedForm));
  EXPECT_TRUE(
      MatNear(mp.CalcInertiaAbout(Vec3(0, 0, h)).matrix(), Diag(Iapex, Iapex, Izz), kClosedForm));
}

// The hollow cone against the difference of two solid cones, each with its closed forms
// (Appendix A: V = π r² H / 3, centroid H/4 above its base, Izz = (3/10) m r²,
// Ixx = (3/20) m r² + (3/80) m H² about the centroid). The inner cone is derived here from the
// wall: its side is the outer side moved inwards by t along the normal. The side's generator
// makes the angle α with the axis, sin α = R/s, cos α = h/s; moving it by t moves its
// intersection with the axis down by t / sin α and with any horizontal plane inwards by
// t / cos α. Open (base plane shared): inner radius R - t s/h, apex at h - t s/R. Closed (the
// base wall t thick too): inner base at z = t with radius (h - t s/R - t) R/h, apex at
// h - t s/R.
struct InnerCone {
  double radius, height, base;
};

InnerCone InnerOf(double R, double h, double t, bool closed) {
  const double s = std::sqrt(R * R + h * h);
  const double apex = h - t * s / R;
  if (!closed) return {R - t * s / h, apex, 0.0};
  return {(apex - t) * R / h, apex - t, t};
}

MassProperties SolidConeClosedForm(double r, double H, double base, double rho) {
  const double m = rho * pi * r * r * H / 3;
  const double Ixx = m * (3 * r * r / 20 + 3 * H * H / 80);
  return MassProperties(m, Vec3(0, 0, base + H / 4),
                        RotationalInertia(Ixx, Ixx, 3 * m * r * r / 10));
}

TEST(RoundShells, HollowConeIsTheDifferenceOfTwoSolidCones) {
  const double R = 0.3, h = 0.8, rho = 2700;
  const double s = std::sqrt(R * R + h * h);
  for (bool closed : {false, true}) {
    const double limit = closed ? R * h / (R + s) : R * h / s;
    for (double t : {0.002, 0.03, 0.1, 0.9 * limit}) {
      SCOPED_TRACE(std::string(closed ? "closed" : "open") + " t = " + std::to_string(t));
      const InnerCone in = InnerOf(R, h, t, closed);
      // The inner cone is the outer one in proportion, and its side is t from the outer side:
      // the distance from the inner apex (0, apex) to the outer generator through (R, 0) and
      // (0, h) is (h - apex) sin α, and from the inner rim likewise.
      EXPECT_TRUE(Near(in.radius / in.height, R / h, kClosedForm));
      const auto to_side = [&](double rho_, double z) { return (R * h - h * rho_ - R * z) / s; };
      EXPECT_TRUE(Near(to_side(0, in.base + in.height), t, kClosedForm));
      EXPECT_TRUE(Near(to_side(in.radius, in.base), t, kClosedForm));
      const MassProperties want = SolidConeClosedForm(R, h, 0, rho) +
                                  SolidConeClosedForm(in.radius, in.height, in.base, rho).Negated();
      const auto cone = MakeHollowCone(R, h, t, closed);
      EXPECT_EQ(cone->kind(), "cone");
      EXPECT_TRUE(cone->is_solid());
      EXPECT_EQ(cone->closed(), closed);
      const MassProperties got = Uniform(*cone, rho);
      ExpectSame(got, want, kClosedForm, h);
      // About the apex and the base centre, through the parallel-axis theorem on both sides.
      for (const Vec3& p : {Vec3(0, 0, h), Vec3(Vec3::Zero())}) {
        EXPECT_TRUE(MatNear(got.CalcInertiaAbout(p).matrix(), want.CalcInertiaAbout(p).matrix(),
                            kClosedForm));
      }
      // Surfaces: the outer side π R s, the inner side π r s_i, and open the annulus
      // π (R² - r²) at the base, closed both bases π R² and π r².
      const double si = std::hypot(in.radius, in.height);
      const double sides = pi * R * s + pi * in.radius * si;
      const double flats =
          closed ? pi * R * R + pi * in.radius * in.radius : pi * (R * R - in.radius * in.radius);
      EXPECT_TRUE(Near(cone->CalcSurfaceArea(), sides + flats, kClosedForm));
    }
  }
}

// A wall of thickness t → 0 is the thin shell: V / t → the shell's area (open: the side π R s;
// closed: with the base π R²), and the centroid and the inertia per unit mass are the shell's.
TEST(RoundShells, ThinHollowConeIsTheConicalShell) {
  const double R = 0.3, h = 0.8, t = 1e-7 * R;
  for (bool closed : {false, true}) {
    SCOPED_TRACE(closed ? "closed" : "open");
    const auto wall = MakeHollowCone(R, h, t, closed);
    const auto shell = MakeThinConicalShell(R, h, closed);
    EXPECT_TRUE(Near(wall->CalcMeasure() / t, shell->CalcMeasure(), kThinLimit));
    EXPECT_TRUE(MatNear(wall->CalcCentroid(), shell->CalcCentroid(), kThinLimit, h));
    EXPECT_TRUE(
        MatNear(wall->CalcUnitInertia().matrix(), shell->CalcUnitInertia().matrix(), kThinLimit));
  }
}

// The lateral surface as a fan of N flat triangles (apex, rim point i, rim point i + 1): a
// pyramid on the regular N-gon inscribed in the base circle; with `closed`, the base N-gon as
// a fan about its centre too. Vertices in double precision, in memory.
TriangleMesh ConeSheetMesh(double R, double h, int N, bool closed) {
  TriangleMesh mesh;
  mesh.vertices.emplace_back(0, 0, h);  // apex
  mesh.vertices.emplace_back(0, 0, 0);  // base centre
  for (int i = 0; i < N; ++i) {
    const double phi = 2 * pi * i / N;
    mesh.vertices.emplace_back(R * std::cos(phi), R * std::sin(phi), 0);
  }
  for (int i = 0; i < N; ++i) {
    const auto a = static_cast<std::uint32_t>(2 + i);
    const auto b = static_cast<std::uint32_t>(2 + (i + 1) % N);
    mesh.triangles.push_back({0, a, b});
    if (closed) mesh.triangles.push_back({1, b, a});
  }
  return mesh;
}

// Area, centroid height, Izz and central Ixx of a sheet of unit areal density (so its mass is
// its area) about z.
using SheetMoments = Eigen::Vector4d;

SheetMoments MomentsOf(const MassProperties& mp) {
  return {mp.mass(), mp.p_BoBcm_B().z(), mp.I_BBcm_B().Izz(), mp.I_BBcm_B().Ixx()};
}

// The same for the mesh above, in closed form for any N. Every triangle has one corner on the
// axis (the apex, or the base centre) and two on the rim circle, π/N either side of their
// mid-plane. Over a triangle with corners v_i, ∫ v vᵀ dA = (A/12)(Σ v_i v_iᵀ + (Σ v_i)(Σ v_i)ᵀ);
// with c = cos(π/N) this gives ⟨ρ²⟩ = R² (1 + 2c²)/6 on every triangle, and on the lateral ones
// ⟨z⟩ = h/3 and ⟨z²⟩ = h²/6 exactly (the corners' heights h, 0, 0). By the N-fold symmetry
// ⟨x²⟩ = ⟨y²⟩ = ⟨ρ²⟩/2. A lateral triangle has base 2R sin(π/N) and height
// √(h² + R² c²) (apex to the chord's midpoint); the base N-gon has area (N/2) R² sin(2π/N).
SheetMoments PyramidSheet(double R, double h, int N, bool closed) {
  const double sn = std::sin(pi / N), c2 = 1 - sn * sn;
  const double lateral = N * R * sn * std::sqrt(h * h + R * R * c2);
  const double base = closed ? N * R * R * std::sin(2 * pi / N) / 2 : 0.0;
  const double rho2 = R * R * (1 + 2 * c2) / 6;
  const double area = lateral + base;
  const double zc = lateral * h / 3 / area;
  // About a transverse axis through the base centre, then at the centroid (eq. 8.29).
  const double J = lateral * (rho2 / 2 + h * h / 6) + base * rho2 / 2;
  return {area, zc, area * rho2, J - area * zc * zc};
}

// The mesh's relative errors against the shell: area, centroid height, Izz and Ixx.
SheetMoments MeshErrors(double R, double h, int N, bool closed) {
  const MassProperties mesh =
      MassPropertiesFromIntegrals(CalcShellIntegrals(ConeSheetMesh(R, h, N, closed)), 1.0);
  const SheetMoments want = MomentsOf(Uniform(*MakeThinConicalShell(R, h, closed), 1.0));
  return (MomentsOf(mesh) - want).cwiseQuotient(want);
}

// The mesh differs from the cone only at the rim: the N-gon in place of the circle. With
// ε = (π/N)², sin(π/N) = (π/N)(1 - ε/6 + O(ε²)) and c² = 1 - ε + O(ε²), so from PyramidSheet:
//   lateral area  π R s (1 + a ε),  a = -(1/6 + R²/(2 s²));   base N-gon π R² (1 - (2/3) ε);
//   ⟨ρ²⟩ = (R²/2)(1 - (2/3) ε).
// Open: the area's relative error is a ε, Izz's (a - 2/3) ε, the centroid is exact, and the
// central Ixx = m (⟨ρ²⟩/2 + h²/18) is off by (a - (R²/6) / (R²/4 + h²/18)) ε. Each coefficient
// is at most 4/3 in magnitude (a ≥ -2/3), and closed, the weighted means of the lateral and
// base ones stay under it too. So the tolerance is (4/3) ε (2.4e-6 at N = 2048), and halving
// the segments quarters each error (second order).
TEST(RoundShells, ConicalShellIsTheLimitOfFineMeshSheets) {
  const double R = 0.3, h = 0.8, s2 = R * R + h * h;
  const int N = 2048;
  const double eps = std::pow(pi / N, 2);
  for (bool closed : {false, true}) {
    SCOPED_TRACE(closed ? "closed" : "open");
    // The mesh functions integrate the flat triangles exactly: the N-gon pyramid's moments.
    for (int n : {N, 2 * N}) {
      const MassProperties mesh =
          MassPropertiesFromIntegrals(CalcShellIntegrals(ConeSheetMesh(R, h, n, closed)), 1.0);
      const SheetMoments got = MomentsOf(mesh), want = PyramidSheet(R, h, n, closed);
      for (int k = 0; k < 4; ++k) EXPECT_TRUE(Near(got[k], want[k], kClosedForm)) << n << " " << k;
    }
    const SheetMoments coarse = MeshErrors(R, h, N, closed);
    const SheetMoments fine = MeshErrors(R, h, 2 * N, closed);
    std::printf("%s: N = %d errors / eps %.4f %.4f %.4f %.4f; ratios N/2N %.4f %.4f %.4f %.4f\n",
                closed ? "closed" : "open", N, coarse[0] / eps, coarse[1] / eps, coarse[2] / eps,
                coarse[3] / eps, coarse[0] / fine[0], coarse[1] / fine[1], coarse[2] / fine[2],
                coarse[3] / fine[3]);
    for (int k = 0; k < 4; ++k) {
      EXPECT_LE(std::abs(coarse[k]), 4.0 / 3 * eps) << k;
      EXPECT_LE(std::abs(fine[k]), 4.0 / 3 * eps / 4) << k;
      if (!closed && k == 1) {
        EXPECT_LE(std::abs(coarse[k]), kClosedForm);  // the open sheet's centroid is exact
        continue;
      }
      // Second order: the ratio of the errors is 4 up to the O(ε) of the next term.
      EXPECT_NEAR(coarse[k] / fine[k], 4.0, 0.01) << k;
    }
    if (!closed) {
      // The leading coefficients themselves, to within the next order.
      const double a = -(1.0 / 6 + R * R / (2 * s2));
      const double b = a - (R * R / 6) / (R * R / 4 + h * h / 18);
      EXPECT_NEAR(coarse[0] / eps, a, eps);
      EXPECT_NEAR(coarse[2] / eps, a - 2.0 / 3, eps);
      EXPECT_NEAR(coarse[3] / eps, b, eps);
    }
  }
}

// The hemispherical shell, with the polar angle θ from +z: dA = 2π R² sin θ dθ, z = R cos θ,
// so A = 2π R², ⟨z⟩ = R/2, ⟨z²⟩ = R²/3 and ⟨ρ²⟩ = R² ⟨sin² θ⟩ = 2R²/3 (Izz = (2/3) m R²).
// About a diameter of the rim ⟨ρ²⟩/2 + ⟨z²⟩ = 2R²/3; at the centroid 2/3 - 1/4 = 5/12 of
// m R². Closed with the disk (πR², Izz = m R²/2, Ixx = m R²/4 at z = 0), weights 2/3 and 1/3:
// z_c = R/3, Izz = (2/3)(2/3) + (1/3)(1/2) = 11/18, Ixx about the rim centre
// (2/3)(2/3) + (1/3)(1/4) = 19/36, at the centroid 19/36 - 1/9 = 5/12 (of m R²).
TEST(RoundShells, HemisphericalShellMatchesItsClosedForms) {
  const double R = 0.25;
  const auto open = MakeThinHemisphericalShell(R);
  EXPECT_EQ(open->kind(), "hemispherical_shell");
  EXPECT_TRUE(Near(open->CalcMeasure(), 2 * pi * R * R, kClosedForm));
  EXPECT_TRUE(Near(open->CalcSurfaceArea(), 2 * pi * R * R, kClosedForm));
  EXPECT_TRUE(MatNear(open->CalcCentroid(), Vec3(0, 0, R / 2), kClosedForm, R));
  EXPECT_TRUE(MatNear(open->CalcUnitInertia().matrix(),
                      Diag(5 * R * R / 12, 5 * R * R / 12, 2 * R * R / 3), kClosedForm));
  const auto closed = MakeThinHemisphericalShell(R, true);
  EXPECT_TRUE(Near(closed->CalcMeasure(), 3 * pi * R * R, kClosedForm));
  EXPECT_TRUE(MatNear(closed->CalcCentroid(), Vec3(0, 0, R / 3), kClosedForm, R));
  EXPECT_TRUE(MatNear(closed->CalcUnitInertia().matrix(),
                      Diag(5 * R * R / 12, 5 * R * R / 12, 11 * R * R / 18), kClosedForm));
  // Two open halves, one turned over, are the spherical shell.
  const MassProperties up = Uniform(*open, 2.0);
  const MassProperties both =
      up + up.ExpressedInParent(RotationFromAxisAngle(Vec3::UnitX(), pi), Vec3::Zero());
  ExpectSame(both, Uniform(*MakeThinSphericalShell(R), 2.0), kClosedForm, R);
  // The thin limit of the hemisphere minus a hemisphere of radius R - t.
  const double t = 1e-7 * R;
  const MassProperties bowl =
      Uniform(*MakeSolidHemisphere(R), 1.0) + Uniform(*MakeSolidHemisphere(R - t), 1.0).Negated();
  EXPECT_TRUE(Near(bowl.mass() / t, open->CalcMeasure(), kThinLimit));
  EXPECT_TRUE(MatNear(bowl.I_BBcm_B().matrix() / bowl.mass(), open->CalcUnitInertia().matrix(),
                      kThinLimit));
}

// The closed cylindrical shell (a can): the wall 2π R h (Izz = m R², Ixx = m (R²/2 + h²/12))
// and two end disks π R² at z = ±h/2 (Izz = m R²/2, Ixx = m (R²/4 + h²/4) by eq. 8.29).
TEST(RoundShells, ClosedCylindricalShellMatchesItsClosedForms) {
  const double R = 0.2, h = 0.7, sigma = 4.0;
  const double mw = sigma * 2 * pi * R * h, md = sigma * pi * R * R;
  const auto can = MakeThinCylindricalShell(R, h, true);
  EXPECT_TRUE(Near(can->CalcSurfaceArea(), 2 * pi * R * h + 2 * pi * R * R, kClosedForm));
  const MassProperties mp = Uniform(*can, sigma);
  EXPECT_TRUE(Near(mp.mass(), mw + 2 * md, kClosedForm));
  EXPECT_TRUE(MatNear(mp.p_BoBcm_B(), Vec3::Zero(), kClosedForm, h));
  const double Ixx = mw * (R * R / 2 + h * h / 12) + 2 * md * (R * R / 4 + h * h / 4);
  EXPECT_TRUE(
      MatNear(mp.I_BBcm_B().matrix(), Diag(Ixx, Ixx, mw * R * R + md * R * R), kClosedForm));
  EXPECT_FALSE(MakeThinCylindricalShell(R, h)->closed());
}

// The toroidal shell: the tube's circle at angle ψ lies σ = R + r cos ψ from the axis and
// dA = r σ dψ dφ, so A = 4π² R r (Pappus); Izz = ∫ σ³ dψ / ∫ σ dψ = R² + (3/2) r²,
// ⟨z²⟩ = r² ∫ sin² ψ σ dψ / ∫ σ dψ = r²/2, Ixx = Izz/2 + r²/2 = R²/2 + (5/4) r². Also the thin
// limit of a torus minus a torus with a tube t thinner.
TEST(RoundShells, ToroidalShellMatchesItsClosedForms) {
  const double R = 0.4, r = 0.1;
  const auto shell = MakeThinToroidalShell(R, r);
  EXPECT_EQ(shell->kind(), "toroidal_shell");
  EXPECT_TRUE(Near(shell->CalcMeasure(), 4 * pi * pi * R * r, kClosedForm));
  EXPECT_TRUE(Near(shell->CalcSurfaceArea(), 4 * pi * pi * R * r, kClosedForm));
  const double Ixx = R * R / 2 + 5 * r * r / 4;
  EXPECT_TRUE(
      MatNear(shell->CalcUnitInertia().matrix(), Diag(Ixx, Ixx, R * R + 1.5 * r * r), kClosedForm));
  const double t = 1e-7 * r;
  const MassProperties ring =
      Uniform(*MakeTorus(R, r), 1.0) + Uniform(*MakeTorus(R, r - t), 1.0).Negated();
  EXPECT_TRUE(Near(ring.mass() / t, shell->CalcMeasure(), kThinLimit));
  EXPECT_TRUE(MatNear(ring.I_BBcm_B().matrix() / ring.mass(), shell->CalcUnitInertia().matrix(),
                      kThinLimit));
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

TEST(RoundShells, BadDimensionsAreNamed) {
  // R = 0.3, h = 0.4: s = 0.5; open wall limit R h / s = 0.24, closed R h / (R + s) = 0.15.
  EXPECT_THAT(ErrorOf([] { MakeHollowCone(0.3, 0.4, 0.24); }),
              HasSubstr("cone: thickness 0.24 m must be smaller than 0.24 m, the distance from "
                        "the centre of the base to the lateral surface"));
  EXPECT_EQ(ErrorOf([] { MakeHollowCone(0.3, 0.4, 0.2399); }), "");
  EXPECT_THAT(ErrorOf([] { MakeHollowCone(0.3, 0.4, 0.15, true); }),
              HasSubstr("cone: thickness 0.15 m must be smaller than 0.15 m, the radius of the "
                        "sphere inscribed in the cone"));
  EXPECT_EQ(ErrorOf([] { MakeHollowCone(0.3, 0.4, 0.1499, true); }), "");
  EXPECT_THAT(ErrorOf([] { MakeHollowCone(0.3, 0.4, -0.01); }),
              HasSubstr("cone: thickness -0.01 m must be positive and finite"));
  EXPECT_THAT(ErrorOf([] { MakeHollowCone(0.3, 0.4, 0); }),
              HasSubstr("cone: thickness 0 m must be positive and finite"));
  EXPECT_THAT(ErrorOf([] { MakeThinConicalShell(0.3, 0); }),
              HasSubstr("conical_shell: height 0 m must be positive and finite"));
  EXPECT_THAT(ErrorOf([] { MakeThinHemisphericalShell(std::nan("")); }),
              HasSubstr("hemispherical_shell: radius nan m must be positive and finite"));
  EXPECT_THAT(
      ErrorOf([] { MakeThinToroidalShell(0.1, 0.2); }),
      HasSubstr("toroidal_shell: minor radius 0.2 m must be smaller than major radius 0.1 m"));
  // Thin shells have no volume to map.
  Vec3 p;
  double J = 0;
  EXPECT_THAT(ErrorOf([&] { MakeThinConicalShell(0.3, 0.4)->MapUnitCube(Vec3::Zero(), &p, &J); }),
              HasSubstr("conical_shell: a thin shape is a surface with no volume"));
}

}  // namespace
}  // namespace chasles
