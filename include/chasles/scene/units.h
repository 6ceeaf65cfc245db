#pragma once
/// @file
/// Physical dimensions, the unit table of the scene format and the unit systems used for
/// output. Units exist only at the edges (scene input, report output): everything below the
/// scene layer is SI, so a Quantity always holds its value in SI.
///
/// Angles are dimensionless, as in SI: 1 rad = 1, 1 deg = pi/180, 1 rev = 2*pi. Hence
/// `100 rpm` is 100*2*pi/60 rad/s and `1 cps` (one cycle, i.e. one revolution, per second)
/// is 2*pi rad/s. There is deliberately no `Hz`: whether a hertz means 1/s or 2*pi rad/s is
/// exactly the ambiguity that produces silent factors of 2*pi.

#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace chasles {

/// Exponents of length, mass and time. Angle is dimensionless (SI convention).
struct Dimension {
  /// Exponent of length.
  int length = 0;
  /// Exponent of mass.
  int mass = 0;
  /// Exponent of time.
  int time = 0;

  friend bool operator==(const Dimension&, const Dimension&) = default;
  /// Dimension of a product: exponents add.
  friend Dimension operator*(const Dimension& a, const Dimension& b) {
    return {a.length + b.length, a.mass + b.mass, a.time + b.time};
  }
  /// Dimension of a quotient: exponents subtract.
  friend Dimension operator/(const Dimension& a, const Dimension& b) {
    return {a.length - b.length, a.mass - b.mass, a.time - b.time};
  }
  /// Dimension of this quantity raised to the integer power `n`.
  Dimension Pow(int n) const { return {length * n, mass * n, time * n}; }
  /// True for pure numbers (ratios and angles).
  bool IsDimensionless() const { return length == 0 && mass == 0 && time == 0; }

  /// The formula alone, e.g. "mass/length^3", "1/time", "dimensionless".
  std::string Formula() const;
  /// A human name where one exists plus the formula, e.g. "density (mass/length^3)";
  /// base dimensions are just "length", "mass", "time".
  std::string Describe() const;
};

/// The named dimensions, each defined here once: the scene reader, the reports and the commands
/// check quantities against them. Names that share a dimension (kRate and kAngularVelocity,
/// kEnergy and kMoment, kMomentum and kImpulse) say what the quantity is.
inline constexpr Dimension kDimensionless{0, 0, 0};
inline constexpr Dimension kLength{1, 0, 0};
inline constexpr Dimension kMass{0, 1, 0};
inline constexpr Dimension kTime{0, 0, 1};
inline constexpr Dimension kArea{2, 0, 0};
inline constexpr Dimension kVolume{3, 0, 0};
inline constexpr Dimension kDensity{-3, 1, 0};
inline constexpr Dimension kArealDensity{-2, 1, 0};
inline constexpr Dimension kLinearDensity{-1, 1, 0};
inline constexpr Dimension kVelocity{1, 0, -1};
inline constexpr Dimension kAcceleration{1, 0, -2};
inline constexpr Dimension kRate{0, 0, -1};
inline constexpr Dimension kAngularVelocity{0, 0, -1};
inline constexpr Dimension kAngularAcceleration{0, 0, -2};
inline constexpr Dimension kForce{1, 1, -2};
inline constexpr Dimension kMoment{2, 1, -2};
inline constexpr Dimension kEnergy{2, 1, -2};
inline constexpr Dimension kPower{2, 1, -3};
inline constexpr Dimension kPressure{-1, 1, -2};
inline constexpr Dimension kMomentum{1, 1, -1};
inline constexpr Dimension kImpulse{1, 1, -1};
inline constexpr Dimension kAngularMomentum{2, 1, -1};
inline constexpr Dimension kInertia{2, 1, 0};
inline constexpr Dimension kStiffness{0, 1, -2};
inline constexpr Dimension kLinearDamping{0, 1, -1};
inline constexpr Dimension kAngularDamping{2, 1, -1};
inline constexpr Dimension kGravitationalParameter{3, 0, -2};

