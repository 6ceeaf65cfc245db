// Solids of revolution and the ellipsoid (Appendix A): cylinder, tube, sphere, thick spherical
// shell, hemisphere, cone, ellipsoid, torus. Their unit-cube maps use cylindrical, spherical or
// toroidal coordinates with the radius linear in u, so that a density polynomial in x, y, z
// stays a polynomial (times sines and cosines) in u and the cubature converges fast.

#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>

#include <boost/math/special_functions/ellint_1.hpp>
#include <boost/math/special_functions/ellint_2.hpp>

#include "chasles/mass/shape.h"
#include "mass/internal/shape_checks.h"

namespace chasles {
namespace {

using internal::RequirePositiveLength;
using internal::RequireSmaller;
using std::numbers::pi;

// Spherical coordinates: radius r, polar angle theta = pi u1 from +z (or `theta_max` u1),
// azimuth phi = 2 pi u2. Returns the unit direction times r and r² sin(theta) d(theta) d(phi)
// per du1 du2, i.e. the angular part of the Jacobian.
Vec3 SphericalPoint(double r, double u1, double u2, double theta_max, double* angular_jacobian) {
  const double theta = theta_max * u1;
  const double phi = 2 * pi * u2;
  const double s = std::sin(theta);
  *angular_jacobian = r * r * s * theta_max * 2 * pi;
  return Vec3(r * s * std::cos(phi), r * s * std::sin(phi), r * std::cos(theta));
}

}  // namespace

double EllipsoidSurfaceArea(double a, double b, double c) {
  // Legendre's formula with the semi-axes sorted a >= b >= c:
  //   S = 2πc² + (2πab / sin φ) (E(φ, k) sin²φ + F(φ, k) cos²φ),
  //   cos φ = c/a,  k² = a² (b² - c²) / (b² (a² - c²)),
  // F and E the incomplete elliptic integrals of the first and second kind (modulus k). A
  // sphere (a = c, φ = 0) is the limit 4πa².
  double s[3] = {a, b, c};
  std::sort(s, s + 3, std::greater<double>());
  const double A = s[0], B = s[1], C = s[2];
  if (A == C) return 4 * pi * A * A;
  const double phi = std::acos(C / A);
  const double sin_phi = std::sin(phi), cos_phi = C / A;
  // a² - c² and b² - c² as products of sums and differences, free of cancellation.
  const double k2 = (A * A * (B - C) * (B + C)) / (B * B * (A - C) * (A + C));
  const double k = std::sqrt(std::min(k2, 1.0));
  const double E = boost::math::ellint_2(k, phi);
  const double F = boost::math::ellint_1(k, phi);
  return 2 * pi * C * C +
         2 * pi * A * B / sin_phi * (E * sin_phi * sin_phi + F * cos_phi * cos_phi);
}

namespace {

class SolidCylinder final : public Shape {
 public:
  SolidCylinder(double R, double h) : R_(R), h_(h) {
    RequirePositiveLength(kind(), "radius", R);
    RequirePositiveLength(kind(), "length", h);
  }
  std::string_view kind() const override { return "cylinder"; }
  Measure measure() const override { return Measure::kVolume; }
  std::vector<ShapeDimension> dimensions() const override {
    return {{"radius", R_}, {"length", h_}};
  }
  double CalcMeasure() const override { return pi * R_ * R_ * h_; }
  // Two end disks and the side: 2πR² + 2πRh.
  double CalcSurfaceArea() const override { return 2 * pi * R_ * (R_ + h_); }
  Vec3 CalcCentroid() const override { return Vec3::Zero(); }
  // Izz = ∫ r² dm = m R²/2 (disk); Ixx = m R²/4 (disk, perpendicular axes) + m h²/12 (rod).
  RotationalInertia CalcUnitInertia() const override {
    const double Ixx = R_ * R_ / 4 + h_ * h_ / 12;
    return RotationalInertia(Ixx, Ixx, R_ * R_ / 2);
  }
  // r = R u0, theta = 2 pi u1, z = h (u2 - 1/2): J = r * R * 2 pi * h.
  void MapUnitCube(const Vec3& u, Vec3* p, double* J) const override {
    const double r = R_ * u[0];
    const double t = 2 * pi * u[1];
    *p = Vec3(r * std::cos(t), r * std::sin(t), h_ * (u[2] - 0.5));
    *J = r * R_ * 2 * pi * h_;
  }

