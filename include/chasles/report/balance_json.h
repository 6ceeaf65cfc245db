#pragma once
/// @file
/// The JSON report of `chasles balance --format json` (docs/modes.md, "Rotors"): a rotor's
/// unbalance, its two-plane correction, the bearing forces at speed, the ISO 21940-11
/// permissible residual unbalance and the whirl rows on elastic bearings. SI.

#include <string>

#include <nlohmann/json.hpp>

#include "chasles/analysis/balance.h"
#include "chasles/analysis/whirl.h"

namespace chasles {

/// {"body", "mass", "static_unbalance", "static_unbalance_vector", "couple_unbalance",
/// "couple_unbalance_vector", "reference_directions", "corrections": [{"plane", "position",
/// "mass", "radius", "angle", "point"}], "residual_after": {"static", "couple"}, "permissible":
/// {"grade", "total", "A", "B", "met"} | null, "bearing_reactions": {"before", "after"} | null,
/// "speed" (with a speed)}: the unbalance of the rotor body `body` about `axis`.
nlohmann::json BalanceJson(const std::string& body, const BalanceReport& report,
                           const RotorAxis& axis);

/// {"speeds": [...] (rad/s), "points": [{"speed", "modes": [{"eigenvalue", "frequency_hz",
/// "damping_ratio", "direction"}]}], "critical_speeds": [{"speed", "directions"}]}.
nlohmann::json WhirlJson(const WhirlMap& whirl);

/// What `chasles balance --format json` prints: BalanceJson with "whirl", WhirlJson or null.
nlohmann::json RotorBalanceJson(const RotorBalance& balance);

}  // namespace chasles
