#pragma once
/// @file
/// The "Checks" section of the simulate and solve text reports (the JSON form is the report
/// layer's CertificateJson, chasles/report/certificate_json.h), and the exit code of --strict.

#include <string>

#include "chasles/analysis/certificate.h"

namespace chasles::cli {

/// Exit code of simulate and solve with --strict when a check fails (README, "Exit codes").
inline constexpr int kExitCheckFailed = 3;

/// The "Checks" section of a text report (SI values: the tolerances are SI-scaled).
std::string CertificateText(const Certificate& certificate);

}  // namespace chasles::cli