 private:
  double R_, h_;
};

class Tube final : public Shape {
 public:
  Tube(double Ri, double Ro, double h) : Ri_(Ri), Ro_(Ro), h_(h) {
    RequirePositiveLength(kind(), "inner radius", Ri);
    RequirePositiveLength(kind(), "outer radius", Ro);
    RequirePositiveLength(kind(), "length", h);
    RequireSmaller(kind(), "inner radius", Ri, "outer radius", Ro);
  }
  std::string_view kind() const override { return "tube"; }
  Measure measure() const override { return Measure::kVolume; }
  std::vector<ShapeDimension> dimensions() const override {
    return {{"inner_radius", Ri_}, {"outer_radius", Ro_}, {"length", h_}};
  }
  // pi (Ro² - Ri²) h, factored so that a thin wall loses no digits.
  double CalcMeasure() const override { return pi * (Ro_ - Ri_) * (Ro_ + Ri_) * h_; }
  // Outer and inner walls 2π(Ro + Ri)h and two annular ends 2π(Ro² - Ri²).
  double CalcSurfaceArea() const override {
    return 2 * pi * (Ro_ + Ri_) * h_ + 2 * pi * (Ro_ - Ri_) * (Ro_ + Ri_);
  }
  Vec3 CalcCentroid() const override { return Vec3::Zero(); }
  // Cylinder(Ro) minus cylinder(Ri): ∫ r² dm / m = (Ro⁴ - Ri⁴)/(2 (Ro² - Ri²)) = (Ro² + Ri²)/2;
  // Ixx = half of that (perpendicular axes) + h²/12.
  RotationalInertia CalcUnitInertia() const override {
    const double s = Ro_ * Ro_ + Ri_ * Ri_;
    const double Ixx = s / 4 + h_ * h_ / 12;
    return RotationalInertia(Ixx, Ixx, s / 2);
  }
  // r = Ri + (Ro - Ri) u0, theta = 2 pi u1, z = h (u2 - 1/2): J = r (Ro - Ri) 2 pi h.
  void MapUnitCube(const Vec3& u, Vec3* p, double* J) const override {
    const double r = Ri_ + (Ro_ - Ri_) * u[0];
    const double t = 2 * pi * u[1];
    *p = Vec3(r * std::cos(t), r * std::sin(t), h_ * (u[2] - 0.5));
    *J = r * (Ro_ - Ri_) * 2 * pi * h_;
  }

 private:
  double Ri_, Ro_, h_;
};

class SolidSphere final : public Shape {
 public:
  explicit SolidSphere(double R) : R_(R) { RequirePositiveLength(kind(), "radius", R); }
  std::string_view kind() const override { return "sphere"; }
  Measure measure() const override { return Measure::kVolume; }
  std::vector<ShapeDimension> dimensions() const override { return {{"radius", R_}}; }
  double CalcMeasure() const override { return 4 * pi * R_ * R_ * R_ / 3; }
  double CalcSurfaceArea() const override { return 4 * pi * R_ * R_; }
  Vec3 CalcCentroid() const override { return Vec3::Zero(); }
  // (2/3) ∫ |p|² dm = (2/3) m (3/5) R² = (2/5) m R² about every axis.
  RotationalInertia CalcUnitInertia() const override {
    const double I = 2 * R_ * R_ / 5;
    return RotationalInertia(I, I, I);
  }
  // r = R u0, polar angle pi u1, azimuth 2 pi u2: J = r² sin(theta) R pi 2 pi.
  void MapUnitCube(const Vec3& u, Vec3* p, double* J) const override {
    double Ja = 0;
    *p = SphericalPoint(R_ * u[0], u[1], u[2], pi, &Ja);
    *J = Ja * R_;
  }

