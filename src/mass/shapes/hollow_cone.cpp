// The hollow cone: a solid right circular cone (base radius R at z = 0, apex at z = h) with a
// wall of thickness t, exact as the difference of two solid cones.
//
// Moving the lateral surface inwards by t along its normal keeps its half-angle α
// (tan α = R/h) and lowers the apex by t / sin α = t s / R, s = √(R² + h²). The inner cone is
// therefore the outer one scaled by k about a point of the axis:
// - open (no base wall): the inner cone keeps the base plane z = 0; its height is h - t s/R,
//   so k = 1 - δ with δ = t s / (R h). It exists while t < R h / s, the distance from the
//   base centre to the lateral surface.
// - closed (a base wall of the same thickness): the inner base is raised to z = t as well, so
//   its height is h - t s/R - t and δ = t (s + R) / (R h). It exists while
//   t < R h / (R + s), the radius of the sphere inscribed in the cone. This inner cone is the
//   set of points at least t inside both faces, i.e. the wall is t thick everywhere.
// The solid cone (R, h) has V = π R² h / 3, centroid h/4 above its base, and per unit volume
// ∫ x² dV = (3/20) R² V, ∫ z² dV = h² V / 10 (about its base), ∫ (x² + y²) dV = (3/10) R² V
// (round_solids.cpp); the inner cone is the same with R, h scaled by k and V by k³, its base
// at z = b (0 open, t closed). Powers 1 - k^n are written as δ times a polynomial in δ, so that
// a thin wall loses no digits.

#include <cmath>
#include <memory>
#include <numbers>

#include <fmt/format.h>
#include <Eigen/Core>

#include "chasles/error.h"
#include "chasles/mass/shape.h"
#include "mass/internal/shape_checks.h"

