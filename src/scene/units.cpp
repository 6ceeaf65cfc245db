#include "chasles/scene/units.h"

#include "chasles/suggest.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <numbers>

#include "chasles/error.h"

namespace chasles {
namespace {

constexpr double kPi = std::numbers::pi;

// Exact definitions (NIST SP 811, appendix B; international yard and pound of 1959;
// standard gravity g_n = 9.80665 m/s^2 from the 3rd CGPM, 1901).
constexpr double kInch = 0.0254;                           // m, exact
constexpr double kFoot = 12 * kInch;                       // 0.3048 m
constexpr double kPound = 0.45359237;                      // kg, exact
constexpr double kStandardGravity = 9.80665;               // m/s^2, exact
constexpr double kPoundForce = kPound * kStandardGravity;  // 4.4482216152605 N
constexpr double kSlug = kPoundForce / kFoot;              // lbf*s^2/ft = 14.5939029372... kg

struct UnitEntry {
  const char* name;
  double factor;
  Dimension dim;
};

// The unit table. Names are case-sensitive.
const std::array kUnits{
    // length
    UnitEntry{"m", 1.0, kLength},
    UnitEntry{"mm", 1e-3, kLength},
    UnitEntry{"cm", 1e-2, kLength},
    UnitEntry{"km", 1e3, kLength},
    UnitEntry{"um", 1e-6, kLength},
    UnitEntry{"in", kInch, kLength},
    UnitEntry{"ft", kFoot, kLength},
    UnitEntry{"yd", 3 * kFoot, kLength},
    UnitEntry{"mi", 5280 * kFoot, kLength},
    // mass
    UnitEntry{"kg", 1.0, kMass},
    UnitEntry{"g", 1e-3, kMass},
    UnitEntry{"mg", 1e-6, kMass},
    UnitEntry{"t", 1e3, kMass},
    UnitEntry{"lb", kPound, kMass},
    UnitEntry{"lbm", kPound, kMass},
    UnitEntry{"oz", kPound / 16, kMass},
    UnitEntry{"slug", kSlug, kMass},
    // time
    UnitEntry{"s", 1.0, kTime},
    UnitEntry{"ms", 1e-3, kTime},
    UnitEntry{"us", 1e-6, kTime},
    UnitEntry{"min", 60.0, kTime},
    UnitEntry{"h", 3600.0, kTime},
    // force
    UnitEntry{"N", 1.0, kForce},
    UnitEntry{"kN", 1e3, kForce},
    UnitEntry{"lbf", kPoundForce, kForce},
    UnitEntry{"kip", 1000 * kPoundForce, kForce},
    UnitEntry{"dyn", 1e-5, kForce},
    // energy, power, pressure
    UnitEntry{"J", 1.0, kEnergy},
    UnitEntry{"kJ", 1e3, kEnergy},
    UnitEntry{"W", 1.0, kPower},
    UnitEntry{"kW", 1e3, kPower},
    UnitEntry{"Pa", 1.0, kPressure},
    UnitEntry{"kPa", 1e3, kPressure},
    UnitEntry{"MPa", 1e6, kPressure},
    UnitEntry{"GPa", 1e9, kPressure},
    UnitEntry{"psi", kPoundForce / (kInch * kInch), kPressure},
    // angle (dimensionless) and angular velocity; a cycle is one revolution
    UnitEntry{"rad", 1.0, kDimensionless},
    UnitEntry{"deg", kPi / 180, kDimensionless},
    UnitEntry{"rev", 2 * kPi, kDimensionless},
    UnitEntry{"rpm", 2 * kPi / 60, kRate},
    UnitEntry{"cps", 2 * kPi, kRate},
    // volume
    UnitEntry{"L", 1e-3, kVolume},
    UnitEntry{"mL", 1e-6, kVolume},
};

void AppendPower(std::string& out, const char* name, int exponent) {
  out += name;
  if (exponent != 1) {
    out += '^';
    out += std::to_string(exponent);
  }
}

// "n1*n2/d1^2": names with positive exponents in the numerator, negative in the denominator.
// `factors` are (name, exponent) in display order.
std::string ComposeFormula(const std::vector<std::pair<std::string, int>>& factors) {
  std::string num, den;
  int den_count = 0;
  for (const auto& [name, e] : factors) {
    if (e > 0) {
      if (!num.empty()) num += "*";
      AppendPower(num, name.c_str(), e);
    } else if (e < 0) {
      if (!den.empty()) den += "*";
      AppendPower(den, name.c_str(), -e);
      ++den_count;
    }
  }
  if (num.empty() && den.empty()) return "";
  if (den.empty()) return num;
  if (num.empty()) num.push_back('1');
  // kg/m/s would be ambiguous to some readers; kg/(m*s) is not.
  std::string out = num;
  out += den_count > 1 ? "/(" : "/";
  out += den;
  if (den_count > 1) out += ')';
  return out;
}

// Optimal string alignment distance: Levenshtein plus adjacent transpositions ("lenght").

}  // namespace

std::string Dimension::Formula() const {
  if (IsDimensionless()) return "dimensionless";
  return ComposeFormula({{"mass", mass}, {"length", length}, {"time", time}});
}

std::string Dimension::Describe() const {
  struct Named {
    Dimension dim;
    const char* name;
  };
  static constexpr std::array kNames{
      Named{{1, 0, 0}, "length"},
      Named{{0, 1, 0}, "mass"},
      Named{{0, 0, 1}, "time"},
      Named{{2, 0, 0}, "area"},
      Named{{3, 0, 0}, "volume"},
      Named{{-3, 1, 0}, "density"},
      Named{{-2, 1, 0}, "areal density"},
      Named{{-1, 1, 0}, "linear density"},
      Named{{1, 0, -1}, "velocity"},
      Named{{1, 0, -2}, "acceleration"},
      Named{{0, 0, -1}, "angular velocity"},
      Named{{0, 0, -2}, "angular acceleration"},
      Named{{1, 1, -2}, "force"},
      Named{{2, 1, -2}, "torque or energy"},
      Named{{2, 1, -3}, "power"},
      Named{{-1, 1, -2}, "pressure or stress"},
      Named{{2, 1, 0}, "moment of inertia"},
      Named{{1, 1, -1}, "momentum or impulse"},
      Named{{2, 1, -1}, "angular momentum"},
      Named{{0, 1, -2}, "stiffness"},
      Named{{0, 1, -1}, "damping coefficient"},
  };
  if (IsDimensionless()) return "dimensionless (angle, ratio)";
  const std::string formula = Formula();
  for (const Named& n : kNames) {
    if (n.dim == *this) {
      if (formula == n.name) return formula;  // base dimensions name themselves
      return std::string(n.name) + " (" + formula + ")";
    }
  }
  return formula;
}

std::optional<Quantity> LookupUnit(std::string_view name) {
  for (const UnitEntry& u : kUnits) {
    if (name == u.name) return Quantity{u.factor, u.dim};
  }
  return std::nullopt;
}

const std::vector<std::string>& UnitNames() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> out;
    for (const UnitEntry& u : kUnits) out.emplace_back(u.name);
    return out;
  }();
  return names;
}