 private:
  double R_;
};

class ThickSphericalShell final : public Shape {
 public:
  ThickSphericalShell(double Ri, double Ro) : Ri_(Ri), Ro_(Ro) {
    RequirePositiveLength(kind(), "inner radius", Ri);
    RequirePositiveLength(kind(), "outer radius", Ro);
    RequireSmaller(kind(), "inner radius", Ri, "outer radius", Ro);
  }
  std::string_view kind() const override { return "thick_spherical_shell"; }
  Measure measure() const override { return Measure::kVolume; }
  std::vector<ShapeDimension> dimensions() const override {
    return {{"inner_radius", Ri_}, {"outer_radius", Ro_}};
  }
  // (4/3) pi (Ro³ - Ri³) with Ro³ - Ri³ = (Ro - Ri)(Ro² + Ro Ri + Ri²): no cancellation.
  double CalcMeasure() const override {
    return 4 * pi * (Ro_ - Ri_) * (Ro_ * Ro_ + Ro_ * Ri_ + Ri_ * Ri_) / 3;
  }
  // The outer and the inner sphere: 4π(Ro² + Ri²).
  double CalcSurfaceArea() const override { return 4 * pi * (Ro_ * Ro_ + Ri_ * Ri_); }
  Vec3 CalcCentroid() const override { return Vec3::Zero(); }
  // Sphere(Ro) minus sphere(Ri): (2/5) (Ro⁵ - Ri⁵)/(Ro³ - Ri³), both differences divided by
  // (Ro - Ri) so that a thin wall tends to the thin shell's (2/3) R² without cancellation.
  RotationalInertia CalcUnitInertia() const override {
    const double a = Ro_, b = Ri_;
    const double num =
        a * a * a * a + a * a * a * b + a * a * b * b + a * b * b * b + b * b * b * b;
    const double den = a * a + a * b + b * b;
    const double I = 2 * num / (5 * den);
    return RotationalInertia(I, I, I);
  }
  // r = Ri + (Ro - Ri) u0, polar angle pi u1, azimuth 2 pi u2.
  void MapUnitCube(const Vec3& u, Vec3* p, double* J) const override {
    double Ja = 0;
    *p = SphericalPoint(Ri_ + (Ro_ - Ri_) * u[0], u[1], u[2], pi, &Ja);
    *J = Ja * (Ro_ - Ri_);
  }

 private:
  double Ri_, Ro_;
};

class SolidHemisphere final : public Shape {
 public:
  explicit SolidHemisphere(double R) : R_(R) { RequirePositiveLength(kind(), "radius", R); }
  std::string_view kind() const override { return "hemisphere"; }
  Measure measure() const override { return Measure::kVolume; }
  std::vector<ShapeDimension> dimensions() const override { return {{"radius", R_}}; }
  double CalcMeasure() const override { return 2 * pi * R_ * R_ * R_ / 3; }
  // The dome 2πR² and the flat face πR².
  double CalcSurfaceArea() const override { return 3 * pi * R_ * R_; }
  // ∫ z dV = pi R⁴/4 over the half ball of volume 2 pi R³/3: z = 3R/8.
  Vec3 CalcCentroid() const override { return Vec3(0, 0, 3 * R_ / 8); }
  // About the flat face's centre every axis gives (2/5) m R² (half of a sphere); shifting the
  // x and y axes to the centroid removes m (3R/8)²: 2/5 - 9/64 = 83/320.
  RotationalInertia CalcUnitInertia() const override {
    const double Ixx = 83 * R_ * R_ / 320;
    return RotationalInertia(Ixx, Ixx, 2 * R_ * R_ / 5);
  }
  // r = R u0, polar angle (pi/2) u1, azimuth 2 pi u2.
  void MapUnitCube(const Vec3& u, Vec3* p, double* J) const override {
    double Ja = 0;
    *p = SphericalPoint(R_ * u[0], u[1], u[2], pi / 2, &Ja);
    *J = Ja * R_;
  }

