#pragma once
/// @file
/// The exit code of --strict (the "Checks" section itself is the report layer's
/// CertificateText, chasles/report/certificate_text.h).

namespace chasles::cli {

/// Exit code of simulate and solve with --strict when a check fails (README, "Exit codes").
inline constexpr int kExitCheckFailed = 3;

}  // namespace chasles::cli
