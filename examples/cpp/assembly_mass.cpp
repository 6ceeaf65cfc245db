// Mass properties of an assembly (the chapter's Example 8.2): two slender rods of the same
// material. The vertical rod (mass 2m, length 2l) stands on the origin O along z; the
// horizontal rod (mass m, length l) leaves its midpoint along y.
//
// Closed forms, derived here:
//  - centre of mass (eq. 8.4): (2m (0, 0, l) + m (0, l/2, l)) / 3m = (0, l/6, l);
//  - inertia about O (eq. 8.16, the chapter's sign convention Iyz = -∫yz dm): the vertical
//    rod gives 2m (2l)²/3 about x and y; the horizontal rod m (l² + l²/3) about x (it lies at
//    height l), m l²/3 about z, m l² about y and the product -∫yz dm = -m l (l/2):
//      [I_O] = m l² [[4, 0, 0], [0, 11/3, -1/2], [0, -1/2, 1/3]];
//  - about the centre of mass (parallel-axis theorem, eq. 8.29, with d = (0, l/6, l), 3m):
//      [I_cm] = [I_O] - 3m (|d|² E - d dᵀ) = m l² diag(11/12, 2/3, 1/4)
//    (diagonal: each rod is symmetric about the centre of mass along its own length);
//  - principal moments about O: 4 m l² about x, and in the y-z block [[a, b], [b, c]] with
//    a = 11/3, b = -1/2, c = 1/3: (a + c)/2 ± sqrt(((a - c)/2)² + b²) = 2 ± sqrt(109)/6;
//    the axis of the larger one is at θ = atan2(2b, a - c)/2 from y towards z.
// The program exits 1 if any value differs from its closed form by more than 1e-9 relative.
#include <cmath>
#include <cstdio>
#include <numbers>

#include "chasles/chasles.h"

namespace {

bool all_ok = true;

// Prints one comparison and remembers a failure; `scale` sets the size that 1e-9 is relative
// to (the value itself unless it is zero).
void Check(const char* what, double value, double expected, double scale = 0) {
  const double ref = scale > 0 ? scale : std::abs(expected);
  const double rel = std::abs(value - expected) / ref;
  const bool ok = rel <= 1e-9;
  all_ok = all_ok && ok;
  std::printf("  %-28s %16.12f   closed form %16.12f   rel. error %.1e %s\n", what, value, expected,
              rel, ok ? "" : "  <-- FAILED");
}

}  // namespace

int main() {
  using namespace chasles;
  const double m = 1.5;  // kg
  const double l = 0.4;  // m

  // 1. Each part's mass properties in its own frame S (a rod lies along z of S, centred).
  const MassProperties vertical_S = MakeSlenderRod(2 * l)->CalcMassProperties(2 * m);
  const MassProperties horizontal_S = MakeSlenderRod(l)->CalcMassProperties(m);

  // 2. Placed in the assembly's frame B (origin O): the vertical rod's centre at (0, 0, l); the
  //    horizontal rod turned so that its z axis points along y, centred at (0, l/2, l).
  const MassProperties vertical = vertical_S.ExpressedInParent(Mat3::Identity(), Vec3(0, 0, l));
  const MassProperties horizontal =
      horizontal_S.ExpressedInParent(RotationTakingZTo(Vec3::UnitY()), Vec3(0, l / 2, l));

  // 3. The composite: mass-weighted centre of mass, each part's inertia shifted to it.
  const MassProperties assembly = vertical + horizontal;
  assembly.Validate("two-rod assembly");

  const double ml2 = m * l * l;
  std::printf("Example 8.2, two rods: m = %g kg, l = %g m\n", m, l);
  std::printf("mass [kg]\n");
  Check("mass", assembly.mass(), 3 * m);
  std::printf("centre of mass from O [m]\n");
  const Vec3& c = assembly.p_BoBcm_B();
  Check("x", c.x(), 0, l);
  Check("y", c.y(), l / 6);
  Check("z", c.z(), l);

  // 4. Inertia about the centre of mass, and about O by the parallel-axis theorem.
  const RotationalInertia& I_cm = assembly.I_BBcm_B();
  std::printf("inertia about the centre of mass [kg m^2]\n");
  Check("Ixx", I_cm.Ixx(), 11.0 / 12 * ml2);
  Check("Iyy", I_cm.Iyy(), 2.0 / 3 * ml2);
  Check("Izz", I_cm.Izz(), 1.0 / 4 * ml2);
  Check("Iyz", I_cm.Iyz(), 0, ml2);
  const RotationalInertia I_O = assembly.CalcInertiaAbout(Vec3::Zero());
  std::printf("inertia about O [kg m^2]\n");
  Check("Ixx", I_O.Ixx(), 4 * ml2);
  Check("Iyy", I_O.Iyy(), 11.0 / 3 * ml2);
  Check("Izz", I_O.Izz(), 1.0 / 3 * ml2);
  Check("Iyz", I_O.Iyz(), -0.5 * ml2);
  Check("Ixy", I_O.Ixy(), 0, ml2);
  Check("Ixz", I_O.Ixz(), 0, ml2);

  // 5. Principal moments (ascending) and axes about O.
  const PrincipalAxes principal = I_O.CalcPrincipalAxes();
  const double root = std::sqrt(109.0) / 6;
  std::printf("principal moments about O [kg m^2]\n");
  Check("I1", principal.moments(0), (2 - root) * ml2);
  Check("I2", principal.moments(1), (2 + root) * ml2);
  Check("I3", principal.moments(2), 4 * ml2);
  const double a = 11.0 / 3, b = -0.5, cc = 1.0 / 3;
  const double theta = 0.5 * std::atan2(2 * b, a - cc);
  const Vec3 axis2(0, std::cos(theta), std::sin(theta));
  std::printf("principal axes about O: I2 at %.6f deg from y towards z, I3 along x\n",
              theta * 180 / std::numbers::pi);
  // An axis is defined up to its sign: turn the computed one towards the closed form first.
  const Vec3 e2 = principal.axes.col(1).dot(axis2) < 0 ? Vec3(-principal.axes.col(1))
                                                       : Vec3(principal.axes.col(1));
  Check("axis2 x", e2.x(), 0, 1);
  Check("axis2 y", e2.y(), axis2.y());
  Check("axis2 z", e2.z(), axis2.z());
  Check("|axis3 x|", std::abs(principal.axes(0, 2)), 1);

  std::printf(all_ok ? "all values agree with the closed forms\n"
                     : "SOME VALUES DISAGREE WITH THE CLOSED FORMS\n");
  return all_ok ? 0 : 1;
}
