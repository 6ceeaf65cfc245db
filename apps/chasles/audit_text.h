#pragma once
/// @file
/// The data of the browser report of `chasles audit` (the mass report's page: each link drawn
/// from its geometry, with the ellipsoids of its given and computed inertia, and the findings
/// listed); the text report is the report layer's AuditText (chasles/report/audit_text.h).

#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "chasles/analysis/audit.h"
#include "chasles/files/robot_model.h"

namespace chasles::cli {

/// The browser report's data for the audited files: the mass report's (kind "mass"), one body
/// per link with a valid given inertial at its pose in its robot's base frame at `joints`,
/// drawn from its primitives and meshes, its mass properties the given ones, "computed" the
/// geometry's source, method and uniform ellipsoid at the given mass; and "audit", per file its
/// counts and per link its line, findings and body (null when not drawn).
nlohmann::json AuditReportData(const std::vector<RobotModel>& models,
                               const std::vector<RobotAudit>& audits,
                               const std::map<std::string, double>& joints);

}  // namespace chasles::cli
