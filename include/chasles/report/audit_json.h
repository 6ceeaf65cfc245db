#pragma once
/// @file
/// The JSON of `chasles audit` (docs/audit.md, "JSON"): per file its path, format, links (each
/// with its line, the inertial given, what its geometry gives, and its findings with their
/// fixes) and the robot's total; tensors in kg·m² about the centre of mass in the link frame,
/// positions in metres.

#include <vector>

#include <nlohmann/json.hpp>

#include "chasles/analysis/audit.h"

namespace chasles {

/// {"files": [...], "robot": the first file's total, "errors", "warnings", "notes"}.
nlohmann::json AuditJson(const std::vector<RobotAudit>& audits);

/// One file's entry: {"path", "format", "robot_name", "links", "robot", "robot_notes",
/// "warnings"}.
nlohmann::json AuditFileJson(const RobotAudit& audit);

}  // namespace chasles
