// Thin shells of revolution (Appendix A and their kin): cylindrical, spherical, hemispherical,
// conical and toroidal shells, mass per unit area in the limit of zero wall thickness. An open
// shell may be closed by the flat disks on its rims, of the same areal density. Each is a sum
// of pieces on the z axis, each piece given by its area, the height of its centroid and its
// inertia per unit mass about that centroid, joined by the parallel-axis theorem.

#include <cmath>
#include <initializer_list>
#include <memory>
#include <numbers>
#include <string_view>
#include <utility>
#include <vector>

#include "chasles/mass/shape.h"
#include "mass/internal/shape_checks.h"

namespace chasles {
namespace {

using internal::RequirePositiveLength;
using internal::RequireSmaller;
using std::numbers::pi;

// One surface of revolution about z: area [m²], centroid height [m], and the inertia per unit
// mass about its centroid [m²], about z (axial) and about a transverse axis.
struct AxialPiece {
  double area;
  double z;
  double axial;
  double transverse;
};

// A thin disk of radius R at height z: Izz = m R²/2, Ixx = m R²/4 (thin_shapes.cpp).
AxialPiece Disk(double R, double z) {
  return {pi * R * R, z, R * R / 2, R * R / 4};
}

// Pieces of one areal density joined: mass in proportion to area, the centroid the
// area-weighted mean, and each transverse inertia moved to the common centroid by the
// parallel-axis theorem (eq. 8.29), I = Σ A_i (I_i + (z_i - z̄)²) / Σ A_i. The axial
// inertias add as they are (every piece is centred on the axis).
AxialPiece Join(std::initializer_list<AxialPiece> pieces) {
  AxialPiece sum{0, 0, 0, 0};
  for (const AxialPiece& p : pieces) {
    sum.area += p.area;
    sum.z += p.area * p.z;
  }
  sum.z /= sum.area;
  for (const AxialPiece& p : pieces) {
    const double d = p.z - sum.z;
    sum.axial += p.area * p.axial;
    sum.transverse += p.area * (p.transverse + d * d);
  }
  sum.axial /= sum.area;
  sum.transverse /= sum.area;
  return sum;
}

// A thin surface of revolution about z of uniform areal density: the joined pieces.
class RevolvedSheet final : public Shape {
 public:
  RevolvedSheet(std::string_view kind, std::vector<ShapeDimension> dimensions, bool closed,
                const AxialPiece& sheet)
      : kind_(kind), dimensions_(std::move(dimensions)), closed_(closed), sheet_(sheet) {}
  std::string_view kind() const override { return kind_; }
  Measure measure() const override { return Measure::kArea; }
  std::vector<ShapeDimension> dimensions() const override { return dimensions_; }
  bool closed() const override { return closed_; }
  double CalcMeasure() const override { return sheet_.area; }
  double CalcSurfaceArea() const override { return sheet_.area; }  // a surface
  Vec3 CalcCentroid() const override { return Vec3(0, 0, sheet_.z); }
  RotationalInertia CalcUnitInertia() const override {
    return RotationalInertia(sheet_.transverse, sheet_.transverse, sheet_.axial);
  }

