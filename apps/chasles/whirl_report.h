#pragma once
// The whirl rows of `chasles balance` (analysis/whirl.h): JSON and text.

#include <string>

#include <nlohmann/json.hpp>

#include "chasles/analysis/whirl.h"

namespace chasles::cli {

/// {"speeds": [...] (rad/s), "points": [{"speed", "modes": [{"eigenvalue", "frequency_hz",
/// "damping_ratio", "direction"}]}], "critical_speeds": [{"speed", "directions"}]}.
nlohmann::json WhirlJson(const WhirlMap& w);

/// One row per speed (forward and backward frequencies), then the critical speeds.
std::string WhirlText(const WhirlMap& w);

}  // namespace chasles::cli
