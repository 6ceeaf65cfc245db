#pragma once
/// @file
/// The text report of `chasles audit` (docs/audit.md): per file its counts, per link its
/// findings with their fixes, the given and the computed inertia, and the robot's total.

#include <string>
#include <vector>

#include "chasles/analysis/audit.h"
#include "chasles/mass/mass_properties.h"
#include "chasles/math/types.h"

namespace chasles {

/// The text report of every file audited.
std::string AuditText(const std::vector<RobotAudit>& audits);

/// "mass 1.219 kg, centre of mass [0, 0, 0] m, inertia [...] kg·m²".
std::string AuditFixSummary(const MassProperties& values);
/// "[Ixx .., Iyy .., Izz .., Ixy .., Ixz .., Iyz ..] kg·m²".
std::string AuditTensorSummary(const Mat3& I);

}  // namespace chasles
