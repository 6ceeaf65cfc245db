// The text report of `chasles balance` (docs/modes.md, "Rotors"; analysis/balance.h and
// analysis/whirl.h have the equations).

#include "chasles/report/balance_text.h"

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <fmt/ranges.h>

namespace chasles {
namespace {

constexpr double kRpmPerRadPerSecond = 30.0 / std::numbers::pi;

/// The frequencies [Hz] of the modes whirling in direction `d`, by |λ|.
std::vector<std::string> Frequencies(const WhirlPoint& p, WhirlDirection d) {
  std::vector<std::string> out;
  for (const WhirlMode& m : p.modes) {
    if (m.direction == d) out.push_back(fmt::format("{:.6g}", m.frequency_hz));
  }
  return out;
}

std::string Directions(const std::vector<WhirlDirection>& ds) {
  std::vector<std::string> names;
  for (const WhirlDirection d : ds) names.emplace_back(WhirlDirectionName(d));
  return names.empty() ? "none" : fmt::format("{}", fmt::join(names, " and "));
}

}  // namespace

std::string BalanceText(const std::string& body, const BalanceReport& r, const RotorAxis& axis) {
  std::string out = fmt::format("Rotor '{}': mass {:.9g} kg\n", body, r.mass);
  out += fmt::format("  static unbalance  {:.9g} kg*m ({:.9g} g*mm)\n", r.static_unbalance_W.norm(),
                     r.static_unbalance_W.norm() * 1e6);
  out += fmt::format("  couple unbalance  {:.9g} kg*m^2\n", r.couple_unbalance_W.norm());
  const char* names[2] = {"A", "B"};
  const double z[2] = {axis.z_A, axis.z_B};
  out += fmt::format(
      "Corrections (angles from [{:.6g}, {:.6g}, {:.6g}] towards [{:.6g}, {:.6g}, "
      "{:.6g}] about the axis):\n",
      r.e1_W.x(), r.e1_W.y(), r.e1_W.z(), r.e2_W.x(), r.e2_W.y(), r.e2_W.z());
  for (int k = 0; k < 2; ++k) {
    const BalanceCorrection& c = r.corrections[static_cast<size_t>(k)];
    if (c.mass == 0.0) {
      out += fmt::format("  plane {} at {:.9g} m: none needed\n", names[k], z[k]);
      continue;
    }
    out += fmt::format("  plane {} at {:.9g} m: {:.9g} kg at radius {:.9g} m, angle {:.6f} deg\n",
                       names[k], z[k], c.mass, c.radius, c.angle * 180.0 / std::numbers::pi);
  }
  out += fmt::format("Residual after correction: {:.3g} kg*m static, {:.3g} kg*m^2 couple\n",
                     r.residual_static, r.residual_couple);
  if (std::isfinite(r.speed)) {
    out +=
        fmt::format("Bearing forces on the rotor at {:.9g} rad/s (rotating with it):\n", r.speed);
    for (int k = 0; k < 2; ++k) {
      out += fmt::format("  {}: {:.9g} N before, {:.3g} N after correction\n", names[k],
                         r.bearing_forces_W[static_cast<size_t>(k)].norm(),
                         r.bearing_forces_after_W[static_cast<size_t>(k)].norm());
    }
  }
  if (std::isfinite(r.permissible)) {
    out += fmt::format(
        "ISO 21940-11 grade G {:.6g}: permissible residual unbalance {:.9g} g*mm ({:.9g} g*mm in "
        "plane A, "
        "{:.9g} g*mm in plane B); the static unbalance is {}\n",
        r.grade, r.permissible * 1e6, r.permissible_per_plane[0] * 1e6,
        r.permissible_per_plane[1] * 1e6,
        r.static_unbalance_W.norm() <= r.permissible ? "within it" : "beyond it");
  }
  return out;
}

std::string WhirlText(const WhirlMap& w) {
  std::string out =
      "Whirl on the bearings (the rotor spinning about the axis through its centre of mass;\n"
      "frequencies in Hz, forward with the spin, backward against it):\n";
  for (const WhirlPoint& p : w.points) {
    const std::vector<std::string> fwd = Frequencies(p, WhirlDirection::kForward),
                                   bwd = Frequencies(p, WhirlDirection::kBackward),
                                   none = Frequencies(p, WhirlDirection::kNone);
    out += fmt::format("  {:>10.6g} rad/s ({:>8.6g} rpm):", p.speed, p.speed * kRpmPerRadPerSecond);
    if (!fwd.empty()) out += fmt::format(" forward {};", fmt::join(fwd, ", "));
    if (!bwd.empty()) out += fmt::format(" backward {};", fmt::join(bwd, ", "));
    if (!none.empty()) {
      out += fmt::format(" {} {};", p.speed > 0.0 ? "no whirl" : "at rest", fmt::join(none, ", "));
    }
    out.back() = '\n';
  }
  if (w.critical_speeds.empty()) {
    out += "Critical speeds: none in this range\n";
  } else {
    out += "Critical speeds (a whirl frequency equals the spin):\n";
    for (const WhirlCriticalSpeed& c : w.critical_speeds) {
      out += fmt::format("  {:.9g} rad/s ({:.6g} rpm), {} whirl\n", c.speed,
                         c.speed * kRpmPerRadPerSecond, Directions(c.directions));
    }
  }
  return out;
}

std::string RotorBalanceText(const RotorBalance& b) {
  return BalanceText(b.body, b.balance, b.axis) + (b.whirl ? WhirlText(*b.whirl) : "");
}

}  // namespace chasles
