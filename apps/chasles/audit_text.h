#pragma once
/// @file
/// The people's report of `chasles audit` (one block per link, findings first) and the data of
/// its browser report (the mass report's page: each link drawn from its geometry, with the
/// ellipsoids of its given and computed inertia, and the findings listed).

#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "chasles/analysis/audit.h"
#include "chasles/files/robot_model.h"

namespace chasles::cli {

/// The text report of every file audited.
std::string AuditText(const std::vector<RobotAudit>& audits);

/// "mass 1.219 kg, centre of mass [0, 0, 0] m, inertia [...] kg·m²".
std::string AuditFixSummary(const MassProperties& values);
/// "[Ixx .., Iyy .., Izz .., Ixy .., Ixz .., Iyz ..] kg·m²".
std::string AuditTensorSummary(const Mat3& I);

/// The browser report's data for the audited files: the mass report's (kind "mass"), one body
/// per link with a valid given inertial at its pose in its robot's base frame at `joints`,
/// drawn from its primitives and meshes, its mass properties the given ones, "computed" the
/// geometry's source, method and uniform ellipsoid at the given mass; and "audit", per file its
/// counts and per link its line, findings and body (null when not drawn).
nlohmann::json AuditReportData(const std::vector<RobotModel>& models,
                               const std::vector<RobotAudit>& audits,
                               const std::map<std::string, double>& joints);

}  // namespace chasles::cli