std::vector<std::string> SuggestUnitNames(std::string_view name) {
  return SuggestNames(name, UnitNames());
}

// ---------------------------------------------------------------------------------------
// UnitSystem

UnitSystem::UnitSystem()
    : spec_("SI"),
      length_{"m", 1.0},
      mass_{"kg", 1.0},
      time_{"s", 1.0},
      angle_{"rad", 1.0},
      force_(Unit{"N", 1.0}) {}

UnitSystem UnitSystem::Parse(std::string_view spec) {
  static const char* const kAccepted =
      "accepted: SI, US; length m mm cm km um in ft yd mi; mass kg g mg t lb lbm oz slug; "
      "time s ms us min h; angle rad deg rev; angular velocity rpm cps; force N kN lbf kip dyn";
  const auto fail = [&](const std::string& what) -> void {
    throw InputError("unit system '" + std::string(spec) + "': " + what + " (" + kAccepted + ")");
  };
  UnitSystem sys;
  sys.spec_ = std::string(spec);
  sys.force_.reset();
  // Which token set each slot, to reject "mm,cm".
  std::string set_length, set_mass, set_time, set_angle, set_rate, set_force;
  const auto claim = [&](std::string& slot, const char* what, const std::string& token) {
    if (!slot.empty()) {
      fail(std::string("two ") + what + " units '" + slot + "' and '" + token + "'");
    }
    slot = token;
  };

  size_t start = 0;
  bool any = false;
  while (start <= spec.size()) {
    size_t end = spec.find(',', start);
    if (end == std::string_view::npos) end = spec.size();
    std::string_view raw = spec.substr(start, end - start);
    while (!raw.empty() && std::isspace(static_cast<unsigned char>(raw.front()))) {
      raw.remove_prefix(1);
    }
    while (!raw.empty() && std::isspace(static_cast<unsigned char>(raw.back()))) {
      raw.remove_suffix(1);
    }
    const std::string token(raw);
    start = end + 1;
    if (token.empty()) fail("empty entry");
    any = true;

    if (token == "SI") {
      sys.length_ = {"m", 1.0};
      sys.mass_ = {"kg", 1.0};
      sys.time_ = {"s", 1.0};
      sys.angle_ = {"rad", 1.0};
      sys.force_.reset();
      sys.angular_velocity_.reset();
      continue;
    }
    if (token == "US") {
      sys.length_ = {"in", kInch};
      sys.mass_ = {"lb", kPound};
      sys.time_ = {"s", 1.0};
      sys.angle_ = {"rad", 1.0};
      sys.force_ = Unit{"lbf", kPoundForce};
      sys.angular_velocity_.reset();
      continue;
    }
    const std::optional<Quantity> q = LookupUnit(token);
    const Unit unit{token, q ? q->value : 0.0};
    if (!q) {
      const auto near = SuggestUnitNames(token);
      fail("unknown unit '" + token + "'" + DidYouMeanHint(near));
    } else if (q->dim == kLength) {
      claim(set_length, "length", token);
      sys.length_ = unit;
    } else if (q->dim == kMass) {
      claim(set_mass, "mass", token);
      sys.mass_ = unit;
    } else if (q->dim == kTime) {
      claim(set_time, "time", token);
      sys.time_ = unit;
    } else if (q->dim == kDimensionless) {
      claim(set_angle, "angle", token);
      sys.angle_ = unit;
    } else if (q->dim == kRate) {
      claim(set_rate, "angular velocity", token);
      sys.angular_velocity_ = unit;
    } else if (q->dim == kForce) {
      claim(set_force, "force", token);
      sys.force_ = unit;
    } else {
      fail("'" + token + "' cannot be a base unit of an output system");
    }
  }
  if (!any) fail("empty spec");

  if (!sys.force_) {
    // Name the force only when the base units are coherent with a named force unit: then
    // "N" (or "lbf", ...) is exactly mass*length/time^2 in this system.
    const double coherent =
        sys.mass_.factor * sys.length_.factor / (sys.time_.factor * sys.time_.factor);
    for (const char* name : {"N", "kN", "lbf", "kip", "dyn"}) {
      const double f = LookupUnit(name)->value;
      if (std::abs(coherent - f) <= 1e-12 * f) {
        sys.force_ = Unit{name, f};
        break;
      }
    }
  }
  if (!sys.force_ && (sys.mass_.name == "lb" || sys.mass_.name == "lbm")) {
    // Whoever counts mass in pounds states forces and energies in pound-force (lbf, lbf*in),
    // as the "US" system does: lb*in^2/s^2 is exact but nobody reads it.
    sys.force_ = Unit{"lbf", LookupUnit("lbf")->value};
  }
  return sys;
}

