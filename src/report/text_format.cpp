#include "chasles/report/text_format.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "chasles/report/json_report.h"

namespace chasles {

double CleanRoundOff(double x, double scale, double threshold) {
  return std::abs(x) <= threshold * scale ? 0.0 : x;
}

UnitSystem TextUnits(const Scene& scene, const TextOptions& options) {
  return UnitSystem::Parse(options.units.empty() ? scene.units : options.units);
}

std::string Show::Number(double x) const {
  // Adding 0.0 turns a negative zero into +0.
  return fmt::format("{:.{}g}", Finite(x, what) + 0.0, digits);
}

double Show::Clean(double x, double scale) const {
  return CleanRoundOff(Finite(x, what), scale, round_off);
}

std::string Show::Unit(const Dimension& d, Angular a) const {
  const std::string unit = units.FormatUnit(d, a);
  return unit.empty() ? "" : " " + unit;
}

std::string Show::Num(double si, const Dimension& d, Angular a) const {
  return Number(units.FromSI(si, d, a));
}

std::string Show::operator()(double si, const Dimension& d, Angular a) const {
  return Num(si, d, a) + Unit(d, a);
}

std::string Show::operator()(const Vec3& si, const Dimension& d, Angular a, double scale) const {
  // stableNorm: |v| of components near 1e200 overflows norm() to inf, and every component
  // would then print as round-off 0.
  const double s = std::max(si.stableNorm(), scale);
  return fmt::format("[{}, {}, {}]{}", Num(Clean(si.x(), s), d, a), Num(Clean(si.y(), s), d, a),
                     Num(Clean(si.z(), s), d, a), Unit(d, a));
}

std::string Show::Xy(const Vec3& si, const Dimension& d, double scale) const {
  const double s = std::max(si.head<2>().stableNorm(), scale);
  return fmt::format("[{}, {}]{}", Num(Clean(si.x(), s), d), Num(Clean(si.y(), s), d), Unit(d));
}

std::string Show::InPlane(bool planar, const Vec3& si, const Dimension& d, double scale) const {
  return planar ? Xy(si, d, scale) : (*this)(si, d, Angular::kNo, scale);
}

std::string Show::Time(double t) const {
  return (*this)(t, kTime);
}

std::string Show::Energy(double e) const {
  const std::string unit = units.FormatUnit(kEnergy);
  return Num(e, kEnergy) + (unit == "N*m" ? " J" : " " + unit);
}

std::string TitleLine(const Scene& scene) {
  return fmt::format("{}{}\n", scene.title.empty() ? scene.file : scene.title,
                     scene.title.empty() ? "" : fmt::format(" ({})", scene.file));
}

}  // namespace chasles
