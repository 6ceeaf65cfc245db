#pragma once
/// @file
/// The certificate (a run's or a solve's checks of its own answer, chasles/analysis/
/// certificate.h) as the JSON object the program's reports carry under "checks".

#include <nlohmann/json.hpp>

#include "chasles/analysis/certificate.h"

namespace chasles {

/// {"passed": bool, "scales": {"force", "moment", "length", "velocity", "energy"}, "checks":
/// [{"name", "description", "applies", "count", "passed", "unit", "worst", "tolerance"} and,
/// for a check that applied, "where", "t" and "phase"]}.
nlohmann::json CertificateJson(const Certificate& certificate);

}  // namespace chasles
