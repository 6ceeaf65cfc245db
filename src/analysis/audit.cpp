// The audit of a robot description (chasles/analysis/audit.h): each link's geometry, its
// inertial on its own and against that geometry, the checks across links, and the robot's
// total at the configuration given.

#include "chasles/analysis/audit.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include <fmt/format.h>

#include "analysis/internal/audit_steps.h"
#include "chasles/analysis/robot_mass.h"
#include "chasles/error.h"

namespace chasles {

const char* SeverityName(Severity severity) {
  switch (severity) {
    case Severity::kError:
      return "error";
    case Severity::kWarning:
      return "warning";
    case Severity::kNote:
      return "note";
  }
  return "?";
}

const char* FindingCodeName(FindingCode code) {
  switch (code) {
    case FindingCode::kNotPositiveDefinite:
      return "not_positive_definite";
    case FindingCode::kTriangleInequality:
      return "triangle_inequality";
    case FindingCode::kZeroMass:
      return "zero_mass";
    case FindingCode::kMissingInertial:
      return "missing_inertial";
    case FindingCode::kPlaceholderInertia:
      return "placeholder_inertia";
    case FindingCode::kImplausibleDensity:
      return "implausible_density";
    case FindingCode::kRadiusOfGyration:
      return "radius_of_gyration";
    case FindingCode::kComOutsideGeometry:
      return "com_outside_geometry";
    case FindingCode::kMismatchGeometry:
      return "mismatch_geometry";
    case FindingCode::kDecimalSlip:
      return "decimal_slip";
    case FindingCode::kTransposedEntries:
      return "transposed_entries";
    case FindingCode::kMirrorMismatch:
      return "mirror_mismatch";
    case FindingCode::kDuplicateInertial:
      return "duplicate_inertial";
    case FindingCode::kFrame:
      return "frame";
    case FindingCode::kSignOfProducts:
      return "sign_of_products";
    case FindingCode::kMissingGeometry:
      return "missing_geometry";
  }
  return "?";
}

std::vector<FindingCode> AllFindingCodes() {
  std::vector<FindingCode> out;
  for (int c = 0; c <= static_cast<int>(FindingCode::kMissingGeometry); ++c) {
    out.push_back(static_cast<FindingCode>(c));
  }
  return out;
}

std::size_t RobotAudit::Count(Severity severity) const {
  std::size_t n = 0;
  for (const LinkAudit& l : links) {
    for (const Finding& f : l.findings) n += f.severity == severity;
  }
  return n;
}

namespace {

/// True when `v` passes the checks that need no judgement: a valid tensor and, against the
/// geometry, a plausible density, the radius of gyration within reach, the centre of mass
/// inside, and no disagreement of an error's size.
bool FixHolds(const LinkAudit& link, const MassProperties& v) {
  using T = internal::AuditThresholds;
  if (!(v.mass() > 0.0) || !v.I_BBcm_B().CheckPhysicallyValid().empty()) return false;
  if (!link.computed) return true;
  const GeometryEstimate& e = link.estimates[*link.computed];
  const double rho = v.mass() / e.volume;
  if (rho < T::kDensityLow || rho > T::kDensityHigh) return false;
  const Mat3& I = v.I_BBcm_B().matrix();
  if (std::sqrt(I.trace() / (2 * v.mass())) > T::kReach * e.RadiusAbout(v.p_BoBcm_B()))
    return false;
  const double margin = T::kComMargin * (e.box_max - e.box_min).norm();
  const Vec3& c = v.p_BoBcm_B();
  if (((c.array() < e.box_min.array() - margin) || (c.array() > e.box_max.array() + margin))
          .any()) {
    return false;
  }
  return internal::TensorFactor(I, e.AtMass(v.mass()).I_BBcm_B().matrix()) <= T::kMismatchError;
}

}  // namespace

const Finding* FixToApply(const LinkAudit& link) {
  const bool error = std::any_of(link.findings.begin(), link.findings.end(),
                                 [](const Finding& f) { return f.severity == Severity::kError; });
  if (!error) return nullptr;
  static constexpr FindingCode kOrder[] = {
      FindingCode::kDecimalSlip,        FindingCode::kTransposedEntries,
      FindingCode::kSignOfProducts,     FindingCode::kFrame,
      FindingCode::kImplausibleDensity, FindingCode::kNotPositiveDefinite,
      FindingCode::kTriangleInequality, FindingCode::kZeroMass,
      FindingCode::kRadiusOfGyration,   FindingCode::kComOutsideGeometry,
      FindingCode::kPlaceholderInertia, FindingCode::kMismatchGeometry,
      FindingCode::kMirrorMismatch,     FindingCode::kDuplicateInertial};
  // The first fix in that order that passes the plain checks; else the first there is.
  const Finding* first = nullptr;
  for (const FindingCode code : kOrder) {
    for (const Finding& f : link.findings) {
      if (f.code != code || !f.fix) continue;
      if (FixHolds(link, *f.fix)) return &f;
      if (!first) first = &f;
    }
  }
  return first;
}

namespace {

/// A link without an inertial: what its format makes of it.
void MissingInertial(const RobotModel& model, const RobotLink& link, LinkAudit& a) {
  if (link.has_inertial || link.geometries.empty()) return;
  const char* meaning =
      model.format == RobotFormat::kUrdf
          ? "URDF makes it massless: a simulator drops it, or refuses it when a joint moves it"
      : model.format == RobotFormat::kSdf
          ? "SDF gives it its defaults, 1 kg and 1 kg·m² about every axis"
          : "MuJoCo computes one from its geoms at 1000 kg/m³";
  std::optional<MassProperties> fix;
  if (a.computed) fix = a.estimates[*a.computed].AtMass(1000.0 * a.estimates[*a.computed].volume);
  internal::AddFinding(
      a, model.format == RobotFormat::kMjcf ? Severity::kNote : Severity::kWarning,
      FindingCode::kMissingInertial, link.line,
      fmt::format("link '{}' has geometry but no inertial: {}", link.name, meaning), fix,
      fix ? "the geometry at 1000 kg/m³ (state the real mass)" : "");
}

LinkAudit AuditLink(const RobotModel& model, const RobotLink& link, internal::MeshCache& meshes) {
  LinkAudit a;
  a.name = link.name;
  a.line = link.line;
  a.has_inertial = link.has_inertial;
  if (link.has_inertial) a.given = GivenMassProperties(link.inertial);
  a.estimates = internal::EstimateGeometry(link, meshes, model.file);
  // A geometry set enclosing less than 1e-30 m³ (a cube of 1e-10 m, an atom's size) is no
  // body's: its implied density (mass / volume) and the moments scaled from it would leave the
  // range of a double for any mass a file may hold (up to 1e18 kg). It is named, not used.
  constexpr double kMinGeometryVolume = 1e-30;  // [m³]
  for (std::size_t i = 0; i < a.estimates.size(); ++i) {
    GeometryEstimate& e = a.estimates[i];
    if (e.volume > 0.0 && e.volume < kMinGeometryVolume) {
      e.notes.push_back(
          fmt::format("{} geometry (line {}) not used: it encloses {:.3g} m³, less "
                      "than {:g} m³",
                      GeometrySetName(e.set), e.lines.empty() ? link.line : e.lines.front(),
                      e.volume, kMinGeometryVolume));
      continue;
    }
    if (e.volume > 0.0 && !a.computed) a.computed = i;
  }
  for (const GeometryEstimate& e : a.estimates) {
    for (const std::string& n : e.notes) {
      internal::AddFinding(a, Severity::kNote, FindingCode::kMissingGeometry,
                           e.lines.empty() ? link.line : e.lines.front(), n);
    }
  }
  MissingInertial(model, link, a);
  internal::CheckInertialAlone(link, a);
  internal::CheckAgainstGeometry(link, a);
  return a;
}

}  // namespace

RobotAudit AuditRobot(const RobotModel& model, const AuditOptions& options) {
  RobotAudit out;
  out.file = model.file;
  out.format = model.format;
  out.robot_name = model.name;
  out.warnings = model.warnings;
  const std::shared_ptr<AuditMeshCache> meshes =
      options.cache ? options.cache : MakeAuditMeshCache(options.load_mesh);
  for (const RobotLink& link : model.links) out.links.push_back(AuditLink(model, link, *meshes));
  internal::CheckAcrossLinks(model, out.links);
  // Findings first by severity (errors first), then in file order.
  for (LinkAudit& a : out.links) {
    std::stable_sort(a.findings.begin(), a.findings.end(),
                     [](const Finding& x, const Finding& y) { return x.severity > y.severity; });
  }
  std::vector<std::optional<MassProperties>> parts;
  for (const LinkAudit& a : out.links) {
    if (a.has_inertial && a.given.mass() > 0.0) {
      parts.emplace_back(a.given);
      if (!a.given.I_BBcm_B().CheckPhysicallyValid().empty()) {
        out.robot_notes.push_back(
            fmt::format("link '{}' enters the total with its invalid tensor", a.name));
      }
    } else {
      parts.emplace_back(std::nullopt);
      if (a.has_inertial) {
        out.robot_notes.push_back(
            fmt::format("link '{}' (mass {:g} kg) is left out", a.name, a.given.mass()));
      }
    }
  }
  try {
    out.robot = CalcRobotMassProperties(CalcLinkPoses(model, options.joints), parts);
  } catch (const InputError& e) {
    if (!options.joints.empty()) throw;
    out.robot_notes.push_back(e.what());
  }
  return out;
}

}  // namespace chasles
