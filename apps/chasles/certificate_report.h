#pragma once
/// @file
/// The "Checks" section of the simulate and solve reports: the certificate (analysis layer)
/// as text and JSON, and the exit code of --strict.

#include <string>

#include <nlohmann/json.hpp>

#include "chasles/analysis/certificate.h"

namespace chasles::cli {

/// Exit code of simulate and solve with --strict when a check fails (README, "Exit codes").
inline constexpr int kExitCheckFailed = 3;

/// The checks as a JSON object: {"passed": bool, "scales": {...}, "checks": [...]}.
nlohmann::json CertificateJson(const Certificate& certificate);

/// The "Checks" section of a text report (SI values: the tolerances are SI-scaled).
std::string CertificateText(const Certificate& certificate);

}  // namespace chasles::cli
