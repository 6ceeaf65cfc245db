#pragma once
/// @file
/// The text report of `chasles balance` (docs/modes.md, "Rotors"): a rotor's static and couple
/// unbalance, the two correction masses, the residual, the bearing forces at speed, the ISO
/// 21940-11 permissible residual unbalance, and the whirl rows on elastic bearings. SI.

#include <string>

#include "chasles/analysis/balance.h"
#include "chasles/analysis/whirl.h"

namespace chasles {

/// The unbalance of the rotor body `body` about `axis` and its correction.
std::string BalanceText(const std::string& body, const BalanceReport& report,
                        const RotorAxis& axis);

/// One row per speed (forward and backward frequencies), then the critical speeds.
std::string WhirlText(const WhirlMap& whirl);

/// What `chasles balance` prints: BalanceText, then WhirlText when there are whirl rows.
std::string RotorBalanceText(const RotorBalance& balance);

}  // namespace chasles