namespace chasles {
namespace {

using internal::RequirePositiveLength;
using std::numbers::pi;

// A quadrilateral in the meridian half-plane (ρ, z), corners c[w][v], mapped bilinearly from
// (w, v) in [0, 1]² and swept round the z axis by θ = 2π u_theta. Returns the point and sets
// `J` to |∂(ρ, z)/∂(w, v)| ρ 2π, the volume per dw dv du_theta.
Vec3 RevolvedQuadPoint(const Eigen::Vector2d (&c)[2][2], double w, double v, double u_theta,
                       double* J) {
  const Eigen::Vector2d p =
      (1 - w) * (1 - v) * c[0][0] + w * (1 - v) * c[1][0] + (1 - w) * v * c[0][1] + w * v * c[1][1];
  const Eigen::Vector2d dw = (1 - v) * (c[1][0] - c[0][0]) + v * (c[1][1] - c[0][1]);
  const Eigen::Vector2d dv = (1 - w) * (c[0][1] - c[0][0]) + w * (c[1][1] - c[1][0]);
  const double theta = 2 * pi * u_theta;
  *J = std::abs(dw.x() * dv.y() - dw.y() * dv.x()) * p.x() * 2 * pi;
  return Vec3(p.x() * std::cos(theta), p.x() * std::sin(theta), p.y());
}

class HollowCone final : public Shape {
 public:
  HollowCone(double R, double h, double t, bool closed)
      : R_(R), h_(h), t_(t), closed_(closed), s_(std::hypot(R, h)) {
    RequirePositiveLength(kind(), "radius", R);
    RequirePositiveLength(kind(), "height", h);
    RequirePositiveLength(kind(), "thickness", t);
    const double limit = closed ? R * h / (R + s_) : R * h / s_;
    if (!(t < limit)) {
      throw InputError(fmt::format(
          "{}: thickness {:.6g} m must be smaller than {:.6g} m, {}", kind(), t, limit,
          closed ? "the radius of the sphere inscribed in the cone, R h / (R + √(R² + h²)): "
                   "a closed hollow cone has walls of that thickness on its side and its base"
                 : "the distance from the centre of the base to the lateral surface, "
                   "R h / √(R² + h²): a thicker wall leaves no hollow"));
    }
    delta_ = closed ? t * (s_ + R) / (R * h) : t * s_ / (R * h);
    k_ = 1 - delta_;
    b_ = closed ? t : 0.0;
    const double d = delta_;
    f3_ = d * (3 + d * (-3 + d));                         // 1 - k³
    f4_ = d * (4 + d * (-6 + d * (4 - d)));               // 1 - k⁴
    f5_ = d * (5 + d * (-10 + d * (10 + d * (-5 + d))));  // 1 - k⁵
  }
  std::string_view kind() const override { return "cone"; }
  Measure measure() const override { return Measure::kVolume; }
  std::vector<ShapeDimension> dimensions() const override {
    return {{"radius", R_}, {"height", h_}, {"thickness", t_}};
  }
  bool closed() const override { return closed_; }
  // V = (π R² h / 3)(1 - k³).
  double CalcMeasure() const override { return pi * R_ * R_ * h_ / 3 * f3_; }
  // Open: the outer and inner lateral surfaces π R s (1 + k²) and the annulus at the base
  // π R² (1 - k²). Closed: the whole outer and inner cones, π R (R + s)(1 + k²).
  double CalcSurfaceArea() const override {
    const double lateral = pi * R_ * s_ * (1 + k_ * k_);
    if (closed_) return lateral + pi * R_ * R_ * (1 + k_ * k_);
    return lateral + pi * R_ * R_ * delta_ * (2 - delta_);
  }
  // ∫ z dV = V₀ (h/4 - k³ (b + k h/4)) = V₀ (h (1 - k⁴)/4 - b k³), V = V₀ (1 - k³).
  Vec3 CalcCentroid() const override { return Vec3(0, 0, CentroidHeight()); }
  // Izz = (3/10) R² (1 - k⁵)/(1 - k³). Ixx: ∫ x² dV = V₀ (3/20) R² (1 - k⁵); about the base
  // plane ∫ z² dV = V₀ (h² (1 - k⁵)/10 - k³ (b k h/2 + b²)) (the inner cone's own
  // ∫ (z' + b)² dV = k³ V₀ (k² h²/10 + 2 b k h/4 + b²)); then moved to the centroid (eq. 8.29).
  RotationalInertia CalcUnitInertia() const override {
    const double k3 = k_ * k_ * k_;
    const double zc = CentroidHeight();
    const double Ixx =
        ((3 * R_ * R_ / 20 + h_ * h_ / 10) * f5_ - k3 * b_ * (k_ * h_ / 2 + b_)) / f3_ - zc * zc;
    return RotationalInertia(Ixx, Ixx, 3 * R_ * R_ / 10 * f5_ / f3_);
  }
  // Open: one quadrilateral of the meridian half-plane, the wall's section between the inner
  // (w = 0) and outer (w = 1) generators, v from the base (0) to the apexes (1). Closed: the
  // base wall for u2 < 1/2 and the side wall above, joined along the segment from the outer
  // rim (R, 0) to the inner rim (k R, t), each mapped over half the range of u2.
  void MapUnitCube(const Vec3& u, Vec3* p, double* J) const override {
    using V2 = Eigen::Vector2d;
    const double Ri = k_ * R_, hi = k_ * h_, t = b_;
    if (!closed_) {
      const V2 c[2][2] = {{V2(Ri, 0), V2(0, hi)}, {V2(R_, 0), V2(0, h_)}};
      *p = RevolvedQuadPoint(c, u[0], u[2], u[1], J);
      return;
    }
    if (u[2] < 0.5) {
      const V2 base[2][2] = {{V2(0, 0), V2(R_, 0)}, {V2(0, t), V2(Ri, t)}};
      *p = RevolvedQuadPoint(base, u[0], 2 * u[2], u[1], J);
    } else {
      const V2 side[2][2] = {{V2(R_, 0), V2(0, h_)}, {V2(Ri, t), V2(0, t + hi)}};
      *p = RevolvedQuadPoint(side, u[0], 2 * u[2] - 1, u[1], J);
    }
    *J *= 2;
  }

 private:
  double CentroidHeight() const { return (h_ * f4_ / 4 - b_ * k_ * k_ * k_) / f3_; }

  double R_, h_, t_;
  bool closed_;
  double s_;
  double delta_ = 0, k_ = 0, b_ = 0, f3_ = 0, f4_ = 0, f5_ = 0;
};

}  // namespace

std::unique_ptr<Shape> MakeHollowCone(double radius, double height, double thickness, bool closed) {
  return std::make_unique<HollowCone>(radius, height, thickness, closed);
}

}  // namespace chasles