 private:
  std::string_view kind_;
  std::vector<ShapeDimension> dimensions_;
  bool closed_;
  AxialPiece sheet_;
};

}  // namespace

std::unique_ptr<Shape> MakeThinCylindricalShell(double radius, double length, bool closed) {
  constexpr std::string_view kind = "cylindrical_shell";
  RequirePositiveLength(kind, "radius", radius);
  RequirePositiveLength(kind, "length", length);
  const double R = radius, h = length;
  // The wall: Izz = m R² (all mass at radius R); Ixx = ∫ (y² + z²) dm = m R²/2 + m h²/12.
  const AxialPiece wall{2 * pi * R * h, 0, R * R, R * R / 2 + h * h / 12};
  const AxialPiece sheet = closed ? Join({wall, Disk(R, -h / 2), Disk(R, h / 2)}) : wall;
  return std::make_unique<RevolvedSheet>(
      kind, std::vector<ShapeDimension>{{"radius", R}, {"length", h}}, closed, sheet);
}

std::unique_ptr<Shape> MakeThinSphericalShell(double radius) {
  constexpr std::string_view kind = "spherical_shell";
  RequirePositiveLength(kind, "radius", radius);
  const double R = radius;
  // By symmetry Ixx = Iyy = Izz = (2/3) ∫ |p|² dm = (2/3) m R².
  const AxialPiece sheet{4 * pi * R * R, 0, 2 * R * R / 3, 2 * R * R / 3};
  return std::make_unique<RevolvedSheet>(kind, std::vector<ShapeDimension>{{"radius", R}}, false,
                                         sheet);
}

std::unique_ptr<Shape> MakeThinHemisphericalShell(double radius, bool closed) {
  constexpr std::string_view kind = "hemispherical_shell";
  RequirePositiveLength(kind, "radius", radius);
  const double R = radius;
  // Archimedes: the area of a sphere between two parallel planes is 2πR times their distance,
  // so the dome's area is spread uniformly over z in [0, R]: A = 2πR², centroid z = R/2 and
  // ∫ z² dA / A = R²/3. About the rim's centre every axis gives (2/3) m R², as for the whole
  // spherical shell (its two halves are mirror images). Moved to the centroid, the transverse
  // moment is 2/3 - (1/2)² = 5/12 of m R².
  const AxialPiece dome{2 * pi * R * R, R / 2, 2 * R * R / 3, 5 * R * R / 12};
  const AxialPiece sheet = closed ? Join({dome, Disk(R, 0)}) : dome;
  return std::make_unique<RevolvedSheet>(kind, std::vector<ShapeDimension>{{"radius", R}}, closed,
                                         sheet);
}

std::unique_ptr<Shape> MakeThinConicalShell(double radius, double height, bool closed) {
  constexpr std::string_view kind = "conical_shell";
  RequirePositiveLength(kind, "radius", radius);
  RequirePositiveLength(kind, "height", height);
  const double R = radius, h = height, s = std::hypot(R, h);
  // At height z = h ζ the surface is a hoop of radius ρ = R (1 - ζ) and slant width s dζ, so
  // dA = 2π R s (1 - ζ) dζ: A = π R s (s the slant height). Weighting by (1 - ζ):
  //   centroid  z = h ∫ ζ (1 - ζ) dζ / ∫ (1 - ζ) dζ = h (1/6) / (1/2) = h/3;
  //   axial     ∫ ρ² dm / m = R² ∫ (1 - ζ)³ dζ / (1/2) = R²/2;
  //   ∫ z² dm / m = h² ∫ ζ² (1 - ζ) dζ / (1/2) = h²/6.
  // Each hoop gives ρ²/2 about a diameter (perpendicular axes), so about a transverse axis
  // through the base centre I = m (R²/4 + h²/6), and through the centroid
  // I = m (R²/4 + h²/6 - h²/9) = m (R²/4 + h²/18).
  const AxialPiece lateral{pi * R * s, h / 3, R * R / 2, R * R / 4 + h * h / 18};
  const AxialPiece sheet = closed ? Join({lateral, Disk(R, 0)}) : lateral;
  return std::make_unique<RevolvedSheet>(
      kind, std::vector<ShapeDimension>{{"radius", R}, {"height", h}}, closed, sheet);
}

std::unique_ptr<Shape> MakeThinToroidalShell(double major_radius, double minor_radius) {
  constexpr std::string_view kind = "toroidal_shell";
  RequirePositiveLength(kind, "major radius", major_radius);
  RequirePositiveLength(kind, "minor radius", minor_radius);
  RequireSmaller(kind, "minor radius", minor_radius, "major radius", major_radius);
  const double R = major_radius, r = minor_radius;
  // The tube's circle, angle ψ, at distance σ = R + r cos ψ from z: dA = r σ dψ dφ, so
  // A = 4π² R r (Pappus). Izz = ∫ σ³ dψ / ∫ σ dψ = (R³ + (3/2) R r²) / R = R² + (3/2) r²;
  // ∫ z² dm / m = r² ∫ sin²ψ σ dψ / ∫ σ dψ = r²/2; Ixx = Izz/2 + r²/2 = R²/2 + (5/4) r².
  const AxialPiece sheet{4 * pi * pi * R * r, 0, R * R + 1.5 * r * r, R * R / 2 + 1.25 * r * r};
  return std::make_unique<RevolvedSheet>(
      kind, std::vector<ShapeDimension>{{"major_radius", R}, {"minor_radius", r}}, false, sheet);
}

}  // namespace chasles
