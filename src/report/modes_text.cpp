#include "chasles/report/modes_text.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>
#include <string>

#include <fmt/format.h>

#include "chasles/report/result_names.h"
#include "chasles/report/text_format.h"

namespace chasles {

namespace {

std::string ModeLine(const Mode& m) {
  if (m.rigid) return fmt::format("  rigid     frees {}\n", m.rigid_coordinate);
  // A neutral mode's Re λ and damping ratio are round-off (1e-16 of |λ|): printed as 0.
  const double re = m.neutral ? 0.0 : m.eigenvalue.real(), im = m.eigenvalue.imag();
  std::string what;
  if (!m.stable) {
    what = fmt::format("grows at {:.9g} 1/s{}", m.growth_rate,
                       im > 0.0 ? fmt::format(", oscillating at {:.9g} Hz", m.frequency_hz) : "");
  } else if (im > 0.0 && m.neutral) {
    what = fmt::format("{:.9g} Hz, undamped", m.frequency_hz);
  } else if (im > 0.0) {
    what = fmt::format("{:.9g} Hz, damping ratio {:.6g}", m.frequency_hz, m.damping_ratio);
  } else if (m.neutral) {
    what = "neutral";
  } else {
    what = fmt::format("decays at {:.9g} 1/s", -re);
  }
  return fmt::format("  {:<9} λ = {:.12g} {} {:.12g}i 1/s: {}\n", m.stable ? "stable" : "UNSTABLE",
                     re, im < 0.0 ? "-" : "+", std::abs(im), what);
}

std::string ShapeText(const Mode& m, const Linearization& lin) {
  std::string out;
  const auto n = static_cast<Eigen::Index>(lin.coordinates.size());
  for (Eigen::Index i = 0; i < n && i < m.shape.size(); ++i) {
    if (std::abs(m.shape[i]) < 1e-9) continue;
    // The amplitude in the coordinate's unit, then its phase in degrees.
    const LinearCoordinate& c = lin.coordinates[static_cast<size_t>(i)];
    out += fmt::format("      {} {:.6g}{} at {:.1f}°\n", c.name, std::abs(m.shape[i]),
                       c.unit.empty() ? "" : " " + c.unit,
                       std::arg(m.shape[i]) * 180.0 / std::numbers::pi);
  }
  return out;
}

}  // namespace

std::string ModesText(const Scene& scene, const OperatingPointModes& s) {
  const OperatingPoint& op = s.operating_point;
  const Linearization& lin = s.modes.linearization;
  std::string out = fmt::format("{}\n", scene.title.empty() ? scene.file : scene.title);
  out += fmt::format(
      "Operating point: {} (residual {:.3g}{})\n",
      op.kind == OperatingPointKind::kEquilibrium ? "static equilibrium" : "steady motion",
      op.residual, op.iterations > 0 ? fmt::format(", {} Newton steps", op.iterations) : "");
  for (const std::string& w : op.warnings) out += fmt::format("  Warning: {}\n", w);
  // Components below 1e-12 of the largest component of any reaction are the solve's
  // round-off: printed as 0 (SI, as the rest of this report).
  double largest = 0.0;
  for (const ReactionReport& r : s.solution.reactions) {
    largest = std::max(largest, r.F_Jc_W.cwiseAbs().maxCoeff());
  }
  const Show show{UnitSystem(), 9, kRunRoundOff, "a value of the modes report"};
  const auto shown = [&](double x) { return show.Number(show.Clean(x, largest)); };
  for (const ReactionReport& r : s.solution.reactions) {
    out += fmt::format("  reaction {:<16} F = [{}, {}, {}] N\n", r.name, shown(r.F_Jc_W.x()),
                       shown(r.F_Jc_W.y()), shown(r.F_Jc_W.z()));
  }
  out += "Coordinates:";
  for (const LinearCoordinate& c : lin.coordinates) out += fmt::format(" {} [{}]", c.name, c.unit);
  out += "\nSpeeds:";
  for (const LinearCoordinate& c : lin.speeds) out += fmt::format(" {} [{}]", c.name, c.unit);
  out += fmt::format(
      "\nLinearisation: exact Jacobians; consistency {:.2g}; against finite "
      "differences of the engine {:.2g}\nModes:\n",
      lin.consistency, lin.finite_difference_check);
  for (const Mode& m : s.modes.modes) {
    out += ModeLine(m);
    if (!m.rigid) out += ShapeText(m, lin);
  }
  out += fmt::format("Verdict: {}\n", s.modes.stable ? "stable (no mode grows)" : "UNSTABLE");
  return out;
}

std::string ModesSweepText(const ModesSweep& w) {
  std::string out =
      fmt::format("Modes against {}{}\n", w.parameter, w.unit.empty() ? "" : " [" + w.unit + "]");
  for (size_t k = 0; k < w.values.size(); ++k) {
    out += fmt::format("{} = {:.9g}{}: {}\n", w.parameter, w.values[k],
                       w.unit.empty() ? "" : " " + w.unit,
                       w.points[k].modes.stable ? "stable" : "UNSTABLE");
    for (const Mode& m : w.points[k].modes.modes) {
      if (!m.rigid) out += ModeLine(m);
    }
  }
  for (const CriticalSpeed& c : w.critical_speeds) {
    out += fmt::format(
        "Critical speed: {} = {:.15g} rad/s ({:.9g} rpm): mode {} whirls at the "
        "spin\n",
        w.parameter, c.speed, c.speed * 30.0 / std::numbers::pi, c.mode + 1);
  }
  out += "Stability changes:\n";
  if (w.changes.empty()) out += "  none in the range\n";
  for (const StabilityChange& c : w.changes) {
    out += fmt::format(
        "  {} = {:.15g}{}: {} ({})\n", w.parameter, c.value, w.unit.empty() ? "" : " " + w.unit,
        c.stable_after ? "stable above" : "unstable above", StabilityChangeKindName(c.kind));
  }
  return out;
}

}  // namespace chasles
