#pragma once
/// @file
/// The people's report of `chasles audit` (one block per link, findings first) and the data of
/// its browser report (the mass report's page: each link drawn from its geometry, with the
/// ellipsoids of its given and computed inertia as parts, and the findings as notes).

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

/// The browser report's data for the audited files.
nlohmann::json AuditReportData(const std::vector<RobotModel>& models,
                               const std::vector<RobotAudit>& audits);

}  // namespace chasles::cli
