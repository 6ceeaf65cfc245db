// The JSON of `chasles audit` (chasles/report/audit_json.h).

#include "chasles/report/audit_json.h"

#include <cmath>

#include "chasles/report/json_report.h"

namespace chasles {

namespace {

nlohmann::json Values(const MassProperties& mp) {
  return {{"mass", mp.mass()},
          {"center_of_mass", VecJson(mp.p_BoBcm_B())},
          {"inertia", MatJson(mp.I_BBcm_B().matrix())}};
}

/// Values, and where the tensor is a body's (positive mass, physically valid) its principal
/// moments (ascending) and axes (rows, in the link frame) and the radii of gyration about those
/// axes, k_i = √(I_i / m) (eq. 8.19).
nlohmann::json Described(const MassProperties& mp) {
  nlohmann::json j = Values(mp);
  j["principal_moments"] = j["principal_axes"] = j["radii_of_gyration"] = nullptr;
  if (!(mp.mass() > 0.0) || !mp.I_BBcm_B().CheckPhysicallyValid().empty()) return j;
  const PrincipalAxes pa = mp.I_BBcm_B().CalcPrincipalAxes();
  j["principal_moments"] = VecJson(pa.moments);
  j["principal_axes"] = MatJson(pa.axes.transpose());
  // sqrt(I_i / m): beyond a double's range for a mass at round-off beside its moments (1e-320
  // kg under 0.1 kg·m²), which no body has: null then, as for an invalid tensor.
  const Vec3 k = pa.moments.cwiseMax(0.0).cwiseQuotient(Vec3::Constant(mp.mass())).cwiseSqrt();
  if (k.allFinite()) j["radii_of_gyration"] = VecJson(k);
  return j;
}

nlohmann::json FindingJson(const Finding& f) {
  nlohmann::json j = {{"severity", SeverityName(f.severity)},
                      {"code", FindingCodeName(f.code)},
                      {"message", f.message},
                      {"line", f.line},
                      {"fix", nullptr}};
  if (f.fix) {
    j["fix"] = Values(*f.fix);
    j["fix"]["rule"] = f.fix_rule;
    if (!f.effect.empty()) j["fix"]["effect"] = f.effect;
  }
  return j;
}

nlohmann::json LinkJson(const LinkAudit& l) {
  nlohmann::json j = {
      {"name", l.name}, {"line", l.line}, {"given", nullptr}, {"computed", nullptr}};
  if (l.has_inertial) j["given"] = Described(l.given);
  if (l.computed) {
    const GeometryEstimate& e = l.estimates[*l.computed];
    const MassProperties mp =
        l.has_inertial && l.given.mass() > 0.0 ? e.AtMass(l.given.mass()) : e.unit_density;
    j["computed"] = Described(mp);
    j["computed"]["source"] = GeometrySetName(e.set);
    j["computed"]["method"] = GeometryMethodName(e.method);
    j["computed"]["volume"] = e.volume;
    j["computed"]["density"] = mp.mass() / e.volume;
    j["computed"]["lines"] = e.lines;
  }
  j["findings"] = nlohmann::json::array();
  for (const Finding& f : l.findings) j["findings"].push_back(FindingJson(f));
  const Finding* fix = FixToApply(l);
  j["fix_applied"] = fix ? nlohmann::json(FindingCodeName(fix->code)) : nlohmann::json(nullptr);
  return j;
}

}  // namespace

nlohmann::json AuditFileJson(const RobotAudit& a) {
  nlohmann::json j = {{"path", a.file},
                      {"format", RobotFormatName(a.format)},
                      {"robot_name", a.robot_name},
                      {"links", nlohmann::json::array()},
                      {"robot", nullptr},
                      {"robot_notes", a.robot_notes},
                      {"warnings", a.warnings}};
  for (const LinkAudit& l : a.links) j["links"].push_back(LinkJson(l));
  if (std::isfinite(a.robot.mass())) j["robot"] = Values(a.robot);
  return j;
}

nlohmann::json AuditJson(const std::vector<RobotAudit>& audits) {
  nlohmann::json j = {{"files", nlohmann::json::array()}, {"robot", nullptr}};
  std::size_t counts[3] = {0, 0, 0};
  for (const RobotAudit& a : audits) {
    j["files"].push_back(AuditFileJson(a));
    for (const Severity s : {Severity::kNote, Severity::kWarning, Severity::kError}) {
      counts[static_cast<int>(s)] += a.Count(s);
    }
  }
  if (!audits.empty()) j["robot"] = j["files"][0]["robot"];
  j["errors"] = counts[2];
  j["warnings"] = counts[1];
  j["notes"] = counts[0];
  j["inertia_convention"] =
      "tensor entries, Ixy = -∫xy dm, about the centre of mass in the link frame [kg m^2]";
  return j;
}

}  // namespace chasles
