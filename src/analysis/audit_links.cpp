// Checks across the links of a robot (analysis/internal/audit_steps.h): the same inertial
// copied onto links of other shapes, left and right twins that disagree, and a mass for a
// massless link from the robot's own typical density.

#include <algorithm>
#include <cctype>
#include <cmath>
#include <map>
#include <string>
#include <tuple>
#include <vector>

#include <fmt/format.h>
#include <Eigen/Eigenvalues>

#include "analysis/internal/audit_steps.h"

namespace chasles::internal {

namespace {

/// The names `name` would have on the other side: one letter l/r (L/R) standing alone or
/// beside another capital (FL_HIP, l_arm, arm_L), or the word left/right, swapped.
std::vector<std::string> TwinNames(const std::string& name) {
  std::vector<std::string> out;
  auto alone = [&](std::size_t i) {
    const bool before = i == 0 || !std::islower(static_cast<unsigned char>(name[i - 1]));
    const bool after =
        i + 1 >= name.size() || !std::islower(static_cast<unsigned char>(name[i + 1]));
    return before && after;
  };
  for (std::size_t i = 0; i < name.size(); ++i) {
    const char ch = name[i];
    const char swap = ch == 'l' ? 'r' : ch == 'r' ? 'l' : ch == 'L' ? 'R' : ch == 'R' ? 'L' : 0;
    if (swap && alone(i)) {
      std::string t = name;
      t[i] = swap;
      out.push_back(t);
    }
  }
  for (const auto& [a, b] : {std::pair<std::string, std::string>{"left", "right"},
                             {"right", "left"},
                             {"Left", "Right"},
                             {"Right", "Left"}}) {
    if (const std::size_t at = name.find(a); at != std::string::npos) {
      out.push_back(name.substr(0, at) + b + name.substr(at + a.size()));
    }
  }
  return out;
}

Vec3 SortedMoments(const Mat3& I) {
  return Eigen::SelfAdjointEigenSolver<Mat3>(I, Eigen::EigenvaluesOnly).eigenvalues();
}

bool HasFinding(const LinkAudit& a, FindingCode code) {
  return std::any_of(a.findings.begin(), a.findings.end(),
                     [&](const Finding& f) { return f.code == code; });
}

void CheckTwins(const RobotModel& model, std::vector<LinkAudit>& audits) {
  std::map<std::string, std::size_t> by_name;
  for (std::size_t i = 0; i < audits.size(); ++i) by_name[audits[i].name] = i;
  for (std::size_t i = 0; i < audits.size(); ++i) {
    for (const std::string& twin : TwinNames(audits[i].name)) {
      const auto it = by_name.find(twin);
      if (it == by_name.end() || it->second == i) continue;
      LinkAudit& a = audits[i];
      const LinkAudit& b = audits[it->second];
      if (!a.has_inertial || !b.has_inertial || !(b.given.mass() > 0.0)) continue;
      const double ma = a.given.mass(), mb = b.given.mass();
      const Vec3 la = SortedMoments(a.given.I_BBcm_B().matrix());
      const Vec3 lb = SortedMoments(b.given.I_BBcm_B().matrix());
      const double mass_ratio = std::max(ma / mb, mb / ma);
      double moment_ratio = 1.0;
      for (int k = 0; k < 3; ++k) {
        if (la[k] > 0 && lb[k] > 0)
          moment_ratio = std::max({moment_ratio, la[k] / lb[k], lb[k] / la[k]});
      }
      if (!(mass_ratio > 1.02) && !(moment_ratio > 1.10)) continue;
      // The twin's mass and principal moments on this link's own principal axes.
      const Eigen::SelfAdjointEigenSolver<Mat3> own(a.given.I_BBcm_B().matrix());
      const MassProperties mirrored(
          mb, a.given.p_BoBcm_B(),
          RotationalInertia::FromMatrix(own.eigenvectors() * lb.asDiagonal() *
                                        own.eigenvectors().transpose()));
      AddFinding(a, Severity::kWarning, FindingCode::kMirrorMismatch, model.links[i].inertial.line,
                 fmt::format("its twin '{}' (line {}) has mass {:.4g} kg and principal moments "
                             "{:.4g}, {:.4g}, {:.4g} kg·m²; this link {:.4g} kg and {:.4g}, "
                             "{:.4g}, {:.4g} kg·m² (a factor {:.3g} apart): mirror images have "
                             "the same",
                             b.name, b.line, mb, lb[0], lb[1], lb[2], ma, la[0], la[1], la[2],
                             std::max(mass_ratio, moment_ratio)),
                 mirrored, "the twin's mass and principal moments on this link's principal axes");
    }
  }
}

void CheckDuplicates(const RobotModel& model, std::vector<LinkAudit>& audits) {
  using Key = std::tuple<double, double, double, double, double, double, double>;
  std::map<Key, std::vector<std::size_t>> groups;
  for (std::size_t i = 0; i < audits.size(); ++i) {
    const RobotLink& link = model.links[i];
    if (!link.has_inertial || !(link.inertial.mass > 0.0)) continue;
    const Mat3& W = link.inertial.I_LcmI_I;
    if (W.isZero(0.0)) continue;
    groups[Key{link.inertial.mass, W(0, 0), W(1, 1), W(2, 2), W(0, 1), W(0, 2), W(1, 2)}].push_back(
        i);
  }
  for (const auto& [key, members] : groups) {
    if (members.size() < 2) continue;
    for (const std::size_t i : members) {
      std::vector<std::string> others;
      for (const std::size_t j : members) {
        const std::vector<std::string> twins = TwinNames(audits[i].name);
        const bool twin = std::find(twins.begin(), twins.end(), audits[j].name) != twins.end();
        if (j != i && !twin)
          others.push_back(
              fmt::format("'{}' (line {})", audits[j].name, model.links[j].inertial.line));
      }
      if (others.empty() || HasFinding(audits[i], FindingCode::kPlaceholderInertia)) continue;
      LinkAudit& a = audits[i];
      std::optional<MassProperties> fix;
      // Identical modules (legs, fingers) legitimately share numbers: a note, and a warning
      // when this link's own geometry disagrees with them.
      Severity severity = Severity::kNote;
      if (a.computed) {
        fix = a.estimates[*a.computed].AtMass(a.given.mass());
        if (TensorFactor(a.given.I_BBcm_B().matrix(), fix->I_BBcm_B().matrix()) >
            AuditThresholds::kMismatchWarning) {
          severity = Severity::kWarning;
        }
      }
      AddFinding(a, severity, FindingCode::kDuplicateInertial, model.links[i].inertial.line,
                 fmt::format("the same mass ({:g} kg) and tensor as {}: copied from another link, "
                             "not computed for this one",
                             std::get<0>(key), fmt::join(others, ", ")),
                 fix, fix ? "the geometry's centre of mass and tensor at the given mass" : "");
    }
  }
}

}  // namespace

void CheckAcrossLinks(const RobotModel& model, std::vector<LinkAudit>& audits) {
  CheckDuplicates(model, audits);
  CheckTwins(model, audits);
  // A massless link with geometry, or one of implausible density that no slip explains: the
  // robot's median density (of its links without errors or warnings) times its volume, the
  // geometry's tensor at that mass.
  std::vector<double> densities;
  for (const LinkAudit& a : audits) {
    const bool sound = std::none_of(a.findings.begin(), a.findings.end(),
                                    [](const Finding& f) { return f.severity != Severity::kNote; });
    if (a.has_inertial && a.computed && a.given.mass() > 0.0 && sound) {
      densities.push_back(a.given.mass() / a.estimates[*a.computed].volume);
    }
  }
  if (densities.empty()) return;
  std::nth_element(densities.begin(), densities.begin() + densities.size() / 2, densities.end());
  const double rho = densities[densities.size() / 2];
  for (LinkAudit& a : audits) {
    if (!a.computed || !(a.estimates[*a.computed].volume > 0.0)) continue;
    for (Finding& f : a.findings) {
      const bool density = f.code == FindingCode::kImplausibleDensity && !f.fix;
      if (f.code != FindingCode::kZeroMass && !density) continue;
      const MassProperties fix =
          a.estimates[*a.computed].AtMass(rho * a.estimates[*a.computed].volume);
      f.fix = fix;
      f.fix_rule = fmt::format(
          "the robot's median density, {:.4g} kg/m³, times the geometry's "
          "volume, and the geometry's tensor at that mass",
          rho);
      f.message += fmt::format(
          "; at the robot's median density of {:.4g} kg/m³ it would weigh "
          "{:.4g} kg",
          rho, fix.mass());
    }
  }
}

}  // namespace chasles::internal
