#include "whirl_report.h"

#include <numbers>
#include <vector>

#include <fmt/format.h>
#include <fmt/ranges.h>

namespace chasles::cli {
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

nlohmann::json WhirlJson(const WhirlMap& w) {
  nlohmann::json speeds = nlohmann::json::array(), points = nlohmann::json::array();
  for (const WhirlPoint& p : w.points) {
    speeds.push_back(p.speed);
    nlohmann::json modes = nlohmann::json::array();
    for (const WhirlMode& m : p.modes) {
      modes.push_back({{"eigenvalue", {m.eigenvalue.real(), m.eigenvalue.imag()}},
                       {"frequency_hz", m.frequency_hz},
                       {"damping_ratio", m.damping_ratio},
                       {"direction", WhirlDirectionName(m.direction)}});
    }
    points.push_back({{"speed", p.speed}, {"modes", modes}});
  }
  nlohmann::json critical = nlohmann::json::array();
  for (const WhirlCriticalSpeed& c : w.critical_speeds) {
    nlohmann::json dirs = nlohmann::json::array();
    for (const WhirlDirection d : c.directions) dirs.push_back(WhirlDirectionName(d));
    critical.push_back({{"speed", c.speed}, {"directions", dirs}});
  }
  return {{"speeds", speeds}, {"points", points}, {"critical_speeds", critical}};
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

}  // namespace chasles::cli
