#include "chasles/mass/density_field.h"

#include <chrono>
#include <cmath>
#include <functional>
#include <memory>
#include <numbers>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "chasles/error.h"
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

// The integrator's requested tolerance and what the tests demand of the result: the estimate
// is conservative (the difference of the 15- and 7-point rules), so 1e-10 requested gives
// 1e-10 achieved with room to spare.
constexpr double kTol = 1e-10;

// Compares mass, centre of mass (relative to `length`) and inertia (relative to its largest
// entry) of two mass distributions.
void ExpectSame(const MassProperties& got, const MassProperties& want, double tol, double length) {
  EXPECT_TRUE(Near(got.mass(), want.mass(), tol));
  EXPECT_TRUE(MatNear(got.p_BoBcm_B(), want.p_BoBcm_B(), tol, length));
  EXPECT_TRUE(MatNear(got.I_BBcm_B().matrix(), want.I_BBcm_B().matrix(), tol));
}

TEST(DensityField, ConstantDensityIsTheUniformSolidOnEverySolid) {
  const double rho = 2700;
  for (const auto& s : AllSolids()) {
    SCOPED_TRACE(s->Describe());
    DensityIntegrationReport report;
    const auto start = std::chrono::steady_clock::now();
    const MassProperties mp = IntegrateDensity(
        *s, [rho](const Vec3&) { return rho; }, kTol, &report);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::printf("%-22s %8ld evaluations %4d regions error %.2g  %.4f s\n",
                std::string(s->kind()).c_str(), report.evaluations, report.regions,
                report.estimated_relative_error, seconds);
    ExpectSame(mp, s->CalcMassProperties(rho * s->CalcMeasure()), kTol, 1.0);
    EXPECT_LE(report.estimated_relative_error, kTol);
  }
}

TEST(DensityField, LinearDensityOnACylinder) {
  // rho = rho0 (1 + k z) on the centred cylinder (z in [-h/2, h/2]). By direct integration:
  //   m = rho0 pi R² h                        (∫ z dz = 0)
  //   m z̄ = rho0 pi R² k ∫ z² dz = rho0 pi R² k h³/12   =>  z̄ = k h²/12
  //   ∫ r² dm = rho0 h pi R⁴/2 = m R²/2       =>  Izz = m R²/2 (the gradient runs along z)
  //   ∫ y² dm = m R²/4,  ∫ z² dm = rho0 pi R² h³/12 = m h²/12
  //   Ixx = Iyy = ∫ (y² + z²) dm - m z̄² = m (R²/4 + h²/12 - k² h⁴/144).
  const double rho0 = 5000, R = 0.2, h = 0.9, k = 1.5 / h;
  const double m = rho0 * pi * R * R * h;
  const double Ixx = m * (R * R / 4 + h * h / 12 - k * k * std::pow(h, 4) / 144);
  const MassProperties want(m, Vec3(0, 0, k * h * h / 12),
                            RotationalInertia(Ixx, Ixx, m * R * R / 2));
  const MassProperties got = IntegrateDensity(
      *MakeSolidCylinder(R, h), [&](const Vec3& p) { return rho0 * (1 + k * p.z()); });
  ExpectSame(got, want, kTol, h);
}

TEST(DensityField, LinearDensityOnABoxGivesAProductOfInertia) {
  // rho = rho0 (1 + kx x + kz z) on the centred box a x b x c. Odd integrands vanish, so
  //   m = rho0 a b c,  x̄ = kx a²/12,  z̄ = kz c²/12,  ȳ = 0,
  //   ∫ x² dm = m a²/12, ∫ y² dm = m b²/12, ∫ z² dm = m c²/12, ∫ xz dm = ∫ xy dm = ∫ yz dm = 0.
  // About the centre of mass: Cxx = m (a²/12 - x̄²), Cyy = m b²/12, Czz = m (c²/12 - z̄²),
  // Cxz = -m x̄ z̄; the tensor holds Ixx = Cyy + Czz, ..., and Ixz = -Cxz = m x̄ z̄.
  const double rho0 = 1200, a = 0.4, b = 0.3, c = 0.8, kx = 0.8 / a, kz = -0.6 / c;
  const double m = rho0 * a * b * c;
  const double xb = kx * a * a / 12, zb = kz * c * c / 12;
  const double Cxx = m * (a * a / 12 - xb * xb), Cyy = m * b * b / 12,
               Czz = m * (c * c / 12 - zb * zb);
  const MassProperties want(m, Vec3(xb, 0, zb),
                            RotationalInertia(Cyy + Czz, Cxx + Czz, Cxx + Cyy, 0, m * xb * zb, 0));
  const MassProperties got = IntegrateDensity(
      *MakeBox(a, b, c), [&](const Vec3& p) { return rho0 * (1 + kx * p.x() + kz * p.z()); });
  ExpectSame(got, want, kTol, c);
  EXPECT_GT(std::abs(got.I_BBcm_B().Ixz()), 1e-3 * got.I_BBcm_B().Trace());
}