 private:
  double R_;
};

class SolidCone final : public Shape {
 public:
  SolidCone(double R, double h) : R_(R), h_(h) {
    RequirePositiveLength(kind(), "radius", R);
    RequirePositiveLength(kind(), "height", h);
  }
  std::string_view kind() const override { return "cone"; }
  Measure measure() const override { return Measure::kVolume; }
  std::vector<ShapeDimension> dimensions() const override {
    return {{"radius", R_}, {"height", h_}};
  }
  double CalcMeasure() const override { return pi * R_ * R_ * h_ / 3; }
  // The base πR² and the lateral surface πR s, s = sqrt(R² + h²) the slant height.
  double CalcSurfaceArea() const override { return pi * R_ * (R_ + std::hypot(R_, h_)); }
  // Cross-section area ∝ (h - z)²: z = ∫ z (h-z)² dz / ∫ (h-z)² dz = h/4.
  Vec3 CalcCentroid() const override { return Vec3(0, 0, h_ / 4); }
  // Izz = ∫ (disk R(z)²/2) dm = (3/10) m R². Ixx about the base = (3/20) m R² + m h²/10;
  // moved to the centroid: h²/10 - (h/4)² = 3 h²/80.
  RotationalInertia CalcUnitInertia() const override {
    const double Ixx = 3 * R_ * R_ / 20 + 3 * h_ * h_ / 80;
    return RotationalInertia(Ixx, Ixx, 3 * R_ * R_ / 10);
  }
  // z = h u2, local radius rho = R (1 - u2), r = rho u0, theta = 2 pi u1: J = r rho 2 pi h.
  void MapUnitCube(const Vec3& u, Vec3* p, double* J) const override {
    const double rho = R_ * (1 - u[2]);
    const double r = rho * u[0];
    const double t = 2 * pi * u[1];
    *p = Vec3(r * std::cos(t), r * std::sin(t), h_ * u[2]);
    *J = r * rho * 2 * pi * h_;
  }

 private:
  double R_, h_;
};

class Ellipsoid final : public Shape {
 public:
  Ellipsoid(double a, double b, double c) : a_(a), b_(b), c_(c) {
    RequirePositiveLength(kind(), "semi-axis along x", a);
    RequirePositiveLength(kind(), "semi-axis along y", b);
    RequirePositiveLength(kind(), "semi-axis along z", c);
  }
  std::string_view kind() const override { return "ellipsoid"; }
  Measure measure() const override { return Measure::kVolume; }
  std::vector<ShapeDimension> dimensions() const override {
    return {{"semi_axis_x", a_}, {"semi_axis_y", b_}, {"semi_axis_z", c_}};
  }
  double CalcMeasure() const override { return 4 * pi * a_ * b_ * c_ / 3; }
  double CalcSurfaceArea() const override { return EllipsoidSurfaceArea(a_, b_, c_); }
  Vec3 CalcCentroid() const override { return Vec3::Zero(); }
  // The unit ball stretched by (a, b, c): ∫ x² dm = m a²/5, so Ixx = m (b² + c²)/5, etc.
  RotationalInertia CalcUnitInertia() const override {
    return RotationalInertia((b_ * b_ + c_ * c_) / 5, (a_ * a_ + c_ * c_) / 5,
                             (a_ * a_ + b_ * b_) / 5);
  }
  // The unit ball's spherical map, stretched: J = a b c r² sin(theta) pi 2 pi.
  void MapUnitCube(const Vec3& u, Vec3* p, double* J) const override {
    double Ja = 0;
    const Vec3 q = SphericalPoint(u[0], u[1], u[2], pi, &Ja);
    *p = Vec3(a_ * q[0], b_ * q[1], c_ * q[2]);
    *J = Ja * a_ * b_ * c_;
  }

