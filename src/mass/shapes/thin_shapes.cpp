// Thin shapes of Appendix A: curves (rod, ring) and flat surfaces (disk, plate); the curved
// shells are in round_shells.cpp. Mass is spread over a length or an area; none can be mapped
// to a volume.

#include <numbers>

#include "chasles/mass/shape.h"
#include "mass/internal/shape_checks.h"

namespace chasles {
namespace {

using internal::RequirePositiveLength;
using std::numbers::pi;

class SlenderRod final : public Shape {
 public:
  explicit SlenderRod(double L) : L_(L) { RequirePositiveLength(kind(), "length", L); }
  std::string_view kind() const override { return "rod"; }
  Measure measure() const override { return Measure::kLength; }
  std::vector<ShapeDimension> dimensions() const override { return {{"length", L_}}; }
  double CalcMeasure() const override { return L_; }
  double CalcSurfaceArea() const override { return 0.0; }  // a curve
  Vec3 CalcCentroid() const override { return Vec3::Zero(); }
  // ∫ z² dm over a uniform segment [-L/2, L/2]: m L²/12 about x and y; nothing about its axis.
  RotationalInertia CalcUnitInertia() const override {
    return RotationalInertia(L_ * L_ / 12, L_ * L_ / 12, 0);
  }

 private:
  double L_;
};

class ThinRing final : public Shape {
 public:
  explicit ThinRing(double R) : R_(R) { RequirePositiveLength(kind(), "radius", R); }
  std::string_view kind() const override { return "ring"; }
  Measure measure() const override { return Measure::kLength; }
  std::vector<ShapeDimension> dimensions() const override { return {{"radius", R_}}; }
  double CalcMeasure() const override { return 2 * pi * R_; }
  double CalcSurfaceArea() const override { return 0.0; }  // a curve
  Vec3 CalcCentroid() const override { return Vec3::Zero(); }
  // All mass at distance R from z: Izz = m R²; perpendicular-axis theorem Ixx = Iyy = Izz/2.
  RotationalInertia CalcUnitInertia() const override {
    return RotationalInertia(R_ * R_ / 2, R_ * R_ / 2, R_ * R_);
  }

 private:
  double R_;
};

class ThinDisk final : public Shape {
 public:
  explicit ThinDisk(double R) : R_(R) { RequirePositiveLength(kind(), "radius", R); }
  std::string_view kind() const override { return "disk"; }
  Measure measure() const override { return Measure::kArea; }
  std::vector<ShapeDimension> dimensions() const override { return {{"radius", R_}}; }
  double CalcMeasure() const override { return pi * R_ * R_; }
  double CalcSurfaceArea() const override { return CalcMeasure(); }  // a surface
  Vec3 CalcCentroid() const override { return Vec3::Zero(); }
  // Izz = ∫ r² dm = m R²/2 (dm = 2m r dr / R²); perpendicular-axis theorem Ixx = Iyy = Izz/2.
  RotationalInertia CalcUnitInertia() const override {
    return RotationalInertia(R_ * R_ / 4, R_ * R_ / 4, R_ * R_ / 2);
  }

 private:
  double R_;
};

class ThinPlate final : public Shape {
 public:
  ThinPlate(double a, double b) : a_(a), b_(b) {
    RequirePositiveLength(kind(), "size along x", a);
    RequirePositiveLength(kind(), "size along y", b);
  }
  std::string_view kind() const override { return "plate"; }
  Measure measure() const override { return Measure::kArea; }
  std::vector<ShapeDimension> dimensions() const override {
    return {{"size_x", a_}, {"size_y", b_}};
  }
  double CalcMeasure() const override { return a_ * b_; }
  double CalcSurfaceArea() const override { return CalcMeasure(); }  // a surface
  Vec3 CalcCentroid() const override { return Vec3::Zero(); }
  // Ixx = ∫ y² dm = m b²/12, Iyy = m a²/12 (uniform segments); Izz = Ixx + Iyy (flat plate).
  RotationalInertia CalcUnitInertia() const override {
    return RotationalInertia(b_ * b_ / 12, a_ * a_ / 12, (a_ * a_ + b_ * b_) / 12);
  }

 private:
  double a_, b_;
};

}  // namespace

std::unique_ptr<Shape> MakeSlenderRod(double length) {
  return std::make_unique<SlenderRod>(length);
}
std::unique_ptr<Shape> MakeThinRing(double radius) {
  return std::make_unique<ThinRing>(radius);
}
std::unique_ptr<Shape> MakeThinDisk(double radius) {
  return std::make_unique<ThinDisk>(radius);
}
std::unique_ptr<Shape> MakeThinPlate(double size_x, double size_y) {
  return std::make_unique<ThinPlate>(size_x, size_y);
}

}  // namespace chasles