/// A value with its dimension; the value is in SI units. NaN by default so that a value never
/// set shows.
struct Quantity {
  /// Value in SI units of `dim` (m, kg, s and their products; angles in rad).
  double value = std::numeric_limits<double>::quiet_NaN();
  /// Dimension of the value.
  Dimension dim;
};

/// The Quantity of one unit by its case-sensitive name ("in" is 0.0254 m, "rpm" is
/// 2*pi/60 1/s), or nullopt if the name is not a unit. Only single names: compose units with
/// the expression parser (ParseUnitSuffix("kg/m^3")).
std::optional<Quantity> LookupUnit(std::string_view name);

/// Every unit name LookupUnit knows, in table order.
const std::vector<std::string>& UnitNames();

/// The unit names closest to an unknown identifier (SuggestNames over UnitNames()).
std::vector<std::string> SuggestUnitNames(std::string_view name);

/// Whether a dimensionless or 1/time^n quantity carries an angle (angle, angular velocity,
/// angular acceleration): only then is it shown in rad, deg or rpm. A frequency or a ratio
/// is Angular::kNo. Ignored for dimensions that involve length or mass (angular momentum
/// is kg*m^2/s, not kg*m^2*rad/s).
enum class Angular { kNo, kYes };

/// Units for OUTPUT (reports). Built from a spec string: a comma-separated list of tokens,
/// applied left to right:
///  - "SI": m, kg, s, rad (the default for anything not listed);
///  - "US": in, lb (mass), s, rad, with forces in lbf;
///  - a length (m mm cm km um in ft yd mi), mass (kg g mg t lb lbm oz slug) or time
///    (s ms us min h) unit fixes that base dimension;
///  - an angle unit (rad deg rev) fixes how angles are shown (angular velocity becomes
///    angle/time, e.g. deg/s);
///  - "rpm" or "cps" shows angular velocities in that unit;
///  - a force unit (N kN lbf kip dyn) shows every mass*length/time^2 factor as that force
///    ("lbf*in" for torque). Without one, the force is named when the base units are
///    coherent with a named force (kg,m,s -> N; slug,ft,s -> lbf; g,cm,s -> dyn; t,m,s -> kN)
///    and is lbf whenever the mass is in pounds (lb, lbm); otherwise it is composed
///    ("g*mm/s^2").
/// e.g. "SI", "US", "mm,g", "ft,slug", "US,deg,rpm". Every shown value satisfies
/// value * factor(FormatUnit(dim)) == SI value, so mixing lb and lbf stays consistent.
class UnitSystem {
 public:
  /// SI: m, kg, s, rad; forces in N.
  UnitSystem();

  /// Parses a spec (see the class comment). Throws InputError naming the bad token and
  /// listing the accepted names.
  static UnitSystem Parse(std::string_view spec);

  /// The unit in which a quantity of dimension `dim` is shown, e.g. "kg*m^2", "lb*in^2",
  /// "N*m", "kg/m^3", "rad/s"; "" for a dimensionless non-angular quantity.
  std::string FormatUnit(const Dimension& dim, Angular angular = Angular::kNo) const;

  /// The SI value `value_si` of dimension `dim` expressed in FormatUnit(dim, angular).
  double FromSI(double value_si, const Dimension& dim, Angular angular = Angular::kNo) const;

  /// The SI value of `value` given in FormatUnit(dim, angular) (inverse of FromSI).
  double ToSI(double value, const Dimension& dim, Angular angular = Angular::kNo) const;

  /// The spec this system was parsed from ("SI" by default).
  const std::string& spec() const { return spec_; }

 private:
  struct Unit {
    std::string name;
    double factor = 1.0;  // SI value of one unit.
  };
  // The unit string and its SI factor for `dim`.
  Unit Compose(const Dimension& dim, Angular angular) const;
  /// Compose's factor alone (no name is built: a report converts millions of values).
  double Factor(const Dimension& dim, Angular angular) const;

  std::string spec_;
  Unit length_, mass_, time_, angle_;
  std::optional<Unit> force_;             // explicitly listed force unit
  std::optional<Unit> angular_velocity_;  // rpm or cps when listed
};

}  // namespace chasles