TEST(DensityField, RadialDensityOnASphere) {
  // rho = rho0 (1 + r²/R²): m = 4 pi rho0 ∫ (r² + r⁴/R²) dr = 4 pi rho0 R³ (1/3 + 1/5);
  // ∫ r² dm = 4 pi rho0 R⁵ (1/5 + 1/7); by symmetry each moment is (2/3) ∫ r² dm.
  const double rho0 = 800, R = 0.25;
  const double m = 4 * pi * rho0 * std::pow(R, 3) * (1.0 / 3 + 1.0 / 5);
  const double I = 2.0 / 3 * 4 * pi * rho0 * std::pow(R, 5) * (1.0 / 5 + 1.0 / 7);
  const MassProperties got = IntegrateDensity(
      *MakeSolidSphere(R), [&](const Vec3& p) { return rho0 * (1 + p.squaredNorm() / (R * R)); });
  ExpectSame(got, MassProperties(m, Vec3::Zero(), RotationalInertia(I, I, I)), kTol, R);
}

// Example 8.1: a cylinder of radius R and height h, aluminium (2712 kg/m³) below height h1 and
// lead (11340 kg/m³) above. The chapter's answer, with z measured from the base:
//   m = rho_Pb pi R² h (1 - c h1/h),  z̄/h = (1 - c (h1/h)²) / (2 (1 - c h1/h)),
//   c = 1 - rho_Al/rho_Pb.
constexpr double kRhoAl = 2712, kRhoPb = 11340;
double Example81Height(double h1_over_h) {
  const double c = 1 - kRhoAl / kRhoPb;
  return (1 - c * h1_over_h * h1_over_h) / (2 * (1 - c * h1_over_h));
}

TEST(DensityField, Example81AsTwoCylinders) {
  const double R = 0.1, h = 0.5;
  const double c = 1 - kRhoAl / kRhoPb;
  for (double f : {0.1, 0.3, 0.5, 0.8}) {
    SCOPED_TRACE(f);
    const double h1 = f * h;
    const auto al = MakeSolidCylinder(R, h1);
    const auto pb = MakeSolidCylinder(R, h - h1);
    // Each part placed with its centre above the base (base at z = 0 in the body frame).
    const MassProperties body =
        al->CalcMassProperties(kRhoAl * al->CalcMeasure())
            .ExpressedInParent(Mat3::Identity(), Vec3(0, 0, h1 / 2)) +
        pb->CalcMassProperties(kRhoPb * pb->CalcMeasure())
            .ExpressedInParent(Mat3::Identity(), Vec3(0, 0, h1 + (h - h1) / 2));
    EXPECT_TRUE(Near(body.mass(), kRhoPb * pi * R * R * h * (1 - c * f), kExact));
    EXPECT_TRUE(Near(body.p_BoBcm_B().z(), h * Example81Height(f), kExact));
  }
  // The chapter's limits: all lead (h1 = 0) and all aluminium (h1 = h) balance at h/2.
  EXPECT_TRUE(Near(Example81Height(0), 0.5, kExact));
  EXPECT_TRUE(Near(Example81Height(1), 0.5, kExact));
}

TEST(DensityField, Example81AsAStepInDensity) {
  // The same body as one density field on the centred cylinder. The step lies on a coordinate
  // surface of the unit-cube map (u2 = h1/h), so bisection along u2 isolates it.
  const double R = 0.1, h = 0.5, f = 0.3, h1 = f * h;
  DensityIntegrationReport report;
  const MassProperties got = IntegrateDensity(
      *MakeSolidCylinder(R, h), [&](const Vec3& p) { return p.z() + h / 2 < h1 ? kRhoAl : kRhoPb; },
      kTol, &report);
  const double c = 1 - kRhoAl / kRhoPb;
  EXPECT_TRUE(Near(got.mass(), kRhoPb * pi * R * R * h * (1 - c * f), kTol));
  EXPECT_TRUE(Near(got.p_BoBcm_B().z() + h / 2, h * Example81Height(f), kTol));
  EXPECT_LE(report.estimated_relative_error, kTol);
}

