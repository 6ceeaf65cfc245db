// Solids with flat faces (Appendix A): the rectangular box and the triangular prism.

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "chasles/error.h"
#include "chasles/mass/shape.h"
#include "mass/internal/shape_checks.h"

namespace chasles {
namespace {

using internal::RequirePositiveLength;

class Box final : public Shape {
 public:
  Box(double a, double b, double c) : a_(a), b_(b), c_(c) {
    RequirePositiveLength(kind(), "size along x", a);
    RequirePositiveLength(kind(), "size along y", b);
    RequirePositiveLength(kind(), "size along z", c);
  }
  std::string_view kind() const override { return "box"; }
  Measure measure() const override { return Measure::kVolume; }
  std::vector<ShapeDimension> dimensions() const override {
    return {{"size_x", a_}, {"size_y", b_}, {"size_z", c_}};
  }
  double CalcMeasure() const override { return a_ * b_ * c_; }
  double CalcSurfaceArea() const override { return 2 * (a_ * b_ + b_ * c_ + c_ * a_); }
  Vec3 CalcCentroid() const override { return Vec3::Zero(); }
  // ∫ x² dm = m a²/12 for a uniform segment of length a: Ixx = m (b² + c²)/12, etc.
  RotationalInertia CalcUnitInertia() const override {
    return RotationalInertia((b_ * b_ + c_ * c_) / 12, (a_ * a_ + c_ * c_) / 12,
                             (a_ * a_ + b_ * b_) / 12);
  }
  // p = (u - 1/2) * (a, b, c) componentwise: J = a b c.
  void MapUnitCube(const Vec3& u, Vec3* p, double* J) const override {
    *p = Vec3(a_ * (u[0] - 0.5), b_ * (u[1] - 0.5), c_ * (u[2] - 0.5));
    *J = a_ * b_ * c_;
  }

 private:
  double a_, b_, c_;
};

double Cross2(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

class TriangularPrism final : public Shape {
 public:
  TriangularPrism(const Eigen::Vector2d& v0, const Eigen::Vector2d& v1, const Eigen::Vector2d& v2,
                  double h)
      : v_{v0, v1, v2}, h_(h) {
    for (int k = 0; k < 3; ++k) {
      if (!v_[k].allFinite()) {
        throw InputError(fmt::format("{}: vertex {} ({:.6g}, {:.6g}) m is not a finite point",
                                     kind(), k, v_[k].x(), v_[k].y()));
      }
    }
    RequirePositiveLength(kind(), "length", h);
    twice_area_ = std::abs(Cross2(v1 - v0, v2 - v0));
    const double longest = std::max({(v1 - v0).norm(), (v2 - v1).norm(), (v0 - v2).norm()});
    // Relative to the longest edge squared, so the test does not depend on the unit of length.
    if (!(twice_area_ > 1e-12 * longest * longest)) {
      throw InputError(fmt::format(
          "{}: the vertices ({:.6g}, {:.6g}), ({:.6g}, {:.6g}), ({:.6g}, {:.6g}) m are collinear "
          "or coincide (triangle area {:.6g} m²); give three vertices that span a triangle",
          kind(), v0.x(), v0.y(), v1.x(), v1.y(), v2.x(), v2.y(), twice_area_ / 2));
    }
  }
  std::string_view kind() const override { return "triangular_prism"; }
  Measure measure() const override { return Measure::kVolume; }
  std::vector<ShapeDimension> dimensions() const override {
    return {{"vertex0_x", v_[0].x()},
            {"vertex0_y", v_[0].y()},
            {"vertex1_x", v_[1].x()},
            {"vertex1_y", v_[1].y()},
            {"vertex2_x", v_[2].x()},
            {"vertex2_y", v_[2].y()},
            {"length", h_}};
  }
  double CalcMeasure() const override { return twice_area_ / 2 * h_; }
  // Two triangular ends 2A and three rectangular sides, the perimeter times the length.
  double CalcSurfaceArea() const override {
    const double perimeter =
        (v_[1] - v_[0]).norm() + (v_[2] - v_[1]).norm() + (v_[0] - v_[2]).norm();
    return twice_area_ + perimeter * h_;
  }
  Vec3 CalcCentroid() const override {
    const Eigen::Vector2d c = (v_[0] + v_[1] + v_[2]) / 3;
    return Vec3(c.x(), c.y(), 0);
  }
  // Triangle second moments about its centroid: ∫ d dᵀ dA = (A/12) Σ_k d_k d_kᵀ with d_k the
  // vertices relative to the centroid (from ∫ p pᵀ dA = (A/12)(Σ v vᵀ + (Σ v)(Σ v)ᵀ), the
  // exact quadratic moment of the barycentric simplex). Per unit mass, C = Σ d dᵀ / 12; the
  // extrusion adds h²/12 along z and no xz, yz products. Ixy = -∫ xy dm = -Cxy.
  RotationalInertia CalcUnitInertia() const override {
    const Eigen::Vector2d c = (v_[0] + v_[1] + v_[2]) / 3;
    Eigen::Matrix2d C = Eigen::Matrix2d::Zero();
    for (const Eigen::Vector2d& v : v_) C += (v - c) * (v - c).transpose();
    C /= 12;
    const double zz = h_ * h_ / 12;
    return RotationalInertia(C(1, 1) + zz, C(0, 0) + zz, C(0, 0) + C(1, 1), -C(0, 1));
  }
  // Collapsed (Duffy) map of the square onto the triangle:
  // q = v0 + u0 ((v1 - v0) + u1 (v2 - v1)), z = h (u2 - 1/2); det ∂q/∂(u0,u1) = u0 (2A).
  void MapUnitCube(const Vec3& u, Vec3* p, double* J) const override {
    const Eigen::Vector2d q = v_[0] + u[0] * ((v_[1] - v_[0]) + u[1] * (v_[2] - v_[1]));
    *p = Vec3(q.x(), q.y(), h_ * (u[2] - 0.5));
    *J = u[0] * twice_area_ * h_;
  }

 private:
  Eigen::Vector2d v_[3];
  double h_;
  double twice_area_ = 0;
};

}  // namespace

std::unique_ptr<Shape> MakeBox(double size_x, double size_y, double size_z) {
  return std::make_unique<Box>(size_x, size_y, size_z);
}
std::unique_ptr<Shape> MakeTriangularPrism(const Eigen::Vector2d& v0, const Eigen::Vector2d& v1,
                                           const Eigen::Vector2d& v2, double length) {
  return std::make_unique<TriangularPrism>(v0, v1, v2, length);
}

}  // namespace chasles