UnitSystem::Unit UnitSystem::Compose(const Dimension& dim, Angular angular) const {
  const double factor = Factor(dim, angular);
  if (angular == Angular::kYes && dim.length == 0 && dim.mass == 0) {
    if (dim.time == -1 && angular_velocity_) return *angular_velocity_;
    return {
        dim.time != 0 ? ComposeFormula({{angle_.name, 1}, {time_.name, dim.time}}) : angle_.name,
        factor};
  }
  // Forces, torques, pressures, stiffnesses, powers: one force factor, then the rest.
  if (force_ && dim.mass == 1 && dim.time <= -2) {
    return {ComposeFormula(
                {{force_->name, 1}, {length_.name, dim.length - 1}, {time_.name, dim.time + 2}}),
            factor};
  }
  return {
      ComposeFormula({{mass_.name, dim.mass}, {length_.name, dim.length}, {time_.name, dim.time}}),
      factor};
}

double UnitSystem::Factor(const Dimension& dim, Angular angular) const {
  if (angular == Angular::kYes && dim.length == 0 && dim.mass == 0) {
    if (dim.time == -1 && angular_velocity_) return angular_velocity_->factor;
    double factor = angle_.factor;
    if (dim.time != 0) factor *= std::pow(time_.factor, dim.time);
    return factor;
  }
  if (force_ && dim.mass == 1 && dim.time <= -2) {
    const int l = dim.length - 1, t = dim.time + 2;
    return force_->factor * std::pow(length_.factor, l) * std::pow(time_.factor, t);
  }
  return std::pow(mass_.factor, dim.mass) * std::pow(length_.factor, dim.length) *
         std::pow(time_.factor, dim.time);
}

std::string UnitSystem::FormatUnit(const Dimension& dim, Angular angular) const {
  return Compose(dim, angular).name;
}

double UnitSystem::FromSI(double value_si, const Dimension& dim, Angular angular) const {
  return value_si / Factor(dim, angular);
}

double UnitSystem::ToSI(double value, const Dimension& dim, Angular angular) const {
  return value * Factor(dim, angular);
}

}  // namespace chasles
