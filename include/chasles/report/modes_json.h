#pragma once
/// @file
/// A mode as JSON (docs/modes.md, "Modes"): what `chasles modes --format json` prints for each
/// mode, and what the browser report's mode page starts from.

#include <nlohmann/json.hpp>

#include "chasles/analysis/modes.h"

namespace chasles {

/// {"eigenvalue": [re, im], "frequency_hz", "damping_ratio", "growth_rate", "stable",
/// "neutral", "rigid", "shape": [[re, im], ...]}, and "frees" for a rigid mode.
nlohmann::json ModeJson(const Mode& m);

}  // namespace chasles
