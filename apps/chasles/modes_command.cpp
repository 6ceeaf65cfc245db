// chasles modes: small motions about a scene's operating point (docs/modes.md) — the static
// equilibrium the initial state settles to, or the steady motion it begins — with the
// eigenvalues of the linearised motion: frequency, damping ratio or growth rate, mode shapes
// in the scene's coordinates, and the stability verdict. With --sweep, the same over a range of
// one parameter (a root locus, a Campbell diagram) and the values where the stability changes,
// found by bisection.

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "chasles/error.h"
#include "chasles/files/output_set.h"
#include "chasles/math/quaternion.h"
#include "chasles/report/json_report.h"
#include "chasles/report/modes_json.h"
#include "chasles/report/modes_text.h"
#include "chasles/report/report_data.h"
#include "chasles/report/result_names.h"
#include "chasles/scene/modes.h"
#include "chasles/scene/scene_dynamics.h"
#include "chasles/scene/scene_error.h"
#include "chasles/scene/solve.h"
#include "chasles/scene/sweep.h"
#include "commands.h"
#include "html_report.h"
#include "scene_args.h"

namespace chasles::cli {
namespace {

nlohmann::json Vec(const Vec3& v) {
  return {v.x(), v.y(), v.z()};
}

nlohmann::json ModesJson(const ModalAnalysis& a) {
  nlohmann::json modes = nlohmann::json::array();
  for (const Mode& m : a.modes) modes.push_back(ModeJson(m));
  return modes;
}

nlohmann::json CoordinatesJson(const std::vector<LinearCoordinate>& c) {
  nlohmann::json out = nlohmann::json::array();
  for (const LinearCoordinate& x : c) out.push_back({{"name", x.name}, {"unit", x.unit}});
  return out;
}

nlohmann::json SceneModesJson(const OperatingPointModes& s) {
  const OperatingPoint& op = s.operating_point;
  nlohmann::json state = nlohmann::json::array();
  for (size_t b = 0; b < s.bodies.size(); ++b) {
    const BodyState& bs = op.state.bodies[b];
    const Eigen::Vector4d q = QuatToWxyz(bs.q_WB);
    state.push_back({{"body", s.bodies[b]},
                     {"position", Vec(bs.p_WBcm)},
                     {"quaternion", {q[0], q[1], q[2], q[3]}},
                     {"velocity", Vec(bs.v_WBcm_W)},
                     {"angular_velocity", Vec(bs.q_WB * bs.w_WB_B)}});
  }
  nlohmann::json reactions = nlohmann::json::array();
  for (const ReactionReport& r : s.solution.reactions) {
    reactions.push_back({{"constraint", r.name},
                         {"point", Vec(r.p_WJ)},
                         {"force", Vec(r.F_Jc_W)},
                         {"moment", Vec(r.M_Jc_W)}});
  }
  nlohmann::json spins = nlohmann::json::array();
  for (size_t b = 0; b < s.bodies.size(); ++b) {
    if (op.generator.spin[b] == 0.0) continue;
    spins.push_back({{"body", s.bodies[b]},
                     {"rate", op.generator.spin[b]},
                     {"axis", Vec(op.generator.spin_axis_B[b])}});
  }
  const Linearization& lin = s.modes.linearization;
  return {{"operating_point",
           {{"kind", OperatingPointKindName(op.kind)},
            {"residual", op.residual},
            {"iterations", op.iterations},
            {"state", state},
            {"turn", Vec(op.generator.w_W)},
            {"translation", Vec(op.generator.v_W)},
            {"spins", spins},
            {"reactions", reactions},
            {"warnings", op.warnings}}},
          {"coordinates", CoordinatesJson(lin.coordinates)},
          {"speeds", CoordinatesJson(lin.speeds)},
          {"linearisation",
           {{"consistency", lin.consistency},
            {"finite_difference_check", lin.finite_difference_check}}},
          {"modes", ModesJson(s.modes)},
          {"stable", s.modes.stable}};
}

nlohmann::json SweepJson(const ModesSweep& w) {
  nlohmann::json points = nlohmann::json::array();
  for (size_t k = 0; k < w.values.size(); ++k) {
    points.push_back({{"parameters", {{w.parameter, w.values[k]}}},
                      {"modes", ModesJson(w.points[k].modes)},
                      {"stable", w.points[k].modes.stable}});
  }
  nlohmann::json changes = nlohmann::json::array();
  for (const StabilityChange& c : w.changes) {
    changes.push_back({{"parameter", w.parameter},
                       {"value", c.value},
                       {"kind", StabilityChangeKindName(c.kind)},
                       {"stable_after", c.stable_after}});
  }
  nlohmann::json critical = nlohmann::json::array();
  for (const CriticalSpeed& c : w.critical_speeds) {
    critical.push_back({{"speed", c.speed}, {"mode", c.mode}});
  }
  return {{"parameter", w.parameter},
          {"unit", w.unit},
          {"points", points},
          {"stability_changes", changes},
          {"critical_speeds", critical}};
}

/// The non-rigid eigenvalues with both members of each complex pair (Im λ >= 0 first), so
/// that their number, the dimension of the non-rigid motion, stays the same along a sweep.
std::vector<std::complex<double>> AllEigenvalues(const ModalAnalysis& a) {
  std::vector<std::complex<double>> out;
  for (const Mode& m : a.modes) {
    if (m.rigid) continue;
    out.push_back(m.eigenvalue);
    if (m.eigenvalue.imag() > 0.0) out.push_back(std::conj(m.eigenvalue));
  }
  return out;
}

/// One row per point: the parameter, then Re and Im (1/s) and the frequency |Im| / 2π (Hz) of
/// each non-rigid eigenvalue, a complex pair's two members one after the other, the modes in
/// order of |λ| — the columns `chasles plot` draws as a root locus (re_k against the
/// parameter) or a Campbell diagram (f_k against it; for a spin in rad/s the column spin_hz,
/// the spin in Hz, is the line whose crossings are the critical speeds). A point with fewer
/// (a rigid mode more) leaves its last cells empty.
std::string SweepCsv(const ModesSweep& w) {
  size_t most = 0;
  for (const OperatingPointModes& p : w.points)
    most = std::max(most, AllEigenvalues(p.modes).size());
  const bool spin = w.unit == "rad/s";
  std::string out = w.parameter + (spin ? ",spin_hz" : "");
  for (size_t k = 1; k <= most; ++k) out += fmt::format(",re_{0},im_{0},f_{0}", k);
  out += ",stable\n";
  for (size_t i = 0; i < w.values.size(); ++i) {
    out += fmt::format("{:.17g}", w.values[i]);
    if (spin) out += fmt::format(",{:.17g}", w.values[i] / (2.0 * std::numbers::pi));
    const std::vector<std::complex<double>> e = AllEigenvalues(w.points[i].modes);
    for (const std::complex<double>& z : e) {
      out += fmt::format(",{:.17g},{:.17g},{:.17g}", z.real(), z.imag(),
                         std::abs(z.imag()) / (2.0 * std::numbers::pi));
    }
    for (size_t n = e.size(); n < most; ++n) out += ",,,";
    out += fmt::format(",{}\n", w.points[i].modes.stable ? 1 : 0);
  }
  return out;
}

}  // namespace

CLI::App* AddModesCommand(CLI::App& app, ModesArgs& args) {
  CLI::App* cmd = app.add_subcommand(
      "modes",
      "Small motions about the scene's operating point: its static equilibrium or the steady "
      "motion its initial state begins; natural frequencies, damping, growth rates, mode "
      "shapes and the stability verdict");
  AddSceneArgs(*cmd, args.scene);
  cmd->add_option("--sweep", args.sweep,
                  "NAME=START:STOP:COUNT: the modes over a range of one parameter, and the "
                  "values where the stability changes (found by bisection)");
  cmd->add_option("--format", args.format, "text, json, or csv (a sweep's table, for plot)")
      ->check(CLI::IsMember({"text", "json", "csv"}));
  cmd->add_option("-o,--out", args.output, "Write the report here (default: standard output)");
  cmd->add_option("--html", args.html,
                  "Also write the browser report here: the bodies at the operating point, each "
                  "mode's motion animated (one HTML file; not with --sweep)");
  cmd->footer(
      "Examples:\n"
      "  chasles modes examples/whipple-bicycle.yaml\n"
      "  chasles modes examples/whipple-bicycle.yaml --html bicycle-modes.html\n"
      "  chasles modes examples/whipple-bicycle.yaml --sweep 'v=0 m/s:10 m/s:21' --format json\n"
      "  chasles modes examples/sleeping-top.yaml --sweep 'spin=20 rad/s:80 rad/s:7'\n"
      "Theory and output: docs/modes.md. Exit codes: 0 success, 2 bad input, 1 internal error.");
  return cmd;
}

int RunModes(const ModesArgs& args) {
  if (args.scene.scene.empty()) {
    throw InputError("chasles modes needs a scene file (chasles modes --help)");
  }
  OutputSet out;  // the targets are checked before the scene is read
  out.Expect(ReportTarget(args.output), "-o");
  if (!args.html.empty()) {
    if (!args.sweep.empty()) {
      throw InputError("--html draws the modes of one operating point: leave out --sweep");
    }
    RequireHtmlReport("--html");
    out.Expect(args.html, "--html");
  }
  std::string report;
  if (args.sweep.empty()) {
    if (args.format == "csv") throw InputError("--format csv is a sweep's table: give --sweep");
    const Scene scene = LoadScene(args.scene);
    const OperatingPointModes s = AnalyseOperatingPointModes(MakeModesDefinition(scene));
    const nlohmann::json j = SceneModesJson(s);
    report = args.format == "json" ? DumpJson(j, "the modes report")
                                   : (CheckFiniteJson(j, "the modes report"), ModesText(scene, s));
    if (!args.html.empty()) out.Add(args.html, HtmlReport(ModesReportData(scene, s)));
  } else {
    const SweepSpec spec = ParseSweep(args.sweep, "command line", "--sweep");
    const auto load = SceneLoader(args.scene);
    const SceneOptions options = SceneOptionsFrom(args.scene);
    const SweepGrid grid = MakeSweepGrid(load(options), {spec}, kDefaultMaxRows);
    const ModesSweep w = SweepModes(grid.parameters, [&](double value) {
      return MakeModesDefinitionAt(load, options, spec.name, grid.parameters.units[0], value);
    });
    const nlohmann::json j = SweepJson(w);
    if (args.format == "json") {
      report = DumpJson(j, "the modes sweep");
    } else {
      CheckFiniteJson(j, "the modes sweep");
      report = args.format == "csv" ? SweepCsv(w) : ModesSweepText(w);
    }
  }
  out.Add(ReportTarget(args.output), std::move(report));
  out.Commit();
  SayWroteHtmlReport(args.html);
  return 0;
}

}  // namespace chasles::cli
