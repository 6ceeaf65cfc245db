// The text report of chasles audit (docs/audit.md): one block per link, findings first.

#include "chasles/report/audit_text.h"

#include <cmath>

#include <fmt/format.h>

namespace chasles {

std::string AuditTensorSummary(const Mat3& I) {
  return fmt::format(
      "[Ixx {:.6g}, Iyy {:.6g}, Izz {:.6g}, Ixy {:.6g}, Ixz {:.6g}, Iyz {:.6g}] kg·m²", I(0, 0),
      I(1, 1), I(2, 2), I(0, 1), I(0, 2), I(1, 2));
}

std::string AuditFixSummary(const MassProperties& v) {
  const Vec3& c = v.p_BoBcm_B();
  return fmt::format("mass {:.6g} kg, centre of mass [{:.6g}, {:.6g}, {:.6g}] m, inertia {}",
                     v.mass(), c.x(), c.y(), c.z(), AuditTensorSummary(v.I_BBcm_B().matrix()));
}

namespace {

void LinkText(std::string& out, const LinkAudit& l) {
  out += fmt::format("\nlink '{}' (line {})\n", l.name, l.line);
  for (const Finding& f : l.findings) {
    out += fmt::format("  {} {} (line {}): {}\n", SeverityName(f.severity), FindingCodeName(f.code),
                       f.line, f.message);
    if (f.fix) {
      out += fmt::format("    fix ({}): {}\n", f.fix_rule, AuditFixSummary(*f.fix));
      if (!f.effect.empty()) out += fmt::format("    effect: {}\n", f.effect);
    }
  }
  if (l.has_inertial) out += fmt::format("  given     {}\n", AuditFixSummary(l.given));
  if (l.computed) {
    const GeometryEstimate& e = l.estimates[*l.computed];
    const bool massive = l.has_inertial && l.given.mass() > 0.0;
    out += fmt::format(
        "  computed  {} geometry ({}), volume {:.6g} m³{}\n", GeometrySetName(e.set),
        GeometryMethodName(e.method), e.volume,
        massive ? fmt::format(", density {:.4g} kg/m³ at the given mass", l.given.mass() / e.volume)
                : "");
    if (massive) out += fmt::format("            {}\n", AuditFixSummary(e.AtMass(l.given.mass())));
  }
}

}  // namespace

std::string AuditText(const std::vector<RobotAudit>& audits) {
  std::string out;
  for (const RobotAudit& a : audits) {
    out += fmt::format(
        "chasles audit: {} ({}, robot '{}', {} links): {} errors, {} warnings, {} "
        "notes\n",
        a.file, RobotFormatName(a.format), a.robot_name, a.links.size(), a.Count(Severity::kError),
        a.Count(Severity::kWarning), a.Count(Severity::kNote));
    out += "Inertias are tensors about the centre of mass in the link frame (Ixy = -∫xy dm).\n";
    for (const std::string& w : a.warnings) out += fmt::format("warning: {}\n", w);
    for (const LinkAudit& l : a.links) LinkText(out, l);
    if (std::isfinite(a.robot.mass())) {
      out += fmt::format("\nrobot '{}' in its base frame: {}\n", a.robot_name,
                         AuditFixSummary(a.robot));
    }
    for (const std::string& n : a.robot_notes) out += fmt::format("  note: {}\n", n);
    out += "\n";
  }
  return out;
}

}  // namespace chasles
