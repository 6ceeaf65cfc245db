// chasles balance: a rotor's static and couple unbalance, the two correction masses in its two
// planes, what is left after them, the bearing forces at speed (the chapter's Euler equations
// about a fixed axis), the ISO 21940-11 permissible residual unbalance for a balance grade and
// the whirl rows on elastic bearings (docs/modes.md, "Rotors"). The library reads the options
// (scene/balance.h), computes (analysis/balance.h has the equations) and writes the reports
// (report/balance_text.h, balance_json.h); this file parses the arguments and writes.

#include <string>
#include <utility>

#include <nlohmann/json.hpp>

#include "chasles/analysis/balance.h"
#include "chasles/error.h"
#include "chasles/files/output_set.h"
#include "chasles/report/balance_json.h"
#include "chasles/report/balance_text.h"
#include "chasles/report/json_report.h"
#include "chasles/scene/balance.h"
#include "chasles/scene/scene.h"
#include "commands.h"
#include "scene_args.h"

namespace chasles::cli {

CLI::App* AddBalanceCommand(CLI::App& app, BalanceArgs& args) {
  CLI::App* cmd = app.add_subcommand(
      "balance",
      "A rotor's static and couple unbalance about its spin axis, the two-plane correction "
      "masses, the bearing forces at speed and the ISO 21940-11 permissible residual "
      "unbalance");
  AddSceneArgs(*cmd, args.scene);
  cmd->add_option("--body", args.body, "The rotor: a body of the scene")->required();
  cmd->add_option("--axis", args.axis, "Spin axis in W, as in a scene: '[0, 0, 1]'");
  cmd->add_option("--through", args.through, "A point of the axis in W: '[0, 0, 0]'");
  cmd->add_option("--planes", args.planes,
                  "The two bearing and correction planes' positions along the axis from "
                  "--through: 'A, B', e.g. '-10 cm, 10 cm'")
      ->required();
  cmd->add_option("--radius", args.radius, "Radius of the correction masses, e.g. '8 cm'")
      ->required();
  cmd->add_option("--speed", args.speed,
                  "Spin for the bearing forces and the grade, e.g. '3000 rpm'");
  cmd->add_option("--grade", args.grade, "ISO 21940-11 balance grade G in mm/s (e.g. 6.3)");
  cmd->add_option("--whirl", args.whirl,
                  "With the rotor on elastic bearings: the spins of the whirl rows, 'A:B:N' "
                  "(default: 0 to twice --speed, 21 spins)");
  cmd->add_option("--format", args.format, "text or json")->check(CLI::IsMember({"text", "json"}));
  cmd->add_option("-o,--out", args.output, "Write the report here (default: standard output)");
  cmd->footer(
      "Example:\n"
      "  chasles balance examples/unbalanced-disk-rotor.yaml --body rotor --axis '[0, 0, 1]' "
      "--planes '-25 cm, 25 cm' --radius '15 cm' --speed '3000 rpm' --grade 6.3\n"
      "Theory: docs/modes.md, section Rotors. Exit codes: 0 success, 2 bad input.");
  return cmd;
}

int RunBalance(const BalanceArgs& args) {
  if (args.scene.scene.empty()) {
    throw InputError("chasles balance needs a scene file (chasles balance --help)");
  }
  OutputSet out;  // the target is checked before the scene is read
  out.Expect(ReportTarget(args.output), "-o");
  const Scene scene = LoadScene(args.scene);
  BalanceOptions options;
  options.body = args.body;
  options.axis = args.axis;
  options.through = args.through;
  options.planes = args.planes;
  options.radius = args.radius;
  options.speed = args.speed;
  options.grade = args.grade;
  options.whirl = args.whirl;
  const RotorBalance balance = AnalyseRotorBalance(MakeBalanceDefinition(scene, options));
  const nlohmann::json j = RotorBalanceJson(balance);
  std::string report;
  if (args.format == "json") {
    report = DumpJson(j, "the balance report");
  } else {
    CheckFiniteJson(j, "the balance report");
    report = RotorBalanceText(balance);
  }
  out.Add(ReportTarget(args.output), std::move(report));
  out.Commit();
  return 0;
}

}  // namespace chasles::cli