 private:
  double a_, b_, c_;
};

class Torus final : public Shape {
 public:
  Torus(double R, double r) : R_(R), r_(r) {
    RequirePositiveLength(kind(), "major radius", R);
    RequirePositiveLength(kind(), "minor radius", r);
    RequireSmaller(kind(), "minor radius", r, "major radius", R);
  }
  std::string_view kind() const override { return "torus"; }
  Measure measure() const override { return Measure::kVolume; }
  std::vector<ShapeDimension> dimensions() const override {
    return {{"major_radius", R_}, {"minor_radius", r_}};
  }
  // Pappus: tube cross-section pi r² swept along a circle of length 2 pi R.
  double CalcMeasure() const override { return 2 * pi * pi * R_ * r_ * r_; }
  // Pappus: the tube's circle 2πr swept round the circle of radius R: 4π² R r.
  double CalcSurfaceArea() const override { return 4 * pi * pi * R_ * r_; }
  Vec3 CalcCentroid() const override { return Vec3::Zero(); }
  // dV = s dA dphi over the tube's disk (radius r), s = R + x the distance from z:
  // Izz = ∫ s³ dA / ∫ s dA = (R³ + 3R r²/4)/R = R² + (3/4) r²; ∫ z² dm / m = r²/4, so
  // Ixx = Izz/2 + r²/4 = R²/2 + (5/8) r².
  RotationalInertia CalcUnitInertia() const override {
    const double Izz = R_ * R_ + 3 * r_ * r_ / 4;
    const double Ixx = R_ * R_ / 2 + 5 * r_ * r_ / 8;
    return RotationalInertia(Ixx, Ixx, Izz);
  }
  // rho = r u0, psi = 2 pi u1 around the tube, phi = 2 pi u2 around z, s = R + rho cos(psi):
  // p = (s cos phi, s sin phi, rho sin psi), J = rho s r (2 pi)².
  void MapUnitCube(const Vec3& u, Vec3* p, double* J) const override {
    const double rho = r_ * u[0];
    const double psi = 2 * pi * u[1];
    const double phi = 2 * pi * u[2];
    const double s = R_ + rho * std::cos(psi);
    *p = Vec3(s * std::cos(phi), s * std::sin(phi), rho * std::sin(psi));
    *J = rho * s * r_ * 4 * pi * pi;
  }

 private:
  double R_, r_;
};

}  // namespace

std::unique_ptr<Shape> MakeSolidCylinder(double radius, double length) {
  return std::make_unique<SolidCylinder>(radius, length);
}
std::unique_ptr<Shape> MakeTube(double inner_radius, double outer_radius, double length) {
  return std::make_unique<Tube>(inner_radius, outer_radius, length);
}
std::unique_ptr<Shape> MakeSolidSphere(double radius) {
  return std::make_unique<SolidSphere>(radius);
}
std::unique_ptr<Shape> MakeThickSphericalShell(double inner_radius, double outer_radius) {
  return std::make_unique<ThickSphericalShell>(inner_radius, outer_radius);
}
std::unique_ptr<Shape> MakeSolidHemisphere(double radius) {
  return std::make_unique<SolidHemisphere>(radius);
}
std::unique_ptr<Shape> MakeSolidCone(double radius, double height) {
  return std::make_unique<SolidCone>(radius, height);
}
std::unique_ptr<Shape> MakeEllipsoid(double semi_axis_x, double semi_axis_y, double semi_axis_z) {
  return std::make_unique<Ellipsoid>(semi_axis_x, semi_axis_y, semi_axis_z);
}
std::unique_ptr<Shape> MakeTorus(double major_radius, double minor_radius) {
  return std::make_unique<Torus>(major_radius, minor_radius);
}

}  // namespace chasles
