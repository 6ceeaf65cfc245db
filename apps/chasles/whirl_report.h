#pragma once
// The whirl rows of `chasles balance` (analysis/whirl.h) as JSON (the text is the report
// layer's WhirlText, chasles/report/balance_text.h).

#include <nlohmann/json.hpp>

#include "chasles/analysis/whirl.h"

namespace chasles::cli {

/// {"speeds": [...] (rad/s), "points": [{"speed", "modes": [{"eigenvalue", "frequency_hz",
/// "damping_ratio", "direction"}]}], "critical_speeds": [{"speed", "directions"}]}.
nlohmann::json WhirlJson(const WhirlMap& w);

}  // namespace chasles::cli
