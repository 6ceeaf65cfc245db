#pragma once
/// @file
/// The "Checks" section of the simulate and solve text reports (the JSON form is
/// CertificateJson, chasles/report/certificate_json.h).

#include <string>

#include "chasles/analysis/certificate.h"

namespace chasles {

/// The "Checks" section of a text report (SI values: the tolerances are SI-scaled).
std::string CertificateText(const Certificate& certificate);

}  // namespace chasles
