#pragma once
/// @file
/// The text reports' formatting kit, one for every report for people (simulate, solve, mass):
/// values converted from SI to the units a reader asked for, round-off next to the size of its
/// kind of quantity printed as 0, times and energies. The JSON and CSV keep every digit in SI.

#include <string>

#include "chasles/math/types.h"
#include "chasles/scene/scene.h"
#include "chasles/scene/units.h"

namespace chasles {

/// Round-off thresholds: a value at most this fraction of the size of its kind of quantity
/// prints as 0. simulate and solve: their values come out of an integration or a linear solve,
/// whose rounding grows with the steps and the conditioning, so a component below 1e-12 of the
/// largest of its kind (a sideways force of 1e-15 N beside 9.81 N) is that rounding.
inline constexpr double kRunRoundOff = 1e-12;
/// mass: its values are closed-form sums over a body's parts, a few roundings each, so the
/// bound is tighter and keeps a small real product of inertia that 1e-12 would hide.
inline constexpr double kMassRoundOff = 1e-13;

/// `x`, or 0 when |x| <= threshold * scale (round-off next to `scale`).
double CleanRoundOff(double x, double scale, double threshold = kRunRoundOff);

/// What every text report is asked for by its reader.
struct TextOptions {
  /// Units of the report: "SI", "US", or a list such as "mm,g" or "ft,slug"; "" = the scene's
  /// own `units:`.
  std::string units;
  /// simulate: the CSV and JSON files its report names on its last line ("Wrote ...").
  std::string csv_path, json_path;
};

/// The unit system a report of `scene` is printed in (TextOptions::units, else the scene's).
/// Throws InputError naming a bad unit.
UnitSystem TextUnits(const Scene& scene, const TextOptions& options);

/// Values of a text report in its units: "9.81 m/s^2", "[1, 0, -2.5] N", "[x, y] m".
struct Show {
  UnitSystem units;
  /// Significant digits of every number.
  int digits = 9;
  /// The round-off threshold (kRunRoundOff or kMassRoundOff).
  double round_off = kRunRoundOff;
  /// The report's name in the error a value that is not finite raises.
  const char* what = "a value of the report";

  /// `x` as printed with `digits` significant digits; a negative zero (a zero force times -1)
  /// prints as the 0 a reader expects. Throws InputError when `x` is not finite.
  std::string Number(double x) const;
  /// `x` (checked finite), or 0 when it is round-off next to `scale` (CleanRoundOff).
  double Clean(double x, double scale) const;
  /// " unit", or "" for a pure number.
  std::string Unit(const Dimension& d, Angular a = Angular::kNo) const;
  /// The SI value `si` in the report's units, without the unit.
  std::string Num(double si, const Dimension& d, Angular a = Angular::kNo) const;
  /// "value unit".
  std::string operator()(double si, const Dimension& d, Angular a = Angular::kNo) const;
  /// "[x, y, z] unit"; a component that is round-off next to max(|v|, scale) prints as 0
  /// (`scale`: the size of that kind of quantity in the report, e.g. the largest acceleration
  /// of any body: a reader sees [2.83, 0, -1.63], not [2.83, -2.5e-32, -1.63]).
  std::string operator()(const Vec3& si, const Dimension& d, Angular a = Angular::kNo,
                         double scale = 0.0) const;
  /// The in-plane components "[x, y] unit" of a vector of a planar scene (round-off as above).
  std::string Xy(const Vec3& si, const Dimension& d, double scale = 0.0) const;
  /// "[x, y] unit" in a planar scene, else "[x, y, z] unit".
  std::string InPlane(bool planar, const Vec3& si, const Dimension& d, double scale = 0.0) const;
  /// A time.
  std::string Time(double t) const;
  /// An energy: as a moment (the same dimension), but in SI by its own name, the joule.
  std::string Energy(double e) const;
};

/// The report's title line: the scene's title and its file, or the file alone.
std::string TitleLine(const Scene& scene);

}  // namespace chasles