TEST(DensityField, SmoothGradedCylinderFromAluminiumToLead) {
  // A smooth version of Example 8.1: rho = rho_Al e^(kappa s), s = z + h/2 the height above the
  // base, kappa = ln(rho_Pb/rho_Al)/h, so the density runs from aluminium to lead. With
  // E = e^(kappa h) = rho_Pb/rho_Al, the integrals ∫0^h s^n e^(kappa s) ds are
  //   M0 = (E - 1)/kappa,  M1 = E (h/kappa - 1/kappa²) + 1/kappa²,
  //   M2 = E (h²/kappa - 2h/kappa² + 2/kappa³) - 2/kappa³,
  // and m = rho_Al pi R² M0, s̄ = M1/M0, Izz = m R²/2,
  // Ixx = m R²/4 + rho_Al pi R² (M2 - M0 s̄²).
  const double R = 0.1, h = 0.5;
  const double kappa = std::log(kRhoPb / kRhoAl) / h, E = kRhoPb / kRhoAl;
  const double M0 = (E - 1) / kappa;
  const double M1 = E * (h / kappa - 1 / (kappa * kappa)) + 1 / (kappa * kappa);
  const double M2 = E * (h * h / kappa - 2 * h / (kappa * kappa) + 2 / std::pow(kappa, 3)) -
                    2 / std::pow(kappa, 3);
  const double A = kRhoAl * pi * R * R;
  const double m = A * M0, sbar = M1 / M0;
  const double Ixx = m * R * R / 4 + A * (M2 - M0 * sbar * sbar);
  const MassProperties want(m, Vec3(0, 0, sbar - h / 2),
                            RotationalInertia(Ixx, Ixx, m * R * R / 2));
  const MassProperties got = IntegrateDensity(*MakeSolidCylinder(R, h), [&](const Vec3& p) {
    return kRhoAl * std::exp(kappa * (p.z() + h / 2));
  });
  ExpectSame(got, want, kTol, h);
  // Heavier on top: the centre of mass is above the middle.
  EXPECT_GT(got.p_BoBcm_B().z(), 0.0);
}

TEST(DensityField, SmoothFieldsAreFastOnEverySolid) {
  // A smooth but nowhere-polynomial field: the work must stay far below 0.1 s (about 1.5
  // million evaluations at the measured few tens of nanoseconds each), and tightening the
  // tolerance must not move the answer by more than the looser one promised.
  const auto rho = [](const Vec3& p) {
    return 1000 * (2 + std::sin(5 * p.x()) * std::cos(3 * p.y()) + std::tanh(p.z()));
  };
  for (const auto& s : AllSolids()) {
    SCOPED_TRACE(s->Describe());
    DensityIntegrationReport report;
    const auto start = std::chrono::steady_clock::now();
    const MassProperties loose = IntegrateDensity(*s, rho, 1e-8, &report);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::printf("%-22s %8ld evaluations %4d regions error %.2g  %.4f s\n",
                std::string(s->kind()).c_str(), report.evaluations, report.regions,
                report.estimated_relative_error, seconds);
    EXPECT_LT(report.evaluations, 1'500'000);
    const MassProperties tight = IntegrateDensity(*s, rho, 1e-12);
    ExpectSame(loose, tight, 1e-8, 1.0);
  }
}

// The InputError message of `f`, or "" when it does not throw.
std::string ErrorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(DensityField, NegativeDensityIsNamedWithItsPoint) {
  const auto cyl = MakeSolidCylinder(0.1, 1);
  const std::string msg = ErrorOf(
      [&] { IntegrateDensity(*cyl, [](const Vec3& p) { return p.z() > 0.25 ? -3.0 : 1.0; }); });
  EXPECT_THAT(msg, HasSubstr("cylinder: density is -3 kg/m^3 at ("));
  EXPECT_THAT(msg, HasSubstr("m of the part's frame; a density cannot be negative"));
}

TEST(DensityField, NonFiniteDensityIsAnError) {
  const auto box = MakeBox(1, 1, 1);
  EXPECT_THAT(ErrorOf([&] { IntegrateDensity(*box, [](const Vec3&) { return NAN; }); }),
              HasSubstr("box: density is not a number at ("));
  EXPECT_THAT(ErrorOf([&] { IntegrateDensity(*box, [](const Vec3&) { return INFINITY; }); }),
              HasSubstr("box: density is infinite at ("));
}

TEST(DensityField, ZeroMassIsAnError) {
  EXPECT_THAT(
      ErrorOf([] { IntegrateDensity(*MakeSolidSphere(1), [](const Vec3&) { return 0.0; }); }),
      HasSubstr("sphere: the density integrates to a total mass of 0 kg"));
}

TEST(DensityField, ThinShapesAreRejected) {
  EXPECT_THAT(ErrorOf([] { IntegrateDensity(*MakeThinDisk(1), [](const Vec3&) { return 1.0; }); }),
              HasSubstr("disk: a density field needs a solid, but this is a thin shape"));
}

TEST(DensityField, BadToleranceIsAnError) {
  EXPECT_THAT(ErrorOf([] {
                IntegrateDensity(
                    *MakeBox(1, 1, 1), [](const Vec3&) { return 1.0; }, 1e-16);
              }),
              HasSubstr("relative tolerance 1e-16 must be at least 1e-14"));
}

TEST(DensityField, UnreachableToleranceSaysWhatWasReached) {
  // A step across an oblique plane is no coordinate surface of the box's map: the error falls
  // only slowly with bisection, and the budget runs out well before 1e-12.
  const std::string msg = ErrorOf([] {
    IntegrateDensity(
        *MakeBox(1, 1, 1), [](const Vec3& p) { return p.x() + p.y() + p.z() > 0.1 ? 2.0 : 1.0; },
        1e-12);
  });
  EXPECT_THAT(msg, HasSubstr("box: density integration reached an estimated relative error of"));
  EXPECT_THAT(msg, HasSubstr("short of the requested 1e-12"));
}

}  // namespace
}  // namespace chasles
