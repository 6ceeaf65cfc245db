// chasles audit: robot descriptions checked against their own geometry (docs/audit.md).

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>

#include "audit_text.h"
#include "chasles/analysis/audit.h"
#include "chasles/error.h"
#include "chasles/files/output_set.h"
#include "chasles/files/robot_reader.h"
#include "chasles/files/robot_writer.h"
#include "chasles/report/audit_json.h"
#include "chasles/report/audit_text.h"
#include "chasles/report/json_report.h"
#include "chasles/scene/robot_file.h"
#include "commands.h"
#include "html_report.h"
#include "scene_args.h"

namespace chasles::cli {

CLI::App* AddAuditCommand(CLI::App& app, AuditArgs& args) {
  CLI::App* cmd = app.add_subcommand(
      "audit",
      "Check the inertials of robot descriptions (URDF, MJCF, SDF) against each link's own "
      "geometry, and write fixes in the file's own syntax");
  cmd->add_option("files", args.files, "Robot files (.urdf, MJCF .xml, .sdf)")->required();
  cmd->add_option("--format", args.format, "text (for people) or json (for programs)")
      ->check(CLI::IsMember({"text", "json"}));
  cmd->add_option("-o,--output", args.output, "Write the report to this file");
  cmd->add_option("--html", args.html,
                  "Also write the browser report: each link drawn from its geometry with the "
                  "ellipsoids of its given and computed inertia, and the findings");
  cmd->add_flag("--fix", args.fix,
                "Write each file with its fixable inertials corrected into --out (only their "
                "numbers change, each with a comment saying why), and print the diff");
  cmd->add_option("--out", args.out_dir, "Folder for the files --fix writes (never the input's)");
  cmd->add_option("--package", args.packages,
                  "Where a package:// URI's package is: NAME=DIR (repeatable; otherwise the "
                  "folders above the file are searched, as ROS does)");
  cmd->add_option("--joint", args.joints,
                  "A joint value for the robot's total: NAME=VALUE in rad or m (repeatable; "
                  "others at zero)");
  cmd->footer(
      "Examples:\n"
      "  chasles audit robot.urdf\n"
      "  chasles audit robot.urdf --format json -o audit.json\n"
      "  chasles audit robot.urdf --fix --out fixed\n"
      "Exit codes: 0 no error found, 3 at least one finding of severity error, 2 unreadable "
      "input (file and line named), 1 internal error. Checks: docs/audit.md.");
  return cmd;
}

namespace {

/// The rewrites of one audited file: one per link with an error and a fix (FixToApply).
std::vector<InertialRewrite> Rewrites(const RobotAudit& audit) {
  std::vector<InertialRewrite> out;
  for (std::size_t i = 0; i < audit.links.size(); ++i) {
    const LinkAudit& l = audit.links[i];
    const Finding* f = FixToApply(l);
    if (!f || !l.has_inertial) continue;
    const MassProperties& v = *f->fix;
    InertialRewrite r;
    r.link = i;
    r.mass = v.mass();
    r.p_LoLcm_L = v.p_BoBcm_B();
    r.I_LcmL_L = v.I_BBcm_B().matrix();
    r.comment = fmt::format("{} ({}); written: {}; was mass {:.6g} kg, {}{}{}",
                            FindingCodeName(f->code), f->fix_rule, AuditFixSummary(v),
                            l.given.mass(), AuditTensorSummary(l.given.I_BBcm_B().matrix()),
                            f->effect.empty() ? "" : "; ", f->effect);
    out.push_back(std::move(r));
  }
  return out;
}

/// --fix: the corrected files, queued in `outputs` (written with the reports, all or none),
/// and their diffs.
nlohmann::json AddFixes(const AuditArgs& args, const std::vector<RobotModel>& models,
                        const std::vector<RobotAudit>& audits, OutputSet& outputs,
                        std::string* diffs) {
  nlohmann::json fixed = nlohmann::json::array();
  for (std::size_t i = 0; i < models.size(); ++i) {
    const std::vector<InertialRewrite> rewrites = Rewrites(audits[i]);
    if (rewrites.empty()) continue;
    const std::filesystem::path target =
        std::filesystem::path(args.out_dir) / std::filesystem::path(models[i].file).filename();
    std::error_code ec;
    if (std::filesystem::equivalent(target, models[i].file, ec)) {
      throw InputError(fmt::format("--out {}: '{}' would be written over the input", args.out_dir,
                                   target.string()));
    }
    const std::string text = RewriteInertials(models[i], rewrites);
    const std::string diff = UnifiedDiff(models[i].text, text, models[i].file, target.string());
    *diffs += diff;
    outputs.Add(target.string(), text);
    fixed.push_back({{"path", models[i].file},
                     {"fixed", target.string()},
                     {"diff", diff},
                     {"links", rewrites.size()}});
  }
  return fixed;
}

}  // namespace

int RunAudit(const AuditArgs& args) {
  RobotReadOptions read;
  read.packages = ParsePackageOptions(args.packages);
  AuditOptions options;
  options.cache = MakeAuditMeshCache(LoadMeshTriangles);  // a mesh shared by files is read once
  options.joints = ParseJointOptions(args.joints);
  // Every target is checked before a file is read.
  OutputSet out;
  out.Expect(ReportTarget(args.output), "-o");
  if (!args.html.empty()) {
    RequireHtmlReport("--html");
    out.Expect(args.html, "--html");
  }
  if (args.fix) {
    if (args.out_dir.empty()) {
      throw InputError("--fix needs --out DIR: corrected files are never written over the input");
    }
    out.ExpectFolder(args.out_dir, "--out");
  }
  std::vector<RobotModel> models;
  std::vector<RobotAudit> audits;
  for (const std::string& file : args.files) {
    models.push_back(ReadRobotFile(file, read));
    audits.push_back(AuditRobot(models.back(), options));
  }
  nlohmann::json j = AuditJson(audits);
  std::string diffs;
  if (args.fix) j["fixed"] = AddFixes(args, models, audits, out, &diffs);
  std::string report =
      args.format == "json" ? DumpJson(j, "the audit report") : AuditText(audits) + diffs;
  if (!args.html.empty()) {
    out.Add(args.html, HtmlReport(AuditReportData(models, audits, options.joints)));
  }
  out.Add(ReportTarget(args.output), std::move(report));
  out.Commit();
  SayWroteHtmlReport(args.html);
  std::size_t errors = 0;
  for (const RobotAudit& a : audits) errors += a.Count(Severity::kError);
  return errors > 0 ? 3 : 0;
}

}  // namespace chasles::cli
